## Copyright (C) 2026 The symplectic developers
##
## This program is free software: you can redistribute it and/or modify it
## under the terms of the GNU General Public License as published by the Free
## Software Foundation, either version 3 of the License, or (at your option)
## any later version.  See the file COPYING.

## -*- texinfo -*-
## @deftypefn  {} {[@var{t}, @var{y}] =} odeSPVI (@var{fcn}, @var{tspan}, @var{y0})
## @deftypefnx {} {[@var{t}, @var{y}] =} odeSPVI (@var{fcn}, @var{tspan}, @var{y0}, @var{opts})
## @deftypefnx {} {[@var{t}, @var{y}] =} odeSPVI (@var{fcn}, @var{tspan}, @var{y0}, @var{opts}, @var{par1}, @dots{})
## @deftypefnx {} {[@var{t}, @var{y}, @var{te}, @var{ye}, @var{ie}] =} odeSPVI (@dots{})
## @deftypefnx {} {@var{sol} =} odeSPVI (@dots{})
## @deftypefnx {} {} odeSPVI (@dots{})
## Solve Hamilton's equations with a symplectic spectral variational
## integrator of any order.
##
## The state is y = [q; p], q and p in R^d.  @var{fcn} returns Hamilton's
## equations, @code{dy = fcn (t, y)} = [dH/dp; -dH/dq + F], a column of
## length 2d; F(t, q, p) is an optional forcing term.  It may return the
## Hessian of H in y as a second output, @code{[dy, ddy] = fcn (t, y)}
## (build it only when @code{nargout > 1}, as @code{symplectic_kepler}
## does); without it Newton's matrix comes from finite differences.
##
## On each step q is a polynomial of @code{Q_DoFs} Legendre modes, and
## the action is approximated by Gauss--Legendre quadrature on
## @code{Nodes} nodes.  The pair (Q_DoFs, Nodes) = (n, m) sets the order,
## 2*min(n-1, 2m-n+1): n = m+1 gives order 2m, the best for m nodes, and
## the default (4, 3) order 6; keep n <= m+1.
##
## With a fixed step (@code{TimeStepSize} or @code{TimeStepNumber}) every
## step is the same symplectic map: the energy error stays bounded
## however long the run, and the momenta of the symmetries of H are
## conserved to round-off; the steps can be long.  Adaptive steps (the
## default) control the local error instead.  @code{StepControl}
## @qcode{"reversible"} gives adaptive steps that keep the energy bounded
## too, as in @code{odeSV}.
##
## @var{tspan}, @var{opts}, @var{par1}, @dots{} and the outputs are as in
## @code{odeSE}; @var{sol} also has order (the order used), Q_DoFs and
## Nodes.  A @var{sol} as @var{y0} continues or retraces its run (see
## @code{odeSE}): @code{odeSPVI (fcn, [T 0], sol)} takes a reversible
## run back to y0.
##
## The options a user sets first:
##
## @table @code
## @item Nodes, Q_DoFs
## m, 1 to 40 (default 3); n, 2 to min(2m, 41) (default m+1).
## @item TimeStepSize, TimeStepNumber
## Fixed step h, or a number of fixed steps.  The last step ends on tf.
## @item RelTol, AbsTol, NormControl, InitialStep, MaxStep
## Adaptive steps, as in @code{ode45} (defaults 1e-3, 1e-6, off,
## automatic, |tf-t0|/10).  The run advances with a companion of one
## more mode and one more node, so @code{sol.order} is the companion's.
## @item StepControl, StepDensityFcn
## @qcode{"standard"} (default) or @qcode{"reversible"}, and the step
## density of the latter, as in @code{odeSV}.
## @item Vectorized
## @qcode{"on"}: @var{fcn} takes a 2d-by-k matrix of states and a 1-by-k
## row of times; all nodes of a Newton iteration then take one call, the
## fastest form for long runs.
## @item Jacobian, HamiltonianHessFcn, JPattern
## Other sources of Newton's matrix, as in @code{odeSE}; a sparse one
## keeps Newton's systems sparse, for large d.
## @item NewtonMatrix, NewtonSystem
## How Newton's matrix is kept and its systems solved: @qcode{"auto"}
## (default) chooses; see the user guide.
## @item NonlinearSolver
## @qcode{"newton"} (default), @qcode{"fixedpoint"} (no Jacobian: for
## non-stiff problems; Newton where it fails) or @qcode{"auto"}.
## @item Events, OutputFcn, OutputSel, Refine, Stats
## As in @code{ode45}, on the method's own dense output.
## @item Hamiltonian, Dense, Ensemble, Parallel
## As in @code{odeSE}.
## @end table
##
## A run that cannot go on warns, with an identifier
## @code{symplectic:@dots{}}, and returns every row computed so far.
## Every option, the pairs and their orders, and Newton's method in
## detail: the user guide, @file{doc/user-guide.md} in the package's
## directory, @code{pkg ("list", "symplectic")@{1@}.dir}.
##
## Example: Kepler's problem, 100 periods of 100 steps each.
##
## @example
## @group
## e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
## opts = symplecticset ("TimeStepSize", 2*pi/100, "Nodes", 3);
## [t, y] = odeSPVI (@@symplectic_kepler, [0 200*pi], y0, opts);
## H = sum (y(:,3:4).^2, 2)/2 - 1 ./ sqrt (sum (y(:,1:2).^2, 2));
## printf ("energy error: %.1e in the first 10 periods, %.1e in the last\n",
##         max (abs (H(t <= 20*pi) + 0.5)), max (abs (H(t >= 180*pi) + 0.5)));
## @end group
## @end example
## @seealso{symdeval, odeSE, odeSV, symplecticset, symplectic_kepler, ode45, odeset, odeplot}
## @end deftypefn

