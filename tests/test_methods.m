## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## Tests of odeSV's Method option (compositions of Stormer-Verlet and
## splitting methods), of SecondOrder (odeSE, odeSV) and of odeSV's
## CompensatedSummation: orders, symplecticity, reversibility, the steps
## against an m-code stepper, calls per step, round-off, events and dense
## output, the errors.  References are independent of the package: exact
## solutions (Kepler's equation, the pendulum through ellipj, the harmonic
## oscillator), an m-code stepper with its own copy of the coefficients
## (mcoefs, from the papers), finite-difference Jacobians.

%!function m = mcoefs (name)
%!  ## The methods, independently of the package.  kind "c": composition,
%!  ## Stormer-Verlet steps of g h for g in a; kind "s": splitting, kick
%!  ## first: for i = 1..s, p += b(i) h F(q), then q += a(i) h p.  order,
%!  ## symmetric, and nf: force evaluations a step of the explicit steps
%!  ## (first same as last: a composition s; a splitting its nonzero b,
%!  ## one less when it ends with a kick, a(s) = 0).
%!  m.kind = "c";  m.b = [];  m.sym = true;
%!  switch (name)
%!    case "verlet"
%!      m.a = 1;  m.order = 2;
%!    case "yoshida4"          # Yoshida, Phys. Lett. A 150 (1990)
%!      x = 2^(1/3);  m.a = [1, -x, 1] / (2 - x);  m.order = 4;
%!    case "suzuki4"           # Suzuki, Phys. Lett. A 146 (1990)
%!      x = 4^(1/3);  m.a = [1, 1, -x, 1, 1] / (4 - x);  m.order = 4;
%!    case "kahanli6"          # Kahan & Li, Math. Comp. 66 (1997), s9odr6a
%!      g = [0.39216144400731414, 0.33259913678935944, -0.70624617255763936, ...
%!           0.082213596293550800, 0.79854399093482996];
%!      m.a = [g, g(end-1:-1:1)];  m.order = 6;
%!    case "kahanli8"          # Kahan & Li, s17odr8a
%!      g = [0.13020248308889008, 0.56116298177510838, -0.38947496264484729, ...
%!           0.15884190655515560, -0.39590389413323758, 0.18453964097831571, ...
%!           0.25837438768632205, 0.29501172360931030, -0.60550853383003451];
%!      m.a = [g, g(end-1:-1:1)];  m.order = 8;
%!    case "mclachlan8"        # McLachlan, SIAM J. Sci. Comput. 16 (1995)
%!      g = [0.74167036435061295, -0.40910082580003159, 0.19075471029623838, ...
%!           -0.57386247111608227, 0.29906418130365592, 0.33462491824529818, ...
%!           0.31529309239676660, -0.79688793935291635];
%!      m.a = [g, g(end-1:-1:1)];  m.order = 8;
%!    case "sofspa10"          # Sofroniou & Spaletta, OMS 20 (2005)
%!      g = [0.078795722521686419, 0.31309610341510853, 0.027918383235078066, ...
%!           -0.22959284159390709, 0.13096206107716486, -0.26973340565451071, ...
%!           0.074973343155891436, 0.11199342399981020, 0.36613344954622675, ...
%!           -0.39910563013603590, 0.10308739852747108, 0.41143087395589024, ...
%!           -0.0048663605831352618, -0.39203335370863991, 0.051942502962449647, ...
%!           0.050665090759924496, 0.049674370639729879, 0.049317735759594538];
%!      m.a = [g, g(end-1:-1:1)];  m.order = 10;
%!    case "ruth3"             # Ruth, IEEE Trans. Nucl. Sci. 30 (1983)
%!      m.kind = "s";  m.a = [2/3, -2/3, 1];  m.b = [7/24, 3/4, -1/24];
%!      m.order = 3;  m.sym = false;
%!    case "candyrozmus4"      # Candy & Rozmus, J. Comput. Phys. 92 (1991)
%!      x = 2^(1/3);  m.kind = "s";
%!      m.a = [2+x+1/x, 1-x-1/x, 1-x-1/x, 2+x+1/x] / 6;
%!      m.b = [0, 1/(2-x), 1/(1-x^2), 1/(2-x)];  m.order = 4;
%!    case "mclachlan4"        # McLachlan & Atela, Nonlinearity 5 (1992)
%!      m.kind = "s";
%!      m.a = [0.51535283743112294, -0.085782019412973646, ...
%!             0.44158302361646652, 0.12884615836538419];
%!      m.b = [0.13449619927743109, -0.22481980307942081, ...
%!             0.75632000051566829, 0.33400360328632143];
%!      m.order = 4;  m.sym = false;
%!    case "blanesmoan6"       # Blanes & Moan, JCAM 142 (2002), SRKN_11^b
%!      a = [0.12322977594627100, 0.29055379779955800, -0.12704921262541700, ...
%!           -0.24633176106207500, 0.35720887279592800];
%!      b = [0.041464998518262400, 0.19812867191806700, -0.040006192104153300, ...
%!           0.075253984301580700, -0.011511387420687900];
%!      m.kind = "s";  m.a = [a, 1 - 2*sum(a), a(end:-1:1), 0];
%!      m.b = [b, 1/2 - sum(b), 1/2 - sum(b), b(end:-1:1)];  m.order = 6;
%!    otherwise
%!      error ("mcoefs: %s", name);
%!  endswitch
%!  if (m.kind == "c")
%!    m.nf = numel (m.a);
%!  else
%!    m.nf = nnz (m.b) - (m.a(end) == 0);
%!  endif
%!endfunction

