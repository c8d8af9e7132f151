/* step_se.c -- symplectic Euler, variant "p implicit, q explicit" (order 1).

   y = [q; p], q, p in R^d, f(t, y) = [f_q; f_p] = [dH/dp; -dH/dq + F].
   One step from (t_k, q_k, p_k) by h (h < 0 runs backwards):

     p_{k+1} = p_k + h f_p(t_k, q_k, p_{k+1})      implicit in p_{k+1}
     q_{k+1} = q_k + h f_q(t_k, q_k, p_{k+1})      explicit

   For F = 0 this is the symplectic Euler method; with the forcing F in f_p
   it is the discrete Lagrange-d'Alembert (forced) variational integrator.

   Implicit solve: simplified Newton (newton.c) on the d unknowns P,
     G(P) = P - p_k - h f_p(t_k, q_k, P),   G'(P) ~ I - h A_pp(t_k, q_k, P),
   A_pp = d f_p / d p from sym_jac.
   - Start: P0 = p_k + h f_p(t_k, y_k) when f(t_k, y_k) is known (FSAL),
     else p_k + (p_k - p_{k-1}) h / h_prev when the last accepted step ended
     at (t_k, y_k), else f(t_k, y_k) is evaluated (one call).
   - Stop: max_i |dP_i| / s <= tol (opts->newton_tol, default 1e-14), with
     s = max(|p_k|_inf, |P0 - p_k|_inf) (1 if both vanish).
   - q_{k+1} needs f_q at the final P, but the last residual was evaluated
     at the previous iterate: f is evaluated at P once more (unless the last
     correction was round-off, |dP| <= 4 eps s).  That gives G(P) for free,
     and it must be <= 4 tol s, else Newton goes on from P with the
     contraction rate this residual shows (at most three solves): newton.c
     may stop after a single iteration, judging by the rate of an earlier
     solve, and was measured up to 1e-10 off.
   - The factored matrix is kept across steps while it pays and while h
     stays within 20% of the h it was built with: each solve's iterations
     beyond NW_BASE = 2 (what a fresh matrix needs) are charged to it, and
     once they add up to the cost of a new one (1 jac call, or n rhs calls
     of finite differences) it is rebuilt at the next solve.  (newton.c
     itself refreshes a matrix under which the iteration stalls.)

   Separable H = T(p) + V(q) (opts->separable): f_p does not depend on p and
   f_q not on q, so the step is explicit: f(t_k, [q_k; p_k]) gives f_p ->
   p_{k+1}; f(t_k, [q_k; p_{k+1}]) gives f_q -> q_{k+1}.  Two calls a step.

   Error estimate (yerr):
     err = y_{k+1} - y_k - (h/2) (f(t_k, y_k) + f(t_{k+1}, y_{k+1})),
   the difference to the trapezoidal rule through the two step points.  The
   trapezoidal rule is O(h^3) locally and this method O(h^2), so err =
   O(h^2) (err_order 1) and estimates the local error of the step.
   f(t_{k+1}, y_{k+1}) of an accepted step is the next step's f(t_k, y_k)
   (FSAL), so the estimate costs one call a step; on the separable path
   that call is also the next step's first call, and the step still costs
   two calls.

   Dense output on the last accepted step: the cubic Hermite interpolant
   through (t_k, y_k, f_k) and (t_{k+1}, y_{k+1}, f_{k+1}) when both f are
   known (they are when want_error or want_dense is set), else linear. */
#include "sym.h"

#include <float.h>
#include <math.h>
#include <string.h>

/* Newton iterations a solve needs with a fresh matrix and a good start;
   iterations beyond this are charged to the kept matrix */
#define NW_BASE 2

/* One step: its start, end and the f values known at its two ends. */
typedef struct {
  double t, h, tend;
  double *y0, *y1, *f0, *f1;    /* n each */
  int have_f0, have_f1;
} se_rec;

typedef struct {
  int d, n;
  int separable, want_f;
  se_rec rec[2];
  se_rec *cur, *trial;   /* last accepted step, step being tried */
  int have_cur;
  int trial_ok;          /* the last step() succeeded: accept() may take it */
  sym_newton nw;
  double h_mat;          /* h the Newton matrix was built with */
  long extra;            /* iterations beyond NW_BASE charged to the matrix */
  double *block;         /* the one allocation holding the arrays below */
  double *x, *scale, *rv;/* d: Newton unknown, its scale, a residual */
  double *yw, *fw;       /* n: last y where f was evaluated, and f there */
  double tw;             /* and the t */
  int have_fw;
  double *ym, *jw;       /* n, n*n: Jacobian work */
  /* the step being solved (for the Newton callbacks) */
  sym_system *sys;
  double tk, hk;
  const double *yk;
} se_state;

