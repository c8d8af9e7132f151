## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## The ode45 contract of odeSE, odeSV and odeSPVI, the rest (the output is
## in test_ode45_output.m): the sol struct and Stats, Vectorized, options
## (case, odepkg scripts, plain structs), extra parameters, backward runs,
## row y0, function names, tspan with more than two elements; the help
## texts, the demos and INDEX.

%!function dy = kepler_counted (t, y)
%!  global CONTRACT_CALLS
%!  CONTRACT_CALLS(end+1) = columns (y);
%!  q = y(1:2, :);
%!  r = sqrt (sum (q.^2, 1));
%!  dy = [y(3:4, :); -q ./ r.^3];
%!endfunction

%!function [dy, ddy] = kepler_hess2 (t, y)
%!  q = y(1:2);  r = norm (q);
%!  dy = [y(3:4); -q / r^3];
%!  ddy = [(eye (2) - 3 * (q * q.') / r^2) / r^3, zeros(2); zeros(2), eye(2)];
%!endfunction

%!function [dy, ddy] = kepler_tally (t, y)
%!  ## kepler_hess2, recording [columns of y, nargout] of every call
%!  global CONTRACT_TALLY
%!  CONTRACT_TALLY(end+1, :) = [columns(y), nargout];
%!  [dy, ddy] = kepler_hess2 (t, y);
%!endfunction

%!function ddy = kepler_hess_tally (t, y)
%!  ## kepler_hess2's Hessian, counting the calls
%!  global CONTRACT_HESS
%!  CONTRACT_HESS += 1;
%!  [~, ddy] = kepler_hess2 (t, y);
%!endfunction

%!function dy = contract_osc (t, y)
%!  dy = [y(2); -y(1)];
%!endfunction

%!function [v, term, dir] = ev_q (t, y)
%!  v = y(1);  term = 0;  dir = 0;
%!endfunction

%!function dy = osc_par (t, y, w, s)
%!  assert (nargin == 4 && strcmp (s, "tag"));
%!  dy = [y(2); -w^2 * y(1)];
%!endfunction

%!function H = osc_par_hess (t, y, w, s)
%!  assert (nargin == 4 && strcmp (s, "tag"));
%!  H = [w^2, 0; 0, 1];
%!endfunction

%!function [v, term, dir] = osc_par_ev (t, y, w, s)
%!  assert (nargin == 4 && strcmp (s, "tag"));
%!  v = y(1);  term = 0;  dir = 0;
%!endfunction

%!shared solvers
%! solvers = {@odeSE, @odeSV, @odeSPVI};

## ------------------------------------------------------------ sol and Stats
%!test
%! f = @(t, y) [y(2); -y(1)];
%! fields = {"nsteps", "nfailed", "nfevals", "npds", "ndecomps", "nlinsols"};
%! for i = 1:3
%!   o = symplecticset ("TimeStepSize", 0.1, "Events", @ev_q);
%!   sol = solvers{i} (f, [0 2], [1 0], o);
%!   [t, y] = solvers{i} (f, [0 2], [1 0], o);
%!   assert (size (sol.x), [1, 21]);
%!   assert (sol.x, t.');
%!   assert (sol.y, y.');
%!   assert (sol.solver, func2str (solvers{i}));
%!   assert (all (isfield (sol, {"xe", "ye", "ie", "stats"})));
%!   assert (all (isfield (sol.stats, fields)));
%!   assert (sol.stats.nsteps, 20);
%!   assert (sol.stats.nfailed, 0);
%!   assert (sol.stats.nfevals > 20);
%!   assert (size (sol.ye), [1, 2]);
%!   if (i == 3)
%!     assert ([sol.order, sol.Q_DoFs, sol.Nodes], [6, 4, 3]);
%!   elseif (i == 2)
%!     assert ({sol.method, sol.order}, {"verlet", 2});
%!   else
%!     assert (! isfield (sol, "order"));
%!   endif
%!   ## without Events: no xe, ye, ie
%!   sol = solvers{i} (f, [0 2], [1 0], symplecticset ("TimeStepSize", 0.1));
%!   assert (! any (isfield (sol, {"xe", "ye", "ie"})));
%! endfor
%! sol = odeSPVI (f, [0 1], [1; 0], symplecticset ("TimeStepSize", 0.1, "Nodes", 2));
%! assert ([sol.order, sol.Q_DoFs, sol.Nodes], [4, 3, 2]);

%!test
%! ## Stats = "on": ode45's three lines, then Newton and Jacobian counts
%! f = @(t, y) [y(2); -sin(y(1))];
%! for i = 1:3
%!   o = symplecticset ("TimeStepSize", 0.1, "Stats", "on");
%!   txt = evalc ("sol = solvers{i} (f, [0 2], [1; 0], o);");
%!   s = sol.stats;
%!   lines = strsplit (strtrim (txt), "\n");
%!   assert (lines{1}, sprintf ("Number of successful steps: %d", s.nsteps));
%!   assert (lines{2}, sprintf ("Number of failed attempts:  %d", s.nfailed));
%!   assert (lines{3}, sprintf ("Number of function calls:   %d", s.nfevals));
%!   assert (! isempty (strfind (txt, sprintf ("Newton iterations: %d", s.nnewton))));
%!   assert (! isempty (regexp (txt, "Jacobian/Hessian evaluations: \\d+ \\(source: finite differences")));
%!   assert (! isempty (strfind (txt, sprintf ("LU decompositions: %d", s.ndecomps))));
%!   assert (s.nnewton > 0 && s.ndecomps > 0);
%!   txt = evalc ("[t, y] = solvers{i} (f, [0 2], [1; 0], symplecticset (o, 'Stats', 'off'));");
%!   assert (isempty (txt));
%! endfor
%! ## the Hessian as second output: odeSPVI's calls that give it give f too
%! e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
%! txt = evalc ("sol = odeSPVI (@kepler_hess2, [0 1], y0, o);");
%! assert (! isempty (strfind (txt, sprintf ("Hessian evaluations: %d (source: second output of FCN (Hessian), calls that also give f;", sol.stats.npds))));
%! assert (sol.stats.npds > 0);

%!test
%! ## sol.stats counts what the user's functions see (help odeSE): fcn is
%! ## called nfevals + npds times with the Hessian as its second output,
%! ## nfevals times otherwise; npds calls of HamiltonianHessFcn; nstates
%! ## states; nfdevals of the calls for finite differences
%! global CONTRACT_TALLY CONTRACT_HESS CONTRACT_CALLS
%! e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
%! o = symplecticset ("TimeStepSize", 2*pi/50);
%! for i = 1:3
%!   ## the Hessian as second output, fixed step
%!   CONTRACT_TALLY = zeros (0, 2);
%!   s = solvers{i} (@kepler_tally, [0 2*pi], y0, o);
%!   assert (s.stats.jacobian_source, "second output of FCN (Hessian)");
%!   assert (rows (CONTRACT_TALLY), s.stats.nfevals + s.stats.npds);
%!   assert (s.stats.npds > 0);
%!   assert (s.stats.nstates, s.stats.nfevals);
%!   assert (s.stats.nsteps, numel (s.x) - 1);
%!   assert (s.stats.nsteps, 50);
%!   assert (s.stats.nfailed, 0);
%!   ## HamiltonianHessFcn, adaptive: it is called npds times; fcn, nfevals
%!   ## times, one or two of them for the probe of the first Hessian
%!   CONTRACT_TALLY = zeros (0, 2);  CONTRACT_HESS = 0;
%!   s = solvers{i} (@kepler_tally, [0 2*pi], y0, ...
%!                   symplecticset ("HamiltonianHessFcn", @kepler_hess_tally));
%!   assert (s.stats.jacobian_source, "HamiltonianHessFcn");
%!   assert (rows (CONTRACT_TALLY), s.stats.nfevals);
%!   assert (all (CONTRACT_TALLY(:, 2) == 1));
%!   assert (CONTRACT_HESS, s.stats.npds);
%!   assert (CONTRACT_HESS > 0);
%!   assert (any (s.stats.nfdevals == [1 2]));
%!   assert (s.stats.nsteps, numel (s.x) - 1);
%!   ## Vectorized, finite differences: a call of k states counts once in
%!   ## nfevals and k times in nstates; the calls for the matrices are
%!   ## those of more states than a step evaluates at once (1; odeSPVI 3),
%!   ## after the probe at y0 and the Vectorized check (a state near y0,
%!   ## then both in one call)
%!   CONTRACT_CALLS = [];
%!   s = solvers{i} (@kepler_counted, [0 2*pi], y0, ...
%!                   symplecticset (o, "Vectorized", "on", ...
%!                                  "NewtonMatrix", "kept"));
%!   assert (s.stats.jacobian_source, "finite differences of FCN");
%!   nodes = 1 + 2 * strcmp (func2str (solvers{i}), "odeSPVI");
%!   assert (numel (CONTRACT_CALLS), s.stats.nfevals);
%!   assert (sum (CONTRACT_CALLS), s.stats.nstates);
%!   assert (CONTRACT_CALLS(1:3), [1 1 2]);
%!   assert (sum (CONTRACT_CALLS(4:end) > nodes), s.stats.nfdevals);
%!   assert (s.stats.nstates > s.stats.nfevals);
%!   assert (s.stats.npds, 0);
%! endfor

## ------------------------------------------------------------ Vectorized
%!test
%! ## odeSPVI: the same trajectory with fewer calls of fcn
%! global CONTRACT_CALLS
%! e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
%! o = symplecticset ("TimeStepSize", 2*pi/100);
%! CONTRACT_CALLS = [];
%! s0 = odeSPVI (@kepler_counted, [0 4*pi], y0, symplecticset (o, "Vectorized", "off"));
%! c0 = CONTRACT_CALLS;
%! CONTRACT_CALLS = [];
%! s1 = odeSPVI (@kepler_counted, [0 4*pi], y0, symplecticset (o, "Vectorized", "on"));
%! c1 = CONTRACT_CALLS;
%! assert (s1.y, s0.y, 1e-12);
%! assert (all (c0 == 1));
%! assert (any (c1 == 3));                  # all nodes in one call
%! assert (numel (c0), s0.stats.nfevals);
%! assert (numel (c1), s1.stats.nfevals);
%! assert (s1.stats.nfevals < 0.6 * s0.stats.nfevals);
%! ## finite-difference matrices: the 3 nodes and their 2d perturbed
%! ## states each in one call, a new matrix on every step (its first
%! ## Newton correction exact); measured 1.57 calls per step
%! assert (sum (c1 == 15), s1.stats.nfdevals);
%! assert (s1.stats.nfdevals, s1.stats.nsteps);
%! assert (s1.stats.nfevals <= 1.7 * s1.stats.nsteps);
%! ## with the matrix kept (NewtonMatrix "kept"): the same states as
%! ## single calls, the nodes and their perturbed states in one call
%! CONTRACT_CALLS = [];
%! s2 = odeSPVI (@kepler_counted, [0 4*pi], y0, symplecticset (o, "Vectorized", "on", "NewtonMatrix", "kept"));
%! c2 = CONTRACT_CALLS;
%! assert (s2.y, s0.y, 1e-12);
%! assert (s2.stats.nstates, s0.stats.nstates + 3);   # the Vectorized check
%! assert (sum (c2 == 15), s2.stats.nfdevals);
%! assert (s2.stats.nfdevals * 12, s0.stats.nfdevals);
%! ## adaptive: the same solution up to the round-off in the step size
%! ## control (fcn's values differ in the last bit between the two forms)
%! tt = linspace (0, 4*pi, 50);
%! oa = odeset ("RelTol", 1e-8, "AbsTol", 1e-10);
%! CONTRACT_CALLS = [];
%! [~, y0v] = odeSPVI (@kepler_counted, tt, y0, symplecticset (oa, "Vectorized", "off"));
%! n0 = numel (CONTRACT_CALLS);
%! CONTRACT_CALLS = [];
%! [~, y1v] = odeSPVI (@kepler_counted, tt, y0, symplecticset (oa, "Vectorized", "on"));
%! n1 = numel (CONTRACT_CALLS);
%! assert (y1v, y0v, 1e-6);
%! assert (n1 < 0.6 * n0);

%!test
%! ## a chain of d = 20 (more states per finite-difference call than the
%! ## kept argument arrays): the same steps as single calls
%! d = 20;  K = diag (2*ones (d, 1)) - diag (ones (d-1, 1), 1) - diag (ones (d-1, 1), -1);
%! f = @(t, y) [y(d+1:end, :); -K * y(1:d, :) - y(1:d, :).^3];
%! y0 = [0.3 * sin(pi * (1:d)' / (d+1)); zeros(d, 1)];
%! ## full system: a matrix from 3 nodes x 2d states, in one call when
%! ## Vectorized; by stages: 2d states and f where it is taken, 2 calls
%! for ns = {"full", "stages"}
%!   o = symplecticset ("TimeStepSize", 0.05, "NewtonSystem", ns{1});
%!   s0 = odeSPVI (f, [0 2], y0, o);
%!   s1 = odeSPVI (f, [0 2], y0, symplecticset (o, "Vectorized", "on"));
%!   assert (s1.y, s0.y, 1e-13);
%!   if (strcmp (ns{1}, "full"))
%!     assert (s1.stats.nfdevals * 2 * d * 3, s0.stats.nfdevals);
%!   else
%!     assert (s1.stats.nfdevals * (2 * d + 1), 2 * s0.stats.nfdevals);
%!   endif
%!   assert (s1.stats.nstates, s0.stats.nstates + 3);   # the Vectorized check
%! endfor

## ------------------------------------------------------------ options
%!test
%! ## odepkg-style scripts: odeset with the package's names (odeset warns)
%! warning ("off", "Octave:invalid-input-arg", "local");
%! f = @(t, y) [y(2); -y(1)];
%! o = odeset ("TimeStepSize", 0.1, "Q_DoFs", 3, "P_DoFs", 2);
%! sol = odeSPVI (f, [0 1], [1; 0], o);
%! assert ([sol.stats.nsteps, sol.Q_DoFs, sol.Nodes, sol.order], [10 3 2 4]);
%! o = odeset ("TimeStepSize", 0.1, "PolynomialDegree", 2);
%! sol = odeSPVI (f, [0 1], [1; 0], o);
%! assert ([sol.Q_DoFs, sol.Nodes], [3 3]);
%! o = odeset ("TimeStepSize", 0.1);
%! for i = 1:2
%!   sol = solvers{i} (f, [0 1], [1; 0], o);
%!   assert (sol.stats.nsteps, 10);
%! endfor

%!test
%! ## names in any case; plain structs; symplecticset does not warn
%! f = @(t, y) [y(2); -y(1)];
%! ref = odeSPVI (f, [0 1], [1; 0], symplecticset ("TimeStepSize", 0.1, "Q_DoFs", 3, "Nodes", 2));
%! lastwarn ("");
%! o1 = symplecticset ("timestepsize", 0.1, "q_dofs", 3, "NODES", 2);
%! assert (lastwarn (), "");
%! assert (isfield (o1, "TimeStepSize") && isfield (o1, "Q_DoFs"));
%! o2 = struct ("timeStepSize", 0.1, "q_dofs", 3, "nodes", 2);
%! o3 = struct ("TIMESTEPSIZE", 0.1, "Q_DOFS", 3, "p_dofs", 2, "EVENTS", []);
%! for o = {o1, o2, o3}
%!   sol = odeSPVI (f, [0 1], [1; 0], o{1});
%!   assert ([sol.Q_DoFs, sol.Nodes], [3 2]);
%!   assert (sol.y, ref.y, 1e-15);
%! endfor
%! ## standard fields in any case, in a plain struct
%! sol = odeSV (f, [0 1], [1; 0], struct ("reltol", 1e-8, "ABSTOL", 1e-10, "stats", "off"));
%! assert (sol.y(:, end), [cos(1); -sin(1)], 1e-5);
%! sol1 = odeSV (f, [0 1], [1; 0], odeset ("RelTol", 1e-3));
%! assert (sol.stats.nsteps > 2 * sol1.stats.nsteps);

## ------------------------------------------------------------ arguments
%!test
%! ## extra parameters reach fcn, Events and HamiltonianHessFcn
%! w = 2;
%! for i = 1:3
%!   o = symplecticset ("TimeStepSize", 0.01, "Events", @osc_par_ev,
%!                      "HamiltonianHessFcn", @osc_par_hess);
%!   [t, y, te] = solvers{i} (@osc_par, [0 3], [1; 0], o, w, "tag");
%!   assert (y(end, :), [cos(w*3), -w*sin(w*3)], 0.1);
%!   assert (te, [pi/4; 3*pi/4], 0.01);
%!   sol = solvers{i} (@osc_par, [0 3], [1; 0], o, w, "tag");
%!   assert (sol.stats.jacobian_source, "HamiltonianHessFcn");
%!   assert (sol.stats.npds > 0);
%! endfor

%!test
%! ## a Hessian wrong by a moderate factor (or zero, or of the wrong sign)
%! ## costs Newton iterations, not accuracy: the same rows as with the
%! ## right one (measured within 5.5e-12 over 500 steps)
%! f = @(t, y) [(y(1)^2+y(2)^2)*y(2); -(y(1)^2+y(2)^2)*y(1)];
%! Ht = @(t, y) [3*y(1)^2+y(2)^2, 2*y(1)*y(2); 2*y(1)*y(2), y(1)^2+3*y(2)^2];
%! o = symplecticset ("TimeStepSize", 0.01);
%! for i = 1:3
%!   [~, a] = solvers{i} (f, [0 5], [1; 0.5], symplecticset (o, "HamiltonianHessFcn", Ht));
%!   for c = [0 -1 0.5 3 10]
%!     lastwarn ("");
%!     [t, b] = solvers{i} (f, [0 5], [1; 0.5], symplecticset (o, "HamiltonianHessFcn", @(t, y) c * Ht (t, y)));
%!     assert (lastwarn (), "");
%!     assert (t(end), 5);
%!     assert (b(end, :), a(end, :), 2e-11);
%!   endfor
%! endfor

%!test
%! ## backward runs, row y0, a function name as a string
%! for i = 1:3
%!   o = symplecticset ("TimeStepSize", 0.01);
%!   [t, y] = solvers{i} ("contract_osc", [1 -2], [cos(1); -sin(1)], o);
%!   [t2, y2] = solvers{i} (@contract_osc, [1 -2], [cos(1), -sin(1)], o);
%!   assert (t, t2);
%!   assert (y, y2);
%!   assert (t, 1 - (0:300)' * 0.01, 1e-13);
%!   assert (y(end, :), [cos(-2), -sin(-2)], 0.02);
%!   ## adaptive backwards
%!   [t, y] = solvers{i} ("contract_osc", [0 -3], [1 0], odeset ("RelTol", 1e-6));
%!   assert (t(end), -3);
%!   assert (all (diff (t) < 0));
%!   assert (y(end, :), [cos(-3), -sin(-3)], 0.05);
%! endfor

%!test
%! ## names and simple handles are called by name, other handles through
%! ## feval: a handle to a subfunction calls the subfunction even where a
%! ## function of the same name is on the path, and a handle to that
%! ## function calls it even where a subfunction of that name is in scope
%! d = tempname ();
%! mkdir (d);
%! unwind_protect
%!   fid = fopen (fullfile (d, "symtest_rhs.m"), "w");
%!   fputs (fid, "function dy = symtest_rhs (t, y)\n  dy = [y(2); -4*y(1)];\nendfunction\n");
%!   fclose (fid);
%!   fid = fopen (fullfile (d, "symtest_scoped.m"), "w");
%!   fputs (fid, ["function [y, yh] = symtest_scoped (solver, o, fh)\n", ...
%!                "  [~, y] = solver (@symtest_rhs, [0 1], [1; 0], o);\n", ...
%!                "  [~, yh] = solver (fh, [0 1], [1; 0], o);\n", ...
%!                "endfunction\n", ...
%!                "function dy = symtest_rhs (t, y)\n", ...
%!                "  dy = [y(2); -y(1)];\n", ...
%!                "endfunction\n"]);
%!   fclose (fid);
%!   addpath (d);
%!   o = symplecticset ("TimeStepSize", 1e-3);
%!   for i = 1:3
%!     ## the subfunction, and a handle made here to the file's function
%!     [y, yh] = symtest_scoped (solvers{i}, o, @symtest_rhs);
%!     assert (y(end, :), [cos(1), -sin(1)], 2e-3);
%!     assert (yh(end, :), [cos(2), -2*sin(2)], 4e-3);
%!     [~, y1] = solvers{i} (@symtest_rhs, [0 1], [1; 0], o);   # the file
%!     [~, y2] = solvers{i} ("symtest_rhs", [0 1], [1; 0], o);
%!     [~, y3] = solvers{i} (@(t, y) symtest_rhs (t, y), [0 1], [1; 0], o);
%!     assert (y1(end, :), [cos(2), -2*sin(2)], 4e-3);
%!     assert (y2, y1);
%!     assert (y3, y1);
%!   endfor
%!   ## a command-line function of the file's name: a call by name finds it
%!   ## first, a handle made to the file before calls the file
%!   fh = @symtest_rhs;
%!   eval ("function dy = symtest_rhs (t, y)\n  dy = [y(2); -9*y(1)];\nendfunction\n");
%!   assert (fh (0, [1; 0]), [0; -4]);
%!   for i = 1:3
%!     [~, y1] = solvers{i} (fh, [0 1], [1; 0], o);
%!     [~, y2] = solvers{i} ("symtest_rhs", [0 1], [1; 0], o);
%!     assert (y1(end, :), [cos(2), -2*sin(2)], 4e-3);
%!     assert (y2(end, :), [cos(3), -3*sin(3)], 1e-2);
%!   endfor
%! unwind_protect_cleanup
%!   clear symtest_rhs
%!   rmpath (d);
%!   confirm_recursive_rmdir (false, "local");
%!   rmdir (d, "s");
%! end_unwind_protect

%!test
%! ## tspan with more than two elements: rows exactly there, steps unchanged
%! f = @(t, y) [y(2); -y(1)];
%! ts = [0, 0.05, 1/3, 1, pi, 9.99, 10];
%! for i = 1:3
%!   o = symplecticset ("TimeStepSize", 0.1);
%!   s2 = solvers{i} (f, [0 10], [1; 0], o);
%!   [t, y] = solvers{i} (f, ts, [1; 0], o);
%!   assert (t, ts(:));
%!   assert (y(end, :), s2.y(:, end).', 1e-14);
%!   o.OutputFcn = @(t, y, flag) false;
%!   o.Stats = "on";
%!   txt = evalc ("[t, y] = solvers{i} (f, ts, [1; 0], o);");
%!   assert (! isempty (strfind (txt, "successful steps: 100")));
%!   ## backward, and a column tspan
%!   [t, y] = solvers{i} (f, -ts(:), [1; 0], symplecticset ("TimeStepSize", 0.1));
%!   assert (t, -ts(:));
%!   assert (y(:, 1), cos (t), 0.06);
%! endfor

%!test
%! ## Refine with a terminal event on a refined time (to round-off): one
%! ## row there, the event's (the refined row 1 ulp before it was kept too)
%! f = @(t, y) [y(2); -y(1)];
%! o = symplecticset ("TimeStepSize", 0.3, "Refine", 3, ...
%!                    "Events", @(t, y) deal (t - 1, 1, 0));
%! for i = 1:3
%!   [t, y, te] = solvers{i} (f, [0 2], [1; 0], o);
%!   assert (t(end), te, 4 * eps);
%!   assert (t(end-1), 0.9, 4 * eps);
%! endfor

%!test
%! ## MaxStep: the default cap is |tf-t0|/10; Inf lifts it, as in ode45 (a
%! ## slow oscillator, whose steps at the default tolerances are longer)
%! f = @(t, y) [y(2); -1e-4 * y(1)];
%! for i = 2:3      # odeSE's steps (at most 4) stay below the cap anyway
%!   [t1, ~] = solvers{i} (f, [0 100], [1; 0], odeset ("Refine", 1));
%!   [t2, ~] = solvers{i} (f, [0 100], [1; 0], odeset ("MaxStep", Inf, "Refine", 1));
%!   [t3, ~] = solvers{i} (f, [0 100], [1; 0], odeset ("MaxStep", 5, "Refine", 1));
%!   assert (max (diff (t1)), 10, 1e-12);
%!   assert (max (diff (t2)) > 15);
%!   assert (max (diff (t3)), 5, 1e-12);
%! endfor

%!test
%! ## steps that MaxStep caps all along, where it divides the span: that
%! ## many steps, as ode45 takes, with no sliver of the round-off that t
%! ## gathered as a step of its own (t summed plainly left 9.4e-14 after
%! ## 1e4 steps of 1e-4: 10002 rows)
%! f = @(t, y) [y(2); 0];     # a free particle: MaxStep binds
%! for i = 1:3
%!   for t0 = [0, 1e8]
%!     [t, ~] = solvers{i} (f, [t0, t0+1], [0; 1], odeset ("MaxStep", 1e-4, "Refine", 1));
%!     assert (numel (t), 10001);
%!     assert (t(end), t0 + 1);
%!     assert (min (diff (t)) > 0.99e-4);
%!   endfor
%! endfor

%!test
%! ## InitialStep = Inf: the first step as long as MaxStep and TSPAN allow,
%! ## as ode45 takes it; the same run as with that step given
%! f = @(t, y) [y(2); -1e-4 * y(1)];
%! for i = 1:3
%!   ## the default cap |tf-t0|/10
%!   [t1, y1] = solvers{i} (f, [0 100], [1; 0], odeset ("InitialStep", Inf, "Refine", 1));
%!   [t2, y2] = solvers{i} (f, [0 100], [1; 0], odeset ("InitialStep", 10, "Refine", 1));
%!   assert (isequal (t1, t2) && isequal (y1, y2));
%!   if (i > 1)    # odeSE's (order 1) first step of 10 fails; it is shortened
%!     assert (t1(2), 10);
%!   endif
%!   ## no cap: the span, backwards too
%!   o = odeset ("InitialStep", Inf, "MaxStep", Inf, "Refine", 1);
%!   [t1, y1] = solvers{i} (f, [0 -2], [1; 0], o);
%!   [t2, y2] = solvers{i} (f, [0 -2], [1; 0], odeset (o, "InitialStep", 2));
%!   assert (isequal (t1, t2) && isequal (y1, y2));
%!   if (i > 1)
%!     assert (t1, [0; -2]);
%!   endif
%!   ## a first step that fails is shortened as any other: the run is
%!   ## as accurate as from the automatic start
%!   ## (errors at t = 10: 3.5e-4, 4.3e-5, 7.5e-9 against 3.5e-4, 4.3e-5,
%!   ## 6.0e-9)
%!   g = @(t, y) [y(2); -y(1)];
%!   o = odeset ("RelTol", 1e-6, "AbsTol", 1e-8);
%!   [t1, y1] = solvers{i} (g, [0 10], [1; 0], odeset (o, "InitialStep", Inf));
%!   [t2, y2] = solvers{i} (g, [0 10], [1; 0], o);
%!   assert (t1(end), 10);
%!   e1 = norm (y1(end, :) - [cos(10), -sin(10)]);
%!   e2 = norm (y2(end, :) - [cos(10), -sin(10)]);
%!   assert (e1 < 2 * e2);
%! endfor

%!test
%! ## spans a few ulps of t wide reach tf as in ode45: steps below 16 ulps
%! ## of t (here all of them, MaxStep being span/10) are raised to that; a
%! ## MaxStep set below it warns at once
%! for i = 1:3
%!   for ts = {[1 1+1e-14], [1e6 1e6+1e-8], [1 1+2*eps], [-2 -2-1e-13]}
%!     tspan = ts{1};
%!     lastwarn ("");
%!     [t, y] = solvers{i} (@contract_osc, tspan, [cos(tspan(1)); -sin(tspan(1))]);
%!     assert (lastwarn (), "");
%!     assert (t([1 end]).', tspan);
%!     assert (y(end, :), [cos(tspan(2)), -sin(tspan(2))], 1e-14);
%!   endfor
%!   name = func2str (solvers{i});
%!   lastwarn ("");
%!   evalc ("[t, y] = solvers{i} (@contract_osc, [1e6 1e6+1e-3], [1 0], odeset ('MaxStep', 1e-14));");
%!   [msg, id] = lastwarn ();
%!   assert (id, "symplectic:step-size");
%!   assert (regexp (msg, ['^' name ': the step size became too small at t = 1000000;']));
%!   assert (t, 1e6);
%! endfor

%!test
%! ## NonNegative and Mass change the problem: not taken, with a warning
%! for i = 1:3
%!   for opt = {"NonNegative", 1; "Mass", eye(2)}.'
%!     lastwarn ("");
%!     evalc ("[t, y] = solvers{i} (@contract_osc, [0 1], [1 0], odeset (opt{:}));");
%!     [msg, id] = lastwarn ();
%!     assert (id, "symplectic:unsupported-option");
%!     assert (msg, [func2str(solvers{i}) ": option " opt{1} " is not supported and is ignored"]);
%!     assert (y(end, :), [cos(1), -sin(1)], 0.05);   # odeSE at RelTol 1e-3
%!   endfor
%! endfor

%!test
%! ## RelTol below 100 eps is raised to it, with a warning (at t0 = 0 the
%! ## least step does not stop an error test that asks for steps round-off
%! ## cannot give: odeSE and odeSV did not finish)
%! for i = 2:3
%!   lastwarn ("");
%!   evalc ("[t, y] = solvers{i} (@contract_osc, [0 1], [1 0], odeset ('RelTol', 1e-300, 'AbsTol', 1e-300));");
%!   [msg, id] = lastwarn ();
%!   assert (id, "symplectic:tolerance");
%!   assert (msg, [func2str(solvers{i}) ": RelTol = 1e-300 is below 100*eps; 2.22045e-14 is used"]);
%!   assert (t(end), 1);
%!   assert (y(end, :), [cos(1), -sin(1)], 1e-9);    # odeSV 1.5e-10
%! endfor

%!test
%! ## sparse arguments, options and values returned by the user's functions
%! ## are taken as full (as ode45 takes a sparse Jacobian): the same rows
%! osc = @(t, y) [y(2); -y(1)];
%! ev = @(t, y) deal (y(1), 0, 0);
%! for i = 1:3
%!   o = symplecticset ("TimeStepSize", 0.1, "Events", ev);
%!   [t0, y0, te0] = solvers{i} (osc, [0 3], [1; 0], o);
%!   assert (te0, pi/2, 0.1);   # odeSE: order 1
%!   sosc = @(t, y) sparse (osc (t, y));
%!   sev = @(t, y) deal (sparse (y(1)), 0, 0);
%!   runs = {{sosc, [0 3], [1; 0], o}, ...
%!           {osc, sparse([0 3]), sparse([1; 0]), o}, ...
%!           {osc, [0 3], [1; 0], symplecticset(o, "Events", sev)}, ...
%!           {osc, [0 3], [1; 0], symplecticset(o, "TimeStepSize", sparse(0.1))}};
%!   for k = 1:numel (runs)
%!     [t, y, te] = solvers{i} (runs{k}{:});
%!     assert ([t y], [t0 y0]);
%!     assert (te, te0);
%!   endfor
%!   ## Newton's matrix from a sparse Jacobian, Jacobian function or Hessian
%!   o = symplecticset ("TimeStepSize", 0.1);
%!   jf = @(t, y) [0 1; -1 0];
%!   hf = @(t, y) eye (2);
%!   for src = {{"Jacobian", [0 1; -1 0]}, {"Jacobian", jf}, ...
%!              {"HamiltonianHessFcn", hf}}
%!     s0 = solvers{i} (osc, [0 3], [1; 0], symplecticset (o, src{1}{:}));
%!     v = src{1}{2};
%!     if (is_function_handle (v))
%!       vs = @(t, y) sparse (v (t, y));
%!     else
%!       vs = sparse (v);
%!     endif
%!     s1 = solvers{i} (osc, [0 3], [1; 0], symplecticset (o, src{1}{1}, vs));
%!     ## kept sparse: Newton's systems by a sparse LU (odeSPVI: by
%!     ## stages), the same steps to round-off
%!     assert (s1.y, s0.y, 1e-12 * max (abs (s0.y(:))));
%!     assert (s1.stats.jacobian_source, s0.stats.jacobian_source);
%!   endfor
%!   ## adaptive, with a sparse AbsTol
%!   [t1, y1] = solvers{i} (osc, [0 3], [1; 0], odeset ("AbsTol", sparse ([1e-6 1e-6])));
%!   [t2, y2] = solvers{i} (osc, [0 3], [1; 0], odeset ("AbsTol", [1e-6 1e-6]));
%!   assert ([t1 y1], [t2 y2]);
%! endfor

## ------------------------------------------------------------ help, demos
%!test
%! ## the help texts render without texinfo errors and say the key things
%! keys = {"TimeStepSize", "RelTol", "Events", "OutputFcn", "OutputSel", ...
%!         "Refine", "Stats", "SOL", "Jacobian", "HamiltonianHessFcn"};
%! for name = {"odeSE", "odeSV", "odeSPVI", "symplecticset"}
%!   [txt, fmt] = get_help_text (name{1});
%!   assert (fmt, "texinfo");
%!   [out, status] = __makeinfo__ (txt, "plain text");
%!   assert (status, 0);
%!   assert (isempty (strfind (out, "warning:")));
%!   assert (isempty (regexp (out, '@(code|var|item|end|example)\>', "once")));
%!   if (! strcmp (name{1}, "symplecticset"))
%!     ## help shows the m-file's text for the MEX function
%!     assert (! isempty (strfind (evalc (["help " name{1}]), "OutputFcn")));
%!     for k = keys
%!       assert (! isempty (strfind (out, k{1})), "%s: %s", name{1}, k{1});
%!     endfor
%!   endif
%! endfor
%! out = __makeinfo__ (get_help_text ("odeSE"), "plain text");
%! ## Refine's defaults are in the user guide's option table; the help
%! ## says the options are as in ode45
%! assert (! isempty (regexp (out, "Refine, Stats\\W+As in\\W+ode45")));
%! assert (! isempty (strfind (out, "odeplot")));
%! assert (! isempty (strfind (out, "Vectorized")));
%! out = __makeinfo__ (get_help_text ("odeSPVI"), "plain text");
%! assert (! isempty (regexp (out, "Refine, Stats\\W+As in\\W+ode45")));
%! assert (! isempty (strfind (out, "Vectorized")));

%!test
%! ## every demo runs off-screen without error; one per solver, since
%! ## demo () prompts between two demos of a file
%! old = get (0, "defaultfigurevisible");
%! set (0, "defaultfigurevisible", "off");
%! warning ("off", "Octave:gnuplot-graphics", "local");
%! unwind_protect
%!   for name = {"odeSE", "odeSV", "odeSPVI"}
%!     [code, idx] = test (file_in_loadpath ([name{1} ".m"]), "grabdemo");
%!     assert (numel (idx) - 1 == 1, "%s has %d demos", name{1}, numel (idx) - 1);
%!     for k = 1:numel (idx) - 1
%!       block = code(idx(k):idx(k+1)-1);
%!       eval (["function __contract_demo__ ()\n" block "\nendfunction"]);
%!       evalc ("__contract_demo__ ();");
%!       clear __contract_demo__;
%!       assert (! isempty (get (0, "currentfigure")), "%s demo %d plots", name{1}, k);
%!       close all;
%!     endfor
%!   endfor
%! unwind_protect_cleanup
%!   close all;
%!   set (0, "defaultfigurevisible", old);
%! end_unwind_protect

%!test
%! ## INDEX lists every function of the package
%! inst = fileparts (file_in_loadpath ("odeSPVI.m"));
%! cand = {fullfile(fileparts (inst), "INDEX"), fullfile(inst, "packinfo", "INDEX")};
%! cand = cand(cellfun (@(f) exist (f, "file") == 2, cand));
%! assert (! isempty (cand), "no INDEX found near %s", inst);
%! txt = fileread (cand{1});
%! assert (! isempty (regexp (txt, "^symplectic >> ", "once")));
%! listed = regexp (txt, '^ +(\w+)', "tokens", "lineanchors");
%! listed = sort ([listed{:}]);
%! m = dir (fullfile (inst, "*.m"));
%! assert (listed, sort (regexprep ({m.name}, '\.m$', "")));

%!test
%! clear -global CONTRACT_CALLS CONTRACT_LOG CONTRACT_TSTOP CONTRACT_TALLY CONTRACT_HESS

%!test
%! ## output times after the end of TimeStepNumber steps: a warning with
%! ## its identifier, and no rows for them
%! for s = {@odeSE, @odeSV, @odeSPVI}
%!   o = symplecticset ("TimeStepNumber", 3, "TimeStepSize", 0.1);
%!   lastwarn ("");
%!   [t, y] = s{1} (@contract_osc, [0 0.05 0.5 2], [1; 0], o);
%!   [msg, id] = lastwarn ();
%!   assert (id, "symplectic:tspan-beyond-end");
%!   assert (! isempty (strfind (msg, "ends at t = 0.3")));
%!   assert (t, [0; 0.05]);
%! endfor

%!test
%! ## N steps of h end on the output time N*h stands for even when t0 + N*h
%! ## rounds short of it (3*0.7 = 2.0999999999999996): the same rows and
%! ## values as TimeStepSize alone, and no warning (forward, backward, and
%! ## towards tf = 0)
%! for s = {@odeSE, @odeSV, @odeSPVI}
%!   on = symplecticset ("TimeStepNumber", 3, "TimeStepSize", 0.7);
%!   oh = symplecticset ("TimeStepSize", 0.7);
%!   for ts = {[0 1 2.1], [0 -1 -2.1], [-2.1 -1 0], [0 2.1], [5 5+2.1]}
%!     lastwarn ("");
%!     [t, y] = s{1} (@contract_osc, ts{1}, [1; 0], on);
%!     assert (lastwarn (), "");
%!     [th, yh] = s{1} (@contract_osc, ts{1}, [1; 0], oh);
%!     assert (t, th);
%!     assert (y, yh);
%!     assert (t(end), ts{1}(end));
%!   endfor
%!   ## a real shortfall, however small, warns
%!   lastwarn ("");
%!   [t, y] = s{1} (@contract_osc, [0 1 2.1+1e-13], [1; 0], on);
%!   [~, id] = lastwarn ();
%!   assert (id, "symplectic:tspan-beyond-end");
%!   assert (t, [0; 1]);
%! endfor

%!function stop = outsel_rec (t, y, flag)
%!  global OUTSEL_Y
%!  if (isempty (flag) || strcmp (flag, "init"))
%!    OUTSEL_Y = [OUTSEL_Y, y(:, end)'];   # init: y0; then one row a step
%!  endif
%!  stop = false;
%!endfunction

## what the help says the solvers take beyond ode45: scalar ISTERMINAL
## and DIRECTION for a VALUE of several events, OutputSel as a logical
## mask, true/false for "on"/"off"
%!test
%! f = @(t, y) [y(2); -y(1)];
%! for s = {@odeSE, @odeSV, @odeSPVI}
%!   o = struct ("TimeStepSize", 0.01, "Events", @(t, y) deal ([y(1); y(2)], 0, -1));
%!   [t, y, te, ye, ie] = s{1} (f, [0 4], [1 0], o);
%!   ## y(1) = cos t falls through 0 at pi/2; y(2) = -sin t at 0 (t0: not
%!   ## an event) and falls through 0 again only at 2 pi
%!   assert (ie(:)', 1);
%!   assert (te, pi/2, 1e-2);          # odeSE, order 1: 1.5658
%!   assert (abs (ye(1)) < 1e-10);
%!   global OUTSEL_Y
%!   for sel = {[false true], 2}
%!     OUTSEL_Y = [];
%!     [t1, y1] = s{1} (f, [0 1], [1 0], struct ("TimeStepSize", 0.1, "OutputSel", sel{1}, "OutputFcn", @outsel_rec));
%!     assert (OUTSEL_Y, y1(:, 2)');   # only y(2) went to OutputFcn
%!   endfor
%!   clear -global OUTSEL_Y
%!   out = evalc ("sa = s{1} (f, [0 1], [1 0], struct ('TimeStepSize', 0.1, 'Stats', true));");
%!   assert (regexp (out, "successful steps"));
%!   out = evalc ("sa = s{1} (f, [0 1], [1 0], struct ('TimeStepSize', 0.1, 'Stats', false));");
%!   assert (out, "");
%! endfor
%! ## odeSE and odeSV: Separable true is "on" (explicit steps, no Newton)
%! for s = {@odeSE, @odeSV}
%!   sb = s{1} (f, [0 1], [1 0], struct ("TimeStepSize", 0.1, "Separable", true));
%!   sc = s{1} (f, [0 1], [1 0], struct ("TimeStepSize", 0.1, "Separable", "on"));
%!   sd = s{1} (f, [0 1], [1 0], struct ("TimeStepSize", 0.1, "Separable", false));
%!   assert (sb.y, sc.y);
%!   assert ([sb.stats.nnewton, sc.stats.nnewton], [0 0]);
%!   assert (sd.stats.nnewton > 0);
%! endfor
