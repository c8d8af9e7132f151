/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* calls.h -- internal to the core: how a callback's return is taken
   (system.c), shared with the Jacobians (jacobian.c). */
#ifndef SYM_CALLS_H
#define SYM_CALLS_H

#include "sym.h"

int sym_all_finite (size_t n, const double *v);
/* A callback's own status: 0 ok, > 0 recoverable, < 0 fatal (mapped to
   SYM_ECALLBACK so the core's codes stay distinct from the user's); the
   failure's t and status are kept in ev->st */
int sym_callback_status (sym_eval *ev, double t, int st);
/* A NaN or Inf in a callback's values at t (in f, or in the user's Df
   with f finite): kept in ev->st, SYM_NONFINITE */
int sym_nonfinite_at (sym_eval *ev, double t);
int sym_nonfinite_df_at (sym_eval *ev, double t);

#endif
