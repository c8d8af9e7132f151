/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* test_splitting.c -- the composition and splitting methods of
   sym_splittings (methods/splitting.c): each table's order conditions
   to round-off, the measured order of every method (explicit, second
   order, implicit), calls per step, the second-order form equal to the
   first-order one, reversibility of the symmetric methods, compensated
   sums, and bad input. */
#include "se_sv_systems.h"

static sym_method_opts
sp_opts (int method, int separable, int second_order, int compensated,
         sym_onestep_opts *own)
{
  sym_method_opts o;
  memset (&o, 0, sizeof (o));
  memset (own, 0, sizeof (*own));
  own->method = method;
  own->separable = separable;
  own->second_order = second_order;
  own->compensated = compensated;
  o.own = own;
  return o;
}

/* Kepler, e = 0.5, semi-major axis 1: after one period, 2 pi, the exact
   solution is y0 */
static const double kep0[4] = { 0.5, 0.0, 0.0, 1.7320508075688772 };

/* the sums of the coefficients are 1, and a symmetric method's rows are
   palindromes (a splitting's kicks mirror its drifts) */
static void
check_tables (void)
{
  for (int k = 0; sym_splittings[k].name; k++)
    {
      const sym_splitting *m = &sym_splittings[k];
      const int s = m->stages;
      double sa = 0.0, sb = 0.0, asym = 0.0;
      for (int i = 0; i < s; i++)
        sa += m->coef[i];
      if (m->kind == SYM_SPLITTING)
        for (int i = 0; i < s; i++)
          sb += m->coef[s + i];
      else
        sb = 1.0;
      CHECK (fabs (sa - 1.0) <= 4e-15 && fabs (sb - 1.0) <= 4e-15,
             "%s: sums %.17g %.17g", m->name, sa, sb);
      CHECK (sym_splitting_find (m->name) == k, "%s: found", m->name);
      if (! m->symmetric)
        continue;
      if (m->kind == SYM_COMPOSITION)
        for (int i = 0; i < s; i++)
          asym = fmax (asym, fabs (m->coef[i] - m->coef[s - 1 - i]));
      else
        {
          /* kick first: b_1, a_1, ..., b_s, a_s read backwards is the
             same sequence when a_s = 0 (b_i = b_{s+1-i}, a_i = a_{s-i})
             or b_1 = 0 (a_i = a_{s+1-i}, b_i = b_{s+2-i}) */
          const double *a = m->coef, *b = m->coef + s;
          if (a[s - 1] == 0.0)
            for (int i = 0; i < s; i++)
              asym = fmax (asym, fabs (b[i] - b[s - 1 - i])
                                 + (i < s - 1 ? fabs (a[i] - a[s - 2 - i])
                                              : 0.0));
          else if (b[0] == 0.0)
            for (int i = 0; i < s; i++)
              asym = fmax (asym, fabs (a[i] - a[s - 1 - i])
                                 + (i > 0 ? fabs (b[i] - b[s - i]) : 0.0));
          else
            asym = 1.0;
        }
      CHECK (asym <= 1e-15, "%s: symmetric, asymmetry %.3g", m->name, asym);
    }
  CHECK (sym_splitting_find ("YOSHIDA4") == sym_splitting_find ("yoshida4"),
         "names in any case");
  CHECK (sym_splitting_find ("yoshida") < 0 && sym_splitting_find ("") < 0
         && sym_splitting_find (NULL) < 0, "unknown names");
}

/* N steps over one Kepler period: the error at the end */
static double
kepler_error (int method, int separable, int second_order, long N,
              long *calls)
{
  tprob P;
  sym_eval ev = tp_eval (&P, P_KEPLER, 1);
  sym_onestep_opts own;
  sym_method_opts o = sp_opts (method, separable, second_order, 0, &own);
  double y[4];
  int st = run_fixed (sym_step_splitting, &ev, &o, 0.0, 2 * M_PI / N, N,
                      kep0, y, NULL, 0);
  if (calls)
    *calls = P.calls;
  return st ? NAN : maxdiff (4, y, kep0);
}

/* The order: from the first N (doubling from 16) with an error below
   1e-3, the slope of the error from N to 2N while it stays above 1e-11 */
