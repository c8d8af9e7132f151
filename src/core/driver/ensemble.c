/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* ensemble.c -- many runs of one system in rounds (sym_ensemble).

   Each member is a plain sym_integrate on a stack of its own
   (coroutine.c).  Its system and driver options are copies whose
   callbacks post a request and yield: an evaluation of f waits for the
   round's batch call, any other callback (Df, events, the sinks, the
   step density) is made at once from the caller's stack.  So the steppers
   and the driver are those of a single run, untouched, and a member
   computes what it would alone: the batch gives each of its states the
   value the user's function gives that column. */
#include "driver.h"
#include "coroutine.h"
#include "../calls.h"

#include <string.h>

enum { REQ_NONE = 0, REQ_F, REQ_CALL };

typedef struct member member;
struct member {
  struct ens *e;
  int idx;
  int slot;               /* its stack's, and its chunk's */
  int carving;            /* its start's blocks come from its chunk */
  sym_co co;
  int done;
  sym_system sys;
  sym_driver_opts d;
  /* the request: k states (times t, the columns of y) into dy, or a call
     made by exec from the slots below; its status back in ret */
  int req, ret;
  int k, single;          /* single: one state by rhs, else rhs_batch */
  double t1;
  const double *t, *y;
  double *dy;
  int (*exec) (member *m);
  double ta, tb;
  const double *ya;
  double *oa, *ob;
  sym_csc *csc;
  int *ia, *ib;
  int na;
};

typedef struct ens {
  const sym_stepper_type *type;
  const sym_system *sys;
  const sym_method_opts *mo;
  sym_ensemble_opts *o;
  int n;
  int stop;               /* what the members' outputs return from now */
  member *m;
  /* the blocks a member allocates at its start (its run's arrays and
     stepper), the same for all: counted at the first member's, then
     carved from a chunk of that size a stack slot, which the slot's
     next member takes over instead of allocating them anew */
  int sized;
  size_t chunk;
  char *chunks;
} ens;

/* ------------------------------------------------------------ carving */
static void
carve_start (member *m)
{
  ens *e = m->e;
  if (e->chunks)
    sym_carve_from (e->chunks + (size_t) m->slot * e->chunk, e->chunk);
  else if (! e->sized)
    sym_carve_from (NULL, 0);
  else
    return;
  m->carving = 1;
}

/* at the member's first call out (its start is over), or its end */
static void
carve_stop (member *m)
{
  if (! m->carving)
    return;
  const size_t asked = sym_carve_end ();
  m->carving = 0;
  if (! m->e->sized)
    {
      m->e->sized = 1;
      m->e->chunk = asked;
    }
}

/* the chunks of ns slots, once the first member has been counted: none
   when there is no memory for them (each member allocates its own) */
static void
make_chunks (ens *e, int ns)
{
  if (e->chunks || ! e->sized || ! e->chunk
      || e->chunk > ((size_t) -1 / 2) / (size_t) ns)
    return;
  e->chunks = sym_malloc (e->chunk * (size_t) ns);
  if (e->chunks)
    sym_carve_region (e->chunks, e->chunk * (size_t) ns);
  else
    e->chunk = 0;
}

/* ------------------------------------------------------------ requests */
static int
post (member *m, int req)
{
  carve_stop (m);
  m->req = req;
  sym_co_yield (&m->co);
  return m->ret;
}

static int
tr_rhs (double t, const double *y, double *dy, void *user)
{
  member *m = user;
  m->k = 1;
  m->single = 1;
  m->t1 = t;
  m->t = &m->t1;
  m->y = y;
  m->dy = dy;
  return post (m, REQ_F);
}

static int
tr_rhs_batch (int k, const double *t, const double *y, double *dy,
              void *user)
{
  member *m = user;
  m->k = k;
  m->single = 0;
  m->t = t;
  m->y = y;
  m->dy = dy;
  return post (m, REQ_F);
}

static int
call (member *m, int (*exec) (member *))
{
  m->exec = exec;
  return post (m, REQ_CALL);
}

static int
ex_jac (member *m)
{
  return m->e->sys->jac (m->ta, m->ya, m->oa, m->e->sys->user);
}

