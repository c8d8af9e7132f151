## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## symhamiltonian and symlagrangian: formulas of the symbolic package
## generated as C.  The truths are hand-written Octave FCNs of the same
## formulas (runs equal to round-off), analytic Hessians, and for the
## double pendulum of symlagrangian the Euler-Lagrange equations written
## by hand and solved by ode45.  Without the symbolic package every test
## says so and passes nothing.

%!shared have, kep, pen, hh, dp, sol, fpu
%! have = ! isempty (pkg ("list", "symbolic"));
%! kep = pen = hh = dp = sol = fpu = [];
%! if (! have)
%!   printf ("test_symbolic: skipped, no symbolic package (octave-symbolic)\n");
%! else
%!   pkg load symbolic
%!   syms q1 q2 p1 p2 mu m g l a b va vb
%!   kep = symhamiltonian ((p1^2 + p2^2) / 2 - mu / sqrt (q1^2 + q2^2),
%!                         [q1 q2], [p1 p2], "Parameters", mu);
%!   pen = symhamiltonian (p1^2 / (2*m*l^2) - m*g*l*cos (q1), q1, p1,
%!                         "Parameters", [m g l]);
%!   hh = symhamiltonian ((p1^2 + p2^2 + q1^2 + q2^2) / 2 + q1^2*q2 - q2^3/3,
%!                        [q1 q2], [p1 p2]);
%!   dp = symlagrangian (va^2 + vb^2/2 + va*vb*cos (a-b) + 2*g*cos (a) + g*cos (b),
%!                       [a b], [va vb], "Parameters", g);
%!   ## the outer solar system: 6 bodies in space, the masses and G as
%!   ## parameters
%!   q = sym ("q", [18 1]); p = sym ("p", [18 1]); ms = sym ("m", [6 1]);
%!   syms G
%!   H = sum (p.^2 ./ kron (ms, [1; 1; 1])) / 2;
%!   for i = 1:5
%!     for j = i+1:6
%!       dq = q(3*j-2:3*j) - q(3*i-2:3*i);
%!       H -= G * ms(i) * ms(j) / sqrt (sum (dq.^2));
%!     endfor
%!   endfor
%!   sol = symhamiltonian (H, q, p, "Parameters", [ms; G]);
%!   ## a beta-FPU chain of 16 unit masses, fixed ends
%!   q = sym ("q", [16 1]); p = sym ("p", [16 1]);
%!   syms beta
%!   r = [q(1); q(2:end) - q(1:end-1); -q(end)];
%!   fpu = symhamiltonian (sum (p.^2) / 2 + sum (r.^2 / 2 + beta * r.^4 / 4),
%!                         q, p, "Parameters", beta);
%! endif

