## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## Every bad input gets a clear error: its message
## begins with the solver's name (once), says what is wrong and what is
## expected, and it has an identifier: "Octave:invalid-input-arg" for bad
## arguments and options, "Octave:invalid-fun-call" for a wrong number of
## arguments, "symplectic:..." for run-time failures; an error thrown by
## one of the user's functions reaches the user with its own identifier
## and message.  Each check_bad call below is one case, run for each
## solver it names.

## check_bad (SOLVERS, ID, PAT, FCN, TSPAN, Y0, ...): each solver in the
## cell SOLVERS, called as [t, y] = solver (FCN, TSPAN, Y0, ...), must
## raise an error with identifier ID whose message matches
## "^<solver>: PAT" (PAT a regular expression).  With ID an identifier of
## the user's own (PAT then begins with "^"), the message must match PAT
## as the user's function (or Octave, for it) wrote it.
%!function check_bad (solvers, id, pat, varargin)
%!  if (! iscell (solvers))
%!    solvers = {solvers};
%!  endif
%!  own = isempty (pat) || pat(1) != "^";
%!  for i = 1:numel (solvers)
%!    name = func2str (solvers{i});
%!    raised = false;
%!    try
%!      [t, y] = solvers{i} (varargin{:});
%!    catch err
%!      raised = true;
%!    end_try_catch
%!    if (! raised)
%!      error ("%s: no error, expected [%s] %s", name, id, pat);
%!    endif
%!    if (! strcmp (err.identifier, id))
%!      error ("%s: identifier '%s', expected '%s' (message: %s)", name,
%!             err.identifier, id, err.message);
%!    endif
%!    if (own)
%!      full = ['^' name ': ' pat];
%!      if (numel (strfind (err.message, [name ":"])) != 1)
%!        error ("%s: the solver's name should appear once: %s", name,
%!               err.message);
%!      endif
%!    else
%!      full = pat;
%!    endif
%!    if (isempty (regexp (err.message, full, "once")))
%!      error ("%s: message '%s' does not match '%s'", name, err.message,
%!             full);
%!    endif
%!  endfor
%!endfunction

%!function dy = bi_osc (t, y)
%!  dy = [y(2); -y(1)];
%!endfunction

## FCN misbehaving from t = 0.5 on (KIND selects how)
%!function dy = bi_late (t, y, kind)
%!  dy = [y(2); -y(1)];
%!  if (t > 0.5)
%!    switch (kind)
%!      case "size",    dy = [dy; 0];
%!      case "complex", dy(2) += 1i;
%!      case "char",    dy = "ab";
%!      case "error",   error ("mytest:late", "my late failure at t = %g", t);
%!    endswitch
%!  endif
%!endfunction

%!function bi_noout (t, y)
%!endfunction

%!function [dy, h] = bi_hess2 (t, y, h)
%!  dy = [y(2); -y(1)];
%!endfunction

%!function [dy, h] = bi_hess4 (t, y, h)
%!  dy = [y(3:4); -y(1:2)];
%!endfunction

%!function [v, term, direction] = bi_events (t, y, kind)
%!  v = y(1);  term = 0;  direction = 0;
%!  switch (kind)
%!    case "empty",   v = [];
%!    case "complex", v = 1i;
%!    case "char",    v = "a";
%!    case "term",    term = [1 1 1];
%!    case "dir",     direction = {1};
%!    case "grow",    v = y(1) * ones (1 + (t > 0.5), 1);
%!    case "error",   error ("mytest:event", "my event failure");
%!  endswitch
%!endfunction

%!function v = bi_events1 (t, y)
%!  v = y(1);
%!endfunction

%!shared all3, f, y0, spvi
%! all3 = {@odeSE, @odeSV, @odeSPVI};
%! spvi = {@odeSPVI};
%! f = @bi_osc;
%! y0 = [1 0];

## ------------------------------------------------------------ calling forms
%!test
%! for s = all3
%!   try
%!     s{1} ();
%!     error ("no error");
%!   catch err
%!     assert (err.identifier, "Octave:invalid-fun-call");
%!     assert (regexp (err.message, ['^' func2str(s{1}) ': expected .*got 0 arguments']));
%!   end_try_catch
%! endfor
%!test check_bad (all3, "Octave:invalid-fun-call", "expected .*got 1 arguments", f);
%!test check_bad (all3, "Octave:invalid-fun-call", "expected .*got 2 arguments", f, [0 1]);
%!test
%! for s = all3
%!   try
%!     [a, b, c, d, e, g] = s{1} (f, [0 1], y0);
%!     error ("no error");
%!   catch err
%!     assert (err.identifier, "Octave:invalid-fun-call");
%!     assert (regexp (err.message, ['^' func2str(s{1}) ': at most 5 outputs']));
%!   end_try_catch
%! endfor

## ------------------------------------------------------------ FCN
%!test check_bad (all3, "Octave:invalid-input-arg", "FCN must be a function handle or the name of a function, got 1x1 double", 1, [0 1], y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "FCN must be a function handle .*got 0x0 double", [], [0 1], y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "FCN must be a function handle .*got 1x1 cell", {f}, [0 1], y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "FCN must be a function handle .*got 1x1 struct", struct ("f", f), [0 1], y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "FCN must be a function handle .*got 1x1 logical", true, [0 1], y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "FCN must be a function handle or the name of a function, got \"no_such_function_xyz_1\", which names no function", "no_such_function_xyz_1", [0 1], y0);
## a file on the path that is not a function (exist () gives 2 for it): a
## text file, a script
%!test
%! d = tempname ();
%! mkdir (d);
%! unwind_protect
%!   fid = fopen (fullfile (d, "sym_notes_xyz.txt"), "w");  fputs (fid, "x");  fclose (fid);
%!   fid = fopen (fullfile (d, "sym_script_xyz.m"), "w");  fputs (fid, "x = 1;\n");  fclose (fid);
%!   addpath (d);
%!   for name = {"sym_notes_xyz.txt", "sym_script_xyz"}
%!     assert (exist (name{1}), 2);
%!     check_bad (all3, "Octave:invalid-input-arg", ["FCN must be a function handle or the name of a function, got \"" regexprep(name{1}, '\.', '\\.') "\", which names no function"], name{1}, [0 1], y0);
%!     check_bad (all3, "Octave:invalid-input-arg", "Events must be a function handle or the name of a function, got \"", f, [0 1], y0, struct ("Events", name{1}));
%!   endfor
%! unwind_protect_cleanup
%!   rmpath (d);
%!   confirm_recursive_rmdir (false, "local");
%!   rmdir (d, "s");
%! end_unwind_protect

