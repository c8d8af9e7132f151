/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* test_spvi_adaptive.c -- the SPVI stepper's error estimate and the
   solves of adaptive steps (directly and through the driver), and its
   dense output. */
#include "sym.h"
#include "testutil.h"
#include "test_spvi_systems.h"

#define T sym_step_spvi

/* --------------------------------------------------------- error estimate */
/* One step from y0 = [1;1] of the pendulum with the estimate, its
   solves converged to round-off (no tolerances set: yerr alone asks for
   the companion); the exact local error is known from the elliptic
   solution.  (3,3) reaches its asymptotic slope late, so it starts at a
   smaller h. */
static void
scenario_error_estimate (void)
{
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
          sym_eval ev = ts_eval (1, ts_pend, ts_pend_jac, NULL);
          sym_method_opts o;
          sym_spvi_opts so;
          ts_opts (&o, &so, n, m);
          int st;
          void *s = T->alloc (ev.dim, &o, &st);
          T->order (s, &order);
          double y0[2] = { 1, 1 }, y1[2], ye[2], yx[2];
          st = T->step (s, &ev, 0.0, h, h, y0, y1, ye);
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
/* a new (4,3) stepper in *s (the old one freed), with the tolerances of
   an adaptive run (RelTol = AbsTol = tol) if tol > 0 */
static int
fresh_stepper (void **s, int d, double tol)
{
  sym_method_opts o;
  sym_spvi_opts so;
  ts_opts (&o, &so, 4, 3);
  int st;
  T->free (*s);
  *s = T->alloc (d, &o, &st);
  if (*s && tol > 0)
    st = ts_adaptive (T, *s, tol, tol);
  return st;
}

/* The same steps with the tolerances of an adaptive run set (the
   method's solve stopping at SYM_SPVI_EST_LO of the smallest error they
   allow, the companion's at SYM_SPVI_EST_HI) and without (yerr alone:
   both converged to round-off): the advanced values and the estimates
   agree to those fractions, for fewer calls.  States along a Kepler orbit
   (e = 0.6), h = 0.05, RelTol = AbsTol = 1e-6; each step from a new
   stepper (Euler start, new matrices), and each step after the one
   before (polynomial start, kept matrices). */
static void
scenario_adaptive_tolerances (void)
{
  const double rtol = 1e-6, atol = 1e-6, h = 0.05;
  sym_eval el = ts_eval (2, ts_kep, ts_kep_jac, NULL);
  sym_eval et = ts_eval (2, ts_kep, ts_kep_jac, NULL);
  void *sa = NULL, *sb = NULL;
  double y[4], ya[4], yb[4], ea[4], eb[4];
  double worst_y = 0.0, worst_e = 0.0;
  int bad = 0;
  for (int pass = 0; pass < 2; pass++)
    {
      ts_kep_y0 (0.6, y);
      double t = 0.0;
      for (int k = 0; k < 200 && ! bad; k++)
        {
          if ((pass == 0 || k == 0)
              && (fresh_stepper (&sa, 2, rtol) || fresh_stepper (&sb, 2, 0)))
            {
              bad = 1;
              CHECK (0, "pass %d step %d: no stepper", pass, k);
              break;
            }
          int s1 = T->step (sa, &el, t, h, t + h, y, ya, ea);
          int s2 = T->step (sb, &et, t, h, t + h, y, yb, eb);
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
  long ca = el.st.cnt.nrhs + el.st.cnt.njac;
  long cb = et.st.cnt.nrhs + et.st.cnt.njac;
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
scenario_adaptive_kepler (void)
{
  double err[5];
  long calls[5], failed[5], steps[5];
  for (int k = 0; k < 5; k++)
    {
      double tol = pow (10.0, -4 - 2 * k);
      sym_system sys = ts_system (2, ts_kep, ts_kep_jac, NULL);
      sym_method_opts mo;
      sym_spvi_opts so;
      ts_opts (&mo, &so, 4, 3);
      sym_driver_opts o;
      memset (&o, 0, sizeof o);
      double y0[4];
      ts_kep_y0 (0.6, y0);
      o.t0 = 0.0;
      o.tf = 10 * 2 * TS_PI;
      o.tol.rtol = tol;
      o.tol.atol = &tol;
      o.tol.atol_len = 1;
      o.refine = 1;
      o.output = kep_out;
      sym_stats stats;
      int st = sym_integrate (T, &sys, &mo, &o, y0, &stats);
      CHECK (st == SYM_DONE, "RelTol %g: status %d", tol, st);
      err[k] = ts_maxdiff (4, kep_end, y0);
      calls[k] = stats.cnt.nrhs + stats.cnt.njac;
      failed[k] = stats.cnt.nfailed;
      steps[k] = stats.cnt.nsteps;
    }
  printf ("adaptive Kepler (4,3), 10 periods, RelTol 1e-4..1e-12: end-point "
          "errors %.2e %.2e %.2e %.2e %.2e, rhs + jac calls %ld %ld %ld %ld "
          "%ld, failed/accepted steps %ld/%ld %ld/%ld %ld/%ld %ld/%ld "
          "%ld/%ld\n", err[0], err[1], err[2], err[3], err[4], calls[0],
          calls[1], calls[2], calls[3], calls[4], failed[0], steps[0],
          failed[1], steps[1], failed[2], steps[2], failed[3], steps[3],
          failed[4], steps[4]);
  /* The orbit's fall towards pericentre makes the error grow several-fold
     from step to step at a fixed h; the predictive control follows that
     trend, so that few steps fail */
  for (int k = 0; k < 5; k++)
    CHECK (failed[k] <= (k ? 0.1 : 0.2) * (steps[k] + failed[k]),
           "RelTol 1e-%d: %ld failed steps of %ld", 4 + 2 * k, failed[k],
           steps[k] + failed[k]);
  for (int k = 1; k < 5; k++)
    CHECK (err[k] * 30 <= err[k - 1], "RelTol 1e-%d: error %.3g, at 1e-%d "
           "%.3g", 4 + 2 * k, err[k], 2 + 2 * k, err[k - 1]);
  /* at RelTol 1e-12 the error is the round-off of the solves */
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
  sym_eval ev = ts_eval (1, ts_osc, ts_osc_jac, NULL);
  sym_method_opts o;
  sym_spvi_opts so;
  ts_opts (&o, &so, n, m);
  o.want_dense = 1;
  int st;
  void *s = T->alloc (ev.dim, &o, &st);
  double y[2] = { 1.0, 0.5 }, yn[2], yd[2], t = 0.3, worst = 0.0;
  *ends = 0.0;
  *calls = 0;
  for (int step = 0; step < 10; step++)
    {
      double ys[2] = { y[0], y[1] };
      st |= T->step (s, &ev, t, h, t + h, y, yn, NULL);
      T->accept (s);
      const long before = ev.st.cnt.nrhs;
      T->dense (s, &ev, t, yd);
      *ends = fmax (*ends, ts_maxdiff (2, yd, ys));
      T->dense (s, &ev, t + h, yd);
      *ends = fmax (*ends, ts_maxdiff (2, yd, yn));
      for (int i = 1; i < 10; i++)
        {
          double tau = h * i / 10.0;
          T->dense (s, &ev, t + tau, yd);
          double ex[2] = { ys[0] * cos (tau) + ys[1] * sin (tau),
                           -ys[0] * sin (tau) + ys[1] * cos (tau) };
          worst = fmax (worst, ts_maxdiff (2, yd, ex));
        }
      *calls += ev.st.cnt.nrhs - before;
      memcpy (y, yn, sizeof y);
      t += h;
    }
  CHECK (st == 0, "dense run (%d,%d): %d", n, m, st);
  T->free (s);
  return worst;
}

/* (4,3): y' interpolated at -1, the m nodes and +1, whose values there
   are off by O(h^(m+1)) (the stage order): local error O(h^(m+2)) =
   O(h^5), where the polynomials of the solution alone (q of degree
   n - 1 = 3) give O(h^4).  f at the step ends, each once (the end of one
   step is the start of the next): 11 calls for 10 steps. */
static void
scenario_dense_nodes (void)
{
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
}

/* the other pairs below order 8 ((3,3), order 4, here): the cubic
   Hermite interpolant through the step's ends, exact there, local error
   O(h^4), f at each end once */
static void
scenario_dense_hermite (void)
{
  double ends[2], worst[2];
  long calls[2];
  for (int k = 0; k < 2; k++)
    worst[k] = dense_osc (3, 3, 0.2 / (1 << k), &ends[k], &calls[k]);
  double sl = log2 (worst[0] / worst[1]);
  printf ("dense (3,3), oscillator: interior local error %.2e (h=0.2), "
          "%.2e (h=0.1), slope %.2f\n", worst[0], worst[1], sl);
  CHECK (ends[0] == 0.0 && ends[1] == 0.0 && calls[0] == 11
         && calls[1] == 11 && sl >= 3.7 && worst[0] < 1e-5,
         "dense (3,3): ends %g %g, calls %ld %ld, %.3g %.3g slope %.2f",
         ends[0], ends[1], calls[0], calls[1], worst[0], worst[1], sl);
}

/* pendulum, (5,4), backwards: dense between the step points agrees with
   the exact solution to the polynomials' accuracy */
static void
scenario_dense_backwards (void)
{
  sym_eval ev = ts_eval (1, ts_pend, ts_pend_jac, NULL);
  sym_method_opts o;
  sym_spvi_opts so;
  ts_opts (&o, &so, 5, 4);
  int st;
  void *s = T->alloc (ev.dim, &o, &st);
  double y[2], yn[2], yd[2], ye[2], h = -0.1, t = 2.0, w = 0.0;
  ts_pend_exact (1.0, 1.0, t, y);
  for (int step = 0; step < 20; step++)
    {
      st |= T->step (s, &ev, t, h, t + h, y, yn, NULL);
      T->accept (s);
      for (int i = 0; i <= 8; i++)
        {
          double ti = t + h * i / 8.0;
          T->dense (s, &ev, ti, yd);
          ts_pend_exact (1.0, 1.0, ti, ye);
          w = fmax (w, ts_maxdiff (2, yd, ye));
        }
      memcpy (y, yn, sizeof y);
      t += h;
    }
  ts_pend_exact (1.0, 1.0, t, ye);
  printf ("dense (5,4), pendulum backwards h = -0.1: max error %.2e (step "
          "points %.2e)\n", w, ts_maxdiff (2, y, ye));
  CHECK (st == 0 && w < 1e-10, "dense backwards: %.3g", w);
  T->free (s);
}

int
main (void)
{
  scenario_error_estimate ();
  scenario_adaptive_tolerances ();
  scenario_adaptive_kepler ();
  scenario_dense_nodes ();
  scenario_dense_hermite ();
  scenario_dense_backwards ();
  return tu_finish ("test_spvi_adaptive");
}
