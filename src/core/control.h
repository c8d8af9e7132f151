/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* control.h -- internal to the core: error norms and step-size choice. */
#ifndef SYM_CONTROL_H
#define SYM_CONTROL_H

#include "sym.h"

double sym_error_norm (int n, const double *e, const double *yold,
                       const double *ynew, double rtol, const double *atol,
                       int atol_len, int norm_control);
/* The smallest error a component of y may have under the tolerances:
   min_i max(atol, rtol |y_i|). */
double sym_error_floor (int n, const double *y, double rtol, double atol);
double sym_step_factor (double err, int q, double facmin, double facmax);
/* After an accepted step (h, err) that followed an accepted one (h_acc,
   err_acc): the smaller of fac and the factor that predicts the error's
   trend (see control.c); err_acc <= 0: fac. */
double sym_step_factor_pred (double fac, double err, int q, double h,
                             double h_acc, double err_acc, double facmin);
/* work: 2n doubles */
int sym_initial_step (sym_system *sys, double t0, const double *y0,
                      const double *f0, double dir, int q, double rtol,
                      const double *atol, int atol_len, double hmax,
                      double *work, double *h_out);

#endif
