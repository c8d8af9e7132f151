## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## Sparse Jacobians and Hessians, and Newton's systems by stages (odeSPVI,
## NewtonSystem).  A sparse Df (HamiltonianHessFcn, FCN's second output, a
## Jacobian function or matrix, finite differences on a sparse JPattern)
## makes the pairs Q_DoFs = Nodes + 1 solve ceil(Nodes/2) stage systems of
## size 2d instead of the whole step system: every result here is checked
## against the same run with full matrices and NewtonSystem "full" (to
## 1e-12), against exact solutions, or against conserved quantities.
## That the stages served is read from the stats: each Newton iteration
## then solves ceil(Nodes/2) systems (nlinsols = ceil(Nodes/2) nnewton),
## the full system one (nlinsols = nnewton).

%!function [dy, H] = fpu (t, y)
%!  ## the chain of bench/fpu.m (fixed ends, V(r) = r^2/2 + r^4/4); its
%!  ## Hessian, sparse, as the second output
%!  d = rows (y) / 2;
%!  r = diff ([0; y(1:d); 0]);
%!  F = r + r.^3;
%!  dy = [y(d+1:end); F(2:end) - F(1:end-1)];
%!  if (nargout > 1)
%!    H = fpu_hess (t, y);
%!  endif
%!endfunction

%!function [dy, H] = fpu_full2 (t, y)
%!  ## the same with the Hessian full
%!  dy = fpu (t, y);
%!  if (nargout > 1)
%!    H = full (fpu_hess (t, y));
%!  endif
%!endfunction

%!function dy = fpu1 (t, y)
%!  dy = fpu (t, y);
%!endfunction

%!function K = fpu_K (q)
%!  ## d2V/dq2: tridiagonal, K = D' diag(V''(r)) D with r = D q
%!  d = numel (q);
%!  r = diff ([0; q; 0]);
%!  c = 1 + 3 * r.^2;
%!  K = spdiags ([-[c(2:d); 0], c(1:d) + c(2:d+1), -[0; c(2:d)]], -1:1, d, d);
%!endfunction

%!function H = fpu_hess (t, y)
%!  d = rows (y) / 2;
%!  H = blkdiag (fpu_K (y(1:d)), speye (d));
%!endfunction

%!function H = fpu_hess_full (t, y)
%!  H = full (fpu_hess (t, y));
%!endfunction

%!function Df = fpu_jac (t, y)
%!  ## df/dy = [0 I; -K 0]
%!  d = rows (y) / 2;
%!  Df = [sparse(d, d), speye(d); -fpu_K(y(1:d)), sparse(d, d)];
%!endfunction

%!function Df = fpu_jac_full (t, y)
%!  Df = full (fpu_jac (t, y));
%!endfunction

%!function H = fpu_hess_count (t, y)
%!  global SPARSE_HESS_CALLS
%!  SPARSE_HESS_CALLS++;
%!  H = fpu_hess (t, y);
%!endfunction

%!function H = fpu_hess_count_full (t, y)
%!  global SPARSE_HESS_CALLS
%!  SPARSE_HESS_CALLS++;
%!  H = fpu_hess_full (t, y);
%!endfunction

%!function E = fpu_energy (y)
%!  ## H of the chain at each row [q p] of y
%!  d = columns (y) / 2;
%!  z = zeros (rows (y), 1);
%!  r = diff ([z, y(:, 1:d), z], 1, 2);
%!  E = sum (y(:, d+1:end).^2, 2) / 2 + sum (r.^2/2 + r.^4/4, 2);
%!endfunction

%!function P = fpu_pattern (d)
%!  P = sparse (2*d, 2*d);
%!  P(1:d, d+1:end) = speye (d);
%!  P(d+1:end, 1:d) = spdiags (ones (d, 3), -1:1, d, d);
%!endfunction

%!function dy = ns1 (t, y)
%!  ## a non-separable H = sum p_i^2 (1 + q_i^2/4) / 2 + the chain's V
%!  d = rows (y) / 2;
%!  q = y(1:d);  p = y(d+1:end);
%!  r = diff ([0; q; 0]);
%!  F = r + r.^3;
%!  dy = [p .* (1 + q.^2/4); -p.^2 .* q / 4 + F(2:end) - F(1:end-1)];
%!endfunction

