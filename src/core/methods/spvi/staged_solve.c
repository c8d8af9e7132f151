/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* staged_solve.c -- the solves of odeSPVI's Newton systems by the stage
   systems (staged.c describes the method; staged_factor.c makes the
   matrices): the forward transform, one solve a stage system (by its
   Schur complement when separable), the back transform; the fixed point
   for J = 0; exact, the iteration of those solves on Newton's own
   matrix. */
#include "staged.h"

#include <complex.h>
#include <float.h>
#include <math.h>
#include <string.h>

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

/* The fixed point's correction as a map (sym_newton_problem's
   correction): with J = 0, x + M^-1 (-R(x)) is a = (h/2) D^-1 F_q (dinv
   is -D^-1) and P = p_k - (h/2) Wd^-1 G F_p, so the new iterate comes
   from f at the nodes alone, without the residual's linear part. */
int
spvi_fp_correction (void *ctx, const double *x, double *dx)
{
  spvi_core *c = ctx;
  const spvi_stages *g = c->sg;
  const int d = c->d, m = c->m;
  const size_t md = (size_t) m * d, nn = 2 * (size_t) d;
  const double hh = 0.5 * c->h, *pk = c->yk + d;
  int st = spvi_eval (c, x);
  if (st)
    return st;
  for (int j = 0; j < m; j++)
    for (int k = 0; k < d; k++)
      {
        double sa = 0.0, sp = 0.0;
        for (int r = 0; r < m; r++)
          {
            sa += g->dinv[j + r * m] * c->F[(size_t) r * nn + k];
            sp += g->wg[j + r * m] * c->F[(size_t) r * nn + d + k];
          }
        const size_t i = (size_t) j * d + k;
        dx[i] = -hh * sa - x[i];
        dx[md + i] = (pk[k] - hh * sp) - x[md + i];
      }
  return SYM_SUCCESS;
}
