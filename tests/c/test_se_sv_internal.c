/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* test_se_sv_internal.c -- the parts the SE and SV steppers share
   (methods/onestep.h): the history of an implicit unknown (sym_pred) and
   the linear move of the cached f (sym_fcache_move). */
#include "se_sv_systems.h"
#include "methods/onestep.h"

/* The history of an implicit unknown (sym_pred): where the errors of the
   base over h^2 are a polynomial of degree <= 8 in t (at equal or unequal
   steps) the start is exact once deg + 2 of them show it; the base
   alone (no start) where its errors vanish; no start with one error,
   beyond twice the last spacing or backwards; a trial that does not
   continue, changes its kind of base or is accepted without a value
   starts the history anew; a failed trial is not taken. */
static double
pred_poly (int deg, int i, double t)
{
  double v = 0.3 * i - 0.7;
  for (int k = 1; k <= deg; k++)
    v += (0.5 + 0.25 * k - 0.1 * i) * pow (t - 0.4, k);
  return v;
}

/* one accepted step of size h with the value x at offset c (kind, base)
   into o's history */
static void
pred_accept (sym_onestep *o, int cont, double h, double c, const double *x,
             int kind, const double *base)
{
  sym_pred_note (&o->pr[0], cont, h, c, x, kind, base);
  o->r.trial_ok = 1;
  sym_onestep_accept (o);
}

static void
scenario_pred (void)
{
  enum { D = 2 };
  double w[(SYM_PRED_MAX + 2) * D], x[D], base[D], v[D];
  sym_onestep o;
  for (int deg = 0; deg <= 8; deg++)
    for (int uneven = 0; uneven < 2; uneven++)
      {
        memset (&o, 0, sizeof o);
        o.npr = 1;
        sym_pred_place (&o.pr[0], D, w);
        /* steps from Tr; the unknown at Tr + h/2 (as SV's p_{k+1/2}) */
        double Tr = 0.0, err = 0.0;
        int started = 0;
        for (int k = 0; k < 14; k++)
          {
            double h = uneven ? 0.05 * (1.0 + 0.3 * (k % 3)) : 0.05;
            double ts = Tr + 0.5 * h;
            for (int i = 0; i < D; i++)
              {
                base[i] = cos (3.0 * ts + i);
                x[i] = base[i] + h * h * pred_poly (deg, i, ts);
              }
            if (sym_pred_start (&o.pr[0], h, 0.5 * h, 1, base, v)
                && o.pr[0].n >= deg + 2)
              {
                started++;
                for (int i = 0; i < D; i++)
                  err = fmax (err, fabs (v[i] - x[i]));
              }
            pred_accept (&o, k > 0, h, 0.5 * h, x, 1, base);
            Tr += h;
          }
        /* from the (deg + 2)-th value (the second for deg 0) on */
        CHECK (started == 14 - (deg + 2) && err <= 1e-10,
               "degree %d uneven %d: %d starts, error %.3g", deg, uneven,
               started, err);
      }
  /* the rules (steps of 0.1, the unknown at their ends) */
  memset (&o, 0, sizeof o);
  o.npr = 1;
  sym_pred_place (&o.pr[0], D, w);
  for (int i = 0; i < D; i++)
    {
      base[i] = 1.0 + i;
      x[i] = base[i] + 0.5;   /* an error of the base that stays */
    }
  pred_accept (&o, 0, 0.1, 0.1, x, 1, base);
  CHECK (! sym_pred_start (&o.pr[0], 0.1, 0.1, 1, base, v), "one error");
  pred_accept (&o, 1, 0.1, 0.1, x, 1, base);
  CHECK (sym_pred_start (&o.pr[0], 0.1, 0.1, 1, base, v)
         && fabs (v[0] - 1.5) <= 1e-15 && fabs (v[1] - 2.5) <= 1e-15,
         "two errors: [%g %g]", v[0], v[1]);
  CHECK (sym_pred_start (&o.pr[0], 0.1, 0.15, 1, base, v)
         && ! sym_pred_start (&o.pr[0], 0.1, 0.25, 1, base, v)
         && ! sym_pred_start (&o.pr[0], 0.1, -0.05, 1, base, v)
         && ! sym_pred_start (&o.pr[0], 0.1, -0.1, 1, base, v)
         && ! sym_pred_start (&o.pr[0], 0.1, -0.2, 1, base, v),
         "up to twice the last spacing ahead, not back");
  CHECK (! sym_pred_start (&o.pr[0], 0.1, 0.1, 2, base, v), "another kind");
  pred_accept (&o, 0, 0.1, 0.1, x, 1, base);
  CHECK (o.pr[0].n == 1, "a trial that did not continue: %d", o.pr[0].n);
  pred_accept (&o, 1, 0.1, 0.1, x, 2, base);
  CHECK (o.pr[0].n == 1 && o.pr[0].kind == 2, "a new kind: %d",
         o.pr[0].n);
  /* the base exact: its errors vanish, and the base alone is best */
  for (int k = 0; k < 3; k++)
    pred_accept (&o, 1, 0.1, 0.1, base, 2, base);
  CHECK (o.pr[0].n == 4 && ! sym_pred_start (&o.pr[0], 0.1, 0.1, 2, base, v),
         "exact base: %d", o.pr[0].n);
  o.r.trial_ok = 1;   /* accepted without a value */
  sym_onestep_accept (&o);
  CHECK (o.pr[0].n == 0, "accepted without a value: %d", o.pr[0].n);
  pred_accept (&o, 1, 0.1, 0.1, x, 2, base);
  o.r.trial_ok = 0;   /* a failed trial is not accepted */
  sym_pred_note (&o.pr[0], 1, 0.1, 0.1, x, 2, base);
  sym_onestep_accept (&o);
  CHECK (o.pr[0].n == 1, "failed trial: %d", o.pr[0].n);
}

