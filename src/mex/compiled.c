/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* compiled.c -- a compiled FCN (symcompile): the shared object's
   functions (inst/symplectic_fcn.h) loaded and given to the core as its
   callbacks, so that no evaluation calls Octave.  The front ends pass
   the object as a struct whose field symplectic_compiled is the shared
   object's path.  dlopen counts its loads: the library is never closed,
   so that a later run (or a later dlopen of the same path) finds it
   loaded. */
#define _GNU_SOURCE
#include "symmex.h"

#include <dlfcn.h>
#include <math.h>
#include <string.h>

#define FIELD "symplectic_compiled"

typedef int (*f_fn) (double, const double *, double *, const double *);
typedef int (*fb_fn) (int, const double *, const double *, double *,
                      const double *);
typedef int (*pat_fn) (int *, int *);
typedef double (*en_fn) (double, const double *, const double *);

struct symmex_compiled_s {
  int d, npar;
  f_fn f, hess, accel;
  fb_fn batch;
  en_fn energy;
  /* the Hessian's pattern (nnz > 0 with hess) */
  int nnz, *hcol, *hrow;
  /* Df = J Hess as compressed columns: entry e is the Hessian's value
     src[e], negated where neg[e] */
  int *dcol, *drow, *src;
  char *neg;
  double *hval;
  const double *par;
  symmex_ctx *c;
};

int
symmex_compiled_arg (const mxArray *fcn)
{
  return fcn && mxIsStruct (fcn) && mxGetNumberOfElements (fcn) == 1
         && mxGetField (fcn, 0, FIELD) && mxIsChar (mxGetField (fcn, 0, FIELD));
}

void *
symmex_compiled_dlopen (const char *path, const char **why)
{
  void *lib = dlopen (path, RTLD_NOW | RTLD_LOCAL);
  *why = lib ? NULL : dlerror ();
  return lib;
}

symmex_compiled *
symmex_compiled_open (const char *who, const mxArray *fcn)
{
  char *path = mxArrayToString (mxGetField (fcn, 0, FIELD));
  const char *why;
  void *lib = symmex_compiled_dlopen (path, &why);
  if (! lib)
    mexErrMsgIdAndTxt ("symplectic:compiled", "%s: the compiled FCN %s "
                       "cannot be loaded (%s); make it again with "
                       "symcompile", who, path, why ? why : "");
  const int *abi = dlsym (lib, "symplectic_abi");
  const int *dim = dlsym (lib, "symplectic_dim");
  const int *npar = dlsym (lib, "symplectic_npar");
  symmex_compiled *k = mxCalloc (1, sizeof (symmex_compiled));
  k->f = (f_fn) dlsym (lib, "symplectic_f");
  mxFree (path);
  if (! abi || ! dim || ! npar)
    mexErrMsgIdAndTxt ("symplectic:compiled-abi", "%s: the compiled code "
                       "declares no SYMPLECTIC_SYSTEM (d, npar) (see "
                       "symplectic_fcn.h)", who);
  if (*abi != 1)
    mexErrMsgIdAndTxt ("symplectic:compiled-abi", "%s: the compiled code "
                       "was written for version %d of symplectic_fcn.h, "
                       "this package's is 1", who, *abi);
  if (*dim < 1 || *npar < 0)
    mexErrMsgIdAndTxt ("symplectic:compiled-abi", "%s: SYMPLECTIC_SYSTEM "
                       "(d, npar) needs d >= 1 and npar >= 0, got (%d, %d)",
                       who, *dim, *npar);
  if (! k->f)
    mexErrMsgIdAndTxt ("symplectic:compiled-abi", "%s: the compiled code "
                       "defines no function symplectic_f (t, y, dy, par)",
                       who);
  k->d = *dim;
  k->npar = *npar;
  k->batch = (fb_fn) dlsym (lib, "symplectic_f_batch");
  k->hess = (f_fn) dlsym (lib, "symplectic_hess");
  k->accel = (f_fn) dlsym (lib, "symplectic_accel");
  k->energy = (en_fn) dlsym (lib, "symplectic_energy");
  pat_fn pat = (pat_fn) dlsym (lib, "symplectic_hess_pattern");
  const int n = 2 * k->d;
  if (k->hess && ! pat)
    k->hess = NULL;
  if (! k->hess)
    return k;
  k->nnz = pat (NULL, NULL);
  if (k->nnz < 0 || k->nnz > n * n)
    mexErrMsgIdAndTxt ("symplectic:compiled", "%s: symplectic_hess_pattern "
                       "gives %d entries for a %dx%d Hessian", who, k->nnz,
                       n, n);
  k->hcol = mxMalloc (sizeof (int) * (n + 1));
  k->hrow = mxMalloc (sizeof (int) * (k->nnz + 1));
  k->hval = mxMalloc (sizeof (double) * (k->nnz + 1));
  pat (k->hcol, k->hrow);
  int ok = k->hcol[0] == 0 && k->hcol[n] == k->nnz;
  for (int j = 0; ok && j < n; j++)
    for (int e = k->hcol[j]; ok && e < k->hcol[j + 1]; e++)
      ok = k->hcol[j + 1] >= k->hcol[j] && k->hrow[e] >= 0 && k->hrow[e] < n
           && (e == k->hcol[j] || k->hrow[e] > k->hrow[e - 1]);
  if (! ok)
    mexErrMsgIdAndTxt ("symplectic:compiled", "%s: symplectic_hess_pattern "
                       "is not a pattern of compressed columns (colptr from "
                       "0 to nnz, rows increasing in 0..%d)", who, n - 1);
  /* Df's column j: the Hessian's p rows (as q rows), then its q rows
     negated (as p rows), each in increasing order */
  k->dcol = mxMalloc (sizeof (int) * (n + 1));
  k->drow = mxMalloc (sizeof (int) * (k->nnz + 1));
  k->src = mxMalloc (sizeof (int) * (k->nnz + 1));
  k->neg = mxMalloc (k->nnz + 1);
  int e = 0;
  for (int j = 0; j < n; j++)
    {
      k->dcol[j] = e;
      for (int pass = 0; pass < 2; pass++)
        for (int s = k->hcol[j]; s < k->hcol[j + 1]; s++)
          {
            const int r = k->hrow[s];
            if ((pass == 0) != (r >= k->d))
              continue;
            k->drow[e] = r >= k->d ? r - k->d : r + k->d;
            k->src[e] = s;
            k->neg[e++] = r < k->d;
          }
    }
  k->dcol[n] = e;
  return k;
}

