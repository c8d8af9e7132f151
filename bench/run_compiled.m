## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## run_compiled.m -- compiled FCNs (symhamiltonian, symcompile) against
## Octave FCNs of the same formulas, the same solver and options, in one
## process run; writes bench/COMPILED.md.  `make bench` runs it with
## inst/, src/ and bench/ on the path, after bench/CORE.md is written.
##
##  K1  odeSV, Separable, Kepler (e = 0.05, h = 2 pi/100): 1e6 steps
##      compiled, fewer with the Octave FCN;
##  K2  odeSPVI (4, 3), the same Kepler, fixed step, Newton on the
##      Hessian; and the compiled run against bench/CORE.md's C-callback
##      step (the core alone);
##  S1  odeSV, Method "kahanli8", SecondOrder, the outer solar system
##      (bench/outer_solar.m, h = 100 days), and bench/kahanli8_loop.c,
##      the same method as a plain C loop (-O2);
##  E1  an ensemble of 1000 Kepler members (e = 0.05 .. 0.6), odeSPVI
##      (4, 3), Vectorized, 100 steps each: the compiled batch's time per
##      member-step against a single Octave-FCN Vectorized run's step;
##  F1  an FPU chain of d = 1e4 (symcompile of tests/compiled/fpu.c),
##      odeSPVI with the sparse Hessian, fixed step 0.1;
##  G1  symhamiltonian of Kepler: first call (generate and compile, in an
##      empty cache) and a second call; G2 the outer solar system's H,
##      first call.
##
## Times are wall clock per step, the median of 3 calls made in turns
## (the machine is shared); the slow Octave-FCN runs take fewer steps.
## About 2 minutes.  Benchmarks are not tests: nothing here asserts.

1;

