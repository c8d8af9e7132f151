/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* options.c -- the options common to the solvers: odeset's fields and the
   package's common ones, matched by name without regard to case, checked,
   with their defaults; and the checks of the steps they ask for against
   TSPAN.  A method's own options are read by its descriptor (methods/)
   with the helpers here. */
#include "symmex.h"

#include <ctype.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

/* The most steps TimeStepNumber and MaxSteps may ask for: SYM_MAX_STEPS,
   or what a long holds where it has 32 bits */
#define MAX_COUNT (LONG_MAX / 2 < SYM_MAX_STEPS ? LONG_MAX / 2 \
                   : (long) SYM_MAX_STEPS)

static int
name_eq (const char *a, const char *b)
{
  for (; *a && *b; a++, b++)
    if (tolower ((unsigned char) *a) != tolower ((unsigned char) *b))
      return 0;
  return *a == *b;
}

/* The non-empty field whose name matches (any case), as given (a sparse
   value kept); two of them (a struct with Nodes and nodes both set) are
   an error: which to take? */
static const mxArray *
field_as_given (const char *solver, const mxArray *s, const char *name)
{
  if (! s)
    return NULL;
  int nf = mxGetNumberOfFields (s), found = -1;
  const mxArray *v = NULL;
  for (int i = 0; i < nf; i++)
    if (name_eq (mxGetFieldNameByNumber (s, i), name))
      {
        const mxArray *vi = mxGetFieldByNumber (s, 0, i);
        if (! vi || mxIsEmpty (vi))
          continue;
        if (found >= 0)
          mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: OPTS sets both %s and %s (names "
                             "are matched in any case); give one of them",
                             solver, mxGetFieldNameByNumber (s, found),
                             mxGetFieldNameByNumber (s, i));
        found = i;
        v = vi;
      }
  symmex_settle (v);
  return v;
}

/* the same, a sparse value made full */
const mxArray *
symmex_field (const char *solver, const mxArray *s, const char *name)
{
  const mxArray *v = field_as_given (solver, s, name);
  return v ? symmex_full (v) : NULL;
}

static int
is_real_numeric (const mxArray *v)
{
  return (mxIsDouble (v) || mxIsSingle (v) || mxIsInt8 (v) || mxIsInt16 (v)
          || mxIsInt32 (v) || mxIsInt64 (v) || mxIsUint8 (v)
          || mxIsUint16 (v) || mxIsUint32 (v) || mxIsUint64 (v))
         && ! mxIsComplex (v);
}

/* Element i of a real numeric array as double. */
static double
elem (const mxArray *v, size_t i)
{
  if (mxIsDouble (v))
    return mxGetPr (v)[i];
  mxArray *in[1] = { (mxArray *) v }, *out[1] = { NULL };
  mexCallMATLAB (1, out, 1, in, "double");
  double x = mxGetPr (out[0])[i];
  mxDestroyArray (out[0]);
  return x;
}

static double
pos_scalar (const char *solver, const mxArray *v, const char *name,
            int allow_inf)
{
  char buf[64];
  if (! is_real_numeric (v) || mxGetNumberOfElements (v) != 1)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: %s must be a positive real scalar, "
                       "got %s", solver, name,
                       symmex_describe (v, buf, sizeof buf));
  double x = elem (v, 0);
  if (! (x > 0) || (! allow_inf && ! isfinite (x)))
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: %s must be a positive %sscalar, got %s",
                       solver, name, allow_inf ? "" : "finite ",
                       SYMMEX_NUM (x, "%g"));
  return x;
}

long
symmex_integer (const char *solver, const mxArray *v, const char *name,
             long lo, long hi)
{
  char buf[64];
  if (! is_real_numeric (v) || mxGetNumberOfElements (v) != 1)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: %s must be an integer scalar, got %s",
                       solver, name, symmex_describe (v, buf, sizeof buf));
  double x = elem (v, 0);
  if (! isfinite (x) || x != floor (x))
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: %s must be an integer, got %s",
                       solver, name, SYMMEX_NUM (x, "%g"));
  if (x < lo || x > hi)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: %s must be between %ld and %ld, got %g",
                       solver, name, lo, hi, x);
  return (long) x;
}

