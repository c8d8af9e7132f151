## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## Octave 7 leaks a little each time a MEX function asks for the data of
## a diagonal or permutation matrix or a range after asking for its
## dimensions (bench/NOTES.md): a Hessian or Jacobian such as eye (n)
## grew the process by kilobytes a call.  tests/leak_types_run.m runs
## odeSPVI with a Hessian or Jacobian of each type Octave can return, from
## each source, in runs that end well and runs whose value goes wrong
## mid-run, one state and an Ensemble; here it runs in a child octave-cli
## (the growth of this process would say nothing), whose resident memory
## must not grow by more than 256 kB over its 4 rounds of all the cases
## after a warm-up round (it grew by about 1.2 MB before the fix).  An
## error also left what the core held to Octave, which keeps the address
## of each such block in a list for good: 400 runs that fail early must
## not grow it by more than 64 kB (192 kB before).  The
## child's allocator neither trims nor maps blocks of its own, so that
## its resident memory only grows, and only when more is used than
## before.  Linux only (VmRSS of /proc/self/status).

%!test
%! if (! exist ("/proc/self/status", "file"))
%!   return;
%! endif
%! dirs = unique ({fileparts(which ("odeSPVI")), fileparts(which ("__odeSPVI__")), ...
%!                 fileparts(which ("leak_types_run"))});
%! octave = fullfile (OCTAVE_HOME (), "bin", "octave-cli");
%! if (! isfile (octave))
%!   octave = "octave-cli";
%! endif
%! scratch = tempname ();
%! mkdir (scratch);
%! code = sprintf ("addpath (%s); leak_types_run (4, '%s');",
%!                 strjoin (strcat ("'", dirs, "'"), ", "), scratch);
%! cmd = sprintf (["MALLOC_TRIM_THRESHOLD_=4294967295 MALLOC_MMAP_THRESHOLD_=33554432 ", ...
%!                 "MALLOC_ARENA_MAX=1 '%s' --norc --quiet --no-gui ", ...
%!                 "--no-window-system --eval \"%s\" < /dev/null 2>&1"],
%!                octave, code);
%! [status, out] = system (cmd);
%! confirm_recursive_rmdir (false, "local");
%! rmdir (scratch, "s");
%! assert (! isempty (strfind (out, "LEAK TYPES DONE")), out);
%! ## every case ended as it should (refused types and wrong sizes with
%! ## an error, the others well)
%! assert (isempty (strfind (out, "WRONG")), out);
%! ncalls = str2double (regexp (out, 'CALLS (\d+)', "tokens", "once"){1});
%! grow = str2double (regexp (out, 'GROWTH (-?\d+) kB', "tokens", "once"){1});
%! printf ("test_leak_types: %d calls after the warm-up: VmRSS %+d kB\n",
%!         ncalls, grow);
%! assert (ncalls > 400);
%! assert (grow <= 256, sprintf ("VmRSS grew by %d kB:\n%s", grow, out));
%! ## 400 Ensemble runs whose sparse Hessian from a file (cleared before
%! ## each) goes wrong at t > 0.2: 64 kB at most (192 kB before the fix)
%! nf = str2double (regexp (out, 'FAILCALLS (\d+) (\d+)', "tokens", "once"));
%! assert (nf(:).', [400 400]);
%! fgrow = str2double (regexp (out, 'FAILGROWTH (-?\d+) kB', "tokens", "once"){1});
%! printf ("test_leak_types: %d failing calls: VmRSS %+d kB\n", nf(1), fgrow);
%! assert (fgrow <= 64, sprintf ("VmRSS grew by %d kB in the failing runs:\n%s",
%!                               fgrow, out));
