/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* ensemble.h -- internal to a run of an ensemble: its state, shared by
   the run (ensemble.c) and its outputs and messages
   (ensemble_outputs.c) */
#ifndef SYMMEX_ENSEMBLE_H
#define SYMMEX_ENSEMBLE_H

#include "symmex.h"

typedef struct ens_out ens_out;
typedef struct {
  ens_out *E;
  int k;
} member_ref;

struct ens_out {
  symmex_ctx *c;
  const symmex_opts *o;
  int K, n;
  int first;               /* members are named first + 1, ..., first + K */
  int rows_form;           /* [t, Y] (else sol, or nothing) */
  size_t R;                /* rows allotted in Y */
  mxArray *Ya;
  double *Y;
  double *tg;              /* the grid's times (NaN: not yet) */
  unsigned char *weak;     /* tg[r] came from a row at an event's time */
  size_t *nrows;           /* each member's rows so far */
  /* the last rows of each member, B of them, component by component,
     until they go into Y together: Y's rows of a member lie R apart,
     and one row at a time would touch a page for each value */
  double *stage;
  size_t B, *flushed;
  double *tlast, *tev;     /* its last row's time, its last event's */
  symmex_ctx **mc;         /* its context: events, sol's rows (made
                              when first needed, symmex_ens_member) */
  const symmex_opts *om;   /* the options of the members' contexts */
  member_ref *ref;
  int *status;
  size_t emitted;          /* rows handed to OutputFcn */
  long stop_row;           /* the row OutputFcn stopped at, or -1 */
  double *orow;            /* n x K: a row of every member */
};

/* ensemble.c: member k's context (NULL: no memory), its staged rows
   into Y, the time of the grid's row r, and a Y made or cut by Octave */
symmex_ctx *symmex_ens_member (ens_out *E, int k);
void symmex_ens_flush (ens_out *E, int k);
double symmex_ens_grid_t (const ens_out *E, size_t r);
mxArray *symmex_ens_y_call (const char *fn, mxArray *Y, size_t R, int n,
                            int K);

/* ensemble_outputs.c: the warnings, the summed counters and their
   Stats lines, and the outputs asked for */
void symmex_ens_report (const symmex_method *m, const void *own,
                        const symmex_opts *o, const symmex_args *a,
                        ens_out *E, const sym_stats *st);
void symmex_ens_stats_sum (const ens_out *E, const sym_stats *st,
                           const sym_stats *sst, int sstatus,
                           sym_stats *sum);
void symmex_ens_print_stats (const ens_out *E, const sym_stats *sum,
                             int sstatus, long nbatch);
void symmex_ens_outputs (ens_out *E, const symmex_method *m,
                         const void *own, const sym_stats *st, int nlhs,
                         mxArray *plhs[]);

#endif
