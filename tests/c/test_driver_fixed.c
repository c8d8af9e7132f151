/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* test_driver_fixed.c -- the driver loop with fixed steps (the test
   steppers of driver_util.h): the steps' times, TimeStepNumber, output
   times, refine, failures, stops and bad input. */
#include "sym.h"
#include "driver_util.h"
#include "testutil.h"

#include <float.h>
#include <math.h>
#include <string.h>

/* fixed step, h not dividing the interval: the last step ends on tf */
static void
scenario_fixed_last_step_on_tf (void)
{
  drv_run r;
  double y0[2] = { 1, 0 };
  int st;
  drv_setup (&r);
  r.o.h_fixed = 0.3;
  const sym_system s0 = r.sys;
  st = drv_integrate (&r, &drv_exact_type, y0);
  CHECK (st == SYM_DONE, "status %s", sym_status_name (st));
  /* the run's sizes for the finite differences were its own */
  CHECK (r.sys.dim == s0.dim && r.sys.rhs == s0.rhs
         && r.sys.rhs_batch == s0.rhs_batch && r.sys.jac == s0.jac
         && r.sys.rhs_jac == s0.rhs_jac && r.sys.user == s0.user,
         "system untouched");
  CHECK (SINK.nrows == 35, "rows %d", SINK.nrows);  /* ceil(10/0.3) steps */
  CHECK (SINK.t[SINK.nrows - 1] == 10.0, "last t %.17g",
         SINK.t[SINK.nrows - 1]);
  CHECK_CLOSE (SINK.t[10], 3.0, 1e-15, "t_10 = t0 + 10 h, not accumulated");
  CHECK_CLOSE (SINK.y[SINK.nrows - 1][0], cos (10.0), 1e-13, "exact flow");
  CHECK (r.stats.cnt.nsteps == 34, "nsteps %ld", r.stats.cnt.nsteps);
  CHECK (r.stats.t_reached == 10.0, "t reached");
}

/* far from t = 0 every fixed step is h itself; the rows are at t0 + k h
   rounded once.  The steps were the differences of those times, which
   vary there by the round-off of t (here by up to 1.5e-6 h).  A last
   step that h does not fit takes what is left. */
static void
scenario_fixed_far_from_zero (void)
{
  drv_run r;
  double y0[2] = { 1, 0 };
  int st;
  for (int part = 0; part < 2; part++)
    {
      drv_setup (&r);
      r.o.t0 = 1e8;
      r.o.tf = 1e8 + (part ? 10.005 : 10.0);
      r.o.h_fixed = 0.01;
      drv_h_least = INFINITY;
      drv_h_most = 0;
      st = drv_integrate (&r, &drv_exact_type, y0);
      CHECK (st == SYM_DONE && SINK.nrows == 1001 + part
             && SINK.t[1000 + part] == r.o.tf, "rows %d", SINK.nrows);
      CHECK (drv_h_most == 0.01
             && drv_h_least == (part ? (1e8 + 10.005) - (1e8 + 10.0) : 0.01),
             "steps %.17g to %.17g", drv_h_least, drv_h_most);
      int on_grid = 1;
      for (int k = 0; k < 1001; k++)
        on_grid &= SINK.t[k] == 1e8 + 0.01 * k;
      CHECK (on_grid, "rows at t0 + k h");
      CHECK_CLOSE (SINK.y[1000][0], cos (10.0), 1e-12, "exact flow over h");
    }
}

/* fixed step, h dividing the interval up to rounding: no tiny step */
static void
scenario_fixed_dividing_span (void)
{
  drv_run r;
  double y0[2] = { 1, 0 };
  int st;
  drv_setup (&r);
  r.o.h_fixed = 0.1;
  st = drv_integrate (&r, &drv_exact_type, y0);
  CHECK (st == SYM_DONE && SINK.nrows == 101, "rows %d", SINK.nrows);
}

