## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## run_reversible.m -- the benchmark of StepControl "reversible" on long
## Kepler runs: the energy error of reversible steps against fixed steps
## and today's standard adaptive steps at (near) equal calls of fcn, and
## against ode45:
##
##  1. odeSV (Verlet, SecondOrder), e = 0.9, 1e4 periods;
##  2. odeSV (Verlet, SecondOrder), e = 0.99, 1e3 periods;
##  3. odeSPVI (Q_DoFs 4, Nodes 3, Vectorized), e = 0.9, 1e4 periods.
##
## In each case the reversible run comes first, at a RelTol set below;
## the fixed-step run takes the number of steps that makes its calls of
## fcn those of the reversible run (calls per step measured on a short
## run, then scaled); the standard adaptive run's RelTol (= AbsTol) is
## guessed from short runs (a power law of calls against RelTol) and then
## set on full runs (its energy drifts, and the orbit's period and calls
## per period with it) to the reversible run's calls; ode45's RelTol (=
## AbsTol) likewise to the same calls per period, over 100 periods (it
## is an m-file: over all periods it would take minutes).  odeSPVI also
## runs reversible with Kepler's density |q|^(-3/2) as StepDensityFcn
## (the default density costs odeSPVI a call of fcn per step), and both
## its adaptive modes again with dense output (Dense "on"), whose f at
## each step's end the reversible density reuses while standard steps
## pay for it, the standard RelTol tuned anew to the reversible Dense-on
## run's calls.  Energy and angular momentum at the step points of each
## run (the sol output, Refine 1).  About 8 minutes on 2 cores.
##
## Writes bench/REVERSIBLE.md and bench/reversible-kepler.png.  Run from
## the top directory:
##
##   octave-cli --norc --no-gui --path "$PWD/inst:$PWD/src:$PWD/bench" bench/run_reversible.m
##
## Benchmarks are not tests: nothing here asserts; the table says which
## of the issue's targets are met.

1;

## ------------------------------------------------------------ functions

function a = kacc (t, q)
  ## Kepler, the acceleration (SecondOrder): y = [q; v]
  a = -q / norm (q)^3;
endfunction

function dy = kep_v (t, y)
  ## Kepler, first-order form [p; -q/|q|^3], Vectorized (columns)
  r3 = (y(1, :).^2 + y(2, :).^2).^1.5;
  dy = [y(3:4, :); -y(1:2, :) ./ r3];
endfunction

function dy = kep (t, y)
  ## Kepler, first-order form, one state (ode45)
  dy = [y(3:4); -y(1:2) / norm(y(1:2))^3];
endfunction

function rho = kep_rho (t, y)
  ## Kepler's step density |q|^(-3/2) (StepDensityFcn), 1/time
  rho = sum (y(1:2, 1).^2)^(-0.75);
endfunction

function [H, L] = kep_HL (y)
  ## energy and angular momentum of the columns [q; v] (unit mass)
  H = (y(3, :).^2 + y(4, :).^2) / 2 - 1 ./ sqrt (y(1, :).^2 + y(2, :).^2);
  L = y(1, :) .* y(4, :) - y(2, :) .* y(3, :);
endfunction

function r = measure (x, y, tf, y0, edges)
  ## the energy and angular momentum errors of the step points (x, y):
  ## largest over the run, over its first and last tenth (in time), and
  ## the largest in each bin of time (edges) for the plot
  [H0, L0] = kep_HL (y0);
  [H, L] = kep_HL (y);
  dH = abs (H - H0);
  dH(! isfinite (dH)) = Inf;
  r.dH = max (dH);
  r.first = max ([dH(x <= tf / 10), NaN]);
  r.last = max ([dH(x >= 0.9 * tf), NaN]);
  r.ratio = r.last / r.first;
  r.dL = max (abs (L - L0)) / abs (L0);
  r.tend = x(end);
  r.preached = x(end) / (2*pi);          # periods integrated
  r.reached = (x(end) >= tf * (1 - 1e-12));
  nb = numel (edges) - 1;
  k = min (max (lookup (edges, x(:)), 1), nb);
  env = accumarray (k, dH(:), [nb 1], @max, NaN);
  env(env <= 0 | ! isfinite (env)) = NaN;
  r.env = env.';
  r.tb = edges(2:end);                   # the bin's end
endfunction

