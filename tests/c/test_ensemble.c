/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* test_ensemble.c -- sym_ensemble (driver/ensemble.c): members run on
   stacks of their own in rounds, their f evaluated in one batch call per
   round.  The truth each member is held to is its own sym_integrate from
   its column: the same rows, events, dense output, status and counters,
   bit for bit, whatever the other members do (K, their order, their
   failures, their events).  Also: the number and shape of the batch
   calls, every callback on the caller's stack, a round callback that
   stops or fails the ensemble, allocation failures, 3000 members, a
   member with a deep stack, bad input. */
#include "sym.h"
#include "driver_util.h"
#include "test_spvi_systems.h"
#include "testutil.h"

#include <limits.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* ------------------------------------------------------------ stacks */
/* The frame of main: a callback on the caller's stack is within a few
   frames of it, a member's stack is a heap block far away. */
static uintptr_t main_frame;
#define NEAR_MAIN ((uintptr_t) 8 << 20)

static uintptr_t
frame_here (void)
{
#if defined (__GNUC__)
  return (uintptr_t) __builtin_frame_address (0);
#else
  volatile char c = 0;
  return (uintptr_t) &c;
#endif
}

/* The big blocks the core holds (the members' stacks among them), kept by
   the allocator below, so that a callback can tell whether it runs inside
   one.  With hw_size set, blocks of that size are filled with a pattern
   and, when freed, measured for the deepest byte written (a stack's high
   water mark). */
#define BIG_MIN ((size_t) 64 << 10)
#define MAXBIG 8192
static struct {
  uintptr_t lo;
  size_t n;
} big[MAXBIG];
static int nbig;
static size_t hw_size, hw_most;
static long hw_blocks;
/* blocks of a member's default stack: held now, most at once, in all */
static long stk_live, stk_most, stk_total;
#define HW_BYTE 0xA5

static long nallocs;     /* the allocator's calls */

static void *
big_alloc (size_t nbytes)
{
  nallocs++;
  void *p = malloc (nbytes);
  if (p && nbytes >= BIG_MIN && nbig < MAXBIG)
    {
      big[nbig].lo = (uintptr_t) p;
      big[nbig].n = nbytes;
      nbig++;
      if (hw_size && nbytes == hw_size)
        memset (p, HW_BYTE, nbytes);
      if (nbytes == SYM_ENS_STACK + SYM_ENS_SKEW)
        {
          stk_total++;
          if (++stk_live > stk_most)
            stk_most = stk_live;
        }
    }
  return p;
}

static void
big_free (void *p)
{
  for (int i = nbig - 1; p && i >= 0; i--)
    if (big[i].lo == (uintptr_t) p)
      {
        if (hw_size && big[i].n == hw_size)
          {
            /* a stack grows down: the untouched pattern at its low end */
            const unsigned char *b = p;
            size_t k = 0;
            while (k < big[i].n && b[k] == HW_BYTE)
              k++;
            if (big[i].n - k > hw_most)
              hw_most = big[i].n - k;
            hw_blocks++;
          }
        stk_live -= big[i].n == SYM_ENS_STACK + SYM_ENS_SKEW;
        big[i] = big[--nbig];
        break;
      }
  free (p);
}

/* what every callback records of the stack it runs on */
enum { CB_RHS, CB_BATCH, CB_JAC, CB_RHSJAC, CB_EVENTS, CB_EVOUT, CB_OUTPUT,
       CB_DENSE, CB_DENSITY, CB_ROUND, NCB };
static const char *const cb_name[NCB] = {
  "rhs", "rhs_batch", "jac", "rhs_jac", "events", "event_out", "output",
  "dense_out", "density", "round" };
static int probing;
static long cb_calls[NCB], cb_off_main[NCB], cb_on_member[NCB];

static void
probe (int cb)
{
  if (! probing)
    return;
  const uintptr_t sp = frame_here ();
  int inside = 0;
  for (int i = 0; i < nbig && ! inside; i++)
    inside = sp >= big[i].lo && sp < big[i].lo + big[i].n;
  const uintptr_t d = sp > main_frame ? sp - main_frame : main_frame - sp;
  cb_calls[cb]++;
  cb_on_member[cb] += inside;
  cb_off_main[cb] += inside || d >= NEAR_MAIN;
}

static void
probe_reset (void)
{
  memset (cb_calls, 0, sizeof cb_calls);
  memset (cb_off_main, 0, sizeof cb_off_main);
  memset (cb_on_member, 0, sizeof cb_on_member);
}

/* ------------------------------------------------------------ records */
typedef struct {
  double *v;
  size_t n, cap;
} dlog;

static void
dlog_put (dlog *l, const double *v, size_t k)
{
  if (l->n + k > l->cap)
    {
      size_t cap = l->cap ? 2 * l->cap : 64;
      while (cap < l->n + k)
        cap *= 2;
      double *p = realloc (l->v, cap * sizeof (double));
      if (! p)
        {
          fprintf (stderr, "test_ensemble: out of memory\n");
          exit (2);
        }
      l->v = p;
      l->cap = cap;
    }
  memcpy (l->v + l->n, v, k * sizeof (double));
  l->n += k;
}

static int
dlog_same (const dlog *a, const dlog *b)
{
  return a->n == b->n
         && (a->n == 0 || memcmp (a->v, b->v, a->n * sizeof (double)) == 0);
}

/* a run's rows (t, y), events (te, ie, ye) and dense output (t, tnew, k,
   the k + 2 columns), as its sinks saw them */
typedef struct {
  int n;
  long nrows, nev, ndense;
  dlog rows, evs, dense;
  long stop_after;     /* the output sink returns stop_val at this row */
  int stop_val;
} rec;

static void
rec_init (rec *r, int n)
{
  memset (r, 0, sizeof *r);
  r->n = n;
}

static void
rec_free (rec *r)
{
  free (r->rows.v);
  free (r->evs.v);
  free (r->dense.v);
  memset (r, 0, sizeof *r);
}

static const double *
rec_last_row (const rec *r)
{
  return r->rows.v + r->rows.n - (size_t) r->n;
}

static int
out_row (double t, const double *y, void *u)
{
  rec *r = u;
  probe (CB_OUTPUT);
  dlog_put (&r->rows, &t, 1);
  dlog_put (&r->rows, y, (size_t) r->n);
  r->nrows++;
  return r->stop_after && r->nrows == r->stop_after ? r->stop_val : 0;
}

static int
out_event (double te, const double *ye, int ie, void *u)
{
  rec *r = u;
  probe (CB_EVOUT);
  double h[2] = { te, ie };
  dlog_put (&r->evs, h, 2);
  dlog_put (&r->evs, ye, (size_t) r->n);
  r->nev++;
  return 0;
}

static int
out_dense (double t, double tnew, int k, const double *y, void *u)
{
  rec *r = u;
  probe (CB_DENSE);
  double h[3] = { t, tnew, k };
  dlog_put (&r->dense, h, 3);
  dlog_put (&r->dense, y, (size_t) r->n * (size_t) (k + 2));
  r->ndense++;
  return 0;
}

static int
same_bits (double a, double b)
{
  return memcmp (&a, &b, sizeof a) == 0;
}

static int
same_stats (const sym_stats *a, const sym_stats *b)
{
  return memcmp (&a->cnt, &b->cnt, sizeof a->cnt) == 0
         && same_bits (a->t_reached, b->t_reached) && a->order == b->order
         && same_bits (a->fail_t, b->fail_t)
         && a->fail_status == b->fail_status && a->fail_df == b->fail_df
         && a->jac_dropped == b->jac_dropped
         && a->rhs_jac_used == b->rhs_jac_used
         && a->sep_broken == b->sep_broken;
}

/* a member against its own single run: 1 if all the same */
static int
same_run (const char *what, int j, int st_a, const rec *a,
          const sym_stats *sa, int st_b, const rec *b, const sym_stats *sb)
{
  int ok = 1;
#define SAME(cond, ...)                                                   \
  do {                                                                    \
    CHECK (cond, __VA_ARGS__);                                            \
    ok &= !! (cond);                                                      \
  } while (0)
  SAME (st_a == st_b, "%s: member %d status %s, alone %s", what, j,
        sym_status_name (st_a), sym_status_name (st_b));
  SAME (dlog_same (&a->rows, &b->rows), "%s: member %d rows differ (%ld "
        "rows, alone %ld)", what, j, a->nrows, b->nrows);
  SAME (dlog_same (&a->evs, &b->evs), "%s: member %d events differ (%ld, "
        "alone %ld)", what, j, a->nev, b->nev);
  SAME (dlog_same (&a->dense, &b->dense), "%s: member %d dense output "
        "differs (%ld, alone %ld)", what, j, a->ndense, b->ndense);
  SAME (same_stats (sa, sb), "%s: member %d stats differ (nrhs %ld, alone "
        "%ld; nsteps %ld, alone %ld)", what, j, sa->cnt.nrhs, sb->cnt.nrhs,
        sa->cnt.nsteps, sb->cnt.nsteps);
#undef SAME
  return ok;
}

/* ------------------------------------------------------------ Kepler */
/* H = |p|^2/2 - 1/|q| in the plane (dim 2), or with a third coordinate
   (dim 3) whose q stays put at a member's marker (its p is 0): the
   marker tells which member a state belongs to. */
