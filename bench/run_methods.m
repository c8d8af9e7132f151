## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## run_methods.m -- the benchmark of odeSV's Method, SecondOrder and
## CompensatedSummation options, in one run:
##
##  1. Kepler, e = 0.5, 100 periods (the exact end point is y0): work and
##     precision of every method of odeSV (Separable "on"; SecondOrder "on"
##     for the best ones) over fixed steps, of odeSPVI (4,3) and (9,8) and
##     of ode45 over tolerances; the calls at an end-point error of 1e-8;
##     SecondOrder against the first-order form at equal steps; compiled
##     yoshida4 against the same method as an m-file loop
##     (bench/yoshida4_mfile.m).
##  2. The outer solar system (bench/outer_solar.m) over 1e5 days: the same
##     against a reference solution whose accuracy is checked by halving
##     its step.
##  3. The round-off of the energy over 1e6 Verlet steps of the outer solar
##     system with and without CompensatedSummation.
##
## Writes bench/METHODS.md and bench/methods-{kepler,solar,compensated}.png.
## Run from the top directory:
##
##   octave-cli --norc --path "inst:src" bench/run_methods.m
##
## (Not bench/methods.m: with bench/ on the path that name would shadow
## Octave's own function methods.)
##
## Benchmarks are not tests: nothing here asserts a time.  Methods that
## odeSV does not know are listed as missing and left out.

1;

## ------------------------------------------------------------ functions

function dy = kep (t, y)
  ## Kepler, first-order form [dH/dp; -dH/dq], one state
  q = y(1:2);
  dy = [y(3:4); -q / norm(q)^3];
endfunction

function a = kacc (t, q)
  ## Kepler, the acceleration (SecondOrder)
  a = -q / norm(q)^3;
endfunction

function dy = kep_v (t, y)
  ## Kepler, first-order form, Vectorized (odeSPVI, finite differences)
  q = y(1:2, :);
  r = sqrt (sum (q.^2, 1));
  dy = [y(3:4, :); -q ./ (r.^3)];
endfunction

function H = kep_H (Y)
  ## energy of the rows [q p] (or [q v])
  H = sum (Y(:, 3:4).^2, 2) / 2 - 1 ./ sqrt (sum (Y(:, 1:2).^2, 2));
endfunction

