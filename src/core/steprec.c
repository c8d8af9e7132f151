/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* steprec.c -- step records, f cache and checked Newton solves shared by
   the symplectic Euler and Stormer-Verlet steppers (see steprec.h). */
#include "steprec.h"

#include <float.h>
#include <math.h>
#include <string.h>

int
sym_same_vec (int n, const double *a, const double *b)
{
  for (int i = 0; i < n; i++)
    if (a[i] != b[i])
      return 0;
  return 1;
}

int
sym_same_time (double a, double b, double h)
{
  return a == b
         || fabs (a - b) <= 4.0 * DBL_EPSILON
                            * fmax (fmax (fabs (a), fabs (b)), fabs (h));
}

double
sym_norm_inf (int n, const double *v)
{
  double m = 0.0;
  for (int i = 0; i < n; i++)
    m = fmax (m, fabs (v[i]));
  return m;
}

void *
sym_onestep_new (const sym_system *sys, size_t size, int *status)
{
  if (! sys || sys->dim < 1 || ! sys->rhs)
    {
      *status = SYM_EBADINPUT;
      return NULL;
    }
  void *s = sym_calloc (1, size);
  if (! s)
    *status = SYM_ENOMEM;
  return s;
}

/* ---------------------------------------------------------------- records */

size_t
sym_recs_len (int n, int naux)
{
  return (size_t) 2 * (4 * (size_t) n + (size_t) naux);
}

void
sym_recs_place (sym_recs *r, int n, int naux, double *w)
{
  memset (r, 0, sizeof (*r));
  r->n = n;
  r->naux = naux;
  for (int k = 0; k < 2; k++)
    {
      r->rec[k].y0 = w; w += n;
      r->rec[k].y1 = w; w += n;
      r->rec[k].f0 = w; w += n;
      r->rec[k].f1 = w; w += n;
      r->rec[k].aux = w; w += naux;
    }
  r->cur = &r->rec[0];
  r->trial = &r->rec[1];
}

int
sym_recs_begin (sym_recs *r, double t, double h, double tend,
                const double *y)
{
  const int n = r->n;
  r->trial_ok = 0;
  sym_rec *tr = r->trial, *cu = r->cur;
  const int cont = r->have_cur && sym_same_time (t, cu->tend, cu->h)
                   && sym_same_vec (n, y, cu->y1);
  if (! (tr->have_f0 && t == tr->t && sym_same_vec (n, y, tr->y0)))
    {
      tr->have_f0 = 0;
      memcpy (tr->y0, y, (size_t) n * sizeof (double));
      if (cont && cu->have_f1)
        {
          memcpy (tr->f0, cu->f1, (size_t) n * sizeof (double));
          tr->have_f0 = 1;
        }
    }
  tr->t = t;
  tr->h = h;
  tr->tend = tend;
  tr->have_f1 = 0;
  return cont;
}

int
sym_recs_f0 (sym_recs *r, sym_system *sys)
{
  sym_rec *tr = r->trial;
  if (tr->have_f0)
    return SYM_SUCCESS;
  int st = sym_rhs (sys, tr->t, tr->y0, tr->f0);
  if (st == SYM_SUCCESS)
    tr->have_f0 = 1;
  return st;
}

int
sym_recs_finish (sym_recs *r, sym_system *sys, int want_f, double *yerr,
                 double *ynext)
{
  const int n = r->n;
  sym_rec *tr = r->trial;
  int st;
  /* a result that overflowed is not evaluated (f there would be called
     with Inf): the driver refuses such a step */
  for (int i = 0; i < n; i++)
    if (! isfinite (tr->y1[i]))
      {
        memcpy (ynext, tr->y1, (size_t) n * sizeof (double));
        for (int k = 0; yerr && k < n; k++)
          yerr[k] = NAN;
        return SYM_SUCCESS;
      }
  if (want_f || yerr)
    {
      if ((st = sym_recs_f0 (r, sys)))
        return st;
      if ((st = sym_rhs (sys, tr->tend, tr->y1, tr->f1)))
        return st;
      tr->have_f1 = 1;
    }
  if (yerr)
    for (int i = 0; i < n; i++)
      yerr[i] = (tr->y1[i] - tr->y0[i])
        - 0.5 * tr->h * (tr->f0[i] + tr->f1[i]);
  memcpy (ynext, tr->y1, (size_t) n * sizeof (double));
  r->trial_ok = 1;
  return SYM_SUCCESS;
}

