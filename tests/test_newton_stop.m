## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## The implicit steps of odeSE and odeSV (a non-separable H) stop only
## when their unknowns are within the Newton tolerance: every step of a
## run against the same step taken again from its start, alone, with
## NewtonTol 1e-15 (its solves converged to round-off), relative to the
## size of the state or of its change.  Fixed steps solve to 1e-3 of
## NewtonTol, adaptive ones to NewtonTol itself.  Before the solves
## checked their result by Newton's own test, at the result's scale, these
## steps missed by up to 7.3 (fixed) and 2.0 (adaptive) times that.

%!function dy = nonsep (t, y)
%!  ## H = p^2/2 (1 + q^2) + q^2/2
%!  q = y(1); p = y(2);
%!  dy = [p * (1 + q^2); -(p^2 * q + q)];
%!endfunction

%!function dy = nonsep2 (t, y)
%!  ## H = p1^2 (1 + q2^2)/2 + p2^2 (1 + q1^2)/2 + |q|^2/2 + 0.1 p1 p2 q1 q2
%!  q1 = y(1); q2 = y(2); p1 = y(3); p2 = y(4);
%!  dy = [p1 * (1 + q2^2) + 0.1 * p2 * q1 * q2;
%!        p2 * (1 + q1^2) + 0.1 * p1 * q1 * q2;
%!        -(p2^2 * q1 + q1 + 0.1 * p1 * p2 * q2);
%!        -(p1^2 * q2 + q2 + 0.1 * p1 * p2 * q1)];
%!endfunction

%!function H = nonsep2_hess (t, y)
%!  ## the Hessian of nonsep2's H, sparse: odeSE and odeSV solve by KLU
%!  q1 = y(1); q2 = y(2); p1 = y(3); p2 = y(4);
%!  a = 0.1 * p2 * q2;  b = 2 * p2 * q1 + 0.1 * p1 * q2;
%!  c = 2 * p1 * q2 + 0.1 * p2 * q1;  e = 0.1 * p1 * q1;
%!  H = sparse ([p2^2 + 1, 0.1 * p1 * p2, a, b;
%!               0.1 * p1 * p2, p1^2 + 1, c, e;
%!               a, c, 1 + q2^2, 0.1 * q1 * q2;
%!               b, e, 0.1 * q1 * q2, 1 + q1^2]);
%!endfunction

## the largest miss of the steps of (t, y) against each step alone at
## NewtonTol 1e-15, relative to max (|y_k|, |y_{k+1} - y_k|)
%!function w = worst_step (solver, f, t, y)
%!  w = 0;
%!  for k = 1:numel (t) - 1
%!    o = symplecticset ("TimeStepSize", t(k+1) - t(k), "NewtonTol", 1e-15);
%!    [~, y1] = solver (f, [t(k), t(k+1)], y(k, :).', o);
%!    s = max (norm (y(k, :), Inf), norm (y(k+1, :) - y(k, :), Inf));
%!    w = max (w, norm (y1(end, :) - y(k+1, :), Inf) / s);
%!  endfor
%!endfunction

%!test
%! ## fixed steps: 100 of h, NewtonTol 1e-8 and 1e-6
%! solvers = {@odeSE, @odeSV};
%! fs = {@nonsep, @nonsep2};
%! y0s = {[0.8; 0.6], [0.8; -0.3; 0.6; 0.9]};
%! for si = 1:2
%!   for fi = 1:2
%!     for h = [0.1 0.3]
%!       for ntol = [1e-8 1e-6]
%!         o = symplecticset ("TimeStepSize", h, "NewtonTol", ntol);
%!         [t, y] = solvers{si} (fs{fi}, [0, 100*h], y0s{fi}, o);
%!         r = worst_step (solvers{si}, fs{fi}, t, y) / (1e-3 * ntol);
%!         assert (r <= 1.5, sprintf ("%s, f %d, h %g, NewtonTol %g: %.3g",
%!                 func2str (solvers{si}), fi, h, ntol, r));
%!       endfor
%!     endfor
%!   endfor
%! endfor

%!test
%! ## adaptive steps solve to NewtonTol itself
%! o = symplecticset ("RelTol", 1e-4, "AbsTol", 1e-6, "NewtonTol", 1e-8,
%!                    "Refine", 1);
%! [t, y] = odeSV (@nonsep, [0, 20], [0.8; 0.6], o);
%! assert (numel (t) > 500);
%! r = worst_step (@odeSV, @nonsep, t, y) / 1e-8;
%! assert (r <= 1.5, sprintf ("adaptive odeSV: %.3g", r));

%!test
%! ## the sparse path (a sparse Hessian: KLU's factors); before, up to
%! ## 3.8 times
%! y0 = [0.8; -0.3; 0.6; 0.9];
%! for ntol = [1e-8 1e-6]
%!   for solver = {@odeSE, @odeSV}
%!     o = symplecticset ("TimeStepSize", 0.3, "NewtonTol", ntol,
%!                        "HamiltonianHessFcn", @nonsep2_hess);
%!     [t, y] = solver{1} (@nonsep2, [0, 30], y0, o);
%!     r = worst_step (solver{1}, @nonsep2, t, y) / (1e-3 * ntol);
%!     assert (r <= 1.5, sprintf ("sparse %s, NewtonTol %g: %.3g",
%!             func2str (solver{1}), ntol, r));
%!   endfor
%! endfor

%!test
%! ## reversible steps solve as fixed ones do; before, up to 2.1 times
%! o = symplecticset ("StepControl", "reversible", "RelTol", 1e-2,
%!                    "NewtonTol", 1e-8, "Refine", 1);
%! [t, y] = odeSV (@nonsep, [0, 30], [0.8; 0.6], o);
%! assert (numel (t) > 500);
%! r = worst_step (@odeSV, @nonsep, t, y) / 1e-11;
%! assert (r <= 1.5, sprintf ("reversible: %.3g", r));

%!test
%! ## the test can fail: a NewtonTol 100 times looser than the one the
%! ## misses are measured against is seen
%! o = symplecticset ("TimeStepSize", 0.3, "NewtonTol", 1e-6);
%! [t, y] = odeSE (@nonsep, [0, 60], [0.8; 0.6], o);
%! assert (worst_step (@odeSE, @nonsep, t, y) / (1e-3 * 1e-8) > 1.5);

%!test
%! ## the check costs little: 6.3 (odeSE) and 5.4 (odeSV) corrections a
%! ## solve on these steps of finite-difference matrices kept from step to
%! ## step, 6.25 and 5.4 when the check was looser
%! for solver = {@odeSE, @odeSV}
%!   o = symplecticset ("TimeStepSize", 0.3, "NewtonTol", 1e-8);
%!   s = solver{1} (@nonsep2, [0, 60], [0.8; -0.3; 0.6; 0.9], o);
%!   nsolves = s.stats.nsteps * (1 + strcmp (func2str (solver{1}), "odeSV"));
%!   assert (s.stats.nnewton / nsolves <= 7,
%!           sprintf ("%s: %.3g", func2str (solver{1}),
%!                    s.stats.nnewton / nsolves));
%! endfor
