/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* sym.h -- the public interface of the symplectic integration core.

   Pure C99: nothing here knows of Octave.  The MEX layer (src/mex/) and the
   C tests (tests/c/) are its clients.

   Conventions
   - y = [q; p], q and p in R^d, n = 2d.  f(t, y) = [dH/dp; -dH/dq + F].
   - Matrices are column-major (as Octave and LAPACK).
   - Every function that can fail returns an int status: 0 success, > 0 a
     recoverable failure (the driver rejects the step and shrinks h), < 0 a
     fatal one (the driver stops and reports it).
   - Every allocation goes through sym_malloc/sym_free (sym_set_allocator),
     so that the MEX build can route it to mxMalloc: an error thrown inside
     a user's callback then leaks nothing.
   - The user's system is read-only to the core; what a run finds out comes
     back in a sym_stats. */
#ifndef SYM_H
#define SYM_H

#include <stddef.h>

#include "tuning.h"

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
  SYM_EOVERFLOW = -9,      /* a step's result overflowed (NaN or Inf in y,
                              f finite), with the fixed or the least step */
  SYM_EDENSITY = -10       /* the step density of a reversible run was not
                              a positive finite number */
};

/* the step control of a run without fixed steps */
enum { SYM_CONTROL_ERROR = 0, SYM_CONTROL_REVERSIBLE = 1 };

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

/* A sparse n-by-n matrix in compressed columns: the rows of column j
   are rowind[colptr[j] .. colptr[j+1] - 1] (increasing), their values
   val[...]; nnz = colptr[n] entries, room for cap.  Df of a large
   system comes so (sym_system.sparse). */
typedef struct {
  int n, nnz, cap;
  int *colptr;      /* n + 1 */
  int *rowind;      /* cap */
  double *val;      /* cap */
} sym_csc;

/* an n-by-n matrix without entries, with room for cap of them */
int sym_csc_init (sym_csc *a, int n, int cap);
/* room for cap entries, the content kept */
int sym_csc_reserve (sym_csc *a, int cap);
void sym_csc_free (sym_csc *a);     /* safe on a zeroed struct */

/* Df as a sparse matrix (sym_system.sparse): the callback fills df
   (sym_csc_reserve for room) */
typedef int (*sym_jac_csc_fn) (double t, const double *y, sym_csc *df,
                               void *user);
typedef int (*sym_rhs_jac_csc_fn) (double t, const double *y, double *dy,
                                   sym_csc *df, void *user);

/* The user's system: read-only to the core. */
typedef struct {
  int dim;                    /* d: y has n = 2d components */
  sym_rhs_fn rhs;             /* required */
  sym_rhs_batch_fn rhs_batch; /* optional (NULL): several states in one call */
  sym_jac_fn jac;             /* optional (NULL): finite differences of rhs */
  sym_rhs_jac_fn rhs_jac;     /* optional (NULL): f and jac's Df in one
                                 call; counted as a jac call only */
  void *user;                 /* passed to every callback */
  /* optional (jp_ncolors 0: none): the pattern of Df, compressed
     columns (jp_colptr: n + 1, jp_rowind: the rows of column j at
     jp_colptr[j] .. jp_colptr[j+1] - 1), and a colouring of its columns
     (sym_pattern_colors): finite differences then step all the columns
     of a colour at once, one state for each colour instead of each
     column, and Df is zero outside the pattern */
  const int *jp_colptr, *jp_rowind, *jp_color;
  int jp_ncolors;
  /* sparse (optional, 0: dense): Df is sparse; it comes from jac_csc or
     rhs_jac_csc (jac and rhs_jac unused), or from finite differences on
     the pattern jp_* (required then) */
  int sparse;
  sym_jac_csc_fn jac_csc;
  sym_rhs_jac_csc_fn rhs_jac_csc;
} sym_system;

/* Colour the columns of an n-by-n pattern (compressed columns, as in
   sym_system) so that no two columns of one colour have a row in
   common, greedily in column order: color[j] for each column; returns
   the number of colours, or -1 when memory runs out or the pattern is
   not valid (colptr not increasing from 0, a row outside 0..n-1). */
