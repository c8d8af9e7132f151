## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## Fuzzing the argument checks: 10000 calls of odeSE, odeSV and odeSPVI
## with randomly malformed arguments (types, sizes, values, option
## structs, misbehaving user functions) from a fixed seed.  Every call must
## end in a result or in an Octave error (caught here), never in a crash
## or a hang; a result must have the documented shape.  Each call is kept
## cheap (short TSPAN, MaxSteps = 50, few fixed steps) so that the whole
## run takes well under a minute, and must return within 2 s.  The second
## test runs hostile but valid problems without MaxSteps.
##
## To see each case before it runs (to find one that crashes Octave):
##   setenv ("SYMPLECTIC_FUZZ_VERBOSE", "1"); test test_fuzz

## random integer in 1..A, or in A..B (randi is slow: this runs 100000 times)
%!function k = fz_ri (a, b)
%!  if (nargin == 1)
%!    k = floor (rand () * a) + 1;
%!  else
%!    k = a + floor (rand () * (b - a + 1));
%!  endif
%!endfunction

## random element of a cell array
%!function v = fz_pick (c)
%!  v = c{fz_ri(numel (c))};
%!endfunction

## junk values for any argument or option
%!function v = fz_junk ()
%!  junkfcn1 = @(varargin) [];
%!  junkfcn2 = @(t, y) y;
%!  junkfcn3 = @(x) x;   # (not @sin: its "Invalid call" error is slow)
%!  pool = {[], 0, -1, 1, 2, 2.5, NaN, Inf, -Inf, 1i, 1+2i, "a", "on", "off", ...
%!          "", {}, {1}, struct(), struct("a", {1, 2}), true, false, int8(3), ...
%!          uint64(2^60), single(0.5), sparse(1), sparse([1 0]), zeros(3), ...
%!          ones(1, 100), [1 2], [0; 1], -1e-300, 1e300, realmax, eps, ...
%!          "no_such_function_fz", junkfcn3, junkfcn1, junkfcn2, ...
%!          1e-20, 1e20, [NaN 1], [1 Inf], int32([0 1]), "fz_rhs", "max"};
%!  v = fz_pick (pool);
%!endfunction

%!function dy = fz_rhs (t, y)
%!  d = floor (numel (y) / 2);
%!  dy = [y(d+1:2*d); -y(1:d)];
%!endfunction

## misbehaving right-hand sides (KIND 1..N)
%!function dy = fz_bad_rhs (t, y, kind)
%!  d = floor (numel (y) / 2);
%!  dy = [y(d+1:2*d); -y(1:d)];
%!  switch (kind)
%!    case 1,  dy = [];
%!    case 2,  dy = "ab";
%!    case 3,  dy = {dy};
%!    case 4,  dy = [dy; 1];
%!    case 5,  dy = dy * 1i;
%!    case 6,  dy = dy * NaN;
%!    case 7,  if (t > 0.03) dy(:) = NaN; endif
%!    case 8,  if (t > 0.03) error ("fuzz:rhs", "fuzz failure at t = %g", t); endif
%!    case 9,  dy = sparse (dy);
%!    case 10, dy = int8 (dy);
%!    case 11, dy = dy.';
%!    case 12, dy = struct ("dy", dy);
%!    case 13, dy = ones (numel (y));
%!    case 14, dy = 1e300 * dy .* exp (1e3 * t);
%!    case 15, dy = 1e2 * [y(d+1:2*d); -y(1:d).^3];
%!    case 16, if (t > 0.03) dy = [dy; 0]; endif
%!    case 17, if (t > 0.03) dy = dy + 1i; endif
%!    case 18, dy = logical (dy);
%!    case 19, dy(end) = Inf;
%!    case 20, dy = single (dy);
%!  endswitch
%!endfunction

%!function [dy, h] = fz_rhs_hess (t, y, kind)
%!  dy = fz_rhs (t, y);
%!  n = numel (y);
%!  switch (kind)
%!    case 1, h = eye (n);
%!    case 2, h = ones (n + 1);
%!    case 3, h = reshape (eye (n), [], 1);
%!    case 4, h = NaN (n);
%!    case 5, h = "x";
%!    case 6, h = {};
%!    otherwise, h = eye (n) * 1i;
%!  endswitch
%!endfunction

