## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## -*- texinfo -*-
## @deftypefn {} {[@var{dy}, @var{hess}] =} memcheck_osc (@var{t}, @var{y})
## The harmonic oscillator with its Hessian as second output, in a file of
## its own: tests/memcheck_run.m calls the solvers with its name and with
## the simple handle @@memcheck_osc, which they call by name.
## @end deftypefn

function [dy, hess] = memcheck_osc (t, y)
  dy = [y(2); -y(1)];
  hess = eye (2);
endfunction
