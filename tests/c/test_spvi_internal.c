/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* test_spvi_internal.c -- the SPVI stepper's parts (methods/spvi/spvi.h):
   its analytic Newton matrix against central differences of its
   residual, the exactness of the predictor, the extrapolated and
   borrowed node Jacobians, the Gauss transform. */
#include "methods/spvi/spvi.h"
#include "testutil.h"
#include "test_spvi_systems.h"

#include <string.h>

#define T sym_step_spvi

/* Set up core c for the step (t, h, yk) as spvi_step (its kept
   evaluations counted from t; here t - c->t is exact) and spvi_solve do. */
static void
setup (spvi_core *c, sym_eval *ev, double t, double h, const double *yk)
{
  spvi_core_move (c, t - c->t);
  c->ev = ev;
  c->t = t;
  c->h = h;
  c->yk = yk;
  c->fvalid = 0;
  for (int j = 0; j < c->m; j++)
    c->tj[j] = t + 0.5 * h * (c->z[j] + 1.0);
}

static double
matrix_vs_fd (int n, int m, sym_eval *ev, const double *yk, double h,
              unsigned seed)
{
  spvi_core c;
  if (spvi_core_init (&c, ev->dim, n, m, SPVI_FULL))
    return INFINITY;
  setup (&c, ev, 0.1, h, yk);
  const int N = c.N, d = ev->dim;
  /* a point near a solution: small a_i, P near p_k, plus noise */
  srand (seed);
  for (int i = 0; i < N; i++)
    c.x[i] = 0.05 * h * ((double) rand () / RAND_MAX - 0.5);
  for (int j = 0; j < m; j++)
    for (int k = 0; k < d; k++)
      c.x[(n - 1) * d + j * d + k] += yk[d + k];
  double *M = malloc ((size_t) N * N * sizeof (double));
  double *rp = malloc ((size_t) N * sizeof (double));
  double *rm = malloc ((size_t) N * sizeof (double));
  double *x = malloc ((size_t) N * sizeof (double));
  double worst = INFINITY;
  if (M && rp && rm && x && ! spvi_matrix (&c, c.x, M))
    {
      double mmax = 0.0;
      for (int i = 0; i < N * N; i++)
        mmax = fmax (mmax, fabs (M[i]));
      worst = 0.0;
      for (int col = 0; col < N; col++)
        {
          double del = 1e-6 * fmax (1e-2, fabs (c.x[col]));
          memcpy (x, c.x, (size_t) N * sizeof (double));
          x[col] += del;
          spvi_residual (&c, x, rp);
          x[col] -= 2 * del;
          spvi_residual (&c, x, rm);
          for (int i = 0; i < N; i++)
            {
              double fd = (rp[i] - rm[i]) / (2 * del);
              worst = fmax (worst, fabs (fd - M[i + (size_t) col * N]));
            }
        }
      worst /= mmax;
    }
  free (x);
  free (rm);
  free (rp);
  free (M);
  spvi_core_free (&c);
  return worst;
}

static void
scenario_matrix (void)
{
  static const int pairs[][2] = { { 2, 1 }, { 3, 2 }, { 4, 3 }, { 3, 3 },
                                  { 4, 2 }, { 5, 4 }, { 6, 4 }, { 2, 3 },
                                  { 9, 8 } };
  const double y2[4] = { 0.3, -0.2, 0.4, 0.5 }, y1[2] = { 0.7, -0.4 };
  double worst = 0.0;
  for (size_t p = 0; p < sizeof pairs / sizeof pairs[0]; p++)
    {
      int n = pairs[p][0], m = pairs[p][1];
      sym_eval s2 = ts_eval (2, ts_ns2, ts_ns2_jac, NULL);
      sym_eval s1 = ts_eval (1, ts_ns1, ts_ns1_jac, NULL);
      double e[3];
      e[0] = matrix_vs_fd (n, m, &s2, y2, 0.3, 1u + p);
      e[1] = matrix_vs_fd (n, m, &s2, y2, -0.2, 7u + p);
      e[2] = matrix_vs_fd (n, m, &s1, y1, 0.5, 3u + p);
      for (int k = 0; k < 3; k++)
        {
          CHECK (e[k] <= 1e-8, "(%d,%d) case %d: matrix vs differences "
                 "%.3g", n, m, k, e[k]);
          worst = fmax (worst, e[k]);
        }
      /* with finite-difference node Jacobians: close, not exact */
      sym_eval sf = ts_eval (2, ts_ns2, NULL, NULL);
      double ef = matrix_vs_fd (n, m, &sf, y2, 0.3, 11u + p);
      CHECK (ef <= 1e-6, "(%d,%d) FD Jacobians: %.3g", n, m, ef);
    }
  printf ("Newton matrix vs central differences of the residual: max "
          "relative difference %.2e\n", worst);
}

