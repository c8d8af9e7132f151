#!/bin/sh
# Copyright (C) 2026 The symplectic developers
# SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.
# p3_profile.sh -- P3 by sampling instead of timing: the solver's time
# (samples under symmex_run, which each gateway's mexFunction calls last,
# so that mexFunction may be gone from the stack as a tail call) over the
# time of its calls of the user's function (samples under mexCallMATLAB,
# all of a call: the arguments in, the function, the results out).  Both
# come from one run, so the load of the machine, which drifts by tens of
# per cent over seconds, largely cancels.  Needs perf; prints a line
# either way, fails never.
# The stacks are unwound from copies of 64 KiB (the most perf takes): with
# 16 KiB a run once counted fewer samples under the solver than under its
# calls of fcn, which run inside it.
#
#   sh bench/p3_profile.sh      (from the top directory, after make)

here=$(cd "$(dirname "$0")" && pwd)
top=$(dirname "$here")
OCTAVE=${OCTAVE:-octave-cli}
if ! command -v perf > /dev/null 2>&1; then
  echo "p3_profile: perf not found: skipped"
  exit 0
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
if ! perf record -q --call-graph dwarf,65528 -F 1000 -o "$tmp/perf.data" \
     "$OCTAVE" --norc --no-gui --path "$top/inst:$top/src" "$here/p3_run.m" \
     > "$tmp/out" 2>&1; then
  echo "p3_profile: perf record failed: skipped"
  exit 0
fi
perf report -i "$tmp/perf.data" --children --sort sym -g none 2> /dev/null \
  > "$tmp/report"
awk '$NF == "symmex_run" && ! m { m = $1 + 0 }
     $NF == "mexCallMATLAB" && ! c { c = $1 + 0 }
     END {
       if (c > m)
         # a call of fcn runs inside the solver: more samples under the
         # call than under the solver means stacks were cut short
         printf "p3_profile: %.1f%% of samples under the calls of fcn but %.1f%% under the solver (stacks cut short): skipped\n", c, m;
       else if (m > 0 && c > 0)
         printf "p3_profile: solver %.1f%% of samples, its calls of fcn %.1f%%: wall / callback time = %.3f\n", m, c, m / c;
       else
         print "p3_profile: no samples under symmex_run: skipped"
     }' "$tmp/report"
