/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

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
   steps while it converges fast).  Every residual costs one sym_rhs_many
   call (m states; one call of the Vectorized batch callback), so the cost
   of a step is its number of corrections; the last correction is not
   followed by another residual: its f_p values are moved linearly to the
   corrected x by the node Jacobians, and they give p_{k+1}.  The returned
   x is therefore the one after the last correction, and the stopping test
   bounds its estimated error: sym_newton stops when theta/(1-theta) |dx|
   <= tol/100 (the same final accuracy as the earlier scheme of converging
   to tol and then one unchecked correction with theta ~ 1e-2, but now
   measured; see core_solve), and then the error that the linear move of
   f_p leaves in p_{k+1} is estimated from the previous correction (whose
   linear move is checked against the f evaluated after it) and, if above
   tol/100, one more correction is made.  If the simplified iteration fails,
   full Newton from the same start.

   The matrix: from the node Jacobians at the start of a step (jac
   callbacks, m of them); then, for the next steps, from node Jacobians
   extrapolated in time (a polynomial through the node Jacobians of the
   last one or two evaluations; no callback, one LU; the companion's,
   when it has none, interpolated from the method's of the same step,
   core_borrow); evaluated anew after
   a solve that needed more than 2 corrections while its first contraction
   was slow (the matrix, not a far start, was to blame), and when h changed
   by > 20%.
   Or, by option (SYM_MATRIX_NEW) or by default with finite differences
   through the batch callback, new at the start of every step (see
   core_solve): its first correction is exact Newton and often the only
   one.

   Predictor: the previous accepted step's polynomials extrapolated (q
   from its Legendre series, re-expanded exactly in the new step by a
   Gauss transform; p from its interpolant through p_k, P_j, p_{k+1};
   with many nodes, only their modes above the noise of the solve, which
   the extrapolation amplifies like 5.8^Nodes: see predict_modes); on
   a first step, after reset, or for the pairs n - 1 > m (whose extra q
   modes do not extrapolate), one explicit Euler estimate: measured, it
   saves 0.6-1.1 iterations per step over the constant start (a_i = 0,
   P_j = p_k) for its one rhs call.  At a fixed step the error of that
   polynomial prediction (converged minus predicted x) is a smooth function
   of the step's start, so the errors of the last steps are extrapolated
   too and added (see predict_history): on Kepler e = 0.6, h = 2 pi/100 the
   start error drops from 1e-6..1e-7 to 1e-9..1e-10 away from pericentre.

   Error estimate: the companion solution on the same step with (n + 1,
   m + 1), its own quadrature, Newton state and LU, started from the
   low-order polynomials; yerr = y_low - y_companion = O(h^(order+1)).
   The adaptive run then advances with the companion's value (local
   extrapolation, as ode45 advances with the higher order of its pair):
   its error is far below the estimate, so the achieved error follows the
   tolerance as a user of ode45 expects.  Neither solve needs round-off
   there: for the pairs n - 1 = m (and their companions, pairs too, with
   the same Newton machinery) each stops at a small fraction of the
   smallest error the tolerances allow (see spvi_step).  Fixed steps (no
   estimate) are the (n, m) method alone.  Where the dense output falls
   back on the solution's polynomials (below), the q polynomial of an
   adaptive step gets the linear correction (z+1)/2 (q_companion -
   q_low)(1), so that it stays continuous and ends on the step's value.

   Dense output (the pairs n - 1 = m): y_k plus the integral of the
   polynomial through dy/dz at -1, at the nodes of the solve the run
   advances with (the method's, or the companion's in adaptive runs:
   stage order m + 1) and at +1, with f evaluated at the step's ends when
   first needed (f at the end of one step is f at the start of the next).
   The node values are off by O(h^(M+1)) for M nodes, so the local error
   is O(h^(M+2)): O(h^(m+3)) adaptive, O(h^(m+2)) fixed, against
   O(h^(m+1)) for the solution's polynomials alone (tests/c/test_spvi.c:
   slope 5.0 against 4.0 for (4,3)).  By Gauss orthogonality the integral
   over the step is the quadrature that gave y_{k+1} (m >= 2); the end
   mismatch, round-off then and O(h^3) for (2,1), is spread linearly, so
   the output ends on the step's value.  The other pairs of order below
   8: the cubic Hermite interpolant through the step's ends (f there, as
   above), O(h^min(4, order)) (in adaptive runs, whose steps follow the
   companion's higher order, it is the larger error); their solution's
   polynomials are only O(h^(order/2)) (p for n - 1 < m, q for n - 1 > m;
   measured in tests/c/test_spvi.c and tests/test_spvi.m).  Without f at
   an end (NaN there), and for the other pairs of order 8 and more: q
   from the Legendre series of the last accepted step, p from the
   polynomial through (-1, p_k), (z_j, P_j), (1, p_{k+1}). */
#include "sym.h"
#include "control.h"
#include "steprec.h"

#include <float.h>
#include <math.h>
#include <string.h>

/* Measured choices, on Kepler e = 0.6, h = 2 pi/100, 1000 periods, pairs
   (3,2), (4,3), (5,4) (tests/c/test_spvi_kepler.c prints (4,3)); the
   measurements are in the comments at their use. */
/* A solve that took more than this many corrections asks for a fresh
   matrix at the next step, if its first contraction was slower than
   SPVI_THETA_FRESH (see core_solve). */
#define SPVI_REFRESH_ITERS 2
#define SPVI_THETA_FRESH 5e-5
/* Adaptive steps: the solves of the pairs n - 1 = m stop when the error
   of their result is below these fractions of the smallest error the
   tolerances allow (sym_error_floor): the method's, which only enters
   the estimate, and the companion's, which the run advances with (see
   spvi_step) */
#define SPVI_EST_LO 1e-3
#define SPVI_EST_HI 1e-4
/* at most this many corrections after sym_newton for the linear move of
   f_p (see core_solve) */
#define SPVI_MOVE_MAX 3
/* Extrapolated node Jacobians: from evaluations at most SPVI_JX_STEPS
   steps back, through at most SPVI_JX_POINTS of their nodes (the latest),
   the older evaluation only when at most SPVI_JX_SPAN steps before the
   latest, and only as many points as keep sum_j |L_j| at the new nodes
   below SPVI_JX_LEBESGUE (see core_extrapolate) */
#define SPVI_JX_STEPS 5
#define SPVI_JX_SPAN 8
#define SPVI_JX_POINTS 6
#define SPVI_JX_LEBESGUE 1e4
/* Predictor: errors of the polynomial prediction extrapolated over at
   most this many past steps (see predict_history) */
#define SPVI_HIST 4
/* A continued prediction whose change from y exceeds this many times the
   last step's change (times 1 + h/h_last) is not used (see
   predict_sane) */
#define SPVI_PRED_SANE 10.0
#define SPVI_MAX_DOFS 100
/* The continued prediction's noise (see predict_modes): cut off when,
   amplified, it can exceed SPVI_PRED_NOISE |y|; modes below SPVI_CHOP
   times their noise are cut */
#define SPVI_PRED_NOISE 1e-6
/* A fixed step that Newton cannot solve from its starts is reached from
   steps down to h/2^SPVI_HALVINGS (see spvi_lengthen) */
#define SPVI_HALVINGS 6
#define SPVI_CHOP 10.0
/* By default a new matrix at the start of every solve (see core_solve)
   only while its LU is this small: measured here, the LU of 64 unknowns takes about
   40 us, two callbacks of Octave; that of 600 (d = 100) takes 12 ms */
#define SPVI_EVERY_N 64

/* The scales of Newton's stopping test: of the a_i (increments of q)
   and of the P_j, and the larger of the two */
typedef struct {
  double q, p, all;
} spvi_scale;

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
  double *Fo, *xfo;    /* the evaluation before it, in this solve */
  int fovalid;
  double dxn[2];       /* sizes of the first two corrections of a solve */
  int ndx;
  double *x, *scale, *x0;
  double *wk;          /* 2d (work) */
  sym_newton nw;
  double h_mat;        /* h of the kept matrix */
  int extra;           /* corrections of slow solves beyond
                          SPVI_REFRESH_ITERS since its Jacobians were
                          evaluated */
  double h_kq;         /* h at which nw.kq was measured */
  /* node Jacobians as evaluated: the latest (Ae[0]) and the one before
     (Ae[1]), at the nodes of the steps (te, he); te from the start of the
     current step (0: this step), counted from the steps' sizes
     (spvi_clock), since differences of the times t vary by their
     round-off */
  double *Ae[2];
  double te[2], he[2];
  int nae;             /* how many of them are valid */
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
  double *xp;          /* the polynomial prediction of x (predict) */
  double *dq;          /* d: end correction of q (adaptive), or zeros */
  int has_dq;
  int cont;            /* xp continued the step before, of the same h */
  /* dense output of the pairs n - 1 = m (see spvi_dense): dy/dz at
     -1, the M nodes of the solve the run advances with, +1, 2d each; the
     ends are h/2 f(t, y) there, evaluated when first needed (fe0, fe1:
     f itself), the nodes' from the solution */
  double *D;           /* (m + 3) x 2d */
  double *fe0, *fe1;   /* 2d each */
  double *emis;        /* 2d: y1 - u(1), the end mismatch (see spvi_dense) */
  int M, have_fe0, have_fe1, have_emis;
  int ends_bad;        /* f at an end is NaN or Inf: the polynomials */
  double noise_q, noise_p;  /* accuracy of a and of P: the solve's
                          tolerance times their scales (at least eps
                          times them) */
} spvi_rec;

