/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* test_quadrature.c -- Gauss-Legendre rules and Legendre polynomials. */
#include "sym.h"
#include "numerics/numerics.h"
#include "testutil.h"

#include <float.h>
#include <string.h>

/* Known rules (closed forms) for m = 1..5, nodes ascending. */
static void
known_rule (int m, double *z, double *w)
{
  switch (m)
    {
    case 1:
      z[0] = 0.0;
      w[0] = 2.0;
      break;
    case 2:
      z[0] = -1.0 / sqrt (3.0);
      z[1] = -z[0];
      w[0] = w[1] = 1.0;
      break;
    case 3:
      z[0] = -sqrt (0.6);
      z[1] = 0.0;
      z[2] = -z[0];
      w[0] = w[2] = 5.0 / 9.0;
      w[1] = 8.0 / 9.0;
      break;
    case 4:
      {
        double a = sqrt (3.0 / 7.0 - 2.0 / 7.0 * sqrt (6.0 / 5.0));
        double b = sqrt (3.0 / 7.0 + 2.0 / 7.0 * sqrt (6.0 / 5.0));
        z[0] = -b;
        z[1] = -a;
        z[2] = a;
        z[3] = b;
        w[0] = w[3] = (18.0 - sqrt (30.0)) / 36.0;
        w[1] = w[2] = (18.0 + sqrt (30.0)) / 36.0;
      }
      break;
    case 5:
      {
        double a = sqrt (5.0 - 2.0 * sqrt (10.0 / 7.0)) / 3.0;
        double b = sqrt (5.0 + 2.0 * sqrt (10.0 / 7.0)) / 3.0;
        z[0] = -b;
        z[1] = -a;
        z[2] = 0.0;
        z[3] = a;
        z[4] = b;
        w[0] = w[4] = (322.0 - 13.0 * sqrt (70.0)) / 900.0;
        w[1] = w[3] = (322.0 + 13.0 * sqrt (70.0)) / 900.0;
        w[2] = 128.0 / 225.0;
      }
      break;
    }
}

static void
scenario_known (void)
{
  double z[5], w[5], zk[5], wk[5];
  for (int m = 1; m <= 5; m++)
    {
      CHECK (sym_gauss_legendre (m, z, w) == 0, "m = %d", m);
      known_rule (m, zk, wk);
      for (int j = 0; j < m; j++)
        {
          CHECK_CLOSE (z[j], zk[j], 1e-15, "known node");
          CHECK_CLOSE (w[j], wk[j], 1e-15, "known weight");
        }
    }
}

/* Sum of weights, symmetry, ascending order, exactness up to degree
   2m-1, and inexactness at degree 2m (the rule is exactly Gauss). */
static void
scenario_rules (void)
{
  enum { MMAX = 64 };
  double z[MMAX], w[MMAX];
  double worst_exact = 0.0, worst_sym = 0.0, worst_sum = 0.0;
  for (int m = 1; m <= MMAX; m++)
    {
      CHECK (sym_gauss_legendre (m, z, w) == 0, "m = %d", m);
      double s = 0.0;
      for (int j = 0; j < m; j++)
        s += w[j];
      worst_sum = fmax (worst_sum, fabs (s - 2.0));
      int asc = 1, inside = 1, pos = 1;
      for (int j = 0; j < m; j++)
        {
          if (j > 0 && ! (z[j] > z[j - 1]))
            asc = 0;
          if (! (fabs (z[j]) < 1.0))
            inside = 0;
          if (! (w[j] > 0.0))
            pos = 0;
          worst_sym = fmax (worst_sym, fabs (z[j] + z[m - 1 - j]));
          worst_sym = fmax (worst_sym, fabs (w[j] - w[m - 1 - j]));
        }
      CHECK (asc && inside && pos, "m = %d: ascending %d inside %d "
             "positive %d", m, asc, inside, pos);
      if (m % 2)
        CHECK (z[m / 2] == 0.0, "m = %d: middle node %g", m, z[m / 2]);
      if (m <= 30)
        for (int k = 0; k <= 2 * m - 1; k++)
          {
            double q = 0.0;
            for (int j = 0; j < m; j++)
              q += w[j] * pow (z[j], k);
            double exact = (k % 2) ? 0.0 : 2.0 / (k + 1.0);
            double e = fabs (q - exact);
            worst_exact = fmax (worst_exact, e);
            CHECK (e <= 1e-14, "m = %d, x^%d: %.17g vs %.17g", m, k, q,
                   exact);
          }
      /* degree 2m: not exact (error = 2^(2m+1) (m!)^4 / ((2m+1) ((2m)!)^3)
         times (2m)!, positive and visible for small m) */
      if (m <= 6)
        {
          double q = 0.0;
          for (int j = 0; j < m; j++)
            q += w[j] * pow (z[j], 2 * m);
          CHECK (fabs (q - 2.0 / (2 * m + 1.0)) > 1e-6,
                 "m = %d: degree 2m integrated exactly?", m);
        }
    }
  CHECK (worst_sum <= 4e-15, "sum of weights off by %g", worst_sum);
  CHECK (worst_sym == 0.0, "asymmetry %g", worst_sym);
  printf ("quadrature: worst |sum w - 2| %.2g, worst x^k error %.2g "
          "(m <= 30)\n", worst_sum, worst_exact);

  /* Larger m: still symmetric, weights positive, integrates cos(x) */
  for (int m = 40; m <= 100; m += 20)
    {
      double zz[100], ww[100];
      CHECK (sym_gauss_legendre (m, zz, ww) == 0, "m = %d", m);
      double q = 0.0;
      for (int j = 0; j < m; j++)
        q += ww[j] * cos (zz[j]);
      CHECK_CLOSE (q, 2.0 * sin (1.0), 1e-14, "integral of cos");
    }
}

