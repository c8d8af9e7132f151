/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* ensemble.c -- a run of an ensemble (Ensemble on): the columns of Y0
   are members, integrated together by sym_ensemble (one batch call of
   FCN for all members' states with Vectorized), each exactly as its own
   run.  Its outputs:
   - [t, Y, te, ye, ie]: the rows on the grid the members share (fixed
     steps, or output times), Y numel (t) x n x members, written in place
     as the members go; a member that stopped early is NaN from there
     (the row of a terminal event, off the grid, is in ye only); ie has
     two columns, the event's index and the member's;
   - sol: a struct array, sol(k) member k's as its own run gives it;
   - OutputFcn: at each row of the grid once every member still running
     has reached it, with the column of all members' states (OutputSel's
     components of member 1, then of member 2, ...);
   - Stats: the members' counters summed; warnings name the member.
   This file: the members set up and run, their rows and events taken as
   they come, OutputFcn after each round; what the run returns and says
   at its end is ensemble_outputs.c's. */
#include "ensemble.h"

#include <limits.h>
#include <math.h>
#include <string.h>

/* a member's status while it runs */
#define RUNNING INT_MIN

/* ------------------------------------------------------------ sinks */
/* No rows yet: at the start, and again when the stacked run failed and
   the members start over in rounds */
static void
rows_clear (ens_out *E)
{
  for (int k = 0; k < E->K; k++)
    {
      E->nrows[k] = 0;
      E->tlast[k] = NAN;
      if (E->flushed)
        E->flushed[k] = 0;
    }
  for (size_t r = 0; r < E->R; r++)
    {
      E->tg[r] = NAN;
      E->weak[r] = 0;
    }
}

/* Member k's context: the shared callbacks' arrays, rows and events of
   its own, no OutputFcn (the ensemble's is called here).  Made on first
   use, possibly on the member's stack (an allocation there must not
   raise an error): NULL when there is no memory. */
symmex_ctx *
symmex_ens_member (ens_out *E, int k)
{
  if (E->mc[k])
    return E->mc[k];
  symmex_ctx *mc = symmex_malloc_or_null (sizeof *mc);
  if (! mc)
    return NULL;
  *mc = *E->c;
  mc->o = E->om;
  mc->members = 1;
  mc->tbuf = NULL;
  mc->yblk = NULL;
  mc->nrows = mc->cap = mc->crows = mc->nblk = mc->blkcap = 0;
  mc->te = mc->ye = NULL;
  mc->ie = NULL;
  mc->nev = mc->evcap = 0;
  mc->dt = mc->dy = NULL;
  mc->nsteps = mc->dcap = 0;
  mc->hbuf = NULL;
  mc->oom = 0;
  E->mc[k] = mc;
  return mc;
}

/* member k's staged rows into Y */
void
symmex_ens_flush (ens_out *E, int k)
{
  const int n = E->n;
  const size_t f = E->flushed[k], cnt = E->nrows[k] - f;
  const double *st = E->stage + (size_t) k * n * E->B;
  for (int i = 0; i < n && cnt; i++)
    memcpy (E->Y + f + E->R * ((size_t) i + (size_t) n * k), st + i * E->B,
            cnt * sizeof (double));
  E->flushed[k] = E->nrows[k];
}

/* component i of member k's row r (in Y or still staged) */
static double
row_value (const ens_out *E, int k, size_t r, int i)
{
  const int n = E->n;
  const size_t f = E->flushed[k];
  if (r < f)
    return E->Y[r + E->R * ((size_t) i + (size_t) n * k)];
  return E->stage[(size_t) k * n * E->B + (size_t) i * E->B + (r - f)];
}

