/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* onestep.c -- step records, their dense output, and the f cache shared
   by the symplectic Euler and Stormer-Verlet steppers (see onestep.h). */
#include "onestep.h"

#include <float.h>
#include <math.h>
#include <string.h>

void *
sym_onestep_new (int dim, int order, size_t size,
                 const sym_method_opts *opts, int *status)
{
  if (dim < 1)
    {
      *status = SYM_EBADINPUT;
      return NULL;
    }
  sym_onestep *o = sym_calloc (1, size);
  if (! o)
    {
      *status = SYM_ENOMEM;
      return NULL;
    }
  const sym_onestep_opts *own = opts ? opts->own : NULL;
  /* the tangent map of explicit steps only */
  if (own && own->tangent
      && ((! own->separable && ! own->second_order)
          || ! sym_tangent_fits (own->tangent, dim)))
    {
      sym_free (o);
      *status = SYM_EBADINPUT;
      return NULL;
    }
  o->tg = own ? own->tangent : NULL;
  o->d = dim;
  o->n = 2 * dim;
  o->order = order;
  o->second_order = own && own->second_order;
  o->separable = o->second_order || (own && own->separable);
  o->want_f = opts && opts->want_dense;
  o->sparse = own && own->sparse && ! o->separable;
  return o;
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
sym_recs_f0 (sym_recs *r, sym_eval *ev)
{
  sym_rec *tr = r->trial;
  return sym_rhs_once (ev, tr->t, tr->y0, tr->f0, &tr->have_f0);
}

int
sym_recs_finish (sym_recs *r, sym_eval *ev, int want_f, double *yerr,
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
      if ((st = sym_recs_f0 (r, ev)))
        return st;
      if ((st = sym_rhs_once (ev, tr->tend, tr->y1, tr->f1, &tr->have_f1)))
        return st;
    }
  if (yerr)
    for (int i = 0; i < n; i++)
      yerr[i] = (tr->y1[i] - tr->y0[i])
        - 0.5 * tr->h * (tr->f0[i] + tr->f1[i]);
  memcpy (ynext, tr->y1, (size_t) n * sizeof (double));
  r->trial_ok = 1;
  return SYM_SUCCESS;
}

static void
recs_accept (sym_recs *r)
{
  if (! r->trial_ok)   /* nothing to accept */
    return;
  sym_rec *c = r->cur;
  r->cur = r->trial;
  r->trial = c;
  r->have_cur = 1;
  r->trial_ok = 0;
}

static int
recs_dense (const sym_recs *r, double t, double *y)
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

int
sym_onestep_end_f (void *state, sym_eval *ev, double *f)
{
  sym_recs *r = &((sym_onestep *) state)->r;
  sym_rec *c = r->cur;
  if (! r->have_cur)
    return SYM_EBADINPUT;
  int st = sym_rhs_once (ev, c->tend, c->y1, c->f1, &c->have_f1);
  if (st == SYM_SUCCESS)
    memcpy (f, c->f1, (size_t) r->n * sizeof (double));
  return st;
}

void
sym_rec_hermite (const sym_rec *c, int n, double th, double *y)
{
  sym_hermite (n, c->h, th, c->y0, c->y1, c->f0, c->f1, y);
}

void
sym_onestep_accept (void *state)
{
  sym_onestep *o = state;
  if (o->r.trial_ok)
    for (int k = 0; k < o->npr; k++)
      sym_pred_commit (&o->pr[k]);
  if (o->r.trial_ok && o->tg)
    sym_tangent_accept (o->tg);
  recs_accept (&o->r);
}

