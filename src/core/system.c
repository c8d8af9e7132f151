/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* system.c -- allocator hook, status names, and counted calls through the
   user's system (rhs, batch rhs, Jacobian or its finite differences). */
#include "sym.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static sym_alloc_fn sym_alloc_hook = malloc;
static sym_free_fn sym_free_hook = free;

void
sym_set_allocator (sym_alloc_fn alloc, sym_free_fn dealloc)
{
  sym_alloc_hook = alloc ? alloc : malloc;
  sym_free_hook = dealloc ? dealloc : free;
}

void *
sym_malloc (size_t nbytes)
{
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
  if (ptr)
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
    case SYM_STOP_OUTPUT: return "SYM_STOP_OUTPUT";
    case SYM_STOP_EVENT: return "SYM_STOP_EVENT";
    default: return status > 0 ? "SYM_RECOVERABLE" : "SYM_ECALLBACK";
    }
}

static int
all_finite (size_t n, const double *v)
{
  for (size_t i = 0; i < n; i++)
    if (! isfinite (v[i]))
      return 0;
  return 1;
}

/* A callback's own status: 0 ok, > 0 recoverable, < 0 fatal (mapped to
   SYM_ECALLBACK so the core's codes stay distinct from the user's). */
static int
callback_status (sym_system *sys, double t, int st)
{
  if (st == 0)
    return SYM_SUCCESS;
  sys->fail_t = t;
  sys->fail_status = st;
  return st > 0 ? SYM_RECOVERABLE : SYM_ECALLBACK;
}

/* A NaN or Inf in a callback's values at t: remembered, reported. */
static int
nonfinite_at (sym_system *sys, double t)
{
  sys->fail_t = t;
  sys->fail_status = SYM_NONFINITE;
  sys->fail_df = 0;
  return SYM_NONFINITE;
}

/* The same, in the user's Df (f finite) */
static int
nonfinite_df_at (sym_system *sys, double t)
{
  nonfinite_at (sys, t);
  sys->fail_df = 1;
  return SYM_NONFINITE;
}

int
sym_rhs (sym_system *sys, double t, const double *y, double *dy)
{
  int n = 2 * sys->dim;
  sys->cnt.nrhs++;
  sys->cnt.nrhs_states++;
  int st = callback_status (sys, t, sys->rhs (t, y, dy, sys->user));
  if (st)
    return st;
  return all_finite (n, dy) ? SYM_SUCCESS : nonfinite_at (sys, t);
}

int
sym_rhs_many (sym_system *sys, int k, const double *t, const double *y,
              double *dy)
{
  int n = 2 * sys->dim;
  if (sys->rhs_batch && k > 1)
    {
      sys->cnt.nrhs++;
      sys->cnt.nrhs_states += k;
      int st = callback_status (sys, t[0],
                                sys->rhs_batch (k, t, y, dy, sys->user));
      if (st)
        return st;
      for (int j = 0; j < k; j++)
        if (! all_finite (n, dy + (size_t) j * n))
          return nonfinite_at (sys, t[j]);
      return SYM_SUCCESS;
    }
  for (int j = 0; j < k; j++)
    {
      int st = sym_rhs (sys, t[j], y + (size_t) j * n, dy + (size_t) j * n);
      if (st)
        return st;
    }
  return SYM_SUCCESS;
}

#define FD_BATCH_DOUBLES ((size_t) 1 << 19)

/* The sizes of y's components at the state y that scale its difference
   steps (see sym.h): max(|y_i|, ytyp_i), and at least FD_FLOOR times the
   largest of them in y_i's half (q or p); in a half that is all zero, the
   other half's largest, or 1 if both are.  Without ytyp (a stepper driven
   from C, not by sym_integrate) a component's own size says nothing when
   it passes through zero, so all of a half take its largest size.
   FD_FLOOR: measured on two uncoupled oscillators of sizes 1 and 1e10 (or
   1e12) in q, FD_FLOOR 1e-6 takes 956 (1088) calls of fcn in adaptive
   odeSPVI, 1e-4 1010 (1489), 1e-3 1100 (3196, and a fixed step of h = 0.05
   fails); with steps from the largest size of the half (FD_FLOOR 1),
   fixed steps fail at 1e10 and the adaptive run takes 25061 calls.  A
   component that stays zero next to others of size S is then stepped by
   sqrt(eps) 1e-6 S, so its column in rows of size S is good to about
   eps / (sqrt(eps) 1e-6) = 1.5e-2, enough for Newton. */
