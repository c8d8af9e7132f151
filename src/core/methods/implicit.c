/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* implicit.c -- the implicit solves of the symplectic Euler and
   Stormer-Verlet steppers: Newton with a kept matrix, started from the
   history of the unknowns (see onestep.h). */
#include "onestep.h"

#include <float.h>
#include <math.h>
#include <string.h>

/* ----------------------------------------------------------------- state */

void *
sym_onestep_alloc (int dim, int order, size_t size, int npr, int naux,
                   size_t nown, const sym_method_opts *opts, int *status,
                   double **own)
{
  int dummy;
  if (! status)
    status = &dummy;
  sym_onestep *o = sym_onestep_new (dim, order, size, opts, status);
  if (! o)
    return NULL;
  const int d = dim, n = 2 * d;
  /* the separable step is explicit: no Df and no Newton state (O(d^2)
     memory) */
  const int implicit = ! o->separable;
  const int jac = implicit && ! o->sparse;
  size_t len = sym_recs_len (n, naux) + sym_fcache_len (d, jac) + nown
               + (implicit ? (size_t) npr * sym_pred_len (d) : 0);
  o->block = sym_calloc (len, sizeof (double));
  int ok = o->block && ! (implicit && sym_onestep_implicit (o, npr, d, opts));
  double *w = o->block;
  if (ok)
    {
      sym_recs_place (&o->r, n, naux, w);
      w += sym_recs_len (n, naux);
      ok = ! sym_onestep_fcache (o, implicit, w);
    }
  if (! ok)
    {
      sym_onestep_free (o);
      *status = SYM_ENOMEM;
      return NULL;
    }
  w += sym_fcache_len (d, jac);
  *own = w;
  w += nown;
  for (int k = 0; implicit && k < npr; k++)
    sym_pred_place (&o->pr[k], d, w + (size_t) k * sym_pred_len (d));
  *status = SYM_SUCCESS;
  return o;
}

/* ------------------------------------------------------------- predictor */

size_t
sym_pred_len (int d)
{
  return (SYM_PRED_MAX + 2) * (size_t) d;
}

void
sym_pred_place (sym_pred *p, int d, double *w)
{
  memset (p, 0, sizeof (*p));
  p->d = d;
  p->x = w;
  p->xnew = w + SYM_PRED_MAX * (size_t) d;
  p->xb = p->xnew + d;
}

void
sym_pred_note (sym_pred *p, int cont, double h, double c, const double *x,
               int kind, const double *base)
{
  const double h2 = h * h;
  for (int i = 0; i < p->d; i++)
    p->xnew[i] = (x[i] - base[i]) / h2;
  p->hnew = h;
  p->cnew = c;
  p->new_cont = cont;
  p->new_kind = kind;
  p->have_new = 1;
}

void
sym_pred_commit (sym_pred *p)
{
  const int d = p->d;
  if (! p->have_new || ! p->new_cont || p->new_kind != p->kind)
    p->n = 0;
  if (! p->have_new)
    return;
  int keep = p->n < SYM_PRED_MAX ? p->n : SYM_PRED_MAX - 1;
  memmove (p->x + d, p->x, (size_t) keep * d * sizeof (double));
  memmove (p->hs + 1, p->hs, (size_t) keep * sizeof (double));
  memmove (p->cs + 1, p->cs, (size_t) keep * sizeof (double));
  memcpy (p->x, p->xnew, (size_t) d * sizeof (double));
  p->hs[0] = p->hnew;
  p->cs[0] = p->cnew;
  p->n = keep + 1;
  p->kind = p->new_kind;
  p->have_new = 0;
}

