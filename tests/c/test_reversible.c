/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* test_reversible.c -- the reversible step-size control of the driver
   (driver/reversible.c) with the symmetric steppers: a run from the end
   back, its first step the forward run's last, retraces the forward
   steps and returns to y0 to round-off (Stoermer-Verlet explicit,
   second-order and implicit, a composition, odeSPVI's pair (4,3)); a
   density that looks at the past only does not; the energy error of
   Kepler's problem at e = 0.9 stays bounded and beats fixed steps at
   equal calls; the angular momentum is kept to round-off; a density that
   is not positive ends the run with the rows so far. */
#include "se_sv_systems.h"

#define KEP_E 0.9
#define MAXROWS 400000

/* the rows of a run (its step points) */
static double rt[MAXROWS], ry[MAXROWS][4];
static long nrows;

static double kep_h (const double *y);
static double kep_l (const double *y);

/* or, for a long run, the largest errors of the energy over its first
   and last tenths of [0, e_span] and of the angular momentum */
static double e_span, e_h0, e_l0, e_first, e_last, e_l;

static int
sink (double t, const double *y, void *u)
{
  (void) u;
  if (e_span > 0)
    {
      double e = fabs (kep_h (y) - e_h0);
      if (t <= 0.1 * e_span)
        e_first = fmax (e_first, e);
      if (t >= 0.9 * e_span)
        e_last = fmax (e_last, e);
      e_l = fmax (e_l, fabs (kep_l (y) - e_l0));
      return 0;
    }
  if (nrows >= MAXROWS)
    return -1;
  rt[nrows] = t;
  memcpy (ry[nrows], y, 4 * sizeof (double));
  nrows++;
  return 0;
}

/* Kepler's problem, a = 1, from the pericentre; f = [v; a] */
static void
kep_y0 (double *y)
{
  y[0] = 1 - KEP_E;
  y[1] = 0;
  y[2] = 0;
  y[3] = sqrt ((1 + KEP_E) / (1 - KEP_E));
}

static double
kep_h (const double *y)
{
  return 0.5 * (y[2] * y[2] + y[3] * y[3]) - 1 / hypot (y[0], y[1]);
}

static double
kep_l (const double *y)
{
  return y[0] * y[3] - y[1] * y[2];
}

/* the time scale of Kepler's problem: |q|^(-3/2) */
static int
dens_kepler (double t, const double *y, double *rho, void *u)
{
  (void) t;
  (void) u;
  *rho = pow (hypot (y[0], y[1]), -1.5);
  return 0;
}

/* the same density, but of the state of the call before: a control
   that looks at the past only */
static double past_q[2];
static int past_have;

static int
dens_past (double t, const double *y, double *rho, void *u)
{
  (void) t;
  (void) u;
  if (! past_have)
    memcpy (past_q, y, sizeof past_q);
  *rho = pow (hypot (past_q[0], past_q[1]), -1.5);
  memcpy (past_q, y, sizeof past_q);
  past_have = 1;
  return 0;
}

static int
dens_bad (double t, const double *y, double *rho, void *u)
{
  (void) y;
  (void) u;
  *rho = t > 1.0 ? -1.0 : 1.0;
  return 0;
}

typedef struct {
  const char *name;
  const sym_stepper_type *const *type;
  int separable, second_order, method;   /* odeSV's options */
  int spvi;                              /* odeSPVI (4, 3) */
} config;

static const config configs[] = {
  { "verlet, second order", &sym_step_sv, 1, 1, 0, 0 },
  { "verlet, separable", &sym_step_sv, 1, 0, 0, 0 },
  { "verlet, implicit", &sym_step_sv, 0, 0, 0, 0 },
  { "yoshida4, second order", &sym_step_splitting, 1, 1, 1, 0 },
  { "spvi (4, 3)", &sym_step_spvi, 0, 0, 0, 1 },
};

/* one run of config c over [t0, tf] from y0 (rows at the step points);
   h0 the first step (0: found), density NULL: the default */
static int
run (const config *c, double t0, double tf, const double *y0, double rtol,
     double h0, sym_density_fn density, tprob *P, sym_stats *st)
{
  static sym_onestep_opts own;
  static sym_spvi_opts so;
  sym_system sys = tp_system (P, P_KEPLER, 1);
  sym_method_opts mo;
  memset (&mo, 0, sizeof mo);
  memset (&own, 0, sizeof own);
  memset (&so, 0, sizeof so);
  own.separable = c->separable;
  own.second_order = c->second_order;
  own.method = c->method;
  so.q_dofs = 4;
  so.nodes = 3;
  mo.own = c->spvi ? (const void *) &so : (const void *) &own;
  static double atol = 1e-12;
  sym_driver_opts o;
  memset (&o, 0, sizeof o);
  o.t0 = t0;
  o.tf = tf;
  o.refine = 1;
  o.tol.rtol = rtol;
  o.tol.atol = &atol;
  o.tol.atol_len = 1;
  o.h0 = h0;
  o.step_control = SYM_CONTROL_REVERSIBLE;
  o.density = density;
  o.output = sink;
  nrows = 0;
  past_have = 0;
  return sym_integrate (*c->type, &sys, &mo, &o, y0, st);
}

/* Forward over about two periods, again to the last step point but one
   (it ends there unshortened, with the same steps), then back from there
   with that run's last step first: y0 again to round-off, and the steps
   mirrored.  Returns the miss |y_back - y0|. */
static double
reversal (const config *c, double rtol, sym_density_fn density, int verbose)
{
  tprob P;
  sym_stats st;
  double y0[4], yend[4];
  kep_y0 (y0);
  int s = run (c, 0, 4 * M_PI, y0, rtol, 0, density, &P, &st);
  CHECK (s == SYM_DONE && nrows > 20, "%s: forward %d, %ld rows", c->name,
         s, nrows);
  CHECK (st.cnt.nfailed == 0, "%s: %ld failed steps", c->name,
         st.cnt.nfailed);
  const long m = nrows - 1;
  const double tm = rt[m - 1];
  static double t1[MAXROWS];
  memcpy (t1, rt, (size_t) nrows * sizeof (double));
  s = run (c, 0, tm, y0, rtol, 0, density, &P, &st);
  CHECK (s == SYM_DONE && nrows == m && rt[m - 1] == tm,
         "%s: to the step point: %d, %ld rows of %ld", c->name, s, nrows, m);
  for (long k = 0; k < nrows && k < m; k++)
    if (rt[k] != t1[k])
      {
        CHECK (0, "%s: step %ld differs: %.17g vs %.17g", c->name, k, rt[k],
               t1[k]);
        break;
      }
  const double hlast = rt[m - 1] - rt[m - 2];
  memcpy (t1, rt, (size_t) m * sizeof (double));
  memcpy (yend, ry[m - 1], sizeof yend);
  s = run (c, tm, 0, yend, rtol, hlast, density, &P, &st);
  CHECK (s == SYM_DONE && (nrows == m || density == dens_past),
         "%s: back: %d, %ld rows of %ld", c->name, s, nrows, m);
  double mirror = 0, miss = 0;
  for (long k = 1; k < nrows && k < m; k++)
    mirror = fmax (mirror, fabs ((rt[k - 1] - rt[k])
                                 - (t1[m - k] - t1[m - k - 1]))
                           / (t1[m - k] - t1[m - k - 1]));
  for (int i = 0; i < 4; i++)
    miss = fmax (miss, fabs (ry[nrows - 1][i] - y0[i]));
  if (verbose)
    printf ("  %-24s %ld steps: miss %.2e, steps mirrored to %.2e\n",
            c->name, m - 1, miss, mirror);
  if (density != dens_past)
    CHECK (mirror <= 1e-6, "%s: mirrored to %.3g", c->name, mirror);
  return miss;
}

static void
check_reversal (void)
{
  for (size_t k = 0; k < sizeof configs / sizeof *configs; k++)
    {
      const config *c = &configs[k];
      const double rtol = c->spvi ? 1e-6 : 1e-4;
      double miss = reversal (c, rtol, NULL, 1);
      CHECK (miss <= 1e-9, "%s: back to y0 within %.3g", c->name, miss);
      double good = reversal (c, rtol, dens_kepler, 1);
      CHECK (good <= 1e-9, "%s: |q|^-1.5: back within %.3g", c->name, good);
      /* the past-only density: the same steps but one, yet no way back */
      double bad = reversal (c, rtol, dens_past, 1);
      CHECK (bad >= 1e3 * good, "%s: a past-only density returns within "
             "%.3g, against %.3g", c->name, bad, good);
    }
}

/* Kepler e = 0.9 over 1000 periods, Stoermer-Verlet second order: the
   energy error of the last tenth is no larger than that of the first
   (bounded), the angular momentum is kept, and fixed steps with the same
   calls err 10 times more */
static void
check_energy (void)
{
  const config *c = &configs[0];
  const double T = 2 * M_PI * 1000;
  tprob P;
  sym_stats st;
  double y0[4];
  kep_y0 (y0);
  e_span = T;
  e_h0 = kep_h (y0);
  e_l0 = kep_l (y0);
  e_first = e_last = e_l = 0;
  int s = run (c, 0, T, y0, 1e-4, 0, NULL, &P, &st);
  CHECK (s == SYM_DONE, "energy run: %d", s);
  const double first = e_first, last = e_last, dl = e_l;
  const long calls = st.cnt.nrhs;
  /* fixed steps: one call each */
  static sym_onestep_opts own = { 1, 1, 0, 0, 0, 0, NULL };
  sym_system sys = tp_system (&P, P_KEPLER, 0);
  sym_method_opts mo;
  memset (&mo, 0, sizeof mo);
  mo.own = &own;
  sym_driver_opts o;
  memset (&o, 0, sizeof o);
  o.t0 = 0;
  o.tf = T;
  o.refine = 1;
  o.h_fixed = T / (double) calls;
  o.output = sink;
  e_first = e_last = 0;
  sym_stats sf;
  s = sym_integrate (sym_step_sv, &sys, &mo, &o, y0, &sf);
  const double fixed = fmax (e_first, e_last);
  e_span = 0;
  printf ("  energy: first tenth %.3e, last %.3e (%ld steps, %ld calls); "
          "L %.1e; fixed steps (%ld calls) %.3e\n", first, last,
          st.cnt.nsteps, calls, dl, sf.cnt.nrhs, fixed);
  CHECK (s == SYM_DONE && sf.cnt.nrhs <= calls + 2, "fixed: %d, %ld calls",
         s, sf.cnt.nrhs);
  CHECK (last <= 1.5 * first, "energy: last tenth %.3g, first %.3g", last,
         first);
  CHECK (dl <= 1e-11, "angular momentum: %.3g", dl);
  CHECK (fixed >= 10 * fmax (first, last), "fixed steps err %.3g, "
         "reversible %.3g", fixed, fmax (first, last));
}

static void
check_bad_density (void)
{
  tprob P;
  sym_stats st;
  double y0[4];
  kep_y0 (y0);
  int s = run (&configs[0], 0, 4, y0, 1e-4, 0, dens_bad, &P, &st);
  CHECK (s == SYM_EDENSITY && nrows > 1 && rt[nrows - 1] > 1.0
         && rt[nrows - 1] < 4 && st.t_reached == rt[nrows - 1],
         "a negative density: %d, %ld rows to %g", s, nrows,
         nrows ? rt[nrows - 1] : 0.0);
}

int
main (void)
{
  check_reversal ();
  check_energy ();
  check_bad_density ();
  return tu_finish ("test_reversible");
}
