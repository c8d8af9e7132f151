/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* test_stagelu.c -- the sparse matrix helpers (sparse.c) against dense
   arithmetic, and the LU of M = I - gamma J (stagelu.c), dense and
   sparse, real and complex: residuals computed here in complex
   arithmetic from the dense J, the two paths agreeing, the symbolic
   analysis kept or redone with J's pattern, singular and non-finite
   matrices, the counters, and every allocation (KLU's included) through
   sym_malloc, failing at each one in turn without a leak. */
#include "sym.h"
#include "numerics/numerics.h"
#include "testutil.h"

#include <complex.h>
#include <string.h>
#include <time.h>

#include <suitesparse/SuiteSparse_config.h>

/* --------------------------------------------------------------- allocator */
/* counts blocks and bytes; allocation al_fail_at fails, and every one
   from al_fail_from on (0: none) */
static long al_count, al_live, al_fail_at, al_fail_from;
static size_t al_bytes, al_peak;

static void *
t_alloc (size_t nbytes)
{
  long k = ++al_count;
  if (k == al_fail_at || (al_fail_from > 0 && k >= al_fail_from))
    return NULL;
  unsigned char *p = malloc (nbytes + 16);
  if (! p)
    return NULL;
  memcpy (p, &nbytes, sizeof nbytes);
  al_live++;
  al_bytes += nbytes;
  if (al_bytes > al_peak)
    al_peak = al_bytes;
  return p + 16;
}

static void
t_free (void *q)
{
  if (! q)
    return;
  unsigned char *p = (unsigned char *) q - 16;
  size_t nbytes;
  memcpy (&nbytes, p, sizeof nbytes);
  al_live--;
  al_bytes -= nbytes;
  free (p);
}

/* ---------------------------------------------------------------- matrices */
static unsigned long long rs = 88172645463325252ULL;

/* uniform in [-1, 1), never 0 */
static double
rnd (void)
{
  rs ^= rs << 13;
  rs ^= rs >> 7;
  rs ^= rs << 17;
  double r = (double) (rs >> 11) * 0x1.0p-53 * 2.0 - 1.0;
  return r != 0.0 ? r : 0.5;
}

/* a random sparse n-by-n J (leading dimension ld, zero elsewhere): a
   tridiagonal band, with holes on the diagonal when holes is set, and
   extra entries at random places */
static void
random_j (int n, int ld, int extra, int holes, double *d)
{
  memset (d, 0, (size_t) ld * n * sizeof (double));
  for (int j = 0; j < n; j++)
    {
      d[(size_t) j * ld + j] = holes && j % 3 == 1 ? 0.0 : rnd ();
      if (j > 0)
        d[(size_t) j * ld + j - 1] = rnd ();
      if (j < n - 1)
        d[(size_t) j * ld + j + 1] = rnd ();
    }
  for (int e = 0; e < extra; e++)
    {
      int i = (int) ((rnd () + 1) / 2 * n), j = (int) ((rnd () + 1) / 2 * n);
      d[(size_t) j * ld + i] = rnd ();
    }
}

/* the nonzeros of the dense d as a sym_csc (rows increasing) */
static int
to_csc (int n, int ld, const double *d, sym_csc *a)
{
  int nz = 0;
  for (size_t k = 0; k < (size_t) n * n; k++)
    nz += d[(k / n) * ld + k % n] != 0.0;
  int st = sym_csc_init (a, n, nz);
  if (st != SYM_SUCCESS)
    return st;
  nz = 0;
  for (int j = 0; j < n; j++)
    {
      a->colptr[j] = nz;
      for (int i = 0; i < n; i++)
        if (d[(size_t) j * ld + i] != 0.0)
          {
            a->rowind[nz] = i;
            a->val[nz++] = d[(size_t) j * ld + i];
          }
    }
  a->colptr[n] = a->nnz = nz;
  return SYM_SUCCESS;
}

/* a sym_csc as a dense n-by-n matrix (duplicates added up) */
static void
to_dense (const sym_csc *a, double *d)
{
  memset (d, 0, (size_t) a->n * a->n * sizeof (double));
  for (int j = 0; j < a->n; j++)
    for (int k = a->colptr[j]; k < a->colptr[j + 1]; k++)
      d[(size_t) j * a->n + a->rowind[k]] += a->val[k];
}

/* colptr from 0 to nnz, rows increasing and inside 0..n-1 */
static int
csc_valid (const sym_csc *a)
{
  if (a->colptr[0] != 0 || a->colptr[a->n] != a->nnz || a->nnz > a->cap)
    return 0;
  for (int j = 0; j < a->n; j++)
    for (int k = a->colptr[j]; k < a->colptr[j + 1]; k++)
      if (a->rowind[k] < 0 || a->rowind[k] >= a->n
          || (k > a->colptr[j] && a->rowind[k] <= a->rowind[k - 1]))
        return 0;
  return 1;
}

/* ------------------------------------------------------------- csc helpers */
static void
test_csc_block (const double *d, const sym_csc *a, int n)
{
  const int cases[][3] = { { 0, 0, 12 }, { 0, 0, 5 }, { 3, 7, 5 },
                           { 7, 2, 5 }, { 11, 11, 1 }, { 4, 4, 0 },
                           { 2, 9, 3 } };
  sym_csc b;
  memset (&b, 0, sizeof b);     /* dst may start zeroed */
  double bd[144];
  for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++)
    {
      int r0 = cases[c][0], c0 = cases[c][1], nb = cases[c][2], ok = 1;
      int st = sym_csc_block (a, r0, c0, nb, &b);
      CHECK (st == SYM_SUCCESS && b.n == nb && csc_valid (&b),
             "block (%d, %d, %d): %s", r0, c0, nb, sym_status_name (st));
      to_dense (&b, bd);
      for (int j = 0; j < nb; j++)
        for (int i = 0; i < nb; i++)
          ok &= bd[j * nb + i] == d[(c0 + j) * n + r0 + i];
      CHECK (ok, "block (%d, %d, %d) equals the dense block", r0, c0, nb);
    }
  CHECK (sym_csc_block (a, 8, 0, 5, &b) == SYM_EBADINPUT, "rows past n");
  CHECK (sym_csc_block (a, 0, -1, 3, &b) == SYM_EBADINPUT, "c0 < 0");
  CHECK (sym_csc_block (a, 0, 0, 13, &b) == SYM_EBADINPUT, "nb > n");
  sym_csc_free (&b);
  sym_csc_free (&b);          /* safe twice: the struct is zeroed */
}