int
sym_pred_start (sym_pred *p, double h, double c, int kind,
                const double *base, double *x)
{
  const int n = p->n, d = p->d;
  if (kind != p->kind || n < 2)
    return 0;
  /* the times of the values from the start of the newest one's step, and
     of the new unknown */
  double u[SYM_PRED_MAX], s = 0.0;
  u[0] = p->cs[0];
  for (int k = 1; k < n; k++)
    {
      s -= p->hs[k];
      u[k] = s + p->cs[k];
    }
  const double t = p->hs[0] + c;
  /* ahead of the newest value by at most twice the last spacing */
  const double ratio = (t - u[0]) / (u[0] - u[1]);
  if (! (ratio > 0.0 && ratio <= 2.0))
    return 0;
  const int Lmax = n - 2 < SYM_PRED_MAX - 2 ? n - 2 : SYM_PRED_MAX - 2;
  if (! (p->wn == n && p->wt == t
         && memcmp (p->wu, u, (size_t) n * sizeof (double)) == 0))
    {
      for (int L = 0; L <= Lmax; L++)
        {
          sym_lagrange_weights (L + 1, u + 1, u[0], p->wr[L]);
          p->wf_ok[L] = 0;
        }
      memcpy (p->wu, u, (size_t) n * sizeof (double));
      p->wn = n;
      p->wt = t;
    }
  /* L = -1: the base alone (no history term) */
  int best = -1;
  double beste = INFINITY;
  for (int L = -1; L <= Lmax; L++)
    {
      /* the newest error from the L + 1 before it */
      const double *w = L >= 0 ? p->wr[L] : NULL;
      double e = 0.0;
      for (int i = 0; i < d; i++)
        {
          double v = p->x[i];
          for (int j = 0; j <= L; j++)
            v -= w[j] * p->x[(size_t) (j + 1) * d + i];
          e = fmax (e, fabs (v));
        }
      if (e < beste)
        {
          beste = e;
          best = L;
        }
    }
  if (best < 0)   /* the base alone: the caller's start */
    return 0;
  const double *w = p->wf[best];
  if (! p->wf_ok[best])
    {
      sym_lagrange_weights (best + 1, u, t, p->wf[best]);
      p->wf_ok[best] = 1;
    }
  for (int i = 0; i < d; i++)
    {
      double v = 0.0;
      for (int j = 0; j <= best; j++)
        v += w[j] * p->x[(size_t) j * d + i];
      x[i] = base[i] + h * h * v;
    }
  return 1;
}

/* ---------------------------------------------------------------- Newton */

void
sym_kept_built (sym_kept *k, double h)
{
  k->h_mat = h;
  k->extra = 0;
}

/* the iterations of the last solve beyond SYM_NW_BASE, charged to the
   kept matrix: a new one when they have cost as much as a Jacobian */
static void
kept_charge (sym_kept *k, const sym_eval *ev)
{
  sym_newton *nw = &k->nw;
  if (nw->iters > SYM_NW_BASE)
    {
      k->extra += nw->iters - SYM_NW_BASE;
      if (k->extra >= sym_jac_cost (ev))
        sym_newton_invalidate (nw);
    }
}

/* The scale of Newton's test at x: the max norm of ref or of x's
   distance to it, whichever is larger, into scale[0..d-1].  No scale: 1;
   a subnormal one: the least normal number, so that the corrections of
   subnormal data are measured against their quantum. */
static double
kept_scale (int d, const double *ref, const double *x, double *scale)
{
  double sc = sym_norm_inf (d, ref);
  for (int i = 0; i < d; i++)
    sc = fmax (sc, fabs (x[i] - ref[i]));
  sc = sc > 0.0 ? fmax (sc, DBL_MIN) : 1.0;
  for (int i = 0; i < d; i++)
    scale[i] = sc;
  return sc;
}

