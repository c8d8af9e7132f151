## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## run_large.m -- the benchmark of large systems: Newton's systems with a
## sparse Hessian solved by stages (sparse LU) against the dense LU of
## the whole step system.
##
##  A. odeSPVI (Q_DoFs 4, Nodes 3, Vectorized) on a beta FPU chain with a
##     sparse (tridiagonal) Hessian, d = 1e2 .. 1e5, the plain fixed-step
##     call (a row at every step): time per step and per degree of
##     freedom; peak memory per degree of freedom, in total and split into
##     the output, the callbacks and the solver's own; and d = 1e5 again
##     with output times (the dense output on);
##  B. odeSPVI (4, 3) on an all-to-all H of d = 2000 (a dense Hessian,
##     returned full): a step's time (runs of 4 and of 2 steps, their
##     difference over 2) with NewtonSystem "full" against "auto";
##  C. implicit odeSV on a non-separable H with a sparse Hessian, d = 1e2
##     .. 1e5 (each d only where the last ones say that it fits);
##  D. d = 100: the sparse paths against the dense ones, final states.
##
## Every run is its own octave-cli process, bench/large_worker.m (which
## says what it measures), so that its peak memory is its own.  About 2
## minutes on 2 cores, most of it the two runs of B's "full".
##
## The environment variable SYM_BENCH_SV_MAXD (default 1e5) is the
## largest d of part C; larger d are also skipped where the runs before
## predict more than SV_MAX_RUN seconds or more than half the available
## memory (see C below).
##
## Writes bench/LARGE.md.  Run from the top directory:
##
##   octave-cli --norc --path "$PWD/inst:$PWD/src:$PWD/bench" bench/run_large.m
##
## Benchmarks are not tests: nothing here asserts; the tables say which of
## the issue's targets are met.

1;

## ------------------------------------------------------------ functions

function r = worker (top, args)
  ## one run of bench/large_worker.m with ARGS (a string of key=value);
  ## a failure that looks like a MEX file being rebuilt is retried after a
  ## minute, twice at most
  out = [tempname() ".bin"];
  p = strjoin ({fullfile(top, "inst"), fullfile(top, "src"), ...
                fullfile(top, "bench")}, pathsep ());
  cmd = sprintf ("octave-cli --norc --path '%s' '%s' %s out='%s' 2>&1", p, ...
                 fullfile (top, "bench", "large_worker.m"), args, out);
  for attempt = 1:3
    [st, txt] = system (cmd);
    if (st == 0 && exist (out, "file"))
      break;
    endif
    mex_like = ! isempty (regexpi (txt, "mex|__ode\\w+__|undefined|invalid ELF|cannot open shared", "once"));
    if (! mex_like || attempt == 3)
      error ("run_large: the worker failed (%s):\n%s", args, txt);
    endif
    printf ("  the worker failed, as if a MEX file were being rebuilt; retrying in 60 s\n%s\n", txt);
    fflush (stdout);
    pause (60);
  endfor
  s = load (out);
  delete (out);
  r = s.res;
  r.mem = r.hwm1 - r.rss0;               # bytes
endfunction

function r = timed (top, base, d, steps, target, minsec, maxsteps)
  ## a run of about target seconds: when the first one took less than
  ## minsec, again with the steps scaled to target
  r = worker (top, sprintf ("%s d=%d steps=%d", base, d, steps));
  r.tries = 1;
  if (r.time < minsec && r.steps < maxsteps)
    steps = min (maxsteps, ceil (target / r.per_step));
    r = worker (top, sprintf ("%s d=%d steps=%d", base, d, steps));
    r.tries = 2;
  endif
endfunction

