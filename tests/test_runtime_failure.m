## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## When the integration cannot go on (FCN keeps returning NaN, Newton
## diverges at the smallest or at the fixed step, the step size underflows,
## MaxSteps is reached), the solvers warn with an identifier, as ode45
## does, and RETURN every row computed up to there (as the solvers' help says).

## run_warn (SOLVER, ARGS...): [t, y, msg, id] of [t, y] = SOLVER (ARGS{:}),
## with the warning it gave (its printout captured, to keep the log clean).
%!function [t, y, msg, id] = run_warn (solver, varargin)
%!  lastwarn ("");
%!  t = y = [];
%!  evalc ("[t, y] = solver (varargin{:});");
%!  [msg, id] = lastwarn ();
%!endfunction

## the harmonic oscillator, whose FCN returns NaN from t = 1 on
%!function dy = rf_nan_after_1 (t, y)
%!  dy = [y(2); -y(1)];
%!  if (t > 1)
%!    dy(:) = NaN;
%!  endif
%!endfunction

%!function [dy, hs] = fcn_nan_hessian (t, y)
%!  dy = [y(2); -y(1)];
%!  hs = [NaN 0; 0 1];
%!endfunction

## H = p^2/2 (1 + q^2/4) + q^2/2 (not separable) with its Hessian times
## c as second output
%!function [dy, hs] = fcn_scaled_hessian (t, y, c)
%!  q = y(1);  p = y(2);
%!  dy = [p * (1 + q^2/4); -(p^2 * q/4 + q)];
%!  hs = c * [p^2/4 + 1, p*q/2; p*q/2, 1 + q^2/4];
%!endfunction

%!shared all3, osc
%! all3 = {@odeSE, @odeSV, @odeSPVI};
%! osc = @(t, y) [y(2); -y(1)];

## NaN after t = 1: adaptive and fixed step, each solver
%!test
%! for s = all3
%!   name = func2str (s{1});
%!   for o = {struct(), struct("TimeStepSize", 0.01), ...
%!            struct("TimeStepSize", 0.01, "Separable", "on")}
%!     [t, y, msg, id] = run_warn (s{1}, @rf_nan_after_1, [0 3], [1 0], o{1});
%!     assert (id, "symplectic:nonfinite");
%!     assert (regexp (msg, ['^' name ': FCN returned NaN or Inf near t = 1(\.0|$| )']));
%!     assert (regexp (msg, 'returning the solution up to t = '));
%!     assert (all (isfinite (y(:))));
%!     assert (columns (y), 2);
%!     assert (rows (y), numel (t));
%!     assert (t(1), 0);
%!     assert (t(end) > 0.95 && t(end) <= 1.0101, sprintf ("%s: t(end) = %.17g", name, t(end)));
%!     assert (all (diff (t) > 0));
%!     ## what was returned is the solution (loose: odeSE is first order)
%!     assert (y(:,1), cos (t), 0.05);
%!   endfor
%! endfor

## an unstable fixed step (h = 3 > 2 on the oscillator) grows the
## solution until a step overflows: the run ends before that step with a
## warning that says so, and every returned row is finite, whatever the
## output options (the Inf row was returned with step output, dropped
## with Refine, and FCN was blamed)
%!test
%! for s = {@odeSE, @odeSV}
%!   name = func2str (s{1});
%!   [t0, y0] = s{1} (osc, [0 1104], [1 0], struct ("TimeStepSize", 3));
%!   for o = {struct("TimeStepSize", 3), ...
%!            struct("TimeStepSize", 3, "Separable", "on"), ...
%!            struct("TimeStepSize", 3, "Refine", 4)}
%!     [t, y, msg, id] = run_warn (s{1}, osc, [0 1200], [1 0], o{1});
%!     assert (id, "symplectic:nonfinite");
%!     assert (regexp (msg, ['^' name ': the solution overflowed \(NaN or Inf\) in the step from t = 1104 ']));
%!     assert (t(end), 1104);
%!     assert (all (isfinite (y(:))));
%!     assert (y(end,:), y0(end,:), -1e-12);
%!     assert (max (abs (y(end,:))) > 1e307);
%!   endfor
%!   sol = s{1} (osc, [0 1200], [1 0], struct ("TimeStepSize", 3));
%!   assert (sol.x(end), 1104);
%!   assert (all (isfinite (sol.y(:))));
%! endfor

