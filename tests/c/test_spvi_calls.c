/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* test_spvi_calls.c -- the calls the SPVI stepper makes: analytic and
   finite-difference Jacobians, the probe of a user's Df, the batch
   callback, f and Df in one call, and the failures of the callbacks and
   of Newton. */
#include "sym.h"
#include "testutil.h"
#include "test_spvi_systems.h"

#define T sym_step_spvi

/* Kepler e = 0.6 from the pericentre, (4,3) with Newton's matrix newmat,
   nsteps steps of 2 pi/100 through ev; the end into y */
static int
kepler_run (sym_eval *ev, int newmat, long nsteps, double *y)
{
  const double h = 2 * TS_PI / 100;
  sym_method_opts o;
  sym_spvi_opts so;
  ts_opts (&o, &so, 4, 3);
  so.newton_matrix = newmat;
  int st;
  void *s = T->alloc (ev->dim, &o, &st);
  if (! s)
    return st;
  ts_kep_y0 (0.6, y);
  st = ts_run_fixed (T, s, ev, 0.0, h, nsteps, y);
  T->free (s);
  return st;
}

/* ------------------------------------------------------- Jacobian sources */
static void
scenario_analytic_vs_fd (void)
{
  double ya[4], yf[4];
  sym_eval sa = ts_eval (2, ts_kep, ts_kep_jac, NULL);
  sym_eval sf = ts_eval (2, ts_kep, NULL, NULL);
  int st1 = kepler_run (&sa, SYM_MATRIX_AUTO, 1000, ya);
  int st2 = kepler_run (&sf, SYM_MATRIX_AUTO, 1000, yf);
  double dif = ts_maxdiff (4, ya, yf);
  CHECK (st1 == 0 && st2 == 0 && dif <= 1e-10,
         "analytic vs finite-difference Jacobian: %.3g", dif);
  /* the analytic Df's only differences: its probe (f and one state) */
  CHECK (sa.st.cnt.nfd == 2 && sf.st.cnt.nfd > 0 && sf.st.cnt.njac == 0,
         "counters: nfd %ld / %ld", sa.st.cnt.nfd, sf.st.cnt.nfd);
  printf ("Kepler (4,3), 10 periods: analytic vs FD Jacobian differ by "
          "%.2e; calls/step: analytic %.2f rhs + %.3f jac, FD %.2f rhs "
          "(%.2f of them FD)\n", dif, sa.st.cnt.nrhs / 1000.0,
          sa.st.cnt.njac / 1000.0, sf.st.cnt.nrhs / 1000.0,
          sf.st.cnt.nfd / 1000.0);
}

/* Kepler's Df times kep_scale: a user's Df far too large */
static double kep_scale;
static int
kep_jac_scaled (double t, const double *y, double *df, void *user)
{
  int st = ts_kep_jac (t, y, df, user);
  for (int i = 0; i < 16; i++)
    df[i] *= kep_scale;
  return st;
}

/* A Df too large by c makes Newton's corrections 1/c of what they should
   be: with c = 1e12 they are below round-off from the first on, and each
   solve stops at once, accepted, at its start.  Without the probe of the
   first Df (jac_probed set by hand) one period ends far from the orbit;
   with it, Df is dropped in the first step (at its first node) and finite
   differences give the steps of the right Df. */
static void
scenario_gross_jacobian (void)
{
  const double h = 2 * TS_PI / 100;
  double yk[4], yu[4], yr[4];
  kep_scale = 1e12;
  for (int probe = 0; probe < 2; probe++)
    {
      sym_eval sk = ts_eval (2, ts_kep, kep_jac_scaled, NULL);
      sk.jac_probed = ! probe;
      int stk = kepler_run (&sk, SYM_MATRIX_AUTO, 100, probe ? yk : yu);
      CHECK (stk == 0 && sk.st.jac_dropped == probe
             && (! probe || (sk.st.jac_dropped_t >= 0.0
                             && sk.st.jac_dropped_t < h && sk.jac == NULL)),
             "Df times 1e12, probe %d: status %d, dropped %d at t = %g",
             probe, stk, sk.st.jac_dropped, sk.st.jac_dropped_t);
    }
  sym_eval sr = ts_eval (2, ts_kep, ts_kep_jac, NULL);
  kepler_run (&sr, SYM_MATRIX_AUTO, 100, yr);
  printf ("Kepler (4,3), one period with Df times 1e12: %.3g from the "
          "steps of the right Df (%.3g without the probe)\n",
          ts_maxdiff (4, yk, yr), ts_maxdiff (4, yu, yr));
  CHECK (ts_maxdiff (4, yk, yr) <= 1e-10 && ts_maxdiff (4, yu, yr) > 1.0,
         "Df times 1e12: %.3g with the probe, %.3g without",
         ts_maxdiff (4, yk, yr), ts_maxdiff (4, yu, yr));
}

