/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* test_se_sv_geometry.c -- geometric properties of the SE and SV steppers:
   symplecticity of the step map, bounded energy error, exact conservation
   of angular momentum, time reversibility of SV. */
#include "se_sv_systems.h"

/* one step from a fresh stepper (so the map depends on y only) */
static int
one_step (int sv, sym_eval *ev, const sym_method_opts *o, double t,
          double h, const double *y, double *y1)
{
  int st;
  void *S = tp_alloc (stepper (sv), ev->dim, o, 0, &st);
  if (! S)
    return st;
  st = stepper (sv)->step (S, ev, t, h, t + h, y, y1, NULL);
  stepper (sv)->free (S);
  return st;
}

/* explicit Euler, not symplectic: shows that the test can fail */
static int
one_step_euler (sym_eval *ev, double t, double h, const double *y,
                double *y1)
{
  double f[8];
  int n = 2 * ev->dim;
  tp_f (ev->user, t, y, f);
  for (int i = 0; i < n; i++)
    y1[i] = y[i] + h * f[i];
  return 0;
}

/* max |M^T J M - J| with M the Jacobian of the step map by central
   differences (delta 1e-5: truncation ~1e-10, round-off ~1e-11) */
static double
symplectic_defect (int method, sym_eval *ev, const sym_method_opts *o,
                   double t, double h, const double *y)
{
  const int d = ev->dim, n = 2 * d;
  const double del = 1e-5;
  double M[64], yp[8], ym[8], fp[8], fm[8];
  for (int j = 0; j < n; j++)
    {
      memcpy (yp, y, (size_t) n * sizeof (double));
      memcpy (ym, y, (size_t) n * sizeof (double));
      yp[j] += del;
      ym[j] -= del;
      int st;
      if (method < 2)
        st = one_step (method, ev, o, t, h, yp, fp)
             | one_step (method, ev, o, t, h, ym, fm);
      else
        st = one_step_euler (ev, t, h, yp, fp)
             | one_step_euler (ev, t, h, ym, fm);
      if (st)
        return INFINITY;
      for (int i = 0; i < n; i++)
        M[i + j * n] = (fp[i] - fm[i]) / (2 * del);
    }
  /* (M^T J M)_{ij} = sum_k M_{k i} (J M)_{k j}, J = [0 I; -I 0] */
  double worst = 0;
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++)
      {
        double s = 0;
        for (int k = 0; k < d; k++)
          s += M[k + i * n] * M[(d + k) + j * n]
               - M[(d + k) + i * n] * M[k + j * n];
        double Jij = (j == i + d) ? 1 : (i == j + d) ? -1 : 0;
        worst = fmax (worst, fabs (s - Jij));
      }
  return worst;
}

static void
scenario_symplectic (void)
{
  struct { int kind, sep; double y0[4]; double h; } cases[] = {
    { P_H1, 0, { 0.5, 0.8 }, 0.1 },
    { P_H1, 0, { 0.5, 0.8 }, -0.2 },
    { P_H2, 0, { 0.3, -0.4, 0.5, 0.2 }, 0.1 },
    { P_H2, 0, { 0.3, -0.4, 0.5, 0.2 }, -0.2 },
    { P_PEND, 1, { 1.2, 0.3 }, 0.3 },
    { P_KEPLER, 0, { 0.9, 0.3, -0.2, 1.0 }, 0.05 },
    { P_KEPLER, 1, { 0.9, 0.3, -0.2, 1.0 }, 0.05 },
  };
  for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++)
    {
      tprob P;
      sym_eval ev = tp_eval (&P, cases[c].kind, 1);
      sym_method_opts o = tp_opts (cases[c].sep, 0);
      for (int m = 0; m < 3; m++)
        {
          double def = symplectic_defect (m, &ev, &o, 0.2, cases[c].h,
                                          cases[c].y0);
          printf ("symplecticity %s kind %d sep %d h %+g: |M'JM - J| = %.2e\n",
                  m == 2 ? "Euler" : mname (m), cases[c].kind, cases[c].sep,
                  cases[c].h, def);
          if (m < 2)
            CHECK (def <= 1e-8, "%s kind %d: defect %g", mname (m),
                   cases[c].kind, def);
          else
            CHECK (def > 1e-4, "explicit Euler must fail: %g", def);
        }
    }
}

