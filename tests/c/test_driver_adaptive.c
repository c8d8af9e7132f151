/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* test_driver_adaptive.c -- the driver loop with adaptive steps (the test
   steppers of driver_util.h): tolerances, MaxStep, InitialStep, spans of
   a few ulps, and the step-size control. */
#include "sym.h"
#include "driver_util.h"
#include "driver/driver.h"
#include "testutil.h"

#include <float.h>
#include <string.h>

/* errors shrink with RelTol, steps grow */
static void
scenario_adaptive_tolerances (void)
{
  drv_run r;
  double y0[2] = { 1, 0 };
  double err[3], rt[3] = { 1e-4, 1e-6, 1e-8 };
  long steps[3];
  for (int k = 0; k < 3; k++)
    {
      drv_setup (&r);
      r.o.tol.rtol = rt[k];
      double at = rt[k];
      r.o.tol.atol = &at;
      int st = drv_integrate (&r, &drv_mid_type, y0);
      CHECK (st == SYM_DONE, "adaptive %s", sym_status_name (st));
      err[k] = fabs (SINK.y[SINK.nrows - 1][0] - cos (10.0));
      steps[k] = r.stats.cnt.nsteps;
      CHECK (SINK.t[SINK.nrows - 1] == 10.0, "ends on tf");
    }
  CHECK (err[0] > 5 * err[1] && err[1] > 5 * err[2],
         "errors %.3g %.3g %.3g", err[0], err[1], err[2]);
  CHECK (steps[0] < steps[1] && steps[1] < steps[2], "steps grow");
}

/* MaxStep respected; 0: |tf - t0| / 10; inf: no cap (as 1e300), as in
   ode45 */
static void
scenario_adaptive_hmax (void)
{
  drv_run r;
  double y0[2] = { 1, 0 };
  drv_setup (&r);
  r.o.hmax = 0.05;
  r.o.tol.rtol = 1e-2;
  int st = drv_integrate (&r, &drv_mid_type, y0);
  int ok = 1;
  for (int i = 1; i < SINK.nrows; i++)
    ok &= SINK.t[i] - SINK.t[i - 1] <= 0.05 * (1 + 1e-12);
  CHECK (ok && st == SYM_DONE, "hmax respected");
  double hbig[3], hcap[3] = { 0.0, INFINITY, 1e300 };
  for (int k = 0; k < 3; k++)
    {
      drv_setup (&r);
      r.o.hmax = hcap[k];
      double at = 0.5;
      r.o.tol.rtol = 0.5;
      r.o.tol.atol = &at;
      r.o.tf = 2;
      st = drv_integrate (&r, &drv_mid_type, y0);
      hbig[k] = 0.0;
      for (int i = 1; i < SINK.nrows; i++)
        hbig[k] = fmax (hbig[k], SINK.t[i] - SINK.t[i - 1]);
      CHECK (st == SYM_DONE, "hmax %g: %s", hcap[k], sym_status_name (st));
    }
  CHECK (hbig[0] <= 0.2 * (1 + 1e-12) && hbig[1] > 0.5
         && hbig[2] == hbig[1], "largest steps %.17g %.17g %.17g",
         hbig[0], hbig[1], hbig[2]);
}

/* a too large initial step is rejected and retried; h0 = inf: the first
   step as long as hmax allows, the same run */
static void
scenario_adaptive_h0 (void)
{
  drv_run r;
  double y0[2] = { 1, 0 };
  drv_setup (&r);
  r.o.h0 = 5;
  r.o.hmax = 5;
  int st = drv_integrate (&r, &drv_mid_type, y0);
  CHECK (st == SYM_DONE && r.stats.cnt.nfailed > 0, "rejections %ld",
         r.stats.cnt.nfailed);
  int rows5 = SINK.nrows;
  double t5 = SINK.t[rows5 - 1], y5 = SINK.y[rows5 - 1][0];
  long fail5 = r.stats.cnt.nfailed;
  drv_setup (&r);
  r.o.h0 = INFINITY;
  r.o.hmax = 5;
  st = drv_integrate (&r, &drv_mid_type, y0);
  CHECK (st == SYM_DONE && SINK.nrows == rows5
         && SINK.t[SINK.nrows - 1] == t5 && SINK.y[SINK.nrows - 1][0] == y5
         && r.stats.cnt.nfailed == fail5,
         "h0 = inf: %s, %d rows, %ld failed (h0 = 5: %d, %ld)",
         sym_status_name (st), SINK.nrows, r.stats.cnt.nfailed, rows5,
         fail5);
}