%!function y = mstep (m, F, y, h)
%!  ## one step of method m for H = |p|^2/2 + V(q), F = -grad V
%!  d = numel (y) / 2;  q = y(1:d);  p = y(d+1:end);
%!  if (m.kind == "c")
%!    for g = m.a
%!      p += (g*h/2) * F (q);  q += (g*h) * p;  p += (g*h/2) * F (q);
%!    endfor
%!  else
%!    for i = 1:numel (m.a)
%!      if (m.b(i) != 0)
%!        p += (m.b(i)*h) * F (q);
%!      endif
%!      q += (m.a(i)*h) * p;
%!    endfor
%!  endif
%!  y = [q; p];
%!endfunction

%!function y = kepler_exact (t, e)
%!  ## Kepler's problem, a = 1, from the pericentre at t = 0: Kepler's
%!  ## equation E - e sin E = t by Newton's method
%!  E = t;
%!  for i = 1:50
%!    E -= (E - e * sin (E) - t) / (1 - e * cos (E));
%!  endfor
%!  s = sqrt (1 - e^2);  r = 1 - e * cos (E);
%!  y = [cos(E) - e; s * sin(E); -sin(E) / r; s * cos(E) / r];
%!endfunction

%!function y = pendulum_exact (t, q0)
%!  ## H = p^2/2 - cos q from (q0, 0): sin(q/2) = k sn(t + K), p = 2 k cn(t + K)
%!  k = sin (q0/2);
%!  [sn, cn] = ellipj (t + ellipke (k^2), k^2);
%!  y = [2 * asin(k * sn); 2 * k * cn];
%!endfunction

%!function dy = kep (t, y)
%!  q = y(1:2);
%!  dy = [y(3:4); -q / norm(q)^3];
%!endfunction

%!function a = kep_acc (t, q)
%!  ## the acceleration of Kepler's problem, for q of 2-by-k (Vectorized)
%!  global TM_CALLS TM_COLS
%!  TM_CALLS += 1;
%!  TM_COLS = max (TM_COLS, columns (q));
%!  assert (rows (q) == 2 && isequal (size (t), [1, columns(q)]));
%!  a = -q ./ sum (q.^2, 1).^1.5;
%!endfunction

%!function dy = pend (t, y)
%!  dy = [y(2); -sin(y(1))];
%!endfunction

