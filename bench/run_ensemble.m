## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## run_ensemble.m -- the benchmark of ensembles (Ensemble "on"):
##
##  A. Kepler, K = 1000 members (eccentricities 0.05 .. 0.6, period 2 pi),
##     fixed step h = 2 pi/100, Vectorized, f = bench/kepler_cols.m: the
##     time per member-step of the ensemble against the time per step of
##     a single run with the same options, for odeSPVI (4, 3) and for
##     odeSV with Separable; members checked against their single runs
##     (isequal);
##  B. K = 16 members, FCN state by state (Vectorized off), odeSPVI (4, 3):
##     the serial ensemble against Parallel = 2 (two processes), the same
##     call otherwise; the results compared (isequal);
##  C. K = 1e4 pendulums (one degree of freedom), 1e3 steps, [t, Y]: the
##     peak memory of the call against the size of its output, for odeSV
##     with Separable (explicit steps: the members as one stacked system),
##     odeSV (implicit) and odeSPVI (members in rounds); each run in its
##     own process (bench/ensemble_worker.m says how it measures).
##
## Times are wall clock (tic/toc around the call), the least of a few
## calls, A and B in this process.  About 5 minutes on 2 cores, most of
## it C's implicit runs.  Writes bench/ENSEMBLE.md.  Run from the top
## directory:
##
##   octave-cli --norc --path "$PWD/inst:$PWD/src:$PWD/bench" bench/run_ensemble.m
##
## Benchmarks are not tests: nothing here asserts; the table says which
## of the issue's targets are met.

1;

function [best, out] = best_of (n, f)
  ## the least time of n calls of f, and the outputs of the last
  best = Inf;
  for i = 1:n
    tic;
    out = f ();
    best = min (best, toc);
  endfor
endfunction

function [best, out] = best_of_turns (n, fs)
  ## the least time of n calls of each of the functions fs, called in
  ## turns (so that a busy spell of the machine falls on all of them),
  ## and the outputs of the last calls
  best = Inf (1, numel (fs));
  out = cell (1, numel (fs));
  for i = 1:n
    for j = 1:numel (fs)
      tic;
      out{j} = fs{j} ();
      best(j) = min (best(j), toc);
    endfor
  endfor
endfunction

function out = run_t_y (solver, fcn, tspan, y0, o)
  [t, y] = solver (fcn, tspan, y0, o);
  out = {t, y};
endfunction

function r = worker (top, args)
  out = [tempname() ".bin"];
  p = strjoin ({fullfile(top, "inst"), fullfile(top, "src"), ...
                fullfile(top, "bench")}, pathsep ());
  cmd = sprintf ("octave-cli --norc --path '%s' '%s' %s out='%s' 2>&1", p, ...
                 fullfile (top, "bench", "ensemble_worker.m"), args, out);
  [st, txt] = system (cmd);
  if (st != 0 || ! exist (out, "file"))
    error ("run_ensemble: the worker failed (%s):\n%s", args, txt);
  endif
  s = load (out);
  delete (out);
  r = s.res;
endfunction

function s = met (ok)
  s = merge (ok, "met", "NOT met");
endfunction

top = fileparts (fileparts (mfilename ("fullpath")));
t_start = tic;
[~, ncpu] = system ("nproc");
[~, uname] = system ("uname -srm");
cpu = regexp (fileread ("/proc/cpuinfo"), 'model name\s*:\s*([^\n]*)', ...
              "tokens", "once");
hdr = sprintf ("Octave %s, %s, %s, %d cores (nproc)", version (), ...
               strtrim (cpu{1}), strtrim (uname), str2double (ncpu));
printf ("%s\n", hdr);

## ------------------------------------------------------------ A
K = 1000;
e = linspace (0.05, 0.6, K);
Y0 = [1 - e; 0 * e; 0 * e; sqrt((1 + e) ./ (1 - e))];
h = 2 * pi / 100;
A = struct ();
cases = {"odeSPVI", @odeSPVI, {}, 2000, 100; ...
         "odeSV", @odeSV, {"Separable", "on"}, 4000, 1000};
