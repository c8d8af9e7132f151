/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* problem.c -- the problem a run solves: the user's functions with the
   argument arrays their calls reuse, FCN probed at the initial point, the
   source of Newton's matrices, the number of events, and the core's
   system of callbacks. */
#include "symmex.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static mxArray *
col (int n)
{
  return mxCreateDoubleMatrix (n, 1, mxREAL);
}

/* A user's function takes (t, y) (OutputFcn: (t, y, flag)) and the
   parameters given after Y0 (or OPTS): one that declares fewer arguments
   (nargin, where Octave knows it) is told at once, naming the option,
   not by its own error at the first call */
/* What f declares, by Octave's nargin or nargout (QUERY); -1 where it
   declares nothing (varargin/varargout, anonymous outputs) or Octave
   cannot tell (built-in functions) */
double
symmex_declared (const mxArray *f, const char *query)
{
  mxArray *in[1] = { (mxArray *) f }, *out[1] = { NULL };
  mxArray *ex = mexCallMATLABWithTrap (1, out, 1, in, query);
  if (ex)
    {
      mxDestroyArray (ex);
      return -1;
    }
  const double k = mxIsNumeric (out[0]) ? mxGetScalar (out[0]) : -1;
  mxDestroyArray (out[0]);
  return k;
}

static void
check_nargin (const symmex_ctx *c, const mxArray *f, const char *what,
              const char *form)
{
  if (! f)
    return;
  const double k = symmex_declared (f, "nargin");
  int fixed = 1;
  for (const char *p = form; *p; p++)
    fixed += *p == ',';
  if (k < 0 || k >= fixed + c->nextra)
    return;
  char ps[64] = "";
  if (c->nextra == 1)
    snprintf (ps, sizeof ps, ", p1");
  else if (c->nextra > 1)
    snprintf (ps, sizeof ps, ", p1, %sp%d", c->nextra > 2 ? "..., " : "",
              c->nextra);
  char follow[64];
  snprintf (follow, sizeof follow, "; it must accept (%s)", form);
  if (c->nextra == 1)
    snprintf (follow, sizeof follow, ": a parameter follows Y0 or OPTS");
  else if (c->nextra > 1)
    snprintf (follow, sizeof follow, ": %d parameters follow Y0 or OPTS",
              c->nextra);
  mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: %s takes %g argument%s, but is "
                     "called as %s (%s%s)%s", c->solver, what, k,
                     k == 1 ? "" : "s", what, form, ps, follow);
}

/* Events must return [value, isterminal, direction], OutputFcn stop: one
   that declares fewer outputs (nargout, where Octave knows it; -1 for
   anonymous functions and varargout) is told at once, naming the option,
   not by Octave's "called with too many outputs" at the first call */
static void
check_nargout (const symmex_ctx *c, const mxArray *f, const char *what,
               int need, const char *outs)
{
  if (! f)
    return;
  const double k = symmex_declared (f, "nargout");
  if (k < 0 || k >= need)
    return;
  mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: the %s function must return %s, "
                     "got %g", c->solver, what, outs, k);
}

/* The call goes through cellfun's ErrorHandler, which keeps the error's
   message (a trapped call of a MEX function does not).  SecondOrder: an
   FCN (t, q) written for y = [q; p] indexes past q; a function that
   returns nothing is called with too many outputs. */
