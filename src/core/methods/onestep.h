/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* onestep.h -- internal to the core: what the one-step methods (se.c,
   sv.c) share.  A pair of step records (the last accepted step and the
   one being tried, swapped on accept) with the f values at their ends and
   their dense output (onestep.c), a cache of the last f (and Df), and
   the implicit solves: Newton with a kept matrix, started from the
   history of the unknowns (implicit.c). */
#ifndef SYM_ONESTEP_H
#define SYM_ONESTEP_H

#include "../sym.h"
#include "../numerics/numerics.h"
#include "tangent.h"

/* ---------------------------------------------------------------- records */
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
int sym_recs_f0 (sym_recs *r, sym_eval *ev);
/* Finish the trial step whose end is in trial->y1: f at both ends when
   want_f or yerr (one call at the end unless the step has set it,
   have_f1; the start's is shared), the
   estimate yerr = y1 - y0 - h/2 (f0 + f1), ynext. */
int sym_recs_finish (sym_recs *r, sym_eval *ev, int want_f, double *yerr,
                     double *ynext);
/* the cubic Hermite interpolant of step c (both f known) at t + th h */
void sym_rec_hermite (const sym_rec *c, int n, double th, double *y);

/* ---------------------------------------------------------------- f cache */
/* The last evaluation of f (at yw, into fw) and a Jacobian work area. */
typedef struct {
  int d;
  double *yw, *fw, *ym, *jw;    /* n, n, n, n*n */
  int sparse;                   /* Df into js, not jw */
  sym_csc js;
  double tw;
  int have_fw;
  int have_jw;                  /* jw holds a Df (of some recent point) */
} sym_fcache;

/* The cache's workspace: with jac, also the n x n Df (jw) that Newton's
   matrices are built from; without, jw is NULL (explicit separable steps
   never ask for Df, and at large d it would be most of their memory). */
size_t sym_fcache_len (int d, int jac);
void sym_fcache_place (sym_fcache *c, int d, int jac, double *w);
/* f at (t, [a; b]) into fw; no call when fw already holds f there */
int sym_fcache_f (sym_fcache *c, sym_eval *ev, double t, const double *a,
                  const double *b);
/* f at (t, [a; b]) into fw from the tangent map's last call of f and
   Df, when it was there (tg NULL: nothing) */
void sym_fcache_feed (sym_fcache *c, const sym_tangent *tg, double t,
                      const double *a, const double *b);
/* Df at (t, [a; b]) into jw.  For finite differences f is evaluated there
   first: the differences need it, and the iteration's first residual then
   finds it in fw. */
int sym_fcache_jac (sym_fcache *c, sym_eval *ev, double t,
                    const double *a, const double *b);
/* After a Newton solve that stopped on a correction of round-off size fw
   holds f at the iterate before it: moved linearly by jw to (t, [a; b]),
   no call (used unmoved, that error kept its sign from step to step and
   drifted).  Nothing is done where fw is at another t, already at
   [a; b], or there is no Df in jw. */
void sym_fcache_move (sym_fcache *c, double t, const double *a,
                      const double *b);

/* ---------------------------------------------------------------- history */
/* The start of an implicit solve from the history of its unknown x (SE:
   p_{k+1}; SV: p_{k+1/2} and q_{k+1}) over the last accepted steps.  The
   history holds the errors x - base of an explicit start (a caller's
   base of some kind: see sym_kick_solve): a smooth function of the step's
   start, O(h^2), zero where the base is exact.  Divided by h^2, they are
   extrapolated to the new step by the Lagrange polynomial through the
   newest L + 1 of them at the times they stand for (offsets from their
   steps' starts plus the steps' sizes), L the degree (0 to
   SYM_PRED_MAX - 2, or none: the base alone) that would have predicted
   the newest error best from the ones before it. */
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
     (wf_ok[L]: computed) */
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
/* the accepted trial's value becomes the newest; a trial that did not
   continue the last accepted step, or had another kind of base, starts
   the history anew */
void sym_pred_commit (sym_pred *p);
/* The start into x for the unknown at offset c from the start of a trial
   step of size h that continues the last accepted one (kind, base: as for
   sym_pred_note; x may be base) when the history holds at least two
   errors of a base of that kind, the unknown is ahead of the newest by
   at most twice the spacing of the last two, and an extrapolation
   predicted the newest error better than none; returns 1, else 0 (x
   untouched: the base alone is the start). */
