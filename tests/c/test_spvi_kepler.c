/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* test_spvi_kepler.c -- long-time behaviour of SPVI (4,3) at a fixed step
   on the Kepler problem, e = 0.6, h = 2 pi/100, 1000 periods (100000
   steps): bounded energy error, angular momentum conserved to round-off,
   the cost per step (Newton iterations, rhs and jac calls, also with the
   batch callback), and the convergence of every step: each result against
   a tightly converged solution of the same step. */
#include "sym.h"
#include "testutil.h"
#include "test_spvi_systems.h"

#include <float.h>
#include <time.h>

#define T sym_step_spvi

/* The batch callback with f changed in its last bit (+-1 ulp of f_p,
   pseudo-random), as the Vectorized form of an Octave function may
   round differently from its scalar form. */
static unsigned lastbit_seed;

static int
kep_batch_lastbit (int k, const double *t, const double *y, double *dy,
                   void *user)
{
  int st = ts_kep_batch (k, t, y, dy, user);
  for (int j = 0; j < k; j++)
    for (int i = 2; i < 4; i++)
      {
        lastbit_seed = lastbit_seed * 1103515245u + 12345u;
        int s = (int) ((lastbit_seed >> 16) % 3) - 1;
        dy[4 * j + i] *= 1.0 + s * DBL_EPSILON;
      }
  return st;
}

/* f and Df in one call (the Hessian as FCN's second output) */
static int
kep_both (double t, const double *y, double *dy, double *df, void *user)
{
  int st = ts_kep (t, y, dy, user);
  return st ? st : ts_kep_jac (t, y, df, user);
}

/* 1000 periods at h = 2 pi/100 from e = 0.6: energy bounded, angular
   momentum at round-off; the cost per step into cost[] (Newton
   iterations, rhs calls, jac calls) */
static void
long_run (sym_eval *ev, int newmat, const char *label, double *cost)
{
  const double e = 0.6, h = 2 * TS_PI / 100;
  const long per_period = 100, periods = 1000;
  const long nsteps = per_period * periods, window = 100 * per_period;
  sym_method_opts o;
  sym_spvi_opts so;
  ts_opts (&o, &so, 4, 3);
  so.newton_matrix = newmat;
  int st;
  void *s = T->alloc (ev->dim, &o, &st);
  CHECK (s != NULL, "alloc: %d", st);
  if (! s)
    return;
  double y[4], yn[4];
  ts_kep_y0 (e, y);
  const double H0 = ts_kep_H (y), L0 = ts_kep_L (y);
  double efirst = 0.0, elast = 0.0, lerr = 0.0, t = 0.0;
  clock_t c0 = clock ();
  for (long k = 0; k < nsteps; k++)
    {
      double tn = h * (double) (k + 1);
      st = T->step (s, ev, t, h, tn, y, yn, NULL);
      if (st)
        break;
      T->accept (s);
      memcpy (y, yn, sizeof y);
      t = tn;
      double de = fabs ((ts_kep_H (y) - H0) / H0);
      if (k < window)
        efirst = fmax (efirst, de);
      if (k >= nsteps - window)
        elast = fmax (elast, de);
      lerr = fmax (lerr, fabs ((ts_kep_L (y) - L0) / L0));
    }
  double secs = (double) (clock () - c0) / CLOCKS_PER_SEC;
  CHECK (st == 0, "%s: step failed: %d (%s) at t = %g", label, st,
         sym_status_name (st), t);
  const sym_counters *c = &ev->st.cnt;
  cost[0] = (double) c->nnewton / nsteps;
  cost[1] = (double) c->nrhs / nsteps;
  cost[2] = (double) c->njac / nsteps;
  printf ("Kepler e = 0.6, (4,3), h = 2pi/100, %ld periods, %s, %.2f s:\n"
          "  relative energy error: max %.3e over the first 100 periods, "
          "%.3e over the last 100 (ratio %.3f)\n"
          "  relative angular momentum error: %.2e\n"
          "  per step: %.3f Newton iterations, %.3f rhs calls, %.4f jac "
          "calls, %.4f LU\n", periods, label, secs, efirst, elast,
          elast / efirst, lerr, cost[0], cost[1], cost[2],
          (double) c->nlu / nsteps);
  CHECK (elast <= 1.5 * efirst, "%s: energy error grows: %.3g -> %.3g",
         label, efirst, elast);
  CHECK (efirst < 1e-6, "%s: energy error %.3g", label, efirst);
  CHECK (lerr <= 1e-12, "%s: angular momentum error %.3g", label, lerr);
  CHECK (c->nnewton_fail == 0, "%s: %ld Newton failures", label,
         c->nnewton_fail);
  T->free (s);
}

