## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## verlet_mfile.m -- Stormer-Verlet (leapfrog) for separable H as a plain
## Octave loop, two calls of the combined FCN per step as the compiled
## explicit path makes them; the reference of benchmark P4.
##
##   [t, y, ncalls] = verlet_mfile (fcn, tf, y0, h)

function [t, y, ncalls] = verlet_mfile (fcn, tf, y0, h)
  d = numel (y0) / 2;
  N = round (tf / h);
  t = h * (0:N).';
  y = zeros (N+1, 2*d);
  y(1, :) = y0(:).';
  q = y0(1:d);  p = y0(d+1:end);
  f = fcn (0, [q; p]);  ncalls = 1;
  fp = f(d+1:end);
  for k = 1:N
    ph = p + h/2 * fp;
    f = fcn (t(k), [q; ph]);
    q = q + h * f(1:d);
    f = fcn (t(k+1), [q; ph]);
    fp = f(d+1:end);
    p = ph + h/2 * fp;
    ncalls += 2;
    y(k+1, :) = [q; p].';
  endfor
endfunction
