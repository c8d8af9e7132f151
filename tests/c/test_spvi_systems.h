/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* test_spvi_systems.h -- test systems (analytic f and Df), an exact
   pendulum solution, a fixed-step loop and failure injection for the
   tests of the SPVI stepper (test_spvi*.c).  Header-only (static inline),
   so that it is not a helper linked into every test. */
#ifndef TEST_SPVI_SYSTEMS_H
#define TEST_SPVI_SYSTEMS_H

#include "sym.h"

#include <float.h>
#include <math.h>
#include <string.h>

#define TS_PI 3.14159265358979323846

/* ---------------------------------------------------------------- user */
/* Failure injection: the call number fail_at (counting every state the
   rhs evaluates, from 1) returns NaN (mode 0), +1 (mode 1) or -1
   (mode 2); jac_fail_at likewise for the Jacobian. */
typedef struct {
  long calls, jcalls;
  long fail_at, jac_fail_at;
  int mode, jac_mode;
  double gamma;        /* damping -gamma p (non-Hamiltonian variant) */
} ts_user;

static inline int
ts_inject (ts_user *u, double *dy, int n)
{
  if (! u)
    return 0;
  u->calls++;
  if (u->fail_at > 0 && u->calls == u->fail_at)
    {
      if (u->mode == 0)
        {
          dy[n - 1] = NAN;
          return 0;
        }
      return u->mode == 1 ? 1 : -1;
    }
  return 0;
}

static inline int
ts_inject_jac (ts_user *u)
{
  if (! u)
    return 0;
  u->jcalls++;
  if (u->jac_fail_at > 0 && u->jcalls == u->jac_fail_at)
    return u->jac_mode == 1 ? 1 : -1;
  return 0;
}

/* Df = J Hess(H) for d dimensions, Hess column-major 2d x 2d:
   rows q: Hess_pq, Hess_pp; rows p: -Hess_qq, -Hess_qp. */
static inline void
ts_df_from_hess (int d, const double *hs, double *df)
{
  int nn = 2 * d;
  for (int c = 0; c < nn; c++)
    for (int r = 0; r < d; r++)
      {
        df[r + c * nn] = hs[(d + r) + c * nn];
        df[(d + r) + c * nn] = -hs[r + c * nn];
      }
}

/* ---------------------------------------------------------------- pendulum
   H = p^2/2 - cos q */
static inline int
ts_pend (double t, const double *y, double *dy, void *user)
{
  (void) t;
  ts_user *u = user;
  dy[0] = y[1];
  dy[1] = -sin (y[0]) - (u ? u->gamma * y[1] : 0.0);
  return ts_inject (u, dy, 2);
}

static inline int
ts_pend_jac (double t, const double *y, double *df, void *user)
{
  (void) t;
  ts_user *u = user;
  df[0] = 0.0;
  df[1] = -cos (y[0]);
  df[2] = 1.0;
  df[3] = u ? -u->gamma : 0.0;
  return ts_inject_jac (u);
}

static inline int
ts_pend_batch (int k, const double *t, const double *y, double *dy,
               void *user)
{
  for (int j = 0; j < k; j++)
    {
      int st = ts_pend (t[j], y + 2 * j, dy + 2 * j, user);
      if (st)
        return st;
    }
  return 0;
}

/* ---------------------------------------------------------------- oscillator
   H = (p^2 + q^2)/2, any d */
static inline int
ts_osc (double t, const double *y, double *dy, void *user)
{
  (void) t;
  (void) user;
  dy[0] = y[1];
  dy[1] = -y[0];
  return 0;
}

static inline int
ts_osc_jac (double t, const double *y, double *df, void *user)
{
  (void) t;
  (void) y;
  (void) user;
  df[0] = 0.0;
  df[1] = -1.0;
  df[2] = 1.0;
  df[3] = 0.0;
  return 0;
}

/* ------------------------------------------------------- nonseparable, d = 1
   H = p^2 (1 + q^2)/2 + q^2/2 */
static inline int
ts_ns1 (double t, const double *y, double *dy, void *user)
{
  (void) t;
  double q = y[0], p = y[1];
  dy[0] = p * (1.0 + q * q);
  dy[1] = -(p * p * q + q);
  return ts_inject (user, dy, 2);
}

static inline int
ts_ns1_jac (double t, const double *y, double *df, void *user)
{
  (void) t;
  double q = y[0], p = y[1];
  df[0] = 2.0 * p * q;
  df[1] = -(p * p + 1.0);
  df[2] = 1.0 + q * q;
  df[3] = -2.0 * p * q;
  return ts_inject_jac (user);
}

