## Copyright (C) 2026 The symplectic developers
##
## This program is free software: you can redistribute it and/or modify it
## under the terms of the GNU General Public License as published by the Free
## Software Foundation, either version 3 of the License, or (at your option)
## any later version.  See the file COPYING.

## -*- texinfo -*-
## @deftypefn  {} {[@var{t}, @var{y}] =} odeSE (@var{fcn}, @var{tspan}, @var{y0})
## @deftypefnx {} {[@var{t}, @var{y}] =} odeSE (@var{fcn}, @var{tspan}, @var{y0}, @var{opts})
## @deftypefnx {} {[@var{t}, @var{y}] =} odeSE (@var{fcn}, @var{tspan}, @var{y0}, @var{opts}, @var{par1}, @dots{})
## @deftypefnx {} {[@var{t}, @var{y}, @var{te}, @var{ye}, @var{ie}] =} odeSE (@dots{})
## @deftypefnx {} {@var{sol} =} odeSE (@dots{})
## @deftypefnx {} {} odeSE (@dots{})
## Solve Hamilton's equations with the symplectic Euler method (order 1).
##
## For a Hamiltonian H(q, p) with q, p in R^d and an optional forcing term
## F, @var{fcn} returns Hamilton's equations for y = [q; p]:
##
## @example
## dy = fcn (t, y) = [dH/dp; -dH/dq + F(t, q, p)]
## @end example
##
## @noindent
## a column of length 2d.  The method is the variant with p implicit and q
## explicit:
##
## @example
## @group
## p(k+1) = p(k) + h * (-dH/dq + F) (t(k), q(k), p(k+1))
## q(k+1) = q(k) + h * dH/dp (t(k), q(k), p(k+1))
## @end group
## @end example
##
## @noindent
## It is symplectic and variational: with a fixed step its energy error
## stays bounded over very long runs and it conserves the momenta of the
## symmetries of H (angular momentum for a central force) to round-off.  A
## forcing term gives the discrete Lagrange--d'Alembert (forced variational)
## integrator.  The implicit equation for p(k+1) is solved by Newton's
## method to near machine precision.
##
## @strong{Arguments} are those of @code{ode45}: @var{tspan} = [t0, tf]
## returns a row at every step; with more than two (strictly monotonic)
## elements, rows exactly at those times, taken from the dense output
## without shortening any step.  tf < t0 integrates backwards.  @var{y0} =
## [q0; p0] is a real vector of even length (row or column).  Extra
## arguments @var{par1}, @dots{} are passed to @var{fcn} (and to the
## Jacobian, Hessian, Events and OutputFcn functions) after t and y.
## @var{t} is a column; @var{y} has one row per time.  With one output,
## @var{sol} is a struct with the fields of @code{ode45}: @code{x} (row of
## times), @code{y} (one column per time), @code{solver}, @code{xe},
## @code{ye}, @code{ie} (with Events) and @code{stats}.  With no output the
## solution is plotted with @code{odeplot}.
##
## @strong{Options} (@code{odeset} fields, or @code{symplecticset} for the
## package's own fields without warnings; names match in any case):
##
## @table @code
## @item TimeStepSize, TimeStepNumber
## Fixed step h (the last step ends exactly on tf) or a fixed number of
## steps: no error control; the geometric guarantees hold in this mode.
## Without them the step is adaptive.
## @item RelTol, AbsTol, NormControl, InitialStep, MaxStep
## Adaptive mode, scaled as in @code{ode45} (defaults 1e-3, 1e-6, off,
## automatic, |tf-t0|/10).  The local error estimate is the difference to
## the trapezoidal rule built from @var{fcn} at both ends of the step,
## y(k+1) - y(k) - h/2 (f(k) + f(k+1)), of size O(h^2) like the method's
## local error; it costs one evaluation of @var{fcn} per step (shared with
## the next step).
## @item Separable
## @qcode{"on"} for H = T(p) + V(q) with no forcing that depends on p: the
## step is explicit, two evaluations of @var{fcn} per step and no Newton.
## @item Jacobian, HamiltonianHessFcn
## Newton's matrix needs df/dy = J * Hess(H), J = [0 I; -I 0], taken from
## the first of: the @code{Jacobian} option (matrix or handle returning
## df/dy); @code{HamiltonianHessFcn}, a handle returning Hess(H); a second
## output of @var{fcn} giving Hess(H) (2d-by-2d or its column-major vector
## of (2d)^2 elements, as in @code{[dy, ddy] = fcn (t, y)}); finite
## differences of @var{fcn} (2d extra evaluations).  With a forcing term
## the Hessian misses dF/dy and Newton works as a quasi-Newton method.
## @code{stats.jacobian_source} says which was used.
## @item NewtonTol, MaxNewtonIterations
## Newton's stopping tolerance (1e-14 relative) and iterations (10).
## @item Events, OutputFcn, OutputSel, Refine, Stats
## As in @code{ode45}.  Event times are located on the dense output
## (cubic Hermite interpolation between steps, from @var{fcn} at the step
## points; linear when only step points are requested).  @code{Refine}
## (default 1: step points only, where the method's properties hold) adds
## interpolated rows between steps.  @code{Stats} prints steps, failed
## steps, @var{fcn} calls, Newton iterations, Jacobian/Hessian evaluations
## and LU factorizations.
## @item Vectorized
## @qcode{"on"}: @var{fcn} accepts a 2d-by-k matrix of states with a 1-by-k
## row of times (used by @code{odeSPVI}; @code{odeSE} evaluates one state at
## a time).
## @end table
##
## A run that cannot go on (Newton fails with the fixed step or at the
## smallest adaptive step, or @var{fcn} keeps returning NaN) warns and
## returns every row computed so far.
##
## Example: a pendulum with a fixed step.
##
## @example
## @group
## pendulum = @@(t, y) [y(2); -sin(y(1))];
## opts = symplecticset ("TimeStepSize", 0.05);
## [t, y] = odeSE (pendulum, [0 100], [1; 0], opts);
## E = y(:,2).^2/2 - cos (y(:,1));   # bounded error, no drift
## @end group
## @end example
## @seealso{odeSV, odeSPVI, symplecticset, ode45, odeset}
## @end deftypefn

function varargout = odeSE (varargin)
  error ("odeSE: the compiled function odeSE.mex is missing; build the package with 'make'");
endfunction