function r = run_sym (solver, fcn, tf, y0, opts, mode, setting, edges)
  ## one run of odeSV or odeSPVI with the sol output: its counts and errors
  tic;  s = solver (fcn, [0 tf], y0, opts);  el = toc;
  st = s.stats;
  r = measure (s.x, s.y, tf, y0, edges);
  r.mode = mode;  r.setting = setting;  r.time = el;
  r.steps = st.nsteps;  r.failed = st.nfailed;
  r.calls = st.nfevals + st.npds + st.nfdevals;
  r.states = st.nstates;
  r.order = s.order;
  r.periods = tf / (2*pi);
endfunction

function [c, ns, nf, x, y] = run45 (tf, y0, tol)
  ## ode45 at RelTol = AbsTol = tol, step points; calls from its Stats
  o45 = odeset ("RelTol", tol, "AbsTol", tol, "Refine", 1, "Stats", "on");
  txt = evalc ("s = ode45 (@kep, [0 tf], y0, o45);");
  c = str2double (regexp (txt, "function calls:\\s*(\\d+)", "tokens", "once"));
  ns = str2double (regexp (txt, "successful steps:\\s*(\\d+)", "tokens", "once"));
  nf = str2double (regexp (txt, "failed attempts:\\s*(\\d+)", "tokens", "once"));
  x = s.x(:).';  y = s.y;
  if (rows (y) != 4)
    y = y.';
  endif
endfunction

function r = run_ode45 (tf, y0, tol, edges)
  tic;  [c, ns, nf, x, y] = run45 (tf, y0, tol);  el = toc;
  r = measure (x, y, tf, y0, edges);
  r.mode = "ode45";  r.setting = sprintf ("RelTol = AbsTol = %.3g", tol);
  r.time = el;  r.steps = ns;  r.failed = nf;  r.calls = c;  r.states = c;
  r.order = 5;  r.periods = tf / (2*pi);
endfunction

function [tol, b] = fit_tol (callsfun, target, tols0, nmore)
  ## a first guess of the tolerance at which callsfun (tol), the calls of
  ## a short run scaled to the full run, is target: runs at tols0, then up
  ## to nmore runs at the tolerance of a power law, log calls = a + b log
  ## tol, through the two runs closest to target
  X = tols0(:).';  C = arrayfun (callsfun, X);
  for k = 0:nmore
    [~, i] = sort (abs (log (C / target)));
    i = i(1:2);
    P = polyfit (log (X(i)), log (C(i)), 1);
    b = P(1);
    if (! (b < -0.02))
      b = -0.2;                          # noise: a slope of the right sign
    endif
    tol = X(i(1)) * (target / C(i(1)))^(1 / b);
    if (k == nmore || abs (C(i(1)) / target - 1) < 0.03)
      break;
    endif
    X(end+1) = tol;  C(end+1) = callsfun (tol);
  endfor
endfunction

function [best, how, tbest, b] = tune_full (runfun, target, tol, b, maxruns, label, band)
  ## full runs r = runfun (tol) until r.calls is within band (default
  ## 0.15, 15%) of target, at most maxruns: the next tolerance from a power law of calls against
  ## tol through the two runs closest to target (the first time with the
  ## slope b of the short runs), a step of at most 10 times in tol, and
  ## inside the bracket of the runs either side of target.  The run
  ## closest to target is kept, and its tolerance is tbest; b is the last
  ## slope.  (Full runs, because a drifting energy changes the period and
  ## with it the calls per period.)
  if (nargin < 7)
    band = 0.15;
  endif
  X = [];  C = [];  runs = {};
  for k = 1:maxruns
    r = runfun (tol);
    ## a run that stopped early: its calls per period reached, scaled to
    ## the full run
    cfull = r.calls * r.periods / r.preached;
    X(end+1) = tol;  C(end+1) = cfull;  runs{end+1} = r;
    printf ("    %s tuning, run %d: RelTol = AbsTol = %.3g, %d calls (over %.4g periods; %.3f of the target per period), %.1f s\n", ...
            label, k, tol, r.calls, r.preached, cfull / target, r.time);
    if (abs (cfull / target - 1) <= band || k == maxruns)
      break;
    endif
    [~, i] = sort (abs (log (C / target)));
    if (numel (X) >= 2 && X(i(1)) != X(i(2)))
      bb = diff (log (C(i(1:2)))) / diff (log (X(i(1:2))));
      if (bb < -0.02)
        b = bb;
      endif
    endif
    step = log (target / C(i(1))) / b;
    step = max (min (step, log (10)), -log (10));
    tn = X(i(1)) * exp (step);
    lo = max ([X(C > target), 0]);      # smaller tol: more calls
    hi = min ([X(C < target), Inf]);
    if (lo > 0 && hi < Inf && (tn <= lo || tn >= hi))
      tn = sqrt (lo * hi);
    endif
    tol = tn;
  endfor
  [~, j] = min (abs (log (C / target)));
  best = runs{j};
  tbest = X(j);
  how = sprintf ("%d full run%s, calls per period %s", numel (X), repmat ("s", 1, numel (X) > 1), ...
                 strjoin (arrayfun (@(c) sprintf ("%.0f", c), C / runs{1}.periods, "uniformoutput", false), ", "));