int sym_pattern_colors (int n, const int *colptr, const int *rowind,
                        int *color);

typedef struct {
  long nsteps;      /* accepted steps */
  long nfailed;     /* rejected steps (error test or Newton failure) */
  long nrhs;        /* calls of rhs (a batch call counts once) */
  long nrhs_states; /* states evaluated (a batch call of k counts k) */
  long nfd;         /* rhs calls spent on finite-difference Jacobians
                       and on the probe of the user's Df (in nrhs) */
  long njac;        /* calls of jac or rhs_jac */
  long nnewton;     /* Newton iterations */
  long nnewton_fail;/* Newton solves that failed */
  long nlu;         /* LU factorizations */
  long nsolve;      /* linear solves with an LU */
  long nrestart;    /* SE/SV solves started again from the explicit start
                       after a recoverable failure from the history's */
} sym_counters;

/* What a run found out: its counters and diagnostics. */
typedef struct {
  sym_counters cnt;
  double t_reached;           /* the last time reached (sym_integrate) */
  int order;                  /* the order of the solution it returned */
  double fail_t;              /* t of the last failed callback */
  int fail_status;            /* its status */
  int fail_df;                /* SYM_NONFINITE came from the user's Df
                                 (f finite) */
  int jac_dropped;            /* the user's Df proved wrong: finite
                                 differences served from jac_dropped_t on
                                 (sym_jac_check, and the probe of the
                                 first Df) */
  double jac_dropped_t;
  int rhs_jac_used;           /* f came with Df from rhs_jac calls */
  int sep_broken;             /* Separable steps found f not separable,
                                 first at sep_broken_t (sym_sep_check) */
  double sep_broken_t;
  /* where a later run can go on from the end of this one (a sol given
     as Y0): fixed steps of restart_h from the grid's origin restart_t0,
     the last row in step restart_k (at its end, or inside it when an
     event ended the run; k0 counted); reversible steps, the densities of
     the step before the last and of the last (0 where there was none) */
  double restart_h, restart_t0;
  long restart_k;
  double restart_rho[2];
} sym_stats;

/* The system as the core evaluates it: the callbacks in use (the user's
   Df is dropped for finite differences when it proves wrong), the sizes
   that scale finite differences, and the stats the calls add to.
   sym_integrate makes its own; code that drives a stepper directly makes
   one with sym_eval_init. */
typedef struct {
  int dim;
  sym_rhs_fn rhs;
  sym_rhs_batch_fn rhs_batch;
  sym_jac_fn jac;             /* NULL: finite differences */
  sym_rhs_jac_fn rhs_jac;
  void *user;
  const int *jp_colptr, *jp_rowind, *jp_color;   /* as in sym_system */
  int jp_ncolors;
  int sparse;                 /* as in sym_system, with its callbacks */
  sym_jac_csc_fn jac_csc;
  sym_rhs_jac_csc_fn rhs_jac_csc;
  int *own_pattern;           /* a pattern of its own (of a dropped sparse
                                 Df) that jp_* point into, or NULL */
  /* the finite differences' workspace and f at the state, kept from
     one Df to the next (freed by sym_eval_free) */
  double *fd_work, *fd_f;
  size_t fd_cap;
  sym_stats st;
  int jac_probed;             /* the first Df has been probed (see
                                 SYM_JAC_GROSS) */
  /* NULL, or the n typical sizes of y's components that set the steps
     of the finite differences: sym_integrate points it at the largest
     |y_i| of y0 and of the accepted steps */
  const double *ytyp;
} sym_eval;

/* ev from sys, with zeroed stats */
void sym_eval_init (sym_eval *ev, const sym_system *sys);
/* what ev allocated itself (own_pattern, the differences' workspace) */
void sym_eval_free (sym_eval *ev);