static void
scenario_adaptive_backward (void)
{
  drv_run r;
  double y0[2] = { 1, 0 };
  drv_setup (&r);
  r.o.tf = -10;
  int st = drv_integrate (&r, &drv_mid_type, y0);
  CHECK (st == SYM_DONE && SINK.t[SINK.nrows - 1] == -10.0,
         "backward adaptive");
  CHECK (fabs (SINK.y[SINK.nrows - 1][0] - cos (10.0)) < 1e-3, "value");
}

/* adaptive steps that MaxStep caps all along, where it divides the
   span: N steps, none a sliver (t summed plainly left the round-off it
   gathered for a step of its own) */
static void
scenario_maxstep_divides_span (void)
{
  drv_run r;
  double y0[2] = { 1, 0 };
  int st;
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
            drv_setup (&r);
            r.o.t0 = t0s[a];
            r.o.tf = t0s[a] + dir * spans[b];
            r.o.hmax = spans[b] / (double) Ns[c];
            r.o.h0 = r.o.hmax;
            r.o.tol.rtol = 1.0;       /* so that MaxStep binds (the pretend */
            r.o.tol.atol = &loose;    /* error is 1e-3 h^3) */
            st = drv_integrate (&r, &drv_exact_type, y0);
            double least = INFINITY;
            for (int i = 1; i < SINK.nrows; i++)
              least = fmin (least, fabs (SINK.t[i] - SINK.t[i - 1]));
            runs++;
            if (st != SYM_DONE || SINK.nrows != Ns[c] + 1
                || SINK.t[SINK.nrows - 1] != r.o.tf || least < 0.5 * r.o.hmax)
              {
                if (bad++ < 5)
                  printf ("  t0 %g, tf %.17g, N %ld: %s, %d rows, least "
                          "step %.3g of %.3g\n", r.o.t0, r.o.tf, Ns[c],
                          sym_status_name (st), SINK.nrows, least, r.o.hmax);
              }
          }
  CHECK (bad == 0, "MaxStep dividing the span: %d of %d runs with a "
         "step too many or too short", bad, runs);
  /* a MaxStep short of dividing the span by less than the least step
     (16 ulps of t): what is left joins the last step.  At t = 1e8,
     1000 steps of 1e-3 (1 - 2e-8) leave 2e-8, 1 to 2 ulps there. */
  drv_setup (&r);
  r.o.t0 = 1e8;
  r.o.tf = 1e8 + 1;
  r.o.hmax = 1e-3 * (1 - 2e-8);
  r.o.h0 = r.o.hmax;
  r.o.tol.rtol = 1.0;
  r.o.tol.atol = &loose;
  st = drv_integrate (&r, &drv_exact_type, y0);
  CHECK (st == SYM_DONE && SINK.nrows == 1001 && SINK.t[1000] == r.o.tf,
         "a remainder below the least step: %d rows", SINK.nrows);
}

/* spans of a few ulps of t: steps below the least step (16 ulps of t)
   that the default MaxStep (span/10) asks for are raised to it, and the
   run reaches tf; a MaxStep set below it ends the run at once */