#define MAXM 16
typedef struct {
  int dim;
  double rmax;        /* f fails where |q| > rmax (0: nowhere) */
  int fail_mode;      /* there: 0 a NaN, else the status returned */
  long nrhs_calls;
  /* the batch calls */
  long nbatch, ncols, nlone, kmin, kmax, since_round;
  /* by member (order_on, dim 3): pos_of[marker] is its place */
  int order_on, last_pos;
  const int *pos_of;
  long order_bad, rhs_pm[MAXM], cols_pm[MAXM], lone_pm[MAXM];
  long most_members;  /* members in one batch call, at most */
} kuser;

static void
kuser_init (kuser *u, int dim)
{
  memset (u, 0, sizeof *u);
  u->dim = dim;
  u->kmin = LONG_MAX;
  u->last_pos = -1;
}

static int
kep_col (const kuser *u, const double *y, double *dy)
{
  const int d = u->dim;
  const double r2 = y[0] * y[0] + y[1] * y[1], r = sqrt (r2), r3 = r2 * r;
  dy[0] = y[d];
  dy[1] = y[d + 1];
  dy[d] = -y[0] / r3;
  dy[d + 1] = -y[1] / r3;
  if (d == 3)
    {
      dy[2] = y[5];
      dy[5] = 0.0;
    }
  if (u->rmax > 0 && r > u->rmax)
    {
      if (u->fail_mode == 0)
        dy[d] = NAN;
      else
        return u->fail_mode;
    }
  return 0;
}

static int
marker_pos (const kuser *u, const double *y)
{
  long mk = lround (y[2]);
  return mk >= 1 && mk <= MAXM ? u->pos_of[mk] : -1;
}

static int
k_rhs (double t, const double *y, double *dy, void *user)
{
  (void) t;
  kuser *u = user;
  probe (CB_RHS);
  u->nrhs_calls++;
  if (u->order_on)
    {
      /* one call per state, the members in their order */
      int pos = marker_pos (u, y);
      if (pos <= u->last_pos || pos < 0)
        u->order_bad++;
      else
        u->rhs_pm[pos]++;
      u->last_pos = pos;
    }
  return kep_col (u, y, dy);
}

static int
k_batch (int k, const double *t, const double *y, double *dy, void *user)
{
  kuser *u = user;
  const int n = 2 * u->dim;
  probe (CB_BATCH);
  u->nbatch++;
  u->since_round++;
  u->ncols += k;
  u->kmin = k < u->kmin ? k : u->kmin;
  u->kmax = k > u->kmax ? k : u->kmax;
  const int lone = k == 2 && t[0] == t[1]
                   && memcmp (y, y + n, (size_t) n * sizeof (double)) == 0;
  u->nlone += lone;
  int last = -1, st = 0;
  long members = 0;
  for (int j = 0; j < k; j++)
    {
      const double *yj = y + (size_t) j * n;
      if (u->order_on)
        {
          /* a member's columns together, the members in their order */
          int pos = marker_pos (u, yj);
          members += pos != last;
          if (pos < last || pos < 0)
            u->order_bad++;
          else
            u->cols_pm[pos]++;
          if (lone && j == 0 && pos >= 0)
            u->lone_pm[pos]++;
          last = pos;
        }
      int s = kep_col (u, yj, dy + (size_t) j * n);
      if (s && ! st)
        st = s;
    }
  if (members > u->most_members)
    u->most_members = members;
  return st;
}

static void
kep_df (const kuser *u, const double *y, double *df)
{
  const int d = u->dim, n = 2 * d;
  const double r2 = y[0] * y[0] + y[1] * y[1], r = sqrt (r2);
  const double r3 = r2 * r, r5 = r3 * r2;
  memset (df, 0, (size_t) n * n * sizeof (double));
  for (int i = 0; i < d; i++)
    df[i + (d + i) * n] = 1.0;
  for (int i = 0; i < 2; i++)
    for (int j = 0; j < 2; j++)
      df[(d + i) + j * n] = -((i == j) / r3 - 3.0 * y[i] * y[j] / r5);
}

static int
k_jac (double t, const double *y, double *df, void *user)
{
  (void) t;
  probe (CB_JAC);
  kep_df (user, y, df);
  return 0;
}

static int
k_rhs_jac (double t, const double *y, double *dy, double *df, void *user)
{
  (void) t;
  probe (CB_RHSJAC);
  kep_df (user, y, df);
  return kep_col (user, y, dy);
}

/* q2 = 0, both ways, not terminal */
static int
k_events (double t, const double *y, double *value, int *isterminal,
          int *direction, void *user)
{
  (void) t;
  (void) user;
  probe (CB_EVENTS);
  value[0] = y[1];
  isterminal[0] = 0;
  direction[0] = 0;
  return 0;
}

/* Kepler's time scale |q|^(-3/2) */
static int
k_density (double t, const double *y, double *rho, void *user)
{
  (void) t;
  (void) user;
  probe (CB_DENSITY);
  *rho = pow (hypot (y[0], y[1]), -1.5);
  return 0;
}

/* jac: 0 finite differences, 1 jac and rhs_jac, 2 jac alone */
static sym_system
kep_system (kuser *u, int batch, int jac)
{
  sym_system s;
  memset (&s, 0, sizeof s);
  s.dim = u->dim;
  s.rhs = k_rhs;
  s.rhs_batch = batch ? k_batch : NULL;
  s.jac = jac ? k_jac : NULL;
  s.rhs_jac = jac == 1 ? k_rhs_jac : NULL;
  s.user = u;
  return s;
}

/* from the pericentre, semi-major axis 1, eccentricity e */
static void
kep_start (double e, int dim, double marker, double *y)
{
  const int d = dim;
  memset (y, 0, (size_t) 2 * d * sizeof (double));
  y[0] = 1.0 - e;
  y[d + 1] = sqrt ((1.0 + e) / (1.0 - e));
  if (d == 3)
    y[2] = marker;
}

/* ------------------------------------------------------------ rounds */
typedef struct {
  kuser *ku;          /* its batch calls since the last round (or NULL) */
  long rounds, bad_since;
  long stop_at;       /* return stop_val from this round on (0: never) */
  int stop_val;
} rounder;

static int
on_round (void *user)
{
  rounder *r = user;
  probe (CB_ROUND);
  r->rounds++;
  if (r->ku)
    {
      /* each round but the first follows one evaluation of the round
         before */
      if (r->ku->since_round != (r->rounds > 1 && r->ku->kmax > 0))
        r->bad_since++;
      r->ku->since_round = 0;
      r->ku->last_pos = -1;
    }
  return r->stop_at && r->rounds >= r->stop_at ? r->stop_val : 0;
}

/* ------------------------------------------------------------ ensembles */
typedef struct {
  int K, n;
  double *y0;
  sym_driver_opts *d;
  rec *recs;
  sym_stats *st;
  int *status;
  sym_ensemble_opts eo;
  rounder rd;
  int rc;
} erun;

static void
erun_init (erun *e, int K, int n)
{
  memset (e, 0, sizeof *e);
  e->K = K;
  e->n = n;
  e->y0 = calloc ((size_t) K * n, sizeof (double));
  e->d = calloc ((size_t) K, sizeof (sym_driver_opts));
  e->recs = calloc ((size_t) K, sizeof (rec));
  e->st = calloc ((size_t) K, sizeof (sym_stats));
  e->status = calloc ((size_t) K, sizeof (int));
  if (! e->y0 || ! e->d || ! e->recs || ! e->st || ! e->status)
    {
      fprintf (stderr, "test_ensemble: out of memory\n");
      exit (2);
    }
  for (int j = 0; j < K; j++)
    {
      rec_init (&e->recs[j], n);
      e->status[j] = 12345;
    }
  e->eo.members = K;
  e->eo.y0 = e->y0;
  e->eo.dopts = e->d;
  e->eo.stats = e->st;
  e->eo.status = e->status;
  e->eo.round = on_round;
  e->eo.round_user = &e->rd;
}

static void
erun_free (erun *e)
{
  for (int j = 0; j < e->K; j++)
    rec_free (&e->recs[j]);
  free (e->y0);
  free (e->d);
  free (e->recs);
  free (e->st);
  free (e->status);
}

static int
erun_go (erun *e, const sym_stepper_type *type, const sym_system *sys,
         const sym_method_opts *mo)
{
  /* the probe looks through every big block: not with thousands */
  probing = e->K <= 64;
  e->rc = sym_ensemble (type, sys, mo, &e->eo);
  probing = 0;
  return e->rc;
}

/* ------------------------------------------------------------ methods */
typedef struct {
  const char *name;
  const sym_stepper_type *const *type;
  int q, m;              /* SPVI's pair */
  int sep;               /* SE, SV, splitting: explicit (separable) */
  const char *split;     /* the splitting stepper's method */
  double h;              /* > 0: fixed steps */
  double rtol;           /* else adaptive, or reversible (rev) */
  int rev;
  int jac;               /* the analytic Df (kep_system) */
  int refine, tout;
} cfg;

