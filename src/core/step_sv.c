/* step_sv.c -- Stoermer-Verlet (order 2), general H.

   y = [q; p], q, p in R^d, f(t, y) = [f_q; f_p] = [dH/dp; -dH/dq + F].
   One step from (t_k, q_k, p_k) by h (h < 0 runs backwards), t_{k+1} =
   t_k + h:

     p_{k+1/2} = p_k + (h/2) f_p(t_k, q_k, p_{k+1/2})                 (1)
     q_{k+1}   = q_k + (h/2) [f_q(t_k, q_k, p_{k+1/2})
                              + f_q(t_{k+1}, q_{k+1}, p_{k+1/2})]       (2)
     p_{k+1}   = p_{k+1/2} + (h/2) f_p(t_{k+1}, q_{k+1}, p_{k+1/2})     (3)

   (1) and (2) are implicit (d unknowns each), (3) is explicit.  The method
   is symplectic and symmetric (the step by -h from t_{k+1} undoes it).

   Implicit solves: simplified Newton (newton.c), one state per equation,
     (1) G(P) = P - p_k - (h/2) f_p(t_k, q_k, P),     G' ~ I - (h/2) A_pp
     (2) G(Q) = Q - q_k - (h/2) [f_q(t_k, q_k, P) + f_q(t_{k+1}, Q, P)],
                                                       G' ~ I - (h/2) A_qq
   (A_pp = d f_p/d p, A_qq = d f_q/d q, blocks of Df from sym_jac).
   - Starts: P0 = p_k + (h/2) f_p(t_k, y_k) when f(t_k, y_k) is known
     (FSAL), else p_k + (p_k - p_{k-1/2}) h / h_prev when the last accepted
     step ended at (t_k, y_k), else f(t_k, y_k) is evaluated (one call);
     Q0 = q_k + h f_q(t_k, q_k, P).
   - Stop: max_i |dx_i| / s <= tol (opts->newton_tol, default 1e-14), with
     s the max norm of p_k (q_k) or of the predicted increment P0 - p_k
     (Q0 - q_k), whichever is larger (1 if both vanish).
   - The f values used after each solve are those at the converged unknown:
     the last residual was evaluated at the previous iterate, so f is
     evaluated at the solution once more (unless the last correction was
     round-off, |dx| <= 4 eps s).  That gives the residual for free, and it
     must be <= 4 tol s, else Newton goes on from there (see solve()).
   - Each factored matrix is kept across steps while it pays and while h
     stays within 20% of the h it was built with: each solve's iterations
     beyond NW_BASE = 2 (what a fresh matrix needs) are charged to it, and
     once they add up to the cost of a new one (1 jac call, or n rhs calls
     of finite differences) it is rebuilt at the next solve.  (newton.c
     itself refreshes a matrix under which the iteration stalls.)

   Separable H = T(p) + V(q) (opts->separable): explicit.  With f_p(q_k)
   from the last step (FSAL) or from f(t_k, y_k) at a fresh start:
     p_{k+1/2} = p_k + (h/2) f_p(q_k)
     A = f(t_k + h/2, [q_k; p_{k+1/2}]) -> q_{k+1} = q_k + h f_q(p_{k+1/2})
     B = f(t_{k+1}, [q_{k+1}; p_{k+1/2}]) -> p_{k+1} = p_{k+1/2}
                                              + (h/2) f_p(q_{k+1})
   and f_p(q_{k+1}) is kept for the next step's first half kick.  Two calls a
   step (plus one at a fresh start).  A is evaluated at the midpoint time:
   for a time-independent T this changes nothing, for T(t, p) it keeps the
   step symmetric.

   Error estimate (yerr):
     err = y_{k+1} - y_k - (h/2) (f(t_k, y_k) + f(t_{k+1}, y_{k+1})),
   the difference to the trapezoidal rule through the two step points.  Both
   are of order 2 with different O(h^3) local errors, so err = O(h^3)
   (err_order 2).  f(t_{k+1}, y_{k+1}) of an accepted step is the next
   step's f(t_k, y_k) (FSAL): the estimate costs one call a step (the
   separable step then costs three).

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

/* One step: its start, end, the f values known at its ends, p_{k+1/2} and
   f_p(t_{k+1}, q_{k+1}, p_{k+1/2}). */