/* TimeStepNumber with TimeStepSize: exactly N steps from t0 */
static void
scenario_time_step_number (void)
{
  drv_run r;
  double y0[2] = { 1, 0 };
  int st;
  drv_setup (&r);
  r.o.h_fixed = 0.25;
  r.o.nsteps_fixed = 7;
  st = drv_integrate (&r, &drv_exact_type, y0);
  CHECK (st == SYM_DONE && SINK.nrows == 8 && SINK.t[7] == 1.75,
         "rows %d, t %.17g", SINK.nrows, SINK.t[7]);
  /* N h = 3 * 0.7 rounds to 2.0999999999999996: the run ends on the
     time it stands for, tf or an output time, and emits its row there;
     a real shortfall is kept */
  drv_setup (&r);
  r.o.h_fixed = 0.7;
  r.o.nsteps_fixed = 3;
  r.o.tf = 2.1;
  CHECK (3 * 0.7 != 2.1 && sym_fixed_end (&r.o) == 2.1, "end %.17g",
         sym_fixed_end (&r.o));
  double touts[3] = { 0, 1, 2.1 };
  r.o.tf = 5;
  r.o.tout = touts;
  r.o.ntout = 3;
  CHECK (sym_fixed_end (&r.o) == 2.1, "end at an output time");
  st = drv_integrate (&r, &drv_exact_type, y0);
  CHECK (st == SYM_DONE && SINK.nrows == 3 && SINK.t[2] == 2.1
         && r.stats.t_reached == 2.1,
         "rows %d, t reached %.17g", SINK.nrows, r.stats.t_reached);
  touts[2] = 2.1 + 1e-13;
  CHECK (sym_fixed_end (&r.o) == 3 * 0.7, "a real shortfall: %.17g",
         sym_fixed_end (&r.o));
  r.o.t0 = 0;
  r.o.tf = -2.1;
  r.o.ntout = 2;
  CHECK (sym_fixed_end (&r.o) == -2.1, "backward");
  r.o.tf = -3;
  CHECK (sym_fixed_end (&r.o) == -3 * 0.7, "backward, tf beyond");
  r.o.nsteps_fixed = 0;
  CHECK (sym_fixed_end (&r.o) == -3, "no TimeStepNumber: tf");

  /* TimeStepNumber alone: N equal steps over tspan */
  drv_setup (&r);
  r.o.nsteps_fixed = 40;
  st = drv_integrate (&r, &drv_exact_type, y0);
  CHECK (st == SYM_DONE && SINK.nrows == 41 && SINK.t[40] == 10.0
         && SINK.t[4] == 1.0, "rows %d", SINK.nrows);
}

/* backward */
static void
scenario_fixed_backward (void)
{
  drv_run r;
  double y0[2] = { 1, 0 };
  int st;
  drv_setup (&r);
  r.o.t0 = 1;
  r.o.tf = -2;
  r.o.h_fixed = 0.5;
  st = drv_integrate (&r, &drv_exact_type, y0);
  CHECK (st == SYM_DONE && SINK.nrows == 7 && SINK.t[6] == -2
         && SINK.t[1] == 0.5,
         "backward rows %d", SINK.nrows);
  CHECK_CLOSE (SINK.y[6][0], cos (-3.0), 1e-13, "backward exact");
}

/* output times: rows exactly there, from the dense output, steps not
   shortened (number of steps unchanged) */
static void
scenario_output_times (void)
{
  drv_run r;
  double y0[2] = { 1, 0 };
  int st;
  double tout[101];
  for (int i = 0; i <= 100; i++)
    tout[i] = 0.1 * i + (i > 0 && i < 100 ? 0.01234 : 0);
  drv_setup (&r);
  r.o.h_fixed = 0.3;
  r.o.tout = tout;
  r.o.ntout = 101;
  st = drv_integrate (&r, &drv_exact_type, y0);
  CHECK (st == SYM_DONE && SINK.nrows == 101, "rows %d", SINK.nrows);
  CHECK (r.stats.cnt.nsteps == 34, "steps %ld", r.stats.cnt.nsteps);
  double maxerr = 0;
  int exact_t = 1;
  for (int i = 0; i < SINK.nrows; i++)
    {
      maxerr = fmax (maxerr, fabs (SINK.y[i][0] - cos (tout[i])));
      exact_t &= SINK.t[i] == tout[i];
    }
  CHECK (exact_t, "output at the requested times");
  CHECK (maxerr < 1e-13, "dense error %.3g", maxerr);
}

/* refine: refine rows per step */
static void
scenario_refine (void)
{
  drv_run r;
  double y0[2] = { 1, 0 };
  int st;
  drv_setup (&r);
  r.o.h_fixed = 0.5;
  r.o.refine = 4;
  st = drv_integrate (&r, &drv_exact_type, y0);
  CHECK (st == SYM_DONE && SINK.nrows == 20 * 4 + 1, "rows %d", SINK.nrows);
  CHECK_CLOSE (SINK.t[1], 0.125, 1e-15, "refined time");
  CHECK_CLOSE (SINK.y[1][0], cos (0.125), 1e-14, "refined value");
}