/* [t, Y]: member k's row r into Y(r, :, k), through its stage */
static int
ens_row (double t, const double *y, void *user)
{
  member_ref *mr = user;
  ens_out *E = mr->E;
  const int k = mr->k, n = E->n;
  const size_t r = E->nrows[k];
  if (r >= E->R)
    return -1;
  const size_t j = r - E->flushed[k];
  double *st = E->stage + (size_t) k * n * E->B + j;
  for (int i = 0; i < n; i++)
    st[(size_t) i * E->B] = y[i];
  /* a row at an event's time may be a terminal event's, off the grid */
  const int at_event = t == E->tev[k];
  if (isnan (E->tg[r]) || (E->weak[r] && ! at_event))
    {
      E->tg[r] = t;
      E->weak[r] = (unsigned char) at_event;
    }
  E->tlast[k] = t;
  E->nrows[k] = r + 1;
  if (j + 1 == E->B)
    symmex_ens_flush (E, k);
  return 0;
}

/* the events function is the shared context's; the user pointer the
   driver passes to it and to the event sink is the member's */
static int
ens_events (double t, const double *y, double *value, int *isterminal,
            int *direction, void *user)
{
  member_ref *mr = user;
  return symmex_cb_events (t, y, value, isterminal, direction, mr->E->c);
}

static int
ens_event (double te, const double *ye, int ie, void *user)
{
  member_ref *mr = user;
  symmex_ctx *mc = symmex_ens_member (mr->E, mr->k);
  mr->E->tev[mr->k] = te;
  return mc ? symmex_sink_event (te, ye, ie, mc) : -1;
}

/* ------------------------------------------------------------ OutputFcn */
/* The time of row r of the grid, or NaN */
double
symmex_ens_grid_t (const ens_out *E, size_t r)
{
  if (E->rows_form)
    return E->tg[r];
  double t = NAN;
  for (int k = 0; k < E->K; k++)
    if (E->mc[k]->nrows > r)
      {
        t = E->mc[k]->tbuf[r];
        if (t != E->tev[k])
          break;
      }
  return t;
}

/* Member k's state at row r (time t) into y, or NaN when it has none
   (it ended before, or its row r is a terminal event's): whether it has */
static int
member_row (const ens_out *E, int k, size_t r, double t, double *y)
{
  const int n = E->n;
  if (E->rows_form && r < E->nrows[k]
      && ! (E->status[k] == SYM_STOP_EVENT && r + 1 == E->nrows[k]
            && E->tlast[k] == E->tev[k]))
    {
      for (int i = 0; i < n; i++)
        y[i] = row_value (E, k, r, i);
      return 1;
    }
  if (! E->rows_form && r < E->mc[k]->nrows && E->mc[k]->tbuf[r] == t)
    {
      memcpy (y, symmex_row (E->mc[k], r), sizeof (double) * n);
      return 1;
    }
  for (int i = 0; i < n; i++)
    y[i] = NAN;
  return 0;
}

/* After each round: OutputFcn at the rows every running member has
   reached (all rows once they have all ended) */
static int
ens_round (void *user)
{
  ens_out *E = user;
  if (! E->o->outputfcn)
    return 0;
  size_t done_rows = (size_t) -1, most = 0;
  for (int k = 0; k < E->K; k++)
    {
      size_t nr = E->rows_form ? E->nrows[k] : E->mc[k]->nrows;
      most = nr > most ? nr : most;
      if (E->status[k] == RUNNING && nr < done_rows)
        done_rows = nr;
    }
  if (done_rows == (size_t) -1)
    done_rows = most;
  /* the first row is OutputFcn's "init" */
  if (E->emitted == 0)
    E->emitted = 1;
  for (size_t r = E->emitted; r < done_rows; r++)
    {
      double t = symmex_ens_grid_t (E, r);
      int any = 0;
      for (int k = 0; k < E->K; k++)
        any |= member_row (E, k, r, t, E->orow + (size_t) k * E->n);
      E->emitted = r + 1;
      /* a row only of terminal events' (off the grid) is not Y's */
      if (any && symmex_outputfcn (E->c, &t, 1, E->orow, ""))
        {
          E->stop_row = (long) r;
          return 1;
        }
    }
  return 0;
}

