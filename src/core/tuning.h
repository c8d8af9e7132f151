/* Copyright (C) 2026 The symplectic developers
   SPDX-License-Identifier: GPL-3.0-or-later; see the file COPYING.  */

/* tuning.h -- every default, limit and tuning constant of the core, each
   with the reason for it.  The measurements behind the numbers are in
   bench/NOTES.md. */
#ifndef SYM_TUNING_H
#define SYM_TUNING_H

/* ------------------------------------------------------------ defaults */
/* Newton's stopping tolerance, relative to the size of its unknowns */
#define SYM_NEWTON_TOL 1e-14
/* Newton iterations per solve before the matrix is refreshed or the step
   retried */
#define SYM_NEWTON_MAXIT 10
/* odeSPVI's nodes; its modes of q default to nodes + 1 (the pairs whose
   order is 2 nodes) */
#define SYM_SPVI_NODES 3

/* ------------------------------------------------------------ limits */
/* The most steps a run may ask for (TimeStepNumber, MaxSteps, a fixed
   step over the span): doubles count them exactly, and a long holds
   them where it has 64 bits */
#define SYM_MAX_STEPS 1e12
/* odeSPVI's nodes: beyond 40 the predictor's continuation is noise and
   the quadrature gains nothing in double precision */
#define SYM_SPVI_MAX_NODES 40

/* ------------------------------------------------------------ Newton */
/* Corrections below 16 ulps of their scale are round-off: accept */
#define SYM_NEWTON_FLOOR 16.0
/* The carried rate of the last solve stands in for theta; floored so that
   one correction suffices only when it is below 1e3 tol */
#define SYM_NEWTON_ETA_MIN 1e-3
#define SYM_NEWTON_ETA_POW 0.8
/* A contraction rate this close to 1 is divergence */
#define SYM_NEWTON_DIVERGE 0.99
/* Full Newton (a new matrix every iterate) accepts a stagnation at rate
   0.5 or worse within 1e3 round-off floors or tol: those pairs are
   ill-conditioned */
#define SYM_NEWTON_FULL_STALL 0.5
#define SYM_NEWTON_FULL_FLOOR 1e3
/* With a new matrix every solve, stop after the first (exact Newton)
   correction when SAFE kq |dx_1|^2 <= tol: 10 drifted the energy (the
   error left is quadratic, it has a sign) */
#define SYM_NEWTON_QUAD_SAFE 100.0
/* measure kq again after this many one-correction stops */
#define SYM_NEWTON_QUAD_AGE 16
/* measure kq only from a second correction this many round-off floors
   above round-off, so that no decision follows the last bits of f */
#define SYM_NEWTON_QUAD_INFO 100.0
/* A fixed step's solve goes to this fraction of the Newton tolerance
   (odeSPVI: the estimated error of its result): round-off, so that the
   error a stop leaves (it has a sign with a kept matrix) does not add up
   over many steps */
#define SYM_FIXED_TOL 1e-2
/* odeSPVI's reversible steps: a tenth of that, so that a run retraced
   comes back nearer to round-off (bench/NOTES.md) */
#define SYM_REVERSIBLE_TOL 1e-3
/* odeSE and odeSV: a tenth of that (their finite-difference matrices
   contract more slowly and leave the stop nearer its bound) */
#define SYM_FIXED_TOL_KEPT 1e-3
/* A kept matrix is rebuilt when h changed by more than this fraction */
#define SYM_REBUILD_H 0.2

/* ------------------------------------------------------------ calls */
/* The user's Df may differ from forward differences by a tenth of the
   largest entry (differences err by ~1% where f varies on a scale below
   their step) */
#define SYM_JAC_AGREE 0.1
/* no more checks of Df after this many that agreed (each costs a Df and
   2d + 1 calls of f) */
#define SYM_JAC_CHECKS 3
/* The first Df is dropped at once when it predicts a change of f more
   than GROSS times off (plus NOISE ulps of f, its round-off): a Df too
   large by 1e12 makes Newton's corrections round-off, and every solve
   stops at its start */
#define SYM_JAC_GROSS 100.0
#define SYM_JAC_NOISE 1e3
/* dense LUs of at most this many unknowns are factored and solved by
   the core's own loops, not LAPACK (numerics/lu.c) */
#define SYM_LU_SMALL 32
/* Separable steps: f_p (SE) or f_q (SV) differing by more than this
   relative size at two evaluations that must agree: not separable */
