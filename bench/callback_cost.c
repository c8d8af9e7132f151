/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* callback_cost.c -- measures what one call of an Octave function costs
   from C, the way the solvers call it: mexCallMATLAB with argument arrays
   that are reused between calls, by name (FCN a function's name, as the
   solvers call names and simple handles) or through feval (FCN a handle,
   as the solvers call anonymous handles and handles to subfunctions).

     sec = callback_cost (fcn, t, y, ncalls, nout)

   returns the mean wall time of one call with nout outputs (1 or 2: f,
   or f and the Hessian) in seconds.  Built by
   bench/run_benchmarks.m with mkoctfile --mex. */
#include "mex.h"
#include "timing.h"

#include <string.h>

void
mexFunction (int nlhs, mxArray *plhs[], int nrhs, const mxArray *prhs[])
{
  if (nrhs != 5)
    mexErrMsgIdAndTxt ("Octave:invalid-fun-call",
                       "callback_cost (FCN, T, Y, NCALLS, NOUT)");
  int nout = (int) mxGetScalar (prhs[4]);
  if (nout < 1 || nout > 2)
    mexErrMsgIdAndTxt ("Octave:invalid-input-arg",
                       "callback_cost: NOUT must be 1 or 2");
  size_t n = mxGetNumberOfElements (prhs[2]);
  long ncalls = (long) mxGetScalar (prhs[3]);
  char name[64] = "";
  if (mxIsChar (prhs[0]) && mxGetString (prhs[0], name, sizeof name))
    mexErrMsgIdAndTxt ("Octave:invalid-input-arg",
                       "callback_cost: FCN's name is too long");
  mxArray *args[3];
  args[0] = (mxArray *) prhs[0];
  args[1] = mxCreateDoubleScalar (mxGetScalar (prhs[1]));
  args[2] = mxCreateDoubleMatrix (n, 1, mxREAL);
  memcpy (mxGetPr (args[2]), mxGetPr (prhs[2]), n * sizeof (double));
  double t0 = now ();
  for (long k = 0; k < ncalls; k++)
    {
      mxArray *out[2] = { NULL, NULL };
      mxGetPr (args[1])[0] += 1e-9;   /* as a solver: new t and y each call */
      if (name[0])
        mexCallMATLAB (nout, out, 2, args + 1, name);
      else
        mexCallMATLAB (nout, out, 3, args, "feval");
      mxDestroyArray (out[0]);
      if (out[1])
        mxDestroyArray (out[1]);
    }
  double el = now () - t0;
  (void) nlhs;
  plhs[0] = mxCreateDoubleScalar (el / (ncalls > 0 ? ncalls : 1));
}
