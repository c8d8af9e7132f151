/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* test_core.c -- the shared parts of the core: allocator hook, counted
   callbacks with NaN/status checks, finite-difference Jacobians, LU, and
   the simplified Newton iteration (convergence, reuse, failure). */
#include "sym.h"
#include "numerics/numerics.h"
#include "tuning.h"
#include "testutil.h"

#include <float.h>
#include <string.h>

static long nalloc = 0;
static void *
count_alloc (size_t n)
{
  nalloc++;
  return malloc (n);
}
static void *
no_alloc (size_t n)
{
  (void) n;
  return NULL;
}
static void
count_free (void *p)
{
  nalloc--;
  free (p);
}

/* H = p^2/2 (1 + q^2) + q^2/2, d = 1 */
static int bad_mode = 0;
static int
nonsep (double t, const double *y, double *dy, void *u)
{
  (void) t; (void) u;
  double q = y[0], p = y[1];
  dy[0] = p * (1 + q * q);
  dy[1] = -(p * p * q + q);
  if (bad_mode == 1)
    dy[1] = NAN;
  return bad_mode == 2 ? 1 : (bad_mode == 3 ? -7 : 0);
}

static int
nonsep_jac (double t, const double *y, double *df, void *u)
{
  (void) t; (void) u;
  double q = y[0], p = y[1];
  df[0] = 2 * p * q;          /* d fq / dq */
  df[1] = -(p * p + 1);       /* d fp / dq */
  df[2] = 1 + q * q;          /* d fq / dp */
  df[3] = -2 * p * q;         /* d fp / dp */
  return 0;
}

/* nonsep with f NaN for q beyond edge_hi or below edge_lo (the edge of
   f's domain), singly and as a batch */
static double edge_lo = -INFINITY, edge_hi = INFINITY;
static int
nonsep_edge (double t, const double *y, double *dy, void *u)
{
  int st = nonsep (t, y, dy, u);
  if (y[0] > edge_hi || y[0] < edge_lo)
    dy[1] = NAN;
  return st;
}

static int
nonsep_edge_batch (int k, const double *t, const double *y, double *dy,
                   void *u)
{
  for (int j = 0; j < k; j++)
    nonsep_edge (t[j], y + 2 * j, dy + 2 * j, u);
  return 0;
}

/* nonsep's Df times *u (a user's Df too large, of the wrong sign, zero),
   and f with it in one call */
static int
nonsep_jac_c (double t, const double *y, double *df, void *u)
{
  nonsep_jac (t, y, df, u);
  for (int i = 0; i < 4; i++)
    df[i] *= *(const double *) u;
  return 0;
}

static int
nonsep_both_c (double t, const double *y, double *dy, double *df, void *u)
{
  int st = nonsep (t, y, dy, u);
  return st ? st : nonsep_jac_c (t, y, df, u);
}

/* an evaluator of nonsep_edge with Df times *c (or finite differences),
   the batch callback if asked for */
static sym_eval
edge_eval (double *c, int batch)
{
  sym_system se;
  memset (&se, 0, sizeof se);
  se.dim = 1;
  se.rhs = nonsep_edge;
  se.rhs_batch = batch ? nonsep_edge_batch : NULL;
  se.jac = c ? nonsep_jac_c : NULL;
  se.user = c;
  sym_eval ev;
  sym_eval_init (&ev, &se);
  return ev;
}

/* The same H at the scale a: H = p^2/2 (1 + (q/a)^2) + q^2/2, whose
   solutions are a times those of a = 1 (u points at a) */
static int
nonsep_a (double t, const double *y, double *dy, void *u)
{
  (void) t;
  double a = *(const double *) u, q = y[0] / a, p = y[1] / a;
  dy[0] = a * p * (1 + q * q);
  dy[1] = -a * (p * p * q + q);
  return 0;
}

/* f = (p, -q^3): the difference quotient of f_p in q at q = 0 is -del^2,
   so it shows the step del */
static int
quartic (double t, const double *y, double *dy, void *u)
{
  (void) t; (void) u;
  dy[0] = y[1];
  dy[1] = -y[0] * y[0] * y[0];
  return 0;
}

static int
near (double x, double ref)
{
  return fabs (x - ref) <= 1e-12 * fabs (ref);
}

/* the same for d = 2: f = (p1, p2, -q1^3, -q2^3) */
static int
quartic2 (double t, const double *y, double *dy, void *u)
{
  (void) t; (void) u;
  dy[0] = y[2];
  dy[1] = y[3];
  dy[2] = -y[0] * y[0] * y[0];
  dy[3] = -y[1] * y[1] * y[1];
  return 0;
}