function [dy, H] = kep_oct (t, y, mu)
  ## Kepler, the Hessian written out as the second output
  q = y(1:2, :);
  r = sqrt (q(1,:) .* q(1,:) + q(2,:) .* q(2,:));
  dy = [y(3:4, :); -mu * q ./ (r .* r .* r)];
  if (nargout > 1)
    q = q(:, 1);  r = r(1);
    A = mu * (eye (2) - (3 / r^2) * (q * q.')) / r^3;
    H = [A(1,1), A(1,2), 0, 0; A(2,1), A(2,2), 0, 0; 0, 0, 1, 0; 0, 0, 0, 1];
  endif
endfunction

function dy = kep_cols (t, y, mu)
  ## Kepler for the columns of y (Vectorized), as bench/kepler_cols.m
  z = y.';
  x = z(:,1);  v = z(:,2);
  r2 = x .* x + v .* v;
  r3 = r2 .* sqrt (r2) / mu;
  dy = [z(:,3), z(:,4), -x ./ r3, -v ./ r3].';
endfunction

function [dy, H] = fpu_oct (t, y, beta)
  d = numel (y) / 2;
  r = diff ([0; y(1:d); 0]);
  dy = [y(d+1:end); diff(r + beta * r .* r .* r)];
  if (nargout > 1)
    k = 1 + 3 * beta * r .* r;
    i = (1:d)';
    H = sparse ([i; i(2:end); i(1:end-1); d + i], [i; i(1:end-1); i(2:end); d + i],
                [k(1:d) + k(2:d+1); -k(2:d); -k(2:d); ones(d, 1)], 2*d, 2*d);
  endif
endfunction

function t = med_turns (fs, n)
  ## the median time of n calls of each of fs, called in turns
  T = zeros (n, numel (fs));
  for i = 1:n
    for j = 1:numel (fs)
      tic;
      r = fs{j} ();
      T(i, j) = toc;
    endfor
  endfor
  t = median (T, 1);
endfunction

function r = solve (s, f, tspan, y0, o, varargin)
  ## one output: with none the solvers would plot
  r = s (f, tspan, y0, o, varargin{:});
endfunction

function y0 = kep_y0 (e)
  y0 = [1 - e; 0 * e; 0 * e; sqrt((1 + e) ./ (1 - e))];
endfunction

function s = us (x)
  s = sprintf ("%.3g us", 1e6 * x);
endfunction

here = fileparts (mfilename ("fullpath"));
top = fileparts (here);
out = fullfile (here, "COMPILED.md");
R = 3;                                   # repeats, the median taken
rows_ = {};
notes = {};
cache0 = getenv ("XDG_CACHE_HOME");
have_sym = ! isempty (pkg ("list", "symbolic"));
if (have_sym)
  pkg load symbolic
  syms q1 q2 p1 p2 mu
  kep = symhamiltonian ((p1^2 + p2^2) / 2 - mu / sqrt (q1^2 + q2^2),
                        [q1 q2], [p1 p2], "Parameters", mu);
  kname = "symhamiltonian";
else
  kep = symcompile (fullfile (top, "tests", "compiled", "kepler.c"));
  kname = "symcompile (tests/compiled/kepler.c)";
  notes{end+1} = "No symbolic package: Kepler by symcompile of tests/compiled/kepler.c; S1, G1, G2 not run.";
endif
T = 2 * pi;  h = T / 100;  y0 = kep_y0 (0.05);

## ---------------------------------------------------------------- K1
o1 = symplecticset ("TimeStepSize", h, "Separable", "on");
nc = 1e6;  no = 2e4;
t = med_turns ({@() solve(@odeSV, @kep_oct, [0 no*h], y0, o1, 1), ...
                @() solve(@odeSV, kep, [0 nc*h], y0, o1, 1)}, R);
to = t(1) / no;  tc = t(2) / nc;
rows_(end+1, :) = {"K1 odeSV Separable, Kepler, fixed step", us(to), us(tc), ...
                   sprintf("%.0f", to / tc), ">= 100", met_text(to / tc >= 100)};
printf ("K1: Octave %s, compiled %s per step\n", us (to), us (tc));

## ---------------------------------------------------------------- K2
o2 = symplecticset ("TimeStepSize", h, "Nodes", 3, "Q_DoFs", 4);
nc = 2e4;  no = 1000;
a = odeSPVI (kep, [0 100*h], y0, o2, 1);
b = odeSPVI (@kep_oct, [0 100*h], y0, o2, 1);
agree = max (abs (a.y(:) - b.y(:)));
t = med_turns ({@() solve(@odeSPVI, @kep_oct, [0 no*h], y0, o2, 1), ...
                @() solve(@odeSPVI, kep, [0 nc*h], y0, o2, 1)}, R);
to = t(1) / no;  tc = t(2) / nc;
rows_(end+1, :) = {"K2 odeSPVI (4,3), Kepler, fixed step, the Hessian", us(to), us(tc), ...
                   sprintf("%.0f", to / tc), ">= 30", met_text(to / tc >= 30)};
printf ("K2: Octave %s, compiled %s per step (runs agree to %.1e)\n", us (to), us (tc), agree);
## against the core alone: CORE.md's times are the least of 5 runs, so
## the compiled run's is here too; its row "f and Df" is the same
## configuration (f and the exact Df by callbacks, no batch form)
tl = Inf;
for i = 1:5
  tic;
  r = solve (@odeSPVI, kep, [0 nc*h], y0, o2, 1);
  tl = min (tl, toc);
endfor
tl /= nc;
txt = fileread (fullfile (here, "CORE.md"));
for row = {{"one run, f and Df", "C, f and Df"}, {"one run", "C, f batch, FD Df"}}
  core = NaN;
  tok = regexp (txt, ['\| ' row{1}{1} ' \| auto \| ([0-9.]+) \|'], "tokens", "once");
  if (! isempty (tok))
    core = 1e-6 * str2double (tok{1});
  endif
  rows_(end+1, :) = {sprintf("K2' the same (least of 5), against CORE.md's step (%s)", row{1}{2}), ...
                     "-", sprintf("%s (C: %s)", us(tl), us(core)), sprintf("%.2f", tl / core), ...
                     "<= 1.5", met_text(tl / core <= 1.5)};
endfor

## ---------------------------------------------------------------- S1
if (have_sym)
  S = outer_solar ();
  q = sym ("q", [18 1]);  p = sym ("p", [18 1]);  ms = sym ("m", [6 1]);
  syms G
  H = sum (p.^2 ./ kron (ms, [1; 1; 1])) / 2;
  for i = 1:5
    for j = i+1:6
      dq = q(3*j-2:3*j) - q(3*i-2:3*i);
      H -= G * ms(i) * ms(j) / sqrt (sum (dq.^2));
    endfor
  endfor
  ## G2: the first call, in an empty cache (the median of R)
  tg2 = zeros (1, R);
  for k = 1:R
    setenv ("XDG_CACHE_HOME", tempname ());
    tic;
    sol = symhamiltonian (H, q, p, "Parameters", [ms; G]);
    tg2(k) = toc;
  endfor
  setenv ("XDG_CACHE_HOME", cache0);
  sol = symhamiltonian (H, q, p, "Parameters", [ms; G]);
  par = [S.m, S.G];
  hs = 100;  nc = 1e5;  no = 1000;
  o3 = symplecticset ("TimeStepSize", hs, "Method", "kahanli8", "SecondOrder", "on");
  yv = [S.q0; S.v0];
  ## the loop, built as the gateways are
  cc = strtrim (mkoctfile ("-p", "CC"));
  exe = [tempname() "-kahanli8"];
  [st, msg] = system (sprintf ("%s -std=c99 -O2 -o '%s' '%s' -lm 2>&1", cc, exe,
                               fullfile (here, "kahanli8_loop.c")));
  if (st)
    error ("run_compiled: cannot build kahanli8_loop.c: %s", msg);
  endif
  acc = @(t, q, pr) S.acc (t, q);        # the masses as S has them
  ## the end point alone (and the midpoint), as the loop keeps nothing
  t = med_turns ({@() solve(@odeSV, acc, [0 no*hs/2 no*hs], yv, o3, par), ...
                  @() solve(@odeSV, sol, [0 nc*hs/2 nc*hs], yv, o3, par)}, R);
  to = t(1) / no;  tc = t(2) / nc;
  [st, txt] = system (sprintf ("'%s' %g %d %d", exe, hs, nc, R));
  unlink (exe);
  v = sscanf (txt, "%g");
  tl = 1e-6 * v(1);
  [~, yc] = odeSV (sol, [0 nc*hs/2 nc*hs], yv, o3, par);
  dl = max (abs (yc(end, 1:18)' - v(2:19))) / max (abs (v(2:19)));
  rows_(end+1, :) = {"S1 odeSV kahanli8 SecondOrder, outer solar system", us(to), us(tc), ...
                     sprintf("%.0f", to / tc), "-", "-"};
  rows_(end+1, :) = {"S1' the same, compiled against the plain C loop (bench/kahanli8_loop.c)", ...
                     "-", sprintf("%s (loop: %s)", us(tc), us(tl)), sprintf("%.2f", tc / tl), ...
                     "<= 2", met_text(tc / tl <= 2)};
  notes{end+1} = sprintf (["S1: %d steps of %g days, output at the midpoint and the end only " ...
                           "(every step's output adds about 1.3 us a step); the solver's and the loop's positions " ...
                           "after them differ by %.1e relative (the same method, a force " ...
                           "summed in another order)."], nc, hs, dl);
  printf ("S1: Octave %s, compiled %s, loop %s per step (end points %.1e apart)\n",
          us (to), us (tc), us (tl), dl);
endif

## ---------------------------------------------------------------- E1
K = 1000;  ns = 100;  no = 1000;
Y0 = kep_y0 (linspace (0.05, 0.6, K));
oe = symplecticset (o2, "Ensemble", "on", "Vectorized", "on");
ov = symplecticset (o2, "Vectorized", "on");
t = med_turns ({@() solve(@odeSPVI, @kep_cols, [0 no*h], y0, ov, 1), ...
                @() solve(@odeSPVI, kep, [0 ns*h], Y0, oe, 1)}, R);
to = t(1) / no;  tc = t(2) / (K * ns);
rows_(end+1, :) = {"E1 odeSPVI (4,3) ensemble, 1000 Kepler members, compiled batch (per member-step); Octave: one Vectorized run", ...
                   us(to), us(tc), sprintf("%.0f", to / tc), ">= 50", met_text(to / tc >= 50)};
printf ("E1: Octave %s per step, compiled %s per member-step\n", us (to), us (tc));

## ---------------------------------------------------------------- F1
d = 1e4;
fpu = symcompile (sprintf ("#define FPU_D %d\n%s", d,
                           fileread (fullfile (top, "tests", "compiled", "fpu.c"))));
yf = [0.1 * sin(pi * (1:d)' / (d + 1)); zeros(d, 1)];
of = symplecticset ("TimeStepSize", 0.1);
nc = 100;  no = 20;
a = odeSPVI (fpu, [0 20*0.1], yf, of, 1);
b = odeSPVI (@fpu_oct, [0 20*0.1], yf, of, 1);
agree = max (abs (a.y(:) - b.y(:))) / max (abs (b.y(:)));
t = med_turns ({@() solve(@odeSPVI, @fpu_oct, [0 no*0.1], yf, of, 1), ...
                @() solve(@odeSPVI, fpu, [0 nc*0.1], yf, of, 1)}, R);
to = t(1) / no;  tc = t(2) / nc;
rows_(end+1, :) = {sprintf("F1 odeSPVI (%d,%d), FPU chain d = 1e4 (symcompile), sparse Hessian", a.Q_DoFs, a.Nodes), ...
                   us(to), us(tc), sprintf("%.1f", to / tc), ">= 10", met_text(to / tc >= 10)};
printf ("F1: Octave %s, compiled %s per step (runs agree to %.1e)\n", us (to), us (tc), agree);

## ---------------------------------------------------------------- G1, G2
if (have_sym)
  syms q1 q2 p1 p2 mu
  Hk = (p1^2 + p2^2) / 2 - mu / sqrt (q1^2 + q2^2);
  t1 = t2 = zeros (1, R);
  for k = 1:R
    setenv ("XDG_CACHE_HOME", tempname ());
    tic;
    f = symhamiltonian (Hk, [q1 q2], [p1 p2], "Parameters", mu);
    t1(k) = toc;
    tic;
    f = symhamiltonian (Hk, [q1 q2], [p1 p2], "Parameters", mu);
    t2(k) = toc;
  endfor
  setenv ("XDG_CACHE_HOME", cache0);
  rows_(end+1, :) = {"G1 symhamiltonian, Kepler, first call (generate and compile)", "-", ...
                     sprintf("%.2f s", median (t1)), "-", "<= 5 s", met_text(median (t1) <= 5)};
  rows_(end+1, :) = {"G1' the same, a second call (cached)", "-", ...
                     sprintf("%.3f s", median (t2)), "-", "<= 0.1 s", met_text(median (t2) <= 0.1)};
  rows_(end+1, :) = {"G2 symhamiltonian, outer solar system (18 dof, 7 parameters), first call", "-", ...
                     sprintf("%.2f s", median (tg2)), "-", "<= 30 s", met_text(median (tg2) <= 30)};
  printf ("G1: first %.2f s, cached %.3f s; G2: first %.2f s\n", median (t1), median (t2), median (tg2));
endif

## ---------------------------------------------------------------- table
fid = fopen (out, "w");
fprintf (fid, "# Compiled FCNs against Octave FCNs\n\n");
fprintf (fid, "Written by bench/run_compiled.m (`make bench`), %s, Octave %s, %d cores.\n",
         datestr (now (), "yyyy-mm-dd HH:MM"), OCTAVE_VERSION, nproc ());
fprintf (fid, ["Wall time per step, the median of %d calls made in turns on a shared machine; " ...
               "the same solver, options and formulas on both sides; the Octave-FCN runs take " ...
               "fewer steps (time per step is what is compared).  Kepler by %s.\n\n"], R, kname);
fprintf (fid, "| case | Octave fcn, per step | compiled, per step | ratio | target | met? |\n");
fprintf (fid, "|---|---|---|---|---|---|\n");
for i = 1:rows (rows_)
  fprintf (fid, "| %s |\n", strjoin (rows_(i, :), " | "));
endfor
if (! isempty (notes))
  fprintf (fid, "\n%s\n", strjoin (notes, "\n\n"));
endif
fclose (fid);
printf ("written %s\n", out);
