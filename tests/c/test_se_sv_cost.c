/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* test_se_sv_cost.c -- SE and SV steppers: separable vs general paths,
   rhs calls per step, Jacobian sources, reuse of Newton's matrix. */
#include "se_sv_systems.h"

/* ------------------------------------------------------------ separable */
/* the separable and the general paths agree, with and without the error
   estimate */
static void
scenario_separable_paths (void)
{
  struct { int kind; double y0[4]; double h; } cases[] = {
    { P_PEND, { 1.2, 0.3 }, 0.1 },
    { P_PENDF, { 1.2, 0.3 }, 0.1 },
    { P_HO, { 1, 0 }, 0.1 },
    { P_KEPLER, { 0.4, 0, 0, 2 }, 0.005 },
  };
  for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++)
    for (int sv = 0; sv < 2; sv++)
      {
        tprob P;
        sym_eval ev = tp_eval (&P, cases[c].kind, 1);
        int n = 2 * ev.dim;
        const long N = 500;
        double y[2][2][8];
        for (int sep = 0; sep < 2; sep++)
          for (int err = 0; err < 2; err++)
            {
              sym_method_opts o = tp_opts (sep, 0);
              int st = run_fixed (stepper (sv), &ev, &o, 0, cases[c].h, N,
                                  cases[c].y0, y[sep][err], NULL, err);
              CHECK (st == 0, "status %d", st);
            }
        double dsep = fmax (maxdiff (n, y[0][0], y[1][0]),
                            maxdiff (n, y[0][1], y[1][1]));
        double derr = fmax (maxdiff (n, y[0][0], y[0][1]),
                            maxdiff (n, y[1][0], y[1][1]));
        printf ("separable on/off %s kind %d: %ld steps, |difference| %.2e "
                "(with/without error estimate %.2e)\n", mname (sv),
                cases[c].kind, N, dsep, derr);
        CHECK (dsep <= 1e-12, "%s kind %d: %g", mname (sv), cases[c].kind,
               dsep);
        CHECK (derr <= 1e-13, "%s kind %d: %g", mname (sv), cases[c].kind,
               derr);
      }
}

/* ------------------------------------------------------------ calls/step */
static void
scenario_calls_per_step (void)
{
  printf ("calls per fixed step (N = 1000 from t0 = -0.35, driver-style "
          "times):\n");
  struct { int kind; double y0[4]; double h; } cases[] = {
    { P_PEND, { 1.2, 0.3 }, 0.01 },
    { P_KEPLER, { 0.4, 0, 0, 2 }, 0.005 },
    { P_H1, { 0.5, 0.8 }, 0.01 },
    { P_H2, { 0.3, -0.4, 0.5, 0.2 }, 0.01 },
  };
  for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++)
    for (int sv = 0; sv < 2; sv++)
      for (int sep = 0; sep < 2; sep++)
        for (int err = 0; err < 2; err++)
          for (int jac = 1; jac >= 0; jac--)
            {
              if (sep && (cases[c].kind == P_H1 || cases[c].kind == P_H2))
                continue;
              if (sep && ! jac)
                continue;
              tprob P;
              sym_eval ev = tp_eval (&P, cases[c].kind, jac);
              const long N = 1000;
              double y[8];
              sym_method_opts o = tp_opts (sep, 0);
              int st = run_fixed (stepper (sv), &ev, &o, -0.35, cases[c].h,
                                  N, cases[c].y0, y, NULL, err);
              CHECK (st == 0, "status %d", st);
              double cps = (double) ev.st.cnt.nrhs / N;
              printf ("  %s kind %d %s %s jac %-8s: rhs %.3f (fd %.3f), "
                      "Newton it %.3f, LU %ld, jac calls %ld\n", mname (sv),
                      cases[c].kind, sep ? "separable" : "general  ",
                      err ? "+error" : "      ", jac ? "analytic" : "FD", cps,
                      (double) ev.st.cnt.nfd / N,
                      (double) ev.st.cnt.nnewton / N, ev.st.cnt.nlu,
                      ev.st.cnt.njac);
              if (sep)
                {
                  /* SE: 2 (the estimate's f(y_{k+1}) is the next step's
                     first call); SV: 2 + 1 at the start, 3 with the
                     estimate */
                  double lim = (sv && err) ? 3.05 : 2.05;
                  CHECK (cps <= lim, "%s sep err %d: %g calls/step",
                         mname (sv), err, cps);
                  CHECK (ev.st.cnt.nnewton == 0 && ev.st.cnt.nlu == 0
                         && ev.st.cnt.njac == 0, "explicit path used Newton");
                }
            }
}

