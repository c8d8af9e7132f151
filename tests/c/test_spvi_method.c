/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* test_spvi_method.c -- the SPVI stepper through its table as a method:
   its pairs and options, allocation, orders of convergence, agreement
   with known methods, symplecticity, symmetry, the predictor, many
   nodes.  The calls it makes are in test_spvi_calls.c, its adaptive
   steps and dense output in test_spvi_adaptive.c. */
#include "sym.h"
#include "driver_util.h"
#include "testutil.h"
#include "test_spvi_systems.h"

#include <stdint.h>

#define T sym_step_spvi

/* ---------------------------------------------------------------- alloc */
/* the pairs (n, m) allowed and refused, and their orders: of the method
   (fixed steps), and of the companion an adaptive run advances with */
static void
scenario_alloc_pairs (void)
{
  int st = 12345;
  struct { int n, m, ok, order; } cases[] = {
    { 2, 1, 1, 2 }, { 3, 2, 1, 4 }, { 4, 3, 1, 6 }, { 3, 3, 1, 4 },
    { 4, 2, 1, 2 }, { 5, 4, 1, 8 }, { 2, 2, 1, 2 }, { 6, 3, 1, 2 },
    { 9, 8, 1, 16 }, { 3, 1, 0, 0 }, { 5, 2, 0, 0 }, { 1, 3, 0, 0 },
    { 7, 3, 0, 0 }, { 2, -1, 0, 0 }, { 101, 100, 0, 0 }
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
    {
      const int n = cases[i].n, m = cases[i].m;
      sym_method_opts o;
      sym_spvi_opts so;
      ts_opts (&o, &so, n, m);
      void *s = T->alloc (1, &o, &st);
      if (! cases[i].ok)
        {
          CHECK (! s && st == SYM_EBADINPUT, "(%d,%d) accepted: %d", n, m,
                 st);
          T->free (s);   /* NULL is fine */
          continue;
        }
      CHECK (s && st == 0, "(%d,%d) refused: %d", n, m, st);
      if (! s)
        continue;
      int est = -1, p = T->order (s, &est);
      CHECK (p == cases[i].order && est == cases[i].order
             && sym_spvi_order (n, m) == p, "(%d,%d): order %d (estimate "
             "%d), expected %d", n, m, p, est, cases[i].order);
      st = ts_adaptive (T, s, 1e-6, 1e-6);
      p = T->order (s, &est);
      CHECK (st == 0 && p == sym_spvi_order (n + 1, m + 1)
             && est == cases[i].order, "(%d,%d) adaptive: order %d "
             "(estimate %d)", n, m, p, est);
      T->free (s);
    }
}

/* defaults, and options refused */
static void
scenario_alloc_options (void)
{
  int st;
  /* defaults: Nodes 3, Q_DoFs = Nodes + 1 */
  sym_method_opts o;
  sym_spvi_opts so;
  ts_opts (&o, &so, 0, 0);
  void *s = T->alloc (1, &o, &st);
  CHECK (s && T->order (s, NULL) == 6, "defaults");
  T->free (s);
  s = T->alloc (1, NULL, &st);
  CHECK (s && T->order (s, NULL) == 6, "NULL options");
  T->free (s);
  ts_opts (&o, &so, 0, 2);
  s = T->alloc (1, &o, &st);
  CHECK (s && T->order (s, NULL) == 4, "Nodes 2 alone gives (3,2)");
  T->free (s);
  ts_opts (&o, &so, 3, 2);
  CHECK (! T->alloc (0, &o, &st) && st == SYM_EBADINPUT, "dim 0");
  o.newton_tol = -1;
  CHECK (! T->alloc (1, &o, &st) && st == SYM_EBADINPUT, "tol < 0");
  ts_opts (&o, &so, 3, 2);
  so.newton_matrix = SYM_MATRIX_NEW + 1;
  CHECK (! T->alloc (1, &o, &st) && st == SYM_EBADINPUT, "matrix 3");
  so.newton_matrix = -1;
  CHECK (! T->alloc (1, &o, &st) && st == SYM_EBADINPUT, "matrix -1");
}

/* dense output before any step, steps refused */
static void
scenario_bad_steps (void)
{
  ts_user u = { 0 };
  sym_eval ev = ts_eval (1, ts_pend, ts_pend_jac, &u);
  sym_method_opts o;
  sym_spvi_opts so;
  ts_opts (&o, &so, 3, 2);
  int st;
  void *s = T->alloc (ev.dim, &o, &st);
  double y[2];
  CHECK (T->dense (s, &ev, 0.0, y) == SYM_EBADINPUT, "dense, no step");
  double y0[2] = { 1, 1 }, y1[2];
  CHECK (T->step (s, &ev, 0.0, 0.0, 0.0, y0, y1, NULL) == SYM_EBADINPUT,
         "h = 0");
  CHECK (T->step (s, &ev, 0.0, NAN, NAN, y0, y1, NULL) == SYM_EBADINPUT,
         "h NaN");
  CHECK (T->step (s, &ev, 0.0, 0.1, INFINITY, y0, y1, NULL)
         == SYM_EBADINPUT, "tend Inf");
  T->free (s);
}

/* Allocation failures: fail the k-th allocation for every k until alloc
   and set_tolerances (the companion) succeed; each failure returns
   SYM_ENOMEM and leaves nothing allocated once the state is freed. */
static void
scenario_alloc_failures (void)
{
  sym_eval ev = ts_eval (2, ts_kep, ts_kep_jac, NULL);
  sym_method_opts o;
  sym_spvi_opts so;
  ts_opts (&o, &so, 4, 3);
  sym_set_allocator (drv_counting_alloc, drv_counting_free);
  int nfail = 0, bad = 0;
  for (long k = 1; k < 1000; k++)
    {
      int st = 0;
      drv_alloc_count = 0;
      drv_alloc_fail_at = k;
      void *s = T->alloc (ev.dim, &o, &st);
      if (s && ! (st = ts_adaptive (T, s, 1e-6, 1e-6)))
        {
          T->free (s);
          break;
        }
      T->free (s);
      nfail++;
      if (st != SYM_ENOMEM || drv_alloc_live != 0)
        bad++;
    }
  drv_alloc_fail_at = 0;
  CHECK (nfail > 10 && bad == 0 && drv_alloc_live == 0,
         "%d failures, %d bad, %ld blocks live", nfail, bad, drv_alloc_live);

  /* the companion allocated lazily by a step that wants yerr */
  drv_alloc_count = 0;
  void *s = T->alloc (ev.dim, &o, &(int) { 0 });
  drv_alloc_fail_at = drv_alloc_count + 1;
  double y[4], yn[4], ye[4];
  ts_kep_y0 (0.6, y);
  int st = T->step (s, &ev, 0.0, 0.05, 0.05, y, yn, ye);
  CHECK (st == SYM_ENOMEM, "lazy companion: %d", st);
  drv_alloc_fail_at = 0;
  st = T->step (s, &ev, 0.0, 0.05, 0.05, y, yn, ye);
  CHECK (st == 0, "then fine: %d", st);
  T->free (s);
  sym_set_allocator (NULL, NULL);
  CHECK (drv_alloc_live == 0, "%ld blocks live", drv_alloc_live);
}

/* ---------------------------------------------------------------- orders */
static void
scenario_orders (void)
{
  static const int pairs[][2] = { { 2, 1 }, { 3, 2 }, { 4, 3 }, { 3, 3 },
                                  { 4, 2 }, { 5, 4 } };
  const double hs[] = { 0.5, 0.25, 0.125, 0.0625 };
  double yex[11][2];
  for (int i = 1; i <= 10; i++)
    ts_pend_exact (1.0, 1.0, (double) i, yex[i]);
  printf ("orders on the pendulum, y0 = [1;1], t in [0,10] (max error at "
          "t = 1..10 vs the exact elliptic-function solution):\n");
  printf ("  (n,m) order  err(h=.5)  err(.25)   err(.125)  err(.0625)  "
          "slopes\n");
  for (size_t p = 0; p < sizeof pairs / sizeof pairs[0]; p++)
    {
      int n = pairs[p][0], m = pairs[p][1];
      double err[4];
      int order = 0;
      for (int k = 0; k < 4; k++)
        {
          ts_user u = { 0 };
          sym_eval ev = ts_eval (1, ts_pend, ts_pend_jac, &u);
          sym_method_opts o;
          sym_spvi_opts so;
          ts_opts (&o, &so, n, m);
          int st;
          void *s = T->alloc (ev.dim, &o, &st);
          order = T->order (s, NULL);
          double y[2] = { 1.0, 1.0 };
          long per = lround (1.0 / hs[k]);
          err[k] = 0.0;
          for (int i = 1; i <= 10 && ! st; i++)
            {
              st = ts_run_fixed (T, s, &ev, (double) (i - 1), hs[k], per,
                                 y);
              err[k] = fmax (err[k], ts_maxdiff (2, y, yex[i]));
            }
          CHECK (st == 0, "(%d,%d) h = %g: status %d", n, m, hs[k], st);
          T->free (s);
        }
      double sl[3];
      for (int k = 0; k < 3; k++)
        sl[k] = log2 (err[k] / err[k + 1]);
      printf ("  (%d,%d)  %2d   %.3e  %.3e  %.3e  %.3e   %.3f %.3f %.3f\n",
              n, m, order, err[0], err[1], err[2], err[3], sl[0], sl[1],
              sl[2]);
      /* a slope counts while the finer error is above round-off (1e-13,
         100 times the accumulated round-off); the finest one within 0.15,
         the coarser within 0.3 */
      int finest = -1;
      for (int k = 0; k < 3; k++)
        if (err[k + 1] > 1e-13)
          finest = k;
      CHECK (finest >= 0, "(%d,%d): no slope above round-off", n, m);
      for (int k = 0; k <= finest; k++)
        CHECK (fabs (sl[k] - order) <= (k == finest ? 0.15 : 0.3),
               "(%d,%d): slope %d = %.3f, order %d", n, m, k, sl[k], order);
      /* below round-off the error must stay there */
      for (int k = finest + 1; k < 3; k++)
        CHECK (err[k + 1] < 1e-13, "(%d,%d) error %g", n, m, err[k + 1]);
    }
}

/* ---------------------------------------------------------------- midpoint */
/* y1 = y0 + h f((y0 + y1)/2), by fixed-point iteration to round-off */
static void
midpoint (sym_rhs_fn f, int nn, double h, const double *y0, double *y1)
{
  double ym[8], fm[8], prev[8];
  memcpy (y1, y0, (size_t) nn * sizeof (double));
  for (int it = 0; it < 500; it++)
    {
      for (int i = 0; i < nn; i++)
        ym[i] = 0.5 * (y0[i] + y1[i]);
      f (0.0, ym, fm, NULL);
      memcpy (prev, y1, (size_t) nn * sizeof (double));
      for (int i = 0; i < nn; i++)
        y1[i] = y0[i] + h * fm[i];
      if (it > 5 && ts_maxdiff (nn, prev, y1) == 0.0)
        break;
    }
}

/* Gauss-Legendre RK, s = 2: K_i = f(y0 + h sum_j a_ij K_j), y1 = y0 +
   h/2 (K_1 + K_2), stages by fixed-point iteration to round-off. */
static void
gauss2 (sym_rhs_fn f, int nn, double h, const double *y0, double *y1)
{
  const double r = sqrt (3.0) / 6.0;
  const double a[2][2] = { { 0.25, 0.25 - r }, { 0.25 + r, 0.25 } };
  double K[2][8] = { { 0 } }, Y[8], Kn[2][8];
  f (0.0, y0, K[0], NULL);
  memcpy (K[1], K[0], sizeof K[0]);
  for (int it = 0; it < 500; it++)
    {
      for (int i = 0; i < 2; i++)
        {
          for (int c = 0; c < nn; c++)
            Y[c] = y0[c] + h * (a[i][0] * K[0][c] + a[i][1] * K[1][c]);
          f (0.0, Y, Kn[i], NULL);
        }
      double ch = fmax (ts_maxdiff (nn, Kn[0], K[0]),
                        ts_maxdiff (nn, Kn[1], K[1]));
      memcpy (K, Kn, sizeof K);
      if (it > 5 && ch == 0.0)
        break;
    }
  for (int c = 0; c < nn; c++)
    y1[c] = y0[c] + 0.5 * h * (K[0][c] + K[1][c]);
}

static void
compare_with (void (*ref) (sym_rhs_fn, int, double, const double *,
                           double *),
              int n, int m, sym_rhs_fn f, sym_jac_fn jac, int d,
              const double *y0, double h, double tol, const char *what)
{
  sym_eval ev = ts_eval (d, f, jac, NULL);
  sym_method_opts o;
  sym_spvi_opts so;
  ts_opts (&o, &so, n, m);
  int st, nn = 2 * d;
  void *s = T->alloc (ev.dim, &o, &st);
  double y[8], yr[8], yn[8], worst = 0.0;
  memcpy (y, y0, (size_t) nn * sizeof (double));
  memcpy (yr, y0, (size_t) nn * sizeof (double));
  /* per step from the same point, and a trajectory of a few steps */
  for (int k = 0; k < 8; k++)
    {
      st = T->step (s, &ev, k * h, h, k * h + h, y, yn, NULL);
      T->accept (s);
      double one[8];
      ref (f, nn, h, y, one);
      worst = fmax (worst, ts_maxdiff (nn, one, yn));
      double tmp[8];
      ref (f, nn, h, yr, tmp);
      memcpy (yr, tmp, sizeof tmp);
      memcpy (y, yn, sizeof yn);
    }
  double traj = ts_maxdiff (nn, y, yr);
  CHECK (st == 0 && worst <= tol && traj <= 8 * tol,
         "%s: per step %.3g, after 8 steps %.3g (tol %.3g)", what, worst,
         traj, tol);
  printf ("%s: max per-step difference %.2e, after 8 steps %.2e\n", what,
          worst, traj);
  T->free (s);
}

static void
scenario_known_methods (void)
{
  const double yp[2] = { 1.0, 1.0 }, yn1[2] = { 0.7, -0.4 };
  const double yn2[4] = { 0.3, -0.2, 0.4, 0.5 };
  compare_with (midpoint, 2, 1, ts_pend, ts_pend_jac, 1, yp, 0.25, 1e-13,
                "(2,1) vs implicit midpoint, pendulum");
  compare_with (midpoint, 2, 1, ts_ns1, ts_ns1_jac, 1, yn1, 0.2, 1e-13,
                "(2,1) vs implicit midpoint, nonseparable d=1");
  compare_with (gauss2, 3, 2, ts_pend, ts_pend_jac, 1, yp, 0.25, 5e-14,
                "(3,2) vs 2-stage Gauss, pendulum");
  compare_with (gauss2, 3, 2, ts_ns1, ts_ns1_jac, 1, yn1, 0.2, 5e-14,
                "(3,2) vs 2-stage Gauss, nonseparable d=1");
  compare_with (gauss2, 3, 2, ts_ns2, ts_ns2_jac, 2, yn2, 0.2, 5e-14,
                "(3,2) vs 2-stage Gauss, nonseparable d=2");
}

/* ------------------------------------------------------------- symplectic */
/* M = d y1 / d y0 by central differences of the one-step map (a fresh
   stepper each time: the same start of Newton), then |M'JM - J|. */
static double
symplecticity (int n, int m, int d, sym_rhs_fn f, sym_jac_fn jac,
               void *user, const double *y0, double h)
{
  sym_eval ev = ts_eval (d, f, jac, user);
  sym_method_opts o;
  sym_spvi_opts so;
  ts_opts (&o, &so, n, m);
  int st = 0, nn = 2 * d;
  double M[64], yp[8], ym[8], y1p[8], y1m[8];
  for (int c = 0; c < nn; c++)
    {
      double del = 1e-5 * fmax (1.0, fabs (y0[c]));
      memcpy (yp, y0, (size_t) nn * sizeof (double));
      memcpy (ym, y0, (size_t) nn * sizeof (double));
      yp[c] += del;
      ym[c] -= del;
      for (int side = 0; side < 2; side++)
        {
          int sa;
          void *s = T->alloc (ev.dim, &o, &sa);
          st |= s ? T->step (s, &ev, 0.0, h, h, side ? ym : yp,
                             side ? y1m : y1p, NULL) : sa;
          T->free (s);
        }
      for (int r = 0; r < nn; r++)
        M[r + c * nn] = (y1p[r] - y1m[r]) / (yp[c] - ym[c]);
    }
  CHECK (st == 0, "symplecticity steps: %d", st);
  /* (M'JM)_ij = sum_k M_ki (JM)_kj, J = [0 I; -I 0] */
  double dev = 0.0;
  for (int i = 0; i < nn; i++)
    for (int j = 0; j < nn; j++)
      {
        double v = 0.0;
        for (int k = 0; k < d; k++)
          v += M[k + i * nn] * M[(d + k) + j * nn]
               - M[(d + k) + i * nn] * M[k + j * nn];
        double Jij = (j == i + d) ? 1.0 : (i == j + d) ? -1.0 : 0.0;
        dev = fmax (dev, fabs (v - Jij));
      }
  return dev;
}

static void
scenario_symplectic (void)
{
  const double y1[2] = { 0.7, -0.4 }, y2[4] = { 0.3, -0.2, 0.4, 0.5 };
  static const int pairs[][2] = { { 2, 1 }, { 4, 3 }, { 3, 3 }, { 5, 4 },
                                  { 4, 2 } };
  double worst = 0.0;
  for (size_t p = 0; p < sizeof pairs / sizeof pairs[0]; p++)
    {
      int n = pairs[p][0], m = pairs[p][1];
      double d1 = symplecticity (n, m, 1, ts_ns1, ts_ns1_jac, NULL, y1, 0.3);
      double d2 = symplecticity (n, m, 2, ts_ns2, ts_ns2_jac, NULL, y2, 0.3);
      CHECK (d1 <= 1e-8 && d2 <= 1e-8, "(%d,%d): |M'JM - J| = %.3g (d=1), "
             "%.3g (d=2)", n, m, d1, d2);
      worst = fmax (worst, fmax (d1, d2));
    }
  /* the test sees a non-symplectic map: the damped pendulum */
  ts_user u = { 0 };
  u.gamma = 0.1;
  double yp[2] = { 1.0, 1.0 };
  double dd = symplecticity (4, 3, 1, ts_pend, ts_pend_jac, &u, yp, 0.3);
  CHECK (dd > 1e-3, "damped pendulum: %.3g", dd);
  printf ("symplecticity: max |M'JM - J| %.2e (damped pendulum: %.2e)\n",
          worst, dd);
}

/* --------------------------------------------------- symmetric, predictor */
/* the method is symmetric: a step back from the end returns to the start */
static void
scenario_symmetric (void)
{
  sym_eval ev = ts_eval (2, ts_ns2, ts_ns2_jac, NULL);
  sym_method_opts o;
  sym_spvi_opts so;
  ts_opts (&o, &so, 4, 3);
  int st;
  void *s = T->alloc (ev.dim, &o, &st);
  double y0[4] = { 0.3, -0.2, 0.4, 0.5 }, y1[4], y2[4];
  st = T->step (s, &ev, 0.0, 0.3, 0.3, y0, y1, NULL);
  T->accept (s);
  st |= T->step (s, &ev, 0.3, -0.3, 0.0, y1, y2, NULL);
  CHECK (st == 0 && ts_maxdiff (4, y0, y2) < 1e-14, "back and forth: %.3g",
         ts_maxdiff (4, y0, y2));
  T->free (s);
}

/* The predictor: continuing steps take fewer iterations than steps
   from the Euler start, with the same results (to the Newton
   tolerance). */
static void
scenario_predictor (void)
{
  sym_method_opts o;
  sym_spvi_opts so;
  ts_opts (&o, &so, 4, 3);
  int st;
  double y0[4] = { 0.3, -0.2, 0.4, 0.5 }, ya[4], yb[4], yn[4];
  memcpy (ya, y0, sizeof ya);
  memcpy (yb, y0, sizeof yb);
  sym_eval s1 = ts_eval (2, ts_ns2, ts_ns2_jac, NULL);
  sym_eval s2 = ts_eval (2, ts_ns2, ts_ns2_jac, NULL);
  void *a = T->alloc (s1.dim, &o, &st), *b = T->alloc (s2.dim, &o, &st);
  const double h = 0.1;
  int bad = 0;
  for (int k = 0; k < 200; k++)
    {
      bad |= T->step (a, &s1, k * h, h, k * h + h, ya, yn, NULL);
      T->accept (a);
      memcpy (ya, yn, sizeof yn);
      /* an autonomous system: starting the step a hair later than the
         last one ended changes nothing but the predictor (off) */
      bad |= T->step (b, &s2, k * h * (1 + 1e-8), h, k * h * (1 + 1e-8) + h,
                      yb, yn, NULL);
      T->accept (b);
      memcpy (yb, yn, sizeof yn);
    }
  double dif = ts_maxdiff (4, ya, yb);
  printf ("predictor, nonseparable d=2, (4,3), h = 0.1: %.2f Newton "
          "iterations and %.2f rhs calls per step (%.2f and %.2f with the "
          "Euler start); difference %.1e\n", s1.st.cnt.nnewton / 200.0,
          s1.st.cnt.nrhs / 200.0, s2.st.cnt.nnewton / 200.0,
          s2.st.cnt.nrhs / 200.0, dif);
  CHECK (! bad && dif < 1e-12, "predictor vs Euler start: %d %.3g", bad,
         dif);
  CHECK (s1.st.cnt.nnewton < s2.st.cnt.nnewton,
         "predictor iterations %ld vs %ld", s1.st.cnt.nnewton,
         s2.st.cnt.nnewton);
  /* energy stays near its start (bounded error of a symplectic method) */
  double H0 = ts_ns2_H (y0), dH = fabs (ts_ns2_H (ya) - H0);
  CHECK (dH < 1e-7, "energy error %.3g", dH);
  T->free (a);
  T->free (b);
}

/* ------------------------------------------------------- many nodes */

/* H = (q^2 + p^2)^2 / 4: a rotation at the rate w = q^2 + p^2 */
static int
quartic (double t, const double *y, double *dy, void *user)
{
  (void) t;
  (void) user;
  double w = y[0] * y[0] + y[1] * y[1];
  dy[0] = w * y[1];
  dy[1] = -w * y[0];
  return 0;
}

static int
quartic_jac (double t, const double *y, double *df, void *user)
{
  (void) t;
  (void) user;
  double q = y[0], p = y[1], w = q * q + p * p;
  df[0] = 2 * q * p;             /* column-major df/dy */
  df[1] = -(w + 2 * q * q);
  df[2] = w + 2 * p * p;
  df[3] = -2 * p * q;
  return 0;
}

/* (Nodes + 1, Nodes) on the rotation from (1, 0.5) with steps h to t
   = 40 (nearest step point): the status, the error there against the
   exact solution into *err, the Newton corrections per step into *its */
static int
rotation_run (int m, double h, double *err, double *its)
{
  sym_eval ev = ts_eval (1, quartic, quartic_jac, NULL);
  sym_method_opts o;
  sym_spvi_opts so;
  ts_opts (&o, &so, m + 1, m);
  int st;
  void *s = T->alloc (ev.dim, &o, &st);
  double y[2] = { 1.0, 0.5 };
  const int ns = (int) (40.0 / h);
  st = ts_run_fixed (T, s, &ev, 0.0, h, ns, y);
  double t = ns * h, w = 1.25;
  *err = fmax (fabs (y[0] - (cos (w * t) + 0.5 * sin (w * t))),
               fabs (y[1] - (-sin (w * t) + 0.5 * cos (w * t))));
  *its = (double) ev.st.cnt.nnewton / ns;
  printf ("rotation, Nodes = %d, h = %g, %d steps: error %.2e, %.2f "
          "corrections per step\n", m, h, ns, *err, *its);
  T->free (s);
  return st;
}

/* Many nodes at a long step: the continued prediction, whose noise the
   continuation amplifies like 5.8^Nodes, is cut to the modes above its
   noise; every run reaches t = 40.  Steps so long that Newton fails from
   the Euler start of the first step (off by O(h |f'|)) are reached from
   shorter steps (spvi_lengthen). */
static void
scenario_many_nodes (void)
{
  const int ms[] = { 15, 20, 25, 30, 40 };
  double err, its;
  for (size_t i = 0; i < sizeof ms / sizeof ms[0]; i++)
    {
      int st = rotation_run (ms[i], 1.0, &err, &its);
      CHECK (st == 0 && err < 1e-12 && its < 4.25, "Nodes = %d: status %d "
             "(%s), error %.3g, %.2f corrections per step", ms[i], st,
             sym_status_name (st), err, its);
    }
  const struct { int m; double h, tol; } ls[] = {
    { 5, 2.0, 1e-3 }, { 8, 1.5, 1e-10 }, { 8, 2.0, 1e-9 },
    { 12, 2.5, 1e-12 }, { 20, 2.0, 1e-12 }
  };
  for (size_t i = 0; i < sizeof ls / sizeof ls[0]; i++)
    {
      int st = rotation_run (ls[i].m, ls[i].h, &err, &its);
      CHECK (st == 0 && err < ls[i].tol, "Nodes = %d, h = %g: status %d "
             "(%s), error %.3g", ls[i].m, ls[i].h, st, sym_status_name (st),
             err);
    }
}

int
main (void)
{
  scenario_alloc_pairs ();
  scenario_alloc_options ();
  scenario_bad_steps ();
  scenario_alloc_failures ();
  scenario_orders ();
  scenario_known_methods ();
  scenario_symplectic ();
  scenario_symmetric ();
  scenario_predictor ();
  scenario_many_nodes ();
  return tu_finish ("test_spvi_method");
}
