/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* se.c -- symplectic Euler, variant "p implicit, q explicit" (order 1).

   y = [q; p], q, p in R^d, f(t, y) = [f_q; f_p] = [dH/dp; -dH/dq + F].
   One step from (t_k, q_k, p_k) by h (h < 0 runs backwards):

     p_{k+1} = p_k + h f_p(t_k, q_k, p_{k+1})      implicit in p_{k+1}
     q_{k+1} = q_k + h f_q(t_k, q_k, p_{k+1})      explicit

   For F = 0 this is the symplectic Euler method; with the forcing F in f_p
   it is the discrete Lagrange-d'Alembert (forced) variational integrator.

   The implicit kick is sym_kick_solve (implicit.c, shared with
   Stormer-Verlet's half kick): simplified Newton on the d unknowns P,
     G(P) = P - p_k - h f_p(t_k, q_k, P),   G'(P) ~ I - h A_pp,
   started from the history of P over an explicit start, stopped when
   its error is estimated below NewtonTol relative to max(|p_k|, |P -
   p_k|) at the result P (SYM_FIXED_TOL_KEPT of it on fixed steps), with
   its matrix kept across steps while it pays.
   q_{k+1} needs f_q at the final P: the solve leaves it in the f cache.

   Separable H = T(p) + V(q): f_p does not depend on p and f_q not on q,
   so the step is explicit: f(t_k, [q_k; p_k]) gives p_{k+1}, f(t_k,
   [q_k; p_{k+1}]) gives q_{k+1}.  Two calls a step; one with
   second_order (f_q = p: q_{k+1} = q_k + h p_{k+1}).

   Error estimate: err = y_{k+1} - y_k - (h/2) (f(t_k, y_k) + f(t_{k+1},
   y_{k+1})), the difference to the trapezoidal rule through the step
   points: O(h^2) (order 1).  f at the end of an accepted step is f at the
   start of the next (FSAL): one call a step.

   Dense output: the cubic Hermite interpolant through the step's ends
   when both f are known (adaptive steps, or dense output wanted), else
   linear. */
#include "onestep.h"

#include <float.h>
#include <math.h>
#include <string.h>

typedef struct {
  sym_onestep o;         /* first: accept and dense (onestep.h) */
  double *x, *scale;     /* d: Newton unknown, its scale */
} se_state;

static void *
se_alloc (int dim, const sym_method_opts *opts, int *status)
{
  /* own: x, scale (d each); one implicit unknown */
  double *w;
  se_state *s = sym_onestep_alloc (dim, 1, sizeof (se_state), 1, 0,
                                   2 * (size_t) dim, opts, status, &w);
  if (! s)
    return NULL;
  s->x = w;
  s->scale = w + dim;
  return s;
}

static int
se_step (void *state, sym_eval *ev, double t, double h, double tend,
         const double *y, double *ynext, double *yerr)
{
  se_state *s = state;
  sym_trial v;
  int st = sym_onestep_trial (&s->o, ev, t, h, tend, y, ynext, &v);
  if (st)
    return st;
  const int d = v.d;
  if (s->o.separable)
    {
      if ((st = sym_recs_f0 (&s->o.r, ev)))
        return st;
      for (int i = 0; i < d; i++)
        v.p1[i] = v.p0[i] + h * v.tr->f0[d + i];
      sym_tangent *tg = s->o.tg;
      /* the drift's blocks first: from Df, the kick's A comes with them
         (the same q), and f at the drift's point for q1 */
      if (tg && ! s->o.second_order
          && (st = sym_tangent_prefetch (tg, ev, t, v.q0, v.p1)))
        return st;
      if (tg && (st = sym_tangent_kick (tg, ev, t, v.q0, v.p0, h)))
        return st;
      if (tg && (st = sym_tangent_drift (tg, ev, t, v.q0, v.p1, h,
                                         s->o.second_order)))
        return st;
      if (s->o.second_order)
        {
          for (int i = 0; i < d; i++)
            v.q1[i] = v.q0[i] + h * v.p1[i];
          return sym_recs_finish (&s->o.r, ev, s->o.want_f, yerr, ynext);
        }
      sym_fcache_feed (&s->o.fc, tg, t, v.q0, v.p1);
      st = sym_fcache_f (&s->o.fc, ev, t, v.q0, v.p1);
      if (st)
        return st;
      /* f_p at (t, q0) with p0 and with p1: the same if H is separable */
      sym_sep_check (ev, t, d, v.tr->f0 + d, s->o.fc.fw + d);
      for (int i = 0; i < d; i++)
        v.q1[i] = v.q0[i] + h * s->o.fc.fw[i];
    }
  else
    {
      sym_kick kick = { d, &s->o.fc, &s->o.k[0], ev, t, h, h, v.tr->y0,
                        &s->o.pr[0] };
      if ((st = sym_kick_solve (&kick, &s->o.r, v.cont, v.cu->y0 + d, s->x,
                                s->scale)))
        return st;
      /* the cache holds f at [q_k; P] */
      memcpy (v.p1, s->x, (size_t) d * sizeof (double));
      for (int i = 0; i < d; i++)
        v.q1[i] = v.q0[i] + h * s->o.fc.fw[i];
    }
  return sym_recs_finish (&s->o.r, ev, s->o.want_f, yerr, ynext);
}

static const sym_stepper_type se_type =
  SYM_ONESTEP_TYPE ("se", se_alloc, sym_onestep_set_tolerances, se_step,
                    sym_onestep_free);

const sym_stepper_type *const sym_step_se = &se_type;