%!function [v, term, direction] = fz_events (t, y, kind)
%!  v = y(1);  term = 0;  direction = 0;
%!  switch (kind)
%!    case 1, term = 1;
%!    case 2, v = y;  term = ones (size (y));  direction = -1;
%!    case 3, v = NaN;
%!    case 4, v = t - 0.05 + 1e-5 * (1:70)';   # 70 events in one step
%!    case 5, v = [];
%!    case 6, term = "a";
%!    case 7, direction = [1 1 1 1 1];
%!    case 8, error ("fuzz:event", "fuzz event failure");
%!    case 9, v = t - 0.05;  term = 1;
%!    case 10, v = y(1) * (1:1 + (t > 0.03));
%!    case 11, v = 1i;
%!    case 12, v = {1};
%!  endswitch
%!endfunction

%!function stop = fz_output (t, y, flag, kind)
%!  stop = false;
%!  switch (kind)
%!    case 1, stop = true;
%!    case 2, stop = "x";
%!    case 3, stop = {};
%!    case 4, stop = [];
%!    case 5, stop = NaN;
%!    case 6, if (strcmp (flag, "")) error ("fuzz:output", "fuzz output failure"); endif
%!    case 7, stop = [1 0 1];
%!    case 8, stop = struct ();
%!    case 9, if (strcmp (flag, "") && t(end) > 0.03) stop = 1; endif
%!  endswitch
%!endfunction

