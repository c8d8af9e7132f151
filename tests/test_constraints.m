## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## Tests of odeSV's Constraints (RATTLE): the planar pendulum in
## Cartesian coordinates (g = q'q - 1) in the SecondOrder and Separable
## forms stays on g = 0 and G f_q = 0; its angle against the angle form
## integrated by ode45 at RelTol 1e-12, order 2; bounded energy; time
## reversal; the double pendulum against its angle form; the options it
## does not take yet, and Y0 off the constraints.

%!function check_bad (id, pat, f)
%!  ## f must raise an error with identifier id whose message matches pat
%!  try
%!    x = f ();
%!  catch err
%!    assert (err.identifier, id);
%!    assert (! isempty (regexp (err.message, pat, "once")), err.message);
%!    return;
%!  end_try_catch
%!  error ("no error raised; expected %s", pat);
%!endfunction

%!function [g, G] = circle (q)
%!  g = q' * q - 1;
%!  G = 2 * q';
%!endfunction

%!function [g, G] = rods (q)
%!  ## two unit rods: origin to mass 1, mass 1 to mass 2; q = [x1 y1 x2 y2]
%!  d = q(3:4) - q(1:2);
%!  g = [q(1:2)' * q(1:2) - 1; d' * d - 1];
%!  G = sparse ([2 * q(1:2)', 0, 0; -2 * d', 2 * d']);
%!endfunction

%!function dy = dbl_angles (t, y)
%!  ## two unit masses on unit rods, unit gravity; y = [th1 th2 w1 w2]
%!  a = y(1); b = y(2); u = y(3); v = y(4); c = a - b;
%!  den = 3 - cos (2 * c);
%!  ua = (-3 * sin (a) - sin (a - 2 * b) - 2 * sin (c) * (v^2 + u^2 * cos (c))) / den;
%!  va = 2 * sin (c) * (2 * u^2 + 2 * cos (a) + v^2 * cos (c)) / den;
%!  dy = [u; v; ua; va];
%!endfunction

%!function f = ifelse_f (o, fso, fsep)
%!  if (strcmp (o.SecondOrder, "on"))
%!    f = fso;
%!  else
%!    f = fsep;
%!  endif
%!endfunction

%!function theta = pend_angle (y)
%!  theta = atan2 (y(:,1), -y(:,2));
%!endfunction

%!shared y0, fso, fsep, o1, o2
%! th0 = 1;
%! y0 = [sin(th0); -cos(th0); 0; 0];
%! fso = @(t, q) [0; -1];
%! ## mass 2: T = |p|^2/4, V = 2 y; the same motion with p = 2 v
%! fsep = @(t, y) [y(3:4) / 2; 0; -2];
%! o1 = symplecticset ("SecondOrder", "on", "Constraints", @circle);
%! o2 = symplecticset ("Separable", "on", "Constraints", @circle);

## on the constraints at every step over 1e4 steps, both forms
%!test
%! o = symplecticset (o1, "TimeStepSize", 0.1);
%! [t, y] = odeSV (fso, [0 1000], y0, o);
%! assert (rows (y), 10001);
%! assert (max (abs (sum (y(:,1:2).^2, 2) - 1)) <= 1e-12);
%! assert (max (abs (sum (2 * y(:,1:2) .* y(:,3:4), 2))) <= 1e-12);
%!test
%! o = symplecticset (o2, "TimeStepSize", 0.1);
%! [t, y] = odeSV (fsep, [0 1000], [y0(1:2); 0; 0], o);
%! assert (max (abs (sum (y(:,1:2).^2, 2) - 1)) <= 1e-12);
%! assert (max (abs (sum (2 * y(:,1:2) .* y(:,3:4) / 2, 2))) <= 1e-12);

## the angle against ode45's on the angle form: order 2
%!test
%! T = 2;
%! [~, ya] = ode45 (@(t, y) [y(2); -sin(y(1))], [0 T/2 T], [1; 0],
%!                  odeset ("RelTol", 1e-12, "AbsTol", 1e-12));
%! ref = ya(end,1);
%! for form = 1:2
%!   err = zeros (1, 3);
%!   for k = 1:3
%!     h = 0.02 / 2^(k-1);
%!     if (form == 1)
%!       [t, y] = odeSV (fso, [0 T], y0, symplecticset (o1, "TimeStepSize", h));
%!     else
%!       [t, y] = odeSV (fsep, [0 T], y0, symplecticset (o2, "TimeStepSize", h));
%!     endif
%!     err(k) = abs (pend_angle (y(end,:)) - ref);
%!   endfor
%!   r = err(1:2) ./ err(2:3);
%!   assert (all (r > 3.8 & r < 4.2), "ratios %g %g", r);
%! endfor

## G by finite differences: the same steps to the differences' error
%!test
%! o = symplecticset (o1, "TimeStepSize", 0.05);
%! [~, ya] = odeSV (fso, [0 20], y0, o);
%! [~, yb] = odeSV (fso, [0 20], y0,
%!                  symplecticset (o, "Constraints", @(q) q' * q - 1));
%! assert (max (abs (ya(:) - yb(:))) <= 1e-9);

## energy bounded over 1e5 steps: no drift
%!test
%! o = symplecticset (o1, "TimeStepSize", 0.05);
%! [t, y] = odeSV (fso, [0 5000], y0, o);
%! E = sum (y(:,3:4).^2, 2) / 2 + y(:,2);
%! dE = abs (E - E(1));
%! half = floor (rows (y) / 2);
%! assert (max (dE) < 1e-2);
%! assert (max (dE(half+1:end)) <= 1.5 * max (dE(1:half)));

## forward, then back from the end: y0 again
%!test
%! for o = {symplecticset(o1, "TimeStepSize", 0.1), symplecticset(o2, "TimeStepSize", 0.1)}
%!   f = ifelse_f (o{1}, fso, fsep);
%!   [~, y] = odeSV (f, [0 100], y0, o{1});
%!   [~, yb] = odeSV (f, [100 0], y(end,:)', o{1});
%!   assert (yb(end,:)', y0, 1e-10);
%! endfor

## the double pendulum: both rods kept (sparse G), against the angle form
%!test
%! th = [1; 2];
%! q0 = [sin(th(1)); -cos(th(1)); sin(th(1)) + sin(th(2)); -cos(th(1)) - cos(th(2))];
%! f = @(t, q) [0; -1; 0; -1];
%! o = symplecticset ("SecondOrder", "on", "Constraints", @rods,
%!                    "TimeStepSize", 0.01);
%! [t, y] = odeSV (f, [0 100], [q0; 0; 0; 0; 0], o);
%! d = y(:,3:4) - y(:,1:2);
%! dv = y(:,7:8) - y(:,5:6);
%! assert (max (abs (sum (y(:,1:2).^2, 2) - 1)) <= 1e-12);
%! assert (max (abs (sum (d.^2, 2) - 1)) <= 1e-12);
%! assert (max (abs (sum (y(:,1:2) .* y(:,5:6), 2))) <= 1e-12);
%! assert (max (abs (sum (d .* dv, 2))) <= 1e-12);
%! E = sum (y(:,5:8).^2, 2) / 2 + y(:,2) + y(:,4);
%! assert (max (abs (E - E(1))) < 0.05);
%! T = 1;
%! [~, ya] = ode45 (@dbl_angles, [0 T/2 T], [th; 0; 0],
%!                  odeset ("RelTol", 1e-12, "AbsTol", 1e-12));
%! xr = [sin(ya(end,1)), -cos(ya(end,1))];
%! xr = [xr, xr + [sin(ya(end,2)), -cos(ya(end,2))]];
%! err = zeros (1, 2);
%! for k = 1:2
%!   [~, y] = odeSV (f, [0 T], [q0; 0; 0; 0; 0],
%!                   symplecticset (o, "TimeStepSize", 0.004 / k));
%!   err(k) = max (abs (y(end,1:4) - xr));
%! endfor
%! assert (err(2) < 2e-5);
%! assert (err(1) / err(2) > 3.5 && err(1) / err(2) < 4.5);

## Refine's rows (the dense output) stay near the constraints; sol, Events
%!test
%! o = symplecticset (o1, "TimeStepSize", 0.01, "Refine", 4);
%! [t, y] = odeSV (fso, [0 10], y0, o);
%! assert (rows (y), 4001);
%! assert (max (abs (sum (y(:,1:2).^2, 2) - 1)) <= 1e-7);
%! ## the bottom crossing x = 0, first at a quarter period: 1.8541/... of
%! ## the angle form (ode45's event)
%! ev = @(t, y) deal (y(1), true, -1);
%! [~, ~, te] = odeSV (fso, [0 10], y0, symplecticset (o, "Events", ev));
%! ws = warning ("off", "all");   # ode45's note on its terminal event
%! [~, ~, tr] = ode45 (@(t, y) [y(2); -sin(y(1))], [0 10], [1; 0],
%!                     odeset ("RelTol", 1e-12, "AbsTol", 1e-12,
%!                             "Events", @(t, y) deal (y(1), true, -1)));
%! warning (ws);
%! assert (te, tr, 1e-4);
%! sol = odeSV (fso, [0 1], y0, symplecticset (o, "Dense", "on"));
%! yd = symdeval (sol, 0.505);
%! assert (abs (sum (yd(1:2).^2) - 1) <= 1e-7);

## Vectorized is taken (the steps call FCN one state at a time)
%!test
%! o = symplecticset (o1, "TimeStepSize", 0.1, "Vectorized", "on");
%! [~, y] = odeSV (@(t, q) [zeros(1, columns (q)); -ones(1, columns (q))],
%!                 [0 10], y0, o);
%! [~, yr] = odeSV (fso, [0 10], y0, symplecticset (o1, "TimeStepSize", 0.1));
%! assert (y, yr, 1e-15);

## Y0 near the constraints: moved onto them, with a warning saying how far
%!test
%! yoff = [y0(1:2) * (1 + 1e-4); 1e-4; 0];
%! lastwarn ("");
%! [t, y] = odeSV (fso, [0 1], yoff, symplecticset (o1, "TimeStepSize", 0.1));
%! [msg, id] = lastwarn ();
%! assert (id, "symplectic:constraints-projected");
%! assert (! isempty (strfind (msg, sprintf ("q by %.3g", 1e-4 * abs (y0(1))))), msg);
%! assert (abs (sum (y(1,1:2).^2) - 1) <= 1e-14);
%! assert (abs (y(1,1:2) * y(1,3:4)') <= 1e-15);
%! assert (y(1,1:2), y0(1:2)', 1e-14);
%!warning <odeSV: Y0 was off the Constraints; moved onto>
%! x = odeSV (@(t, y) [y(3:4) / 2; 0; -2], [0 1], [0.6; -0.8002; 0; 0],
%!            symplecticset ("Separable", "on", "TimeStepSize", 0.1,
%!                       "Constraints", @(q) q' * q - 1));
## on them to round-off: no warning
%!test
%! lastwarn ("");
%! x = odeSV (fso, [0 1], y0, symplecticset (o1, "TimeStepSize", 0.1));
%! assert (lastwarn (), "");

## a solve that fails on the multipliers (too few iterations; G rank
## deficient from t = 1 on): the warning, and the rows up to there
%!test
%! o = symplecticset (o1, "TimeStepSize", 0.1);
%! lastwarn ("");
%! [t, y] = odeSV (fso, [0 1], y0, symplecticset (o, "MaxNewtonIterations", 1));
%! [~, id] = lastwarn ();
%! assert (id, "symplectic:newton-failed");
%! assert (rows (y), 1);
%! lastwarn ("");
%! [t, y] = odeSV (fso, [0 3], y0, symplecticset (o, "Constraints",
%!                 @(q) deal (q' * q - 1, 2 * q' * (q(1) > 0.5))));
%! [msg, id] = lastwarn ();
%! assert (id, "symplectic:newton-failed");
%! assert (t(end), 1, 1e-12);
%! assert (rows (y), 11);

## Separable on for an H that is not: said, as without Constraints
%!test
%! lastwarn ("");
%! [t, y] = odeSV (@(t, y) [y(3:4) * (1 + y(1)^2); 0; -1], [0 1], y0,
%!                 symplecticset (o2, "TimeStepSize", 0.1));
%! [~, id] = lastwarn ();
%! assert (id, "symplectic:not-separable");

## a sol as Y0 goes on with the same steps
%!test
%! o = symplecticset (o1, "TimeStepSize", 0.1);
%! sol = odeSV (fso, [0 1], y0, o);
%! sol2 = odeSV (fso, [1 2], sol, o);
%! [t, y] = odeSV (fso, [0 2], y0, o);
%! assert (sol2.y(:,end), y(end,:)', 1e-14);

## what this release does not take: said, naming the solver and option
%!test
%! check_bad ("Octave:invalid-input-arg", "odeSE: Constraints is not supported by odeSE yet",
%!   @() odeSE (@(t, y) [y(3:4); 0; -1], [0 1], [1; 0; 0; 0],
%!          symplecticset ("TimeStepSize", 0.1, "Constraints", @circle)));
%!test
%! check_bad ("Octave:invalid-input-arg", "odeSPVI: Constraints is not supported by odeSPVI yet",
%!   @() odeSPVI (@(t, y) [y(3:4); 0; -1], [0 1], [1; 0; 0; 0],
%!            symplecticset ("TimeStepSize", 0.1, "Constraints", @circle)));
%!test
%! check_bad ("Octave:invalid-input-arg", "odeSV: Constraints takes fixed explicit RATTLE steps; not yet with a general H",
%!   @() odeSV (@(t, y) [y(3:4); 0; -1], [0 1], [1; 0; 0; 0],
%!          symplecticset ("TimeStepSize", 0.1, "Constraints", @circle)));
%!test
%! check_bad ("Octave:invalid-input-arg", "odeSV: Constraints .* not yet with adaptive steps: give TimeStepSize",
%!   @() odeSV (@(t, q) [0; -1], [0 1], [1; 0; 0; 0],
%!          symplecticset ("SecondOrder", "on", "RelTol", 1e-6, "Constraints", @circle)));
%!test
%! check_bad ("Octave:invalid-input-arg", "odeSV: Constraints .* not yet with Method",
%!   @() odeSV (@(t, q) [0; -1], [0 1], [1; 0; 0; 0],
%!          symplecticset ("SecondOrder", "on", "TimeStepSize", 0.1,
%!                         "Method", "yoshida4", "Constraints", @circle)));
%!test
%! check_bad ("Octave:invalid-input-arg", "odeSV: Constraints .* not yet with StepControl \"reversible\"",
%!   @() odeSV (@(t, q) [0; -1], [0 1], [1; 0; 0; 0],
%!          symplecticset ("SecondOrder", "on", "StepControl", "reversible",
%!                         "Constraints", @circle)));
%!test
%! check_bad ("Octave:invalid-input-arg", "odeSV: Constraints .* not yet with Ensemble",
%!   @() odeSV (@(t, q) [0; -1], [0 1], [1 1; 0 0; 0 0; 0 0],
%!          symplecticset ("SecondOrder", "on", "TimeStepSize", 0.1,
%!                         "Ensemble", "on", "Constraints", @circle)));
%!test
%! check_bad ("Octave:invalid-input-arg", "odeSV: Constraints .* not yet with VerletForm \"position\"",
%!   @() odeSV (@(t, q) [0; -1], [0 1], [1; 0; 0; 0],
%!          symplecticset ("SecondOrder", "on", "TimeStepSize", 0.1,
%!                         "VerletForm", "position", "Constraints", @circle)));
%!test
%! check_bad ("Octave:invalid-input-arg", "odeSV: Constraints .* not yet with CompensatedSummation",
%!   @() odeSV (@(t, q) [0; -1], [0 1], [1; 0; 0; 0],
%!          symplecticset ("SecondOrder", "on", "TimeStepSize", 0.1,
%!                         "CompensatedSummation", "on", "Constraints", @circle)));
## bad Constraints functions
%!test
%! check_bad ("Octave:invalid-input-arg", "odeSV: Constraints must be a function handle or the name of a function, got 1x1 double",
%!   @() odeSV (@(t, q) [0; -1], [0 1], [1; 0; 0; 0],
%!          symplecticset ("SecondOrder", "on", "TimeStepSize", 0.1, "Constraints", 3)));
%!test
%! check_bad ("Octave:invalid-input-arg", "odeSV: the Constraints function must return g\\(q\\), a vector of m real values, 1 <= m < 2 \\(the positions\\), got 2 values",
%!   @() odeSV (@(t, q) [0; -1], [0 1], [1; 0; 0; 0],
%!          symplecticset ("SecondOrder", "on", "TimeStepSize", 0.1,
%!                         "Constraints", @(q) q - 1)));
%!test
%! check_bad ("Octave:invalid-input-arg", "odeSV: the Constraints function must return g\\(q\\), a vector of m real values, 1 <= m < 2 \\(the positions\\), got \\[\\](0x0)|got 0x0",
%!   @() odeSV (@(t, q) [0; -1], [0 1], [1; 0; 0; 0],
%!          symplecticset ("SecondOrder", "on", "TimeStepSize", 0.1,
%!                         "Constraints", @(q) [])));
%!test
%! ## the right size at q0, the wrong one later
%! check_bad ("Octave:invalid-input-arg", "odeSV: the Constraints function must return g\\(q\\), a vector of 1 real values, got",
%!   @() odeSV (@(t, q) [0; -1], [0 1], [1; 0; 0; 0],
%!          symplecticset ("SecondOrder", "on", "TimeStepSize", 0.1,
%!                         "Constraints", @(q) (q' * q - 1) * ones (1 + (q(2) < -1e-6), 1))));
%!test
%! check_bad ("Octave:invalid-input-arg", "odeSV: the Constraints function's second output G = dg/dq must be a 1x2 real matrix \\(full or sparse\\), got 2x1 double",
%!   @() odeSV (@(t, q) [0; -1], [0 1], [1; 0; 0; 0],
%!          symplecticset ("SecondOrder", "on", "TimeStepSize", 0.1,
%!                         "Constraints", @(q) deal (q' * q - 1, 2 * q))));
%!test
%! check_bad ("Octave:invalid-input-arg", "odeSV: the Constraints function takes no argument, but is called as CON \\(q\\)",
%!   @() odeSV (@(t, q) [0; -1], [0 1], [1; 0; 0; 0],
%!          symplecticset ("SecondOrder", "on", "TimeStepSize", 0.1,
%!                         "Constraints", @() 0)));
%!test
%! check_bad ("symplectic:nonfinite", "odeSV: the Constraints function returned NaN \\(element 1\\) at q0",
%!   @() odeSV (@(t, q) [0; -1], [0 1], [1; 0; 0; 0],
%!          symplecticset ("SecondOrder", "on", "TimeStepSize", 0.1,
%!                         "Constraints", @(q) NaN)));
%!test
%! check_bad ("Octave:invalid-input-arg", "odeSV: Y0 is far from the Constraints: .* q moves by 0.5 relative .* more than 0.01",
%!   @() odeSV (@(t, q) [0; -1], [0 1], [2; 0; 0; 0],
%!          symplecticset ("SecondOrder", "on", "TimeStepSize", 0.1, "Constraints", @circle)));
%!test
%! ## a velocity along the rod
%! check_bad ("Octave:invalid-input-arg", "odeSV: Y0 is far from the Constraints: .* p by 1, more than 0.01",
%!   @() odeSV (@(t, q) [0; -1], [0 1], [1; 0; 1; 0],
%!          symplecticset ("SecondOrder", "on", "TimeStepSize", 0.1, "Constraints", @circle)));
%!test
%! check_bad ("Octave:invalid-input-arg", "odeSV: Y0 could not be moved onto the Constraints .*G G' is singular",
%!   @() odeSV (@(t, q) [0; -1], [0 1], [0; 0; 0; 0],
%!          symplecticset ("SecondOrder", "on", "TimeStepSize", 0.1, "Constraints", @circle)));
