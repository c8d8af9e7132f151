/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* step.c -- odeSPVI's stepper (see spvi.h): its state, the step (start,
   the method's solve, the companion's for the error estimate), accept,
   and its table. */
#include "spvi.h"

#include <math.h>
#include <string.h>

static void
rec_free (spvi_rec *r)
{
  sym_free (r->y0);
  sym_free (r->y1);
  sym_free (r->a);
  sym_free (r->P);
  sym_free (r->dq);
  sym_free (r->D);
  sym_free (r->fe0);
  sym_free (r->fe1);
  sym_free (r->emis);
  sym_free (r->cmp);
  r->y0 = r->y1 = r->a = r->P = r->dq = r->cmp = NULL;
  r->D = r->fe0 = r->fe1 = r->emis = NULL;
}

/* (dense: the dense output's data too, D, fe0 and emis) */
static int
rec_init (spvi_rec *r, int d, int n, int m, int dense)
{
  memset (r, 0, sizeof (*r));
  r->y0 = sym_calloc (2 * (size_t) d, sizeof (double));
  r->y1 = sym_calloc (2 * (size_t) d, sizeof (double));
  r->a = sym_calloc ((size_t) (n - 1) * d, sizeof (double));
  r->P = sym_calloc ((size_t) m * d, sizeof (double));
  r->dq = sym_calloc ((size_t) d, sizeof (double));
  r->fe1 = sym_calloc (2 * (size_t) d, sizeof (double));
  r->cmp = sym_calloc (2 * (size_t) d, sizeof (double));
  if (dense)
    {
      r->D = sym_calloc ((size_t) (m + 3) * 2 * d, sizeof (double));
      r->fe0 = sym_calloc (2 * (size_t) d, sizeof (double));
      r->emis = sym_calloc (2 * (size_t) d, sizeof (double));
    }
  if (! r->y0 || ! r->y1 || ! r->a || ! r->P || ! r->dq || ! r->fe1
      || ! r->cmp || (dense && (! r->D || ! r->fe0 || ! r->emis)))
    {
      rec_free (r);
      return SYM_ENOMEM;
    }
  return SYM_SUCCESS;
}

static void
spvi_free (void *state)
{
  spvi_state *s = state;
  if (! s)
    return;
  spvi_core_free (&s->lo);
  spvi_core_free (&s->hi);
  rec_free (&s->rec[0]);
  rec_free (&s->rec[1]);
  sym_free (s->xi);
  sym_free (s->vinv);
  sym_free (s->f0);
  sym_free (s->lv);
  sym_free (s->dlv);
  sym_free (s->cb);
  sym_free (s->gz);
  sym_free (s->gw);
  sym_free (s->vq);
  sym_free (s->ach);
  sym_free (s->pz);
  sym_free (s->pw);
  sym_free (s->pc);
  sym_free (s->dhist);
  sym_free (s->xp);
  sym_free (s->hw);
  sym_free (s->pt_q);
  sym_free (s->pt_p);
  sym_free (s);
}

/* The Gauss transform: for a polynomial v of degree < n, a_i = (2i+1)/2
   sum_l w_l v(xi_l) l_i(xi_l) (exact, the products have degree <= 2n -
   2): the inverse of the Legendre-Vandermonde matrix at the n Gauss
   points */
static int
gauss_transform (spvi_state *s)
{
  const int n = s->n;
  double *wl = sym_calloc (n, sizeof (double));
  if (! wl)
    return SYM_ENOMEM;
  int st = sym_gauss_legendre (n, s->xi, wl);
  if (! st)
    for (int l = 0; l < n; l++)
      {
        sym_legendre (n, s->xi[l], s->lv, s->dlv);
        for (int i = 0; i < n; i++)
          s->vinv[i * n + l] = 0.5 * (2 * i + 1) * wl[l] * s->lv[i];
      }
  sym_free (wl);
  return st;
}

