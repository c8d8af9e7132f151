## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## Tests of odeSV's VerletForm (kick-drift-kick "velocity" and
## drift-kick-drift "position" Verlet steps, for Verlet and the
## compositions of Method) and of CompensatedSummation's default: orders,
## symplecticity, reversibility, the steps against an m-code
## drift-kick-drift loop, the accuracy of both forms on Kepler e = 0.6,
## the round-off floor, calls per step, the other paths (adaptive,
## reversible, dense output and events, Vectorized, Ensemble), the
## errors.  References are independent of the package: Kepler's equation,
## the published end error of the order-8 composition, an m-code stepper
## with its own copy of the coefficients, finite-difference Jacobians.

%!function y = kepler_exact (t, e)
%!  ## Kepler's problem, a = 1, from the pericentre at t = 0
%!  E = t;
%!  for i = 1:50
%!    E -= (E - e * sin (E) - t) / (1 - e * cos (E));
%!  endfor
%!  s = sqrt (1 - e^2);  r = 1 - e * cos (E);
%!  y = [cos(E) - e; s * sin(E); -sin(E) / r; s * cos(E) / r];
%!endfunction

%!function y0 = kepler_y0 (e)
%!  y0 = [1 - e; 0; 0; sqrt((1 + e) / (1 - e))];
%!endfunction

%!function a = acc (t, q)
%!  ## Kepler's acceleration, for q of 2-by-k (Vectorized); no BLAS
%!  a = -q ./ (q(1,:).^2 + q(2,:).^2).^1.5;
%!endfunction

%!function dy = kep (t, y)
%!  dy = [y(3:4, :); acc(t, y(1:2, :))];
%!endfunction

%!function g = kahanli8_gamma ()
%!  ## Kahan & Li, Math. Comp. 66 (1997), s17odr8a
%!  g = [0.13020248308889008, 0.56116298177510838, -0.38947496264484729, ...
%!       0.15884190655515560, -0.39590389413323758, 0.18453964097831571, ...
%!       0.25837438768632205, 0.29501172360931030, -0.60550853383003451];
%!  g = [g, g(end-1:-1:1)];
%!endfunction

%!function y1 = last_y (f, tspan, y0, varargin)
%!  sol = odeSV (f, tspan, y0, symplecticset (varargin{:}));
%!  y1 = sol.y(:, end);
%!endfunction

## ----------------------------------------------------------------- orders
%!test
%! ## Kepler e = 0.2 to a time that is not a whole period; steps doubled:
%! ## the error falls by 2^order (within 0.35), both forms, both fcn forms
%! e = 0.2;  y0 = kepler_y0 (e);
%! cases = {"verlet", 2, [400 800], 1; "yoshida4", 4, [50 100], 1;
%!          "kahanli6", 6, [40 80], 4*pi+1; "kahanli8", 8, [30 60], 4*pi+1};
%! for k = 1:rows (cases)
%!   [m, p, N, T] = cases{k, :};
%!   for form = {"velocity", "position"}
%!     for fo = {{@acc, "SecondOrder"}, {@kep, "Separable"}}
%!       err = zeros (1, 2);
%!       for i = 1:2
%!         y1 = last_y (fo{1}{1}, [0 T], y0, "TimeStepNumber", N(i), ...
%!                      "Method", m, "VerletForm", form{1}, fo{1}{2}, "on");
%!         err(i) = norm (y1 - kepler_exact (T, e));
%!       endfor
%!       s = log2 (err(1) / err(2));
%!       assert (abs (s - p) <= 0.35, "%s %s %s: order %.2f, errors %s",
%!               m, form{1}, fo{1}{2}, s, mat2str (err, 3));
%!       assert (min (err) > 1e-12);
%!     endfor
%!   endfor
%! endfor

