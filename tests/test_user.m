## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## What a new user meets: a typo in a plain struct, options of adaptive
## steps given with a fixed step, the messages' times, Refine's default,
## the 2013 call form and option name Explicit, the Hamiltonian option,
## and sol's dense output (symdeval) at the method's order.

%!shared all3, osc
%! all3 = {@odeSE, @odeSV, @odeSPVI};
%! osc = @(t, y) [y(2); -y(1)];

%!function [msg, id] = warning_of (run)
%!  ## the last warning that the call run () gives
%!  lastwarn ("");
%!  x = run ();
%!  [msg, id] = lastwarn ();
%!endfunction

%!test
%! ## a typo in a plain struct: said, with the nearest option; an option
%! ## of another solver is not a typo: said as ignored
%! for s = all3
%!   name = func2str (s{1});
%!   [msg, id] = warning_of (@() s{1} (osc, [0 1], [1 0], struct ("Nodse", 3, "TimeStepSize", 0.1)));
%!   assert (id, "symplectic:unknown-option");
%!   assert (msg, [name ": unknown option Nodse is ignored; did you mean Nodes?"]);
%!   [msg, id] = warning_of (@() s{1} (osc, [0 1], [1 0], struct ("Zzzzzz", 3, "TimeStepSize", 0.1)));
%!   assert (msg, [name ": unknown option Zzzzzz is ignored"]);
%!   [msg, id] = warning_of (@() s{1} (osc, [0 1], [1 0], struct ("Nodes", 3, "Separable", "off", "TimeStepSize", 0.1)));
%!   if (strcmp (name, "odeSPVI"))
%!     assert (msg, "");    # Separable off asks for nothing
%!   else
%!     assert (id, "symplectic:ignored-option");
%!     assert (msg, [name ": option Nodes is used by odeSPVI only; ignored"]);
%!   endif
%! endfor

%!test
%! ## RelTol and AbsTol with a fixed step do nothing: said
%! for s = all3
%!   name = func2str (s{1});
%!   [msg, id] = warning_of (@() s{1} (osc, [0 1], [1 0], struct ("RelTol", 1e-8, "AbsTol", 1e-9, "TimeStepSize", 0.1)));
%!   assert (id, "symplectic:ignored-option");
%!   assert (msg, [name ": RelTol and AbsTol are for adaptive steps only and are ignored with a fixed step (TimeStepSize or TimeStepNumber)"]);
%!   [msg, id] = warning_of (@() s{1} (osc, [0 1], [1 0], symplecticset ("TimeStepSize", 0.1)));
%!   assert (msg, "");
%! endfor

%!test
%! ## times in messages: as written (0.3, not 0.30000000000000004); a NaN
%! ## with a fixed step advises a smaller one (none was tried)
%! for s = all3
%!   name = func2str (s{1});
%!   [msg, id] = warning_of (@() s{1} (osc, [0 1], [1 0], struct ("TimeStepSize", 0.1, "MaxSteps", 3)));
%!   assert (id, "symplectic:max-steps");
%!   assert (msg, [name ": MaxSteps reached at t = 0.3; returning the solution up to t = 0.3"]);
%!   f = @(t, y) [y(2); -y(1) + 0 / (t < 0.45)];
%!   [msg, id] = warning_of (@() s{1} (f, [0 1], [1 0], struct ("TimeStepSize", 0.1)));
%!   assert (id, "symplectic:nonfinite");
%!   assert (regexp (msg, "with the fixed step \\(try a smaller TimeStepSize\\)"));
%!   assert (isempty (strfind (msg, "did not help")));
%! endfor

