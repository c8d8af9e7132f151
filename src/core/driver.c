/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* driver.c -- the integration loop.  It owns nothing method-specific:
   it takes steps through a stepper table (fixed or adaptive h), accepts or
   rejects them, hands rows to the output sink (step points, refined points
   or requested output times, all from the stepper's own dense output), and
   locates events on that dense output. */
#include "sym.h"
#include "control.h"

#include <float.h>
#include <math.h>
#include <string.h>

typedef struct {
  const sym_stepper_type *type;
  void *state;
  sym_system *sys;
  const sym_driver_opts *o;
  int n;
  double dir;
  /* events */
  double *vold, *vnew, *vtry;
  double *vs;           /* event values at the samples inside a step */
  double *vca, *vcb;    /* and at the vertices between them */
  double *tcand;        /* the vertices' places */
  int *term, *edir;
  double *ydense;
  /* events found in one step, sorted by time (nevents each) */
  double *tfound;
  int *kfound;
  /* next requested output time index (ntout > 2) */
  int iout;
} run_t;

static int
emit (run_t *r, double t, const double *y)
{
  int st = r->o->output ? r->o->output (t, y, r->o->output_user) : 0;
  if (st < 0)
    return SYM_EOUTPUT;
  return st > 0 ? SYM_STOP_OUTPUT : SYM_SUCCESS;
}

static int
call_events (run_t *r, double t, const double *y, double *v)
{
  int st = r->o->events (t, y, v, r->term, r->edir, r->o->event_user);
  if (st)
    {
      r->sys->fail_t = t;
      r->sys->fail_status = st;
      return st > 0 ? SYM_RECOVERABLE : SYM_ECALLBACK;
    }
  return SYM_SUCCESS;
}

/* The event values v at t inside the accepted step (its dense output) */
static int
events_at (run_t *r, double t, double *v)
{
  int st = r->type->dense (r->state, r->sys, t, r->ydense);
  return st ? st : call_events (r, t, r->ydense, v);
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
locate (run_t *r, int k, double ta, double ga, double tb, double gb,
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
  for (int it = 0; it < 200; it++)
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
events_between (run_t *r, double ta, const double *va, double tb,
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
      int st = r->type->dense (r->state, r->sys, tfound[j], r->ydense);
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
      || ! (fabs (g) > 64 * DBL_EPSILON * big))
    return NAN;
  return u;
}

/* The events of the accepted step (t, tnew]: the event values at its
   ends, and at ns = o->event_samples equally spaced points inside it on
   the dense output, so that a zero pair inside the step (the function
   back to its sign at the end) is seen when a sample falls between its
   zeros.  A pair between two samples is still found where the parabola
   through three neighbouring samples of the function has its extremum
   between them on the other side of zero: the function is evaluated
   there too (q = sin t above 0.99 for 0.28 of its period, samples 0.4
   apart: found).  The pieces in time order until a terminal event.
   Events at one time: within 32 ulps of t and 64 eps of the step. */
static int
handle_events (run_t *r, double t, double tnew, double *tstop)
{
  const int ne = r->o->nevents;
  const int ns = r->o->event_samples > 0 ? r->o->event_samples : 0;
  const double same = 32 * DBL_EPSILON * fmax (fabs (t), fabs (tnew))
                      + 64 * DBL_EPSILON * fabs (tnew - t);
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

/* Rows for the accepted step (t, tnew] up to tstop (a terminal event time,
   or NAN). */
static int
output_step (run_t *r, double t, double h, double tnew, const double *ynew,
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
            st = emit (r, to, ynew);
          else
            {
              st = r->type->dense (r->state, r->sys, to, r->ydense);
              if (st)
                return st;
              st = emit (r, to, r->ydense);
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
          st = r->type->dense (r->state, r->sys, ti, r->ydense);
          if (st)
            return st;
          if ((st = emit (r, ti, r->ydense)))
            return st;
        }
      if (! stopped && (st = emit (r, tnew, ynew)))
        return st;
    }
  if (stopped)
    {
      /* the event row ends the output, as in ode45 */
      st = r->type->dense (r->state, r->sys, tstop, r->ydense);
      if (st)
        return st;
      if (o->ntout > 2 && r->iout > 0 && o->tout[r->iout - 1] == tstop)
        return SYM_SUCCESS;   /* already there */
      return emit (r, tstop, r->ydense);
    }
  return SYM_SUCCESS;
}

/* The least step size at t: 16 ulps of t (at least the least normal
   number), so that t + h moves by more than the round-off of t. */
static double
hmin_at (double t)
{
  return fmax (16 * DBL_EPSILON * fabs (t), DBL_MIN);
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
  const double tol = 16 * DBL_EPSILON * fmax (fabs (o->t0), len);
  double best = fabs (o->tf - tend), snap = o->tf;
  for (int i = 1; o->ntout > 2 && o->tout && i < o->ntout; i++)
    if (fabs (o->tout[i] - tend) < best)
      {
        best = fabs (o->tout[i] - tend);
        snap = o->tout[i];
      }
  return best <= tol ? snap : tend;
}

/* Map a recoverable cause that can no longer be cured to a fatal status.
   small_step: the step that failed was the least one (adaptive runs); a
   callback's request for a smaller step is otherwise (fixed steps, the
   first call at t0) a callback failure. */
static int
fatal_from (int cause, int small_step)
{
  switch (cause)
    {
    case SYM_NONFINITE: return SYM_ENONFINITE;
    case SYM_NEWTON_FAIL:
    case SYM_SINGULAR: return SYM_ENEWTON;
    default: return small_step ? SYM_ESTEPSIZE : SYM_ECALLBACK;
    }
}

int
sym_integrate (const sym_stepper_type *type, sym_system *sys,
               const sym_method_opts *mopts, const sym_driver_opts *o,
               const double *y0, double *t_reached)
{
  const int n = 2 * sys->dim;
  run_t r;
  memset (&r, 0, sizeof (r));
  r.type = type;
  r.sys = sys;
  r.o = o;
  r.n = n;
  if (t_reached)
    *t_reached = o->t0;
  if (sys->dim < 1 || ! sys->rhs || ! (o->tf != o->t0)
      || ! isfinite (o->t0) || ! isfinite (o->tf))
    return SYM_EBADINPUT;
  r.dir = o->tf > o->t0 ? 1.0 : -1.0;
  const int fixed = o->h_fixed > 0 || o->nsteps_fixed > 0;
  /* a fixed step of more steps than a long counts (and than doubles
     count exactly) */
  if (o->nsteps_fixed <= 0 && o->h_fixed > 0
      && ! (fabs (o->tf - o->t0) / o->h_fixed <= SYM_MAX_FIXED_STEPS))
    return SYM_EBADINPUT;
  if (! fixed && (! (o->rtol > 0) || ! o->atol
                  || (o->atol_len != 1 && o->atol_len != n)))
    return SYM_EBADINPUT;
  for (int i = 0; ! fixed && i < o->atol_len; i++)
    if (! (o->atol[i] > 0) || ! isfinite (o->atol[i]))
      return SYM_EBADINPUT;
  if (o->ntout > 2 && (! o->tout || o->tout[0] != o->t0))
    return SYM_EBADINPUT;

  sym_method_opts mo = *mopts;
  mo.want_error = ! fixed;
  mo.est_rtol = fixed ? 0.0 : o->rtol;
  mo.est_atol = 0.0;
  for (int i = 0; ! fixed && i < o->atol_len; i++)
    mo.est_atol = i ? fmin (mo.est_atol, o->atol[i]) : o->atol[0];
  mo.want_dense = mopts->want_dense || o->ntout > 2 || o->refine > 1
                  || o->nevents > 0;
  int st = SYM_SUCCESS;
  r.state = type->alloc (sys, &mo, &st);
  if (! r.state)
    return st ? st : SYM_ENOMEM;

  int ne = o->nevents > 0 ? o->nevents : 0;
  const int ns = o->event_samples > 0 ? o->event_samples : 0;
  double *work = sym_calloc ((size_t) 7 * n + (7 + (size_t) ns) * ne + 1,
                             sizeof (double));
  int *iwork = sym_calloc ((size_t) 3 * ne + 1, sizeof (int));
  if (! work || ! iwork)
    {
      sym_free (work);
      sym_free (iwork);
      type->free (r.state);
      return SYM_ENOMEM;
    }
  double *y = work, *ynew = work + n, *yerr = work + 2 * n;
  double *ftmp = work + 3 * n;    /* 2n: initial step work */
  r.ydense = work + 5 * n;
  double *ytyp = work + 6 * n;
  r.vold = work + 7 * n;
  r.vnew = r.vold + ne;
  r.vtry = r.vnew + ne;
  r.tfound = r.vtry + ne;
  r.vca = r.tfound + ne;
  r.vcb = r.vca + ne;
  r.tcand = r.vcb + ne;
  r.vs = r.tcand + ne;
  r.term = iwork;
  r.edir = iwork + ne;
  r.kfound = iwork + 2 * ne;
  memcpy (y, y0, (size_t) n * sizeof (double));
  /* the sizes of y's components for the finite differences (sym.h): the
     largest |y_i| of the run's accepted states */
  const double *ytyp_caller = sys->ytyp;
  for (int i = 0; i < n; i++)
    ytyp[i] = fabs (y[i]);
  sys->ytyp = ytyp;
  sys->jac_probed = 0;
  sys->sep_broken = 0;

  double t = o->t0;
  int result = SYM_DONE;

  /* first row and first event values */
  if (o->ntout > 2)
    r.iout = 1;
  st = emit (&r, t, y);
  if (st)
    {
      result = st;
      goto done;
    }
  if (ne && o->events)
    {
      st = call_events (&r, t, y, r.vold);
      if (st)
        {
          result = st < 0 ? st : SYM_ECALLBACK;
          goto done;
        }
    }

  /* the end of the run */
  double tend = o->tf;
  long nfixed = 0;
  double hfix = 0;
  if (fixed)
    {
      if (o->nsteps_fixed > 0)
        {
          nfixed = o->nsteps_fixed;
          hfix = o->h_fixed > 0 ? o->h_fixed : fabs (o->tf - o->t0) / nfixed;
          tend = sym_fixed_end (o);
        }
      else
        {
          hfix = o->h_fixed;
          double ratio = fabs (o->tf - o->t0) / hfix;
          nfixed = (long) ceil (ratio - 1e-9 * fmax (1.0, ratio));
          if (nfixed < 1)
            nfixed = 1;
        }
    }

  /* as in ode45: MaxStep = Inf lifts the default cap */
  const int user_hmax = o->hmax > 0;
  double hmax = user_hmax ? o->hmax : 0.1 * fabs (o->tf - o->t0);
  double h = 0;
  int q = type->err_order ? type->err_order (r.state) : type->order;
  if (! fixed)
    {
      if (o->h0 > 0)
        h = fmin (o->h0, hmax);
      else
        {
          double *f0 = ynew;
          st = sym_rhs (sys, t, y, f0);
          if (st)
            {
              result = st < 0 ? st : fatal_from (st, 0);
              goto done;
            }
          st = sym_initial_step (sys, t, y, f0, r.dir, q, o->rtol, o->atol,
                                 o->atol_len, hmax, ftmp, &h);
          if (st)
            {
              result = st;
              goto done;
            }
        }
      h = fmin (h, fabs (tend - t));
    }

  long k = 0;                /* fixed: steps taken */
  int last_rejected = 0;
  long jac_checked_at = -1;   /* nsteps at the last sym_jac_check */
  int jac_agreed = 0;         /* its checks that found Df right */
  double h_acc = 0, err_acc = 0;   /* the last accepted step (predictive
                                      control, control.c) */
  double tcomp = 0;   /* adaptive: the steps' sum minus t (round-off) */
  for (;;)
    {
      double hs, tnew;
      int last = 0;
      if (fixed)
        {
          if (k >= nfixed)
            break;
          if (k == nfixed - 1)
            {
              tnew = tend;
              last = 1;
            }
          else
            tnew = o->t0 + r.dir * hfix * (double) (k + 1);
          /* each step takes h itself and ends at t0 + k h rounded once;
             the last ends at tend and takes what is left when h does not
             divide the span (beyond the round-off of t).  The difference
             of those ends varies by the round-off of t (up to 1.5e-6 h at
             t = 1e8, h = 0.01): taken as the step, it made each step a
             slightly different map, and the Newton starts of odeSE and
             odeSV from the last steps (steprec.h) worse far from t = 0:
             odeSE at h = 0.01 took 2.28 and 3.00 calls per step from
             t0 = 1e4 and 1e8 against 2.00 near 0 (tests/test_se_sv.m) */
          hs = r.dir * hfix;
          if (last && fabs (tnew - t - hs)
                      > 16 * DBL_EPSILON * fmax (fabs (t), fabs (tnew)))
            hs = tnew - t;
        }
      else
        {
          if (r.dir * (t - tend) >= 0)
            break;
          double rem = fabs (tend - t);
          /* the least step: below it the round-off of t itself swamps the
             step.  A smaller h from the default MaxStep (span/10), the
             initial step or the controller is raised to it, and only a
             step that fails there ends the run (below); a MaxStep the user
             set below it ends the run here. */
          const double hmin = hmin_at (t);
          h = fmax (h, user_hmax ? fmin (hmin, hmax) : hmin);
          /* what would be left after this step joins it when it is
             below the least step, or round-off of the span */
          if (h >= rem || rem - h <= fmax (1e-10 * rem, hmin_at (tend)))
            {
              h = rem;
              last = 1;
            }
          if (h < hmin && ! last)
            {
              result = SYM_ESTEPSIZE;
              goto done;
            }
          /* the step is the representable increment of t: where h is a
             few ulps of t, t + h rounds by up to half an ulp, which the
             state would otherwise not follow.  t is summed with the
             rounding of the earlier steps carried along (tcomp, as
             Octave's integrators sum t), so that steps of MaxStep where it
             divides the span end on tend instead of leaving a sliver of
             the accumulated round-off (9.4e-14 after 1e4 steps of 1e-4
             from 0) for a step of its own */
          tnew = last ? tend : t + (r.dir * h + tcomp);
          hs = tnew - t;
        }
      if (o->max_steps > 0 && sys->cnt.nsteps >= o->max_steps)
        {
          result = SYM_EMAXSTEPS;
          goto done;
        }

      st = type->step (r.state, sys, t, hs, tnew, y, ynew,
                       fixed ? NULL : yerr);
      /* Newton failed with the user's Df: if it disagrees with finite
         differences of f (a Hessian without a forcing term's dF/dy, a
         wrong Jacobian), finite differences serve from here on, with a
         new stepper (its matrices came from the user's Df), and the step
         is tried again.  Checked at most once per accepted step, and no
         more after SYM_JAC_CHECKS checks that agreed (each costs a Df
         and 2d + 1 calls of f; adaptive runs fail Newton now and then
         with a right Df too: one check, 6 calls, in 10 Kepler periods at
         RelTol 1e-4, tests/c/test_spvi.c).  The same when the user's Df
         had a NaN or Inf (f finite), which no smaller step cures. */
      if ((st == SYM_NEWTON_FAIL || (st == SYM_NONFINITE && sys->fail_df))
          && (sys->jac || sys->rhs_jac)
          && jac_checked_at != sys->cnt.nsteps && jac_agreed < SYM_JAC_CHECKS)
        {
          int dropped = 0, st_step = st;
          jac_checked_at = sys->cnt.nsteps;
          st = sym_jac_check (sys, t, y, &dropped);
          /* a NaN or a smaller step asked for by the check's calls: the
             step's own failure stands */
          if (st > 0)
            st = st_step;
          else if (! st && dropped)
            {
              type->free (r.state);
              r.state = type->alloc (sys, &mo, &st);
              if (! r.state)
                {
                  result = st ? st : SYM_ENOMEM;
                  goto done;
                }
              continue;
            }
          else if (! st)
            {
              jac_agreed++;
              st = st_step;
            }
        }
      if (st < 0)
        {
          result = st;
          goto done;
        }
      /* A result beyond the doubles (f was finite wherever the step took
         it, but h f or the sum overflowed: an unstable fixed step grows
         the solution until it does) is not accepted: a fixed step ends the
         run before it, an adaptive one is retried shorter. */
      int overflow = 0;
      for (int i = 0; st == 0 && i < n; i++)
        if (! isfinite (ynew[i]))
          overflow = 1;
      double err = 0;
      if (st == 0 && ! overflow && ! fixed)
        err = sym_error_norm (n, yerr, y, ynew, o->rtol, o->atol,
                              o->atol_len, o->norm_control);
      if (st > 0 || overflow || (! fixed && ! (err <= 1.0)))
        {
          sys->cnt.nfailed++;
          if (fixed)
            {
              result = overflow ? SYM_EOVERFLOW
                       : fatal_from (st > 0 ? st : SYM_NONFINITE, 0);
              goto done;
            }
          double fac = st > 0 || overflow ? 0.5
                       : sym_step_factor (err, q, 0.2, 1.0);
          if (st == 0 && last_rejected)
            fac = fmin (fac, 0.5);
          last_rejected = 1;
          /* failed at the least step: nothing smaller can be tried */
          if (h <= hmin_at (t))
            {
              result = st > 0 ? fatal_from (st, 1)
                       : overflow ? SYM_EOVERFLOW : SYM_ESTEPSIZE;
              goto done;
            }
          h *= fac;
          continue;
        }

      /* accepted */
      type->accept (r.state);
      sys->cnt.nsteps++;
      k++;

      double tstop = NAN;
      if (ne && o->events)
        {
          st = call_events (&r, tnew, ynew, r.vnew);
          if (! st)
            st = handle_events (&r, t, tnew, &tstop);
          if (st)
            {
              result = st < 0 ? st : SYM_ECALLBACK;
              goto done;
            }
        }
      st = output_step (&r, t, hs, tnew, ynew, tstop);
      if (st)
        {
          t = isnan (tstop) ? tnew : tstop;
          result = st;
          goto done;
        }
      if (! isnan (tstop))
        {
          t = tstop;
          result = SYM_STOP_EVENT;
          goto done;
        }
      if (! fixed)
        {
          /* the rounding of tnew = t + (dir h + tcomp), exactly (TwoSum) */
          const double a = r.dir * h + tcomp, bv = tnew - t;
          tcomp = last ? 0.0 : (t - (tnew - bv)) + (a - bv);
        }
      t = tnew;
      memcpy (y, ynew, (size_t) n * sizeof (double));
      for (int i = 0; i < n; i++)
        ytyp[i] = fmax (ytyp[i], fabs (y[i]));
      if (ne)
        memcpy (r.vold, r.vnew, (size_t) ne * sizeof (double));
      if (! fixed)
        {
          double fac = sym_step_factor (err, q, 0.2, last_rejected ? 1.0 : 5.0);
          fac = sym_step_factor_pred (fac, err, q, hs, h_acc, err_acc, 0.2);
          h_acc = fabs (hs);
          err_acc = fmax (err, 1e-2);
          h = fmin (h * fac, hmax);
          last_rejected = 0;
        }
      (void) last;
    }

done:
  sys->ytyp = ytyp_caller;
  if (t_reached)
    *t_reached = t;
  sym_free (iwork);
  sym_free (work);
  if (r.state)
    type->free (r.state);
  return result;
}