/* "on"/"off" strings, or a logical/numeric finite scalar (nonzero: on). */
int
symmex_on_off (const char *solver, const mxArray *v, const char *name)
{
  if (mxIsChar (v) && mxGetM (v) == 1)
    {
      char buf[8];
      if (mxGetString (v, buf, sizeof buf) == 0)
        {
          if (name_eq (buf, "on") || name_eq (buf, "yes"))
            return 1;
          if (name_eq (buf, "off") || name_eq (buf, "no"))
            return 0;
        }
    }
  else if ((mxIsLogical (v) || is_real_numeric (v))
           && mxGetNumberOfElements (v) == 1
           && (mxIsLogical (v) || isfinite (elem (v, 0))))
    return mxIsLogical (v) ? mxGetLogicals (v)[0] != 0 : elem (v, 0) != 0;
  char buf[64];
  mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: %s must be \"on\" or \"off\", got %s",
                     solver, name, symmex_describe_word (v, buf, sizeof buf));
  return 0;
}

static const mxArray *
function_opt (const char *solver, const mxArray *opts, const char *name)
{
  const mxArray *v = symmex_field (solver, opts, name);
  char buf[64];
  if (v && ! symmex_is_function (v))
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: %s must be a function handle or the "
                       "name of a function, got %s", solver, name,
                       symmex_describe_fn (v, buf, sizeof buf));
  return v;
}

/* RelTol, AbsTol (a scalar or one per component) and NormControl, with
   ode45's defaults */
static void
parse_tolerances (const char *solver, const mxArray *opts, int n,
                  symmex_opts *o)
{
  const mxArray *v;
  char buf[64];
  o->rtol = (v = symmex_field (solver, opts, "RelTol"))
            ? pos_scalar (solver, v, "RelTol", 0) : 1e-3;
  o->atol = mxMalloc (sizeof (double) * n);
  o->atol_len = 1;
  o->atol[0] = 1e-6;
  if ((v = symmex_field (solver, opts, "AbsTol")))
    {
      size_t k = mxGetNumberOfElements (v);
      if (! is_real_numeric (v) || (k != 1 && k != (size_t) n)
          || ! symmex_is_vector (v))
        mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: AbsTol must be a positive "
                           "scalar or a vector of %d elements (numel (Y0)), "
                           "got %s", solver, n,
                           symmex_describe (v, buf, sizeof buf));
      for (size_t i = 0; i < k; i++)
        {
          o->atol[i] = elem (v, i);
          if (! (o->atol[i] > 0) || ! isfinite (o->atol[i]))
            mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: AbsTol must be positive "
                               "and finite, got %s", solver,
                               SYMMEX_NUM (o->atol[i], "%g"));
        }
      o->atol_len = (int) k;
    }
  o->norm_control = (v = symmex_field (solver, opts, "NormControl"))
                    ? symmex_on_off (solver, v, "NormControl") : 0;
  if (o->norm_control && o->atol_len > 1)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: AbsTol must be a scalar when "
                       "NormControl is \"on\"", solver);
}

/* OutputSel: indices into y (1-based), or a logical mask */
static void
parse_outputsel (const char *solver, const mxArray *v, int n,
                 symmex_opts *o)
{
  char buf[64];
  size_t k = mxGetNumberOfElements (v);
  if ((! is_real_numeric (v) && ! mxIsLogical (v)) || ! symmex_is_vector (v))
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: OutputSel must be a vector of "
                       "indices into Y0, got %s", solver,
                       symmex_describe (v, buf, sizeof buf));
  o->outputsel = mxMalloc (sizeof (int) * (k + 1));
  if (mxIsLogical (v))
    {
      if (k != (size_t) n)
        mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: a logical OutputSel must have "
                           "%d elements (one per element of Y0), got %d",
                           solver, n, (int) k);
      for (size_t i = 0; i < k; i++)
        if (mxGetLogicals (v)[i])
          o->outputsel[o->noutputsel++] = (int) i;
      return;
    }
  for (size_t i = 0; i < k; i++)
    {
      double x = elem (v, i);
      if (x != floor (x) || x < 1 || x > n)
        mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: OutputSel must hold integer "
                           "indices between 1 and %d, got %s", solver, n,
                           SYMMEX_NUM (x, "%g"));
      o->outputsel[o->noutputsel++] = (int) x - 1;
    }
}

