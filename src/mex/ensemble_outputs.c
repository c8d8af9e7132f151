/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* ensemble_outputs.c -- what a run of an ensemble (ensemble.c) returns
   and says at its end: [t, Y, te, ye, ie] with the rows after a
   member's end NaN, or sol, one struct a member; the members' warnings;
   Stats, the members' counters summed. */
#include "ensemble.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* the members whose own warnings are given; the rest are counted */
#define WARN_MEMBERS 5

/* ------------------------------------------------------------ outputs */
/* [t, Y]: the terminal events' rows dropped, the rows after a member's
   end NaN, Y cut to the rows of t; events by member, then time */
static void
rows_outputs (ens_out *E, int nlhs, mxArray *plhs[])
{
  const int K = E->K, n = E->n;
  const size_t R = E->R;
  size_t Rt = 0;
  for (int k = 0; k < K; k++)
    {
      symmex_ens_flush (E, k);
      if (E->status[k] == SYM_STOP_EVENT && E->nrows[k] > 0
          && E->tlast[k] == E->tev[k])
        E->nrows[k]--;
      Rt = E->nrows[k] > Rt ? E->nrows[k] : Rt;
    }
  if (E->stop_row >= 0 && (size_t) E->stop_row + 1 < Rt)
    Rt = (size_t) E->stop_row + 1;
  double *Y = E->Y;
  for (int k = 0; k < K; k++)
    for (int i = 0; i < n; i++)
      {
        double *col = Y + R * ((size_t) i + (size_t) n * k);
        for (size_t r = E->nrows[k]; r < Rt; r++)
          col[r] = NAN;
      }
  if (Rt < R)
    {
      /* Y (1:Rt, :, :), by Octave (the one copy of Y, when members
         ended early) */
      E->Ya = symmex_ens_y_call ("resize", E->Ya, Rt, n, K);
    }
  plhs[0] = mxCreateDoubleMatrix (Rt, 1, mxREAL);
  if (Rt)
    memcpy (mxGetPr (plhs[0]), E->tg, Rt * sizeof (double));
  plhs[1] = E->Ya;
  if (nlhs <= 2)
    return;
  const double tend = Rt ? E->tg[Rt - 1] : NAN;
  size_t nev = 0;
  for (int k = 0; k < K; k++)
    nev += E->mc[k] ? E->mc[k]->nev : 0;
  mxArray *te = mxCreateDoubleMatrix (nev ? nev : 0, nev ? 1 : 0, mxREAL);
  mxArray *ye = mxCreateDoubleMatrix (nev, nev ? n : 0, mxREAL);
  mxArray *ie = mxCreateDoubleMatrix (nev, nev ? 2 : 0, mxREAL);
  size_t e = 0;
  for (int k = 0; k < K; k++)
    {
      const symmex_ctx *m = E->mc[k];
      for (size_t j = 0; m && j < m->nev; j++)
        {
          /* none beyond t(end) when OutputFcn stopped the run */
          if (E->stop_row >= 0 && Rt
              && (E->tg[Rt - 1] - E->tg[0]) * (m->te[j] - tend) > 0)
            continue;
          mxGetPr (te)[e] = m->te[j];
          for (int i = 0; i < n; i++)
            mxGetPr (ye)[e + nev * i] = m->ye[j * n + i];
          mxGetPr (ie)[e] = m->ie[j] + 1;
          mxGetPr (ie)[e + nev] = E->first + k + 1;
          e++;
        }
    }
  if (e < nev)
    {
      /* the dropped ones: the kept rows moved up */
      for (int i = 0; i < n; i++)
        memmove (mxGetPr (ye) + e * i, mxGetPr (ye) + nev * i,
                 e * sizeof (double));
      memmove (mxGetPr (ie) + e, mxGetPr (ie) + nev, e * sizeof (double));
      mxSetM (te, e);
      mxSetM (ye, e);
      mxSetM (ie, e);
      if (e == 0)
        {
          mxSetN (te, 0);
          mxSetN (ye, 0);
          mxSetN (ie, 0);
        }
    }
  symmex_event_plhs (nlhs, plhs, te, ye, ie);
}

/* sol: 1 x K, sol(k) as member k's own run returns it */
static mxArray *
sol_outputs (ens_out *E, const symmex_method *m, const void *own,
             const sym_stats *st)
{
  mxArray *all = NULL;
  for (int k = 0; k < E->K; k++)
    {
      char jac_used[160];
      symmex_jac_used (E->mc[k], &st[k], jac_used, sizeof jac_used);
      mxArray *s = NULL;
      symmex_outputs (m, own, E->mc[k], &st[k], jac_used, 1, &s);
      if (! all)
        all = mxCreateStructMatrix (1, E->K, 0, NULL);
      for (int f = 0; f < mxGetNumberOfFields (s); f++)
        {
          const char *name = mxGetFieldNameByNumber (s, f);
          if (mxGetFieldNumber (all, name) < 0)
            mxAddField (all, name);
          mxSetField (all, k, name, mxGetFieldByNumber (s, 0, f));
          mxSetFieldByNumber (s, 0, f, NULL);
        }
      mxDestroyArray (s);
    }
  return all;
}

