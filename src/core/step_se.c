/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* step_se.c -- symplectic Euler, variant "p implicit, q explicit" (order 1).

   y = [q; p], q, p in R^d, f(t, y) = [f_q; f_p] = [dH/dp; -dH/dq + F].
   One step from (t_k, q_k, p_k) by h (h < 0 runs backwards):

     p_{k+1} = p_k + h f_p(t_k, q_k, p_{k+1})      implicit in p_{k+1}
     q_{k+1} = q_k + h f_q(t_k, q_k, p_{k+1})      explicit

   For F = 0 this is the symplectic Euler method; with the forcing F in f_p
   it is the discrete Lagrange-d'Alembert (forced) variational integrator.

   Implicit solve (sym_kick_solve of steprec.c, shared with Stormer-Verlet
   with h/2 for h): simplified Newton (newton.c) on the d unknowns P,
     G(P) = P - p_k - h f_p(t_k, q_k, P),   G'(P) ~ I - h A_pp(t_k, q_k, P),
   A_pp = d f_p / d p from sym_jac.
   - Start: the explicit P0 = p_k + h f_p(t_k, y_k) when f(t_k, y_k) is
     known (FSAL), else p_k + (p_k - p_{k-1}) h / h_prev when the last
     accepted step ended at (t_k, y_k), else f(t_k, y_k) is evaluated (one
     call); plus, when the steps continue one another, the errors P - P0
     of the last steps extrapolated (sym_pred, steprec.h; again from P0
     alone after a recoverable failure from there).  Measured on P_H1 of
     tests/c (H = p^2/2 (1 + q^2) + q^2/2, h = 0.01): 2.01 calls per step
     (rhs + jac), the explicit start alone 4.04 (its matrix was also
     rebuilt on 70% of the steps).
   - Stop: max_i |dP_i| / s <= tol (opts->newton_tol, default
     1e-14; for a fixed step SYM_FIXED_TOL_KEPT = 1e-3 times that,
     steprec.h),
     with s = max(|p_k|_inf, |P0 - p_k|_inf) (1 if both vanish).
   - q_{k+1} needs f_q at the final P, but the last residual was evaluated
     at the previous iterate: f is evaluated at P once more (unless the last
     correction was round-off, |dP| <= 4 eps s: f is then moved there by Df,
     sym_fcache_move).  That gives G(P) for free,
     and it must be <= 4 tol s, else Newton goes on from P with the
     contraction rate this residual shows (at most three solves): newton.c
     may stop after a single iteration, judging by the rate of an earlier
     solve, and was measured up to 1e-10 off.
   - The factored matrix is kept across steps while it pays and while h
     stays within 20% of the h it was built with: each solve's iterations
     beyond SYM_NW_BASE = 2 (steprec.h: what a fresh matrix needs) are
     charged to it, and
     once they add up to the cost of a new one (1 jac call, or n rhs calls
     of finite differences) it is rebuilt at the next solve.  (newton.c
     itself refreshes a matrix under which the iteration stalls.)

   Separable H = T(p) + V(q) (opts->separable): f_p does not depend on p and
   f_q not on q, so the step is explicit: f(t_k, [q_k; p_k]) gives f_p ->
   p_{k+1}; f(t_k, [q_k; p_{k+1}]) gives f_q -> q_{k+1}.  Two calls a step.

   Error estimate (yerr):
     err = y_{k+1} - y_k - (h/2) (f(t_k, y_k) + f(t_{k+1}, y_{k+1})),
   the difference to the trapezoidal rule through the two step points.  The
   trapezoidal rule is O(h^3) locally and this method O(h^2), so err =
   O(h^2) (err_order 1) and estimates the local error of the step.
   f(t_{k+1}, y_{k+1}) of an accepted step is the next step's f(t_k, y_k)
   (FSAL), so the estimate costs one call a step; on the separable path
   that call is also the next step's first call, and the step still costs
   two calls.

   Dense output on the last accepted step: the cubic Hermite interpolant
   through (t_k, y_k, f_k) and (t_{k+1}, y_{k+1}, f_{k+1}) when both f are
   known (they are when want_error or want_dense is set), else linear. */
#include "sym.h"
#include "steprec.h"

#include <float.h>
#include <math.h>
#include <string.h>