endfunction

function s = fmt_e (x)
  if (isfinite (x))
    s = sprintf ("%.2e", x);
  elseif (isinf (x))
    s = "Inf";
  else
    s = "-";
  endif
endfunction

function calls = short_calls (solver, fcn, y0, opts, Ps, P)
  ## calls of a run over Ps periods, scaled to P periods
  s = solver (fcn, [0 Ps*2*pi], y0, opts);
  calls = (s.stats.nfevals + s.stats.npds + s.stats.nfdevals) * P / Ps;
endfunction

## ------------------------------------------------------------ set up

t_all = tic;
here = fileparts (mfilename ("fullpath"));
addpath (here);
warning ("off", "Octave:gnuplot-graphics");
graphics_toolkit ("gnuplot");
more off;

T = 2*pi;
nb = 400;                                # bins of time for the plot
## the cases: label, solver, fcn, options of the solver, e, periods,
## reversible RelTol, periods of ode45, first tolerances of the standard
## mode's short runs, a StepDensityFcn to try, whether to compare also
## with dense output (Dense on)
C = struct ("label", {}, "solver", {}, "fcn", {}, "opts", {}, "e", {}, ...
            "P", {}, "rtol", {}, "P45", {}, "tols0", {}, "rho", {}, "dense", {});
osv = symplecticset ("SecondOrder", "on", "Refine", 1);
ospvi = symplecticset ("Q_DoFs", 4, "Nodes", 3, "Vectorized", "on", "Refine", 1);
C(end+1) = struct ("label", "odeSV, e = 0.9", "solver", @odeSV, "fcn", @kacc, ...
                   "opts", osv, "e", 0.9, "P", 1e4, "rtol", 1e-3, "P45", 1e2, ...
                   "tols0", [1e-5 1e-7], "rho", [], "dense", false);
C(end+1) = struct ("label", "odeSV, e = 0.99", "solver", @odeSV, "fcn", @kacc, ...
                   "opts", osv, "e", 0.99, "P", 1e3, "rtol", 1e-4, "P45", 1e2, ...
                   "tols0", [1e-5 1e-7], "rho", [], "dense", false);
C(end+1) = struct ("label", "odeSPVI (4,3), e = 0.9", "solver", @odeSPVI, "fcn", @kep_v, ...
                   "opts", ospvi, "e", 0.9, "P", 1e4, "rtol", 1e-8, "P45", 1e2, ...
                   "tols0", [1e-8 1e-10], "rho", @kep_rho, "dense", true);

