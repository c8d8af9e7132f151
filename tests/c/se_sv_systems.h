/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* se_sv_systems.h -- test problems for the SE and SV steppers
   (test_se_sv_*.c): analytic f and Df, failure injection, a fixed-step
   loop over the stepper table, an RK4 reference and naive fixed-point
   versions of both schemes.  Functions are static inline so that each
   test program may use any subset of them without warnings. */
#ifndef SE_SV_SYSTEMS_H
#define SE_SV_SYSTEMS_H

#include "sym.h"
#include "testutil.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum {
  P_H1,       /* d=1, H = p^2/2 (1+q^2) + q^2/2                 non-separable */
  P_H1F,      /* P_H1 + forcing F = 0.3 cos(2t) - 0.1 p         non-separable */
  P_PEND,     /* d=1, H = p^2/2 - cos q                          separable */
  P_PENDF,    /* P_PEND + forcing F = 0.5 cos(t)                 separable */
  P_HO,       /* d=1, H = (p^2+q^2)/2                            separable */
  P_DAMPED,   /* P_HO + forcing -c p                             (f_p has p) */
  P_KEPLER,   /* d=2, H = |p|^2/2 - 1/|q|                        separable */
  P_H2        /* d=2, coupled non-separable (see tp_f)           non-separable */
};

typedef struct {
  int kind;
  double c;          /* damping of P_DAMPED */
  long calls;        /* rhs calls */
  long jcalls;       /* jac calls */
  /* failure injection: on call number fail_at (1-based) of rhs (jac) */
  long fail_at, jfail_at;
  int fail_mode, jfail_mode;   /* 1 NaN, 2 return +1, 3 return -1 */
} tprob;

static inline int
tp_dim (int kind)
{
  return (kind == P_KEPLER || kind == P_H2) ? 2 : 1;
}

/* f(t, y) for problem kind (no counting) */
static inline void
tp_f (const tprob *P, double t, const double *y, double *f)
{
  switch (P->kind)
    {
    case P_H1:
    case P_H1F:
      {
        double q = y[0], p = y[1];
        f[0] = p * (1 + q * q);
        f[1] = -(p * p * q + q);
        if (P->kind == P_H1F)
          f[1] += 0.3 * cos (2 * t) - 0.1 * p;
        break;
      }
    case P_PEND:
    case P_PENDF:
      f[0] = y[1];
      f[1] = -sin (y[0]);
      if (P->kind == P_PENDF)
        f[1] += 0.5 * cos (t);
      break;
    case P_HO:
      f[0] = y[1];
      f[1] = -y[0];
      break;
    case P_DAMPED:
      f[0] = y[1];
      f[1] = -y[0] - P->c * y[1];
      break;
    case P_KEPLER:
      {
        double r2 = y[0] * y[0] + y[1] * y[1], r3 = r2 * sqrt (r2);
        f[0] = y[2];
        f[1] = y[3];
        f[2] = -y[0] / r3;
        f[3] = -y[1] / r3;
        break;
      }
    case P_H2:
      {
        /* H = p1^2 (1+q2^2)/2 + p2^2 (1+q1^2)/2 + (q1^2+q2^2)/2
               + 0.1 p1 p2 q1 q2 */
        double q1 = y[0], q2 = y[1], p1 = y[2], p2 = y[3];
        f[0] = p1 * (1 + q2 * q2) + 0.1 * p2 * q1 * q2;
        f[1] = p2 * (1 + q1 * q1) + 0.1 * p1 * q1 * q2;
        f[2] = -(p2 * p2 * q1 + q1 + 0.1 * p1 * p2 * q2);
        f[3] = -(p1 * p1 * q2 + q2 + 0.1 * p1 * p2 * q1);
        break;
      }
    }
}