/* The stepper (n, m) with the Newton matrix newmat for d dimensions */
static void *
new_stepper (int d, int n, int m, int newmat)
{
  sym_method_opts o;
  sym_spvi_opts so;
  ts_opts (&o, &so, n, m);
  so.newton_matrix = newmat;
  int st;
  return T->alloc (d, &o, &st);
}

/* One step of the pair (n, m) from (t, y) by h from a new stepper (Euler
   start, new matrix) with Newton's tolerance 1e-18: a tightly converged
   step */
static int
tight_step (int n, int m, sym_eval *ev, double t, double h, const double *y,
            double *yr)
{
  sym_method_opts o;
  sym_spvi_opts so;
  ts_opts (&o, &so, n, m);
  o.newton_tol = 1e-18;
  o.max_newton = 30;
  int st;
  void *rs = T->alloc (ev->dim, &o, &st);
  if (! rs)
    return st;
  st = T->step (rs, ev, t, h, t + h, y, yr, NULL);
  T->free (rs);
  return st;
}

/* Over 10 periods every step against the same step converged tightly;
   the largest relative difference */
static double
converged (sym_eval *sc, int newmat, sym_eval *sr)
{
  const double h = 2 * TS_PI / 100;
  void *cs = new_stepper (2, 4, 3, newmat);
  double yc[4], ycn[4], yr[4];
  ts_kep_y0 (0.6, yc);
  double worst = 0.0, rms = 0.0;
  const long nc = 1000;
  int stc = 0;
  for (long k = 0; k < nc && ! stc; k++)
    {
      double t0 = h * (double) k, t1 = h * (double) (k + 1);
      stc = T->step (cs, sc, t0, h, t1, yc, ycn, NULL);
      stc |= tight_step (4, 3, sr, t0, h, yc, yr);
      T->accept (cs);
      double dif = 0.0, ymax = 0.0;
      for (int i = 0; i < 4; i++)
        {
          dif = fmax (dif, fabs (ycn[i] - yr[i]));
          ymax = fmax (ymax, fabs (yr[i]));
        }
      worst = fmax (worst, dif / ymax);
      rms += (dif / ymax) * (dif / ymax);
      memcpy (yc, ycn, sizeof yc);
    }
  printf ("  each step vs the same step converged tightly, 10 periods: max "
          "relative difference %.2e (rms %.1e)\n", worst, sqrt (rms / nc));
  T->free (cs);
  return stc ? INFINITY : worst;
}

static int
pend_both (double t, const double *y, double *dy, double *df, void *user)
{
  int st = ts_pend (t, y, dy, user);
  return st ? st : ts_pend_jac (t, y, df, user);
}

/* The mean change of energy per step against the same step converged
   tightly: the pendulum from (2.5, 0.3) with (9,8), h = 0.3 (its
   truncation error is below round-off), 20000 steps.  A one-correction
   stop leaves a quadratic, signed error: with too small a safety factor
   (SYM_NEWTON_QUAD_SAFE) it drifts. */