static void
test_csc_copy_pattern (const double *d, sym_csc *a, int n)
{
  sym_csc c, e;
  double cd[144];
  CHECK (sym_csc_init (&c, 3, 0) == SYM_SUCCESS && c.cap == 0
         && c.colptr[3] == 0, "init with cap 0");
  CHECK (! sym_csc_same_pattern (a, &c), "a 3-by-3 is not a's pattern");
  CHECK (sym_csc_copy (&c, a) == SYM_SUCCESS && c.n == n && csc_valid (&c),
         "copy into a smaller matrix");
  to_dense (&c, cd);
  CHECK (! memcmp (cd, d, sizeof cd), "the copy's values");
  CHECK (sym_csc_same_pattern (a, &c) && sym_csc_same_pattern (&c, a),
         "a copy has the same pattern");
  c.val[c.nnz / 2] += 1.0;
  CHECK (sym_csc_same_pattern (a, &c), "values do not change the pattern");
  /* a row moved within its column (kept increasing) */
  int j = 0;
  while (c.colptr[j + 1] == c.colptr[j]
         || c.rowind[c.colptr[j + 1] - 1] == n - 1)
    j++;
  c.rowind[c.colptr[j + 1] - 1]++;
  CHECK (! sym_csc_same_pattern (a, &c), "a row moved");
  memset (&e, 0, sizeof e);
  CHECK (sym_csc_copy (&e, a) == SYM_SUCCESS && sym_csc_same_pattern (a, &e),
         "copy into a zeroed struct");
  /* room kept: a reserve keeps the entries */
  CHECK (sym_csc_reserve (&e, e.cap + 100) == SYM_SUCCESS
         && sym_csc_same_pattern (a, &e), "reserve keeps the content");
  to_dense (&e, cd);
  CHECK (! memcmp (cd, d, sizeof cd), "values after reserve");
  CHECK (sym_csc_copy (&e, &c) == SYM_SUCCESS && sym_csc_same_pattern (&c, &e),
         "copy into a larger one");
  sym_csc_free (&c);
  sym_csc_free (&e);
}

