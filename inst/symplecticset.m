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
## spelling below.  The package's fields are:
##
## @table @code
## @item TimeStepSize
## Constant step size h > 0: no error control, the mode in which the
## long-time behaviour of energy and momenta is guaranteed.  The last step
## is shortened to end exactly on the final time.
## @item TimeStepNumber
## With @code{TimeStepSize}: take exactly this many steps from t0 (the end
## of @var{tspan} then only gives the direction; where t0 + N*h rounds to
## within 16 ulps of a time of @var{tspan}, as 3*0.7 does of 2.1, the last
## step ends on that time and its row is output).  Alone: that many equal
## steps over @var{tspan}.
## @item Q_DoFs
## @code{odeSPVI}: number of Legendre modes of q on each step (polynomial
## degree Q_DoFs-1), at least 2 and at most 2*Nodes and 41.  Default
## Nodes+1.
## @item Nodes
## @code{odeSPVI}: number of Gauss--Legendre quadrature nodes (1 to 40).
## Default 3.  @code{P_DoFs} is accepted as an alias.
## @item PolynomialDegree
## @code{odeSPVI}: sets Q_DoFs = degree+1, and Nodes = degree+1 unless
## Nodes is given (degree 1 to 39).
## Given together with Q_DoFs (or P_DoFs with Nodes) it
## must agree with it: @code{odeSPVI} refuses a disagreement.
## @item HamiltonianHessFcn
## Handle @code{hess (t, y, @dots{})} returning the Hessian of H with
## respect to y = [q; p], as a 2d-by-2d matrix or its column-major vector.
## @item Separable
## @qcode{"on"} when H = T(p) + V(q) (and no forcing depends on p):
## @code{odeSE} and @code{odeSV} then take explicit steps.  Default
## @qcode{"off"}.
## @item SecondOrder
## @qcode{"on"}: @code{odeSE} and @code{odeSV} take @var{fcn} as the
## acceleration, @code{a = fcn (t, q)} = -dV/dq of unit masses, and y =
## [q; v] (explicit steps, one call of @var{fcn} per force stage).
## Default @qcode{"off"}.
## @item Method
## @code{odeSV}: the Verlet composition or splitting method to use
## (@qcode{"verlet"}, @qcode{"yoshida4"}, @dots{}; the table is in
## @code{help odeSV}).  Default @qcode{"verlet"}.
## @item CompensatedSummation
## @code{odeSV}: @qcode{"on"} sums the updates of explicit (fixed or
## reversible) steps with compensation, which keeps the round-off of the
## energy of very long runs near that of a single step.  Default
## @qcode{"on"} for the explicit steps of a @code{Method} other than
## @qcode{"verlet"}, else @qcode{"off"}.
## @item VerletForm
## @code{odeSV}: the Verlet step of the method and of its compositions,
## @qcode{"velocity"} (kick-drift-kick, the default) or
## @qcode{"position"} (drift-kick-drift; explicit steps only).
## @item StepControl
## Adaptive steps: @qcode{"standard"} (error estimates, as
## @code{ode45}) or @qcode{"reversible"} (a time-symmetric step density
## that keeps the energy error bounded; @code{odeSV} and @code{odeSPVI},
## see @code{help odeSV}).  Default @qcode{"standard"}.
## @item StepDensityFcn
## With @code{StepControl} @qcode{"reversible"}: handle
## @code{rho = fcn (t, y, @dots{})} returning the step density rho > 0
## (1/time; the steps are eps/rho).  Default: |f(t,y)| / |y|.
## @item NewtonTol
## Stopping tolerance of Newton's method, relative to the size of q for
## the unknowns of q and to the size of p for those of p (in the units of
## each).
## Default 1e-14.  Fixed steps are converged to NewtonTol/100
## (@code{odeSPVI}) and NewtonTol/1000 (@code{odeSE}, @code{odeSV}).
## @item MaxNewtonIterations
## Newton iterations per solve before the matrix is refreshed or the step
## is retried.  Default 10.
## @item NewtonMatrix
## @code{odeSPVI}: @qcode{"kept"} keeps Newton's matrix (and its LU) across
## steps while Newton converges fast, evaluating the Hessian or Jacobian
## seldom; @qcode{"new"} evaluates it at the start of every step, so that
## the first Newton correction is exact and often the only one (fewer
## calls of @var{fcn}, but Hessians on every step).  Default
## @qcode{"auto"}: @qcode{"new"} when @code{Vectorized} is on and the
## matrix comes from finite differences (the nodes and their perturbed
## states then take one call) and (Q_DoFs-1+Nodes)*d <= 64, else
## @qcode{"kept"}.  Pairs other than Q_DoFs = Nodes+1 keep their matrix.
## @item NewtonSystem
## @code{odeSPVI}: how Newton's linear systems are solved.
## @qcode{"full"}: one LU of the whole step system, of size
## (Q_DoFs-1+Nodes)*d; @qcode{"stages"}: ceil(Nodes/2) systems of size 2d
## (d for a separable H with a full Hessian) that one Jacobian for all
## nodes reduces it to, for the pairs Q_DoFs = Nodes+1 only.  Default
## @qcode{"auto"}: @qcode{"stages"} when the Hessian or Jacobian is
## sparse, or when (Q_DoFs-1+Nodes)*d > 600, for those pairs; else
## @qcode{"full"}.
## @item MaxSteps
## Largest number of steps of a run.  Default: no limit.
## @item Hamiltonian
## Handle @code{H (t, y, @dots{})}: its values at @code{sol.x} come back
## in @code{sol.H}, their largest relative change in
## @code{sol.stats.max_dH} and in @code{Stats}.
## @item Dense
## @qcode{"on"}: @code{sol} keeps each step's dense output, which
## @code{symdeval} evaluates at any time.  Default @qcode{"off"}.
## @item Ensemble
## @qcode{"on"}: the columns of @var{y0} are the initial states of
## members integrated together (outputs in @code{help odeSE}, section
## Ensembles).  Default @qcode{"off"}.
## @item Parallel
## With @code{Ensemble} @qcode{"on"}: a positive integer P, the number of
## local processes the members are split across (1, the default: this
## process), or the connections @code{pconnect} returned, one process per
## server.  The columns of @var{y0} go in min(P, K) contiguous chunks, as
## even as possible, each run as an ensemble in another Octave process
## (@code{parcellfun}, or the servers), and the outputs are merged: they
## equal those of the run in this process to the bit, whatever P.  Stats
## are printed per chunk, under its members' range; the other processes'
## warnings are given here.  @var{fcn} and the functions it calls must
## exist in the other processes (anonymous functions go with their
## values, named ones must be function files on the path there).  Needs
## Octave's package @code{parallel}; not with @code{OutputFcn}, nor
## without outputs (the plot).
## @end table
##
## @code{Explicit}, the 2013 odepkg name of @code{Separable}, is accepted
## too.  A name that neither @code{odeset} nor this package knows gets a
## warning with the nearest known name, and is kept in the result.
##
## Arguments are taken in order, a later value of a name replacing an
## earlier one; a field of a struct replaces only when it is not empty (as
## @code{odeset} documents for @var{newopts}; Octave 7's @code{odeset}
## empties the fields of @var{oldopts} that are empty in @var{newopts},
## @code{symplecticset} does not), a name/value pair always.
##
## The result holds all the package's fields (empty unless set), so
## @code{odeset (opts, @dots{})} warns once for each of them, set or not;
## add options to such a struct with @code{symplecticset (opts, @dots{})}.
##
## Setting a field by assignment, @code{opts.Q_DoFs = 4}, works as well;
## scripts written for the odepkg solvers, which passed these names to
## @code{odeset}, keep working (with @code{odeset}'s warning).
##
## @example
## @group
## opts = symplecticset ("TimeStepSize", 0.01, "Nodes", 4, "RelTol", 1e-8);
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
                       "NewtonTol", "MaxNewtonIterations", "NewtonMatrix", ...
                       "NewtonSystem", "MaxSteps", "Hamiltonian", "Dense", "StepControl", ...
                       "StepDensityFcn", "Ensemble", "Parallel"};
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
    printf ("CompensatedSummation: {\"off\", \"on\"}, [on for Method's explicit steps]\n");
    printf ("         VerletForm:  {[\"velocity\"], \"position\"} (odeSV)\n");
    printf ("          NewtonTol:  scalar, >0, [1e-14]\n");
    printf ("MaxNewtonIterations:  integer, >0, [10]\n");
    printf ("       NewtonMatrix:  {[\"auto\"], \"kept\", \"new\"}\n");
    printf ("       NewtonSystem:  {[\"auto\"], \"full\", \"stages\"}\n");
    printf ("           MaxSteps:  integer, >0, [] (no limit)\n");
    printf ("        Hamiltonian:  function handle, []\n");
    printf ("              Dense:  {[\"off\"], \"on\"}\n");
    printf ("        StepControl:  {[\"standard\"], \"reversible\"}\n");
    printf ("     StepDensityFcn:  function handle, []\n");
    printf ("           Ensemble:  {[\"off\"], \"on\"}\n");
    printf ("           Parallel:  integer, >0, [1]; or pconnect's connections\n");
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