/* ------------------------------------------------------- nonseparable, d = 2
   H = |p|^2/2 + |q|^2/2 + c (p1 q2)^2 + s q1^2 q2,  c = 0.5, s = 0.3 */
#define TS_NS2_C 0.5
#define TS_NS2_S 0.3
static inline int
ts_ns2 (double t, const double *y, double *dy, void *user)
{
  (void) t;
  const double c = TS_NS2_C, s = TS_NS2_S;
  double q1 = y[0], q2 = y[1], p1 = y[2], p2 = y[3];
  dy[0] = p1 + 2.0 * c * p1 * q2 * q2;
  dy[1] = p2;
  dy[2] = -(q1 + 2.0 * s * q1 * q2);
  dy[3] = -(q2 + 2.0 * c * p1 * p1 * q2 + s * q1 * q1);
  return ts_inject (user, dy, 4);
}

static inline int
ts_ns2_jac (double t, const double *y, double *df, void *user)
{
  (void) t;
  const double c = TS_NS2_C, s = TS_NS2_S;
  double q1 = y[0], q2 = y[1], p1 = y[2];
  double hs[16] = { 0 };
#define HS(i, j) hs[(i) + 4 * (j)]
  HS (0, 0) = 1.0 + 2.0 * s * q2;
  HS (0, 1) = HS (1, 0) = 2.0 * s * q1;
  HS (1, 1) = 1.0 + 2.0 * c * p1 * p1;
  HS (1, 2) = HS (2, 1) = 4.0 * c * p1 * q2;
  HS (2, 2) = 1.0 + 2.0 * c * q2 * q2;
  HS (3, 3) = 1.0;
#undef HS
  ts_df_from_hess (2, hs, df);
  return ts_inject_jac (user);
}

static inline double
ts_ns2_H (const double *y)
{
  const double c = TS_NS2_C, s = TS_NS2_S;
  double q1 = y[0], q2 = y[1], p1 = y[2], p2 = y[3];
  return 0.5 * (p1 * p1 + p2 * p2) + 0.5 * (q1 * q1 + q2 * q2)
         + c * p1 * p1 * q2 * q2 + s * q1 * q1 * q2;
}

/* ---------------------------------------------------------------- Kepler
   H = |p|^2/2 - 1/|q| */
static inline int
ts_kep (double t, const double *y, double *dy, void *user)
{
  (void) t;
  double r2 = y[0] * y[0] + y[1] * y[1], r3 = r2 * sqrt (r2);
  dy[0] = y[2];
  dy[1] = y[3];
  dy[2] = -y[0] / r3;
  dy[3] = -y[1] / r3;
  return ts_inject (user, dy, 4);
}

static inline int
ts_kep_jac (double t, const double *y, double *df, void *user)
{
  (void) t;
  double r2 = y[0] * y[0] + y[1] * y[1], r = sqrt (r2), r3 = r2 * r;
  double r5 = r3 * r2;
  memset (df, 0, 16 * sizeof (double));
  df[0 + 2 * 4] = 1.0;
  df[1 + 3 * 4] = 1.0;
  for (int i = 0; i < 2; i++)
    for (int j = 0; j < 2; j++)
      df[(2 + i) + j * 4] = -((i == j) / r3 - 3.0 * y[i] * y[j] / r5);
  return ts_inject_jac (user);
}

static inline int
ts_kep_batch (int k, const double *t, const double *y, double *dy,
              void *user)
{
  for (int j = 0; j < k; j++)
    {
      int st = ts_kep (t[j], y + 4 * j, dy + 4 * j, user);
      if (st)
        return st;
    }
  return 0;
}

static inline double
ts_kep_H (const double *y)
{
  return 0.5 * (y[2] * y[2] + y[3] * y[3])
         - 1.0 / sqrt (y[0] * y[0] + y[1] * y[1]);
}

static inline double
ts_kep_L (const double *y)
{
  return y[0] * y[3] - y[1] * y[2];
}

static inline void
ts_kep_y0 (double e, double *y)
{
  y[0] = 1.0 - e;
  y[1] = 0.0;
  y[2] = 0.0;
  y[3] = sqrt ((1.0 + e) / (1.0 - e));
}

/* ---------------------------------------------------------------- systems */
static inline sym_system
ts_system (int d, sym_rhs_fn rhs, sym_jac_fn jac, void *user)
{
  sym_system s;
  memset (&s, 0, sizeof (s));
  s.dim = d;
  s.rhs = rhs;
  s.jac = jac;
  s.user = user;
  return s;
}

/* the same as the core evaluates it, for the stepper driven directly */
static inline sym_eval
ts_eval (int d, sym_rhs_fn rhs, sym_jac_fn jac, void *user)
{
  sym_system s = ts_system (d, rhs, jac, user);
  sym_eval ev;
  sym_eval_init (&ev, &s);
  return ev;
}

