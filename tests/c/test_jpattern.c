/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* test_jpattern.c -- finite differences with the pattern of Df: the
   colouring of its columns (sym_pattern_colors), and Jacobians from one
   state per colour equal to those from one state per column, single and
   batched, at a fraction of the calls. */
#include "sym.h"
#include "testutil.h"

#include <string.h>

/* An FPU chain of D masses (fixed ends, V(r) = r^2/2 + r^4/4): f_q = p,
   f_p tridiagonal in q; rhs evaluates one state, rhs_batch several */
#define D 12
#define N (2 * D)

static long nstates;

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

static int
fpu_rhs (double t, const double *y, double *dy, void *u)
{
  (void) t;
  (void) u;
  nstates++;
  fpu (y, dy);
  return 0;
}

static int
fpu_batch (int k, const double *t, const double *y, double *dy, void *u)
{
  (void) t;
  (void) u;
  for (int j = 0; j < k; j++)
    fpu (y + (size_t) j * N, dy + (size_t) j * N);
  nstates += k;
  return 0;
}

/* Df's pattern: the identity in the q rows' p columns, a tridiagonal
   band in the p rows' q columns (compressed columns) */
static int colptr[N + 1], rowind[3 * D + D];

static void
fpu_pattern (void)
{
  int nz = 0;
  for (int j = 0; j < D; j++)   /* column q_j: rows p_{j-1}, p_j, p_{j+1} */
    {
      colptr[j] = nz;
      for (int i = j - 1; i <= j + 1; i++)
        if (i >= 0 && i < D)
          rowind[nz++] = D + i;
    }
  for (int j = 0; j < D; j++)   /* column p_j: row q_j */
    {
      colptr[D + j] = nz;
      rowind[nz++] = j;
    }
  colptr[N] = nz;
}

/* the chain as the core evaluates it: batched or not, with the pattern
   cp, ri and its colouring (nc colours) or none (nc = 0) */
static sym_eval
fpu_eval (int batch, const int *cp, const int *ri, const int *color, int nc)
{
  sym_system sys;
  memset (&sys, 0, sizeof sys);
  sys.dim = D;
  sys.rhs = fpu_rhs;
  sys.rhs_batch = batch ? fpu_batch : NULL;
  sys.jp_colptr = cp;
  sys.jp_rowind = ri;
  sys.jp_color = color;
  sys.jp_ncolors = nc;
  sym_eval ev;
  sym_eval_init (&ev, &sys);
  return ev;
}

/* no two columns of a colour share a row */
static int
valid_colors (int n, const int *cp, const int *ri, const int *color,
              int ncolors)
{
  for (int a = 0; a < n; a++)
    {
      if (color[a] < 0 || color[a] >= ncolors)
        return 0;
      for (int b = a + 1; b < n; b++)
        if (color[a] == color[b])
          for (int r = cp[a]; r < cp[a + 1]; r++)
            for (int s = cp[b]; s < cp[b + 1]; s++)
              if (ri[r] == ri[s])
                return 0;
    }
  return 1;
}

static void
check_colors (void)
{
  int color[N];
  fpu_pattern ();
  int nc = sym_pattern_colors (N, colptr, rowind, color);
  /* three for the band of q, and the p columns share them */
  CHECK (nc == 3 && valid_colors (N, colptr, rowind, color, nc),
         "FPU pattern: %d colours", nc);
  /* dense: a colour per column; diagonal: one colour */
  static int dcp[5], dri[16], icp[5], iri[4];
  for (int j = 0; j <= 4; j++)
    {
      dcp[j] = 4 * j;
      icp[j] = j;
    }
  for (int k = 0; k < 16; k++)
    dri[k] = k % 4;
  for (int k = 0; k < 4; k++)
    iri[k] = k;
  int c4[4];
  nc = sym_pattern_colors (4, dcp, dri, c4);
  CHECK (nc == 4 && valid_colors (4, dcp, dri, c4, nc), "dense: %d", nc);
  nc = sym_pattern_colors (4, icp, iri, c4);
  CHECK (nc == 1, "diagonal: %d colours", nc);
  /* invalid patterns */
  int bad[5] = { 0, 2, 1, 3, 4 };
  CHECK (sym_pattern_colors (4, bad, iri, c4) == -1, "decreasing colptr");
  int out[4] = { 0, 1, 7, 3 };
  CHECK (sym_pattern_colors (4, icp, out, c4) == -1, "row out of range");
  CHECK (sym_pattern_colors (0, icp, iri, c4) == -1, "n = 0");
  CHECK (sym_pattern_colors (4, NULL, iri, c4) == -1, "no colptr");
}