/* sym_fcache_move: f moved linearly by the cached Df to a nearby point at
   the same t; nothing without a Df, at another t, or at the same point */
static void
scenario_fcache_move (void)
{
  double w[3 * 2 + 4];
  sym_fcache c;
  sym_fcache_place (&c, 1, 1, w);
  c.yw[0] = 1.0;
  c.yw[1] = 2.0;
  c.fw[0] = 10.0;
  c.fw[1] = 20.0;
  c.tw = 0.5;
  c.have_fw = 1;
  const double J[4] = { 1.0, 3.0, 2.0, 4.0 };   /* column-major */
  memcpy (c.jw, J, sizeof J);
  double a = 1.0 + 1e-3, b = 2.0 - 2e-3;
  sym_fcache_move (&c, 0.5, &a, &b);
  CHECK (c.fw[0] == 10.0 && c.fw[1] == 20.0, "no Df: no move");
  c.have_jw = 1;
  sym_fcache_move (&c, 0.25, &a, &b);
  CHECK (c.fw[0] == 10.0 && c.yw[0] == 1.0, "another t: no move");
  sym_fcache_move (&c, 0.5, &a, &b);
  CHECK_CLOSE (c.fw[0], 10.0 + 1.0 * 1e-3 - 2.0 * 2e-3, 1e-14, "f_q moved");
  CHECK_CLOSE (c.fw[1], 20.0 + 3.0 * 1e-3 - 4.0 * 2e-3, 1e-14, "f_p moved");
  CHECK (c.yw[0] == a && c.yw[1] == b, "now at the point");
  double f0 = c.fw[0];
  sym_fcache_move (&c, 0.5, &a, &b);
  CHECK (c.fw[0] == f0, "same point: no move");
}

int
main (void)
{
  scenario_pred ();
  scenario_fcache_move ();
  return tu_finish ("test_se_sv_internal");
}