typedef struct {
  int d, n, m, order;
  int pred_cont;       /* the last start continued the step before */
  int hermite;         /* dense output of the pairs n - 1 != m of order
                          below 8: cubic Hermite through the step's
                          ends (see spvi_dense) */
  double tol;
  int maxit;
  int newmat;          /* opts->newton_matrix */
  double est_rtol, est_atol;   /* opts: the adaptive tolerances, or 0 */
  spvi_core lo, hi;
  int have_hi;
  spvi_rec rec[2];
  spvi_rec *cur, *trial;
  int have_cur, trial_ok;
  double *xi, *vinv;   /* n Gauss points; a_i = sum_l vinv[i*n+l] v(xi_l) */
  double *f0;          /* 2d: f(t_k, y_k) for the Euler start */
  double *lv, *dlv;    /* n + 1: Legendre values (work) */
  double *cb;          /* m + 3: Lagrange basis values (work) */
  double *gz, *gw;     /* ng Gauss points on [-1, 1] for the dense output */
  int ng;
  double *vq;          /* n d: values of q (work) */
  /* the continued prediction with its noise cut off (predict_modes) */
  double *ach;         /* (n - 1) d: q's modes a_i */
  double *pz, *pw;     /* m + 2 Gauss points and weights */
  double *pc;          /* (m + 2) d: p's Legendre coefficients */
  /* errors of the polynomial prediction (solution - prediction) of the
     last nhist accepted steps, newest first, SPVI_HIST + 1 of N each; all
     continued steps of size hhist */
  double *dhist;
  int nhist;
  double hhist;
  /* the largest sizes of q and of p in the steps solved so far (see
     start_scale) */
  double typ_q, typ_p;
  /* the last step spvi_clock was given */
  double ck_t, ck_h, ck_tend;
  int ck_ok;
} spvi_state;

/* ---------------------------------------------------------------- core */