## a solution within a finite-difference step of the edge of FCN's domain
## (NaN for q > 1, from q = 1 - 1e-9): the Newton matrix from finite
## differences, and the probe of a given Hessian or Jacobian, step the
## other way; these runs ended at t = 0, blaming FCN
%!test
%! f = @(t, y) [y(2); -y(1)] + 0 / (y(1) <= 1);
%! q0 = 1 - 1e-9;
%! for s = all3
%!   for o = {struct("TimeStepSize", 0.1), ...
%!            struct("TimeStepSize", 0.1, "HamiltonianHessFcn", @(t, y) eye (2)), ...
%!            struct("TimeStepSize", 0.1, "Jacobian", [0 1; -1 0]), struct()}
%!     [t, y, msg, id] = run_warn (s{1}, f, [0 1], [q0 0], o{1});
%!     assert (id, "");
%!     assert (t(end), 1);
%!     assert (y(:,1), q0 * cos (t), 0.05);
%!   endfor
%! endfor

## the same with output at given times and with the sol struct
%!test
%! for s = all3
%!   [t, y, msg, id] = run_warn (s{1}, @rf_nan_after_1, 0:0.25:3, [1 0]);
%!   assert (id, "symplectic:nonfinite");
%!   ## the requested times reached (the last step may end just short of 1)
%!   assert (numel (t) >= 4);
%!   assert (t, (0:0.25:0.25*(numel (t) - 1))');
%!   assert (t(end) <= 1);
%!   assert (y(:,1), cos (t), 0.05);
%!   lastwarn ("");
%!   evalc ("sol = s{1} (@rf_nan_after_1, [0 3], [1 0]);");
%!   [~, id] = lastwarn ();
%!   assert (id, "symplectic:nonfinite");
%!   assert (sol.x(end) > 0.95 && sol.x(end) <= 1);
%!   assert (all (isfinite (sol.y(:))));
%! endfor

## NaN in the forced part only of a 2-degree-of-freedom system, with
## Refine: rows still all finite, in order (odeSPVI evaluates FCN only at
## its interior nodes, so its last step may end a little after t = 1.5)
%!test
%! f = @(t, y) [y(3:4); -y(1:2) + [0; 1 / (t <= 1.5) - 1]];
%! for s = all3
%!   [t, y, msg, id] = run_warn (s{1}, f, [0 3], [1 0 0 1], struct ("Refine", 3));
%!   assert (id, "symplectic:nonfinite");
%!   assert (all (isfinite (y(:))));
%!   assert (t(end) > 1.4 && t(end) < 1.6);
%!   assert (all (diff (t) > 0));
%! endfor

## the Jacobian or the Hessian returning NaN or Inf (FCN finite): a
## smaller step cannot cure it, so finite differences of FCN take over
## from there, as for a Df that disagrees with them (below); before, the
## run stopped there with a warning
%!test
%! f = @(t, y) [y(2); -y(1)^3];
%! for s = all3
%!   ref = s{1} (f, [0 2], [1 0]);
%!   o = struct ("Jacobian", @(t, y) [0 1; -3*y(1)^2 0] / (t < 0.5));
%!   lastwarn ("");
%!   sol = s{1} (f, [0 2], [1 0], o);
%!   assert (lastwarn (), "");
%!   assert (sol.x(end), 2);
%!   assert (sol.y(:, end), ref.y(:, end), 1e-3);
%!   tok = regexp (sol.stats.jacobian_source, '^Jacobian \(function\), then finite differences of FCN from t = (\S+)$', "tokens");
%!   assert (numel (tok), 1);
%!   tj = str2double (tok{1}{1});
%!   assert (tj >= 0.5 && tj < 2);
%!   o = struct ("HamiltonianHessFcn", @(t, y) eye (2) * NaN);
%!   sol = s{1} (osc, [0 2], [1 0], o);
%!   assert (sol.x(end), 2);
%!   assert (sol.stats.jacobian_source, "HamiltonianHessFcn, then finite differences of FCN from t = 0");
%! endfor

## a collapse into a singularity (H = p^2/2 - 1/|q| from q = 1, p = 0
## reaches q = 0 at t = pi/(2*sqrt(2)) = 1.1107): adaptive steps shrink
## until they cannot; the solution up to there comes back
%!test
%! f = @(t, y) [y(2); -sign(y(1)) / y(1)^2];
%! tc = pi / (2 * sqrt (2));
%! for s = {@odeSE, @odeSPVI}
%!   name = func2str (s{1});
%!   [t, y, msg, id] = run_warn (s{1}, f, [0 2], [1 0]);
%!   assert (any (strcmp (id, {"symplectic:step-size", "symplectic:newton-failed", "symplectic:nonfinite"})), id);
%!   assert (regexp (msg, ['^' name ': .*returning the solution up to']));
%!   assert (t(end) > 1.0 && t(end) < tc + 1e-6);
%!   assert (all (isfinite (y(:))));
%!   assert (rows (y) > 10);
%! endfor

## Newton cannot converge with a (much too) large fixed step; with the
## exact Hessian too (it agrees with finite differences: kept)
%!test
%! f = @(t, y) [y(2); -1e3 * y(1)^3];
%! [t, y, msg, id] = run_warn (@odeSPVI, f, [0 10], [10 0], struct ("TimeStepSize", 1));
%! assert (id, "symplectic:newton-failed");
%! assert (regexp (msg, '^odeSPVI: Newton''s method did not converge at t = 0 with the fixed step'));
%! assert (t, 0);
%! assert (y, [10 0]);
%! o = struct ("TimeStepSize", 1, "HamiltonianHessFcn", @(t, y) [3e3 * y(1)^2, 0; 0, 1]);
%! [t, y, msg, id] = run_warn (@odeSPVI, f, [0 10], [10 0], o);
%! assert (id, "symplectic:newton-failed");
%! assert (t, 0);
%! evalc ("s = odeSPVI (f, [0 10], [10 0], o);");
%! assert (s.stats.jacobian_source, "HamiltonianHessFcn");
%! ## nor at q = 1e6, where the finite differences (steps of sqrt(eps) |q|)
%! ## of a pendulum err by 1%
%! o = struct ("TimeStepSize", 1.5, "MaxNewtonIterations", 1, ...
%!             "HamiltonianHessFcn", @(t, y) [cos(y(1)) 0; 0 1]);
%! evalc ("s = odeSPVI (@(t, y) [y(2); -sin(y(1))], [0 30], [1e6+1; 2.5], o);");
%! assert (s.stats.jacobian_source, "HamiltonianHessFcn");

## Newton fails with a Hessian that misses a forcing term's dF/dy (here
## the damping -c p, c = 100: the run stopped at t = 0) or with a wrong
## Jacobian: finite differences of FCN take over, and the run goes on as
## it would have with them from the start
%!test
%! c = 100;
%! f = @(t, y) [y(2); -y(1) - c * y(2)];
%! for s = all3
%!   o = struct ("TimeStepSize", 0.01);
%!   ref = s{1} (f, [0 2], [1 0], o);
%!   lastwarn ("");
%!   sol = s{1} (f, [0 2], [1 0], setfield (o, "HamiltonianHessFcn", @(t, y) eye (2)));
%!   assert (lastwarn (), "");
%!   assert (sol.x(end), 2);
%!   assert (sol.y, ref.y, 1e-12);
%!   assert (sol.stats.jacobian_source, "HamiltonianHessFcn, then finite differences of FCN from t = 0");
%! endfor
%! ## a Hessian with a NaN (fcn finite), as second output of fcn too:
%! ## before, the steps shrank to 1e-309 and the run stopped at t0
%! for s = all3
%!   for t0 = [0 1]
%!     o = struct ("TimeStepSize", 0.01);
%!     ref = s{1} (f, [t0 t0+1], [1 0], o);
%!     o.HamiltonianHessFcn = @(t, y) [NaN 0; 0 1];
%!     lastwarn ("");
%!     sol = s{1} (f, [t0 t0+1], [1 0], o);
%!     assert (lastwarn (), "");
%!     assert (sol.y, ref.y, 1e-12);
%!     assert (sol.stats.jacobian_source, sprintf ("HamiltonianHessFcn, then finite differences of FCN from t = %g", t0));
%!   endfor
%!   sol = s{1} (@fcn_nan_hessian, [0 1], [1 0]);
%!   assert (sol.x(end), 1);
%!   assert (sol.stats.jacobian_source, "second output of FCN (Hessian), then finite differences of FCN from t = 0");
%! endfor
%! sol = odeSPVI (osc, [0 2], [1 0], struct ("Jacobian", 1e6 * [1 1; 1 1]));
%! assert (sol.stats.nsteps < 50);    # before: 261771 steps, 16 million calls
%! assert (sol.y(:, end), [cos(2); -sin(2)], 1e-3);
%! assert (regexp (sol.stats.jacobian_source, '^Jacobian \(constant matrix\), then finite differences of FCN from t = '));

## A Hessian far too large (a user's of 1e12 or 1e14 times H's): Newton's
## corrections were below round-off from the first on, each solve was
## accepted at its start, and the runs ended far from the solution with
## no word (odeSPVI's energy error 4e2 with 1e12, odeSV's 1.2e-2 with 1e14
## against 8e-6).  The first Hessian is probed against f along one
## direction and dropped: the runs are those of finite differences.
%!test
%! f = @(t, y, c) fcn_scaled_hessian (t, y, c);
%! for s = all3
%!   o = struct ("TimeStepSize", 0.01);
%!   ref = s{1} (f, [0 2], [1 0.5], o, 1);
%!   for c = [1e3 1e12 1e14]
%!     lastwarn ("");
%!     sol = s{1} (@fcn_scaled_hessian, [0 2], [1 0.5], o, c);
%!     assert (lastwarn (), "");
%!     assert (sol.y, ref.y, 1e-12);
%!     tok = regexp (sol.stats.jacobian_source, '^second output of FCN \(Hessian\), then finite differences of FCN from t = (\S+)$', "tokens");
%!     assert (numel (tok), 1);
%!     assert (str2double (tok{1}{1}) < 0.01);
%!   endfor
%!   ## the right one, and one 10 times too large (Newton slower), stay
%!   for c = [1 10]
%!     sol = s{1} (@fcn_scaled_hessian, [0 2], [1 0.5], o, c);
%!     assert (sol.y, ref.y, 1e-12);
%!     assert (sol.stats.jacobian_source, "second output of FCN (Hessian)");
%!   endfor
%! endfor

## MaxSteps
%!test
%! for s = all3
%!   name = func2str (s{1});
%!   [t, y, msg, id] = run_warn (s{1}, osc, [0 100], [1 0], struct ("MaxSteps", 10, "Refine", 1));
%!   assert (id, "symplectic:max-steps");
%!   assert (regexp (msg, ['^' name ': MaxSteps reached at t = ']));
%!   assert (rows (y), 11);
%!   assert (t(end) < 100);
%!   [t, y, msg, id] = run_warn (s{1}, osc, [0 100], [1 0], struct ("MaxSteps", 10, "TimeStepSize", 0.5));
%!   assert (id, "symplectic:max-steps");
%!   assert (t, (0:0.5:5)', 1e-12);
%!   ## with output times the run stops between them: the message says
%!   ## where it stopped and up to which row it returns
%!   [t, y, msg, id] = run_warn (s{1}, osc, [0 1 2 50 100], [1 0], struct ("MaxSteps", 30, "TimeStepSize", 0.1));
%!   assert (id, "symplectic:max-steps");
%!   assert (t, [0; 1; 2]);
%!   assert (regexp (msg, ['^' name ': MaxSteps reached at t = (3|2\.9999999\d*|3\.0000000\d*); returning the solution up to t = 2$']));
%! endfor

## the warnings can be turned off by their identifiers; rows still return
%!test
%! warning ("off", "symplectic:nonfinite", "local");
%! lastwarn ("");
%! [t, y] = odeSPVI (@rf_nan_after_1, [0 3], [1 0]);
%! assert (lastwarn (), "");
%! assert (t(end) > 0.95 && t(end) <= 1);

%!test
%! ## The finite differences scale with the problem: H = p^2/2 (1 + (q/a)^2) +
%! ## q^2/2, whose solutions are a times those of a = 1, is solved alike
%! ## at every scale.  Before, their steps of sqrt(eps) max(1, |y_i|) were
%! ## 150 a at a = 1e-10: the fixed-step runs stopped at t = 0 ("Newton's
%! ## method did not converge") and the adaptive ones failed 2562 steps of
%! ## odeSV (none at a = 1).
%! for s = all3
%!   for adaptive = [false true]
%!     r = {};
%!     for a = [1 1e-10 1e10]
%!       f = @(t, y) a * [y(2)/a * (1 + (y(1)/a)^2); -((y(2)/a)^2 * y(1)/a + y(1)/a)];
%!       if (adaptive)
%!         o = odeset ("RelTol", 1e-6, "AbsTol", 1e-6 * a);
%!       else
%!         o = struct ("TimeStepSize", 0.05);
%!       endif
%!       lastwarn ("");
%!       r{end+1} = s{1} (f, [0 5], a * [0.8; 0.6], o);
%!       assert (lastwarn (), "");
%!       assert (r{end}.stats.jacobian_source, "finite differences of FCN");
%!       assert (r{end}.x(end), 5);
%!       ## the same steps (adaptive: up to the round-off of the controller,
%!       ## which moves the steps by 1e-7 relative on odeSPVI's 18 steps)
%!       assert (r{end}.x, r{1}.x, adaptive * 1e-6);
%!       assert (r{end}.y / a, r{1}.y, adaptive * 1e-6 + 1e-14);
%!       assert ([r{end}.stats.nsteps, r{end}.stats.nfailed], ...
%!               [r{1}.stats.nsteps, r{1}.stats.nfailed]);
%!     endfor
%!   endfor
%! endfor

%!test
%! ## so a right Hessian is not taken for a wrong one at a small scale:
%! ## before, after a Newton failure the differences (wrong there) replaced
%! ## it, and the runs at a = 1e-10 took 3 to 74 times the calls.  The
%! ## same steps at every scale; the calls within 5%: odeSE's solves start
%! ## from the history of the unknown, at round-off from the solution in
%! ## places, so whether a last correction is round-off (and f at the
%! ## solution needs no call) follows the last bits (62429 vs 61080 calls)
%! for s = all3
%!   n = k = [];
%!   for a = [1 1e-10]
%!     f = @(t, y) a * [y(2)/a * (1 + (y(1)/a)^2); -((y(2)/a)^2 * y(1)/a + y(1)/a)];
%!     hs = @(t, y) [(y(2)/a)^2 + 1, 2 * y(2)*y(1)/a^2; 2 * y(2)*y(1)/a^2, 1 + (y(1)/a)^2];
%!     o = odeset ("RelTol", 1e-6, "AbsTol", 1e-6 * a, "InitialStep", 3, "MaxStep", 3);
%!     sol = s{1} (f, [0 20], a * [0.8; 0.6], symplecticset (o, "HamiltonianHessFcn", hs));
%!     assert (sol.stats.jacobian_source, "HamiltonianHessFcn");
%!     n(end+1) = sol.stats.nfevals;
%!     k(end+1) = sol.stats.nsteps;
%!   endfor
%!   assert (k(2), k(1));
%!   assert (n(2), n(1), 0.05 * n(1));
%! endfor

%!test
%! ## components of one half of very different sizes: two uncoupled
%! ## oscillators, q = (0, 0.8) and p = (1e10, 0.6), the second nonlinear
%! ## at size 1.  Each component is differenced at its own size (and at
%! ## least 1e-6 times its half's largest); a rule tried first, steps from
%! ## the largest size of the half, stopped the fixed-step runs at t = 0,
%! ## 2.1 and 2.35, and adaptive odeSPVI took 25061 calls
%! f = @(t, y) [y(3); y(4) * (1 + y(2)^2); -y(1); -(y(4)^2 * y(2) + y(2))];
%! g = @(t, y) [y(2) * (1 + y(1)^2); -(y(2)^2 * y(1) + y(1))];
%! ## (Newton's test measures the state with one size, 1e10 here, so the
%! ## small oscillator is converged less tightly than alone: its energy
%! ## error is compared, not its values)
%! H = @(q, p) p.^2/2 .* (1 + q.^2) + q.^2/2;
%! for s = all3
%!   lastwarn ("");
%!   ref = s{1} (g, [0 5], [0.8; 0.6], struct ("TimeStepSize", 0.05));
%!   sol = s{1} (f, [0 5], [0; 0.8; 1e10; 0.6], struct ("TimeStepSize", 0.05));
%!   assert (lastwarn (), "");
%!   assert (sol.x(end), 5);
%!   dh = max (abs (H (sol.y(2, :), sol.y(4, :)) - H (0.8, 0.6)));
%!   dhref = max (abs (H (ref.y(1, :), ref.y(2, :)) - H (0.8, 0.6)));
%!   assert (dh, dhref, 0.1 * dhref + 1e-6);
%!   assert (sol.y([1 3], end), [1e10 * sin(5); 1e10 * cos(5)], 1e10 * 0.05);
%!   ref = s{1} (g, [0 5], [0.8; 0.6], odeset ("RelTol", 1e-6, "AbsTol", 1e-6));
%!   sol = s{1} (f, [0 5], [0; 0.8; 1e10; 0.6], odeset ("RelTol", 1e-6, "AbsTol", 1e-6 * [1 1 1e10 1]));
%!   assert (lastwarn (), "");
%!   assert (sol.stats.nfevals < 1.5 * ref.stats.nfevals + 200);
%! endfor
