## Copyright (C) 2026 The symplectic developers
##
## This program is free software: you can redistribute it and/or modify it
## under the terms of the GNU General Public License as published by the Free
## Software Foundation, either version 3 of the License, or (at your option)
## any later version.  See the file COPYING.

## -*- texinfo -*-
## @deftypefn  {} {[@var{t}, @var{y}] =} odeSV (@var{fcn}, @var{tspan}, @var{y0})
## @deftypefnx {} {[@var{t}, @var{y}] =} odeSV (@var{fcn}, @var{tspan}, @var{y0}, @var{opts})
## @deftypefnx {} {[@var{t}, @var{y}] =} odeSV (@var{fcn}, @var{tspan}, @var{y0}, @var{opts}, @var{par1}, @dots{})
## @deftypefnx {} {[@var{t}, @var{y}, @var{te}, @var{ye}, @var{ie}] =} odeSV (@dots{})
## @deftypefnx {} {@var{sol} =} odeSV (@dots{})
## @deftypefnx {} {} odeSV (@dots{})
## Solve Hamilton's equations with the St@"ormer--Verlet method (order 2).
##
## @var{fcn} returns Hamilton's equations for y = [q; p], q, p in R^d:
## @code{dy = fcn (t, y) = [dH/dp; -dH/dq + F(t, q, p)]}, F an optional
## forcing term.  One step:
##
## @example
## @group
## p(k+1/2) = p(k) + h/2 * fp (t(k), q(k), p(k+1/2))                  (implicit)
## q(k+1)   = q(k) + h/2 * (fq (t(k), q(k), p(k+1/2))
##                         + fq (t(k+1), q(k+1), p(k+1/2)))          (implicit)
## p(k+1)   = p(k+1/2) + h/2 * fp (t(k+1), q(k+1), p(k+1/2))          (explicit)
## @end group
## @end example
##
## @noindent
## with fq = dH/dp and fp = -dH/dq + F.  The method is symplectic,
## symmetric (time-reversible) and variational: with a fixed step its
## energy error stays bounded (of size h^2) over very long runs, and the
## momenta of the symmetries of H are conserved to round-off.  With
## @code{Separable} @qcode{"on"} (H = T(p) + V(q)) it is the explicit
## leapfrog: two evaluations of @var{fcn} per step, at the same p with two
## q; a dH/dp that differs between them (H not separable) gets the
## warning @code{symplectic:not-separable}.
##
## The implicit equations for p(k+1/2) and q(k+1) are solved by Newton's
## method started, as in @code{odeSE}, from their values at the last steps
## (the errors of the explicit starts p(k) + (h/2) f_p(t(k), q(k),
## p(k-1/2)), exact for a separable H, and q(k) + h f_q(t(k), q(k),
## p(k+1/2)), extrapolated): on the non-separable H of
## @file{tests/test_se_sv.m} at h = 0.01, 3.96 evaluations of @var{fcn}
## per step (8.0 from the explicit starts alone).
##
## Arguments, outputs and options are those of @code{odeSE} (see
## @code{help odeSE}): @code{TimeStepSize}/@code{TimeStepNumber} for fixed
## steps, @code{RelTol}/@code{AbsTol} for adaptive ones, the four sources
## of Newton's matrix (@code{Jacobian}, @code{HamiltonianHessFcn}, a second
## output of @var{fcn}, finite differences), @code{Separable},
## @code{Events}, @code{OutputFcn}, @code{OutputSel}, @code{Refine},
## @code{Stats}, @code{NewtonTol}, @code{MaxNewtonIterations}.
##
## In adaptive mode the local error estimate is the difference to the
## trapezoidal rule built from @var{fcn} at both ends of the step plus the
## trapezoidal rule's own local error,
## y(k+1) - y(k) - h/2 (f(k) + f(k+1)) + (h^3/12) d^3y/dt^3, with the
## third derivative from the values of @var{fcn} at the last three step
## points (at a fresh start: at the step's ends and its midpoint, one more
## evaluation).  It matches the local error in every component to leading
## order; the first part alone would be zero in p for separable H, where
## Verlet's p-update is the trapezoidal rule.  It costs one evaluation of
## @var{fcn} per step.  Adaptive steps do not keep the energy of fast
## oscillations, which they can pump by orders of magnitude (see RelTol
## in @code{help odeSE}): use a fixed step for such systems.  Dense
## output (for output times, @code{Refine} and events) is the cubic
## Hermite interpolant through the step points.
##
## Example: Kepler's problem over 100 orbits with a fixed step; the energy
## error stays bounded and the angular momentum is conserved.
##
## @example
## @group
## kepler = @@(t, y) [y(3:4); -y(1:2) / norm(y(1:2))^3];
## e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
## opts = symplecticset ("TimeStepSize", 2*pi/1000, "Separable", "on");
## [t, y] = odeSV (kepler, [0 200*pi], y0, opts);
## L = y(:,1).*y(:,4) - y(:,2).*y(:,3);     # constant to round-off
## @end group
## @end example
## @seealso{odeSE, odeSPVI, symplecticset, ode45, odeset}
## @end deftypefn

