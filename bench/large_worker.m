## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## large_worker.m -- one run of bench/run_large.m, in its own octave-cli
## process so that its peak memory is its own.  bench/run_large.m starts
## it as
##
##   octave-cli --norc --path "$PWD/inst:$PWD/src:$PWD/bench" bench/large_worker.m \
##       case=fpu d=1000 steps=60 h=0.1 hess=sparse system=auto \
##       tout=steps mintime=1 out=FILE
##
## case:    fpu  -- odeSPVI (Q_DoFs 4, Nodes 3, Vectorized) on a beta FPU
##                  chain (bench/fpu.m's H, with fixed ends);
##          mf   -- odeSPVI (4, 3) on H = |p|^2/2 - (1/d) sum_{i<j}
##                  cos(q_i - q_j), all-to-all: a dense Hessian;
##          ns   -- odeSV (implicit Verlet) on the non-separable
##                  H = sum p_i^2 (1 + q_i^2/4)/2 + the FPU chain's V.
## hess:    sparse or full -- what HamiltonianHessFcn returns (mf: full).
## system:  the NewtonSystem option of odeSPVI (auto, full, stages).
## tout:    steps -- tspan = [0, tf]: a row at every step, no output
##                   times (the plain fixed-step call);
##          mid   -- tspan = [0, tf/2, tf] (default): output times, three
##                   rows, all at step points (steps is made even); for
##                   odeSPVI output times switch on its dense output.
## mintime: the call is repeated (the same call, its output cleared in
##          between) until all calls together took at least mintime
##          seconds (default 0: one call); only the first is measured
##          for memory.
##
## What it does: a warm-up run of the same solver, options and form of
## tspan at d = 10 (4 steps), so that the MEX file and its libraries are
## loaded; then VmHWM is reset to VmRSS (writing 5 to
## /proc/self/clear_refs) and VmRSS and VmHWM are read from
## /proc/self/status; then the timed call, [t, y] = solver (fcn, tspan,
## y0, opts) with TimeStepSize h and steps fixed steps (tf = steps h);
## then VmHWM again; then the repeats, if any, for the time alone.
## Saves the struct res (times, memory, energy error, final state, the
## solver's Stats) to out, in Octave's binary format.
##
## only:    fcn or hess (case fpu) -- no run: after the warm-up, the peak
##          of one call of fcn on 3 states (the 3 nodes of a Newton
##          iteration, Vectorized) or of one call of the Hessian function,
##          measured as above (res.cb = VmHWM after - VmRSS before).

1;

## ------------------------------------------------------------ problems

function Hs = fpu_hs (t, y)
  ## its Hessian, sparse: [K 0; 0 I], K tridiagonal
  d = rows (y) / 2;
  r = diff ([0; y(1:d, 1); 0]);
  k = 1 + 3 * r.^2;                      # V''(r)
  K = spdiags ([[-k(2:end-1); 0], k(1:end-1) + k(2:end), [0; -k(2:end-1)]], ...
               -1:1, d, d);
  Hs = [K, sparse(d, d); sparse(d, d), speye(d)];
endfunction

function H = fpu_hf (t, y)
  ## the same Hessian stored full
  H = full (fpu_hs (t, y));
endfunction

function E = fpu_H (y)
  ## energy of the rows of y
  d = columns (y) / 2;
  q = y(:, 1:d);  p = y(:, d+1:end);
  z = zeros (rows (y), 1);
  r = diff ([z, q, z], 1, 2);
  E = sum (p.^2, 2) / 2 + sum (r.^2 / 2 + r.^4 / 4, 2);
endfunction

