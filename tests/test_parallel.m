## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## Parallel: an ensemble's members split into contiguous chunks, each run
## in another Octave process (parcellfun of the parallel package, or the
## servers of a pconnect network).  The truth every result is held to is
## the same ensemble run in this process (Parallel 1): t, Y, the events,
## sol must equal it to the bit (isequaln: the rows after a member's end
## are NaN in both), whatever the number of processes.  FCN and Events
## are anonymous functions throughout: the other processes get them with
## their text (functions of this file are command-line functions, which
## other processes do not have).

%!shared f, Y0, o, ev
%! ## the pendulum from rest at 7 amplitudes; the event q = 2 downwards,
%! ## terminal, is met by the 3 largest only, p = 0 (not terminal) by all
%! f = @(t, y) [y(2,:); -sin(y(1,:))];
%! Y0 = [linspace(0.4, 2.9, 7); zeros(1, 7)];
%! o = symplecticset ("TimeStepSize", 0.1, "Ensemble", "on");
%! ev = @(t, y) deal ([y(1) - 2; y(2)], [1; 0], [-1; 0]);

%!function n = count (str, pat)
%!  n = numel (regexp (str, pat, "start"));
%!endfunction

## ------------------------------------------------------------ bit-identity
%!test
%! ## [t, Y]: 2 and 3 processes (chunks 4+3 and 3+2+2) as the serial run
%! for s = {@odeSPVI, @odeSV}
%!   [t, Y] = s{1} (f, [0 6], Y0, o);
%!   for P = [2 3]
%!     [tp, Yp] = s{1} (f, [0 6], Y0, symplecticset (o, "Parallel", P));
%!     assert (isequal (tp, t) && isequal (Yp, Y), "%s, Parallel %d",
%!             func2str (s{1}), P);
%!   endfor
%! endfor

