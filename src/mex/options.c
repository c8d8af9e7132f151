/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* options.c -- odeset options and the package's own fields, matched by
   name without regard to case, checked, with the defaults that the help
   of symplecticset lists. */
#include "symmex.h"

#include <ctype.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* The most steps TimeStepNumber and MaxSteps may ask for: 1e12, or what
   a long holds where it has 32 bits */
#define MAX_COUNT (LONG_MAX / 2 < 1000000000000LL ? LONG_MAX / 2 \
                   : (long) 1000000000000LL)

static const char *BADARG = "Octave:invalid-input-arg";

static int
name_eq (const char *a, const char *b)
{
  for (; *a && *b; a++, b++)
    if (tolower ((unsigned char) *a) != tolower ((unsigned char) *b))
      return 0;
  return *a == *b;
}

/* The non-empty field whose name matches (any case); two of them (a
   struct with Nodes and nodes both set) are an error: which to take? */
static const mxArray *
field (const char *solver, const mxArray *s, const char *name)
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
          mexErrMsgIdAndTxt (BADARG, "%s: OPTS sets both %s and %s (names "
                             "are matched in any case); give one of them",
                             solver, mxGetFieldNameByNumber (s, found),
                             mxGetFieldNameByNumber (s, i));
        found = i;
        v = vi;
      }
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

const char *
symmex_describe (const mxArray *v, char *buf, size_t len)
{
  /* the dimensions as size () gives them, then the class */
  const mwSize *dims = mxGetDimensions (v);
  mwSize nd = mxGetNumberOfDimensions (v);
  size_t k = 0;
  buf[0] = '\0';
  for (mwSize i = 0; i < nd && k < len; i++)
    {
      int w = snprintf (buf + k, len - k, "%s%lu", i ? "x" : "",
                        (unsigned long) dims[i]);
      if (w < 0)
        break;
      k += (size_t) w;
    }
  if (k < len)
    snprintf (buf + k, len - k, " %s%s%s", mxIsSparse (v) ? "sparse " : "",
              mxIsComplex (v) ? "complex " : "", mxGetClassName (v));
  return buf;
}

int
symmex_is_size (const mxArray *a, size_t r, size_t k)
{
  return mxGetNumberOfDimensions (a) == 2 && mxGetM (a) == r
         && mxGetN (a) == k;
}

int
symmex_is_vector (const mxArray *a)
{
  return mxGetNumberOfDimensions (a) == 2
         && (mxGetM (a) == 1 || mxGetN (a) == 1);
}

const char *
symmex_num (char *buf, size_t len, const char *fmt, double x)
{
  if (isnan (x))
    snprintf (buf, len, "NaN");
  else if (isinf (x))
    snprintf (buf, len, x > 0 ? "Inf" : "-Inf");
  else
    snprintf (buf, len, fmt, x);
  return buf;
}

/* A one-row text of 1 to 39 characters in quotes, then after; anything
   else as symmex_describe gives it */
static const char *
describe_text (const mxArray *v, char *buf, size_t len, const char *after)
{
  char text[40];
  if (mxIsChar (v) && mxGetNumberOfDimensions (v) == 2 && mxGetM (v) == 1
      && mxGetN (v) > 0 && mxGetN (v) < sizeof text
      && ! mxGetString (v, text, sizeof text))
    {
      snprintf (buf, len, "\"%s\"%s", text, after);
      return buf;
    }
  return symmex_describe (v, buf, len);
}

const char *
symmex_describe_word (const mxArray *v, char *buf, size_t len)
{
  return describe_text (v, buf, len, "");
}

const char *
symmex_describe_fn (const mxArray *v, char *buf, size_t len)
{
  return describe_text (v, buf, len, ", which names no function");
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
    mexErrMsgIdAndTxt (BADARG, "%s: %s must be a positive real scalar, "
                       "got %s", solver, name,
                       symmex_describe (v, buf, sizeof buf));
  double x = elem (v, 0);
  if (! (x > 0) || (! allow_inf && ! isfinite (x)))
    mexErrMsgIdAndTxt (BADARG, "%s: %s must be a positive %sscalar, got %s",
                       solver, name, allow_inf ? "" : "finite ",
                       SYMMEX_NUM (x, "%g"));
  return x;
}

