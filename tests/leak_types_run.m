## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## -*- texinfo -*-
## @deftypefn {} {} leak_types_run (@var{nrounds}, @var{filedir})
## The workload of tests/test_leak_types.m, run in a child octave-cli:
## odeSPVI with a Hessian or Jacobian of each type Octave can return
## (full, sparse, diagonal, permutation, range, single, integer, logical,
## complex), from HamiltonianHessFcn, FCN's second output, a Jacobian
## function or a constant Jacobian matrix; runs that end well and runs
## whose value goes wrong mid-run; one state and an Ensemble of 3.
## After a warm-up round of every case, @var{nrounds} rounds of one call
## of each run between two readings of VmRSS; printed: a line
## @samp{CASE name growth_kB} for each case (its own calls' growth),
## @samp{WRONG ...} for a case whose calls did not end as they should,
## then @samp{CALLS n} and @samp{GROWTH g kB}; then 100 @var{nrounds}
## calls of the last case (an Ensemble whose sparse Hessian, from a file
## cleared before each call, goes wrong at t > 0.2): @samp{FAILCALLS n
## failed} and @samp{FAILGROWTH g kB}; then @samp{LEAK TYPES DONE}.
## @var{filedir}: a writable directory for the Hessian function file that
## the last case clears between calls.
## @end deftypefn

function leak_types_run (nrounds, filedir)
  ## the pendulum, H = p^2/2 - cos q: Hess = diag (cos q, 1), Df = J Hess;
  ## each type made from the exact matrix M (those that cannot hold it
  ## give Newton a worse one: more refreshes, more calls)
  f = @(t, y) [y(2, :); -sin(y(1, :))];
  hess = @(y) [cos(y(1)) 0; 0 1];
  jac = @(y) [0 1; -cos(y(1)) 0];
  types = {
    "full",    @(M) M,                         true
    "sparse",  @(M) sparse (M),                true
    "diag",    @(M) diag (diag (M)),           true
    "perm",    @(M) eye (rows (M))(:, 1:columns (M)), true
    "single",  @(M) single (diag (diag (M))),  true    # a float diagonal
    "singlef", @(M) single (M),                true
    "int8",    @(M) int8 (M),                  true
    "logical", @(M) logical (M),               false
    "complex", @(M) complex (M),               false
  };
  y0 = [2; 0];
  cases = cell (0, 5);
  for ens = [false true]
    for fail = [false true]
      tag = [{"", "-ens"}{ens + 1}, {"", "-fail"}{fail + 1}];
      for i = 1:rows (types)
        [nm, mk, ok] = types{i, :};
        if (fail && ! ok)
          continue;   # refused at the first call already
        endif
        ok = ok && ! fail;
        hv = @(t, y) wrong_after (t, fail, @() mk (hess (y)), @() mk (eye (3)));
        jv = @(t, y) wrong_after (t, fail, @() mk (jac (y)), @() mk (eye (3)));
        cases = add (cases, ["hess-" nm tag], f,
                     struct ("HamiltonianHessFcn", hv), ens, ok);
        cases = add (cases, ["jac-" nm tag], f, struct ("Jacobian", jv),
                     ens, ok);
        if (i <= 5)
          cases = add (cases, ["fcn2-" nm tag], @(t, y) fcn2 (t, y, hv),
                       struct (), ens, ok);
        endif
        ## a constant Jacobian matrix (cannot go wrong mid-run)
        if (! fail)
          cases = add (cases, ["jacm-" nm tag], f,
                       struct ("Jacobian", mk (jac (y0))), ens, ok);
        endif
      endfor
      ## a range: the Hessian as a vector (a poor one), and as a Jacobian
      ## (not n-by-n: refused)
      rv = @(t, y) wrong_after (t, fail, @() 1:-1/3:0, @() 1:9);
      cases = add (cases, ["hess-range" tag], f,
                   struct ("HamiltonianHessFcn", rv), ens, ! fail);
      if (! fail)
        cases = add (cases, ["jac-range" tag], f, struct ("Jacobian", rv),
                     ens, false);
      endif
    endfor
  endfor
  ## a sparse Hessian from a file, cleared between calls (Ensemble, wrong
  ## size at t > 0.2)
  fid = fopen (fullfile (filedir, "leak_types_hess.m"), "w");
  fprintf (fid, "function h = leak_types_hess (t, y)\n");
  fprintf (fid, "  h = sparse ([cos(y(1)) 0; 0 1]);\n");
  fprintf (fid, "  if (t > 0.2)\n    h = speye (3);\n  endif\nendfunction\n");
  fclose (fid);
  addpath (filedir);
  cases = add (cases, "hessfile-sparse-ens-fail-cleared", f,
               struct ("HamiltonianHessFcn", @leak_types_hess), true, false);
  for k = 1:rows (cases)
    o = cases{k, 3};
    o.TimeStepSize = 0.1;
    cases{k, 6} = y0;
    if (cases{k, 4})
      o.Ensemble = "on";
      cases{k, 6} = [2 1.9 1.8; 0 0 0];
    endif
    cases{k, 3} = o;
  endfor
  ## a warm-up round (Octave's and the allocator's working set), then
  ## NROUNDS rounds of every case between two readings
  nfail = zeros (rows (cases), 1);
  grow = zeros (rows (cases), 1);
  for k = 1:rows (cases)
    one_case (cases(k, :), 2);
  endfor
  r0 = rss_kb ();
  for r = 1:nrounds
    for k = 1:rows (cases)
      g0 = rss_kb ();
      nfail(k) += one_case (cases(k, :), 1);
      grow(k) += rss_kb () - g0;
    endfor
  endfor
  r1 = rss_kb ();
  for k = 1:rows (cases)
    [nm, ~, ~, ~, ok] = cases{k, 1:5};
    if (nfail(k) != (! ok) * nrounds)
      printf ("WRONG %s: %d of %d calls failed\n", nm, nfail(k), nrounds);
    endif
    printf ("CASE %s %d\n", nm, grow(k));
  endfor
  printf ("CALLS %d\n", nrounds * rows (cases));
  printf ("GROWTH %d kB\n", r1 - r0);
  ## runs that fail early, many of them: an error used to leave what the
  ## core held to Octave, which keeps each block's address for good
  c = cases(end, :);
  one_case (c, 20);
  r0 = rss_kb ();
  nf = one_case (c, 100 * nrounds);
  printf ("FAILCALLS %d %d\n", 100 * nrounds, nf);
  printf ("FAILGROWTH %d kB\n", rss_kb () - r0);
  printf ("LEAK TYPES DONE\n");
endfunction

function cases = add (cases, nm, f, o, ens, ok)
  cases(end+1, :) = {nm, f, o, ens, ok};
endfunction

function nfail = one_case (c, n)
  [nm, f, o, ~, ~, y0] = c{:};
  nfail = 0;
  for i = 1:n
    if (strcmp (nm, "hessfile-sparse-ens-fail-cleared"))
      clear leak_types_hess;
    endif
    try
      [t, y] = odeSPVI (f, [0 3], y0, o);
    catch
      nfail++;
    end_try_catch
  endfor
endfunction

function v = wrong_after (t, fail, good, bad)
  if (fail && t > 1.5)
    v = bad ();
  else
    v = good ();
  endif
endfunction

function [dy, h] = fcn2 (t, y, hv)
  dy = [y(2); -sin(y(1))];
  h = hv (t, y);
endfunction

function kb = rss_kb ()
  s = fileread ("/proc/self/status");
  kb = str2double (regexp (s, 'VmRSS:\s*(\d+)\s*kB', "tokens", "once"){1});
endfunction
