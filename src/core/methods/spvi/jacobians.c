/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* jacobians.c -- odeSPVI's Newton matrix from the node Jacobians
   A_j = Df(t_j, Q_j, P_j) = [Aqq Aqp; Apq App]:
     dR1_s/dP_j = w_j l_s'(z_j) I + (h/2) g_sj App_j
     dR1_s/da_i = (h/2) sum_j g_sj phi_i(z_j) Apq_j
     dR2_r/dP_j = delta_rj (h/2) Aqp_r
     dR2_r/da_i = (h/2) phi_i(z_r) Aqq_r - l_i'(z_r) I.
   The node Jacobians are evaluated (one per node: the exact matrix also
   keeps the full-Newton fallback quadratic), or, for the next steps,
   extrapolated in time from the last evaluations (no callback, one LU),
   and for the companion interpolated from the method's of the same
   step. */
#include "spvi.h"

#include <math.h>
#include <string.h>

/* Keep the node Jacobians in c->A for the extrapolation
   (spvi_extrapolate): a new step's evaluation becomes the latest, a
   second one on the same step (a refresh inside sym_newton) replaces
   it. */
static void
keep (spvi_core *c)
{
  const size_t nn = 2 * (size_t) c->d;
  if (c->nae > 0 && c->te[0] != 0.0)
    {
      double *tmp = c->Ae[1];
      c->Ae[1] = c->Ae[0];
      c->Ae[0] = tmp;
      c->te[1] = c->te[0];
      c->he[1] = c->he[0];
      c->nae = 2;
    }
  else if (c->nae == 0)
    c->nae = 1;
  memcpy (c->Ae[0], c->A, nn * nn * (size_t) c->m * sizeof (double));
  c->te[0] = 0.0;
  c->he[0] = c->h;
}

/* The Newton matrix from the node Jacobians in c->A and the step c->h.
   Its columns are written in order, each from its own loops (a column
   of M per (i, l) or (j, l)), so that the compiler sees no aliasing. */
static void
fill (spvi_core *c, double *M)
{
  const int d = c->d, n = c->n, m = c->m, N = c->N;
  const size_t nn = 2 * (size_t) d, nb = nn * nn;
  const double hh = 0.5 * c->h;
  const double *const A = c->A, *const g = c->g, *const phi = c->phi;
  const double *const wdl = c->wdl, *const dl = c->dl;
  c->h_mat = c->h;
  c->noise_ok = 0;
  const int p0 = (n - 1) * d;     /* first P column, first R2 row */
  /* the a_i columns: dR1_s/da_i, then dR2_r/da_i */
  for (int i = 1; i < n; i++)
    for (int l = 0; l < d; l++)
      {
        double *col = M + (size_t) ((i - 1) * d + l) * N;
        for (int s = 1; s < n; s++)
          for (int k = 0; k < d; k++)
            {
              double v = 0.0;
              for (int j = 0; j < m; j++)
                v += g[j * n + s] * phi[j * n + i] * APQ (A + j * nb, k, l);
              col[(s - 1) * d + k] = hh * v;
            }
        for (int r = 0; r < m; r++)
          {
            const double *Ar = A + r * nb;
            for (int k = 0; k < d; k++)
              col[p0 + r * d + k] = hh * phi[r * n + i] * AQQ (Ar, k, l)
                                    - (k == l ? dl[r * n + i] : 0);
          }
      }
  /* the P_j columns: dR1_s/dP_j, then dR2_r/dP_j (r = j only) */
  for (int j = 0; j < m; j++)
    {
      const double *Aj = A + j * nb;
      for (int l = 0; l < d; l++)
        {
          double *col = M + (size_t) (p0 + j * d + l) * N;
          for (int s = 1; s < n; s++)
            {
              const double gs = hh * g[j * n + s];
              for (int k = 0; k < d; k++)
                col[(s - 1) * d + k] = gs * APP (Aj, k, l)
                                       + (k == l ? wdl[j * n + s] : 0);
            }
          for (int i = p0; i < N; i++)
            col[i] = 0.0;
          for (int k = 0; k < d; k++)
            col[p0 + j * d + k] = hh * AQP (Aj, k, l);
        }
    }
}

/* The node Jacobians c->A at x, with f at x when the same calls give it
   (the residual at this x, which follows, reuses it) */