/* Vectorized: the batch callback gives the same numbers, bit for bit,
   with one call per residual instead of m */
static void
scenario_vectorized (void)
{
  double ya[4], yb[4];
  sym_eval sa = ts_eval (2, ts_kep, ts_kep_jac, NULL);
  sym_eval sb = ts_eval (2, ts_kep, ts_kep_jac, NULL);
  sb.rhs_batch = ts_kep_batch;
  int st1 = kepler_run (&sa, SYM_MATRIX_AUTO, 1000, ya);
  int st3 = kepler_run (&sb, SYM_MATRIX_AUTO, 1000, yb);
  CHECK (st1 == 0 && st3 == 0 && ts_maxdiff (4, ya, yb) == 0.0,
         "batch vs single calls differ by %.3g", ts_maxdiff (4, ya, yb));
  CHECK (sb.st.cnt.nrhs_states == sa.st.cnt.nrhs_states
         && 2 * sb.st.cnt.nrhs < sa.st.cnt.nrhs,
         "batch: %ld calls (%ld states) vs %ld calls (%ld states)",
         sb.st.cnt.nrhs, sb.st.cnt.nrhs_states, sa.st.cnt.nrhs,
         sa.st.cnt.nrhs_states);
  printf ("Vectorized: %.2f rhs calls per step (%.2f states) vs %.2f\n",
          sb.st.cnt.nrhs / 1000.0, sb.st.cnt.nrhs_states / 1000.0,
          sa.st.cnt.nrhs / 1000.0);
}

/* Vectorized with finite differences: each step's matrix is new, from
   one call for the nodes and their 2d m perturbed states, whose f the
   residual there reuses; then a step needs one call when its first,
   exact Newton correction is enough.  The steps are those of the
   analytic Jacobian to round-off. */
static void
scenario_vectorized_fd (void)
{
  double ya[4], yf[4], yfb[4];
  sym_eval sa = ts_eval (2, ts_kep, ts_kep_jac, NULL);
  sym_eval sf = ts_eval (2, ts_kep, NULL, NULL);
  sym_eval sfb = ts_eval (2, ts_kep, NULL, NULL);
  sfb.rhs_batch = ts_kep_batch;
  int st = kepler_run (&sa, SYM_MATRIX_AUTO, 1000, ya)
           | kepler_run (&sf, SYM_MATRIX_AUTO, 1000, yf);
  int st4 = kepler_run (&sfb, SYM_MATRIX_AUTO, 1000, yfb);
  CHECK (st == 0 && st4 == 0 && ts_maxdiff (4, ya, yfb) <= 1e-10,
         "batched FD vs analytic Jacobian differ by %.3g",
         ts_maxdiff (4, ya, yfb));
  const sym_counters *c = &sfb.st.cnt;
  CHECK (c->nfd == 1000
         && c->nrhs_states - 1 == 15 * c->nfd + 3 * (c->nrhs - 1 - c->nfd)
         && c->nrhs <= 1650,
         "batched FD: %ld FD calls (%ld states), %ld calls in all",
         c->nfd, c->nrhs_states, c->nrhs);
  printf ("Vectorized, FD Jacobians: %.2f rhs calls per step (%.2f of them "
          "FD) vs %.2f (%.2f) with single calls\n", c->nrhs / 1000.0,
          c->nfd / 1000.0, sf.st.cnt.nrhs / 1000.0, sf.st.cnt.nfd / 1000.0);
}

/* With the matrix kept (asked for): the same steps as single calls, bit
   for bit, each matrix's 2d m perturbed states and the nodes' own f in
   one call (the other calls: the first step's Euler start, one state,
   then the nodes' evaluations, 3 states each) */
