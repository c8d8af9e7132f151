/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* reversible.c -- time-reversible step-size control.  The steps follow
   a step density rho: h_{n+1/2} = eps / rho_{n+1/2}, with

     (rho_{n-1/2} + rho_{n+1/2}) / 2 = rho(t_n, y_n)

   at every step point.  The recurrence reads the same backwards
   (rho_{n-1/2} from rho_{n+1/2} and y_n), so with a symmetric step the
   map (y_n, rho_{n-1/2}) -> (y_{n+1}, rho_{n+1/2}) is reversible: run
   back from the end with the last step first, it retraces the forward
   steps.  A control that looks at the past alone (the error estimate of
   standard control) breaks that symmetry, and with it the bounded energy
   error of a symplectic method.  rho(t, y) needs no gradient, only its
   value at the step points. */
#include "driver.h"

#include <math.h>

/* rho(t, y): the user's density, or |f| / sqrt (|y|^2 + |atol|^2), the
   inverse time over which y changes by its own size; at_end: (t, y) is
   the end of the last accepted step, whose f the stepper may know */
static int
density (sym_run *r, double t, const double *y, int at_end, double *rho)
{
  const sym_driver_opts *o = r->o;
  const int n = r->n;
  int st;
  if (o->density)
    {
      if ((st = o->density (t, y, rho, o->density_user)))
        return st;
      return *rho > 0 && isfinite (*rho) ? SYM_SUCCESS : SYM_EDENSITY;
    }
  if (at_end && r->type->end_f)
    st = r->type->end_f (r->state, &r->ev, r->fn);
  else
    st = sym_rhs (&r->ev, t, y, r->fn);
  if (st)
    return st;
  const sym_tolerances *tol = &o->tol;
  double nf = 0, ny = 0;
  for (int i = 0; i < n; i++)
    {
      const double a = tol->atol[tol->atol_len > 1 ? i : 0];
      nf += r->fn[i] * r->fn[i];
      ny += y[i] * y[i] + a * a;
    }
  *rho = sqrt (nf / ny);
  return isfinite (*rho) ? SYM_SUCCESS : SYM_NONFINITE;
}

/* a callback's failure where no smaller step can help */
static int
fatal (int st)
{
  return st >= 0 ? (st == SYM_NONFINITE ? SYM_ENONFINITE : SYM_ECALLBACK)
         : st;
}

/* the step of density rho, capped by MaxStep */
static double
step_of (const sym_run *r, double rho)
{
  double h = rho > 0 ? r->eps / rho : INFINITY;
  return r->user_hmax ? fmin (h, r->hmax) : h;
}

int
sym_rev_start (sym_run *r)
{
  const sym_driver_opts *o = r->o;
  int p = r->type->order (r->state, NULL), st;
  r->eps = fmin (pow (o->tol.rtol, 1.0 / (p > 0 ? p : 1)), SYM_REV_EPS_MAX);
  r->user_hmax = o->hmax > 0;
  r->hmax = o->hmax;
  if (o->rho0 > 0)
    {
      r->rho_half = o->rho0;
      return SYM_SUCCESS;
    }
  if (o->h0 > 0)
    {
      r->rho_half = isinf (o->h0) ? 0 : r->eps / o->h0;
      return SYM_SUCCESS;
    }
  /* rho_{1/2} = (rho(y_0) + rho(y_1)) / 2, y_1 a trial step of it */
  double rho0;
  if ((st = density (r, r->t, r->y, 0, &rho0)))
    return fatal (st);
  r->rho_half = rho0;
  for (int k = 0; k < SYM_REV_START; k++)
    {
      double h = fmin (step_of (r, r->rho_half), fabs (r->tend - r->t));
      double tn = r->t + r->dir * h, rho1;
      st = r->type->step (r->state, &r->ev, r->t, tn - r->t, tn, r->y,
                          r->ynew, NULL);
      if (st > 0)
        break;    /* the run's first step will say what went wrong */
      if (st < 0)
        return st;
      if ((st = density (r, tn, r->ynew, 0, &rho1)))
        return st > 0 ? SYM_SUCCESS : st;   /* as for the step */
      r->rho_half = 0.5 * (rho0 + rho1);
    }
  return SYM_SUCCESS;
}

int
sym_rev_next (sym_run *r)
{
  double rho;
  int st = density (r, r->t, r->y, 1, &rho);
  if (st)
    return fatal (st);
  r->rho_prev = r->rho_half;
  r->rho_half = fmax (2.0 * rho - r->rho_half, SYM_REV_FLOOR * rho);
  return SYM_SUCCESS;
}

double
sym_rev_step (const sym_run *r)
{
  return step_of (r, r->rho_half);
}
