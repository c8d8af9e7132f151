/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* symmex.h -- the Octave side of the package: the only code that includes
   mex.h.  One call of a solver (entry.c) reads its arguments (args.c) and
   options (options.c, and the method's own through its descriptor,
   methods/), turns the user's functions into callbacks of the core
   (problem.c, callbacks.c), runs the core, and builds the outputs
   (outputs.c) and messages (messages.c).  Nothing here knows a method but
   its descriptor. */
#ifndef SYMMEX_H
#define SYMMEX_H

#include "mex.h"
#include "../core/sym.h"

/* ------------------------------------------------------------ methods */
struct symmex_opts_s;

/* A method as the MEX layer sees it: one descriptor each (methods/). */
typedef struct {
  const char *name;                     /* the solver: messages, sol.solver */
  const sym_stepper_type *const *type;  /* the core's stepper */
  /* its own options: read from OPTS (NULL when none were given) into own,
     the core's options struct of the method (own_size bytes), with every
     default filled in; errors name the solver */
  size_t own_size;
  void (*parse) (const char *solver, const mxArray *opts, void *own);
  /* its own option names (NULL-terminated) */
  const char *const *option_names;
  /* whether its steps solve Newton's equations (need Df) */
  int (*needs_newton) (const void *own);
  /* fields it adds to sol (may be NULL) */
  void (*sol_fields) (mxArray *sol, const void *own, const sym_stats *st);
  /* Why Newton can fail whatever the step (with fixed steps the message
     then does not advise a smaller one), or NULL */
  const char *(*newton_hint) (const void *own);
  /* what the steps found changing when Separable is on but f is not
     separable (NULL: the method has no Separable) */
  const char *sep_broken;
  /* The core's stepper for own, its options checked against the common
     ones o (errors name the solver); NULL: *type */
  const sym_stepper_type *(*stepper) (const char *solver, const void *own,
                                      const struct symmex_opts_s *o);
  /* whether FCN is the acceleration a(t, q) of y = [q; v] (f = [v; a]);
     NULL: never */
  int (*second_order) (const void *own);
  /* why the method's step is not symmetric (StepControl "reversible"
     needs one), or NULL when it is */
  const char *(*asymmetric) (const void *own);
  /* whether the method takes Df sparse (and, with commit, notes in own
     that it will); NULL: never (a sparse Df is made full) */
  int (*take_sparse) (void *own, int commit);
  /* own carries the tangent map tg (TangentMap; tangent.c); NULL: the
     method has none */
  void (*take_tangent) (void *own, sym_tangent *tg);
} symmex_method;

extern const symmex_method symmex_method_se;
extern const symmex_method symmex_method_sv;
extern const symmex_method symmex_method_spvi;
/* all of them (NULL-terminated) */
extern const symmex_method *const symmex_methods[];

/* The whole call of a solver: NAME (fcn, tspan, y0, opts, p1, ...). */
/* the size of a block of the core's that could not be allocated in this
   call (0: none); blocks of SYMMEX_PROBE_BYTES or more are tried first */
#define SYMMEX_PROBE_BYTES ((size_t) 64 << 20)
/* mxMalloc (nbytes), or NULL when the block cannot be had (mxMalloc
   itself would raise an error) */
void *symmex_malloc_or_null (size_t nbytes);
/* whether a block of nbytes could be had now (tried and given back) */
int symmex_can_allocate (double nbytes);
/* the rows of the output are kept in blocks of about this many bytes */
#define SYMMEX_ROW_BLOCK ((size_t) 1 << 20)
extern size_t symmex_alloc_failed;
void symmex_run (const symmex_method *m, int nlhs, mxArray *plhs[],
                 int nrhs, const mxArray *prhs[]);

/* ------------------------------------------------------------ arguments */
typedef struct {
  const mxArray *fcn;
  const double *tspan;
  int ntspan;
  double dir;                 /* the sign of tf - t0 */
  const double *y0;
  int n;                      /* numel (y0) = 2d (rows, in an ensemble) */
  int members;                /* Ensemble: the columns of Y0; else 1 */
  const mxArray *opts;        /* OPTS, or NULL */
  int nextra;                 /* P1, ... */
  const mxArray *const *extra;
  /* Y0 a struct with the field symplectic_restart (the front ends' form
     of a sol given as Y0): its y, and where the steps go on from
     (sym_driver_opts k0, grid_t0, rho0) */
  long k0;
  double grid_t0, rho0;
} symmex_args;

