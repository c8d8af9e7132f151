/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* outputs.c -- what a run hands back: the rows and events as they come
   (the core's sinks), OutputFcn, and the outputs [t, y, te, ye, ie] or
   sol with its stats. */
#include "symmex.h"

#include <math.h>
#include <string.h>

/* OutputFcn's stop flag as `if (stop)` takes it (as ode45 does): true
   when all its elements are nonzero, false when empty; NaN and values
   that are not logical, char or real numeric are errors. */
static int
stop_flag (symmex_ctx *c, mxArray **pa, double t)
{
  char buf[64];
  if (mxIsEmpty (*pa))
    return 0;
  mxArray *a = symmex_take_full (pa);
  if (! (mxIsNumeric (a) || mxIsLogical (a) || mxIsChar (a))
      || mxIsComplex (a))
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: OutputFcn must return a logical or "
                       "real numeric stop flag, got %s at t = %.15g",
                       c->solver, symmex_describe (a, buf, sizeof buf), t);
  size_t k = mxGetNumberOfElements (a);
  /* logical (the usual false) and char without a call of double () */
  if (mxIsLogical (a) || mxIsChar (a))
    {
      for (size_t i = 0; i < k; i++)
        if (mxIsLogical (a) ? ! mxGetLogicals (a)[i] : ! mxGetChars (a)[i])
          return 0;
      return 1;
    }
  const double *v = mxGetPr (symmex_take_double (pa));
  int stop = 1;
  for (size_t i = 0; i < k; i++)
    {
      if (isnan (v[i]))
        mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: OutputFcn returned NaN as its stop "
                           "flag at t = %.15g", c->solver, t);
      if (v[i] == 0.0)
        stop = 0;
    }
  return stop;
}

/* OutputFcn (t, y(OutputSel), flag, extras...): returns its stop flag. */
int
symmex_outputfcn (symmex_ctx *c, const double *t, int nt, const double *y,
                const char *flag)
{
  const symmex_opts *o = c->o;
  int nsel = o->outputsel ? o->noutputsel : c->n;
  mxArray *ta, *ya;
  if (! t)
    {
      ta = mxCreateDoubleMatrix (0, 0, mxREAL);
      ya = mxCreateDoubleMatrix (0, 0, mxREAL);
    }
  else
    {
      ta = mxCreateDoubleMatrix (nt, 1, mxREAL);
      memcpy (mxGetPr (ta), t, sizeof (double) * nt);
      /* an ensemble's: each member's OutputSel in turn */
      const int K = c->members > 1 ? c->members : 1;
      ya = mxCreateDoubleMatrix ((size_t) nsel * K, 1, mxREAL);
      for (int j = 0; j < K; j++)
        for (int i = 0; i < nsel; i++)
          mxGetPr (ya)[(size_t) j * nsel + i]
            = y[(size_t) j * c->n + (o->outputsel ? o->outputsel[i] : i)];
    }
  c->oargs[1] = ta;
  c->oargs[2] = ya;
  c->oargs[3] = mxCreateString (flag);
  int nout = strcmp (flag, "") == 0 ? 1 : 0;
  mxArray *out[1] = { NULL };
  if (nout)
    symmex_call_cb (c, SYMMEX_CB_OUTPUT, out, c->nargs + 1, c->oargs,
                    c->oname, "OutputFcn", "STOP (true to end the run)");
  else
    symmex_call (0, out, c->nargs + 1, c->oargs, c->oname);
  int stop = nout && out[0] ? stop_flag (c, out, t ? t[0] : NAN) : 0;
  if (out[0])
    mxDestroyArray (out[0]);
  mxDestroyArray (c->oargs[3]);
  mxDestroyArray (ya);
  mxDestroyArray (ta);
  return stop;
}

/* *p grown to cap items of size bytes each: 0 when that does not fit (the
   block stays as it was: mxRealloc returns NULL then, it does not raise
   an error as mxMalloc does) */
static int
grow (void **p, size_t cap, size_t size)
{
  if (size && cap > (size_t) -1 / size)
    return 0;
  void *q = mxRealloc (*p, cap * size);
  if (! q)
    return 0;
  *p = q;
  return 1;
}

/* The capacity after cap (at least first), or 0 and c->oom when the
   arrays (item sizes in sizes, k of them) cannot grow to it */
static size_t
grow_all (symmex_ctx *c, size_t cap, size_t first, void **arrays[],
          const size_t *sizes, int k)
{
  const size_t want = cap ? 2 * cap : first;
  for (int i = 0; i < k; i++)
    if (! grow (arrays[i], want, sizes[i]))
      {
        c->oom = 1;
        return 0;
      }
  return want;
}

