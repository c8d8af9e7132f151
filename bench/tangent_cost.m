## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## tangent_cost -- what TangentMap costs a step: odeSV on Kepler (e = 0.5,
## 200 steps a period, 2e4 steps), explicit fixed Verlet steps, without
## it and with the full Phi (the Hessian as FCN's second output, or by
## central differences of a one-output FCN) or one deviation vector; the
## least CPU time of a few runs each.  Run from the source tree:
##   octave-cli --eval "addpath ('inst', 'src', 'bench'); tangent_cost"
function tangent_cost (reps = 5)
  e = 0.5;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
  h = 2*pi/200;  N = 2e4;
  o = symplecticset ("TimeStepSize", h, "TimeStepNumber", N,
                     "Separable", "on");
  ot = symplecticset (o, "TangentMap", "on");
  ov = symplecticset (o, "TangentMap", [1; 0; 0; 0]);
  runs = {"none", @symplectic_kepler, o; ...
          "Phi, Hessian from FCN", @symplectic_kepler, ot; ...
          "Phi, central differences", @kepler_cols, ot; ...
          "one vector, Hessian from FCN", @symplectic_kepler, ov};
  t = zeros (rows (runs), 1);
  for k = 1:rows (runs)
    best = Inf;
    for r = 1:reps
      c0 = cputime ();
      sol = odeSV (runs{k,2}, [0, N*h], y0, runs{k,3});
      best = min (best, cputime () - c0);
    endfor
    t(k) = best;
    ## two-output calls (f and the Hessian) count in npds, not nfevals
    printf ("%-30s %7.2f us a step, %5.2f x none, %d calls of FCN\n",
            runs{k,1}, 1e6 * best / N, best / t(1),
            sol.stats.nfevals + sol.stats.npds);
  endfor
endfunction