/* FCN, TSPAN, Y0, OPTS and the extra parameters; errors name the solver */
void symmex_read_args (const char *solver, int nlhs, int nrhs,
                       const mxArray *prhs[], symmex_args *a);

/* ------------------------------------------------------------ options */
enum { JAC_NONE = 0, JAC_FD, JAC_MATRIX, JAC_FCN, JAC_HESSFCN, JAC_FCN2,
       JAC_COMPILED };

/* The options common to the solvers (odeset's fields and the package's
   common ones) */
typedef struct symmex_opts_s {
  double rtol;
  double *atol;
  int atol_len;
  int norm_control;
  double h0, hmax;
  const mxArray *events;      /* handle or NULL */
  const mxArray *outputfcn;   /* handle/name or NULL */
  int *outputsel;             /* 0-based indices, or NULL */
  int noutputsel;
  int refine;                 /* 0: not given */
  int stats;
  int vectorized;
  const mxArray *jacobian;    /* matrix or handle, or NULL */
  /* JPattern as compressed columns and their colouring (jp_ncolors 0:
     none) */
  int *jp_colptr, *jp_rowind, *jp_color;
  int jp_ncolors;
  int jp_sparse;              /* JPattern was a sparse matrix */
  const mxArray *hessfcn;     /* handle or NULL */
  double h_fixed;
  long nsteps_fixed;
  double newton_tol;
  int max_newton;
  long max_steps;
  const mxArray *hamiltonian; /* H (t, y, ...) for the energy, or NULL */
  int dense;                  /* sol carries the dense output */
  int reversible;             /* StepControl "reversible" */
  const mxArray *densityfcn;  /* StepDensityFcn, or NULL */
  int ensemble;               /* Ensemble: the columns of Y0 are members */
  const mxArray *constraints; /* Constraints (odeSV), or NULL */
  const mxArray *tangent;     /* TangentMap as given, or NULL */
  const mxArray *indicators;  /* Indicators as given, or NULL */
} symmex_opts;

/* Parse OPTS (an odeset struct, a plain struct, or []) for a problem of
   n = 2d components, then check the steps it asks for against TSPAN */
void symmex_parse_options (const char *solver, const symmex_args *a,
                           symmex_opts *o);
/* The fields of OPTS that are other solvers' options (m's own parsed):
   their values checked as those solvers check them (errors name m), then
   each warned about once as ignored (symplectic:ignored-option), unless
   it is an on/off option left off */
void symmex_check_others (const symmex_method *m, const mxArray *opts);
/* fixed steps (TimeStepSize or TimeStepNumber) */
int symmex_fixed (const symmex_opts *o);

/* For the descriptors' parsers: the non-empty field of OPTS named name
   (in any case; NULL if none), and checked values of it */
const mxArray *symmex_field (const char *solver, const mxArray *opts,
                             const char *name);
long symmex_integer (const char *solver, const mxArray *v, const char *name,
                     long lo, long hi);
int symmex_on_off (const char *solver, const mxArray *v, const char *name);
/* v one of words (NULL-terminated, matched in any case): its index */
int symmex_word (const char *solver, const mxArray *v, const char *name,
                 const char *const *words);

/* ------------------------------------------------------------ the problem */
#define SYMMEX_MAXBATCH 64

/* The user's functions as the core's callbacks, and what the run collects
   for the outputs */