## ------------------------------------------------------------ TSPAN
%!test check_bad (all3, "Octave:invalid-input-arg", "TSPAN must be a real vector .*of at least 2 elements, got 1x1 double", f, 0, y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "TSPAN must be a real vector .*of at least 2 elements, got 0x0 double", f, [], y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "TSPAN must be strictly monotonic \\(elements 1 and 2 are 0 and 0\\)", f, [0 0], y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "TSPAN must be strictly monotonic \\(elements 2 and 3 are 1 and 1\\)", f, [0 1 1 2], y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "TSPAN must be strictly monotonic \\(elements 2 and 3 are 1 and 0.5\\)", f, [0 1 0.5], y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "TSPAN must be strictly monotonic", f, [1 0 0.5], y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "TSPAN must be finite, element 2 is NaN", f, [0 NaN], y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "TSPAN must be finite, element 2 is Inf", f, [0 Inf], y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "TSPAN must be finite, element 1 is -Inf", f, [-Inf 0], y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "TSPAN must be a real vector .*got 1x2 complex double", f, [0 1i], y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "TSPAN must be a real vector .*got 1x2 char", f, "ab", y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "TSPAN must be a real vector .*got 1x2 cell", f, {0, 1}, y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "TSPAN must be a real vector .*got 2x2 double", f, [0 1; 2 3], y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "TSPAN must be a real vector .*got 1x2 complex double", f, sparse ([0 1i]), y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "TSPAN must be a real vector .*got 1x2 logical", f, [false true], y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "TSPAN must be a real vector .*got 1x1x2 double", f, reshape ([0 1], 1, 1, 2), y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "TSPAN must span a finite interval", f, [-realmax realmax], y0);

## (sparse arguments, options and returned values are taken as full: a
## sparse value with another fault gets that fault's message)

## ------------------------------------------------------------ Y0
%!test check_bad (all3, "Octave:invalid-input-arg", "Y0 must be a non-empty real numeric vector \\[q0; p0\\], got 0x0 double", f, [0 1], []);
%!test check_bad (all3, "Octave:invalid-input-arg", "Y0 must be a non-empty .*got 1x0 double", f, [0 1], zeros (1, 0));
%!test check_bad (all3, "Octave:invalid-input-arg", "Y0 must have an even number of elements \\[q; p\\], got 3", f, [0 1], [1 2 3]);
%!test check_bad (all3, "Octave:invalid-input-arg", "Y0 must have an even number of elements \\[q; p\\], got 1", f, [0 1], 1);
%!test check_bad (all3, "Octave:invalid-input-arg", "Y0 must be real, got a complex value", f, [0 1], [1+2i 0]);
%!test check_bad (all3, "Octave:invalid-input-arg", "Y0 must be a non-empty real numeric vector .*got 1x2 logical", f, [0 1], [true false]);
%!test check_bad (all3, "Octave:invalid-input-arg", "Y0 must be a non-empty real numeric vector .*got 1x2 char", f, [0 1], "ab");
%!test check_bad (all3, "Octave:invalid-input-arg", "Y0 must be a non-empty real numeric vector .*got 1x2 cell", f, [0 1], {1, 0});
%!test check_bad (all3, "Octave:invalid-input-arg", "Y0 must be a non-empty real numeric vector .*got 1x1 struct", f, [0 1], struct ("q", 1));
%!test check_bad (all3, "Octave:invalid-input-arg", "Y0 must be real, got a complex value", f, [0 1], sparse ([1i 0]));
%!test check_bad (all3, "Octave:invalid-input-arg", "Y0 must be a non-empty real numeric vector .*got 2x2 double", f, [0 1], eye (2));
%!test check_bad (all3, "Octave:invalid-input-arg", "Y0 must be a non-empty real numeric vector .*got 1x1x2 double", f, [0 1], ones (1, 1, 2));
%!test check_bad (all3, "Octave:invalid-input-arg", "Y0 must be finite, element 1 is NaN", f, [0 1], [NaN 0]);
%!test check_bad (all3, "Octave:invalid-input-arg", "Y0 must be finite, element 2 is Inf", f, [0 1], [0 Inf]);
%!test check_bad (all3, "Octave:invalid-input-arg", "Y0 must be finite, element 4 is -Inf", f, [0 1], [0 0 0 -Inf]);

