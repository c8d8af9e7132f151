#!/bin/sh
# Copyright (C) 2026 The symplectic developers
# SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.
# check_memory.sh -- the MEX functions under valgrind (make check-memory).
#
#   tests/check_memory.sh [DIRS [OCTAVE]]
#
# DIRS: the directories of the solvers' m-files and of their MEX gateways,
# separated by ':' (default: inst/ and src/ of this tree).
#
# Runs tests/memcheck_run.m (a short tour of every solver, option, error
# and failure path) in octave-cli under valgrind's memcheck, then judges
# the log:
#
# * Errors whose stack involves our code -- the MEX files __odeSE__.mex,
#   __odeSV__.mex, __odeSPVI__.mex, or any function or source file of
#   src/core and src/mex (sym_*, symmex_*, mexFunction, run.c, driver.c,
#   ...) -- fail the check: invalid reads/writes/frees, uses of
#   uninitialised values, overlapping copies, bad syscall arguments.
# * Errors entirely inside Octave or the system libraries are Octave's own
#   noise: reported (counted), not failed.  tests/valgrind-octave.supp
#   silences the known ones (uninitialised-value reports from the
#   optimised BLAS/LAPACK kernels, which read past the data they use).
# * Leaks are not judged here: Octave keeps most of its memory until exit;
#   tests/test_leak.m checks that a failing call leaks nothing.
#
# Exit status 0 when the workload ran as expected and no error involves
# our code; 1 otherwise.  The full log is build/check-memory.log, Octave's
# output build/check-memory.out.
# Takes about 90 s (valgrind 3.19, one core of a 2-core VM).  Set
# VALGRIND_EXTRA=--track-origins=yes to see where uninitialised values
# come from (about 150 s).

here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
DIRS=${1:-$root/inst:$root/src}
OCTAVE=${2:-octave-cli}
VALGRIND=${VALGRIND:-valgrind}
log=$root/build/check-memory.log
out=$root/build/check-memory.out

command -v "$VALGRIND" >/dev/null 2>&1 || {
  echo "check-memory: valgrind not found (make deps, or apt-get install valgrind)"
  exit 1
}
mkdir -p "$root/build"
rm -f "$log"

# A distinct exit code for "valgrind found errors", so that it is not
# confused with the workload failing (exit 1) or Octave crashing.
VG_ERR=97
start=$(date +%s)
OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 \
"$VALGRIND" --tool=memcheck --error-exitcode=$VG_ERR --leak-check=no \
  --num-callers=40 $VALGRIND_EXTRA \
  --suppressions="$here/valgrind-octave.supp" --log-file="$log" \
  "$OCTAVE" --norc --quiet --no-gui --no-history \
  --eval "addpath ('$DIRS'); addpath ('$here'); exit (memcheck_run ())" \
  > "$out" 2>&1
rc=$?
secs=$(($(date +%s) - start))

# Split the log into error records (blank "==PID== " lines separate them)
# and count those whose stack mentions our code.
srcs=$(cd "$here/../src" && find . -name '*.c' -exec basename {} .c \; | sort -u | paste -sd'|')
ours="ode[A-Z]+(__)?\\.mex|mexFunction|symmex_|[^a-z_](sym|spvi)_[a-z_]+ |($srcs)\\.c:"
kinds='Invalid (read|write|free)|Conditional jump|Use of uninitialised|Syscall param|Mismatched free|Source and destination overlap|Argument .* of function|Uninitialised value'
report=$(awk -v ours="$ours" -v kinds="$kinds" '
  function flush() {
    if (rec != "" && rec ~ kinds) {
      if (rec ~ ours) {
        # the first 5 records, 16 lines each, go to the report
        if (++nours <= 5) {
          k = split (rec, line, "\n")
          for (i = 1; i <= k && i <= 17; i++) print line[i] > "/dev/stderr"
          if (k > 17) print "   ..." > "/dev/stderr"
        }
      }
      else nother++
    }
    rec = ""
  }
  /^==[0-9]+== *$/ { flush(); next }
  /^==[0-9]+== / { rec = rec "\n" $0 }
  END { flush(); printf "%d %d\n", nours + 0, nother + 0 }
' "$log" 2>"$log.ours")
set -- $report
nours=$1
nother=$2
summary=$(grep "ERROR SUMMARY" "$log" | tail -n 1 | sed 's/^==[0-9]*== //')

echo "check-memory: valgrind run took ${secs} s (exit status $rc); ${summary:-no summary}"
status=0
if [ "$nours" -gt 0 ]; then
  echo "check-memory: FAIL: $nours error(s) in our code (the first ones; all in $log):"
  cat "$log.ours"
  status=1
fi
if [ "$nother" -gt 0 ]; then
  echo "check-memory: $nother error(s) inside Octave or its libraries only (not ours; see $log)"
fi
case $rc in
  0|$VG_ERR) ;;   # valgrind's errors: judged above
  *)
    echo "check-memory: FAIL: the workload under valgrind exited with status $rc"
    tail -n 20 "$log"
    status=1 ;;
esac
if ! grep -q "memcheck_run: 0 unexpected results" "$out"; then
  echo "check-memory: FAIL: the workload did not run as expected:"
  cat "$out"
  status=1
fi
if ! grep -q "ERROR SUMMARY" "$log"; then
  echo "check-memory: FAIL: valgrind did not finish (no ERROR SUMMARY in $log)"
  status=1
fi
rm -f "$log.ours"
[ $status -eq 0 ] && echo "check-memory: passed (no memory error in odeSE, odeSV, odeSPVI)"
exit $status
