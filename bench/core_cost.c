/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* core_cost.c -- what the integration core costs without Octave: the
   dense LU of small systems (the core's loops against LAPACK's), and a
   step of odeSPVI (4, 3) on Kepler's problem with C callbacks, alone and
   as a member of an ensemble.  Writes Markdown to the file given (or to
   standard output).  Built and run by `make bench-core`. */
#define _POSIX_C_SOURCE 199309L   /* clock_gettime */
#include "sym.h"
#include "numerics/numerics.h"
#include "tuning.h"
#include "timing.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define ROUNDS 5
#define PI 3.14159265358979323846

/* ------------------------------------------------------------ LU */

/* one factorisation and one solve of a copy of A, by the core's loops
   (t[0]) and by LAPACK through the core's wrappers (t[1]): the least of
   ROUNDS rounds, the two called in turns (a threaded BLAS leaves its
   threads spinning for a while after a call, which slows what follows
   on a machine of two cores: both get the same share of that) */
static void
lu_time (int n, const double *A, double t[2])
{
  const size_t nn = (size_t) n * n;
  double *F = malloc (nn * sizeof (double));
  double *b = malloc ((size_t) n * sizeof (double));
  int *ip = malloc ((size_t) n * sizeof (int));
  const long reps = 2000000 / (long) nn + 100;
  t[0] = t[1] = INFINITY;
  for (int r = 0; r < ROUNDS; r++)
    for (int own = 1; own >= 0; own--)
      {
        const double t0 = now ();
        for (long k = 0; k < reps; k++)
          {
            memcpy (F, A, nn * sizeof (double));
            for (int i = 0; i < n; i++)
              b[i] = 1.0;
            if (own)
              {
                sym_lu_small_factor (n, F, ip);
                sym_lu_small_solve (n, F, ip, b);
              }
            else
              {
                sym_getrf (0, n, F, ip);
                sym_getrs (0, n, F, ip, b);
              }
          }
        const double tr = (now () - t0) / reps;
        t[! own] = tr < t[! own] ? tr : t[! own];
      }
  free (F);
  free (b);
  free (ip);
}

/* ------------------------------------------------------------ Kepler */

static long nstates;

static int
kepler (double t, const double *y, double *dy, void *user)
{
  (void) t;
  (void) user;
  const double r2 = y[0] * y[0] + y[1] * y[1], r3 = r2 * sqrt (r2);
  dy[0] = y[2];
  dy[1] = y[3];
  dy[2] = -y[0] / r3;
  dy[3] = -y[1] / r3;
  nstates++;
  return 0;
}

static int
kepler_batch (int k, const double *t, const double *y, double *dy,
              void *user)
{
  for (int j = 0; j < k; j++)
    kepler (t[j], y + 4 * j, dy + 4 * j, user);
  return 0;
}

/* Df of Kepler (4-by-4, column-major), as a compiled FCN's Hessian
   gives it */
static int
kepler_jac (double t, const double *y, double *df, void *user)
{
  (void) t;
  (void) user;
  const double r2 = y[0] * y[0] + y[1] * y[1], r = sqrt (r2);
  const double r3 = r2 * r, r5 = r3 * r2;
  memset (df, 0, 16 * sizeof (double));
  df[0 + 4 * 2] = 1.0;
  df[1 + 4 * 3] = 1.0;
  df[2 + 4 * 0] = -1.0 / r3 + 3.0 * y[0] * y[0] / r5;
  df[2 + 4 * 1] = 3.0 * y[0] * y[1] / r5;
  df[3 + 4 * 0] = df[2 + 4 * 1];
  df[3 + 4 * 1] = -1.0 / r3 + 3.0 * y[1] * y[1] / r5;
  return 0;
}

static int
kepler_rhs_jac (double t, const double *y, double *dy, double *df,
                void *user)
{
  kepler (t, y, dy, user);
  return kepler_jac (t, y, df, user);
}

/* K members (K = 1: one sym_integrate), eccentricities 0.05 to 0.6,
   nsteps fixed steps of 2 pi / 100, NewtonMatrix newmat; with_df: f and
   Df by separate callbacks and no batch one (what a compiled FCN gives
   the core), else f alone with its batch form: the least time per
   member-step of ROUNDS runs, and the states evaluated per member-step */
