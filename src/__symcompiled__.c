/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* __symcompiled__.c -- MEX entry point of a compiled FCN's calls from
   Octave (inst/@symfcn): what its shared object holds, and f, the
   Hessian, H and the acceleration at given states.

     info = __symcompiled__ ("info", S, WHO)
     dy = __symcompiled__ ("f", S, T, Y, PAR)        Y: n-by-m
     [dy, hess] = __symcompiled__ ("fh", S, T, Y, PAR)  one state
     h = __symcompiled__ ("energy", S, T, Y, PAR)    1-by-m
     a = __symcompiled__ ("accel", S, T, Q, PAR)     d-by-m

   S is the struct the front ends pass (field symplectic_compiled: the
   shared object's path); errors name WHO (info) or symfcn. */
#include "mex/symmex.h"

#include <string.h>

static const char *const who_eval = "symfcn";

/* PAR: empty for npar 0, else a real vector of npar elements */
static const double *
par_arg (const symmex_compiled *k, int nrhs, const mxArray *prhs[])
{
  const int np = symmex_compiled_npar (k);
  const mxArray *p = nrhs > 4 ? prhs[4] : NULL;
  char buf[64];
  if (np == 0 && (! p || mxIsEmpty (p)))
    return NULL;
  if (! p || ! mxIsDouble (p) || mxIsComplex (p) || mxIsSparse (p)
      || mxGetNumberOfElements (p) != (size_t) np)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: the compiled FCN takes %d "
                       "parameter%s as PAR, a real vector, got %s", who_eval,
                       np, np == 1 ? "" : "s",
                       p ? symmex_describe (p, buf, sizeof buf) : "none");
  return mxGetPr (p);
}

static mxArray *
info (const symmex_compiled *k)
{
  static const char *names[] = { "dim", "npar", "batch", "accel", "energy",
                                 "hessian", "nnz" };
  mxArray *s = mxCreateStructMatrix (1, 1, 7, names);
  int nnz;
  const int *cp, *ri;
  symmex_compiled_pattern (k, &nnz, &cp, &ri);
  mxSetField (s, 0, "dim", mxCreateDoubleScalar (symmex_compiled_dim (k)));
  mxSetField (s, 0, "npar", mxCreateDoubleScalar (symmex_compiled_npar (k)));
  static const char *has[] = { "batch", "accel", "energy", "hessian" };
  for (int i = 0; i < 4; i++)
    mxSetField (s, 0, has[i],
                mxCreateLogicalScalar (symmex_compiled_has (k, i)));
  mxSetField (s, 0, "nnz", mxCreateDoubleScalar (nnz < 0 ? 0 : nnz));
  return s;
}

/* the Hessian's values as an n-by-n matrix, sparse where the solvers
   take it sparse */
static mxArray *
hessian (const symmex_compiled *k, const double *val)
{
  int nnz;
  const int *cp, *ri;
  symmex_compiled_pattern (k, &nnz, &cp, &ri);
  const int n = 2 * symmex_compiled_dim (k);
  if (! symmex_compiled_sparse (k))
    {
      mxArray *h = mxCreateDoubleMatrix (n, n, mxREAL);
      double *v = mxGetPr (h);
      for (int j = 0; j < n; j++)
        for (int e = cp[j]; e < cp[j + 1]; e++)
          v[ri[e] + (size_t) j * n] = val[e];
      return h;
    }
  mxArray *h = mxCreateSparse (n, n, nnz > 0 ? nnz : 1, mxREAL);
  mwIndex *jc = mxGetJc (h), *ir = mxGetIr (h);
  double *v = mxGetPr (h);
  for (int j = 0; j <= n; j++)
    jc[j] = cp[j];
  for (int e = 0; e < nnz; e++)
    {
      ir[e] = ri[e];
      v[e] = val[e];
    }
  return h;
}