/* adaptive-style use of separable SE and SV: random h, rejections (retries
   from the same point), yerr every attempt: 2 calls per attempt (SE), 3
   (SV), one more for f at the start, and for SV one more for each attempt
   before the first accepted step (the estimate's midpoint call) */
static void
scenario_calls_adaptive (void)
{
  for (int sv = 0; sv < 2; sv++)
    {
      tprob P;
      sym_eval ev = tp_eval (&P, P_PEND, 1);
      sym_method_opts o = tp_opts (1, 0);
      int st;
      void *S = tp_alloc (stepper (sv), ev.dim, &o, 1, &st);
      double y[2] = { 1.2, 0.3 }, yn[2], ye[2], t = 0, h = 0.05;
      long attempts = 0, accepted = 0, fresh = 0;
      srand (7);
      while (accepted < 500 && ! st)
        {
          st = stepper (sv)->step (S, &ev, t, h, t + h, y, yn, ye);
          attempts++;
          fresh += accepted == 0;
          if (rand () % 4 == 0)   /* reject: retry with a smaller h */
            {
              h *= 0.6;
              continue;
            }
          stepper (sv)->accept (S);
          accepted++;
          t += h;
          memcpy (y, yn, sizeof y);
          h *= 1.0 + 0.5 * (rand () / (double) RAND_MAX);
          h = fmin (h, 0.1);
        }
      CHECK (st == 0, "status %d", st);
      double cpa = (double) ev.st.cnt.nrhs / attempts;
      printf ("adaptive-style separable %s with error estimate: %ld attempts "
              "(%ld accepted), %.3f rhs calls per attempt\n", mname (sv),
              attempts, accepted, cpa);
      if (! sv)
        CHECK (ev.st.cnt.nrhs == 2 * attempts + 1, "SE: %ld calls for %ld",
               ev.st.cnt.nrhs, attempts);
      else
        CHECK (ev.st.cnt.nrhs == 3 * attempts + 1 + fresh,
               "SV: %ld calls for %ld (%ld fresh)", ev.st.cnt.nrhs, attempts,
               fresh);
      stepper (sv)->free (S);
    }
}

/* ------------------------------------------------------------ jacobians */
static void
scenario_jacobian_sources (void)
{
  /* the test problems' own Df against differences of their f */
  int kinds[] = { P_H1, P_H1F, P_H2, P_KEPLER, P_DAMPED, P_PENDF };
  for (size_t c = 0; c < sizeof kinds / sizeof kinds[0]; c++)
    {
      tprob P;
      sym_eval ev = tp_eval (&P, kinds[c], 1);
      int n = 2 * ev.dim;
      double y[4] = { 0.3, -0.4, 0.5, 0.2 }, J[64], Jn[64], yp[4], ym[4],
             fp[4], fm[4];
      if (n == 2)
        y[0] = 0.7, y[1] = -0.3;
      if (kinds[c] == P_KEPLER)
        y[0] = 0.8;
      tp_df (&P, 0.3, y, J);
      for (int j = 0; j < n; j++)
        {
          memcpy (yp, y, sizeof y);
          memcpy (ym, y, sizeof y);
          yp[j] += 1e-6;
          ym[j] -= 1e-6;
          tp_f (&P, 0.3, yp, fp);
          tp_f (&P, 0.3, ym, fm);
          for (int i = 0; i < n; i++)
            Jn[i + j * n] = (fp[i] - fm[i]) / 2e-6;
        }
      CHECK (maxdiff (n * n, J, Jn) < 1e-8, "test Df kind %d: %g", kinds[c],
             maxdiff (n * n, J, Jn));
    }
  /* runs with analytic Df and with sym_jac's finite differences */
  struct { int kind; double y0[4]; double h; } cases[] = {
    { P_H1, { 0.5, 0.8 }, 0.05 },
    { P_H1F, { 0.5, 0.8 }, 0.05 },
    { P_H2, { 0.3, -0.4, 0.5, 0.2 }, 0.05 },
    { P_DAMPED, { 1, 0 }, 0.1 },
    { P_KEPLER, { 0.4, 0, 0, 2 }, 0.005 },
  };
  for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++)
    for (int sv = 0; sv < 2; sv++)
      {
        double y[2][8];
        long calls[2], nlu[2];
        int n = 0;
        for (int jac = 0; jac < 2; jac++)
          {
            tprob P;
            sym_eval ev = tp_eval (&P, cases[c].kind, jac);
            n = 2 * ev.dim;
            sym_method_opts o = tp_opts (0, 0);
            int st = run_fixed (stepper (sv), &ev, &o, 0, cases[c].h, 400,
                                cases[c].y0, y[jac], NULL, 0);
            CHECK (st == 0, "status %d", st);
            calls[jac] = ev.st.cnt.nrhs;
            nlu[jac] = ev.st.cnt.nlu;
          }
        double dj = maxdiff (n, y[0], y[1]);
        printf ("jacobian analytic vs FD %s kind %d: |difference| %.2e after "
                "400 steps (rhs calls %ld vs %ld, LU %ld vs %ld)\n",
                mname (sv), cases[c].kind, dj, calls[1], calls[0], nlu[1],
                nlu[0]);
        CHECK (dj <= 1e-10, "%s kind %d: %g", mname (sv), cases[c].kind, dj);
      }
}

