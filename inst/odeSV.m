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
## (order 2), or with a symplectic method of higher order built from it.
##
## The state is y = [q; p], q and p in R^d.  @var{fcn} returns Hamilton's
## equations, @code{dy = fcn (t, y)} = [dH/dp; -dH/dq + F], a column of
## length 2d; F(t, q, p) is an optional forcing term.  The method is
## symmetric (time-reversible) as well as symplectic.  For
## H = T(p) + V(q) set @code{Separable} to @qcode{"on"}: the step is then
## the explicit leapfrog, two calls of @var{fcn} and no Newton.
## Otherwise Newton's method solves the implicit stages, with the Hessian
## of H from a second output of @var{fcn}, @code{[dy, ddy] = fcn (t, y)}
## (build it only when @code{nargout > 1}), or from finite differences.
##
## With a fixed step (@code{TimeStepSize} or @code{TimeStepNumber}) every
## step is the same symplectic map: the energy error stays bounded, of
## size O(h^2), however long the run, and the momenta of the symmetries
## of H are conserved to round-off.  Adaptive steps (the default) control
## the local error instead and lose that guarantee; @code{StepControl}
## @qcode{"reversible"} keeps it with time-symmetric adaptive steps that
## crowd where the motion is fast (an eccentric orbit's pericentre).
##
## @var{tspan}, @var{opts}, @var{par1}, @dots{} and the outputs are as in
## @code{odeSE}; @var{sol} also has method and order.  A @var{sol} as
## @var{y0} continues or retraces its run (see @code{odeSE}):
## @code{odeSV (fcn, [T 0], sol)} takes a reversible run back to y0.
##
## The options a user sets first:
##
## @table @code
## @item TimeStepSize, TimeStepNumber
## Fixed step h, or a number of fixed steps.  The last step ends on tf.
## @item RelTol, AbsTol, NormControl, InitialStep, MaxStep
## Adaptive steps, as in @code{ode45} (defaults 1e-3, 1e-6, off,
## automatic, |tf-t0|/10); ignored, with a warning, with a fixed step.
## @item StepControl, StepDensityFcn
## @qcode{"standard"} (the default, error-controlled steps) or
## @qcode{"reversible"}, and the latter's step density rho (t, y), in
## steps per unit time (for Kepler's problem
## @code{@@(t, y) norm (y(1:2))^-1.5}).
## @item Separable
## @qcode{"on"}: the explicit leapfrog, for H = T(p) + V(q) (an
## @var{fcn} that shows otherwise gets a warning).  Default @qcode{"off"}.
## @item SecondOrder
## @qcode{"on"}: @var{fcn} returns the acceleration, @code{a = fcn (t,
## q)}, and y = [q; v] with v = dq/dt: one call of @var{fcn} per force
## evaluation.
## @item Method
## @qcode{"verlet"} (default); compositions of Verlet steps, for any H:
## @qcode{"yoshida4"}, @qcode{"suzuki4"}, @qcode{"kahanli6"},
## @qcode{"kahanli8"}, @qcode{"mclachlan8"}, @qcode{"sofspa10"} (the
## number is the order); splitting methods, for a separable H:
## @qcode{"ruth3"}, @qcode{"candyrozmus4"}, @qcode{"mclachlan4"},
## @qcode{"blanesmoan6"}.  Fixed or reversible steps.
## @item VerletForm
## @qcode{"velocity"} (kick-drift-kick, default) or @qcode{"position"}
## (drift-kick-drift): the inner Verlet step, with Separable or SecondOrder.
## @item CompensatedSummation
## Explicit steps sum their updates with compensation: on by default for
## every Method but Verlet's, and for reversible steps; @qcode{"off"}
## turns it off.
## @item Constraints
## Holonomic constraints g(q) = 0: @code{g = con (q)} (m < d values) or
## @code{[g, G] = con (q)}, G = dg/dq.  RATTLE steps: order 2, symmetric,
## symplectic on the constraints, kept to round-off; fixed steps with
## @code{Separable} or @code{SecondOrder} (user guide, section 11).
## @item Jacobian, HamiltonianHessFcn, JPattern
## Other sources of Newton's matrix, as in @code{odeSE}.
## @item Vectorized
## @qcode{"on"}: @var{fcn} takes a 2d-by-k matrix of states and a 1-by-k
## row of times.
## @item Events, OutputFcn, OutputSel, Refine, Stats
## As in @code{ode45}.
## @item Hamiltonian, Dense, Ensemble, Parallel
## As in @code{odeSE}.
## @item TangentMap, Indicators
## As in @code{odeSE}, for every @code{Method} and @code{VerletForm}.
## @end table
##
## A run that cannot go on warns, with an identifier
## @code{symplectic:@dots{}}, and returns every row computed so far.
## Every option, the methods and their costs, and reversible steps in
## detail: the user guide, @file{doc/user-guide.md} in the package's
## directory, @code{pkg ("list", "symplectic")@{1@}.dir}.
##
## Example: Kepler's orbit of eccentricity 0.6 over 100 periods, 1000
## steps per period.  The angular momentum stays at its start to
## round-off, and the energy error does not grow.
##
## @example
## @group
## e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
## opts = symplecticset ("TimeStepSize", 2*pi/1000, "Separable", "on");
## [t, y] = odeSV (@@symplectic_kepler, [0 200*pi], y0, opts);
## L = y(:,1).*y(:,4) - y(:,2).*y(:,3);
## H = sum (y(:,3:4).^2, 2)/2 - 1 ./ sqrt (sum (y(:,1:2).^2, 2));
## printf ("|L - L(0)| <= %.1e, |H - H(0)| <= %.1e\n",
##         max (abs (L - L(1))), max (abs (H - H(1))));
## plot (t / (2*pi), H - H(1));
## xlabel ("periods");  ylabel ("H(t) - H(0)");
## @end group
## @end example
## @seealso{symdeval, odeSE, odeSPVI, symplecticset, symplectic_kepler, ode45, odeset, odeplot}
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
  if (nargin >= 3 && isstruct (varargin{3})
      && ! isfield (varargin{3}, "symplectic_restart"))
    ## a sol as Y0: continued or retraced (private/__sol_extend__.m)
    [varargout{1:nargout}] = __sol_extend__ ("odeSV", @__odeSV__, nargout,
                                             varargin{:});
  elseif (nargin >= 4 && isstruct (varargin{4})
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
%! ## The double well H = p^2/2 + q^4/4 - q^2/2 with the explicit leapfrog
%! ## (Separable): orbits in each well and around both.  Then Kepler's
%! ## problem at eccentricity 0.9 over 50 periods: reversible steps keep
%! ## the energy error bounded, standard adaptive steps let it drift.
%! duffing = @(t, y) [y(2); y(1) - y(1)^3];
%! opts = symplecticset ("TimeStepSize", 0.05, "Separable", "on");
%! orbits = {};
%! for q0 = [0.2, 0.6, 1.0, 1.3, 1.45, 1.6, 1.9]
%!   for s = [-1, 1]
%!     [t, y] = odeSV (duffing, [0 15], [s*q0; 0], opts);
%!     orbits{end+1} = y;
%!   endfor
%! endfor
%! acc = @(t, q) -q / norm (q)^3;
%! H = @(y) sum (y(:,3:4).^2, 2)/2 - 1 ./ sqrt (sum (y(:,1:2).^2, 2));
%! e = 0.9;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];  tf = 100*pi;
%! o = symplecticset ("SecondOrder", "on", "Refine", 1);
%! [t1, y1] = odeSV (acc, [0 tf], y0, symplecticset (o, "StepControl",
%!                   "reversible", "RelTol", 1e-4));
%! [t2, y2] = odeSV (acc, [0 tf], y0, symplecticset (o, "RelTol", 1e-6,
%!                   "AbsTol", 1e-6));
%! dH1 = max (abs (H (y1) + 0.5), eps);
%! dH2 = max (abs (H (y2) + 0.5), eps);
%! printf ("Kepler, e = 0.9, 50 periods: largest energy error in the first and the last 5 periods\n");
%! printf ("  reversible, %5d steps:  %.2e  %.2e\n", numel (t1) - 1,
%!         max (dH1(t1 <= tf/10)), max (dH1(t1 >= 0.9*tf)));
%! printf ("  standard,   %5d steps:  %.2e  %.2e\n", numel (t2) - 1,
%!         max (dH2(t2 <= tf/10)), max (dH2(t2 >= 0.9*tf)));
%! ## the figure; with no display it is drawn off screen and written to a
%! ## PNG, and with no graphics toolkit that works the numbers are all
%! warning ("off", "Octave:gnuplot-graphics", "local");
%! headless = ! have_window_system ();
%! try
%!   if (headless)
%!     fig = figure ("visible", "off");
%!   else
%!     fig = figure ();
%!   endif
%!   subplot (1, 2, 1);
%!   hold on;
%!   for i = 1:numel (orbits)
%!     plot (orbits{i}(:,1), orbits{i}(:,2), "b");
%!   endfor
%!   hold off;
%!   xlabel ("q");  ylabel ("p");
%!   title ("double well, h = 0.05");
%!   subplot (1, 2, 2);
%!   semilogy (t1 / (2*pi), dH1, "b", t2 / (2*pi), dH2, "r");
%!   xlabel ("periods");  ylabel ("|H(t) - H(0)|");
%!   legend (sprintf ("reversible, %d steps", numel (t1) - 1),
%!           sprintf ("standard, %d steps", numel (t2) - 1),
%!           "location", "southeast");
%!   title ("Kepler, e = 0.9: energy error");
%!   if (headless)
%!     print (fig, "odeSV-demo.png", "-dpng", "-r100");
%!     printf ("no display: figure written to %s\n", fullfile (pwd, "odeSV-demo.png"));
%!   endif
%! catch err
%!   printf ("no figure (%s)\n", err.message);
%! end_try_catch

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
%! ## reversible steps (the user guide's example): over 20 periods of Kepler's
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
%! ## the user guide's Method example: a Nystrom splitting of order 6 on Kepler
%! ## (e = 0.6), SecondOrder; energy error 3e-10 over 16 periods (the
%! ## method's tests are in tests/test_methods.m)
%! e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
%! o = symplecticset ("Method", "blanesmoan6", "SecondOrder", "on", "TimeStepSize", 0.05);
%! sol = odeSV (@(t, q) -q / norm (q)^3, [0 100], y0, o);
%! H = sum (sol.y(3:4,:).^2, 1)/2 - 1 ./ sqrt (sum (sol.y(1:2,:).^2, 1));
%! assert (max (abs (H - H(1))) < 1e-9);
%! assert ({sol.method, sol.order}, {"blanesmoan6", 6});
%! assert (sol.stats.nfevals, 11 * 2000 + 2);