/* Calls through ev with counting and checks.  sym_rhs returns the
   callback's status, or SYM_NONFINITE when dy has a NaN or Inf (fail_t is
   set).  sym_rhs_many evaluates k states (batch callback if present, else k
   calls).  sym_jac uses ev->jac, or forward differences of rhs when it is
   NULL (n extra rhs calls, counted in nfd), with f0 = f(t, y) if the caller
   has it (else NULL: one more call).  The difference step of y_i is
   sqrt(eps) times its size: max(|y_i|, ytyp_i), and at least SYM_FD_FLOOR
   times the largest such size in its half (q or p); in a half that is all
   zero, the other half's largest, or 1 if both are.  Without ytyp every
   component of a half takes the half's largest size. */
int sym_rhs (sym_eval *ev, double t, const double *y, double *dy);
/* sym_rhs into dy unless *have says dy holds f(t, y) already; sets *have
   on success (a step record's f at its ends, evaluated when first
   needed) */
int sym_rhs_once (sym_eval *ev, double t, const double *y, double *dy,
                  int *have);
int sym_rhs_many (sym_eval *ev, int k, const double *t, const double *y,
                  double *dy);
int sym_jac (sym_eval *ev, double t, const double *y, const double *f0,
             double *df);
/* Df at k states (the columns of y, times t, f0 their f) into k n-by-n
   blocks of df: ev->jac for each, or forward differences with every
   perturbed state of all k in one batch call when there is rhs_batch. */
int sym_jac_many (sym_eval *ev, int k, const double *t, const double *y,
                  const double *f0, double *df);
/* f and Df at k states: sym_rhs_many and sym_jac_many, except that finite
   differences with a batch callback evaluate the states and their
   perturbed states in one call (when all fit in one).  rhs_jac is not
   used. */
int sym_rhs_jac_many (sym_eval *ev, int k, const double *t,
                      const double *y, double *f, double *df);
/* f and Df at one state: one call of rhs_jac (counted in njac) if there
   is one, else sym_rhs and sym_jac. */
int sym_rhs_jac (sym_eval *ev, double t, const double *y, double *dy,
                 double *df);
/* Sparse Df (ev->sparse): sym_jac and sym_rhs_jac for a sym_csc, from
   the callbacks or from finite differences on the pattern (jp_*: one
   state for each colour); the user's sparse Df is probed and checked as
   a dense one is, and replaced by finite differences on the system's
   pattern, or on its own, when it proves wrong */
int sym_jac_csc (sym_eval *ev, double t, const double *y, const double *f0,
                 sym_csc *df);
int sym_rhs_jac_csc (sym_eval *ev, double t, const double *y, double *dy,
                     sym_csc *df);
/* After a Newton failure with the user's Df: compare it at (t, y) with
   forward differences of rhs.  If they differ by more than SYM_JAC_AGREE
   times the largest entry of either (a Hessian that misses a forcing
   term's dF/dy, a wrong Jacobian), or the user's Df has a NaN or Inf where
   f is finite, jac and rhs_jac are dropped (finite differences serve from
   then on) and *dropped is set.  Returns a callback's status (then nothing
   is dropped) or SYM_SUCCESS. */
int sym_jac_check (sym_eval *ev, double t, const double *y, int *dropped);
/* What a Df costs, in calls of f: 1 from the user's, 2d by finite
   differences (a sparse Df: one per colour of its pattern) */
int sym_jac_cost (const sym_eval *ev);
/* Separable steps check, with the f they evaluate anyway, that f_p does
   not change with p at the same (t, q) (SE) or f_q with q at the same p
   (SV): whether u and v (k values) differ by more than SYM_SEP_TOL of
   their size; if so, sets st.sep_broken (and _t) at t the first time */
void sym_sep_check (sym_eval *ev, double t, int k, const double *u,
                    const double *v);

/* ---------------------------------------------------------------- methods */
/* Options common to the methods; a method's own options come as its own
   struct through own (NULL: its defaults). */
/* Holonomic constraints g(q) = 0 (m values, m < d) for RATTLE
   (sym_step_rattle): con fills g (m) and, when G is not NULL, G = dg/dq
   (m-by-d, column-major); has_G 0: con never fills G, the core takes
   central differences of g.  A status as for sym_rhs_fn. */
typedef int (*sym_con_fn) (const double *q, double *g, double *G,
                           void *user);
