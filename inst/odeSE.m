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
## The state is y = [q; p], q and p in R^d.  @var{fcn} returns Hamilton's
## equations, @code{dy = fcn (t, y)} = [dH/dp; -dH/dq + F], a column of
## length 2d; F(t, q, p) is an optional forcing term (-c*p for a damping).
## For the pendulum, H = p^2/2 - cos(q):
## @code{fcn = @@(t, y) [y(2); -sin(y(1))]}.  The step takes p implicit
## and q explicit; Newton's method solves it, with the Hessian of H from
## a second output of @var{fcn}, @code{[dy, ddy] = fcn (t, y)} (build it
## only when @code{nargout > 1}), or from finite differences.  For
## H = T(p) + V(q) set @code{Separable} to @qcode{"on"}: the step is then
## explicit, two calls of @var{fcn} and no Newton.
##
## With a fixed step (@code{TimeStepSize} or @code{TimeStepNumber}) every
## step is the same symplectic map: the energy error stays bounded, of
## size O(h), however long the run, and the momenta of the symmetries of
## H are conserved to round-off.  Adaptive steps, the default as in
## @code{ode45}, control the local error instead and lose that
## guarantee.  For long runs use a fixed step.
##
## @var{tspan} is [t0, tf] (a row at every step) or more times (rows
## exactly there, from the dense output, the steps unchanged); tf < t0
## runs backwards.  @var{opts} comes from @code{symplecticset} or
## @code{odeset} ([] for the defaults).  @var{par1}, @dots{} are passed
## to @var{fcn} and the other functions after t and y.  @var{t} is a
## column and @var{y} has a row per time.  @var{sol} has the fields of
## @code{ode45} (x, y, solver, xe, ye, ie, stats).  With no output the
## solution is plotted with @code{odeplot}.
##
## @var{y0} may be the @var{sol} of a run of the same solver, with
## @var{tspan}(1) its end: the run goes on beyond it, or back.  It starts
## at the step point before the last step (shortened, maybe, to end
## there), fixed steps on the same grid (a continued run is the run over
## the whole span, explicit steps to the bit), reversible ones with the
## densities @var{sol} keeps in its field restart (a run back retraces
## them to y0).  Options not given are those of that run; the @var{sol}
## returned is the two joined (a run back: its own, from the end point).
##
## The options a user sets first:
##
## @table @code
## @item TimeStepSize, TimeStepNumber
## Fixed step h, or a number of fixed steps.  The last step ends on tf.
## @item RelTol, AbsTol, NormControl, InitialStep, MaxStep
## Adaptive steps, as in @code{ode45} (defaults 1e-3, 1e-6, off,
## automatic, |tf-t0|/10); ignored, with a warning, with a fixed step.
## @item Separable
## @qcode{"on"} for H = T(p) + V(q), with no forcing that depends on p
## (an @var{fcn} that shows otherwise gets a warning).  Default
## @qcode{"off"}.
## @item SecondOrder
## @qcode{"on"}: @var{fcn} returns the acceleration, @code{a = fcn (t,
## q)}, and y = [q; v] with v = dq/dt: one call of @var{fcn} per step.
## @item Jacobian, HamiltonianHessFcn, JPattern
## Other sources of Newton's matrix: df/dy, a function returning the
## Hessian of H, or the nonzero pattern of df/dy for finite differences.
## @item Vectorized
## @qcode{"on"}: @var{fcn} takes a 2d-by-k matrix of states and a 1-by-k
## row of times.
## @item Events, OutputFcn, OutputSel, Refine, Stats
## As in @code{ode45}.
## @item Hamiltonian, Dense
## A handle @code{H (t, y, @dots{})}, whose values at @code{sol.x} come
## back in @code{sol.H}; @qcode{"on"}: @var{sol} keeps the dense output
## for @code{symdeval}.
## @item Ensemble, Parallel
## @qcode{"on"}: each column of @var{y0} (2d-by-K) is a member's initial
## state, and @var{y} is numel(@var{t})-by-2d-by-K; the members can be
## split across processes.
## @item TangentMap, Indicators
## Explicit fixed steps, one output: @qcode{"on"} gives Phi = dy_k/dy_0,
## the exact derivative of the steps, in @code{sol.phi}
## (2d-by-2d-by-numel (sol.x)); a 2d-by-k V0 gives Phi*V0.  Hessian from
## @var{fcn}'s second output, @code{HamiltonianHessFcn}, else central
## differences (about 1e-10 relative).  @qcode{"lyapunov"}: the maximal
## Lyapunov exponent of one vector in @code{sol.lyapunov}.  User guide,
## section 14.
## @end table
##
## A run that cannot go on (Newton fails, @var{fcn} returns NaN or Inf)
## warns, with an identifier @code{symplectic:@dots{}}, and returns every
## row computed so far.  Every option, the steps and the outputs in
## detail: the user guide, @file{doc/user-guide.md} in the package's
## directory, @code{pkg ("list", "symplectic")@{1@}.dir}.
##
## Example: the pendulum over 1000 time units with h = 0.05; the energy
## error is as small at the end as at the start.
##
## @example
## @group
## pendulum = @@(t, y) [y(2); -sin(y(1))];
## opts = symplecticset ("TimeStepSize", 0.05);
## [t, y] = odeSE (pendulum, [0 1000], [1; 0], opts);
## dE = abs (y(:,2).^2/2 - cos (y(:,1)) + cos (1));
## printf ("energy error: %.1e in [0, 100], %.1e in [900, 1000]\n",
##         max (dE(t <= 100)), max (dE(t >= 900)));
## @end group
## @end example
## @seealso{symdeval, odeSV, odeSPVI, symplecticset, ode45, odeset, odeplot}
## @end deftypefn

