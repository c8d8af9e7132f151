/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* driver_util.h -- what the tests of the driver loop (test_driver_*.c)
   share: two test steppers, so that the driver is tested independently
   of the real methods, the harmonic oscillator, output and event sinks,
   and event functions.
   - "exact": the exact flow of the harmonic oscillator q' = p, p' = -q
     (rotation), with the exact flow as dense output: events and output
     times must then be found to round-off.  Its method options' own
     (an int, or NULL for 0) is the number of event samples inside each
     step it asks of the driver;
   - "midpoint": the explicit midpoint rule (order 2) with the Euler
     step as embedded estimate (err = O(h^2)), cubic Hermite dense
     output.
   It also has an allocator that fails on demand, for the tests of
   allocation failures. */
#ifndef DRIVER_UTIL_H
#define DRIVER_UTIL_H

#include "sym.h"

/* ------------------------------------------------------------ system */
typedef struct {
  double nan_after;   /* rhs returns NaN for t > nan_after */
  long fatal_at;      /* rhs returns -1 on this call number (0: never) */
  long smaller_from;  /* rhs returns 1 (asks for a smaller step) from this
                         call number on (0: never) */
  long calls;
} drv_ho_user;

int drv_ho_rhs (double t, const double *y, double *dy, void *u);

/* ------------------------------------------------------------ steppers */
extern const sym_stepper_type drv_exact_type;
extern const sym_stepper_type drv_mid_type;
/* the least and the largest h the exact stepper was given */
extern double drv_h_least, drv_h_most;

/* ------------------------------------------------------------ sinks */
#define DRV_MAXROWS 200000
typedef struct {
  int nrows;
  double t[DRV_MAXROWS], y[DRV_MAXROWS][2];
  int stop_after;      /* ask to stop after this many rows (0: never) */
  int nev;
  double te[1000];
  int ie[1000];
  double ye[1000][2];
} drv_sink;
/* the rows and events of the last run */
extern drv_sink SINK;

int drv_out_row (double t, const double *y, void *u);
int drv_out_event (double te, const double *ye, int ie, void *u);

/* ------------------------------------------------------------ allocator */
/* For sym_set_allocator: fails allocation number drv_alloc_fail_at (from
   1; 0: none) of those counted in drv_alloc_count, and keeps the number
   of blocks not yet freed in drv_alloc_live */
extern long drv_alloc_count, drv_alloc_live, drv_alloc_fail_at;
void *drv_counting_alloc (size_t nbytes);
void drv_counting_free (void *p);

/* ------------------------------------------------------------ runs */
/* A run of the oscillator and what it found out */
typedef struct {
  sym_system sys;
  drv_ho_user hu;
  sym_driver_opts o;
  sym_method_opts mo;
  sym_stats stats;
  double atol;
} drv_run;

/* from t0 = 0 to tf = 10, one row per step, RelTol 1e-6 and AbsTol 1e-8,
   rows and events into SINK (cleared) */
void drv_setup (drv_run *r);
int drv_integrate (drv_run *r, const sym_stepper_type *type,
                   const double *y0);
/* A fixed-step run (h = 0.5, to tf = 10) of the exact flow from (t0, y)
   with nevents events of ev (user data u), checked at the step points
   and at that many samples inside each step; the events land in SINK */
int drv_run_events (sym_event_fn ev, int nevents, void *u, int samples,
                    double t0, const double *y, sym_stats *stats);

#endif
