## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## Ensembles (Ensemble "on"): the columns of Y0 are members integrated
## together.  The truth every result is held to is the run of each member
## alone: with a fixed step its rows, events and stats must equal a single
## run's to the bit (isequal), whatever the number and order of members;
## adaptive members (each with its own steps) too, in the sol form.

%!function dy = kep (t, y)
%!  ## Kepler, vectorized: a column per state; no power (.^), which
%!  ## Octave computes for a lone value by pow and for an array by
%!  ## products, now and then a bit apart: a column alone and in a batch
%!  ## give the same numbers
%!  r = sqrt (y(1,:) .* y(1,:) + y(2,:) .* y(2,:));
%!  r3 = r .* r .* r;
%!  dy = [y(3,:); y(4,:); -y(1,:) ./ r3; -y(2,:) ./ r3];
%!endfunction

%!function dy = kep_pow (t, y)
%!  ## the same with powers: a column alone and in a batch differ
%!  r = sqrt (y(1,:).^2 + y(2,:).^2);
%!  dy = [y(3,:); y(4,:); -y(1,:) ./ r.^3; -y(2,:) ./ r.^3];
%!endfunction

%!function Y0 = kep_y0 (e)
%!  e = e(:)';
%!  Y0 = [1 - e; 0 * e; 0 * e; sqrt((1 + e) ./ (1 - e))];
%!endfunction

%!function dy = pend_cut (t, y)
%!  ## the pendulum, NaN once q is past 3 (a member that goes over the
%!  ## top fails there; the others swing)
%!  dy = [y(2,:); -sin(y(1,:))];
%!  dy(:, abs (y(1,:)) > 3) = NaN;
%!endfunction

%!function [v, term, dir] = cross_q1 (t, y)
%!  ## q1 = 0 downwards, terminal: each Kepler member at its own time
%!  v = y(1);  term = 1;  dir = -1;
%!endfunction

%!function [v, term, dir] = cross_q2 (t, y)
%!  ## q2 = 0 either way, not terminal
%!  v = y(2);  term = 0;  dir = 0;
%!endfunction

%!function dy = kep_counted (t, y)
%!  global ens_calls
%!  ens_calls += 1;
%!  dy = kep (t, y);
%!endfunction

%!function dy = kep_scaled (t, y, mu)
%!  dy = kep (t, y);
%!  dy(3:4,:) *= mu;
%!endfunction

%!function same_sol (a, b)
%!  ## a member's sol against its own run's b: equal to the bit, except
%!  ## that b's counts include the calls that probe FCN before the run
%!  ## (the ensemble makes them once, for member 1, and counts them in
%!  ## Stats, not in each member's sol)
%!  sa = a.stats;  sb = b.stats;
%!  a = rmfield (a, "stats");  b = rmfield (b, "stats");
%!  ## a member's sol does not continue (no restart: see odeSV's help)
%!  assert (! isfield (a, "restart"));
%!  if (isfield (b, "restart"))
%!    b = rmfield (b, "restart");
%!  endif
%!  assert (isequal (a, b));
%!  probe = sb.nfevals - sa.nfevals;
%!  assert (probe >= 1 && probe <= 2);
%!  assert (sb.nstates - sa.nstates >= probe);
%!  sa = rmfield (sa, {"nfevals", "nstates"});
%!  sb = rmfield (sb, {"nfevals", "nstates"});
%!  assert (isequal (sa, sb));
%!endfunction

%!function stop = record_out (t, y, flag)
%!  global ens_out
%!  ens_out{end+1} = {t, y, flag};
%!  stop = false;
%!endfunction

%!function stop = stop_at_one (t, y, flag)
%!  stop = ! isempty (t) && strcmp (flag, "") && t(1) >= 1;
%!endfunction

