## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## run_benchmarks.m -- every benchmark of the package in one process run,
## printed as one table and written to bench/RESULTS.md with the machine and
## Octave version.  `make bench` runs it with inst/ and src/ on the path.
##
## Each row gives wall time per step and callbacks per step (from Stats), so
## fewer calls can be told from cheaper calls.  Benchmarks are not tests:
## nothing here asserts a time.

1;

function [dy, ddy] = kepler (t, y)
  ## works for one state or, Vectorized, for the columns of y
  q = y(1:2, :);
  r = sqrt (sum (q.^2, 1));
  dy = [y(3:4, :); -q ./ r.^3];
  if (nargout > 1)
    ## Hess(H) = [V''(q) 0; 0 I], written out (blkdiag is a slow m-file;
    ## both the compiled solver and the m-file reference call this)
    q = q(:, 1);  r = r(1);
    A = (eye (2) - (3 / r^2) * (q * q.')) / r^3;
    ddy = [A(1,1), A(1,2), 0, 0; A(2,1), A(2,2), 0, 0; 0, 0, 1, 0; 0, 0, 0, 1];
  endif
endfunction

function dy = kepler_v (t, y)
  ## one output (Newton's matrices then by finite differences), Vectorized
  q = y(1:2, :);
  r = sqrt (sum (q.^2, 1));
  dy = [y(3:4, :); -q ./ r.^3];
endfunction

function [dy, ddy] = rot3 (t, y)
  ## H = |p|^2/2 (1 + |q|^2/4) + |q|^4/8 + (q.p)^2/4 in 3-D: rotation
  ## invariant, not separable (tests/test_se_sv.m); the Hessian as second
  ## output
  q = y(1:3);  p = y(4:6);  s = q.' * p;  I = eye (3);
  dy = [p * (1 + q.'*q/4) + s*q/2; -(q * (p.'*p)/4 + q * (q.'*q)/2 + s*p/2)];
  if (nargout > 1)
    Hqp = p*q.'/2 + s*I/2 + q*p.'/2;
    ddy = [(p.'*p)/4*I + (q.'*q)/2*I + q*q.' + p*p.'/2, Hqp;
           Hqp.', (1 + q.'*q/4)*I + q*q.'/2];
  endif
endfunction

function dy = rot3_f (t, y)
  ## rot3 without the Hessian: finite-difference matrices
  dy = rot3 (t, y);
endfunction

function dy = kepler_count (t, y)
  ## kepler, counting its calls (A1)
  global A1_NCALLS
  A1_NCALLS++;
  dy = kepler (t, y);
endfunction

function dy = kepler1 (t, y)
  q = y(1:2);
  dy = [y(3:4); -q / norm(q)^3];   # no space before "(" inside []
endfunction

function r = call_loop (f, y, ncalls)
  ## ncalls calls of f (t, y) from an m-file loop and nothing else: what
  ## the calls of the Verlet loop (P4) cost without its other lines
  for k = 1:ncalls
    r = f (k, y);
  endfor
endfunction

function s = timeit (f, minsec)
  ## best of repeated runs of at least minsec seconds in all
  s = Inf;  tot = 0;
  while (tot < minsec || ! isfinite (s))
    ## one output: with none the solvers would plot, as ode45 does
    tic;  r = f ();  el = toc;
    s = min (s, el);  tot += el;
  endwhile
endfunction

here = fileparts (mfilename ("fullpath"));
addpath (here);
## rebuilt on every run: a stale probe would measure other calls
mkoctfile ("--mex", "-o", fullfile (here, "callback_cost.mex"), ...
           fullfile (here, "callback_cost.c"));
clear callback_cost;

e = 0.6;
y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
T = 2*pi;
H = @(y) sum (y(:,3:4).^2, 2) / 2 - 1 ./ sqrt (sum (y(:,1:2).^2, 2));
H0 = H (y0.');
rows_ = {};

## ---------------------------------------------------------------- B0
## The solvers call a simple handle such as @kepler by its name, anonymous
## handles and handles to subfunctions through feval.  Timed as the
## solvers are (best of runs over at least 3 s), with one output (f) and
## with two (f and the Hessian, as Newton's matrix asks for it).
cb = timeit (@() callback_cost ("kepler", 0, y0, 2000, 1), 3) / 2000;
cb2 = timeit (@() callback_cost ("kepler", 0, y0, 2000, 2), 3) / 2000;
cbf = timeit (@() callback_cost (@kepler, 0, y0, 2000, 1), 3) / 2000;
printf ("callback cost: Kepler %.2f us by name (%.2f us with the Hessian), %.2f us through feval\n", ...
        1e6*cb, 1e6*cb2, 1e6*cbf);
rows_(end+1, :) = {"B0", "C->Octave call of Kepler's fcn: by name (as the solvers call @kepler), with the Hessian as second output, through feval", ...
                sprintf("%.1f us, %.1f us, %.1f us per call", 1e6*cb, 1e6*cb2, 1e6*cbf), "measured"};

## ---------------------------------------------------------------- P1-P3
h = T/100;
opts = symplecticset ("TimeStepSize", h, "Nodes", 3, "Q_DoFs", 4);
nper = 20;
sol = odeSPVI (@kepler, [0 nper*T], y0, opts);        # warm-up, counts
[~, ym, st] = spvi_mfile (@kepler, T, y0, h, 4, 3);
calls_mex = (sol.stats.nfevals + sol.stats.npds) / sol.stats.nsteps;
## Vectorized: with the Hessian (one call per node for a matrix), and with
## an fcn of one output (finite-difference matrices: all nodes' perturbed
## states in one call)
optv = symplecticset (opts, "Vectorized", "on");
solv = odeSPVI (@kepler, [0 nper*T], y0, optv);
calls_vec = (solv.stats.nfevals + solv.stats.npds) / solv.stats.nsteps;
solf = odeSPVI (@kepler_v, [0 nper*T], y0, optv);
calls_vf = (solf.stats.nfevals + solf.stats.npds) / solf.stats.nsteps;
## single calls with a new matrix on every step (NewtonMatrix "new"):
## fewer calls, but each step's 3 first calls also compute the Hessian
optn = symplecticset (opts, "NewtonMatrix", "new");
soln = odeSPVI (@kepler, [0 nper*T], y0, optn);
calls_new = (soln.stats.nfevals + soln.stats.npds) / soln.stats.nsteps;
## the m-file (one period) and the three odeSPVI runs (20 periods) in turns
[tt, tall] = timeit_turns ({@() spvi_mfile(@kepler, T, y0, h, 4, 3), ...
                            @() odeSPVI(@kepler, [0 nper*T], y0, opts), ...
                            @() odeSPVI(@kepler, [0 nper*T], y0, optv), ...
                            @() odeSPVI(@kepler_v, [0 nper*T], y0, optv), ...
                            @() odeSPVI(@kepler, [0 nper*T], y0, optn)}, 20);
t_m = tt(1);  t_mex = tt(2);  t_vec = tt(3);  t_vf = tt(4);  t_new = tt(5);
## the ratio within each round (m-file and odeSPVI run back to back)
rr = (tall(:, 1) / st.nsteps) ./ (tall(:, 2) / sol.stats.nsteps);
ms_mex = 1e3 * t_mex / sol.stats.nsteps;

ms_m = 1e3 * t_m / st.nsteps;
calls_m = (st.nfcn + st.nhess) / st.nsteps;
agree = norm (ym(end, :).' - sol.y(:, 101), Inf);
printf ("P1: m-file %.3f ms/step (%.1f fcn + %.1f Hessian calls), odeSPVI %.3f ms/step, ratio %.1f\n", ...
        ms_m, st.nfcn/st.nsteps, st.nhess/st.nsteps, ms_mex, ms_m/ms_mex);
ms_vf = 1e3 * t_vf / solf.stats.nsteps;
ms_new = 1e3 * t_new / soln.stats.nsteps;
rows_(end+1, :) = {"P1", "odeSPVI (4,3), h = T/100, Kepler: m-file fsolve reference / odeSPVI", ...
                sprintf("%.2f ms / %.3f ms per step = %.1fx (best of each; within a round: median %.1fx, %.1f-%.1fx over %d rounds; results agree to %.1e); NewtonMatrix new: %.3f ms = %.1fx; Vectorized, fcn without Hessian: %.3f ms = %.1fx (agree to %.1e)", ...
                         ms_m, ms_mex, ms_m / ms_mex, median (rr), min (rr), max (rr), numel (rr), ...
                         agree, ms_new, ms_m / ms_new, ms_vf, ms_m / ms_vf, ...
                         norm (ym(end, :).' - solf.y(:, 101), Inf)), ">= 50x"};
rows_(end+1, :) = {"P2", "callbacks per step (fcn + Hessian), odeSPVI (4,3)", ...
                sprintf("%.2f (matrix kept, the default; m-file: %.2f); NewtonMatrix new: %.2f; Vectorized: with Hessian %.2f (kept), without Hessian %.2f (new, the default)", ...
                         calls_mex, calls_m, calls_new, calls_vec, calls_vf), ...
                "<= 6; <= 2 Vectorized"};
## each call at its own cost: the Hessian calls return two outputs.  The
## probe and the solver take turns.
tt = timeit_turns ({@() callback_cost("kepler", 0, y0, 2000, 1), ...
                    @() callback_cost("kepler", 0, y0, 500, 2), ...
                    @() odeSPVI(@kepler, [0 5*T], y0, opts)}, 6);
nst5 = 500;   # steps in 5 periods
over = tt(3) / (nst5 * (sol.stats.nfevals * tt(1) / 2000 ...
                        + sol.stats.npds * tt(2) / 500) / sol.stats.nsteps);
rows_(end+1, :) = {"P3", "wall time / (callbacks x callback cost, with the Hessian for npds; measured in turns), odeSPVI (4,3)", ...
                sprintf("%.2f (Vectorized: %.2f ms/step)", over, 1e3 * t_vec / solv.stats.nsteps), "<= 1.2"};

## P3 by sampling (bench/p3_profile.sh, needs perf): the same ratio from
## one run, little affected by the machine's drifting load
[~, p3p] = system (sprintf ("sh '%s'", fullfile (here, "p3_profile.sh")));
p3p = strtrim (strrep (p3p, "p3_profile: ", ""));
printf ("P3 sampled: %s\n", p3p);
rows_(end+1, :) = {"P3s", "P3 by sampling one run (bench/p3_profile.sh): samples under the MEX entry / under mexCallMATLAB", ...
                p3p, "<= 1.2"};

## ---------------------------------------------------------------- P4
hv = T/1000;  nv = 10;
ov = symplecticset ("TimeStepSize", hv, "Separable", "on");
s4 = odeSV (@kepler1, [0 nv*T], y0, ov);
## with the two calls per step alone, in turns with both: from C by name,
## as odeSV makes them (callback_cost, which does not read the result),
## and from an m-file loop through the handle, as the Verlet loop does
nc4 = 2 * s4.stats.nsteps;
tt = timeit_turns ({@() odeSV(@kepler1, [0 nv*T], y0, ov), ...
                    @() verlet_mfile(@kepler1, nv*T, y0, hv), ...
                    @() callback_cost("kepler1", 0, y0, nc4, 1), ...
                    @() call_loop(@kepler1, y0, nc4)}, 9);
t_sv = tt(1);  t_vm = tt(2);  t_cc = tt(3);  t_cl = tt(4);
[~, yvm] = verlet_mfile (@kepler1, nv*T, y0, hv);
us_sv = 1e6 * t_sv / s4.stats.nsteps;  us_vm = 1e6 * t_vm / s4.stats.nsteps;
rows_(end+1, :) = {"P4", "odeSV Separable (explicit) vs plain m-file Verlet loop, Kepler", ...
                sprintf("%.1f us vs %.1f us per step = %.2fx; %.3f calls/step; agree to %.1e", ...
                         us_sv, us_vm, us_vm / us_sv, s4.stats.nfevals / s4.stats.nsteps, ...
                         norm(yvm(end, :).' - s4.y(:, end), Inf)), ">= 2x, <= 2.05 calls"};
us_cc = 1e6 * t_cc / s4.stats.nsteps;  us_cl = 1e6 * t_cl / s4.stats.nsteps;
rows_(end+1, :) = {"P4f", "P4's two calls per step alone: from C by name (as odeSV makes them), from an m-file loop through the handle; odeSV / its calls; the loop's other lines; loop / calls from C (the ratio of a solver that costs nothing beyond its calls)", ...
                sprintf("%.1f us, %.1f us per step; odeSV %.2f times its calls; the loop's other lines %.1f us; %.2fx", ...
                         us_cc, us_cl, us_sv / us_cc, us_vm - us_cl, us_vm / us_cc), "shown (P4's bound)"};

## ---------------------------------------------------------------- P5
o45 = odeset ("RelTol", 1e-10, "AbsTol", 1e-10);
tic;  [t45, y45] = ode45 (@kepler1, [0 100*T], y0, o45);  t_45 = toc;
dH45 = abs (H (y45) - H0) / abs (H0);
## odeSPVI at a high order and a large step: (9,8), order 16, h = T/30.
## P5p below shows the pairs (m+1, m) at steps that keep the energy error
## far below 1e-9; the higher ones cost less per period, and (9,8) at T/30
## (3e-12) leaves a wide margin.  Timed over all 1000 periods: Vectorized
## with an fcn of one output (finite-difference matrices, all nodes in one
## call), and with single calls and the Hessian as second output.
o5 = symplecticset ("TimeStepSize", T/30, "Nodes", 8, "Q_DoFs", 9);
o5v = symplecticset (o5, "Vectorized", "on");
tic;  [t5, y5] = odeSPVI (@kepler_v, [0 1000*T], y0, o5v);  t_sv5 = toc;
tic;  [t5s, y5s] = odeSPVI (@kepler, [0 1000*T], y0, o5);  t_sp = toc;
dH5 = abs (H (y5) - H0) / abs (H0);
dH5s = abs (H (y5s) - H0) / abs (H0);
first = t5 <= 100*T;  last = t5 >= 900*T;
rows_(end+1, :) = {"P5", "Kepler 1000 periods: ode45 1e-10 (timed over 100 periods, x10) vs odeSPVI (9,8) h = T/30: Vectorized (fcn without Hessian); single calls with the Hessian", ...
                sprintf("ode45 %.0f s, abs(dH/H) %.1e at 100 periods (growing); odeSPVI Vectorized %.1f s = 1/%.0f, max abs(dH/H) %.1e (first 100 periods %.1e, last 100 %.1e); single calls %.1f s = 1/%.1f, max abs(dH/H) %.1e", ...
                         10 * t_45, dH45(end), t_sv5, 10 * t_45 / t_sv5, max(dH5), ...
                         max(dH5(first)), max(dH5(last)), t_sp, 10 * t_45 / t_sp, ...
                         max(dH5s)), "bounded, <= 1e-9, <= 1/20 of ode45's time"};
## the pairs, Vectorized, over 20 periods: seconds per 100 periods, energy
pairs = [5 4 100; 7 6 40; 9 8 30; 11 10 25];
txt = {};
for i = 1:rows (pairs)
  op = symplecticset ("TimeStepSize", T/pairs(i, 3), "Q_DoFs", pairs(i, 1), ...
                      "Nodes", pairs(i, 2), "Vectorized", "on");
  [tp, yp] = odeSPVI (@kepler_v, [0 20*T], y0, op);
  tpp = timeit (@() odeSPVI (@kepler_v, [0 20*T], y0, op), 1);
  txt{end+1} = sprintf ("(%d,%d) T/%d: %.2f s, %.1e", pairs(i, :), 5 * tpp, ...
                        max (abs (H (yp) - H0) / abs (H0)));
endfor
rows_(end+1, :) = {"P5p", "odeSPVI pairs (m+1,m), Vectorized without Hessian, Kepler: s per 100 periods, max abs(dH/H) over 20", ...
                strjoin(txt, "; "), "choice of P5"};

## ---------------------------------------------------------------- A1
## Adaptive steps (the default of every solver): odeSPVI with the Hessian
## as second output against ode45, the same fcn, Kepler over 10 periods
## (the exact end point is y0), in turns.  Calls of fcn counted in a
## separate run of each (ode45 through a counting wrapper, not timed).
global A1_NCALLS
A1_NCALLS = 0;
txt = {};
for tol = [1e-6 1e-8 1e-10]
  oa = odeset ("RelTol", tol, "AbsTol", tol);
  tt = timeit_turns ({@() ode45(@kepler, [0 10*T], y0, oa), ...
                      @() odeSPVI(@kepler, [0 10*T], y0, oa)}, 4);
  [~, ya45] = ode45 (@kepler, [0 10*T], y0, oa);
  sa = odeSPVI (@kepler, [0 10*T], y0, oa);
  A1_NCALLS = 0;
  sc = ode45 (@kepler_count, [0 10*T], y0, oa);   # an output: no plot
  txt{end+1} = sprintf ("%.0e: ode45 %.3f s, %d calls, error %.1e; odeSPVI %.3f s = 1/%.1f, %d calls, error %.1e", ...
                        tol, tt(1), A1_NCALLS, norm (ya45(end, :).' - y0, Inf), ...
                        tt(2), tt(1) / tt(2), sa.stats.nfevals + sa.stats.npds, ...
                        norm (sa.y(:, end) - y0, Inf));
endfor
rows_(end+1, :) = {"A1", "adaptive, Kepler 10 periods, RelTol = AbsTol: ode45 vs odeSPVI (4,3) with the Hessian as second output, time in turns, calls, end-point error", ...
                strjoin(txt, "; "), "shown"};

## ---------------------------------------------------------------- P6
ds = [1 10 100 300];
per = zeros (2, numel (ds));  cps = per;
for i = 1:numel (ds)
  d = ds(i);
  q0 = 0.1 * sin (pi * (1:d).' / (d+1));
  yf = [q0; zeros(d, 1)];
  nst = 200;
  of = symplecticset ("TimeStepSize", 0.05, "TimeStepNumber", nst);
  s6 = odeSPVI (@fpu, [0 1], yf, of);
  per(1, i) = timeit (@() odeSPVI (@fpu, [0 1], yf, of), 1) / nst;
  cps(1, i) = (s6.stats.nfevals + s6.stats.npds) / nst;
  s6 = odeSV (@fpu, [0 1], yf, symplecticset (of, "Separable", "on"));
  per(2, i) = timeit (@() odeSV (@fpu, [0 1], yf, symplecticset (of, "Separable", "on")), 1) / nst;
  cps(2, i) = s6.stats.nfevals / nst;
endfor
rows_(end+1, :) = {"P6", "FPU chain, time per step at d = 1, 10, 100, 300: odeSPVI (4,3)", ...
                sprintf("%s us (calls/step %s); d=100 / d=1 = %.1f", ...
                         mat2str(round(1e6 * per(1, :))), mat2str(cps(1, :), 3), ...
                         per(1, 3) / per(1, 1)), "d=100 <= 10x d=1"};
rows_(end+1, :) = {"P6b", "FPU chain, odeSV Separable, same d", ...
                sprintf("%s us (calls/step %s)", mat2str(round(1e6 * per(2, :))), ...
                         mat2str(cps(2, :), 3)), "scaling shown"};

## the FPU chain at d = 1 and 10 with a new matrix on every step: fewer
## calls, but every step's first calls build the Hessian (with blkdiag)
per_n = zeros (1, 2);  cps_n = per_n;
for i = 1:2
  d = ds(i);
  q0 = 0.1 * sin (pi * (1:d).' / (d+1));
  yf = [q0; zeros(d, 1)];
  of = symplecticset ("TimeStepSize", 0.05, "TimeStepNumber", 200);
  ofn = symplecticset (of, "NewtonMatrix", "new");
  s6 = odeSPVI (@fpu, [0 1], yf, ofn);
  tt = timeit_turns ({@() odeSPVI(@fpu, [0 1], yf, of), ...
                      @() odeSPVI(@fpu, [0 1], yf, ofn)}, 2);
  per_n(i) = tt(2) / tt(1);
  cps_n(i) = (s6.stats.nfevals + s6.stats.npds) / 200;
endfor
rows_(end+1, :) = {"P6n", "FPU chain d = 1, 10, odeSPVI (4,3) with NewtonMatrix new: time per step / that of the kept matrix", ...
                sprintf("%s (calls/step %s)", mat2str(per_n, 2), mat2str(cps_n, 3)), ...
                "shown (the Hessian's cost decides)"};

## ---------------------------------------------------------------- S1
## odeSE and odeSV on a non-separable H: Newton on every step, started from
## the history of the unknowns; fixed steps h = 0.01 and 0.05 over t = 20,
## with the Hessian as second output and with finite differences
yr = [1; 0.2; -0.3; 0.1; 0.8; 0.4];
txt = {};
fns = {@rot3, @rot3_f};  labels = {"Hessian", "FD"};
for solver = {@odeSE, @odeSV}
  for k = 1:2
    for h = [0.01 0.05]
      os = symplecticset ("TimeStepSize", h);
      ss = solver{1} (fns{k}, [0 20], yr, os);
      tps = timeit (@() solver{1} (fns{k}, [0 20], yr, os), 1) / ss.stats.nsteps;
      txt{end+1} = sprintf ("%s %s h = %.2f: %.0f us, %.2f calls", ...
                            func2str (solver{1}), labels{k}, h, 1e6 * tps, ...
                            (ss.stats.nfevals + ss.stats.npds) / ss.stats.nsteps);
    endfor
  endfor
endfor
rows_(end+1, :) = {"S1", "odeSE, odeSV on a non-separable H in 3-D (tests/test_se_sv.m), fixed step, Newton started from the last steps: time and callbacks (fcn + Hessian) per step", ...
                strjoin(txt, "; "), "shown"};

## ---------------------------------------------------------------- report
[~, cpu] = system ("sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1");
[~, kern] = system ("uname -srm");
hdr = sprintf ("Octave %s, %s, %s, %d cores", version (), strtrim (cpu), ...
               strtrim (kern), nproc ());
lines = {"| # | measure | result | target |", "|---|---|---|---|"};
for i = 1:rows (rows_)
  lines{end+1} = sprintf ("| %s | %s | %s | %s |", rows_{i, :});
endfor
printf ("\n%s\n\n%s\n", hdr, strjoin (lines, "\n"));
fid = fopen (fullfile (here, "RESULTS.md"), "w");
fprintf (fid, "# Benchmark results\n\nWritten by `make bench` (bench/run_benchmarks.m) on %s.\n\n%s\n\n%s\n", ...
         datestr (now, "yyyy-mm-dd"), hdr, strjoin (lines, "\n"));
fclose (fid);
