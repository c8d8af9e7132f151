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
## a column of length 2d (any real numeric class, or a row or sparse:
## taken as a full double column; logical, char or complex values are
## errors, as are NaN or Inf at t0).  The method is the variant with p
## implicit and q
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
## method to near machine precision, started from the values of p(k+1) at
## the last steps: the errors of an explicit start (p(k) + h f_p(t(k),
## y(k)) when f there is known, else the last step's increment of p) over
## up to 16 steps, extrapolated by the polynomial of degree (up to 14)
## that would have predicted the newest of them best.  On a non-separable
## H at a fixed step this makes a step cost about as many evaluations of
## @var{fcn} as the explicit separable one (2.00 per step in
## @file{tests/test_se_sv.m}, 4.0 from the explicit start alone; from
## t0 = 1e8 the same).  A solve from there that fails (Newton, or
## @var{fcn} NaN or asking for a smaller step) is tried again from the
## explicit start.
##
## @strong{Arguments} are those of @code{ode45}: @var{tspan} = [t0, tf]
## returns a row at every step; with more than two (strictly monotonic)
## elements, rows exactly at those times, taken from the dense output
## without shortening any step.  tf < t0 integrates backwards.  @var{y0} =
## [q0; p0] is a real vector of even length (row or column).  @var{opts}
## is a struct, or any empty value (@code{[]}, @code{@{@}}, an empty
## string) for the defaults.  Extra arguments @var{par1}, @dots{} come
## after it and are passed to @var{fcn} (and to the
## Jacobian, Hessian, Events and OutputFcn functions) after t and y;
## unlike Octave's @code{ode45}, a fourth argument that is neither a struct
## nor empty is refused rather than taken as @var{par1} (pass [] before
## the parameters).  @var{t} is a column; @var{y} has one row per time, in
## double precision whatever the class of @var{tspan} and @var{y0}.  With
## one output, @var{sol} is a struct with the fields of @code{ode45}:
## @code{x} (row of times), @code{y} (one column per time),
## @code{solver}, @code{xe}, @code{ye}, @code{ie} (with Events) and
## @code{stats}.  With no output the solution is plotted with
## @code{odeplot}.
##
## @strong{Options} (@code{odeset} fields, or @code{symplecticset} for the
## package's own fields without warnings; names match in any case, and a
## struct that sets one of these options in two spellings is refused):
##
## @table @code
## @item TimeStepSize, TimeStepNumber
## Fixed step h (the last step ends exactly on tf) or a fixed number of
## steps: no error control; the geometric guarantees hold in this mode.
## Every step is h itself, the same map at any t, and ends at t0 + k h
## rounded once (the rows' times), so a run from t0 = 1e8 takes the same
## steps as one from 0; only a last step that h does not fit ends on tf
## with what is left of the span.  Without them the step is adaptive.
## @item RelTol, AbsTol, NormControl, InitialStep, MaxStep
## Adaptive mode, scaled as in @code{ode45} (defaults 1e-3, 1e-6, off,
## automatic, |tf-t0|/10; MaxStep = Inf: no cap; InitialStep = Inf: the
## first step as long as MaxStep and @var{tspan} allow, as in
## @code{ode45}).  The local error
## estimate is the difference to the trapezoidal rule built from @var{fcn}
## at both ends of the step, y(k+1) - y(k) - h/2 (f(k) + f(k+1)), of size
## O(h^2) like the method's local error; it costs one evaluation of
## @var{fcn} per step (shared with the next step).  After an accepted
## step the next step is the smaller
## of the classical choice, 0.9 (1/err)^(1/(p+1)) times the last, and the
## one that follows the change of the error over the last two accepted
## steps (predictive control), so that where the error grows along the
## solution steps do not alternate between failed and accepted (the same
## in all three solvers).  No step is shorter than 16 ulps of t (below
## that the round-off of t swamps the step): a smaller step asked for by
## the controller or by the default MaxStep is raised to it, so that spans
## only a few ulps wide are integrated too; a step that fails at that size,
## or a MaxStep set below it, ends the run with the warning
## @qcode{"symplectic:step-size"}.  The times of the steps are summed
## with their round-off carried along (as Octave's own solvers sum
## them), and what would be left after a step joins it when it is below
## the least step: steps of a MaxStep that divides the span end on
## @var{tf}, that many of them, with no short last step (as in
## @code{ode45}).  A MaxStep that would take more than
## 1e12 steps is refused, as such a TimeStepSize is, and a RelTol below
## 100*eps is raised to it with the warning @qcode{"symplectic:tolerance"}
## (near t = 0 the least step bounds neither).
## Adaptive steps of @code{odeSE} and @code{odeSV} do not keep the energy
## of fast oscillations: the local error of an oscillating component
## vanishes twice per period, the step sizes follow that phase, and a
## step sequence locked to the phase moves the oscillation's energy
## steadily.  On two oscillators of frequencies 1 and 100, the fast one
## at amplitude 1e-3, over [0, 100] (@file{bench/adaptive_runs.m}), the
## fast oscillator's energy at the end, relative to its start, is:
##
## @multitable @columnfractions .28 .18 .18 .18 .18
## @headitem RelTol, AbsTol @tab @code{odeSE} @tab @code{odeSV} @tab @code{ode45} @tab @code{odeSPVI}
## @item default @tab 0.011 @tab 3.64 @tab 0.555 @tab 1
## @item 1e-3, 1e-3 @tab 1.4e-5 @tab 5.9e5 @tab 30.2 @tab 1
## @item 1e-4, 1e-4 @tab 1.2e-6 @tab 74.9 @tab 0.95 @tab 1
## @item 1e-6, 1e-6 @tab 5.4e-7 @tab 1.3 @tab 0.95 @tab 1
## @end multitable
##
## @noindent
## (@code{odeSPVI} within 6.3e-5 of 1 all along).  A fixed step keeps it:
## @code{odeSV} with TimeStepSize = 0.002 stays within 0.01 of 1 (the
## method's own oscillation of the energy, (w h)^2/4), however long the
## run (@file{tests/test_se_sv.m}).  For such systems use a fixed step, or
## @code{odeSPVI}.
## @item Separable
## @qcode{"on"} for H = T(p) + V(q) with no forcing that depends on p: the
## step is explicit, two evaluations of @var{fcn} per step and no Newton.
## Those two evaluations are at the same q and t with two values of p, so
## a dH/dq (with the forcing) that changes with p shows there: the run
## then warns, once, with the identifier @code{symplectic:not-separable}
## (@code{odeSV}'s are at the same p with two q, so it warns when dH/dp
## changes with q, or with t).  The explicit step of an H that is not
## separable is not the method: of lower order, and not symplectic.
## @item Jacobian, HamiltonianHessFcn
## Newton's matrix needs df/dy = J * Hess(H), J = [0 I; -I 0], taken from
## the first of: the @code{Jacobian} option (matrix or handle returning
## df/dy); @code{HamiltonianHessFcn}, a handle returning Hess(H); a second
## output of @var{fcn} giving Hess(H) (2d-by-2d or its column-major vector
## of (2d)^2 elements, as in @code{[dy, ddy] = fcn (t, y)}); finite
## differences of @var{fcn} (2d extra evaluations; steps of sqrt(eps)
## times each component's size, the largest it has had in the run, and at
## least 1e-6 times the largest size among q's components for q's, among
## p's for p's: a problem and the same problem scaled take the same
## steps; backward steps, all of them, where @var{fcn} is NaN or Inf at a
## forward one, as at the edge of its domain).  With a forcing term the Hessian misses dF/dy and Newton
## works as a quasi-Newton method; a
## Hessian off by a moderate factor (0 to 10, or of the wrong sign) costs
## iterations, not accuracy.  When Newton fails with the Jacobian or
## Hessian given and it differs from finite differences of @var{fcn} at
## the step's start by more than a tenth of their largest entry (a strong
## damping, a wrong Jacobian), or when it has a NaN or Inf where
## @var{fcn} is finite, finite differences serve for the rest of
## the run and the step is tried again; @code{stats.jacobian_source} then
## says from which t.  (At most three checks that agree are made in a
## run: each costs a Jacobian and 2d+1 calls of @var{fcn}.)  Newton's
## stopping test measures its corrections, so a matrix too large by many
## orders of magnitude (1e12) would make them tiny and pass unconverged
## steps as converged.  So the first Jacobian or Hessian given is probed
## at its point, at the cost of two calls of @var{fcn} (one when it is
## the second output of @var{fcn}): the change of @var{fcn} over a small
## step along one direction (the opposite one where @var{fcn} is NaN or
## Inf there; no probe if it is both ways) against df/dy times that
## step.  When they
## differ by more than 100 times the change, finite differences serve
## from there on (@code{stats.jacobian_source} says from which t); a
## matrix too small, of the wrong sign or missing dF/dy is left to the
## check above.
## @code{stats.jacobian_source} says which was used.  Sparse matrices
## (here, in the other options, in @var{tspan}, @var{y0} and in what
## @var{fcn} returns) are taken as full.
## @item NewtonTol, MaxNewtonIterations
## Newton's stopping tolerance (1e-14 relative) and iterations (10).  With
## a fixed step (here and in @code{odeSV}) each solve is converged to
## NewtonTol/1000: the Newton matrix is kept across steps, so the error a
## stop leaves has the same sign from step to step and adds up.  On the
## non-separable rotation-invariant H of @file{tests/test_se_sv.m} (h =
## 0.05, 10000 steps) the angular momentum drifted at NewtonTol itself by
## 1.5e-13 to 7.8e-13 (@code{odeSE} or @code{odeSV}, with the Hessian
## given or finite differences); at NewtonTol/1000 it stays within 1e-14,
## as round-off does, for at most 12% more calls.  A solve that stops on
## a correction
## of round-off size has f at the iterate before it, moved to the result
## by the Jacobian (used unmoved, that error of a few ulps kept its sign
## too: 1.5e-13 over 10000 steps with the Hessian given, 9e-15 moved).
## In adaptive runs, NewtonTol.
## @item Events, OutputFcn, OutputSel, Refine, Stats
## As in @code{ode45}; also, scalar ISTERMINAL and DIRECTION hold for every
## element of VALUE, @code{OutputSel} may be a logical mask, and the
## options that take @qcode{"on"} or @qcode{"off"} take true or false too.
## @code{OutputFcn} is called with the flag @qcode{"init"}, then
## @qcode{""} with each row (an empty char; @code{ode45} passes [] there:
## test it with @code{isempty}), then @qcode{"done"}.  A value that
## @code{OutputFcn} returns stops the run when @code{if} would take it as
## true (all its elements nonzero; a char too); NaN, and values other
## than logical, char or real numeric, are errors.  Event times, output
## times and refined rows come
## from the dense output (cubic Hermite interpolation between steps, from
## @var{fcn} at the step points).  An event counts where its function
## changes sign or becomes zero (in the chosen direction) after t0,
## between the points where the Events function is evaluated: the step
## points (and in @code{odeSPVI}, whose steps are long, more points
## inside each step: see its help).  Two zeros between two such points
## (the function back to its sign) are not seen, as in @code{ode45};
## @code{MaxStep} or a smaller TimeStepSize closes the gap.
## A zero at t0 itself is not reported, a zero that touches without a
## change of sign only when it falls on such a point.  An Events function
## whose VALUE is empty at t0 gives no events; a NaN in VALUE is an error
## (it has no sign); DIRECTION must hold -1, 0 or 1 (other values, which
## @code{ode45} takes as a direction that never occurs, are errors).
## Events located at the time of a terminal event (within the round-off
## of their location) are reported with it.  @var{te} and @var{ie} are
## columns, @var{ye} has a row per event (@code{sol.xe}, @code{sol.ye},
## @code{sol.ie} likewise); with no event all three are 0-by-0, as in
## @code{ode45}.
## @code{Refine}
## (default 1: step points only, where the method's properties hold) adds
## interpolated rows between steps; as in @code{ode45} it is ignored with
## more than two @var{tspan} elements and for the @var{sol} output.
## @code{Stats} prints steps, failed
## steps, @var{fcn} calls, Newton iterations, Jacobian/Hessian evaluations
## and LU factorizations.  Whatever @code{Stats}, @code{sol.stats} holds
## the counts: @code{nsteps} (accepted steps), @code{nfailed} (steps
## tried again, for the error test or a Newton failure), @code{nfevals}
## (calls of @var{fcn} for f, a Vectorized call counting once; those for
## finite-difference matrices included), @code{nstates} (states those
## calls evaluated: a Vectorized call of k columns counts k),
## @code{nfdevals} (of @code{nfevals}, the calls for finite-difference
## matrices and for the probe of a given Jacobian or Hessian), @code{npds}
## (evaluations of the matrix given: calls of the Jacobian function or
## of @code{HamiltonianHessFcn}, uses of a constant Jacobian matrix, or
## calls of @var{fcn} for its second output), @code{nnewton} (Newton
## iterations), @code{ndecomps} (LU factorizations), @code{nlinsols}
## (linear solves with them) and @code{jacobian_source} (where Newton's
## matrix came from).  @var{fcn} is called @code{nfevals + npds} times
## when Newton's matrix comes from its second output, else
## @code{nfevals} times.
## @item Vectorized
## @qcode{"on"}: @var{fcn} accepts a 2d-by-k matrix of states with a 1-by-k
## row of times.  @code{odeSE} steps one state at a time; its
## finite-difference Jacobians (no Jacobian or Hessian source) then take one
## call for their 2d perturbed states instead of 2d calls.
## @item NonNegative, Mass
## Not supported (a projection onto y >= 0 would break the symplectic map;
## Hamilton's equations have no mass matrix): ignored with the warning
## @qcode{"symplectic:unsupported-option"}.  The other fields of
## @code{odeset} are hints for other solvers and are ignored.
## @end table
##
## A run that cannot go on (Newton fails with the fixed step or at the
## smallest adaptive step, @var{fcn} keeps returning NaN, or a step's
## result overflows, as an unstable fixed step's does in the end: that
## step is refused) warns and returns every row computed so far, all
## finite.  The warnings' identifiers are
## @code{symplectic:newton-failed}, @code{symplectic:nonfinite},
## @code{symplectic:step-size}, @code{symplectic:max-steps},
## and @code{symplectic:output-stop} (OutputFcn asked to stop before tf;
## no event after the row where it stopped is returned), and
## @code{symplectic:tolerance} for a RelTol raised to 100*eps,
## @code{symplectic:tspan-beyond-end} for output times after the end of
## TimeStepNumber steps, @code{symplectic:not-separable} (see
## @code{Separable}); an error in a
## function of the user's ends the run with that error; bad
## arguments raise errors with the identifier
## @code{Octave:invalid-input-arg} whose message begins with the solver's
## name, and a NaN or Inf from @var{fcn} at t0 (where no smaller step can
## help) an error with the identifier @code{symplectic:nonfinite}.
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