%!function H = ns_hess (t, y)
%!  d = rows (y) / 2;
%!  q = y(1:d);  p = y(d+1:end);
%!  H = [fpu_K(q) + spdiags(p.^2/4, 0, d, d), spdiags(p.*q/2, 0, d, d);
%!       spdiags(p.*q/2, 0, d, d), spdiags(1 + q.^2/4, 0, d, d)];
%!endfunction

%!function H = ns_hess_full (t, y)
%!  H = full (ns_hess (t, y));
%!endfunction

%!function E = ns_energy (y)
%!  d = columns (y) / 2;
%!  q = y(:, 1:d);  p = y(:, d+1:end);
%!  z = zeros (rows (y), 1);
%!  r = diff ([z, q, z], 1, 2);
%!  E = sum (p.^2 .* (1 + q.^2/4), 2) / 2 + sum (r.^2/2 + r.^4/4, 2);
%!endfunction

%!function A = fd_jac (f, y)
%!  ## df/dy by central differences (independent of the package)
%!  n = numel (y);  A = zeros (n);
%!  for j = 1:n
%!    e = zeros (n, 1);  e(j) = 1e-5;
%!    A(:, j) = (f (0, y + e) - f (0, y - e)) / 2e-5;
%!  endfor
%!endfunction

%!function e = relerr (a, b)
%!  e = max (abs (a(:) - b(:))) / max (abs (b(:)));
%!endfunction

%!function by_stages (s, m)
%!  ## each Newton iteration solved ceil(m/2) stage systems
%!  assert (s.stats.nnewton > 0);
%!  assert (s.stats.nlinsols, ceil (m/2) * s.stats.nnewton);
%!endfunction

%!function by_full (s)
%!  ## each Newton iteration solved the one whole system
%!  assert (s.stats.nnewton > 0);
%!  assert (s.stats.nlinsols, s.stats.nnewton);
%!endfunction

%!function y0 = fpu_y0 (d)
%!  ## a slow mode in q, a fast pattern in p (as tests/test_jpattern.m)
%!  y0 = [0.3 * sin((1:d)' * pi / (d+1)); 0.1 * cos((1:d)')];
%!endfunction

%!function s0 = fpu_ref ()
%!  ## the reference of the d = 40 runs: full Hessian, the whole system
%!  ## (the path as it was before stages), h = 0.05 to t = 2
%!  s0 = odeSPVI (@fpu1, [0 2], fpu_y0 (40), symplecticset ("TimeStepSize",
%!                0.05, "HamiltonianHessFcn", @fpu_hess_full, "NewtonSystem", "full"));
%!endfunction

%!function [d, y0, o] = chain40 ()
%!  ## the d = 40 chain and its fixed step
%!  d = 40;
%!  y0 = fpu_y0 (d);
%!  o = symplecticset ("TimeStepSize", 0.05);
%!endfunction

## ------------------------------------------------ the matrices themselves
%!test
%! ## the Hessian written here against finite differences of FCN, at a
%! ## state with large bonds (V'' far from 1); all sources agree
%! [d, y0, o] = chain40 ();
%! y = [0.8 * sin((1:d)' * 1.3); 0.5 * cos((1:d)' * 0.7)];
%! Hs = fpu_hess (0, y);
%! assert (issparse (Hs));
%! assert (size (Hs), [2*d, 2*d]);
%! assert (nnz (Hs), 3*d - 2 + d);
%! A = fd_jac (@fpu1, y);
%! J = [zeros(d), eye(d); -eye(d), zeros(d)];
%! assert (J * full (Hs), A, 1e-8 * norm (A, Inf));
%! ## not a trivial match: the q-q block is far from the linear chain's
%! K0 = full (spdiags (ones (d, 1) * [-1 2 -1], -1:1, d, d));
%! assert (norm (full (Hs(1:d, 1:d)) - K0, Inf) > 1);
%! assert (full (fpu_jac (0, y)), A, 1e-8 * norm (A, Inf));
%! [~, H2] = fpu (0, y);
%! assert (issparse (H2) && issparse (fpu_jac (0, y)));
%! assert (isequal (H2, Hs));
%! ## the same for the non-separable H
%! A = fd_jac (@ns1, y);
%! Hn = ns_hess (0, y);
%! assert (issparse (Hn));
%! assert (J * full (Hn), A, 1e-8 * norm (A, Inf));
%! assert (norm (full (Hn(1:d, d+1:end)), Inf) > 0.1);

