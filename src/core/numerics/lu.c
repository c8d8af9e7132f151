/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* lu.c -- dense LU by LAPACK (dgetrf/dgetrs), factored once and solved
   many times. */
#include "numerics.h"

#include <math.h>

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
  info = sym_getrs (0, lu->n, lu->a, lu->ipiv, b);
  return info == 0 ? SYM_SUCCESS : SYM_EBADINPUT;
}
