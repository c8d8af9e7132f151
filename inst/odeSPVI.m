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
## Solve Hamilton's equations with a spectral variational integrator of any
## order.
##
## @var{fcn} returns Hamilton's equations for y = [q; p], q, p in R^d:
## @code{dy = fcn (t, y) = [dH/dp; -dH/dq + F(t, q, p)]}, F an optional
## forcing term.  It may return the Hessian of H as a second output
## (@code{[dy, ddy] = fcn (t, y)}, ddy 2d-by-2d or its column-major vector).
##
## On each step [t(k), t(k)+h], mapped to z in [-1, 1], q is a polynomial
## in the Legendre basis, q(z) = sum_i a_i l_i(z), i < n = @code{Q_DoFs},
## and the action is approximated by Gauss--Legendre quadrature on
## m = @code{Nodes} nodes z_j (weights w_j) with nodal momenta p_j.
## Stationarity of the discrete action gives, for each component:
##
## @example
## @group
## sum_j w_j [p_j l_s'(z_j) + h/2 l_s(z_j) fp(q(z_j), p_j)]
##                 + l_s(-1) p(k) - l_s(1) p(k+1) = 0,   s < n
## fq(q(z_r), p_r) - 2/h sum_i a_i l_i'(z_r) = 0,        each node r
## q(-1) = q(k),   q(k+1) = q(1)
## @end group
## @end example
##
## @noindent
## (fq = dH/dp, fp = -dH/dq + F), solved by a simplified Newton method in C
## to near machine precision, started from the previous step's polynomials.
## The method is symplectic and variational: with a fixed step the energy
## error stays bounded over very long runs and momenta are conserved to
## round-off.
##
## @strong{Order.}  Pairs are written (n, m) = (Q_DoFs, Nodes) here and
## below.  The order is 2*min(n-1, 2m-n+1):
##
## @multitable @columnfractions .2 .2 .2 .4
## @headitem Q_DoFs n @tab Nodes m @tab order @tab note
## @item 2 @tab 1 @tab 2 @tab implicit midpoint rule
## @item 3 @tab 2 @tab 4 @tab 2-stage Gauss collocation
## @item 4 @tab 2 @tab 2 @tab loses order (n-1 > m)
## @item 3 @tab 3 @tab 4 @tab
## @item 4 @tab 3 @tab 6 @tab default; 3-stage Gauss collocation
## @item 5 @tab 3 @tab 4 @tab loses order (n-1 > m)
## @item m+1 @tab m @tab 2m @tab the best n for m nodes
## @end multitable
##
## Pairs with n > 2m (such as (3,1) or (5,2)) do not converge and are
## refused with an error; pairs with n-1 > m lose order as the table shows,
## and are degenerate: their extra modes of q are fixed only by the
## curvature d2H/dq2.  Where it vanishes (a free particle, a constant
## force) Newton's matrix is singular and the run stops at t0 whatever
## the step (tests/test_spvi.m); where it is small (a pendulum near
## q = pi/2) their local error grows and Newton may fail at some steps.
## (4,2) reaches its order on a pendulum from q = 1 (tests/test_spvi.m);
## use n <= m+1 otherwise.
## @code{sol.order} gives the order actually used (see RelTol below for
## adaptive runs).
##
## @strong{Options} (@code{odeset} fields, or @code{symplecticset} for the
## package's own fields without warnings; names match in any case, and a
## struct that sets one of these options in two spellings is refused):
##
## @table @code
## @item Nodes (alias P_DoFs), Q_DoFs, PolynomialDegree
## m (default 3), n (default m+1); @code{PolynomialDegree} sets
## n = degree+1 (and m = degree+1 unless @code{Nodes} is given).  Two
## names of one number (Nodes and P_DoFs; Q_DoFs and PolynomialDegree)
## may both be given only with values that agree.  Many nodes work at
## long steps: each step starts from the last step's polynomials
## extrapolated, with only their modes above the solve's round-off (the
## extrapolation amplifies the others like 5.8^Nodes); on the rotation
## H = (q^2+p^2)^2/4 from (1, 0.5) with h = 1, Nodes = 20 and 30 run to
## t = 40 within 1e-12 of the exact solution (@file{tests/test_spvi.m}).
## A fixed step that Newton cannot solve from its start is reached from
## shorter steps (h/2, h/4, ... down to h/64, each solution extended as
## the start of the step twice as long): on that rotation h = 2 with
## Nodes = 8 and h = 2.5 with Nodes = 12 failed at the first step and
## now reach t = 40 with errors of 3.4e-10 and 4.5e-14.
## @item TimeStepSize, TimeStepNumber
## Fixed step (the last step ends exactly on tf) or a fixed number of
## steps: no error control; the geometric guarantees hold in this mode.
## Every step is h itself and ends at t0 + k h rounded once, as in
## @code{odeSE}.
## @item RelTol, AbsTol, NormControl, InitialStep, MaxStep
## Adaptive mode (the default), scaled as in @code{ode45} (defaults,
## InitialStep and MaxStep as in @code{odeSE}).  The local error
## is estimated, as in the original method, by a companion solution on the
## same step with one more mode and one more node (n+1, m+1), started from
## the lower-order solution.  The run then advances with the companion's
## value (local extrapolation, as @code{ode45} advances with the higher
## order of its pair), so the achieved error follows the tolerance: on
## Kepler (e = 0.6, one period) RelTol = AbsTol = 1e-10 gives an end-point
## error of 5e-11.  @code{sol.order} is then the companion's order
## (8 for the default pair).  Neither solve of an adaptive step is
## converged to round-off (for the pairs Q_DoFs = Nodes+1): the
## lower-order one, which only enters the estimate, stops when its error
## is below 1e-3 of the smallest error the tolerances allow
## (min_i max(AbsTol, RelTol*|y_i|)), the companion's below 1e-4 of it,
## neither below NewtonTol/100: fewer calls than solves to round-off, and
## the end-point error still follows the tolerance: on Kepler (e = 0.6,
## 10 periods, RelTol = AbsTol = 1e-4 to 1e-12) it shrinks at least 30
## times per factor 100, to a few 1e-12 at 1e-12, where the round-off of
## the solves decides (6e-14 to 4.5e-12 for the orbit turned by angles up
## to 1.1e-14 rad, @file{tests/test_spvi.m}).  The step size follows
## the trend of the error over the last two accepted steps as well as its
## size (predictive control, see @code{help odeSE}): on the same runs at
## most 16% of the attempted steps fail (24 of 157 at RelTol 1e-4, 15 of
## 419 at 1e-8), against 26-28% without it at RelTol 1e-4 to 1e-8.  With
## that, and
## the companion's Newton matrices interpolated from the method's node
## Jacobians of the same step (no call of @var{fcn}), the runs make
## 3635 4750 8005 13330 24879 evaluations of f and of its Jacobian (each
## counted once, as separate callbacks; with the Hessian as second output
## of @var{fcn} that is nfevals + 2*npds; these are the C tests' counts,
## and the same runs from Octave count one more) at RelTol 1e-4 to 1e-12,
## against 4765 6876 10763 14356 24398 before both: 7-31% fewer down to
## 1e-10, 2% more at 1e-12.
## @item Jacobian, HamiltonianHessFcn
## Newton's matrix needs df/dy = J * Hess(H) at the nodes, from the first
## of: the @code{Jacobian} option (matrix or handle returning df/dy);
## @code{HamiltonianHessFcn} (handle returning Hess(H)); the second output
## of @var{fcn}; finite differences of @var{fcn} (steps of sqrt(eps) times
## each component's size, the largest it has had in the run, and at least
## 1e-6 times the largest size among q's components for q's, among p's
## for p's: a problem and the same problem scaled take the same steps).
## The matrix is kept and
## reused while Newton converges fast, or new on every step (see
## NewtonMatrix).  @code{stats.jacobian_source} tells
## which source was used.  A Jacobian or Hessian given is dropped for
## finite differences as in @code{odeSE}: when Newton fails with it and it
## disagrees with them, or when the first one differs from the change of
## @var{fcn} along one direction by more than 100 times that change (a
## matrix far too large, which would let unconverged steps pass as
## converged; this probe costs one or two calls of @var{fcn} in a run).
## With the second output of @var{fcn}, one call
## with two outputs gives both the Hessian and f at a node, and the
## residual there uses that f: @code{stats.npds} counts these calls and
## @code{stats.nfevals} the calls with one output, so that their sum is
## the number of calls of @var{fcn}.
## @item Vectorized
## @qcode{"on"}: @var{fcn} accepts a 1-by-k row of times and a 2d-by-k
## matrix of states and returns 2d-by-k; all quadrature nodes of a Newton
## iteration are then evaluated in one call, and a finite-difference
## matrix (no Jacobian or Hessian source) takes one call for all nodes
## and their 2d perturbed states each; such a matrix is then new on every
## step (NewtonMatrix @qcode{"auto"}), so that a step often needs one call
## in all: 1.57 calls per step on Kepler with the default pair and
## TimeStepSize = 2*pi/100.  The Hessian (from any source) is asked for
## one node at a time.  For long runs this is the fastest form: Kepler
## (e = 0.6) over 1000 periods with Nodes = 8, Q_DoFs = 9 and
## TimeStepSize = 2*pi/30 keeps the energy error at 3e-12 in about 1/50
## of the time @code{ode45} needs at RelTol = AbsTol = 1e-10, whose
## energy error grows linearly (8.5e-9 after 100 periods;
## @file{bench/run_benchmarks.m}, P5).
## @item NewtonMatrix
## @qcode{"kept"}: Newton's matrix (from the node Jacobians) and its LU
## are kept across steps while Newton converges fast; between
## evaluations the node Jacobians are extrapolated in time.  Two
## corrections per step are typical (2.37 on Kepler, (4,3), h = 2*pi/100,
## with the Hessian as second output of @var{fcn}: 7.11 calls per step,
## 0.57 of them with two outputs).
## @qcode{"new"}: a new matrix at every step's predicted start, whose
## first correction is then exact Newton; the step stops after it when
## its quadratic error, estimated from earlier steps, is far below
## NewtonTol (1.57 corrections per step on Kepler: with the Hessian as
## second output of @var{fcn}, 3 calls with two outputs and 1.71 with one
## per step).  Fewer calls, but Hessians on every step: faster when the
## Hessian is cheap beside f.  Default @qcode{"auto"}: @qcode{"new"} with
## Vectorized finite-difference matrices of at most 64 unknowns
## ((Q_DoFs-1+Nodes)*d), else @qcode{"kept"}.  Both converge every step to
## round-off (within 3e-16 of a tightly converged step on Kepler).  Only
## the pairs Q_DoFs = Nodes+1 (the default) use it; the others always
## keep their matrix.
## @item NewtonTol, MaxNewtonIterations
## Newton's stopping tolerance (1e-14 relative) and iterations (10).  With
## a fixed step the result of a step is converged to NewtonTol/100; in
## adaptive mode see RelTol.  That keeps Kepler's angular momentum at
## round-off (1000 periods), but the error left has a sign that can
## persist from step to step: on a non-separable rotation-invariant H in
## 3-D the angular momentum drifted by 2.1e-13 over 10000 steps, and
## NewtonTol = 1e-16 kept it at round-off (3e-15) for 10% more calls
## (@file{tests/test_spvi.m}).
## @item Events, OutputFcn, OutputSel, Refine, Stats
## As in @code{ode45} (arguments, outputs and events as in @code{help
## odeSE}); output times, refined rows and event locations come
## from the method's own dense output: for the pairs Q_DoFs = Nodes + 1
## (the default), the integral of the polynomial through y' at the step's
## ends and at the nodes of the solve the run advances with (the companion
## of one more node in adaptive runs), which ends on the step's value.  It
## costs a call of @var{fcn} at each step's end (at most one per step, and
## only for steps with output or an event inside); its local error is
## O(h^(Nodes+3)) in adaptive runs and O(h^(Nodes+2)) with a fixed step.
## Kepler (e = 0.6), one period, 401 output times: at RelTol = AbsTol =
## 1e-10 within 2.6e-10 of the exact solution (the step points 5e-11;
## @code{ode45} 7.4e-9), and with TimeStepSize = 2*pi/200 within 1.3e-7, as
## the step points (tests/test_spvi.m).  In adaptive runs the error at
## output times is of the order of the tolerance (their local error is
## that of the estimate), while the step points, advanced with the
## companion, are often far more accurate: the pendulum from q = 1,
## p = 0.5 over [0, 10] at RelTol = 1e-9, AbsTol = 1e-12 is within 1.2e-9
## at 1001 output times and 6.1e-12 at its 55 step points.  The other
## pairs use, below order 8, the cubic Hermite interpolant through the
## step's ends (@var{fcn} there, as above): error O(h^min(4, order)), as
## small as the step points' up to order 4 (oscillator, h = 0.025: (3,3)
## 1.2e-9 between the steps, 8.4e-10 at them).  From order 8, and for a
## step with NaN or Inf from @var{fcn} at an end, the solution's own
## polynomials (q(z), and the polynomial through p(k), the nodal p_j and
## p(k+1)), whose error is O(h^(order/2)): (5,5), h = 0.05: 1.4e-9,
## against 1.6e-8 for the Hermite interpolant of (4,4).  In adaptive runs
## of these pairs the steps follow the companion's higher order and the
## cubic's O(h^4) dominates between them: the oscillator over [0, 10] at
## RelTol = AbsTol = 1e-9 is within 2.6e-7 at output times with (3,3)
## and 2.3e-5 with (4,4) (6e-12 at the step points; the default pair
## 6.6e-10).
## @code{Refine} defaults to 1 (step points only); as in
## @code{ode45} it is ignored with more than two @var{tspan} elements and
## for the @var{sol} output.
## With Events the Events function is also evaluated at Nodes equally
## spaced points inside every step, on the dense output, and where the
## parabola through three neighbouring values of one of its components
## turns back across zero between two of them, at that turning point
## too: a pair of zeros inside one long step is then found.  q = sin t
## crossing 0.99 or 0.999 (for 0.28 or 0.09 of every 2*pi) over [0, 20]
## gives all 6 events at RelTol = AbsTol = 1e-3 to 1e-8, where the sign
## changes between step points alone (steps of 0.3 to 1.5) are 0 to 4
## of them.  Over 40 phases, q = sin (t + phi), all 255 crossings of 0.99
## are found at 1e-3 and 1e-4, and of 0.999 at 1e-4, but only 217 at 1e-3
## (13 phases miss some; tests/test_spvi.m): narrower excursions, against
## longer steps, can be missed, which @code{MaxStep} prevents.  On every
## step this costs Nodes calls
## of the Events function and the call of @var{fcn} at the step's end
## (above): on Kepler with a fixed step 2*pi/100 and an @var{fcn} without
## the Hessian (finite-difference matrices), 10.4 instead of 9.4 calls of
## @var{fcn} per step.
## @end table
##
## A run that cannot go on (Newton fails with the fixed step or at the
## smallest adaptive step, @var{fcn} keeps returning NaN, or a step's
## result overflows, as an unstable fixed step's does in the end: that
## step is refused) warns and returns every row computed so far, all
## finite.  The warnings' identifiers are
## @code{symplectic:newton-failed}, @code{symplectic:nonfinite},
## @code{symplectic:step-size}, @code{symplectic:max-steps},
## and @code{symplectic:output-stop} (and those of @code{help odeSE}); an
## error in a function of the user's ends the run with that error; bad
## arguments raise errors with the identifier
## @code{Octave:invalid-input-arg} whose message begins with the solver's
## name, and a NaN or Inf from @var{fcn} at t0 (where no smaller step can
## help) an error with the identifier @code{symplectic:nonfinite}.
##
## Example: Kepler's problem (eccentricity 0.6) over 100 periods with a
## fixed step; the energy error stays bounded.  The Hessian is built only
## when asked for (nargout > 1): most calls need f alone (0.57 of the
## 7.11 calls per step ask for it, see NewtonMatrix).
##
## @example
## @group
## function [dy, ddy] = kepler (t, y)
##   q = y(1:2);  r = norm (q);
##   dy = [y(3:4); -q / r^3];
##   if (nargout > 1)    # the Hessian of H, only when it is asked for
##     ddy = [(eye(2) - 3*(q*q')/r^2) / r^3, zeros(2); zeros(2), eye(2)];
##   endif
## endfunction
## e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
## opts = symplecticset ("TimeStepSize", 2*pi/100, "Nodes", 3);
## [t, y] = odeSPVI (@@kepler, [0 200*pi], y0, opts);
## H = sum (y(:,3:4).^2, 2)/2 - 1 ./ sqrt (sum (y(:,1:2).^2, 2));
## max (abs (H + 0.5))     # bounded, no drift
## @end group
## @end example
## @seealso{odeSE, odeSV, symplecticset, ode45, odeset}
## @end deftypefn

function varargout = odeSPVI (varargin)
  error ("odeSPVI: the compiled function odeSPVI.mex is missing; build the package with 'make'");
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