/* Df (n-by-n, column-major) */
static inline void
tp_df (const tprob *P, double t, const double *y, double *J)
{
  (void) t;
  int n = 2 * tp_dim (P->kind);
  memset (J, 0, (size_t) n * n * sizeof (double));
#define A(i, j) J[(i) + (j) * n]
  switch (P->kind)
    {
    case P_H1:
    case P_H1F:
      {
        double q = y[0], p = y[1];
        A (0, 0) = 2 * p * q;
        A (0, 1) = 1 + q * q;
        A (1, 0) = -(p * p + 1);
        A (1, 1) = -2 * p * q;
        if (P->kind == P_H1F)
          A (1, 1) -= 0.1;
        break;
      }
    case P_PEND:
    case P_PENDF:
      A (0, 1) = 1;
      A (1, 0) = -cos (y[0]);
      break;
    case P_HO:
      A (0, 1) = 1;
      A (1, 0) = -1;
      break;
    case P_DAMPED:
      A (0, 1) = 1;
      A (1, 0) = -1;
      A (1, 1) = -P->c;
      break;
    case P_KEPLER:
      {
        double r2 = y[0] * y[0] + y[1] * y[1], r = sqrt (r2);
        double r3 = r2 * r, r5 = r3 * r2;
        A (0, 2) = 1;
        A (1, 3) = 1;
        A (2, 0) = -1 / r3 + 3 * y[0] * y[0] / r5;
        A (2, 1) = 3 * y[0] * y[1] / r5;
        A (3, 0) = 3 * y[0] * y[1] / r5;
        A (3, 1) = -1 / r3 + 3 * y[1] * y[1] / r5;
        break;
      }
    case P_H2:
      {
        double q1 = y[0], q2 = y[1], p1 = y[2], p2 = y[3];
        /* Hessian of H, order (q1, q2, p1, p2) */
        double Hq1q1 = p2 * p2 + 1, Hq1q2 = 0.1 * p1 * p2,
               Hq2q2 = p1 * p1 + 1;
        double Hq1p1 = 0.1 * p2 * q2, Hq1p2 = 2 * p2 * q1 + 0.1 * p1 * q2;
        double Hq2p1 = 2 * p1 * q2 + 0.1 * p2 * q1, Hq2p2 = 0.1 * p1 * q1;
        double Hp1p1 = 1 + q2 * q2, Hp1p2 = 0.1 * q1 * q2,
               Hp2p2 = 1 + q1 * q1;
        /* f_q = H_p: d/dq = H_pq, d/dp = H_pp */
        A (0, 0) = Hq1p1; A (0, 1) = Hq2p1; A (0, 2) = Hp1p1; A (0, 3) = Hp1p2;
        A (1, 0) = Hq1p2; A (1, 1) = Hq2p2; A (1, 2) = Hp1p2; A (1, 3) = Hp2p2;
        /* f_p = -H_q: d/dq = -H_qq, d/dp = -H_qp */
        A (2, 0) = -Hq1q1; A (2, 1) = -Hq1q2; A (2, 2) = -Hq1p1; A (2, 3) = -Hq1p2;
        A (3, 0) = -Hq1q2; A (3, 1) = -Hq2q2; A (3, 2) = -Hq2p1; A (3, 3) = -Hq2p2;
        break;
      }
    }
#undef A
}

static inline double
tp_energy (const tprob *P, const double *y)
{
  switch (P->kind)
    {
    case P_H1:
      return 0.5 * y[1] * y[1] * (1 + y[0] * y[0]) + 0.5 * y[0] * y[0];
    case P_PEND:
      return 0.5 * y[1] * y[1] - cos (y[0]);
    case P_HO:
      return 0.5 * (y[0] * y[0] + y[1] * y[1]);
    case P_KEPLER:
      return 0.5 * (y[2] * y[2] + y[3] * y[3])
             - 1 / sqrt (y[0] * y[0] + y[1] * y[1]);
    default:
      return NAN;
    }
}

static inline int
tp_fail (long call, long at, int mode, double *v, int n)
{
  if (call != at)
    return 0;
  if (mode == 1)
    {
      v[n - 1] = NAN;
      return 0;
    }
  return mode == 2 ? 1 : -1;
}

static inline int
tp_rhs (double t, const double *y, double *dy, void *user)
{
  tprob *P = user;
  P->calls++;
  tp_f (P, t, y, dy);
  return tp_fail (P->calls, P->fail_at, P->fail_mode, dy,
                  2 * tp_dim (P->kind));
}

