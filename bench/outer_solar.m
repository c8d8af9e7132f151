## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## outer_solar.m -- the outer solar system, Sun + Jupiter, Saturn, Uranus,
## Neptune and Pluto, with the data of
##
##   E. Hairer, C. Lubich, G. Wanner, Geometric Numerical Integration,
##   2nd ed., Springer 2006, Section I.2.4, Table 2.3:
##
## masses relative to the Sun, the Sun's augmented by the inner planets
## (m0 = 1.00000597682), G = 2.95912208286e-4, positions in AU and
## velocities in AU/day at 5 September 1994 (time in days), the Sun at the
## origin and at rest.  H(q, p) = sum |p_i|^2 / (2 m_i)
## - G sum_{i<j} m_i m_j / |q_i - q_j|, p_i = m_i v_i.
##
##   S = outer_solar ()
##
## S.names, S.m (1-by-6), S.G; S.q0, S.v0, S.p0 (18-by-1, body by body:
## x, y, z of the Sun, then of Jupiter, ...);
## S.acc:  a = S.acc (t, q), the accelerations (18-by-k for q 18-by-k),
##         the fcn of SecondOrder "on", y = [q; v];
## S.fcn:  dy = S.fcn (t, y) = [dH/dp; -dH/dq] for y = [q; p] (36-by-k),
##         the fcn of the first-order form (Separable "on", odeSPVI);
## S.Hv:   H of the rows of Y = [q v] (n-by-36), S.Hp of the rows [q p];
## S.Hv_kdk2: S.Hv_kdk2 (Y, h), the energy of the rows [q v] plus the
##         h^2 term of the modified Hamiltonian of the kick-drift-kick
##         Verlet step, h^2 (v' V'' v / 12 - grad V' M^-1 grad V / 24):
##         its change along a Verlet run is O(h^4) plus round-off.

function S = outer_solar ()
  S.names = {"Sun", "Jupiter", "Saturn", "Uranus", "Neptune", "Pluto"};
  S.m = [1.00000597682, 0.000954786104043, 0.000285583733151, ...
         0.0000437273164546, 0.0000517759138449, 1/1.3e8];
  S.G = 2.95912208286e-4;
  q = [ 0,           0,           0;
       -3.5023653,  -3.8169847,  -1.5507963;
        9.0755314,  -3.0458353,  -1.6483708;
        8.3101420, -16.2901086,  -7.2521278;
       11.4707666, -25.7294829, -10.8169456;
      -15.5387357, -25.2225594,  -3.1902382];
  v = [ 0,           0,           0;
        0.00565429, -0.00412490, -0.00190589;
        0.00168318,  0.00483525,  0.00192462;
        0.00354178,  0.00137102,  0.00055029;
        0.00288930,  0.00114527,  0.00039677;
        0.00276725, -0.00170702, -0.00136504];
  S.q0 = reshape (q.', 18, 1);
  S.v0 = reshape (v.', 18, 1);
  mm = kron (S.m(:), ones (3, 1));            # the mass of each coordinate
  S.p0 = mm .* S.v0;
  ## the 15 pairs (i, j), i < j; with the differences d_k = q_j - q_i of
  ## the pairs (45 rows, Dm * q), acc = Am * (d_k / |d_k|^3):
  ## Am(i, k) = G m_j, Am(j, k) = -G m_i (each coordinate)
  [J, I] = find (triu (ones (6), 1).');
  I = I.';  J = J.';
  Dm = zeros (45, 18);  Am = zeros (18, 45);
  for k = 1:15
    for c = 1:3
      Dm(3*k-3+c, 3*J(k)-3+c) = 1;
      Dm(3*k-3+c, 3*I(k)-3+c) = -1;
      Am(3*I(k)-3+c, 3*k-3+c) = S.G * S.m(J(k));
      Am(3*J(k)-3+c, 3*k-3+c) = -S.G * S.m(I(k));
    endfor
  endfor
  S.acc = @(t, q) os_acc (q, Dm, Am);
  S.fcn = @(t, y) os_fcn (y, Dm, Am, mm);
  S.Hv = @(Y) os_energy (Y(:, 1:18), Y(:, 19:36) .* mm.', S.m, S.G, I, J);
  S.Hp = @(Y) os_energy (Y(:, 1:18), Y(:, 19:36), S.m, S.G, I, J);
  S.Hv_kdk2 = @(Y, h) os_kdk2 (Y, h, S.m, S.G, I, J);
endfunction

function a = os_acc (q, Dm, Am)
  ## q: 18-by-k (k = 1, or Vectorized)
  k = columns (q);
  D = reshape (Dm * q, 3, 15*k);
  r2 = sum (D.^2, 1);
  a = Am * reshape (D ./ (r2 .* sqrt (r2)), 45, k);
endfunction

function dy = os_fcn (y, Dm, Am, mm)
  dy = [y(19:36, :) ./ mm; mm .* os_acc(y(1:18, :), Dm, Am)];
endfunction

function H = os_energy (Q, P, m, G, I, J)
  ## rows of Q and P: positions and momenta
  mm = kron (m, ones (1, 3));
  T = sum (P.^2 ./ mm, 2) / 2;
  V = zeros (rows (Q), 1);
  for k = 1:15
    d = Q(:, 3*J(k)-2:3*J(k)) - Q(:, 3*I(k)-2:3*I(k));
    V -= G * m(I(k)) * m(J(k)) ./ sqrt (sum (d.^2, 2));
  endfor
  H = T + V;
endfunction

function H = os_kdk2 (Y, h, m, G, I, J)
  ## H + h^2 (v' V'' v / 12 - |grad V|^2_(M^-1) / 24), rows Y = [q v]
  Q = Y(:, 1:18);  Vv = Y(:, 19:36);
  mm = kron (m, ones (1, 3));
  H = os_energy (Q, Vv .* mm, m, G, I, J);
  vHv = zeros (rows (Q), 1);
  F = zeros (size (Q));                        # -grad V, the forces
  for k = 1:15
    ci = 3*I(k)-2:3*I(k);  cj = 3*J(k)-2:3*J(k);
    d = Q(:, cj) - Q(:, ci);  w = Vv(:, cj) - Vv(:, ci);
    r2 = sum (d.^2, 2);  r = sqrt (r2);
    c = G * m(I(k)) * m(J(k));
    ## V = -c / |d|: w' V'' w = -c (3 (d.w)^2 / r^5 - |w|^2 / r^3)
    vHv -= c * (3 * sum (d .* w, 2).^2 ./ (r2.^2 .* r) - sum (w.^2, 2) ./ (r2 .* r));
    f = c * d ./ (r2 .* r);                    # force on i, towards j
    F(:, ci) += f;  F(:, cj) -= f;
  endfor
  H += h^2 * (vHv / 12 - sum (F.^2 ./ mm, 2) / 24);
endfunction
