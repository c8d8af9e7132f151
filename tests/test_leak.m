## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## An error thrown by the user's function in the middle of a run leaves
## the MEX function through mexCallMATLAB, without coming back: everything
## the run holds must be freed by Octave then (mxMalloc / mxCreate*).
## 1000 such calls (the three solvers; errors from FCN, the Hessian, the
## Jacobian, the Events and the OutputFcn functions, in adaptive and
## fixed-step runs, with long and short output buffers) must leave Octave's
## resident memory (VmRSS of /proc/self/status) within 10 MB of where it
## was after a warm-up.  Linux only (skipped elsewhere).

%!function dy = leak_rhs (t, y, tfail)
%!  if (t > tfail)
%!    error ("leaktest:boom", "leak test: failing at t = %g", t);
%!  endif
%!  d = numel (y) / 2;
%!  dy = [y(d+1:end); -y(1:d)];
%!endfunction

%!function h = leak_hess (t, y, tfail)
%!  if (t > tfail)
%!    error ("leaktest:hess", "leak test: Hessian failing at t = %g", t);
%!  endif
%!  h = eye (numel (y));
%!endfunction

%!function [v, term, dir] = leak_events (t, y, tfail)
%!  if (t > tfail)
%!    error ("leaktest:event", "leak test: event failing at t = %g", t);
%!  endif
%!  v = y(1);  term = 0;  dir = 0;
%!endfunction

%!function stop = leak_output (t, y, flag, tfail)
%!  stop = false;
%!  if (strcmp (flag, "") && t(end) > tfail)
%!    error ("leaktest:output", "leak test: OutputFcn failing at t = %g", t(end));
%!  endif
%!endfunction

%!function kb = leak_rss_kb ()
%!  s = fileread ("/proc/self/status");
%!  tok = regexp (s, 'VmRSS:\s*(\d+)\s*kB', "tokens", "once");
%!  kb = str2double (tok{1});
%!endfunction

## One batch of 100 failing calls (all kinds); returns how many failed
## with the expected identifier.
%!function nok = leak_batch ()
%!  solvers = {@odeSE, @odeSV, @odeSPVI};
%!  y0 = [linspace(1, 0.5, 10), zeros(1, 10)]';   # d = 10: sizeable work arrays
%!  nok = 0;
%!  for i = 1:100
%!    s = solvers{mod (i, 3) + 1};
%!    kind = mod (floor (i / 3), 6);
%!    tfail = 0.2 + 0.7 * mod (i, 7) / 7;
%!    f = @(t, y) leak_rhs (t, y, Inf);
%!    o = struct ();
%!    switch (kind)
%!      case 0    # FCN fails, adaptive
%!        f = @(t, y) leak_rhs (t, y, tfail);  id = "leaktest:boom";
%!      case 1    # FCN fails, fixed step (many rows buffered first)
%!        f = @(t, y) leak_rhs (t, y, tfail);  id = "leaktest:boom";
%!        o.TimeStepSize = 5e-3;
%!      case 2    # the Hessian fails (Newton may keep its first matrix
%!                # for the whole run: fail at once)
%!        o.HamiltonianHessFcn = @(t, y) leak_hess (t, y, -1);
%!        o.TimeStepSize = 0.01;  id = "leaktest:hess";
%!      case 3    # the Jacobian fails
%!        o.Jacobian = @(t, y) [zeros(10) eye(10); -eye(10) zeros(10)] * leak_hess (t, y, -1);
%!        id = "leaktest:hess";
%!      case 4    # the event function fails
%!        o.Events = @(t, y) leak_events (t, y, tfail);  id = "leaktest:event";
%!      case 5    # the output function fails
%!        o.OutputFcn = @(t, y, flag) leak_output (t, y, flag, tfail);
%!        id = "leaktest:output";
%!    endswitch
%!    try
%!      [t, y] = s (f, [0 1], y0, o);
%!    catch err
%!      nok += strcmp (err.identifier, id);
%!    end_try_catch
%!  endfor
%!endfunction

%!test
%! if (! exist ("/proc/self/status", "file"))
%!   return;   # not Linux: no VmRSS to read
%! endif
%! ## warm-up: load everything, let the allocator reach its working set
%! for k = 1:2
%!   assert (leak_batch (), 100);
%! endfor
%! rss0 = leak_rss_kb ();
%! nok = 0;
%! for k = 1:10
%!   nok += leak_batch ();
%! endfor
%! rss1 = leak_rss_kb ();
%! printf ("test_leak: 1000 failing calls: VmRSS %d kB -> %d kB (%+d kB)\n",
%!         rss0, rss1, rss1 - rss0);
%! assert (nok, 1000);
%! assert (rss1 - rss0 < 10 * 1024);