#define FD_FLOOR 1e-6
static void
fd_sizes (const sym_system *sys, const double *y, double *size)
{
  const int d = sys->dim;
  double big[2], low[2];
  for (int i = 0; i < 2 * d; i++)
    {
      size[i] = fabs (y[i]);
      if (sys->ytyp)
        size[i] = fmax (size[i], sys->ytyp[i]);
    }
  for (int half = 0; half < 2; half++)
    {
      big[half] = 0.0;
      for (int i = half * d; i < (half + 1) * d; i++)
        big[half] = fmax (big[half], size[i]);
    }
  const double fl = sys->ytyp ? FD_FLOOR : 1.0;
  for (int half = 0; half < 2; half++)
    low[half] = big[half] > 0 ? fl * big[half]
                : big[1 - half] > 0 ? big[1 - half] : 1.0;
  for (int i = 0; i < 2 * d; i++)
    size[i] = fmax (size[i], low[i >= d]);
}

/* Forward differences at k states (columns of y, times t, f0 their f):
   df holds k n-by-n Jacobians.  The step of column c balances truncation
   (~ delta) against round-off (~ eps / delta).  With a batch callback all
   k n perturbed states go in one call, else one rhs call each; the
   results are the same.  With fout instead of f0, the k states' own f are
   evaluated too, into fout: with a batch callback in the same call as the
   perturbed states when all fit in one.  Counted in nfd (and nrhs). */
static int
jac_fd_many (sym_system *sys, int k, const double *t, const double *y,
             const double *f0, double *fout, double *df)
{
  const int n = 2 * sys->dim;
  const int batch = sys->rhs_batch != NULL;
  const size_t cols = (size_t) k * n;
  /* columns evaluated per call: all of them with a batch callback, up to
     FD_BATCH_DOUBLES values of y in one call (a chain of d = 300 at 3
     nodes has 1800 columns of 600) */
  size_t ncw = batch ? cols : 1;
  if (ncw * n > FD_BATCH_DOUBLES)
    ncw = FD_BATCH_DOUBLES / n > 0 ? FD_BATCH_DOUBLES / n : 1;
  /* the states' own f: leading columns of the one call, or a call first */
  const size_t nb = fout && batch && (cols + k) * n <= FD_BATCH_DOUBLES
                    ? (size_t) k : 0;
  long before = sys->cnt.nrhs;
  if (fout && ! nb)
    {
      int st = sym_rhs_many (sys, k, t, y, fout);
      if (st)
        return st;
      before = sys->cnt.nrhs;
    }
  if (fout)
    f0 = fout;
  double *w = sym_malloc ((2 * (ncw + nb) * n + 3 * cols + nb + n)
                          * sizeof (double));
  if (! w)
    return SYM_ENOMEM;
  double *yp = w, *fp = w + (ncw + nb) * n, *del = w + 2 * (ncw + nb) * n;
  double *tp = del + cols, *yv = tp + cols + nb;   /* yv: perturbed values */
  const double sq = sqrt (DBL_EPSILON);
  for (size_t j = 0; j < nb; j++)
    {
      memcpy (yp + j * n, y + j * n, (size_t) n * sizeof (double));
      tp[j] = t[j];
    }
  double *size = yv + cols;   /* n: the sizes of one state's components */
  int st = SYM_SUCCESS;
  /* forward steps; if f is NaN or Inf at a stepped state (a state within
     a step of the edge of f's domain), all of them once more backwards */
  for (int pass = 0; pass < 2 && (pass == 0 || st == SYM_NONFINITE);
       pass++)
    {
      st = SYM_SUCCESS;
      for (size_t c = 0; c < cols; c++)
        {
          const double *yj = y + (c / n) * n;
          int i = (int) (c % n);
          if (i == 0)
            fd_sizes (sys, yj, size);
          double d = (pass ? -sq : sq) * size[i];
          volatile double yi = yj[i] + d;   /* exact representable step */
          yv[c] = yi;
          del[c] = yi - yj[i];
          tp[nb + c] = t[c / n];
        }
      for (size_t c0 = 0; c0 < cols && ! st; c0 += ncw)
        {
          size_t c1 = c0 + ncw < cols ? c0 + ncw : cols;
          size_t lead = c0 == 0 ? nb : 0;   /* the states themselves, first */
          double *ypc = yp + lead * n, *fpc = fp + lead * n;
          for (size_t c = c0; c < c1; c++)
            {
              double *col = ypc + (c - c0) * n;
              memcpy (col, y + (c / n) * n, (size_t) n * sizeof (double));
              col[c % n] = yv[c];
            }
          st = batch ? sym_rhs_many (sys, (int) (c1 - c0 + lead),
                                     tp + nb + c0 - lead, yp, fp)
                     : sym_rhs (sys, tp[nb + c0], yp, fp);
          if (! st && lead)
            memcpy (fout, fp, lead * n * sizeof (double));
          for (size_t c = c0; c < c1 && ! st; c++)
            {
              const double *fc = fpc + (c - c0) * n, *f0j = f0 + (c / n) * n;
              double *dfc = df + (c / n) * n * n + (c % n) * n;
              for (int i = 0; i < n; i++)
                dfc[i] = (fc[i] - f0j[i]) / del[c];
            }
        }
    }
  sys->cnt.nfd += sys->cnt.nrhs - before;
  sym_free (w);
  return st;
}