int
sym_kept_solve (sym_kept *k, const sym_newton_problem *prob,
                sym_eval *ev, double h, int d, const double *ref, double *x,
                double *scale)
{
  sym_newton *nw = &k->nw;
  if (nw->have_matrix && fabs (h - k->h_mat) > SYM_REBUILD_H * fabs (k->h_mat))
    sym_newton_invalidate (nw);
  kept_scale (d, ref, x, scale);
  for (int round = 0; round < SYM_KEPT_ROUNDS; round++)
    {
      int st = sym_newton_solve (nw, prob, x, scale, &ev->st.cnt);
      if (st)
        {
          sym_newton_invalidate (nw);
          return st;
        }
      /* The test is relative to the scale of the result, not of the
         start (a far start would loosen it).  The last correction in
         that scale; the cache holds f at the iterate before it, a
         round-off step away when it is below ROUNDOFF */
      const double sc = kept_scale (d, ref, x, scale);
      const double last = sym_norm_inf (d, nw->dx) / sc;
      if (last <= SYM_KEPT_ROUNDOFF * DBL_EPSILON)
        {
          kept_charge (k, ev);
          return SYM_SUCCESS;
        }
      /* The next correction with the same matrix (it leaves f at x in
         the cache) shows the rate th, and the error of x, |dx| / (1 -
         th), is newton.c's estimate with that rate: x is taken only when
         it is below tol (round-off: SYM_KEPT_CHECK_ULPS) */
      double dn;
      if ((st = sym_newton_dx (nw, prob, x, scale, &ev->st.cnt, &dn)))
        {
          sym_newton_invalidate (nw);
          return st;
        }
      const double th = dn / fmax (last, DBL_MIN);
      kept_charge (k, ev);
      if (dn <= SYM_KEPT_CHECK_ULPS * DBL_EPSILON
          || (th < 1.0 && dn <= (1.0 - th) * nw->tol))
        return SYM_SUCCESS;
      if (! isfinite (dn))
        break;
      /* not converged: the correction is taken, and the rate it shows
         replaces the one newton.c trusted */
      sym_newton_apply (nw, x, &ev->st.cnt);
      nw->eta = th < SYM_KEPT_RATE_MAX ? th / (1.0 - th) : 1.0;
    }
  /* no solve reached tol: a failure (the caller tries another start, a
     smaller step, or ends the run), not an unconverged result */
  ev->st.cnt.nnewton_fail++;
  sym_newton_invalidate (nw);
  return SYM_NEWTON_FAIL;
}

int
sym_kept_init (sym_kept *k, int d, const sym_method_opts *opts, int sparse)
{
  k->sparse = sparse;
  if (sym_newton_init (&k->nw, d, opts)
      || (sparse ? sym_stage_lu_init (&k->slu, d, 1)
                   || sym_csc_init (&k->blk, d, 0)
                 : sym_newton_lu (&k->nw)))
    return SYM_ENOMEM;
  k->tol = k->nw.tol;
  k->nw.tol *= SYM_FIXED_TOL_KEPT;
  return SYM_SUCCESS;
}

void
sym_kept_free (sym_kept *k)
{
  sym_newton_free (&k->nw);
  sym_stage_lu_free (&k->slu);
  sym_csc_free (&k->blk);
}

int
sym_kept_factor (sym_kept *k, const sym_fcache *fc, int r0, double c,
                 double h, sym_counters *cnt)
{
  int st = sym_csc_block (&fc->js, r0, r0, fc->d, &k->blk);
  if (! st)
    st = sym_stage_lu_factor (&k->slu, c, 0.0, NULL, 0, &k->blk, cnt);
  if (! st)
    sym_kept_built (k, h);
  return st;
}

/* the solve with sym_kept_factor's LU (a problem's solve; ctx: the
   sym_kept) */
static int
kept_lsolve (sym_kept *k, double *b, sym_counters *cnt)
{
  return sym_stage_lu_solve (&k->slu, b, cnt);
}

void
sym_kept_adaptive (sym_kept *k)
{
  k->nw.tol = k->tol;
}

/* ---------------------------------------------------------------- kick */

static int
kick_residual (void *ctx, const double *x, double *r)
{
  const sym_kick *kk = ctx;
  const int d = kk->d;
  int st = sym_fcache_f (kk->fc, kk->ev, kk->t, kk->yk, x);
  if (st)
    return st;
  for (int i = 0; i < d; i++)
    r[i] = x[i] - kk->yk[d + i] - kk->c * kk->fc->fw[d + i];
  return SYM_SUCCESS;
}

static int
kick_matrix (void *ctx, const double *x, double *a)
{
  const sym_kick *kk = ctx;
  const int d = kk->d, n = 2 * d;
  int st = sym_fcache_jac (kk->fc, kk->ev, kk->t, kk->yk, x);
  if (st)
    return st;
  for (int j = 0; j < d; j++)
    for (int i = 0; i < d; i++)
      a[i + (size_t) j * d] = (i == j ? 1.0 : 0.0)
        - kk->c * kk->fc->jw[(d + i) + (size_t) (d + j) * n];
  sym_kept_built (kk->k, kk->h);
  return SYM_SUCCESS;
}