void
sym_recs_accept (sym_recs *r)
{
  if (! r->trial_ok)   /* nothing to accept */
    return;
  sym_rec *c = r->cur;
  r->cur = r->trial;
  r->trial = c;
  r->have_cur = 1;
  r->trial_ok = 0;
}

int
sym_recs_dense (const sym_recs *r, double t, double *y)
{
  if (! y || ! r->have_cur || ! isfinite (t))
    return SYM_EBADINPUT;
  const sym_rec *c = r->cur;
  const int n = r->n;
  if (t == c->t)
    {
      memcpy (y, c->y0, (size_t) n * sizeof (double));
      return SYM_SUCCESS;
    }
  if (t == c->tend)
    {
      memcpy (y, c->y1, (size_t) n * sizeof (double));
      return SYM_SUCCESS;
    }
  const double th = (t - c->t) / c->h;
  if (c->have_f0 && c->have_f1)
    sym_rec_hermite (c, n, th, y);
  else
    for (int i = 0; i < n; i++)
      y[i] = c->y0[i] + th * (c->y1[i] - c->y0[i]);
  return SYM_SUCCESS;
}

void
sym_hermite (int n, double h, double th, const double *y0, const double *y1,
             const double *f0, const double *f1, double *y)
{
  const double u = 1.0 - th;
  const double a0 = u * u * (1.0 + 2.0 * th), a1 = th * th * (3.0 - 2.0 * th);
  const double b0 = h * th * u * u, b1 = -h * th * th * u;
  for (int i = 0; i < n; i++)
    y[i] = a0 * y0[i] + a1 * y1[i] + b0 * f0[i] + b1 * f1[i];
}

