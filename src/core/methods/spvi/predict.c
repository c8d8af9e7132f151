/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* predict.c -- the start of odeSPVI's Newton solves and the scales of
   their stopping test.

   The start: the previous accepted step's polynomials extrapolated (q
   from its Legendre series, re-expanded exactly in the new step by a
   Gauss transform; p from its interpolant through p_k, P_j, p_{k+1}),
   with many nodes only their modes above the noise of the solve (which
   the extrapolation amplifies like 5.8^Nodes); at a fixed step plus the
   extrapolated errors of the last steps' predictions (a smooth function
   of the step's start).  On a first step, after a failure, or for the
   pairs n - 1 > m (whose extra q modes do not extrapolate): one explicit
   Euler estimate. */
#include "spvi.h"

#include <float.h>
#include <math.h>
#include <string.h>

/* The momentum polynomial of step r (through (-1, p_k), (z_j, P_j),
   (1, p_{k+1})) at z, into p (d values). */
void
spvi_rec_p (const spvi_state *s, const spvi_rec *r, double z, double *p)
{
  const int d = s->d, m = s->m;
  sym_lagrange_basis (m + 2, s->lo.xb, s->lo.bw, z, s->cb);
  for (int k = 0; k < d; k++)
    {
      double v = s->cb[0] * r->y0[d + k] + s->cb[m + 1] * r->y1[d + k];
      for (int j = 0; j < m; j++)
        v += s->cb[j + 1] * r->P[(size_t) j * d + k];
      p[k] = v;
    }
}

/* q(z) - q_k of the modes a (a_1..a_{n-1}, d values each; a step's
   r->a), into q */
void
spvi_modes_dq (const spvi_state *s, const double *a, double z, double *q)
{
  const int d = s->d, n = s->n;
  sym_legendre (n, z, s->lv, s->dlv);
  for (int k = 0; k < d; k++)
    {
      double v = 0.0;
      for (int i = 1; i < n; i++)
        v += a[(size_t) (i - 1) * d + k]
             * (s->lv[i] - ((i % 2) ? -1.0 : 1.0));
      q[k] = v;
    }
}

/* The modes of the continued prediction (see predict_modes): the
   highest mode of c (nm modes of d values, mode i at c[i*d]) from mode
   lo on whose size exceeds SYM_SPVI_CHOP (2i + 1)^pw noise in some component
   (lo - 1 if none). */
static int
top_mode (const double *c, int nm, int d, int lo, int pw, double noise)
{
  for (int i = nm - 1; i >= lo; i--)
    {
      double thr = SYM_SPVI_CHOP * noise * (pw ? 2.0 * i + 1.0 : 1.0);
      for (int k = 0; k < d; k++)
        if (! (fabs (c[(size_t) i * d + k]) <= thr))
          return i;
    }
  return lo - 1;
}

/* The continued prediction evaluates the last step's polynomials at z =
   1 + rho (z' + 1), up to zmax = 1 + 2 rho, outside [-1, 1], where
   Legendre modes grow like |l_i(zmax)| (about 5.8^i / 6 at rho = 1).  The
   solve left a noise of about r->noise_q in each a_i, and about (2i + 1)
   r->noise_p in the i-th Legendre coefficient of the p polynomial
   (through p_k, P_j, p_{k+1}), and the continuation amplifies them by as
   much: for many nodes the prediction is noise.  When the amplified noise
   can exceed SYM_SPVI_PRED_NOISE |y|, the modes at the top of each series
   that are below SYM_SPVI_CHOP times their noise are cut off.  Returns
   the highest Legendre mode of p to use, or m + 1 for the p polynomial
   itself (spvi_rec_p); q's modes are in s->ach. */
