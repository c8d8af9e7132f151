/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* odeSE.c -- MEX entry point of odeSE: its descriptor (mex/methods/se.c)
   into the common entry (mex/entry.c). */
#include "mex/symmex.h"

void
mexFunction (int nlhs, mxArray *plhs[], int nrhs, const mxArray *prhs[])
{
  symmex_run (&symmex_method_se, nlhs, plhs, nrhs, prhs);
}