typedef struct symmex_ctx_s {
  const char *solver;
  int d, n;
  int members;               /* OutputFcn's y holds this many states */
  /* SecondOrder: FCN takes q and returns a (nf = d values), f = [v; a];
     else nf = n */
  int second_order, nf;
  /* feval arguments: {fcn, t, y, extras...}; t and y are reused */
  mxArray **args;
  int nargs;
  mxArray *batch_t[SYMMEX_MAXBATCH + 1], *batch_y[SYMMEX_MAXBATCH + 1];
  int big_k;                 /* the k of batch_t[0], batch_y[0] */
  /* Jacobian */
  int jac_source;
  mxArray **jargs;           /* {handle, t, y, extras...} for Jacobian/Hess */
  const double *jac_const;
  /* events */
  mxArray **eargs;
  int nevents;
  /* output */
  const symmex_opts *o;
  mxArray **oargs;           /* {OutputFcn, t, y, flag, extras...} */
  int nextra;
  const mxArray *const *extra;
  /* the rows: their times, and their y in blocks of crows rows each
     (symmex_row), so that the outputs are made block by block, each
     freed once copied: the rows are never held twice */
  double *tbuf, **yblk;
  size_t nrows, cap, crows, nblk, blkcap;
  double *te, *ye;
  int *ie;
  size_t nev, evcap;
  /* the names the user's functions are called by, or "" (feval) */
  char fname[64], jname[64], ename[64], oname[64];
  long probe_calls, probe_states;  /* calls of FCN before the run */
  long probe_jac;              /* calls of the Jacobian's source before it */
  int fcn2_sparse;             /* the probe's second output was sparse */
  /* Separable: f_p at (t0, q0) changed with p (the probe); FCN at
     (t0, y0) kept for the run's first call of it there, which the probe
     of f_p then stands in for (f0_kept: not yet used) */
  int sep_probe_broken, f0_kept;
#define SYMMEX_SEP_PROBE "dH/dq changed with p at the same q"
  double *f0, t0;
  const double *y0;
  int sparse;                  /* Df goes to the core sparse */
  int oom;                     /* an output buffer could not grow */
  const char *nonfinite_what;  /* which function last returned NaN/Inf */
  double nonfinite_t;          /* and at which t */
  /* sol's dense output: each step's [t; tnew] and its dense samples
     (n x (dk + 2) each) */
  double *dt, *dy;
  size_t nsteps, dcap;
  int dk;
  /* StepDensityFcn's arguments, and its last value and t */
  mxArray **dargs;
  char dname[64];
  double density, density_t;
  /* the Hamiltonian at the rows, its largest relative change */
  double *hbuf, max_dh;
  /* FCN is compiled (symcompile): its functions, or NULL */
  struct symmex_compiled_s *compiled;
  unsigned called;             /* bits 1 << SYMMEX_CB_*: called once */
  /* TangentMap: Phi at the rows (tangent.c), or NULL */
  struct symmex_tangent_s *tangent;
} symmex_ctx;

/* the user's functions whose first call is checked (symmex_call_cb) */
enum { SYMMEX_CB_JAC, SYMMEX_CB_OUTPUT, SYMMEX_CB_DENSITY,
       SYMMEX_CB_HAMILTONIAN };

/* The context of a run: FCN probed at (t0, y0) (its size and values,
   FCN (t, q) returning a when second_order, and, when need_jac, whether it
   gives the Hessian as a second output; when separable, whether f_p
   changes with p there),
   the source of Newton's matrix, the number of events, OutputFcn's
   "init" (odeplot when nargout is 0); the core's system into sys */
symmex_ctx *symmex_problem (const char *solver, const symmex_args *a,
                            symmex_opts *o, int need_jac, int second_order,
                            int separable, int nlhs, sym_system *sys);

/* Whether Df comes sparse: a sparse Jacobian matrix, a sparse value of
   the Jacobian's function or the Hessian's at (t0, y0) (that call is
   made here, counted in c->probe_jac), or finite differences on a sparse
   JPattern */
int symmex_sparse_source (symmex_ctx *c, const symmex_args *a);
/* the core's system takes Df sparse from then on */
void symmex_use_sparse (symmex_ctx *c, sym_system *sys);

/* outputs.c: row r of the rows kept */
double *symmex_row (const symmex_ctx *c, size_t r);

/* callbacks.c: the core's callbacks (user: the symmex_ctx) */
int symmex_cb_rhs (double t, const double *y, double *dy, void *user);
int symmex_cb_rhs_batch (int k, const double *t, const double *y,
                         double *dy, void *user);
