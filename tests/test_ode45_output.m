## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## The ode45 contract of odeSE, odeSV and odeSPVI, output: output times and
## dense output, events, OutputFcn/OutputSel/odeplot, Refine.  References
## are exact: Kepler's problem through Kepler's equation (solved by Newton),
## the harmonic oscillator through cos and sin.

%!function Y = kepler_exact (t, e)
%!  ## a = 1, period 2*pi, periapsis at t = 0 on the q1 axis:
%!  ## y(0) = [1-e; 0; 0; sqrt((1+e)/(1-e))]; rows of [q1 q2 p1 p2]
%!  t = t(:);  E = t;
%!  for it = 1:60
%!    dE = (E - e * sin (E) - t) ./ (1 - e * cos (E));
%!    E -= dE;
%!    if (max (abs (dE)) < 1e-15)
%!      break;
%!    endif
%!  endfor
%!  den = 1 - e * cos (E);  b = sqrt (1 - e^2);
%!  Y = [cos(E) - e, b * sin(E), -sin(E) ./ den, b * cos(E) ./ den];
%!endfunction

%!function dy = kepler (t, y)
%!  ## accepts a 4-by-k matrix of states (Vectorized)
%!  q = y(1:2, :);
%!  r = sqrt (sum (q.^2, 1));
%!  dy = [y(3:4, :); -q ./ r.^3];
%!endfunction

%!function [v, term, dir] = ev_q (t, y)
%!  v = y(1);  term = 0;  dir = 0;
%!endfunction

%!function [v, term, dir] = ev_q_terminal (t, y)
%!  v = y(1);  term = 1;  dir = 0;
%!endfunction

%!function [v, term, dir] = ev_q_p (t, y)
%!  ## 1: q falling through 0; 2: p rising through 0; neither terminal
%!  v = [y(1); y(2)];  term = [0; 0];  dir = [-1; 1];
%!endfunction

%!function stop = recorder (t, y, flag, varargin)
%!  ## logs every call; stops on a row with t >= CONTRACT_TSTOP
%!  global CONTRACT_LOG CONTRACT_TSTOP
%!  CONTRACT_LOG(end+1, :) = {t, y, flag, varargin};
%!  stop = isempty (flag) && ! isempty (CONTRACT_TSTOP) && t >= CONTRACT_TSTOP;
%!endfunction

%!function dy = osc_par (t, y, w, s)
%!  assert (nargin == 4 && strcmp (s, "tag"));
%!  dy = [y(2); -w^2 * y(1)];
%!endfunction

%!shared solvers
%! solvers = {@odeSE, @odeSV, @odeSPVI};

## ------------------------------------------------------------ dense output
%!test
%! ## odeSPVI (Q_DoFs 4, Nodes 3), h = 2*pi/100 on Kepler (e = 0.6) over 10
%! ## periods: rows at 1000 times that are not step points (each 0.37 h
%! ## after one) are as accurate as the step points.
%! e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];  h = 2*pi/100;  tf = 20*pi;
%! o = symplecticset ("TimeStepSize", h, "Q_DoFs", 4, "Nodes", 3);
%! [ts, ys] = odeSPVI (@kepler, [0 tf], y0, o);
%! assert (numel (ts), 1001);
%! err_step = max (max (abs (ys - kepler_exact (ts, e))));
%! tt = ((0:999) + 0.37) * h;
%! frac = tt / h - floor (tt / h);
%! assert (min (min (frac, 1 - frac)) > 0.3);   # far from step points
%! [t, y] = odeSPVI (@kepler, [0 tt tf], y0, o);
%! assert (t(2:end-1), tt(:));
%! err_dense = max (max (abs (y(2:end-1, :) - kepler_exact (tt, e))));
%! assert (err_step < 2e-4 && err_step > 0);
%! assert (err_dense <= 10 * err_step, "dense %.3g step %.3g", err_dense, err_step);
%! ## the last row is the step point at tf itself
%! assert (y(end, :), ys(end, :), 1e-14);