static void *
failing_alloc (size_t n)
{
  (void) n;
  return NULL;
}

static void
scenario_bad_input (void)
{
  double z[5], w[5];
  CHECK (sym_gauss_legendre (0, z, w) == SYM_EBADINPUT, "m = 0");
  CHECK (sym_gauss_legendre (-3, z, w) == SYM_EBADINPUT, "m < 0");
  sym_set_allocator (failing_alloc, NULL);
  int st = sym_gauss_legendre (5, z, w);
  sym_set_allocator (NULL, NULL);
  CHECK (st == SYM_ENOMEM, "allocation failure: %d", st);
  CHECK (sym_gauss_legendre (5, z, w) == 0, "allocator restored");
}

/* Closed forms of l_0..l_5 and their derivatives. */
static void
closed_forms (double x, double *l, double *dl)
{
  double x2 = x * x, x3 = x2 * x, x4 = x3 * x, x5 = x4 * x;
  l[0] = 1.0;
  l[1] = x;
  l[2] = (3.0 * x2 - 1.0) / 2.0;
  l[3] = (5.0 * x3 - 3.0 * x) / 2.0;
  l[4] = (35.0 * x4 - 30.0 * x2 + 3.0) / 8.0;
  l[5] = (63.0 * x5 - 70.0 * x3 + 15.0 * x) / 8.0;
  dl[0] = 0.0;
  dl[1] = 1.0;
  dl[2] = 3.0 * x;
  dl[3] = (15.0 * x2 - 3.0) / 2.0;
  dl[4] = (140.0 * x3 - 60.0 * x) / 8.0;
  dl[5] = (315.0 * x4 - 210.0 * x2 + 15.0) / 8.0;
}

static void
scenario_legendre (void)
{
  double l[40], dl[40], lc[6], dlc[6];
  const double xs[] = { -1.0, -0.9, -0.31, 0.0, 0.25, 0.5, 0.77, 1.0 };
  for (size_t t = 0; t < sizeof xs / sizeof xs[0]; t++)
    {
      double x = xs[t];
      sym_legendre (6, x, l, dl);
      closed_forms (x, lc, dlc);
      for (int i = 0; i < 6; i++)
        {
          CHECK_CLOSE (l[i], lc[i], 1e-15, "l_i closed form");
          CHECK_CLOSE (dl[i], dlc[i], 1e-14, "l_i' closed form");
        }
    }
  /* endpoints, exactly: l_i(1) = 1, l_i(-1) = (-1)^i,
     l_i'(1) = i(i+1)/2, l_i'(-1) = (-1)^(i+1) i(i+1)/2 */
  sym_legendre (40, 1.0, l, dl);
  int ok = 1;
  for (int i = 0; i < 40; i++)
    ok &= l[i] == 1.0 && dl[i] == i * (i + 1) / 2.0;
  CHECK (ok, "values at +1");
  sym_legendre (40, -1.0, l, dl);
  ok = 1;
  for (int i = 0; i < 40; i++)
    ok &= l[i] == ((i % 2) ? -1.0 : 1.0)
          && dl[i] == ((i % 2) ? 1.0 : -1.0) * i * (i + 1) / 2.0;
  CHECK (ok, "values at -1");

  /* derivatives of high degree vs central differences */
  double lp[40], lm[40], tmp[40];
  const double hx = 1e-6;
  double worst = 0.0;
  for (double x = -0.95; x < 0.96; x += 0.173)
    {
      sym_legendre (40, x, l, dl);
      sym_legendre (40, x + hx, lp, tmp);
      sym_legendre (40, x - hx, lm, tmp);
      for (int i = 0; i < 40; i++)
        {
          double fd = (lp[i] - lm[i]) / (2 * hx);
          double rel = fabs (fd - dl[i]) / fmax (1.0, fabs (dl[i]));
          worst = fmax (worst, rel);
        }
    }
  CHECK (worst < 1e-6, "derivative vs central difference: %g", worst);
  /* orthogonality with a 30-point rule: int l_i l_k = 2/(2i+1) delta */
  double z[30], w[30];
  sym_gauss_legendre (30, z, w);
  double worst_orth = 0.0;
  for (int i = 0; i < 30; i++)
    for (int k = 0; k < 30; k++)
      {
        double s = 0.0;
        for (int j = 0; j < 30; j++)
          {
            sym_legendre (30, z[j], l, dl);
            s += w[j] * l[i] * l[k];
          }
        double exact = i == k ? 2.0 / (2 * i + 1.0) : 0.0;
        worst_orth = fmax (worst_orth, fabs (s - exact));
      }
  CHECK (worst_orth < 1e-14, "orthogonality %g", worst_orth);
  /* n = 0, 1 are fine */
  l[0] = dl[0] = 7.0;
  sym_legendre (0, 0.3, l, dl);
  CHECK (l[0] == 7.0, "n = 0 writes nothing");
  sym_legendre (1, 0.3, l, dl);
  CHECK (l[0] == 1.0 && dl[0] == 0.0, "n = 1");
}

int
main (void)
{
  scenario_known ();
  scenario_rules ();
  scenario_bad_input ();
  scenario_legendre ();
  return tu_finish ("test_quadrature");
}
