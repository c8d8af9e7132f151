## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## Tests of TangentMap (odeSE, odeSV with explicit fixed steps): sol.phi
## against Richardson-extrapolated central differences of the package's
## own map (the same fixed steps from perturbed y0), its symplecticity
## after 1e4 steps, the harmonic oscillator's Phi = A^k with the one-step
## matrix A written out by hand, deviation vectors against Phi * V0, and
## the errors of what is not supported.  The Hessian comes from FCN's
## second output, HamiltonianHessFcn, or (neither) central differences.

%!function D = mapdiff (solver, f, tspan, y0, o)
%!  ## d y_N / d y_0 of the map the solver runs with o (no TangentMap):
%!  ## central differences at dl and 2 dl, extrapolated (error O(dl^4))
%!  n = numel (y0);  D = zeros (n);
%!  for j = 1:n
%!    dl = 1e-5 * max (1, abs (y0(j)));
%!    e = zeros (n, 1);  e(j) = dl;
%!    d1 = (solver (f, tspan, y0 + e, o).y(:,end) ...
%!          - solver (f, tspan, y0 - e, o).y(:,end)) / (2*dl);
%!    d2 = (solver (f, tspan, y0 + 2*e, o).y(:,end) ...
%!          - solver (f, tspan, y0 - 2*e, o).y(:,end)) / (4*dl);
%!    D(:,j) = (4*d1 - d2) / 3;
%!  endfor
%!endfunction

%!function r = relerr (a, b)
%!  r = norm (a - b, "fro") / norm (b, "fro");
%!endfunction

%!function [f, hess] = kepler1 (t, y)
%!  ## Kepler with one output only (hess: the Hessian of H, separately)
%!  q = y(1:2);  r = norm (q);
%!  f = [y(3:4); -q / r^3];
%!endfunction

%!function f = kepler_v (t, y)
%!  ## Kepler for the columns of y (Vectorized)
%!  r3 = sqrt (y(1,:).^2 + y(2,:).^2).^3;
%!  f = [y(3:4,:); -y(1:2,:) ./ r3];
%!endfunction

