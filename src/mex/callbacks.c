/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* callbacks.c -- the user's functions as callbacks of the core: FCN (one
   state, or Vectorized several), its Hessian or the Jacobian, and the
   Events function, each value checked as it comes back.

   Every allocation is mxMalloc'd (the core's allocator hook points there)
   so that an error raised inside a user's function, which leaves this MEX
   function through mexCallMATLAB without coming back, leaks nothing:
   Octave frees it all when the call ends. */
#include "symmex.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* Check a value returned by a user's function: real numeric with k
   elements (or logical, when logical_ok: the Events function's VALUE and
   flags, as ode45 takes them); convert it to double if needed.  Returns a
   double array. */
const double *
symmex_checked (symmex_ctx *c, mxArray **pa, size_t k, const char *what,
                int logical_ok, double t, const char *expect_fmt, ...)
{
  mxArray *a = symmex_take_full (pa);
  char buf[64];
  if (! a || ! (mxIsNumeric (a) || (logical_ok && mxIsLogical (a)))
      || mxIsComplex (a)
      || mxGetNumberOfElements (a) != k)
    {
      /* what was expected, formatted only here: callbacks stay cheap */
      char expect[128];
      va_list ap;
      va_start (ap, expect_fmt);
      vsnprintf (expect, sizeof expect, expect_fmt, ap);
      va_end (ap);
      if (a && mxIsComplex (a) && mxGetNumberOfElements (a) == k)
        mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: %s returned a complex value at "
                           "t = %.15g; expected %s", c->solver, what, t,
                           expect);
      mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: %s must return %s, got %s at "
                         "t = %.15g", c->solver, what, expect,
                         a ? symmex_describe (a, buf, sizeof buf)
                         : "nothing", t);
    }
  return mxGetPr (symmex_take_double (pa));
}

/* The core finds NaN/Inf itself (and retries with a smaller step); this
   only remembers which of the user's functions gave them, for the
   warning when the run cannot go on. */
static void
note_nonfinite (symmex_ctx *c, const double *v, size_t k, const char *what,
                double t)
{
  for (size_t i = 0; i < k; i++)
    if (! isfinite (v[i]))
      {
        c->nonfinite_what = what;
        c->nonfinite_t = t;
        return;
      }
}

/* ------------------------------------------------------------ calls */

/* type, name and file of a function handle as functions () gives them
   (file may be NULL: not wanted); 0 if that fails or they do not fit */
static int
handle_info (const mxArray *f, char *type, size_t tlen, char *fn,
             size_t flen, char *file, size_t filelen)
{
  mxArray *in[1] = { (mxArray *) f }, *out[1] = { NULL };
  mxArray *ex = mexCallMATLABWithTrap (1, out, 1, in, "functions");
  if (ex)
    {
      mxDestroyArray (ex);
      return 0;
    }
  const mxArray *ty = mxIsStruct (out[0])
                      ? mxGetField (out[0], 0, "type") : NULL;
  const mxArray *nm = mxIsStruct (out[0])
                      ? mxGetField (out[0], 0, "function") : NULL;
  const mxArray *fl = mxIsStruct (out[0])
                      ? mxGetField (out[0], 0, "file") : NULL;
  int ok = ty && nm && mxIsChar (ty) && mxIsChar (nm)
           && mxGetNumberOfElements (ty) < tlen
           && mxGetNumberOfElements (nm) < flen
           && ! mxGetString (ty, type, tlen) && ! mxGetString (nm, fn, flen);
  if (ok && file)
    {
      file[0] = '\0';
      ok = ! fl || mxIsEmpty (fl)
           || (mxIsChar (fl) && mxGetNumberOfElements (fl) < filelen
               && ! mxGetString (fl, file, filelen));
    }
  mxDestroyArray (out[0]);
  return ok;
}

/* Whether the name fn finds the file "file" (which (fn), as a call by
   name finds it) */
