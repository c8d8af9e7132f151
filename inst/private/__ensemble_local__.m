## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## -*- texinfo -*-
## @deftypefn {} {@var{res} =} __ensemble_local__ (@var{name}, @var{nc}, @var{jobs}, @var{first}, @var{last})
## The chunks @var{jobs} of a Parallel run of solver @var{name} (members
## @var{first}(c) to @var{last}(c)) in local processes of the parallel
## package (private).  @var{res}@{c@}: what @code{__ensemble_chunk__}
## returned for chunk c.
##
## Each chunk has a file (@code{mark}) while it runs, where its process
## writes its id: if the process dies, the file names the members it
## held.  On any error the package ends its processes, and any of this
## run's that is left is killed and reaped.  A process that died holding
## a chunk makes the error @code{symplectic:parallel-worker} naming its
## members.
##
## Ctrl-C does not reach the run until its chunks end: the package's wait
## for a result ignores Octave's interrupt (the interrupt goes to another
## thread, and the wait, a @code{poll} without timeout, is not woken).
## @end deftypefn

function res = __ensemble_local__ (name, nc, jobs, first, last)

  ## a private function's handle reaches the other process with its
  ## file (the gateway's by its name, on the path it is given there)
  worker = @__ensemble_chunk__;
  ## the processes it starts must not hold this one's pipes (the
  ## symbolic package's Python would wait on them, and so Octave's exit)
  __cloexec__ ();
  marks = tempname ();
  mkdir (marks);
  for c = 1:nc
    jobs{c}.mark = fullfile (marks, sprintf ("%d", c));
  endfor
  ended = false;
  unwind_protect
    try
      ## the package's own lines on a failure ("could not receive
      ## result") are not the user's: the error below says what it was
      evalc ("res = parcellfun (nc, worker, jobs, 'UniformOutput', false);");
      ended = true;
    catch err
      ended = true;
      worker_failed (name, jobs, first, last, err);
    end_try_catch
  unwind_protect_cleanup
    if (! ended)
      ## interrupted (once the chunks ended): the processes go too
      end_pool (mark_pids (jobs));
    endif
    for c = 1:nc
      [~, ~] = unlink (jobs{c}.mark);
    endfor
    [~, ~] = rmdir (marks);
  end_unwind_protect

endfunction

## The process ids in the chunks' files (NaN: none yet, or ended).
function pid = mark_pids (jobs)
  pid = NaN (1, numel (jobs));
  for c = 1:numel (jobs)
    try
      pid(c) = str2double (fileread (jobs{c}.mark));
    catch
    end_try_catch
  endfor
  pid(! (pid > 0)) = NaN;
endfunction

## This run's processes (PIDS) are killed, then the package ends all its
## processes and reaps them; any of PIDS still there is reaped here.
## Killed first, they print nothing (one the package ends may print its
## lines, "could not read second variable").  The package's lines, and
## the SIGPIPE of its writes to the killed ones (Octave reports it at its
## next command run), are not the user's.
function end_pool (pids)
  pids = pids(isfinite (pids));
  for p = pids
    [ppid, state] = proc_parent (p);
    if (ppid == getpid () && ! strcmp (state, "Z"))
      kill (p, SIG ().KILL);
    endif
  endfor
  try
    evalc ("parcellfun_set_nproc (0); system ('true');");
  catch
  end_try_catch
  for p = pids
    [ppid, state] = proc_parent (p);
    if (ppid == getpid ())
      if (! strcmp (state, "Z"))
        kill (p, SIG ().KILL);
      endif
      waitpid (p);
    endif
  endfor
endfunction

## The run failed: a process of the parallel package ended without
## returning its chunk (it exited, was killed, or crashed), or the
## package itself failed.  The dead process is the one of the chunks
## still running that has ended (an Octave that exits takes a moment):
## it is reaped here, for how it ended.  Then the package ends all its
## processes (they are started again by the next run), and any of this
## run's that is left is killed and reaped: no process and no zombie
## stays behind.  The error names the members the dead process held.
function worker_failed (name, jobs, first, last, err)
  pid = mark_pids (jobs);
  held = find (isfinite (pid));
  dead = [];
  how = {};
  t0 = tic ();
  while (! isempty (held))
    for c = held
      [p, st] = waitpid (pid(c), WNOHANG ());
      if (p == pid(c))
        dead(end+1) = c;
        how{end+1} = ended_how (st);
      elseif (p < 0 && ! exist (sprintf ("/proc/%d", pid(c)), "dir")
              && exist ("/proc/self", "dir"))
        dead(end+1) = c;   # not this process's child: gone, how unknown
        how{end+1} = "ended";
      endif
    endfor
    if (! isempty (dead) || toc (t0) > 1)
      break;
    endif
    pause (0.01);
  endwhile
  end_pool (pid(held));
  if (! isempty (dead))
    parts = arrayfun (@(c, h) sprintf ("the process that ran members %d to %d %s before it returned them",
                                       first(c), last(c), h{1}),
                      dead, how, "UniformOutput", false);
    msg = sprintf ("%s: Parallel: %s", name, strjoin (parts, "; "));
  else
    msg = sprintf ("%s: Parallel: a process of the parallel package failed (%s)",
                   name, err.message);
    if (! isempty (held))
      parts = arrayfun (@(c) sprintf ("%d to %d", first(c), last(c)), held,
                        "UniformOutput", false);
      msg = sprintf ("%s; members %s were not done", msg,
                     strjoin (parts, ", "));
    endif
  endif
  error ("symplectic:parallel-worker", "%s", msg);
endfunction

function s = ended_how (st)
  if (WIFEXITED (st))
    s = sprintf ("exited with status %d", WEXITSTATUS (st));
  elseif (WIFSIGNALED (st))
    sig = SIG ();
    fn = fieldnames (sig);
    k = find (cellfun (@(f) sig.(f) == WTERMSIG (st), fn), 1);
    if (isempty (k))
      s = sprintf ("was killed by signal %d", WTERMSIG (st));
    else
      s = sprintf ("was killed by signal %d (SIG%s)", WTERMSIG (st), fn{k});
    endif
  else
    s = "ended";
  endif
endfunction

## A process's parent and state, from /proc (NaN where there is none).
function [ppid, state] = proc_parent (pid)
  ppid = NaN;
  state = "";
  try
    s = fileread (sprintf ("/proc/%d/stat", pid));
  catch
    return;
  end_try_catch
  k = rindex (s, ")");   # the name, in parentheses, may hold blanks
  v = strsplit (strtrim (s(k+1:end)), " ");
  if (numel (v) >= 2)
    state = v{1};
    ppid = str2double (v{2});
  endif
endfunction
