## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## -*- texinfo -*-
## @deftypefn {} {@var{s} =} __symfcn_gateway__ (@var{fcn})
## The form in which the solvers' gateways take a compiled FCN: a struct
## whose field symplectic_compiled is the shared object's path.
## @end deftypefn

function s = __symfcn_gateway__ (fcn)
  s = struct ("symplectic_compiled", fcn.lib);
endfunction