static void
scenario_vectorized_fd_kept (void)
{
  double yf[4], yfk[4];
  sym_eval sf = ts_eval (2, ts_kep, NULL, NULL);
  sym_eval sfk = ts_eval (2, ts_kep, NULL, NULL);
  sfk.rhs_batch = ts_kep_batch;
  int st2 = kepler_run (&sf, SYM_MATRIX_AUTO, 1000, yf);
  int st5 = kepler_run (&sfk, SYM_MATRIX_KEPT, 1000, yfk);
  CHECK (st2 == 0 && st5 == 0 && ts_maxdiff (4, yf, yfk) == 0.0,
         "batched FD, kept matrix, vs single calls differ by %.3g",
         ts_maxdiff (4, yf, yfk));
  const sym_counters *k = &sfk.st.cnt, *f = &sf.st.cnt;
  CHECK (k->nrhs_states == f->nrhs_states && k->nfd > 0
         && k->nfd * 12 == f->nfd
         && k->nrhs - k->nfd == 1 + (f->nrhs - f->nfd - 1) / 3 - k->nfd,
         "batched FD, kept: %ld FD calls (%ld states) vs %ld; rhs %ld vs %ld",
         k->nfd, k->nrhs_states, f->nfd, k->nrhs, f->nrhs);
}

/* f and Df in one call (the Hessian as FCN's second output): the same
   arithmetic as ts_kep and ts_kep_jac; a NaN in Df at call nan_at */
static long both_calls, both_nan_at;

static int
kep_both (double t, const double *y, double *dy, double *df, void *user)
{
  int st = ts_kep (t, y, dy, user);
  if (st)
    return st;
  st = ts_kep_jac (t, y, df, user);
  if (++both_calls == both_nan_at)
    df[3] = NAN;
  return st;
}

/* The combined call gives the same steps, bit for bit, and saves the rhs
   call of every node at which a matrix is evaluated: the residual there
   reuses its f. */
static void
scenario_rhs_jac (void)
{
  double ya[4], yc[4];
  sym_eval sa = ts_eval (2, ts_kep, ts_kep_jac, NULL);
  sym_eval sc = ts_eval (2, ts_kep, ts_kep_jac, NULL);
  sc.rhs_jac = kep_both;
  both_calls = both_nan_at = 0;
  int st1 = kepler_run (&sa, SYM_MATRIX_AUTO, 1000, ya);
  int st2 = kepler_run (&sc, SYM_MATRIX_AUTO, 1000, yc);
  CHECK (st1 == 0 && st2 == 0 && ts_maxdiff (4, ya, yc) == 0.0,
         "combined f and Df: statuses %d %d, differ by %.3g", st1, st2,
         ts_maxdiff (4, ya, yc));
  /* the probe of Df costs 1 call with f in the combined call, else 2 */
  const sym_counters *a = &sa.st.cnt, *c = &sc.st.cnt;
  CHECK (c->njac == a->njac && both_calls == c->njac && a->njac > 0
         && c->nfd == 1 && a->nfd == 2 && c->nrhs == a->nrhs - a->njac - 1,
         "combined: %ld rhs + %ld jac (%ld calls), separate %ld rhs + %ld "
         "jac", c->nrhs, c->njac, both_calls, a->nrhs, a->njac);
  printf ("f with Df in one call: %.3f rhs + %.3f jac calls per step "
          "(separate: %.3f + %.3f)\n", c->nrhs / 1000.0, c->njac / 1000.0,
          a->nrhs / 1000.0, a->njac / 1000.0);
}

/* With a new matrix at every step (asked for), the combined call gives m
   calls per step that also give f at the nodes; the steps agree with the
   kept matrix to round-off */
static void
scenario_rhs_jac_new_matrix (void)
{
  double ya[4], yn[4];
  sym_eval sa = ts_eval (2, ts_kep, ts_kep_jac, NULL);
  sym_eval snew = ts_eval (2, ts_kep, ts_kep_jac, NULL);
  snew.rhs_jac = kep_both;
  both_calls = both_nan_at = 0;
  int st = kepler_run (&sa, SYM_MATRIX_AUTO, 1000, ya);
  both_calls = 0;
  int st1 = kepler_run (&snew, SYM_MATRIX_NEW, 1000, yn);
  CHECK (st == 0 && st1 == 0 && ts_maxdiff (4, ya, yn) <= 1e-10,
         "new matrix every step: status %d, differs by %.3g", st1,
         ts_maxdiff (4, ya, yn));
  const sym_counters *c = &snew.st.cnt;
  CHECK (both_calls == c->njac && c->njac == 3000 && c->nrhs <= 1800
         && c->nfd == 1 && (c->nrhs - c->nfd) % 3 == 1,
         "new matrix every step: %ld rhs + %ld jac (%ld calls)", c->nrhs,
         c->njac, both_calls);
  printf ("  a new matrix every step: %.3f rhs + %.3f jac calls per step\n",
          c->nrhs / 1000.0, c->njac / 1000.0);
}

