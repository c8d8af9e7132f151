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
## Solve Hamilton's equations with the symplectic St@"ormer--Verlet method
## (order 2).
##
## The state is y = [q; p], q and p in R^d.  @var{fcn} returns Hamilton's
## equations, @code{dy = fcn (t, y)} = [dH/dp; -dH/dq + F], a column of
## length 2d; F(t, q, p) is an optional forcing term (the example below
## gives @var{fcn} for Kepler's problem).  With fq = dH/dp and
## fp = -dH/dq + F, one step of size h is
##
## @example
## @group
## p(k+1/2) = p(k) + h/2 fp(t(k), q(k), p(k+1/2))                (implicit)
## q(k+1)   = q(k) + h/2 (fq(t(k), q(k), p(k+1/2))
##                        + fq(t(k+1), q(k+1), p(k+1/2)))        (implicit)
## p(k+1)   = p(k+1/2) + h/2 fp(t(k+1), q(k+1), p(k+1/2))
## @end group
## @end example
##
## @noindent
## The method is symmetric (time-reversible) as well as symplectic.  For
## H = T(p) + V(q) set @code{Separable} to @qcode{"on"}: the step is then
## the explicit leapfrog, two calls of @var{fcn} and no Newton.
## Otherwise Newton's method solves the implicit stages; its matrix needs
## the Hessian of H, taken from the first of: the @code{Jacobian} option
## (df/dy), the @code{HamiltonianHessFcn} option, a second output of
## @var{fcn}, @code{[dy, ddy] = fcn (t, y)} with ddy the 2d-by-2d Hessian
## of H in y or its column-major vector (build it only when
## @code{nargout > 1}), and finite differences of @var{fcn}.
##
## @strong{Why a fixed step.}  With @code{TimeStepSize} (or
## @code{TimeStepNumber}) every step is one and the same symplectic map,
## which follows the exact flow of a modified Hamiltonian within O(h^2)
## of H: the energy error oscillates at size O(h^2) without drift however
## long the run, and the momenta of the symmetries of H are conserved to
## round-off.  Adaptive steps (the default) control the local error
## instead; each new step size is a new map, and on fast oscillations the
## step sizes lock to their phase and can pump their energy by orders of
## magnitude.  For long runs, and for such systems, use a fixed step, or
## reversible steps.
##
## @strong{Reversible steps.}  Where the motion needs small steps in a
## small part of the orbit (close encounters, eccentric orbits), a fixed
## step wastes most of its work.  With @code{StepControl}
## @qcode{"reversible"} the steps follow a step density rho instead:
## h(k+1/2) = eps/rho(k+1/2), with
##
## @example
## (rho(k-1/2) + rho(k+1/2)) / 2 = rho(t(k), y(k))
## @end example
##
## @noindent
## at every step point.  The recurrence reads the same backwards, so the
## whole run is time-reversible (run back from the end, its first step the
## last one, it retraces the steps) and the energy error stays bounded, as
## with a fixed step.  rho(t, y) is @code{StepDensityFcn} (steps per unit
## time; for Kepler's problem @code{@@(t, y) norm (y(1:2))^-1.5}), by
## default |f(t,y)| / sqrt(|y|^2 + |AbsTol|^2), which needs f at the step
## points: with @code{SecondOrder} the step has it; otherwise it is the
## call per step that the dense output (@code{Refine} > 1, output times,
## events) and standard steps' error estimate make as well.
## eps = RelTol^(1/p) for a method of order p, at most 0.05 (beyond it
## the density changes too much within a step).  @code{InitialStep} is the
## first step exactly; without it two trial steps find it.  There is no
## error estimate and no rejected step: a step whose Newton iteration fails
## ends the run.  The last step is shortened to end on tf, and
## @code{MaxStep} (no cap by default) bounds the steps; both break the
## symmetry where they act.
##
## @strong{Higher order.}  @code{Method} replaces the Verlet step by a
## composition of Verlet steps (any H; implicit stages unless
## @code{Separable} is on) or by a splitting method (separable H only).
## All are symplectic, all but two symmetric (time-reversible); they take
## fixed steps (@code{TimeStepSize} or @code{TimeStepNumber}) or, the
## symmetric ones, reversible steps.
##
## @multitable @columnfractions 0.2 0.1 0.1 0.6
## @headitem Method @tab order @tab stages @tab kind
## @item @qcode{"verlet"} @tab 2 @tab 1 @tab the default
## @item @qcode{"yoshida4"} @tab 4 @tab 3 @tab composition (triple jump)
## @item @qcode{"suzuki4"} @tab 4 @tab 5 @tab composition
## @item @qcode{"kahanli6"} @tab 6 @tab 9 @tab composition
## @item @qcode{"kahanli8"} @tab 8 @tab 17 @tab composition
## @item @qcode{"mclachlan8"} @tab 8 @tab 15 @tab composition
## @item @qcode{"sofspa10"} @tab 10 @tab 35 @tab composition
## @item @qcode{"ruth3"} @tab 3 @tab 3 @tab splitting, not symmetric
## @item @qcode{"candyrozmus4"} @tab 4 @tab 3 @tab splitting
## @item @qcode{"mclachlan4"} @tab 4 @tab 4 @tab splitting, not symmetric (*)
## @item @qcode{"blanesmoan6"} @tab 6 @tab 11 @tab splitting (*)
## @end multitable
##
## @noindent
## (*) Nystrom methods: their order holds for a kinetic energy quadratic
## in p, T = |p|^2/2 (or p'*inv(M)*p/2), as with @code{SecondOrder}; for
## other T it is 3 and 4.  Stages are force evaluations f_p per step; in
## the first-order form each drift between them also needs f_q, about
## two calls of @var{fcn} per stage.
##
## With @code{SecondOrder} on, @var{fcn} returns the acceleration, @code{a =
## fcn (t, q)}, y = [q; v] with v = dq/dt, and a stage makes one call.
## For H = |p|^2/2 + V(q), a = -dV/dq; for masses m_i, a_i = F_i / m_i:
## the steps are then those of H = p'*inv(M)*p/2 + V(q) with p = M v.
## For example, Kepler's problem with the sixth-order Nystrom splitting:
## @code{odeSV (@@(t, q) -q / norm (q)^3, [0 100], y0,
## symplecticset ("Method", "blanesmoan6", "SecondOrder", "on",
## "TimeStepSize", 0.05))}.
##
## @code{CompensatedSummation} sums the updates of q and p with
## compensation, which keeps the round-off of the energy near that of a
## single step over runs of a million steps and more.
##
## @var{tspan}, @var{opts}, @var{par1}, @dots{} and the outputs are as in
## @code{odeSE}: @var{sol} has the fields of @code{ode45}, and with no
## output the solution is plotted with @code{odeplot}.
##
## @table @code
## @item TimeStepSize, TimeStepNumber
## Fixed step h, or a number of fixed steps.  The last step ends on tf.
## @item RelTol, AbsTol, NormControl, InitialStep, MaxStep
## Adaptive steps, as in @code{ode45} (defaults 1e-3, 1e-6, off,
## automatic, |tf-t0|/10; reversible steps: see above).  The error estimate is the distance to the
## trapezoidal rule through the step's ends plus that rule's own leading
## error term, so that it holds in q and in p.
## @item StepControl, StepDensityFcn
## @qcode{"standard"} (the default): the error-controlled steps above;
## @qcode{"reversible"}: steps of a step density (above).
## @item Separable (alias Explicit)
## @qcode{"on"}: explicit leapfrog (above); a warning when @var{fcn}
## shows that dH/dp depends on q (or t).  Default @qcode{"off"}.
## @item Method, SecondOrder, CompensatedSummation
## Above.  Defaults @qcode{"verlet"}, @qcode{"off"}, @qcode{"off"}; names
## of methods are matched without regard to case.  @code{sol.method} and
## @code{sol.order} say which method ran.
## @item Jacobian, HamiltonianHessFcn
## Sources of Newton's matrix (above); @code{sol.stats.jacobian_source}
## says which one served.  A sparse one keeps the implicit solves
## sparse (Stoermer-Verlet itself: not the
## compositions of @code{Method}, nor @code{CompensatedSummation}); the one call of the function at (t0, y0) that tells is
## counted in @code{npds}.
## @item JPattern
## The nonzero pattern of df/dy (2d-by-2d, sparse or full): finite
## differences then step the columns that share no row together, a few
## calls of @var{fcn} for a banded system instead of 2d.  Given as a
## sparse matrix, the matrices it makes are sparse too.
## @item NewtonTol, MaxNewtonIterations
## Newton's relative tolerance (1e-14; fixed steps converge to
## NewtonTol/1000, and so do reversible ones) and iterations per solve
## (10).
## @item Vectorized
## @qcode{"on"}: @var{fcn} takes a 2d-by-k matrix of states and a 1-by-k
## row of times; finite-difference matrices then take one call.
## @item Events, OutputFcn, OutputSel, Refine, Stats
## As in @code{ode45}, on the dense output (cubic Hermite between the
## step points).  @code{Refine} adds interpolated rows (by default 4 per
## step of an adaptive run, none with a fixed step); @code{Stats} prints
## the counts of @code{sol.stats}.
## @item Hamiltonian, Dense, MaxSteps
## As in @code{odeSE}.
## @item Ensemble, Parallel
## Many initial states at once, the columns of @var{y0}, as in
## @code{odeSE}.
## @end table
##
## A run that cannot go on warns, with an identifier
## @code{symplectic:@dots{}}, and returns every row computed so far.
##
## Example: Kepler's orbit of eccentricity 0.6 over 100 periods, 1000
## steps per period.  The angular momentum stays at its start to
## round-off, and the energy error does not grow.
##
## @example
## @group
## kepler = @@(t, y) [y(3:4); -y(1:2) / norm(y(1:2))^3];
## e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
## opts = symplecticset ("TimeStepSize", 2*pi/1000, "Separable", "on");
## [t, y] = odeSV (kepler, [0 200*pi], y0, opts);
## L = y(:,1).*y(:,4) - y(:,2).*y(:,3);
## H = sum (y(:,3:4).^2, 2)/2 - 1 ./ sqrt (sum (y(:,1:2).^2, 2));
## printf ("|L - L(0)| <= %.1e, |H - H(0)| <= %.1e\n",
##         max (abs (L - L(1))), max (abs (H - H(1))));
## plot (t / (2*pi), H - H(1));
## xlabel ("periods");  ylabel ("H(t) - H(0)");
## @end group
## @end example
##
## The same orbit at eccentricity 0.9 with reversible steps, which
## crowd at the pericentre:
##
## @example
## @group
## e = 0.9;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
## opts = symplecticset ("StepControl", "reversible", "RelTol", 1e-5,
##                       "SecondOrder", "on");
## [t, y] = odeSV (@@(t, q) -q / norm (q)^3, [0 200*pi], y0, opts);
## @end group
## @end example
## @seealso{symdeval, odeSE, odeSPVI, symplecticset, ode45, odeset, odeplot}
## @end deftypefn