/* the sparse kick matrix I - c A_pp (a problem's factor and solve) */
static int
kick_factor (void *ctx, const double *x, sym_counters *cnt)
{
  const sym_kick *kk = ctx;
  int st = sym_fcache_jac (kk->fc, kk->ev, kk->t, kk->yk, x);
  return st ? st : sym_kept_factor (kk->k, kk->fc, kk->d, kk->c, kk->h, cnt);
}

static int
kick_lsolve (void *ctx, double *b, sym_counters *cnt)
{
  return kept_lsolve (((const sym_kick *) ctx)->k, b, cnt);
}

/* The kick's explicit start into xb: p_k + c f_p(t_k, y_k) when f there
   is known (returns 1); else, when the trial continues the last accepted
   step, that step's matching increment (p_k - prev), rescaled to this h
   (returns 2: SE's p_k + h f_p(t_{k-1}, q_{k-1}, p_k), SV's p_k + (h/2)
   f_p(t_k, q_k, p_{k-1/2}), which is exact for a separable H); else 0. */
static int
kick_explicit (const sym_kick *kk, const sym_recs *r, int cont,
               const double *prev, double *xb)
{
  const int d = kk->d;
  const sym_rec *tr = r->trial, *cu = r->cur;
  const double *p0 = tr->y0 + d;
  if (tr->have_f0)
    {
      for (int i = 0; i < d; i++)
        xb[i] = p0[i] + kk->c * tr->f0[d + i];
      return 1;
    }
  if (! cont)
    return 0;
  for (int i = 0; i < d; i++)
    xb[i] = p0[i] + (p0[i] - prev[i]) * (kk->h / cu->h);
  return 2;
}

int
sym_pred_solve (sym_kept *k, const sym_newton_problem *prob,
                sym_eval *ev, double h, sym_pred *pr, int cont, double c,
                int kind, const double *base, const double *ref, double *x,
                double *scale)
{
  const int d = pr->d;
  int st = SYM_NEWTON_FAIL, tried = 0;
  for (int from_pred = cont; st > 0 && from_pred >= 0; from_pred--)
    {
      if (from_pred && ! sym_pred_start (pr, h, c, kind, base, x))
        continue;
      if (! from_pred)
        {
          /* no history, or a recoverable failure from its start (Newton's,
             or fcn's at a start off the solution) */
          ev->st.cnt.nrestart += tried;
          memcpy (x, base, (size_t) d * sizeof (double));
        }
      st = sym_kept_solve (k, prob, ev, h, d, ref, x, scale);
      tried = 1;
    }
  if (! st)
    sym_pred_note (pr, cont, h, c, x, kind, base);
  return st;
}

int
sym_kick_solve (const sym_kick *kk, sym_recs *r, int cont,
                const double *prev, double *x, double *scale)
{
  const int d = kk->d;
  const double *p0 = r->trial->y0 + d;
  sym_newton_problem prob = { kick_residual, kick_matrix, (void *) kk,
                              kk->k->sparse ? kick_factor : NULL,
                              kk->k->sparse ? kick_lsolve : NULL, NULL };
  double *xb = kk->pr->xb;
  int kind = kick_explicit (kk, r, cont, prev, xb);
  /* f(t_k, y_k) is evaluated when there is no explicit start without it,
     or when its increment and p_k both vanish (no scale for Newton) */
  if (! kind || (kind == 2 && sym_norm_inf (d, p0) == 0.0
                 && sym_norm_inf (d, xb) == 0.0))
    {
      int st = sym_recs_f0 (r, kk->ev);
      if (st)
        return st;
      kind = kick_explicit (kk, r, cont, prev, xb);
    }
  int st = sym_pred_solve (kk->k, &prob, kk->ev, kk->h, kk->pr, cont,
                           kk->c, kind, xb, p0, x, scale);
  /* f at [q_k; P] (moved there if the solve stopped on a round-off
     correction) */
  if (! st)
    sym_fcache_move (kk->fc, kk->t, kk->yk, x);
  return st;
}
