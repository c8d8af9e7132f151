/* step_spvi.c -- the spectral variational integrator (odeSPVI).

   The method.  One step [t_k, t_k + h]; z in [-1, 1], t(z) = t_k +
   (h/2)(z + 1); y = [q; p], f = [f_q; f_p] (f_q = dH/dp, f_p = -dH/dq +
   forcing).  n = Q_DoFs Legendre modes for q, m = Nodes Gauss-Legendre
   nodes z_j, weights w_j:
     q(z) = sum_{i<n} a_i l_i(z),  nodal momenta P_j,  Q_j = q(z_j),
     f_j = f(t(z_j), Q_j, P_j).
   Stationarity of the discrete action (h/2) sum_j w_j L(q(z_j), q'(z_j))
   with q(-1) = q_k, q(1) = q_{k+1}, in Hamiltonian form:
    (E1) s < n: sum_j w_j [P_j l_s'(z_j) + (h/2) l_s(z_j) f_p,j]
                + l_s(-1) p_k - l_s(1) p_{k+1} = 0
    (E2) r < m: f_q,r - (2/h) sum_i a_i l_i'(z_r) = 0
    (E3) sum_i a_i l_i(-1) = q_k,  q_{k+1} = sum_i a_i l_i(1).

   Reduced system.  E1 with s = 0 gives p_{k+1} = p_k + (h/2) sum_j w_j
   f_p,j explicitly, and E3 gives a_0, so with phi_i(z) = l_i(z) -
   l_i(-1):  q(z) = q_k + sum_{i>=1} a_i phi_i(z),  q_{k+1} = q_k +
   sum_{i>=1} a_i (1 - (-1)^i).  The unknowns, per dimension, are
   x = (a_1..a_{n-1}, P_1..P_m); the equations (s = 1..n-1, r = 1..m):
    (R1) sum_j w_j l_s'(z_j) (P_j - p_k) + (h/2) sum_j g_sj f_p,j = 0,
         g_sj = w_j (l_s(z_j) - 1)
    (R2) (h/2) f_q,r - sum_i a_i l_i'(z_r) = 0.
   R1 is E1 with p_{k+1} substituted and sum_j w_j l_s'(z_j) = 1 - (-1)^s
   (exact: degree s - 1 <= 2m - 1) used to write it in P_j - p_k: its terms
   are then O(h) and their round-off is relative to the increments, not to
   |p|.  R2 is E2 times h/2, so both blocks of the Newton matrix are O(1)
   with O(h) couplings:
     dR1_s/dP_j = w_j l_s'(z_j) I + (h/2) g_sj App_j
     dR1_s/da_i = (h/2) sum_j g_sj phi_i(z_j) Apq_j
     dR2_r/dP_j = delta_rj (h/2) Aqp_r
     dR2_r/da_i = (h/2) phi_i(z_r) Aqq_r - l_i'(z_r) I
   with A_j = Df(t_j, Q_j, P_j) = [Aqq Aqp; Apq App].  (For n - 1 != m the
   h -> 0 limit of this matrix is singular: the O(h) terms carry the
   information, an intrinsic 1/h or 1/h^2 conditioning of those pairs.)
   Order 2 min(n - 1, 2m - n + 1); n > 2m does not converge and is refused;
   (n, m) = (s + 1, s) is s-stage Gauss collocation, (2, 1) the implicit
   midpoint rule.

   Solution: sym_newton (simplified Newton, LU kept across iterations and
   steps while it converges fast; rebuilt when h changed by > 20% since it
   depends on h, and after a solve that needed more than 3 iterations),
   then one more correction with the residual at the converged x, whose f
   values also give p_{k+1} (see core_solve).  If the simplified iteration
   fails, full Newton from the same start.  One sym_rhs_many call (m
   states) per residual, so the Vectorized batch callback serves all nodes
   at once.

   Predictor: the previous accepted step's polynomials extrapolated (q
   from its Legendre series, re-expanded exactly in the new step by a
   Gauss transform; p from its interpolant through p_k, P_j, p_{k+1}); on
   a first step, after reset, or for the pairs n - 1 > m (whose extra q
   modes do not extrapolate), one explicit Euler estimate: measured, it
   saves 0.6-1.1 iterations per step over the constant start (a_i = 0,
   P_j = p_k) for its one rhs call.

   Error estimate: the companion solution on the same step with (n + 1,
   m + 1), its own quadrature, Newton state and LU, started from the
   low-order polynomials; yerr = y_low - y_companion = O(h^(order+1)).

   Dense output: q from the Legendre series of the last accepted step, p
   from the polynomial through (-1, p_k), (z_j, P_j), (1, p_{k+1}). */
#include "sym.h"

#include <float.h>
#include <math.h>
#include <string.h>

/* A solve that took more than this many iterations asks for a fresh
   matrix at the next step (measured on Kepler (4,3): 3 saves a quarter of
   the iterations for 0.14 matrices per step; see core_solve). */
