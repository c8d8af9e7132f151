/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* dense.c -- odeSPVI's continuous output on the last accepted step.

   The pairs n - 1 = m: y_k plus the integral of the polynomial through
   dy/dz at -1, at the nodes of the solve the run advances with (the
   method's, or the companion's in adaptive runs) and at +1, with f
   evaluated at the step's ends when first needed (f at the end of one
   step is f at the start of the next).  The node values are off by
   O(h^(M+1)) for M nodes, so the local error is O(h^(M+2)), against
   O(h^(m+1)) for the solution's own polynomials.  By Gauss orthogonality
   the integral over the step is the quadrature that gave y_{k+1}; the end
   mismatch (round-off, and O(h^3) for (2,1)) is spread linearly, so the
   output ends on the step's value.  The other pairs of order below 8: the
   cubic Hermite interpolant through the step's ends, O(h^min(4, order))
   (their solution's polynomials are only O(h^(order/2))).  Without f at
   an end (NaN there), and for the other pairs of order 8 and more: q from
   the Legendre series of the step, p from the polynomial through (-1,
   p_k), (z_j, P_j), (1, p_{k+1}); an adaptive step's q gets the linear
   correction (z+1)/2 (q_companion - q_low)(1), so that it ends on the
   step's value. */
#include "spvi.h"

#include <math.h>
#include <string.h>

/* The dense output's data from the solve c (at its final x) into r: the
   nodes' dy/dz, dq/dz from the q polynomial and dp/dz = h/2 f_p (moved
   to the final x by core_solve).  The ends are not known yet. */
void
spvi_rec_nodes (spvi_rec *r, const spvi_core *c)
{
  const int d = c->d, n = c->n, m = c->m;
  const size_t nn = 2 * (size_t) d;
  const double hh = 0.5 * c->h;
  for (int j = 0; j < m; j++)
    {
      double *Dj = r->D + (size_t) (j + 1) * nn;
      for (int k = 0; k < d; k++)
        {
          double v = 0.0;
          for (int i = 1; i < n; i++)
            v += c->dl[j * n + i] * c->x[(size_t) (i - 1) * d + k];
          Dj[k] = v;
          Dj[d + k] = hh * c->F[(size_t) j * nn + d + k];
        }
    }
  r->M = m;
}

/* dy/dz at the ends of r, from f there (one call each when not known) */
static int
rec_ends (spvi_rec *r, sym_eval *ev, int d)
{
  const size_t nn = 2 * (size_t) d;
  const double hh = 0.5 * r->h;
  int st;
  if ((st = sym_rhs_once (ev, r->t, r->y0, r->fe0, &r->have_fe0))
      || (st = sym_rhs_once (ev, r->tend, r->y1, r->fe1, &r->have_fe1)))
    return st;
  for (size_t i = 0; r->M > 0 && i < nn; i++)
    {
      r->D[i] = hh * r->fe0[i];
      r->D[(size_t) (r->M + 1) * nn + i] = hh * r->fe1[i];
    }
  return SYM_SUCCESS;
}

/* u = the integral from -1 to z of the polynomial through r's dy/dz at
   -1, its M nodes and +1 (Gauss quadrature, exact: the degree is M + 1
   <= m + 2) */
static void
rec_integral (const spvi_state *s, const spvi_rec *r, double z, double *u)
{
  const spvi_core *c = r->M == s->m ? &s->lo : &s->hi;
  const int np = r->M + 2;
  const size_t nn = 2 * (size_t) s->d;
  const double half = 0.5 * (z + 1.0);
  memset (u, 0, nn * sizeof (double));
  for (int g = 0; g < s->ng; g++)
    {
      sym_lagrange_basis (np, c->xb, c->bw, -1.0 + half * (s->gz[g] + 1.0),
                      s->cb);
      for (int i = 0; i < np; i++)
        {
          const double wgt = half * s->gw[g] * s->cb[i];
          const double *Di = r->D + (size_t) i * nn;
          for (size_t k = 0; k < nn; k++)
            u[k] += wgt * Di[k];
        }
    }
}

int
spvi_dense (void *state, sym_eval *ev, double t, double *y)
{
  spvi_state *s = state;
  const int d = s->d;
  spvi_rec *r = s->cur;
  /* (no data for it without want_dense at alloc) */
  if (! s->have_cur || ! r->D)
    return SYM_EBADINPUT;
  if (t == r->t)
    {
      memcpy (y, r->y0, 2 * (size_t) d * sizeof (double));
      return SYM_SUCCESS;
    }
  if (t == r->tend)
    {
      memcpy (y, r->y1, 2 * (size_t) d * sizeof (double));
      return SYM_SUCCESS;
    }
  double z = 2.0 * (t - r->t) / r->h - 1.0;
  if (! r->ends_bad && (r->M > 0 || s->hermite))
    {
      int st = rec_ends (r, ev, d);
      if (st < 0)
        return st;        /* a fatal callback status ends the run */
      if (st == SYM_SUCCESS && r->M == 0)
        {
          /* the other pairs: cubic Hermite through the step's ends */
          sym_hermite (2 * d, r->h, 0.5 * (z + 1.0), r->y0, r->y1, r->fe0,
                       r->fe1, y);
          return SYM_SUCCESS;
        }
      if (st == SYM_SUCCESS)
        {
          if (! r->have_emis)
            {
              rec_integral (s, r, 1.0, r->emis);
              for (int k = 0; k < 2 * d; k++)
                r->emis[k] = r->y1[k] - r->y0[k] - r->emis[k];
              r->have_emis = 1;
            }
          rec_integral (s, r, z, y);
          for (int k = 0; k < 2 * d; k++)
            y[k] += r->y0[k] + 0.5 * (z + 1.0) * r->emis[k];
          return SYM_SUCCESS;
        }
      /* f is NaN or Inf at an end of the step (it may be beyond a
         singularity that no node reached): this step's dense output is
         then its solution's own polynomials */
      r->ends_bad = 1;
    }
  spvi_modes_dq (s, r->a, z, y);
  for (int k = 0; k < d; k++)
    y[k] += r->y0[k] + (r->has_dq ? 0.5 * (z + 1.0) * r->dq[k] : 0.0);
  spvi_rec_p (s, r, z, y + d);
  return SYM_SUCCESS;
}