/* The value of the Jacobian's function or the Hessian's (jac_source
   JAC_FCN, JAC_HESSFCN or JAC_FCN2: FCN's second output) at (t, y) */
mxArray *symmex_jac_value (symmex_ctx *c, double t, const double *y);
/* Df sparse (sym_system.sparse): the Jacobian or Hessian as the user's
   function returns it, full or sparse, its entries that are not zero */
int symmex_cb_jac_csc (double t, const double *y, sym_csc *df, void *user);
int symmex_cb_rhs_jac_csc (double t, const double *y, double *dy,
                           sym_csc *df, void *user);
int symmex_cb_jac (double t, const double *y, double *df, void *user);
int symmex_cb_rhs_jac (double t, const double *y, double *dy, double *df,
                       void *user);
int symmex_cb_events (double t, const double *y, double *value,
                      int *isterminal, int *direction, void *user);
int symmex_cb_density (double t, const double *y, double *rho, void *user);
/* a user's function: args = {f, t, y, ...}, by name when it has one */
void symmex_call (int nout, mxArray **out, int nargs, mxArray **args,
                  const char *name);
/* The first call of a user's function with one output (what: how the
   help names it, expect: what it must return), through cellfun's
   ErrorHandler: a function that cannot return a value, and (index_hint)
   an FCN for SecondOrder that indexes past q, get an error that names
   the solver and the function; any other error is raised as it came */
void symmex_call_first (symmex_ctx *c, mxArray **out, int nargs,
                        mxArray **args, const char *what, const char *expect,
                        int index_hint);
/* symmex_call of the callback cb: its first call by symmex_call_first */
void symmex_call_cb (symmex_ctx *c, int cb, mxArray **out, int nargs,
                     mxArray **args, const char *name, const char *what,
                     const char *expect);
/* the name f can be called by (into name), or "" for feval */
void symmex_direct_name (const mxArray *f, char *name, size_t len);
/* a value returned by FCN or the Hessian: checked, as doubles */
const double *symmex_checked (symmex_ctx *c, mxArray **pa, size_t k,
                              const char *what, int logical_ok, double t,
                              const char *expect_fmt, ...);
/* what a Hessian must be, for messages (arguments n, n, n^2) */
extern const char *const SYMMEX_HESS_EXPECT;
/* a is n-by-n, a row or a column (or not of n^2 elements at all) */
int symmex_hessian_shape (const mxArray *a, int n);
/* a's double form (a new array) */
mxArray *symmex_to_double (const mxArray *a);
/* A value returned by a user's function, replaced in *pa by its full
   form (sparse values are taken as full), or by its double form (a
   numeric, logical or char value); the replaced array is destroyed. */
mxArray *symmex_take_full (mxArray **pa);
mxArray *symmex_take_double (mxArray **pa);

/* compiled.c: a compiled FCN (symcompile), loaded from its shared
   object; the front ends pass it as a struct with the field
   symplectic_compiled (the object's path) */
typedef struct symmex_compiled_s symmex_compiled;
int symmex_compiled_arg (const mxArray *fcn);
void *symmex_compiled_dlopen (const char *path, const char **why);
/* its functions (errors name who) */
symmex_compiled *symmex_compiled_open (const char *who, const mxArray *fcn);
/* In symmex_problem: the library, PAR1 checked, f probed at (t0, y0),
   the source of Newton's matrices (its Hessian unless the options give
   one), JPattern from the Hessian's pattern */
void symmex_compiled_problem (symmex_ctx *c, const symmex_args *a,
                              symmex_opts *o, int need_jac);
/* its functions as the core's callbacks */
void symmex_compiled_system (symmex_ctx *c, sym_system *sys);
int symmex_compiled_sparse_source (const symmex_ctx *c);
void symmex_compiled_use_sparse (symmex_ctx *c, sym_system *sys);
int symmex_compiled_rhs (double t, const double *y, double *dy, void *user);
int symmex_compiled_rhs_batch (int k, const double *t, const double *y,
                               double *dy, void *user);