/* Jacobian: a function, or a constant real n-by-n matrix (df/dy) */
static const mxArray *
parse_jacobian (const char *solver, const mxArray *v, int n)
{
  char buf[64];
  if (symmex_is_function (v))
    return v;
  if (! is_real_numeric (v) || ! symmex_is_size (v, n, n))
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: Jacobian must be a function "
                       "handle or a real %dx%d matrix (df/dy), got %s",
                       solver, n, n, symmex_describe (v, buf, sizeof buf));
  /* single or integer: a double copy (freed with the call) */
  if (! mxIsDouble (v))
    v = symmex_to_double (v);
  const double *jv = mxGetPr (v);
  /* a sparse one: its stored entries */
  const size_t nv = mxIsSparse (v) ? mxGetJc (v)[n] : (size_t) n * n;
  for (size_t i = 0; i < nv; i++)
    if (! isfinite (jv[i]))
      mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: the Jacobian matrix must be "
                         "finite, element %d is %s", solver, (int) i + 1,
                         SYMMEX_NUM (jv[i], "%g"));
  return v;
}

/* JPattern: the nonzero pattern of df/dy, a real or logical n-by-n
   matrix (full or sparse), as compressed columns with a colouring of
   them for the finite differences */
static void
parse_jpattern (const char *solver, const mxArray *v, int n, symmex_opts *o)
{
  char buf[64];
  if (! (is_real_numeric (v) || mxIsLogical (v)) || ! symmex_is_size (v, n, n))
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: JPattern must be a real or "
                       "logical %dx%d matrix (the nonzero pattern of df/dy), "
                       "got %s", solver, n, n,
                       symmex_describe (v, buf, sizeof buf));
  mxArray *a = mxIsLogical (v) || mxIsSparse (v) ? NULL
               : symmex_to_double (v);
  int *cp = mxCalloc ((size_t) n + 1, sizeof (int));
  size_t cap = 16, nnz = 0;
  int *ri = mxMalloc (cap * sizeof (int));
  const mxLogical *lv = mxIsLogical (v) ? mxGetData (v) : NULL;
  const double *dv = lv ? NULL : a ? mxGetPr (a) : mxGetPr (v);
  for (int j = 0; j < n; j++)
    {
      /* a sparse matrix's stored entries (in the order of their rows), or
         every entry of a full one; those that are not zero */
      const mwIndex *jc = mxIsSparse (v) ? mxGetJc (v) : NULL;
      const mwIndex *ir = mxIsSparse (v) ? mxGetIr (v) : NULL;
      const size_t q0 = jc ? jc[j] : (size_t) j * n;
      const size_t q1 = jc ? jc[j + 1] : (size_t) (j + 1) * n;
      for (size_t q = q0; q < q1; q++)
        {
          if (lv ? ! lv[q] : dv[q] == 0.0)
            continue;
          if (nnz == cap)
            ri = mxRealloc (ri, (cap *= 2) * sizeof (int));
          ri[nnz++] = ir ? (int) ir[q] : (int) (q - q0);
        }
      cp[j + 1] = (int) nnz;
    }
  o->jp_colptr = cp;
  o->jp_rowind = ri;
  o->jp_sparse = mxIsSparse (v);
  o->jp_color = mxMalloc ((size_t) n * sizeof (int));
  o->jp_ncolors = sym_pattern_colors (n, cp, ri, o->jp_color);
  if (o->jp_ncolors < 1)
    o->jp_ncolors = 0;   /* (an empty pattern: nothing to colour) */
}

/* Fixed steps, Newton's controls, MaxSteps */
static void
parse_steps (const char *solver, const mxArray *opts, symmex_opts *o)
{
  const mxArray *v;
  o->h_fixed = (v = symmex_field (solver, opts, "TimeStepSize"))
               ? pos_scalar (solver, v, "TimeStepSize", 0) : 0;
  o->nsteps_fixed = (v = symmex_field (solver, opts, "TimeStepNumber"))
                    ? symmex_integer (solver, v, "TimeStepNumber", 1,
                                      MAX_COUNT) : 0;
  o->newton_tol = (v = symmex_field (solver, opts, "NewtonTol"))
                  ? pos_scalar (solver, v, "NewtonTol", 0) : 0;
  if (! (o->newton_tol < 1))
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: NewtonTol must be below 1 (it is "
                       "relative to the size of q or p), got %s", solver,
                       SYMMEX_NUM (o->newton_tol, "%g"));
  o->max_newton = (v = symmex_field (solver, opts, "MaxNewtonIterations"))
                  ? (int) symmex_integer (solver, v, "MaxNewtonIterations",
                                          1, 1000) : 0;
  o->max_steps = (v = symmex_field (solver, opts, "MaxSteps"))
                 ? symmex_integer (solver, v, "MaxSteps", 1, MAX_COUNT) : 0;
}

