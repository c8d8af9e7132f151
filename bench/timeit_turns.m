## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## [t, tab] = timeit_turns (fs, minsec, minrounds)
##
## The best time of each function in the cell fs, run in turns (a, b,
## ..., a, b, ...) for at least minsec seconds in all and at least
## minrounds rounds (default 2): the load of the machine drifts over
## seconds, and a ratio of two times is only fair when both saw it.  tab:
## every time, one row per round.  The functions are called with one
## output (with none the solvers would plot).

function [t, tab] = timeit_turns (fs, minsec, minrounds = 2)
  n = numel (fs);
  tab = zeros (0, n);  tot = 0;
  while (tot < minsec || rows (tab) < minrounds)
    tab(end+1, :) = 0;
    for i = 1:n
      tic;  r = fs{i} ();  el = toc;
      tab(end, i) = el;  tot += el;
    endfor
  endwhile
  t = min (tab, [], 1);
endfunction
