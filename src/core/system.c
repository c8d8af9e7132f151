/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* system.c -- allocator hook, status names, and the counted and checked
   calls of the user's f (single and batch). */
#include "calls.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static sym_alloc_fn sym_alloc_hook = malloc;
static sym_free_fn sym_free_hook = free;

/* the carving of blocks from a chunk (calls.h) */
#define CARVE_ALIGN 16
static struct {
  int on;
  char *next, *end;       /* what is left of the chunk */
  size_t asked;           /* bytes asked since sym_carve_from */
  uintptr_t lo, hi;       /* the region sym_free leaves alone */
} carve;

void
sym_set_allocator (sym_alloc_fn alloc, sym_free_fn dealloc)
{
  sym_alloc_hook = alloc ? alloc : malloc;
  sym_free_hook = dealloc ? dealloc : free;
  /* a caller that starts anew ends a carving an error cut short */
  memset (&carve, 0, sizeof carve);
}

void
sym_carve_region (const void *lo, size_t nbytes)
{
  carve.lo = (uintptr_t) lo;
  carve.hi = lo ? carve.lo + nbytes : 0;
}

void
sym_carve_from (void *chunk, size_t nbytes)
{
  carve.on = 1;
  carve.next = chunk;
  carve.end = chunk ? (char *) chunk + nbytes : NULL;
  carve.asked = 0;
}

size_t
sym_carve_end (void)
{
  carve.on = 0;
  carve.next = carve.end = NULL;
  return carve.asked;
}

void *
sym_malloc (size_t nbytes)
{
  if (carve.on && nbytes <= (size_t) -1 / 2)
    {
      const size_t nb = (nbytes + CARVE_ALIGN - 1) / CARVE_ALIGN
                        * CARVE_ALIGN;
      carve.asked += nb ? nb : CARVE_ALIGN;
      if (nb && carve.next && nb <= (size_t) (carve.end - carve.next))
        {
          void *p = carve.next;
          carve.next += nb;
          return p;
        }
    }
  return sym_alloc_hook (nbytes ? nbytes : 1);
}

void *
sym_calloc (size_t count, size_t size)
{
  if (size && count > (size_t) -1 / size)
    return NULL;
  void *p = sym_malloc (count * size);
  if (p)
    memset (p, 0, count * size);
  return p;
}

void
sym_free (void *ptr)
{
  /* a carved block goes with its chunk */
  if (ptr && ! ((uintptr_t) ptr >= carve.lo && (uintptr_t) ptr < carve.hi))
    sym_free_hook (ptr);
}

const char *
sym_status_name (int status)
{
  switch (status)
    {
    case SYM_SUCCESS: return "SYM_SUCCESS";
    case SYM_RECOVERABLE: return "SYM_RECOVERABLE";
    case SYM_NONFINITE: return "SYM_NONFINITE";
    case SYM_NEWTON_FAIL: return "SYM_NEWTON_FAIL";
    case SYM_SINGULAR: return "SYM_SINGULAR";
    case SYM_EBADINPUT: return "SYM_EBADINPUT";
    case SYM_ENOMEM: return "SYM_ENOMEM";
    case SYM_ECALLBACK: return "SYM_ECALLBACK";
    case SYM_ESTEPSIZE: return "SYM_ESTEPSIZE";
    case SYM_ENEWTON: return "SYM_ENEWTON";
    case SYM_ENONFINITE: return "SYM_ENONFINITE";
    case SYM_EMAXSTEPS: return "SYM_EMAXSTEPS";
    case SYM_EOUTPUT: return "SYM_EOUTPUT";
    case SYM_EOVERFLOW: return "SYM_EOVERFLOW";
    case SYM_EDENSITY: return "SYM_EDENSITY";
    case SYM_STOP_OUTPUT: return "SYM_STOP_OUTPUT";
    case SYM_STOP_EVENT: return "SYM_STOP_EVENT";
    default: return status > 0 ? "SYM_RECOVERABLE" : "SYM_ECALLBACK";
    }
}

int
sym_all_finite (size_t n, const double *v)
{
  for (size_t i = 0; i < n; i++)
    if (! isfinite (v[i]))
      return 0;
  return 1;
}