function varargout = odeSV (varargin)
  ## The solver is the compiled gateway __odeSV__ (src/__odeSV__.c); this
  ## m-file holds its help and tests.  With no output it plots with
  ## odeplot, as ode45 does.
  ## Parallel other than 1 shares an ensemble's members out to other
  ## processes (private/__ensemble_parallel__.m).
  ## a compiled FCN (symcompile) goes to the gateway as its struct
  if (nargin >= 1 && isa (varargin{1}, "symfcn"))
    varargin{1} = __symfcn_gateway__ (varargin{1});
  endif
  if (nargin >= 4 && isstruct (varargin{4})
      && __ensemble_parallel__ ("odeSV", varargin{4}))
    [varargout{1:nargout}] = __ensemble_parallel__ ("odeSV", @__odeSV__,
                                                    nargout, varargin{:});
  elseif (nargout == 0)
    __odeSV__ (varargin{:});
  else
    [varargout{1:nargout}] = __odeSV__ (varargin{:});
  endif
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

%!demo
%! ## Kepler's problem at eccentricity 0.9 over 200 periods: reversible
%! ## steps keep the energy error bounded; standard adaptive steps with
%! ## about as many steps let it drift.
%! acc = @(t, q) -q / norm (q)^3;
%! H = @(y) sum (y(:,3:4).^2, 2)/2 - 1 ./ sqrt (sum (y(:,1:2).^2, 2));
%! e = 0.9;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];  tf = 400*pi;
%! o = symplecticset ("SecondOrder", "on", "Refine", 1);
%! [t1, y1] = odeSV (acc, [0 tf], y0, symplecticset (o, "StepControl",
%!                   "reversible", "RelTol", 1e-4));
%! [t2, y2] = odeSV (acc, [0 tf], y0, symplecticset (o, "RelTol", 1e-6,
%!                   "AbsTol", 1e-6));
%! figure ();
%! semilogy (t1 / (2*pi), max (abs (H (y1) + 0.5), eps), "b",
%!           t2 / (2*pi), max (abs (H (y2) + 0.5), eps), "r");
%! xlabel ("periods");  ylabel ("|H(t) - H(0)|");
%! legend (sprintf ("reversible, %d steps", numel (t1) - 1),
%!         sprintf ("standard, %d steps", numel (t2) - 1),
%!         "location", "southeast");
%! title ("Kepler, e = 0.9: energy error");

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
%! ## reversible steps (the second example): over 20 periods of Kepler's
%! ## problem at e = 0.9, the energy error of the last periods is no larger
%! ## than that of the first, the angular momentum is kept, and the steps
%! ## near the pericentre are the shortest
%! e = 0.9;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
%! opts = symplecticset ("StepControl", "reversible", "RelTol", 1e-5,
%!                       "SecondOrder", "on", "Refine", 1);
%! [t, y] = odeSV (@(t, q) -q / norm (q)^3, [0 40*pi], y0, opts);
%! H = sum (y(:,3:4).^2, 2)/2 - 1 ./ sqrt (sum (y(:,1:2).^2, 2));
%! L = y(:,1).*y(:,4) - y(:,2).*y(:,3);
%! dH = abs (H - H(1));
%! assert (max (dH(t >= 36*pi)) <= 1.5 * max (dH(t <= 4*pi)));
%! assert (max (dH) < 1e-3);
%! assert (max (abs (L - L(1))) < 1e-12);
%! h = diff (t);  r = sqrt (sum (y(1:end-1,1:2).^2, 2));
%! assert (max (h(r < 0.2)) < min (h(r > 1.8)) / 10);

