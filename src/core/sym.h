/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* sym.h -- the public interface of the symplectic integration core.

   Pure C99: nothing here knows of Octave.  The MEX layer (src/mex/) and the
   C tests (tests/c/) are the two clients.

   Conventions
   - y = [q; p], q and p in R^d, n = 2d.  f(t, y) = [dH/dp; -dH/dq + F].
   - Matrices are column-major (as Octave and LAPACK).
   - Every function that can fail returns an int status: 0 success, > 0 a
     recoverable failure (the driver rejects the step and shrinks h), < 0 a
     fatal one (the driver stops and reports it).  Named codes below.
   - Every allocation goes through sym_malloc/sym_free (see sym_set_allocator)
     so the MEX build can route it to mxMalloc: an error thrown inside a user
     callback then leaks nothing. */
#ifndef SYM_H
#define SYM_H

#include <limits.h>
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---------------------------------------------------------------- status */
enum {
  SYM_SUCCESS = 0,
  /* > 0: recoverable (retry with a smaller step) */
  SYM_RECOVERABLE = 1,     /* a callback asked for a smaller step */
  SYM_NONFINITE = 2,       /* a callback returned NaN or Inf */
  SYM_NEWTON_FAIL = 3,     /* Newton iteration did not converge */
  SYM_SINGULAR = 4,        /* singular Newton matrix */
  /* < 0: fatal */
  SYM_EBADINPUT = -1,      /* invalid argument to a core function */
  SYM_ENOMEM = -2,         /* allocation failed */
  SYM_ECALLBACK = -3,      /* a callback returned a fatal status, or asked
                              for a smaller step where there is none (a
                              fixed step, the first call at t0) */
  SYM_ESTEPSIZE = -4,      /* step size fell below the round-off limit */
  SYM_ENEWTON = -5,        /* Newton failed and the step cannot shrink */
  SYM_ENONFINITE = -6,     /* non-finite values that a smaller step cannot cure */
  SYM_EMAXSTEPS = -7,      /* more steps than allowed */
  SYM_EOUTPUT = -8,        /* the output sink reported an error */
  SYM_EOVERFLOW = -9       /* a step's result overflowed (NaN or Inf in y,
                              f finite), with the fixed or the least step */
};

/* Ways a run ends well (returned by sym_integrate) */
enum {
  SYM_DONE = 0,            /* reached tf */
  SYM_STOP_OUTPUT = 100,   /* the output sink asked to stop */
  SYM_STOP_EVENT = 101     /* a terminal event */
};

const char *sym_status_name (int status);

/* ---------------------------------------------------------------- memory */
typedef void *(*sym_alloc_fn) (size_t nbytes);
typedef void (*sym_free_fn) (void *ptr);
/* Set the allocator for all later allocations (default: malloc/free). */
void sym_set_allocator (sym_alloc_fn alloc, sym_free_fn dealloc);
void *sym_malloc (size_t nbytes);            /* NULL on failure */
void *sym_calloc (size_t count, size_t size);/* zeroed; NULL on failure */
void sym_free (void *ptr);                   /* NULL is fine */

/* ---------------------------------------------------------------- system */
/* f(t, y) -> dy, all of length n = 2d. */
typedef int (*sym_rhs_fn) (double t, const double *y, double *dy, void *user);
/* Batch form (Vectorized): k states as the columns of the n-by-k matrix y,
   their times in t[0..k-1]; dy is n-by-k. */
typedef int (*sym_rhs_batch_fn) (int k, const double *t, const double *y,
                                 double *dy, void *user);
/* Df = d f / d y at (t, y): n-by-n column-major. */
typedef int (*sym_jac_fn) (double t, const double *y, double *df, void *user);
/* f and Df at (t, y) in one call, when the user's function gives both at
   the cost of one call (the Hessian as a second output). */
typedef int (*sym_rhs_jac_fn) (double t, const double *y, double *dy,
                               double *df, void *user);

typedef struct {
  long nsteps;      /* accepted steps */
  long nfailed;     /* rejected steps (error test or Newton failure) */
  long nrhs;        /* calls of rhs (a batch call counts once) */
  long nrhs_states; /* states evaluated (a batch call of k counts k) */
  long nfd;         /* rhs calls spent on finite-difference Jacobians
                       and on the probe of the user's Df
                       (included in nrhs) */
  long njac;        /* calls of jac */
  long nnewton;     /* Newton iterations */
  long nnewton_fail;/* Newton solves that failed */
  long nlu;         /* LU factorizations */
  long nsolve;      /* linear solves with an LU */
  long nrestart;    /* SE/SV solves started again from the explicit start
                       after a recoverable failure from the history's */
} sym_counters;