%!function [dy, H] = kep_oct (t, y, mu)
%!  r = sqrt (y(1) * y(1) + y(2) * y(2));
%!  dy = [y(3); y(4); -mu * y(1) / r^3; -mu * y(2) / r^3];
%!  q = y(1:2);
%!  H = blkdiag (mu * (eye (2) / r^3 - 3 * (q * q') / r^5), eye (2));
%!endfunction

%!function a = kep_acc (t, q, mu)
%!  a = -mu * q / norm (q)^3;
%!endfunction

%!function [dy, H] = pen_oct (t, y, par)
%!  [m, g, l] = deal (par(1), par(2), par(3));
%!  dy = [y(2) / (m*l^2); -m*g*l*sin(y(1))];
%!  H = diag ([m*g*l*cos(y(1)), 1 / (m*l^2)]);
%!endfunction

%!function [dy, H] = hh_oct (t, y)
%!  x = y(1); z = y(2);
%!  dy = [y(3); y(4); -x - 2*x*z; -z - x^2 + z^2];
%!  H = blkdiag ([1 + 2*z, 2*x; 2*x, 1 - 2*z], eye (2));
%!endfunction

%!function [dy, Hs] = sol_oct (t, y, par)
%!  ## the N-body H by hand: pair by pair, V = -G m_i m_j / |q_j - q_i|
%!  m = par(1:6); G = par(7); mm = kron (m(:), [1; 1; 1]);
%!  acc = zeros (18, 1); Hq = zeros (18);
%!  for i = 1:5
%!    for j = i+1:6
%!      a = 3*i-2:3*i; b = 3*j-2:3*j;
%!      d = y(b) - y(a); r = norm (d); c = G * m(i) * m(j);
%!      acc(a) += c * d / r^3; acc(b) -= c * d / r^3;
%!      B = c * (eye (3) / r^3 - 3 * (d * d') / r^5);
%!      Hq(a,a) += B; Hq(b,b) += B; Hq(a,b) -= B; Hq(b,a) -= B;
%!    endfor
%!  endfor
%!  dy = [y(19:36) ./ mm; acc];
%!  Hs = blkdiag (Hq, diag (1 ./ mm));
%!endfunction

%!function [dy, H] = fpu_oct (t, y, beta)
%!  d = numel (y) / 2;
%!  r = diff ([0; y(1:d); 0]);
%!  dy = [y(d+1:end); diff(r + beta * r .* r .* r)];
%!  k = 1 + 3 * beta * r .* r;
%!  Hq = spdiags ([[-k(2:d); 0], k(1:d) + k(2:d+1), [0; -k(2:d)]], -1:1, d, d);
%!  H = blkdiag (Hq, speye (d));
%!endfunction

%!function V = sol_pot (y, par)
%!  V = 0;
%!  for i = 1:5
%!    for j = i+1:6
%!      V -= par(7) * par(i) * par(j) / norm (y(3*j-2:3*j) - y(3*i-2:3*i));
%!    endfor
%!  endfor
%!endfunction

%!function a = sol_acc (t, q, par)
%!  ## the accelerations, -M^-1 dV/dq
%!  dy = sol_oct (t, [q; zeros(18, 1)], par);
%!  a = dy(19:36) ./ kron (par(1:6)', [1; 1; 1]);
%!endfunction

%!function [y0, par] = solar_data ()
%!  ## the outer solar system on 5 September 1994 (AU, days), the Sun's
%!  ## mass with the inner planets'; y0 = [q; p], p = m v
%!  par = [1.00000597682, 0.000954786104043, 0.000285583733151, ...
%!         0.0000437273164546, 0.0000517759138449, 1/1.3e8, 2.95912208286e-4];
%!  q = [0 0 0; -3.5023653 -3.8169847 -1.5507963; 9.0755314 -3.0458353 -1.6483708;
%!       8.3101420 -16.2901086 -7.2521278; 11.4707666 -25.7294829 -10.8169456;
%!       -15.5387357 -25.2225594 -3.1902382]';
%!  v = [0 0 0; 0.00565429 -0.00412490 -0.00190589; 0.00168318 0.00483525 0.00192462;
%!       0.00354178 0.00137102 0.00055029; 0.00288930 0.00114527 0.00039677;
%!       0.00276725 -0.00170702 -0.00136504]';
%!  y0 = [q(:); v(:) .* kron(par(1:6)', [1; 1; 1])];
%!endfunction

%!function J = stepjac (s, f, y0, opts, varargin)
%!  ## the Jacobian of the run's end point in y0, by central differences
%!  n = numel (y0); J = zeros (n); del = 1e-5;
%!  for k = 1:n
%!    e = zeros (n, 1); e(k) = del;
%!    [~, yp] = s (f, [0 1], y0 + e, opts, varargin{:});
%!    [~, ym] = s (f, [0 1], y0 - e, opts, varargin{:});
%!    J(:,k) = (yp(end,:) - ym(end,:))' / (2 * del);
%!  endfor
%!endfunction

%!function dx = dp_el (t, x, g)
%!  ## the double pendulum's Euler-Lagrange equations in (q, v), by hand
%!  a = x(1); b = x(2); va = x(3); vb = x(4); s = sin (a - b); c = cos (a - b);
%!  M = [2 c; c 1];
%!  dx = [va; vb; M \ [-2*g*sin(a) - s*vb^2; -g*sin(b) + s*va^2]];
%!endfunction

%!function e = relerr (a, b)
%!  e = max (abs (a(:) - b(:))) / max (abs (b(:)));
%!endfunction

%!function experr (f, pat)
%!  try
%!    f ();
%!  catch err
%!    assert (! isempty (regexp (err.message, pat, "once")), err.message);
%!    return;
%!  end_try_catch
%!  error ("no error, expected '%s'", pat);
%!endfunction

%!test
%! ## 100 fixed steps, every solver, implicit (Newton on the generated Hessian)
%! if (! have) return; endif
%! y0k = [0.5; 0; 0; sqrt(3)]; y0h = [0.1; -0.2; 0.3; 0.25];
%! opts = symplecticset ("TimeStepSize", 0.05, "TimeStepNumber", 100);
%! for s = {@odeSE, @odeSV, @odeSPVI}
%!   [~, y1] = s{1} (kep, [0 5], y0k, opts, 1.5);
%!   [~, y2] = s{1} (@kep_oct, [0 5], y0k, opts, 1.5);
%!   assert (rows (y1), 101);
%!   assert (relerr (y1, y2) <= 1e-13, func2str (s{1}));
%!   [~, y1] = s{1} (pen, [0 5], [1; 0], opts, [2 9.81 0.5]);
%!   [~, y2] = s{1} (@pen_oct, [0 5], [1; 0], opts, [2 9.81 0.5]);
%!   assert (relerr (y1, y2) <= 1e-13, func2str (s{1}));
%!   [~, y1] = s{1} (hh, [0 5], y0h, opts);
%!   [~, y2] = s{1} (@hh_oct, [0 5], y0h, opts);
%!   assert (relerr (y1, y2) <= 1e-13, func2str (s{1}));
%! endfor

%!test
%! ## the outer solar system and the FPU chain: 100 fixed steps, every solver
%! if (! have) return; endif
%! [y0, par] = solar_data ();
%! opts = symplecticset ("TimeStepSize", 50, "TimeStepNumber", 100);
%! for s = {@odeSE, @odeSV, @odeSPVI}
%!   [~, y1] = s{1} (sol, [0 5000], y0, opts, par);
%!   [~, y2] = s{1} (@sol_oct, [0 5000], y0, opts, par);
%!   assert (relerr (y1, y2) <= 1e-13, func2str (s{1}));
%! endfor
%! d = 16; y0 = [0.1 * sin(pi * (1:d)' / (d + 1)); zeros(d, 1)];
%! opts = symplecticset ("TimeStepSize", 0.1, "TimeStepNumber", 100);
%! for s = {@odeSE, @odeSV, @odeSPVI}
%!   [~, y1] = s{1} (fpu, [0 10], y0, opts, 1);
%!   [~, y2] = s{1} (@fpu_oct, [0 10], y0, opts, 1);
%!   assert (relerr (y1, y2) <= 1e-13, func2str (s{1}));
%! endfor
%! ## the explicit forms: Separable, and SecondOrder on y = [q; v]
%! opts = symplecticset ("TimeStepSize", 50, "TimeStepNumber", 100,
%!                       "Separable", "on", "Method", "kahanli8");
%! [y0, par] = solar_data ();
%! [~, y1] = odeSV (sol, [0 5000], y0, opts, par);
%! [~, y2] = odeSV (@sol_oct, [0 5000], y0, opts, par);
%! assert (relerr (y1, y2) <= 1e-13);
%! opts = symplecticset ("TimeStepSize", 50, "TimeStepNumber", 100,
%!                       "SecondOrder", "on", "Method", "kahanli8");
%! mm = kron (par(1:6)', [1; 1; 1]); yv = [y0(1:18); y0(19:36) ./ mm];
%! [~, y1] = odeSV (sol, [0 5000], yv, opts, par);
%! [~, y2] = odeSV (@sol_acc, [0 5000], yv, opts, par);
%! assert (relerr (y1, y2) <= 1e-13);

%!test
%! ## generated Hessians of the solar system and the chain: the analytic ones
%! if (! have) return; endif
%! [y0, par] = solar_data ();
%! [dy, H] = sol (0, y0, par);
%! [dy2, H2] = sol_oct (0, y0, par);
%! assert (dy, dy2, 1e-14 * norm (dy2, Inf));
%! assert (full (H), H2, 1e-13 * norm (H2, Inf));
%! assert (sol.nnz, nnz (H2));
%! E = sum (y0(19:36) .* dy2(1:18)) / 2 + sol_pot (y0, par);
%! assert (sol.energy (0, y0, par), E, 1e-14 * abs (E));
%! y = [0.1 * sin(1:16)'; cos(1:16)'];
%! [dy, H] = fpu (0, y, 1.5);
%! [dy2, H2] = fpu_oct (0, y, 1.5);
%! assert (dy, dy2, 1e-14);
%! assert (full (H), full (H2), 1e-14);
%! assert (fpu.nnz, 3 * 16 - 2 + 16);

%!test
%! ## symplecticity: the Jacobian of 10 steps keeps the form J (central
%! ## differences), compiled fcn, every solver
%! if (! have) return; endif
%! y0 = [0.1; -0.2; 0.3; 0.25];
%! Om = [zeros(2), eye(2); -eye(2), zeros(2)];
%! opts = symplecticset ("TimeStepSize", 0.1, "TimeStepNumber", 10);
%! for s = {@odeSE, @odeSV, @odeSPVI}
%!   J = stepjac (s{1}, hh, y0, opts);
%!   assert (norm (J' * Om * J - Om, Inf) < 1e-8, func2str (s{1}));
%!   assert (norm (J - eye (4), Inf) > 0.1);     # the map moves y0
%! endfor
%! ## a map that is not symplectic fails the same check: a damping force
%! syms x y px py c
%! fd = symhamiltonian ((px^2 + py^2 + x^2 + y^2) / 2 + x^2*y - y^3/3,
%!                      [x y], [px py], "Parameters", c, "Force", -c * [px; py]);
%! J = stepjac (@odeSV, fd, y0, opts, 0.1);
%! assert (norm (J' * Om * J - Om, Inf) > 1e-2);

%!test
%! ## reversal: forward, then back from the end point, to y0 (symmetric
%! ## methods), compiled fcn
%! if (! have) return; endif
%! [y0, par] = solar_data ();
%! opts = symplecticset ("TimeStepSize", 50, "TimeStepNumber", 200, "Separable", "on",
%!                       "Method", "kahanli8");
%! [~, y1] = odeSV (sol, [0 1e4], y0, opts, par);
%! [~, yb] = odeSV (sol, [1e4 0], y1(end,:)', opts, par);
%! assert (norm (y1(end,:)' - y0, Inf) > 1);
%! assert (relerr (yb(end,:)', y0) < 1e-12);
%! y0 = [0.5; 0; 0; sqrt(3)];
%! opts = symplecticset ("TimeStepSize", 0.05, "TimeStepNumber", 100);
%! for s = {@odeSV, @odeSPVI}
%!   [~, y1] = s{1} (kep, [0 5], y0, opts, 1);
%!   [~, yb] = s{1} (kep, [5 0], y1(end,:)', opts, 1);
%!   assert (relerr (yb(end,:)', y0) < 1e-11, func2str (s{1}));
%! endfor

%!test
%! ## odeSV explicit: Separable, and SecondOrder on the generated acceleration
%! if (! have) return; endif
%! y0k = [0.5; 0; 0; sqrt(3)];
%! opts = symplecticset ("TimeStepSize", 0.05, "TimeStepNumber", 100, "Separable", "on");
%! [~, y1] = odeSV (kep, [0 5], y0k, opts, 1);
%! [~, y2] = odeSV (@kep_oct, [0 5], y0k, opts, 1);
%! assert (relerr (y1, y2) <= 1e-13);
%! [~, y1] = odeSV (hh, [0 5], [0.1; -0.2; 0.3; 0.25], opts);
%! [~, y2] = odeSV (@hh_oct, [0 5], [0.1; -0.2; 0.3; 0.25], opts);
%! assert (relerr (y1, y2) <= 1e-13);
%! opts = symplecticset ("TimeStepSize", 0.05, "TimeStepNumber", 100, "SecondOrder", "on");
%! [~, y1] = odeSV (kep, [0 5], y0k, opts, 1);
%! [~, y2] = odeSV (@kep_acc, [0 5], y0k, opts, 1);
%! assert (relerr (y1, y2) <= 1e-13);
%! [~, y1] = odeSV (pen, [0 5], [1; 0], opts, [2 9.81 0.5]);
%! [~, y2] = odeSV (@(t, q, par) -par(2) / par(3) * sin (q), [0 5], [1; 0], opts, [2 9.81 0.5]);
%! assert (relerr (y1, y2) <= 1e-13);

%!test
%! ## generated Hessians and energies against the analytic ones
%! if (! have) return; endif
%! for y = [0.5 0.1 0.2 1.5; -0.7 0.4 -0.3 0.1]'
%!   [dy, H] = kep (0, y, 1.5);
%!   [dy2, H2] = kep_oct (0, y, 1.5);
%!   assert (full (H), H2, 1e-14 * norm (H2, 1));
%!   assert (dy, dy2, 1e-14 * norm (dy2));
%!   [~, H] = hh (0, y);
%!   [~, H2] = hh_oct (0, y);
%!   assert (full (H), H2, 1e-15);
%!   assert (kep.energy (0, y, 1.5), sum (y(3:4).^2) / 2 - 1.5 / norm (y(1:2)), 1e-14);
%! endfor
%! [~, H] = pen (0, [0.3; 0.7], [2 9.81 0.5]);
%! [~, H2] = pen_oct (0, [0.3; 0.7], [2 9.81 0.5]);
%! assert (full (H), H2, 1e-14);
%! assert (kep.nnz, 6);                 # the zero blocks are left out

%!test
%! ## symlagrangian, the double pendulum (M(q) not constant) against ode45
%! if (! have) return; endif
%! g = 9.81; q0 = [1; 0.5]; v0 = [0.3; -0.2];
%! p0 = dp.momentum (q0, v0, g);
%! assert (p0, [2 cos(0.5); cos(0.5) 1] * v0, 1e-15);
%! assert (dp.velocity (q0, p0, g), v0, 1e-15);
%! opts = symplecticset ("TimeStepSize", 0.01, "Method", "kahanli8");
%! [t, y] = odeSV (dp, [0 1], [q0; p0], opts, g);
%! [~, x] = ode45 (@(t, x) dp_el (t, x, g), [0 1], [q0; v0],
%!                 odeset ("RelTol", 1e-12, "AbsTol", 1e-12));
%! v1 = dp.velocity (y(end,1:2)', y(end,3:4)', g);
%! assert ([y(end,1:2)'; v1], x(end,:)', 1e-9);

%!test
%! ## the double pendulum's energy stays bounded over 2*10^4 Verlet steps
%! if (! have) return; endif
%! g = 9.81; q0 = [1; 0.5]; y0 = [q0; dp.momentum(q0, [0.3; -0.2], g)];
%! E = @(x) x(3)^2 + x(4)^2/2 + x(3)*x(4)*cos(x(1)-x(2)) - 2*g*cos(x(1)) - g*cos(x(2));
%! E0 = E ([q0; 0.3; -0.2]);
%! assert (dp.energy (0, y0, g), E0, 1e-13);
%! opts = symplecticset ("TimeStepSize", 0.005, "TimeStepNumber", 20000);
%! [~, y] = odeSV (dp, [0 100], y0, opts, g);
%! e = zeros (1, 201); k = round (linspace (1, rows (y), 201));
%! for j = 1:201
%!   e(j) = dp.energy (0, y(k(j),:)', g);
%! endfor
%! assert (max (abs (e - E0)) < 1e-3 * abs (E0));

%!test
%! ## errors name the function and the argument
%! if (! have) return; endif
%! syms x y px py k c
%! experr (@() symhamiltonian ([x; y], [x y], [px py]), "^symhamiltonian: H must be a scalar");
%! experr (@() symhamiltonian (x*px, [x y], px), "^symhamiltonian: Q and P must have the same length");
%! experr (@() symhamiltonian (k*x^2 + px^2, x, px), "^symhamiltonian: symbols not bound.*: k");
%! experr (@() symhamiltonian (x^2 + px^2, x, px, "Force", [x; x]), "^symhamiltonian: Force must have 1");
%! experr (@() symhamiltonian (x^2 + px^2, x, px, "Mass", 1), "^symhamiltonian: unknown option 'Mass'");
%! experr (@() odeSV (kep, [0 1], [1; 0; 0; 1], symplecticset ("TimeStepSize", 0.1)),
%!         "compiled FCN takes its parameters");
%! experr (@() odeSV (pen, [0 1], [1; 0], symplecticset ("TimeStepSize", 0.1), [1 2]),
%!         "^odeSV: the compiled FCN takes its parameters as PAR1");
%! experr (@() symlagrangian (px^4 - x^2, x, px), "^symlagrangian: L must be quadratic in V");
%! experr (@() symlagrangian (px*x - x^2, x, px), "^symlagrangian: the mass matrix");

%!test
%! ## a force F(t, q, p) adds to dp/dt; time-dependent H
%! if (! have) return; endif
%! syms x px t c
%! f = symhamiltonian (px^2/2 + x^2/2 + x*cos(t), x, px, "Time", t,
%!                     "Parameters", c, "Force", -c*px);
%! assert (f (0.3, [0.2; 0.5], 0.1), [0.5; -0.2 - cos(0.3) - 0.05], 1e-15);