#define SYM_SEP_TOL 1e-8
/* A finite-difference step is at least this fraction of the largest size
   in its half of y, so that a component passing through zero keeps a
   useful step */
#define SYM_FD_FLOOR 1e-6
/* a finite-difference workspace of at most this many doubles is taken
   on the stack (4 KB; a member of an ensemble has SYM_ENS_STACK) */
#define SYM_FD_LOCAL 512
/* values of y in one batch call of finite differences */
#define SYM_FD_BATCH_DOUBLES ((size_t) 1 << 19)

/* ------------------------------------------------------------ control */
/* the step-size factor's safety, and its bounds after a rejection and an
   acceptance */
#define SYM_CTRL_SAFETY 0.9
#define SYM_CTRL_FACMIN 0.2
#define SYM_CTRL_FACMAX 5.0
/* after a failed step and a Newton failure: halve */
#define SYM_CTRL_FACFAIL 0.5
/* the predictive factor takes errors no smaller than this, so that
   round-off level errors make no trend */
#define SYM_CTRL_ERR_FLOOR 1e-2
/* Reversible control: the largest eps (steps of eps / rho), beyond which
   the density changes too much within a step for its recurrence to
   follow it; the trial steps that find the first density; and the least
   rho_{n+1/2} as a fraction of rho(y_n), which keeps a density that
   falls by more than that within a step positive (not reversible there) */
#define SYM_REV_EPS_MAX 0.05
#define SYM_REV_START 2
#define SYM_REV_FLOOR 0.25
/* a remainder of the span below this fraction of a reversible step
   joins it: a run back from a step point sums the same steps in another
   order, and misses t0 by their round-off */
#define SYM_REV_JOIN 1e-6
/* The least step is 16 ulps of t: t + h then moves by more than t's
   round-off; and 4 ulps of the span: a run creeping towards a
   singularity stops, and a step that fails at every size fails about 52
   times in a row at most (each failure after the first halves h) */
#define SYM_HMIN_ULPS 16.0
#define SYM_HMIN_SPAN 4.0
/* what is left of the span after a step joins it when below this
   fraction of the span (or the least step) */
#define SYM_SPAN_SLIVER 1e-10
/* a fixed step that divides the span within this relative round-off
   takes no extra short step */
#define SYM_FIXED_FIT 1e-9
/* t0 + N h is rounded three times: within this many ulps of max(|t0|,
   N h) of an output time it is that time */
#define SYM_SNAP_ULPS 16.0

/* ------------------------------------------------------------ events */
/* Illinois iterations at most (a bracket of a few ulps ends them) */
#define SYM_EVENT_ITERS 200
/* events within 32 ulps of t and 64 eps of the step are at one time */
#define SYM_EVENT_SAME_ULPS 32.0
#define SYM_EVENT_SAME_STEP 64.0
/* a parabola's vertex must be this many ulps of the values beyond zero
   to predict a zero pair */
#define SYM_EVENT_VERTEX_ULPS 64.0

/* ------------------------------------------------------------ one-step */
/* Newton iterations a solve needs with a fresh matrix and a good start;
   those beyond are charged to the kept matrix */
#define SYM_NW_BASE 2
/* solves of the history of the implicit unknowns: up to this many past
   errors of the explicit start, extrapolated */
#define SYM_PRED_MAX 16
/* odeSE/odeSV: a last correction below this many ulps of the scale
   needs no check of its result */
#define SYM_KEPT_ROUNDOFF 4.0
/* the check of a solve's result (implicit.c) takes a next correction
   below this many ulps of the scale as round-off, and at most this many
   solves are made */
#define SYM_KEPT_CHECK_ULPS 8.0
#define SYM_KEPT_ROUNDS 3
/* a failed check showing a rate above this restarts the rate estimate
   at 1 */
#define SYM_KEPT_RATE_MAX 0.5

/* ------------------------------------------------------------ odeSPVI */
/* A solve of more corrections refreshes the matrix (once the extra ones
   have cost a new one), unless its first contraction was below
   THETA_FRESH: then the start, not the matrix, was far */
#define SYM_SPVI_REFRESH_ITERS 2
#define SYM_SPVI_THETA_FRESH 5e-5
/* the pairs n - 1 != m (ill-conditioned, their solves end with one
   unchecked correction): a fresh matrix after more than this many */
#define SYM_SPVI_REFRESH_SLOW 3
/* Adaptive solves stop at these fractions of the smallest error the
   tolerances allow: the method's (it only enters the estimate) and the
   companion's (the run advances with it) */