function varargout = odeSPVI (varargin)
  ## The solver is the compiled gateway __odeSPVI__ (src/__odeSPVI__.c); this
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
    [varargout{1:nargout}] = __sol_extend__ ("odeSPVI", @__odeSPVI__, nargout,
                                             varargin{:});
  elseif (nargin >= 4 && isstruct (varargin{4})
      && __ensemble_parallel__ ("odeSPVI", varargin{4}))
    [varargout{1:nargout}] = __ensemble_parallel__ ("odeSPVI", @__odeSPVI__,
                                                    nargout, varargin{:});
  elseif (nargout == 0)
    __odeSPVI__ (varargin{:});
  else
    [varargout{1:nargout}] = __odeSPVI__ (varargin{:});
  endif
endfunction

%!demo
%! ## The pendulum with long steps (h = 0.5), drawn from the method's own
%! ## dense output (Refine = 8; the dots are the steps); the energy error
%! ## over 20 periods of Kepler's problem (e = 0.6), bounded for odeSPVI
%! ## (order 6, 50 steps per period) and growing for ode45; and events:
%! ## the orbit's crossings of the q1 axis, located on the dense output.
%! pendulum = @(t, y) [y(2); -sin(y(1))];
%! opts = symplecticset ("TimeStepSize", 0.5, "Refine", 8);
%! orbits = {};
%! for q0 = [0.5, 1.5, 2.5, 3]
%!   [t, y] = odeSPVI (pendulum, [0 20], [q0; 0], opts);
%!   orbits{end+1} = y;
%! endfor
%! H = @(y) sum (y(:,3:4).^2, 2)/2 - 1 ./ sqrt (sum (y(:,1:2).^2, 2));
%! e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];  tf = 40*pi;
%! [t1, y1] = odeSPVI (@symplectic_kepler, [0 tf], y0,
%!                     symplecticset ("TimeStepSize", 2*pi/50));
%! [t2, y2] = ode45 (@symplectic_kepler, [0 tf], y0,
%!                   odeset ("RelTol", 1e-5, "AbsTol", 1e-8));
%! dH1 = max (abs (H (y1) + 0.5), eps);
%! dH2 = max (abs (H (y2) + 0.5), eps);
%! printf ("Kepler, e = 0.6, 20 periods: largest energy error in the first and the last 2 periods\n");
%! printf ("  odeSPVI, h = T/50:     %.2e  %.2e\n", max (dH1(t1 <= tf/10)), max (dH1(t1 >= 0.9*tf)));
%! printf ("  ode45, RelTol = 1e-5:  %.2e  %.2e\n", max (dH2(t2 <= tf/10)), max (dH2(t2 >= 0.9*tf)));
%! opts = symplecticset ("RelTol", 1e-10, "AbsTol", 1e-12, "Refine", 4,
%!                       "Events", @(t, y) deal (y(2), 0, 0));
%! [t, y, te, ye] = odeSPVI (@symplectic_kepler, [0 6*pi], y0, opts);
%! printf ("axis crossings at t/pi = %s: distance from the exact k*pi %.2e\n",
%!         mat2str (te' / pi, 6), max (abs (te' - pi * (1:numel (te)))));
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
%!   subplot (2, 2, 1);
%!   hold on;
%!   for i = 1:numel (orbits)
%!     plot (orbits{i}(:,1), orbits{i}(:,2), "b-",
%!           orbits{i}(1:8:end,1), orbits{i}(1:8:end,2), "k.");
%!   endfor
%!   hold off;
%!   axis ([-pi pi -2.2 2.2]);
%!   xlabel ("q");  ylabel ("p");
%!   title ("pendulum, h = 0.5");
%!   subplot (2, 2, 2);
%!   semilogy (t1 / (2*pi), dH1, "b", t2 / (2*pi), dH2, "r");
%!   xlabel ("periods");  ylabel ("|H(t) - H(0)|");
%!   legend ("odeSPVI, h = 2\\pi/50", "ode45, RelTol = 1e-5", "location", "southeast");
%!   title ("Kepler, e = 0.6: energy error");
%!   subplot (2, 2, 3);
%!   plot (y(:,1), y(:,2), "b", ye(:,1), ye(:,2), "ro");
%!   axis equal;
%!   xlabel ("q_1");  ylabel ("q_2");
%!   title (sprintf ("%d axis crossings", numel (te)));
%!   if (headless)
%!     print (fig, "odeSPVI-demo.png", "-dpng", "-r100");
%!     printf ("no display: figure written to %s\n", fullfile (pwd, "odeSPVI-demo.png"));
%!   endif
%! catch err
%!   printf ("no figure (%s)\n", err.message);
%! end_try_catch