int sym_pred_start (sym_pred *p, double h, double c, int kind,
                    const double *base, double *x);


/* ---------------------------------------------------------------- Newton */
/* A Newton state with the h its matrix was built with, the iterations
   beyond SYM_NW_BASE charged to that matrix, and the tolerance of
   adaptive steps (fixed steps solve to SYM_FIXED_TOL_KEPT of it). */
typedef struct {
  sym_newton nw;
  double h_mat;
  long extra;
  double tol;
  /* a sparse Df: the matrix I - c B (B a block of Df) by KLU */
  int sparse;
  sym_stage_lu slu;
  sym_csc blk;
} sym_kept;

/* sym_newton_init for d unknowns, the tolerance of fixed steps */
int sym_kept_init (sym_kept *k, int d, const sym_method_opts *opts,
                   int sparse);
void sym_kept_free (sym_kept *k);
/* a sparse Newton matrix I - c B, B the d-by-d block of fc's Df at (r0,
   r0), factored (a matrix callback's work, sym_kept_built included) */
int sym_kept_factor (sym_kept *k, const sym_fcache *fc, int r0, double c,
                     double h, sym_counters *cnt);
/* adaptive steps: the tolerance itself */
void sym_kept_adaptive (sym_kept *k);
/* to be called by a matrix callback that has built a matrix for h */
void sym_kept_built (sym_kept *k, double h);
/* Solve for x (d unknowns) with the kept matrix for step h: a new
   matrix when h changed by more than SYM_REBUILD_H or the extra
   iterations have cost as much as a new Jacobian.  The scale of the test
   is the max norm of ref (the unknown's value at the step's start) or of
   x's distance to it, whichever is larger: at the start for newton.c,
   at the result for the check.  newton.c may stop after one iteration,
   judging by an earlier solve's rate; one more correction from x with
   the same matrix (which leaves f at x in the cache) checks that by
   newton.c's own estimate with the rate it shows, and a failed check
   takes that correction and iterates on (SYM_KEPT_ROUNDS solves at most,
   then SYM_NEWTON_FAIL).  A last correction at round-off level needs no
   check.  scale: d of work. */
int sym_kept_solve (sym_kept *k, const sym_newton_problem *prob,
                    sym_eval *ev, double h, int d, const double *ref,
                    double *x, double *scale);
/* sym_kept_solve for the unknown of the history pr at offset c from the
   start of the trial step (of size h), from sym_pred_start's start when
   the trial continues the last accepted step (cont) and the history
   serves, else from base (kind: as for sym_pred_note); again from base
   after a recoverable failure from the history's start (counted in
   nrestart).  On success x is noted in the history. */
int sym_pred_solve (sym_kept *k, const sym_newton_problem *prob,
                    sym_eval *ev, double h, sym_pred *pr, int cont,
                    double c, int kind, const double *base,
                    const double *ref, double *x, double *scale);

/* The implicit kick P = p_k + c f_p(t_k, q_k, P) of symplectic Euler
   (c = h) and of Stormer-Verlet's first half kick (c = h/2):
     G(P) = P - p_k - c f_p(t_k, q_k, P),   G'(P) ~ I - c A_pp,
   A_pp = d f_p / d p; f at [q_k; P] stays in the cache fc. */
typedef struct {
  int d;
  sym_fcache *fc;
  sym_kept *k;            /* the Newton state kept for this kick */
  sym_eval *ev;
  double t, h, c;         /* t_k, the step, the kick's coefficient */
  const double *yk;       /* [q_k; p_k] */
  sym_pred *pr;           /* the history of P (at t_k + c) */
} sym_kick;

/* Solve the kick of the trial step of r into x (d), with scale: d of
   work, by sym_pred_solve with the history kk->pr.  The base (the
   explicit start): P0 = p_k + c f_p(t_k, y_k) when f(t_k, y_k) is known,
   else p_k + (p_k - prev) h / h_prev from the last accepted step when it
   ends where this one starts (cont; prev: its p at the point matching P;
   for SV this is p_k + c f_p(t_k, q_k, p_{k-1/2}), exact for a separable
   H), else f(t_k, y_k) is evaluated (one call), as it is when that
   increment and p_k both vanish.  On success the cache holds f at
   [q_k; P] (sym_fcache_move). */
