/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* quadrature.c -- Gauss-Legendre nodes and weights, Legendre polynomials.

   Nodes: Golub-Welsch.  The Jacobi matrix of the Legendre weight is the
   symmetric tridiagonal T with zero diagonal and off-diagonals
   beta_k = k / sqrt(4k^2 - 1), k = 1..m-1; its eigenvalues are the nodes
   and w_j = 2 v_j(1)^2 (v_j the normalized eigenvectors).  LAPACK's dstev
   gives them to a few ulp times a modest factor, so each node is then
   polished by Newton's method on P_m (three-term recurrence) and the
   weights are recomputed from w = 2 / ((1 - z^2) P_m'(z)^2); finally the
   rule is made exactly symmetric. */
#include "numerics.h"

#include <math.h>

/* P_m(x) and P_m'(x) by the recurrence, in long double (see below).  For
   |x| < 1 the derivative comes from (1 - x^2) P_m' = m (P_{m-1} - x P_m);
   the nodes are inside, and (1 - x)(1 + x) keeps its digits near +-1. */
static void
legendre_pm (int m, long double x, long double *pm, long double *dpm)
{
  long double p0 = 1.0L, p1 = x;
  for (int k = 1; k < m; k++)
    {
      long double p2 = ((2.0L * k + 1.0L) * x * p1 - k * p0) / (k + 1.0L);
      p0 = p1;
      p1 = p2;
    }
  *pm = p1;
  *dpm = m * (p0 - x * p1) / ((1.0L - x) * (1.0L + x));
}

int
sym_gauss_legendre (int m, double *z, double *w)
{
  if (m < 1 || ! z || ! w)
    return SYM_EBADINPUT;
  if (m == 1)
    {
      z[0] = 0.0;
      w[0] = 2.0;
      return SYM_SUCCESS;
    }

  double *e = sym_malloc ((size_t) (m - 1) * sizeof (double));
  double *v = sym_malloc ((size_t) m * m * sizeof (double));
  double *work = sym_malloc ((size_t) (2 * m - 2) * sizeof (double));
  if (! e || ! v || ! work)
    {
      sym_free (work);
      sym_free (v);
      sym_free (e);
      return SYM_ENOMEM;
    }
  for (int i = 0; i < m; i++)
    z[i] = 0.0;
  for (int k = 1; k < m; k++)
    e[k - 1] = k / sqrt (4.0 * k * k - 1.0);
  int info = sym_stev (m, z, e, v, work);
  if (info == 0)
    for (int j = 0; j < m; j++)
      w[j] = 2.0 * v[(size_t) j * m] * v[(size_t) j * m];
  sym_free (work);
  sym_free (v);
  sym_free (e);
  if (info != 0)
    return SYM_EBADINPUT;

  /* Polish in long double (x86: 64-bit mantissa; where long double is
     just double, weights near the ends lose to ~1e-14 at m = 30).  The
     extra digits matter for the weights: near the ends w varies fast with
     the node (d log w / dx = -2x / (1 - x^2) at a root), so w must be
     evaluated at the root itself, not at its rounding to double (1e-14
     relative errors at m = 30 otherwise).  Two Newton steps: the first
     lands within an ulp or two of double, the second settles it. */
  for (int j = 0; j < m; j++)
    {
      long double x = z[j], pm, dpm;
      for (int it = 0; it < 2; it++)
        {
          legendre_pm (m, x, &pm, &dpm);
          x -= pm / dpm;
        }
      legendre_pm (m, x, &pm, &dpm);
      z[j] = (double) x;
      w[j] = (double) (2.0L / ((1.0L - x) * (1.0L + x) * dpm * dpm));
    }

  /* Exact symmetry: z_j = -z_{m-1-j}, w_j = w_{m-1-j}, middle node 0. */
  for (int j = 0; j < m / 2; j++)
    {
      double zs = 0.5 * (z[m - 1 - j] - z[j]);
      double ws = 0.5 * (w[j] + w[m - 1 - j]);
      z[j] = -zs;
      z[m - 1 - j] = zs;
      w[j] = w[m - 1 - j] = ws;
    }
  if (m % 2)
    z[m / 2] = 0.0;
  return SYM_SUCCESS;
}

void
sym_legendre (int n, double x, double *l, double *dl)
{
  if (n < 1)
    return;
  l[0] = 1.0;
  dl[0] = 0.0;
  if (n < 2)
    return;
  l[1] = x;
  dl[1] = 1.0;
  /* (i+1) l_{i+1} = (2i+1) x l_i - i l_{i-1};
     l_{i+1}' = l_{i-1}' + (2i+1) l_i  (no division by x^2 - 1, so the
     endpoints are fine: l_i(1) = 1, l_i(-1) = (-1)^i exactly). */
  for (int i = 1; i + 1 < n; i++)
    {
      l[i + 1] = ((2.0 * i + 1.0) * x * l[i] - i * l[i - 1]) / (i + 1.0);
      dl[i + 1] = dl[i - 1] + (2.0 * i + 1.0) * l[i];
    }
}
