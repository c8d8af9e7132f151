/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* test_driver.c -- the driver loop on its own: fixed and adaptive steps,
   output times, refine, events, stops, failures.  Two test steppers live
   here so that the driver is tested independently of the real methods:
   - "exact": the exact flow of the harmonic oscillator q' = p, p' = -q
     (rotation), with the exact flow as dense output: events and output
     times must then be found to round-off;
   - "midpoint": the explicit midpoint rule (order 2) with the Euler
     step as embedded estimate (err = O(h^2)), cubic Hermite dense output. */
#include "sym.h"
#include "control.h"
#include "testutil.h"

#include <float.h>
#include <string.h>

/* ------------------------------------------------------------ systems */
typedef struct {
  double nan_after;   /* rhs returns NaN for t > nan_after */
  long fatal_at;      /* rhs returns -1 on this call number (0: never) */
  long smaller_from;  /* rhs returns 1 (asks for a smaller step) from this
                         call number on (0: never) */
  long calls;
} ho_user;

static int
ho_rhs (double t, const double *y, double *dy, void *u)
{
  ho_user *hu = u;
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

/* ------------------------------------------------------------ exact stepper */
typedef struct {
  double t, h, y[2];      /* current accepted step start */
  double tt, th, ty[2];   /* trial */
} exact_state;

static void *
ex_alloc (const sym_system *s, const sym_method_opts *o, int *st)
{
  (void) s; (void) o;
  exact_state *e = sym_calloc (1, sizeof *e);
  *st = e ? 0 : SYM_ENOMEM;
  return e;
}

/* the least and the largest h the exact stepper was given */
static double h_least = INFINITY, h_most = 0;

static int
ex_step (void *st, sym_system *sys, double t, double h, double tend,
         const double *y, double *yn, double *yerr)
{
  exact_state *e = st;
  double dy[2];
  int s = sym_rhs (sys, tend, y, dy);   /* to count calls and see NaNs */
  h_least = fmin (h_least, h);
  h_most = fmax (h_most, h);
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
ex_dense (void *st, sym_system *sys, double t, double *y)
{
  (void) sys;
  exact_state *e = st;
  double s = t - e->t;
  y[0] = cos (s) * e->y[0] + sin (s) * e->y[1];
  y[1] = -sin (s) * e->y[0] + cos (s) * e->y[1];
  return 0;
}

static void ex_reset (void *st) { (void) st; }
static void ex_free (void *st) { sym_free (st); }
static int ex_err_order (const void *st) { (void) st; return 2; }
static int ex_order (const void *st) { (void) st; return 99; }

static const sym_stepper_type exact_type = {
  "exact", 99, ex_err_order, ex_order, ex_alloc, ex_step, ex_accept,
  ex_dense, ex_reset, ex_free
};

/* ------------------------------------------------------------ midpoint */
typedef struct {
  double t, h, y0[2], y1[2], f0[2], f1[2];
  double tt, th, ty0[2], ty1[2], tf0[2], tf1[2];
} mid_state;

static int
mid_step (void *st, sym_system *sys, double t, double h, double tend,
          const double *y, double *yn, double *yerr)
{
  mid_state *m = st;
  double f0[2], ym[2], fm[2], f1[2];
  int s = sym_rhs (sys, t, y, f0);
  if (s)
    return s;
  for (int i = 0; i < 2; i++)
    ym[i] = y[i] + 0.5 * h * f0[i];
  if ((s = sym_rhs (sys, t + 0.5 * h, ym, fm)))
    return s;
  for (int i = 0; i < 2; i++)
    yn[i] = y[i] + h * fm[i];
  if ((s = sym_rhs (sys, tend, yn, f1)))
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
mid_dense (void *st, sym_system *sys, double t, double *y)
{
  (void) sys;
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
mid_alloc (const sym_system *s, const sym_method_opts *o, int *st)
{
  (void) s; (void) o;
  mid_state *m = sym_calloc (1, sizeof *m);
  *st = m ? 0 : SYM_ENOMEM;
  return m;
}

static int mid_err_order (const void *st) { (void) st; return 1; }
static int mid_order (const void *st) { (void) st; return 2; }

static const sym_stepper_type mid_type = {
  "midpoint", 2, mid_err_order, mid_order, mid_alloc, mid_step, mid_accept,
  mid_dense, ex_reset, ex_free
};

/* ------------------------------------------------------------ sinks */
#define MAXROWS 200000
typedef struct sink_s {
  int nrows;
  double t[MAXROWS], y[MAXROWS][2];
  int stop_after;      /* ask to stop after this many rows (0: never) */
  int nev;
  double te[1000];
  int ie[1000];
  double ye[1000][2];
} sink;
static sink S;

static int
out_row (double t, const double *y, void *u)
{
  sink *s = u;
  if (s->nrows < MAXROWS)
    {
      s->t[s->nrows] = t;
      s->y[s->nrows][0] = y[0];
      s->y[s->nrows][1] = y[1];
    }
  s->nrows++;
  return s->stop_after && s->nrows >= s->stop_after;
}

typedef struct { int terminal; int direction; } ev_user;

static int
out_event (double te, const double *ye, int ie, void *u)
{
  (void) u;
  sink *s = &S;
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

/* events: q = 0 (any direction, terminal per flag), p = 0.5 rising */
static int
ev_fn (double t, const double *y, double *v, int *term, int *dir, void *u)
{
  (void) t;
  ev_user *eu = u;
  v[0] = y[0];
  v[1] = y[1] - 0.5;
  term[0] = eu->terminal;
  term[1] = 0;
  dir[0] = eu->direction;
  dir[1] = 1;
  return 0;
}

/* an event at t = 1 (non-terminal, any direction); counts its calls in
   the long that is its user data */
static int
ev_time (double t, const double *y, double *v, int *term, int *dir, void *u)
{
  (void) y;
  (*(long *) u)++;
  v[0] = t - 1.0;
  term[0] = 0;
  dir[0] = 0;
  return 0;
}

/* q - level (cos t - level on the exact flow), terminal per flag */
typedef struct
{
  double level;
  int terminal;
} peak_user;

static int
ev_peak (double t, const double *y, double *v, int *term, int *dir, void *u)
{
  const peak_user *pu = u;
  (void) t;
  v[0] = y[0] - pu->level;
  term[0] = pu->terminal;
  dir[0] = 0;
  return 0;
}

/* cos t - 0.9999 and cos (t - 0.05) - 0.9999 on the exact flow: narrow
   excursions above zero centred 0.05 apart */
static int
ev_two_peaks (double t, const double *y, double *v, int *term, int *dir,
              void *u)
{
  (void) t;
  (void) u;
  v[0] = y[0] - 0.9999;
  v[1] = y[0] * cos (0.05) - y[1] * sin (0.05) - 0.9999;
  term[0] = term[1] = 0;
  dir[0] = dir[1] = 0;
  return 0;
}

/* t - 1.125, terminal, and t - 1.125 - 4.4e-16 (2 ulps later): the first
   on a sample point of the step (1, 1.5] with 3 samples */
static int
ev_at_sample (double t, const double *y, double *v, int *term, int *dir,
              void *u)
{
  (void) y;
  (void) u;
  v[0] = t - 1.125;
  v[1] = (t - 1.125) - 4.4e-16;
  term[0] = 1;
  term[1] = 0;
  dir[0] = dir[1] = 0;
  return 0;
}

/* two event functions with the same zeros, q and 2 q, terminal per
   flags (an int[2] as user data) */
static int
ev_twin (double t, const double *y, double *v, int *term, int *dir, void *u)
{
  (void) t;
  const int *flags = u;
  v[0] = y[0];
  v[1] = 2 * y[0];
  term[0] = flags[0];
  term[1] = flags[1];
  dir[0] = dir[1] = 0;
  return 0;
}

static void
setup (sym_system *sys, ho_user *hu, sym_driver_opts *o, const double *atol)
{
  memset (sys, 0, sizeof *sys);
  memset (hu, 0, sizeof *hu);
  hu->nan_after = INFINITY;
  sys->dim = 1;
  sys->rhs = ho_rhs;
  sys->user = hu;
  memset (o, 0, sizeof *o);
  o->t0 = 0;
  o->tf = 10;
  o->refine = 1;
  o->rtol = 1e-6;
  o->atol = atol;
  o->atol_len = 1;
  o->output = out_row;
  o->output_user = &S;
  o->event_out = out_event;
  o->event_user = NULL;
  memset (&S, 0, sizeof S);
}

/* A fixed-step run (h = 0.5, to tf = 10) of the exact flow from (t0, y)
   with nevents events of ev (user data u), checked at the step points
   and at that many samples inside each step; the events land in S. */
static int
run_events (sym_event_fn ev, int nevents, void *u, int samples, double t0,
            const double *y, double *tr)
{
  sym_system sys;
  ho_user hu;
  sym_driver_opts o;
  sym_method_opts mo;
  double atol = 1e-8;
  memset (&mo, 0, sizeof mo);
  setup (&sys, &hu, &o, &atol);
  o.t0 = t0;
  o.h_fixed = 0.5;
  o.nevents = nevents;
  o.events = ev;
  o.event_user = u;
  o.event_samples = samples;
  return sym_integrate (&exact_type, &sys, &mo, &o, y, tr);
}

int
main (void)
{
  sym_system sys;
  ho_user hu;
  sym_driver_opts o;
  sym_method_opts mo;
  memset (&mo, 0, sizeof mo);
  double atol = 1e-8, y0[2] = { 1, 0 }, tr;
  int st;

  /* fixed step, h not dividing the interval: the last step ends on tf */
  setup (&sys, &hu, &o, &atol);
  o.h_fixed = 0.3;
  st = sym_integrate (&exact_type, &sys, &mo, &o, y0, &tr);
  CHECK (st == SYM_DONE, "status %s", sym_status_name (st));
  /* the run's sizes for the finite differences were its own */
  CHECK (sys.ytyp == NULL, "ytyp set back");
  CHECK (S.nrows == 35, "rows %d", S.nrows);   /* ceil(10/0.3) = 34 steps */
  CHECK (S.t[S.nrows - 1] == 10.0, "last t %.17g", S.t[S.nrows - 1]);
  CHECK_CLOSE (S.t[10], 3.0, 1e-15, "t_10 = t0 + 10 h, not accumulated");
  CHECK_CLOSE (S.y[S.nrows - 1][0], cos (10.0), 1e-13, "exact flow");
  CHECK (sys.cnt.nsteps == 34, "nsteps %ld", sys.cnt.nsteps);
  CHECK (tr == 10.0, "t reached");

  /* far from t = 0 every fixed step is h itself; the rows are at t0 + k h
     rounded once.  The steps were the differences of those times, which
     vary there by the round-off of t (here by up to 1.5e-6 h).  A last
     step that h does not fit takes what is left. */
  for (int part = 0; part < 2; part++)
    {
      setup (&sys, &hu, &o, &atol);
      o.t0 = 1e8;
      o.tf = 1e8 + (part ? 10.005 : 10.0);
      o.h_fixed = 0.01;
      h_least = INFINITY;
      h_most = 0;
      st = sym_integrate (&exact_type, &sys, &mo, &o, y0, &tr);
      CHECK (st == SYM_DONE && S.nrows == 1001 + part
             && S.t[1000 + part] == o.tf, "rows %d", S.nrows);
      CHECK (h_most == 0.01
             && h_least == (part ? (1e8 + 10.005) - (1e8 + 10.0) : 0.01),
             "steps %.17g to %.17g", h_least, h_most);
      int on_grid = 1;
      for (int k = 0; k < 1001; k++)
        on_grid &= S.t[k] == 1e8 + 0.01 * k;
      CHECK (on_grid, "rows at t0 + k h");
      CHECK_CLOSE (S.y[1000][0], cos (10.0), 1e-12, "exact flow over h");
    }

  /* fixed step, h dividing the interval up to rounding: no tiny step */
  setup (&sys, &hu, &o, &atol);
  o.h_fixed = 0.1;
  st = sym_integrate (&exact_type, &sys, &mo, &o, y0, &tr);
  CHECK (S.nrows == 101, "rows %d", S.nrows);

  /* TimeStepNumber with TimeStepSize: exactly N steps from t0 */
  setup (&sys, &hu, &o, &atol);
  o.h_fixed = 0.25;
  o.nsteps_fixed = 7;
  st = sym_integrate (&exact_type, &sys, &mo, &o, y0, &tr);
  CHECK (S.nrows == 8 && S.t[7] == 1.75, "rows %d, t %.17g", S.nrows,
         S.t[7]);
  /* N h = 3 * 0.7 rounds to 2.0999999999999996: the run ends on the
     time it stands for, tf or an output time, and emits its row there;
     a real shortfall is kept */
  setup (&sys, &hu, &o, &atol);
  o.h_fixed = 0.7;
  o.nsteps_fixed = 3;
  o.tf = 2.1;
  CHECK (3 * 0.7 != 2.1 && sym_fixed_end (&o) == 2.1, "end %.17g",
         sym_fixed_end (&o));
  double touts[3] = { 0, 1, 2.1 };
  o.tf = 5;
  o.tout = touts;
  o.ntout = 3;
  CHECK (sym_fixed_end (&o) == 2.1, "end at an output time");
  st = sym_integrate (&exact_type, &sys, &mo, &o, y0, &tr);
  CHECK (st == SYM_DONE && S.nrows == 3 && S.t[2] == 2.1 && tr == 2.1,
         "rows %d, t reached %.17g", S.nrows, tr);
  touts[2] = 2.1 + 1e-13;
  CHECK (sym_fixed_end (&o) == 3 * 0.7, "a real shortfall: %.17g",
         sym_fixed_end (&o));
  o.t0 = 0;
  o.tf = -2.1;
  o.ntout = 2;
  CHECK (sym_fixed_end (&o) == -2.1, "backward");
  o.tf = -3;
  CHECK (sym_fixed_end (&o) == -3 * 0.7, "backward, tf beyond");
  o.nsteps_fixed = 0;
  CHECK (sym_fixed_end (&o) == -3, "no TimeStepNumber: tf");

  /* TimeStepNumber alone: N equal steps over tspan */
  setup (&sys, &hu, &o, &atol);
  o.nsteps_fixed = 40;
  st = sym_integrate (&exact_type, &sys, &mo, &o, y0, &tr);
  CHECK (S.nrows == 41 && S.t[40] == 10.0 && S.t[4] == 1.0,
         "rows %d", S.nrows);

  /* backward */
  setup (&sys, &hu, &o, &atol);
  o.t0 = 1;
  o.tf = -2;
  o.h_fixed = 0.5;
  st = sym_integrate (&exact_type, &sys, &mo, &o, y0, &tr);
  CHECK (st == SYM_DONE && S.nrows == 7 && S.t[6] == -2 && S.t[1] == 0.5,
         "backward rows %d", S.nrows);
  CHECK_CLOSE (S.y[6][0], cos (-3.0), 1e-13, "backward exact");

  /* output times: rows exactly there, from the dense output, steps not
     shortened (number of steps unchanged) */
  {
    double tout[101];
    for (int i = 0; i <= 100; i++)
      tout[i] = 0.1 * i + (i > 0 && i < 100 ? 0.01234 : 0);
    setup (&sys, &hu, &o, &atol);
    o.h_fixed = 0.3;
    o.tout = tout;
    o.ntout = 101;
    st = sym_integrate (&exact_type, &sys, &mo, &o, y0, &tr);
    CHECK (S.nrows == 101, "rows %d", S.nrows);
    CHECK (sys.cnt.nsteps == 34, "steps %ld", sys.cnt.nsteps);
    double maxerr = 0;
    int exact_t = 1;
    for (int i = 0; i < S.nrows; i++)
      {
        maxerr = fmax (maxerr, fabs (S.y[i][0] - cos (tout[i])));
        exact_t &= S.t[i] == tout[i];
      }
    CHECK (exact_t, "output at the requested times");
    CHECK (maxerr < 1e-13, "dense error %.3g", maxerr);
  }

  /* refine: refine rows per step */
  setup (&sys, &hu, &o, &atol);
  o.h_fixed = 0.5;
  o.refine = 4;
  st = sym_integrate (&exact_type, &sys, &mo, &o, y0, &tr);
  CHECK (S.nrows == 20 * 4 + 1, "rows %d", S.nrows);
  CHECK_CLOSE (S.t[1], 0.125, 1e-15, "refined time");
  CHECK_CLOSE (S.y[1][0], cos (0.125), 1e-14, "refined value");

  /* events with the exact flow: zeros of q at pi/2 + k pi, and of
     p - 0.5 rising at 2 pi - pi/6 + 2 k pi, located to round-off */
  {
    static ev_user eu;
    eu.terminal = 0;
    eu.direction = 0;
    setup (&sys, &hu, &o, &atol);
    o.h_fixed = 0.3;
    o.nevents = 2;
    o.events = ev_fn;
    o.event_user = &eu;
    st = sym_integrate (&exact_type, &sys, &mo, &o, y0, &tr);
    CHECK (st == SYM_DONE, "events run %s", sym_status_name (st));
    int nq = 0, np = 0, ordered = 1;
    double eq = 0, ep = 0;
    for (int i = 0; i < S.nev; i++)
      {
        if (i > 0)
          ordered &= S.te[i] > S.te[i - 1];
        if (S.ie[i] == 0)
          {
            eq = fmax (eq, fabs (S.te[i] - (M_PI / 2 + nq * M_PI)));
            nq++;
          }
        else
          {
            /* p = -sin t = 0.5 rising: t = 2 pi - pi/6 + 2 k pi ... and
               -sin t rising through 0.5 happens at t = 7 pi / 6 + 2 k pi */
            eq = fmax (eq, 0);
            ep = fmax (ep, fabs (S.te[i] - (7 * M_PI / 6 + np * 2 * M_PI)));
            np++;
          }
      }
    CHECK (nq == 3 && np == 2, "events found: %d %d", nq, np);
    CHECK (eq < 1e-14 && ep < 1e-14, "event time errors %.3g %.3g", eq, ep);
    CHECK (ordered, "events in time order");
    CHECK (S.nrows == 35, "non-terminal events add no rows");
  }

  /* terminal event on q = 0 falling: stops at pi/2 exactly, last row */
  {
    static ev_user eu;
    eu.terminal = 1;
    eu.direction = -1;
    setup (&sys, &hu, &o, &atol);
    o.h_fixed = 0.3;
    o.nevents = 2;
    o.events = ev_fn;
    o.event_user = &eu;
    o.event_out = NULL;
    st = sym_integrate (&exact_type, &sys, &mo, &o, y0, &tr);
    CHECK (st == SYM_STOP_EVENT, "status %s", sym_status_name (st));
    CHECK_CLOSE (S.t[S.nrows - 1], M_PI / 2, 1e-14, "terminal event time");
    CHECK_CLOSE (S.y[S.nrows - 1][0], 0.0, 1e-14, "terminal event value");
    CHECK (S.nrows == 7, "rows before pi/2 plus the event: %d", S.nrows);
    CHECK_CLOSE (tr, M_PI / 2, 1e-14, "t reached");
  }
  /* rising only: the first rising zero of q is 3 pi / 2 */
  {
    static ev_user eu;
    eu.terminal = 1;
    eu.direction = 1;
    setup (&sys, &hu, &o, &atol);
    o.h_fixed = 0.3;
    o.nevents = 2;
    o.events = ev_fn;
    o.event_user = &eu;
    o.event_out = NULL;
    st = sym_integrate (&exact_type, &sys, &mo, &o, y0, &tr);
    CHECK (st == SYM_STOP_EVENT, "status");
    CHECK_CLOSE (S.t[S.nrows - 1], 3 * M_PI / 2, 1e-14, "rising event");
  }

  /* an event on a step point (t = 1, h = 0.25): reported once, at 1,
     with one call of the events function per step and one at t0 (no
     search inside the step: it took 57 calls before) */
  {
    static long ncalls;
    ncalls = 0;
    setup (&sys, &hu, &o, &atol);
    o.tf = 2;
    o.h_fixed = 0.25;
    o.nevents = 1;
    o.events = ev_time;
    o.event_user = &ncalls;
    st = sym_integrate (&exact_type, &sys, &mo, &o, y0, &tr);
    CHECK (st == SYM_DONE && S.nev == 1 && S.te[0] == 1.0,
           "event on a step point: %s, %d events, te %.17g",
           sym_status_name (st), S.nev, S.nev ? S.te[0] : NAN);
    CHECK (ncalls == 9, "event on a step point: %ld calls of events "
           "(8 steps and t0)", ncalls);
  }

  /* a zero pair inside one step: q = cos t exceeds 0.99 only for
     |t - 2 pi| < acos(0.99) = 0.1415, inside the step (6, 6.5] of
     h = 0.5.  At the step points alone it is unseen; with 3 samples
     inside each step both zeros are found, in order, to round-off; a
     terminal one (from t0 = 6) stops the run at the first.  Above 0.9999
     (|t - 2 pi| < 0.0141) the pair lies between the samples 6.25 and
     6.375: found at the vertex of the parabola through the samples. */
  {
    static peak_user pu;
    for (int run = 0; run < 4; run++)
      {
        pu.level = run == 3 ? 0.9999 : 0.99;
        pu.terminal = run == 2;
        const double a = acos (pu.level);
        const double tz[3] = { a, 2 * M_PI - a, 2 * M_PI + a };
        double y6[2] = { cos (6.0), -sin (6.0) };
        st = run_events (ev_peak, 1, &pu, run ? 3 : 0,
                         pu.terminal ? 6.0 : 0.0, pu.terminal ? y6 : y0,
                         &tr);
        if (run == 0)
          CHECK (st == SYM_DONE && S.nev == 1
                 && fabs (S.te[0] - tz[0]) < 1e-14,
                 "zero pair, step points only: %s, %d events (the pair "
                 "unseen)", sym_status_name (st), S.nev);
        else if (run != 2)
          {
            double err = 0;
            for (int i = 0; i < S.nev && i < 3; i++)
              err = fmax (err, fabs (S.te[i] - tz[i]));
            /* the zeros near the top: slope 0.014, so the round-off of
               q (1e-16) moves them by 1e-14 */
            CHECK (st == SYM_DONE && S.nev == 3
                   && err < (run == 3 ? 1e-12 : 1e-14),
                   "zero pair above %g, 3 samples a step: %s, %d events, "
                   "error %.3g", pu.level, sym_status_name (st), S.nev, err);
          }
        else
          CHECK (st == SYM_STOP_EVENT && S.nev == 1
                 && fabs (S.te[0] - tz[1]) < 1e-14
                 && fabs (tr - tz[1]) < 1e-14,
                 "terminal zero pair: %s, %d events, te %.17g",
                 sym_status_name (st), S.nev, S.nev ? S.te[0] : NAN);
      }
  }

  /* two such pairs in one piece between samples (6.25, 6.375], each
     found at its own vertex, and the pairs of the first step too: all
     zeros, in time order */
  {
    st = run_events (ev_two_peaks, 2, NULL, 3, 0.0, y0, &tr);
    const double a = acos (0.9999), c = 0.05;
    const double tz[7] = { a, c - a, c + a, 2 * M_PI - a, 2 * M_PI + a,
                           2 * M_PI + c - a, 2 * M_PI + c + a };
    const int iz[7] = { 0, 1, 1, 0, 0, 1, 1 };
    double err = 0;
    int same = S.nev == 7;
    for (int i = 0; i < S.nev && i < 7; i++)
      {
        err = fmax (err, fabs (S.te[i] - tz[i]));
        same &= S.ie[i] == iz[i];
      }
    CHECK (st == SYM_DONE && same && err < 1e-12,
           "two pairs in one piece: %s, %d events, error %.3g",
           sym_status_name (st), S.nev, err);
  }

  /* a terminal event on a sample point and another two ulps after it, in
     the next piece: both reported at the stop, as within one piece */
  {
    st = run_events (ev_at_sample, 2, NULL, 3, 0.0, y0, &tr);
    CHECK (st == SYM_STOP_EVENT && S.nev == 2 && S.te[0] == 1.125
           && S.ie[1] == 1 && fabs (S.te[1] - 1.125) < 1e-15
           && tr == 1.125,
           "terminal event on a sample point: %s, %d events",
           sym_status_name (st), S.nev);
  }

  /* two events that vanish together: both are reported at the stop,
     whichever of them is terminal, and no later event */
  {
    static const int flags[3][2] = { { 1, 0 }, { 0, 1 }, { 1, 1 } };
    for (int f = 0; f < 3; f++)
      {
        setup (&sys, &hu, &o, &atol);
        o.h_fixed = 0.3;
        o.nevents = 2;
        o.events = ev_twin;
        o.event_user = (void *) flags[f];
        st = sym_integrate (&exact_type, &sys, &mo, &o, y0, &tr);
        CHECK (st == SYM_STOP_EVENT, "twin events %d: status %s", f,
               sym_status_name (st));
        CHECK (S.nev == 2 && S.ie[0] == 0 && S.ie[1] == 1,
               "twin events %d: %d events, ie %d %d", f, S.nev, S.ie[0],
               S.ie[1]);
        CHECK (fabs (S.te[0] - M_PI / 2) < 1e-14
               && fabs (S.te[1] - M_PI / 2) < 1e-14,
               "twin events %d: te %.17g %.17g", f, S.te[0], S.te[1]);
        CHECK_CLOSE (S.t[S.nrows - 1], M_PI / 2, 1e-14,
                     "twin events: last row");
      }
  }

  /* adaptive: errors shrink with rtol; hmax respected */
  {
    double err[3], rt[3] = { 1e-4, 1e-6, 1e-8 };
    long steps[3];
    for (int k = 0; k < 3; k++)
      {
        setup (&sys, &hu, &o, &atol);
        o.rtol = rt[k];
        double at = rt[k];
        o.atol = &at;
        st = sym_integrate (&mid_type, &sys, &mo, &o, y0, &tr);
        CHECK (st == SYM_DONE, "adaptive %s", sym_status_name (st));
        err[k] = fabs (S.y[S.nrows - 1][0] - cos (10.0));
        steps[k] = sys.cnt.nsteps;
        CHECK (S.t[S.nrows - 1] == 10.0, "ends on tf");
      }
    CHECK (err[0] > 5 * err[1] && err[1] > 5 * err[2],
           "errors %.3g %.3g %.3g", err[0], err[1], err[2]);
    CHECK (steps[0] < steps[1] && steps[1] < steps[2], "steps grow");

    setup (&sys, &hu, &o, &atol);
    o.hmax = 0.05;
    o.rtol = 1e-2;
    st = sym_integrate (&mid_type, &sys, &mo, &o, y0, &tr);
    int ok = 1;
    for (int i = 1; i < S.nrows; i++)
      ok &= S.t[i] - S.t[i - 1] <= 0.05 * (1 + 1e-12);
    CHECK (ok && st == SYM_DONE, "hmax respected");
    /* hmax 0: |tf - t0| / 10; inf: no cap (as 1e300), as in ode45 */
    double hbig[3], hcap[3] = { 0.0, INFINITY, 1e300 };
    for (int k = 0; k < 3; k++)
      {
        setup (&sys, &hu, &o, &atol);
        o.hmax = hcap[k];
        double at = 0.5;
        o.rtol = 0.5;
        o.atol = &at;
        o.tf = 2;
        st = sym_integrate (&mid_type, &sys, &mo, &o, y0, &tr);
        hbig[k] = 0.0;
        for (int i = 1; i < S.nrows; i++)
          hbig[k] = fmax (hbig[k], S.t[i] - S.t[i - 1]);
        CHECK (st == SYM_DONE, "hmax %g: %s", hcap[k], sym_status_name (st));
      }
    CHECK (hbig[0] <= 0.2 * (1 + 1e-12) && hbig[1] > 0.5
           && hbig[2] == hbig[1], "largest steps %.17g %.17g %.17g",
           hbig[0], hbig[1], hbig[2]);
    /* a too large initial step is rejected and retried */
    setup (&sys, &hu, &o, &atol);
    o.h0 = 5;
    o.hmax = 5;
    st = sym_integrate (&mid_type, &sys, &mo, &o, y0, &tr);
    CHECK (st == SYM_DONE && sys.cnt.nfailed > 0, "rejections %ld",
           sys.cnt.nfailed);
    /* h0 = inf: the first step as long as hmax allows, the run above */
    {
      int rows5 = S.nrows;
      double t5 = S.t[rows5 - 1], y5 = S.y[rows5 - 1][0];
      long fail5 = sys.cnt.nfailed;
      setup (&sys, &hu, &o, &atol);
      o.h0 = INFINITY;
      o.hmax = 5;
      st = sym_integrate (&mid_type, &sys, &mo, &o, y0, &tr);
      CHECK (st == SYM_DONE && S.nrows == rows5 && S.t[S.nrows - 1] == t5
             && S.y[S.nrows - 1][0] == y5 && sys.cnt.nfailed == fail5,
             "h0 = inf: %s, %d rows, %ld failed (h0 = 5: %d, %ld)",
             sym_status_name (st), S.nrows, sys.cnt.nfailed, rows5, fail5);
    }
    /* backward adaptive */
    setup (&sys, &hu, &o, &atol);
    o.tf = -10;
    st = sym_integrate (&mid_type, &sys, &mo, &o, y0, &tr);
    CHECK (st == SYM_DONE && S.t[S.nrows - 1] == -10.0, "backward adaptive");
    CHECK (fabs (S.y[S.nrows - 1][0] - cos (10.0)) < 1e-3, "value");
  }

  /* adaptive steps that MaxStep caps all along, where it divides the
     span: N steps, none a sliver.  t summed plainly left the round-off it
     gathered (up to 1.9e-12 after 1e5 steps of 1e-5 from 0, and a few
     ulps far from 0: 91 of 280 such runs of odeSV had a step too many)
     for a step of its own */
  {
    const double t0s[] = { 0.0, 1.0, -3.7, 1e4, 1e8, -1e8 };
    const double spans[] = { 1.0, 12.584366058104878, 1.6513676438767741 };
    const long Ns[] = { 3, 455, 1412, 10000, 100000 };
    int bad = 0, runs = 0;
    double loose = 1.0;
    for (int a = 0; a < 6; a++)
      for (int b = 0; b < 3; b++)
        for (int c = 0; c < 5; c++)
          for (int dir = -1; dir <= 1; dir += 2)
            {
              setup (&sys, &hu, &o, &atol);
              o.t0 = t0s[a];
              o.tf = t0s[a] + dir * spans[b];
              o.hmax = spans[b] / (double) Ns[c];
              o.h0 = o.hmax;
              o.rtol = 1.0;       /* so that MaxStep binds (the pretend */
              o.atol = &loose;    /* error is 1e-3 h^3) */
              st = sym_integrate (&exact_type, &sys, &mo, &o, y0, &tr);
              double least = INFINITY;
              for (int i = 1; i < S.nrows; i++)
                least = fmin (least, fabs (S.t[i] - S.t[i - 1]));
              runs++;
              if (st != SYM_DONE || S.nrows != Ns[c] + 1
                  || S.t[S.nrows - 1] != o.tf || least < 0.5 * o.hmax)
                {
                  if (bad++ < 5)
                    printf ("  t0 %g, tf %.17g, N %ld: %s, %d rows, least "
                            "step %.3g of %.3g\n", o.t0, o.tf, Ns[c],
                            sym_status_name (st), S.nrows, least, o.hmax);
                }
            }
    CHECK (bad == 0, "MaxStep dividing the span: %d of %d runs with a "
           "step too many or too short", bad, runs);
    /* a MaxStep short of dividing the span by less than the least step
       (16 ulps of t): what is left joins the last step.  At t = 1e8,
       1000 steps of 1e-3 (1 - 2e-8) leave 2e-8, 1 to 2 ulps there. */
    setup (&sys, &hu, &o, &atol);
    o.t0 = 1e8;
    o.tf = 1e8 + 1;
    o.hmax = 1e-3 * (1 - 2e-8);
    o.h0 = o.hmax;
    o.rtol = 1.0;
    o.atol = &loose;
    st = sym_integrate (&exact_type, &sys, &mo, &o, y0, &tr);
    CHECK (st == SYM_DONE && S.nrows == 1001 && S.t[1000] == o.tf,
           "a remainder below the least step: %d rows", S.nrows);
  }

  /* NaN after t = 1: adaptive gives up with ENONFINITE, rows up to ~1 */
  {
    setup (&sys, &hu, &o, &atol);
    hu.nan_after = 1.0;
    st = sym_integrate (&mid_type, &sys, &mo, &o, y0, &tr);
    CHECK (st == SYM_ENONFINITE, "status %s", sym_status_name (st));
    CHECK (S.t[S.nrows - 1] <= 1.0 && S.t[S.nrows - 1] > 0.99,
           "last row at %.17g", S.t[S.nrows - 1]);
    int finite = 1;
    for (int i = 0; i < S.nrows; i++)
      finite &= isfinite (S.y[i][0]) && isfinite (S.y[i][1]);
    CHECK (finite, "rows finite");
    /* fixed: fails at once, at the step to 1.1 (rows t = 0, ..., 1) */
    setup (&sys, &hu, &o, &atol);
    hu.nan_after = 1.0;
    o.h_fixed = 0.1;
    st = sym_integrate (&exact_type, &sys, &mo, &o, y0, &tr);
    CHECK (st == SYM_ENONFINITE && S.nrows == 11, "fixed NaN: %s, %d rows",
           sym_status_name (st), S.nrows);
  }

  /* a fatal callback status stops the run with SYM_ECALLBACK */
  setup (&sys, &hu, &o, &atol);
  hu.fatal_at = 30;
  o.h_fixed = 0.1;
  st = sym_integrate (&exact_type, &sys, &mo, &o, y0, &tr);
  CHECK (st == SYM_ECALLBACK && S.nrows == 30, "fatal: %s rows %d",
         sym_status_name (st), S.nrows);

  /* the output sink asks to stop */
  setup (&sys, &hu, &o, &atol);
  S.stop_after = 5;
  o.h_fixed = 0.1;
  st = sym_integrate (&exact_type, &sys, &mo, &o, y0, &tr);
  CHECK (st == SYM_STOP_OUTPUT && S.nrows == 5, "stop: %s rows %d",
         sym_status_name (st), S.nrows);

  /* spans of a few ulps of t: steps below the least step (16 ulps of t)
     that the default MaxStep (span/10) asks for are raised to it, and the
     run reaches tf; a MaxStep set below it ends the run at once */
  {
    const double spans[][2] = { { 1, 1 + 1e-14 }, { 1e6, 1e6 + 1e-8 },
                                { 1, 1 + 2 * DBL_EPSILON },
                                { -2, -2 - 1e-13 } };
    for (size_t i = 0; i < sizeof spans / sizeof spans[0]; i++)
      {
        setup (&sys, &hu, &o, &atol);
        o.t0 = spans[i][0];
        o.tf = spans[i][1];
        st = sym_integrate (&exact_type, &sys, &mo, &o, y0, &tr);
        CHECK (st == SYM_DONE && tr == o.tf && S.t[S.nrows - 1] == o.tf
               && S.nrows >= 2 && S.nrows <= 12,
               "span [%.17g, %.17g]: %s, %d rows", o.t0, o.tf,
               sym_status_name (st), S.nrows);
      }
    setup (&sys, &hu, &o, &atol);
    o.t0 = 1;
    o.tf = 2;
    o.hmax = 1e-20;
    st = sym_integrate (&exact_type, &sys, &mo, &o, y0, &tr);
    CHECK (st == SYM_ESTEPSIZE && S.nrows == 1 && tr == 1,
           "MaxStep below the least step: %s, %d rows",
           sym_status_name (st), S.nrows);
  }

  /* bad input */
  setup (&sys, &hu, &o, &atol);
  o.tf = 0;
  CHECK (sym_integrate (&exact_type, &sys, &mo, &o, y0, &tr)
         == SYM_EBADINPUT, "t0 == tf refused");
  setup (&sys, &hu, &o, &atol);
  o.rtol = 0;
  CHECK (sym_integrate (&exact_type, &sys, &mo, &o, y0, &tr)
         == SYM_EBADINPUT, "rtol 0 refused");
  /* an AbsTol of another length than 1 or n (read past its end before),
     or not positive */
  {
    const double atol2[2] = { 1e-6, 0.0 };
    setup (&sys, &hu, &o, atol2);
    sys.dim = 2;
    o.atol_len = 3;
    CHECK (sym_integrate (&mid_type, &sys, &mo, &o, y0, &tr)
           == SYM_EBADINPUT, "atol_len 3 with n = 4 refused");
    setup (&sys, &hu, &o, atol2);
    o.atol_len = 2;
    CHECK (sym_integrate (&mid_type, &sys, &mo, &o, y0, &tr)
           == SYM_EBADINPUT, "an AbsTol of 0 refused");
  }
  /* a fixed step of more steps than a long holds: refused (the count
     overflowed to one step over the whole span) */
  setup (&sys, &hu, &o, &atol);
  o.h_fixed = 1e-300;
  CHECK (sym_integrate (&mid_type, &sys, &mo, &o, y0, &tr)
         == SYM_EBADINPUT && S.nrows == 0, "h_fixed 1e-300 refused: %d "
         "rows", S.nrows);
  /* a callback that asks for a smaller step where there is none: a
     callback failure, not a step size that fell below round-off */
  for (int k = 0; k < 2; k++)
    {
      setup (&sys, &hu, &o, &atol);
      o.h_fixed = k ? 0.1 : 0.0;
      hu.smaller_from = k ? 10 : 1;
      st = sym_integrate (&mid_type, &sys, &mo, &o, y0, &tr);
      CHECK (st == SYM_ECALLBACK, "%s: a callback asking for a smaller "
             "step: %s", k ? "fixed step" : "adaptive, at t0",
             sym_status_name (st));
    }

  /* predictive step-size control (control.c).  A model error that grows
     along the run by g per step at a fixed h: err_n = c g^n h_n^(q+1).
     After two accepted steps the predicted factor meets it exactly: the
     next error is safety^(q+1) = 0.9^7 for q = 6, where the standard
     factor alone gives g times that, a failed step for g = 4. */
  {
    const int q = 6;
    const double c = 3e5, g = 4.0;
    double h[3] = { 0.1, 0.09, 0 }, err[3];
    for (int k = 0; k < 2; k++)
      err[k] = c * pow (g, k) * pow (h[k], q + 1);
    double fac = sym_step_factor (err[1], q, 0.2, 5.0);
    double fp = sym_step_factor_pred (fac, err[1], q, h[1], h[0], err[0],
                                      0.2);
    h[2] = h[1] * fp;
    err[2] = c * pow (g, 2) * pow (h[2], q + 1);
    CHECK_CLOSE (err[2], pow (0.9, q + 1), 1e-12, "predicted step's error");
    double err_std = c * pow (g, 2) * pow (h[1] * fac, q + 1);
    CHECK_CLOSE (err_std, g * pow (0.9, q + 1), 1e-12,
                 "standard factor's error");
    /* a falling error (g < 1): the standard factor stands */
    CHECK (sym_step_factor_pred (fac, err[1], q, h[1], h[0], 1e6 * err[1],
                                 0.2) == fac, "falling error");
    /* no earlier accepted step, or no finite error: the standard factor */
    CHECK (sym_step_factor_pred (fac, err[1], q, h[1], 0.0, 0.0, 0.2) == fac
           && sym_step_factor_pred (fac, NAN, q, h[1], h[0], err[0], 0.2)
              == fac, "no trend");
    /* the prediction never shrinks h below facmin */
    CHECK (sym_step_factor_pred (fac, err[1], q, h[1], h[0], 1e-30, 0.2)
           == 0.2, "facmin");
  }

  return tu_finish ("test_driver");
}
