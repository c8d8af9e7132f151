/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* sv.c -- Stoermer-Verlet (order 2), general H.

   y = [q; p], q, p in R^d, f(t, y) = [f_q; f_p] = [dH/dp; -dH/dq + F].
   One step from (t_k, q_k, p_k) by h (h < 0 runs backwards), t_{k+1} =
   t_k + h:

     p_{k+1/2} = p_k + (h/2) f_p(t_k, q_k, p_{k+1/2})                 (1)
     q_{k+1}   = q_k + (h/2) [f_q(t_k, q_k, p_{k+1/2})
                              + f_q(t_{k+1}, q_{k+1}, p_{k+1/2})]       (2)
     p_{k+1}   = p_{k+1/2} + (h/2) f_p(t_{k+1}, q_{k+1}, p_{k+1/2})     (3)

   (1) and (2) are implicit (d unknowns each), (3) is explicit.  The method
   is symplectic and symmetric (the step by -h from t_{k+1} undoes it).

   Implicit solves: simplified Newton, one kept state per equation,
     (1) the kick of symplectic Euler with h/2 (sym_kick_solve),
     (2) G(Q) = Q - q_k - (h/2) [f_q(t_k, q_k, P) + f_q(t_{k+1}, Q, P)],
         G' ~ I - (h/2) A_qq,
   each started from the history of its unknown over an explicit start
   (Q0 = q_k + h f_q(t_k, q_k, P)), stopped as in se.c.  The f values used
   after each solve are those at the converged unknown (left in the f
   cache).

   Separable H = T(p) + V(q): explicit (leapfrog).  With f_p(q_k) from
   the last step (FSAL) or from f(t_k, y_k) at a fresh start:
     p_{k+1/2} = p_k + (h/2) f_p(q_k)
     A = f(t_k + h/2, [q_k; p_{k+1/2}]) -> q_{k+1} = q_k + h f_q(p_{k+1/2})
     B = f(t_{k+1}, [q_{k+1}; p_{k+1/2}]) -> p_{k+1} = p_{k+1/2}
                                              + (h/2) f_p(q_{k+1})
   Two calls a step (plus one at a fresh start); A at the midpoint time
   keeps the step symmetric for a T(t, p).  With second_order (f_q = p)
   A is not called: one call a step, and f at the step's end is known.

   Position form (own->position, separable H only): the adjoint
   drift-kick-drift step, q half drifts around a whole kick at the
   midpoint, also two calls a step (one with second_order; sv_position).

   Error estimate, of the local error y_{k+1} - y(t_{k+1}):
     err = y_{k+1} - y_k - (h/2) (f(t_k, y_k) + f(t_{k+1}, y_{k+1}))
           + (h^3/12) y''',
   the difference to the trapezoidal rule plus the rule's own leading
   error (for a separable H the first part vanishes in p: the p-update is
   the trapezoidal rule).  O(h^3) (order 2), componentwise.  y''' = f''
   is the second divided difference of f through the last step's start,
   t_k and t_{k+1} when the steps continue one another, else through t_k,
   t_k + h/2 and t_{k+1} with f at the cubic Hermite midpoint (one more
   call).

   Dense output: the cubic Hermite interpolant through the step's ends
   when both f are known, else linear. */
#include "onestep.h"

#include <float.h>
#include <math.h>
#include <string.h>

/* Each step record also keeps (aux) p_{k+1/2} and f_p(t_{k+1}, q_{k+1},
   p_{k+1/2}), d values each (the position form: q_{k+1/2} and f_q(t_{k+1},
   q_{k+1/2}, p_{k+1})). */
#define PH(rec) ((rec)->aux)
#define FPE(rec, d) ((rec)->aux + (d))

typedef struct {
  sym_onestep o;         /* first: accept and dense (onestep.h) */
  double *x, *scale;     /* d: Newton unknown, its scale */
  double *fqa;           /* d: f_q(t_k, q_k, p_{k+1/2}) */
  double *ym;            /* n: the estimate's midpoint at a fresh start */
  int position;          /* drift-kick-drift (explicit steps only) */
  /* the step being solved (for the Newton callbacks) */
  sym_eval *ev;
  double tk, hk;
  const double *yk;
  const double *pk;      /* (2): p_{k+1/2} */
} sv_state;

