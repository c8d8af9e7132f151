## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## Compiled FCNs (symcompile): Kepler, the pendulum and an FPU chain
## written in C (tests/compiled/*.c) against the same formulas as Octave
## functions.  The truth is the Octave FCN's run: the compiled one must
## equal it to round-off (1e-13 relative) in every mode the solvers have;
## the cache, its fallback and its errors are checked on files.

%!shared here, cache0, cache, kep, pen, fpu, y0k
%! here = fileparts (which ("test_compiled"));
%! cache0 = getenv ("XDG_CACHE_HOME");
%! cache = tempname ();
%! setenv ("XDG_CACHE_HOME", cache);
%! kep = symcompile (fullfile (here, "compiled", "kepler.c"));
%! pen = symcompile (fullfile (here, "compiled", "pendulum.c"));
%! fpu = symcompile (fullfile (here, "compiled", "fpu.c"));
%! y0k = [0.5; 0; 0; sqrt(3)];          # Kepler, eccentricity 0.5

%!function [dy, H] = kep_oct (t, y, mu)
%!  r = sqrt (y(1,:) .* y(1,:) + y(2,:) .* y(2,:));
%!  r3 = r .* r .* r;
%!  dy = [y(3,:); y(4,:); -mu * y(1,:) ./ r3; -mu * y(2,:) ./ r3];
%!  if (nargout > 1)
%!    q = y(1:2);
%!    H = blkdiag (mu * (eye (2) / r3 - 3 * (q * q') / (r3 * r * r)), eye (2));
%!  endif
%!endfunction

%!function a = kep_acc (t, q, mu)
%!  r = sqrt (q(1) * q(1) + q(2) * q(2));
%!  a = -mu * q / (r * r * r);
%!endfunction

%!function [dy, H] = pen_oct (t, y)
%!  dy = [y(2,:); -sin(y(1,:))];
%!  dy(2, abs (y(1,:)) > 3) = NaN;
%!  H = [cos(y(1)) 0; 0 1];
%!endfunction

%!function [dy, H] = fpu_oct (t, y, beta)
%!  d = numel (y) / 2;
%!  r = diff ([0; y(1:d); 0]);
%!  dy = [y(d+1:end); diff(r + beta * r .* r .* r)];
%!  k = 1 + 3 * beta * r .* r;
%!  Hq = spdiags ([[-k(2:d); 0], k(1:d) + k(2:d+1), [0; -k(2:d)]], -1:1, d, d);
%!  H = blkdiag (Hq, speye (d));
%!endfunction

%!function e = relerr (a, b)
%!  e = max (abs (a(:) - b(:))) / max (abs (b(:)));
%!endfunction

## ------------------------------------------------------------ the runs
%!test
%! ## fixed steps, 100 of them, every solver, Newton on the Hessian
%! opts = symplecticset ("TimeStepSize", 0.05, "TimeStepNumber", 100);
%! for s = {@odeSE, @odeSV, @odeSPVI}
%!   sol = s{1} (kep, [0 5], y0k, opts, 1);
%!   [t2, y2] = s{1} (@kep_oct, [0 5], y0k, opts, 1);
%!   assert (numel (sol.x), 101);
%!   assert (relerr (sol.y', y2) <= 1e-13, func2str (s{1}));
%!   assert (sol.stats.jacobian_source, "compiled Hessian of FCN");
%! endfor

%!test
%! ## explicit steps (Separable) and the pendulum, fixed steps
%! opts = symplecticset ("TimeStepSize", 0.1, "TimeStepNumber", 100,
%!                       "Separable", "on");
%! for s = {@odeSE, @odeSV}
%!   [~, y1] = s{1} (pen, [0 10], [1; 0], opts);
%!   [~, y2] = s{1} (@pen_oct, [0 10], [1; 0], opts);
%!   assert (relerr (y1, y2) <= 1e-13);
%!   [~, y1] = s{1} (kep, [0 5], y0k, opts, 1);
%!   [~, y2] = s{1} (@kep_oct, [0 5], y0k, opts, 1);
%!   assert (relerr (y1, y2) <= 1e-13);
%! endfor
%! [~, y1] = odeSPVI (pen, [0 10], [1; 0], symplecticset ("TimeStepSize", 0.1));
%! [~, y2] = odeSPVI (@pen_oct, [0 10], [1; 0], symplecticset ("TimeStepSize", 0.1));
%! assert (relerr (y1, y2) <= 1e-13);

%!test
%! ## adaptive steps: the same steps, the same values
%! opts = struct ("RelTol", 1e-8, "AbsTol", 1e-10);
%! for s = {@odeSE, @odeSV, @odeSPVI}
%!   [t1, y1] = s{1} (kep, [0 3], y0k, opts, 1);
%!   [t2, y2] = s{1} (@kep_oct, [0 3], y0k, opts, 1);
%!   assert (numel (t1), numel (t2));
%!   assert (relerr (y1, y2) <= 1e-13, func2str (s{1}));
%!   [t1, y1] = s{1} (pen, [0 10], [1; 0], opts);
%!   [t2, y2] = s{1} (@pen_oct, [0 10], [1; 0], opts);
%!   assert (numel (t1), numel (t2));
%!   assert (relerr (y1, y2) <= 1e-13, func2str (s{1}));
%! endfor

%!test
%! ## SecondOrder: the compiled acceleration
%! opts = symplecticset ("TimeStepSize", 0.05, "TimeStepNumber", 100,
%!                       "SecondOrder", "on");
%! [~, y1] = odeSV (kep, [0 5], y0k, opts, 1);
%! [~, y2] = odeSV (@kep_acc, [0 5], y0k, opts, 1);
%! assert (relerr (y1, y2) <= 1e-13);
%! opts.Method = "kahanli8";
%! [~, y1] = odeSV (kep, [0 5], y0k, opts, 1);
%! [~, y2] = odeSV (@kep_acc, [0 5], y0k, opts, 1);
%! assert (relerr (y1, y2) <= 1e-13);

%!test
%! ## reversible steps: the same run, and back to y0
%! opts = symplecticset ("StepControl", "reversible", "RelTol", 1e-6);
%! [t1, y1] = odeSV (kep, [0 3], y0k, opts, 1);
%! [t2, y2] = odeSV (@kep_oct, [0 3], y0k, opts, 1);
%! assert (numel (t1), numel (t2));
%! assert (relerr (y1, y2) <= 1e-13);
%! [~, yb] = odeSV (kep, [3 0], y1(end,:), opts, 1);
%! [~, yb2] = odeSV (@kep_oct, [3 0], y2(end,:), opts, 1);
%! assert (relerr (yb, yb2) <= 1e-13);
%! assert (yb(end,:), y0k', 1e-8);

%!test
%! ## Vectorized: the batch function, the same run
%! opts = struct ("Vectorized", "on", "RelTol", 1e-8);
%! [t1, y1] = odeSPVI (kep, [0 3], y0k, opts, 1);
%! [t2, y2] = odeSPVI (@kep_oct, [0 3], y0k, opts, 1);
%! assert (numel (t1), numel (t2));
%! assert (relerr (y1, y2) <= 1e-13);

%!test
%! ## an ensemble: each member as its own run
%! e = [0.1 0.3 0.5 0.7];
%! Y0 = [1 - e; 0 * e; 0 * e; sqrt((1 + e) ./ (1 - e))];
%! for v = {"on", "off"}
%!   opts = symplecticset ("TimeStepSize", 0.05, "TimeStepNumber", 100,
%!                         "Ensemble", "on", "Vectorized", v{1});
%!   for s = {@odeSV, @odeSPVI}
%!     [~, Y] = s{1} (kep, [0 5], Y0, opts, 1);
%!     o1 = rmfield (opts, "Ensemble");
%!     for m = 1:numel (e)
%!       [~, y2] = s{1} (@kep_oct, [0 5], Y0(:,m), o1, 1);
%!       assert (relerr (Y(:,:,m), y2) <= 1e-13);
%!     endfor
%!   endfor
%! endfor

%!function stop = outfn ()
%!  global calls
%!  calls++;
%!  stop = false;
%!endfunction

%!test
%! ## Events, OutputFcn (Octave functions, given PAR too), sol and symdeval
%! global calls
%! calls = 0;
%! opts = struct ("Events", @(t, y, mu) deal (y(2), 0, -1), "RelTol", 1e-9,
%!                "OutputFcn", @(t, y, f, mu) outfn (), "Dense", "on");
%! sol1 = odeSPVI (kep, [0 10], y0k, opts, 1);
%! assert (calls > 0);
%! sol2 = odeSPVI (@kep_oct, [0 10], y0k, opts, 1);
%! assert (numel (sol1.xe), 2);
%! assert (sol1.xe, sol2.xe, 1e-12);
%! assert (sol1.xe(:)', [pi, 3 * pi], 1e-6);   # the apocentre (period 2 pi)
%! assert (relerr (symdeval (sol1, 1.234), symdeval (sol2, 1.234)) <= 1e-13);
%! clear -global calls

%!test
%! ## the chain: a sparse Hessian (sparse Newton), JPattern from its pattern
%! d = 40;
%! y0 = [0.1 * sin(pi * (1:d)' / (d + 1)); zeros(d, 1)];
%! assert (fpu.nnz, 3 * d - 2 + d);
%! opts = symplecticset ("TimeStepSize", 0.1, "TimeStepNumber", 100);
%! sol = odeSPVI (fpu, [0 10], y0, opts, 1);
%! [~, y2] = odeSPVI (@fpu_oct, [0 10], y0, opts, 1);
%! assert (relerr (sol.y', y2) <= 1e-13);
%! assert (sol.stats.jacobian_source, "compiled Hessian of FCN");
%! [dy, H] = fpu (0, y0, 1);
%! [dy2, H2] = fpu_oct (0, y0, 1);
%! assert (issparse (H));
%! assert (dy, dy2, 1e-15);
%! assert (full (H), full (H2), 1e-14);

%!test
%! ## NaN from f: the warning and the part computed, as an Octave FCN's
%! opts = symplecticset ("TimeStepSize", 0.1, "Separable", "on");
%! [msg1, id1] = lastwarn ("", "");
%! [t1, y1] = odeSV (pen, [0 10], [0; 2.5], opts);
%! [msg1, id1] = lastwarn ("", "");
%! [t2, y2] = odeSV (@pen_oct, [0 10], [0; 2.5], opts);
%! [msg2, id2] = lastwarn ();
%! assert (id1, id2);
%! assert (msg1, msg2);
%! assert (! isempty (strfind (msg1, "NaN")));
%! assert (t1, t2);
%! assert (relerr (y1, y2) <= 1e-13);
%! assert (t1(end) < 10);

## ------------------------------------------------------------ from Octave
%!test
%! ## f, the Hessian, H and the acceleration against the formulas
%! y = [0.3; -0.4; 0.2; 1.1];
%! [dy, H] = kep (0, y, 2);
%! [dy2, H2] = kep_oct (0, y, 2);
%! assert (dy, dy2, 1e-15);
%! assert (H, H2, 1e-14);
%! assert (kep.energy (0, y, 2), (0.2^2 + 1.1^2) / 2 - 2 / 0.5, 1e-15);
%! assert (kep.acceleration (0, y(1:2), 2), kep_acc (0, y(1:2), 2), 1e-15);
%! Y = [y, 2 * y];
%! assert (kep (0, Y, 2), kep_oct (0, Y, 2), 1e-15);
%! assert ([kep.dim, kep.npar, kep.nnz], [2 1 6]);
%! assert (kep.hessian && kep.energy (0, y, 1) < 0);
%! h = kep.energy;
%! assert (h (0, y, 2), kep.energy (0, y, 2));
%! ## the energy as the Hamiltonian option
%! sol = odeSV (kep, [0 5], y0k, symplecticset ("TimeStepSize", 0.01,
%!              "Separable", "on", "Hamiltonian", kep.energy), 1);
%! assert (sol.H(1), -0.5, 1e-14);
%! assert (sol.stats.max_dH < 1e-3);

## ------------------------------------------------------------ the cache
%!test
%! ## a second call compiles nothing: the same file, loaded
%! f = fullfile (here, "compiled", "kepler.c");
%! s0 = stat (kep.lib);
%! tic;
%! k2 = symcompile (f);
%! el = toc;
%! assert (k2.cached);
%! assert (! kep.cached);
%! assert (k2.lib, kep.lib);
%! assert (stat (k2.lib).mtime, s0.mtime);
%! assert (el < 0.5);
%! assert (strncmp (kep.lib, fullfile (cache, "symplectic"), numel (cache)));
%! assert (exist (kep.source, "file"), 2);

%!test
%! ## an unwritable cache: a temporary directory instead
%! old = getenv ("XDG_CACHE_HOME");
%! unwind_protect
%!   setenv ("XDG_CACHE_HOME", "/dev/null/cache");
%!   k = symcompile (fullfile (here, "compiled", "pendulum.c"));
%!   assert (strncmp (k.lib, fullfile (tempdir (), "symplectic-cache-"),
%!                    numel (fullfile (tempdir (), "symplectic-cache-"))));
%!   [~, y] = odeSV (k, [0 1], [1; 0], symplecticset ("TimeStepSize", 0.1));
%!   assert (rows (y), 11);
%! unwind_protect_cleanup
%!   setenv ("XDG_CACHE_HOME", old);
%! end_unwind_protect

%!test
%! ## two processes building the same entry at once
%! tdir = tempname ();
%! mkdir (tdir);
%! src = sprintf (["#include \"symplectic_fcn.h\"\nSYMPLECTIC_SYSTEM (1, 0);\n" ...
%!                 "int symplectic_f (double t, const double *y, double *dy," ...
%!                 " const double *par)\n{ dy[0] = y[1]; dy[1] = -y[0] * %d; return 0; }\n"],
%!                randi (1e9));
%! script = fullfile (tdir, "build.m");
%! fid = fopen (script, "w");
%! fprintf (fid, "addpath ('%s', '%s');\nk = symcompile (fileread ('%s'));\n",
%!          fileparts (which ("symcompile")), fileparts (which ("__symcompiled__")),
%!          fullfile (tdir, "src.c"));
%! fprintf (fid, "y = k (0, [1; 2]);\nprintf ('ok %%g\\n', y(1));\n");
%! fclose (fid);
%! fid = fopen (fullfile (tdir, "src.c"), "w");
%! fputs (fid, src);
%! fclose (fid);
%! oct = fullfile (OCTAVE_HOME (), "bin", "octave-cli");
%! cmd = sprintf (["XDG_CACHE_HOME='%s' '%s' --norc --quiet --no-gui '%s' > '%s/1.out' 2>&1 & " ...
%!                 "XDG_CACHE_HOME='%s' '%s' --norc --quiet --no-gui '%s' > '%s/2.out' 2>&1; wait"],
%!                tdir, oct, script, tdir, tdir, oct, script, tdir);
%! system (cmd);
%! for i = 1:2
%!   out = fileread (fullfile (tdir, sprintf ("%d.out", i)));
%!   assert (! isempty (strfind (out, "ok 2")), out);
%! endfor
%! assert (numel (dir (fullfile (tdir, "symplectic", "symfcn-*.so"))), 1);
%! assert (isempty (dir (fullfile (tdir, "symplectic", ".tmp-*"))));
%! confirm_recursive_rmdir (false, "local");
%! rmdir (tdir, "s");

## ------------------------------------------------------------ errors
%!test
%! ## a compile error: the compiler's message and the C file's path
%! n0 = numel (dir (fullfile (cache, "symplectic")));
%! try
%!   symcompile ("#include \"symplectic_fcn.h\"\nSYMPLECTIC_SYSTEM (1, 0);\nint symplectic_f (oops\n");
%!   error ("no error");
%! catch err
%!   assert (err.identifier, "symplectic:compile");
%!   tok = regexp (err.message, '^symcompile: the C compiler failed on (\S+\.c):\n', "tokens", "once");
%!   assert (! isempty (tok), err.message);
%!   assert (! isempty (strfind (err.message, "error")));
%!   assert (! isempty (strfind (fileread (tok{1}), "int symplectic_f (oops")));
%!   unlink (tok{1});
%! end_try_catch
%! ## nothing left in the cache
%! assert (numel (dir (fullfile (cache, "symplectic"))), n0);

%!test
%! ## the ABI: no symplectic_f, no SYMPLECTIC_SYSTEM; nothing cached
%! n0 = numel (dir (fullfile (cache, "symplectic")));
%! try
%!   symcompile ("#include \"symplectic_fcn.h\"\nSYMPLECTIC_SYSTEM (1, 0);\nint g (void) { return 0; }\n");
%!   error ("no error");
%! catch err
%!   assert (err.identifier, "symplectic:compiled-abi");
%!   assert (! isempty (regexp (err.message, '^symcompile: the compiled code defines no function symplectic_f', "once")), err.message);
%! end_try_catch
%! try
%!   symcompile ("int symplectic_f (double t, const double *y, double *dy, const double *p)\n{ return 0; }\n");
%!   error ("no error");
%! catch err
%!   assert (! isempty (regexp (err.message, '^symcompile: the compiled code declares no SYMPLECTIC_SYSTEM', "once")), err.message);
%! end_try_catch
%! assert (numel (dir (fullfile (cache, "symplectic"))), n0);

%!error <odeSV: the compiled FCN takes its parameters as PAR1, a real vector of SYMPLECTIC_SYSTEM's npar elements, got none>
%! odeSV (kep, [0 1], y0k, symplecticset ("TimeStepSize", 0.1));
%!error <odeSPVI: the compiled FCN takes its parameters as PAR1.*got 1x2 double>
%! odeSPVI (kep, [0 1], y0k, symplecticset ("TimeStepSize", 0.1), [1 2]);
%!error <odeSE: the compiled FCN takes no parameters, got 1x1 double>
%! odeSE (pen, [0 1], [1; 0], [], 3);
%!error <odeSV: the compiled FCN has d = 2 \(y of 4 components\), but Y0 has 2 elements>
%! odeSV (kep, [0 1], [1; 0], [], 1);
%!error <odeSV: SecondOrder needs the acceleration>
%! f = symcompile ("#include \"symplectic_fcn.h\"\nSYMPLECTIC_SYSTEM (1, 0);\nint symplectic_f (double t, const double *y, double *dy, const double *p)\n{ dy[0] = y[1]; dy[1] = -y[0]; return 0; }\n");
%! odeSV (f, [0 1], [1; 0], symplecticset ("TimeStepSize", 0.1, "SecondOrder", "on"));
%!error <symfcn: the compiled FCN takes 1 parameter as PAR>
%! kep (0, y0k);
%!error <odeSV: FCN returned NaN \(element 2\) at t = 0, the initial point>
%! odeSV (pen, [0 1], [3.5; 0], []);

%!test
%! setenv ("XDG_CACHE_HOME", cache0);
%! confirm_recursive_rmdir (false, "local");
%! rmdir (cache, "s");
