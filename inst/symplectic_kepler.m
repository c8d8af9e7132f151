## Copyright (C) 2026 The symplectic developers
##
## This program is free software: you can redistribute it and/or modify it
## under the terms of the GNU General Public License as published by the Free
## Software Foundation, either version 3 of the License, or (at your option)
## any later version.  See the file COPYING.

## -*- texinfo -*-
## @deftypefn  {} {@var{dy} =} symplectic_kepler (@var{t}, @var{y})
## @deftypefnx {} {[@var{dy}, @var{ddy}] =} symplectic_kepler (@var{t}, @var{y})
## Kepler's problem in the plane, an example @var{fcn} for the solvers
## @code{odeSE}, @code{odeSV} and @code{odeSPVI}.
##
## H = |p|^2/2 - 1/|q| for y = [q1; q2; p1; p2]; @var{dy} = [dH/dp; -dH/dq]
## = [p; -q/|q|^3].  @var{y} may hold several states as its columns (the
## option @code{Vectorized}, and ensembles): @var{dy} then has a column
## per state, and a column gives the same numbers alone and among others.
## The second output is the 4-by-4 Hessian of H at a single state, which
## Newton's method of the implicit solvers uses; it is computed only when
## asked for.
##
## The orbit from y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))] has eccentricity e,
## period 2*pi and energy H = -1/2.
##
## @example
## @group
## e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
## opts = symplecticset ("TimeStepSize", 2*pi/100);
## [t, y] = odeSPVI (@@symplectic_kepler, [0 20*pi], y0, opts);
## H = sum (y(:,3:4).^2, 2)/2 - 1 ./ sqrt (sum (y(:,1:2).^2, 2));
## printf ("largest energy error over 10 periods: %.1e\n", max (abs (H + 0.5)));
## @end group
## @end example
## @seealso{odeSPVI, odeSV, odeSE, symplecticset}
## @end deftypefn

function [dy, ddy] = symplectic_kepler (t, y)

  if (nargin != 2)
    print_usage ();
  endif
  if (rows (y) != 4)
    error ("Octave:invalid-input-arg",
           "symplectic_kepler: Y must have 4 rows [q1; q2; p1; p2], got %d",
           rows (y));
  endif
  ## the rows from the transpose, whose columns are contiguous: indexing
  ## rows of a wide matrix costs far more than the arithmetic on them
  z = y.';
  x = z(:,1);  v = z(:,2);
  r2 = x .* x + v .* v;
  r3 = r2 .* sqrt (r2);
  dy = [z(:,3), z(:,4), -x ./ r3, -v ./ r3].';
  if (nargout > 1)
    if (columns (y) != 1)
      error ("Octave:invalid-input-arg",
             "symplectic_kepler: the Hessian is for one state, got %d columns",
             columns (y));
    endif
    q = [x; v];
    ddy = [(eye (2) - 3 * (q * q.') / r2) / r3, zeros(2); zeros(2), eye(2)];
  endif

endfunction

%!test
%! ## f against its formula, several columns alike alone and together
%! Y = [1 0.4 -2; 0 0.3 0.5; 0 1 0.1; 1.2 -0.5 0.7];
%! F = symplectic_kepler (0, Y);
%! for j = 1:3
%!   q = Y(1:2,j);
%!   assert (F(:,j), [Y(3:4,j); -q / norm(q)^3], 1e-15);
%!   assert (symplectic_kepler (0, Y(:,j)), F(:,j));
%! endfor

%!test
%! ## the Hessian against central differences of the gradient of H
%! y = [0.7; -0.4; 0.3; 1.1];
%! [~, ddy] = symplectic_kepler (0, y);
%! gradH = @(y) [-1 0 0 0; 0 -1 0 0; 0 0 1 0; 0 0 0 1] ...
%!              * symplectic_kepler (0, y)([3 4 1 2]);
%! h = 1e-6;  D = zeros (4);
%! for j = 1:4
%!   e = zeros (4, 1);  e(j) = h;
%!   D(:,j) = (gradH (y + e) - gradH (y - e)) / (2*h);
%! endfor
%! assert (ddy, D, 1e-8);
%! assert (ddy, ddy.', 1e-15);

%!test
%! ## the help's example: odeSPVI (4, 3), 10 periods of e = 0.6 at h = T/100
%! e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
%! opts = symplecticset ("TimeStepSize", 2*pi/100);
%! [t, y] = odeSPVI (@symplectic_kepler, [0 20*pi], y0, opts);
%! H = sum (y(:,3:4).^2, 2)/2 - 1 ./ sqrt (sum (y(:,1:2).^2, 2));
%! assert (max (abs (H + 0.5)) < 1e-5);
%! assert (y(end,:), y0.', 1e-3);

%!error <Invalid call> symplectic_kepler (1)
%!error <Y must have 4 rows> symplectic_kepler (0, [1; 0])
%!error <the Hessian is for one state, got 2 columns> [a, b] = symplectic_kepler (0, ones (4, 2))
