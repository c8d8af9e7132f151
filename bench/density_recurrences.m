## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## density_recurrences.m -- the choices behind StepControl "reversible"
## (bench/NOTES.md): three time-symmetric recurrences for the step
## density, and how large eps may be.  Run from the top of the tree:
##   octave-cli --path "$PWD/inst:$PWD/src" bench/density_recurrences.m
##
## Part 1, in m-code (Stormer-Verlet on Kepler's problem, 100 periods,
## density rho = |f| / |y|), with h = eps / rho_{n+1/2}:
##   arithmetic: (rho_{n-1/2} + rho_{n+1/2}) / 2 = rho(y_n)   (the package's)
##   geometric:   rho_{n-1/2} rho_{n+1/2} = rho(y_n)^2
##   gradient:    rho_{n+1/2} = rho_{n-1/2} + eps G(y_n), G = (d rho/dt) / rho
##                (Hairer and Soederlind's form: G is d rho / d tau in the
##                time tau of the steps, d tau / dt = rho)
##                (its derivative by central differences here: two more
##                calls of f per step, which a solver cannot afford)
## Part 2, with the package: odeSPVI (4,3) at e = 0.99 with eps above the
## cap of 0.05, reached by scaling the default density down (h = eps /
## rho: a density c times smaller is an eps 1/c times larger).

1;

function a = acc (q)
  a = -q / norm (q)^3;
endfunction

function r = dens (q, v)
  r = norm ([v; acc(q)]) / norm ([q; v]);
endfunction

function g = dlogdens (q, v)
  d = 1e-6;
  g = (log (dens (q + d*v, v + d*acc (q))) ...
       - log (dens (q - d*v, v - d*acc (q)))) / (2*d);
endfunction

function [first, last, nsteps] = verlet_run (e, periods, ep, kind)
  q = [1-e; 0];  v = [0; sqrt((1+e)/(1-e))];
  H = @(q, v) v'*v/2 - 1/norm (q);
  H0 = H (q, v);  T = 2*pi*periods;
  r0 = dens (q, v);
  if (kind == 3)
    z = r0 + ep/2 * dlogdens (q, v);
  else
    z = r0;                     # two trial steps, as the package starts
    for k = 1:2
      h = ep / z;  vh = v + h/2*acc (q);  q1 = q + h*vh;
      v1 = vh + h/2*acc (q1);
      z = ifelse_mean (kind, r0, dens (q1, v1));
    endfor
  endif
  t = 0;  a = acc (q);  nsteps = 0;  first = 0;  last = 0;
  while (t < T)
    h = ep / z;
    vh = v + h/2*a;  q = q + h*vh;  a = acc (q);  v = vh + h/2*a;
    t += h;  nsteps++;
    switch (kind)
      case 1
        z = 2*dens (q, v) - z;
      case 2
        z = dens (q, v)^2 / z;
      case 3
        z = z + ep * dlogdens (q, v);
    endswitch
    if (! (z > 0) || ! isfinite (z))
      first = last = Inf;  return;
    endif
    dh = abs (H (q, v) - H0);
    if (t <= 0.1*T)
      first = max (first, dh);
    elseif (t >= 0.9*T)
      last = max (last, dh);
    endif
  endwhile
endfunction

function m = ifelse_mean (kind, a, b)
  if (kind == 2)
    m = sqrt (a*b);
  else
    m = (a + b) / 2;
  endif
endfunction

function [sol, out] = evalc_sol (f, T, y0, o)
  sol = [];
  out = evalc ("sol = odeSPVI (f, [0 T], y0, o);");
endfunction

names = {"arithmetic", "geometric", "gradient"};
printf ("Part 1: Stormer-Verlet, Kepler, 100 periods, rho = |f|/|y|\n");
printf ("%5s %5s %-11s %10s %11s %11s\n", "e", "eps", "recurrence",
        "steps/per", "dH first", "dH last");
for e = [0.9 0.99]
  for ep = [0.02 0.05 0.1 0.2]
    for kind = 1:3
      [f1, l1, ns] = verlet_run (e, 100, ep, kind);
      printf ("%5.2f %5.2f %-11s %10.0f %11.2e %11.2e\n", e, ep,
              names{kind}, ns / 100, f1, l1);
    endfor
  endfor
endfor

printf ("\nPart 2: odeSPVI (4,3), Kepler e = 0.99, 100 periods\n");
printf ("%5s %10s %11s %11s\n", "eps", "steps/per", "dH first", "dH last");
f = @(t, y) [y(3:4,:); -y(1:2,:) ./ sqrt(sum(y(1:2,:).^2, 1)).^3];
Hy = @(y) 0.5*sum (y(:,3:4).^2, 2) - 1 ./ sqrt (sum (y(:,1:2).^2, 2));
e = 0.99;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];  T = 200*pi;
for ep = [0.05 0.06 0.07 0.08 0.1]
  c = 0.05 / ep;
  rho = @(t, y) c * norm (f (t, y)) / sqrt (sum (y.^2) + 4e-12);
  o = symplecticset ("StepControl", "reversible", "RelTol", 1e-3,
                     "AbsTol", 1e-6, "Q_DoFs", 4, "Nodes", 3,
                     "Vectorized", "on", "StepDensityFcn", rho);
  [sol, ~] = evalc_sol (f, T, y0, o);
  t = sol.x(:);  dH = abs (Hy (sol.y') - Hy (y0'));
  if (t(end) < T)
    printf ("%5.2f  the run stopped at t = %.1f: %s\n", ep, t(end), lastwarn ());
  else
    printf ("%5.2f %10.0f %11.2e %11.2e\n", ep, numel (t) / 100,
            max (dH(t <= 0.1*T)), max (dH(t >= 0.9*T)));
  endif
endfor
