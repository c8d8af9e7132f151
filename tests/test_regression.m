## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## The outputs of a fixed set of runs (regression_runs.m: the three
## solvers, fixed and adaptive steps, events, Vectorized, every source of
## Newton's matrix, the FPU chain) against those recorded in
## regression.txt.gz (record_regression.m).  A change of the code's
## structure must keep them; a change meant to change the results records
## them anew.
##
## The reference was recorded on one machine; the same code on another
## takes other BLAS kernels (OpenBLAS picks them by CPU), other LAPACK
## blocking, and other variants of libm's pow, sin, exp (glibc picks FMA
## or SSE2 versions by CPU).  Each of these moves results by round-off,
## and a Newton solve that stops near its tolerance then takes one
## iteration more or less.  So (tools/check-blas.sh runs this file under
## several of them):
##
## * exact runs (fixed explicit steps, an FCN of elementwise arithmetic
##   and sqrt only: IEEE operations in a fixed order, no BLAS, LAPACK or
##   libm call) are compared to the bit.
## * other fixed-step runs: each step's Newton solve stops within
##   SYM_NEWTON_TOL = 1e-14 (relative) of its root whatever the BLAS, so
##   after N steps the outputs may move by N * 1e-14, magnified at most
##   ~10 times by the flows over these spans (<= 4 Kepler periods):
##   tolerance 10 * N * 1e-14 relative to the output's size (2e-11 for
##   200 steps; the largest change seen is 5e-13).
## * adaptive runs: a round-off change of kappa ulps in a step's error
##   estimate (scaled by RelTol) changes that step's size by kappa *
##   eps / RelTol relative; the steps sum to the span, so the times and
##   the solution move by at most kappa * eps / RelTol of their size.
##   kappa = 1000 (Newton's 1e-14 is 45 ulps, times the flow's growth):
##   tolerance 1000 * eps / RelTol (2e-9 at RelTol 1e-4, 2e-5 at 1e-8;
##   the largest change seen is 1e-9 at RelTol 1e-8, about 0.06 eps /
##   RelTol).
## * the counts of sol.stats: the steps of a fixed run exactly; the
##   steps and failed steps of an adaptive run within 1 + 1 %; the
##   Newton counts (f evaluations, matrices, decompositions, solves,
##   iterations, finite-difference calls, states) within 2 + 20 %: a
##   solve near its tolerance takes an iteration more or less, and a kept
##   matrix is refreshed a step earlier or later (the largest changes
##   seen: 8 of 328 matrices, 2.4 %; the 20-node solves of "fixed nodes20
##   odeSPVI", which stop at round-off, 86 iterations against 76, 13 %,
##   under OPENBLAS_CORETYPE Haswell).  Event indices (ie) exactly.

%!function tol = regression_tol (r, want)
%!  ## the relative tolerance of run r's floating outputs (see above)
%!  if (r.exact)
%!    tol = 0;
%!  elseif (r.fixed)
%!    tol = 10 * want.counts(1) * 1e-14;
%!  else
%!    tol = 1000 * eps / r.opts.RelTol;
%!  endif
%!endfunction

%!function ok = counts_ok (r, a, b)
%!  ## steps and failed steps, then the Newton counts (see above)
%!  if (r.fixed)
%!    slack = [0, 0];
%!  else
%!    slack = 1 + 0.01 * b(1:2);
%!  endif
%!  slack = [slack, 2 + 0.2 * b(3:end)];
%!  if (r.exact)
%!    slack(:) = 0;
%!  endif
%!  ok = all (abs (a - b) <= slack);
%!endfunction

%!test
%! runs = regression_runs ();
%! file = fullfile (fileparts (which ("regression_runs")), "regression.txt.gz");
%! s = load (file);
%! ref = s.ref;
%! assert ({ref.name}, {runs.name});
%! bad = {};
%! for k = 1:numel (runs)
%!   r = runs(k);
%!   got = regression_outputs (r);
%!   want = ref(k).out;
%!   assert (fieldnames (got), fieldnames (want));
%!   tol = regression_tol (r, want);
%!   for f = fieldnames (want).'
%!     a = got.(f{1});  b = want.(f{1});
%!     if (! isequal (size (a), size (b)))
%!       ok = false;
%!       err = Inf;
%!     elseif (strcmp (f{1}, "counts"))
%!       ok = counts_ok (r, a, b);
%!       err = max (abs (a - b));
%!     elseif (strcmp (f{1}, "ie") || tol == 0)
%!       ok = isequaln (a, b);
%!       err = max (abs (a(:) - b(:)));
%!     else
%!       err = max (abs (a(:) - b(:))) / max (abs (b(:)));
%!       ok = err <= tol;
%!     endif
%!     if (! ok)
%!       bad{end+1} = sprintf ("%s: %s (%.3g, tolerance %.3g)", r.name,
%!                             f{1}, err, tol);
%!     endif
%!   endfor
%! endfor
%! if (! isempty (bad))
%!   error ("differ from the recorded outputs: %s", strjoin (bad, "; "));
%! endif

%!test
%! ## the exact runs are those that claim no BLAS, LAPACK or libm call:
%! ## fixed explicit steps; the tolerances of the others are not zero
%! runs = regression_runs ();
%! ex = [runs.exact];
%! assert (nnz (ex), 4);
%! assert (all ([runs(ex).fixed]));
%! for r = runs(ex)
%!   assert (r.opts.Separable, "on");
%! endfor
%! s = load (fullfile (fileparts (which ("regression_runs")), "regression.txt.gz"));
%! for k = find (! ex)
%!   assert (regression_tol (runs(k), s.ref(k).out) > 0);
%! endfor
