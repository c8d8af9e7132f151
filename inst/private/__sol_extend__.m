## Copyright (C) 2026 The symplectic developers
##
## This program is free software: you can redistribute it and/or modify it
## under the terms of the GNU General Public License as published by the Free
## Software Foundation, either version 3 of the License, or (at your option)
## any later version.  See the file COPYING.

## -*- texinfo -*-
## @deftypefn {} {[@dots{}] =} __sol_extend__ (@var{solver}, @var{gateway}, @var{nout}, @var{fcn}, @var{tspan}, @var{sol}, @dots{})
## A sol of @var{solver} given as Y0: the run continued beyond its end
## (TSPAN on in its direction) or retraced (TSPAN back), from the last
## step point before its last step when that step may have been
## shortened: fixed steps go on on the same grid, reversible ones with
## the densities the sol keeps (sol.restart).  Options not given are the
## sol's run's.  The outputs are the gateway's: [t, y, te, ye, ie] from
## tspan(1) on, or sol (a continuation's joined to the given one).
## @end deftypefn

function varargout = __sol_extend__ (solver, gateway, nout, fcn, tspan, sol, varargin)
  if (! (isfield (sol, "solver") && isfield (sol, "x") && isfield (sol, "y")))
    error ("Octave:invalid-input-arg",
           "%s: Y0 must be a non-empty real numeric vector [q0; p0] or the sol of a run of %s, got %dx%d struct (a sol has the fields x, y and solver)",
           solver, solver, rows (sol), columns (sol));
  endif
  if (! strcmp (sol.solver, solver))
    error ("Octave:invalid-input-arg",
           "%s: Y0 is the sol of a run of %s; give it to %s, or give its end sol.y(:,end) as Y0",
           solver, sol.solver, sol.solver);
  endif
  x = sol.x;
  if (numel (x) < 1 || ndims (sol.y) != 2 || columns (sol.y) != numel (x))
    error ("Octave:invalid-input-arg",
           "%s: Y0 is a sol with no rows, or of an Ensemble run; give a state vector as Y0",
           solver);
  endif
  if (! (isnumeric (tspan) && isreal (tspan) && numel (tspan) >= 2))
    error ("Octave:invalid-input-arg",
           "%s: TSPAN must be a real vector [T0, TF] or [T0, T1, ..., TF]", solver);
  endif
  tspan = double (tspan(:).');
  T = x(end);
  if (tspan(1) != T)
    error ("Octave:invalid-input-arg",
           "%s: with a sol as Y0, TSPAN(1) must be its end sol.x(end) = %.17g, got %.17g",
           solver, T, tspan(1));
  endif
  dir = sign (tspan(end) - tspan(1));
  back = numel (x) > 1 && dir != sign (x(end) - x(1));

  ## OPTS (a struct or []) then P1, ...: options not given are the run's
  given = [];
  extra = varargin;
  if (numel (varargin) >= 1 && (isstruct (varargin{1}) || isempty (varargin{1})))
    given = varargin{1};
    extra = varargin(2:end);
  endif
  r = [];
  if (isfield (sol, "restart"))
    r = sol.restart;
  endif
  opts = given;
  if (! isempty (r) && isstruct (r.options))
    if (isstruct (given))
      opts = symplecticset (r.options, given);
    else
      opts = r.options;
    endif
  endif

  ## sol.phi would not join the sol's (Phi restarts at the identity)
  if (isstruct (opts) && isfield (opts, "TangentMap")
      && ! isempty (opts.TangentMap)
      && ! (ischar (opts.TangentMap) && any (strcmpi (opts.TangentMap, {"off", "no"})))
      && ! (isscalar (opts.TangentMap) && ! ischar (opts.TangentMap)
            && ! opts.TangentMap))
    error ("Octave:invalid-input-arg",
           "%s: TangentMap is not supported with a sol as Y0 (Phi would restart from the identity there); start from the state sol.y(:,end)",
           solver);
  endif

  ## where the run starts: the last step point before the last step, when
  ## the sol says how its steps go on from there, TSPAN's output times are
  ## beyond it, and no options that change the steps were given
  y0 = sol.y(:,end);
  t0 = T;
  k0 = 0;  g0 = 0;  rho0 = 0;
  steps = {"TimeStepSize", "TimeStepNumber", "RelTol", "AbsTol", ...
           "InitialStep", "MaxStep", "StepControl", "StepDensityFcn", "Method"};
  steps_given = isstruct (given) ...
                && any (cellfun (@(f) isfield (given, f) && ! isempty (given.(f)),
                                 steps));
  from_prev = false;
  if (! isempty (r) && numel (x) >= 2 && ! steps_given)
    tp = x(end-1);
    inside = any (dir * (tspan(2:end) - tp) <= 0);
    if (r.h > 0 && ! inside)
      from_prev = true;
      opts = symplecticset (opts, "TimeStepSize", r.h, "TimeStepNumber", []);
      if (! back)
        k0 = r.k - 1;
        g0 = r.t0;
      endif
    elseif (r.h == 0 && ! inside && r.rho(2 - back) > 0)
      from_prev = true;
      rho0 = r.rho(2 - back);
    endif
    if (from_prev)
      t0 = tp;
      y0 = sol.y(:,end-1);
    endif
  endif
  ts = tspan;
  ts(1) = t0;
  y0s = struct ("symplectic_restart", true, "y", y0, "k", k0, "t0", g0,
                "rho", rho0);
  if (nout == 0)
    gateway (fcn, ts, y0s, opts, extra{:});
    return;
  endif
  out = cell (1, max (nout, 1));
  [out{:}] = gateway (fcn, ts, y0s, opts, extra{:});

  if (nout > 1)
    ## [t, y, te, ye, ie] from tspan(1) on: its first row the sol's end
    keep = dir * (out{1} - T) > 0;
    out{1} = [T; out{1}(keep)];
    out{2} = [sol.y(:,end).'; out{2}(keep,:)];
    if (nout > 2)
      ev = dir * (out{3} - T) > 0;
      out{3} = out{3}(ev);
      if (nout > 3)
        out{4} = out{4}(ev,:);
      endif
      if (nout > 4)
        out{5} = out{5}(ev);
      endif
    endif
    varargout = out;
    return;
  endif

  s = out{1};
  if (back)
    ## a retrace: the run back alone, from the sol's end
    if (from_prev)
      s.x = [T, s.x];
      s.y = [sol.y(:,end), s.y];
      if (isfield (s, "H") && isfield (sol, "H"))
        s.H = [sol.H(end), s.H];
      endif
    endif
    varargout{1} = s;
    return;
  endif
  ## a continuation: the sol's rows to the start of the run, then the run's
  n = numel (x) - from_prev;
  c = s;
  c.x = [x(1:n), s.x(2:end)];
  c.y = [sol.y(:,1:n), s.y(:,2:end)];
  if (isfield (s, "H") && isfield (sol, "H"))
    c.H = [sol.H(1:n), s.H(2:end)];
  endif
  if (isfield (s, "xe") && isfield (sol, "xe"))
    ev = dir * (s.xe - T) > 0;
    c.xe = [sol.xe; s.xe(ev)];
    c.ye = [sol.ye; s.ye(ev,:)];
    c.ie = [sol.ie; s.ie(ev)];
  endif
  if (isfield (s, "dense") && isfield (sol, "dense"))
    m = columns (sol.dense.t) - from_prev;
    c.dense.t = [sol.dense.t(:,1:m), s.dense.t];
    c.dense.y = cat (3, sol.dense.y(:,:,1:m), s.dense.y);
  endif
  if (isfield (sol, "stats"))
    for [v, f] = s.stats
      if (isnumeric (v) && isfield (sol.stats, f))
        c.stats.(f) = sol.stats.(f) + v;
      endif
    endfor
  endif
  varargout{1} = c;
endfunction
