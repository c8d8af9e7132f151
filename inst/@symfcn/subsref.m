## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## -*- texinfo -*-
## @deftypefn  {} {@var{dy} =} subsref (@var{fcn}, @var{idx})
## Calls and fields of a compiled FCN: @code{fcn (t, y, par)},
## @code{[dy, hess] = fcn (t, y, par)}, @code{fcn.energy (t, y, par)},
## @code{fcn.acceleration (t, q, par)}, @code{fcn.hessian_at (t, y, par)},
## and the fields (see symfcn).
## @end deftypefn

function varargout = subsref (fcn, idx)
  g = struct ("symplectic_compiled", fcn.lib);
  switch (idx(1).type)
    case "()"
      a = idx(1).subs;
      if (numel (a) < 2 || numel (a) > 3)
        error ("Octave:invalid-fun-call",
               "symfcn: call it as FCN (T, Y) or FCN (T, Y, PAR)");
      endif
      if (nargout < 2)
        varargout{1} = __symcompiled__ ("f", g, a{:});
      else
        [varargout{1}, varargout{2}] = __symcompiled__ ("fh", g, a{:});
      endif
      rest = idx(2:end);
    case "."
      switch (idx(1).subs)
        case "energy"
          v = @(t, y, varargin) __symcompiled__ ("energy", g, t, y, varargin{:});
        case "acceleration"
          v = @(t, q, varargin) __symcompiled__ ("accel", g, t, q, varargin{:});
        case "hessian_at"
          v = @(t, y, varargin) hess_at (g, t, y, varargin{:});
        otherwise
          s = struct (fcn);
          if (isfield (s, idx(1).subs) && ! strcmp (idx(1).subs, "extra"))
            v = s.(idx(1).subs);
          elseif (isfield (s.extra, idx(1).subs))
            v = s.extra.(idx(1).subs);
          else
            error ("Octave:invalid-indexing",
                   "symfcn: no field or method '%s'", idx(1).subs);
          endif
      endswitch
      rest = idx(2:end);
      if (! isempty (rest) && strcmp (rest(1).type, "()")
          && is_function_handle (v))
        [varargout{1:max (nargout, 1)}] = v (rest(1).subs{:});
        rest = rest(2:end);
      else
        varargout{1} = v;
      endif
    otherwise
      error ("Octave:invalid-indexing", "symfcn: no {} indexing");
  endswitch
  if (! isempty (rest))
    varargout{1} = subsref (varargout{1}, rest);
  endif
endfunction

function h = hess_at (g, t, y, varargin)
  [~, h] = __symcompiled__ ("fh", g, t, y, varargin{:});
endfunction
