/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* A chain of FPU_D unit masses with fixed ends, springs V(r) = r^2/2 +
   beta r^4/4 (beta = par[0]): H = |p|^2/2 + sum V(q_{i+1} - q_i), q_0 =
   q_{D+1} = 0.  Its Hessian is tridiagonal in q and the identity in p
   (tests/test_compiled.m; bench/run_compiled.m with FPU_D defined
   first) */
#include "symplectic_fcn.h"

#ifndef FPU_D
#define FPU_D 40
#endif
#define D FPU_D

SYMPLECTIC_SYSTEM (D, 1);

/* V'(r) and V''(r) of the spring from q_{i-1} to q_i (i = 0..D) */
static double
dv (const double *q, int i, double beta)
{
  const double r = (i < D ? q[i] : 0) - (i > 0 ? q[i - 1] : 0);
  return r + beta * r * r * r;
}

static double
ddv (const double *q, int i, double beta)
{
  const double r = (i < D ? q[i] : 0) - (i > 0 ? q[i - 1] : 0);
  return 1 + 3 * beta * r * r;
}

int
symplectic_f (double t, const double *y, double *dy, const double *par)
{
  const double beta = par[0];
  double left = dv (y, 0, beta);
  for (int i = 0; i < D; i++)
    {
      const double right = dv (y, i + 1, beta);
      dy[i] = y[D + i];
      dy[D + i] = right - left;   /* -dH/dq_i */
      left = right;
    }
  return 0;
}

int
symplectic_accel (double t, const double *q, double *a, const double *par)
{
  const double beta = par[0];
  double left = dv (q, 0, beta);
  for (int i = 0; i < D; i++)
    {
      const double right = dv (q, i + 1, beta);
      a[i] = right - left;
      left = right;
    }
  return 0;
}

double
symplectic_energy (double t, const double *y, const double *par)
{
  double h = 0;
  for (int i = 0; i <= D; i++)
    {
      const double r = (i < D ? y[i] : 0) - (i > 0 ? y[i - 1] : 0);
      h += r * r / 2 + par[0] * r * r * r * r / 4;
      if (i < D)
        h += y[D + i] * y[D + i] / 2;
    }
  return h;
}

/* column j < D: rows j-1, j, j+1 (within q); column D + i: row D + i */
int
symplectic_hess_pattern (int *colptr, int *rowind)
{
  int e = 0;
  for (int j = 0; j < 2 * D; j++)
    {
      if (colptr)
        colptr[j] = e;
      for (int r = j - 1; r <= j + 1; r++)
        if ((j < D && r >= 0 && r < D) || (j >= D && r == j))
          {
            if (rowind)
              rowind[e] = r;
            e++;
          }
    }
  if (colptr)
    colptr[2 * D] = e;
  return e;
}

int
symplectic_hess (double t, const double *y, double *v, const double *par)
{
  const double beta = par[0];
  int e = 0;
  for (int j = 0; j < D; j++)
    {
      const double kl = ddv (y, j, beta), kr = ddv (y, j + 1, beta);
      if (j > 0)
        v[e++] = -kl;
      v[e++] = kl + kr;
      if (j < D - 1)
        v[e++] = -kr;
    }
  for (int i = 0; i < D; i++)
    v[e++] = 1;
  return 0;
}
