/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* jacobian.c -- Df for Newton's matrices: the user's (Jacobian, or the
   Hessian as FCN's second output), checked once on its first use and
   again after a Newton failure, or forward differences of f. */
#include "calls.h"
#include "numerics/numerics.h"

#include <float.h>
#include <math.h>
#include <string.h>

/* The sizes of y's components at the state y that scale its difference
   steps (see sym.h): max(|y_i|, ytyp_i), and at least SYM_FD_FLOOR times
   the largest of them in y_i's half (q or p); in a half that is all zero,
   the other half's largest, or 1 if both are.  Without ytyp (a stepper
   driven directly) a component's own size says nothing when it passes
   through zero, so all of a half take its largest size. */
static void
fd_sizes (const sym_eval *ev, const double *y, double *size)
{
  const int d = ev->dim;
  double big[2], low[2];
  for (int i = 0; i < 2 * d; i++)
    {
      size[i] = fabs (y[i]);
      if (ev->ytyp)
        size[i] = fmax (size[i], ev->ytyp[i]);
    }
  for (int half = 0; half < 2; half++)
    {
      big[half] = 0.0;
      for (int i = half * d; i < (half + 1) * d; i++)
        big[half] = fmax (big[half], size[i]);
    }
  const double fl = ev->ytyp ? SYM_FD_FLOOR : 1.0;
  for (int half = 0; half < 2; half++)
    low[half] = fmax (big[half] > 0 ? fl * big[half]
                      : big[1 - half] > 0 ? big[1 - half] : 1.0,
                      /* a step of subnormal data: at least DBL_MIN */
                      DBL_MIN / sqrt (DBL_EPSILON));
  for (int i = 0; i < 2 * d; i++)
    size[i] = fmax (size[i], low[i >= d]);
}

/* The colour of column j: its own column without a pattern */
static int
fd_color (const sym_eval *ev, int j)
{
  return ev->jp_ncolors > 0 ? ev->jp_color[j] : j;
}

/* The differences' workspace of at least need doubles: ev's, grown when
   too small; kept for the run, as a Df of the same size follows each
   step or Newton failure, and an allocation for each is needless work */
static double *
fd_room (sym_eval *ev, size_t need)
{
  if (need > ev->fd_cap)
    {
      sym_free (ev->fd_work);
      ev->fd_work = sym_malloc (need * sizeof (double));
      ev->fd_cap = ev->fd_work ? need : 0;
    }
  return ev->fd_work;
}

/* Forward differences at k states (columns of y, times t, f0 their f):
   df holds k n-by-n Jacobians.  The step of column j balances truncation
   (~ delta) against round-off (~ eps / delta).  Without a pattern each
   column is stepped in a state of its own; with one (sym_system) all the
   columns of a colour at once, their rows read from that state's f and
   the rest of Df zero.  With a batch callback all the stepped states go
   in one call, else one rhs call each; the results are the same.  With
   fout instead of f0, the k states' own f are evaluated too, into fout:
   with a batch callback in the same call as the stepped states when all
   fit in one.  Counted in nfd (and nrhs). */
static int
jac_fd_many (sym_eval *ev, int k, const double *t, const double *y,
             const double *f0, double *fout, double *df)
{
  const int n = 2 * ev->dim;
  const int batch = ev->rhs_batch != NULL;
  const int ng = ev->jp_ncolors > 0 ? ev->jp_ncolors : n;
  const size_t cols = (size_t) k * ng;    /* the stepped states */
  /* states evaluated per call: all of them with a batch callback, up to
     SYM_FD_BATCH_DOUBLES values of y in one call (a chain of d = 300 at 3
     nodes has 1800 columns of 600) */
  size_t ncw = batch ? cols : 1;
  if (ncw * n > SYM_FD_BATCH_DOUBLES)
    ncw = SYM_FD_BATCH_DOUBLES / n > 0 ? SYM_FD_BATCH_DOUBLES / n : 1;
  /* the states' own f: leading columns of the one call, or a call first */
  const size_t nb = fout && batch && (cols + k) * n <= SYM_FD_BATCH_DOUBLES
                    ? (size_t) k : 0;
  long before = ev->st.cnt.nrhs;
  if (fout && ! nb)
    {
      int st = sym_rhs_many (ev, k, t, y, fout);
      if (st)
        return st;
      before = ev->st.cnt.nrhs;
    }
  if (fout)
    f0 = fout;
  const size_t kn = (size_t) k * n;
  const size_t need = 2 * (ncw + nb) * n + 2 * kn + cols + nb + n;
  /* a small system's workspace on the stack: an allocation costs more
     than its differences (a block of the MEX allocator most of all) */
  double local[SYM_FD_LOCAL];
  double *w = need <= SYM_FD_LOCAL ? local : fd_room (ev, need);
  if (! w)
    return SYM_ENOMEM;
  double *yp = w, *fp = w + (ncw + nb) * n, *del = w + 2 * (ncw + nb) * n;
  double *yv = del + kn;                /* kn: the stepped values */
  double *tp = yv + kn;                 /* cols + nb: the states' times */
  double *size = tp + cols + nb;        /* n: one state's sizes */
  const double sq = sqrt (DBL_EPSILON);
  for (size_t j = 0; j < nb; j++)
    {
      memcpy (yp + j * n, y + j * n, (size_t) n * sizeof (double));
      tp[j] = t[j];
    }
  for (size_t c = 0; c < cols; c++)
    tp[nb + c] = t[c / ng];
  int st = SYM_SUCCESS;
  /* forward steps; if f is NaN or Inf at a stepped state (a state within
     a step of the edge of f's domain), all of them once more backwards */
  for (int pass = 0; pass < 2 && (pass == 0 || st == SYM_NONFINITE);
       pass++)
    {
      st = SYM_SUCCESS;
      for (int s = 0; s < k; s++)
        {
          const double *ys = y + (size_t) s * n;
          fd_sizes (ev, ys, size);
          for (int i = 0; i < n; i++)
            {
              volatile double yi = ys[i] + (pass ? -sq : sq) * size[i];
              yv[(size_t) s * n + i] = yi;   /* an exact representable step */
              del[(size_t) s * n + i] = yi - ys[i];
            }
        }
      for (size_t c0 = 0; c0 < cols && ! st; c0 += ncw)
        {
          size_t c1 = c0 + ncw < cols ? c0 + ncw : cols;
          size_t lead = c0 == 0 ? nb : 0;   /* the states themselves, first */
          double *ypc = yp + lead * n, *fpc = fp + lead * n;
          for (size_t c = c0; c < c1; c++)
            {
              const size_t s = c / ng;
              const int g = (int) (c % ng);
              double *col = ypc + (c - c0) * n;
              memcpy (col, y + s * n, (size_t) n * sizeof (double));
              for (int j = 0; j < n; j++)
                if (fd_color (ev, j) == g)
                  col[j] = yv[s * n + j];
            }
          st = batch ? sym_rhs_many (ev, (int) (c1 - c0 + lead),
                                     tp + nb + c0 - lead, yp, fp)
                     : sym_rhs (ev, tp[nb + c0], yp, fp);
          if (! st && lead)
            memcpy (fout, fp, lead * n * sizeof (double));
          for (size_t c = c0; c < c1 && ! st; c++)
            {
              const size_t s = c / ng;
              const int g = (int) (c % ng);
              const double *fc = fpc + (c - c0) * n, *f0s = f0 + s * n;
              for (int j = 0; j < n; j++)
                {
                  if (fd_color (ev, j) != g)
                    continue;
                  double *dfc = df + s * n * n + (size_t) j * n;
                  const double dj = del[s * n + j];
                  if (ev->jp_ncolors <= 0)
                    for (int i = 0; i < n; i++)
                      dfc[i] = (fc[i] - f0s[i]) / dj;
                  else
                    {
                      memset (dfc, 0, (size_t) n * sizeof (double));
                      for (int r = ev->jp_colptr[j];
                           r < ev->jp_colptr[j + 1]; r++)
                        {
                          const int i = ev->jp_rowind[r];
                          dfc[i] = (fc[i] - f0s[i]) / dj;
                        }
                    }
                }
            }
        }
    }
  ev->st.cnt.nfd += ev->st.cnt.nrhs - before;
  return st;
}

/* greedy colouring of a pattern's columns (sym.h) */
int
sym_pattern_colors (int n, const int *colptr, const int *rowind,
                    int *color)
{
  if (n < 1 || ! colptr || ! rowind || ! color || colptr[0] != 0)
    return -1;
  for (int j = 0; j < n; j++)
    if (colptr[j + 1] < colptr[j])
      return -1;
  const int nnz = colptr[n];
  for (int r = 0; r < nnz; r++)
    if (rowind[r] < 0 || rowind[r] >= n)
      return -1;
  /* the columns of each row (compressed rows), and the colours a column
     may not take (mark[c] == j: forbidden for column j) */
  int *rowptr = sym_calloc ((size_t) n + 1, sizeof (int));
  int *colind = sym_malloc (((size_t) nnz + 1) * sizeof (int));
  int *fill = sym_malloc ((size_t) n * sizeof (int));
  int *mark = sym_malloc ((size_t) n * sizeof (int));
  int ncolors = -1;
  if (rowptr && colind && fill && mark)
    {
      for (int r = 0; r < nnz; r++)
        rowptr[rowind[r] + 1]++;
      for (int i = 0; i < n; i++)
        {
          rowptr[i + 1] += rowptr[i];
          fill[i] = rowptr[i];
          mark[i] = -1;
        }
      for (int j = 0; j < n; j++)
        for (int r = colptr[j]; r < colptr[j + 1]; r++)
          colind[fill[rowind[r]]++] = j;
      ncolors = 0;
      for (int j = 0; j < n; j++)
        {
          /* the colours of the earlier columns that share a row with j */
          for (int r = colptr[j]; r < colptr[j + 1]; r++)
            {
              const int i = rowind[r];
              for (int q = rowptr[i]; q < rowptr[i + 1] && colind[q] < j;
                   q++)
                mark[color[colind[q]]] = j;
            }
          int c = 0;
          while (c < ncolors && mark[c] == j)
            c++;
          color[j] = c;
          if (c == ncolors)
            ncolors++;
        }
    }
  sym_free (rowptr);
  sym_free (colind);
  sym_free (fill);
  sym_free (mark);
  return ncolors;
}

static int
jac_fd (sym_eval *ev, double t, const double *y, const double *f0,
        double *df)
{
  if (f0)
    return jac_fd_many (ev, 1, &t, y, f0, NULL, df);
  /* f(t, y) apart from the workspace jac_fd_many takes: on the stack,
     or kept as that is */
  const size_t n = 2 * (size_t) ev->dim;
  double local[SYM_FD_LOCAL / 8];
  if (n > SYM_FD_LOCAL / 8 && ! ev->fd_f
      && ! (ev->fd_f = sym_malloc (n * sizeof (double))))
    return SYM_ENOMEM;
  double *fb = n > SYM_FD_LOCAL / 8 ? ev->fd_f : local;
  long before = ev->st.cnt.nrhs;
  int st = sym_rhs (ev, t, y, fb);
  ev->st.cnt.nfd += ev->st.cnt.nrhs - before;
  if (! st)
    st = jac_fd_many (ev, 1, &t, y, fb, NULL, df);
  return st;
}

/* The first Df a run gets from the user's jac or rhs_jac (sym.h,
   SYM_JAC_GROSS), df at (t, y), with f0 = f(t, y) or NULL: compared along
   one direction with a forward difference of rhs, and dropped for finite
   differences (into df) when it is grossly too large.  A failed call of rhs returns its status,
   as in the finite differences, and leaves the probe to be made again. */
static int jac_fd_csc (sym_eval *ev, double t, const double *y,
                       const double *f0, sym_csc *df);
static int own_pattern (sym_eval *ev, const sym_csc *df);
static int jac_check_csc (sym_eval *ev, double t, const double *y,
                          int *dropped);

/* (df dense, or dfs sparse) */
static int
jac_probe (sym_eval *ev, double t, const double *y, const double *f0,
           double *df, sym_csc *dfs)
{
  const int n = 2 * ev->dim;
  ev->jac_probed = 1;
  double *w = sym_malloc (6 * (size_t) n * sizeof (double));
  if (! w)
    return SYM_ENOMEM;
  double *fb = w, *yp = w + n, *fp = w + 2 * n, *size = w + 3 * n;
  double *dy = w + 4 * n, *pred = w + 5 * n;
  long before = ev->st.cnt.nrhs;
  int st = SYM_SUCCESS;
  if (! f0)
    {
      st = sym_rhs (ev, t, y, fb);
      f0 = fb;
    }
  /* a direction with every component of its own size (as the finite
     differences step them) and varied weights and signs, so that no
     structure of Df hides a wrong part of it */
  fd_sizes (ev, y, size);
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
  if (! st && (st = sym_rhs (ev, t, yp, fp)) == SYM_NONFINITE)
    {
      for (int i = 0; i < n; i++)
        {
          volatile double yi = y[i] - (yp[i] - y[i]);
          yp[i] = yi;
        }
      st = sym_rhs (ev, t, yp, fp);
      if (st == SYM_NONFINITE)
        {
          ev->st.cnt.nfd += ev->st.cnt.nrhs - before;
          sym_free (w);
          return SYM_SUCCESS;
        }
    }
  ev->st.cnt.nfd += ev->st.cnt.nrhs - before;
  if (st)
    {
      ev->jac_probed = 0;
      sym_free (w);
      return st;
    }
  double dif = 0.0, ref = 0.0, fbig = 0.0;
  for (int j = 0; j < n; j++)
    dy[j] = yp[j] - y[j];
  if (dfs)
    sym_csc_mv (dfs, dy, pred);
  else
    for (int i = 0; i < n; i++)
      {
        pred[i] = 0.0;
        for (int j = 0; j < n; j++)
          pred[i] += df[i + (size_t) j * n] * dy[j];
      }
  for (int i = 0; i < n; i++)
    {
      double del = fp[i] - f0[i];
      dif = fmax (dif, fabs (del - pred[i]));
      ref = fmax (ref, fabs (del));
      fbig = fmax (fbig, fmax (fabs (f0[i]), fabs (fp[i])));
    }
  /* the difference's own round-off: f's rounding, a few ulps of f */
  ref += SYM_JAC_NOISE * DBL_EPSILON * fbig;
  if (dif > SYM_JAC_GROSS * ref && ! (dfs && (st = own_pattern (ev, dfs))))
    {
      ev->jac = NULL;
      ev->rhs_jac = NULL;
      ev->jac_csc = NULL;
      ev->rhs_jac_csc = NULL;
      ev->st.jac_dropped = 1;
      ev->st.jac_dropped_t = t;
      st = dfs ? jac_fd_csc (ev, t, y, f0, dfs) : jac_fd (ev, t, y, f0, df);
    }
  sym_free (w);
  return st;
}

int
sym_jac (sym_eval *ev, double t, const double *y, const double *f0,
         double *df)
{
  if (! ev->jac)
    return jac_fd (ev, t, y, f0, df);
  int n = 2 * ev->dim;
  ev->st.cnt.njac++;
  int st = sym_callback_status (ev, t, ev->jac (t, y, df, ev->user));
  if (st)
    return st;
  if (! sym_all_finite ((size_t) n * (size_t) n, df))
    return sym_nonfinite_df_at (ev, t);
  return ev->jac_probed ? SYM_SUCCESS : jac_probe (ev, t, y, f0, df, NULL);
}

int
sym_rhs_jac (sym_eval *ev, double t, const double *y, double *dy,
             double *df)
{
  if (! ev->rhs_jac)
    {
      int st = sym_rhs (ev, t, y, dy);
      return st ? st : sym_jac (ev, t, y, dy, df);
    }
  int n = 2 * ev->dim;
  ev->st.cnt.njac++;
  ev->st.rhs_jac_used = 1;
  int st = sym_callback_status (ev, t, ev->rhs_jac (t, y, dy, df, ev->user));
  if (st)
    return st;
  if (! sym_all_finite (n, dy))
    return sym_nonfinite_at (ev, t);
  if (! sym_all_finite ((size_t) n * (size_t) n, df))
    return sym_nonfinite_df_at (ev, t);
  return ev->jac_probed ? SYM_SUCCESS : jac_probe (ev, t, y, dy, df, NULL);
}

int
sym_jac_many (sym_eval *ev, int k, const double *t, const double *y,
              const double *f0, double *df)
{
  const size_t n = 2 * (size_t) ev->dim;
  if (! ev->jac)
    return jac_fd_many (ev, k, t, y, f0, NULL, df);
  for (int j = 0; j < k; j++)
    {
      int st = sym_jac (ev, t[j], y + j * n, NULL, df + j * n * n);
      if (st)
        return st;
    }
  return SYM_SUCCESS;
}

int
sym_rhs_jac_many (sym_eval *ev, int k, const double *t, const double *y,
                  double *f, double *df)
{
  if (! ev->jac)
    return jac_fd_many (ev, k, t, y, NULL, f, df);
  int st = sym_rhs_many (ev, k, t, y, f);
  return st ? st : sym_jac_many (ev, k, t, y, f, df);
}

int
sym_jac_check (sym_eval *ev, double t, const double *y, int *dropped)
{
  const size_t n = 2 * (size_t) ev->dim;
  *dropped = 0;
  if (ev->sparse)
    return ev->jac_csc || ev->rhs_jac_csc
           ? jac_check_csc (ev, t, y, dropped) : SYM_SUCCESS;
  if (! ev->jac && ! ev->rhs_jac)
    return SYM_SUCCESS;
  double *w = sym_malloc ((2 * n * n + n) * sizeof (double));
  if (! w)
    return SYM_ENOMEM;
  double *du = w, *dfd = w + n * n, *f = w + 2 * n * n;
  sym_jac_fn jac = ev->jac;
  sym_rhs_jac_fn rhs_jac = ev->rhs_jac;
  int st = rhs_jac ? sym_rhs_jac (ev, t, y, f, du)
                   : sym_jac (ev, t, y, NULL, du);
  /* a NaN or Inf in Df alone (f finite) */
  int bad_du = st == SYM_NONFINITE && ev->st.fail_df;
  if (! st || bad_du)
    {
      /* f(t, y) came with the Hessian, else jac_fd evaluates it */
      ev->jac = NULL;
      ev->rhs_jac = NULL;
      st = jac_fd (ev, t, y, rhs_jac ? f : NULL, dfd);
      double big = 0.0, dif = 0.0;
      for (size_t i = 0; ! st && ! bad_du && i < n * n; i++)
        {
          big = fmax (big, fmax (fabs (du[i]), fabs (dfd[i])));
          dif = fmax (dif, fabs (du[i] - dfd[i]));
        }
      *dropped = ! st && (bad_du || dif > SYM_JAC_AGREE * big);
      if (*dropped)
        {
          ev->st.jac_dropped = 1;
          ev->st.jac_dropped_t = t;
        }
      else
        {
          ev->jac = jac;
          ev->rhs_jac = rhs_jac;
        }
    }
  sym_free (w);
  return st;
}

/* ---------------------------------------------------------------- sparse */

/* Forward differences on the pattern into the sparse df: one stepped
   state for each colour (all in one batch call when there is one, up to
   SYM_FD_BATCH_DOUBLES values), the values read from the rows of each
   column's pattern.  f0 = f(t, y), or NULL: one more call.  Counted in
   nfd (and nrhs). */
static int
jac_fd_csc (sym_eval *ev, double t, const double *y, const double *f0,
            sym_csc *df)
{
  const int n = 2 * ev->dim, ng = ev->jp_ncolors;
  if (ng <= 0)
    return SYM_EBADINPUT;
  const int nnz = ev->jp_colptr[n];
  if (sym_csc_reserve (df, nnz))
    return SYM_ENOMEM;
  size_t ncw = ev->rhs_batch ? (size_t) ng : 1;
  if (ncw * n > SYM_FD_BATCH_DOUBLES)
    ncw = SYM_FD_BATCH_DOUBLES / n > 0 ? SYM_FD_BATCH_DOUBLES / n : 1;
  double *w = fd_room (ev, (2 * ncw + 3) * (size_t) n + ncw);
  if (! w)
    return SYM_ENOMEM;
  double *yp = w, *fp = w + ncw * n, *del = fp + ncw * n, *size = del + n;
  double *fb = size + n, *tp = fb + n;
  long before = ev->st.cnt.nrhs;
  int st = SYM_SUCCESS;
  if (! f0 && ! (st = sym_rhs (ev, t, y, fb)))
    f0 = fb;
  const double sq = sqrt (DBL_EPSILON);
  /* f NaN or Inf at a stepped state: all of them once more backwards */
  for (int pass = 0; f0 && pass < 2; pass++)
    {
      if (pass == 1 && st != SYM_NONFINITE)
        break;
      st = SYM_SUCCESS;
      fd_sizes (ev, y, size);
      for (int i = 0; i < n; i++)
        {
          volatile double yi = y[i] + (pass ? -sq : sq) * size[i];
          del[i] = yi - y[i];       /* an exact representable step */
        }
      for (int g0 = 0; g0 < ng && ! st; g0 += (int) ncw)
        {
          const int g1 = g0 + (int) ncw < ng ? g0 + (int) ncw : ng;
          for (int g = g0; g < g1; g++)
            {
              double *col = yp + (size_t) (g - g0) * n;
              memcpy (col, y, (size_t) n * sizeof (double));
              tp[g - g0] = t;
            }
          for (int j = 0; j < n; j++)
            if (ev->jp_color[j] >= g0 && ev->jp_color[j] < g1)
              yp[(size_t) (ev->jp_color[j] - g0) * n + j] += del[j];
          st = ev->rhs_batch ? sym_rhs_many (ev, g1 - g0, tp, yp, fp)
                             : sym_rhs (ev, t, yp, fp);
          for (int j = 0; j < n && ! st; j++)
            {
              const int g = ev->jp_color[j];
              if (g < g0 || g >= g1)
                continue;
              const double *fc = fp + (size_t) (g - g0) * n;
              for (int r = ev->jp_colptr[j]; r < ev->jp_colptr[j + 1]; r++)
                df->val[r] = (fc[ev->jp_rowind[r]] - f0[ev->jp_rowind[r]])
                             / del[j];
            }
        }
    }
  if (! st)
    {
      df->n = n;
      df->nnz = nnz;
      memcpy (df->colptr, ev->jp_colptr, (size_t) (n + 1) * sizeof (int));
      memcpy (df->rowind, ev->jp_rowind, (size_t) nnz * sizeof (int));
    }
  ev->st.cnt.nfd += ev->st.cnt.nrhs - before;
  return st;
}

int
sym_jac_csc (sym_eval *ev, double t, const double *y, const double *f0,
             sym_csc *df)
{
  if (! ev->jac_csc)
    return jac_fd_csc (ev, t, y, f0, df);
  ev->st.cnt.njac++;
  int st = sym_callback_status (ev, t, ev->jac_csc (t, y, df, ev->user));
  if (st)
    return st;
  if (! sym_all_finite ((size_t) df->nnz, df->val))
    return sym_nonfinite_df_at (ev, t);
  return ev->jac_probed ? SYM_SUCCESS : jac_probe (ev, t, y, f0, NULL, df);
}

int
sym_rhs_jac_csc (sym_eval *ev, double t, const double *y, double *dy,
                 sym_csc *df)
{
  if (! ev->rhs_jac_csc)
    {
      int st = sym_rhs (ev, t, y, dy);
      return st ? st : sym_jac_csc (ev, t, y, dy, df);
    }
  ev->st.cnt.njac++;
  ev->st.rhs_jac_used = 1;
  int st = sym_callback_status (ev, t,
                                ev->rhs_jac_csc (t, y, dy, df, ev->user));
  if (st)
    return st;
  if (! sym_all_finite (2 * (size_t) ev->dim, dy))
    return sym_nonfinite_at (ev, t);
  if (! sym_all_finite ((size_t) df->nnz, df->val))
    return sym_nonfinite_df_at (ev, t);
  return ev->jac_probed ? SYM_SUCCESS : jac_probe (ev, t, y, dy, NULL, df);
}

/* The pattern of the finite differences that replace a dropped sparse
   Df: the system's, or the dropped one's, coloured and kept in ev (freed
   by sym_eval_free) */
static int
own_pattern (sym_eval *ev, const sym_csc *df)
{
  if (ev->jp_ncolors > 0)
    return SYM_SUCCESS;
  const int n = df->n, nnz = df->nnz;
  int *w = sym_malloc (((size_t) 2 * n + 1 + nnz) * sizeof (int));
  if (! w)
    return SYM_ENOMEM;
  memcpy (w, df->colptr, ((size_t) n + 1) * sizeof (int));
  memcpy (w + n + 1, df->rowind, (size_t) nnz * sizeof (int));
  int *color = w + n + 1 + nnz;
  const int nc = sym_pattern_colors (n, w, w + n + 1, color);
  if (nc < 1)
    {
      sym_free (w);
      return nc < 0 ? SYM_ENOMEM : SYM_EBADINPUT;
    }
  ev->own_pattern = w;
  ev->jp_colptr = w;
  ev->jp_rowind = w + n + 1;
  ev->jp_color = color;
  ev->jp_ncolors = nc;
  return SYM_SUCCESS;
}

void
sym_eval_free (sym_eval *ev)
{
  if (ev->own_pattern)
    {
      sym_free (ev->own_pattern);
      ev->own_pattern = NULL;
      ev->jp_colptr = ev->jp_rowind = ev->jp_color = NULL;
      ev->jp_ncolors = 0;
    }
  sym_free (ev->fd_work);
  sym_free (ev->fd_f);
  ev->fd_work = ev->fd_f = NULL;
  ev->fd_cap = 0;
}

/* the largest |a - b| and the largest entry of a and b: column by column
   through the dense column w (n zeros, left zero) */
static void
csc_compare (const sym_csc *a, const sym_csc *b, double *w, double *dif,
             double *big)
{
  *dif = *big = 0.0;
  for (int j = 0; j < a->n; j++)
    {
      for (int e = a->colptr[j]; e < a->colptr[j + 1]; e++)
        {
          w[a->rowind[e]] = a->val[e];
          *big = fmax (*big, fabs (a->val[e]));
        }
      for (int e = b->colptr[j]; e < b->colptr[j + 1]; e++)
        {
          w[b->rowind[e]] -= b->val[e];
          *big = fmax (*big, fabs (b->val[e]));
        }
      for (int pass = 0; pass < 2; pass++)
        {
          const sym_csc *m = pass ? b : a;
          for (int e = m->colptr[j]; e < m->colptr[j + 1]; e++)
            {
              *dif = fmax (*dif, fabs (w[m->rowind[e]]));
              w[m->rowind[e]] = 0.0;
            }
        }
    }
}

/* sym_jac_check for a sparse Df: the finite differences on the system's
   pattern, or on the user's Df's own */
static int
jac_check_csc (sym_eval *ev, double t, const double *y, int *dropped)
{
  const int n = 2 * ev->dim;
  sym_csc du, dfd;
  double *w = sym_calloc (2 * (size_t) n, sizeof (double));
  int st = sym_csc_init (&du, n, 0);
  if (! st)
    st = sym_csc_init (&dfd, n, 0);
  if (st || ! w)
    {
      sym_csc_free (&du);
      sym_free (w);
      return SYM_ENOMEM;
    }
  double *f = w + n;
  sym_jac_csc_fn jac = ev->jac_csc;
  sym_rhs_jac_csc_fn rhs_jac = ev->rhs_jac_csc;
  st = rhs_jac ? sym_rhs_jac_csc (ev, t, y, f, &du)
               : sym_jac_csc (ev, t, y, NULL, &du);
  int bad_du = st == SYM_NONFINITE && ev->st.fail_df;
  if ((! st || bad_du) && ! (st = own_pattern (ev, &du)))
    {
      ev->jac_csc = NULL;
      ev->rhs_jac_csc = NULL;
      st = jac_fd_csc (ev, t, y, rhs_jac ? f : NULL, &dfd);
      double big = 0.0, dif = 0.0;
      if (! st && ! bad_du)
        csc_compare (&du, &dfd, w, &dif, &big);
      *dropped = ! st && (bad_du || dif > SYM_JAC_AGREE * big);
      if (*dropped)
        {
          ev->st.jac_dropped = 1;
          ev->st.jac_dropped_t = t;
        }
      else
        {
          ev->jac_csc = jac;
          ev->rhs_jac_csc = rhs_jac;
        }
    }
  sym_csc_free (&du);
  sym_csc_free (&dfd);
  sym_free (w);
  return st;
}

int
sym_jac_cost (const sym_eval *ev)
{
  if (ev->jac || ev->rhs_jac || ev->jac_csc || ev->rhs_jac_csc)
    return 1;
  return ev->sparse && ev->jp_ncolors > 0 ? ev->jp_ncolors : 2 * ev->dim;
}
