/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* test_alloc_failure.c -- every allocation of a run may fail: with the
   k-th allocation failing, for every k up to the count a run makes, each
   method, fixed and adaptive (the splitting stepper: fixed only), with
   events and dense output, returns SYM_ENOMEM and frees all it took
   (the sanitizers see any use of NULL or leak). */
#include "sym.h"
#include "driver_util.h"
#include "testutil.h"

static int
event_q (double t, const double *y, double *value, int *isterminal,
         int *direction, void *user)
{
  (void) t;
  (void) user;
  value[0] = y[0];
  isterminal[0] = 0;
  direction[0] = 0;
  return 0;
}

static int
dense_sink (double t, double tnew, int k, const double *y, void *user)
{
  (void) t;
  (void) tnew;
  (void) k;
  (void) y;
  (void) user;
  return 0;
}

/* runs of the oscillator on [0, 2] failing the k-th allocation, k = 1,
   2, ... until one makes no more allocations than k - 1 and succeeds */
static void
failing_runs (const char *what, const sym_stepper_type *type,
              const void *own, double h_fixed)
{
  double y0[2] = { 1, 0 };
  long k;
  int ok = 1;
  for (k = 1; k < 10000; k++)
    {
      drv_run r;
      drv_setup (&r);
      r.o.tf = 2;
      r.o.h_fixed = h_fixed;
      r.o.nevents = 1;
      r.o.events = event_q;
      r.o.dense_out = dense_sink;
      r.mo.own = own;
      drv_alloc_count = drv_alloc_live = 0;
      drv_alloc_fail_at = k;
      int st = drv_integrate (&r, type, y0);
      if (drv_alloc_live != 0)
        {
          CHECK (0, "%s: %ld blocks not freed with allocation %ld failing",
                 what, drv_alloc_live, k);
          ok = 0;
        }
      if (drv_alloc_count < k)
        {
          CHECK (st == SYM_DONE, "%s: %s without a failing allocation",
                 what, sym_status_name (st));
          break;
        }
      if (st != SYM_ENOMEM)
        {
          CHECK (0, "%s: %s with allocation %ld failing", what,
                 sym_status_name (st), k);
          ok = 0;
        }
    }
  CHECK (ok && k > 3 && k < 10000, "%s: %ld allocations", what, k - 1);
}

int
main (void)
{
  sym_set_allocator (drv_counting_alloc, drv_counting_free);
  sym_onestep_opts sep = { 1, 0, 0, 0, 0, 0, NULL },
                   impl = { 0, 0, 0, 0, 0, 0, NULL };
  sym_spvi_opts sp = { 0, 0, SYM_MATRIX_AUTO, SYM_SYSTEM_AUTO, 0,
                        SYM_NONLINEAR_NEWTON };
  /* the splitting stepper: fixed steps of yoshida4, explicit (with
     compensated sums) and implicit */
  sym_onestep_opts y4e = { 1, 0, 1, 1, 0, 0, NULL },
                   y4i = { 0, 0, 1, 0, 0, 0, NULL };
  const struct {
    const char *name;
    const sym_stepper_type *const *type;
    const void *own;
  } m[] = { { "SE explicit", &sym_step_se, &sep },
            { "SE implicit", &sym_step_se, &impl },
            { "SV explicit", &sym_step_sv, &sep },
            { "SV implicit", &sym_step_sv, &impl },
            { "SPVI", &sym_step_spvi, &sp } };
  for (size_t i = 0; i < sizeof m / sizeof m[0]; i++)
    {
      failing_runs (m[i].name, *m[i].type, m[i].own, 0.0);
      failing_runs (m[i].name, *m[i].type, m[i].own, 0.1);
    }
  failing_runs ("yoshida4 explicit", sym_step_splitting, &y4e, 0.1);
  failing_runs ("yoshida4 implicit", sym_step_splitting, &y4i, 0.1);
  sym_set_allocator (NULL, NULL);
  return tu_finish ("test_alloc_failure");
}
