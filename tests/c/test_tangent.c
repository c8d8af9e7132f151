/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* test_tangent.c -- the tangent map of explicit steps (sym_tangent,
   methods/tangent.c): Phi against extrapolated central differences of
   the steppers' own map (Kepler, the forced pendulum; Df from jac and
   by differences; SE, SV in both forms, the splitting stepper's
   methods), Phi' J Phi = J after 1e4 steps, the oscillator's Phi = A^N
   with A written out, and the refusals. */
#include "se_sv_systems.h"

static double
rel_diff (int n, int m, const double *a, const double *b)
{
  double num = 0.0, den = 0.0;
  for (int i = 0; i < n * m; i++)
    {
      num += (a[i] - b[i]) * (a[i] - b[i]);
      den += b[i] * b[i];
    }
  return sqrt (num / den);
}

/* d y_N / d y_0 of N steps without the tangent map: central differences
   at dl and 2 dl, extrapolated (error O(dl^4)) */
static void
map_diff (const sym_stepper_type *T, int kind, const sym_method_opts *o,
          double h, long N, const double *y0, double *D)
{
  tprob P;
  sym_eval ev = tp_eval (&P, kind, 0);
  const int n = 2 * ev.dim;
  double y[8], yp[8], ym[8], d1[8];
  for (int j = 0; j < n; j++)
    {
      const double dl = 1e-5 * fmax (1.0, fabs (y0[j]));
      for (int r = 1; r <= 2; r++)
        {
          memcpy (y, y0, (size_t) n * sizeof (double));
          y[j] = y0[j] + r * dl;
          run_fixed (T, &ev, o, 0.0, h, N, y, yp, NULL, 0);
          y[j] = y0[j] - r * dl;
          run_fixed (T, &ev, o, 0.0, h, N, y, ym, NULL, 0);
          for (int i = 0; i < n; i++)
            {
              const double c = (yp[i] - ym[i]) / (2 * r * dl);
              if (r == 1)
                d1[i] = c;
              else
                D[i + j * n] = (4 * d1[i] - c) / 3;
            }
        }
    }
  sym_eval_free (&ev);
}

/* N steps with the tangent map into phi (n-by-n); the status */
static int
run_tangent (const sym_stepper_type *T, int kind, int with_jac,
             sym_onestep_opts own, double h, long N, const double *y0,
             double *phi, long *calls)
{
  tprob P;
  sym_eval ev = tp_eval (&P, kind, with_jac);
  const int n = 2 * ev.dim;
  sym_tangent *tg = sym_tangent_new (ev.dim, n, NULL);
  own.tangent = tg;
  sym_method_opts o;
  memset (&o, 0, sizeof o);
  o.own = &own;
  double y[8];
  int st = run_fixed (T, &ev, &o, 0.0, h, N, y0, y, NULL, 0);
  memcpy (phi, sym_tangent_phi (tg), (size_t) n * n * sizeof (double));
  if (calls)
    *calls = P.calls;
  sym_tangent_free (tg);
  sym_eval_free (&ev);
  return st;
}

static void
check_against_differences (void)
{
  static const double kep[4] = { 0.5, 0.0, 0.0, 1.7320508075688772 };
  static const double pen[2] = { 1.0, 0.5 };
  const sym_stepper_type *types[3] = { sym_step_se, sym_step_sv,
                                       sym_step_splitting };
  /* the splitting stepper: yoshida4, ruth3, blanesmoan6 */
  static const char *const methods[3] = { "yoshida4", "ruth3",
                                          "blanesmoan6" };
  for (int kk = 0; kk < 2; kk++)
    {
      const int kind = kk ? P_PENDF : P_KEPLER;
      const double *y0 = kk ? pen : kep, h = kk ? 0.05 : 2 * M_PI / 200;
      const long N = kk ? 400 : 200;
      const int n = 2 * tp_dim (kind);
      for (int t = 0; t < 3; t++)
        for (int v = 0; v < (t == 2 ? 3 : 2); v++)
          for (int jac = 0; jac < 2; jac++)
            {
              sym_onestep_opts own;
              memset (&own, 0, sizeof own);
              own.separable = 1;
              own.position = t == 1 && v == 1;
              own.method = t == 2 ? sym_splitting_find (methods[v]) : 0;
              sym_method_opts o;
              memset (&o, 0, sizeof o);
              o.own = &own;
              double D[16], phi[16];
              map_diff (types[t], kind, &o, h, N, y0, D);
              int st = run_tangent (types[t], kind, jac, own, h, N, y0, phi,
                                    NULL);
              double e = rel_diff (n, n, phi, D);
              CHECK (st == 0 && e < 1e-7, "%s %s v%d jac %d: status %d, "
                     "relative difference %.3g", types[t]->name,
                     kk ? "pendulum" : "kepler", v, jac, st, e);
            }
    }
}