## ------------------------------------------- sparse sources at d = 40, (4,3)
%!test
%! ## the reference ran the whole system
%! s0 = fpu_ref ();
%! by_full (s0);
%! assert (s0.stats.jacobian_source, "HamiltonianHessFcn");
%! assert (s0.x(end), 2);
%! assert (numel (s0.x), 41);

%!test
%! ## sparse HamiltonianHessFcn
%! [d, y0, o] = chain40 ();
%! s0 = fpu_ref ();
%! s = odeSPVI (@fpu1, [0 2], y0, symplecticset (o, "HamiltonianHessFcn", @fpu_hess));
%! assert (s.stats.jacobian_source, "HamiltonianHessFcn");
%! assert (s.x, s0.x);
%! assert (relerr (s.y(:, end), s0.y(:, end)) <= 1e-12);
%! assert (relerr (s.y, s0.y) <= 1e-12);
%! by_stages (s, 3);

%!test
%! ## sparse second output of FCN, against the full second output
%! [d, y0, o] = chain40 ();
%! s0 = fpu_ref ();
%! s = odeSPVI (@fpu, [0 2], y0, o);
%! sf = odeSPVI (@fpu_full2, [0 2], y0, symplecticset (o, "NewtonSystem", "full"));
%! assert (s.stats.jacobian_source, "second output of FCN (Hessian)");
%! assert (sf.stats.jacobian_source, "second output of FCN (Hessian)");
%! assert (relerr (s.y(:, end), sf.y(:, end)) <= 1e-12);
%! assert (relerr (s.y(:, end), s0.y(:, end)) <= 1e-12);
%! by_stages (s, 3);
%! by_full (sf);

%!test
%! ## sparse Jacobian function, against the full one
%! [d, y0, o] = chain40 ();
%! s0 = fpu_ref ();
%! s = odeSPVI (@fpu1, [0 2], y0, symplecticset (o, "Jacobian", @fpu_jac));
%! sf = odeSPVI (@fpu1, [0 2], y0, symplecticset (o, "Jacobian", @fpu_jac_full,
%!                                                "NewtonSystem", "full"));
%! assert (s.stats.jacobian_source, "Jacobian (function)");
%! assert (relerr (s.y(:, end), sf.y(:, end)) <= 1e-12);
%! assert (relerr (s.y(:, end), s0.y(:, end)) <= 1e-12);
%! by_stages (s, 3);
%! by_full (sf);

%!test
%! ## finite differences on a sparse JPattern give a sparse Df: one
%! ## evaluation of FCN per colour (3 for the chain), and at most one more
%! ## for f at the point, per matrix (each matrix: ceil(3/2) = 2 LUs);
%! ## against the same pattern full and the whole system
%! [d, y0, o] = chain40 ();
%! s0 = fpu_ref ();
%! P = fpu_pattern (d);
%! s = odeSPVI (@fpu1, [0 2], y0, symplecticset (o, "JPattern", P));
%! sf = odeSPVI (@fpu1, [0 2], y0, symplecticset (o, "JPattern", full (P),
%!                                                "NewtonSystem", "full"));
%! assert (s.stats.jacobian_source, "finite differences of FCN");
%! assert (relerr (s.y(:, end), sf.y(:, end)) <= 1e-12);
%! assert (relerr (s.y(:, end), s0.y(:, end)) <= 1e-12);
%! by_full (sf);
%! by_stages (s, 3);
%! k = s.stats.ndecomps / 2;
%! assert (k >= 1 && k == round (k));
%! assert (s.stats.nfdevals >= 3 && s.stats.nfdevals <= 4 * k);

