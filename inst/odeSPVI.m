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
## Hessian of H in y as a second output, @code{[dy, ddy] = fcn (t, y)},
## ddy 2d-by-2d or its column-major vector: build it only when
## @code{nargout > 1}, as in the example below.
##
## On each step q is a polynomial of @code{Q_DoFs} Legendre modes, and
## the action is approximated by Gauss--Legendre quadrature on
## @code{Nodes} nodes with a momentum at each node; the discrete
## Euler--Lagrange equations of the step are solved by Newton's method.
## The pair (Q_DoFs, Nodes) = (n, m) sets the order,
## 2*min(n-1, 2m-n+1): n = m+1 gives order 2m, the best for m nodes, and
## the default (4, 3) order 6; (2, 1) is the implicit midpoint rule.
## Pairs with n > 2m are refused; pairs with n-1 > m lose order and
## can fail where d2H/dq2 is zero or small: keep n <= m+1.
##
## @strong{Why a fixed step.}  With @code{TimeStepSize} (or
## @code{TimeStepNumber}) every step is one and the same symplectic map,
## which follows the exact flow of a modified Hamiltonian close to H: the
## energy error oscillates without drift however long the run, and the
## momenta of the symmetries of H are conserved to round-off.  Adaptive
## steps (the default) control the local error instead, and each new step
## size is a new map.  Use a fixed step for long runs, or
## @code{StepControl} @qcode{"reversible"}: steps that follow a step
## density by a time-symmetric recurrence, which keeps the energy error
## bounded like a fixed step while the steps crowd where the motion is
## fast (@code{help odeSV} says how; here eps = RelTol^(1/order), at most
## 0.05).  The default density needs f at the step points, a call per
## step that the dense output (@code{Refine} > 1, output times, events,
## @code{Dense}) makes anyway and shares; a run without dense output
## saves it with a @code{StepDensityFcn}.  The step being symmetric for
## every pair (n, m), so is the run.
##
## @var{tspan}, @var{opts}, @var{par1}, @dots{} and the outputs are as in
## @code{odeSE}; @var{sol} has the fields of @code{ode45} and also order
## (the order used), Q_DoFs and Nodes.
##
## @table @code
## @item Nodes (alias P_DoFs), Q_DoFs, PolynomialDegree
## m, 1 to 40 (default 3); n, 2 to min(2m, 41) (default m+1); the
## degree 1 to 39.
## @code{PolynomialDegree} sets n = degree+1, and m = degree+1 unless
## Nodes is given.
## @item TimeStepSize, TimeStepNumber
## Fixed step h, or a number of fixed steps.  The last step ends on tf.
## @item RelTol, AbsTol, NormControl, InitialStep, MaxStep
## Adaptive steps, as in @code{ode45} (defaults 1e-3, 1e-6, off,
## automatic, |tf-t0|/10; reversible steps: see above).  The error is
## estimated with a companion
## solution of one more mode and one more node, and the run advances with
## it, so @code{sol.order} is the companion's.
## @item StepControl, StepDensityFcn
## @qcode{"standard"} (default) or @qcode{"reversible"} (above), and the
## step density of the latter, as for @code{odeSV}.
## @item Jacobian, HamiltonianHessFcn
## Newton's matrix comes from the first of: @code{Jacobian} (df/dy),
## @code{HamiltonianHessFcn} (a handle returning the Hessian), the second
## output of @var{fcn}, finite differences of @var{fcn}.
## @code{sol.stats.jacobian_source} says which one served.
## A sparse Hessian or Jacobian is used sparse (see NewtonSystem); the
## one call of the function at (t0, y0) that tells is counted in
## @code{npds}.
## @item JPattern
## The nonzero pattern of df/dy (2d-by-2d, sparse or full): finite
## differences then step the columns that share no row together, a few
## calls of @var{fcn} for a banded system instead of 2d per node.  Given
## as a sparse matrix, the matrices it makes are sparse too.
## @item NewtonMatrix
## @qcode{"kept"}: Newton's matrix and its LU are kept across steps while
## Newton converges fast; @qcode{"new"}: a new one at every step (fewer
## calls of @var{fcn}, but Hessians on every step).  Default
## @qcode{"auto"}: @qcode{"new"} for Vectorized finite differences of at
## most 64 unknowns, else @qcode{"kept"}.
## @item NewtonSystem
## @qcode{"stages"}: Newton's system of (Q_DoFs-1+Nodes)*d unknowns is
## reduced, with one Jacobian for all nodes, to ceil(Nodes/2) systems of
## size 2d (one real, the others complex), or of size d when the Hessian
## is full and H separable; a sparse Hessian or Jacobian keeps them
## sparse (KLU), so that memory and time grow linearly with d for a
## banded one.  Pairs Q_DoFs = Nodes+1 only.  @qcode{"full"}: one dense
## LU of the whole system (a sparse Hessian is made full).  Default
## @qcode{"auto"}: @qcode{"stages"} for those pairs when the Hessian or
## Jacobian is sparse or the system has more than 600 unknowns, else
## @qcode{"full"}; the other pairs with a sparse Hessian or Jacobian
## factor the whole system sparse, with one Jacobian for all nodes.
## @item NewtonTol, MaxNewtonIterations
## Newton's relative tolerance (1e-14; fixed steps converge to
## NewtonTol/100, and so do reversible ones) and iterations per solve
## (10).
## @item Vectorized
## @qcode{"on"}: @var{fcn} takes a 2d-by-k matrix of states and a 1-by-k
## row of times; all nodes of a Newton iteration then take one call, the
## fastest form for long runs.
## @item Events, OutputFcn, OutputSel, Refine, Stats
## As in @code{ode45}, on the method's own dense output.
## @code{Refine} defaults to 4 rows per step of an adaptive run, to the
## step points with a fixed step.  The Events function is also evaluated
## at Nodes points inside each step, so that a pair of zeros inside one
## long step is found.
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
## Example: Kepler's problem, 100 periods of 100 steps each.
##
## @example
## @group
## function [dy, ddy] = kepler (t, y)
##   q = y(1:2);  r = norm (q);
##   dy = [y(3:4); -q / r^3];
##   if (nargout > 1)
##     ddy = [(eye(2) - 3*(q*q')/r^2) / r^3, zeros(2); zeros(2), eye(2)];
##   endif
## endfunction
## e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
## opts = symplecticset ("TimeStepSize", 2*pi/100, "Nodes", 3);
## [t, y] = odeSPVI (@@kepler, [0 200*pi], y0, opts);
## H = sum (y(:,3:4).^2, 2)/2 - 1 ./ sqrt (sum (y(:,1:2).^2, 2));
## printf ("energy error: %.1e in the first 10 periods, %.1e in the last\n",
##         max (abs (H(t <= 20*pi) + 0.5)), max (abs (H(t >= 180*pi) + 0.5)));
## @end group
## @end example
## @seealso{symdeval, odeSE, odeSV, symplecticset, ode45, odeset, odeplot}
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
  if (nargin >= 4 && isstruct (varargin{4})
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
%! ## Phase portrait of the pendulum with large steps (h = 0.5) drawn from
%! ## the method's own dense output (Refine = 8); the dots are the steps.
%! pendulum = @(t, y) [y(2); -sin(y(1))];
%! opts = symplecticset ("TimeStepSize", 0.5, "Refine", 8);
%! figure ();
%! hold on;
%! for q0 = [0.5, 1.5, 2.5, 3]
%!   [t, y] = odeSPVI (pendulum, [0 20], [q0; 0], opts);
%!   plot (y(:,1), y(:,2), "b-", y(1:8:end,1), y(1:8:end,2), "k.");
%! endfor
%! hold off;
%! axis ([-pi pi -2.2 2.2]);
%! xlabel ("q");  ylabel ("p");
%! title ("odeSPVI: pendulum, h = 0.5, dense output between the steps");

%!demo
%! ## Energy error over 20 periods of Kepler's problem (eccentricity 0.6):
%! ## odeSPVI (order 6, 50 steps per period) keeps it bounded (no drift);
%! ## that of ode45 grows with time.
%! kepler = @(t, y) [y(3:4); -y(1:2) / norm(y(1:2))^3];
%! H = @(y) sum (y(:,3:4).^2, 2)/2 - 1 ./ sqrt (sum (y(:,1:2).^2, 2));
%! e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];  tf = 40*pi;
%! [t1, y1] = odeSPVI (kepler, [0 tf], y0, symplecticset ("TimeStepSize", 2*pi/50));
%! [t2, y2] = ode45 (kepler, [0 tf], y0, odeset ("RelTol", 1e-5, "AbsTol", 1e-8));
%! figure ();
%! semilogy (t1 / (2*pi), max (abs (H (y1) + 0.5), eps), "b",
%!           t2 / (2*pi), max (abs (H (y2) + 0.5), eps), "r");
%! xlabel ("periods");  ylabel ("|H(t) - H(0)|");
%! legend ("odeSPVI, h = 2\\pi/50", "ode45, RelTol = 1e-5", "location", "southeast");
%! title ("Kepler, e = 0.6: energy error");

%!demo
%! ## Events: the orbit's crossings of the q1 axis (periapsis and
%! ## apoapsis), located on the dense output; adaptive steps.
%! kepler = @(t, y) [y(3:4); -y(1:2) / norm(y(1:2))^3];
%! e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
%! opts = symplecticset ("RelTol", 1e-10, "AbsTol", 1e-12, "Refine", 4,
%!                       "Events", @(t, y) deal (y(2), 0, 0));
%! [t, y, te, ye] = odeSPVI (kepler, [0 6*pi], y0, opts);
%! figure ();
%! plot (y(:,1), y(:,2), "b", ye(:,1), ye(:,2), "ro");
%! axis equal;
%! xlabel ("q_1");  ylabel ("q_2");
%! title (sprintf ("odeSPVI: %d axis crossings, at t/pi = %s", numel (te),
%!                 mat2str (te' / pi, 6)));

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
