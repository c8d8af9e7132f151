/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* newton.c -- Newton's iteration shared by the implicit steppers.

   Simplified mode, as in implicit Runge-Kutta codes: one LU serves many
   iterations and, while convergence stays fast, many steps.  With dx_k
   the k-th correction and theta = |dx_k| / |dx_{k-1}| the contraction
   rate, the distance to the solution after dx_k is about theta/(1-theta)
   |dx_k|; the iteration stops when that is below tol.  Before theta is
   known, the eta = theta/(1-theta) of the last solve stands in for it.

   With quad set the matrix is new at the start of every solve, so that
   the first correction is an exact Newton step: the error it leaves is
   quadratic, about kq |dx_1|^2, far below theta |dx_1|.  kq is a
   property of the problem near its solution, measured as |dx_2| /
   |dx_1|^2 whenever a second correction is made with that matrix, and it
   serves the next solves.  That error has a sign, so the safety factor
   SYM_NEWTON_QUAD_SAFE keeps it from adding up over many steps.

   Full mode: a new matrix at every iterate, for problems on which a
   stale matrix makes the simplified iteration diverge. */
#include "numerics.h"

#include <float.h>
#include <math.h>
#include <string.h>

/* what a sweep of the simplified iteration returns when it is too slow
   (not a status: a callback's recoverable failure is one) */
#define SWEEP_SLOW 1000

int
sym_newton_init (sym_newton *nw, int n, const sym_method_opts *opts)
{
  memset (nw, 0, sizeof (*nw));
  nw->n = n;
  nw->tol = opts && opts->newton_tol > 0 ? opts->newton_tol : SYM_NEWTON_TOL;
  nw->maxit = opts && opts->max_newton > 0 ? opts->max_newton
              : SYM_NEWTON_MAXIT;
  nw->eta = 1.0;
  nw->r = sym_malloc ((size_t) 3 * n * sizeof (double));
  if (! nw->r)
    {
      sym_newton_free (nw);
      return SYM_ENOMEM;
    }
  nw->dx = nw->r + n;
  nw->x0 = nw->r + 2 * n;
  return SYM_SUCCESS;
}

void
sym_newton_free (sym_newton *nw)
{
  sym_lu_free (&nw->lu);
  sym_free (nw->r);
  nw->r = nw->dx = nw->x0 = NULL;
}

int
sym_newton_lu (sym_newton *nw)
{
  return nw->lu.a ? SYM_SUCCESS : sym_lu_init (&nw->lu, nw->n);
}

void
sym_newton_invalidate (sym_newton *nw)
{
  nw->have_matrix = 0;
  nw->lu.factored = 0;
}

static double
scaled_norm (int n, const double *v, const double *scale)
{
  /* the largest, or NaN if any is: without a branch on each */
  double m = 0.0;
  int nan = 0;
  for (int i = 0; i < n; i++)
    {
      const double a = fabs (v[i]) / scale[i];
      nan |= a != a;
      m = a > m ? a : m;
    }
  return nan ? NAN : m;
}

int
sym_newton_dx (sym_newton *nw, const sym_newton_problem *p, const double *x,
               const double *scale, sym_counters *c, double *dxn)
{
  int st;
  if (p->correction)
    st = p->correction (p->ctx, x, nw->dx);
  else
    {
      if ((st = p->residual (p->ctx, x, nw->r)))
        return st;
      for (int i = 0; i < nw->n; i++)
        nw->dx[i] = -nw->r[i];
      st = p->solve ? p->solve (p->ctx, nw->dx, c)
                    : sym_lu_solve (&nw->lu, nw->dx, c);
    }
  if (! st && scale && dxn)
    *dxn = scaled_norm (nw->n, nw->dx, scale);
  return st;
}

void
sym_newton_apply (sym_newton *nw, double *x, sym_counters *c)
{
  for (int i = 0; i < nw->n; i++)
    x[i] += nw->dx[i];
  if (c)
    c->nnewton++;
}

/* G'(x) evaluated and factored: by the problem's factor, or its matrix
   and the dense LU */
static int
factor (sym_newton *nw, const sym_newton_problem *p, const double *x,
        sym_counters *c)
{
  if (p->factor)
    return p->factor (p->ctx, x, c);
  int st = sym_newton_lu (nw);
  if (! st && (st = p->matrix (p->ctx, x, nw->lu.a)))
    /* the callback may have written part of the matrix: drop it */
    sym_newton_invalidate (nw);
  return st ? st : sym_lu_factor (&nw->lu, c);
}