%!test
%! ## Refine: 4 rows per step on adaptive runs, as ode45; fixed steps keep
%! ## the user's grid; a given Refine holds for both
%! for s = all3
%!   sol = s{1} (osc, [0 5], [1 0]);
%!   [t, ~] = s{1} (osc, [0 5], [1 0]);
%!   assert (numel (t), 4 * sol.stats.nsteps + 1);
%!   assert (t(1:4:end), sol.x.', 1e-14);
%!   [t, ~] = s{1} (osc, [0 5], [1 0], odeset ("Refine", 2));
%!   assert (numel (t), 2 * sol.stats.nsteps + 1);
%!   [t, ~] = s{1} (osc, [0 1], [1 0], symplecticset ("TimeStepSize", 0.1));
%!   assert (t, (0:0.1:1).', 1e-15);
%!   [t, ~] = s{1} (osc, [0 1], [1 0], symplecticset ("TimeStepSize", 0.1, "Refine", 2));
%!   assert (numel (t), 21);
%! endfor

%!test
%! ## the 2013 form: parameters after Y0 without OPTS
%! f = @(t, y, w, c) [y(2); -w^2 * y(1) - c * y(2)];
%! for s = all3
%!   [t1, y1] = s{1} (f, [0 1], [1 0], 2, 0.1);
%!   [t2, y2] = s{1} (f, [0 1], [1 0], [], 2, 0.1);
%!   assert (isequal (t1, t2) && isequal (y1, y2));
%! endfor

%!test
%! ## Explicit (odepkg's name of Separable), "yes" and "no" too
%! for s = {@odeSE, @odeSV}
%!   a = s{1} (osc, [0 1], [1 0], struct ("TimeStepSize", 0.1, "Explicit", "yes"));
%!   b = s{1} (osc, [0 1], [1 0], struct ("TimeStepSize", 0.1, "Separable", "on"));
%!   assert (isequal (a.y, b.y));
%!   assert (a.stats.nnewton, 0);
%!   c = s{1} (osc, [0 1], [1 0], struct ("TimeStepSize", 0.1, "Explicit", "no"));
%!   assert (c.stats.nnewton > 0);
%! endfor
%!error <Separable and its alias Explicit disagree> x = odeSV (@(t, y) [y(2); -y(1)], [0 1], [1 0], struct ("Separable", "on", "Explicit", "no"))

%!test
%! ## the Hamiltonian option: its values at sol.x, their largest relative
%! ## change in sol.stats and in Stats
%! H = @(t, y) (y(1)^2 + y(2)^2) / 2;
%! for s = all3
%!   o = symplecticset ("TimeStepSize", 0.1, "Hamiltonian", H);
%!   sol = s{1} (osc, [0 10], [1 0], o);
%!   Hx = (sol.y(1,:).^2 + sol.y(2,:).^2) / 2;
%!   assert (sol.H, Hx, 1e-15);
%!   assert (sol.stats.max_dH, max (abs (Hx - 0.5)) / 0.5, 1e-15);
%!   out = evalc ("x_ = s{1} (osc, [0 10], [1 0], symplecticset (o, 'Stats', 'on'));");
%!   v = sscanf (out(strfind (out, "Largest relative change of H:"):end),
%!               "Largest relative change of H: %g");
%!   assert (v, sol.stats.max_dH, 1e-3 * sol.stats.max_dH);
%! endfor
%! ## with the parameters of FCN
%! f = @(t, y, w) [y(2); -w^2 * y(1)];
%! Hw = @(t, y, w) (w^2 * y(1)^2 + y(2)^2) / 2;
%! sol = odeSPVI (f, [0 1], [1 0], symplecticset ("TimeStepSize", 0.1, "Hamiltonian", Hw), 3);
%! assert (sol.H(1), 4.5);
%!error <the Hamiltonian must return a real scalar> x = odeSV (@(t, y) [y(2); -y(1)], [0 1], [1 0], symplecticset ("Hamiltonian", @(t, y) y))

%!test
%! ## sol's dense output at its order: symdeval between the steps of
%! ## odeSV (the method's order 2) and of odeSPVI (4,3) (Nodes + 2 = 5 on
%! ## fixed steps; 6 at the steps) against cos
%! tq = linspace (0.05, 9.95, 200);
%! for c = {{@odeSV, 2, 0.1}, {@odeSPVI, 5, 0.5}}
%!   [s, p, h] = c{1}{:};
%!   e = zeros (1, 2);
%!   for k = 1:2
%!     sol = s (osc, [0 10], [1; 0], symplecticset ("TimeStepSize", h / 2^(k-1), "Dense", "on"));
%!     e(k) = max (abs (symdeval (sol, tq)(1,:) - cos (tq)));
%!   endfor
%!   assert (log2 (e(1) / e(2)), p, 0.5);
%! endfor
