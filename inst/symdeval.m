## Copyright (C) 2026 The symplectic developers
##
## This program is free software: you can redistribute it and/or modify it
## under the terms of the GNU General Public License as published by the Free
## Software Foundation, either version 3 of the License, or (at your option)
## any later version.  See the file COPYING.

## -*- texinfo -*-
## @deftypefn {} {@var{y} =} symdeval (@var{sol}, @var{t})
## Evaluate a solution of the symplectic solvers at any times, from the
## solver's own dense output.
##
## @var{sol} is the struct that @code{odeSE}, @code{odeSV} or
## @code{odeSPVI} return with one output; @var{t} is a vector of times
## within @code{sol.x(1)} and @code{sol.x(end)}.  @var{y} has one column
## per element of @var{t}, as @code{sol.y} has one per element of
## @code{sol.x}.
##
## @var{sol} must come from a run with the option @code{Dense}
## @qcode{"on"}, which keeps each step's continuous output in
## @code{sol.dense} (its values at the step's Chebyshev--Lobatto points;
## for @code{odeSV} and @code{odeSPVI}'s fixed steps it costs one call
## of @var{fcn} per step more: f at the step's end).  The values are
## those that the solver gives at output times: the cubic Hermite
## interpolant of the step's ends for @code{odeSE} and @code{odeSV}; for
## @code{odeSPVI} its own polynomial through the nodes, of order Nodes+2
## between the steps of a fixed-step run (Nodes+3 in adaptive runs).
## More in the user guide,
## @file{doc/user-guide.md} in the package's directory,
## @code{pkg ("list", "symplectic")@{1@}.dir}.
##
## @example
## @group
## sol = odeSPVI (@@(t, y) [y(2); -y(1)], [0 10], [1; 0],
##                symplecticset ("TimeStepSize", 0.5, "Dense", "on"));
## y = symdeval (sol, [0.25 3.3 7]);
## printf ("%.2e\n", max (abs (y(1,:) - cos ([0.25 3.3 7]))));
## @end group
## @end example
## @seealso{odeSPVI, odeSE, odeSV}
## @end deftypefn