static const cfg cfgs[] = {
  /* name, stepper, q, m, sep, split, h, rtol, rev, jac, refine, tout */
  { "SPVI (4,3) fixed", &sym_step_spvi,
    4, 3, 0, NULL, 0.1, 0, 0, 0, 2, 0 },
  { "SPVI (4,3) adaptive", &sym_step_spvi,
    4, 3, 0, NULL, 0, 1e-8, 0, 0, 1, 0 },
  { "SPVI (3,3) fixed", &sym_step_spvi,
    3, 3, 0, NULL, 0.1, 0, 0, 0, 1, 0 },
  { "SPVI (3,3) adaptive", &sym_step_spvi,
    3, 3, 0, NULL, 0, 1e-8, 0, 0, 1, 1 },
  { "SPVI (4,3) fixed, Df", &sym_step_spvi,
    4, 3, 0, NULL, 0.1, 0, 0, 1, 1, 0 },
  { "SPVI (4,3) adaptive, jac", &sym_step_spvi,
    4, 3, 0, NULL, 0, 1e-8, 0, 2, 1, 0 },
  { "SPVI (4,3) reversible", &sym_step_spvi,
    4, 3, 0, NULL, 0, 1e-6, 1, 0, 1, 0 },
  { "SV implicit fixed", &sym_step_sv,
    0, 0, 0, NULL, 0.05, 0, 0, 0, 1, 0 },
  { "SV implicit fixed, jac", &sym_step_sv,
    0, 0, 0, NULL, 0.05, 0, 0, 2, 1, 0 },
  { "SV implicit adaptive", &sym_step_sv,
    0, 0, 0, NULL, 0, 1e-6, 0, 0, 1, 0 },
  { "SE implicit fixed", &sym_step_se,
    0, 0, 0, NULL, 0.02, 0, 0, 0, 1, 0 },
  { "SE implicit adaptive", &sym_step_se,
    0, 0, 0, NULL, 0, 1e-4, 0, 0, 1, 0 },
  { "SV explicit fixed", &sym_step_sv,
    0, 0, 1, NULL, 0.05, 0, 0, 0, 1, 0 },
  { "SV explicit adaptive", &sym_step_sv,
    0, 0, 1, NULL, 0, 1e-6, 0, 0, 1, 0 },
  { "SE explicit fixed", &sym_step_se,
    0, 0, 1, NULL, 0.02, 0, 0, 0, 1, 0 },
  { "SE explicit adaptive", &sym_step_se,
    0, 0, 1, NULL, 0, 1e-4, 0, 0, 1, 0 },
  { "yoshida4 implicit", &sym_step_splitting,
    0, 0, 0, "yoshida4", 0.1, 0, 0, 0, 1, 0 },
  { "yoshida4 explicit", &sym_step_splitting,
    0, 0, 1, "yoshida4", 0.1, 0, 0, 0, 1, 0 },
  { "kahanli6 explicit reversible", &sym_step_splitting,
    0, 0, 1, "kahanli6", 0, 1e-6, 1, 0, 1, 0 },
};
#define NCFG ((int) (sizeof cfgs / sizeof cfgs[0]))

static const cfg *
cfg_named (const char *name)
{
  for (int i = 0; i < NCFG; i++)
    if (! strcmp (cfgs[i].name, name))
      return &cfgs[i];
  fprintf (stderr, "test_ensemble: no method %s\n", name);
  exit (2);
}

typedef struct {
  sym_method_opts mo;
  sym_spvi_opts so;
  sym_onestep_opts oo;
} mopts;

static void
make_mo (const cfg *c, mopts *m)
{
  memset (m, 0, sizeof *m);
  if (*c->type == sym_step_spvi)
    {
      m->so.q_dofs = c->q;
      m->so.nodes = c->m;
      m->mo.own = &m->so;
    }
  else
    {
      m->oo.separable = c->sep;
      m->oo.method = c->split ? sym_splitting_find (c->split) : 0;
      m->mo.own = &m->oo;
    }
}

/* The columns of test 1: eccentricities, ends and output times of their
   own, so that the members end at different rounds */
#define NC 7
static const double ecc[NC] = { 0.05, 0.6, 0.2, 0.45, 0.1, 0.3, 0.55 };
static double tf_of[NC], tout_of[NC][64];
static int ntout_of[NC];
static double atol_one = 1e-12;
static double tf_short;   /* > 0: every column ends there */

static void
columns_setup (void)
{
  for (int c = 0; c < NC; c++)
    {
      tf_of[c] = 3.0 + 0.37 * c;
      int k = 0;
      for (double t = 0; t < tf_of[c] - 1e-9 && k < 63; t += 0.25)
        tout_of[c][k++] = t;
      tout_of[c][k++] = tf_of[c];
      ntout_of[c] = k;
    }
}

static void
kep_dopts (const cfg *c, int col, rec *r, sym_driver_opts *o)
{
  memset (o, 0, sizeof *o);
  o->t0 = 0;
  o->tf = tf_short > 0 ? tf_short : tf_of[col];
  o->refine = c->refine;
  if (c->h > 0)
    o->h_fixed = c->h;
  else
    {
      o->tol.rtol = c->rtol;
      o->tol.atol = &atol_one;
      o->tol.atol_len = 1;
    }
  if (c->rev)
    {
      o->step_control = SYM_CONTROL_REVERSIBLE;
      o->density = k_density;
      o->density_user = r;
    }
  if (c->tout)
    {
      o->tout = tout_of[col];
      o->ntout = ntout_of[col];
    }
  o->nevents = 1;
  o->events = k_events;
  o->event_user = r;
  o->event_out = out_event;
  o->output = out_row;
  o->output_user = r;
  /* members with and without a dense sink */
  o->dense_out = col % 2 ? NULL : out_dense;
  o->dense_user = r;
}

/* the single runs of the columns (test 1's truth) */
typedef struct {
  rec r[NC];
  sym_stats st[NC];
  int status[NC];
} refs;

static void
refs_run (refs *R, const cfg *c, int batch)
{
  mopts m;
  make_mo (c, &m);
  for (int col = 0; col < NC; col++)
    {
      kuser u;
      kuser_init (&u, 3);
      sym_system sys = kep_system (&u, batch, c->jac);
      double y0[6];
      kep_start (ecc[col], 3, col + 1, y0);
      sym_driver_opts o;
      rec_init (&R->r[col], 6);
      kep_dopts (c, col, &R->r[col], &o);
      R->status[col] = sym_integrate (*c->type, &sys, &m.mo, &o, y0,
                                      &R->st[col]);
    }
}

static void
refs_free (refs *R)
{
  for (int col = 0; col < NC; col++)
    rec_free (&R->r[col]);
}

/* Test 2: the batch calls of an ensemble of test 1 */
static void
check_batching (const char *what, const erun *e, const kuser *u, int batch)
{
  long maxrhs = 0, sumrhs = 0, sumstates = 0;
  for (int j = 0; j < e->K; j++)
    {
      maxrhs = e->st[j].cnt.nrhs > maxrhs ? e->st[j].cnt.nrhs : maxrhs;
      sumrhs += e->st[j].cnt.nrhs;
      sumstates += e->st[j].cnt.nrhs_states;
    }
  const int L = e->eo.max_live;
  const int all = L <= 0 || L >= e->K;
  CHECK (e->rd.rounds == e->eo.nrounds, "%s: %ld rounds, round callback "
         "%ld", what, e->eo.nrounds, e->rd.rounds);
  /* all at once: each round evaluates one call of every member still
     running, and the member with the most calls ends in the round after
     its last; one at a time: each member's calls and its end in rounds
     of its own */
  if (all)
    CHECK (e->eo.nrounds == maxrhs + 1, "%s: %ld rounds, most calls of a "
           "member %ld", what, e->eo.nrounds, maxrhs);
  else if (L == 1)
    CHECK (e->eo.nrounds == sumrhs + e->K, "%s: %ld rounds, %ld calls of "
           "the members", what, e->eo.nrounds, sumrhs);
  CHECK (u->order_bad == 0, "%s: %ld states out of member order", what,
         u->order_bad);
  if (batch)
    {
      CHECK (e->eo.nbatch == u->nbatch
             && u->nbatch == (all ? maxrhs : L == 1 ? sumrhs : u->nbatch),
             "%s: nbatch %ld, batch calls %ld, rounds that needed f %ld",
             what, e->eo.nbatch, u->nbatch, all ? maxrhs : sumrhs);
      CHECK (u->kmin >= 2 && u->nrhs_calls == 0,
             "%s: a batch call of %ld columns, %ld rhs calls", what,
             u->kmin, u->nrhs_calls);
      CHECK (u->most_members <= (all ? e->K : L), "%s: %ld members in a "
             "batch call", what, u->most_members);
      if (all)
        CHECK (e->rd.bad_since == 0, "%s: %ld rounds without exactly one "
               "batch call before them", what, e->rd.bad_since);
      /* every state of every member once, a lone one twice */
      CHECK (u->ncols - u->nlone == sumstates, "%s: %ld columns, %ld lone, "
             "%ld states of the members", what, u->ncols, u->nlone,
             sumstates);
      for (int j = 0; j < e->K; j++)
        CHECK (u->cols_pm[j] - u->lone_pm[j] == e->st[j].cnt.nrhs_states,
               "%s: member %d: %ld columns, %ld states", what, j,
               u->cols_pm[j] - u->lone_pm[j], e->st[j].cnt.nrhs_states);
      if (e->K >= 7 && all)
        CHECK (3 * e->eo.nbatch <= sumrhs, "%s: %ld batch calls for %ld "
               "calls of the members", what, e->eo.nbatch, sumrhs);
    }
  else
    {
      CHECK (e->eo.nbatch == 0 && u->nbatch == 0, "%s: nbatch %ld", what,
             e->eo.nbatch);
      for (int j = 0; j < e->K; j++)
        CHECK (u->rhs_pm[j] == e->st[j].cnt.nrhs
               && e->st[j].cnt.nrhs == e->st[j].cnt.nrhs_states,
               "%s: member %d: %ld rhs calls, nrhs %ld", what, j,
               u->rhs_pm[j], e->st[j].cnt.nrhs);
    }
}

