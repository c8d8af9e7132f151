/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* steprec.h -- internal to the core: what the one-step methods of
   step_se.c and step_sv.c share (step_spvi.c takes the cubic Hermite
   interpolant).  A pair of step records (the last accepted step and the
   one being tried, swapped on accept) with the f values at their ends,
   their dense output, a cache of the last f (and Df) evaluation, and the
   checked Newton solve with its kept matrix. */
#ifndef SYM_STEPREC_H
#define SYM_STEPREC_H

#include "sym.h"

/* Newton iterations a solve needs with a fresh matrix and a good start;
   iterations beyond this are charged to the kept matrix */
#define SYM_NW_BASE 2

/* A fixed step (no error estimate wanted) is solved to SYM_FIXED_TOL
   times the Newton tolerance, in all three steppers (odeSPVI: the
   estimated error of the returned solution, see core_solve in
   step_spvi.c); for odeSE and odeSV SYM_FIXED_TOL_KEPT (below), round-off:
   1e-17 relative by default, the residual check then at 8 eps; an
   adaptive step to the
   tolerance itself (odeSPVI: see spvi_step).
   With the matrix kept, the error a stop leaves has the same sign from
   step to step, so it adds up: on H = |p|^2/2 (1 + |q|^2/4) - 1/|q| in
   3-D (rotation-invariant, non-separable; h = 2 pi/200, finite-difference
   matrices) the angular momentum drifted linearly by 4.2e-12 (odeSE) and
   2.4e-11 (odeSV) over 20000 steps at the tolerance itself, 5.4e-13 and
   1.4e-12 at 1e-1 of it; at 1e-2, 6e-14 (round-off: sqrt(20000) eps |L|
   is 2.6e-14; tests/test_se_sv.m holds 10000 steps within 2e-13) for 8%
   more calls (6.28 -> 6.79 and 10.67 -> 11.57 per step); with the
   Hessian as FCN's second output on H = p^2/2 (1 + q^2) + q^4/4, 9% and
   3% more. */
#define SYM_FIXED_TOL 1e-2
/* odeSE and odeSV: a tenth of that.  At 1e-2, with finite-difference
   matrices (whose slower contraction leaves the stop nearer its bound),
   odeSV still drifted on H = |p|^2/2 (1 + |q|^2/4) + |q|^4/8 + (q.p)^2/4
   in 3-D, h = 0.05: the angular momentum by 4.1e-13 over 40000 steps;
   at 1e-3, 2.2e-14, for the same calls per step (14.598).  Calls per
   step on five problems (pendulum, Kepler and these with Separable off,
   finite differences or the Hessian): +0 to +0.5%, +2.4% for odeSE on H
   = p^2/2 (1 + q^2) + q^2/2 with finite differences.  Still needed with
   the starts from the history (sym_pred): on the first H at h = 0.05,
   10000 steps, L drifted by 1.5e-13 to 7.8e-13 at the tolerance itself
   (odeSE, odeSV; Hessian or finite differences), <= 1e-14 at 1e-3 of it,
   for at most 12% more calls. */
#define SYM_FIXED_TOL_KEPT 1e-3

/* One step: its start, end, the f values known at its two ends, and the
   method's own values (aux), which travel with the record. */
typedef struct {
  double t, h, tend;
  double *y0, *y1, *f0, *f1;    /* n each */
  double *aux;                  /* naux */
  int have_f0, have_f1;
} sym_rec;

typedef struct {
  int n, naux;
  sym_rec rec[2];
  sym_rec *cur, *trial;   /* last accepted step, step being tried */
  int have_cur;
  int trial_ok;           /* the last step succeeded: accept may take it */
} sym_recs;

/* The start of the SE and SV allocs: a zeroed state of size bytes, or
   NULL with *status SYM_EBADINPUT (no system) or SYM_ENOMEM. */
void *sym_onestep_new (const sym_system *sys, size_t size, int *status);

