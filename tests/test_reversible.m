## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## Tests of StepControl "reversible" (time-symmetric variable steps,
## h_{n+1/2} = eps / rho_{n+1/2} with the symmetric recurrence of rho) in
## odeSV (Stormer-Verlet in the first-order and SecondOrder forms, and
## the symmetric Methods) and odeSPVI: reversibility, its loss under a
## density that looks at the past step only, bounded energy over long
## runs, eps against RelTol, the default density, the output features
## (output times, Refine, events, sol and symdeval, Stats), the errors
## and warnings.  References are independent of the package: the run itself
## played backward (the backward steps must mirror the forward ones and
## land on y0 to round-off), Kepler's equation (exact solution), Kepler's
## invariants (energy, angular momentum, the period 2*pi of the pericentre
## passages), ode45 at tight tolerances, and the standard adaptive control
## of the same solver at a like number of steps.

%!function y = kepler_exact (t, e)
%!  ## Kepler's problem, a = 1, from the pericentre at t = 0: Kepler's
%!  ## equation E - e sin E = t by Newton's method; one row per t
%!  y = zeros (numel (t), 4);
%!  s = sqrt (1 - e^2);
%!  for k = 1:numel (t)
%!    E = t(k) + sign (sin (t(k))) * 0.85 * e;   # Danby's start
%!    for i = 1:60
%!      dE = (E - e * sin (E) - t(k)) / (1 - e * cos (E));
%!      E -= dE;
%!      if (abs (dE) <= 1e-15 * max (1, abs (E)))
%!        break;
%!      endif
%!    endfor
%!    r = 1 - e * cos (E);
%!    y(k, :) = [cos(E) - e, s * sin(E), -sin(E) / r, s * cos(E) / r];
%!  endfor
%!endfunction

%!function dy = kep (t, y)
%!  ## Hamilton's equations of Kepler's problem, y = [q; p]
%!  q = y(1:2);
%!  dy = [y(3:4); -q / norm(q)^3];
%!endfunction

%!function a = kep_acc (t, q)
%!  ## its acceleration (SecondOrder), y = [q; v]
%!  a = -q / norm (q)^3;
%!endfunction

%!function r = lagged_rho (t, y)
%!  ## a past-only density: Kepler's norm(q)^(-1.5), but at the state of
%!  ## the PREVIOUS call (the one before the step now taken); called
%!  ## without arguments it forgets that state
%!  persistent prev
%!  if (nargin == 0)
%!    prev = [];  r = [];
%!    return;
%!  endif
%!  if (isempty (prev))
%!    prev = y;
%!  endif
%!  r = norm (prev(1:2))^(-1.5);
%!  prev = y;
%!endfunction

%!function r = bad_rho (t, y, v, ts)
%!  ## Kepler's density, but v from t = ts on
%!  if (t >= ts)
%!    r = v;
%!  else
%!    r = norm (y(1:2))^(-1.5);
%!  endif
%!endfunction