/* an ensemble of test 1: member j runs column col[j] */
static void
ens_check (const cfg *c, int batch, const refs *R, int K, const int *col,
           int direct, int max_live)
{
  char what[160];
  snprintf (what, sizeof what, "%s, %s, K = %d%s%s, max_live %d", c->name,
            batch ? "batch" : "no batch", K,
            K > 1 && col[0] != 0 ? ", permuted" : "",
            direct ? ", direct sinks" : "", max_live);
  mopts m;
  make_mo (c, &m);
  kuser u;
  kuser_init (&u, 3);
  int pos_of[MAXM + 1];
  for (int i = 0; i <= MAXM; i++)
    pos_of[i] = -1;
  for (int j = 0; j < K; j++)
    pos_of[col[j] + 1] = j;
  u.pos_of = pos_of;
  u.order_on = 1;
  sym_system sys = kep_system (&u, batch, c->jac);
  erun e;
  erun_init (&e, K, 6);
  e.rd.ku = &u;
  e.eo.direct_sinks = direct;
  e.eo.max_live = max_live;
  stk_live = stk_most = stk_total = 0;
  for (int j = 0; j < K; j++)
    {
      kep_start (ecc[col[j]], 3, col[j] + 1, e.y0 + 6 * j);
      kep_dopts (c, col[j], &e.recs[j], &e.d[j]);
    }
  int rc = erun_go (&e, *c->type, &sys, &m.mo);
  CHECK (rc == SYM_SUCCESS, "%s: sym_ensemble %s", what,
         sym_status_name (rc));
  int ok = 1;
  for (int j = 0; j < K; j++)
    ok &= same_run (what, j, e.status[j], &e.recs[j], &e.st[j],
                    R->status[col[j]], &R->r[col[j]], &R->st[col[j]]);
  if (! ok)
    fprintf (stderr, "  (%s not bit-identical to single runs)\n", what);
  check_batching (what, &e, &u, batch);
  /* a stack for each member running at once, and no more */
  const long want = max_live > 0 && max_live < K ? max_live : K;
  CHECK (stk_total == want && stk_most == want && stk_live == 0,
         "%s: %ld stacks, %ld at once, %ld left", what, stk_total, stk_most,
         stk_live);
  erun_free (&e);
}

/* ------------------------------------------------------------ test 1-3 */
static long t1_members;

static void
test_identity (void)
{
  static const int one[1] = { 3 }, two[2] = { 0, 1 };
  static const int ident[NC] = { 0, 1, 2, 3, 4, 5, 6 };
  static const int perm[NC] = { 4, 0, 6, 2, 5, 1, 3 };
  probe_reset ();
  for (int ci = 0; ci < NCFG; ci++)
    for (int batch = 0; batch < 2; batch++)
      {
        const cfg *c = &cfgs[ci];
        refs R;
        refs_run (&R, c, batch);
        for (int col = 0; col < NC; col++)
          CHECK (R.status[col] == SYM_DONE && R.r[col].nrows > 1,
                 "%s: the single run of column %d: %s", c->name, col,
                 sym_status_name (R.status[col]));
        ens_check (c, batch, &R, 1, one, 0, 0);
        ens_check (c, batch, &R, 2, two, 0, 0);
        ens_check (c, batch, &R, NC, ident, 0, 0);
        ens_check (c, batch, &R, NC, perm, 0, 0);
        t1_members += 1 + 2 + 2 * NC;
        refs_free (&R);
      }
  /* Test 3: every callback of those ensembles ran on the caller's stack */
  for (int cb = 0; cb < NCB; cb++)
    {
      CHECK (cb_calls[cb] > 0, "callback %s never called", cb_name[cb]);
      CHECK (cb_off_main[cb] == 0, "callback %s: %ld of %ld calls off the "
             "caller's stack (%ld on a member's)", cb_name[cb],
             cb_off_main[cb], cb_calls[cb], cb_on_member[cb]);
    }
  printf ("  identity: %d methods x 2, %ld members; callbacks probed:",
          NCFG, t1_members);
  for (int cb = 0; cb < NCB; cb++)
    printf (" %s %ld", cb_name[cb], cb_calls[cb]);
  printf ("\n");
}

/* Test 3 with direct sinks: the sinks may run on a member's stack (and
   do: no switch for a row), every other callback still on the caller's */
static void
test_direct_sinks (void)
{
  static const int perm[NC] = { 4, 0, 6, 2, 5, 1, 3 };
  static const char *const pick[] = { "SPVI (4,3) fixed",
    "SPVI (4,3) fixed, Df", "SV implicit fixed, jac",
    "SPVI (4,3) reversible" };
  for (size_t i = 0; i < sizeof pick / sizeof pick[0]; i++)
    for (int batch = 0; batch < 2; batch++)
      {
        const cfg *c = cfg_named (pick[i]);
        refs R;
        refs_run (&R, c, batch);
        probe_reset ();
        ens_check (c, batch, &R, NC, perm, 1, 0);
        CHECK (cb_on_member[CB_OUTPUT] == cb_calls[CB_OUTPUT]
               && cb_calls[CB_OUTPUT] > 0, "%s: direct sinks: %ld of %ld "
               "rows on a member's stack", c->name,
               cb_on_member[CB_OUTPUT], cb_calls[CB_OUTPUT]);
        for (int cb = 0; cb < NCB; cb++)
          if (cb != CB_OUTPUT && cb != CB_EVOUT && cb != CB_DENSE)
            CHECK (cb_off_main[cb] == 0, "%s: direct sinks: callback %s: "
                   "%ld of %ld calls off the caller's stack", c->name,
                   cb_name[cb], cb_off_main[cb], cb_calls[cb]);
        refs_free (&R);
      }
}

/* Members a few at a time (max_live): a member starts on the stack of
   one that ended, and still computes what it does alone */
static void
test_max_live (void)
{
  static const int ident[NC] = { 0, 1, 2, 3, 4, 5, 6 };
  static const int perm[NC] = { 4, 0, 6, 2, 5, 1, 3 };
  static const char *const pick[] = { "SPVI (4,3) fixed",
    "SPVI (4,3) adaptive", "SV implicit adaptive", "SPVI (4,3) reversible",
    "yoshida4 explicit" };
  for (size_t i = 0; i < sizeof pick / sizeof pick[0]; i++)
    for (int batch = 0; batch < 2; batch++)
      {
        const cfg *c = cfg_named (pick[i]);
        refs R;
        refs_run (&R, c, batch);
        ens_check (c, batch, &R, NC, ident, 0, 1);
        ens_check (c, batch, &R, NC, perm, 0, 2);
        ens_check (c, batch, &R, NC, ident, batch, 3);
        ens_check (c, batch, &R, NC, perm, 0, NC + 5);
        refs_free (&R);
      }
}

/* The blocks a member makes at its start (its run's arrays, its
   stepper) come from a chunk of its stack's slot, which the next member
   there takes over: of an ensemble of K like members two at a time, only
   the first member's come from the allocator, and in these runs a
   member makes all its blocks at its start: the members beyond the
   first call the allocator not at all (their second stack aside), and
   still compute what they do alone. */
static void
test_recycled (void)
{
  static const char *const pick[] = { "SPVI (4,3) fixed",
    "SPVI (4,3) adaptive", "SV implicit adaptive", "yoshida4 explicit" };
  enum { K = 8 };
  for (size_t i = 0; i < sizeof pick / sizeof pick[0]; i++)
    {
      const cfg *c = cfg_named (pick[i]);
      mopts m;
      make_mo (c, &m);
      kuser u;
      kuser_init (&u, 3);
      sym_system sys = kep_system (&u, 1, c->jac);
      double y0[6];
      kep_start (ecc[1], 3, 2, y0);
      sym_driver_opts o;
      rec alone;
      rec_init (&alone, 6);
      kep_dopts (c, 1, &alone, &o);
      sym_stats sa;
      long n0 = nallocs;
      const int sta = sym_integrate (*c->type, &sys, &m.mo, &o, y0, &sa);
      const long single = nallocs - n0;
      long ens[2];
      for (int big_k = 0; big_k < 2; big_k++)
        {
          const int k = big_k ? K : 1;
          erun e;
          erun_init (&e, k, 6);
          e.eo.max_live = 2;
          for (int j = 0; j < k; j++)
            {
              memcpy (e.y0 + 6 * j, y0, sizeof y0);
              kep_dopts (c, 1, &e.recs[j], &e.d[j]);
            }
          n0 = nallocs;
          CHECK (erun_go (&e, *c->type, &sys, &m.mo) == SYM_SUCCESS,
                 "%s: recycled blocks: sym_ensemble", c->name);
          ens[big_k] = nallocs - n0;
          for (int j = 0; j < k; j++)
            if (! same_run (c->name, j, e.status[j], &e.recs[j], &e.st[j],
                            sta, &alone, &sa))
              fprintf (stderr, "  (recycled blocks: not as alone)\n");
          erun_free (&e);
        }
      const double per = (double) (ens[1] - ens[0]) / (K - 1);
      printf ("  %s: %ld allocations alone, %.1f per further member\n",
              c->name, single, per);
      /* (K - 1) members more, and one stack more: 1 / (K - 1) */
      CHECK (per < 1.0 && single > 1, "%s: %.1f allocations per further "
             "member, %ld alone", c->name, per, single);
      rec_free (&alone);
    }
}

