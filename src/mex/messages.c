/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* messages.c -- what the user reads: values described for error messages,
   the warning of a run that could not go on, Stats, and the wrappers that
   give every message the solver's name once. */
#include "symmex.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

const char *
symmex_describe (const mxArray *v, char *buf, size_t len)
{
  /* the dimensions as size () gives them, then the class */
  const mwSize *dims = mxGetDimensions (v);
  mwSize nd = mxGetNumberOfDimensions (v);
  size_t k = 0;
  buf[0] = '\0';
  for (mwSize i = 0; i < nd && k < len; i++)
    {
      int w = snprintf (buf + k, len - k, "%s%lu", i ? "x" : "",
                        (unsigned long) dims[i]);
      if (w < 0)
        break;
      k += (size_t) w;
    }
  if (k < len)
    snprintf (buf + k, len - k, " %s%s%s", mxIsSparse (v) ? "sparse " : "",
              mxIsComplex (v) ? "complex " : "", mxGetClassName (v));
  return buf;
}

const char *
symmex_num (char *buf, size_t len, const char *fmt, double x)
{
  if (isnan (x))
    snprintf (buf, len, "NaN");
  else if (isinf (x))
    snprintf (buf, len, x > 0 ? "Inf" : "-Inf");
  else
    snprintf (buf, len, fmt, x);
  return buf;
}

/* A one-row text of 1 to 39 characters in quotes, then after; anything
   else as symmex_describe gives it */
static const char *
describe_text (const mxArray *v, char *buf, size_t len, const char *after)
{
  char text[40];
  if (mxIsChar (v) && mxGetNumberOfDimensions (v) == 2 && mxGetM (v) == 1
      && mxGetN (v) > 0 && mxGetN (v) < sizeof text
      && ! mxGetString (v, text, sizeof text))
    {
      snprintf (buf, len, "\"%s\"%s", text, after);
      return buf;
    }
  return symmex_describe (v, buf, len);
}

const char *
symmex_describe_word (const mxArray *v, char *buf, size_t len)
{
  return describe_text (v, buf, len, "");
}

const char *
symmex_describe_fn (const mxArray *v, char *buf, size_t len)
{
  return describe_text (v, buf, len, ", which names no function");
}

/* Newton failed: with the fixed step (advise a smaller one unless the
   method knows better), or even with the smallest step */
static void
warn_newton (const symmex_method *m, const void *own, const symmex_opts *o,
             const symmex_ctx *c, double treached, double tlast)
{
  /* a NaN/Inf matrix also ends as a Newton failure: say so */
  char why[160] = "";
  if (c->nonfinite_what && strcmp (c->nonfinite_what, "FCN") != 0)
    snprintf (why, sizeof why, " (%s returned NaN or Inf at t = %.15g)",
              c->nonfinite_what, c->nonfinite_t);
  const char *hint = ! why[0] && m->newton_hint ? m->newton_hint (own) : NULL;
  if (hint)
    snprintf (why, sizeof why, " (%s)", hint);
  mexWarnMsgIdAndTxt ("symplectic:newton-failed", "%s: Newton's method did "
                      "not converge at t = %.15g %s%s; returning the "
                      "solution up to t = %.15g", m->name, treached,
                      symmex_fixed (o)
                      ? (hint ? "with the fixed step"
                         : "with the fixed step (try a smaller TimeStepSize)")
                      : o->reversible
                      ? (hint ? "with the reversible step"
                         : "with the reversible step (try a smaller RelTol)")
                      : "even with the smallest step", why, tlast);
}