/* Newton test problem: x^3 - a = 0 componentwise, plus a coupling */
typedef struct { double a[3]; int nres, nmat; } cube;
static int
cube_res (void *ctx, const double *x, double *r)
{
  cube *c = ctx;
  c->nres++;
  for (int i = 0; i < 3; i++)
    r[i] = x[i] * x[i] * x[i] + 0.1 * x[(i + 1) % 3] - c->a[i];
  return 0;
}
static int
cube_mat (void *ctx, const double *x, double *a)
{
  cube *c = ctx;
  c->nmat++;
  memset (a, 0, 9 * sizeof (double));
  for (int i = 0; i < 3; i++)
    {
      a[i + 3 * i] = 3 * x[i] * x[i];
      a[i + 3 * ((i + 1) % 3)] += 0.1;
    }
  return 0;
}
static int
cube_bad_res (void *ctx, const double *x, double *r)
{
  (void) ctx;
  for (int i = 0; i < 3; i++)
    r[i] = x[i] * x[i] + 1.0;   /* no real root: Newton cannot converge */
  return 0;
}

/* a linear chain of CH_D unit masses, fixed ends: f_q = p, f_p = -K q */
#define CH_D 256
static int
chain (double t, const double *y, double *dy, void *u)
{
  (void) t; (void) u;
  for (int i = 0; i < CH_D; i++)
    {
      double l = i > 0 ? y[i - 1] : 0.0, r = i < CH_D - 1 ? y[i + 1] : 0.0;
      dy[i] = y[CH_D + i];
      dy[CH_D + i] = l - 2.0 * y[i] + r;
    }
  return 0;
}

static long chain_calls;
static int
chain_batch (int k, const double *t, const double *y, double *dy, void *u)
{
  chain_calls++;
  for (int j = 0; j < k; j++)
    chain (t[j], y + (size_t) 2 * CH_D * j, dy + (size_t) 2 * CH_D * j, u);
  return 0;
}

/* nonsep for the columns of y, one call */
static long batch_calls, batch_states;
static int
nonsep_batch (int k, const double *t, const double *y, double *dy, void *u)
{
  batch_calls++;
  batch_states += k;
  for (int j = 0; j < k; j++)
    {
      int st = nonsep (t[j], y + 2 * j, dy + 2 * j, u);
      if (st)
        return st;
    }
  return 0;
}

/* an evaluator of f (and Df) for d = dim, as a stepper's caller makes it */
static sym_eval
make_eval (int dim, sym_rhs_fn rhs, sym_jac_fn jac, void *user)
{
  sym_system s;
  memset (&s, 0, sizeof s);
  s.dim = dim;
  s.rhs = rhs;
  s.jac = jac;
  s.user = user;
  sym_eval ev;
  sym_eval_init (&ev, &s);
  return ev;
}

static void
scenario_status_names (void)
{
  CHECK (strcmp (sym_status_name (SYM_ENEWTON), "SYM_ENEWTON") == 0, "name");
  CHECK (strcmp (sym_status_name (SYM_STOP_EVENT), "SYM_STOP_EVENT") == 0,
         "name");
}

/* counted callbacks, NaN and status mapping; a batch without a batch
   callback is k single calls */
static void
scenario_counted_calls (void)
{
  sym_eval ev = make_eval (1, nonsep, NULL, NULL);
  double y[2] = { 0.3, -0.7 }, dy[2];
  CHECK (sym_rhs (&ev, 0, y, dy) == 0 && ev.st.cnt.nrhs == 1, "rhs");
  bad_mode = 1;
  CHECK (sym_rhs (&ev, 2.5, y, dy) == SYM_NONFINITE && ev.st.fail_t == 2.5,
         "NaN detected");
  bad_mode = 2;
  CHECK (sym_rhs (&ev, 0, y, dy) == SYM_RECOVERABLE, "recoverable");
  bad_mode = 3;
  CHECK (sym_rhs (&ev, 0, y, dy) == SYM_ECALLBACK
         && ev.st.fail_status == -7, "fatal");
  bad_mode = 0;

  double yy[6] = { 0.1, 0.2, 0.3, 0.4, 0.5, 0.6 }, tt[3] = { 0, 1, 2 };
  double dd[6];
  long before = ev.st.cnt.nrhs;
  CHECK (sym_rhs_many (&ev, 3, tt, yy, dd) == 0
         && ev.st.cnt.nrhs == before + 3, "rhs_many");
  nonsep (0, yy + 2, dy, NULL);
  CHECK (dd[2] == dy[0] && dd[3] == dy[1], "rhs_many values");
}

