/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* loop.c -- the integration loop.  It owns nothing method-specific: it
   schedules steps (fixed or adaptive h), attempts them through a stepper
   table, rejects or commits them (events, rows, the next h), and reports
   what the run found out. */
#include "driver.h"

#include <float.h>
#include <math.h>
#include <string.h>

/* what advance and commit return to go on (not a status of sym.h) */
#define RUN_ON 1000

/* The least step size at t: SYM_HMIN_ULPS ulps of t, so that t + h moves
   by more than the round-off of t, and SYM_HMIN_SPAN ulps of the span, so
   that a run creeping towards a singularity (steps shrinking with the
   distance to it) stops; at least the least double. */
static double
hmin_at (const sym_run *r, double t)
{
  const double span = fabs (r->o->tf - r->o->t0);
  return fmax (fmax (SYM_HMIN_ULPS * DBL_EPSILON * fabs (t),
                     SYM_HMIN_SPAN * DBL_EPSILON * span),
               nextafter (0.0, 1.0));
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

static int
check_input (const sym_system *sys, const sym_driver_opts *o, int fixed)
{
  const int n = 2 * sys->dim;
  const sym_tolerances *tol = &o->tol;
  if (sys->dim < 1 || ! sys->rhs || ! (o->tf != o->t0)
      || ! isfinite (o->t0) || ! isfinite (o->tf))
    return SYM_EBADINPUT;
  /* more fixed steps than a run may take */
  if (o->nsteps_fixed <= 0 && o->h_fixed > 0
      && ! (fabs (o->tf - o->t0) / o->h_fixed <= SYM_MAX_STEPS))
    return SYM_EBADINPUT;
  if (! fixed && (! (tol->rtol > 0) || ! tol->atol
                  || (tol->atol_len != 1 && tol->atol_len != n)))
    return SYM_EBADINPUT;
  for (int i = 0; ! fixed && i < tol->atol_len; i++)
    if (! (tol->atol[i] > 0) || ! isfinite (tol->atol[i]))
      return SYM_EBADINPUT;
  if (o->ntout > 2 && (! o->tout || o->tout[0] != o->t0))
    return SYM_EBADINPUT;
  /* going on from step k0 of a grid: t0 must be its point, as the
     schedule rounds it, for the steps to fall on the same grid */
  if (o->k0 > 0
      && (! fixed || o->nsteps_fixed > 0 || ! (o->h_fixed > 0)
          || o->t0 != o->grid_t0 + (o->tf > o->t0 ? 1.0 : -1.0)
                      * o->h_fixed * (double) o->k0))
    return SYM_EBADINPUT;
  return SYM_SUCCESS;
}

/* A new stepper state for the run (at its start, and after the user's Df
   was dropped: its matrices came from that Df) */
static int
new_stepper (sym_run *r)
{
  int st = SYM_SUCCESS;
  if (r->state)
    r->type->free (r->state);
  r->state = r->type->alloc (r->ev.dim, &r->mo, &st);
  if (! r->state)
    return st ? st : SYM_ENOMEM;
  if (! r->fixed && ! r->reversible
      && (st = r->type->set_tolerances (r->state, &r->o->tol)))
    return st;
  r->type->order (r->state, &r->q);
  return SYM_SUCCESS;
}

/* The run's arrays and stepper */
static int
run_alloc (sym_run *r)
{
  const int n = r->n, ne = r->ne;
  int st = new_stepper (r);
  if (st)
    return st;
  r->ns = r->ne && r->type->dense_samples
          ? r->type->dense_samples (r->state) : 0;
  r->nd = r->o->dense_out ? r->type->dense_degree (r->state) - 1 : 0;
  if (r->nd < 0)
    r->nd = 0;
  const int ns = r->ns;
  double *w = sym_calloc ((size_t) (10 + r->nd) * n
                          + (7 + (size_t) ns) * ne + 1, sizeof (double));
  int *iw = sym_calloc ((size_t) 3 * ne + 1, sizeof (int));
  r->y = w;
  r->term = iw;
  if (! w || ! iw)
    return SYM_ENOMEM;
  r->ynew = w + n;
  r->yerr = w + 2 * n;       /* and 2n after it: the initial step's work */
  r->ydense = w + 5 * n;
  r->ytyp = w + 6 * n;
  r->vold = w + 7 * n;
  r->vnew = r->vold + ne;
  r->vtry = r->vnew + ne;
  r->tfound = r->vtry + ne;
  r->vca = r->tfound + ne;
  r->vcb = r->vca + ne;
  r->tcand = r->vcb + ne;
  r->vs = r->tcand + ne;
  r->yd = r->vs + (size_t) ns * ne;     /* n (nd + 2) */
  r->fn = r->yd + (size_t) (r->nd + 2) * n;
  r->edir = iw + ne;
  r->kfound = iw + 2 * ne;
  return SYM_SUCCESS;
}

static void
run_free (sym_run *r)
{
  sym_free (r->term);
  sym_free (r->y);
  if (r->state)
    r->type->free (r->state);
  sym_eval_free (&r->ev);
}

/* The first row and event values; the schedule of fixed steps, or the
   first adaptive step */
static int
run_start (sym_run *r)
{
  const sym_driver_opts *o = r->o;
  int st;
  if (o->ntout > 2)
    r->iout = 1;
  if ((st = sym_emit (r, r->t, r->y)))
    return st;
  if (r->ne && o->events && (st = sym_run_events (r, r->t, r->y, r->vold)))
    return st < 0 ? st : SYM_ECALLBACK;
  r->tend = o->tf;
  r->tgrid = o->t0;
  if (r->fixed)
    {
      if (o->k0 > 0)
        {
          /* the steps and their number as for a run from the grid's origin */
          sym_driver_opts g = *o;
          g.t0 = o->grid_t0;
          r->tgrid = o->grid_t0;
          r->hfix = o->h_fixed;
          r->nfixed = sym_fixed_steps (&g);
          r->k = o->k0;
        }
      else if (o->nsteps_fixed > 0)
        {
          r->nfixed = o->nsteps_fixed;
          r->hfix = o->h_fixed > 0 ? o->h_fixed
                    : fabs (o->tf - o->t0) / r->nfixed;
          r->tend = sym_fixed_end (o);
        }
      else
        {
          r->hfix = o->h_fixed;
          r->nfixed = sym_fixed_steps (o);
        }
      return SYM_SUCCESS;
    }
  if (r->reversible)
    return sym_rev_start (r);
  /* as in ode45: MaxStep = Inf lifts the default cap */
  r->user_hmax = o->hmax > 0;
  r->hmax = r->user_hmax ? o->hmax : 0.1 * fabs (o->tf - o->t0);
  if (o->h0 > 0)
    r->h = fmin (o->h0, r->hmax);
  else
    {
      double *f0 = r->ynew;
      if ((st = sym_rhs (&r->ev, r->t, r->y, f0)))
        return st < 0 ? st : fatal_from (st, 0);
      if ((st = sym_initial_step (&r->ev, r->t, r->y, f0, r->dir, r->q,
                                  &o->tol, r->hmax, r->yerr, &r->h)))
        return st;
    }
  r->h = fmin (r->h, fabs (r->tend - r->t));
  return SYM_SUCCESS;
}

/* The next step: its size *hs and end *tnew, *last if it ends the run.
   Returns 1 when the run is over, or a fatal status. */
static int
schedule (sym_run *r, double *hs, double *tnew, int *last)
{
  const double t = r->t;
  *last = 0;
  if (r->fixed)
    {
      if (r->k >= r->nfixed)
        return 1;
      *last = r->k == r->nfixed - 1;
      *tnew = *last ? r->tend : r->tgrid + r->dir * r->hfix * (double) (r->k + 1);
      /* each step is h itself, ending at t0 + k h rounded once, so that
         every step is the same map at any t; the last takes what is left
         when h does not fit the span beyond the round-off of t */
      *hs = r->dir * r->hfix;
      if (*last && fabs (*tnew - t - *hs)
                   > SYM_HMIN_ULPS * DBL_EPSILON * fmax (fabs (t), fabs (*tnew)))
        *hs = *tnew - t;
    }
  else
    {
      if (r->dir * (t - r->tend) >= 0)
        return 1;
      const double rem = fabs (r->tend - t), hmin = hmin_at (r, t);
      /* below the least step the round-off of t swamps the step: a
         smaller h is raised to it, a MaxStep the user set below it ends
         the run; a reversible step is what its density says */
      if (r->reversible)
        r->h = sym_rev_step (r);
      else
        r->h = fmax (r->h, r->user_hmax ? fmin (hmin, r->hmax) : hmin);
      /* a remainder below the least step, or round-off of the span, joins
         this step */
      if (r->h >= rem
          || rem - r->h <= fmax (SYM_SPAN_SLIVER * rem, hmin_at (r, r->tend))
          || (r->reversible && rem - r->h <= SYM_REV_JOIN * r->h))
        {
          r->h = rem;
          *last = 1;
        }
      if (r->h < hmin && ! *last)
        return SYM_ESTEPSIZE;
      /* the step is the representable increment of t; t is summed with
         the rounding of the earlier steps carried along (tcomp), so that
         steps of a MaxStep that divides the span end on tend */
      *tnew = *last ? r->tend : t + (r->dir * r->h + r->tcomp);
      *hs = *tnew - t;
    }
  if (r->o->max_steps > 0 && r->ev.st.cnt.nsteps >= r->o->max_steps)
    return SYM_EMAXSTEPS;
  return SYM_SUCCESS;
}

/* After a Newton failure with the user's Df (or a NaN in it): if Df
   disagrees with finite differences of f, those serve from here on, with
   a new stepper, and the step is tried again (*again).  Checked at most
   once per accepted step and no more after SYM_JAC_CHECKS checks that
   agreed. */
static int
check_jacobian (sym_run *r, int st, int *again)
{
  sym_eval *ev = &r->ev;
  *again = 0;
  if (! (st == SYM_NEWTON_FAIL || (st == SYM_NONFINITE && ev->st.fail_df))
      || ! (ev->jac || ev->rhs_jac || ev->jac_csc || ev->rhs_jac_csc)
      || r->jac_checked_at == ev->st.cnt.nsteps
      || r->jac_agreed >= SYM_JAC_CHECKS)
    return st;
  int dropped = 0;
  r->jac_checked_at = ev->st.cnt.nsteps;
  int stc = sym_jac_check (ev, r->t, r->y, &dropped);
  /* a NaN or a smaller step asked for by the check's calls: the step's
     own failure stands */
  if (stc > 0)
    return st;
  if (stc < 0)
    return stc;
  if (dropped)
    {
      *again = 1;
      return new_stepper (r);
    }
  r->jac_agreed++;
  return st;
}

/* A rejected step of size hs (status st > 0, or an overflow, or err > 1):
   a fatal status, or SYM_SUCCESS with h shrunk */
static int
reject (sym_run *r, double hs, int st, int overflow, double err)
{
  r->ev.st.cnt.nfailed++;
  if (r->fixed || r->reversible)
    return overflow ? SYM_EOVERFLOW
           : fatal_from (st > 0 ? st : SYM_NONFINITE, 0);
  double fac = st > 0 || overflow ? SYM_CTRL_FACFAIL
               : sym_step_factor (err, r->q, SYM_CTRL_FACMIN, 1.0);
  if (st == 0 && r->last_rejected)
    fac = fmin (fac, SYM_CTRL_FACFAIL);
  /* failed at the least step, or nothing shorter was tried than at the
     last rejection (a remainder of the span below the least step joins
     the step): nothing smaller can be tried.  Each rejection after the
     first at least halves h, so a run fails at most about 52 steps in a
     row (log2 of the span over the least step) before it stops */
  const int stuck = r->last_rejected && ! (fabs (hs) < r->h_rejected);
  r->last_rejected = 1;
  r->h_rejected = fabs (hs);
  if (r->h <= hmin_at (r, r->t) || stuck)
    return st > 0 ? fatal_from (st, 1)
           : overflow ? SYM_EOVERFLOW : SYM_ESTEPSIZE;
  r->h *= fac;
  return SYM_SUCCESS;
}

/* An accepted step (hs, tnew) of error norm err: events, rows, the new
   point and the next h.  RUN_ON to go on, else how the run ends. */
static int
commit (sym_run *r, double hs, double tnew, int last, double err)
{
  const int n = r->n;
  r->type->accept (r->state);
  r->ev.st.cnt.nsteps++;
  r->k++;
  double tstop = NAN;
  int st = sym_output_dense (r, r->t, tnew);
  if (st)
    return st;
  if (r->ne && r->o->events)
    {
      st = sym_run_events (r, tnew, r->ynew, r->vnew);
      if (! st)
        st = sym_handle_events (r, r->t, tnew, &tstop);
      if (st)
        return st < 0 ? st : SYM_ECALLBACK;
    }
  if ((st = sym_output_step (r, r->t, hs, tnew, r->ynew, tstop)))
    {
      r->t = isnan (tstop) ? tnew : tstop;
      return st;
    }
  if (! isnan (tstop))
    {
      r->t = tstop;
      return SYM_STOP_EVENT;
    }
  if (! r->fixed)
    {
      /* the rounding of tnew = t + (dir h + tcomp), exactly (TwoSum) */
      const double a = r->dir * r->h + r->tcomp, bv = tnew - r->t;
      r->tcomp = last ? 0.0 : (r->t - (tnew - bv)) + (a - bv);
    }
  r->t = tnew;
  memcpy (r->y, r->ynew, (size_t) n * sizeof (double));
  for (int i = 0; i < n; i++)
    r->ytyp[i] = fmax (r->ytyp[i], fabs (r->y[i]));
  if (r->ne)
    memcpy (r->vold, r->vnew, (size_t) r->ne * sizeof (double));
  if (r->reversible)
    return last ? RUN_ON : (st = sym_rev_next (r)) ? st : RUN_ON;
  if (! r->fixed)
    {
      double fac = sym_step_factor (err, r->q, SYM_CTRL_FACMIN,
                                    r->last_rejected ? 1.0 : SYM_CTRL_FACMAX);
      fac = sym_step_factor_pred (fac, err, r->q, hs, r->h_acc, r->err_acc,
                                  SYM_CTRL_FACMIN);
      r->h_acc = fabs (hs);
      r->err_acc = fmax (err, SYM_CTRL_ERR_FLOOR);
      r->h = fmin (r->h * fac, r->hmax);
      r->last_rejected = 0;
    }
  return RUN_ON;
}

/* Attempt steps from the current point until one is accepted and
   committed: RUN_ON to go on, else how the run ends */
static int
advance (sym_run *r)
{
  const int n = r->n;
  for (;;)
    {
      double hs, tnew, err = 0;
      int last, again, st = schedule (r, &hs, &tnew, &last);
      if (st)
        return st > 0 ? SYM_DONE : st;
      const int control = ! r->fixed && ! r->reversible;
      st = r->type->step (r->state, &r->ev, r->t, hs, tnew, r->y, r->ynew,
                          control ? r->yerr : NULL);
      if ((st = check_jacobian (r, st, &again)) < 0)
        return st;
      if (again)
        continue;
      /* a result beyond the doubles (h f or the sum overflowed, f finite:
         an unstable fixed step grows the solution until it does) is not
         accepted */
      int overflow = 0;
      for (int i = 0; st == 0 && i < n; i++)
        if (! isfinite (r->ynew[i]))
          overflow = 1;
      if (st == 0 && ! overflow && control)
        err = sym_error_norm (n, r->yerr, r->y, r->ynew, &r->o->tol);
      if (st > 0 || overflow || (control && ! (err <= 1.0)))
        {
          if ((st = reject (r, hs, st, overflow, err)))
            return st;
          continue;
        }
      return commit (r, hs, tnew, last, err);
    }
}

int
sym_integrate (const sym_stepper_type *type, const sym_system *sys,
               const sym_method_opts *mopts, const sym_driver_opts *o,
               const double *y0, sym_stats *stats)
{
  sym_run r;
  memset (&r, 0, sizeof (r));
  r.fixed = o->h_fixed > 0 || o->nsteps_fixed > 0;
  r.reversible = ! r.fixed && o->step_control == SYM_CONTROL_REVERSIBLE;
  int result = check_input (sys, o, r.fixed);
  if (result)
    {
      if (stats)
        {
          memset (stats, 0, sizeof (*stats));
          stats->t_reached = o->t0;
        }
      return result;
    }
  r.type = type;
  r.o = o;
  r.n = 2 * sys->dim;
  r.dir = o->tf > o->t0 ? 1.0 : -1.0;
  r.ne = o->nevents > 0 ? o->nevents : 0;
  r.t = o->t0;
  r.jac_checked_at = -1;
  if (mopts)
    r.mo = *mopts;
  r.mo.want_dense = r.mo.want_dense || o->ntout > 2 || o->refine > 1
                    || o->nevents > 0 || o->dense_out;
  r.mo.reversible = r.reversible;
  sym_eval_init (&r.ev, sys);
  if (! (result = run_alloc (&r)))
    {
      /* the sizes of y's components for the finite differences: the
         largest |y_i| of the run's accepted states */
      memcpy (r.y, y0, (size_t) r.n * sizeof (double));
      for (int i = 0; i < r.n; i++)
        r.ytyp[i] = fabs (r.y[i]);
      r.ev.ytyp = r.ytyp;
      result = run_start (&r);
    }
  if (! result)
    do
      result = advance (&r);
    while (result == RUN_ON);
  if (stats)
    {
      *stats = r.ev.st;
      stats->t_reached = r.t;
      stats->restart_h = r.fixed ? r.hfix : 0;
      stats->restart_t0 = r.tgrid;
      stats->restart_k = r.k;
      stats->restart_rho[0] = r.reversible ? r.rho_prev : 0;
      stats->restart_rho[1] = r.reversible ? r.rho_half : 0;
      if (r.state)
        stats->order = type->order (r.state, NULL);
    }
  run_free (&r);
  return result;
}
