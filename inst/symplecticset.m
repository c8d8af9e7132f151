## Copyright (C) 2026 The symplectic developers
##
## This program is free software: you can redistribute it and/or modify it
## under the terms of the GNU General Public License as published by the Free
## Software Foundation, either version 3 of the License, or (at your option)
## any later version.  See the file COPYING.

## -*- texinfo -*-
## @deftypefn  {} {@var{opts} =} symplecticset ()
## @deftypefnx {} {@var{opts} =} symplecticset (@var{name}, @var{value}, @dots{})
## @deftypefnx {} {@var{opts} =} symplecticset (@var{oldopts}, @var{name}, @var{value}, @dots{})
## @deftypefnx {} {@var{opts} =} symplecticset (@var{oldopts}, @var{newopts})
## Create or modify an options structure for the symplectic solvers
## @code{odeSE}, @code{odeSV} and @code{odeSPVI}.
##
## @code{symplecticset} works as @code{odeset} and accepts all of its
## fields, plus the fields of this package, without the warning that
## @code{odeset} gives for names it does not know.  Names are matched
## without regard to case; the fields of the result have the canonical
## spelling below.  With no arguments and no output it lists the fields,
## their values and defaults.  The package's fields:
##
## @table @code
## @item TimeStepSize
## Constant step size h > 0: the mode in which the long-time behaviour
## of energy and momenta is guaranteed.  Default: adaptive steps.
## @item TimeStepNumber
## With @code{TimeStepSize}: take exactly this many steps from t0.
## Alone: that many equal steps over @var{tspan}.
## @item Separable
## @qcode{"on"} when H = T(p) + V(q): @code{odeSE} and @code{odeSV} then
## take explicit steps.  Default @qcode{"off"}.
## @item SecondOrder
## @qcode{"on"}: @code{odeSE} and @code{odeSV} take @var{fcn} as the
## acceleration, @code{a = fcn (t, q)}, and y = [q; v].
## @item Method
## @code{odeSV}: the Verlet composition or splitting method
## (@qcode{"verlet"}, @qcode{"yoshida4"}, @dots{}; @code{help odeSV}).
## @item CompensatedSummation
## @code{odeSV}: @qcode{"on"} sums the updates of explicit steps with
## compensation.  Default @qcode{"on"} for the explicit steps of a
## @code{Method} other than @qcode{"verlet"} and for reversible ones,
## else @qcode{"off"}.
## @item VerletForm
## @code{odeSV}: @qcode{"velocity"} (kick-drift-kick, the default) or
## @qcode{"position"} (drift-kick-drift; explicit steps only).
## @item Nodes, Q_DoFs, PolynomialDegree
## @code{odeSPVI}: Gauss--Legendre nodes m (1 to 40, default 3;
## @code{P_DoFs} is an alias), Legendre modes of q (2 to min(2m, 41),
## default m+1), or the degree of q, which sets both.
## @item StepControl, StepDensityFcn
## @qcode{"standard"} (error estimates, as @code{ode45}; the default) or
## @qcode{"reversible"} (@code{odeSV}, @code{odeSPVI}: time-symmetric
## steps that keep the energy error bounded), and the latter's step
## density, a handle @code{rho = fcn (t, y, @dots{})} in steps per unit
## time.
## @item HamiltonianHessFcn
## Handle @code{hess (t, y, @dots{})} returning the Hessian of H with
## respect to y = [q; p], 2d-by-2d or its column-major vector.
## @item NewtonTol, MaxNewtonIterations
## Newton's tolerance, relative to the size of q and of p (default
## 1e-14), and its iterations per solve (default 10).
## @item NewtonMatrix, NewtonSystem
## @code{odeSPVI}: how Newton's matrix is kept (@qcode{"kept"},
## @qcode{"new"}) and its systems solved (@qcode{"full"},
## @qcode{"stages"}).  Default @qcode{"auto"}.
## @item NonlinearSolver
## @code{odeSPVI} with Q_DoFs = Nodes + 1: the step's equations by Newton
## (@qcode{"newton"}, default), by fixed-point iteration with Newton where
## it fails (@qcode{"fixedpoint"}), or by fixed point until it is slow
## (@qcode{"auto"}).
## @item MaxSteps
## Largest number of steps of a run.  Default: no limit.
## @item Hamiltonian
## Handle @code{H (t, y, @dots{})}: its values at @code{sol.x} come back
## in @code{sol.H}, their largest relative change in
## @code{sol.stats.max_dH} and in @code{Stats}.
## @item Dense
## @qcode{"on"}: @code{sol} keeps each step's dense output, which
## @code{symdeval} evaluates at any time.  Default @qcode{"off"}.
## @item Constraints
## @code{odeSV}: handle @code{g = con (q)} (or @code{[g, G] = con (q)},
## G = dg/dq) of holonomic constraints g(q) = 0; RATTLE steps
## (@code{help odeSV}).  Default: none.
## @item Ensemble, Parallel
## @qcode{"on"}: the columns of @var{y0} are the initial states of
## members integrated together; the number of local processes to split
## them across, or the connections @code{pconnect} returned (package
## @code{parallel}; any other value is an error).  Default
## @qcode{"off"}, 1.  A process that dies holding members ends the call
## with the error @code{symplectic:parallel-worker} naming them.
## @item TangentMap, Indicators
## @code{odeSE}, @code{odeSV}: @qcode{"on"} (or a 2d-by-k V0) gives
## Phi = dy_k/dy_0 (Phi*V0) in @code{sol.phi}; @qcode{"lyapunov"} the
## maximal Lyapunov exponent in @code{sol.lyapunov}.  @code{help odeSE}.
## @end table
##
## A name that neither @code{odeset} nor this package knows gets a
## warning with the nearest known name.  Arguments are taken in order, a
## later value of a name replacing an earlier one; a field of a struct
## replaces only when it is not empty, a name/value pair always.  Add
## options to a struct with @code{symplecticset (opts, @dots{})}, which
## does not warn (@code{odeset} warns for the package's fields); setting
## a field by assignment, @code{opts.Nodes = 4}, works as well.  Every
## option, its values and the solvers that use it: the user guide,
## @file{doc/user-guide.md} in the package's directory,
## @code{pkg ("list", "symplectic")@{1@}.dir}.
##
## @example
## @group
## opts = symplecticset ("TimeStepSize", 0.01, "Nodes", 4);
## [t, y] = odeSPVI (@@(t, y) [y(2); -sin(y(1))], [0 10], [1; 0], opts);
## @end group
## @end example
## @seealso{odeset, odeget, odeSPVI, odeSE, odeSV, symdeval}
## @end deftypefn

