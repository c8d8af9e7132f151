## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## -*- texinfo -*-
## @deftypefn {} {} display (@var{fcn})
## Show a compiled FCN: its size and the functions it has.
## @end deftypefn

function display (fcn)
  s = struct (fcn);
  has = {};
  if (s.hessian)
    has{end+1} = sprintf ("Hessian (%d entries)", s.nnz);
  endif
  names = {"batch", "batch f"; "accel", "acceleration"; "energy", "energy H"};
  for i = 1:rows (names)
    if (s.(names{i,1}))
      has{end+1} = names{i,2};
    endif
  endfor
  more = "";
  if (! isempty (has))
    more = sprintf (", %s", has{:});
  endif
  printf ("%s = compiled FCN: d = %d, %d parameter%s, f%s\n", inputname (1),
          s.dim, s.npar, ifelse_s (s.npar != 1), more);
  printf ("  %s\n", s.lib);
endfunction

function s = ifelse_s (c)
  if (c)
    s = "s";
  else
    s = "";
  endif
endfunction