%!test
%! ## other pairs Q_DoFs = Nodes + 1: sparse Hessian against full
%! [d, y0, o] = chain40 ();
%! s0 = fpu_ref ();
%! for nm = [2 1; 3 2; 6 5].'
%!   on = symplecticset (o, "Q_DoFs", nm(1), "Nodes", nm(2));
%!   s = odeSPVI (@fpu1, [0 2], y0, symplecticset (on, "HamiltonianHessFcn", @fpu_hess));
%!   sf = odeSPVI (@fpu1, [0 2], y0, symplecticset (on, "HamiltonianHessFcn",
%!                 @fpu_hess_full, "NewtonSystem", "full"));
%!   assert ([s.Q_DoFs, s.Nodes, s.order], [nm.', 2*nm(2)]);
%!   assert (relerr (s.y(:, end), sf.y(:, end)) <= 1e-12,
%!           "(%d,%d): %g", nm, relerr (s.y(:, end), sf.y(:, end)));
%!   by_stages (s, nm(2));
%!   by_full (sf);
%!   ## and the pair's own accuracy: far from (4,3)'s result at low order
%!   if (nm(2) < 3)
%!     assert (relerr (s.y(:, end), s0.y(:, end)) > 1e-10);
%!   endif
%! endfor

## ----------------------------------------- a linear chain, constant sparse Df
%!test
%! ## V = r^2/2: f = A y with A = [0 I; -K0 0] sparse, given as the
%! ## Jacobian matrix.  On a linear system (4,3) (Gauss collocation with
%! ## 3 nodes) is the (3,3) Pade approximant of exp(h A): the steps
%! ## against R(hA)^N y0 to round-off, against expm (t A) y0 to order 6
%! ## (measured 2.8e-11 at h = 0.1, 4.4e-13 at h = 0.05; 3.6e-15 from
%! ## R(hA)^N y0)
%! n = 20;
%! K0 = spdiags (ones (n, 1) * [-1 2 -1], -1:1, n, n);
%! A = [sparse(n, n), speye(n); -K0, sparse(n, n)];
%! f = @(t, y) A * y;
%! z0 = [sin((1:n)' * pi / (n+1)); 0.2 * cos((1:n)')];
%! yex = expm (2 * full (A)) * z0;
%! err = [];
%! for h = [0.1 0.05]
%!   s = odeSPVI (f, [0 2], z0, symplecticset ("TimeStepSize", h, "Jacobian", A));
%!   sf = odeSPVI (f, [0 2], z0, symplecticset ("TimeStepSize", h, "Jacobian",
%!                 full (A), "NewtonSystem", "full"));
%!   assert (s.stats.jacobian_source, "Jacobian (constant matrix)");
%!   Z = h * full (A);  I = eye (2*n);
%!   R = (I - Z/2 + Z^2/10 - Z^3/120) \ (I + Z/2 + Z^2/10 + Z^3/120);
%!   assert (s.y(:, end), R^round (2/h) * z0, 1e-13);
%!   assert (relerr (s.y(:, end), sf.y(:, end)) <= 1e-12);
%!   by_stages (s, 3);
%!   by_full (sf);
%!   err(end+1) = norm (s.y(:, end) - yex, Inf);
%! endfor
%! assert (err(1) < 3e-10 && err(2) < 5e-12);
%! assert (abs (log2 (err(1) / err(2)) - 6) <= 0.3);

## ------------------------------------------------------------------ adaptive
%!test
%! ## adaptive steps with a sparse Hessian: as with full matrices and the
%! ## whole system, and as a reference of (4,3) at fixed h = 0.01 on the
%! ## whole system (error about 1e-14); the energy kept to the tolerance
%! [d, y0, o] = chain40 ();
%! oa = symplecticset ("RelTol", 1e-8, "AbsTol", 1e-10);
%! s = odeSPVI (@fpu1, [0 5], y0, symplecticset (oa, "HamiltonianHessFcn", @fpu_hess));
%! sf = odeSPVI (@fpu1, [0 5], y0, symplecticset (oa, "HamiltonianHessFcn",
%!               @fpu_hess_full, "NewtonSystem", "full"));
%! [~, yr] = odeSPVI (@fpu1, [0 5], y0, symplecticset ("TimeStepSize", 0.01,
%!                    "HamiltonianHessFcn", @fpu_hess_full, "NewtonSystem", "full"));
%! ## (measured: 28 steps each, 8.6e-14 apart, 2.0e-12 from the
%! ## reference, energy 4.3e-14)
%! assert (s.x(end), 5);
%! assert (s.stats.nsteps > 10 && s.stats.nsteps < 200);
%! assert (relerr (s.y(:, end), sf.y(:, end)) <= 1e-7);
%! assert (relerr (s.y(:, end), yr(end, :).') <= 1e-7);
%! assert (relerr (sf.y(:, end), yr(end, :).') <= 1e-7);
%! E = fpu_energy (s.y.');
%! assert (max (abs (E - E(1))) / E(1) < 1e-11);

## ----------------------------------------------------------------- long run
%!test
%! ## d = 100, 5000 fixed steps h = 0.1, sparse Hessian: the energy error
%! ## bounded (measured 1.8e-12; 1.5e-12 in the first tenth, 1.8e-12 in
%! ## the last), no drift
%! n = 100;
%! z0 = fpu_y0 (n);
%! [t, y] = odeSPVI (@fpu1, [0 500], z0, symplecticset ("TimeStepSize", 0.1,
%!                   "HamiltonianHessFcn", @fpu_hess));
%! assert (numel (t), 5001);
%! assert (t(end), 500);
%! E = fpu_energy (y);
%! dE = abs (E - E(1)) / E(1);
%! k = 500;
%! assert (max (dE) < 2e-11);
%! assert (max (dE(end-k+1:end)) <= 2 * max (dE(2:k+1)));
%! assert (max (dE(2:k+1)) > 0);

## -------------------------------------------------------------------- large
%!test
%! ## d = 20000: the whole step system would have (6 d)^2 doubles (over
%! ## 100 GB); by sparse stages 3 steps take a fraction of a second.  The
%! ## energy to 1e-10 (measured 3.6e-13)
%! n = 20000;
%! z0 = fpu_y0 (n);
%! [t, y] = odeSPVI (@fpu1, [0 0.3], z0, symplecticset ("TimeStepSize", 0.1,
%!                   "HamiltonianHessFcn", @fpu_hess));
%! assert (t, [0; 0.1; 0.2; 0.3], 1e-15);
%! assert (size (y), [4, 2*n]);
%! E = fpu_energy (y);
%! assert (max (abs (E - E(1))) / E(1) < 1e-10);
%! ## it moved: q(0.3) = q0 + 0.3 p0 + O(0.3^2)
%! dq = y(end, 1:n).' - z0(1:n);
%! assert (norm (dq - 0.3 * z0(n+1:end), Inf) < 0.06);
%! assert (norm (dq, Inf) > 0.02);

## ------------------------------------------------------------- NewtonSystem
%!error <odeSPVI: NewtonSystem must be "auto", "full" or "stages", got "both">
%! t = odeSPVI (@fpu1, [0 1], [0.1; 0.2; 0; 0], symplecticset ("NewtonSystem", "both"));
%!error <odeSPVI: NewtonSystem "stages" needs Q_DoFs = Nodes \+ 1, got Q_DoFs = 3 with Nodes = 3>
%! t = odeSPVI (@fpu1, [0 1], [0.1; 0.2; 0; 0],
%!              symplecticset ("NewtonSystem", "stages", "Q_DoFs", 3, "Nodes", 3));

%!test
%! ## symplecticset knows the option (no warning of an unknown one)
%! lastwarn ("");
%! os = symplecticset ("NewtonSystem", "stages");
%! assert (os.NewtonSystem, "stages");
%! assert (lastwarn (), "");

%!test
%! ## "full" with a sparse Hessian: the whole system (the Hessian made
%! ## full), the same steps as the full Hessian's, and as auto's to 1e-12
%! [d, y0, o] = chain40 ();
%! s0 = fpu_ref ();
%! s = odeSPVI (@fpu1, [0 2], y0, symplecticset (o, "HamiltonianHessFcn",
%!              @fpu_hess, "NewtonSystem", "full"));
%! sa = odeSPVI (@fpu1, [0 2], y0, symplecticset (o, "HamiltonianHessFcn", @fpu_hess));
%! by_full (s);
%! by_stages (sa, 3);
%! assert (s.y, s0.y);
%! assert (relerr (s.y(:, end), sa.y(:, end)) <= 1e-12);
%! ## "stages" with the sparse Hessian is auto's path
%! ss = odeSPVI (@fpu1, [0 2], y0, symplecticset (o, "HamiltonianHessFcn",
%!               @fpu_hess, "NewtonSystem", "stages"));
%! assert (ss.y, sa.y);

%!test
%! ## Q_DoFs = 3, Nodes = 3 (no stages) with a sparse Hessian: the whole
%! ## step system, sparse (one solve per correction), the same steps as
%! ## the dense one to round-off; at d = 20000 too (dense: 115 GB)
%! [d, y0, o] = chain40 ();
%! s0 = fpu_ref ();
%! oq = symplecticset (o, "Q_DoFs", 3, "Nodes", 3);
%! s = odeSPVI (@fpu1, [0 2], y0, symplecticset (oq, "HamiltonianHessFcn", @fpu_hess));
%! sf = odeSPVI (@fpu1, [0 2], y0, symplecticset (oq, "HamiltonianHessFcn", @fpu_hess_full));
%! assert (relerr (s.y(:, end), sf.y(:, end)) <= 1e-12);
%! by_full (s);
%! dl = 20000;
%! yl = [0.1 * sin((1:dl)' * pi / (dl+1)); zeros(dl, 1)];
%! sl = odeSPVI (@fpu1, [0 0.15], yl, symplecticset ("TimeStepSize", 0.05,
%!               "Q_DoFs", 3, "Nodes", 3, "HamiltonianHessFcn", @fpu_hess));
%! assert (sl.x(end), 0.15, 1e-14);
%! E = fpu_energy ([yl, sl.y(:, end)].');
%! assert (abs (E(2) - E(1)) <= 1e-10 * E(1));
%! ## and it is the (3,3) method: order 4, not the reference's result
%! assert (s.order, 4);
%! assert (relerr (s.y(:, end), s0.y(:, end)) > 1e-10);
%! assert (relerr (s.y(:, end), s0.y(:, end)) < 1e-4);

## ------------------------------------------ dense matrices through stages
%!test
%! ## separable H, full Hessian, d = 120: auto takes the stages (6*120 >
%! ## 64; the same steps, bit for bit, as "stages"), against "full"
%! [d, y0, o] = chain40 ();
%! n = 120;
%! z0 = fpu_y0 (n);
%! oh = symplecticset (o, "HamiltonianHessFcn", @fpu_hess_full);
%! sa = odeSPVI (@fpu1, [0 1], z0, oh);
%! ss = odeSPVI (@fpu1, [0 1], z0, symplecticset (oh, "NewtonSystem", "stages"));
%! sf = odeSPVI (@fpu1, [0 1], z0, symplecticset (oh, "NewtonSystem", "full"));
%! assert (isequal (sa.y, ss.y));
%! by_stages (sa, 3);
%! by_full (sf);
%! assert (relerr (sa.y(:, end), sf.y(:, end)) <= 1e-12);
%! ## below the threshold auto keeps the whole system: d = 10, 6*10 <= 64
%! by_full (odeSPVI (@fpu1, [0 0.5], fpu_y0 (10), symplecticset (o, "HamiltonianHessFcn",
%!                   @fpu_hess_full)));

%!test
%! ## non-separable H (d2H/dqdp != 0), full Hessian: "stages" against
%! ## "full"; both conserve the energy to the method's accuracy
%! [d, y0, o] = chain40 ();
%! oh = symplecticset (o, "HamiltonianHessFcn", @ns_hess_full);
%! ss = odeSPVI (@ns1, [0 2], y0, symplecticset (oh, "NewtonSystem", "stages"));
%! sf = odeSPVI (@ns1, [0 2], y0, symplecticset (oh, "NewtonSystem", "full"));
%! by_stages (ss, 3);
%! by_full (sf);
%! assert (relerr (ss.y(:, end), sf.y(:, end)) <= 1e-12);
%! ## sparse too
%! sp = odeSPVI (@ns1, [0 2], y0, symplecticset (o, "HamiltonianHessFcn", @ns_hess));
%! by_stages (sp, 3);
%! assert (relerr (sp.y(:, end), sf.y(:, end)) <= 1e-12);
%! ## (measured 3.5e-16 and 2.8e-16 apart; energy 1.6e-14)
%! E = ns_energy (ss.y.');
%! assert (max (abs (E - E(1))) / E(1) < 1e-12);

## -------------------------------------------------------------------- errors
%!error <odeSPVI: HamiltonianHessFcn must return the Hessian of H, a 80x80 matrix>
%! t = odeSPVI (@fpu1, [0 1], [0.1 * ones(40, 1); zeros(40, 1)],
%!              symplecticset ("TimeStepSize", 0.1, "HamiltonianHessFcn",
%!                             @(t, y) speye (81)));
%!error <odeSPVI: HamiltonianHessFcn returned a complex value>
%! t = odeSPVI (@fpu1, [0 1], [0.1 * ones(40, 1); zeros(40, 1)],
%!              symplecticset ("TimeStepSize", 0.1, "HamiltonianHessFcn",
%!                             @(t, y) (1 + 1i) * fpu_hess (t, y)));
%!error <odeSPVI: FCN \(second output\) must return the Hessian of H, a 8x8 matrix>
%! t = odeSPVI (@(t, y) deal (fpu1 (t, y), speye (9)), [0 1],
%!              [0.1; 0.2; 0.3; 0.4; 0; 0; 0; 0], symplecticset ("TimeStepSize", 0.1));
%!error <odeSPVI: the Jacobian function returned a complex value>
%! t = odeSPVI (@fpu1, [0 1], [0.1; 0.2; 0.3; 0.4; 0; 0; 0; 0],
%!              symplecticset ("TimeStepSize", 0.1, "Jacobian", @(t, y) 1i * fpu_jac (t, y)));
%!error <odeSPVI: Jacobian must be a function handle or a real 8x8 matrix \(df/dy\), got 8x8 sparse complex>
%! t = odeSPVI (@fpu1, [0 1], [0.1; 0.2; 0.3; 0.4; 0; 0; 0; 0],
%!              symplecticset ("TimeStepSize", 0.1, "Jacobian", 1i * speye (8)));

## --------------------------------------------------------------------- stats
%!test
%! ## npds counts every call of the Hessian function, the call at (t0, y0)
%! ## that finds it sparse included
%! [d, y0, o] = chain40 ();
%! global SPARSE_HESS_CALLS
%! SPARSE_HESS_CALLS = 0;
%! s = odeSPVI (@fpu1, [0 2], y0, symplecticset (o, "HamiltonianHessFcn", @fpu_hess_count));
%! assert (SPARSE_HESS_CALLS >= 2);
%! assert (s.stats.npds, SPARSE_HESS_CALLS);
%! by_stages (s, 3);
%! ## adaptive
%! SPARSE_HESS_CALLS = 0;
%! s = odeSPVI (@fpu1, [0 2], y0, symplecticset ("RelTol", 1e-8, "AbsTol", 1e-10,
%!              "HamiltonianHessFcn", @fpu_hess_count));
%! assert (s.stats.npds, SPARSE_HESS_CALLS);
%! ## a full Hessian: the same count (auto looks at it too), and "full"
%! ## makes no call to look
%! SPARSE_HESS_CALLS = 0;
%! s = odeSPVI (@fpu1, [0 2], y0, symplecticset (o, "HamiltonianHessFcn", @fpu_hess_count_full));
%! assert (s.stats.npds, SPARSE_HESS_CALLS);
%! SPARSE_HESS_CALLS = 0;
%! s = odeSPVI (@fpu1, [0 2], y0, symplecticset (o, "HamiltonianHessFcn",
%!              @fpu_hess_count_full, "NewtonSystem", "full"));
%! assert (s.stats.npds, SPARSE_HESS_CALLS);
%! assert (SPARSE_HESS_CALLS >= 1);
%! clear -global SPARSE_HESS_CALLS

## ---------------------------------------------- a given matrix that is wrong
## The user guide (section 6): a Jacobian or Hessian given is probed at
## its point, finite differences taking over when it is far from f's
## change, and again when Newton fails with it or it has NaN or Inf where
## f is finite.  A sparse one as a full one (the finite differences then
## on its own pattern).
%!test
%! ## a sparse Hessian a million times too large
%! [d, y0, o] = chain40 ();
%! s0 = fpu_ref ();
%! sf = odeSPVI (@fpu1, [0 2], y0, symplecticset (o, "HamiltonianHessFcn",
%!               @(t, y) 1e6 * fpu_hess_full (t, y)));
%! assert (strncmp (sf.stats.jacobian_source,
%!                  "HamiltonianHessFcn, then finite differences of FCN", 50));
%! assert (relerr (sf.y(:, end), s0.y(:, end)) <= 1e-10);
%! s = odeSPVI (@fpu1, [0 2], y0, symplecticset (o, "HamiltonianHessFcn",
%!              @(t, y) 1e6 * fpu_hess (t, y)));
%! assert (relerr (s.y(:, end), s0.y(:, end)) <= 1e-10);

%!test
%! ## a sparse Hessian with a NaN entry
%! [d, y0, o] = chain40 ();
%! s0 = fpu_ref ();
%! sf = odeSPVI (@fpu1, [0 2], y0, symplecticset (o, "HamiltonianHessFcn",
%!               @(t, y) fpu_hess_full (t, y) + sparse (1, 1, NaN, 2*d, 2*d)));
%! assert (sf.x(end), 2);
%! assert (relerr (sf.y(:, end), s0.y(:, end)) <= 1e-10);
%! s = odeSPVI (@fpu1, [0 2], y0, symplecticset (o, "HamiltonianHessFcn",
%!              @(t, y) fpu_hess (t, y) + sparse (1, 1, NaN, 2*d, 2*d)));
%! assert (s.x(end), 2);
%! assert (relerr (s.y(:, end), s0.y(:, end)) <= 1e-10);

## ------------------------------------------------------------- odeSV, odeSE
%!test
%! ## implicit steps on the non-separable H: a sparse Hessian gives the
%! ## same result as the full one (whether made full or solved sparse)
%! n = 20;
%! z0 = fpu_y0 (n);
%! for solver = {@odeSV, @odeSE}
%!   os = symplecticset ("TimeStepSize", 0.05);
%!   s = solver{1} (@ns1, [0 2], z0, symplecticset (os, "HamiltonianHessFcn", @ns_hess));
%!   sf = solver{1} (@ns1, [0 2], z0, symplecticset (os, "HamiltonianHessFcn", @ns_hess_full));
%!   assert (s.stats.jacobian_source, "HamiltonianHessFcn");
%!   assert (s.x(end), 2);
%!   assert (s.stats.nnewton > 0);
%!   assert (relerr (s.y(:, end), sf.y(:, end)) <= 1e-12);
%!   ## and close to odeSPVI's order-6 result: first or second order
%!   r = odeSPVI (@ns1, [0 2], z0, symplecticset (os, "HamiltonianHessFcn", @ns_hess));
%!   ## (measured 8e-5 for odeSV, 6e-3 for odeSE)
%!   e = relerr (s.y(:, end), r.y(:, end));
%!   assert (e < 5e-2 && e > 1e-10);
%! endfor