/* Kepler, e = 0.1, 1e4 steps of T/100, Df from jac */
static void
check_symplectic (void)
{
  static const double y0[4] = { 0.9, 0.0, 0.0, 1.1055415967851332 };
  const int n = 4;
  const sym_stepper_type *types[4] = { sym_step_se, sym_step_sv,
                                       sym_step_splitting,
                                       sym_step_splitting };
  const int meth[4] = { 0, 0, sym_splitting_find ("yoshida4"),
                        sym_splitting_find ("ruth3") };
  for (int t = 0; t < 4; t++)
    {
      sym_onestep_opts own;
      memset (&own, 0, sizeof own);
      own.separable = 1;
      own.method = meth[t];
      double P[16];
      int st = run_tangent (types[t], P_KEPLER, 1, own, 2 * M_PI / 100,
                            10000, y0, P, NULL);
      /* P' J P - J, J = [0 I; -I 0] */
      double err = 0.0, big = 0.0;
      for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++)
          {
            double s = 0.0;
            for (int k = 0; k < 2; k++)
              s += P[k + i * n] * P[k + 2 + j * n]
                   - P[k + 2 + i * n] * P[k + j * n];
            const double jij = (j == i + 2) - (i == j + 2);
            err += (s - jij) * (s - jij);
            big += P[i + j * n] * P[i + j * n];
          }
      CHECK (st == 0 && big > 1e6 && sqrt (err) / big < 1e-12,
             "%s %d: |P'JP - J| / |P|^2 = %.3g (|P|^2 %.3g)",
             types[t]->name, meth[t], sqrt (err) / big, big);
    }
}

/* the oscillator: SE's A = [1 - h^2, h; -h, 1], Verlet's [1 - h^2/2, h;
   -h + h^3/4, 1 - h^2/2], A^N by repeated products */
static void
check_oscillator (void)
{
  const double h = 0.1, y0[2] = { 1.0, 0.0 };
  const long N = 1000;
  for (int sv = 0; sv < 2; sv++)
    {
      const double A[4] = { sv ? 1 - h * h / 2 : 1 - h * h,
                            sv ? -h + h * h * h / 4 : -h,
                            h, sv ? 1 - h * h / 2 : 1 };
      double E[4] = { 1, 0, 0, 1 }, W[4];
      for (long k = 0; k < N; k++)
        {
          W[0] = A[0] * E[0] + A[2] * E[1];
          W[1] = A[1] * E[0] + A[3] * E[1];
          W[2] = A[0] * E[2] + A[2] * E[3];
          W[3] = A[1] * E[2] + A[3] * E[3];
          memcpy (E, W, sizeof E);
        }
      sym_onestep_opts own;
      memset (&own, 0, sizeof own);
      own.separable = 1;
      double phi[4];
      long calls;
      int st = run_tangent (stepper (sv), P_HO, 1, own, h, N, y0, phi,
                            &calls);
      double e = rel_diff (2, 2, phi, E);
      CHECK (st == 0 && e < 1e-12, "%s oscillator: %.3g", mname (sv), e);
      /* and second_order (f_q = p, the drift's identity) */
      own.second_order = 1;
      st = run_tangent (stepper (sv), P_HO, 1, own, h, N, y0, phi, NULL);
      e = rel_diff (2, 2, phi, E);
      CHECK (st == 0 && e < 1e-12, "%s oscillator, second order: %.3g",
             mname (sv), e);
    }
}

/* deviation vectors: Phi V0 */
static void
check_vectors (void)
{
  static const double y0[4] = { 0.5, 0.1, -0.2, 1.6 };
  static const double V0[8] = { 1, 0, 0.5, 2, 0, 1, -1, 0.25 };
  tprob P;
  sym_eval ev = tp_eval (&P, P_KEPLER, 1);
  sym_tangent *tf = sym_tangent_new (2, 4, NULL);
  sym_tangent *tv = sym_tangent_new (2, 2, V0);
  sym_onestep_opts own;
  memset (&own, 0, sizeof own);
  own.separable = 1;
  sym_method_opts o;
  memset (&o, 0, sizeof o);
  o.own = &own;
  double y[4];
  own.tangent = tf;
  run_fixed (sym_step_sv, &ev, &o, 0.0, 0.01, 300, y0, y, NULL, 0);
  own.tangent = tv;
  run_fixed (sym_step_sv, &ev, &o, 0.0, 0.01, 300, y0, y, NULL, 0);
  const double *F = sym_tangent_phi (tf), *G = sym_tangent_phi (tv);
  double PV[8];
  for (int j = 0; j < 2; j++)
    for (int i = 0; i < 4; i++)
      {
        PV[i + 4 * j] = 0.0;
        for (int k = 0; k < 4; k++)
          PV[i + 4 * j] += F[i + 4 * k] * V0[k + 4 * j];
      }
  CHECK (sym_tangent_columns (tv) == 2, "columns");
  CHECK (rel_diff (4, 2, G, PV) < 1e-13, "Phi V0: %.3g",
         rel_diff (4, 2, G, PV));
  sym_tangent_free (tf);
  sym_tangent_free (tv);
  sym_eval_free (&ev);
}

