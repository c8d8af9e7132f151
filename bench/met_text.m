## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## s = met_text (b)
##
## "met" or "not met": whether a benchmark's target was reached, for the
## tables of bench/*.md.

function s = met_text (b)
  if (b)
    s = "met";
  else
    s = "not met";
  endif
endfunction