double *
symmex_row (const symmex_ctx *c, size_t r)
{
  return c->yblk[r / c->crows] + (r % c->crows) * c->n;
}

/* room for row c->nrows: the times grown, a new block of rows when the
   last is full; 0 when it does not fit (c->oom) */
static int
row_room (symmex_ctx *c)
{
  if (! c->crows)
    {
      c->crows = SYMMEX_ROW_BLOCK / (sizeof (double) * c->n);
      c->crows = c->crows ? c->crows : 1;
    }
  if (c->nrows == c->cap)
    {
      void **a[] = { (void **) &c->tbuf };
      const size_t sz[] = { sizeof (double) };
      size_t cap = grow_all (c, c->cap, 256, a, sz, 1);
      if (! cap)
        return 0;
      c->cap = cap;
    }
  if (c->nrows < c->nblk * c->crows)
    return 1;
  if (c->nblk == c->blkcap)
    {
      void **a[] = { (void **) &c->yblk };
      const size_t sz[] = { sizeof (double *) };
      size_t cap = grow_all (c, c->blkcap, 16, a, sz, 1);
      if (! cap)
        return 0;
      c->blkcap = cap;
    }
  /* one that cannot be had is told as the output's (mxMalloc would
     raise its own error) */
  double *b = symmex_malloc_or_null (c->crows * sizeof (double) * c->n);
  if (! b)
    {
      c->oom = 1;
      return 0;
    }
  c->yblk[c->nblk++] = b;
  return 1;
}

int
symmex_sink_row (double t, const double *y, void *user)
{
  symmex_ctx *c = user;
  if (! row_room (c))
    return -1;
  c->tbuf[c->nrows] = t;
  memcpy (symmex_row (c, c->nrows), y, sizeof (double) * c->n);
  c->nrows++;
  if (c->tangent)
    symmex_tangent_row (c);
  if (c->o->outputfcn && c->nrows > 1)
    {
      if (symmex_outputfcn (c, &t, 1, y, ""))
        return 1;
    }
  return 0;
}

int
symmex_sink_event (double te, const double *ye, int ie, void *user)
{
  symmex_ctx *c = user;
  if (c->nev == c->evcap)
    {
      void **a[] = { (void **) &c->te, (void **) &c->ye, (void **) &c->ie };
      const size_t sz[] = { sizeof (double), sizeof (double) * c->n,
                            sizeof (int) };
      size_t cap = grow_all (c, c->evcap, 16, a, sz, 3);
      if (! cap)
        return -1;
      c->evcap = cap;
    }
  c->te[c->nev] = te;
  memcpy (c->ye + c->nev * c->n, ye, sizeof (double) * c->n);
  c->ie[c->nev] = ie;
  c->nev++;
  return 0;
}

int
symmex_sink_dense (double t, double tnew, int k, const double *y, void *user)
{
  symmex_ctx *c = user;
  const size_t per = (size_t) c->n * (k + 2);
  if (c->nsteps == c->dcap)
    {
      void **a[] = { (void **) &c->dt, (void **) &c->dy };
      const size_t sz[] = { 2 * sizeof (double), sizeof (double) * per };
      size_t cap = grow_all (c, c->dcap, 256, a, sz, 2);
      if (! cap)
        return -1;
      c->dcap = cap;
    }
  c->dk = k;
  c->dt[2 * c->nsteps] = t;
  c->dt[2 * c->nsteps + 1] = tnew;
  memcpy (c->dy + c->nsteps * per, y, sizeof (double) * per);
  c->nsteps++;
  return 0;
}

void
symmex_energy (symmex_ctx *c)
{
  const int n = c->n;
  mxArray **args = mxCalloc (c->nargs, sizeof (mxArray *));
  memcpy (args, c->args, sizeof (mxArray *) * c->nargs);
  args[0] = (mxArray *) c->o->hamiltonian;
  /* its own y: FCN's holds q alone with SecondOrder */
  args[2] = mxCreateDoubleMatrix (n, 1, mxREAL);
  char name[64];
  symmex_direct_name (args[0], name, sizeof name);
  c->hbuf = mxMalloc (sizeof (double) * (c->nrows + 1));
  c->max_dh = 0.0;
  for (size_t r = 0; r < c->nrows; r++)
    {
      mxArray *out[1] = { NULL };
      mxGetPr (args[1])[0] = c->tbuf[r];
      memcpy (mxGetPr (args[2]), symmex_row (c, r), sizeof (double) * n);
      symmex_call_cb (c, SYMMEX_CB_HAMILTONIAN, out, c->nargs, args, name,
                      "the Hamiltonian", "a real scalar");
      c->hbuf[r] = symmex_checked (c, out, 1, "the Hamiltonian", 0,
                                   c->tbuf[r], "a real scalar")[0];
      mxDestroyArray (out[0]);
      const double h0 = c->hbuf[0], dh = fabs (c->hbuf[r] - h0);
      const double rel = h0 != 0.0 ? dh / fabs (h0) : dh;
      if (rel > c->max_dh || isnan (rel))
        c->max_dh = rel;
    }
  mxDestroyArray (args[2]);
}

