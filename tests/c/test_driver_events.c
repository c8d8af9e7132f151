/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* test_driver_events.c -- event location by the driver loop on the exact
   flow (driver_util.h): crossings, directions, terminal events, zero
   pairs inside a step, events that vanish together. */
#include "sym.h"
#include "driver_util.h"
#include "testutil.h"

#include <float.h>
#include <string.h>

typedef struct { int terminal; int direction; } ev_user;

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

/* A run of the exact flow with h = 0.3 and the events of ev_fn,
   terminal and of direction as given (event sink kept or not) */
static int
run_ev_fn (drv_run *r, int terminal, int direction, int sink_events)
{
  static ev_user eu;
  double y0[2] = { 1, 0 };
  eu.terminal = terminal;
  eu.direction = direction;
  drv_setup (r);
  r->o.h_fixed = 0.3;
  r->o.nevents = 2;
  r->o.events = ev_fn;
  r->o.event_user = &eu;
  if (! sink_events)
    r->o.event_out = NULL;
  return drv_integrate (r, &drv_exact_type, y0);
}

/* events with the exact flow: zeros of q at pi/2 + k pi, and of
   p - 0.5 rising at 2 pi - pi/6 + 2 k pi, located to round-off */
static void
scenario_events_located (void)
{
  drv_run r;
  int st = run_ev_fn (&r, 0, 0, 1);
  CHECK (st == SYM_DONE, "events run %s", sym_status_name (st));
  int nq = 0, np = 0, ordered = 1;
  double eq = 0, ep = 0;
  for (int i = 0; i < SINK.nev; i++)
    {
      if (i > 0)
        ordered &= SINK.te[i] > SINK.te[i - 1];
      if (SINK.ie[i] == 0)
        {
          eq = fmax (eq, fabs (SINK.te[i] - (M_PI / 2 + nq * M_PI)));
          nq++;
        }
      else
        {
          /* p = -sin t = 0.5 rising: t = 2 pi - pi/6 + 2 k pi ... and
             -sin t rising through 0.5 happens at t = 7 pi / 6 + 2 k pi */
          eq = fmax (eq, 0);
          ep = fmax (ep, fabs (SINK.te[i] - (7 * M_PI / 6 + np * 2 * M_PI)));
          np++;
        }
    }
  CHECK (nq == 3 && np == 2, "events found: %d %d", nq, np);
  CHECK (eq < 1e-14 && ep < 1e-14, "event time errors %.3g %.3g", eq, ep);
  CHECK (ordered, "events in time order");
  CHECK (SINK.nrows == 35, "non-terminal events add no rows");
}

/* terminal event on q = 0 falling: stops at pi/2 exactly, last row */
static void
scenario_terminal_event (void)
{
  drv_run r;
  int st = run_ev_fn (&r, 1, -1, 0);
  CHECK (st == SYM_STOP_EVENT, "status %s", sym_status_name (st));
  CHECK_CLOSE (SINK.t[SINK.nrows - 1], M_PI / 2, 1e-14, "terminal event time");
  CHECK_CLOSE (SINK.y[SINK.nrows - 1][0], 0.0, 1e-14, "terminal event value");
  CHECK (SINK.nrows == 7, "rows before pi/2 plus the event: %d", SINK.nrows);
  CHECK_CLOSE (r.stats.t_reached, M_PI / 2, 1e-14, "t reached");
}

/* rising only: the first rising zero of q is 3 pi / 2 */
static void
scenario_rising_event (void)
{
  drv_run r;
  int st = run_ev_fn (&r, 1, 1, 0);
  CHECK (st == SYM_STOP_EVENT, "status");
  CHECK_CLOSE (SINK.t[SINK.nrows - 1], 3 * M_PI / 2, 1e-14, "rising event");
}

/* an event on a step point (t = 1, h = 0.25): reported once, at 1,
   with one call of the events function per step and one at t0 (no
   search inside the step) */