static double
energy_bias (sym_eval *sc, int newmat, double *itps)
{
  const double h = 0.3;
  const long ns = 20000;
  sym_eval sr = ts_eval (1, ts_pend, ts_pend_jac, NULL);
  void *cs = new_stepper (1, 9, 8, newmat);
  int st = 0;
  double y[2] = { 2.5, 0.3 }, yn[2], yr[2], sum = 0.0;
  for (long k = 0; k < ns && ! st; k++)
    {
      st = T->step (cs, sc, h * k, h, h * k + h, y, yn, NULL);
      st |= tight_step (9, 8, &sr, h * k, h, y, yr);
      T->accept (cs);
      sum += sin (yr[0]) * (yn[0] - yr[0]) + yr[1] * (yn[1] - yr[1]);
      memcpy (y, yn, sizeof y);
    }
  *itps = (double) sc->st.cnt.nnewton / ns;
  T->free (cs);
  return st ? INFINITY : sum / ns;
}

/* The kept matrix (a separate jac callback): the cost per step stays
   within its bounds */
static void
scenario_kept_matrix (void)
{
  double cost[3];
  sym_eval ev = ts_eval (2, ts_kep, ts_kep_jac, NULL);
  long_run (&ev, SYM_MATRIX_AUTO, "jac callback", cost);
  CHECK (cost[0] < 2.5 && cost[1] < 7.5 && cost[1] + cost[2] < 8.0,
         "cost per step: %.3f it, %.3f rhs + %.3f jac", cost[0], cost[1],
         cost[2]);
}

/* A new matrix on every step (SYM_MATRIX_NEW) from the calls that give f
   and Df at the nodes, its first correction exact Newton */
static void
scenario_new_matrix (void)
{
  double cost[3];
  sym_eval ev = ts_eval (2, ts_kep, ts_kep_jac, NULL);
  ev.rhs_jac = kep_both;
  long_run (&ev, SYM_MATRIX_NEW, "new matrix, f and Df in one call", cost);
  CHECK (cost[0] < 1.65 && cost[2] == 3.0 && cost[1] < 1.9,
         "cost per step: %.3f it, %.3f rhs + %.3f jac", cost[0], cost[1],
         cost[2]);
}

/* The batch callback: one call per residual, the same numbers bit for
   bit (100 periods) */
static void
scenario_batch (void)
{
  const double e = 0.6, h = 2 * TS_PI / 100;
  sym_eval sb = ts_eval (2, ts_kep, ts_kep_jac, NULL);
  sym_eval sa = ts_eval (2, ts_kep, ts_kep_jac, NULL);
  sb.rhs_batch = ts_kep_batch;
  void *b = new_stepper (2, 4, 3, SYM_MATRIX_AUTO);
  void *a = new_stepper (2, 4, 3, SYM_MATRIX_AUTO);
  double ya[4], yb[4];
  ts_kep_y0 (e, ya);
  ts_kep_y0 (e, yb);
  const long nb = 100 * 100;
  int sta = ts_run_fixed (T, a, &sa, 0.0, h, nb, ya);
  int stb = ts_run_fixed (T, b, &sb, 0.0, h, nb, yb);
  double brhs = (double) sb.st.cnt.nrhs / nb;
  double bjac = (double) sb.st.cnt.njac / nb;
  printf ("  batch callback, 100 periods: %.3f rhs calls (%.3f states) + "
          "%.4f jac calls per step\n", brhs,
          (double) sb.st.cnt.nrhs_states / nb, bjac);
  CHECK (sta == 0 && stb == 0 && ts_maxdiff (4, ya, yb) == 0.0
         && sb.st.cnt.nrhs_states == sa.st.cnt.nrhs_states,
         "batch: status %d %d, difference %.3g", sta, stb,
         ts_maxdiff (4, ya, yb));
  CHECK (brhs < 2.5 && brhs + bjac < 3.2, "batch cost per step: %.3f rhs + "
         "%.3f jac", brhs, bjac);
  T->free (a);
  T->free (b);
}