function r = a_parts (top, r, cbfrom)
  ## part A: the callbacks' peaks (each in its own process, or those of
  ## the run CBFROM) and the solver's own: total - output - the larger
  if (isempty (cbfrom))
    cf = worker (top, sprintf ("case=fpu hess=sparse d=%d only=fcn", r.d));
    ch = worker (top, sprintf ("case=fpu hess=sparse d=%d only=hess", r.d));
    r.cb_f = cf.mem;  r.cb_hess = ch.mem;
  else
    r.cb_f = cbfrom.cb_f;  r.cb_hess = cbfrom.cb_hess;
  endif
  r.cb = max (r.cb_f, r.cb_hess);
  r.own = r.mem - r.outbytes - r.cb;
endfunction

function n = steps_for (per_step, target, minsteps, maxsteps)
  n = min (maxsteps, max (minsteps, ceil (target / per_step)));
  n = 2 * ceil (n / 2);
endfunction

function s = kb (bytes)
  s = sprintf ("%.0f", bytes);
endfunction

function s = mb (bytes)
  s = sprintf ("%.1f", bytes / 2^20);
endfunction

function s = dtext (d)
  s = sprintf ("1e%d", round (log10 (d)));
  if (10^round (log10 (d)) != d)
    s = sprintf ("%d", d);
  endif
endfunction

function v = meminfo (key)
  s = fileread ("/proc/meminfo");
  v = 1024 * str2double (regexp (s, [key ":\\s*(\\d+)"], "tokens", "once"){1});
endfunction

function s = stats_line (txt)
  ## the counts of Stats "on" in one line
  L = strtrim (strsplit (strtrim (txt), "\n"));
  L = L(! cellfun (@isempty, L));
  L = regexprep (L, "^Number of ", "");
  s = regexprep (strjoin (L, "; "), "\\s+", " ");
endfunction

## ------------------------------------------------------------ set-up

t_all = tic;
here = fileparts (mfilename ("fullpath"));
top = fileparts (here);
TARGET_S = 1.5;                          # seconds a timed run aims at
MIN_S = 1;                               # and takes at least
A_MINSTEPS = 12;                         # A: steps of a run, at least
A_MAXSTEPS = 24;                         # and at most (output <= 400 B/dof)
SV_MAX_RUN = 120;                        # C: largest predicted run (s)

[~, cpu] = system ("lscpu | sed -n 's/^Model name:[[:space:]]*//p'");
[~, kern] = system ("uname -srm");
hdr = sprintf ("Octave %s, %s, %s, %d cores (nproc), %.0f GiB of memory", ...
               version (), strtrim (cpu), strtrim (kern), nproc (), ...
               meminfo ("MemTotal") / 2^30);
printf ("%s\n", hdr);

## ------------------------------------------------------------ A

printf ("\nA. FPU chain, sparse Hessian, odeSPVI (4, 3), h = 0.1, [t, y] = odeSPVI (fcn, [0 tf], y0, opts)\n");
dA = [1e2 1e3 1e4 1e5];
A = {};
ps = NaN;
for k = 1:numel (dA)
  d = dA(k);
  if (k == 1)
    n = A_MAXSTEPS;
  else
    n = steps_for (ps * d / dA(k-1), TARGET_S, A_MINSTEPS, A_MAXSTEPS);
  endif
  r = worker (top, sprintf ("case=fpu h=0.1 hess=sparse system=auto tout=steps mintime=%g d=%d steps=%d", ...
                            MIN_S, d, n));
  ps = r.per_step;
  A{k} = a_parts (top, r, []);
  r = A{k};
  printf ("  d = %-7s %3d steps %4d call(s) %7.3f s  %9.3g s/step  %6.3f us/step/dof  peak %6.1f MB = %5.0f B/dof: output %4.0f, callbacks %3.0f (fcn %3.0f, Hessian %3.0f), solver's own %5.0f  dE %.1e\n", ...
          dtext (d), r.steps, r.calls, r.time, r.per_step, 1e6 * r.per_step / d, ...
          r.mem / 2^20, r.mem / d, r.outbytes / d, r.cb / d, r.cb_f / d, ...
          r.cb_hess / d, r.own / d, r.dE);
  fflush (stdout);
