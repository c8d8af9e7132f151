## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## Conservation does not depend on the units of q and p: Kepler with q
## and p rescaled canonically (q by s, p by 1/s), and the outer solar
## system in its natural units (AU, days, solar masses: momenta 1e-5 to
## 1e-11 against positions of 5 to 40), with fixed steps.  The angular
## momentum of every solver's run, and the total momentum of the N-body
## system, stay at round-off (1e-13 relative); the Newton solves converge
## each of q and p to its own size.

%!function dy = kepler_scaled (t, y, s)
%!  ## H = s^2 |p|^2/2 - s/|q|: Kepler's H in q' = s q, p' = p/s
%!  r = sqrt (y(1)^2 + y(2)^2);
%!  dy = [s^2 * y(3:4); -s * y(1:2) / r^3];
%!endfunction

%!function L = kepler_L (y)
%!  L = y(:,1) .* y(:,4) - y(:,2) .* y(:,3);
%!endfunction

%!function [m, y0, G] = outer_solar_system ()
%!  ## Sun (with the inner planets), Jupiter, Saturn, Uranus, Neptune,
%!  ## Pluto: masses in solar masses, positions in AU, velocities in AU
%!  ## per day (Hairer, Lubich, Wanner, Geometric Numerical Integration,
%!  ## section I.2.4)
%!  m = [1.00000597682; 0.000954786104043; 0.000285583733151; ...
%!       0.0000437273164546; 0.0000517759138449; 1/1.3e8];
%!  q = [0 0 0; -3.5023653 -3.8169847 -1.5507963;
%!       9.0755314 -3.0458353 -1.6483708; 8.3101420 -16.2901086 -7.2521278;
%!       11.4707666 -25.7294829 -10.8169456;
%!       -15.5387357 -25.2225594 -3.1902382];
%!  v = [0 0 0; 0.00565429 -0.00412490 -0.00190589;
%!       0.00168318 0.00483525 0.00192462; 0.00354178 0.00137102 0.00055029;
%!       0.00288930 0.00114527 0.00039677;
%!       0.00276725 -0.00170702 -0.00136504];
%!  G = 2.95912208286e-4;
%!  y0 = [reshape(q.', [], 1); reshape((v .* m).', [], 1)];
%!endfunction

%!function dy = nbody (t, y, m, G)
%!  ## H = sum |p_i|^2/(2 m_i) - sum_{i<j} G m_i m_j / |q_i - q_j|
%!  N = numel (m);
%!  q = reshape (y(1:3*N), 3, N);
%!  p = reshape (y(3*N+1:end), 3, N);
%!  f = zeros (3, N);
%!  for i = 1:N-1
%!    dq = q(:,i+1:N) - q(:,i);
%!    fij = G * m(i) * m(i+1:N).' .* dq ./ sum (dq.^2, 1).^1.5;
%!    f(:,i) += sum (fij, 2);
%!    f(:,i+1:N) -= fij;
%!  endfor
%!  dy = [reshape(p ./ m.', [], 1); f(:)];
%!endfunction

%!function [L, P] = nbody_momenta (y)
%!  ## total angular momentum (rows of 3) and total momentum, one row each
%!  N = columns (y) / 6;
%!  L = zeros (rows (y), 3);
%!  P = zeros (rows (y), 3);
%!  for i = 1:N
%!    q = y(:, 3*i-2:3*i);
%!    p = y(:, 3*N+3*i-2:3*N+3*i);
%!    L += cross (q, p, 2);
%!    P += p;
%!  endfor
%!endfunction

%!function e = drift (v)
%!  ## the largest change of a conserved vector along the rows, relative
%!  e = max (sqrt (sum ((v - v(1,:)).^2, 2))) / norm (v(1,:));
%!endfunction

%!test
%! ## Kepler e = 0.6, 50 periods at h = T/100, q scaled by s and p by 1/s
%! e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
%! o = symplecticset ("TimeStepSize", 2*pi/100);
%! for s = [1 1e3 1e-3]
%!   Y0 = [s * y0(1:2); y0(3:4) / s];
%!   f = @(t, y) kepler_scaled (t, y, s);
%!   for solver = {@odeSE, @odeSV, @odeSPVI}
%!     [~, y] = solver{1} (f, [0 100*pi], Y0, o);
%!     L = kepler_L (y);
%!     assert (max (abs (L - L(1))) / abs (L(1)) < 1e-13,
%!             sprintf ("%s, s = %g: angular momentum off by %.2g",
%!                      func2str (solver{1}), s,
%!                      max (abs (L - L(1))) / abs (L(1))));
%!   endfor
%! endfor

%!test
%! ## the scaled run is the unscaled run, scaled (odeSPVI, (4,3) and (3,2),
%! ## with finite-difference Newton matrices and with the Hessian)
%! e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
%! s = 1e3;
%! hess = @(t, y, s) blkdiag (s * (eye (2) - 3 * (y(1:2) * y(1:2).') ...
%!                                 / (y(1:2).' * y(1:2))) ...
%!                            / sqrt (y(1:2).' * y(1:2))^3, s^2 * eye (2));
%! for pair = [4 3; 3 2].'
%!   for src = 1:2
%!     o = symplecticset ("TimeStepSize", 2*pi/100, "Q_DoFs", pair(1),
%!                        "Nodes", pair(2));
%!     o1 = o;  os = o;
%!     if (src == 2)
%!       o1.HamiltonianHessFcn = @(t, y) hess (t, y, 1);
%!       os.HamiltonianHessFcn = @(t, y) hess (t, y, s);
%!     endif
%!     [~, y1] = odeSPVI (@(t, y) kepler_scaled (t, y, 1), [0 20*pi], y0, o1);
%!     [~, ys] = odeSPVI (@(t, y) kepler_scaled (t, y, s), [0 20*pi],
%!                        [s * y0(1:2); y0(3:4) / s], os);
%!     assert (ys(:,1:2) / s, y1(:,1:2), 1e-11);
%!     assert (ys(:,3:4) * s, y1(:,3:4), 1e-11);
%!   endfor
%! endfor

%!test
%! ## the outer solar system in AU, days and solar masses, h = 50 days,
%! ## 500 steps: angular and total momentum at round-off for the three
%! ## solvers (implicit steps: Separable off)
%! [m, y0, G] = outer_solar_system ();
%! f = @(t, y) nbody (t, y, m, G);
%! o = symplecticset ("TimeStepSize", 50);
%! for solver = {@odeSE, @odeSV, @odeSPVI}
%!   [~, y] = solver{1} (f, [0 25000], y0, o);
%!   [L, P] = nbody_momenta (y);
%!   name = func2str (solver{1});
%!   assert (drift (L) < 1e-13,
%!           sprintf ("%s: angular momentum off by %.2g", name, drift (L)));
%!   assert (drift (P) < 1e-13,
%!           sprintf ("%s: momentum off by %.2g", name, drift (P)));
%! endfor