/* The predictor on a trajectory the method reproduces exactly: q'' = t
   (H = p^2/2 - t q: q cubic, p quadratic).  With (4,3) the step is exact,
   so the extrapolated start of the next step is its solution. */
static int
cubic_rhs (double t, const double *y, double *dy, void *user)
{
  (void) user;
  dy[0] = y[1];
  dy[1] = t;
  return 0;
}

static int
cubic_jac (double t, const double *y, double *df, void *user)
{
  (void) t;
  (void) y;
  (void) user;
  df[0] = df[1] = df[3] = 0.0;
  df[2] = 1.0;
  return 0;
}

static void
scenario_predictor_exact (void)
{
  sym_eval ev = ts_eval (1, cubic_rhs, cubic_jac, NULL);
  sym_method_opts o;
  sym_spvi_opts so;
  ts_opts (&o, &so, 4, 3);
  int st;
  spvi_state *s = T->alloc (ev.dim, &o, &st);
  double y[2] = { 0.5, -1.0 }, yn[2];
  const double t0 = 0.3;
  double t = t0, worst_pred = 0.0, worst_exact = 0.0;
  /* steps of changing size, forwards: the re-expansion of the polynomials
     on a new step must be exact too */
  const double hs[] = { 0.2, 0.2, 0.35, 0.1, 0.25 };
  for (int k = 0; k < 5; k++)
    {
      st |= T->step (s, &ev, t, hs[k], t + hs[k], y, yn, NULL);
      if (k > 0)
        worst_pred = fmax (worst_pred, ts_maxdiff (s->lo.N, s->lo.nw.x0,
                                                   s->lo.x));
      T->accept (s);
      t += hs[k];
      memcpy (y, yn, sizeof y);
      /* exact: q = q0 + p0 (t-t0) + (t^3 - t0^3)/6 - t0^2 (t-t0)/2,
         p = p0 + (t^2 - t0^2)/2 */
      double dt = t - t0;
      double qx = 0.5 - dt + (t * t * t - t0 * t0 * t0) / 6.0
                  - 0.5 * t0 * t0 * dt;
      double px = -1.0 + 0.5 * (t * t - t0 * t0);
      worst_exact = fmax (worst_exact, fmax (fabs (y[0] - qx),
                                             fabs (y[1] - px)));
    }
  printf ("predictor on a cubic trajectory: start vs solution %.2e, "
          "solution vs exact %.2e\n", worst_pred, worst_exact);
  CHECK (st == 0, "status %d", st);
  /* round-off only, amplified by the extrapolation to old z up to
     1 + 2 h/h_old = 4.5 (l_3(4.5) = 220): 5e-15 at equal steps, 1e-13
     after h grows 1.75 times */
  CHECK (worst_pred <= 1e-12, "predictor not exact: %.3g", worst_pred);
  CHECK (worst_exact <= 1e-14, "not exact: %.3g", worst_exact);
  T->free (s);
}

/* The extrapolated node Jacobians: exact (to round-off) when Df is a
   polynomial in t of degree < m along the solution.  f = (p, -t q): Df =
   [0 1; -t 0], linear in t.  Also the sample selection with two earlier
   evaluations, and the limits (nothing to extrapolate from, too far). */
static int
tlin_rhs (double t, const double *y, double *dy, void *user)
{
  (void) user;
  dy[0] = y[1];
  dy[1] = -t * y[0];
  return 0;
}

static int
tlin_jac (double t, const double *y, double *df, void *user)
{
  (void) y;
  (void) user;
  df[0] = 0.0;
  df[1] = -t;
  df[2] = 1.0;
  df[3] = 0.0;
  return 0;
}

/* max error of c's node Jacobians (d = 1) against tlin_jac at its nodes */
static double
tlin_jac_error (const spvi_core *c)
{
  double worst = 0.0;
  for (int j = 0; j < c->m; j++)
    {
      double ex[4];
      tlin_jac (c->tj[j], NULL, ex, NULL);
      for (int e = 0; e < 4; e++)
        worst = fmax (worst, fabs (c->A[j * 4 + e] - ex[e]));
    }
  return worst;
}

