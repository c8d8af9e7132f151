/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* splittings.c -- the composition and splitting methods of odeSV, as
   data (sym.h: sym_splitting).  Coefficients from the published values
   (closed forms evaluated to 20 digits, the rest to 17 significant
   digits, which fix a double), each with its source.
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

/* W. Kahan and R.-C. Li, "Composition constants for raising the orders
   of unconventional schemes for ordinary differential equations", Math.
   Comp. 66 (1997) 1089-1099: s9odr6a (published to 26 digits). */
static const double kahanli6[] = {
  0.39216144400731414, 0.33259913678935944, -0.70624617255763936,
  0.082213596293550800, 0.79854399093482996, 0.082213596293550800,
  -0.70624617255763936, 0.33259913678935944, 0.39216144400731414
};

/* Kahan and Li (1997), as above: s17odr8a. */
static const double kahanli8[] = {
  0.13020248308889008, 0.56116298177510838, -0.38947496264484729,
  0.15884190655515560, -0.39590389413323758, 0.18453964097831571,
  0.25837438768632205, 0.29501172360931030, -0.60550853383003451,
  0.29501172360931030, 0.25837438768632205, 0.18453964097831571,
  -0.39590389413323758, 0.15884190655515560, -0.38947496264484729,
  0.56116298177510838, 0.13020248308889008
};

/* R. I. McLachlan, "On the numerical integration of ordinary
   differential equations by symmetric composition methods", SIAM J.
   Sci. Comput. 16 (1995) 151-168: order 8, 15 stages. */
static const double mclachlan8[] = {
  0.74167036435061295, -0.40910082580003159, 0.19075471029623838,
  -0.57386247111608227, 0.29906418130365592, 0.33462491824529818,
  0.31529309239676660, -0.79688793935291635, 0.31529309239676660,
  0.33462491824529818, 0.29906418130365592, -0.57386247111608227,
  0.19075471029623838, -0.40910082580003159, 0.74167036435061295
};

/* M. Sofroniou and G. Spaletta, "Derivation of symmetric composition
   constants for symmetric integrators", Optim. Methods Softw. 20 (2005)
   597-613: order 10, 35 stages. */
static const double sofspa10[] = {
  0.078795722521686419, 0.31309610341510853, 0.027918383235078066,
  -0.22959284159390709, 0.13096206107716486, -0.26973340565451071,
  0.074973343155891436, 0.11199342399981020, 0.36613344954622675,
  -0.39910563013603590, 0.10308739852747108, 0.41143087395589024,
  -0.0048663605831352618, -0.39203335370863991, 0.051942502962449647,
  0.050665090759924496, 0.049674370639729879, 0.049317735759594538,
  0.049674370639729879, 0.050665090759924496, 0.051942502962449647,
  -0.39203335370863991, -0.0048663605831352618, 0.41143087395589024,
  0.10308739852747108, -0.39910563013603590, 0.36613344954622675,
  0.11199342399981020, 0.074973343155891436, -0.26973340565451071,
  0.13096206107716486, -0.22959284159390709, 0.027918383235078066,
  0.31309610341510853, 0.078795722521686419
};

/* R. D. Ruth, "A canonical integration technique", IEEE Trans. Nucl.
   Sci. NS-30 (1983) 2669-2671: a = (2/3, -2/3, 1), b = (7/24, 3/4,
   -1/24). */
static const double ruth3[] = {
  2.0 / 3.0, -2.0 / 3.0, 1.0,
  7.0 / 24.0, 3.0 / 4.0, -1.0 / 24.0
};

/* J. Candy and W. Rozmus, "A symplectic integration algorithm for
   separable Hamiltonian functions", J. Comput. Phys. 92 (1991) 230-256
   (also E. Forest and R. D. Ruth, Physica D 43 (1990) 105-117): with c =
   2^(1/3), a = ((2 + c + 1/c)/6, (1 - c - 1/c)/6, (1 - c - 1/c)/6, (2 + c
   + 1/c)/6), b = (0, 1/(2 - c), 1/(1 - c^2), 1/(2 - c)): it begins with
   a drift. */
static const double candyrozmus4[] = {
  0.67560359597982882, -0.17560359597982882, -0.17560359597982882,
  0.67560359597982882,
  0.0, 1.3512071919596576, -1.7024143839193153, 1.3512071919596576
};

/* R. I. McLachlan and P. Atela, "The accuracy of symplectic
   integrators", Nonlinearity 5 (1992) 541-562: their optimal 4-stage
   method of order 4 (published to 19 digits), a Nystrom method (order 4
   for T quadratic in p, 3 otherwise), not symmetric. */
static const double mclachlan4[] = {
  0.51535283743112294, -0.085782019412973646, 0.44158302361646652,
  0.12884615836538419,
  0.13449619927743109, -0.22481980307942081, 0.75632000051566829,
  0.33400360328632143
};

/* S. Blanes and P. C. Moan, "Practical symplectic partitioned
   Runge-Kutta and Runge-Kutta-Nystrom methods", J. Comput. Appl. Math.
   142 (2002) 313-330: SRKN_11^b, order 6 for T quadratic in p (4
   otherwise), 11 forces a step.  Published to 15 digits; b_6 = 1/2 -
   (b_1 + ... + b_5) and a_6 = 1 - 2 (a_1 + ... + a_5) from the
   consistency conditions. */
static const double blanesmoan6[] = {
  0.12322977594627100, 0.29055379779955800, -0.12704921262541700,
  -0.24633176106207500, 0.35720887279592800, 0.20477705429147000,
  0.35720887279592800, -0.24633176106207500, -0.12704921262541700,
  0.29055379779955800, 0.12322977594627100, 0.0,
  0.041464998518262400, 0.19812867191806700, -0.040006192104153300,
  0.075253984301580700, -0.011511387420687900, 0.23666992478693110,
  0.23666992478693110, -0.011511387420687900, 0.075253984301580700,
  -0.040006192104153300, 0.19812867191806700, 0.041464998518262400
};

const sym_splitting sym_splittings[] = {
  { "verlet", SYM_COMPOSITION, 2, 1, 1, verlet },
  { "yoshida4", SYM_COMPOSITION, 4, 1, 3, yoshida4 },
  { "suzuki4", SYM_COMPOSITION, 4, 1, 5, suzuki4 },
  { "kahanli6", SYM_COMPOSITION, 6, 1, 9, kahanli6 },
  { "kahanli8", SYM_COMPOSITION, 8, 1, 17, kahanli8 },
  { "mclachlan8", SYM_COMPOSITION, 8, 1, 15, mclachlan8 },
  { "sofspa10", SYM_COMPOSITION, 10, 1, 35, sofspa10 },
  { "ruth3", SYM_SPLITTING, 3, 0, 3, ruth3 },
  { "candyrozmus4", SYM_SPLITTING, 4, 1, 4, candyrozmus4 },
  { "mclachlan4", SYM_SPLITTING, 4, 0, 4, mclachlan4 },
  { "blanesmoan6", SYM_SPLITTING, 6, 1, 12, blanesmoan6 },
  { NULL, 0, 0, 0, 0, NULL }
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