/* finite-difference Jacobian vs analytic, at every scale of the problem */
static void
scenario_fd_jacobian (void)
{
  sym_eval ev = make_eval (1, nonsep, NULL, NULL);
  double y[2] = { 0.3, -0.7 }, df[4], dfa[4];
  nonsep_jac (0, y, dfa, NULL);
  CHECK (sym_jac (&ev, 0, y, NULL, df) == 0, "fd jac");
  CHECK (ev.st.cnt.nfd == 3 && ev.st.cnt.nrhs == 3, "fd calls %ld",
         ev.st.cnt.nfd);
  double e = 0;
  for (int i = 0; i < 4; i++)
    e = fmax (e, fabs (df[i] - dfa[i]));
  CHECK (e < 1e-7, "fd jacobian error %.3g", e);
  /* nonsep at the scale a has the Jacobian of a = 1 at y / a: the steps
     must scale with the problem */
  for (int ia = 0; ia < 3; ia++)
    for (int iq = 0; iq < 2; iq++)
      {
        double a = ia == 0 ? 1e-10 : (ia == 1 ? 1.0 : 1e10);
        double ys[2] = { iq ? 0.8 * a : 0.0, 0.6 * a }, u1[2] = { ys[0] / a,
                                                                 0.6 };
        double dfs[4], dfu[4];
        sym_eval sa = make_eval (1, nonsep_a, NULL, &a);
        nonsep_jac (0, u1, dfu, NULL);
        CHECK (sym_jac (&sa, 0, ys, NULL, dfs) == 0, "fd jac, a = %g", a);
        double es = 0;
        for (int i = 0; i < 4; i++)
          es = fmax (es, fabs (dfs[i] - dfu[i]));
        CHECK (es < 1e-7, "fd jacobian at the scale %g, q = %g: error %.3g",
               a, ys[0], es);
      }
}

/* The step of q is sqrt(eps) times the size of q: max(|q|, ytyp_q), p's
   size when q's is zero, 1 when both are */
static void
scenario_fd_steps (void)
{
  const double sq = sqrt (DBL_EPSILON);
  double yq[2] = { 0.0, 1e-3 }, dq[4], typ[2] = { 2.0, 0.0 };
  sym_eval sq4 = make_eval (1, quartic, NULL, NULL);
  CHECK (sym_jac (&sq4, 0, yq, NULL, dq) == 0
         && near (dq[1], -(sq * 1e-3) * (sq * 1e-3)), "step from p's size: "
         "%.17g", dq[1]);
  sq4.ytyp = typ;
  CHECK (sym_jac (&sq4, 0, yq, NULL, dq) == 0
         && near (dq[1], -(sq * 2.0) * (sq * 2.0)), "step from ytyp: %.17g",
         dq[1]);
  yq[1] = 0.0;
  typ[0] = 0.0;
  CHECK (sym_jac (&sq4, 0, yq, NULL, dq) == 0 && near (dq[1], -sq * sq),
         "step 1 at y = 0: %.17g", dq[1]);
  /* d = 2 (the quartic in each q): with ytyp, each component its own
     size, at least SYM_FD_FLOOR times the largest of its half; without,
     the largest of its half */
  double y2[4] = { 1e10, 0.0, 0.0, 0.0 }, d2[16], typ2[4] = { 0, 3.0, 0, 0 };
  sym_eval s2 = make_eval (2, quartic2, NULL, NULL);
  s2.ytyp = typ2;
  CHECK (sym_jac (&s2, 0, y2, NULL, d2) == 0
         && near (d2[1 * 4 + 3], -(sq * 1e4) * (sq * 1e4)),
         "q2 stepped by sqrt(eps) 1e-6 |q1|: %.17g", d2[7]);
  typ2[1] = 1e5;
  CHECK (sym_jac (&s2, 0, y2, NULL, d2) == 0
         && near (d2[1 * 4 + 3], -(sq * 1e5) * (sq * 1e5)),
         "q2 stepped by its own size: %.17g", d2[7]);
  s2.ytyp = NULL;
  CHECK (sym_jac (&s2, 0, y2, NULL, d2) == 0
         && near (d2[1 * 4 + 3], -(sq * 1e10) * (sq * 1e10)),
         "without ytyp, by the size of q: %.17g", d2[7]);
}

/* with a batch callback: the same Jacobians, bit for bit, from one call
   per state (f given) or one call for all perturbed states of k states
   (sym_jac_many); counted in nfd */