/* NaN after t = 1: adaptive gives up with ENONFINITE, rows up to ~1 */
static void
scenario_nonfinite (void)
{
  drv_run r;
  double y0[2] = { 1, 0 };
  int st;
  drv_setup (&r);
  r.hu.nan_after = 1.0;
  st = drv_integrate (&r, &drv_mid_type, y0);
  CHECK (st == SYM_ENONFINITE, "status %s", sym_status_name (st));
  CHECK (SINK.t[SINK.nrows - 1] <= 1.0 && SINK.t[SINK.nrows - 1] > 0.99,
         "last row at %.17g", SINK.t[SINK.nrows - 1]);
  int finite = 1;
  for (int i = 0; i < SINK.nrows; i++)
    finite &= isfinite (SINK.y[i][0]) && isfinite (SINK.y[i][1]);
  CHECK (finite, "rows finite");
  /* fixed: fails at once, at the step to 1.1 (rows t = 0, ..., 1) */
  drv_setup (&r);
  r.hu.nan_after = 1.0;
  r.o.h_fixed = 0.1;
  st = drv_integrate (&r, &drv_exact_type, y0);
  CHECK (st == SYM_ENONFINITE && SINK.nrows == 11, "fixed NaN: %s, %d rows",
         sym_status_name (st), SINK.nrows);
}

/* a fatal callback status stops the run with SYM_ECALLBACK */
static void
scenario_fatal_callback (void)
{
  drv_run r;
  double y0[2] = { 1, 0 };
  int st;
  drv_setup (&r);
  r.hu.fatal_at = 30;
  r.o.h_fixed = 0.1;
  st = drv_integrate (&r, &drv_exact_type, y0);
  CHECK (st == SYM_ECALLBACK && SINK.nrows == 30, "fatal: %s rows %d",
         sym_status_name (st), SINK.nrows);
}

/* the output sink asks to stop */
static void
scenario_output_stop (void)
{
  drv_run r;
  double y0[2] = { 1, 0 };
  int st;
  drv_setup (&r);
  SINK.stop_after = 5;
  r.o.h_fixed = 0.1;
  st = drv_integrate (&r, &drv_exact_type, y0);
  CHECK (st == SYM_STOP_OUTPUT && SINK.nrows == 5, "stop: %s rows %d",
         sym_status_name (st), SINK.nrows);
}

/* bad input */
static void
scenario_bad_input (void)
{
  drv_run r;
  double y0[2] = { 1, 0 };
  drv_setup (&r);
  r.o.tf = 0;
  CHECK (drv_integrate (&r, &drv_exact_type, y0) == SYM_EBADINPUT,
         "t0 == tf refused");
  drv_setup (&r);
  r.o.tol.rtol = 0;
  CHECK (drv_integrate (&r, &drv_exact_type, y0) == SYM_EBADINPUT,
         "rtol 0 refused");
  /* an AbsTol of another length than 1 or n (read past its end before),
     or not positive */
  const double atol2[2] = { 1e-6, 0.0 };
  drv_setup (&r);
  r.o.tol.atol = atol2;
  r.sys.dim = 2;
  r.o.tol.atol_len = 3;
  CHECK (drv_integrate (&r, &drv_mid_type, y0) == SYM_EBADINPUT,
         "atol_len 3 with n = 4 refused");
  drv_setup (&r);
  r.o.tol.atol = atol2;
  r.o.tol.atol_len = 2;
  CHECK (drv_integrate (&r, &drv_mid_type, y0) == SYM_EBADINPUT,
         "an AbsTol of 0 refused");
  /* a fixed step of more than SYM_MAX_STEPS steps: refused (the count
     overflowed to one step over the whole span) */
  drv_setup (&r);
  r.o.h_fixed = 1e-300;
  CHECK (drv_integrate (&r, &drv_mid_type, y0)
         == SYM_EBADINPUT && SINK.nrows == 0, "h_fixed 1e-300 refused: %d "
         "rows", SINK.nrows);
}

/* a callback that asks for a smaller step where there is none: a
   callback failure, not a step size that fell below round-off */
static void
scenario_smaller_step_where_none (void)
{
  drv_run r;
  double y0[2] = { 1, 0 };
  int st;
  for (int k = 0; k < 2; k++)
    {
      drv_setup (&r);
      r.o.h_fixed = k ? 0.1 : 0.0;
      r.hu.smaller_from = k ? 10 : 1;
      st = drv_integrate (&r, &drv_mid_type, y0);
      CHECK (st == SYM_ECALLBACK, "%s: a callback asking for a smaller "
             "step: %s", k ? "fixed step" : "adaptive, at t0",
             sym_status_name (st));
    }
}

/* A run that goes on from step k0 of an earlier run's grid (a sol as Y0):
   from the step point before the earlier run's shortened last step, its
   rows are those of the run over the whole span, to the bit; the stats
   say where to go on from.  A reversible run started with the density
   the earlier run's last step had takes the whole run's next step. */
