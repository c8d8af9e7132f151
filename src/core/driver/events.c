/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* events.c -- zero crossings of the event functions, located on the
   stepper's dense output: sign changes between the step's ends and the
   samples inside it, and zero pairs predicted between samples by the
   parabola through three of them. */
#include "driver.h"

#include <float.h>
#include <math.h>

int
sym_run_events (sym_run *r, double t, const double *y, double *v)
{
  int st = r->o->events (t, y, v, r->term, r->edir, r->o->event_user);
  if (st)
    {
      r->ev.st.fail_t = t;
      r->ev.st.fail_status = st;
      return st > 0 ? SYM_RECOVERABLE : SYM_ECALLBACK;
    }
  return SYM_SUCCESS;
}

/* The event values v at t inside the accepted step (its dense output) */
static int
events_at (sym_run *r, double t, double *v)
{
  int st = r->type->dense (r->state, &r->ev, t, r->ydense);
  return st ? st : sym_run_events (r, t, r->ydense, v);
}

/* Does event k cross zero from a to b in its selected direction? */
static int
crosses (double a, double b, int direction)
{
  if (a == 0 || isnan (a) || isnan (b))
    return 0;
  int up = a < 0 && b >= 0, down = a > 0 && b <= 0;
  if (direction > 0)
    return up;
  if (direction < 0)
    return down;
  return up || down;
}

/* Locate the zero of event k in (ta, tb] on the dense output by the
   Illinois variant of regula falsi, bisecting when it stalls; stop at a
   bracket of a few ulps.  ga, gb: values at ta, tb. */
static int
locate (sym_run *r, int k, double ta, double ga, double tb, double gb,
        double *te)
{
  int side = 0;
  if (gb == 0)
    {
      /* the zero is the step's end itself (a fixed step landing on it):
         regula falsi would propose tb and fall back on bisection, some
         50 calls of the events function for nothing */
      *te = tb;
      return SYM_SUCCESS;
    }
  for (int it = 0; it < SYM_EVENT_ITERS; it++)
    {
      double width = fabs (tb - ta);
      if (width <= 4 * DBL_EPSILON * fmax (fabs (ta), fabs (tb))
          || width <= DBL_MIN)
        break;
      double tm;
      if (it % 4 == 3)
        tm = 0.5 * (ta + tb);    /* guaranteed progress */
      else
        tm = tb - gb * (tb - ta) / (gb - ga);
      if (! (tm > fmin (ta, tb) && tm < fmax (ta, tb)))
        tm = 0.5 * (ta + tb);
      int st = events_at (r, tm, r->vtry);
      if (st)
        return st;
      double gm = r->vtry[k];
      if (gm == 0)
        {
          ta = tb = tm;
          ga = gb = 0;
          break;
        }
      if ((gm < 0) == (ga < 0))
        {
          ta = tm;
          ga = gm;
          if (side == -1)
            gb *= 0.5;
          side = -1;
        }
      else
        {
          tb = tm;
          gb = gm;
          if (side == 1)
            ga *= 0.5;
          side = 1;
        }
    }
  /* the end after the crossing: the event has happened there */
  *te = tb;
  return SYM_SUCCESS;
}

/* Find the events in (ta, tb] (va, vb: the event values at its ends)
   and report them in time order up to and including the first terminal
   one, and those located at its time too: within same of it (two event
   functions that vanish together, located apart by the round-off of the
   dense output and of the functions, are both reported whichever of them
   is terminal; q and tanh(q) near t = 0 came out 1e-17 apart).  *tstop
   is set to the terminal event's time (or stays NAN). */
static int
events_between (sym_run *r, double ta, const double *va, double tb,
                const double *vb, double same, double *tstop)
{
  const sym_driver_opts *o = r->o;
  int ne = o->nevents;
  /* found events: insertion into arrays sorted by time (at most one per
     event function, so ne entries suffice) */
  double *tfound = r->tfound;
  int *kfound = r->kfound;
  int nf = 0;
  for (int k = 0; k < ne; k++)
    {
      if (! crosses (va[k], vb[k], r->edir[k]))
        continue;
      double te;
      int st = locate (r, k, ta, va[k], tb, vb[k], &te);
      if (st)
        return st;
      int j = nf++;
      while (j > 0 && r->dir * (tfound[j - 1] - te) > 0)
        {
          tfound[j] = tfound[j - 1];
          kfound[j] = kfound[j - 1];
          j--;
        }
      tfound[j] = te;
      kfound[j] = k;
    }
  for (int j = 0; j < nf; j++)
    {
      if (! isnan (*tstop) && ! (fabs (tfound[j] - *tstop) <= same))
        break;
      int st = r->type->dense (r->state, &r->ev, tfound[j], r->ydense);
      if (st)
        return st;
      if (o->event_out)
        {
          st = o->event_out (tfound[j], r->ydense, kfound[j], o->event_user);
          if (st < 0)
            return SYM_EOUTPUT;
        }
      if (r->term[kfound[j]] && isnan (*tstop))
        *tstop = tfound[j];
    }
  return SYM_SUCCESS;
}