for c = 1:rows (cases)
  [name, solver, extra, n1, nk] = cases{c,:};
  o1 = symplecticset ("TimeStepSize", h, "Vectorized", "on", extra{:});
  oK = symplecticset (o1, "Ensemble", "on");
  printf ("\nA. %s, Kepler, single run of %d steps, ensemble of %d members x %d steps\n", ...
          name, n1, K, nk);
  fflush (stdout);
  [tt, outs] = best_of_turns (5, {@() run_t_y(solver, @kepler_cols, [0 n1*h], Y0(:,300), o1), ...
                                  @() run_t_y(solver, @kepler_cols, [0 nk*h], Y0, oK)});
  t1 = tt(1);  tK = tt(2);  out = outs{2};
  same = true;
  for k = [1 300 K]
    [t, y] = solver (@kepler_cols, [0 nk*h], Y0(:,k), o1);
    same = same && isequal (t, out{1}) && isequal (y, out{2}(:,:,k));
  endfor
  ## the plain single run, FCN state by state, for scale
  o0 = symplecticset ("TimeStepSize", h, extra{:});
  t0 = best_of (5, @() run_t_y (solver, @kepler_cols, [0 n1*h], Y0(:,300), o0));
  A.(name) = struct ("single", t1 / n1, "plain", t0 / n1, ...
                     "member", tK / (K * nk), "same", same);
  printf ("  single run %.2f us/step (Vectorized off: %.2f), ensemble %.3f us/member-step = 1/%.0f; members = their runs: %d\n", ...
          1e6 * t1 / n1, 1e6 * t0 / n1, 1e6 * tK / (K * nk), ...
          (t1 / n1) / (tK / (K * nk)), same);
  fflush (stdout);
endfor

## ------------------------------------------------------------ B
printf ("\nB. odeSPVI (4, 3), 16 members, Vectorized off: serial against Parallel = 2\n");
fflush (stdout);
KB = 16;
nB = 6000;
oB = symplecticset ("TimeStepSize", h, "Ensemble", "on");
[ts, outs] = best_of (5, @() run_t_y (@odeSPVI, @kepler_cols, [0 nB*h], Y0(:,1:KB), oB));
B.serial = ts;
B.parallel = NaN;
B.same = false;
B.note = "";
try
  oP = symplecticset (oB, "Parallel", 2);
  [tp, outp] = best_of (5, @() run_t_y (@odeSPVI, @kepler_cols, [0 nB*h], Y0(:,1:KB), oP));
  B.parallel = tp;
  B.same = isequal (outs, outp);
catch err
  B.note = err.message;
end_try_catch
printf ("  serial %.2f s, Parallel = 2 %.2f s: %.2fx; the same to the bit: %d %s\n", ...
        B.serial, B.parallel, B.serial / B.parallel, B.same, B.note);
fflush (stdout);

## ------------------------------------------------------------ C
printf ("\nC. 1e4 pendulums, 1e3 steps, peak memory of the call / its output\n");
fflush (stdout);
C = {};
runs = {"odeSV", "on"; "odeSV", "off"; "odeSPVI", "off"};
for i = 1:rows (runs)
  r = worker (top, sprintf ("solver=%s separable=%s K=10000 steps=1000", ...
                            runs{i,:}));
  r.name = runs{i,1};
  r.separable = runs{i,2};
  C{end+1} = r;
  printf ("  %-8s Separable %-3s: output %.1f MB, peak %.1f MB = %.2fx, %.1f s (%.2f us/member-step), dE %.1e\n", ...
          r.name, r.separable, r.out / 2^20, r.peak / 2^20, r.peak / r.out, ...
          r.time, 1e6 * r.time / (r.K * r.steps), r.dE);
  fflush (stdout);
endfor

## ------------------------------------------------------------ ENSEMBLE.md
el = toc (t_start);
f = fopen (fullfile (top, "bench", "ENSEMBLE.md"), "w");
fprintf (f, "# Ensembles: many initial states in one call\n\n");
fprintf (f, "Written by bench/run_ensemble.m on %s in %.0f s.\n\n%s\n\n", ...
         datestr (now (), "yyyy-mm-dd HH:MM"), el, hdr);
fprintf (f, "Re-run from the top directory (after make):\n\n");
fprintf (f, "    octave-cli --norc --path \"$PWD/inst:$PWD/src:$PWD/bench\" bench/run_ensemble.m\n\n");
fprintf (f, "## The issue's measures\n\n");
fprintf (f, "| part | measure | result | target | |\n|---|---|---|---|---|\n");
s = A.odeSPVI;
fprintf (f, "| A | odeSPVI (4, 3), K = 1000, Vectorized: a single run's step / the ensemble's member-step | %.2f us / %.3f us = %.1f | >= 50 | %s |\n", ...
         1e6 * s.single, 1e6 * s.member, s.single / s.member, met (s.single / s.member >= 50));
