/* callback_cost.c -- measures what one call of an Octave function costs
   from C, the way the solvers call it: mexCallMATLAB ("feval") with
   argument arrays that are reused between calls.

     sec = callback_cost (fcn, t, y, ncalls)

   returns the mean wall time of one call in seconds.  Built by
   bench/run_benchmarks.m with mkoctfile --mex. */
#include "mex.h"

#include <string.h>
#include <time.h>

static double
now (void)
{
  struct timespec ts;
  clock_gettime (CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

void
mexFunction (int nlhs, mxArray *plhs[], int nrhs, const mxArray *prhs[])
{
  if (nrhs != 4)
    mexErrMsgIdAndTxt ("Octave:invalid-fun-call",
                       "callback_cost (FCN, T, Y, NCALLS)");
  size_t n = mxGetNumberOfElements (prhs[2]);
  long ncalls = (long) mxGetScalar (prhs[3]);
  mxArray *args[3];
  args[0] = (mxArray *) prhs[0];
  args[1] = mxCreateDoubleScalar (mxGetScalar (prhs[1]));
  args[2] = mxCreateDoubleMatrix (n, 1, mxREAL);
  memcpy (mxGetPr (args[2]), mxGetPr (prhs[2]), n * sizeof (double));
  double t0 = now ();
  for (long k = 0; k < ncalls; k++)
    {
      mxArray *out[1] = { NULL };
      mxGetPr (args[1])[0] += 1e-9;   /* as a solver: new t and y each call */
      mexCallMATLAB (1, out, 3, args, "feval");
      mxDestroyArray (out[0]);
    }
  double el = now () - t0;
  (void) nlhs;
  plhs[0] = mxCreateDoubleScalar (el / (ncalls > 0 ? ncalls : 1));
}
