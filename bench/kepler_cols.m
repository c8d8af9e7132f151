## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## dy = kepler_cols (t, y) -- Kepler's f for states as the columns of y
## (Vectorized, and a single column alike): the rows are taken from the
## transpose, whose columns are contiguous (indexing rows of a wide
## matrix costs Octave far more than arithmetic on them).  A column alone
## and a column among others give the same numbers.
function dy = kepler_cols (t, y)
  z = y.';
  x = z(:,1);  v = z(:,2);
  r2 = x .* x + v .* v;
  r3 = r2 .* sqrt (r2);
  dy = [z(:,3), z(:,4), -x ./ r3, -v ./ r3].';
endfunction