#define SPVI_REFRESH_ITERS 3
#define SPVI_MAX_DOFS 100

/* One (n, m) discretization with its own Newton solver: the method, and
   (n + 1, m + 1) for the error estimate. */
typedef struct {
  int n, m, d, N;      /* N = (n - 1 + m) d unknowns */
  double *z, *w;       /* nodes, weights */
  double *phi;         /* phi[j*n + i] = l_i(z_j) - l_i(-1) */
  double *dl;          /* dl[j*n + i] = l_i'(z_j) */
  double *wdl;         /* w_j l_i'(z_j) */
  double *g;           /* w_j (l_i(z_j) - 1) */
  double *xb, *bw;     /* -1, z_1..z_m, 1 and their barycentric weights */
  double *A;           /* node Jacobians, (2d)^2 each, of the kept matrix */
  double *Y, *F, *tj;  /* node states and f values (2d x m), node times */
  double *xf;          /* the x at which F was evaluated */
  int fvalid;
  double *x, *scale, *x0;
  sym_newton nw;
  double h_mat;        /* h of the kept matrix */
  int cb_fail;         /* status of a failed callback in the matrix */
  /* the step being solved, for the callbacks */
  sym_system *sys;
  double t, h;
  const double *yk;
} spvi_core;

/* A step: where it started, its end, its polynomials. */
typedef struct {
  double t, h, tend;
  double *y0, *y1;     /* 2d each */
  double *a;           /* a_1..a_{n-1}: a[(i-1)*d + k] */
  double *P;           /* P[j*d + k] */
} spvi_rec;

typedef struct {
  int d, n, m, order;
  double tol;
  int maxit;
  spvi_core lo, hi;
  int have_hi;
  spvi_rec rec[2];
  spvi_rec *cur, *trial;
  int have_cur, trial_ok;
  double *xi, *vinv;   /* n Gauss points; a_i = sum_l vinv[i*n+l] v(xi_l) */
  double *f0;          /* 2d: f(t_k, y_k) for the Euler start */
  double *lv, *dlv;    /* n + 1: Legendre values (work) */
  double *cb;          /* m + 2: Lagrange basis values (work) */
  double *vq;          /* n d: values of q (work) */
} spvi_state;

/* ---------------------------------------------------------------- core */

static void
core_free (spvi_core *c)
{
  sym_newton_free (&c->nw);
  double **p[] = { &c->z, &c->w, &c->phi, &c->dl, &c->wdl, &c->g, &c->xb,
                   &c->bw, &c->A, &c->Y, &c->F, &c->tj, &c->xf, &c->x,
                   &c->scale, &c->x0 };
  for (size_t i = 0; i < sizeof p / sizeof p[0]; i++)
    {
      sym_free (*p[i]);
      *p[i] = NULL;
    }
}

/* Barycentric weights of the points x_0..x_{np-1}. */
static void
bary_weights (int np, const double *x, double *bw)
{
  for (int i = 0; i < np; i++)
    {
      double p = 1.0;
      for (int k = 0; k < np; k++)
        if (k != i)
          p *= x[i] - x[k];
      bw[i] = 1.0 / p;
    }
}

/* Values c_i = L_i(x) of the Lagrange basis: the first barycentric form
   (backward stable, also outside the points, where the predictor uses
   it). */
static void
lagrange_basis (int np, const double *xb, const double *bw, double x,
                double *c)
{
  double l = 1.0;
  for (int i = 0; i < np; i++)
    {
      if (x == xb[i])
        {
          for (int k = 0; k < np; k++)
            c[k] = k == i;
          return;
        }
      l *= x - xb[i];
    }
  for (int i = 0; i < np; i++)
    c[i] = l * bw[i] / (x - xb[i]);
}