void
symmex_report (const symmex_method *m, const void *own,
               const symmex_opts *o, const symmex_args *a, symmex_ctx *c,
               const sym_stats *st, int status)
{
  const char *name = m->name;
  const double treached = st->t_reached;
  double tlast = c->nrows ? c->tbuf[c->nrows - 1] : a->tspan[0];
  switch (status)
    {
    case SYM_DONE:
    case SYM_STOP_EVENT:
      break;
    case SYM_STOP_OUTPUT:
      /* the events of a step are found before its rows go out: those
         after the row where OutputFcn stopped are dropped, so that, as in
         ode45, no returned event lies beyond t(end) */
      while (c->nev > 0 && a->dir * (c->te[c->nev - 1] - tlast) > 0)
        c->nev--;
      /* a stop on the last row ends nothing early: no warning */
      if (tlast != a->tspan[a->ntspan - 1])
        mexWarnMsgIdAndTxt ("symplectic:output-stop", "%s: OutputFcn asked "
                            "to stop at t = %.15g; returning the solution up "
                            "to there", name, tlast);
      break;
    case SYM_ENEWTON:
      warn_newton (m, own, o, c, treached, tlast);
      break;
    case SYM_ENONFINITE:
      mexWarnMsgIdAndTxt ("symplectic:nonfinite", "%s: %s returned NaN or "
                          "Inf near t = %.15g %s; returning the solution up "
                          "to t = %.15g", name, c->nonfinite_what
                          ? c->nonfinite_what : "FCN", st->fail_t,
                          symmex_fixed (o) ? "with the fixed step (try a "
                          "smaller TimeStepSize)" : o->reversible ? "with the "
                          "reversible step (try a smaller RelTol)" : "and a "
                          "smaller step did not help", tlast);
      break;
    case SYM_EOVERFLOW:
      mexWarnMsgIdAndTxt ("symplectic:nonfinite", "%s: the solution "
                          "overflowed (NaN or Inf) in the step from "
                          "t = %.15g%s; returning the solution up to "
                          "t = %.15g", name, treached, symmex_fixed (o)
                          ? " (an unstable fixed step? try a smaller "
                            "TimeStepSize)" : o->reversible ? " (try a "
                            "smaller RelTol)" : " even with the smallest step",
                          tlast);
      break;
    case SYM_ESTEPSIZE:
      mexWarnMsgIdAndTxt ("symplectic:step-size", "%s: the step size became "
                          "too small at t = %.15g; returning the solution up "
                          "to t = %.15g", name, treached, tlast);
      break;
    case SYM_EDENSITY:
      mexWarnMsgIdAndTxt ("symplectic:step-density", "%s: StepDensityFcn "
                          "returned %s at t = %.15g, not a positive finite "
                          "density; returning the solution up to t = %.15g",
                          name, SYMMEX_NUM (c->density, "%g"), c->density_t,
                          tlast);
      break;
    case SYM_EMAXSTEPS:
      mexWarnMsgIdAndTxt ("symplectic:max-steps", "%s: MaxSteps reached at "
                          "t = %.15g; returning the solution up to "
                          "t = %.15g", name, treached, tlast);
      break;
    case SYM_ENOMEM:
      if (symmex_alloc_failed)
        mexErrMsgIdAndTxt ("Octave:out-of-memory", "%s: out of memory: the "
                           "integrator's workspace needs a block of %.3g GB "
                           "that cannot be allocated", name,
                           (double) symmex_alloc_failed / 1e9);
      mexErrMsgIdAndTxt ("Octave:out-of-memory", "%s: out of memory", name);
      break;
    case SYM_EOUTPUT:
      /* an output buffer could not grow: the outputs built from it would
         need as much again, so an error (with the buffers freed) rather
         than the rows so far */
      if (! c->oom)
        mexErrMsgIdAndTxt ("symplectic:internal", "%s: internal failure "
                           "(%s)", name, sym_status_name (status));
      mexErrMsgIdAndTxt ("Octave:out-of-memory", "%s: out of memory for the "
                         "output after t = %.15g (%lu rows); ask for less: "
                         "fewer output times in TSPAN, a smaller Refine, or "
                         "Dense off", name, tlast, (unsigned long) c->nrows);
      break;
    case SYM_ECALLBACK:
      mexWarnMsgIdAndTxt ("symplectic:callback", "%s: a callback failed at "
                          "t = %.15g; returning the solution up to there",
                          name, st->fail_t);
      break;
    default:
      mexErrMsgIdAndTxt ("symplectic:internal", "%s: internal failure (%s)",
                         name, sym_status_name (status));
    }
  /* Separable on, but f found not separable at (t0, y0) by the probe
     (symmex_problem), or by the steps themselves */
  if ((c->sep_probe_broken || st->sep_broken) && m->sep_broken)
    mexWarnMsgIdAndTxt ("symplectic:not-separable", "%s: Separable is on, "
                        "but FCN is not of a separable H = T(p) + V(q) "
                        "without p in the forcing: %s at t = %.15g; the "
                        "explicit steps are then not the method (of lower "
                        "order, not symplectic): set Separable off", name,
                        c->sep_probe_broken ? SYMMEX_SEP_PROBE
                        : m->sep_broken, c->sep_probe_broken
                        ? a->tspan[0] : st->sep_broken_t);
}

