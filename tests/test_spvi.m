## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## Tests of odeSPVI through the Octave interface: measured orders against
## the exact pendulum, symplecticity, Kepler's invariants over many periods,
## the four sources of Newton's matrix, adaptive control, bad pairs.

%!function y = pendulum_exact (t, y0)
%!  ## H = p^2/2 - cos q, libration: sin(q/2) = k sn(u), p = 2 k cn(u),
%!  ## u = u0 + t, k = sin(qmax/2), with Jacobi's elliptic functions
%!  E = y0(2)^2/2 - cos (y0(1));
%!  k = sin (acos (-E) / 2);
%!  s0 = sin (y0(1)/2) / k;
%!  u0 = asin (s0);                # then Newton on sn(u0) = s0 (sn' = cn dn)
%!  for it = 1:50
%!    [sn, cn, dn] = ellipj (u0, k^2);
%!    du = (sn - s0) / (cn * dn);
%!    u0 -= du;
%!    if (abs (du) < 1e-17)
%!      break;
%!    endif
%!  endfor
%!  if (y0(2) < 0)
%!    error ("pendulum_exact: p0 >= 0 assumed");
%!  endif
%!  [sn, cn] = ellipj (u0 + t(:), k^2);
%!  y = [2 * asin(k * sn), 2 * k * cn];
%!endfunction

%!function dy = pendulum (t, y)
%!  dy = [y(2); -sin(y(1))];
%!endfunction

