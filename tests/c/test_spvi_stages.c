/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* test_spvi_stages.c -- odeSPVI's Newton systems by stage systems
   (staged.c) against the whole step system: the same fixed steps to
   round-off, dense and sparse, with finite differences (one state per
   column, or per colour of the pattern) and with the user's sparse Df,
   and the pairs without stages by their whole system, sparse;
   bounded energy over long runs; the stage systems' sizes (no matrix of
   size d^2 for a sparse Df); and the refusals. */
#include "sym.h"
#include "driver_util.h"
#include "testutil.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* An FPU chain of D masses, fixed ends, V(r) = r^2/2 + r^4/4 */
static int D;

static void
fpu (const double *y, double *dy)
{
  const double *q = y, *p = y + D;
  for (int i = 0; i < D; i++)
    {
      double rl = q[i] - (i > 0 ? q[i - 1] : 0.0);
      double rr = (i < D - 1 ? q[i + 1] : 0.0) - q[i];
      dy[i] = p[i];
      dy[D + i] = (rr + rr * rr * rr) - (rl + rl * rl * rl);
    }
}

static double
energy (const double *y)
{
  double e = 0.0;
  for (int i = 0; i <= D; i++)
    {
      double r = (i < D ? y[i] : 0.0) - (i > 0 ? y[i - 1] : 0.0);
      e += 0.5 * r * r + 0.25 * r * r * r * r;
      if (i < D)
        e += 0.5 * y[D + i] * y[D + i];
    }
  return e;
}

static int
fpu_rhs (double t, const double *y, double *dy, void *u)
{
  (void) t;
  (void) u;
  fpu (y, dy);
  return 0;
}

static int
fpu_batch (int k, const double *t, const double *y, double *dy, void *u)
{
  (void) t;
  (void) u;
  for (int j = 0; j < k; j++)
    fpu (y + (size_t) j * 2 * D, dy + (size_t) j * 2 * D);
  return 0;
}

/* Df's pattern: column j < D (q_j): rows D + j - 1 .. D + j + 1; column
   D + j (p_j): row j */
static int *colptr, *rowind, *color, ncolors;

static void
pattern (void)
{
  const int n = 2 * D;
  colptr = malloc ((n + 1) * sizeof (int));
  rowind = malloc (4 * (size_t) D * sizeof (int));
  color = malloc (n * sizeof (int));
  int e = 0;
  for (int j = 0; j < n; j++)
    {
      colptr[j] = e;
      if (j < D)
        {
          for (int i = j - 1; i <= j + 1; i++)
            if (i >= 0 && i < D)
              rowind[e++] = D + i;
        }
      else
        rowind[e++] = j - D;
    }
  colptr[n] = e;
  ncolors = sym_pattern_colors (n, colptr, rowind, color);
}

/* the user's sparse Df, times jscale (a wrong one), its first value
   jnan (NaN: a wrong one) */
static long ncsc;
static double jscale = 1.0, jnan = 0.0;

static int
fpu_jac_csc (double t, const double *y, sym_csc *df, void *u)
{
  (void) t;
  (void) u;
  const int n = 2 * D;
  ncsc++;
  if (sym_csc_reserve (df, colptr[n]))
    return -1;
  df->n = n;
  df->nnz = colptr[n];
  memcpy (df->colptr, colptr, (n + 1) * sizeof (int));
  memcpy (df->rowind, rowind, colptr[n] * sizeof (int));
  for (int j = 0; j < n; j++)
    for (int e = colptr[j]; e < colptr[j + 1]; e++)
      {
        const int i = rowind[e];
        if (j >= D)
          df->val[e] = 1.0;
        else
          {
            /* dF_i/dq_j, F_i = V'(r_{i+1}) - V'(r_i), r_i = q_i - q_{i-1} */
            const int k = i - D;
            double rl = y[k] - (k > 0 ? y[k - 1] : 0.0);
            double rr = (k < D - 1 ? y[k + 1] : 0.0) - y[k];
            double cl = 1.0 + 3.0 * rl * rl, cr = 1.0 + 3.0 * rr * rr;
            df->val[e] = k == j ? -(cl + cr) : k == j + 1 ? cl : cr;
          }
        df->val[e] *= jscale;
      }
  df->val[0] += jnan;
  return 0;
}