## ------------------------------------------------------------ what FCN returns
%!test check_bad (all3, "Octave:invalid-input-arg", "FCN must return a vector of 2 real elements, got 3x1 double at t = 0$", @(t, y) [1; 2; 3], [0 1], y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "FCN must return a vector of 2 real elements, got 0x0 double at t = 0", @(t, y) [], [0 1], y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "FCN must return a vector of 2 real elements, got 1x2 char at t = 0", @(t, y) "ab", [0 1], y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "FCN must return a vector of 2 real elements, got 1x2 cell at t = 0", @(t, y) {1, 2}, [0 1], y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "FCN must return a vector of 2 real elements, got 1x1 struct at t = 0", @(t, y) struct (), [0 1], y0);
## logical is not numeric (a logical Y0 is refused too)
%!test check_bad (all3, "Octave:invalid-input-arg", "FCN must return a vector of 2 real elements, got 2x1 logical at t = 0", @(t, y) [true; false], [0 1], y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "FCN must return a vector of 2 real elements, got 3x1 double at t = 0", @(t, y) sparse ([1; 2; 3]), [0 1], y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "FCN returned a complex value at t = 0; expected a vector of 2 real elements", @(t, y) [1i; 2], [0 1], y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "FCN returned a complex value at t = 2; expected", @(t, y) [1i; 2], [2 3], y0);
%!test check_bad (all3, "symplectic:nonfinite", "FCN returned NaN \\(element 1\\) at t = 0, the initial point", @(t, y) [NaN; 2], [0 1], y0);
%!test check_bad (all3, "symplectic:nonfinite", "FCN returned Inf \\(element 2\\) at t = 0, the initial point", @(t, y) [1; Inf], [0 1], y0);
%!test check_bad (all3, "symplectic:nonfinite", "FCN returned -Inf \\(element 2\\) at t = -1, the initial point", @(t, y) [1; -Inf], [-1 1], y0);
## a computed NaN has its sign bit set: it printed as "-nan"
%!test check_bad (all3, "symplectic:nonfinite", "FCN returned NaN \\(element 2\\) at t = 0, the initial point", @(t, y) [y(2); 0/0], [0 1], y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "Y0 must be finite, element 2 is NaN$", f, [0 1], [1; 0/0]);
## ... or misbehaving later: the message says at which t
%!test check_bad (all3, "Octave:invalid-input-arg", "FCN must return a vector of 2 real elements, got 3x1 double at t = 0\\.[5-9]", @(t, y) bi_late (t, y, "size"), [0 1], y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "FCN returned a complex value at t = 0\\.[5-9]", @(t, y) bi_late (t, y, "complex"), [0 1], y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "FCN must return .*got 1x2 char at t = 0\\.[5-9]", @(t, y) bi_late (t, y, "char"), [0 1], y0, struct ("TimeStepSize", 0.1));
## (odeSPVI evaluates its nodes in one call)
%!test check_bad (spvi, "Octave:invalid-input-arg", "FCN must return a 2x[0-9]+ real matrix \\(Vectorized\\), got 2x1 double at t = ", f, [0 1], y0, struct ("Vectorized", "on"));
## the right numbers of elements in more dimensions (mxGetN multiplies the
## trailing ones: these were taken)
%!test check_bad (spvi, "Octave:invalid-input-arg", "FCN must return a 2x[0-9]+ real matrix \\(Vectorized\\), got 2x1x[0-9]+ double at t = ", @(t, y) reshape ([y(2, :); -y(1, :)], 2, 1, columns (y)), [0 1], y0, struct ("Vectorized", "on"));
%!test check_bad (all3, "Octave:invalid-input-arg", "Jacobian must be a function handle or a real 2x2 matrix \\(df/dy\\), got 2x1x2 double", f, [0 1], y0, struct ("Jacobian", reshape ([0 -1 1 0], 2, 1, 2)));
%!test check_bad (all3, "Octave:invalid-input-arg", "the Jacobian function must return a 2x2 real matrix \\(df/dy\\), got 2x1x2 double at t = ", f, [0 1], y0, struct ("Jacobian", @(t, y) reshape ([0 -1 1 0], 2, 1, 2)));
%!test check_bad (all3, "Octave:invalid-input-arg", "OutputSel must be a vector of indices into Y0, got 2x2 double", f, [0 1], y0, struct ("OutputSel", [1 2; 2 1]));

## ------------------------------------------------------------ errors of the user's functions
%!test check_bad (all3, "mytest:boom", "^my failure 42$", @(t, y) error ("mytest:boom", "my failure %d", 42), [0 1], y0);
%!test check_bad (all3, "mytest:late", "^my late failure at t = 0\\.[5-9]", @(t, y) bi_late (t, y, "error"), [0 1], y0);
%!test check_bad (all3, "mytest:late", "^my late failure", @(t, y) bi_late (t, y, "error"), [0 1], y0, struct ("TimeStepSize", 0.01));
%!test check_bad (all3, "", "^an error without identifier$", @(t, y) error ("an error without identifier"), [0 1], y0);
%!test check_bad (all3, "Octave:index-out-of-bounds", "^index \\(7\\): out of bound|^y\\(7\\): out of bound", @(t, y) [y(2); y(7)], [0 1], y0);
%!test check_bad (all3, "Octave:undefined-function", "^'undefined_thing_xyz' undefined", @(t, y) [y(2); undefined_thing_xyz], [0 1], y0);
## a function that returns nothing: named with the solver, at its first call
%!test check_bad (all3, "Octave:invalid-input-arg", "FCN must return dy/dt = f\\(t, y\\), but returns nothing; calling it at t = 0 gave: bi_noout: function called with too many outputs", @bi_noout, [0 1], y0);
%!test check_bad (all3, "Octave:invalid-input-arg", "FCN must return dy/dt = f\\(t, y\\), but returns nothing; calling it at t = 0 gave: .*called with too many outputs", @(t, y) assert (true), [0 1], y0);
%!test check_bad ({@odeSE, @odeSV}, "Octave:invalid-input-arg", "FCN must return the acceleration a\\(t, q\\), but returns nothing; .*called with too many outputs", @(t, q) assert (true), [0 1], y0, struct ("SecondOrder", "on"));
%!test check_bad (all3, "Octave:invalid-input-arg", "OutputFcn must return STOP \\(true to end the run\\), but returns nothing; calling it at t = 0\\.[0-9]+ gave: .*called with too many outputs", f, [0 1], y0, struct ("OutputFcn", @(t, y, flag) assert (true), "TimeStepSize", 0.1));
%!test check_bad (all3, "Octave:invalid-input-arg", "the Jacobian function must return a matrix, but returns nothing; calling it at t = 0 gave: .*called with too many outputs", f, [0 1], y0, struct ("Jacobian", @(t, y) assert (true)));
%!test check_bad (spvi, "Octave:invalid-input-arg", "HamiltonianHessFcn must return a matrix, but returns nothing; calling it at t = 0 gave: .*called with too many outputs", f, [0 1], y0, struct ("HamiltonianHessFcn", @(t, y) assert (true)));
%!test check_bad ({@odeSV, @odeSPVI}, "Octave:invalid-input-arg", "StepDensityFcn must return a real scalar, but returns nothing; calling it at t = 0 gave: .*called with too many outputs", f, [0 1], y0, struct ("StepControl", "reversible", "RelTol", 1e-3, "StepDensityFcn", @(t, y) assert (true)));
%!error <odeSV: the Hamiltonian must return a real scalar, but returns nothing; calling it at t = 0 gave: .*called with too many outputs>
%! s = odeSV (@(t, y) [y(2); -y(1)], [0 1], [1; 0], symplecticset ("TimeStepSize", 0.1, "Hamiltonian", @(t, y) assert (true)));
%!test check_bad (all3, "mytest:extra", "^extra parameter 7$", @(t, y, a) error ("mytest:extra", "extra parameter %d", a), [0 1], y0, [], 7);
%!test check_bad (all3, "mytest:jac", "^my Jacobian failure$", f, [0 1], y0, struct ("Jacobian", @(t, y) error ("mytest:jac", "my Jacobian failure")));
%!test check_bad (all3, "mytest:hess", "^my Hessian failure$", f, [0 1], y0, struct ("HamiltonianHessFcn", @(t, y) error ("mytest:hess", "my Hessian failure")));
%!test check_bad (all3, "mytest:event", "^my event failure$", f, [0 1], y0, struct ("Events", @(t, y) bi_events (t, y, "error")));
%!test check_bad (all3, "mytest:output", "^my output failure$", f, [0 1], y0, struct ("OutputFcn", @(t, y, flag) error ("mytest:output", "my output failure")));