R = cell (1, numel (C));                 # runs of each case
D = cell (1, numel (C));                 # its runs with dense output
K = cell (1, numel (C));                 # how each run's setting was found
E = cell (1, numel (C));                 # bin edges of each case's plot
tcase = zeros (1, numel (C));
for ic = 1:numel (C)
  t_case = tic;
  c = C(ic);
  e = c.e;  tf = c.P * T;
  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
  Ps = max (10, c.P / 100);              # short runs for the tuning
  ## bins of whole periods, log-spaced in time, the first [0, T)
  edges = T * unique ([0, round(logspace (0, log10 (c.P), nb))]);
  E{ic} = edges;
  printf ("\n%d. %s, %g periods\n", ic, c.label, c.P);

  ## (a) reversible
  o = symplecticset (c.opts, "StepControl", "reversible", "RelTol", c.rtol);
  ra = run_sym (c.solver, c.fcn, tf, y0, o, "reversible", ...
                sprintf ("RelTol = %.3g", c.rtol), edges);
  printf ("  reversible RelTol %.3g: %d calls, %d steps, %d failed, %.1f s; dH %.2e (first tenth %.2e, last %.2e), dL %.1e\n", ...
          c.rtol, ra.calls, ra.steps, ra.failed, ra.time, ra.dH, ra.first, ra.last, ra.dL);
  target = ra.calls;

  ## (b) fixed steps with the same calls: calls per step on short runs at
  ## the step, twice
  N = ra.steps;
  for k = 1:2
    ns = max (1, round (N * Ps / c.P));
    s = c.solver (c.fcn, [0 Ps*T], y0, symplecticset (c.opts, "TimeStepNumber", ns));
    cps = (s.stats.nfevals + s.stats.npds + s.stats.nfdevals) / s.stats.nsteps;
    N = round (target / cps);
  endfor
  hfix = tf / N;
  rb = run_sym (c.solver, c.fcn, tf, y0, symplecticset (c.opts, "TimeStepNumber", N), ...
                "fixed steps", sprintf ("h = %.4g (%.1f per period)", hfix, N / c.P), edges);
  printf ("  fixed h = %.4g (%d steps): %d calls (%.3f of reversible), %.1f s; dH %.2e\n", ...
          hfix, N, rb.calls, rb.calls / target, rb.time, rb.dH);
  K{ic}.fixed = sprintf ("%.3f calls per step on %g periods", cps, Ps);

  ## (c) standard adaptive steps, RelTol = AbsTol: a first guess from
  ## short runs, then full runs
  cf = @(tol) short_calls (c.solver, c.fcn, y0, ...
                           symplecticset (c.opts, "RelTol", tol, "AbsTol", tol), Ps, c.P);
  [tol, b] = fit_tol (cf, target, c.tols0, 2);
  rf = @(tol) run_sym (c.solver, c.fcn, tf, y0, symplecticset (c.opts, "RelTol", tol, "AbsTol", tol), ...
                       "standard adaptive", sprintf ("RelTol = AbsTol = %.3g", tol), edges);
  [rc, how, tolc, bc] = tune_full (rf, target, tol, b, 5, "standard");
  printf ("  standard %s (%s): %d calls (%.3f of reversible), %d steps, %d failed; dH %.2e (first %.2e, last %.2e)\n", ...
          rc.setting, how, rc.calls, rc.calls / target, rc.steps, rc.failed, rc.dH, rc.first, rc.last);
  K{ic}.standard = how;

  ## (d) ode45, the same calls per period, over P45 periods
  tf45 = c.P45 * T;
  target45 = target * c.P45 / c.P;
  cf45 = @(tol) run45 (10 * T, y0, tol) * c.P45 / 10;
  [tol45, b45] = fit_tol (cf45, target45, [1e-7 1e-9], 2);
  [rd, how45] = tune_full (@(tol) run_ode45 (tf45, y0, tol, edges), target45, tol45, b45, 6, "ode45");
  printf ("  ode45 %s (%s), %g periods: %d calls (%.3f of reversible per period); dH %.2e (first %.2e, last %.2e)\n", ...
          rd.setting, how45, c.P45, rd.calls, (rd.calls / rd.preached) / (target45 / c.P45), rd.dH, rd.first, rd.last);
  K{ic}.ode45 = how45;

  R{ic} = [ra, rb, rc, rd];

  ## (e) where given, reversible with Kepler's density |q|^(-3/2) as
  ## StepDensityFcn (no call of fcn for the density), the same RelTol,
  ## against the runs above
  if (! isempty (c.rho))
    o = symplecticset (o, "StepDensityFcn", c.rho);
    re = run_sym (c.solver, c.fcn, tf, y0, o, "reversible, StepDensityFcn norm(q)^-1.5", ...
                  sprintf ("RelTol = %.3g", c.rtol), edges);
    printf ("  reversible, StepDensityFcn: %d calls, %d steps, %.1f s; dH %.2e (first tenth %.2e, last %.2e), dL %.1e\n", ...
            re.calls, re.steps, re.time, re.dH, re.first, re.last, re.dL);
    R{ic}(end+1) = re;
  endif

  ## (f) where asked, both adaptive modes with dense output (Dense on, still
  ## Refine 1: the errors at the step points, as above).  The dense output
  ## evaluates f at each step's end, in both modes; the reversible
  ## density takes it from there, standard steps pay it on top.  The
  ## reversible run at the same RelTol; the standard run's RelTol (=
  ## AbsTol) from the one above: its calls plus one a step, a power law
  ## with the slope of its tuning to the reversible Dense-on run's calls,
  ## then full runs (at most 3, within 10%).
  if (c.dense)
    od = symplecticset (c.opts, "StepControl", "reversible", "RelTol", c.rtol, "Dense", "on");
    rad = run_sym (c.solver, c.fcn, tf, y0, od, "reversible, Dense on", ...
                   sprintf ("RelTol = %.3g", c.rtol), edges);
    printf ("  reversible, Dense on: %d calls (%.3f a step; %.3f without dense output), %d steps, %.1f s; dH %.2e (first tenth %.2e, last %.2e), dL %.1e\n", ...
            rad.calls, rad.calls / rad.steps, ra.calls / ra.steps, rad.steps, rad.time, ...
            rad.dH, rad.first, rad.last, rad.dL);
    targetd = rad.calls;
    guess = rc.calls + rc.steps;         # rc's calls with dense output
    told = tolc * (targetd / guess)^(1 / bc);
    printf ("  standard, Dense on: from RelTol %.3g (%d calls + %d steps = %d) and slope %.3f, a first RelTol %.3g\n", ...
            tolc, rc.calls, rc.steps, guess, bc, told);
    rfd = @(tol) run_sym (c.solver, c.fcn, tf, y0, ...
                          symplecticset (c.opts, "RelTol", tol, "AbsTol", tol, "Dense", "on"), ...
                          "standard adaptive, Dense on", sprintf ("RelTol = AbsTol = %.3g", tol), edges);
    [rcd, howd] = tune_full (rfd, targetd, told, bc, 3, "standard, Dense on", 0.10);
    printf ("  standard, Dense on, %s (%s): %d calls (%.3f of reversible Dense on; %.3f a step), %d steps, %d failed; dH %.2e (first %.2e, last %.2e)\n", ...
            rcd.setting, howd, rcd.calls, rcd.calls / targetd, rcd.calls / rcd.steps, rcd.steps, ...
            rcd.failed, rcd.dH, rcd.first, rcd.last);
    K{ic}.dense = sprintf ("from RelTol = AbsTol = %.3g above: %d + %d calls, a RelTol %.3g by the slope %.3f; %s", ...
                           tolc, rc.calls, rc.steps, told, bc, howd);
    D{ic} = [rad, rcd];
  endif
  tcase(ic) = toc (t_case);
  printf ("  case %d: %.0f s (%.0f s in all)\n", ic, tcase(ic), toc (t_all));
