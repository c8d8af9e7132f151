/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* kahanli8_loop.c -- the outer solar system (bench/outer_solar.m's data)
   by the composition "kahanli8" of velocity Verlet, written as a plain C
   loop with no solver around it: the floor that odeSV's Method
   "kahanli8", SecondOrder "on" with a compiled FCN is measured against
   (bench/run_compiled.m).  The same steps as the solver's: kicks of
   (g_{i-1} + g_i) h / 2 and drifts of g_i h, one force per drift (the
   last one the next step's first), the sums compensated across the run
   as CompensatedSummation "on" (the default) does.  The force is the
   pairwise sum, written by hand.

     kahanli8_loop H NSTEPS ROUNDS

   prints the median time per step (us) of ROUNDS runs of NSTEPS steps of
   H days, then the final y = [q; v] (36 numbers).  Built -O2 as the
   gateways are.  */

#define _POSIX_C_SOURCE 199309L   /* clock_gettime */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "timing.h"

#define NB 6
#define D (3 * NB)

static const double g8[17] = {
  0.13020248308889008, 0.56116298177510838, -0.38947496264484729,
  0.15884190655515560, -0.39590389413323758, 0.18453964097831571,
  0.25837438768632205, 0.29501172360931030, -0.60550853383003451,
  0.29501172360931030, 0.25837438768632205, 0.18453964097831571,
  -0.39590389413323758, 0.15884190655515560, -0.38947496264484729,
  0.56116298177510838, 0.13020248308889008
};

static const double mass[NB] = {
  1.00000597682, 0.000954786104043, 0.000285583733151,
  0.0000437273164546, 0.0000517759138449, 1.0 / 1.3e8
};
static const double G = 2.95912208286e-4;

static const double q0[D] = {
  0, 0, 0,
  -3.5023653, -3.8169847, -1.5507963,
  9.0755314, -3.0458353, -1.6483708,
  8.3101420, -16.2901086, -7.2521278,
  11.4707666, -25.7294829, -10.8169456,
  -15.5387357, -25.2225594, -3.1902382
};
static const double v0[D] = {
  0, 0, 0,
  0.00565429, -0.00412490, -0.00190589,
  0.00168318, 0.00483525, 0.00192462,
  0.00354178, 0.00137102, 0.00055029,
  0.00288930, 0.00114527, 0.00039677,
  0.00276725, -0.00170702, -0.00136504
};

/* a = -M^-1 grad V, pair by pair */
static void
accel (const double *q, double *a)
{
  memset (a, 0, D * sizeof (double));
  for (int i = 0; i < NB; i++)
    for (int j = i + 1; j < NB; j++)
      {
        const double dx = q[3 * j] - q[3 * i], dy = q[3 * j + 1] - q[3 * i + 1],
          dz = q[3 * j + 2] - q[3 * i + 2];
        const double r2 = dx * dx + dy * dy + dz * dz;
        const double s = G / (r2 * sqrt (r2));
        const double si = s * mass[j], sj = s * mass[i];
        a[3 * i] += si * dx;  a[3 * i + 1] += si * dy;  a[3 * i + 2] += si * dz;
        a[3 * j] -= sj * dx;  a[3 * j + 1] -= sj * dy;  a[3 * j + 2] -= sj * dz;
      }
}

static inline void
comp_add (double *x, double *c, double dx)
{
  const double y = dx - *c, t = *x + y;
  *c = (t - *x) - y;
  *x = t;
}

static void
run (double h, long nsteps, double *q, double *v)
{
  double a[D], cq[D] = { 0 }, cv[D] = { 0 }, b[18];
  for (int i = 0; i <= 17; i++)
    b[i] = 0.5 * ((i > 0 ? g8[i - 1] : 0.0) + (i < 17 ? g8[i] : 0.0));
  memcpy (q, q0, sizeof q0);
  memcpy (v, v0, sizeof v0);
  accel (q, a);
  for (long n = 0; n < nsteps; n++)
    {
      for (int k = 0; k < 17; k++)
        {
          const double bh = b[k] * h, ah = g8[k] * h;
          for (int i = 0; i < D; i++)
            comp_add (&v[i], &cv[i], bh * a[i]);
          for (int i = 0; i < D; i++)
            comp_add (&q[i], &cq[i], ah * v[i]);
          accel (q, a);
        }
      for (int i = 0; i < D; i++)
        comp_add (&v[i], &cv[i], b[17] * h * a[i]);
    }
}

int
main (int argc, char **argv)
{
  if (argc != 4)
    {
      fprintf (stderr, "usage: kahanli8_loop H NSTEPS ROUNDS\n");
      return 1;
    }
  const double h = atof (argv[1]);
  const long nsteps = atol (argv[2]);
  const int rounds = atoi (argv[3]);
  double q[D], v[D], t[64];
  const int nr = rounds < 1 ? 1 : rounds > 64 ? 64 : rounds;
  for (int r = 0; r < nr; r++)
    {
      const double t0 = now ();
      run (h, nsteps, q, v);
      t[r] = (now () - t0) / nsteps;
    }
  /* the median: others share the machine */
  printf ("%.6f\n", 1e6 * median (t, nr));
  for (int i = 0; i < D; i++)
    printf ("%.17g\n", q[i]);
  for (int i = 0; i < D; i++)
    printf ("%.17g\n", v[i]);
  return 0;
}