static int
core_init (spvi_core *c, int d, int n, int m)
{
  memset (c, 0, sizeof (*c));
  c->n = n;
  c->m = m;
  c->d = d;
  c->N = (n - 1 + m) * d;
  size_t nn = 2 * (size_t) d, nm = (size_t) n * m;
  c->z = sym_calloc (m, sizeof (double));
  c->w = sym_calloc (m, sizeof (double));
  c->phi = sym_calloc (nm, sizeof (double));
  c->dl = sym_calloc (nm, sizeof (double));
  c->wdl = sym_calloc (nm, sizeof (double));
  c->g = sym_calloc (nm, sizeof (double));
  c->xb = sym_calloc (m + 2, sizeof (double));
  c->bw = sym_calloc (m + 2, sizeof (double));
  c->A = sym_calloc (nn * nn * m, sizeof (double));
  c->Y = sym_calloc (nn * m, sizeof (double));
  c->F = sym_calloc (nn * m, sizeof (double));
  c->tj = sym_calloc (m, sizeof (double));
  c->xf = sym_calloc (c->N, sizeof (double));
  c->x = sym_calloc (c->N, sizeof (double));
  c->scale = sym_calloc (c->N, sizeof (double));
  c->x0 = sym_calloc (c->N, sizeof (double));
  double *l = sym_calloc (2 * (size_t) n, sizeof (double));
  int st = SYM_ENOMEM;
  if (! c->z || ! c->w || ! c->phi || ! c->dl || ! c->wdl || ! c->g
      || ! c->xb || ! c->bw || ! c->A || ! c->Y || ! c->F || ! c->tj
      || ! c->xf || ! c->x || ! c->scale || ! c->x0 || ! l)
    goto fail;
  if ((st = sym_newton_init (&c->nw, c->N)))
    goto fail;
  if ((st = sym_gauss_legendre (m, c->z, c->w)))
    goto fail;
  for (int j = 0; j < m; j++)
    {
      sym_legendre (n, c->z[j], l, l + n);
      for (int i = 0; i < n; i++)
        {
          double lm1 = (i % 2) ? -1.0 : 1.0;     /* l_i(-1) */
          c->phi[j * n + i] = l[i] - lm1;
          c->dl[j * n + i] = l[n + i];
          c->wdl[j * n + i] = c->w[j] * l[n + i];
          c->g[j * n + i] = c->w[j] * (l[i] - 1.0);
        }
    }
  c->xb[0] = -1.0;
  for (int j = 0; j < m; j++)
    c->xb[j + 1] = c->z[j];
  c->xb[m + 1] = 1.0;
  bary_weights (m + 2, c->xb, c->bw);
  sym_free (l);
  return SYM_SUCCESS;

fail:
  sym_free (l);
  core_free (c);
  return st;
}

/* Node states Y_j = [Q_j; P_j] from x. */
static void
core_states (spvi_core *c, const double *x)
{
  const int d = c->d, n = c->n, m = c->m;
  const double *a = x, *P = x + (size_t) (n - 1) * d;
  for (int j = 0; j < m; j++)
    {
      double *yj = c->Y + (size_t) j * 2 * d;
      const double *phij = c->phi + (size_t) j * n;
      for (int k = 0; k < d; k++)
        {
          double s = 0.0;
          for (int i = 1; i < n; i++)
            s += phij[i] * a[(size_t) (i - 1) * d + k];
          yj[k] = c->yk[k] + s;
          yj[d + k] = P[(size_t) j * d + k];
        }
    }
}

/* F = f at the nodes of x (one batch call), cached by x. */
static int
core_eval (spvi_core *c, const double *x)
{
  size_t nb = (size_t) c->N * sizeof (double);
  if (c->fvalid && memcmp (c->xf, x, nb) == 0)
    return SYM_SUCCESS;
  c->fvalid = 0;
  core_states (c, x);
  int st = sym_rhs_many (c->sys, c->m, c->tj, c->Y, c->F);
  if (st)
    return st;
  memcpy (c->xf, x, nb);
  c->fvalid = 1;
  return SYM_SUCCESS;
}

static int
core_residual (void *ctx, const double *x, double *r)
{
  spvi_core *c = ctx;
  const int d = c->d, n = c->n, m = c->m, nn = 2 * d;
  const double *a = x, *P = x + (size_t) (n - 1) * d, *pk = c->yk + d;
  const double hh = 0.5 * c->h;
  int st = core_eval (c, x);
  if (st)
    return st;
  for (int s = 1; s < n; s++)
    for (int k = 0; k < d; k++)
      {
        double s1 = 0.0, s2 = 0.0;
        for (int j = 0; j < m; j++)
          {
            s1 += c->wdl[j * n + s] * (P[(size_t) j * d + k] - pk[k]);
            s2 += c->g[j * n + s] * c->F[(size_t) j * nn + d + k];
          }
        r[(size_t) (s - 1) * d + k] = s1 + hh * s2;
      }
  double *r2 = r + (size_t) (n - 1) * d;
  for (int j = 0; j < m; j++)
    for (int k = 0; k < d; k++)
      {
        double s1 = 0.0;
        for (int i = 1; i < n; i++)
          s1 += c->dl[j * n + i] * a[(size_t) (i - 1) * d + k];
        r2[(size_t) j * d + k] = hh * c->F[(size_t) j * nn + k] - s1;
      }
  return SYM_SUCCESS;
}

/* The node Jacobian block used for node j. */
static const double *
core_A (const spvi_core *c, int j)
{
  size_t nn = 2 * (size_t) c->d;
  return c->A + (size_t) j * nn * nn;
}

static void core_fill (spvi_core *c, double *M);