%!function r = reversal (solver, f, T, y0, o, reset)
%!  ## The recipe of reversibility: forward over [0 T]; again to the step
%!  ## point tm before the (shortened) last step, which must give the same
%!  ## steps and end exactly on tm (r.same); backward from there to 0 with
%!  ## the last forward step as the first.  r.miss: |y_back(0) - y0|_inf;
%!  ## r.nsteps: the steps forward and backward; r.dt: the largest
%!  ## |t_back - t_forward| over the mirrored times; r.dstep: the largest
%!  ## relative difference of the backward steps from the forward ones
%!  ## reversed but the backward's last, shortened to end on 0 (Inf if
%!  ## their numbers differ).  reset (optional) is called before each run.
%!  if (nargin < 6)
%!    reset = @() [];
%!  endif
%!  reset ();
%!  [t1, ~] = solver (f, [0 T], y0, o);
%!  m = numel (t1) - 1;
%!  tm = t1(m);
%!  reset ();
%!  [t2, y2] = solver (f, [0 tm], y0, o);
%!  r.same = isequal (t2, t1(1:m));
%!  hb = t2(end) - t2(end-1);
%!  reset ();
%!  [tb, yb] = solver (f, [tm 0], y2(end, :).', symplecticset (o, "InitialStep", hb));
%!  r.tend = tb(end);
%!  r.miss = norm (yb(end, :).' - y0, Inf);
%!  r.nsteps = [numel(t2), numel(tb)] - 1;
%!  r.tm = tm;
%!  r.ym = y2(end, :).';
%!  if (numel (tb) == numel (t2))
%!    h2 = diff (t2);
%!    hr = -flipud (diff (tb));
%!    r.dstep = max (abs (hr(2:end) - h2(2:end)) ./ abs (h2(2:end)));
%!    r.dt = max (abs (flipud (tb) - t2));
%!  else
%!    r.dstep = r.dt = Inf;
%!  endif
%!endfunction

%!function check_mirror (r, nmin, misstol, e, gain)
%!  ## the checks of a reversal r (see reversal): the rerun to tm took the
%!  ## same steps, the backward run ended on 0 after as many steps, mirrored
%!  ## to round-off, back on y0 within misstol, at least nmin steps, and the
%!  ## forward run's own error at tm (against Kepler's equation at
%!  ## eccentricity e) above gain times the miss
%!  assert (r.same);
%!  assert (r.tend, 0);
%!  assert (r.nsteps(2), r.nsteps(1));
%!  assert (r.nsteps(1) > nmin);
%!  assert (r.dstep <= 3e-10, "steps: %g", r.dstep);
%!  assert (r.dt <= 1e-10, "times: %g", r.dt);
%!  assert (r.miss <= misstol, "miss: %g", r.miss);
%!  err = norm (r.ym - kepler_exact (r.tm, e).', Inf);
%!  assert (err > gain * r.miss, "forward error %g, miss %g", err, r.miss);
%!endfunction

%!function [msg, sol] = evalc_warn (run)
%!  ## sol = run () with its warnings caught, and the last one's text
%!  sol = [];  lastwarn ("");
%!  evalc ("sol = run ();");
%!  msg = lastwarn ();
%!endfunction

%!function d = max_dH_tenths (t, y)
%!  ## max |H - H0| of Kepler's problem over the first and the last tenth
%!  ## of [t(1), t(end)]
%!  H = sum (y(:, 3:4).^2, 2) / 2 - 1 ./ sqrt (sum (y(:, 1:2).^2, 2));
%!  dH = abs (H - H(1));
%!  T = t(end) - t(1);
%!  d = [max(dH(t <= t(1) + T/10)), max(dH(t >= t(end) - T/10))];
%!endfunction

%!shared e, y0, P, orev
%! e = 0.9;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];   # Kepler, pericentre
%! P = 2*pi;                                         # the period
%! orev = symplecticset ("StepControl", "reversible", "RelTol", 1e-4, ...
%!                       "Refine", 1, "MaxStep", Inf);

## ----------------------------------------------------------------- reversibility
%!test
%! ## odeSV, SecondOrder (explicit Verlet), e = 0.9 over 3 periods: the
%! ## backward run mirrors the forward steps and lands on y0 to round-off,
%! ## while the forward run is many orders of magnitude less accurate (so
%! ## the return is not the solution's accuracy)
%! r = reversal (@odeSV, @kep_acc, 3*P, y0, symplecticset (orev, "SecondOrder", "on"));
%! check_mirror (r, 100, 1e-8, e, 1e4);

%!test
%! ## odeSV, first-order form, Separable on (explicit leapfrog)
%! r = reversal (@odeSV, @kep, 3*P, y0, symplecticset (orev, "Separable", "on"));
%! check_mirror (r, 100, 1e-8, e, 1e4);

%!test
%! ## odeSV, Method yoshida4 (a symmetric composition), SecondOrder
%! r = reversal (@odeSV, @kep_acc, 3*P, y0, ...
%!               symplecticset (orev, "SecondOrder", "on", "Method", "yoshida4"));
%! check_mirror (r, 30, 3e-9, e, 1e3);

%!test
%! ## odeSPVI (Q_DoFs 4, Nodes 3: order 6, implicit steps by Newton)
%! r = reversal (@odeSPVI, @kep, 3*P, y0, ...
%!               symplecticset (orev, "Q_DoFs", 4, "Nodes", 3, "Vectorized", "off"));
%! check_mirror (r, 10, 5e-9, e, 1e3);

%!test
%! ## odeSPVI's other pairs (n, m) are symmetric too: orders 4, 4 and 8
%! for pr = [3 2; 3 3; 5 4].'
%!   o = symplecticset (orev, "Q_DoFs", pr(1), "Nodes", pr(2), "RelTol", 1e-8);
%!   r = reversal (@odeSPVI, @kep, 2*P, y0, o);
%!   assert (r.same);
%!   assert (r.nsteps(2) == r.nsteps(1), "(%d, %d): %d steps forward, %d back",
%!           pr, r.nsteps);
%!   assert (r.miss <= 1e-8, "(%d, %d): miss %g", pr, r.miss);
%! endfor

%!test
%! ## the other symmetric methods are taken and reversible too: a splitting
%! ## (candyrozmus4, first-order form), a Nystrom splitting (blanesmoan6)
%! ## and a composition of order 6 (kahanli6), SecondOrder
%! fs = {@kep, @kep_acc, @kep_acc};
%! names = {"candyrozmus4", "blanesmoan6", "kahanli6"};
%! form = {"Separable", "SecondOrder", "SecondOrder"};
%! for k = 1:3
%!   nm = names{k};
%!   r = reversal (@odeSV, fs{k}, 3*P, y0, symplecticset (orev, form{k}, "on", "Method", nm));
%!   assert (r.same, nm);
%!   assert (r.nsteps(2) == r.nsteps(1), "%s: %d steps forward, %d backward",
%!           nm, r.nsteps(1), r.nsteps(2));
%!   assert (r.dt <= 1e-10, "%s: times %g", nm, r.dt);
%!   assert (r.miss <= 1e-8, "%s: miss %g", nm, r.miss);
%! endfor

%!test
%! ## the mirror holds whatever T: the backward run ends on 0 with the
%! ## first forward step (shortened by round-off), not with an extra
%! ## sliver step where the sum of its steps falls short of tm by
%! ## round-off; both densities (the default, a StepDensityFcn)
%! o = symplecticset (orev, "SecondOrder", "on");
%! os = symplecticset (o, "StepDensityFcn", @(t, y) norm (y(1:2))^(-1.5));
%! for T = P * [1.5 2 3 3.5 4]
%!   for oo = {o, os}
%!     r = reversal (@odeSV, @kep_acc, T, y0, oo{1});
%!     assert (r.same);
%!     assert (r.nsteps(2) == r.nsteps(1), "T = %g: %d steps forward, %d backward",
%!             T, r.nsteps(1), r.nsteps(2));
%!     assert (r.dt <= 1e-10, "T = %g: times %g", T, r.dt);
%!     assert (r.miss <= 1e-8, "T = %g: miss %g", T, r.miss);
%!   endfor
%! endfor

## ----------------------------------------------------------------- sensitivity
%!test
%! ## a density updated from the past step only (lagged_rho) breaks the
%! ## symmetry: reversed, it misses y0 by orders of magnitude more than
%! ## the same density taken at the step point (memoryless)
%! o = symplecticset (orev, "SecondOrder", "on", ...
%!                    "StepDensityFcn", @(t, y) norm (y(1:2))^(-1.5));
%! r = reversal (@odeSV, @kep_acc, 3*P, y0, o);
%! assert (r.same);
%! assert (r.miss <= 1e-8, "miss: %g", r.miss);
%! rl = reversal (@odeSV, @kep_acc, 3*P, y0, ...
%!                symplecticset (o, "StepDensityFcn", @lagged_rho), @() lagged_rho ());
%! assert (rl.same);            # a deterministic run all the same
%! assert (rl.miss > 1e3 * r.miss, "lagged %g, memoryless %g", rl.miss, r.miss);
%! assert (rl.miss > 1e-4);
%! ## and its backward steps are not the forward ones (Inf: not as many)
%! assert (rl.dstep > 1e-6);

## ----------------------------------------------------------------- energy
%!test
%! ## 200 periods of e = 0.9 (SecondOrder Verlet): reversible steps keep
%! ## the energy error bounded (no larger over the last tenth of the run
%! ## than over the first), the angular momentum to round-off; the
%! ## standard control at a like number of steps lets the energy drift
%! T = 200 * P;
%! sol = odeSV (@kep_acc, [0 T], y0, symplecticset (orev, "SecondOrder", "on"));
%! t = sol.x(:);  y = sol.y.';
%! assert (t(end), T);
%! assert (sol.stats.nfailed, 0);
%! d = max_dH_tenths (t, y);
%! assert (d(2) <= 1.5 * d(1), "reversible: dH %s", mat2str (d, 3));
%! assert (d(1) > 1e-6);        # a real energy error, not round-off
%! L = y(:, 1) .* y(:, 4) - y(:, 2) .* y(:, 3);
%! assert (max (abs (L - L(1))) <= 1e-11 * abs (L(1)));
%! ss = odeSV (@kep_acc, [0 T], y0, symplecticset ("SecondOrder", "on", ...
%!                                                  "RelTol", 1e-6, "Refine", 1));
%! assert (abs (log (ss.stats.nsteps / sol.stats.nsteps)) < log (1.25),
%!         "steps: standard %d, reversible %d", ss.stats.nsteps, sol.stats.nsteps);
%! ds = max_dH_tenths (ss.x(:), ss.y.');
%! assert (ds(2) > 3 * ds(1), "standard: dH %s", mat2str (ds, 3));
%! assert (ds(2) / ds(1) > 3 * d(2) / d(1));
%! assert (ds(2) > 3 * d(2), "last tenth: standard %g, reversible %g", ds(2), d(2));

## ----------------------------------------------------------------- accuracy
%!test
%! ## RelTol sets eps = RelTol^(1/p) (below its cap): a hundredfold
%! ## smaller RelTol takes 10 times the steps of Verlet (p = 2), a 1e4
%! ## times smaller one 10 times those of yoshida4 (p = 4), and the error
%! ## of either, ~ eps^p = RelTol, shrinks as RelTol.
%! ## Errors at t = 2 periods against Kepler's equation
%! T = 2 * P;  yT = kepler_exact (T, e).';
%! cases = {"verlet", [1e-5 1e-7]; "yoshida4", [1e-6 1e-10]};
%! for k = 1:rows (cases)
%!   n = [0 0];  err = [0 0];
%!   for i = 1:2
%!     o = symplecticset (orev, "SecondOrder", "on", "Method", cases{k, 1}, ...
%!                        "RelTol", cases{k, 2}(i));
%!     [t, y] = odeSV (@kep_acc, [0 T], y0, o);
%!     n(i) = numel (t) - 1;
%!     err(i) = norm (y(end, :).' - yT, Inf);
%!   endfor
%!   assert (abs (n(2) / n(1) - 10) < 0.5, "%s: steps %s", cases{k, 1}, mat2str (n));
%!   assert (abs (log10 (err(1) / err(2)) - log10 (cases{k, 2}(1) / cases{k, 2}(2))) < 0.3,
%!           "%s: errors %s", cases{k, 1}, mat2str (err, 3));
%! endfor

%!test
%! ## without StepDensityFcn the density is ||f|| / sqrt(||y||^2 + n AbsTol^2)
%! ## at the step points: the same formula as a StepDensityFcn gives the
%! ## same steps (first-order form, Separable on; InitialStep given, so
%! ## that no trial steps are involved)
%! for atol = [1e-6 1e-2]
%!   o = symplecticset (orev, "Separable", "on", "InitialStep", 1e-3, "AbsTol", atol);
%!   [t1, y1] = odeSV (@kep, [0 P], y0, o);
%!   rho = @(t, y) norm (kep (t, y)) / sqrt (norm (y)^2 + 4 * atol^2);
%!   [t2, y2] = odeSV (@kep, [0 P], y0, symplecticset (o, "StepDensityFcn", rho));
%!   assert (numel (t2), numel (t1));
%!   assert (t2, t1, 1e-12 * P);
%!   assert (y2, y1, 1e-10);
%! endfor

## ----------------------------------------------------------------- output
%!test
%! ## output times (301 of them, from the dense output) agree with ode45
%! ## at tight tolerances to the accuracy of the run; the steps are those
%! ## of [0 tf] (the last row is the plain run's); the references agree
%! ## with Kepler's equation
%! RT = 1e-6;
%! o = symplecticset ("StepControl", "reversible", "RelTol", RT, "SecondOrder", "on");
%! ts = linspace (0, 2*P, 301);
%! [t, y] = odeSV (@kep_acc, ts, y0, o);
%! assert (t, ts(:));
%! [~, yref] = ode45 (@kep, ts, y0, odeset ("RelTol", 1e-12, "AbsTol", 1e-12));
%! assert (yref, kepler_exact (ts, e), 1e-7);
%! err = max (max (abs (y - yref)));
%! assert (err <= 1e4 * RT, "output times: %g", err);
%! [t1, y1] = odeSV (@kep_acc, [0 2*P], y0, symplecticset (o, "Refine", 1));
%! assert (y(end, :), y1(end, :), 1e-13);
%! assert (max (max (abs (y1 - kepler_exact (t1, e)))) <= 1e4 * RT);
%! ## Refine: default 4 rows per step, the step points at 1:4:end;
%! ## Refine 1: the step points alone
%! [tr, yr] = odeSV (@kep_acc, [0 2*P], y0, o);
%! assert (numel (tr), 4 * (numel (t1) - 1) + 1);
%! assert (tr(1:4:end), t1, 1e-14);
%! assert (yr(1:4:end, :), y1, 1e-13);
%! mid = setdiff (1:numel (tr), 1:4:numel (tr))(1:7:end);   # a sample
%! rerr = max (max (abs (yr(mid, :) - kepler_exact (tr(mid), e))));
%! assert (rerr <= 1e4 * RT, "Refine: %g", rerr);
%! [t8, ~] = odeSV (@kep_acc, [0 2*P], y0, symplecticset (o, "Refine", 8));
%! assert (numel (t8), 8 * (numel (t1) - 1) + 1);

%!test
%! ## events: the pericentre passages (q.v = 0 rising) are at multiples of
%! ## the period 2*pi, and their rows at the pericentre y0; a terminal
%! ## event ends the run at the first
%! RT = 1e-6;
%! ev = @(t, y) deal (y(1)*y(3) + y(2)*y(4), 0, 1);
%! o = symplecticset ("StepControl", "reversible", "RelTol", RT, ...
%!                    "SecondOrder", "on", "Events", ev);
%! [t, y, te, ye, ie] = odeSV (@kep_acc, [0 3*P+1], y0, o);
%! k = round (te / P);
%! assert (k(k > 0).', [1 2 3]);
%! assert (all (ie == 1));
%! terr = max (abs (te - k * P));
%! assert (terr <= 1e3 * RT, "event times: %g", terr);
%! assert (max (max (abs (ye - y0.'))) <= 1e3 * RT);
%! ## the other direction: the apocentres, at odd multiples of pi
%! ev2 = @(t, y) deal (y(1)*y(3) + y(2)*y(4), 0, -1);
%! [~, ~, te2] = odeSV (@kep_acc, [0 3*P+1], y0, symplecticset (o, "Events", ev2));
%! assert (round (te2(:).' / pi), [1 3 5]);
%! assert (max (abs (te2(:).' - [1 3 5] * pi)) <= 1e3 * RT);
%! ## terminal
%! evt = @(t, y) deal (y(1)*y(3) + y(2)*y(4), 1, 1);
%! [t, y, te] = odeSV (@kep_acc, [0 3*P+1], y0, symplecticset (o, "Events", evt));
%! assert (numel (te), 1);
%! assert (t(end), te);
%! assert (abs (te - P) <= 1e3 * RT);

%!test
%! ## the sol struct: its x are the step points of the run, symdeval
%! ## interpolates them (against Kepler's equation), no failed steps;
%! ## Stats prints the same counts
%! RT = 1e-6;
%! o = symplecticset ("StepControl", "reversible", "RelTol", RT, "SecondOrder", "on");
%! [t1, y1] = odeSV (@kep_acc, [0 2*P], y0, symplecticset (o, "Refine", 1));
%! sol = odeSV (@kep_acc, [0 2*P], y0, symplecticset (o, "Dense", "on"));
%! assert (sol.x(:), t1);
%! assert (sol.y.', y1);
%! assert (sol.stats.nsteps, numel (t1) - 1);
%! assert (sol.stats.nfailed, 0);
%! tt = linspace (0.01, 2*P - 0.01, 97);
%! yy = symdeval (sol, tt);
%! derr = max (max (abs (yy.' - kepler_exact (tt, e))));
%! assert (derr <= 1e4 * RT, "symdeval: %g", derr);
%! assert (symdeval (sol, sol.x(5)), sol.y(:, 5), 1e-14);
%! sol = odeSV (@kep_acc, [0 2*P], y0, o);     # without Dense: the same steps
%! assert (sol.x(:), t1);
%! txt = evalc ("sol2 = odeSV (@kep_acc, [0 2*P], y0, symplecticset (o, 'Stats', 'on'));");
%! assert (! isempty (strfind (txt, "Number of failed attempts:  0")));
%! assert (! isempty (strfind (txt, sprintf ("Number of successful steps: %d", sol.stats.nsteps))));
%! ## the same in odeSPVI
%! sp = odeSPVI (@kep, [0 P], y0, symplecticset (o, "SecondOrder", "off", "RelTol", 1e-6));
%! assert (sp.stats.nfailed, 0);
%! assert (sp.x(end), P);
%! assert (norm (sp.y(:, end) - y0, Inf) <= 1e-2);

%!test
%! ## InitialStep is exactly the first step, MaxStep caps the steps, and
%! ## StepDensityFcn gets the extra parameters of the solver
%! o = symplecticset (orev, "SecondOrder", "on", "InitialStep", 1e-3);
%! t = odeSV (@kep_acc, [0 P], y0, o).x;
%! assert (t(2) - t(1), 1e-3);
%! t = odeSV (@kep_acc, [0 P], y0, symplecticset (o, "MaxStep", 0.01)).x;
%! assert (max (diff (t)) <= 0.01 * (1 + 1e-12));
%! assert (numel (t) > P / 0.01);
%! acc = @(t, q, c) -c * q / norm (q)^3;
%! rho = @(t, y, c) c * norm (y(1:2))^(-1.5);
%! s1 = odeSV (acc, [0 P], y0, symplecticset (o, "StepDensityFcn", rho), 1);
%! s2 = odeSV (@kep_acc, [0 P], y0, symplecticset (o, "StepDensityFcn",
%!                                                  @(t, y) norm (y(1:2))^(-1.5)));
%! assert (s1.x, s2.x);
%! assert (s1.y, s2.y);

## ----------------------------------------------------------------- errors
%!error <odeSE: StepControl>
%! t = odeSE (@kep, [0 1], [0.5; 0; 0; 1.7], symplecticset ("StepControl", "reversible"));
%!error <odeSE: StepControl>
%! t = odeSE (@kep_acc, [0 1], [0.5; 0; 0; 1.7], symplecticset ("StepControl", "Reversible", "SecondOrder", "on"));
%!error <StepControl>
%! t = odeSV (@kep, [0 1], [0.5; 0; 0; 1.7], symplecticset ("StepControl", "sometimes"));
%!error <StepControl>
%! t = odeSPVI (@kep, [0 1], [0.5; 0; 0; 1.7], symplecticset ("StepControl", 1));
%!error <StepControl>
%! t = odeSV (@kep, [0 1], [0.5; 0; 0; 1.7], symplecticset ("StepControl", "reversible", "TimeStepSize", 0.1));
%!error <StepControl>
%! t = odeSV (@kep, [0 1], [0.5; 0; 0; 1.7], symplecticset ("StepControl", "reversible", "TimeStepNumber", 10));
%!error <StepControl>
%! t = odeSPVI (@kep, [0 1], [0.5; 0; 0; 1.7], symplecticset ("StepControl", "reversible", "TimeStepSize", 0.1));
%!error <odeSV.*(StepControl|symmetric|reversible)>
%! t = odeSV (@kep, [0 1], [0.5; 0; 0; 1.7], symplecticset ("StepControl", "reversible", "Method", "ruth3", "Separable", "on"));
%!error <odeSV.*(StepControl|symmetric|reversible)>
%! t = odeSV (@kep_acc, [0 1], [0.5; 0; 0; 1.7], symplecticset ("StepControl", "reversible", "Method", "mclachlan4", "SecondOrder", "on"));
%!error <odeSV.*StepDensityFcn>
%! t = odeSV (@kep, [0 1], [0.5; 0; 0; 1.7], symplecticset ("StepControl", "reversible", "StepDensityFcn", 3));
%!error <odeSPVI.*StepDensityFcn>
%! t = odeSPVI (@kep, [0 1], [0.5; 0; 0; 1.7], symplecticset ("StepControl", "reversible", "StepDensityFcn", {1}));
%!error <StepDensityFcn>
%! t = odeSV (@kep, [0 1], [0.5; 0; 0; 1.7], symplecticset ("StepControl", "reversible", "Separable", "on", "StepDensityFcn", @(t, y) [1; 2]));
%!error <StepDensityFcn>
%! t = odeSV (@kep, [0 1], [0.5; 0; 0; 1.7], symplecticset ("StepControl", "reversible", "Separable", "on", "StepDensityFcn", @(t, y) "abc"));
%!error <StepDensityFcn>
%! t = odeSPVI (@kep, [0 1], [0.5; 0; 0; 1.7], symplecticset ("StepControl", "reversible", "StepDensityFcn", @(t, y) 1 + 2i));
%!error <StepDensityFcn>
%! t = odeSV (@kep_acc, [0 1], [0.5; 0; 0; 1.7], symplecticset ("StepControl", "reversible", "SecondOrder", "on", "StepDensityFcn", @(t, y) []));

%!warning <StepDensityFcn>
%! [t, y] = odeSV (@kep_acc, [0 2], y0, symplecticset (orev, "SecondOrder", "on", "StepDensityFcn", @(t, y) bad_rho (t, y, -1, 1)));

%!test
%! ## a density <= 0, NaN or Inf mid-run ends the run with a warning
%! ## naming StepDensityFcn; the rows so far come back
%! for v = [-1, 0, NaN, Inf]
%!   o = symplecticset (orev, "SecondOrder", "on", ...
%!                      "StepDensityFcn", @(t, y) bad_rho (t, y, v, 1));
%!   lastwarn ("");
%!   evalc ("[t, y] = odeSV (@kep_acc, [0 2], y0, o);");
%!   msg = lastwarn ();
%!   assert (! isempty (regexp (msg, "^odeSV: .*StepDensityFcn")), "v = %g: %s", v, msg);
%!   assert (t(end) >= 1 - 0.1 && t(end) < 2, "v = %g: t(end) = %g", v, t(end));
%!   ## the warning says at which t
%!   tw = str2double (regexp (msg, "t = ([-+.0-9eE]+)", "tokens", "once"));
%!   assert (abs (tw - t(end)) <= 1e-12 * t(end), "v = %g: %s", v, msg);
%!   assert (rows (y), numel (t));
%!   assert (all (isfinite (y(:))));
%!   assert (y(end, :), kepler_exact (t(end), e), 1e-2);
%! endfor
%! ## odeSPVI, first order
%! o = symplecticset (orev, "StepDensityFcn", @(t, y) bad_rho (t, y, NaN, 1));
%! lastwarn ("");
%! evalc ("[t, y] = odeSPVI (@kep, [0 2], y0, o);");
%! assert (! isempty (regexp (lastwarn (), "^odeSPVI: .*StepDensityFcn")), lastwarn ());
%! assert (t(end) < 2 && t(end) > 0.5);
%! assert (all (isfinite (y(:))));

%!test
%! ## a NaN of fcn ends a reversible run (no step is shortened) with the
%! ## rows so far and a warning that says so
%! f = @(t, y) merge (t > 1, NaN (4, 1), [y(3:4); -y(1:2) / norm(y(1:2))^3]);
%! o = symplecticset ("StepControl", "reversible", "Separable", "on");
%! [msg, sol] = evalc_warn (@() odeSV (f, [0 3], [0.5; 0; 0; 1.7], o));
%! assert (sol.x(end) > 0.5 && sol.x(end) < 1.1);
%! assert (! isempty (regexp (msg, "odeSV: FCN returned NaN or Inf .* reversible step", "once")));

%!test
%! ## the default density's f at the step points is the f that odeSPVI's
%! ## dense output evaluates: with the dense output (Dense) a reversible
%! ## run makes no more calls than without, but at its first and last
%! ## points, where a standard run makes one more per step
%! calls = @(s) s.stats.nfevals + s.stats.nfdevals;
%! o = symplecticset ("Q_DoFs", 4, "Nodes", 3, "RelTol", 1e-8);
%! or = symplecticset (o, "StepControl", "reversible");
%! s1 = odeSPVI (@kep, [0 2*P], y0, or);
%! s4 = odeSPVI (@kep, [0 2*P], y0, symplecticset (or, "Dense", "on"));
%! assert (s4.x, s1.x);
%! assert (calls (s4) - calls (s1) <= 2);
%! d1 = odeSPVI (@kep, [0 2*P], y0, o);
%! d4 = odeSPVI (@kep, [0 2*P], y0, symplecticset (o, "Dense", "on"));
%! assert (calls (d4) - calls (d1) >= 0.9 * d1.stats.nsteps);

%!test
%! ## CompensatedSummation with reversible steps (on by default): the same
%! ## steps as without, the sums differing from the plain ones by round-off
%! o = symplecticset (orev, "SecondOrder", "on", "RelTol", 1e-5);
%! [t1, y1] = odeSV (@kep_acc, [0 2*P], y0, symplecticset (o, "CompensatedSummation", "off"));
%! [t2, y2] = odeSV (@kep_acc, [0 2*P], y0, o);
%! assert (numel (t2), numel (t1));
%! assert (t2, t1, 1e-11);
%! assert (y2, y1, 1e-10);
%! assert (! isequal (y2, y1));   # the default sums are compensated