typedef struct {
  sym_onestep o;         /* first: accept, dense, reset (steprec.h) */
  int d, n;
  int separable, want_f;
  sym_kept kn;           /* Newton for p_{k+1} */
  double *block;         /* the one allocation holding the arrays */
  double *x, *scale, *rv;/* d: Newton unknown, its scale, a residual */
} se_state;

static void se_free (void *state);

static void *
se_alloc (const sym_system *sys, const sym_method_opts *opts, int *status)
{
  int dummy;
  if (! status)
    status = &dummy;
  se_state *s = sym_onestep_new (sys, sizeof (se_state), status);
  if (! s)
    return NULL;
  const int d = sys->dim, n = 2 * d;
  s->d = d;
  s->n = n;
  if (opts)
    {
      s->separable = opts->separable != 0;
      s->want_f = opts->want_error || opts->want_dense;
    }
  /* records, f cache, and x, scale, rv: 3d; the separable step is
     explicit: no Df and no Newton state (O(d^2) memory) */
  const int implicit = ! s->separable;
  size_t len = sym_recs_len (n, 0) + sym_fcache_len (d, implicit)
               + 3 * (size_t) d + (implicit ? sym_pred_len (d) : 0);
  s->block = sym_calloc (len, sizeof (double));
  if (! s->block || (implicit && sym_kept_init (&s->kn, d, opts)))
    {
      se_free (s);
      *status = SYM_ENOMEM;
      return NULL;
    }
  double *w = s->block;
  sym_recs_place (&s->o.r, n, 0, w);
  w += sym_recs_len (n, 0);
  sym_fcache_place (&s->o.fc, d, implicit, w);
  w += sym_fcache_len (d, implicit);
  s->x = w; w += d;
  s->scale = w; w += d;
  s->rv = w; w += d;
  if (implicit)
    {
      s->o.npr = 1;
      sym_pred_place (&s->o.pr[0], d, w);
    }
  *status = SYM_SUCCESS;
  return s;
}

static void
se_free (void *state)
{
  se_state *s = state;
  if (! s)
    return;
  sym_newton_free (&s->kn.nw);   /* safe on the zeroed struct too */
  sym_free (s->block);
  sym_free (s);
}

static int
se_step (void *state, sym_system *sys, double t, double h, double tend,
         const double *y, double *ynext, double *yerr)
{
  se_state *s = state;
  int st;
  if (! s || ! sys || ! y || ! ynext || ! isfinite (t) || ! isfinite (h)
      || ! isfinite (tend) || h == 0.0)
    return SYM_EBADINPUT;
  const int d = s->d;
  const int cont = sym_recs_begin (&s->o.r, t, h, tend, y);
  sym_rec *tr = s->o.r.trial, *cu = s->o.r.cur;
  const double *q0 = tr->y0, *p0 = tr->y0 + d;
  double *q1 = tr->y1, *p1 = tr->y1 + d;

  if (s->separable)
    {
      if ((st = sym_recs_f0 (&s->o.r, sys)))
        return st;
      for (int i = 0; i < d; i++)
        p1[i] = p0[i] + h * tr->f0[d + i];
      st = sym_fcache_f (&s->o.fc, sys, t, q0, p1);
      if (st)
        return st;
      /* f_p at (t, q0) with p0 and with p1: the same if H is separable */
      sym_sep_check (sys, t, d, tr->f0 + d, s->o.fc.fw + d);
      for (int i = 0; i < d; i++)
        q1[i] = q0[i] + h * s->o.fc.fw[i];
    }
  else
    {
      sym_kick kick = { d, &s->o.fc, &s->kn, sys, t, h, h, tr->y0,
                        &s->o.pr[0] };
      if ((st = sym_kick_solve (&kick, &s->o.r, cont, cu->y0 + d, s->x,
                                s->scale, s->rv)))
        return st;
      /* the cache holds f at [q_k; P] */
      memcpy (p1, s->x, (size_t) d * sizeof (double));
      for (int i = 0; i < d; i++)
        q1[i] = q0[i] + h * s->o.fc.fw[i];
    }
  return sym_recs_finish (&s->o.r, sys, s->want_f, yerr, ynext);
}

static int
se_order (const void *state)
{
  (void) state;
  return 1;
}

static const sym_stepper_type se_type = {
  "se", 1, se_order, se_order, se_alloc, se_step, sym_onestep_accept,
  sym_onestep_dense, sym_onestep_reset, se_free
};

const sym_stepper_type *const sym_step_se = &se_type;