/* Df at a state of the chain by finite differences, without and with
   the pattern, one state at a time and batched: equal to the bit (a row
   of f depends only on its pattern's columns, so that stepping the other
   columns of a colour with it changes none of its arithmetic), with
   the pattern's zeros exact, from 3 states instead of N */
static void
check_jacobians (void)
{
  int color[N];
  fpu_pattern ();
  const int nc = sym_pattern_colors (N, colptr, rowind, color);
  double y[N], f0[N], df[2][N * N];
  for (int i = 0; i < N; i++)
    y[i] = 0.3 * sin (1.0 + i) + (i >= D ? 0.1 * i : 0.0);
  fpu (y, f0);
  for (int batch = 0; batch < 2; batch++)
    {
      long states[2];
      for (int pat = 0; pat < 2; pat++)
        {
          sym_eval ev = fpu_eval (batch, colptr, rowind, color,
                                  pat ? nc : 0);
          nstates = 0;
          int st = sym_jac (&ev, 0.0, y, f0, df[pat]);
          CHECK (st == SYM_SUCCESS, "sym_jac: %s", sym_status_name (st));
          states[pat] = nstates;
          CHECK (ev.st.cnt.nfd == (batch ? 1 : (pat ? nc : N)),
                 "batch %d, pattern %d: %ld calls for finite differences",
                 batch, pat, ev.st.cnt.nfd);
          sym_eval_free (&ev);
        }
      CHECK (states[0] == N && states[1] == nc,
             "batch %d: %ld and %ld states", batch, states[0], states[1]);
      CHECK (memcmp (df[0], df[1], sizeof df[0]) == 0,
             "batch %d: Df with the pattern differs", batch);
      /* the pattern's zeros: f_q does not depend on q */
      double z = 0.0;
      for (int i = 0; i < D; i++)
        for (int j = 0; j < D; j++)
          z = fmax (z, fabs (df[1][i + j * N]));
      CHECK (z == 0.0, "zeros of the pattern: %g", z);
    }
  /* a pattern that misses entries of Df leaves them out: the column of
     q_0 without its row p_1 */
  int cp2[N + 1], ri2[4 * D], c2[N], nz2 = 0;
  for (int k = 0; k < colptr[N]; k++)
    if (k != 1)                 /* column 0's rows: p_0, p_1 */
      ri2[nz2++] = rowind[k];
  cp2[0] = 0;
  for (int j = 1; j <= N; j++)
    cp2[j] = colptr[j] - 1;
  const int nc2 = sym_pattern_colors (N, cp2, ri2, c2);
  sym_eval ev = fpu_eval (0, cp2, ri2, c2, nc2);
  double dm[N * N];
  int st = sym_jac (&ev, 0.0, y, f0, dm);
  CHECK (st == SYM_SUCCESS && dm[(D + 1) + 0 * N] == 0.0
         && df[0][(D + 1) + 0 * N] != 0.0 && dm[D + 0 * N] == df[0][D],
         "a missing entry: %g (full %g)", dm[(D + 1) + 0 * N],
         df[0][(D + 1) + 0 * N]);
  sym_eval_free (&ev);
}

int
main (void)
{
  check_colors ();
  check_jacobians ();
  return tu_finish ("test_jpattern");
}
