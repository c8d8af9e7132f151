/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* lapack.c -- the LAPACK and BLAS routines the core calls, each made on
   the stack of the core's caller (sym_outside).  A member of an ensemble
   runs on a stack of its own of some hundred KB; a threaded BLAS can
   take megabytes of stack in one factorization (OpenBLAS's parallel
   dgetrf), and calls from there would overflow it. */
#include "numerics.h"

extern void dgetrf_ (const int *m, const int *n, double *a, const int *lda,
                     int *ipiv, int *info);
extern void dgetrs_ (const char *trans, const int *n, const int *nrhs,
                     const double *a, const int *lda, const int *ipiv,
                     double *b, const int *ldb, int *info);
/* complex*16 arrays as (re, im) pairs of doubles */
extern void zgetrf_ (const int *m, const int *n, double *a, const int *lda,
                     int *ipiv, int *info);
extern void zgetrs_ (const char *trans, const int *n, const int *nrhs,
                     const double *a, const int *lda, const int *ipiv,
                     double *b, const int *ldb, int *info);
extern void dgemm_ (const char *ta, const char *tb, const int *m,
                    const int *n, const int *k, const double *alpha,
                    const double *a, const int *lda, const double *b,
                    const int *ldb, const double *beta, double *c,
                    const int *ldc);
extern void dgeev_ (const char *jobvl, const char *jobvr, const int *n,
                    double *a, const int *lda, double *wr, double *wi,
                    double *vl, const int *ldvl, double *vr, const int *ldvr,
                    double *work, const int *lwork, int *info);
extern void dstev_ (const char *jobz, const int *n, double *d, double *e,
                    double *z, const int *ldz, double *work, int *info);

/* the arguments of one call, and its info */
typedef struct {
  int n, m, k, lda, ldb, ldc, lwork, info, cplx;
  double *a, *b, *c, *d, *e, *wr, *wi, *work;
  const double *ca, *cb;
  int *ipiv;
  const int *cipiv;
} call_args;

static void
run_getrf (void *p)
{
  call_args *x = p;
  if (x->cplx)
    zgetrf_ (&x->n, &x->n, x->a, &x->n, x->ipiv, &x->info);
  else
    dgetrf_ (&x->n, &x->n, x->a, &x->n, x->ipiv, &x->info);
}

int
sym_getrf (int cplx, int n, double *a, int *ipiv)
{
  call_args x = { .n = n, .cplx = cplx, .a = a, .ipiv = ipiv };
  sym_outside (run_getrf, &x);
  return x.info;
}

static void
run_getrs (void *p)
{
  call_args *x = p;
  const int one = 1;
  if (x->cplx)
    zgetrs_ ("N", &x->n, &one, x->ca, &x->n, x->cipiv, x->b, &x->n,
             &x->info);
  else
    dgetrs_ ("N", &x->n, &one, x->ca, &x->n, x->cipiv, x->b, &x->n,
             &x->info);
}

int
sym_getrs (int cplx, int n, const double *a, const int *ipiv, double *b)
{
  call_args x = { .n = n, .cplx = cplx, .ca = a, .cipiv = ipiv, .b = b };
  sym_outside (run_getrs, &x);
  return x.info;
}

static void
run_gemm (void *p)
{
  call_args *x = p;
  const double one = 1.0, zero = 0.0;
  dgemm_ ("N", "N", &x->m, &x->n, &x->k, &one, x->ca, &x->lda, x->cb,
          &x->ldb, &zero, x->c, &x->ldc);
}

void
sym_gemm (int m, int n, int k, const double *a, int lda, const double *b,
          int ldb, double *c, int ldc)
{
  call_args x = { .m = m, .n = n, .k = k, .ca = a, .lda = lda, .cb = b,
                  .ldb = ldb, .c = c, .ldc = ldc };
  sym_outside (run_gemm, &x);
}

static void
run_geev (void *p)
{
  call_args *x = p;
  const int one = 1;
  dgeev_ ("N", "V", &x->n, x->a, &x->n, x->wr, x->wi, NULL, &one, x->c,
          &x->n, x->work, &x->lwork, &x->info);
}

int
sym_geev (int n, double *a, double *wr, double *wi, double *vr,
          double *work, int lwork)
{
  call_args x = { .n = n, .a = a, .wr = wr, .wi = wi, .c = vr,
                  .work = work, .lwork = lwork };
  sym_outside (run_geev, &x);
  return x.info;
}

static void
run_stev (void *p)
{
  call_args *x = p;
  dstev_ ("V", &x->n, x->d, x->e, x->c, &x->n, x->work, &x->info);
}

int
sym_stev (int n, double *d, double *e, double *z, double *work)
{
  call_args x = { .n = n, .d = d, .e = e, .c = z, .work = work };
  sym_outside (run_stev, &x);
  return x.info;
}