/* ------------------------------------------------------------ explicit steps */
/* Explicit fixed steps act on each component alone: the members stacked
   as one system y = [q_1; ..; q_K; p_1; ..; p_K] take the same steps as
   each alone, to the bit, and its f is one Vectorized call of the
   members' states as columns.  No switch between members, no copy of
   their steppers: the cheapest ensemble there is. */
typedef struct {
  symmex_ctx *c;
  ens_out *E;
  int K, d;
  double *tk, *ym, *fm, *row;
  size_t cap;             /* columns of ym and fm */
} stack_ctx;

static int
stack_rhs_batch (int k, const double *t, const double *y, double *dy,
                 void *user)
{
  stack_ctx *s = user;
  const int K = s->K, d = s->d, n = 2 * d;
  const size_t N = (size_t) d * K, cols = (size_t) k * K;
  if (cols > s->cap)
    {
      mxFree (s->tk);
      mxFree (s->ym);
      mxFree (s->fm);
      s->tk = mxMalloc (cols * sizeof (double));
      s->ym = mxMalloc (cols * n * sizeof (double));
      s->fm = mxMalloc (cols * n * sizeof (double));
      s->cap = cols;
    }
  for (int j = 0; j < k; j++)
    for (int m = 0; m < K; m++)
      {
        const size_t col = (size_t) j * K + m;
        const double *yj = y + (size_t) j * 2 * N + (size_t) m * d;
        double *c = s->ym + col * n;
        s->tk[col] = t[j];
        for (int i = 0; i < d; i++)
          {
            c[i] = yj[i];
            c[d + i] = yj[N + i];
          }
      }
  int st = symmex_cb_rhs_batch ((int) cols, s->tk, s->ym, s->fm, s->c);
  for (int j = 0; j < k; j++)
    for (int m = 0; m < K; m++)
      {
        const size_t col = (size_t) j * K + m;
        double *dyj = dy + (size_t) j * 2 * N + (size_t) m * d;
        const double *c = s->fm + col * n;
        for (int i = 0; i < d; i++)
          {
            dyj[i] = c[i];
            dyj[N + i] = c[d + i];
          }
      }
  return st;
}

static int
stack_rhs (double t, const double *y, double *dy, void *user)
{
  return stack_rhs_batch (1, &t, y, dy, user);
}

static int
stack_row (double t, const double *y, void *user)
{
  stack_ctx *s = user;
  const int K = s->K, d = s->d;
  const size_t N = (size_t) d * K;
  for (int m = 0; m < K; m++)
    {
      for (int i = 0; i < d; i++)
        {
          s->row[i] = y[(size_t) m * d + i];
          s->row[d + i] = y[N + (size_t) m * d + i];
        }
      if (ens_row (t, s->row, &s->E->ref[m]))
        return -1;
    }
  return 0;
}

/* The members as one stacked system: its status (SYM_DONE: every member
   is done, its rows in E), its stats into st */
static int
run_stacked (ens_out *E, const sym_stepper_type *type, const symmex_args *a,
             const sym_method_opts *mo, const sym_driver_opts *dopt,
             sym_stats *st)
{
  const int K = E->K, d = E->n / 2;
  const size_t N = (size_t) d * K;
  stack_ctx s;
  memset (&s, 0, sizeof s);
  s.c = E->c;
  s.E = E;
  s.K = K;
  s.d = d;
  s.row = mxMalloc (E->n * sizeof (double));
  double *y0 = mxMalloc (2 * N * sizeof (double));
  for (int m = 0; m < K; m++)
    for (int i = 0; i < d; i++)
      {
        y0[(size_t) m * d + i] = a->y0[(size_t) m * E->n + i];
        y0[N + (size_t) m * d + i] = a->y0[(size_t) m * E->n + d + i];
      }
  sym_system sys;
  memset (&sys, 0, sizeof sys);
  sys.dim = (int) N;
  sys.rhs = stack_rhs;
  sys.rhs_batch = stack_rhs_batch;
  sys.user = &s;
  sym_driver_opts ds = *dopt;
  ds.output = stack_row;
  ds.output_user = &s;
  ds.events = NULL;
  ds.event_out = NULL;
  ds.dense_out = NULL;
  ds.density = NULL;
  int status = sym_integrate (type, &sys, mo, &ds, y0, st);
  mxFree (y0);
  mxFree (s.row);
  mxFree (s.tk);
  mxFree (s.ym);
  mxFree (s.fm);
  return status;
}

