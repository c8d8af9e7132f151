## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## Hostile runs: singularities at and inside the span, huge and subnormal
## scales, a Vectorized FCN that is not, and an output that does not fit
## in memory.  Each returns within seconds: it integrates, or stops with a
## warning naming the solver, where it stopped and why, and returns the
## solution so far, or (the Vectorized FCN, the output) ends in an error
## that says why; none crashes or runs forever.

%!shared all3, osc
%! all3 = {@odeSE, @odeSV, @odeSPVI};
%! osc = @(t, y) [y(2); -y(1)];

%!function [t, y, msg, id, secs] = timed (run)
%!  ## run () with its last warning and time; the warning text is not shown
%!  lastwarn ("");
%!  t0 = tic ();
%!  evalc ("[t, y] = run ();");
%!  secs = toc (t0);
%!  [msg, id] = lastwarn ();
%!endfunction

%!function tol = ifelse_tol (c, tsub, name)
%!  ## the error the data allow: the subnormal quantum, or odeSE's O(h)
%!  tol = ifelse (c < 1e-300, tsub, 0);
%!  tol += ifelse (strcmp (name, "odeSE"), 0.02, 1e-4);
%!endfunction

%!function v = ifelse (c, a, b)
%!  if (c) v = a; else v = b; endif
%!endfunction

%!test
%! ## f singular at the end of the span (y = rotation by 2 - 2 sqrt (1 - t)):
%! ## odeSE and odeSV, which evaluate f at t = 1, stop short of it, MaxSteps
%! ## or not (failed steps are bounded too); odeSPVI's nodes are inside its
%! ## steps, and it reaches t = 1
%! f = @(t, y) [y(2); -y(1)] / sqrt (1 - t);
%! for s = all3
%!   name = func2str (s{1});
%!   for o = {struct("MaxSteps", 100), struct()}
%!     [t, y, msg, id, secs] = timed (@() s{1} (f, [0 1], [1; 0], o{1}));
%!     assert (secs < 10);
%!     assert (all (isfinite (y(:))));
%!     if (strcmp (name, "odeSPVI"))
%!       assert (isempty (msg) && t(end) == 1);
%!     else
%!       assert (regexp (msg, ["^" name ": .* up to t = 0\\.9"]));
%!       assert (t(end) < 1);
%!     endif
%!     phi = 2 - 2 * sqrt (1 - t);
%!     assert (y, [cos(phi), -sin(phi)], ifelse (strcmp (name, "odeSPVI"), 2e-3, 0.03));
%!   endfor
%! endfor

%!test
%! ## f singular at t = 0, approached from below: a step floor relative to
%! ## the span ends the creeping towards it
%! f = @(t, y) [y(2); -y(1)] / t;
%! for s = all3
%!   name = func2str (s{1});
%!   [t, y, msg, id, secs] = timed (@() s{1} (f, [-1 0], [1; 0]));
%!   assert (secs < 10);
%!   assert (id, "symplectic:step-size");
%!   assert (regexp (msg, ["^" name ": the step size became too small at t = -"]));
%!   assert (t(end) < 0 && t(end) > -1e-10);
%! endfor

%!test
%! ## a step that fails at every size (the error of f = 1e10/t over a step
%! ## from 0 does not shrink with h): failures in a row are bounded, each
%! ## after the first halving h down to the least step (4 ulps of the span)
%! f = @(t, y) [1e10*(t > 0)/max(t, realmin); 0];
%! for s = all3
%!   name = func2str (s{1});
%!   lastwarn ("");
%!   evalc ("sol = s{1} (f, [0 1], [0; 0], odeset ('InitialStep', 1));");
%!   [msg, id] = lastwarn ();
%!   assert (id, "symplectic:step-size");
%!   assert (regexp (msg, ["^" name ": the step size became too small at t = 0;"]));
%!   assert (sol.stats.nsteps, 0);
%!   assert (sol.stats.nfailed >= 10 && sol.stats.nfailed <= 2 + log2 (1 / (4 * eps)));
%! endfor

%!test
%! ## huge scales: f = 0 on [0, 1e110]; a slow oscillator 1e-200 f on
%! ## [0, 1e200] (its solution cos(1e-200 t)); f = 0 from t0 = 1.54e117
%! ## over 1e-10 t0, and from 1e125 and 1e300
%! zero = @(t, y) [0; 0];
%! slow = @(t, y) 1e-200 * [y(2); -y(1)];
%! for s = all3
%!   [t, y, msg, ~, secs] = timed (@() s{1} (zero, [0 1e110], [1; 0]));
%!   assert (secs < 10 && isempty (msg) && t(end) == 1e110 && isequal (y(end,:), [1 0]));
%!   [t, y, msg, ~, secs] = timed (@() s{1} (slow, [0 1e200], [1; 0], odeset ("RelTol", 1e-6)));
%!   assert (secs < 10 && isempty (msg) && t(end) == 1e200);
%!   assert (y(end,1), cos (1), 1e-3);
%!   for t0 = [1.54e117, 1e125, 1e300]
%!     [t, y, msg, ~, secs] = timed (@() s{1} (zero, [t0, t0 * (1 + 1e-10)], [1; 0]));
%!     assert (secs < 10 && isempty (msg) && t(end) == t0 * (1 + 1e-10));
%!   endfor
%! endfor

