#!/bin/sh
# Copyright (C) 2026 The symplectic developers
# SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.
# tools/install-deps.sh -- make sure the build and test dependencies are
# present; install the missing ones from Debian's packages.
#
#   sh tools/install-deps.sh           (make deps)
#   sh tools/install-deps.sh memory    (make deps-memory)
#
# Checks: octave-cli, mkoctfile, a C compiler that links against LAPACK,
# BLAS and KLU (SuiteSparse, for sparse Jacobians), Octave's parallel
# package (pkg load parallel: the option Parallel and its tests), its
# symbolic package (pkg load symbolic, with SymPy: symhamiltonian,
# symlagrangian and their tests; optional for users); with
# `memory`, valgrind too (only make check-memory and make valgrind need
# it).  When all are there it only checks (quick, no network); otherwise
# it runs apt-get update + apt-get install once for the whole set (as
# root, or through sudo when not root and sudo exists).
#
# Environment: SYM_DEPS_FORCE=1 installs even if everything looks present.
set -eu

PACKAGES="octave octave-dev liblapack-dev libblas-dev libsuitesparse-dev octave-parallel octave-symbolic"
TOOLS="octave-cli mkoctfile"
case "${1:-}" in
  "") ;;
  memory)
    PACKAGES="$PACKAGES valgrind"
    TOOLS="$TOOLS valgrind" ;;
  *)
    echo "usage: sh tools/install-deps.sh [memory]" >&2
    exit 2 ;;
esac

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# Sets $missing to what is absent (empty when all is there).
check () {
  missing=""
  for c in $TOOLS; do
    command -v "$c" >/dev/null 2>&1 || missing="$missing $c"
  done
  # LAPACK/BLAS dev libraries: check that a program links with them (file
  # names vary with the BLAS alternative in use; a link test does not).
  cc=$(command -v cc || command -v gcc || true)
  if [ -z "$cc" ]; then
    missing="$missing cc"
  else
    printf 'void dgetrf_(void);\nint main(void){dgetrf_();return 0;}\n' > "$tmp/t.c"
    "$cc" "$tmp/t.c" -o "$tmp/t" -llapack -lblas >/dev/null 2>&1 \
      || missing="$missing liblapack-dev/libblas-dev"
    printf '#include <suitesparse/klu.h>\nint main(void){klu_common c;return klu_defaults(&c)!=1;}\n' > "$tmp/k.c"
    "$cc" "$tmp/k.c" -o "$tmp/k" -lklu -lsuitesparseconfig >/dev/null 2>&1 \
      || missing="$missing libsuitesparse-dev"
  fi
  # the parallel package: that Octave can load it (it may also come from
  # pkg install -forge, not from Debian)
  if command -v octave-cli >/dev/null 2>&1; then
    octave-cli --norc --no-gui --eval "pkg load parallel" </dev/null \
      >/dev/null 2>&1 || missing="$missing octave-parallel"
    octave-cli --norc --no-gui --eval "pkg load symbolic; sym ('x');" </dev/null \
      >/dev/null 2>&1 || missing="$missing octave-symbolic"
  fi
}

check
if [ -z "$missing" ] && [ "${SYM_DEPS_FORCE:-0}" != 1 ]; then
  echo "deps: ok ($(echo $TOOLS | sed 's/ /, /g'), LAPACK/BLAS, KLU, the parallel and symbolic packages present)"
  exit 0
fi

echo "deps: missing:${missing:- nothing (SYM_DEPS_FORCE=1)}"
if [ "$(id -u)" -eq 0 ]; then
  SUDO=""
elif command -v sudo >/dev/null 2>&1; then
  SUDO="sudo"
else
  echo "deps: not root and no sudo; as root run: apt-get install $PACKAGES" >&2
  exit 1
fi
if ! command -v apt-get >/dev/null 2>&1; then
  echo "deps: apt-get not found (not Debian?); install: $PACKAGES" >&2
  exit 1
fi

echo "deps: installing $PACKAGES"
# sudo does not pass the environment by default: set it on the command line.
$SUDO env DEBIAN_FRONTEND=noninteractive apt-get update
$SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y $PACKAGES

# Re-check, so a broken install fails here and not later in the build.
check
if [ -n "$missing" ]; then
  echo "deps: still missing after apt-get install:$missing" >&2
  exit 1
fi
echo "deps: ok"
