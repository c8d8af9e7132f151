/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* driver_util.c -- the test steppers, system and sinks of the driver's
   tests (driver_util.h). */
#include "driver_util.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

drv_sink SINK;
double drv_h_least = INFINITY, drv_h_most = 0;

int
drv_ho_rhs (double t, const double *y, double *dy, void *u)
{
  drv_ho_user *hu = u;
  hu->calls++;
  if (hu->fatal_at && hu->calls == hu->fatal_at)
    return -1;
  if (hu->smaller_from && hu->calls >= hu->smaller_from)
    return 1;
  dy[0] = y[1];
  dy[1] = -y[0];
  if (t > hu->nan_after)
    dy[0] = NAN;
  return 0;
}

/* ------------------------------------------------------------ exact */
typedef struct {
  double t, h, y[2];      /* current accepted step start */
  double tt, th, ty[2];   /* trial */
  int samples;
} exact_state;

static void *
ex_alloc (int dim, const sym_method_opts *o, int *st)
{
  (void) dim;
  exact_state *e = sym_calloc (1, sizeof *e);
  *st = e ? 0 : SYM_ENOMEM;
  if (e && o && o->own)
    e->samples = *(const int *) o->own;
  return e;
}

static int
ex_order (const void *st, int *est)
{
  (void) st;
  if (est)
    *est = 2;
  return 99;
}

static int
no_tolerances (void *st, const sym_tolerances *tol)
{
  (void) st;
  (void) tol;
  return 0;
}

static int
ex_step (void *st, sym_eval *ev, double t, double h, double tend,
         const double *y, double *yn, double *yerr)
{
  exact_state *e = st;
  double dy[2];
  int s = sym_rhs (ev, tend, y, dy);   /* to count calls and see NaNs */
  drv_h_least = fmin (drv_h_least, h);
  drv_h_most = fmax (drv_h_most, h);
  if (s)
    return s;
  yn[0] = cos (h) * y[0] + sin (h) * y[1];
  yn[1] = -sin (h) * y[0] + cos (h) * y[1];
  if (yerr)
    yerr[0] = yerr[1] = 1e-3 * h * h * h;   /* a smooth pretend error */
  e->tt = t;
  e->th = h;
  e->ty[0] = y[0];
  e->ty[1] = y[1];
  return 0;
}

static void
ex_accept (void *st)
{
  exact_state *e = st;
  e->t = e->tt;
  e->h = e->th;
  memcpy (e->y, e->ty, sizeof e->y);
}

static int
ex_dense (void *st, sym_eval *ev, double t, double *y)
{
  (void) ev;
  exact_state *e = st;
  double s = t - e->t;
  y[0] = cos (s) * e->y[0] + sin (s) * e->y[1];
  y[1] = -sin (s) * e->y[0] + cos (s) * e->y[1];
  return 0;
}

static int
ex_samples (const void *st)
{
  return ((const exact_state *) st)->samples;
}

static void ex_free (void *st) { sym_free (st); }

/* the exact flow, sampled as a polynomial of this degree */
static int ex_degree (const void *st) { (void) st; return 12; }

const sym_stepper_type drv_exact_type = {
  "exact", ex_alloc, ex_order, no_tolerances, ex_step, ex_accept, ex_dense,
  ex_samples, ex_degree, ex_free, NULL
};

/* ------------------------------------------------------------ midpoint */
typedef struct {
  double t, h, y0[2], y1[2], f0[2], f1[2];
  double tt, th, ty0[2], ty1[2], tf0[2], tf1[2];
} mid_state;

static int
mid_step (void *st, sym_eval *ev, double t, double h, double tend,
          const double *y, double *yn, double *yerr)
{
  mid_state *m = st;
  double f0[2], ym[2], fm[2], f1[2];
  int s = sym_rhs (ev, t, y, f0);
  if (s)
    return s;
  for (int i = 0; i < 2; i++)
    ym[i] = y[i] + 0.5 * h * f0[i];
  if ((s = sym_rhs (ev, t + 0.5 * h, ym, fm)))
    return s;
  for (int i = 0; i < 2; i++)
    yn[i] = y[i] + h * fm[i];
  if ((s = sym_rhs (ev, tend, yn, f1)))
    return s;
  if (yerr)
    for (int i = 0; i < 2; i++)
      yerr[i] = h * (fm[i] - f0[i]);
  m->tt = t;
  m->th = h;
  memcpy (m->ty0, y, sizeof m->ty0);
  memcpy (m->ty1, yn, sizeof m->ty1);
  memcpy (m->tf0, f0, sizeof m->tf0);
  memcpy (m->tf1, f1, sizeof m->tf1);
  return 0;
}

