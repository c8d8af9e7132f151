## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## yoshida4_mfile.m -- the 4th-order triple jump of Stormer-Verlet steps
## (H. Yoshida, Phys. Lett. A 150 (1990) 262) for separable H as a plain
## Octave loop: three kick-drift-kick Verlet steps of sizes g1 h, g0 h,
## g1 h, g1 = 1 / (2 - 2^(1/3)), g0 = 1 - 2 g1, the force of the end of
## one stage reused at the start of the next, as the compiled explicit
## path makes its calls; the reference of bench/run_methods.m (c).
##
##   [t, y, ncalls] = yoshida4_mfile (fcn, tf, y0, h)
##   [t, y, ncalls] = yoshida4_mfile (fcn, tf, y0, h, "secondorder")
##
## First-order form (as odeSV with Separable "on"): fcn (t, [q; p]) =
## [dH/dp; -dH/dq], two calls per stage (the drift, the kick), 6 per step.
## "secondorder" (as SecondOrder "on"): a = fcn (t, q), y = [q; v], one
## call per stage, 3 per step.

function [t, y, ncalls] = yoshida4_mfile (fcn, tf, y0, h, form)
  so = nargin > 4 && strcmpi (form, "secondorder");
  g1 = 1 / (2 - 2^(1/3));
  g = h * [g1, 1 - 2*g1, g1];                 # the stages' step sizes
  c = [0, cumsum(g)];                         # their starts in the step
  d = numel (y0) / 2;
  N = round (tf / h);
  t = h * (0:N).';
  y = zeros (N+1, 2*d);
  y(1, :) = y0(:).';
  q = y0(1:d);  p = y0(d+1:end);
  if (so)
    a = fcn (0, q);  ncalls = 1;
    for k = 1:N
      for i = 1:3
        p = p + g(i)/2 * a;
        q = q + g(i) * p;
        a = fcn (t(k) + c(i+1), q);
        p = p + g(i)/2 * a;
      endfor
      ncalls += 3;
      y(k+1, :) = [q; p].';
    endfor
  else
    f = fcn (0, [q; p]);  ncalls = 1;
    fp = f(d+1:end);
    for k = 1:N
      for i = 1:3
        ph = p + g(i)/2 * fp;
        f = fcn (t(k) + c(i), [q; ph]);
        q = q + g(i) * f(1:d);
        f = fcn (t(k) + c(i+1), [q; ph]);
        fp = f(d+1:end);
        p = ph + g(i)/2 * fp;
      endfor
      ncalls += 6;
      y(k+1, :) = [q; p].';
    endfor
  endif
endfunction