/* ------------------------------------------------------------ callbacks */

static void
note (symmex_compiled *k, const double *v, size_t m, double t)
{
  for (size_t i = 0; i < m; i++)
    if (! isfinite (v[i]))
      {
        k->c->nonfinite_what = "FCN";
        k->c->nonfinite_t = t;
        return;
      }
}

static int
cp_rhs (double t, const double *y, double *dy, void *user)
{
  symmex_compiled *k = ((symmex_ctx *) user)->compiled;
  const int d = k->d;
  int st;
  if (k->c->second_order)
    {
      memcpy (dy, y + d, sizeof (double) * d);
      st = k->accel (t, y, dy + d, k->par);
    }
  else
    st = k->f (t, y, dy, k->par);
  note (k, dy, 2 * d, t);
  return st;
}

int
symmex_compiled_rhs_batch (int m, const double *t, const double *y,
                           double *dy, void *user)
{
  symmex_compiled *k = ((symmex_ctx *) user)->compiled;
  const size_t n = 2 * k->d;
  int st = 0;
  if (k->batch && ! k->c->second_order)
    st = k->batch (m, t, y, dy, k->par);
  else
    for (int j = 0; j < m && st == 0; j++)
      st = cp_rhs (t[j], y + j * n, dy + j * n, user);
  note (k, dy, n * m, t[0]);
  return st;
}

int
symmex_compiled_rhs (double t, const double *y, double *dy, void *user)
{
  return cp_rhs (t, y, dy, user);
}

static int
cp_hess (symmex_compiled *k, double t, const double *y)
{
  int st = k->hess (t, y, k->hval, k->par);
  for (int e = 0; e < k->nnz; e++)
    if (! isfinite (k->hval[e]))
      {
        k->c->nonfinite_what = "the compiled Hessian";
        k->c->nonfinite_t = t;
        break;
      }
  return st;
}

static int
cp_jac (double t, const double *y, double *df, void *user)
{
  symmex_compiled *k = ((symmex_ctx *) user)->compiled;
  const int n = 2 * k->d;
  int st = cp_hess (k, t, y);
  memset (df, 0, sizeof (double) * n * n);
  for (int j = 0; j < n; j++)
    for (int e = k->dcol[j]; e < k->dcol[j + 1]; e++)
      {
        const double v = k->hval[k->src[e]];
        df[k->drow[e] + (size_t) j * n] = k->neg[e] ? -v : v;
      }
  return st;
}

