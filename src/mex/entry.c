/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* entry.c -- one call of a solver: its arguments and options, the
   problem, the run of the core, the outputs.  The method enters only
   through its descriptor. */
#include "symmex.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* The driver's options for the run: output times or every step (sol:
   step points only, as ode45 gives it), Refine, fixed or adaptive
   steps, events and the sinks */
static void
driver_opts (const symmex_args *a, const symmex_opts *o, symmex_ctx *c,
             int want_sol, sym_driver_opts *d)
{
  memset (d, 0, sizeof (*d));
  d->t0 = a->tspan[0];
  d->tf = a->tspan[a->ntspan - 1];
  d->tout = a->tspan;
  d->ntout = want_sol ? 2 : a->ntspan;
  /* Refine: ode45's 4 rows per adaptive step unless given, the user's
     grid (step points) on fixed steps */
  d->refine = (d->ntout > 2 || want_sol) ? 1
              : o->refine ? o->refine : symmex_fixed (o) ? 1 : 4;
  d->h_fixed = o->h_fixed;
  d->nsteps_fixed = o->nsteps_fixed;
  d->tol.rtol = o->rtol;
  d->tol.atol = o->atol;
  d->tol.atol_len = o->atol_len;
  d->tol.norm_control = o->norm_control;
  d->h0 = o->h0;
  d->hmax = o->hmax;
  d->max_steps = o->max_steps;
  d->step_control = o->reversible ? SYM_CONTROL_REVERSIBLE
                    : SYM_CONTROL_ERROR;
  d->k0 = a->k0;
  d->grid_t0 = a->grid_t0;
  d->rho0 = a->rho0;
  d->density = o->densityfcn ? symmex_cb_density : NULL;
  d->density_user = c;
  d->nevents = c->nevents;
  d->events = c->nevents > 0 ? symmex_cb_events : NULL;
  d->event_user = c;
  d->event_out = symmex_sink_event;
  d->output = symmex_sink_row;
  d->output_user = c;
  d->dense_out = want_sol && o->dense ? symmex_sink_dense : NULL;
  d->dense_user = c;
}

size_t symmex_alloc_failed;
int symmex_in_ensemble;

int
symmex_can_allocate (double nbytes)
{
  if (! (nbytes >= 0 && nbytes <= (double) (SIZE_MAX / 2)))
    return 0;
  if (nbytes == 0)
    return 1;
  /* the only malloc of the MEX files: freed at once, with no user code
     in between, so that nothing is held outside mxMalloc */
  void *p = malloc ((size_t) nbytes);
  if (! p)
    return 0;
  free (p);
  return 1;
}

void *
symmex_malloc_or_null (size_t nbytes)
{
  return symmex_can_allocate ((double) nbytes) ? mxMalloc (nbytes) : NULL;
}

/* The core's allocator: mxMalloc (Octave frees it however the call
   ends); a block of SYMMEX_PROBE_BYTES or more that cannot be had comes
   back as NULL (symmex_malloc_or_null): the core then stops with
   SYM_ENOMEM, said with the block's size and the solver's name
   (mxMalloc's own error names the gateway).  Each block is linked in a
   list, so that an error can free what the run holds before it leaves
   (symmex_release_core): Octave 7 frees a block left to it, but keeps
   its address in a list of its own for good (bench/NOTES.md). */
typedef struct core_block core_block;
struct core_block {
  core_block *prev, *next;
};
static core_block *core_blocks;

static void *
core_alloc (size_t nbytes)
{
  const size_t hdr = sizeof (core_block);
  if (nbytes > SIZE_MAX - hdr)
    return NULL;
  core_block *b = nbytes < SYMMEX_PROBE_BYTES && ! symmex_in_ensemble
                  ? mxMalloc (nbytes + hdr)
                  : symmex_malloc_or_null (nbytes + hdr);
  if (! b)
    {
      symmex_alloc_failed = nbytes;
      return NULL;
    }
  b->prev = NULL;
  b->next = core_blocks;
  if (core_blocks)
    core_blocks->prev = b;
  core_blocks = b;
  return b + 1;
}

static void
core_free (void *ptr)
{
  if (! ptr)
    return;
  core_block *b = (core_block *) ptr - 1;
  if (b->prev)
    b->prev->next = b->next;
  else
    core_blocks = b->next;
  if (b->next)
    b->next->prev = b->prev;
  mxFree (b);
}

void *
symmex_core_mark (void)
{
  return core_blocks;
}

void
symmex_core_back (void *mark)
{
  core_blocks = mark;
}

