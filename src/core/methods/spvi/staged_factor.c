/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* staged_factor.c -- the matrices of odeSPVI's stage systems (staged.c
   describes the method): J = Df at the middle node (or, exact, every
   node's Jacobian), the separable case's Schur complements, the whole
   sparse system of the pairs n - 1 != m, and their LUs; and what is
   read back from J (its p rows times a vector, its noise sums). */
#include "staged.h"

#include <complex.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static int
cmp_int (const void *a, const void *b)
{
  const int x = *(const int *) a, y = *(const int *) b;
  return (x > y) - (x < y);
}

/* v times the column l of J's block (rows r0.., cols c0..), d rows, into
   the column work at rows base.. (their rows listed) */
static void
add_block_col (spvi_stages *g, int d, int r0, int c0, int l, double v,
               int base, int *nr)
{
  const sym_csc *J = &g->Js;
  for (int e = J->colptr[c0 + l]; e < J->colptr[c0 + l + 1]; e++)
    {
      const int i = J->rowind[e] - r0;
      if (i < 0 || i >= d || v == 0.0)
        continue;
      if (g->wcol[base + i] == 0.0)
        g->rows[(*nr)++] = base + i;
      g->wcol[base + i] += v * J->val[e];
      if (g->wcol[base + i] == 0.0)
        g->wcol[base + i] = DBL_MIN;   /* keeps its place in the list */
    }
}

/* the same for v at row base + l (an identity block's entry) */
static void
add_diag (spvi_stages *g, int row, double v, int *nr)
{
  if (v == 0.0)
    return;
  if (g->wcol[row] == 0.0)
    g->rows[(*nr)++] = row;
  g->wcol[row] += v;
  if (g->wcol[row] == 0.0)
    g->wcol[row] = DBL_MIN;
}

/* M - I of the whole step system (jacobians.c's M with every node's
   Jacobian J), column by column: the diagonal always present */
static int
assemble_whole (spvi_core *c, spvi_stages *g)
{
  const int d = c->d, n = c->n, m = c->m, N = c->N, p0 = (n - 1) * d;
  const double hh = 0.5 * c->h;
  sym_csc *M = &g->Mw;
  int nnz = 0;
  M->colptr[0] = 0;
  for (int col = 0; col < N; col++)
    {
      int nr = 0;
      const int l = col < p0 ? col % d : (col - p0) % d;
      if (col < p0)
        {
          const int i = col / d + 1;           /* the mode a_i */
          for (int s = 1; s < n; s++)
            {
              double v = 0.0;
              for (int j = 0; j < m; j++)
                v += c->g[j * n + s] * c->phi[j * n + i];
              add_block_col (g, d, d, 0, l, hh * v, (s - 1) * d, &nr);
            }
          for (int r = 0; r < m; r++)
            {
              add_block_col (g, d, 0, 0, l, hh * c->phi[r * n + i],
                             p0 + r * d, &nr);
              add_diag (g, p0 + r * d + l, -c->dl[r * n + i], &nr);
            }
        }
      else
        {
          const int j = (col - p0) / d;        /* the momentum P_j */
          for (int s = 1; s < n; s++)
            {
              add_block_col (g, d, d, d, l, hh * c->g[j * n + s],
                             (s - 1) * d, &nr);
              add_diag (g, (s - 1) * d + l, c->wdl[j * n + s], &nr);
            }
          add_block_col (g, d, 0, d, l, hh, p0 + j * d, &nr);
        }
      add_diag (g, col, -1.0, &nr);
      qsort (g->rows, nr, sizeof (int), cmp_int);
      if (sym_csc_reserve (M, nnz + nr + (N - col - 1)))
        return SYM_ENOMEM;
      for (int k = 0; k < nr; k++)
        {
          const int i = g->rows[k];
          M->rowind[nnz] = i;
          M->val[nnz++] = g->wcol[i] == DBL_MIN ? 0.0 : g->wcol[i];
          g->wcol[i] = 0.0;
        }
      M->colptr[col + 1] = nnz;
    }
  M->nnz = nnz;
  return SYM_SUCCESS;
}

/* the stage LUs of size nlu (allocated when the size changes) */
static int
stage_lus (spvi_stages *g, int nlu)
{
  if (g->nlu == nlu)
    return SYM_SUCCESS;
  for (int i = 0; i < g->ns; i++)
    sym_stage_lu_free (&g->lu[i]);
  g->nlu = 0;
  for (int i = 0; i < g->ns; i++)
    {
      int st = sym_stage_lu_init (&g->lu[i], nlu, g->sparse);
      if (st)
        return st;
    }
  g->nlu = nlu;
  return SYM_SUCCESS;
}

/* whether the dense J has Jqq = 0 and Jpp = 0; then K = Jpq Jqp */
static int
schur_setup (spvi_stages *g, int d)
{
  const size_t nn = 2 * (size_t) d;
  const size_t dd = (size_t) d;
  for (size_t j = 0; j < nn; j++)
    for (size_t i = j < dd ? 0 : dd; i < (j < dd ? dd : nn); i++)
      if (g->J[i + j * nn] != 0.0)
        return 0;
  if (! g->K && ! (g->K = sym_malloc ((size_t) d * d * sizeof (double))))
    return SYM_ENOMEM;
  /* a unit mass, Jqp = I: K is Jpq, no product */
  int unit = 1;
  for (size_t j = 0; j < dd && unit; j++)
    for (size_t i = 0; i < dd && unit; i++)
      unit = g->J[i + (dd + j) * nn] == (i == j);
  if (unit)
    {
      for (size_t j = 0; j < dd; j++)
        memcpy (g->K + j * dd, g->J + dd + j * nn, dd * sizeof (double));
      return 1;
    }
  const int ld = (int) nn;
  sym_gemm (d, d, d, g->J + d, ld, g->J + nn * d, ld, g->K, d);
  return 1;
}

/* the same for a sparse J, whose Jqp must also be diagonal: K = Jpq
   diag (Jqp) keeps Jpq's pattern */
static int
schur_setup_sparse (spvi_stages *g, int d)
{
  const sym_csc *J = &g->Js;
  for (int j = 0; j < 2 * d; j++)
    for (int e = J->colptr[j]; e < J->colptr[j + 1]; e++)
      {
        const int i = J->rowind[e];
        if (J->val[e] != 0.0 && (i < d) == (j < d))
          return 0;               /* Jqq or Jpp */
        if (J->val[e] != 0.0 && i < d && j - d != i)
          return 0;               /* Jqp not diagonal */
      }
  if (! g->aq && ! (g->aq = sym_malloc ((size_t) d * sizeof (double))))
    return SYM_ENOMEM;
  if ((! g->Bs.colptr && sym_csc_init (&g->Bs, d, 0))
      || sym_csc_block (J, d, 0, d, &g->Bs))
    return SYM_ENOMEM;
  g->unit_mass = 1;
  for (int j = 0; j < d; j++)
    {
      g->aq[j] = 0.0;
      for (int e = J->colptr[d + j]; e < J->colptr[d + j + 1]; e++)
        if (J->rowind[e] == j)
          g->aq[j] = J->val[e];
      g->unit_mass = g->unit_mass && g->aq[j] == 1.0;
    }
  /* K = Jpq itself for a unit mass, else Jpq with its columns scaled */
  if (g->unit_mass)
    return 1;
  if ((! g->Ks.colptr && sym_csc_init (&g->Ks, d, 0))
      || sym_csc_copy (&g->Ks, &g->Bs))
    return SYM_ENOMEM;
  for (int j = 0; j < d; j++)
    for (int e = g->Ks.colptr[j]; e < g->Ks.colptr[j + 1]; e++)
      g->Ks.val[e] *= g->aq[j];
  return 1;
}

/* J = Df at the middle node of x (f there from the last evaluation when
   it was at x) */
static int
eval_jac (spvi_core *c, const double *x)
{
  spvi_stages *g = c->sg;
  const size_t nn = 2 * (size_t) c->d;
  const int j = c->m / 2;
  sym_eval *ev = c->ev;
  const int fhere = c->fvalid
                    && memcmp (c->xf, x, (size_t) c->N * sizeof (double)) == 0;
  spvi_states (c, x);
  const double *y = c->Y + j * nn, *f0 = fhere ? c->F + j * nn : NULL;
  if (g->sparse)
    return ev->rhs_jac_csc && ! fhere
           ? sym_rhs_jac_csc (ev, c->tj[j], y, g->wv, &g->Js)
           : sym_jac_csc (ev, c->tj[j], y, f0, &g->Js);
  return ev->rhs_jac && ! fhere
         ? sym_rhs_jac (ev, c->tj[j], y, g->wv, g->J)
         : sym_jac (ev, c->tj[j], y, f0, g->J);
}

/* exact: the node Jacobians at x into c->A (allocated at the first
   use), J the middle node's */
static int
exact_jac (spvi_core *c, const double *x)
{
  spvi_stages *g = c->sg;
  const size_t nn = 2 * (size_t) c->d, m = (size_t) c->m;
  if (! g->a_full)
    {
      double *A = sym_calloc (nn * nn * m, sizeof (double));
      g->rb = sym_calloc (2 * (size_t) c->N, sizeof (double));
      g->dyb = sym_calloc (2 * nn * m, sizeof (double));
      if (! A || ! g->rb || ! g->dyb)
        {
          sym_free (A);
          return SYM_ENOMEM;
        }
      sym_free (c->A);
      c->A = A;
      g->a_full = 1;
    }
  int st = spvi_node_jacobians (c, x);
  if (! st)
    memcpy (g->J, spvi_A (c, c->m / 2), nn * nn * sizeof (double));
  return st;
}

int
spvi_stages_factor (void *ctx, const double *x, sym_counters *cnt)
{
  spvi_core *c = ctx;
  spvi_stages *g = c->sg;
  const double hh = 0.5 * c->h;
  c->h_mat = c->h;
  c->noise_ok = 0;
  c->nae = 1;
  c->extra = 0;
  if (c->fp)
    return SYM_SUCCESS;   /* J = 0: nothing to evaluate or factor */
  int st = c->exact ? exact_jac (c, x) : eval_jac (c, x);
  if (st)
    return st;
  if (g->whole)
    {
      /* M = I + (M - I) */
      st = assemble_whole (c, g);
      return st ? st : sym_stage_lu_factor (&g->lu[0], -1.0, 0.0, NULL, 0,
                                            &g->Mw, cnt);
    }
  g->schur = 0;
  if ((st = g->sparse ? schur_setup_sparse (g, c->d)
                      : schur_setup (g, c->d)) < 0)
    return st;
  g->schur = st;
  if ((st = stage_lus (g, g->schur ? c->d : 2 * c->d)))
    return st;
  for (int i = 0; i < g->ns; i++)
    {
      /* I - gamma J, or I - gamma^2 K */
      double complex gam = -hh * g->lam[i];
      if (g->schur)
        gam *= gam;
      if ((st = sym_stage_lu_factor (&g->lu[i], creal (gam), cimag (gam),
                                     g->schur ? g->K : g->J,
                                     g->schur ? c->d : 2 * c->d,
                                     ! g->schur ? &g->Js
                                     : g->unit_mass ? &g->Bs : &g->Ks,
                                     cnt)))
        return st;
    }
  return SYM_SUCCESS;
}

/* out (d values) = the p rows of node j's Jacobian times dy (2d) */
void
spvi_jac_p (spvi_core *c, int j, const double *dy, double *out)
{
  const int d = c->d;
  const size_t nn = 2 * (size_t) d;
  const spvi_stages *g = c->sg;
  if (c->fp)
    {
      memset (out, 0, (size_t) d * sizeof (double));
      return;
    }
  if (g && g->sparse && ! c->exact)
    {
      /* J's p rows only */
      const sym_csc *J = &g->Js;
      memset (out, 0, (size_t) d * sizeof (double));
      for (size_t l = 0; l < nn; l++)
        if (dy[l] != 0.0)
          for (int e = J->colptr[l]; e < J->colptr[l + 1]; e++)
            if (J->rowind[e] >= d)
              out[J->rowind[e] - d] += J->val[e] * dy[l];
      return;
    }
  const double *A = g && ! c->exact ? g->J : spvi_A (c, j);
  for (int k = 0; k < d; k++)
    out[k] = 0.0;
  for (size_t l = 0; l < nn; l++)
    if (dy[l] != 0.0)
      for (int k = 0; k < d; k++)
        out[k] += A[(d + k) + l * nn] * dy[l];
}

/* max_k sum_l |Jqp_kl| pa_l and max_k sum_l |Jpq_kl| qa_l of J */
void
spvi_stages_noise (spvi_core *c, const double *qa, const double *pa)
{
  const int d = c->d;
  const size_t nn = 2 * (size_t) d;
  spvi_stages *g = c->sg;
  double *row = g->wv;          /* the row sums, q rows then p rows */
  if (c->fp)
    {
      c->noise_q = c->noise_p = 0.0;
      c->noise_ok = 1;
      return;
    }
  memset (row, 0, nn * sizeof (double));
  for (size_t l = 0; l < nn; l++)
    {
      const double a = l < (size_t) d ? qa[l] : pa[l - d];
      if (g->sparse)
        {
          for (int e = g->Js.colptr[l]; e < g->Js.colptr[l + 1]; e++)
            {
              const int k = g->Js.rowind[e];
              if ((k < d) != (l < (size_t) d))
                row[k] += fabs (g->Js.val[e]) * a;
            }
        }
      else
        for (size_t k = l < (size_t) d ? d : 0;
             k < (l < (size_t) d ? nn : (size_t) d); k++)
          row[k] += fabs (g->J[k + l * nn]) * a;
    }
  c->noise_q = c->noise_p = 0.0;
  for (int k = 0; k < d; k++)
    {
      c->noise_q = fmax (c->noise_q, row[k]);
      c->noise_p = fmax (c->noise_p, row[d + k]);
    }
  c->noise_ok = 1;
}
