/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* spvi.h -- internal to the spectral variational integrator (odeSPVI):
   its equations (equations.c), Newton matrices (jacobians.c), their
   stage systems (staged.c, staged_factor.c, staged_solve.c), solve
   (solve.c), predictor (predict.c), dense output (dense.c) and stepper
   (step.c).

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
   used to write it in P_j - p_k, so that its round-off is relative to the
   increments, not to |p|; R2 is E2 times h/2: both blocks of Newton's
   matrix are O(1) with O(h) couplings (see jacobians.c).  For n - 1 != m
   the h -> 0 limit of that matrix is singular: an intrinsic 1/h or 1/h^2
   conditioning of those pairs.  Order 2 min(n - 1, 2m - n + 1); n > 2m
   does not converge and is refused; (n, m) = (s + 1, s) is s-stage Gauss
   collocation, (2, 1) the implicit midpoint rule.

   Error estimate: the companion solution on the same step with (n + 1,
   m + 1), its own quadrature, Newton state and LU, started from the
   low-order polynomials; yerr = y_low - y_companion.  An adaptive run
   advances with the companion's value (local extrapolation, as ode45
   advances with the higher order of its pair).  Fixed steps are the
   (n, m) method alone, solved to round-off. */
#ifndef SYM_SPVI_H
#define SYM_SPVI_H

#include "../../sym.h"
#include "../../numerics/numerics.h"

/* The scales of Newton's stopping test: of the a_i (increments of q)
   and of the P_j, and the larger of the two */
typedef struct {
  double q, p, all;
} spvi_scale;

/* Newton's systems by stage systems (staged.c) */
typedef struct spvi_stages spvi_stages;
enum { SPVI_FULL = 0, SPVI_STAGES = 1, SPVI_STAGES_SPARSE = 2 };

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
  double *A;           /* node Jacobians, (2d)^2 each, of the kept matrix
                          (with stages only when exact) */
  spvi_stages *sg;     /* NULL: Newton's matrix in full, dense */
  int fp;              /* this solve by fixed-point iteration: the
                          stages' solve with J = 0 (solve.c) */
  int fp_off;          /* NonlinearSolver auto: Newton from now on */
  int exact;           /* stages with a new matrix every solve: node
                          Jacobians evaluated, the stages' solve iterated
                          to Newton's own correction (staged_solve.c) */
  double *Y, *F, *tj;  /* node states and f values (2d x m), node times */
  double *xf;          /* the x at which F was evaluated */
  int fvalid;
  double *Fo, *xfo;    /* the evaluation before it, in this solve */
  int fovalid;
  double dxn[2];       /* sizes of the first two corrections of a solve */
  int ndx;
  double *x, *scale;   /* (the start of a solve: nw.x0) */
  double *wk;          /* 3d (work) */
  double *inc;         /* 2d: y_{k+1} - y_k of the last spvi_end, before
                          its rounding */
  sym_newton nw;
  double move_tol;     /* the bound on move_error (solve.c) */
  double h_mat;        /* h of the kept matrix */
  /* |Aqp| |p| and |Apq| |q| of the node Jacobians in A (see
     predict.c), at the state of the step that first asked; noise_ok = 0
     when A changes */
  double noise_q, noise_p;
  int noise_ok;
  int extra;           /* corrections of slow solves beyond
                          SYM_SPVI_REFRESH_ITERS since its Jacobians were
                          evaluated */
  double h_kq;         /* h at which nw.kq was measured */
  /* node Jacobians as evaluated: the latest (Ae[0]) and the one before
     (Ae[1]), at the nodes of the steps (te, he); te from the start of the
     current step (0: this step), counted from the steps' sizes
     (spvi_core_move), since differences of the times t vary by their
     round-off */
  double *Ae[2];
  double te[2], he[2];
  int nae;             /* how many of them are valid */
  /* the step being solved, for the callbacks */
  sym_eval *ev;
  double t, h;
  const double *yk;
} spvi_core;

