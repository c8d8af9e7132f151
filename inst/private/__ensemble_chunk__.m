## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## -*- texinfo -*-
## @deftypefn {} {@var{r} =} __ensemble_chunk__ (@var{job})
## One chunk of a Parallel run, in a process of the parallel package
## (private: __ensemble_parallel__.m hands this function's handle to
## @code{parcellfun}, and a server of a @code{pconnect} network defines
## it from this file's text, so no option of the solvers reaches it).
##
## @var{job}: @code{gateway} (the solver's compiled gateway, or its name),
## @code{nout}, @code{members} ([first last]), @code{args} (the solver's
## arguments, all of @var{y0}) and @code{mark} (a file name, or empty).
## The chunk's members run through the gateway (its internal option
## @code{__members__}: FCN is checked at the first member of all, and
## the members keep their numbers in warnings and in @var{ie}), with
## what it prints and warns captured.  @var{r}: the outputs, that text,
## the last warning and the error (as data), in one struct.
##
## @code{mark} holds this process's id while the chunk runs (removed
## when it ends): if the process dies, the caller knows from it which
## members it held.
## @end deftypefn

function r = __ensemble_chunk__ (job)

  if (! isempty (job.mark))
    fid = fopen (job.mark, "w");
    if (fid >= 0)
      fprintf (fid, "%d\n", getpid ());
      fclose (fid);
    endif
  endif
  args = job.args;
  args{4}.__members__ = job.members;
  out = cell (1, max (job.nout, 1));
  err = [];
  ## the warnings as their bare lines (the caller warns again)
  bt = warning ("query", "backtrace");
  warning ("off", "backtrace");
  lastwarn ("");
  unwind_protect
    text = evalc ("try\n [out{:}] = feval (job.gateway, args{:});\ncatch err\nend_try_catch");
  unwind_protect_cleanup
    warning (bt.state, "backtrace");
  end_unwind_protect
  [lmsg, lid] = lastwarn ();
  if (! isempty (err))
    err = struct ("message", err.message, "identifier", err.identifier);
    out = {};
  endif
  r = struct ("out", {out}, "text", text, "lastwarn", {{lmsg, lid}},
              "error", err);
  if (! isempty (job.mark))
    unlink (job.mark);
  endif

endfunction