/* ------------------------------------------------------------ test 4 */
/* Pendulum H = p^2/2 - cos q from (q0, 0), a terminal event at q = 0
   going down: at the quarter period K(sin^2(q0/2)), which only the small
   amplitudes reach before tf. */
static int
p_rhs (double t, const double *y, double *dy, void *user)
{
  (void) user;
  probe (CB_RHS);
  return ts_pend (t, y, dy, NULL);
}

static int
p_batch (int k, const double *t, const double *y, double *dy, void *user)
{
  (void) user;
  probe (CB_BATCH);
  for (int j = 0; j < k; j++)
    ts_pend (t[j], y + 2 * j, dy + 2 * j, NULL);
  return 0;
}

static int
p_event (double t, const double *y, double *value, int *isterminal,
         int *direction, void *user)
{
  (void) t;
  (void) user;
  probe (CB_EVENTS);
  value[0] = y[0];
  isterminal[0] = 1;
  direction[0] = -1;
  return 0;
}

static void
test_events (void)
{
  static const double q0[] = { 0.3, 2.0, 1.0, 2.8, 0.6, 2.3 };
  const int K = (int) (sizeof q0 / sizeof q0[0]);
  const double tf = 1.8;
  static const struct {
    const char *name;
    double h, rtol, tol;
  } runs[] = { { "SPVI (4,3) adaptive", 0, 1e-10, 1e-7 },
               { "SPVI (4,3) fixed", 0.05, 0, 1e-6 } };
  long nstop = 0;
  for (size_t ri = 0; ri < sizeof runs / sizeof runs[0]; ri++)
    for (int batch = 0; batch < 2; batch++)
      {
        char what[96];
        snprintf (what, sizeof what, "events, %s, %s", runs[ri].name,
                  batch ? "batch" : "no batch");
        sym_system sys;
        memset (&sys, 0, sizeof sys);
        sys.dim = 1;
        sys.rhs = p_rhs;
        sys.rhs_batch = batch ? p_batch : NULL;
        sym_method_opts mo;
        sym_spvi_opts so;
        ts_opts (&mo, &so, 4, 3);
        mo.want_dense = 0;
        erun e;
        erun_init (&e, K, 2);
        rec alone;
        for (int j = 0; j < K; j++)
          {
            sym_driver_opts *o = &e.d[j];
            memset (o, 0, sizeof *o);
            o->tf = tf;
            o->refine = 1;
            o->h_fixed = runs[ri].h;
            o->tol.rtol = runs[ri].rtol;
            o->tol.atol = &atol_one;
            o->tol.atol_len = 1;
            o->nevents = 1;
            o->events = p_event;
            o->event_user = &e.recs[j];
            o->event_out = out_event;
            o->output = out_row;
            o->output_user = &e.recs[j];
            e.y0[2 * j] = q0[j];
          }
        erun_go (&e, sym_step_spvi, &sys, &mo);
        CHECK (e.rc == SYM_SUCCESS, "%s: %s", what, sym_status_name (e.rc));
        for (int j = 0; j < K; j++)
          {
            /* the truth: the quarter period K(m), m = sin^2(q0/2) */
            const double s = sin (0.5 * q0[j]), m = s * s;
            const double quarter = ts_carlson_rf (0.0, 1.0 - m, 1.0);
            const int stops = quarter < tf;
            CHECK (e.status[j] == (stops ? SYM_STOP_EVENT : SYM_DONE),
                   "%s: member %d (q0 %g, quarter period %.4f): %s", what, j,
                   q0[j], quarter, sym_status_name (e.status[j]));
            const double tend = e.recs[j].nrows ? rec_last_row (&e.recs[j])[-1]
                                                : NAN;
            if (stops)
              {
                nstop++;
                CHECK (e.recs[j].nev == 1, "%s: member %d: %ld events", what,
                       j, e.recs[j].nev);
                CHECK_CLOSE (tend, quarter, runs[ri].tol, "the event's time");
                CHECK_CLOSE (e.recs[j].nev ? e.recs[j].evs.v[0] : NAN,
                             quarter, runs[ri].tol, "te");
              }
            else
              CHECK (e.recs[j].nev == 0 && tend == tf, "%s: member %d: %ld "
                     "events, ends at %g", what, j, e.recs[j].nev, tend);
            /* and what it does alone */
            sym_stats st;
            sym_driver_opts o = e.d[j];
            rec_init (&alone, 2);
            o.event_user = o.output_user = &alone;
            int s1 = sym_integrate (sym_step_spvi, &sys, &mo, &o,
                                    e.y0 + 2 * j, &st);
            same_run (what, j, e.status[j], &e.recs[j], &e.st[j], s1, &alone,
                      &st);
            rec_free (&alone);
          }
        erun_free (&e);
      }
  CHECK (nstop == 4L * 3, "%ld members stopped by their event", nstop);
}

/* ------------------------------------------------------------ test 5 */
/* f fails beyond |q| = 1.7, which only the member of eccentricity 0.85
   reaches (its apocentre is 1.85; the others' at most 1.5) */
static void
test_failures (void)
{
  static const double e5[] = { 0.1, 0.3, 0.85, 0.5, 0.2 };
  const int K = 5, bad = 2;
  static const int modes[] = { 0, 1, -1 };
  static const struct {
    const char *name;
    double h, rtol;
    const sym_stepper_type *const *type;
  } runs[] = { { "SPVI (4,3) fixed", 0.05, 0, &sym_step_spvi },
               { "SPVI (4,3) adaptive", 0, 1e-8, &sym_step_spvi },
               { "SV implicit fixed", 0.05, 0, &sym_step_sv } };
  for (size_t ri = 0; ri < sizeof runs / sizeof runs[0]; ri++)
    for (int mi = 0; mi < 3; mi++)
      for (int batch = 0; batch < 2; batch++)
        {
          char what[128];
          snprintf (what, sizeof what, "failure (%s), %s, %s",
                    modes[mi] == 0 ? "NaN" : modes[mi] > 0 ? "status 1"
                    : "status -1", runs[ri].name,
                    batch ? "batch" : "no batch");
          kuser u;
          kuser_init (&u, 2);
          u.rmax = 1.7;
          u.fail_mode = modes[mi];
          sym_system sys = kep_system (&u, batch, 0);
          sym_method_opts mo;
          sym_spvi_opts so;
          sym_onestep_opts oo;
          memset (&oo, 0, sizeof oo);
          ts_opts (&mo, &so, 4, 3);
          mo.want_dense = 0;
          if (*runs[ri].type != sym_step_spvi)
            mo.own = &oo;
          erun e;
          erun_init (&e, K, 4);
          e.rd.ku = &u;
          for (int j = 0; j < K; j++)
            {
              sym_driver_opts *o = &e.d[j];
              memset (o, 0, sizeof *o);
              o->tf = 4.0;
              o->refine = 1;
              o->h_fixed = runs[ri].h;
              o->tol.rtol = runs[ri].rtol;
              o->tol.atol = &atol_one;
              o->tol.atol_len = 1;
              o->output = out_row;
              o->output_user = &e.recs[j];
              kep_start (e5[j], 2, 0, e.y0 + 4 * j);
            }
          erun_go (&e, *runs[ri].type, &sys, &mo);
          CHECK (e.rc == SYM_SUCCESS, "%s: %s", what, sym_status_name (e.rc));
          /* a batch that failed was made again member by member */
          CHECK (e.eo.nbatch == u.nbatch, "%s: nbatch %ld, batch calls %ld",
                 what, e.eo.nbatch, u.nbatch);
          for (int j = 0; j < K; j++)
            {
              rec alone;
              rec_init (&alone, 4);
              sym_stats st;
              sym_driver_opts o = e.d[j];
              o.output_user = &alone;
              int s1 = sym_integrate (*runs[ri].type, &sys, &mo, &o,
                                      e.y0 + 4 * j, &st);
              if (j == bad)
                {
                  CHECK (s1 < 0 && e.status[j] < 0 && e.st[j].fail_t > 1,
                         "%s: the failing member: %s (alone %s) at t = %g",
                         what, sym_status_name (e.status[j]),
                         sym_status_name (s1), e.st[j].fail_t);
                  if (ri == 0 && batch)
                    printf ("  %s: the failing member ends %s at t = %.4g\n",
                            what, sym_status_name (e.status[j]),
                            e.st[j].t_reached);
                }
              else
                CHECK (e.status[j] == SYM_DONE, "%s: member %d: %s", what, j,
                       sym_status_name (e.status[j]));
              same_run (what, j, e.status[j], &e.recs[j], &e.st[j], s1,
                        &alone, &st);
              rec_free (&alone);
            }
          erun_free (&e);
        }
}

