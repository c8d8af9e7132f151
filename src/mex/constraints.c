/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* constraints.c -- odeSV's Constraints: the user's g = con (q) (or [g, G]
   = con (q)) as the core's callback, probed at q0, and Y0 moved onto the
   constraints before the run. */
#include "symmex.h"

#include <float.h>
#include <math.h>
#include <string.h>

typedef struct {
  const char *solver;
  int d, m;
  mxArray *args[2];        /* {con, q} */
  char name[64];
  sym_constraints cs;
} con_ctx;

static const char *const G_EXPECT = "the Constraints function's second "
                                    "output G = dg/dq must be";

/* the user's function at q with nout outputs into out */
static void
con_call (con_ctx *k, const double *q, int nout, mxArray **out)
{
  memcpy (mxGetPr (k->args[1]), q, sizeof (double) * k->d);
  out[0] = out[1] = NULL;
  symmex_call (nout, out, 2, k->args, k->name);
}

/* g's values (m of them when m > 0), checked */
static const double *
con_g (con_ctx *k, mxArray **pa, int m)
{
  char buf[64];
  mxArray *a = symmex_take_full (pa);
  const size_t ne = a ? mxGetNumberOfElements (a) : 0;
  if (! a || ! mxIsNumeric (a) || mxIsComplex (a)
      || (m > 0 && ne != (size_t) m) || (m == 0 && ne < 1))
    {
      if (m > 0)
        mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: the Constraints function "
                           "must return g(q), a vector of %d real values, "
                           "got %s", k->solver, m,
                           a ? symmex_describe (a, buf, sizeof buf)
                           : "nothing");
      mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: the Constraints function must "
                         "return g(q), a vector of m real values, 1 <= m < "
                         "%d (the positions), got %s", k->solver, k->d,
                         a ? symmex_describe (a, buf, sizeof buf)
                         : "nothing");
    }
  return mxGetPr (symmex_take_double (pa));
}

static const double *
con_G (con_ctx *k, mxArray **pa)
{
  char buf[64];
  mxArray *a = *pa;
  if (! a || ! mxIsNumeric (a) || mxIsComplex (a)
      || ! symmex_is_size (a, k->m, k->d))
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: %s a %dx%d real matrix (full or "
                       "sparse), got %s", k->solver, G_EXPECT, k->m, k->d,
                       a ? symmex_describe (a, buf, sizeof buf) : "nothing");
  symmex_take_full (pa);
  return mxGetPr (symmex_take_double (pa));
}

static int
con_cb (const double *q, double *g, double *G, void *user)
{
  con_ctx *k = user;
  mxArray *out[2];
  /* a function that gives G is always asked for it: one written with
     deal (g, G) cannot return g alone */
  con_call (k, q, k->cs.has_G ? 2 : 1, out);
  memcpy (g, con_g (k, &out[0], k->m), sizeof (double) * k->m);
  mxDestroyArray (out[0]);
  if (k->cs.has_G)
    {
      const double *v = con_G (k, &out[1]);
      if (G)
        memcpy (G, v, sizeof (double) * k->m * k->d);
      mxDestroyArray (out[1]);
    }
  return 0;
}

