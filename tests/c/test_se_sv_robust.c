/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* test_se_sv_robust.c -- SE and SV steppers: separable vs general paths,
   rhs calls per step, Jacobian sources, LU reuse, failure injection (rhs,
   Jacobian, allocator), bad input, reset. */
#include "se_sv_systems.h"
#include "test_spvi_systems.h"   /* ts_osc_jac */
#include "steprec.h"

static const sym_stepper_type *
stepper (int sv)
{
  return sv ? sym_step_sv : sym_step_se;
}

static const char *
mname (int sv)
{
  return sv ? "SV" : "SE";
}

/* ------------------------------------------------------------ separable */
static void
test_separable (void)
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
        sym_system sys = tp_system (&P, cases[c].kind, 1);
        int n = 2 * sys.dim;
        const long N = 500;
        double y[2][2][8];
        for (int sep = 0; sep < 2; sep++)
          for (int err = 0; err < 2; err++)
            {
              sym_method_opts o = tp_opts (sep, err, 0);
              int st = run_fixed (stepper (sv), &sys, &o, 0, cases[c].h, N,
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
test_calls (void)
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
              sym_system sys = tp_system (&P, cases[c].kind, jac);
              const long N = 1000;
              double y[8];
              sym_method_opts o = tp_opts (sep, err, 0);
              int st = run_fixed (stepper (sv), &sys, &o, -0.35, cases[c].h,
                                  N, cases[c].y0, y, NULL, err);
              CHECK (st == 0, "status %d", st);
              double cps = (double) sys.cnt.nrhs / N;
              printf ("  %s kind %d %s %s jac %-8s: rhs %.3f (fd %.3f), "
                      "Newton it %.3f, LU %ld, jac calls %ld\n", mname (sv),
                      cases[c].kind, sep ? "separable" : "general  ",
                      err ? "+error" : "      ", jac ? "analytic" : "FD", cps,
                      (double) sys.cnt.nfd / N, (double) sys.cnt.nnewton / N,
                      sys.cnt.nlu, sys.cnt.njac);
              if (sep)
                {
                  /* SE: 2 (the estimate's f(y_{k+1}) is the next step's
                     first call); SV: 2 + 1 at the start, 3 with the
                     estimate */
                  double lim = (sv && err) ? 3.05 : 2.05;
                  CHECK (cps <= lim, "%s sep err %d: %g calls/step",
                         mname (sv), err, cps);
                  CHECK (sys.cnt.nnewton == 0 && sys.cnt.nlu == 0
                         && sys.cnt.njac == 0, "explicit path used Newton");
                }
            }
}

/* adaptive-style use of separable SE and SV: random h, rejections (retries
   from the same point), yerr every attempt: 2 calls per attempt (SE), 3
   (SV), one more for f at the start, and for SV one more for each attempt
   before the first accepted step (the estimate's midpoint call) */
