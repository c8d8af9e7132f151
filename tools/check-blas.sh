#!/bin/bash
# Copyright (C) 2026 The symplectic developers
# SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.
#
# tools/check-blas.sh OCTAVE DEVPATH [full] -- the Octave tests under the
# BLAS kernels, LAPACK and libm variants other machines get: OpenBLAS's
# core types (OPENBLAS_CORETYPE; SkylakeX only where the CPU has
# AVX-512), Debian's reference BLAS and LAPACK (LD_LIBRARY_PATH), and
# glibc's libm without its FMA/AVX2 variants (GLIBC_TUNABLES).  Each
# configuration is checked to be in effect: the core OpenBLAS reports,
# the libraries mapped in /proc/self/maps.  Quick (default):
# tests/test_regression.m and the solvers' own tests; full: the whole
# Octave suite (run_tests), about 10 min a configuration.  CONFIGS (a
# space-separated list) runs only those configurations, in that order.
set -u
octave=$1
devpath=$2
mode=${3:-quick}
top=$(cd "$(dirname "$0")/.." && pwd)
multi=/usr/lib/x86_64-linux-gnu

if [ "$mode" = full ]; then
  body='exit (run_tests ());'
else
  body='n = 0; m = 0;
        for f = {"tests/test_regression.m", "inst/odeSE.m", "inst/odeSV.m", "inst/odeSPVI.m"}
          [a, b] = test (fullfile (top, f{1}), "quiet", stdout);
          printf ("%-30s pass %d/%d\n", f{1}, a, b);
          n += a;  m += b;
        endfor
        printf ("%d passed, %d failed\n", n, m - n);
        exit (n != m || m == 0);'
fi
code="top = '$top'; addpath ('$top/tests', '${devpath//:/\', \'}');
      maps = fileread ('/proc/self/maps');
      libs = unique (regexp (maps, '\S*lib(open)?(blas|lapack)\S*', 'match'));
      printf ('loaded: %s\n', strjoin (libs, ' '));
      $body"

configs=(Prescott Nehalem Sandybridge Haswell Zen SkylakeX reference-blas libm-sse2)
if [ -n "${CONFIGS:-}" ]; then
  read -r -a configs <<< "$CONFIGS"
fi
status=0
for c in "${configs[@]}"; do
  env=(OPENBLAS_VERBOSE=2)
  case $c in
    reference-blas) env+=(LD_LIBRARY_PATH=$multi/blas:$multi/lapack) ;;
    libm-sse2) env+=(GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2,-FMA,-FMA4,-AVX) ;;
    SkylakeX)
      if ! grep -q avx512f /proc/cpuinfo; then
        echo "== $c: skipped (this CPU has no AVX-512)"
        continue
      fi
      env+=(OPENBLAS_CORETYPE=$c) ;;
    *) env+=(OPENBLAS_CORETYPE=$c) ;;
  esac
  echo "== $c: ${env[*]}"
  start=$(date +%s)
  out=$(env "${env[@]}" "$octave" --norc --quiet --no-gui --eval "$code" 2>&1)
  st=$?
  echo "$out" | grep -v -E '^error: ignoring const execution_exception'
  # the configuration must be the one asked for
  case $c in
    reference-blas)
      echo "$out" | grep '^loaded:' | grep -q "$multi/blas/libblas" \
        && ! echo "$out" | grep '^loaded:' | grep -q openblas \
        || { echo "FAIL: $c: the reference BLAS is not the one loaded"; st=1; } ;;
    libm-sse2) ;;
    *) echo "$out" | grep -q "^Core: $c\$" \
         || { echo "FAIL: $c: OpenBLAS did not take core $c"; st=1; } ;;
  esac
  echo "== $c: exit $st, $(( $(date +%s) - start )) s"
  [ $st -eq 0 ] || status=1
done
[ $status -eq 0 ] && echo "check-blas: all configurations passed" \
  || echo "check-blas: FAILED"
exit $status