endfor
A = [A{:}];
## the same d = 1e5 run with output times: the dense output on
d = dA(end);
printf ("  d = %s, output times [0 tf/2 tf] (dense output on) ...\n", dtext (d));  fflush (stdout);
r = worker (top, sprintf ("case=fpu h=0.1 hess=sparse system=auto tout=mid d=%d steps=%d", ...
                          d, A(end).steps));
Adense = a_parts (top, r, A(end));
printf ("  d = %-7s %3d steps, dense output: %7.3f s  %9.3g s/step  %6.3f us/step/dof  peak %6.1f MB = %5.0f B/dof: output %4.0f, callbacks %3.0f, solver's own %5.0f  dE %.1e\n", ...
        dtext (d), Adense.steps, Adense.time, Adense.per_step, 1e6 * Adense.per_step / d, ...
        Adense.mem / 2^20, Adense.mem / d, Adense.outbytes / d, Adense.cb / d, ...
        Adense.own / d, Adense.dE);
fflush (stdout);
usA = 1e6 * [A.per_step] ./ dA;
ratioA = usA(dA == 1e5) / usA(dA == 1e3);
memA = [A.mem] ./ dA;                    # total peak per dof
ownA = [A.own] ./ dA;                    # the solver's own per dof
big = dA >= 1e4;
[ownA_big, kbig] = max (ownA .* big);
memA_big = max (memA(big));
a_time_ok = ratioA <= 3;
a_mem_ok = ownA_big <= 2048;

## ------------------------------------------------------------ B

printf ("\nB. all-to-all H, dense Hessian returned full, d = 2000, odeSPVI (4, 3), runs of 2 and 4 steps of 0.1\n");
dB = 2000;
B = struct ("full", {{}}, "auto", {{}});
nB = [2 4];
for sys = {"full", "auto"}
  for k = 1:numel (nB)
    printf ("  NewtonSystem \"%s\", %d steps ...\n", sys{1}, nB(k));  fflush (stdout);
    r = worker (top, sprintf ("case=mf d=%d steps=%d h=0.1 hess=full system=%s", ...
                              dB, nB(k), sys{1}));
    printf ("  NewtonSystem \"%s\", %d steps: %.3f s, %.3f s/step, peak %.1f MB, dE %.1e\n", ...
            sys{1}, nB(k), r.time, r.per_step, r.mem / 2^20, r.dE);
    fflush (stdout);
    B.(sys{1}){k} = r;
  endfor
endfor
B.full = [B.full{:}];  B.auto = [B.auto{:}];
## a step's time: the difference of the two runs over the 2 steps more
## (the start, the probe of the Hessian and the first step's Euler start
## cancel); the whole runs' times per step are shown too
stepB = @(v) (v(2).time - v(1).time) / (nB(2) - nB(1));
minBf = stepB (B.full);  minBa = stepB (B.auto);
ratioB = minBf / minBa;
## the relative difference of the final states of the runs of each length
diffB = 0;
for k = 1:numel (nB)
  diffB = max (diffB, max (abs (B.auto(k).yend - B.full(k).yend)) ...
                      / max (abs (B.full(k).yend)));
endfor
printf ("  s per step (4 steps less 2): full %.3f, auto %.3f; full / auto = %.2f; final states differ by %.2e (relative)\n", ...
        minBf, minBa, ratioB, diffB);

## ------------------------------------------------------------ C

printf ("\nC. non-separable H, sparse Hessian, odeSV (implicit Verlet), h = 0.1\n");
maxd = str2double (getenv ("SYM_BENCH_SV_MAXD"));
if (! isfinite (maxd))
  maxd = 1e5;