## ------------------------------------------------------------ bit-identity
%!test
%! ## every solver, fixed steps, FCN state by state: each member is its
%! ## own run to the bit, also in another order and alone
%! Y0 = kep_y0 ([0.1 0.3 0.5 0.7 0.2]);
%! perm = [4 1 5 3 2];
%! runs = {@odeSPVI, {}; @odeSPVI, {"Nodes", 2, "Q_DoFs", 2}; ...
%!         @odeSV, {}; @odeSV, {"Separable", "on"}; ...
%!         @odeSV, {"Method", "yoshida4"}; @odeSE, {}; ...
%!         @odeSE, {"Separable", "on"}};
%! for i = 1:rows (runs)
%!   s = runs{i,1};
%!   o1 = symplecticset ("TimeStepSize", 0.05, runs{i,2}{:});
%!   o = symplecticset (o1, "Ensemble", "on");
%!   [t, Y] = s (@kep, [0 4], Y0, o);
%!   assert (size (Y), [81 4 5]);
%!   for k = 1:5
%!     [t1, y1] = s (@kep, [0 4], Y0(:,k), o1);
%!     assert (isequal (t, t1) && isequal (Y(:,:,k), y1), ...
%!             "%s %d member %d", func2str (s), i, k);
%!   endfor
%!   [~, Yp] = s (@kep, [0 4], Y0(:,perm), o);
%!   assert (isequal (Yp, Y(:,:,perm)));
%!   [~, Y1] = s (@kep, [0 4], Y0(:,3), o);
%!   assert (isequal (Y1, Y(:,:,3)));
%! endfor

%!test
%! ## Vectorized: one call for all members; each member is its own
%! ## Vectorized run to the bit when FCN computes a column alike in any
%! ## batch (kep)
%! Y0 = kep_y0 (linspace (0.05, 0.8, 9));
%! for s = {@odeSPVI, @odeSV, @odeSE}
%!   o1 = symplecticset ("TimeStepSize", 0.05, "Vectorized", "on");
%!   o = symplecticset (o1, "Ensemble", "on");
%!   [t, Y] = s{1} (@kep, [0 3], Y0, o);
%!   for k = [1 5 9]
%!     [t1, y1] = s{1} (@kep, [0 3], Y0(:,k), o1);
%!     assert (isequal (t, t1) && isequal (Y(:,:,k), y1));
%!   endfor
%! endfor

%!test
%! ## Vectorized with an FCN whose lone column differs from a column in a
%! ## batch: a member still does not depend on the others, their number
%! ## or their order (a lone state goes as two equal columns)
%! Y0 = kep_y0 (linspace (0.05, 0.8, 6));
%! o = symplecticset ("TimeStepSize", 0.05, "Vectorized", "on", ...
%!                    "Ensemble", "on");
%! for s = {@odeSPVI, @odeSV}
%!   [~, Y] = s{1} (@kep_pow, [0 3], Y0, o);
%!   [~, Yr] = s{1} (@kep_pow, [0 3], fliplr (Y0), o);
%!   [~, Y4] = s{1} (@kep_pow, [0 3], Y0(:,4), o);
%!   assert (isequal (Yr, Y(:,:,end:-1:1)));
%!   assert (isequal (Y4, Y(:,:,4)));
%! endfor

%!test
%! ## adaptive steps are each member's own: sol(k) is its own run's sol
%! Y0 = kep_y0 ([0.2 0.6 0.4]);
%! o1 = symplecticset ("RelTol", 1e-7, "AbsTol", 1e-9);
%! o = symplecticset (o1, "Ensemble", "on");
%! for s = {@odeSPVI, @odeSV, @odeSE}
%!   sol = s{1} (@kep, [0 5], Y0, o);
%!   assert (size (sol), [1 3]);
%!   for k = 1:3
%!     same_sol (sol(k), s{1} (@kep, [0 5], Y0(:,k), o1));
%!   endfor
%!   ## the members took different steps
%!   assert (numel (sol(1).x) != numel (sol(2).x));
%! endfor

