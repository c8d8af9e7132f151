/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* rattle.c -- RATTLE: Stoermer-Verlet on the manifold of holonomic
   constraints g(q) = 0 (m of them) and of their velocity constraints
   G(q) f_q = 0, G = dg/dq, for H = T(p) + V(q) (or SecondOrder, f_q = p).
   One step from (t_k, q_k, p_k) by h:

     p_{k+1/2} = p_k + (h/2) (f_p(q_k) - G(q_k)' lambda)
     q_{k+1}   = q_k + h f_q(p_{k+1/2}),       g(q_{k+1}) = 0
     p_{k+1}   = p_{k+1/2} + (h/2) (f_p(q_{k+1}) - G(q_{k+1})' mu),
                                   G(q_{k+1}) f_q(p_{k+1}) = 0

   lambda by simplified Newton on g(q_{k+1}(lambda)) = 0 with the matrix
   (h^2/2) G(q^0) A G(q_k)' (q^0 the first iterate, A = d f_q / d p: I
   with second_order, else forward differences of f_q along the columns
   of G(q_k)', m calls); mu by one linear solve with second_order, else by
   simplified Newton in the same way.  A solve stops when its correction,
   or the next one as the rate of the last two predicts it, is below
   max(1e-2 NewtonTol, 16 eps) of q's (p's) size, or it stagnates at
   round-off; one that does not is a failure (SYM_NEWTON_FAIL), never a
   step.  Symmetric and symplectic on the manifold, order 2.

   Fixed steps only (no error estimate).  Dense output: the cubic
   Hermite interpolant with the constrained derivatives at the ends
   (f_p - G' lambda at the start, f_p - G' mu at the end).  G comes from
   the user or from central differences of g (step cbrt(eps) times q's
   size). */
#include "onestep.h"

#include <float.h>
#include <math.h>
#include <string.h>

/* a record's aux: the derivatives at its ends (n each), mu (m), G at its
   end (m*d) */
#define D0(r) ((r)->aux)
#define D1(r, n) ((r)->aux + (n))
#define MU(r, n) ((r)->aux + 2 * (n))
#define GE(r, n, m) ((r)->aux + 2 * (n) + (m))

typedef struct {
  sym_onestep o;           /* first: accept (onestep.h) */
  const sym_constraints *cs;
  int m, maxit;
  double tol;
  sym_lu lu;               /* m-by-m */
  /* work */
  double *g, *G0, *W, *lam, *dl, *ph, *fp1, *fq1, *dv, *yw, *fw, *cw;
} rattle_state;

/* g (and G when not NULL) at q; central differences for G when the
   user gives none; work: d + 2m */
static int
con_eval (const sym_constraints *cs, int d, const double *q, double *g,
          double *G, double *work)
{
  const int m = cs->m;
  int st = cs->con (q, g, cs->has_G ? G : NULL, cs->user);
  if (st)
    return st;
  for (int k = 0; k < m; k++)
    if (! isfinite (g[k]))
      return SYM_NONFINITE;
  if (! G)
    return SYM_SUCCESS;
  if (! cs->has_G)
    {
      double *qw = work, *gp = work + d, *gm = work + d + m;
      double qs = sym_norm_inf (d, q);
      if (qs == 0.0)
        qs = 1.0;
      memcpy (qw, q, (size_t) d * sizeof (double));
      const double c = cbrt (DBL_EPSILON);
      for (int j = 0; j < d; j++)
        {
          const double hj = c * fmax (fabs (q[j]), qs);
          volatile double up = q[j] + hj, dn = q[j] - hj;
          qw[j] = up;
          if ((st = cs->con (qw, gp, NULL, cs->user)))
            return st;
          qw[j] = dn;
          if ((st = cs->con (qw, gm, NULL, cs->user)))
            return st;
          qw[j] = q[j];
          for (int k = 0; k < m; k++)
            G[k + (size_t) j * m] = (gp[k] - gm[k]) / (up - dn);
        }
    }
  for (size_t k = 0; k < (size_t) m * d; k++)
    if (! isfinite (G[k]))
      return SYM_NONFINITE;
  return SYM_SUCCESS;
}

/* v (d) = G' x (G m-by-d, x m) times c, added to v */
static void
gt_axpy (int m, int d, const double *G, double c, const double *x,
         double *v)
{
  for (int i = 0; i < d; i++)
    {
      double sum = 0.0;
      for (int k = 0; k < m; k++)
        sum += G[k + (size_t) i * m] * x[k];
      v[i] += c * sum;
    }
}

/* r (m) = G v */
static void
g_mv (int m, int d, const double *G, const double *v, double *r)
{
  for (int k = 0; k < m; k++)
    r[k] = 0.0;
  for (int i = 0; i < d; i++)
    for (int k = 0; k < m; k++)
      r[k] += G[k + (size_t) i * m] * v[i];
}

/* f_q at (t, [q; p]) into fq (d); yw, fw: n of work */
static int
eval_fq (sym_eval *ev, double t, const double *q, const double *p,
         double *fq, double *yw, double *fw)
{
  const int d = ev->dim;
  memcpy (yw, q, (size_t) d * sizeof (double));
  memcpy (yw + d, p, (size_t) d * sizeof (double));
  int st = sym_rhs (ev, t, yw, fw);
  if (st == SYM_SUCCESS)
    memcpy (fq, fw, (size_t) d * sizeof (double));
  return st;
}

/* W (d-by-m) = A G', A = d f_q / d p at (t, q, p): G' itself with
   second_order, else forward differences of f_q along G's rows (fq: f_q
   at p; pw: d of work, yw and fw n) */
static int
dirs (sym_eval *ev, int so, int m, double t, const double *q,
      const double *p, const double *fq, const double *G, double *W,
      double *pw, double *yw, double *fw)
{
  const int d = ev->dim;
  if (so)
    {
      for (int j = 0; j < m; j++)
        for (int i = 0; i < d; i++)
          W[i + (size_t) j * d] = G[j + (size_t) i * m];
      return SYM_SUCCESS;
    }
  double ps = sym_norm_inf (d, p);
  if (ps == 0.0)
    ps = 1.0;
  for (int j = 0; j < m; j++)
    {
      double un = 0.0;
      for (int i = 0; i < d; i++)
        un = fmax (un, fabs (G[j + (size_t) i * m]));
      if (un == 0.0)
        return SYM_SINGULAR;
      const double e = sqrt (DBL_EPSILON) * ps / un;
      for (int i = 0; i < d; i++)
        pw[i] = p[i] + e * G[j + (size_t) i * m];
      double *wj = W + (size_t) j * d;
      int st = eval_fq (ev, t, q, pw, wj, yw, fw);
      ev->st.cnt.nfd++;
      if (st)
        return st;
      for (int i = 0; i < d; i++)
        wj[i] = (wj[i] - fq[i]) / e;
    }
  return SYM_SUCCESS;
}

/* lu = G W (m-by-m), factored */
static int
factor_gw (sym_lu *lu, int m, int d, const double *G, const double *W,
           sym_counters *cnt)
{
  for (int b = 0; b < m; b++)
    g_mv (m, d, G, W + (size_t) b * d, lu->a + (size_t) b * m);
  return sym_lu_factor (lu, cnt);
}

/* a correction of size size (prev: the last one's) ends the solve: below
   tol of the scale, or the next one, by the rate theta = size / prev the
   two show, theta / (1 - theta) size below it, or no longer shrinking at
   round-off */
static int
converged (double size, double prev, double tol, double scale)
{
  const double theta = size / prev;
  return size <= tol * scale
         || (isfinite (prev) && theta < 0.5
             && theta / (1.0 - theta) * size <= tol * scale)
         || (size <= 1e3 * DBL_EPSILON * scale && size > 0.5 * prev);
}

static void rattle_free (void *state);

static void *
rattle_alloc (int dim, const sym_method_opts *opts, int *status)
{
  int dummy;
  if (! status)
    status = &dummy;
  const sym_onestep_opts *own = opts ? opts->own : NULL;
  const sym_constraints *cs = opts ? opts->constraints : NULL;
  if (! own || ! (own->separable || own->second_order) || ! cs || ! cs->con
      || cs->m < 1 || cs->m >= dim)
    {
      *status = SYM_EBADINPUT;
      return NULL;
    }
  const int d = dim, n = 2 * d, m = cs->m;
  const size_t naux = 2 * (size_t) n + m + (size_t) m * d;
  /* g, lam, dl (m); G0, W (m d); ph, fp1, fq1, dv (d); yw, fw (n); cw
     (d + 2m) */
  const size_t nown = 5 * (size_t) m + 2 * (size_t) m * d + 5 * (size_t) d
                      + 2 * (size_t) n;
  double *w;
  rattle_state *s = sym_onestep_alloc (dim, 2, sizeof (rattle_state), 0,
                                       (int) naux, nown, opts, status, &w);
  if (! s)
    return NULL;
  s->cs = cs;
  s->m = m;
  s->maxit = opts->max_newton > 0 ? opts->max_newton : SYM_NEWTON_MAXIT;
  s->tol = fmax (1e-2 * (opts->newton_tol > 0 ? opts->newton_tol
                         : SYM_NEWTON_TOL), 16 * DBL_EPSILON);
  s->g = w; w += m;
  s->lam = w; w += m;
  s->dl = w; w += m;
  s->G0 = w; w += (size_t) m * d;
  s->W = w; w += (size_t) m * d;
  s->ph = w; w += d;
  s->fp1 = w; w += d;
  s->fq1 = w; w += d;
  s->dv = w; w += d;
  s->yw = w; w += n;
  s->fw = w; w += n;
  s->cw = w;
  if (sym_lu_init (&s->lu, m))
    {
      rattle_free (s);
      *status = SYM_ENOMEM;
      return NULL;
    }
  return s;
}

static void
rattle_free (void *state)
{
  rattle_state *s = state;
  if (! s)
    return;
  sym_lu_free (&s->lu);
  sym_onestep_free (s);
}

/* lambda: q1 on g = 0 (see the top) */
static int
solve_lambda (rattle_state *s, sym_eval *ev, const sym_trial *v,
              const double *fp0, double *G1)
{
  const int d = v->d, m = s->m, so = s->o.second_order;
  const double t = v->tr->t, h = v->tr->h, hh = 0.5 * h, c = h * hh;
  double *ph = s->ph, *lam = s->lam, *dl = s->dl, *dq = s->dv;
  sym_counters *cnt = &ev->st.cnt;
  int st;
  for (int i = 0; i < d; i++)
    ph[i] = v->p0[i] + hh * fp0[i];
  gt_axpy (m, d, s->G0, -hh, lam, ph);
  /* q1 = q0 + h f_q(ph), the f_q at ph kept in fq1 */
  if (so)
    memcpy (s->fq1, ph, (size_t) d * sizeof (double));
  else if ((st = eval_fq (ev, t + hh, v->q0, ph, s->fq1, s->yw, s->fw)))
    return st;
  for (int i = 0; i < d; i++)
    v->q1[i] = v->q0[i] + h * s->fq1[i];
  if ((st = dirs (ev, so, m, t + hh, v->q0, ph, s->fq1, s->G0, s->W,
                  dq, s->yw, s->fw)))
    return st;
  double qs = sym_norm_inf (d, v->q0), prev = INFINITY;
  if (qs == 0.0)
    qs = 1.0;
  for (int it = 0; it < s->maxit; it++)
    {
      cnt->nnewton++;
      if ((st = con_eval (s->cs, d, v->q1, s->g, it == 0 ? G1 : NULL,
                          s->cw)))
        return st;
      if (it == 0 && (st = factor_gw (&s->lu, m, d, G1, s->W, cnt)))
        return st;
      for (int k = 0; k < m; k++)
        dl[k] = s->g[k] / c;
      sym_lu_solve (&s->lu, dl, cnt);
      for (int i = 0; i < d; i++)
        dq[i] = 0.0;
      for (int k = 0; k < m; k++)
        {
          lam[k] += dl[k];
          for (int i = 0; i < d; i++)
            dq[i] -= c * s->W[i + (size_t) k * d] * dl[k];
        }
      gt_axpy (m, d, s->G0, -hh, dl, ph);
      const double size = sym_norm_inf (d, dq);
      if (! isfinite (size))
        break;
      if (converged (size, prev, s->tol, qs))
        {
          /* the last correction is linear in it (exact with
             second_order) */
          for (int i = 0; i < d; i++)
            v->q1[i] = so ? v->q0[i] + h * ph[i] : v->q1[i] + dq[i];
          return SYM_SUCCESS;
        }
      prev = size;
      if (so)
        memcpy (s->fq1, ph, (size_t) d * sizeof (double));
      else if ((st = eval_fq (ev, t + hh, v->q0, ph, s->fq1, s->yw,
                              s->fw)))
        return st;
      for (int i = 0; i < d; i++)
        v->q1[i] = v->q0[i] + h * s->fq1[i];
    }
  cnt->nnewton_fail++;
  return SYM_NEWTON_FAIL;
}

/* mu: p1 on G1 f_q = 0, f_q(p1) into fq1 */
static int
solve_mu (rattle_state *s, sym_eval *ev, const sym_trial *v,
          const double *G1, double *mu)
{
  const int d = v->d, m = s->m, so = s->o.second_order;
  const double tend = v->tr->tend, hh = 0.5 * v->tr->h;
  double *p1 = v->p1, *dl = s->dl, *dp = s->dv;
  sym_counters *cnt = &ev->st.cnt;
  int st;
  for (int i = 0; i < d; i++)
    p1[i] = s->ph[i] + hh * s->fp1[i];
  if (so)
    {
      /* linear: (h/2) G1 G1' mu = G1 (ph + (h/2) f_p(q1)) */
      for (int j = 0; j < m; j++)
        for (int i = 0; i < d; i++)
          s->W[i + (size_t) j * d] = G1[j + (size_t) i * m];
      if ((st = factor_gw (&s->lu, m, d, G1, s->W, cnt)))
        return st;
      g_mv (m, d, G1, p1, mu);
      for (int k = 0; k < m; k++)
        mu[k] /= hh;
      sym_lu_solve (&s->lu, mu, cnt);
      gt_axpy (m, d, G1, -hh, mu, p1);
      memcpy (s->fq1, p1, (size_t) d * sizeof (double));
      return SYM_SUCCESS;
    }
  memcpy (mu, s->lam, (size_t) m * sizeof (double));
  gt_axpy (m, d, G1, -hh, mu, p1);
  if ((st = eval_fq (ev, tend, v->q1, p1, s->fq1, s->yw, s->fw)))
    return st;
  if ((st = dirs (ev, 0, m, tend, v->q1, p1, s->fq1, G1, s->W, dp, s->yw,
                  s->fw))
      || (st = factor_gw (&s->lu, m, d, G1, s->W, cnt)))
    return st;
  double ps = fmax (sym_norm_inf (d, s->ph), sym_norm_inf (d, p1));
  ps = fmax (ps, fabs (hh) * sym_norm_inf (d, s->fp1));
  if (ps == 0.0)
    ps = 1.0;
  double prev = INFINITY;
  for (int it = 0; it < s->maxit; it++)
    {
      cnt->nnewton++;
      g_mv (m, d, G1, s->fq1, dl);
      for (int k = 0; k < m; k++)
        dl[k] /= hh;
      sym_lu_solve (&s->lu, dl, cnt);
      for (int i = 0; i < d; i++)
        dp[i] = 0.0;
      gt_axpy (m, d, G1, -hh, dl, dp);
      for (int k = 0; k < m; k++)
        mu[k] += dl[k];
      for (int i = 0; i < d; i++)
        p1[i] += dp[i];
      const double size = sym_norm_inf (d, dp);
      if (! isfinite (size))
        break;
      if (converged (size, prev, s->tol, ps))
        {
          for (int k = 0; k < m; k++)
            for (int i = 0; i < d; i++)
              s->fq1[i] -= hh * s->W[i + (size_t) k * d] * dl[k];
          return SYM_SUCCESS;
        }
      prev = size;
      if ((st = eval_fq (ev, tend, v->q1, p1, s->fq1, s->yw, s->fw)))
        return st;
    }
  cnt->nnewton_fail++;
  return SYM_NEWTON_FAIL;
}

static int
rattle_step (void *state, sym_eval *ev, double t, double h, double tend,
             const double *y, double *ynext, double *yerr)
{
  rattle_state *s = state;
  if (yerr)
    return SYM_EBADINPUT;     /* fixed steps only */
  sym_trial v;
  int st = sym_onestep_trial (&s->o, ev, t, h, tend, y, ynext, &v);
  if (st)
    return st;
  const int d = v.d, n = 2 * d, m = s->m;
  if ((st = sym_recs_f0 (&s->o.r, ev)))
    return st;
  const double *f0 = v.tr->f0;
  double *G1 = GE (v.tr, n, m), *mu = MU (v.tr, n);
  if (v.cont)
    {
      memcpy (s->G0, GE (v.cu, n, m), (size_t) m * d * sizeof (double));
      memcpy (s->lam, MU (v.cu, n), (size_t) m * sizeof (double));
    }
  else
    {
      if ((st = con_eval (s->cs, d, v.q0, s->g, s->G0, s->cw)))
        return st;
      memset (s->lam, 0, (size_t) m * sizeof (double));
    }
  if ((st = solve_lambda (s, ev, &v, f0 + d, G1)))
    return st;
  /* f_p (q1) */
  memcpy (s->yw, v.q1, (size_t) d * sizeof (double));
  memcpy (s->yw + d, s->ph, (size_t) d * sizeof (double));
  if ((st = sym_rhs (ev, tend, s->yw, s->fw)))
    return st;
  /* f_q at p_{k+1/2} with q_k (before the last, tiny, correction) and
     with q_{k+1}: the same if H is separable */
  if (! s->o.second_order)
    sym_sep_check (ev, t, d, s->fq1, s->fw);
  memcpy (s->fp1, s->fw + d, (size_t) d * sizeof (double));
  if ((st = con_eval (s->cs, d, v.q1, s->g, G1, s->cw)))
    return st;
  if ((st = solve_mu (s, ev, &v, G1, mu)))
    return st;
  /* f at the end, unconstrained (the next step's start), and the
     constrained derivatives of the dense output */
  double *f1 = v.tr->f1, *d0 = D0 (v.tr), *d1 = D1 (v.tr, n);
  memcpy (f1, s->fq1, (size_t) d * sizeof (double));
  memcpy (f1 + d, s->fp1, (size_t) d * sizeof (double));
  v.tr->have_f1 = 1;
  memcpy (d0, f0, (size_t) n * sizeof (double));
  gt_axpy (m, d, s->G0, -1.0, s->lam, d0 + d);
  memcpy (d1, f1, (size_t) n * sizeof (double));
  gt_axpy (m, d, G1, -1.0, mu, d1 + d);
  return sym_recs_finish (&s->o.r, ev, 0, NULL, ynext);
}

static int
rattle_dense (void *state, sym_eval *ev, double t, double *y)
{
  (void) ev;
  rattle_state *s = state;
  if (! s || ! y || ! s->o.r.have_cur || ! isfinite (t))
    return SYM_EBADINPUT;
  const sym_rec *c = s->o.r.cur;
  const int n = s->o.n;
  if (t == c->t)
    memcpy (y, c->y0, (size_t) n * sizeof (double));
  else if (t == c->tend)
    memcpy (y, c->y1, (size_t) n * sizeof (double));
  else
    sym_hermite (n, c->h, (t - c->t) / c->h, c->y0, c->y1, D0 (c),
                 D1 (c, n), y);
  return SYM_SUCCESS;
}

static int
rattle_tolerances (void *state, const sym_tolerances *tol)
{
  (void) state;
  (void) tol;
  return SYM_EBADINPUT;       /* no error estimate: fixed steps only */
}

static const sym_stepper_type rattle_type = {
  "rattle", rattle_alloc, sym_onestep_order, rattle_tolerances,
  rattle_step, sym_onestep_accept, rattle_dense, sym_onestep_dense_samples,
  sym_onestep_dense_degree, rattle_free, sym_onestep_end_f
};

const sym_stepper_type *const sym_step_rattle = &rattle_type;

/* ------------------------------------------------------------ projection */

int
sym_constraints_project (const sym_constraints *cs, sym_eval *ev,
                         int second_order, double t, double *y,
                         double *dq, double *dp)
{
  const int d = ev->dim, n = 2 * d, m = cs ? cs->m : 0;
  if (! cs || m < 1 || m >= d || ! y || ! dq || ! dp)
    return SYM_EBADINPUT;
  sym_lu lu;
  if (sym_lu_init (&lu, m))
    return SYM_ENOMEM;
  /* g, z (m); G, W (m d); q0, p0, fq, pw (d); yw, fw (n); cw (d + 2m) */
  const size_t len = 4 * (size_t) m + 2 * (size_t) m * d + 5 * (size_t) d
                     + 2 * (size_t) n;
  double *w = sym_calloc (len, sizeof (double));
  if (! w)
    {
      sym_lu_free (&lu);
      return SYM_ENOMEM;
    }
  double *g = w, *z = g + m, *G = z + m, *W = G + (size_t) m * d;
  double *q0 = W + (size_t) m * d, *p0 = q0 + d, *fq = p0 + d, *pw = fq + d;
  double *yw = pw + d, *fw = yw + n, *cw = fw + n;
  double *q = y, *p = y + d;
  sym_counters *cnt = &ev->st.cnt;
  memcpy (q0, q, (size_t) d * sizeof (double));
  memcpy (p0, p, (size_t) d * sizeof (double));
  double qs = sym_norm_inf (d, q), prev = INFINITY;
  if (qs == 0.0)
    qs = 1.0;
  int st = SYM_NEWTON_FAIL;
  /* q: minimum-norm corrections q -= G' (G G')^{-1} g */
  for (int it = 0; it < 50; it++)
    {
      int s2 = con_eval (cs, d, q, g, G, cw);
      if (! s2)
        s2 = dirs (ev, 1, m, t, q, p, NULL, G, W, pw, yw, fw);
      if (! s2)
        s2 = factor_gw (&lu, m, d, G, W, cnt);
      if (s2)
        {
          st = s2;
          break;
        }
      memcpy (z, g, (size_t) m * sizeof (double));
      sym_lu_solve (&lu, z, cnt);
      double size = 0.0;
      for (int i = 0; i < d; i++)
        {
          double c = 0.0;
          for (int k = 0; k < m; k++)
            c += G[k + (size_t) i * m] * z[k];
          q[i] -= c;
          size = fmax (size, fabs (c));
        }
      if (! isfinite (size))
        break;
      if (converged (size, prev, 16 * DBL_EPSILON, qs))
        {
          st = SYM_SUCCESS;
          break;
        }
      prev = size;
    }
  /* p: along G' onto G f_q(p) = 0 (one linear solve with second_order) */
  if (st == SYM_SUCCESS)
    st = con_eval (cs, d, q, g, G, cw);
  if (st == SYM_SUCCESS && second_order)
    {
      st = dirs (ev, 1, m, t, q, p, NULL, G, W, pw, yw, fw);
      if (! st)
        st = factor_gw (&lu, m, d, G, W, cnt);
      for (int r = 0; r < 2 && ! st; r++)
        {
          g_mv (m, d, G, p, z);
          sym_lu_solve (&lu, z, cnt);
          gt_axpy (m, d, G, -1.0, z, p);
        }
    }
  else if (st == SYM_SUCCESS)
    {
      double ps = sym_norm_inf (d, p);
      if (ps == 0.0)
        ps = 1.0;
      prev = INFINITY;
      st = eval_fq (ev, t, q, p, fq, yw, fw);
      if (! st)
        st = dirs (ev, 0, m, t, q, p, fq, G, W, pw, yw, fw);
      if (! st)
        st = factor_gw (&lu, m, d, G, W, cnt);
      for (int it = 0; ! st; it++)
        {
          if (it == 50)
            {
              st = SYM_NEWTON_FAIL;
              break;
            }
          g_mv (m, d, G, fq, z);
          sym_lu_solve (&lu, z, cnt);
          for (int i = 0; i < d; i++)
            pw[i] = 0.0;
          gt_axpy (m, d, G, -1.0, z, pw);
          for (int i = 0; i < d; i++)
            p[i] += pw[i];
          const double size = sym_norm_inf (d, pw);
          if (! isfinite (size))
            st = SYM_NEWTON_FAIL;
          else if (converged (size, prev, 16 * DBL_EPSILON, ps))
            break;
          else
            st = eval_fq (ev, t, q, p, fq, yw, fw);
          prev = size;
        }
    }
  *dq = *dp = 0.0;
  for (int i = 0; i < d; i++)
    {
      *dq = fmax (*dq, fabs (q[i] - q0[i]));
      *dp = fmax (*dp, fabs (p[i] - p0[i]));
    }
  sym_free (w);
  sym_lu_free (&lu);
  return st;
}
