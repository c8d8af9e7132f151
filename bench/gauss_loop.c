/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* gauss_loop.c -- a reference for odeSPVI's C core: the plainest loop of
   s-stage Gauss collocation (s = 4, order 8) on Kepler's problem, with no
   package code and no solver around it.  Fixed step h = 400 pi / 113137
   over 113137 steps (200 periods, e = 0.6); the stage equations
   Z_i = h sum_j a_ij f(y + Z_j) by fixed-point iteration, started from the
   previous step's collocation polynomial, until the change is at
   round-off; y summed with compensation.  Prints the numbers to standard
   output, or appends them as a Markdown section to the file given.
   Built and run by `make bench-gauss` (and appended to CORE.md by
   `make bench-core`). */
#define _POSIX_C_SOURCE 199309L   /* clock_gettime */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "timing.h"

#define S 4                 /* stages */
#define N 4                 /* 2 dof: q1 q2 p1 p2 */
#define ECC 0.6
#define STEPS 113137L
#define PERIODS 200
#define ROUNDS 5
#define MAXIT 50
#define PI 3.14159265358979323846

static double A[S][S], B[S], C[S];
/* E[i][j]: the previous step's Lagrange basis (nodes 0, c_1..c_s) at
   1 + c_i, so that the old collocation polynomial gives the new guess */
static double E[S][S];

/* Legendre P_s and its derivative at x, by the three-term recurrence */
static void
legendre (int s, long double x, long double *p, long double *dp)
{
  long double p0 = 1.0L, p1 = x;
  for (int k = 2; k <= s; k++)
    {
      const long double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
      p0 = p1;
      p1 = p2;
    }
  *p = p1;
  *dp = s * (x * p1 - p0) / (x * x - 1.0L);
}

/* solve the n x n system M x = r in place (partial pivoting); long double
   so that the coefficients come out right to the last bit of a double */
static void
solve (int n, long double M[S][S], long double r[S])
{
  for (int k = 0; k < n; k++)
    {
      int piv = k;
      for (int i = k + 1; i < n; i++)
        if (fabsl (M[i][k]) > fabsl (M[piv][k]))
          piv = i;
      for (int j = 0; j < n; j++)
        {
          const long double t = M[k][j];
          M[k][j] = M[piv][j];
          M[piv][j] = t;
        }
      const long double t = r[k];
      r[k] = r[piv];
      r[piv] = t;
      for (int i = k + 1; i < n; i++)
        {
          const long double m = M[i][k] / M[k][k];
          for (int j = k; j < n; j++)
            M[i][j] -= m * M[k][j];
          r[i] -= m * r[k];
        }
    }
  for (int k = n - 1; k >= 0; k--)
    {
      for (int j = k + 1; j < n; j++)
        r[k] -= M[k][j] * r[j];
      r[k] /= M[k][k];
    }
}

/* nodes: the roots of P_s mapped to (0, 1), by Newton from the Chebyshev
   guesses; A and b from the collocation conditions
   sum_j a_ij c_j^(k-1) = c_i^k / k, sum_j b_j c_j^(k-1) = 1 / k */
static void
coefficients (void)
{
  long double c[S];
  for (int i = 0; i < S; i++)
    {
      long double x = cosl (3.14159265358979323846264338L * (S - i - 0.25L)
                            / (S + 0.5L)), p, dp;
      for (int it = 0; it < 100; it++)
        {
          legendre (S, x, &p, &dp);
          const long double dx = p / dp;
          x -= dx;
          if (fabsl (dx) <= 1e-19L)
            break;
        }
      c[i] = (1.0L + x) / 2.0L;
      C[i] = (double) c[i];
    }
  for (int i = 0; i <= S; i++)
    {
      long double M[S][S], r[S];
      const long double ci = i < S ? c[i] : 1.0L;    /* i = S: the b row */
      for (int k = 0; k < S; k++)
        {
          long double ck = 1.0L;
          for (int m = 0; m < k + 1; m++)
            ck *= ci;
          r[k] = ck / (k + 1);
          for (int j = 0; j < S; j++)
            M[k][j] = powl (c[j], k);
        }
      solve (S, M, r);
      for (int j = 0; j < S; j++)
        {
          if (i < S)
            A[i][j] = (double) r[j];
          else
            B[j] = (double) r[j];
        }
    }
  for (int i = 0; i < S; i++)
    for (int j = 0; j < S; j++)
      {
        const long double t = 1.0L + c[i];
        long double l = t / c[j];                 /* the factor of node 0 */
        for (int m = 0; m < S; m++)
          if (m != j)
            l *= (t - c[m]) / (c[j] - c[m]);
        E[i][j] = (double) l;
      }
}

static void
kepler (const double *y, double *f)
{
  const double r2 = y[0] * y[0] + y[1] * y[1], r3 = r2 * sqrt (r2);
  f[0] = y[2];
  f[1] = y[3];
  f[2] = -y[0] / r3;
  f[3] = -y[1] / r3;
}

static double
energy (const double *y)
{
  return 0.5 * (y[2] * y[2] + y[3] * y[3])
         - 1.0 / sqrt (y[0] * y[0] + y[1] * y[1]);
}

typedef struct
{
  double y[N];          /* end point */
  double herr;          /* max |H - H0| over the step points (if asked) */
  long iters;           /* fixed-point sweeps, all steps */
  long fevals;
} run_result;