static int
jac_fd (sym_system *sys, double t, const double *y, const double *f0,
        double *df)
{
  if (f0)
    return jac_fd_many (sys, 1, &t, y, f0, NULL, df);
  int n = 2 * sys->dim;
  double *fb = sym_malloc ((size_t) n * sizeof (double));
  if (! fb)
    return SYM_ENOMEM;
  long before = sys->cnt.nrhs;
  int st = sym_rhs (sys, t, y, fb);
  sys->cnt.nfd += sys->cnt.nrhs - before;
  if (! st)
    st = jac_fd_many (sys, 1, &t, y, fb, NULL, df);
  sym_free (fb);
  return st;
}

/* The first Df a run gets from the user's jac or rhs_jac (sym.h,
   SYM_JAC_GROSS), df at (t, y), with f0 = f(t, y) or NULL: compared along
   one direction with a forward difference of rhs, and dropped for finite
   differences (into df) when it is grossly too large.  A failed call of rhs returns its status,
   as in the finite differences, and leaves the probe to be made again. */
static int
jac_probe (sym_system *sys, double t, const double *y, const double *f0,
           double *df)
{
  const int n = 2 * sys->dim;
  sys->jac_probed = 1;
  double *w = sym_malloc (4 * (size_t) n * sizeof (double));
  if (! w)
    return SYM_ENOMEM;
  double *fb = w, *yp = w + n, *fp = w + 2 * n, *size = w + 3 * n;
  long before = sys->cnt.nrhs;
  int st = SYM_SUCCESS;
  if (! f0)
    {
      st = sym_rhs (sys, t, y, fb);
      f0 = fb;
    }
  /* a direction with every component of its own size (as the finite
     differences step them) and varied weights and signs, so that no
     structure of Df hides a wrong part of it */
  fd_sizes (sys, y, size);
  const double sq = sqrt (DBL_EPSILON);
  for (int i = 0; i < n; i++)
    {
      double wt = (i & 1 ? -1.0 : 1.0) * (0.5 + 0.05 * ((i * 37) % 11));
      volatile double yi = y[i] + sq * size[i] * wt;   /* exact step */
      yp[i] = yi;
    }
  /* f NaN or Inf at the stepped state (y within a step of the edge of f's
     domain): the opposite direction; NaN there too, no probe (Df is
     kept, as the finite differences could not be made either) */
  if (! st && (st = sym_rhs (sys, t, yp, fp)) == SYM_NONFINITE)
    {
      for (int i = 0; i < n; i++)
        {
          volatile double yi = y[i] - (yp[i] - y[i]);
          yp[i] = yi;
        }
      st = sym_rhs (sys, t, yp, fp);
      if (st == SYM_NONFINITE)
        {
          sys->cnt.nfd += sys->cnt.nrhs - before;
          sym_free (w);
          return SYM_SUCCESS;
        }
    }
  sys->cnt.nfd += sys->cnt.nrhs - before;
  if (st)
    {
      sys->jac_probed = 0;
      sym_free (w);
      return st;
    }
  double dif = 0.0, ref = 0.0, fbig = 0.0;
  for (int i = 0; i < n; i++)
    {
      double pred = 0.0;
      for (int j = 0; j < n; j++)
        pred += df[i + (size_t) j * n] * (yp[j] - y[j]);
      double del = fp[i] - f0[i];
      dif = fmax (dif, fabs (del - pred));
      ref = fmax (ref, fabs (del));
      fbig = fmax (fbig, fmax (fabs (f0[i]), fabs (fp[i])));
    }
  /* the difference's own round-off: f's rounding, a few ulps of f */
  ref += SYM_JAC_NOISE * DBL_EPSILON * fbig;
  if (dif > SYM_JAC_GROSS * ref)
    {
      sys->jac = NULL;
      sys->rhs_jac = NULL;
      sys->jac_dropped = 1;
      sys->jac_dropped_t = t;
      st = jac_fd (sys, t, y, f0, df);
    }
  sym_free (w);
  return st;
}