static int
same_vec (int n, const double *a, const double *b)
{
  for (int i = 0; i < n; i++)
    if (a[i] != b[i])
      return 0;
  return 1;
}

/* the end of the last step (of size h) and the start of this one: the
   driver may form them as t + h and t0 + k h, a few ulps apart */
static int
same_time (double a, double b, double h)
{
  return a == b
         || fabs (a - b) <= 4.0 * DBL_EPSILON
                            * fmax (fmax (fabs (a), fabs (b)), fabs (h));
}

static double
norm_inf (int n, const double *v)
{
  double m = 0.0;
  for (int i = 0; i < n; i++)
    m = fmax (m, fabs (v[i]));
  return m;
}

/* f at (t, [a; b]) into fw, remembered with its argument; no call when fw
   already holds f there */
static int
eval_at (se_state *s, double t, const double *a, const double *b)
{
  const int d = s->d;
  if (s->have_fw && s->tw == t && same_vec (d, s->yw, a)
      && same_vec (d, s->yw + d, b))
    return SYM_SUCCESS;
  memcpy (s->yw, a, (size_t) d * sizeof (double));
  memcpy (s->yw + d, b, (size_t) d * sizeof (double));
  s->tw = t;
  s->have_fw = 0;
  int st = sym_rhs (s->sys, t, s->yw, s->fw);
  if (st == SYM_SUCCESS)
    s->have_fw = 1;
  return st;
}

/* G(P) = P - p_k - h f_p(t_k, q_k, P); f at [q_k; P] stays in fw. */
static int
se_residual (void *ctx, const double *x, double *r)
{
  se_state *s = ctx;
  const int d = s->d;
  int st = eval_at (s, s->tk, s->yk, x);
  if (st)
    return st;
  for (int i = 0; i < d; i++)
    r[i] = x[i] - s->yk[d + i] - s->hk * s->fw[d + i];
  return SYM_SUCCESS;
}

/* G'(P) ~ I - h A_pp at [q_k; P].  For finite differences f is evaluated
   there first: the differences need it, and the iteration's first residual
   then finds it in fw. */
static int
se_matrix (void *ctx, const double *x, double *a)
{
  se_state *s = ctx;
  const int d = s->d, n = s->n;
  const double *y, *f0 = NULL;
  int st;
  if (! s->sys->jac)
    {
      if ((st = eval_at (s, s->tk, s->yk, x)))
        return st;
      y = s->yw;
      f0 = s->fw;
    }
  else
    {
      memcpy (s->ym, s->yk, (size_t) d * sizeof (double));
      memcpy (s->ym + d, x, (size_t) d * sizeof (double));
      y = s->ym;
    }
  if ((st = sym_jac (s->sys, s->tk, y, f0, s->jw)))
    return st;
  for (int j = 0; j < d; j++)
    for (int i = 0; i < d; i++)
      a[i + (size_t) j * d] = (i == j ? 1.0 : 0.0)
        - s->hk * s->jw[(d + i) + (size_t) (d + j) * n];
  s->h_mat = s->hk;
  s->extra = 0;
  return SYM_SUCCESS;
}

static void se_free (void *state);

static void *
se_alloc (const sym_system *sys, const sym_method_opts *opts, int *status)
{
  int dummy;
  if (! status)
    status = &dummy;
  if (! sys || sys->dim < 1 || ! sys->rhs)
    {
      *status = SYM_EBADINPUT;
      return NULL;
    }
  const int d = sys->dim, n = 2 * d;
  se_state *s = sym_calloc (1, sizeof (*s));
  if (! s)
    {
      *status = SYM_ENOMEM;
      return NULL;
    }
  s->d = d;
  s->n = n;
  if (opts)
    {
      s->separable = opts->separable != 0;
      s->want_f = opts->want_error || opts->want_dense;
    }
  /* rec: 2 x 4n; x, scale, rv: 3d; yw, fw, ym: 3n; jw: n*n */
  size_t len = (size_t) 8 * n + 3 * (size_t) d + 3 * (size_t) n
               + (size_t) n * n;
  s->block = sym_calloc (len, sizeof (double));
  if (! s->block || sym_newton_init (&s->nw, d))
    {
      se_free (s);
      *status = SYM_ENOMEM;
      return NULL;
    }
  double *w = s->block;
  for (int k = 0; k < 2; k++)
    {
      s->rec[k].y0 = w; w += n;
      s->rec[k].y1 = w; w += n;
      s->rec[k].f0 = w; w += n;
      s->rec[k].f1 = w; w += n;
    }
  s->x = w; w += d;
  s->scale = w; w += d;
  s->rv = w; w += d;
  s->yw = w; w += n;
  s->fw = w; w += n;
  s->ym = w; w += n;
  s->jw = w;
  if (opts && opts->newton_tol > 0)
    s->nw.tol = opts->newton_tol;
  if (opts && opts->max_newton > 0)
    s->nw.maxit = opts->max_newton;
  s->cur = &s->rec[0];
  s->trial = &s->rec[1];
  *status = SYM_SUCCESS;
  return s;
}

