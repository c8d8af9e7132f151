/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* solve.c -- odeSPVI's solve of one step: Newton (simplified, with a kept,
   extrapolated, borrowed or new matrix; full as the fallback) on the
   reduced equations, then the step's end from the solution.

   Every residual costs one sym_rhs_many call (m states; one call of the
   Vectorized batch callback), so the cost of a step is its number of
   corrections.  The last correction is not followed by another residual:
   the f_p of the last evaluation are moved linearly to the corrected x by
   the node Jacobians (spvi_end), and they give p_{k+1}.  So the stopping
   test bounds the estimated error of the result itself, at tol/100 of
   NewtonTol on fixed steps (SYM_FIXED_TOL), and the error of that move is
   estimated from the previous correction's move, checked against the f
   evaluated after it: above tol, one more correction.

   The pairs n - 1 != m keep an earlier scheme: their matrices are
   ill-conditioned, so that a contraction rate measured from two
   corrections does not bound the error left.  They converge to the
   Newton tolerance, then make one more correction from a new residual,
   unchecked; their matrices are evaluated, never extrapolated. */
#include "spvi.h"

#include <float.h>
#include <math.h>
#include <string.h>

/* Estimated error, relative to S, that the linear move of f_p from xf
   (the last evaluation) to x leaves in p_{k+1} = p_k + (h/2) sum_j w_j
   f_p,j: the move from xfo to xf by the same node Jacobians is compared
   with the f_p evaluated at xf, node by node, and scaled by the ratio of
   the two moves.  0 if x = xf; infinite if there is no earlier
   evaluation to compare with. */
static double
move_error (spvi_core *c, double S)
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
          n1 = sym_fmax_acc (sym_fmax_acc (n1, fabs (v1)), fabs (dy[d + k]));
          n2 = sym_fmax_acc (sym_fmax_acc (n2, fabs (v2)),
                             fabs (a[ip] - af[ip]));
        }
      if (n2 == 0.0)
        continue;
      if (! c->fovalid || n1 == 0.0)
        return INFINITY;
      /* the fixed point's J is 0: nothing moved */
      double *jdy = dy + nn;
      if (! c->fp)
        spvi_jac_p (c, j, dy, jdy);
      for (int k = 0; k < d; k++)
        {
          double v = c->F[(size_t) j * nn + d + k]
                     - c->Fo[(size_t) j * nn + d + k];
          if (! c->fp)
            v -= jdy[k];
          mis = sym_fmax_acc (mis, fabs (v));
        }
      e += c->w[j] * mis * (n2 / n1);
    }
  return 0.5 * fabs (c->h) * e / S;
}

/* The matrix for the solve of (t, h) by the core c (the method's, s->lo,
   or the companion's): a kept matrix is dropped when h changed by more
   than SYM_REBUILD_H, else extrapolated to this step's nodes; a new one
   on every solve (quad: its first correction is exact Newton, often the
   only one) by option, or by default when the node Jacobians are finite
   differences through the batch callback (the nodes and their perturbed
   states take one call) and the LU is small; the companion's from the
   method's Jacobians when it has none.  Returns whether the matrix is new
   on every solve. */
static int
prepare_matrix (spvi_core *c, sym_eval *ev, const spvi_state *s, double h)
{
  const int fast = c->n - 1 == c->m, method = c == &s->lo;
  if (c->nw.have_matrix
      && ! (fabs (h - c->h_mat) <= SYM_REBUILD_H * fabs (c->h_mat)))
    sym_newton_invalidate (&c->nw);
  const int every = fast && method
                    && (s->newmat == SYM_MATRIX_NEW
                        || (s->newmat == SYM_MATRIX_AUTO
                            && c->N <= SYM_SPVI_EVERY_N && ev->rhs_batch
                            && ! ev->jac && ! ev->rhs_jac));
  /* the stages' solve is Newton's own only when exact (staged.c) */
  c->exact = every && spvi_stages_dense (c) && ! c->fp;
  c->nw.quad = every && (! c->sg || c->exact);
  if (every)
    {
      sym_newton_invalidate (&c->nw);
      /* kq follows h (it is about h/2 times a second derivative of f) */
      if (c->nw.kq_ok
          && ! (fabs (h - c->h_kq) <= SYM_REBUILD_H * fabs (c->h_kq)))
        c->nw.kq_ok = 0;
    }
  if (c->sg)
    ;   /* no node Jacobians to extrapolate or borrow: kept or new */
  else if (fast && c->nw.have_matrix)
    spvi_extrapolate (c, ev);
  else if (fast && ! method)
    spvi_borrow (c, &s->lo, ev);
  return every;
}

/* After Newton: the corrections that the move of f_p to the final x
   needs (pairs n - 1 = m: while its estimated error exceeds move_tol; after a single exact correction, nw.one, the Jacobians of
   the move are those at xf itself and its error is the quadratic
   remainder that Newton's estimate has bounded), or the earlier scheme's
   one more correction (not counted in iters) */
static int
final_corrections (spvi_core *c, sym_eval *ev, const spvi_scale *S,
                   const sym_newton_problem *prob)
{
  const int fast = c->n - 1 == c->m;
  int st = SYM_SUCCESS;
  for (int k = 0; fast && ! c->nw.one && k < SYM_SPVI_MOVE_MAX
                  && move_error (c, S->p) > c->move_tol; k++)
    {
      if ((st = sym_newton_dx (&c->nw, prob, c->x, NULL, &ev->st.cnt,
                               NULL)))
        return st;
      sym_newton_apply (&c->nw, c->x, &ev->st.cnt);
      c->nw.iters++;
    }
  if (! fast && ! (st = sym_newton_dx (&c->nw, prob, c->x, NULL,
                                       &ev->st.cnt, NULL)))
    sym_newton_apply (&c->nw, c->x, &ev->st.cnt);
  return st;
}

