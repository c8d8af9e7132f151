## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## -*- texinfo -*-
## @deftypefn  {} {@var{tf} =} __ensemble_parallel__ (@var{name}, @var{opts})
## @deftypefnx {} {[@dots{}] =} __ensemble_parallel__ (@var{name}, @var{gateway}, @var{nout}, @var{fcn}, @var{tspan}, @var{y0}, @var{opts}, @dots{})
## The option @code{Parallel} of odeSE, odeSV and odeSPVI (private).
##
## With two arguments: whether @var{opts} sets @code{Parallel} to anything
## but 1 (the solver then calls the second form; otherwise its gateway).
##
## With more: the run of solver @var{name} (its compiled gateway
## @var{gateway}, @var{nout} outputs asked for) with the columns of
## @var{y0}, the ensemble's members, split into contiguous chunks, each
## run as an ensemble by @var{name} in another Octave process: local ones
## through @code{parcellfun}, or servers of a @code{pconnect} network.
## The chunks' outputs are merged into those of the run of all members in
## this process, to the bit; their printed output (Stats) and warnings are
## given here.
##
## The other process runs its chunk through @code{__ensemble_chunk__}
## (private, by its handle: no option of the solver reaches it), which
## returns the chunk's outputs, what it printed and warned, and its
## error, in one struct.  Local processes: @code{__ensemble_local__}
## (Ctrl-C, a process that dies).
## @end deftypefn

function varargout = __ensemble_parallel__ (name, varargin)

  if (nargin == 2)
    opts = varargin{1};
    if (! isscalar (opts))
      varargout{1} = false;   # the gateway says what is wrong
      return;
    endif
    [v, ~, nset] = parallel_opt (opts);
    varargout{1} = nset > 1 || (nset == 1 && ! (isnumeric (v) && isscalar (v)
                                                 && v == 1));
    return;
  endif

  gateway = varargin{1};
  nout = varargin{2};
  args = varargin(3:end);
  opts = args{4};
  [P, names, nset] = parallel_opt (opts);
  if (nset > 1)
    given = names(cellfun (@(f) ! isempty (opts.(f)), names));
    error ("Octave:invalid-input-arg",
           "%s: OPTS sets both %s and %s (names are matched in any case); give one of them",
           name, given{1}, given{2});
  endif
  ## the gateway never sees Parallel (it would ignore it anyway)
  for i = 1:numel (names)
    opts.(names{i}) = [];
  endfor
  args{4} = opts;

  remote = isa (P, "pconnections");
  if (! remote && ! (isnumeric (P) && isreal (P) && isscalar (P)
                     && isfinite (P) && P >= 1 && P == fix (P)))
    error ("Octave:invalid-input-arg",
           "%s: Parallel must be a positive integer (the number of processes) or the connections pconnect returned, got %s",
           name, describe (P));
  endif
  fn = fieldnames (opts);
  given = fn(strcmpi (fn, "Ensemble"));
  given = given(cellfun (@(f) ! isempty (opts.(f)), given));
  if (numel (given) > 1)
    error ("Octave:invalid-input-arg",
           "%s: OPTS sets both %s and %s (names are matched in any case); give one of them",
           name, given{1}, given{2});
  endif
  if (! ensemble_on (opts))
    error ("Octave:invalid-input-arg", "%s: Parallel needs Ensemble on", name);
  endif
  if (nout == 0 || ! isempty (field_value (opts, "OutputFcn")))
    error ("Octave:invalid-input-arg",
           "%s: with Parallel, OutputFcn (and the plot of a call without outputs) cannot follow the members run in other processes; ask for outputs without OutputFcn, or set Parallel to 1",
           name);
  endif
  if (! remote)
    need_parallel_package (name);
  endif

  Y0 = args{3};
  K = columns (Y0);
  if (remote)
    info = network_get_info (P);
    servers = find (! [info.local_machine]);
    if (isempty (servers))
      error ("Octave:invalid-input-arg",
             "%s: Parallel: the connections hold no server", name);
    endif
    nc = min (numel (servers), K);
  else
    nc = min (double (P), K);
  endif
  if (nc < 1 || (nc == 1 && ! remote))
    ## one chunk (or no member): nothing to share out
    [varargout{1:nout}] = gateway (args{:});
    return;
  endif

  ## contiguous chunks, as even as possible, the first ones the larger
  sz = repmat (floor (K / nc), 1, nc);
  sz(1:mod (K, nc)) += 1;
  last = cumsum (sz);
  first = last - sz + 1;
  jobs = cell (1, nc);
  for c = 1:nc
    jobs{c} = struct ("gateway", gateway, "nout", nout,
                      "members", [first(c), last(c)], "args", {args},
                      "mark", "");
  endfor

  if (remote)
    res = run_remote (name, P, servers(1:nc), info(servers(1:nc)), jobs);
  else
    res = __ensemble_local__ (name, nc, jobs, first, last);
  endif

  ## a chunk's error is the run's (the first one, by member)
  for c = 1:nc
    e = res{c}.error;
    if (! isempty (e))
      if (isempty (e.message))
        e.message = sprintf ("%s: members %d to %d: unknown error", name,
                             first(c), last(c));
      elseif (strcmp (e.identifier, "Octave:undefined-function"))
        e.message = sprintf ("%s (in the process that ran members %d to %d: the functions the run calls must be on its path there; command-line functions do not go to other processes)",
                             e.message, first(c), last(c));
      endif
      error (struct ("message", e.message, "identifier", e.identifier));
    endif
  endfor

  seen = {};
  for c = 1:nc
    seen = replay (name, res{c}, first(c), last(c), K, seen);
  endfor

  outs = cellfun (@(r) r.out, res, "UniformOutput", false);
  if (nout == 1)
    varargout{1} = merge_sol (cellfun (@(o) o{1}, outs, "UniformOutput", false));
  else
    varargout = merge_rows (outs, nout);
  endif