static mxArray *
rows_matrix (const double *buf, size_t nrows, int n)
{
  /* buf holds the rows as columns of an n-by-nrows array */
  mxArray *a = mxCreateDoubleMatrix (nrows, n, mxREAL);
  double *p = mxGetPr (a);
  for (size_t r = 0; r < nrows; r++)
    for (int i = 0; i < n; i++)
      p[r + (size_t) i * nrows] = buf[r * n + i];
  return a;
}

/* The rows as an nrows-by-n matrix (rows: y in rows, as ode45 gives
   them) or n-by-nrows (columns: sol.y); each block of them freed once
   copied */
static mxArray *
rows_out (symmex_ctx *c, int rows)
{
  const size_t nrows = c->nrows, n = c->n;
  mxArray *a = rows ? mxCreateDoubleMatrix (nrows, n, mxREAL)
                    : mxCreateDoubleMatrix (n, nrows, mxREAL);
  double *p = mxGetPr (a);
  for (size_t b = 0; b < c->nblk; b++)
    {
      const size_t r0 = b * c->crows;
      for (size_t r = r0; r < nrows && r < r0 + c->crows; r++)
        {
          const double *y = symmex_row (c, r);
          if (rows)
            for (size_t i = 0; i < n; i++)
              p[r + i * nrows] = y[i];
          else
            memcpy (p + r * n, y, sizeof (double) * n);
        }
      mxFree (c->yblk[b]);
      c->yblk[b] = NULL;
    }
  c->nblk = 0;
  return a;
}

static mxArray *
column_of (const double *v, size_t k)
{
  mxArray *a = mxCreateDoubleMatrix (k, 1, mxREAL);
  if (k)
    memcpy (mxGetPr (a), v, sizeof (double) * k);
  return a;
}

/* The events found: te (column), ye (one row each), ie (column, 1-based);
   with none, all three 0-by-0, as ode45 returns them */
static void
event_outputs (const symmex_ctx *c, int n, mxArray **te, mxArray **ye,
               mxArray **ie)
{
  if (c->nev == 0)
    {
      *te = mxCreateDoubleMatrix (0, 0, mxREAL);
      *ye = mxCreateDoubleMatrix (0, 0, mxREAL);
      *ie = mxCreateDoubleMatrix (0, 0, mxREAL);
      return;
    }
  *te = column_of (c->te, c->nev);
  *ye = rows_matrix (c->ye, c->nev, n);
  *ie = mxCreateDoubleMatrix (c->nev, 1, mxREAL);
  for (size_t i = 0; i < c->nev; i++)
    mxGetPr (*ie)[i] = c->ie[i] + 1;
}

static mxArray *
stats_struct (const sym_counters *k, const char *jac_source)
{
  const char *names[] = { "nsteps", "nfailed", "nfevals", "npds",
                          "ndecomps", "nlinsols", "nnewton", "nfdevals",
                          "nstates", "jacobian_source" };
  mxArray *s = mxCreateStructMatrix (1, 1, 10, names);
  double vals[] = { k->nsteps, k->nfailed, k->nrhs, k->njac, k->nlu,
                    k->nsolve, k->nnewton, k->nfd, k->nrhs_states };
  for (int i = 0; i < 9; i++)
    mxSetFieldByNumber (s, 0, i, mxCreateDoubleScalar (vals[i]));
  mxSetFieldByNumber (s, 0, 9, mxCreateString (jac_source));
  return s;
}


static mxArray *
row_of (const double *v, size_t k)
{
  mxArray *a = mxCreateDoubleMatrix (1, k, mxREAL);
  if (k)
    memcpy (mxGetPr (a), v, sizeof (double) * k);
  return a;
}

/* sol.dense: t (2 x steps, each step's start and end) and y (n x (k + 2)
   x steps, each step's dense output at its Chebyshev-Lobatto points) */