/* ------------------------------------------------------------ messages */
/* The members' warnings, each under its member's name: the first
   WARN_MEMBERS by their own, the rest in one; an OutputFcn stop once */
void
symmex_ens_report (const symmex_method *m, const void *own,
                   const symmex_opts *o, const symmex_args *a, ens_out *E,
                   const sym_stats *st)
{
  int warned = 0, more = 0, first_more = 0;
  for (int k = 0; k < E->K; k++)
    {
      const int s = E->status[k];
      /* an OutputFcn stop is the ensemble's, said once below */
      if (s == SYM_STOP_OUTPUT && E->stop_row >= 0 && ! st[k].sep_broken)
        continue;
      if ((s == SYM_DONE || s == SYM_STOP_EVENT) && ! st[k].sep_broken)
        continue;
      if (warned == WARN_MEMBERS && s != SYM_ENOMEM && s != SYM_EOUTPUT)
        {
          if (! more++)
            first_more = E->first + k + 1;
          continue;
        }
      char name[96];
      snprintf (name, sizeof name, "%s: member %d", m->name,
                E->first + k + 1);
      symmex_method mk = *m;
      mk.name = name;
      symmex_ctx *mc = symmex_ens_member (E, k);
      if (! mc)
        mexErrMsgIdAndTxt ("Octave:out-of-memory", "%s: out of memory",
                           m->name);
      if (E->rows_form)
        {
          /* its last row, for the message */
          mc->tbuf = &E->tlast[k];
          mc->nrows = E->nrows[k] > 0;
        }
      symmex_report (&mk, own, o, a, mc, &st[k], s == SYM_STOP_OUTPUT
                                                   ? SYM_DONE : s);
      warned++;
    }
  if (more)
    mexWarnMsgIdAndTxt ("symplectic:members", "%s: %d more members stopped "
                        "early or drew a warning (the first of them is "
                        "member %d); sol(k).stats and the NaN rows of Y "
                        "tell which", m->name, more, first_more);
  if (E->stop_row >= 0)
    {
      const double t = symmex_ens_grid_t (E, (size_t) E->stop_row);
      if (t != a->tspan[a->ntspan - 1])
        mexWarnMsgIdAndTxt ("symplectic:output-stop", "%s: OutputFcn asked "
                            "to stop at t = %.15g; returning the solution up "
                            "to there", m->name, t);
    }
}

/* ------------------------------------------------------------ Stats */
/* The counters Stats prints, into *sum: the members' summed, or the
   stacked run's (sstatus SYM_DONE), with the probe calls of FCN */
void
symmex_ens_stats_sum (const ens_out *E, const sym_stats *st,
                      const sym_stats *sst, int sstatus, sym_stats *sum)
{
  const symmex_ctx *c = E->c;
  memset (sum, 0, sizeof *sum);
  sum->cnt.nrhs = c->probe_calls;
  sum->cnt.nrhs_states = c->probe_states;
  sum->cnt.njac = c->probe_jac;
  for (int k = 0; k < E->K; k++)
    {
      long *to = (long *) &sum->cnt;
      const long *from = (const long *) &st[k].cnt;
      for (size_t i = 0; i < sizeof sum->cnt / sizeof (long); i++)
        to[i] += from[i];
      if (st[k].jac_dropped && ! sum->jac_dropped)
        {
          sum->jac_dropped = 1;
          sum->jac_dropped_t = st[k].jac_dropped_t;
        }
      sum->rhs_jac_used |= st[k].rhs_jac_used;
    }
  if (sstatus == SYM_DONE)
    {
      /* one run did it all: its counts */
      sum->cnt = sst->cnt;
      sum->cnt.nrhs += c->probe_calls;
      sum->cnt.nrhs_states += c->probe_states;
    }
}

/* Stats: how the members ran, then the counters of sum */
void
symmex_ens_print_stats (const ens_out *E, const sym_stats *sum, int sstatus,
                        long nbatch)
{
  const int K = E->K;
  char jac_used[160];
  symmex_jac_used (E->c, sum, jac_used, sizeof jac_used);
  if (sstatus == SYM_DONE)
    mexPrintf ("Members: %d, integrated as one system of %d "
               "components (explicit fixed steps, Vectorized); its "
               "counts:\n", K, E->n * K);
  else if (E->o->vectorized)
    mexPrintf ("Members: %d, summed below (%ld Vectorized calls of FCN "
               "for all of them at once)\n", K, nbatch);
  else
    mexPrintf ("Members: %d, summed below\n", K);
  symmex_print_stats (sum, jac_used, E->c);
}

/* The outputs asked for: [t, Y, ...], or sol (nothing for nlhs 0) */
void
symmex_ens_outputs (ens_out *E, const symmex_method *m, const void *own,
                    const sym_stats *st, int nlhs, mxArray *plhs[])
{
  if (E->rows_form)
    rows_outputs (E, nlhs, plhs);
  else if (nlhs == 1)
    {
      if (E->o->hamiltonian)
        for (int k = 0; k < E->K; k++)
          symmex_energy (E->mc[k]);
      plhs[0] = sol_outputs (E, m, own, st);
    }
}

