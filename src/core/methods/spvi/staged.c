/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* staged.c -- odeSPVI's Newton systems reduced to stage systems of size
   2d (or d), for the pairs n - 1 = m (Gauss collocation), as implicit
   Runge-Kutta codes reduce theirs.  This file: the stages' transforms
   from the method's coefficients, and their state's setup and release;
   J and the matrices made from it are staged_factor.c's, the solves
   staged_solve.c's.

   With one Jacobian J for all nodes, Newton's matrix (jacobians.c) is
   M = B0 + Bf (I (x) J) U: B0 the constant part, U the map from x to the
   node states (Q_j, P_j), Bf how the nodes' f enter the equations.  For
   n - 1 = m, U and B0 are invertible and U B0^-1 Bf = (h/2) S (x) I, the
   same m-by-m S for q and p (S = Wd^-1 G = -Phi D^-1 in the notation of
   spvi.h: Wd_sj = w_j l_s'(z_j), G_sj = g_sj, Phi_ji = phi_i(z_j), D_ri =
   l_i'(z_r)).  So M dx = b becomes, for dY = U dx,
     dY_j + (h/2) sum_l S_jl J dY_l = g_j,  g = U B0^-1 b,
   and with S = T Lambda T^-1 each Z_i = (T^-1 dY)_i solves
     (I + (h/2) lambda_i J) Z_i = (T^-1 g)_i,
   one real system of size 2d for each real lambda_i and one complex one
   for each conjugate pair (the other is its conjugate).  Then dY = T Z
   and dx = U^-1 dY (dP = dY's P, da = Phi^-1 dQ).  The LU of the
   ((n - 1 + m) d)^2 matrix becomes ceil(m/2) LUs of (2d)^2 (sparse when
   J is), and no node Jacobian but J is kept.

   The other pairs with a sparse J (whole): Newton's matrix itself,
   assembled sparse from J's blocks, one sparse LU.

   A separable H has Jqq = Jpp = 0: I - c J is then solved by its Schur
   complement, (I - c^2 Jpq Jqp) Zp = bp + c Jpq bq, Zq = bq + c Jqp Zp,
   of size d (sparse: for a diagonal Jqp, so that Jpq Jqp keeps Jpq's
   pattern).

   J is Df at the middle node of the iterate the matrix is made at: a
   simplified Newton whose matrix misses the nodes' own Jacobians by O(h),
   so that its contraction is O(h^2).  With a new matrix every solve
   (exact), the node Jacobians come with the same calls, and each solve
   is iterated on Newton's own matrix (spvi_matvec) with the stages as
   its preconditioner, to round-off: a few products per correction, and
   the correction is Newton's, whose quadratic error the stopping test
   of newton.c's quad mode assumes.  With J = 0 (fp) the iteration is
   the fixed point of the step's equations, as non-stiff implicit
   Runge-Kutta codes iterate theirs: no Jacobian, no LU. */
#include "staged.h"

#include <complex.h>
#include <math.h>
#include <string.h>

/* Invert the m-by-m complex a (column-major) into ai by Gauss-Jordan
   with partial pivoting; -1 if singular */
static int
cinv (int m, const double complex *a, double complex *ai,
      double complex *w)
{
  memcpy (w, a, (size_t) m * m * sizeof (*w));
  for (int i = 0; i < m; i++)
    for (int j = 0; j < m; j++)
      ai[i + j * m] = i == j;
  for (int k = 0; k < m; k++)
    {
      int p = k;
      for (int i = k + 1; i < m; i++)
        if (cabs (w[i + k * m]) > cabs (w[p + k * m]))
          p = i;
      if (w[p + k * m] == 0)
        return -1;
      for (int j = 0; j < m; j++)
        {
          double complex t = w[k + j * m];
          w[k + j * m] = w[p + j * m];
          w[p + j * m] = t;
          t = ai[k + j * m];
          ai[k + j * m] = ai[p + j * m];
          ai[p + j * m] = t;
        }
      double complex piv = w[k + k * m];
      for (int j = 0; j < m; j++)
        {
          w[k + j * m] /= piv;
          ai[k + j * m] /= piv;
        }
      for (int i = 0; i < m; i++)
        if (i != k && w[i + k * m] != 0)
          {
            double complex f = w[i + k * m];
            for (int j = 0; j < m; j++)
              {
                w[i + j * m] -= f * w[k + j * m];
                ai[i + j * m] -= f * ai[k + j * m];
              }
          }
    }
  return 0;
}

/* The transforms of the stage systems from the method's coefficients:
   0, SYM_ENOMEM, or -1 when S is not the same for q and p (a pair n - 1 != m) or
   cannot be diagonalized well */
static int
transforms (spvi_core *c, spvi_stages *g)
{
  const int n = c->n, m = c->m;
  const size_t mm = (size_t) m * m;
  if (n - 1 != m)
    return -1;
  double complex *wd = sym_malloc (8 * mm * sizeof (double complex));
  double *rs = sym_malloc ((2 * mm + 8 * (size_t) m + 2 * mm) * sizeof (double));
  int st = SYM_ENOMEM;
  if (! wd || ! rs)
    goto done;
  st = -1;
  double complex *wdi = wd + mm, *phi = wd + 2 * mm, *phii = wd + 3 * mm;
  double complex *dl = wd + 4 * mm, *dli = wd + 5 * mm, *T = wd + 6 * mm;
  double complex *w = wd + 7 * mm;
  for (int r = 0; r < m; r++)
    for (int i = 0; i < m; i++)
      {
        wd[r + i * m] = c->wdl[i * n + r + 1];   /* Wd_sj: s = r + 1, j = i */
        phi[r + i * m] = c->phi[r * n + i + 1];  /* Phi_ji: j = r */
        dl[r + i * m] = c->dl[r * n + i + 1];    /* D_ri */
      }
  if (cinv (m, wd, wdi, w) || cinv (m, phi, phii, w) || cinv (m, dl, dli, w))
    goto done;
  /* S = Wd^-1 G, and the same from q's side: -Phi D^-1 */
  double *S = rs, *wr = rs + mm, *wi = wr + m, *vr = wi + m, *work = vr + mm;
  double smax = 0.0, diff = 0.0;
  for (int i = 0; i < m; i++)
    for (int j = 0; j < m; j++)
      {
        double complex s1 = 0, s2 = 0;
        for (int k = 0; k < m; k++)
          {
            s1 += wdi[i + k * m] * c->g[j * n + k + 1];
            s2 -= phi[i + k * m] * dli[k + j * m];
          }
        S[i + j * m] = creal (s1);
        smax = fmax (smax, cabs (s1));
        diff = fmax (diff, cabs (s1 - s2));
      }
  if (! (diff <= SYM_SPVI_STAGE_SAME * smax))
    goto done;
  memcpy (g->wg, S, mm * sizeof (double));   /* (geev overwrites S) */
  int info = sym_geev (m, S, wr, wi, vr, work, 4 * m + (int) mm);
  if (info)
    goto done;
  for (int j = 0; j < m; j++)
    {
      if (wi[j] != 0.0 && j + 1 < m)
        {
          for (int i = 0; i < m; i++)
            {
              T[i + j * m] = vr[i + j * m] + I * vr[i + (j + 1) * m];
              T[i + (j + 1) * m] = vr[i + j * m] - I * vr[i + (j + 1) * m];
            }
          j++;
        }
      else
        for (int i = 0; i < m; i++)
          T[i + j * m] = vr[i + j * m];
    }
  double complex *Ti = dl;    /* D is no longer needed */
  if (cinv (m, T, Ti, w))
    goto done;
  /* one stage system for each real eigenvalue and each pair (the first
     of it, wi > 0 as dgeev orders them) */
  g->ns = 0;
  for (int j = 0; j < m; j++)
    if (wi[j] >= 0.0)
      {
        int i = g->ns++;
        g->idx[i] = j;
        g->lam[i] = wr[j] + I * wi[j];
      }
  /* rows of the forward transforms (rq on the R2 rows, rp on the R1
     rows) for the systems solved; the back transforms bq = Phi^-1 T and
     bp = T for all eigenvalues */
  for (int i = 0; i < g->ns; i++)
    for (int r = 0; r < m; r++)
      {
        const int e = g->idx[i];
        double complex v = 0;
        for (int k = 0; k < m; k++)
          v += Ti[e + k * m] * wdi[k + r * m];
        g->rq[i + r * m] = g->lam[i] * Ti[e + r * m];
        g->rp[i + r * m] = v;
      }
  for (int j = 0; j < m; j++)
    for (int i = 0; i < g->ns; i++)
      {
        const int e = g->idx[i];
        double complex v = 0;
        for (int k = 0; k < m; k++)
          v += phii[j + k * m] * T[k + e * m];
        g->bq[j + i * m] = v;
        g->bp[j + i * m] = T[j + e * m];
      }
  for (size_t e = 0; e < mm; e++)
    {
      g->dinv[e] = -creal (dli[e]);
      g->wdinv[e] = creal (wdi[e]);
    }
  st = 0;
done:
  sym_free (wd);
  sym_free (rs);
  return st;
}


void
spvi_stages_free (spvi_core *c)
{
  spvi_stages *g = c->sg;
  if (! g)
    return;
  for (int i = 0; i < SYM_SPVI_MAX_NODES; i++)
    sym_stage_lu_free (&g->lu[i]);
  sym_csc_free (&g->Js);
  sym_csc_free (&g->Mw);
  sym_free (g->wcol);
  sym_free (g->rows);
  sym_csc_free (&g->Bs);
  sym_csc_free (&g->Ks);
  sym_free (g->aq);
  sym_free (g->K);
  sym_free (g->rq);
  sym_free (g->J);
  sym_free (g->z);
  sym_free (g->wv);
  sym_free (g->rb);
  sym_free (g->dyb);
  sym_free (g->dinv);
  sym_free (g->fw);
  sym_free (g);
  c->sg = NULL;
}

int
spvi_stages_init (spvi_core *c, int sparse)
{
  const int m = c->m;
  const size_t nn = 2 * (size_t) c->d, mm = (size_t) m * m;
  spvi_stages *g = c->sg = sym_calloc (1, sizeof (*g));
  if (! g)
    return SYM_ENOMEM;
  g->sparse = sparse;
  g->rq = sym_calloc (4 * mm, sizeof (double complex));
  g->wv = sym_calloc (nn, sizeof (double));
  g->J = sparse ? NULL : sym_calloc (nn * nn, sizeof (double));
  g->dinv = sym_calloc (3 * mm, sizeof (double));
  g->fw = sym_calloc (c->N, sizeof (double));
  if (! g->rq || ! g->wv || (! sparse && ! g->J) || ! g->dinv || ! g->fw
      || (sparse && sym_csc_init (&g->Js, (int) nn, 0)))
    return SYM_ENOMEM;
  g->rp = g->rq + mm;
  g->bq = g->rq + 2 * mm;
  g->bp = g->rq + 3 * mm;
  g->wdinv = g->dinv + mm;
  g->wg = g->dinv + 2 * mm;
  int st = transforms (c, g);
  if (st == -1 && sparse)
    {
      /* a pair n - 1 != m: the whole system, sparse */
      g->whole = 1;
      g->ns = 0;
      g->wcol = sym_calloc (c->N, sizeof (double));
      g->rows = sym_malloc ((size_t) c->N * sizeof (int));
      if (! g->wcol || ! g->rows || sym_csc_init (&g->Mw, c->N, 0)
          || sym_stage_lu_init (&g->lu[0], c->N, 1))
        return SYM_ENOMEM;
      return SYM_SUCCESS;
    }
  if (st)
    return st == -1 ? SYM_EBADINPUT : st;
  g->z = sym_calloc (nn * g->ns, sizeof (double complex));
  return g->z ? SYM_SUCCESS : SYM_ENOMEM;
}

int
spvi_stages_dense (const spvi_core *c)
{
  return c->sg && ! c->sg->sparse && ! c->sg->whole;
}