static int
core_matrix (void *ctx, const double *x, double *M)
{
  spvi_core *c = ctx;
  const int m = c->m;
  const size_t nn = 2 * (size_t) c->d;
  int st;
  /* Finite differences need f at the nodes: evaluate it once here (one
     batch call), and the residual at this x reuses it. */
  if (! c->sys->jac)
    {
      if ((st = core_eval (c, x)))
        return c->cb_fail = st;
    }
  else
    core_states (c, x);
  /* One Jacobian per node: also measured, one at the middle node for all
     (m times fewer jac calls per matrix, but slower contraction and, on
     Kepler (4,3), as many calls in all); the exact matrix also keeps the
     full-Newton fallback quadratic. */
  for (int j = 0; j < m; j++)
    {
      st = sym_jac (c->sys, c->tj[j], c->Y + j * nn,
                    c->sys->jac ? NULL : c->F + j * nn, c->A + j * nn * nn);
      if (st)
        return c->cb_fail = st;
    }
  core_fill (c, M);
  return SYM_SUCCESS;
}

/* The Newton matrix from the node Jacobians in c->A and the step c->h. */
static void
core_fill (spvi_core *c, double *M)
{
  const int d = c->d, n = c->n, m = c->m, N = c->N;
  const size_t nn = 2 * (size_t) d;
  const double hh = 0.5 * c->h;
  c->h_mat = c->h;
  memset (M, 0, (size_t) N * N * sizeof (double));
#define MAT(row, col) M[(size_t) (col) * N + (row)]
#define AQQ(A, k, l) (A)[(k) + (size_t) (l) * nn]
#define AQP(A, k, l) (A)[(k) + (size_t) (d + (l)) * nn]
#define APQ(A, k, l) (A)[(d + (k)) + (size_t) (l) * nn]
#define APP(A, k, l) (A)[(d + (k)) + (size_t) (d + (l)) * nn]
  const int p0 = (n - 1) * d;     /* first P column, first R2 row */
  for (int s = 1; s < n; s++)
    for (int k = 0; k < d; k++)
      {
        int row = (s - 1) * d + k;
        for (int j = 0; j < m; j++)
          {
            const double *Aj = core_A (c, j);
            double gs = hh * c->g[j * n + s];
            for (int l = 0; l < d; l++)
              MAT (row, p0 + j * d + l) = gs * APP (Aj, k, l)
                                          + (k == l ? c->wdl[j * n + s] : 0);
          }
        for (int i = 1; i < n; i++)
          for (int l = 0; l < d; l++)
            {
              double v = 0.0;
              for (int j = 0; j < m; j++)
                v += c->g[j * n + s] * c->phi[j * n + i]
                     * APQ (core_A (c, j), k, l);
              MAT (row, (i - 1) * d + l) = hh * v;
            }
      }
  for (int r = 0; r < m; r++)
    {
      const double *Ar = core_A (c, r);
      for (int k = 0; k < d; k++)
        {
          int row = p0 + r * d + k;
          for (int l = 0; l < d; l++)
            MAT (row, p0 + r * d + l) = hh * AQP (Ar, k, l);
          for (int i = 1; i < n; i++)
            for (int l = 0; l < d; l++)
              MAT (row, (i - 1) * d + l) = hh * c->phi[r * n + i]
                                           * AQQ (Ar, k, l)
                                           - (k == l ? c->dl[r * n + i] : 0);
        }
    }
#undef MAT
}

/* Newton's method with a new matrix at every iterate: the fallback when
   the simplified iteration fails.  Needed by the pairs n - 1 > m, whose
   equations are nearly singular where the potential's curvature is small
   (the modes invisible to the kinetic quadrature are fixed by it alone),
   so that a stale matrix can make the simplified iteration diverge (the
   pendulum with (4,2) near q = pi/2, h = 0.5).  Same stopping test as
   sym_newton; an iteration that stagnates near round-off (those pairs are
   ill-conditioned) is accepted there. */
static int
core_full_newton (spvi_core *c, sym_system *sys)
{
  sym_newton *nw = &c->nw;
  const int N = c->N;
  const double floor_tol = 16.0 * DBL_EPSILON;
  double dxold = 0.0, eta = 1.0, theta = 0.0;
  int st;
  nw->iters = 0;
  for (int k = 0; k < nw->maxit; k++)
    {
      nw->have_matrix = 0;
      st = core_matrix (c, c->x, nw->lu.a);
      if (st)
        return st;
      if (sym_lu_factor (&nw->lu, &sys->cnt))
        return SYM_NEWTON_FAIL;
      nw->have_matrix = 1;
      if ((st = core_residual (c, c->x, nw->r)))
        return st;
      for (int i = 0; i < N; i++)
        nw->dx[i] = -nw->r[i];
      if ((st = sym_lu_solve (&nw->lu, nw->dx, &sys->cnt)))
        return st;
      double dxn = 0.0;
      for (int i = 0; i < N; i++)
        {
          c->x[i] += nw->dx[i];
          double a = fabs (nw->dx[i]) / c->scale[i];
          if (a > dxn || isnan (a))
            dxn = a;
        }
      sys->cnt.nnewton++;
      nw->iters++;
      if (! isfinite (dxn))
        break;
      if (k > 0)
        {
          theta = dxn / fmax (dxold, DBL_MIN);
          if (theta >= 0.5 && dxn <= fmax (nw->tol, 1e3 * floor_tol))
            {
              nw->theta = theta;         /* round-off level */
              nw->eta = 1.0;
              return SYM_SUCCESS;
            }
          if (theta >= 1.0)
            break;
          eta = theta / (1.0 - theta);
        }
      if ((k > 0 && eta * dxn <= nw->tol) || dxn <= floor_tol)
        {
          nw->theta = theta;
          nw->eta = eta;
          return SYM_SUCCESS;
        }
      dxold = dxn;
    }
  sys->cnt.nnewton_fail++;
  nw->have_matrix = 0;
  return SYM_NEWTON_FAIL;
}