static void
parse_common (const char *solver, const mxArray *opts, int n, symmex_opts *o)
{
  const mxArray *v;
  char buf[64];
  memset (o, 0, sizeof (*o));
  if (opts && ! mxIsEmpty (opts)
      && ! (mxIsStruct (opts) && mxGetNumberOfElements (opts) == 1))
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: OPTS must be a struct from odeset "
                       "or symplecticset (or a plain 1x1 struct), got %s",
                       solver, symmex_describe (opts, buf, sizeof buf));
  if (opts && mxIsEmpty (opts))
    opts = NULL;
  parse_tolerances (solver, opts, n, o);
  /* Inf: the first step as long as MaxStep and TSPAN allow (the driver
     caps it), as ode45 takes it */
  o->h0 = (v = symmex_field (solver, opts, "InitialStep"))
          ? pos_scalar (solver, v, "InitialStep", 1) : 0;
  o->hmax = (v = symmex_field (solver, opts, "MaxStep"))
            ? pos_scalar (solver, v, "MaxStep", 1) : 0;
  o->events = function_opt (solver, opts, "Events");
  o->outputfcn = function_opt (solver, opts, "OutputFcn");
  if ((v = symmex_field (solver, opts, "OutputSel")))
    parse_outputsel (solver, v, n, o);
  o->refine = (v = symmex_field (solver, opts, "Refine"))
              ? (int) symmex_integer (solver, v, "Refine", 1, 1000000) : 0;
  o->stats = (v = symmex_field (solver, opts, "Stats"))
             ? symmex_on_off (solver, v, "Stats") : 0;
  o->vectorized = (v = symmex_field (solver, opts, "Vectorized"))
                  ? symmex_on_off (solver, v, "Vectorized") : 0;
  /* these two may be sparse: they then make sparse Newton matrices */
  if ((v = field_as_given (solver, opts, "Jacobian")))
    o->jacobian = parse_jacobian (solver, v, n);
  if ((v = field_as_given (solver, opts, "JPattern")))
    parse_jpattern (solver, v, n, o);
  o->hessfcn = function_opt (solver, opts, "HamiltonianHessFcn");
  o->hamiltonian = function_opt (solver, opts, "Hamiltonian");
  o->dense = (v = symmex_field (solver, opts, "Dense"))
             ? symmex_on_off (solver, v, "Dense") : 0;
  static const char *const controls[] = { "standard", "reversible", NULL };
  o->reversible = (v = symmex_field (solver, opts, "StepControl"))
                  ? symmex_word (solver, v, "StepControl", controls) : 0;
  o->densityfcn = function_opt (solver, opts, "StepDensityFcn");
  o->ensemble = (v = symmex_field (solver, opts, "Ensemble"))
                ? symmex_on_off (solver, v, "Ensemble") : 0;
  /* RATTLE's: odeSV only in this release */
  o->constraints = function_opt (solver, opts, "Constraints");
  if (o->constraints && strcmp (solver, "odeSV") != 0)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: Constraints is not supported by "
                       "%s yet; odeSV takes them (RATTLE)", solver, solver);
  o->tangent = field_as_given (solver, opts, "TangentMap");
  o->indicators = field_as_given (solver, opts, "Indicators");
  parse_steps (solver, opts, o);

  /* odeset fields that would change the problem solved: not taken (a
     projection onto y >= 0 would break the symplectic map; Hamilton's
     equations have no mass matrix), and said so rather than ignored
     silently.  odeset's hints for other solvers (MaxOrder, BDF, ...)
     are ignored. */
  static const char *unsupported[] = { "NonNegative", "Mass" };
  for (size_t i = 0; i < sizeof unsupported / sizeof *unsupported; i++)
    if (symmex_field (solver, opts, unsupported[i]))
      mexWarnMsgIdAndTxt ("symplectic:unsupported-option", "%s: option %s "
                          "is not supported and is ignored", solver,
                          unsupported[i]);
}