static inline int
tp_jac (double t, const double *y, double *df, void *user)
{
  tprob *P = user;
  int n = 2 * tp_dim (P->kind);
  P->jcalls++;
  tp_df (P, t, y, df);
  return tp_fail (P->jcalls, P->jfail_at, P->jfail_mode, df, n * n);
}

/* a system for problem kind; jac analytic if with_jac */
static inline sym_system
tp_system (tprob *P, int kind, int with_jac)
{
  sym_system s;
  memset (&s, 0, sizeof (s));
  memset (P, 0, sizeof (*P));
  P->kind = kind;
  P->c = 0.1;
  s.dim = tp_dim (kind);
  s.rhs = tp_rhs;
  s.jac = with_jac ? tp_jac : NULL;
  s.user = P;
  return s;
}

/* the same as the core evaluates it, for the steppers driven directly */
static inline sym_eval
tp_eval (tprob *P, int kind, int with_jac)
{
  sym_system s = tp_system (P, kind, with_jac);
  sym_eval ev;
  sym_eval_init (&ev, &s);
  return ev;
}

/* the options: Separable (own points at static storage, so that the
   struct may be copied), dense output wanted */
static inline sym_method_opts
tp_opts (int separable, int want_dense)
{
  static const sym_onestep_opts own[2] = { { 0, 0, 0, 0, 0, 0, NULL },
                                           { 1, 0, 0, 0, 0, 0, NULL } };
  sym_method_opts o;
  memset (&o, 0, sizeof (o));
  o.own = &own[separable != 0];
  o.want_dense = want_dense;
  return o;
}

/* A stepper for fixed steps, or (adaptive) switched to the adaptive steps
   of a run with tolerances, which ask for the error estimate; NULL with
   *st on failure */
static inline void *
tp_alloc (const sym_stepper_type *T, int dim, const sym_method_opts *o,
          int adaptive, int *st)
{
  static const double atol = 1e-6;
  static const sym_tolerances tol = { 1e-6, &atol, 1, 0 };
  void *S = T->alloc (dim, o, st);
  if (S && adaptive && (*st = T->set_tolerances (S, &tol)))
    {
      T->free (S);
      return NULL;
    }
  return S;
}

/* N fixed steps of h from (t0, y0) into y (n); if traj != NULL, the states
   y_0..y_N go into traj ((N+1)-by-n, row k at traj + k n).  adaptive: the
   stepper of an adaptive run, asked for yerr every step.  Returns the
   first failing status. */
static inline int
run_fixed (const sym_stepper_type *T, sym_eval *ev,
           const sym_method_opts *o, double t0, double h, long N,
           const double *y0, double *y, double *traj, int adaptive)
{
  int st, n = 2 * ev->dim;
  void *S = tp_alloc (T, ev->dim, o, adaptive, &st);
  if (! S)
    return st;
  double yc[8], yn[8], ye[8];
  memcpy (yc, y0, (size_t) n * sizeof (double));
  if (traj)
    memcpy (traj, yc, (size_t) n * sizeof (double));
  double t = t0;
  for (long k = 0; k < N; k++)
    {
      /* times as the driver forms them in fixed-step mode */
      double tnew = t0 + h * (double) (k + 1);
      st = T->step (S, ev, t, tnew - t, tnew, yc, yn, adaptive ? ye : NULL);
      if (st)
        break;
      T->accept (S);
      t = tnew;
      memcpy (yc, yn, (size_t) n * sizeof (double));
      if (traj)
        memcpy (traj + (size_t) (k + 1) * n, yc, (size_t) n * sizeof (double));
    }
  T->free (S);
  memcpy (y, yc, (size_t) n * sizeof (double));
  return st;
}

static inline const sym_stepper_type *
stepper (int sv)
{
  return sv ? sym_step_sv : sym_step_se;
}

static inline const char *
mname (int sv)
{
  return sv ? "SV" : "SE";
}