/* SV on the harmonic oscillator, h = 0.1, 1e5 steps */
static void
scenario_energy (void)
{
  for (int sep = 0; sep < 2; sep++)
    {
      tprob P;
      sym_eval ev = tp_eval (&P, P_HO, 1);
      sym_method_opts o = tp_opts (sep, 0);
      const long N = 100000;
      const double h = 0.1;
      int st;
      void *S = tp_alloc (sym_step_sv, ev.dim, &o, 0, &st);
      double y[2] = { 1, 0 }, yn[2], t = 0;
      double E0 = tp_energy (&P, y), emax = 0, efirst = 0, elast = 0;
      for (long k = 0; k < N && ! st; k++)
        {
          st = sym_step_sv->step (S, &ev, t, h, t + h, y, yn, NULL);
          sym_step_sv->accept (S);
          t += h;
          memcpy (y, yn, sizeof y);
          double e = fabs (tp_energy (&P, y) - E0) / E0;
          emax = fmax (emax, e);
          if (k < N / 10)
            efirst = fmax (efirst, e);
          if (k >= N - N / 10)
            elast = fmax (elast, e);
        }
      CHECK (st == 0, "status %d", st);
      printf ("energy SV HO sep %d: max rel. error %.4e, first 10%% %.4e, "
              "last 10%% %.4e (ratio %.4f); rhs calls/step %.3f\n", sep, emax,
              efirst, elast, elast / efirst, (double) ev.st.cnt.nrhs / N);
      CHECK (emax <= 3e-3, "energy error %g", emax);
      CHECK (elast <= 1.5 * efirst, "energy drift %g vs %g", elast, efirst);
      sym_step_sv->free (S);
    }
}

/* Kepler, e = 0.6: angular momentum q1 p2 - q2 p1 */
static void
scenario_kepler (void)
{
  for (int sv = 0; sv < 2; sv++)
    for (int sep = 0; sep < 2; sep++)
      {
        tprob P;
        sym_eval ev = tp_eval (&P, P_KEPLER, 1);
        sym_method_opts o = tp_opts (sep, 0);
        const long N = 10000;
        const double h = 0.005;
        int st;
        void *S = tp_alloc (stepper (sv), ev.dim, &o, 0, &st);
        double y[4] = { 0.4, 0, 0, 2 }, yn[4], t = 0;
        double L0 = y[0] * y[3] - y[1] * y[2], E0 = tp_energy (&P, y);
        double lmax = 0, emax = 0;
        for (long k = 0; k < N && ! st; k++)
          {
            st = stepper (sv)->step (S, &ev, t, h, t + h, y, yn, NULL);
            stepper (sv)->accept (S);
            t += h;
            memcpy (y, yn, sizeof y);
            lmax = fmax (lmax, fabs (y[0] * y[3] - y[1] * y[2] - L0) / L0);
            emax = fmax (emax, fabs (tp_energy (&P, y) - E0) / fabs (E0));
          }
        CHECK (st == 0, "status %d", st);
        printf ("Kepler %s sep %d: %ld steps of %g: max rel. angular momentum "
                "error %.2e, energy error %.2e; rhs/step %.3f, Newton it/step "
                "%.3f, LU %ld\n", mname (sv), sep, N, h, lmax, emax,
                (double) ev.st.cnt.nrhs / N, (double) ev.st.cnt.nnewton / N,
                ev.st.cnt.nlu);
        CHECK (lmax <= 1e-12, "%s sep %d: angular momentum %g", mname (sv),
               sep, lmax);
        stepper (sv)->free (S);
      }
}