int
symmex_word (const char *solver, const mxArray *v, const char *name,
             const char *const *words)
{
  char buf[16] = "", what[64], list[128] = "";
  int k;
  if (mxIsChar (v) && mxGetString (v, buf, sizeof buf) == 0)
    for (k = 0; words[k]; k++)
      if (name_eq (buf, words[k]))
        return k;
  for (k = 0; words[k]; k++)
    snprintf (list + strlen (list), sizeof list - strlen (list),
              "%s\"%s\"", k == 0 ? "" : words[k + 1] ? ", " : " or ",
              words[k]);
  mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: %s must be %s, got %s", solver,
                     name, list, symmex_describe_word (v, what, sizeof what));
  return -1;
}

int
symmex_fixed (const symmex_opts *o)
{
  return o->h_fixed > 0 || o->nsteps_fixed > 0;
}

/* SYM_MAX_STEPS as people write it: 1e12 */
static const char *
max_steps_text (void)
{
  static char buf[24];
  snprintf (buf, sizeof buf, "%g", SYM_MAX_STEPS);
  char *e = strstr (buf, "e+");
  if (e)
    memmove (e + 1, e + 2, strlen (e + 2) + 1);
  return buf;
}

/* Fixed steps: a number of steps that fits a long, and steps that move t
   (the core computes t0 + k*h).  Adaptive steps: a MaxStep that would take
   more steps than allowed is refused as such a TimeStepSize is (near
   t = 0 the least step, 16 ulps of t, does not bound it), and RelTol is at
   least 100 eps, as in other ode45 codes (below it the error test asks for
   steps that round-off cannot give). */
static void
check_steps (const char *name, const symmex_args *a, symmex_opts *o)
{
  const double t0 = a->tspan[0], t1 = a->tspan[a->ntspan - 1];
  const double span = fabs (t1 - t0);
  if (symmex_fixed (o))
    {
      double h = o->h_fixed > 0 ? o->h_fixed : span / o->nsteps_fixed;
      double tmax = fmax (fabs (t0), fabs (t1));
      if (o->h_fixed > 0 && o->nsteps_fixed > 0)
        {
          double tend = t0 + a->dir * h * (double) o->nsteps_fixed;
          if (! isfinite (tend))
            mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: TimeStepNumber*TimeStepSize"
                               " = %ld*%g overflows; expected a finite end "
                               "time", name, o->nsteps_fixed, h);
          tmax = fmax (tmax, fabs (tend));
        }
      else if (o->h_fixed > 0 && span / h > SYM_MAX_STEPS)
        mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: TimeStepSize = %g needs %.3g "
                           "steps to cover TSPAN, more than the %s allowed; "
                           "expected TimeStepSize >= %g", name, h, span / h,
                           max_steps_text (), span / SYM_MAX_STEPS);
      if (h < 8 * DBL_EPSILON * tmax)
        mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: the fixed step %g is below the "
                           "round-off of t (|t| up to %g); expected a step "
                           ">= %g", name, h, tmax, 8 * DBL_EPSILON * tmax);
      return;
    }
  if (o->hmax > 0 && span / o->hmax > SYM_MAX_STEPS)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: MaxStep = %g needs %.3g steps to "
                       "cover TSPAN, more than the %s allowed; expected "
                       "MaxStep >= %g", name, o->hmax, span / o->hmax,
                       max_steps_text (), span / SYM_MAX_STEPS);
  if (o->rtol < 100 * DBL_EPSILON)
    {
      mexWarnMsgIdAndTxt ("symplectic:tolerance", "%s: RelTol = %g is below "
                          "100*eps; %g is used", name, o->rtol,
                          100 * DBL_EPSILON);
      o->rtol = 100 * DBL_EPSILON;
    }
}

/* The options a solver knows: odeset's (Octave 7), the package's common
   ones, every method's own (and Explicit, odepkg's name of Separable) */
static const char *const odeset_names[] = {
  "AbsTol", "BDF", "Events", "InitialSlope", "InitialStep", "JConstant",
  "JPattern", "Jacobian", "MStateDependence", "Mass", "MassSingular",
  "MaxOrder", "MaxStep", "MvPattern", "NonNegative", "NormControl",
  "OutputFcn", "OutputSel", "Refine", "RelTol", "Stats", "Vectorized", NULL
};
static const char *const common_names[] = {
  "TimeStepSize", "TimeStepNumber", "HamiltonianHessFcn", "NewtonTol",
  "MaxNewtonIterations", "MaxSteps", "Hamiltonian", "Dense", "StepControl",
  "StepDensityFcn", "Ensemble", "Parallel", "TangentMap", "Indicators",
  "__members__", "Constraints", NULL
};