static void
test_csc_mv (const double *d, const sym_csc *a, int n)
{
  double x[12], y[12], z[12];
  for (int i = 0; i < n; i++)
    x[i] = rnd ();
  sym_csc_mv (a, x, y);
  double err = 0;
  for (int i = 0; i < n; i++)
    {
      z[i] = 0;
      for (int j = 0; j < n; j++)
        z[i] += d[j * n + i] * x[j];
      err = fmax (err, fabs (y[i] - z[i]));
    }
  CHECK (err <= 1e-15 * n, "A x: error %.3g against the dense product", err);
}

static void
test_csc (void)
{
  const int n = 12;
  double d[144];
  sym_csc a;
  for (int k = 0; k < n * n; k++)
    d[k] = rnd () > 0.4 ? rnd () : 0.0;
  d[11 * n + 11] = 0.0;      /* an empty corner, an empty column */
  for (int i = 0; i < n; i++)
    d[5 * n + i] = 0.0;
  CHECK (to_csc (n, n, d, &a) == SYM_SUCCESS && csc_valid (&a), "test A");
  test_csc_block (d, &a, n);
  test_csc_copy_pattern (d, &a, n);
  test_csc_mv (d, &a, n);
  sym_csc_free (&a);
  CHECK (sym_csc_init (&a, -1, 0) == SYM_EBADINPUT && ! a.colptr,
         "init n < 0");
}

/* ---------------------------------------------------------------- stage LU */
static double complex
cval (const double *v, int cplx, int i)
{
  return cplx ? v[2 * i] + v[2 * i + 1] * I : v[i];
}

/* |M x - b| / (|M| |x|) (max norms), M = I - gamma J from the dense J */
static double
residual (int n, int ld, const double *d, double complex g, int cplx,
          const double *x, const double *b)
{
  double rmax = 0, mnorm = 0, xmax = 0;
  for (int i = 0; i < n; i++)
    {
      double complex r = -cval (b, cplx, i);
      double row = 0;
      for (int j = 0; j < n; j++)
        {
          double complex m = (i == j) - g * d[(size_t) j * ld + i];
          r += m * cval (x, cplx, j);
          row += cabs (m);
        }
      rmax = fmax (rmax, cabs (r));
      mnorm = fmax (mnorm, row);
      xmax = fmax (xmax, cabs (cval (x, cplx, i)));
    }
  return rmax / (mnorm * xmax);
}

static void
rhs (int len, double *b)
{
  for (int k = 0; k < len; k++)
    b[k] = sin (k + 1.0) + 0.25;
}

/* Factor I - gamma J with s (dense: d, leading dimension ld; sparse:
   js) and solve for a fixed b into x (2n); *res: the residual */
static int
factor_solve (sym_stage_lu *s, int n, int ld, const double *d,
              const sym_csc *js, double gr, double gi, double *x,
              sym_counters *c, double *res)
{
  int cplx = gi != 0, len = cplx ? 2 * n : n;
  double b[80];
  rhs (len, b);
  memcpy (x, b, len * sizeof (double));
  int st = sym_stage_lu_factor (s, gr, gi, s->sparse ? NULL : d, ld,
                                s->sparse ? js : NULL, c);
  if (st == SYM_SUCCESS)
    st = sym_stage_lu_solve (s, x, c);
  *res = st == SYM_SUCCESS ? residual (n, ld, d, gr + gi * I, cplx, x, b)
                           : INFINITY;
  return st;
}

