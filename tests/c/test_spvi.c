/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* test_spvi.c -- the SPVI stepper through its table (alloc / step / accept
   / dense / reset / free), with C callbacks.  The long Kepler run is in
   test_spvi_kepler.c, the Newton matrix against finite differences of the
   residual in test_spvi_internal.c. */
#include "sym.h"
#include "testutil.h"
#include "test_spvi_systems.h"

#include <stdint.h>

static const sym_stepper_type *T;

/* ---------------------------------------------------------------- alloc */
static void
test_alloc (void)
{
  ts_user u = { 0 };
  sym_system sys = ts_system (1, ts_pend, ts_pend_jac, &u);
  int st = 12345;
  struct { int n, m, ok, order; } cases[] = {
    { 2, 1, 1, 2 }, { 3, 2, 1, 4 }, { 4, 3, 1, 6 }, { 3, 3, 1, 4 },
    { 4, 2, 1, 2 }, { 5, 4, 1, 8 }, { 2, 2, 1, 2 }, { 6, 3, 1, 2 },
    { 9, 8, 1, 16 }, { 3, 1, 0, 0 }, { 5, 2, 0, 0 }, { 1, 3, 0, 0 },
    { 7, 3, 0, 0 }, { 2, -1, 0, 0 }, { 101, 100, 0, 0 }
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
    {
      sym_method_opts o = ts_opts (cases[i].n, cases[i].m);
      void *s = T->alloc (&sys, &o, &st);
      if (cases[i].ok)
        {
          CHECK (s && st == 0, "(%d,%d) refused: %d", cases[i].n, cases[i].m,
                 st);
          if (s)
            {
              CHECK (T->method_order (s) == cases[i].order
                     && T->err_order (s) == cases[i].order,
                     "(%d,%d): order %d, expected %d", cases[i].n,
                     cases[i].m, T->method_order (s), cases[i].order);
              T->free (s);
            }
        }
      else
        {
          CHECK (! s && st == SYM_EBADINPUT, "(%d,%d) accepted: %d",
                 cases[i].n, cases[i].m, st);
          T->free (s);   /* NULL is fine */
        }
    }
  /* defaults: Nodes 3, Q_DoFs = Nodes + 1 */
  sym_method_opts o = ts_opts (0, 0);
  void *s = T->alloc (&sys, &o, &st);
  CHECK (s && T->method_order (s) == 6 && T->order == 6, "defaults");
  T->free (s);
  s = T->alloc (&sys, NULL, &st);
  CHECK (s && T->method_order (s) == 6, "NULL options");
  T->free (s);
  o = ts_opts (0, 2);
  s = T->alloc (&sys, &o, &st);
  CHECK (s && T->method_order (s) == 4, "Nodes 2 alone gives (3,2)");
  T->free (s);
  sym_system bad = ts_system (0, ts_pend, NULL, NULL);
  o = ts_opts (3, 2);
  CHECK (! T->alloc (&bad, &o, &st) && st == SYM_EBADINPUT, "dim 0");
  o.newton_tol = -1;
  CHECK (! T->alloc (&sys, &o, &st) && st == SYM_EBADINPUT, "tol < 0");
  o = ts_opts (3, 2);
  o.newton_matrix = SYM_MATRIX_NEW + 1;
  CHECK (! T->alloc (&sys, &o, &st) && st == SYM_EBADINPUT, "matrix 3");
  o.newton_matrix = -1;
  CHECK (! T->alloc (&sys, &o, &st) && st == SYM_EBADINPUT, "matrix -1");
  /* dense before any step */
  o = ts_opts (3, 2);
  s = T->alloc (&sys, &o, &st);
  double y[2];
  CHECK (T->dense (s, &sys, 0.0, y) == SYM_EBADINPUT, "dense, no step");
  double y0[2] = { 1, 1 }, y1[2];
  CHECK (T->step (s, &sys, 0.0, 0.0, 0.0, y0, y1, NULL) == SYM_EBADINPUT,
         "h = 0");
  CHECK (T->step (s, &sys, 0.0, NAN, NAN, y0, y1, NULL) == SYM_EBADINPUT,
         "h NaN");
  CHECK (T->step (s, &sys, 0.0, 0.1, INFINITY, y0, y1, NULL)
         == SYM_EBADINPUT, "tend Inf");
  T->free (s);
}

/* Allocation failures: fail the k-th allocation for every k until alloc
   succeeds; each failure returns NULL with SYM_ENOMEM and leaves nothing
   allocated. */
static long live_blocks, alloc_count, fail_alloc_at;

static void *
counting_alloc (size_t n)
{
  if (++alloc_count == fail_alloc_at)
    return NULL;
  void *p = malloc (n);
  if (p)
    live_blocks++;
  return p;
}

static void
counting_free (void *p)
{
  if (p)
    live_blocks--;
  free (p);
}

static void
test_alloc_failures (void)
{
  sym_system sys = ts_system (2, ts_kep, ts_kep_jac, NULL);
  sym_method_opts o = ts_opts (4, 3);
  o.want_error = 1;
  sym_set_allocator (counting_alloc, counting_free);
  int nfail = 0, bad = 0;
  for (long k = 1; k < 1000; k++)
    {
      int st = 0;
      alloc_count = 0;
      fail_alloc_at = k;
      void *s = T->alloc (&sys, &o, &st);
      if (s)
        {
          T->free (s);
          break;
        }
      nfail++;
      if (st != SYM_ENOMEM || live_blocks != 0)
        bad++;
    }
  fail_alloc_at = 0;
  CHECK (nfail > 10 && bad == 0 && live_blocks == 0,
         "%d failures, %d bad, %ld blocks live", nfail, bad, live_blocks);

  /* the companion allocated lazily by a step that wants yerr */
  o.want_error = 0;
  alloc_count = 0;
  void *s = T->alloc (&sys, &o, &(int) { 0 });
  fail_alloc_at = alloc_count + 1;
  double y[4], yn[4], ye[4];
  ts_kep_y0 (0.6, y);
  int st = T->step (s, &sys, 0.0, 0.05, 0.05, y, yn, ye);
  CHECK (st == SYM_ENOMEM, "lazy companion: %d", st);
  fail_alloc_at = 0;
  st = T->step (s, &sys, 0.0, 0.05, 0.05, y, yn, ye);
  CHECK (st == 0, "then fine: %d", st);
  T->free (s);
  sym_set_allocator (NULL, NULL);
  CHECK (live_blocks == 0, "%ld blocks live", live_blocks);
}

/* ---------------------------------------------------------------- orders */
static void
test_orders (void)
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
          sym_system sys = ts_system (1, ts_pend, ts_pend_jac, &u);
          sym_method_opts o = ts_opts (n, m);
          int st;
          void *s = T->alloc (&sys, &o, &st);
          order = T->method_order (s);
          double y[2] = { 1.0, 1.0 };
          long per = lround (1.0 / hs[k]);
          err[k] = 0.0;
          for (int i = 1; i <= 10 && ! st; i++)
            {
              st = ts_run_fixed (T, s, &sys, (double) (i - 1), hs[k], per,
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
  sym_system sys = ts_system (d, f, jac, NULL);
  sym_method_opts o = ts_opts (n, m);
  int st, nn = 2 * d;
  void *s = T->alloc (&sys, &o, &st);
  double y[8], yr[8], yn[8], worst = 0.0;
  memcpy (y, y0, (size_t) nn * sizeof (double));
  memcpy (yr, y0, (size_t) nn * sizeof (double));
  /* per step from the same point, and a trajectory of a few steps */
  for (int k = 0; k < 8; k++)
    {
      st = T->step (s, &sys, k * h, h, k * h + h, y, yn, NULL);
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
test_known_methods (void)
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
/* M = d y1 / d y0 by central differences of the one-step map (a reset
   stepper each time: the same start of Newton), then |M'JM - J|. */
static double
symplecticity (int n, int m, int d, sym_rhs_fn f, sym_jac_fn jac,
               void *user, const double *y0, double h)
{
  sym_system sys = ts_system (d, f, jac, user);
  sym_method_opts o = ts_opts (n, m);
  int st, nn = 2 * d;
  void *s = T->alloc (&sys, &o, &st);
  double M[64], yp[8], ym[8], y1p[8], y1m[8];
  for (int c = 0; c < nn; c++)
    {
      double del = 1e-5 * fmax (1.0, fabs (y0[c]));
      memcpy (yp, y0, (size_t) nn * sizeof (double));
      memcpy (ym, y0, (size_t) nn * sizeof (double));
      yp[c] += del;
      ym[c] -= del;
      T->reset (s);
      st |= T->step (s, &sys, 0.0, h, h, yp, y1p, NULL);
      T->reset (s);
      st |= T->step (s, &sys, 0.0, h, h, ym, y1m, NULL);
      for (int r = 0; r < nn; r++)
        M[r + c * nn] = (y1p[r] - y1m[r]) / (yp[c] - ym[c]);
    }
  T->free (s);
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
test_symplectic (void)
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

/* ------------------------------------------------------- Jacobian sources */
/* Kepler's Df times kep_scale: a user's Df far too large */
static double kep_scale;
static int
kep_jac_scaled (double t, const double *y, double *df, void *user)
{
  int st = ts_kep_jac (t, y, df, user);
  for (int i = 0; i < 16; i++)
    df[i] *= kep_scale;
  return st;
}

static void
test_jacobian_sources (void)
{
  const double h = 2 * TS_PI / 100;
  double ya[4], yf[4], yb[4];
  ts_kep_y0 (0.6, ya);
  memcpy (yf, ya, sizeof ya);
  memcpy (yb, ya, sizeof ya);
  sym_system sa = ts_system (2, ts_kep, ts_kep_jac, NULL);
  sym_system sf = ts_system (2, ts_kep, NULL, NULL);
  sym_system sb = ts_system (2, ts_kep, ts_kep_jac, NULL);
  sb.rhs_batch = ts_kep_batch;
  sym_method_opts o = ts_opts (4, 3);
  int st;
  void *s1 = T->alloc (&sa, &o, &st), *s2 = T->alloc (&sf, &o, &st);
  void *s3 = T->alloc (&sb, &o, &st);
  int st1 = ts_run_fixed (T, s1, &sa, 0.0, h, 1000, ya);
  int st2 = ts_run_fixed (T, s2, &sf, 0.0, h, 1000, yf);
  int st3 = ts_run_fixed (T, s3, &sb, 0.0, h, 1000, yb);
  double dif = ts_maxdiff (4, ya, yf);
  CHECK (st1 == 0 && st2 == 0 && dif <= 1e-10,
         "analytic vs finite-difference Jacobian: %.3g", dif);
  /* the analytic Df's only differences: its probe (f and one state) */
  CHECK (sa.cnt.nfd == 2 && sf.cnt.nfd > 0 && sf.cnt.njac == 0,
         "counters: nfd %ld / %ld", sa.cnt.nfd, sf.cnt.nfd);
  /* A Df too large by c makes Newton's corrections 1/c of what they
     should be: with c = 1e12 they are below round-off from the first on,
     and each solve stops at once, accepted, at its start.  Without the
     probe of the first Df (jac_probed set by hand) one period with c =
     1e12 ends far from the orbit (measured: 25 away); with it, Df is
     dropped in the first step (at its first node) and finite differences
     give the steps of the right Df. */
  {
    double yk[4], yu[4];
    kep_scale = 1e12;
    for (int probe = 0; probe < 2; probe++)
      {
        double *yy = probe ? yk : yu;
        ts_kep_y0 (0.6, yy);
        sym_system sk = ts_system (2, ts_kep, kep_jac_scaled, NULL);
        sk.jac_probed = ! probe;
        void *sp = T->alloc (&sk, &o, &st);
        int stk = ts_run_fixed (T, sp, &sk, 0.0, h, 100, yy);
        T->free (sp);
        CHECK (stk == 0 && sk.jac_dropped == probe
               && (! probe || (sk.jac_dropped_t >= 0.0
                               && sk.jac_dropped_t < h && sk.jac == NULL)),
               "Df times 1e12, probe %d: status %d, dropped %d at t = %g",
               probe, stk, sk.jac_dropped, sk.jac_dropped_t);
      }
    double yr[4];
    ts_kep_y0 (0.6, yr);
    sym_system sr = ts_system (2, ts_kep, ts_kep_jac, NULL);
    void *sp = T->alloc (&sr, &o, &st);
    ts_run_fixed (T, sp, &sr, 0.0, h, 100, yr);
    T->free (sp);
    printf ("Kepler (4,3), one period with Df times 1e12: %.3g from the "
            "steps of the right Df (%.3g without the probe)\n",
            ts_maxdiff (4, yk, yr), ts_maxdiff (4, yu, yr));
    CHECK (ts_maxdiff (4, yk, yr) <= 1e-10 && ts_maxdiff (4, yu, yr) > 1.0,
           "Df times 1e12: %.3g with the probe, %.3g without",
           ts_maxdiff (4, yk, yr), ts_maxdiff (4, yu, yr));
  }
  printf ("Kepler (4,3), 10 periods: analytic vs FD Jacobian differ by "
          "%.2e; calls/step: analytic %.2f rhs + %.3f jac, FD %.2f rhs "
          "(%.2f of them FD)\n", dif, sa.cnt.nrhs / 1000.0,
          sa.cnt.njac / 1000.0, sf.cnt.nrhs / 1000.0, sf.cnt.nfd / 1000.0);
  /* Vectorized: the batch callback gives the same numbers, bit for bit,
     with one call per residual instead of m */
  CHECK (st3 == 0 && ts_maxdiff (4, ya, yb) == 0.0,
         "batch vs single calls differ by %.3g", ts_maxdiff (4, ya, yb));
  CHECK (sb.cnt.nrhs_states == sa.cnt.nrhs_states
         && 2 * sb.cnt.nrhs < sa.cnt.nrhs,
         "batch: %ld calls (%ld states) vs %ld calls (%ld states)",
         sb.cnt.nrhs, sb.cnt.nrhs_states, sa.cnt.nrhs, sa.cnt.nrhs_states);
  printf ("Vectorized: %.2f rhs calls per step (%.2f states) vs %.2f\n",
          sb.cnt.nrhs / 1000.0, sb.cnt.nrhs_states / 1000.0,
          sa.cnt.nrhs / 1000.0);
  /* Vectorized with finite differences: each step's matrix is new (see
     core_solve), from one call for the nodes and their 2d m perturbed
     states, whose f the residual there reuses; then a step needs one
     call when its first, exact Newton correction is enough.  The steps
     are those of the analytic Jacobian to round-off (measured 1.57 calls
     per step instead of the 9.42 of single calls, 2.37 of the kept
     matrix) */
  double yfb[4];
  ts_kep_y0 (0.6, yfb);
  sym_system sfb = ts_system (2, ts_kep, NULL, NULL);
  sfb.rhs_batch = ts_kep_batch;
  void *s4 = T->alloc (&sfb, &o, &st);
  int st4 = ts_run_fixed (T, s4, &sfb, 0.0, h, 1000, yfb);
  CHECK (st4 == 0 && ts_maxdiff (4, ya, yfb) <= 1e-10,
         "batched FD vs analytic Jacobian differ by %.3g",
         ts_maxdiff (4, ya, yfb));
  CHECK (sfb.cnt.nfd == 1000 && sfb.cnt.nrhs_states - 1 == 15 * sfb.cnt.nfd
                                + 3 * (sfb.cnt.nrhs - 1 - sfb.cnt.nfd)
         && sfb.cnt.nrhs <= 1650,
         "batched FD: %ld FD calls (%ld states), %ld calls in all",
         sfb.cnt.nfd, sfb.cnt.nrhs_states, sfb.cnt.nrhs);
  printf ("Vectorized, FD Jacobians: %.2f rhs calls per step (%.2f of them "
          "FD) vs %.2f (%.2f) with single calls\n", sfb.cnt.nrhs / 1000.0,
          sfb.cnt.nfd / 1000.0, sf.cnt.nrhs / 1000.0, sf.cnt.nfd / 1000.0);
  /* With the matrix kept (asked for): the same steps as single calls, bit
     for bit, each matrix's 2d m perturbed states and the nodes' own f in
     one call (the other calls: the first step's Euler start, one state,
     then the nodes' evaluations, 3 states each) */
  double yfk[4];
  ts_kep_y0 (0.6, yfk);
  sym_system sfk = ts_system (2, ts_kep, NULL, NULL);
  sfk.rhs_batch = ts_kep_batch;
  sym_method_opts ok = o;
  ok.newton_matrix = SYM_MATRIX_KEPT;
  void *s5 = T->alloc (&sfk, &ok, &st);
  int st5 = ts_run_fixed (T, s5, &sfk, 0.0, h, 1000, yfk);
  CHECK (st5 == 0 && ts_maxdiff (4, yf, yfk) == 0.0,
         "batched FD, kept matrix, vs single calls differ by %.3g",
         ts_maxdiff (4, yf, yfk));
  CHECK (sfk.cnt.nrhs_states == sf.cnt.nrhs_states && sfk.cnt.nfd > 0
         && sfk.cnt.nfd * 12 == sf.cnt.nfd
         && sfk.cnt.nrhs - sfk.cnt.nfd
            == 1 + (sf.cnt.nrhs - sf.cnt.nfd - 1) / 3 - sfk.cnt.nfd,
         "batched FD, kept: %ld FD calls (%ld states) vs %ld; rhs %ld vs %ld",
         sfk.cnt.nfd, sfk.cnt.nrhs_states, sf.cnt.nfd, sfk.cnt.nrhs,
         sf.cnt.nrhs);
  T->free (s5);
  T->free (s4);
  T->free (s1);
  T->free (s2);
  T->free (s3);
}

/* f and Df in one call (the Hessian as FCN's second output): the same
   arithmetic as ts_kep and ts_kep_jac; a NaN in Df at call nan_at */
static long both_calls, both_nan_at;

static int
kep_both (double t, const double *y, double *dy, double *df, void *user)
{
  int st = ts_kep (t, y, dy, user);
  if (st)
    return st;
  st = ts_kep_jac (t, y, df, user);
  if (++both_calls == both_nan_at)
    df[3] = NAN;
  return st;
}

/* The combined call gives the same steps, bit for bit, and saves the rhs
   call of every node at which a matrix is evaluated: the residual there
   reuses its f.  With a new matrix at every step (asked for), it gives m
   calls per step that also give f at the nodes, and measured 1.71
   further rhs calls per step instead of 7.11 + 0.57 jac calls; the steps
   agree with the kept matrix to round-off. */
static void
test_rhs_jac (void)
{
  const double h = 2 * TS_PI / 100;
  double ya[4], yc[4], yn[4];
  ts_kep_y0 (0.6, ya);
  memcpy (yc, ya, sizeof ya);
  memcpy (yn, ya, sizeof ya);
  sym_system sa = ts_system (2, ts_kep, ts_kep_jac, NULL);
  sym_system sc = ts_system (2, ts_kep, ts_kep_jac, NULL);
  sym_system snew = ts_system (2, ts_kep, ts_kep_jac, NULL);
  sc.rhs_jac = snew.rhs_jac = kep_both;
  sym_method_opts o = ts_opts (4, 3), onew = o;
  onew.newton_matrix = SYM_MATRIX_NEW;
  int st;
  void *s1 = T->alloc (&sa, &o, &st), *s2 = T->alloc (&sc, &o, &st);
  both_calls = both_nan_at = 0;
  int st1 = ts_run_fixed (T, s1, &sa, 0.0, h, 1000, ya);
  int st2 = ts_run_fixed (T, s2, &sc, 0.0, h, 1000, yc);
  CHECK (st1 == 0 && st2 == 0 && ts_maxdiff (4, ya, yc) == 0.0,
         "combined f and Df: statuses %d %d, differ by %.3g", st1, st2,
         ts_maxdiff (4, ya, yc));
  /* the probe of Df costs 1 call with f in the combined call, else 2 */
  CHECK (sc.cnt.njac == sa.cnt.njac && both_calls == sc.cnt.njac
         && sa.cnt.njac > 0 && sc.cnt.nfd == 1 && sa.cnt.nfd == 2
         && sc.cnt.nrhs == sa.cnt.nrhs - sa.cnt.njac - 1,
         "combined: %ld rhs + %ld jac (%ld calls), separate %ld rhs + %ld "
         "jac", sc.cnt.nrhs, sc.cnt.njac, both_calls, sa.cnt.nrhs,
         sa.cnt.njac);
  printf ("f with Df in one call: %.3f rhs + %.3f jac calls per step "
          "(separate: %.3f + %.3f)\n", sc.cnt.nrhs / 1000.0,
          sc.cnt.njac / 1000.0, sa.cnt.nrhs / 1000.0, sa.cnt.njac / 1000.0);
  T->free (s1);
  T->free (s2);
  s1 = T->alloc (&snew, &onew, &st);
  both_calls = 0;
  st1 = ts_run_fixed (T, s1, &snew, 0.0, h, 1000, yn);
  CHECK (st1 == 0 && ts_maxdiff (4, ya, yn) <= 1e-10,
         "new matrix every step: status %d, differs by %.3g", st1,
         ts_maxdiff (4, ya, yn));
  CHECK (both_calls == snew.cnt.njac && snew.cnt.njac == 3000
         && snew.cnt.nrhs <= 1800 && snew.cnt.nfd == 1
         && (snew.cnt.nrhs - snew.cnt.nfd) % 3 == 1,
         "new matrix every step: %ld rhs + %ld jac (%ld calls)",
         snew.cnt.nrhs, snew.cnt.njac, both_calls);
  printf ("  a new matrix every step: %.3f rhs + %.3f jac calls per step\n",
          snew.cnt.nrhs / 1000.0, snew.cnt.njac / 1000.0);
  T->free (s1);
  /* a NaN in Df is reported as one, with its time */
  sym_system sn = ts_system (2, ts_kep, ts_kep_jac, NULL);
  sn.rhs_jac = kep_both;
  void *s3 = T->alloc (&sn, &o, &st);
  ts_kep_y0 (0.6, yc);
  both_calls = 0;
  both_nan_at = 2;
  st = T->step (s3, &sn, 0.0, h, h, yc, ya, NULL);
  CHECK (st == SYM_NONFINITE && sn.fail_t > 0.0 && sn.fail_t < h,
         "NaN in the combined Df: %d (%s) at t = %g", st,
         sym_status_name (st), sn.fail_t);
  both_nan_at = 0;
  T->free (s3);
}

/* --------------------------------------------------------- error estimate */
static void
test_error_estimate (void)
{
  /* one step from y0 = [1;1] of the pendulum; the exact local error is
     known from the elliptic solution */
  /* (3,3) reaches its asymptotic slope late (4.46 4.76 4.89 4.95 from
     h = 0.4), so it starts at a smaller h */
  static const int pairs[][2] = { { 4, 3 }, { 3, 2 }, { 3, 3 } };
  static const double h0[] = { 0.4, 0.4, 0.1 };
  for (size_t p = 0; p < sizeof pairs / sizeof pairs[0]; p++)
    {
      int n = pairs[p][0], m = pairs[p][1];
      double en[3], le[3], rel[3];
      int order = 0;
      for (int k = 0; k < 3; k++)
        {
          double h = h0[p] / (1 << k);
          sym_system sys = ts_system (1, ts_pend, ts_pend_jac, NULL);
          sym_method_opts o = ts_opts (n, m);
          o.want_error = 1;
          int st;
          void *s = T->alloc (&sys, &o, &st);
          order = T->err_order (s);
          double y0[2] = { 1, 1 }, y1[2], ye[2], yx[2];
          st = T->step (s, &sys, 0.0, h, h, y0, y1, ye);
          CHECK (st == 0, "step with yerr: %d", st);
          ts_pend_exact (1.0, 1.0, h, yx);
          /* with an estimate the step advances with the companion; the
             estimate is of the low-order value y1 + yerr */
          double d[2] = { y1[0] + ye[0] - yx[0], y1[1] + ye[1] - yx[1] };
          en[k] = fmax (fabs (ye[0]), fabs (ye[1]));
          le[k] = fmax (fabs (d[0]), fabs (d[1]));
          double hi = fmax (fabs (y1[0] - yx[0]), fabs (y1[1] - yx[1]));
          if (k == 2)
            CHECK (hi < 0.1 * le[k], "(%d,%d): advanced value error %.3g "
                   "vs low order %.3g", n, m, hi, le[k]);
          rel[k] = ts_maxdiff (2, ye, d) / le[k];
          T->free (s);
        }
      double s1 = log2 (en[0] / en[1]), s2 = log2 (en[1] / en[2]);
      printf ("error estimate (%d,%d): |yerr| %.3e %.3e %.3e (slopes %.2f "
              "%.2f, expected %d); |yerr - true error|/|true error| %.2g "
              "%.2g %.2g\n", n, m, en[0], en[1], en[2], s1, s2, order + 1,
              rel[0], rel[1], rel[2]);
      CHECK (fabs (s2 - (order + 1)) <= 0.3 && fabs (s1 - (order + 1)) <= 0.5,
             "(%d,%d): yerr slopes %.2f %.2f, expected %d", n, m, s1, s2,
             order + 1);
      /* the companion is of higher order: yerr is the true local error */
      CHECK (rel[1] < 0.1 && rel[2] < 0.1, "(%d,%d): yerr vs true error "
             "%.2g %.2g", n, m, rel[1], rel[2]);
    }
}

/* ---------------------------------------------- adaptive solve tolerances */
/* The same steps with the adaptive tolerances in the options (the
   method's solve stopping at 1e-3 of the smallest error they allow, the
   companion's at 1e-4) and without (both converged to round-off): the
   advanced values and the estimates agree to those fractions, for fewer
   calls.  States along a Kepler orbit (e = 0.6), h = 0.05, RelTol =
   AbsTol = 1e-6; each step from a reset stepper (Euler start, new
   matrices), and each step after the one before (polynomial start, kept
   matrices). */
static void
test_adaptive_tolerances (void)
{
  const double rtol = 1e-6, atol = 1e-6, h = 0.05;
  sym_system sl = ts_system (2, ts_kep, ts_kep_jac, NULL);
  sym_system st_ = ts_system (2, ts_kep, ts_kep_jac, NULL);
  sym_method_opts ol = ts_opts (4, 3), ot = ol;
  ol.want_error = ot.want_error = 1;
  ol.est_rtol = rtol;
  ol.est_atol = atol;
  int st;
  void *sa = T->alloc (&sl, &ol, &st), *sb = T->alloc (&st_, &ot, &st);
  double y[4], ya[4], yb[4], ea[4], eb[4];
  double worst_y = 0.0, worst_e = 0.0;
  int bad = 0;
  for (int pass = 0; pass < 2; pass++)
    {
      ts_kep_y0 (0.6, y);
      T->reset (sa);
      T->reset (sb);
      double t = 0.0;
      for (int k = 0; k < 200 && ! bad; k++)
        {
          if (pass == 0)
            {
              T->reset (sa);
              T->reset (sb);
            }
          int s1 = T->step (sa, &sl, t, h, t + h, y, ya, ea);
          int s2 = T->step (sb, &st_, t, h, t + h, y, yb, eb);
          if (s1 || s2)
            {
              bad = 1;
              CHECK (0, "pass %d step %d: status %d %d", pass, k, s1, s2);
              break;
            }
          T->accept (sa);
          T->accept (sb);
          double w = INFINITY;
          for (int i = 0; i < 4; i++)
            w = fmin (w, fmax (atol, rtol * fabs (y[i])));
          worst_y = fmax (worst_y, ts_maxdiff (4, ya, yb) / w);
          worst_e = fmax (worst_e, ts_maxdiff (4, ea, eb) / w);
          memcpy (y, yb, sizeof y);
          t += h;
        }
    }
  long ca = sl.cnt.nrhs + sl.cnt.njac, cb = st_.cnt.nrhs + st_.cnt.njac;
  printf ("adaptive tolerances, Kepler (4,3), h = 0.05, 400 steps: values "
          "differ by %.2g, estimates by %.2g of the error floor; %ld "
          "against %ld rhs + jac calls converged to round-off\n", worst_y,
          worst_e, ca, cb);
  /* bounds twice the stopping tests (their estimates of the error left,
     not bounds; the companion starts from the method's solution) */
  CHECK (worst_y <= 2 * 1e-4, "advanced values differ by %.3g of the floor",
         worst_y);
  CHECK (worst_e <= 2 * (1e-3 + 1e-4), "estimates differ by %.3g of the "
         "floor", worst_e);
  CHECK (ca < 0.95 * cb, "calls %ld, converged to round-off %ld", ca, cb);
  T->free (sa);
  T->free (sb);
}

/* Adaptive Kepler, e = 0.6, 10 periods, RelTol = AbsTol = 1e-4..1e-12:
   the end-point error against the exact solution (the start) follows the
   tolerance down to 1e-12: each 100-fold tighter tolerance gives an
   error at least 30 times smaller. */
static double kep_end[4];

static int
kep_out (double t, const double *y, void *user)
{
  (void) t;
  (void) user;
  memcpy (kep_end, y, sizeof kep_end);
  return 0;
}

static void
test_adaptive_kepler (void)
{
  double err[5];
  long calls[5], failed[5], steps[5];
  for (int k = 0; k < 5; k++)
    {
      double tol = pow (10.0, -4 - 2 * k);
      sym_system sys = ts_system (2, ts_kep, ts_kep_jac, NULL);
      sym_method_opts mo = ts_opts (4, 3);
      sym_driver_opts o;
      memset (&o, 0, sizeof o);
      double y0[4], tr;
      ts_kep_y0 (0.6, y0);
      o.t0 = 0.0;
      o.tf = 10 * 2 * TS_PI;
      o.rtol = tol;
      o.atol = &tol;
      o.atol_len = 1;
      o.refine = 1;
      o.output = kep_out;
      int st = sym_integrate (T, &sys, &mo, &o, y0, &tr);
      CHECK (st == SYM_DONE, "RelTol %g: status %d", tol, st);
      err[k] = ts_maxdiff (4, kep_end, y0);
      calls[k] = sys.cnt.nrhs + sys.cnt.njac;
      failed[k] = sys.cnt.nfailed;
      steps[k] = sys.cnt.nsteps;
    }
  printf ("adaptive Kepler (4,3), 10 periods, RelTol 1e-4..1e-12: end-point "
          "errors %.2e %.2e %.2e %.2e %.2e, rhs + jac calls %ld %ld %ld %ld "
          "%ld, failed/accepted steps %ld/%ld %ld/%ld %ld/%ld %ld/%ld "
          "%ld/%ld\n", err[0], err[1], err[2], err[3], err[4], calls[0],
          calls[1], calls[2], calls[3], calls[4], failed[0], steps[0],
          failed[1], steps[1], failed[2], steps[2], failed[3], steps[3],
          failed[4], steps[4]);
  /* The orbit's fall towards pericentre makes the error grow several-fold
     from step to step at a fixed h; the predictive control (control.c)
     follows that trend: without it a quarter of the steps at RelTol
     1e-4..1e-8 failed (45/131, 85/220, 137/400 failed/accepted); with
     it 24/133, 17/222, 15/404. */
  for (int k = 0; k < 5; k++)
    CHECK (failed[k] <= (k ? 0.1 : 0.2) * (steps[k] + failed[k]),
           "RelTol 1e-%d: %ld failed steps of %ld", 4 + 2 * k, failed[k],
           steps[k] + failed[k]);
  for (int k = 1; k < 5; k++)
    CHECK (err[k] * 30 <= err[k - 1], "RelTol 1e-%d: error %.3g, at 1e-%d "
           "%.3g", 4 + 2 * k, err[k], 2 + 2 * k, err[k - 1]);
  /* At RelTol 1e-12 the error is that of the round-off of the solves:
     orbits turned by 0 to 1.1e-14 rad end 6.4e-14 to 4.5e-12 off (odeSPVI,
     tests/test_spvi.m, 12 angles); 2.2e-12 here */
  CHECK (err[4] < 1e-11, "RelTol 1e-12: error %.3g", err[4]);
}

/* ----------------------------------------------------------- dense output */
/* Ten steps of h with the pair (n, m) on the harmonic oscillator (exact:
   q = q0 cos t + p0 sin t, p = -q0 sin t + p0 cos t) from (1, 0.5) at
   t = 0.3: the largest error of the dense output inside the steps
   against the exact flow from each step's start (its local error), the
   largest mismatch at the steps' ends into *ends, and the rhs calls the
   dense output made into *calls. */
static double
dense_osc (int n, int m, double h, double *ends, long *calls)
{
  sym_system sys = ts_system (1, ts_osc, ts_osc_jac, NULL);
  sym_method_opts o = ts_opts (n, m);
  o.want_dense = 1;
  int st;
  void *s = T->alloc (&sys, &o, &st);
  double y[2] = { 1.0, 0.5 }, yn[2], yd[2], t = 0.3, worst = 0.0;
  *ends = 0.0;
  *calls = 0;
  for (int step = 0; step < 10; step++)
    {
      double ys[2] = { y[0], y[1] };
      st |= T->step (s, &sys, t, h, t + h, y, yn, NULL);
      T->accept (s);
      const long before = sys.cnt.nrhs;
      T->dense (s, &sys, t, yd);
      *ends = fmax (*ends, ts_maxdiff (2, yd, ys));
      T->dense (s, &sys, t + h, yd);
      *ends = fmax (*ends, ts_maxdiff (2, yd, yn));
      for (int i = 1; i < 10; i++)
        {
          double tau = h * i / 10.0;
          T->dense (s, &sys, t + tau, yd);
          double ex[2] = { ys[0] * cos (tau) + ys[1] * sin (tau),
                           -ys[0] * sin (tau) + ys[1] * cos (tau) };
          worst = fmax (worst, ts_maxdiff (2, yd, ex));
        }
      *calls += sys.cnt.nrhs - before;
      memcpy (y, yn, sizeof y);
      t += h;
    }
  CHECK (st == 0, "dense run (%d,%d): %d", n, m, st);
  T->free (s);
  return worst;
}

static void
test_dense (void)
{
  /* (4,3): y' interpolated at -1, the m nodes and +1, whose values there
     are off by O(h^(m+1)) (the stage order): local error O(h^(m+2)) =
     O(h^5); the polynomials of the solution alone (q of degree n - 1 = 3)
     gave O(h^4): 9.3e-7 and 5.8e-8, slope 4.00.  f at the step ends, each
     once (the end of one step is the start of the next): 11 calls for 10
     steps. */
  double ends[2], worst[2];
  long calls[2];
  for (int k = 0; k < 2; k++)
    worst[k] = dense_osc (4, 3, 0.2 / (1 << k), &ends[k], &calls[k]);
  double sl = log2 (worst[0] / worst[1]);
  printf ("dense (4,3), oscillator: interior local error %.2e (h=0.2), "
          "%.2e (h=0.1), slope %.2f; endpoints %.1e\n", worst[0], worst[1],
          sl, fmax (ends[0], ends[1]));
  CHECK (ends[0] == 0.0 && ends[1] == 0.0, "endpoints off by %g %g",
         ends[0], ends[1]);
  CHECK (calls[0] == 11 && calls[1] == 11, "dense output made %ld, %ld rhs "
         "calls for 10 steps", calls[0], calls[1]);
  CHECK (sl >= 4.7 && worst[0] < 1e-7, "dense: %.3g %.3g slope %.2f",
         worst[0], worst[1], sl);

  /* the other pairs below order 8 ((3,3), order 4, here): the cubic
     Hermite interpolant through the step's ends, exact there, local error
     O(h^4) (the solution's polynomials gave 1.85e-3 and 2.18e-4, slope
     3.09), f at each end once */
  for (int k = 0; k < 2; k++)
    worst[k] = dense_osc (3, 3, 0.2 / (1 << k), &ends[k], &calls[k]);
  sl = log2 (worst[0] / worst[1]);
  printf ("dense (3,3), oscillator: interior local error %.2e (h=0.2), "
          "%.2e (h=0.1), slope %.2f\n", worst[0], worst[1], sl);
  CHECK (ends[0] == 0.0 && ends[1] == 0.0 && calls[0] == 11
         && calls[1] == 11 && sl >= 3.7 && worst[0] < 1e-5,
         "dense (3,3): ends %g %g, calls %ld %ld, %.3g %.3g slope %.2f",
         ends[0], ends[1], calls[0], calls[1], worst[0], worst[1], sl);

  /* pendulum, (5,4), backwards: dense between the step points agrees with
     the exact solution to the polynomials' accuracy */
  sym_system sys = ts_system (1, ts_pend, ts_pend_jac, NULL);
  sym_method_opts o = ts_opts (5, 4);
  int st;
  void *s = T->alloc (&sys, &o, &st);
  double y[2], yn[2], yd[2], ye[2], h = -0.1, t = 2.0, w = 0.0;
  ts_pend_exact (1.0, 1.0, t, y);
  for (int step = 0; step < 20; step++)
    {
      st |= T->step (s, &sys, t, h, t + h, y, yn, NULL);
      T->accept (s);
      for (int i = 0; i <= 8; i++)
        {
          double ti = t + h * i / 8.0;
          T->dense (s, &sys, ti, yd);
          ts_pend_exact (1.0, 1.0, ti, ye);
          w = fmax (w, ts_maxdiff (2, yd, ye));
        }
      memcpy (y, yn, sizeof y);
      t += h;
    }
  ts_pend_exact (1.0, 1.0, t, ye);
  printf ("dense (5,4), pendulum backwards h = -0.1: max error %.2e (step "
          "points %.2e)\n", w, ts_maxdiff (2, y, ye));
  /* 7.6e-10 from the solution's polynomials alone */
  CHECK (st == 0 && w < 1e-10, "dense backwards: %.3g", w);
  T->free (s);
}

/* --------------------------------------------------- symmetric, predictor */
static void
test_symmetric_and_predictor (void)
{
  /* the method is symmetric: a step back from the end returns to the
     start */
  sym_system sys = ts_system (2, ts_ns2, ts_ns2_jac, NULL);
  sym_method_opts o = ts_opts (4, 3);
  int st;
  void *s = T->alloc (&sys, &o, &st);
  double y0[4] = { 0.3, -0.2, 0.4, 0.5 }, y1[4], y2[4];
  st = T->step (s, &sys, 0.0, 0.3, 0.3, y0, y1, NULL);
  T->accept (s);
  st |= T->step (s, &sys, 0.3, -0.3, 0.0, y1, y2, NULL);
  CHECK (st == 0 && ts_maxdiff (4, y0, y2) < 1e-14, "back and forth: %.3g",
         ts_maxdiff (4, y0, y2));
  T->free (s);

  /* The predictor: continuing steps take fewer iterations than steps
     after reset, with the same results (to the Newton tolerance). */
  double ya[4], yb[4], yn[4];
  memcpy (ya, y0, sizeof ya);
  memcpy (yb, y0, sizeof yb);
  sym_system s1 = ts_system (2, ts_ns2, ts_ns2_jac, NULL);
  sym_system s2 = ts_system (2, ts_ns2, ts_ns2_jac, NULL);
  void *a = T->alloc (&s1, &o, &st), *b = T->alloc (&s2, &o, &st);
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
          "Euler start); difference %.1e\n", s1.cnt.nnewton / 200.0,
          s1.cnt.nrhs / 200.0, s2.cnt.nnewton / 200.0, s2.cnt.nrhs / 200.0,
          dif);
  CHECK (! bad && dif < 1e-12, "predictor vs reset: %d %.3g", bad, dif);
  CHECK (s1.cnt.nnewton < s2.cnt.nnewton, "predictor iterations %ld vs %ld",
         s1.cnt.nnewton, s2.cnt.nnewton);
  /* energy stays near its start (bounded error of a symplectic method) */
  double H0 = ts_ns2_H (y0), dH = fabs (ts_ns2_H (ya) - H0);
  CHECK (dH < 1e-7, "energy error %.3g", dH);
  T->free (a);
  T->free (b);
}

/* ---------------------------------------------------------------- failures */
static int
one_step_with_failure (long fail_at, int mode, long jac_fail_at,
                       int jac_mode, int want_err, int prior_steps,
                       sym_system *out)
{
  ts_user u = { 0 };
  sym_system sys = ts_system (2, ts_kep, ts_kep_jac, &u);
  sym_method_opts o = ts_opts (4, 3);
  o.want_error = want_err;
  int st;
  void *s = T->alloc (&sys, &o, &st);
  double y[4], yn[4], ye[4];
  ts_kep_y0 (0.6, y);
  const double h = 0.05;
  st = ts_run_fixed (T, s, &sys, 0.0, h, prior_steps, y);
  /* the last step's dense output (its first use evaluates f at the
     step's ends: before the calls are counted) */
  double ydense[4], ydense2[4];
  if (prior_steps)
    T->dense (s, &sys, prior_steps * h - 0.5 * h, ydense);
  u.calls = u.jcalls = 0;
  u.mode = mode;
  u.jac_fail_at = jac_fail_at;
  u.jac_mode = jac_mode;
  if (fail_at < 0)
    {
      /* the last call of this step (with yerr: the companion's last) */
      sym_system cs = sys;
      ts_user cu = u;
      cs.user = &cu;
      double cy[4], cyn[4], cye[4];
      memcpy (cy, y, sizeof y);
      sym_method_opts co = o;
      void *c = T->alloc (&cs, &co, &st);
      ts_kep_y0 (0.6, cy);
      st = ts_run_fixed (T, c, &cs, 0.0, h, prior_steps, cy);
      cu.calls = 0;
      st |= T->step (c, &cs, prior_steps * h, h, prior_steps * h + h, cy, cyn,
                     want_err ? cye : NULL);
      fail_at = cu.calls;
      T->free (c);
    }
  u.fail_at = fail_at;
  if (! st)
    st = T->step (s, &sys, prior_steps * h, h, prior_steps * h + h, y, yn,
                  want_err ? ye : NULL);
  /* the step is not accepted: dense output still is the last step's */
  if (prior_steps)
    {
      T->dense (s, &sys, prior_steps * h - 0.5 * h, ydense2);
      CHECK (ts_maxdiff (4, ydense, ydense2) == 0.0, "dense changed");
    }
  /* and the stepper works on */
  u.fail_at = u.jac_fail_at = 0;
  int st2 = T->step (s, &sys, prior_steps * h, h, prior_steps * h + h, y, yn,
                     want_err ? ye : NULL);
  CHECK (st2 == 0, "after the failure: %d", st2);
  *out = sys;
  T->free (s);
  return st;
}

/* H = p^2/2 - q^3/3: q'' = q^2 */
static int
blowup (double t, const double *y, double *dy, void *user)
{
  (void) t;
  (void) user;
  dy[0] = y[1];
  dy[1] = y[0] * y[0];
  return 0;
}

static int
blowup_jac (double t, const double *y, double *df, void *user)
{
  (void) t;
  (void) user;
  df[0] = 0.0;
  df[1] = 2.0 * y[0];
  df[2] = 1.0;
  df[3] = 0.0;
  return 0;
}

static void
test_failures (void)
{
  sym_system sys;
  struct { long at; int mode; long jat; int jmode; int err, prior;
           int expect; } c[] = {
    /* rhs: the first call (Euler start), a Newton iteration, the polish,
       the companion; NaN, recoverable, fatal */
    { 1, 0, 0, 0, 0, 0, SYM_NONFINITE },
    { 1, 1, 0, 0, 0, 0, SYM_RECOVERABLE },
    { 1, 2, 0, 0, 0, 0, SYM_ECALLBACK },
    { 5, 0, 0, 0, 0, 0, SYM_NONFINITE },
    { 5, 1, 0, 0, 0, 0, SYM_RECOVERABLE },
    { 5, 2, 0, 0, 0, 0, SYM_ECALLBACK },
    { 2, 0, 0, 0, 0, 3, SYM_NONFINITE },
    { 2, 1, 0, 0, 0, 3, SYM_RECOVERABLE },
    { 2, 2, 0, 0, 0, 3, SYM_ECALLBACK },
    { -1, 0, 0, 0, 1, 3, SYM_NONFINITE },
    { -1, 1, 0, 0, 1, 3, SYM_RECOVERABLE },
    { -1, 2, 0, 0, 1, 3, SYM_ECALLBACK },
    { -1, 0, 0, 0, 0, 3, SYM_NONFINITE },
    /* jac: recoverable and fatal passed on */
    { 0, 0, 1, 1, 0, 0, SYM_RECOVERABLE },
    { 0, 0, 2, 2, 0, 0, SYM_ECALLBACK },
    { 0, 0, 1, 2, 1, 3, SYM_ECALLBACK },
  };
  for (size_t i = 0; i < sizeof c / sizeof c[0]; i++)
    {
      int st = one_step_with_failure (c[i].at, c[i].mode, c[i].jat,
                                      c[i].jmode, c[i].err, c[i].prior, &sys);
      CHECK (st == c[i].expect, "case %zu: status %d (%s), expected %d", i,
             st, sym_status_name (st), c[i].expect);
      CHECK ((st > 0) == (c[i].expect > 0), "case %zu: sign", i);
    }
  /* Newton failures, recoverable: an iteration limit of 1 in an
     adaptive step (a fixed step is then reached from shorter ones,
     spvi_lengthen, and succeeds) ... */
  sym_system ks = ts_system (2, ts_kep, ts_kep_jac, NULL);
  sym_method_opts o = ts_opts (4, 3);
  o.max_newton = 1;
  int st;
  void *s = T->alloc (&ks, &o, &st);
  double y[4], yn[4], ye[4];
  ts_kep_y0 (0.6, y);
  st = T->step (s, &ks, 0.0, 0.1, 0.1, y, yn, ye);
  CHECK (st == SYM_NEWTON_FAIL && ks.cnt.nnewton_fail > 0,
         "max_newton 1: %d", st);
  st = T->step (s, &ks, 0.0, 0.1, 0.1, y, yn, NULL);
  CHECK (st == 0, "max_newton 1, fixed step: %d", st);
  T->free (s);
  /* ... and a step past a blow-up (q'' = q^2 from q = p = 1 blows up near
     t = 1.4): no solution */
  sym_system bs = ts_system (1, blowup, blowup_jac, NULL);
  o = ts_opts (4, 3);
  s = T->alloc (&bs, &o, &st);
  double yb[2] = { 1.0, 1.0 }, ybn[2];
  st = T->step (s, &bs, 0.0, 4.0, 4.0, yb, ybn, NULL);
  CHECK (st > 0, "step past the blow-up: %d (%s), y = %g %g", st,
         sym_status_name (st), ybn[0], ybn[1]);
  st = T->step (s, &bs, 0.0, 0.01, 0.01, yb, ybn, NULL);
  CHECK (st == 0, "then a small one: %d", st);
  T->free (s);
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
  sym_system sys = ts_system (1, quartic, quartic_jac, NULL);
  sym_method_opts o = ts_opts (m + 1, m);
  int st;
  void *s = T->alloc (&sys, &o, &st);
  double y[2] = { 1.0, 0.5 };
  const int ns = (int) (40.0 / h);
  st = ts_run_fixed (T, s, &sys, 0.0, h, ns, y);
  double t = ns * h, w = 1.25;
  *err = fmax (fabs (y[0] - (cos (w * t) + 0.5 * sin (w * t))),
               fabs (y[1] - (-sin (w * t) + 0.5 * cos (w * t))));
  *its = (double) sys.cnt.nnewton / ns;
  printf ("rotation, Nodes = %d, h = %g, %d steps: error %.2e, %.2f "
          "corrections per step\n", m, h, ns, *err, *its);
  T->free (s);
  return st;
}

/* Many nodes at a long step: the continued prediction, whose noise the
   continuation amplifies like 5.8^Nodes, is cut to the modes above its
   noise (predict_modes).  Before, on this rotation (rate 1.25) from
   (1, 0.5) with h = 1, Nodes = 20 failed at t = 22 (8.05 corrections per
   step), Nodes = 25, 30, 40 at t = 2, and Nodes = 15 took 4.20
   corrections per step; measured now 3.27-3.58 for Nodes = 15..40, every
   run to t = 40 within 1e-13 of the exact solution.  Steps so long that
   Newton fails from the Euler start of the first step (off by O(h
   |f'|)) are reached from shorter steps (spvi_lengthen): before, the
   runs of the second table failed at t = 0; measured now: errors 3.7e-4,
   4.3e-12, 3.4e-10, 8.9e-16, 3.3e-14. */
static void
test_many_nodes (void)
{
  const int ms[] = { 15, 20, 25, 30, 40 };
  double err, its;
  for (size_t i = 0; i < sizeof ms / sizeof ms[0]; i++)
    {
      int st = rotation_run (ms[i], 1.0, &err, &its);
      CHECK (st == 0 && err < 1e-12 && its < 4.0, "Nodes = %d: status %d "
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
  T = sym_step_spvi;
  test_alloc ();
  test_alloc_failures ();
  test_orders ();
  test_known_methods ();
  test_symplectic ();
  test_jacobian_sources ();
  test_rhs_jac ();
  test_error_estimate ();
  test_adaptive_tolerances ();
  test_adaptive_kepler ();
  test_dense ();
  test_symmetric_and_predictor ();
  test_failures ();
  test_many_nodes ();
  return tu_finish ("test_spvi");
}