## Representative tests (the full ode45-contract tests are in
## tests/test_ode45_contract.m).
%!test
%! ## dense output at output times is as accurate as the steps
%! f = @(t, y) [y(2); -y(1)];
%! o = symplecticset ("TimeStepSize", 0.1);
%! [t, y] = odeSPVI (f, [0 0.05 1.234 pi 10], [1; 0], o);
%! assert (t, [0; 0.05; 1.234; pi; 10]);
%! assert (y, [cos(t), -sin(t)], 1e-7);

%!test
%! ## events to 1e-10 with a fixed step; a terminal event ends the run
%! f = @(t, y) [y(2); -y(1)];
%! o = symplecticset ("TimeStepSize", 0.02, "Events", @(t, y) deal (y(1), 0, 0));
%! [t, y, te, ye, ie] = odeSPVI (f, [0 10], [1; 0], o);
%! assert (te, pi/2 + (0:2)' * pi, 1e-10);
%! o = symplecticset (o, "Events", @(t, y) deal (y(1), 1, 0));
%! sol = odeSPVI (f, [0 10], [1; 0], o);
%! assert (sol.xe, pi/2, 1e-10);
%! assert (sol.x(end), sol.xe);
%! assert (sol.y(:, end), sol.ye(:));
%! assert ([sol.order, sol.Q_DoFs, sol.Nodes], [6, 4, 3]);

%!test
%! ## Vectorized: the same trajectory with one call for all nodes
%! f = @(t, y) [y(2, :); -sin(y(1, :))];
%! o = symplecticset ("TimeStepSize", 0.1);
%! s0 = odeSPVI (f, [0 5], [1; 0], o);
%! s1 = odeSPVI (f, [0 5], [1; 0], symplecticset (o, "Vectorized", "on"));
%! assert (s1.y, s0.y, 1e-12);
%! assert (s1.stats.nfevals < s0.stats.nfevals / 2);