/* doubles the records need; place them in w */
size_t sym_recs_len (int n, int naux);
void sym_recs_place (sym_recs *r, int n, int naux, double *w);
/* Start the trial step (t, h), ending at the time tend, from y: f(t, y)
   is reused from an earlier attempt from the same point, or from the end
   of the last accepted step.  Returns whether the last accepted step ends
   where this one starts. */
int sym_recs_begin (sym_recs *r, double t, double h, double tend,
                    const double *y);
/* f at the trial step's start, evaluated if not known */
int sym_recs_f0 (sym_recs *r, sym_system *sys);
/* Finish the trial step whose end is in trial->y1: f at both ends when
   want_f or yerr (one call at the end; the start's is shared), the
   estimate yerr = y1 - y0 - h/2 (f0 + f1), ynext. */
int sym_recs_finish (sym_recs *r, sym_system *sys, int want_f, double *yerr,
                     double *ynext);
void sym_recs_accept (sym_recs *r);
/* cubic Hermite with both f values, else linear; exact at the ends */
int sym_recs_dense (const sym_recs *r, double t, double *y);
/* the cubic Hermite interpolant through (y0, f0) at t and (y1, f1) at
   t + h, at t + th h (n components); of step c (both f known) */
void sym_hermite (int n, double h, double th, const double *y0,
                  const double *y1, const double *f0, const double *f1,
                  double *y);
void sym_rec_hermite (const sym_rec *c, int n, double th, double *y);
/* forget the last step and every f kept */
void sym_recs_forget (sym_recs *r);

/* The last evaluation of f (at yw, into fw) and a Jacobian work area. */
typedef struct {
  int d;
  double *yw, *fw, *ym, *jw;    /* n, n, n, n*n */
  double tw;
  int have_fw;
  int have_jw;                  /* jw holds a Df (of some recent point) */
} sym_fcache;

/* The start of an implicit solve from the history of its unknown x (SE:
   p_{k+1}; SV: p_{k+1/2} and q_{k+1}) over the last accepted steps.  The
   history holds the errors x - base of an explicit start, the base (the
   kick's p_k + c f_p(t_k, y_k) when f there is known, else its
   continuation of the last step's increment, see sym_kick_solve; SV's
   q_k + h f_q(t_k, q_k, p_{k+1/2})): a smooth function of the step's
   start, O(h^2), and zero where the base is exact (as for a separable
   part of H).  Divided by h^2, they are extrapolated to the new step by
   the Lagrange polynomial through the newest L + 1 of them at the times
   they stand for (offsets from their steps' starts plus the steps'
   sizes), L the degree (0 to SYM_PRED_MAX - 2, or none: the base alone) that
   would have predicted the newest error best from the ones before it.
   Measured (tests/c/test_se_sv_robust.c, LU policy, P_H1, h = 0.01 and
   0.05, rhs + jac calls per step): SE 2.01 and 3.29, SV 3.86 and 6.13;
   with the explicit starts alone 4.04 and 5.34, 7.89 and 9.80.  On the
   3-D H of tests/test_se_sv.m with the Hessian, h = 0.05, calls per step
   of odeSE (odeSV) with errors kept over 4, 8, 12, 16 steps: 4.52 (8.97),
   3.55 (6.97), 3.31 (6.13), 3.05 (6.00); at h = 0.01, 3.01 (6.00) with
   4, 2.00 (3.98) from 8 on; at h = 0.1 and 0.2, 4.73 and 5.22 (9.10 and
   10.60) with 16, 6.56 and 8.05 (11.35 and 13.57) from the explicit
   starts.  Dividing by h^2 (an error of the explicit start is O(h^2))
   keeps them smooth where h changes: adaptive odeSV at RelTol = AbsTol =
   1e-7 on that H takes 13% fewer calls than without.  A fixed step is h
   itself at any t (driver.c): when it was the difference of the rounded
   ends t0 + k h, which varies by the round-off of t, the errors varied
   with it (SE's explicit start has terms in h h_prev), and odeSE at
   h = 0.01 took 2.28, 2.56, 3.00 calls per step from t0 = 1e4, 1e6, 1e8
   instead of 2.00. */