void
symmex_call_first (symmex_ctx *c, mxArray **out, int nargs, mxArray **args,
                   const char *what, const char *expect, int index_hint)
{
  mxArray *in[16], *cells[16];
  const int nin = nargs + 5;
  if (nin > 16)
    {
      symmex_call (1, out, nargs, args, "");
      return;
    }
  mxArray *h = NULL, *hs = mxCreateString ("@(e, varargin) struct "
                                           "(\"symplectic_error__\", e)");
  mexCallMATLAB (1, &h, 1, &hs, "str2func");
  mxDestroyArray (hs);
  in[0] = (mxArray *) args[0];
  for (int i = 1; i < nargs; i++)
    {
      cells[i] = mxCreateCellMatrix (1, 1);
      mxSetCell (cells[i], 0, mxDuplicateArray (args[i]));
      in[i] = cells[i];
    }
  in[nargs] = mxCreateString ("ErrorHandler");
  in[nargs + 1] = h;
  in[nargs + 2] = mxCreateString ("UniformOutput");
  in[nargs + 3] = mxCreateLogicalScalar (0);
  mxArray *res = NULL;
  void *mark = symmex_core_mark ();
  mexCallMATLAB (1, &res, nin - 1, in, "cellfun");
  symmex_core_back (mark);
  for (int i = 1; i < nargs; i++)
    mxDestroyArray (cells[i]);
  for (int i = nargs; i < nin - 1; i++)
    mxDestroyArray (in[i]);
  mxArray *v = mxGetCell (res, 0);
  const mxArray *e = v && mxIsStruct (v)
                     ? mxGetField (v, 0, "symplectic_error__") : NULL;
  if (! e)
    {
      out[0] = v ? mxDuplicateArray (v) : NULL;
      symmex_settle (out[0]);
      mxDestroyArray (res);
      return;
    }
  const mxArray *mm = mxGetField (e, 0, "message");
  const mxArray *mi = mxGetField (e, 0, "identifier");
  char *msg = mm && mxIsChar (mm) ? mxArrayToString (mm) : NULL;
  char *id = mi && mxIsChar (mi) ? mxArrayToString (mi) : NULL;
  const double t = mxGetNumberOfElements (args[1]) >= 1
                   && mxIsDouble (args[1]) ? mxGetPr (args[1])[0] : NAN;
  if (index_hint && id && strcmp (id, "Octave:index-out-of-bounds") == 0)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: with SecondOrder on, FCN is "
                       "called as FCN (t, q), q the first half of Y0 (%d "
                       "of its %d elements), and must return the "
                       "acceleration a(t, q) of as many; calling it at "
                       "t = %.15g gave: %s", c->solver, c->d, c->n, t,
                       msg ? msg : "");
  if (id && strcmp (id, "Octave:invalid-fun-call") == 0 && msg
      && strstr (msg, "called with too many outputs"))
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: %s must return %s, but returns "
                       "nothing; calling it at t = %.15g gave: %s",
                       c->solver, what, expect, t, msg);
  /* the user's own error, as it came */
  mxArray *st = mxCreateStructMatrix (1, 1, 0, NULL);
  mxSetFieldByNumber (st, 0, mxAddField (st, "message"),
                      mxCreateString (msg ? msg : ""));
  mxSetFieldByNumber (st, 0, mxAddField (st, "identifier"),
                      mxCreateString (id ? id : ""));
  mexCallMATLAB (0, NULL, 1, &st, "rethrow");
}

void
symmex_call_cb (symmex_ctx *c, int cb, mxArray **out, int nargs,
                mxArray **args, const char *name, const char *what,
                const char *expect)
{
  if (c->called & (1u << cb))
    symmex_call (1, out, nargs, args, name);
  else
    {
      c->called |= 1u << cb;
      symmex_call_first (c, out, nargs, args, what, expect, 0);
    }
}

/* Vectorized: FCN (t, Y) must give, in column j, FCN (t, Y(:,j)).
   Checked once, on y0 and a state near it, against single calls (an FCN
   that indexes y linearly gives a matrix of the right size but mixes the
   columns); skipped where f is not finite there (the edge of its
   domain) */
static void
check_vectorized (symmex_ctx *c, const symmex_args *a, const double *f0)
{
  const int n = c->n;
  double *y1 = mxMalloc (sizeof (double) * 6 * n), *f1 = y1 + n;
  double *Y = y1 + 2 * n, *F = y1 + 4 * n;
  double tt[2] = { a->tspan[0], a->tspan[0] };
  for (int i = 0; i < n; i++)
    {
      y1[i] = a->y0[i] + 1e-3 * (fabs (a->y0[i]) + 1.0) * (i % 2 ? -1 : 1);
      Y[i] = a->y0[i];
      Y[n + i] = y1[i];
    }
  symmex_cb_rhs (a->tspan[0], y1, f1, c);
  symmex_cb_rhs_batch (2, tt, Y, F, c);
  c->probe_calls += 2;
  c->probe_states += 3;
  double big = 0.0, dif = 0.0;
  int col = 1;
  for (int i = 0; i < n; i++)
    {
      if (! isfinite (f1[i]) || ! isfinite (F[n + i]))
        {
          mxFree (y1);
          return;
        }
      big = fmax (big, fmax (fabs (f0[i]), fabs (f1[i])));
      if (fabs (F[i] - f0[i]) > dif)
        {
          dif = fabs (F[i] - f0[i]);
          col = 1;
        }
      if (fabs (F[n + i] - f1[i]) > dif)
        {
          dif = fabs (F[n + i] - f1[i]);
          col = 2;
        }
    }
  mxFree (y1);
  if (dif > 1e-10 * big)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: Vectorized is on, but FCN does "
                       "not evaluate the columns of Y one by one: column %d "
                       "of FCN (t, Y) differs from FCN (t, Y(:,%d)) by %.3g "
                       "at t = %.15g; make FCN take a %d-by-k Y, or set "
                       "Vectorized off", c->solver, col, col, dif,
                       a->tspan[0], c->nf);
}

