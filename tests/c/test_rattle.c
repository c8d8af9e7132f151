/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* test_rattle.c -- RATTLE (methods/rattle.c) with C callbacks: the planar
   pendulum in Cartesian coordinates, in the second-order form and with a
   general separable T = |p|^2 / (2 mu) (the differences of f_q), stays on
   g = 0 and G f_q = 0; its angle against the angle form integrated by
   RK4 at a tiny step, order 2; the step by -h undoes a step; the double
   pendulum keeps both rods; bad options are refused; y0 off the
   manifold is projected. */
#include "sym.h"
#include "testutil.h"

#include <string.h>

/* --------------------------------------------------------- systems */
typedef struct {
  int so;          /* y = [q; v], f = [v; a] */
  double mu;       /* the mass of T = |p|^2 / (2 mu) (so: 1) */
  long ncon;
} pend;

/* one mass in the plane under unit gravity: V = mu y */
static int
pend_rhs (double t, const double *y, double *dy, void *u)
{
  (void) t;
  const pend *P = u;
  dy[0] = y[2] / P->mu;
  dy[1] = y[3] / P->mu;
  dy[2] = 0.0;
  dy[3] = -P->mu;
  return 0;
}

static int
pend_con (const double *q, double *g, double *G, void *u)
{
  pend *P = u;
  P->ncon++;
  g[0] = q[0] * q[0] + q[1] * q[1] - 1.0;
  if (G)
    {
      G[0] = 2.0 * q[0];
      G[1] = 2.0 * q[1];
    }
  return 0;
}

/* two unit masses on unit rods from the origin: q = [x1 y1 x2 y2] */
static int
dbl_rhs (double t, const double *y, double *dy, void *u)
{
  (void) t;
  (void) u;
  for (int i = 0; i < 4; i++)
    dy[i] = y[4 + i];
  dy[4] = 0.0;
  dy[5] = -1.0;
  dy[6] = 0.0;
  dy[7] = -1.0;
  return 0;
}

static int
dbl_con (const double *q, double *g, double *G, void *u)
{
  (void) u;
  const double dx = q[2] - q[0], dy = q[3] - q[1];
  g[0] = q[0] * q[0] + q[1] * q[1] - 1.0;
  g[1] = dx * dx + dy * dy - 1.0;
  if (G)
    {
      double v[8] = { 2 * q[0], -2 * dx, 2 * q[1], -2 * dy, 0, 2 * dx, 0,
                      2 * dy };
      memcpy (G, v, sizeof v);
    }
  return 0;
}

/* --------------------------------------------------------- sinks */
typedef struct {
  int d;
  double (*check) (const double *y, int d, double *hid);
  double gmax, hmax;    /* the largest |g| and |G f_q| over the rows */
  double last[8];
  long rows;
} sink;

static double
pend_check (const double *y, int d, double *hid)
{
  (void) d;
  *hid = fabs (2 * y[0] * y[2] + 2 * y[1] * y[3]);
  return fabs (y[0] * y[0] + y[1] * y[1] - 1.0);
}

static double
dbl_check (const double *y, int d, double *hid)
{
  (void) d;
  const double dx = y[2] - y[0], dy = y[3] - y[1];
  const double du = y[6] - y[4], dv = y[7] - y[5];
  *hid = fmax (fabs (y[0] * y[4] + y[1] * y[5]), fabs (dx * du + dy * dv));
  return fmax (fabs (y[0] * y[0] + y[1] * y[1] - 1.0),
               fabs (dx * dx + dy * dy - 1.0));
}

static int
sink_row (double t, const double *y, void *u)
{
  (void) t;
  sink *s = u;
  double hid;
  s->gmax = fmax (s->gmax, s->check (y, s->d, &hid));
  s->hmax = fmax (s->hmax, hid);
  memcpy (s->last, y, sizeof (double) * 2 * s->d);
  s->rows++;
  return 0;
}

