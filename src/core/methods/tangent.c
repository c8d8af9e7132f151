/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* tangent.c -- the tangent map of explicit steps (sym.h: sym_tangent;
   the steppers' hooks in tangent.h).

   An explicit step is a sequence of kicks p += c f_p(t, q) and drifts q
   += c f_q(t, p).  Its derivative is the product of theirs: a kick maps
   a column [u; v] of Phi to [u; v + c A u], A = d f_p / d q at the
   kick's (t, q), a drift to [u + c B v; v], B = d f_q / d p at its (t,
   p).  Each factor is symplectic when A and B are symmetric (Hessians
   of V and T), so Phi is, to round-off.

   A and B come as blocks of the system's Df (one call gives both; each
   is kept with its (t, q) or (t, p), so that a kick at the point of the
   last one, the FSAL kick of Verlet, costs nothing), else by central
   differences of f in q (or p), which for a smooth f of unit scale are
   good to about 1e-10 relative (steps of cbrt(eps) times the size of
   the half). */
#include "tangent.h"
#include "../numerics/numerics.h"

#include <float.h>
#include <math.h>
#include <string.h>

/* states of one batch of central differences (two for each column) */
#define TG_CHUNK 32

struct sym_tangent_s {
  int d, n, m;
  double *phi, *trial;       /* n*m each: accepted, being stepped */
  double *blk[2];            /* d*d: 0 the kick's A, 1 the drift's B */
  double *key[2];            /* d: the q (A) or p (B) they are at */
  double tkey[2];
  int have[2];
  double *df;                /* n*n, the system's Df (allocated on use) */
  double *y, *f;             /* n each */
  double *ys, *fs, *ts;      /* 2 TG_CHUNK states, their f, their t */
  double *acc;               /* d */
  double *block;
  int have_f;                /* f holds f at (tf, y): the last Df came
                                with it (rhs_jac) */
  double tf;
  int renorm;                /* the column kept at unit norm */
  double logsum;             /* the sum of the logs of its norms */
};

sym_tangent *
sym_tangent_new (int dim, int m, const double *v0)
{
  if (dim < 1 || m < 1 || (! v0 && m != 2 * dim))
    return NULL;
  sym_tangent *tg = sym_calloc (1, sizeof *tg);
  if (! tg)
    return NULL;
  const size_t d = (size_t) dim, n = 2 * d, ch = 2 * TG_CHUNK;
  const size_t len = 2 * n * (size_t) m + 2 * d * d + 2 * d + 2 * n
                     + 2 * ch * n + ch + d;
  tg->block = sym_malloc (len * sizeof (double));
  if (! tg->block)
    {
      sym_free (tg);
      return NULL;
    }
  tg->d = dim;
  tg->n = (int) n;
  tg->m = m;
  double *w = tg->block;
  tg->phi = w; w += n * m;
  tg->trial = w; w += n * m;
  tg->blk[0] = w; w += d * d;
  tg->blk[1] = w; w += d * d;
  tg->key[0] = w; w += d;
  tg->key[1] = w; w += d;
  tg->y = w; w += n;
  tg->f = w; w += n;
  tg->ys = w; w += ch * n;
  tg->fs = w; w += ch * n;
  tg->ts = w; w += ch;
  tg->acc = w;
  if (v0)
    memcpy (tg->phi, v0, n * m * sizeof (double));
  else
    {
      memset (tg->phi, 0, n * n * sizeof (double));
      for (size_t i = 0; i < n; i++)
        tg->phi[i + i * n] = 1.0;
    }
  memcpy (tg->trial, tg->phi, n * m * sizeof (double));
  return tg;
}

void
sym_tangent_free (sym_tangent *tg)
{
  if (! tg)
    return;
  sym_free (tg->df);
  sym_free (tg->block);
  sym_free (tg);
}

const double *
sym_tangent_phi (const sym_tangent *tg)
{
  return tg->phi;
}