static int
tr_jac (double t, const double *y, double *df, void *user)
{
  member *m = user;
  m->ta = t;
  m->ya = y;
  m->oa = df;
  return call (m, ex_jac);
}

static int
ex_rhs_jac (member *m)
{
  return m->e->sys->rhs_jac (m->ta, m->ya, m->oa, m->ob, m->e->sys->user);
}

static int
tr_rhs_jac (double t, const double *y, double *dy, double *df, void *user)
{
  member *m = user;
  m->ta = t;
  m->ya = y;
  m->oa = dy;
  m->ob = df;
  return call (m, ex_rhs_jac);
}

static int
ex_jac_csc (member *m)
{
  return m->e->sys->jac_csc (m->ta, m->ya, m->csc, m->e->sys->user);
}

static int
tr_jac_csc (double t, const double *y, sym_csc *df, void *user)
{
  member *m = user;
  m->ta = t;
  m->ya = y;
  m->csc = df;
  return call (m, ex_jac_csc);
}

static int
ex_rhs_jac_csc (member *m)
{
  return m->e->sys->rhs_jac_csc (m->ta, m->ya, m->oa, m->csc,
                                 m->e->sys->user);
}

static int
tr_rhs_jac_csc (double t, const double *y, double *dy, sym_csc *df,
                void *user)
{
  member *m = user;
  m->ta = t;
  m->ya = y;
  m->oa = dy;
  m->csc = df;
  return call (m, ex_rhs_jac_csc);
}

static int
ex_events (member *m)
{
  const sym_driver_opts *d = &m->e->o->dopts[m->idx];
  return d->events (m->ta, m->ya, m->oa, m->ia, m->ib, d->event_user);
}

static int
tr_events (double t, const double *y, double *value, int *isterminal,
           int *direction, void *user)
{
  member *m = user;
  m->ta = t;
  m->ya = y;
  m->oa = value;
  m->ia = isterminal;
  m->ib = direction;
  return call (m, ex_events);
}

static int
ex_event_out (member *m)
{
  const sym_driver_opts *d = &m->e->o->dopts[m->idx];
  return d->event_out (m->ta, m->ya, m->na, d->event_user);
}

static int
tr_event_out (double te, const double *ye, int ie, void *user)
{
  member *m = user;
  carve_stop (m);
  m->ta = te;
  m->ya = ye;
  m->na = ie;
  return m->e->o->direct_sinks ? ex_event_out (m)
         : call (m, ex_event_out);
}

static int
ex_output (member *m)
{
  const sym_driver_opts *d = &m->e->o->dopts[m->idx];
  int st = d->output (m->ta, m->ya, d->output_user);
  /* a stop of the whole ensemble: at each member's next row */
  return st == 0 && m->e->stop ? m->e->stop : st;
}

static int
tr_output (double t, const double *y, void *user)
{
  member *m = user;
  carve_stop (m);
  m->ta = t;
  m->ya = y;
  return m->e->o->direct_sinks ? ex_output (m) : call (m, ex_output);
}

static int
ex_dense_out (member *m)
{
  const sym_driver_opts *d = &m->e->o->dopts[m->idx];
  return d->dense_out (m->ta, m->tb, m->na, m->ya, d->dense_user);
}

static int
tr_dense_out (double t, double tnew, int k, const double *y, void *user)
{
  member *m = user;
  carve_stop (m);
  m->ta = t;
  m->tb = tnew;
  m->na = k;
  m->ya = y;
  return m->e->o->direct_sinks ? ex_dense_out (m)
         : call (m, ex_dense_out);
}

static int
ex_density (member *m)
{
  const sym_driver_opts *d = &m->e->o->dopts[m->idx];
  return d->density (m->ta, m->ya, m->oa, d->density_user);
}

static int
tr_density (double t, const double *y, double *rho, void *user)
{
  member *m = user;
  m->ta = t;
  m->ya = y;
  m->oa = rho;
  return call (m, ex_density);
}

/* ------------------------------------------------------------ members */
static void
member_run (void *arg)
{
  member *m = arg;
  ens *e = m->e;
  carve_start (m);
  e->o->status[m->idx]
    = sym_integrate (e->type, &m->sys, e->mo, &m->d,
                     e->o->y0 + (size_t) m->idx * e->n,
                     e->o->stats ? &e->o->stats[m->idx] : NULL);
  carve_stop (m);
}