static void
scenario_event_on_step_point (void)
{
  drv_run r;
  double y0[2] = { 1, 0 };
  int st;
  static long ncalls;
  ncalls = 0;
  drv_setup (&r);
  r.o.tf = 2;
  r.o.h_fixed = 0.25;
  r.o.nevents = 1;
  r.o.events = ev_time;
  r.o.event_user = &ncalls;
  st = drv_integrate (&r, &drv_exact_type, y0);
  CHECK (st == SYM_DONE && SINK.nev == 1 && SINK.te[0] == 1.0,
         "event on a step point: %s, %d events, te %.17g",
         sym_status_name (st), SINK.nev, SINK.nev ? SINK.te[0] : NAN);
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
static void
scenario_zero_pair_in_step (void)
{
  double y0[2] = { 1, 0 };
  sym_stats stats;
  int st;
  static peak_user pu;
  for (int run = 0; run < 4; run++)
    {
      pu.level = run == 3 ? 0.9999 : 0.99;
      pu.terminal = run == 2;
      const double a = acos (pu.level);
      const double tz[3] = { a, 2 * M_PI - a, 2 * M_PI + a };
      double y6[2] = { cos (6.0), -sin (6.0) };
      st = drv_run_events (ev_peak, 1, &pu, run ? 3 : 0,
                           pu.terminal ? 6.0 : 0.0, pu.terminal ? y6 : y0,
                           &stats);
      if (run == 0)
        CHECK (st == SYM_DONE && SINK.nev == 1
               && fabs (SINK.te[0] - tz[0]) < 1e-14,
               "zero pair, step points only: %s, %d events (the pair "
               "unseen)", sym_status_name (st), SINK.nev);
      else if (run != 2)
        {
          double err = 0;
          for (int i = 0; i < SINK.nev && i < 3; i++)
            err = fmax (err, fabs (SINK.te[i] - tz[i]));
          /* the zeros near the top: slope 0.014, so the round-off of
             q (1e-16) moves them by 1e-14 */
          CHECK (st == SYM_DONE && SINK.nev == 3
                 && err < (run == 3 ? 1e-12 : 1e-14),
                 "zero pair above %g, 3 samples a step: %s, %d events, "
                 "error %.3g", pu.level, sym_status_name (st), SINK.nev, err);
        }
      else
        CHECK (st == SYM_STOP_EVENT && SINK.nev == 1
               && fabs (SINK.te[0] - tz[1]) < 1e-14
               && fabs (stats.t_reached - tz[1]) < 1e-14,
               "terminal zero pair: %s, %d events, te %.17g",
               sym_status_name (st), SINK.nev, SINK.nev ? SINK.te[0] : NAN);
    }
}

/* two such pairs in one piece between samples (6.25, 6.375], each
   found at its own vertex, and the pairs of the first step too: all
   zeros, in time order */
static void
scenario_two_pairs_in_piece (void)
{
  double y0[2] = { 1, 0 };
  sym_stats stats;
  int st;
  st = drv_run_events (ev_two_peaks, 2, NULL, 3, 0.0, y0, &stats);
  const double a = acos (0.9999), c = 0.05;
  const double tz[7] = { a, c - a, c + a, 2 * M_PI - a, 2 * M_PI + a,
                         2 * M_PI + c - a, 2 * M_PI + c + a };
  const int iz[7] = { 0, 1, 1, 0, 0, 1, 1 };
  double err = 0;
  int same = SINK.nev == 7;
  for (int i = 0; i < SINK.nev && i < 7; i++)
    {
      err = fmax (err, fabs (SINK.te[i] - tz[i]));
      same &= SINK.ie[i] == iz[i];
    }
  CHECK (st == SYM_DONE && same && err < 1e-12,
         "two pairs in one piece: %s, %d events, error %.3g",
         sym_status_name (st), SINK.nev, err);
}

/* a terminal event on a sample point and another two ulps after it, in
   the next piece: both reported at the stop, as within one piece */
static void
scenario_terminal_on_sample (void)
{
  double y0[2] = { 1, 0 };
  sym_stats stats;
  int st;
  st = drv_run_events (ev_at_sample, 2, NULL, 3, 0.0, y0, &stats);
  CHECK (st == SYM_STOP_EVENT && SINK.nev == 2 && SINK.te[0] == 1.125
         && SINK.ie[1] == 1 && fabs (SINK.te[1] - 1.125) < 1e-15
         && stats.t_reached == 1.125,
         "terminal event on a sample point: %s, %d events",
         sym_status_name (st), SINK.nev);
}

/* two events that vanish together: both are reported at the stop,
   whichever of them is terminal, and no later event */
static void
scenario_twin_events (void)
{
  drv_run r;
  double y0[2] = { 1, 0 };
  int st;
  static const int flags[3][2] = { { 1, 0 }, { 0, 1 }, { 1, 1 } };
  for (int f = 0; f < 3; f++)
    {
      drv_setup (&r);
      r.o.h_fixed = 0.3;
      r.o.nevents = 2;
      r.o.events = ev_twin;
      r.o.event_user = (void *) flags[f];
      st = drv_integrate (&r, &drv_exact_type, y0);
      CHECK (st == SYM_STOP_EVENT, "twin events %d: status %s", f,
             sym_status_name (st));
      CHECK (SINK.nev == 2 && SINK.ie[0] == 0 && SINK.ie[1] == 1,
             "twin events %d: %d events, ie %d %d", f, SINK.nev, SINK.ie[0],
             SINK.ie[1]);
      CHECK (fabs (SINK.te[0] - M_PI / 2) < 1e-14
             && fabs (SINK.te[1] - M_PI / 2) < 1e-14,
             "twin events %d: te %.17g %.17g", f, SINK.te[0], SINK.te[1]);
      CHECK_CLOSE (SINK.t[SINK.nrows - 1], M_PI / 2, 1e-14,
                   "twin events: last row");
    }
}

int
main (void)
{
  scenario_events_located ();
  scenario_terminal_event ();
  scenario_rising_event ();
  scenario_event_on_step_point ();
  scenario_zero_pair_in_step ();
  scenario_two_pairs_in_piece ();
  scenario_terminal_on_sample ();
  scenario_twin_events ();
  return tu_finish ("test_driver_events");
}