typedef struct {
  int dim;                    /* d: y has n = 2d components */
  sym_rhs_fn rhs;             /* required */
  sym_rhs_batch_fn rhs_batch; /* optional (NULL): several states in one call */
  sym_jac_fn jac;             /* optional (NULL): finite differences of rhs */
  sym_rhs_jac_fn rhs_jac;     /* optional (NULL): f and jac's Df in one
                                 call; counted as a jac call only */
  void *user;                 /* passed to every callback */
  sym_counters cnt;           /* kept by the core; zero it before a run */
  double fail_t;              /* t of the last failed callback (for messages) */
  int fail_status;            /* its status */
  int fail_df;                /* SYM_NONFINITE in jac's or rhs_jac's Df
                                 (f finite) */
  int jac_dropped;            /* jac/rhs_jac dropped by sym_jac_check or
                                 by the probe of the first Df */
  double jac_dropped_t;       /* at this t */
  int jac_probed;             /* the user's Df was probed (SYM_JAC_GROSS);
                                 sym_integrate clears it for its run */
  int sep_broken;             /* Separable steps found f not separable:
                                 f_p changed with p at the same (t, q)
                                 (SE), or f_q with q at the same p (SV),
                                 by more than SYM_SEP_TOL of f; first at
                                 sep_broken_t.  sym_integrate clears it */
  double sep_broken_t;
  /* NULL, or the n typical sizes of y's components that set the steps of
     the finite differences (see sym_jac): sym_integrate points it, for its
     run, at the largest |y_i| of y0 and the accepted steps, and sets it
     back when it returns */
  const double *ytyp;
} sym_system;

/* Calls through the system with counting and checks.  sym_rhs returns the
   callback's status, or SYM_NONFINITE when dy has a NaN or Inf (fail_t is
   set).  sym_rhs_many evaluates k states (batch callback if present, else k
   calls).  sym_jac uses sys->jac, or forward differences of rhs when it is
   NULL (n extra rhs calls, counted in nfd), with f0 = f(t, y) if the caller
   has it (else NULL: one more call).  The difference step of y_i is
   sqrt(eps) times its size: max(|y_i|, ytyp_i), and at least 1e-6 times
   the largest such size in its half (q or p); in a half that is all zero,
   the other half's largest, or 1 if both are.  Without ytyp every
   component of a half takes the half's largest size.  So the steps scale
   with the problem (a system whose q and p are of size 1e-10 is
   differenced as one of size 1), q and p may have different units, and a
   component that passes through zero keeps the step of its largest size
   in the run. */
int sym_rhs (sym_system *sys, double t, const double *y, double *dy);
int sym_rhs_many (sym_system *sys, int k, const double *t, const double *y,
                  double *dy);
int sym_jac (sym_system *sys, double t, const double *y, const double *f0,
             double *df);
/* Df at k states (the columns of y, times t, f0 their f: needed by the
   finite differences) into k n-by-n blocks of df: sys->jac for each, or
   forward differences with every perturbed state of all k in one batch
   call when the system has rhs_batch. */
int sym_jac_many (sym_system *sys, int k, const double *t, const double *y,
                  const double *f0, double *df);
/* f and Df at k states (into f and k n-by-n blocks of df): sym_rhs_many
   and sym_jac_many, except that finite differences with a batch callback
   evaluate the states and their perturbed states in one call (when all
   fit in one).  rhs_jac is not used. */
int sym_rhs_jac_many (sym_system *sys, int k, const double *t,
                      const double *y, double *f, double *df);
/* f and Df at one state: one call of rhs_jac (counted in njac) if the
   system has it, else sym_rhs and sym_jac. */
int sym_rhs_jac (sym_system *sys, double t, const double *y, double *dy,
                 double *df);
/* How far the user's Df may differ from forward differences: a tenth
   (the differences, with steps of sqrt(eps) times the size of y_i, err
   by 1% where f varies on a scale far below it, a pendulum at q = 1e6; a
   missing damping c against a Hessian of size 1 differs by c).
   sym_integrate checks no more after SYM_JAC_CHECKS checks that agreed. */
