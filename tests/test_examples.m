## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## The examples a user copies: every ```octave block of README.md and of
## the user guide, and every @example of the package's help texts, runs
## without error on the solvers on the path (the development tree under
## make check, the installed package under run_tests ("installed") and
## make check-installed, which reads the guide installed with it).  A
## block whose first line is "% not run" (a calling form, a fragment, a
## run that needs other machines) is skipped; there are only a few.
## Also: each help text is at most 110 lines, and every demo of the
## package runs in a child octave-cli with no terminal and no display.

%!function root = source_tree ()
%!  ## tests/ is on the path (run_tests adds it); its parent has README.md
%!  root = fileparts (fileparts (which ("run_tests")));
%!endfunction

%!function guide = guide_file ()
%!  ## the installed guide when the solvers are the installed package's
%!  info = pkg ("list", "symplectic");
%!  guide = "";
%!  if (! isempty (info) && info{1}.loaded)
%!    guide = fullfile (info{1}.dir, "doc", "user-guide.md");
%!  endif
%!  if (isempty (guide) || ! isfile (guide))
%!    guide = fullfile (source_tree (), "doc", "user-guide.md");
%!  endif
%!endfunction

%!function blocks = markdown_blocks (file)
%!  ## the ```octave blocks of FILE: code and the line of the fence
%!  lines = strsplit (fileread (file), "\n");
%!  blocks = struct ("code", {}, "line", {}, "skip", {});
%!  i = 1;
%!  while (i <= numel (lines))
%!    if (regexp (lines{i}, '^```octave\s*$', "once"))
%!      j = i + 1;
%!      while (j <= numel (lines) && isempty (regexp (lines{j}, '^```\s*$', "once")))
%!        j += 1;
%!      endwhile
%!      code = lines(i+1:j-1);
%!      skip = ! isempty (code) && ! isempty (regexp (code{1}, '^%\s*not run', "once"));
%!      blocks(end+1) = struct ("code", strjoin (code, "\n"), "line", i, "skip", skip);
%!      i = j;
%!    endif
%!    i += 1;
%!  endwhile
%!endfunction

%!function blocks = help_blocks (name)
%!  ## the @example blocks of NAME's texinfo help, as a user reads them
%!  txt = get_help_text (name);
%!  blocks = {};
%!  [s, e] = regexp (txt, '@example\s*\n.*?@end example', "start", "end");
%!  for k = 1:numel (s)
%!    b = txt(s(k)+9:e(k)-12);
%!    b = regexprep (b, '^\s*@(end )?group\s*\n', "", "lineanchors");
%!    b = strrep (strrep (strrep (b, "@@", "@"), "@{", "{"), "@}", "}");
%!    b = strrep (b, "@dots{}", "...");
%!    blocks{end+1} = b;
%!  endfor
%!endfunction

%!function msg = run_example (code)
%!  ## CODE as a script of its own, in this function's fresh workspace;
%!  ## returns "" or the error's message.  Functions it defines are
%!  ## cleared after, so that no example leans on another's.
%!  f = [tempname() "_example.m"];
%!  [d, nm] = fileparts (f);
%!  nm = regexprep (nm, '\W', "_");
%!  f = fullfile (d, ["ex_" nm ".m"]);
%!  fid = fopen (f, "w");
%!  ## the lines that put the package on the path: the runner has done it
%!  code = regexprep (code, '^\s*(addpath\s+inst\s+src|pkg\s+load\s+symplectic)\>[^\n]*', "",
%!                    "lineanchors");
%!  fprintf (fid, "1;\n%s\n", code);
%!  fclose (fid);
%!  fnames = regexp (code, '^\s*function\s+(?:\[[^\]]*\]\s*=\s*|\w+\s*=\s*)?(\w+)',
%!                   "tokens", "lineanchors");
%!  msg = "";
%!  olddir = pwd ();
%!  scratch = tempname ();
%!  mkdir (scratch);
%!  unwind_protect
%!    cd (scratch);              # files an example writes go there
%!    try
%!      evalc ("source (f);");
%!    catch err
%!      msg = err.message;
%!    end_try_catch
%!  unwind_protect_cleanup
%!    cd (olddir);
%!    close all;
%!    delete (f);
%!    confirm_recursive_rmdir (false, "local");
%!    rmdir (scratch, "s");
%!    for k = 1:numel (fnames)
%!      clear (fnames{k}{1});
%!    endfor
%!  end_unwind_protect
%!endfunction

%!function check_markdown (file, maxskip)
%!  blocks = markdown_blocks (file);
%!  assert (numel (blocks) >= 3, "%s: only %d octave blocks found", file, numel (blocks));
%!  assert (sum ([blocks.skip]) <= maxskip, "%s: %d blocks marked not run", file, sum ([blocks.skip]));
%!  bad = {};
%!  set (0, "defaultfigurevisible", "off");
%!  for k = find (! [blocks.skip])
%!    msg = run_example (blocks(k).code);
%!    if (! isempty (msg))
%!      bad{end+1} = sprintf ("%s:%d: %s", file, blocks(k).line, msg);
%!    endif
%!  endfor
%!  if (! isempty (bad))
%!    error ("examples that fail:\n%s", strjoin (bad, "\n"));
%!  endif
%!endfunction