%!test
%! ## odeSE and odeSV: the dense output has the method's order (error at
%! ## 100 output times off the step grid: /2 resp. /4 when h halves)
%! e = 0.2;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];  tf = pi;
%! tt = ((0:99) + 0.37) * tf / 100;
%! cases = {@odeSE, tf ./ [200 400 800], 1; @odeSV, tf ./ [25 50 100], 2};
%! for i = 1:2
%!   hs = cases{i, 2};  err = zeros (size (hs));
%!   for j = 1:numel (hs)
%!     o = symplecticset ("TimeStepSize", hs(j), "Separable", "on");
%!     [t, y] = cases{i, 1} (@kepler, [0 tt tf], y0, o);
%!     err(j) = max (max (abs (y(2:end-1, :) - kepler_exact (tt, e))));
%!   endfor
%!   s = log2 (err(1:end-1) ./ err(2:end));
%!   assert (all (abs (s - cases{i, 3}) <= 0.15), "%s slopes %s",
%!           func2str (cases{i, 1}), mat2str (s, 3));
%! endfor

## ------------------------------------------------------------ events
%!test
%! ## a zero that touches without a change of sign counts only on a step
%! ## point (as the help says)
%! f = @(t, y) [y(2); -y(1)];
%! ev = @(t, y) deal ((t - 0.5)^2, 0, 0);
%! for i = 1:3
%!   [~, ~, te] = solvers{i} (f, [0 1], [1; 0], symplecticset ("TimeStepSize", 0.1, "Events", ev));
%!   assert (te, 0.5);
%!   [~, ~, te] = solvers{i} (f, [0 1], [1; 0], symplecticset ("TimeStepSize", 0.3, "Events", ev));
%!   assert (isempty (te));
%! endfor

%!test
%! ## the shapes of the event outputs, as ode45's: with no event all are
%! ## 0-by-0 (they were 0-by-1, 0-by-2, 0-by-1), with k events te and ie
%! ## are k-by-1 and ye k-by-2
%! f = @(t, y) [y(2); -y(1)];
%! for ev = {@(t, y) deal(y(1) - 5, 0, 0), @(t, y) deal(y(1), 0, 0)}
%!   o = odeset ("Events", ev{1});
%!   [~, ~, te0, ye0, ie0] = ode45 (f, [0 4], [1; 0], o);
%!   s0 = ode45 (f, [0 4], [1; 0], o);
%!   for i = 1:3
%!     [~, ~, te, ye, ie] = solvers{i} (f, [0 4], [1; 0], o);
%!     assert ([size(te); size(ye); size(ie)], [size(te0); size(ye0); size(ie0)]);
%!     s = solvers{i} (f, [0 4], [1; 0], o);
%!     assert ([size(s.xe); size(s.ye); size(s.ie)], [size(s0.xe); size(s0.ye); size(s0.ie)]);
%!   endfor
%! endfor
%! [~, ~, te, ye, ie] = odeSV (f, [0 1], [1; 0]);
%! assert ([size(te); size(ye); size(ie)], zeros (3, 2));

%!test
%! ## harmonic oscillator, q = 0 at pi/2 + k pi: odeSPVI to 1e-10
%! f = @(t, y) [y(2); -y(1)];
%! texact = pi/2 + (0:2)' * pi;
%! runs = {symplecticset("TimeStepSize", 0.02), ...
%!         symplecticset("RelTol", 1e-14, "AbsTol", 1e-14)};
%! for i = 1:2
%!   o = symplecticset (runs{i}, "Events", @ev_q);
%!   [t, y, te, ye, ie] = odeSPVI (f, [0 10], [1; 0], o);
%!   assert (numel (te), 3);
%!   assert (te, texact, 1e-10);
%!   assert (abs (ye(:, 1)) < 1e-14);
%!   assert (ye(:, 2), -sin (texact), 1e-8);
%!   assert (ie, ones (3, 1));
%!   assert (t(end), 10);          # non-terminal: the run goes on
%! endfor