/* ------------------------------------------------------------ test 6 */
/* A round callback that stops (1) or fails (-1) the ensemble at round N:
   every member ends at its next row with SYM_STOP_OUTPUT (SYM_EOUTPUT),
   its rows those of its run alone up to there. */
static void
test_round_stop (void)
{
  static const double e4[] = { 0.1, 0.4, 0.2, 0.5 };
  const int K = 4;
  for (int val = 1; val >= -1; val -= 2)
    for (int direct = 0; direct < 3; direct++)
      for (int batch = 0; batch < 2; batch++)
        {
          char what[96];
          snprintf (what, sizeof what, "round returns %d, %s%s", val,
                    batch ? "batch" : "no batch",
                    direct == 1 ? ", direct sinks"
                    : direct == 2 ? ", 2 at a time" : "");
          kuser u;
          kuser_init (&u, 2);
          sym_system sys = kep_system (&u, batch, 0);
          sym_method_opts mo;
          sym_spvi_opts so;
          ts_opts (&mo, &so, 4, 3);
          mo.want_dense = 0;
          erun e;
          erun_init (&e, K, 4);
          /* 2 at a time: the last two start after the stop and end at
             their first row */
          e.eo.direct_sinks = direct == 1;
          e.eo.max_live = direct == 2 ? 2 : 0;
          e.rd.stop_at = 40;
          e.rd.stop_val = val;
          for (int j = 0; j < K; j++)
            {
              sym_driver_opts *o = &e.d[j];
              memset (o, 0, sizeof *o);
              o->tf = 3.0;
              o->refine = 1;
              o->h_fixed = 0.1;
              o->output = out_row;
              o->output_user = &e.recs[j];
              kep_start (e4[j], 2, 0, e.y0 + 4 * j);
            }
          erun_go (&e, sym_step_spvi, &sys, &mo);
          CHECK (e.rc == SYM_SUCCESS && e.rd.rounds >= 40
                 && e.rd.rounds <= e.eo.nrounds, "%s: %s after %ld rounds "
                 "(%ld of the callback)", what, sym_status_name (e.rc),
                 e.eo.nrounds, e.rd.rounds);
          for (int j = 0; j < K; j++)
            {
              rec alone;
              rec_init (&alone, 4);
              sym_stats st;
              sym_driver_opts o = e.d[j];
              o.output_user = &alone;
              int s1 = sym_integrate (sym_step_spvi, &sys, &mo, &o,
                                      e.y0 + 4 * j, &st);
              const rec *r = &e.recs[j];
              CHECK (s1 == SYM_DONE && e.status[j]
                     == (val > 0 ? SYM_STOP_OUTPUT : SYM_EOUTPUT),
                     "%s: member %d: %s", what, j,
                     sym_status_name (e.status[j]));
              CHECK (r->nrows >= 1 && r->nrows < alone.nrows
                     && memcmp (r->rows.v, alone.rows.v,
                                r->rows.n * sizeof (double)) == 0,
                     "%s: member %d: %ld rows, not the first of its %ld "
                     "alone", what, j, r->nrows, alone.nrows);
              CHECK (e.st[j].cnt.nsteps < st.cnt.nsteps
                     && e.st[j].cnt.nrhs < st.cnt.nrhs,
                     "%s: member %d: %ld steps, alone %ld", what, j,
                     e.st[j].cnt.nsteps, st.cnt.nsteps);
              rec_free (&alone);
            }
          erun_free (&e);
        }
}

/* A member's own sink that stops (1) or fails (-1) at its 5th row: that
   member alone ends so, the others run to tf, each as alone */
static void
test_own_stop (void)
{
  static const double e4[] = { 0.1, 0.4, 0.2, 0.5 };
  const int K = 4, who = 2;
  for (int val = 1; val >= -1; val -= 2)
    for (int batch = 0; batch < 2; batch++)
      {
        char what[96];
        snprintf (what, sizeof what, "member %d's sink returns %d at row 5, "
                  "%s", who, val, batch ? "batch" : "no batch");
        kuser u;
        kuser_init (&u, 2);
        sym_system sys = kep_system (&u, batch, 0);
        sym_method_opts mo;
        sym_spvi_opts so;
        ts_opts (&mo, &so, 4, 3);
        erun e;
        erun_init (&e, K, 4);
        for (int j = 0; j < K; j++)
          {
            sym_driver_opts *o = &e.d[j];
            memset (o, 0, sizeof *o);
            o->tf = 3.0;
            o->refine = 1;
            o->tol.rtol = 1e-8;
            o->tol.atol = &atol_one;
            o->tol.atol_len = 1;
            o->output = out_row;
            o->output_user = &e.recs[j];
            kep_start (e4[j], 2, 0, e.y0 + 4 * j);
          }
        e.recs[who].stop_after = 5;
        e.recs[who].stop_val = val;
        erun_go (&e, sym_step_spvi, &sys, &mo);
        CHECK (e.rc == SYM_SUCCESS, "%s: %s", what, sym_status_name (e.rc));
        for (int j = 0; j < K; j++)
          {
            const int want = j != who ? SYM_DONE
                             : val > 0 ? SYM_STOP_OUTPUT : SYM_EOUTPUT;
            CHECK (e.status[j] == want && (j != who || e.recs[j].nrows == 5),
                   "%s: member %d: %s, %ld rows", what, j,
                   sym_status_name (e.status[j]), e.recs[j].nrows);
            rec alone;
            rec_init (&alone, 4);
            alone.stop_after = e.recs[j].stop_after;
            alone.stop_val = val;
            sym_stats st;
            sym_driver_opts o = e.d[j];
            o.output_user = &alone;
            int s1 = sym_integrate (sym_step_spvi, &sys, &mo, &o,
                                    e.y0 + 4 * j, &st);
            same_run (what, j, e.status[j], &e.recs[j], &e.st[j], s1, &alone,
                      &st);
            rec_free (&alone);
          }
        erun_free (&e);
      }
}

/* A round stop and a member without an output sink: it has no row to
   stop at and runs on to tf (sym.h says so); the other stops */
static void
test_round_stop_no_sink (void)
{
  kuser u;
  kuser_init (&u, 2);
  sym_system sys = kep_system (&u, 1, 0);
  sym_method_opts mo;
  sym_spvi_opts so;
  ts_opts (&mo, &so, 4, 3);
  mo.want_dense = 0;
  erun e;
  erun_init (&e, 2, 4);
  e.rd.stop_at = 10;
  e.rd.stop_val = 1;
  for (int j = 0; j < 2; j++)
    {
      sym_driver_opts *o = &e.d[j];
      memset (o, 0, sizeof *o);
      o->tf = 3.0;
      o->refine = 1;
      o->h_fixed = 0.1;
      o->output = j ? out_row : NULL;
      o->output_user = &e.recs[j];
      kep_start (0.2, 2, 0, e.y0 + 4 * j);
    }
  erun_go (&e, sym_step_spvi, &sys, &mo);
  CHECK (e.status[0] == SYM_DONE && e.st[0].cnt.nsteps == 30
         && e.status[1] == SYM_STOP_OUTPUT && e.st[1].cnt.nsteps < 30,
         "round stop at round 10: member without output sink %s (%ld "
         "steps), member with one %s (%ld steps)",
         sym_status_name (e.status[0]), e.st[0].cnt.nsteps,
         sym_status_name (e.status[1]), e.st[1].cnt.nsteps);
  erun_free (&e);
}

/* ------------------------------------------------------------ test 7 */
/* Allocation number k failing, for every k up to what a whole ensemble
   allocates: either sym_ensemble says SYM_ENOMEM and no member ran, or
   every member ended, as alone (SYM_DONE) or with SYM_ENOMEM; and no
   block is left. */