#define SYM_JAC_AGREE 0.1
#define SYM_JAC_CHECKS 3
/* The first Df the user's jac or rhs_jac gives (sym_jac, sym_rhs_jac;
   then jac_probed is set) is probed at its (t, y): the change of f over a
   step dy along one direction (every component stepped by sqrt(eps)
   times its size, as the finite differences step it) against Df dy.
   When they differ by more than SYM_JAC_GROSS times the change of f
   (plus SYM_JAC_NOISE ulps of f, its round-off), Df is dropped as by
   sym_jac_check, and finite differences of rhs serve from there on,
   starting with this Df.  Only a Df far too large fails it: one too small
   (zero), of the wrong sign or missing a forcing term's dF/dy differs by
   about the change itself, slows Newton, and sym_jac_check judges it
   after a failure.  A Df too large by c makes the corrections 1/c of
   Newton's: on Kepler, odeSPVI (4,3), h = 2 pi/100, c = 1e9 still made
   Newton fail (and sym_jac_check dropped Df), but with c = 1e12 they are
   below round-off from the first on, so each solve stops at once,
   accepted as converged at its start, and one period ends 25 away from
   the orbit without this probe (tests/c/test_spvi.c; the probe itself in
   tests/c/test_core.c).  Costs 2 calls of rhs per run (1 with rhs_jac),
   counted in nfd. */
#define SYM_JAC_GROSS 100.0
#define SYM_JAC_NOISE 1e3
/* After a Newton failure with the user's Df (jac or rhs_jac): compare it
   at (t, y) with forward differences of rhs.  If they differ by more than
   SYM_JAC_AGREE times the largest entry of either (a Hessian that misses
   a forcing term's dF/dy, or a wrong Jacobian), jac and rhs_jac are set
   to NULL, so that finite differences serve from then on, and
   jac_dropped, jac_dropped_t and *dropped are set; also when the user's
   Df has a NaN or Inf where the differences are finite (a smaller step
   cannot cure it).  Returns a callback's status (then nothing is
   dropped) or SYM_SUCCESS. */
int sym_jac_check (sym_system *sys, double t, const double *y,
                   int *dropped);

/* ---------------------------------------------------------------- LAPACK */
/* Dense LU with reuse: factor once, solve many times. */
typedef struct {
  int n;
  double *a;      /* n*n: the matrix, overwritten by its LU factors */
  int *ipiv;
  int factored;   /* 1 after a successful sym_lu_factor */
} sym_lu;

int sym_lu_init (sym_lu *lu, int n);          /* allocates; SYM_ENOMEM */
void sym_lu_free (sym_lu *lu);
/* SYM_SINGULAR if singular or not finite */
int sym_lu_factor (sym_lu *lu, sym_counters *c);
int sym_lu_solve (sym_lu *lu, double *b, sym_counters *c); /* b <- A \ b */

/* ---------------------------------------------------------------- Newton */
/* Simplified Newton as in implicit Runge-Kutta codes: the matrix is kept
   (and its LU reused) while convergence is fast; the contraction rate theta
   is estimated every iteration; the iteration stops when
   theta/(1-theta)*|dx| <= tol (|.| the max norm of dx./scale), or when |dx|
   itself is at round-off level.  A slow or diverging iteration with a stale
   matrix asks for a fresh one (from x) and goes on; with a fresh one it
   fails with SYM_NEWTON_FAIL (also for a singular matrix).  A failed
   callback, of the residual or of the matrix, ends the solve with its own
   status. */
typedef struct {
  /* r = G(x) */
  int (*residual) (void *ctx, const double *x, double *r);
  /* A = G'(x) (or a good approximation), n-by-n column-major */
  int (*matrix) (void *ctx, const double *x, double *a);
  void *ctx;
} sym_newton_problem;