endfor

## ------------------------------------------------------------ plot
figure ("visible", "off", "position", [0 0 1500 560]);
for ic = 1:numel (C)
  subplot (1, numel (C), ic);
  hold on;
  for r = R{ic}
    ok = isfinite (r.env);
    loglog (r.tb(ok) / T, r.env(ok), "linewidth", 1.2, "displayname", ...
            sprintf ("%s, %.0f calls/period", r.mode, r.calls / r.preached));
  endfor
  ## the runs with dense output, dashed (the reversible one lies on the
  ## reversible run without it: the same steps)
  for r = D{ic}
    ok = isfinite (r.env);
    loglog (r.tb(ok) / T, r.env(ok), "--", "linewidth", 1.5, "displayname", ...
            sprintf ("%s, %.0f calls/period", r.mode, r.calls / r.preached));
  endfor
  set (gca, "xscale", "log", "yscale", "log");
  xlim ([1, E{ic}(end) / T]);
  grid on;
  xlabel ("t (periods)");
  if (ic == 1)
    ylabel ("|H - H0|, largest over each bin of periods (log-spaced)");
  endif
  title (sprintf ("%s, %g periods (ode45: %g)", C(ic).label, C(ic).P, C(ic).P45));
  set (legend ("location", "southoutside"), "interpreter", "none");
  hold off;
endfor
print ("-dpng", "-r80", fullfile (here, "reversible-kepler.png"));
close all;

## ------------------------------------------------------------ report
t_total = toc (t_all);
[~, cpu] = system ("sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1");
[~, kern] = system ("uname -srm");
hdr = sprintf ("Octave %s, %s, %s, %d cores", version (), strtrim (cpu), ...
               strtrim (kern), nproc ());