static void
scenario_fd_batched (void)
{
  double y[2] = { 0.3, -0.7 }, df[4], dfb[4];
  double ym[6] = { 0.3, -0.7, 1.1, 0.4, -2.0, 0.05 };
  double tm[3] = { 0.0, 0.5, 1.0 }, fm[6], dfm[12], dfs[12];
  for (int j = 0; j < 3; j++)
    nonsep (tm[j], ym + 2 * j, fm + 2 * j, NULL);
  sym_eval ss = make_eval (1, nonsep, NULL, NULL);
  CHECK (sym_jac (&ss, 0, y, NULL, df) == 0, "fd jac");
  sym_eval sb = make_eval (1, nonsep, NULL, NULL);
  sb.rhs_batch = nonsep_batch;
  batch_calls = batch_states = 0;
  CHECK (sym_jac (&sb, 0, y, NULL, dfb) == 0
         && memcmp (dfb, df, sizeof df) == 0, "batched fd jac");
  CHECK (sb.st.cnt.nrhs == 2 && sb.st.cnt.nfd == 2 && batch_calls == 1
         && batch_states == 2, "batched fd calls: %ld rhs, %ld fd, %ld "
         "batch", sb.st.cnt.nrhs, sb.st.cnt.nfd, batch_calls);
  memset (&sb.st.cnt, 0, sizeof sb.st.cnt);
  batch_calls = batch_states = 0;
  CHECK (sym_jac_many (&sb, 3, tm, ym, fm, dfm) == 0 && sb.st.cnt.nrhs == 1
         && sb.st.cnt.nfd == 1 && sb.st.cnt.nrhs_states == 6
         && batch_calls == 1 && batch_states == 6, "jac_many batched: "
         "%ld calls", sb.st.cnt.nrhs);
  memset (&ss.st.cnt, 0, sizeof ss.st.cnt);
  CHECK (sym_jac_many (&ss, 3, tm, ym, fm, dfs) == 0 && ss.st.cnt.nrhs == 6
         && ss.st.cnt.nfd == 6 && memcmp (dfs, dfm, sizeof dfm) == 0,
         "jac_many single calls: %ld, same values", ss.st.cnt.nrhs);
  /* f and Df together: with the batch callback one call for the 3
     states and their 6 perturbed states; the same numbers */
  double fr[6], dfr[12];
  memset (&sb.st.cnt, 0, sizeof sb.st.cnt);
  batch_calls = batch_states = 0;
  CHECK (sym_rhs_jac_many (&sb, 3, tm, ym, fr, dfr) == 0
         && batch_calls == 1 && batch_states == 9 && sb.st.cnt.nfd == 1
         && memcmp (fr, fm, sizeof fm) == 0
         && memcmp (dfr, dfs, sizeof dfs) == 0,
         "rhs_jac_many batched: %ld calls of %ld states", batch_calls,
         batch_states);
  memset (&ss.st.cnt, 0, sizeof ss.st.cnt);
  CHECK (sym_rhs_jac_many (&ss, 3, tm, ym, fr, dfr) == 0
         && ss.st.cnt.nrhs == 9 && ss.st.cnt.nfd == 6
         && memcmp (fr, fm, sizeof fm) == 0
         && memcmp (dfr, dfs, sizeof dfs) == 0,
         "rhs_jac_many single calls: %ld", ss.st.cnt.nrhs);
  /* a NaN in a perturbed state's f is reported with its time */
  bad_mode = 1;
  memset (&sb.st.cnt, 0, sizeof sb.st.cnt);
  CHECK (sym_jac_many (&sb, 3, tm, ym, fm, dfm) == SYM_NONFINITE
         && sb.st.fail_t == 0.0, "jac_many NaN: fail_t %g", sb.st.fail_t);
  bad_mode = 0;
}

/* a large batch goes in parts: 3 states of n = 512, 1536 perturbed
   states of 512 values, at most SYM_FD_BATCH_DOUBLES values a call: 2
   calls */
