/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* splittings.c -- the composition and splitting methods of odeSV, as
   data (sym.h: sym_splitting).  Coefficients from the published values
   to 20 digits (the compiler rounds them), each with its source.
   Compositions list all gamma_i of their Stoermer-Verlet steps;
   splittings their drifts a_1..a_s and then their kicks b_1..b_s, kick
   first (p += b_i h f_p, then q += a_i h f_q). */
#include "../sym.h"

#include <ctype.h>

/* Stoermer-Verlet itself */
static const double verlet[] = { 1.0 };

/* H. Yoshida, "Construction of higher order symplectic integrators",
   Phys. Lett. A 150 (1990) 262-268: the triple jump, gamma_1 = gamma_3 =
   1/(2 - 2^(1/3)), gamma_2 = -2^(1/3)/(2 - 2^(1/3)). */
static const double yoshida4[] = {
  1.3512071919596576340, -1.7024143839193152681, 1.3512071919596576340
};

/* M. Suzuki, "Fractal decomposition of exponential operators with
   applications to many-body theories and Monte Carlo simulations",
   Phys. Lett. A 146 (1990) 319-323: p = 1/(4 - 4^(1/3)), (p, p, 1 - 4p,
   p, p). */
static const double suzuki4[] = {
  0.41449077179437573714, 0.41449077179437573714, -0.65796308717750294857,
  0.41449077179437573714, 0.41449077179437573714
};

const sym_splitting sym_splittings[] = {
  { "verlet", SYM_COMPOSITION, 2, 1, 1, verlet, 0 },
  { "yoshida4", SYM_COMPOSITION, 4, 1, 3, yoshida4, 0 },
  { "suzuki4", SYM_COMPOSITION, 4, 1, 5, suzuki4, 0 },
  { NULL, 0, 0, 0, 0, NULL, 0 }
};

int
sym_splitting_find (const char *name)
{
  for (int k = 0; name && sym_splittings[k].name; k++)
    {
      const char *a = name, *b = sym_splittings[k].name;
      while (*a && tolower ((unsigned char) *a) == *b)
        a++, b++;
      if (! *a && ! *b)
        return k;
    }
  return -1;
}