key = {"| case | measure | result | target | |", "|---|---|---|---|---|"};
for ic = 1:numel (C)
  ra = R{ic}(1);  rb = R{ic}(2);  rc = R{ic}(3);  rd = R{ic}(4);
  lab = C(ic).label;
  fr = rb.dH / ra.dH;  sr = rc.dH / ra.dH;
  key{end+1} = sprintf ("| %s | reversible: largest energy error in the last tenth / in the first tenth | %.2e / %.2e = %.3g | <= 1.5 | %s |", ...
                        lab, ra.last, ra.first, ra.ratio, met_text (ra.ratio <= 1.5));
  key{end+1} = sprintf ("| %s | reversible: angular momentum, largest relative error | %.1e | round-off | %s |", ...
                        lab, ra.dL, met_text (ra.dL < 1e-11));
  key{end+1} = sprintf ("| %s | energy error, fixed steps / reversible, at calls %d / %d = %.3f | %s / %s = %.3g | >= 10 | %s |", ...
                        lab, rb.calls, ra.calls, rb.calls / ra.calls, fmt_e (rb.dH), fmt_e (ra.dH), ...
                        fr, met_text (fr >= 10));
  key{end+1} = sprintf ("| %s | energy error, standard adaptive / reversible, at calls %d / %d = %.3f | %s / %s = %.3g | >= 10 | %s |", ...
                        lab, rc.calls, ra.calls, rc.calls / ra.calls, fmt_e (rc.dH), fmt_e (ra.dH), ...
                        sr, met_text (sr >= 10));
  key{end+1} = sprintf ("| %s | standard adaptive: last tenth / first tenth (its drift) | %s / %s = %.3g | | |", ...
                        lab, fmt_e (rc.last), fmt_e (rc.first), rc.ratio);
  if (rd.reached)
    stop45 = sprintf ("ode45's last / first tenth %.3g", rd.ratio);
  else
    stop45 = sprintf ("ode45 stopped at t = %.4g (%.0f periods; step size too small)", rd.tend, rd.tend / T);
  endif
  for re = R{ic}(5:end)
    fr = rb.dH / re.dH;  sr = rc.dH / re.dH;
    key{end+1} = sprintf ("| %s | %s: last tenth / first tenth | %.2e / %.2e = %.3g | <= 1.5 | %s |", ...
                          lab, re.mode, re.last, re.first, re.ratio, met_text (re.ratio <= 1.5));
    key{end+1} = sprintf ("| %s | %s: angular momentum, largest relative error | %.1e | round-off | %s |", ...
                          lab, re.mode, re.dL, met_text (re.dL < 1e-11));
    key{end+1} = sprintf ("| %s | energy error, fixed steps / %s, at calls %d / %d = %.3f | %s / %s = %.3g | >= 10 | %s |", ...
                          lab, re.mode, rb.calls, re.calls, rb.calls / re.calls, fmt_e (rb.dH), ...
                          fmt_e (re.dH), fr, met_text (fr >= 10));
    key{end+1} = sprintf ("| %s | energy error, standard adaptive / %s, at calls %d / %d = %.3f | %s / %s = %.3g | >= 10 | %s |", ...
                          lab, re.mode, rc.calls, re.calls, rc.calls / re.calls, fmt_e (rc.dH), ...
                          fmt_e (re.dH), sr, met_text (sr >= 10));
  endfor
  if (! isempty (D{ic}))
    rad = D{ic}(1);  rcd = D{ic}(2);
    sr = rcd.dH / rad.dH;
    dlab = "with dense output (Dense on): the step ends' f that the dense output evaluates also serves the density";
    key{end+1} = sprintf ("| %s | **%s** (calls per step: reversible %.3f, standard %.3f; without dense output %.3f and %.3f) | | | |", ...
                          lab, dlab, rad.calls / rad.steps, rcd.calls / rcd.steps, ...
                          ra.calls / ra.steps, rc.calls / rc.steps);
    key{end+1} = sprintf ("| %s | Dense on: reversible: last tenth / first tenth | %.2e / %.2e = %.3g | <= 1.5 | %s |", ...
                          lab, rad.last, rad.first, rad.ratio, met_text (rad.ratio <= 1.5));
    key{end+1} = sprintf ("| %s | Dense on: reversible: angular momentum, largest relative error | %.1e | round-off | %s |", ...
                          lab, rad.dL, met_text (rad.dL < 1e-11));
    key{end+1} = sprintf ("| %s | Dense on: energy error, standard adaptive / reversible, both Dense on, at calls %d / %d = %.3f | %s / %s = %.3g | >= 10 | %s |", ...
                          lab, rcd.calls, rad.calls, rcd.calls / rad.calls, fmt_e (rcd.dH), ...
                          fmt_e (rad.dH), sr, met_text (sr >= 10));
    key{end+1} = sprintf ("| %s | Dense on: standard adaptive: last tenth / first tenth (its drift) | %s / %s = %.3g | | |", ...
                          lab, fmt_e (rcd.last), fmt_e (rcd.first), rcd.ratio);
  endif
  key{end+1} = sprintf ("| %s | ode45 over %g periods, at %.3f times the reversible run's calls per period (per period reached): energy error / the reversible run's (over its %g periods) | %s / %s = %.3g; %s | shown | |", ...
                        lab, rd.periods, (rd.calls / rd.preached) / (ra.calls / ra.periods), ...
                        ra.periods, fmt_e (rd.dH), fmt_e (ra.dH), rd.dH / ra.dH, stop45);