static void
integrate (const double *y0, int monitor, run_result *res)
{
  const double h = 2.0 * PI * PERIODS / STEPS;
  double y[N], err[N] = { 0 }, Z[S][N] = { { 0 } }, F[S][N], dy[N];
  double hA[S][S], hB[S];
  for (int i = 0; i < S; i++)
    {
      hB[i] = h * B[i];
      for (int j = 0; j < S; j++)
        hA[i][j] = h * A[i][j];
    }
  for (int k = 0; k < N; k++)
    y[k] = y0[k];
  const double H0 = energy (y0);
  double herr = 0.0;
  long iters = 0;
  int first = 1;
  for (long n = 0; n < STEPS; n++)
    {
      /* start: the old collocation polynomial at t_n + c_i h, less the
         increment taken (zero on the first step) */
      if (! first)
        {
          double Zn[S][N];
          for (int i = 0; i < S; i++)
            for (int k = 0; k < N; k++)
              {
                double z = -dy[k];
                for (int j = 0; j < S; j++)
                  z += E[i][j] * Z[j][k];
                Zn[i][k] = z;
              }
          for (int i = 0; i < S; i++)
            for (int k = 0; k < N; k++)
              Z[i][k] = Zn[i][k];
        }
      first = 0;
      double ymax = 0.0;
      for (int k = 0; k < N; k++)
        ymax = fmax (ymax, fabs (y[k]));
      double dold = INFINITY;
      for (int it = 0; it < MAXIT; it++)
        {
          for (int i = 0; i < S; i++)
            {
              double yi[N];
              for (int k = 0; k < N; k++)
                yi[k] = y[k] + Z[i][k];
              kepler (yi, F[i]);
            }
          iters++;
          double d = 0.0;
          for (int i = 0; i < S; i++)
            for (int k = 0; k < N; k++)
              {
                double z = 0.0;
                for (int j = 0; j < S; j++)
                  z += hA[i][j] * F[j][k];
                d = fmax (d, fabs (z - Z[i][k]));
                Z[i][k] = z;
              }
          /* at round-off: the change is below 1e-16 of |y| or has
             stopped decreasing */
          if (d <= 1e-16 * ymax || d >= dold)
            break;
          dold = d;
        }
      /* y += h b' F, compensated: err holds what the sum lost */
      for (int k = 0; k < N; k++)
        {
          double s = 0.0;
          for (int j = 0; j < S; j++)
            s += hB[j] * F[j][k];
          dy[k] = s;
          const double a = s + err[k], yn = y[k] + a;
          err[k] = (y[k] - yn) + a;
          y[k] = yn;
        }
      if (monitor)
        herr = fmax (herr, fabs (energy (y) - H0));
    }
  for (int k = 0; k < N; k++)
    res->y[k] = y[k];
  res->herr = herr;
  res->iters = iters;
  res->fevals = S * iters;
}

int
main (int argc, char **argv)
{
  coefficients ();
  const double y0[N] = { 1.0 - ECC, 0.0, 0.0,
                         sqrt ((1.0 + ECC) / (1.0 - ECC)) };
  run_result res;
  double t[ROUNDS];
  for (int r = 0; r < ROUNDS; r++)
    {
      const double t0 = now ();
      integrate (y0, 0, &res);
      t[r] = (now () - t0) / STEPS;
    }
  qsort (t, ROUNDS, sizeof t[0], cmp_double);
  integrate (y0, 1, &res);        /* the same steps, with the energy */
  double dist = 0.0;
  for (int k = 0; k < N; k++)
    dist += (res.y[k] - y0[k]) * (res.y[k] - y0[k]);
  dist = sqrt (dist);

  FILE *f = argc > 1 ? fopen (argv[1], "a") : stdout;
  if (! f)
    {
      perror (argv[1]);
      return 1;
    }
  if (f == stdout)
    {
      printf ("Gauss s = %d, Kepler e = %g, %ld steps of 400 pi/113137\n",
              S, ECC, STEPS);
      printf ("|y(end) - y0|_2        %.3e\n", dist);
      printf ("max |H - H0|           %.3e\n", res.herr);
      printf ("iterations per step    %.2f\n", (double) res.iters / STEPS);
      printf ("f evaluations per step %.2f\n", (double) res.fevals / STEPS);
      printf ("us per step (least)    %.3f\n", 1e6 * t[0]);
    }
  else
    {
      fprintf (f, "\n## Plain Gauss collocation loop\n\n"
               "bench/gauss_loop.c (`make bench-gauss`): %d-stage Gauss "
               "(order %d) with no package code, Kepler e = %g, %ld fixed "
               "steps of 400 pi/%ld (%d periods); fixed-point iteration "
               "started from the previous step's collocation polynomial, "
               "stopped when the change is below 1e-16 |y| or stops "
               "decreasing; y summed with compensation; time the least "
               "of %d runs.\n\n"
               "| y(end) - y0 (2-norm) | max energy error | iterations "
               "per step | f per step | us per step |\n"
               "|---|---|---|---|---|\n"
               "| %.2e | %.2e | %.2f | %.2f | %.3f |\n",
               S, 2 * S, ECC, STEPS, STEPS, PERIODS, ROUNDS, dist, res.herr,
               (double) res.iters / STEPS, (double) res.fevals / STEPS,
               1e6 * t[0]);
      fclose (f);
    }
  return 0;
}