/* FCN at (t0, y0): its size and values (kept in c->f0 when keep_f0), and
   (probe_hess) whether it gives the Hessian as a second output; returns
   that */
static int
probe_fcn (symmex_ctx *c, const symmex_args *a, int probe_hess, int keep_f0)
{
  const int n = c->n;
  mxArray *out[2] = { NULL, NULL };
  int have2 = 0;
  if (probe_hess)
    {
      void *mark = symmex_core_mark ();
      mxArray *ex = mexCallMATLABWithTrap (2, out, c->nargs, c->args,
                                           "feval");
      symmex_core_back (mark);
      if (ex)
        {
          mxDestroyArray (ex);
          out[0] = out[1] = NULL;
        }
      else
        {
          symmex_settle (out[0]);
          symmex_settle (out[1]);
          have2 = out[1] && ! mxIsEmpty (out[1]);
        }
    }
  if (! out[0])
    symmex_call_first (c, out, c->nargs, c->args, "FCN", c->second_order
                       ? "the acceleration a(t, q)" : "dy/dt = f(t, y)",
                       c->second_order);
  c->probe_calls = c->probe_states = 1;
  const double *v = symmex_checked (c, &out[0], c->nf, "FCN", 0,
                                    a->tspan[0], c->second_order
                                    ? "the acceleration, a vector of %d real "
                                      "elements (SecondOrder)"
                                    : "a vector of %d real elements", c->nf);
  /* f at y0 (SecondOrder: [v0; a]) */
  double *f0 = mxMalloc (sizeof (double) * n);
  memcpy (f0, c->second_order ? a->y0 + c->d : v, sizeof (double) * c->nf);
  if (c->second_order)
    memcpy (f0 + c->d, v, sizeof (double) * c->d);
  for (int i = 0; i < c->nf; i++)
    if (! isfinite (v[i]))
      mexErrMsgIdAndTxt ("symplectic:nonfinite", "%s: FCN returned %s "
                         "(element %d) at t = %.15g, the initial point",
                         c->solver, SYMMEX_NUM (v[i], "%g"), i + 1,
                         a->tspan[0]);
  if (c->o->vectorized)
    check_vectorized (c, a, f0);
  if (keep_f0)
    c->f0 = f0;    /* (probe_separable's) */
  else
    mxFree (f0);
  /* a sparse Hessian of the right size and type is not made full here
     (at large d it could not be) */
  c->fcn2_sparse = have2 && mxIsSparse (out[1]) && mxIsDouble (out[1])
                   && ! mxIsComplex (out[1]) && symmex_is_size (out[1], n, n);
  if (have2 && ! c->fcn2_sparse)
    symmex_checked (c, &out[1], symmex_hessian_shape (out[1], n)
                    ? (size_t) n * n : (size_t) -1, "FCN (second output)",
                    0, a->tspan[0], SYMMEX_HESS_EXPECT, n, n, n * n);
  return have2;
}

/* Separable: f_p = -dH/dq (with the forcing) must not change with p.
   odeSE's steps see it (two calls at the same t and q); odeSV's calls
   are at the same p, so FCN is called once more here, at (t0, q0) with
   another p.  That call stands in for the run's first call at (t0, y0),
   served from the probe's value (symmex_cb_rhs), so that the calls are
   as many as without it.  Skipped where f is not finite there. */
static void
probe_separable (symmex_ctx *c, const symmex_args *a)
{
  const int n = c->n, d = c->d;
  double *y1 = mxMalloc (sizeof (double) * 2 * n), *f1 = y1 + n;
  memcpy (y1, a->y0, sizeof (double) * n);
  for (int i = d; i < n; i++)
    y1[i] += 1e-3 * (fabs (a->y0[i]) + 1.0) * (i % 2 ? -1 : 1);
  symmex_cb_rhs (a->tspan[0], y1, f1, c);
  c->probe_calls++;
  c->probe_states++;
  double big = 0.0, dif = 0.0;
  for (int i = d; i < n; i++)
    {
      if (! isfinite (f1[i]))
        break;
      big = fmax (big, fmax (fabs (c->f0[i]), fabs (f1[i])));
      dif = fmax (dif, fabs (f1[i] - c->f0[i]));
    }
  c->sep_probe_broken = dif > SYM_SEP_TOL * big;
  c->f0_kept = 1;
  c->t0 = a->tspan[0];
  c->y0 = a->y0;
  mxFree (y1);
}

