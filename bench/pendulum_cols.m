## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## dy = pendulum_cols (t, y) -- the pendulum H = p^2/2 - cos q for states
## as the columns of y (Vectorized, and a single column alike)
function dy = pendulum_cols (t, y)
  dy = [y(2,:); -sin(y(1,:))];
endfunction