/* the renormalised column: its log growth is log |Phi v0| */
static void
check_renormalised (void)
{
  static const double y0[4] = { 0.5, 0.1, -0.2, 1.6 }, v0[4] = { 0, 1, 0, 0 };
  tprob P;
  sym_eval ev = tp_eval (&P, P_KEPLER, 1);
  sym_tangent *ta = sym_tangent_new (2, 1, v0), *tb = sym_tangent_new (2, 1,
                                                                      v0);
  CHECK (sym_tangent_renormalise (tb) == SYM_SUCCESS, "renormalise");
  sym_onestep_opts own;
  memset (&own, 0, sizeof own);
  own.separable = 1;
  sym_method_opts o;
  memset (&o, 0, sizeof o);
  o.own = &own;
  double y[4];
  own.tangent = ta;
  run_fixed (sym_step_se, &ev, &o, 0.0, 0.01, 500, y0, y, NULL, 0);
  own.tangent = tb;
  run_fixed (sym_step_se, &ev, &o, 0.0, 0.01, 500, y0, y, NULL, 0);
  const double *a = sym_tangent_phi (ta), *b = sym_tangent_phi (tb);
  const double na = sqrt (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]
                          + a[3] * a[3]);
  CHECK_CLOSE (sym_tangent_log_growth (tb), log (na), 1e-12, "log growth");
  CHECK (na > 1.5, "grew: %g", na);
  for (int i = 0; i < 4; i++)
    CHECK_CLOSE (b[i], a[i] / na, 1e-13, "unit vector");
  CHECK (sym_tangent_log_growth (ta) == 0.0, "no renormalisation");
  sym_tangent_free (ta);
  sym_tangent_free (tb);
  sym_eval_free (&ev);
}

static void
check_bad_input (void)
{
  CHECK (sym_tangent_new (0, 1, NULL) == NULL, "dim 0");
  CHECK (sym_tangent_new (2, 3, NULL) == NULL, "identity of 3 columns");
  CHECK (sym_tangent_new (2, 0, NULL) == NULL, "no columns");
  sym_tangent_free (NULL);
  sym_tangent *tg = sym_tangent_new (1, 2, NULL);
  CHECK (sym_tangent_renormalise (tg) == SYM_EBADINPUT, "renormalise 2");
  sym_onestep_opts own;
  sym_method_opts o;
  memset (&own, 0, sizeof own);
  memset (&o, 0, sizeof o);
  o.own = &own;
  own.tangent = tg;
  int st = 0;
  /* implicit steps: refused */
  const sym_stepper_type *types[3] = { sym_step_se, sym_step_sv,
                                       sym_step_splitting };
  for (int t = 0; t < 3; t++)
    {
      st = 0;
      void *s = types[t]->alloc (1, &o, &st);
      CHECK (! s && st == SYM_EBADINPUT, "%s implicit: %d", types[t]->name,
             st);
    }
  /* another dimension */
  own.separable = 1;
  void *s = sym_step_sv->alloc (2, &o, &st);
  CHECK (! s && st == SYM_EBADINPUT, "dimension: %d", st);
  /* adaptive steps */
  s = sym_step_se->alloc (1, &o, &st);
  static const double atol = 1e-6;
  static const sym_tolerances tol = { 1e-6, &atol, 1, 0 };
  CHECK (s && sym_step_se->set_tolerances (s, &tol) == SYM_EBADINPUT,
         "tolerances");
  sym_step_se->free (s);
  /* and so a run of sym_integrate with them fails at once */
  tprob P;
  sym_system sys = tp_system (&P, P_HO, 1);
  sym_driver_opts d;
  memset (&d, 0, sizeof d);
  d.tf = 1.0;
  d.tol = tol;
  const double y0[2] = { 1, 0 };
  st = sym_integrate (sym_step_sv, &sys, &o, &d, y0, NULL);
  CHECK (st == SYM_EBADINPUT, "adaptive run: %d", st);
  /* fixed steps through the driver: Phi of its last step */
  d.h_fixed = 0.1;
  st = sym_integrate (sym_step_sv, &sys, &o, &d, y0, NULL);
  const double h = 0.1, *phi = sym_tangent_phi (tg);
  CHECK (st == SYM_DONE && fabs (phi[0] - cos (1.0)) < 0.01
         && fabs (phi[1] + sin (1.0)) < 0.01 && fabs (phi[3] - cos (1.0))
         < 0.01, "fixed run: %d, %g %g (h %g)", st, phi[0], phi[1], h);
  sym_tangent_free (tg);
}

int
main (void)
{
  check_against_differences ();
  check_symplectic ();
  check_oscillator ();
  check_vectors ();
  check_renormalised ();
  check_bad_input ();
  return tu_finish ("test_tangent");
}
