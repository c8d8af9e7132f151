## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## A sol given as Y0: the run continued beyond its end, or retraced back
## to its start.  References: y0 itself (a retrace of a reversible run
## must land on it, where a run back from the end point misses by the
## shortened last step), the run over the whole span (a continued fixed
## step run equals it), the exact solution of the oscillator, and the
## run from sol's end with the options given anew.  The errors.

%!function a = kep_acc (t, q)
%!  a = -q / norm (q)^3;
%!endfunction

%!function dy = kep (t, y)
%!  dy = [y(3:4); -y(1:2) / norm(y(1:2))^3];
%!endfunction

%!shared e, y0, T, acc, f
%! e = 0.9;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];  T = 100*pi;  # 50 periods
%! acc = @kep_acc;
%! f = @(t, y) [y(2); -sin(y(1)) + 0.1*cos(t)];   # a forced pendulum

%!test
%! ## odeSV reversible, Kepler e = 0.9, 50 periods, RelTol 1e-4: back to y0
%! ## to round-off (the run back from the end point alone misses by the
%! ## last step, shortened to land on T); the rows start at the end point,
%! ## then the step point before the last step
%! o = symplecticset ("SecondOrder", "on", "StepControl", "reversible",
%!                    "RelTol", 1e-4);
%! sol = odeSV (acc, [0 T], y0, o);
%! b = odeSV (acc, [T 0], sol);
%! assert (b.x(end), 0);
%! assert ([b.x(1:2); b.y(:,1:2)], [sol.x([end, end-1]); sol.y(:,[end, end-1])]);
%! assert (b.stats.nsteps, sol.stats.nsteps - 1);
%! assert (norm (b.y(:,end) - y0, Inf) < 1e-9);       # 1.7e-10
%! naive = odeSV (acc, [T 0], sol.y(:,end), o);
%! assert (norm (naive.y(:,end) - y0, Inf) > 1e-3);   # 2.5e-3
%! ## [t, y] the same rows (Refine is 1 on reversible steps through sol)
%! [t, y] = odeSV (acc, [T 0], sol);
%! assert (t(1), T);
%! assert (t(end), 0);
%! assert (norm (y(end,:).' - y0, Inf) < 1e-9);
%! ## without compensated sums (the default's) their round-off adds up
%! oc = symplecticset (o, "CompensatedSummation", "off");
%! sol = odeSV (acc, [0 T], y0, oc);
%! b = odeSV (acc, [T 0], sol);
%! assert (norm (b.y(:,end) - y0, Inf) < 1e-7);       # 4.6e-9, 1.5e-8 by libm

%!test
%! ## odeSPVI reversible, the same orbit: back to y0 to round-off
%! o = symplecticset ("StepControl", "reversible", "RelTol", 1e-4);
%! sol = odeSPVI (@kep, [0 T], y0, o);
%! b = odeSPVI (@kep, [T 0], sol);
%! assert (b.x(end), 0);
%! assert (b.x(2), sol.x(end-1));
%! assert (norm (b.y(:,end) - y0, Inf) < 1e-9);       # 4.7e-10
%! naive = odeSPVI (@kep, [T 0], sol.y(:,end), o);
%! assert (norm (naive.y(:,end) - y0, Inf) > 1e-7);   # 7.9e-7
%! ## solves converged further stay at round-off
%! o = symplecticset (o, "NewtonTol", 1e-16);
%! b = odeSPVI (@kep, [T 0], odeSPVI (@kep, [0 T], y0, o));
%! assert (norm (b.y(:,end) - y0, Inf) < 1e-9);       # 4.2e-10

%!test
%! ## a reversible run continued takes the steps of the run over the whole
%! ## span (to the round-off of t), and the energy stays bounded
%! o = symplecticset ("SecondOrder", "on", "StepControl", "reversible",
%!                    "RelTol", 1e-4);
%! a = odeSV (acc, [0 T/5], y0, o);
%! c = odeSV (acc, [T/5 T/2], a);
%! w = odeSV (acc, [0 T/2], y0, o);
%! assert (numel (c.x), numel (w.x));
%! assert (c.x, w.x, 1e-10);
%! assert (c.y, w.y, 1e-6);
%! assert (c.restart.options.RelTol, 1e-4);

%!test
%! ## fixed steps continued: the run over the whole span to the bit
%! ## (explicit steps; the last step of the first run was shortened to end
%! ## on 1.05, and twice continued)
%! for s = {@odeSE, @odeSV}
%!   for form = {"Separable", "SecondOrder"}
%!     if (strcmp (form{1}, "Separable"))
%!       g = f;  z0 = [1; 0];
%!     else
%!       g = @(t, q) -sin (q) + 0.1*cos (t);  z0 = [1; 0];
%!     endif
%!     o = symplecticset ("TimeStepSize", 0.1, form{1}, "on");
%!     w = s{1} (g, [0 3.5], z0, o);
%!     a = s{1} (g, [0 1.05], z0, o);
%!     assert (a.x(end) - a.x(end-1) < 0.1 - 1e-3);
%!     c = s{1} (g, [1.05 2.35], a);
%!     c = s{1} (g, [2.35 3.5], c);
%!     assert (isequal (c.x, w.x) && isequal (c.y, w.y));
%!     assert (c.stats.nsteps >= w.stats.nsteps);
%!     [tw, yw] = s{1} (g, [0 3.5], z0, o);
%!     [t, y] = s{1} (g, [1.05 3.5], a);
%!     assert (t(1), 1.05);
%!     assert (y(1,:), a.y(:,end).');
%!     assert (isequal (t(2:end), tw(12:end)) && isequal (y(2:end,:), yw(12:end,:)));
%!   endfor
%! endfor

%!test
%! ## TimeStepNumber: the continuation keeps its step; implicit steps
%! ## (Newton's start from the run's history, which a continuation begins
%! ## anew) to Newton's tolerance
%! for s = {@odeSE, @odeSV, @odeSPVI}
%!   a = s{1} (f, [0 1], [1; 0], symplecticset ("TimeStepNumber", 7));
%!   c = s{1} (f, [1 3], a);
%!   w = s{1} (f, [0 3], [1; 0], symplecticset ("TimeStepSize", 1/7));
%!   assert (isequal (c.x, w.x));
%!   assert (c.y, w.y, 1e-14);
%! endfor

%!test
%! ## odeSPVI fixed steps continued: the steps' grid to the bit, the states
%! ## to Newton's tolerance
%! o = symplecticset ("TimeStepSize", 0.01);
%! w = odeSPVI (f, [0 23.5], [1; 0], o);
%! a = odeSPVI (f, [0 10.05], [1; 0], o);
%! c = odeSPVI (f, [10.05 23.5], a);
%! assert (isequal (c.x, w.x));
%! assert (c.y, w.y, 1e-13);

%!test
%! ## fixed steps retraced: Verlet is symmetric, back to y0 to round-off;
%! ## symplectic Euler is not, and misses by O(h)
%! o = symplecticset ("TimeStepSize", 0.1, "Separable", "on");
%! g = @(t, y) [y(2); -sin(y(1))];
%! a = odeSV (g, [0 9.95], [1; 0], o);
%! b = odeSV (g, [9.95 0], a);
%! assert (b.x(end), 0);
%! assert (b.y(:,end), [1; 0], 1e-13);
%! a = odeSE (g, [0 9.95], [1; 0], o);
%! b = odeSE (g, [9.95 0], a);
%! assert (norm (b.y(:,end) - [1; 0]) > 1e-3);

%!test
%! ## standard adaptive steps: continued from the end with the run's
%! ## options (the rows after the first are the run from sol's end with
%! ## them); the oscillator's exact solution
%! h = @(t, y) [y(2); -y(1)];
%! o = symplecticset ("RelTol", 1e-8, "AbsTol", 1e-10);
%! a = odeSV (h, [0 2], [1; 0], o);
%! c = odeSV (h, [2 5], a);
%! r = odeSV (h, [2 5], a.y(:,end), o);
%! assert (isequal (c.x, [a.x, r.x(2:end)]) && isequal (c.y, [a.y, r.y(:,2:end)]));
%! w = odeSV (h, [0 5], [1; 0], o);
%! assert (c.y(:,end), [cos(5); -sin(5)], 4e-6);     # the whole run's 1.5e-6
%! assert (c.y(:,end), w.y(:,end), 1e-7);
%! ## options given replace the run's
%! c = odeSV (h, [2 5], a, symplecticset ("TimeStepSize", 0.5));
%! assert (c.x(end-6:end), 2:0.5:5, 1e-14);

%!test
%! ## output times beyond the end, events of the continuation only, Dense
%! ## and the Hamiltonian joined
%! g = @(t, y) [y(2); -y(1)];
%! ev = @(t, y) deal (y(1), 0, 0);                  # q = cos t through 0
%! o = symplecticset ("TimeStepSize", 0.01, "Separable", "on", "Events", ev,
%!                    "Dense", "on", "Hamiltonian", @(t, y) sum (y.^2)/2);
%! a = odeSV (g, [0 2.005], [1; 0], o);
%! c = odeSV (g, [2.005 6], a);
%! w = odeSV (g, [0 6], [1; 0], o);
%! assert (isequal (c.x, w.x) && isequal (c.y, w.y) && isequal (c.H, w.H));
%! assert (c.xe, [pi/2; 3*pi/2], 1e-4);
%! assert (isequal (c.xe, w.xe));
%! assert (isequal (c.dense.t, w.dense.t) && isequal (c.dense.y, w.dense.y));
%! [t, y, te] = odeSV (g, [2.005 3 4 6], a);
%! assert (t, [2.005; 3; 4; 6]);
%! assert (y(:,1), cos (t), 1e-4);
%! assert (te, 3*pi/2, 1e-4);

## errors: they name the solver and the argument
%!shared g, sv, sp
%! g = @(t, y) [y(2); -y(1)];
%! sv = odeSV (g, [0 1], [1; 0], symplecticset ("TimeStepSize", 0.1));
%! sp = odeSPVI (g, [0 1], [1; 0], symplecticset ("TimeStepSize", 0.1));
%!error <odeSE: Y0 is the sol of a run of odeSV> odeSE (g, [1 2], sv)
%!error <odeSV: Y0 is the sol of a run of odeSPVI> odeSV (g, [1 2], sp)
%!error <odeSPVI: Y0 is the sol of a run of odeSV> odeSPVI (g, [1 2], sv)
%!error <odeSV: with a sol as Y0, TSPAN\(1\) must be its end> odeSV (g, [0.9 2], sv)
%!error <odeSV: with a sol as Y0, TSPAN\(1\) must be its end> odeSV (g, [0 2], sv)
%!error <odeSV: Y0 must be a non-empty real numeric vector \[q0; p0\] or the sol of a run of odeSV, got 1x1 struct> odeSV (g, [1 2], struct ("x", 1))
%!error <odeSPVI: Y0 has no field y> odeSPVI (g, [0 1], struct ("symplectic_restart", true))
%!error <odeSE: TSPAN must be a real vector> odeSE (g, 1, odeSE (g, [0 1], [1; 0]))
%!error <odeSV: Y0 is a sol with no rows> odeSV (g, [1 2], struct ("x", [0 1], "y", ones (2, 2, 2), "solver", "odeSV"))