/* the last row of a run */
static double *ylast;
static double emax, e0;

static int
sink (double t, const double *y, void *u)
{
  (void) t;
  (void) u;
  memcpy (ylast, y, 2 * (size_t) D * sizeof (double));
  double e = energy (y);
  emax = fmax (emax, fabs (e - e0));
  return 0;
}

enum { DENSE_FD, SPARSE_FD, SPARSE_JAC };
/* the user's Df comes without the system's pattern */
static int no_pattern;

/* a fixed-step run of nsteps steps h of the pair (nq, nodes), Newton's
   systems as system, Df as kind; the last state into yl */
static int
run (int nq, int nodes, int system, int kind, int batch, double h,
     long nsteps, const double *y0, double *yl, sym_stats *st)
{
  sym_system sys;
  memset (&sys, 0, sizeof sys);
  sys.dim = D;
  sys.rhs = fpu_rhs;
  sys.rhs_batch = batch ? fpu_batch : NULL;
  if (kind != DENSE_FD)
    {
      sys.sparse = 1;
      if (! (kind == SPARSE_JAC && no_pattern))
        {
          sys.jp_colptr = colptr;
          sys.jp_rowind = rowind;
          sys.jp_color = color;
          sys.jp_ncolors = ncolors;
        }
      sys.jac_csc = kind == SPARSE_JAC ? fpu_jac_csc : NULL;
    }
  sym_spvi_opts so = { nq, nodes, SYM_MATRIX_AUTO, system,
                       kind != DENSE_FD, SYM_NONLINEAR_NEWTON };
  sym_method_opts mo;
  memset (&mo, 0, sizeof mo);
  mo.own = &so;
  sym_driver_opts o;
  memset (&o, 0, sizeof o);
  o.t0 = 0.0;
  o.tf = h * nsteps;
  o.h_fixed = h;
  o.nsteps_fixed = nsteps;
  o.refine = 1;
  o.output = sink;
  ylast = yl;
  e0 = energy (y0);
  emax = 0.0;
  return sym_integrate (sym_step_spvi, &sys, &mo, &o, y0, st);
}

static double
reldiff (const double *a, const double *b)
{
  double dm = 0.0, ym = 0.0;
  for (int i = 0; i < 2 * D; i++)
    {
      dm = fmax (dm, fabs (a[i] - b[i]));
      ym = fmax (ym, fabs (b[i]));
    }
  return dm / ym;
}

static void
start (double *y0)
{
  for (int i = 0; i < D; i++)
    {
      y0[i] = 0.3 * sin (3.0 * M_PI * (i + 1) / (D + 1));
      y0[D + i] = 0.2 * cos (M_PI * (i + 1) / (D + 1));
    }
}

/* every way of solving gives the fixed steps of the whole system */
static void
test_same_steps (void)
{
  /* the last three are no collocation pairs: the sparse whole system */
  static const int pairs[][2] = { { 4, 3 }, { 2, 1 }, { 3, 2 }, { 6, 5 },
                                  { 3, 3 }, { 2, 2 }, { 5, 3 } };
  D = 24;
  pattern ();
  double *y0 = malloc (2 * D * sizeof (double));
  double *yf = malloc (2 * D * sizeof (double));
  double *ys = malloc (2 * D * sizeof (double));
  start (y0);
  for (size_t p = 0; p < sizeof pairs / sizeof pairs[0]; p++)
    {
      const int nq = pairs[p][0], nd = pairs[p][1];
      sym_stats sf, ss;
      CHECK (run (nq, nd, SYM_SYSTEM_FULL, DENSE_FD, 0, 0.05, 40, y0, yf,
                  &sf) == SYM_DONE, "full (%d,%d)", nq, nd);
      for (int kind = DENSE_FD; kind <= SPARSE_JAC; kind++)
        for (int batch = 0; batch < 2; batch++)
          {
            ncsc = 0;
            CHECK (run (nq, nd, nq - 1 == nd ? SYM_SYSTEM_STAGES
                                              : SYM_SYSTEM_AUTO, kind,
                        batch, 0.05, 40, y0, ys, &ss) == SYM_DONE,
                   "stages (%d,%d) kind %d", nq, nd, kind);
            double r = reldiff (ys, yf);
            CHECK (r <= 1e-12, "(%d,%d) kind %d batch %d: stages differ "
                   "from the whole system by %.3g", nq, nd, kind, batch, r);
            /* (its probe: f at a stepped state, and at the point) */
            CHECK (kind != SPARSE_JAC || (ncsc > 0 && ss.cnt.nfd <= 2
                                          && ! ss.jac_dropped),
                   "the user's sparse Df served (%ld calls, %ld fd)", ncsc,
                   ss.cnt.nfd);
            /* a Jacobian by colours costs ncolors calls, not 2d */
            if (kind == SPARSE_FD && ! batch)
              CHECK (ss.cnt.nfd <= (ncolors + 1) * ss.cnt.njac
                                   + (ncolors + 1) * ss.cnt.nlu,
                     "colours: %ld fd calls for %ld LUs", ss.cnt.nfd,
                     ss.cnt.nlu);
          }
    }
  free (y0);
  free (yf);
  free (ys);
  free (colptr);
  free (rowind);
  free (color);
}