int
spvi_node_jacobians (spvi_core *c, const double *x)
{
  const int m = c->m;
  const size_t nn = 2 * (size_t) c->d;
  int st;
  const size_t nb = (size_t) c->N * sizeof (double);
  const int fhere = c->fvalid && memcmp (c->xf, x, nb) == 0;
  if (c->ev->rhs_jac || (! c->ev->jac && ! fhere))
    {
      /* f comes with the Jacobians: from the same calls (the Hessian as
         FCN's second output), or for finite differences from the call of
         the perturbed states (one batch, or the m calls before them) */
      if (! fhere)
        spvi_eval_shift (c, x);
      c->fvalid = 0;
      spvi_states (c, x);
      if (c->ev->rhs_jac)
        {
          for (int j = 0; j < m; j++)
            if ((st = sym_rhs_jac (c->ev, c->tj[j], c->Y + j * nn,
                                   c->F + j * nn, c->A + j * nn * nn)))
              return st;
        }
      else if ((st = sym_rhs_jac_many (c->ev, m, c->tj, c->Y, c->F,
                                       c->A)))
        return st;
      memcpy (c->xf, x, nb);
      c->fvalid = 1;
      return SYM_SUCCESS;
    }
  /* the Jacobian callback, or finite differences from the F at x */
  spvi_states (c, x);
  return sym_jac_many (c->ev, m, c->tj, c->Y, c->F, c->A);
}

int
spvi_matrix (void *ctx, const double *x, double *M)
{
  spvi_core *c = ctx;
  int st = spvi_node_jacobians (c, x);
  if (st)
    return st;
  keep (c);
  fill (c, M);
  c->extra = 0;
  return SYM_SUCCESS;
}

/* out = M v for Newton's matrix M of the node Jacobians c->A and the step
   c->h (the entries of fill, as a product); dy: work, 4d m */
void
spvi_matvec (const spvi_core *c, const double *v, double *out, double *dy)
{
  const int d = c->d, n = c->n, m = c->m;
  const size_t nn = 2 * (size_t) d;
  const double hh = 0.5 * c->h;
  const double *da = v, *dP = v + (size_t) (n - 1) * d;
  double *df = dy + nn * m;
  /* the nodes' dY_j = [dQ_j; dP_j], then dF_j = A_j dY_j */
  for (int j = 0; j < m; j++)
    {
      double *y = dy + j * nn, *f = df + j * nn;
      for (int k = 0; k < d; k++)
        {
          double s = 0.0;
          for (int i = 1; i < n; i++)
            s += c->phi[j * n + i] * da[(size_t) (i - 1) * d + k];
          y[k] = s;
          y[d + k] = dP[(size_t) j * d + k];
        }
      const double *A = spvi_A (c, j);
      for (size_t k = 0; k < nn; k++)
        f[k] = 0.0;
      for (size_t l = 0; l < nn; l++)
        if (y[l] != 0.0)
          for (size_t k = 0; k < nn; k++)
            f[k] += A[k + l * nn] * y[l];
    }
  for (int s = 1; s < n; s++)
    for (int k = 0; k < d; k++)
      {
        double s1 = 0.0, s2 = 0.0;
        for (int j = 0; j < m; j++)
          {
            s1 += c->wdl[j * n + s] * dP[(size_t) j * d + k];
            s2 += c->g[j * n + s] * df[j * nn + d + k];
          }
        out[(size_t) (s - 1) * d + k] = s1 + hh * s2;
      }
  double *o2 = out + (size_t) (n - 1) * d;
  for (int j = 0; j < m; j++)
    for (int k = 0; k < d; k++)
      {
        double s1 = 0.0;
        for (int i = 1; i < n; i++)
          s1 += c->dl[j * n + i] * da[(size_t) (i - 1) * d + k];
        o2[(size_t) j * d + k] = hh * df[j * nn + k] - s1;
      }
}

/* The current step starts shift after the last one: the kept
   evaluations' starts count from it (see spvi_clock). */
void
spvi_core_move (spvi_core *c, double shift)
{
  for (int e = 0; e < c->nae; e++)
    c->te[e] -= shift;
}

/* The node Jacobians c->A at the points xe[i] (one per node) from np
   samples, the blocks src[j] at the points xs[j] (barycentric weights
   bw): their interpolating polynomial. */
static void
interp_A (spvi_core *c, int np, const double *xs, const double *bw,
               const double *const *src, const double *xe)
{
  const size_t nn = 2 * (size_t) c->d, nb = nn * nn;
  double cb[2 * SYM_SPVI_JX_POINTS];
  for (int i = 0; i < c->m; i++)
    {
      sym_lagrange_basis (np, xs, bw, xe[i], cb);
      double *Ai = c->A + (size_t) i * nb;
      for (size_t e = 0; e < nb; e++)
        {
          double v = 0.0;
          for (int j = 0; j < np; j++)
            v += cb[j] * src[j][e];
          Ai[e] = v;
        }
    }
}

/* The matrix from c->A, factored; 0 (and no matrix: sym_newton evaluates
   one) if the LU failed. */