static void
scenario_extrapolate (void)
{
  sym_eval ev = ts_eval (1, tlin_rhs, tlin_jac, NULL);
  const double yk[2] = { 0.4, -0.3 };
  double worst = 0.0;
  int ok = 1;
  for (int m = 1; m <= 4; m++)
    {
      spvi_core c;
      if (spvi_core_init (&c, 1, m + 1, m, SPVI_FULL))
        {
          ok = 0;
          continue;
        }
      double *M = malloc ((size_t) c.N * c.N * sizeof (double));
      const double h = 0.25;
      /* evaluations at the steps from 0.5 and 0.75 (at least two sample
         times even for m = 1), then steps 1..6 steps after the latest
         (the last one too far) */
      setup (&c, &ev, 0.5, h, yk);
      spvi_matrix (&c, c.x, M);
      setup (&c, &ev, 0.75, h, yk);
      spvi_matrix (&c, c.x, M);
      ok &= c.nae == 2;
      for (int k = 1; k <= 6; k++)
        {
          setup (&c, &ev, 0.75 + k * h, h, yk);
          c.nw.have_matrix = 1;
          int done = spvi_extrapolate (&c, &ev);
          ok &= done == (k <= SYM_SPVI_JX_STEPS);
          if (! done)
            continue;
          worst = fmax (worst, tlin_jac_error (&c));
        }
      /* none kept: nothing to extrapolate from */
      c.nae = 0;
      setup (&c, &ev, 1.0, h, yk);
      ok &= spvi_extrapolate (&c, &ev) == 0;
      free (M);
      spvi_core_free (&c);
    }
  printf ("extrapolated node Jacobians, Df linear in t: max error %.2e\n",
          worst);
  CHECK (ok, "extrapolation done where it should not be, or not done");
  /* round-off, amplified by at most SYM_SPVI_JX_LEBESGUE */
  CHECK (worst < 1e-11, "extrapolated Jacobians off by %.3g", worst);
}

/* The companion's node Jacobians interpolated from the method's of the
   same step (spvi_borrow): exact for Df linear in t (m >= 2 points), no
   callback, and refused for another step or another h. */
static void
scenario_borrow (void)
{
  sym_eval ev = ts_eval (1, tlin_rhs, tlin_jac, NULL);
  const double yk[2] = { 0.4, -0.3 };
  double worst = 0.0;
  int ok = 1;
  for (int m = 2; m <= 4; m++)
    {
      spvi_core lo, hi;
      if (spvi_core_init (&lo, 1, m + 1, m, SPVI_FULL)
          || spvi_core_init (&hi, 1, m + 2, m + 1, SPVI_FULL))
        {
          ok = 0;
          continue;
        }
      double *M = malloc ((size_t) lo.N * lo.N * sizeof (double));
      const double t = 0.5, h = 0.25;
      setup (&lo, &ev, t, h, yk);
      spvi_matrix (&lo, lo.x, M);
      long njac = ev.st.cnt.njac;
      setup (&hi, &ev, t, h, yk);
      ok &= spvi_borrow (&hi, &lo, &ev) == 1 && hi.nw.have_matrix
            && hi.nw.lu.factored && ev.st.cnt.njac == njac;
      worst = fmax (worst, tlin_jac_error (&hi));
      /* not from another step (both cores move on, as in spvi_step), nor
         at another h */
      sym_newton_invalidate (&hi.nw);
      setup (&lo, &ev, t + h, h, yk);
      setup (&hi, &ev, t + h, h, yk);
      ok &= spvi_borrow (&hi, &lo, &ev) == 0 && ! hi.nw.have_matrix;
      setup (&lo, &ev, t, h, yk);
      setup (&hi, &ev, t, 0.5 * h, yk);
      ok &= spvi_borrow (&hi, &lo, &ev) == 0 && ! hi.nw.have_matrix;
      free (M);
      spvi_core_free (&lo);
      spvi_core_free (&hi);
    }
  printf ("companion's node Jacobians from the method's, Df linear in t: "
          "max error %.2e\n", worst);
  CHECK (ok, "borrowed where it should not be, or not borrowed");
  CHECK (worst < 1e-13, "borrowed Jacobians off by %.3g", worst);
}

/* The Gauss transform inverts the Legendre-Vandermonde matrix. */
static void
scenario_vinv (void)
{
  double worst = 0.0;
  for (int n = 2; n <= 12; n++)
    {
      sym_method_opts o;
      sym_spvi_opts so;
      ts_opts (&o, &so, n, n);
      int st;
      spvi_state *s = T->alloc (1, &o, &st);
      double l[12], dl[12];
      for (int i = 0; i < n; i++)
        for (int k = 0; k < n; k++)
          {
            double v = 0.0;
            for (int j = 0; j < n; j++)
              {
                sym_legendre (n, s->xi[j], l, dl);
                v += s->vinv[i * n + j] * l[k];
              }
            worst = fmax (worst, fabs (v - (i == k)));
          }
      T->free (s);
    }
  CHECK (worst < 1e-13, "Vinv V - I: %.3g", worst);
}

int
main (void)
{
  scenario_matrix ();
  scenario_predictor_exact ();
  scenario_extrapolate ();
  scenario_borrow ();
  scenario_vinv ();
  return tu_finish ("test_spvi_internal");
}