static int
name_finds (const char *fn, const char *file)
{
  mxArray *in[1] = { mxCreateString (fn) }, *out[1] = { NULL };
  mxArray *ex = mexCallMATLABWithTrap (1, out, 1, in, "which");
  mxDestroyArray (in[0]);
  if (ex)
    {
      mxDestroyArray (ex);
      return 0;
    }
  char *w = mxIsChar (out[0]) ? mxArrayToString (out[0]) : NULL;
  int same = w && strcmp (w, file) == 0;
  mxFree (w);
  mxDestroyArray (out[0]);
  return same;
}

/* The name f can be called by, or "" when f must go through feval.  A
   call by name skips feval's own call (bench B0).  A call by name looks
   the name up
   in the scope the solver was called from, where a subfunction or private
   function of that name comes first; a simple handle @name looks it up
   among the functions visible everywhere.  So a function's name is called
   by name (feval would look it up the same way), a simple handle only when
   a handle made from its name in the caller's scope is simple too (no
   subfunction or private function of that name there), and all other
   handles (anonymous, to subfunctions, to private functions) through
   feval.  A simple handle bound to a file that the name does not find
   (a command-line function of that name comes first for a call by name,
   not for the handle) goes through feval too. */
void
symmex_direct_name (const mxArray *f, char *name, size_t len)
{
  name[0] = '\0';
  char buf[64] = "", type[16] = "", file[4096] = "";
  if (mxIsChar (f))
    {
      if (mxGetNumberOfElements (f) >= sizeof buf
          || mxGetString (f, buf, sizeof buf))
        return;
    }
  else if (! mxIsFunctionHandle (f)
           || ! handle_info (f, type, sizeof type, buf, sizeof buf, file,
                             sizeof file)
           || strcmp (type, "simple") != 0)
    return;
  /* an identifier only (not "pkg.fcn", not an expression) */
  if (! ((buf[0] >= 'a' && buf[0] <= 'z') || (buf[0] >= 'A' && buf[0] <= 'Z')))
    return;
  for (const char *p = buf; *p; p++)
    if (! ((*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z')
           || (*p >= '0' && *p <= '9') || *p == '_'))
      return;
  if (mxIsFunctionHandle (f))
    {
      mxArray *in[1] = { mxCreateString (buf) }, *out[1] = { NULL };
      mxArray *ex = mexCallMATLABWithTrap (1, out, 1, in, "str2func");
      mxDestroyArray (in[0]);
      if (ex)
        {
          mxDestroyArray (ex);
          return;
        }
      char fn2[64];
      int same = handle_info (out[0], type, sizeof type, fn2, sizeof fn2,
                              NULL, 0)
                 && strcmp (type, "simple") == 0 && strcmp (fn2, buf) == 0;
      mxDestroyArray (out[0]);
      /* a handle bound to a file that the name does not find (a file on
         the path shadowed by a command-line function of the same name,
         which a call by name finds first) */
      if (! same || (file[0] && ! name_finds (buf, file)))
        return;
    }
  if (strlen (buf) < len)
    strcpy (name, buf);
}

/* Call a user's function: args = {f, t, y, ...}; by name when it has one,
   else feval (f, t, y, ...). */
void
symmex_call (int nout, mxArray **out, int nargs, mxArray **args,
           const char *name)
{
  void *mark = symmex_core_mark ();
  if (name[0])
    mexCallMATLAB (nout, out, nargs - 1, args + 1, name);
  else
    mexCallMATLAB (nout, out, nargs, args, "feval");
  symmex_core_back (mark);
  for (int i = 0; i < nout; i++)
    symmex_settle (out[i]);
}

/* ------------------------------------------------------------ callbacks */

/* FCN at (t, y) with nout outputs: the first, checked, into dy (and
   destroyed), the others left in out */
static void
call_fcn (symmex_ctx *c, double t, const double *y, int nout, mxArray **out,
          double *dy)
{
  const int nf = c->nf;
  mxGetPr (c->args[1])[0] = t;
  memcpy (mxGetPr (c->args[2]), y, sizeof (double) * nf);
  symmex_call (nout, out, c->nargs, c->args, c->fname);
  const double *v = symmex_checked (c, out, nf, "FCN", 0, t,
                                    "a vector of %d real elements", nf);
  note_nonfinite (c, v, nf, "FCN", t);
  /* SecondOrder: f = [v; a] */
  if (c->second_order)
    memcpy (dy, y + nf, sizeof (double) * nf);
  memcpy (dy + (c->n - nf), v, sizeof (double) * nf);
  mxDestroyArray (out[0]);
}

int
symmex_cb_rhs (double t, const double *y, double *dy, void *user)
{
  symmex_ctx *c = user;
  if (c->compiled)
    return symmex_compiled_rhs (t, y, dy, user);
  /* the first call at (t0, y0) after the probe of Separable: its value */
  if (c->f0_kept && t == c->t0
      && memcmp (y, c->y0, sizeof (double) * c->n) == 0)
    {
      memcpy (dy, c->f0, sizeof (double) * c->n);
      c->f0_kept = 0;
      c->probe_calls--;
      c->probe_states--;
      return 0;
    }
  mxArray *out[1] = { NULL };
  call_fcn (c, t, y, 1, out, dy);
  return 0;
}

/* Vectorized: fcn (t_row, Y) with Y n-by-k returns n-by-k. */
int
symmex_cb_rhs_batch (int k, const double *t, const double *y, double *dy,
              void *user)
{
  symmex_ctx *c = user;
  if (c->compiled)
    return symmex_compiled_rhs_batch (k, t, y, dy, user);
  /* argument arrays kept for each k up to SYMMEX_MAXBATCH, and for the last
     larger k (finite differences batch 2d Nodes states) */
  int slot = k <= SYMMEX_MAXBATCH ? k : 0;
  if (slot == 0 && c->big_k != k)
    {
      if (c->batch_t[0])
        {
          mxDestroyArray (c->batch_t[0]);
          mxDestroyArray (c->batch_y[0]);
        }
      c->batch_t[0] = c->batch_y[0] = NULL;
      c->big_k = k;
    }
  const int n = c->n, nf = c->nf;
  if (! c->batch_t[slot])
    {
      c->batch_t[slot] = mxCreateDoubleMatrix (1, k, mxREAL);
      c->batch_y[slot] = mxCreateDoubleMatrix (nf, k, mxREAL);
    }
  mxArray *t1 = c->args[1], *y1 = c->args[2];
  c->args[1] = c->batch_t[slot];
  c->args[2] = c->batch_y[slot];
  memcpy (mxGetPr (c->args[1]), t, sizeof (double) * k);
  if (c->second_order)
    for (int j = 0; j < k; j++)
      memcpy (mxGetPr (c->args[2]) + (size_t) j * nf, y + (size_t) j * n,
              sizeof (double) * nf);
  else
    memcpy (mxGetPr (c->args[2]), y, sizeof (double) * n * k);
  mxArray *out[1] = { NULL };
  symmex_call (1, out, c->nargs, c->args, c->fname);
  c->args[1] = t1;
  c->args[2] = y1;
  static const char *expect = "a %dx%d real matrix (Vectorized)";
  if (out[0] && ! symmex_is_size (out[0], nf, k))
    symmex_checked (c, out, (size_t) -1, "FCN", 0, t[0], expect, nf, k);
  const double *v = symmex_checked (c, out, (size_t) nf * k, "FCN", 0,
                                    t[0], expect, nf, k);
  note_nonfinite (c, v, (size_t) nf * k, "FCN", t[0]);
  if (c->second_order)
    for (int j = 0; j < k; j++)
      {
        memcpy (dy + (size_t) j * n, y + (size_t) j * n + nf,
                sizeof (double) * nf);
        memcpy (dy + (size_t) j * n + nf, v + (size_t) j * nf,
                sizeof (double) * nf);
      }
  else
    memcpy (dy, v, sizeof (double) * n * k);
  mxDestroyArray (out[0]);
  return 0;
}

/* Hess(H) (n-by-n, or its column-major vector) -> Df = J * Hess. */
static void
hess_to_df (int d, const double *hs, double *df)
{
  int n = 2 * d;
  for (int j = 0; j < n; j++)
    for (int i = 0; i < d; i++)
      {
        df[i + (size_t) j * n] = hs[(i + d) + (size_t) j * n];
        df[(i + d) + (size_t) j * n] = -hs[i + (size_t) j * n];
      }
}

/* what a Hessian must be, for messages (arguments n, n, n^2) */
const char *const SYMMEX_HESS_EXPECT = "the Hessian of H, a %dx%d matrix or "
                                       "a vector of %d elements";

/* a is n-by-n, or a row or column (or not yet known to hold n^2 elements:
   checked_values says what it holds) */
int
symmex_hessian_shape (const mxArray *a, int n)
{
  if (! a || mxGetNumberOfElements (a) != (size_t) n * n)
    return 1;
  return symmex_is_size (a, n, n) || symmex_is_vector (a);
}

/* The Hessian of H (JAC_HESSFCN, JAC_FCN2) in out[0] -> df. */
static void
take_hessian (symmex_ctx *c, mxArray **out, double t, double *df)
{
  int n = c->n;
  int fcn2 = c->jac_source == JAC_FCN2;
  const char *what = fcn2 ? "FCN (second output)" : "HamiltonianHessFcn";
  if (! symmex_hessian_shape (out[0], n))
    symmex_checked (c, out, (size_t) -1, what, 0, t, SYMMEX_HESS_EXPECT, n, n,
                    n * n);
  const double *v = symmex_checked (c, out, (size_t) n * n, what, 0, t,
                                    SYMMEX_HESS_EXPECT, n, n, n * n);
  note_nonfinite (c, v, (size_t) n * n,
                  fcn2 ? "FCN's second output (the Hessian)"
                       : "HamiltonianHessFcn", t);
  hess_to_df (c->d, v, df);
}

mxArray *
symmex_jac_value (symmex_ctx *c, double t, const double *y)
{
  mxGetPr (c->jargs[1])[0] = t;
  memcpy (mxGetPr (c->jargs[2]), y, sizeof (double) * c->n);
  mxArray *out[2] = { NULL, NULL };
  if (c->jac_source == JAC_FCN2)
    {
      symmex_call (2, out, c->nargs, c->jargs, c->jname);
      mxDestroyArray (out[0]);
      return out[1];
    }
  symmex_call_cb (c, SYMMEX_CB_JAC, out, c->nargs, c->jargs, c->jname,
                  c->jac_source == JAC_FCN ? "the Jacobian function"
                  : "HamiltonianHessFcn", "a matrix");
  return out[0];
}

int
symmex_cb_jac (double t, const double *y, double *df, void *user)
{
  symmex_ctx *c = user;
  int n = c->n;
  if (c->jac_source == JAC_MATRIX)
    {
      if (! c->jac_const)
        c->jac_const = mxGetPr (symmex_full (c->o->jacobian));
      memcpy (df, c->jac_const, sizeof (double) * n * n);
      return 0;
    }
  mxArray *out[1] = { symmex_jac_value (c, t, y) };
  if (c->jac_source == JAC_FCN)
    {
      static const char *expect = "a %dx%d real matrix (df/dy)";
      if (out[0] && ! symmex_is_size (out[0], n, n))
        symmex_checked (c, out, (size_t) -1, "the Jacobian function", 0, t,
                        expect, n, n);
      const double *v = symmex_checked (c, out, (size_t) n * n,
                                        "the Jacobian function", 0, t,
                                        expect, n, n);
      note_nonfinite (c, v, (size_t) n * n, "the Jacobian function", t);
      memcpy (df, v, sizeof (double) * n * n);
    }
  else
    take_hessian (c, out, t, df);
  mxDestroyArray (out[0]);
  return 0;
}

/* ------------------------------------------------------------ sparse Df */

/* A matrix a (n-by-n, sparse or full; its entries that are not zero)
   into df: as it is (a Jacobian), or Df = J * a for a Hessian: the p
   rows of a, then minus its q rows, in each column */
static void
to_csc (const mxArray *a, int n, int hess, sym_csc *df)
{
  const int d = n / 2, sp = mxIsSparse (a);
  const mwIndex *jc = sp ? mxGetJc (a) : NULL, *ir = sp ? mxGetIr (a) : NULL;
  const double *v = mxGetPr (a);
  size_t cap = sp ? jc[n] : 0;
  if (! sp)
    for (size_t i = 0; i < (size_t) n * n; i++)
      cap += v[i] != 0.0;
  if (sym_csc_reserve (df, (int) cap))
    mexErrMsgIdAndTxt ("symplectic:nomem", "out of memory for a sparse "
                       "Jacobian of %zu entries", cap);
  df->n = n;
  int e = 0;
  for (int j = 0; j < n; j++)
    {
      const size_t q0 = sp ? jc[j] : (size_t) j * n;
      const size_t q1 = sp ? jc[j + 1] : (size_t) (j + 1) * n;
      df->colptr[j] = e;
      /* a Hessian's p rows come first (they become Df's q rows) */
      for (int pass = hess ? 0 : 1; pass < 2; pass++)
        for (size_t q = q0; q < q1; q++)
          {
            const int r = sp ? (int) ir[q] : (int) (q - q0);
            if ((! sp && v[q] == 0.0) || (hess && (pass == 0) != (r >= d)))
              continue;
            df->rowind[e] = hess ? (r >= d ? r - d : r + d) : r;
            df->val[e++] = hess && r < d ? -v[q] : v[q];
          }
    }
  df->colptr[n] = df->nnz = e;
}

/* The sparse Df of the user's function's value in out[0], checked as in
   symmex_cb_jac (its size and type; what: its name for messages) */
static void
take_sparse (symmex_ctx *c, mxArray **out, double t, int hess,
             const char *what, sym_csc *df)
{
  const int n = c->n;
  const mxArray *a = out[0];
  if (! a || ! mxIsSparse (a) || mxIsComplex (a) || ! mxIsDouble (a)
      || ! symmex_is_size (a, n, n))
    {
      /* anything else as the dense path takes it (and refuses it) */
      if (hess && ! symmex_hessian_shape (a, n))
        symmex_checked (c, out, (size_t) -1, what, 0, t, SYMMEX_HESS_EXPECT,
                        n, n, n * n);
      symmex_checked (c, out, (size_t) n * n, what, 0, t, hess
                      ? SYMMEX_HESS_EXPECT : "a %dx%d real matrix (df/dy)",
                      n, n, n * n);
    }
  to_csc (out[0], n, hess, df);
  note_nonfinite (c, df->val, df->nnz, what, t);
}

int
symmex_cb_jac_csc (double t, const double *y, sym_csc *df, void *user)
{
  symmex_ctx *c = user;
  if (c->jac_source == JAC_MATRIX)
    {
      to_csc (c->o->jacobian, c->n, 0, df);
      return 0;
    }
  mxArray *out[1] = { symmex_jac_value (c, t, y) };
  const int hess = c->jac_source != JAC_FCN;
  take_sparse (c, out, t, hess, c->jac_source == JAC_FCN
               ? "the Jacobian function" : c->jac_source == JAC_FCN2
               ? "FCN (second output)" : "HamiltonianHessFcn", df);
  mxDestroyArray (out[0]);
  return 0;
}

int
symmex_cb_rhs_jac_csc (double t, const double *y, double *dy, sym_csc *df,
                       void *user)
{
  symmex_ctx *c = user;
  mxArray *out[2] = { NULL, NULL };
  call_fcn (c, t, y, 2, out, dy);
  take_sparse (c, &out[1], t, 1, "FCN (second output)", df);
  mxDestroyArray (out[1]);
  return 0;
}

/* JAC_FCN2: f and the Hessian from one call of FCN with two outputs. */
int
symmex_cb_rhs_jac (double t, const double *y, double *dy, double *df, void *user)
{
  symmex_ctx *c = user;
  mxArray *out[2] = { NULL, NULL };
  call_fcn (c, t, y, 2, out, dy);
  take_hessian (c, &out[1], t, df);
  mxDestroyArray (out[1]);
  return 0;
}

int
symmex_cb_events (double t, const double *y, double *value, int *isterminal,
           int *direction, void *user)
{
  symmex_ctx *c = user;
  mxGetPr (c->eargs[1])[0] = t;
  memcpy (mxGetPr (c->eargs[2]), y, sizeof (double) * c->n);
  mxArray *out[3] = { NULL, NULL, NULL };
  symmex_call (3, out, c->nargs, c->eargs, c->ename);
  if (! out[1] || ! out[2])
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: the Events function must return three "
                       "outputs [VALUE, ISTERMINAL, DIRECTION], got %d at "
                       "t = %.15g", c->solver, out[0] ? (out[1] ? 2 : 1) : 0,
                       t);
  const double *v = symmex_checked (c, &out[0], c->nevents,
                                    "the Events function", 1, t,
                                    "VALUE of %d real element%s", c->nevents,
                                    c->nevents == 1 ? "" : "s");
  /* a NaN has no sign: no crossing could be told (and the located time
     of one next to it would be arbitrary) */
  for (int i = 0; i < c->nevents; i++)
    if (isnan (v[i]))
      mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: the Events function returned NaN in "
                         "VALUE(%d) at t = %.15g", c->solver, i + 1, t);
  memcpy (value, v, sizeof (double) * c->nevents);
  for (int k = 1; k < 3; k++)
    {
      size_t ne = mxGetNumberOfElements (out[k]);
      if (ne != 1 && ne != (size_t) c->nevents)
        symmex_checked (c, &out[k], c->nevents, "the Events function", 1, t,
                        "ISTERMINAL and DIRECTION of the size of VALUE");
      const double *w = symmex_checked (c, &out[k], ne, "the Events function",
                                        1, t, "ISTERMINAL and DIRECTION of "
                                        "the size of VALUE");
      for (int i = 0; i < c->nevents; i++)
        {
          double x = w[ne == 1 ? 0 : i];
          if (k == 1)
            isterminal[i] = x != 0;
          else if (x == 1.0 || x == -1.0 || x == 0.0)
            direction[i] = (int) x;
          else
            mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: the Events function must "
                               "return DIRECTION of -1, 0 or 1, got %s at "
                               "t = %.15g", c->solver, SYMMEX_NUM (x, "%g"),
                               t);
        }
    }
  for (int k = 0; k < 3; k++)
    mxDestroyArray (out[k]);
  return 0;
}

/* StepDensityFcn (t, y, par1, ...): a real scalar */
int
symmex_cb_density (double t, const double *y, double *rho, void *user)
{
  symmex_ctx *c = user;
  mxGetPr (c->dargs[1])[0] = t;
  memcpy (mxGetPr (c->dargs[2]), y, sizeof (double) * c->n);
  mxArray *out = NULL;
  symmex_call_cb (c, SYMMEX_CB_DENSITY, &out, c->nargs, c->dargs, c->dname,
                  "StepDensityFcn", "a real scalar");
  const double *v = symmex_checked (c, &out, 1, "StepDensityFcn", 0, t,
                                    "a real scalar");
  /* the core refuses a value that is not positive and finite */
  *rho = c->density = v[0];
  c->density_t = t;
  mxDestroyArray (out);
  return 0;
}