/* ------------------------------------------------------- the run's steps */
/* The members this call runs, into *ar: all of Y0's columns, or the
   share that the internal option __members__ = [first last] (1-based)
   names: the Parallel option's m-code gives each process its share so
   (FCN was checked at the ensemble's first member, and the members
   keep their numbers).  Returns the first one's index (0-based). */
static int
members_share (const char *name, const symmex_args *a, symmex_args *ar)
{
  *ar = *a;
  const mxArray *v = a->opts && mxIsStruct (a->opts)
                     ? symmex_field (name, a->opts, "__members__") : NULL;
  if (! v)
    return 0;
  const double *r = mxIsDouble (v) && ! mxIsComplex (v)
                    && mxGetNumberOfElements (v) == 2 ? mxGetPr (v) : NULL;
  if (! r || ! (r[0] >= 1 && r[0] <= r[1] && r[1] <= a->members)
      || r[0] != floor (r[0]) || r[1] != floor (r[1]))
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: __members__ must be [first "
                       "last], 1 <= first <= last <= %d", name, a->members);
  const int first = (int) r[0] - 1;
  ar->members = (int) (r[1] - r[0]) + 1;
  ar->y0 = a->y0 + (size_t) first * a->n;
  return first;
}

/* Octave's fn (Y, R, n, K), or fn (R, n, K) without Y: a Y of R x n x K
   made or cut by Octave (Y and the sizes are destroyed) */
mxArray *
symmex_ens_y_call (const char *fn, mxArray *Y, size_t R, int n, int K)
{
  mxArray *in[4];
  int nin = 0;
  if (Y)
    in[nin++] = Y;
  in[nin++] = mxCreateDoubleScalar ((double) R);
  in[nin++] = mxCreateDoubleScalar (n);
  in[nin++] = mxCreateDoubleScalar (K);
  mxArray *out[1] = { NULL };
  mexCallMATLAB (1, out, nin, in, fn);
  for (int i = 0; i < nin; i++)
    mxDestroyArray (in[i]);
  return out[0];
}

/* [t, Y]'s arrays: Y of R rows, the grid, the staged rows */
static void
rows_init (ens_out *E, const char *name, long R)
{
  const int K = E->K, n = E->n;
  E->R = (size_t) R;
  /* Y made by Octave's zeros and written in place: an array made by
     mxCreateNumericArray is copied when it is returned, which would
     double the peak memory of a large ensemble.  One that cannot be
     had is said here (zeros would give its own message) */
  const double ybytes = (double) R * n * K * sizeof (double);
  if (! symmex_can_allocate (ybytes))
    mexErrMsgIdAndTxt ("Octave:out-of-memory", "%s: out of memory for "
                       "the output: Y of %ld x %d x %d needs %.3g GB; "
                       "ask for fewer rows (output times in TSPAN, "
                       "Refine) or fewer members in a call", name, R,
                       n, K, ybytes / 1e9);
  E->Ya = symmex_ens_y_call ("zeros", NULL, E->R, n, K);
  E->Y = mxGetPr (E->Ya);
  E->tg = mxMalloc ((E->R ? E->R : 1) * sizeof (double));
  E->weak = mxMalloc (E->R ? E->R : 1);
  const size_t per = (size_t) n * K * sizeof (double);
  E->B = ((size_t) 4 << 20) / per;
  E->B = E->B < 1 ? 1 : E->B > 64 ? 64 : E->B;
  E->stage = mxMalloc (per * E->B);
  E->flushed = mxMalloc (K * sizeof (size_t));
}

