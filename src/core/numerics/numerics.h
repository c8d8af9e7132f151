/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* numerics.h -- internal to the core: dense LU, Newton's iteration,
   polynomials (Lagrange, Hermite, Legendre) and Gauss quadrature, and
   small vector helpers. */
#ifndef SYM_NUMERICS_H
#define SYM_NUMERICS_H

#include "../sym.h"

/* fmax (m, x) for an m that is not NaN (a NaN x leaves m), inline: the
   running maxima of the hot loops, where the library call costs */
static inline double
sym_fmax_acc (double m, double x)
{
  return x > m ? x : m;
}

/* ---------------------------------------------------------------- vectors */
double sym_norm_inf (int n, const double *v);
int sym_same_vec (int n, const double *a, const double *b);
/* the end of the last step (of size h) and the start of this one, within
   a few ulps */
int sym_same_time (double a, double b, double h);
/* steps of the same size up to the round-off of fixed steps
   (SYM_SAME_STEP) */
int sym_same_step (double h, double hprev);

/* ---------------------------------------------------------------- LAPACK */
/* fn (arg) on the stack of the core's caller: at once, unless the core
   runs an ensemble's member on a stack of its own (driver/coroutine.c),
   which then waits while its caller makes the call */
void sym_outside (void (*fn) (void *), void *arg);

/* The LAPACK and BLAS routines the core calls (lapack.c), through
   sym_outside; they return LAPACK's info.  cplx: complex*16 arrays as
   (re, im) pairs of doubles (zgetrf, zgetrs) */
int sym_getrf (int cplx, int n, double *a, int *ipiv);
int sym_getrs (int cplx, int n, const double *a, const int *ipiv, double *b);
/* c = a b (m-by-k times k-by-n) */
void sym_gemm (int m, int n, int k, const double *a, int lda,
               const double *b, int ldb, double *c, int ldc);
/* the eigenvalues wr + i wi and right eigenvectors vr (n-by-n) of a
   (destroyed): dgeev */
int sym_geev (int n, double *a, double *wr, double *wi, double *vr,
              double *work, int lwork);
/* the eigenvalues (into d) and eigenvectors z (n-by-n) of the symmetric
   tridiagonal matrix of diagonal d and off-diagonal e: dstev */
int sym_stev (int n, double *d, double *e, double *z, double *work);

/* ---------------------------------------------------------------- LU */
/* Dense LU with reuse (LAPACK dgetrf/dgetrs): factor once, solve many
   times. */
typedef struct {
  int n;
  double *a;      /* n*n: the matrix, overwritten by its LU factors */
  int *ipiv;
  int factored;   /* 1 after a successful sym_lu_factor */
} sym_lu;

int sym_lu_init (sym_lu *lu, int n);          /* allocates; SYM_ENOMEM */
void sym_lu_free (sym_lu *lu);
/* SYM_SINGULAR if singular or not finite */
int sym_lu_factor (sym_lu *lu, sym_counters *c);
int sym_lu_solve (sym_lu *lu, double *b, sym_counters *c); /* b <- A \ b */
/* the loops sym_lu takes up to SYM_LU_SMALL unknowns (for any n): the
   pivots dgetrf takes and its factors up to round-off; 0, or the 1-based
   column of a zero pivot */
int sym_lu_small_factor (int n, double *a, int *ipiv);
void sym_lu_small_solve (int n, const double *a, const int *ipiv, double *b);

/* ---------------------------------------------------------------- sparse */
/* (sparse.c) a and b have the same n, colptr and rowind */
int sym_csc_same_pattern (const sym_csc *a, const sym_csc *b);
/* dst = src (dst grows as needed) */
int sym_csc_copy (sym_csc *dst, const sym_csc *src);
/* y = A x (A n-by-n, x and y n values, not overlapping) */
void sym_csc_mv (const sym_csc *a, const double *x, double *y);
/* the square block A(r0 : r0+nb-1, c0 : c0+nb-1) into dst (grows) */
int sym_csc_block (const sym_csc *a, int r0, int c0, int nb, sym_csc *dst);

/* The linear systems of Newton's staged solves (stagelu.c):
   M = I - gamma J, gamma = gr + i gi, J n-by-n real, dense (column-major,
   leading dimension ld) or sparse (sym_csc).  gi = 0: a real LU (LAPACK
   dgetrf, or KLU), else a complex one (zgetrf, or KLU's complex
   factorization); the sparse symbolic analysis is kept while the pattern
   of J stays the same.  Every allocation, KLU's included, goes through
   sym_malloc. */
typedef struct {
  int n;
  int sparse;        /* J comes as sym_csc */
  int cplx;          /* the factors are complex (gi != 0) */
  int factored;
  double *a;         /* dense: n*n real or complex (interleaved) */
  int *ipiv;
  void *klu;         /* sparse: the KLU objects (stagelu.c) */
} sym_stage_lu;

int sym_stage_lu_init (sym_stage_lu *s, int n, int sparse);
void sym_stage_lu_free (sym_stage_lu *s);   /* safe on a zeroed struct */
/* Factor I - (gr + i gi) J (J: dense with ld, or Js when sparse);
   SYM_SINGULAR when singular or not finite, SYM_ENOMEM; counts nlu */
int sym_stage_lu_factor (sym_stage_lu *s, double gr, double gi,
                         const double *J, int ld, const sym_csc *Js,
                         sym_counters *c);
/* b <- M \ b: n doubles (real factors) or n complex values as (re, im)
   pairs, 2n doubles (complex factors); counts nsolve */
int sym_stage_lu_solve (sym_stage_lu *s, double *b, sym_counters *c);

