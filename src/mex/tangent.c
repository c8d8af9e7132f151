/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* tangent.c -- TangentMap: "on" for the full Phi = d y_k / d y_0, or an
   n-by-k matrix of initial deviation vectors; the core carries it
   through the explicit fixed steps of odeSE and odeSV (core:
   methods/tangent.c), and Phi at every step point comes back in
   sol.phi.  What this version cannot carry it through is refused here,
   before the run, naming the solver and the option. */
#include "symmex.h"

#include <math.h>
#include <string.h>

typedef struct symmex_tangent_s {
  const sym_tangent *tg;
  size_t len;          /* n * m */
  double *buf;         /* Phi at the rows kept */
  int lyap;            /* Indicators "lyapunov" */
  double *lbuf;        /* and the log growth at the rows */
  size_t rows, cap;
} symmex_tangent;

/* Indicators: "lyapunov" (a word or a cell of words), or none ({},
   "none"); whether the exponent is asked for */
static int
indicators (const char *name, const mxArray *v)
{
  static const char *const words[] = { "lyapunov", "none", NULL };
  if (! v)
    return 0;
  if (! mxIsCell (v))
    return symmex_word (name, v, "Indicators", words) == 0;
  int lyap = 0;
  for (size_t k = 0; k < mxGetNumberOfElements (v); k++)
    {
      const mxArray *e = mxGetCell (v, k);
      char buf[64];
      if (! e || ! mxIsChar (e))
        mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: Indicators must be "
                           "\"lyapunov\" or a cell of such names, got an "
                           "element %s", name,
                           e ? symmex_describe (e, buf, sizeof buf) : "[]");
      lyap |= symmex_word (name, e, "Indicators", words) == 0;
    }
  return lyap;
}

static void
refuse (const char *solver, const char *why)
{
  mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: TangentMap %s", solver, why);
}

sym_tangent *
symmex_tangent_setup (const symmex_method *m, void *own,
                      const symmex_args *a, const symmex_opts *o, int nlhs)
{
  const mxArray *v = o->tangent;
  const char *name = m->name;
  const int n = a->n;
  char buf[64];
  const int lyap = indicators (name, o->indicators);
  if (lyap && ! v)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: Indicators \"lyapunov\" needs "
                       "TangentMap, a %d-by-1 deviation vector to follow",
                       name, n);
  if (! v)
    return NULL;
  const double *v0 = NULL;
  int cols = n;
  if (mxIsChar (v) || mxIsLogical (v)
      || (mxIsNumeric (v) && mxGetNumberOfElements (v) == 1 && n > 1))
    {
      if (! symmex_on_off (name, v, "TangentMap"))
        {
          if (lyap)
            mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: Indicators \"lyapunov\" "
                               "needs TangentMap, a %d-by-1 deviation "
                               "vector to follow; TangentMap is off", name,
                               n);
          return NULL;
        }
    }
  else
    {
      if (! mxIsDouble (v) || mxIsComplex (v) || mxIsSparse (v)
          || mxGetNumberOfDimensions (v) != 2 || mxGetM (v) != (size_t) n
          || mxGetN (v) < 1)
        mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: TangentMap must be \"on\", "
                           "\"off\" or a %d-by-k real matrix of initial "
                           "deviation vectors, got %s", name, n,
                           symmex_describe (v, buf, sizeof buf));
      v0 = mxGetPr (v);
      for (size_t i = 0; i < mxGetNumberOfElements (v); i++)
        if (! isfinite (v0[i]))
          mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: TangentMap's deviation "
                             "vectors must be finite, got %s in element %zu",
                             name, SYMMEX_NUM (v0[i], "%g"), i + 1);
      cols = (int) mxGetN (v);
    }
  if (lyap && cols != 1)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: Indicators \"lyapunov\" follows "
                       "one deviation vector: give TangentMap as a %d-by-1 "
                       "vector, got %d-by-%d", name, n, n, cols);
  if (! m->take_tangent)
    refuse (name, "is not supported by this solver yet (its stages are "
            "implicit); use odeSE or odeSV with Separable or SecondOrder "
            "on");
  if (m->needs_newton (own))
    refuse (name, "needs explicit steps: set Separable (or SecondOrder) on "
            "(the implicit steps of a general H do not carry it yet)");
  if (! symmex_fixed (o) || o->reversible)
    refuse (name, "needs fixed steps: give TimeStepSize or TimeStepNumber "
            "(adaptive and reversible steps do not carry it yet)");
  if (o->ensemble)
    refuse (name, "is not supported with Ensemble yet");
  if (o->events)
    refuse (name, "is not supported with Events yet (Phi is known at the "
            "step points only)");
  if (o->dense)
    refuse (name, "is not supported with Dense (Phi is not interpolated)");
  if (a->k0 > 0 || a->rho0 > 0)
    refuse (name, "is not supported with a sol as Y0 (Phi would restart "
            "from the identity there); start from the state sol.y(:,end)");
  if (nlhs != 1)
    refuse (name, "comes back in sol.phi only: call with one output, "
            "sol = solver (...)");
  sym_tangent *tg = sym_tangent_new (n / 2, cols, v0);
  if (! tg)
    mexErrMsgIdAndTxt ("symplectic:nomem", "%s: out of memory for "
                       "TangentMap (%d-by-%d)", name, n, cols);
  if (lyap)
    sym_tangent_renormalise (tg);
  m->take_tangent (own, tg);
  return tg;
}