endif
dC = [1e2 1e3 1e4 1e5];
C = struct ("d", num2cell (dC), "run", {[]}, "skip", "", "why", "");
memavail = meminfo ("MemAvailable");
for k = 1:numel (dC)
  d = dC(k);
  if (d > maxd)
    C(k).skip = "skipped (SYM_BENCH_SV_MAXD)";
    C(k).why = sprintf ("d > SYM_BENCH_SV_MAXD = %g", maxd);
    printf ("  d = %-7s %s\n", dtext (d), C(k).skip);
    continue;
  endif
  if (k > 1)
    prev = find (! cellfun (@isempty, {C(1:k-1).run}));
    if (numel (prev) < k - 1)
      C(k).skip = C(k-1).skip;
      C(k).why = "a smaller d was skipped";
      printf ("  d = %-7s %s\n", dtext (d), C(k).skip);
      continue;
    endif
    ## the growth of the time per step and of the peak with d, measured
    ## between the last two runs (at least linear), extrapolated
    r1 = C(k-1).run;  ea = 1;  eb = 1;
    if (k > 2)
      r0 = C(k-2).run;
      ea = max (1, log (r1.per_step / r0.per_step) / log (r1.d / r0.d));
      eb = max (1, log (max (r1.mem, 1) / max (r0.mem, 1)) / log (r1.d / r0.d));
      if (eb > 1.5)
        ## a peak growing as d^2 is a dense matrix, and its LU then takes
        ## d^3 (at small d the time per step is mostly callbacks)
        ea = max (ea, 3);
      endif
    endif
    ps = r1.per_step * (d / r1.d)^ea;
    pm = max (r1.mem, 1) * (d / r1.d)^eb;
    if (r1.time > 60 || 6 * ps > SV_MAX_RUN || pm > memavail / 2)
      if (ea > 1.5 || eb > 1.5)
        C(k).skip = "skipped (dense)";
      else
        C(k).skip = "skipped (time)";
      endif
      C(k).why = sprintf ("predicted from d = %s: %.3g s per step (time per step ~ d^%.2f), peak %.3g GB (~ d^%.2f); limits %g s a run, %.3g GB", ...
                          dtext (r1.d), ps, ea, pm / 1e9, eb, SV_MAX_RUN, memavail / 2e9);
      printf ("  d = %-7s %s: %s\n", dtext (d), C(k).skip, C(k).why);
      continue;
    endif
    n = steps_for (ps, TARGET_S, 6, 20000);
  else
    n = 2000;
  endif
  r = timed (top, "case=ns h=0.1 hess=sparse", d, n, TARGET_S, MIN_S, 20000);
  C(k).run = r;
  printf ("  d = %-7s %5d steps %7.3f s  %9.3g s/step  %6.3f us/step/dof  peak %7.1f MB = %5.0f B/dof  dE %.1e\n", ...
          dtext (d), r.steps, r.time, r.per_step, 1e6 * r.per_step / d, ...
          r.mem / 2^20, r.mem / d, r.dE);
  fflush (stdout);
endfor
ranC = ! cellfun (@isempty, {C.run});
usC = NaN (size (dC));
for k = find (ranC)
  usC(k) = 1e6 * C(k).run.per_step / dC(k);
endfor

## ------------------------------------------------------------ D

printf ("\nD. d = 100, 100 steps of 0.1: sparse paths against dense ones\n");
D = struct ();
D.spvi_sparse = worker (top, "case=fpu d=100 steps=100 h=0.1 hess=sparse system=auto");
D.spvi_full = worker (top, "case=fpu d=100 steps=100 h=0.1 hess=full system=full");
D.sv_sparse = worker (top, "case=ns d=100 steps=100 h=0.1 hess=sparse");
D.sv_full = worker (top, "case=ns d=100 steps=100 h=0.1 hess=full");
rel = @(a, b) max (abs (a.yend - b.yend)) / max (abs (b.yend));
diffD1 = rel (D.spvi_sparse, D.spvi_full);
diffD2 = rel (D.sv_sparse, D.sv_full);
printf ("  odeSPVI: %.2e;  odeSV: %.2e\n", diffD1, diffD2);

## ------------------------------------------------------------ report

t_total = toc (t_all);
md = {};
md{end+1} = "# Large systems: sparse Hessians, Newton's systems by stages\n";
md{end+1} = sprintf ("Written by bench/run_large.m on %s in %.0f s.\n\n%s\n", ...
                     datestr (now, "yyyy-mm-dd HH:MM"), t_total, hdr);