/* classical RK4 with N steps of h (reference) */
static inline void
rk4 (const tprob *P, double t0, double h, long N, const double *y0, double *y)
{
  int n = 2 * tp_dim (P->kind);
  double k1[8], k2[8], k3[8], k4[8], w[8];
  memcpy (y, y0, (size_t) n * sizeof (double));
  for (long k = 0; k < N; k++)
    {
      double t = t0 + k * h;
      tp_f (P, t, y, k1);
      for (int i = 0; i < n; i++) w[i] = y[i] + 0.5 * h * k1[i];
      tp_f (P, t + 0.5 * h, w, k2);
      for (int i = 0; i < n; i++) w[i] = y[i] + 0.5 * h * k2[i];
      tp_f (P, t + 0.5 * h, w, k3);
      for (int i = 0; i < n; i++) w[i] = y[i] + h * k3[i];
      tp_f (P, t + h, w, k4);
      for (int i = 0; i < n; i++)
        y[i] += h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
    }
}

/* Fixed-point iteration x <- g(x) to its round-off limit (independent of
   newton.c): stops when an iterate repeats or the change stops shrinking
   after reaching 1e-15 relative. */
#define FP_MAXIT 400

/* naive SE step: P = p + h f_p(t, q, P) by fixed point; q1 = q + h f_q */
static inline void
naive_se (const tprob *P, double t, double h, const double *y, double *y1)
{
  int d = tp_dim (P->kind), n = 2 * d;
  double w[8], f[8], Pn[4], best = INFINITY;
  memcpy (w, y, (size_t) n * sizeof (double));
  for (int it = 0; it < FP_MAXIT; it++)
    {
      tp_f (P, t, w, f);
      double ch = 0, sc = 0;
      for (int i = 0; i < d; i++)
        {
          Pn[i] = y[d + i] + h * f[d + i];
          ch = fmax (ch, fabs (Pn[i] - w[d + i]));
          sc = fmax (sc, fabs (Pn[i]));
          w[d + i] = Pn[i];
        }
      if (ch == 0 || (ch <= 1e-15 * fmax (sc, 1e-300) && ch >= best))
        break;
      best = fmin (best, ch);
    }
  tp_f (P, t, w, f);
  for (int i = 0; i < d; i++)
    {
      y1[i] = y[i] + h * f[i];
      y1[d + i] = w[d + i];
    }
}

/* naive SV step, both implicit stages by fixed point */
static inline void
naive_sv (const tprob *P, double t, double h, const double *y, double *y1)
{
  int d = tp_dim (P->kind), n = 2 * d;
  double w[8], f[8], fa[4], best = INFINITY;
  memcpy (w, y, (size_t) n * sizeof (double));
  for (int it = 0; it < FP_MAXIT; it++)
    {
      tp_f (P, t, w, f);
      double ch = 0, sc = 0;
      for (int i = 0; i < d; i++)
        {
          double v = y[d + i] + 0.5 * h * f[d + i];
          ch = fmax (ch, fabs (v - w[d + i]));
          sc = fmax (sc, fabs (v));
          w[d + i] = v;
        }
      if (ch == 0 || (ch <= 1e-15 * fmax (sc, 1e-300) && ch >= best))
        break;
      best = fmin (best, ch);
    }
  tp_f (P, t, w, f);           /* f_q(t, q, P) at the final P */
  memcpy (fa, f, (size_t) d * sizeof (double));
  best = INFINITY;
  for (int it = 0; it < FP_MAXIT; it++)
    {
      tp_f (P, t + h, w, f);
      double ch = 0, sc = 0;
      for (int i = 0; i < d; i++)
        {
          double v = y[i] + 0.5 * h * (fa[i] + f[i]);
          ch = fmax (ch, fabs (v - w[i]));
          sc = fmax (sc, fabs (v));
          w[i] = v;
        }
      if (ch == 0 || (ch <= 1e-15 * fmax (sc, 1e-300) && ch >= best))
        break;
      best = fmin (best, ch);
    }
  tp_f (P, t + h, w, f);
  for (int i = 0; i < d; i++)
    {
      y1[i] = w[i];
      y1[d + i] = w[d + i] + 0.5 * h * f[d + i];
    }
}

static inline double
maxdiff (int n, const double *a, const double *b)
{
  double m = 0;
  for (int i = 0; i < n; i++)
    m = fmax (m, fabs (a[i] - b[i]));
  return m;
}

static inline double
maxabs (int n, const double *a)
{
  double m = 0;
  for (int i = 0; i < n; i++)
    m = fmax (m, fabs (a[i]));
  return m;
}

#endif