#define SYM_PRED_MAX 16
typedef struct {
  int d;                   /* the unknown's size */
  int n;                   /* errors held (x), newest first */
  int kind;                /* of their base (a caller's label) */
  int have_new, new_cont, new_kind;  /* the trial's solved value, whether
                              the trial continued the last accepted step,
                              the kind of its base */
  double hs[SYM_PRED_MAX], hnew;  /* the sizes of their steps */
  double cs[SYM_PRED_MAX], cnew;  /* their offsets from their steps'
                                     starts */
  double *x;               /* SYM_PRED_MAX * d */
  double *xnew;            /* d */
  double *xb;              /* d: work for the caller's base */
  /* the Lagrange weights of the last start, kept for the next one at the
     same times (every start of a fixed-step run): wr[L] those of degree L
     at the newest value from the ones before it, wf[L] at the new unknown
     (wf_ok[L]: computed); they cost 1.8 us a start where computed anew
     (16 values, d = 3; odeSE's step is 35 us), 0.45 us taken from here */
  int wn, wf_ok[SYM_PRED_MAX];
  double wu[SYM_PRED_MAX], wt;
  double wr[SYM_PRED_MAX][SYM_PRED_MAX], wf[SYM_PRED_MAX][SYM_PRED_MAX];
} sym_pred;

size_t sym_pred_len (int d);
void sym_pred_place (sym_pred *p, int d, double *w);
/* the solution x of its unknown of the trial step of size h, at offset c
   from the step's start (t_k + c), base its explicit start of the given
   kind; cont: the trial starts where the last accepted step ended */
void sym_pred_note (sym_pred *p, int cont, double h, double c,
                    const double *x, int kind, const double *base);
/* The start into x for the unknown at offset c from the start of a trial
   step of size h that continues the last accepted one (kind, base: as for
   sym_pred_note; x may be base) when the history holds at least two
   errors of a base of that kind, the unknown is ahead of the newest by
   at most twice the spacing of the last two, and an extrapolation
   predicted the newest error better than none; returns 1, else 0 (x
   untouched: the base alone is the start). */
int sym_pred_start (sym_pred *p, double h, double c, int kind,
                    const double *base, double *x);

/* The head of the SE and SV states (their first member): what their
   accept, dense output and reset act on */
typedef struct {
  sym_recs r;            /* last accepted step, step being tried */
  sym_fcache fc;         /* the last f evaluated */
  int npr;               /* implicit unknowns with a predictor (0 to 2) */
  sym_pred pr[2];
} sym_onestep;

/* accept, dense and reset of a state that starts with a sym_onestep;
   reset forgets the last step (dense output, predictor, FSAL) and every f
   kept, the Newton matrices stay: newton.c refreshes them if they no
   longer serve */
void sym_onestep_accept (void *state);
int sym_onestep_dense (void *state, sym_system *sys, double t, double *y);
void sym_onestep_reset (void *state);

/* The cache's workspace: with jac, also the n x n Df (jw) that the
   implicit steps' Newton matrices are built from; without, jw is NULL
   (the explicit separable steps never ask for Df, and at large d it
   would be most of their memory). */
size_t sym_fcache_len (int d, int jac);
void sym_fcache_place (sym_fcache *c, int d, int jac, double *w);
/* f at (t, [a; b]) into fw; no call when fw already holds f there */
int sym_fcache_f (sym_fcache *c, sym_system *sys, double t, const double *a,
                  const double *b);
/* Df at (t, [a; b]) into jw.  For finite differences f is evaluated there
   first: the differences need it, and the iteration's first residual then
   finds it in fw. */
int sym_fcache_jac (sym_fcache *c, sym_system *sys, double t,
                    const double *a, const double *b);
/* After a Newton solve that stopped on a correction of round-off size
   (sym_kept_solve) fw holds f at the iterate before it: moved linearly by
   jw to (t, [a; b]), no call.  Used as f there without the move, that
   error of a few ulps kept its sign from step to step (the kept matrix)
   and drifted: the angular momentum of a rotation-invariant H in 3-D,
   odeSE, by 1.5e-17 per step.  Nothing is done where fw is at another t,
   already at [a; b], or there is no Df in jw. */
