/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* odeSV.c -- MEX entry point of odeSV; all the work is in mex/ and core/. */
#include "mex/symmex.h"

void
mexFunction (int nlhs, mxArray *plhs[], int nrhs, const mxArray *prhs[])
{
  static const symmex_solver solver = { "odeSV", NULL, 0 };
  symmex_solver s = solver;
  s.type = sym_step_sv;
  symmex_run (&s, nlhs, plhs, nrhs, prhs);
}