function varargout = odeSV (varargin)
  error ("odeSV: the compiled function odeSV.mex is missing; build the package with 'make'");
endfunction

%!demo
%! ## Phase portrait of the double well H = p^2/2 + q^4/4 - q^2/2 with the
%! ## explicit leapfrog (Separable): orbits in each well and around both.
%! duffing = @(t, y) [y(2); y(1) - y(1)^3];
%! opts = symplecticset ("TimeStepSize", 0.05, "Separable", "on");
%! figure ();
%! hold on;
%! for q0 = [0.2, 0.6, 1.0, 1.3, 1.45, 1.6, 1.9]
%!   for s = [-1, 1]
%!     [t, y] = odeSV (duffing, [0 15], [s*q0; 0], opts);
%!     plot (y(:,1), y(:,2), "b");
%!   endfor
%! endfor
%! hold off;
%! xlabel ("q");  ylabel ("p");
%! title ("odeSV: phase portrait of the double well, h = 0.05");

%!demo
%! ## Energy error over 20 periods of Kepler's problem (eccentricity 0.3):
%! ## Stormer-Verlet with a fixed step keeps it bounded (no drift); that of
%! ## ode45 grows with time.
%! kepler = @(t, y) [y(3:4); -y(1:2) / norm(y(1:2))^3];
%! H = @(y) sum (y(:,3:4).^2, 2)/2 - 1 ./ sqrt (sum (y(:,1:2).^2, 2));
%! e = 0.3;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];  tf = 40*pi;
%! opts = symplecticset ("TimeStepSize", 2*pi/200, "Separable", "on");
%! [t1, y1] = odeSV (kepler, [0 tf], y0, opts);
%! [t2, y2] = ode45 (kepler, [0 tf], y0, odeset ("RelTol", 1e-4, "AbsTol", 1e-7));
%! figure ();
%! semilogy (t1 / (2*pi), max (abs (H (y1) + 0.5), eps), "b",
%!           t2 / (2*pi), max (abs (H (y2) + 0.5), eps), "r");
%! xlabel ("periods");  ylabel ("|H(t) - H(0)|");
%! legend ("odeSV, h = 2\\pi/200", "ode45, RelTol = 1e-4", "location", "southeast");
%! title ("Kepler, e = 0.3: energy error");

## Representative tests (the full ode45-contract tests are in
## tests/test_ode45_contract.m).
%!test
%! ## output times, Refine, and the sol struct
%! f = @(t, y) [y(2); -y(1)];
%! o = symplecticset ("TimeStepSize", 0.1);
%! [t, y] = odeSV (f, [0 0.25 1 2], [1; 0], o);
%! assert (t, [0; 0.25; 1; 2]);
%! assert (y, [cos(t), -sin(t)], 2e-3);
%! [t, y] = odeSV (f, [0 1], [1; 0], symplecticset (o, "Refine", 2));
%! assert (t, (0:20)' * 0.05, 1e-14);
%! sol = odeSV (f, [0 1], [1; 0], symplecticset (o, "Refine", 2));
%! assert (sol.x, (0:10) * 0.1, 1e-14);
%! assert (sol.solver, "odeSV");
%! assert (sol.stats.nsteps, 10);

%!test
%! ## events with a direction; extra parameters reach fcn and Events
%! f = @(t, y, w) [y(2); -w^2 * y(1)];
%! ev = @(t, y, w) deal (y(2), 0, 1);     # p = -2 sin(2t) rises through 0
%! o = symplecticset ("TimeStepSize", 0.001, "Events", ev);
%! [t, y, te, ye, ie] = odeSV (f, [0 5], [1; 0], o, 2);
%! assert (te, [pi/2; 3*pi/2], 1e-5);
%! assert (ie, [1; 1]);
%! assert (t(end), 5);
