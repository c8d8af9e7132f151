/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* step_sv.c -- Stoermer-Verlet (order 2), general H.

   y = [q; p], q, p in R^d, f(t, y) = [f_q; f_p] = [dH/dp; -dH/dq + F].
   One step from (t_k, q_k, p_k) by h (h < 0 runs backwards), t_{k+1} =
   t_k + h:

     p_{k+1/2} = p_k + (h/2) f_p(t_k, q_k, p_{k+1/2})                 (1)
     q_{k+1}   = q_k + (h/2) [f_q(t_k, q_k, p_{k+1/2})
                              + f_q(t_{k+1}, q_{k+1}, p_{k+1/2})]       (2)
     p_{k+1}   = p_{k+1/2} + (h/2) f_p(t_{k+1}, q_{k+1}, p_{k+1/2})     (3)

   (1) and (2) are implicit (d unknowns each), (3) is explicit.  The method
   is symplectic and symmetric (the step by -h from t_{k+1} undoes it).

   Implicit solves: simplified Newton (newton.c), one state per equation,
     (1) G(P) = P - p_k - (h/2) f_p(t_k, q_k, P),     G' ~ I - (h/2) A_pp
         (the kick of symplectic Euler with h/2: sym_kick_solve, steprec.c)
     (2) G(Q) = Q - q_k - (h/2) [f_q(t_k, q_k, P) + f_q(t_{k+1}, Q, P)],
                                                       G' ~ I - (h/2) A_qq
   (A_pp = d f_p/d p, A_qq = d f_q/d q, blocks of Df from sym_jac).
   - Starts: the explicit P0 = p_k + (h/2) f_p(t_k, y_k) when f(t_k, y_k)
     is known (FSAL), else p_k + (p_k - p_{k-1/2}) h / h_prev (= p_k + (h/2)
     f_p(t_k, q_k, p_{k-1/2}), exact for a separable H) when the last
     accepted step ended at (t_k, y_k), else f(t_k, y_k) is evaluated (one
     call); Q0 = q_k + h f_q(t_k, q_k, P); each plus, when the steps
     continue one another, the errors P - P0 (Q - Q0) of the last steps
     extrapolated (sym_pred, steprec.h; again from P0 (Q0) alone after a
     recoverable failure from there).  Measured on P_H1 of tests/c (h =
     0.01): 3.86 calls per step, the explicit starts alone 7.89.
   - Stop: max_i |dx_i| / s <= tol (opts->newton_tol, default
     1e-14; for a fixed step SYM_FIXED_TOL_KEPT = 1e-3 times that,
     steprec.h),
     with s the max norm of p_k (q_k) or of the predicted increment
     P0 - p_k (Q0 - q_k), whichever is larger (1 if both vanish).
   - The f values used after each solve are those at the converged unknown:
     the last residual was evaluated at the previous iterate, so f is
     evaluated at the solution once more (unless the last correction was
     round-off, |dx| <= 4 eps s: f is then moved there by Df,
     sym_fcache_move).  That gives the residual for free, and it
     must be <= 4 tol s, else Newton goes on from there (see solve()).
   - Each factored matrix is kept across steps while it pays and while h
     stays within 20% of the h it was built with: each solve's iterations
     beyond SYM_NW_BASE = 2 (steprec.h: what a fresh matrix needs) are
     charged to it, and
     once they add up to the cost of a new one (1 jac call, or n rhs calls
     of finite differences) it is rebuilt at the next solve.  (newton.c
     itself refreshes a matrix under which the iteration stalls.)

   Separable H = T(p) + V(q) (opts->separable): explicit.  With f_p(q_k)
   from the last step (FSAL) or from f(t_k, y_k) at a fresh start:
     p_{k+1/2} = p_k + (h/2) f_p(q_k)
     A = f(t_k + h/2, [q_k; p_{k+1/2}]) -> q_{k+1} = q_k + h f_q(p_{k+1/2})
     B = f(t_{k+1}, [q_{k+1}; p_{k+1/2}]) -> p_{k+1} = p_{k+1/2}
                                              + (h/2) f_p(q_{k+1})
   and f_p(q_{k+1}) is kept for the next step's first half kick.  Two calls a
   step (plus one at a fresh start).  A is evaluated at the midpoint time:
   for a time-independent T this changes nothing, for T(t, p) it keeps the
   step symmetric.

   Error estimate (yerr), of the local error y_{k+1} - y(t_{k+1}):
     err = y_{k+1} - y_k - (h/2) (f(t_k, y_k) + f(t_{k+1}, y_{k+1}))
           + (h^3/12) y'''.
   The first part is the difference to the trapezoidal rule through the two
   step points, the local error of Stoermer-Verlet minus that of the
   trapezoidal rule; the second is the trapezoidal rule's own local error
   (h^3/12) y''' + O(h^4).  Both are needed: for separable H the p-update
   of Stoermer-Verlet is the trapezoidal rule (p_{k+1} - p_k = (h/2)
   (f_p(q_k) + f_p(q_{k+1}))), so the first part vanishes in p, and the
   local error of p is all in the second.  err = local error + O(h^4)
   (err_order 2), componentwise.  y''' = f'' is the second divided
   difference of f through the last accepted step's start, t_k and t_{k+1}
   when the last accepted step ends where this one starts, else (a fresh
   start) the second difference through t_k, t_k + h/2 and t_{k+1}, with
   f at the cubic Hermite midpoint (y_k + y_{k+1})/2 + (h/8) (f_k - f_{k+1})
   (one more call: y_m is O(h^3) accurate, f'' O(h)).  f(t_{k+1}, y_{k+1})
   of an accepted step is the next step's f(t_k, y_k) (FSAL): the estimate
   costs one call a step (the separable step then costs three), one more at
   a fresh start.

   Dense output on the last accepted step: the cubic Hermite interpolant
   through (t_k, y_k, f_k) and (t_{k+1}, y_{k+1}, f_{k+1}) when both f are
   known (they are when want_error or want_dense is set), else linear. */
#include "sym.h"
#include "steprec.h"

#include <float.h>
#include <math.h>
#include <string.h>

/* Each step record also keeps (aux) p_{k+1/2} and f_p(t_{k+1}, q_{k+1},
   p_{k+1/2}), d values each. */
#define PH(rec) ((rec)->aux)
#define FPE(rec, d) ((rec)->aux + (d))

typedef struct {
  sym_onestep o;         /* first: accept, dense, reset (steprec.h) */
  int d, n;
  int separable, want_f;
  sym_kept kp, kq;       /* Newton for equations (1) and (2) */
  double *block;         /* the one allocation holding the arrays */
  double *x, *scale, *rv;/* d: Newton unknown, its scale, a residual */
  double *fqa;           /* d: f_q(t_k, q_k, p_{k+1/2}) */
  double *ym;            /* n: the estimate's midpoint at a fresh start */
  /* the step being solved (for the Newton callbacks) */
  sym_system *sys;
  double tk, hk;
  const double *yk;
  const double *pk;      /* (2): p_{k+1/2} */
} sv_state;

/* (2): G(Q) = Q - q_k - (h/2) [f_q(t_k, q_k, P) + f_q(t_{k+1}, Q, P)] */
static int
res_q (void *ctx, const double *x, double *r)
{
  sv_state *s = ctx;
  const int d = s->d;
  int st = sym_fcache_f (&s->o.fc, s->sys, s->tk + s->hk, x, s->pk);
  if (st)
    return st;
  const double hh = 0.5 * s->hk;
  for (int i = 0; i < d; i++)
    r[i] = x[i] - s->yk[i] - hh * s->fqa[i] - hh * s->o.fc.fw[i];
  return SYM_SUCCESS;
}

static int
mat_q (void *ctx, const double *x, double *a)
{
  sv_state *s = ctx;
  const int d = s->d, n = s->n;
  int st = sym_fcache_jac (&s->o.fc, s->sys, s->tk + s->hk, x, s->pk);
  if (st)
    return st;
  const double hh = 0.5 * s->hk;
  for (int j = 0; j < d; j++)
    for (int i = 0; i < d; i++)
      a[i + (size_t) j * d] = (i == j ? 1.0 : 0.0)
        - hh * s->o.fc.jw[i + (size_t) j * n];
  sym_kept_built (&s->kq, s->hk);
  return SYM_SUCCESS;
}

static void sv_free (void *state);

static void *
sv_alloc (const sym_system *sys, const sym_method_opts *opts, int *status)
{
  int dummy;
  if (! status)
    status = &dummy;
  sv_state *s = sym_onestep_new (sys, sizeof (sv_state), status);
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
  /* records (aux: 2d), f cache, and x, scale, rv, fqa: 4d, ym: n; the
     separable step is explicit: no Df and no Newton state (O(d^2)) */
  const int implicit = ! s->separable;
  size_t len = sym_recs_len (n, 2 * d) + sym_fcache_len (d, implicit)
               + 4 * (size_t) d + (size_t) n
               + (implicit ? 2 * sym_pred_len (d) : 0);
  s->block = sym_calloc (len, sizeof (double));
  if (! s->block
      || (implicit && (sym_kept_init (&s->kp, d, opts)
                       || sym_kept_init (&s->kq, d, opts))))
    {
      sv_free (s);
      *status = SYM_ENOMEM;
      return NULL;
    }
  double *w = s->block;
  sym_recs_place (&s->o.r, n, 2 * d, w);
  w += sym_recs_len (n, 2 * d);
  sym_fcache_place (&s->o.fc, d, implicit, w);
  w += sym_fcache_len (d, implicit);
  s->x = w; w += d;
  s->scale = w; w += d;
  s->rv = w; w += d;
  s->fqa = w; w += d;
  s->ym = w; w += n;
  if (implicit)
    {
      s->o.npr = 2;
      sym_pred_place (&s->o.pr[0], d, w);
      sym_pred_place (&s->o.pr[1], d, w + sym_pred_len (d));
    }
  *status = SYM_SUCCESS;
  return s;
}

static void
sv_free (void *state)
{
  sv_state *s = state;
  if (! s)
    return;
  /* safe on a zeroed struct too */
  sym_newton_free (&s->kq.nw);
  sym_newton_free (&s->kp.nw);
  sym_free (s->block);
  sym_free (s);
}

/* yerr += (h^3/12) y''', the trapezoidal rule's local error (see the top):
   f'' from the last accepted step's start when it ends where the trial
   starts (cont), else from f at the cubic Hermite midpoint (one call) */