/* Solve the step (t, h, yk) from the start c->x; on success c->x holds
   the solution and yend = [q_{k+1}; p_{k+1}].  polish: the final
   correction below (the method's step; the companion of the error
   estimate does without it: its result only enters a difference). */
static int
core_solve (spvi_core *c, sym_system *sys, double t, double h,
            const double *yk, double S, const spvi_state *s, int polish,
            double *yend)
{
  const int d = c->d, n = c->n, m = c->m, N = c->N;
  const size_t nn = 2 * (size_t) d;
  const double hh = 0.5 * h;
  c->sys = sys;
  c->t = t;
  c->h = h;
  c->yk = yk;
  c->fvalid = 0;
  for (int j = 0; j < m; j++)
    c->tj[j] = t + hh * (c->z[j] + 1.0);
  /* The matrix depends on h: a new one when h changed by more than 20%.
     Measured on adaptive Kepler (4,3), rtol 1e-6..1e-12, rhs + jac calls:
     rebuilding it instead from the kept node Jacobians (a new LU only, as
     RADAU5 does) saves jac calls but costs as many more iterations (+0..4%
     in all; -2% with finite-difference Jacobians); never invalidating on h
     costs +0..10%. */
  if (c->nw.have_matrix && ! (fabs (h - c->h_mat) <= 0.2 * fabs (c->h_mat)))
    sym_newton_invalidate (&c->nw);
  for (int i = 0; i < N; i++)
    c->scale[i] = S;
  c->nw.tol = s->tol;
  c->nw.maxit = s->maxit;
  sym_newton_problem prob = { core_residual, core_matrix, c };
  memcpy (c->x0, c->x, (size_t) N * sizeof (double));
  c->cb_fail = 0;
  int st = sym_newton_solve (&c->nw, &prob, c->x, c->scale, &sys->cnt);
  /* sym_newton reports a recoverable failure of the matrix callback as
     SYM_NEWTON_FAIL: pass the callback's own status on instead (and do
     not retry: it asked for a smaller step) */
  if (st == SYM_NEWTON_FAIL && c->cb_fail > 0)
    st = c->cb_fail;
  if (st == SYM_NEWTON_FAIL)
    {
      memcpy (c->x, c->x0, (size_t) N * sizeof (double));
      st = core_full_newton (c, sys);
    }
  if (! st && polish)
    st = core_residual (c, c->x, c->nw.r);
  if (st)
    {
      c->fvalid = 0;
      return st;
    }
  /* The end of the step must be exact to round-off, and p_{k+1} needs f_p
     at the final x, not at the iterate before it.  Measured on Kepler
     (4,3), h = 2 pi/100, 1000 periods, relative drift of the angular
     momentum (an exact invariant of the method, so it shows what the
     iteration leaves): f_p moved to the final x linearly by the node
     Jacobians, no extra call: 5e-11; f evaluated at the final x (one more
     rhs_many): 5e-13; that evaluation used as one more simplified Newton
     correction, with f_p moved linearly to the corrected x (what is done
     here; same cost): 5e-14, the round-off level (4e-14 with tol 1e-18). */
  if (polish)
    {
      for (int i = 0; i < N; i++)
        c->nw.dx[i] = -c->nw.r[i];
      if ((st = sym_lu_solve (&c->nw.lu, c->nw.dx, &sys->cnt)))
        return st;
      for (int i = 0; i < N; i++)
        c->x[i] += c->nw.dx[i];
      sys->cnt.nnewton++;
    }
  /* Fresh matrix for the next step after a slow solve (RADAU5 refreshes
     its Jacobian when theta > 1e-3; counting iterations is the cheaper
     rule here: on Kepler (4,3) 4.07 iterations and 12.6 calls per step,
     against 5.03 and 15.1 with the matrix of the first step kept
     throughout, 4.39 and 13.4 with the theta rule). */
  if (c->nw.iters > SPVI_REFRESH_ITERS)
    sym_newton_invalidate (&c->nw);

  /* F is at xf, the iterate before the last correction: f_p += Apq dQ +
     App dP (the node Jacobians of the kept matrix; the correction is
     tiny, so their age does not matter). */
  const double *a = c->x, *P = c->x + (size_t) (n - 1) * d;
  for (int j = 0; j < m; j++)
    {
      const double *Aj = core_A (c, j);
      double *Fj = c->F + (size_t) j * nn;
      double *dy = c->Y + (size_t) j * nn;      /* work */
      for (int k = 0; k < d; k++)
        {
          double v = 0.0;
          for (int i = 1; i < n; i++)
            v += c->phi[j * n + i] * (a[(size_t) (i - 1) * d + k]
                                      - c->xf[(size_t) (i - 1) * d + k]);
          dy[k] = v;
          dy[d + k] = P[(size_t) j * d + k]
                      - c->xf[(size_t) (n - 1) * d + (size_t) j * d + k];
        }
      for (int k = 0; k < d; k++)
        {
          double v = 0.0;
          for (int l = 0; l < d; l++)
            v += APQ (Aj, k, l) * dy[l] + APP (Aj, k, l) * dy[d + l];
          Fj[d + k] += v;
        }
    }
  c->fvalid = 0;   /* F no longer matches xf */

  for (int k = 0; k < d; k++)
    {
      double dqk = 0.0, dpk = 0.0;
      for (int i = 1; i < n; i += 2)
        dqk += 2.0 * a[(size_t) (i - 1) * d + k];
      for (int j = 0; j < m; j++)
        dpk += c->w[j] * c->F[(size_t) j * nn + d + k];
      yend[k] = yk[k] + dqk;
      yend[d + k] = yk[d + k] + hh * dpk;
    }
  return SYM_SUCCESS;
}
#undef AQQ
#undef AQP
#undef APQ
#undef APP