static void
scenario_fd_batch_in_parts (void)
{
  const size_t n = 2 * CH_D, k = 3;
  double *yc = malloc (k * n * sizeof (double));
  double *fc = malloc (k * n * sizeof (double));
  double *j1 = malloc (k * n * n * sizeof (double));
  double *j2 = malloc (k * n * n * sizeof (double));
  double tc[3] = { 0.0, 0.1, 0.2 };
  for (size_t i = 0; i < k * n; i++)
    yc[i] = sin (0.37 * (double) i);
  for (size_t j = 0; j < k; j++)
    chain (tc[j], yc + j * n, fc + j * n, NULL);
  sym_eval cb = make_eval (CH_D, chain, NULL, NULL);
  sym_eval cs = cb;
  cb.rhs_batch = chain_batch;
  chain_calls = 0;
  CHECK (sym_jac_many (&cb, (int) k, tc, yc, fc, j1) == 0
         && chain_calls == 2 && cb.st.cnt.nfd == 2
         && cb.st.cnt.nrhs_states == (long) (k * n),
         "chain: %ld batch calls, %ld states", chain_calls,
         cb.st.cnt.nrhs_states);
  CHECK (sym_jac_many (&cs, (int) k, tc, yc, fc, j2) == 0
         && cs.st.cnt.nrhs == (long) (k * n)
         && memcmp (j1, j2, k * n * n * sizeof (double)) == 0,
         "chain: batched in parts vs single calls");
  /* and the values: Df = [0 I; -K 0] to the differences' accuracy */
  double err = 0.0;
  for (size_t c = 0; c < n; c++)
    for (size_t r = 0; r < n; r++)
      {
        double ex = 0.0;
        if (r < CH_D && c == r + CH_D)
          ex = 1.0;
        else if (r >= CH_D && c < CH_D)
          ex = c == r - CH_D ? -2.0
               : (c + 1 == r - CH_D || c == r - CH_D + 1) ? 1.0 : 0.0;
        err = fmax (err, fabs (j1[n * n + c * n + r] - ex));
      }
  CHECK (err < 1e-6, "chain Jacobian error %.3g", err);
  /* too large for the stack's workspace: the run's, kept from one Df to
     the next (the same Df again, without memory, and to the bit); a new
     run without memory gets SYM_ENOMEM */
  sym_set_allocator (no_alloc, count_free);
  CHECK (sym_jac_many (&cb, (int) k, tc, yc, fc, j2) == 0
         && memcmp (j1, j2, k * n * n * sizeof (double)) == 0,
         "chain: the workspace kept for the next Df");
  sym_eval_free (&cb);
  CHECK (sym_jac_many (&cb, (int) k, tc, yc, fc, j2) == SYM_ENOMEM,
         "chain: finite differences without memory");
  sym_set_allocator (count_alloc, count_free);
  sym_eval_free (&cs);
  free (yc);
  free (fc);
  free (j1);
  free (j2);
}

static void
scenario_analytic_jac (void)
{
  sym_eval ev = make_eval (1, nonsep, nonsep_jac, NULL);
  double y[2] = { 0.3, -0.7 }, df[4], dfa[4];
  nonsep_jac (0, y, dfa, NULL);
  CHECK (sym_jac (&ev, 0, y, NULL, df) == 0 && ev.st.cnt.njac == 1
         && df[2] == dfa[2], "analytic jac");
}

/* LU: solve a 3x3 system; singular matrix reported */
static void
scenario_lu (void)
{
  sym_lu lu;
  CHECK (sym_lu_init (&lu, 3) == 0, "lu init");
  double A[9] = { 4, 1, 0, 1, 3, 1, 0, 1, 2 }, b[3] = { 1, 2, 3 };
  memcpy (lu.a, A, sizeof A);
  CHECK (sym_lu_factor (&lu, NULL) == 0, "factor");
  CHECK (sym_lu_solve (&lu, b, NULL) == 0, "solve");
  for (int i = 0; i < 3; i++)
    {
      double r = -(i + 1);
      for (int j = 0; j < 3; j++)
        r += A[i + 3 * j] * b[j];
      CHECK (fabs (r) < 1e-14, "residual %.3g", r);
    }
  memset (lu.a, 0, 9 * sizeof (double));
  CHECK (sym_lu_factor (&lu, NULL) == SYM_SINGULAR, "singular");
  /* not finite (h Df overflowing): no factors either */
  memcpy (lu.a, A, sizeof A);
  lu.a[4] = INFINITY;
  CHECK (sym_lu_factor (&lu, NULL) == SYM_SINGULAR && ! lu.factored,
         "not finite");
  CHECK (sym_lu_solve (&lu, b, NULL) == SYM_EBADINPUT, "no solve unfactored");
  sym_lu_free (&lu);
}

extern void dgetrf_ (const int *m, const int *n, double *a, const int *lda,
                     int *ipiv, int *info);

/* LU of every size from 1 to SYM_LU_SMALL + 8 (the core's own loops and
   LAPACK's): random matrices solve to a small backward error; up to
   SYM_LU_SMALL the pivots are LAPACK's dgetrf's and the factors agree
   with its to round-off; a zero pivot at any column is singular */