void
sym_eval_init (sym_eval *ev, const sym_system *sys)
{
  memset (ev, 0, sizeof (*ev));
  ev->dim = sys->dim;
  ev->rhs = sys->rhs;
  ev->rhs_batch = sys->rhs_batch;
  ev->jac = sys->jac;
  ev->rhs_jac = sys->rhs_jac;
  ev->user = sys->user;
  ev->sparse = sys->sparse;
  if (sys->sparse)
    {
      /* a sparse Df comes only as one */
      ev->jac = NULL;
      ev->rhs_jac = NULL;
      ev->jac_csc = sys->jac_csc;
      ev->rhs_jac_csc = sys->rhs_jac_csc;
    }
  if (sys->jp_ncolors > 0 && sys->jp_colptr && sys->jp_rowind
      && sys->jp_color)
    {
      ev->jp_colptr = sys->jp_colptr;
      ev->jp_rowind = sys->jp_rowind;
      ev->jp_color = sys->jp_color;
      ev->jp_ncolors = sys->jp_ncolors;
    }
}

/* A callback's own status: 0 ok, > 0 recoverable, < 0 fatal (mapped to
   SYM_ECALLBACK so the core's codes stay distinct from the user's). */
int
sym_callback_status (sym_eval *ev, double t, int st)
{
  if (st == 0)
    return SYM_SUCCESS;
  ev->st.fail_t = t;
  ev->st.fail_status = st;
  return st > 0 ? SYM_RECOVERABLE : SYM_ECALLBACK;
}

/* A NaN or Inf in a callback's values at t: remembered, reported. */
int
sym_nonfinite_at (sym_eval *ev, double t)
{
  ev->st.fail_t = t;
  ev->st.fail_status = SYM_NONFINITE;
  ev->st.fail_df = 0;
  return SYM_NONFINITE;
}

/* The same, in the user's Df (f finite) */
int
sym_nonfinite_df_at (sym_eval *ev, double t)
{
  sym_nonfinite_at (ev, t);
  ev->st.fail_df = 1;
  return SYM_NONFINITE;
}

int
sym_rhs (sym_eval *ev, double t, const double *y, double *dy)
{
  int n = 2 * ev->dim;
  ev->st.cnt.nrhs++;
  ev->st.cnt.nrhs_states++;
  int st = sym_callback_status (ev, t, ev->rhs (t, y, dy, ev->user));
  if (st)
    return st;
  return sym_all_finite (n, dy) ? SYM_SUCCESS : sym_nonfinite_at (ev, t);
}

int
sym_rhs_once (sym_eval *ev, double t, const double *y, double *dy,
              int *have)
{
  if (*have)
    return SYM_SUCCESS;
  int st = sym_rhs (ev, t, y, dy);
  if (st == SYM_SUCCESS)
    *have = 1;
  return st;
}

int
sym_rhs_many (sym_eval *ev, int k, const double *t, const double *y,
              double *dy)
{
  int n = 2 * ev->dim;
  if (ev->rhs_batch && k > 1)
    {
      ev->st.cnt.nrhs++;
      ev->st.cnt.nrhs_states += k;
      int st = sym_callback_status (ev, t[0],
                                ev->rhs_batch (k, t, y, dy, ev->user));
      if (st)
        return st;
      for (int j = 0; j < k; j++)
        if (! sym_all_finite (n, dy + (size_t) j * n))
          return sym_nonfinite_at (ev, t[j]);
      return SYM_SUCCESS;
    }
  for (int j = 0; j < k; j++)
    {
      int st = sym_rhs (ev, t[j], y + (size_t) j * n, dy + (size_t) j * n);
      if (st)
        return st;
    }
  return SYM_SUCCESS;
}

void
sym_sep_check (sym_eval *ev, double t, int k, const double *u,
               const double *v)
{
  if (ev->st.sep_broken)
    return;
  double big = 0.0, dif = 0.0;
  for (int i = 0; i < k; i++)
    {
      big = fmax (big, fmax (fabs (u[i]), fabs (v[i])));
      dif = fmax (dif, fabs (u[i] - v[i]));
    }
  if (dif > SYM_SEP_TOL * big)
    {
      ev->st.sep_broken = 1;
      ev->st.sep_broken_t = t;
    }
}

