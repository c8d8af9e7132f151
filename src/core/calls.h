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

/* Blocks carved from a chunk instead of taken from the allocator: the
   arrays and stepper an ensemble's member makes at its start, the same
   for every member, from one chunk of a member's stack slot that the
   next member there takes over.  sym_carve_from carves sym_malloc's
   blocks (16-byte aligned) from chunk (NULL: none, just counted) until
   sym_carve_end, which returns the bytes asked meanwhile, those that
   did not fit included (they came from the allocator).  sym_free leaves
   alone the blocks within the region of sym_carve_region (NULL: none).
   sym_set_allocator ends both. */
void sym_carve_region (const void *lo, size_t nbytes);
void sym_carve_from (void *chunk, size_t nbytes);
size_t sym_carve_end (void);

#endif
