/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* sv.c -- odeSV: Stoermer-Verlet (core: methods/sv.c) and the
   compositions and splittings of the table sym_splittings (core:
   methods/splitting.c), chosen by Method.  Own options: those of odeSE,
   Method, CompensatedSummation, VerletForm; sol gains the method and its
   order. */
#include "onestep.h"

#include <stdio.h>
#include <string.h>

static const char *const sv_options[] = {
  "Separable", "SecondOrder", "Method", "CompensatedSummation",
  "VerletForm", NULL
};

static void
sv_parse (const char *solver, const mxArray *opts, void *own)
{
  sym_onestep_opts *o = own;
  symmex_onestep_parse (solver, opts, own);
  const mxArray *v = symmex_field (solver, opts, "Method");
  o->method = 0;
  if (v)
    {
      char name[32] = "";
      if (! mxIsChar (v) || mxGetNumberOfElements (v) >= sizeof name
          || mxGetString (v, name, sizeof name)
          || (o->method = sym_splitting_find (name)) < 0)
        {
          char list[512] = "";
          for (int k = 0; sym_splittings[k].name; k++)
            snprintf (list + strlen (list), sizeof list - strlen (list),
                      "%s\"%s\"", k ? ", " : "", sym_splittings[k].name);
          char got[64];
          mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: Method must be one of %s; "
                             "got %s", solver, list,
                             symmex_describe_word (v, got, sizeof got));
        }
    }
  /* on by default where it costs no call and no measurable time: the
     explicit steps of a method other than Verlet, and Verlet's reversible
     ones (a run retraced from its sol comes back to round-off).  Verlet's
     fixed steps stay on its own stepper, whose runs continue to the bit */
  static const char *const controls[] = { "standard", "reversible", NULL };
  const mxArray *sc = symmex_field (solver, opts, "StepControl");
  const int reversible = sc && symmex_word (solver, sc, "StepControl",
                                            controls) == 1;
  const mxArray *c = symmex_field (solver, opts, "CompensatedSummation");
  o->compensated = c ? symmex_on_off (solver, c, "CompensatedSummation")
                   : (o->method != 0 || reversible) && o->separable;
  static const char *const forms[] = { "velocity", "position", NULL };
  const mxArray *f = symmex_field (solver, opts, "VerletForm");
  o->position = f ? symmex_word (solver, f, "VerletForm", forms) == 1 : 0;
  const sym_splitting *m = &sym_splittings[o->method];
  if (o->position && m->kind == SYM_SPLITTING)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: VerletForm \"position\" is for "
                       "Verlet and its compositions; Method \"%s\" is a "
                       "splitting with its own kicks and drifts (leave "
                       "VerletForm out)", solver, m->name);
  if (o->position && ! o->separable)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: VerletForm \"position\" takes "
                       "explicit steps: set Separable (or SecondOrder) on, "
                       "or leave VerletForm \"velocity\" for a general H",
                       solver);
}

/* Stoermer-Verlet's own stepper, with its adaptive steps, unless another
   method or compensated sums are asked for: those take the splitting
   stepper's fixed or reversible steps */
/* Constraints: RATTLE, and what it does not do yet refused */
static const sym_stepper_type *
sv_rattle (const char *solver, const sym_onestep_opts *s,
           const symmex_opts *o)
{
  const char *no = ! s->separable ? "a general H (implicit stages): set "
                   "Separable (or SecondOrder) on"
                   : s->method ? "Method (the compositions of RATTLE)"
                   : o->reversible ? "StepControl \"reversible\""
                   : ! symmex_fixed (o) ? "adaptive steps: give "
                   "TimeStepSize or TimeStepNumber"
                   : o->ensemble ? "Ensemble"
                   : s->position ? "VerletForm \"position\""
                   : s->compensated ? "CompensatedSummation" : NULL;
  if (no)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: Constraints takes fixed explicit "
                       "RATTLE steps; not yet with %s", solver, no);
  return sym_step_rattle;
}

static const sym_stepper_type *
sv_stepper (const char *solver, const void *own, const symmex_opts *o)
{
  const sym_onestep_opts *s = own;
  const sym_splitting *m = &sym_splittings[s->method];
  if (o->constraints)
    return sv_rattle (solver, s, o);
  if (s->method == 0 && ! s->compensated)
    return sym_step_sv;
  if (! symmex_fixed (o) && ! o->reversible)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: %s takes fixed steps or "
                       "StepControl \"reversible\": give TimeStepSize or "
                       "TimeStepNumber, or set StepControl", solver,
                       s->method ? "Method" : "CompensatedSummation");
  if (m->kind == SYM_SPLITTING && ! s->separable)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: Method \"%s\" is a splitting of "
                       "H = T(p) + V(q): set Separable (or SecondOrder) on, "
                       "or choose a composition of Verlet steps", solver,
                       m->name);
  if (s->compensated && ! s->separable)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: CompensatedSummation sums the "
                       "updates of explicit steps: set Separable (or "
                       "SecondOrder) on", solver);
  return sym_step_splitting;
}

static void
sv_sol_fields (mxArray *sol, const void *own, const sym_stats *st)
{
  const sym_onestep_opts *s = own;
  (void) st;
  mxAddField (sol, "method");
  mxAddField (sol, "order");
  mxSetField (sol, 0, "method",
              mxCreateString (sym_splittings[s->method].name));
  mxSetField (sol, 0, "order",
              mxCreateDoubleScalar (sym_splittings[s->method].order));
}

static const char *
sv_asymmetric (const void *own)
{
  static char why[96];
  const sym_onestep_opts *s = own;
  if (sym_splittings[s->method].symmetric)
    return NULL;
  snprintf (why, sizeof why, "Method \"%s\" is not",
            sym_splittings[s->method].name);
  return why;
}

const symmex_method symmex_method_sv = {
  "odeSV", &sym_step_sv, sizeof (sym_onestep_opts), sv_parse,
  sv_options, symmex_onestep_needs_newton, sv_sol_fields, NULL,
  "dH/dp changed with q (or t) at the same p", sv_stepper,
  symmex_onestep_second_order, sv_asymmetric, symmex_onestep_take_sparse,
  symmex_onestep_take_tangent
};