function r = one_run (solver, fcn, tf, y0, opts, efun, Hfun, label, form, N, h)
  ## one fixed-step (or adaptive) run: time, calls, error, energy
  r.label = label;  r.form = form;  r.N = N;  r.h = h;
  try
    tic;  s = solver (fcn, [0 tf], y0, opts);  el = toc;
  catch err
    ## a failed run is shown as such; the sweep stops at it
    printf ("  %s %s N = %g: %s\n", label, form, N, err.message);
    r.time = NaN;  r.steps = NaN;  r.calls = NaN;  r.states = NaN;
    r.order = NaN;  r.err = Inf;  r.dH = Inf;
    return;
  end_try_catch
  r.label = label;  r.form = form;  r.N = N;  r.h = h;
  r.time = el;
  r.steps = s.stats.nsteps;
  r.calls = s.stats.nfevals + s.stats.npds + s.stats.nfdevals;
  r.states = s.stats.nstates;
  r.order = NaN;
  if (isfield (s, "order"))
    r.order = s.order;
  endif
  Y = s.y.';
  if (s.x(end) < tf * (1 - 1e-12) || ! all (isfinite (Y(end, :))))
    r.err = Inf;  r.dH = Inf;
  else
    r.err = efun (Y(end, :).');
    H = Hfun (Y);
    r.dH = max (abs (H - H(1)));
  endif
endfunction

function R = sweep (runN, N0, fac, cap, floor_err, maxruns)
  ## runs runN (N) for N = N0, N0*fac, ... while the calls stay below cap,
  ## the error above floor_err and still falling
  R = [];  N = N0;
  for k = 1:maxruns
    r = runN (N);
    R = [R, r];
    if (r.err < floor_err || ! isfinite (r.calls))
      break;
    endif
    if (k > 1 && r.err < 1e3 * floor_err && r.err > 0.3 * R(end-1).err)
      break;                                   # the round-off floor
    endif
    Nn = ceil (N * fac);
    if (r.calls * Nn / N > cap)
      break;
    endif
    N = Nn;
  endfor
endfunction

function [c, how] = calls_at (x, err, target)
  ## x (calls) at err = target: log-log interpolation between the two runs
  ## that bracket it, or extrapolation with the slope fitted to the last
  ## up to three runs below 1 when none reaches it; the first run's x, as
  ## a bound, when every run is below it
  c = NaN;  how = "-";
  ok = isfinite (err) & err > 0 & err < 1 & isfinite (x);
  x = x(ok);  err = err(ok);
  [x, i] = sort (x);  err = err(i);
  if (numel (x) < 2)
    return;
  endif
  k = find (err(1:end-1) >= target & err(2:end) < target, 1);
  if (! isempty (k))
    lx = log (x(k:k+1));  ly = log (err(k:k+1));
    c = exp (lx(1) + (log (target) - ly(1)) * diff (lx) / diff (ly));
    how = "interpolated";
    return;
  endif
  if (all (err < target))
    c = x(1);
    how = "at most: every run is below";
    return;
  endif
  j = max (1, numel (x) - 2):numel (x);
  P = polyfit (log (x(j)), log (err(j)), 1);
  if (P(1) < -0.5 && P(1) > -20)
    c = exp ((log (target) - P(2)) / P(1));
    how = sprintf ("extrapolated, slope %.1f", P(1));
  endif
endfunction

function s = fmt_e (x)
  if (isfinite (x))
    s = sprintf ("%.1e", x);
  else
    s = "-";
  endif
endfunction

function lines = wp_table (R, Nname)
  lines = {sprintf("| method | form | order | %s | steps | calls of fcn | f evaluations | time (s) | end error | max energy error |", Nname), ...
           "|---|---|---|---|---|---|---|---|---|---|"};
  for r = R
    lines{end+1} = sprintf ("| %s | %s | %s | %s | %d | %d | %d | %.3f | %s | %s |", ...
                            r.label, r.form, num2str (r.order), r.Nstr, r.steps, ...
                            r.calls, r.states, r.time, fmt_e (r.err), fmt_e (r.dH));
  endfor
endfunction

function wp_plot (G, file, ttl, errlabel)
  ## G: cell of {label, runs}; error against f evaluations and time
  figure ("visible", "off", "position", [0 0 1400 620]);
  sty = {"-o", "-s", "-^", "-v", "-d", "-x", "-+", "-*", "--o", "--s", ...
         "--^", "--v", "--d", "--x", "--+", "--*", ":o", ":s", ":^", ":v"};
  for panel = 1:2
    subplot (1, 2, panel);
    hold on;
    for i = 1:numel (G)
      R = G{i}{2};
      e = [R.err];  ok = isfinite (e) & e > 0;
      if (panel == 1)
        x = [R.states];
      else
        x = [R.time];
      endif
      loglog (x(ok), e(ok), sty{1 + mod (i-1, numel (sty))}, "linewidth", 1.2, ...
              "markersize", 4, "displayname", G{i}{1});
    endfor
    set (gca, "xscale", "log", "yscale", "log");
    grid on;
    if (panel == 1)
      xlabel ("evaluations of f (calls; odeSPVI: states)");
      ylabel (errlabel);
      title (ttl);
    else
      xlabel ("wall time (s)");
      legend ("location", "eastoutside");
    endif
    hold off;
  endfor
  print ("-dpng", "-r80", file);
  close all;
endfunction

## ------------------------------------------------------------ set up

t_all = tic;
here = fileparts (mfilename ("fullpath"));
addpath (here);
warning ("off", "Octave:gnuplot-graphics");
graphics_toolkit ("gnuplot");
more off;

mlist = {"verlet", "yoshida4", "suzuki4", "kahanli6", "kahanli8", ...
           "mclachlan8", "sofspa10", "ruth3", "candyrozmus4", "mclachlan4", ...
           "blanesmoan6"};
## steps per period to start from (the error about 1e-1 on Kepler) and the
## factor between runs (about 16 times less error from one run to the
## next), by order
have = {};  missing = {};  order = [];
e = 0.5;  T = 2*pi;  nper = 100;
y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
for i = 1:numel (mlist)
  try
    s = odeSV (@kep, [0 T], y0, symplecticset ("TimeStepNumber", 10, ...
               "Separable", "on", "Method", mlist{i}));
    have{end+1} = mlist{i};  order(end+1) = s.order;
  catch
    missing{end+1} = mlist{i};
  end_try_catch
endfor
printf ("odeSV methods: %s; missing: %s\n", strjoin (have, ", "), ...
        strjoin ([missing, {"none"}](1:max (1, numel (missing))), ", "));
N0_of = @(p) round (interp1 ([2 3 4 6 8 10], [500 150 120 50 30 20], min (max (p, 2), 10)));
fac_of = @(p) 2^max (0.5, min (1, 4/p));

## ------------------------------------------------------------ 1. Kepler
printf ("\n1. Kepler e = %.1f, %d periods\n", e, nper);
tf = nper * T;
H0 = kep_H (y0.');
kerr = @(y) norm (y - y0);
cap = 3e5;                               # calls per run (Verlet: 6e5)
floor_k = 1e-12;
KS = {};                                 # {label, runs} for the plot
best = struct ("name", {}, "c8", {});
for i = 1:numel (have)
  m = have{i};
  os = symplecticset ("Separable", "on", "Method", m);
  runN = @(N) one_run (@odeSV, @kep, tf, y0, ...
                       symplecticset (os, "TimeStepNumber", nper * N), ...
                       kerr, @kep_H, m, "Separable", N, T / N);
  if (strcmp (m, "verlet"))
    R = sweep (runN, 1000, 2, 6e5, floor_k, 10);
  else
    R = sweep (runN, N0_of (order(i)), fac_of (order(i)), cap, floor_k, 10);
  endif
  for k = 1:numel (R)
    R(k).Nstr = sprintf ("%d", R(k).N);
  endfor
  [c8, how] = calls_at ([R.calls], [R.err], 1e-8);
  printf ("  %-13s order %2d: %d runs, errors %s .. %s, calls at 1e-8 %s (%s)\n", m, ...
          order(i), numel (R), fmt_e (R(1).err), fmt_e (R(end).err), fmt_e (c8), how);
  KS{end+1} = {m, R};
  best(end+1) = struct ("name", m, "c8", c8);
  KC8.(m) = {c8, how, m, "Separable"};
endfor
## one more run for the two with the fewest calls at 1e-8 where their runs
## stopped short of it: at 1.2 times the extrapolated calls, so that 1e-8
## is read off between two runs
[~, ix] = sort ([best.c8]);
for j = ix(1:min (2, numel (ix)))
  m = best(j).name;  ki = find (strcmp (have, m));
  R = KS{ki}{2};
  if (isfinite (best(j).c8) && min ([R.err]) >= 1e-8)
    N = ceil (1.2 * best(j).c8 / (R(end).calls / R(end).N));
    r = one_run (@odeSV, @kep, tf, y0, symplecticset ("TimeStepNumber", nper * N, ...
                 "Separable", "on", "Method", m), kerr, @kep_H, m, "Separable", N, T / N);
    r.Nstr = sprintf ("%d", N);
    R = [R, r];
    KS{ki}{2} = R;
    [c8, how] = calls_at ([R.calls], [R.err], 1e-8);
    best(j).c8 = c8;
    KC8.(m) = {c8, how, m, "Separable"};
    printf ("  %-13s N = %d: error %s, calls at 1e-8 %s (%s)\n", m, N, fmt_e (r.err), ...
            fmt_e (c8), how);
  endif
endfor
## SecondOrder for the three best (fewest calls at 1e-8) and verlet, at
## the same steps
[~, ix] = sort ([best.c8]);
so_list = unique ([{"verlet"}, {best(ix(1:min (3, numel (ix)))).name}], "stable");
for i = 1:numel (so_list)
  m = so_list{i};
  Rs = KS{find (strcmp (have, m))}{2};
  R = [];
  for r0 = Rs
    r = one_run (@odeSV, @kacc, tf, y0, symplecticset ("TimeStepNumber", nper * r0.N, ...
                 "SecondOrder", "on", "Method", m), kerr, @kep_H, m, "SecondOrder", r0.N, T / r0.N);
    r.Nstr = sprintf ("%d", r.N);
    R = [R, r];
  endfor
  [c8, how] = calls_at ([R.calls], [R.err], 1e-8);
  KC8.([m "_so"]) = {c8, how, m, "SecondOrder"};
  printf ("  %-13s SecondOrder: calls at 1e-8 %s (%s)\n", m, fmt_e (c8), how);
  KS{end+1} = {sprintf("%s SecondOrder", m), R};
endfor
## odeSPVI (4,3) and (9,8), Vectorized with finite-difference matrices
for pr = [4 3 20; 9 8 8].'
  lab = sprintf ("odeSPVI (%d,%d)", pr(1), pr(2));
  op = symplecticset ("Q_DoFs", pr(1), "Nodes", pr(2), "Vectorized", "on");
  p = 2 * min (pr(1) - 1, 2*pr(2) - pr(1) + 1);
  runN = @(N) one_run (@odeSPVI, @kep_v, tf, y0, ...
                       symplecticset (op, "TimeStepNumber", nper * N), ...
                       kerr, @kep_H, lab, "Vectorized", N, T / N);
  R = sweep (runN, pr(3), fac_of (p), cap, floor_k, 8);
  for k = 1:numel (R)
    R(k).Nstr = sprintf ("%d", R(k).N);
  endfor
  [c8, how] = calls_at ([R.states], [R.err], 1e-8);
  KC8.(sprintf ("spvi%d%d", pr(1), pr(2))) = {c8, how, lab, "Vectorized"};
  printf ("  %s: f evaluations at 1e-8 %s (%s)\n", lab, fmt_e (c8), how);
  KS{end+1} = {lab, R};
endfor
## ode45 over tolerances (RelTol = AbsTol); its calls from its Stats
R = [];
for tol = [1e-7 1e-8 1e-9 1e-10 1e-11]
  o45 = odeset ("RelTol", tol, "AbsTol", tol, "Stats", "on");
  tic;  txt = evalc ("[t45, y45] = ode45 (@kep, [0 tf], y0, o45);");  el = toc;
  nc = str2double (regexp (txt, "function calls:\\s*(\\d+)", "tokens", "once"));
  r = struct ("label", "ode45", "form", "first-order", "N", tol, "h", NaN, ...
              "time", el, "steps", rows (t45) - 1, "calls", nc, "states", nc, ...
              "order", 5, "err", kerr (y45(end, :).'), ...
              "dH", max (abs (kep_H (y45) - H0)), "Nstr", sprintf ("tol %.0e", tol));
  R = [R, r];
endfor
[c8, how] = calls_at ([R.calls], [R.err], 1e-8);
KC8.ode45 = {c8, how, "ode45", "first-order"};
printf ("  ode45: calls at 1e-8 %s (%s)\n", fmt_e (c8), how);
KS{end+1} = {"ode45", R};
Kall = [];
for i = 1:numel (KS)
  Kall = [Kall, KS{i}{2}];
endfor
wp_plot (KS, fullfile (here, "methods-kepler.png"), ...
         sprintf ("Kepler e = %.1f, %d periods", e, nper), "end-point error |y - y0|");

## (a) calls at an end-point error of 1e-8
names = fieldnames (KC8);
ex = {};  exc = [];
for i = 1:numel (have)
  if (! strcmp (have{i}, "verlet") && isfinite (KC8.(have{i}){1}))
    ex{end+1} = have{i};  exc(end+1) = KC8.(have{i}){1};
  endif
endfor
[cbest, ib] = min (exc);  bestm = ex{ib};
ratio_verlet = cbest / KC8.verlet{1};
ratio_ode45 = cbest / KC8.ode45{1};
## the same in the SecondOrder form (one call per stage)
so_c = Inf;  so_m = "-";
for m = so_list
  if (! strcmp (m{1}, "verlet") && KC8.([m{1} "_so"]){1} < so_c)
    so_c = KC8.([m{1} "_so"]){1};  so_m = m{1};
  endif
endfor
printf ("  (a) best explicit (Separable): %s, %.3g calls at 1e-8; verlet %.3g (%s): %.2g; ode45 %.3g (%s): %.2g\n", ...
        bestm, cbest, KC8.verlet{1}, KC8.verlet{2}, ratio_verlet, KC8.ode45{1}, ...
        KC8.ode45{2}, ratio_ode45);

## (b) SecondOrder against the first-order form, Verlet, equal steps
ob1 = symplecticset ("TimeStepNumber", 10 * 1000, "Separable", "on");
ob2 = symplecticset ("TimeStepNumber", 10 * 1000, "SecondOrder", "on");
[tb, tbt] = timeit_turns ({@() odeSV(@kep, [0 10*T], y0, ob1), ...
                           @() odeSV(@kacc, [0 10*T], y0, ob2)}, 4, 3);
rb = tb(1) / tb(2);
rbr = tbt(:, 1) ./ tbt(:, 2);
printf ("  (b) Kepler Verlet 1e4 steps: first-order %.1f ms, SecondOrder %.1f ms: %.2fx\n", ...
        1e3 * tb(1), 1e3 * tb(2), rb);

## (c) compiled yoshida4 against the m-file loop, equal steps, both forms
nc_ = 5;  hc = T / 1000;
oc1 = symplecticset ("TimeStepNumber", nc_ * 1000, "Separable", "on", "Method", "yoshida4");
oc2 = symplecticset ("TimeStepNumber", nc_ * 1000, "SecondOrder", "on", "Method", "yoshida4");
[~, ym1, ncm1] = yoshida4_mfile (@kep, nc_ * T, y0, hc);
[~, ym2, ncm2] = yoshida4_mfile (@kacc, nc_ * T, y0, hc, "secondorder");
sc1 = odeSV (@kep, [0 nc_*T], y0, oc1);
sc2 = odeSV (@kacc, [0 nc_*T], y0, oc2);
agree_c = [norm(ym1(end, :).' - sc1.y(:, end)), norm(ym2(end, :).' - sc2.y(:, end))];
[tc, tct] = timeit_turns ({@() yoshida4_mfile(@kep, nc_*T, y0, hc), ...
                           @() odeSV(@kep, [0 nc_*T], y0, oc1), ...
                           @() yoshida4_mfile(@kacc, nc_*T, y0, hc, "secondorder"), ...
                           @() odeSV(@kacc, [0 nc_*T], y0, oc2)}, 8, 3);
rc1 = tc(1) / tc(2);  rc2 = tc(3) / tc(4);
printf ("  (c) yoshida4 5000 steps: Separable m-file %.1f ms / compiled %.1f ms = %.2fx; SecondOrder %.1f / %.1f ms = %.2fx\n", ...
        1e3 * tc(1), 1e3 * tc(2), rc1, 1e3 * tc(3), 1e3 * tc(4), rc2);
t_part1 = toc (t_all);

## ------------------------------------------------------------ 2. solar
printf ("\n2. Outer solar system, 1e5 days\n");
S = outer_solar ();
tfs = 1e5;
ys0 = [S.q0; S.v0];                      # SecondOrder, ode45: y = [q; v]
yp0 = [S.q0; S.p0];                      # first-order form: y = [q; p]
E0 = abs (S.Hv (ys0.'));
## reference: odeSPVI (9,8) at h = 25 d, checked against h = 12.5 d
opr = symplecticset ("Q_DoFs", 9, "Nodes", 8, "Vectorized", "on");
tic;
sr1 = odeSPVI (S.fcn, [0 tfs], yp0, symplecticset (opr, "TimeStepNumber", 4000));
sr2 = odeSPVI (S.fcn, [0 tfs], yp0, symplecticset (opr, "TimeStepNumber", 8000));
t_ref = toc;
qref = sr2.y(1:18, end);
ref_acc = norm (sr1.y(1:18, end) - qref);
printf ("  reference odeSPVI (9,8) h = 12.5 d; h = 25 d differs by %.1e AU (%.1f s)\n", ...
        ref_acc, t_ref);
serr = @(y) norm (y(1:18) - qref);
floor_s = max (10 * ref_acc, 1e-12);
caps = 8e4;                              # calls per run (Separable: 7e4)
SS = {};
N0s_of = @(p) round (interp1 ([2 3 4 6 8 10], [1000 800 500 300 250 200], min (max (p, 2), 10)));
for i = 1:numel (have)
  m = have{i};
  os = symplecticset ("SecondOrder", "on", "Method", m);
  runN = @(N) one_run (@odeSV, S.acc, tfs, ys0, symplecticset (os, "TimeStepNumber", N), ...
                       serr, @(Y) S.Hv (Y) / E0, m, "SecondOrder", N, tfs / N);
  R = sweep (runN, N0s_of (order(i)), fac_of (order(i)), caps, floor_s, 8);
  for k = 1:numel (R)
    R(k).Nstr = sprintf ("%.4g", R(k).h);
  endfor
  [c6, how] = calls_at ([R.calls], [R.err], 1e-6);
  SC6.(m) = {c6, how, m, "SecondOrder"};
  printf ("  %-13s order %2d: %d runs, errors %s .. %s, calls at 1e-6 AU %s (%s)\n", m, ...
          order(i), numel (R), fmt_e (R(1).err), fmt_e (R(end).err), fmt_e (c6), how);
  SS{end+1} = {m, R};
endfor
## the first-order form (Separable) for verlet and the best one
ssel = {};  sc = [];
for i = 1:numel (have)
  if (! strcmp (have{i}, "verlet") && isfinite (SC6.(have{i}){1}))
    ssel{end+1} = have{i};  sc(end+1) = SC6.(have{i}){1};
  endif
endfor
[~, ib] = min (sc);  sbest = ssel{ib};
for m = unique ({"verlet", sbest}, "stable")
  Rs = SS{find (strcmp (have, m{1}))}{2};
  R = [];
  for r0 = Rs(2 * [Rs.calls] <= 7e4)
    r = one_run (@odeSV, S.fcn, tfs, yp0, symplecticset ("TimeStepNumber", r0.N, ...
                 "Separable", "on", "Method", m{1}), serr, @(Y) S.Hp (Y) / E0, ...
                 m{1}, "Separable", r0.N, r0.h);
    r.Nstr = sprintf ("%.4g", r.h);
    R = [R, r];
  endfor
  [c6, how] = calls_at ([R.calls], [R.err], 1e-6);
  SC6.([m{1} "_sep"]) = {c6, how, m{1}, "Separable"};
  SS{end+1} = {sprintf("%s Separable", m{1}), R};
endfor
## odeSPVI (4,3), (9,8), Vectorized
for pr = [4 3 1000; 9 8 100].'
  lab = sprintf ("odeSPVI (%d,%d)", pr(1), pr(2));
  op = symplecticset ("Q_DoFs", pr(1), "Nodes", pr(2), "Vectorized", "on");
  p = 2 * min (pr(1) - 1, 2*pr(2) - pr(1) + 1);
  runN = @(N) one_run (@odeSPVI, S.fcn, tfs, yp0, symplecticset (op, "TimeStepNumber", N), ...
                       serr, @(Y) S.Hp (Y) / E0, lab, "Vectorized", N, tfs / N);
  R = sweep (runN, pr(3), fac_of (p), caps, floor_s, 7);
  for k = 1:numel (R)
    R(k).Nstr = sprintf ("%.4g", R(k).h);
  endfor
  [c6, how] = calls_at ([R.states], [R.err], 1e-6);
  SC6.(sprintf ("spvi%d%d", pr(1), pr(2))) = {c6, how, lab, "Vectorized"};
  SS{end+1} = {lab, R};
endfor
## ode45 on y = [q; v]
fqv = @(t, y) [y(19:36); S.acc(t, y(1:18))];
R = [];
for tol = [1e-6 1e-8 1e-10 1e-11]
  o45 = odeset ("RelTol", tol, "AbsTol", tol, "Stats", "on");
  tic;  txt = evalc ("[t45, y45] = ode45 (fqv, [0 tfs], ys0, o45);");  el = toc;
  nc = str2double (regexp (txt, "function calls:\\s*(\\d+)", "tokens", "once"));
  Hs = S.Hv (y45) / E0;
  r = struct ("label", "ode45", "form", "[q; v]", "N", tol, "h", NaN, ...
              "time", el, "steps", rows (t45) - 1, "calls", nc, "states", nc, ...
              "order", 5, "err", serr (y45(end, :).'), ...
              "dH", max (abs (Hs - Hs(1))), "Nstr", sprintf ("tol %.0e", tol));
  R = [R, r];
endfor
[c6, how] = calls_at ([R.calls], [R.err], 1e-6);
SC6.ode45 = {c6, how, "ode45", "[q; v]"};
SS{end+1} = {"ode45", R};
Sall = [];
for i = 1:numel (SS)
  Sall = [Sall, SS{i}{2}];
endfor
## the reference against the closest run of odeSV (another method)
isv = ! strncmp ({Sall.label}, "odeSPVI", 7) & ! strcmp ({Sall.label}, "ode45");
[ref_x, j] = min ([Sall(isv).err]);
Ssv = Sall(isv);
ref_xs = sprintf ("%s (%s, h = %s d)", Ssv(j).label, Ssv(j).form, Ssv(j).Nstr);
wp_plot (SS, fullfile (here, "methods-solar.png"), ...
         "outer solar system, 1e5 days", "position error at the end (AU)");
printf ("  best: %s, %.3g calls at 1e-6 AU; verlet %.3g (%s); ode45 %.3g (%s)\n", sbest, ...
        SC6.(sbest){1}, SC6.verlet{1}, SC6.verlet{2}, SC6.ode45{1}, SC6.ode45{2});
## (b) on the outer solar system: Verlet h = 10 d, 1e4 steps
ob1 = symplecticset ("TimeStepNumber", 1e4, "Separable", "on");
ob2 = symplecticset ("TimeStepNumber", 1e4, "SecondOrder", "on");
tbs = timeit_turns ({@() odeSV(S.fcn, [0 tfs], yp0, ob1), ...
                     @() odeSV(S.acc, [0 tfs], ys0, ob2)}, 4, 3);
rbs = tbs(1) / tbs(2);
printf ("  (b) solar Verlet 1e4 steps: first-order %.0f ms, SecondOrder %.0f ms: %.2fx\n", ...
        1e3 * tbs(1), 1e3 * tbs(2), rbs);
t_part2 = toc (t_all) - t_part1;

## ------------------------------------------------------------ 3. compensated
## Verlet (kick-drift-kick), SecondOrder, h = 0.25 d, 1e6 steps.  Its energy
## error is O(h^2) = 1e-9 and hides the round-off; the energy plus the h^2
## term of the modified Hamiltonian (S.Hv_kdk2) is conserved up to O(h^4),
## below 1e-15 of |H| at this step (16 times less than at h = 0.5 d, where it
## was 5.6e-15 in the compensated run), so its change is the round-off.
printf ("\n3. CompensatedSummation, outer solar system, Verlet, 1e6 steps\n");
nst = 1e6;  hcs = 0.25;
cs_on = {"off", "on"};
EC = cell (1, 2);  tcs = zeros (1, 2);
for i = 1:2
  o = symplecticset ("TimeStepNumber", nst, "SecondOrder", "on", ...
                     "CompensatedSummation", cs_on{i});
  tic;  s = odeSV (S.acc, [0 nst*hcs], ys0, o);  tcs(i) = toc;
  E = S.Hv_kdk2 (s.y.', hcs);
  EC{i} = (E - E(1)) / abs (E(1));
  clear s E;
endfor
## RMS of the relative error over windows (n/10^0.25, n]
edges = round (10.^(1:0.25:6));
cen = sqrt (edges(1:end-1) .* edges(2:end));
rms_ = zeros (2, numel (cen));  mx_ = rms_;
for i = 1:2
  for k = 1:numel (cen)
    w = EC{i}(edges(k)+1:edges(k+1)+1);
    rms_(i, k) = sqrt (mean (w.^2));
    mx_(i, k) = max (abs (EC{i}(1:edges(k+1)+1)));
  endfor
endfor
fitm = cen >= 1e3;
slope = zeros (1, 2);
for i = 1:2
  P = polyfit (log10 (cen(fitm)), log10 (rms_(i, fitm)), 1);
  slope(i) = P(1);
endfor
printf ("  RMS at 1e6 steps: off %.1e, on %.1e; slopes (n >= 1e3): off %.2f, on %.2f; time %.1f s / %.1f s\n", ...
        rms_(1, end), rms_(2, end), slope(1), slope(2), tcs(1), tcs(2));
figure ("visible", "off", "position", [0 0 900 600]);
blk = 1000;
nb = floor (nst / blk);
for i = 1:2
  env = max (reshape (abs (EC{i}(2:nb*blk+1)), blk, nb), [], 1);
  loglog (blk * (1:nb), env, "linewidth", 1);
  hold on;
endfor
loglog (cen, rms_(1, :), "o-", "linewidth", 2, cen, rms_(2, :), "s-", "linewidth", 2);
nn = [1e3 1e6];
loglog (nn, rms_(1, find (cen >= 1e3, 1)) * (nn / 1e3).^0.5, "k--", ...
        nn, rms_(1, find (cen >= 1e3, 1)) * (nn / 1e3), "k:");
hold off;
grid on;
xlabel ("steps n");
ylabel ("relative change of the modified energy H + h^2 H_2", "interpreter", "none");
title (sprintf ("outer solar system, Verlet SecondOrder, h = %g d: round-off of the energy", hcs), ...
       "interpreter", "none");
legend ({"off: max over blocks of 1000 steps", "on: max over blocks of 1000 steps", ...
         sprintf("off: RMS over windows, slope %.2f", slope(1)), ...
         sprintf("on: RMS over windows, slope %.2f", slope(2)), "slope 1/2", "slope 1"}, ...
        "location", "northwest");
print ("-dpng", "-r80", fullfile (here, "methods-compensated.png"));
close all;
clear EC;
t_part3 = toc (t_all) - t_part1 - t_part2;
t_total = toc (t_all);

## ------------------------------------------------------------ report
[~, cpu] = system ("sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1");
[~, kern] = system ("uname -srm");
hdr = sprintf ("Octave %s, %s, %s, %d cores", version (), strtrim (cpu), ...
               strtrim (kern), nproc ());
yes = @(b) met_text (b);
key = {"| # | measure | result | target | |", "|---|---|---|---|---|"};
key{end+1} = sprintf ("| a1 | Kepler, calls of fcn at an end-point error of 1e-8: best explicit method (Separable) / Verlet (Separable); in the SecondOrder form (one call per stage): best / Verlet | %s %.3g / %.3g (%s) = %.2g; SecondOrder: %s %.3g / %.3g (%s) | <= 1/5 | %s |", ...
                      bestm, cbest, KC8.verlet{1}, KC8.verlet{2}, ratio_verlet, so_m, so_c, ...
                      KC8.verlet_so{1}, KC8.verlet_so{2}, yes (ratio_verlet <= 0.2));
key{end+1} = sprintf ("| a2 | the same against ode45 (RelTol = AbsTol) | %.3g / %.3g (%s) = %.2g | fewer | %s |", ...
                      cbest, KC8.ode45{1}, KC8.ode45{2}, ratio_ode45, yes (ratio_ode45 < 1));
key{end+1} = sprintf ("| b | Verlet first-order (Separable, 2 calls per step) / SecondOrder (1 call), equal steps, time in turns: Kepler 1e4 steps; outer solar system 1e4 steps | %.2fx (%.1f / %.1f ms; within rounds %.2f-%.2fx); %.2fx (%.0f / %.0f ms) | >= 1.8x | %s |", ...
                      rb, 1e3*tb(1), 1e3*tb(2), min (rbr), max (rbr), rbs, 1e3*tbs(1), 1e3*tbs(2), yes (rb >= 1.8));
key{end+1} = sprintf ("| c | yoshida4, Kepler 5000 steps, m-file loop (bench/yoshida4_mfile.m, the same fcn) / compiled, time in turns: Separable (6 calls per step each); SecondOrder (3 calls each) | %.2fx (%.1f / %.1f ms); %.2fx (%.1f / %.1f ms); ends agree to %.0e, %.0e; calls %d / %d, %d / %d | >= 1.5x | %s (Separable), %s (SecondOrder) |", ...
                      rc1, 1e3*tc(1), 1e3*tc(2), rc2, 1e3*tc(3), 1e3*tc(4), agree_c, ncm1, sc1.stats.nfevals, ...
                      ncm2, sc2.stats.nfevals, yes (rc1 >= 1.5), yes (rc2 >= 1.5));
key{end+1} = sprintf ("| s | outer solar system, calls of fcn at a position error of 1e-6 AU: best (SecondOrder) / Verlet (SecondOrder) / ode45 | %s %.3g / %.3g (%s) / %.3g (%s) | shown | |", ...
                      sbest, SC6.(sbest){1}, SC6.verlet{1}, SC6.verlet{2}, SC6.ode45{1}, SC6.ode45{2});
key{end+1} = sprintf ("| d | energy round-off over 1e6 Verlet steps (outer solar system), RMS of the relative error in the last window, without / with CompensatedSummation; fitted slopes in n | %.1e / %.1e; slopes %.2f / %.2f; run times %.1f / %.1f s | with: sqrt(n) or slower | %s |", ...
                      rms_(1, end), rms_(2, end), slope(1), slope(2), tcs(1), tcs(2), yes (slope(2) <= 0.6));

printf ("\n%s\n\n%s\n", hdr, strjoin (key, "\n"));

## per-method summaries at the error targets
sumk = {"| method | form | calls at 1e-8 | how |", "|---|---|---|---|"};
for f = fieldnames (KC8).'
  sumk{end+1} = sprintf ("| %s | %s | %s | %s |", KC8.(f{1}){3}, KC8.(f{1}){4}, fmt_e (KC8.(f{1}){1}), KC8.(f{1}){2});
endfor
sums = {"| method | form | calls at 1e-6 AU | how |", "|---|---|---|---|"};
for f = fieldnames (SC6).'
  sums{end+1} = sprintf ("| %s | %s | %s | %s |", SC6.(f{1}){3}, SC6.(f{1}){4}, fmt_e (SC6.(f{1}){1}), SC6.(f{1}){2});
endfor
cst = {"| steps n (window) | RMS without | RMS with | max up to n without | max up to n with |", ...
       "|---|---|---|---|---|"};
for k = 1:numel (cen)
  cst{end+1} = sprintf ("| %d-%d | %.1e | %.1e | %.1e | %.1e |", edges(k)+1, edges(k+1), ...
                        rms_(1, k), rms_(2, k), mx_(1, k), mx_(2, k));
endfor

fid = fopen (fullfile (here, "METHODS.md"), "w");
fprintf (fid, "# Benchmark of odeSV's methods\n\n");
fprintf (fid, "Written by bench/run_methods.m on %s in %.0f s (Kepler %.0f s, outer solar system %.0f s, compensated summation %.0f s).\n\n%s\n\n", ...
         datestr (now, "yyyy-mm-dd"), t_total, t_part1, t_part2, t_part3, hdr);
fprintf (fid, "odeSV methods run: %s.  Missing (not known to odeSV in this build): %s.\n\n", ...
         strjoin (have, ", "), strjoin ([missing, {"none"}](1:max (1, numel (missing))), ", "));
fprintf (fid, "## Key ratios\n\n%s\n\n", strjoin (key, "\n"));
fprintf (fid, "Calls at an error level are read off the runs by log-log interpolation between the two runs that bracket it; where no run reaches it, by extrapolation with the slope fitted to the last three runs (marked; none when that slope is not between -20 and -0.5); where every run is below it, the calls of the cheapest run as a bound (marked).  Times are single runs (wall clock) in the tables; the ratios b and c are the best of runs made in turns.\n\n");
fprintf (fid, "## 1. Kepler, e = %.1f, %d periods\n\n", e, nper);
fprintf (fid, "q0 = [1-e; 0], p0 = [0; sqrt((1+e)/(1-e))], the exact end point is y0.  End error: |y(end) - y0| (2-norm over q and p).  Energy error: max |H - H0| over the steps (H0 = -1/2).  Fixed steps: steps per period N (TimeStepNumber = 100 N).  odeSV first-order form (Separable \"on\") for every method, fcn = [p; -q/|q|^3]: two calls per stage; SecondOrder \"on\" (fcn = -q/|q|^3, one call per stage) for Verlet and the three methods with the fewest calls at 1e-8, at the same steps.  Each method's runs go from about 1e-1 of error down by about 16 times a run until 3e5 calls (Verlet 6e5) or an error of 1e-12; for the two with the fewest calls at 1e-8, one more run at 1.2 times the calls extrapolated to 1e-8.  odeSPVI: Vectorized, finite-difference Newton matrices (f evaluations = states evaluated, sol.stats.nstates; calls = calls of fcn).  ode45: RelTol = AbsTol = tol, calls from its Stats.  Plot: methods-kepler.png.\n\n");
fprintf (fid, "### Calls (f evaluations) at an end-point error of 1e-8\n\n%s\n\n", strjoin (sumk, "\n"));
fprintf (fid, "### All runs\n\n%s\n\n", strjoin (wp_table (Kall, "N (steps/period)"), "\n"));
fprintf (fid, "## 2. Outer solar system, 1e5 days\n\n");
fprintf (fid, "Sun and the five outer planets, bench/outer_solar.m: data of E. Hairer, C. Lubich, G. Wanner, Geometric Numerical Integration, 2nd ed., Springer 2006, Section I.2.4 (Table 2.3).  Error: 2-norm of the 18 positions at t = 1e5 days against the reference, in AU.  Energy error: max |H - H0| / |H0| over the steps.  odeSV: SecondOrder \"on\" (y = [q; v], fcn = the accelerations) for every method, the first-order form (Separable \"on\", y = [q; p], p = m v) for Verlet and the best one at the same steps; step h in days.  odeSPVI: first-order form, Vectorized, finite differences.  ode45: y = [q; v].\n\n");
fprintf (fid, "Reference: odeSPVI (9,8) at h = 12.5 d (8000 steps); the run at h = 25 d differs from it by %.1e AU at the end, and errors below about %.0e AU are not resolved; the closest run of odeSV, %s, ends %.1e AU from it.  Each method's steps go from an error of about 1e-1 down by about 16 times a run until 8e4 calls or that floor; the first-order form at the same steps up to 7e4 calls.  Plot: methods-solar.png.\n\n", ref_acc, floor_s, ref_xs, ref_x);
fprintf (fid, "### Calls (f evaluations) at a position error of 1e-6 AU\n\n%s\n\n", strjoin (sums, "\n"));
fprintf (fid, "### All runs\n\n%s\n\n", strjoin (wp_table (Sall, "h (days)"), "\n"));
fprintf (fid, "## 3. Compensated summation, outer solar system, 1e6 steps\n\n");
fprintf (fid, "odeSV Verlet, SecondOrder \"on\", h = %g d, 1e6 steps (%.0f years), CompensatedSummation \"off\" and \"on\".  The energy error of Verlet itself is O(h^2) (about 1e-9 of |H| at this step) and would hide the round-off, so the quantity followed is the energy plus the h^2 term of the kick-drift-kick Verlet step's modified Hamiltonian, H~ = H + h^2 (v' V''(q) v / 12 - grad V' M^-1 grad V / 24) (bench/outer_solar.m, Hv_kdk2): it is conserved up to O(h^4), which at this step is below 1e-15 of |H|, the level at which H itself is evaluated in double precision.  Its change over the run is the round-off.  RMS over windows of steps (n/10^0.25, n], the relative error |H~(n) - H~(0)| / |H(0)|; slopes fitted to log RMS against log n for n >= 1e3.  Plot: methods-compensated.png.\n\n", ...
         hcs, nst * hcs / 365.25);
fprintf (fid, "Slopes: without %.2f, with %.2f.  Run times: %.1f s without, %.1f s with.\n\n%s\n", ...
         slope(1), slope(2), tcs(1), tcs(2), strjoin (cst, "\n"));
fclose (fid);
printf ("\nrun_methods.m: %.0f s in all (Kepler %.0f s, solar %.0f s, compensated %.0f s)\n", ...
        t_total, t_part1, t_part2, t_part3);