md{end+1} = "Re-run from the top directory (after make):\n\n    octave-cli --norc --path \"$PWD/inst:$PWD/src:$PWD/bench\" bench/run_large.m\n";
md{end+1} = sprintf (["What is measured.  Every run is its own octave-cli process " ...
  "(bench/large_worker.m): a warm-up call of the same solver with the same options and " ...
  "the same form of tspan at d = 10 (so that the MEX file, the sparse LU and the m-files " ...
  "are loaded); then VmHWM is reset to VmRSS (5 written to /proc/self/clear_refs%s), " ...
  "VmRSS is read from /proc/self/status (\"before\"), the solver's call is timed (wall " ...
  "clock, tic/toc around the call, its Stats included) and VmHWM is read again " ...
  "(\"after\").  Total peak = VmHWM after - VmRSS before: all the memory the call " ...
  "touched at its highest, that is the solver's work space, the m-file callbacks' " ...
  "temporaries and the output [t, y].  Every run has fixed steps, TimeStepSize h = 0.1, " ...
  "tf = steps h.  Energy error: max |H - H0| / |H0| over the output's rows.  Time per " ...
  "step: the call's time / steps; per dof (degree of freedom; d of them, the state has 2d " ...
  "entries): / d.  Parts B, C and D call `[t, y] = solver (fcn, [0, tf/2, tf], y0, opts)` " ...
  "(an even number of steps: three rows, all at step points); part A calls the plain " ...
  "fixed-step form, see there.  Times are from a machine that may have been busy.\n"], ...
  merge (all ([A.reset Adense.reset]), "", "; it failed, so VmHWM before may be higher than VmRSS"));

## A
md{end+1} = "## A. FPU chain, sparse Hessian, odeSPVI (4, 3)\n";
md{end+1} = sprintf (["H = sum p_i^2/2 + sum_{i=0}^{d} V(q_{i+1} - q_i), q_0 = q_{d+1} = 0, " ...
  "V(r) = r^2/2 + r^4/4 (bench/fpu.m); q0_i = 0.2 sin(1.3 i), p0_i = 0.2 cos(0.7 i) " ...
  "(about the same energy per dof at every d).  odeSPVI with Q_DoFs 4, Nodes 3 (order 6), " ...
  "Vectorized \"on\", TimeStepSize 0.1, HamiltonianHessFcn returning the sparse " ...
  "Hessian [K 0; 0 I] (K tridiagonal: 4d - 2 nonzeros), NewtonSystem \"auto\" (by " ...
  "stages), NewtonMatrix default.\n\n" ...
  "The timed call is the plain fixed-step one, `[t, y] = odeSPVI (fcn, [0 tf], y0, opts)`: " ...
  "no output times, a row at every step.  (Output times would switch on the dense output " ...
  "and its work arrays; the last row of the table is that case.)  Steps, even: at most " ...
  "%d, so that the output stays small (d = 1e2 takes that many), and fewer where %.1f s " ...
  "would take fewer at the time per step of the d before, but at least %d.  Where the call " ...
  "took less than %.0f s, the same call is made again in the same process (its output " ...
  "cleared in between) until the calls took %.0f s together: time per step = the calls' " ...
  "time / (calls x steps); the memory is the first call's.\n\n" ...
  "Memory per dof, in bytes, each / d:\n\n" ...
  "- total: the total peak (above);\n" ...
  "- output: the size of [t, y], (steps + 1) (2d + 1) 8 bytes.  The solver gathers the " ...
  "rows in a buffer as it goes and copies them into [t, y] only after it has freed its " ...
  "work space, so while it steps it holds at most this size of rows besides its work " ...
  "space;\n" ...
  "- callbacks: the peaks of one call of fcn on 3 states (the 3 nodes of a Newton " ...
  "iteration, Vectorized) and of one call of the Hessian function, each measured as " ...
  "above in its own process after the warm-up (no array of size d held yet); the two " ...
  "are never called at once, so the larger counts;\n" ...
  "- solver's own = total - output - callbacks' larger peak.\n\n" ...
  "These peaks also depend on how the C library's allocator lays out the process's " ...
  "memory (blocks freed inside its heap stay resident and are reused or not): at " ...
  "d = 1e4 the same call, started with its arguments written differently, peaked 6-8%% " ...
  "apart, and more with a longer output.  Read them to about 10%%.\n\n" ...
  "The target of at most 2 KB (2048 B) per dof is judged on the solver's own, at d >= " ...
  "1e4 (at smaller d the process's fixed costs weigh); the total is shown too.  The last " ...
  "row is d = 1e5 again, with output times [0 tf/2 tf]: three rows, the dense output on " ...
  "(information, no target; its callbacks are those measured for d = 1e5 above, one call).\n"], ...
  A_MAXSTEPS, TARGET_S, A_MINSTEPS, MIN_S, MIN_S);