## ------------------------------------------------------------ Jacobian and Hessian
%!test check_bad (all3, "Octave:invalid-input-arg", "Jacobian must be a function handle or a real 2x2 matrix \\(df/dy\\), got 3x3 double", f, [0 1], y0, struct ("Jacobian", ones (3)));
%!test check_bad (all3, "Octave:invalid-input-arg", "Jacobian must be .*got 3x3 sparse double", f, [0 1], y0, struct ("Jacobian", speye (3)));
%!test check_bad (all3, "Octave:invalid-input-arg", "Jacobian must be .*got 2x2 complex double", f, [0 1], y0, struct ("Jacobian", 1i * eye (2)));
%!test check_bad (all3, "Octave:invalid-input-arg", "Jacobian must be .*got 1x22 char", f, [0 1], y0, struct ("Jacobian", "no_such_function_xyz_2"));
%!test check_bad (all3, "Octave:invalid-input-arg", "the Jacobian matrix must be finite, element 4 is NaN", f, [0 1], y0, struct ("Jacobian", [0 1; -1 NaN]));
%!test check_bad (all3, "Octave:invalid-input-arg", "the Jacobian function must return a 2x2 real matrix \\(df/dy\\), got 3x3 double at t = ", f, [0 1], y0, struct ("Jacobian", @(t, y) ones (3)));
%!test check_bad (all3, "Octave:invalid-input-arg", "the Jacobian function must return a 2x2 real matrix \\(df/dy\\), got 1x4 double at t = ", f, [0 1], y0, struct ("Jacobian", @(t, y) ones (1, 4)));
%!test check_bad (all3, "Octave:invalid-input-arg", "HamiltonianHessFcn must return the Hessian of H, a 2x2 matrix or a vector of 4 elements, got 3x3 double at t = ", f, [0 1], y0, struct ("HamiltonianHessFcn", @(t, y) ones (3)));
%!test check_bad (all3, "Octave:invalid-input-arg", "HamiltonianHessFcn returned a complex value at t = ", f, [0 1], y0, struct ("HamiltonianHessFcn", @(t, y) 1i * eye (2)));
%!test check_bad (all3, "Octave:invalid-input-arg", "HamiltonianHessFcn must be a function handle or the name of a function, got 1x1 double", f, [0 1], y0, struct ("HamiltonianHessFcn", 5));
%!test check_bad (all3, "Octave:invalid-input-arg", "FCN \\(second output\\) must return the Hessian of H, a 2x2 matrix or a vector of 4 elements, got 3x3 double at t = 0", @(t, y) bi_hess2 (t, y, ones (3)), [0 1], y0);
## the right number of elements in the wrong shape: accepted before
%!test check_bad (all3, "Octave:invalid-input-arg", "HamiltonianHessFcn must return the Hessian of H, a 4x4 matrix or a vector of 16 elements, got 2x8 double at t = [0-9.e-]+$", @(t, y) [y(3:4); -y(1:2)], [0 1], [1; 0; 0; 1], struct ("HamiltonianHessFcn", @(t, y) reshape (eye (4), 2, 8)));
%!test check_bad (all3, "Octave:invalid-input-arg", "FCN \\(second output\\) must return the Hessian of H, a 4x4 matrix or a vector of 16 elements, got 8x2 double at t = 0$", @(t, y) bi_hess4 (t, y, reshape (eye (4), 8, 2)), [0 1], [1; 0; 0; 1]);
%!test check_bad (all3, "Octave:invalid-input-arg", "HamiltonianHessFcn must return .*got 1x2x2 double at t = [0-9.e-]+$", f, [0 1], y0, struct ("HamiltonianHessFcn", @(t, y) reshape (eye (2), 1, 2, 2)));
%!test check_bad (all3, "Octave:invalid-input-arg", "HamiltonianHessFcn must return .*got 2x2 logical at t = [0-9.e-]+$", f, [0 1], y0, struct ("HamiltonianHessFcn", @(t, y) true (2)));
## as a matrix, a row or a column: the same run
%!test
%! f4 = @(t, y) [y(3:4); -y(1:2)];
%! o = struct ("TimeStepSize", 0.1);
%! for s = {@odeSE, @odeSV, @odeSPVI}
%!   ref = s{1} (f4, [0 1], [1; 0; 0; 1], setfield (o, "HamiltonianHessFcn", @(t, y) eye (4)));
%!   for shape = {[1 16], [16 1]}
%!     sol = s{1} (f4, [0 1], [1; 0; 0; 1], setfield (o, "HamiltonianHessFcn", @(t, y) reshape (eye (4), shape{1})));
%!     assert (sol.y, ref.y, 0);
%!     sol = s{1} (@(t, y) bi_hess4 (t, y, reshape (eye (4), shape{1})), [0 1], [1; 0; 0; 1], o);
%!     assert (sol.stats.jacobian_source, "second output of FCN (Hessian)");
%!     assert (sol.y, ref.y, 0);
%!   endfor
%! endfor
%!test check_bad (all3, "Octave:invalid-input-arg", "FCN \\(second output\\) must return .*got 1x1 cell at t = 0", @(t, y) bi_hess2 (t, y, {1}), [0 1], y0);