/* The work does not depend on the last bits of f (the decisions of the
   iteration are not taken at the round-off level): 20 periods with
   analytic Jacobians (the kept matrix) and with finite differences (a
   new matrix every step, its one-correction stops and measurements of
   kq), the batch callback as is against 5 runs with f perturbed: the
   same number of states evaluated. */
static void
scenario_last_bits (void)
{
  const double e = 0.6, h = 2 * TS_PI / 100;
  int same = 1;
  for (int fd = 0; fd < 2; fd++)
    {
      long ref = -1;
      for (int r = 0; r <= 5; r++)
        {
          sym_eval sp = ts_eval (2, ts_kep, fd ? NULL : ts_kep_jac, NULL);
          sp.rhs_batch = ts_kep_batch;
          if (r > 0)
            {
              sp.rhs_batch = kep_batch_lastbit;
              lastbit_seed = 17u * r + 1u;
            }
          void *p = new_stepper (2, 4, 3, SYM_MATRIX_AUTO);
          double yp[4];
          ts_kep_y0 (e, yp);
          int st = ts_run_fixed (T, p, &sp, 0.0, h, 20 * 100, yp);
          T->free (p);
          if (r == 0)
            ref = sp.st.cnt.nrhs_states;
          else if (st || sp.st.cnt.nrhs_states != ref)
            {
              same = 0;
              fprintf (stderr, "last bits of f (%s Jacobian, run %d): %ld "
                       "states against %ld\n", fd ? "FD" : "analytic", r,
                       sp.st.cnt.nrhs_states, ref);
            }
        }
    }
  CHECK (same, "the number of states evaluated follows the last bits of f");
}

/* Converged to round-off, every step, with the kept matrix and with a new
   matrix every step (asked for, with the combined calls, and by default,
   with Vectorized finite differences) */
static void
scenario_converged (void)
{
  sym_eval sc = ts_eval (2, ts_kep, ts_kep_jac, NULL);
  sym_eval sr = ts_eval (2, ts_kep, ts_kep_jac, NULL);
  double worst = converged (&sc, SYM_MATRIX_AUTO, &sr);
  CHECK (worst <= 1e-15, "kept matrix: not converged: %.3g", worst);
  sc = ts_eval (2, ts_kep, ts_kep_jac, NULL);
  sc.rhs_jac = kep_both;
  worst = converged (&sc, SYM_MATRIX_NEW, &sr);
  CHECK (worst <= 1e-15, "new matrix, combined calls: not converged: %.3g",
         worst);
  sc = ts_eval (2, ts_kep, NULL, NULL);
  sc.rhs_batch = ts_kep_batch;
  worst = converged (&sc, SYM_MATRIX_AUTO, &sr);
  CHECK (worst <= 1e-15, "new matrix, Vectorized FD: not converged: %.3g",
         worst);
}

static void
scenario_energy_bias (void)
{
  double it1, it2;
  sym_eval sp = ts_eval (1, ts_pend, ts_pend_jac, NULL);
  double b1 = energy_bias (&sp, SYM_MATRIX_AUTO, &it1);
  sp = ts_eval (1, ts_pend, ts_pend_jac, NULL);
  sp.rhs_jac = pend_both;
  double b2 = energy_bias (&sp, SYM_MATRIX_NEW, &it2);
  printf ("pendulum (9,8), h = 0.3: mean energy change per step against "
          "tight solves %.2e (kept matrix, %.3f corrections per step), "
          "%.2e (new matrix, %.3f)\n", b1, it1, b2, it2);
  CHECK (fabs (b1) <= 5e-18 && fabs (b2) <= 5e-18 && it2 < 1.8,
         "energy bias per step: %.3g kept, %.3g new (%.3f corrections)", b1,
         b2, it2);
}

int
main (void)
{
  scenario_kept_matrix ();
  scenario_new_matrix ();
  scenario_batch ();
  scenario_last_bits ();
  scenario_converged ();
  scenario_energy_bias ();
  return tu_finish ("test_spvi_kepler");
}
