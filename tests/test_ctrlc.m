## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## Ctrl-C during a long integration returns Octave to its prompt, still
## working: tests/ctrlc_test.sh runs octave-cli --interactive, sends SIGINT
## to it during runs of odeSPVI, odeSE and odeSV (long calls, with Events,
## OutputFcn and Jacobian callbacks, and a loop of short calls), then
## checks that it integrates again, prints a marker and exits normally.
## It tests the MEX files this Octave uses (the development tree or the
## installed package).  About 13 s.
##
## Skipped where no POSIX shell or mkfifo is available.

%!test
%! script = file_in_loadpath ("ctrlc_test.sh");
%! if (isempty (script) || ispc () || system ("command -v mkfifo >/dev/null 2>&1") != 0)
%!   warning ("test_ctrlc: skipped: needs tests/ctrlc_test.sh, sh and mkfifo");
%!   return;
%! endif
%! ## the directories of the m-file front end and of its MEX gateway
%! dirs = strjoin (unique ({fileparts(which ("odeSPVI")),
%!                          fileparts(which ("__odeSPVI__"))}), pathsep ());
%! octave = fullfile (OCTAVE_HOME (), "bin", "octave-cli");
%! if (! exist (octave, "file"))
%!   octave = "octave-cli";
%! endif
%! [status, out] = system (sprintf ("sh '%s' '%s' '%s' 2>&1", script, dirs,
%!                                  octave));
%! if (status != 0 || numel (strfind (out, ": ok (MARKER 1")) != 5)
%!   error ("ctrlc_test.sh failed (exit status %d):\n%s", status, out);
%! endif
