/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* test_newton_stop.c -- the implicit solves of odeSE and odeSV stop only
   when their unknown is within the Newton tolerance of the root:
   sym_kept_solve (methods/implicit.c) on a linear problem whose root is
   known and whose kept matrix is stale, and the steps of non-separable
   problems against the same steps solved to round-off by a fixed point
   (se_sv_systems.h), with the Newton corrections they cost. */
#include "se_sv_systems.h"
#include "methods/onestep.h"

/* ------------------------------------------------------- a linear root */
/* G(x) = a (x - r): the root r; the matrix callback gives the slope a at
   the time it is called, which a later change of a makes stale */
typedef struct {
  sym_kept *k;
  double a, r, h;
  long nres;
  /* noisy > 0: the root moves by noisy / 20 and noisy at odd and even
     calls (an f whose noise is above the tolerance) */
  double noisy;
} lin_prob;

static int
lin_res (void *ctx, const double *x, double *g)
{
  lin_prob *L = ctx;
  L->nres++;
  if (L->noisy > 0)
    L->r += L->nres % 2 ? L->noisy / 20 : L->noisy;
  g[0] = L->a * (x[0] - L->r);
  return SYM_SUCCESS;
}

static int
lin_mat (void *ctx, const double *x, double *m)
{
  lin_prob *L = ctx;
  (void) x;
  m[0] = L->a;
  sym_kept_built (L->k, L->h);
  return SYM_SUCCESS;
}

/* One solve of the problem (a, r) from x0 after a first solve with an
   exact matrix (a = 1, root 0.5) has left a tiny carried rate: a kept
   matrix of slope 1 against a slope a, rate 1 - a.  Returns the error
   |x - r| in units of tol, with the status and the corrections. */
static double
lin_case (double a, double first_dx, int *st, long *nnewton, long *nres)
{
  const double tol = 1e-8, r = 0.75;
  tprob P;
  sym_eval ev = tp_eval (&P, P_H1, 1);    /* a user's Df: cost 1 */
  sym_method_opts o = tp_opts (0, 0);
  o.newton_tol = tol;
  sym_kept k;
  memset (&k, 0, sizeof k);
  *st = sym_kept_init (&k, 1, &o, 0);
  if (*st)
    return INFINITY;
  sym_kept_adaptive (&k);                 /* the tolerance itself */
  lin_prob L = { &k, 1.0, 0.5, 0.1, 0, 0.0 };
  sym_newton_problem prob = { lin_res, lin_mat, &L, NULL, NULL, NULL };
  /* ref 1: the scale is 1 near the roots */
  const double ref = 1.0;
  double x = 0.0, scale;
  *st = sym_kept_solve (&k, &prob, &ev, L.h, 1, &ref, &x, &scale);
  CHECK (*st == 0 && fabs (x - 0.5) <= 4 * DBL_EPSILON,
         "exact matrix: status %d, x - r = %.3g", *st, x - 0.5);
  /* the start whose first correction (slope 1) is first_dx tol: newton.c
     may take it by the carried rate; the error it leaves is (1 - a) / a
     of it */
  L.a = a;
  L.r = r;
  x = r - first_dx * tol / a;
  long n0 = ev.st.cnt.nnewton;
  L.nres = 0;
  *st = sym_kept_solve (&k, &prob, &ev, L.h, 1, &ref, &x, &scale);
  *nnewton = ev.st.cnt.nnewton - n0;
  *nres = L.nres;
  sym_kept_free (&k);
  return fabs (x - r) / tol;
}

/* A first correction newton.c takes (1e3 tol times the carried rate is
   at most tol) that leaves 3 tol (a = 1/2 with slope 1: rate 1/2) or 6
   tol behind (a = 1/4: the residual a |x - r| is 4 times smaller than
   the error): the check of the result goes on to tol.  A first
   correction of 1e4 tol is not taken at all. */
static void
scenario_linear (void)
{
  struct { double a, dx; } cases[] = {
    { 0.5, 3.0 }, { 0.25, 2.0 }, { 0.5, 0.5 }, { 0.25, 1e4 }, { 0.9, 5.0 }
  };
  for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++)
    {
      int st;
      long nn, nres;
      double e = lin_case (cases[c].a, cases[c].dx, &st, &nn, &nres);
      printf ("linear a %g, first correction %g tol: error %.3g tol, "
              "%ld corrections, %ld residuals\n", cases[c].a, cases[c].dx,
              e, nn, nres);
      CHECK (st == 0 && e <= 1.0, "a %g dx %g: status %d, error %.3g tol",
             cases[c].a, cases[c].dx, st, e);
      /* at rate 1 - a from an error e0 = dx / a tol, no more corrections
         than reach tol plus the check's own, and the one that tells the
         rate */
      double e0 = cases[c].dx / cases[c].a;
      long need = e0 <= 1.0 ? 0
                  : (long) ceil (log (e0) / -log (1.0 - cases[c].a));
      CHECK (nn <= need + 3, "a %g dx %g: %ld corrections for %ld",
             cases[c].a, cases[c].dx, nn, need);
    }
}