void
symmex_release_core (void)
{
  while (core_blocks)
    {
      core_block *b = core_blocks;
      core_blocks = b->next;
      mxFree (b);
    }
}

static void
run (const symmex_method *m, int nlhs, mxArray *plhs[], int nrhs,
     const mxArray *prhs[])
{
  const char *name = m->name;
  symmex_alloc_failed = 0;
  symmex_in_ensemble = 0;
  sym_set_allocator (core_alloc, core_free);

  symmex_args a;
  symmex_opts o;
  symmex_read_args (name, nlhs, nrhs, prhs, &a);
  symmex_parse_options (name, &a, &o);
  void *own = mxCalloc (1, m->own_size);
  m->parse (name, a.opts && ! mxIsEmpty (a.opts) ? a.opts : NULL, own);
  symmex_check_others (m, a.opts && ! mxIsEmpty (a.opts) ? a.opts : NULL);
  const char *why = o.reversible ? m->asymmetric (own) : NULL;
  if (why)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: StepControl \"reversible\" needs "
                       "a symmetric method; %s", name, why);

  const sym_stepper_type *type = m->stepper ? m->stepper (name, own, &o)
                                 : *m->type;
  symmex_ensemble_check (name, &a, &o, nlhs);
  sym_tangent *tg = symmex_tangent_setup (m, own, &a, &o, nlhs);
  sym_system sys;
  const int second = m->second_order && m->second_order (own);
  const int need_jac = m->needs_newton (own)
                       || (tg && symmex_tangent_needs_jac (&o, second));
  symmex_ctx *c = symmex_problem (name, &a, &o, need_jac,
                                  second, m->sep_broken
                                  && ! m->needs_newton (own) && ! second,
                                  nlhs, &sys);
  if (tg)
    symmex_tangent_attach (c, tg);
  if (m->needs_newton (own) && m->take_sparse && m->take_sparse (own, 0)
      && symmex_sparse_source (c, &a))
    {
      m->take_sparse (own, 1);
      symmex_use_sparse (c, &sys);
    }
  sym_method_opts mo;
  memset (&mo, 0, sizeof mo);
  if (o.constraints)
    mo.constraints = symmex_constraints (c, &a, &sys);
  mo.newton_tol = o.newton_tol;
  mo.max_newton = o.max_newton;
  mo.own = own;
  sym_driver_opts dopt;
  driver_opts (&a, &o, c, nlhs == 1, &dopt);
  if (dopt.ntout > 2)
    {
      double tend = sym_fixed_end (&dopt);
      if (a.dir * (dopt.tf - tend) > 0)
        mexWarnMsgIdAndTxt ("symplectic:tspan-beyond-end", "%s: "
                            "TimeStepNumber*TimeStepSize ends at t = %g; "
                            "no output for TSPAN beyond that", name, tend);
    }

  if (o.ensemble)
    {
      symmex_ensemble (m, own, type, &a, &o, c, &sys, &mo, &dopt, nlhs,
                       plhs);
      return;
    }
  sym_stats st;
  int status = sym_integrate (type, &sys, &mo, &dopt, a.y0, &st);
  /* the probe of FCN at (t0, y0), and of its Vectorized form */
  st.cnt.nrhs += c->probe_calls;
  st.cnt.nrhs_states += c->probe_states;
  st.cnt.njac += c->probe_jac;

  if (o.outputfcn)
    symmex_outputfcn (c, NULL, 0, NULL, "done");
  symmex_report (m, own, &o, &a, c, &st, status);
  if (o.hamiltonian && (nlhs == 1 || o.stats))
    symmex_energy (c);
  char jac_used[160];
  symmex_jac_used (c, &st, jac_used, sizeof jac_used);
  if (o.stats)
    symmex_print_stats (&st, jac_used, c);
  symmex_outputs (m, own, c, &st, jac_used, nlhs, plhs);
  sym_tangent_free (tg);
  if (nlhs == 1 && (status == SYM_DONE || status == SYM_STOP_EVENT
                    || status == SYM_STOP_OUTPUT))
    symmex_sol_restart (plhs[0], &st, a.opts);
}

void
symmex_run (const symmex_method *m, int nlhs, mxArray *plhs[], int nrhs,
            const mxArray *prhs[])
{
  /* a run from inside a user's function (nested) has a list of its own;
     the outer run's comes back when it ends (one that an error cut short
     went with its call) */
  core_block *outer = core_blocks;
  core_blocks = NULL;
  run (m, nlhs, plhs, nrhs, prhs);
  core_blocks = outer;
}
