## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## -*- texinfo -*-
## @deftypefn {} {@var{out} =} regression_outputs (@var{r})
## Run @var{r}, one of regression_runs (), and return what
## tests/test_regression.m compares: the outputs asked for (t, y and the
## events, or the fields x, y, xe, ye, ie of sol), and the counts of a
## second run in the sol form (its steps are the same; sol.stats counts
## its calls).
## @end deftypefn

function out = regression_outputs (r)
  out = struct ();
  if (r.nout == 1)
    sol = r.solver (r.fcn, r.tspan, r.y0, r.opts);
    for f = {"x", "y", "xe", "ye", "ie"}
      if (isfield (sol, f{1}))
        out.(f{1}) = sol.(f{1});
      endif
    endfor
  else
    [t, y, te, ye, ie] = r.solver (r.fcn, r.tspan, r.y0, r.opts);
    out.t = t;
    out.y = y;
    if (r.nout == 5)
      out.te = te;
      out.ye = ye;
      out.ie = ie;
    endif
    sol = r.solver (r.fcn, r.tspan([1 end]), r.y0, r.opts);
  endif
  s = sol.stats;
  out.counts = [s.nsteps, s.nfailed, s.nfevals, s.npds, s.ndecomps, ...
                s.nlinsols, s.nnewton, s.nfdevals, s.nstates];
endfunction
