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
## @code{fcn = @@(t, y) [y(2); -sin(y(1))]}.  One step of size h is
##
## @example
## @group
## p(k+1) = p(k) + h * (-dH/dq + F) (t(k), q(k), p(k+1))     (implicit)
## q(k+1) = q(k) + h * dH/dp (t(k), q(k), p(k+1))            (explicit)
## @end group
## @end example
##
## @noindent
## and Newton's method solves it.  Its matrix needs the Hessian of H, taken
## from the first of: the @code{Jacobian} option (df/dy), the
## @code{HamiltonianHessFcn} option (a handle returning the Hessian), a
## second output of @var{fcn}, @code{[dy, ddy] = fcn (t, y)} with ddy the
## 2d-by-2d Hessian of H in y or its column-major vector (build it only
## when @code{nargout > 1}), and finite differences of @var{fcn}.  For
## H = T(p) + V(q) set @code{Separable} to @qcode{"on"}: the step is then
## explicit, two calls of @var{fcn} and no Newton.
##
## @strong{Why a fixed step.}  With @code{TimeStepSize} (or
## @code{TimeStepNumber}) every step is one and the same symplectic map,
## and such a map follows the exact flow of a modified Hamiltonian within
## O(h) of H: the energy error oscillates at size O(h) and does not drift,
## however long the run, and the momenta of the symmetries of H (angular
## momentum for a central force) are conserved to round-off.  Adaptive
## steps, the default as in @code{ode45}, control the local error
## instead; a new step size is a new map, so this guarantee is lost, and
## on fast oscillations the step sizes lock to their phase and can drain
## their energy.  For long runs use a fixed step.  (@code{StepControl}
## @qcode{"reversible"}, the adaptive steps that keep the energy bounded,
## needs a symmetric method: @code{odeSV} or @code{odeSPVI}; odeSE
## refuses it.)
##
## @var{tspan} is [t0, tf] (a row at every step) or more times (rows
## exactly there, from the dense output, steps unchanged); tf < t0 runs
## backwards.  @var{opts} comes from @code{symplecticset} or
## @code{odeset} ([] for the defaults); an option no solver knows is
## said, with the nearest known name.  @var{par1}, @dots{} are passed to
## @var{fcn} and the other functions after t and y; without @var{opts}
## they may follow @var{y0} directly (the 2013 form
## @code{odeSE (fcn, tspan, y0, par1, @dots{})}).  @var{t} is a column
## and @var{y} has a row per time.  @var{sol} has the fields of
## @code{ode45}: x, y, solver, xe, ye, ie (with Events) and stats; with
## @code{Dense} @qcode{"on"} also the dense output that @code{symdeval}
## evaluates, with @code{Hamiltonian} the values H of H at x.  With no
## output the solution is plotted with @code{odeplot}.
##
## @strong{Ensembles.}  With @code{Ensemble} @qcode{"on"}, each column of
## @var{y0} (2d-by-K) is the initial state of a member, and the K members
## are integrated together, each exactly as a run of its own would be:
## with a fixed step, member k's rows equal those of a run from
## @code{y0(:,k)} to the bit, whatever K or the order of the columns.
## @var{y} is then numel(@var{t})-by-2d-by-K, @code{y(:,:,k)} member k's
## rows on the times @var{t} that the members share (the fixed steps, or
## the times of @var{tspan}); a member that stops early (a terminal
## event, a failure) has NaN rows from there, the state at its event
## being in @var{ye}.  @var{ie} has two columns, the event's index and
## the member's, and the events come member by member.  @var{sol} is a
## 1-by-K struct array, @code{sol(k)} member k's as its own run returns
## it.  Adaptive steps are each member's own: @code{[t, y]} needs output
## times in @var{tspan} then, or ask for @var{sol}.  With
## @code{Vectorized} @qcode{"on"}, one call of @var{fcn} evaluates the
## states of all members at once (a lone state comes as two equal
## columns), so that the members share the cost of a call; members are
## to the bit as their own runs when @var{fcn} computes a column alike in
## any batch.  Without it @var{fcn} is called for each state.  Newton's
## method works member by member; a member that fails stops alone, with
## a warning that names it.  @code{OutputFcn} is called at each shared
## time once every running member has reached it, with the column of all
## members' states (the @code{OutputSel} components of member 1, then of
## member 2, @dots{}); @code{Stats} sums the members' counts.
## @code{Parallel}, a number of processes, splits the members across
## them (package @code{parallel}); given the connections of
## @code{pconnect}, across servers on other machines.  The results are
## the same to the bit.
##
## @table @code
## @item TimeStepSize, TimeStepNumber
## Fixed step h, or a number of fixed steps.  The last step ends on tf.
## @item RelTol, AbsTol, NormControl, InitialStep, MaxStep
## Adaptive steps, as in @code{ode45} (defaults 1e-3, 1e-6, off,
## automatic, |tf-t0|/10); given with a fixed step they are ignored, with
## a warning.  The error estimate is the distance to the trapezoidal rule
## through the step's ends.
## @item Separable (alias Explicit)
## @qcode{"on"} for H = T(p) + V(q), with no forcing that depends on p.
## An @var{fcn} that shows otherwise gets a warning.  Default
## @qcode{"off"}.
## @item SecondOrder
## @qcode{"on"}: @var{fcn} returns the acceleration, @code{a = fcn (t,
## q)} (-dV/dq for H = |p|^2/2 + V(q)), a column of length d, and y =
## [q; v] with v = dq/dt; the steps are the explicit ones, one call of
## @var{fcn} each.  Default @qcode{"off"}.
## @item Jacobian, HamiltonianHessFcn
## Sources of Newton's matrix (above); @code{sol.stats.jacobian_source}
## says which one served.  A sparse one keeps the implicit solves
## sparse; the one call of the function at (t0, y0) that tells is
## counted in @code{npds}.
## @item JPattern
## The nonzero pattern of df/dy (2d-by-2d, sparse or full): finite
## differences then step the columns that share no row together, a few
## calls of @var{fcn} for a banded system instead of 2d.  Given as a
## sparse matrix, the matrices it makes are sparse too.
## @item NewtonTol, MaxNewtonIterations
## Newton's relative tolerance (1e-14; fixed steps converge to
## NewtonTol/1000) and iterations per solve (10).
## @item Vectorized
## @qcode{"on"}: @var{fcn} takes a 2d-by-k matrix of states and a 1-by-k
## row of times; finite-difference matrices then take one call.
## @item Events, OutputFcn, OutputSel, Refine, Stats
## As in @code{ode45}.  Events are located on the dense output (cubic
## Hermite between the step points); two zeros between two step points
## are missed, as in @code{ode45} (a shorter step closes the gap).
## @code{Refine} adds interpolated rows: by default 4 rows per step of an
## adaptive run, as @code{ode45}, and the step points alone (the grid of
## h) with a fixed step.  @code{Stats} prints the counts that
## @code{sol.stats} holds.
## @item Hamiltonian
## A handle @code{H (t, y, par1, @dots{})}: @code{sol.H} holds its values
## at @code{sol.x}, and @code{sol.stats.max_dH} and @code{Stats} the
## largest relative change from H(t0) (absolute if H(t0) = 0).
## @item Dense
## @qcode{"on"}: @var{sol} keeps each step's dense output, for
## @code{symdeval}.
## @item MaxSteps
## Largest number of steps of a run (default: no limit).
## @item Ensemble, Parallel
## @qcode{"on"}: the columns of @var{y0} are members (above); the
## processes, or the servers' connections, to split them across
## (default 1: this process).
## @end table
##
## A run that cannot go on (Newton fails, @var{fcn} returns NaN or Inf,
## MaxSteps is reached) warns, with an identifier @code{symplectic:@dots{}},
## and returns every row computed so far.
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
  if (nargin >= 4 && isstruct (varargin{4})
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
%! ## Phase portrait of the pendulum H = p^2/2 - cos(q): librations inside
%! ## the separatrix, rotations outside, all with one fixed step h = 0.05.
%! pendulum = @(t, y) [y(2); -sin(y(1))];
%! opts = symplecticset ("TimeStepSize", 0.05);
%! figure ();
%! hold on;
%! for q0 = [0.5, 1, 1.5, 2, 2.5, 3]
%!   [t, y] = odeSE (pendulum, [0 17], [q0; 0], opts);
%!   plot (y(:,1), y(:,2), "b");
%! endfor
%! for p0 = [2.2, 2.6, -2.2, -2.6]
%!   ## rotations: from one end of [-pi, pi] across to the other
%!   [t, y] = odeSE (pendulum, [0 8], [-pi*sign(p0); p0], opts);
%!   plot (y(:,1), y(:,2), "r");
%! endfor
%! hold off;
%! axis ([-pi pi -3 3]);
%! xlabel ("q");  ylabel ("p");
%! title ("odeSE: phase portrait of the pendulum, h = 0.05");

%!demo
%! ## Energy error over time: symplectic Euler with a fixed step keeps it
%! ## bounded (of size h, no drift); that of ode45 (default tolerances)
%! ## grows with time.
%! pendulum = @(t, y) [y(2); -sin(y(1))];
%! E = @(y) y(:,2).^2/2 - cos (y(:,1));
%! y0 = [2; 0];  tf = 200;
%! opts = symplecticset ("TimeStepSize", 0.05, "Separable", "on");
%! [t1, y1] = odeSE (pendulum, [0 tf], y0, opts);
%! [t2, y2] = ode45 (pendulum, [0 tf], y0);
%! dE1 = max (abs (E (y1) - E (y0')), eps);
%! dE2 = max (abs (E (y2) - E (y0')), eps);
%! figure ();
%! semilogy (t1, dE1, "b", t2, dE2, "r");
%! xlabel ("t");  ylabel ("|H(t) - H(0)|");
%! legend ("odeSE, h = 0.05", "ode45", "location", "southeast");
%! title ("Pendulum: energy error");
%! printf ("max energy error in the first and the last tenth of [0, %g]:\n", tf);
%! printf ("  odeSE %.2e %.2e\n", max (dE1(t1 <= tf/10)), max (dE1(t1 >= 0.9*tf)));
%! printf ("  ode45 %.2e %.2e\n", max (dE2(t2 <= tf/10)), max (dE2(t2 >= 0.9*tf)));

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