static long
pos_integer (const char *solver, const mxArray *v, const char *name,
             long lo, long hi)
{
  char buf[64];
  if (! is_real_numeric (v) || mxGetNumberOfElements (v) != 1)
    mexErrMsgIdAndTxt (BADARG, "%s: %s must be an integer scalar, got %s",
                       solver, name, symmex_describe (v, buf, sizeof buf));
  double x = elem (v, 0);
  if (! isfinite (x) || x != floor (x))
    mexErrMsgIdAndTxt (BADARG, "%s: %s must be an integer, got %s",
                       solver, name, SYMMEX_NUM (x, "%g"));
  if (x < lo || x > hi)
    mexErrMsgIdAndTxt (BADARG, "%s: %s must be between %ld and %ld, got %g",
                       solver, name, lo, hi, x);
  return (long) x;
}

/* "on"/"off" strings, or a logical/numeric finite scalar (nonzero: on). */
static int
on_off (const char *solver, const mxArray *v, const char *name)
{
  if (mxIsChar (v) && mxGetM (v) == 1)
    {
      char buf[8];
      if (mxGetString (v, buf, sizeof buf) == 0)
        {
          if (name_eq (buf, "on"))
            return 1;
          if (name_eq (buf, "off"))
            return 0;
        }
    }
  else if ((mxIsLogical (v) || is_real_numeric (v))
           && mxGetNumberOfElements (v) == 1
           && (mxIsLogical (v) || isfinite (elem (v, 0))))
    return mxIsLogical (v) ? mxGetLogicals (v)[0] != 0 : elem (v, 0) != 0;
  char buf[64];
  mexErrMsgIdAndTxt (BADARG, "%s: %s must be \"on\" or \"off\", got %s",
                     solver, name, symmex_describe_word (v, buf, sizeof buf));
  return 0;
}

mxArray *
symmex_full (const mxArray *a)
{
  if (! a || ! mxIsSparse (a))
    return (mxArray *) a;
  mxArray *in[1] = { (mxArray *) a }, *out[1] = { NULL };
  mexCallMATLAB (1, out, 1, in, "full");
  return out[0];
}

int
symmex_is_function (const mxArray *a)
{
  if (mxIsFunctionHandle (a))
    return 1;
  if (mxIsChar (a) && mxGetM (a) == 1 && mxGetN (a) > 0)
    {
      mxArray *in[1] = { (mxArray *) a }, *out[1] = { NULL };
      mexCallMATLAB (1, out, 1, in, "exist");
      double e = mxGetScalar (out[0]);
      mxDestroyArray (out[0]);
      if (e == 3 || e == 5 || e == 103)
        return 1;
      if (e != 2)
        return 0;
      /* 2 is any file on the path, a script too: nargin knows functions */
      out[0] = NULL;
      mxArray *ex = mexCallMATLABWithTrap (1, out, 1, in, "nargin");
      if (ex)
        {
          mxDestroyArray (ex);
          return 0;
        }
      mxDestroyArray (out[0]);
      return 1;
    }
  return 0;
}

static const mxArray *
function_opt (const char *solver, const mxArray *opts, const char *name)
{
  const mxArray *v = field (solver, opts, name);
  char buf[64];
  if (v && ! symmex_is_function (v))
    mexErrMsgIdAndTxt (BADARG, "%s: %s must be a function handle or the "
                       "name of a function, got %s", solver, name,
                       symmex_describe_fn (v, buf, sizeof buf));
  return v;
}

