## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## -*- texinfo -*-
## @deftypefn {} {@var{runs} =} regression_runs ()
## The fixed set of runs whose outputs tests/test_regression.m compares
## with those recorded in tests/regression.txt.gz: the three solvers, fixed
## and adaptive steps, events, Vectorized, every source of Newton's
## matrix, Separable, output times and Refine, and the FPU chain of
## d = 10.  Each run is a struct with fields name, solver (a handle),
## fcn, tspan, y0, opts, nout (the outputs asked for: 2, 5, or 1 for
## sol), fixed (true when its steps are fixed) and exact (true when no
## BLAS, LAPACK or libm call enters its results: then compared to the
## bit; tests/test_regression.m says which runs those are).
##
## tests/record_regression.m writes the reference; record it anew only
## for a change that is meant to change the results, and say why in the
## commit.
## @end deftypefn

function runs = regression_runs ()

  e = 0.6;
  kep0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
  T = 2*pi;
  fix = @(varargin) symplecticset ("TimeStepSize", T/50, varargin{:});
  ## adaptive tolerances for a few hundred steps of each order
  tols = {1e-4, 1e-6, 1e-8};
  adatol = @(i, varargin) symplecticset ("RelTol", tols{i},
                                         "AbsTol", tols{i} / 100,
                                         "Refine", 1, varargin{:});
  tout = linspace (0, 4*T, 11);
  runs = struct ("name", {}, "solver", {}, "fcn", {}, "tspan", {},
                 "y0", {}, "opts", {}, "nout", {}, "fixed", {},
                 "exact", {});

  ## The three solvers on Kepler e = 0.6: fixed and adaptive, finite
  ## differences (fcn of one output), the Hessian as second output
  solvers = {@odeSE, @odeSV, @odeSPVI};
  for i = 1:3
    s = solvers{i};
    nm = func2str (s);
    ada = @(varargin) adatol (i, varargin{:});
    runs(end+1) = run (["fixed fd " nm], s, @kepler1, tout, kep0, fix (), 2);
    runs(end+1) = run (["fixed hess2 " nm], s, @kepler, tout, kep0,
                       fix (), 2);
    runs(end+1) = run (["adaptive fd " nm], s, @kepler1, [0 T/2], kep0,
                       ada (), 2, false);
    runs(end+1) = run (["adaptive hess2 " nm], s, @kepler, tout, kep0,
                       ada (), 2, false);
    ## the other sources of the matrix
    runs(end+1) = run (["fixed hessfcn " nm], s, @kepler1, tout, kep0,
                       fix ("HamiltonianHessFcn", @kepler_hess), 2);
    runs(end+1) = run (["fixed jacfcn " nm], s, @kepler1, tout, kep0,
                       fix ("Jacobian", @kepler_jac), 2);
    runs(end+1) = run (["fixed jacmatrix " nm], s, @oscillator,
                       linspace (0, 20, 11), [1; 0.5],
                       fix ("Jacobian", [0 1; -4 0]), 2);
    ## events: a terminal one (the pendulum through q = 0 downwards) and
    ## the crossings of y(2) = 0 on Kepler, with step output and sol
    runs(end+1) = run (["fixed events " nm], s, @kepler, [0 4*T], kep0,
                       fix ("Events", @kepler_events), 5);
    runs(end+1) = run (["adaptive events " nm], s, @pendulum, [0 20],
                       [1; 0.5], ada ("Events", @pendulum_events), 5,
                       false);
    runs(end+1) = run (["fixed sol " nm], s, @kepler, [0 T], kep0,
                       fix ("Events", @kepler_events), 1);
    runs(end+1) = run (["adaptive sol " nm], s, @pendulum, [0 5],
                       [1; 0.5], ada (), 1, false);
    ## Refine and an adaptive run backwards
    runs(end+1) = run (["adaptive refine " nm], s, @kepler, [0 T/8], kep0,
                       ada ("Refine", 3), 2, false);
    runs(end+1) = run (["adaptive backwards " nm], s, @kepler, [T 3*T/4],
                       kep0, ada ("MaxStep", 0.1), 2, false);
    ## a non-separable H in 3-D
    runs(end+1) = run (["fixed rot3 " nm], s, @rot3, linspace (0, 10, 6),
                       [1; 0.2; -0.3; 0.1; 0.9; 0.4],
                       symplecticset ("TimeStepSize", 0.05), 2);
    ## FPU chain of d = 10
    runs(end+1) = run (["fixed fpu10 " nm], s, @fpu, linspace (0, 10, 6),
                       fpu_y0 (10), symplecticset ("TimeStepSize", 0.05),
                       2);
    ## a damping the Hessian misses: the dropped matrix source
    runs(end+1) = run (["fixed damped " nm], s, @damped, linspace (0, 5, 6),
                       [1; 0], symplecticset ("TimeStepSize", 0.1,
                       "HamiltonianHessFcn", @oscillator_hess), 2);
  endfor

  ## Separable (explicit) odeSE and odeSV; at fixed steps with an FCN of
  ## elementwise +, -, .*, ./, .^2, .^3, sqrt only (kepler1, fpu) no
  ## BLAS, LAPACK or libm call enters: exact
  for i = 1:2
    s = solvers{i};
    nm = func2str (s);
    ada = @(varargin) adatol (i, varargin{:});
    runs(end+1) = run (["fixed separable " nm], s, @kepler1, tout, kep0,
                       fix ("Separable", "on"), 2, true, true);
    runs(end+1) = run (["adaptive separable " nm], s, @kepler1, [0 T/2],
                       kep0, ada ("Separable", "on"), 2, false);
    runs(end+1) = run (["fixed separable fpu10 " nm], s, @fpu,
                       linspace (0, 10, 6), fpu_y0 (10),
                       symplecticset ("TimeStepSize", 0.05,
                                      "Separable", "on"), 2, true, true);
  endfor

  ## odeSPVI: Vectorized, the matrix kept or new, other pairs
  ada = @(varargin) adatol (3, varargin{:});
  runs(end+1) = run ("fixed vectorized odeSPVI", @odeSPVI, @kepler1, tout,
                     kep0, fix ("Vectorized", "on"), 2);
  runs(end+1) = run ("fixed vectorized kept odeSPVI", @odeSPVI, @kepler1,
                     tout, kep0, fix ("Vectorized", "on",
                                      "NewtonMatrix", "kept"), 2);
  runs(end+1) = run ("adaptive vectorized odeSPVI", @odeSPVI, @kepler1,
                     tout, kep0, ada ("Vectorized", "on"), 2, false);
  runs(end+1) = run ("fixed new odeSPVI", @odeSPVI, @kepler, tout, kep0,
                     fix ("NewtonMatrix", "new"), 2);
  runs(end+1) = run ("fixed vectorized fpu10 odeSPVI", @odeSPVI, @fpu,
                     linspace (0, 10, 6), fpu_y0 (10),
                     symplecticset ("TimeStepSize", 0.05,
                                    "Vectorized", "on"), 2);
  pairs = [2 1; 3 2; 3 3; 4 2; 2 3; 9 8];
  for k = 1:rows (pairs)
    nm = sprintf ("(%d,%d)", pairs(k,1), pairs(k,2));
    o = {"Q_DoFs", pairs(k,1), "Nodes", pairs(k,2)};
    runs(end+1) = run (["fixed pair " nm " odeSPVI"], @odeSPVI, @kepler,
                       tout, kep0, fix (o{:}), 2);
    runs(end+1) = run (["adaptive pair " nm " odeSPVI"], @odeSPVI,
                       @kepler, [0 T/2], kep0, adatol (2, o{:}), 2,
                       false);
  endfor
  ## many nodes at a long step (the predictor's cut of noisy modes)
  runs(end+1) = run ("fixed nodes20 odeSPVI", @odeSPVI, @quartic,
                     linspace (0, 20, 5), [1; 0.5],
                     symplecticset ("TimeStepSize", 1, "Nodes", 20), 2);