typedef struct {
  int m;
  sym_con_fn con;
  int has_G;
  void *user;
} sym_constraints;

typedef struct {
  double newton_tol;   /* 0: SYM_NEWTON_TOL */
  int max_newton;      /* 0: SYM_NEWTON_MAXIT */
  int want_dense;      /* dense() will be called (the driver sets it) */
  int reversible;      /* the steps are reversible ones (the driver sets
                          it) */
  const void *own;
  const sym_constraints *constraints;  /* RATTLE's (NULL: none) */
} sym_method_opts;

/* The tolerances of an adaptive run, as the driver's error test applies
   them (control.c): the tolerance seam of a stepper. */
typedef struct {
  double rtol;
  const double *atol;  /* atol_len = 1 or n */
  int atol_len;
  int norm_control;
} sym_tolerances;

/* A stepper type: a const table, its functions static in the method's
   files.  Life cycle: alloc (for fixed steps, no error estimate);
   set_tolerances once before the first step of an adaptive run (step
   will then be asked for an error estimate); for each attempt step, and
   accept when the driver keeps it (the trial becomes the current step:
   dense output and the next start use it); free. */
typedef struct {
  const char *name;
  void *(*alloc) (int dim, const sym_method_opts *opts, int *status);
  /* The order p of the solution step returns (local error O(h^(p+1)));
     *est (if not NULL): the order q of its error estimate, O(h^(q+1)),
     what the step-size control needs */
  int (*order) (const void *state, int *est);
  int (*set_tolerances) (void *state, const sym_tolerances *tol);
  /* Step from (t, y) by h (h < 0 runs backwards) into ynext; if yerr is
     not NULL, also an estimate of the local error (n components).  tend
     is the time the step's end is known by: t + h up to the round-off of
     t (the driver's fixed steps take the same h every step and end at
     t0 + k h rounded once). */
  int (*step) (void *state, sym_eval *ev, double t, double h, double tend,
               const double *y, double *ynext, double *yerr);
  void (*accept) (void *state);
  /* y(t) on the last accepted step, t within it: its own continuous
     output */
  int (*dense) (void *state, sym_eval *ev, double t, double *y);
  /* points inside each step at which the driver also samples the event
     functions on the dense output (long steps can hide a zero pair) */
  int (*dense_samples) (const void *state);
  /* the degree of the dense output's polynomial on a step (at most) */
  int (*dense_degree) (const void *state);
  void (*free) (void *state);
  /* f at the end of the last accepted step into f: the step's own value
     when it has one, else evaluated (and kept for the dense output and
     the next step) */
  int (*end_f) (void *state, sym_eval *ev, double *f);
} sym_stepper_type;

/* odeSE and odeSV: explicit steps for H = T(p) + V(q); second_order: f_q
   = p identically (H = |p|^2/2 + V(q), y = [q; v]), so that the steps
   call f for f_p only (implies separable).  The splitting stepper also
   reads method (an index of sym_splittings) and compensated (compensated
   summation of its explicit updates). */
typedef struct {
  int separable;
  int second_order;
  int method;
  int compensated;
  int sparse;   /* Df sparse (sym_system.sparse): the implicit solves of
                   SE and SV factor theirs by KLU */
  int position; /* SV and the compositions: drift-kick-drift Verlet steps
                   (explicit only), else kick-drift-kick */
  struct sym_tangent_s *tangent;  /* NULL, or the tangent map the explicit
                                     fixed steps carry (below) */
} sym_onestep_opts;
extern const sym_stepper_type *const sym_step_se;
extern const sym_stepper_type *const sym_step_sv;
/* RATTLE (opts->constraints required; own: a sym_onestep_opts with
   separable or second_order on): Stoermer-Verlet with the multipliers of
   g(q) = 0 and of its velocity constraint G(q) dH/dp = 0, explicit force
   stages, fixed steps only (no error estimate); order 2, symmetric */
