/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* run.c -- one call of a solver: arguments, the user's functions as C
   callbacks of the core, the output sink, warnings, Stats and outputs.

   Every allocation is mxMalloc'd (the core's allocator hook points there)
   so that an error raised inside a user's function, which leaves this MEX
   function through mexCallMATLAB without coming back, leaks nothing:
   Octave frees it all when the call ends. */
#include "symmex.h"

#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

static const char *BADARG = "Octave:invalid-input-arg";
#define MAXBATCH 64

typedef struct {
  const char *solver;
  int d, n;
  /* feval arguments: {fcn, t, y, extras...}; t and y are reused */
  mxArray **args;
  int nargs;
  mxArray *batch_t[MAXBATCH + 1], *batch_y[MAXBATCH + 1];
  int big_k;                 /* the k of batch_t[0], batch_y[0] */
  /* Jacobian */
  int jac_source;
  mxArray **jargs;           /* {handle, t, y, extras...} for Jacobian/Hess */
  const double *jac_const;
  /* events */
  mxArray **eargs;
  int nevents;
  /* output */
  const symmex_opts *o;
  mxArray **oargs;           /* {OutputFcn, t, y, flag, extras...} */
  int nextra;
  const mxArray **extra;
  double *tbuf, *ybuf;
  size_t nrows, cap;
  double *te, *ye;
  int *ie;
  size_t nev, evcap;
  int output_stopped;
  /* the names the user's functions are called by, or "" (see
     call_user) */
  char fname[64], jname[64], ename[64], oname[64];
  const char *nonfinite_what;  /* which function last returned NaN/Inf */
  double nonfinite_t;          /* and at which t */
} ctx_t;

/* ------------------------------------------------------------ helpers */

static mxArray *
col (int n)
{
  return mxCreateDoubleMatrix (n, 1, mxREAL);
}

/* a's double form (a new array) */
static mxArray *
to_double (const mxArray *a)
{
  mxArray *in[1] = { (mxArray *) a }, *out[1] = { NULL };
  mexCallMATLAB (1, out, 1, in, "double");
  return out[0];
}

/* A value returned by a user's function, replaced in *pa by its full
   form (sparse values are taken as full), or by its double form (a
   numeric, logical or char value); the replaced array is destroyed. */
static mxArray *
take_full (mxArray **pa)
{
  mxArray *a = *pa;
  if (a && mxIsSparse (a))
    {
      *pa = symmex_full (a);
      mxDestroyArray (a);
    }
  return *pa;
}

static mxArray *
take_double (mxArray **pa)
{
  mxArray *a = *pa;
  if (! mxIsDouble (a))
    {
      *pa = to_double (a);
      mxDestroyArray (a);
    }
  return *pa;
}

/* Check a value returned by a user's function: real numeric with k
   elements (or logical, when logical_ok: the Events function's VALUE and
   flags, as ode45 takes them); convert it to double if needed.  Returns a
   double array. */
static const double *
checked_values (ctx_t *c, mxArray **pa, size_t k, const char *what,
                int logical_ok, double t, const char *expect_fmt, ...)
{
  mxArray *a = take_full (pa);
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
        mexErrMsgIdAndTxt (BADARG, "%s: %s returned a complex value at "
                           "t = %.17g; expected %s", c->solver, what, t,
                           expect);
      mexErrMsgIdAndTxt (BADARG, "%s: %s must return %s, got %s at "
                         "t = %.17g", c->solver, what, expect,
                         a ? symmex_describe (a, buf, sizeof buf)
                         : "nothing", t);
    }
  return mxGetPr (take_double (pa));
}

/* The core finds NaN/Inf itself (and retries with a smaller step); this
   only remembers which of the user's functions gave them, for the
   warning when the run cannot go on. */
static void
note_nonfinite (ctx_t *c, const double *v, size_t k, const char *what,
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
   call by name skips feval's own call: measured 1.6 us less per call (of
   13 us) on Kepler's fcn (bench B0).  A call by name looks the name up
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
static void
direct_name (const mxArray *f, char *name, size_t len)
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
static void
call_user (int nout, mxArray **out, int nargs, mxArray **args,
           const char *name)
{
  if (name[0])
    mexCallMATLAB (nout, out, nargs - 1, args + 1, name);
  else
    mexCallMATLAB (nout, out, nargs, args, "feval");
}

/* ------------------------------------------------------------ callbacks */

static int
cb_rhs (double t, const double *y, double *dy, void *user)
{
  ctx_t *c = user;
  mxArray *out[1] = { NULL };
  mxGetPr (c->args[1])[0] = t;
  memcpy (mxGetPr (c->args[2]), y, sizeof (double) * c->n);
  call_user (1, out, c->nargs, c->args, c->fname);
  const double *v = checked_values (c, out, c->n, "FCN", 0, t,
                                    "a vector of %d real elements", c->n);
  note_nonfinite (c, v, c->n, "FCN", t);
  memcpy (dy, v, sizeof (double) * c->n);
  mxDestroyArray (out[0]);
  return 0;
}

