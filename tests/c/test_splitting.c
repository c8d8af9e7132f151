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

/* Kepler, eccentricity KEP_E, semi-major axis 1, from the pericentre */
#define KEP_E 0.2
static double kep0[4];

/* its exact solution at t: Kepler's equation E - e sin E = t by Newton */
static void
kepler_exact (double t, double *y)
{
  const double e = KEP_E, b = sqrt (1 - e * e);
  double E = t;
  for (int k = 0; k < 50; k++)
    E -= (E - e * sin (E) - t) / (1 - e * cos (E));
  const double r = 1 - e * cos (E);
  y[0] = cos (E) - e;
  y[1] = b * sin (E);
  y[2] = -sin (E) / r;
  y[3] = b * cos (E) / r;
}

/* The end of the runs that measure the order: not a whole period (an
   odd-order method's leading error cancels over whole periods of
   Kepler's problem), and long enough for the high orders to show above
   round-off over a range of steps */
static double
order_span (int k)
{
  return sym_splittings[k].order > 4 ? 4 * M_PI + 1 : 1.0;
}

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

/* N steps over [0, order_span] into y, the calls they made in calls */
static int
kepler_run (int method, int separable, int second_order, long N, double *y,
            long *calls)
{
  tprob P;
  sym_eval ev = tp_eval (&P, P_KEPLER, 1);
  sym_onestep_opts own;
  sym_method_opts o = sp_opts (method, separable, second_order, 0, &own);
  const double T = order_span (method);
  int st = run_fixed (sym_step_splitting, &ev, &o, 0.0, T / N, N, kep0, y,
                      NULL, 0);
  if (calls)
    *calls = P.calls;
  return st;
}

/* and the error at the end */
static double
kepler_error (int method, int separable, int second_order, long N,
              long *calls)
{
  double y[4], ex[4];
  int st = kepler_run (method, separable, second_order, N, y, calls);
  kepler_exact (order_span (method), ex);
  return st ? NAN : maxdiff (4, y, ex);
}

/* The least-squares slope of -log (error) against log (N) over the
   errors between 1e-11 and 1e-5 (1e-7 for orders above 4, whose coarse
   steps are not yet asymptotic), at least 4 and at most 12 of them, of N
   growing geometrically by 5/4: the order of an error function err
   (k, N) */
static double
fit_order (double (*err) (int, int, long), int k, int sep, double *lo,
           double *hi)
{
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int m = 0;
  *lo = INFINITY;
  *hi = 0;
  for (long N = 8; N < 40000 && m < 12; N += N / 4)
    {
      double e = err (k, sep, N);
      if (e < 1e-11)
        break;
      /* (a failed run: a step too long for Newton) */
      if (e > (sym_splittings[k].order > 4 ? 1e-7 : 1e-5) || ! (e == e))
        continue;
      double x = log ((double) N), y = -log (e);
      sx += x, sy += y, sxx += x * x, sxy += x * y, m++;
      *lo = fmin (*lo, e);
      *hi = fmax (*hi, e);
    }
  return m >= 4 ? (m * sxy - sx * sy) / (m * sxx - sx * sx) : NAN;
}

static double
kepler_err (int k, int sep, long N)
{
  return kepler_error (k, sep, 0, N, NULL);
}

static void
check_order (int k, int separable, const char *form)
{
  const sym_splitting *m = &sym_splittings[k];
  double lo, hi, slope = fit_order (kepler_err, k, separable, &lo, &hi);
  CHECK (fabs (slope - m->order) <= 0.3, "%s %s: order %.2f (nominal %d), "
         "errors %.3g to %.3g", m->name, form, slope, m->order, hi, lo);
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

/* the implicit stages on a non-separable H over [0, T] (T = 1, or 8
   for the high orders): the error against RK4 with steps of 1e-4 */
static double
h2_err (int k, int sep, long N)
{
  static double ref[2][4];
  static int have_ref[2] = { 0, 0 };
  const double y0[4] = { 0.5, 0.1, 0.2, 1.2 };
  const int j = sym_splittings[k].order > 4;
  const double T = j ? 8.0 : 1.0;
  tprob P;
  sym_eval ev = tp_eval (&P, P_H2, 1);
  if (! have_ref[j])
    {
      rk4 (&P, 0.0, 1e-4, (long) (T * 1e4), y0, ref[j]);
      have_ref[j] = 1;
    }
  sym_onestep_opts own;
  sym_method_opts o = sp_opts (k, sep, 0, 0, &own);
  double y[4];
  int st = run_fixed (sym_step_splitting, &ev, &o, 0.0, T / N, N, y0, y,
                      NULL, 0);
  return st ? NAN : maxdiff (4, y, ref[j]);
}

static void
check_implicit_order (int k)
{
  const sym_splitting *m = &sym_splittings[k];
  double lo, hi, slope = fit_order (h2_err, k, 0, &lo, &hi);
  CHECK (fabs (slope - m->order) <= 0.3, "%s implicit: order %.2f "
         "(nominal %d), errors %.3g to %.3g", m->name, slope, m->order, hi,
         lo);
}

/* The implicit stages of a separable H solve the explicit method's
   equations: the results agree to Newton's tolerance */
static void
check_implicit_same (int k)
{
  double d = 0.0, y1[4], y2[4];
  for (long N = 20; N <= 40; N += 20)
    {
      int st = kepler_run (k, 1, 0, N, y1, NULL);
      st = st ? st : kepler_run (k, 0, 0, N, y2, NULL);
      d = fmax (d, st ? INFINITY : maxdiff (4, y1, y2));
    }
  CHECK (d <= 1e-12, "%s: implicit and explicit steps differ by %.3g",
         sym_splittings[k].name, d);
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
  /* no options: Verlet's implicit stages */
  S = sym_step_splitting->alloc (2, NULL, &st);
  CHECK (S != NULL && st == SYM_SUCCESS, "no options: %s",
         sym_status_name (st));
  sym_step_splitting->free (S);
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
  kepler_exact (0.0, kep0);
  check_tables ();
  for (int k = 0; sym_splittings[k].name; k++)
    {
      const sym_splitting *m = &sym_splittings[k];
      check_order (k, 1, "explicit");
      check_calls (k);
      check_reversible (k);
      if (m->kind == SYM_COMPOSITION && m->order <= 6)
        check_implicit_order (k);
      if (m->kind == SYM_COMPOSITION)
        check_implicit_same (k);
    }
  check_compensated ();
  check_bad_input ();
  return tu_finish ("test_splitting");
}