/* The outputs' state for the members of a: [t, Y]'s rows with
   nlhs >= 2 (R of them), else each member's context, made as it runs */
static void
ens_init (ens_out *E, const char *name, symmex_ctx *c, const symmex_opts *o,
          const symmex_args *a, int first, int nlhs, long R)
{
  const int K = a->members, n = a->n;
  memset (E, 0, sizeof *E);
  E->c = c;
  E->o = o;
  E->K = K;
  E->n = n;
  E->first = first;
  E->rows_form = nlhs >= 2;
  E->stop_row = -1;
  E->nrows = mxMalloc (K * sizeof (size_t));
  E->tlast = mxMalloc (K * sizeof (double));
  E->tev = mxMalloc (K * sizeof (double));
  E->mc = mxCalloc (K, sizeof (symmex_ctx *));
  E->ref = mxCalloc (K, sizeof (member_ref));
  E->status = mxMalloc (K * sizeof (int));
  E->orow = o->outputfcn ? mxMalloc ((size_t) n * K * sizeof (double))
            : NULL;
  if (E->rows_form)
    rows_init (E, name, R);
  rows_clear (E);
  symmex_opts *om = mxMalloc (sizeof *om);
  *om = *o;
  om->outputfcn = NULL;
  E->om = om;
}

/* Member k's driver options dk[k]: dopt's, with the ensemble's sinks */
static void
members_dopts (ens_out *E, const char *name, const sym_driver_opts *dopt,
               sym_driver_opts *dk)
{
  for (int k = 0; k < E->K; k++)
    {
      /* sol's rows are each member's context's */
      symmex_ctx *mc = E->rows_form ? NULL : symmex_ens_member (E, k);
      if (! E->rows_form && ! mc)
        mexErrMsgIdAndTxt ("Octave:out-of-memory", "%s: out of memory",
                           name);
      E->ref[k].E = E;
      E->ref[k].k = k;
      E->tev[k] = NAN;
      E->status[k] = RUNNING;
      dk[k] = *dopt;
      dk[k].output = E->rows_form ? ens_row : symmex_sink_row;
      dk[k].output_user = E->rows_form ? (void *) &E->ref[k] : (void *) mc;
      dk[k].event_out = ens_event;
      dk[k].event_user = &E->ref[k];
      dk[k].events = dopt->events ? ens_events : NULL;
      dk[k].dense_out = ! E->rows_form && dopt->dense_out
                        ? symmex_sink_dense : NULL;
      dk[k].dense_user = mc;
    }
}

/* Explicit fixed steps, Vectorized, rows only: the members stacked as
   one system.  Its status (SYM_DONE: every member done, the stats in
   *sst), or -1 when not stacked; should that run fail, the rows are
   cleared for the members to run again on their own, each to its end */
static int
try_stacked (ens_out *E, const symmex_method *m, const void *own,
             const sym_stepper_type *type, const symmex_args *a,
             const sym_method_opts *mo, const sym_driver_opts *dopt,
             sym_stats *sst)
{
  const symmex_opts *o = E->o;
  const int K = E->K, n = E->n;
  const int stacked = o->vectorized && symmex_fixed (o)
                      && ! m->needs_newton (own) && ! o->events
                      && ! o->outputfcn && E->rows_form && K >= 2
                      && (size_t) n * K <= INT_MAX;
  memset (sst, 0, sizeof *sst);
  int sstatus = stacked ? run_stacked (E, type, a, mo, dopt, sst) : -1;
  if (sstatus == SYM_DONE)
    for (int k = 0; k < K; k++)
      E->status[k] = SYM_DONE;
  else if (stacked)
    rows_clear (E);
  return sstatus;
}