static void
scenario_lu_sizes (void)
{
  unsigned long seed = 12345;
  for (int n = 1; n <= SYM_LU_SMALL + 8; n++)
    {
      sym_lu lu;
      CHECK (sym_lu_init (&lu, n) == 0, "lu init %d", n);
      const size_t nn = (size_t) n * n;
      double *A = malloc (nn * sizeof (double));
      double *F = malloc (nn * sizeof (double));
      double *b = malloc ((size_t) n * sizeof (double));
      double *x = malloc ((size_t) n * sizeof (double));
      int *ip = malloc ((size_t) n * sizeof (int));
      for (size_t i = 0; i < nn; i++)
        {
          seed = seed * 6364136223846793005UL + 1442695040888963407UL;
          A[i] = (double) (seed >> 11) / 9007199254740992.0 - 0.5;
        }
      double anorm = 0.0, bnorm = 0.0;
      for (int i = 0; i < n; i++)
        {
          double r = 0.0;
          for (int j = 0; j < n; j++)
            r += fabs (A[i + (size_t) j * n]);
          anorm = fmax (anorm, r);
          b[i] = x[i] = cos (i + 1.0);
          bnorm = fmax (bnorm, fabs (b[i]));
        }
      memcpy (lu.a, A, nn * sizeof (double));
      CHECK (sym_lu_factor (&lu, NULL) == 0, "factor %d", n);
      CHECK (sym_lu_solve (&lu, x, NULL) == 0, "solve %d", n);
      double res = 0.0, xnorm = 0.0;
      for (int i = 0; i < n; i++)
        {
          double r = -b[i];
          for (int j = 0; j < n; j++)
            r += A[i + (size_t) j * n] * x[j];
          res = fmax (res, fabs (r));
          xnorm = fmax (xnorm, fabs (x[i]));
        }
      CHECK (res <= 4.0 * n * DBL_EPSILON * (anorm * xnorm + bnorm),
             "n %d: backward error %.3g", n,
             res / (anorm * xnorm + bnorm));
      if (n <= SYM_LU_SMALL)
        {
          int info = 0;
          memcpy (F, A, nn * sizeof (double));
          dgetrf_ (&n, &n, F, &n, ip, &info);
          int same = info == 0;
          double dif = 0.0;
          for (int i = 0; i < n; i++)
            same = same && ip[i] == lu.ipiv[i];
          for (size_t i = 0; i < nn; i++)
            dif = fmax (dif, fabs (F[i] - lu.a[i]));
          CHECK (same, "n %d: the pivots of dgetrf", n);
          CHECK (dif <= 1e3 * DBL_EPSILON * anorm, "n %d: factors differ "
                 "from dgetrf's by %.3g", n, dif);
        }
      /* column c zero: an exactly zero pivot at c */
      const int c = n / 2;
      if (n > 1)
        {
          memcpy (lu.a, A, nn * sizeof (double));
          for (int i = 0; i < n; i++)
            lu.a[i + (size_t) c * n] = 0.0;
          CHECK (sym_lu_factor (&lu, NULL) == SYM_SINGULAR && ! lu.factored,
                 "n %d: singular at column %d", n, c);
        }
      free (A);
      free (F);
      free (b);
      free (x);
      free (ip);
      sym_lu_free (&lu);
    }
  /* a pivot row found below: a permutation matrix, and equal sizes
     (the first of them pivots, as in LAPACK) */
  sym_lu lu;
  CHECK (sym_lu_init (&lu, 3) == 0, "lu init");
  const double P[9] = { 0, 0, 1, 1, 0, 0, 0, 1, 0 };
  double b[3] = { 1, 2, 3 };
  memcpy (lu.a, P, sizeof P);
  CHECK (sym_lu_factor (&lu, NULL) == 0 && sym_lu_solve (&lu, b, NULL) == 0
         && b[0] == 3 && b[1] == 1 && b[2] == 2, "permutation: %g %g %g",
         b[0], b[1], b[2]);
  /* a subnormal pivot: multipliers by division (its reciprocal is
     Inf); A = [4e-310 0 0; 2e-310 1 0; 1e-310 0 1], x = (1, 1, 1) */
  const double S[9] = { 4e-310, 2e-310, 1e-310, 0, 1, 0, 0, 0, 1 };
  double bs[3] = { 4e-310, 1, 1 };
  memcpy (lu.a, S, sizeof S);
  CHECK (sym_lu_factor (&lu, NULL) == 0 && sym_lu_solve (&lu, bs, NULL) == 0
         && fabs (bs[0] - 1) < 1e-14 && fabs (bs[1] - 1) < 1e-14
         && fabs (bs[2] - 1) < 1e-14, "subnormal pivot: %g %g %g", bs[0],
         bs[1], bs[2]);
  const double T[9] = { 1, -1, 1, 2, 1, 0, 0, 3, 1 };
  memcpy (lu.a, T, sizeof T);
  CHECK (sym_lu_factor (&lu, NULL) == 0 && lu.ipiv[0] == 1, "ties: pivot %d",
         lu.ipiv[0]);
  sym_lu_free (&lu);
}

