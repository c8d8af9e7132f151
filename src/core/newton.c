/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* newton.c -- dense LU (LAPACK dgetrf/dgetrs) and the simplified Newton
   iteration shared by the implicit steppers.

   The iteration is that of implicit Runge-Kutta codes: one LU serves many
   iterations and, while convergence stays fast, many steps.  With dx_k the k-th correction and
   theta_k = |dx_k| / |dx_{k-1}| the contraction rate, the distance to the
   solution after dx_k is about theta/(1-theta) |dx_k|; we stop when that is
   below tol.  Before theta is known, the eta = theta/(1-theta) of the last
   solve stands in for it.

   With quad set the matrix is new at the start of every solve, so that
   the first correction is an exact Newton step: the error it leaves is
   quadratic, about kq |dx_1|^2 (kq = omega/2 in the terms of the
   affine-covariant Newton theory), far below theta |dx_1|.  kq is a
   property of the problem near its solution: it is measured as |dx_2| /
   |dx_1|^2 whenever a second correction is made with that matrix and
   |dx_2| is well above round-off (NEWTON_QUAD_INFO times the round-off
   floor: at 10 times it, |dx_2| still carried 5% of noise from the last
   bits of G, and the decisions it fed with them), and it serves
   the next solves.  Measured with SPVI on Kepler e = 0.6, (4,3), h =
   2 pi/100 (tests/c/test_spvi_kepler.c): the error after the first
   correction divided by |dx_1|^2 stays within 1e-3..1e-1 wherever it is
   above round-off, and every step stays within 2.9e-16 of a tightly
   converged solve, as with the kept matrix.  The error left is
   quadratic, so it has a sign: summed over many steps it drifts.  With
   the safety factor NEWTON_QUAD_SAFE = 10, the pendulum with (9,8), h =
   0.3, gained 1.1e-17 of energy per step on average against tightly
   converged steps (its energy error grew from 1.3e-13 to 1.2e-11 over
   1e5..1e6 steps); with 100 the mean is 1.6e-18, the same as the kept
   matrix's 1.3e-18 (noise 2e-19), and the energy error stays at
   1e-13 over 1e6 steps; 100 costs 0.06 (Kepler) to 0.15 (pendulum (9,8))
   more corrections per step than 10.  A new measurement after every 4
   or 1000 solves instead of 16 changed little (Kepler, safety 10). */
#include "sym.h"

#include <float.h>
#include <math.h>
#include <string.h>

#define NEWTON_QUAD_SAFE 100.0
#define NEWTON_QUAD_AGE 16
#define NEWTON_QUAD_INFO 100.0

extern void dgetrf_ (const int *m, const int *n, double *a, const int *lda,
                     int *ipiv, int *info);
extern void dgetrs_ (const char *trans, const int *n, const int *nrhs,
                     const double *a, const int *lda, const int *ipiv,
                     double *b, const int *ldb, int *info);

int
sym_lu_init (sym_lu *lu, int n)
{
  lu->n = n;
  lu->factored = 0;
  lu->a = sym_malloc ((size_t) n * n * sizeof (double));
  lu->ipiv = sym_malloc ((size_t) n * sizeof (int));
  if (! lu->a || ! lu->ipiv)
    {
      sym_lu_free (lu);
      return SYM_ENOMEM;
    }
  return SYM_SUCCESS;
}

void
sym_lu_free (sym_lu *lu)
{
  sym_free (lu->ipiv);
  sym_free (lu->a);
  lu->ipiv = NULL;
  lu->a = NULL;
  lu->factored = 0;
}

int
sym_lu_factor (sym_lu *lu, sym_counters *c)
{
  int info = 0;
  if (c)
    c->nlu++;
  /* An Inf or NaN here comes from finite Jacobians (those are checked
     when they come back), h Df overflowing: no factors, as for a
     singular matrix (a Newton failure; SYM_NONFINITE would stand for a
     callback's NaN at a time it did not set). */
  for (size_t i = 0; i < (size_t) lu->n * lu->n; i++)
    if (! isfinite (lu->a[i]))
      {
        lu->factored = 0;
        return SYM_SINGULAR;
      }
  dgetrf_ (&lu->n, &lu->n, lu->a, &lu->n, lu->ipiv, &info);
  lu->factored = (info == 0);
  return info == 0 ? SYM_SUCCESS : SYM_SINGULAR;
}

int
sym_lu_solve (sym_lu *lu, double *b, sym_counters *c)
{
  int info = 0, one = 1;
  if (! lu->factored)
    return SYM_EBADINPUT;
  if (c)
    c->nsolve++;
  dgetrs_ ("N", &lu->n, &one, lu->a, &lu->n, lu->ipiv, b, &lu->n, &info);
  return info == 0 ? SYM_SUCCESS : SYM_EBADINPUT;
}