/* The members in rounds by sym_ensemble, each with its options dk[k]
   and its stats st[k]: the number of Vectorized calls of FCN */
static long
run_rounds (ens_out *E, const char *name, const sym_stepper_type *type,
            const symmex_args *a, const sym_system *sys,
            const sym_method_opts *mo, sym_driver_opts *dk, sym_stats *st)
{
  const int K = E->K;
  sym_ensemble_opts eo;
  memset (&eo, 0, sizeof eo);
  eo.members = K;
  eo.y0 = a->y0;
  eo.dopts = dk;
  eo.stats = st;
  eo.status = E->status;
  eo.round = ens_round;
  eo.round_user = E;
  /* every sink here is plain C: called on the members' stacks */
  eo.direct_sinks = 1;
  /* OutputFcn sees all members at each time: all in lockstep then */
  eo.max_live = E->o->outputfcn ? 0 : SYM_ENS_LIVE;
  symmex_in_ensemble = 1;
  int s = sym_ensemble (type, sys, mo, &eo);
  symmex_in_ensemble = 0;
  if (s)
    mexErrMsgIdAndTxt (s == SYM_ENOMEM ? "Octave:out-of-memory"
                       : "symplectic:internal", "%s: %s for the ensemble "
                       "of %d members", name, s == SYM_ENOMEM
                       ? "out of memory" : "internal failure", K);
  return eo.nbatch;
}

/* ------------------------------------------------------------ the run */
void
symmex_ensemble_check (const char *name, const symmex_args *a,
                       const symmex_opts *o, int nlhs)
{
  /* rows on shared times: fixed steps, or output times */
  if (o->ensemble && ! symmex_fixed (o) && a->ntspan <= 2
      && (nlhs != 1 || o->outputfcn))
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: with Ensemble on and adaptive "
                       "steps each member takes steps of its own: %s needs "
                       "output times in TSPAN (more than two), or a fixed "
                       "step; or ask for SOL", name,
                       o->outputfcn || nlhs == 0 ? "OutputFcn" : "[T, Y]");
}

void
symmex_ensemble (const symmex_method *m, const void *own,
                 const sym_stepper_type *type, const symmex_args *a,
                 const symmex_opts *o, symmex_ctx *c, const sym_system *sys,
                 const sym_method_opts *mo, const sym_driver_opts *dopt,
                 int nlhs, mxArray *plhs[])
{
  const char *name = m->name;
  symmex_args ar;
  const int first = members_share (name, a, &ar);
  a = &ar;
  const int K = a->members;
  c->members = K;
  ens_out E;
  ens_init (&E, name, c, o, a, first, nlhs, sym_output_rows (dopt));
  sym_driver_opts *dk = mxMalloc (K * sizeof (sym_driver_opts));
  sym_stats *st = mxCalloc (K, sizeof (sym_stats));
  members_dopts (&E, name, dopt, dk);
  sym_stats sst;
  const int sstatus = try_stacked (&E, m, own, type, a, mo, dopt, &sst);
  const long nbatch = sstatus == SYM_DONE ? 0
                      : run_rounds (&E, name, type, a, sys, mo, dk, st);
  if (o->outputfcn)
    symmex_outputfcn (c, NULL, 0, NULL, "done");
  sym_stats sum;
  symmex_ens_stats_sum (&E, st, &sst, sstatus, &sum);
  /* the stacked run's warnings as one run's (Separable), else by member */
  if (sstatus == SYM_DONE)
    symmex_report (m, own, o, a, c, &sst, SYM_DONE);
  else
    symmex_ens_report (m, own, o, a, &E, st);
  if (o->stats)
    symmex_ens_print_stats (&E, &sum, sstatus, nbatch);
  symmex_ens_outputs (&E, m, own, st, nlhs, plhs);
}