static void
check_order (int k, int separable, const char *form)
{
  const sym_splitting *m = &sym_splittings[k];
  double e1 = NAN, e2 = NAN;
  long N = 16;
  for (; N < 200000; N *= 2)
    {
      e1 = kepler_error (k, separable, 0, N, NULL);
      if (e1 < 1e-3)
        break;
    }
  e2 = kepler_error (k, separable, 0, 2 * N, NULL);
  double slope = log2 (e1 / e2);
  CHECK (e2 > 1e-11 && fabs (slope - m->order) <= 0.3,
         "%s %s: order %.2f (nominal %d), errors %.3g %.3g at N = %ld",
         m->name, form, slope, m->order, e1, e2, N);
}

/* calls per step, explicit: one per kick with second_order, but a last
   kick's f_p serves the next step's first kick (FSAL: a composition of s
   Verlet steps makes s calls); one more per drift with the first-order
   f (each drift follows a kick); second order equal to the first-order
   form */
static void
check_calls (int k)
{
  const sym_splitting *m = &sym_splittings[k];
  int kicks = 0, drifts = 0;
  if (m->kind == SYM_COMPOSITION)
    kicks = drifts = m->stages;
  else
    {
      for (int i = 0; i < m->stages; i++)
        {
          kicks += m->coef[m->stages + i] != 0.0;
          drifts += m->coef[i] != 0.0;
        }
      kicks -= m->coef[m->stages - 1] == 0.0;
    }
  long c1, c2, s1, s2;
  double e1 = kepler_error (k, 1, 0, 100, &c1);
  double e2 = kepler_error (k, 1, 0, 200, &c2);
  double f1 = kepler_error (k, 0, 1, 100, &s1);
  double f2 = kepler_error (k, 0, 1, 200, &s2);
  double per1 = (c2 - c1) / 100.0, per2 = (s2 - s1) / 100.0;
  CHECK (per2 == kicks, "%s: %.2f calls per step with second_order, "
         "expected %d", m->name, per2, kicks);
  CHECK (per1 == kicks + drifts, "%s: %.2f calls per step, expected %d",
         m->name, per1, kicks + drifts);
  CHECK (fabs (e1 - f1) <= 1e-15 * fmax (1.0, e1) && e2 == e2 && f2 == f2,
         "%s: second order %.17g vs first order %.17g", m->name, f1, e1);
}

/* the symmetric methods: N steps of h and N of -h return to y0 */
static void
check_reversible (int k)
{
  const sym_splitting *m = &sym_splittings[k];
  for (int sep = 1; sep >= (m->kind == SYM_COMPOSITION ? 0 : 1); sep--)
    {
      tprob P;
      sym_eval ev = tp_eval (&P, sep ? P_KEPLER : P_H2, 1);
      sym_onestep_opts own;
      sym_method_opts o = sp_opts (k, sep, 0, 0, &own);
      const double y0[4] = { 0.5, 0.1, 0.2, 1.2 };
      double y1[4], y2[4];
      const long N = 20;
      const double h = 0.05;
      int st = run_fixed (sym_step_splitting, &ev, &o, 0.0, h, N, y0, y1,
                          NULL, 0);
      st = st ? st : run_fixed (sym_step_splitting, &ev, &o, N * h, -h, N,
                                y1, y2, NULL, 0);
      double back = maxdiff (4, y2, y0), moved = maxdiff (4, y1, y0);
      if (m->symmetric)
        CHECK (st == 0 && back <= 5e-14, "%s %s: back to y0 within %.3g",
               m->name, sep ? "explicit" : "implicit", back);
      else
        CHECK (st == 0 && back > 1e-8 && moved > 0.1,
               "%s: not symmetric, yet back within %.3g", m->name, back);
    }
}

/* the implicit stages on a non-separable H: order against RK4 */
static void
check_implicit_order (int k)
{
  const sym_splitting *m = &sym_splittings[k];
  tprob P;
  const double y0[4] = { 0.5, 0.1, 0.2, 1.2 }, T = 1.0;
  double ref[4], y[4], err[2];
  sym_system sys = tp_system (&P, P_H2, 1);
  (void) sys;   /* P's kind for rk4 */
  rk4 (&P, 0.0, T / 4000, 4000, y0, ref);
  long N = 4;
  for (; N < 4096; N *= 2)
    {
      for (int j = 0; j < 2; j++)
        {
          sym_eval ev = tp_eval (&P, P_H2, 1);
          sym_onestep_opts own;
          sym_method_opts o = sp_opts (k, 0, 0, 0, &own);
          long Nj = N << j;
          int st = run_fixed (sym_step_splitting, &ev, &o, 0.0, T / Nj, Nj,
                              y0, y, NULL, 0);
          err[j] = st ? NAN : maxdiff (4, y, ref);
        }
      if (err[0] < 1e-3)
        break;
    }
  double slope = log2 (err[0] / err[1]);
  CHECK (err[1] > 1e-11 && fabs (slope - m->order) <= 0.3,
         "%s implicit: order %.2f (nominal %d), errors %.3g %.3g at N = %ld",
         m->name, slope, m->order, err[0], err[1], N);
}