static void
core_free (spvi_core *c)
{
  sym_newton_free (&c->nw);
  double **p[] = { &c->z, &c->w, &c->phi, &c->dl, &c->wdl, &c->g, &c->xb,
                   &c->bw, &c->A, &c->Y, &c->F, &c->tj, &c->xf, &c->x,
                   &c->scale, &c->x0, &c->Fo, &c->xfo, &c->wk, &c->Ae[0],
                   &c->Ae[1] };
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
  c->Fo = sym_calloc (nn * m, sizeof (double));
  c->xfo = sym_calloc (c->N, sizeof (double));
  c->wk = sym_calloc (nn, sizeof (double));
  c->Ae[0] = sym_calloc (nn * nn * m, sizeof (double));
  c->Ae[1] = sym_calloc (nn * nn * m, sizeof (double));
  c->x = sym_calloc (c->N, sizeof (double));
  c->scale = sym_calloc (c->N, sizeof (double));
  c->x0 = sym_calloc (c->N, sizeof (double));
  double *l = sym_calloc (2 * (size_t) n, sizeof (double));
  int st = SYM_ENOMEM;
  if (! c->z || ! c->w || ! c->phi || ! c->dl || ! c->wdl || ! c->g
      || ! c->xb || ! c->bw || ! c->A || ! c->Y || ! c->F || ! c->tj
      || ! c->xf || ! c->x || ! c->scale || ! c->x0 || ! l || ! c->Fo
      || ! c->xfo || ! c->wk || ! c->Ae[0] || ! c->Ae[1])
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

/* Before a new evaluation at x: the last one becomes the one before it
   (Fo at xfo), and the size of the move between them is kept in dxn while
   fewer than two are. */
static void
core_eval_shift (spvi_core *c, const double *x)
{
  c->fovalid = c->fvalid;
  if (c->fvalid)
    {
      double *tmp = c->Fo;
      c->Fo = c->F;
      c->F = tmp;
      tmp = c->xfo;
      c->xfo = c->xf;
      c->xf = tmp;
      if (c->ndx < 2)
        {
          double v = 0.0;
          for (int i = 0; i < c->N; i++)
            v = fmax (v, fabs (x[i] - c->xfo[i]));
          c->dxn[c->ndx++] = v;
        }
    }
  c->fvalid = 0;
}

/* F = f at the nodes of x (one batch call), cached by x.  The evaluation
   before it in the same solve is kept in Fo (at xfo), and the sizes of the
   first two moves between evaluations (the first two corrections) in
   dxn. */
static int
core_eval (spvi_core *c, const double *x)
{
  size_t nb = (size_t) c->N * sizeof (double);
  if (c->fvalid && memcmp (c->xf, x, nb) == 0)
    return SYM_SUCCESS;
  core_eval_shift (c, x);
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
static void core_keep (spvi_core *c);

static int
core_matrix (void *ctx, const double *x, double *M)
{
  spvi_core *c = ctx;
  const int m = c->m;
  const size_t nn = 2 * (size_t) c->d;
  int st;
  /* One Jacobian per node: also measured, one at the middle node for all
     (m times fewer jac calls per matrix, but slower contraction and, on
     Kepler (4,3), as many calls in all); the exact matrix also keeps the
     full-Newton fallback quadratic. */
  const size_t nb = (size_t) c->N * sizeof (double);
  const int fhere = c->fvalid && memcmp (c->xf, x, nb) == 0;
  if (c->sys->rhs_jac || (! c->sys->jac && ! fhere))
    {
      /* f comes with the Jacobians: from the same calls (the Hessian as
         FCN's second output), or for finite differences from the call of
         the perturbed states (one batch, or the m calls before them); the
         residual at this x, which follows, reuses it.  Measured on Kepler
         (4,3), h = 2 pi/100: with the Hessian 0.57 fewer rhs calls per
         step; with Vectorized finite differences one call fewer per
         matrix, 0.19 per step. */
      if (! fhere)
        core_eval_shift (c, x);
      c->fvalid = 0;
      core_states (c, x);
      if (c->sys->rhs_jac)
        {
          for (int j = 0; j < m; j++)
            if ((st = sym_rhs_jac (c->sys, c->tj[j], c->Y + j * nn,
                                   c->F + j * nn, c->A + j * nn * nn)))
              return st;
        }
      else if ((st = sym_rhs_jac_many (c->sys, m, c->tj, c->Y, c->F,
                                       c->A)))
        return st;
      memcpy (c->xf, x, nb);
      c->fvalid = 1;
    }
  else
    {
      /* the Jacobian callback, or finite differences from the F at x */
      core_states (c, x);
      if ((st = sym_jac_many (c->sys, m, c->tj, c->Y, c->F, c->A)))
        return st;
    }
  core_keep (c);
  core_fill (c, M);
  c->extra = 0;
  return SYM_SUCCESS;
}

/* Keep the node Jacobians in c->A for the extrapolation
   (core_extrapolate): a new step's evaluation becomes the latest, a
   second one on the same step (a refresh inside sym_newton) replaces
   it. */
static void
core_keep (spvi_core *c)
{
  const size_t nn = 2 * (size_t) c->d;
  if (c->nae > 0 && c->te[0] != 0.0)
    {
      double *tmp = c->Ae[1];
      c->Ae[1] = c->Ae[0];
      c->Ae[0] = tmp;
      c->te[1] = c->te[0];
      c->he[1] = c->he[0];
      c->nae = 2;
    }
  else if (c->nae == 0)
    c->nae = 1;
  memcpy (c->Ae[0], c->A, nn * nn * (size_t) c->m * sizeof (double));
  c->te[0] = 0.0;
  c->he[0] = c->h;
}

/* The current step starts shift after the last one: the kept
   evaluations' starts count from it (see spvi_clock). */
static void
core_move (spvi_core *c, double shift)
{
  for (int e = 0; e < c->nae; e++)
    c->te[e] -= shift;
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

/* The node Jacobians c->A at the points xe[i] (one per node) from np
   samples, the blocks src[j] at the points xs[j] (barycentric weights
   bw): their interpolating polynomial. */
static void
core_interp_A (spvi_core *c, int np, const double *xs, const double *bw,
               const double *const *src, const double *xe)
{
  const size_t nn = 2 * (size_t) c->d, nb = nn * nn;
  double cb[2 * SPVI_JX_POINTS];
  for (int i = 0; i < c->m; i++)
    {
      lagrange_basis (np, xs, bw, xe[i], cb);
      double *Ai = c->A + (size_t) i * nb;
      for (size_t e = 0; e < nb; e++)
        {
          double v = 0.0;
          for (int j = 0; j < np; j++)
            v += cb[j] * src[j][e];
          Ai[e] = v;
        }
    }
}

/* The matrix from c->A, factored; 0 (and no matrix: sym_newton evaluates
   one) if the LU failed. */
static int
core_refactor (spvi_core *c, sym_system *sys)
{
  core_fill (c, c->nw.lu.a);
  if (sym_lu_factor (&c->nw.lu, &sys->cnt))
    {
      sym_newton_invalidate (&c->nw);
      return 0;
    }
  return 1;
}

/* The node Jacobians of this step (c->A) extrapolated in time from the
   evaluated ones, and the matrix and LU from them; 0 if not done (nothing
   to extrapolate from, or too far).  The node Jacobians are smooth
   functions of t along the solution, sampled at the nodes of the steps
   where they were evaluated: a polynomial through the latest samples
   (at most SPVI_JX_POINTS; fewer while sum_j |L_j| at the new nodes
   exceeds SPVI_JX_LEBESGUE) predicts them at the new nodes.  Measured
   (Kepler, see the top): against keeping the evaluated ones unchanged,
   the contraction rate one step after an evaluation drops from 1e-2..1e-3
   to 1e-4..1e-6, and the rhs + jac calls per step from 8.76 to 7.68 for
   (4,3), 6.55 to 5.58 for (3,2), 10.72 to 9.64 for (5,4); of that the
   older evaluation gives 0.04-0.25.  Extrapolating further than about 5
   steps did not pay. */
static int
core_extrapolate (spvi_core *c, sym_system *sys)
{
  const int m = c->m;
  const size_t nn = 2 * (size_t) c->d, nb = nn * nn;
  if (c->nae < 1 || c->te[0] == 0.0
      || ! (fabs (c->te[0]) <= SPVI_JX_STEPS * fabs (c->he[0])
                                   * (1 + 1e-9)))
    return 0;
  /* sample times in units of he[0] from te[0], ascending in the direction
     of integration; the older evaluation first */
  double ts[2 * SPVI_JX_POINTS], bw[2 * SPVI_JX_POINTS];
  double cb[2 * SPVI_JX_POINTS];
  const double *src[2 * SPVI_JX_POINTS];
  int np = 0;
  for (int e = (c->nae > 1 && fabs (c->te[0] - c->te[1])
                              <= SPVI_JX_SPAN * fabs (c->he[0]) * (1 + 1e-9));
       e >= 0; e--)
    for (int j = 0; j < m; j++)
      {
        double tz = (c->te[e] - c->te[0]) / c->he[0]
                    + 0.5 * (c->he[e] / c->he[0]) * (1.0 + c->z[j]);
        /* the latest SPVI_JX_POINTS only (they come in ascending order) */
        if (np == SPVI_JX_POINTS)
          {
            memmove (ts, ts + 1, (np - 1) * sizeof (double));
            memmove (src, src + 1, (np - 1) * sizeof (src[0]));
            np--;
          }
        ts[np] = tz;
        src[np++] = c->Ae[e] + (size_t) j * nb;
      }
  /* the new nodes, likewise */
  double xe[SPVI_MAX_DOFS + 1];
  for (int i = 0; i < m; i++)
    xe[i] = (0.5 * c->h * (c->z[i] + 1.0) - c->te[0]) / c->he[0];
  int off = 0;
  for (;; off++)
    {
      bary_weights (np - off, ts + off, bw);
      double lam = 0.0;
      for (int i = 0; i < m; i++)
        {
          lagrange_basis (np - off, ts + off, bw, xe[i], cb);
          double sum = 0.0;
          for (int j = 0; j < np - off; j++)
            sum += fabs (cb[j]);
          lam = isnan (sum) ? INFINITY : fmax (lam, sum);
        }
      if (lam <= SPVI_JX_LEBESGUE || np - off == 1)
        break;
    }
  core_interp_A (c, np - off, ts + off, bw, src + off, xe);
  core_refactor (c, sys);
  return 1;
}

/* The companion's matrix, when it has none (a new h, a slow solve), from
   the method's node Jacobians of the same step (evaluated there at (t,
   h)) interpolated to the companion's nodes by the polynomial through
   them: no callback, one LU.  Its first residual then takes f at its
   nodes by rhs calls, not by calls that also give the Hessian, and no
   finite differences are made for it.  Measured on adaptive Kepler e =
   0.6, (4,3), 10 periods, RelTol 1e-4..1e-12 (tests/c/test_spvi.c): jac
   calls 1003 1305 1211 1386 1725 -> 561 625 739 1030 1577, rhs calls
   +0.1..7.5%, the same errors; timed in turns from Octave, 1-9% faster
   with the Hessian as FCN's second output, 8-25% with finite
   differences down to RelTol 1e-10 (bench/adaptive_runs.m lists the
   calls).  Returns 1 if it made the matrix. */
static int
core_borrow (spvi_core *c, const spvi_core *src, sym_system *sys)
{
  const size_t nn = 2 * (size_t) c->d, nb = nn * nn;
  const int ms = src->m;
  if (src->nae < 1 || src->te[0] != 0.0 || src->he[0] != c->h
      || ms > SPVI_JX_POINTS)
    return 0;
  double bw[SPVI_JX_POINTS];
  const double *sp[SPVI_JX_POINTS];
  bary_weights (ms, src->z, bw);
  for (int j = 0; j < ms; j++)
    sp[j] = src->Ae[0] + (size_t) j * nb;
  core_interp_A (c, ms, src->z, bw, sp, c->z);
  core_keep (c);
  if (! core_refactor (c, sys))
    return 0;
  c->nw.have_matrix = 1;
  return 1;
}

/* Estimated error, relative to S, that the linear move of f_p from xf
   (the last evaluation) to x leaves in p_{k+1} = p_k + (h/2) sum_j w_j
   f_p,j: the move from xfo to xf by the same node Jacobians is compared
   with the f_p evaluated at xf, node by node, and scaled by the ratio of
   the two moves.  0 if x = xf; infinite if there is no earlier
   evaluation to compare with. */
static double
core_move_error (spvi_core *c, double S)
{
  const int d = c->d, n = c->n, m = c->m;
  const size_t nn = 2 * (size_t) d;
  const double *a = c->x, *af = c->xf, *ao = c->xfo;
  double e = 0.0;
  for (int j = 0; j < m; j++)
    {
      double n1 = 0.0, n2 = 0.0, mis = 0.0;
      double *dy = c->wk;        /* Y(xf) - Y(xfo) at node j */
      for (int k = 0; k < d; k++)
        {
          double v1 = 0.0, v2 = 0.0;
          for (int i = 1; i < n; i++)
            {
              size_t ik = (size_t) (i - 1) * d + k;
              v1 += c->phi[j * n + i] * (af[ik] - ao[ik]);
              v2 += c->phi[j * n + i] * (a[ik] - af[ik]);
            }
          size_t ip = (size_t) (n - 1) * d + (size_t) j * d + k;
          dy[k] = v1;
          dy[d + k] = af[ip] - ao[ip];
          n1 = fmax (n1, fmax (fabs (v1), fabs (dy[d + k])));
          n2 = fmax (n2, fmax (fabs (v2), fabs (a[ip] - af[ip])));
        }
      if (n2 == 0.0)
        continue;
      if (! c->fovalid || n1 == 0.0)
        return INFINITY;
      const double *Aj = c->A + (size_t) j * nn * nn;
      for (int k = 0; k < d; k++)
        {
          double v = c->F[(size_t) j * nn + d + k]
                     - c->Fo[(size_t) j * nn + d + k];
          for (size_t l = 0; l < nn; l++)
            v -= Aj[(d + k) + l * nn] * dy[l];
          mis = fmax (mis, fabs (v));
        }
      e += c->w[j] * mis * (n2 / n1);
    }
  return 0.5 * fabs (c->h) * e / S;
}

/* Solve the step (t, h, yk) from the start c->x; on success c->x holds
   the solution and yend = [q_{k+1}; p_{k+1}].  c is the method's core
   (s->lo) or the companion's (s->hi).  For the pairs n - 1 = m (the
   companion of such a pair is one too) tol bounds the estimated error of
   the result relative to S: SYM_FIXED_TOL times the Newton tolerance
   (round-off) for a fixed step, looser in adaptive runs (see spvi_step).

   The pairs n - 1 != m keep the earlier scheme (sym_newton to the Newton
   tolerance, then one more correction from a new residual, unchecked;
   matrices evaluated, never extrapolated; refreshed after more than 3
   iterations; no history in the predictor; tol is not used): their
   matrices are ill-conditioned (see the top), so that the contraction
   rate measured from two corrections does not bound the error left
   (measured on Kepler, 100 periods, local difference to a tightly
   converged step: (3,3) 5e-16, (2,3) 8e-15 with the scheme of the pairs
   n - 1 = m, against 2.3e-16 and 2.4e-16 with the earlier one; the
   earlier one but with the history in the predictor: 1.4e-15 for
   (2,3)).  The extra correction is made by the method and by the
   companion, the value an adaptive run advances with: without it the
   companion (3,3) of (2,2) carried a Newton error of about 100 NewtonTol
   per step, and the error of adaptive runs grew as the tolerance shrank
   (Kepler e = 0.6, one period, RelTol = AbsTol = 1e-8..1e-11: 1.6e-8,
   3.6e-8, 6.3e-8, 8.4e-8; now 3.8e-10, 1.8e-11, 1.4e-13, 2.0e-12, as
   (2,3); tests/test_spvi.m). */
static int
core_solve (spvi_core *c, sym_system *sys, double t, double h,
            const double *yk, const spvi_scale *S, const spvi_state *s,
            double tol,
            double *yend)
{
  const int d = c->d, n = c->n, m = c->m, N = c->N;
  const size_t nn = 2 * (size_t) d;
  const double hh = 0.5 * h;
  const int method = c == &s->lo;
  const int fast = n - 1 == m;
  int st;
  c->sys = sys;
  c->t = t;
  c->h = h;
  c->yk = yk;
  c->fvalid = 0;
  c->ndx = 0;
  for (int j = 0; j < m; j++)
    c->tj[j] = t + hh * (c->z[j] + 1.0);
  /* The matrix depends on h: a new one when h changed by more than 20%.
     Measured on adaptive Kepler (4,3), rtol 1e-6..1e-12, rhs + jac calls:
     rebuilding it instead from the kept node Jacobians (a new LU only, as
     implicit Runge-Kutta codes do) saves jac calls but costs as many more iterations (+0..4%
     in all; -2% with finite-difference Jacobians); never invalidating on h
     costs +0..10%. */
  if (c->nw.have_matrix && ! (fabs (h - c->h_mat) <= 0.2 * fabs (c->h_mat)))
    sym_newton_invalidate (&c->nw);
  /* A kept matrix of an earlier step: from the node Jacobians extrapolated
     to this step's nodes (no callback) */
  /* A new matrix at the start of every solve (SYM_MATRIX_NEW, or by
     default when the node Jacobians are finite differences with the batch
     callback, so that the nodes and their perturbed states take one call,
     and the LU is small): its first correction is then exact Newton, and
     sym_newton (quad) stops after it when its estimated quadratic error
     is below tol.  Measured on Kepler e = 0.6, (4,3), h = 2 pi/100, 1000
     periods: 1.57 residuals per step instead of 2.37; with Vectorized
     finite differences 1.57 calls per step instead of 2.37; with the
     Hessian as FCN's second output and single calls 3 + 1.71 calls per
     step instead of 6.54 + 0.57, but those 3 calls also compute the
     Hessian, so whether that pays depends on its cost (in time 1.1 times
     slower on Kepler, 2.9 on the FPU chain, d = 1; bench/ P1, P6n): hence
     not by default.  The same accuracy (every step within 2.9e-16 of a
     tightly converged solve; the pairs (2,1) to (11,10) on Kepler and the
     pendulum within 1.3x of the kept matrix's differences; no drift of
     energy, see newton.c).  Nor only on the steps after one whose start
     was far (|x - start| > X S; Kepler, 20 periods, rhs + jac calls and
     time per step, 88 us for the kept matrix): X = 1e-6 6.60, 90 us;
     1e-8 6.27, 95 us; 1e-9 5.82, 94 us; X = 0 (every step) 4.71, 98 us.
     Each call saved is a call that computes the Hessian instead. */
  const int every = fast && method
                    && (s->newmat == SYM_MATRIX_NEW
                        || (s->newmat == SYM_MATRIX_AUTO && N <= SPVI_EVERY_N
                            && sys->rhs_batch && ! sys->jac
                            && ! sys->rhs_jac));
  c->nw.quad = every;
  if (every)
    {
      sym_newton_invalidate (&c->nw);
      /* kq follows h (it is about h/2 times a second derivative of f) */
      if (c->nw.kq_ok && ! (fabs (h - c->h_kq) <= 0.2 * fabs (c->h_kq)))
        c->nw.kq_ok = 0;
    }
  if (fast && c->nw.have_matrix)
    core_extrapolate (c, sys);
  else if (fast && ! method)
    core_borrow (c, &s->lo, sys);
  for (int i = 0; i < N; i++)
    c->scale[i] = i < (n - 1) * d ? S->q : S->p;
  /* The returned x is the one after the last correction (no residual
     follows it), so the stopping test theta/(1-theta) |dx| <= tol bounds
     the error of the result itself: with tol/100 it is as accurate as the
     earlier scheme (converge to tol, then one more correction from a new
     residual, unchecked, with theta ~ 1e-2): local difference to a
     tightly converged solution at most 2.8e-16 relative, angular momentum
     of Kepler at round-off (1000 periods, see the top: 2e-14..1.3e-13).
     With tol itself (so that tol bounds the result after the last
     correction), 0.5 calls per step fewer, but local differences up to
     1.9e-14, angular momentum drifts of 1.3e-12 for (4,3) and 1.2e-11 for
     (3,2), a growing energy error for (5,4); with tol/10, 0.2-0.4 calls
     fewer, local differences up to 1.5e-15 and drifts up to 1.3e-12. */
  c->nw.tol = fast ? tol : s->tol;
  c->nw.maxit = s->maxit;
  sym_newton_problem prob = { core_residual, core_matrix, c };
  memcpy (c->x0, c->x, (size_t) N * sizeof (double));
  st = sym_newton_solve (&c->nw, &prob, c->x, c->scale, &sys->cnt);
  if (every && c->nw.kq_new)
    c->h_kq = h;
  /* a failed callback of the matrix comes back with its own status
     (newton.c): no retry, it asks for a smaller step */
  if (st == SYM_NEWTON_FAIL)
    {
      memcpy (c->x, c->x0, (size_t) N * sizeof (double));
      st = core_full_newton (c, sys);
    }
  /* p_{k+1} needs f_p at the final x: the f_p of the last evaluation are
     moved there linearly (below).  The Jacobians of that move are those of
     the matrix, of an earlier point or step, so the move errs by about
     (h/2) |A - Df| |dx|, which the contraction rate of the iteration
     (|dx| is the step to the final x) does not always bound: measured on
     (3,2), local differences up to 6.9e-16 and an angular momentum drift
     of 1.9e-13 without the check below; with it, 2.3e-16 and 9e-14, for
     0.03-0.04 more corrections per step.  (The earlier scheme evaluated f
     at the converged x once more and made one more correction from it,
     moving f_p only by that much smaller one: an extra residual on every
     step.)  After a single exact correction (nw.one) the Jacobians of the
     move are those at xf itself: its error is the quadratic remainder,
     of the order that sym_newton's estimate kq |dx_1|^2 has bounded. */
  for (int k = 0; ! st && fast && ! c->nw.one && k < SPVI_MOVE_MAX
                  && core_move_error (c, S->p) > c->nw.tol; k++)
    {
      if ((st = core_residual (c, c->x, c->nw.r)))
        break;
      for (int i = 0; i < N; i++)
        c->nw.dx[i] = -c->nw.r[i];
      if ((st = sym_lu_solve (&c->nw.lu, c->nw.dx, &sys->cnt)))
        break;
      for (int i = 0; i < N; i++)
        c->x[i] += c->nw.dx[i];
      sys->cnt.nnewton++;
      c->nw.iters++;
    }
  /* the earlier scheme: one more correction (not counted in iters), in
     the method's solve and in the companion's (see above) */
  if (! st && ! fast && ! (st = core_residual (c, c->x, c->nw.r)))
    {
      for (int i = 0; i < N; i++)
        c->nw.dx[i] = -c->nw.r[i];
      if (! (st = sym_lu_solve (&c->nw.lu, c->nw.dx, &sys->cnt)))
        {
          for (int i = 0; i < N; i++)
            c->x[i] += c->nw.dx[i];
          sys->cnt.nnewton++;
        }
    }
  if (st)
    {
      c->fvalid = 0;
      return st;
    }
  /* A fresh matrix for the next step after a slow solve (more than
     SPVI_REFRESH_ITERS corrections), unless the matrix was not to blame:
     its first contraction |dx_2|/|dx_1| was below SPVI_THETA_FRESH, so the
     start was just far (near the pericentre of Kepler the predictor is off
     by 1e-3, and even a fresh matrix needs 3 corrections).  Measured
     (Kepler, 1000 periods; rhs + jac calls per step for (4,3), (3,2),
     (5,4)): refresh after more than 3 corrections (the earlier rule,
     chosen with start errors of 1e-6 and a final extra correction) 9.39,
     6.50, 12.40; after more than 2: 7.59, 5.48, 9.68, of them 0.78, 0.72,
     0.80 jac; the rule here: 7.68, 5.58, 9.64, of them 0.57, 0.52, 0.60
     jac.  A quarter fewer matrices for 0.1 more calls; with
     finite-difference Jacobians (each 2d rhs calls per node) it is 0.5-0.6
     calls fewer: 9.39, 7.17, 11.44 rhs calls against 9.93, 7.64, 12.08. */
  if (fast && c->nw.iters > SPVI_REFRESH_ITERS
      && ! (c->ndx >= 2 && c->dxn[1] <= SPVI_THETA_FRESH * c->dxn[0]))
    {
      /* the extra corrections must have cost as many calls as new node
         Jacobians: as many as one correction with the user's Jacobian
         (the same as refreshing at once), 2d times as many with finite
         differences (by single calls; Vectorized takes the same steps) */
      c->extra += c->nw.iters - SPVI_REFRESH_ITERS;
      const int cost = sys->jac || sys->rhs_jac ? 1 : 2 * d;
      if (c->extra >= cost)
        sym_newton_invalidate (&c->nw);
    }
  else if (! fast && c->nw.iters > 3)
    sym_newton_invalidate (&c->nw);

  /* F is at xf, the iterate before the last correction: f_p += Apq dQ +
     App dP (the node Jacobians of the matrix; the error of this move was
     checked above). */
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
  sym_free (r->xp);
  sym_free (r->dq);
  sym_free (r->D);
  sym_free (r->fe0);
  sym_free (r->fe1);
  sym_free (r->emis);
  r->y0 = r->y1 = r->a = r->P = r->xp = r->dq = NULL;
  r->D = r->fe0 = r->fe1 = r->emis = NULL;
}

static int
rec_init (spvi_rec *r, int d, int n, int m)
{
  memset (r, 0, sizeof (*r));
  r->y0 = sym_calloc (2 * (size_t) d, sizeof (double));
  r->y1 = sym_calloc (2 * (size_t) d, sizeof (double));
  r->a = sym_calloc ((size_t) (n - 1) * d, sizeof (double));
  r->P = sym_calloc ((size_t) m * d, sizeof (double));
  r->xp = sym_calloc ((size_t) (n - 1 + m) * d, sizeof (double));
  r->dq = sym_calloc ((size_t) d, sizeof (double));
  r->D = sym_calloc ((size_t) (m + 3) * 2 * d, sizeof (double));
  r->fe0 = sym_calloc (2 * (size_t) d, sizeof (double));
  r->fe1 = sym_calloc (2 * (size_t) d, sizeof (double));
  r->emis = sym_calloc (2 * (size_t) d, sizeof (double));
  if (! r->y0 || ! r->y1 || ! r->a || ! r->P || ! r->xp || ! r->dq
      || ! r->D || ! r->fe0 || ! r->fe1 || ! r->emis)
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
  sym_free (s->gz);
  sym_free (s->gw);
  sym_free (s->vq);
  sym_free (s->ach);
  sym_free (s->pz);
  sym_free (s->pw);
  sym_free (s->pc);
  sym_free (s->dhist);
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
                   || ! (opts->newton_tol < 1.0)
                   || opts->newton_matrix < SYM_MATRIX_AUTO
                   || opts->newton_matrix > SYM_MATRIX_NEW)))
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
  s->hermite = n - 1 != m && s->order < 8;
  s->tol = opts && opts->newton_tol > 0 ? opts->newton_tol : 1e-14;
  s->maxit = opts && opts->max_newton > 0 ? opts->max_newton : 10;
  s->newmat = opts ? opts->newton_matrix : SYM_MATRIX_AUTO;
  s->est_rtol = opts ? opts->est_rtol : 0.0;
  s->est_atol = opts ? opts->est_atol : 0.0;
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
      s->dhist = sym_calloc ((size_t) (SPVI_HIST + 1) * s->lo.N,
                             sizeof (double));
      if (! s->xi || ! s->vinv || ! s->f0 || ! s->lv || ! s->dlv || ! s->cb
          || ! s->vq || ! s->dhist || ! s->gz || ! s->gw || ! s->ach
          || ! s->pz || ! s->pw || ! s->pc)
        st = SYM_ENOMEM;
      if (! st)
        st = sym_gauss_legendre (s->ng, s->gz, s->gw);
      if (! st)
        st = sym_gauss_legendre (m + 2, s->pz, s->pw);
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

/* q(z) - q_k of the modes a (a_1..a_{n-1}, d values each; a step's
   r->a), into q */
static void
modes_dq (const spvi_state *s, const double *a, double z, double *q)
{
  const int d = s->d, n = s->n;
  sym_legendre (n, z, s->lv, s->dlv);
  for (int k = 0; k < d; k++)
    {
      double v = 0.0;
      for (int i = 1; i < n; i++)
        v += a[(size_t) (i - 1) * d + k]
             * (s->lv[i] - ((i % 2) ? -1.0 : 1.0));
      q[k] = v;
    }
}

/* The dense output's data from the solve c (at its final x) into r: the
   nodes' dy/dz, dq/dz from the q polynomial and dp/dz = h/2 f_p (moved
   to the final x by core_solve).  The ends are not known yet. */
static void
rec_nodes (spvi_rec *r, const spvi_core *c)
{
  const int d = c->d, n = c->n, m = c->m;
  const size_t nn = 2 * (size_t) d;
  const double hh = 0.5 * c->h;
  for (int j = 0; j < m; j++)
    {
      double *Dj = r->D + (size_t) (j + 1) * nn;
      for (int k = 0; k < d; k++)
        {
          double v = 0.0;
          for (int i = 1; i < n; i++)
            v += c->dl[j * n + i] * c->x[(size_t) (i - 1) * d + k];
          Dj[k] = v;
          Dj[d + k] = hh * c->F[(size_t) j * nn + d + k];
        }
    }
  r->M = m;
}

/* dy/dz at the ends of r, from f there (one call each when not known) */
static int
rec_ends (spvi_rec *r, sym_system *sys, int d)
{
  const size_t nn = 2 * (size_t) d;
  const double hh = 0.5 * r->h;
  int st;
  if (! r->have_fe0)
    {
      if ((st = sym_rhs (sys, r->t, r->y0, r->fe0)))
        return st;
      r->have_fe0 = 1;
    }
  if (! r->have_fe1)
    {
      if ((st = sym_rhs (sys, r->tend, r->y1, r->fe1)))
        return st;
      r->have_fe1 = 1;
    }
  for (size_t i = 0; r->M > 0 && i < nn; i++)
    {
      r->D[i] = hh * r->fe0[i];
      r->D[(size_t) (r->M + 1) * nn + i] = hh * r->fe1[i];
    }
  return SYM_SUCCESS;
}

/* u = the integral from -1 to z of the polynomial through r's dy/dz at
   -1, its M nodes and +1 (Gauss quadrature, exact: the degree is M + 1
   <= m + 2) */
static void
rec_integral (const spvi_state *s, const spvi_rec *r, double z, double *u)
{
  const spvi_core *c = r->M == s->m ? &s->lo : &s->hi;
  const int np = r->M + 2;
  const size_t nn = 2 * (size_t) s->d;
  const double half = 0.5 * (z + 1.0);
  memset (u, 0, nn * sizeof (double));
  for (int g = 0; g < s->ng; g++)
    {
      lagrange_basis (np, c->xb, c->bw, -1.0 + half * (s->gz[g] + 1.0),
                      s->cb);
      for (int i = 0; i < np; i++)
        {
          const double wgt = half * s->gw[g] * s->cb[i];
          const double *Di = r->D + (size_t) i * nn;
          for (size_t k = 0; k < nn; k++)
            u[k] += wgt * Di[k];
        }
    }
}

/* The modes of the continued prediction (see predict_modes): the
   highest mode of c (nm modes of d values, mode i at c[i*d]) from mode
   lo on whose size exceeds SPVI_CHOP (2i + 1)^pw noise in some component
   (lo - 1 if none). */
static int
top_mode (const double *c, int nm, int d, int lo, int pw, double noise)
{
  for (int i = nm - 1; i >= lo; i--)
    {
      double thr = SPVI_CHOP * noise * (pw ? 2.0 * i + 1.0 : 1.0);
      for (int k = 0; k < d; k++)
        if (! (fabs (c[(size_t) i * d + k]) <= thr))
          return i;
    }
  return lo - 1;
}

/* The continued prediction evaluates the last step's polynomials at z =
   1 + rho (z' + 1), up to zmax = 1 + 2 rho, outside [-1, 1], where
   Legendre modes grow like |l_i(zmax)| (about 5.8^i / 6 at rho = 1).  The
   solve left a noise of about r->noise in each a_i (q), and about (2i +
   1) r->noise in the i-th Legendre coefficient of the p polynomial
   (through p_k, P_j, p_{k+1}), and the continuation amplifies them by as
   much: for many nodes the prediction is noise.  On H = (q^2 + p^2)^2/4
   from (1, 0.5) (a rotation at the rate 1.25) with h = 1 and Nodes = 20
   every continued start was off by 1.4..3.3 relative to |y|, Newton took
   8 corrections per step and failed at t = 22 (t = 27 from Octave, with
   finite-difference matrices); Nodes = 25, 30, 40 failed at t = 2.
   When the amplified noise can exceed SPVI_PRED_NOISE |y|, the modes at
   the top of each series that are below SPVI_CHOP times their noise are
   cut off: the starts are then off by about 1e-6, Newton takes 3.3-3.6
   corrections per step for Nodes = 15..40 and every run goes through
   (tests/c/test_spvi.c).  Measured, the noise of the top modes is below
   0.2 r->noise for q and up to 30 r->noise for p (Nodes = 30), where the
   cut is at 10 and 10 (2i + 1) = 410..610 times r->noise.  The pairs up
   to Nodes = 10 at rho <= 1 and the NewtonTol of fixed steps are below
   the SPVI_PRED_NOISE bound (3e-7 |y| at Nodes = 10) and predict as
   before.  On Kepler e = 0.6 at fixed steps (5000 steps, each against
   the same step converged tightly) the largest difference went from
   3.6e-15, 1.3e-14, 1.0e-13 to 9.3e-16, 9.3e-16, 1.1e-15 for Nodes =
   12, 15, 20 at h = T/20, T/20, T/15, with 36.0, 45.4, 69.8 rhs + jac
   calls per step instead of 34.4, 48.7, 96.5.  Returns
   the highest Legendre mode of p to use, or m + 1 for the p polynomial
   itself (rec_p); q's modes are in s->ach. */
static int
predict_modes (spvi_state *s, const spvi_rec *r, double zmax, double ynorm)
{
  const int d = s->d, n = s->n, m = s->m;
  const size_t na = (size_t) (n - 1) * d;
  const int nl = n > m + 2 ? n : m + 2;
  memcpy (s->ach, r->a, na * sizeof (double));
  sym_legendre (nl, zmax, s->lv, s->dlv);
  double amp = 0.0;
  for (int i = 1; i < n; i++)
    amp += fabs (s->lv[i]) + 1.0;
  for (int i = 0; i < m + 2; i++)
    amp += (2.0 * i + 1.0) * fabs (s->lv[i]);
  if (! (amp * fmax (r->noise_q, r->noise_p) > SPVI_PRED_NOISE * ynorm))
    return m + 1;
  int kq = top_mode (r->a, n - 1, d, 0, 0, r->noise_q) + 1;
  memset (s->ach + (size_t) kq * d, 0,
          (na - (size_t) kq * d) * sizeof (double));
  /* p's Legendre coefficients (degree m + 1) by Gauss quadrature */
  memset (s->pc, 0, (size_t) (m + 2) * d * sizeof (double));
  for (int l = 0; l < m + 2; l++)
    {
      rec_p (s, r, s->pz[l], s->vq);
      sym_legendre (m + 2, s->pz[l], s->lv, s->dlv);
      for (int i = 0; i < m + 2; i++)
        {
          double c = 0.5 * (2.0 * i + 1.0) * s->pw[l] * s->lv[i];
          for (int k = 0; k < d; k++)
            s->pc[(size_t) i * d + k] += c * s->vq[k];
        }
    }
  return top_mode (s->pc, m + 2, d, 1, 1, r->noise_p);
}

/* Whether the polynomial prediction in s->lo.x of the step continuing r
   by rho times its h, from y, stays within SPVI_PRED_SANE times the
   change of y over r (times 1 + rho) of y.  Extrapolated to [1, 1 + 2
   rho] the polynomials of many modes or nodes amplify the round-off of
   their coefficients (the Legendre l_i(3) grows like 5.8^i): for Nodes
   above about 24 their prediction was far off, and since the scale of
   Newton's stopping test is the size of the state over the step, taken
   from that prediction, Newton stopped at once on a wrong solution
   (pendulum, h = 1, Nodes = 30: an error of 715 at t = 20, no warning). */
static int
predict_sane (const spvi_state *s, const spvi_rec *r, double rho,
              const double *y)
{
  const int d = s->d, n = s->n, m = s->m;
  const double *a = s->lo.x, *P = s->lo.x + (size_t) (n - 1) * d;
  double prev = 0.0, dev = 0.0;
  for (int k = 0; k < 2 * d; k++)
    prev = fmax (prev, fabs (r->y1[k] - r->y0[k]));
  for (int k = 0; k < d; k++)
    {
      double v = 0.0;
      for (int i = 1; i < n; i++)
        v += fabs (a[(size_t) (i - 1) * d + k]);
      dev = fmax (dev, v);
      for (int j = 0; j < m; j++)
        dev = fmax (dev, fabs (P[(size_t) j * d + k] - y[d + k]));
    }
  return isfinite (dev) && dev <= SPVI_PRED_SANE * (1.0 + fabs (rho)) * prev;
}

/* The start x = (a, P) in s->lo.x from the polynomials of the solved
   step r evaluated at its z = z0 + rho (z' + 1) for the new step's z'
   (z0 = 1: the step after r; z0 = -1: a step from r's start, rho times
   as long), with only their modes above the noise (predict_modes). */
static void
predict_poly (spvi_state *s, const spvi_rec *r, double z0, double rho,
              double ynorm)
{
  const int d = s->d, n = s->n, m = s->m;
  double *a = s->lo.x, *P = s->lo.x + (size_t) (n - 1) * d;
  int kp = predict_modes (s, r, z0 + 2.0 * fabs (rho), ynorm);
  for (int l = 0; l < n; l++)
    modes_dq (s, s->ach, z0 + rho * (s->xi[l] + 1.0),
              s->vq + (size_t) l * d);
  /* q(z) - q(z0) of the old step, the new step's increments; the
     constant part drops out of a_i, i >= 1 */
  for (int i = 1; i < n; i++)
    for (int k = 0; k < d; k++)
      {
        double q0 = z0 > 0 ? r->y1[k] - r->y0[k] : 0.0;
        double v = 0.0;
        for (int l = 0; l < n; l++)
          v += s->vinv[i * n + l] * (s->vq[(size_t) l * d + k] - q0);
        a[(size_t) (i - 1) * d + k] = v;
      }
  for (int j = 0; j < m; j++)
    {
      double z = z0 + rho * (s->lo.z[j] + 1.0);
      if (kp > m)
        {
          rec_p (s, r, z, P + (size_t) j * d);
          continue;
        }
      sym_legendre (kp + 1, z, s->lv, s->dlv);
      for (int k = 0; k < d; k++)
        {
          double v = 0.0;
          for (int i = 0; i <= kp; i++)
            v += s->pc[(size_t) i * d + k] * s->lv[i];
          P[(size_t) j * d + k] = v;
        }
    }
}

/* The scales of the step from y starting at s->lo.x: the size of q
   (|q_k|, |q_{k+1}|, and the largest of the steps before) for the a_i,
   the size of p (|p_k|, |P_j|, likewise) for the P_j, so that a block
   passing through zero keeps the scale of its size in the run; a block
   of zeros takes the other's size (1 if both are zero).  Fixed steps converge each block to round-off of its own size,
   so that conservation does not depend on the units of q and p (with
   one scale for all, P_j of 1e-6 the size of q were left off by 1e-6
   of their size).  Within a block one scale serves all components: a
   per-component scale cannot be met below the round-off that f's
   coupling carries from the large components into the small ones.
   Adaptive steps take the larger size for both blocks (adaptive=1):
   their solves stop at an absolute accuracy set by the tolerances. */
static spvi_scale
start_scale (spvi_state *s, const double *y, int adaptive)
{
  const int d = s->d, n = s->n, m = s->m;
  const double *a = s->lo.x, *P = s->lo.x + (size_t) (n - 1) * d;
  double sq = 0.0;
  for (int k = 0; k < d; k++)
    {
      double v = y[k];
      for (int i = 1; i < n; i += 2)
        v += 2.0 * a[(size_t) (i - 1) * d + k];
      sq = fmax (sq, fmax (fabs (v), fabs (y[k])));
    }
  double sp = fmax (inf_norm (d, y + d), inf_norm (m * d, P));
  spvi_scale S;
  S.all = fmax (sq, sp) > 0 ? fmax (sq, sp) : 1.0;
  if (isfinite (sq) && isfinite (sp))
    {
      s->typ_q = sq = fmax (sq, s->typ_q);
      s->typ_p = sp = fmax (sp, s->typ_p);
    }
  S.q = adaptive || ! (sq > 0) ? S.all : sq;
  S.p = adaptive || ! (sp > 0) ? S.all : sp;
  return S;
}

/* The start of Newton for the step (t, h, y) into s->lo.x; returns the
   scales of the stopping test in *S (adaptive: see start_scale). */
static int
predict (spvi_state *s, sym_system *sys, double t, double h, const double *y,
         int euler, int adaptive, spvi_scale *S)
{
  const int d = s->d, n = s->n, m = s->m;
  double *a = s->lo.x, *P = s->lo.x + (size_t) (n - 1) * d;
  double ynorm = inf_norm (2 * d, y);
  const spvi_rec *r = s->cur;
  /* n - 1 > m: the q polynomial carries modes that the kinetic
     quadrature cannot see (fixed by the potential's curvature); they do
     not extrapolate (l_3(3) = 63), so those pairs start from Euler. */
  int cont = ! euler && s->have_cur && n - 1 <= m
             && fabs (t - r->tend) <= 1e-10 * fabs (r->h)
                                      + 4 * DBL_EPSILON * fabs (t);
  for (int k = 0; cont && k < 2 * d; k++)
    cont = fabs (y[k] - r->y1[k]) <= 1e-12 * ynorm;
  /* the same h (up to the round-off of fixed steps t0 + k h) */
  s->trial->cont = cont && fabs (h - r->h) <= 1e-10 * fabs (h);
  if (cont)
    {
      /* new z' <-> old z = 1 + rho (z' + 1) */
      double rho = h / r->h;
      predict_poly (s, r, 1.0, rho, ynorm);
      cont = predict_sane (s, r, rho, y);
      s->trial->cont = s->trial->cont && cont;
    }
  s->pred_cont = cont;
  if (! cont)
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
  *S = start_scale (s, y, adaptive);
  return SYM_SUCCESS;
}

/* Binomial extrapolation: v_new ~ sum_{l<L} XC[L][l] v_{-l}, exact for
   polynomials of degree < L in the step number. */
static const double XC[SPVI_HIST + 1][SPVI_HIST] = {
  { 0 }, { 1 }, { 2, -1 }, { 3, -3, 1 }, { 4, -6, 4, -1 }
};

/* The start of a continued step of the history's h: the polynomial
   prediction (in s->lo.x, kept in the trial's xp) plus the extrapolated
   errors of the predictions of the last steps.  The error of the
   polynomial prediction is O(h^(m+1)) (the stage order) but a smooth
   function of the step's start at a fixed h, so its differences over
   steps are smaller by factors of about h/(time scale).  The order L
   (<= SPVI_HIST) is the one that would have predicted the newest error
   best from the ones before (a wrong order near fast passages, where the
   extrapolation is poor, costs nothing: the start is then off anyway).
   Measured (Kepler, see the top; rhs + jac calls per step for (4,3),
   (3,2), (5,4)): without it 8.37, 6.57, 10.36; with it 7.68, 5.58, 9.64.
   The start error of (4,3) goes from 1e-6..1e-7 to 1e-9..1e-10 over most
   of the orbit (near the pericentre, r = 0.4, it stays 1e-3 with or
   without).  L up to 5 or 6 saves another 0.1-0.2 calls but amplifies
   the round-off of the past solutions (by up to 2^L - 1, after the
   factor 10-100 of the polynomial continuation) to the size of the start
   error itself near the apocentre (1e-12): the number of corrections then
   follows the last bits of f (the Vectorized form of an Octave function
   against its scalar form: 0.5% more or fewer evaluations; see
   test_spvi_kepler); with L <= 4 it did not in any of the runs measured.
   Not for n - 1 != m (see core_solve). */
static void
predict_history (spvi_state *s, double h)
{
  const int N = s->lo.N;
  const spvi_rec *tr = s->trial;
  memcpy (tr->xp, s->lo.x, (size_t) N * sizeof (double));
  /* not for n - 1 != m (see core_solve) */
  if (s->n - 1 != s->m || ! tr->cont || s->nhist < 2
      || ! (fabs (h - s->hhist) <= 1e-10 * fabs (h)))
    return;
  int best_l = 0;
  double best = INFINITY;
  for (int L = 0; L < s->nhist && L <= SPVI_HIST; L++)
    {
      double e = 0.0;
      for (int i = 0; i < N; i++)
        {
          double v = s->dhist[i];
          for (int l = 0; l < L; l++)
            v -= XC[L][l] * s->dhist[(size_t) (l + 1) * N + i];
          e = fmax (e, fabs (v));
        }
      if (e < best)
        {
          best = e;
          best_l = L;
        }
    }
  for (int l = 0; l < best_l; l++)
    for (int i = 0; i < N; i++)
      s->lo.x[i] += XC[best_l][l] * s->dhist[(size_t) l * N + i];
}

/* The accuracy of the solved a and P of r, by tol (pairs n - 1 = m) or
   the Newton tolerance */
static void
rec_noise (const spvi_state *s, spvi_rec *r, double tol,
           const spvi_scale *S)
{
  const double e = fmax (s->n - 1 == s->m ? tol : s->tol, DBL_EPSILON);
  r->noise_q = e * S->q;
  r->noise_p = e * S->p;
}

/* A fixed step whose Newton failed from both starts (continued and
   Euler) is reached from shorter ones: the step h/2^k from the Euler
   start for the smallest k <= SPVI_HALVINGS that converges, then each
   solution's polynomials extended to twice its length (predict_poly)
   as the start of the step twice as long, up to h.  This follows the
   solution of the step equations that tends to the identity as h -> 0,
   where Newton from the Euler start, off by O(h |f'|), diverges.
   Measured on H = (q^2 + p^2)^2/4 from (1, 0.5) (a rotation at the
   rate 1.25): the first step failed for h = 1.5, 2, 2.5 with Nodes = 5,
   8, 12, 20; now these runs go through (tests/c/test_spvi.c).  On
   success the solution of (t, h) is in s->lo and tr->y1, its scale in
   *S. */
static int
spvi_lengthen (spvi_state *s, sym_system *sys, double t, double h,
               double tol, spvi_scale *S)
{
  spvi_rec *tr = s->trial;
  const int d = s->d, na = (s->n - 1) * d;
  const double *y = tr->y0;
  int k, st = SYM_NEWTON_FAIL;
  for (k = 1; k <= SPVI_HALVINGS && st == SYM_NEWTON_FAIL; k++)
    {
      st = predict (s, sys, t, ldexp (h, -k), y, 1, 0, S);
      if (! st)
        st = core_solve (&s->lo, sys, t, ldexp (h, -k), y, S, s, tol,
                         tr->y1);
    }
  /* solved h/2^(k-1); then h/2^(k-2), ..., h */
  for (k -= 2; ! st && k >= 0; k--)
    {
      memcpy (tr->a, s->lo.x, (size_t) na * sizeof (double));
      memcpy (tr->P, s->lo.x + na, (size_t) s->m * d * sizeof (double));
      rec_noise (s, tr, tol, S);
      predict_poly (s, tr, -1.0, 2.0, inf_norm (2 * d, y));
      *S = start_scale (s, y, 0);
      st = core_solve (&s->lo, sys, t, ldexp (h, -k), y, S, s, tol,
                       tr->y1);
    }
  return st;
}

/* A step (t, h) ending at tend is about to be solved: the cores' kept
   evaluations are moved to count from t.  A step that starts where the
   last one ended moves them by that step's h, so that fixed steps see
   the same times at any t (far from t = 0 the differences of the step
   times vary by the round-off of t: from t0 = 1e8 Kepler's (4,3) at
   h = 2 pi/100 took 12 calls more in 14226, and its solution drifted
   6e-12 from the one from 0 over 2000 steps); a step from elsewhere by
   the difference of the times. */
static void
spvi_clock (spvi_state *s, double t, double h, double tend)
{
  if (s->ck_ok && t != s->ck_t)
    {
      const double shift = t == s->ck_tend ? s->ck_h : t - s->ck_t;
      core_move (&s->lo, shift);
      if (s->have_hi)
        core_move (&s->hi, shift);
    }
  s->ck_t = t;
  s->ck_h = h;
  s->ck_tend = tend;
  s->ck_ok = 1;
}

static int
spvi_step (void *state, sym_system *sys, double t, double h, double tend,
           const double *y, double *ynext, double *yerr)
{
  spvi_state *s = state;
  const int d = s->d, n = s->n, m = s->m, nn = 2 * d;
  s->trial_ok = 0;
  if (! (h != 0.0) || ! isfinite (h) || ! isfinite (t) || ! isfinite (tend))
    return SYM_EBADINPUT;
  if (yerr && ! s->have_hi)
    {
      int st = core_init (&s->hi, d, n + 1, m + 1);
      if (st)
        return st;
      s->have_hi = 1;
    }
  spvi_clock (s, t, h, tend);
  spvi_rec *tr = s->trial;
  memcpy (tr->y0, y, (size_t) nn * sizeof (double));
  spvi_scale S;
  int st = predict (s, sys, t, h, tr->y0, 0, yerr != NULL, &S);
  if (st)
    return st;
  predict_history (s, h);
  /* A fixed step is converged to round-off.  An adaptive one advances
     with the companion, so the method's solution only enters the estimate
     y_low - y_companion (and the dense output within the step): its
     solve stops at SPVI_EST_LO of the smallest error the tolerances
     allow, the companion's at SPVI_EST_HI.  Measured on Kepler e = 0.6,
     10 periods, RelTol = AbsTol = 1e-4..1e-12 (test_adaptive_kepler in
     tests/c/test_spvi.c): 4765 6876 10763 14356 24398 rhs + jac calls
     against 6722 9378 14978 17688 27011 when the method's solve was
     converged to round-off and the companion's to the Newton tolerance
     (10-29% fewer), the same end-point errors down to 1e-10, and at 1e-12
     8.5e-12 instead of 1.2e-9 (the companion's Newton tolerance was the
     floor: it is the value the run advances with).  The predictive step
     control (control.c) then brought them to 3967 5142 8173 13506 25003,
     and the companion's interpolated matrices (core_borrow) to 3629 4750
     8005 13330 24879; 3635 at 1e-4 now, with one check of the Jacobian
     after a Newton failure (driver.c). */
  const double tol_rf = SYM_FIXED_TOL * s->tol;
  const double w = yerr && s->est_rtol > 0
                   ? sym_error_floor (nn, y, s->est_rtol, s->est_atol) : 0.0;
  const double tol_lo = fmax (tol_rf, SPVI_EST_LO * w / S.all);
  const double tol_hi = fmax (tol_rf, SPVI_EST_HI * w / S.all);
  st = core_solve (&s->lo, sys, t, h, tr->y0, &S, s, tol_lo, tr->y1);
  if (st == SYM_NEWTON_FAIL && s->pred_cont && ! yerr)
    {
      /* The continued start was too far off (the pairs n - 1 < m, whose
         p polynomial through many nodes extrapolates poorly, or many
         nodes at a long step): once more from the Euler start, as after
         a reset, before the step is given up.  Fixed steps only: there a
         failure ends the run, while an adaptive run shrinks the step,
         for fewer calls than the retry (adaptive Kepler, 10 periods,
         RelTol 1e-4: 3687 rhs + jac calls with the retry, 3635
         without).  Measured on H = (q^2 + p^2)^2/4 from (1, 0.5), h = 0.2:
         (2,5) failed at t = 1.6 from a start 0.34 off (relative), and
         (4,8) likewise, and (21,20) at h = 1 at t = 4; with the retry
         all three run through (tests/test_spvi.m).  (No estimate, so
         w = 0 and the tolerances do not depend on the new S.) */
      st = predict (s, sys, t, h, tr->y0, 1, 0, &S);
      if (! st)
        {
          predict_history (s, h);
          st = core_solve (&s->lo, sys, t, h, tr->y0, &S, s, tol_lo,
                           tr->y1);
        }
    }
  /* Fixed steps only, as above */
  if (st == SYM_NEWTON_FAIL && ! yerr)
    st = spvi_lengthen (s, sys, t, h, tol_lo, &S);
  if (st)
    return st;
  memcpy (tr->a, s->lo.x, (size_t) (n - 1) * d * sizeof (double));
  memcpy (tr->P, s->lo.x + (size_t) (n - 1) * d,
          (size_t) m * d * sizeof (double));
  tr->t = t;
  tr->h = h;
  tr->tend = tend;
  tr->has_dq = 0;
  tr->M = 0;
  tr->have_fe0 = tr->have_fe1 = tr->have_emis = tr->ends_bad = 0;
  rec_noise (s, tr, tol_lo, &S);
  if (n - 1 == m)
    rec_nodes (tr, &s->lo);

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
      st = core_solve (c, sys, t, h, tr->y0, &S, s, tol_hi, yerr);
      if (st)
        return st;
      if (n - 1 == m)
        rec_nodes (tr, c);
      /* yerr holds the companion's value: advance with it (local
         extrapolation) and return the estimate of the low-order error */
      for (int k = 0; k < d; k++)
        tr->dq[k] = yerr[k] - tr->y1[k];
      tr->has_dq = 1;
      for (int i = 0; i < nn; i++)
        {
          double hi = yerr[i];
          yerr[i] = tr->y1[i] - hi;
          tr->y1[i] = hi;
        }
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
  /* the error of its polynomial prediction joins the history */
  const spvi_rec *tr = s->trial;
  const int N = s->lo.N, na = (s->n - 1) * s->d;
  if (tr->cont)
    {
      if (! (s->nhist > 0 && fabs (tr->h - s->hhist) <= 1e-10 * fabs (tr->h)))
        s->nhist = 0;
      memmove (s->dhist + N, s->dhist,
               (size_t) SPVI_HIST * N * sizeof (double));
      for (int i = 0; i < na; i++)
        s->dhist[i] = tr->a[i] - tr->xp[i];
      for (int i = na; i < N; i++)
        s->dhist[i] = tr->P[i - na] - tr->xp[i];
      if (s->nhist <= SPVI_HIST)
        s->nhist++;
      s->hhist = tr->h;
    }
  else
    s->nhist = 0;
  /* f at the end of the last step, if the dense output evaluated it, is
     f at the start of this one */
  spvi_rec *cu = s->cur, *tw = s->trial;
  if (s->have_cur && cu->have_fe1 && cu->tend == tw->t
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

static int
spvi_dense (void *state, sym_system *sys, double t, double *y)
{
  spvi_state *s = state;
  const int d = s->d;
  spvi_rec *r = s->cur;
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
  if (! r->ends_bad && (r->M > 0 || s->hermite))
    {
      int st = rec_ends (r, sys, d);
      if (st < 0)
        return st;        /* a fatal callback status ends the run */
      if (st == SYM_SUCCESS && r->M == 0)
        {
          /* the other pairs: cubic Hermite through the step's ends */
          sym_hermite (2 * d, r->h, 0.5 * (z + 1.0), r->y0, r->y1, r->fe0,
                       r->fe1, y);
          return SYM_SUCCESS;
        }
      if (st == SYM_SUCCESS)
        {
          if (! r->have_emis)
            {
              rec_integral (s, r, 1.0, r->emis);
              for (int k = 0; k < 2 * d; k++)
                r->emis[k] = r->y1[k] - r->y0[k] - r->emis[k];
              r->have_emis = 1;
            }
          rec_integral (s, r, z, y);
          for (int k = 0; k < 2 * d; k++)
            y[k] += r->y0[k] + 0.5 * (z + 1.0) * r->emis[k];
          return SYM_SUCCESS;
        }
      /* f is NaN or Inf at an end of the step (it may be beyond a
         singularity that no node reached): this step's dense output is
         then its solution's own polynomials */
      r->ends_bad = 1;
    }
  modes_dq (s, r->a, z, y);
  for (int k = 0; k < d; k++)
    y[k] += r->y0[k] + (r->has_dq ? 0.5 * (z + 1.0) * r->dq[k] : 0.0);
  rec_p (s, r, z, y + d);
  return SYM_SUCCESS;
}

static void
spvi_reset (void *state)
{
  spvi_state *s = state;
  s->have_cur = 0;
  s->trial_ok = 0;
  s->nhist = 0;
  s->lo.nae = 0;
  sym_newton_invalidate (&s->lo.nw);
  s->lo.nw.kq_ok = 0;
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