%!test
%! ## tiny and huge data are data: y0 = 1e-320 (subnormal) and 1e300, the
%! ## oscillator's solution scaled, fixed steps and adaptive ones (with
%! ## AbsTol of the data's size); a subnormal span
%! tq = [0 2 5];
%! for s = all3
%!   for c = [1e-320, 1e300]
%!     o = symplecticset ("TimeStepSize", 0.01);
%!     [t, y, msg] = timed (@() s{1} (osc, tq, [c; 0], o));
%!     assert (isempty (msg));
%!     ## subnormal data have about 11 bits
%!     tol = ifelse_tol (c, 0.03, func2str (s{1}));
%!     assert (y(:,1) / c, cos (tq(:)), tol);
%!     o = odeset ("RelTol", 1e-6, "AbsTol", max (1e-6 * c, 1e-323));
%!     [t, y, msg] = timed (@() s{1} (osc, tq, [c; 0], o));
%!     assert (isempty (msg));
%!     assert (y(:,1) / c, cos (tq(:)), ifelse_tol (c, 1e-2, func2str (s{1})));
%!   endfor
%!   [t, y, msg] = timed (@() s{1} (osc, [0 1e-320], [1; 0]));
%!   assert (isempty (msg) && t(end) == 1e-320 && y(end,1) == 1);
%! endfor

%!error <Vectorized is on, but FCN does not evaluate the columns of Y one by one: column 1 of FCN \(t, Y\) differs from FCN \(t, Y\(:,1\)\)> x = odeSPVI (@(t, y) [y(end/2+1:end); -y(1:end/2)], [0 1], [1; 0], odeset ("Vectorized", "on"));
%!error <Vectorized is on, but FCN does not evaluate> x = odeSE (@(t, y) [y(end/2+1:end); -y(1:end/2)], [0 1], [1; 0], odeset ("Vectorized", "on"));

%!test
%! ## a Vectorized FCN that is: no complaint; one that is NaN at the probed
%! ## state near y0 (the edge of its domain): no check, no complaint
%! g = @(t, y) [y(2,:); -y(1,:)];
%! [t, y] = odeSPVI (g, [0 1], [1; 0], odeset ("Vectorized", "on"));
%! assert (y(end,1), cos (1), 1e-6);
%! h = @(t, y) [y(2,:); -y(1,:) + 0 ./ (y(1,:) <= 1)];
%! [t, y] = odeSPVI (h, [0 1], [1; 0], odeset ("Vectorized", "on"));
%! assert (t(end), 1);

%!function [st, out] = limited_child (lines)
%!  ## run the Octave code LINES (a cell of strings) in a child Octave under
%!  ## ulimit -v 1500000 (1.5 GB), one BLAS thread; st = -1 when no bash or
%!  ## when Octave does not start under that limit here
%!  st = -1;  out = "";
%!  if (ispc () || system ("command -v bash > /dev/null") != 0)
%!    return;
%!  endif
%!  paths = strsplit (path (), pathsep ());
%!  keep = paths(cellfun (@(p) ! isempty (dir (fullfile (p, "__odeSV__.mex"))) ...
%!                              || ! isempty (dir (fullfile (p, "odeSV.m"))), paths));
%!  script = [tempname() ".m"];
%!  fid = fopen (script, "w");
%!  fprintf (fid, "addpath ('%s');\n", strjoin (keep, pathsep ()));
%!  fprintf (fid, "%s\n", lines{:});
%!  fclose (fid);
%!  run = @(code) system (sprintf (["bash -c 'ulimit -v 1500000; OPENBLAS_NUM_THREADS=1 ", ...
%!                                  "OMP_NUM_THREADS=1 \"%s\" --norc --quiet --no-gui %s' 2>&1"],
%!                                 fullfile (OCTAVE_HOME (), "bin", "octave-cli"), code));
%!  unwind_protect
%!    [st0, out0] = run ("--eval \"disp (42)\"");
%!    if (st0 != 0 || isempty (strfind (out0, "42")))
%!      printf ("skipped: Octave does not start under ulimit -v 1500000 here\n");
%!      return;
%!    endif
%!    [st, out] = run (["\"" script "\""]);
%!  unwind_protect_cleanup
%!    delete (script);
%!  end_unwind_protect
%!endfunction

%!test
%! ## an output that does not fit: a child process under an address-space
%! ## limit gets an error naming the solver, not a crash
%! [st, out] = limited_child ({
%!   ["[t, y] = odeSV (@(t, y) [y(end/2+1:end); -y(1:end/2)], [0 1], ", ...
%!    "ones (2000, 1), struct ('TimeStepNumber', 1e6, 'Separable', 'on'));"]});
%! if (st == -1)
%!   return;
%! endif
%! assert (st < 128, sprintf ("exit status %d:\n%s", st, out));   # no signal
%! assert (! isempty (regexp (out, "error: odeSV: out of memory for the output after t = 0\\.\\d+ \\(\\d+ rows\\)")), out);

%!test
%! ## a workspace that cannot be had: Newton's matrix of odeSPVI with 40
%! ## nodes at d = 2000 (205 GB), as one system, is an error naming the
%! ## solver and the size of a block that failed, before any step.  In a
%! ## child under a 1.5 GB address-space limit: in the runner's own process
%! ## the blocks that can be had are allocated first (14.8 GB resident)
%! [st, out] = limited_child ({
%!   "d = 2000;"
%!   "o = symplecticset ('TimeStepSize', 0.05, 'Nodes', 40, 'NewtonSystem', 'full');"
%!   "try"
%!   "  sol = odeSPVI (@(t, y) [y(d+1:end); -y(1:d)], [0 0.1], ones (2*d, 1), o);"
%!   "  disp ('no error');"
%!   "catch e"
%!   "  printf ('caught <%s> <%s>\\n', e.identifier, e.message);"
%!   "end_try_catch"});
%! if (st < 0)
%!   return;
%! endif
%! assert (st, 0, out);
%! assert (! isempty (regexp (out, "caught <Octave:out-of-memory> <odeSPVI: out of memory: the integrator's workspace needs a block of [\\d.]+ GB")), out);