static int
predict_modes (spvi_state *s, const spvi_rec *r, double zmax, double ynorm)
{
  const int d = s->d, n = s->n, m = s->m;
  const size_t na = (size_t) (n - 1) * d;
  const int nl = n > m + 2 ? n : m + 2;
  memcpy (s->ach, r->a, na * sizeof (double));
  double amp = s->pt_amp;
  if (! s->pt_ok)
    {
      sym_legendre (nl, zmax, s->lv, s->dlv);
      amp = 0.0;
      for (int i = 1; i < n; i++)
        amp += fabs (s->lv[i]) + 1.0;
      for (int i = 0; i < m + 2; i++)
        amp += (2.0 * i + 1.0) * fabs (s->lv[i]);
      s->pt_amp = amp;
    }
  if (! (amp * fmax (r->noise_q, r->noise_p) > SYM_SPVI_PRED_NOISE * ynorm))
    return m + 1;
  int kq = top_mode (r->a, n - 1, d, 0, 0, r->noise_q) + 1;
  memset (s->ach + (size_t) kq * d, 0,
          (na - (size_t) kq * d) * sizeof (double));
  /* p's Legendre coefficients (degree m + 1) by Gauss quadrature */
  memset (s->pc, 0, (size_t) (m + 2) * d * sizeof (double));
  for (int l = 0; l < m + 2; l++)
    {
      spvi_rec_p (s, r, s->pz[l], s->vq);
      sym_legendre (m + 2, s->pz[l], s->lv, s->dlv);
      for (int i = 0; i < m + 2; i++)
        {
          double c = 0.5 * (2.0 * i + 1.0) * s->pw[l] * s->lv[i];
          for (int k = 0; k < d; k++)
            s->pc[(size_t) i * d + k] += c * s->vq[k];
        }
    }
  return top_mode (s->pc, m + 2, d, 1, 1, r->noise_p);
}

/* Whether the polynomial prediction in s->lo.x of the step continuing r
   by rho times its h, from y, stays within SYM_SPVI_PRED_SANE times the
   change of y over r (times 1 + rho) of y.  Extrapolated to [1, 1 + 2
   rho] the polynomials of many modes or nodes amplify the round-off of
   their coefficients, and the scales of Newton's stopping test are taken
   from the prediction: a prediction far off would let Newton stop at
   once on a wrong solution. */
static int
predict_sane (const spvi_state *s, const spvi_rec *r, double rho,
              const double *y)
{
  const int d = s->d, n = s->n, m = s->m;
  const double *a = s->lo.x, *P = s->lo.x + (size_t) (n - 1) * d;
  double prev = 0.0, dev = 0.0;
  for (int k = 0; k < 2 * d; k++)
    prev = sym_fmax_acc (prev, fabs (r->y1[k] - r->y0[k]));
  for (int k = 0; k < d; k++)
    {
      double v = 0.0;
      for (int i = 1; i < n; i++)
        v += fabs (a[(size_t) (i - 1) * d + k]);
      dev = sym_fmax_acc (dev, v);
      for (int j = 0; j < m; j++)
        dev = sym_fmax_acc (dev,
                           fabs (P[(size_t) j * d + k] - y[d + k]));
    }
  return isfinite (dev) && dev <= SYM_SPVI_PRED_SANE * (1.0 + fabs (rho)) * prev;
}

/* The start x = (a, P) in s->lo.x from the polynomials of the solved
   step r evaluated at its z = z0 + rho (z' + 1) for the new step's z'
   (z0 = 1: the step after r; z0 = -1: a step from r's start, rho times
   as long), with only their modes above the noise (predict_modes). */
static void
predict_poly (spvi_state *s, const spvi_rec *r, double z0, double rho,
              double ynorm)
{
  const int d = s->d, n = s->n, m = s->m;
  double *a = s->lo.x, *P = s->lo.x + (size_t) (n - 1) * d;
  if (! (s->pt_ok && z0 == s->pt_z0 && rho == s->pt_rho))
    {
      /* the basis values at this (z0, rho), as spvi_modes_dq and
         spvi_rec_p evaluate them */
      s->pt_ok = 0;
      for (int l = 0; l < n; l++)
        {
          sym_legendre (n, z0 + rho * (s->xi[l] + 1.0), s->lv, s->dlv);
          for (int i = 1; i < n; i++)
            s->pt_q[l * n + i] = s->lv[i] - ((i % 2) ? -1.0 : 1.0);
        }
      for (int j = 0; j < m; j++)
        sym_lagrange_basis (m + 2, s->lo.xb, s->lo.bw,
                            z0 + rho * (s->lo.z[j] + 1.0),
                            s->pt_p + (size_t) j * (m + 2));
    }
  int kp = predict_modes (s, r, z0 + 2.0 * fabs (rho), ynorm);
  s->pt_z0 = z0;
  s->pt_rho = rho;
  s->pt_ok = 1;
  for (int l = 0; l < n; l++)
    for (int k = 0; k < d; k++)
      {
        double v = 0.0;
        for (int i = 1; i < n; i++)
          v += s->ach[(size_t) (i - 1) * d + k] * s->pt_q[l * n + i];
        s->vq[(size_t) l * d + k] = v;
      }
  /* q(z) - q(z0) of the old step, the new step's increments; the
     constant part drops out of a_i, i >= 1 */
  for (int i = 1; i < n; i++)
    for (int k = 0; k < d; k++)
      {
        double q0 = z0 > 0 ? r->y1[k] - r->y0[k] : 0.0;
        double v = 0.0;
        for (int l = 0; l < n; l++)
          v += s->vinv[i * n + l] * (s->vq[(size_t) l * d + k] - q0);
        a[(size_t) (i - 1) * d + k] = v;
      }
  for (int j = 0; j < m; j++)
    {
      double z = z0 + rho * (s->lo.z[j] + 1.0);
      if (kp > m)
        {
          /* spvi_rec_p at z */
          const double *cb = s->pt_p + (size_t) j * (m + 2);
          for (int k = 0; k < d; k++)
            {
              double v = cb[0] * r->y0[d + k] + cb[m + 1] * r->y1[d + k];
              for (int l = 0; l < m; l++)
                v += cb[l + 1] * r->P[(size_t) l * d + k];
              P[(size_t) j * d + k] = v;
            }
          continue;
        }
      sym_legendre (kp + 1, z, s->lv, s->dlv);
      for (int k = 0; k < d; k++)
        {
          double v = 0.0;
          for (int i = 0; i <= kp; i++)
            v += s->pc[(size_t) i * d + k] * s->lv[i];
          P[(size_t) j * d + k] = v;
        }
    }
}

