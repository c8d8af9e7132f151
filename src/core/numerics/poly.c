/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* poly.c -- interpolating polynomials (Lagrange, Hermite), extrapolation
   weights, and the vector helpers the steppers share. */
#include "numerics.h"

#include <float.h>
#include <math.h>

double
sym_norm_inf (int n, const double *v)
{
  double m = 0.0;
  for (int i = 0; i < n; i++)
    m = fmax (m, fabs (v[i]));
  return m;
}

int
sym_same_vec (int n, const double *a, const double *b)
{
  for (int i = 0; i < n; i++)
    if (a[i] != b[i])
      return 0;
  return 1;
}

int
sym_same_time (double a, double b, double h)
{
  return a == b
         || fabs (a - b) <= 4.0 * DBL_EPSILON
                            * fmax (fmax (fabs (a), fabs (b)), fabs (h));
}

int
sym_same_step (double h, double hprev)
{
  return fabs (h - hprev) <= SYM_SAME_STEP * fabs (h);
}

void
sym_bary_weights (int np, const double *x, double *bw)
{
  for (int i = 0; i < np; i++)
    {
      double p = 1.0;
      for (int k = 0; k < np; k++)
        if (k != i)
          p *= x[i] - x[k];
      bw[i] = 1.0 / p;
    }
}

void
sym_lagrange_basis (int np, const double *xb, const double *bw, double x,
                    double *c)
{
  double l = 1.0;
  for (int i = 0; i < np; i++)
    {
      if (x == xb[i])
        {
          for (int k = 0; k < np; k++)
            c[k] = k == i;
          return;
        }
      l *= x - xb[i];
    }
  for (int i = 0; i < np; i++)
    c[i] = l * bw[i] / (x - xb[i]);
}

void
sym_lagrange_weights (int np, const double *ts, double t, double *c)
{
  for (int j = 0; j < np; j++)
    {
      double v = 1.0;
      for (int k = 0; k < np; k++)
        if (k != j)
          v *= (t - ts[k]) / (ts[j] - ts[k]);
      c[j] = v;
    }
}

const double *
sym_extrap_weights (int L)
{
  /* (-1)^l binomial(L, l + 1) */
  static const double w[5][4] = {
    { 0 }, { 1 }, { 2, -1 }, { 3, -3, 1 }, { 4, -6, 4, -1 }
  };
  return L >= 0 && L <= 4 ? w[L] : NULL;
}

void
sym_hermite (int n, double h, double th, const double *y0, const double *y1,
             const double *f0, const double *f1, double *y)
{
  const double u = 1.0 - th;
  const double a0 = u * u * (1.0 + 2.0 * th), a1 = th * th * (3.0 - 2.0 * th);
  const double b0 = h * th * u * u, b1 = -h * th * th * u;
  for (int i = 0; i < n; i++)
    y[i] = a0 * y0[i] + a1 * y1[i] + b0 * f0[i] + b1 * f1[i];
}
