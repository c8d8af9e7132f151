/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* onestep.c -- what the descriptors of odeSE and odeSV share: their own
   option Separable (odepkg's name: Explicit). */
#include "onestep.h"

const char *const symmex_onestep_options[] = { "Separable", NULL };

void
symmex_onestep_parse (const char *solver, const mxArray *opts, void *own)
{
  sym_onestep_opts *o = own;
  const mxArray *v = symmex_field (solver, opts, "Separable");
  const mxArray *x = symmex_field (solver, opts, "Explicit");
  int vs = v ? symmex_on_off (solver, v, "Separable") : 0;
  int xs = x ? symmex_on_off (solver, x, "Explicit") : 0;
  if (v && x && vs != xs)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: Separable and its alias Explicit "
                       "disagree; give one of them", solver);
  o->separable = v ? vs : xs;
}

/* explicit steps for a separable H */
int
symmex_onestep_needs_newton (const void *own)
{
  const sym_onestep_opts *o = own;
  return ! o->separable;
}