#define SYM_SPVI_EST_LO 1e-3
#define SYM_SPVI_EST_HI 1e-4
/* at most this many corrections for the error of the linear move of f_p
   into p_{k+1} */
#define SYM_SPVI_MOVE_MAX 3
/* Node Jacobians extrapolated from evaluations at most STEPS steps back,
   through at most POINTS nodes, the older evaluation only within SPAN
   steps, and only while the Lebesgue sum stays below LEBESGUE */
#define SYM_SPVI_JX_STEPS 5
#define SYM_SPVI_JX_SPAN 8
#define SYM_SPVI_JX_POINTS 6
#define SYM_SPVI_JX_LEBESGUE 1e4
/* those steps are counted from the steps' sizes, up to round-off */
#define SYM_SPVI_JX_SLACK 1e-9
/* past errors of the polynomial prediction extrapolated (more amplifies
   the round-off of past solutions to the size of the start error) */
#define SYM_SPVI_HIST 4
/* a continued prediction that moves more than this many times the last
   step's change is not used */
#define SYM_SPVI_PRED_SANE 10.0
/* the continuation's noise (amplified like 5.8^Nodes) is cut off when it
   can exceed PRED_NOISE |y|: modes below CHOP times their noise go */
#define SYM_SPVI_PRED_NOISE 1e-6
#define SYM_SPVI_CHOP 10.0
/* a fixed step Newton cannot reach is approached from h / 2^HALVINGS */
#define SYM_SPVI_HALVINGS 6
/* by default a new matrix on every step (Vectorized finite differences)
   only while its LU is this small: an LU of 64 unknowns costs about two
   callbacks of Octave */
#define SYM_SPVI_EVERY_N 64
/* odeSPVI's fixed steps hold the error of the final move of f_p
   (solve.c) to this fraction of their solve's tolerance: an extrapolated
   matrix's move errs with a sign, step after step, and drifts the energy
   at the solve's own tolerance */
#define SYM_SPVI_MOVE_FIXED 1e-1
/* odeSPVI's fixed-point iteration (NonlinearSolver): at least this many
   iterations a solve; "auto" turns to Newton after a solve of more than
   SLOW */
#define SYM_SPVI_FP_MAXIT 30
/* and on fixed and reversible steps it goes to this fraction of their
   tolerance */
#define SYM_SPVI_FP_TOL 1e-2
#define SYM_SPVI_FP_SLOW 12
/* exact stages (staged_solve.c): the iteration on Newton's matrix stops
   when its change is below EPS ulps of the correction, or after ITERS
   (its contraction is O(h^2): two or three suffice) */
#define SYM_SPVI_EXACT_EPS 4.0
#define SYM_SPVI_EXACT_ITERS 8
/* by default Newton's systems go by stages (staged.c) above STAGES_N
   unknowns of the whole step system when the pair has at most
   STAGES_NODES nodes, and above STAGES_N_MANY whatever its nodes (many
   nodes at a long step: the whole system's Newton converges where the
   staged one, with one J for all nodes, fails) */
#define SYM_SPVI_STAGES_N 64
#define SYM_SPVI_STAGES_NODES 16
#define SYM_SPVI_STAGES_N_MANY 600
/* the stage reduction needs the same S from q's and p's equations: to
   this relative round-off */
#define SYM_SPVI_STAGE_SAME 1e-10
/* a sparse LU is made again in the pivot order of the last full one (no
   allocation, no search) while the ratio of its pivots stays above this
   fraction of that one's; else a full factorization */
#define SYM_KLU_REFACTOR 1e-3
/* steps of the same size, up to the round-off of fixed steps */
#define SYM_SAME_STEP 1e-10

/* the stack of an ensemble's member: the deepest a run goes (the
   stepper, LAPACK, the driver) is far below this; only the pages
   touched become resident */
#define SYM_ENS_STACK ((size_t) 256 << 10)
/* and up to this much more, by which the members' stack tops are
   staggered: blocks of one size start at the same offset of a page, and
   tops that lie a multiple of a page apart share their cache sets */
#define SYM_ENS_SKEW ((size_t) 60 * 320)
/* the members of an ensemble that run at once (without an OutputFcn,
   which needs them all): enough for batches where a call of FCN costs
   little per state, few enough that their steppers and stacks (some
   tens of KB each) stay in the cache and far below the output of a long
   run (bench/NOTES.md) */
#define SYM_ENS_LIVE 256

#endif