/* (2): G(Q) = Q - q_k - (h/2) [f_q(t_k, q_k, P) + f_q(t_{k+1}, Q, P)] */
static int
res_q (void *ctx, const double *x, double *r)
{
  sv_state *s = ctx;
  const int d = s->o.d;
  int st = sym_fcache_f (&s->o.fc, s->ev, s->tk + s->hk, x, s->pk);
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
  const int d = s->o.d, n = s->o.n;
  int st = sym_fcache_jac (&s->o.fc, s->ev, s->tk + s->hk, x, s->pk);
  if (st)
    return st;
  const double hh = 0.5 * s->hk;
  for (int j = 0; j < d; j++)
    for (int i = 0; i < d; i++)
      a[i + (size_t) j * d] = (i == j ? 1.0 : 0.0)
        - hh * s->o.fc.jw[i + (size_t) j * n];
  sym_kept_built (&s->o.k[1], s->hk);
  return SYM_SUCCESS;
}

/* the sparse matrix of the drift, I - (h/2) A_qq (a problem's factor and
   solve) */
static int
factor_q (void *ctx, const double *x, sym_counters *cnt)
{
  sv_state *s = ctx;
  int st = sym_fcache_jac (&s->o.fc, s->ev, s->tk + s->hk, x, s->pk);
  return st ? st : sym_kept_factor (&s->o.k[1], &s->o.fc, 0, 0.5 * s->hk,
                                    s->hk, cnt);
}

static int
lsolve_q (void *ctx, double *b, sym_counters *cnt)
{
  sv_state *s = ctx;
  return sym_stage_lu_solve (&s->o.k[1].slu, b, cnt);
}

static void *
sv_alloc (int dim, const sym_method_opts *opts, int *status)
{
  int dummy;
  if (! status)
    status = &dummy;
  const sym_onestep_opts *own = opts ? opts->own : NULL;
  /* the position form is explicit only */
  if (own && own->position && ! own->separable && ! own->second_order)
    {
      *status = SYM_EBADINPUT;
      return NULL;
    }
  /* records with aux (2d); own: x, scale, fqa (d each), ym (n); two
     implicit unknowns */
  double *w;
  sv_state *s = sym_onestep_alloc (dim, 2, sizeof (sv_state), 2, 2 * dim,
                                   5 * (size_t) dim, opts, status, &w);
  if (! s)
    return NULL;
  const int d = dim;
  s->position = own && own->position;
  s->x = w; w += d;
  s->scale = w; w += d;
  s->fqa = w; w += d;
  s->ym = w;
  return s;
}

/* yerr += (h^3/12) y''', the trapezoidal rule's local error (see the top):
   f'' from the last accepted step's start when it ends where the trial
   starts (cont), else from f at the cubic Hermite midpoint (one call) */
static int
sv_trap_error (sv_state *s, sym_eval *ev, int cont, double *yerr)
{
  const sym_rec *tr = s->o.r.trial, *cu = s->o.r.cur;
  const int n = s->o.n;
  const double h = tr->h;
  if (cont && cu->have_f0 && cu->h * h > 0.0)
    {
      /* (h^3 / (6 (h + hp))) times the divided difference, as h times
         differences of f and ratios of steps: no power of h, which
         overflows for huge spans and underflows for tiny ones */
      const double hp = cu->h, r = h / (6.0 * (h + hp)), q = h / hp;
      for (int i = 0; i < n; i++)
        yerr[i] += h * (r * ((tr->f1[i] - tr->f0[i])
                             - q * (tr->f0[i] - cu->f0[i])));
      return SYM_SUCCESS;
    }
  double *ym = s->ym;
  sym_rec_hermite (tr, n, 0.5, ym);
  int st = sym_fcache_f (&s->o.fc, ev, tr->t + 0.5 * h, ym, ym + s->o.d);
  if (st)
    return st;
  const double *fm = s->o.fc.fw;
  for (int i = 0; i < n; i++)
    yerr[i] += (h / 3.0) * (tr->f0[i] - 2.0 * fm[i] + tr->f1[i]);
  return SYM_SUCCESS;
}

/* the end of a step: f at the ends as needed, the estimate, ynext */
static int
sv_finish (sv_state *s, sym_eval *ev, int cont, double *yerr,
           double *ynext)
{
  int st = sym_recs_finish (&s->o.r, ev, s->o.want_f, yerr, ynext);
  if (st)
    return st;
  /* (not after a result that overflowed: sym_recs_finish left it
     unevaluated and the trial unfinished) */
  if (yerr && s->o.r.trial_ok && (st = sv_trap_error (s, ev, cont, yerr)))
    s->o.r.trial_ok = 0;
  return st;
}