static void
scenario_tiny_spans (void)
{
  drv_run r;
  double y0[2] = { 1, 0 };
  int st;
  const double spans[][2] = { { 1, 1 + 1e-14 }, { 1e6, 1e6 + 1e-8 },
                              { 1, 1 + 2 * DBL_EPSILON },
                              { -2, -2 - 1e-13 } };
  for (size_t i = 0; i < sizeof spans / sizeof spans[0]; i++)
    {
      drv_setup (&r);
      r.o.t0 = spans[i][0];
      r.o.tf = spans[i][1];
      st = drv_integrate (&r, &drv_exact_type, y0);
      CHECK (st == SYM_DONE && r.stats.t_reached == r.o.tf
             && SINK.t[SINK.nrows - 1] == r.o.tf && SINK.nrows >= 2
             && SINK.nrows <= 12,
             "span [%.17g, %.17g]: %s, %d rows", r.o.t0, r.o.tf,
             sym_status_name (st), SINK.nrows);
    }
  drv_setup (&r);
  r.o.t0 = 1;
  r.o.tf = 2;
  r.o.hmax = 1e-20;
  st = drv_integrate (&r, &drv_exact_type, y0);
  CHECK (st == SYM_ESTEPSIZE && SINK.nrows == 1 && r.stats.t_reached == 1,
         "MaxStep below the least step: %s, %d rows",
         sym_status_name (st), SINK.nrows);
}

/* q' = p/t, p' = -q/t: singular at t = 0 */
static int
rhs_over_t (double t, const double *y, double *dy, void *u)
{
  (void) u;
  dy[0] = y[1] / t;
  dy[1] = -y[0] / t;
  return 0;
}

/* q' = 1e10/t for t > 0: a step from 0 fails at every size */
static int
rhs_fails_always (double t, const double *y, double *dy, void *u)
{
  (void) y;
  (void) u;
  dy[0] = t > 0 ? 1e10 / t : 0.0;
  dy[1] = 0.0;
  return 0;
}

/* the step floor (4 ulps of the span): a run creeping towards a
   singularity at tf stops close to it with SYM_ESTEPSIZE; a step that
   fails at every size fails at most about 52 times (each failure after
   the first halves h) */
static void
scenario_step_floor (void)
{
  drv_run r;
  double y0[2] = { 1, 0 };
  drv_setup (&r);
  r.sys.rhs = rhs_over_t;
  r.o.t0 = -1;
  r.o.tf = 0;
  int st = drv_integrate (&r, &drv_mid_type, y0);
  CHECK (st == SYM_ESTEPSIZE && r.stats.t_reached < 0
         && r.stats.t_reached > -1e-10 && r.stats.cnt.nsteps < 100000,
         "creeping to 0: %s at t = %.3g after %ld steps",
         sym_status_name (st), r.stats.t_reached, r.stats.cnt.nsteps);
  double z[2] = { 0, 0 };
  drv_setup (&r);
  r.sys.rhs = rhs_fails_always;
  r.o.tf = 1;
  r.o.h0 = 1;
  st = drv_integrate (&r, &drv_mid_type, z);
  CHECK (st == SYM_ESTEPSIZE && r.stats.cnt.nsteps == 0
         && r.stats.cnt.nfailed >= 10 && r.stats.cnt.nfailed <= 53,
         "failing at every size: %s after %ld failed steps",
         sym_status_name (st), r.stats.cnt.nfailed);
}

/* predictive step-size control (control.c).  A model error that grows
   along the run by g per step at a fixed h: err_n = c g^n h_n^(q+1).
   After two accepted steps the predicted factor meets it exactly: the
   next error is safety^(q+1) = 0.9^7 for q = 6, where the standard
   factor alone gives g times that, a failed step for g = 4. */
static void
scenario_predictive_control (void)
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

int
main (void)
{
  scenario_adaptive_tolerances ();
  scenario_adaptive_hmax ();
  scenario_adaptive_h0 ();
  scenario_adaptive_backward ();
  scenario_maxstep_divides_span ();
  scenario_tiny_spans ();
  scenario_step_floor ();
  scenario_predictive_control ();
  return tu_finish ("test_driver_adaptive");
}
