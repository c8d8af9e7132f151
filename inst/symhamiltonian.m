## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## -*- texinfo -*-
## @deftypefn  {} {@var{fcn} =} symhamiltonian (@var{H}, @var{q}, @var{p})
## @deftypefnx {} {@var{fcn} =} symhamiltonian (@dots{}, @var{name}, @var{value}, @dots{})
## Hamilton's equations of a formula, generated as C and compiled: an FCN
## that odeSE, odeSV and odeSPVI call with no Octave call per evaluation.
##
## @var{H} is a scalar expression of the @code{symbolic} package, @var{q}
## and @var{p} vectors of its symbols of equal length d; y = [q; p].
## Options:
## @table @code
## @item "Time", t
## the symbol of time in H (and in the force);
## @item "Parameters", [m1 m2 G]
## symbols whose values are given at solve time as the solver's PAR1, a
## vector in this order: a new value needs no new compile;
## @item "Force", F
## a d-vector F(t, q, p) added to dp/dt (Lagrange--d'Alembert).
## @end table
##
## Generated: f = [dH/dp; -dH/dq + F], the Hessian of H with its nonzero
## pattern (Newton's matrix of the implicit steps), H itself
## (@code{fcn.energy}), the batch form (@code{Vectorized}, @code{Ensemble}),
## and, when H = p'M^-1 p/2 + V(q) with constant M and F free of p, the
## acceleration for @code{SecondOrder}.  Common subexpressions are shared.
## Compiling and caching are symcompile's: a second call with the same H
## costs no compile (and in the same session no generation either).  Every symbol of H must be in q, p, t or the
## parameters.
##
## Example: Kepler with the parameter mu.
## @example
## @group
## syms q1 q2 p1 p2 mu
## H = (p1^2 + p2^2) / 2 - mu / sqrt (q1^2 + q2^2);
## fcn = symhamiltonian (H, [q1 q2], [p1 p2], "Parameters", mu);
## opts = symplecticset ("TimeStepSize", 0.01, "Separable", "on");
## [t, y] = odeSV (fcn, [0 10], [0.5; 0; 0; sqrt(3)], opts, 1);
## @end group
## @end example
## @seealso{symlagrangian, symcompile, odeSV, odeSPVI, odeSE}
## @end deftypefn

function fcn = symhamiltonian (H, q, p, varargin)
  who = "symhamiltonian";
  if (nargin < 3)
    print_usage ();
  endif
  persistent memo;
  if (isempty (memo))
    memo = containers.Map ();
  endif
  ## the same arguments (the SymPy forms of the formulas, assumptions
  ## included) give the same C: generated once a session, as SymPy costs
  ## far more than the lookup; only arguments that were accepted are kept
  key = memo_key ([{H, q, p}, varargin]);
  if (! isempty (key) && isKey (memo, key))
    c = memo(key);
    [src, hasacc] = c{:};
  else
    [H, q, p, t, par, F] = __symham_args__ (who, H, q, p, varargin{:});
    [src, hasacc] = __symham_source__ (who, H, q, p, t, par, F);
    if (! isempty (key))
      if (memo.Count >= 64)
        memo = containers.Map ();
      endif
      memo(key) = {src, hasacc};
    endif
  endif
  extra = struct ("H", H, "formula", "hamiltonian", "accel", hasacc);
  fcn = __symcompile_build__ (src, "", extra, who);
endfunction

## the arguments as text: sym by their SymPy form, strings and numbers as
## they are; "" (no memo) for anything else
function key = memo_key (args)
  key = "";
  parts = cell (size (args));
  for k = 1:numel (args)
    x = args{k};
    if (isa (x, "sym"))
      parts{k} = ["sym " mat2str(size (x)) " " struct(x).pickle];
    elseif (ischar (x) && isrow (x))
      parts{k} = ["char " x];
    elseif (isnumeric (x) && isreal (x) && ! issparse (x))
      parts{k} = [class(x) " " mat2str(size (x)) " " mat2str(double (x(:).'), 17)];
    else
      return;
    endif
  endfor
  key = hash ("md5", strjoin (parts, "\n--\n"));
endfunction

%!shared kep
%! if (exist ("syms") || ! isempty (pkg ("list", "symbolic")))
%!   pkg load symbolic
%!   syms q1 q2 p1 p2 mu
%!   kep = symhamiltonian ((p1^2 + p2^2) / 2 - mu / sqrt (q1^2 + q2^2), ...
%!                         [q1 q2], [p1 p2], "Parameters", mu);
%! endif
%!test
%! if (isempty (kep)) return; endif
%! y = [0.5; 0.1; 0.2; 1.5]; r = norm (y(1:2));
%! assert (kep (0, y, 2), [y(3:4); -2 * y(1:2) / r^3], 1e-14);
%! assert (kep.energy (0, y, 2), sum (y(3:4).^2) / 2 - 2 / r, 1e-14);
%!test
%! ## the memo: the same arguments, the same library; other ones, not
%! if (isempty (kep)) return; endif
%! syms q1 q2 p1 p2 mu
%! H = (p1^2 + p2^2) / 2 - mu / sqrt (q1^2 + q2^2);
%! k2 = symhamiltonian (H, [q1 q2], [p1 p2], "Parameters", mu);
%! assert (k2.lib, kep.lib);
%! assert (k2.cached);
%! k3 = symhamiltonian (H, [q1 q2], [p1 p2], "Parameters", mu, "Force", -mu * [p1; p2]);
%! assert (! strcmp (k3.lib, kep.lib));
%! y = [0.5; 0.1; 0.2; 1.5];
%! assert (k3 (0, y, 2), kep (0, y, 2) - [0; 0; 2 * y(3:4)], 1e-15);
%!error <symhamiltonian: symbols not bound.*: mu>
%! pkg load symbolic
%! syms q1 q2 p1 p2 mu
%! symhamiltonian ((p1^2 + p2^2) / 2 - mu / sqrt (q1^2 + q2^2), [q1 q2], [p1 p2]);