int
sym_jac (sym_system *sys, double t, const double *y, const double *f0,
         double *df)
{
  if (! sys->jac)
    return jac_fd (sys, t, y, f0, df);
  int n = 2 * sys->dim;
  sys->cnt.njac++;
  int st = callback_status (sys, t, sys->jac (t, y, df, sys->user));
  if (st)
    return st;
  if (! all_finite ((size_t) n * (size_t) n, df))
    return nonfinite_df_at (sys, t);
  return sys->jac_probed ? SYM_SUCCESS : jac_probe (sys, t, y, f0, df);
}

int
sym_rhs_jac (sym_system *sys, double t, const double *y, double *dy,
             double *df)
{
  if (! sys->rhs_jac)
    {
      int st = sym_rhs (sys, t, y, dy);
      return st ? st : sym_jac (sys, t, y, dy, df);
    }
  int n = 2 * sys->dim;
  sys->cnt.njac++;
  int st = callback_status (sys, t, sys->rhs_jac (t, y, dy, df, sys->user));
  if (st)
    return st;
  if (! all_finite (n, dy))
    return nonfinite_at (sys, t);
  if (! all_finite ((size_t) n * (size_t) n, df))
    return nonfinite_df_at (sys, t);
  return sys->jac_probed ? SYM_SUCCESS : jac_probe (sys, t, y, dy, df);
}

int
sym_jac_many (sym_system *sys, int k, const double *t, const double *y,
              const double *f0, double *df)
{
  const size_t n = 2 * (size_t) sys->dim;
  if (! sys->jac)
    return jac_fd_many (sys, k, t, y, f0, NULL, df);
  for (int j = 0; j < k; j++)
    {
      int st = sym_jac (sys, t[j], y + j * n, NULL, df + j * n * n);
      if (st)
        return st;
    }
  return SYM_SUCCESS;
}

int
sym_rhs_jac_many (sym_system *sys, int k, const double *t, const double *y,
                  double *f, double *df)
{
  if (! sys->jac)
    return jac_fd_many (sys, k, t, y, NULL, f, df);
  int st = sym_rhs_many (sys, k, t, y, f);
  return st ? st : sym_jac_many (sys, k, t, y, f, df);
}

void
sym_sep_check (sym_system *sys, double t, int k, const double *u,
               const double *v)
{
  if (sys->sep_broken)
    return;
  double big = 0.0, dif = 0.0;
  for (int i = 0; i < k; i++)
    {
      big = fmax (big, fmax (fabs (u[i]), fabs (v[i])));
      dif = fmax (dif, fabs (u[i] - v[i]));
    }
  if (dif > SYM_SEP_TOL * big)
    {
      sys->sep_broken = 1;
      sys->sep_broken_t = t;
    }
}

int
sym_jac_check (sym_system *sys, double t, const double *y, int *dropped)
{
  const size_t n = 2 * (size_t) sys->dim;
  *dropped = 0;
  if (! sys->jac && ! sys->rhs_jac)
    return SYM_SUCCESS;
  double *w = sym_malloc ((2 * n * n + n) * sizeof (double));
  if (! w)
    return SYM_ENOMEM;
  double *du = w, *dfd = w + n * n, *f = w + 2 * n * n;
  sym_jac_fn jac = sys->jac;
  sym_rhs_jac_fn rhs_jac = sys->rhs_jac;
  int st = rhs_jac ? sym_rhs_jac (sys, t, y, f, du)
                   : sym_jac (sys, t, y, NULL, du);
  /* a NaN or Inf in Df alone (f finite) */
  int bad_du = st == SYM_NONFINITE && sys->fail_df;
  if (! st || bad_du)
    {
      /* f(t, y) came with the Hessian, else jac_fd evaluates it */
      sys->jac = NULL;
      sys->rhs_jac = NULL;
      st = jac_fd (sys, t, y, rhs_jac ? f : NULL, dfd);
      double big = 0.0, dif = 0.0;
      for (size_t i = 0; ! st && ! bad_du && i < n * n; i++)
        {
          big = fmax (big, fmax (fabs (du[i]), fabs (dfd[i])));
          dif = fmax (dif, fabs (du[i] - dfd[i]));
        }
      *dropped = ! st && (bad_du || dif > SYM_JAC_AGREE * big);
      if (*dropped)
        {
          sys->jac_dropped = 1;
          sys->jac_dropped_t = t;
        }
      else
        {
          sys->jac = jac;
          sys->rhs_jac = rhs_jac;
        }
    }
  sym_free (w);
  return st;
}