%!function H = kepler_hess (t, y)
%!  q = y(1:2);  r2 = q.' * q;
%!  H = [(eye (2) - 3 * (q * q.') / r2) / r2^1.5, zeros(2); zeros(2), eye(2)];
%!endfunction

%!function J = symj (d)
%!  J = [zeros(d), eye(d); -eye(d), zeros(d)];
%!endfunction

## ------------------------------------------------------------ Kepler
%!shared y0, h, N, o, tspan
%! e = 0.5;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
%! h = 2*pi/200;  N = 200;  tspan = [0, N*h];
%! o = symplecticset ("TimeStepSize", h, "TimeStepNumber", N, ...
%!                    "Separable", "on");

%!test
%! ## odeSV, the Hessian as FCN's second output: one period, |Phi| ~ 360
%! sol = odeSV (@symplectic_kepler, tspan, y0,
%!              symplecticset (o, "TangentMap", "on"));
%! assert (size (sol.phi), [4, 4, numel(sol.x)]);
%! assert (sol.phi(:,:,1), eye (4));
%! ## the steps take f from the calls that give the Hessian too: the
%! ## same solution, and no more calls of FCN than without TangentMap
%! s0 = odeSV (@symplectic_kepler, tspan, y0, o);
%! assert (sol.y, s0.y, 4 * eps);
%! assert (sol.stats.nfevals + sol.stats.npds <= s0.stats.nfevals + 2);
%! D = mapdiff (@odeSV, @symplectic_kepler, tspan, y0, o);
%! assert (norm (D) > 100);
%! assert (relerr (sol.phi(:,:,end), D) < 1e-7);
%! ## and at a step point halfway (the map of the first N/2 steps)
%! oh = symplecticset (o, "TimeStepNumber", N/2);
%! Dh = mapdiff (@odeSV, @symplectic_kepler, tspan / 2, y0, oh);
%! assert (relerr (sol.phi(:,:,N/2+1), Dh) < 1e-7);

%!test
%! ## odeSE: HamiltonianHessFcn, and central differences of a one-output FCN
%! D = mapdiff (@odeSE, @kepler1, tspan, y0, o);
%! s1 = odeSE (@kepler1, tspan, y0, symplecticset (o, "TangentMap", "on",
%!             "HamiltonianHessFcn", @kepler_hess));
%! s2 = odeSE (@kepler1, tspan, y0, symplecticset (o, "TangentMap", "on"));
%! assert (relerr (s1.phi(:,:,end), D) < 1e-7);
%! assert (relerr (s2.phi(:,:,end), D) < 1e-7);
%! ## the differences cost calls of FCN: 2d for each block
%! assert (s2.stats.nfdevals > 4 * N);
%! assert (s1.stats.nfdevals < 10);
%! assert (s1.stats.jacobian_source, "HamiltonianHessFcn");
%! assert (s2.stats.jacobian_source, "finite differences of FCN");
%! ## Vectorized: the differences' states in batches, the same Phi
%! s3 = odeSE (@kepler_v, tspan, y0, symplecticset (o, "TangentMap", "on",
%!             "Vectorized", "on"));
%! s4 = odeSE (@kepler_v, tspan, y0, symplecticset (o, "TangentMap", "on"));
%! ## (a last bit of f moves a difference by eps/cbrt(eps) relative)
%! assert (s3.phi, s4.phi, 1e-9 * norm (s4.phi(:,:,end), "fro"));
%! assert (s3.stats.nfevals < s4.stats.nfevals / 2);
%! assert (relerr (s3.phi(:,:,end), D) < 1e-7);

%!test
%! ## odeSV's Methods: compositions, splittings, the position form
%! for m = {"yoshida4", "ruth3", "blanesmoan6", "mclachlan4"}
%!   om = symplecticset (o, "Method", m{1});
%!   sol = odeSV (@symplectic_kepler, tspan, y0,
%!                symplecticset (om, "TangentMap", "on"));
%!   D = mapdiff (@odeSV, @symplectic_kepler, tspan, y0, om);
%!   assert (relerr (sol.phi(:,:,end), D) < 1e-7, m{1});
%! endfor
%! op = symplecticset (o, "VerletForm", "position");
%! sol = odeSV (@kepler1, tspan, y0, symplecticset (op, "TangentMap", "on"));
%! D = mapdiff (@odeSV, @kepler1, tspan, y0, op);
%! assert (relerr (sol.phi(:,:,end), D) < 1e-7);

## ------------------------------------------------------------ pendulum
%!test
%! ## SecondOrder (the drift's Jacobian is the identity), both solvers,
%! ## the Hessian by differences and from HamiltonianHessFcn
%! a = @(t, q) -sin (q);  y0 = [1; 0.5];  h = 0.05;  N = 400;
%! o = symplecticset ("TimeStepSize", h, "TimeStepNumber", N,
%!                    "SecondOrder", "on");
%! hs = @(t, y) [cos(y(1)), 0; 0, 1];
%! for s = {@odeSV, @odeSE}
%!   D = mapdiff (s{1}, a, [0, N*h], y0, o);
%!   s1 = s{1} (a, [0, N*h], y0, symplecticset (o, "TangentMap", "on"));
%!   s2 = s{1} (a, [0, N*h], y0, symplecticset (o, "TangentMap", "on",
%!                                              "HamiltonianHessFcn", hs));
%!   assert (relerr (s1.phi(:,:,end), D) < 1e-7);
%!   assert (relerr (s2.phi(:,:,end), D) < 1e-7);
%! endfor
%! ## a Separable pendulum with suzuki4 in the position form
%! f = @(t, y) [y(2); -sin(y(1))];
%! om = symplecticset ("TimeStepSize", h, "TimeStepNumber", N,
%!                     "Separable", "on", "Method", "suzuki4",
%!                     "VerletForm", "position");
%! D = mapdiff (@odeSV, f, [0, N*h], y0, om);
%! sol = odeSV (f, [0, N*h], y0, symplecticset (om, "TangentMap", "on"));
%! assert (relerr (sol.phi(:,:,end), D) < 1e-7);

## ------------------------------------------------------------ symplecticity
%!test
%! ## Phi' J Phi = J after 1e4 steps of Kepler (e = 0.1, 100 steps a
%! ## period), relative to |Phi|^2 (Phi grows linearly, to ~5e3)
%! e = 0.1;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];  N = 1e4;
%! acc = @(t, q) -q / norm (q)^3;
%! o = symplecticset ("TimeStepSize", 2*pi/100, "TimeStepNumber", N,
%!                    "SecondOrder", "on", "TangentMap", "on",
%!                    "HamiltonianHessFcn", @kepler_hess);
%! J = symj (2);
%! runs = {{@odeSE, "verlet"}, {@odeSV, "verlet"}, {@odeSV, "yoshida4"}, ...
%!         {@odeSV, "ruth3"}};
%! for k = 1:numel (runs)
%!   oo = o;
%!   if (isequal (runs{k}{1}, @odeSV))
%!     oo = symplecticset (o, "Method", runs{k}{2});
%!   endif
%!   sol = runs{k}{1} (acc, [0, N*2*pi/100], y0, oo);
%!   P = sol.phi(:,:,end);
%!   assert (norm (P) > 1e3);
%!   assert (norm (P.'*J*P - J, "fro") / norm (P, "fro")^2 < 1e-12);
%! endfor

## ------------------------------------------------------------ oscillator
%!test
%! ## H = (q^2 + p^2)/2: the step map is linear, Phi_k = A^k exactly
%! f = @(t, y) [y(2); -y(1)];  h = 0.1;  N = 1e4;
%! o = symplecticset ("TimeStepSize", h, "TimeStepNumber", N,
%!                    "Separable", "on", "TangentMap", "on",
%!                    "HamiltonianHessFcn", @(t, y) eye (2));
%! ## symplectic Euler: p1 = p - h q, q1 = q + h p1
%! Ase = [1 - h^2, h; -h, 1];
%! ## Verlet: p' = p - h/2 q, q1 = q + h p', p1 = p' - h/2 q1
%! Asv = [1 - h^2/2, h; -h + h^3/4, 1 - h^2/2];
%! ## position form: q' = q + h/2 p, p1 = p - h q', q1 = q' + h/2 p1
%! Apo = [1 - h^2/2, h - h^3/4; -h, 1 - h^2/2];
%! s = odeSE (f, [0, N*h], [1; 0], o);
%! for k = [1, 2, 100, N]
%!   assert (s.phi(:,:,k+1), Ase^k, 1e-12);
%! endfor
%! s = odeSV (f, [0, N*h], [1; 0], o);
%! assert (s.phi(:,:,end), Asv^N, 1e-12);
%! assert (s.phi(:,:,2), Asv, 4 * eps);
%! s = odeSV (f, [0, N*h], [1; 0], symplecticset (o, "VerletForm", "position"));
%! assert (s.phi(:,:,end), Apo^N, 1e-12);
%! assert (s.phi(:,:,2), Apo, 4 * eps);
%! ## not A (a wrong kick or drift would show here)
%! assert (norm (Asv - Apo) > h^3 / 8);
%! ## SecondOrder, the Hessian by differences: exact but for their round-off
%! s = odeSV (@(t, q) -q, [0, N*h], [1; 0],
%!            symplecticset (o, "SecondOrder", "on", "HamiltonianHessFcn", []));
%! assert (s.phi(:,:,end), Asv^N, 1e-7);
%! assert (s.phi(:,:,2), Asv, 1e-10);

%!test
%! ## yoshida4 on the oscillator: A the product of its three Verlet steps
%! f = @(t, y) [y(2); -y(1)];  h = 0.3;  N = 500;
%! g = [1, -2^(1/3), 1] / (2 - 2^(1/3));
%! V = @(h) [1 - h^2/2, h; -h + h^3/4, 1 - h^2/2];
%! A = V (g(3)*h) * V (g(2)*h) * V (g(1)*h);
%! s = odeSV (f, [0, N*h], [0.3; -1], symplecticset ("TimeStepSize", h,
%!            "TimeStepNumber", N, "Separable", "on", "Method", "yoshida4",
%!            "TangentMap", "on", "HamiltonianHessFcn", @(t, y) eye (2)));
%! assert (s.phi(:,:,end), A^N, 1e-12);

## ------------------------------------------------------------ deviation vectors
%!test
%! ## k deviation vectors: Phi * V0 at every step point
%! f = @(t, y) [y(3:4); -y(1) - 2*y(1)*y(2); -y(2) - y(1)^2 + y(2)^2];
%! y0 = [0; 0.1; 0.45; 0.1];  V0 = [1 0; 0 1; 0.5 -1; 2 0.25];
%! o = symplecticset ("TimeStepSize", 0.05, "TimeStepNumber", 400,
%!                    "Separable", "on");
%! s1 = odeSV (f, [0 20], y0, symplecticset (o, "TangentMap", "on"));
%! s2 = odeSV (f, [0 20], y0, symplecticset (o, "TangentMap", V0));
%! assert (size (s2.phi), [4, 2, numel(s2.x)]);
%! assert (s2.y, s1.y);
%! for k = [1, 2, 200, 401]
%!   P = s1.phi(:,:,k) * V0;
%!   assert (s2.phi(:,:,k), P, 1e-13 * norm (P, "fro"));
%! endfor
%! ## one vector, on odeSE
%! s3 = odeSE (f, [0 20], y0, symplecticset (o, "TangentMap", V0(:,2)));
%! s4 = odeSE (f, [0 20], y0, symplecticset (o, "TangentMap", "on"));
%! assert (size (s3.phi), [4, 1, 401]);
%! assert (s3.phi(:,1,end), s4.phi(:,:,end) * V0(:,2),
%!         1e-13 * norm (s3.phi(:,1,end)));

%!test
%! ## "off" and a run without it: no phi, the same solution
%! f = @(t, y) [y(2); -y(1)];
%! o = symplecticset ("TimeStepSize", 0.1, "TimeStepNumber", 10,
%!                    "Separable", "on");
%! s1 = odeSV (f, [0 1], [1; 0], symplecticset (o, "TangentMap", "off"));
%! s2 = odeSV (f, [0 1], [1; 0], symplecticset (o, "TangentMap", "on"));
%! assert (! isfield (s1, "phi"));
%! assert (s2.y, s1.y);

## ------------------------------------------------------------ Lyapunov
%!test
%! ## the oscillator: |Phi v0| stays bounded, the exponent goes to 0 as 1/t
%! f = @(t, y) [y(2); -y(1)];  h = 0.1;  N = 1e4;
%! sol = odeSV (f, [0, N*h], [1; 0], symplecticset ("TimeStepSize", h,
%!              "TimeStepNumber", N, "Separable", "on", "TangentMap", [0; 1],
%!              "Indicators", "lyapunov"));
%! assert (size (sol.lyapunov), size (sol.x));
%! assert (isnan (sol.lyapunov(1)));
%! assert (abs (sol.lyapunov(end)) < 2e-3);
%! assert (abs (sol.lyapunov(1001)) < 2e-2);
%! ## sol.phi holds the renormalised vector
%! assert (norm (sol.phi(:,1,end)), 1, 1e-14);
%! ## the log growth against |Phi v0| of a run without renormalisation
%! s2 = odeSV (f, [0, N*h], [1; 0], symplecticset ("TimeStepSize", h,
%!             "TimeStepNumber", N, "Separable", "on", "TangentMap", [0; 1]));
%! for k = [2, 17, 1001, N+1]
%!   lg = log (norm (s2.phi(:,1,k))) / sol.x(k);
%!   assert (sol.lyapunov(k), lg, 1e-12 + 1e-12 * abs (lg));
%!   assert (sol.phi(:,1,k), s2.phi(:,1,k) / norm (s2.phi(:,1,k)), 1e-13);
%! endfor

%!test
%! ## Henon-Heiles at E = 1/6, a chaotic orbit: the exponent positive, and
%! ## equal to the estimate from central differences of the package's own
%! ## map along the same orbit (pairs of states +-dl w about sol.y every Tr,
%! ## w renormalised there: an ensemble run of two members)
%! a = @(t, q) [-q(1) - 2*q(1)*q(2); -q(2) - q(1)^2 + q(2)^2];
%! av = @(t, q) [-q(1,:) - 2*q(1,:).*q(2,:); -q(2,:) - q(1,:).^2 + q(2,:).^2];
%! hs = @(t, y) [1 + 2*y(2), 2*y(1), 0, 0; 2*y(1), 1 - 2*y(2), 0, 0;
%!               0, 0, 1, 0; 0, 0, 0, 1];
%! E = 1/6;  yv = -0.1;  y0 = [0; yv; sqrt(2*(E - yv^2/2 + yv^3/3)); 0];
%! h = 0.05;  T = 500;  N = T/h;  v0 = [1; 0; 0; 0];
%! o = symplecticset ("TimeStepSize", h, "TimeStepNumber", N,
%!                    "SecondOrder", "on", "TangentMap", v0,
%!                    "Indicators", {"lyapunov"}, "HamiltonianHessFcn", hs);
%! sol = odeSV (a, [0, T], y0, o);
%! Tr = 2;  m = round (Tr/h);  dl = 1e-6;
%! oe = symplecticset ("TimeStepSize", h, "TimeStepNumber", m,
%!                     "SecondOrder", "on", "Ensemble", "on",
%!                     "Vectorized", "on");
%! S = 0;  w = v0;
%! for k = 1:round (T/Tr)
%!   c = sol.y(:,(k-1)*m+1);
%!   s = odeSV (av, [0, Tr], [c + dl*w, c - dl*w], oe);
%!   w = (s(1).y(:,end) - s(2).y(:,end)) / (2*dl);
%!   S += log (norm (w));
%!   w /= norm (w);
%! endfor
%! assert (sol.lyapunov(end) > 0.05);
%! assert (sol.lyapunov(end), S / T, 1e-6 * S / T);
%! assert (sol.phi(:,1,end), w, 1e-6);
%! ## the Hessian by differences gives the same
%! s2 = odeSV (a, [0, T], y0, symplecticset (o, "HamiltonianHessFcn", []));
%! assert (s2.lyapunov(end), sol.lyapunov(end), 1e-6 * sol.lyapunov(end));

## ------------------------------------------------------------ errors
%!shared f, of
%! f = @(t, y) [y(2); -y(1)];
%! of = symplecticset ("TimeStepSize", 0.1, "Separable", "on",
%!                     "TangentMap", "on");
%!error <odeSPVI: TangentMap is not supported by this solver yet> odeSPVI (f, [0 1], [1; 0], of);
%!error <odeSV: TangentMap needs explicit steps: set Separable> odeSV (f, [0 1], [1; 0], symplecticset (of, "Separable", "off"));
%!error <odeSE: TangentMap needs explicit steps> odeSE (f, [0 1], [1; 0], symplecticset ("TangentMap", "on", "TimeStepSize", 0.1));
%!error <odeSV: TangentMap needs fixed steps: give TimeStepSize> odeSV (f, [0 1], [1; 0], symplecticset ("Separable", "on", "TangentMap", "on"));
%!error <odeSV: TangentMap needs fixed steps> odeSV (f, [0 1], [1; 0], symplecticset ("Separable", "on", "TangentMap", "on", "StepControl", "reversible"));
%!error <odeSV: TangentMap is not supported with Ensemble> odeSV (f, [0 1], [1 2; 0 0], symplecticset (of, "Ensemble", "on"));
%!error <odeSE: TangentMap is not supported with Events> odeSE (f, [0 1], [1; 0], symplecticset (of, "Events", @(t, y) deal (y(1), 0, 0)));
%!error <odeSV: TangentMap is not supported with Dense> odeSV (f, [0 1], [1; 0], symplecticset (of, "Dense", "on"));
%!error <odeSV: TangentMap comes back in sol.phi only: call with one output> [t, y] = odeSV (f, [0 1], [1; 0], of);
%!error <odeSV: TangentMap is not supported with a sol as Y0> s = odeSV (f, [1 2], odeSV (f, [0 1], [1; 0], of), of);
%!error <odeSV: TangentMap must be "on" or "off", got "maybe"> odeSV (f, [0 1], [1; 0], symplecticset (of, "TangentMap", "maybe"));
%!error <odeSV: TangentMap must be "on", "off" or a 2-by-k real matrix of initial deviation vectors, got 3x1 double> odeSV (f, [0 1], [1; 0], symplecticset (of, "TangentMap", [1; 2; 3]));
%!error <odeSE: TangentMap must be "on", "off" or a 2-by-k real matrix .* got 2x1 complex double> odeSE (f, [0 1], [1; 0], symplecticset (of, "TangentMap", [1; 1i]));
%!error <odeSV: TangentMap's deviation vectors must be finite, got NaN in element 2> odeSV (f, [0 1], [1; 0], symplecticset (of, "TangentMap", [1; NaN]));
%!error <odeSV: TangentMap needs explicit steps> odeSV (f, [0 1], [1; 0], symplecticset (of, "Separable", "off", "Method", "yoshida4"));
%!error id=Octave:invalid-input-arg odeSV (f, [0 1], [1; 0], symplecticset (of, "TangentMap", {1}));
%!error <odeSV: Indicators "lyapunov" needs TangentMap, a 2-by-1 deviation vector to follow> s = odeSV (f, [0 1], [1; 0], symplecticset ("TimeStepSize", 0.1, "Separable", "on", "Indicators", "lyapunov"));
%!error <odeSV: Indicators "lyapunov" needs TangentMap, .*TangentMap is off> s = odeSV (f, [0 1], [1; 0], symplecticset (of, "TangentMap", "off", "Indicators", "lyapunov"));
%!error <odeSE: Indicators "lyapunov" follows one deviation vector: give TangentMap as a 2-by-1 vector, got 2-by-2> s = odeSE (f, [0 1], [1; 0], symplecticset (of, "Indicators", "lyapunov"));
%!error <odeSV: Indicators must be "lyapunov" or "none", got "megno"> s = odeSV (f, [0 1], [1; 0], symplecticset (of, "TangentMap", [1; 0], "Indicators", "megno"));
%!error <odeSV: Indicators must be "lyapunov" or a cell of such names, got an element 1x1 double> s = odeSV (f, [0 1], [1; 0], symplecticset (of, "TangentMap", [1; 0], "Indicators", {"lyapunov", 1}));
%!error <odeSPVI: Indicators "lyapunov" needs TangentMap> s = odeSPVI (f, [0 1], [1; 0], symplecticset ("Indicators", "lyapunov"));
%!test
%! ## "none" and {} ask for nothing
%! s = odeSV (f, [0 1], [1; 0], symplecticset (of, "TangentMap", [1; 0], "Indicators", "none"));
%! assert (! isfield (s, "lyapunov"));
%! s = odeSV (f, [0 1], [1; 0], symplecticset (of, "Indicators", {}));
%! assert (! isfield (s, "lyapunov"));
