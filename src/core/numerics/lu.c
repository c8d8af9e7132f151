/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* lu.c -- dense LU, factored once and solved many times: by LAPACK
   (dgetrf/dgetrs), or for n <= SYM_LU_SMALL by the loops below, where a
   BLAS spends more on its calls than on the arithmetic.  The small
   path's results are the same whatever BLAS Octave links. */
#include "numerics.h"
#include "tuning.h"

#include <float.h>
#include <math.h>

/* Partial pivoting as LAPACK's unblocked dgetf2, column by column: the
   first row of largest |a(i,k)| pivots column k.  ipiv is 1-based as
   LAPACK's.  Returns 0, or k + 1 for the first exactly zero pivot (the
   rest is not factored). */
int
sym_lu_small_factor (int n, double *a, int *ipiv)
{
  for (int k = 0; k < n; k++)
    {
      double *ck = a + (size_t) k * n;
      int p = k;
      double amax = fabs (ck[k]);
      for (int i = k + 1; i < n; i++)
        if (fabs (ck[i]) > amax)
          {
            amax = fabs (ck[i]);
            p = i;
          }
      ipiv[k] = p + 1;
      if (ck[p] == 0.0)
        return k + 1;
      if (p != k)
        for (int j = 0; j < n; j++)
          {
            double *cj = a + (size_t) j * n;
            const double t = cj[k];
            cj[k] = cj[p];
            cj[p] = t;
          }
      /* the multipliers by the pivot's reciprocal, unless that would
         overflow (a subnormal pivot): then by division, as dgetf2 */
      if (fabs (ck[k]) >= DBL_MIN)
        {
          const double r = 1.0 / ck[k];
          for (int i = k + 1; i < n; i++)
            ck[i] *= r;
        }
      else
        for (int i = k + 1; i < n; i++)
          ck[i] /= ck[k];
      for (int j = k + 1; j < n; j++)
        {
          double *cj = a + (size_t) j * n;
          const double akj = cj[k];
          if (akj != 0.0)
            for (int i = k + 1; i < n; i++)
              cj[i] -= ck[i] * akj;
        }
    }
  return 0;
}

/* b <- A \ b from sym_lu_small_factor's factors: the row swaps, L y = b
   (unit diagonal), U x = y, each column of the factors taken at once */
void
sym_lu_small_solve (int n, const double *a, const int *ipiv, double *b)
{
  for (int k = 0; k < n; k++)
    {
      const int p = ipiv[k] - 1;
      if (p != k)
        {
          const double t = b[k];
          b[k] = b[p];
          b[p] = t;
        }
    }
  for (int k = 0; k < n; k++)
    {
      const double *ck = a + (size_t) k * n;
      const double bk = b[k];
      if (bk != 0.0)
        for (int i = k + 1; i < n; i++)
          b[i] -= ck[i] * bk;
    }
  for (int k = n - 1; k >= 0; k--)
    {
      const double *ck = a + (size_t) k * n;
      const double bk = b[k] /= ck[k];
      if (bk != 0.0)
        for (int i = 0; i < k; i++)
          b[i] -= ck[i] * bk;
    }
}

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
  /* An Inf or NaN here comes from h Df overflowing (the Jacobians are
     checked when they come back): no factors, as for a singular matrix */
  for (size_t i = 0; i < (size_t) lu->n * lu->n; i++)
    if (! isfinite (lu->a[i]))
      {
        lu->factored = 0;
        return SYM_SINGULAR;
      }
  if (lu->n <= SYM_LU_SMALL)
    info = sym_lu_small_factor (lu->n, lu->a, lu->ipiv);
  else
    info = sym_getrf (0, lu->n, lu->a, lu->ipiv);
  lu->factored = (info == 0);
  return info == 0 ? SYM_SUCCESS : SYM_SINGULAR;
}

int
sym_lu_solve (sym_lu *lu, double *b, sym_counters *c)
{
  int info = 0;
  if (! lu->factored)
    return SYM_EBADINPUT;
  if (c)
    c->nsolve++;
  if (lu->n <= SYM_LU_SMALL)
    sym_lu_small_solve (lu->n, lu->a, lu->ipiv, b);
  else
    info = sym_getrs (0, lu->n, lu->a, lu->ipiv, b);
  return info == 0 ? SYM_SUCCESS : SYM_EBADINPUT;
}