endfunction

## The value of the option Parallel (the non-empty field whose name is
## Parallel in any case, as the gateway matches names), every field so
## named, and how many of them are set.
function [v, names, nset] = parallel_opt (opts)
  fn = fieldnames (opts);
  names = fn(strcmpi (fn, "Parallel"));
  v = [];
  nset = 0;
  for i = 1:numel (names)
    if (! isempty (opts.(names{i})))
      v = opts.(names{i});
      nset += 1;
    endif
  endfor
endfunction

function v = field_value (opts, name)
  fn = fieldnames (opts);
  v = [];
  for f = fn(strcmpi (fn, name))'
    if (! isempty (opts.(f{1})))
      v = opts.(f{1});
    endif
  endfor
endfunction

## Ensemble on, as the gateway reads it: "on"/"yes" or a non-zero scalar
function tf = ensemble_on (opts)
  v = field_value (opts, "Ensemble");
  if (ischar (v))
    tf = any (strcmpi (v, {"on", "yes"}));
  else
    tf = ((islogical (v) || (isnumeric (v) && isreal (v))) && isscalar (v)
          && isfinite (v) && v != 0);
  endif
endfunction

function s = describe (v)
  if (ischar (v))
    s = sprintf ("\"%s\"", v(:)');
  elseif ((isnumeric (v) || islogical (v)) && isscalar (v))
    s = sprintf ("%s %s", class (v), num2str (v));
  else
    s = sprintf ("a %s %s", strjoin (arrayfun (@num2str, size (v),
                                                "UniformOutput", false), "x"),
                 class (v));
  endif
endfunction

function need_parallel_package (name)
  if (exist ("parcellfun") == 2)
    return;
  endif
  try
    pkg ("load", "parallel");
  catch
  end_try_catch
  if (exist ("parcellfun") != 2)
    error ("%s: Parallel needs the parallel package (Debian: octave-parallel; or pkg install -forge parallel)",
           name);
  endif
endfunction

## The chunks on the servers: each gets its job (after the command that
## runs it), then the results come back in order while the others run.
function res = run_remote (name, conns, idx, info, jobs)
  ## Run at the server, in its workspace: the package loaded if it is
  ## installed but not loaded, the chunk's runner defined from the text of
  ## its private file there (private functions cannot be reached from the
  ## workspace), errors returned as data.
  cmd = sprintf (["__symplectic_job__ = precv (sockets(1));\n", ...
                  "try\n", ...
                  "  if (! exist (\"%s\", \"file\"))\n", ...
                  "    try\n", ...
                  "      pkg load symplectic\n", ...
                  "    catch\n", ...
                  "    end_try_catch\n", ...
                  "  endif\n", ...
                  "  if (! exist (\"%s\", \"file\"))\n", ...
                  "    error (\"%s: Parallel: the server does not find %s; install the symplectic package there, or add it to the server's path (reval)\");\n", ...
                  "  endif\n", ...
                  "  eval (fileread (fullfile (fileparts (which (\"%s\")), \"private\", \"__ensemble_chunk__.m\")));\n", ...
                  "  __symplectic_res__ = __ensemble_chunk__ (__symplectic_job__);\n", ...
                  "catch __symplectic_err__\n", ...
                  "  __symplectic_res__ = struct (\"error\", struct (\"message\", __symplectic_err__.message, \"identifier\", __symplectic_err__.identifier));\n", ...
                  "end_try_catch\n", ...
                  "psend (__symplectic_res__, sockets(1));\n", ...
                  "clear __symplectic_job__ __symplectic_res__ __symplectic_err__\n"],
                 name, name, name, name, name);
  n = numel (idx);
  res = cell (1, n);
  c = 0;
  try
    for c = 1:n
      reval (cmd, conns(idx(c)));
      ## the gateway by its name: it resolves there once the package is
      ## loaded, after the job has arrived
      jobs{c}.gateway = func2str (jobs{c}.gateway);
      psend (jobs{c}, conns(idx(c)));
    endfor
    for c = 1:n
      res{c} = precv (conns(idx(c)));
      if (! isfield (res{c}, "out"))
        ## the server's own failure (the solver not found there)
        res{c} = struct ("out", {{}}, "text", "", "lastwarn", {{"", ""}},
                         "error", res{c}.error);
      endif
    endfor
  catch err
    ## a job may be left half done there: the network is no longer usable
    try
      sclose (conns);
    catch
    end_try_catch
    error ("%s: Parallel: server %s failed: %s (the connections are closed now)",
           name, info(max (c, 1)).peername, err.message);
  end_try_catch
endfunction

## A chunk's printed output under the range of its members, and its
## warnings again, from here (the members keep their numbers in them).
## A warning that is not a member's is given once for all chunks.
function seen = replay (name, r, first, last, K, seen)
  lines = regexp (r.text, '[^\n]*(\n|$)', "match");
  headed = false;
  shown = "";
  for i = 1:numel (lines)
    s = lines{i};
    if (! strncmp (s, "warning: ", 9))
      if (isempty (s))
        continue;
      endif
      if (! headed)
        printf ("Members %d to %d (of %d):\n", first, last, K);
        headed = true;
      endif
      fputs (stdout, s);
      shown = s;
      continue;
    endif
    msg = regexprep (s(10:end), '\n$', "");
    id = "";
    if (strcmp (msg, r.lastwarn{1}))
      id = r.lastwarn{2};
    elseif (strncmp (msg, [name ": "], numel (name) + 2))
      id = warning_id (msg);
    endif
    if (isempty (regexp (msg, '^\S+: member \d+: |the first of them is member', "once")))
      if (any (strcmp (msg, seen)))
        continue;
      endif
      seen{end+1} = msg;
    endif
    if (isempty (id))
      warning ("%s", msg);
    else
      warning (id, "%s", msg);
    endif
  endfor
  if (! isempty (shown) && shown(end) != "\n")
    fputs (stdout, "\n");
  endif
endfunction

## The identifier of one of the gateway's warnings (src/mex/messages.c,
## options.c, entry.c, ensemble_outputs.c) from its text: only the last warning
## of a chunk comes back with its identifier (lastwarn).
function id = warning_id (msg)
  persistent table = {
    "Newton's method did not converge", "symplectic:newton-failed"
    "returned NaN or Inf near t = |the solution overflowed", "symplectic:nonfinite"
    "the step size became too small", "symplectic:step-size"
    "StepDensityFcn returned", "symplectic:step-density"
    "MaxSteps reached at", "symplectic:max-steps"
    "a callback failed at", "symplectic:callback"
    "Separable is on, but FCN", "symplectic:not-separable"
    "more members stopped early or drew a warning", "symplectic:members"
    "OutputFcn asked to stop", "symplectic:output-stop"
    "TimeStepNumber\\*TimeStepSize ends at", "symplectic:tspan-beyond-end"
    "is not supported and is ignored", "symplectic:unsupported-option"
    "is below 100\\*eps", "symplectic:tolerance"
    "unknown option", "symplectic:unknown-option"
    "Y0 was off the Constraints", "symplectic:constraints-projected"
    "is ignored without StepControl|for adaptive steps only and|is used by .* only; ignored", "symplectic:ignored-option"};
  id = "";
  for i = 1:rows (table)
    if (! isempty (regexp (msg, table{i,1}, "once")))
      id = table{i,2};
      return;
    endif
  endfor
endfunction

## [t, Y, te, ye, ie] of the chunks as one run's: t the longest chunk's
## (a chunk whose members all stopped early is shorter), Y padded with
## NaN rows (the events come with their members' numbers).
function out = merge_rows (outs, nout)
  nc = numel (outs);
  nr = cellfun (@(o) rows (o{1}), outs);
  [R, longest] = max (nr);
  out = cell (1, nout);
  out{1} = outs{longest}{1};
  Ys = cell (1, nc);
  for c = 1:nc
    Y = outs{c}{2};
    if (rows (Y) < R)
      Y(rows (Y)+1:R, :, :) = NaN;
    endif
    Ys{c} = Y;
  endfor
  out{2} = cat (3, Ys{:});
  for j = 3:min (nout, 5)
    parts = cellfun (@(o) o{j}, outs, "UniformOutput", false);
    out{j} = vertcat (parts{:});
    if (isempty (out{j}))
      out{j} = [];   # none: 0x0, as the gateway gives
    endif
  endfor
  ## outputs past ie, if the gateway ever returns some: the first chunk's
  for j = 6:nout
    out{j} = outs{1}{j};
  endfor
endfunction

## The chunks' 1 x k struct arrays as one: the fields in the order of
## their first appearance, as the gateway builds its struct array.
function sol = merge_sol (sols)
  sol = sols{1};
  for c = 2:numel (sols)
    s = sols{c};
    for f = setdiff (fieldnames (s), fieldnames (sol), "stable")'
      [sol.(f{1})] = deal ([]);
    endfor
    for f = setdiff (fieldnames (sol), fieldnames (s), "stable")'
      [s.(f{1})] = deal ([]);
    endfor
    sol = [sol, orderfields(s, sol)];
  endfor
endfunction
