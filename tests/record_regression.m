## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## record_regression.m -- write tests/regression.txt.gz, the outputs of
## regression_runs () that tests/test_regression.m compares with.  Run
## from the top of the tree after `make`:
##
##   octave-cli --norc --path inst:src:tests tests/record_regression.m

runs = regression_runs ();
ref = struct ("name", {runs.name});
for k = 1:numel (runs)
  ref(k).out = regression_outputs (runs(k));
endfor
file = fullfile (fileparts (mfilename ("fullpath")), "regression.txt.gz");
save ("-text", "-zip", file, "ref");
printf ("record_regression: %d runs into %s\n", numel (runs), file);