/* Where the parabola through three equally spaced event values a, b, c
   (at u = -1, 0, 1) has its vertex: u, or NAN if that is not in (lo, hi)
   or its value there is not clearly (beyond the round-off of the values)
   of the other sign than b: no zero pair predicted (a zero that only
   touches, as (t - 1)^2 does, is not one). */
static double
vertex_pair (double a, double b, double c, double lo, double hi)
{
  double curv = a - 2 * b + c;
  if (! (b != 0) || ! (curv != 0) || (curv > 0) != (b > 0))
    return NAN;   /* no extremum towards the other sign */
  double u = -(c - a) / (2 * curv);
  double g = b - (c - a) * (c - a) / (8 * curv);
  double big = fmax (fabs (a), fmax (fabs (b), fabs (c)));
  if (! (u > lo && u < hi) || (g > 0) == (b > 0)
      || ! (fabs (g) > SYM_EVENT_VERTEX_ULPS * DBL_EPSILON * big))
    return NAN;
  return u;
}

/* The events of the accepted step (t, tnew]: the event values at its
   ends, and at ns = dense_samples equally spaced points inside it on
   the dense output, so that a zero pair inside the step (the function
   back to its sign at the end) is seen when a sample falls between its
   zeros.  A pair between two samples is still found where the parabola
   through three neighbouring samples of the function has its extremum
   between them on the other side of zero: the function is evaluated
   there too.  The pieces in time order until a terminal event.  Events
   at one time: within SYM_EVENT_SAME_ULPS of t and SYM_EVENT_SAME_STEP
   eps of the step. */
int
sym_handle_events (sym_run *r, double t, double tnew, double *tstop)
{
  const int ne = r->ne, ns = r->ns;
  const double same = SYM_EVENT_SAME_ULPS * DBL_EPSILON
                      * fmax (fabs (t), fabs (tnew))
                      + SYM_EVENT_SAME_STEP * DBL_EPSILON * fabs (tnew - t);
  const double dt = (tnew - t) / (ns + 1);
  int st;
  /* points 0..ns + 1: t, the samples, tnew; their event values */
#define PT(i) ((i) == ns + 1 ? tnew \
               : t + (tnew - t) * ((double) (i) / (ns + 1)))
#define VAL(i) ((i) == 0 ? r->vold : (i) == ns + 1 ? r->vnew \
                : r->vs + (size_t) ((i) - 1) * ne)
  for (int i = 1; i <= ns; i++)
    if ((st = events_at (r, PT (i), VAL (i))))
      return st;
  for (int j = 0; j <= ns; j++)
    {
      double ta = PT (j), tb = PT (j + 1);
      /* after a terminal event, only the events at its time (one on a
         sample point, another located an ulp after it) */
      if (! isnan (*tstop) && ! (fabs (ta - *tstop) <= same))
        break;
      const double t0 = ta;
      const double *va = VAL (j), *vb = VAL (j + 1);
      /* vertices of a predicted zero pair in (ta, tb), as fractions of
         the piece, in order */
      int nc = 0;
      for (int k = 0; k < ne && ns > 0; k++)
        {
          if (! (va[k] != 0 && vb[k] != 0 && (va[k] > 0) == (vb[k] > 0)))
            continue;
          double u = NAN;
          if (j >= 1)          /* centred on point j: u in (0, 1) */
            u = vertex_pair (VAL (j - 1)[k], va[k], vb[k], 0, 1);
          if (isnan (u) && j + 2 <= ns + 1)   /* on j + 1: (-1, 0) */
            {
              u = vertex_pair (va[k], vb[k], VAL (j + 2)[k], -1, 0);
              u += 1;
            }
          if (isnan (u))
            continue;
          int c = nc++;
          while (c > 0 && r->tcand[c - 1] > u)
            {
              r->tcand[c] = r->tcand[c - 1];
              c--;
            }
          r->tcand[c] = u;
        }
      for (int c = 0; c < nc && isnan (*tstop); c++)
        {
          double tc = t0 + dt * r->tcand[c];
          if (! (r->dir * (tc - ta) > 0 && r->dir * (tb - tc) > 0))
            continue;
          double *vc = va == r->vca ? r->vcb : r->vca;
          st = events_at (r, tc, vc);
          if (! st)
            st = events_between (r, ta, va, tc, vc, same, tstop);
          if (st)
            return st;
          ta = tc;
          va = vc;
        }
      if ((isnan (*tstop) || fabs (ta - *tstop) <= same)
          && (st = events_between (r, ta, va, tb, vb, same, tstop)))
        return st;
    }
#undef VAL
#undef PT
  return SYM_SUCCESS;
}