%!test
%! ## adaptive steps with output times: rows on the shared times
%! Y0 = kep_y0 ([0.2 0.6]);
%! o1 = symplecticset ("RelTol", 1e-8);
%! tout = linspace (0, 5, 11);
%! [t, Y] = odeSPVI (@kep, tout, Y0, symplecticset (o1, "Ensemble", "on"));
%! assert (t, tout');
%! for k = 1:2
%!   [~, y1] = odeSPVI (@kep, tout, Y0(:,k), o1);
%!   assert (isequal (Y(:,:,k), y1));
%! endfor

%!test
%! ## fixed steps with Refine and extra parameters
%! Y0 = kep_y0 ([0.2 0.6]);
%! o1 = symplecticset ("TimeStepSize", 0.1, "Refine", 3);
%! [t, Y] = odeSV (@kep_scaled, [0 2], Y0, ...
%!                 symplecticset (o1, "Ensemble", "on"), 1.5);
%! assert (numel (t), 61);
%! for k = 1:2
%!   [t1, y1] = odeSV (@kep_scaled, [0 2], Y0(:,k), o1, 1.5);
%!   assert (isequal (t, t1) && isequal (Y(:,:,k), y1));
%! endfor

%!function a = kep_acc (t, q)
%!  ## Kepler's acceleration (SecondOrder), vectorized
%!  r = sqrt (q(1,:) .* q(1,:) + q(2,:) .* q(2,:));
%!  r3 = r .* r .* r;
%!  a = [-q(1,:) ./ r3; -q(2,:) ./ r3];
%!endfunction

%!test
%! ## explicit fixed steps with Vectorized go as one stacked system: each
%! ## member is still its own run to the bit, in every explicit variant
%! Y0 = kep_y0 ([0.1 0.3 0.5 0.7 0.2 0.45]);
%! runs = {@odeSV, @kep, {"Separable", "on"}; ...
%!         @odeSV, @kep, {"Separable", "on", "Method", "yoshida4"}; ...
%!         @odeSV, @kep, {"Separable", "on", "CompensatedSummation", "on"}; ...
%!         @odeSV, @kep_acc, {"SecondOrder", "on", "Method", "blanesmoan6"}; ...
%!         @odeSE, @kep, {"Separable", "on"}; ...
%!         @odeSE, @kep_acc, {"SecondOrder", "on"}};
%! for i = 1:rows (runs)
%!   [s, f, extra] = runs{i,:};
%!   o1 = symplecticset ("TimeStepSize", 0.07, "Vectorized", "on", extra{:});
%!   for tspan = {[0 5], linspace(0, 5, 13)}
%!     [t, Y] = s (f, tspan{1}, Y0, symplecticset (o1, "Ensemble", "on"));
%!     for k = [1 4 6]
%!       [t1, y1] = s (f, tspan{1}, Y0(:,k), o1);
%!       assert (isequal (t, t1) && isequal (Y(:,:,k), y1), "run %d member %d", i, k);
%!     endfor
%!   endfor
%! endfor

%!test
%! ## a member that fails in the stacked system: the members run again on
%! ## their own, and only that one stops
%! Y0 = [0.5 1.0 0.3 0.2; 0 2.5 0 0.1];
%! o1 = symplecticset ("TimeStepSize", 0.05, "Vectorized", "on", ...
%!                     "Separable", "on");
%! warning ("off", "symplectic:nonfinite", "local");
%! [t, Y] = odeSV (@pend_cut, [0 10], Y0, symplecticset (o1, "Ensemble", "on"));
%! for k = 1:4
%!   [t1, y1] = odeSV (@pend_cut, [0 10], Y0(:,k), o1);
%!   n = numel (t1);
%!   assert (isequal (Y(1:n,:,k), y1));
%!   assert (all (isnan (Y(n+1:end,:,k)(:))));
%! endfor
%! assert (numel (t), 201);

## ------------------------------------------------------------ Vectorized cost
%!test
%! ## K members with Vectorized cost the calls of one member (an explicit
%! ## step: the same rounds), not K times as many
%! global ens_calls
%! Y0 = kep_y0 (linspace (0.05, 0.8, 50));
%! o = symplecticset ("TimeStepSize", 0.05, "Vectorized", "on", ...
%!                    "Separable", "on");
%! ens_calls = 0;
%! [~, y] = odeSV (@kep_counted, [0 5], Y0(:,1), o);
%! one = ens_calls;
%! ens_calls = 0;
%! [~, Y] = odeSV (@kep_counted, [0 5], Y0, symplecticset (o, "Ensemble", "on"));
%! assert (ens_calls <= one + 2);
%! assert (all (isfinite (Y(:))));
%! clear -global ens_calls

## ------------------------------------------------------------ events
%!test
%! ## a terminal event each member reaches at its own time: it stops
%! ## there alone (NaN rows after its last step, the state at the event
%! ## in ye), the others go on; te, ye as the members' own runs
%! Y0 = kep_y0 ([0.1 0.4 0.7]);
%! o1 = symplecticset ("TimeStepSize", 0.01, "Events", @cross_q1);
%! [t, Y, te, ye, ie] = odeSPVI (@kep, [0 3], Y0, ...
%!                               symplecticset (o1, "Ensemble", "on"));
%! assert (ie(:,2)', [1 2 3]);
%! assert (ie(:,1)', [1 1 1]);
%! for k = 1:3
%!   [t1, y1, te1, ye1, ie1] = odeSPVI (@kep, [0 3], Y0(:,k), o1);
%!   ## the single run's last row is the event's, off the grid of h
%!   n = numel (t1) - 1;
%!   assert (isequal (Y(1:n,:,k), y1(1:n,:)));
%!   assert (all (isnan (Y(n+1:end,:,k)(:))));
%!   assert (isequal (te(k), te1) && isequal (ye(k,:), ye1));
%! endfor
%! ## t runs as far as the last member
%! assert (t(end) < te(1) && te(1) - t(end) < 0.01);

%!test
%! ## non-terminal events: each member's, member by member
%! Y0 = kep_y0 ([0.1 0.5]);
%! o1 = symplecticset ("TimeStepSize", 0.02, "Events", @cross_q2);
%! [t, Y, te, ye, ie] = odeSV (@kep, [0 15], Y0, ...
%!                             symplecticset (o1, "Ensemble", "on"));
%! for k = 1:2
%!   [~, ~, te1, ye1] = odeSV (@kep, [0 15], Y0(:,k), o1);
%!   assert (isequal (te(ie(:,2) == k), te1));
%!   assert (isequal (ye(ie(:,2) == k,:), ye1));
%! endfor
%! assert (issorted (ie(:,2)));
%! assert (sum (ie(:,2) == 1) >= 4);

%!test
%! ## no events: empty outputs as a single run's
%! o = symplecticset ("TimeStepSize", 0.1, "Events", @cross_q1, ...
%!                    "Ensemble", "on");
%! [t, Y, te, ye, ie] = odeSV (@kep, [0 0.5], kep_y0 ([0.1 0.2]), o);
%! assert (isempty (te) && isempty (ye) && isempty (ie));

%!test
%! ## sol: events in each member's sol
%! Y0 = kep_y0 ([0.1 0.7]);
%! o1 = symplecticset ("TimeStepSize", 0.01, "Events", @cross_q1);
%! sol = odeSPVI (@kep, [0 3], Y0, symplecticset (o1, "Ensemble", "on"));
%! for k = 1:2
%!   same_sol (sol(k), odeSPVI (@kep, [0 3], Y0(:,k), o1));
%! endfor

## ------------------------------------------------------------ failures
%!test
%! ## a member that fails (NaN) stops alone with a warning naming it;
%! ## the others are their own runs to the bit
%! Y0 = [0.5 1.0 0.3; 0 2.5 0];      # member 2 goes over the top
%! o1 = symplecticset ("TimeStepSize", 0.05);
%! lastwarn ("");
%! evalc ("[t, Y] = odeSV (@pend_cut, [0 10], Y0, symplecticset (o1, \"Ensemble\", \"on\"));");
%! [msg, id] = lastwarn ();
%! assert (id, "symplectic:nonfinite");
%! assert (strncmp (msg, "odeSV: member 2: ", 17));
%! for k = [1 3]
%!   [t1, y1] = odeSV (@pend_cut, [0 10], Y0(:,k), o1);
%!   assert (isequal (t, t1) && isequal (Y(:,:,k), y1));
%! endfor
%! warning ("off", "symplectic:nonfinite", "local");
%! [t2, y2] = odeSV (@pend_cut, [0 10], Y0(:,2), o1);
%! n = numel (t2);
%! assert (n < numel (t));
%! assert (isequal (Y(1:n,:,2), y2));
%! assert (all (isnan (Y(n+1:end,:,2)(:))));

%!test
%! ## many failing members: a few warnings of their own, then one count
%! Y0 = [zeros(1, 9); 2.5 * ones(1, 9)];
%! o = symplecticset ("TimeStepSize", 0.05, "Ensemble", "on");
%! warning ("off", "symplectic:nonfinite", "local");
%! lastwarn ("");
%! evalc ("[t, Y] = odeSV (@pend_cut, [0 10], Y0, o);");
%! [msg, id] = lastwarn ();
%! assert (id, "symplectic:members");
%! assert (! isempty (strfind (msg, "4 more members")));
%! assert (! isempty (strfind (msg, "member 6")));

## ------------------------------------------------------------ OutputFcn, Stats
%!test
%! ## OutputFcn: "init" with all members' y0, then each shared time with
%! ## the column of all members' OutputSel components, then "done"
%! global ens_out
%! ens_out = {};
%! Y0 = kep_y0 ([0.1 0.5]);
%! o = symplecticset ("TimeStepSize", 0.5, "Ensemble", "on", ...
%!                    "OutputFcn", @record_out, "OutputSel", [1 3]);
%! [t, Y] = odeSV (@kep, [0 2], Y0, o);
%! assert (numel (ens_out), numel (t) + 1);
%! assert (ens_out{1}{3}, "init");
%! assert (ens_out{1}{1}(:), [0; 2]);
%! assert (ens_out{1}{2}, reshape (Y0([1 3],:), [], 1));
%! for r = 2:numel (t)
%!   assert (ens_out{r}{1}, t(r));
%!   assert (ens_out{r}{2}, reshape (squeeze (Y(r,[1 3],:)), [], 1));
%! endfor
%! assert (ens_out{end}{3}, "done");
%! clear -global ens_out

%!test
%! ## OutputFcn with terminal events: its times are those of t, the rows
%! ## of the events themselves (off the grid) go to ye alone
%! global ens_out
%! ens_out = {};
%! o = symplecticset ("TimeStepSize", 0.05, "Ensemble", "on", ...
%!                    "Events", @cross_q1, "OutputFcn", @record_out);
%! [t, Y, te] = odeSV (@kep, [0 3], kep_y0 ([0.1 0.5]), o);
%! ts = cellfun (@(c) c{1}, ens_out(2:end-1));
%! assert (ts(:), t(2:end));
%! assert (numel (te), 2);
%! clear -global ens_out

%!test
%! ## OutputFcn's stop ends every member there, with one warning
%! o = symplecticset ("TimeStepSize", 0.25, "Ensemble", "on", ...
%!                    "OutputFcn", @stop_at_one);
%! lastwarn ("");
%! evalc ("[t, Y] = odeSV (@kep, [0 3], kep_y0 ([0.1 0.5 0.3]), o);");
%! [msg, id] = lastwarn ();
%! assert (id, "symplectic:output-stop");
%! assert (t(end), 1);
%! assert (size (Y), [5 4 3]);
%! assert (all (isfinite (Y(:))));

%!test
%! ## Stats: the members' counts summed
%! Y0 = kep_y0 ([0.1 0.5 0.3]);
%! o1 = symplecticset ("TimeStepSize", 0.1, "Stats", "on");
%! out = evalc ("[t, Y] = odeSV (@kep, [0 2], Y0, symplecticset (o1, \"Ensemble\", \"on\"));");
%! assert (! isempty (strfind (out, "Members: 3")));
%! assert (! isempty (strfind (out, "Number of successful steps: 60")));
%! sol = odeSV (@kep, [0 2], Y0, symplecticset (o1, "Ensemble", "on", "Stats", "off"));
%! assert ([sol.stats](2).nsteps, 20);

%!function dy = kep_fail (t, y)
%!  ## an error raised by the user's function when a member passes t = 1
%!  if (any (t > 1))
%!    error ("ens:fcn", "failing at t = %g", max (t));
%!  endif
%!  dy = kep (t, y);
%!endfunction

%!test
%! ## an error of FCN in mid-run leaves the call with its message, from
%! ## rounds and from the stacked system alike; the next call is whole
%! Y0 = kep_y0 ([0.1 0.5 0.3]);
%! for x = {{}, {"Vectorized", "on"}, {"Vectorized", "on", "Separable", "on"}}
%!   o = symplecticset ("TimeStepSize", 0.05, "Ensemble", "on", x{1}{:});
%!   try
%!     [t, Y] = odeSV (@kep_fail, [0 2], Y0, o);
%!     error ("no error");
%!   catch err
%!     assert (err.identifier, "ens:fcn");
%!   end_try_catch
%!   [t, Y] = odeSV (@kep, [0 2], Y0, o);
%!   [t1, y1] = odeSV (@kep, [0 2], Y0(:,2), rmfield (o, "Ensemble"));
%!   assert (isequal (Y(:,:,2), y1));
%! endfor

%!test
%! ## the internal share of members (Parallel's): members keep their
%! ## numbers
%! Y0 = kep_y0 ([0.1 0.5 0.3 0.2]);
%! o = symplecticset ("TimeStepSize", 0.05, "Ensemble", "on");
%! [t, Y] = odeSV (@kep, [0 1], Y0, o);
%! o.__members__ = [2 3];
%! [t2, Y2] = odeSV (@kep, [0 1], Y0, o);
%! assert (isequal (t2, t) && isequal (Y2, Y(:,:,2:3)));

## ------------------------------------------------------------ errors
%!error <odeSV: __members__ must be \[first last\], 1 <= first <= last <= 2>
%! o = symplecticset ("TimeStepSize", 0.1, "Ensemble", "on");  o.__members__ = [2 3];
%! [t, Y] = odeSV (@kep, [0 1], kep_y0 ([0.1 0.2]), o);
%!error <odeSV: with Ensemble on, Y0 must have an even number of rows>
%! t = odeSV (@kep, [0 1], ones (3, 2), symplecticset ("Ensemble", "on"));
%!error <odeSV: with Ensemble on, Y0 must be a non-empty real matrix>
%! t = odeSV (@kep, [0 1], ones (2, 2, 2), symplecticset ("Ensemble", "on"));
%!error <odeSV: with Ensemble on, Y0 must be a non-empty real matrix>
%! t = odeSV (@kep, [0 1], [], symplecticset ("Ensemble", "on"));
%!error <odeSV: Y0 must be finite, element \(2, 3\) is NaN>
%! t = odeSV (@kep, [0 1], [ones(2, 2), [1; NaN]], symplecticset ("Ensemble", "on"));
%!error <odeSPVI: Ensemble must be>
%! t = odeSPVI (@kep, [0 1], ones (4, 2), symplecticset ("Ensemble", "maybe"));
%!error <odeSPVI: with Ensemble on and adaptive steps each member takes steps of its own: \[T, Y\] needs output times>
%! [t, y] = odeSPVI (@kep, [0 1], kep_y0 ([0.1 0.2]), symplecticset ("Ensemble", "on"));
%!error <odeSPVI: with Ensemble on and adaptive steps each member takes steps of its own: OutputFcn needs output times>
%! sol = odeSPVI (@kep, [0 1], kep_y0 ([0.1 0.2]), symplecticset ("Ensemble", "on", "OutputFcn", @record_out));
%!error <odeSE: Y0 must be a non-empty real numeric vector>
%! t = odeSE (@kep, [0 1], ones (4, 2), symplecticset ("TimeStepSize", 0.1));
## an output beyond any memory (1e12 rows of 20 members: 320 TB) is said
## before the run, with the solver's name
%!error <odeSV: out of memory for the output: Y of \d+ x 2 x 20 needs 3.2e\+05 GB>
%! o = symplecticset ("TimeStepSize", 1e-5, "Ensemble", "on");
%! [t, Y] = odeSV (@(t, y) [y(2,:); -y(1,:)], [0 1e7], repmat ([1; 0], 1, 20), o);