/* The edit distance of a and b, without regard to case */
static int
distance (const char *a, const char *b)
{
  int la = (int) strlen (a), lb = (int) strlen (b), row[64];
  if (la >= 64 || lb >= 64)
    return 64;
  for (int j = 0; j <= lb; j++)
    row[j] = j;
  for (int i = 1; i <= la; i++)
    {
      int diag = row[0];
      row[0] = i;
      for (int j = 1; j <= lb; j++)
        {
          int up = row[j];
          int cost = tolower ((unsigned char) a[i - 1])
                     != tolower ((unsigned char) b[j - 1]);
          int best = diag + cost;
          if (up + 1 < best)
            best = up + 1;
          if (row[j - 1] + 1 < best)
            best = row[j - 1] + 1;
          row[j] = best;
          diag = up;
        }
    }
  return row[lb];
}

/* name among list: 1; else its nearest in list into *near, at *dist */
static int
known_in (const char *name, const char *const *list, const char **near,
          int *dist)
{
  for (int i = 0; list[i]; i++)
    {
      if (name_eq (name, list[i]))
        return 1;
      int d = distance (name, list[i]);
      if (d < *dist)
        {
          *dist = d;
          *near = list[i];
        }
    }
  return 0;
}

/* The fields of a struct symplecticset made that it warned about: its
   result holds odeset's fields in odeset's order, then the names neither
   knows (warned about there), then the package's, TimeStepSize first; a
   field added later comes after those.  Returns the index of its
   TimeStepSize (the names from 22 to there were warned about), or 0. */
static int
warned_upto (const mxArray *opts)
{
  const int nf = mxGetNumberOfFields (opts);
  int k = 0;
  for (; odeset_names[k]; k++)
    if (k >= nf || strcmp (mxGetFieldNameByNumber (opts, k),
                           odeset_names[k]) != 0)
      return 0;
  for (; k < nf; k++)
    if (strcmp (mxGetFieldNameByNumber (opts, k), "TimeStepSize") == 0)
      return k;
  return 0;
}

/* A field of OPTS that no solver knows (a typo in a plain struct, or one
   added to a struct of odeset or symplecticset) is said once, with the
   nearest known name; those symplecticset said already are not */
static void
check_names (const char *solver, const mxArray *opts)
{
  static const char *const alias[] = { "Explicit", NULL };
  const int nf = opts && mxIsStruct (opts) ? mxGetNumberOfFields (opts) : 0;
  const int warned = nf ? warned_upto (opts) : 0;
  for (int i = 0; i < nf; i++)
    {
      const char *name = mxGetFieldNameByNumber (opts, i);
      const mxArray *v = mxGetFieldByNumber (opts, 0, i);
      if (! v || mxIsEmpty (v) || i < warned)
        continue;
      const char *near = NULL;
      int dist = 64, known = known_in (name, odeset_names, &near, &dist)
                             || known_in (name, common_names, &near, &dist)
                             || known_in (name, alias, &near, &dist);
      for (int k = 0; ! known && symmex_methods[k]; k++)
        known = known_in (name, symmex_methods[k]->option_names, &near,
                          &dist);
      if (known)
        continue;
      if (near && (dist <= 2 || 3 * dist <= (int) strlen (near)))
        mexWarnMsgIdAndTxt ("symplectic:unknown-option", "%s: unknown "
                            "option %s is ignored; did you mean %s?",
                            solver, name, near);
      else
        mexWarnMsgIdAndTxt ("symplectic:unknown-option", "%s: unknown "
                            "option %s is ignored", solver, name);
    }
}

/* The options of adaptive steps given with fixed ones: said, as they do
   nothing there; StepControl "reversible" with them is an error, and
   StepDensityFcn without it is said */
