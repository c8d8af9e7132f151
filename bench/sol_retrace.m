## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## A reversible run retraced from its sol (Y0 = sol) against a run back
## from its end point: Kepler e = 0.9, 50 periods, RelTol 1e-4.  Prints
## |y_back(0) - y0|_inf, the steps and the times (bench/NOTES.md).
##   octave-cli --eval "addpath ('inst', 'src'); source ('bench/sol_retrace.m')"

e = 0.9;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];  T = 100*pi;
acc = @(t, q) -q / norm (q)^3;
kep = @(t, y) [y(3:4); -y(1:2) / norm(y(1:2))^3];
base = symplecticset ("StepControl", "reversible", "RelTol", 1e-4);
so = symplecticset (base, "SecondOrder", "on");
sc = symplecticset (so, "CompensatedSummation", "off");
runs = {"odeSV SecondOrder", @odeSV, acc, so;
        "odeSV SecondOrder, sums plain", @odeSV, acc, sc;
        "odeSPVI (4,3)", @odeSPVI, kep, base;
        "odeSPVI (4,3), NewtonTol 1e-16", @odeSPVI, kep, ...
        symplecticset(base, "NewtonTol", 1e-16)};
printf ("%-32s %7s %10s %10s %7s %7s\n", "run", "steps", "from sol", "from end", "fwd s", "back s");
for i = 1:rows (runs)
  [name, solver, f, o] = runs{i, :};
  tic;  sol = solver (f, [0 T], y0, o);  tf = toc;
  tic;  b = solver (f, [T 0], sol);  tb = toc;
  n = solver (f, [T 0], sol.y(:,end), o);
  printf ("%-32s %7d %10.2e %10.2e %7.2f %7.2f\n", name, sol.stats.nsteps,
          norm (b.y(:,end) - y0, Inf), norm (n.y(:,end) - y0, Inf), tf, tb);
endfor
