#!/bin/sh
# Copyright (C) 2026 The symplectic developers
# SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.
#
# tools/block-rss.sh FILE [OCTAVE] -- the peak resident memory and time
# of each test block of FILE (an m-file of %! blocks), each run alone in
# a child Octave (with the file's %!shared and %!function blocks) under
# /usr/bin/time -v.  Run from the top of the tree after make; one block
# at a time, so that a heavy block shows alone.  Prints one line a block:
# "block N (line L): RSS MB, S s, pass|FAIL: first line".
set -eu
file=$1
octave=${2:-octave-cli}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# split into blocks: a block starts at a line "%!word"; shared and
# function blocks go with every test block
awk -v dir="$tmp" '
  /^%![a-z]/ { n++; kind = $0; sub(/^%!/, "", kind); sub(/[ (<].*/, "", kind);
               line[n] = NR; isctx[n] = (kind == "shared" || kind == "function" || kind == "endfunction") }
  /^%!/ && n > 0 { text[n] = text[n] $0 "\n" }
  END {
    for (i = 1; i <= n; i++) if (isctx[i]) ctx = ctx text[i];
    for (i = 1; i <= n; i++) if (! isctx[i]) {
      k++; f = sprintf ("%s/blk%03d_L%d.m", dir, k, line[i]);
      printf "%s", ctx text[i] > f; close (f) }
  }' "$file"
for b in "$tmp"/blk*.m; do
  base=$(basename "$b" .m)
  /usr/bin/time -v -o "$tmp/time" "$octave" --norc --quiet --no-gui --eval \
    "addpath ('inst', 'src', 'tests'); [n, m] = test ('$b', 'quiet', stdout); exit (n != m);" \
    > "$tmp/out" 2>&1 && res=pass || res=FAIL
  rss=$(sed -n 's/.*Maximum resident set size (kbytes): //p' "$tmp/time")
  wall=$(sed -n 's/.*Elapsed (wall clock) time (h:mm:ss or m:ss): //p' "$tmp/time")
  head=$(sed -n '1,/^%!/{/^%![a-z]/{n;p;q}}' "$b" | head -n 1)
  first=$(grep -v -E '^%!(shared|function|endfunction| )' "$b" | head -n 2 | tail -n 1)
  printf "%s: %6d MB, %s, %s: %s\n" "$base" $((rss / 1024)) "$wall" "$res" \
    "$(echo "$first" | cut -c 1-70)"
done