/* --------------------------------------------------------- runs */
static int
run (const sym_system *sys, sym_onestep_opts *own, sym_constraints *cs,
     double tf, double h, long nsteps, int refine, const double *y0,
     sink *sk)
{
  sym_method_opts mo;
  memset (&mo, 0, sizeof mo);
  mo.own = own;
  mo.constraints = cs;
  sym_driver_opts d;
  memset (&d, 0, sizeof d);
  d.t0 = 0.0;
  d.tf = tf;
  d.h_fixed = h;
  d.nsteps_fixed = nsteps;
  d.refine = refine;
  d.output = sink_row;
  d.output_user = sk;
  sym_stats st;
  return sym_integrate (sym_step_rattle, sys, &mo, &d, y0, &st);
}

/* the angle form th'' = -sin th by RK4 with n steps to T */
static double
angle_ref (double th0, double T, long n)
{
  double x = th0, v = 0.0, h = T / n;
  for (long k = 0; k < n; k++)
    {
      double k1x = v, k1v = -sin (x);
      double k2x = v + 0.5 * h * k1v, k2v = -sin (x + 0.5 * h * k1x);
      double k3x = v + 0.5 * h * k2v, k3v = -sin (x + 0.5 * h * k2x);
      double k4x = v + h * k3v, k4v = -sin (x + h * k3x);
      x += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
      v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    }
  return x;
}

static void
test_pendulum (int so, int has_G)
{
  pend P = { so, so ? 1.0 : 2.0, 0 };
  sym_system sys;
  memset (&sys, 0, sizeof sys);
  sys.dim = 2;
  sys.rhs = pend_rhs;
  sys.user = &P;
  sym_onestep_opts own;
  memset (&own, 0, sizeof own);
  own.separable = 1;
  own.second_order = so;
  sym_constraints cs = { 1, pend_con, has_G, &P };
  const double th0 = 1.0, T = 2.0;
  double y0[4] = { sin (th0), -cos (th0), 0, 0 };
  const double ref = angle_ref (th0, T, 200000);
  double err[3];
  for (int k = 0; k < 3; k++)
    {
      sink sk = { 2, pend_check, 0, 0, { 0 }, 0 };
      const double h = 0.02 / (1 << k);
      int st = run (&sys, &own, &cs, T, h, 0, 1, y0, &sk);
      CHECK (st == SYM_DONE, "so %d: status %d", so, st);
      err[k] = fabs (atan2 (sk.last[0], -sk.last[1]) - ref);
    }
  for (int k = 0; k < 2; k++)
    CHECK (err[k] / err[k + 1] > 3.6 && err[k] / err[k + 1] < 4.4,
           "so %d G %d: error ratio %g (%g, %g)", so, has_G,
           err[k] / err[k + 1], err[k], err[k + 1]);
  /* 1e4 steps: on the manifold at every row */
  sink sk = { 2, pend_check, 0, 0, { 0 }, 0 };
  int st = run (&sys, &own, &cs, 1e3, 0.1, 10000, 1, y0, &sk);
  CHECK (st == SYM_DONE && sk.rows == 10001, "status %d rows %ld", st,
         sk.rows);
  const double tolh = has_G ? 1e-12 : 1e-9;
  CHECK (sk.gmax <= 1e-12 && sk.hmax / P.mu <= tolh,
         "so %d G %d: |g| %g, |G f_q| %g", so, has_G, sk.gmax,
         sk.hmax / P.mu);
  /* 1000 steps forward, then back by -h: y0 again */
  sink fw = { 2, pend_check, 0, 0, { 0 }, 0 };
  st = run (&sys, &own, &cs, 100.0, 0.1, 1000, 1, y0, &fw);
  double y1[4];
  memcpy (y1, fw.last, sizeof y1);
  sink bk = { 2, pend_check, 0, 0, { 0 }, 0 };
  st = run (&sys, &own, &cs, -100.0, 0.1, 1000, 1, y1, &bk);
  double dev = 0.0;
  for (int i = 0; i < 4; i++)
    dev = fmax (dev, fabs (bk.last[i] - y0[i]));
  /* differences of g carry round-off of eps^(2/3) that the way back
     meets at other points */
  CHECK (st == SYM_DONE && dev <= (has_G ? 1e-10 : 1e-9),
         "so %d G %d: back to y0 within %g", so, has_G, dev);
  /* Refine's rows (the dense output) near the manifold */
  sink rf = { 2, pend_check, 0, 0, { 0 }, 0 };
  st = run (&sys, &own, &cs, 10.0, 0.01, 0, 4, y0, &rf);
  CHECK (st == SYM_DONE && rf.rows == 4001 && rf.gmax <= 1e-7,
         "refine: rows %ld, |g| %g", rf.rows, rf.gmax);
}