function y = symdeval (sol, t)

  if (nargin != 2)
    print_usage ();
  endif
  if (! isstruct (sol) || ! all (isfield (sol, {"x", "y", "solver"})))
    error ("Octave:invalid-input-arg",
           "symdeval: SOL must be the struct of odeSE, odeSV or odeSPVI (with one output)");
  endif
  if (numel (sol) != 1)
    error ("Octave:invalid-input-arg",
           "symdeval: SOL is a %dx%d struct array (an ensemble's sol): give one member's, symdeval (sol(k), T)",
           rows (sol), columns (sol));
  endif
  if (! isfield (sol, "dense"))
    error ("Octave:invalid-input-arg",
           "symdeval: SOL carries no dense output: call %s with the option Dense \"on\"",
           sol.solver);
  endif
  if (! isnumeric (t) || ! isreal (t) || ! isvector (t) && ! isempty (t))
    error ("Octave:invalid-input-arg",
           "symdeval: T must be a real vector of times");
  endif
  t = double (t(:)).';
  lo = min (sol.x([1 end]));
  hi = max (sol.x([1 end]));
  out = ! (t >= lo & t <= hi);
  if (any (out))
    error ("Octave:invalid-input-arg",
           "symdeval: T = %g is outside the span [%g, %g] of SOL",
           t(find (out, 1)), lo, hi);
  endif

  D = sol.dense;
  n = rows (sol.y);
  y = zeros (n, numel (t));
  if (isempty (t))
    return;
  endif
  ## each t in the last step that starts at or before it (steps run from
  ## D.t(1,:) to D.t(2,:), forwards or backwards)
  dir = sign (D.t(2,1) - D.t(1,1));
  i = max (lookup (dir * D.t(1,:), dir * t), 1);
  K = size (D.y, 2) - 1;                   # the polynomial's degree
  th = (1 - cos (pi * (0:K) / K)) / 2;     # Chebyshev-Lobatto points
  w = (-1) .^ (0:K);
  w([1 end]) /= 2;
  for k = unique (i)
    j = find (i == k);
    s = (t(j) - D.t(1,k)) / (D.t(2,k) - D.t(1,k));
    c = w ./ (s(:) - th);                  # numel (j) x (K + 1)
    v = (c * D.y(:,:,k).') ./ sum (c, 2);
    [hit, at] = ismember (s(:), th);       # at a point itself
    v(hit, :) = D.y(:, at(hit), k).';
    y(:, j) = v.';
  endfor

endfunction

%!demo
%! ## The solution between the steps: odeSPVI with long fixed steps
%! ## (h = 0.5) on the oscillator, evaluated by symdeval on a fine grid
%! ## from the run's dense output, against the exact solution cos(t).
%! opts = symplecticset ("TimeStepSize", 0.5, "Dense", "on");
%! sol = odeSPVI (@(t, y) [y(2); -y(1)], [0 10], [1; 0], opts);
%! tq = linspace (0, 10, 401);
%! y = symdeval (sol, tq);
%! printf ("%d steps of 0.5; error of symdeval on 401 times: %.2e (at the steps %.2e)\n",
%!         numel (sol.x) - 1, max (abs (y(1,:) - cos (tq))),
%!         max (abs (sol.y(1,:) - cos (sol.x))));
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
%!   subplot (2, 1, 1);
%!   plot (tq, y(1,:), "b", sol.x, sol.y(1,:), "ko");
%!   xlabel ("t");  ylabel ("q");
%!   title ("symdeval between the steps (o)");
%!   subplot (2, 1, 2);
%!   semilogy (tq, max (abs (y(1,:) - cos (tq)), eps));
%!   xlabel ("t");  ylabel ("|q - cos(t)|");
%!   if (headless)
%!     print (fig, "symdeval-demo.png", "-dpng", "-r100");
%!     printf ("no display: figure written to %s\n", fullfile (pwd, "symdeval-demo.png"));
%!   endif
%! catch err
%!   printf ("no figure (%s)\n", err.message);
%! end_try_catch

%!test
%! ## odeSPVI, fixed steps: symdeval gives the values the solver gives at
%! ## output times (the same dense output), and the exact solution to the
%! ## method's accuracy
%! f = @(t, y) [y(2); -y(1)];
%! o = symplecticset ("TimeStepSize", 0.5, "Dense", "on");
%! tq = linspace (0, 10, 37);
%! sol = odeSPVI (f, [0 10], [1; 0], o);
%! [~, yt] = odeSPVI (f, tq, [1; 0], o);
%! assert (symdeval (sol, tq), yt.', 1e-13);
%! assert (symdeval (sol, tq), [cos(tq); -sin(tq)], 1e-5);

%!test
%! ## odeSE, odeSV and adaptive odeSPVI; the step points are the solution
%! f = @(t, y) [y(2); -sin(y(1))];
%! for s = {@odeSE, @odeSV, @odeSPVI}
%!   sol = s{1} (f, [0 5], [1; 0], symplecticset ("Dense", "on"));
%!   assert (symdeval (sol, sol.x), sol.y, 1e-14);
%!   tq = linspace (0, 5, 23);
%!   [~, yt] = s{1} (f, tq, [1; 0]);
%!   assert (symdeval (sol, tq), yt.', 1e-12);
%! endfor

%!test
%! ## backwards, and a run ended by a terminal event
%! f = @(t, y) [y(2); -y(1)];
%! sol = odeSV (f, [2 0], [1; 0], symplecticset ("TimeStepSize", 0.01, "Dense", "on"));
%! assert (symdeval (sol, [1.5 0.3]), [cos(-0.5) cos(-1.7); -sin(-0.5) -sin(-1.7)], 1e-4);
%! o = symplecticset ("TimeStepSize", 0.3, "Dense", "on", "Events", @(t, y) deal (y(1), 1, -1));
%! sol = odeSPVI (f, [0 10], [1; 0], o);
%! assert (sol.x(end), pi/2, 1e-6);
%! assert (symdeval (sol, sol.x(end)), sol.y(:,end), 1e-12);

%!shared sol
%! sol = odeSV (@(t, y) [y(2); -y(1)], [0 1], [1; 0], symplecticset ("Dense", "on"));
%!error <outside the span> symdeval (sol, 2)
%!error <SOL must be the struct> symdeval (struct ("x", 1), 0.5)
%!error <T must be a real vector> symdeval (sol, "a")
%!error <SOL carries no dense output: call odeSV with the option Dense "on"> symdeval (odeSV (@(t, y) [y(2); -y(1)], [0 1], [1; 0]), 0.5)
%!error <Invalid call> symdeval (1)
%!error <symdeval: SOL is a 1x2 struct array \(an ensemble's sol\): give one member's, symdeval \(sol\(k\), T\)>
%! s2 = odeSV (@(t, y) [y(2,:); -y(1,:)], [0 1], [1 2; 0 0],
%!             symplecticset ("TimeStepSize", 0.1, "Ensemble", "on", "Dense", "on"));
%! symdeval (s2, 0.5);