/* The scales of the step (h) from y starting at s->lo.x: for the a_i,
   the size of q (|q_k|, |q_{k+1}|) or the round-off that p's carries
   into q through the step (|h| |Aqp| |p|, by the node Jacobians of the
   kept matrix, at the state where it was first used), and the largest
   of these of the steps before; for the
   P_j likewise the size of p (|p_k|, |P_j|) or |h| |Apq| |q|.  So fixed
   steps converge each block to its own round-off, whatever the units of
   q and p, and a block passing through zero keeps the scale of its size
   in the run; a block of zeros takes the other's size (1 if both are
   zero).  Within a block one scale serves all components: a
   per-component scale cannot be met below the round-off that f's
   coupling carries from the large components into the small ones.
   Adaptive steps take the larger size for both blocks (adaptive = 1):
   their solves stop at an absolute accuracy set by the tolerances. */
/* The round-off of one block carried into the other by the node
   Jacobians in c->A: max |Aqp| |p| and max |Apq| |q| (qa, pa: the sizes
   of the components); computed once for each matrix */
static void
carried_noise (spvi_core *c, const double *qa, const double *pa)
{
  const int d = c->d;
  const size_t nn = 2 * (size_t) d;
  c->noise_q = c->noise_p = 0.0;
  for (int j = 0; j < c->m; j++)
    {
      const double *A = spvi_A (c, j);
      for (int k = 0; k < d; k++)
        {
          double nq = 0.0, np = 0.0;
          for (int l = 0; l < d; l++)
            {
              nq += fabs (AQP (A, k, l)) * pa[l];
              np += fabs (APQ (A, k, l)) * qa[l];
            }
          c->noise_q = fmax (c->noise_q, nq);
          c->noise_p = fmax (c->noise_p, np);
        }
    }
  c->noise_ok = 1;
}

static spvi_scale
start_scale (spvi_state *s, const double *y, double h, int adaptive)
{
  const int d = s->d, n = s->n, m = s->m;
  const double *a = s->lo.x, *P = s->lo.x + (size_t) (n - 1) * d;
  double *qa = s->vq, *pa = s->vq + d;
  double sq = 0.0, sp = 0.0;
  for (int k = 0; k < d; k++)
    {
      double v = y[k];
      for (int i = 1; i < n; i += 2)
        v += 2.0 * a[(size_t) (i - 1) * d + k];
      qa[k] = fmax (fabs (v), fabs (y[k]));
      pa[k] = fabs (y[d + k]);
      for (int j = 0; j < m; j++)
        pa[k] = fmax (pa[k], fabs (P[(size_t) j * d + k]));
      sq = sym_fmax_acc (sq, qa[k]);
      sp = sym_fmax_acc (sp, pa[k]);
    }
  spvi_scale S;
  S.all = fmax (sq, sp) > 0 ? fmax (sq, sp) : 1.0;
  if (s->lo.nae > 0 && ! s->lo.noise_ok)
    {
      if (s->lo.sg)
        spvi_stages_noise (&s->lo, qa, pa);
      else
        carried_noise (&s->lo, qa, pa);
    }
  if (s->lo.nae > 0)
    {
      sq = fmax (sq, fabs (h) * s->lo.noise_q);
      sp = fmax (sp, fabs (h) * s->lo.noise_p);
    }
  if (isfinite (sq) && isfinite (sp))
    {
      s->typ_q = sq = fmax (sq, s->typ_q);
      s->typ_p = sp = fmax (sp, s->typ_p);
    }
  S.q = adaptive || ! (sq > 0) ? S.all : sq;
  S.p = adaptive || ! (sp > 0) ? S.all : sp;
  /* subnormal data: corrections measured against their quantum */
  S.q = fmax (S.q, DBL_MIN);
  S.p = fmax (S.p, DBL_MIN);
  S.all = fmax (S.all, DBL_MIN);
  return S;
}