function varargout = odeSE (varargin)
  ## The solver is the compiled gateway __odeSE__ (src/__odeSE__.c); this
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
    [varargout{1:nargout}] = __sol_extend__ ("odeSE", @__odeSE__, nargout,
                                             varargin{:});
  elseif (nargin >= 4 && isstruct (varargin{4})
      && __ensemble_parallel__ ("odeSE", varargin{4}))
    [varargout{1:nargout}] = __ensemble_parallel__ ("odeSE", @__odeSE__,
                                                    nargout, varargin{:});
  elseif (nargout == 0)
    __odeSE__ (varargin{:});
  else
    [varargout{1:nargout}] = __odeSE__ (varargin{:});
  endif
endfunction

%!demo
%! ## The pendulum H = p^2/2 - cos(q) with one fixed step h = 0.05: its
%! ## phase portrait (librations inside the separatrix, rotations outside),
%! ## and the energy error over time, bounded for symplectic Euler and
%! ## growing for ode45 (default tolerances).
%! pendulum = @(t, y) [y(2); -sin(y(1))];
%! opts = symplecticset ("TimeStepSize", 0.05, "Separable", "on");
%! orbits = {};
%! for q0 = [0.5, 1, 1.5, 2, 2.5, 3]
%!   [t, y] = odeSE (pendulum, [0 17], [q0; 0], opts);
%!   orbits(end+1, :) = {y, "b"};
%! endfor
%! for p0 = [2.2, 2.6, -2.2, -2.6]
%!   ## rotations: from one end of [-pi, pi] across to the other
%!   [t, y] = odeSE (pendulum, [0 8], [-pi*sign(p0); p0], opts);
%!   orbits(end+1, :) = {y, "r"};
%! endfor
%! E = @(y) y(:,2).^2/2 - cos (y(:,1));
%! y0 = [2; 0];  tf = 200;
%! [t1, y1] = odeSE (pendulum, [0 tf], y0, opts);
%! [t2, y2] = ode45 (pendulum, [0 tf], y0);
%! dE1 = max (abs (E (y1) - E (y0')), eps);
%! dE2 = max (abs (E (y2) - E (y0')), eps);
%! printf ("pendulum from q = 2: largest energy error in the first and the last tenth of [0, %g]\n", tf);
%! printf ("  odeSE, h = 0.05:  %.2e  %.2e\n", max (dE1(t1 <= tf/10)), max (dE1(t1 >= 0.9*tf)));
%! printf ("  ode45:            %.2e  %.2e\n", max (dE2(t2 <= tf/10)), max (dE2(t2 >= 0.9*tf)));
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
%!   for i = 1:rows (orbits)
%!     plot (orbits{i,1}(:,1), orbits{i,1}(:,2), orbits{i,2});
%!   endfor
%!   hold off;
%!   axis ([-pi pi -3 3]);
%!   xlabel ("q");  ylabel ("p");
%!   title ("phase portrait, h = 0.05");
%!   subplot (1, 2, 2);
%!   semilogy (t1, dE1, "b", t2, dE2, "r");
%!   xlabel ("t");  ylabel ("|H(t) - H(0)|");
%!   legend ("odeSE, h = 0.05", "ode45", "location", "southeast");
%!   title ("energy error");
%!   if (headless)
%!     print (fig, "odeSE-demo.png", "-dpng", "-r100");
%!     printf ("no display: figure written to %s\n", fullfile (pwd, "odeSE-demo.png"));
%!   endif
%! catch err
%!   printf ("no figure (%s)\n", err.message);
%! end_try_catch

## Representative tests (the full ode45-contract tests are in
## tests/test_ode45_contract.m).
%!test
%! ## fixed step: a row at every step, the last one on tf
%! f = @(t, y) [y(2); -y(1)];
%! [t, y] = odeSE (f, [0 1], [1 0], symplecticset ("TimeStepSize", 0.3));
%! assert (t, [0; 0.3; 0.6; 0.9; 1], 1e-15);
%! assert (size (y), [5, 2]);
%! assert (y(end, :), [cos(1), -sin(1)], 0.2);

%!test
%! ## output times from the dense output; the steps stay those of [t0 tf]
%! f = @(t, y) [y(2); -y(1)];
%! o = symplecticset ("TimeStepSize", 0.01);
%! [t, y] = odeSE (f, [0 0.123 0.5 1], [1; 0], o);
%! assert (t, [0; 0.123; 0.5; 1]);
%! assert (y, [cos(t), -sin(t)], 0.01);
%! [t2, y2] = odeSE (f, [0 1], [1; 0], o);
%! assert (y(end, :), y2(end, :), 1e-15);

%!test
%! ## a terminal event: the event row is the last one; sol has ode45's fields
%! f = @(t, y) [y(2); -y(1)];
%! o = symplecticset ("TimeStepSize", 0.001, "Events", @(t, y) deal (y(1), 1, -1));
%! [t, y, te, ye, ie] = odeSE (f, [0 5], [1; 0], o);
%! assert (te, pi/2, 2e-3);
%! assert ([t(end), y(end, :)], [te, ye]);
%! assert (ie, 1);
%! sol = odeSE (f, [0 5], [1; 0], o);
%! assert (all (isfield (sol, {"x", "y", "solver", "xe", "ye", "ie", "stats"})));
%! assert (sol.solver, "odeSE");
%! assert (size (sol.y), [2, numel(sol.x)]);