void
symmex_parse_options (const char *solver, const mxArray *opts, int n,
                      int is_spvi, symmex_opts *o)
{
  const mxArray *v;
  char buf[64];
  memset (o, 0, sizeof (*o));
  if (opts && ! mxIsEmpty (opts)
      && ! (mxIsStruct (opts) && mxGetNumberOfElements (opts) == 1))
    mexErrMsgIdAndTxt (BADARG, "%s: OPTS must be a struct from odeset or "
                       "symplecticset (or a plain 1x1 struct), got %s",
                       solver, symmex_describe (opts, buf, sizeof buf));
  if (opts && mxIsEmpty (opts))
    opts = NULL;

  o->rtol = (v = field (solver, opts, "RelTol"))
            ? pos_scalar (solver, v, "RelTol", 0) : 1e-3;
  o->atol = mxMalloc (sizeof (double) * n);
  o->atol_len = 1;
  o->atol[0] = 1e-6;
  if ((v = field (solver, opts, "AbsTol")))
    {
      size_t k = mxGetNumberOfElements (v);
      if (! is_real_numeric (v) || (k != 1 && k != (size_t) n)
          || ! symmex_is_vector (v))
        mexErrMsgIdAndTxt (BADARG, "%s: AbsTol must be a positive scalar or "
                           "a vector of %d elements (numel (Y0)), got %s",
                           solver, n, symmex_describe (v, buf, sizeof buf));
      for (size_t i = 0; i < k; i++)
        {
          o->atol[i] = elem (v, i);
          if (! (o->atol[i] > 0) || ! isfinite (o->atol[i]))
            mexErrMsgIdAndTxt (BADARG, "%s: AbsTol must be positive and "
                               "finite, got %s", solver,
                               SYMMEX_NUM (o->atol[i], "%g"));
        }
      o->atol_len = (int) k;
    }
  o->norm_control = (v = field (solver, opts, "NormControl"))
                    ? on_off (solver, v, "NormControl") : 0;
  if (o->norm_control && o->atol_len > 1)
    mexErrMsgIdAndTxt (BADARG, "%s: AbsTol must be a scalar when "
                       "NormControl is \"on\"", solver);
  /* Inf: the first step as long as MaxStep and TSPAN allow (the driver
     caps it), as ode45 takes it */
  o->h0 = (v = field (solver, opts, "InitialStep"))
          ? pos_scalar (solver, v, "InitialStep", 1) : 0;
  o->hmax = (v = field (solver, opts, "MaxStep"))
            ? pos_scalar (solver, v, "MaxStep", 1) : 0;
  o->events = function_opt (solver, opts, "Events");
  o->outputfcn = function_opt (solver, opts, "OutputFcn");
  if ((v = field (solver, opts, "OutputSel")))
    {
      size_t k = mxGetNumberOfElements (v);
      if ((! is_real_numeric (v) && ! mxIsLogical (v))
          || ! symmex_is_vector (v))
        mexErrMsgIdAndTxt (BADARG, "%s: OutputSel must be a vector of "
                           "indices into Y0, got %s", solver,
                           symmex_describe (v, buf, sizeof buf));
      o->outputsel = mxMalloc (sizeof (int) * (k + 1));
      if (mxIsLogical (v))
        {
          if (k != (size_t) n)
            mexErrMsgIdAndTxt (BADARG, "%s: a logical OutputSel must have "
                               "%d elements (one per element of Y0), got "
                               "%d", solver, n, (int) k);
          for (size_t i = 0; i < k; i++)
            if (mxGetLogicals (v)[i])
              o->outputsel[o->noutputsel++] = (int) i;
        }
      else
        for (size_t i = 0; i < k; i++)
          {
            double x = elem (v, i);
            if (x != floor (x) || x < 1 || x > n)
              mexErrMsgIdAndTxt (BADARG, "%s: OutputSel must hold integer "
                                 "indices between 1 and %d, got %s", solver, n,
                                 SYMMEX_NUM (x, "%g"));
            o->outputsel[o->noutputsel++] = (int) x - 1;
          }
    }
  o->refine = (v = field (solver, opts, "Refine"))
              ? (int) pos_integer (solver, v, "Refine", 1, 1000000) : 1;
  o->stats = (v = field (solver, opts, "Stats"))
             ? on_off (solver, v, "Stats") : 0;
  o->vectorized = (v = field (solver, opts, "Vectorized"))
                  ? on_off (solver, v, "Vectorized") : 0;
  if ((v = field (solver, opts, "Jacobian")))
    {
      if (symmex_is_function (v))
        o->jacobian = v;
      else if (is_real_numeric (v) && symmex_is_size (v, n, n))
        {
          if (! mxIsDouble (v))
            {
              /* single or integer: a double copy (freed with the call) */
              mxArray *in[1] = { (mxArray *) v }, *out[1] = { NULL };
              mexCallMATLAB (1, out, 1, in, "double");
              v = out[0];
            }
          const double *jv = mxGetPr (v);
          for (size_t i = 0; i < (size_t) n * n; i++)
            if (! isfinite (jv[i]))
              mexErrMsgIdAndTxt (BADARG, "%s: the Jacobian matrix must be "
                                 "finite, element %d is %s", solver,
                                 (int) i + 1, SYMMEX_NUM (jv[i], "%g"));
          o->jacobian = v;
        }
      else
        mexErrMsgIdAndTxt (BADARG, "%s: Jacobian must be a function handle "
                           "or a real %dx%d matrix (df/dy), got %s",
                           solver, n, n, symmex_describe (v, buf, sizeof buf));
    }
  o->hessfcn = function_opt (solver, opts, "HamiltonianHessFcn");
  o->h_fixed = (v = field (solver, opts, "TimeStepSize"))
               ? pos_scalar (solver, v, "TimeStepSize", 0) : 0;
  o->nsteps_fixed = (v = field (solver, opts, "TimeStepNumber"))
                    ? pos_integer (solver, v, "TimeStepNumber", 1,
                                   MAX_COUNT) : 0;
  o->separable = (v = field (solver, opts, "Separable"))
                 ? on_off (solver, v, "Separable") : 0;
  o->newton_tol = (v = field (solver, opts, "NewtonTol"))
                  ? pos_scalar (solver, v, "NewtonTol", 0) : 0;
  if (! (o->newton_tol < 1))
    mexErrMsgIdAndTxt (BADARG, "%s: NewtonTol must be below 1 (it is "
                       "relative to the size of q or p), got %s", solver,
                       SYMMEX_NUM (o->newton_tol, "%g"));
  o->max_newton = (v = field (solver, opts, "MaxNewtonIterations"))
                  ? (int) pos_integer (solver, v, "MaxNewtonIterations", 1,
                                       1000) : 0;
  o->max_steps = (v = field (solver, opts, "MaxSteps"))
                 ? pos_integer (solver, v, "MaxSteps", 1, MAX_COUNT) : 0;

  /* odeset fields that would change the problem solved: not taken (a
     projection onto y >= 0 would break the symplectic map; Hamilton's
     equations have no mass matrix), and said so rather than ignored
     silently.  odeset's hints for other solvers (JPattern, MaxOrder, BDF,
     ...) are ignored. */
  static const char *unsupported[] = { "NonNegative", "Mass" };
  for (size_t i = 0; i < sizeof unsupported / sizeof *unsupported; i++)
    if (field (solver, opts, unsupported[i]))
      mexWarnMsgIdAndTxt ("symplectic:unsupported-option", "%s: option %s "
                          "is not supported and is ignored", solver,
                          unsupported[i]);

  /* odeSPVI: Q_DoFs (modes of q) and Nodes (alias P_DoFs); odepkg's
     PolynomialDegree sets Q_DoFs = degree + 1 (and Nodes unless given). */
  o->nodes = 3;
  o->q_dofs = 0;
  if (is_spvi)
    {
      const mxArray *vn = field (solver, opts, "Nodes");
      const mxArray *vp = field (solver, opts, "P_DoFs");
      const mxArray *vq = field (solver, opts, "Q_DoFs");
      const mxArray *vd = field (solver, opts, "PolynomialDegree");
      /* two names of one number that disagree are refused rather than
         one of them winning */
      int pn = vn ? (int) pos_integer (solver, vn, "Nodes", 1, 40) : 0;
      int pp = vp ? (int) pos_integer (solver, vp, "P_DoFs", 1, 40) : 0;
      int pq = vq ? (int) pos_integer (solver, vq, "Q_DoFs", 2, 41) : 0;
      int pd = vd ? 1 + (int) pos_integer (solver, vd, "PolynomialDegree",
                                           1, 40) : 0;
      if (vn && vp && pn != pp)
        mexErrMsgIdAndTxt (BADARG, "%s: Nodes = %d and its alias P_DoFs = "
                           "%d disagree; give one of them", solver, pn, pp);
      if (vq && vd && pq != pd)
        mexErrMsgIdAndTxt (BADARG, "%s: Q_DoFs = %d and PolynomialDegree = "
                           "%d (Q_DoFs = degree + 1) disagree; give one of "
                           "them", solver, pq, pd - 1);
      if (vn || vp)
        o->nodes = vn ? pn : pp;
      else if (vd)
        o->nodes = pd;
      o->q_dofs = vq ? pq : vd ? pd : o->nodes + 1;
      if (o->q_dofs > 2 * o->nodes)
        mexErrMsgIdAndTxt (BADARG, "%s: Q_DoFs = %d with Nodes = %d is a "
                           "degenerate pair: the scheme does not converge "
                           "unless Q_DoFs <= 2*Nodes", solver, o->q_dofs,
                           o->nodes);
      /* Newton's matrix: kept across steps, or new on every step */
      o->newton_matrix = SYM_MATRIX_AUTO;
      const mxArray *vm = field (solver, opts, "NewtonMatrix");
      if (vm)
        {
          char buf[8] = "";
          if (! mxIsChar (vm) || mxGetString (vm, buf, sizeof buf) != 0
              || ! (name_eq (buf, "auto") || name_eq (buf, "kept")
                    || name_eq (buf, "new")))
            {
              char what[64];
              mexErrMsgIdAndTxt (BADARG, "%s: NewtonMatrix must be \"auto\", "
                                 "\"kept\" or \"new\", got %s", solver,
                                 symmex_describe_word (vm, what, sizeof what));
            }
          o->newton_matrix = name_eq (buf, "kept") ? SYM_MATRIX_KEPT
                             : name_eq (buf, "new") ? SYM_MATRIX_NEW
                             : SYM_MATRIX_AUTO;
        }
    }
}

