## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## symhamiltonian and symlagrangian: formulas of the symbolic package
## generated as C.  The truths are hand-written Octave FCNs of the same
## formulas (runs equal to round-off), analytic Hessians, and for the
## double pendulum of symlagrangian the Euler-Lagrange equations written
## by hand and solved by ode45.  Without the symbolic package every test
## says so and passes nothing.

%!shared have, kep, pen, hh, dp
%! have = ! isempty (pkg ("list", "symbolic"));
%! kep = pen = hh = dp = [];
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
