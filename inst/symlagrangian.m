## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## -*- texinfo -*-
## @deftypefn  {} {@var{fcn} =} symlagrangian (@var{L}, @var{q}, @var{v})
## @deftypefnx {} {@var{fcn} =} symlagrangian (@dots{}, @var{name}, @var{value}, @dots{})
## The Hamiltonian FCN of a Lagrangian L = v'M(q)v/2 + a(q)'v - V(q),
## generated as C and compiled (see symhamiltonian).
##
## @var{L} is a scalar expression of the @code{symbolic} package, @var{q}
## and @var{v} vectors of its symbols (coordinates and velocities).  The
## Legendre transform is done symbolically: p = dL/dv = M(q) v + a(q),
## v = M(q)^-1 (p - a(q)), H = p'v - L; then as symhamiltonian, with the
## same options ("Time", "Parameters", "Force").  The state is y = [q; p]
## as everywhere in the package.  A Lagrangian not quadratic in v (M
## depending on v, or singular) is refused.
##
## The map between velocities and momenta:
## @code{p = fcn.momentum (q, v, par)} and @code{v = fcn.velocity (q, p,
## par)} (PAR only with "Parameters"; Q, V, P may have a column for each
## state).  They are Octave functions of the formulas, for initial values
## and for reading a run back.
## @code{fcn.H} is the Hamiltonian as a sym expression.
##
## Example: the double pendulum in angles (unit masses and lengths).
## @example
## @group
## syms a b va vb g
## L = va^2 + vb^2/2 + va*vb*cos(a-b) + 2*g*cos(a) + g*cos(b);
## fcn = symlagrangian (L, [a b], [va vb], "Parameters", g);
## y0 = [1; 0.5; fcn.momentum([1; 0.5], [0; 0], 9.81)];
## opts = symplecticset ("TimeStepSize", 1e-3);
## [t, y] = odeSV (fcn, [0 1], y0, opts, 9.81);
## @end group
## @end example
## @seealso{symhamiltonian, symcompile, odeSV}
## @end deftypefn

function fcn = symlagrangian (L, q, v, varargin)
  who = "symlagrangian";
  if (nargin < 3)
    print_usage ();
  endif
  [L, q, v, t, par, F] = __symham_args__ (who, L, q, v, varargin{:});
  d = numel (q);
  p = sym (zeros (d, 1));
  for k = 1:d
    p(k) = sym (sprintf ("p_%s", char (v(k))));
  endfor
  cmd = {
    '(L, q, v, p) = _ins'
    'import sympy as S'
    'Lf = lambda x: list(x) if getattr(x, "is_Matrix", False) else [x]'
    'q = Lf(q); v = Lf(v); p = Lf(p); d = len(q)'
    'L = S.sympify(L)'
    'M = S.Matrix(d, d, lambda i, j: S.diff(L, v[i], v[j]))'
    'if any(e.free_symbols & set(v) for e in M):'
    '    return "not quadratic", 0, 0, 0'
    'z = {w: 0 for w in v}'
    'a = S.Matrix([S.diff(L, w).subs(z) for w in v])'
    'vv = S.Matrix(v)'
    'rest = S.simplify(L - (vv.T * M * vv)[0] / 2 - (a.T * vv)[0])'
    'if rest.free_symbols & set(v):'
    '    return "not quadratic", 0, 0, 0'
    'if S.simplify(M.det()) == 0:'
    '    return "singular", 0, 0, 0'
    'pv = S.Matrix(p)'
    'vel = M.LUsolve(pv - a)'
    'vel = vel.applyfunc(S.simplify)'
    'H = (pv.T * vel)[0] - L.xreplace(dict(zip(v, vel)))'
    'mom = M * vv + a'
    'return "", H, vel, mom'
  };
  [msg, H, vel, mom] = pycall_sympy__ (cmd, L, q, v, p);
  if (strcmp (msg, "not quadratic"))
    error ("Octave:invalid-input-arg",
           "symlagrangian: L must be quadratic in V (v'M(q)v/2 + a(q)'v - V(q))");
  elseif (strcmp (msg, "singular"))
    error ("Octave:invalid-input-arg",
           "symlagrangian: the mass matrix d2L/dV2 is singular");
  endif
  opts = {};
  if (! isempty (t)) opts(end+1:end+2) = {"Time", t}; endif
  if (! isempty (par)) opts(end+1:end+2) = {"Parameters", par}; endif
  if (! isempty (F)) opts(end+1:end+2) = {"Force", F}; endif
  [H, ~, ~, ~, ~, ~] = __symham_args__ (who, H, q, p, opts{:});
  [src, hasacc] = __symham_source__ (who, H, q, p, t, par, F);
  if (isempty (par)) par = sym ([]); endif
  extra = struct ("H", H, "formula", "lagrangian", "accel", hasacc,
                  "L", L, "velocity", mapfcn (vel, [q; p; par(:)]),
                  "momentum", mapfcn (mom, [q; v; par(:)]));
  fcn = __symcompile_build__ (src, "", extra, who);
endfunction

## EXPR of VARS as a numeric function of (X, W, PAR), columns of states
function h = mapfcn (expr, vars)
  g = function_handle (expr, "vars", num2cell (vars));
  h = @(x, w, varargin) vmap (g, numel (expr), numel (vars), x, w, varargin{:});
endfunction

function out = vmap (g, d, nv, x, w, par = [])
  if (rows (x) != d || ! isequal (size (x), size (w)))
    error ("Octave:invalid-input-arg",
           "symlagrangian: velocity and momentum take Q and V (or P) of %d rows, of one size",
           d);
  endif
  if (nv != 2 * d + numel (par))
    error ("Octave:invalid-input-arg",
           "symlagrangian: velocity and momentum need PAR, %d values",
           nv - 2 * d);
  endif
  out = zeros (size (x));
  for k = 1:columns (x)
    a = num2cell ([x(:,k); w(:,k); par(:)]);
    out(:,k) = g (a{:});
  endfor
endfunction