/* ------------------------------------------------------------ messages */

/* See symmex.h: Octave prefixes "NAME: " to the messages of
   mexErrMsgIdAndTxt and mexWarnMsgIdAndTxt; drop ours so it shows once.
   (A message that does not begin with the MEX function's name is passed on
   as it is.)  From here on the two names are Octave's own functions. */
#undef mexErrMsgIdAndTxt
#undef mexWarnMsgIdAndTxt

static const char *
without_own_prefix (const char *msg)
{
  const char *fn = mexFunctionName ();
  size_t k = fn ? strlen (fn) : 0;
  if (k && strncmp (msg, fn, k) == 0 && msg[k] == ':' && msg[k + 1] == ' ')
    return msg + k + 2;
  return msg;
}

void
symmex_err (const char *id, const char *fmt, ...)
{
  char msg[2048];
  va_list ap;
  va_start (ap, fmt);
  vsnprintf (msg, sizeof msg, fmt, ap);
  va_end (ap);
  mexErrMsgIdAndTxt (id, "%s", without_own_prefix (msg));
}

void
symmex_warn (const char *id, const char *fmt, ...)
{
  char msg[2048];
  va_list ap;
  va_start (ap, fmt);
  vsnprintf (msg, sizeof msg, fmt, ap);
  va_end (ap);
  mexWarnMsgIdAndTxt (id, "%s", without_own_prefix (msg));
}