int symmex_compiled_sparse (const symmex_compiled *k);
/* for the Octave calls (__symcompiled__): what 0 f, 1 the acceleration,
   2 H (at m columns of y), 3 the Hessian's values (one state); -100
   when the library has no such function */
int symmex_compiled_eval (symmex_compiled *k, int what, int m,
                          const double *t, const double *y,
                          const double *par, double *out);
void symmex_compiled_pattern (const symmex_compiled *k, int *nnz,
                              const int **colptr, const int **rowind);
int symmex_compiled_dim (const symmex_compiled *k);
int symmex_compiled_npar (const symmex_compiled *k);
/* what 0 batch, 1 acceleration, 2 energy, 3 Hessian */
int symmex_compiled_has (const symmex_compiled *k, int what);

/* constraints.c: the Constraints function probed at q0 (its m, whether
   it gives G), as the core's callback; Y0 projected onto the constraints
   (a->y0 then points at the projected copy), with a warning when it
   moved more than round-off, an error past SYMMEX_CON_FAR relative */
#define SYMMEX_CON_FAR 1e-2
const sym_constraints *symmex_constraints (symmex_ctx *c, symmex_args *a,
                                           const sym_system *sys);
/* What f declares, by Octave's nargin or nargout (query); -1 where it
   declares nothing or Octave cannot tell */
double symmex_declared (const mxArray *f, const char *query);

/* ------------------------------------------------------------ outputs */
/* the core's output and event sinks (user: the symmex_ctx) */
int symmex_sink_row (double t, const double *y, void *user);
int symmex_sink_event (double te, const double *ye, int ie, void *user);
int symmex_sink_dense (double t, double tnew, int k, const double *y,
                       void *user);
/* the Hamiltonian option at every row into c->hbuf, and the largest
   relative change from the first (the absolute one if H(t0) = 0) */
void symmex_energy (symmex_ctx *c);
/* OutputFcn (t, y(OutputSel), flag, extras...): its stop flag */
int symmex_outputfcn (symmex_ctx *c, const double *t, int nt,
                      const double *y, const char *flag);
/* sol.restart: what a run given sol as Y0 goes on from (the steps'
   grid or densities, st's restart_*) and the OPTS of this run */
void symmex_sol_restart (mxArray *sol, const sym_stats *st,
                         const mxArray *opts);
/* te, ye, ie into plhs[2..] as far as nlhs asks (the others destroyed) */
void symmex_event_plhs (int nlhs, mxArray *plhs[], mxArray *te,
                        mxArray *ye, mxArray *ie);
/* [t, y, te, ye, ie] or sol into plhs (the rows' blocks freed as they
   are copied: the last use of the rows) */
void symmex_outputs (const symmex_method *m, const void *own,
                     symmex_ctx *c, const sym_stats *st,
                     const char *jac_used, int nlhs, mxArray *plhs[]);

/* ensemble.c: the run of an ensemble (Ensemble on): its members by
   sym_ensemble, its outputs and messages (ensemble_outputs.c), in place
   of a single run's */
void symmex_ensemble (const symmex_method *m, const void *own,
                      const sym_stepper_type *type, const symmex_args *a,
                      const symmex_opts *o, symmex_ctx *c,
                      const sym_system *sys, const sym_method_opts *mo,
                      const sym_driver_opts *dopt, int nlhs, mxArray *plhs[]);
/* an ensemble's outputs need shared times: an error when they have none */
void symmex_ensemble_check (const char *name, const symmex_args *a,
                            const symmex_opts *o, int nlhs);
/* an ensemble runs: every allocation of the core is tried first
   (symmex_malloc_or_null), since an error raised on a member's stack
   could not unwind */
extern int symmex_in_ensemble;

/* tangent.c: TangentMap.  Its value read and checked against the run
   (what this version does not carry Phi through is an error naming the
   solver and the option); NULL when off.  own carries it then. */
sym_tangent *symmex_tangent_setup (const symmex_method *m, void *own,
                                   const symmex_args *a,
                                   const symmex_opts *o, int nlhs);
/* whether the run needs the Jacobian's source for it (FCN's second
   output, HamiltonianHessFcn, Jacobian) */