/* factor_solve, checked */
static void
stage_solve (const char *what, sym_stage_lu *s, int n, int ld,
             const double *d, const sym_csc *js, double gr, double gi,
             double *x, sym_counters *c)
{
  double res;
  int st = factor_solve (s, n, ld, d, js, gr, gi, x, c, &res);
  CHECK (st == SYM_SUCCESS && s->factored, "%s: %s", what,
         sym_status_name (st));
  CHECK (res < 1e-13, "%s: residual %.3g", what, res);
}

static double
rel_diff (int len, const double *x, const double *y)
{
  double dmax = 0, xmax = 0;
  for (int k = 0; k < len; k++)
    {
      dmax = fmax (dmax, fabs (x[k] - y[k]));
      xmax = fmax (xmax, fabs (x[k]));
    }
  return dmax / xmax;
}

/* n = 1, 5, 40, real and complex gamma, dense (J with ld > n) and
   sparse: residuals, and the two solutions the same */
static void
test_solves (void)
{
  const int ns[] = { 1, 5, 40 };
  const double gs[][2] = { { 0.7, 0.0 }, { -1.3, 0.0 }, { 0.3, 0.45 },
                           { 0.25, -0.6 } };
  static double d[42 * 40];
  double xd[80], xs[80];
  char what[80];
  for (int in = 0; in < 3; in++)
    for (int holes = 0; holes < 2; holes++)
      {
        int n = ns[in], ld = n + 2;
        sym_stage_lu sd, ss;
        sym_csc js;
        random_j (n, ld, n / 4, holes, d);
        if (n == 1 && holes)
          d[0] = 0.0;           /* J without entries */
        CHECK (to_csc (n, ld, d, &js) == SYM_SUCCESS, "J");
        CHECK (sym_stage_lu_init (&sd, n, 0) == SYM_SUCCESS, "init dense");
        CHECK (sym_stage_lu_init (&ss, n, 1) == SYM_SUCCESS, "init sparse");
        for (int ig = 0; ig < 4; ig++)
          {
            double gr = gs[ig][0], gi = gs[ig][1];
            snprintf (what, sizeof what, "n %d%s gamma %g%+gi dense", n,
                      holes ? " (diagonal holes)" : "", gr, gi);
            stage_solve (what, &sd, n, ld, d, NULL, gr, gi, xd, NULL);
            snprintf (what, sizeof what, "n %d%s gamma %g%+gi sparse", n,
                      holes ? " (diagonal holes)" : "", gr, gi);
            stage_solve (what, &ss, n, ld, d, &js, gr, gi, xs, NULL);
            double rd = rel_diff (gi != 0 ? 2 * n : n, xd, xs);
            CHECK (rd < 1e-12, "%s: dense and sparse differ by %.3g", what,
                   rd);
          }
        sym_stage_lu_free (&sd);
        sym_stage_lu_free (&ss);
        sym_stage_lu_free (&ss);   /* safe twice */
        sym_csc_free (&js);
      }
}

/* allocations by one factor of s */
static long
factor_allocs (const char *what, sym_stage_lu *s, int n, const double *d,
               const sym_csc *js, double gr, double gi, double *x)
{
  long before = al_count;
  stage_solve (what, s, n, n, d, js, gr, gi, x, NULL);
  return al_count - before;
}

/* The symbolic analysis kept while J's pattern stays (fewer
   allocations, KLU's numeric ones only), redone when it changes; real
   and complex factors share it */
