## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## -*- texinfo -*-
## @deftypefn {} {[@var{H}, @var{q}, @var{p}, @var{t}, @var{par}, @var{F}] =} __symham_args__ (@var{who}, @var{H}, @var{q}, @var{p}, @dots{})
## The arguments of symhamiltonian and symlagrangian, checked: errors name
## @var{who}.  Absent options come back empty.  Internal.
## @end deftypefn

function [H, q, p, t, par, F] = __symham_args__ (who, H, q, p, varargin)
  if (! exist ("sym", "class") && ! exist ("syms"))
    try
      pkg load symbolic
    catch
      error ("Octave:missing-dependency",
             "%s: needs the symbolic package (octave-symbolic; pkg load symbolic)",
             who);
    end_try_catch
  endif
  if (! isa (H, "sym") || ! isscalar (H))
    error ("Octave:invalid-input-arg", "%s: H must be a scalar sym expression", who);
  endif
  q = vecsym (who, "Q", q);
  p = vecsym (who, "P", p);
  if (numel (q) != numel (p))
    error ("Octave:invalid-input-arg",
           "%s: Q and P must have the same length (%d and %d)", who,
           numel (q), numel (p));
  endif
  t = []; par = []; F = [];
  if (mod (numel (varargin), 2))
    error ("Octave:invalid-input-arg", "%s: options come as NAME, VALUE pairs", who);
  endif
  for k = 1:2:numel (varargin)
    name = varargin{k}; v = varargin{k+1};
    if (! ischar (name))
      error ("Octave:invalid-input-arg", "%s: option names are strings", who);
    endif
    switch (lower (name))
      case "time"
        t = vecsym (who, "Time", v);
        if (numel (t) != 1)
          error ("Octave:invalid-input-arg", "%s: Time must be one symbol", who);
        endif
      case "parameters"
        if (! isempty (v))
          par = vecsym (who, "Parameters", v);
        endif
      case "force"
        if (! isa (v, "sym"))
          v = sym (v);
        endif
        if (numel (v) != numel (q))
          error ("Octave:invalid-input-arg",
                 "%s: Force must have %d components, as Q", who, numel (q));
        endif
        F = v(:);
      otherwise
        error ("Octave:invalid-input-arg", "%s: unknown option '%s'", who, name);
    endswitch
  endfor
endfunction

function v = vecsym (who, what, v)
  if (! isa (v, "sym") || ! isvector (v) || isempty (v))
    error ("Octave:invalid-input-arg", "%s: %s must be a vector of symbols", who, what);
  endif
  v = v(:);
  for k = 1:numel (v)
    if (! isempty (regexp (char (v(k)), '[^A-Za-z0-9_]', "once")))
      error ("Octave:invalid-input-arg",
             "%s: %s(%d) is not a symbol", who, what, k);
    endif
  endfor
endfunction