extern const sym_stepper_type *const sym_step_rattle;
/* Move y = [q; p] onto g(q) = 0 (q by minimum-norm Newton corrections)
   and G(q) dH/dp = 0 (p along G(q)'); second_order: dH/dp = p, else
   f_q of ev's rhs at t.  *dq, *dp: the largest change of q and of p. */
int sym_constraints_project (const sym_constraints *cs, sym_eval *ev,
                             int second_order, double t, double *y,
                             double *dq, double *dp);

/* A composition or splitting method as data.  SYM_COMPOSITION: the step
   is Stoermer-Verlet steps of gamma_i h, i = 1..stages (coef[i-1]), valid
   for any H.  SYM_SPLITTING (separable H only): stages pairs of a kick p
   += b_i h f_p(q) and then a drift q += a_i h f_q(p), coef = {a_1..a_s,
   b_1..b_s}.  sym_splittings ends with a NULL name; its first row is
   Stoermer-Verlet itself. */
enum { SYM_COMPOSITION = 0, SYM_SPLITTING = 1 };
typedef struct {
  const char *name;
  int kind;
  int order;
  int symmetric;
  int stages;
  const double *coef;
} sym_splitting;
extern const sym_splitting sym_splittings[];
/* the index of the method called name (any case), or -1 */
int sym_splitting_find (const char *name);
/* the splitting stepper: steps of sym_splittings[own->method] without
   error control (fixed or reversible);
   explicit (separable or second_order) or, for a composition, implicit
   Stoermer-Verlet stages */
extern const sym_stepper_type *const sym_step_splitting;

/* odeSPVI: q_dofs Legendre modes of q, nodes Gauss-Legendre nodes (0:
   SYM_SPVI_NODES and nodes + 1); Newton's matrix kept across steps,
   new at every step, or chosen (SYM_MATRIX_*); Newton's linear systems
   (SYM_SYSTEM_*): the whole step's, one dense LU of ((q_dofs - 1 +
   nodes) d)^2, or ceil(nodes/2) stage systems of size 2d with one
   Jacobian for all nodes (the pairs q_dofs = nodes + 1 only), or chosen:
   stages when Df is sparse or the whole system has more than
   SYM_SPVI_STAGES_N unknowns (tuning.h).  sparse: the system's Df is sparse
   (sym_system.sparse): stages, or for the other pairs the whole system
   with one Jacobian for all nodes, factored sparse */
typedef struct {
  int q_dofs, nodes;
  int newton_matrix;
  int system;
  int sparse;
  int nonlinear;   /* SYM_NONLINEAR_*: the stage equations by Newton, by
                      fixed-point iteration falling back to Newton on a
                      solve it does not converge, or (auto) by fixed
                      point until the first such solve, then Newton (the
                      pairs q_dofs = nodes + 1 only) */
} sym_spvi_opts;
enum { SYM_MATRIX_AUTO = 0, SYM_MATRIX_KEPT = 1, SYM_MATRIX_NEW = 2 };
enum { SYM_NONLINEAR_NEWTON = 0, SYM_NONLINEAR_FIXEDPOINT = 1,
       SYM_NONLINEAR_AUTO = 2 };
enum { SYM_SYSTEM_AUTO = 0, SYM_SYSTEM_FULL = 1, SYM_SYSTEM_STAGES = 2 };
extern const sym_stepper_type *const sym_step_spvi;
/* its order: 2 min(n - 1, 2m - n + 1) for n modes and m nodes */
int sym_spvi_order (int q_dofs, int nodes);

/* ---------------------------------------------------------------- tangent */
/* The tangent map of a run of explicit steps (SE, SV, the splitting
   stepper; sym_onestep_opts.tangent): Phi = d y_k / d y_0 applied to m
   columns (n-by-m; the full map when they start as the identity), the
   exact derivative of the discrete map, carried through every kick by
   d f_p / d q and every drift by d f_q / d p (the identity with
   second_order).  Those blocks come from the system's Df (jac, or
   rhs_jac's), else from central differences of f, 2d calls a block.
   The steppers refuse it (SYM_EBADINPUT) with implicit steps or an
   error estimate. */