/* A residual whose root moves by 10 tol between a correction of 0.5 tol
   that newton.c takes and the check of it, solve after solve: no result
   within tol, a failure (SYM_NEWTON_FAIL, counted), not a result. */
static void
scenario_noisy (void)
{
  const double tol = 1e-8;
  tprob P;
  sym_eval ev = tp_eval (&P, P_H1, 1);
  sym_method_opts o = tp_opts (0, 0);
  o.newton_tol = tol;
  sym_kept k;
  memset (&k, 0, sizeof k);
  int st = sym_kept_init (&k, 1, &o, 0);
  CHECK (st == 0, "init: %d", st);
  sym_kept_adaptive (&k);
  lin_prob L = { &k, 1.0, 0.75, 0.1, 0, 10 * tol };
  sym_newton_problem prob = { lin_res, lin_mat, &L, NULL, NULL, NULL };
  const double ref = 1.0;
  double x = L.r, scale;
  st = sym_kept_solve (&k, &prob, &ev, L.h, 1, &ref, &x, &scale);
  printf ("noisy residual: status %d after %ld residuals, %ld failed\n", st,
          L.nres, ev.st.cnt.nnewton_fail);
  CHECK (st == SYM_NEWTON_FAIL && ev.st.cnt.nnewton_fail == 1
         && L.nres == 2 * SYM_KEPT_ROUNDS,
         "status %d, %ld residuals, %ld failures", st, L.nres,
         ev.st.cnt.nnewton_fail);
  sym_kept_free (&k);
}

/* ------------------------------------------------- steps of SE and SV */
/* The unknowns of a step from y (P of SE, P and Q of SV) against the
   same step by naive_se / naive_sv, relative to the scale of Newton's
   test: max(|x(t_k)|, |x - x(t_k)|) per unknown, times tol.  SV's Q is
   solved with the P found, whose error it carries (h/2 (f_q,p + f_q,p)
   times it): measured against the naive drift from that P. */
static double
step_ratio (const tprob *P, int sv, double t, double h, const double *y,
            const double *y1, double tol)
{
  const int d = tp_dim (P->kind);
  double yr[8], w[8], f[8];
  if (! sv)
    {
      naive_se (P, t, h, y, yr);
      double s = maxabs (d, y + d);
      for (int i = 0; i < d; i++)
        s = fmax (s, fabs (yr[d + i] - y[d + i]));
      return maxdiff (d, y1 + d, yr + d) / (tol * s);
    }
  /* P = p_{k+1/2} from p_{k+1} = P + (h/2) f_p(t + h, q_{k+1}, P): the
     stepper's P is not an output; the naive one's is, and the stepper's
     q_{k+1} comes from its own P: compare P through the naive kick, then
     Q through the naive drift from the stepper's P (recovered by a
     fixed point on p_{k+1} = P + (h/2) f_p(q_{k+1}, P)) */
  naive_sv (P, t, h, y, yr);
  memcpy (w, y1, (size_t) 2 * d * sizeof (double));
  for (int it = 0; it < FP_MAXIT; it++)
    {
      tp_f (P, t + h, w, f);
      double ch = 0;
      for (int i = 0; i < d; i++)
        {
          double v = y1[d + i] - 0.5 * h * f[d + i];
          ch = fmax (ch, fabs (v - w[d + i]));
          w[d + i] = v;
        }
      if (ch == 0)
        break;
    }
  double Ph[4], Pr[4], sp = maxabs (d, y + d), sq = maxabs (d, y);
  memcpy (Ph, w + d, (size_t) d * sizeof (double));
  /* the naive kick's P */
  memcpy (w, yr, (size_t) 2 * d * sizeof (double));
  for (int it = 0; it < FP_MAXIT; it++)
    {
      tp_f (P, t + h, w, f);
      double ch = 0;
      for (int i = 0; i < d; i++)
        {
          double v = yr[d + i] - 0.5 * h * f[d + i];
          ch = fmax (ch, fabs (v - w[d + i]));
          w[d + i] = v;
        }
      if (ch == 0)
        break;
    }
  memcpy (Pr, w + d, (size_t) d * sizeof (double));
  for (int i = 0; i < d; i++)
    sp = fmax (sp, fabs (Pr[i] - y[d + i]));
  double rp = maxdiff (d, Ph, Pr) / (tol * sp);
  /* the naive drift from the stepper's P */
  double fa[4], Q[4];
  memcpy (w, y, (size_t) d * sizeof (double));
  memcpy (w + d, Ph, (size_t) d * sizeof (double));
  tp_f (P, t, w, f);
  memcpy (fa, f, (size_t) d * sizeof (double));
  for (int it = 0; it < FP_MAXIT; it++)
    {
      tp_f (P, t + h, w, f);
      double ch = 0;
      for (int i = 0; i < d; i++)
        {
          Q[i] = y[i] + 0.5 * h * (fa[i] + f[i]);
          ch = fmax (ch, fabs (Q[i] - w[i]));
          w[i] = Q[i];
        }
      if (ch == 0)
        break;
    }
  for (int i = 0; i < d; i++)
    sq = fmax (sq, fabs (Q[i] - y[i]));
  return fmax (rp, maxdiff (d, y1, Q) / (tol * sq));
}