%!function dy = nonsep (t, y)
%!  ## H = |p|^2/2 (1 + |q|^2/4) + |q|^4/8 in 2-D: not separable
%!  q = y(1:2);  p = y(3:4);
%!  dy = [p * (1 + q.'*q/4); -(q * (p.'*p)/4 + q * (q.'*q)/2)];
%!endfunction

%!function s = fitted_slope (N, err)
%!  ## least-squares slope of log(err) against log(h), h ~ 1/N
%!  c = polyfit (-log (N), log (err), 1);
%!  s = c(1);
%!endfunction

%!function M = step_jacobian (step, y0)
%!  ## d(y1)/d(y0) of the map step by central differences of steps 1e-3
%!  ## and 5e-4 (relative to y0) extrapolated (Richardson): error O(1e-12)
%!  ## here, where central differences alone have 1e-10 at steps of 1e-5
%!  ## (their h^2 term 9e-11, round-off 3e-11) and 1e-9 at 1e-6
%!  n = numel (y0);  M = zeros (n);
%!  for j = 1:n
%!    e = zeros (n, 1);  e(j) = 1e-3 * max (1, abs (y0(j)));
%!    D1 = (step (y0 + e) - step (y0 - e)) / (2 * e(j));
%!    D2 = (step (y0 + e/2) - step (y0 - e/2)) / e(j);
%!    M(:, j) = (4 * D2 - D1) / 3;
%!  endfor
%!endfunction

%!function y = rk4_step (f, y, h)
%!  k1 = f (0, y);  k2 = f (0, y + h/2*k1);  k3 = f (0, y + h/2*k2);
%!  k4 = f (0, y + h*k3);
%!  y += h/6 * (k1 + 2*k2 + 2*k3 + k4);
%!endfunction

%!function stop = rows6 (t, y, flag)
%!  ## OutputFcn: records the number of rows of y it gets
%!  global TM_ROWS
%!  if (! isempty (y))
%!    TM_ROWS(end+1) = rows (y);
%!  endif
%!  stop = false;
%!endfunction

%!function y1 = last_row (solver, f, tspan, y0, o)
%!  [~, y] = solver (f, tspan, y0, o);
%!  y1 = y(end, :).';
%!endfunction

%!function check_orders (names, Ns, f, T, y0, yT, opts, floor)
%!  ## for each method: the errors at T of the runs of N(i) steps (Ns.(name))
%!  ## against yT, their fitted slope within 0.3 of the nominal order, and
%!  ## (floor > 0) every error above floor, clear of round-off
%!  for k = 1:numel (names)
%!    m = mcoefs (names{k});  N = Ns.(names{k});  err = zeros (size (N));
%!    for i = 1:numel (N)
%!      o = symplecticset (opts, "TimeStepNumber", N(i), "Method", names{k});
%!      err(i) = norm (last_row (@odeSV, f, [0 T], y0, o) - yT, Inf);
%!    endfor
%!    s = fitted_slope (N, err);
%!    assert (abs (s - m.order) <= 0.3, "%s: slope %.2f, errors %s",
%!            names{k}, s, mat2str (err, 3));
%!    assert (min (err) > floor);
%!  endfor
%!endfunction

%!shared names, comps, e, y0k
%! names = {"verlet", "yoshida4", "suzuki4", "kahanli6", "kahanli8", ...
%!          "mclachlan8", "sofspa10", "ruth3", "candyrozmus4", ...
%!          "mclachlan4", "blanesmoan6"};
%! comps = names(1:7);     # the compositions
%! e = 0.5;  y0k = [1-e; 0; 0; sqrt((1+e)/(1-e))];   # Kepler, pericentre

## ----------------------------------------------------------------- orders
%!test
%! ## the references: Kepler's equation and ellipj agree with ode45 at
%! ## tight tolerances (whose own error is some 1e-13)
%! oo = odeset ("RelTol", 1e-13, "AbsTol", 1e-13);
%! [~, y] = ode45 (@kep, [0 1], y0k, oo);
%! assert (norm (y(end, :).' - kepler_exact (1, e), Inf) < 1e-12);
%! [~, y] = ode45 (@pend, [0 1.5], [2; 0], oo);
%! assert (norm (y(end, :).' - pendulum_exact (1.5, 2), Inf) < 1e-12);
%! ## and the m-code reference stepper has the nominal orders (yoshida4,
%! ## ruth3), so that it is a reference for the package
%! for nm = {"yoshida4", "ruth3"}
%!   m = mcoefs (nm{1});  err = [];
%!   for N = [256 512]
%!     y = [2; 0];
%!     for k = 1:N
%!       y = mstep (m, @(q) -sin (q), y, 1.5/N);
%!     endfor
%!     err(end+1) = norm (y - pendulum_exact (1.5, 2), Inf);
%!   endfor
%!   assert (abs (log2 (err(1) / err(2)) - m.order) < 0.05);
%! endfor

%!test
%! ## measured order = nominal, explicit steps (Separable on), Kepler e =
%! ## 0.5 from the pericentre to t = 1, exact solution by Kepler's equation.
%! ## Not at a whole period: there ruth3's error has slope 4.0 (its h^3
%! ## term returns to zero with the orbit), at t = 1 it shows 2.9.  The N
%! ## keep the errors between 1e-3 and 5e-13 (round-off 1e-14), in the
%! ## asymptotic range (sofspa10: slopes of 10.4, 9.4, 10.2 between
%! ## successive N: the window between its h^12 term and round-off is
%! ## narrow).  Measured in the order of names: 2.00 3.99 3.99 6.00 7.99
%! ## 7.92 9.99 2.89 3.99 4.00 5.98
%! T = 1;  yT = kepler_exact (T, e);
%! Ns = struct ("verlet", [32 64 128], "yoshida4", [32 64 128], ...
%!              "suzuki4", [16 32 64], "kahanli6", [16 32 64], ...
%!              "kahanli8", [8 11 16 23], "mclachlan8", [11 16 23 32], ...
%!              "sofspa10", [4 6 8 10], "ruth3", [256 362 512 724], ...
%!              "candyrozmus4", [32 64 128], "mclachlan4", [16 32 64], ...
%!              "blanesmoan6", [8 16 32]);
%! check_orders (names, Ns, @kep, T, y0k, yT, symplecticset ("Separable", "on"), 1e-13);

%!test
%! ## the same on the pendulum H = p^2/2 - cos q from (2, 0) to t = 1.5,
%! ## exact solution by ellipj (sofspa10: N = 3..5, errors 4e-11 to
%! ## 2.5e-13).  Measured: 2.00 4.00 4.01 5.99 8.00 8.07 9.89 3.00 4.00
%! ## 3.99 6.02
%! T = 1.5;  yT = pendulum_exact (T, 2);
%! Ns = struct ("verlet", [16 32 64], "yoshida4", [16 32 64], ...
%!              "suzuki4", [8 16 32], "kahanli6", [8 16 32], ...
%!              "kahanli8", [4 6 8], "mclachlan8", [4 6 8 12], ...
%!              "sofspa10", [3 4 5], "ruth3", [24 48 96], ...
%!              "candyrozmus4", [12 24 48], "mclachlan4", [8 16 32], ...
%!              "blanesmoan6", [4 6 8 12]);
%! check_orders (names, Ns, @pend, T, [2; 0], yT, symplecticset ("Separable", "on"), 1e-13);

%!test
%! ## the compositions on the implicit path (Separable off: Stormer-Verlet
%! ## stages by Newton's method), Kepler as above (a separable H: Newton
%! ## ends after one iteration; the next test has a non-separable one).
%! ## Measured: 2.00 3.99 3.99 6.00 7.99 7.92 9.98
%! T = 1;  yT = kepler_exact (T, e);
%! Ns = struct ("verlet", [32 64 128], "yoshida4", [32 64 128], ...
%!              "suzuki4", [16 32 64], "kahanli6", [16 32 64], ...
%!              "kahanli8", [8 11 16 23], "mclachlan8", [11 16 23 32], ...
%!              "sofspa10", [4 6 8 10]);
%! check_orders (comps, Ns, @kep, T, y0k, yT, symplecticset (), 0);

%!test
%! ## and on a non-separable H (H = |p|^2/2 (1 + |q|^2/4) + |q|^4/8), where
%! ## each Verlet stage takes Newton iterations; reference ode45 at
%! ## tight tolerances (error ~1e-13, the errors fitted >= 8e-9).
%! ## Measured: 4.01, 5.98
%! y0 = [0.5; -0.3; 0.4; 0.7];  T = 2;
%! [~, y] = ode45 (@nonsep, [0 T], y0, odeset ("RelTol", 1e-13, "AbsTol", 1e-13));
%! yT = y(end, :).';
%! Ns = struct ("yoshida4", [10 20 40], "kahanli6", [5 10 20]);
%! check_orders (fieldnames (Ns).', Ns, @nonsep, T, y0, yT, symplecticset (), 1e-10);

%!test
%! ## mclachlan4 and blanesmoan6 are Runge-Kutta-Nystrom methods: their
%! ## orders hold for T = |p|^2/2 only.  With T = p^4/4 they drop to 3 and
%! ## 4, where the splittings of any T keep theirs; reference ode45 at
%! ## tight tolerances.  Measured: ruth3 2.98, candyrozmus4 3.96,
%! ## mclachlan4 2.95, blanesmoan6 4.01
%! f = @(t, y) [y(2)^3; -sin(y(1))];
%! y0 = [1; 0.8];  T = 2;
%! [~, y] = ode45 (f, [0 T], y0, odeset ("RelTol", 1e-13, "AbsTol", 1e-13));
%! yT = y(end, :).';
%! expect = struct ("ruth3", 3, "candyrozmus4", 4, "mclachlan4", 3, "blanesmoan6", 4);
%! for nm = fieldnames (expect).'
%!   N = [8 16 32];  err = zeros (size (N));
%!   for i = 1:numel (N)
%!     o = symplecticset ("TimeStepNumber", N(i), "Separable", "on", "Method", nm{1});
%!     err(i) = norm (last_row (@odeSV, f, [0 T], y0, o) - yT, Inf);
%!   endfor
%!   s = fitted_slope (N, err);
%!   assert (abs (s - expect.(nm{1})) <= 0.3, "%s: slope %.2f, errors %s",
%!           nm{1}, s, mat2str (err, 3));
%! endfor

## ----------------------------------------------------------------- symplecticity
%!test
%! ## the one-step map M = dy1/dy0 satisfies M' J M = J: explicit steps on
%! ## Kepler for every method, implicit ones on a non-separable H for the
%! ## compositions (measured: 2e-13 to 1.4e-12, the error of the finite
%! ## differences); a non-symplectic map of the same size, a step of the
%! ## classical Runge-Kutta method, misses by 1.5e-6
%! J = [zeros(2), eye(2); -eye(2), zeros(2)];
%! y0 = [0.8; 0.3; -0.2; 1.1];  h = 0.1;
%! for k = 1:numel (names)
%!   o = symplecticset ("TimeStepSize", h, "TimeStepNumber", 1, ...
%!                      "Separable", "on", "Method", names{k});
%!   M = step_jacobian (@(y) last_row (@odeSV, @kep, [0 h], y, o), y0);
%!   assert (norm (M.' * J * M - J) <= 1e-11, "%s: %g", names{k},
%!           norm (M.' * J * M - J));
%!   assert (norm (M - eye (4)) > 0.05);
%! endfor
%! y0 = [0.5; -0.3; 0.4; 0.7];  h = 0.2;
%! for k = 1:numel (comps)
%!   o = symplecticset ("TimeStepSize", h, "TimeStepNumber", 1, ...
%!                      "Method", comps{k});
%!   M = step_jacobian (@(y) last_row (@odeSV, @nonsep, [0 h], y, o), y0);
%!   assert (norm (M.' * J * M - J) <= 1e-11, "%s implicit: %g", comps{k},
%!           norm (M.' * J * M - J));
%!   assert (norm (M - eye (4)) > 0.05);
%! endfor
%! ## the control: one step of the classical Runge-Kutta method
%! M = step_jacobian (@(y) rk4_step (@nonsep, y, h), y0);
%! assert (norm (M.' * J * M - J) > 1e-6);

## ----------------------------------------------------------------- reversibility
%!test
%! ## N steps forward, N back from the end: the symmetric methods return
%! ## to y0 to round-off (measured: 1.5e-17 to 2.5e-15), ruth3 and
%! ## mclachlan4 (not symmetric) do not (4.6e-4 and 1.0e-6)
%! N = 10;  h = 0.1;
%! for k = 1:numel (names)
%!   m = mcoefs (names{k});
%!   o = symplecticset ("TimeStepSize", h, "Separable", "on", "Method", names{k});
%!   [t, y] = odeSV (@kep, [0, N*h], y0k, o);
%!   assert (numel (t), N + 1);
%!   [tb, yb] = odeSV (@kep, [N*h, 0], y(end, :).', o);
%!   assert (numel (tb), N + 1);
%!   d = norm (yb(end, :).' - y0k) / norm (y0k);
%!   if (m.sym)
%!     assert (d <= 1e-13, "%s: %g", names{k}, d);
%!   else
%!     assert (d > 1e-8, "%s: %g", names{k}, d);
%!   endif
%! endfor

%!test
%! ## the implicit compositions on the non-separable H (the solves are
%! ## converged to NewtonTol/1000; measured 1.1e-16, 5.0e-16, 4.4e-16)
%! N = 10;  h = 0.1;  y0 = [0.5; -0.3; 0.4; 0.7];
%! for nm = {"verlet", "yoshida4", "kahanli6"}
%!   o = symplecticset ("TimeStepSize", h, "Method", nm{1});
%!   [~, y] = odeSV (@nonsep, [0, N*h], y0, o);
%!   [~, yb] = odeSV (@nonsep, [N*h, 0], y(end, :).', o);
%!   d = norm (yb(end, :).' - y0) / norm (y0);
%!   assert (d <= 1e-13, "%s: %g", nm{1}, d);
%!   assert (norm (y(end, :).' - y0) > 0.1);
%! endfor

## ----------------------------------------------------------------- the steps
%!test
%! ## the first steps on Kepler against the m-code stepper with its own
%! ## coefficients: explicit first-order form for every method, the
%! ## implicit path (Separable off) for the compositions
%! h = 0.1;
%! for k = 1:numel (names)
%!   m = mcoefs (names{k});
%!   ym = zeros (4, 3);  y = y0k;
%!   for i = 1:3
%!     y = mstep (m, @(q) -q / norm (q)^3, y, h);
%!     ym(:, i) = y;
%!   endfor
%!   o = symplecticset ("TimeStepSize", h, "TimeStepNumber", 3, ...
%!                      "Separable", "on", "Method", names{k});
%!   sol = odeSV (@kep, [0 1], y0k, o);
%!   assert (sol.x, (0:3) * h, 1e-15);
%!   d = norm (sol.y(:, 2:end) - ym, Inf) / norm (ym, Inf);
%!   assert (d <= 1e-14, "%s: %g", names{k}, d);
%!   ## the step is not that of another method
%!   if (k > 1)
%!     assert (norm (sol.y(:, 2) - mstep (mcoefs ("verlet"), @(q) -q / norm (q)^3, y0k, h)) > 1e-6);
%!   endif
%!   assert (sol.method, names{k});
%!   assert (sol.order, m.order);
%!   if (m.kind == "c")
%!     sol = odeSV (@kep, [0 1], y0k, symplecticset (o, "Separable", "off"));
%!     d = norm (sol.y(:, 2:end) - ym, Inf) / norm (ym, Inf);
%!     assert (d <= 1e-13, "%s implicit: %g", names{k}, d);
%!   endif
%! endfor

%!test
%! ## names in any case
%! o = symplecticset ("TimeStepSize", 0.1, "TimeStepNumber", 2, "Separable", "on");
%! s1 = odeSV (@kep, [0 1], y0k, symplecticset (o, "Method", "yoshida4"));
%! s2 = odeSV (@kep, [0 1], y0k, symplecticset (o, "Method", "YoShiDa4"));
%! assert (s2.y, s1.y);
%! ## verlet by name is the default method, and the one that takes
%! ## adaptive steps too
%! s1 = odeSV (@kep, [0 1], y0k, o);
%! s2 = odeSV (@kep, [0 1], y0k, symplecticset (o, "Method", "verlet"));
%! assert (s2.y, s1.y);
%! o = symplecticset ("RelTol", 1e-6, "AbsTol", 1e-8, "Separable", "on");
%! s1 = odeSV (@kep, [0 1], y0k, o);
%! s2 = odeSV (@kep, [0 1], y0k, symplecticset (o, "Method", "Verlet"));
%! assert (s2.y, s1.y);
%! assert (s2.stats.nsteps > 10 && numel (unique (round (diff (s2.x) * 1e12))) > 1);

## ----------------------------------------------------------------- SecondOrder
%!test
%! ## calls per step with SecondOrder: one per force stage (first same as
%! ## last), counted by a global counter in FCN (and in sol.stats.nfevals)
%! ## between runs of N and 2N steps: the compositions s (verlet 1 ...
%! ## sofspa10 35), ruth3 3, candyrozmus4 3, mclachlan4 4, blanesmoan6 11;
%! ## the first-order form calls FCN for each drift as well
%! global TM_CALLS TM_COLS
%! N = 20;  h = 0.01;
%! for k = 1:numel (names)
%!   m = mcoefs (names{k});
%!   c = zeros (1, 2);  nf = c;
%!   for j = 1:2
%!     TM_CALLS = 0;  TM_COLS = 0;
%!     o = symplecticset ("TimeStepSize", h, "TimeStepNumber", j*N, ...
%!                        "SecondOrder", "on", "Method", names{k});
%!     sol = odeSV (@kep_acc, [0 1], y0k, o);
%!     c(j) = TM_CALLS;  nf(j) = sol.stats.nfevals;
%!   endfor
%!   assert (c, nf);
%!   assert ((c(2) - c(1)) / N == m.nf, "%s: %g calls per step", names{k},
%!           (c(2) - c(1)) / N);
%!   ## the first-order form: a call for each drift too (a composition 2 s)
%!   o = symplecticset (o, "SecondOrder", "off", "Separable", "on");
%!   s1 = odeSV (@kep, [0 1], y0k, symplecticset (o, "TimeStepNumber", N));
%!   s2 = odeSV (@kep, [0 1], y0k, symplecticset (o, "TimeStepNumber", 2*N));
%!   c = (s2.stats.nfevals - s1.stats.nfevals) / N;
%!   assert (c == m.nf + nnz (m.a), "%s: %g calls per step, first-order form",
%!           names{k}, c);
%! endfor
%! ## odeSE: one call a step
%! c = zeros (1, 2);
%! for j = 1:2
%!   TM_CALLS = 0;
%!   sol = odeSE (@kep_acc, [0 1], y0k, symplecticset ("TimeStepSize", h, ...
%!                "TimeStepNumber", j*N, "SecondOrder", "on"));
%!   c(j) = TM_CALLS;
%! endfor
%! assert ((c(2) - c(1)) / N == 1);
%! clear -global TM_CALLS TM_COLS

%!test
%! ## SecondOrder gives the steps of the first-order form with f = [v; a(q)]
%! ## (Separable on), to round-off
%! global TM_CALLS TM_COLS
%! o = symplecticset ("TimeStepSize", 0.05, "TimeStepNumber", 20);
%! s1 = odeSE (@kep, [0 1], y0k, symplecticset (o, "Separable", "on"));
%! s2 = odeSE (@kep_acc, [0 1], y0k, symplecticset (o, "SecondOrder", "on"));
%! assert (norm (s2.y - s1.y, Inf) <= 1e-14 * norm (s1.y, Inf), "odeSE: %g",
%!         norm (s2.y - s1.y, Inf));
%! assert (s2.x, s1.x);
%! for nm = {"verlet", "yoshida4", "kahanli8", "ruth3", "candyrozmus4", "blanesmoan6"}
%!   o = symplecticset (o, "Method", nm{1});
%!   s1 = odeSV (@kep, [0 1], y0k, symplecticset (o, "Separable", "on"));
%!   s2 = odeSV (@kep_acc, [0 1], y0k, symplecticset (o, "SecondOrder", "on"));
%!   d = norm (s2.y - s1.y, Inf) / norm (s1.y, Inf);
%!   assert (d <= 1e-14, "%s: %g", nm{1}, d);
%!   ## Separable on as well is accepted
%!   s3 = odeSV (@kep_acc, [0 1], y0k, symplecticset (o, "SecondOrder", "on", ...
%!                                                    "Separable", "on"));
%!   assert (s3.y, s2.y);
%! endfor
%! clear -global TM_CALLS TM_COLS

%!test
%! ## Vectorized SecondOrder: FCN gets Q of d-by-k (kep_acc checks the
%! ## sizes) and gives the same steps
%! global TM_CALLS TM_COLS
%! for nm = {"verlet", "yoshida4", "mclachlan4"}
%!   o = symplecticset ("TimeStepSize", 0.05, "TimeStepNumber", 20, ...
%!                      "SecondOrder", "on", "Method", nm{1});
%!   TM_COLS = 0;
%!   s1 = odeSV (@kep_acc, [0 1], y0k, o);
%!   assert (TM_COLS, 1);
%!   s2 = odeSV (@kep_acc, [0 1], y0k, symplecticset (o, "Vectorized", "on"));
%!   assert (TM_COLS, 2);   # the check of Vectorized at the start
%!   assert (s2.y, s1.y, 1e-15);
%! endfor
%! o = symplecticset ("TimeStepSize", 0.05, "TimeStepNumber", 20, "SecondOrder", "on");
%! s1 = odeSE (@kep_acc, [0 1], y0k, o);
%! TM_COLS = 0;
%! s2 = odeSE (@kep_acc, [0 1], y0k, symplecticset (o, "Vectorized", "on"));
%! assert (TM_COLS, 2);
%! assert (s2.y, s1.y, 1e-15);
%! clear -global TM_CALLS TM_COLS

%!test
%! ## SecondOrder in d = 3 against the exact solution of an anisotropic
%! ## oscillator, with Events, OutputFcn and Hamiltonian getting y = [q; v]
%! w = [1; 2; 3];  q0 = [1; 0.5; -0.2];  v0 = [0; 0.3; 0.1];
%! ex = @(t) [q0 .* cos(w*t) + v0 ./ w .* sin(w*t); -q0 .* w .* sin(w*t) + v0 .* cos(w*t)];
%! global TM_ROWS
%! TM_ROWS = [];
%! o = symplecticset ("TimeStepSize", 0.01, "SecondOrder", "on", "Method", "yoshida4", ...
%!                    "Hamiltonian", @(t, y) sum (y(4:6).^2 + (w .* y(1:3)).^2) / 2, ...
%!                    "Events", @(t, y) deal (y(1), 0, -1), "OutputFcn", @rows6);
%! sol = odeSV (@(t, q) -w.^2 .* q, [0 3], [q0; v0], o);
%! assert (size (sol.y, 1), 6);
%! assert (! isempty (TM_ROWS) && all (TM_ROWS == 6));
%! clear -global TM_ROWS
%! ## measured: 2.9e-7, max_dH 1.4e-8 (relative), event 1.0e-9 and 5.2e-8
%! assert (norm (sol.y(:, end) - ex (3), Inf) < 1e-6);
%! H = sum (sol.y(4:6, :).^2 + (w .* sol.y(1:3, :)).^2, 1) / 2;
%! assert (sol.H(:).', H, 1e-14);
%! assert (sol.stats.max_dH, max (abs (H - H(1))) / H(1), 1e-15);
%! assert (sol.stats.max_dH < 1e-7);
%! assert (sol.xe, pi/2, 1e-8);
%! assert (sol.ye, ex (sol.xe).', 1e-6);

## ----------------------------------------------------------------- CompensatedSummation
%!test
%! ## the same steps as without, to round-off, on a short run
%! for nm = {"verlet", "yoshida4", "kahanli6", "ruth3", "blanesmoan6"}
%!   o = symplecticset ("TimeStepSize", 0.01, "TimeStepNumber", 100, "Method", nm{1});
%!   for form = {{@kep, "Separable"}, {@kep_acc, "SecondOrder"}}
%!     o1 = symplecticset (o, form{1}{2}, "on");
%!     s1 = odeSV (form{1}{1}, [0 1], y0k, o1);
%!     s2 = odeSV (form{1}{1}, [0 1], y0k, symplecticset (o1, "CompensatedSummation", "on"));
%!     d = norm (s2.y - s1.y, Inf) / norm (s1.y, Inf);
%!     assert (d <= 1e-12, "%s, %s: %g", nm{1}, form{1}{2}, d);
%!     assert (s2.stats.nfevals, s1.stats.nfevals);
%!   endfor
%! endfor
%! clear -global TM_CALLS TM_COLS

%!test
%! ## long runs of the harmonic oscillator, steps so small that the
%! ## truncation error is negligible: compensated sums leave a far smaller
%! ## round-off.  Verlet: its exact invariant (p^2 + (1 - h^2/4) q^2)/2,
%! ## 2e5 steps of 1e-3 (measured: 2.2e-14 plain, 1.1e-16 compensated);
%! ## yoshida4: energy and the exact solution after 1e5 steps of 1e-4
%! ## (measured: 4.9e-14 and 3.7e-14 plain, 1.1e-16 and 7.8e-16
%! ## compensated)
%! a = @(t, q) -q;
%! h = 1e-3;  N = 2e5;
%! o = symplecticset ("TimeStepSize", h, "TimeStepNumber", N, "SecondOrder", "on");
%! dI = zeros (1, 2);  cs = {"off", "on"};
%! for j = 1:2
%!   [~, y] = odeSV (a, [0 1], [1; 0], symplecticset (o, "CompensatedSummation", cs{j}));
%!   I = (y(:, 2).^2 + (1 - h^2/4) * y(:, 1).^2) / 2;
%!   dI(j) = max (abs (I - I(1)));
%! endfor
%! assert (dI(2) * 20 < dI(1), "verlet: %s", mat2str (dI, 3));
%! h = 1e-4;  N = 1e5;
%! o = symplecticset ("TimeStepSize", h, "TimeStepNumber", N, "SecondOrder", "on", ...
%!                    "Method", "yoshida4");
%! dE = zeros (1, 2);  err = dE;
%! for j = 1:2
%!   [t, y] = odeSV (a, [0 1], [1; 0], symplecticset (o, "CompensatedSummation", cs{j}));
%!   dE(j) = max (abs ((y(:, 1).^2 + y(:, 2).^2) / 2 - 0.5));
%!   err(j) = norm (y(end, :) - [cos(t(end)), -sin(t(end))], Inf);
%! endfor
%! assert (dE(2) * 20 < dE(1), "yoshida4 energy: %s", mat2str (dE, 3));
%! assert (err(2) * 10 < err(1), "yoshida4 error: %s", mat2str (err, 3));

## ----------------------------------------------------------------- events, dense output
%!test
%! ## yoshida4 on the harmonic oscillator: the events q = 0 (t = pi/2,
%! ## 3pi/2) are located to the accuracy of the method (measured: 2.0e-6
%! ## and 1.2e-7, the errors on the steps), not to that of a linear
%! ## interpolation (h^2/8 = 3.1e-4); halving h divides the event error
%! ## by 16
%! f = @(t, y) [y(2); -y(1)];
%! ev = @(t, y) deal (y(1), 0, 0);
%! err = zeros (1, 2);  gerr = err;
%! hs = [0.05 0.025];
%! for i = 1:2
%!   o = symplecticset ("TimeStepSize", hs(i), "Separable", "on", ...
%!                      "Method", "yoshida4", "Events", ev);
%!   [t, y, te, ye, ie] = odeSV (f, [0 5], [1; 0], o);
%!   assert (numel (te), 2);
%!   assert (ie(:).', [1 1]);
%!   err(i) = max (abs (te(:).' - [pi/2, 3*pi/2]));
%!   gerr(i) = max (max (abs (y - [cos(t), -sin(t)])));
%!   ## the event rows are on the solution
%!   assert (ye, [cos(te(:)), -sin(te(:))], 2 * gerr(i) + hs(i)^4);
%!   assert (err(i) <= 2 * gerr(i) + hs(i)^4, "h = %g: %g (grid %g)", hs(i),
%!           err(i), gerr(i));
%! endfor
%! assert (err(1) < 2e-5);
%! assert (log2 (err(1) / err(2)) > 3.5, "event errors %s", mat2str (err, 3));

%!test
%! ## Refine rows and Dense output (cubic Hermite between the steps) are
%! ## close to the exact solution, to the method's error plus h^4/384
%! ## (measured: 1.3e-6, on the steps 2.0e-6; a linear interpolation
%! ## would miss by h^2/8 = 3.1e-4)
%! f = @(t, y) [y(2); -y(1)];
%! h = 0.05;
%! o = symplecticset ("TimeStepSize", h, "Separable", "on", "Method", "yoshida4");
%! [t, y] = odeSV (f, [0 3], [1; 0], o);
%! gerr = max (max (abs (y - [cos(t), -sin(t)])));
%! [tr, yr] = odeSV (f, [0 3], [1; 0], symplecticset (o, "Refine", 4));
%! assert (numel (tr), 4 * (numel (t) - 1) + 1);
%! assert (yr(1:4:end, :), y, 1e-15);
%! mid = setdiff (1:numel (tr), 1:4:numel (tr));
%! assert (all (abs (tr(mid) / h - round (tr(mid) / h)) > 0.2));
%! rerr = max (max (abs (yr(mid, :) - [cos(tr(mid)), -sin(tr(mid))])));
%! assert (rerr <= 2 * (gerr + h^4/384), "Refine: %g (grid %g)", rerr, gerr);
%! assert (rerr < 2e-5);
%! sol = odeSV (f, [0 3], [1; 0], symplecticset (o, "Dense", "on"));
%! tt = linspace (0.03, 2.97, 50);
%! yy = symdeval (sol, tt);
%! derr = max (max (abs (yy - [cos(tt); -sin(tt)])));
%! assert (derr <= 2 * (gerr + h^4/384), "Dense: %g (grid %g)", derr, gerr);
%! ## output times from the dense output: the steps stay those of [0 3]
%! [t2, y2] = odeSV (f, [0 0.123 1.5 3], [1; 0], o);
%! assert (y2(end, :), y(end, :), 1e-15);
%! assert (y2, [cos(t2), -sin(t2)], 2 * (gerr + h^4/384));

## ----------------------------------------------------------------- errors
%!error <odeSV.*Method>
%! odeSV (@kep, [0 1], [0.5; 0; 0; 1.7], symplecticset ("Method", "nosuch", "TimeStepSize", 0.1));
%!error <odeSV.*Method>
%! odeSV (@kep, [0 1], [0.5; 0; 0; 1.7], symplecticset ("Method", 4, "TimeStepSize", 0.1));
%!error <odeSV.*Method.*Separable|odeSV.*Separable.*Method>
%! odeSV (@kep, [0 1], [0.5; 0; 0; 1.7], symplecticset ("Method", "ruth3", "TimeStepSize", 0.1));
%!error <odeSV.*Method.*Separable|odeSV.*Separable.*Method>
%! odeSV (@kep, [0 1], [0.5; 0; 0; 1.7], symplecticset ("Method", "blanesmoan6", "TimeStepSize", 0.1, "Separable", "off"));
%!error <odeSV.*TimeStepSize>
%! odeSV (@kep, [0 1], [0.5; 0; 0; 1.7], symplecticset ("Method", "yoshida4", "Separable", "on"));
%!error <odeSV.*TimeStepSize>
%! odeSV (@kep, [0 1], [0.5; 0; 0; 1.7], symplecticset ("Method", "candyrozmus4", "Separable", "on", "RelTol", 1e-6));
%!error <odeSV.*CompensatedSummation.*Separable>
%! odeSV (@kep, [0 1], [0.5; 0; 0; 1.7], symplecticset ("CompensatedSummation", "on", "TimeStepSize", 0.1));
%!error <odeSV.*CompensatedSummation.*TimeStepSize>
%! odeSV (@kep, [0 1], [0.5; 0; 0; 1.7], symplecticset ("CompensatedSummation", "on", "Separable", "on"));
%!error <odeSV.*SecondOrder.*Separable>
%! odeSV (@(t, q) -q, [0 1], [1; 0], symplecticset ("SecondOrder", "on", "Separable", "off", "TimeStepSize", 0.1));
%!error <odeSE.*SecondOrder.*Separable>
%! odeSE (@(t, q) -q, [0 1], [1; 0], symplecticset ("SecondOrder", "on", "Separable", "off", "TimeStepSize", 0.1));
%!error <odeSV.*acceleration.*2>
%! odeSV (@(t, q) [q; 1], [0 1], [1; 0; 0; 1], symplecticset ("SecondOrder", "on", "TimeStepSize", 0.1));
%!error <odeSV.*acceleration.*2>
%! odeSV (@(t, q) q(1), [0 1], [1; 0; 0; 1], symplecticset ("SecondOrder", "on", "TimeStepSize", 0.1, "Method", "yoshida4"));
%!error <odeSE.*acceleration.*2>
%! odeSE (@(t, q) [q; 1], [0 1], [1; 0; 0; 1], symplecticset ("SecondOrder", "on", "TimeStepSize", 0.1));
%!error <odeSV.*SecondOrder>
%! odeSV (@(t, q) -q, [0 1], [1; 0], symplecticset ("SecondOrder", "maybe", "TimeStepSize", 0.1));

%!test
%! ## odeSE has no Method, nor CompensatedSummation: as the options of the
%! ## other solvers, they are ignored, with a warning naming odeSV
%! o = symplecticset ("TimeStepSize", 0.1, "Separable", "on");
%! s1 = odeSE (@kep, [0 1], y0k, o);
%! lastwarn ("");
%! evalc ("s2 = odeSE (@kep, [0 1], y0k, symplecticset (o, 'Method', 'yoshida4', 'CompensatedSummation', 'on'));");
%! [msg, id] = lastwarn ();
%! assert (id, "symplectic:ignored-option");
%! assert (msg, "odeSE: option CompensatedSummation is used by odeSV only; ignored");
%! assert (s2.y, s1.y);

## odeSPVI takes FCN as Hamilton's equations only: SecondOrder, which
## changes what FCN means, is refused rather than ignored
%!error <odeSPVI.*SecondOrder>
%! odeSPVI (@(t, q) -q, [0 1], [1; 0], symplecticset ("SecondOrder", "on"));