/* The position form (drift-kick-drift) for a separable H, into the
   trial's y1.  With f_q(p_k) from the last step (FSAL: its end's drift
   evaluated it) or from f(t_k, y_k) at a fresh start:
     q_{k+1/2} = q_k + (h/2) f_q(p_k)
     B = f(t_k + h/2, [q_{k+1/2}; p_k]) -> p_{k+1} = p_k + h f_p(q_{k+1/2})
     C = f(t_{k+1}, [q_{k+1/2}; p_{k+1}]) -> q_{k+1} = q_{k+1/2}
                                               + (h/2) f_q(p_{k+1})
   Two calls a step; with second_order (f_q = p) one, B, and f at the
   step's end is not known (f_p(q_{k+1}) is never evaluated).  The aux
   of a record keeps q_{k+1/2} and f_q(p_{k+1}). */
static int
sv_position (sv_state *s, sym_eval *ev, const sym_trial *v)
{
  const int d = v->d, so = s->o.second_order;
  const double t = v->tr->t, h = v->tr->h, hh = 0.5 * h;
  const double *fq = v->p0;
  double *qh = PH (v->tr), *fqe = FPE (v->tr, d);
  int st;
  if (! so)
    {
      if (v->cont)
        fq = FPE (v->cu, d);
      else
        {
          if ((st = sym_recs_f0 (&s->o.r, ev)))
            return st;
          fq = v->tr->f0;
        }
      memcpy (s->fqa, fq, (size_t) d * sizeof (double));
    }
  for (int i = 0; i < d; i++)
    qh[i] = v->q0[i] + hh * fq[i];
  sym_tangent *tg = s->o.tg;
  if (tg && ((st = sym_tangent_drift (tg, ev, t, v->q0, v->p0, hh, so))
             || (st = sym_tangent_kick (tg, ev, t + hh, qh, v->p0, h))))
    return st;
  sym_fcache_feed (&s->o.fc, tg, t + hh, qh, v->p0);
  if ((st = sym_fcache_f (&s->o.fc, ev, t + hh, qh, v->p0)))  /* B */
    return st;
  /* f_q at p_k with q_k (or q_{k-1/2}) and with q_{k+1/2}: the same if H
     is separable (and T does not depend on t) */
  if (! so)
    sym_sep_check (ev, t, d, s->fqa, s->o.fc.fw);
  for (int i = 0; i < d; i++)
    v->p1[i] = v->p0[i] + h * s->o.fc.fw[d + i];
  if (tg && (st = sym_tangent_drift (tg, ev, v->tr->tend, qh, v->p1, hh,
                                     so)))
    return st;
  if (so)
    {
      for (int i = 0; i < d; i++)
        v->q1[i] = qh[i] + hh * v->p1[i];
      return SYM_SUCCESS;
    }
  sym_fcache_feed (&s->o.fc, tg, v->tr->tend, qh, v->p1);
  if ((st = sym_fcache_f (&s->o.fc, ev, v->tr->tend, qh, v->p1)))  /* C */
    return st;
  for (int i = 0; i < d; i++)
    {
      fqe[i] = s->o.fc.fw[i];
      v->q1[i] = qh[i] + hh * fqe[i];
    }
  return SYM_SUCCESS;
}