%!test
%! ## events with a direction; extra parameters reach fcn and Events
%! f = @(t, y, w) [y(2); -w^2 * y(1)];
%! ev = @(t, y, w) deal (y(2), 0, 1);     # p = -2 sin(2t) rises through 0
%! o = symplecticset ("TimeStepSize", 0.001, "Events", ev);
%! [t, y, te, ye, ie] = odeSV (f, [0 5], [1; 0], o, 2);
%! assert (te, [pi/2; 3*pi/2], 1e-5);
%! assert (ie, [1; 1]);
%! assert (t(end), 5);

%!test
%! ## the help's Method example: a Nystrom splitting of order 6 on Kepler
%! ## (e = 0.6), SecondOrder; energy error 3e-10 over 16 periods (the
%! ## method's tests are in tests/test_methods.m)
%! e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
%! o = symplecticset ("Method", "blanesmoan6", "SecondOrder", "on", "TimeStepSize", 0.05);
%! sol = odeSV (@(t, q) -q / norm (q)^3, [0 100], y0, o);
%! H = sum (sol.y(3:4,:).^2, 1)/2 - 1 ./ sqrt (sum (sol.y(1:2,:).^2, 1));
%! assert (max (abs (H - H(1))) < 1e-9);
%! assert ({sol.method, sol.order}, {"blanesmoan6", 6});
%! assert (sol.stats.nfevals, 11 * 2000 + 2);