t = {"| d | steps | calls | time per call (s) | s/step | us/step/dof | total peak (MB) | total /dof (B) | output /dof (B) | callbacks /dof (B): fcn, Hessian | solver's own /dof (B) | energy error |", ...
     "|---|---|---|---|---|---|---|---|---|---|---|---|"};
for k = 1:numel (A)
  r = A(k);
  t{end+1} = sprintf ("| %s | %d | %d | %.3f | %.3g | %.3f | %s | %s | %s | %s, %s | %s | %.1e |", ...
                      dtext (r.d), r.steps, r.calls, r.time / r.calls, r.per_step, ...
                      usA(k), mb (r.mem), kb (memA(k)), kb (r.outbytes / r.d), ...
                      kb (r.cb_f / r.d), kb (r.cb_hess / r.d), kb (ownA(k)), r.dE);
endfor
r = Adense;
t{end+1} = sprintf ("| %s, output times [0 tf/2 tf] (dense output on) | %d | %d | %.3f | %.3g | %.3f | %s | %s | %s | %s, %s | %s | %.1e |", ...
                    dtext (r.d), r.steps, r.calls, r.time / r.calls, r.per_step, ...
                    1e6 * r.per_step / r.d, mb (r.mem), kb (r.mem / r.d), ...
                    kb (r.outbytes / r.d), kb (r.cb_f / r.d), kb (r.cb_hess / r.d), ...
                    kb (r.own / r.d), r.dE);
md{end+1} = [strjoin(t, "\n") "\n"];
md{end+1} = sprintf ("Solver's counts at d = %s (rows at every step): %s.\n", dtext (A(end).d), stats_line (A(end).stats));

## B
md{end+1} = "## B. Dense Hessian, d = 2000: NewtonSystem \"full\" against \"auto\"\n";
md{end+1} = sprintf (["H = |p|^2/2 + V(q), V = -(1/d) sum_{i<j} cos(q_i - q_j) (all-to-all: " ...
  "every entry of d2V/dq2 is nonzero), d = %d; q0 = linspace(-1, 1, d), p0_i = 0.1 cos(i).  " ...
  "odeSPVI (4, 3), fixed steps of 0.1, HamiltonianHessFcn returning the Hessian " ...
  "full (%d-by-%d).  \"full\": one dense LU of the step system, ((Q_DoFs - 1 + Nodes) d)^2 " ...
  "= %d^2 entries (the code as it was before); \"auto\": the stages (here chosen because " ...
  "the system is large; H is separable, so of size d).  Each system runs 2 and 4 steps, " ...
  "each run its own process; a step's time is the difference of the two runs' times over " ...
  "the 2 steps more, so that what a run does once (its start, the call of the Hessian " ...
  "function that finds it full, the first step's start from an Euler step) cancels.  It " ...
  "includes the Hessians, the LU factorizations and the calls of FCN.  Difference: max " ...
  "|y_auto - y_full| / max |y_full| over the final states of the runs of each length.\n"], ...
  dB, 2*dB, 2*dB, 6*dB);
