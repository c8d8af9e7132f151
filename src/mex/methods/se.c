/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* se.c -- odeSE: symplectic Euler (core: methods/se.c). */
#include "onestep.h"

static const char *
se_asymmetric (const void *own)
{
  (void) own;
  return "symplectic Euler is not (odeSV's Stoermer-Verlet is)";
}

const symmex_method symmex_method_se = {
  "odeSE", &sym_step_se, sizeof (sym_onestep_opts), symmex_onestep_parse,
  symmex_onestep_options, symmex_onestep_needs_newton, NULL, NULL,
  "dH/dq changed with p at the same q", NULL, symmex_onestep_second_order,
  se_asymmetric, symmex_onestep_take_sparse,
  symmex_onestep_take_tangent
};