/* A step: where it started, its end, its polynomials. */
typedef struct {
  double t, h, tend;
  double *y0, *y1;     /* 2d each */
  double *a;           /* a_1..a_{n-1}: a[(i-1)*d + k] */
  double *P;           /* P[j*d + k] */
  double *dq;          /* d: end correction of q (adaptive), or zeros */
  int has_dq;
  int cont;            /* xp continued the step before, of the same h */
  /* dense output of the pairs n - 1 = m (dense.c): dy/dz at -1, the M
     nodes of the solve the run advances with, +1, 2d each; the ends are
     h/2 f(t, y) there, evaluated when first needed (fe0, fe1: f itself),
     the nodes' from the solution */
  double *D;           /* (m + 3) x 2d; D, fe0 and emis only with dense
                          output */
  double *fe0, *fe1;   /* 2d each */
  double *emis;        /* 2d: y1 - u(1), the end mismatch */
  double *cmp;         /* 2d: the rounding of y1 (fixed steps: their sum
                          compensated, step.c) */
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
                          below 8: cubic Hermite through the step's ends */
  double tol;
  int maxit;
  int newmat;          /* SYM_MATRIX_AUTO, _KEPT or _NEW */
  int nonlinear;       /* SYM_NONLINEAR_* */
  int stages;          /* SPVI_FULL, _STAGES or _STAGES_SPARSE */
  int adaptive;        /* set_tolerances was called */
  int reversible;      /* reversible steps: solved further (a retraced
                          run then comes back to round-off) */
  double est_rtol, est_atol;   /* the adaptive tolerances (atol: the
                                  smallest) */
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
  /* the continued prediction with its noise cut off (predict.c) */
  double *ach;         /* (n - 1) d: q's modes a_i */
  double *pz, *pw;     /* m + 2 Gauss points and weights */
  double *pc;          /* (m + 2) d: p's Legendre coefficients */
  /* errors of the polynomial prediction (solution - prediction) of the
     last nhist accepted steps, newest first, SYM_SPVI_HIST + 1 of N each;
     all continued steps of size hhist */
  float *dhist;        /* (single precision, in units of dscale: they
                          only correct a start, and held a large part of
                          a large system's memory) */
  double dscale[SYM_SPVI_HIST + 1];
  double *xp;          /* the trial's polynomial prediction of x
                          (predict.c), for dhist when it is accepted */
  double *hw;          /* N: work of spvi_predict_history */
  /* the basis values predict_poly evaluates at its points, for (z0, rho)
     (pt_ok): the same at every continued step of a fixed h */
  double pt_z0, pt_rho, pt_amp;
  int pt_ok;
  double *pt_q;        /* n x n: l_i(z_l) - l_i(-1) at the n points of q */
  double *pt_p;        /* m x (m + 2): p's Lagrange basis at the nodes */
  int nhist;
  double hhist;
  /* the largest sizes of q and of p in the steps solved so far */
  double typ_q, typ_p;
  /* the last step spvi_clock was given */
  double ck_t, ck_h, ck_tend;
  int ck_ok;
} spvi_state;

/* The node Jacobian block used for node j */
static inline const double *
spvi_A (const spvi_core *c, int j)
{
  const size_t nn = 2 * (size_t) c->d;
  return c->A + (size_t) j * nn * nn;
}

/* The blocks of node Jacobian A (2d x 2d): A = [Aqq Aqp; Apq App] */
#define AQQ(A, k, l) (A)[(k) + (size_t) (l) * nn]
#define AQP(A, k, l) (A)[(k) + (size_t) (d + (l)) * nn]
#define APQ(A, k, l) (A)[(d + (k)) + (size_t) (l) * nn]
#define APP(A, k, l) (A)[(d + (k)) + (size_t) (d + (l)) * nn]

/* ---------------------------------------------------------------- equations.c */
/* stages: SPVI_FULL, SPVI_STAGES or SPVI_STAGES_SPARSE */
int spvi_core_init (spvi_core *c, int d, int n, int m, int stages);
void spvi_core_free (spvi_core *c);
/* node states Y_j = [Q_j; P_j] from x */
void spvi_states (spvi_core *c, const double *x);
/* before a new evaluation at x: the last one becomes the one before it */
void spvi_eval_shift (spvi_core *c, const double *x);
/* F = f at the nodes of x (one batch call), unless F is already at x */
int spvi_eval (spvi_core *c, const double *x);
/* the residual (R1, R2) at x (sym_newton_problem's residual) */
int spvi_residual (void *ctx, const double *x, double *r);
/* after the solve: f_p of the last evaluation moved to the final x by the
   node Jacobians, and the step's end [q_{k+1}; p_{k+1}] into yend */
