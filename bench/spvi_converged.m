## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## spvi_converged (SYS, NM, N) -- odeSPVI (5,4), Vectorized, on Kepler
## e = 0.6 over 200 periods in N fixed steps, NewtonSystem SYS and
## NewtonMatrix NM: the end point's distance from y0, the largest energy
## error, Newton corrections and calls of FCN per step (bench/NOTES.md).
function spvi_converged (sys, nm, N, periods, nodes, qd)
  if nargin < 4, periods = 200; end
  if nargin < 5, nodes = 4; end
  if nargin < 6, qd = 5; end
  e = 0.6; y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
  f = @(t, y) [y(3,:); y(4,:); -y(1,:)./(y(1,:).^2+y(2,:).^2).^1.5; -y(2,:)./(y(1,:).^2+y(2,:).^2).^1.5];
  T = 2*pi*periods;
  o = symplecticset ("Q_DoFs", qd, "Nodes", nodes, "Vectorized", "on", "NewtonSystem", sys, "NewtonMatrix", nm, "TimeStepNumber", N);
  tic; sol = odeSPVI (f, [0 T], y0, o); tm = toc;
  y = sol.y(:, end);
  H = @(y) (y(3,:).^2+y(4,:).^2)/2 - 1./sqrt(y(1,:).^2+y(2,:).^2);
  E = H(sol.y); H0 = H(y0);
  s = sol.stats;
  printf ("%s %s N=%d: err %.3g  maxdE %.3g  newton/step %.4f  fevals/step %.4f  (%.1fs)\n", sys, nm, N, norm (y - y0), max (abs (E - H0)), s.nnewton / N, s.nfevals / N, tm);
end
