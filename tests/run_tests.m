## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## -*- texinfo -*-
## @deftypefn  {} {@var{status} =} run_tests ()
## @deftypefnx {} {@var{status} =} run_tests ("installed")
## Run the Octave test suite of the symplectic package; return 0 if every
## test passed and at least one ran, 1 otherwise.
##
## @code{run_tests ()} tests the development tree: the m-files of
## @file{inst/} and the MEX files that @code{make} built in @file{src/}.
## @code{run_tests ("installed")} tests the installed package
## instead (after @code{pkg load symplectic}), the way @code{pkg test
## symplectic} does.  In both modes it runs, with @code{test}:
##
## @itemize
## @item the @code{%!} blocks of every m-file of the package (recursively,
## skipping @file{private/} as @code{pkg test} does), of every C source
## in @file{src/} that has any (@code{pkg install} extracts those into
## @file{*.c-tst} files) and of @file{src/*-tst} (in installed mode: of the
## @file{*-tst} files of the installed package);
## @item every @file{tests/test_*.m} file of the source tree.
## @end itemize
##
## If the environment variable @env{SYMPLECTIC_TESTS} is set (a
## space-separated list of file names relative to the source tree,
## e.g. @samp{inst/odeSE.m tests/test_bad_input.m}), only those files
## run, after the layout check; @code{make check-quick} uses it.
##
## The last line printed is @samp{N passed, M failed}.  Used by
## @code{make check}:
##
## @example
## octave-cli --norc --quiet --eval 'addpath ("tests"); exit (run_tests ())'
## @end example
##
## The layout it checks first: the solvers @code{odeSE}, @code{odeSV},
## @code{odeSPVI} are the m-files of @file{inst/} (help, tests, front
## ends), and each calls its compiled gateway @code{__odeSE__} etc., a
## @file{.mex} built from @file{src/__odeSE__.c} etc.: in @file{src/} in
## the development tree, in the package's architecture-dependent
## directory once installed (as Octave's @code{ode15s.m} calls
## @code{__ode15__}).
## @end deftypefn

