/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* output.c -- the rows a run hands to the output sink: the step points,
   refined points or requested output times, all from the stepper's dense
   output, and the row of a terminal event. */
#include "driver.h"

#include <float.h>
#include <math.h>
#include <string.h>

int
sym_emit (sym_run *r, double t, const double *y)
{
  int st = r->o->output ? r->o->output (t, y, r->o->output_user) : 0;
  if (st < 0)
    return SYM_EOUTPUT;
  return st > 0 ? SYM_STOP_OUTPUT : SYM_SUCCESS;
}

/* Rows for the accepted step (t, tnew] up to tstop (a terminal event time,
   or NAN). */
int
sym_output_step (sym_run *r, double t, double h, double tnew, const double *ynew,
             double tstop)
{
  const sym_driver_opts *o = r->o;
  int stopped = ! isnan (tstop);
  double tlim = stopped ? tstop : tnew;
  int st;
  if (o->ntout > 2)
    {
      while (r->iout < o->ntout && r->dir * (o->tout[r->iout] - tlim) <= 0)
        {
          double to = o->tout[r->iout];
          if (to == tnew)
            st = sym_emit (r, to, ynew);
          else
            {
              st = r->type->dense (r->state, &r->ev, to, r->ydense);
              if (st)
                return st;
              st = sym_emit (r, to, r->ydense);
            }
          r->iout++;
          if (st)
            return st;
        }
    }
  else
    {
      for (int j = 1; j < o->refine; j++)
        {
          double ti = t + h * j / o->refine;
          /* a refined row within round-off of a terminal event's row
             (4 ulps) would repeat it */
          if (r->dir * (ti - tlim)
              >= (stopped ? -4 * DBL_EPSILON * fmax (fabs (ti), fabs (tlim))
                          : 0))
            break;
          st = r->type->dense (r->state, &r->ev, ti, r->ydense);
          if (st)
            return st;
          if ((st = sym_emit (r, ti, r->ydense)))
            return st;
        }
      if (! stopped && (st = sym_emit (r, tnew, ynew)))
        return st;
    }
  if (stopped)
    {
      /* the event row ends the output, as in ode45 */
      st = r->type->dense (r->state, &r->ev, tstop, r->ydense);
      if (st)
        return st;
      if (o->ntout > 2 && r->iout > 0 && o->tout[r->iout - 1] == tstop)
        return SYM_SUCCESS;   /* already there */
      return sym_emit (r, tstop, r->ydense);
    }
  return SYM_SUCCESS;
}

long
sym_fixed_steps (const sym_driver_opts *o)
{
  if (o->nsteps_fixed > 0)
    return o->nsteps_fixed;
  if (! (o->h_fixed > 0))
    return 0;
  double ratio = fabs (o->tf - o->t0) / o->h_fixed;
  long k = (long) ceil (ratio - SYM_FIXED_FIT * fmax (1.0, ratio));
  return k < 1 ? 1 : k;
}

long
sym_output_rows (const sym_driver_opts *o)
{
  if (o->ntout > 2)
    return o->ntout;
  long k = sym_fixed_steps (o);
  return k > 0 ? k * (o->refine > 1 ? o->refine : 1) + 1 : -1;
}

double
sym_fixed_end (const sym_driver_opts *o)
{
  if (! (o->nsteps_fixed > 0 && o->h_fixed > 0))
    return o->tf;
  const double dir = o->tf >= o->t0 ? 1.0 : -1.0;
  const double len = o->h_fixed * (double) o->nsteps_fixed;
  const double tend = o->t0 + dir * len;
  /* t0 + N h is rounded three times (h, N h, the sum) and the time it
     stands for once more (e.g. 3 * 0.7 = 2.0999999999999996, not 2.1):
     within 16 ulps of max(|t0|, N h) it is that output time */
  const double tol = SYM_SNAP_ULPS * DBL_EPSILON * fmax (fabs (o->t0), len);
  double best = fabs (o->tf - tend), snap = o->tf;
  for (int i = 1; o->ntout > 2 && o->tout && i < o->ntout; i++)
    if (fabs (o->tout[i] - tend) < best)
      {
        best = fabs (o->tout[i] - tend);
        snap = o->tout[i];
      }
  return best <= tol ? snap : tend;
}

int
sym_output_dense (sym_run *r, double t, double tnew)
{
  const int n = r->n, nd = r->nd;
  const double pi = 3.14159265358979323846;
  if (! r->o->dense_out)
    return SYM_SUCCESS;
  memcpy (r->yd, r->y, (size_t) n * sizeof (double));
  for (int i = 1; i <= nd; i++)
    {
      const double th = 0.5 * (1.0 - cos (pi * i / (nd + 1)));
      int st = r->type->dense (r->state, &r->ev, t + th * (tnew - t),
                               r->yd + (size_t) i * n);
      if (st)
        return st;
    }
  memcpy (r->yd + (size_t) (nd + 1) * n, r->ynew, (size_t) n * sizeof (double));
  return r->o->dense_out (t, tnew, nd, r->yd, r->o->dense_user) < 0
         ? SYM_EOUTPUT : SYM_SUCCESS;
}