static void *
spvi_alloc (int dim, const sym_method_opts *opts, int *status)
{
  int dummy;
  if (! status)
    status = &dummy;
  const sym_spvi_opts *own = opts ? opts->own : NULL;
  const int m = own && own->nodes ? own->nodes : SYM_SPVI_NODES;
  const int n = own && own->q_dofs ? own->q_dofs : m + 1;
  const int newmat = own ? own->newton_matrix : SYM_MATRIX_AUTO;
  const int system = own ? own->system : SYM_SYSTEM_AUTO;
  const int sparse = own && own->sparse;
  const int nonlin = own ? own->nonlinear : SYM_NONLINEAR_NEWTON;
  /* n > 2m: the quadrature cannot see the top modes and the iteration
     does not converge; also n < 2 (no motion) */
  if (dim < 1 || n < 2 || m < 1 || n > 2 * m || m > SYM_SPVI_MAX_NODES
      || (opts && (opts->newton_tol < 0 || opts->max_newton < 0
                   || ! (opts->newton_tol < 1.0)))
      || newmat < SYM_MATRIX_AUTO || newmat > SYM_MATRIX_NEW
      || system < SYM_SYSTEM_AUTO || system > SYM_SYSTEM_STAGES
      /* stages need a pair n - 1 = m; a sparse Df, the staged solver
         (by stages, or for the other pairs the whole system, sparse) */
      || (n - 1 != m && system == SYM_SYSTEM_STAGES)
      || nonlin < SYM_NONLINEAR_NEWTON || nonlin > SYM_NONLINEAR_AUTO
      || (n - 1 != m && nonlin != SYM_NONLINEAR_NEWTON)
      || (sparse && system == SYM_SYSTEM_FULL))
    {
      *status = SYM_EBADINPUT;
      return NULL;
    }
  const int d = dim;
  spvi_state *s = sym_calloc (1, sizeof (*s));
  if (! s)
    {
      *status = SYM_ENOMEM;
      return NULL;
    }
  s->d = d;
  s->n = n;
  s->m = m;
  s->order = sym_spvi_order (n, m);
  s->hermite = n - 1 != m && s->order < 8;
  s->tol = opts && opts->newton_tol > 0 ? opts->newton_tol : SYM_NEWTON_TOL;
  s->reversible = opts && opts->reversible;
  s->maxit = opts && opts->max_newton > 0 ? opts->max_newton
             : SYM_NEWTON_MAXIT;
  s->newmat = newmat;
  s->nonlinear = nonlin;
  if (sparse)
    s->stages = SPVI_STAGES_SPARSE;
  else if (system == SYM_SYSTEM_STAGES
           /* the fixed point is the stages' solve with J = 0 */
           || nonlin != SYM_NONLINEAR_NEWTON
           || (system == SYM_SYSTEM_AUTO && n - 1 == m
               && (size_t) (n - 1 + m) * d
                  > (m <= SYM_SPVI_STAGES_NODES ? SYM_SPVI_STAGES_N
                     : SYM_SPVI_STAGES_N_MANY)))
    s->stages = SPVI_STAGES;
  int st = spvi_core_init (&s->lo, d, n, m, s->stages);
  if (! st)
    st = rec_init (&s->rec[0], d, n, m, opts && opts->want_dense);
  if (! st)
    st = rec_init (&s->rec[1], d, n, m, opts && opts->want_dense);
  if (! st)
    {
      s->xi = sym_calloc (n, sizeof (double));
      s->vinv = sym_calloc ((size_t) n * n, sizeof (double));
      s->f0 = sym_calloc (2 * (size_t) d, sizeof (double));
      s->lv = sym_calloc ((n > m ? n : m) + 2, sizeof (double));
      s->dlv = sym_calloc ((n > m ? n : m) + 2, sizeof (double));
      s->cb = sym_calloc (m + 3, sizeof (double));
      s->vq = sym_calloc ((size_t) n * d, sizeof (double));
      s->ach = sym_calloc ((size_t) n * d, sizeof (double));
      s->pz = sym_calloc (m + 2, sizeof (double));
      s->pw = sym_calloc (m + 2, sizeof (double));
      s->pc = sym_calloc ((size_t) (m + 2) * d, sizeof (double));
      /* exact for the integrand of the dense output, of degree <= m + 2 */
      s->ng = m / 2 + 2;
      s->gz = sym_calloc (s->ng, sizeof (double));
      s->gw = sym_calloc (s->ng, sizeof (double));
      s->xp = sym_calloc (s->lo.N, sizeof (double));
      s->hw = sym_calloc (s->lo.N, sizeof (double));
      s->pt_q = sym_calloc ((size_t) n * n, sizeof (double));
      s->pt_p = sym_calloc ((size_t) m * (m + 2), sizeof (double));
      s->dhist = sym_calloc ((size_t) (SYM_SPVI_HIST + 1) * s->lo.N,
                             sizeof (float));
      if (! s->xi || ! s->vinv || ! s->f0 || ! s->lv || ! s->dlv || ! s->cb
          || ! s->vq || ! s->dhist || ! s->xp || ! s->hw || ! s->pt_q || ! s->pt_p || ! s->gz
          || ! s->gw || ! s->ach
          || ! s->pz || ! s->pw || ! s->pc)
        st = SYM_ENOMEM;
      if (! st)
        st = sym_gauss_legendre (s->ng, s->gz, s->gw);
      if (! st)
        st = sym_gauss_legendre (m + 2, s->pz, s->pw);
    }
  if (! st)
    st = gauss_transform (s);
  if (st)
    {
      spvi_free (s);
      *status = st;
      return NULL;
    }
  s->cur = &s->rec[0];
  s->trial = &s->rec[1];
  *status = SYM_SUCCESS;
  return s;
}