static int
sv_trap_error (sv_state *s, sym_system *sys, int cont, double *yerr)
{
  const sym_rec *tr = s->o.r.trial, *cu = s->o.r.cur;
  const int n = s->n;
  const double h = tr->h;
  if (cont && cu->have_f0 && cu->h * h > 0.0)
    {
      const double hp = cu->h, c = h * h * h / (6.0 * (h + hp));
      for (int i = 0; i < n; i++)
        yerr[i] += c * ((tr->f1[i] - tr->f0[i]) / h
                        - (tr->f0[i] - cu->f0[i]) / hp);
      return SYM_SUCCESS;
    }
  double *ym = s->ym;
  sym_rec_hermite (tr, n, 0.5, ym);
  int st = sym_fcache_f (&s->o.fc, sys, tr->t + 0.5 * h, ym, ym + s->d);
  if (st)
    return st;
  const double *fm = s->o.fc.fw;
  for (int i = 0; i < n; i++)
    yerr[i] += (h / 3.0) * (tr->f0[i] - 2.0 * fm[i] + tr->f1[i]);
  return SYM_SUCCESS;
}

static int
sv_step (void *state, sym_system *sys, double t, double h, double tend,
         const double *y, double *ynext, double *yerr)
{
  sv_state *s = state;
  int st;
  if (! s || ! sys || ! y || ! ynext || ! isfinite (t) || ! isfinite (h)
      || ! isfinite (tend) || h == 0.0)
    return SYM_EBADINPUT;
  const int d = s->d;
  const int cont = sym_recs_begin (&s->o.r, t, h, tend, y);
  sym_rec *tr = s->o.r.trial, *cu = s->o.r.cur;
  const double *q0 = tr->y0, *p0 = tr->y0 + d;
  double *q1 = tr->y1, *p1 = tr->y1 + d, *ph = PH (tr), *fpe = FPE (tr, d);
  const double hh = 0.5 * h;
  s->sys = sys;
  s->tk = t;
  s->hk = h;
  s->yk = tr->y0;

  if (s->separable)
    {
      const double *fp;
      if (cont)
        fp = FPE (cu, d);
      else
        {
          if ((st = sym_recs_f0 (&s->o.r, sys)))
            return st;
          fp = tr->f0 + d;
        }
      for (int i = 0; i < d; i++)
        ph[i] = p0[i] + hh * fp[i];
      st = sym_fcache_f (&s->o.fc, sys, t + hh, q0, ph);     /* A */
      if (st)
        return st;
      for (int i = 0; i < d; i++)
        q1[i] = q0[i] + h * s->o.fc.fw[i];
      memcpy (s->fqa, s->o.fc.fw, (size_t) d * sizeof (double));
      st = sym_fcache_f (&s->o.fc, sys, tr->tend, q1, ph);   /* B */
      if (st)
        return st;
      /* f_q at p_{k+1/2} with q0 and with q1: the same if H is separable
         (and T does not depend on t) */
      sym_sep_check (sys, t, d, s->fqa, s->o.fc.fw);
    }
  else
    {
      double *x = s->x;
      /* (1), started from the history of p_{k+1/2} over an explicit half
         kick (sym_kick_solve) */
      sym_kick kick = { d, &s->o.fc, &s->kp, sys, t, h, hh, tr->y0,
                        &s->o.pr[0] };
      if ((st = sym_kick_solve (&kick, &s->o.r, cont, PH (cu), x, s->scale,
                                s->rv)))
        return st;
      /* the cache holds f at [q_k; P] */
      memcpy (ph, x, (size_t) d * sizeof (double));
      memcpy (s->fqa, s->o.fc.fw, (size_t) d * sizeof (double));
      /* (2), started from the history of q_{k+1} with the base q_k + h
         f_q(t_k, q_k, P) when it serves, else (and again after a
         recoverable failure from there) by the base (sym_pred_solve) */
      s->pk = ph;
      sym_newton_problem pq = { res_q, mat_q, s };
      double *base = s->o.pr[1].xb;
      for (int i = 0; i < d; i++)
        base[i] = q0[i] + h * s->fqa[i];
      st = sym_pred_solve (&s->kq, &pq, sys, h, &s->o.pr[1], cont, h, 1,
                           base, q0, x, s->scale, s->rv);
      if (st)
        return st;
      sym_fcache_move (&s->o.fc, s->tk + s->hk, x, ph);
      memcpy (q1, x, (size_t) d * sizeof (double));
    }
  /* (3): the cache holds f at [q_{k+1}; p_{k+1/2}] on both paths */
  for (int i = 0; i < d; i++)
    {
      fpe[i] = s->o.fc.fw[d + i];
      p1[i] = ph[i] + hh * s->o.fc.fw[d + i];
    }
  if ((st = sym_recs_finish (&s->o.r, sys, s->want_f, yerr, ynext)))
    return st;
  /* (not after a result that overflowed: sym_recs_finish left it
     unevaluated and the trial unfinished) */
  if (yerr && s->o.r.trial_ok && (st = sv_trap_error (s, sys, cont, yerr)))
    s->o.r.trial_ok = 0;
  return st;
}

static int
sv_order (const void *state)
{
  (void) state;
  return 2;
}

static const sym_stepper_type sv_type = {
  "sv", 2, sv_order, sv_order, sv_alloc, sv_step, sym_onestep_accept,
  sym_onestep_dense, sym_onestep_reset, sv_free
};

const sym_stepper_type *const sym_step_sv = &sv_type;
