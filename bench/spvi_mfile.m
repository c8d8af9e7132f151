## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## spvi_mfile.m -- the spectral variational integrator in plain Octave, as
## the original m-file stepper did it: the whole system (Legendre modes
## a_0..a_{n-1}, nodal momenta p_1..p_m, q_{k+1}, p_{k+1} per component)
## solved by fsolve with the analytic Jacobian built from the Hessian of H
## given by the second output of FCN, started from the constant guess.
## This is the reference the compiled odeSPVI is measured against.
##
##   [t, y, stats] = spvi_mfile (fcn, tf, y0, h, n, m, tol)
##
## tol (default 1e-13) is fsolve's TolX and TolFun: with its defaults
## (1e-6) the result is off by 1e-2 after one Kepler period.
##
## stats.nfcn and stats.nhess count the calls of FCN with one and with two
## outputs.

function [t, y, stats] = spvi_mfile (fcn, tf, y0, h, n, m, tol)

  global SPVI_MFILE_NFCN SPVI_MFILE_NHESS
  SPVI_MFILE_NFCN = 0;
  SPVI_MFILE_NHESS = 0;

  ## Gauss-Legendre nodes and weights (Golub-Welsch) and Legendre values
  k = 1:m-1;
  [V, Z] = eig (diag (k ./ sqrt (4*k.^2 - 1), 1) + diag (k ./ sqrt (4*k.^2 - 1), -1));
  [z, idx] = sort (diag (Z));
  w = 2 * V(1, idx).'.^2;
  [L, D] = legendre_table (n, z);        # m-by-n values, derivatives
  Lm = (-1).^(0:n-1);  Lp = ones (1, n);  # l_i(-1), l_i(1)

  [C0, B] = patterns (n, m, h, w, L, D, Lm, Lp);
  d = numel (y0) / 2;
  N = round (abs (tf) / h);
  t = h * (0:N).';
  y = zeros (N+1, 2*d);
  y(1, :) = y0(:).';
  ## tolerances tight enough that the result is as accurate as the
  ## compiled solver's (fsolve's defaults leave errors of 1e-2 on Kepler)
  if (nargin < 7)
    tol = 1e-13;
  endif
  opts = optimset ("Jacobian", "on", "TolX", tol, "TolFun", tol);
  for s = 1:N
    q0 = y(s, 1:d);  p0 = y(s, d+1:end);
    x0 = [q0; zeros(n-1, d); repmat(p0, m, 1); q0; p0];
    F = @(x) system (x, fcn, t(s), h, q0, p0, n, m, d, w, z, L, D, Lm, Lp, ...
                     C0, B);
    x = fsolve (F, x0(:), opts);
    x = reshape (x, n + m + 2, d);
    y(s+1, :) = [x(end-1, :), x(end, :)];
  endfor
  stats = struct ("nfcn", SPVI_MFILE_NFCN, "nhess", SPVI_MFILE_NHESS, ...
                  "nsteps", N);
endfunction

function [L, D] = legendre_table (n, z)
  L = zeros (numel (z), n);  D = L;
  L(:, 1) = 1;
  if (n > 1)
    L(:, 2) = z;  D(:, 2) = 1;
  endif
  for i = 2:n-1      # l_i from l_{i-1}, l_{i-2} (degree i)
    L(:, i+1) = ((2*i-1) * z .* L(:, i) - (i-1) * L(:, i-1)) / i;
    D(:, i+1) = D(:, i-1) + (2*i-1) * L(:, i);
  endfor
endfunction

function [R, Jac] = system (x, fcn, t0, h, q0, p0, n, m, d, w, z, L, D, Lm, Lp, C0, B)
  global SPVI_MFILE_NFCN SPVI_MFILE_NHESS
  X = reshape (x, n + m + 2, d);
  A = X(1:n, :);  P = X(n+1:n+m, :);  q1 = X(end-1, :);  p1 = X(end, :);
  Q = L * A;                              # q at the nodes, m-by-d
  fq = zeros (m, d);  fp = zeros (m, d);
  Hs = cell (m, 1);
  for j = 1:m
    tj = t0 + h/2 * (z(j) + 1);
    if (nargout > 1)
      [f, H] = fcn (tj, [Q(j, :), P(j, :)].');
      SPVI_MFILE_NHESS++;
      Hs{j} = reshape (H, 2*d, 2*d);
    else
      f = fcn (tj, [Q(j, :), P(j, :)].');
      SPVI_MFILE_NFCN++;
    endif
    fq(j, :) = f(1:d).';  fp(j, :) = f(d+1:end).';
  endfor
  R1 = D.' * (w .* P) + h/2 * L.' * (w .* fp) + Lm.' * p0 - Lp.' * p1;
  R2 = fq - 2/h * D * A;
  R3 = Lm * A - q0;
  R4 = Lp * A - q1;
  R = [R1; R2; R3; R4];
  R = R(:);
  if (nargout > 1)
    ## unknowns and equations ordered as X(:): row r of component k at
    ## r + (k-1)*(n+m+2).  Block (k, c) of the Jacobian is the constant
    ## part (k == c) plus, at each node j, the entries of Df_j = J*Hess_j
    ## times constant patterns: Jac = kron (I, C0) + sum_j kron (Df blocks,
    ## B_j).
    Jac = kron (eye (d), C0);
    for j = 1:m
      H = Hs{j};
      Aqq = H(d+1:end, 1:d);  Aqp = H(d+1:end, d+1:end);
      Apq = -H(1:d, 1:d);     App = -H(1:d, d+1:end);
      Jac += kron (Apq, B{j, 1}) + kron (App, B{j, 2}) ...
             + kron (Aqq, B{j, 3}) + kron (Aqp, B{j, 4});
    endfor
  endif
endfunction

function [C0, B] = patterns (n, m, h, w, L, D, Lm, Lp)
  NN = n + m + 2;
  C0 = zeros (NN);
  C0(1:n, n+1:n+m) = (w .* D).';      # R1_s / P_j: w_j l_s'(z_j)
  C0(1:n, NN) = -Lp.';                # R1_s / p1
  C0(n+1:n+m, 1:n) = -2/h * D;        # R2_r / a_i
  C0(n+m+1, 1:n) = Lm;                # R3 / a_i
  C0(n+m+2, 1:n) = Lp;                # R4 / a_i
  C0(n+m+2, n+m+1) = -1;              # R4 / q1
  B = cell (m, 4);
  for j = 1:m
    B(j, :) = {zeros(NN), zeros(NN), zeros(NN), zeros(NN)};
    B{j, 1}(1:n, 1:n) = h/2 * w(j) * L(j, :).' * L(j, :);   # dfp/dq
    B{j, 2}(1:n, n+j) = h/2 * w(j) * L(j, :).';             # dfp/dp
    B{j, 3}(n+j, 1:n) = L(j, :);                            # dfq/dq
    B{j, 4}(n+j, n+j) = 1;                                  # dfq/dp
  endfor
endfunction