int symmex_tangent_needs_jac (const symmex_opts *o, int second_order);
/* c keeps Phi at its rows (symmex_sink_row calls symmex_tangent_row) */
void symmex_tangent_attach (symmex_ctx *c, sym_tangent *tg);
void symmex_tangent_row (symmex_ctx *c);
/* sol.phi, n-by-m-by-rows (the kept Phi freed) */
void symmex_tangent_sol (symmex_ctx *c, mxArray *sol);

/* ------------------------------------------------------------ messages */
/* The warning of a run that could not go on (or the error it is), after
   OutputFcn's "done"; drops the events beyond an OutputFcn stop */
void symmex_report (const symmex_method *m, const void *own,
                    const symmex_opts *o, const symmex_args *a,
                    symmex_ctx *c, const sym_stats *st, int status);
/* the source of Newton's matrices as Stats and sol.stats say it */
void symmex_jac_used (const symmex_ctx *c, const sym_stats *st, char *buf,
                      size_t len);
void symmex_print_stats (const sym_stats *st, const char *jac_used,
                         const symmex_ctx *c);

/* "1x2 double", "2x2 sparse double", "1x1 complex double", "1x3 char": what
   the user gave, for messages (into buf, returned) */
const char *symmex_describe (const mxArray *v, char *buf, size_t len);
/* the same for a value that should be a word ("on", "kept"): a short
   text in quotes, "maybe" */
const char *symmex_describe_word (const mxArray *v, char *buf, size_t len);
/* the same for a value that should be a function; a name in quotes */
const char *symmex_describe_fn (const mxArray *v, char *buf, size_t len);
/* x for a message, as Octave writes it: printf's fmt ("%g", "%.17g"), or
   NaN, Inf, -Inf; into buf, returned.  SYMMEX_NUM (x, fmt) gives it a
   buffer of its own, valid for the statement it is in. */
const char *symmex_num (char *buf, size_t len, const char *fmt, double x);
#define SYMMEX_NUM(x, fmt) symmex_num ((char[40]) { 0 }, 40, (fmt), (x))

/* ------------------------------------------------------------ values */
/* Is a a function handle, or the name of a function (not of a script or
   of another file)? */
int symmex_is_function (const mxArray *a);
/* a is an r-by-k matrix (two dimensions: mxGetN multiplies the trailing
   ones) */
int symmex_is_size (const mxArray *a, size_t r, size_t k);
/* a is a vector: two dimensions, one of them 1 */
int symmex_is_vector (const mxArray *a);
/* a itself, or when a is sparse its full copy: sparse arguments, options
   and values returned by the user's functions are taken as their full
   equivalents. */
mxArray *symmex_full (const mxArray *a);
/* a's data asked for before anything else of it (values.c: what Octave
   leaks otherwise); every value from Octave goes through it first */
void symmex_settle (const mxArray *a);

/* Octave's mexErrMsgIdAndTxt and mexWarnMsgIdAndTxt put "NAME: " (the
   running MEX function's name) in front of every message, and ours already
   begin with the solver's name ("odeSPVI: Y0 must ..."): these wrappers
   (messages.c) raise Octave's own error and warning instead, so that the
   message reads as written.  Every mexErrMsgIdAndTxt/mexWarnMsgIdAndTxt of
   the MEX layer goes through them. */
void symmex_err (const char *id, const char *fmt, ...);
/* frees every block the core holds (entry.c): before an error */
void symmex_release_core (void);
/* the list of the run's core blocks, and put back: a user's function
   that catches the error of a nested run returns with that run's list
   (its blocks freed by Octave) in place of its caller's, so every call
   of user code puts the caller's back when it returns */
void *symmex_core_mark (void);
void symmex_core_back (void *mark);
void symmex_warn (const char *id, const char *fmt, ...);
#ifndef SYMMEX_NO_REDIRECT
#define mexErrMsgIdAndTxt symmex_err
#define mexWarnMsgIdAndTxt symmex_warn
#endif

/* the identifier of bad input */
#define SYMMEX_BADARG "Octave:invalid-input-arg"

#endif