int
sym_onestep_dense (void *state, sym_eval *ev, double t, double *y)
{
  (void) ev;
  if (! state)
    return SYM_EBADINPUT;
  return recs_dense (&((sym_onestep *) state)->r, t, y);
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
sym_onestep_fcache (sym_onestep *o, int implicit, double *w)
{
  sym_fcache_place (&o->fc, o->d, implicit && ! o->sparse, w);
  o->fc.sparse = o->sparse;
  return o->sparse && sym_csc_init (&o->fc.js, o->n, 0) ? SYM_ENOMEM
                                                        : SYM_SUCCESS;
}

int
sym_fcache_f (sym_fcache *c, sym_eval *ev, double t, const double *a,
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
  int st = sym_rhs (ev, t, c->yw, c->fw);
  if (st == SYM_SUCCESS)
    c->have_fw = 1;
  return st;
}

void
sym_fcache_feed (sym_fcache *c, const sym_tangent *tg, double t,
                 const double *a, const double *b)
{
  const double *f = tg ? sym_tangent_f (tg, t, a, b) : NULL;
  if (! f)
    return;
  const int d = c->d;
  memcpy (c->yw, a, (size_t) d * sizeof (double));
  memcpy (c->yw + d, b, (size_t) d * sizeof (double));
  memcpy (c->fw, f, 2 * (size_t) d * sizeof (double));
  c->tw = t;
  c->have_fw = 1;
}

int
sym_fcache_jac (sym_fcache *c, sym_eval *ev, double t, const double *a,
                const double *b)
{
  const int d = c->d;
  int st;
  c->have_jw = 0;
  if (c->sparse)
    {
      if ((st = sym_fcache_f (c, ev, t, a, b)))
        return st;
      st = sym_jac_csc (ev, t, c->yw, c->fw, &c->js);
    }
  else if (! ev->jac)
    {
      if ((st = sym_fcache_f (c, ev, t, a, b)))
        return st;
      st = sym_jac (ev, t, c->yw, c->fw, c->jw);
    }
  else
    {
      memcpy (c->ym, a, (size_t) d * sizeof (double));
      memcpy (c->ym + d, b, (size_t) d * sizeof (double));
      st = sym_jac (ev, t, c->ym, NULL, c->jw);
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
  if (c->sparse)
    for (int j = 0; j < n; j++)
      for (int e = c->js.colptr[j]; e < c->js.colptr[j + 1]; e++)
        c->fw[c->js.rowind[e]] += c->js.val[e] * dy[j];
  else
    for (int j = 0; j < n; j++)
      if (dy[j] != 0.0)
        for (int i = 0; i < n; i++)
          c->fw[i] += c->jw[i + (size_t) j * n] * dy[j];
  memcpy (c->yw, a, (size_t) d * sizeof (double));
  memcpy (c->yw + d, b, (size_t) d * sizeof (double));
}


int
sym_onestep_implicit (sym_onestep *o, int npr, int d,
                      const sym_method_opts *opts)
{
  o->npr = npr;
  for (int k = 0; k < npr; k++)
    if (sym_kept_init (&o->k[k], d, opts, o->sparse))
      return SYM_ENOMEM;
  return SYM_SUCCESS;
}

void
sym_onestep_free (void *state)
{
  sym_onestep *o = state;
  if (! o)
    return;
  /* safe on a zeroed struct too */
  for (int k = 1; k >= 0; k--)
    sym_kept_free (&o->k[k]);
  sym_csc_free (&o->fc.js);
  sym_free (o->block);
  sym_free (o);
}

int
sym_onestep_begin (sym_onestep *o, const sym_eval *ev, double t, double h,
                   double tend, const double *y, const double *ynext,
                   int *cont)
{
  if (! o || ! ev || ! y || ! ynext || ! isfinite (t) || ! isfinite (h)
      || ! isfinite (tend) || h == 0.0)
    return SYM_EBADINPUT;
  *cont = sym_recs_begin (&o->r, t, h, tend, y);
  if (o->tg)
    sym_tangent_begin (o->tg);
  return SYM_SUCCESS;
}

int
sym_onestep_trial (sym_onestep *o, const sym_eval *ev, double t, double h,
                   double tend, const double *y, const double *ynext,
                   sym_trial *v)
{
  int st = sym_onestep_begin (o, ev, t, h, tend, y, ynext, &v->cont);
  if (st)
    return st;
  const int d = o->d;
  v->d = d;
  v->tr = o->r.trial;
  v->cu = o->r.cur;
  v->q0 = v->tr->y0;
  v->p0 = v->tr->y0 + d;
  v->q1 = v->tr->y1;
  v->p1 = v->tr->y1 + d;
  return SYM_SUCCESS;
}

int
sym_onestep_order (const void *state, int *est)
{
  const sym_onestep *o = state;
  if (est)
    *est = o->order;
  return o->order;
}

/* adaptive steps: f at both ends of every step, Newton to its tolerance */
int
sym_onestep_set_tolerances (void *state, const sym_tolerances *tol)
{
  sym_onestep *o = state;
  (void) tol;
  /* the tangent map is of fixed steps (an adaptive run's rejected
     trials and the step size's dependence on y are not carried) */
  if (o->tg)
    return SYM_EBADINPUT;
  o->want_f = 1;
  for (int k = 0; k < o->npr; k++)
    sym_kept_adaptive (&o->k[k]);
  return SYM_SUCCESS;
}

/* events are sampled at the step points only: short steps of low order */
int
sym_onestep_dense_samples (const void *state)
{
  (void) state;
  return 0;
}

/* the cubic Hermite interpolant of the step's ends */
int
sym_onestep_dense_degree (const void *state)
{
  (void) state;
  return 3;
}
