## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## -*- texinfo -*-
## @deftypefn  {} {@var{fcn} =} symcompile (@var{source})
## @deftypefnx {} {@var{fcn} =} symcompile (@var{file})
## Compile Hamilton's equations written in C into an FCN that odeSE, odeSV
## and odeSPVI call directly, with no Octave call per evaluation.
##
## @var{source} is the C code as a string, or @var{file} the name of a
## @file{.c} file.  It includes @file{symplectic_fcn.h} (installed with the
## package, beside this function; it documents every function) and defines:
##
## @itemize
## @item @code{SYMPLECTIC_SYSTEM (d, npar);} once: d degrees of freedom
## (y = [q; p] has 2d components) and npar parameters;
## @item @code{int symplectic_f (double t, const double *y, double *dy,
## const double *par)}: dy = [dH/dp; -dH/dq + F];
## @item optionally @code{symplectic_hess_pattern} and
## @code{symplectic_hess}: the Hessian of H with its nonzero pattern
## (compressed columns), Newton's matrix of the implicit steps (sparse for
## large systems with few entries, and JPattern follows from it);
## @code{symplectic_accel}: the acceleration for @code{SecondOrder};
## @code{symplectic_energy}: H; @code{symplectic_f_batch}: f at several
## states at once (@code{Vectorized}, @code{Ensemble}).
## @end itemize
##
## Each function returns 0, or > 0 to ask for a smaller step, < 0 to stop.
## The parameters are the solver's first extra argument, a real vector of
## npar elements: @code{odeSV (fcn, tspan, y0, opts, par)}; a new value needs
## no new compile.
##
## The code is compiled with the C compiler and flags of @command{mkoctfile}
## (@code{mkoctfile -p CC}, @code{CFLAGS}, @code{CPICFLAG}) into a shared
## object in the per-user cache @file{$XDG_CACHE_HOME/symplectic} (default
## @file{~/.cache/symplectic}; a temporary directory when that cannot be
## written), named by a hash of the code, the compiler and its flags, the
## header and the package's version: the same code is compiled once, and
## later calls load it (@code{@var{fcn}.cached} is true then).  Headers that
## the code includes from elsewhere are not part of the hash.  Processes that
## build the same entry at once each write a file of their own and rename
## it into place.  A compile error shows the compiler's message and the path
## of the C file it compiled.
##
## @var{fcn} is also callable from Octave: @code{dy = fcn (t, y)},
## @code{[dy, hess] = fcn (t, y)} (the Hessian of H), @code{fcn.energy (t,
## y)}, @code{fcn.acceleration (t, q)}, with the parameters as a third
## argument; Y may have a column for each state.  @code{fcn.energy} alone is
## a function handle, for the option @code{Hamiltonian}.  Events, OutputFcn
## and the other options are Octave functions as always (they get PAR too).
##
## Example: the pendulum H = p^2/2 - cos q.
## @example
## @group
## fcn = symcompile (["#include <math.h>\n#include \"symplectic_fcn.h\"\n" ...
##   "SYMPLECTIC_SYSTEM (1, 0);\n" ...
##   "int symplectic_f (double t, const double *y, double *dy,\n" ...
##   "                  const double *par)\n" ...
##   "{ dy[0] = y[1]; dy[1] = -sin (y[0]); return 0; }\n"]);
## [t, y] = odeSV (fcn, [0 10], [1; 0], symplecticset ("TimeStepSize", 0.01));
## @end group
## @end example
## @seealso{symhamiltonian, odeSV, odeSPVI, odeSE}
## @end deftypefn

function fcn = symcompile (source)
  if (nargin != 1)
    print_usage ();
  endif
  if (! ischar (source) || (! isrow (source) && ! isempty (source)))
    error ("Octave:invalid-input-arg",
           "symcompile: SOURCE must be C code or the name of a .c file, as a string");
  endif
  srcdir = "";
  if (! any (source == "\n"))
    if (! exist (source, "file"))
      error ("Octave:invalid-input-arg",
             "symcompile: %s is no file (give the C code itself, or the name of a .c file)",
             source);
    endif
    file = source;
    source = fileread (file);
    srcdir = fileparts (make_absolute_filename (file));
  endif
  fcn = __symcompile_build__ (source, srcdir, struct ());
endfunction

%!shared src
%! src = ["#include <math.h>\n#include \"symplectic_fcn.h\"\n" ...
%!        "SYMPLECTIC_SYSTEM (1, 1);\n" ...
%!        "int symplectic_f (double t, const double *y, double *dy,\n" ...
%!        "                  const double *par)\n" ...
%!        "{ dy[0] = y[1]; dy[1] = -par[0] * sin (y[0]); return 0; }\n"];
%!test
%! fcn = symcompile (src);
%! assert (fcn (0, [1; 2], 3), [2; -3 * sin(1)], 1e-15);
%! opts = symplecticset ("TimeStepSize", 0.1, "Separable", "on");
%! [t, y] = odeSV (fcn, [0 1], [1; 0], opts, 9.81);
%! [t2, y2] = odeSV (@(t, y, g) [y(2); -g * sin(y(1))], [0 1], [1; 0], opts, 9.81);
%! assert (y, y2, 1e-14);
%!error <SOURCE must be C code> symcompile (1)
%!error <is no file> symcompile ("no_such_file_here.c")
%!error <odeSV: the compiled FCN takes its parameters> ...
%! odeSV (symcompile (src), [0 1], [1; 0], symplecticset ("TimeStepSize", 0.1));
