## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## The outputs of a fixed set of runs (regression_runs.m: the three
## solvers, fixed and adaptive steps, events, Vectorized, every source of
## Newton's matrix, the FPU chain) against those recorded in
## regression.txt.gz (record_regression.m): fixed steps to the bit,
## adaptive ones within 1e-12 relative to the size of each output, and
## the counts of sol.stats equal.  A change of the code's structure must
## keep them; a change meant to change the results records them anew.

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
%!   for f = fieldnames (want).'
%!     a = got.(f{1});  b = want.(f{1});
%!     if (! isequal (size (a), size (b)))
%!       ok = false;
%!     elseif (r.fixed || strcmp (f{1}, "counts") || strcmp (f{1}, "ie"))
%!       ok = isequaln (a, b);
%!     else
%!       ok = all (abs (a(:) - b(:)) <= 1e-12 * max (abs (b(:))));
%!     endif
%!     if (! ok)
%!       bad{end+1} = sprintf ("%s: %s", r.name, f{1});
%!     endif
%!   endfor
%! endfor
%! if (! isempty (bad))
%!   error ("differ from the recorded outputs: %s", strjoin (bad, "; "));
%! endif