static int
cp_rhs_jac (double t, const double *y, double *dy, double *df, void *user)
{
  int st = cp_rhs (t, y, dy, user);
  return st ? st : cp_jac (t, y, df, user);
}

static int
cp_jac_csc (double t, const double *y, sym_csc *df, void *user)
{
  symmex_compiled *k = ((symmex_ctx *) user)->compiled;
  const int n = 2 * k->d;
  int st = cp_hess (k, t, y);
  if (sym_csc_reserve (df, k->nnz))
    return SYM_ENOMEM;
  df->n = n;
  memcpy (df->colptr, k->dcol, sizeof (int) * (n + 1));
  memcpy (df->rowind, k->drow, sizeof (int) * k->nnz);
  for (int e = 0; e < k->nnz; e++)
    {
      const double v = k->hval[k->src[e]];
      df->val[e] = k->neg[e] ? -v : v;
    }
  df->nnz = k->nnz;
  return st;
}

static int
cp_rhs_jac_csc (double t, const double *y, double *dy, sym_csc *df,
                void *user)
{
  int st = cp_rhs (t, y, dy, user);
  return st ? st : cp_jac_csc (t, y, df, user);
}

/* ------------------------------------------------------------ the run */

/* The Hessian goes sparse where that pays: a large n and few entries */
int
symmex_compiled_sparse (const symmex_compiled *k)
{
  const double n = 2.0 * k->d;
  return k->hess && n >= 64 && k->nnz <= n * n / 16;
}

void
symmex_compiled_problem (symmex_ctx *c, const symmex_args *a,
                         symmex_opts *o, int need_jac)
{
  symmex_compiled *k = symmex_compiled_open (c->solver, a->fcn);
  c->compiled = k;
  k->c = c;
  if (2 * k->d != c->n)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: the compiled FCN has d = %d "
                       "(y of %d components), but Y0 has %d %s", c->solver,
                       k->d, 2 * k->d, c->n,
                       c->members > 1 ? "rows" : "elements");
  if (c->second_order && ! k->accel)
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: SecondOrder needs the "
                       "acceleration, and the compiled FCN has none "
                       "(symplectic_accel)", c->solver);
  /* the parameters: PAR1, a real vector of npar elements */
  const mxArray *par = c->nextra > 0 ? c->extra[0] : NULL;
  char buf[64];
  if (c->nextra > 1 || (k->npar == 0 && par && ! mxIsEmpty (par))
      || (k->npar > 0 && (! par || ! mxIsDouble (par) || mxIsComplex (par)
                          || mxIsSparse (par)
                          || mxGetNumberOfElements (par) != (size_t) k->npar)))
    mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: the compiled FCN takes %s, got "
                       "%s", c->solver, k->npar == 0 ? "no parameters"
                       : "its parameters as PAR1, a real vector of "
                         "SYMPLECTIC_SYSTEM's npar elements",
                       c->nextra > 1 ? "more than one PAR"
                       : par ? symmex_describe (par, buf, sizeof buf)
                       : "none");
  if (k->npar > 0)
    {
      const double *p = mxGetPr (par);
      for (int i = 0; i < k->npar; i++)
        if (! isfinite (p[i]))
          mexErrMsgIdAndTxt (SYMMEX_BADARG, "%s: PAR1 must be finite, "
                             "element %d is %s", c->solver, i + 1,
                             SYMMEX_NUM (p[i], "%g"));
      k->par = p;
    }
  /* f at (t0, y0), as an Octave FCN is probed */
  double *f0 = mxMalloc (sizeof (double) * c->n);
  int st = cp_rhs (a->tspan[0], a->y0, f0, c);
  c->probe_calls = c->probe_states = 1;
  for (int i = 0; i < c->n; i++)
    if (! isfinite (f0[i]))
      mexErrMsgIdAndTxt ("symplectic:nonfinite", "%s: FCN returned %s "
                         "(element %d) at t = %.15g, the initial point",
                         c->solver, SYMMEX_NUM (f0[i], "%g"),
                         i + 1 - (c->second_order ? k->d : 0), a->tspan[0]);
  if (st < 0)
    mexErrMsgIdAndTxt ("symplectic:compiled", "%s: the compiled FCN "
                       "returned the status %d at t = %.15g, the initial "
                       "point", c->solver, st, a->tspan[0]);
  mxFree (f0);
  if (! need_jac)
    return;
  if (o->jacobian && ! symmex_is_function (o->jacobian))
    c->jac_source = JAC_MATRIX;
  else if (o->jacobian)
    c->jac_source = JAC_FCN;
  else if (o->hessfcn)
    c->jac_source = JAC_HESSFCN;
  else
    c->jac_source = k->hess ? JAC_COMPILED : JAC_FD;
  if (c->jac_source == JAC_FCN || c->jac_source == JAC_HESSFCN)
    {
      c->jargs = mxCalloc (c->nargs, sizeof (mxArray *));
      memcpy (c->jargs, c->args, sizeof (mxArray *) * c->nargs);
      c->jargs[0] = (mxArray *) (o->jacobian ? o->jacobian : o->hessfcn);
      c->jargs[1] = mxCreateDoubleScalar (0);
      c->jargs[2] = mxCreateDoubleMatrix (c->n, 1, mxREAL);
      symmex_direct_name (c->jargs[0], c->jname, sizeof c->jname);
    }
  /* JPattern from the Hessian's pattern, when none was given */
  if (k->hess && o->jp_ncolors == 0)
    {
      o->jp_colptr = k->dcol;
      o->jp_rowind = k->drow;
      o->jp_color = mxMalloc (sizeof (int) * (c->n + 1));
      o->jp_ncolors = sym_pattern_colors (c->n, k->dcol, k->drow,
                                          o->jp_color);
      if (o->jp_ncolors < 0)
        o->jp_ncolors = 0;
      o->jp_sparse = symmex_compiled_sparse (k);
    }
}