static void
test_double (void)
{
  sym_system sys;
  memset (&sys, 0, sizeof sys);
  sys.dim = 4;
  sys.rhs = dbl_rhs;
  sym_onestep_opts own;
  memset (&own, 0, sizeof own);
  own.separable = own.second_order = 1;
  sym_constraints cs = { 2, dbl_con, 1, NULL };
  double y0[8] = { 1, 0, 2, 0, 0, 0, 0, 0 };
  sink sk = { 4, dbl_check, 0, 0, { 0 }, 0 };
  int st = run (&sys, &own, &cs, 100.0, 0.01, 10000, 1, y0, &sk);
  CHECK (st == SYM_DONE && sk.gmax <= 1e-12 && sk.hmax <= 1e-12,
         "double: status %d, |g| %g, |G v| %g", st, sk.gmax, sk.hmax);
}

static void
test_bad (void)
{
  pend P = { 1, 1.0, 0 };
  sym_system sys;
  memset (&sys, 0, sizeof sys);
  sys.dim = 2;
  sys.rhs = pend_rhs;
  sys.user = &P;
  sym_onestep_opts own;
  memset (&own, 0, sizeof own);
  double y0[4] = { 1, 0, 0, 0 };
  sym_constraints cs = { 1, pend_con, 1, &P };
  sink sk = { 2, pend_check, 0, 0, { 0 }, 0 };
  /* not separable; no constraints; m >= d */
  CHECK (run (&sys, &own, &cs, 1, 0.1, 0, 1, y0, &sk) == SYM_EBADINPUT,
         "a general H refused");
  own.separable = 1;
  CHECK (run (&sys, &own, NULL, 1, 0.1, 0, 1, y0, &sk) == SYM_EBADINPUT,
         "no constraints refused");
  cs.m = 2;
  CHECK (run (&sys, &own, &cs, 1, 0.1, 0, 1, y0, &sk) == SYM_EBADINPUT,
         "m = d refused");
  cs.m = 1;
  /* adaptive steps: no estimate */
  sym_method_opts mo;
  memset (&mo, 0, sizeof mo);
  mo.own = &own;
  mo.constraints = &cs;
  sym_driver_opts d;
  memset (&d, 0, sizeof d);
  d.tf = 1;
  d.tol.rtol = 1e-3;
  double atol = 1e-6;
  d.tol.atol = &atol;
  d.tol.atol_len = 1;
  d.output = sink_row;
  d.output_user = &sk;
  int st = sym_integrate (sym_step_rattle, &sys, &mo, &d, y0, NULL);
  CHECK (st < 0, "adaptive steps refused: %d", st);
}

static void
test_project (void)
{
  for (int so = 1; so >= 0; so--)
    {
      pend P = { so, so ? 1.0 : 2.0, 0 };
      sym_system sys;
      memset (&sys, 0, sizeof sys);
      sys.dim = 2;
      sys.rhs = pend_rhs;
      sys.user = &P;
      sym_eval ev;
      sym_eval_init (&ev, &sys);
      sym_constraints cs = { 1, pend_con, 0, &P };
      double y[4] = { 0.6, -0.81, 0.3, 0.1 }, dq, dp;
      int st = sym_constraints_project (&cs, &ev, so, 0.0, y, &dq, &dp);
      double hid, g = pend_check (y, 2, &hid);
      CHECK (st == 0 && g <= 1e-14 && hid <= 1e-9 && dq > 1e-3 && dp > 1e-2,
             "project so %d: status %d, g %g, hidden %g, dq %g, dp %g", so,
             st, g, hid, dq, dp);
      /* on the circle's ray, p along its tangent */
      CHECK (fabs (y[1] / y[0] + 0.81 / 0.6) <= 1e-9, "minimum-norm move");
      sym_eval_free (&ev);
    }
}

int
main (void)
{
  test_pendulum (1, 1);
  test_pendulum (0, 1);
  test_pendulum (1, 0);
  test_double ();
  test_bad ();
  test_project ();
  return tu_finish ("test_rattle");
}
