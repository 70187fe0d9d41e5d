"""The study's settings: targets, error levels, budgets, repeats and the peers' options.

Part of :mod:`bench.workprecision` (its docstring states the conventions).
"""

from __future__ import annotations

from mechanics._floats import EPS

SCHEMA = "bodycheck.workprecision/2"
#: The error of the headline comparison on the free top (issue 6).
TARGET_ERROR = 1e-10
#: The error levels of the per-decade comparison (issue 15): ours at least as fast as
#: scipy's best at each.
DECADES = tuple(10.0**-k for k in range(4, 13))
#: Issue 15's targets, as (goal, must) ratios of scipy's time to ours.
STEPPER_GOAL, STEPPER_MUST = 10.0, 3.0
EXACT_GOAL = 1e5
BATCH_GOAL = 50.0
#: The batch of free bodies against scipy body by body (full run, quick run): bodies,
#: bodies scipy runs (its time is scaled to the batch), tolerance, horizon (one
#: rotation at |ω| = 1).
BATCH_BODIES = {False: 10**4, True: 200}
BATCH_SCIPY_SAMPLE = {False: 20, True: 3}
BATCH_RTOL = 1e-9
BATCH_SEED = 20261125
#: The compiled-engine peer (issue 15): MuJoCo's run quoted in the issue.
MUJOCO_J = (1.0, 2.0, 3.0)
MUJOCO_W0 = (0.02, 1.0, 0.01)
MUJOCO_T = 20.0
MUJOCO_DT = 1e-3
MUJOCO_EXTRA = "pip install -e '.[mujoco]'"
#: Errors are plotted no lower than this (a few eps: the exact references' own accuracy).
ERROR_FLOOR = 4 * EPS
#: Runs longer than this are timed once (seconds).
LONG_RUN_S = 2.0
#: A method's sweep stops after a run longer than this (seconds): full, quick.
BUDGET_S = {False: 30.0, True: 0.6}
#: Rotations of the free top (full run, quick run).
FREE_TOP_ROTATIONS = {False: 1000, True: 20}
SCIPY_METHODS = ("RK45", "DOP853", "LSODA", "Radau")
#: Periodic problems end this fraction of a period past a whole number of periods,
#: so that a method that never moves (the initial state) is not exactly right there.
FINAL_PHASE = 0.3
SCIPY_STAGES = {"RK45": 6, "DOP853": 12}