%!test
%! ## odeSE / odeSV with a fixed step h: event times within h resp. h^2
%! ## (their global errors; measured 0.50 h and 0.33 h^2)
%! f = @(t, y) [y(2); -y(1)];
%! texact = pi/2 + (0:2)' * pi;
%! h = 0.01;
%! for k = 1:2
%!   solver = {@odeSE, @odeSV}{k};
%!   o = symplecticset ("TimeStepSize", h, "Events", @ev_q);
%!   [t, y, te, ye, ie] = solver (f, [0 10], [1; 0], o);
%!   assert (numel (te), 3);
%!   assert (te, texact, h^k);
%!   assert (abs (ye(:, 1)) < 1e-14);    # located on the dense output
%! endfor

%!test
%! ## a terminal event ends the run there: last row = event row
%! f = @(t, y) [y(2); -y(1)];
%! h = 0.1;
%! for i = 1:3
%!   o = symplecticset ("TimeStepSize", h, "Events", @ev_q_terminal);
%!   [t, y, te, ye, ie] = solvers{i} (f, [0 10], [1; 0], o);
%!   assert (te, pi/2, h);
%!   assert (t(end), te);
%!   assert (y(end, :), ye);
%!   assert (abs (ye(1)) < 1e-14);
%!   assert (ie, 1);
%!   grid = (0:100)' * h;
%!   assert (t(1:end-1), grid(grid < te), 1e-13);   # the steps before te
%!   ## with Refine and with output times
%!   [t, y, te] = solvers{i} (f, [0 10], [1; 0], symplecticset (o, "Refine", 3));
%!   assert (t(end), te);
%!   grid = (0:300)' * h / 3;
%!   assert (t(1:end-1), grid(grid < te), 1e-13);
%!   [t, y, te] = solvers{i} (f, [0 1 2 3], [1; 0], o);
%!   assert (t, [0; 1; te]);
%!   ## sol output
%!   sol = solvers{i} (f, [0 10], [1; 0], o);
%!   assert (sol.xe, te);
%!   assert (sol.x(end), te);
%!   assert (sol.ye, y(end, :));
%!   assert (sol.ie, 1);
%! endfor

%!test
%! ## direction filtering and event indices; backward as well
%! f = @(t, y) [y(2); -y(1)];
%! for i = 1:3
%!   o = symplecticset ("TimeStepSize", 0.01, "Events", @ev_q_p);
%!   [t, y, te, ye, ie] = solvers{i} (f, [0 10], [1; 0], o);
%!   ## q falls through 0 at pi/2, 5pi/2; p = -sin t rises through 0 at pi, 3pi
%!   assert (ie, [1; 2; 1; 2]);
%!   assert (te, [pi/2; pi; 5*pi/2; 3*pi], 1e-2);
%!   sol = solvers{i} (f, [0 10], [1; 0], o);
%!   assert (sol.xe, te);
%!   assert (sol.ye, ye);
%!   assert (sol.ie, ie);
%!   ## backwards from 0 to -10 (directions as t runs backwards): q falls
%!   ## through 0 at -pi/2 and -5pi/2, p rises at -2pi
%!   [t, y, te, ye, ie] = solvers{i} (f, [0 -10], [1; 0], o);
%!   assert (ie, [1; 2; 1]);
%!   assert (te, [-pi/2; -2*pi; -5*pi/2], 1e-2);
%! endfor

