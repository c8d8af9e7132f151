/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* __odeSPVI__.c -- MEX entry point of odeSPVI: its descriptor
   (mex/methods/spvi.c) into the common entry (mex/entry.c).  Built as
   __odeSPVI__.mex, the compiled gateway that inst/odeSPVI.m (its help and
   tests) calls, as Octave's ode15s.m calls __ode15__. */
#include "mex/symmex.h"

void
mexFunction (int nlhs, mxArray *plhs[], int nrhs, const mxArray *prhs[])
{
  symmex_run (&symmex_method_spvi, nlhs, plhs, nrhs, prhs);
}