/* a NaN in the combined Df is reported as one, with its time */
static void
scenario_rhs_jac_nan (void)
{
  const double h = 2 * TS_PI / 100;
  sym_eval sn = ts_eval (2, ts_kep, ts_kep_jac, NULL);
  sn.rhs_jac = kep_both;
  sym_method_opts o;
  sym_spvi_opts so;
  ts_opts (&o, &so, 4, 3);
  int st;
  void *s3 = T->alloc (sn.dim, &o, &st);
  double yc[4], ya[4];
  ts_kep_y0 (0.6, yc);
  both_calls = 0;
  both_nan_at = 2;
  st = T->step (s3, &sn, 0.0, h, h, yc, ya, NULL);
  CHECK (st == SYM_NONFINITE && sn.st.fail_t > 0.0 && sn.st.fail_t < h,
         "NaN in the combined Df: %d (%s) at t = %g", st,
         sym_status_name (st), sn.st.fail_t);
  both_nan_at = 0;
  T->free (s3);
}

/* ---------------------------------------------------------------- failures */
/* One step of Kepler (4,3) after prior_steps steps, with the rhs failing
   (mode) at its call fail_at (-1: the step's last call) or the Jacobian
   at its call jac_fail_at; with the error estimate of an adaptive run if
   adaptive.  The status of the failed step; the stepper must go on. */
static int
one_step_with_failure (long fail_at, int mode, long jac_fail_at,
                       int jac_mode, int adaptive, int prior_steps)
{
  ts_user u = { 0 };
  sym_eval ev = ts_eval (2, ts_kep, ts_kep_jac, &u);
  sym_method_opts o;
  sym_spvi_opts so;
  ts_opts (&o, &so, 4, 3);
  int st;
  void *s = T->alloc (ev.dim, &o, &st);
  if (adaptive)
    st = ts_adaptive (T, s, 1e-6, 1e-6);
  double y[4], yn[4], ye[4], *yerr = adaptive ? ye : NULL;
  ts_kep_y0 (0.6, y);
  const double h = 0.05, t = prior_steps * h;
  st |= ts_run_fixed (T, s, &ev, 0.0, h, prior_steps, y);
  /* the last step's dense output (its first use evaluates f at the
     step's ends: before the calls are counted) */
  double ydense[4], ydense2[4];
  if (prior_steps)
    T->dense (s, &ev, t - 0.5 * h, ydense);
  u.calls = u.jcalls = 0;
  u.mode = mode;
  u.jac_fail_at = jac_fail_at;
  u.jac_mode = jac_mode;
  if (fail_at < 0)
    {
      /* the last call of this step (with yerr: the companion's last) */
      sym_eval cs = ev;
      ts_user cu = u;
      cs.user = &cu;
      double cy[4], cyn[4], cye[4];
      void *c = T->alloc (cs.dim, &o, &st);
      if (adaptive)
        st = ts_adaptive (T, c, 1e-6, 1e-6);
      ts_kep_y0 (0.6, cy);
      st |= ts_run_fixed (T, c, &cs, 0.0, h, prior_steps, cy);
      cu.calls = 0;
      st |= T->step (c, &cs, t, h, t + h, cy, cyn, adaptive ? cye : NULL);
      fail_at = cu.calls;
      T->free (c);
    }
  u.fail_at = fail_at;
  if (! st)
    st = T->step (s, &ev, t, h, t + h, y, yn, yerr);
  /* the step is not accepted: dense output still is the last step's */
  if (prior_steps)
    {
      T->dense (s, &ev, t - 0.5 * h, ydense2);
      CHECK (ts_maxdiff (4, ydense, ydense2) == 0.0, "dense changed");
    }
  /* and the stepper works on */
  u.fail_at = u.jac_fail_at = 0;
  int st2 = T->step (s, &ev, t, h, t + h, y, yn, yerr);
  CHECK (st2 == 0, "after the failure: %d", st2);
  T->free (s);
  return st;
}

