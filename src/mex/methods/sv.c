/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* sv.c -- odeSV: Stoermer-Verlet (core: methods/sv.c). */
#include "onestep.h"

const symmex_method symmex_method_sv = {
  "odeSV", &sym_step_sv, sizeof (sym_onestep_opts), symmex_onestep_parse,
  symmex_onestep_options, symmex_onestep_needs_newton, NULL, NULL,
  "dH/dp changed with q (or t) at the same p"
};
