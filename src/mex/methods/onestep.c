/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* onestep.c -- what the descriptors of odeSE and odeSV share: their own
   options Separable (odepkg's name: Explicit) and SecondOrder. */
#include "onestep.h"

const char *const symmex_onestep_options[] = { "Separable", "SecondOrder",
                                               NULL };

void
symmex_onestep_parse (const char *solver, const mxArray *opts, void *own)
{
  sym_onestep_opts *o = own;
  const mxArray *v = symmex_field (solver, opts, "Separable");
  const mxArray *x = symmex_field (solver, opts, "Explicit");
  const mxArray *so = symmex_field (solver, opts, "SecondOrder");
  int vs = v ? symmex_on_off (solver, v, "Separable") : 0;
  int xs = x ? symmex_on_off (solver, x, "Explicit") : 0;
  if (v && x && vs != xs)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: Separable and its alias Explicit "
                       "disagree; give one of them", solver);
  o->separable = v ? vs : xs;
  o->second_order = so ? symmex_on_off (solver, so, "SecondOrder") : 0;
  /* q'' = a(q) is separable: its steps are the explicit ones */
  if (o->second_order && (v || x) && ! o->separable)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: SecondOrder is on and %s is off; "
                       "the second-order form q'' = a(t, q) is separable "
                       "(leave %s out)", solver, v ? "Separable" : "Explicit",
                       v ? "Separable" : "Explicit");
  if (o->second_order)
    o->separable = 1;
}

/* explicit steps for a separable H */
int
symmex_onestep_needs_newton (const void *own)
{
  const sym_onestep_opts *o = own;
  return ! o->separable;
}

int
symmex_onestep_second_order (const void *own)
{
  const sym_onestep_opts *o = own;
  return o->second_order;
}

int
symmex_onestep_take_sparse (void *own, int commit)
{
  sym_onestep_opts *o = own;
  const int ok = ! o->separable && ! o->second_order && o->method == 0
                 && ! o->compensated;
  if (ok && commit)
    o->sparse = 1;
  return ok;
}

void
symmex_onestep_take_tangent (void *own, sym_tangent *tg)
{
  ((sym_onestep_opts *) own)->tangent = tg;
}
