## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## p3_run.m -- the run that bench/p3_profile.sh samples: odeSPVI (4,3),
## h = T/100, on Kepler (e = 0.6) over 30 periods, as in P1-P3 of
## bench/run_benchmarks.m.

1;

function [dy, ddy] = kepler (t, y)
  q = y(1:2, :);
  r = sqrt (sum (q.^2, 1));
  dy = [y(3:4, :); -q ./ r.^3];
  if (nargout > 1)
    q = q(:, 1);  r = r(1);
    A = (eye (2) - (3 / r^2) * (q * q.')) / r^3;
    ddy = [A(1,1), A(1,2), 0, 0; A(2,1), A(2,2), 0, 0; 0, 0, 1, 0; 0, 0, 0, 1];
  endif
endfunction

e = 0.6;
y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
T = 2*pi;
opts = symplecticset ("TimeStepSize", T/100, "Nodes", 3, "Q_DoFs", 4);
sol = odeSPVI (@kepler, [0 30*T], y0, opts);
printf ("p3_run: %d steps, %.2f calls per step\n", sol.stats.nsteps, ...
        (sol.stats.nfevals + sol.stats.npds) / sol.stats.nsteps);