typedef struct {
  double t, h, tend;
  double *y0, *y1, *f0, *f1;    /* n each */
  double *ph, *fpe;             /* d each */
  int have_f0, have_f1;
} sv_rec;

typedef struct {
  int d, n;
  int separable, want_f;
  sv_rec rec[2];
  sv_rec *cur, *trial;   /* last accepted step, step being tried */
  int have_cur;
  int trial_ok;          /* the last step() succeeded: accept() may take it */
  sym_newton nwp, nwq;   /* equations (1) and (2) */
  double hp_mat, hq_mat; /* h their matrices were built with */
  long xp, xq;           /* iterations beyond NW_BASE charged to them */
  double *block;         /* the one allocation holding the arrays below */
  double *x, *scale, *rv;/* d: Newton unknown, its scale, a residual */
  double *fqa;           /* d: f_q(t_k, q_k, p_{k+1/2}) */
  double *yw, *fw;       /* n: last y where f was evaluated, and f there */
  double tw;
  int have_fw;
  double *ym, *jw;       /* n, n*n: Jacobian work */
  /* the step being solved (for the Newton callbacks) */
  sym_system *sys;
  double tk, hk;
  const double *yk;
  const double *pk;      /* (2): p_{k+1/2} */
} sv_state;

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
eval_at (sv_state *s, double t, const double *a, const double *b)
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

/* Df at (t, [a; b]) into jw.  For finite differences f is evaluated there
   first: the differences need it, and the iteration's first residual then
   finds it in fw. */
static int
jac_at (sv_state *s, double t, const double *a, const double *b)
{
  const int d = s->d;
  int st;
  if (! s->sys->jac)
    {
      if ((st = eval_at (s, t, a, b)))
        return st;
      return sym_jac (s->sys, t, s->yw, s->fw, s->jw);
    }
  memcpy (s->ym, a, (size_t) d * sizeof (double));
  memcpy (s->ym + d, b, (size_t) d * sizeof (double));
  return sym_jac (s->sys, t, s->ym, NULL, s->jw);
}

/* (1): G(P) = P - p_k - (h/2) f_p(t_k, q_k, P) */
static int
res_p (void *ctx, const double *x, double *r)
{
  sv_state *s = ctx;
  const int d = s->d;
  int st = eval_at (s, s->tk, s->yk, x);
  if (st)
    return st;
  const double hh = 0.5 * s->hk;
  for (int i = 0; i < d; i++)
    r[i] = x[i] - s->yk[d + i] - hh * s->fw[d + i];
  return SYM_SUCCESS;
}

static int
mat_p (void *ctx, const double *x, double *a)
{
  sv_state *s = ctx;
  const int d = s->d, n = s->n;
  int st = jac_at (s, s->tk, s->yk, x);
  if (st)
    return st;
  const double hh = 0.5 * s->hk;
  for (int j = 0; j < d; j++)
    for (int i = 0; i < d; i++)
      a[i + (size_t) j * d] = (i == j ? 1.0 : 0.0)
        - hh * s->jw[(d + i) + (size_t) (d + j) * n];
  s->hp_mat = s->hk;
  s->xp = 0;
  return SYM_SUCCESS;
}

/* (2): G(Q) = Q - q_k - (h/2) [f_q(t_k, q_k, P) + f_q(t_{k+1}, Q, P)] */
static int
res_q (void *ctx, const double *x, double *r)
{
  sv_state *s = ctx;
  const int d = s->d;
  int st = eval_at (s, s->tk + s->hk, x, s->pk);
  if (st)
    return st;
  const double hh = 0.5 * s->hk;
  for (int i = 0; i < d; i++)
    r[i] = x[i] - s->yk[i] - hh * s->fqa[i] - hh * s->fw[i];
  return SYM_SUCCESS;
}

static int
mat_q (void *ctx, const double *x, double *a)
{
  sv_state *s = ctx;
  const int d = s->d, n = s->n;
  int st = jac_at (s, s->tk + s->hk, x, s->pk);
  if (st)
    return st;
  const double hh = 0.5 * s->hk;
  for (int j = 0; j < d; j++)
    for (int i = 0; i < d; i++)
      a[i + (size_t) j * d] = (i == j ? 1.0 : 0.0)
        - hh * s->jw[i + (size_t) j * n];
  s->hq_mat = s->hk;
  s->xq = 0;
  return SYM_SUCCESS;
}