/* A step (t, h) ending at tend is about to be solved: the cores' kept
   evaluations are moved to count from t.  A step that starts where the
   last one ended moves them by that step's h, so that fixed steps see
   the same times at any t (differences of the step times vary by the
   round-off of t); a step from elsewhere by the difference of the
   times. */
static void
spvi_clock (spvi_state *s, double t, double h, double tend)
{
  if (s->ck_ok && t != s->ck_t)
    {
      const double shift = t == s->ck_tend ? s->ck_h : t - s->ck_t;
      spvi_core_move (&s->lo, shift);
      if (s->have_hi)
        spvi_core_move (&s->hi, shift);
    }
  s->ck_t = t;
  s->ck_h = h;
  s->ck_tend = tend;
  s->ck_ok = 1;
}

/* The smallest error a component of y may have under the tolerances:
   min_i max(atol, rtol |y_i|) */
static double
error_floor (int n, const double *y, double rtol, double atol)
{
  double w = INFINITY;
  for (int i = 0; i < n; i++)
    w = fmin (w, fmax (atol, rtol * fabs (y[i])));
  return w;
}

/* The method's solve of the trial step from y into tr->y1 (and s->lo.x),
   to tol, after the start in s->lo.x (scales *S).  A fixed step is
   converged to round-off, and when Newton fails from the continued start
   (too far off: the pairs n - 1 < m, whose p polynomial through many
   nodes extrapolates poorly, or many nodes at a long step) it is tried
   again from the Euler start, then reached from shorter steps
   (spvi_lengthen): a fixed step's failure ends the run, while an
   adaptive run shrinks the step, for fewer calls than the retries. */
static int
solve_method (spvi_state *s, sym_eval *ev, double t, double h,
              int adaptive, double tol, spvi_scale *S)
{
  spvi_rec *tr = s->trial;
  int st = spvi_solve (&s->lo, ev, t, h, tr->y0, S, s, tol, tr->y1);
  if (st == SYM_NEWTON_FAIL && s->pred_cont && ! adaptive)
    {
      st = spvi_predict (s, ev, t, h, tr->y0, 1, 0, S);
      if (! st)
        {
          spvi_predict_history (s, h);
          st = spvi_solve (&s->lo, ev, t, h, tr->y0, S, s, tol, tr->y1);
        }
    }
  if (st == SYM_NEWTON_FAIL && ! adaptive)
    st = spvi_lengthen (s, ev, t, h, tol, S);
  return st;
}

/* The companion (n+1, m+1) of the trial step into yerr, started from the
   method's polynomials (the same a_i and a_n = 0; P at its nodes from the
   method's p polynomial); then the trial advances with the companion's
   value (local extrapolation) and yerr is the estimate of the method's
   error */
static int
solve_companion (spvi_state *s, sym_eval *ev, double t, double h,
                 double tol, const spvi_scale *S, double *yerr)
{
  const int d = s->d, n = s->n, m = s->m, nn = 2 * d;
  spvi_rec *tr = s->trial;
  spvi_core *c = &s->hi;
  memcpy (c->x, tr->a, (size_t) (n - 1) * d * sizeof (double));
  for (int k = 0; k < d; k++)
    c->x[(size_t) (n - 1) * d + k] = 0.0;
  for (int j = 0; j < m + 1; j++)
    spvi_rec_p (s, tr, c->z[j], c->x + (size_t) n * d + (size_t) j * d);
  int st = spvi_solve (c, ev, t, h, tr->y0, S, s, tol, yerr);
  if (st)
    return st;
  if (n - 1 == m && tr->D)
    spvi_rec_nodes (tr, c);
  for (int k = 0; k < d; k++)
    tr->dq[k] = yerr[k] - tr->y1[k];
  tr->has_dq = 1;
  for (int i = 0; i < nn; i++)
    {
      double hi = yerr[i];
      yerr[i] = tr->y1[i] - hi;
      tr->y1[i] = hi;
    }
  return SYM_SUCCESS;
}