static void
test_patterns (void)
{
  const int n = 40;
  static double da[1600], db[1600];
  double x[80];
  sym_csc ja, jb;
  sym_stage_lu s;
  random_j (n, n, 12, 0, da);
  memcpy (db, da, sizeof db);
  for (int k = 0; k < n * n; k++)      /* B: the band of A only */
    if (abs (k / n - k % n) > 1)
      db[k] = 0.0;
  CHECK (to_csc (n, n, da, &ja) == SYM_SUCCESS
         && to_csc (n, n, db, &jb) == SYM_SUCCESS && jb.nnz < ja.nnz,
         "A and B");
  CHECK (sym_stage_lu_init (&s, n, 1) == SYM_SUCCESS, "init");
  factor_allocs ("A", &s, n, da, &ja, 0.5, 0.0, x);
  long b1 = factor_allocs ("B (new analysis)", &s, n, db, &jb, 0.5, 0.0, x);
  for (int k = 0; k < jb.nnz; k++)
    jb.val[k] *= -1.5;
  for (int k = 0; k < n * n; k++)
    db[k] *= -1.5;
  long b2 = factor_allocs ("B, new values", &s, n, db, &jb, 0.5, 0.0, x);
  long b3 = factor_allocs ("B, complex", &s, n, db, &jb, 0.5, 0.3, x);
  /* C: B's colptr, a row moved (column 0: rows 0, 2 for 0, 1) */
  static double dc[1600];
  sym_csc jc;
  memcpy (dc, db, sizeof dc);
  dc[2] = dc[1];
  dc[1] = 0.0;
  CHECK (to_csc (n, n, dc, &jc) == SYM_SUCCESS
         && ! memcmp (jc.colptr, jb.colptr, (n + 1) * sizeof (int)), "C");
  long c1 = factor_allocs ("C (a row moved)", &s, n, dc, &jc, 0.5, 0.3, x);
  /* counted where stagelu.c routes KLU's memory through sym_malloc */
#if defined (__GNUC__) && defined (__ELF__) \
    && defined (SUITESPARSE_MAIN_VERSION) && SUITESPARSE_MAIN_VERSION < 7
  /* new values of the same pattern and kind: factored again in place;
     a complex factor made anew (through sym_malloc), the analysis kept */
  CHECK (b2 == 0 && b3 > 0, "KLU's numeric factors: %ld and %ld "
         "allocations", b2, b3);
  CHECK (b3 < b1, "the analysis kept: %ld allocations, %ld with an "
         "analysis", b3, b1);
  CHECK (c1 > b3, "C analysed anew: %ld allocations", c1);
#else
  (void) b1, (void) b2, (void) b3, (void) c1;
#endif
  factor_allocs ("B after C", &s, n, db, &jb, 0.5, 0.3, x);
  sym_csc_free (&jc);
  factor_allocs ("A again", &s, n, da, &ja, -0.2, 0.9, x);
  factor_allocs ("A, real", &s, n, da, &ja, 1.1, 0.0, x);
  sym_stage_lu_free (&s);
  sym_csc_free (&ja);
  sym_csc_free (&jb);
}

/* singular and non-finite M on s (sparse or not) with n = 5, and
   solves without factors: 6 factors (1 good), 1 good solve */
static void
singular_cases (sym_stage_lu *s, sym_counters *c)
{
  const int n = 5, sp = s->sparse;
  double d[25], x[10];
  sym_csc js;
  rhs (2 * n, x);
  CHECK (sym_stage_lu_solve (s, x, c) == SYM_EBADINPUT,
         "%d: solve before a factor", sp);
  /* J = I / gamma: M = 0 exactly (gamma a power of 2) */
  memset (d, 0, sizeof d);
  for (int i = 0; i < n; i++)
    d[i * n + i] = 0.25;
  CHECK (to_csc (n, n, d, &js) == SYM_SUCCESS, "J");
  CHECK (sym_stage_lu_factor (s, 4.0, 0.0, d, n, &js, c) == SYM_SINGULAR
         && ! s->factored, "%d: M = 0", sp);
  CHECK (sym_stage_lu_solve (s, x, c) == SYM_EBADINPUT,
         "%d: solve after a singular factor", sp);
  /* a zero row: J(2, :) = e_2' / gamma, the rest random */
  random_j (n, n, 6, 0, d);
  for (int j = 0; j < n; j++)
    d[j * n + 2] = j == 2 ? 0.5 : 0.0;
  sym_csc_free (&js);
  CHECK (to_csc (n, n, d, &js) == SYM_SUCCESS, "J");
  CHECK (sym_stage_lu_factor (s, 2.0, 0.0, d, n, &js, c) == SYM_SINGULAR
         && ! s->factored, "%d: M(2, :) = 0", sp);
  stage_solve ("then complex", s, n, n, d, &js, 2.0, 0.5, x, c);
  /* NaN, Inf, and gamma J overflowing; real and complex */
  double bad[] = { NAN, INFINITY, 1e300 };
  for (int k = 0; k < 3; k++)
    {
      js.val[2] = bad[k];
      to_dense (&js, d);
      CHECK (sym_stage_lu_factor (s, 1e10, 0.5 * (k == 1), d, n, &js, c)
             == SYM_SINGULAR && ! s->factored, "%d: %g in J", sp, bad[k]);
      CHECK (sym_stage_lu_solve (s, x, c) == SYM_EBADINPUT,
             "%d: solve after a non-finite J", sp);
    }
  sym_csc_free (&js);
}

