## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## demo.m -- the README's demonstration (make demo).
##
## Kepler's problem, eccentricity 0.6, over 100 periods: odeSPVI and odeSV
## with fixed steps against ode45 with tight tolerances.  Prints wall time,
## steps, the largest relative energy error over the run and over its last
## tenth, and the angular momentum error; writes the energy error over time
## to demo-energy.png.
##
## make demo runs it with the development tree's inst/ (the solvers'
## m-files) and src/ (their MEX gateways) on the path; run by hand, it
## adds them itself unless the solvers are there already (pkg load
## symplectic).

1;

if (exist ("__odeSPVI__") != 3)
  top = fileparts (fileparts (mfilename ("fullpath")));
  addpath (fullfile (top, "inst"), fullfile (top, "src"));
endif

function [dy, ddy] = kepler (t, y)
  q = y(1:2);
  r = norm (q);
  dy = [y(3:4); -q / r^3];
  if (nargout > 1)
    ddy = blkdiag ((eye (2) - 3 * (q * q.') / r^2) / r^3, eye (2));
  endif
endfunction

e = 0.6;
y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
periods = 100;
tf = 2*pi*periods;
H = @(y) sum (y(:,3:4).^2, 2) / 2 - 1 ./ sqrt (sum (y(:,1:2).^2, 2));
L = @(y) y(:,1) .* y(:,4) - y(:,2) .* y(:,3);
H0 = H (y0.');  L0 = L (y0.');

## (no space before "(" inside {}: it would split the element in two)
runs = {
  "odeSPVI (4,3), h = T/100", @() odeSPVI(@kepler, [0 tf], y0, ...
        symplecticset("TimeStepSize", 2*pi/100, "Nodes", 3))
  "odeSV, h = T/1000, explicit", @() odeSV(@kepler, [0 tf], y0, ...
        symplecticset("TimeStepSize", 2*pi/1000, "Separable", "on"))
  "ode45, RelTol = 1e-8", @() ode45(@kepler, [0 tf], y0, ...
        odeset("RelTol", 1e-8, "AbsTol", 1e-10))
};

printf ("\nKepler's problem, e = %.1f, %d periods (Octave %s)\n\n", e, ...
        periods, version ());
printf ("%-30s %9s %8s %12s %14s %12s\n", "solver", "time [s]", "steps", ...
        "max |dH/H|", "last 10% |dH/H|", "max |dL/L|");
curves = cell (rows (runs), 2);
for i = 1:rows (runs)
  tic;
  [t, y] = runs{i, 2} ();
  el = toc;
  dH = abs (H (y) - H0) / abs (H0);
  dL = abs (L (y) - L0) / abs (L0);
  last = t >= 0.9 * tf;
  printf ("%-30s %9.2f %8d %12.2e %14.2e %12.2e\n", runs{i, 1}, el, ...
          numel (t) - 1, max (dH), max (dH(last)), max (dL));
  ## the largest error over each period: the envelope of the oscillation
  k = floor (t / (2*pi) - 1e-9) + 1;  k(1) = 1;
  env = accumarray (k, dH, [], @max);
  curves(i, :) = {(1:numel (env)).', max(env, 1e-17)};
endfor
printf ("\nThe symplectic solvers keep the energy error bounded (no drift) and\n");
printf ("the angular momentum at round-off; ode45's energy error grows with time.\n");

## The plot needs a graphics toolkit that can print without a display
## (gnuplot here); without one the table above is the demonstration.
try
  try
    warning ("off", "all", "local");   # the toolkit's advice is not for us here
    graphics_toolkit ("gnuplot");
  catch
  end_try_catch
  fig = figure ("visible", "off");
  for i = 1:rows (runs)
    semilogy (curves{i, 1}, curves{i, 2});
    hold on;
  endfor
  hold off;
  grid on;
  xlabel ("periods");
  ylabel ("max relative energy error per period");
  title ("Kepler, e = 0.6");
  legend (runs(:, 1), "location", "east");
  print (fig, "demo-energy.png", "-dpng", "-r80");
  printf ("\nEnergy error plot written to %s\n", fullfile (pwd, "demo-energy.png"));
catch err
  printf ("\nNo plot (%s)\n", err.message);
end_try_catch