## ------------------------------------------------------------ OPTS
## two fields of one name in different cases, both set: which to take?
## (before, the first, silently); one of them empty is no conflict
%!test check_bad (all3, "Octave:invalid-input-arg", "OPTS sets both RelTol and reltol \\(names are matched in any case\\); give one of them", f, [0 1], y0, struct ("RelTol", 1e-3, "reltol", 1e-5));
%!test check_bad (spvi, "Octave:invalid-input-arg", "OPTS sets both Nodes and nodes", f, [0 1], y0, struct ("Nodes", 3, "nodes", 5));
%!test check_bad (all3, "Octave:invalid-input-arg", "OPTS sets both Events and EVENTS", f, [0 1], y0, struct ("Events", @(t, y) deal (y(1), 0, 0), "EVENTS", @(t, y) deal (y(2), 0, 0)));
%!test
%! o = symplecticset ("TimeStepSize", 0.1);
%! o.nodes = 4;                     # o.Nodes is there, empty
%! sol = odeSPVI (f, [0 1], y0, o);
%! assert (sol.Nodes, 4);

## any empty OPTS is the defaults (the help says so)
%!test
%! for s = all3
%!   [t0, y0d] = s{1} (f, [0 1], y0);
%!   for e = {[], {}, "", zeros(0, 3)}
%!     [t, y] = s{1} (f, [0 1], y0, e{1});
%!     assert ([t, y], [t0, y0d]);
%!   endfor
%! endfor
## a fourth argument that is not a struct is FCN's first parameter (the
## 2013 form): an FCN of (t, y) alone is told so
%!test check_bad (all3, "Octave:invalid-input-arg", "FCN takes 2 arguments, but is called as FCN \\(t, y, p1\\): a parameter follows Y0 or OPTS$", f, [0 1], y0, 5);
%!test check_bad (all3, "Octave:invalid-input-arg", "FCN takes 2 arguments, but is called as FCN \\(t, y, p1, p2\\): 2 parameters follow Y0 or OPTS$", f, [0 1], y0, "RelTol", 2);
%!test check_bad (all3, "Octave:invalid-input-arg", "OPTS must be a struct .*got 1x2 struct", f, [0 1], y0, struct ("RelTol", {1e-3, 1e-4}));
%!test check_bad (all3, "Octave:invalid-input-arg", "RelTol must be a positive finite scalar, got -1", f, [0 1], y0, struct ("RelTol", -1));
%!test check_bad (all3, "Octave:invalid-input-arg", "RelTol must be a positive finite scalar, got 0", f, [0 1], y0, struct ("RelTol", 0));
%!test check_bad (all3, "Octave:invalid-input-arg", "RelTol must be a positive finite scalar, got NaN", f, [0 1], y0, struct ("RelTol", NaN));
%!test check_bad (all3, "Octave:invalid-input-arg", "RelTol must be a positive finite scalar, got Inf", f, [0 1], y0, struct ("RelTol", Inf));
%!test check_bad (all3, "Octave:invalid-input-arg", "RelTol must be a positive real scalar, got 1x1 char", f, [0 1], y0, struct ("RelTol", "a"));
%!test check_bad (all3, "Octave:invalid-input-arg", "RelTol must be a positive real scalar, got 1x2 double", f, [0 1], y0, struct ("RelTol", [1 2]));
%!test check_bad (all3, "Octave:invalid-input-arg", "RelTol must be a positive finite scalar, got -1", f, [0 1], y0, struct ("reltol", -1));
%!test check_bad (all3, "Octave:invalid-input-arg", "AbsTol must be positive and finite, got -1", f, [0 1], y0, struct ("AbsTol", -1));
%!test check_bad (all3, "Octave:invalid-input-arg", "AbsTol must be positive and finite, got 0", f, [0 1], y0, struct ("AbsTol", [1e-6 0]));
%!test check_bad (all3, "Octave:invalid-input-arg", "AbsTol must be positive and finite, got NaN", f, [0 1], y0, struct ("AbsTol", NaN));
%!test check_bad (all3, "Octave:invalid-input-arg", "AbsTol must be a positive scalar or a vector of 2 elements \\(numel \\(Y0\\)\\), got 1x3 double", f, [0 1], y0, struct ("AbsTol", [1 2 3]));
%!test check_bad (all3, "Octave:invalid-input-arg", "AbsTol must be a positive scalar or a vector of 2 elements .*got 1x1 char", f, [0 1], y0, struct ("AbsTol", "a"));
## numel (Y0) elements, but not a vector (ode45 refuses it too)
%!test check_bad (all3, "Octave:invalid-input-arg", "AbsTol must be a positive scalar or a vector of 4 elements .*got 2x2 double", @(t, y) [y(3:4); -y(1:2)], [0 1], [1 0 0 1], struct ("AbsTol", 1e-6 * ones (2)));
%!test check_bad (all3, "Octave:invalid-input-arg", "AbsTol must be .*got 1x1x2 double", f, [0 1], y0, struct ("AbsTol", 1e-6 * ones (1, 1, 2)));
%!test check_bad (all3, "Octave:invalid-input-arg", "AbsTol must be a scalar when NormControl is \"on\"", f, [0 1], y0, struct ("AbsTol", [1 2], "NormControl", "on"));
%!test check_bad (all3, "Octave:invalid-input-arg", "MaxStep must be a positive scalar, got 0", f, [0 1], y0, struct ("MaxStep", 0));
%!test check_bad (all3, "Octave:invalid-input-arg", "MaxStep must be a positive scalar, got -1", f, [0 1], y0, struct ("MaxStep", -1));
%!test check_bad (all3, "Octave:invalid-input-arg", "MaxStep must be a positive scalar, got NaN", f, [0 1], y0, struct ("MaxStep", NaN));
%!test check_bad (all3, "Octave:invalid-input-arg", "MaxStep must be a positive real scalar, got 1x1 cell", f, [0 1], y0, struct ("MaxStep", {{1}}));
## more than 1e12 steps (near t = 0 the least step does not bound them)
%!test check_bad (all3, "Octave:invalid-input-arg", "MaxStep = 1e-300 needs 1e\\+300 steps to cover TSPAN, more than the 1e12 allowed; expected MaxStep >= 1e-12", f, [0 1], y0, struct ("MaxStep", 1e-300));
%!test check_bad (all3, "Octave:invalid-input-arg", "MaxStep = 1e-20 needs 1e\\+20 steps", f, [1 2], y0, struct ("MaxStep", 1e-20));
%!test check_bad (all3, "Octave:invalid-input-arg", "InitialStep must be a positive scalar, got -1", f, [0 1], y0, struct ("InitialStep", -1));
%!test check_bad (all3, "Octave:invalid-input-arg", "InitialStep must be a positive scalar, got 0", f, [0 1], y0, struct ("InitialStep", 0));
%!test check_bad (all3, "Octave:invalid-input-arg", "InitialStep must be a positive scalar, got NaN", f, [0 1], y0, struct ("InitialStep", NaN));
%!test check_bad (all3, "Octave:invalid-input-arg", "InitialStep must be a positive scalar, got -Inf", f, [0 1], y0, struct ("InitialStep", -Inf));
%!test check_bad (all3, "Octave:invalid-input-arg", "InitialStep must be a positive real scalar, got 1x2 double", f, [0 1], y0, struct ("InitialStep", [1 2]));
%!test check_bad (all3, "Octave:invalid-input-arg", "TimeStepSize must be a positive finite scalar, got 0", f, [0 1], y0, struct ("TimeStepSize", 0));
%!test check_bad (all3, "Octave:invalid-input-arg", "TimeStepSize must be a positive finite scalar, got -0.1", f, [0 1], y0, struct ("TimeStepSize", -0.1));
%!test check_bad (all3, "Octave:invalid-input-arg", "TimeStepSize must be a positive finite scalar, got NaN", f, [0 1], y0, struct ("TimeStepSize", NaN));
%!test check_bad (all3, "Octave:invalid-input-arg", "TimeStepSize must be a positive finite scalar, got Inf", f, [0 1], y0, struct ("TimeStepSize", Inf));
%!test check_bad (all3, "Octave:invalid-input-arg", "TimeStepSize must be a positive real scalar, got 1x2 double", f, [0 1], y0, struct ("TimeStepSize", [0.1 0.2]));
%!test check_bad (all3, "Octave:invalid-input-arg", "TimeStepSize must be a positive real scalar, got 1x1 logical", f, [0 1], y0, struct ("TimeStepSize", true));
%!test check_bad (all3, "Octave:invalid-input-arg", "TimeStepSize = 1e-300 needs 1e\\+300 steps to cover TSPAN, more than the 1e12 allowed", f, [0 1], y0, struct ("TimeStepSize", 1e-300));
%!test check_bad (all3, "Octave:invalid-input-arg", "the fixed step 1e-09 is below the round-off of t", f, [1e8 1e8+1], y0, struct ("TimeStepSize", 1e-9, "TimeStepNumber", 3));
%!test check_bad (all3, "Octave:invalid-input-arg", "TimeStepNumber\\*TimeStepSize = .* overflows", f, [0 1], y0, struct ("TimeStepSize", 1e300, "TimeStepNumber", 1e10));
%!test check_bad (all3, "Octave:invalid-input-arg", "TimeStepNumber must be between 1 and 1000000000000, got 0", f, [0 1], y0, struct ("TimeStepSize", 0.1, "TimeStepNumber", 0));
%!test check_bad (all3, "Octave:invalid-input-arg", "TimeStepNumber must be between 1 and 1000000000000, got -3", f, [0 1], y0, struct ("TimeStepNumber", -3));
%!test check_bad (all3, "Octave:invalid-input-arg", "TimeStepNumber must be an integer, got 2.5", f, [0 1], y0, struct ("TimeStepSize", 0.1, "TimeStepNumber", 2.5));
%!test check_bad (all3, "Octave:invalid-input-arg", "TimeStepNumber must be an integer, got Inf", f, [0 1], y0, struct ("TimeStepNumber", Inf));
%!test check_bad (all3, "Octave:invalid-input-arg", "MaxSteps must be between 1 and .*, got 0", f, [0 1], y0, struct ("MaxSteps", 0));
%!test check_bad (all3, "Octave:invalid-input-arg", "MaxSteps must be an integer, got 1.5", f, [0 1], y0, struct ("MaxSteps", 1.5));
%!test check_bad (all3, "Octave:invalid-input-arg", "NewtonTol must be a positive finite scalar, got 0", f, [0 1], y0, struct ("NewtonTol", 0));
%!test check_bad (all3, "Octave:invalid-input-arg", "NewtonTol must be below 1 \\(it is relative to the size of q or p\\), got 1$", f, [0 1], y0, struct ("NewtonTol", 1));
%!test check_bad (all3, "Octave:invalid-input-arg", "NewtonTol must be below 1 .*got 1e\\+300", f, [0 1], y0, struct ("NewtonTol", 1e300));
%!test check_bad (all3, "Octave:invalid-input-arg", "MaxNewtonIterations must be between 1 and 1000, got 0", f, [0 1], y0, struct ("MaxNewtonIterations", 0));
%!test check_bad (all3, "Octave:invalid-input-arg", "Refine must be between 1 and .*, got 0", f, [0 1], y0, struct ("Refine", 0));
%!test check_bad (all3, "Octave:invalid-input-arg", "Refine must be an integer, got 2.5", f, [0 1], y0, struct ("Refine", 2.5));
%!test check_bad (all3, "Octave:invalid-input-arg", "NormControl must be \"on\" or \"off\", got \"maybe\"", f, [0 1], y0, struct ("NormControl", "maybe"));
%!test check_bad (all3, "Octave:invalid-input-arg", "Stats must be \"on\" or \"off\", got 1x1 complex double", f, [0 1], y0, struct ("Stats", 5i));
%!test check_bad ({@odeSE, @odeSV}, "Octave:invalid-input-arg", "Separable must be \"on\" or \"off\", got \"x\"", f, [0 1], y0, struct ("Separable", "x"));
%!test check_bad (all3, "Octave:invalid-input-arg", "NormControl must be \"on\" or \"off\", got 1x1 double", f, [0 1], y0, struct ("NormControl", NaN));
%!test check_bad (all3, "Octave:invalid-input-arg", "Stats must be \"on\" or \"off\", got 2x1 char", f, [0 1], y0, struct ("Stats", ["o"; "n"]));
%!test check_bad ({@odeSPVI}, "Octave:invalid-input-arg", "NewtonMatrix must be \"auto\", \"kept\" or \"new\", got \"old\"", f, [0 1], y0, struct ("NewtonMatrix", "old"));
%!test check_bad ({@odeSPVI}, "Octave:invalid-input-arg", "NewtonMatrix must be \"auto\", \"kept\" or \"new\", got 1x1 double", f, [0 1], y0, struct ("NewtonMatrix", 1));
%!test check_bad ({@odeSPVI}, "Octave:invalid-input-arg", "NewtonMatrix must be \"auto\", \"kept\" or \"new\", got \"automatic\"", f, [0 1], y0, struct ("NewtonMatrix", "automatic"));
%!test check_bad (all3, "Octave:invalid-input-arg", "Vectorized must be \"on\" or \"off\", got 1x2 double", f, [0 1], y0, struct ("Vectorized", [1 1]));
%!test check_bad (all3, "Octave:invalid-input-arg", "OutputSel must hold integer indices between 1 and 2, got 0", f, [0 1], y0, struct ("OutputSel", [0 1]));
%!test check_bad (all3, "Octave:invalid-input-arg", "OutputSel must hold integer indices between 1 and 2, got 1.5", f, [0 1], y0, struct ("OutputSel", 1.5));
%!test check_bad (all3, "Octave:invalid-input-arg", "OutputSel must hold integer indices between 1 and 2, got 5", f, [0 1], y0, struct ("OutputSel", 5));
%!test check_bad (all3, "Octave:invalid-input-arg", "OutputSel must be a vector of indices into Y0, got 1x1 cell", f, [0 1], y0, struct ("OutputSel", {{1}}));
%!test check_bad (all3, "Octave:invalid-input-arg", "a logical OutputSel must have 2 elements \\(one per element of Y0\\), got 1$", f, [0 1], y0, struct ("OutputSel", true));