void
mexFunction (int nlhs, mxArray *plhs[], int nrhs, const mxArray *prhs[])
{
  char cmd[16];
  if (nrhs < 2 || ! mxIsChar (prhs[0])
      || mxGetString (prhs[0], cmd, sizeof cmd)
      || ! symmex_compiled_arg (prhs[1]))
    mexErrMsgIdAndTxt ("Octave:invalid-fun-call", "__symcompiled__: "
                       "expected (CMD, S, ...) with S a compiled FCN's "
                       "struct");
  if (strcmp (cmd, "info") == 0)
    {
      char who[64] = "symcompile";
      if (nrhs > 2 && mxIsChar (prhs[2]))
        mxGetString (prhs[2], who, sizeof who);
      plhs[0] = info (symmex_compiled_open (who, prhs[1]));
      return;
    }
  symmex_compiled *k = symmex_compiled_open (who_eval, prhs[1]);
  const int d = symmex_compiled_dim (k), n = 2 * d;
  const int what = strcmp (cmd, "f") == 0 ? 0 : strcmp (cmd, "fh") == 0 ? 3
                   : strcmp (cmd, "accel") == 0 ? 1
                   : strcmp (cmd, "energy") == 0 ? 2 : -1;
  if (what < 0 || nrhs < 4)
    mexErrMsgIdAndTxt ("Octave:invalid-fun-call", "__symcompiled__: "
                       "unknown call %s", cmd);
  const int rows = what == 1 ? d : n;
  const mxArray *ta = prhs[2], *ya = prhs[3];
  char buf[64];
  if (! mxIsDouble (ya) || mxIsComplex (ya) || mxIsSparse (ya)
      || mxGetNumberOfDimensions (ya) != 2 || mxGetM (ya) != (size_t) rows
      || (what == 3 && mxGetN (ya) != 1))
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: %s must be a real %s of %d "
                       "rows (%s), got %s", who_eval, what == 1 ? "Q" : "Y",
                       what == 3 ? "column" : "matrix", rows,
                       what == 1 ? "q" : "[q; p]",
                       symmex_describe (ya, buf, sizeof buf));
  const int m = (int) mxGetN (ya);
  if (! mxIsDouble (ta) || mxIsComplex (ta) || mxIsSparse (ta)
      || (mxGetNumberOfElements (ta) != 1
          && mxGetNumberOfElements (ta) != (size_t) m))
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: T must be a real scalar or one "
                       "time for each column of Y, got %s", who_eval,
                       symmex_describe (ta, buf, sizeof buf));
  const double *par = par_arg (k, nrhs, prhs);
  double *t = mxMalloc (sizeof (double) * (m + 1));
  for (int j = 0; j < m; j++)
    t[j] = mxGetPr (ta)[mxGetNumberOfElements (ta) == 1 ? 0 : j];
  const double *y = mxGetPr (ya);
  int st;
  if (what == 3)
    {
      plhs[0] = mxCreateDoubleMatrix (n, 1, mxREAL);
      st = symmex_compiled_eval (k, 0, 1, t, y, par, mxGetPr (plhs[0]));
      if (nlhs > 1 && st == 0)
        {
          int nnz;
          const int *cp, *ri;
          symmex_compiled_pattern (k, &nnz, &cp, &ri);
          if (nnz < 0)
            mexErrMsgIdAndTxt ("symplectic:compiled", "%s: the compiled "
                               "FCN has no Hessian (symplectic_hess)",
                               who_eval);
          double *val = mxMalloc (sizeof (double) * (nnz + 1));
          st = symmex_compiled_eval (k, 3, 1, t, y, par, val);
          plhs[1] = hessian (k, val);
        }
    }
  else
    {
      plhs[0] = mxCreateDoubleMatrix (what == 2 ? 1 : rows, m, mxREAL);
      st = symmex_compiled_eval (k, what, m, t, y, par, mxGetPr (plhs[0]));
    }
  if (st == -100)
    mexErrMsgIdAndTxt ("symplectic:compiled", "%s: the compiled FCN has no "
                       "%s", who_eval, what == 1
                       ? "acceleration (symplectic_accel)"
                       : "energy (symplectic_energy)");
  if (st != 0)
    mexWarnMsgIdAndTxt ("symplectic:compiled-status", "%s: the compiled "
                        "FCN returned the status %d", who_eval, st);
}