static double
spvi_time (int K, long nsteps, int newmat, int with_df, double *states)
{
  sym_system sys;
  memset (&sys, 0, sizeof sys);
  sys.dim = 2;
  sys.rhs = kepler;
  if (with_df)
    {
      sys.jac = kepler_jac;
      sys.rhs_jac = kepler_rhs_jac;
    }
  else
    sys.rhs_batch = kepler_batch;
  sym_spvi_opts so;
  memset (&so, 0, sizeof so);
  so.q_dofs = 4;
  so.nodes = 3;
  so.newton_matrix = newmat;
  sym_method_opts mo;
  memset (&mo, 0, sizeof mo);
  mo.own = &so;
  const double h = 2.0 * PI / 100.0;
  double *y0 = malloc (4 * (size_t) K * sizeof (double));
  sym_driver_opts *d = calloc ((size_t) K, sizeof *d);
  int *status = calloc ((size_t) K, sizeof (int));
  for (int j = 0; j < K; j++)
    {
      const double e = 0.05 + 0.55 * j / (K > 1 ? K - 1 : 1);
      y0[4 * j] = 1.0 - e;
      y0[4 * j + 1] = 0.0;
      y0[4 * j + 2] = 0.0;
      y0[4 * j + 3] = sqrt ((1.0 + e) / (1.0 - e));
      d[j].tf = nsteps * h;
      d[j].h_fixed = h;
      d[j].refine = 1;
    }
  double best = INFINITY;
  for (int r = 0; r < ROUNDS; r++)
    {
      nstates = 0;
      int ok;
      const double t0 = now ();
      if (K == 1)
        ok = sym_integrate (sym_step_spvi, &sys, &mo, d, y0, NULL) == SYM_DONE;
      else
        {
          sym_ensemble_opts e;
          memset (&e, 0, sizeof e);
          e.members = K;
          e.y0 = y0;
          e.dopts = d;
          e.status = status;
          e.max_live = SYM_ENS_LIVE;
          ok = sym_ensemble (sym_step_spvi, &sys, &mo, &e) == SYM_SUCCESS;
          for (int j = 0; j < K; j++)
            ok = ok && status[j] == SYM_DONE;
        }
      const double t = (now () - t0) / ((double) K * nsteps);
      if (! ok)
        {
          fprintf (stderr, "core_cost: a Kepler run failed\n");
          exit (1);
        }
      best = t < best ? t : best;
      *states = (double) nstates / ((double) K * nsteps);
    }
  free (y0);
  free (d);
  free (status);
  return best;
}

/* the last row of a run */
static int
last_row (double t, const double *y, void *user)
{
  (void) t;
  memcpy (user, y, 4 * sizeof (double));
  return 0;
}

/* (5, 4) on Kepler e = 0.6 over 200 periods in 113137 fixed steps (the
   problem of the plain Gauss loop, bench/gauss_loop.c), no batch callback:
   the least time per step of ROUNDS runs, the states per step and the end
   point's distance from y0 */
static double
spvi54_time (int nonlinear, int system, double *states, double *err)
{
  sym_system sys;
  memset (&sys, 0, sizeof sys);
  sys.dim = 2;
  sys.rhs = kepler;
  sym_spvi_opts so;
  memset (&so, 0, sizeof so);
  so.q_dofs = 5;
  so.nodes = 4;
  so.nonlinear = nonlinear;
  so.system = system;
  sym_method_opts mo;
  memset (&mo, 0, sizeof mo);
  mo.own = &so;
  const long nsteps = 113137;
  const double e = 0.6, y0[4] = { 1.0 - e, 0.0, 0.0, sqrt ((1.0 + e) / (1.0 - e)) };
  double best = INFINITY;
  for (int r = 0; r < ROUNDS; r++)
    {
      sym_driver_opts d;
      memset (&d, 0, sizeof d);
      d.tf = 400.0 * PI;
      d.h_fixed = d.tf / nsteps;
      d.refine = 1;
      double y[4];
      d.output = last_row;
      d.output_user = y;
      nstates = 0;
      const double t0 = now ();
      const int ok = sym_integrate (sym_step_spvi, &sys, &mo, &d, y0, NULL)
                     == SYM_DONE;
      const double t = (now () - t0) / nsteps;
      if (! ok)
        {
          fprintf (stderr, "core_cost: a (5, 4) run failed\n");
          exit (1);
        }
      best = t < best ? t : best;
      *states = (double) nstates / nsteps;
      double e2 = 0.0;
      for (int i = 0; i < 4; i++)
        e2 += (y[i] - y0[i]) * (y[i] - y0[i]);
      *err = sqrt (e2);
    }
  return best;
}

