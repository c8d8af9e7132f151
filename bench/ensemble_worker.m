## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## ensemble_worker.m -- one memory run of bench/run_ensemble.m, in its own
## octave-cli process so that its peak memory is its own:
##
##   octave-cli --norc --path "$PWD/inst:$PWD/src:$PWD/bench" \
##       bench/ensemble_worker.m solver=odeSV separable=on K=10000 \
##       steps=1000 out=FILE
##
## K pendulums (1 degree of freedom, q0 from 0.1 to 2.5, p0 = 0), fixed
## steps of 0.01, Vectorized, [t, Y] = solver (@pendulum_cols, [0 tf],
## Y0, opts) with Ensemble on.  A warm-up call (10 members, 10 steps)
## loads the MEX file and the m-files; then VmHWM is reset to VmRSS (5
## written to /proc/self/clear_refs), VmRSS is read ("before"), the call
## is timed, and VmHWM is read again ("after").  Saves res: the peak
## (after - before) and the output's bytes (t and Y), the time, the
## largest energy error over members and rows.

1;

function v = status_kb (name)
  s = fileread ("/proc/self/status");
  v = str2double (regexp (s, [name ":\\s*(\\d+)"], "tokens", "once"){1});
endfunction

kv = struct ("solver", "odeSV", "separable", "off", "K", "10000", ...
             "steps", "1000", "out", "");
for a = argv ()'
  p = strsplit (a{1}, "=");
  kv.(p{1}) = p{2};
endfor
solver = str2func (kv.solver);
K = str2double (kv.K);
steps = str2double (kv.steps);
h = 0.01;
q0 = linspace (0.1, 2.5, K);
Y0 = [q0; zeros(1, K)];
o = symplecticset ("TimeStepSize", h, "Vectorized", "on", "Ensemble", "on");
if (strcmp (kv.separable, "on"))
  o = symplecticset (o, "Separable", "on");
endif
[t, Y] = solver (@pendulum_cols, [0 10*h], Y0(:,1:10), o);
clear t Y
fid = fopen ("/proc/self/clear_refs", "w");
fputs (fid, "5");
fclose (fid);
rss0 = status_kb ("VmRSS");
tic;
[t, Y] = solver (@pendulum_cols, [0 steps*h], Y0, o);
res.time = toc;
res.peak = (status_kb ("VmHWM") - rss0) * 1024;
res.out = (numel (t) + numel (Y)) * 8;
E = squeeze (Y(:,2,:)).^2 / 2 - cos (squeeze (Y(:,1,:)));
res.dE = max (max (abs (E - E(1,:))));
res.K = K;
res.steps = steps;
save ("-binary", kv.out, "res");