/* Y0 onto g = 0 and G dH/dp = 0 (see symmex.h) */
static void
project_y0 (symmex_ctx *c, symmex_args *a, const sym_system *sys,
            const sym_constraints *cs)
{
  const int n = c->n, d = c->d;
  double *y = mxMalloc (sizeof (double) * n);
  memcpy (y, a->y0, sizeof (double) * n);
  sym_eval ev;
  sym_eval_init (&ev, sys);
  double dq, dp;
  int st = sym_constraints_project (cs, &ev, c->second_order, a->tspan[0],
                                    y, &dq, &dp);
  c->probe_calls += ev.st.cnt.nrhs;
  c->probe_states += ev.st.cnt.nrhs_states;
  sym_eval_free (&ev);
  if (st)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: Y0 could not be moved onto the "
                       "Constraints g(q) = 0 and G(q) dH/dp = 0 (%s); give "
                       "a Y0 on them, with G of full rank m there",
                       c->solver, st == SYM_SINGULAR ? "G G' is singular"
                       : st == SYM_NONFINITE ? "a value was NaN or Inf"
                       : "Newton did not converge");
  /* relative to the largest |y0_i| (p may be zero, or small) */
  double ys = 0.0;
  for (int i = 0; i < n; i++)
    ys = fmax (ys, fmax (fabs (a->y0[i]), fabs (y[i])));
  (void) d;
  const double rq = dq / (ys > 0 ? ys : 1), rp = dp / (ys > 0 ? ys : 1);
  if (rq > SYMMEX_CON_FAR || rp > SYMMEX_CON_FAR)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: Y0 is far from the Constraints: "
                       "onto g(q) = 0 and G(q) dH/dp = 0 q moves by %.3g "
                       "relative and p by %.3g, more than %g; give a Y0 on "
                       "them (or near: it is then moved, with a warning)",
                       c->solver, rq, rp, SYMMEX_CON_FAR);
  if (rq > 64 * DBL_EPSILON || rp > 64 * DBL_EPSILON)
    {
      mexWarnMsgIdAndTxt ("symplectic:constraints-projected", "%s: Y0 was "
                          "off the Constraints; moved onto g(q) = 0 and "
                          "G(q) dH/dp = 0: q by %.3g (%.3g relative), p by "
                          "%.3g (%.3g relative)", c->solver, dq, rq, dp, rp);
      /* the probe's f at the given y0 no longer serves the first call */
      c->f0_kept = 0;
    }
  a->y0 = y;
}

const sym_constraints *
symmex_constraints (symmex_ctx *c, symmex_args *a, const sym_system *sys)
{
  const mxArray *f = c->o->constraints;
  con_ctx *k = mxCalloc (1, sizeof (con_ctx));
  k->solver = c->solver;
  k->d = c->d;
  k->args[0] = (mxArray *) f;
  k->args[1] = mxCreateDoubleMatrix (c->d, 1, mxREAL);
  symmex_direct_name (f, k->name, sizeof k->name);
  const double nin = symmex_declared (f, "nargin");
  if (nin == 0)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: the Constraints function takes "
                       "no argument, but is called as CON (q), q the %d "
                       "positions", c->solver, c->d);
  const double nout = symmex_declared (f, "nargout");
  if (nout == 0)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: the Constraints function must "
                       "return g(q) (and optionally G = dg/dq), got no "
                       "output", c->solver);
  /* two outputs when it may give them: an anonymous function (nargout
     -1) that gives one is called again with one */
  mxArray *out[2] = { NULL, NULL };
  memcpy (mxGetPr (k->args[1]), a->y0, sizeof (double) * c->d);
  int has_G = 0;
  if (nout != 1)
    {
      void *mark = symmex_core_mark ();
      mxArray *ex = mexCallMATLABWithTrap (2, out, 2, k->args, "feval");
      symmex_core_back (mark);
      if (ex)
        {
          mxDestroyArray (ex);
          out[0] = out[1] = NULL;
        }
      else
        has_G = out[1] != NULL;
    }
  if (! out[0])
    con_call (k, a->y0, 1, out);
  const double *g = con_g (k, &out[0], 0);
  k->m = (int) mxGetNumberOfElements (out[0]);
  if (k->m >= c->d)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: the Constraints function must "
                       "return g(q), a vector of m real values, 1 <= m < %d "
                       "(the positions), got %d values", c->solver, c->d,
                       k->m);
  for (int i = 0; i < k->m; i++)
    if (! isfinite (g[i]))
      mexErrMsgIdAndTxt ("symplectic:nonfinite", "%s: the Constraints "
                         "function returned %s (element %d) at q0, the "
                         "initial positions", c->solver,
                         SYMMEX_NUM (g[i], "%g"), i + 1);
  if (has_G)
    con_G (k, &out[1]);
  for (int i = 0; i < 2; i++)
    if (out[i])
      mxDestroyArray (out[i]);
  k->cs.m = k->m;
  k->cs.con = con_cb;
  k->cs.has_G = has_G;
  k->cs.user = k;
  project_y0 (c, a, sys, &k->cs);
  return &k->cs;
}
