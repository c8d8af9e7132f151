/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* equations.c -- odeSPVI's discrete equations (see spvi.h): the
   precomputed Legendre and quadrature values of one (n, m) pair, the node
   states, the evaluations of f at the nodes, the residual, and the step's
   end from the solution. */
#include "spvi.h"

#include <math.h>
#include <string.h>

void
spvi_core_free (spvi_core *c)
{
  sym_newton_free (&c->nw);
  spvi_stages_free (c);
  double **p[] = { &c->z, &c->w, &c->phi, &c->dl, &c->wdl, &c->g, &c->xb,
                   &c->bw, &c->A, &c->Y, &c->F, &c->tj, &c->xf, &c->x,
                   &c->scale, &c->Fo, &c->xfo, &c->wk, &c->inc, &c->Ae[0],
                   &c->Ae[1] };
  for (size_t i = 0; i < sizeof p / sizeof p[0]; i++)
    {
      sym_free (*p[i]);
      *p[i] = NULL;
    }
}

int
spvi_core_init (spvi_core *c, int d, int n, int m, int stages)
{
  memset (c, 0, sizeof (*c));
  c->n = n;
  c->m = m;
  c->d = d;
  c->N = (n - 1 + m) * d;
  size_t nn = 2 * (size_t) d, nm = (size_t) n * m;
  c->z = sym_calloc (m, sizeof (double));
  c->w = sym_calloc (m, sizeof (double));
  c->phi = sym_calloc (nm, sizeof (double));
  c->dl = sym_calloc (nm, sizeof (double));
  c->wdl = sym_calloc (nm, sizeof (double));
  c->g = sym_calloc (nm, sizeof (double));
  c->xb = sym_calloc (m + 2, sizeof (double));
  c->bw = sym_calloc (m + 2, sizeof (double));
  const size_t na = stages ? 1 : nn * nn * m;   /* node Jacobians */
  c->A = sym_calloc (na, sizeof (double));
  c->Y = sym_calloc (nn * m, sizeof (double));
  c->F = sym_calloc (nn * m, sizeof (double));
  c->tj = sym_calloc (m, sizeof (double));
  c->xf = sym_calloc (c->N, sizeof (double));
  c->Fo = sym_calloc (nn * m, sizeof (double));
  c->xfo = sym_calloc (c->N, sizeof (double));
  c->wk = sym_calloc (nn + d, sizeof (double));
  c->inc = sym_calloc (nn, sizeof (double));
  c->Ae[0] = sym_calloc (na, sizeof (double));
  c->Ae[1] = sym_calloc (na, sizeof (double));
  c->x = sym_calloc (c->N, sizeof (double));
  c->scale = sym_calloc (c->N, sizeof (double));
  double *l = sym_calloc (2 * (size_t) n, sizeof (double));
  int st = SYM_ENOMEM;
  if (! c->z || ! c->w || ! c->phi || ! c->dl || ! c->wdl || ! c->g
      || ! c->xb || ! c->bw || ! c->A || ! c->Y || ! c->F || ! c->tj
      || ! c->xf || ! c->x || ! c->scale || ! l || ! c->Fo
      || ! c->xfo || ! c->wk || ! c->inc || ! c->Ae[0] || ! c->Ae[1])
    goto fail;
  if ((st = sym_newton_init (&c->nw, c->N, NULL))
      || (! stages && (st = sym_newton_lu (&c->nw))))
    goto fail;
  if ((st = sym_gauss_legendre (m, c->z, c->w)))
    goto fail;
  for (int j = 0; j < m; j++)
    {
      sym_legendre (n, c->z[j], l, l + n);
      for (int i = 0; i < n; i++)
        {
          double lm1 = (i % 2) ? -1.0 : 1.0;     /* l_i(-1) */
          c->phi[j * n + i] = l[i] - lm1;
          c->dl[j * n + i] = l[n + i];
          c->wdl[j * n + i] = c->w[j] * l[n + i];
          c->g[j * n + i] = c->w[j] * (l[i] - 1.0);
        }
    }
  c->xb[0] = -1.0;
  for (int j = 0; j < m; j++)
    c->xb[j + 1] = c->z[j];
  c->xb[m + 1] = 1.0;
  sym_bary_weights (m + 2, c->xb, c->bw);
  if (stages && (st = spvi_stages_init (c, stages == SPVI_STAGES_SPARSE)))
    goto fail;
  sym_free (l);
  return SYM_SUCCESS;

fail:
  sym_free (l);
  spvi_core_free (c);
  return st;
}

/* Node states Y_j = [Q_j; P_j] from x. */
void
spvi_states (spvi_core *c, const double *x)
{
  const int d = c->d, n = c->n, m = c->m;
  const double *a = x, *P = x + (size_t) (n - 1) * d;
  for (int j = 0; j < m; j++)
    {
      double *yj = c->Y + (size_t) j * 2 * d;
      const double *phij = c->phi + (size_t) j * n;
      for (int k = 0; k < d; k++)
        {
          double s = 0.0;
          for (int i = 1; i < n; i++)
            s += phij[i] * a[(size_t) (i - 1) * d + k];
          yj[k] = c->yk[k] + s;
          yj[d + k] = P[(size_t) j * d + k];
        }
    }
}