/* the member's copies of the system and its options: every callback
   there is, as a request */
static void
member_setup (ens *e, member *m, int idx)
{
  const sym_system *s = e->sys;
  const sym_driver_opts *d = &e->o->dopts[idx];
  m->e = e;
  m->idx = idx;
  m->sys = *s;
  m->sys.user = m;
  m->sys.rhs = tr_rhs;
  m->sys.rhs_batch = s->rhs_batch ? tr_rhs_batch : NULL;
  m->sys.jac = s->jac ? tr_jac : NULL;
  m->sys.rhs_jac = s->rhs_jac ? tr_rhs_jac : NULL;
  m->sys.jac_csc = s->jac_csc ? tr_jac_csc : NULL;
  m->sys.rhs_jac_csc = s->rhs_jac_csc ? tr_rhs_jac_csc : NULL;
  m->d = *d;
  m->d.events = d->events ? tr_events : NULL;
  m->d.event_user = m;
  m->d.event_out = d->event_out ? tr_event_out : NULL;
  m->d.output = d->output ? tr_output : NULL;
  m->d.output_user = m;
  m->d.dense_out = d->dense_out ? tr_dense_out : NULL;
  m->d.dense_user = m;
  m->d.density = d->density ? tr_density : NULL;
  m->d.density_user = m;
}

/* run m on until it waits for f or ends, making its other calls */
static void
advance (member *m)
{
  m->req = REQ_NONE;
  sym_co_resume (&m->co);
  while (! m->co.finished && m->req == REQ_CALL)
    {
      m->ret = m->exec (m);
      m->req = REQ_NONE;
      sym_co_resume (&m->co);
    }
  if (m->co.finished)
    m->done = 1;
}

/* ------------------------------------------------------------ the round's f */
typedef struct {
  double *t, *y, *dy;
  size_t cap;
} gather;

static int
gather_room (gather *g, int n, size_t k)
{
  if (k <= g->cap)
    return 0;
  size_t cap = k > 2 * g->cap ? k : 2 * g->cap;
  sym_free (g->t);
  sym_free (g->y);
  sym_free (g->dy);
  g->t = sym_malloc (cap * sizeof (double));
  g->y = sym_malloc (cap * n * sizeof (double));
  g->dy = sym_malloc (cap * n * sizeof (double));
  g->cap = g->t && g->y && g->dy ? cap : 0;
  return g->cap ? 0 : SYM_ENOMEM;
}

/* m's states as its own run would evaluate them */
static int
eval_alone (const sym_system *s, member *m)
{
  if (! m->single)
    return s->rhs_batch (m->k, m->t, m->y, m->dy, s->user);
  return s->rhs (m->t[0], m->y, m->dy, s->user);
}

/* f for every member waiting: with a batch callback, one call of all
   their states (alone, when the batch fails or has no memory); else each
   member's as its run would */
static void
evaluate (ens *e, gather *g, int lo, int hi)
{
  const sym_system *s = e->sys;
  const int n = e->n;
  const size_t nb = (size_t) n * sizeof (double);
  size_t k = 0;
  for (int i = lo; i < hi; i++)
    if (! e->m[i].done && e->m[i].req == REQ_F)
      k += (size_t) e->m[i].k;
  int st = SYM_ENOMEM;
  /* a single state goes as two equal columns: a user's function may
     compute a lone column otherwise than a column among others (a power
     of a scalar by pow, of an array by products), and a member's values
     must not depend on how many share its batch */
  if (k > 0 && s->rhs_batch && ! gather_room (g, n, k + (k == 1)))
    {
      size_t c = 0;
      for (int i = lo; i < hi; i++)
        {
          member *m = &e->m[i];
          if (m->done || m->req != REQ_F)
            continue;
          memcpy (g->t + c, m->t, (size_t) m->k * sizeof (double));
          memcpy (g->y + c * n, m->y, (size_t) m->k * nb);
          c += (size_t) m->k;
        }
      if (k == 1)
        {
          g->t[1] = g->t[0];
          memcpy (g->y + n, g->y, nb);
        }
      st = s->rhs_batch ((int) (k + (k == 1)), g->t, g->y, g->dy, s->user);
      e->o->nbatch++;
    }
  size_t c = 0;
  for (int i = lo; i < hi; i++)
    {
      member *m = &e->m[i];
      if (m->done || m->req != REQ_F)
        continue;
      if (st == SYM_SUCCESS)
        {
          memcpy (m->dy, g->dy + c * n, (size_t) m->k * nb);
          m->ret = SYM_SUCCESS;
        }
      else
        {
          m->ret = eval_alone (s, m);
          e->o->nbatch += ! m->single;
        }
      c += (size_t) m->k;
    }
}