/* Newton: converges to machine precision; the LU is reused by the next
   solve from a nearby start */
static void
scenario_newton (void)
{
  sym_newton nw;
  CHECK (sym_newton_init (&nw, 3, NULL) == 0, "newton init");
  cube c = { { 1, 8, 27 }, 0, 0 };
  sym_newton_problem p = { cube_res, cube_mat, &c, NULL, NULL, NULL };
  double x[3] = { 1.1, 2.1, 2.9 }, sc[3] = { 1, 1, 1 };
  sym_counters cnt;
  memset (&cnt, 0, sizeof cnt);
  CHECK (sym_newton_solve (&nw, &p, x, sc, &cnt) == 0, "newton converges");
  double r[3];
  cube_res (&c, x, r);
  CHECK (fabs (r[0]) + fabs (r[1]) + fabs (r[2]) < 1e-13,
         "residual %.3g", fabs (r[0]) + fabs (r[1]) + fabs (r[2]));
  CHECK (c.nmat <= 2 && cnt.nlu == c.nmat, "matrices %d", c.nmat);
  int nmat1 = c.nmat;
  long it1 = cnt.nnewton;
  c.a[0] = 1.001;
  CHECK (sym_newton_solve (&nw, &p, x, sc, &cnt) == 0, "second solve");
  CHECK (c.nmat == nmat1, "matrix reused (%d)", c.nmat);
  CHECK (cnt.nnewton - it1 <= 6, "iterations %ld (theta %.2g)",
         cnt.nnewton - it1, nw.theta);
  cube_res (&c, x, r);
  CHECK (fabs (r[0]) < 1e-13, "converged again");
  /* a far start with the stale matrix: refreshed, still converges */
  c.a[0] = 1.5;
  c.a[1] = 6;
  CHECK (sym_newton_solve (&nw, &p, x, sc, &cnt) == 0, "refresh converges");
  cube_res (&c, x, r);
  CHECK (fabs (r[0]) + fabs (r[1]) < 1e-12, "residual after refresh");
  CHECK (c.nmat > nmat1, "matrix refreshed");
  /* no solution: fails cleanly */
  sym_newton_problem bad = { cube_bad_res, cube_mat, &c, NULL, NULL, NULL };
  sym_newton_invalidate (&nw);
  double xb[3] = { 1, 1, 1 };
  int st = sym_newton_solve (&nw, &bad, xb, sc, &cnt);
  CHECK (st == SYM_NEWTON_FAIL, "failure reported: %s", sym_status_name (st));
  CHECK (cnt.nnewton_fail >= 1, "failure counted");
  sym_newton_free (&nw);
}

/* The probe of the user's first Df (SYM_JAC_GROSS): a Df too large by
   1e3 or 1e12 is dropped and finite differences give this Df already;
   the right one, one of the wrong sign, or zero stays.  It costs 2 calls
   of f with jac (f and f along a direction), 1 with rhs_jac (which gave
   f), and is made once. */
static void
scenario_jac_probe (void)
{
  double yp[2] = { 0.3, -0.7 }, dfp[4], dfx[4], fx[2];
  const double scales[] = { 1.0, -1.0, 0.0, 10.0, 1e3, 1e12 };
  nonsep_jac (0, yp, dfx, NULL);
  for (int k = 0; k < 6; k++)
    for (int both = 0; both < 2; both++)
      {
        double c = scales[k];
        sym_eval sj = make_eval (1, nonsep, nonsep_jac_c, &c);
        if (both)
          sj.rhs_jac = nonsep_both_c;
        int stp = both ? sym_rhs_jac (&sj, 0.25, yp, fx, dfp)
                       : sym_jac (&sj, 0.25, yp, NULL, dfp);
        int drop = c > 100.0;
        double e = 0.0;
        for (int i = 0; i < 4; i++)
          e = fmax (e, fabs (dfp[i] - (drop ? 1.0 : c) * dfx[i]));
        CHECK (stp == 0 && sj.jac_probed && sj.st.jac_dropped == drop
               && (drop ? sj.jac == NULL && sj.rhs_jac == NULL
                          && sj.st.jac_dropped_t == 0.25
                          && sj.st.cnt.nfd == 2 - both + 2 && e < 1e-7
                        : sj.jac == nonsep_jac_c && e == 0.0
                          && sj.st.cnt.nfd == 2 - both)
               && sj.st.cnt.nrhs == sj.st.cnt.nfd && sj.st.cnt.njac == 1,
               "probe of Df times %g (%s): dropped %d, %ld calls of f, "
               "Df off by %.3g", c, both ? "rhs_jac" : "jac",
               sj.st.jac_dropped, sj.st.cnt.nrhs, e);
        /* made once: the next Df costs no call of f */
        long calls = sj.st.cnt.nrhs;
        stp = both ? sym_rhs_jac (&sj, 0.5, yp, fx, dfp)
                   : sym_jac (&sj, 0.5, yp, NULL, dfp);
        CHECK (stp == 0 && (drop || sj.st.cnt.nrhs == calls),
               "second Df: %ld calls of f", sj.st.cnt.nrhs - calls);
      }
  /* a failed call of f in the probe is reported, and the probe made
     again with the next Df */
  double c = 1e12;
  sym_eval sj = make_eval (1, nonsep, nonsep_jac_c, &c);
  bad_mode = 1;
  int stp = sym_jac (&sj, 0.25, yp, NULL, dfp);
  CHECK (stp == SYM_NONFINITE && ! sj.jac_probed && sj.jac != NULL,
         "NaN in the probe: status %d", stp);
  bad_mode = 0;
  stp = sym_jac (&sj, 0.25, yp, NULL, dfp);
  CHECK (stp == 0 && sj.jac_probed && sj.st.jac_dropped, "probe again: %d",
         stp);
}

