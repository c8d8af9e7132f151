/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* The pendulum H = p^2/2 - cos q, with its Hessian and energy; f is NaN
   once |q| > 3 (a swing over the top fails there: tests/test_compiled.m) */
#include <math.h>
#include "symplectic_fcn.h"

SYMPLECTIC_SYSTEM (1, 0);

int
symplectic_f (double t, const double *y, double *dy, const double *par)
{
  dy[0] = y[1];
  dy[1] = fabs (y[0]) > 3 ? NAN : -sin (y[0]);
  return 0;
}

int
symplectic_accel (double t, const double *q, double *a, const double *par)
{
  a[0] = -sin (q[0]);
  return 0;
}

double
symplectic_energy (double t, const double *y, const double *par)
{
  return y[1] * y[1] / 2 - cos (y[0]);
}

int
symplectic_hess_pattern (int *colptr, int *rowind)
{
  if (colptr)
    {
      colptr[0] = 0;
      colptr[1] = 1;
      colptr[2] = 2;
      rowind[0] = 0;
      rowind[1] = 1;
    }
  return 2;
}

int
symplectic_hess (double t, const double *y, double *v, const double *par)
{
  v[0] = cos (y[0]);
  v[1] = 1;
  return 0;
}