/* arguments that are not valid: SYM_EBADINPUT */
static void
bad_arguments (sym_stage_lu *s)
{
  const int n = 5;
  double d[25];
  sym_csc js;
  CHECK (sym_stage_lu_factor (&s[1], 1, 0, NULL, 0, NULL, NULL)
         == SYM_EBADINPUT, "sparse without Js");
  CHECK (sym_stage_lu_factor (&s[0], 1, 0, NULL, n, NULL, NULL)
         == SYM_EBADINPUT, "dense without J");
  random_j (n, n, 0, 0, d);
  CHECK (sym_stage_lu_factor (&s[0], 1, 0, d, n - 1, NULL, NULL)
         == SYM_EBADINPUT, "dense with ld < n");
  CHECK (to_csc (n, n, d, &js) == SYM_SUCCESS, "J");
  int t = js.rowind[0];
  js.rowind[0] = js.rowind[1];
  js.rowind[1] = t;
  CHECK (sym_stage_lu_factor (&s[1], 1, 0, NULL, 0, &js, NULL)
         == SYM_EBADINPUT, "rows not increasing");
  js.rowind[1] = n;
  CHECK (sym_stage_lu_factor (&s[1], 1, 0, NULL, 0, &js, NULL)
         == SYM_EBADINPUT, "a row outside");
  sym_csc_free (&js);
}

/* the cases above on a dense and a sparse stage LU, and the counters */
static void
test_failures (void)
{
  sym_stage_lu s[2];
  sym_counters c;
  memset (&c, 0, sizeof c);
  CHECK (sym_stage_lu_init (&s[0], 0, 0) == SYM_EBADINPUT && ! s[0].a,
         "init n = 0");
  for (int sp = 0; sp < 2; sp++)
    {
      CHECK (sym_stage_lu_init (&s[sp], 5, sp) == SYM_SUCCESS, "init");
      singular_cases (&s[sp], &c);
    }
  CHECK (c.nlu == 12 && c.nsolve == 2, "counters: nlu %ld, nsolve %ld",
         c.nlu, c.nsolve);
  bad_arguments (s);
  for (int sp = 0; sp < 2; sp++)
    sym_stage_lu_free (&s[sp]);
}

/* -------------------------------------------------------------- allocation */
/* A life of a stage LU: init, factor with J A, solve, factor with J B
   (sparse: a new analysis, more room), solve, free.  The first status
   that is not a success, or SYM_SUCCESS with the solutions checked */
static int
life (int n, int sparse, double gi, const double *da, const sym_csc *ja,
      const double *db, const sym_csc *jb, double *x)
{
  sym_stage_lu s;
  int st = sym_stage_lu_init (&s, n, sparse);
  if (st != SYM_SUCCESS)
    return st;
  for (int k = 0; k < 2 && st == SYM_SUCCESS; k++)
    {
      double res;
      st = factor_solve (&s, n, n, k ? db : da, k ? jb : ja, 0.6, gi, x,
                         NULL, &res);
      if (st == SYM_SUCCESS)
        CHECK (res < 1e-13, "life %d: residual %.3g", k, res);
    }
  sym_stage_lu_free (&s);
  return st;
}

/* life with the k-th allocation failing (all from it on: every_from),
   k = 1, 2, ... until one needs fewer: SYM_ENOMEM and no block left */