static void sv_free (void *state);

static void *
sv_alloc (const sym_system *sys, const sym_method_opts *opts, int *status)
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
  sv_state *s = sym_calloc (1, sizeof (*s));
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
  /* rec: 2 x (4n + 2d); x, scale, rv, fqa: 4d; yw, fw, ym: 3n; jw: n*n */
  size_t len = (size_t) 2 * (4 * (size_t) n + 2 * (size_t) d)
               + 4 * (size_t) d + 3 * (size_t) n + (size_t) n * n;
  s->block = sym_calloc (len, sizeof (double));
  if (! s->block || sym_newton_init (&s->nwp, d)
      || sym_newton_init (&s->nwq, d))
    {
      sv_free (s);
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
      s->rec[k].ph = w; w += d;
      s->rec[k].fpe = w; w += d;
    }
  s->x = w; w += d;
  s->scale = w; w += d;
  s->rv = w; w += d;
  s->fqa = w; w += d;
  s->yw = w; w += n;
  s->fw = w; w += n;
  s->ym = w; w += n;
  s->jw = w;
  for (int k = 0; k < 2; k++)
    {
      sym_newton *nw = k ? &s->nwq : &s->nwp;
      if (opts && opts->newton_tol > 0)
        nw->tol = opts->newton_tol;
      if (opts && opts->max_newton > 0)
        nw->maxit = opts->max_newton;
    }
  s->cur = &s->rec[0];
  s->trial = &s->rec[1];
  *status = SYM_SUCCESS;
  return s;
}

static void
sv_free (void *state)
{
  sv_state *s = state;
  if (! s)
    return;
  /* safe on a zeroed struct too */
  sym_newton_free (&s->nwq);
  sym_newton_free (&s->nwp);
  sym_free (s->block);
  sym_free (s);
}

/* Solve one of the implicit equations from x (s->x); then fw holds f at
   the solution.  newton.c may stop after a single iteration, judging by the
   contraction rate of an earlier solve (measured: up to 1e-10 off); the f
   needed at the solution gives the residual there for free, which checks
   that a posteriori, and a failed check goes on iterating from there, its
   first residual already known, with the contraction rate that residual
   shows (at most three solves).  A last correction at round-off level
   needs neither. */
static int
solve (sv_state *s, sym_newton *nw, double *h_mat, long *extra,
       const sym_newton_problem *prob, double sc)
{
  const int d = s->d;
  if (nw->have_matrix && fabs (s->hk - *h_mat) > 0.2 * fabs (*h_mat))
    sym_newton_invalidate (nw);
  if (! (sc > 0.0))
    sc = 1.0;
  for (int i = 0; i < d; i++)
    s->scale[i] = sc;
  for (int round = 0; round < 3; round++)
    {
      int st = sym_newton_solve (nw, prob, s->x, s->scale, &s->sys->cnt);
      if (st)
        {
          sym_newton_invalidate (nw);
          return st;
        }
      if (nw->iters > NW_BASE)
        {
          *extra += nw->iters - NW_BASE;
          if (*extra >= (s->sys->jac ? 1 : s->n))
            sym_newton_invalidate (nw);
        }
      /* fw: f at the previous iterate, a round-off step away */
      if (norm_inf (d, nw->dx) <= 4.0 * DBL_EPSILON * sc)
        return SYM_SUCCESS;
      if ((st = prob->residual (prob->ctx, s->x, s->rv)))
        return st;
      double rn = norm_inf (d, s->rv);
      if (rn <= fmax (4.0 * nw->tol, 8.0 * DBL_EPSILON) * sc)
        return SYM_SUCCESS;
      /* the residual is about the next correction: the rate it shows
         replaces the one newton.c trusted */
      double th = rn / fmax (norm_inf (d, nw->dx), DBL_MIN);
      nw->eta = th < 0.5 ? th / (1.0 - th) : 1.0;
    }
  return SYM_SUCCESS;   /* three solves claimed convergence: take it */
}