function opts = symplecticset (varargin)

  persistent fields = {"TimeStepSize", "TimeStepNumber", "Q_DoFs", ...
                       "Nodes", "P_DoFs", "PolynomialDegree", ...
                       "HamiltonianHessFcn", "Separable", "Explicit", ...
                       "SecondOrder", "Method", "CompensatedSummation", ...
                       "VerletForm", ...
                       "Constraints", ...
                       "NewtonTol", "MaxNewtonIterations", "NewtonMatrix", ...
                       "NewtonSystem", "NonlinearSolver", "MaxSteps", "Hamiltonian", "Dense", "StepControl", ...
                       "StepDensityFcn", "Ensemble", "Parallel", ...
                       "TangentMap", "Indicators"};
  persistent odeset_fields = fieldnames (odeset ());

  if (nargin == 0 && nargout == 0)
    odeset ();
    printf ("\nOptions of the symplectic package:\n");
    printf ("       TimeStepSize:  scalar, >0, [] (adaptive)\n");
    printf ("     TimeStepNumber:  integer, >0, []\n");
    printf ("             Q_DoFs:  integer, 2..min(2*Nodes,41), [Nodes+1]\n");
    printf ("              Nodes:  integer, 1..40, [3] (alias P_DoFs)\n");
    printf ("   PolynomialDegree:  integer, 1..39, []\n");
    printf (" HamiltonianHessFcn:  function handle, []\n");
    printf ("          Separable:  {[\"off\"], \"on\"}\n");
    printf ("        SecondOrder:  {[\"off\"], \"on\"}\n");
    printf ("             Method:  string, [\"verlet\"] (odeSV)\n");
    printf ("CompensatedSummation: {\"off\", \"on\"}, [on for Method's and reversible explicit steps]\n");
    printf ("         VerletForm:  {[\"velocity\"], \"position\"} (odeSV)\n");
    printf ("        Constraints:  function handle, [] (odeSV)\n");
    printf ("          NewtonTol:  scalar, >0, [1e-14]\n");
    printf ("MaxNewtonIterations:  integer, >0, [10]\n");
    printf ("       NewtonMatrix:  {[\"auto\"], \"kept\", \"new\"}\n");
    printf ("       NewtonSystem:  {[\"auto\"], \"full\", \"stages\"}\n");
    printf ("    NonlinearSolver:  {[\"newton\"], \"fixedpoint\", \"auto\"} (odeSPVI)\n");
    printf ("           MaxSteps:  integer, >0, [] (no limit)\n");
    printf ("        Hamiltonian:  function handle, []\n");
    printf ("              Dense:  {[\"off\"], \"on\"}\n");
    printf ("        StepControl:  {[\"standard\"], \"reversible\"}\n");
    printf ("     StepDensityFcn:  function handle, []\n");
    printf ("           Ensemble:  {[\"off\"], \"on\"}\n");
    printf ("           Parallel:  integer, >0, [1]; or pconnect's connections\n");
    printf ("         TangentMap:  {[\"off\"], \"on\"}, or a 2d-by-k matrix\n");
    printf ("         Indicators:  {[\"none\"], \"lyapunov\"}\n");
    return;
  endif

  ## Every argument in order, the last value of a name winning: a field of
  ## a struct only when it is not empty (as odeset documents for
  ## NEWSTRUCT; Octave 7's odeset (OLD, NEW) empties OLD's fields instead),
  ## a name/value pair always.  odeset's part is collected as pairs, one
  ## per name (matched without regard to case), and given to odeset once.
  ours = struct ();
  names = {};
  vals = {};
  i = 1;
  while (i <= nargin)
    a = varargin{i};
    if (isstruct (a))
      if (! isscalar (a))
        error ("Octave:invalid-input-arg",
               "symplecticset: option structs must be 1x1");
      endif
      fn = fieldnames (a);
      for k = 1:numel (fn)
        [ours, names, vals] = put (ours, names, vals, fields, fn{k},
                                   a.(fn{k}), false);
      endfor
      i += 1;
    elseif (ischar (a) && isrow (a))
      if (i == nargin)
        error ("Octave:invalid-input-arg",
               "symplecticset: option \"%s\" has no value", a);
      endif
      [ours, names, vals] = put (ours, names, vals, fields, a,
                                 varargin{i+1}, true);
      i += 2;
    elseif (ischar (a) && isempty (a))
      error ("Octave:invalid-input-arg",
             "symplecticset: argument %d is an empty option name; expected an option name such as \"TimeStepSize\"",
             i);
    else
      error ("Octave:invalid-input-arg",
             "symplecticset: expected option names (strings) or structs, argument %d is a %s",
             i, class (a));
    endif
  endwhile

  ## a name neither odeset nor the package knows: said with the nearest
  ## known name, and kept in the result (the solvers say it again)
  known = ismember (lower (names), lower (odeset_fields));
  for k = find (! known)
    hint = nearest_name (names{k}, [odeset_fields(:); fields(:)]);
    warning ("symplectic:unknown-option",
             "symplecticset: unknown option %s%s", names{k}, hint);
  endfor
  pairs = [names(known); vals(known)];
  opts = odeset (pairs{:});
  for k = find (! known)
    opts.(names{k}) = vals{k};
  endfor
  for k = 1:numel (fields)
    if (isfield (ours, fields{k}))
      opts.(fields{k}) = ours.(fields{k});
    elseif (! isfield (opts, fields{k}))
      opts.(fields{k}) = [];
    endif
  endfor