typedef struct sym_tangent_s sym_tangent;
/* v0: the n-by-m initial columns, or NULL for the identity (m = n);
   NULL on bad sizes or without memory */
sym_tangent *sym_tangent_new (int dim, int m, const double *v0);
void sym_tangent_free (sym_tangent *tg);     /* NULL is fine */
/* Phi at the end of the last accepted step (v0 before the first) */
const double *sym_tangent_phi (const sym_tangent *tg);
int sym_tangent_columns (const sym_tangent *tg);
/* the maximal Lyapunov exponent's renormalisation (one column only,
   else SYM_EBADINPUT): after every accepted step the column is scaled
   to unit norm and the log of its norm added up (what
   sym_tangent_log_growth returns), so that it never overflows */
int sym_tangent_renormalise (sym_tangent *tg);
double sym_tangent_log_growth (const sym_tangent *tg);

/* ---------------------------------------------------------------- driver */
/* Events: value[k] for k < nevents; isterminal/direction as in Octave.
   A NaN value has no sign: no crossing is seen next to it. */
typedef int (*sym_event_fn) (double t, const double *y, double *value,
                             int *isterminal, int *direction, void *user);
/* Output sink: one row (t, y).  Return 0 to go on, 1 to stop the run,
   < 0 on error.  A step's events go to the event sink before its rows. */
typedef int (*sym_output_fn) (double t, const double *y, void *user);
/* Event sink: an event located at (te, ye), index ie (0-based). */
typedef int (*sym_eventout_fn) (double te, const double *ye, int ie,
                                void *user);
/* The step density rho(t, y) > 0 of a reversible run (1 / time): its
   steps are eps / rho (sym_driver_opts.step_control) */
typedef int (*sym_density_fn) (double t, const double *y, double *rho,
                               void *user);
/* Dense sink: the dense output of the accepted step [t, tnew] at the
   Chebyshev-Lobatto points t + th_i (tnew - t), th_i = (1 - cos (pi i /
   (k + 1))) / 2, i = 0..k+1 (enough for the step's polynomial, of degree
   k + 1 = dense_degree), as the columns of the n-by-(k + 2) y (the first
   is y(t), the last y(tnew)).  Return 0 to go on, < 0 on error. */
typedef int (*sym_denseout_fn) (double t, double tnew, int k,
                                const double *y, void *user);

typedef struct {
  double t0, tf;
  /* output times (strictly monotonic, tout[0] = t0): when ntout > 2 rows go
     out exactly at these times from the dense output; else at every step */
  const double *tout;
  int ntout;
  int refine;          /* ntout <= 2: rows per step (1: step points only) */
  /* fixed step: h_fixed > 0 (sign taken from tf - t0); nsteps_fixed > 0
     takes exactly that many steps, else steps to tf with the last one
     shortened to end on tf (at most SYM_MAX_STEPS of them, else
     SYM_EBADINPUT) */
  double h_fixed;
  long nsteps_fixed;
  /* adaptive (each atol > 0 and finite, else SYM_EBADINPUT) */
  sym_tolerances tol;
  double h0;           /* 0: automatic; inf: as long as hmax allows */
  double hmax;         /* 0: |tf - t0| / 10; inf: no cap (as ode45) */
  /* SYM_CONTROL_REVERSIBLE: steps h_{n+1/2} = eps / rho_{n+1/2} from the
     time-symmetric recurrence (rho_{n-1/2} + rho_{n+1/2}) / 2 = rho(t_n,
     y_n), eps = min (rtol^(1/p), SYM_REV_EPS_MAX) for a method of order
     p; rho is density (NULL: |f(t, y)| / sqrt (|y|^2 + |atol|^2), atol
     as n values, with f at the step points); h0 the first step (0: the
     first density from SYM_REV_START trial steps); hmax 0: no cap.  No
     error estimate: the steps solve as fixed ones do, and a failed one
     ends the run.  Reversible for a symmetric method: the steps from the
     end back, the first one the forward run's last, retrace them. */
  int step_control;
  /* a run that goes on from a step point of an earlier one: fixed steps
     (h_fixed, nsteps_fixed 0), k0 > 0 steps taken from the grid's origin
     grid_t0, t0 = grid_t0 + k0 h as the steps round it (else
     SYM_EBADINPUT), the steps on the same grid and their number counted
     from grid_t0; reversible, rho0 > 0 the first step's density (in
     place of h0) */
  long k0;
  double grid_t0, rho0;
  sym_density_fn density;
  void *density_user;
  long max_steps;      /* 0: no limit */
  /* events */
  int nevents;
  sym_event_fn events;
  void *event_user;
  sym_eventout_fn event_out;
  /* output */
  sym_output_fn output;
  void *output_user;
  sym_denseout_fn dense_out;  /* NULL: none */
  void *dense_user;
} sym_driver_opts;