void
sym_rec_hermite (const sym_rec *c, int n, double th, double *y)
{
  sym_hermite (n, c->h, th, c->y0, c->y1, c->f0, c->f1, y);
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

/* the accepted trial's value becomes the newest; a trial that did not
   continue the last accepted step, or had another kind of base, starts
   the history anew */
static void
pred_commit (sym_pred *p)
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

/* the weights at t of the Lagrange polynomial through the times ts[0..m-1]
   (distinct) */
static void
lagrange_weights (int m, const double *ts, double t, double *w)
{
  for (int j = 0; j < m; j++)
    {
      double v = 1.0;
      for (int k = 0; k < m; k++)
        if (k != j)
          v *= (t - ts[k]) / (ts[j] - ts[k]);
      w[j] = v;
    }
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
          lagrange_weights (L + 1, u + 1, u[0], p->wr[L]);
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
      lagrange_weights (best + 1, u, t, p->wf[best]);
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

void
sym_recs_forget (sym_recs *r)
{
  r->have_cur = 0;
  r->trial_ok = 0;
  r->rec[0].have_f0 = r->rec[0].have_f1 = 0;
  r->rec[1].have_f0 = r->rec[1].have_f1 = 0;
}

void
sym_onestep_accept (void *state)
{
  sym_onestep *o = state;
  if (o->r.trial_ok)
    for (int k = 0; k < o->npr; k++)
      pred_commit (&o->pr[k]);
  sym_recs_accept (&o->r);
}

int
sym_onestep_dense (void *state, sym_system *sys, double t, double *y)
{
  (void) sys;
  if (! state)
    return SYM_EBADINPUT;
  return sym_recs_dense (&((sym_onestep *) state)->r, t, y);
}

void
sym_onestep_reset (void *state)
{
  sym_onestep *o = state;
  sym_recs_forget (&o->r);
  o->fc.have_fw = 0;
  for (int k = 0; k < o->npr; k++)
    o->pr[k].n = o->pr[k].have_new = 0;
}

/* ---------------------------------------------------------------- f cache */

size_t
sym_fcache_len (int d, int jac)
{
  const size_t n = 2 * (size_t) d;
  return 3 * n + (jac ? n * n : 0);
}

void
sym_fcache_place (sym_fcache *c, int d, int jac, double *w)
{
  const int n = 2 * d;
  memset (c, 0, sizeof (*c));
  c->d = d;
  c->yw = w; w += n;
  c->fw = w; w += n;
  c->ym = w; w += n;
  c->jw = jac ? w : NULL;
}

int
sym_fcache_f (sym_fcache *c, sym_system *sys, double t, const double *a,
              const double *b)
{
  const int d = c->d;
  if (c->have_fw && c->tw == t && sym_same_vec (d, c->yw, a)
      && sym_same_vec (d, c->yw + d, b))
    return SYM_SUCCESS;
  memcpy (c->yw, a, (size_t) d * sizeof (double));
  memcpy (c->yw + d, b, (size_t) d * sizeof (double));
  c->tw = t;
  c->have_fw = 0;
  int st = sym_rhs (sys, t, c->yw, c->fw);
  if (st == SYM_SUCCESS)
    c->have_fw = 1;
  return st;
}

int
sym_fcache_jac (sym_fcache *c, sym_system *sys, double t, const double *a,
                const double *b)
{
  const int d = c->d;
  int st;
  c->have_jw = 0;
  if (! sys->jac)
    {
      if ((st = sym_fcache_f (c, sys, t, a, b)))
        return st;
      st = sym_jac (sys, t, c->yw, c->fw, c->jw);
    }
  else
    {
      memcpy (c->ym, a, (size_t) d * sizeof (double));
      memcpy (c->ym + d, b, (size_t) d * sizeof (double));
      st = sym_jac (sys, t, c->ym, NULL, c->jw);
    }
  c->have_jw = st == SYM_SUCCESS;
  return st;
}

void
sym_fcache_move (sym_fcache *c, double t, const double *a, const double *b)
{
  const int d = c->d, n = 2 * d;
  if (! c->have_fw || ! c->have_jw || c->tw != t
      || (sym_same_vec (d, c->yw, a) && sym_same_vec (d, c->yw + d, b)))
    return;
  double *dy = c->ym;
  for (int j = 0; j < d; j++)
    {
      dy[j] = a[j] - c->yw[j];
      dy[d + j] = b[j] - c->yw[d + j];
    }
  for (int j = 0; j < n; j++)
    if (dy[j] != 0.0)
      for (int i = 0; i < n; i++)
        c->fw[i] += c->jw[i + (size_t) j * n] * dy[j];
  memcpy (c->yw, a, (size_t) d * sizeof (double));
  memcpy (c->yw + d, b, (size_t) d * sizeof (double));
}

/* ---------------------------------------------------------------- Newton */

void
sym_kept_built (sym_kept *k, double h)
{
  k->h_mat = h;
  k->extra = 0;
}

int
sym_kept_solve (sym_kept *k, const sym_newton_problem *prob,
                sym_system *sys, double h, int d, double sc, double *x,
                double *scale, double *rv)
{
  sym_newton *nw = &k->nw;
  if (nw->have_matrix && fabs (h - k->h_mat) > 0.2 * fabs (k->h_mat))
    sym_newton_invalidate (nw);
  if (! (sc > 0.0))
    sc = 1.0;
  for (int i = 0; i < d; i++)
    scale[i] = sc;
  for (int round = 0; round < 3; round++)
    {
      int st = sym_newton_solve (nw, prob, x, scale, &sys->cnt);
      if (st)
        {
          sym_newton_invalidate (nw);
          return st;
        }
      if (nw->iters > SYM_NW_BASE)
        {
          k->extra += nw->iters - SYM_NW_BASE;
          if (k->extra >= (sys->jac ? 1 : 2 * d))
            sym_newton_invalidate (nw);
        }
      /* the cache holds f at the previous iterate, a round-off step away */
      if (sym_norm_inf (d, nw->dx) <= 4.0 * DBL_EPSILON * sc)
        return SYM_SUCCESS;
      if ((st = prob->residual (prob->ctx, x, rv)))
        return st;
      double rn = sym_norm_inf (d, rv);
      if (rn <= fmax (4.0 * nw->tol, 8.0 * DBL_EPSILON) * sc)
        return SYM_SUCCESS;
      /* the residual is about the next correction: the rate it shows
         replaces the one newton.c trusted */
      double th = rn / fmax (sym_norm_inf (d, nw->dx), DBL_MIN);
      nw->eta = th < 0.5 ? th / (1.0 - th) : 1.0;
    }
  return SYM_SUCCESS;   /* three solves claimed convergence: take it */
}

int
sym_kept_init (sym_kept *k, int d, const sym_method_opts *opts)
{
  if (sym_newton_init (&k->nw, d))
    return SYM_ENOMEM;
  if (opts && opts->newton_tol > 0)
    k->nw.tol = opts->newton_tol;
  if (opts && ! opts->want_error)
    k->nw.tol *= SYM_FIXED_TOL_KEPT;
  if (opts && opts->max_newton > 0)
    k->nw.maxit = opts->max_newton;
  return SYM_SUCCESS;
}

/* ---------------------------------------------------------------- kick */

static int
kick_residual (void *ctx, const double *x, double *r)
{
  const sym_kick *kk = ctx;
  const int d = kk->d;
  int st = sym_fcache_f (kk->fc, kk->sys, kk->t, kk->yk, x);
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
  int st = sym_fcache_jac (kk->fc, kk->sys, kk->t, kk->yk, x);
  if (st)
    return st;
  for (int j = 0; j < d; j++)
    for (int i = 0; i < d; i++)
      a[i + (size_t) j * d] = (i == j ? 1.0 : 0.0)
        - kk->c * kk->fc->jw[(d + i) + (size_t) (d + j) * n];
  sym_kept_built (kk->k, kk->h);
  return SYM_SUCCESS;
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
                sym_system *sys, double h, sym_pred *pr, int cont, double c,
                int kind, const double *base, const double *ref, double *x,
                double *scale, double *rv)
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
          sys->cnt.nrestart += tried;
          memcpy (x, base, (size_t) d * sizeof (double));
        }
      double sc = sym_norm_inf (d, ref);
      for (int i = 0; i < d; i++)
        sc = fmax (sc, fabs (x[i] - ref[i]));
      st = sym_kept_solve (k, prob, sys, h, d, sc, x, scale, rv);
      tried = 1;
    }
  if (! st)
    sym_pred_note (pr, cont, h, c, x, kind, base);
  return st;
}

int
sym_kick_solve (const sym_kick *kk, sym_recs *r, int cont,
                const double *prev, double *x, double *scale, double *rv)
{
  const int d = kk->d;
  const double *p0 = r->trial->y0 + d;
  sym_newton_problem prob = { kick_residual, kick_matrix, (void *) kk };
  double *xb = kk->pr->xb;
  int kind = kick_explicit (kk, r, cont, prev, xb);
  /* f(t_k, y_k) is evaluated when there is no explicit start without it,
     or when its increment and p_k both vanish (no scale for Newton) */
  if (! kind || (kind == 2 && sym_norm_inf (d, p0) == 0.0
                 && sym_norm_inf (d, xb) == 0.0))
    {
      int st = sym_recs_f0 (r, kk->sys);
      if (st)
        return st;
      kind = kick_explicit (kk, r, cont, prev, xb);
    }
  int st = sym_pred_solve (kk->k, &prob, kk->sys, kk->h, kk->pr, cont,
                           kk->c, kind, xb, p0, x, scale, rv);
  /* f at [q_k; P] (moved there if the solve stopped on a round-off
     correction) */
  if (! st)
    sym_fcache_move (kk->fc, kk->t, kk->yk, x);
  return st;
}