## -------------------------------------------------- the m-code reference
%!test
%! ## kahanli8 in the position form equals a plain m-code drift-kick-drift
%! ## composition with the published coefficients (to round-off)
%! e = 0.6;  y0 = kepler_y0 (e);  h = 0.05;  n = 40;  g = kahanli8_gamma ();
%! q = y0(1:2);  p = y0(3:4);
%! for k = 1:n
%!   for gi = g
%!     q += (gi*h/2) * p;  p += (gi*h) * acc (0, q);  q += (gi*h/2) * p;
%!   endfor
%! endfor
%! for fo = {{@acc, "SecondOrder"}, {@kep, "Separable"}}
%!   y1 = last_y (fo{1}{1}, [0 n*h], y0, "TimeStepNumber", n, "Method", ...
%!                "kahanli8", "VerletForm", "position", fo{1}{2}, "on");
%!   assert (y1, [q; p], 1e-12);
%! endfor
%! ## and the two forms are different methods (their ends differ by 1e-9)
%! yv = last_y (@acc, [0 n*h], y0, "TimeStepNumber", n, "Method", ...
%!              "kahanli8", "SecondOrder", "on");
%! assert (norm (yv - [q; p]) > 1e-10);

## ----------------------------------------------------------- symplecticity
%!test
%! ## the Jacobian M of one step (central differences of 1e-5) keeps
%! ## M' J M = J to the differences' own error (measured 3e-10 to 5e-10);
%! ## the same measure finds an explicit Euler step far from it
%! e = 0.2;  y0 = kepler_y0 (e);  h = 0.3;
%! J = [zeros(2) eye(2); -eye(2) zeros(2)];
%! function M = jac_fd (phi, y0)
%!   M = zeros (4);
%!   for j = 1:4
%!     ej = zeros (4, 1);  ej(j) = 1e-5;
%!     M(:, j) = (phi (y0 + ej) - phi (y0 - ej)) / 2e-5;
%!   endfor
%! endfunction
%! for m = {"verlet", "yoshida4", "kahanli8"}
%!   for fo = {{@acc, "SecondOrder"}, {@kep, "Separable"}}
%!     phi = @(y) last_y (fo{1}{1}, [0 h], y, "TimeStepNumber", 1, ...
%!                        "Method", m{1}, "VerletForm", "position", ...
%!                        fo{1}{2}, "on");
%!     M = jac_fd (phi, y0);
%!     assert (norm (M'*J*M - J, Inf) < 2e-9, "%s %s", m{1}, fo{1}{2});
%!   endfor
%! endfor
%! M = jac_fd (@(y) y + h * kep (0, y), y0);
%! assert (norm (M'*J*M - J, Inf) > 1e-2);

## ---------------------------------------------------------- reversibility
%!test
%! ## forward N fixed steps, then back from the end: y0 again to round-off
%! e = 0.6;  y0 = kepler_y0 (e);
%! for m = {"verlet", "kahanli8"}
%!   for fo = {{@acc, "SecondOrder"}, {@kep, "Separable"}}
%!     o = {"TimeStepNumber", 500, "Method", m{1}, "VerletForm", ...
%!          "position", fo{1}{2}, "on"};
%!     y1 = last_y (fo{1}{1}, [0 10], y0, o{:});
%!     y2 = last_y (fo{1}{1}, [10 0], y1, o{:});
%!     assert (norm (y2 - y0) < 1e-12, "%s %s: %.2g", m{1}, fo{1}{2},
%!             norm (y2 - y0));
%!     assert (norm (y1 - y0) > 0.1);
%!   endfor
%! endfor
%!test
%! ## reversible steps in the position form retrace themselves too
%! e = 0.6;  y0 = kepler_y0 (e);
%! for m = {"verlet", "kahanli8"}
%!   o = symplecticset ("StepControl", "reversible", "RelTol", 1e-6, ...
%!                      "Method", m{1}, "VerletForm", "position", ...
%!                      "SecondOrder", "on");
%!   s1 = odeSV (@acc, [0 4*pi], y0, o);
%!   ## back from the last step point before the (shortened) last step
%!   tb = s1.x(end-1);  yb = s1.y(:, end-1);
%!   o2 = symplecticset (o, "InitialStep", s1.x(end-1) - s1.x(end-2));
%!   s2 = odeSV (@acc, [tb 0], yb, o2);
%!   assert (norm (s2.y(:, end) - y0) < 1e-9, "%s: %.2g", m{1},
%!           norm (s2.y(:, end) - y0));
%! endfor

## ------------------------------------------------- Kepler e = 0.6, 200 periods
%!test
%! ## kahanli8 at N = 12566 steps over 200 periods (h = 0.1): the position
%! ## form ends 3.4e-6 from y0 (the figure published for the order-8
%! ## drift-kick-drift composition; measured 3.37e-6), the velocity form
%! ## 7.3e-4 (216 times more), at the same calls of fcn
%! e = 0.6;  y0 = kepler_y0 (e);  err = zeros (1, 2);  nf = zeros (1, 2);
%! forms = {"velocity", "position"};
%! for i = 1:2
%!   sol = odeSV (@acc, [0 400*pi], y0, symplecticset ("TimeStepNumber", ...
%!                12566, "Method", "kahanli8", "VerletForm", forms{i}, ...
%!                "SecondOrder", "on"));
%!   err(i) = norm (sol.y(:, end) - y0);  nf(i) = sol.stats.nfevals;
%! endfor
%! assert (err(2), 3.4e-6, 0.2e-6);
%! assert (err(1) / err(2) >= 100, "ratio %.1f", err(1) / err(2));
%! assert (abs (nf(1) - nf(2)) <= 1);
%! assert (nf(2) <= 17 * 12566 + 1);

## -------------------------------------------------------- calls per step
%!test
%! ## the same calls of fcn in both forms: Verlet 2 a step (Separable), 1
%! ## (SecondOrder); a composition of s stages 2s and s; plus at most one
%! ## at the start
%! e = 0.6;  y0 = kepler_y0 (e);  N = 50;
%! for m = {{"verlet", 1}, {"yoshida4", 3}, {"kahanli8", 17}}
%!   for fo = {{@acc, "SecondOrder", 1}, {@kep, "Separable", 2}}
%!     for form = {"velocity", "position"}
%!       sol = odeSV (fo{1}{1}, [0 1], y0, symplecticset ("TimeStepNumber", N,
%!                    "Method", m{1}{1}, "VerletForm", form{1}, fo{1}{2}, "on"));
%!       nf = sol.stats.nfevals;  want = fo{1}{3} * m{1}{2} * N;
%!       assert (nf >= want && nf <= want + 2, "%s %s %s: %d calls",
%!               m{1}{1}, fo{1}{2}, form{1}, nf);
%!     endfor
%!   endfor
%! endfor

## -------------------------------------------- compensated summation default
%!test
%! ## the explicit compositions sum with compensation unless told not to:
%! ## the default is "on" to the bit, and "off" is another (worse) run
%! e = 0.6;  y0 = kepler_y0 (e);
%! o = {"TimeStepNumber", 200, "Method", "kahanli8", "SecondOrder", "on"};
%! yd = last_y (@acc, [0 2*pi], y0, o{:});
%! assert (isequal (yd, last_y (@acc, [0 2*pi], y0, o{:}, ...
%!                              "CompensatedSummation", "on")));
%! assert (! isequal (yd, last_y (@acc, [0 2*pi], y0, o{:}, ...
%!                                "CompensatedSummation", "off")));
%!test
%! ## the round-off floor: kahanli8 (position) over 5 periods in 6000 steps
%! ## (1e5 stages; the truncation error of H is below 1e-20), the largest
%! ## energy error: measured 8.9e-16 by default, 3.3e-14 with
%! ## CompensatedSummation "off" (over 10 and 20 periods too)
%! e = 0.6;  y0 = kepler_y0 (e);
%! H = @(y) (y(3,:).^2 + y(4,:).^2)/2 - 1 ./ sqrt (y(1,:).^2 + y(2,:).^2);
%! o = symplecticset ("TimeStepNumber", 6000, "Method", "kahanli8", ...
%!                    "VerletForm", "position", "SecondOrder", "on");
%! sd = odeSV (@acc, [0 10*pi], y0, o);
%! so = odeSV (@acc, [0 10*pi], y0, symplecticset (o, ...
%!             "CompensatedSummation", "off"));
%! ed = max (abs (H (sd.y) + 0.5));  eo = max (abs (H (so.y) + 0.5));
%! assert (ed < 4e-15, "default %.2g", ed);
%! assert (eo > 5 * ed, "off %.2g, default %.2g", eo, ed);
%!test
%! ## Verlet's own stepper keeps its default (no compensated sums, adaptive
%! ## steps allowed), as do the implicit compositions
%! e = 0.6;  y0 = kepler_y0 (e);
%! sol = odeSV (@kep, [0 1], y0, symplecticset ("Separable", "on", ...
%!              "VerletForm", "position", "RelTol", 1e-6));
%! assert (sol.stats.nsteps > 10);
%! y1 = last_y (@kep, [0 1], y0, "TimeStepNumber", 40, "Method", "yoshida4");
%! assert (norm (y1 - kepler_exact (1, e)) < 3e-4);

## ---------------------------------------------------------- the other paths
%!test
%! ## adaptive steps in the position form: the error estimate holds as in
%! ## the velocity form (global errors over a period of e = 0.6 at RelTol
%! ## 1e-5 and 1e-7, measured: 6.0e-3 and 2.9e-4 velocity, 9.3e-3 and
%! ## 4.4e-4 position, at about the same steps)
%! e = 0.6;  y0 = kepler_y0 (e);  T = 2*pi + 1;  tols = [1e-5 1e-7];
%! for fo = {{@acc, "SecondOrder"}, {@kep, "Separable"}}
%!   err = zeros (2);  ns = zeros (2);  forms = {"velocity", "position"};
%!   for i = 1:2
%!     for j = 1:2
%!       sol = odeSV (fo{1}{1}, [0 T], y0, symplecticset ("RelTol", tols(j),
%!                    "AbsTol", tols(j), "VerletForm", forms{i}, fo{1}{2}, "on"));
%!       err(i, j) = norm (sol.y(:, end) - kepler_exact (T, e));
%!       ns(i, j) = sol.stats.nsteps;
%!     endfor
%!   endfor
%!   assert (err(2, 2) < err(2, 1) / 10);
%!   assert (err(2, :) < 3 * err(1, :));
%!   assert (ns(2, :) < 1.3 * ns(1, :));
%! endfor
%!test
%! ## events and output times on the dense output of the position form:
%! ## y(2) = 0 at the apocentre t = pi, the output times on the orbit
%! ## (measured: Verlet 1.6e-4 and 9.4e-5, velocity form 4.3e-4 and
%! ## 3.1e-4; kahanli8 4e-15 and 2.2e-12 in both forms)
%! e = 0.6;  y0 = kepler_y0 (e);
%! ev = @(t, y) deal (y(2), 0, -1);
%! for m = {{"verlet", 1e-3}, {"kahanli8", 1e-9}}
%!   o = symplecticset ("TimeStepSize", 2*pi/2000, "Method", m{1}{1}, ...
%!                      "VerletForm", "position", "SecondOrder", "on", ...
%!                      "Events", ev);
%!   [t, y, te, ye] = odeSV (@acc, [0 1 2.5 5], y0, o);
%!   assert (t, [0; 1; 2.5; 5]);
%!   assert (numel (te), 1);
%!   assert (te, pi, m{1}{2});
%!   assert (ye.', kepler_exact (te, e), m{1}{2});
%!   for k = 1:numel (t)
%!     assert (y(k, :).', kepler_exact (t(k), e), m{1}{2});
%!   endfor
%! endfor
%!test
%! ## Vectorized and Ensemble: the members' runs are the single runs
%! e = [0.2 0.6];  Y0 = [kepler_y0(e(1)), kepler_y0(e(2))];
%! o = {"TimeStepNumber", 100, "Method", "yoshida4", "VerletForm", ...
%!      "position", "SecondOrder", "on"};
%! [t, Y] = odeSV (@acc, [0 2], Y0, symplecticset (o{:}, "Ensemble", "on", ...
%!                 "Vectorized", "on"));
%! for k = 1:2
%!   y1 = last_y (@acc, [0 2], Y0(:, k), o{:});
%!   assert (Y(end, :, k).', y1, 1e-13);
%! endfor
%! [t, Y] = odeSV (@kep, [0 2], Y0, symplecticset (o{1:end-2}, "Separable", ...
%!                 "on", "Ensemble", "on"));
%! for k = 1:2
%!   y1 = last_y (@kep, [0 2], Y0(:, k), o{1:end-2}, "Separable", "on");
%!   assert (Y(end, :, k).', y1, 1e-13);
%! endfor
%!warning <odeSV.*Separable is on.*d(H/dp changed with q|H/dq changed with p)>
%! ## the position form checks separability with the calls it makes
%! f = @(t, y) [y(2) * (1 + y(1)^2/4); -sin(y(1)) - y(2)^2 * y(1)/4];
%! sol = odeSV (f, [0 1], [1; 0.5], symplecticset ("Separable", "on", ...
%!              "VerletForm", "position", "TimeStepSize", 0.1));

## ------------------------------------------------------------------ errors
%!error <odeSV: VerletForm must be "velocity" or "position", got "drift">
%! odeSV (@acc, [0 1], kepler_y0 (0.2), symplecticset ("SecondOrder", "on",
%!        "TimeStepSize", 0.1, "VerletForm", "drift"));
%!error <odeSV: VerletForm must be>
%! odeSV (@acc, [0 1], kepler_y0 (0.2), symplecticset ("SecondOrder", "on",
%!        "TimeStepSize", 0.1, "VerletForm", 1));
%!error <odeSV: VerletForm "position" is for Verlet and its compositions; Method "blanesmoan6" is a splitting>
%! odeSV (@acc, [0 1], kepler_y0 (0.2), symplecticset ("SecondOrder", "on",
%!        "TimeStepSize", 0.1, "Method", "blanesmoan6", "VerletForm", "position"));
%!error <odeSV: VerletForm "position" takes explicit steps: set Separable>
%! odeSV (@kep, [0 1], kepler_y0 (0.2), symplecticset ("TimeStepSize", 0.1,
%!        "VerletForm", "position"));
%!error <odeSV: VerletForm "position" takes explicit steps: set Separable>
%! odeSV (@kep, [0 1], kepler_y0 (0.2), symplecticset ("TimeStepSize", 0.1,
%!        "Method", "kahanli8", "VerletForm", "position"));
%!test
%! ## the error carries the identifier of the package's bad arguments, and
%! ## "velocity" with a splitting is the default, accepted
%! try
%!   odeSV (@acc, [0 1], [1;0;0;1], symplecticset ("SecondOrder", "on",
%!          "TimeStepSize", 0.1, "VerletForm", "dkd"));
%!   error ("no error");
%! catch err
%!   assert (err.identifier, "Octave:invalid-input-arg");
%! end_try_catch
%! y1 = last_y (@acc, [0 1], kepler_y0 (0.2), "SecondOrder", "on", ...
%!              "TimeStepSize", 0.1, "Method", "ruth3", "VerletForm", "velocity");
%! assert (all (isfinite (y1)));