/* A fresh matrix for the next step after a slow solve (more than
   SYM_SPVI_REFRESH_ITERS corrections), unless the matrix was not to
   blame: its first contraction |dx_2|/|dx_1| was below
   SYM_SPVI_THETA_FRESH, so the start was just far.  The extra corrections
   must have cost as many calls as new node Jacobians: as many as one
   correction with the user's Jacobian (refreshing at once), 2d times as
   many with finite differences (Vectorized takes the same steps). */
static void
refresh_policy (spvi_core *c, const sym_eval *ev)
{
  if (c->n - 1 != c->m)
    {
      if (c->nw.iters > SYM_SPVI_REFRESH_SLOW)
        sym_newton_invalidate (&c->nw);
      return;
    }
  if (c->nw.iters > SYM_SPVI_REFRESH_ITERS
      && ! (c->ndx >= 2 && c->dxn[1] <= SYM_SPVI_THETA_FRESH * c->dxn[0]))
    {
      c->extra += c->nw.iters - SYM_SPVI_REFRESH_ITERS;
      const int cost = sym_jac_cost (ev);
      if (c->extra >= cost)
        sym_newton_invalidate (&c->nw);
    }
}

/* Fixed point (v = 1) or Newton for the next solve: the stages' factors
   are those of the other one */
static void
set_fp (spvi_core *c, int v)
{
  if (c->fp == v)
    return;
  c->fp = v;
  sym_newton_invalidate (&c->nw);
  c->nw.kq_ok = 0;
}

int
spvi_solve (spvi_core *c, sym_eval *ev, double t, double h,
            const double *yk, const spvi_scale *S, const spvi_state *s,
            double tol, double *yend)
{
  const int d = c->d, n = c->n, m = c->m, N = c->N;
  const int fast = n - 1 == m;
  c->ev = ev;
  c->t = t;
  c->h = h;
  c->yk = yk;
  c->fvalid = 0;
  c->ndx = 0;
  for (int j = 0; j < m; j++)
    c->tj[j] = t + 0.5 * h * (c->z[j] + 1.0);
  set_fp (c, c->sg && s->nonlinear != SYM_NONLINEAR_NEWTON && ! c->fp_off);
  int every = prepare_matrix (c, ev, s, h);
  for (int i = 0; i < N; i++)
    c->scale[i] = i < (n - 1) * d ? S->q : S->p;
  c->nw.tol = fast ? tol : s->tol;
  /* a fixed point to round-off stops by its linear rate, whose error has
     a sign from step to step: further below the tolerance */
  if (c->fp && tol <= SYM_FIXED_TOL * s->tol)
    c->nw.tol *= SYM_SPVI_FP_TOL;
  c->move_tol = s->adaptive ? c->nw.tol : SYM_SPVI_MOVE_FIXED * c->nw.tol;
  c->nw.maxit = c->fp ? fmax (s->maxit, SYM_SPVI_FP_MAXIT) : s->maxit;
  sym_newton_problem prob = { spvi_residual, spvi_matrix, c,
                              c->sg ? spvi_stages_factor : NULL,
                              c->sg ? spvi_stages_solve : NULL,
                              c->fp && fast ? spvi_fp_correction : NULL };
  int st = sym_newton_solve (&c->nw, &prob, c->x, c->scale, &ev->st.cnt);
  if (c->fp && (st == SYM_NEWTON_FAIL || c->nw.iters > SYM_SPVI_FP_SLOW))
    {
      /* auto: a fixed point that fails, or converges slowly, gives way
         to Newton for the rest of the run; a failed one is solved again
         by Newton */
      if (s->nonlinear == SYM_NONLINEAR_AUTO)
        c->fp_off = 1;
      if (st == SYM_NEWTON_FAIL)
        {
          memcpy (c->x, c->nw.x0, (size_t) N * sizeof (double));
          set_fp (c, 0);
          prob.correction = NULL;
          every = prepare_matrix (c, ev, s, h);
          c->nw.maxit = s->maxit;
          st = sym_newton_solve (&c->nw, &prob, c->x, c->scale,
                                 &ev->st.cnt);
        }
    }
  if (every && c->nw.kq_new)
    c->h_kq = h;
  /* the simplified iteration failed (a failed callback comes back with
     its own status: no retry, it asks for a smaller step): full Newton
     from the same start, which the pairs n - 1 > m need where the
     potential's curvature is small */
  if (st == SYM_NEWTON_FAIL)
    {
      memcpy (c->x, c->nw.x0, (size_t) N * sizeof (double));
      c->nw.mode = SYM_NEWTON_FULL;
      st = sym_newton_solve (&c->nw, &prob, c->x, c->scale, &ev->st.cnt);
      c->nw.mode = SYM_NEWTON_SIMPLIFIED;
    }
  if (! st)
    st = final_corrections (c, ev, S, &prob);
  if (st)
    {
      c->fvalid = 0;
      return st;
    }
  refresh_policy (c, ev);
  spvi_end (c, yend);
  return SYM_SUCCESS;
}