function status = run_tests (mode = "dev")

  root = fileparts (fileparts (mfilename ("fullpath")));
  srcdir = fullfile (root, "src");
  testsdir = fullfile (root, "tests");

  ## The MEX entry points are the C files at the top of src/, __NAME__.c:
  ## the gateways of the solvers NAME.
  entries = dir (fullfile (srcdir, "*.c"));
  mexnames = regexprep ({entries.name}, '\.c$', "");
  solvers = regexprep (mexnames, '^__(.*)__$', "$1");
  ## gateways without a front end of that name (__symcompiled__, which
  ## the @symfcn class calls) are checked as MEX files only
  front = cellfun (@(s) isfile (fullfile (root, "inst", [s ".m"])), solvers);

  switch (mode)
    case "dev"
      mdir = fullfile (root, "inst");
      pkgdirs = {mdir};
      addpath (mdir, srcdir);
      ## C sources with %! blocks (pkg install turns them into *-tst
      ## files) and src/*-tst (pkg install copies them).
      tst = dir (fullfile (srcdir, "*-tst"));
      csrc = cellfun (@(f) fullfile (srcdir, f), [{entries.name}, {tst.name}],
                      "uniformoutput", false);
    case "installed"
      pkg ("load", "symplectic");
      info = pkg ("list", "symplectic");
      if (isempty (info))
        error ("run_tests: package symplectic is not installed");
      endif
      mdir = info{1}.dir;
      pkgdirs = unique ({info{1}.dir, info{1}.archprefix});
      pkgdirs = pkgdirs(cellfun (@isfolder, pkgdirs));
      csrc = {};
    otherwise
      error ("run_tests: MODE must be \"dev\" or \"installed\"");
  endswitch
  ## Shared helpers of the test scripts (tests/*.m not named test_*).
  addpath (testsdir);

  printf ("Testing symplectic (%s): %s\n", mode, strjoin (pkgdirs, ", "));

  ## Each gateway must resolve to a MEX file, and each solver to its
  ## m-file (a stray odeSE.mex of an old build would shadow it).
  nbad = 0;
  hint = ifelse_str (strcmp (mode, "dev"), " (run make)", "");
  for i = 1:numel (mexnames)
    try
      w = which (mexnames{i});   # loads the MEX file: may fail
    catch err
      printf ("FAIL: %s: %s\n", mexnames{i}, err.message);
      nbad += 1;
      continue;
    end_try_catch
    [~, ~, wext] = fileparts (w);
    if (! strcmp (wext, ".mex"))
      printf ("FAIL: %s resolves to '%s', not to a .mex%s\n",
              mexnames{i}, w, hint);
      nbad += 1;
    endif
    if (! front(i))
      continue;
    endif
    w = which (solvers{i});
    if (! strcmp (w, fullfile (mdir, [solvers{i} ".m"])))
      printf ("FAIL: %s resolves to '%s', not to %s\n", solvers{i}, w,
              fullfile (mdir, [solvers{i} ".m"]));
      nbad += 1;
    endif
  endfor

  files = {};
  for i = 1:numel (pkgdirs)
    files = [files, package_test_files(pkgdirs{i})];
  endfor
  files = [files, csrc];
  t = dir (fullfile (testsdir, "test_*.m"));
  files = [files, cellfun(@(f) fullfile (testsdir, f), sort ({t.name}),
                          "uniformoutput", false)];
  files = files(cellfun (@has_tests, files));
  ## A subset (make check-quick): keep the files named, complain of the rest.
  subset = strsplit (strtrim (getenv ("SYMPLECTIC_TESTS")));
  subset = subset(! cellfun (@isempty, subset));
  if (! isempty (subset))
    rel = cellfun (@(f) rel_name (f, [{root}, pkgdirs]), files,
                   "uniformoutput", false);
    for k = find (! ismember (subset, rel))
      printf ("FAIL: SYMPLECTIC_TESTS names '%s', which has no tests\n",
              subset{k});
      nbad += 1;
    endfor
    files = files(ismember (rel, subset));
  endif

  ## Run from an empty scratch directory: nothing there can shadow a
  ## package function, and files the tests write do not litter the tree.
  olddir = pwd ();
  scratch = tempname ();
  mkdir (scratch);
  set (0, "defaultfigurevisible", "off");
  npass = 0;
  nfail = nbad;
  nxfail = 0;
  nskip = 0;
  unwind_protect
    cd (scratch);
    for i = 1:numel (files)
      f = files{i};
      name = rel_name (f, [{root}, pkgdirs]);
      tic_f = tic ();
      try
        ## Failing blocks are written to stdout ("quiet": only those).
        [n, nmax, nxf, nbug, nsk, nrtsk] = test (f, "quiet", stdout);
      catch err
        printf ("FAIL: test (\"%s\") raised: %s\n", f, err.message);
        n = 0;  nmax = 1;  nxf = nbug = nsk = nrtsk = 0;
      end_try_catch
      cd (scratch);   # in case a test changed directory
      bad = nmax - n - nxf - nbug;
      printf ("%-50s pass %d/%d%s  (%.1f s)\n", name, n, nmax,
              ifelse_str (bad > 0, sprintf ("  FAIL %d", bad), ""),
              toc (tic_f));
      npass += n;
      nfail += bad;
      nxfail += nxf + nbug;
      nskip += nsk + nrtsk;
    endfor
  unwind_protect_cleanup
    cd (olddir);
    confirm_recursive_rmdir (false, "local");
    rmdir (scratch, "s");
  end_unwind_protect

  if (nxfail || nskip)
    printf ("(%d expected failures, %d skipped)\n", nxfail, nskip);
  endif
  if (npass + nfail == 0)
    printf ("no tests ran\n");
  endif
  printf ("%d passed, %d failed\n", npass, nfail);
  status = double (nfail > 0 || npass + nfail == 0);

endfunction

## The m-files and *-tst files under D, as pkg test finds them.
function files = package_test_files (d)
  files = {};
  lst = dir (d);
  for i = 1:numel (lst)
    nm = lst(i).name;
    f = fullfile (d, nm);
    if (nm(1) == ".")
      continue;
    elseif (lst(i).isdir)
      if (! strcmp (nm, "private"))
        files = [files, package_test_files(f)];
      endif
    elseif ((numel (nm) > 2 && strcmp (nm(end-1:end), ".m"))
            || (numel (nm) > 4 && strcmp (nm(end-3:end), "-tst")))
      files{end+1} = f;
    endif
  endfor
endfunction

## F relative to the first of DIRS that contains it.
function name = rel_name (f, dirs)
  name = f;
  for d = dirs
    name = strrep (name, [d{1} filesep], "");
  endfor
endfunction

## Whether file F has test blocks (the same test as pkg test's).
function tf = has_tests (f)
  str = fileread (f);
  tf = ! isempty (regexp (str, '^%!(assert|error|fail|test|xtest|warning)',
                          "lineanchors", "once"));
endfunction

function s = ifelse_str (c, a, b)
  if (c)
    s = a;
  else
    s = b;
  endif
endfunction
