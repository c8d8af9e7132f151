/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* tangent.h -- internal to the core: the hooks by which the explicit
   steps of se.c, sv.c and splitting.c carry the tangent map (sym.h:
   sym_tangent; tangent.c).  A step begins its trial Phi from the
   accepted one, moves it with each kick and drift it takes, and accept
   makes it the accepted one. */
#ifndef SYM_TANGENT_H
#define SYM_TANGENT_H

#include "../sym.h"

/* tg is of a system of dimension dim */
int sym_tangent_fits (const sym_tangent *tg, int dim);
/* the trial starts from the accepted Phi */
void sym_tangent_begin (sym_tangent *tg);
/* a kick p += c f_p (t, q): Phi_p += c (d f_p / d q) Phi_q, the block at
   (t, [q; p]) */
int sym_tangent_kick (sym_tangent *tg, sym_eval *ev, double t,
                      const double *q, const double *p, double c);
/* a drift q += c f_q (t, p): Phi_q += c (d f_q / d p) Phi_p; identity:
   f_q = p (second_order), no call */
int sym_tangent_drift (sym_tangent *tg, sym_eval *ev, double t,
                       const double *q, const double *p, double c,
                       int identity);
/* the drift's block at (t, [q; p]) made ready (with Df, the kick's
   too), no step of Phi */
int sym_tangent_prefetch (sym_tangent *tg, sym_eval *ev, double t,
                          const double *q, const double *p);
/* f at (t, [q; p]) when the last Df came with it from there, else
   NULL */
const double *sym_tangent_f (const sym_tangent *tg, double t,
                             const double *q, const double *p);
/* the trial becomes the accepted Phi */
void sym_tangent_accept (sym_tangent *tg);

#endif