## ------------------------------------------------------------ Events and OutputFcn
%!test check_bad (all3, "Octave:invalid-input-arg", "Events must be a function handle or the name of a function, got 1x1 double", f, [0 1], y0, struct ("Events", 3));
%!test check_bad (all3, "Octave:invalid-input-arg", "Events must be a function handle .*got \"no_such_function_xyz_3\", which names no function", f, [0 1], y0, struct ("Events", "no_such_function_xyz_3"));
%!test check_bad (all3, "Octave:invalid-input-arg", "OutputFcn must be a function handle or the name of a function, got 1x1 double", f, [0 1], y0, struct ("OutputFcn", 3));
%!test check_bad (all3, "Octave:invalid-input-arg", "OutputFcn must be a function handle .*got \"no_such_function_xyz_4\", which names no function", f, [0 1], y0, struct ("OutputFcn", "no_such_function_xyz_4"));
%!test check_bad (all3, "Octave:invalid-input-arg", "OutputFcn must be a function handle .*got 1x1 cell", f, [0 1], y0, struct ("OutputFcn", {{@odeplot}}));
%!test check_bad (all3, "Octave:invalid-input-arg", "the Events function must return three outputs \\[VALUE, ISTERMINAL, DIRECTION\\], got 1", f, [0 1], y0, struct ("Events", @(t, y) y(1)));
%!test check_bad (all3, "Octave:invalid-input-arg", "the Events function must return three outputs \\[VALUE, ISTERMINAL, DIRECTION\\], got 1", f, [0 1], y0, struct ("Events", @bi_events1));
%!test
%! ## an empty VALUE at t0: no events, as in ode45
%! for s = all3
%!   o = struct ("Events", @(t, y) bi_events (t, y, "empty"), "TimeStepSize", 0.1);
%!   [t, y, te, ye, ie] = s{1} (f, [0 1], y0, o);
%!   assert (numel (t), 11);
%!   assert (isempty (te) && isempty (ye) && isempty (ie));
%!   sol = s{1} (f, [0 1], y0, o);
%!   assert (isempty (sol.xe) && isempty (sol.ie));
%! endfor
%!test check_bad (all3, "Octave:invalid-input-arg", "the Events function must return \\[VALUE, ISTERMINAL, DIRECTION\\] with a real VALUE, got VALUE = 1x1 cell", f, [0 1], y0, struct ("Events", @(t, y) deal ({1}, 0, 0)));
%!test check_bad (all3, "Octave:invalid-input-arg", "the Events function must return .*got VALUE = 1x1 complex double", f, [0 1], y0, struct ("Events", @(t, y) bi_events (t, y, "complex")));
%!test check_bad (all3, "Octave:invalid-input-arg", "the Events function must return .*got VALUE = 1x1 char", f, [0 1], y0, struct ("Events", @(t, y) bi_events (t, y, "char")));
%!test check_bad (all3, "Octave:invalid-input-arg", "the Events function must return ISTERMINAL and DIRECTION of the size of VALUE, got 1x3 double at t = 0", f, [0 1], y0, struct ("Events", @(t, y) bi_events (t, y, "term")));
%!test check_bad (all3, "Octave:invalid-input-arg", "the Events function must return ISTERMINAL and DIRECTION .*got 1x1 cell at t = 0", f, [0 1], y0, struct ("Events", @(t, y) bi_events (t, y, "dir")));
%!test check_bad (all3, "Octave:invalid-input-arg", "the Events function must return VALUE of 1 real element, got 2x1 double at t = 0\\.[5-9]", f, [0 1], y0, struct ("Events", @(t, y) bi_events (t, y, "grow")));
%!test check_bad (all3, "Octave:invalid-input-arg", "the Events function must return DIRECTION of -1, 0 or 1, got 2 at t = 0", f, [0 1], y0, struct ("Events", @(t, y) deal (y(1), 0, 2)));
%!test check_bad (all3, "Octave:invalid-input-arg", "the Events function must return DIRECTION of -1, 0 or 1, got 0.5 at t = 0", f, [0 1], y0, struct ("Events", @(t, y) deal ([y(1); y(2)], 0, [1; 0.5])));
%!test check_bad (all3, "Octave:invalid-input-arg", "the Events function returned NaN in VALUE\\(2\\) at t = 0$", f, [0 1], y0, struct ("Events", @(t, y) deal ([y(1); NaN], 0, 0)));
%!test check_bad (all3, "Octave:invalid-input-arg", "the Events function returned NaN in VALUE\\(1\\) at t = 0\\.[45]", f, [0 1], y0, struct ("Events", @(t, y) deal (merge (t < 0.45, y(1), NaN), 0, 0), "TimeStepSize", 0.1));

