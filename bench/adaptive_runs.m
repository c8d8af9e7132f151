## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## adaptive_runs.m -- adaptive steps of the three solvers on Kepler
## (e = 0.6 and 0.9, 10 periods) and the pendulum (50 time units), with
## the Hessian as second output of fcn, and odeSPVI on Kepler e = 0.6
## without it (finite differences): steps, failed steps, callbacks (fcn
## and Hessian, of them with the Hessian) and the end-point error, at
## RelTol = AbsTol from 1e-3 down; then, on two oscillators of
## frequencies 1 and 100, how much adaptive steps of ode45 and the three
## solvers, and fixed steps of odeSV, change the fast one's energy (help
## odeSE quotes it).  Not part of `make bench` (it times nothing); the
## step-size control's comments in src/core/control.c quote it.  Run
## from the top directory after make:
##
##   octave-cli --path inst:src bench/adaptive_runs.m

1;

function [dy, ddy] = kepler (t, y)
  q = y(1:2);  r = norm (q);
  dy = [y(3:4); -q / r^3];
  if (nargout > 1)
    A = (eye (2) - (3 / r^2) * (q * q.')) / r^3;
    ddy = [A, zeros(2); zeros(2), eye(2)];
  endif
endfunction

function dy = kepler_f (t, y)
  ## one output: the solver's matrices then by finite differences
  dy = kepler (t, y);
endfunction

function [dy, ddy] = pendulum (t, y)
  dy = [y(2); -sin(y(1))];
  if (nargout > 1)
    ddy = [cos(y(1)), 0; 0, 1];
  endif
endfunction

T = 2*pi;
probs = {};
for e = [0.6 0.9]
  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
  ## after whole periods the exact solution is y0 again
  probs(end+1, :) = {sprintf("Kepler e = %.1f", e), @kepler, [0 10*T], y0, y0};
endfor
y0 = probs{1, 4};
probs(end+1, :) = {"Kepler 0.6, FD", @kepler_f, [0 10*T], y0, y0};
yp0 = [0; 1.9];
## reference: (9,8), order 16, at a small fixed step
oref = symplecticset ("TimeStepSize", 1e-3, "Nodes", 8, "Q_DoFs", 9);
[~, yr] = odeSPVI (@pendulum, [0 50], yp0, oref);
probs(end+1, :) = {"pendulum", @pendulum, [0 50], yp0, yr(end, :).'};

solvers = {@odeSPVI, @odeSV, @odeSE};
printf ("%-16s %-8s %7s %7s %7s %8s %7s %10s\n", "problem", "solver", "RelTol", ...
        "steps", "failed", "calls", "Hess", "error");
for i = 1:rows (probs)
  for k = 1:numel (solvers)
    tols = [1e-3 1e-4 1e-6 1e-8 1e-10 1e-12];
    if (k > 1)
      tols = [1e-3 1e-4 1e-6];    # low orders: small steps below that
      if (strfind (probs{i, 1}, "FD"))
        continue;
      endif
    endif
    for tol = tols
      o = odeset ("RelTol", tol, "AbsTol", tol);
      s = solvers{k} (probs{i, 2}, probs{i, 3}, probs{i, 4}, o);
      printf ("%-16s %-8s %7.0e %7d %7d %8d %7d %10.2e\n", probs{i, 1}, ...
              func2str (solvers{k}), tol, s.stats.nsteps, s.stats.nfailed, ...
              s.stats.nfevals + s.stats.npds, s.stats.npds, ...
              norm (s.y(:, end) - probs{i, 5}, Inf));
    endfor
  endfor
endfor

## Two oscillators, H = (p1^2 + q1^2)/2 + (p2^2 + w^2 q2^2)/2 with w = 100,
## the fast one at amplitude 1e-3 (q2), over [0, 100]: the fast
## oscillator's energy E2 over the run relative to its start (1 exact):
## its least and largest value, its value at the end and its largest
## distance from 1, and the end-point error.  Adaptive steps follow the
## phase of the fast oscillation (its local error vanishes twice per
## period), and the step sequence, locked to that phase, drains or pumps
## its energy; a fixed step keeps it (help odeSE, RelTol).
w = 100;
osc2 = @(t, y) [y(3:4, :); -y(1, :); -w^2 * y(2, :)];
y0 = [1; 1e-3; 0; 0];
yex = @(t) [cos(t); 1e-3*cos(w*t); -sin(t); -1e-3*w*sin(w*t)];
E2 = @(y) (y(4, :).^2 + w^2 * y(2, :).^2) / (w^2 * 1e-6);
E2s = @(e) [min(e), max(e), e(end), max(abs (e - 1))];
printf ("\ntwo oscillators (w = 1, 100), [0, 100]: fast energy E2\n");
printf ("%-8s %-26s %7s %7s %9s %9s %9s %9s %10s\n", "solver", ...
        "options", "steps", "failed", "E2 min", "E2 max", "E2 end", ...
        "|E2-1|", "error");
row = "%-8s %-26s %7d %7g %9.2g %9.3g %9.3g %9.2g %10.2e\n";
runs = {"default", 1e-3, 1e-4, 1e-6};
for k = 1:4
  for i = 1:numel (runs)
    if (i == 1)
      o = odeset ();
      what = "default";
    else
      o = odeset ("RelTol", runs{i}, "AbsTol", runs{i});
      what = sprintf ("RelTol = AbsTol = %g", runs{i});
    endif
    if (k == 1)
      s = ode45 (osc2, [0 100], y0, o);
      name = "ode45";
      nfailed = NaN;
    else
      s = solvers{k-1} (osc2, [0 100], y0, o);
      name = func2str (solvers{k-1});
      nfailed = s.stats.nfailed;
    endif
    if (rows (s.y) != 4)
      s.y = s.y.';
    endif
    printf (row, name, what, numel (s.x) - 1, nfailed, E2s (E2 (s.y)), ...
            norm (s.y(:, end) - yex (100), Inf));
  endfor
endfor
for h = [0.01 0.002]
  o = symplecticset ("TimeStepSize", h, "Separable", "on");
  s = odeSV (osc2, [0 100], y0, o);
  printf (row, "odeSV", sprintf ("TimeStepSize = %g", h), s.stats.nsteps, ...
          0, E2s (E2 (s.y)), norm (s.y(:, end) - yex (100), Inf));
endfor
