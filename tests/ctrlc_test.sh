#!/bin/sh
# Copyright (C) 2026 The symplectic developers
# SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.
# ctrlc_test.sh -- Ctrl-C (SIGINT) during a long integration must bring an
# interactive Octave back to its prompt, still working.
#
#   tests/ctrlc_test.sh [DIRS [OCTAVE]]
#
# DIRS: the directories of the solvers' m-files (odeSE.m, ...) and of
# their MEX gateways (__odeSE__.mex, ...), separated by ':' (default: the
# inst/ and src/ beside this script's directory); OCTAVE: the octave-cli
# to run (default octave-cli).  Run by tests/test_ctrlc.m (so by make
# check); exit status 0 when every scenario passed.
#
# Each scenario starts octave-cli --interactive reading commands from a
# FIFO (a real prompt, as at a terminal, without needing one: without
# --interactive Octave quits on SIGINT instead of returning to the
# prompt), sends it a command that would run for days, sends SIGINT after
# about 2 s, then asks it to integrate a small problem and print a marker,
# and to exit with status 7.  Octave that hangs more than LIMIT seconds is
# killed (by its process id) and the scenario fails.

here=$(cd "$(dirname "$0")" && pwd)
DIRS=${1:-$here/../inst:$here/../src}
OCTAVE=${2:-octave-cli}
LIMIT=${CTRLC_LIMIT:-30}

tmp=$(mktemp -d) || exit 1
octpid=
cleanup () {
  if [ -n "$octpid" ]; then kill -KILL "$octpid" 2>/dev/null; fi
  rm -rf "$tmp"
}
trap cleanup EXIT

# wait_for FILE PATTERN SECONDS: 0 when PATTERN shows up in FILE in time
wait_for () {
  i=0
  while [ "$i" -lt $(($3 * 10)) ]; do
    grep -q "$2" "$1" 2>/dev/null && return 0
    sleep 0.1
    i=$((i + 1))
  done
  return 1
}

fail=0
run_scenario () {   # NAME COMMAND
  name=$1
  log=$tmp/$name.log
  fifo=$tmp/$name.fifo
  mkfifo "$fifo" || return 1
  OPENBLAS_NUM_THREADS=1 "$OCTAVE" --norc --quiet --no-gui --no-history \
    --interactive < "$fifo" > "$log" 2>&1 &
  octpid=$!
  exec 3> "$fifo"
  printf '%s\n' "addpath ('$DIRS'); f = @(t, y) [y(2); -y(1)]; printf ('READY\\n'); fflush (stdout);" >&3
  if ! wait_for "$log" READY "$LIMIT"; then
    echo "ctrlc_test: $name: Octave did not start"; cat "$log"
    exec 3>&-; kill -KILL "$octpid" 2>/dev/null; wait "$octpid" 2>/dev/null
    octpid=; fail=1; return
  fi
  # RUNNING: the command has started (so SIGINT cannot hit the prompt);
  # tic: the marker line says how long the interrupted command ran
  printf '%s\n' "printf ('RUNNING\\n'); fflush (stdout); tic; $2" >&3
  if ! wait_for "$log" RUNNING "$LIMIT"; then
    echo "ctrlc_test: $name: FAIL: the command did not start"; cat "$log"
    exec 3>&-; kill -KILL "$octpid" 2>/dev/null; wait "$octpid" 2>/dev/null
    octpid=; fail=1; return
  fi
  sleep 2
  kill -INT "$octpid"
  printf '%s\n' "el = toc; [tt, yy] = odeSPVI (f, [0 1], [1 0]); ok = abs (yy(end,1) - cos (1)) < 1e-2 && ! exist ('t_never', 'var'); printf ('MARKER %d after %.1f s\\n', ok, el); fflush (stdout); exit (7);" >&3
  exec 3>&-
  # Octave must print the marker and exit by itself within LIMIT seconds
  i=0
  while kill -0 "$octpid" 2>/dev/null && [ "$i" -lt $((LIMIT * 10)) ]; do
    sleep 0.1
    i=$((i + 1))
  done
  if kill -0 "$octpid" 2>/dev/null; then
    echo "ctrlc_test: $name: FAIL: Octave still running ${LIMIT} s after SIGINT (killed)"
    kill -KILL "$octpid" 2>/dev/null
    wait "$octpid" 2>/dev/null
    octpid=; cat "$log"; fail=1; return
  fi
  wait "$octpid"; rc=$?
  octpid=
  if [ "$rc" -eq 7 ] && grep -q "MARKER 1 after" "$log"; then
    echo "ctrlc_test: $name: ok ($(grep -o 'MARKER 1 after [0-9.]* s' "$log"))"
  else
    echo "ctrlc_test: $name: FAIL (exit status $rc, expected 7 and MARKER 1)"
    cat "$log"
    fail=1
  fi
}

# one long fixed-step run (1e11 steps): SIGINT arrives inside the MEX
# function, in a callback of FCN
run_scenario spvi_fixed "t_never = odeSPVI (f, [0 1e9], [1 0], struct ('TimeStepSize', 0.01));"
# one long adaptive run of each of the other solvers
run_scenario se_adaptive "t_never = odeSE (f, [0 1e9], [1 0]);"
run_scenario sv_events "t_never = odeSV (f, [0 1e9], [1 0], struct ('TimeStepSize', 0.01, 'Events', @(t, y) deal (y(1), 0, 0)));"
# with an OutputFcn and the Jacobian from a function: SIGINT may land in
# any of the three callbacks
run_scenario spvi_outputfcn "t_never = odeSPVI (f, [0 1e9], [1 0], struct ('TimeStepSize', 0.01, 'OutputFcn', @(t, y, flag) false, 'Jacobian', @(t, y) [0 1; -1 0]));"
# many short calls in a loop: SIGINT lands anywhere (also between calls)
run_scenario loop "while (true) [~, ~] = odeSPVI (f, [0 10], [1 0]); [~, ~] = odeSE (f, [0 10], [1 0]); endwhile; t_never = 1;"

exit $fail