/* ---------------------------------------------------------------- state */

static void
rec_free (spvi_rec *r)
{
  sym_free (r->y0);
  sym_free (r->y1);
  sym_free (r->a);
  sym_free (r->P);
  r->y0 = r->y1 = r->a = r->P = NULL;
}

static int
rec_init (spvi_rec *r, int d, int n, int m)
{
  memset (r, 0, sizeof (*r));
  r->y0 = sym_calloc (2 * (size_t) d, sizeof (double));
  r->y1 = sym_calloc (2 * (size_t) d, sizeof (double));
  r->a = sym_calloc ((size_t) (n - 1) * d, sizeof (double));
  r->P = sym_calloc ((size_t) m * d, sizeof (double));
  if (! r->y0 || ! r->y1 || ! r->a || ! r->P)
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
  core_free (&s->lo);
  core_free (&s->hi);
  rec_free (&s->rec[0]);
  rec_free (&s->rec[1]);
  sym_free (s->xi);
  sym_free (s->vinv);
  sym_free (s->f0);
  sym_free (s->lv);
  sym_free (s->dlv);
  sym_free (s->cb);
  sym_free (s->vq);
  sym_free (s);
}

static int
spvi_order (int n, int m)
{
  int a = n - 1, b = 2 * m - n + 1;
  return 2 * (a < b ? a : b);
}