%!test
%! ## many event functions crossing in one step are all found, in time
%! ## order, up to the terminal one (the last to cross)
%! f = @(t, y) [y(2); -y(1)];
%! c = linspace (0.99, 0.9, 100)';
%! term = [zeros(99, 1); 1];
%! ev = @(t, y) deal (y(1) - c, term, zeros (100, 1));
%! o = symplecticset ("TimeStepSize", 0.5, "Events", ev);
%! [t, y, te, ye, ie] = odeSPVI (f, [0 10], [1; 0], o);
%! assert (ie, (1:100)');
%! assert (te, acos (c), 1e-3);
%! assert (t(end), te(end));
%! assert (numel (t), 2);

%!test
%! ## two event functions that vanish together (q and 2q): both are
%! ## reported at the stop, whichever of them is terminal
%! f = @(t, y) [y(2); -y(1)];
%! for i = 1:3
%!   for term = {[1; 0], [0; 1], [1; 1]}
%!     ev = @(t, y) deal ([y(1); 2*y(1)], term{1}, [0; 0]);
%!     o = symplecticset ("TimeStepSize", 0.1, "Events", ev);
%!     [t, y, te, ye, ie] = solvers{i} (f, [0 10], [1; 0], o);
%!     assert (ie, [1; 2]);
%!     assert (te, [pi/2; pi/2], 0.1^i);
%!     assert (te(1), te(2), 4 * eps);
%!     assert (t(end), te(find (term{1}, 1)));
%!   endfor
%! endfor
%! ## q and tanh(q) crossing near t = 0 (adaptive): located 1e-17 apart by
%! ## round-off, still reported together (before, one of them was lost)
%! for i = 1:3
%!   for t0 = [-1, -1.001]
%!     ev = @(t, y) deal ([y(1); tanh(y(1))], [0; 1], [1; 1]);
%!     o = symplecticset ("RelTol", 1e-8, "AbsTol", 1e-10, "Events", ev);
%!     [t, y, te, ye, ie] = solvers{i} (f, [t0 3], [sin(t0); cos(t0)], o);
%!     assert (sort (ie), [1; 2]);
%!     assert (te(1), te(2), 1e-15);
%!     assert (abs (te(1)) < 1e-3);    # odeSE: 4.5e-5
%!   endfor
%! endfor

## ------------------------------------------------------------ OutputFcn
%!test
%! ## init (tspan, y0), every returned row with flag "", then done
%! global CONTRACT_LOG CONTRACT_TSTOP
%! f = @(t, y) [y(2); -y(1)];
%! for i = 1:3
%!   for tspan = {[0 1], [0 0.25 0.5 1]}
%!     CONTRACT_LOG = cell (0, 4);  CONTRACT_TSTOP = [];
%!     o = symplecticset ("TimeStepSize", 0.1, "OutputFcn", @recorder);
%!     [t, y] = solvers{i} (f, tspan{1}, [1; 0], o);
%!     L = CONTRACT_LOG;
%!     assert (L{1, 3}, "init");
%!     assert (L{1, 1}(:), tspan{1}(:));
%!     assert (L{1, 2}, [1; 0]);
%!     assert (L{end, 3}, "done");
%!     assert (isempty (L{end, 1}) && isempty (L{end, 2}));
%!     rows = L(2:end-1, :);
%!     assert (all (cellfun (@(s) ischar (s) && isempty (s), rows(:, 3))));
%!     assert ([rows{:, 1}]', t(2:end));
%!     assert ([rows{:, 2}]', y(2:end, :));
%!   endfor
%! endfor

%!test
%! ## a true return value stops the run; the rows so far are returned
%! global CONTRACT_LOG CONTRACT_TSTOP
%! f = @(t, y) [y(2); -y(1)];
%! for i = 1:3
%!   CONTRACT_LOG = cell (0, 4);  CONTRACT_TSTOP = 0.45;
%!   o = symplecticset ("TimeStepSize", 0.1, "OutputFcn", @recorder);
%!   lastwarn ("");
%!   evalc ("[t, y] = solvers{i} (f, [0 1], [1; 0], o);");
%!   [~, id] = lastwarn ();
%!   assert (id, "symplectic:output-stop");
%!   assert (t, (0:0.1:0.5)', 1e-15);
%!   rows = CONTRACT_LOG(2:end-1, :);
%!   assert ([rows{:, 1}]', t(2:end));
%!   assert ([rows{:, 2}]', y(2:end, :));
%!   assert (CONTRACT_LOG{end, 3}, "done");
%!   ## the same with Refine: stops at a refined row
%!   CONTRACT_LOG = cell (0, 4);  CONTRACT_TSTOP = 0.42;
%!   evalc ("[t, y] = solvers{i} (f, [0 1], [1; 0], symplecticset (o, 'Refine', 4));");
%!   assert (t, (0:17)' * 0.025, 1e-15);
%!   rows = CONTRACT_LOG(2:end-1, :);
%!   assert ([rows{:, 1}]', t(2:end));
%! endfor
%! CONTRACT_TSTOP = [];

%!test
%! ## a stop inside a step (at an output time or a refined row) returns no
%! ## event after t(end), as ode45; a stop on the last row (tf) does not warn
%! f = @(t, y) [y(2); -y(1)];                 # q = cos t: zero at pi/2
%! ev = @(t, y) deal (y(1), 0, 0);
%! for i = 1:3
%!   o = odeset ("Events", ev, "OutputFcn", @(t, y, fl) isempty (fl) && t(end) >= 1.2);
%!   warning ("off", "symplectic:output-stop", "local");
%!   [t, y, te, ye, ie] = solvers{i} (f, 0:0.1:10, [1; 0], o);
%!   assert (t(end), 1.2, 1e-12);
%!   assert (size (te, 1), 0);
%!   assert (size (ye, 1), 0);
%!   assert (size (ie, 1), 0);
%!   o = symplecticset ("TimeStepSize", 2, "Refine", 10, "Events", ev, ...
%!                      "OutputFcn", @(t, y, fl) isempty (fl) && t(end) >= 0.4);
%!   sol = solvers{i} (f, [0 4], [1; 0], o);
%!   [t, y, te] = solvers{i} (f, [0 4], [1; 0], o);
%!   assert (t(end), 0.4, 1e-12);
%!   assert (size (te, 1), 0);
%!   ## the stop after the event's row keeps the event
%!   o = symplecticset (o, "OutputFcn", @(t, y, fl) isempty (fl) && t(end) >= 1.8);
%!   [t, y, te] = solvers{i} (f, [0 4], [1; 0], o);
%!   assert (t(end), 1.8, 1e-12);
%!   assert (numel (te), 1);         # h = 2: odeSE's zero is at 0.79
%!   assert (te > 0 && te < 1.8);
%!   warning ("on", "symplectic:output-stop", "local");
%!   lastwarn ("");
%!   o = odeset ("OutputFcn", @(t, y, fl) isempty (fl) && t(end) >= 1);
%!   [t, y] = solvers{i} (f, [0 1], [1; 0], o);
%!   assert (t(end), 1);
%!   assert (lastwarn (), "");
%! endfor

%!test
%! ## the stop flag as "if" takes it: all elements nonzero stops (a char
%! ## too), a zero or empty value goes on; NaN and other classes are errors
%! f = @(t, y) [y(2); -y(1)];
%! stops = {"yes", int8(2), [1 1], single(1), sparse(1)};
%! goes = {[], [1 0], 0, false, int32(0), ""};
%! for i = 1:3
%!   for v = stops
%!     o = symplecticset ("TimeStepSize", 0.1, "OutputFcn", @(t, y, fl) v{1});
%!     warning ("off", "symplectic:output-stop", "local");
%!     [t, y] = solvers{i} (f, [0 1], [1; 0], o);
%!     assert (t, [0; 0.1], 1e-15);
%!   endfor
%!   for v = goes
%!     o = symplecticset ("TimeStepSize", 0.1, "OutputFcn", @(t, y, fl) v{1});
%!     [t, y] = solvers{i} (f, [0 1], [1; 0], o);
%!     assert (numel (t), 11);
%!   endfor
%!   name = func2str (solvers{i});
%!   bad = {NaN, [1 NaN], {1}, struct("a", 1), 1i, @sin};
%!   for k = 1:numel (bad)
%!     o = symplecticset ("TimeStepSize", 0.1, "OutputFcn", @(t, y, fl) bad{k});
%!     msg = "";
%!     try
%!       [t, y] = solvers{i} (f, [0 1], [1; 0], o);
%!     catch err
%!       msg = err.message;
%!     end_try_catch
%!     if (k <= 2)
%!       assert (msg, [name ": OutputFcn returned NaN as its stop flag at t = 0.1"]);
%!     else
%!       pre = [name ": OutputFcn must return a logical or real numeric stop flag, got "];
%!       assert (strncmp (msg, pre, numel (pre)));
%!     endif
%!   endfor
%! endfor

%!test
%! ## OutputSel: only the selected components; extra parameters arrive
%! global CONTRACT_LOG CONTRACT_TSTOP
%! CONTRACT_TSTOP = [];
%! for i = 1:3
%!   CONTRACT_LOG = cell (0, 4);
%!   o = symplecticset ("TimeStepSize", 0.1, "OutputFcn", @recorder, "OutputSel", 2);
%!   [t, y] = solvers{i} (@osc_par, [0 1], [1; 0], o, 2, "tag");
%!   assert (CONTRACT_LOG{1, 2}, 0);
%!   rows = CONTRACT_LOG(2:end-1, :);
%!   assert ([rows{:, 2}]', y(2:end, 2));
%!   assert (all (cellfun (@(c) isequal (c, {2, "tag"}), CONTRACT_LOG(:, 4))));
%!   CONTRACT_LOG = cell (0, 4);
%!   o = symplecticset (o, "OutputSel", [2 1]);
%!   [t, y] = solvers{i} (@osc_par, [0 1], [1; 0], o, 2, "tag");
%!   rows = CONTRACT_LOG(2:end-1, :);
%!   assert ([rows{:, 2}]', y(2:end, [2 1]));
%! endfor

%!test
%! ## odeplot as OutputFcn (off-screen), and no output argument: a plot
%! old = get (0, "defaultfigurevisible");
%! set (0, "defaultfigurevisible", "off");
%! warning ("off", "Octave:gnuplot-graphics", "local");
%! unwind_protect
%!   f = @(t, y) [y(2); -y(1)];
%!   o = symplecticset ("TimeStepSize", 0.1, "OutputFcn", @odeplot);
%!   for i = 1:3
%!     hf = figure ();
%!     [t, y] = solvers{i} (f, [0 2], [1; 0], o);
%!     hl = get (gca (), "children");
%!     assert (numel (hl), 2);
%!     for k = 1:2
%!       assert (get (hl(k), "xdata")(:), t);
%!     endfor
%!     assert (sort ([get(hl(1), "ydata")(end), get(hl(2), "ydata")(end)]),
%!             sort (y(end, :)));
%!     close all;
%!     solvers{i} (f, [0 2], [1; 0], symplecticset ("TimeStepSize", 0.1));
%!     assert (! isempty (get (0, "currentfigure")));
%!     close all;
%!   endfor
%! unwind_protect_cleanup
%!   close all;
%!   set (0, "defaultfigurevisible", old);
%! end_unwind_protect

## ------------------------------------------------------------ Refine
%!test
%! ## default 1 (step points); Refine = 4: 4 rows per step from the dense
%! ## output; ignored with more than two tspan elements and for sol
%! f = @(t, y) [y(2); -y(1)];
%! tol = [0.06, 5e-3, 1e-7];     # the methods' accuracy at h = 0.1
%! for i = 1:3
%!   o = symplecticset ("TimeStepSize", 0.1);
%!   [t, y] = solvers{i} (f, [0 10], [1; 0], o);
%!   assert (t, (0:100)' * 0.1, 1e-13);
%!   o.Refine = 4;
%!   [t, y] = solvers{i} (f, [0 10], [1; 0], o);
%!   assert (numel (t), 401);
%!   assert (t, (0:400)' * 0.025, 1e-13);
%!   assert (y, [cos(t), -sin(t)], tol(i));
%!   ## rows at step points are the same as without Refine
%!   [t1, y1] = solvers{i} (f, [0 10], [1; 0], symplecticset (o, "Refine", 1));
%!   assert (y(1:4:end, :), y1, 1e-14);
%!   [t, y] = solvers{i} (f, [0 1 2.5 10], [1; 0], o);
%!   assert (t, [0; 1; 2.5; 10]);
%!   sol = solvers{i} (f, [0 10], [1; 0], o);
%!   assert (numel (sol.x), 101);
%!   ## adaptive
%!   oa = symplecticset ("RelTol", 1e-6, "Refine", 4);
%!   sa = solvers{i} (f, [0 10], [1; 0], oa);
%!   [t, y] = solvers{i} (f, [0 10], [1; 0], oa);
%!   assert (numel (t), 4 * sa.stats.nsteps + 1);
%!   assert (t(1:4:end), sa.x(:));
%! endfor
