/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* test_se_sv_failures.c -- SE and SV steppers when things go wrong:
   failure injection (rhs, Jacobian), Newton failure, allocation failure,
   memory of the explicit paths, bad input, a wrong user Df, overflow,
   f that is not separable. */
#include "se_sv_systems.h"
#include "test_spvi_systems.h"   /* ts_osc_jac */

/* ------------------------------------------------------------ injection */
/* Three steps (the first from a fresh start); on the failing step, check
   the status, then retry it without the failure and go on: the result must
   match the clean run. */
typedef struct {
  int sv, kind, sep, jac, err;
} fcase;

static int
three_steps (const fcase *fc, tprob *P, sym_eval *ev, double *y,
             int *fail_status)
{
  int st;
  sym_method_opts o = tp_opts (fc->sep, 1);
  void *S = tp_alloc (stepper (fc->sv), ev->dim, &o, fc->err, &st);
  if (! S)
    return st;
  double yn[8], ye[8], t = 0.2, h = 0.05, yd[8];
  int n = 2 * ev->dim;
  *fail_status = 0;
  for (int k = 0; k < 3; k++)
    {
      st = stepper (fc->sv)->step (S, ev, t, h, t + h, y, yn,
                                   fc->err ? ye : NULL);
      if (st)
        {
          *fail_status = st;
          if (st < 0 && k > 0)
            {
              /* the last accepted step is still there */
              int sd = stepper (fc->sv)->dense (S, ev, t, yd);
              CHECK (sd == 0 && maxdiff (n, yd, y) == 0, "dense after fail");
            }
          P->fail_at = P->jfail_at = 0;   /* the retry succeeds */
          st = stepper (fc->sv)->step (S, ev, t, h, t + h, y, yn,
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

/* what the injections met */
typedef struct {
  long ncases, ninject, njinject, nfdnan, nretry;
  int seen[3][2];   /* failures reported, by mode: rhs, Jacobian */
} tally;

static int
mode_status (int mode)
{
  return mode == 1 ? SYM_NONFINITE : mode == 2 ? SYM_RECOVERABLE
         : SYM_ECALLBACK;
}

/* rhs failures at every call of the clean run (calls of them) */
static void
inject_rhs (const fcase *fc, const double *yi, const double *yclean,
            long calls, tally *ta)
{
  for (long at = 1; at <= calls; at++)
    for (int mode = 1; mode <= 3; mode++)
      {
        tprob P;
        sym_eval ev = tp_eval (&P, fc->kind, fc->jac);
        int n = 2 * ev.dim, fs;
        double y[8];
        P.fail_at = at;
        P.fail_mode = mode;
        memcpy (y, yi, (size_t) n * sizeof (double));
        int st = three_steps (fc, &P, &ev, y, &fs);
        ta->ninject++;
        /* also inside a finite-difference Jacobian (a failed matrix) the
           step reports the callback's own status; but a NaN at a
           forward-stepped state of the finite differences (or of the
           probe of the user's Df) is met by stepping backwards, and a
           recoverable failure in a solve started from the history of the
           unknown by the solve from the explicit start: no failure, the
           same result */
        int retry = mode <= 2 && fs == 0 && ev.st.cnt.nrestart > 0;
        int fd_nan = mode == 1 && fs == 0 && ! retry && ev.st.cnt.nfd > 0;
        int ok = fd_nan || retry || fs == mode_status (mode);
        ta->nfdnan += fd_nan;
        ta->nretry += retry;
        CHECK (ok, "%s kind %d sep %d jac %d err %d: rhs fail mode %d at "
               "call %ld -> status %d (%s)", mname (fc->sv), fc->kind,
               fc->sep, fc->jac, fc->err, mode, at, fs,
               sym_status_name (fs));
        CHECK (ev.st.fail_status != 0, "fail_status not set");
        CHECK (st == 0, "retry failed: %d", st);
        double dv = maxdiff (n, y, yclean);
        CHECK (dv <= 1e-12, "after retry: %g", dv);
        ta->seen[mode - 1][0] += ! fd_nan && ! retry;
      }
}

/* Jacobian failures at every call of the clean run */
static void
inject_jac (const fcase *fc, const double *yi, const double *yclean,
            long jcalls, tally *ta)
{
  for (long at = 1; at <= jcalls; at++)
    for (int mode = 1; mode <= 3; mode++)
      {
        tprob P;
        sym_eval ev = tp_eval (&P, fc->kind, fc->jac);
        int n = 2 * ev.dim, fs;
        double y[8];
        P.jfail_at = at;
        P.jfail_mode = mode;
        memcpy (y, yi, (size_t) n * sizeof (double));
        int st = three_steps (fc, &P, &ev, y, &fs);
        ta->njinject++;
        int retry = mode <= 2 && fs == 0 && ev.st.cnt.nrestart > 0;
        int ok = retry || fs == mode_status (mode);
        ta->nretry += retry;
        ta->seen[mode - 1][1] += ! retry;
        CHECK (ok, "%s kind %d: jac fail mode %d at call %ld -> status %d "
               "(%s)", mname (fc->sv), fc->kind, mode, at, fs,
               sym_status_name (fs));
        CHECK (st == 0, "retry failed: %d", st);
        CHECK (maxdiff (n, y, yclean) <= 1e-12, "after retry: %g",
               maxdiff (n, y, yclean));
      }
}

static void
scenario_failure_injection (void)
{
  const double y0[3][4] = { { 0.5, 0.8 }, { 0.3, -0.4, 0.5, 0.2 },
                            { 0.4, 0, 0, 2 } };
  const int kinds[] = { P_H1, P_H2, P_PEND, P_KEPLER };
  tally ta;
  memset (&ta, 0, sizeof ta);
  for (int sv = 0; sv < 2; sv++)
    for (int kc = 0; kc < 4; kc++)
      for (int err = 0; err < 2; err++)
        for (int jac = 0; jac < 2; jac++)
          {
            fcase fc = { sv, kinds[kc], kc >= 2, jac, err };
            if (fc.sep && ! jac)
              continue;
            const double *yi = fc.kind == P_H2 ? y0[1]
                               : fc.kind == P_KEPLER ? y0[2] : y0[0];
            tprob P;
            sym_eval ev = tp_eval (&P, fc.kind, jac);
            double yclean[8];
            int fs;
            memcpy (yclean, yi, 2 * (size_t) ev.dim * sizeof (double));
            int st = three_steps (&fc, &P, &ev, yclean, &fs);
            CHECK (st == 0 && fs == 0, "clean run %d %d", st, fs);
            ta.ncases++;
            inject_rhs (&fc, yi, yclean, P.calls, &ta);
            inject_jac (&fc, yi, yclean, P.jcalls, &ta);
          }
  printf ("failure injection: %ld configurations, %ld rhs failures, %ld "
          "Jacobian failures injected, each reported with its own status "
          "(rhs/Jacobian: NaN %d/%d NONFINITE, +1 %d/%d RECOVERABLE, -1 "
          "%d/%d ECALLBACK), or, %ld NaN at forward-stepped states of "
          "finite differences, met by backward steps, and %ld recoverable "
          "failures in solves started from the history, met by the "
          "explicit start\n", ta.ncases, ta.ninject, ta.njinject,
          ta.seen[0][0], ta.seen[0][1], ta.seen[1][0], ta.seen[1][1],
          ta.seen[2][0], ta.seen[2][1], ta.nfdnan, ta.nretry);
  CHECK (ta.nfdnan > 0, "the backward finite differences were exercised");
  CHECK (ta.nretry > 0, "the retry from the explicit start was exercised");
}

/* Newton cannot converge: a recoverable failure, and the stepper goes on.
   Here the implicit kick has no solution at all: on P_H1, f_p = -(p^2 q +
   q), so P = p_k + c f_p(q_k, P) at q_k = 2.5, p_k = 3 is 2.5 c P^2 + P +
   2.5 c - 3 = 0, real roots only for 25 c^2 - 30 c - 1 <= 0, c <= 1.23;
   h = 5 asks for c = 5 (SE) or 2.5 (SV). */
static void
scenario_newton_fail (void)
{
  for (int sv = 0; sv < 2; sv++)
    {
      tprob P;
      sym_eval ev = tp_eval (&P, P_H1, 1);
      sym_method_opts o = tp_opts (0, 0);
      int st;
      void *S = tp_alloc (stepper (sv), ev.dim, &o, 1, &st);
      double y[2] = { 2.5, 3.0 }, yn[2], ye[2], yref[2];
      st = stepper (sv)->step (S, &ev, 0, 5.0, 5.0, y, yn, ye);
      printf ("Newton at h = 5 on P_H1 from (2.5, 3) %s: status %d (%s)\n",
              mname (sv), st, sym_status_name (st));
      CHECK (st == SYM_NEWTON_FAIL, "%s: %d", mname (sv), st);
      st = stepper (sv)->step (S, &ev, 0, 0.001, 0.001, y, yn, ye);
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

/* every allocation of alloc may fail, and a step's own allocations */
static void
scenario_alloc_failure (void)
{
  for (int sv = 0; sv < 2; sv++)
    {
      tprob P;
      sym_eval ev = tp_eval (&P, P_H2, 0);
      sym_method_opts o = tp_opts (0, 1);
      int st;
      sym_set_allocator (counting_alloc, free);
      alloc_count = 0;
      alloc_fail_at = 0;
      void *S = stepper (sv)->alloc (ev.dim, &o, &st);
      long nalloc = alloc_count;
      stepper (sv)->free (S);
      for (long k = 1; k <= nalloc; k++)
        {
          alloc_count = 0;
          alloc_fail_at = k;
          st = 12345;
          S = stepper (sv)->alloc (ev.dim, &o, &st);
          CHECK (S == NULL && st == SYM_ENOMEM, "alloc failure %ld: %p %d", k,
                 S, st);
          if (S)
            stepper (sv)->free (S);
        }
      /* a step of a small system allocates nothing: its finite
         differences work on the stack (a large system's failing
         workspace is test_core's) */
      alloc_count = 0;
      alloc_fail_at = 0;
      S = tp_alloc (stepper (sv), ev.dim, &o, 1, &st);
      const long before = alloc_count;
      alloc_fail_at = alloc_count + 1;
      double y[4] = { 0.3, -0.4, 0.5, 0.2 }, yn[4], ye[4];
      st = stepper (sv)->step (S, &ev, 0, 0.05, 0.05, y, yn, ye);
      CHECK (st == 0 && alloc_count == before && ev.st.cnt.nfd > 0,
             "step without memory: %d, %ld allocations", st,
             alloc_count - before);
      alloc_fail_at = 0;
      stepper (sv)->free (S);
      sym_set_allocator (NULL, NULL);
      printf ("allocation failures %s: each of the %ld allocations of alloc "
              "fails cleanly\n", mname (sv), nalloc);
    }
}

/* The explicit (Separable) steps allocate O(d) memory, the implicit ones
   the O(d^2) of their Newton matrices and Df: counted at d = 1000 (a
   harmonic chain, f = [p; -q]). */
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
scenario_separable_memory (void)
{
  int d = 1000;
  sym_system sys;
  memset (&sys, 0, sizeof sys);
  sys.dim = d;
  sys.rhs = osc_rhs;
  sys.user = &d;
  sym_eval ev;
  sym_eval_init (&ev, &sys);
  double *y = calloc (4 * (size_t) d, sizeof (double));
  double *yn = y + 2 * d;
  for (int sv = 0; sv < 2; sv++)
    for (int sep = 1; sep >= 0; sep--)
      {
        sym_method_opts o = tp_opts (sep, 0);
        int st;
        alloc_bytes = 0;
        sym_set_allocator (bytes_alloc, free);
        void *S = stepper (sv)->alloc (d, &o, &st);
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
            st = stepper (sv)->step (S, &ev, 0, 0.01, 0.01, y, yn, NULL);
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
/* Refused: a dimension below 1, a step without an evaluator, h = 0 or
   not finite, t or tend not finite; a system without rhs (the driver's
   check: a stepper no longer sees the system) */
static void
scenario_bad_input (void)
{
  for (int sv = 0; sv < 2; sv++)
    {
      tprob P;
      sym_eval ev = tp_eval (&P, P_PEND, 1);
      sym_method_opts o = tp_opts (1, 0);
      int st;
      CHECK (stepper (sv)->alloc (-1, &o, &st) == NULL
             && st == SYM_EBADINPUT, "dim -1");
      CHECK (stepper (sv)->alloc (0, &o, &st) == NULL
             && st == SYM_EBADINPUT, "dim 0");
      CHECK (stepper (sv)->alloc (0, &o, NULL) == NULL, "no status");
      void *S = stepper (sv)->alloc (ev.dim, NULL, &st);   /* default opts */
      CHECK (S != NULL && st == 0, "NULL opts");
      double y[2] = { 1.2, 0.3 }, yn[2];
      CHECK (stepper (sv)->step (S, NULL, 0, 0.1, 0.1, y, yn, NULL)
             == SYM_EBADINPUT, "no evaluator");
      CHECK (stepper (sv)->step (S, &ev, 0, 0.0, 0.0, y, yn, NULL)
             == SYM_EBADINPUT, "h = 0");
      CHECK (stepper (sv)->step (S, &ev, 0, NAN, NAN, y, yn, NULL)
             == SYM_EBADINPUT, "h = NaN");
      CHECK (stepper (sv)->step (S, &ev, INFINITY, 0.1, INFINITY, y, yn,
                                 NULL) == SYM_EBADINPUT, "t = Inf");
      CHECK (stepper (sv)->step (S, &ev, 0, 0.1, NAN, y, yn, NULL)
             == SYM_EBADINPUT, "tend = NaN");
      stepper (sv)->free (S);
      stepper (sv)->free (NULL);

      sym_system bad = tp_system (&P, P_PEND, 1);
      bad.rhs = NULL;
      sym_driver_opts dopts;
      memset (&dopts, 0, sizeof dopts);
      dopts.tf = 1.0;
      dopts.h_fixed = 0.1;
      CHECK (sym_integrate (stepper (sv), &bad, &o, &dopts, y, NULL)
             == SYM_EBADINPUT, "no rhs");

      /* accept after a failed step takes nothing */
      ev = tp_eval (&P, P_PEND, 1);
      S = stepper (sv)->alloc (ev.dim, &o, &st);
      P.fail_at = P.calls + 1;
      P.fail_mode = 2;
      CHECK (stepper (sv)->step (S, &ev, 0, 0.1, 0.1, y, yn, NULL)
             == SYM_RECOVERABLE, "injected failure");
      stepper (sv)->accept (S);
      CHECK (stepper (sv)->dense (S, &ev, 0.05, yn) == SYM_EBADINPUT,
             "accept after a failure");
      stepper (sv)->free (S);
      P.fail_at = 0;
    }
}

/* A fresh state (what the driver makes after an event stop or a dropped
   Df) starts afresh: f(t_k, y_k) again, the same result, no dense output
   before its first step */
static void
scenario_fresh_state (void)
{
  for (int sv = 0; sv < 2; sv++)
    {
      tprob P;
      sym_eval ev = tp_eval (&P, P_PEND, 1);
      sym_method_opts o = tp_opts (1, 0);
      int st;
      double y[2] = { 1.2, 0.3 }, yn[2], y1[2], y2[2], y2b[2];
      void *S = stepper (sv)->alloc (ev.dim, &o, &st);
      stepper (sv)->step (S, &ev, 0, 0.1, 0.1, y, y1, NULL);
      stepper (sv)->accept (S);
      long c0 = ev.st.cnt.nrhs;
      stepper (sv)->step (S, &ev, 0.1, 0.1, 0.1 + 0.1, y1, y2, NULL);
      long c_cont = ev.st.cnt.nrhs - c0;
      stepper (sv)->free (S);
      S = stepper (sv)->alloc (ev.dim, &o, &st);
      CHECK (stepper (sv)->dense (S, &ev, 0.05, yn) == SYM_EBADINPUT,
             "dense of a fresh state");
      c0 = ev.st.cnt.nrhs;
      stepper (sv)->step (S, &ev, 0.1, 0.1, 0.1 + 0.1, y1, y2b, NULL);
      long c_fresh = ev.st.cnt.nrhs - c0;
      CHECK (maxdiff (2, y2, y2b) == 0, "from a fresh state: %g",
             maxdiff (2, y2, y2b));
      if (sv)
        CHECK (c_cont == 2 && c_fresh == 3, "SV calls %ld %ld", c_cont,
               c_fresh);
      else
        CHECK (c_cont == 2 && c_fresh == 2, "SE calls %ld %ld", c_cont,
               c_fresh);
      stepper (sv)->free (S);
    }
}

/* the output sink of the runs below: the last row */
static int
keep_last (double t, const double *y, void *user)
{
  (void) t;
  memcpy (user, y, 2 * sizeof (double));
  return 0;
}

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
   oscillator's, ts_osc_jac.  A Df with a NaN (f finite) is dropped too. */
static void
scenario_jac_check (void)
{
  tprob P;
  sym_eval ev = tp_eval (&P, P_DAMPED, 1);
  P.c = 100.0;
  double y[2] = { 0.7, -0.4 };
  int dropped = -1;
  CHECK (sym_jac_check (&ev, 0.5, y, &dropped) == SYM_SUCCESS
         && dropped == 0 && ev.jac == tp_jac && ! ev.st.jac_dropped,
         "the exact Df is kept: %d", dropped);
  ev.jac = ts_osc_jac;
  CHECK (sym_jac_check (&ev, 0.5, y, &dropped) == SYM_SUCCESS
         && dropped == 1 && ev.jac == NULL && ev.st.jac_dropped
         && ev.st.jac_dropped_t == 0.5, "Df without the damping is dropped");
  ev = tp_eval (&P, P_DAMPED, 1);
  ev.jac = nan_jac;
  CHECK (sym_jac_check (&ev, 0.5, y, &dropped) == SYM_SUCCESS
         && dropped == 1 && ev.jac == NULL && ev.st.jac_dropped,
         "a Df with a NaN is dropped: %d", dropped);

  for (int sv = 0; sv < 2; sv++)
    {
      double yend[3][2];
      int dropped_run[3];
      for (int k = 0; k < 3; k++)
        {
          sym_system sys = tp_system (&P, P_DAMPED, 1);
          P.c = 100.0;
          sys.jac = k == 2 ? nan_jac : k ? ts_osc_jac : NULL;
          sym_method_opts mo = tp_opts (0, 0);
          sym_driver_opts o = fixed_run (2.0, 0.01, keep_last, yend[k]);
          double y0[2] = { 1.0, 0.0 };
          sym_stats stats;
          int st = sym_integrate (stepper (sv), &sys, &mo, &o, y0, &stats);
          CHECK (st == SYM_DONE && stats.t_reached == 2.0, "%s, c = 100, "
                 "%s: %s at t = %g", mname (sv), k == 2 ? "Df with a NaN"
                 : k ? "Df without damping" : "finite differences",
                 sym_status_name (st), stats.t_reached);
          dropped_run[k] = stats.jac_dropped;
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
scenario_overflow (void)
{
  for (int sv = 0; sv < 2; sv++)
    for (int sep = 0; sep < 2; sep++)
      for (int dense = 0; dense < 2; dense++)
        {
          tprob P;
          sym_system sys = tp_system (&P, P_HO, 1);
          sys.rhs = rhs_watch;
          rhs_saw_inf = 0;
          sym_method_opts mo = tp_opts (sep, dense);
          rows_seen r = { 0, 1, NAN };
          sym_driver_opts o = fixed_run (1200.0, 3.0, rows_watch, &r);
          o.refine = dense ? 4 : 1;
          double y0[2] = { 1.0, 0.0 };
          sym_stats stats;
          int st = sym_integrate (stepper (sv), &sys, &mo, &o, y0, &stats);
          CHECK (st == SYM_EOVERFLOW && stats.t_reached == 1104.0
                 && r.t == 1104.0 && r.finite && ! rhs_saw_inf, "%s, "
                 "separable %d, dense %d: %s at t = %g, last row t = %g, "
                 "rows finite %d, f at Inf %d", mname (sv), sep, dense,
                 sym_status_name (st), stats.t_reached, r.t, r.finite,
                 rhs_saw_inf);
        }
}

/* Separable steps flag an f that is not separable (sym_sep_check): SE
   when f_p moves with p (P_H1, and the damping of P_DAMPED), SV when f_q
   moves with q (P_H1); not for the separable problems, forced in t or
   not */
static void
scenario_sep_check (void)
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
        sym_method_opts mo = tp_opts (1, 0);
        double y0[4] = { 0.5, 0.3, 0.1, 1.2 }, yend[4];
        sym_driver_opts o = fixed_run (1.0, 0.1, keep_last, yend);
        sym_stats stats;
        stats.sep_broken = -1;   /* set by the run */
        int st = sym_integrate (stepper (sv), &sys, &mo, &o, y0, &stats);
        int want = sv ? sv_flags[k] : se_flags[k];
        CHECK (st == SYM_DONE && stats.sep_broken == want
               && (! want || stats.sep_broken_t == 0.0), "%s kind %d: "
               "status %s, not separable %d (want %d) at t = %g",
               mname (sv), kinds[k], sym_status_name (st), stats.sep_broken,
               want, stats.sep_broken_t);
      }
}

int
main (void)
{
  scenario_failure_injection ();
  scenario_newton_fail ();
  scenario_alloc_failure ();
  scenario_separable_memory ();
  scenario_bad_input ();
  scenario_fresh_state ();
  scenario_jac_check ();
  scenario_overflow ();
  scenario_sep_check ();
  return tu_finish ("test_se_sv_failures");
}