static void
failing_lives (int sparse, double gi, int every_from)
{
  const int n = 20;
  static double da[400], db[400];
  double x[40];
  sym_csc ja, jb;
  random_j (n, n, 0, 1, da);
  random_j (n, n, 30, 0, db);
  CHECK (to_csc (n, n, da, &ja) == SYM_SUCCESS
         && to_csc (n, n, db, &jb) == SYM_SUCCESS, "J");
  long k, live = al_live, bad = 0;
  int st = SYM_ENOMEM;
  for (k = 1; k < 100000; k++)
    {
      al_count = 0;
      if (every_from)
        al_fail_from = k;
      else
        al_fail_at = k;
      st = life (n, sparse, gi, da, &ja, db, &jb, x);
      al_fail_from = al_fail_at = 0;
      if (al_live != live)
        {
          bad++;
          CHECK (0, "%ld blocks left with allocation %ld failing",
                 al_live - live, k);
        }
      if (al_count < k)
        break;
      if (st != SYM_ENOMEM)
        {
          bad++;
          CHECK (0, "%s with allocation %ld failing", sym_status_name (st),
                 k);
        }
    }
  CHECK (st == SYM_SUCCESS && ! bad && k > 2,
         "sparse %d gi %g every_from %d: %ld allocations, last %s", sparse,
         gi, every_from, k - 1, sym_status_name (st));
  printf ("  %s %s, allocation k %s: %ld allocations in a life\n",
          sparse ? "sparse" : "dense", gi != 0 ? "complex" : "real",
          every_from ? "and all after failing" : "failing", k - 1);
  sym_csc_free (&ja);
  sym_csc_free (&jb);
}

static void
test_allocation (void)
{
  for (int sparse = 0; sparse < 2; sparse++)
    for (int every = 0; every < 2; every++)
      {
        failing_lives (sparse, 0.0, every);
        failing_lives (sparse, 0.4, every);
      }
}

/* ---------------------------------------------------------------- large */
/* |M x - b| / (|M| |x|) (max norms), M = I - g J from the entries of a
   sparse J that has its diagonal; x and b complex */
static double
csc_residual (const sym_csc *js, double complex g, const double *x,
              const double *b)
{
  int n = js->n;
  double rmax = 0, mnorm = 0, xmax = 0;
  double complex *r = calloc (n, sizeof (double complex));
  double *row = calloc (n, sizeof (double));
  for (int j = 0; j < n; j++)
    {
      xmax = fmax (xmax, cabs (cval (x, 1, j)));
      for (int k = js->colptr[j]; k < js->colptr[j + 1]; k++)
        {
          int i = js->rowind[k];
          double complex m = (i == j) - g * js->val[k];
          r[i] += m * cval (x, 1, j);
          row[i] += cabs (m);
        }
    }
  for (int i = 0; i < n; i++)
    {
      rmax = fmax (rmax, cabs (r[i] - cval (b, 1, i)));
      mnorm = fmax (mnorm, row[i]);
    }
  free (r);
  free (row);
  return rmax / (mnorm * xmax);
}

/* n = 200000, J tridiagonal, gamma complex, sparse: a residual from the
   band, and memory far below n^2 */