int
sym_tangent_columns (const sym_tangent *tg)
{
  return tg->m;
}

int
sym_tangent_fits (const sym_tangent *tg, int dim)
{
  return tg->d == dim;
}

void
sym_tangent_begin (sym_tangent *tg)
{
  memcpy (tg->trial, tg->phi, (size_t) tg->n * tg->m * sizeof (double));
}

int
sym_tangent_renormalise (sym_tangent *tg)
{
  if (tg->m != 1)
    return SYM_EBADINPUT;
  tg->renorm = 1;
  return SYM_SUCCESS;
}

double
sym_tangent_log_growth (const sym_tangent *tg)
{
  return tg->logsum;
}

void
sym_tangent_accept (sym_tangent *tg)
{
  double *w = tg->phi;
  tg->phi = tg->trial;
  tg->trial = w;
  if (! tg->renorm)
    return;
  double s = 0.0;
  for (int i = 0; i < tg->n; i++)
    s = hypot (s, tg->phi[i]);
  /* (a vector that vanished or overflowed is left as it is) */
  if (s > 0.0 && isfinite (s))
    {
      tg->logsum += log (s);
      for (int i = 0; i < tg->n; i++)
        tg->phi[i] /= s;
    }
}

/* both blocks from the system's Df at (t, y), kept with their keys */
static int
blocks_from_df (sym_tangent *tg, sym_eval *ev, double t)
{
  const int d = tg->d, n = tg->n;
  if (! tg->df && ! (tg->df = sym_malloc ((size_t) n * n * sizeof (double))))
    return SYM_ENOMEM;
  /* f and Df in one call when the system has it: the step's own call
     of f at the point is then served from it (sym_fcache_feed) */
  int st = ev->rhs_jac ? sym_rhs_jac (ev, t, tg->y, tg->f, tg->df)
                       : sym_jac (ev, t, tg->y, NULL, tg->df);
  if (st)
    return st;
  tg->have_f = ev->rhs_jac != NULL;
  tg->tf = t;
  for (int j = 0; j < d; j++)
    for (int i = 0; i < d; i++)
      {
        tg->blk[0][i + (size_t) j * d] = tg->df[d + i + (size_t) j * n];
        tg->blk[1][i + (size_t) j * d] = tg->df[i + (size_t) (d + j) * n];
      }
  for (int k = 0; k < 2; k++)
    {
      memcpy (tg->key[k], tg->y + k * d, (size_t) d * sizeof (double));
      tg->tkey[k] = t;
      tg->have[k] = 1;
    }
  return SYM_SUCCESS;
}

/* block k by central differences of f: in q (k = 0, the rows of f_p)
   or in p (k = 1, the rows of f_q), TG_CHUNK columns a batch */
static int
block_by_differences (sym_tangent *tg, sym_eval *ev, double t, int k)
{
  const int d = tg->d, n = tg->n, x0 = k == 0 ? 0 : d, r0 = k == 0 ? d : 0;
  const double rel = cbrt (DBL_EPSILON);
  double big = 0.0;
  for (int i = 0; i < d; i++)
    big = fmax (big, fabs (tg->y[x0 + i]));
  if (big == 0.0)
    big = 1.0;
  double *a = tg->blk[k];
  for (int j0 = 0; j0 < d; j0 += TG_CHUNK)
    {
      const int nc = d - j0 < TG_CHUNK ? d - j0 : TG_CHUNK;
      for (int c = 0; c < 2 * nc; c++)
        {
          const int j = j0 + c / 2;
          double *ys = tg->ys + (size_t) c * n;
          memcpy (ys, tg->y, (size_t) n * sizeof (double));
          const double x = tg->y[x0 + j];
          const double h = rel * fmax (fabs (x), big);
          ys[x0 + j] = c % 2 ? x - h : x + h;
          tg->ts[c] = t;
        }
      const long calls = ev->st.cnt.nrhs;
      int st = sym_rhs_many (ev, 2 * nc, tg->ts, tg->ys, tg->fs);
      ev->st.cnt.nfd += ev->st.cnt.nrhs - calls;
      if (st)
        return st;
      for (int c = 0; c < nc; c++)
        {
          const int j = j0 + c;
          const double *yp = tg->ys + (size_t) 2 * c * n;
          const double *ym = yp + n;
          const double *fp = tg->fs + (size_t) 2 * c * n + r0;
          const double *fm = fp + n;
          /* the steps as the doubles took them */
          const double dx = yp[x0 + j] - ym[x0 + j];
          for (int i = 0; i < d; i++)
            a[i + (size_t) j * d] = (fp[i] - fm[i]) / dx;
        }
    }
  memcpy (tg->key[k], tg->y + x0, (size_t) d * sizeof (double));
  tg->tkey[k] = t;
  tg->have[k] = 1;
  return SYM_SUCCESS;
}