/* The start of Newton for the step (t, h, y) into s->lo.x; returns the
   scales of the stopping test in *S (adaptive: see start_scale). */
int
spvi_predict (spvi_state *s, sym_eval *ev, double t, double h,
              const double *y, int euler, int adaptive, spvi_scale *S)
{
  const int d = s->d, n = s->n, m = s->m;
  double *a = s->lo.x, *P = s->lo.x + (size_t) (n - 1) * d;
  double ynorm = sym_norm_inf (2 * d, y);
  const spvi_rec *r = s->cur;
  /* n - 1 > m: the q polynomial carries modes that the kinetic
     quadrature cannot see (fixed by the potential's curvature); they do
     not extrapolate (l_3(3) = 63), so those pairs start from Euler. */
  int cont = ! euler && s->have_cur && n - 1 <= m
             && sym_same_time (t, r->tend, r->h)
             && sym_same_vec (2 * d, y, r->y1);
  s->trial->cont = cont && sym_same_step (h, r->h);
  if (cont)
    {
      /* new z' <-> old z = 1 + rho (z' + 1) */
      double rho = h / r->h;
      predict_poly (s, r, 1.0, rho, ynorm);
      cont = predict_sane (s, r, rho, y);
      s->trial->cont = s->trial->cont && cont;
    }
  s->pred_cont = cont;
  if (! cont)
    {
      /* explicit Euler: q(z) = q_k + (h/2)(z + 1) f_q, p likewise */
      int st = sym_rhs (ev, t, y, s->f0);
      if (st)
        return st;
      for (int k = 0; k < d; k++)
        {
          a[k] = 0.5 * h * s->f0[k];
          for (int i = 2; i < n; i++)
            a[(size_t) (i - 1) * d + k] = 0.0;
          for (int j = 0; j < m; j++)
            P[(size_t) j * d + k] = y[d + k]
                                    + 0.5 * h * (s->lo.z[j] + 1.0)
                                      * s->f0[d + k];
        }
    }
  *S = start_scale (s, y, h, adaptive);
  return SYM_SUCCESS;
}

/* The start of a continued step of the history's h: the polynomial
   prediction (in s->lo.x, kept in the trial's xp) plus the extrapolated
   errors of the predictions of the last steps.  The error of the
   polynomial prediction is O(h^(m+1)) (the stage order) but a smooth
   function of the step's start at a fixed h, so its differences over
   steps are smaller by factors of about h/(time scale).  The order L
   (<= SYM_SPVI_HIST) is the one that would have predicted the newest
   error best from the ones before.  Not for n - 1 != m (see solve.c). */