/* energy bounded over a long staged run of a sparse chain */
static void
test_energy (void)
{
  D = 64;
  pattern ();
  double *y0 = malloc (2 * D * sizeof (double));
  double *y1 = malloc (2 * D * sizeof (double));
  start (y0);
  sym_stats st;
  CHECK (run (4, 3, SYM_SYSTEM_AUTO, SPARSE_FD, 0, 0.1, 20000, y0, y1, &st)
         == SYM_DONE, "long run");
  CHECK (emax <= 1e-9 * e0, "energy error %.3g of %.3g", emax, e0);
  /* simplified Newton: a matrix (2 stage LUs) kept over several steps */
  CHECK (st.cnt.nlu / 2 < st.cnt.nsteps / 3, "%ld LUs in %ld steps",
         st.cnt.nlu, st.cnt.nsteps);
  free (y0);
  free (y1);
  free (colptr);
  free (rowind);
  free (color);
}

/* a long chain: the stage systems stay sparse (ASan would refuse the
   8 (6d)^2 bytes = 86 GB of the whole system) */
static void
test_large (void)
{
  D = 20000;
  pattern ();
  double *y0 = malloc (2 * D * sizeof (double));
  double *y1 = malloc (2 * D * sizeof (double));
  start (y0);
  sym_stats st;
  CHECK (run (4, 3, SYM_SYSTEM_AUTO, SPARSE_FD, 1, 0.1, 5, y0, y1, &st)
         == SYM_DONE, "large run");
  CHECK (fabs (energy (y1) - e0) <= 1e-10 * e0, "energy %.17g vs %.17g",
         energy (y1), e0);
  free (y0);
  free (y1);
  free (colptr);
  free (rowind);
  free (color);
}

static void
test_refusals (void)
{
  D = 4;
  pattern ();
  double y0[8], y1[8];
  start (y0);
  sym_stats st;
  /* stages need a pair n - 1 = m; a sparse Df, no whole dense system */
  CHECK (run (3, 3, SYM_SYSTEM_STAGES, DENSE_FD, 0, 0.1, 2, y0, y1, &st)
         == SYM_EBADINPUT, "stages of (3,3)");

  CHECK (run (4, 3, SYM_SYSTEM_FULL, SPARSE_FD, 0, 0.1, 2, y0, y1, &st)
         == SYM_EBADINPUT, "sparse, full system");
  free (colptr);
  free (rowind);
  free (color);
}

/* a wrong sparse Df (a million times too large, or with a NaN) is
   dropped for finite differences on its own pattern: the run's steps are
   those of the right one */