t = {"| NewtonSystem | steps | run (s) | s/step (whole run) | peak (MB) | energy error | counts |", "|---|---|---|---|---|---|---|"};
for sys = {"full", "auto"}
  for k = 1:numel (B.(sys{1}))
    r = B.(sys{1})(k);
    t{end+1} = sprintf ("| %s | %d | %.2f | %.3f | %s | %.1e | %s |", sys{1}, nB(k), r.time, ...
                        r.per_step, mb (r.mem), r.dE, stats_line (r.stats));
  endfor
endfor
md{end+1} = [strjoin(t, "\n") "\n"];
md{end+1} = sprintf (["A step (4 steps less 2, over 2): full %.3f s, auto %.3f s; " ...
                      "full / auto = %.1f.\n"], minBf, minBa, ratioB);

## C
md{end+1} = "## C. Implicit odeSV, non-separable H, sparse Hessian\n";
md{end+1} = sprintf (["H = sum p_i^2 (1 + q_i^2/4)/2 + the FPU chain's V (as in A); " ...
  "q0, p0 as in A.  odeSV (Verlet, Separable \"off\": Newton on the implicit stages), " ...
  "TimeStepSize 0.1, HamiltonianHessFcn returning the sparse Hessian (6d - 2 nonzeros).  " ...
  "Each run aims at %.1f s (its steps chosen from the d before, at least 6, and run again " ...
  "with more if it took less than %.1f s); peak: the total peak, as above.  " ...
  "Each d after the first runs only where the runs before predict that it fits: the " ...
  "time per step and the peak grown from the last d as d^a and d^b, a and b measured " ...
  "between the last two d (at least 1; a at least 3 where b is above 1.5, a dense " ...
  "matrix, whose LU takes d^3 while at small d the callbacks hide it); skipped where the last run took more than 60 s, " ...
  "6 steps would take more than %g s, or the peak would pass half the memory available " ...
  "(\"skipped (dense)\" where a or b is above 1.5: the solver then forms dense " ...
  "matrices), and above SYM_BENCH_SV_MAXD (%g here).\n"], TARGET_S, MIN_S, SV_MAX_RUN, maxd);
t = {"| d | steps | time (s) | s/step | us/step/dof | peak (MB) | peak/dof (B) | energy error |", ...
     "|---|---|---|---|---|---|---|---|"};
for k = 1:numel (C)
  if (ranC(k))
    r = C(k).run;
    t{end+1} = sprintf ("| %s | %d | %.2f | %.3g | %.3f | %s | %s | %.1e |", dtext (r.d), ...
                        r.steps, r.time, r.per_step, usC(k), mb (r.mem), ...
                        kb (r.mem / r.d), r.dE);
  else
    t{end+1} = sprintf ("| %s | %s: %s | | | | | | |", dtext (dC(k)), C(k).skip, C(k).why);
  endif
endfor
md{end+1} = [strjoin(t, "\n") "\n"];
kC = find (ranC, 1, "last");
md{end+1} = sprintf ("Solver's counts at d = %s: %s.\n", dtext (dC(kC)), stats_line (C(kC).run.stats));

## D
md{end+1} = "## D. The sparse paths against the dense ones, d = 100\n";
md{end+1} = ["100 fixed steps of 0.1.  odeSPVI (4, 3): the FPU chain of A, sparse Hessian " ...
  "with NewtonSystem \"auto\" against the same Hessian stored full with NewtonSystem " ...
  "\"full\".  odeSV: the H of C, sparse Hessian against the same Hessian stored full.  " ...
  "Difference: max |y_sparse - y_full| / max |y_full| over the final state.\n"];
t = {"| solver | sparse: s/step | full: s/step | difference of the final states |", "|---|---|---|---|"};
t{end+1} = sprintf ("| odeSPVI | %.3g | %.3g | %.1e |", D.spvi_sparse.per_step, D.spvi_full.per_step, diffD1);
t{end+1} = sprintf ("| odeSV | %.3g | %.3g | %.1e |", D.sv_sparse.per_step, D.sv_full.per_step, diffD2);
md{end+1} = [strjoin(t, "\n") "\n"];