static void
se_free (void *state)
{
  se_state *s = state;
  if (! s)
    return;
  sym_newton_free (&s->nw);   /* safe on the zeroed struct too */
  sym_free (s->block);
  sym_free (s);
}

static int
se_step (void *state, sym_system *sys, double t, double h, const double *y,
         double *ynext, double *yerr)
{
  se_state *s = state;
  int st;
  if (! s || ! sys || ! y || ! ynext || ! isfinite (t) || ! isfinite (h)
      || h == 0.0)
    return SYM_EBADINPUT;
  const int d = s->d, n = s->n;
  s->trial_ok = 0;
  se_rec *tr = s->trial, *cu = s->cur;
  /* does the last accepted step end where this one starts? */
  const int cont = s->have_cur && same_time (t, cu->tend, cu->h)
                   && same_vec (n, y, cu->y1);
  /* f(t, y) is known from an earlier attempt from the same point, or from
     the end of the last accepted step */
  if (! (tr->have_f0 && t == tr->t && same_vec (n, y, tr->y0)))
    {
      tr->have_f0 = 0;
      memcpy (tr->y0, y, (size_t) n * sizeof (double));
      if (cont && cu->have_f1)
        {
          memcpy (tr->f0, cu->f1, (size_t) n * sizeof (double));
          tr->have_f0 = 1;
        }
    }
  tr->t = t;
  tr->h = h;
  tr->tend = t + h;
  tr->have_f1 = 0;
  const double *q0 = tr->y0, *p0 = tr->y0 + d;
  double *q1 = tr->y1, *p1 = tr->y1 + d;
  s->sys = sys;

  if (s->separable)
    {
      if (! tr->have_f0)
        {
          st = sym_rhs (sys, t, tr->y0, tr->f0);
          if (st)
            return st;
          tr->have_f0 = 1;
        }
      for (int i = 0; i < d; i++)
        p1[i] = p0[i] + h * tr->f0[d + i];
      st = eval_at (s, t, q0, p1);
      if (st)
        return st;
      for (int i = 0; i < d; i++)
        q1[i] = q0[i] + h * s->fw[i];
    }
  else
    {
      double *x = s->x;
      double sc = 0.0;
      for (int pass = 0; pass < 2; pass++)
        {
          if (! tr->have_f0 && (! cont || pass == 1))
            {
              st = sym_rhs (sys, t, tr->y0, tr->f0);
              if (st)
                return st;
              tr->have_f0 = 1;
            }
          if (tr->have_f0)
            for (int i = 0; i < d; i++)
              x[i] = p0[i] + h * tr->f0[d + i];
          else   /* cont: the last step's increment */
            for (int i = 0; i < d; i++)
              x[i] = p0[i] + (p0[i] - cu->y0[d + i]) * (h / cu->h);
          sc = norm_inf (d, p0);
          for (int i = 0; i < d; i++)
            sc = fmax (sc, fabs (x[i] - p0[i]));
          if (sc > 0.0 || tr->have_f0)
            break;
        }
      if (! (sc > 0.0))
        sc = 1.0;
      for (int i = 0; i < d; i++)
        s->scale[i] = sc;

      if (s->nw.have_matrix && fabs (h - s->h_mat) > 0.2 * fabs (s->h_mat))
        sym_newton_invalidate (&s->nw);
      s->tk = t;
      s->hk = h;
      s->yk = tr->y0;
      sym_newton_problem prob = { se_residual, se_matrix, s };
      /* newton.c may stop after a single iteration, judging by the
         contraction rate of an earlier solve; the f needed at the solution
         gives the residual there for free, which checks that a posteriori
         (a failed check goes on iterating from there, its first residual
         already known, with the contraction rate that residual shows).  A
         last correction at round-off level needs neither: fw, f at the
         previous iterate, is then f at P. */
      for (int round = 0; round < 3; round++)
        {
          st = sym_newton_solve (&s->nw, &prob, x, s->scale, &sys->cnt);
          if (st)
            {
              sym_newton_invalidate (&s->nw);
              return st;
            }
          if (s->nw.iters > NW_BASE)
            {
              s->extra += s->nw.iters - NW_BASE;
              if (s->extra >= (sys->jac ? 1 : n))
                sym_newton_invalidate (&s->nw);
            }
          if (norm_inf (d, s->nw.dx) <= 4.0 * DBL_EPSILON * sc)
            break;
          if ((st = se_residual (s, x, s->rv)))
            return st;
          double rn = norm_inf (d, s->rv);
          if (rn <= fmax (4.0 * s->nw.tol, 8.0 * DBL_EPSILON) * sc)
            break;
          /* the residual is about the next correction: the rate it shows
             replaces the one newton.c trusted */
          double th = rn / fmax (norm_inf (d, s->nw.dx), DBL_MIN);
          s->nw.eta = th < 0.5 ? th / (1.0 - th) : 1.0;
        }
      memcpy (p1, x, (size_t) d * sizeof (double));
      for (int i = 0; i < d; i++)
        q1[i] = q0[i] + h * s->fw[i];
    }

  if (s->want_f || yerr)
    {
      if (! tr->have_f0)
        {
          st = sym_rhs (sys, t, tr->y0, tr->f0);
          if (st)
            return st;
          tr->have_f0 = 1;
        }
      st = sym_rhs (sys, tr->tend, tr->y1, tr->f1);
      if (st)
        return st;
      tr->have_f1 = 1;
    }
  if (yerr)
    for (int i = 0; i < n; i++)
      yerr[i] = (tr->y1[i] - tr->y0[i])
        - 0.5 * h * (tr->f0[i] + tr->f1[i]);
  memcpy (ynext, tr->y1, (size_t) n * sizeof (double));
  s->trial_ok = 1;
  return SYM_SUCCESS;
}