void
symmex_compiled_system (symmex_ctx *c, sym_system *sys)
{
  sys->rhs = cp_rhs;
  /* as for an Octave FCN: the steps then make the same choices (a batch
     makes finite differences cheap, and changes when Df is renewed) */
  sys->rhs_batch = c->o->vectorized ? symmex_compiled_rhs_batch : NULL;
  if (c->jac_source == JAC_COMPILED)
    {
      sys->jac = cp_jac;
      sys->rhs_jac = cp_rhs_jac;
    }
}

int
symmex_compiled_sparse_source (const symmex_ctx *c)
{
  return c->jac_source == JAC_COMPILED && symmex_compiled_sparse (c->compiled);
}

void
symmex_compiled_use_sparse (symmex_ctx *c, sym_system *sys)
{
  if (c->jac_source != JAC_COMPILED)
    return;
  sys->jac_csc = cp_jac_csc;
  sys->rhs_jac_csc = cp_rhs_jac_csc;
}

/* ------------------------------------------------------------ Octave calls */

int
symmex_compiled_dim (const symmex_compiled *k)
{
  return k->d;
}

/* For __symcompiled__: f (or the acceleration) at the m columns of y,
   the Hessian, H.  par: NULL or npar values (checked by the caller). */
int
symmex_compiled_eval (symmex_compiled *k, int what, int m, const double *t,
                      const double *y, const double *par, double *out)
{
  const size_t n = 2 * k->d;
  int st = 0;
  for (int j = 0; j < m && st == 0; j++)
    switch (what)
      {
      case 0:
        st = k->f (t[j], y + j * n, out + j * n, par);
        break;
      case 1:
        if (! k->accel)
          return -100;
        st = k->accel (t[j], y + j * k->d, out + j * k->d, par);
        break;
      case 2:
        if (! k->energy)
          return -100;
        out[j] = k->energy (t[j], y + j * n, par);
        break;
      default:
        if (! k->hess)
          return -100;
        st = k->hess (t[j], y + j * n, out, par);
        break;
      }
  return st;
}

void
symmex_compiled_pattern (const symmex_compiled *k, int *nnz,
                         const int **colptr, const int **rowind)
{
  *nnz = k->hess ? k->nnz : -1;
  *colptr = k->hcol;
  *rowind = k->hrow;
}

int
symmex_compiled_npar (const symmex_compiled *k)
{
  return k->npar;
}

int
symmex_compiled_has (const symmex_compiled *k, int what)
{
  switch (what)
    {
    case 0: return k->batch != NULL;
    case 1: return k->accel != NULL;
    case 2: return k->energy != NULL;
    default: return k->hess != NULL;
    }
}
