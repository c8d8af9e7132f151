/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* odeSPVI.c -- MEX entry point of odeSPVI; all the work is in mex/ and core/. */
#include "mex/symmex.h"

void
mexFunction (int nlhs, mxArray *plhs[], int nrhs, const mxArray *prhs[])
{
  static const symmex_solver solver = { "odeSPVI", NULL, 1 };
  symmex_solver s = solver;
  s.type = sym_step_spvi;
  symmex_run (&s, nlhs, plhs, nrhs, prhs);
}