static void
failing_ensembles (const char *what, const cfg *c, int batch, int max_live)
{
  static const int cols[3] = { 2, 0, 5 };
  const int K = 3;
  mopts m;
  make_mo (c, &m);
  refs R;
  tf_short = 0.6;
  refs_run (&R, c, batch);
  long total = -1, n_enomem = 0, n_member = 0, n_alldone = 0;
  int ok = 1;
  sym_set_allocator (drv_counting_alloc, drv_counting_free);
  for (long k = 0; total < 0 || k <= total; k++)
    {
      kuser u;
      kuser_init (&u, 3);
      sym_system sys = kep_system (&u, batch, c->jac);
      erun e;
      erun_init (&e, K, 6);
      e.eo.round = NULL;
      e.eo.max_live = max_live;
      for (int j = 0; j < K; j++)
        {
          kep_start (ecc[cols[j]], 3, cols[j] + 1, e.y0 + 6 * j);
          kep_dopts (c, cols[j], &e.recs[j], &e.d[j]);
        }
      drv_alloc_count = 0;
      drv_alloc_live = 0;
      drv_alloc_fail_at = k;
      int rc = sym_ensemble (*c->type, &sys, &m.mo, &e.eo);
      if (drv_alloc_live != 0)
        {
          CHECK (0, "%s: %ld blocks left with allocation %ld failing", what,
                 drv_alloc_live, k);
          ok = 0;
        }
      if (k == 0)
        {
          total = drv_alloc_count;
          CHECK (rc == SYM_SUCCESS, "%s: %s", what, sym_status_name (rc));
        }
      if (rc == SYM_ENOMEM)
        {
          n_enomem++;
          for (int j = 0; j < K; j++)
            if (e.recs[j].nrows || e.status[j] != 12345)
              {
                CHECK (0, "%s: allocation %ld failing: SYM_ENOMEM, yet "
                       "member %d ran", what, k, j);
                ok = 0;
              }
        }
      else if (rc != SYM_SUCCESS)
        {
          CHECK (0, "%s: allocation %ld failing: %s", what, k,
                 sym_status_name (rc));
          ok = 0;
        }
      else
        {
          int fails = 0;
          for (int j = 0; j < K; j++)
            if (e.status[j] == SYM_ENOMEM)
              fails++;
            else if (! same_run (what, j, e.status[j], &e.recs[j], &e.st[j],
                                 R.status[cols[j]], &R.r[cols[j]],
                                 &R.st[cols[j]]))
              {
                fprintf (stderr, "  (with allocation %ld failing)\n", k);
                ok = 0;
              }
          n_member += fails > 0;
          n_alldone += k > 0 && fails == 0;
        }
      erun_free (&e);
    }
  sym_set_allocator (big_alloc, big_free);
  drv_alloc_fail_at = 0;
  tf_short = 0;
  CHECK (ok && total > 10 && n_enomem > 0 && n_member > 0,
         "%s: %ld allocations: %ld SYM_ENOMEM, %ld with a member's failure",
         what, total, n_enomem, n_member);
  printf ("  %s: %ld allocations; failing each: %ld times SYM_ENOMEM, %ld "
          "times a member failed, %ld times all members done\n", what, total,
          n_enomem, n_member, n_alldone);
  refs_free (&R);
}

/* ------------------------------------------------------------ test 8 */
static void
test_scale (void)
{
  const int K = 3000, n = 4;
  kuser u;
  kuser_init (&u, 2);
  sym_system sys = kep_system (&u, 1, 0);
  sym_method_opts mo;
  sym_spvi_opts so;
  ts_opts (&mo, &so, 4, 3);
  mo.want_dense = 0;
  erun e;
  erun_init (&e, K, n);
  e.rd.ku = &u;
  for (int j = 0; j < K; j++)
    {
      sym_driver_opts *o = &e.d[j];
      memset (o, 0, sizeof *o);
      o->tf = 5.0;
      o->refine = 1;
      o->h_fixed = 0.1;
      o->output = out_row;
      o->output_user = &e.recs[j];
      kep_start (0.4 * j / (K - 1), 2, 0, e.y0 + n * j);
    }
  erun_go (&e, sym_step_spvi, &sys, &mo);
  CHECK (e.rc == SYM_SUCCESS, "scale: %s", sym_status_name (e.rc));
  long done = 0, maxrhs = 0;
  double herr = 0;
  for (int j = 0; j < K; j++)
    {
      done += e.status[j] == SYM_DONE && e.recs[j].nrows == 51
              && e.st[j].cnt.nsteps == 50;
      if (e.st[j].cnt.nrhs > maxrhs)
        maxrhs = e.st[j].cnt.nrhs;
      if (e.recs[j].nrows > 0)
        herr = fmax (herr, fabs (ts_kep_H (rec_last_row (&e.recs[j]))
                                 - ts_kep_H (e.y0 + n * j)));
      else
        herr = INFINITY;
    }
  CHECK (done == K, "scale: %ld of %d members done in 50 steps", done, K);
  CHECK (herr < 1e-6, "scale: energy error %.3g", herr);
  CHECK (e.eo.nbatch == maxrhs && e.eo.nrounds == maxrhs + 1
         && u.kmax >= K, "scale: %ld batch calls, %ld rounds, most calls %ld, "
         "widest batch %ld", e.eo.nbatch, e.eo.nrounds, maxrhs, u.kmax);
  int same = 0;
  for (int s = 0; s < 20; s++)
    {
      const int j = (int) ((long) s * (K - 1) / 19);
      rec alone;
      rec_init (&alone, n);
      sym_stats st;
      sym_driver_opts o = e.d[j];
      o.output_user = &alone;
      int s1 = sym_integrate (sym_step_spvi, &sys, &mo, &o, e.y0 + n * j,
                              &st);
      same += same_run ("scale", j, e.status[j], &e.recs[j], &e.st[j], s1,
                        &alone, &st);
      rec_free (&alone);
    }
  printf ("  scale: %d members, %ld rounds, %ld batch calls of up to %ld "
          "columns, energy error %.2e, %d of 20 sampled bit-identical\n", K,
          e.eo.nrounds, e.eo.nbatch, u.kmax, herr, same);
  erun_free (&e);
}

/* ------------------------------------------------------------ test 9 */
/* An FPU-beta chain of d = 50 (ends fixed): H = |p|^2/2 + sum V(q_{i+1} -
   q_i), V(x) = x^2/2 + x^4/4 */
#define CHAIN_D 50
static void
chain_col (const double *y, double *dy)
{
  const int d = CHAIN_D;
  double force[CHAIN_D + 1];
  for (int i = 0; i <= d; i++)
    {
      const double a = i > 0 ? y[i - 1] : 0.0, b = i < d ? y[i] : 0.0;
      const double x = b - a;
      force[i] = x + x * x * x;
    }
  for (int i = 0; i < d; i++)
    {
      dy[i] = y[d + i];
      dy[d + i] = force[i + 1] - force[i];
    }
}

static int
chain_rhs (double t, const double *y, double *dy, void *user)
{
  (void) t;
  (void) user;
  probe (CB_RHS);
  chain_col (y, dy);
  return 0;
}

static int
chain_batch (int k, const double *t, const double *y, double *dy,
             void *user)
{
  (void) t;
  (void) user;
  probe (CB_BATCH);
  for (int j = 0; j < k; j++)
    chain_col (y + (size_t) j * 2 * CHAIN_D, dy + (size_t) j * 2 * CHAIN_D);
  return 0;
}

/* running under valgrind (its preloaded library) */
static int
under_valgrind (void)
{
  const char *p = getenv ("LD_PRELOAD");
  return p && strstr (p, "vgpreload") != NULL;
}

/* the members' rows of one chain ensemble (K = 2) on stacks of
   stack_bytes (0: the default), the deepest byte written into hw_most */
static void
chain_ensemble (erun *e, const sym_stepper_type *type, const sym_system *sys,
                const sym_method_opts *mo, size_t stack_bytes)
{
  const int n = 2 * CHAIN_D, K = 2;
  erun_init (e, K, n);
  e->eo.stack_bytes = stack_bytes;
  for (int j = 0; j < K; j++)
    {
      sym_driver_opts *o = &e->d[j];
      memset (o, 0, sizeof *o);
      o->tf = 0.15;
      o->refine = 1;
      o->h_fixed = 0.05;
      o->output = out_row;
      o->output_user = &e->recs[j];
      for (int i = 0; i < CHAIN_D; i++)
        {
          e->y0[j * n + i] = (0.5 + 0.3 * j) * sin (TS_PI * (i + 1)
                                                    / (CHAIN_D + 1));
          e->y0[j * n + CHAIN_D + i] = 0.1 * j * cos (0.3 * i);
        }
    }
  /* a stack's block: its size and the room its top is staggered by */
  hw_size = under_valgrind () ? 0
            : (stack_bytes ? stack_bytes : SYM_ENS_STACK) + SYM_ENS_SKEW;
  hw_most = 0;
  hw_blocks = 0;
  erun_go (e, type, sys, mo);
  hw_size = 0;
}

/* Deep members: SPVI (9,8) on a chain of d = 50 by finite differences,
   its stage systems (auto) or the whole system of 800 unknowns in one
   dense LU, SPVI (4,3)'s whole system (300 unknowns: auto) and SV's
   implicit step.  How deep a member goes is first measured on a stack of
   32 MB (a multithreaded BLAS's LU of 100 unknowns or more writes some
   4-5 MB deep: it shows there without harm), then the run on the
   default stack, if it fits, is held to the runs alone. */
