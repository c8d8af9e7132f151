## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## fpu.m -- a beta Fermi-Pasta-Ulam chain of d unit masses with fixed ends:
## H = sum p_i^2/2 + sum_{i=0}^{d} V(q_{i+1} - q_i), q_0 = q_{d+1} = 0,
## V(r) = r^2/2 + beta r^4/4, beta = 1.  Returns Hamilton's equations and,
## as a second output, the Hessian of H (2d-by-2d, sparse pattern stored
## full).  Vectorized: y may hold several states as columns.
##
##   [dy, hess] = fpu (t, y)

function [dy, hess] = fpu (t, y)
  d = rows (y) / 2;
  q = y(1:d, :);  p = y(d+1:end, :);
  z = zeros (1, columns (y));
  r = diff ([z; q; z]);                  # d+1 bonds
  F = r + r.^3;                          # V'(r)
  dy = [p; F(2:end, :) - F(1:end-1, :)];
  if (nargout > 1)
    k = 1 + 3 * r(:, 1).^2;               # V''(r)
    K = diag (k(1:end-1) + k(2:end)) - diag (k(2:end-1), 1) - diag (k(2:end-1), -1);
    hess = blkdiag (K, eye (d));
  endif
endfunction