/* SV: N steps with h, then N with -h, back to y0.  The forced pendulum
   (P_PENDF) is chaotic at this amplitude: round-off grows like 1e-16 e^(lambda
   t) over the run, so there only the check that each single step is undone
   applies (a second stepper steps by -h from the end of each step). */
static void
scenario_reversible (void)
{
  struct { int kind, sep; double y0[4]; double h; int whole; } cases[] = {
    { P_H1, 0, { 0.5, 0.8 }, 0.05, 1 },
    { P_H1F, 0, { 0.5, 0.8 }, 0.05, 1 },
    { P_H2, 0, { 0.3, -0.4, 0.5, 0.2 }, 0.05, 1 },
    { P_PEND, 1, { 1.2, 0.3 }, 0.1, 1 },
    { P_PEND, 0, { 1.2, 0.3 }, 0.1, 1 },
    { P_PENDF, 1, { 1.2, 0.3 }, 0.1, 0 },
    { P_PENDF, 0, { 1.2, 0.3 }, 0.1, 0 },
    { P_KEPLER, 1, { 0.4, 0, 0, 2 }, 0.01, 1 },
    { P_KEPLER, 0, { 0.4, 0, 0, 2 }, 0.01, 1 },
  };
  for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++)
    for (int err = 0; err < 2; err++)
      {
        tprob P;
        sym_eval ev = tp_eval (&P, cases[c].kind, 1);
        int n = 2 * ev.dim, st, st2;
        sym_method_opts o = tp_opts (cases[c].sep, 0);
        const long N = 1000;
        double h = cases[c].h, ye[8], y[8], yn[8], yb[8], step_dev = 0;
        void *S = tp_alloc (sym_step_sv, ev.dim, &o, err, &st);
        void *S2 = tp_alloc (sym_step_sv, ev.dim, &o, err, &st2);
        memcpy (y, cases[c].y0, sizeof cases[c].y0);
        double t = 0.1;
        for (long k = 0; k < 2 * N && ! st; k++)
          {
            double hk = k < N ? h : -h;
            double tn = 0.1 + (k < N ? (k + 1) : (2 * N - k - 1)) * h;
            st = sym_step_sv->step (S, &ev, t, hk, t + hk, y, yn,
                                    err ? ye : NULL);
            sym_step_sv->accept (S);
            st |= sym_step_sv->step (S2, &ev, tn, -hk, tn - hk, yn, yb, NULL);
            step_dev = fmax (step_dev, maxdiff (n, yb, y)
                                       / fmax (1, maxabs (n, y)));
            t = tn;
            memcpy (y, yn, sizeof y);
          }
        double dev = maxdiff (n, y, cases[c].y0);
        CHECK (st == 0, "status %d", st);
        printf ("reversibility SV kind %d sep %d adaptive %d: single steps "
                "undone to %.2e; |y - y0| after %ld + %ld steps = %.2e%s\n",
                cases[c].kind, cases[c].sep, err, step_dev, N, N, dev,
                cases[c].whole ? "" : " (chaotic: not checked)");
        /* the implicit path undoes a step to the Newton tolerance (1e-14
           per solve, two solves each way), the explicit one to round-off */
        CHECK (step_dev <= (cases[c].sep ? 2e-15 : 1e-13),
               "kind %d: single step %g", cases[c].kind, step_dev);
        if (cases[c].whole)
          CHECK (dev <= 1e-12 * N, "kind %d: %g", cases[c].kind, dev);
        sym_step_sv->free (S);
        sym_step_sv->free (S2);
      }
}

int
main (void)
{
  scenario_symplectic ();
  scenario_energy ();
  scenario_kepler ();
  scenario_reversible ();
  return tu_finish ("test_se_sv_geometry");
}
