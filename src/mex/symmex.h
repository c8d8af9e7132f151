/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* symmex.h -- the Octave side of the package: the only code that includes
   mex.h.  It validates arguments and options, turns the user's function
   handles into C callbacks of the core, and builds the outputs. */
#ifndef SYMMEX_H
#define SYMMEX_H

#include "mex.h"
#include "../core/sym.h"

/* Which solver is running: its name (for messages) and stepper table. */
typedef struct {
  const char *name;
  const sym_stepper_type *type;
  int is_spvi;
} symmex_solver;

/* The whole call of a solver: odeXX (fcn, tspan, y0, opts, p1, ...). */
void symmex_run (const symmex_solver *solver, int nlhs, mxArray *plhs[],
                 int nrhs, const mxArray *prhs[]);

/* ------------------------------------------------------------ options */
enum { JAC_NONE = 0, JAC_FD, JAC_MATRIX, JAC_FCN, JAC_HESSFCN, JAC_FCN2 };

typedef struct {
  double rtol;
  double *atol;
  int atol_len;
  int norm_control;
  double h0, hmax;
  const mxArray *events;      /* handle or NULL */
  const mxArray *outputfcn;   /* handle/name or NULL */
  int *outputsel;             /* 0-based indices, or NULL */
  int noutputsel;
  int refine;
  int stats;
  int vectorized;
  const mxArray *jacobian;    /* matrix or handle, or NULL */
  const mxArray *hessfcn;     /* handle or NULL */
  double h_fixed;
  long nsteps_fixed;
  int q_dofs, nodes;
  int separable;
  double newton_tol;
  int max_newton;
  int newton_matrix;          /* odeSPVI: SYM_MATRIX_AUTO, _KEPT, _NEW */
  long max_steps;
} symmex_opts;

/* Parse opts (an odeset struct, a plain struct, or []) for a problem of
   n = 2d components; errors name the solver. */
void symmex_parse_options (const char *solver, const mxArray *opts, int n,
                           int is_spvi, symmex_opts *o);

/* Is a a function handle, or the name of a function (not of a script or
   of another file)? */
int symmex_is_function (const mxArray *a);

/* a is an r-by-k matrix (two dimensions: mxGetN multiplies the trailing
   ones) */
int symmex_is_size (const mxArray *a, size_t r, size_t k);
/* a is a vector: two dimensions, one of them 1 */
int symmex_is_vector (const mxArray *a);

/* "1x2 double", "2x2 sparse double", "1x1 complex double", "1x3 char": what
   the user gave, for messages (into buf, returned) */
const char *symmex_describe (const mxArray *v, char *buf, size_t len);
/* the same for a value that should be a word ("on", "kept"): a short
   text in quotes, "maybe" */
const char *symmex_describe_word (const mxArray *v, char *buf, size_t len);
/* the same for a value that should be a function; a name in quotes */
const char *symmex_describe_fn (const mxArray *v, char *buf, size_t len);

/* x for a message, as Octave writes it: printf's fmt ("%g", "%.17g"), or
   NaN, Inf, -Inf (C's printf writes nan, -nan, inf); into buf, returned.
   SYMMEX_NUM (x, fmt) gives it a buffer of its own, valid for the
   statement it is in. */
const char *symmex_num (char *buf, size_t len, const char *fmt, double x);
#define SYMMEX_NUM(x, fmt) symmex_num ((char[40]) { 0 }, 40, (fmt), (x))

/* a itself, or when a is sparse its full copy (freed when the MEX function
   returns, or by the caller): sparse arguments, options and values returned
   by the user's functions are taken as their full equivalents. */
mxArray *symmex_full (const mxArray *a);

/* Octave's mexErrMsgIdAndTxt and mexWarnMsgIdAndTxt put "NAME: " (the
   running MEX function's name) in front of every message, and ours already
   begin with the solver's name ("odeSPVI: Y0 must ..."): the user would see
   it twice.  These wrappers (options.c) format the message, drop that
   leading "NAME: " and pass the rest on, so it appears once.  Every
   mexErrMsgIdAndTxt/mexWarnMsgIdAndTxt of the MEX layer goes through them. */
void symmex_err (const char *id, const char *fmt, ...);
void symmex_warn (const char *id, const char *fmt, ...);
#ifndef SYMMEX_NO_REDIRECT
#define mexErrMsgIdAndTxt symmex_err
#define mexWarnMsgIdAndTxt symmex_warn
#endif

#endif