/* The Newton matrix is kept across steps (one LU for a whole run on a
   linear problem, where it stays exact) and rebuilt after a change of h by
   more than SYM_REBUILD_H. */
static void
scenario_lu_reuse (void)
{
  for (int sv = 0; sv < 2; sv++)
    {
      tprob P;
      sym_eval ev = tp_eval (&P, P_DAMPED, 1);
      sym_method_opts o = tp_opts (0, 0);
      int st;
      void *S = tp_alloc (stepper (sv), ev.dim, &o, 0, &st);
      double y[2] = { 1, 0 }, yn[2], t = 0, h = 0.01;
      for (int k = 0; k < 100; k++)
        {
          st |= stepper (sv)->step (S, &ev, t, h, t + h, y, yn, NULL);
          stepper (sv)->accept (S);
          t += h;
          memcpy (y, yn, sizeof y);
        }
      long lu100 = ev.st.cnt.nlu;
      st |= stepper (sv)->step (S, &ev, t, 1.1 * h, t + 1.1 * h, y, yn, NULL);
      long lu_small = ev.st.cnt.nlu - lu100;
      st |= stepper (sv)->step (S, &ev, t, 1.5 * h, t + 1.5 * h, y, yn, NULL);
      long lu_big = ev.st.cnt.nlu - lu100 - lu_small;
      CHECK (st == 0, "status");
      printf ("LU reuse %s (damped oscillator): %ld factorizations in 100 "
              "steps of h = 0.01 (Newton it/step %.2f); then h*1.1: %ld new, "
              "h*1.5: %ld new\n", mname (sv), lu100, ev.st.cnt.nnewton / 100.0,
              lu_small, lu_big);
      CHECK (lu100 == (sv ? 2 : 1), "LU not reused: %ld", lu100);
      CHECK (lu_small == 0, "h*1.1 refactored");
      CHECK (lu_big == (sv ? 2 : 1), "h*1.5: %ld", lu_big);
      stepper (sv)->free (S);
    }
}

/* On a nonlinear problem the matrix is rebuilt when the extra iterations
   it causes add up to the cost of a new Jacobian: bounds on the cost at
   h = 0.01 and 0.05, with the starts from the history of the unknowns */
static void
scenario_lu_policy (void)
{
  for (int sv = 0; sv < 2; sv++)
    for (int ih = 0; ih < 2; ih++)
      {
        /* the P_H1 run is about 10 time units */
        double h = ih ? 0.05 : 0.01;
        long N = (long) (10 / h);
        tprob P;
        sym_eval ev = tp_eval (&P, P_H1, 1);
        sym_method_opts o = tp_opts (0, 0);
        double y0[2] = { 0.5, 0.8 }, y[2];
        int st = run_fixed (stepper (sv), &ev, &o, 0, h, N, y0, y, NULL, 0);
        double cost = (double) (ev.st.cnt.nrhs + ev.st.cnt.njac) / N;
        CHECK (st == 0, "status %d", st);
        printf ("LU policy %s P_H1 h = %.2f: %.2f callbacks/step (rhs %.2f + "
                "jac %.2f), Newton it/step %.2f, LU/step %.2f\n", mname (sv),
                h, cost, (double) ev.st.cnt.nrhs / N,
                (double) ev.st.cnt.njac / N, (double) ev.st.cnt.nnewton / N,
                (double) ev.st.cnt.nlu / N);
        double lim = sv ? (ih ? 7.5 : 4.3) : (ih ? 4.2 : 2.3);
        CHECK (cost <= lim, "%s h %g: %g callbacks/step", mname (sv), h, cost);
      }
}

int
main (void)
{
  scenario_separable_paths ();
  scenario_calls_per_step ();
  scenario_calls_adaptive ();
  scenario_jacobian_sources ();
  scenario_lu_reuse ();
  scenario_lu_policy ();
  return tu_finish ("test_se_sv_cost");
}