/* ------------------------------------------------------------ the rounds */
int
sym_ensemble (const sym_stepper_type *type, const sym_system *sys,
              const sym_method_opts *mopts, sym_ensemble_opts *o)
{
  if (! type || ! sys || ! o || o->members < 1 || ! o->y0 || ! o->dopts
      || ! o->status || sys->dim < 1)
    return SYM_EBADINPUT;
  o->nbatch = 0;
  o->nrounds = 0;
  const int K = o->members;
  const size_t ss = o->stack_bytes ? o->stack_bytes : SYM_ENS_STACK;
  ens e;
  memset (&e, 0, sizeof e);
  e.type = type;
  e.sys = sys;
  e.mo = mopts;
  e.o = o;
  e.n = 2 * sys->dim;
  e.m = sym_calloc ((size_t) K, sizeof (member));
  /* at most max_live members hold a stack (and a stepper) at once: a
     member's stack goes to the next one when it ends */
  const int ns = o->max_live > 0 && o->max_live < K ? o->max_live : K;
  char **stacks = sym_calloc ((size_t) ns, sizeof (char *));
  int *free_stack = sym_malloc ((size_t) ns * sizeof (int));
  int *stack_of = sym_malloc ((size_t) K * sizeof (int));
  int st = e.m && stacks && free_stack && stack_of ? SYM_SUCCESS
           : SYM_ENOMEM;
  /* the stacks' tops staggered, each block SYM_ENS_SKEW larger */
  const size_t skew_max = SYM_ENS_SKEW;
  for (int i = 0; i < ns && ! st; i++)
    {
      stacks[i] = sym_malloc (ss + skew_max);
      free_stack[i] = ns - 1 - i;
      if (! stacks[i])
        st = SYM_ENOMEM;
    }
  int nfree = st ? 0 : ns;
  gather g = { NULL, NULL, NULL, 0 };
  /* members lo.. next-1 have started; those before lo have all ended */
  int lo = 0, next = 0, live = 0;
  while (! st && (live > 0 || next < K))
    {
      for (; next < K && nfree > 0; next++, live++)
        {
          const int j = free_stack[--nfree];
          const size_t skew = (size_t) (next % 61) * 320;
          member_setup (&e, &e.m[next], next);
          stack_of[next] = j;
          e.m[next].slot = j;
          if (sym_co_init (&e.m[next].co, stacks[j], ss + skew_max - skew,
                           member_run, &e.m[next]))
            {
              /* no context for it: it ends before its start */
              o->status[next] = SYM_ENOMEM;
              e.m[next].done = 1;
              sym_co_release (&e.m[next].co);
              free_stack[nfree++] = j;
              live--;
            }
        }
      for (int i = lo; i < next; i++)
        {
          member *m = &e.m[i];
          if (m->done)
            continue;
          advance (m);
          make_chunks (&e, ns);
          if (m->done)
            {
              live--;
              sym_co_release (&m->co);
              free_stack[nfree++] = stack_of[i];
            }
        }
      while (lo < next && e.m[lo].done)
        lo++;
      o->nrounds++;
      if (o->round && ! e.stop)
        {
          int r = o->round (o->round_user);
          if (r)
            e.stop = r > 0 ? 1 : r;
        }
      if (live > 0)
        evaluate (&e, &g, lo, next);
    }
  sym_carve_region (NULL, 0);
  sym_free (e.chunks);
  for (int i = 0; stacks && i < ns; i++)
    sym_free (stacks[i]);
  sym_free (stacks);
  sym_free (free_stack);
  sym_free (stack_of);
  sym_free (e.m);
  sym_free (g.t);
  sym_free (g.y);
  sym_free (g.dy);
  return st;
}