/* A fixed step's end y + inc summed with the rounding of y carried (y
   the last step's end; else none): the round-off of many steps then
   does not add up in the phase */
static void
compensate (spvi_state *s, double t, const double *y)
{
  const int nn = 2 * s->d;
  spvi_rec *tr = s->trial;
  const spvi_rec *cu = s->cur;
  const int carry = s->have_cur && cu->tend == t
                    && memcmp (cu->y1, y, (size_t) nn * sizeof (double)) == 0;
  for (int i = 0; i < nn; i++)
    {
      const double e = (carry ? cu->cmp[i] : 0.0) + s->lo.inc[i];
      tr->y1[i] = y[i] + e;
      tr->cmp[i] = (y[i] - tr->y1[i]) + e;
    }
}

/* A fixed step is converged to round-off.  An adaptive one advances with
   the companion, so the method's solution only enters the estimate (and
   the dense output within the step): its solve stops at SYM_SPVI_EST_LO
   of the smallest error the tolerances allow, the companion's at
   SYM_SPVI_EST_HI. */
static int
spvi_step (void *state, sym_eval *ev, double t, double h, double tend,
           const double *y, double *ynext, double *yerr)
{
  spvi_state *s = state;
  const int d = s->d, n = s->n, m = s->m, nn = 2 * d;
  s->trial_ok = 0;
  if (! (h != 0.0) || ! isfinite (h) || ! isfinite (t) || ! isfinite (tend))
    return SYM_EBADINPUT;
  if (yerr && ! s->have_hi)
    {
      int st = spvi_core_init (&s->hi, d, n + 1, m + 1, s->stages);
      if (st)
        return st;
      s->have_hi = 1;
    }
  spvi_clock (s, t, h, tend);
  spvi_rec *tr = s->trial;
  memcpy (tr->y0, y, (size_t) nn * sizeof (double));
  spvi_scale S;
  int st = spvi_predict (s, ev, t, h, tr->y0, 0, yerr != NULL, &S);
  if (st)
    return st;
  spvi_predict_history (s, h);
  const double tol_rf = (s->reversible ? SYM_REVERSIBLE_TOL : SYM_FIXED_TOL)
                        * s->tol;
  const double w = yerr && s->est_rtol > 0
                   ? error_floor (nn, y, s->est_rtol, s->est_atol) : 0.0;
  const double tol_lo = fmax (tol_rf, SYM_SPVI_EST_LO * w / S.all);
  const double tol_hi = fmax (tol_rf, SYM_SPVI_EST_HI * w / S.all);
  if ((st = solve_method (s, ev, t, h, yerr != NULL, tol_lo, &S)))
    return st;
  if (! yerr)
    compensate (s, t, y);
  memcpy (tr->a, s->lo.x, (size_t) (n - 1) * d * sizeof (double));
  memcpy (tr->P, s->lo.x + (size_t) (n - 1) * d,
          (size_t) m * d * sizeof (double));
  tr->t = t;
  tr->h = h;
  tr->tend = tend;
  tr->has_dq = 0;
  tr->M = 0;
  tr->have_fe0 = tr->have_fe1 = tr->have_emis = tr->ends_bad = 0;
  spvi_rec_noise (s, tr, tol_lo, &S);
  if (n - 1 == m && tr->D)
    spvi_rec_nodes (tr, &s->lo);
  if (yerr && (st = solve_companion (s, ev, t, h, tol_hi, &S, yerr)))
    return st;
  memcpy (ynext, tr->y1, (size_t) nn * sizeof (double));
  s->trial_ok = 1;
  return SYM_SUCCESS;
}

