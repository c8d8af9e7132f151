## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## run_verletform.m -- odeSV's VerletForm and CompensatedSummation on
## Kepler e = 0.6 over 200 periods (the exact end point is y0): kahanli8
## with SecondOrder, both inner Verlet forms at N = 12566 steps (17
## forces a step), then the round-off floor at N = 117647 (2e6 stages)
## with and without compensation, and their times.  Writes
## bench/VERLETFORM.md.  From the top of the tree after make:
##   octave-cli --norc --path inst:src bench/run_verletform.m

e = 0.6;  y0 = [1-e; 0; 0; sqrt((1+e)/(1-e))];  T = 400*pi;
acc = @(t, q) -q / norm (q)^3;
base = symplecticset ("Method", "kahanli8", "SecondOrder", "on");
out = {};
function [err, nf, tm] = one (acc, T, y0, o)
  t0 = tic;  [~, y] = odeSV (acc, [0 T], y0, symplecticset (o, "Stats", "off"));
  tm = toc (t0);
  sol = odeSV (acc, [0 T], y0, o);
  err = norm (y(end,:)' - y0);  nf = sol.stats.nfevals / sol.stats.nsteps;
endfunction
cases = {12566, "velocity", "on"; 12566, "position", "on";
         117647, "velocity", "off"; 117647, "velocity", "on";
         117647, "position", "off"; 117647, "position", "on"};
for i = 1:rows (cases)
  [N, form, comp] = cases{i, :};
  o = symplecticset (base, "TimeStepNumber", N, "VerletForm", form,
                     "CompensatedSummation", comp);
  [err, nf, tm] = one (acc, T, y0, o);
  out{end+1} = sprintf ("| %d | %s | %s | %.2e | %.1f | %.2f |", N, form,
                         comp, err, nf, tm);
  printf ("%s\n", out{end});
endfor
fid = fopen (fullfile (fileparts (mfilename ("fullpath")), "VERLETFORM.md"), "w");
fprintf (fid, "# odeSV kahanli8, SecondOrder: VerletForm and CompensatedSummation\n\n");
fprintf (fid, "Kepler e = 0.6, 200 periods (bench/run_verletform.m): the end point's\n");
fprintf (fid, "distance from y0, force evaluations per step, seconds of one run\n");
fprintf (fid, "(this machine, %s).\n\n", datestr (now, "yyyy-mm-dd"));
fprintf (fid, "| steps | VerletForm | CompensatedSummation | error | forces/step | s |\n");
fprintf (fid, "|---|---|---|---|---|---|\n");
fprintf (fid, "%s\n", out{:});
fclose (fid);