/* The source of Newton's matrices, in the order of precedence: the
   Jacobian (matrix or function), HamiltonianHessFcn, FCN's second output,
   finite differences */
static void
jacobian_source (symmex_ctx *c, const symmex_opts *o, int have2)
{
  if (o->jacobian && ! symmex_is_function (o->jacobian))
    {
      c->jac_source = JAC_MATRIX;
      /* (made full only if the dense path takes it: symmex_cb_jac) */
      c->jac_const = NULL;
    }
  else if (o->jacobian)
    c->jac_source = JAC_FCN;
  else if (o->hessfcn)
    c->jac_source = JAC_HESSFCN;
  else if (have2)
    c->jac_source = JAC_FCN2;
  else
    c->jac_source = JAC_FD;
  if (c->jac_source == JAC_MATRIX || c->jac_source == JAC_FD)
    return;
  c->jargs = mxCalloc (c->nargs, sizeof (mxArray *));
  memcpy (c->jargs, c->args, sizeof (mxArray *) * c->nargs);
  c->jargs[0] = (mxArray *) (c->jac_source == JAC_FCN ? o->jacobian
                             : c->jac_source == JAC_HESSFCN ? o->hessfcn
                             : c->args[0]);
  c->jargs[1] = mxCreateDoubleScalar (0);
  c->jargs[2] = col (c->n);
  symmex_direct_name (c->jargs[0], c->jname, sizeof c->jname);
}

/* Events: one call at t0 tells how many there are */
static void
count_events (symmex_ctx *c, const symmex_args *a, const mxArray *events)
{
  char buf[64];
  c->eargs = mxCalloc (c->nargs, sizeof (mxArray *));
  memcpy (c->eargs, c->args, sizeof (mxArray *) * c->nargs);
  c->eargs[0] = (mxArray *) events;
  c->eargs[1] = mxCreateDoubleScalar (a->tspan[0]);
  c->eargs[2] = col (c->n);
  memcpy (mxGetPr (c->eargs[2]), a->y0, sizeof (double) * c->n);
  mxArray *eo[3] = { NULL, NULL, NULL };
  symmex_direct_name (events, c->ename, sizeof c->ename);
  symmex_call (3, eo, c->nargs, c->eargs, c->ename);
  if (! eo[1] || ! eo[2])
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: the Events function must return "
                       "three outputs [VALUE, ISTERMINAL, DIRECTION], got %d",
                       c->solver, eo[0] ? (eo[1] ? 2 : 1) : 0);
  /* an empty VALUE: no events (as in ode45) */
  if (! eo[0] || ! (mxIsNumeric (eo[0]) || mxIsLogical (eo[0]))
      || mxIsComplex (eo[0]))
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: the Events function must return "
                       "[VALUE, ISTERMINAL, DIRECTION] with a real VALUE, "
                       "got VALUE = %s", c->solver,
                       eo[0] ? symmex_describe (eo[0], buf, sizeof buf)
                       : "nothing");
  c->nevents = (int) mxGetNumberOfElements (eo[0]);
  for (int k = 0; k < 3; k++)
    mxDestroyArray (eo[k]);
}

