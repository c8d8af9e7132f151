/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* control.c -- error norms and step-size choice for the adaptive driver,
   scaled exactly as Octave's ode45 scales them, so that RelTol and AbsTol
   mean the same thing to a user of either. */
#include "driver.h"

#include <float.h>
#include <math.h>

/* ode45's AbsRel norm: max_i |e_i| / max(atol_i, rtol * max(|y_i|, |yold_i|));
   with NormControl: |e| / max(atol, rtol * max(|y|, |yold|)) in the 2-norm. */
double
sym_error_norm (int n, const double *e, const double *yold,
                const double *ynew, const sym_tolerances *tol)
{
  const double rtol = tol->rtol, *atol = tol->atol;
  const int atol_len = tol->atol_len;
  if (tol->norm_control)
    {
      double ne = 0, ny = 0, nyo = 0;
      for (int i = 0; i < n; i++)
        {
          ne += e[i] * e[i];
          ny += ynew[i] * ynew[i];
          nyo += yold[i] * yold[i];
        }
      double sc = fmax (atol[0], rtol * fmax (sqrt (ny), sqrt (nyo)));
      return sqrt (ne) / sc;
    }
  double m = 0;
  for (int i = 0; i < n; i++)
    {
      double a = atol[atol_len > 1 ? i : 0];
      double sc = fmax (a, rtol * fmax (fabs (ynew[i]), fabs (yold[i])));
      double r = fabs (e[i]) / sc;
      if (r > m || isnan (r))
        m = r;
    }
  return m;
}

/* The factor by which to multiply h after a step with error norm err, for
   an estimate of order q+1 (err = O(h^(q+1))). */
double
sym_step_factor (double err, int q, double facmin, double facmax)
{
  if (err <= 0 || ! isfinite (err))
    return err <= 0 ? facmax : facmin;
  double fac = SYM_CTRL_SAFETY * pow (err, -1.0 / (q + 1));
  return fmin (facmax, fmax (facmin, fac));
}

/* Predictive control: the error of a step grows with h as h^(q+1), but
   also along the solution (Kepler's orbit falling towards pericentre);
   where it grows from step to step, the standard factor, which assumes
   the next error constant at the same h, proposes steps that fail.  The
   predicted factor fac (h / h_acc) (err_acc / err)^(1/(q+1)) extrapolates
   the trend of the last two accepted steps; the smaller of the two is
   taken, so that the prediction only ever shortens a step. */
double
sym_step_factor_pred (double fac, double err, int q, double h,
                      double h_acc, double err_acc, double facmin)
{
  if (! (err_acc > 0) || ! (err > 0) || ! (h_acc > 0) || ! isfinite (err))
    return fac;
  double fp = fac * (fabs (h) / h_acc) * pow (err_acc / err, 1.0 / (q + 1));
  return fmin (fac, fmax (facmin, fp));
}

/* Starting step (the classical starting-step estimate): balance
   h*|f0| and h^(q+1) * |f'| against the tolerance.  Costs one rhs call
   (f0 is given). */
int
sym_initial_step (sym_eval *ev, double t0, const double *y0,
                  const double *f0, double dir, int q,
                  const sym_tolerances *tol, double hmax, double *work,
                  double *h_out)
{
  const int n = 2 * ev->dim, atol_len = tol->atol_len;
  const double rtol = tol->rtol, *atol = tol->atol;
  double d0 = 0, d1 = 0;
  for (int i = 0; i < n; i++)
    {
      double sc = atol[atol_len > 1 ? i : 0] + rtol * fabs (y0[i]);
      d0 = fmax (d0, fabs (y0[i]) / sc);
      d1 = fmax (d1, fabs (f0[i]) / sc);
    }
  double h0 = (d0 < 1e-5 || d1 < 1e-5) ? 1e-6 : 0.01 * d0 / d1;
  h0 = fmin (h0, hmax);
  double *y1 = work, *f1 = work + n;
  for (int i = 0; i < n; i++)
    y1[i] = y0[i] + dir * h0 * f0[i];
  int st = sym_rhs (ev, t0 + dir * h0, y1, f1);
  if (st)
    {
      /* a failing probe: start small and let the driver's control work */
      *h_out = h0;
      return st < 0 ? st : SYM_SUCCESS;
    }
  double d2 = 0;
  for (int i = 0; i < n; i++)
    {
      double sc = atol[atol_len > 1 ? i : 0] + rtol * fabs (y0[i]);
      d2 = fmax (d2, fabs (f1[i] - f0[i]) / sc);
    }
  d2 /= h0;
  double h1;
  if (fmax (d1, d2) <= 1e-15)
    h1 = fmax (1e-6, h0 * 1e-3);
  else
    h1 = pow (0.01 / fmax (d1, d2), 1.0 / (q + 1));
  *h_out = fmin (fmin (100 * h0, h1), hmax);
  return SYM_SUCCESS;
}