static void
spvi_accept (void *state)
{
  spvi_state *s = state;
  if (! s->trial_ok)
    return;
  /* the error of its polynomial prediction joins the history */
  const spvi_rec *tr = s->trial;
  const int N = s->lo.N, na = (s->n - 1) * s->d;
  if (tr->cont)
    {
      if (! (s->nhist > 0 && sym_same_step (tr->h, s->hhist)))
        s->nhist = 0;
      memmove (s->dhist + N, s->dhist,
               (size_t) SYM_SPVI_HIST * N * sizeof (float));
      memmove (s->dscale + 1, s->dscale, SYM_SPVI_HIST * sizeof (double));
      /* in units of its largest error: single precision holds its range
         at any size of the data */
      double big = 0.0;
      for (int i = 0; i < N; i++)
        big = sym_fmax_acc (big, fabs ((i < na ? tr->a[i] : tr->P[i - na])
                                       - s->xp[i]));
      s->dscale[0] = big > 0.0 && isfinite (big) ? big : 1.0;
      for (int i = 0; i < N; i++)
        s->dhist[i] = (float) (((i < na ? tr->a[i] : tr->P[i - na])
                                - s->xp[i]) / s->dscale[0]);
      if (s->nhist <= SYM_SPVI_HIST)
        s->nhist++;
      s->hhist = tr->h;
    }
  else
    s->nhist = 0;
  /* f at the end of the last step, if the dense output evaluated it, is
     f at the start of this one */
  spvi_rec *cu = s->cur, *tw = s->trial;
  if (s->have_cur && tw->fe0 && cu->have_fe1 && cu->tend == tw->t
      && memcmp (cu->y1, tw->y0, 2 * (size_t) s->d * sizeof (double)) == 0)
    {
      memcpy (tw->fe0, cu->fe1, 2 * (size_t) s->d * sizeof (double));
      tw->have_fe0 = 1;
    }
  spvi_rec *tmp = s->cur;
  s->cur = s->trial;
  s->trial = tmp;
  s->have_cur = 1;
  s->trial_ok = 0;
}

int
sym_spvi_order (int q_dofs, int nodes)
{
  int a = q_dofs - 1, b = 2 * nodes - q_dofs + 1;
  return 2 * (a < b ? a : b);
}

/* Adaptive runs advance with the companion: its order, the method's for
   the estimate */
static int
spvi_order (const void *state, int *est)
{
  const spvi_state *s = state;
  if (est)
    *est = s->order;
  return s->adaptive ? sym_spvi_order (s->n + 1, s->m + 1) : s->order;
}

static int
spvi_set_tolerances (void *state, const sym_tolerances *tol)
{
  spvi_state *s = state;
  s->adaptive = 1;
  s->est_rtol = tol->rtol;
  s->est_atol = tol->atol[0];
  for (int i = 1; i < tol->atol_len; i++)
    s->est_atol = fmin (s->est_atol, tol->atol[i]);
  if (! s->have_hi)
    {
      int st = spvi_core_init (&s->hi, s->d, s->n + 1, s->m + 1, s->stages);
      if (st)
        return st;
      s->have_hi = 1;
    }
  return SYM_SUCCESS;
}

/* the events are also sampled at as many points inside a step as it has
   nodes: a long step of high order can hide a zero pair */
static int
spvi_dense_samples (const void *state)
{
  const spvi_state *s = state;
  return s->m;
}

/* the pairs n - 1 = m: the integral of the polynomial through the M + 2
   values of dy/dz (M the nodes of the solve the run advances with),
   degree M + 2; the others: the cubic Hermite interpolant, or q of degree
   n - 1 and p of degree m + 1 */
static int
spvi_dense_degree (const void *state)
{
  const spvi_state *s = state;
  const int M = s->adaptive ? s->m + 1 : s->m;
  int deg = s->n - 1 > s->m + 1 ? s->n - 1 : s->m + 1;
  return s->n - 1 == s->m ? M + 2 : deg > 3 ? deg : 3;
}

/* f at the end of the last accepted step: the dense output's, or
   evaluated and kept for it and for the next step's start */
static int
spvi_end_f (void *state, sym_eval *ev, double *f)
{
  spvi_state *s = state;
  spvi_rec *cu = s->cur;
  const size_t n = 2 * (size_t) s->d;
  if (! s->have_cur)
    return SYM_EBADINPUT;
  int st = sym_rhs_once (ev, cu->tend, cu->y1, cu->fe1, &cu->have_fe1);
  if (st == SYM_SUCCESS)
    memcpy (f, cu->fe1, n * sizeof (double));
  return st;
}

static const sym_stepper_type spvi_type = {
  "spvi", spvi_alloc, spvi_order, spvi_set_tolerances, spvi_step,
  spvi_accept, spvi_dense, spvi_dense_samples, spvi_dense_degree, spvi_free,
  spvi_end_f
};

const sym_stepper_type *const sym_step_spvi = &spvi_type;
