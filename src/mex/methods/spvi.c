/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* spvi.c -- odeSPVI: the spectral variational integrator (core:
   methods/spvi/).  Its own options: Q_DoFs (modes of q), Nodes (alias
   P_DoFs), odepkg's PolynomialDegree (Q_DoFs = degree + 1, and Nodes
   unless given), NewtonMatrix, NewtonSystem, NonlinearSolver; sol gains the order used
   and the pair. */
#include "../symmex.h"

static const char *const spvi_options[] = {
  "Q_DoFs", "Nodes", "P_DoFs", "PolynomialDegree", "NewtonMatrix",
  "NewtonSystem", "NonlinearSolver", NULL
};

/* Nodes and its alias, Q_DoFs and PolynomialDegree: two names of one
   number that disagree are refused rather than one of them winning */
static void
spvi_pair (const char *solver, const mxArray *opts, sym_spvi_opts *o)
{
  const int mx = SYM_SPVI_MAX_NODES;
  const mxArray *vn = symmex_field (solver, opts, "Nodes");
  const mxArray *vp = symmex_field (solver, opts, "P_DoFs");
  const mxArray *vq = symmex_field (solver, opts, "Q_DoFs");
  const mxArray *vd = symmex_field (solver, opts, "PolynomialDegree");
  int pn = vn ? (int) symmex_integer (solver, vn, "Nodes", 1, mx) : 0;
  int pp = vp ? (int) symmex_integer (solver, vp, "P_DoFs", 1, mx) : 0;
  int pq = vq ? (int) symmex_integer (solver, vq, "Q_DoFs", 2, mx + 1) : 0;
  int pd = vd ? 1 + (int) symmex_integer (solver, vd, "PolynomialDegree",
                                          1, mx - 1) : 0;
  if (vn && vp && pn != pp)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: Nodes = %d and its alias P_DoFs "
                       "= %d disagree; give one of them", solver, pn, pp);
  if (vq && vd && pq != pd)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: Q_DoFs = %d and PolynomialDegree "
                       "= %d (Q_DoFs = degree + 1) disagree; give one of "
                       "them", solver, pq, pd - 1);
  o->nodes = vn ? pn : vp ? pp : vd ? pd : SYM_SPVI_NODES;
  o->q_dofs = vq ? pq : vd ? pd : o->nodes + 1;
  if (o->q_dofs > 2 * o->nodes)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: Q_DoFs = %d with Nodes = %d is a "
                       "degenerate pair: the scheme does not converge unless "
                       "Q_DoFs <= 2*Nodes", solver, o->q_dofs, o->nodes);
}

static void
spvi_parse (const char *solver, const mxArray *opts, void *own)
{
  static const char *const matrix[] = { "auto", "kept", "new", NULL };
  sym_spvi_opts *o = own;
  /* an option of odeSE and odeSV, but one that changes what FCN means:
     refused rather than ignored */
  const mxArray *so = symmex_field (solver, opts, "SecondOrder");
  if (so && symmex_on_off (solver, so, "SecondOrder"))
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: SecondOrder is for odeSE and "
                       "odeSV; give %s FCN as Hamilton's equations, "
                       "[v; a(t, q)] for y = [q; v]", solver, solver);
  spvi_pair (solver, opts, o);
  const mxArray *v = symmex_field (solver, opts, "NewtonMatrix");
  const int k = v ? symmex_word (solver, v, "NewtonMatrix", matrix) : 0;
  o->newton_matrix = k == 1 ? SYM_MATRIX_KEPT : k == 2 ? SYM_MATRIX_NEW
                     : SYM_MATRIX_AUTO;
  static const char *const system[] = { "auto", "full", "stages", NULL };
  v = symmex_field (solver, opts, "NewtonSystem");
  const int ks = v ? symmex_word (solver, v, "NewtonSystem", system) : 0;
  o->system = ks == 1 ? SYM_SYSTEM_FULL : ks == 2 ? SYM_SYSTEM_STAGES
              : SYM_SYSTEM_AUTO;
  if (o->system == SYM_SYSTEM_STAGES && o->q_dofs != o->nodes + 1)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: NewtonSystem \"stages\" needs "
                       "Q_DoFs = Nodes + 1, got Q_DoFs = %d with Nodes = %d",
                       solver, o->q_dofs, o->nodes);
  static const char *const nonlin[] = { "newton", "fixedpoint", "auto",
                                        NULL };
  v = symmex_field (solver, opts, "NonlinearSolver");
  const int kn = v ? symmex_word (solver, v, "NonlinearSolver", nonlin) : 0;
  o->nonlinear = kn == 1 ? SYM_NONLINEAR_FIXEDPOINT
                 : kn == 2 ? SYM_NONLINEAR_AUTO : SYM_NONLINEAR_NEWTON;
  if (o->nonlinear != SYM_NONLINEAR_NEWTON && o->q_dofs != o->nodes + 1)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: NonlinearSolver \"%s\" needs "
                       "Q_DoFs = Nodes + 1, got Q_DoFs = %d with Nodes = %d",
                       solver, nonlin[kn], o->q_dofs, o->nodes);
  if (o->nonlinear != SYM_NONLINEAR_NEWTON && o->system == SYM_SYSTEM_FULL)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: NonlinearSolver \"%s\" iterates "
                       "by stages; it falls back to Newton by stages too, "
                       "not with NewtonSystem \"full\"", solver, nonlin[kn]);
}

/* a sparse Df stays sparse (by stages for the pairs Q_DoFs = Nodes + 1,
   else the whole system) unless NewtonSystem is "full" */
static int
spvi_take_sparse (void *own, int commit)
{
  sym_spvi_opts *o = own;
  const int ok = o->system != SYM_SYSTEM_FULL;
  if (ok && commit)
    o->sparse = 1;
  return ok;
}

static int
spvi_needs_newton (const void *own)
{
  (void) own;
  return 1;
}

/* the order of the solution returned (adaptive runs advance with the
   companion of the error estimate) and the pair */
static void
spvi_sol_fields (mxArray *sol, const void *own, const sym_stats *st)
{
  const sym_spvi_opts *o = own;
  mxAddField (sol, "order");
  mxAddField (sol, "Q_DoFs");
  mxAddField (sol, "Nodes");
  mxSetField (sol, 0, "order", mxCreateDoubleScalar (st->order));
  mxSetField (sol, 0, "Q_DoFs", mxCreateDoubleScalar (o->q_dofs));
  mxSetField (sol, 0, "Nodes", mxCreateDoubleScalar (o->nodes));
}

/* the pairs n - 1 > m: their extra modes of q are fixed only by d2H/dq2
   (singular Newton matrices where it vanishes, whatever the step) */
static const char *
spvi_newton_hint (const void *own)
{
  const sym_spvi_opts *o = own;
  return o->q_dofs - 1 > o->nodes
         ? "Q_DoFs - 1 > Nodes: such pairs are degenerate where d2H/dq2 "
           "vanishes or is small; Q_DoFs <= Nodes + 1 is not"
         : NULL;
}

/* the Galerkin step with Gauss nodes is symmetric for every pair */
static const char *
spvi_asymmetric (const void *own)
{
  (void) own;
  return NULL;
}

const symmex_method symmex_method_spvi = {
  "odeSPVI", &sym_step_spvi, sizeof (sym_spvi_opts), spvi_parse,
  spvi_options, spvi_needs_newton, spvi_sol_fields, spvi_newton_hint, NULL,
  NULL, NULL, spvi_asymmetric, spvi_take_sparse
};