## ------------------------------------------------------------ odeSPVI: Q_DoFs, Nodes
%!test check_bad (spvi, "Octave:invalid-input-arg", "Q_DoFs must be an integer, got 2.5", f, [0 1], y0, struct ("Q_DoFs", 2.5));
%!test check_bad (spvi, "Octave:invalid-input-arg", "Q_DoFs must be between 2 and 41, got 1", f, [0 1], y0, struct ("Q_DoFs", 1));
%!test check_bad (spvi, "Octave:invalid-input-arg", "Q_DoFs must be between 2 and 41, got -1", f, [0 1], y0, struct ("Q_DoFs", -1));
%!test check_bad (spvi, "Octave:invalid-input-arg", "Q_DoFs must be between 2 and 41, got 42", f, [0 1], y0, struct ("Q_DoFs", 42, "Nodes", 40));
%!test check_bad (spvi, "Octave:invalid-input-arg", "Q_DoFs must be an integer, got NaN", f, [0 1], y0, struct ("Q_DoFs", NaN));
%!test check_bad (spvi, "Octave:invalid-input-arg", "Q_DoFs must be an integer, got Inf", f, [0 1], y0, struct ("Q_DoFs", Inf));
%!test check_bad (spvi, "Octave:invalid-input-arg", "Q_DoFs must be an integer scalar, got 1x1 char", f, [0 1], y0, struct ("Q_DoFs", "a"));
%!test check_bad (spvi, "Octave:invalid-input-arg", "Q_DoFs must be an integer scalar, got 1x2 double", f, [0 1], y0, struct ("Q_DoFs", [2 3]));
%!test check_bad (spvi, "Octave:invalid-input-arg", "Q_DoFs must be an integer scalar, got 1x1 complex double", f, [0 1], y0, struct ("Q_DoFs", 2 + 1i));
%!test check_bad (spvi, "Octave:invalid-input-arg", "Nodes must be between 1 and 40, got 0", f, [0 1], y0, struct ("Nodes", 0));
%!test check_bad (spvi, "Octave:invalid-input-arg", "Nodes must be an integer, got 1.5", f, [0 1], y0, struct ("Nodes", 1.5));
%!test check_bad (spvi, "Octave:invalid-input-arg", "Nodes must be between 1 and 40, got 100", f, [0 1], y0, struct ("Nodes", 100));
%!test check_bad (spvi, "Octave:invalid-input-arg", "Nodes must be an integer scalar, got 1x1 logical", f, [0 1], y0, struct ("Nodes", true));
%!test check_bad (spvi, "Octave:invalid-input-arg", "P_DoFs must be between 1 and 40, got -1", f, [0 1], y0, struct ("P_DoFs", -1));
%!test check_bad (spvi, "Octave:invalid-input-arg", "Q_DoFs = 7 with Nodes = 3 is a degenerate pair: .*Q_DoFs <= 2\\*Nodes", f, [0 1], y0, struct ("Q_DoFs", 7, "Nodes", 3));
%!test check_bad (spvi, "Octave:invalid-input-arg", "Q_DoFs = 3 with Nodes = 1 is a degenerate pair", f, [0 1], y0, struct ("Q_DoFs", 3, "Nodes", 1));
%!test check_bad (spvi, "Octave:invalid-input-arg", "Q_DoFs = 5 with Nodes = 2 is a degenerate pair", f, [0 1], y0, struct ("Q_DoFs", 5, "P_DoFs", 2));
%!test check_bad (spvi, "Octave:invalid-input-arg", "PolynomialDegree must be between 1 and 39, got 0", f, [0 1], y0, struct ("PolynomialDegree", 0));
%!test check_bad (spvi, "Octave:invalid-input-arg", "PolynomialDegree must be between 1 and 39, got 41", f, [0 1], y0, struct ("PolynomialDegree", 41));
%!test check_bad (spvi, "Octave:invalid-input-arg", "PolynomialDegree must be an integer, got 2.5", f, [0 1], y0, struct ("PolynomialDegree", 2.5));
%!test check_bad (spvi, "Octave:invalid-input-arg", "Q_DoFs = 5 with Nodes = 2 is a degenerate pair", f, [0 1], y0, struct ("PolynomialDegree", 4, "Nodes", 2));
%!test check_bad (spvi, "Octave:invalid-input-arg", "Nodes = 5 and its alias P_DoFs = 2 disagree; give one of them", f, [0 1], y0, symplecticset ("Nodes", 5, "P_DoFs", 2));
%!test check_bad (spvi, "Octave:invalid-input-arg", "Q_DoFs = 3 and PolynomialDegree = 5 \\(Q_DoFs = degree \\+ 1\\) disagree", f, [0 1], y0, struct ("PolynomialDegree", 5, "Q_DoFs", 3));
%!test
%! ## two names of one number that agree are taken
%! o = symplecticset ("TimeStepSize", 0.1, "Nodes", 4, "P_DoFs", 4, "PolynomialDegree", 4, "Q_DoFs", 5);
%! s = odeSPVI (@(t, y) [y(2); -y(1)], [0 1], [1; 0], o);
%! assert ([s.Q_DoFs, s.Nodes], [5 4]);
%! s = odeSPVI (@(t, y) [y(2); -y(1)], [0 1], [1; 0], struct ("TimeStepSize", 0.1, "PolynomialDegree", 5, "P_DoFs", 4));
%! assert ([s.Q_DoFs, s.Nodes], [6 4]);

## ------------------------------------------------------------ good inputs of unusual types work
%!test
%! for s = all3
%!   [t, y] = s{1} (f, single ([0 1]), int8 ([1 0]));
%!   assert (class (y), "double");
%!   assert (y(end,1), cos (1), 5e-2);
%!   [t, y] = s{1} (f, [0 1], [1 0], struct ("Jacobian", single ([0 1; -1 0])));
%!   assert (y(end,1), cos (1), 5e-2);
%!   [t, y] = s{1} (@(t, y) int32 ([0; 0]), [0 1], [1 0]);
%!   assert (y(end,:), [1 0]);
%! endfor