function dy = mf_f (t, y)
  ## all-to-all: dV/dq_i = (1/d) sum_j sin(q_i - q_j)
  d = rows (y) / 2;
  q = y(1:d);
  s = sum (sin (q - q.'), 2);
  dy = [y(d+1:end); -(1/d) * s];
endfunction

function H = mf_hf (t, y)
  ## its Hessian, dense, returned full
  d = rows (y) / 2;
  q = y(1:d);
  C = (1/d) * cos (q - q.');
  C(1:d+1:end) = 0;
  Vqq = -C;
  Vqq(1:d+1:end) = sum (C, 2);
  H = [Vqq, zeros(d); zeros(d), eye(d)];
endfunction

function E = mf_H (y)
  d = columns (y) / 2;
  E = zeros (rows (y), 1);
  for k = 1:rows (y)
    q = y(k, 1:d).';
    E(k) = sum (y(k, d+1:end).^2) / 2 ...
           - (sum (sum (cos (q - q.'))) - d) / (2 * d);
  endfor
endfunction

function dy = ns_f (t, y)
  ## H = sum p_i^2 (1 + q_i^2/4)/2 + sum V(r): not separable
  d = rows (y) / 2;
  q = y(1:d);  p = y(d+1:end);
  r = diff ([0; q; 0]);
  F = r + r.^3;
  dy = [p .* (1 + q.^2 / 4); -p.^2 .* q / 4 + F(2:end) - F(1:end-1)];
endfunction

function Hs = ns_hs (t, y)
  ## its Hessian, sparse: [K + diag(p^2/4), diag(p q/2); diag(p q/2),
  ## diag(1 + q^2/4)]
  d = rows (y) / 2;
  q = y(1:d);  p = y(d+1:end);
  r = diff ([0; q; 0]);
  k = 1 + 3 * r.^2;
  B = [[-k(2:end-1); 0], k(1:end-1)+k(2:end)+p.^2/4, [0; -k(2:end-1)]];
  K = spdiags (B, -1:1, d, d);
  D = spdiags (p .* q / 2, 0, d, d);
  P = spdiags (1 + q.^2 / 4, 0, d, d);
  Hs = [K, D; D, P];
endfunction

function H = ns_hf (t, y)
  H = full (ns_hs (t, y));
endfunction

function E = ns_H (y)
  d = columns (y) / 2;
  q = y(:, 1:d);  p = y(:, d+1:end);
  z = zeros (rows (y), 1);
  r = diff ([z, q, z], 1, 2);
  E = sum (p.^2 .* (1 + q.^2 / 4), 2) / 2 + sum (r.^2 / 2 + r.^4 / 4, 2);
endfunction

## ------------------------------------------------------------ the runs

function v = proc_bytes (key)
  ## a line of /proc/self/status (kB) in bytes
  s = fileread ("/proc/self/status");
  v = 1024 * str2double (regexp (s, [key ":\\s*(\\d+)"], "tokens", "once"){1});
endfunction

function ok = reset_hwm ()
  ## VmHWM := VmRSS (Linux; false where it cannot be done)
  ok = false;
  fid = fopen ("/proc/self/clear_refs", "w");
  if (fid >= 0)
    ok = fprintf (fid, "5") == 1;
    ok = (fclose (fid) == 0) && ok;
  endif
endfunction

function [solver, f, hf, Hfun, y0, o] = setup (cas, d, h, hess, sys)
  i = (1:d).';
  switch (cas)
    case "fpu"
      ## bench/fpu.m, asked for f alone (Vectorized: the columns of y)
      solver = @odeSPVI;  f = @fpu;  Hfun = @fpu_H;
      hf = merge (strcmp (hess, "full"), {@fpu_hf}, {@fpu_hs}){1};
      y0 = [0.2 * sin(1.3 * i); 0.2 * cos(0.7 * i)];
      o = symplecticset ("TimeStepSize", h, "Q_DoFs", 4, "Nodes", 3, ...
                         "Vectorized", "on", "HamiltonianHessFcn", hf);
    case "mf"
      solver = @odeSPVI;  f = @mf_f;  Hfun = @mf_H;  hf = @mf_hf;
      y0 = [linspace(-1, 1, d).'; 0.1 * cos(i)];
      o = symplecticset ("TimeStepSize", h, "Q_DoFs", 4, "Nodes", 3, ...
                         "HamiltonianHessFcn", hf);
    case "ns"
      solver = @odeSV;  f = @ns_f;  Hfun = @ns_H;
      hf = merge (strcmp (hess, "full"), {@ns_hf}, {@ns_hs}){1};
      y0 = [0.2 * sin(1.3 * i); 0.2 * cos(0.7 * i)];
      o = symplecticset ("TimeStepSize", h, "HamiltonianHessFcn", hf);
    otherwise
      error ("large_worker: unknown case %s", cas);
  endswitch
  o.Stats = "on";
  if (strcmp (func2str (solver), "odeSPVI"))
    o = symplecticset (o, "NewtonSystem", sys);
  endif
endfunction

## ------------------------------------------------------------ main

a = struct ("case", "fpu", "d", "100", "steps", "10", "h", "0.1", ...
            "hess", "sparse", "system", "auto", "tout", "mid", ...
            "mintime", "0", "only", "", "out", "");
for k = 1:numel (argv ())
  kv = strsplit (argv (){k}, "=");
  a.(kv{1}) = strjoin (kv(2:end), "=");
endfor
d = str2double (a.d);  n = str2double (a.steps);  h = str2double (a.h);
mintime = str2double (a.mintime);
switch (a.tout)
  case "steps"
    tsp = @(n) [0, n*h];                 # a row at every step
  case "mid"
    n = 2 * ceil (n / 2);                # tf/2 a step point
    tsp = @(n) [0, n/2*h, n*h];
  otherwise
    error ("large_worker: unknown tout %s", a.tout);
endswitch

## warm-up: the MEX file, its libraries and the m-files loaded
[solver, f, hf, Hfun, y0, o] = setup (a.case, 10, h, a.hess, a.system);
tspan = tsp (4);
evalc ("[t, y] = solver (f, tspan, y0, o);");
clear t y solver f hf Hfun y0 o

## the m-file callbacks alone (only=fcn or only=hess, case fpu): no run;
## after the warm-up, the peak of one call, measured the same way, in a
## process that holds no array of size d yet
if (! isempty (a.only))
  [solver, f, hf, Hfun, y0, o] = setup (a.case, d, h, a.hess, a.system);
  Y = repmat (y0, 1, 3);                 # fcn on 3 states: the 3 nodes of
  tt = zeros (1, 3);                     # a Newton iteration, Vectorized
  res = struct ("case", a.case, "d", d, "only", a.only);
  res.reset = reset_hwm ();
  res.rss0 = proc_bytes ("VmRSS");
  if (strcmp (a.only, "fcn"))
    dy = f (tt, Y);
  else
    H = hf (0, y0);
  endif
  res.hwm1 = proc_bytes ("VmHWM");
  res.cb = res.hwm1 - res.rss0;
  if (! isempty (a.out))
    save ("-binary", a.out, "res");
  endif
  printf ("worker %s d=%d callback %s alone: peak-rss %.1f MB\n", a.case, d, ...
          a.only, res.cb / 2^20);
  return;
endif


[solver, f, hf, Hfun, y0, o] = setup (a.case, d, h, a.hess, a.system);
tspan = tsp (n);
res.reset = reset_hwm ();
res.rss0 = proc_bytes ("VmRSS");
res.hwm0 = proc_bytes ("VmHWM");
tic;
stats = evalc ("[t, y] = solver (f, tspan, y0, o);");
res.time1 = toc;
res.hwm1 = proc_bytes ("VmHWM");

res.case = a.case;  res.d = d;  res.steps = n;  res.h = h;
res.hess = a.hess;  res.system = a.system;  res.tout = a.tout;
res.tend = t(end);
res.reached = abs (t(end) - n * h) <= 1e-9 * n * h;
res.outbytes = 8 * (numel (t) + numel (y));
E = Hfun ([y0.'; y]);
res.dE = max (abs (E(2:end) - E(1))) / abs (E(1));
res.yend = y(end, :);
res.stats = stats;
res.nrows = rows (y);
clear t y E

## the same call again, for the time alone
times = res.time1;
while (sum (times) < mintime && numel (times) < 1000)
  tic;
  evalc ("[t, y] = solver (f, tspan, y0, o);");
  times(end+1) = toc;
  clear t y
endwhile
res.calls = numel (times);
res.time = sum (times);
res.per_step = res.time / (res.calls * n);
res.per_step_min = min (times) / n;

if (! isempty (a.out))
  save ("-binary", a.out, "res");
endif
printf ("worker %s d=%d steps=%d hess=%s system=%s tout=%s: %d call(s), %.3f s, %.4g s/step, peak-rss %.1f MB, dE %.2e\n", ...
        a.case, d, n, a.hess, a.system, a.tout, res.calls, res.time, res.per_step, ...
        (res.hwm1 - res.rss0) / 2^20, res.dE);