static void
test_large (void)
{
  const int n = 200000;
  const double complex g = 0.4 + 0.7 * I;
  sym_csc js;
  sym_stage_lu s;
  double *x = malloc (2 * (size_t) n * sizeof (double));
  double *b = malloc (2 * (size_t) n * sizeof (double));
  CHECK (sym_csc_init (&js, n, 3 * n - 2) == SYM_SUCCESS, "J");
  int nz = 0;
  for (int j = 0; j < n; j++)
    {
      js.colptr[j] = nz;
      for (int i = j - 1; i <= j + 1; i++)
        if (i >= 0 && i < n)
          {
            js.rowind[nz] = i;
            js.val[nz++] = rnd () * (i == j ? 3 : 1);
          }
    }
  js.colptr[n] = js.nnz = nz;
  rhs (2 * n, b);
  memcpy (x, b, 2 * (size_t) n * sizeof (double));
  size_t peak0 = al_bytes;
  al_peak = al_bytes;
  clock_t t0 = clock ();
  CHECK (sym_stage_lu_init (&s, n, 1) == SYM_SUCCESS, "init");
  int st = sym_stage_lu_factor (&s, creal (g), cimag (g), NULL, 0, &js, NULL);
  clock_t t1 = clock ();
  CHECK (st == SYM_SUCCESS, "factor: %s", sym_status_name (st));
  CHECK (sym_stage_lu_solve (&s, x, NULL) == SYM_SUCCESS, "solve");
  clock_t t2 = clock ();
  double res = csc_residual (&js, g, x, b);
  CHECK (res < 1e-13, "n = %d: residual %.3g", n, res);
  CHECK (al_peak - peak0 < (size_t) 1000 * n,
         "n = %d: %zu bytes at most", n, al_peak - peak0);
  printf ("  n = %d tridiagonal complex: factor %.3f s, solve %.3f s, "
          "%.1f MB at most, residual %.2g\n", n,
          (double) (t1 - t0) / CLOCKS_PER_SEC,
          (double) (t2 - t1) / CLOCKS_PER_SEC,
          (double) (al_peak - peak0) / 1e6, res);
  sym_stage_lu_free (&s);
  sym_csc_free (&js);
  free (x);
  free (b);
}

/* Factors again in the kept pivot order only while it serves: M = I - J
   with J = [0 .1; .1 0] pivots on its diagonal; then J = [1 1; 1 0] (the
   same pattern) has a zero there, and a full factorization must be made
   again: the solve is right */
static void
test_refactor_fallback (void)
{
  double j1[4] = { 0.0, 0.1, 0.1, 0.0 }, j2[4] = { 1.0, 1.0, 1.0, 0.0 };
  sym_csc a, b;
  sym_stage_lu s;
  CHECK (to_csc (2, 2, j1, &a) == SYM_SUCCESS
         && to_csc (2, 2, j2, &b) == SYM_SUCCESS && a.nnz == 2
         && b.nnz == 3, "J1, J2");
  /* J1's pattern has no diagonal: give it J2's, with a zero there */
  sym_csc_free (&a);
  CHECK (sym_csc_copy (&a, &b) == SYM_SUCCESS, "copy");
  a.val[0] = 0.0;
  a.val[1] = 0.1;
  a.val[2] = 0.1;
  CHECK (sym_stage_lu_init (&s, 2, 1) == SYM_SUCCESS, "init");
  for (int k = 0; k < 2; k++)
    {
      const sym_csc *J = k ? &b : &a;
      const double *jd = k ? j2 : j1;
      CHECK (sym_stage_lu_factor (&s, 1.0, 0.0, NULL, 0, J, NULL)
             == SYM_SUCCESS, "factor %d", k);
      double x[2] = { 1.0, 2.0 };
      CHECK (sym_stage_lu_solve (&s, x, NULL) == SYM_SUCCESS, "solve %d", k);
      /* (I - J) x = [1; 2] */
      double r0 = x[0] - jd[0] * x[0] - jd[2] * x[1] - 1.0;
      double r1 = x[1] - jd[1] * x[0] - jd[3] * x[1] - 2.0;
      CHECK (fabs (r0) < 1e-14 && fabs (r1) < 1e-14, "solve %d: residual "
             "%.3g %.3g", k, r0, r1);
    }
  sym_stage_lu_free (&s);
  sym_csc_free (&a);
  sym_csc_free (&b);
}

int
main (void)
{
  sym_set_allocator (t_alloc, t_free);
  test_csc ();
  CHECK (al_live == 0, "csc helpers: %ld blocks left", al_live);
  test_solves ();
  test_patterns ();
  test_failures ();
  test_refactor_fallback ();
  CHECK (al_live == 0, "stage LU: %ld blocks left", al_live);
  test_allocation ();
  test_large ();
  CHECK (al_live == 0 && al_bytes == 0, "at the end: %ld blocks left",
         al_live);
  sym_set_allocator (NULL, NULL);
  return tu_finish ("test_stagelu");
}