endfunction

## Set option NAME to V: a package field in OURS (canonical name), any
## other in the pairs NAMES/VALS (one entry per name, case-insensitive).
## From a struct (always = false) an empty V only fills a name not yet set.
## "; did you mean NAME?" for the known name nearest to name (edit
## distance without regard to case, at most 2 or a third of its length),
## or ""
function hint = nearest_name (name, known)
  hint = "";
  best = Inf;
  a = lower (name);
  for k = 1:numel (known)
    b = lower (known{k});
    d = 0:numel (b);
    for i = 1:numel (a)
      prev = d;
      d(1) = i;
      for j = 1:numel (b)
        d(j+1) = min ([prev(j+1) + 1, d(j) + 1, prev(j) + (a(i) != b(j))]);
      endfor
    endfor
    if (d(end) < best)
      best = d(end);
      hint = known{k};
    endif
  endfor
  if (best <= 2 || 3 * best <= numel (hint))
    hint = sprintf ("; did you mean %s?", hint);
  else
    hint = "";
  endif
endfunction

function [ours, names, vals] = put (ours, names, vals, fields, name, v, always)
  j = find (strcmpi (name, fields), 1);
  if (! isempty (j))
    if (always || ! isempty (v) || ! isfield (ours, fields{j}))
      ours.(fields{j}) = v;
    endif
    return;
  endif
  k = find (strcmpi (name, names), 1);
  if (isempty (k))
    names{end+1} = name;
    vals{end+1} = v;
  elseif (always || ! isempty (v))
    vals{k} = v;
  endif