static void
mid_accept (void *st)
{
  mid_state *m = st;
  m->t = m->tt;
  m->h = m->th;
  memcpy (m->y0, m->ty0, sizeof m->y0);
  memcpy (m->y1, m->ty1, sizeof m->y1);
  memcpy (m->f0, m->tf0, sizeof m->f0);
  memcpy (m->f1, m->tf1, sizeof m->f1);
}

static int
mid_dense (void *st, sym_eval *ev, double t, double *y)
{
  (void) ev;
  mid_state *m = st;
  double s = (t - m->t) / m->h, h = m->h;
  double h00 = (1 + 2 * s) * (1 - s) * (1 - s), h10 = s * (1 - s) * (1 - s);
  double h01 = s * s * (3 - 2 * s), h11 = s * s * (s - 1);
  for (int i = 0; i < 2; i++)
    y[i] = h00 * m->y0[i] + h10 * h * m->f0[i] + h01 * m->y1[i]
           + h11 * h * m->f1[i];
  return 0;
}

static void *
mid_alloc (int dim, const sym_method_opts *o, int *st)
{
  (void) dim;
  (void) o;
  mid_state *m = sym_calloc (1, sizeof *m);
  *st = m ? 0 : SYM_ENOMEM;
  return m;
}

static int
mid_order (const void *st, int *est)
{
  (void) st;
  if (est)
    *est = 1;
  return 2;
}

static int mid_samples (const void *st) { (void) st; return 0; }
static int mid_degree (const void *st) { (void) st; return 3; }

const sym_stepper_type drv_mid_type = {
  "midpoint", mid_alloc, mid_order, no_tolerances, mid_step, mid_accept,
  mid_dense, mid_samples, mid_degree, ex_free, NULL
};

/* ------------------------------------------------------------ sinks */
int
drv_out_row (double t, const double *y, void *u)
{
  drv_sink *s = u;
  if (s->nrows < DRV_MAXROWS)
    {
      s->t[s->nrows] = t;
      s->y[s->nrows][0] = y[0];
      s->y[s->nrows][1] = y[1];
    }
  s->nrows++;
  return s->stop_after && s->nrows >= s->stop_after;
}

int
drv_out_event (double te, const double *ye, int ie, void *u)
{
  (void) u;
  drv_sink *s = &SINK;
  if (s->nev < 1000)
    {
      s->te[s->nev] = te;
      s->ie[s->nev] = ie;
      s->ye[s->nev][0] = ye[0];
      s->ye[s->nev][1] = ye[1];
    }
  s->nev++;
  return 0;
}

/* ------------------------------------------------------------ runs */
void
drv_setup (drv_run *r)
{
  memset (r, 0, sizeof *r);
  r->hu.nan_after = INFINITY;
  r->sys.dim = 1;
  r->sys.rhs = drv_ho_rhs;
  r->sys.user = &r->hu;
  r->atol = 1e-8;
  r->o.t0 = 0;
  r->o.tf = 10;
  r->o.refine = 1;
  r->o.tol.rtol = 1e-6;
  r->o.tol.atol = &r->atol;
  r->o.tol.atol_len = 1;
  r->o.output = drv_out_row;
  r->o.output_user = &SINK;
  r->o.event_out = drv_out_event;
  r->o.event_user = NULL;
  memset (&SINK, 0, sizeof SINK);
}

long drv_alloc_count, drv_alloc_live, drv_alloc_fail_at;

void *
drv_counting_alloc (size_t nbytes)
{
  if (++drv_alloc_count == drv_alloc_fail_at)
    return NULL;
  void *p = malloc (nbytes);
  if (p)
    drv_alloc_live++;
  return p;
}

void
drv_counting_free (void *p)
{
  if (p)
    drv_alloc_live--;
  free (p);
}

int
drv_integrate (drv_run *r, const sym_stepper_type *type, const double *y0)
{
  return sym_integrate (type, &r->sys, &r->mo, &r->o, y0, &r->stats);
}

int
drv_run_events (sym_event_fn ev, int nevents, void *u, int samples,
                double t0, const double *y, sym_stats *stats)
{
  drv_run r;
  drv_setup (&r);
  r.mo.own = &samples;
  r.o.t0 = t0;
  r.o.h_fixed = 0.5;
  r.o.nevents = nevents;
  r.o.events = ev;
  r.o.event_user = u;
  int st = drv_integrate (&r, &drv_exact_type, y);
  *stats = r.stats;
  return st;
}
