## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## Tests of odeSE and odeSV through the Octave interface: orders,
## symplecticity, long-time energy, momenta, reversibility, the explicit
## separable paths, the four Jacobian sources, forcing, adaptive control.
## References are independent of the package: ode45 at tight tolerances,
## analytic solutions and exact invariants.

%!function dy = nonsep (t, y)
%!  ## H = p^2/2 (1 + q^2) + q^2/2
%!  q = y(1); p = y(2);
%!  dy = [p * (1 + q^2); -(p^2 * q + q)];
%!endfunction

%!function [dy, ddy] = nonsep2 (t, y)
%!  q = y(1); p = y(2);
%!  dy = [p * (1 + q^2); -(p^2 * q + q)];
%!  ddy = [p^2 + 1, 2*p*q; 2*p*q, 1 + q^2];
%!endfunction

%!function H = nonsep_hess (t, y)
%!  q = y(1); p = y(2);
%!  H = [p^2 + 1, 2*p*q; 2*p*q, 1 + q^2];
%!endfunction

%!function Df = nonsep_jac (t, y)
%!  q = y(1); p = y(2);
%!  Df = [2*p*q, 1 + q^2; -(p^2 + 1), -2*p*q];
%!endfunction

%!function dy = pendulum (t, y)
%!  dy = [y(2); -sin(y(1))];
%!endfunction

%!function dy = kepler (t, y)
%!  q = y(1:2);
%!  dy = [y(3:4); -q / norm(q)^3];
%!endfunction

%!function yref = reference (f, tf, y0)
%!  o = odeset ("RelTol", 1e-12, "AbsTol", 1e-13);
%!  [~, y] = ode45 (f, [0, tf], y0, o);
%!  yref = y(end, :);
%!endfunction

%!function s = slopes (solver, f, tf, y0, hs, yref, varargin)
%!  err = zeros (size (hs));
%!  for i = 1:numel (hs)
%!    o = symplecticset ("TimeStepSize", hs(i), varargin{:});
%!    [~, y] = solver (f, [0, tf], y0, o);
%!    err(i) = norm (y(end, :) - yref, Inf);
%!  endfor
%!  s = log2 (err(1:end-1) ./ err(2:end));
%!endfunction

## ----------------------------------------------------------------- orders
%!test
%! hs = 0.1 ./ 2.^(0:3);
%! yref = reference (@nonsep, 2, [0.5; 0.5]);
%! s = slopes (@odeSE, @nonsep, 2, [0.5; 0.5], hs, yref);
%! assert (all (abs (s - 1) <= 0.1), "odeSE slopes %s", mat2str (s, 3));
%! s = slopes (@odeSV, @nonsep, 2, [0.5; 0.5], hs, yref);
%! assert (all (abs (s - 2) <= 0.1), "odeSV slopes %s", mat2str (s, 3));

%!test
%! hs = 0.1 ./ 2.^(0:3);
%! yref = reference (@pendulum, 5, [1; 1]);
%! s = slopes (@odeSE, @pendulum, 5, [1; 1], hs, yref);
%! assert (all (abs (s - 1) <= 0.1), "odeSE slopes %s", mat2str (s, 3));
%! s = slopes (@odeSV, @pendulum, 5, [1; 1], hs, yref);
%! assert (all (abs (s - 2) <= 0.1), "odeSV slopes %s", mat2str (s, 3));
%! s = slopes (@odeSV, @pendulum, 5, [1; 1], hs, yref, "Separable", "on");
%! assert (all (abs (s - 2) <= 0.1), "odeSV explicit slopes %s", mat2str (s, 3));
%! s = slopes (@odeSE, @pendulum, 5, [1; 1], hs, yref, "Separable", "on");
%! assert (all (abs (s - 1) <= 0.1), "odeSE explicit slopes %s", mat2str (s, 3));

