/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* symplectic_fcn.h -- the functions of a compiled FCN (symcompile).

   A C file written against this header is compiled by symcompile into a
   shared object that odeSE, odeSV and odeSPVI call directly: no Octave
   call per evaluation.  symhamiltonian and symlagrangian generate such
   a file.  Conventions are the package's: y = [q; p], q and p of d
   components, n = 2d; matrices column-major; PAR is the solver's PAR1
   (a real vector of SYMPLECTIC_SYSTEM's npar elements; NULL when npar
   is 0).  Each function returns 0 on success, > 0 to ask for a smaller
   step, < 0 to stop the run (as the core's callbacks do).

   Required: SYMPLECTIC_SYSTEM (d, npar) once, and symplectic_f.
   Optional (define those the system has):
     symplectic_f_batch       f at k states, the columns of y (n-by-k),
                              their times t[0..k-1] (Vectorized, ensembles;
                              without it f is called k times)
     symplectic_hess_pattern  the nonzero pattern of the n-by-n Hessian of
                              H as compressed columns: the rows of column j
                              are rowind[colptr[j] .. colptr[j+1] - 1],
                              increasing; returns nnz; called first with
                              NULL, NULL for nnz alone
     symplectic_hess          the Hessian's values in the pattern's order
                              (Newton's matrix of the implicit steps)
     symplectic_accel         a = -M^-1 dV/dq for H = p'M^-1 p/2 + V(q):
                              d values from q (SecondOrder)
     symplectic_energy        H (t, y) (the Hamiltonian option, fcn.energy)

   Example (the pendulum H = p^2/2 - cos q):

     #include <math.h>
     #include "symplectic_fcn.h"
     SYMPLECTIC_SYSTEM (1, 0);
     int symplectic_f (double t, const double *y, double *dy,
                       const double *par)
     { dy[0] = y[1]; dy[1] = -sin (y[0]); return 0; }  */
#ifndef SYMPLECTIC_FCN_H
#define SYMPLECTIC_FCN_H

#define SYMPLECTIC_ABI_VERSION 1

#if defined (__GNUC__)
#define SYMPLECTIC_EXPORT __attribute__ ((visibility ("default")))
#else
#define SYMPLECTIC_EXPORT
#endif

/* d degrees of freedom (y has 2d components), npar parameters */
#define SYMPLECTIC_SYSTEM(d, npar)                                      \
  SYMPLECTIC_EXPORT const int symplectic_abi = SYMPLECTIC_ABI_VERSION;  \
  SYMPLECTIC_EXPORT const int symplectic_dim = (d);                     \
  SYMPLECTIC_EXPORT const int symplectic_npar = (npar)

#ifdef __cplusplus
extern "C" {
#endif

SYMPLECTIC_EXPORT int symplectic_f (double t, const double *y, double *dy,
                                    const double *par);
SYMPLECTIC_EXPORT int symplectic_f_batch (int k, const double *t,
                                          const double *y, double *dy,
                                          const double *par);
SYMPLECTIC_EXPORT int symplectic_hess_pattern (int *colptr, int *rowind);
SYMPLECTIC_EXPORT int symplectic_hess (double t, const double *y,
                                       double *val, const double *par);
SYMPLECTIC_EXPORT int symplectic_accel (double t, const double *q,
                                        double *a, const double *par);
SYMPLECTIC_EXPORT double symplectic_energy (double t, const double *y,
                                            const double *par);

#ifdef __cplusplus
}
#endif

#endif