int sym_kick_solve (const sym_kick *kk, sym_recs *r, int cont,
                    const double *prev, double *x, double *scale);

/* ---------------------------------------------------------------- state */
/* The head of the SE and SV states (their first member): what their
   accept, dense output and tolerances act on */
typedef struct {
  int d, n;              /* y = [q; p] of n = 2d */
  int order;             /* of the method and of its error estimate */
  int separable;         /* H = T(p) + V(q): explicit steps */
  int second_order;      /* f_q = p: no call for it (implies separable) */
  double *block;         /* the one allocation holding the arrays */
  sym_recs r;            /* last accepted step, step being tried */
  sym_fcache fc;         /* the last f evaluated */
  int npr;               /* implicit unknowns (0 to 2): each with its */
  sym_pred pr[2];        /* history */
  sym_kept k[2];         /* and Newton state */
  int want_f;            /* f at both ends of every step (estimate,
                            dense output) */
  int sparse;            /* implicit with a sparse Df */
  sym_tangent *tg;       /* the tangent map the steps carry, or NULL */
} sym_onestep;

/* o's f cache placed at w, with a dense Df when implicit and not sparse,
   else (sparse) a sym_csc of its own; SYM_ENOMEM */
int sym_onestep_fcache (sym_onestep *o, int implicit, double *w);

/* The start of the SE and SV allocs: a zeroed state of size bytes with
   its head filled from dim, the method's order and opts, or NULL with
   *status SYM_EBADINPUT (dim < 1) or SYM_ENOMEM. */
void *sym_onestep_new (int dim, int order, size_t size,
                       const sym_method_opts *opts, int *status);
/* npr implicit unknowns of size d: their Newton states */
int sym_onestep_implicit (sym_onestep *o, int npr, int d,
                          const sym_method_opts *opts);
/* The alloc of SE and SV: sym_onestep_new and the one block, with the
   records (naux of their own each), the f cache, the state's own nown
   doubles (*own) and, for implicit steps, npr unknowns' histories and
   Newton states; NULL with *status on failure (nothing left allocated) */
void *sym_onestep_alloc (int dim, int order, size_t size, int npr,
                         int naux, size_t nown, const sym_method_opts *opts,
                         int *status, double **own);
/* what the stepper tables of SE and SV share, for a state that starts
   with a sym_onestep */
/* The start of a step (t, h) ending at tend from y: the arguments
   checked, the trial begun (sym_recs_begin: *cont) */
int sym_onestep_begin (sym_onestep *o, const sym_eval *ev, double t,
                       double h, double tend, const double *y,
                       const double *ynext, int *cont);
/* The trial step as the steps of SE and SV read it: its record and the
   last accepted step's, y0 = [q0; p0] at its start, y1 = [q1; p1] at
   its end (to be written), whether it continues the last accepted step */
typedef struct {
  int d;
  sym_rec *tr, *cu;
  const double *q0, *p0;
  double *q1, *p1;
  int cont;
} sym_trial;
/* sym_onestep_begin, and the trial begun into *v */
int sym_onestep_trial (sym_onestep *o, const sym_eval *ev, double t,
                       double h, double tend, const double *y,
                       const double *ynext, sym_trial *v);
int sym_onestep_order (const void *state, int *est);
int sym_onestep_set_tolerances (void *state, const sym_tolerances *tol);
void sym_onestep_accept (void *state);
int sym_onestep_dense (void *state, sym_eval *ev, double t, double *y);
int sym_onestep_dense_samples (const void *state);
int sym_onestep_dense_degree (const void *state);
void sym_onestep_free (void *state);
/* f at the end of the last accepted step (evaluated if not known, and
   kept: the next step starts with it) */
int sym_onestep_end_f (void *state, sym_eval *ev, double *f);

/* The stepper table of a one-step method: its name, alloc,
   set_tolerances, step and free, the rest the shared functions above */
#define SYM_ONESTEP_TYPE(name, alloc, set_tolerances, step, free)       \
  { name, alloc, sym_onestep_order, set_tolerances, step,               \
    sym_onestep_accept, sym_onestep_dense, sym_onestep_dense_samples,   \
    sym_onestep_dense_degree, free, sym_onestep_end_f }

#endif