endfor

tab = {"| case | mode | setting | periods | calls of fcn | calls per period (reached) | steps | failed | f evaluations | order | max energy error | first tenth | last tenth | last / first | angular momentum (rel.) | time (s) |", ...
       "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"};
for ic = 1:numel (C)
  for r = [R{ic}, D{ic}]
    per = sprintf ("%g", r.periods);
    if (! r.reached)
      per = sprintf ("%g (ended at t = %.4g)", r.periods, r.tend);
    endif
    tab{end+1} = sprintf ("| %s | %s | %s | %s | %d | %.1f | %d | %d | %d | %d | %s | %s | %s | %.3g | %s | %.1f |", ...
                          C(ic).label, r.mode, r.setting, per, r.calls, ...
                          r.calls / r.preached, r.steps, r.failed, r.states, r.order, ...
                          fmt_e (r.dH), fmt_e (r.first), fmt_e (r.last), r.ratio, ...
                          fmt_e (r.dL), r.time);
  endfor
endfor

printf ("\n%s\n\n%s\n\n%s\n", hdr, strjoin (key, "\n"), strjoin (tab, "\n"));

## what the shortened runs would have cost, from the runs made
r4 = cellfun (@(x) x(4), R);
us45 = 1e6 * sum ([r4.time]) / sum ([r4.calls]);
r1 = cellfun (@(x) x(1), R(1:2));
ussv = 1e6 * sum ([r1.time]) / sum ([r1.calls]);
spvi_note = "";
if (C(3).P < 1e4)
  spvi_note = sprintf (" (not 1e4 periods: its reversible, fixed-step and standard runs here took %.0f s, %.0f s over 1e4 periods, beyond this benchmark's time)", ...
                       sum ([R{3}(1:3).time]), sum ([R{3}(1:3).time]) * 1e4 / C(3).P);
endif

fid = fopen (fullfile (here, "REVERSIBLE.md"), "w");
fprintf (fid, "# Reversible step-size control on long Kepler runs\n\n");
fprintf (fid, "Written by bench/run_reversible.m on %s in %.0f s (the cases %s s).\n\n%s\n\n", ...
         datestr (now, "yyyy-mm-dd"), t_total, strjoin (arrayfun (@(x) sprintf ("%.0f", x), tcase, "uniformoutput", false), ", "), hdr);