/* ---------------------------------------------------------------- Newton */
/* Newton's method on G(x) = 0 (newton.c).  Simplified (the default mode):
   the matrix is kept (and its LU reused) while convergence is fast; the
   contraction rate theta is estimated every iteration; the iteration
   stops when theta/(1-theta) |dx| <= tol (|.| the max norm of dx./scale),
   or when |dx| is at round-off.  A slow or diverging iteration with a
   stale matrix asks for a fresh one and goes on; with a fresh one it fails
   with SYM_NEWTON_FAIL (also for a singular matrix).  Full: a new matrix
   at every iterate.  A failed callback ends the solve with its own
   status. */
typedef struct {
  /* r = G(x) */
  int (*residual) (void *ctx, const double *x, double *r);
  /* A = G'(x) (or a good approximation), n-by-n column-major */
  int (*matrix) (void *ctx, const double *x, double *a);
  void *ctx;
  /* optional, for a problem that factors its own matrix (NULL: matrix
     and a dense LU): factor G'(x), or a good approximation (SYM_SINGULAR
     when singular); solve b <- G'(x) \ b with those factors */
  int (*factor) (void *ctx, const double *x, sym_counters *c);
  int (*solve) (void *ctx, double *b, sym_counters *c);
  /* optional (NULL: residual and solve): dx = -A^-1 G(x) at once, for a
     fixed matrix A whose correction is a map of x (a fixed point) */
  int (*correction) (void *ctx, const double *x, double *dx);
} sym_newton_problem;

enum { SYM_NEWTON_SIMPLIFIED = 0, SYM_NEWTON_FULL = 1 };

typedef struct {
  int n;
  sym_lu lu;        /* allocated at its first use: not for a problem
                       with its own factor and solve */
  int mode;         /* SYM_NEWTON_SIMPLIFIED or _FULL */
  int have_matrix;  /* lu holds a factored matrix that may be reused */
  int fresh;        /* that matrix was computed in this solve */
  double tol;       /* stop tolerance on the scaled max norm */
  int maxit;        /* iterations per solve */
  double eta;       /* theta/(1-theta) carried from the last solve */
  double theta;     /* last contraction rate */
  int iters;        /* iterations of the last solve */
  /* Exact first corrections (quad: every solve starts with a new matrix
     at its start x, so that the first correction is Newton's own): the
     error left after it is about kq |dx_1|^2, kq measured as |dx_2| /
     |dx_1|^2; a solve then stops after one correction when
     SYM_NEWTON_QUAD_SAFE kq |dx_1|^2 <= tol, at most SYM_NEWTON_QUAD_AGE
     times in a row before a second correction measures again.  one: the
     last solve stopped so; kq_new: it measured kq.  kq_ok = 0 forgets
     kq (a new h, a new problem). */
  int quad;
  double kq;
  int kq_ok, kq_age, one, kq_new;
  double *r, *dx, *x0;   /* work; x0: the start of the last solve */
} sym_newton;

/* tolerance and iterations from opts (0: the defaults) */
int sym_newton_init (sym_newton *nw, int n, const sym_method_opts *opts);
void sym_newton_free (sym_newton *nw);
/* nw->lu allocated (SYM_ENOMEM) */
int sym_newton_lu (sym_newton *nw);
/* Forget the kept matrix (e.g. after a change of h). */
void sym_newton_invalidate (sym_newton *nw);
/* Solve G(x) = 0 from the start x (overwritten by the solution) in nw's
   mode.  scale[i] > 0 weights component i in the stopping norm. */
int sym_newton_solve (sym_newton *nw, const sym_newton_problem *p, double *x,
                      const double *scale, sym_counters *c);
/* One correction from x with the factored matrix: nw->dx = -A^{-1} G(x)
   (not applied: the caller adds it); *dxn its scaled max norm, NaN or Inf
   when not finite (scale NULL: not computed) */
int sym_newton_dx (sym_newton *nw, const sym_newton_problem *p,
                   const double *x, const double *scale, sym_counters *c,
                   double *dxn);
/* x += nw->dx, counted as a Newton iteration */
void sym_newton_apply (sym_newton *nw, double *x, sym_counters *c);

/* ---------------------------------------------------------------- polynomials */
/* Barycentric weights of the points x_0..x_{np-1} */
void sym_bary_weights (int np, const double *x, double *bw);
/* The Lagrange basis c_i = L_i(x) through the points xb (barycentric
   weights bw), by the first barycentric form (backward stable, also
   outside the points); for many x at the same points */
void sym_lagrange_basis (int np, const double *xb, const double *bw,
                         double x, double *c);
/* The same c_i at t as products of ratios: for one t */
void sym_lagrange_weights (int np, const double *ts, double t, double *c);
/* Weights w_l of v_new = sum_{l<L} w_l v_{-l}: the polynomial of degree
   L - 1 through L equally spaced values, one spacing further (exact
   integers, L <= 4) */
const double *sym_extrap_weights (int L);
/* The cubic Hermite interpolant through (y0, f0) at t and (y1, f1) at
   t + h, at t + th h (n components) */
void sym_hermite (int n, double h, double th, const double *y0,
                  const double *y1, const double *f0, const double *f1,
                  double *y);

/* ---------------------------------------------------------------- quadrature */
/* Gauss-Legendre nodes z[0..m-1] (ascending, in [-1, 1]) and weights w,
   by Golub-Welsch (LAPACK dstev).  Returns 0 or a status < 0. */
int sym_gauss_legendre (int m, double *z, double *w);
/* Legendre polynomials l_0..l_{n-1} and their derivatives at x:
   l[i] = l_i(x), dl[i] = l_i'(x). */
void sym_legendre (int n, double x, double *l, double *dl);

#endif