/* Compensated sums.  Leapfrog conserves Ht = (p^2 + (1 - h^2/4) q^2)/2
   of the oscillator exactly, so that the change of Ht over a run is its
   round-off: compensated sums leave the rounding of the increments
   (relative size h), not of the sums. */
static void
check_compensated (void)
{
  double dev[2];
  const double h = 1.0 / 128, w = 1.0 - h * h / 4;
  for (int c = 0; c < 2; c++)
    {
      tprob P;
      sym_eval ev = tp_eval (&P, P_HO, 0);
      sym_onestep_opts own;
      sym_method_opts o = sp_opts (0, 1, 1, c, &own);
      const double y0[2] = { 1.0, 0.0 };
      double y[2];
      int st = run_fixed (sym_step_splitting, &ev, &o, 0.0, h, 1000000, y0,
                          y, NULL, 0);
      dev[c] = st ? NAN : fabs ((y[1] * y[1] + w * y[0] * y[0]) - w) / 2;
    }
  CHECK (dev[1] <= 1e-14 && dev[1] * 10 < dev[0],
         "compensated: Ht changed by %.3g, without %.3g", dev[1], dev[0]);
}

static void
check_bad_input (void)
{
  int st = 0;
  sym_onestep_opts own;
  const int ruth = sym_splitting_find ("ruth3");
  sym_method_opts o = sp_opts (ruth >= 0 ? ruth : 1, 0, 0, 0, &own);
  void *S = NULL;
  if (ruth >= 0)
    S = sym_step_splitting->alloc (2, &o, &st);
  CHECK (ruth < 0 || (! S && st == SYM_EBADINPUT),
         "a splitting with implicit steps: %s", sym_status_name (st));
  o = sp_opts (1, 0, 0, 1, &own);
  S = sym_step_splitting->alloc (2, &o, &st);
  CHECK (! S && st == SYM_EBADINPUT, "compensated implicit: %s",
         sym_status_name (st));
  o = sp_opts (1000, 1, 0, 0, &own);
  S = sym_step_splitting->alloc (2, &o, &st);
  CHECK (! S && st == SYM_EBADINPUT, "method out of range: %s",
         sym_status_name (st));
  o = sp_opts (-1, 1, 0, 0, &own);
  S = sym_step_splitting->alloc (2, &o, &st);
  CHECK (! S && st == SYM_EBADINPUT, "method -1: %s", sym_status_name (st));
  o = sp_opts (1, 1, 0, 0, &own);
  S = sym_step_splitting->alloc (2, &o, &st);
  CHECK (S != NULL, "alloc: %s", sym_status_name (st));
  if (S)
    {
      static const double atol = 1e-6;
      static const sym_tolerances tol = { 1e-6, &atol, 1, 0 };
      tprob P;
      sym_eval ev = tp_eval (&P, P_KEPLER, 0);
      double yn[4], ye[4];
      CHECK (sym_step_splitting->set_tolerances (S, &tol) == SYM_EBADINPUT,
             "no adaptive steps");
      CHECK (sym_step_splitting->step (S, &ev, 0.0, 0.1, 0.1, kep0, yn, ye)
             == SYM_EBADINPUT, "no error estimate");
      sym_step_splitting->free (S);
    }
}

int
main (void)
{
  check_tables ();
  for (int k = 0; sym_splittings[k].name; k++)
    {
      const sym_splitting *m = &sym_splittings[k];
      check_order (k, 1, "explicit");
      check_calls (k);
      check_reversible (k);
      if (m->kind == SYM_COMPOSITION)
        check_implicit_order (k);
    }
  check_compensated ();
  check_bad_input ();
  return tu_finish ("test_splitting");
}