## ----------------------------------------------------------------- symplecticity
%!test
%! ## the Jacobian M of one step satisfies M' J M = J
%! J = [0 1; -1 0];
%! y0 = [0.3; -0.7];  h = 0.2;  del = 1e-5;
%! for solver = {@odeSE, @odeSV}
%!   o = symplecticset ("TimeStepSize", h);
%!   M = zeros (2);
%!   for j = 1:2
%!     e = zeros (2, 1); e(j) = del;
%!     [~, yp] = solver{1} (@nonsep, [0 h], y0 + e, o);
%!     [~, ym] = solver{1} (@nonsep, [0 h], y0 - e, o);
%!     M(:, j) = (yp(end, :) - ym(end, :)).' / (2 * del);
%!   endfor
%!   assert (norm (M.' * J * M - J) <= 1e-8);
%!   ## and the map is not trivially the identity
%!   assert (norm (M - eye (2)) > 0.1);
%! endfor

## ----------------------------------------------------------------- long time
%!test
%! ## harmonic oscillator, h = 0.1, 1e5 steps: bounded energy, no drift
%! f = @(t, y) [y(2); -y(1)];
%! o = symplecticset ("TimeStepSize", 0.1, "Separable", "on");
%! [t, y] = odeSV (f, [0, 1e4], [1; 0], o);
%! assert (numel (t), 1e5 + 1);
%! E = (y(:, 1).^2 + y(:, 2).^2) / 2;
%! rel = abs (E - 0.5) / 0.5;
%! assert (max (rel) <= 3e-3);
%! n10 = round (numel (rel) / 10);
%! assert (max (rel(end-n10+1:end)) <= 1.5 * max (rel(1:n10)));

%!test
%! ## Kepler: angular momentum to 1e-12 relative over 1e4 fixed steps
%! e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
%! L0 = y0(1) * y0(4) - y0(2) * y0(3);
%! for solver = {@odeSE, @odeSV}
%!   for sep = {"off", "on"}
%!     o = symplecticset ("TimeStepSize", 0.01, "Separable", sep{1});
%!     [t, y] = solver{1} (@kepler, [0, 100], y0, o);
%!     assert (numel (t), 1e4 + 1);
%!     L = y(:, 1) .* y(:, 4) - y(:, 2) .* y(:, 3);
%!     assert (max (abs (L - L0)) / abs (L0) <= 1e-12);
%!   endfor
%! endfor

%!test
%! ## a rotation-invariant, non-separable H in 3-D: the angular momentum
%! ## stays at round-off (sqrt(N) eps |L| is 1.9e-14 for N = 10000).  The
%! ## Newton matrix is kept across steps, so the error a solve leaves has
%! ## the same sign from step to step; at NewtonTol itself L drifted
%! ## linearly, by 2e-12 (odeSE) and 1.2e-11 (odeSV) over these steps.
%! f = @(t, y) [y(4:6) * (1 + y(1:3).' * y(1:3) / 4);
%!              -((y(4:6).' * y(4:6)) / 4 * y(1:3) + y(1:3) / norm (y(1:3))^3)];
%! y0 = [0.4; 0; 0.1; 0; 2*cos(0.3); 2*sin(0.3)];
%! L0 = cross (y0(1:3), y0(4:6)).';
%! o = symplecticset ("TimeStepSize", 2*pi/200);
%! for solver = {@odeSE, @odeSV}
%!   [t, y] = solver{1} (f, [0, 10000*2*pi/200], y0, o);
%!   assert (numel (t), 10001);
%!   dL = max (abs (cross (y(:, 1:3), y(:, 4:6), 2) - L0), [], 2);
%!   assert (max (dL) <= 2e-13, "%s: %g", func2str (solver{1}), max (dL));
%! endfor

%!function [dy, ddy] = rot3_hess (t, y)
%!  ## H = |p|^2/2 (1 + |q|^2/4) + |q|^4/8 + (q.p)^2/4 in 3-D, rotation
%!  ## invariant; its Hessian as second output
%!  q = y(1:3);  p = y(4:6);  s = q.' * p;  I = eye (3);
%!  dy = [p * (1 + q.'*q/4) + s*q/2; -(q * (p.'*p)/4 + q * (q.'*q)/2 + s*p/2)];
%!  if (nargout > 1)
%!    Hqp = p*q.'/2 + s*I/2 + q*p.'/2;
%!    ddy = [(p.'*p)/4*I + (q.'*q)/2*I + q*q.' + p*p.'/2, Hqp;
%!           Hqp.', (1 + q.'*q/4)*I + q*q.'/2];
%!  endif
%!endfunction

%!test
%! ## the same with the Hessian given: a solve that stops on a round-off
%! ## correction has f at the iterate before it, which is moved to the
%! ## result by the Hessian; used unmoved, that error of a few ulps kept
%! ## its sign and L drifted by 1.5e-13 (odeSE) over these 10000 steps
%! ## (9e-15 now; odeSV 1e-14)
%! ## With finite differences (f alone), whose matrices contract more
%! ## slowly, odeSV's stop at NewtonTol/100 drifted by 9.8e-14 over these
%! ## steps (4.1e-13 over 40000): fixed steps of odeSE and odeSV now stop
%! ## at NewtonTol/1000 (5.8e-15)
%! y0 = [1; 0.2; -0.3; 0.1; 0.8; 0.4];
%! L0 = cross (y0(1:3), y0(4:6)).';
%! o = symplecticset ("TimeStepSize", 0.05);
%! for solver = {@odeSE, @odeSV}
%!   for fn = {@rot3_hess, @(t, y) rot3_hess(t, y)(:)}
%!     [t, y] = solver{1} (fn{1}, [0, 500], y0, o);
%!     assert (numel (t), 10001);
%!     dL = max (abs (cross (y(:, 1:3), y(:, 4:6), 2) - L0), [], 2);
%!     assert (max (dL) <= 4e-14, "%s, %s: %g", func2str (solver{1}),
%!             func2str (fn{1}), max (dL));
%!   endfor
%! endfor

%!test
%! ## Newton's start from the history of the unknowns: at h = 0.01 the
%! ## fixed steps of this non-separable H cost about as many calls as the
%! ## explicit separable ones (odeSE 2.00 with the Hessian, odeSV 3.96),
%! ## and the angular momentum stays at round-off over 20000 steps (8e-15;
%! ## from the explicit start alone: 4.0 and 8.0 calls per step, and L
%! ## drifted linearly, by 5.1e-14 and 5.4e-14 here)
%! y0 = [1; 0.2; -0.3; 0.1; 0.8; 0.4];
%! L0 = cross (y0(1:3), y0(4:6)).';
%! o = symplecticset ("TimeStepSize", 0.01);
%! lim = [2.3, 4.4];
%! solvers = {@odeSE, @odeSV};
%! for k = 1:2
%!   sol = solvers{k} (@rot3_hess, [0, 200], y0, o);
%!   assert (columns (sol.x), 20001);
%!   calls = (sol.stats.nfevals + sol.stats.npds) / sol.stats.nsteps;
%!   assert (calls <= lim(k), "%s: %.3f calls per step", func2str (solvers{k}),
%!           calls);
%!   y = sol.y.';
%!   dL = max (abs (cross (y(:, 1:3), y(:, 4:6), 2) - L0), [], 2);
%!   assert (max (dL) <= 2e-14, "%s: %g", func2str (solvers{k}), max (dL));
%! endfor

%!test
%! ## far from t = 0 a fixed step is h itself, as near 0: the same solution
%! ## and the same calls from t0 = 1e8 as from t0 = 0 (the end of a step
%! ## is t0 + k h rounded; when the step was the difference of those ends,
%! ## which varies by the round-off of t, 1.5e-6 h here, the two runs
%! ## differed by 8e-9 and odeSE took 3.00 calls per step from 1e8 against
%! ## 2.00 from 0, odeSV 5.64 against 3.98)
%! y0 = [1; 0.2; -0.3; 0.1; 0.8; 0.4];
%! h = 0.01;  N = 2000;
%! o = symplecticset ("TimeStepSize", h, "TimeStepNumber", N);
%! for solver = {@odeSE, @odeSV}
%!   s0 = solver{1} (@rot3_hess, [0, N*h], y0, o);
%!   s8 = solver{1} (@rot3_hess, [1e8, 1e8 + N*h], y0, o);
%!   assert (s8.x, 1e8 + h * (0:N));
%!   assert (s8.y, s0.y);   # to the bit: f does not depend on t
%!   c0 = s0.stats.nfevals + s0.stats.npds;
%!   c8 = s8.stats.nfevals + s8.stats.npds;
%!   assert (c8 == c0, "%s: %d calls from 1e8, %d from 0",
%!           func2str (solver{1}), c8, c0);
%! endfor

%!test
%! ## Separable "on" with an f that is not separable: the explicit steps
%! ## find it from the f they evaluate anyway (odeSE: dH/dq at the same q
%! ## with two p; odeSV: dH/dp at the same p with two q) and warn; a
%! ## separable H, also with forcing in t, gives no warning
%! fns = {@nonsep, @(t, y) [y(2); -y(1) - 0.1*y(2)], ...
%!        @(t, y) [y(2); -sin(y(1)) + 0.5*cos(t)], @kepler};
%! y0s = {[0.5 0.3], [0.5 0.3], [0.5 0.3], [0.4 0 0 2]};
%! ## which warn: odeSE the first two, odeSV the first (damping leaves its
%! ## dH/dp alone)
%! expect = {[true true false false], [true false false false]};
%! solvers = {@odeSE, @odeSV};
%! for k = 1:2
%!   for j = 1:4
%!     for o = {struct("Separable", "on", "TimeStepSize", 0.1), ...
%!              struct("Separable", "on")}
%!       lastwarn ("");
%!       evalc ("[~, ~] = solvers{k} (fns{j}, [0 1], y0s{j}, o{1});");
%!       [msg, id] = lastwarn ();
%!       assert (strcmp (id, "symplectic:not-separable"), expect{k}(j),
%!               sprintf ("%s, f %d: [%s] %s", func2str (solvers{k}), j, id, msg));
%!     endfor
%!   endfor
%! endfor

%!test
%! ## odeSV is time-reversible
%! N = 200;  h = 0.05;  y0 = [0.3; -0.7];
%! o = symplecticset ("TimeStepSize", h);
%! [~, y] = odeSV (@nonsep, [0, N*h], y0, o);
%! [~, yb] = odeSV (@nonsep, [N*h, 0], y(end, :), o);
%! assert (numel (yb(:, 1)), N + 1);
%! ## to round-off: the fixed steps' solves are converged to NewtonTol/1000
%! ## (at NewtonTol itself the way back missed y0 by 6e-13)
%! assert (norm (yb(end, :).' - y0, Inf) <= 1e-13);
%! ## while odeSE is not (its adjoint differs), so the test can fail
%! [~, y] = odeSE (@nonsep, [0, N*h], y0, o);
%! [~, yb] = odeSE (@nonsep, [N*h, 0], y(end, :), o);
%! assert (norm (yb(end, :).' - y0, Inf) > 1e-6);

## ----------------------------------------------------------------- separable
%!test
%! e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
%! for solver = {@odeSE, @odeSV}
%!   o1 = symplecticset ("TimeStepSize", 0.01, "Stats", "off");
%!   o2 = symplecticset (o1, "Separable", "on");
%!   s1 = solver{1} (@kepler, [0, 20], y0, o1);
%!   s2 = solver{1} (@kepler, [0, 20], y0, o2);
%!   ## the same method: equal to round-off, which the 2000 steps of the
%!   ## orbit grow (odeSV: 2.2e-12; its implicit q-solve starts from the
%!   ## history of q_{k+1}, the explicit step computes q_k + h f_q at once)
%!   assert (s2.y, s1.y, 1e-11);
%!   calls = s2.stats.nfevals / s2.stats.nsteps;
%!   assert (calls <= 2.05, "%.3f calls per step", calls);
%!   assert (s2.stats.nnewton, 0);
%!   assert (s1.stats.nnewton > 0);
%! endfor

## ----------------------------------------------------------------- Jacobians
%!test
%! y0 = [0.5; 0.5];
%! for solver = {@odeSE, @odeSV}
%!   o = symplecticset ("TimeStepSize", 0.05);
%!   s1 = solver{1} (@nonsep, [0 3], y0, o);                        # FD
%!   s2 = solver{1} (@nonsep2, [0 3], y0, o);                       # 2nd output
%!   s3 = solver{1} (@nonsep, [0 3], y0, symplecticset (o, "HamiltonianHessFcn", @nonsep_hess));
%!   s4 = solver{1} (@nonsep, [0 3], y0, symplecticset (o, "Jacobian", @nonsep_jac));
%!   assert (s1.stats.jacobian_source, "finite differences of FCN");
%!   assert (s2.stats.jacobian_source, "second output of FCN (Hessian)");
%!   assert (s3.stats.jacobian_source, "HamiltonianHessFcn");
%!   assert (s4.stats.jacobian_source, "Jacobian (function)");
%!   assert (s2.y, s1.y, 1e-10);
%!   assert (s3.y, s1.y, 1e-10);
%!   assert (s4.y, s1.y, 1e-10);
%!   assert (s2.stats.npds > 0 && s3.stats.npds > 0 && s4.stats.npds > 0);
%!   assert (s1.stats.nfdevals > 0);
%! endfor

%!test
%! ## a Hessian as a column-major vector (the 2013 convention), and a
%! ## constant Jacobian matrix for a linear problem
%! f = @(t, y) [y(2); -4*y(1)];
%! o = symplecticset ("TimeStepSize", 0.01);
%! s1 = odeSV (f, [0 2], [1; 0], o);
%! s2 = odeSV (f, [0 2], [1; 0], symplecticset (o, "HamiltonianHessFcn", @(t, y) [4; 0; 0; 1]));
%! s3 = odeSV (f, [0 2], [1; 0], symplecticset (o, "Jacobian", [0 1; -4 0]));
%! assert (s2.y, s1.y, 1e-12);
%! assert (s3.y, s1.y, 1e-12);
%! assert (s3.stats.jacobian_source, "Jacobian (constant matrix)");

## ----------------------------------------------------------------- forcing
%!test
%! ## damped oscillator q'' + c q' + q = 0, forcing -c p, against the
%! ## analytic solution; the error has the method's order
%! c = 0.1;  w = sqrt (1 - c^2/4);
%! f = @(t, y) [y(2); -y(1) - c * y(2)];
%! qex = @(t) exp (-c*t/2) .* (cos (w*t) + c/(2*w) * sin (w*t));
%! pex = @(t) -exp (-c*t/2) .* (1 + c^2/(4*w^2)) * w .* sin (w*t);
%! tf = 5;  hs = 0.1 ./ 2.^(0:2);
%! for k = 1:2
%!   solver = {@odeSE, @odeSV}{k};
%!   err = zeros (size (hs));
%!   for i = 1:numel (hs)
%!     [t, y] = solver (f, [0 tf], [1; 0], symplecticset ("TimeStepSize", hs(i)));
%!     err(i) = norm ([y(end, 1) - qex(tf), y(end, 2) - pex(tf)], Inf);
%!   endfor
%!   s = log2 (err(1:end-1) ./ err(2:end));
%!   assert (all (abs (s - k) <= 0.1), "slopes %s", mat2str (s, 3));
%!   ## the damping is really there
%!   assert (y(end, 1)^2 + y(end, 2)^2 < 0.7);
%! endfor

## ----------------------------------------------------------------- adaptive
%!test
%! e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
%! tf = 2*pi;
%! yref = y0.';   # one period returns to the start
%! err = zeros (1, 3);  nst = err;
%! rt = [1e-4 1e-5 1e-6];
%! for i = 1:3
%!   o = odeset ("RelTol", rt(i), "AbsTol", rt(i) * 1e-2);
%!   s = odeSV (@kepler, [0 tf], y0, o);
%!   err(i) = norm (s.y(:, end).' - yref, Inf);
%!   nst(i) = s.stats.nsteps;
%! endfor
%! assert (all (err(1:end-1) ./ err(2:end) >= 4), "errors %s", mat2str (err, 3));
%! assert (all (diff (nst) > 0));

%!test
%! ## the error estimate holds every component to its tolerance: q loose, p
%! ## tight; each step's local error against the oscillator's exact flow,
%! ## on the explicit and the implicit path (the p-update of Verlet is the
%! ## trapezoidal rule, so an estimate by the trapezoidal rule alone would
%! ## see no error in p: local errors 8e5 times AbsTol(2))
%! f = @(t, y) [y(2); -y(1)];
%! tol = [1e-2 1e-8];
%! for sep = {"off", "on"}
%!   o = symplecticset ("RelTol", 1e-12, "AbsTol", tol, "Separable", sep{1});
%!   [t, y] = odeSV (f, [0 20], [1; 0], o);
%!   h = diff (t);
%!   ye = [cos(h) .* y(1:end-1, 1) + sin(h) .* y(1:end-1, 2), ...
%!         -sin(h) .* y(1:end-1, 1) + cos(h) .* y(1:end-1, 2)];
%!   r = max (abs (y(2:end, :) - ye) ./ tol);
%!   assert (r(2) <= 1.5 && r(2) >= 0.1, "local error / AbsTol %s", mat2str (r, 3));
%!   assert (abs (y(end, 2) + sin (20)) < 1e-4);
%! endfor

%!test
%! ## the same on Kepler e = 0.99 (pericentre at r = 0.01), RelTol = AbsTol
%! ## = 1e-8: 40 steps spread over the period, each against ode45 from the
%! ## same start (before the estimate held p too: up to 580 x tolerance)
%! kep = @(t, y) [y(3:4); -y(1:2) / norm(y(1:2))^3];
%! e = 0.99;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
%! tol = 1e-8;
%! [t, y] = odeSV (kep, [0 2*pi], y0, symplecticset ("RelTol", tol, "AbsTol", tol, "Separable", "on"));
%! oo = odeset ("RelTol", 1e-13, "AbsTol", 1e-15);
%! idx = round (linspace (1, numel (t) - 1, 40));
%! r = zeros (numel (idx), 4);
%! for k = 1:numel (idx)
%!   i = idx(k);
%!   [~, ye] = ode45 (kep, [t(i) t(i+1)], y(i, :).', oo);
%!   r(k, :) = abs (y(i+1, :) - ye(end, :)) ./ (tol + tol * max (abs (y(i, :)), abs (y(i+1, :))));
%! endfor
%! assert (max (r(:)) <= 1.5, "local error / tolerance %s", mat2str (max (r), 3));

%!test
%! ## odeSE adaptive: tighter tolerance, smaller error
%! e = 0.3;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
%! err = zeros (1, 2);
%! rt = [1e-3 1e-4];
%! for i = 1:2
%!   s = odeSE (@kepler, [0 2*pi], y0, odeset ("RelTol", rt(i), "AbsTol", rt(i)));
%!   err(i) = norm (s.y(:, end) - y0, Inf);
%! endfor
%! assert (err(1) / err(2) >= 2.5, "errors %s", mat2str (err, 3));

## ----------------------------------------------------------------- backward
%!test
%! f = @(t, y) [y(2); -y(1)];
%! [t, y] = odeSV (f, [1, -2], [cos(1); -sin(1)], symplecticset ("TimeStepSize", 1e-3));
%! assert (t(end), -2);
%! assert (all (diff (t) < 0));
%! assert (y(end, :), [cos(-2), -sin(-2)], 1e-6);
%! [t, y] = odeSE (f, [1, -2], [cos(1); -sin(1)], odeset ("RelTol", 1e-6, "AbsTol", 1e-8));
%! assert (t(end), -2);
%! assert (y(end, :), [cos(-2), -sin(-2)], 1e-3);

## --------------------------------------------------- Vectorized Jacobians
%!test
%! ## with Vectorized, a finite-difference Jacobian takes one call for its
%! ## 2d perturbed states: the same steps, 2d times fewer calls for it
%! f = @(t, y) [y(2,:) .* (1 + y(1,:).^2); -(y(2,:).^2 .* y(1,:) + y(1,:))];
%! o = symplecticset ("TimeStepSize", 0.05);
%! for solver = {@odeSE, @odeSV}
%!   s0 = solver{1} (f, [0 5], [0.5; 0.2], o);
%!   s1 = solver{1} (f, [0 5], [0.5; 0.2], symplecticset (o, "Vectorized", "on"));
%!   assert (s1.y, s0.y, 1e-13);
%!   assert (s0.stats.jacobian_source, "finite differences of FCN");
%!   assert (s1.stats.nfdevals > 0);
%!   assert (2 * s1.stats.nfdevals, s0.stats.nfdevals);
%!   ## less the two calls of the Vectorized check
%!   assert (s0.stats.nfevals - s1.stats.nfevals, s1.stats.nfdevals - 2);
%! endfor

## ------------------------------------------------- fast oscillation, fixed
%!test
%! ## two oscillators, frequencies 1 and 100, the fast one at amplitude
%! ## 1e-3: a fixed step of odeSV keeps the fast one's energy (help odeSE,
%! ## RelTol; bench/adaptive_runs.m shows adaptive steps moving it).
%! ## Verlet conserves p^2 + w^2 q^2 (1 - (w h)^2/4) exactly for each
%! ## oscillator, so the energy itself changes by at most (w h)^2/4
%! w = 100;  h = 0.002;
%! f = @(t, y) [y(3:4); -y(1); -w^2 * y(2)];
%! y0 = [1; 1e-3; 0; 0];
%! s = odeSV (f, [0 100], y0, symplecticset ("TimeStepSize", h, "Separable", "on"));
%! assert (s.stats.nsteps, 50000);
%! E2 = (s.y(4, :).^2 + w^2 * s.y(2, :).^2) / (w^2 * 1e-6);
%! I2 = (s.y(4, :).^2 + w^2 * (1 - (w*h)^2/4) * s.y(2, :).^2) / (w^2 * 1e-6);
%! assert (max (abs (I2 - I2(1))) < 1e-12);
%! assert (max (abs (E2 - 1)) <= (w*h)^2/4 + 1e-12);
%! assert (max (abs (E2 - 1)) > 0.99 * (w*h)^2/4);
%! I1 = s.y(3, :).^2 + (1 - h^2/4) * s.y(1, :).^2;
%! assert (max (abs (I1 - I1(1))) < 1e-12);