symmex_ctx *
symmex_problem (const char *solver, const symmex_args *a, symmex_opts *o,
                int need_jac, int second_order, int separable, int nlhs,
                sym_system *sys)
{
  const int n = a->n;
  symmex_ctx *c = mxCalloc (1, sizeof (symmex_ctx));
  c->solver = solver;
  c->n = n;
  c->members = a->members;
  c->d = n / 2;
  c->second_order = second_order;
  c->nf = second_order ? c->d : n;
  c->o = o;
  c->nextra = a->nextra;
  c->extra = a->extra;
  c->nargs = 3 + c->nextra;
  c->args = mxCalloc (c->nargs, sizeof (mxArray *));
  c->args[0] = (mxArray *) a->fcn;
  c->args[1] = mxCreateDoubleScalar (a->tspan[0]);
  c->args[2] = col (c->nf);
  for (int i = 0; i < c->nextra; i++)
    c->args[3 + i] = (mxArray *) c->extra[i];
  memcpy (mxGetPr (c->args[2]), a->y0, sizeof (double) * c->nf);
  int compiled = symmex_compiled_arg (a->fcn);
  if (! compiled)
    {
      symmex_direct_name (a->fcn, c->fname, sizeof c->fname);
      check_nargin (c, a->fcn, "FCN", second_order ? "t, q" : "t, y");
    }
  check_nargin (c, o->jacobian && symmex_is_function (o->jacobian)
                ? o->jacobian : NULL, "Jacobian", "t, y");
  check_nargin (c, o->hessfcn, "HamiltonianHessFcn", "t, y");
  check_nargin (c, o->events, "Events", "t, y");
  check_nargin (c, o->outputfcn, "OutputFcn", "t, y, flag");
  check_nargout (c, o->events, "Events", 3,
                 "three outputs [VALUE, ISTERMINAL, DIRECTION]");
  check_nargout (c, o->outputfcn, "OutputFcn", 1,
                 "one output, STOP (true to end the run)");
  check_nargin (c, o->reversible ? o->densityfcn : NULL, "StepDensityFcn",
                "t, y");
  check_nargin (c, o->hamiltonian, "Hamiltonian", "t, y");

  c->jac_source = JAC_NONE;
  if (compiled)
    symmex_compiled_problem (c, a, o, need_jac);
  else
    {
      /* the Hessian as FCN's second output only matters to Newton */
      separable = separable && c->members == 1;
      int have2 = probe_fcn (c, a, need_jac && ! o->jacobian
                             && ! o->hessfcn, separable);
      if (separable)
        probe_separable (c, a);
      if (need_jac)
        jacobian_source (c, o, have2);
    }
  if (o->events)
    count_events (c, a, o->events);
  if (o->densityfcn && o->reversible)
    {
      c->dargs = mxCalloc (c->nargs, sizeof (mxArray *));
      memcpy (c->dargs, c->args, sizeof (mxArray *) * c->nargs);
      c->dargs[0] = (mxArray *) o->densityfcn;
      c->dargs[1] = mxCreateDoubleScalar (a->tspan[0]);
      c->dargs[2] = col (c->n);
      symmex_direct_name (o->densityfcn, c->dname, sizeof c->dname);
    }

  /* nargout = 0 and no OutputFcn plots with odeplot, as ode45 */
  if (nlhs == 0 && ! o->outputfcn)
    o->outputfcn = mxCreateString ("odeplot");
  if (o->outputfcn)
    {
      c->oargs = mxCalloc (c->nargs + 1, sizeof (mxArray *));
      c->oargs[0] = (mxArray *) o->outputfcn;
      symmex_direct_name (o->outputfcn, c->oname, sizeof c->oname);
      for (int i = 0; i < c->nextra; i++)
        c->oargs[4 + i] = (mxArray *) c->extra[i];
      symmex_outputfcn (c, a->tspan, a->ntspan, a->y0, "init");
    }

  memset (sys, 0, sizeof (*sys));
  sys->dim = c->d;
  sys->rhs = symmex_cb_rhs;
  sys->rhs_batch = o->vectorized ? symmex_cb_rhs_batch : NULL;
  sys->jac = c->jac_source == JAC_FD || c->jac_source == JAC_NONE ? NULL
             : symmex_cb_jac;
  sys->rhs_jac = c->jac_source == JAC_FCN2 ? symmex_cb_rhs_jac : NULL;
  sys->user = c;
  sys->jp_colptr = o->jp_colptr;
  sys->jp_rowind = o->jp_rowind;
  sys->jp_color = o->jp_color;
  sys->jp_ncolors = o->jp_ncolors;
  if (c->compiled)
    symmex_compiled_system (c, sys);
  return c;
}

int
symmex_sparse_source (symmex_ctx *c, const symmex_args *a)
{
  const symmex_opts *o = c->o;
  switch (c->jac_source)
    {
    case JAC_MATRIX:
      return mxIsSparse (o->jacobian);
    case JAC_FCN2:
      return c->fcn2_sparse;
    case JAC_FD:
      return o->jp_sparse && o->jp_ncolors > 0;
    case JAC_FCN:
    case JAC_HESSFCN:
      {
        mxArray *v = symmex_jac_value (c, a->tspan[0], a->y0);
        c->probe_jac = 1;
        int sp = v && mxIsSparse (v);
        mxDestroyArray (v);
        return sp;
      }
    case JAC_COMPILED:
      return symmex_compiled_sparse_source (c);
    default:
      return 0;
    }
}

void
symmex_use_sparse (symmex_ctx *c, sym_system *sys)
{
  c->sparse = 1;
  sys->sparse = 1;
  sys->jac = NULL;
  sys->rhs_jac = NULL;
  sys->jac_csc = c->jac_source == JAC_FD ? NULL : symmex_cb_jac_csc;
  sys->rhs_jac_csc = c->jac_source == JAC_FCN2 ? symmex_cb_rhs_jac_csc
                     : NULL;
  symmex_compiled_use_sparse (c, sys);
}
