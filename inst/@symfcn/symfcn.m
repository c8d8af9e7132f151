## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## -*- texinfo -*-
## @deftypefn {} {@var{fcn} =} symfcn (@var{s})
## A compiled FCN, as symcompile, symhamiltonian and symlagrangian return
## it: odeSE, odeSV and odeSPVI take it as FCN.  @code{dy = fcn (t, y)},
## @code{[dy, hess] = fcn (t, y)}, @code{fcn.energy (t, y)},
## @code{fcn.acceleration (t, q)} (PAR as a third argument) evaluate it;
## @code{fcn.dim}, @code{fcn.npar}, @code{fcn.hessian}, @code{fcn.nnz},
## @code{fcn.energy} (alone: a function handle), @code{fcn.lib} (the shared
## object), @code{fcn.source} (its C file) and @code{fcn.cached} describe
## it.  Made by those functions, not called directly.
## @seealso{symcompile, symhamiltonian}
## @end deftypefn

function fcn = symfcn (s)
  if (nargin != 1 || ! isstruct (s) || ! isfield (s, "lib"))
    error ("Octave:invalid-input-arg",
           "symfcn: made by symcompile, symhamiltonian or symlagrangian");
  endif
  fcn = class (s, "symfcn");
endfunction