## A valid call, then 1 to 3 random mutations.  Returns the arguments and
## how many outputs to ask for (1, 2 or 5: never 0, which would plot).
%!function [args, nout, desc] = fz_case ()
%!  d = fz_ri (3);
%!  n = 2 * d;
%!  yb = randn (n, 1);
%!  y0 = yb;
%!  fcn = @fz_rhs;
%!  tspan = fz_pick ({[0 0.1], [0 0.05 0.1], [0.1 0], [0 0.02 0.04 0.06 0.08 0.1], [-0.1 0]});
%!  opts = struct ("MaxSteps", 50);
%!  ## some valid options
%!  ev0 = @(t, y) fz_events (t, y, 0);
%!  out0 = @(t, y, flag) fz_output (t, y, flag, 0);
%!  hess0 = @(t, y) eye (numel (y));
%!  valid = {"RelTol", 1e-4; "AbsTol", 1e-8; "TimeStepSize", 0.02; ...
%!           "TimeStepNumber", 3; "Separable", "on"; "Nodes", 2; ...
%!           "Q_DoFs", 3; "Refine", 2; "NormControl", "on"; ...
%!           "InitialStep", 0.01; "MaxStep", 0.03; "NewtonTol", 1e-10; ...
%!           "MaxNewtonIterations", 5; "Events", ev0; ...
%!           "OutputFcn", out0; ...
%!           "OutputSel", 1; "Jacobian", zeros(n); ...
%!           "HamiltonianHessFcn", hess0; "PolynomialDegree", 2; ...
%!           "Vectorized", "off"; "P_DoFs", 3; "Stats", "off"; ...
%!           "Method", "yoshida4"; "SecondOrder", "on"; ...
%!           "CompensatedSummation", "on"; "Method", "blanesmoan6"; ...
%!           "StepControl", "reversible"; ...
%!           "StepDensityFcn", @(t, y) 1 + sum (abs (y))};
%!  for i = 1:fz_ri (0, 3)
%!    j = fz_ri (rows (valid));
%!    opts.(valid{j,1}) = valid{j,2};
%!  endfor
%!  extra = {};
%!  risky = false;
%!  nout = fz_pick ({1, 2, 2, 2, 5});
%!  nargs = 4;
%!  desc = '';
%!  fields = [valid(:,1)', {"MaxSteps", "reltol", "ABSTOL", "Mass", "NoSuchOption"}];
%!  for m = 1:fz_ri (3)
%!    what = fz_ri (14);
%!    desc = sprintf ("%s m%d", desc, what);
%!    if (any (what == [8 9 10 11 12 14]) && ! (isstruct (opts) && isscalar (opts)))
%!      opts = struct ();
%!    endif
%!    switch (what)
%!      case 1   # FCN replaced by junk
%!        fcn = fz_junk ();
%!      case {2, 3}   # FCN misbehaves
%!        k = fz_ri (20);
%!        fcn = @(t, y) fz_bad_rhs (t, y, k);
%!        risky = any (k == [14 15]);
%!        desc = sprintf ("%s(rhs %d)", desc, k);
%!      case 4   # FCN with a second output
%!        k = fz_ri (7);
%!        fcn = @(t, y) fz_rhs_hess (t, y, k);
%!      case 5   # TSPAN junk
%!        tspan = fz_pick ({fz_junk(), [0 0], [0 0.1 0.05], [0 0.1 0.1], ...
%!                          [0 NaN], [0; 0.1], [0 1e-300], 0.1, [1e10 1e10+1], ...
%!                          [0 0.1]+1i, {0, 0.1}, "ab", [0 0.1 Inf], -[0 0.1]});
%!      case 6   # Y0 junk
%!        y0 = fz_pick ({fz_junk(), [], zeros(1, 0), randn(3, 1), randn(2), ...
%!                       [1 NaN], [1 Inf 0 0], yb+1i, logical(yb), ...
%!                       single(yb), int16(yb), sparse(yb), num2cell(yb), ...
%!                       "ab", yb.', randn(1, 8)});
%!      case 7   # OPTS not a struct
%!        opts = fz_junk ();
%!      case {8, 9, 10}   # an option set to junk
%!        f = fz_pick (fields);
%!        opts.(f) = fz_junk ();
%!        desc = sprintf ("%s(%s)", desc, f);
%!      case 11  # Events
%!        k = fz_ri (12);
%!        opts.Events = @(t, y) fz_events (t, y, k);
%!        desc = sprintf ("%s(events %d)", desc, k);
%!      case 12  # OutputFcn
%!        k = fz_ri (9);
%!        opts.OutputFcn = @(t, y, flag) fz_output (t, y, flag, k);
%!      case 13  # fewer arguments, or extra parameters
%!        nargs = fz_ri (0, 3);
%!        if (nargs == 0)
%!          nargs = 4;
%!          extra = repmat ({fz_junk()}, 1, fz_ri (3));
%!        endif
%!      case 14  # odeSPVI: Q_DoFs / Nodes / degree
%!        opts.(fz_pick ({"Q_DoFs", "Nodes", "P_DoFs", "PolynomialDegree"})) = ...
%!          fz_pick ({0, 1, 2, 3, 4, 5, 7, 2.5, -1, 40, 41, 100, NaN, "3", [2 3]});
%!    endswitch
%!  endfor
%!  ## keep every run short: at most 50 steps, unless MaxSteps itself is junk
%!  ## (the default options, without MaxSteps, only with right-hand sides
%!  ## that do not need millions of steps)
%!  if (risky && isempty (opts))
%!    opts = struct ();
%!  elseif (risky && nargs == 3)
%!    fcn = @fz_rhs;
%!  endif
%!  if (isstruct (opts) && isscalar (opts))
%!    if (! isfield (opts, "MaxSteps") || isempty (opts.MaxSteps))
%!      opts.MaxSteps = 50;
%!    endif
%!    ## a valid but huge Refine would make huge outputs
%!    if (isfield (opts, "Refine") && isnumeric (opts.Refine) && isscalar (opts.Refine) && opts.Refine > 10)
%!      opts.Refine = 3;
%!    endif
%!  endif
%!  all_args = [{fcn, tspan, y0, opts}, extra];
%!  if (nargs < 4)
%!    args = all_args(1:nargs);
%!  else
%!    args = all_args;
%!  endif
%!endfunction

%!function s = ifelse_id (id)
%!  s = id;
%!  if (isempty (id))
%!    s = "(no identifier: from the user's functions)";
%!  endif
%!endfunction

%!test
%! ## a fixed seed: the same 10000 calls every run
%! rand ("state", 20130517);
%! randn ("state", 20130517);
%! warning ("off", "all", "local");
%! verbose = ! isempty (getenv ("SYMPLECTIC_FUZZ_VERBOSE"));
%! solvers = {@odeSE, @odeSV, @odeSPVI};
%! ncalls = 10000;
%! nres = 0;
%! nerr = 0;
%! ids = {};
%! tstart = tic ();
%! for k = 1:ncalls
%!   s = solvers{mod (k, 3) + 1};
%!   [args, nout, desc] = fz_case ();
%!   if (verbose)
%!     printf ("fuzz %d: %s nargin %d nargout %d:%s\n", k, func2str (s),
%!             numel (args), nout, desc);
%!     fflush (stdout);
%!   endif
%!   tcall = cputime ();
%!   try
%!     ## Stats = "on" (or 1, or true) prints: keep the log clean (evalc)
%!     quiet = numel (args) > 3 && isstruct (args{4}) && isfield (args{4}, "Stats");
%!     switch (nout)
%!       case 1
%!         if (quiet)
%!           evalc ("sol = s (args{:});");
%!         else
%!           sol = s (args{:});
%!         endif
%!         assert (isstruct (sol) && isrow (sol.x));
%!         assert (size (sol.y), [numel(args{3}), numel(sol.x)]);
%!       case 2
%!         if (quiet)
%!           evalc ("[t, y] = s (args{:});");
%!         else
%!           [t, y] = s (args{:});
%!         endif
%!         assert (iscolumn (t) || isempty (t));
%!         assert (size (y), [numel(t), numel(args{3})]);
%!         assert (isreal (y) && isa (y, "double"));
%!       case 5
%!         if (quiet)
%!           evalc ("[t, y, te, ye, ie] = s (args{:});");
%!         else
%!           [t, y, te, ye, ie] = s (args{:});
%!         endif
%!         assert (size (y, 1), numel (t));
%!         assert (size (ye, 1), numel (te));
%!         assert (numel (ie), numel (te));
%!     endswitch
%!     nres += 1;
%!   catch err
%!     if (strncmp (err.identifier, "Octave:assert", 13)
%!         || ! isempty (strfind (err.message, "ASSERT errors"))
%!         || ! isempty (strfind (err.message, "assert (")))
%!       error ("fuzz call %d (%s:%s) returned a malformed result: %s", k,
%!              func2str (s), desc, err.message);
%!     endif
%!     assert (ischar (err.message) && ! isempty (err.message));
%!     ids{end+1} = err.identifier;
%!     nerr += 1;
%!   end_try_catch
%!   secs = cputime () - tcall;
%!   if (secs > 2)
%!     error ("fuzz call %d (%s:%s) took %.1f s", k, func2str (s), desc, secs);
%!   endif
%! endfor
%! el = toc (tstart);
%! [u, ~, j] = unique (ids);
%! cnt = accumarray (j(:), 1);
%! printf ("test_fuzz: %d calls in %.1f s: %d results, %d errors:\n",
%!         ncalls, el, nres, nerr);
%! for i = 1:numel (u)
%!   printf ("  %5d  %s\n", cnt(i), ifelse_id (u{i}));
%! endfor
%! assert (nres + nerr, ncalls);
%! ## both outcomes must be common, or the fuzzer tests little
%! assert (nres > 500 && nerr > 3000);

## Hostile but valid problems: singularities at, inside and just past the
## span; huge, tiny and subnormal data, times and spans; f that is
## discontinuous, blows up, turns NaN, or is not vectorized; odd
## tolerances and steps.  Each combination asks for a bounded amount of
## work; no MaxSteps.
%!function [args, desc] = fz_hostile ()
%!  pick = @(c) c{fz_ri(numel (c))};
%!  any_c = {1, 1e-320, 1e-300, 1e300, 1e150};
%!  ## name, f, data scales, start times, span lengths
%!  rhs = {"osc", @(t, y) [y(2); -y(1)], any_c, ...
%!         {0, -1, 1e6, 1e117, 1e300, -1e-300, 1e-320}, {1, 10, -5, 1e-10, 1e-300, 1e-320};
%!         "1/sqrt(1-t)", @(t, y) [y(2); -y(1)] / sqrt (1 - t), any_c, ...
%!         {0, 0.5, 1 - 1e-10}, {1, 2, -1};
%!         "1/t", @(t, y) [y(2); -y(1)] / t, any_c, {-1, -1e-10, -1e-300, 1}, {1, 2, -1};
%!         "1/(t-0.5)", @(t, y) [y(2); -y(1)] / (t - 0.5), any_c, {0, 1e-320}, {1, -1};
%!         "zero", @(t, y) [0; 0], any_c, {0, 1e6, 1e117, 1e125, 1e300, -1e300, 1e-320}, ...
%!         {1, 1e-10, 1e110, 1e200, 1e300, -1e200, 1e-320};
%!         "slow", @(t, y) 1e-200 * [y(2); -y(1)], any_c, {0, 1e117, -1e200}, {1e200, 1e150, -3e200};
%!         "fast", @(t, y) 1e200 * [y(2); -y(1)], any_c, {0, 1e-320, 1e-150}, {1e-200, 5e-200, -1e-200};
%!         "exp", @(t, y) [y(2); -y(1)] * exp (t), any_c, {0, -100, 1}, {1, 3, -100};
%!         "sign", @(t, y) [y(2); -sign(y(1))], {1, 10}, {0, 1e6}, {1, 10, -1};
%!         "cubic", @(t, y) [y(2); -y(1)^3], {1, 2}, {0, -1}, {1, 10};
%!         "blowup", @(t, y) [y(2)^2; -y(1)], {1, -1, 3}, {0}, {1, 10, -10};
%!         "nan", @(t, y) [y(2); -y(1)] ./ (t <= 0.3), any_c, {0}, {1};
%!         "nonvec", @(t, y) [y(end/2+1:end); -y(1:end/2)], any_c, {0, 1e300}, {1, 1e-10};
%!         "stiff", @(t, y) [y(2); -1e8 * y(1)], any_c, {0, 1e6}, {1e-3, -1e-3}};
%!  j = fz_ri (rows (rhs));
%!  c = pick (rhs{j,3});
%!  t0 = pick (rhs{j,4});
%!  tf = t0 + pick (rhs{j,5});
%!  if (tf == t0)
%!    tf = t0 + 8 * eps (t0) + 1e-320;
%!  endif
%!  tf = max (min (tf, realmax), -realmax);
%!  len = abs (tf - t0);
%!  opts = struct ();
%!  for m = 1:fz_ri (0, 3)
%!    switch (fz_ri (10))
%!      case 1,  opts.RelTol = pick ({1e-3, 1e-5, 1, 0.5});
%!      case 2,  opts.AbsTol = pick ({1e-6, 1e-8, 1e300, max(1e-6 * c, 1e-323)});
%!      case 3,  opts.InitialStep = pick ({1e-300, 1e-320, 1e-10, 1e300, 0.5});
%!      case 4,  opts.MaxStep = pick ({len / 1e3, 1e300, 0.5});
%!      case 5,  opts.TimeStepNumber = pick ({1, 10, 1e3, 1e4});
%!      case 6,  opts.TimeStepSize = len / pick ({1, 10, 1e3, 1e4});
%!      case 7,  opts.Vectorized = "on";
%!      case 8,  opts.Separable = "on";
%!      case 9,  opts.NormControl = "on";
%!      case 10, opts.MaxNewtonIterations = pick ({1, 2, 50});
%!    endswitch
%!  endfor
%!  opts.Refine = 1;
%!  args = {rhs{j,2}, [t0 tf], c * [1; 0], opts};
%!  desc = sprintf ("%s, y0 = %g [1; 0], tspan = [%.17g %.17g]", rhs{j,1}, c, t0, tf);
%!  f = fieldnames (opts);
%!  for i = 1:numel (f)
%!    v = opts.(f{i});
%!    if (! ischar (v))
%!      v = sprintf ("%.17g", v);
%!    endif
%!    desc = [desc, ", ", f{i}, " = ", v];
%!  endfor
%!endfunction

%!test
%! ## hostile runs: each returns within seconds of CPU time (the load of a
%! ## shared machine does not count), on its own: at tf; or short of it
%! ## with a warning naming the solver and t, and the finite solution so
%! ## far; or with an error naming the solver (or FCN's own)
%! rand ("state", 20261127);
%! solvers = {@odeSE, @odeSV, @odeSPVI};
%! ncalls = 900;
%! slowest = 0;
%! outcome = zeros (1, 3);
%! for k = 1:ncalls
%!   s = solvers{mod (k, 3) + 1};
%!   name = func2str (s);
%!   [args, desc] = fz_hostile ();
%!   what = sprintf ("hostile call %d: %s %s", k, name, desc);
%!   lastwarn ("");
%!   t0 = cputime ();
%!   try
%!     evalc ("[t, y] = s (args{:});");
%!     secs = cputime () - t0;
%!     [msg, id] = lastwarn ();
%!     tspan = args{2};
%!     assert (iscolumn (t) && t(1) == tspan(1), what);
%!     assert (all (sign (tspan(2) - tspan(1)) * diff (t) > 0), what);
%!     assert (all (isfinite (y(:))), what);
%!     if (t(end) == tspan(end) || isfield (args{4}, "TimeStepNumber"))
%!       outcome(1) += 1;
%!     else
%!       assert (strncmp (id, "symplectic:", 11), what);
%!       assert (! isempty (regexp (msg, ["^" name ": .*t = "])), [what ": " msg]);
%!       outcome(2) += 1;
%!     endif
%!   catch err
%!     secs = cputime () - t0;
%!     if (strncmp (err.message, "ASSERT", 6) || strncmp (err.message, "hostile", 7))
%!       rethrow (err);
%!     endif
%!     assert (strncmp (err.message, [name ": "], numel (name) + 2)
%!             || strcmp (err.identifier, "Octave:nonconformant-args"),
%!             [what ": " err.message]);
%!     outcome(3) += 1;
%!   end_try_catch
%!   assert (secs < 5, sprintf ("%s took %.1f s", what, secs));
%!   slowest = max (slowest, secs);
%! endfor
%! printf ("test_fuzz: %d hostile calls: %d reached tf, %d stopped with a warning, %d errors; slowest %.2f s\n",
%!         ncalls, outcome, slowest);
%! assert (all (outcome > 50));