void spvi_end (spvi_core *c, double *yend);

/* ---------------------------------------------------------------- jacobians.c */
/* Newton's matrix at x from new node Jacobians (sym_newton_problem's
   matrix) */
int spvi_matrix (void *ctx, const double *x, double *M);
/* the node Jacobians c->A at x (f at x too where the same calls give it) */
int spvi_node_jacobians (spvi_core *c, const double *x);
/* out = M v, M Newton's matrix of c->A (dy: work, 4 d m) */
void spvi_matvec (const spvi_core *c, const double *v, double *out,
                  double *dy);
/* the kept evaluations count from a step that starts shift later */
void spvi_core_move (spvi_core *c, double shift);
/* the matrix from node Jacobians extrapolated in time (no callback);
   0 if not made */
int spvi_extrapolate (spvi_core *c, sym_eval *ev);
/* the companion's matrix from the method's node Jacobians of the same
   step, interpolated to its nodes; 1 if made */
int spvi_borrow (spvi_core *c, const spvi_core *src, sym_eval *ev);

/* ---------------------------------------------------------------- staged.c */
/* c->sg for the pair of c (SYM_EBADINPUT: not a pair n - 1 = m) */
int spvi_stages_init (spvi_core *c, int sparse);
/* whether the stages can be exact (dense J) */
int spvi_stages_dense (const spvi_core *c);
void spvi_stages_free (spvi_core *c);

/* ---------------------------------------------------------- staged_factor.c */
/* sym_newton_problem's factor */
int spvi_stages_factor (void *ctx, const double *x, sym_counters *cnt);
/* out (d) = the p rows of node j's Jacobian (c->A, or the stages' J
   unless exact) times dy (2d) */
void spvi_jac_p (spvi_core *c, int j, const double *dy, double *out);
/* c->noise_q, noise_p from the stages' J (see predict.c) */
void spvi_stages_noise (spvi_core *c, const double *qa, const double *pa);

/* ----------------------------------------------------------- staged_solve.c */
/* sym_newton_problem's solve */
int spvi_stages_solve (void *ctx, double *b, sym_counters *cnt);
/* sym_newton_problem's correction of the fixed point (c->fp) */
int spvi_fp_correction (void *ctx, const double *x, double *dx);

/* ---------------------------------------------------------------- solve.c */
/* Solve the step (t, h, yk) from the start c->x to tol (relative to the
   scales S); on success c->x holds the solution and yend = [q_{k+1};
   p_{k+1}] */
int spvi_solve (spvi_core *c, sym_eval *ev, double t, double h,
                const double *yk, const spvi_scale *S, const spvi_state *s,
                double tol, double *yend);

/* ---------------------------------------------------------------- predict.c */
/* the momentum polynomial of step r (through (-1, p_k), (z_j, P_j),
   (1, p_{k+1})) at z, into p (d values) */
void spvi_rec_p (const spvi_state *s, const spvi_rec *r, double z,
                 double *p);
/* q(z) - q_k of the modes a (a_1..a_{n-1}, d values each), into q */
void spvi_modes_dq (const spvi_state *s, const double *a, double z,
                    double *q);
/* the accuracy of the solved a and P of r */
void spvi_rec_noise (const spvi_state *s, spvi_rec *r, double tol,
                     const spvi_scale *S);
/* The start of Newton for the step (t, h, y) into s->lo.x (euler: from
   an explicit Euler step, not the last step's polynomials); the scales of
   the stopping test into *S (adaptive: one scale for q and p) */
int spvi_predict (spvi_state *s, sym_eval *ev, double t, double h,
                  const double *y, int euler, int adaptive, spvi_scale *S);
/* the start plus the extrapolated errors of the last predictions */
void spvi_predict_history (spvi_state *s, double h);
/* a fixed step that Newton could not solve, reached from shorter ones */
int spvi_lengthen (spvi_state *s, sym_eval *ev, double t, double h,
                   double tol, spvi_scale *S);

/* ---------------------------------------------------------------- dense.c */
/* the dense output's data at the nodes of the solve c into r */
void spvi_rec_nodes (spvi_rec *r, const spvi_core *c);
int spvi_dense (void *state, sym_eval *ev, double t, double *y);

#endif