static int
refactor (spvi_core *c, sym_eval *ev)
{
  if (sym_newton_lu (&c->nw))
    return 0;
  fill (c, c->nw.lu.a);
  if (sym_lu_factor (&c->nw.lu, &ev->st.cnt))
    {
      sym_newton_invalidate (&c->nw);
      return 0;
    }
  return 1;
}

/* The node Jacobians of this step (c->A) extrapolated in time from the
   evaluated ones, and the matrix and LU from them; 0 if not done (nothing
   to extrapolate from, or too far).  The node Jacobians are smooth
   functions of t along the solution, sampled at the nodes of the steps
   where they were evaluated: a polynomial through the latest samples
   (at most SYM_SPVI_JX_POINTS; fewer while sum_j |L_j| at the new nodes
   exceeds SYM_SPVI_JX_LEBESGUE) predicts them at the new nodes: a kept
   matrix then contracts nearly as a fresh one. */
int
spvi_extrapolate (spvi_core *c, sym_eval *ev)
{
  const int m = c->m;
  const size_t nn = 2 * (size_t) c->d, nb = nn * nn;
  if (c->nae < 1 || c->te[0] == 0.0
      || ! (fabs (c->te[0]) <= SYM_SPVI_JX_STEPS * fabs (c->he[0])
                                   * (1 + SYM_SPVI_JX_SLACK)))
    return 0;
  /* sample times in units of he[0] from te[0], ascending in the direction
     of integration; the older evaluation first */
  double ts[2 * SYM_SPVI_JX_POINTS], bw[2 * SYM_SPVI_JX_POINTS];
  double cb[2 * SYM_SPVI_JX_POINTS];
  const double *src[2 * SYM_SPVI_JX_POINTS];
  int np = 0;
  for (int e = (c->nae > 1 && fabs (c->te[0] - c->te[1])
                              <= SYM_SPVI_JX_SPAN * fabs (c->he[0])
                                 * (1 + SYM_SPVI_JX_SLACK));
       e >= 0; e--)
    for (int j = 0; j < m; j++)
      {
        double tz = (c->te[e] - c->te[0]) / c->he[0]
                    + 0.5 * (c->he[e] / c->he[0]) * (1.0 + c->z[j]);
        /* the latest SYM_SPVI_JX_POINTS only (they come in ascending order) */
        if (np == SYM_SPVI_JX_POINTS)
          {
            memmove (ts, ts + 1, (np - 1) * sizeof (double));
            memmove (src, src + 1, (np - 1) * sizeof (src[0]));
            np--;
          }
        ts[np] = tz;
        src[np++] = c->Ae[e] + (size_t) j * nb;
      }
  /* the new nodes, likewise */
  double xe[SYM_SPVI_MAX_NODES + 1];
  for (int i = 0; i < m; i++)
    xe[i] = (0.5 * c->h * (c->z[i] + 1.0) - c->te[0]) / c->he[0];
  int off = 0;
  for (;; off++)
    {
      sym_bary_weights (np - off, ts + off, bw);
      double lam = 0.0;
      for (int i = 0; i < m; i++)
        {
          sym_lagrange_basis (np - off, ts + off, bw, xe[i], cb);
          double sum = 0.0;
          for (int j = 0; j < np - off; j++)
            sum += fabs (cb[j]);
          lam = isnan (sum) ? INFINITY : fmax (lam, sum);
        }
      if (lam <= SYM_SPVI_JX_LEBESGUE || np - off == 1)
        break;
    }
  interp_A (c, np - off, ts + off, bw, src + off, xe);
  refactor (c, ev);
  return 1;
}

/* The companion's matrix, when it has none (a new h, a slow solve), from
   the method's node Jacobians of the same step (evaluated there at (t,
   h)) interpolated to the companion's nodes by the polynomial through
   them: no callback, one LU.  Its first residual then takes f at its
   nodes by rhs calls, not by calls that also give the Hessian, and no
   finite differences are made for it.  Returns 1 if it made the
   matrix. */
int
spvi_borrow (spvi_core *c, const spvi_core *src, sym_eval *ev)
{
  const size_t nn = 2 * (size_t) c->d, nb = nn * nn;
  const int ms = src->m;
  if (src->nae < 1 || src->te[0] != 0.0 || src->he[0] != c->h
      || ms > SYM_SPVI_JX_POINTS)
    return 0;
  double bw[SYM_SPVI_JX_POINTS];
  const double *sp[SYM_SPVI_JX_POINTS];
  sym_bary_weights (ms, src->z, bw);
  for (int j = 0; j < ms; j++)
    sp[j] = src->Ae[0] + (size_t) j * nb;
  interp_A (c, ms, src->z, bw, sp, c->z);
  keep (c);
  if (! refactor (c, ev))
    return 0;
  c->nw.have_matrix = 1;
  return 1;
}