static const char *
jac_source_name (int s)
{
  switch (s)
    {
    case JAC_MATRIX: return "Jacobian (constant matrix)";
    case JAC_FCN: return "Jacobian (function)";
    case JAC_HESSFCN: return "HamiltonianHessFcn";
    case JAC_FCN2: return "second output of FCN (Hessian)";
    case JAC_FD: return "finite differences of FCN";
    case JAC_COMPILED: return "compiled Hessian of FCN";
    default: return "none (explicit steps)";
    }
}

void
symmex_jac_used (const symmex_ctx *c, const sym_stats *st, char *buf,
                 size_t len)
{
  if (st->jac_dropped)
    snprintf (buf, len, "%s, then finite differences of FCN from "
              "t = %.15g", jac_source_name (c->jac_source),
              st->jac_dropped_t);
  else
    snprintf (buf, len, "%s", jac_source_name (c->jac_source));
}

void
symmex_print_stats (const sym_stats *st, const char *jac_used,
                    const symmex_ctx *c)
{
  const sym_counters *k = &st->cnt;
  mexPrintf ("Number of successful steps: %ld\n", k->nsteps);
  mexPrintf ("Number of failed attempts:  %ld\n", k->nfailed);
  mexPrintf ("Number of function calls:   %ld\n", k->nrhs);
  mexPrintf ("Number of Newton iterations: %ld\n", k->nnewton);
  mexPrintf ("Number of Jacobian/Hessian evaluations: %ld (source: %s%s; "
             "%ld function calls for finite differences)\n", k->njac,
             jac_used, st->rhs_jac_used && ! st->jac_dropped
             ? ", calls that also give f" : "", k->nfd);
  mexPrintf ("Number of LU decompositions: %ld\n", k->nlu);
  mexPrintf ("Number of linear solves:     %ld\n", k->nsolve);
  if (c->hbuf)
    mexPrintf ("Largest relative change of H: %.3g\n", c->max_dh);
}

/* ------------------------------------------------------------ wrappers */

/* See symmex.h.  The message goes out through Octave's own error and
   warning, so that it reads as the solver wrote it, whatever the MEX
   function is called. */
static void
raise (const char *fn, const char *id, const char *fmt, va_list ap)
{
  char msg[2048];
  vsnprintf (msg, sizeof msg, fmt, ap);
  /* an error leaves this call: what the core holds goes first */
  if (fn[0] == 'e')
    symmex_release_core ();
  mxArray *args[3] = { mxCreateString (id), mxCreateString ("%s"),
                       mxCreateString (msg) };
  mexCallMATLAB (0, NULL, 3, args, fn);
  for (int i = 0; i < 3; i++)
    mxDestroyArray (args[i]);
}

void
symmex_err (const char *id, const char *fmt, ...)
{
  va_list ap;
  va_start (ap, fmt);
  raise ("error", id, fmt, ap);
  va_end (ap);
}

void
symmex_warn (const char *id, const char *fmt, ...)
{
  va_list ap;
  va_start (ap, fmt);
  raise ("warning", id, fmt, ap);
  va_end (ap);
}
