/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* args.c -- a solver's arguments FCN, TSPAN, Y0, OPTS, P1, ...: checked,
   with errors that name the solver and say what was expected. */
#include "symmex.h"

#include <math.h>

static int
is_plain_numeric (const mxArray *a)
{
  return mxIsNumeric (a) && ! mxIsComplex (a);
}

/* a as doubles (a converted copy when it is of another class) */
static const double *
doubles (const mxArray *a)
{
  return mxGetPr (mxIsDouble (a) ? a : symmex_to_double (a));
}

static void
read_tspan (const char *name, const mxArray *arg, symmex_args *a)
{
  char buf[64];
  const mxArray *ts = symmex_full (arg);
  if (! is_plain_numeric (ts) || mxGetNumberOfElements (ts) < 2
      || ! symmex_is_vector (ts))
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: TSPAN must be a real vector [T0, "
                       "TF] or [T0, T1, ..., TF] of at least 2 elements, got "
                       "%s", name, symmex_describe (ts, buf, sizeof buf));
  const double *tspan = doubles (ts);
  const int nt = (int) mxGetNumberOfElements (ts);
  for (int i = 0; i < nt; i++)
    if (! isfinite (tspan[i]))
      mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: TSPAN must be finite, element "
                         "%d is %s", name, i + 1,
                         SYMMEX_NUM (tspan[i], "%g"));
  const double dir = tspan[1] > tspan[0] ? 1 : -1;
  for (int i = 1; i < nt; i++)
    if (! (dir * (tspan[i] - tspan[i - 1]) > 0))
      mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: TSPAN must be strictly "
                         "monotonic (elements %d and %d are %.17g and "
                         "%.17g)", name, i, i + 1, tspan[i - 1], tspan[i]);
  if (! isfinite (tspan[nt - 1] - tspan[0]))
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: TSPAN must span a finite "
                       "interval, TF - T0 = %g - (%g) overflows", name,
                       tspan[nt - 1], tspan[0]);
  a->tspan = tspan;
  a->ntspan = nt;
  a->dir = dir;
}

/* Y0: a vector, or with Ensemble on a matrix with a column for each
   member */
static void
read_y0 (const char *name, const mxArray *arg, int ensemble, symmex_args *a)
{
  char buf[64];
  const mxArray *y0a = symmex_full (arg);
  a->members = 1;
  if (ensemble)
    {
      if (! is_plain_numeric (y0a) || mxIsEmpty (y0a)
          || mxGetNumberOfDimensions (y0a) != 2)
        mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: with Ensemble on, Y0 must be "
                           "a non-empty real matrix [q0; p0] with a column "
                           "for each member, got %s", name,
                           symmex_describe (y0a, buf, sizeof buf));
      if (mxGetM (y0a) % 2)
        mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: with Ensemble on, Y0 must "
                           "have an even number of rows [q; p], got %d",
                           name, (int) mxGetM (y0a));
      if (mxGetM (y0a) * mxGetN (y0a) > (size_t) 1 << 31)
        mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: Y0 is too large (%s)", name,
                           symmex_describe (y0a, buf, sizeof buf));
      const double *y0 = doubles (y0a);
      const size_t k = mxGetNumberOfElements (y0a);
      for (size_t i = 0; i < k; i++)
        if (! isfinite (y0[i]))
          mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: Y0 must be finite, element "
                             "(%d, %d) is %s", name,
                             (int) (i % mxGetM (y0a)) + 1,
                             (int) (i / mxGetM (y0a)) + 1,
                             SYMMEX_NUM (y0[i], "%g"));
      a->y0 = y0;
      a->n = (int) mxGetM (y0a);
      a->members = (int) mxGetN (y0a);
      return;
    }
  if (! is_plain_numeric (y0a) || mxIsEmpty (y0a) || ! symmex_is_vector (y0a))
    {
      if (mxIsComplex (y0a))
        mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: Y0 must be real, got a "
                           "complex value", name);
      mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: Y0 must be a non-empty real "
                         "numeric vector [q0; p0], got %s", name,
                         symmex_describe (y0a, buf, sizeof buf));
    }
  const int n = (int) mxGetNumberOfElements (y0a);
  if (n % 2)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: Y0 must have an even number of "
                       "elements [q; p], got %d", name, n);
  const double *y0 = doubles (y0a);
  for (int i = 0; i < n; i++)
    if (! isfinite (y0[i]))
      mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: Y0 must be finite, element %d "
                         "is %s", name, i + 1, SYMMEX_NUM (y0[i], "%g"));
  a->y0 = y0;
  a->n = n;
}

void
symmex_read_args (const char *name, int nlhs, int nrhs,
                  const mxArray *prhs[], symmex_args *a)
{
  char buf[64];
  if (nrhs < 3)
    mexErrMsgIdAndTxt ("Octave:invalid-fun-call",
                       "%s: expected %s (FCN, TSPAN, Y0) or %s (FCN, TSPAN, "
                       "Y0, OPTS, P1, ...), got %d arguments", name, name,
                       name, nrhs);
  if (nlhs > 5)
    mexErrMsgIdAndTxt ("Octave:invalid-fun-call",
                       "%s: at most 5 outputs [T, Y, TE, YE, IE]", name);
  a->fcn = prhs[0];
  if (! symmex_is_function (a->fcn) && ! symmex_compiled_arg (a->fcn))
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: FCN must be a function handle or "
                       "the name of a function, got %s", name,
                       symmex_describe_fn (a->fcn, buf, sizeof buf));
  read_tspan (name, prhs[1], a);
  /* OPTS is a struct or []; anything else in its place is the first
     parameter, as in the 2013 form NAME (fcn, tspan, y0, p1, ...) */
  const int has_opts = nrhs > 3 && (mxIsStruct (prhs[3])
                                    || mxIsEmpty (prhs[3]));
  a->opts = has_opts ? prhs[3] : NULL;
  a->nextra = nrhs > 3 ? nrhs - 3 - has_opts : 0;
  a->extra = prhs + 3 + has_opts;
  const mxArray *ens = a->opts && mxIsStruct (a->opts)
                       ? symmex_field (name, a->opts, "Ensemble") : NULL;
  const mxArray *y0 = prhs[2];
  a->k0 = 0;
  a->grid_t0 = a->rho0 = 0;
  if (mxIsStruct (y0) && mxGetField (y0, 0, "symplectic_restart"))
    {
      /* from the front ends (a sol given as Y0): the state and where the
         steps go on from; checked by the core against TSPAN */
      const mxArray *k = mxGetField (y0, 0, "k"), *g = mxGetField (y0, 0, "t0"),
                    *rho = mxGetField (y0, 0, "rho");
      a->k0 = k && mxIsDouble (k) && ! mxIsEmpty (k) ? (long) mxGetScalar (k) : 0;
      a->grid_t0 = g && mxIsDouble (g) && ! mxIsEmpty (g) ? mxGetScalar (g) : 0;
      a->rho0 = rho && mxIsDouble (rho) && ! mxIsEmpty (rho)
                ? mxGetScalar (rho) : 0;
      y0 = mxGetField (y0, 0, "y");
      if (! y0)
        mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: Y0 has no field y", name);
    }
  read_y0 (name, y0, ens ? symmex_on_off (name, ens, "Ensemble") : 0, a);
}