static void
check_fixed (const char *solver, const mxArray *opts, const symmex_opts *o)
{
  static const char *const adaptive[] = { "RelTol", "AbsTol", "NormControl",
                                          "InitialStep", "MaxStep", NULL };
  char list[128] = "";
  int nlist = 0;
  if (o->reversible && symmex_fixed (o))
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: StepControl \"reversible\" "
                       "chooses the steps; leave out TimeStepSize and "
                       "TimeStepNumber (or take StepControl \"standard\")",
                       solver);
  if (o->densityfcn && ! o->reversible)
    mexWarnMsgIdAndTxt ("symplectic:ignored-option", "%s: StepDensityFcn "
                        "is ignored without StepControl \"reversible\"",
                        solver);
  if (! symmex_fixed (o))
    return;
  const char *given[8];
  for (int k = 0; adaptive[k]; k++)
    if (symmex_field (solver, opts, adaptive[k]))
      given[nlist++] = adaptive[k];
  for (int k = 0; k < nlist; k++)
    snprintf (list + strlen (list), sizeof list - strlen (list), "%s%s",
              k == 0 ? "" : k + 1 < nlist ? ", " : " and ", given[k]);
  if (nlist)
    mexWarnMsgIdAndTxt ("symplectic:ignored-option", "%s: %s %s for "
                        "adaptive steps only and %s ignored with a fixed "
                        "step (TimeStepSize or TimeStepNumber)", solver,
                        list, nlist > 1 ? "are" : "is",
                        nlist > 1 ? "are" : "is");
}

/* name is one of method k's own options (Explicit: where Separable is) */
static int
own_option (const symmex_method *k, const char *name)
{
  for (int i = 0; k->option_names[i]; i++)
    if (name_eq (name, k->option_names[i])
        || (name_eq (name, "Explicit")
            && name_eq (k->option_names[i], "Separable")))
      return 1;
  return 0;
}

/* an on/off option left off: it asks for nothing any solver does not do */
static int
is_off (const mxArray *v)
{
  char buf[8];
  if (mxIsChar (v))
    return mxGetM (v) == 1 && mxGetString (v, buf, sizeof buf) == 0
           && (name_eq (buf, "off") || name_eq (buf, "no"));
  return (mxIsLogical (v) || is_real_numeric (v))
         && mxGetNumberOfElements (v) == 1
         && (mxIsLogical (v) ? ! mxGetLogicals (v)[0] : elem (v, 0) == 0);
}

void
symmex_check_others (const symmex_method *m, const mxArray *opts)
{
  const int nf = opts && mxIsStruct (opts) ? mxGetNumberOfFields (opts) : 0;
  if (! nf)
    return;
  /* first the values, as the solvers that use them check them (a value
     no solver takes is an error in every one): each other method parses
     the fields that are its own and not m's */
  for (int k = 0; symmex_methods[k]; k++)
    {
      const symmex_method *other = symmex_methods[k];
      if (other == m)
        continue;
      mxArray *sub = mxCreateStructMatrix (1, 1, 0, NULL);
      for (int i = 0; i < nf; i++)
        {
          const char *name = mxGetFieldNameByNumber (opts, i);
          const mxArray *v = mxGetFieldByNumber (opts, 0, i);
          if (v && ! mxIsEmpty (v) && own_option (other, name)
              && ! own_option (m, name))
            mxSetFieldByNumber (sub, 0, mxAddField (sub, name),
                                mxDuplicateArray (v));
        }
      if (mxGetNumberOfFields (sub) > 0)
        {
          void *scratch = mxCalloc (1, other->own_size);
          other->parse (m->name, sub, scratch);
          mxFree (scratch);
        }
      mxDestroyArray (sub);
    }
  /* then each such field once, with the solvers that use it */
  for (int i = 0; i < nf; i++)
    {
      const char *name = mxGetFieldNameByNumber (opts, i);
      const mxArray *v = mxGetFieldByNumber (opts, 0, i);
      if (! v || mxIsEmpty (v) || own_option (m, name) || is_off (v))
        continue;
      char users[64] = "";
      int nu = 0;
      for (int k = 0; symmex_methods[k]; k++)
        if (symmex_methods[k] != m && own_option (symmex_methods[k], name))
          snprintf (users + strlen (users), sizeof users - strlen (users),
                    "%s%s", nu++ ? " and " : "", symmex_methods[k]->name);
      if (nu)
        mexWarnMsgIdAndTxt ("symplectic:ignored-option", "%s: option %s is "
                            "used by %s only; ignored", m->name, name,
                            users);
    }
}

void
symmex_parse_options (const char *solver, const symmex_args *a,
                      symmex_opts *o)
{
  const mxArray *opts = a->opts && ! mxIsEmpty (a->opts) ? a->opts : NULL;
  parse_common (solver, a->opts, a->n, o);
  check_names (solver, opts);
  check_fixed (solver, opts, o);
  check_steps (solver, a, o);
}