int
main (int argc, char **argv)
{
  FILE *f = argc > 1 ? fopen (argv[1], "w") : stdout;
  if (! f)
    {
      perror (argv[1]);
      return 1;
    }
  fprintf (f, "# The core's costs, without Octave\n\n"
           "Written by bench/core_cost.c (`make bench-core`); times are "
           "the least of %d rounds on a machine that may have been busy.\n\n",
           ROUNDS);

  fprintf (f, "## Dense LU of n unknowns: one factorisation and one solve\n\n"
           "Random matrices; the core takes its own loops up to "
           "SYM_LU_SMALL = %d unknowns, LAPACK (with the BLAS Octave "
           "links, its threads as that BLAS sets them) above; the two "
           "are timed in turns.\n\n"
           "| n | own loops (us) | LAPACK (us) |\n|---|---|---|\n",
           SYM_LU_SMALL);
  const int sizes[] = { 4, 8, 12, 16, 24, 32, 40, 48, 64 };
  unsigned long seed = 7;
  for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++)
    {
      const int n = sizes[i];
      double *A = malloc ((size_t) n * n * sizeof (double));
      for (int k = 0; k < n * n; k++)
        {
          seed = seed * 6364136223846793005UL + 1442695040888963407UL;
          A[k] = (double) (seed >> 11) / 9007199254740992.0 - 0.5;
        }
      double t[2];
      lu_time (n, A, t);
      fprintf (f, "| %d | %.3f | %.3f |\n", n, 1e6 * t[0], 1e6 * t[1]);
      fflush (f);
      free (A);
    }

  fprintf (f, "\n## odeSPVI (4, 3), Kepler, fixed step 2 pi/100, C "
           "callbacks\n\n"
           "One run of 20000 steps (e = 0.05), or an ensemble of 1000 "
           "members (e from 0.05 to 0.6) of 100 steps each, %d at once; "
           "NewtonMatrix as the gateways pass it (\"auto\" takes \"new\" "
           "with a batch callback); f with its batch form and finite-"
           "difference Df, or (\"f and Df\") f and the exact Df by separate "
           "callbacks and no batch form, what a compiled FCN gives the "
           "core.\n\n"
           "| run | NewtonMatrix | us per member-step | states of f per "
           "member-step |\n|---|---|---|---|\n", SYM_ENS_LIVE);
  const struct { const char *name; int K; long steps; } runs[] = {
    { "one run", 1, 20000 }, { "1000 members", 1000, 100 } };
  const struct { const char *name; int mode; } modes[] = {
    { "auto", SYM_MATRIX_AUTO }, { "kept", SYM_MATRIX_KEPT } };
  for (int m = 0; m < 2; m++)
    for (int r = 0; r < 2; r++)
      {
        double states = 0.0;
        const double t = spvi_time (runs[r].K, runs[r].steps, modes[m].mode,
                                    0, &states);
        fprintf (f, "| %s | %s | %.3f | %.1f |\n", runs[r].name,
                 modes[m].name, 1e6 * t, states);
        fflush (f);
      }
  {
    double states = 0.0;
    const double t = spvi_time (1, 20000, SYM_MATRIX_AUTO, 1, &states);
    fprintf (f, "| one run, f and Df | auto | %.3f | %.1f |\n", 1e6 * t,
             states);
    fflush (f);
  }

  fprintf (f, "\n## odeSPVI (5, 4), Kepler e = 0.6, 200 periods, 113137 "
           "fixed steps, C callback\n\n"
           "NonlinearSolver and NewtonSystem; no batch callback, so Newton "
           "keeps its matrix (\"kept\").\n\n"
           "| NonlinearSolver | NewtonSystem | us per step | states of f "
           "per step | end error |\n|---|---|---|---|---|\n");
  const struct { const char *nl, *sy; int n, s; } nls[] = {
    { "newton", "full", SYM_NONLINEAR_NEWTON, SYM_SYSTEM_FULL },
    { "newton", "stages", SYM_NONLINEAR_NEWTON, SYM_SYSTEM_STAGES },
    { "fixedpoint", "(stages)", SYM_NONLINEAR_FIXEDPOINT, SYM_SYSTEM_AUTO } };
  for (size_t i = 0; i < sizeof nls / sizeof nls[0]; i++)
    {
      double states = 0.0, err = 0.0;
      const double t = spvi54_time (nls[i].n, nls[i].s, &states, &err);
      fprintf (f, "| %s | %s | %.3f | %.1f | %.2e |\n", nls[i].nl, nls[i].sy,
               1e6 * t, states, err);
      fflush (f);
    }
  if (f != stdout)
    fclose (f);
  return 0;
}
