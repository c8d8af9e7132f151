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
/* work: 2n doubles */
int sym_initial_step (sym_system *sys, double t0, const double *y0,
                      const double *f0, double dir, int q, double rtol,
                      const double *atol, int atol_len, double hmax,
                      double *work, double *h_out);

#endif