static int
new_matrix (sym_newton *nw, const sym_newton_problem *p, const double *x,
            sym_counters *c)
{
  int st = factor (nw, p, x, c);
  if (st && st != SYM_SINGULAR)
    {
      sym_newton_invalidate (nw);
      return st;
    }
  nw->have_matrix = (st == SYM_SUCCESS);
  nw->fresh = nw->have_matrix;
  return st;
}

/* The status of a solve whose matrix failed: the callback's own (fatal,
   a smaller step asked for, NaN or Inf), SYM_NEWTON_FAIL for a singular
   matrix. */
static int
matrix_failure (int st)
{
  return st == SYM_SINGULAR ? SYM_NEWTON_FAIL : st;
}

/* Exact first corrections (see the top), after correction k (0 or 1) of
   size dxn (dxold: the one before): 1 if the solve may stop after it */
static int
quad_stop (sym_newton *nw, int k, double dxn, double dxold)
{
  const double floor_tol = SYM_NEWTON_FLOOR * DBL_EPSILON;
  if (k == 0 && nw->kq_ok && nw->kq_age < SYM_NEWTON_QUAD_AGE
      && SYM_NEWTON_QUAD_SAFE * nw->kq * dxn * dxn <= nw->tol)
    {
      nw->kq_age++;
      nw->one = 1;
      nw->theta = 0.0;
      return 1;
    }
  if (k == 1)
    {
      if (dxn > SYM_NEWTON_QUAD_INFO * floor_tol)
        {
          nw->kq = dxn / (dxold * dxold);
          nw->kq_ok = 1;
          nw->kq_new = 1;
        }
      nw->kq_age = 0;
    }
  return 0;
}

/* The rate of the last solve, floored: a tiny carried rate would accept
   a first correction far above round-off */
static double
carried_eta (const sym_newton *nw)
{
  return fmax (pow (fmax (nw->eta, DBL_EPSILON), SYM_NEWTON_ETA_POW),
               SYM_NEWTON_ETA_MIN);
}

/* Whether at rate theta (< 1) the nleft iterations left cannot bring the
   error after dxn below tol: theta^nleft / (1 - theta) dxn > tol.  For
   nleft >= 2 theta^nleft <= theta^2, so a bound below tol / 2 (room for
   the rounding) answers without pow, as it would */
static int
too_slow (double theta, int nleft, double dxn, double tol)
{
  if (nleft >= 2 && theta * theta / (1.0 - theta) * dxn <= 0.5 * tol)
    return 0;
  return pow (theta, nleft) / (1.0 - theta) * dxn > tol;
}

/* One sweep of the simplified iteration with the matrix in nw->lu, from
   the rate estimate *eta (negative: carried_eta, made when the first
   correction's test needs it): SYM_SUCCESS, a callback's status, or
   SWEEP_SLOW (*diverged: diverging) */
static int
simplified_sweep (sym_newton *nw, const sym_newton_problem *p, double *x,
                  const double *scale, sym_counters *c, int refreshes,
                  double *eta, int *diverged)
{
  const double floor_tol = SYM_NEWTON_FLOOR * DBL_EPSILON;
  double dxold = 0.0, theta = 0.0, dxn = 0.0;
  *diverged = 0;
  for (int k = 0; k < nw->maxit; k++)
    {
      int st = sym_newton_dx (nw, p, x, scale, c, &dxn);
      if (st)
        return st;
      if (! isfinite (dxn))
        {
          *diverged = 1;
          return SWEEP_SLOW;
        }
      sym_newton_apply (nw, x, c);
      nw->iters++;
      if (nw->quad && refreshes == 0 && nw->fresh && k <= 1
          && quad_stop (nw, k, dxn, dxold))
        return SYM_SUCCESS;
      if (k > 0)
        {
          theta = dxn / fmax (dxold, DBL_MIN);
          if (theta >= SYM_NEWTON_DIVERGE)
            {
              if (dxn <= floor_tol)   /* stagnating at round-off */
                {
                  nw->theta = theta;
                  nw->eta = 1.0;
                  return SYM_SUCCESS;
                }
              *diverged = 1;
              return SWEEP_SLOW;
            }
          *eta = theta / (1.0 - theta);
        }
      /* carried_eta >= SYM_NEWTON_ETA_MIN: above that bound the test
         fails whatever its value, which no later test reads */
      if (*eta < 0.0
          && (dxn <= floor_tol || SYM_NEWTON_ETA_MIN * dxn <= nw->tol))
        *eta = carried_eta (nw);
      if ((*eta >= 0.0 && *eta * dxn <= nw->tol) || dxn <= floor_tol)
        {
          nw->theta = theta;
          nw->eta = *eta;
          return SYM_SUCCESS;
        }
      /* predicted failure: at this rate the iterations left cannot reach
         tol */
      if (k > 0 && too_slow (theta, nw->maxit - 1 - k, dxn, nw->tol))
        return SWEEP_SLOW;
      dxold = dxn;
    }
  return SWEEP_SLOW;
}