/* A state within a finite-difference step of the edge of f's domain:
   the steps go backwards (forward ones gave NaN and ended runs at t0),
   singly and in one batch call for three states; the probe of a user's
   Df steps the other way; with NaN on both sides there is no probe (Df
   kept) and no finite differences; NaN at the state itself stays a
   failure. */
static void
scenario_domain_edge (void)
{
  double ye[6] = { 0.3, -0.7, 0.3, -0.7, 0.3, -0.7 }, te[3] = { 0, 0, 0 };
  double dfe[12], dfx[4], fx[6];
  nonsep_jac (0, ye, dfx, NULL);
  edge_hi = 0.3 + 1e-9;
  for (int batch = 0; batch < 2; batch++)
    {
      sym_eval se = edge_eval (NULL, batch);
      int ste = sym_rhs_jac_many (&se, 3, te, ye, fx, dfe);
      double e = 0.0;
      for (int i = 0; i < 12; i++)
        e = fmax (e, fabs (dfe[i] - dfx[i % 4]));
      CHECK (ste == 0 && e < 1e-6, "FD at the edge (batch %d): status "
             "%d, Df off by %.3g", batch, ste, e);
    }
  for (int k = 0; k < 2; k++)
    {
      double c = k ? 1e12 : 1.0;
      sym_eval se = edge_eval (&c, 0);
      int ste = sym_jac (&se, 0, ye, NULL, dfe);
      double e = 0.0;
      for (int i = 0; i < 4; i++)
        e = fmax (e, fabs (dfe[i] - (k ? 1.0 : c) * dfx[i]));
      CHECK (ste == 0 && se.jac_probed && se.st.jac_dropped == k
             && e < 1e-6, "probe at the edge, Df times %g: status %d, "
             "dropped %d, off by %.3g", c, ste, se.st.jac_dropped, e);
    }
  edge_lo = 0.3 - 1e-9;
  double c = 1e12;
  sym_eval se = edge_eval (&c, 0);
  int ste = sym_jac (&se, 0, ye, NULL, dfe);
  CHECK (ste == 0 && se.jac_probed && ! se.st.jac_dropped
         && dfe[2] == c * dfx[2], "NaN both ways: no probe, status %d",
         ste);
  se.jac = NULL;
  CHECK (sym_jac (&se, 0, ye, NULL, dfe) == SYM_NONFINITE,
         "NaN both ways: no finite differences");
  edge_lo = edge_hi = 0.0;
  CHECK (sym_rhs_jac (&se, 0, ye, fx, dfe) == SYM_NONFINITE,
         "NaN at the state itself");
  edge_lo = -INFINITY;
  edge_hi = INFINITY;
}

int
main (void)
{
  sym_set_allocator (count_alloc, count_free);
  scenario_status_names ();
  scenario_counted_calls ();
  scenario_fd_jacobian ();
  scenario_fd_steps ();
  scenario_fd_batched ();
  scenario_fd_batch_in_parts ();
  scenario_analytic_jac ();
  scenario_lu ();
  scenario_lu_sizes ();
  scenario_newton ();
  scenario_jac_probe ();
  scenario_domain_edge ();
  CHECK (nalloc == 0, "every allocation freed through the hook (%ld left)",
         nalloc);
  return tu_finish ("test_core");
}