void
spvi_predict_history (spvi_state *s, double h)
{
  const int N = s->lo.N;
  const spvi_rec *tr = s->trial;
  memcpy (s->xp, s->lo.x, (size_t) N * sizeof (double));
  if (s->n - 1 != s->m || ! tr->cont || s->nhist < 2
      || ! sym_same_step (h, s->hhist))
    return;
  /* every order's error in one pass over the components: each v_L
     summed in the order of l, as order L alone would */
  const int nL = s->nhist < SYM_SPVI_HIST + 1 ? s->nhist : SYM_SPVI_HIST + 1;
  const float *const dh = s->dhist;
  const double d0 = s->dscale[0];
  double c[SYM_SPVI_HIST + 1][SYM_SPVI_HIST], e[SYM_SPVI_HIST + 1];
  for (int L = 0; L < nL; L++)
    {
      const double *wL = sym_extrap_weights (L);
      for (int l = 0; l < L; l++)
        c[L][l] = wL[l] * s->dscale[l + 1];
      e[L] = 0.0;
    }
#if SYM_SPVI_HIST == 4
  /* the usual full history, by registers */
  if (nL == 5)
    {
      const float *h1 = dh + N, *h2 = h1 + N, *h3 = h2 + N, *h4 = h3 + N;
      double e0 = 0.0, e1 = 0.0, e2 = 0.0, e3 = 0.0, e4 = 0.0;
      for (int i = 0; i < N; i++)
        {
          const double v0 = d0 * dh[i], g1 = h1[i], g2 = h2[i], g3 = h3[i],
                       g4 = h4[i];
          const double v1 = v0 - c[1][0] * g1;
          const double v2 = v0 - c[2][0] * g1 - c[2][1] * g2;
          const double v3 = v0 - c[3][0] * g1 - c[3][1] * g2 - c[3][2] * g3;
          const double v4 = v0 - c[4][0] * g1 - c[4][1] * g2 - c[4][2] * g3
                            - c[4][3] * g4;
          /* fmax (e, |v|), inline: a NaN v leaves e */
          e0 = fabs (v0) > e0 ? fabs (v0) : e0;
          e1 = fabs (v1) > e1 ? fabs (v1) : e1;
          e2 = fabs (v2) > e2 ? fabs (v2) : e2;
          e3 = fabs (v3) > e3 ? fabs (v3) : e3;
          e4 = fabs (v4) > e4 ? fabs (v4) : e4;
        }
      e[0] = e0;
      e[1] = e1;
      e[2] = e2;
      e[3] = e3;
      e[4] = e4;
    }
  else
#endif
  for (int i = 0; i < N; i++)
    {
      double dl[SYM_SPVI_HIST + 1];
      for (int l = 0; l < nL; l++)
        dl[l] = dh[(size_t) l * N + i];
      const double v0 = d0 * dl[0];
      for (int L = 0; L < nL; L++)
        {
          double v = v0;
          for (int l = 0; l < L; l++)
            v -= c[L][l] * dl[l + 1];
          /* fmax (e, |v|), inline: a NaN v leaves e */
          if (fabs (v) > e[L])
            e[L] = fabs (v);
        }
    }
  int best_l = 0;
  double best = INFINITY;
  for (int L = 0; L < nL; L++)
    if (e[L] < best)
      {
        best = e[L];
        best_l = L;
      }
  const double *w = sym_extrap_weights (best_l);
  for (int l = 0; l < best_l; l++)
    for (int i = 0; i < N; i++)
      s->lo.x[i] += w[l] * s->dscale[l] * s->dhist[(size_t) l * N + i];
}

/* The accuracy of the solved a and P of r, by tol (pairs n - 1 = m) or
   the Newton tolerance */
void
spvi_rec_noise (const spvi_state *s, spvi_rec *r, double tol,
                const spvi_scale *S)
{
  const double e = fmax (s->n - 1 == s->m ? tol : s->tol, DBL_EPSILON);
  r->noise_q = e * S->q;
  r->noise_p = e * S->p;
}

/* A fixed step whose Newton failed from both starts (continued and
   Euler) is reached from shorter ones: the step h/2^k from the Euler
   start for the smallest k <= SYM_SPVI_HALVINGS that converges, then each
   solution's polynomials extended to twice its length (predict_poly)
   as the start of the step twice as long, up to h.  This follows the
   solution of the step equations that tends to the identity as h -> 0,
   where Newton from the Euler start, off by O(h |f'|), diverges.  On
   success the solution of (t, h) is in s->lo and tr->y1, its scales in
   *S. */
int
spvi_lengthen (spvi_state *s, sym_eval *ev, double t, double h,
               double tol, spvi_scale *S)
{
  spvi_rec *tr = s->trial;
  const int d = s->d, na = (s->n - 1) * d;
  const double *y = tr->y0;
  int k, st = SYM_NEWTON_FAIL;
  for (k = 1; k <= SYM_SPVI_HALVINGS && st == SYM_NEWTON_FAIL; k++)
    {
      st = spvi_predict (s, ev, t, ldexp (h, -k), y, 1, 0, S);
      if (! st)
        st = spvi_solve (&s->lo, ev, t, ldexp (h, -k), y, S, s, tol,
                         tr->y1);
    }
  /* solved h/2^(k-1); then h/2^(k-2), ..., h */
  for (k -= 2; ! st && k >= 0; k--)
    {
      memcpy (tr->a, s->lo.x, (size_t) na * sizeof (double));
      memcpy (tr->P, s->lo.x + na, (size_t) s->m * d * sizeof (double));
      spvi_rec_noise (s, tr, tol, S);
      predict_poly (s, tr, -1.0, 2.0, sym_norm_inf (2 * d, y));
      *S = start_scale (s, y, ldexp (h, -k), 0);
      st = spvi_solve (&s->lo, ev, t, ldexp (h, -k), y, S, s, tol,
                       tr->y1);
    }
  return st;
}