static mxArray *
dense_struct (const symmex_ctx *c)
{
  const char *fields[] = { "t", "y" };
  mxArray *d = mxCreateStructMatrix (1, 1, 2, fields);
  mxArray *t = mxCreateDoubleMatrix (2, c->nsteps, mxREAL);
  if (c->nsteps)
    memcpy (mxGetPr (t), c->dt, sizeof (double) * 2 * c->nsteps);
  const mwSize dims[3] = { (mwSize) c->n, (mwSize) c->dk + 2,
                           (mwSize) c->nsteps };
  mxArray *y = mxCreateNumericArray (3, dims, mxDOUBLE_CLASS, mxREAL);
  if (c->nsteps)
    memcpy (mxGetPr (y), c->dy,
            sizeof (double) * c->n * (c->dk + 2) * c->nsteps);
  mxSetField (d, 0, "t", t);
  mxSetField (d, 0, "y", y);
  return d;
}

static mxArray *
sol_struct (const symmex_method *m, const void *own, symmex_ctx *c,
            const sym_stats *st, const char *jac_used)
{
  const int n = c->n, has_ev = c->o->events != NULL;
  const char *fields[] = { "x", "y", "solver", "xe", "ye", "ie", "stats" };
  mxArray *s = mxCreateStructMatrix (1, 1, 3, fields);
  mxArray *x = mxCreateDoubleMatrix (1, c->nrows, mxREAL);
  if (c->nrows)
    memcpy (mxGetPr (x), c->tbuf, sizeof (double) * c->nrows);
  mxArray *y = rows_out (c, 0);
  mxSetField (s, 0, "x", x);
  mxSetField (s, 0, "y", y);
  mxSetField (s, 0, "solver", mxCreateString (m->name));
  if (has_ev)
    {
      mxArray *te, *ye, *ie;
      event_outputs (c, n, &te, &ye, &ie);
      for (int k = 3; k < 6; k++)
        mxAddField (s, fields[k]);
      mxSetField (s, 0, "xe", te);
      mxSetField (s, 0, "ye", ye);
      mxSetField (s, 0, "ie", ie);
    }
  mxAddField (s, "stats");
  mxSetField (s, 0, "stats", stats_struct (&st->cnt, jac_used));
  if (c->hbuf)
    {
      mxAddField (s, "H");
      mxSetField (s, 0, "H", row_of (c->hbuf, c->nrows));
      mxAddField (mxGetField (s, 0, "stats"), "max_dH");
      mxSetField (mxGetField (s, 0, "stats"), 0, "max_dH",
                  mxCreateDoubleScalar (c->max_dh));
    }
  if (c->o->dense)
    {
      mxAddField (s, "dense");
      mxSetField (s, 0, "dense", dense_struct (c));
    }
  if (c->tangent)
    symmex_tangent_sol (c, s);
  if (m->sol_fields)
    m->sol_fields (s, own, st);
  return s;
}

void
symmex_outputs (const symmex_method *m, const void *own,
                symmex_ctx *c, const sym_stats *st,
                const char *jac_used, int nlhs, mxArray *plhs[])
{
  const int n = c->n;
  if (nlhs == 0)
    return;
  if (nlhs == 1)
    {
      plhs[0] = sol_struct (m, own, c, st, jac_used);
      return;
    }
  plhs[0] = column_of (c->tbuf, c->nrows);
  plhs[1] = rows_out (c, 1);
  if (nlhs > 2)
    {
      mxArray *te, *ye, *ie;
      event_outputs (c, n, &te, &ye, &ie);
      symmex_event_plhs (nlhs, plhs, te, ye, ie);
    }
}

void
symmex_event_plhs (int nlhs, mxArray *plhs[], mxArray *te, mxArray *ye,
                   mxArray *ie)
{
  plhs[2] = te;
  if (nlhs > 3)
    plhs[3] = ye;
  else
    mxDestroyArray (ye);
  if (nlhs > 4)
    plhs[4] = ie;
  else
    mxDestroyArray (ie);
}

void
symmex_sol_restart (mxArray *sol, const sym_stats *st, const mxArray *opts)
{
  const char *names[] = { "h", "t0", "k", "rho", "options" };
  mxArray *r = mxCreateStructMatrix (1, 1, 5, names);
  mxSetField (r, 0, "h", mxCreateDoubleScalar (st->restart_h));
  mxSetField (r, 0, "t0", mxCreateDoubleScalar (st->restart_t0));
  mxSetField (r, 0, "k", mxCreateDoubleScalar ((double) st->restart_k));
  mxSetField (r, 0, "rho", row_of (st->restart_rho, 2));
  mxSetField (r, 0, "options", opts && mxIsStruct (opts)
                               ? mxDuplicateArray (opts)
                               : mxCreateDoubleMatrix (0, 0, mxREAL));
  mxAddField (sol, "restart");
  mxSetField (sol, 0, "restart", r);
}