static int
solve_simplified (sym_newton *nw, const sym_newton_problem *p, double *x,
                  const double *scale, sym_counters *c)
{
  int st, refreshes = 0, diverged;
  double eta = -1.0;   /* carried_eta, when needed */
  nw->fresh = 0;
  nw->one = 0;
  nw->kq_new = 0;
  memcpy (nw->x0, x, (size_t) nw->n * sizeof (double));
  if (! nw->have_matrix && (st = new_matrix (nw, p, x, c)))
    return matrix_failure (st);
  for (;;)
    {
      st = simplified_sweep (nw, p, x, scale, c, refreshes, &eta, &diverged);
      if (st != SWEEP_SLOW)
        return st;
      /* Slow or diverging: a stale matrix is refreshed (at the start when
         diverging) and the solve goes on; a divergence with a fresh
         matrix, or too many refreshes, fails (the caller shrinks h) */
      if ((diverged && nw->fresh) || refreshes >= 2)
        {
          if (c)
            c->nnewton_fail++;
          nw->eta = 1.0;
          return SYM_NEWTON_FAIL;
        }
      refreshes++;
      if (diverged)
        memcpy (x, nw->x0, (size_t) nw->n * sizeof (double));
      if ((st = new_matrix (nw, p, x, c)))
        return matrix_failure (st);
      eta = 1.0;
    }
}

static int
solve_full (sym_newton *nw, const sym_newton_problem *p, double *x,
            const double *scale, sym_counters *c)
{
  const double floor_tol = SYM_NEWTON_FLOOR * DBL_EPSILON;
  double dxold = 0.0, eta = 1.0, theta = 0.0, dxn = 0.0;
  int st;
  for (int k = 0; k < nw->maxit; k++)
    {
      nw->have_matrix = 0;
      if ((st = factor (nw, p, x, c)))
        return st == SYM_SINGULAR ? SYM_NEWTON_FAIL : st;
      nw->have_matrix = 1;
      if ((st = sym_newton_dx (nw, p, x, scale, c, &dxn)))
        return st;
      sym_newton_apply (nw, x, c);
      nw->iters++;
      if (! isfinite (dxn))
        break;
      if (k > 0)
        {
          theta = dxn / fmax (dxold, DBL_MIN);
          if (theta >= SYM_NEWTON_FULL_STALL
              && dxn <= fmax (nw->tol, SYM_NEWTON_FULL_FLOOR * floor_tol))
            {
              nw->theta = theta;         /* round-off level */
              nw->eta = 1.0;
              return SYM_SUCCESS;
            }
          if (theta >= 1.0)
            break;
          eta = theta / (1.0 - theta);
        }
      if ((k > 0 && eta * dxn <= nw->tol) || dxn <= floor_tol)
        {
          nw->theta = theta;
          nw->eta = eta;
          return SYM_SUCCESS;
        }
      dxold = dxn;
    }
  if (c)
    c->nnewton_fail++;
  nw->have_matrix = 0;
  return SYM_NEWTON_FAIL;
}

int
sym_newton_solve (sym_newton *nw, const sym_newton_problem *p, double *x,
                  const double *scale, sym_counters *c)
{
  nw->iters = 0;
  return nw->mode == SYM_NEWTON_FULL ? solve_full (nw, p, x, scale, c)
                                     : solve_simplified (nw, p, x, scale, c);
}