/* Vectorized: fcn (t_row, Y) with Y n-by-k returns n-by-k. */
static int
cb_rhs_batch (int k, const double *t, const double *y, double *dy,
              void *user)
{
  ctx_t *c = user;
  /* argument arrays kept for each k up to MAXBATCH, and for the last
     larger k (finite differences batch 2d Nodes states) */
  int slot = k <= MAXBATCH ? k : 0;
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
  if (! c->batch_t[slot])
    {
      c->batch_t[slot] = mxCreateDoubleMatrix (1, k, mxREAL);
      c->batch_y[slot] = mxCreateDoubleMatrix (c->n, k, mxREAL);
    }
  mxArray *t1 = c->args[1], *y1 = c->args[2];
  c->args[1] = c->batch_t[slot];
  c->args[2] = c->batch_y[slot];
  memcpy (mxGetPr (c->args[1]), t, sizeof (double) * k);
  memcpy (mxGetPr (c->args[2]), y, sizeof (double) * c->n * k);
  mxArray *out[1] = { NULL };
  call_user (1, out, c->nargs, c->args, c->fname);
  c->args[1] = t1;
  c->args[2] = y1;
  static const char *expect = "a %dx%d real matrix (Vectorized)";
  if (out[0] && ! symmex_is_size (out[0], c->n, k))
    checked_values (c, out, (size_t) -1, "FCN", 0, t[0], expect, c->n, k);
  const double *v = checked_values (c, out, (size_t) c->n * k, "FCN", 0,
                                    t[0], expect, c->n, k);
  note_nonfinite (c, v, (size_t) c->n * k, "FCN", t[0]);
  memcpy (dy, v, sizeof (double) * c->n * k);
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
static const char *const HESS_EXPECT = "the Hessian of H, a %dx%d matrix or "
                                       "a vector of %d elements";

/* a is n-by-n, or a row or column (or not yet known to hold n^2 elements:
   checked_values says what it holds) */
static int
hessian_shape (const mxArray *a, int n)
{
  if (! a || mxGetNumberOfElements (a) != (size_t) n * n)
    return 1;
  return symmex_is_size (a, n, n) || symmex_is_vector (a);
}

/* The Hessian of H (JAC_HESSFCN, JAC_FCN2) in out[0] -> df. */
static void
take_hessian (ctx_t *c, mxArray **out, double t, double *df)
{
  int n = c->n;
  int fcn2 = c->jac_source == JAC_FCN2;
  const char *what = fcn2 ? "FCN (second output)" : "HamiltonianHessFcn";
  if (! hessian_shape (out[0], n))
    checked_values (c, out, (size_t) -1, what, 0, t, HESS_EXPECT, n, n,
                    n * n);
  const double *v = checked_values (c, out, (size_t) n * n, what, 0, t,
                                    HESS_EXPECT, n, n, n * n);
  note_nonfinite (c, v, (size_t) n * n,
                  fcn2 ? "FCN's second output (the Hessian)"
                       : "HamiltonianHessFcn", t);
  hess_to_df (c->d, v, df);
}

static int
cb_jac (double t, const double *y, double *df, void *user)
{
  ctx_t *c = user;
  int n = c->n;
  if (c->jac_source == JAC_MATRIX)
    {
      memcpy (df, c->jac_const, sizeof (double) * n * n);
      return 0;
    }
  mxGetPr (c->jargs[1])[0] = t;
  memcpy (mxGetPr (c->jargs[2]), y, sizeof (double) * n);
  mxArray *out[2] = { NULL, NULL };
  if (c->jac_source == JAC_FCN2)
    {
      call_user (2, out, c->nargs, c->jargs, c->jname);
      mxDestroyArray (out[0]);
      out[0] = out[1];
    }
  else
    call_user (1, out, c->nargs, c->jargs, c->jname);
  if (c->jac_source == JAC_FCN)
    {
      static const char *expect = "a %dx%d real matrix (df/dy)";
      if (out[0] && ! symmex_is_size (out[0], n, n))
        checked_values (c, out, (size_t) -1, "the Jacobian function", 0, t,
                        expect, n, n);
      const double *v = checked_values (c, out, (size_t) n * n,
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

/* JAC_FCN2: f and the Hessian from one call of FCN with two outputs. */
static int
cb_rhs_jac (double t, const double *y, double *dy, double *df, void *user)
{
  ctx_t *c = user;
  mxGetPr (c->args[1])[0] = t;
  memcpy (mxGetPr (c->args[2]), y, sizeof (double) * c->n);
  mxArray *out[2] = { NULL, NULL };
  call_user (2, out, c->nargs, c->args, c->fname);
  const double *v = checked_values (c, out, c->n, "FCN", 0, t,
                                    "a vector of %d real elements", c->n);
  note_nonfinite (c, v, c->n, "FCN", t);
  memcpy (dy, v, sizeof (double) * c->n);
  mxDestroyArray (out[0]);
  take_hessian (c, &out[1], t, df);
  mxDestroyArray (out[1]);
  return 0;
}

static int
cb_events (double t, const double *y, double *value, int *isterminal,
           int *direction, void *user)
{
  ctx_t *c = user;
  mxGetPr (c->eargs[1])[0] = t;
  memcpy (mxGetPr (c->eargs[2]), y, sizeof (double) * c->n);
  mxArray *out[3] = { NULL, NULL, NULL };
  call_user (3, out, c->nargs, c->eargs, c->ename);
  if (! out[1] || ! out[2])
    mexErrMsgIdAndTxt (BADARG, "%s: the Events function must return three "
                       "outputs [VALUE, ISTERMINAL, DIRECTION], got %d at "
                       "t = %.17g", c->solver, out[0] ? (out[1] ? 2 : 1) : 0,
                       t);
  const double *v = checked_values (c, &out[0], c->nevents,
                                    "the Events function", 1, t,
                                    "VALUE of %d real element%s", c->nevents,
                                    c->nevents == 1 ? "" : "s");
  /* a NaN has no sign: no crossing could be told (and the located time
     of one next to it would be arbitrary) */
  for (int i = 0; i < c->nevents; i++)
    if (isnan (v[i]))
      mexErrMsgIdAndTxt (BADARG, "%s: the Events function returned NaN in "
                         "VALUE(%d) at t = %.17g", c->solver, i + 1, t);
  memcpy (value, v, sizeof (double) * c->nevents);
  for (int k = 1; k < 3; k++)
    {
      size_t ne = mxGetNumberOfElements (out[k]);
      if (ne != 1 && ne != (size_t) c->nevents)
        checked_values (c, &out[k], c->nevents, "the Events function", 1, t,
                        "ISTERMINAL and DIRECTION of the size of VALUE");
      const double *w = checked_values (c, &out[k], ne, "the Events function",
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
            mexErrMsgIdAndTxt (BADARG, "%s: the Events function must "
                               "return DIRECTION of -1, 0 or 1, got %s at "
                               "t = %.17g", c->solver, SYMMEX_NUM (x, "%g"),
                               t);
        }
    }
  for (int k = 0; k < 3; k++)
    mxDestroyArray (out[k]);
  return 0;
}

/* OutputFcn's stop flag as `if (stop)` takes it (as ode45 does): true
   when all its elements are nonzero, false when empty; NaN and values
   that are not logical, char or real numeric are errors. */
static int
stop_flag (ctx_t *c, mxArray **pa, double t)
{
  char buf[64];
  if (mxIsEmpty (*pa))
    return 0;
  mxArray *a = take_full (pa);
  if (! (mxIsNumeric (a) || mxIsLogical (a) || mxIsChar (a))
      || mxIsComplex (a))
    mexErrMsgIdAndTxt (BADARG, "%s: OutputFcn must return a logical or "
                       "real numeric stop flag, got %s at t = %.17g",
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
  const double *v = mxGetPr (take_double (pa));
  int stop = 1;
  for (size_t i = 0; i < k; i++)
    {
      if (isnan (v[i]))
        mexErrMsgIdAndTxt (BADARG, "%s: OutputFcn returned NaN as its stop "
                           "flag at t = %.17g", c->solver, t);
      if (v[i] == 0.0)
        stop = 0;
    }
  return stop;
}

/* OutputFcn (t, y(OutputSel), flag, extras...): returns its stop flag. */
static int
call_outputfcn (ctx_t *c, const double *t, int nt, const double *y,
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
      ya = mxCreateDoubleMatrix (nsel, 1, mxREAL);
      for (int i = 0; i < nsel; i++)
        mxGetPr (ya)[i] = y[o->outputsel ? o->outputsel[i] : i];
    }
  c->oargs[1] = ta;
  c->oargs[2] = ya;
  c->oargs[3] = mxCreateString (flag);
  int nout = strcmp (flag, "") == 0 ? 1 : 0;
  mxArray *out[1] = { NULL };
  call_user (nout, out, c->nargs + 1, c->oargs, c->oname);
  int stop = nout && out[0] ? stop_flag (c, out, t ? t[0] : NAN) : 0;
  if (out[0])
    mxDestroyArray (out[0]);
  mxDestroyArray (c->oargs[3]);
  mxDestroyArray (ya);
  mxDestroyArray (ta);
  return stop;
}

static int
sink_row (double t, const double *y, void *user)
{
  ctx_t *c = user;
  if (c->nrows == c->cap)
    {
      c->cap = c->cap ? 2 * c->cap : 256;
      c->tbuf = mxRealloc (c->tbuf, sizeof (double) * c->cap);
      c->ybuf = mxRealloc (c->ybuf, sizeof (double) * c->cap * c->n);
    }
  c->tbuf[c->nrows] = t;
  memcpy (c->ybuf + c->nrows * c->n, y, sizeof (double) * c->n);
  c->nrows++;
  if (c->o->outputfcn && c->nrows > 1)
    {
      if (call_outputfcn (c, &t, 1, y, ""))
        {
          c->output_stopped = 1;
          return 1;
        }
    }
  return 0;
}

static int
sink_event (double te, const double *ye, int ie, void *user)
{
  ctx_t *c = user;
  if (c->nev == c->evcap)
    {
      c->evcap = c->evcap ? 2 * c->evcap : 16;
      c->te = mxRealloc (c->te, sizeof (double) * c->evcap);
      c->ye = mxRealloc (c->ye, sizeof (double) * c->evcap * c->n);
      c->ie = mxRealloc (c->ie, sizeof (int) * c->evcap);
    }
  c->te[c->nev] = te;
  memcpy (c->ye + c->nev * c->n, ye, sizeof (double) * c->n);
  c->ie[c->nev] = ie;
  c->nev++;
  return 0;
}

/* ------------------------------------------------------------ arguments */

static int
is_plain_numeric (const mxArray *a)
{
  return mxIsNumeric (a) && ! mxIsComplex (a);
}

/* ------------------------------------------------------------ outputs */

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
event_outputs (const ctx_t *c, int n, mxArray **te, mxArray **ye,
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
    default: return "none (explicit steps)";
    }
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

/* ------------------------------------------------------------ the run */

void
symmex_run (const symmex_solver *solver, int nlhs, mxArray *plhs[],
            int nrhs, const mxArray *prhs[])
{
  const char *name = solver->name;
  char buf[64];
  sym_set_allocator (mxMalloc, mxFree);

  if (nrhs < 3)
    mexErrMsgIdAndTxt ("Octave:invalid-fun-call",
                       "%s: expected %s (FCN, TSPAN, Y0) or %s (FCN, TSPAN, "
                       "Y0, OPTS, P1, ...), got %d arguments", name, name,
                       name, nrhs);
  if (nlhs > 5)
    mexErrMsgIdAndTxt ("Octave:invalid-fun-call",
                       "%s: at most 5 outputs [T, Y, TE, YE, IE]", name);

  /* FCN */
  const mxArray *fcn = prhs[0];
  if (! symmex_is_function (fcn))
    mexErrMsgIdAndTxt (BADARG, "%s: FCN must be a function handle or the "
                       "name of a function, got %s", name,
                       symmex_describe_fn (fcn, buf, sizeof buf));

  /* TSPAN */
  const mxArray *ts = symmex_full (prhs[1]);
  if (! is_plain_numeric (ts) || mxGetNumberOfElements (ts) < 2
      || ! symmex_is_vector (ts))
    mexErrMsgIdAndTxt (BADARG, "%s: TSPAN must be a real vector [T0, TF] or "
                       "[T0, T1, ..., TF] of at least 2 elements, got %s",
                       name, symmex_describe (ts, buf, sizeof buf));
  mxArray *tsd = mxIsDouble (ts) ? NULL : to_double (ts);
  const double *tspan = mxGetPr (tsd ? tsd : ts);
  int ntspan = (int) mxGetNumberOfElements (ts);
  for (int i = 0; i < ntspan; i++)
    if (! isfinite (tspan[i]))
      mexErrMsgIdAndTxt (BADARG, "%s: TSPAN must be finite, element %d is "
                         "%s", name, i + 1, SYMMEX_NUM (tspan[i], "%g"));
  double dir = tspan[1] > tspan[0] ? 1 : -1;
  for (int i = 1; i < ntspan; i++)
    if (! (dir * (tspan[i] - tspan[i - 1]) > 0))
      mexErrMsgIdAndTxt (BADARG, "%s: TSPAN must be strictly monotonic "
                         "(elements %d and %d are %.17g and %.17g)", name, i,
                         i + 1, tspan[i - 1], tspan[i]);
  if (! isfinite (tspan[ntspan - 1] - tspan[0]))
    mexErrMsgIdAndTxt (BADARG, "%s: TSPAN must span a finite interval, "
                       "TF - T0 = %g - (%g) overflows", name,
                       tspan[ntspan - 1], tspan[0]);

  /* Y0 */
  const mxArray *y0a = symmex_full (prhs[2]);
  if (! is_plain_numeric (y0a) || mxIsEmpty (y0a) || ! symmex_is_vector (y0a))
    {
      if (mxIsComplex (y0a))
        mexErrMsgIdAndTxt (BADARG, "%s: Y0 must be real, got a complex "
                           "value", name);
      mexErrMsgIdAndTxt (BADARG, "%s: Y0 must be a non-empty real numeric "
                         "vector [q0; p0], got %s", name,
                         symmex_describe (y0a, buf, sizeof buf));
    }
  int n = (int) mxGetNumberOfElements (y0a);
  if (n % 2)
    mexErrMsgIdAndTxt (BADARG, "%s: Y0 must have an even number of elements "
                       "[q; p], got %d", name, n);
  mxArray *y0d = mxIsDouble (y0a) ? NULL : to_double (y0a);
  const double *y0 = mxGetPr (y0d ? y0d : y0a);
  for (int i = 0; i < n; i++)
    if (! isfinite (y0[i]))
      mexErrMsgIdAndTxt (BADARG, "%s: Y0 must be finite, element %d is %s",
                         name, i + 1, SYMMEX_NUM (y0[i], "%g"));

  /* OPTS */
  symmex_opts o;
  symmex_parse_options (name, nrhs > 3 ? prhs[3] : NULL, n, solver->is_spvi,
                        &o);

  /* fixed steps: a number of steps that fits a long, and steps that move
     t (the core computes t0 + k*h) */
  if (o.h_fixed > 0 || o.nsteps_fixed > 0)
    {
      double t0 = tspan[0], t1 = tspan[ntspan - 1];
      double span = fabs (t1 - t0);
      double h = o.h_fixed > 0 ? o.h_fixed : span / o.nsteps_fixed;
      double tmax = fmax (fabs (t0), fabs (t1));
      if (o.h_fixed > 0 && o.nsteps_fixed > 0)
        {
          double tend = t0 + dir * h * (double) o.nsteps_fixed;
          if (! isfinite (tend))
            mexErrMsgIdAndTxt (BADARG, "%s: TimeStepNumber*TimeStepSize = "
                               "%ld*%g overflows; expected a finite end "
                               "time", name, o.nsteps_fixed, h);
          tmax = fmax (tmax, fabs (tend));
        }
      else if (o.h_fixed > 0 && span / h > 1e12)
        mexErrMsgIdAndTxt (BADARG, "%s: TimeStepSize = %g needs %.3g steps "
                           "to cover TSPAN, more than the 1e12 allowed; "
                           "expected TimeStepSize >= %g", name, h, span / h,
                           span / 1e12);
      if (h < 8 * DBL_EPSILON * tmax)
        mexErrMsgIdAndTxt (BADARG, "%s: the fixed step %g is below the "
                           "round-off of t (|t| up to %g); expected a step "
                           ">= %g", name, h, tmax, 8 * DBL_EPSILON * tmax);
    }

  /* adaptive steps: a MaxStep that would take more than 1e12 steps is
     refused as such a TimeStepSize is (near t = 0 the least step, 16 ulps
     of t, does not bound it: the run would not end), and RelTol is at
     least 100 eps, as in other ode45 codes (below it the error test asks
     for steps that round-off cannot give: at t0 = 0 odeSE and odeSV took
     steps of 1e-148 at RelTol 1e-300) */
  if (! (o.h_fixed > 0 || o.nsteps_fixed > 0))
    {
      double span = fabs (tspan[ntspan - 1] - tspan[0]);
      if (o.hmax > 0 && span / o.hmax > 1e12)
        mexErrMsgIdAndTxt (BADARG, "%s: MaxStep = %g needs %.3g steps to "
                           "cover TSPAN, more than the 1e12 allowed; "
                           "expected MaxStep >= %g", name, o.hmax,
                           span / o.hmax, span / 1e12);
      if (o.rtol < 100 * DBL_EPSILON)
        {
          mexWarnMsgIdAndTxt ("symplectic:tolerance", "%s: RelTol = %g is "
                              "below 100*eps; %g is used", name, o.rtol,
                              100 * DBL_EPSILON);
          o.rtol = 100 * DBL_EPSILON;
        }
    }

  /* the context and the reused argument arrays of feval */
  ctx_t *c = mxCalloc (1, sizeof (ctx_t));
  c->solver = name;
  c->n = n;
  c->d = n / 2;
  c->o = &o;
  c->nextra = nrhs > 4 ? nrhs - 4 : 0;
  c->extra = prhs + 4;
  c->nargs = 3 + c->nextra;
  c->args = mxCalloc (c->nargs, sizeof (mxArray *));
  c->args[0] = (mxArray *) fcn;
  c->args[1] = mxCreateDoubleScalar (tspan[0]);
  c->args[2] = col (n);
  for (int i = 0; i < c->nextra; i++)
    c->args[3 + i] = (mxArray *) c->extra[i];
  memcpy (mxGetPr (c->args[2]), y0, sizeof (double) * n);
  direct_name (fcn, c->fname, sizeof c->fname);

  /* Probe FCN at (t0, y0): its size and values, and whether it gives the
     Hessian as a second output (only when Newton will need a matrix). */
  int need_jac = ! (o.separable && ! solver->is_spvi);
  int probe_hess = need_jac && ! o.jacobian && ! o.hessfcn;
  mxArray *out[2] = { NULL, NULL };
  int have2 = 0;
  if (probe_hess)
    {
      mxArray *ex = mexCallMATLABWithTrap (2, out, c->nargs, c->args,
                                           "feval");
      if (ex)
        {
          mxDestroyArray (ex);
          out[0] = out[1] = NULL;
        }
      else if (out[1] && ! mxIsEmpty (out[1]))
        have2 = 1;
    }
  if (! out[0])
    call_user (1, out, c->nargs, c->args, c->fname);
  const double *f0 = checked_values (c, &out[0], n, "FCN", 0, tspan[0],
                                     "a vector of %d real elements", n);
  for (int i = 0; i < n; i++)
    if (! isfinite (f0[i]))
      mexErrMsgIdAndTxt ("symplectic:nonfinite", "%s: FCN returned %s "
                         "(element %d) at t = %.17g, the initial point",
                         name, SYMMEX_NUM (f0[i], "%g"), i + 1, tspan[0]);
  if (have2)
    checked_values (c, &out[1], hessian_shape (out[1], n) ? (size_t) n * n
                                : (size_t) -1, "FCN (second output)", 0,
                    tspan[0], HESS_EXPECT, n, n, n * n);

  /* the Jacobian source, in the order of precedence (README: Options) */
  c->jac_source = JAC_NONE;
  if (need_jac)
    {
      if (o.jacobian && ! symmex_is_function (o.jacobian))
        {
          c->jac_source = JAC_MATRIX;
          c->jac_const = mxGetPr (o.jacobian);
        }
      else if (o.jacobian)
        c->jac_source = JAC_FCN;
      else if (o.hessfcn)
        c->jac_source = JAC_HESSFCN;
      else if (have2)
        c->jac_source = JAC_FCN2;
      else
        c->jac_source = JAC_FD;
      if (c->jac_source != JAC_MATRIX && c->jac_source != JAC_FD)
        {
          c->jargs = mxCalloc (c->nargs, sizeof (mxArray *));
          memcpy (c->jargs, c->args, sizeof (mxArray *) * c->nargs);
          c->jargs[0] = (mxArray *) (c->jac_source == JAC_FCN ? o.jacobian
                                     : c->jac_source == JAC_HESSFCN
                                     ? o.hessfcn : fcn);
          c->jargs[1] = mxCreateDoubleScalar (0);
          c->jargs[2] = col (n);
          direct_name (c->jargs[0], c->jname, sizeof c->jname);
        }
    }

  /* Events: one call at t0 tells how many there are */
  if (o.events)
    {
      c->eargs = mxCalloc (c->nargs, sizeof (mxArray *));
      memcpy (c->eargs, c->args, sizeof (mxArray *) * c->nargs);
      c->eargs[0] = (mxArray *) o.events;
      c->eargs[1] = mxCreateDoubleScalar (tspan[0]);
      c->eargs[2] = col (n);
      memcpy (mxGetPr (c->eargs[2]), y0, sizeof (double) * n);
      mxArray *eo[3] = { NULL, NULL, NULL };
      direct_name (o.events, c->ename, sizeof c->ename);
      call_user (3, eo, c->nargs, c->eargs, c->ename);
      if (! eo[1] || ! eo[2])
        mexErrMsgIdAndTxt (BADARG, "%s: the Events function must return "
                           "three outputs [VALUE, ISTERMINAL, DIRECTION], "
                           "got %d", name, eo[0] ? (eo[1] ? 2 : 1) : 0);
      /* an empty VALUE: no events (as in ode45) */
      if (! eo[0] || ! (mxIsNumeric (eo[0]) || mxIsLogical (eo[0]))
          || mxIsComplex (eo[0]))
        mexErrMsgIdAndTxt (BADARG, "%s: the Events function must return "
                           "[VALUE, ISTERMINAL, DIRECTION] with a real "
                           "VALUE, got VALUE = %s", name,
                           eo[0] ? symmex_describe (eo[0], buf, sizeof buf)
                           : "nothing");
      c->nevents = (int) mxGetNumberOfElements (eo[0]);
      for (int k = 0; k < 3; k++)
        mxDestroyArray (eo[k]);
    }

  /* sol output: step points only, as ode45 does */
  int want_sol = nlhs == 1;
  int ntout = want_sol ? 2 : ntspan;
  double tf = tspan[ntspan - 1];

  /* OutputFcn: nargout = 0 and no OutputFcn plots with odeplot, as ode45 */
  mxArray *odeplot = NULL;
  if (nlhs == 0 && ! o.outputfcn)
    {
      odeplot = mxCreateString ("odeplot");
      o.outputfcn = odeplot;
    }
  if (o.outputfcn)
    {
      c->oargs = mxCalloc (c->nargs + 1, sizeof (mxArray *));
      c->oargs[0] = (mxArray *) o.outputfcn;
      direct_name (o.outputfcn, c->oname, sizeof c->oname);
      for (int i = 0; i < c->nextra; i++)
        c->oargs[4 + i] = (mxArray *) c->extra[i];
      call_outputfcn (c, tspan, ntspan, y0, "init");
    }

  /* the system and the run */
  sym_system sys;
  memset (&sys, 0, sizeof sys);
  sys.dim = c->d;
  sys.rhs = cb_rhs;
  sys.rhs_batch = o.vectorized ? cb_rhs_batch : NULL;
  sys.jac = (c->jac_source == JAC_FD || c->jac_source == JAC_NONE) ? NULL
            : cb_jac;
  sys.rhs_jac = c->jac_source == JAC_FCN2 ? cb_rhs_jac : NULL;
  sys.user = c;
  /* the probe: one evaluation of f (a two-output call that raised, as a
     function of one output does on its call, evaluated nothing) */
  sys.cnt.nrhs = 1;
  sys.cnt.nrhs_states = 1;

  sym_method_opts mo;
  memset (&mo, 0, sizeof mo);
  mo.q_dofs = o.q_dofs;
  mo.nodes = o.nodes;
  mo.newton_tol = o.newton_tol;
  mo.max_newton = o.max_newton;
  mo.newton_matrix = o.newton_matrix;
  mo.separable = o.separable;

  sym_driver_opts dopt;
  memset (&dopt, 0, sizeof dopt);
  dopt.t0 = tspan[0];
  dopt.tf = tf;
  dopt.tout = tspan;
  dopt.ntout = ntout;
  dopt.refine = (ntout > 2 || want_sol) ? 1 : o.refine;
  dopt.h_fixed = o.h_fixed;
  dopt.nsteps_fixed = o.nsteps_fixed;
  dopt.rtol = o.rtol;
  dopt.atol = o.atol;
  dopt.atol_len = o.atol_len;
  dopt.norm_control = o.norm_control;
  dopt.h0 = o.h0;
  dopt.hmax = o.hmax;
  dopt.max_steps = o.max_steps;
  dopt.nevents = c->nevents;
  dopt.events = c->nevents > 0 ? cb_events : NULL;
  /* odeSPVI's long steps: the events function also at Nodes points
     inside each step (see its help) */
  dopt.event_samples = solver->type == sym_step_spvi ? o.nodes : 0;
  dopt.event_user = c;
  dopt.event_out = sink_event;
  dopt.output = sink_row;
  dopt.output_user = c;

  if (ntout > 2)
    {
      double tend = sym_fixed_end (&dopt);
      if (dir * (tf - tend) > 0)
        mexWarnMsgIdAndTxt ("symplectic:tspan-beyond-end", "%s: "
                            "TimeStepNumber*TimeStepSize ends at t = %g; "
                            "no output for TSPAN beyond that", name, tend);
    }

  double treached = tspan[0];
  int status = sym_integrate (solver->type, &sys, &mo, &dopt, y0, &treached);

  if (o.outputfcn)
    call_outputfcn (c, NULL, 0, NULL, "done");

  /* a run that could not go on: warn, and return what was computed */
  double tlast = c->nrows ? c->tbuf[c->nrows - 1] : tspan[0];
  switch (status)
    {
    case SYM_DONE:
    case SYM_STOP_EVENT:
      break;
    case SYM_STOP_OUTPUT:
      {
        /* the events of a step are found before its rows go out: those
           after the row where OutputFcn stopped are dropped, so that, as
           in ode45, no returned event lies beyond t(end) */
        while (c->nev > 0 && dir * (c->te[c->nev - 1] - tlast) > 0)
          c->nev--;
        /* a stop on the last row ends nothing early: no warning */
        if (tlast != tspan[ntspan - 1])
          mexWarnMsgIdAndTxt ("symplectic:output-stop", "%s: OutputFcn "
                              "asked to stop at t = %.17g; returning the "
                              "solution up to there", name, tlast);
      }
      break;
    case SYM_ENEWTON:
      {
        /* a NaN/Inf matrix also ends as a Newton failure: say so */
        char why[160] = "";
        if (c->nonfinite_what && strcmp (c->nonfinite_what, "FCN") != 0)
          snprintf (why, sizeof why, " (%s returned NaN or Inf at "
                    "t = %.17g)", c->nonfinite_what, c->nonfinite_t);
        /* odeSPVI's pairs n - 1 > m: their extra modes of q are fixed
           only by d2H/dq2 (singular Newton matrices where it vanishes,
           whatever the step) */
        int degenerate = o.q_dofs - 1 > o.nodes && ! why[0];
        if (degenerate)
          snprintf (why, sizeof why, " (Q_DoFs - 1 > Nodes: such pairs "
                    "are degenerate where d2H/dq2 vanishes or is small; "
                    "Q_DoFs <= Nodes + 1 is not)");
        mexWarnMsgIdAndTxt ("symplectic:newton-failed", "%s: Newton's "
                            "method did not converge at t = %.17g %s%s; "
                            "returning the solution up to t = %.17g", name,
                            treached, (o.h_fixed > 0 || o.nsteps_fixed > 0)
                            ? (degenerate ? "with the fixed step"
                               : "with the fixed step (try a smaller "
                                 "TimeStepSize)")
                            : "even with the smallest step", why, tlast);
      }
      break;
    case SYM_ENONFINITE:
      mexWarnMsgIdAndTxt ("symplectic:nonfinite", "%s: %s returned NaN or "
                          "Inf near t = %.17g and a smaller step did not "
                          "help; returning the solution up to t = %.17g",
                          name, c->nonfinite_what ? c->nonfinite_what
                          : "FCN", sys.fail_t, tlast);
      break;
    case SYM_EOVERFLOW:
      mexWarnMsgIdAndTxt ("symplectic:nonfinite", "%s: the solution "
                          "overflowed (NaN or Inf) in the step from "
                          "t = %.17g%s; returning the solution up to "
                          "t = %.17g", name, treached,
                          (o.h_fixed > 0 || o.nsteps_fixed > 0)
                          ? " (an unstable fixed step? try a smaller "
                            "TimeStepSize)" : " even with the smallest step",
                          tlast);
      break;
    case SYM_ESTEPSIZE:
      mexWarnMsgIdAndTxt ("symplectic:step-size", "%s: the step size became "
                          "too small at t = %.17g; returning the solution up "
                          "to t = %.17g", name, treached, tlast);
      break;
    case SYM_EMAXSTEPS:
      mexWarnMsgIdAndTxt ("symplectic:max-steps", "%s: MaxSteps reached at "
                          "t = %.17g; returning the solution up to "
                          "t = %.17g", name, treached, tlast);
      break;
    case SYM_ENOMEM:
      mexErrMsgIdAndTxt ("Octave:out-of-memory", "%s: out of memory", name);
      break;
    case SYM_ECALLBACK:
      mexWarnMsgIdAndTxt ("symplectic:callback", "%s: a callback failed at "
                          "t = %.17g; returning the solution up to there",
                          name, sys.fail_t);
      break;
    default:
      mexErrMsgIdAndTxt ("symplectic:internal", "%s: internal failure (%s)",
                         name, sym_status_name (status));
    }

  /* Separable on, but f found not separable by the steps themselves */
  if (sys.sep_broken)
    mexWarnMsgIdAndTxt ("symplectic:not-separable", "%s: Separable is on, "
                        "but FCN is not of a separable H = T(p) + V(q) "
                        "without p in the forcing: %s at t = %.17g; the "
                        "explicit steps are then not the method (of lower "
                        "order, not symplectic): set Separable off", name,
                        solver->type == sym_step_se
                        ? "dH/dq changed with p at the same q"
                        : "dH/dp changed with q (or t) at the same p",
                        sys.sep_broken_t);

  /* the source of Newton's matrices, and whether it was dropped for
     finite differences after a Newton failure (sym_jac_check) */
  char jac_used[160];
  if (sys.jac_dropped)
    snprintf (jac_used, sizeof jac_used, "%s, then finite differences of "
              "FCN from t = %.17g", jac_source_name (c->jac_source),
              sys.jac_dropped_t);
  else
    snprintf (jac_used, sizeof jac_used, "%s",
              jac_source_name (c->jac_source));

  if (o.stats)
    {
      mexPrintf ("Number of successful steps: %ld\n", sys.cnt.nsteps);
      mexPrintf ("Number of failed attempts:  %ld\n", sys.cnt.nfailed);
      mexPrintf ("Number of function calls:   %ld\n", sys.cnt.nrhs);
      mexPrintf ("Number of Newton iterations: %ld\n", sys.cnt.nnewton);
      mexPrintf ("Number of Jacobian/Hessian evaluations: %ld (source: %s%s; "
                 "%ld function calls for finite differences)\n",
                 sys.cnt.njac, jac_used,
                 sys.rhs_jac && solver->is_spvi
                 ? ", calls that also give f" : "", sys.cnt.nfd);
      mexPrintf ("Number of LU decompositions: %ld\n", sys.cnt.nlu);
      mexPrintf ("Number of linear solves:     %ld\n", sys.cnt.nsolve);
    }

  /* outputs */
  if (nlhs == 0)
    return;
  if (want_sol)
    {
      int has_ev = o.events != NULL;
      const char *fields[12];
      int nf = 0;
      fields[nf++] = "x";
      fields[nf++] = "y";
      fields[nf++] = "solver";
      if (has_ev)
        {
          fields[nf++] = "xe";
          fields[nf++] = "ye";
          fields[nf++] = "ie";
        }
      fields[nf++] = "stats";
      if (solver->is_spvi)
        {
          fields[nf++] = "order";
          fields[nf++] = "Q_DoFs";
          fields[nf++] = "Nodes";
        }
      mxArray *s = mxCreateStructMatrix (1, 1, nf, fields);
      mxArray *x = mxCreateDoubleMatrix (1, c->nrows, mxREAL);
      if (c->nrows)
        memcpy (mxGetPr (x), c->tbuf, sizeof (double) * c->nrows);
      mxArray *y = mxCreateDoubleMatrix (n, c->nrows, mxREAL);
      if (c->nrows)
        memcpy (mxGetPr (y), c->ybuf, sizeof (double) * c->nrows * n);
      mxSetField (s, 0, "x", x);
      mxSetField (s, 0, "y", y);
      mxSetField (s, 0, "solver", mxCreateString (name));
      if (has_ev)
        {
          mxArray *te, *ye, *ie;
          event_outputs (c, n, &te, &ye, &ie);
          mxSetField (s, 0, "xe", te);
          mxSetField (s, 0, "ye", ye);
          mxSetField (s, 0, "ie", ie);
        }
      mxSetField (s, 0, "stats", stats_struct (&sys.cnt, jac_used));
      if (solver->is_spvi)
        {
          int nq = o.q_dofs, m = o.nodes;
          /* the order actually used: adaptive runs advance with the
             (n+1, m+1) companion of the error estimate */
          int adaptive = ! (o.h_fixed > 0 || o.nsteps_fixed > 0);
          if (adaptive)
            {
              nq++;
              m++;
            }
          int ord = 2 * (nq - 1 < 2 * m - nq + 1 ? nq - 1 : 2 * m - nq + 1);
          if (adaptive)
            {
              nq--;
              m--;
            }
          mxSetField (s, 0, "order", mxCreateDoubleScalar (ord));
          mxSetField (s, 0, "Q_DoFs", mxCreateDoubleScalar (nq));
          mxSetField (s, 0, "Nodes", mxCreateDoubleScalar (m));
        }
      plhs[0] = s;
      return;
    }
  plhs[0] = column_of (c->tbuf, c->nrows);
  if (nlhs > 1)
    plhs[1] = rows_matrix (c->ybuf, c->nrows, n);
  if (nlhs > 2)
    {
      mxArray *te, *ye, *ie;
      event_outputs (c, n, &te, &ye, &ie);
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
}