/* Where a run of TimeStepNumber steps of TimeStepSize ends (h_fixed > 0,
   nsteps_fixed > 0): t0 + N h in the direction of tf, or the output time
   (tf or one of tout) within round-off of it (16 ulps of max(|t0|, N h)),
   so that N steps of h still end on the time N h stands for; else tf. */
double sym_fixed_end (const sym_driver_opts *o);
/* The number of fixed steps a run of o takes (0: o has no fixed steps) */
long sym_fixed_steps (const sym_driver_opts *o);
/* The most rows a run of o hands to its output sink: its output times,
   or its fixed steps' rows (Refine's included); -1 when that depends on
   the run (adaptive steps without output times) */
long sym_output_rows (const sym_driver_opts *o);

/* Integrate sys from y0.  Returns SYM_DONE, SYM_STOP_OUTPUT,
   SYM_STOP_EVENT or a status < 0 (rows handed to the output sink so far
   stay valid).  stats (if not NULL) receives what the run found out. */
int sym_integrate (const sym_stepper_type *type, const sym_system *sys,
                   const sym_method_opts *mopts, const sym_driver_opts *dopts,
                   const double *y0, sym_stats *stats);

/* ---------------------------------------------------------------- ensemble */
/* An ensemble: the members, runs of sym_integrate of one system from the
   columns of y0 (n-by-members), each with its own driver options (its
   sinks, their users), stats and status.  Each member runs on a stack of
   its own, on the caller's thread; every callback of the system and of
   the members' driver options is called from the caller's stack, never
   from a member's (so that a callback may raise an error that unwinds
   the caller).  The members run in rounds: each runs on until it needs
   f, then all their states are evaluated in one call of the system's
   rhs_batch (when it has one; else each state by rhs, in member order).
   A member computes exactly what its own sym_integrate would: its
   status, rows and stats are those of a run alone; one that fails stops
   alone.  A batch call that returns a failure is made again member by
   member, so that each gets the status of its own states. */
typedef struct {
  int members;
  const double *y0;
  const sym_driver_opts *dopts;   /* members of them */
  sym_stats *stats;               /* members of them, or NULL */
  int *status;                    /* members of them: sym_integrate's */
  /* optional: after each round, from the caller's stack: 0 to go on, 1
     to stop every member at its next row (its output then returns 1; a
     member without an output sink runs on), < 0 for an error (the same,
     returning that) */
  int (*round) (void *user);
  void *round_user;
  size_t stack_bytes;             /* a member's stack; 0: SYM_ENS_STACK */
  /* the members' output, event and dense sinks may be called from
     their own stacks (they call nothing that may raise an error): no
     switch for a row */
  int direct_sinks;
  /* at most this many members at once (0: all): a member starts when
     another has ended, and only the ones running hold a stack and a
     stepper; the round callback sees the members running in lockstep
     only when all of them are */
  int max_live;
  long nbatch;                    /* out: calls of rhs_batch */
  long nrounds;                   /* out: rounds */
} sym_ensemble_opts;

/* Returns SYM_SUCCESS once every member has ended (each one's end in
   status), or SYM_EBADINPUT, SYM_ENOMEM (no member ran). */
int sym_ensemble (const sym_stepper_type *type, const sym_system *sys,
                  const sym_method_opts *mopts, sym_ensemble_opts *e);

#ifdef __cplusplus
}
#endif

#endif
