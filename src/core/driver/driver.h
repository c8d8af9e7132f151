/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* driver.h -- internal to the driver: the state of a run, shared by the
   loop (loop.c), the step-size control (control.c), event location
   (events.c) and the rows handed out (output.c). */
#ifndef SYM_DRIVER_H
#define SYM_DRIVER_H

#include "../sym.h"

typedef struct {
  const sym_stepper_type *type;
  void *state;
  sym_method_opts mo;      /* the method's options for this run */
  sym_eval ev;
  const sym_driver_opts *o;
  int n;
  double dir;
  int fixed;               /* fixed steps (no error control) */
  /* the current point and the step being tried */
  double t;
  double *y, *ynew, *yerr;
  double *ydense;          /* a point of the dense output */
  double *ytyp;            /* the sizes of y's components (sym_eval) */
  /* fixed steps */
  long nfixed, k;
  double hfix, tend, tgrid;   /* tgrid: the origin of the steps' grid */
  /* adaptive steps */
  double h, hmax;
  int user_hmax;
  int q;                   /* the order of the error estimate */
  int last_rejected;       /* the last step tried was rejected */
  double h_rejected;       /* the size of the last rejected step */
  double h_acc, err_acc;   /* the last accepted step (predictive control) */
  double tcomp;            /* the steps' sum minus t (round-off) */
  /* reversible control: eps, the density of the step to take
     (rho_{n+1/2}), f at a step point (n) */
  int reversible;
  double eps, rho_half;
  double rho_prev;         /* the density of the step before (restart) */
  double *fn;
  long jac_checked_at;     /* nsteps at the last sym_jac_check */
  int jac_agreed;          /* its checks that found Df right */
  /* events */
  int ne, ns;              /* event functions, samples inside a step */
  double *vold, *vnew, *vtry;
  double *vs;              /* event values at the samples inside a step */
  double *vca, *vcb;       /* and at the vertices between them */
  double *tcand;           /* the vertices' places */
  int *term, *edir;
  double *tfound;          /* events found in one step, sorted by time */
  int *kfound;
  /* output */
  int iout;                /* next requested output time (ntout > 2) */
  int nd;                  /* dense samples inside a step (dense_out) */
  double *yd;              /* their values and the ends', n x (nd + 2) */
} sym_run;

/* ---------------------------------------------------------------- control */
/* ode45's error norm of e (AbsRel, or the 2-norm with norm_control) */
double sym_error_norm (int n, const double *e, const double *yold,
                       const double *ynew, const sym_tolerances *tol);
/* The factor by which to multiply h after a step with error norm err, for
   an estimate of order q (err = O(h^(q+1))), within [facmin, facmax] */
double sym_step_factor (double err, int q, double facmin, double facmax);
/* After an accepted step (h, err) that followed an accepted one (h_acc,
   err_acc): the smaller of fac and the factor that predicts the error's
   trend; err_acc <= 0: fac. */
double sym_step_factor_pred (double fac, double err, int q, double h,
                             double h_acc, double err_acc, double facmin);
/* The first step of an adaptive run from (t0, y0, f0 = f(t0, y0)) in
   direction dir: one call of f; work: 2n doubles */
int sym_initial_step (sym_eval *ev, double t0, const double *y0,
                      const double *f0, double dir, int q,
                      const sym_tolerances *tol, double hmax, double *work,
                      double *h_out);

/* Reversible control (reversible.c): eps and the first step's density
   (rho_half) from (t0, y0); the next density after the accepted step that
   ended at (t, y), the current point */
int sym_rev_start (sym_run *r);
int sym_rev_next (sym_run *r);
/* the next step's size: eps / rho_half, capped by a MaxStep given */
double sym_rev_step (const sym_run *r);

/* ---------------------------------------------------------------- events */
/* The event values at (t, y) into v (the callback's failure maps to a
   status) */
int sym_run_events (sym_run *r, double t, const double *y, double *v);
/* The events of the accepted step (t, tnew]: located on the dense output
   and reported in time order up to the first terminal one; *tstop its
   time (else NAN) */
int sym_handle_events (sym_run *r, double t, double tnew, double *tstop);

/* ---------------------------------------------------------------- output */
/* One row to the output sink: SYM_SUCCESS, SYM_STOP_OUTPUT, SYM_EOUTPUT */
int sym_emit (sym_run *r, double t, const double *y);
/* The rows of the accepted step (t, tnew] of size h, up to tstop (a
   terminal event's time, or NAN) */
int sym_output_step (sym_run *r, double t, double h, double tnew,
                     const double *ynew, double tstop);
/* The dense output of the accepted step (t, tnew] to the dense sink */
int sym_output_dense (sym_run *r, double t, double tnew);

#endif