%!function [dy, ddy] = kepler (t, y)
%!  q = y(1:2);  r = norm (q);
%!  dy = [y(3:4); -q / r^3];
%!  if (nargout > 1)
%!    ddy = blkdiag ((eye (2) - 3 * (q * q.') / r^2) / r^3, eye (2));
%!  endif
%!endfunction

%!function H = kepler_hess (t, y)
%!  [~, H] = kepler (t, y);
%!endfunction

%!function Df = kepler_jac (t, y)
%!  [~, H] = kepler (t, y);
%!  Df = [H(3:4, :); -H(1:2, :)];
%!endfunction

%!function dy = kepler1 (t, y)
%!  dy = kepler (t, y);
%!endfunction

%!function dy = kepler_count (t, y)
%!  global KEPLER_CALLS
%!  KEPLER_CALLS++;
%!  dy = kepler (t, y);
%!endfunction

%!function y = kepler_exact (t, e)
%!  ## Kepler's equation E - e sin E = t (period 2 pi, pericentre at t = 0)
%!  E = t(:).';
%!  for it = 1:60
%!    E -= (E - e * sin (E) - t(:).') ./ (1 - e * cos (E));
%!  endfor
%!  dE = 1 ./ (1 - e * cos (E));
%!  y = [cos(E) - e; sqrt(1-e^2) * sin(E); -sin(E) .* dE; sqrt(1-e^2) * cos(E) .* dE].';
%!endfunction

## ----------------------------------------------------------------- orders
%!test
%! ## slopes on the pendulum, y0 = [1; 1], t in [0, 10], against the exact
%! ## solution: order 2*min(n-1, 2m-n+1)
%! y0 = [1; 1];
%! yex = pendulum_exact (10, y0);
%! ## the reference itself: a conserved energy check
%! assert (yex(2)^2/2 - cos (yex(1)), y0(2)^2/2 - cos (y0(1)), 1e-14);
%! hs = 0.5 ./ 2.^(0:3);
%! pairs = [2 1; 3 2; 4 3; 3 3; 4 2; 5 4];
%! for i = 1:rows (pairs)
%!   n = pairs(i, 1);  m = pairs(i, 2);
%!   p = 2 * min (n-1, 2*m-n+1);
%!   err = zeros (size (hs));
%!   for k = 1:numel (hs)
%!     o = symplecticset ("TimeStepSize", hs(k), "Q_DoFs", n, "Nodes", m);
%!     [~, y] = odeSPVI (@pendulum, [0 10], y0, o);
%!     err(k) = norm (y(end, :) - yex, Inf);
%!   endfor
%!   s = log2 (err(1:end-1) ./ err(2:end));
%!   ok = err(2:end) > 1e-12;          # slopes above round-off
%!   s = s(ok);
%!   assert (! isempty (s));
%!   assert (abs (s(end) - p) <= 0.15, "(%d,%d): slopes %s", n, m, mat2str (s, 3));
%!   assert (all (abs (s - p) <= 0.3), "(%d,%d): slopes %s", n, m, mat2str (s, 3));
%! endfor

%!test
%! ## (2,1) is the implicit midpoint rule: compare with an independent one
%! h = 0.1;  y = [1; 1];  f = @(y) [y(2); -sin(y(1))];
%! o = symplecticset ("TimeStepSize", h, "Q_DoFs", 2, "Nodes", 1);
%! [~, ys] = odeSPVI (@pendulum, [0 20*h], y, o);
%! for k = 1:20
%!   z = y;
%!   for it = 1:100
%!     z = y + h * f ((y + z) / 2);
%!   endfor
%!   assert (ys(k+1, :).', z, 1e-13 * k);
%!   y = z;
%! endfor

## ----------------------------------------------------------------- geometry
%!test
%! ## symplecticity of the one-step map on a non-separable H
%! f = @(t, y) [y(2) * (1 + y(1)^2); -(y(2)^2 * y(1) + y(1))];
%! J = [0 1; -1 0];  y0 = [0.3; -0.7];  h = 0.3;  del = 1e-5;
%! for nm = [2 1; 4 3; 3 3].'
%!   o = symplecticset ("TimeStepSize", h, "Q_DoFs", nm(1), "Nodes", nm(2));
%!   M = zeros (2);
%!   for j = 1:2
%!     e = zeros (2, 1);  e(j) = del;
%!     [~, yp] = odeSPVI (f, [0 h], y0 + e, o);
%!     [~, ym] = odeSPVI (f, [0 h], y0 - e, o);
%!     M(:, j) = (yp(end, :) - ym(end, :)).' / (2 * del);
%!   endfor
%!   assert (norm (M.' * J * M - J) <= 1e-8);
%!   assert (norm (M - eye (2)) > 0.1);
%! endfor

%!test
%! ## Kepler e = 0.6, h = T/100, (4,3), 200 periods: bounded energy error,
%! ## angular momentum to round-off (1000 periods: tests/c/test_spvi_kepler)
%! e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
%! o = symplecticset ("TimeStepSize", 2*pi/100, "Q_DoFs", 4, "Nodes", 3);
%! [t, y] = odeSPVI (@kepler, [0 200*2*pi], y0, o);
%! H = sum (y(:, 3:4).^2, 2) / 2 - 1 ./ sqrt (sum (y(:, 1:2).^2, 2));
%! L = y(:, 1) .* y(:, 4) - y(:, 2) .* y(:, 3);
%! dH = abs (H + 0.5) / 0.5;
%! first = t <= 20*2*pi;  last = t >= 180*2*pi;
%! assert (max (dH(last)) <= 1.5 * max (dH(first)));
%! assert (max (dH) < 1e-6);
%! assert (max (abs (L - L(1))) / abs (L(1)) <= 1e-12);

%!test
%! ## a rotation-invariant, non-separable H in 3-D, 10000 fixed steps (the
%! ## help's NewtonTol item): the angular momentum drifts by 2.1e-13 with
%! ## the defaults (the f_p of p_{k+1} are moved linearly to the converged
%! ## nodes, and that move's error, checked to NewtonTol/100, has the same
%! ## sign from step to step); with NewtonTol = 1e-16 it stays at
%! ## round-off, 3e-15 (sqrt(N) eps |L| is 1.9e-14)
%! f = @(t, y) [y(4:6) * (1 + y(1:3).' * y(1:3) / 4);
%!              -((y(4:6).' * y(4:6)) / 4 * y(1:3) + y(1:3) / norm (y(1:3))^3)];
%! y0 = [0.4; 0; 0.1; 0; 2*cos(0.3); 2*sin(0.3)];
%! L0 = cross (y0(1:3), y0(4:6)).';
%! o = symplecticset ("TimeStepSize", 2*pi/200);
%! [~, y] = odeSPVI (f, [0, 10000*2*pi/200], y0, o);
%! assert (max (max (abs (cross (y(:, 1:3), y(:, 4:6), 2) - L0))) <= 1e-12);
%! [~, y] = odeSPVI (f, [0, 10000*2*pi/200], y0, symplecticset (o, "NewtonTol", 1e-16));
%! assert (max (max (abs (cross (y(:, 1:3), y(:, 4:6), 2) - L0))) <= 3e-14);

%!test
%! ## the four sources of Newton's matrix give the same trajectory
%! e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
%! o = symplecticset ("TimeStepSize", 2*pi/100);
%! s1 = odeSPVI (@kepler1, [0 4*pi], y0, o);
%! s2 = odeSPVI (@kepler, [0 4*pi], y0, o);
%! s3 = odeSPVI (@kepler1, [0 4*pi], y0, symplecticset (o, "HamiltonianHessFcn", @kepler_hess));
%! s4 = odeSPVI (@kepler1, [0 4*pi], y0, symplecticset (o, "Jacobian", @kepler_jac));
%! assert (s1.stats.jacobian_source, "finite differences of FCN");
%! assert (s2.stats.jacobian_source, "second output of FCN (Hessian)");
%! assert (s3.stats.jacobian_source, "HamiltonianHessFcn");
%! assert (s4.stats.jacobian_source, "Jacobian (function)");
%! assert (s2.y, s1.y, 1e-10);
%! assert (s3.y, s1.y, 1e-10);
%! assert (s4.y, s1.y, 1e-10);

%!test
%! ## with the Hessian as FCN's second output, the matrix and the residual
%! ## at one point come from one call: the same steps, bit for bit, as with
%! ## the same Hessian from HamiltonianHessFcn, one FCN call fewer per
%! ## Hessian evaluation and in the probe of the first Hessian (nfdevals:
%! ## f at a step along one direction, and f at the point itself when the
%! ## Hessian came alone)
%! e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
%! o = symplecticset ("TimeStepSize", 2*pi/100);
%! s2 = odeSPVI (@kepler, [0 4*pi], y0, o);
%! s3 = odeSPVI (@kepler1, [0 4*pi], y0, symplecticset (o, "HamiltonianHessFcn", @kepler_hess));
%! ## (HamiltonianHessFcn is also called once at (t0, y0), to see whether
%! ## it returns a sparse matrix)
%! assert (s2.y, s3.y);
%! assert (s2.stats.npds, s3.stats.npds - 1);
%! assert (s3.stats.npds > 1);
%! assert (s2.stats.nfdevals, 1);
%! assert (s3.stats.nfdevals, 2);
%! assert (s2.stats.nfevals, s3.stats.nfevals - (s3.stats.npds - 1) - 1);
%! ## NewtonMatrix "new": every step takes a new matrix at its start (3
%! ## calls, whose f the residual there reuses), its first Newton
%! ## correction exact and often the last; the steps agree to round-off,
%! ## with fewer calls (C measurement: 4.71 against 7.11 per step)
%! s4 = odeSPVI (@kepler, [0 4*pi], y0, symplecticset (o, "NewtonMatrix", "new"));
%! assert (s4.y, s2.y, 1e-12);
%! assert (s4.stats.npds, 3 * s4.stats.nsteps);
%! assert ((s4.stats.nfevals + s4.stats.npds) / s4.stats.nsteps <= 5);
%! assert ((s2.stats.nfevals + s2.stats.npds) / s2.stats.nsteps >= 6.5);
%! ## "kept" is the default here; "KEPT" is the same
%! s5 = odeSPVI (@kepler, [0 4*pi], y0, symplecticset (o, "NewtonMatrix", "KEPT"));
%! assert (s5.y, s2.y);
%! assert (s5.stats.nfevals, s2.stats.nfevals);
%! ## adaptive: both reach the tolerance (exact solution: the orbit
%! ## closes after each period)
%! oa = odeset ("RelTol", 1e-8, "AbsTol", 1e-10);
%! [~, ya] = odeSPVI (@kepler, [0 4*pi], y0, oa);
%! [~, yn] = odeSPVI (@kepler, [0 4*pi], y0, symplecticset (oa, "NewtonMatrix", "new"));
%! assert (ya(end, :).', y0, 1e-7);
%! assert (yn(end, :).', y0, 1e-7);

%!test
%! ## far from t = 0 a fixed step is h itself, as near 0 (the ends of the
%! ## steps are t0 + k h rounded), and the Jacobians are extrapolated over
%! ## times counted from the steps' sizes: from t0 = 1e8 the same calls
%! ## and the same solution, to the bit.  When the step was the difference
%! ## of those ends, which varies there by 2.4e-7 h, the calls were 6.5%
%! ## more and the solutions 4.4e-8 apart; with h itself but the times of
%! ## the extrapolation taken from t, 12 calls more in 14226 and 6e-12.
%! e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
%! h = 2*pi/100;  N = 2000;
%! o = symplecticset ("TimeStepSize", h, "TimeStepNumber", N);
%! s0 = odeSPVI (@kepler, [0, N*h], y0, o);
%! s8 = odeSPVI (@kepler, [1e8, 1e8 + N*h], y0, o);
%! assert (s8.x, 1e8 + h * (0:N));
%! assert (s8.y, s0.y);   # to the bit: f does not depend on t
%! assert (s8.stats.nfevals, s0.stats.nfevals);
%! assert (s8.stats.npds, s0.stats.npds);

%!test
%! ## sol reports the pair and its order
%! s = odeSPVI (@pendulum, [0 1], [1; 0], symplecticset ("TimeStepSize", 0.1, "Nodes", 4));
%! assert ([s.Q_DoFs, s.Nodes, s.order], [5, 4, 8]);
%! s = odeSPVI (@pendulum, [0 1], [1; 0], symplecticset ("TimeStepSize", 0.1, "PolynomialDegree", 2));
%! assert ([s.Q_DoFs, s.Nodes, s.order], [3, 3, 4]);
%! s = odeSPVI (@pendulum, [0 1], [1; 0], symplecticset ("TimeStepSize", 0.1));
%! assert ([s.Q_DoFs, s.Nodes, s.order], [4, 3, 6]);

%!test
%! ## adaptive mode advances with the (n+1, m+1) companion: its order
%! s = odeSPVI (@pendulum, [0 1], [1; 0], odeset ("RelTol", 1e-6));
%! assert ([s.Q_DoFs, s.Nodes, s.order], [4, 3, 8]);

## ----------------------------------------------------------------- adaptive
%!test
%! ## Kepler e = 0.6, 10 periods at RelTol = AbsTol = 1e-12: end-point
%! ## error 3.4e-12, in 24880 calls (the help: 6e-14 to 4.5e-12 as the
%! ## round-off falls)
%! e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
%! s = odeSPVI (@kepler, [0 20*pi], y0, odeset ("RelTol", 1e-12, "AbsTol", 1e-12));
%! assert (norm (s.y(:, end) - y0, Inf) < 1e-11);
%! assert (s.stats.nfevals + 2 * s.stats.npds, 24880, 50);
%! ## at this tolerance the round-off of the solves decides: the orbit
%! ## turned by 1e-15 to 1.1e-14 rad ends 6.4e-14 to 4.5e-12 off
%! err = zeros (1, 11);
%! for k = 1:11
%!   R = [cos(k*1e-15), -sin(k*1e-15); sin(k*1e-15), cos(k*1e-15)];
%!   yk = [R * y0(1:2); R * y0(3:4)];
%!   sk = odeSPVI (@kepler, [0 20*pi], yk, odeset ("RelTol", 1e-12, "AbsTol", 1e-12));
%!   err(k) = norm (sk.y(:, end) - yk, Inf);
%! endfor
%! assert (max (err) < 1e-11, "%.3g ", err);
%!test
%! ## Kepler e = 0.6, one period (the exact solution returns to y0): 100x
%! ## tighter RelTol gives at least 30x smaller end-point error, and
%! ## RelTol = 1e-10 reaches 1e-8
%! e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
%! rt = [1e-4 1e-6 1e-8 1e-10];
%! err = zeros (size (rt));  nst = err;
%! for i = 1:numel (rt)
%!   s = odeSPVI (@kepler, [0 2*pi], y0, odeset ("RelTol", rt(i), "AbsTol", rt(i)));
%!   err(i) = norm (s.y(:, end) - y0, Inf);
%!   nst(i) = s.stats.nsteps;
%!   assert (s.x(end), 2*pi);
%! endfor
%! assert (all (err(1:end-1) ./ err(2:end) >= 30), "errors %s", mat2str (err, 3));
%! assert (err(end) <= 1e-8);
%! assert (all (diff (nst) > 0));
%! ## the estimate is honest: the error is not below round-off everywhere
%! assert (err(1) > 1e-6);

%!test
%! ## the adaptive dense output is continuous and ends on each step's value
%! e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
%! s = odeSPVI (@kepler, [0 2*pi], y0, odeset ("RelTol", 1e-6, "AbsTol", 1e-6));
%! tm = s.x(5) * (1 - 1e-13);
%! [t, y] = odeSPVI (@kepler, [0, tm, 2*pi], y0, odeset ("RelTol", 1e-6, "AbsTol", 1e-6));
%! assert (y(2, :), s.y(:, 5).', 1e-9);

%!test
%! ## output times between the steps (Kepler e = 0.6, one period, 401 times)
%! ## against Kepler's equation: the dense output interpolates y' at the
%! ## step's ends and the nodes of the solve the run advances with.  At
%! ## RelTol = AbsTol = 1e-10 its error is 2.6e-10 (the step points' 5e-11;
%! ## the solution's own polynomials gave 6.3e-7, ode45 7.4e-9), for at most
%! ## one more call per step (f at each step's end)
%! e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
%! o = odeset ("RelTol", 1e-10, "AbsTol", 1e-10);
%! ts = linspace (0, 2*pi, 401);
%! [t, y] = odeSPVI (@kepler1, ts, y0, o);
%! assert (max (abs (y - kepler_exact (ts, e))(:)) < 1e-9);
%! global KEPLER_CALLS
%! KEPLER_CALLS = 0;
%! s0 = odeSPVI (@kepler_count, [0 2*pi], y0, o);
%! n0 = KEPLER_CALLS;
%! KEPLER_CALLS = 0;
%! [t, y2] = odeSPVI (@kepler_count, ts, y0, o);
%! assert (y2, y);
%! ncalls = KEPLER_CALLS;
%! clear -global KEPLER_CALLS
%! assert (ncalls > n0 && ncalls <= n0 + s0.stats.nsteps + 1);
%! ## fixed step, (4,3), h = T/200: as accurate between the steps as at them
%! ## (1.3e-7 both; the solution's own polynomials gave 1.5e-6)
%! o = symplecticset ("TimeStepSize", 2*pi/200);
%! [~, y] = odeSPVI (@kepler1, ts, y0, o);
%! s = odeSPVI (@kepler1, [0 2*pi], y0, o);
%! es = max (abs (s.y.' - kepler_exact (s.x, e))(:));
%! assert (max (abs (y - kepler_exact (ts, e))(:)) < 1.5 * es);

%!test
%! ## adaptive: the output times' error is of the order of the tolerance,
%! ## the step points' (advanced with the companion) far smaller (pendulum,
%! ## 1001 output times: measured 1.2e-9 against 6.1e-12)
%! o = odeset ("RelTol", 1e-9, "AbsTol", 1e-12);
%! ts = linspace (0, 10, 1001);
%! [~, y] = odeSPVI (@pendulum, ts, [1; 0.5], o);
%! s = odeSPVI (@pendulum, [0 10], [1; 0.5], o);
%! ed = max (abs (y - pendulum_exact (ts, [1; 0.5]))(:));
%! es = max (abs (s.y.' - pendulum_exact (s.x, [1; 0.5]))(:));
%! assert (ed < 2e-9);
%! assert (es < 1e-11);
%! assert (ed > 1e-10);     # as the help says: not at the step points' level

%!test
%! ## dense output of the other pairs (oscillator, 1001 output times):
%! ## below order 8 the cubic Hermite interpolant through the step's ends,
%! ## as accurate as the step points up to order 4 (measured (3,3), h =
%! ## 0.025: 1.2e-9 and 8.4e-10; the solution's polynomials gave O(h^2)
%! ## in p), O(h^4) above ((4,4): 1.6e-8 at h = 0.05); from order 8 the
%! ## polynomials, O(h^(order/2)) ((5,5): 1.4e-9)
%! f = @(t, y) [y(2); -y(1)];
%! ex = @(t) [cos(t), -sin(t)];
%! tout = linspace (0, 3, 1001)';
%! err = @(n, m, h) max (abs (nthargout (2, @odeSPVI, f, tout, [1; 0], symplecticset ("TimeStepSize", h, "Q_DoFs", n, "Nodes", m)) - ex (tout))(:));
%! for nm = [3 3; 2 3; 6 3; 3 4].'
%!   o = symplecticset ("TimeStepSize", 0.025, "Q_DoFs", nm(1), "Nodes", nm(2));
%!   [ts, ys] = odeSPVI (f, [0 3], [1; 0], o);
%!   assert (err (nm(1), nm(2), 0.025) < 1.6 * max (abs (ys - ex (ts))(:)));
%! endfor
%! e1 = err (4, 4, 0.05);  e2 = err (4, 4, 0.025);
%! assert (e1 < 2e-8);
%! assert (log2 (e1 / e2) > 3.8);
%! assert (err (5, 5, 0.05) < 2e-9);
%! ## adaptive: the steps follow the companion's order, the cubic's error
%! ## dominates between them (measured 2.6e-7, 2.3e-5; (4,3) 6.6e-10)
%! ts = linspace (0, 10, 2001)';
%! for nm = [3 3 5e-7; 4 4 5e-5; 4 3 1e-9].'
%!   o = symplecticset ("RelTol", 1e-9, "AbsTol", 1e-9, "Q_DoFs", nm(1), "Nodes", nm(2));
%!   [t, y] = odeSPVI (f, ts, [0; 1], o);
%!   assert (max (abs (y - [sin(ts), cos(ts)])(:)) < nm(3));
%! endfor

%!test
%! ## adaptive (2,2): the companion (3,3) the run advances with is
%! ## converged as tightly as a fixed step; before, the error grew as the
%! ## tolerance shrank (Kepler e = 0.6, one period: 1.6e-8 at 1e-8, 6.3e-8
%! ## at 1e-10; now 3.8e-10 and 1.4e-13)
%! e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
%! for tol = [1e-8 1e-10]
%!   o = symplecticset ("RelTol", tol, "AbsTol", tol, "Q_DoFs", 2, "Nodes", 2);
%!   s = odeSPVI (@kepler1, [0 2*pi], y0, o);
%!   assert (s.y(:, end), y0, tol / 5);
%! endfor

%!test
%! ## a continued start too far off for Newton: the step is tried once more
%! ## from the Euler start.  Before, on H = (q^2+p^2)^2/4 (a rotation at
%! ## the rate q^2+p^2), (2,5) and (4,8) with h = 0.2 stopped at t = 1.6,
%! ## Nodes = 20 with h = 1 at t = 4.  Many nodes at a long step: the
%! ## continued start is cut to the modes above its noise; before, Nodes =
%! ## 20 stopped at t = 27 and Nodes = 30 at t = 2 (h = 1).  Steps so long
%! ## that Newton fails from the first step's Euler start are reached from
%! ## shorter ones; before, h = 2 with Nodes = 8 and h = 2.5 with Nodes =
%! ## 12 stopped at t = 0 (measured now 3.4e-10 and 4.5e-14).
%! f = @(t, y) [(y(1)^2+y(2)^2)*y(2); -(y(1)^2+y(2)^2)*y(1)];
%! ex = @(t) [cos(1.25*t) + 0.5*sin(1.25*t), -sin(1.25*t) + 0.5*cos(1.25*t)];
%! runs = {symplecticset("TimeStepSize", 0.2, "Q_DoFs", 2, "Nodes", 5), 10, 0.15;
%!         symplecticset("TimeStepSize", 0.2, "Q_DoFs", 4, "Nodes", 8), 10, 2e-7;
%!         symplecticset("TimeStepSize", 1, "Nodes", 20), 40, 1e-12;
%!         symplecticset("TimeStepSize", 1, "Nodes", 30), 40, 1e-12;
%!         symplecticset("TimeStepSize", 2, "Nodes", 8), 40, 1e-9;
%!         symplecticset("TimeStepSize", 2.5, "Nodes", 12), 40, 1e-12};
%! for i = 1:rows (runs)
%!   lastwarn ("");
%!   [t, y] = odeSPVI (f, [0 runs{i, 2}], [1; 0.5], runs{i, 1});
%!   assert (lastwarn (), "");
%!   assert (t(end), runs{i, 2});
%!   assert (y(end, :), ex (t(end)), runs{i, 3});
%! endfor

%!test
%! ## many nodes: the continued prediction of a step (its polynomials
%! ## extrapolated) amplifies round-off like 5.8^Nodes; a wild one is not
%! ## used.  Before, Nodes = 30 gave an error of 715 at t = 20 with h = 1
%! ## (Newton's scale came from the prediction), and adaptive Nodes = 40
%! ## took steps of 1e-6.
%! o = symplecticset ("TimeStepSize", 1, "Nodes", 30);
%! [t, y] = odeSPVI (@pendulum, [0 20], [1; 0.5], o);
%! assert (y(end, :), pendulum_exact (20, [1; 0.5]), 1e-14);   # 6.7e-16
%! s = odeSPVI (@pendulum, [0 2], [1; 0.5], symplecticset ("Nodes", 40, "MaxSteps", 200));
%! assert (s.x(end), 2);
%! assert (s.stats.nsteps < 50);
%! assert (s.y(:, end).', pendulum_exact (2, [1; 0.5]), 1e-11);

## ----------------------------------------------------------------- bad pairs
%!error <degenerate pair> odeSPVI (@pendulum, [0 1], [1; 0], symplecticset ("Q_DoFs", 3, "Nodes", 1))
%!error <degenerate pair> odeSPVI (@pendulum, [0 1], [1; 0], symplecticset ("Q_DoFs", 5, "Nodes", 2))

%!test
%! ## the pairs n - 1 > m are degenerate where d2H/dq2 vanishes: on free
%! ## fall Newton fails at t0 whatever the step, and the warning says why;
%! ## (4,3) is exact there
%! f = @(t, y) [y(2); -1];
%! for pr = [4 2; 5 3; 6 4]'
%!   for h = [0.1 0.01]
%!     o = symplecticset ("TimeStepSize", h, "Q_DoFs", pr(1), "Nodes", pr(2));
%!     lastwarn ("");
%!     evalc ("[t, y] = odeSPVI (f, [0 1], [0; 1], o);");
%!     [msg, id] = lastwarn ();
%!     assert (id, "symplectic:newton-failed");
%!     assert (t, 0);
%!     assert (! isempty (strfind (msg, "Q_DoFs - 1 > Nodes: such pairs are degenerate where d2H/dq2 vanishes")));
%!     assert (isempty (strfind (msg, "try a smaller")));
%!   endfor
%! endfor
%! [t, y] = odeSPVI (f, [0 1], [0; 1], symplecticset ("TimeStepSize", 0.1));
%! assert (y(end, :), [0.5, 0], 1e-14);
%!error <Q_DoFs must be between 2> odeSPVI (@pendulum, [0 1], [1; 0], symplecticset ("Q_DoFs", 1))
%!error <Nodes must be between 1> odeSPVI (@pendulum, [0 1], [1; 0], symplecticset ("Nodes", 0))
%!error <Nodes must be an integer> odeSPVI (@pendulum, [0 1], [1; 0], symplecticset ("Nodes", 2.5))
%!error <P_DoFs must be between 1> odeSPVI (@pendulum, [0 1], [1; 0], symplecticset ("P_DoFs", 41))

## ----------------------------------------------------------------- events
%!test
%! ## q = sin t exceeds 0.99 for 0.28 of every 2 pi (0.999: 0.09): a pair
%! ## of zeros that one long step holds whole.  The Events function is also
%! ## evaluated at Nodes points inside each step and at the extremum of
%! ## the parabola through three of them, so all 6 zeros in [0, 20] are
%! ## found, in order and accurately; the sign changes between step points
%! ## alone miss pairs in every run here.
%! f = @(t, y) [y(2); -y(1)];
%! for th = [0.99 0.999]
%!   ev = @(t, y) deal (y(1) - th, false, 0);
%!   a = asin (th);
%!   tz = sort ([a + 2*pi*(0:3), pi - a + 2*pi*(0:3)]);
%!   tz = tz(tz < 20);
%!   for tol = [1e-3 1e-4 1e-6 1e-8]
%!     o = symplecticset ("RelTol", tol, "AbsTol", tol, "Events", ev);
%!     sol = odeSPVI (f, [0 20], [0; 1], o);
%!     assert (numel (sol.xe), 6);
%!     assert (sol.xe(:).', tz, 10 * tol / (1 - th));
%!     assert (all (diff (sol.xe) > 0));
%!     g = sol.y(1, :) - th;
%!     seen = sum (sign (g(1:end-1)) != sign (g(2:end)));
%!     assert (seen < 6);
%!     [t, y, te] = odeSPVI (f, [0 20], [0; 1], o);
%!     assert (te, sol.xe(:));
%!   endfor
%! endfor
%!test
%! ## the same excursions at 40 phases, q = sin (t + phi): crossing 0.99,
%! ## all 255 zeros are found at RelTol = AbsTol = 1e-3 and 1e-4; crossing
%! ## 0.999, all at 1e-4, but at 1e-3 (steps up to 1.5 against an
%! ## excursion 0.09 of 2 pi long) 217 (13 phases miss some; the help)
%! f = @(t, y) [y(2); -y(1)];
%! for th = [0.99 0.999]
%!   a = asin (th);
%!   for tol = [1e-3 1e-4]
%!     tot = 0;  found = 0;
%!     for ph = (0:39) * 2*pi/40
%!       tz = [2*pi*(-1:4) + a - ph, 2*pi*(-1:4) + pi - a - ph];
%!       tot += sum (tz > 1e-9 & tz < 20);
%!       o = symplecticset ("RelTol", tol, "AbsTol", tol, ...
%!                          "Events", @(t, y) deal (y(1) - th, false, 0));
%!       sol = odeSPVI (f, [0 20], [sin(ph); cos(ph)], o);
%!       found += numel (sol.xe);
%!     endfor
%!     assert (tot, 255);
%!     if (th == 0.999 && tol == 1e-3)
%!       assert (found >= 200 && found <= tot);
%!     else
%!       assert (found, tot);
%!     endif
%!   endfor
%! endfor

%!test
%! ## a terminal event at the first zero of such a pair ends the run there
%! f = @(t, y) [y(2); -y(1)];
%! for tol = [1e-3 1e-4 1e-6]
%!   o = symplecticset ("RelTol", tol, "AbsTol", tol, ...
%!                      "Events", @(t, y) deal (y(1) - 0.99, true, 0));
%!   [t, y, te] = odeSPVI (f, [3 20], [sin(3); cos(3)], o);
%!   assert (te, 2*pi + asin (0.99), 10 * tol);
%!   assert (t(end), te);
%! endfor
%!test
%! ## the cost of Events: the call of fcn at each step's end for the dense
%! ## output, one per step (Kepler, fixed step 2 pi/100, 10 periods: about
%! ## 10 calls per step without Events, 11 with), and Nodes calls of the
%! ## Events function per step besides those that locate the events
%! e = 0.6;
%! y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
%! kep = @(t, y) [y(3:4); -y(1:2) / norm(y(1:2))^3];
%! o = symplecticset ("TimeStepSize", 2*pi/100);
%! s0 = odeSPVI (kep, [0 20*pi], y0, o);
%! s1 = odeSPVI (kep, [0 20*pi], y0, symplecticset (o, "Events", @(t, y) deal (y(2), 0, 0)));
%! assert (s1.stats.nsteps, s0.stats.nsteps);
%! assert (s0.stats.nfevals / s0.stats.nsteps, 10, 0.5);
%! assert (s1.stats.nfevals - s0.stats.nfevals, s0.stats.nsteps, 2);
%! assert (s1.xe(:).', pi * (1:20), 1e-4);   # the phase error of h = T/100
%!test
%! ## the help's example: Kepler e = 0.6, 100 periods at h = 2 pi/100: the
%! ## energy error stays at 7e-8, as large over the last 10 periods as over
%! ## the first 10
%! e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
%! opts = symplecticset ("TimeStepSize", 2*pi/100, "Nodes", 3);
%! [t, y] = odeSPVI (@kepler, [0 200*pi], y0, opts);
%! H = sum (y(:,3:4).^2, 2)/2 - 1 ./ sqrt (sum (y(:,1:2).^2, 2));
%! dH = abs (H + 0.5);
%! first = max (dH(t <= 20*pi));  last = max (dH(t >= 180*pi));
%! assert (max (dH) < 1e-7);
%! assert (last < 1.1 * first);

%!test
%! ## fixed steps converge every solve: (5,4) on Kepler e = 0.6 over 200
%! ## periods, N = 113137 steps, the staged Newton against the full one.
%! ## The exact Gauss map ends within about 1e-11 of y0; a solve that
%! ## stops early drifts the energy and the phase (1e-8 once).
%! e = 0.6; y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))]; N = 113137;
%! f = @(t, y) [y(3,:); y(4,:); -y(1:2,:) ./ (y(1,:).^2 + y(2,:).^2).^1.5];
%! H = @(y) (y(3,:).^2 + y(4,:).^2) / 2 - 1 ./ sqrt (y(1,:).^2 + y(2,:).^2);
%! sys = {"stages", "full", "stages"}; nm = {"auto", "auto", "kept"};
%! for k = 1:3
%!   o = symplecticset ("Q_DoFs", 5, "Nodes", 4, "Vectorized", "on", ...
%!                      "NewtonSystem", sys{k}, "NewtonMatrix", nm{k}, ...
%!                      "TimeStepNumber", N);
%!   s{k} = odeSPVI (f, [0 400*pi], y0, o);
%!   assert (norm (s{k}.y(:,end) - y0) < 1e-10);
%!   assert (max (abs (H (s{k}.y) - H (y0))) < 1e-14);
%! endfor
%! ## the staged Newton takes the full one's corrections (about 1.09 a
%! ## step), or fewer: the stops at round-off move with the BLAS kernel
%! ## by a few in 1e4 (122702 to 122789 staged against 122769 full)
%! assert (s{1}.stats.nnewton <= 1.001 * s{2}.stats.nnewton);
%! assert (s{1}.stats.nfevals <= 1.001 * s{2}.stats.nfevals);

%!test
%! ## NonlinearSolver: the fixed point solves the same equations as Newton
%! ## (results to round-off); on a stiff step it falls back to Newton
%! e = 0.6; y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
%! kep = @(t, y) [y(3:4); -y(1:2) / norm(y(1:2))^3];
%! o = symplecticset ("Q_DoFs", 5, "Nodes", 4, "TimeStepSize", 2*pi/200);
%! sn = odeSPVI (kep, [0 4*pi], y0, o);
%! for nls = {"fixedpoint", "auto"}
%!   sf = odeSPVI (kep, [0 4*pi], y0, symplecticset (o, "NonlinearSolver", nls{1}));
%!   assert (sf.y, sn.y, 1e-12);
%! endfor
%! ## adaptive steps too
%! oa = symplecticset ("RelTol", 1e-8, "AbsTol", 1e-8);
%! sa = odeSPVI (kep, [0 2*pi], y0, symplecticset (oa, "NonlinearSolver", "fixedpoint"));
%! assert (sa.y(:,end), y0, 1e-6);
%! ## omega h = 4: the fixed point diverges; Newton solves those steps
%! w = 40; f = @(t, y) [y(2); -w^2 * y(1)];
%! os = symplecticset ("TimeStepSize", 0.1, "Nodes", 3);
%! s0 = odeSPVI (f, [0 5], [1; 0], os);
%! for nls = {"fixedpoint", "auto"}
%!   s1 = odeSPVI (f, [0 5], [1; 0], symplecticset (os, "NonlinearSolver", nls{1}));
%!   assert (s1.y, s0.y, 1e-12);
%! endfor
%!error <odeSPVI: NonlinearSolver "fixedpoint" needs Q_DoFs = Nodes \+ 1>
%! odeSPVI (@(t, y) [y(2); -y(1)], [0 1], [1; 0], symplecticset ("Q_DoFs", 3, "Nodes", 3, "NonlinearSolver", "fixedpoint", "TimeStepSize", 0.1));
%!error <odeSPVI: NonlinearSolver "auto" iterates by stages>
%! odeSPVI (@(t, y) [y(2); -y(1)], [0 1], [1; 0], symplecticset ("NewtonSystem", "full", "NonlinearSolver", "auto", "TimeStepSize", 0.1));
%!error <NonlinearSolver>
%! odeSPVI (@(t, y) [y(2); -y(1)], [0 1], [1; 0], symplecticset ("NonlinearSolver", "picard", "TimeStepSize", 0.1));