typedef struct {
  int n;
  sym_lu lu;
  int have_matrix;  /* lu holds a factored matrix that may be reused */
  int fresh;        /* that matrix was computed in this solve */
  double tol;       /* stop tolerance on the scaled max norm (default 1e-14) */
  int maxit;        /* iterations per solve (default 10) */
  double eta;       /* theta/(1-theta) carried from the last solve */
  double theta;     /* last contraction rate */
  int iters;        /* iterations of the last solve */
  /* Exact first corrections (set quad when every solve starts with a new
     matrix at its start x, so that the first correction is Newton's own):
     the error left after it is about kq |dx_1|^2, kq measured as
     |dx_2| / |dx_1|^2 on solves where |dx_2| is well above round-off; a
     solve then stops after one correction when 100 kq |dx_1|^2 <= tol, at
     most 16 times in a row before a second correction measures again
     (see newton.c).  one: the last solve stopped so; kq_new: it measured
     kq.  kq_ok = 0 forgets kq (a new h, a new problem). */
  int quad;
  double kq;
  int kq_ok, kq_age, one, kq_new;
  double *r, *dx, *x0;   /* work */
} sym_newton;

int sym_newton_init (sym_newton *nw, int n);
void sym_newton_free (sym_newton *nw);
/* Forget the kept matrix (e.g. after a change of h). */
void sym_newton_invalidate (sym_newton *nw);
/* Solve G(x) = 0 from the start x (overwritten by the solution).  scale[i]
   > 0 weights component i in the stopping norm. */
int sym_newton_solve (sym_newton *nw, const sym_newton_problem *p, double *x,
                      const double *scale, sym_counters *c);

/* ---------------------------------------------------------------- steppers */
typedef struct {
  int q_dofs;          /* SPVI: Legendre modes for q (>= 2) */
  int nodes;           /* SPVI: Gauss-Legendre nodes (>= 1) */
  double newton_tol;   /* 0: default */
  int max_newton;      /* 0: default */
  int separable;       /* SE/SV: explicit steps for H = T(p) + V(q) */
  int newton_matrix;   /* SPVI: SYM_MATRIX_AUTO (0), _KEPT or _NEW */
  int want_error;      /* the driver will ask for error estimates */
  /* the tolerances of the adaptive error control (the driver sets them
     with want_error; est_atol the smallest AbsTol): a stepper may stop
     the nonlinear solves that only feed the estimate well below them.
     0: none, converge to round-off */
  double est_rtol, est_atol;
  int want_dense;      /* the driver will call dense() */
} sym_method_opts;

/* SPVI's Newton matrix: kept across steps while Newton converges fast,
   or new at the start of every step (its first correction exact Newton,
   often enough); auto: new when the nodes' Jacobians come in the same
   batch call as their f (finite differences with rhs_batch) and the
   matrix is small, else kept (see step_spvi.c). */
enum { SYM_MATRIX_AUTO = 0, SYM_MATRIX_KEPT = 1, SYM_MATRIX_NEW = 2 };

/* A stepper type: a const table, its functions static in the method's file.
   Life cycle: alloc; then for each attempt step (trial state), and accept
   when the driver keeps the step (the trial becomes the current step: dense
   output and the predictor of the next start use it); reset forgets the
   history (after an event stop or a restart); free. */
typedef struct {
  const char *name;
  int order;          /* order of the method with the options given */
  /* order of the error estimate: err = O(h^(err_order+1)) */
  int (*err_order) (const void *state);
  int (*method_order) (const void *state);
  void *(*alloc) (const sym_system *sys, const sym_method_opts *opts,
                  int *status);
  /* Step from (t, y) by h (h < 0 runs backwards) into ynext; if yerr is not
     NULL, also an estimate of the local error (n components).  tend is
     the time the step's end is known by (its dense output and the next
     step's start), t + h up to the round-off of t: the driver's fixed
     steps take the same h every step and end at t0 + k h rounded once
     (driver.c). */
  int (*step) (void *state, sym_system *sys, double t, double h,
               double tend, const double *y, double *ynext, double *yerr);
  void (*accept) (void *state);
  /* y(t) on the last accepted step, t within it: its own continuous output */
  int (*dense) (void *state, sym_system *sys, double t, double *y);
  void (*reset) (void *state);
  void (*free) (void *state);
} sym_stepper_type;

extern const sym_stepper_type *const sym_step_se;
extern const sym_stepper_type *const sym_step_sv;
extern const sym_stepper_type *const sym_step_spvi;

/* ---------------------------------------------------------------- driver */
/* Events: value[k] for k < nevents; isterminal/direction as in Octave.
   A NaN value has no sign: no crossing is seen next to it (the Octave
   layer refuses it). */
