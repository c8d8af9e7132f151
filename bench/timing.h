/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* timing.h -- the benchmarks' clock and the order of their times, one
   copy for the C programs of bench/ (static inline: a header alone,
   nothing more to compile or link in the commands that build them).
   clock_gettime is POSIX: a program built -std=c99 defines
   _POSIX_C_SOURCE 199309L before its first header. */
#ifndef BENCH_TIMING_H
#define BENCH_TIMING_H

#include <stdlib.h>
#include <time.h>

/* seconds on the monotonic clock */
static inline double
now (void)
{
  struct timespec ts;
  clock_gettime (CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

/* qsort's comparison of two doubles, ascending */
static inline int
cmp_double (const void *a, const void *b)
{
  const double x = *(const double *) a, y = *(const double *) b;
  return (x > y) - (x < y);
}

/* the median of t[0..n-1], n >= 1; t is left sorted */
static inline double
median (double *t, int n)
{
  qsort (t, (size_t) n, sizeof t[0], cmp_double);
  return n % 2 ? t[n / 2] : 0.5 * (t[n / 2 - 1] + t[n / 2]);
}

#endif