static void
test_deep (void)
{
  const int n = 2 * CHAIN_D, K = 2;
  const size_t big_stack = (size_t) 32 << 20;
  static const struct {
    const char *name;
    int spvi, q, m, system;
  } runs[] = { { "SPVI (9,8), stages", 1, 9, 8, SYM_SYSTEM_AUTO },
               { "SPVI (9,8), whole system", 1, 9, 8, SYM_SYSTEM_FULL },
               { "SPVI (4,3), whole system (auto)", 1, 4, 3, SYM_SYSTEM_AUTO },
               { "SV implicit", 0, 0, 0, 0 } };
  for (size_t ri = 0; ri < sizeof runs / sizeof runs[0]; ri++)
    for (int batch = 0; batch < 2; batch++)
      {
        char what[96];
        snprintf (what, sizeof what, "%s, chain d = 50, %s", runs[ri].name,
                  batch ? "batch" : "no batch");
        sym_system sys;
        memset (&sys, 0, sizeof sys);
        sys.dim = CHAIN_D;
        sys.rhs = chain_rhs;
        sys.rhs_batch = batch ? chain_batch : NULL;
        sym_method_opts mo;
        sym_spvi_opts so;
        sym_onestep_opts oo;
        memset (&oo, 0, sizeof oo);
        ts_opts (&mo, &so, runs[ri].q, runs[ri].m);
        so.system = runs[ri].system;
        mo.want_dense = 0;
        if (! runs[ri].spvi)
          mo.own = &oo;
        const sym_stepper_type *type = runs[ri].spvi ? sym_step_spvi
                                                     : sym_step_sv;
        erun e;
        /* valgrind takes the stack below a member's last frame as
           undefined: the pattern cannot be read back there, and the depth
           is measured under ASan only; the runs on the default stack are
           held to the runs alone all the same */
        const int vg = under_valgrind ();
        if (! vg)
          chain_ensemble (&e, type, &sys, &mo, big_stack);
        const size_t deep = vg ? 0 : hw_most;
        CHECK (vg || (e.rc == SYM_SUCCESS && hw_blocks == K
                      && e.status[0] == SYM_DONE
                      && e.status[1] == SYM_DONE), "%s: %s, %s %s, %ld "
               "stacks measured", what, sym_status_name (e.rc),
               sym_status_name (e.status[0]), sym_status_name (e.status[1]),
               hw_blocks);
        if (! vg)
          erun_free (&e);
        const int fits = vg || (deep > 0 && deep < SYM_ENS_STACK / 4 * 3);
        CHECK (fits, "%s: a member writes %zu bytes deep into its stack, "
               "the default stack has %zu", what, deep,
               (size_t) SYM_ENS_STACK);
        printf ("  %s: deepest stack use %zu bytes", what, deep);
        if (! fits)
          {
            printf (": not run on the default stack\n");
            continue;
          }
        chain_ensemble (&e, type, &sys, &mo, 0);
        printf (" (%zu on the default stack of %zu)\n", hw_most,
                (size_t) SYM_ENS_STACK);
        CHECK (e.rc == SYM_SUCCESS && (vg || hw_blocks == K), "%s: %s, %ld "
               "stacks measured", what, sym_status_name (e.rc), hw_blocks);
        for (int j = 0; j < K; j++)
          {
            rec alone;
            rec_init (&alone, n);
            sym_stats st;
            sym_driver_opts o = e.d[j];
            o.output_user = &alone;
            int s1 = sym_integrate (type, &sys, &mo, &o, e.y0 + n * j, &st);
            CHECK (s1 == SYM_DONE && st.cnt.nfd > 0, "%s: alone %s, %ld "
                   "calls for differences", what, sym_status_name (s1),
                   st.cnt.nfd);
            same_run (what, j, e.status[j], &e.recs[j], &e.st[j], s1, &alone,
                      &st);
            rec_free (&alone);
          }
        erun_free (&e);
      }
}

/* ------------------------------------------------------------ test 10 */
static void
test_bad_input (void)
{
  kuser u;
  kuser_init (&u, 2);
  sym_system sys = kep_system (&u, 1, 0);
  sym_method_opts mo;
  sym_spvi_opts so;
  ts_opts (&mo, &so, 4, 3);
  erun e;
  erun_init (&e, 3, 4);
  for (int j = 0; j < 3; j++)
    {
      sym_driver_opts *o = &e.d[j];
      memset (o, 0, sizeof *o);
      o->tf = 1.0;
      o->refine = 1;
      o->h_fixed = 0.1;
      o->output = out_row;
      o->output_user = &e.recs[j];
      kep_start (0.1 * j, 2, 0, e.y0 + 4 * j);
    }
  sym_set_allocator (drv_counting_alloc, drv_counting_free);
  drv_alloc_count = drv_alloc_live = drv_alloc_fail_at = 0;
  const sym_ensemble_opts good = e.eo;
  for (int c = 0; c < 8; c++)
    {
      sym_ensemble_opts o = good;
      sym_system s = sys;
      const sym_stepper_type *type = sym_step_spvi;
      const char *what[] = { "members 0", "members -1", "y0 NULL",
                             "dopts NULL", "status NULL", "type NULL",
                             "sys NULL", "dim 0" };
      switch (c)
        {
        case 0: o.members = 0; break;
        case 1: o.members = -1; break;
        case 2: o.y0 = NULL; break;
        case 3: o.dopts = NULL; break;
        case 4: o.status = NULL; break;
        case 5: type = NULL; break;
        case 6: break;
        case 7: s.dim = 0; break;
        }
      o.nbatch = o.nrounds = 77;
      int rc = sym_ensemble (type, c == 6 ? NULL : &s, &mo, &o);
      CHECK (rc == SYM_EBADINPUT, "%s: %s", what[c], sym_status_name (rc));
    }
  int rc = sym_ensemble (sym_step_spvi, &sys, &mo, NULL);
  CHECK (rc == SYM_EBADINPUT, "options NULL: %s", sym_status_name (rc));
  CHECK (drv_alloc_count == 0 && u.nbatch == 0 && u.nrhs_calls == 0
         && e.rd.rounds == 0 && e.status[0] == 12345,
         "bad input: %ld allocations, %ld calls, %ld rounds",
         drv_alloc_count, u.nbatch + u.nrhs_calls, e.rd.rounds);
  sym_set_allocator (big_alloc, big_free);
  /* a member's own bad options end it alone, as its run alone; stats
     NULL is allowed */
  e.d[1].tf = e.d[1].t0;
  e.eo.stats = NULL;
  erun_go (&e, sym_step_spvi, &sys, &mo);
  CHECK (e.rc == SYM_SUCCESS && e.status[1] == SYM_EBADINPUT
         && e.recs[1].nrows == 0 && e.status[0] == SYM_DONE
         && e.status[2] == SYM_DONE, "a member's bad options: %s, %s %s %s",
         sym_status_name (e.rc), sym_status_name (e.status[0]),
         sym_status_name (e.status[1]), sym_status_name (e.status[2]));
  for (int j = 0; j < 3; j += 2)
    {
      rec alone;
      rec_init (&alone, 4);
      sym_stats st;
      sym_driver_opts o = e.d[j];
      o.output_user = &alone;
      int s1 = sym_integrate (sym_step_spvi, &sys, &mo, &o, e.y0 + 4 * j,
                              &st);
      CHECK (s1 == e.status[j] && dlog_same (&alone.rows, &e.recs[j].rows),
             "beside a bad member: member %d not as alone", j);
      rec_free (&alone);
    }
  erun_free (&e);
}

/* ------------------------------------------------------------ main */
static double
seconds (void)
{
  return (double) clock () / CLOCKS_PER_SEC;
}

int
main (int argc, char **argv)
{
  main_frame = frame_here ();
  /* the progress so far shows if a member's stack overflows */
  setvbuf (stdout, NULL, _IOLBF, BUFSIZ);
  sym_set_allocator (big_alloc, big_free);
  columns_setup ();
  if (argc == 2 && strcmp (argv[1], "deep") == 0)
    {
      test_deep ();
      sym_set_allocator (NULL, NULL);
      return tu_finish ("test_ensemble deep");
    }
  double t0 = seconds ();
#define PHASE(label, call)                                                \
  do {                                                                    \
    double ts = seconds ();                                               \
    call;                                                                 \
    printf ("  [%s: %.2f s]\n", label, seconds () - ts);                  \
  } while (0)
  PHASE ("1-3 identity, batching, stacks", test_identity ());
  PHASE ("3 direct sinks", test_direct_sinks ());
  PHASE ("1-2 max_live", test_max_live ());
  PHASE ("1-2 recycled blocks", test_recycled ());
  PHASE ("4 events", test_events ());
  PHASE ("5 failures", test_failures ());
  PHASE ("6 round stop", test_round_stop ());
  PHASE ("6 a member's own stop", test_own_stop ());
  PHASE ("6 round stop, no sink", test_round_stop_no_sink ());
  PHASE ("7 allocation failures",
         failing_ensembles ("allocation failures, SPVI fixed, batch",
                            cfg_named ("SPVI (4,3) fixed"), 1, 0));
  PHASE ("7 allocation failures",
         failing_ensembles ("allocation failures, SPVI adaptive, batch, "
                            "2 at a time",
                            cfg_named ("SPVI (4,3) adaptive"), 1, 2));
  PHASE ("7 allocation failures",
         failing_ensembles ("allocation failures, SV adaptive, no batch",
                            cfg_named ("SV implicit adaptive"), 0, 0));
  PHASE ("8 scale", test_scale ());
  PHASE ("9 deep stacks", test_deep ());
  /* section 9 again with BLAS threads (make check runs with one): a
     threaded LU goes megabytes deep, which must happen on the caller's
     stack, not on a member's */
  const char *th = getenv ("OPENBLAS_NUM_THREADS");
  if (argc == 1 && th && strcmp (th, "1") == 0)
    {
      char cmd[4096];
      snprintf (cmd, sizeof cmd, "OPENBLAS_NUM_THREADS=2 '%s' deep", argv[0]);
      CHECK (system (cmd) == 0, "9 deep stacks with two BLAS threads");
    }
  PHASE ("10 bad input", test_bad_input ());
  printf ("  total %.2f s\n", seconds () - t0);
  sym_set_allocator (NULL, NULL);
  return tu_finish ("test_ensemble");
}