fprintf (f, "| A | odeSPVI (4, 3): the single run with Vectorized off / the member-step | %.2f us / %.3f us = %.1f | (information) | |\n", ...
         1e6 * s.plain, 1e6 * s.member, s.plain / s.member);
s = A.odeSV;
fprintf (f, "| A | odeSV, Separable, K = 1000, Vectorized: a single run's step / the member-step | %.2f us / %.3f us = %.0f | >= 100 | %s |\n", ...
         1e6 * s.single, 1e6 * s.member, s.single / s.member, met (s.single / s.member >= 100));
fprintf (f, "| A | members against their own runs (members 1, 300, 1000) | %s | isequal | %s |\n", ...
         merge (A.odeSPVI.same && A.odeSV.same, "equal", "DIFFER"), ...
         met (A.odeSPVI.same && A.odeSV.same));
fprintf (f, "| B | 16 members, Vectorized off, odeSPVI (4, 3): serial / Parallel = 2 | %.2f s / %.2f s = %.2f | >= 1.7 | %s |\n", ...
         B.serial, B.parallel, B.serial / B.parallel, met (B.serial / B.parallel >= 1.7));
fprintf (f, "| B | Parallel = 2 against serial | %s | isequal | %s |\n", ...
         merge (B.same, "equal", "DIFFER"), met (B.same));
for i = 1:numel (C)
  r = C{i};
  fprintf (f, "| C | 1e4 pendulums, 1e3 steps, %s%s: peak / output | %.1f MB / %.1f MB = %.2f | <= 1.5 | %s |\n", ...
           r.name, merge (strcmp (r.separable, "on"), " Separable", ""), ...
           r.peak / 2^20, r.out / 2^20, r.peak / r.out, met (r.peak / r.out <= 1.5));
endfor
fprintf (f, "\n## What is measured\n\n");
fprintf (f, "A. Kepler's problem, y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))] for K = 1000 eccentricities e from 0.05 to 0.6 (all of period 2 pi), fixed step h = 2 pi/100, `Vectorized` on, FCN bench/kepler_cols.m (a column alone and among others alike).  The single run (member 300, e = %.3f) takes %d steps (odeSPVI) or %d (odeSV), the ensemble %d or %d steps of every member; each time is the least of 5 calls of `[t, y] = solver (...)`, the single run and the ensemble called in turns; a member-step is the ensemble's time / (K x steps).  For scale, the single run with `Vectorized` off: odeSPVI %.2f us/step, odeSV %.2f us/step.\n\n", ...
         e(300), cases{1,4}, cases{2,4}, cases{1,5}, cases{2,5}, 1e6 * A.odeSPVI.plain, 1e6 * A.odeSV.plain);
fprintf (f, "B. Members 1 to 16 of A, `Vectorized` off (FCN called for each state), %d steps, odeSPVI (4, 3); the least of 5 calls each; Parallel = 2 splits the members between two processes of the package `parallel`.%s\n\n", ...
         nB, merge (isempty (B.note), "", [" Parallel failed: " B.note]));
fprintf (f, "C. K = 1e4 pendulums H = p^2/2 - cos q, q0 from 0.1 to 2.5, p0 = 0, fixed step 0.01, 1e3 steps, `Vectorized` on, `[t, Y] = solver (@pendulum_cols, [0 10], Y0, opts)`: the output is t and Y, 1001 x 2 x 1e4 doubles.  Each run is its own octave-cli process (bench/ensemble_worker.m): a warm-up call, then VmHWM is reset to VmRSS, the call is made, and the peak is VmHWM after less VmRSS before: everything the call touched at its highest, the output included.  odeSV with Separable takes explicit steps: the members go as one stacked system; the other two run in rounds, at most 128 members at once (SYM_ENS_LIVE).\n\n");
fprintf (f, "| run | time | us per member-step | largest energy error |\n|---|---|---|---|\n");
for i = 1:numel (C)
  r = C{i};
  fprintf (f, "| %s%s | %.1f s | %.2f | %.1e |\n", r.name, ...
           merge (strcmp (r.separable, "on"), " Separable", ""), ...
           r.time, 1e6 * r.time / (r.K * r.steps), r.dE);
endfor
fprintf (f, "\nTimes are from a machine that may have been busy.\n");
fclose (f);
printf ("\nwrote bench/ENSEMBLE.md (%.0f s)\n", el);