typedef int (*sym_event_fn) (double t, const double *y, double *value,
                             int *isterminal, int *direction, void *user);
/* Output sink: one row (t, y).  Return 0 to go on, 1 to stop the run,
   < 0 on error.  A step's events go to the event sink before its rows
   go out, so a stop at a row inside a step leaves events after that row
   reported (the Octave layer drops them, as ode45 returns none after
   t(end)). */
typedef int (*sym_output_fn) (double t, const double *y, void *user);
/* Event sink: an event located at (te, ye), index ie (0-based). */
typedef int (*sym_eventout_fn) (double te, const double *ye, int ie,
                                void *user);

/* The most steps a fixed TimeStepSize may need (doubles count them
   exactly; the Octave layer refuses more than 1e12), and within a long
   where that has 32 bits */
#define SYM_MAX_FIXED_STEPS \
  (LONG_MAX / 2 < 1e15 ? (double) (LONG_MAX / 2) : 1e15)

typedef struct {
  double t0, tf;
  /* output times (strictly monotonic, tout[0] = t0): when ntout > 2 rows go
     out exactly at these times from the dense output; else at every step */
  const double *tout;
  int ntout;
  int refine;          /* ntout <= 2: rows per step (1: step points only) */
  /* fixed step: h_fixed > 0 (sign taken from tf - t0); nsteps_fixed > 0
     takes exactly that many steps, else steps to tf with the last one
     shortened to end on tf (at most SYM_MAX_FIXED_STEPS of them, else
     SYM_EBADINPUT) */
  double h_fixed;
  long nsteps_fixed;
  /* adaptive */
  double rtol;
  const double *atol;  /* atol_len = 1 or n, each > 0 and finite (else
                          SYM_EBADINPUT) */
  int atol_len;
  int norm_control;
  double h0;           /* 0: automatic; inf: as long as hmax allows */
  double hmax;         /* 0: |tf - t0| / 10; inf: no cap (as ode45) */
  long max_steps;      /* 0: no limit */
  /* events */
  int nevents;
  sym_event_fn events;
  void *event_user;
  sym_eventout_fn event_out;
  int event_samples;   /* events also checked at this many equally spaced
                          points inside each step, on the dense output,
                          and where the parabola through three of them
                          turns back across zero (a zero pair inside one
                          step is otherwise unseen); 0: at the step
                          points only */
  /* output */
  sym_output_fn output;
  void *output_user;
} sym_driver_opts;

/* Where a run of TimeStepNumber steps of TimeStepSize ends (h_fixed > 0,
   nsteps_fixed > 0): t0 + N h in the direction of tf, or the output time
   (tf or one of tout) that it is within round-off of (16 ulps of
   max(|t0|, N h)), so that N steps of h still end on the time N h stands
   for; otherwise tf. */
double sym_fixed_end (const sym_driver_opts *o);

/* Separable steps (odeSE/odeSV with Separable) check, with the f they
   evaluate anyway, that f_p does not change with p at the same (t, q)
   (SE) or f_q with q at the same p (SV), to this relative size */
#define SYM_SEP_TOL 1e-8
/* Whether u and v (k values) differ by more than SYM_SEP_TOL of their
   size; if so, sets sys->sep_broken (and _t) at t the first time */
void sym_sep_check (sym_system *sys, double t, int k, const double *u,
                    const double *v);

/* Integrate from y0.  Returns SYM_DONE, SYM_STOP_OUTPUT, SYM_STOP_EVENT or a
   status < 0 (rows handed to the output sink so far stay valid).
   *t_reached is the last time reached. */
int sym_integrate (const sym_stepper_type *type, sym_system *sys,
                   const sym_method_opts *mopts, const sym_driver_opts *dopts,
                   const double *y0, double *t_reached);

/* ---------------------------------------------------------------- quadrature */
/* Gauss-Legendre nodes z[0..m-1] (ascending, in [-1, 1]) and weights w,
   by Golub-Welsch (LAPACK dstev).  Returns 0 or a status < 0. */
int sym_gauss_legendre (int m, double *z, double *w);
/* Legendre polynomials l_0..l_{n-1} and their derivatives at x:
   l[i] = l_i(x), dl[i] = l_i'(x). */
void sym_legendre (int n, double x, double *l, double *dl);

#ifdef __cplusplus
}
#endif

#endif
