/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* splitting.c -- steps of a composition or splitting method of
   sym_splittings (splittings.c): a method is a row of coefficients.

   Explicit steps (separable H, or second_order: f_q = p).  Every method
   is a sequence of pairs, a kick and then a drift,
     p += b_i h f_p(t + c_i h, q),   q += a_i h f_q(t + e_i h, p),
   c_i = a_1 + ... + a_{i-1} the time of q, e_i = b_1 + ... + b_i that of
   p.  A composition of Stoermer-Verlet steps gamma_1 .. gamma_s is the
   sequence b = (gamma_1/2, (gamma_1 + gamma_2)/2, ..., gamma_s/2), a =
   (gamma_1, ..., gamma_s, 0): its neighbouring half kicks merged.  In
   the position form (own->position) the Verlet steps are drift-kick-drift
   and their half drifts merge: b = (0, gamma_1, ..., gamma_s), a =
   (gamma_1/2, (gamma_1 + gamma_2)/2, ..., gamma_s/2).  f at
   one point gives f_q at the current p and f_p at the current q; a value
   is reused while its argument has not moved, so the last kick's f_p
   (the position form: drift's f_q) serves the next step's first (FSAL)
   and a zero
   coefficient costs nothing.  For separable f a pair then costs two calls (one for the
   drift, one for the kick), with second_order one (the kick).
   Compensated summation (optional) carries the round-off of every update
   of q and p in a second vector, across steps too.

   Implicit steps (a composition for any H): gamma_i h steps of the
   Stoermer-Verlet stepper (sv.c), one state of it for each distinct
   gamma_i, which keeps its Newton matrices for that step size (one
   state for all would build new ones at every change of the size).

   The step has no error estimate: fixed or reversible steps only (the
   driver asks for no estimate there).  Dense output: the
   cubic Hermite interpolant through the step's ends (onestep.c). */
#include "onestep.h"

#include <math.h>
#include <string.h>

/* Each step record also keeps (aux): whether f_p and f_q at its end are
   known, that f_p (d) and f_q (d), and the compensation of its end (n). */
#define FPE_OK(rec) ((rec)->aux[0])
#define FQE_OK(rec) ((rec)->aux[1])
#define FPE(rec) ((rec)->aux + 2)
#define FQE(rec, d) ((rec)->aux + 2 + (d))
#define COMP(rec, d) ((rec)->aux + 2 + 2 * (d))

typedef struct {
  sym_onestep o;          /* first: accept and dense (onestep.h) */
  const sym_splitting *m;
  int npairs;
  int comp;               /* compensated summation */
  int position;           /* drift-kick-drift Verlet steps */
  double *a, *b;          /* npairs: drift and kick coefficients */
  double *ca, *cb;        /* npairs: c_i and e_i (see the top) */
  double *fq;             /* d: f_q at the current p */
  double *yw;             /* n: an implicit stage's result */
  /* implicit: a Stoermer-Verlet state for each distinct gamma (its
     Newton matrices are kept for its step size), ninner of them, and the
     one of each stage */
  void **inner;
  int ninner, *stage_inner;
} sp_state;

static void
sp_free (void *state)
{
  sp_state *s = state;
  if (! s)
    return;
  for (int j = 0; j < s->ninner; j++)
    sym_step_sv->free (s->inner[j]);
  sym_free (s->inner);
  sym_free (s->stage_inner);
  sym_onestep_free (s);
}

/* the Stoermer-Verlet states of the stages of an implicit composition */
static int
sp_inner (sp_state *s, const sym_method_opts *opts)
{
  const int k = s->m->stages;
  const double *g = s->m->coef;
  sym_method_opts io;
  if (opts)
    io = *opts;
  else
    memset (&io, 0, sizeof io);
  static const sym_onestep_opts implicit = { 0, 0, 0, 0, 0, 0, NULL };
  io.own = &implicit;
  io.want_dense = 0;
  s->inner = sym_calloc ((size_t) k, sizeof (void *));
  s->stage_inner = sym_calloc ((size_t) k, sizeof (int));
  if (! s->inner || ! s->stage_inner)
    return SYM_ENOMEM;
  for (int i = 0; i < k; i++)
    {
      int j = 0;
      while (j < i && g[j] != g[i])
        j++;
      if (j < i)
        {
          s->stage_inner[i] = s->stage_inner[j];
          continue;
        }
      int st;
      s->stage_inner[i] = s->ninner;
      if (! (s->inner[s->ninner] = sym_step_sv->alloc (s->o.d, &io, &st)))
        return st;
      s->ninner++;
    }
  return SYM_SUCCESS;
}

/* The pairs of m into s (see the top); position: drift-kick-drift
   Verlet steps */
static void
sp_pairs (sp_state *s, int position)
{
  const sym_splitting *m = s->m;
  const int k = m->stages;
  if (m->kind == SYM_SPLITTING)
    {
      memcpy (s->a, m->coef, (size_t) k * sizeof (double));
      memcpy (s->b, m->coef + k, (size_t) k * sizeof (double));
    }
  else
    {
      const double *g = m->coef;
      for (int i = 0; i <= k; i++)
        {
          const double half = 0.5 * ((i > 0 ? g[i - 1] : 0.0)
                                     + (i < k ? g[i] : 0.0));
          s->b[i] = position ? (i > 0 ? g[i - 1] : 0.0) : half;
          s->a[i] = position ? half : (i < k ? g[i] : 0.0);
        }
    }
  double c = 0.0, e = 0.0;
  for (int i = 0; i < s->npairs; i++)
    {
      s->ca[i] = c;
      e += s->b[i];
      s->cb[i] = e;
      c += s->a[i];
    }
}

static void *
sp_alloc (int dim, const sym_method_opts *opts, int *status)
{
  int dummy;
  if (! status)
    status = &dummy;
  const sym_onestep_opts *own = opts ? opts->own : NULL;
  int nm = 0;
  while (sym_splittings[nm].name)
    nm++;
  const int im = own ? own->method : 0;
  if (im < 0 || im >= nm)
    {
      *status = SYM_EBADINPUT;
      return NULL;
    }
  const sym_splitting *m = &sym_splittings[im];
  const int sep = own && (own->separable || own->second_order);
  /* a splitting needs separable H; the compensated sums are of the
     explicit updates; the position form is of explicit Verlet steps */
  const int position = own && own->position;
  if ((! sep && m->kind == SYM_SPLITTING)
      || (! sep && own && own->compensated)
      || (position && (! sep || m->kind == SYM_SPLITTING)))
    {
      *status = SYM_EBADINPUT;
      return NULL;
    }
  sp_state *s = sym_onestep_new (dim, m->order, sizeof (sp_state), opts,
                                 status);
  if (! s)
    return NULL;
  s->m = m;
  s->comp = own && own->compensated;
  s->position = position;
  s->npairs = m->kind == SYM_SPLITTING ? m->stages : m->stages + 1;
  const int d = dim, n = 2 * d, naux = 2 + 2 * d + n;
  size_t len = sym_recs_len (n, naux) + sym_fcache_len (d, 0)
               + 4 * (size_t) s->npairs + (size_t) d + (size_t) n;
  s->o.block = sym_calloc (len, sizeof (double));
  if (! s->o.block || (! sep && sp_inner (s, opts)))
    {
      sp_free (s);
      *status = SYM_ENOMEM;
      return NULL;
    }
  double *w = s->o.block;
  sym_recs_place (&s->o.r, n, naux, w);
  w += sym_recs_len (n, naux);
  sym_fcache_place (&s->o.fc, d, 0, w);
  w += sym_fcache_len (d, 0);
  s->a = w; w += s->npairs;
  s->b = w; w += s->npairs;
  s->ca = w; w += s->npairs;
  s->cb = w; w += s->npairs;
  s->fq = w; w += d;
  s->yw = w;
  sp_pairs (s, position);
  *status = SYM_SUCCESS;
  return s;
}

/* x += dx, carrying the round-off in c */
static inline void
comp_add (double *x, double *c, double dx)
{
  const double y = dx - *c, t = *x + y;
  *c = (t - *x) - y;
  *x = t;
}

/* the time t + c h, on tend when c is 1 */
static double
sp_time (double t, double h, double tend, double c)
{
  return c == 1.0 ? tend : t + c * h;
}

static int
sp_explicit (sp_state *s, sym_eval *ev, int cont, double *yerr,
             double *ynext)
{
  const int d = s->o.d, n = s->o.n, so = s->o.second_order;
  const int comp = s->comp;
  sym_rec *tr = s->o.r.trial, *cu = s->o.r.cur;
  const double t = tr->t, h = tr->h;
  double *q = tr->y1, *p = tr->y1 + d, *fp = FPE (tr);
  double *c = COMP (tr, d), *fq = so ? p : s->fq;
  int st, fp_ok = 0, fq_ok = so;
  memcpy (tr->y1, tr->y0, (size_t) n * sizeof (double));
  if (comp && cont)
    memcpy (c, COMP (cu, d), (size_t) n * sizeof (double));
  else
    memset (c, 0, (size_t) n * sizeof (double));
  /* f_p at q_k and f_q at p_k: the last step's (FSAL); what the first
     update needs and did not get so, with the other from f(t_k, y_k),
     which the record keeps (not evaluated for a method that begins with
     a drift when f_q is p) */
  if (cont && FPE_OK (cu) != 0.0)
    {
      memcpy (fp, FPE (cu), (size_t) d * sizeof (double));
      fp_ok = 1;
    }
  if (cont && ! so && s->position && FQE_OK (cu) != 0.0)
    {
      memcpy (fq, FQE (cu, d), (size_t) d * sizeof (double));
      fq_ok = 1;
    }
  if (s->b[0] != 0.0 ? ! fp_ok : ! fq_ok)
    {
      if ((st = sym_recs_f0 (&s->o.r, ev)))
        return st;
      memcpy (fp, tr->f0 + d, (size_t) d * sizeof (double));
      if (! so)
        memcpy (fq, tr->f0, (size_t) d * sizeof (double));
      fp_ok = fq_ok = 1;
    }
  for (int k = 0; k < s->npairs; k++)
    {
      const double bh = s->b[k] * h, ah = s->a[k] * h;
      if (bh != 0.0)
        {
          const double tk = sp_time (t, h, tr->tend, s->ca[k]);
          /* (the tangent map's call of f and Df, when it makes one, gives
             the kick's f) */
          if (s->o.tg && (st = sym_tangent_kick (s->o.tg, ev, tk, q, p, bh)))
            return st;
          if (! fp_ok)
            {
              sym_fcache_feed (&s->o.fc, s->o.tg, tk, q, p);
              if ((st = sym_fcache_f (&s->o.fc, ev, tk, q, p)))
                return st;
              memcpy (fp, s->o.fc.fw + d, (size_t) d * sizeof (double));
              fp_ok = 1;
            }
          for (int i = 0; i < d; i++)
            if (comp)
              comp_add (&p[i], &c[d + i], bh * fp[i]);
            else
              p[i] += bh * fp[i];
          fq_ok = so;
        }
      if (ah != 0.0)
        {
          const double td = sp_time (t, h, tr->tend, s->cb[k]);
          if (s->o.tg
              && (st = sym_tangent_drift (s->o.tg, ev, td, q, p, ah, so)))
            return st;
          if (! fq_ok)
            {
              sym_fcache_feed (&s->o.fc, s->o.tg, td, q, p);
              if ((st = sym_fcache_f (&s->o.fc, ev, td, q, p)))
                return st;
              memcpy (fq, s->o.fc.fw, (size_t) d * sizeof (double));
              fq_ok = 1;
            }
          for (int i = 0; i < d; i++)
            if (comp)
              comp_add (&q[i], &c[i], ah * fq[i]);
            else
              q[i] += ah * fq[i];
          fp_ok = 0;
        }
    }
  FPE_OK (tr) = fp_ok;
  FQE_OK (tr) = fq_ok && ! so;
  if (fq_ok && ! so)
    memcpy (FQE (tr, d), fq, (size_t) d * sizeof (double));
  if (fp_ok && fq_ok)
    {
      /* f at the end is known: no call for the dense output */
      memcpy (tr->f1, fq, (size_t) d * sizeof (double));
      memcpy (tr->f1 + d, fp, (size_t) d * sizeof (double));
      tr->have_f1 = 1;
    }
  return sym_recs_finish (&s->o.r, ev, s->o.want_f, yerr, ynext);
}

static int
sp_implicit (sp_state *s, sym_eval *ev, double *yerr, double *ynext)
{
  const int n = s->o.n;
  sym_rec *tr = s->o.r.trial;
  const sym_stepper_type *sv = sym_step_sv;
  const double *g = s->m->coef;
  double ti = tr->t;
  int st;
  FPE_OK (tr) = 0;
  FQE_OK (tr) = 0;
  memcpy (tr->y1, tr->y0, (size_t) n * sizeof (double));
  for (int k = 0; k < s->m->stages; k++)
    {
      const double hk = g[k] * tr->h;
      const double te = k == s->m->stages - 1 ? tr->tend : ti + hk;
      void *in = s->inner[s->stage_inner[k]];
      if ((st = sv->step (in, ev, ti, hk, te, tr->y1, s->yw, NULL)))
        return st;
      sv->accept (in);
      memcpy (tr->y1, s->yw, (size_t) n * sizeof (double));
      ti = te;
    }
  return sym_recs_finish (&s->o.r, ev, s->o.want_f, yerr, ynext);
}

static int
sp_step (void *state, sym_eval *ev, double t, double h, double tend,
         const double *y, double *ynext, double *yerr)
{
  sp_state *s = state;
  int st, cont;
  /* no error estimate: fixed or reversible steps only */
  if (yerr)
    return SYM_EBADINPUT;
  if ((st = sym_onestep_begin (&s->o, ev, t, h, tend, y, ynext, &cont)))
    return st;
  return s->inner ? sp_implicit (s, ev, yerr, ynext)
                  : sp_explicit (s, ev, cont, yerr, ynext);
}

static int
sp_set_tolerances (void *state, const sym_tolerances *tol)
{
  (void) state;
  (void) tol;
  return SYM_EBADINPUT;
}

static const sym_stepper_type sp_type =
  SYM_ONESTEP_TYPE ("splitting", sp_alloc, sp_set_tolerances, sp_step,
                    sp_free);

const sym_stepper_type *const sym_step_splitting = &sp_type;
