/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* Kepler, H = |p|^2/2 - mu/|q| (mu = par[0]), with every optional
   function of symplectic_fcn.h (tests/test_compiled.m) */
#include <math.h>
#include "symplectic_fcn.h"

SYMPLECTIC_SYSTEM (2, 1);

int
symplectic_f (double t, const double *y, double *dy, const double *par)
{
  const double r = sqrt (y[0] * y[0] + y[1] * y[1]), r3 = r * r * r;
  dy[0] = y[2];
  dy[1] = y[3];
  dy[2] = -par[0] * y[0] / r3;
  dy[3] = -par[0] * y[1] / r3;
  return 0;
}

int
symplectic_f_batch (int k, const double *t, const double *y, double *dy,
                    const double *par)
{
  for (int j = 0; j < k; j++)
    symplectic_f (t[j], y + 4 * j, dy + 4 * j, par);
  return 0;
}

int
symplectic_accel (double t, const double *q, double *a, const double *par)
{
  const double r = sqrt (q[0] * q[0] + q[1] * q[1]), r3 = r * r * r;
  a[0] = -par[0] * q[0] / r3;
  a[1] = -par[0] * q[1] / r3;
  return 0;
}

double
symplectic_energy (double t, const double *y, const double *par)
{
  return (y[2] * y[2] + y[3] * y[3]) / 2
         - par[0] / sqrt (y[0] * y[0] + y[1] * y[1]);
}

/* the q block full, the p block the identity */
int
symplectic_hess_pattern (int *colptr, int *rowind)
{
  static const int cp[5] = { 0, 2, 4, 5, 6 }, ri[6] = { 0, 1, 0, 1, 2, 3 };
  if (colptr)
    for (int i = 0; i < 5; i++)
      colptr[i] = cp[i];
  if (rowind)
    for (int i = 0; i < 6; i++)
      rowind[i] = ri[i];
  return 6;
}

int
symplectic_hess (double t, const double *y, double *v, const double *par)
{
  const double r2 = y[0] * y[0] + y[1] * y[1], r = sqrt (r2);
  const double r3 = r2 * r, r5 = r3 * r2, mu = par[0];
  v[0] = mu * (1 / r3 - 3 * y[0] * y[0] / r5);
  v[1] = -mu * 3 * y[0] * y[1] / r5;
  v[2] = v[1];
  v[3] = mu * (1 / r3 - 3 * y[1] * y[1] / r5);
  v[4] = 1;
  v[5] = 1;
  return 0;
}
