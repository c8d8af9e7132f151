## Copyright (C) 2026 The symplectic developers
## SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.

## Options and FCN as a newcomer gets them wrong: another solver's option
## is said as ignored, a value no solver takes is an error in every
## solver, a typo is warned once, Separable is probed in odeSV, and FCN of
## the wrong form is said by the solver.

%!shared f, y0
%! f = @(t, y) [y(2); -sin(y(1))];
%! y0 = [1; 0];

%!warning <odeSPVI: option Method is used by odeSV only; ignored>
%! x = odeSPVI (f, [0 1], y0, symplecticset ("TimeStepSize", 0.1, "Method", "kahanli8"));
%!warning <odeSE: option Nodes is used by odeSPVI only; ignored>
%! x = odeSE (f, [0 1], y0, symplecticset ("TimeStepSize", 0.1, "Nodes", 5));
%!error <odeSPVI: Separable must be "on" or "off", got "maybe">
%! x = odeSPVI (f, [0 1], y0, symplecticset ("TimeStepSize", 0.1, "Separable", "maybe"));
%!error <odeSE: Method must be one of .*; got "bogus">
%! x = odeSE (f, [0 1], y0, symplecticset ("TimeStepSize", 0.1, "Method", "bogus"));
%!error <odeSV: NewtonMatrix must be "auto", "kept" or "new", got "bogus">
%! x = odeSV (f, [0 1], y0, symplecticset ("TimeStepSize", 0.1, "NewtonMatrix", "bogus"));
%!error <odeSV: Nodes must be an integer, got 2.5>
%! x = odeSV (f, [0 1], y0, symplecticset ("TimeStepSize", 0.1, "Nodes", 2.5));

%!test
%! ## a typo through symplecticset: warned once (by symplecticset), not
%! ## again by the solver; a field added later is warned by the solver
%! txt = evalc ("x = odeSPVI (f, [0 1], y0, symplecticset ('TimeStepSize', 0.1, 'Nodse', 3));");
%! assert (numel (strfind (txt, "unknown option Nodse")), 1);
%! o = symplecticset ("TimeStepSize", 0.1);
%! o.Nodse = 3;
%! txt = evalc ("x = odeSPVI (f, [0 1], y0, o);");
%! assert (numel (strfind (txt, "odeSPVI: unknown option Nodse")), 1);

%!warning <odeSV: RelTol is for adaptive steps only and is ignored with a fixed step>
%! x = odeSV (f, [0 1], y0, symplecticset ("TimeStepSize", 0.1, "RelTol", 1e-3));

%!test
%! ## Separable on with damping: odeSV warns as odeSE does, and the
%! ## calls of FCN are as many as without the probe
%! g = @(t, y) [y(2); -y(1) - 0.1 * y(2)];
%! lastwarn ("");
%! x = odeSV (g, [0 1], y0, symplecticset ("TimeStepSize", 0.01, "Separable", "on"));
%! [msg, id] = lastwarn ();
%! assert (id, "symplectic:not-separable");
%! assert (regexp (msg, "^odeSV: Separable is on.*changed with p at the same q at t = 0;"));
%! sol = odeSV (f, [0 1], y0, symplecticset ("TimeStepSize", 0.01, "Separable", "on"));
%! assert (sol.stats.nfevals, 202);

%!error <odeSV: FCN takes 1 argument, but is called as FCN \(t, y\)>
%! x = odeSV (@(y) [y(2); -sin(y(1))], [0 1], [1; 0]);
%!error <odeSV: FCN takes 1 argument>
%! x = odeSV (@(t) t, [0 1], [1; 0]);
%!error <odeSV: with SecondOrder on, FCN is called as FCN \(t, q\).*gave: .*out of bound>
%! x = odeSV (f, [0 1], y0, symplecticset ("SecondOrder", "on", "TimeStepSize", 0.1));
%!error id=my:id
%! x = odeSE (@(t, q) error ("my:id", "mine"), [0 1], y0, symplecticset ("SecondOrder", "on", "TimeStepSize", 0.1));
%!error <odeSV: Events takes 1 argument, but is called as Events \(t, y\)>
%! x = odeSV (f, [0 1], y0, struct ("Events", @(t) t));
%!error <odeSV: OutputFcn takes 2 arguments, but is called as OutputFcn \(t, y, flag\)>
%! x = odeSV (f, [0 1], y0, struct ("OutputFcn", @(t, y) false));
%!function out_nothing (t, y, flag)
%!endfunction
%!function v = event_value_only (t, y)
%!  v = y(1);
%!endfunction
%!error <odeSV: the OutputFcn function must return one output, STOP \(true to end the run\), got 0>
%! x = odeSV (f, [0 1], y0, struct ("OutputFcn", @out_nothing, "TimeStepSize", 0.1));
%!error <odeSPVI: the Events function must return three outputs \[VALUE, ISTERMINAL, DIRECTION\], got 1>
%! x = odeSPVI (f, [0 1], y0, struct ("Events", @event_value_only, "TimeStepSize", 0.1));
%!test
%! ## anonymous functions do not declare their outputs: they pass
%! [t, y, te] = odeSV (f, [0 2], y0, struct ("TimeStepSize", 0.01,
%!                     "Events", @(t, y) deal (y(1), 0, 0),
%!                     "OutputFcn", @(t, y, flag) false));
%! assert (te, ellipke (sin (0.5)^2), 1e-3);   # the pendulum's T/4 from 1 rad
%!error <odeSV: StepDensityFcn takes 1 argument>
%! x = odeSV (f, [0 1], y0, struct ("StepDensityFcn", @(t) 1, "StepControl", "reversible"));