/* Before a new evaluation at x: the last one becomes the one before it
   (Fo at xfo), and the size of the move between them is kept in dxn while
   fewer than two are. */
void
spvi_eval_shift (spvi_core *c, const double *x)
{
  c->fovalid = c->fvalid;
  if (c->fvalid)
    {
      double *tmp = c->Fo;
      c->Fo = c->F;
      c->F = tmp;
      tmp = c->xfo;
      c->xfo = c->xf;
      c->xf = tmp;
      if (c->ndx < 2)
        {
          double v = 0.0;
          for (int i = 0; i < c->N; i++)
            v = sym_fmax_acc (v, fabs (x[i] - c->xfo[i]));
          c->dxn[c->ndx++] = v;
        }
    }
  c->fvalid = 0;
}

/* F = f at the nodes of x (one batch call), cached by x.  The evaluation
   before it in the same solve is kept in Fo (at xfo), and the sizes of the
   first two moves between evaluations (the first two corrections) in
   dxn. */
int
spvi_eval (spvi_core *c, const double *x)
{
  size_t nb = (size_t) c->N * sizeof (double);
  if (c->fvalid && memcmp (c->xf, x, nb) == 0)
    return SYM_SUCCESS;
  spvi_eval_shift (c, x);
  spvi_states (c, x);
  int st = sym_rhs_many (c->ev, c->m, c->tj, c->Y, c->F);
  if (st)
    return st;
  memcpy (c->xf, x, nb);
  c->fvalid = 1;
  return SYM_SUCCESS;
}

int
spvi_residual (void *ctx, const double *x, double *r)
{
  spvi_core *c = ctx;
  const int d = c->d, n = c->n, m = c->m, nn = 2 * d;
  const double *a = x, *P = x + (size_t) (n - 1) * d, *pk = c->yk + d;
  const double hh = 0.5 * c->h;
  int st = spvi_eval (c, x);
  if (st)
    return st;
  for (int s = 1; s < n; s++)
    for (int k = 0; k < d; k++)
      {
        double s1 = 0.0, s2 = 0.0;
        for (int j = 0; j < m; j++)
          {
            s1 += c->wdl[j * n + s] * (P[(size_t) j * d + k] - pk[k]);
            s2 += c->g[j * n + s] * c->F[(size_t) j * nn + d + k];
          }
        r[(size_t) (s - 1) * d + k] = s1 + hh * s2;
      }
  double *r2 = r + (size_t) (n - 1) * d;
  for (int j = 0; j < m; j++)
    for (int k = 0; k < d; k++)
      {
        double s1 = 0.0;
        for (int i = 1; i < n; i++)
          s1 += c->dl[j * n + i] * a[(size_t) (i - 1) * d + k];
        r2[(size_t) j * d + k] = hh * c->F[(size_t) j * nn + k] - s1;
      }
  return SYM_SUCCESS;
}

/* F is at xf, the iterate before the last correction (c->x): f_p +=
   Apq dQ + App dP by the node Jacobians of the matrix (solve.c checks
   the error of this move), then q_{k+1} and p_{k+1} */
void
spvi_end (spvi_core *c, double *yend)
{
  const int d = c->d, n = c->n, m = c->m;
  const size_t nn = 2 * (size_t) d;
  const double hh = 0.5 * c->h;
  const double *yk = c->yk;
  const double *a = c->x, *P = c->x + (size_t) (n - 1) * d;
  /* the fixed point's J is 0: no move */
  for (int j = 0; j < m && ! c->fp; j++)
    {
      double *Fj = c->F + (size_t) j * nn;
      double *dy = c->Y + (size_t) j * nn;      /* work */
      for (int k = 0; k < d; k++)
        {
          double v = 0.0;
          for (int i = 1; i < n; i++)
            v += c->phi[j * n + i] * (a[(size_t) (i - 1) * d + k]
                                      - c->xf[(size_t) (i - 1) * d + k]);
          dy[k] = v;
          dy[d + k] = P[(size_t) j * d + k]
                      - c->xf[(size_t) (n - 1) * d + (size_t) j * d + k];
        }
      spvi_jac_p (c, j, dy, c->wk);
      for (int k = 0; k < d; k++)
        Fj[d + k] += c->wk[k];
    }
  c->fvalid = 0;   /* F no longer matches xf */

  for (int k = 0; k < d; k++)
    {
      double dqk = 0.0, dpk = 0.0;
      for (int i = 1; i < n; i += 2)
        dqk += 2.0 * a[(size_t) (i - 1) * d + k];
      for (int j = 0; j < m; j++)
        dpk += c->w[j] * c->F[(size_t) j * nn + d + k];
      c->inc[k] = dqk;
      c->inc[d + k] = hh * dpk;
      yend[k] = yk[k] + dqk;
      yend[d + k] = yk[d + k] + c->inc[d + k];
    }
}