void sym_fcache_move (sym_fcache *c, double t, const double *a,
                      const double *b);

/* A Newton state with the h its matrix was built with and the iterations
   beyond SYM_NW_BASE charged to that matrix. */
typedef struct {
  sym_newton nw;
  double h_mat;
  long extra;
} sym_kept;

/* to be called by a matrix callback that has built a matrix for h */
void sym_kept_built (sym_kept *k, double h);
/* Solve for x (d unknowns, scale sc) with the kept matrix for step h: a
   new matrix when h changed by more than 20% or the extra iterations have
   cost as much as a new Jacobian.  newton.c may stop after one iteration,
   judging by an earlier solve's rate; the residual at the solution (which
   leaves f there in the cache the residual uses) checks that, and a failed
   check iterates on with the rate it shows (three solves at most).  A last
   correction at round-off level needs no check.  rv, scale: d of work. */
int sym_kept_solve (sym_kept *k, const sym_newton_problem *prob,
                    sym_system *sys, double h, int d, double sc, double *x,
                    double *scale, double *rv);

/* sym_newton_init for d unknowns with the tolerance and iteration limit
   of opts (if set); a fixed step's tolerance is SYM_FIXED_TOL times
   opts' */
int sym_kept_init (sym_kept *k, int d, const sym_method_opts *opts);

/* sym_kept_solve for the unknown of the history pr at offset c from the
   start of the trial step (of size h), from
   sym_pred_start's start when the trial continues the last accepted step
   (cont) and the history serves, else from base (kind: as for
   sym_pred_note); again from base after a recoverable failure
   (status > 0) from the history's start (counted in nrestart).  The
   scale is the max norm of ref (the unknown's value at the step's start)
   or of the start's distance to it, whichever is larger.  On success x
   is noted in the history. */
int sym_pred_solve (sym_kept *k, const sym_newton_problem *prob,
                    sym_system *sys, double h, sym_pred *pr, int cont,
                    double c, int kind, const double *base,
                    const double *ref, double *x, double *scale,
                    double *rv);

/* The implicit kick P = p_k + c f_p(t_k, q_k, P) of symplectic Euler
   (c = h) and of Stormer-Verlet's first half kick (c = h/2):
     G(P) = P - p_k - c f_p(t_k, q_k, P),   G'(P) ~ I - c A_pp,
   A_pp = d f_p / d p; f at [q_k; P] stays in the cache fc. */
typedef struct {
  int d;
  sym_fcache *fc;
  sym_kept *k;            /* the Newton state kept for this kick */
  sym_system *sys;
  double t, h, c;         /* t_k, the step, the kick's coefficient */
  const double *yk;       /* [q_k; p_k] */
  sym_pred *pr;           /* the history of P (at t_k + c) */
} sym_kick;

/* Solve the kick of the trial step of r into x (d), with scale, rv: d of
   work, by sym_pred_solve with the history kk->pr.  The base (the
   explicit start): P0 = p_k + c f_p(t_k, y_k) when f(t_k, y_k) is known,
   else p_k + (p_k - prev) h / h_prev from the last accepted step when it
   ends where this one starts (cont; prev: its p at the point matching P;
   for SV this is p_k + c f_p(t_k, q_k, p_{k-1/2}), exact for a separable
   H), else f(t_k, y_k) is evaluated (one call), as it is when that
   increment and p_k both vanish.  Newton's scale is max(|p_k|, |start -
   p_k|) (1 if both vanish).  On success the cache holds f at [q_k; P]
   (sym_fcache_move). */
int sym_kick_solve (const sym_kick *kk, sym_recs *r, int cont,
                    const double *prev, double *x, double *scale,
                    double *rv);

int sym_same_vec (int n, const double *a, const double *b);
/* the end of the last step (of size h) and the start of this one: the
   driver may form them as t + h and t0 + k h, a few ulps apart */
int sym_same_time (double a, double b, double h);
double sym_norm_inf (int n, const double *v);

#endif