endfunction

%!demo
%! ## Options: one struct of symplecticset for the common settings, and
%! ## symplecticset (opts, ...) for each variant.  Kepler's problem
%! ## (e = 0.6, 10 periods, 50 fixed steps per period) with odeSPVI at
%! ## 2 to 5 nodes: the energy error falls with the order, 2*Nodes.
%! opts = symplecticset ("TimeStepSize", 2*pi/50, "Vectorized", "on");
%! H = @(y) sum (y(:,3:4).^2, 2)/2 - 1 ./ sqrt (sum (y(:,1:2).^2, 2));
%! e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];
%! printf ("odeSPVI, Kepler e = 0.6, h = T/50, 10 periods:\n");
%! runs = {};
%! for m = 2:5
%!   o = symplecticset (opts, "Nodes", m);
%!   [t, y] = odeSPVI (@symplectic_kepler, [0 20*pi], y0, o);
%!   dH = max (abs (H (y) + 0.5), eps);
%!   runs(end+1, :) = {t / (2*pi), dH};
%!   printf ("  Nodes = %d (order %2d): largest energy error %.2e\n", m, 2*m, max (dH));
%! endfor
%! ## the figure; with no display it is drawn off screen and written to a
%! ## PNG, and with no graphics toolkit that works the numbers are all
%! warning ("off", "Octave:gnuplot-graphics", "local");
%! headless = ! have_window_system ();
%! try
%!   if (headless)
%!     fig = figure ("visible", "off");
%!   else
%!     fig = figure ();
%!   endif
%!   semilogy (runs'{:});
%!   xlabel ("periods");  ylabel ("|H(t) - H(0)|");
%!   legend ("Nodes = 2", "3", "4", "5", "location", "eastoutside");
%!   title ("Kepler, e = 0.6, h = T/50: energy error");
%!   if (headless)
%!     print (fig, "symplecticset-demo.png", "-dpng", "-r100");
%!     printf ("no display: figure written to %s\n", fullfile (pwd, "symplecticset-demo.png"));
%!   endif
%! catch err
%!   printf ("no figure (%s)\n", err.message);
%! end_try_catch

## odeset warns for the package's fields of a symplecticset struct (the
## help says so); symplecticset adds to it without a warning
%!test
%! lastwarn ("");
%! evalc ("o = odeset (symplecticset ('Nodes', 4), 'RelTol', 1e-6);");
%! assert (regexp (lastwarn (), "unknown option"));
%! lastwarn ("");
%! o = symplecticset (symplecticset ("Nodes", 4), "RelTol", 1e-6);
%! assert (lastwarn (), "");
%! assert ([o.Nodes, o.RelTol], [4 1e-6]);

%!test
%! opts = symplecticset ("TimeStepSize", 0.1, "q_dofs", 4, "RelTol", 1e-5);
%! assert (opts.TimeStepSize, 0.1);
%! assert (opts.Q_DoFs, 4);
%! assert (opts.RelTol, 1e-5);
%! assert (isempty (opts.Nodes));
%! assert (isfield (opts, "AbsTol"));

%!test
%! ## a typo: said in the package's name, with the nearest option
%! lastwarn ("");
%! opts = symplecticset ("Nodse", 3);
%! [msg, id] = lastwarn ();
%! assert (id, "symplectic:unknown-option");
%! assert (msg, "symplecticset: unknown option Nodse; did you mean Nodes?");
%! assert (opts.Nodse, 3);
%! lastwarn ("");
%! opts = symplecticset ("Zzzzzz", 1);
%! assert (lastwarn (), "symplecticset: unknown option Zzzzzz");

%!test
%! ## no warning for the package's names
%! lastwarn ("");
%! opts = symplecticset ("Nodes", 3, "Separable", "on", "newtonmatrix", "new");
%! assert (lastwarn (), "");
%! assert (opts.Separable, "on");
%! assert (opts.NewtonMatrix, "new");

%!test
%! ## merging with an old struct keeps its values
%! old = symplecticset ("Nodes", 5, "RelTol", 1e-4);
%! new = symplecticset (old, "TimeStepSize", 0.5);
%! assert (new.Nodes, 5);
%! assert (new.RelTol, 1e-4);
%! assert (new.TimeStepSize, 0.5);
%! new2 = symplecticset (old, struct ("nodes", 2));
%! assert (new2.Nodes, 2);

%!test
%! ## (OLDOPTS, NEWOPTS): the empty fields of NEWOPTS leave OLDOPTS's, for
%! ## odeset's fields too (odeset (OLD, NEW) of Octave 7 empties them)
%! base = symplecticset ("RelTol", 1e-10, "AbsTol", 1e-12, "Nodes", 5);
%! o = symplecticset (base, symplecticset ("TimeStepSize", 0.1));
%! assert ([o.RelTol, o.AbsTol, o.Nodes, o.TimeStepSize], [1e-10, 1e-12, 5, 0.1]);
%! o = symplecticset (base, odeset ("AbsTol", 1e-9));
%! assert ([o.RelTol, o.AbsTol], [1e-10, 1e-9]);
%! ## arguments in order, the last value winning; a pair sets even []
%! o = symplecticset ("Nodes", 5, "RelTol", 1e-5, struct ("Nodes", 2, "RelTol", 1e-2));
%! assert ([o.Nodes, o.RelTol], [2, 1e-2]);
%! o = symplecticset (base, "RelTol", [], "reltol", 1e-7);
%! assert (o.RelTol, 1e-7);
%! o = symplecticset (base, "RelTol", []);
%! assert (isempty (o.RelTol));

%!error <option "Nodes" has no value> symplecticset ("Nodes")
%!error <expected option names> symplecticset (3)
%!error <argument 3 is an empty option name> symplecticset ("Nodes", 3, "", 2)