static int
sv_step (void *state, sym_system *sys, double t, double h, const double *y,
         double *ynext, double *yerr)
{
  sv_state *s = state;
  int st;
  if (! s || ! sys || ! y || ! ynext || ! isfinite (t) || ! isfinite (h)
      || h == 0.0)
    return SYM_EBADINPUT;
  const int d = s->d, n = s->n;
  s->trial_ok = 0;
  sv_rec *tr = s->trial, *cu = s->cur;
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
  double *q1 = tr->y1, *p1 = tr->y1 + d, *ph = tr->ph;
  const double hh = 0.5 * h;
  s->sys = sys;
  s->tk = t;
  s->hk = h;
  s->yk = tr->y0;

  if (s->separable)
    {
      const double *fp;
      if (cont)
        fp = cu->fpe;
      else
        {
          if (! tr->have_f0)
            {
              st = sym_rhs (sys, t, tr->y0, tr->f0);
              if (st)
                return st;
              tr->have_f0 = 1;
            }
          fp = tr->f0 + d;
        }
      for (int i = 0; i < d; i++)
        ph[i] = p0[i] + hh * fp[i];
      st = eval_at (s, t + hh, q0, ph);                   /* A */
      if (st)
        return st;
      for (int i = 0; i < d; i++)
        q1[i] = q0[i] + h * s->fw[i];
      st = eval_at (s, tr->tend, q1, ph);                 /* B */
      if (st)
        return st;
      for (int i = 0; i < d; i++)
        {
          tr->fpe[i] = s->fw[d + i];
          p1[i] = ph[i] + hh * s->fw[d + i];
        }
    }
  else
    {
      double *x = s->x;
      double sc = 0.0;
      /* (1) */
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
              x[i] = p0[i] + hh * tr->f0[d + i];
          else   /* cont: the last step's first half kick, rescaled */
            for (int i = 0; i < d; i++)
              x[i] = p0[i] + (p0[i] - cu->ph[i]) * (h / cu->h);
          sc = norm_inf (d, p0);
          for (int i = 0; i < d; i++)
            sc = fmax (sc, fabs (x[i] - p0[i]));
          if (sc > 0.0 || tr->have_f0)
            break;
        }
      sym_newton_problem pp = { res_p, mat_p, s };
      st = solve (s, &s->nwp, &s->hp_mat, &s->xp, &pp, sc);
      if (st)
        return st;
      memcpy (ph, x, (size_t) d * sizeof (double));
      memcpy (s->fqa, s->fw, (size_t) d * sizeof (double));
      /* (2) */
      s->pk = ph;
      for (int i = 0; i < d; i++)
        x[i] = q0[i] + h * s->fqa[i];
      sc = norm_inf (d, q0);
      for (int i = 0; i < d; i++)
        sc = fmax (sc, fabs (x[i] - q0[i]));
      sym_newton_problem pq = { res_q, mat_q, s };
      st = solve (s, &s->nwq, &s->hq_mat, &s->xq, &pq, sc);
      if (st)
        return st;
      memcpy (q1, x, (size_t) d * sizeof (double));
      /* (3) */
      for (int i = 0; i < d; i++)
        {
          tr->fpe[i] = s->fw[d + i];
          p1[i] = ph[i] + hh * s->fw[d + i];
        }
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
      yerr[i] = (tr->y1[i] - tr->y0[i]) - hh * (tr->f0[i] + tr->f1[i]);
  memcpy (ynext, tr->y1, (size_t) n * sizeof (double));
  s->trial_ok = 1;
  return SYM_SUCCESS;
}

static void
sv_accept (void *state)
{
  sv_state *s = state;
  if (! s->trial_ok)   /* nothing to accept */
    return;
  sv_rec *r = s->cur;
  s->cur = s->trial;
  s->trial = r;
  s->have_cur = 1;
  s->trial_ok = 0;
}

static int
sv_dense (void *state, sym_system *sys, double t, double *y)
{
  sv_state *s = state;
  (void) sys;
  if (! s || ! y || ! s->have_cur || ! isfinite (t))
    return SYM_EBADINPUT;
  const sv_rec *c = s->cur;
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
sv_reset (void *state)
{
  sv_state *s = state;
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
sv_order (const void *state)
{
  (void) state;
  return 2;
}

static const sym_stepper_type sv_type = {
  "sv", 2, sv_order, sv_order, sv_alloc, sv_step, sv_accept, sv_dense,
  sv_reset, sv_free
};

const sym_stepper_type *const sym_step_sv = &sv_type;
