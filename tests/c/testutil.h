/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* testutil.h -- a minimal check harness for the C tests of the core.
   Each test program counts its checks and ends with
   "<name>: N passed, M failed"; it exits non-zero when M > 0. */
#ifndef SYM_TESTUTIL_H
#define SYM_TESTUTIL_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static int tu_pass = 0, tu_fail = 0;

#define CHECK(cond, ...)                                                  \
  do {                                                                    \
    if (cond)                                                             \
      tu_pass++;                                                          \
    else                                                                  \
      {                                                                   \
        tu_fail++;                                                        \
        fprintf (stderr, "FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond);  \
        fprintf (stderr, __VA_ARGS__);                                    \
        fputc ('\n', stderr);                                             \
      }                                                                   \
  } while (0)

/* |a - b| <= tol, printing both on failure */
#define CHECK_CLOSE(a, b, tol, what)                                      \
  do {                                                                    \
    double tu_a = (a), tu_b = (b);                                        \
    CHECK (fabs (tu_a - tu_b) <= (tol), "%s: %.17g vs %.17g (diff %.3g, " \
           "tol %.3g)", what, tu_a, tu_b, fabs (tu_a - tu_b),             \
           (double) (tol));                                               \
  } while (0)

static int
tu_finish (const char *name)
{
  printf ("%s: %d passed, %d failed\n", name, tu_pass, tu_fail);
  return tu_fail ? 1 : 0;
}

#endif