%!test
%! ## [t, Y, te, ye, ie] with events: the last chunk's members all stop
%! ## early (its t is the shorter; NaN rows fill it), ie(:,2) counts the
%! ## members from the first of all
%! oe = symplecticset (o, "Events", ev);
%! for s = {@odeSPVI, @odeSV}
%!   [t, Y, te, ye, ie] = s{1} (f, [0 6], Y0, oe);
%!   assert (any (isnan (Y(:))) && any (ie(:,1) == 1));
%!   assert (unique (ie(ie(:,1) == 1, 2))', 5:7);
%!   for P = [2 3]
%!     [tp, Yp, tep, yep, iep] = s{1} (f, [0 6], Y0,
%!                                      symplecticset (oe, "Parallel", P));
%!     assert (isequaln ({tp, Yp, tep, yep, iep}, {t, Y, te, ye, ie}),
%!             "%s, Parallel %d", func2str (s{1}), P);
%!   endfor
%! endfor

%!test
%! ## sol: the 1 x K struct array, each member's struct as in the serial run
%! oe = symplecticset (o, "Events", ev);
%! for s = {@odeSPVI, @odeSV}
%!   sol = s{1} (f, [0 6], Y0, oe);
%!   for P = [2 3]
%!     solp = s{1} (f, [0 6], Y0, symplecticset (oe, "Parallel", P));
%!     assert (size (solp), [1 7]);
%!     assert (isequaln (solp, sol), "%s, Parallel %d", func2str (s{1}), P);
%!     assert (isequal (fieldnames (solp), fieldnames (sol)));
%!   endfor
%! endfor

%!test
%! ## odeSE too; more processes than members: one member each; extra
%! ## arguments of FCN go along
%! g = @(t, y, w) [y(2,:); -w^2 * sin(y(1,:))];
%! [t, Y] = odeSE (g, [0 3], Y0(:,1:3), o, 1.5);
%! [tp, Yp] = odeSE (g, [0 3], Y0(:,1:3), symplecticset (o, "Parallel", 8), 1.5);
%! assert (isequal (tp, t) && isequal (Yp, Y));

%!test
%! ## Vectorized: FCN gets a chunk's states at once; lone members (7
%! ## processes) too
%! ov = symplecticset (o, "Vectorized", "on");
%! [t, Y] = odeSV (f, [0 3], Y0, ov);
%! for P = [3 7]
%!   [tp, Yp] = odeSV (f, [0 3], Y0, symplecticset (ov, "Parallel", P));
%!   assert (isequal (tp, t) && isequal (Yp, Y));
%! endfor

%!test
%! ## Parallel 1 is the run in this process; a lower-case field name
%! ## counts as Parallel, as odeset matches names
%! [t, Y] = odeSV (f, [0 2], Y0, o);
%! [t1, Y1] = odeSV (f, [0 2], Y0, symplecticset (o, "Parallel", 1));
%! assert (isequal (t1, t) && isequal (Y1, Y));
%! op = o;  op.parallel = 2;
%! [t2, Y2] = odeSV (f, [0 2], Y0, op);
%! assert (isequal (t2, t) && isequal (Y2, Y));
%! ## without Ensemble, Parallel 1 is allowed (the default)
%! [ts, ys] = odeSV (f, [0 2], Y0(:,1), symplecticset ("TimeStepSize", 0.1,
%!                                                     "Parallel", 1));
%! assert (isequal (ys, Y(:,:,1)));

## ------------------------------------------------------------ output, warnings
%!test
%! ## Stats: each chunk's, under the range of its members
%! out = evalc ("[~, ~] = odeSV (f, [0 1], Y0, symplecticset (o, 'Parallel', 2, 'Stats', 'on'));");
%! assert (count (out, 'Members 1 to 4 \(of 7\):\nMembers: 4, summed below'), 1);
%! assert (count (out, 'Members 5 to 7 \(of 7\):\nMembers: 3, summed below'), 1);
%! assert (count (out, 'Number of successful steps: 40\n'), 1);
%! assert (count (out, 'Number of successful steps: 30\n'), 1);

%!test
%! ## failing members (FCN not finite for |q| >= 2, members 5 to 8 of 8,
%! ## the second chunk's all): their warnings, numbered as in the serial
%! ## run and with its identifier; NaN rows as there.  FCN is checked at
%! ## member 1's initial state in every process, as in the serial run.
%! g = @(t, y) [y(2,:); -sin(y(1,:))] ./ (abs (y(1,:)) < 2);
%! Z0 = Y0(:, [1:4, 5:7, 7]);
%! ws = warning ("query", "backtrace");
%! wn = warning ("query", "symplectic:nonfinite");
%! warning ("off", "backtrace");
%! unwind_protect
%!   lastwarn ("");
%!   serial = evalc ("[t, Y] = odeSV (g, [0 1], Z0, o);");
%!   [~, id] = lastwarn ();
%!   assert (id, "symplectic:nonfinite");
%!   assert (count (serial, 'warning: odeSV: member [5-8]: FCN returned NaN'), 4);
%!   for P = [2 3]
%!     lastwarn ("");
%!     par = evalc ("[tp, Yp] = odeSV (g, [0 1], Z0, symplecticset (o, 'Parallel', P));");
%!     [msg, idp] = lastwarn ();
%!     assert (par, serial);
%!     assert (idp, "symplectic:nonfinite");
%!     assert (strncmp (msg, "odeSV: member 8: ", 17));
%!     assert (isequaln (tp, t) && isequaln (Yp, Y));
%!   endfor
%!   ## the first warning of a chunk (not its last) has its identifier too
%!   warning ("error", "symplectic:nonfinite");
%!   try
%!     [tp, Yp] = odeSV (g, [0 1], Z0, symplecticset (o, "Parallel", 2));
%!     error ("no error");
%!   catch err
%!     assert (err.identifier, "symplectic:nonfinite");
%!     assert (strncmp (err.message, "odeSV: member 5: FCN returned NaN", 33));
%!   end_try_catch
%! unwind_protect_cleanup
%!   warning (wn.state, "symplectic:nonfinite");
%!   warning (ws.state, "backtrace");
%! end_unwind_protect

%!test
%! ## an error of FCN in another process is this call's, message and id
%! h = @(t, y) [y(2,:); -sin(y(1,:))] + 0 * (y(1) > 2.5 && error ("t:far", "member too far"));
%! try
%!   [t, Y] = odeSV (h, [0 2], Y0, symplecticset (o, "Parallel", 2));
%!   error ("no error");
%! catch err
%!   assert (err.message, "member too far");
%!   assert (err.identifier, "t:far");
%! end_try_catch

%!function y = here_only (y)
%!endfunction

%!error <here_only' undefined.*command-line functions do not go to other processes>
%! [t, Y] = odeSV (@(t, y) here_only ([y(2,:); -y(1,:)]), [0 1], Y0,
%!                 symplecticset (o, "Parallel", 2));

%!test
%! ## the table that gives the workers' warnings their identifiers knows
%! ## every warning of the gateways (src/mex)
%! src = fullfile (fileparts (which ("__odeSV__")), "mex");
%! ids = {};
%! for cf = dir (fullfile (src, "*.c"))'
%!   tok = regexp (fileread (fullfile (src, cf.name)),
%!                 'mexWarnMsgIdAndTxt \("(symplectic:[a-z-]+)"', "tokens");
%!   ids = [ids, cellfun(@(c) c{1}, tok, "UniformOutput", false)];
%! endfor
%! ids = unique (ids);
%! assert (numel (ids) >= 10);
%! table = fileread (fullfile (fileparts (which ("odeSV")), "private",
%!                             "__ensemble_parallel__.m"));
%! for i = 1:numel (ids)
%!   assert (! isempty (strfind (table, ["\"" ids{i} "\""])), ids{i});
%! endfor

## ------------------------------------------------------------ bad use
%!error <odeSV: Parallel needs Ensemble on>
%! [t, y] = odeSV (f, [0 1], [1; 0], symplecticset ("TimeStepSize", 0.1, "Parallel", 2));
%!error <odeSPVI: Parallel needs Ensemble on>
%! [t, y] = odeSPVI (f, [0 1], Y0, symplecticset ("TimeStepSize", 0.1, "Ensemble", "off", "Parallel", 3));
%!error <odeSV: Parallel must be a positive integer .* got double 0>
%! [t, Y] = odeSV (f, [0 1], Y0, symplecticset (o, "Parallel", 0));
%!error <odeSV: Parallel must be a positive integer .* got double -1>
%! [t, Y] = odeSV (f, [0 1], Y0, symplecticset (o, "Parallel", -1));
%!error <odeSV: Parallel must be a positive integer .* got double 1.5>
%! [t, Y] = odeSV (f, [0 1], Y0, symplecticset (o, "Parallel", 1.5));
%!error <odeSV: Parallel must be a positive integer .* got "two">
%! [t, Y] = odeSV (f, [0 1], Y0, symplecticset (o, "Parallel", "two"));
%!error <odeSE: Parallel must be a positive integer .* got double Inf>
%! [t, Y] = odeSE (f, [0 1], Y0, symplecticset (o, "Parallel", Inf));
%!error <odeSV: Parallel must be a positive integer>
%! [t, Y] = odeSV (f, [0 1], Y0, symplecticset (o, "Parallel", true));
%!error <odeSV: Parallel must be a positive integer .* got a 1x2 double>
%! [t, Y] = odeSV (f, [0 1], Y0, symplecticset (o, "Parallel", [2 2]));
%!test
%! ## a struct is no way into the processes' runs (they run their chunks
%! ## through a private function): it is a bad value, as any other, the
%! ## error before any other check of the arguments
%! w = struct ("worker_nargout", 1, "members", [1 1]);
%! msg = ": Parallel must be a positive integer (the number of processes) or the connections pconnect returned, got a ";
%! cases = {@odeSV, {1}, "junk", w, ["odeSV" msg "1x1 struct"]
%!          @odeSPVI, f, Y0, setfield(w, "members", [1 7]), ["odeSPVI" msg "1x1 struct"]
%!          @odeSE, f, Y0, struct("worker_nargout", {2, 2}), ["odeSE" msg "1x2 struct"]};
%! for i = 1:rows (cases)
%!   try
%!     r = cases{i,1} (cases{i,2}, [0 1], cases{i,3},
%!                     symplecticset (o, "Parallel", cases{i,4}));
%!     error ("no error");
%!   catch err
%!     assert (err.message, cases{i,5});
%!     assert (err.identifier, "Octave:invalid-input-arg");
%!   end_try_catch
%! endfor

%!error <odeSV: OPTS sets both Parallel and parallel>
%! op = symplecticset (o, "Parallel", 2);  op.parallel = 3;
%! [t, Y] = odeSV (f, [0 1], Y0, op);
%!error <odeSV: OPTS sets both Ensemble and ENSEMBLE>
%! op = symplecticset (o, "Parallel", 2);  op.ENSEMBLE = "off";
%! [t, Y] = odeSV (f, [0 1], Y0, op);
%!error <odeSPVI: with Parallel, OutputFcn .* cannot follow>
%! [t, Y] = odeSPVI (f, [0 1], Y0, symplecticset (o, "Parallel", 2, "OutputFcn", @(t, y, flag) false));
## no outputs: the plot would be odeplot's (the error comes before it)
%!error <odeSV: with Parallel, OutputFcn \(and the plot of a call without outputs\)>
%! odeSV (f, [0 1], Y0, symplecticset (o, "Parallel", 2));

%!test
%! ## without the parallel package (none listed in a fresh process)
%! dirs = {fileparts(which ("odeSV")), fileparts(which ("__odeSV__"))};
%! code = ["d = tempname (); mkdir (d); ", ...
%!         "pkg ('global_list', fullfile (d, 'g')); ", ...
%!         "pkg ('local_list', fullfile (d, 'l')); ", ...
%!         "try, [t, Y] = odeSV (@(t, y) [y(2,:); -y(1,:)], [0 1], [1 2; 0 0], ", ...
%!         "symplecticset ('TimeStepSize', 0.1, 'Ensemble', 'on', 'Parallel', 2)); ", ...
%!         "catch e, disp (e.message), end; rmdir (d);"];
%! [~, out] = system (sprintf ("\"%s\" --norc --no-gui --path \"%s\" --eval \"%s\" 2>&1",
%!                             fullfile (OCTAVE_HOME (), "bin", "octave-cli"),
%!                             strjoin (dirs, pathsep ()), code));
%! assert (! isempty (strfind (out, "odeSV: Parallel needs the parallel package (Debian: octave-parallel; or pkg install -forge parallel)")), out);

%!test
%! ## a process that started the symbolic package's Python, then a
%! ## Parallel run, must exit: the parallel package's processes must not
%! ## keep Python's input open (Octave's exit waits for Python)
%! if (isempty (pkg ("list", "symbolic")))
%!   printf ("test_parallel: exit after symbolic skipped, no symbolic package\n");
%! else
%!   dirs = {fileparts(which ("odeSV")), fileparts(which ("__odeSV__"))};
%!   code = ["pkg load symbolic; x = sym ('x'); ", ...
%!           "[t, Y] = odeSV (@(t, y) [y(2,:); -y(1,:)], [0 1], [1 2; 0 0], ", ...
%!           "symplecticset ('TimeStepSize', 0.1, 'Ensemble', 'on', 'Parallel', 2)); ", ...
%!           "printf ('ran %d\\n', numel (t)); exit (0);"];
%!   [st, out] = system (sprintf ("timeout -s KILL 120 \"%s\" --norc --no-gui --path \"%s\" --eval \"%s\" 2>&1",
%!                                fullfile (OCTAVE_HOME (), "bin", "octave-cli"),
%!                                strjoin (dirs, pathsep ()), code));
%!   assert (! isempty (strfind (out, "ran 11")), out);
%!   assert (st, 0, sprintf ("exit status %d (137: killed, it did not exit)", st));
%! endif

%!test
%! ## A process that dies holding a chunk (FCN calls exit, or the process
%! ## is killed: SIGKILL, SIGSEGV), in a fresh Octave: the error names the
%! ## members it held, with the identifier symplectic:parallel-worker;
%! ## none of the parallel package's lines ("could not receive result")
%! ## and no "broken pipe" is printed; no process of the package is left
%! ## (none alive, no zombie: no child of that Octave at all), and the
%! ## next run starts new ones.  Run 4: the other chunk's process is busy
%! ## (FCN takes 0.5 s a call, 10 s for the run), the call ends at once.
%! dirs = {fileparts(which ("odeSV")), fileparts(which ("__odeSV__"))};
%! script = [tempname() ".m"];
%! fid = fopen (script, "w");
%! fputs (fid, strjoin ({
%!   "pkg load parallel"
%!   "pid0 = getpid ();"
%!   "o = symplecticset ('TimeStepSize', 0.1, 'Ensemble', 'on', 'Parallel', 2);"
%!   "Y0 = [linspace(0.4, 2.9, 7); zeros(1, 7)];"
%!   "g = @(t, y) [y(2,:); -sin(y(1,:))];"
%!   "die = {@() feval (@exit, 3), @() kill (getpid (), 9), @() kill (getpid (), 11), @() kill (getpid (), 9)};"
%!   "for i = 1:4"
%!   "  slow = (i == 4);"
%!   "  f = @(t, y) g (t, y) + 0 * (getpid () != pid0 && any (y(1,:) > 2.5) && die{i} ()) + 0 * (slow && getpid () != pid0 && any (abs (y(1,:) - 1.65) < 0.1) && ! pause (0.5));"
%!   "  t0 = tic ();"
%!   "  try"
%!   "    [t, Y] = odeSV (f, [0 2], Y0, o);"
%!   "    id = ''; msg = 'no error';"
%!   "  catch err"
%!   "    id = err.identifier; msg = err.message;"
%!   "  end_try_catch"
%!   "  el = toc (t0);"
%!   "  system ('true');   # Octave reports a pending SIGPIPE here"
%!   "  kids = [];"
%!   "  for d = readdir ('/proc')'"
%!   "    p = str2double (d{1});"
%!   "    if (isfinite (p))"
%!   "      try"
%!   "        st = fileread (sprintf ('/proc/%d/stat', p));"
%!   "        v = strsplit (strtrim (st(rindex (st, ')')+1:end)), ' ');"
%!   "        if (str2double (v{2}) == pid0)"
%!   "          kids(end+1) = p;"
%!   "        endif"
%!   "      catch"
%!   "      end_try_catch"
%!   "    endif"
%!   "  endfor"
%!   "  printf ('RUN %d|%s|%s|%.2f|%s|\\n', i, id, msg, el, num2str (kids));"
%!   "endfor"
%!   "[t, Y] = odeSV (g, [0 2], Y0, o);"
%!   "[t1, Y1] = odeSV (g, [0 2], Y0, symplecticset (o, 'Parallel', 1));"
%!   "printf ('AFTER %d\\n', isequal (Y, Y1));"
%!   }, "\n"));
%! fclose (fid);
%! unwind_protect
%!   [~, out] = system (sprintf ("timeout -s KILL 120 \"%s\" --norc --no-gui --quiet --path \"%s\" \"%s\" 2>&1",
%!                               fullfile (OCTAVE_HOME (), "bin", "octave-cli"),
%!                               strjoin (dirs, pathsep ()), script));
%! unwind_protect_cleanup
%!   unlink (script);
%! end_unwind_protect
%! how = {"exited with status 3", "was killed by signal 9 (SIGKILL)", ...
%!        "was killed by signal 11 (SIGSEGV)", "was killed by signal 9 (SIGKILL)"};
%! for i = 1:4
%!   r = regexp (out, sprintf ('RUN %d\\|([^|]*)\\|([^|]*)\\|([^|]*)\\|([^|]*)\\|', i), "tokens", "once");
%!   assert (numel (r) == 4, "%s", out);
%!   assert (strcmp (r{1}, "symplectic:parallel-worker"), "%s", out);
%!   assert (strcmp (r{2}, ["odeSV: Parallel: the process that ran members 5 to 7 " how{i} " before it returned them"]), "%s", out);
%!   assert (str2double (r{3}) < 8, "run %d took %s s", i, r{3});
%!   assert (isempty (r{4}), "run %d left children %s", i, r{4});
%! endfor
%! assert (! isempty (strfind (out, "AFTER 1")), "%s", out);
%! assert (isempty (regexp (out, '(^|\n)could not|broken pipe', "once")), "%s", out);

## ------------------------------------------------------------ servers
%!test
%! ## Two servers of a pconnect network on this machine: the server
%! ## program of the parallel package (octave-pserver, without TLS: the
%! ## Debian build has none) started in the background, connected to as
%! ## 127.0.0.1 and 127.0.0.2 (the client always uses the default ports,
%! ## so one server program answers both; it runs an Octave process for
%! ## each).  It refuses to run as root: as root it runs as nobody.  The
%! ## servers get a copy of the package's files on their path and a
%! ## function only they have, which FCN calls: the results prove where
%! ## the members ran.
%! pkg load parallel
%! host = gethostname ();
%! pidfile = sprintf ("/tmp/.octave-%s.pid", host);
%! if (exist (pidfile, "file"))
%!   opid = str2double (fileread (pidfile));
%!   if (isfinite (opid) && opid > 0 && kill (opid, 0) == 0)
%!     printf ("test_parallel: servers skipped, one runs already (%s)\n", pidfile);
%!     return;
%!   endif
%!   unlink (pidfile);   # left by a server that no longer runs
%! endif
%! ## the server program's log files that it leaves in /tmp
%! logs = strcat (sprintf ("/tmp/octave_error-%s", host), {".log", ".bak"});
%! logs = logs(! cellfun (@(f) exist (f, "file"), logs));
%! bin = fullfile (fileparts (which ("pserver")), "bin", "octave-pserver");
%! if (! exist (bin, "file"))
%!   bin = "/usr/libexec/octave-pserver";
%! endif
%! [~, uid] = system ("id -u");
%! prefix = "";
%! if (str2double (uid) == 0)
%!   prefix = "setpriv --reuid=65534 --regid=65534 --clear-groups ";
%! endif
%! srv = tempname ();  home = tempname ();
%! mkdir (srv);  mkdir (home);
%! pid = NaN;  conns = [];
%! unwind_protect
%!   copyfile (fullfile (fileparts (which ("odeSV")), "*"), srv);
%!   copyfile (fullfile (fileparts (which ("__odeSV__")), "__ode*__.mex"), srv);
%!   fid = fopen (fullfile (srv, "server_side.m"), "w");
%!   fputs (fid, "function x = server_side (x)\nendfunction\n");
%!   fclose (fid);
%!   system (sprintf ("chmod -R a+rX '%s' '%s'", srv, home));
%!   start = sprintf ("%senv HOME='%s' '%s' --octave-binary='%s' --no-auth < /dev/null > /dev/null 2>&1",
%!                    prefix, home, bin,
%!                    fullfile (OCTAVE_HOME (), "bin", "octave-cli"));
%!   ## it cannot listen while its ports are still held (TIME_WAIT, up to
%!   ## a minute) by the connections of a run just before: it is tried
%!   ## again until then
%!   t0 = tic ();
%!   while (! isfinite (pid) && toc (t0) < 75)
%!     assert (system (start), 0);
%!     for i = 1:20
%!       pause (0.05);
%!       if (exist (pidfile, "file"))
%!         pid = str2double (fileread (pidfile));
%!         if (isfinite (pid))
%!           break;
%!         endif
%!       endif
%!     endfor
%!   endwhile
%!   assert (isfinite (pid), "the server did not start (see /tmp/octave_error-%s.log)", host);
%!   for i = 1:50
%!     try
%!       conns = pconnect ({"127.0.0.1", "127.0.0.2"}, struct ("use_tls", false));
%!       break;
%!     catch err
%!       if (i == 50)
%!         rethrow (err);
%!       endif
%!       pause (0.1);
%!     end_try_catch
%!   endfor
%!   netid = network_get_info (conns)(1).network_id;
%!   logs = [logs, strcat(sprintf ("/tmp/octave_error-%s_%s", host, netid),
%!                        {".log", ".bak"})];
%!   reval (sprintf ("addpath ('%s');", srv), conns(2:3));
%!   reval ("psend (getpid (), sockets(1));", conns(2:3));
%!   assert (precv (conns(2)) != precv (conns(3)));
%!   ## FCN here and FCN there compute the same
%!   fs = @(t, y) server_side ([y(2,:); -sin(y(1,:))]);
%!   oe = symplecticset (o, "Events", ev);
%!   [t, Y, te, ye, ie] = odeSV (f, [0 6], Y0, oe);
%!   [tp, Yp, tep, yep, iep] = odeSV (fs, [0 6], Y0, symplecticset (oe, "Parallel", conns));
%!   assert (isequaln ({tp, Yp, tep, yep, iep}, {t, Y, te, ye, ie}));
%!   sol = odeSPVI (f, [0 6], Y0, oe);
%!   solp = odeSPVI (fs, [0 6], Y0, symplecticset (oe, "Parallel", conns));
%!   assert (isequaln (solp, sol));
%!   ## a server's error is this call's
%!   try
%!     [tp, Yp] = odeSV (@(t, y) error ("t:srv", "from the server"), [0 1], Y0,
%!                       symplecticset (o, "Parallel", conns));
%!     error ("no error");
%!   catch err
%!     assert (err.message, "from the server");
%!   end_try_catch
%!   ## and the network is still good
%!   [tp, Yp] = odeSV (fs, [0 6], Y0, symplecticset (o, "Parallel", conns));
%!   [t, Y] = odeSV (f, [0 6], Y0, o);
%!   assert (isequal (tp, t) && isequal (Yp, Y));
%! unwind_protect_cleanup
%!   if (! isempty (conns))
%!     try
%!       sclose (conns);
%!     catch
%!     end_try_catch
%!   endif
%!   if (isfinite (pid))
%!     ## the server's Octave processes end with the connections; in case
%!     ## one is left, it goes with the server program
%!     [~, ch] = system (sprintf ("ps -o pid= --ppid %d", pid));
%!     for p = [reshape(str2num (ch), 1, []), pid]
%!       try
%!         kill (p, 15);
%!       catch
%!       end_try_catch
%!     endfor
%!   endif
%!   for i = 1:numel (logs)
%!     if (exist (logs{i}, "file"))
%!       delete (logs{i});
%!     endif
%!   endfor
%!   confirm_recursive_rmdir (false, "local");
%!   rmdir (srv, "s");
%!   rmdir (home, "s");
%! end_unwind_protect