static void
test_wrong_jac (void)
{
  D = 16;
  pattern ();
  double y0[32], yr[32], yw[32];
  start (y0);
  sym_stats st;
  CHECK (run (4, 3, SYM_SYSTEM_STAGES, SPARSE_JAC, 0, 0.05, 40, y0, yr, &st)
         == SYM_DONE, "right Df");
  for (int c = 0; c < 4; c++)
    {
      /* with the system's pattern and without (its own then) */
      no_pattern = c >= 2;
      jscale = c % 2 ? 1.0 : 1e6;
      jnan = c % 2 ? NAN : 0.0;
      int s = run (4, 3, SYM_SYSTEM_STAGES, SPARSE_JAC, 0, 0.05, 40, y0, yw,
                   &st);
      CHECK (s == SYM_DONE && st.jac_dropped, "wrong Df %d: %s, dropped %d",
             c, sym_status_name (s), st.jac_dropped);
      CHECK (reldiff (yw, yr) <= 1e-12, "wrong Df %d: %.3g from the right "
             "one's steps", c, reldiff (yw, yr));
    }
  jscale = 1.0;
  jnan = 0.0;
  no_pattern = 0;
  free (colptr);
  free (rowind);
  free (color);
}

/* every allocation of a staged run, KLU's included, fails cleanly:
   SYM_ENOMEM and nothing left allocated */
static void
test_alloc_failure (void)
{
  D = 6;
  pattern ();
  double y0[12], y1[12];
  start (y0);
  /* (3,3): the whole system, sparse */
  for (int kind = DENSE_FD; kind <= SPARSE_JAC + 2; kind++)
    {
      const int whole = kind > SPARSE_JAC;
      long k;
      sym_set_allocator (drv_counting_alloc, drv_counting_free);
      for (k = 1; k < 100000; k++)
        {
          sym_stats st;
          drv_alloc_count = drv_alloc_live = 0;
          drv_alloc_fail_at = k;
          ylast = y1;
          int s = whole ? run (3, 3, SYM_SYSTEM_AUTO, kind - 2, 0, 0.1, 3,
                               y0, y1, &st)
                        : run (4, 3, SYM_SYSTEM_STAGES, kind, 0, 0.1, 3, y0,
                               y1, &st);
          CHECK (drv_alloc_live == 0, "kind %d: %ld blocks left with "
                 "allocation %ld failing", kind, drv_alloc_live, k);
          if (drv_alloc_count < k)
            {
              CHECK (s == SYM_DONE, "kind %d: %s with no failure", kind,
                     sym_status_name (s));
              break;
            }
          /* (the user's Df callback reports its own failure) */
          CHECK (s == SYM_ENOMEM
                 || ((whole ? kind - 2 : kind) == SPARSE_JAC
                     && s == SYM_ECALLBACK),
                 "kind %d: %s with allocation %ld failing", kind,
                 sym_status_name (s), k);
        }
      sym_set_allocator (NULL, NULL);
      CHECK (k > 10 && k < 100000, "kind %d: %ld allocations", kind, k - 1);
    }
  free (colptr);
  free (rowind);
  free (color);
}

/* a stepper allocated without want_dense keeps no dense output's data:
   dense () refuses */
static void
test_no_dense (void)
{
  D = 3;
  double y0[6], y1[6], yd[6];
  start (y0);
  sym_system sys;
  memset (&sys, 0, sizeof sys);
  sys.dim = D;
  sys.rhs = fpu_rhs;
  sym_eval ev;
  sym_eval_init (&ev, &sys);
  sym_spvi_opts so = { 4, 3, SYM_MATRIX_AUTO, SYM_SYSTEM_STAGES, 0,
                       SYM_NONLINEAR_NEWTON };
  sym_method_opts mo;
  memset (&mo, 0, sizeof mo);
  mo.own = &so;
  for (int want = 0; want < 2; want++)
    {
      mo.want_dense = want;
      int st;
      void *s = sym_step_spvi->alloc (D, &mo, &st);
      CHECK (s && sym_step_spvi->step (s, &ev, 0.0, 0.1, 0.1, y0, y1, NULL)
             == SYM_SUCCESS, "a step");
      sym_step_spvi->accept (s);
      st = sym_step_spvi->dense (s, &ev, 0.05, yd);
      CHECK (st == (want ? SYM_SUCCESS : SYM_EBADINPUT), "dense (want %d): "
             "%s", want, sym_status_name (st));
      sym_step_spvi->free (s);
    }
  sym_eval_free (&ev);
}

int
main (void)
{
  test_same_steps ();
  test_energy ();
  test_large ();
  test_refusals ();
  test_wrong_jac ();
  test_no_dense ();
  test_alloc_failure ();
  return tu_finish ("test_spvi_stages");
}