fprintf (fid, "Re-run from the top directory (after make):\n\n    octave-cli --norc --no-gui --path \"$PWD/inst:$PWD/src:$PWD/bench\" bench/run_reversible.m\n\n");
fprintf (fid, "Kepler's problem (a = 1, period 2 pi) from the pericentre: q0 = [1-e; 0], v0 = [0; sqrt((1+e)/(1-e))], H = |v|^2/2 - 1/|q|, L = q1 v2 - q2 v1.  Three cases: odeSV (Verlet) with SecondOrder \"on\" (fcn = -q/|q|^3, one call per step), e = 0.9 over %g periods and e = 0.99 over %g; odeSPVI with Q_DoFs 4, Nodes 3 (order 6), Vectorized \"on\" (fcn = [v; -q/|q|^3] on the columns; Newton's matrices by finite differences, one call each), e = 0.9 over %g periods%s.  The modes:\n\n", C(1).P, C(2).P, C(3).P, spvi_note);
fprintf (fid, "- reversible: StepControl \"reversible\" at the RelTol in the table, the default step density (no StepDensityFcn), no InitialStep, default MaxStep;\n");
fprintf (fid, "- fixed steps: TimeStepNumber such that the calls of fcn are those of the reversible run (calls per step measured on a short run at that step, twice, then scaled: %s; %s; %s);\n", K{1}.fixed, K{2}.fixed, K{3}.fixed);
fprintf (fid, "- standard adaptive (the default StepControl): RelTol = AbsTol tuned to the reversible run's calls, first from short runs (1/100 of the periods, at least 10) and a power law of calls against RelTol, then on full runs (its energy drifts, the orbit's period with it, and so do the calls per period), keeping the run closest to the calls (%s; %s; %s).  odeSPVI's adaptive runs advance with the companion solution of one more mode and node (order 8, `sol.order`);\n", K{1}.standard, K{2}.standard, K{3}.standard);
fprintf (fid, "- for odeSPVI also reversible with Kepler's step density |q|^(-3/2) as StepDensityFcn, the same RelTol: the default density needs f at each step point, a call of fcn per step that odeSPVI's step makes no other use of (odeSV's SecondOrder step reuses its force), and this shows what the steps do without that call; it is compared with the same fixed-step and standard runs, whose calls the table gives;\n");
if (any ([C.dense]))
  id = find ([C.dense]);
  fprintf (fid, "- for %s also both adaptive modes with dense output (`Dense` \"on\", Refine 1 still, so that the errors are again those at the step points): the reversible run at the same RelTol, the standard run at a RelTol = AbsTol tuned to the reversible Dense-on run's calls (%s).  Two footings, then: without dense output (the rows above) the reversible default density costs a call of fcn per step that standard steps do not make; with dense output both modes evaluate f at each step's end for it, and the reversible density takes its f from there, at no extra call, while standard steps pay that call on top (calls per step, reversible %s without dense output and %s with it, standard %s and %s);\n", ...
           strjoin ({C(id).label}, ", "), strjoin (cellfun (@(k) k.dense, K(id), "uniformoutput", false), "; "), ...
           strjoin (arrayfun (@(i) sprintf ("%.3f", R{i}(1).calls / R{i}(1).steps), id, "uniformoutput", false), ", "), ...
           strjoin (arrayfun (@(i) sprintf ("%.3f", D{i}(1).calls / D{i}(1).steps), id, "uniformoutput", false), ", "), ...
           strjoin (arrayfun (@(i) sprintf ("%.3f", R{i}(3).calls / R{i}(3).steps), id, "uniformoutput", false), ", "), ...
           strjoin (arrayfun (@(i) sprintf ("%.3f", D{i}(2).calls / D{i}(2).steps), id, "uniformoutput", false), ", "));
endif
fprintf (fid, "- ode45 (Octave's): RelTol = AbsTol tuned the same way to the reversible run's calls per period, over the periods in the table, fewer than the others' (ode45 is an m-file, 6 calls a step; its runs here took %.0f us a call against %.0f us for odeSV's reversible runs, so that over all periods at equal calls its runs would take %s s) (%s; %s; %s).\n\n", us45, ussv, strjoin (arrayfun (@(ic) sprintf ("%.0f", R{ic}(4).time * C(ic).P / C(ic).P45), 1:numel (C), "uniformoutput", false), ", "), K{1}.ode45, K{2}.ode45, K{3}.ode45);
fprintf (fid, "Calls of fcn: `sol.stats` nfevals + npds + nfdevals; with Vectorized (odeSPVI) these count calls, each of one or a few states, and f evaluations are the states (`sol.stats.nstates`); ode45: its Stats.  Energy and angular momentum at every step point (the sol output, Refine 1); first and last tenth: t <= tf/10 and t >= 0.9 tf.  Everything but the times is machine-independent (up to round-off); times are single runs, wall clock, on a machine that may have been busy.  Plot: reversible-kepler.png, the largest |H - H0| over bins of whole periods (up to %d, log-spaced in time; plotted at each bin's end; the runs with dense output dashed).\n\n", nb);
fprintf (fid, "## The issue's measures\n\n%s\n\n", strjoin (key, "\n"));
fprintf (fid, "## All runs\n\n%s\n", strjoin (tab, "\n"));
fclose (fid);
printf ("\nrun_reversible.m: %.0f s in all\n", t_total);
