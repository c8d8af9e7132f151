/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* staged.h -- internal to the stage systems of odeSPVI's Newton solves
   (staged.c: the transforms and the state; staged_factor.c: J and the
   matrices made from it; staged_solve.c: the solves).  The method is
   described at the top of staged.c. */
#ifndef SYM_SPVI_STAGED_H
#define SYM_SPVI_STAGED_H

#include "spvi.h"

#include <complex.h>

struct spvi_stages {
  int ns;                       /* stage systems */
  int idx[SYM_SPVI_MAX_NODES];  /* their eigenvalue's index in S */
  double complex lam[SYM_SPVI_MAX_NODES];
  double complex *rq, *rp;      /* forward transforms, [i + r m] */
  double complex *bq, *bp;      /* back transforms, [j + i m] */
  sym_stage_lu lu[SYM_SPVI_MAX_NODES];
  int nlu;                      /* their size: 0 (none yet), d or 2d */
  int sparse;
  /* J with zero blocks Jqq and Jpp (a separable H; sparse: and a
     diagonal Jqp, a diagonal mass): the stage systems by their Schur
     complements I - gamma^2 K, K = Jpq Jqp, of size d */
  int schur;
  double *K;
  sym_csc Bs, Ks;               /* sparse: Jpq, and K (unit_mass:
                                   Jqp = I, K is Bs) */
  int unit_mass;
  double *aq;                   /* sparse: Jqp's diagonal (d) */
  double *J;                    /* dense: (2d)^2 */
  sym_csc Js;                   /* sparse */
  double complex *z;            /* work: ns x 2d */
  /* J = 0 (fp): M is its constant part, whose inverse maps the R2 rows
     to the da by -D^-1 and the R1 rows to the dP by Wd^-1 (real m x m,
     column-major), without the transforms */
  double *dinv, *wdinv;
  double *wg;                   /* S = Wd^-1 G (m x m): the fixed point's
                                   P from the nodes' f_p */
  double *fw;                   /* work: N */
  /* the pairs n - 1 != m with a sparse J: no stages (ns = 0), the whole
     system M, assembled sparse as M - I (lu[0], factored as I + (M - I))
     from J's blocks as jacobians.c's matrix with every A_j = J */
  int whole;
  sym_csc Mw;
  double *wcol;                 /* work: N (a column of M - I) */
  int *rows;                    /* work: N (its rows) */
  double *wv;                   /* work: 2d */
  /* exact: c->A sized for the node Jacobians; work: the right side and
     the residual (N each), the products' node values (4 d m) */
  int a_full;
  double *rb, *dyb;
};

#endif
