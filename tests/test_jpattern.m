## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## JPattern: finite-difference Newton matrices from the pattern of df/dy.
## The columns are coloured so that no two of a colour share a row, and
## each colour takes one stepped state instead of each column.  On an FPU
## chain (f_q = p, f_p tridiagonal in q) the result is the same to the bit
## as without the pattern, from 3 evaluations of FCN per Newton matrix
## instead of 2d.

%!function dy = fpu1 (t, y)
%!  ## the chain of bench/fpu.m (fixed ends, V(r) = r^2/2 + r^4/4), one
%!  ## output (no Hessian: finite differences); Vectorized
%!  d = rows (y) / 2;
%!  q = y(1:d, :);  z = zeros (1, columns (y));
%!  r = diff ([z; q; z]);
%!  F = r + r.^3;
%!  dy = [y(d+1:end, :); F(2:end, :) - F(1:end-1, :)];
%!endfunction

%!function P = fpu_pattern (d)
%!  P = sparse (2*d, 2*d);
%!  P(1:d, d+1:end) = speye (d);
%!  P(d+1:end, 1:d) = spdiags (ones (d, 3), -1:1, d, d);
%!endfunction

%!shared d, y0, P
%! d = 20;
%! y0 = [0.3 * sin((1:d)' * pi / (d+1)); 0.1 * cos((1:d)')];
%! P = fpu_pattern (d);

%!test
%! ## the same steps, from 3 evaluations per matrix instead of 2d = 40
%! ## (each matrix: sol.stats.nfdevals over the matrices built); the
%! ## pattern as a logical and a double full matrix
%! for s = {@odeSE, @odeSV, @odeSPVI}
%!   o = symplecticset ("TimeStepSize", 0.05);
%!   s0 = s{1} (@fpu1, [0 2], y0, o);
%!   for pat = {full(P) != 0, 2 * full(P)}
%!     s1 = s{1} (@fpu1, [0 2], y0, symplecticset (o, "JPattern", pat{1}));
%!     assert (s1.y, s0.y);
%!     assert (s1.stats.nsteps, s0.stats.nsteps);
%!     ## matrices built: the calls for them over 2d without, over 3 with
%!     ## (odeSPVI, by stages at this size: and f where it is taken)
%!     e = isequal (s{1}, @odeSPVI);
%!     m = s0.stats.nfdevals / (2*d + e);
%!     assert (m >= 1 && m == round (m));
%!     assert (s1.stats.nfdevals, (3 + e) * m);
%!   endfor
%! endfor

%!test
%! ## the pattern as a sparse matrix: sparse matrices, 3 evaluations each
%! ## (odeSPVI: and f where its Jacobian is taken), the same steps to
%! ## round-off (odeSPVI by stages: 2 solves per correction)
%! for s = {@odeSE, @odeSV, @odeSPVI}
%!   o = symplecticset ("TimeStepSize", 0.05);
%!   s0 = s{1} (@fpu1, [0 2], y0, o);
%!   s1 = s{1} (@fpu1, [0 2], y0, symplecticset (o, "JPattern", P));
%!   assert (s1.y, s0.y, 1e-12 * max (abs (s0.y(:))));
%!   m = s1.stats.ndecomps / (1 + isequal (s{1}, @odeSPVI));
%!   assert (s1.stats.nfdevals, (3 + isequal (s{1}, @odeSPVI)) * m);
%! endfor
%! assert (s1.stats.nlinsols, 2 * s1.stats.nnewton);

%!test
%! ## Vectorized: one call per matrix either way, 3 states in it instead
%! ## of 2d; adaptive steps too
%! o = symplecticset ("RelTol", 1e-8, "AbsTol", 1e-10, "Vectorized", "on");
%! s0 = odeSV (@fpu1, [0 2], y0, o);
%! s1 = odeSV (@fpu1, [0 2], y0, symplecticset (o, "JPattern", P));
%! assert (s1.y, s0.y);
%! assert (s1.stats.nfdevals, s0.stats.nfdevals);
%! m = s0.stats.nfdevals;
%! assert (s0.stats.nstates - s1.stats.nstates, m * (2*d - 3));

%!test
%! ## a pattern that misses entries of df/dy gives a wrong Newton matrix:
%! ## the run still converges (Newton, fixed steps), only slower; here
%! ## the pattern of f_p without its band's off-diagonals (odeSPVI, whose
%! ## matrix holds all of df/dy; measured 64 iterations instead of 40)
%! Q = P;  Q(d+1:end, 1:d) = speye (d);
%! o = symplecticset ("TimeStepSize", 0.05);
%! s0 = odeSPVI (@fpu1, [0 1], y0, o);
%! s1 = odeSPVI (@fpu1, [0 1], y0, symplecticset (o, "JPattern", Q));
%! assert (s1.y, s0.y, 1e-12);
%! assert (s1.stats.nnewton > 1.2 * s0.stats.nnewton);

%!test
%! ## with a Jacobian or a Hessian from the user, JPattern has nothing to
%! ## do: the same run
%! o = symplecticset ("TimeStepSize", 0.05, "Jacobian", @(t, y) [0 1; -1 0]);
%! s0 = odeSV (@(t, y) [y(2); -y(1)], [0 1], [1; 0], o);
%! s1 = odeSV (@(t, y) [y(2); -y(1)], [0 1], [1; 0], symplecticset (o, "JPattern", [0 1; 1 0]));
%! assert (s1.y, s0.y);
%! assert (s1.stats.nfdevals, s0.stats.nfdevals);   # (the probe of Df)

%!error <odeSV: JPattern must be a real or logical 4x4 matrix>
%! odeSV (@(t, y) -y, [0 1], [1; 0; 0; 1], symplecticset ("JPattern", eye (2)));
%!error <odeSE: JPattern must be a real or logical 2x2 matrix>
%! odeSE (@(t, y) -y, [0 1], [1; 0], symplecticset ("JPattern", "ab"));
%!error <odeSPVI: JPattern must be a real or logical 2x2 matrix>
%! odeSPVI (@(t, y) -y, [0 1], [1; 0], symplecticset ("JPattern", 1i * eye (2)));
%!error <odeSPVI: JPattern must be a real or logical 2x2 matrix>
%! odeSPVI (@(t, y) -y, [0 1], [1; 0], symplecticset ("JPattern", {1, 2; 3, 4}));
