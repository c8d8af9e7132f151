/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* onestep.c -- what the descriptors of odeSE and odeSV share: their own
   option Separable. */
#include "onestep.h"

const char *const symmex_onestep_options[] = { "Separable", NULL };

void
symmex_onestep_parse (const char *solver, const mxArray *opts, void *own)
{
  sym_onestep_opts *o = own;
  const mxArray *v = symmex_field (solver, opts, "Separable");
  o->separable = v ? symmex_on_off (solver, v, "Separable") : 0;
}

/* explicit steps for a separable H */
int
symmex_onestep_needs_newton (const void *own)
{
  const sym_onestep_opts *o = own;
  return ! o->separable;
}
