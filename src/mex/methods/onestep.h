/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* onestep.h -- the parts of the odeSE and odeSV descriptors they share */
#ifndef SYMMEX_ONESTEP_H
#define SYMMEX_ONESTEP_H

#include "../symmex.h"

extern const char *const symmex_onestep_options[];
void symmex_onestep_parse (const char *solver, const mxArray *opts,
                           void *own);
int symmex_onestep_needs_newton (const void *own);
int symmex_onestep_second_order (const void *own);
/* the implicit steps of Stoermer-Verlet and symplectic Euler take a
   sparse Df (the compositions of Method, and explicit steps, do not) */
int symmex_onestep_take_sparse (void *own, int commit);
void symmex_onestep_take_tangent (void *own, sym_tangent *tg);

#endif
