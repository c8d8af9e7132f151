## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## -*- texinfo -*-
## @deftypefn {} {@var{fcn} =} __symcompile_build__ (@var{source}, @var{srcdir}, @var{extra}, @var{who})
## The C code @var{source} (symplectic_fcn.h's functions) as a compiled
## FCN (a symfcn object): loaded from the per-user cache, or compiled into
## it.  @var{srcdir} (or "") goes on the include path; @var{extra} is kept
## in the object (fields that the object's "." indexing returns); errors
## name @var{who}.  Internal to symcompile, symhamiltonian, symlagrangian.
## @end deftypefn

function fcn = __symcompile_build__ (source, srcdir, extra, who = "symcompile")
  persistent cfg;
  if (isempty (cfg))
    cfg = compiler_config (who);
  endif
  key = hash ("md5", [source "\n--\n" cfg.cc "\n" cfg.cflags "\n" cfg.pic ...
                      "\n" cfg.version "\n" cfg.header]);
  dir = cache_dir (who);
  so = fullfile (dir, ["symfcn-" key ".so"]);
  csrc = fullfile (dir, ["symfcn-" key ".c"]);
  gate = struct ("symplectic_compiled", so);
  cached = false;
  if (exist (so, "file"))
    try
      info = __symcompiled__ ("info", gate, who);
      cached = true;
    catch
      ## not loadable (a damaged entry): built again below
    end_try_catch
  endif
  if (! cached)
    info = build (cfg, dir, key, source, srcdir, so, csrc, who);
  endif
  s.lib = so;
  s.source = csrc;
  s.cached = cached;
  for f = fieldnames (info).'
    s.(f{1}) = info.(f{1});
  endfor
  s.extra = extra;
  fcn = symfcn (s);
endfunction

## Compile into a file of this process's own, check it, then rename it into
## place: another process building the same entry renames a file of the
## same content, and nothing half-written ever has the entry's name.
function info = build (cfg, dir, key, source, srcdir, so, csrc, who)
  tag = sprintf ("%s.%d.%08x", key, getpid (), randi (2^31 - 1));
  tmpc = fullfile (dir, [".tmp-" tag ".c"]);
  tmpso = fullfile (dir, [".tmp-" tag ".so"]);
  fid = fopen (tmpc, "w");
  if (fid < 0)
    error ("symplectic:cache", "%s: cannot write %s", who, tmpc);
  endif
  fputs (fid, source);
  fclose (fid);
  inc = ["-I" quote(cfg.hdrdir)];
  if (! isempty (srcdir))
    inc = [inc " -I" quote(srcdir)];
  endif
  cmd = sprintf ("%s %s %s -shared %s -o %s %s -lm 2>&1", cfg.cc, cfg.cflags,
                 cfg.pic, inc, quote (tmpso), quote (tmpc));
  [st, out] = system (cmd);
  if (st != 0 || ! exist (tmpso, "file"))
    keep = keep_source (tmpc, key);
    unlink_quiet (tmpso);
    if (st == 127)
      error ("symplectic:compile",
             "%s: no C compiler: '%s' (mkoctfile -p CC) cannot be run; the C file is %s",
             who, cfg.cc, keep);
    endif
    error ("symplectic:compile", "%s: the C compiler failed on %s:\n%s",
           who, keep, strtrim (out));
  endif
  try
    info = __symcompiled__ ("info", struct ("symplectic_compiled", tmpso), who);
  catch err
    keep = keep_source (tmpc, key);
    unlink_quiet (tmpso);
    error (err.identifier, "%s (the C file: %s)", err.message, keep);
  end_try_catch
  [err, msg] = rename (tmpso, so);
  if (err)
    unlink_quiet (tmpso);
    unlink_quiet (tmpc);
    error ("symplectic:cache", "%s: cannot move the compiled code to %s: %s",
           who, so, msg);
  endif
  if (rename (tmpc, csrc))
    unlink_quiet (tmpc);
  endif
endfunction

## a failed C file, moved out of the cache to where the user can read it
function keep = keep_source (tmpc, key)
  keep = fullfile (tempdir (), ["symplectic-" key ".c"]);
  if (! movefile (tmpc, keep))
    keep = tmpc;
  endif
endfunction

function unlink_quiet (f)
  if (exist (f, "file"))
    unlink (f);
  endif
endfunction

## a path for the shell, in single quotes
function s = quote (p)
  s = ["'" strrep(p, "'", "'\\''") "'"];
endfunction

## $XDG_CACHE_HOME/symplectic (~/.cache/symplectic), else a directory of the
## user's own in the temporary directory
function dir = cache_dir (who)
  base = getenv ("XDG_CACHE_HOME");
  if (isempty (base))
    base = fullfile (getenv ("HOME"), ".cache");
  endif
  dir = fullfile (base, "symplectic");
  if (can_write (dir))
    return;
  endif
  user = getenv ("USER");
  if (isempty (user))
    user = "user";
  endif
  first = dir;
  dir = fullfile (tempdir (), ["symplectic-cache-" user]);
  if (! can_write (dir))
    error ("symplectic:cache", "%s: neither %s nor %s can be written",
           who, first, dir);
  endif
endfunction

function ok = can_write (dir)
  ok = exist (dir, "dir") == 7;
  if (! ok)
    [ok, ~] = mkdir (dir);
    if (! ok || exist (dir, "dir") != 7)
      ok = false;
      return;
    endif
  endif
  probe = fullfile (dir, sprintf (".probe-%d-%08x", getpid (), randi (2^31 - 1)));
  fid = fopen (probe, "w");
  ok = fid >= 0;
  if (ok)
    fclose (fid);
    unlink (probe);
  endif
endfunction

## mkoctfile's C compiler and flags, the header and the package's version
## (all in the cache key)
function cfg = compiler_config (who)
  mk = getenv ("MKOCTFILE");
  if (isempty (mk))
    mk = fullfile (OCTAVE_HOME (), "bin", ["mkoctfile-" OCTAVE_VERSION()]);
    if (! exist (mk, "file"))
      mk = fullfile (OCTAVE_HOME (), "bin", "mkoctfile");
    endif
    if (! exist (mk, "file"))
      mk = "mkoctfile";
    endif
  endif
  [st, out] = system (sprintf ("%s -p CC && %s -p CFLAGS && %s -p CPICFLAG",
                               mk, mk, mk));
  lines = regexp (out, '\n', "split");
  if (st != 0 || numel (lines) < 3)
    error ("symplectic:compile",
           "%s: mkoctfile (%s) cannot tell the C compiler:\n%s", who, mk,
           strtrim (out));
  endif
  cfg.cc = strtrim (lines{1});
  cfg.cflags = strtrim (lines{2});
  cfg.pic = strtrim (lines{3});
  instdir = fileparts (fileparts (mfilename ("fullpath")));
  cfg.hdrdir = instdir;
  cfg.header = fileread (fullfile (instdir, "symplectic_fcn.h"));
  cfg.version = "unknown";
  for d = {fullfile(instdir, "packinfo", "DESCRIPTION"), ...
           fullfile(instdir, "..", "DESCRIPTION")}
    if (exist (d{1}, "file"))
      v = regexp (fileread (d{1}), '(?m)^Version:\s*(\S+)', "tokens", "once");
      if (! isempty (v))
        cfg.version = v{1};
        break;
      endif
    endif
  endfor
endfunction