int
sym_newton_init (sym_newton *nw, int n)
{
  memset (nw, 0, sizeof (*nw));
  nw->n = n;
  nw->tol = 1e-14;
  nw->maxit = 10;
  nw->eta = 1.0;
  nw->r = sym_malloc ((size_t) 3 * n * sizeof (double));
  if (! nw->r || sym_lu_init (&nw->lu, n))
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

void
sym_newton_invalidate (sym_newton *nw)
{
  nw->have_matrix = 0;
  nw->lu.factored = 0;
}

static double
scaled_norm (int n, const double *v, const double *scale)
{
  double m = 0.0;
  for (int i = 0; i < n; i++)
    {
      double a = fabs (v[i]) / scale[i];
      if (a > m || isnan (a))
        m = a;
    }
  return m;
}

static int
new_matrix (sym_newton *nw, const sym_newton_problem *p, const double *x,
            sym_counters *c)
{
  int st = p->matrix (p->ctx, x, nw->lu.a);
  if (st)
    {
      /* the callback may have written part of the matrix: drop it */
      sym_newton_invalidate (nw);
      return st;
    }
  st = sym_lu_factor (&nw->lu, c);
  nw->have_matrix = (st == SYM_SUCCESS);
  nw->fresh = nw->have_matrix;
  return st;
}

/* The status of a solve whose matrix failed: the callback's own (fatal,
   a smaller step asked for, NaN or Inf: the run's message then names the
   function and t), SYM_NEWTON_FAIL for a singular matrix. */
static int
matrix_failure (int st)
{
  return st == SYM_SINGULAR ? SYM_NEWTON_FAIL : st;
}

int
sym_newton_solve (sym_newton *nw, const sym_newton_problem *p, double *x,
                  const double *scale, sym_counters *c)
{
  const int n = nw->n;
  /* Below this the corrections are round-off: accept. */
  const double floor_tol = 16.0 * DBL_EPSILON;
  int st;
  int refreshes = 0;
  /* The rate of the last solve stands in for theta before this solve has
     its own; a tiny carried rate would accept a first correction far above
     round-off, so it is floored (then one iteration suffices only when
     the first correction is already below 1e3 * tol). */
  double eta = fmax (pow (fmax (nw->eta, DBL_EPSILON), 0.8), 1e-3);

  nw->iters = 0;
  nw->fresh = 0;
  nw->one = 0;
  nw->kq_new = 0;
  memcpy (nw->x0, x, (size_t) n * sizeof (double));
  if (! nw->have_matrix)
    {
      st = new_matrix (nw, p, x, c);
      if (st)
        return matrix_failure (st);
    }

  for (;;)
    {
      double dxold = 0.0, theta = 0.0;
      int diverged = 0;
      for (int k = 0; k < nw->maxit; k++)
        {
          st = p->residual (p->ctx, x, nw->r);
          if (st)
            return st;
          for (int i = 0; i < n; i++)
            nw->dx[i] = -nw->r[i];
          st = sym_lu_solve (&nw->lu, nw->dx, c);
          if (st)
            return st;
          double dxn = scaled_norm (n, nw->dx, scale);
          if (! isfinite (dxn))
            {
              diverged = 1;
              break;
            }
          for (int i = 0; i < n; i++)
            x[i] += nw->dx[i];
          if (c)
            c->nnewton++;
          nw->iters++;
          if (nw->quad && refreshes == 0 && nw->fresh && k <= 1)
            {
              /* exact first corrections (see the top) */
              if (k == 0 && nw->kq_ok && nw->kq_age < NEWTON_QUAD_AGE
                  && NEWTON_QUAD_SAFE * nw->kq * dxn * dxn <= nw->tol)
                {
                  nw->kq_age++;
                  nw->one = 1;
                  nw->theta = 0.0;
                  return SYM_SUCCESS;
                }
              if (k == 1)
                {
                  if (dxn > NEWTON_QUAD_INFO * floor_tol)
                    {
                      nw->kq = dxn / (dxold * dxold);
                      nw->kq_ok = 1;
                      nw->kq_new = 1;
                    }
                  nw->kq_age = 0;
                }
            }
          if (k > 0)
            {
              theta = dxn / fmax (dxold, DBL_MIN);
              if (theta >= 0.99)
                {
                  if (dxn <= floor_tol)   /* stagnating at round-off */
                    {
                      nw->theta = theta;
                      nw->eta = 1.0;
                      return SYM_SUCCESS;
                    }
                  diverged = 1;
                  break;
                }
              eta = theta / (1.0 - theta);
            }
          if (eta * dxn <= nw->tol || dxn <= floor_tol)
            {
              nw->theta = theta;
              nw->eta = eta;
              return SYM_SUCCESS;
            }
          /* predicted failure: at this rate the iterations left cannot
             reach tol */
          if (k > 0
              && pow (theta, nw->maxit - 1 - k) / (1.0 - theta) * dxn
                 > nw->tol)
            break;
          dxold = dxn;
        }
      /* Slow or diverging.  A stale matrix is refreshed at the start and
         the solve restarts; a slow but converging iteration gets a fresh
         matrix at the current iterate and goes on; a divergence with a
         fresh matrix, or too many refreshes, fails (the caller shrinks h). */
      if ((diverged && nw->fresh) || refreshes >= 2)
        {
          if (c)
            c->nnewton_fail++;
          nw->eta = 1.0;
          return SYM_NEWTON_FAIL;
        }
      refreshes++;
      if (diverged)
        memcpy (x, nw->x0, (size_t) n * sizeof (double));
      st = new_matrix (nw, p, x, c);
      if (st)
        return matrix_failure (st);
      eta = 1.0;
    }
}