%!test
%! check_markdown (fullfile (source_tree (), "README.md"), 2);

%!test
%! check_markdown (guide_file (), 4);

%!test
%! ## every help text's examples; every help has one
%! set (0, "defaultfigurevisible", "off");
%! bad = {};
%! for name = {"odeSE", "odeSV", "odeSPVI", "symplecticset", "symdeval", "symplectic_kepler"}
%!   b = help_blocks (name{1});
%!   if (isempty (b))
%!     bad{end+1} = sprintf ("%s: no @example in its help", name{1});
%!   endif
%!   for k = 1:numel (b)
%!     msg = run_example (b{k});
%!     if (! isempty (msg))
%!       bad{end+1} = sprintf ("help %s, example %d: %s", name{1}, k, msg);
%!     endif
%!   endfor
%! endfor
%! if (! isempty (bad))
%!   error ("examples that fail:\n%s", strjoin (bad, "\n"));
%! endif

%!test
%! ## help texts stay short (ode45's is 71 lines): the texinfo block from
%! ## "-*- texinfo -*-" to the end of the help comment; each says where
%! ## the user guide is
%! for name = {"odeSE", "odeSV", "odeSPVI", "symplecticset", "symdeval", "symplectic_kepler"}
%!   [txt, fmt] = get_help_text (name{1});
%!   ## (get_help_text drops the marker line and keeps its newline)
%!   n = numel (strfind (regexprep (txt, '\s+$', ""), "\n")) + 1;
%!   assert (fmt, "texinfo");
%!   assert (n <= 110, "help %s has %d lines, more than 110", name{1}, n);
%! endfor
%! for name = {"odeSE", "odeSV", "odeSPVI", "symplecticset", "symdeval"}
%!   assert (! isempty (strfind (get_help_text (name{1}), "user-guide.md")),
%!           "help %s does not say where the user guide is", name{1});
%! endfor

%!test
%! ## the marker and the parsers find what they should
%! f = [tempname() ".md"];
%! fid = fopen (f, "w");
%! fprintf (fid, "x\n```octave\na = 1;\n```\n```sh\nls\n```\n```octave\n%% not run: a form\nfoo (\n```\n");
%! fclose (fid);
%! b = markdown_blocks (f);
%! delete (f);
%! assert ({b.code}, {"a = 1;", "% not run: a form\nfoo ("});
%! assert ([b.skip], [false, true]);
%! assert ([b.line], [2, 8]);
%! assert (run_example ("a = 1;"), "");
%! assert (run_example ("error ('my:id', 'boom %d', 3);"), "boom 3");
%! assert (! isempty (run_example ("undefined_function_xyz (1)")));
%! ## a function an example defines does not outlive it
%! assert (run_example ("function r = ex_fun_xyz ()\n  r = 1;\nendfunction\nassert (ex_fun_xyz (), 1);"), "");
%! assert (exist ("ex_fun_xyz"), 0);

%!test
%! ## every demo of the package, in a child octave-cli with stdin from
%! ## /dev/null and no display: each runs (demo prints "NAME example N:"
%! ## before it and "failed" after one that fails), prints its numbers,
%! ## and writes a PNG when a graphics toolkit can print
%! names = {"odeSE", "odeSV", "odeSPVI", "symplecticset", "symdeval"};
%! dirs = unique ({fileparts(which ("odeSPVI")), fileparts(which ("__odeSPVI__"))});
%! octave = fullfile (OCTAVE_HOME (), "bin", "octave-cli");
%! if (! isfile (octave))
%!   octave = "octave-cli";
%! endif
%! scratch = tempname ();
%! mkdir (scratch);
%! code = sprintf ("addpath (%s); names = {%s}; for i = 1:numel (names), demo (names{i}); endfor; printf ('TOOLKITS %%d\\nDEMOS DONE\\n', numel (available_graphics_toolkits ()));",
%!                 strjoin (strcat ("'", dirs, "'"), ", "),
%!                 strjoin (strcat ("'", names, "'"), ", "));
%! cmd = sprintf ("cd '%s' && '%s' --norc --quiet --no-gui --no-window-system --eval \"%s\" < /dev/null 2>&1",
%!                scratch, octave, code);
%! [status, out] = system (cmd);
%! pngs = dir (fullfile (scratch, "*.png"));
%! confirm_recursive_rmdir (false, "local");
%! rmdir (scratch, "s");
%! assert (status, 0, out);
%! assert (! isempty (strfind (out, "DEMOS DONE")), out);
%! assert (isempty (regexp (out, 'example \d+: failed', "once")), out);
%! assert (isempty (strfind (out, "reading user-input failed")), out);
%! for i = 1:numel (names)
%!   assert (! isempty (strfind (out, [names{i} " example 1:"])), out);
%!   assert (isempty (strfind (out, [names{i} " example 2:"])), out);
%! endfor
%! ## the numbers each demo prints
%! assert (numel (regexp (out, '\d\.\d+e[-+]\d\d')) >= 5, out);
%! ntk = str2double (regexp (out, 'TOOLKITS (\d+)', "tokens", "once"){1});
%! if (ntk > 0)
%!   assert (numel (pngs) >= numel (names), out);
%! endif