/* The options of the pair (n, m) (0: the defaults) into o, its own part
   into so, which o->own points at */
static inline void
ts_opts (sym_method_opts *o, sym_spvi_opts *so, int n, int m)
{
  memset (o, 0, sizeof (*o));
  memset (so, 0, sizeof (*so));
  so->q_dofs = n;
  so->nodes = m;
  o->own = so;
  o->want_dense = 1;     /* the tests call dense () on the steps */
}

/* Switch a stepper to the steps of an adaptive run with RelTol rtol and
   AbsTol atol */
static inline int
ts_adaptive (const sym_stepper_type *type, void *state, double rtol,
             double atol)
{
  const sym_tolerances tol = { rtol, &atol, 1, 0 };
  return type->set_tolerances (state, &tol);
}

/* Fixed steps t = t0 + k h, k = 1..nsteps, from y (overwritten): step
   then accept, as the driver does.  Returns the first nonzero status. */
static inline int
ts_run_fixed (const sym_stepper_type *type, void *state, sym_eval *ev,
              double t0, double h, long nsteps, double *y)
{
  double yn[64];
  int nn = 2 * ev->dim;
  double t = t0;
  for (long k = 0; k < nsteps; k++)
    {
      double tn = t0 + h * (double) (k + 1);
      int st = type->step (state, ev, t, h, tn, y, yn, NULL);
      if (st)
        return st;
      type->accept (state);
      memcpy (y, yn, (size_t) nn * sizeof (double));
      t = tn;
    }
  return 0;
}

/* ------------------------------------------------------------ exact pendulum
   H = p^2/2 - cos q below the separatrix (E < 1):
     sin(q/2) = k sn(u0 + t | k^2),  p = 2k cn(u0 + t | k^2),
   k^2 = (1 + E)/2.  sn, cn by the descending AGM (Abramowitz-Stegun
   16.4), u0 = F(phi0 | k^2) by Carlson's R_F (duplication). */
static inline double
ts_carlson_rf (double x, double y, double z)
{
  for (int it = 0; it < 100; it++)
    {
      double sx = sqrt (x), sy = sqrt (y), sz = sqrt (z);
      double lam = sx * sy + sy * sz + sz * sx;
      x = 0.25 * (x + lam);
      y = 0.25 * (y + lam);
      z = 0.25 * (z + lam);
      double a = (x + y + z) / 3.0;
      double dx = 1.0 - x / a, dy = 1.0 - y / a, dz = 1.0 - z / a;
      if (fmax (fabs (dx), fmax (fabs (dy), fabs (dz))) < 1e-4)
        {
          double e2 = dx * dy - dz * dz, e3 = dx * dy * dz;
          return (1.0 - e2 / 10.0 + e3 / 14.0 + e2 * e2 / 24.0
                  - 3.0 * e2 * e3 / 44.0) / sqrt (a);
        }
    }
  return NAN;
}

static inline void
ts_jacobi_sncn (double u, double m, double *sn, double *cn)
{
  double a[32], c[32];
  double b = sqrt (1.0 - m);
  a[0] = 1.0;
  c[0] = sqrt (m);
  int nn = 0;
  while (nn < 30 && fabs (c[nn]) > 1e-17)
    {
      double an = 0.5 * (a[nn] + b);
      c[nn + 1] = 0.5 * (a[nn] - b);
      b = sqrt (a[nn] * b);
      a[nn + 1] = an;
      nn++;
    }
  double phi = ldexp (a[nn] * u, nn);
  for (int k = nn; k > 0; k--)
    phi = 0.5 * (phi + asin (c[k] * sin (phi) / a[k]));
  *sn = sin (phi);
  *cn = cos (phi);
}

static inline void
ts_pend_exact (double q0, double p0, double t, double *y)
{
  double E = 0.5 * p0 * p0 - cos (q0);
  double k2 = 0.5 * (1.0 + E), k = sqrt (k2);
  double s0 = sin (0.5 * q0) / k, c0 = p0 / (2.0 * k);
  double phi0 = atan2 (s0, c0);
  double sp = sin (phi0), cp = cos (phi0);
  double u0 = sp * ts_carlson_rf (cp * cp, 1.0 - k2 * sp * sp, 1.0);
  double sn, cn;
  ts_jacobi_sncn (u0 + t, k2, &sn, &cn);
  y[0] = 2.0 * asin (k * sn);
  y[1] = 2.0 * k * cn;
}

static inline double
ts_maxdiff (int n, const double *a, const double *b)
{
  double m = 0.0;
  for (int i = 0; i < n; i++)
    m = fmax (m, fabs (a[i] - b[i]));
  return m;
}

#endif
