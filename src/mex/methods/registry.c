/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* registry.c -- every method's descriptor: their option names are the
   package's, known to every solver (an option of another method is not
   a typo). */
#include "../symmex.h"

const symmex_method *const symmex_methods[] = {
  &symmex_method_se, &symmex_method_sv, &symmex_method_spvi, NULL
};