endfunction

function r = run (name, solver, fcn, tspan, y0, opts, nout, fixed = true,
                  exact = false)
  r = struct ("name", name, "solver", solver, "fcn", fcn, "tspan", tspan,
              "y0", y0, "opts", opts, "nout", nout, "fixed", fixed,
              "exact", exact);
endfunction

function [dy, ddy] = kepler (t, y)
  q = y(1:2);
  r = sqrt (q.' * q);
  dy = [y(3:4); -q / r^3];
  if (nargout > 1)
    A = (eye (2) - (3 / r^2) * (q * q.')) / r^3;
    ddy = [A, zeros(2); zeros(2), eye(2)];
  endif
endfunction

function dy = kepler1 (t, y)
  ## one output (finite-difference matrices); Vectorized
  q = y(1:2, :);
  r = sqrt (sum (q.^2, 1));
  dy = [y(3:4, :); -q ./ r.^3];
endfunction

function H = kepler_hess (t, y)
  [~, H] = kepler (t, y);
endfunction

function Df = kepler_jac (t, y)
  [~, H] = kepler (t, y);
  Df = [H(3:4, :); -H(1:2, :)];
endfunction

function [v, term, dir] = kepler_events (t, y)
  v = y(2);
  term = 0;
  dir = 0;
endfunction

function dy = pendulum (t, y)
  dy = [y(2); -sin(y(1))];
endfunction

function [v, term, dir] = pendulum_events (t, y)
  ## p through zero (both ways), and q through zero downwards, terminal
  v = [y(2); y(1)];
  term = [0; 1];
  dir = [0; -1];
endfunction

function dy = oscillator (t, y)
  dy = [y(2); -4 * y(1)];
endfunction

function H = oscillator_hess (t, y)
  H = [1 0; 0 1];
endfunction

function dy = damped (t, y)
  ## H = (q^2 + p^2)/2 with the forcing -0.3 p (its dF/dp is not in the
  ## Hessian: Newton then drops it for finite differences)
  dy = [y(2); -y(1) - 0.3 * y(2)];
endfunction

function dy = quartic (t, y)
  ## H = (q^2 + p^2)^2 / 4: a rotation at the rate q^2 + p^2
  s = y(1)^2 + y(2)^2;
  dy = [s * y(2); -s * y(1)];
endfunction

function [dy, ddy] = rot3 (t, y)
  ## H = |p|^2/2 (1 + |q|^2/4) + |q|^4/8 + (q.p)^2/4
  q = y(1:3);  p = y(4:6);  s = q.' * p;  I = eye (3);
  dy = [p * (1 + q.'*q/4) + s*q/2; -(q * (p.'*p)/4 + q * (q.'*q)/2 + s*p/2)];
  if (nargout > 1)
    Hqp = p*q.'/2 + s*I/2 + q*p.'/2;
    ddy = [(p.'*p)/4*I + (q.'*q)/2*I + q*q.' + p*p.'/2, Hqp;
           Hqp.', (1 + q.'*q/4)*I + q*q.'/2];
  endif
endfunction

function [dy, hess] = fpu (t, y)
  ## a beta FPU chain with fixed ends, Vectorized; the Hessian as second
  ## output
  d = rows (y) / 2;
  q = y(1:d, :);  p = y(d+1:end, :);
  z = zeros (1, columns (y));
  r = diff ([z; q; z]);
  F = r + r.^3;
  dy = [p; F(2:end, :) - F(1:end-1, :)];
  if (nargout > 1)
    k = 1 + 3 * r(:, 1).^2;
    K = diag (k(1:end-1) + k(2:end)) - diag (k(2:end-1), 1) ...
        - diag (k(2:end-1), -1);
    hess = blkdiag (K, eye (d));
  endif
endfunction

function y0 = fpu_y0 (d)
  y0 = [sin(pi * (1:d).' / (d + 1)); zeros(d, 1)];
endfunction
