/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* staged.c -- odeSPVI's Newton systems reduced to stage systems of size
   2d (or d), for the pairs n - 1 = m (Gauss collocation), as implicit
   Runge-Kutta codes reduce theirs.

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
#include "spvi.h"

#include <complex.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

struct spvi_stages {
  int ns;                       /* stage systems */
  int idx[SYM_SPVI_MAX_NODES];  /* their eigenvalue's index in S */
  double complex lam[SYM_SPVI_MAX_NODES];
  double complex *rq, *rp;      /* forward transforms, [i + r m] */
  double complex *bq, *bp;      /* back transforms, [j + i m] */
  sym_stage_lu lu[SYM_SPVI_MAX_NODES];
  int nlu;                      /* their size: 0 (none yet), d or 2d */
  int sparse;
  /* J with zero blocks Jqq and Jpp (a separable H; sparse: and a
     diagonal Jqp, a diagonal mass): the stage systems by their Schur
     complements I - gamma^2 K, K = Jpq Jqp, of size d */
  int schur;
  double *K;
  sym_csc Bs, Ks;               /* sparse: Jpq, and K (unit_mass:
                                   Jqp = I, K is Bs) */
  int unit_mass;
  double *aq;                   /* sparse: Jqp's diagonal (d) */
  double *J;                    /* dense: (2d)^2 */
  sym_csc Js;                   /* sparse */
  double complex *z;            /* work: ns x 2d */
  /* J = 0 (fp): M is its constant part, whose inverse maps the R2 rows
     to the da by -D^-1 and the R1 rows to the dP by Wd^-1 (real m x m,
     column-major), without the transforms */
  double *dinv, *wdinv;
  double *fw;                   /* work: N */
  /* the pairs n - 1 != m with a sparse J: no stages (ns = 0), the whole
     system M, assembled sparse as M - I (lu[0], factored as I + (M - I))
     from J's blocks as jacobians.c's matrix with every A_j = J */
  int whole;
  sym_csc Mw;
  double *wcol;                 /* work: N (a column of M - I) */
  int *rows;                    /* work: N (its rows) */
  double *wv;                   /* work: 2d */
  /* exact: c->A sized for the node Jacobians; work: the right side and
     the residual (N each), the products' node values (4 d m) */
  int a_full;
  double *rb, *dyb;
};

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
  g->dinv = sym_calloc (2 * mm, sizeof (double));
  g->fw = sym_calloc (c->N, sizeof (double));
  if (! g->rq || ! g->wv || (! sparse && ! g->J) || ! g->dinv || ! g->fw
      || (sparse && sym_csc_init (&g->Js, (int) nn, 0)))
    return SYM_ENOMEM;
  g->rp = g->rq + mm;
  g->bq = g->rq + 2 * mm;
  g->bp = g->rq + 3 * mm;
  g->wdinv = g->dinv + mm;
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
spvi_stages_dense (const spvi_core *c)
{
  return c->sg && ! c->sg->sparse && ! c->sg->whole;
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

/* y += s M x: M the d-by-d block at M (leading dimension ld), x and y
   k-component values (k = 1 real, 2 complex as (re, im) pairs), s
   real or complex */
static void
block_mv (int d, const double *M, size_t ld, const double *x, double *y,
          int k, double complex s)
{
  for (int j = 0; j < d; j++)
    {
      const double complex xj = k == 1 ? s * x[j]
                                : s * (x[2 * j] + I * x[2 * j + 1]);
      if (xj == 0)
        continue;
      const double xr = creal (xj), xi = cimag (xj);
      const double *mj = M + (size_t) j * ld;
      if (k == 1)
        for (int i = 0; i < d; i++)
          y[i] += mj[i] * xr;
      else
        for (int i = 0; i < d; i++)
          {
            y[2 * i] += mj[i] * xr;
            y[2 * i + 1] += mj[i] * xi;
          }
    }
}

/* y += s B x for the sparse B, as block_mv */
static void
sparse_mv (const sym_csc *B, const double *x, double *y, int k,
           double complex s)
{
  for (int j = 0; j < B->n; j++)
    {
      const double complex xj = k == 1 ? s * x[j]
                                : s * (x[2 * j] + I * x[2 * j + 1]);
      if (xj == 0)
        continue;
      for (int e = B->colptr[j]; e < B->colptr[j + 1]; e++)
        {
          const int i = B->rowind[e];
          y[k * i] += B->val[e] * creal (xj);
          if (k == 2)
            y[2 * i + 1] += B->val[e] * cimag (xj);
        }
    }
}

/* z <- (I - gamma J) \ z, z = [zq; zp] with k components each, by the
   Schur complement: (I - gamma^2 Jpq Jqp) zp = bp + gamma Jpq bq, then
   zq = bq + gamma Jqp zp */
static int
schur_solve (spvi_stages *g, int i, int d, double hh, double *z, int k,
             sym_counters *cnt)
{
  const size_t nn = 2 * (size_t) d;
  const double complex gam = -hh * g->lam[i];
  double *zq = z, *zp = z + (size_t) k * d;
  if (g->sparse)
    sparse_mv (&g->Bs, zq, zp, k, gam);
  else
    block_mv (d, g->J + d, nn, zq, zp, k, gam);
  int st = sym_stage_lu_solve (&g->lu[i], zp, cnt);
  if (st)
    return st;
  if (! g->sparse)
    block_mv (d, g->J + nn * d, nn, zp, zq, k, gam);
  else
    for (int j = 0; j < d; j++)
      {
        const double complex v = gam * g->aq[j]
                                 * (k == 1 ? zp[j]
                                    : zp[2 * j] + I * zp[2 * j + 1]);
        zq[k * j] += creal (v);
        if (k == 2)
          zq[2 * j + 1] += cimag (v);
      }
  return SYM_SUCCESS;
}

/* b <- M \ b for J = 0: da = -D^-1 b2, dP = Wd^-1 b1 */
static void
fp_apply (const spvi_core *c, double *b)
{
  const spvi_stages *g = c->sg;
  const int d = c->d, m = c->m;
  const size_t md = (size_t) m * d;
  double *x = g->fw;
  memcpy (x, b, 2 * md * sizeof (double));
  const double *b1 = x, *b2 = x + md;
  for (int j = 0; j < m; j++)
    for (int k = 0; k < d; k++)
      {
        double sa = 0.0, sp = 0.0;
        for (int r = 0; r < m; r++)
          {
            sa += g->dinv[j + r * m] * b2[(size_t) r * d + k];
            sp += g->wdinv[j + r * m] * b1[(size_t) r * d + k];
          }
        b[(size_t) j * d + k] = sa;
        b[md + (size_t) j * d + k] = sp;
      }
}

/* b <- M \ b by the stage systems (see the top) */
static int
stages_apply (spvi_core *c, double *b, sym_counters *cnt)
{
  spvi_stages *g = c->sg;
  const int d = c->d, m = c->m, ns = g->ns;
  const size_t nn = 2 * (size_t) d;
  if (g->whole)
    return sym_stage_lu_solve (&g->lu[0], b, cnt);
  if (c->fp)
    {
      fp_apply (c, b);
      return SYM_SUCCESS;
    }
  double *b1 = b, *b2 = b + (size_t) m * d;    /* R1 rows, R2 rows */
  for (int i = 0; i < ns; i++)
    {
      double complex *zi = g->z + i * nn;
      for (int k = 0; k < d; k++)
        {
          double complex vq = 0, vp = 0;
          for (int r = 0; r < m; r++)
            {
              vq += g->rq[i + r * m] * b2[(size_t) r * d + k];
              vp += g->rp[i + r * m] * b1[(size_t) r * d + k];
            }
          zi[k] = vq;
          zi[d + k] = vp;
        }
      if (cimag (g->lam[i]) == 0.0)
        {
          /* a real system: its values in place, as real numbers */
          double *zr = (double *) zi;
          for (size_t k = 0; k < nn; k++)
            zr[k] = creal (zi[k]);
        }
      const int k = cimag (g->lam[i]) == 0.0 ? 1 : 2;
      int st = g->schur ? schur_solve (g, i, d, 0.5 * c->h_mat,
                                       (double *) zi, k, cnt)
                        : sym_stage_lu_solve (&g->lu[i], (double *) zi, cnt);
      if (st)
        return st;
    }
  /* back: da = Phi^-1 T Z_q, dP = T Z_p (pairs twice the real part) */
  for (int k = 0; k < d; k++)
    for (int j = 0; j < m; j++)
      {
        double sa = 0.0, sp = 0.0;
        for (int i = 0; i < ns; i++)
          {
            const double complex *zi = g->z + i * nn;
            if (cimag (g->lam[i]) == 0.0)
              {
                const double *zr = (const double *) zi;
                sa += creal (g->bq[j + i * m]) * zr[k];
                sp += creal (g->bp[j + i * m]) * zr[d + k];
              }
            else
              {
                sa += 2.0 * creal (g->bq[j + i * m] * zi[k]);
                sp += 2.0 * creal (g->bp[j + i * m] * zi[d + k]);
              }
          }
        b[(size_t) j * d + k] = sa;
        b2[(size_t) j * d + k] = sp;
      }
  return SYM_SUCCESS;
}

/* b <- M \ b; exact: M Newton's matrix of the node Jacobians, by the
   stages' solves of the residuals of M x = b until the change is at
   round-off.  One that does not contract (a J far from the nodes') ends
   the iteration, and the solve's stopping test no longer takes its
   corrections for Newton's (nw.quad off until the next matrix). */
int
spvi_stages_solve (void *ctx, double *b, sym_counters *cnt)
{
  spvi_core *c = ctx;
  spvi_stages *g = c->sg;
  if (! c->exact)
    return stages_apply (c, b, cnt);
  const int N = c->N;
  double *b0 = g->rb, *r = g->rb + N, prev = INFINITY;
  memcpy (b0, b, (size_t) N * sizeof (double));
  int st = stages_apply (c, b, cnt);
  for (int k = 0; ! st; k++)
    {
      spvi_matvec (c, b, r, g->dyb);
      for (int i = 0; i < N; i++)
        r[i] = b0[i] - r[i];
      if ((st = stages_apply (c, r, cnt)))
        break;
      double nr = 0.0, nx = 0.0;
      for (int i = 0; i < N; i++)
        {
          b[i] += r[i];
          nr = fmax (nr, fabs (r[i]));
          nx = fmax (nx, fabs (b[i]));
        }
      if (! (nr > SYM_SPVI_EXACT_EPS * DBL_EPSILON * nx))
        break;
      if (nr > 0.5 * prev || k + 1 == SYM_SPVI_EXACT_ITERS)
        {
          c->nw.quad = 0;
          break;
        }
      prev = nr;
    }
  return st;
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