static int
sv_step (void *state, sym_eval *ev, double t, double h, double tend,
         const double *y, double *ynext, double *yerr)
{
  sv_state *s = state;
  const double hh = 0.5 * h;
  sym_trial v;
  int st = sym_onestep_trial (&s->o, ev, t, h, tend, y, ynext, &v);
  if (st)
    return st;
  const int d = v.d;
  double *ph = PH (v.tr), *fpe = FPE (v.tr, d);
  s->ev = ev;
  s->tk = t;
  s->hk = h;
  s->yk = v.tr->y0;

  if (s->o.separable && s->position)
    {
      if ((st = sv_position (s, ev, &v)))
        return st;
      return sv_finish (s, ev, v.cont, yerr, ynext);
    }
  if (s->o.separable)
    {
      const double *fp;
      if (v.cont)
        fp = FPE (v.cu, d);
      else
        {
          if ((st = sym_recs_f0 (&s->o.r, ev)))
            return st;
          fp = v.tr->f0 + d;
        }
      for (int i = 0; i < d; i++)
        ph[i] = v.p0[i] + hh * fp[i];
      if (s->o.tg
          && ((st = sym_tangent_kick (s->o.tg, ev, t, v.q0, v.p0, hh))
              || (st = sym_tangent_drift (s->o.tg, ev, t + hh, v.q0, ph, h,
                                          s->o.second_order))))
        return st;
      if (s->o.second_order)
        for (int i = 0; i < d; i++)
          v.q1[i] = v.q0[i] + h * ph[i];
      else
        {
          sym_fcache_feed (&s->o.fc, s->o.tg, t + hh, v.q0, ph);
          st = sym_fcache_f (&s->o.fc, ev, t + hh, v.q0, ph);     /* A */
          if (st)
            return st;
          for (int i = 0; i < d; i++)
            v.q1[i] = v.q0[i] + h * s->o.fc.fw[i];
          memcpy (s->fqa, s->o.fc.fw, (size_t) d * sizeof (double));
        }
      if (s->o.tg
          && (st = sym_tangent_kick (s->o.tg, ev, v.tr->tend, v.q1, ph, hh)))
        return st;
      sym_fcache_feed (&s->o.fc, s->o.tg, v.tr->tend, v.q1, ph);
      st = sym_fcache_f (&s->o.fc, ev, v.tr->tend, v.q1, ph);   /* B */
      if (st)
        return st;
      /* f_q at p_{k+1/2} with q0 and with q1: the same if H is separable
         (and T does not depend on t) */
      if (! s->o.second_order)
        sym_sep_check (ev, t, d, s->fqa, s->o.fc.fw);
    }
  else
    {
      double *x = s->x;
      /* (1), started from the history of p_{k+1/2} over an explicit half
         kick (sym_kick_solve) */
      sym_kick kick = { d, &s->o.fc, &s->o.k[0], ev, t, h, hh, v.tr->y0,
                        &s->o.pr[0] };
      if ((st = sym_kick_solve (&kick, &s->o.r, v.cont, PH (v.cu), x,
                                s->scale)))
        return st;
      /* the cache holds f at [q_k; P] */
      memcpy (ph, x, (size_t) d * sizeof (double));
      memcpy (s->fqa, s->o.fc.fw, (size_t) d * sizeof (double));
      /* (2), started from the history of q_{k+1} with the base q_k + h
         f_q(t_k, q_k, P) when it serves, else (and again after a
         recoverable failure from there) by the base (sym_pred_solve) */
      s->pk = ph;
      sym_newton_problem pq = { res_q, mat_q, s,
                                s->o.sparse ? factor_q : NULL,
                                s->o.sparse ? lsolve_q : NULL, NULL };
      double *base = s->o.pr[1].xb;
      for (int i = 0; i < d; i++)
        base[i] = v.q0[i] + h * s->fqa[i];
      st = sym_pred_solve (&s->o.k[1], &pq, ev, h, &s->o.pr[1], v.cont, h, 1,
                           base, v.q0, x, s->scale);
      if (st)
        return st;
      sym_fcache_move (&s->o.fc, s->tk + s->hk, x, ph);
      memcpy (v.q1, x, (size_t) d * sizeof (double));
    }
  /* (3): the cache holds f at [q_{k+1}; p_{k+1/2}] on both paths */
  for (int i = 0; i < d; i++)
    {
      fpe[i] = s->o.fc.fw[d + i];
      v.p1[i] = ph[i] + hh * s->o.fc.fw[d + i];
    }
  if (s->o.second_order)
    {
      /* f at the end is [p_{k+1}; f_p(q_{k+1})]: no call */
      memcpy (v.tr->f1, v.p1, (size_t) d * sizeof (double));
      memcpy (v.tr->f1 + d, fpe, (size_t) d * sizeof (double));
      v.tr->have_f1 = 1;
    }
  return sv_finish (s, ev, v.cont, yerr, ynext);
}

static const sym_stepper_type sv_type =
  SYM_ONESTEP_TYPE ("sv", sv_alloc, sym_onestep_set_tolerances, sv_step,
                    sym_onestep_free);

const sym_stepper_type *const sym_step_sv = &sv_type;