## targets
key = {"| part | measure | result | target | |", "|---|---|---|---|---|"};
key{end+1} = sprintf ("| A | time per step per dof, d = 1e5 / d = 1e3 | %.3f / %.3f us = %.2f | <= 3 | %s |", ...
                      usA(dA == 1e5), usA(dA == 1e3), ratioA, met_text (a_time_ok));
key{end+1} = sprintf ("| A | the solver's own peak per dof (total - output - callbacks), the largest at d >= 1e4 | %s B (d = 1e4: %s, 1e5: %s) | <= 2048 B | %s |", ...
                      kb (ownA_big), kb (ownA(dA == 1e4)), kb (ownA(dA == 1e5)), met_text (a_mem_ok));
key{end+1} = sprintf ("| A | the total peak per dof (with the output and the callbacks), the largest at d >= 1e4 | %s B (d = 1e4: %s, 1e5: %s) | (information) | |", ...
                      kb (memA_big), kb (memA(dA == 1e4)), kb (memA(dA == 1e5)));
key{end+1} = sprintf ("| A | the solver's own peak per dof, d = 1e5 with output times [0 tf/2 tf] (dense output on) | %s B | (information) | |", ...
                      kb (Adense.own / Adense.d));
key{end+1} = sprintf ("| A | energy error, largest over d | %.1e | sanity (round-off to h^6) | |", max ([A.dE Adense.dE]));
key{end+1} = sprintf ("| B | s per step (runs of 4 steps less 2), NewtonSystem \"full\" / \"auto\", d = %d | %.2f / %.2f = %.1f | >= 10 | %s |", ...
                      dB, minBf, minBa, ratioB, met_text (ratioB >= 10));
key{end+1} = sprintf ("| B | max relative difference of the final states | %.1e | <= 1e-12 | %s |", ...
                      diffB, met_text (diffB <= 1e-12));
if (ranC(dC == 1e4))
  r43 = usC(dC == 1e4) / usC(dC == 1e3);
  r42 = usC(dC == 1e4) / usC(dC == 1e2);
  key{end+1} = sprintf ("| C | time per step per dof, d = 1e4 / d = 1e3 (and / d = 1e2) | %.3f / %.3f us = %.2f (%.2f) | <= 3 (as A) | %s |", ...
                        usC(dC == 1e4), usC(dC == 1e3), r43, r42, met_text (r43 <= 3));
  if (ranC(dC == 1e5))
    key{end+1} = sprintf ("| C | time per step per dof, d = 1e5 / d = 1e3 | %.2f | <= 3 (as A) | %s |", ...
                          usC(dC == 1e5) / usC(dC == 1e3), met_text (usC(dC == 1e5) / usC(dC == 1e3) <= 3));
  endif
else
  key{end+1} = sprintf ("| C | time per step per dof, d = 1e4 / d = 1e3 | d = 1e4 %s | <= 3 (as A) | not met |", C(dC == 1e4).skip);
endif
key{end+1} = sprintf ("| C | energy error, largest over d | %.1e | sanity (h^2) | |", max (arrayfun (@(c) c.run.dE, C(ranC))));
key{end+1} = sprintf ("| D | odeSPVI, sparse & stages against full & \"full\" | %.1e | <= 1e-12 | %s |", ...
                      diffD1, met_text (diffD1 <= 1e-12));
key{end+1} = sprintf ("| D | odeSV, sparse against full Hessian | %.1e | <= 1e-12 | %s |", ...
                      diffD2, met_text (diffD2 <= 1e-12));
md = [md(1:3), {["## The issue's measures\n\n" strjoin(key, "\n") "\n"]}, md(4:end)];

fid = fopen (fullfile (here, "LARGE.md"), "w");
fprintf (fid, "%s\n", strjoin (md, "\n"));
fclose (fid);
printf ("\n%s\n\nwrote %s in %.0f s\n", strjoin (key, "\n"), fullfile (here, "LARGE.md"), t_total);