/* N steps of h, each against its naive version from the same start:
   the worst ratio (step_ratio) and the corrections per step */
static double
run_ratio (int kind, int jac, int sv, int adaptive, double ntol, double h,
           long N, double *per_step)
{
  tprob P;
  sym_eval ev = tp_eval (&P, kind, jac);
  sym_method_opts o = tp_opts (0, 0);
  o.newton_tol = ntol;
  const sym_stepper_type *T = stepper (sv);
  const int n = 2 * ev.dim;
  int st;
  void *S = tp_alloc (T, ev.dim, &o, adaptive, &st);
  CHECK (S != NULL, "alloc: %d", st);
  if (! S)
    return INFINITY;
  double yc[8], yn[8], ye[8], worst = 0.0, t = 0.0;
  const double y0[4] = { 0.8, -0.3, 0.6, 0.9 };
  if (kind == P_H1)
    {
      yc[0] = 0.8;
      yc[1] = 0.6;
    }
  else
    memcpy (yc, y0, sizeof y0);
  /* adaptive steps solve to the tolerance itself, fixed ones to
     SYM_FIXED_TOL_KEPT of it; not below round-off */
  const double tol = fmax (ntol * (adaptive ? 1.0 : SYM_FIXED_TOL_KEPT),
                           16 * DBL_EPSILON);
  long k;
  for (k = 0; k < N; k++)
    {
      double tnew = h * (double) (k + 1);
      st = T->step (S, &ev, t, tnew - t, tnew, yc, yn, adaptive ? ye : NULL);
      if (st)
        break;
      T->accept (S);
      worst = fmax (worst, step_ratio (&P, sv, t, tnew - t, yc, yn, tol));
      t = tnew;
      memcpy (yc, yn, (size_t) n * sizeof (double));
    }
  CHECK (st == 0, "%s kind %d: status %d at step %ld", mname (sv), kind, st,
         k);
  *per_step = (double) ev.st.cnt.nnewton / (double) N;
  T->free (S);
  return worst;
}

static void
scenario_steps (void)
{
  const int kinds[2] = { P_H1, P_H2 };
  const double tols[3] = { 1e-10, 1e-8, 1e-6 };
  const double hs[2] = { 0.1, 0.3 };
  double worst = 0.0, most = 0.0;
  for (int adaptive = 0; adaptive < 2; adaptive++)
    for (int ki = 0; ki < 2; ki++)
      for (int jac = 0; jac < 2; jac++)
        for (int sv = 0; sv < 2; sv++)
          for (int ti = 0; ti < 3; ti++)
            for (int hi = 0; hi < 2; hi++)
              {
                double per;
                double r = run_ratio (kinds[ki], jac, sv, adaptive, tols[ti],
                                      hs[hi], 500, &per);
                worst = fmax (worst, r);
                most = fmax (most, per / (sv ? 2 : 1));
                CHECK (r <= 1.5, "%s kind %d jac %d adaptive %d NewtonTol "
                       "%g h %g: error %.3g tol", mname (sv), kinds[ki], jac,
                       adaptive, tols[ti], hs[hi], r);
              }
  printf ("steps: worst error %.3g tol, at most %.3g corrections a solve\n",
          worst, most);
  CHECK (most <= 8.0, "%.3g corrections a solve", most);
}

int
main (void)
{
  scenario_linear ();
  scenario_noisy ();
  scenario_steps ();
  return tu_finish ("test_newton_stop");
}