/* block k at (t, [q; p]): kept, from Df, or by differences */
static int
block_at (sym_tangent *tg, sym_eval *ev, double t, const double *q,
          const double *p, int k)
{
  const int d = tg->d;
  const double *x = k == 0 ? q : p;
  if (tg->have[k] && tg->tkey[k] == t && sym_same_vec (d, tg->key[k], x))
    return SYM_SUCCESS;
  memcpy (tg->y, q, (size_t) d * sizeof (double));
  memcpy (tg->y + d, p, (size_t) d * sizeof (double));
  const int df = ev->jac || ev->rhs_jac;
  tg->have_f = 0;
  /* (what is being overwritten is not kept if that fails) */
  tg->have[k] = 0;
  if (df)
    tg->have[1 - k] = 0;
  return df ? blocks_from_df (tg, ev, t)
            : block_by_differences (tg, ev, t, k);
}

const double *
sym_tangent_f (const sym_tangent *tg, double t, const double *q,
               const double *p)
{
  const int d = tg->d;
  return tg->have_f && tg->tf == t && sym_same_vec (d, tg->y, q)
         && sym_same_vec (d, tg->y + d, p) ? tg->f : NULL;
}

/* the rows dst of every column of the trial += c M (its rows src) */
static void
apply (sym_tangent *tg, const double *mat, int src, int dst, double c)
{
  const int d = tg->d, n = tg->n;
  double *acc = tg->acc;
  for (int j = 0; j < tg->m; j++)
    {
      double *col = tg->trial + (size_t) j * n;
      const double *u = col + src;
      double *v = col + dst;
      if (! mat)
        {
          for (int i = 0; i < d; i++)
            v[i] += c * u[i];
          continue;
        }
      memset (acc, 0, (size_t) d * sizeof (double));
      for (int l = 0; l < d; l++)
        {
          const double ul = u[l];
          if (ul == 0.0)
            continue;
          const double *ml = mat + (size_t) l * d;
          for (int i = 0; i < d; i++)
            acc[i] += ml[i] * ul;
        }
      for (int i = 0; i < d; i++)
        v[i] += c * acc[i];
    }
}

int
sym_tangent_kick (sym_tangent *tg, sym_eval *ev, double t, const double *q,
                  const double *p, double c)
{
  int st = block_at (tg, ev, t, q, p, 0);
  if (st)
    return st;
  apply (tg, tg->blk[0], 0, tg->d, c);
  return SYM_SUCCESS;
}

int
sym_tangent_prefetch (sym_tangent *tg, sym_eval *ev, double t,
                      const double *q, const double *p)
{
  return block_at (tg, ev, t, q, p, 1);
}

int
sym_tangent_drift (sym_tangent *tg, sym_eval *ev, double t, const double *q,
                   const double *p, double c, int identity)
{
  if (! identity)
    {
      int st = block_at (tg, ev, t, q, p, 1);
      if (st)
        return st;
    }
  apply (tg, identity ? NULL : tg->blk[1], tg->d, 0, c);
  return SYM_SUCCESS;
}