/* each failure of a callback is reported with its own status */
static void
scenario_callback_failures (void)
{
  struct { long at; int mode; long jat; int jmode; int err, prior;
           int expect; } c[] = {
    /* rhs: the first call (Euler start), a Newton iteration, the polish,
       the companion; NaN, recoverable, fatal */
    { 1, 0, 0, 0, 0, 0, SYM_NONFINITE },
    { 1, 1, 0, 0, 0, 0, SYM_RECOVERABLE },
    { 1, 2, 0, 0, 0, 0, SYM_ECALLBACK },
    { 5, 0, 0, 0, 0, 0, SYM_NONFINITE },
    { 5, 1, 0, 0, 0, 0, SYM_RECOVERABLE },
    { 5, 2, 0, 0, 0, 0, SYM_ECALLBACK },
    { 2, 0, 0, 0, 0, 3, SYM_NONFINITE },
    { 2, 1, 0, 0, 0, 3, SYM_RECOVERABLE },
    { 2, 2, 0, 0, 0, 3, SYM_ECALLBACK },
    { -1, 0, 0, 0, 1, 3, SYM_NONFINITE },
    { -1, 1, 0, 0, 1, 3, SYM_RECOVERABLE },
    { -1, 2, 0, 0, 1, 3, SYM_ECALLBACK },
    { -1, 0, 0, 0, 0, 3, SYM_NONFINITE },
    /* jac: recoverable and fatal passed on */
    { 0, 0, 1, 1, 0, 0, SYM_RECOVERABLE },
    { 0, 0, 2, 2, 0, 0, SYM_ECALLBACK },
    { 0, 0, 1, 2, 1, 3, SYM_ECALLBACK },
  };
  for (size_t i = 0; i < sizeof c / sizeof c[0]; i++)
    {
      int st = one_step_with_failure (c[i].at, c[i].mode, c[i].jat,
                                      c[i].jmode, c[i].err, c[i].prior);
      CHECK (st == c[i].expect, "case %zu: status %d (%s), expected %d", i,
             st, sym_status_name (st), c[i].expect);
      CHECK ((st > 0) == (c[i].expect > 0), "case %zu: sign", i);
    }
}

/* H = p^2/2 - q^3/3: q'' = q^2 */
static int
blowup (double t, const double *y, double *dy, void *user)
{
  (void) t;
  (void) user;
  dy[0] = y[1];
  dy[1] = y[0] * y[0];
  return 0;
}

static int
blowup_jac (double t, const double *y, double *df, void *user)
{
  (void) t;
  (void) user;
  df[0] = 0.0;
  df[1] = 2.0 * y[0];
  df[2] = 1.0;
  df[3] = 0.0;
  return 0;
}

/* Newton failures, recoverable: an iteration limit of 1 in a step with
   the error estimate (a fixed step is then reached from shorter ones,
   spvi_lengthen, and succeeds), and a step past a blow-up (q'' = q^2
   from q = p = 1 blows up near t = 1.4): no solution */
static void
scenario_newton_failures (void)
{
  sym_eval ks = ts_eval (2, ts_kep, ts_kep_jac, NULL);
  sym_method_opts o;
  sym_spvi_opts so;
  ts_opts (&o, &so, 4, 3);
  o.max_newton = 1;
  int st;
  void *s = T->alloc (ks.dim, &o, &st);
  double y[4], yn[4], ye[4];
  ts_kep_y0 (0.6, y);
  st = T->step (s, &ks, 0.0, 0.1, 0.1, y, yn, ye);
  CHECK (st == SYM_NEWTON_FAIL && ks.st.cnt.nnewton_fail > 0,
         "max_newton 1: %d", st);
  st = T->step (s, &ks, 0.0, 0.1, 0.1, y, yn, NULL);
  CHECK (st == 0, "max_newton 1, fixed step: %d", st);
  T->free (s);
  sym_eval bs = ts_eval (1, blowup, blowup_jac, NULL);
  ts_opts (&o, &so, 4, 3);
  s = T->alloc (bs.dim, &o, &st);
  double yb[2] = { 1.0, 1.0 }, ybn[2];
  st = T->step (s, &bs, 0.0, 4.0, 4.0, yb, ybn, NULL);
  CHECK (st > 0, "step past the blow-up: %d (%s), y = %g %g", st,
         sym_status_name (st), ybn[0], ybn[1]);
  st = T->step (s, &bs, 0.0, 0.01, 0.01, yb, ybn, NULL);
  CHECK (st == 0, "then a small one: %d", st);
  T->free (s);
}

int
main (void)
{
  scenario_analytic_vs_fd ();
  scenario_gross_jacobian ();
  scenario_vectorized ();
  scenario_vectorized_fd ();
  scenario_vectorized_fd_kept ();
  scenario_rhs_jac ();
  scenario_rhs_jac_new_matrix ();
  scenario_rhs_jac_nan ();
  scenario_callback_failures ();
  scenario_newton_failures ();
  return tu_finish ("test_spvi_calls");
}
