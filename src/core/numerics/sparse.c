/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* sparse.c -- square sparse matrices in compressed columns (sym_csc):
   their storage, copies, products with a vector and square blocks.

   The number of entries is colptr[n]; nnz is kept equal to it in what
   these functions write.  rowind and val have room for cap entries. */
#include "numerics.h"

#include <string.h>

/* the entries of a (0 without colptr) */
static int
csc_count (const sym_csc *a)
{
  return a->colptr ? a->colptr[a->n] : 0;
}

int
sym_csc_init (sym_csc *a, int n, int cap)
{
  memset (a, 0, sizeof (*a));
  if (n < 0 || cap < 0)
    return SYM_EBADINPUT;
  a->colptr = sym_calloc ((size_t) n + 1, sizeof (int));
  if (! a->colptr)
    return SYM_ENOMEM;
  a->n = n;
  int st = sym_csc_reserve (a, cap);
  if (st != SYM_SUCCESS)
    sym_csc_free (a);
  return st;
}

int
sym_csc_reserve (sym_csc *a, int cap)
{
  if (cap < 0)
    return SYM_EBADINPUT;
  if (cap <= a->cap)
    return SYM_SUCCESS;
  int *ri = sym_malloc ((size_t) cap * sizeof (int));
  double *v = sym_malloc ((size_t) cap * sizeof (double));
  if (! ri || ! v)
    {
      sym_free (ri);
      sym_free (v);
      return SYM_ENOMEM;
    }
  /* all the old room, not only colptr[n]: a callback may fill rowind
     and val before colptr */
  if (a->cap > 0)
    {
      memcpy (ri, a->rowind, (size_t) a->cap * sizeof (int));
      memcpy (v, a->val, (size_t) a->cap * sizeof (double));
    }
  sym_free (a->rowind);
  sym_free (a->val);
  a->rowind = ri;
  a->val = v;
  a->cap = cap;
  return SYM_SUCCESS;
}

void
sym_csc_free (sym_csc *a)
{
  sym_free (a->colptr);
  sym_free (a->rowind);
  sym_free (a->val);
  memset (a, 0, sizeof (*a));
}

int
sym_csc_same_pattern (const sym_csc *a, const sym_csc *b)
{
  if (a->n != b->n || ! a->colptr || ! b->colptr)
    return 0;
  if (memcmp (a->colptr, b->colptr, ((size_t) a->n + 1) * sizeof (int)))
    return 0;
  int nz = csc_count (a);
  return nz == 0
         || ! memcmp (a->rowind, b->rowind, (size_t) nz * sizeof (int));
}

/* a made n-by-n with room for cap entries; its entries are dropped when
   n changes (colptr is then new, all zero) */
static int
csc_shape (sym_csc *a, int n, int cap)
{
  int st = sym_csc_reserve (a, cap);
  if (st != SYM_SUCCESS || (a->colptr && a->n == n))
    return st;
  int *cp = sym_calloc ((size_t) n + 1, sizeof (int));
  if (! cp)
    return SYM_ENOMEM;
  sym_free (a->colptr);
  a->colptr = cp;
  a->n = n;
  a->nnz = 0;
  return SYM_SUCCESS;
}

int
sym_csc_copy (sym_csc *dst, const sym_csc *src)
{
  if (dst == src)
    return SYM_SUCCESS;
  if (! src->colptr || src->n < 0)
    return SYM_EBADINPUT;
  int nz = csc_count (src);
  int st = csc_shape (dst, src->n, nz);
  if (st != SYM_SUCCESS)
    return st;
  memcpy (dst->colptr, src->colptr, ((size_t) src->n + 1) * sizeof (int));
  if (nz > 0)
    {
      memcpy (dst->rowind, src->rowind, (size_t) nz * sizeof (int));
      memcpy (dst->val, src->val, (size_t) nz * sizeof (double));
    }
  dst->nnz = nz;
  return SYM_SUCCESS;
}

void
sym_csc_mv (const sym_csc *a, const double *x, double *y)
{
  for (int i = 0; i < a->n; i++)
    y[i] = 0.0;
  for (int j = 0; j < a->n; j++)
    for (int k = a->colptr[j]; k < a->colptr[j + 1]; k++)
      y[a->rowind[k]] += a->val[k] * x[j];
}

/* the entries of column j of a in rows r0 .. r0+nb-1: *k0 .. *k1 - 1
   (the rows increase, so they are one run) */
static void
csc_col_range (const sym_csc *a, int j, int r0, int nb, int *k0, int *k1)
{
  int k = a->colptr[j], end = a->colptr[j + 1];
  while (k < end && a->rowind[k] < r0)
    k++;
  *k0 = k;
  while (k < end && a->rowind[k] < r0 + nb)
    k++;
  *k1 = k;
}

int
sym_csc_block (const sym_csc *a, int r0, int c0, int nb, sym_csc *dst)
{
  if (dst == a || ! a->colptr || nb < 0 || r0 < 0 || c0 < 0
      || r0 > a->n - nb || c0 > a->n - nb)
    return SYM_EBADINPUT;
  int nz = 0, k0, k1;
  for (int j = 0; j < nb; j++)
    {
      csc_col_range (a, c0 + j, r0, nb, &k0, &k1);
      nz += k1 - k0;
    }
  int st = csc_shape (dst, nb, nz);
  if (st != SYM_SUCCESS)
    return st;
  nz = 0;
  for (int j = 0; j < nb; j++)
    {
      dst->colptr[j] = nz;
      csc_col_range (a, c0 + j, r0, nb, &k0, &k1);
      for (int k = k0; k < k1; k++, nz++)
        {
          dst->rowind[nz] = a->rowind[k] - r0;
          dst->val[nz] = a->val[k];
        }
    }
  dst->colptr[nb] = nz;
  dst->nnz = nz;
  return SYM_SUCCESS;
}