static void
se_accept (void *state)
{
  se_state *s = state;
  if (! s->trial_ok)   /* nothing to accept */
    return;
  se_rec *r = s->cur;
  s->cur = s->trial;
  s->trial = r;
  s->have_cur = 1;
  s->trial_ok = 0;
}

static int
se_dense (void *state, sym_system *sys, double t, double *y)
{
  se_state *s = state;
  (void) sys;
  if (! s || ! y || ! s->have_cur || ! isfinite (t))
    return SYM_EBADINPUT;
  const se_rec *c = s->cur;
  const int n = s->n;
  if (t == c->t)
    {
      memcpy (y, c->y0, (size_t) n * sizeof (double));
      return SYM_SUCCESS;
    }
  if (t == c->tend)
    {
      memcpy (y, c->y1, (size_t) n * sizeof (double));
      return SYM_SUCCESS;
    }
  const double th = (t - c->t) / c->h, h = c->h;
  if (c->have_f0 && c->have_f1)
    {
      const double u = 1.0 - th;
      const double a0 = u * u * (1.0 + 2.0 * th), a1 = th * th * (3.0 - 2.0 * th);
      const double b0 = h * th * u * u, b1 = -h * th * th * u;
      for (int i = 0; i < n; i++)
        y[i] = a0 * c->y0[i] + a1 * c->y1[i] + b0 * c->f0[i] + b1 * c->f1[i];
    }
  else
    for (int i = 0; i < n; i++)
      y[i] = c->y0[i] + th * (c->y1[i] - c->y0[i]);
  return SYM_SUCCESS;
}

static void
se_reset (void *state)
{
  se_state *s = state;
  /* forget the last step (dense output, predictor, FSAL) and every f kept;
     the Newton matrices stay: newton.c refreshes them if they no longer
     serve */
  s->have_cur = 0;
  s->trial_ok = 0;
  s->rec[0].have_f0 = s->rec[0].have_f1 = 0;
  s->rec[1].have_f0 = s->rec[1].have_f1 = 0;
  s->have_fw = 0;
}

static int
se_order (const void *state)
{
  (void) state;
  return 1;
}

static const sym_stepper_type se_type = {
  "se", 1, se_order, se_order, se_alloc, se_step, se_accept, se_dense,
  se_reset, se_free
};

const sym_stepper_type *const sym_step_se = &se_type;
