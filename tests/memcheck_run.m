## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## -*- texinfo -*-
## @deftypefn {} {@var{status} =} memcheck_run ()
## The workload of @code{make check-memory} (tests/check_memory.sh): a
## short tour of odeSE, odeSV and odeSPVI meant to run under valgrind, so
## that every code path of the MEX layer and of the core that a user can
## reach is executed at least once: adaptive and fixed steps, output times,
## Refine, the sol struct, events, OutputFcn/OutputSel, every Jacobian
## source, Vectorized, Separable, backwards, Stats; bad inputs (errors
## raised in the MEX layer), errors thrown by the user's functions in the
## middle of a run, NaN from FCN, Newton and MaxSteps failures (warnings
## with partial results), SecondOrder, odeSV's methods, JPattern,
## reversible steps, sparse Newton matrices, ensembles.
## Returns 0 if all results were as expected, 1 otherwise (valgrind's own
## findings are judged by check_memory.sh).
## Not a test_*.m file: the test runner does not run it.
## @end deftypefn

function status = memcheck_run ()

  nbad = 0;
  warning ("off", "all");
  osc = @(t, y) [y(2); -y(1)];
  kep = @(t, y) [y(3:4); -y(1:2) / norm(y(1:2))^3];
  y0k = [0.4; 0; 0; 2];
  solvers = {@odeSE, @odeSV, @odeSPVI};

  for i = 1:3
    s = solvers{i};
    name = func2str (s);
    ## adaptive, fixed, output times, Refine, backwards, sol
    [t, y] = s (osc, [0 1], [1 0]);
    nbad += check (abs (y(end,1) - cos (1)) < 5e-2, name, "adaptive");
    [t, y] = s (osc, [0 1], [1 0], struct ("TimeStepSize", 0.1));
    nbad += check (numel (t) == 11, name, "fixed");
    [t, y] = s (osc, [0 1], [1 0], struct ("TimeStepSize", 0.1, "TimeStepNumber", 4));
    nbad += check (numel (t) == 5, name, "fixed N");
    [t, y] = s (kep, linspace (0, 2, 7), y0k, struct ("RelTol", 1e-6, "AbsTol", [1 1 1 1] * 1e-8));
    nbad += check (numel (t) == 7, name, "tspan times");
    [t, y] = s (kep, [0 1], y0k, struct ("Refine", 4, "NormControl", "on"));
    nbad += check (numel (t) > 4, name, "refine");
    [t, y] = s (osc, [1 0], [1 0]);
    nbad += check (t(end) == 0, name, "backwards");
    sol = s (osc, [0 1], [1 0]);
    nbad += check (isstruct (sol) && numel (sol.x) == columns (sol.y), name, "sol");
    ## Jacobian sources
    [t, y] = s (osc, [0 1], [1 0], struct ("Jacobian", [0 1; -1 0]));
    [t, y] = s (osc, [0 1], [1 0], struct ("Jacobian", @(t, y) [0 1; -1 0]));
    [t, y] = s (osc, [0 1], [1 0], struct ("HamiltonianHessFcn", @(t, y) eye (2)));
    [t, y] = s (@mc_hess2, [0 1], [1 0]);
    ## called by name: a simple handle and a name, with the Hessian
    [t, y] = s (@memcheck_osc, [0 1], [1 0], struct ("TimeStepSize", 0.1));
    [t2, y2] = s ("memcheck_osc", [0 1], [1 0], struct ("TimeStepSize", 0.1));
    nbad += check (isequal (y, y2) && abs (y(end,1) - cos (1)) < 5e-2, name, "by name");
    ## Vectorized finite differences of more states than the kept arrays
    d = 12;
    [t, y] = s (@(t, y) [y(d+1:end, :); -y(1:d, :).^3], [0 0.2], ...
                [0.1 * ones(d, 1); zeros(d, 1)], ...
                struct ("TimeStepSize", 0.1, "Vectorized", "on"));
    nbad += check (numel (t) == 3 && all (isfinite (y(:))), name, "vectorized FD, d = 12");
    [t, y] = s (kep, [0 1], y0k, struct ("Separable", "on", "TimeStepSize", 0.05));
    [t, y] = s (@(t, y) [y(2,:); -y(1,:)], [0 1], [1 0], struct ("Vectorized", "on"));
    nbad += check (abs (y(end,1) - cos (1)) < 5e-2, name, "vectorized");
    ## sparse arguments, options and returned values (taken as full)
    [t, y] = s (@(t, y) sparse ([y(2); -y(1)]), sparse ([0 1]), sparse ([1 0]), ...
                struct ("HamiltonianHessFcn", @(t, y) speye (2), "AbsTol", sparse ([1e-6 1e-6])));
    nbad += check (abs (y(end,1) - cos (1)) < 5e-2, name, "sparse");
    [t, y] = s (osc, [0 1], [1 0], struct ("Jacobian", sparse ([0 1; -1 0]), "TimeStepSize", 0.1));
    nbad += check (numel (t) == 11, name, "sparse Jacobian");
    ## sparse Newton matrices (KLU): a mass that is not the identity, a
    ## non-separable H, a sparse Hessian with a NaN (dropped for finite
    ## differences on its own pattern) and one too large (the probe)
    [t, y] = s (@(t, y) [2*y(2); -y(1)], [0 1], [1 0], struct ("HamiltonianHessFcn", @(t, y) sparse ([1 0; 0 2]), "TimeStepSize", 0.1));
    nbad += check (abs (y(end,1) - cos (sqrt (2))) < 0.15, name, "sparse, mass 1/2");
    [t, y] = s (@(t, y) [y(2) + y(1); -y(1) - y(2)], [0 1], [1 0], struct ("HamiltonianHessFcn", @(t, y) sparse ([1 1; 1 1]), "TimeStepSize", 0.1));
    nbad += check (all (isfinite (y(:))), name, "sparse, not separable");
    sol = s (osc, [0 0.1], [1 0], struct ("TimeStepSize", 0.01, "HamiltonianHessFcn", @(t, y) sparse ([NaN 0; 0 1])));
    nbad += check (sol.x(end) == 0.1 && ! isempty (strfind (sol.stats.jacobian_source, "then finite")), name, "sparse NaN Hessian dropped");
    sol = s (osc, [0 0.1], [1 0], struct ("TimeStepSize", 0.01, "HamiltonianHessFcn", @(t, y) 1e8 * speye (2)));
    nbad += check (sol.x(end) == 0.1 && ! isempty (strfind (sol.stats.jacobian_source, "then finite")), name, "sparse Hessian too large");
    if (strcmp (name, "odeSPVI"))
      ## a pair without stages: the whole system, sparse
      [t, y] = s (osc, [0 1], [1 0], struct ("HamiltonianHessFcn", @(t, y) speye (2), "Q_DoFs", 3, "Nodes", 3, "TimeStepSize", 0.1));
      nbad += check (abs (y(end,1) - cos (1)) < 1e-4, name, "sparse, whole system");
    endif
    ## a span of a few ulps of t, and a MaxStep below the least step
    [t, y] = s (osc, [1 1+1e-14], [1 0]);
    nbad += check (t(end) == 1+1e-14, name, "span of a few ulps");
    evalc ("[t, y] = s (osc, [1e6 1e6+1e-3], [1 0], struct ('MaxStep', 1e-14));");
    nbad += check (t(end) == 1e6, name, "MaxStep below the least step");
    ## RelTol raised to 100 eps (a warning); a MaxStep of more than 1e12
    ## steps and the name of a file that is no function (errors)
    evalc ("[t, y] = s (osc, [0 0.01], [1 0], struct ('RelTol', 1e-300));");
    nbad += check (t(end) == 0.01, name, "RelTol raised");
    nbad += expect_error (s, "Octave:invalid-input-arg", osc, [0 1], [1 0], struct ("MaxStep", 1e-300));
    nbad += expect_error (s, "Octave:invalid-input-arg", "memcheck_run.m", [0 1], [1 0]);
    ## Newton fails with a Hessian that misses the damping: finite
    ## differences take over (a new stepper)
    sol = s (@(t, y) [y(2); -y(1) - 100 * y(2)], [0 0.1], [1 0], ...
             struct ("TimeStepSize", 0.01, "HamiltonianHessFcn", @(t, y) eye (2)));
    nbad += check (sol.x(end) == 0.1 && ! isempty (strfind (sol.stats.jacobian_source, "then finite")), name, "Hessian dropped");
    ## and a Hessian with a NaN
    sol = s (osc, [0 0.1], [1 0], struct ("TimeStepSize", 0.01, "HamiltonianHessFcn", @(t, y) [NaN 0; 0 1]));
    nbad += check (sol.x(end) == 0.1 && ! isempty (strfind (sol.stats.jacobian_source, "then finite")), name, "NaN Hessian dropped");
    ## events, OutputFcn, OutputSel, Stats
    ev = @(t, y) deal ([y(1); y(2)], [0; 1], [0; -1]);
    [t, y, te, ye, ie] = s (osc, [0 8], [1 0], struct ("Events", ev));
    nbad += check (numel (te) >= 1 && abs (t(end) - 2*pi) < 0.1, name, "events");
    ev2 = @(t, y) deal (t - 0.5 + 1e-3 * (1:70)', zeros (70, 1), 0);
    [t, y, te] = s (osc, [0 1], [1 0], struct ("Events", ev2, "TimeStepSize", 0.1));
    nbad += check (numel (te) >= 64, name, "70 events in one step");
    nrows = 0;
    out = @(t, y, flag) false;
    [t, y] = s (osc, [0 1], [1 0], struct ("OutputFcn", out, "OutputSel", 2));
    [t, y] = s (osc, [0 1], [1 0], struct ("OutputFcn", @(t, y, flag) ! isempty (t) && t(end) > 0.5));
    nbad += check (t(end) < 1, name, "OutputFcn stop");
    [t, y] = s (osc, [0 1], [1 0], struct ("OutputFcn", @(t, y, flag) "yes"));
    nbad += check (t(end) < 1, name, "OutputFcn stop, char");
    nbad += expect_error (s, "Octave:invalid-input-arg", osc, [0 1], [1 0], struct ("OutputFcn", @(t, y, flag) {1}));
    [t, y, te] = s (osc, [0 1], [1 0], struct ("Events", @(t, y) deal ([], 0, 0)));
    nbad += check (t(end) == 1 && isempty (te), name, "empty event VALUE");
    evalc ("[t, y] = s (osc, [0 1], [1 0], struct ('Stats', 'on'));");
    ## extra parameters
    [t, y] = s (@(t, y, a, b) a * [y(2); -y(1)] + b, [0 1], [1 0], [], 1, 0);
    ## run-time failures: warnings and partial results
    lastwarn ("");
    [t, y] = s (@(t, y) [y(2); -y(1)] ./ (t <= 0.5), [0 1], [1 0]);
    nbad += check (t(end) <= 0.51 && all (isfinite (y(:))), name, "NaN after 0.5");
    [t, y] = s (@(t, y) [y(2); -y(1)] ./ (t <= 0.5), [0 1], [1 0], struct ("TimeStepSize", 0.01));
    nbad += check (t(end) <= 0.51 && all (isfinite (y(:))), name, "NaN after 0.5, fixed");
    [t, y] = s (osc, [0 100], [1 0], struct ("MaxSteps", 5, "Refine", 1));
    nbad += check (numel (t) == 6, name, "MaxSteps");
    [t, y] = s (@(t, y) [y(2); -1e3 * y(1)^3], [0 10], [10 0], struct ("TimeStepSize", 1));
    ## errors: bad arguments, and the user's own errors in mid-run
    nbad += expect_error (s, "Octave:invalid-input-arg", osc, [0 1], [1 2 3]);
    nbad += expect_error (s, "Octave:invalid-input-arg", osc, [0 NaN], [1 0]);
    nbad += expect_error (s, "Octave:invalid-input-arg", osc, [0 1], [1 0], struct ("RelTol", -1));
    nbad += expect_error (s, "Octave:invalid-input-arg", @(t, y) [1; 2; 3], [0 1], [1 0]);
    nbad += expect_error (s, "Octave:invalid-input-arg", @(t, y) [y(2); -y(1)] + (t > 0.5) * 1i, [0 1], [1 0]);
    nbad += expect_error (s, "Octave:invalid-input-arg", osc, [0 1], [1 0], struct ("Jacobian", @(t, y) ones (3)));
    ## a Hessian of the wrong shape, one name set twice, a NaN in Y0 (its
    ## message formatted by SYMMEX_NUM)
    nbad += expect_error (s, "Octave:invalid-input-arg", osc, [0 1], [1 0], struct ("HamiltonianHessFcn", @(t, y) reshape (eye (2), 1, 2, 2)));
    nbad += expect_error (s, "Octave:invalid-input-arg", osc, [0 1], [1 0], struct ("RelTol", 1e-3, "reltol", 1e-4));
    nbad += expect_error (s, "Octave:invalid-input-arg", osc, [0 1], [1 0/0]);
    nbad += expect_error (s, "mc:fcn", @(t, y) mc_fail_after (t, y, 0.5), [0 1], [1 0]);
    nbad += expect_error (s, "mc:fcn", @(t, y) mc_fail_after (t, y, 0.5), [0 1], [1 0], struct ("TimeStepSize", 0.01, "Refine", 2));
    nbad += expect_error (s, "mc:ev", osc, [0 1], [1 0], struct ("Events", @(t, y) mc_ev_fail (t, y)));
    nbad += expect_error (s, "Octave:invalid-input-arg", osc, [0 1], [1 0], struct ("Events", @(t, y) deal (merge (t < 0.45, y(1), NaN), 0, 0), "TimeStepSize", 0.1));
    ## zero pairs inside steps (odeSPVI: samples inside the step and the
    ## parabola's turning points)
    [t, y, te] = s (osc, [0 20], [1 0], struct ("Events", @(t, y) deal (y(1) - 0.99, 0, 0), "RelTol", 1e-4));
    nbad += check (numel (te) == 7, name, "zero pairs");
    nbad += expect_error (s, "mc:out", osc, [0 1], [1 0], struct ("OutputFcn", @(t, y, f) mc_out_fail (t, y, f)));
    nbad += expect_error (s, "mc:hess", osc, [0 1], [1 0], struct ("HamiltonianHessFcn", @(t, y) error ("mc:hess", "x")));
  endfor
  ## odeSPVI's own options
  nbad += expect_error (@odeSPVI, "Octave:invalid-input-arg", osc, [0 1], [1 0], struct ("Q_DoFs", 9, "Nodes", 2));
  for q = [2 3 5]
    [t, y] = odeSPVI (kep, [0 1], y0k, struct ("Q_DoFs", q, "Nodes", 3));
  endfor
  [t, y] = odeSPVI (kep, [0 1], y0k, struct ("PolynomialDegree", 6, "TimeStepSize", 0.1));
  nbad += check (numel (t) == 11, "odeSPVI", "PolynomialDegree");
  ## a new Newton matrix on every step, fixed and adaptive
  for ts = {0.1, []}
    [t, y] = odeSPVI (kep, [0 1], y0k, struct ("NewtonMatrix", "new", "TimeStepSize", ts{1}));
    nbad += check (all (isfinite (y(:))), "odeSPVI", "NewtonMatrix new");
  endfor
  nbad += expect_error (@odeSPVI, "Octave:invalid-input-arg", osc, [0 1], [1 0], struct ("NewtonMatrix", "x"));
  ## SecondOrder (FCN gets q alone; Hamiltonian, Events and OutputFcn
  ## [q; v]), Vectorized too; odeSV's methods, explicit and implicit, with
  ## compensated sums, events and dense output
  acc = @(t, q) -q ./ sum (q.^2, 1).^1.5;
  Hk = @(t, y) sum (y(3:4).^2) / 2 - 1 / norm (y(1:2));
  for s = {@odeSE, @odeSV}
    sol = s{1} (acc, [0 1], y0k, struct ("SecondOrder", "on", "TimeStepSize", 0.01, ...
                "Hamiltonian", Hk, "Events", @(t, y) deal (y(2) - 0.5, 0, 0), ...
                "OutputFcn", @(t, y, flag) false, "Vectorized", "on", "Dense", "on"));
    nbad += check (sol.stats.max_dH < 0.1 && numel (sol.xe) == 1, func2str (s{1}), "SecondOrder");
    [t, y] = s{1} (acc, [0 1], y0k, struct ("SecondOrder", "on"));
    nbad += check (t(end) == 1, func2str (s{1}), "SecondOrder adaptive");
    nbad += expect_error (s{1}, "Octave:invalid-input-arg", @(t, q) [q; 1], [0 1], y0k, struct ("SecondOrder", "on"));
  endfor
  for m = {"yoshida4", "blanesmoan6"}
    [t, y, te] = odeSV (kep, [0 1], y0k, struct ("Method", m{1}, "TimeStepSize", 0.05, ...
                        "Separable", "on", "CompensatedSummation", "on", "Refine", 3, ...
                        "Events", @(t, y) deal (y(2) - 0.5, 0, 0)));
    nbad += check (numel (t) == 61 && numel (te) == 1, m{1}, "explicit");
  endfor
  [t, y] = odeSV (kep, [0 1], y0k, struct ("Method", "suzuki4", "TimeStepSize", 0.05));
  nbad += check (numel (t) == 21 && all (isfinite (y(:))), "suzuki4", "implicit");
  nbad += expect_error (@odeSV, "Octave:invalid-input-arg", kep, [0 1], y0k, struct ("Method", "ruth3", "TimeStepSize", 0.05));
  nbad += expect_error (@odeSV, "Octave:invalid-input-arg", kep, [0 1], y0k, struct ("Method", "yoshida4"));
  ## ensembles: members in rounds (their stacks, the batch of all their
  ## states, events, a failing member, sol, OutputFcn and its stop),
  ## explicit steps stacked, and a user's error raised in mid-run
  kepv = @(t, y) [y(3:4,:); -y(1:2,:) ./ (sum (y(1:2,:) .* y(1:2,:), 1) .^ 1.5)];
  Y0 = [y0k, y0k .* [1.1; 1; 1; 0.9], [1; 0; 0; 0]];
  for s = {@odeSE, @odeSV, @odeSPVI}
    name = func2str (s{1});
    o = struct ("Ensemble", "on", "TimeStepSize", 0.05, "Vectorized", "on", ...
                "Events", @(t, y) deal (y(2) - 0.5, 1, 0));
    [t, Y, te, ye, ie] = s{1} (kepv, [0 2], Y0, o);
    nbad += check (size (Y, 3) == 3 && columns (ie) == 2, name, "ensemble");
    sol = s{1} (kepv, [0 1], Y0(:,1:2), rmfield (o, "TimeStepSize"));
    nbad += check (numel (sol) == 2, name, "ensemble sol");
    [t, Y] = s{1} (kepv, [0 1], Y0(:,1:2), struct ("Ensemble", "on", "TimeStepSize", 0.1, ...
                   "OutputFcn", @(t, y, flag) ! isempty (t) && t(1) > 0.5));
    nbad += check (t(end) < 1, name, "ensemble OutputFcn stop");
    nbad += expect_error (s{1}, "mc:fcn", @(t, y) mc_fail_after (t, y, 0.5), [0 1], [1 0; 0 1]', ...
                          struct ("Ensemble", "on", "TimeStepSize", 0.1));
  endfor
  [t, Y] = odeSV (kepv, [0 1], Y0(:,1:2), struct ("Ensemble", "on", "TimeStepSize", 0.05, ...
                  "Vectorized", "on", "Separable", "on"));
  nbad += check (all (isfinite (Y(:))), "odeSV", "ensemble stacked");
  ## JPattern (sparse and full), finite differences by colours
  for pat = {sparse([0 0 1 0; 0 0 0 1; 1 1 0 0; 1 1 0 0]), logical([0 0 1 0; 0 0 0 1; 1 1 0 0; 1 1 0 0])}
    sol = odeSPVI (kep, [0 1], y0k, struct ("JPattern", pat{1}, "TimeStepSize", 0.1));
    nbad += check (numel (sol.x) == 11 && sol.stats.nfdevals > 0, "odeSPVI", "JPattern");
  endfor
  nbad += expect_error (@odeSV, "Octave:invalid-input-arg", kep, [0 1], y0k, struct ("JPattern", eye (2)));
  ## reversible steps: the default density (f at the step points, kept by
  ## the steppers), a user's density, its failure, trial steps and events
  rev = struct ("StepControl", "reversible", "Events", @(t, y) deal (y(2) - 0.5, 0, 0));
  sol = odeSV (acc, [0 1], y0k, setfield (rev, "SecondOrder", "on"));
  nbad += check (sol.x(end) == 1 && numel (sol.xe) == 1, "odeSV", "reversible");
  [t, y] = odeSV (kep, [0 1], y0k, setfield (rev, "Method", "yoshida4"));
  nbad += check (t(end) == 1, "yoshida4", "reversible implicit");
  sol = odeSPVI (kep, [0 1], y0k, setfield (rev, "StepDensityFcn", @(t, y) norm (y(1:2))^-1.5));
  nbad += check (sol.x(end) == 1, "odeSPVI", "reversible");
  [t, y] = evalc_run (@odeSV, kep, y0k, setfield (rev, "StepDensityFcn", @(t, y) 10 - 20 * (t > 0.5)));
  nbad += check (t(end) < 1, "odeSV", "reversible, a density that vanishes");
  nbad += expect_error (@odeSE, "Octave:invalid-input-arg", kep, [0 1], y0k, rev);

  ## a run inside FCN that fails mid-run, its error caught there; then
  ## the outer run's own error frees the outer run's blocks, not the
  ## inner run's (which Octave freed)
  nbad += expect_error (@odeSPVI, "Octave:invalid-input-arg", @mc_nested, [0 1], [1; 0], struct ("TimeStepSize", 0.1));

  printf ("memcheck_run: %d unexpected results\n", nbad);
  status = double (nbad > 0);

endfunction

function [t, y] = evalc_run (s, f, y0, o)
  t = y = [];
  evalc ("[t, y] = s (f, [0 1], y0, o);");
endfunction

function bad = check (ok, name, what)
  bad = ! ok;
  if (bad)
    printf ("memcheck_run: %s: unexpected result (%s)\n", name, what);
  endif
endfunction

function bad = expect_error (s, id, varargin)
  bad = 1;
  try
    [t, y] = s (varargin{:});
    printf ("memcheck_run: %s: no error, expected %s\n", func2str (s), id);
  catch err
    bad = ! strcmp (err.identifier, id);
    if (bad)
      printf ("memcheck_run: %s: error %s (%s), expected %s\n", func2str (s),
              err.identifier, err.message, id);
    endif
  end_try_catch
endfunction

function [dy, h] = mc_hess2 (t, y)
  dy = [y(2); -y(1)];
  h = eye (2);
endfunction

function dy = mc_nested (t, y)
  persistent n = 0;
  n++;
  if (n == 2)
    try
      odeSPVI (@(t, y) mc_fail_after (t, y, 0.3), [0 1], [1; 0], struct ("TimeStepSize", 0.1));
    catch
    end_try_catch
  endif
  if (t > 0.5)
    dy = [1; 2; 3];    # the wrong size: the outer run's own error
  else
    dy = [y(2); -y(1)];
  endif
endfunction

function dy = mc_fail_after (t, y, tf)
  if (t > tf)
    error ("mc:fcn", "failing at t = %g", t);
  endif
  dy = [y(2); -y(1)];
endfunction

function [v, term, dir] = mc_ev_fail (t, y)
  if (t > 0.3)
    error ("mc:ev", "event failing at t = %g", t);
  endif
  v = y(1);  term = 0;  dir = 0;
endfunction

function stop = mc_out_fail (t, y, flag)
  if (strcmp (flag, "") && t(end) > 0.3)
    error ("mc:out", "output failing");
  endif
  stop = false;
endfunction