static void
test_calls_adaptive (void)
{
  for (int sv = 0; sv < 2; sv++)
    {
      tprob P;
      sym_system sys = tp_system (&P, P_PEND, 1);
      sym_method_opts o = tp_opts (1, 1, 0);
      int st;
      void *S = stepper (sv)->alloc (&sys, &o, &st);
      double y[2] = { 1.2, 0.3 }, yn[2], ye[2], t = 0, h = 0.05;
      long attempts = 0, accepted = 0, fresh = 0;
      srand (7);
      while (accepted < 500 && ! st)
        {
          st = stepper (sv)->step (S, &sys, t, h, t + h, y, yn, ye);
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
      double cpa = (double) sys.cnt.nrhs / attempts;
      printf ("adaptive-style separable %s with error estimate: %ld attempts "
              "(%ld accepted), %.3f rhs calls per attempt\n", mname (sv),
              attempts, accepted, cpa);
      if (! sv)
        CHECK (sys.cnt.nrhs == 2 * attempts + 1, "SE: %ld calls for %ld",
               sys.cnt.nrhs, attempts);
      else
        CHECK (sys.cnt.nrhs == 3 * attempts + 1 + fresh,
               "SV: %ld calls for %ld (%ld fresh)", sys.cnt.nrhs, attempts,
               fresh);
      stepper (sv)->free (S);
    }
}

/* ------------------------------------------------------------ jacobians */
static void
test_jacobian_sources (void)
{
  /* the test problems' own Df against differences of their f */
  int kinds[] = { P_H1, P_H1F, P_H2, P_KEPLER, P_DAMPED, P_PENDF };
  for (size_t c = 0; c < sizeof kinds / sizeof kinds[0]; c++)
    {
      tprob P;
      sym_system sys = tp_system (&P, kinds[c], 1);
      int n = 2 * sys.dim;
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
            sym_system sys = tp_system (&P, cases[c].kind, jac);
            n = 2 * sys.dim;
            sym_method_opts o = tp_opts (0, 0, 0);
            int st = run_fixed (stepper (sv), &sys, &o, 0, cases[c].h, 400,
                                cases[c].y0, y[jac], NULL, 0);
            CHECK (st == 0, "status %d", st);
            calls[jac] = sys.cnt.nrhs;
            nlu[jac] = sys.cnt.nlu;
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
   more than 20%.  On a nonlinear problem it is rebuilt when the extra
   iterations it causes add up to the cost of a new Jacobian.  Measured
   while tuning that rule (P_H1, h = 0.01, 5 time units, rhs + jac calls per
   step, Newton started from an explicit step): SE 5.92 with the matrix
   never rebuilt, 4.00 rebuilt every step, 3.97 with the rule; SV 10.50,
   7.87, 7.83.  Here: bounds on the cost at h = 0.01 and 0.05 with the
   starts from the history of the unknowns (sym_pred), which also keep the
   matrix longer: SE 2.01 and 3.29, SV 3.86 and 6.13 (with the explicit
   starts alone 4.04, 5.34, 7.89, 9.80). */
static void
test_lu_reuse (void)
{
  for (int sv = 0; sv < 2; sv++)
    {
      tprob P;
      sym_system sys = tp_system (&P, P_DAMPED, 1);
      sym_method_opts o = tp_opts (0, 0, 0);
      int st;
      void *S = stepper (sv)->alloc (&sys, &o, &st);
      double y[2] = { 1, 0 }, yn[2], t = 0, h = 0.01;
      for (int k = 0; k < 100; k++)
        {
          st |= stepper (sv)->step (S, &sys, t, h, t + h, y, yn, NULL);
          stepper (sv)->accept (S);
          t += h;
          memcpy (y, yn, sizeof y);
        }
      long lu100 = sys.cnt.nlu;
      st |= stepper (sv)->step (S, &sys, t, 1.1 * h, t + 1.1 * h, y, yn, NULL);
      long lu_small = sys.cnt.nlu - lu100;
      st |= stepper (sv)->step (S, &sys, t, 1.5 * h, t + 1.5 * h, y, yn, NULL);
      long lu_big = sys.cnt.nlu - lu100 - lu_small;
      CHECK (st == 0, "status");
      printf ("LU reuse %s (damped oscillator): %ld factorizations in 100 "
              "steps of h = 0.01 (Newton it/step %.2f); then h*1.1: %ld new, "
              "h*1.5: %ld new\n", mname (sv), lu100, sys.cnt.nnewton / 100.0,
              lu_small, lu_big);
      CHECK (lu100 == (sv ? 2 : 1), "LU not reused: %ld", lu100);
      CHECK (lu_small == 0, "h*1.1 refactored");
      CHECK (lu_big == (sv ? 2 : 1), "h*1.5: %ld", lu_big);
      stepper (sv)->free (S);
    }
  for (int sv = 0; sv < 2; sv++)
    for (int ih = 0; ih < 2; ih++)
      {
        /* the P_H1 run is about 10 time units */
        double h = ih ? 0.05 : 0.01;
        long N = (long) (10 / h);
        tprob P;
        sym_system sys = tp_system (&P, P_H1, 1);
        sym_method_opts o = tp_opts (0, 0, 0);
        double y0[2] = { 0.5, 0.8 }, y[2];
        int st = run_fixed (stepper (sv), &sys, &o, 0, h, N, y0, y, NULL, 0);
        double cost = (double) (sys.cnt.nrhs + sys.cnt.njac) / N;
        CHECK (st == 0, "status %d", st);
        printf ("LU policy %s P_H1 h = %.2f: %.2f callbacks/step (rhs %.2f + "
                "jac %.2f), Newton it/step %.2f, LU/step %.2f\n", mname (sv),
                h, cost, (double) sys.cnt.nrhs / N, (double) sys.cnt.njac / N,
                (double) sys.cnt.nnewton / N, (double) sys.cnt.nlu / N);
        double lim = sv ? (ih ? 7.5 : 4.3) : (ih ? 4.2 : 2.3);
        CHECK (cost <= lim, "%s h %g: %g callbacks/step", mname (sv), h, cost);
      }
}

/* ------------------------------------------------------------ failures */
/* Three steps (the first from a fresh start); on the failing step, check
   the status, then retry it without the failure and go on: the result must
   match the clean run. */
typedef struct {
  int sv, kind, sep, jac, err;
} fcase;

static int
three_steps (const fcase *fc, tprob *P, sym_system *sys, double *y,
             int *fail_status, int *fail_step)
{
  int st;
  sym_method_opts o = tp_opts (fc->sep, fc->err, 1);
  void *S = stepper (fc->sv)->alloc (sys, &o, &st);
  if (! S)
    return st;
  double yn[8], ye[8], t = 0.2, h = 0.05, yd[8];
  int n = 2 * sys->dim;
  *fail_status = 0;
  *fail_step = -1;
  for (int k = 0; k < 3; k++)
    {
      st = stepper (fc->sv)->step (S, sys, t, h, t + h, y, yn,
                                   fc->err ? ye : NULL);
      if (st)
        {
          *fail_status = st;
          *fail_step = k;
          if (st < 0 && k > 0)
            {
              /* the last accepted step is still there */
              int sd = stepper (fc->sv)->dense (S, sys, t, yd);
              CHECK (sd == 0 && maxdiff (n, yd, y) == 0, "dense after fail");
            }
          P->fail_at = P->jfail_at = 0;   /* the retry succeeds */
          st = stepper (fc->sv)->step (S, sys, t, h, t + h, y, yn,
                                       fc->err ? ye : NULL);
          if (st)
            break;
        }
      stepper (fc->sv)->accept (S);
      t += h;
      memcpy (y, yn, (size_t) n * sizeof (double));
    }
  stepper (fc->sv)->free (S);
  return st;
}

static void
test_failures (void)
{
  const double y0[3][4] = { { 0.5, 0.8 }, { 0.3, -0.4, 0.5, 0.2 },
                            { 0.4, 0, 0, 2 } };
  long ncases = 0, ninject = 0, njinject = 0, nfdnan = 0, nretry = 0;
  int seen[3][8];
  memset (seen, 0, sizeof seen);
  for (int sv = 0; sv < 2; sv++)
    for (int kc = 0; kc < 4; kc++)
      for (int err = 0; err < 2; err++)
        for (int jac = 0; jac < 2; jac++)
          {
            int kinds[] = { P_H1, P_H2, P_PEND, P_KEPLER };
            fcase fc = { sv, kinds[kc], kc >= 2, jac, err };
            if (fc.sep && ! jac)
              continue;
            const double *yi = (tp_dim (fc.kind) == 2) ? y0[1] : y0[0];
            double yclean[8], y[8];
            if (fc.kind == P_PEND)
              yi = y0[0];
            if (fc.kind == P_KEPLER)
              yi = y0[2];
            tprob P;
            sym_system sys = tp_system (&P, fc.kind, jac);
            int n = 2 * sys.dim, fs, fk;
            memcpy (yclean, yi, (size_t) n * sizeof (double));
            int st = three_steps (&fc, &P, &sys, yclean, &fs, &fk);
            CHECK (st == 0 && fs == 0, "clean run %d %d", st, fs);
            long calls = P.calls, jcalls = P.jcalls;
            ncases++;
            /* rhs failures at every call */
            for (long at = 1; at <= calls; at++)
              for (int mode = 1; mode <= 3; mode++)
                {
                  sys = tp_system (&P, fc.kind, jac);
                  P.fail_at = at;
                  P.fail_mode = mode;
                  memcpy (y, yi, (size_t) n * sizeof (double));
                  st = three_steps (&fc, &P, &sys, y, &fs, &fk);
                  ninject++;
                  /* also inside a finite-difference Jacobian (a failed
                     matrix) the step reports the callback's own status;
                     but a NaN at a forward-stepped state of the finite
                     differences (or of the probe of the user's Df) is
                     met by stepping backwards: no failure, the same
                     result (checked below) */
                  /* and a recoverable failure (NaN, +1) in a solve
                     started from the history of the unknown (the third
                     step, with f at the steps' ends known) is met by the
                     solve from the explicit start: no failure either */
                  int retry = mode <= 2 && fs == 0 && sys.cnt.nrestart > 0;
                  int fd_nan = mode == 1 && fs == 0 && ! retry
                               && sys.cnt.nfd > 0;
                  int ok = fd_nan || retry
                           || fs == (mode == 1 ? SYM_NONFINITE
                                     : mode == 2 ? SYM_RECOVERABLE
                                     : SYM_ECALLBACK);
                  nfdnan += fd_nan;
                  nretry += retry;
                  CHECK (ok, "%s kind %d sep %d jac %d err %d: rhs fail mode "
                         "%d at call %ld -> status %d (%s)", mname (sv),
                         fc.kind, fc.sep, jac, err, mode, at, fs,
                         sym_status_name (fs));
                  CHECK (sys.fail_status != 0, "fail_status not set");
                  CHECK (st == 0, "retry failed: %d", st);
                  double dv = maxdiff (n, y, yclean);
                  CHECK (dv <= 1e-12, "after retry: %g", dv);
                  seen[mode - 1][0] += ! fd_nan && ! retry;
                }
            /* Jacobian failures */
            for (long at = 1; at <= jcalls; at++)
              for (int mode = 1; mode <= 3; mode++)
                {
                  sys = tp_system (&P, fc.kind, jac);
                  P.jfail_at = at;
                  P.jfail_mode = mode;
                  memcpy (y, yi, (size_t) n * sizeof (double));
                  st = three_steps (&fc, &P, &sys, y, &fs, &fk);
                  njinject++;
                  int retry = mode <= 2 && fs == 0 && sys.cnt.nrestart > 0;
                  int ok = retry || fs == (mode == 1 ? SYM_NONFINITE
                                           : mode == 2 ? SYM_RECOVERABLE
                                           : SYM_ECALLBACK);
                  nretry += retry;
                  seen[mode - 1][1] += ! retry;
                  CHECK (ok, "%s kind %d: jac fail mode %d at call %ld -> "
                         "status %d (%s)", mname (sv), fc.kind, mode, at, fs,
                         sym_status_name (fs));
                  CHECK (st == 0, "retry failed: %d", st);
                  CHECK (maxdiff (n, y, yclean) <= 1e-12, "after retry: %g",
                         maxdiff (n, y, yclean));
                }
          }
  printf ("failure injection: %ld configurations, %ld rhs failures, %ld "
          "Jacobian failures injected, each reported with its own status "
          "(rhs/Jacobian: NaN %d/%d NONFINITE, +1 %d/%d RECOVERABLE, -1 "
          "%d/%d ECALLBACK), or, %ld NaN at forward-stepped states of "
          "finite differences, met by backward steps, and %ld recoverable "
          "failures in solves started from the history, met by the "
          "explicit start\n", ncases, ninject, njinject, seen[0][0],
          seen[0][1], seen[1][0], seen[1][1], seen[2][0], seen[2][1],
          nfdnan, nretry);
  CHECK (nfdnan > 0, "the backward finite differences were exercised");
  CHECK (nretry > 0, "the retry from the explicit start was exercised");
}

/* Newton cannot converge: a recoverable failure, and the stepper goes on.
   Here the implicit kick has no solution at all: on P_H1, f_p = -(p^2 q +
   q), so P = p_k + c f_p(q_k, P) at q_k = 2.5, p_k = 3 is 2.5 c P^2 + P +
   2.5 c - 3 = 0, real roots only for 25 c^2 - 30 c - 1 <= 0, c <= 1.23;
   h = 5 asks for c = 5 (SE) or 2.5 (SV). */
static void
test_newton_fail (void)
{
  for (int sv = 0; sv < 2; sv++)
    {
      tprob P;
      sym_system sys = tp_system (&P, P_H1, 1);
      sym_method_opts o = tp_opts (0, 1, 0);
      int st;
      void *S = stepper (sv)->alloc (&sys, &o, &st);
      double y[2] = { 2.5, 3.0 }, yn[2], ye[2], yref[2];
      st = stepper (sv)->step (S, &sys, 0, 5.0, 5.0, y, yn, ye);
      printf ("Newton at h = 5 on P_H1 from (2.5, 3) %s: status %d (%s)\n",
              mname (sv), st, sym_status_name (st));
      CHECK (st == SYM_NEWTON_FAIL, "%s: %d", mname (sv), st);
      st = stepper (sv)->step (S, &sys, 0, 0.001, 0.001, y, yn, ye);
      CHECK (st == 0, "after the failure: %d", st);
      (sv ? naive_sv : naive_se) (&P, 0, 0.001, y, yref);
      CHECK (maxdiff (2, yn, yref) < 1e-13, "after the failure: %g",
             maxdiff (2, yn, yref));
      stepper (sv)->free (S);
    }
}

/* ------------------------------------------------------------ allocator */
static long alloc_count, alloc_fail_at;

static void *
counting_alloc (size_t n)
{
  alloc_count++;
  if (alloc_count == alloc_fail_at)
    return NULL;
  return malloc (n);
}

static void
test_alloc_failure (void)
{
  for (int sv = 0; sv < 2; sv++)
    {
      tprob P;
      sym_system sys = tp_system (&P, P_H2, 0);
      sym_method_opts o = tp_opts (0, 1, 1);
      int st;
      sym_set_allocator (counting_alloc, free);
      alloc_count = 0;
      alloc_fail_at = 0;
      void *S = stepper (sv)->alloc (&sys, &o, &st);
      long nalloc = alloc_count;
      stepper (sv)->free (S);
      for (long k = 1; k <= nalloc; k++)
        {
          alloc_count = 0;
          alloc_fail_at = k;
          st = 12345;
          S = stepper (sv)->alloc (&sys, &o, &st);
          CHECK (S == NULL && st == SYM_ENOMEM, "alloc failure %ld: %p %d", k,
                 S, st);
          if (S)
            stepper (sv)->free (S);
        }
      /* a step whose finite-difference Jacobian cannot get memory */
      alloc_count = 0;
      alloc_fail_at = 0;
      S = stepper (sv)->alloc (&sys, &o, &st);
      alloc_fail_at = alloc_count + 1;
      double y[4] = { 0.3, -0.4, 0.5, 0.2 }, yn[4], ye[4];
      st = stepper (sv)->step (S, &sys, 0, 0.05, 0.05, y, yn, ye);
      CHECK (st == SYM_ENOMEM, "step without memory: %d", st);
      alloc_fail_at = 0;
      st = stepper (sv)->step (S, &sys, 0, 0.05, 0.05, y, yn, ye);
      CHECK (st == 0, "step after memory came back: %d", st);
      stepper (sv)->free (S);
      sym_set_allocator (NULL, NULL);
      printf ("allocation failures %s: each of the %ld allocations of alloc "
              "fails cleanly\n", mname (sv), nalloc);
    }
}

/* The explicit (Separable) steps allocate O(d) memory, the implicit ones
   the O(d^2) of their Newton matrices and Df: counted at d = 1000 (a
   harmonic chain, f = [p; -q]), where d^2 doubles are 8 MB. */
static size_t alloc_bytes;

static void *
bytes_alloc (size_t n)
{
  alloc_bytes += n;
  return malloc (n);
}

static int
osc_rhs (double t, const double *y, double *dy, void *user)
{
  const int d = *(const int *) user;
  (void) t;
  for (int i = 0; i < d; i++)
    {
      dy[i] = y[d + i];
      dy[d + i] = -y[i];
    }
  return 0;
}

static void
test_separable_memory (void)
{
  int d = 1000;
  sym_system sys;
  memset (&sys, 0, sizeof sys);
  sys.dim = d;
  sys.rhs = osc_rhs;
  sys.user = &d;
  double *y = calloc (4 * (size_t) d, sizeof (double));
  double *yn = y + 2 * d;
  for (int sv = 0; sv < 2; sv++)
    for (int sep = 1; sep >= 0; sep--)
      {
        sym_method_opts o;
        memset (&o, 0, sizeof o);
        o.separable = sep;
        int st;
        alloc_bytes = 0;
        sym_set_allocator (bytes_alloc, free);
        void *S = stepper (sv)->alloc (&sys, &o, &st);
        sym_set_allocator (NULL, NULL);
        size_t bytes = alloc_bytes;
        CHECK (S != NULL, "%s d = %d: alloc %d", mname (sv), d, st);
        if (! S)
          continue;
        if (sep)
          {
            /* and the step runs without the O(d^2) parts: one explicit
               step of the chain from q = 1, p = 0 */
            for (int i = 0; i < d; i++)
              y[i] = 1.0, y[d + i] = 0.0;
            st = stepper (sv)->step (S, &sys, 0, 0.01, 0.01, y, yn, NULL);
            CHECK (st == 0 && fabs (yn[0] - cos (0.01)) < 1e-4
                   && fabs (yn[d] + sin (0.01)) < 1e-4,
                   "%s separable step at d = %d: %d %g %g", mname (sv), d,
                   st, yn[0], yn[d]);
          }
        stepper (sv)->free (S);
        const double per_d = (double) bytes / (8.0 * d);
        printf ("%s d = %d, Separable %s: alloc takes %zu bytes (%.0f "
                "doubles per d)\n", mname (sv), d, sep ? "on" : "off", bytes,
                per_d);
        if (sep)
          CHECK (per_d < 100, "%s separable: %g doubles per d", mname (sv),
                 per_d);
        else
          CHECK (per_d > d, "%s implicit: %g doubles per d (its Newton "
                 "matrices need d^2)", mname (sv), per_d);
      }
  free (y);
}

/* ------------------------------------------------------------ misc */
static void
test_bad_input_and_reset (void)
{
  for (int sv = 0; sv < 2; sv++)
    {
      tprob P;
      sym_system sys = tp_system (&P, P_PEND, 1);
      sym_method_opts o = tp_opts (1, 0, 0);
      int st;
      CHECK (stepper (sv)->alloc (NULL, &o, &st) == NULL
             && st == SYM_EBADINPUT, "NULL system");
      sym_system bad = sys;
      bad.dim = 0;
      CHECK (stepper (sv)->alloc (&bad, &o, &st) == NULL
             && st == SYM_EBADINPUT, "dim 0");
      bad = sys;
      bad.rhs = NULL;
      CHECK (stepper (sv)->alloc (&bad, &o, NULL) == NULL, "no rhs");
      void *S = stepper (sv)->alloc (&sys, NULL, &st);   /* default opts */
      CHECK (S != NULL && st == 0, "NULL opts");
      double y[2] = { 1.2, 0.3 }, yn[2];
      CHECK (stepper (sv)->step (S, &sys, 0, 0.0, 0.0, y, yn, NULL)
             == SYM_EBADINPUT, "h = 0");
      CHECK (stepper (sv)->step (S, &sys, 0, NAN, NAN, y, yn, NULL)
             == SYM_EBADINPUT, "h = NaN");
      CHECK (stepper (sv)->step (S, &sys, INFINITY, 0.1, INFINITY, y, yn,
                                 NULL) == SYM_EBADINPUT, "t = Inf");
      CHECK (stepper (sv)->step (S, &sys, 0, 0.1, NAN, y, yn, NULL)
             == SYM_EBADINPUT, "tend = NaN");
      stepper (sv)->free (S);
      stepper (sv)->free (NULL);

      /* accept after a failed step takes nothing */
      S = stepper (sv)->alloc (&sys, &o, &st);
      P.fail_at = P.calls + 1;
      P.fail_mode = 2;
      CHECK (stepper (sv)->step (S, &sys, 0, 0.1, 0.1, y, yn, NULL)
             == SYM_RECOVERABLE, "injected failure");
      stepper (sv)->accept (S);
      CHECK (stepper (sv)->dense (S, &sys, 0.05, yn) == SYM_EBADINPUT,
             "accept after a failure");
      stepper (sv)->free (S);
      P.fail_at = 0;

      /* reset: the next step starts afresh (f(t_k, y_k) again) and gives
         the same result */
      S = stepper (sv)->alloc (&sys, &o, &st);
      double y1[2], y2[2], y2b[2];
      stepper (sv)->step (S, &sys, 0, 0.1, 0.1, y, y1, NULL);
      stepper (sv)->accept (S);
      long c0 = sys.cnt.nrhs;
      stepper (sv)->step (S, &sys, 0.1, 0.1, 0.1 + 0.1, y1, y2, NULL);
      long c_cont = sys.cnt.nrhs - c0;
      stepper (sv)->reset (S);
      CHECK (stepper (sv)->dense (S, &sys, 0.05, yn) == SYM_EBADINPUT,
             "dense after reset");
      c0 = sys.cnt.nrhs;
      stepper (sv)->step (S, &sys, 0.1, 0.1, 0.1 + 0.1, y1, y2b, NULL);
      long c_reset = sys.cnt.nrhs - c0;
      CHECK (maxdiff (2, y2, y2b) == 0, "after reset: %g",
             maxdiff (2, y2, y2b));
      if (sv)
        CHECK (c_cont == 2 && c_reset == 3, "SV calls %ld %ld", c_cont,
               c_reset);
      else
        CHECK (c_cont == 2 && c_reset == 2, "SE calls %ld %ld", c_cont,
               c_reset);
      stepper (sv)->free (S);
    }
}

/* the output sink of test_jac_check: the last row */
static int
keep_last (double t, const double *y, void *user)
{
  (void) t;
  memcpy (user, y, 2 * sizeof (double));
  return 0;
}

/* A Df with a NaN where f is finite (a Hessian undefined there) */
static int
nan_jac (double t, const double *y, double *df, void *user)
{
  tp_jac (t, y, df, user);
  df[1] = NAN;
  return 0;
}

/* A Newton failure with the user's Df checks it against finite
   differences: dropped when it disagrees (the run then goes on with
   finite differences, as it would have from the start), kept when it
   agrees.  The Df that misses the damping of P_DAMPED is the undamped
   oscillator's, ts_osc_jac.  A Df with a NaN (f finite) is dropped too:
   before, the step shrank to nothing. */
/* Driver options of a fixed-step run from 0 to tf with steps h, the rows
   handed to out (user data u) */
static sym_driver_opts
fixed_run (double tf, double h, sym_output_fn out, void *u)
{
  sym_driver_opts o;
  memset (&o, 0, sizeof o);
  o.t0 = 0.0;
  o.tf = tf;
  o.h_fixed = h;
  o.refine = 1;
  o.output = out;
  o.output_user = u;
  return o;
}

static void
test_jac_check (void)
{
  tprob P;
  sym_system sys = tp_system (&P, P_DAMPED, 1);
  P.c = 100.0;
  double y[2] = { 0.7, -0.4 };
  int dropped = -1;
  CHECK (sym_jac_check (&sys, 0.5, y, &dropped) == SYM_SUCCESS
         && dropped == 0 && sys.jac == tp_jac && ! sys.jac_dropped,
         "the exact Df is kept: %d", dropped);
  sys.jac = ts_osc_jac;
  CHECK (sym_jac_check (&sys, 0.5, y, &dropped) == SYM_SUCCESS
         && dropped == 1 && sys.jac == NULL && sys.jac_dropped
         && sys.jac_dropped_t == 0.5, "Df without the damping is dropped");
  sys = tp_system (&P, P_DAMPED, 1);
  sys.jac = nan_jac;
  CHECK (sym_jac_check (&sys, 0.5, y, &dropped) == SYM_SUCCESS
         && dropped == 1 && sys.jac == NULL && sys.jac_dropped,
         "a Df with a NaN is dropped: %d", dropped);

  for (int sv = 0; sv < 2; sv++)
    {
      double yend[3][2];
      int dropped_run[3];
      for (int k = 0; k < 3; k++)
        {
          sys = tp_system (&P, P_DAMPED, 1);
          P.c = 100.0;
          sys.jac = k == 2 ? nan_jac : k ? ts_osc_jac : NULL;
          sym_method_opts mo = tp_opts (0, 0, 0);
          sym_driver_opts o = fixed_run (2.0, 0.01, keep_last, yend[k]);
          double y0[2] = { 1.0, 0.0 }, tr = 0.0;
          int st = sym_integrate (stepper (sv), &sys, &mo, &o, y0, &tr);
          CHECK (st == SYM_DONE && tr == 2.0, "%s, c = 100, %s: %s at t = "
                 "%g", mname (sv), k == 2 ? "Df with a NaN"
                 : k ? "Df without damping" : "finite differences",
                 sym_status_name (st), tr);
          dropped_run[k] = sys.jac_dropped;
        }
      CHECK (! dropped_run[0] && dropped_run[1] && dropped_run[2]
             && maxdiff (2, yend[0], yend[1]) < 1e-12
             && maxdiff (2, yend[0], yend[2]) < 1e-12,
             "%s: Df dropped %d %d %d, differences %g %g", mname (sv),
             dropped_run[0], dropped_run[1], dropped_run[2],
             maxdiff (2, yend[0], yend[1]), maxdiff (2, yend[0], yend[2]));
    }
}

/* f that records whether it was ever called at a non-finite state */
static int rhs_saw_inf;
static int
rhs_watch (double t, const double *y, double *dy, void *user)
{
  for (int i = 0; i < 2; i++)
    if (! isfinite (y[i]))
      rhs_saw_inf = 1;
  return tp_rhs (t, y, dy, user);
}

/* rows handed out: all finite? the last t */
typedef struct { long rows; int finite; double t; } rows_seen;
static int
rows_watch (double t, const double *y, void *user)
{
  rows_seen *r = user;
  r->rows++;
  r->finite = r->finite && isfinite (y[0]) && isfinite (y[1]);
  r->t = t;
  return 0;
}

/* An unstable fixed step (the oscillator, h = 3 > 2) grows the solution
   until a step's result overflows: that step is refused, the run ends
   with SYM_EOVERFLOW at the step before it (t = 1104), every row handed
   out is finite and f is never called with Inf; with and without the
   dense output and the error estimate's f at the step's end, and on the
   separable path */
static void
test_overflow (void)
{
  for (int sv = 0; sv < 2; sv++)
    for (int sep = 0; sep < 2; sep++)
      for (int dense = 0; dense < 2; dense++)
        {
          tprob P;
          sym_system sys = tp_system (&P, P_HO, 1);
          sys.rhs = rhs_watch;
          rhs_saw_inf = 0;
          sym_method_opts mo = tp_opts (sep, 0, dense);
          rows_seen r = { 0, 1, NAN };
          sym_driver_opts o = fixed_run (1200.0, 3.0, rows_watch, &r);
          o.refine = dense ? 4 : 1;
          double y0[2] = { 1.0, 0.0 }, tr = 0.0;
          int st = sym_integrate (stepper (sv), &sys, &mo, &o, y0, &tr);
          CHECK (st == SYM_EOVERFLOW && tr == 1104.0 && r.t == 1104.0
                 && r.finite && ! rhs_saw_inf, "%s, separable %d, dense "
                 "%d: %s at t = %g, last row t = %g, rows finite %d, f at "
                 "Inf %d", mname (sv), sep, dense, sym_status_name (st),
                 tr, r.t, r.finite, rhs_saw_inf);
        }
}

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
test_pred (void)
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
  sym_onestep_reset (&o);
  CHECK (o.pr[0].n == 0 && ! o.pr[0].have_new, "reset");
}

/* sym_fcache_move: f moved linearly by the cached Df to a nearby point at
   the same t; nothing without a Df, at another t, or at the same point */
static void
test_fcache_move (void)
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

/* Separable steps flag an f that is not separable (sym_sep_check): SE
   when f_p moves with p (P_H1, and the damping of P_DAMPED), SV when f_q
   moves with q (P_H1); not for the separable problems, forced in t or
   not */
static void
test_sep_check (void)
{
  const int kinds[] = { P_H1, P_DAMPED, P_PEND, P_PENDF, P_HO, P_KEPLER };
  const int se_flags[] = { 1, 1, 0, 0, 0, 0 }, sv_flags[] = { 1, 0, 0, 0,
                                                             0, 0 };
  for (int sv = 0; sv < 2; sv++)
    for (int k = 0; k < 6; k++)
      {
        tprob P;
        sym_system sys = tp_system (&P, kinds[k], 0);
        P.c = 0.1;
        sym_method_opts mo = tp_opts (1, 0, 0);
        double y0[4] = { 0.5, 0.3, 0.1, 1.2 }, yend[4], tr = 0.0;
        sym_driver_opts o = fixed_run (1.0, 0.1, keep_last, yend);
        sys.sep_broken = -1;   /* cleared by the run */
        int st = sym_integrate (stepper (sv), &sys, &mo, &o, y0, &tr);
        int want = sv ? sv_flags[k] : se_flags[k];
        CHECK (st == SYM_DONE && sys.sep_broken == want
               && (! want || sys.sep_broken_t == 0.0), "%s kind %d: "
               "status %s, not separable %d (want %d) at t = %g",
               mname (sv), kinds[k], sym_status_name (st), sys.sep_broken,
               want, sys.sep_broken_t);
      }
}

int
main (void)
{
  test_separable ();
  test_calls ();
  test_calls_adaptive ();
  test_jacobian_sources ();
  test_lu_reuse ();
  test_failures ();
  test_newton_fail ();
  test_jac_check ();
  test_overflow ();
  test_fcache_move ();
  test_pred ();
  test_sep_check ();
  test_alloc_failure ();
  test_separable_memory ();
  test_bad_input_and_reset ();
  return tu_finish ("test_se_sv_robust");
}