/* SecondOrder's FCN returns the acceleration only: its Hessian comes
   from HamiltonianHessFcn or Jacobian, else by differences */
int
symmex_tangent_needs_jac (const symmex_opts *o, int second_order)
{
  return ! second_order || o->hessfcn || o->jacobian;
}

void
symmex_tangent_attach (symmex_ctx *c, sym_tangent *tg)
{
  symmex_tangent *t = mxCalloc (1, sizeof *t);
  t->tg = tg;
  t->len = (size_t) c->n * (size_t) sym_tangent_columns (tg);
  t->lyap = indicators (c->solver, c->o->indicators);
  c->tangent = t;
  /* (the stats name the source of the tangent's blocks) */
  if (c->jac_source == JAC_NONE)
    c->jac_source = JAC_FD;
}

void
symmex_tangent_row (symmex_ctx *c)
{
  symmex_tangent *t = c->tangent;
  const int lyap = t->lyap;
  if (t->rows == t->cap)
    {
      size_t cap = t->cap ? 2 * t->cap : 64;
      t->buf = mxRealloc (t->buf, cap * t->len * sizeof (double));
      if (lyap)
        t->lbuf = mxRealloc (t->lbuf, cap * sizeof (double));
      t->cap = cap;
    }
  if (lyap)
    t->lbuf[t->rows] = sym_tangent_log_growth (t->tg);
  memcpy (t->buf + t->rows * t->len, sym_tangent_phi (t->tg),
          t->len * sizeof (double));
  t->rows++;
}

void
symmex_tangent_sol (symmex_ctx *c, mxArray *sol)
{
  symmex_tangent *t = c->tangent;
  mwSize dims[3] = { (mwSize) c->n,
                     (mwSize) sym_tangent_columns (t->tg),
                     (mwSize) t->rows };
  mxArray *phi = mxCreateNumericArray (3, dims, mxDOUBLE_CLASS, mxREAL);
  if (t->rows)
    memcpy (mxGetPr (phi), t->buf, t->rows * t->len * sizeof (double));
  mxFree (t->buf);
  t->buf = NULL;
  mxAddField (sol, "phi");
  mxSetField (sol, 0, "phi", phi);
  if (! t->lbuf)
    return;
  /* the exponent's estimate at each row: the log growth over the time
     from t0 (none at t0 itself) */
  mxArray *ly = mxCreateDoubleMatrix (1, t->rows, mxREAL);
  double *l = mxGetPr (ly);
  for (size_t k = 0; k < t->rows; k++)
    l[k] = k ? t->lbuf[k] / (c->tbuf[k] - c->tbuf[0]) : NAN;
  mxFree (t->lbuf);
  t->lbuf = NULL;
  mxAddField (sol, "lyapunov");
  mxSetField (sol, 0, "lyapunov", ly);
}