static void
scenario_continue_on_grid (void)
{
  static double tw[4000], yw[4000][2];
  drv_run r;
  double y0[2] = { 1, 0 };
  int st, nw;
  drv_setup (&r);
  r.o.h_fixed = 0.1;
  r.o.tf = 23.45;
  st = drv_integrate (&r, &drv_mid_type, y0);
  nw = SINK.nrows;
  memcpy (tw, SINK.t, sizeof (double) * (size_t) nw);
  memcpy (yw, SINK.y, sizeof (double) * 2 * (size_t) nw);
  drv_setup (&r);
  r.o.h_fixed = 0.1;
  r.o.tf = 10.05;
  st = drv_integrate (&r, &drv_mid_type, y0);
  CHECK (st == SYM_DONE && r.stats.restart_h == 0.1
         && r.stats.restart_t0 == 0 && r.stats.restart_k == 101
         && SINK.nrows == 102, "restart h %g t0 %g k %ld, rows %d",
         r.stats.restart_h, r.stats.restart_t0, r.stats.restart_k,
         SINK.nrows);
  double yk[2] = { SINK.y[100][0], SINK.y[100][1] };
  const double tk = SINK.t[100];
  drv_setup (&r);
  r.o.h_fixed = 0.1;
  r.o.t0 = tk;
  r.o.tf = 23.45;
  r.o.k0 = 100;
  r.o.grid_t0 = 0;
  st = drv_integrate (&r, &drv_mid_type, yk);
  int same = st == SYM_DONE && SINK.nrows == nw - 100;
  for (int i = 0; same && i < SINK.nrows; i++)
    same = SINK.t[i] == tw[100 + i] && SINK.y[i][0] == yw[100 + i][0]
           && SINK.y[i][1] == yw[100 + i][1];
  CHECK (same, "continued on the grid: the whole run's rows (%d of %d)",
         SINK.nrows, nw - 100);
  CHECK (r.stats.restart_k == nw - 1, "k counted from the grid's origin");
  /* not on the grid, or not fixed steps: bad input */
  for (int k = 0; k < 3; k++)
    {
      drv_setup (&r);
      r.o.h_fixed = k == 2 ? 0 : 0.1;
      r.o.nsteps_fixed = k == 1 ? 50 : 0;
      r.o.t0 = k == 0 ? nextafter (tk, 0) : tk;
      r.o.tf = 23.45;
      r.o.k0 = 100;
      st = drv_integrate (&r, &drv_mid_type, yk);
      CHECK (st == SYM_EBADINPUT, "k0 with %s: %s", k == 0 ? "t0 off the "
             "grid" : k == 1 ? "TimeStepNumber" : "adaptive steps",
             sym_status_name (st));
    }
  /* reversible: the density of the last step */
  drv_setup (&r);
  r.o.step_control = SYM_CONTROL_REVERSIBLE;
  r.o.tol.rtol = 1e-4;
  r.o.tf = 20;
  st = drv_integrate (&r, &drv_mid_type, y0);
  nw = SINK.nrows;
  memcpy (tw, SINK.t, sizeof (double) * (size_t) (nw < 4000 ? nw : 4000));
  drv_setup (&r);
  r.o.step_control = SYM_CONTROL_REVERSIBLE;
  r.o.tol.rtol = 1e-4;
  st = drv_integrate (&r, &drv_mid_type, y0);
  const int n = SINK.nrows;
  CHECK (st == SYM_DONE && n >= 4 && n < 4000 && r.stats.restart_rho[0] > 0
         && r.stats.restart_rho[1] > 0, "reversible: rows %d, rho %g %g", n,
         r.stats.restart_rho[0], r.stats.restart_rho[1]);
  const double rho = r.stats.restart_rho[1];
  double ym[2] = { SINK.y[n - 2][0], SINK.y[n - 2][1] };
  drv_setup (&r);
  r.o.step_control = SYM_CONTROL_REVERSIBLE;
  r.o.tol.rtol = 1e-4;
  r.o.t0 = tw[n - 2];
  r.o.tf = 20;
  r.o.rho0 = rho;
  st = drv_integrate (&r, &drv_mid_type, ym);
  CHECK (st == SYM_DONE && SINK.nrows > 2
         && fabs (SINK.t[1] - tw[n - 1]) <= 1e-12 * 20
         && fabs (SINK.t[2] - tw[n]) <= 1e-12 * 20,
         "reversible, rho0: the whole run's steps (%.17g %.17g)",
         SINK.t[1], tw[n - 1]);
}

int
main (void)
{
  scenario_fixed_last_step_on_tf ();
  scenario_fixed_far_from_zero ();
  scenario_fixed_dividing_span ();
  scenario_time_step_number ();
  scenario_fixed_backward ();
  scenario_output_times ();
  scenario_refine ();
  scenario_nonfinite ();
  scenario_fatal_callback ();
  scenario_output_stop ();
  scenario_bad_input ();
  scenario_smaller_step_where_none ();
  scenario_continue_on_grid ();
  return tu_finish ("test_driver_fixed");
}