static void *
spvi_alloc (const sym_system *sys, const sym_method_opts *opts, int *status)
{
  int dummy;
  if (! status)
    status = &dummy;
  /* 0: the defaults, Nodes = 3, Q_DoFs = Nodes + 1 */
  int m = opts && opts->nodes ? opts->nodes : 3;
  int n = opts && opts->q_dofs ? opts->q_dofs : m + 1;
  /* n > 2m: the quadrature cannot see the top modes and the iteration
     does not converge; also n < 2 (no motion) */
  if (! sys || sys->dim < 1 || ! sys->rhs || n < 2 || m < 1 || n > 2 * m
      || n > SPVI_MAX_DOFS || m > SPVI_MAX_DOFS
      || (opts && (opts->newton_tol < 0 || opts->max_newton < 0
                   || ! (opts->newton_tol < 1.0))))
    {
      *status = SYM_EBADINPUT;
      return NULL;
    }
  const int d = sys->dim;
  spvi_state *s = sym_calloc (1, sizeof (*s));
  if (! s)
    {
      *status = SYM_ENOMEM;
      return NULL;
    }
  s->d = d;
  s->n = n;
  s->m = m;
  s->order = spvi_order (n, m);
  s->tol = opts && opts->newton_tol > 0 ? opts->newton_tol : 1e-14;
  s->maxit = opts && opts->max_newton > 0 ? opts->max_newton : 10;
  int st = core_init (&s->lo, d, n, m);
  if (! st && opts && opts->want_error)
    {
      st = core_init (&s->hi, d, n + 1, m + 1);
      s->have_hi = ! st;
    }
  if (! st)
    st = rec_init (&s->rec[0], d, n, m);
  if (! st)
    st = rec_init (&s->rec[1], d, n, m);
  if (! st)
    {
      s->xi = sym_calloc (n, sizeof (double));
      s->vinv = sym_calloc ((size_t) n * n, sizeof (double));
      s->f0 = sym_calloc (2 * (size_t) d, sizeof (double));
      s->lv = sym_calloc (n + 2, sizeof (double));
      s->dlv = sym_calloc (n + 2, sizeof (double));
      s->cb = sym_calloc (m + 3, sizeof (double));
      s->vq = sym_calloc ((size_t) n * d, sizeof (double));
      if (! s->xi || ! s->vinv || ! s->f0 || ! s->lv || ! s->dlv || ! s->cb
          || ! s->vq)
        st = SYM_ENOMEM;
    }
  /* The Gauss transform: for a polynomial v of degree < n,
     a_i = (2i+1)/2 sum_l w_l v(xi_l) l_i(xi_l) (exact, the products have
     degree <= 2n - 2).  It is the inverse of the Legendre-Vandermonde
     matrix at the n Gauss points. */
  double *wl = NULL;
  if (! st && ! (wl = sym_calloc (n, sizeof (double))))
    st = SYM_ENOMEM;
  if (! st)
    st = sym_gauss_legendre (n, s->xi, wl);
  if (! st)
    for (int l = 0; l < n; l++)
      {
        sym_legendre (n, s->xi[l], s->lv, s->dlv);
        for (int i = 0; i < n; i++)
          s->vinv[i * n + l] = 0.5 * (2 * i + 1) * wl[l] * s->lv[i];
      }
  sym_free (wl);
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

static double
inf_norm (int n, const double *v)
{
  double m = 0.0;
  for (int i = 0; i < n; i++)
    m = fmax (m, fabs (v[i]));
  return m;
}

/* The momentum polynomial of step r (through (-1, p_k), (z_j, P_j),
   (1, p_{k+1})) at z, into p (d values). */
static void
rec_p (const spvi_state *s, const spvi_rec *r, double z, double *p)
{
  const int d = s->d, m = s->m;
  lagrange_basis (m + 2, s->lo.xb, s->lo.bw, z, s->cb);
  for (int k = 0; k < d; k++)
    {
      double v = s->cb[0] * r->y0[d + k] + s->cb[m + 1] * r->y1[d + k];
      for (int j = 0; j < m; j++)
        v += s->cb[j + 1] * r->P[(size_t) j * d + k];
      p[k] = v;
    }
}

/* q(z) - q_k of step r, into q (d values). */
static void
rec_dq (const spvi_state *s, const spvi_rec *r, double z, double *q)
{
  const int d = s->d, n = s->n;
  sym_legendre (n, z, s->lv, s->dlv);
  for (int k = 0; k < d; k++)
    {
      double v = 0.0;
      for (int i = 1; i < n; i++)
        v += r->a[(size_t) (i - 1) * d + k]
             * (s->lv[i] - ((i % 2) ? -1.0 : 1.0));
      q[k] = v;
    }
}

/* The start of Newton for the step (t, h, y) into s->lo.x; returns the
   scale of the stopping test in *S. */
static int
predict (spvi_state *s, sym_system *sys, double t, double h, const double *y,
         double *S)
{
  const int d = s->d, n = s->n, m = s->m;
  double *a = s->lo.x, *P = s->lo.x + (size_t) (n - 1) * d;
  double ynorm = inf_norm (2 * d, y);
  const spvi_rec *r = s->cur;
  /* n - 1 > m: the q polynomial carries modes that the kinetic
     quadrature cannot see (fixed by the potential's curvature); they do
     not extrapolate (l_3(3) = 63), so those pairs start from Euler. */
  int cont = s->have_cur && n - 1 <= m
             && fabs (t - r->tend) <= 1e-10 * fabs (r->h)
                                      + 4 * DBL_EPSILON * fabs (t);
  for (int k = 0; cont && k < 2 * d; k++)
    cont = fabs (y[k] - r->y1[k]) <= 1e-12 * ynorm;
  double qend = 0.0;
  if (cont)
    {
      /* new z' <-> old z = 1 + rho (z' + 1) */
      double rho = h / r->h;
      for (int l = 0; l < n; l++)
        rec_dq (s, r, 1.0 + rho * (s->xi[l] + 1.0), s->vq + (size_t) l * d);
      /* q(z) - q_{k+1} of the old step; its constant part drops out of
         a_i, i >= 1 */
      for (int i = 1; i < n; i++)
        for (int k = 0; k < d; k++)
          {
            double v = 0.0;
            for (int l = 0; l < n; l++)
              v += s->vinv[i * n + l]
                   * (s->vq[(size_t) l * d + k] - (r->y1[k] - r->y0[k]));
            a[(size_t) (i - 1) * d + k] = v;
          }
      for (int j = 0; j < m; j++)
        rec_p (s, r, 1.0 + rho * (s->lo.z[j] + 1.0), P + (size_t) j * d);
    }
  else
    {
      /* explicit Euler: q(z) = q_k + (h/2)(z + 1) f_q, p likewise */
      int st = sym_rhs (sys, t, y, s->f0);
      if (st)
        return st;
      for (int k = 0; k < d; k++)
        {
          a[k] = 0.5 * h * s->f0[k];
          for (int i = 2; i < n; i++)
            a[(size_t) (i - 1) * d + k] = 0.0;
          for (int j = 0; j < m; j++)
            P[(size_t) j * d + k] = y[d + k]
                                    + 0.5 * h * (s->lo.z[j] + 1.0)
                                      * s->f0[d + k];
        }
    }
  for (int k = 0; k < d; k++)
    {
      double v = y[k];
      for (int i = 1; i < n; i += 2)
        v += 2.0 * a[(size_t) (i - 1) * d + k];
      qend = fmax (qend, fabs (v));
    }
  /* One scale for all unknowns: the size of the state over the step.  A
     per-component scale cannot be met below the round-off that f's
     coupling carries from the large components into the small ones (the
     iteration would stagnate and fail), and the a_i (increments of q) and
     P_j are all measured against it: q_{k+1} and p_{k+1} are then
     converged to tol relative to |y|. */
  double sc = fmax (ynorm, fmax (qend, inf_norm (m * d, P)));
  *S = sc > 0 ? sc : 1.0;
  return SYM_SUCCESS;
}

static int
spvi_step (void *state, sym_system *sys, double t, double h, const double *y,
           double *ynext, double *yerr)
{
  spvi_state *s = state;
  const int d = s->d, n = s->n, m = s->m, nn = 2 * d;
  s->trial_ok = 0;
  if (! (h != 0.0) || ! isfinite (h) || ! isfinite (t))
    return SYM_EBADINPUT;
  if (yerr && ! s->have_hi)
    {
      int st = core_init (&s->hi, d, n + 1, m + 1);
      if (st)
        return st;
      s->have_hi = 1;
    }
  spvi_rec *tr = s->trial;
  memcpy (tr->y0, y, (size_t) nn * sizeof (double));
  double S;
  int st = predict (s, sys, t, h, tr->y0, &S);
  if (st)
    return st;
  st = core_solve (&s->lo, sys, t, h, tr->y0, S, s, 1, tr->y1);
  if (st)
    return st;
  memcpy (tr->a, s->lo.x, (size_t) (n - 1) * d * sizeof (double));
  memcpy (tr->P, s->lo.x + (size_t) (n - 1) * d,
          (size_t) m * d * sizeof (double));
  tr->t = t;
  tr->h = h;
  tr->tend = t + h;

  if (yerr)
    {
      /* companion (n+1, m+1) from the low-order polynomials: the same a_i
         and a_n = 0; P at its nodes from the low-order p polynomial */
      spvi_core *c = &s->hi;
      memcpy (c->x, tr->a, (size_t) (n - 1) * d * sizeof (double));
      for (int k = 0; k < d; k++)
        c->x[(size_t) (n - 1) * d + k] = 0.0;
      for (int j = 0; j < m + 1; j++)
        rec_p (s, tr, c->z[j], c->x + (size_t) n * d + (size_t) j * d);
      st = core_solve (c, sys, t, h, tr->y0, S, s, 0, yerr);
      if (st)
        return st;
      for (int i = 0; i < nn; i++)
        yerr[i] = tr->y1[i] - yerr[i];
    }
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
  spvi_rec *tmp = s->cur;
  s->cur = s->trial;
  s->trial = tmp;
  s->have_cur = 1;
  s->trial_ok = 0;
}

static int
spvi_dense (void *state, sym_system *sys, double t, double *y)
{
  (void) sys;
  spvi_state *s = state;
  const int d = s->d;
  const spvi_rec *r = s->cur;
  if (! s->have_cur)
    return SYM_EBADINPUT;
  if (t == r->t)
    {
      memcpy (y, r->y0, 2 * (size_t) d * sizeof (double));
      return SYM_SUCCESS;
    }
  if (t == r->tend)
    {
      memcpy (y, r->y1, 2 * (size_t) d * sizeof (double));
      return SYM_SUCCESS;
    }
  double z = 2.0 * (t - r->t) / r->h - 1.0;
  rec_dq (s, r, z, y);
  for (int k = 0; k < d; k++)
    y[k] += r->y0[k];
  rec_p (s, r, z, y + d);
  return SYM_SUCCESS;
}

static void
spvi_reset (void *state)
{
  spvi_state *s = state;
  s->have_cur = 0;
  s->trial_ok = 0;
  sym_newton_invalidate (&s->lo.nw);
  if (s->have_hi)
    sym_newton_invalidate (&s->hi.nw);
}

static int
spvi_method_order (const void *state)
{
  const spvi_state *s = state;
  return s->order;
}

static int
spvi_err_order (const void *state)
{
  const spvi_state *s = state;
  return s->order;
}

static const sym_stepper_type spvi_type = {
  "spvi",
  6,   /* the default Q_DoFs = 4, Nodes = 3 */
  spvi_err_order,
  spvi_method_order,
  spvi_alloc,
  spvi_step,
  spvi_accept,
  spvi_dense,
  spvi_reset,
  spvi_free
};

const sym_stepper_type *const sym_step_spvi = &spvi_type;
