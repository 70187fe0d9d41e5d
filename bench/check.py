"""``bodycheck bench --check``: the speed targets as ratios measured in one short run,
failing with the figure and the target (issue 30, item 5).

Each target is a ratio of two wall times measured here, in the same process, one after
the other: scipy's over ours at equal or better error.  Both sides are timed as the best
of ``repeats`` runs (the minimum: on a shared machine the noise only ever adds time), after
one untimed run of each kernel (numba's compilation or cache load is not the method's
cost).  The problems are the work-precision study's at its quick sizes
(:func:`bench.workprecision.reference_problems`):

- **free top** (issue 15): scipy's DOP853 at :data:`SCIPY_RTOL` against our fastest
  run that reaches its error; target :data:`~bench.workprecision.settings.STEPPER_GOAL`
  (10).
- **heavy top, pendulum, impact** (issue 30): scipy's best — the faster of LSODA and
  DOP853 at :data:`SCIPY_RTOL`, the two that are scipy's fastest at every decade of the
  full study's tables (``docs/bench/workprecision.md``) — against our fastest run
  (compiled right-hand side) that reaches its error; target 1.
- **batch** (issue 15): :data:`CHECK_BODIES` free bodies in one compiled DOP853 run
  against scipy body by body (:func:`bench.workprecision.sweeps.batched_vs_scipy`);
  target :data:`~bench.workprecision.settings.BATCH_GOAL` (50).
- **scenes** (issue 30, item 1): each smooth scenario of the conformance battery
  (:data:`SMOOTH_SCENARIOS`), MuJoCo's RK4 (tuned contact) against the scene engine at
  equal or better battery error: the scene engine integrating (DOP853, compiled) at the
  first of :data:`SCENE_RTOLS` that reaches MuJoCo's error, or else with its exact flow
  (``method = "auto"``, what a scene file runs by default); each side's wall time the
  least of ``repeats`` (:func:`mechanics.conformance.run_battery`); target 1.  Skipped,
  saying so, where MuJoCo is not installed.

Margins, measured on a 2-core machine with both cores busy (a mutation run and the full
study), five runs of the whole check: the same ratio varied by up to 2.2× from run to run,
and the lowest of each was free top 96 (9.6× its target), heavy top 16, pendulum 22 (12
in an earlier set of five), impact 4.4, batch 98 (2.0×).  So a check fails on a regression
of the kind it guards (a kernel falling back to Python is 50–100× slower), not on noise.
The full study (``bodycheck bench``) measures the same targets at full size; this is its
guard in CI (``make bench-check``).
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from .workprecision.problems import Problem, reference_problems
from .workprecision.settings import BATCH_GOAL, STEPPER_GOAL
from .workprecision.study import bench_repeats
from .workprecision.sweeps import _Progress, batched_vs_scipy, warm_compiled

#: scipy's tolerance in every check: mid-range of the decades, where both sides run
#: well clear of their start-up cost at the quick sizes
SCIPY_RTOL = 1e-9
#: scipy's methods that count for "scipy's best" (the faster of them)
SCIPY_BEST = ("scipy-LSODA", "scipy-DOP853")
#: our tolerances, tried from the loosest: the fastest that reaches scipy's error counts
OUR_RTOLS = (1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13)
#: the batch's size: the study's quick 200 bodies measured 78–162 (five runs under load),
#: too near the target 50 for a fixed per-call cost; 1000 amortise it (ours ~30 ms)
CHECK_BODIES = 1000
#: the battery's scenarios with no contact, where MuJoCo's RK4 is fourth order
SMOOTH_SCENARIOS = (
    "free_top_axis1",
    "free_top_axis3",
    "free_top_near_separatrix",
    "heavy_top",
    "parabola",
)
#: the scene engine's tolerances, tried from the default: 3e-14 is near the floor the
#: scene files allow (100 eps)
SCENE_RTOLS = (1e-12, 1e-13, 3e-14)


@dataclass(frozen=True)
class Check:
    """One target: the ratio measured, its target, and what was compared."""

    name: str
    measured: float | None
    target: float
    detail: str

    @property
    def passed(self) -> bool:
        return self.measured is not None and self.measured >= self.target

    def line(self) -> str:
        m = "not measured" if self.measured is None else f"{self.measured:.3g}"
        status = "met" if self.passed else "BELOW TARGET"
        return f"{status:>12}: {self.name}: {m} (target ≥ {self.target:g}) — {self.detail}"


def _best_of(fn: Callable[[], object], repeats: int) -> tuple[object, float]:
    """fn's result and its fastest wall time over ``repeats`` runs."""
    best, out = float("inf"), None
    for _ in range(max(repeats, 1)):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return out, best


def equal_error_ratio(
    problem: Problem,
    scipy_methods: Sequence[str],
    ours: Sequence[str],
    repeats: int,
) -> tuple[float | None, str]:
    """scipy's fastest run among ``scipy_methods`` at :data:`SCIPY_RTOL` over our fastest
    run (of the methods ``ours`` at :data:`OUR_RTOLS`) whose error is at most its error;
    None (with the reason) if none of ours reaches it."""
    theirs = []
    for m in scipy_methods:
        runner = problem.methods[m][2]
        run, t = _best_of(lambda r=runner: r(SCIPY_RTOL), repeats)
        theirs.append((t, run.error, m))
    t_s, e_s, m_s = min(theirs)
    best = None
    for m in ours:
        runner = problem.methods[m][2]
        for rtol in OUR_RTOLS:
            runner(rtol)  # untimed: a new function's conversion is not the method's cost
            run, t = _best_of(lambda r=runner, p=rtol: r(p), repeats)
            if run.error <= e_s:
                if best is None or t < best[0]:
                    best = (t, run.error, m, rtol)
                break
    if best is None:
        return None, f"{m_s} rtol {SCIPY_RTOL:g}: {e_s:.2e} in {t_s:.3g} s; none of ours reaches it"
    t_o, e_o, m_o, r_o = best
    return t_s / t_o, (
        f"{m_s} rtol {SCIPY_RTOL:g}: {e_s:.2e} in {t_s:.3g} s; "
        f"ours {m_o} rtol {r_o:g}: {e_o:.2e} in {t_o:.3g} s"
    )


def _battery_run(adapter, name: str, repeats: int) -> tuple[float, float] | None:
    """(wall time, error) of the adapter's finest run of the scenario, or None where it
    does not pass it."""
    from mechanics.conformance import run_battery

    r = run_battery(adapter, scenarios=[name], repeats=repeats)[name]
    if r.status != "pass" or not r.runs:
        return None
    return r.wall_time, r.runs[-1].error


def scene_checks(repeats: int, mujoco=None, engine=None) -> list[Check] | str:
    """The scenes' checks (see the module docstring), or why they are skipped.
    ``mujoco`` and ``engine`` (a factory ``engine(method, rtol)``) replace the adapters
    (the tests pass stand-ins)."""
    from mechanics.conformance.adapters.reference import SceneEngineAdapter

    if mujoco is None:
        try:
            from mechanics.conformance.adapters.mujoco import MuJoCoAdapter
        except ImportError as exc:  # pragma: no cover (MuJoCo is in the lock)
            return f"MuJoCo is not installed ({exc})"
        mujoco = MuJoCoAdapter("RK4", "tuned")
    if engine is None:

        def engine(method, rtol):
            return SceneEngineAdapter(method, rtol=rtol, atol=rtol)

    checks = []
    for name in SMOOTH_SCENARIOS:
        theirs = _battery_run(mujoco, name, repeats)
        if theirs is None:
            checks.append(Check(f"{name}, MuJoCo RK4 / scene engine", None, 1.0, "MuJoCo fails it"))
            continue
        t_m, e_m = theirs
        tried = [("integrate", r) for r in SCENE_RTOLS] + [("auto", None)]
        ours = None
        for method, rtol in tried:
            got = _battery_run(engine(method, rtol), name, repeats)
            if got is not None and got[1] <= e_m:
                ours = (method, rtol, *got)
                break
        if ours is None:
            detail = f"MuJoCo {e_m:.2e} in {t_m:.3g} s; the scene engine never reaches it"
            checks.append(Check(f"{name}, MuJoCo RK4 / scene engine", None, 1.0, detail))
            continue
        method, rtol, t_o, e_o = ours
        how = method if rtol is None else f"{method} rtol {rtol:g}"
        detail = f"MuJoCo {e_m:.2e} in {t_m:.3g} s; ours ({how}) {e_o:.2e} in {t_o:.3g} s"
        checks.append(Check(f"{name}, MuJoCo RK4 / scene engine", t_m / t_o, 1.0, detail))
    return checks


def run_checks(
    problems: Sequence[Problem] | None = None,
    *,
    repeats: int = 3,
    batch: bool = True,
    scenes: bool = True,
    out: Callable[[str], None] = print,
) -> list[Check]:
    """Every check of the module docstring, measured now (``problems`` replaces the
    study's quick problems: the tests pass broken ones)."""
    if problems is None:
        warm_compiled()
        problems = reference_problems(quick=True)
    checks = []
    for p in problems:
        ours = [m for m in p.methods if m.startswith("dop853")]
        if p.name == "free_top":
            ratio, detail = equal_error_ratio(p, ("scipy-DOP853",), ours, repeats)
            checks.append(Check("free top, scipy DOP853 / ours", ratio, STEPPER_GOAL, detail))
        else:
            ratio, detail = equal_error_ratio(p, SCIPY_BEST, ours, repeats)
            checks.append(Check(f"{p.name}, scipy's best / ours", ratio, 1.0, detail))
    if batch:
        b = batched_vs_scipy(True, repeats, _Progress(2, False), bodies=CHECK_BODIES)
        checks.append(
            Check(
                f"batch of {b['bodies']} free bodies, scipy body by body / ours",
                b["ratio"],
                BATCH_GOAL,
                f"ours {b['ours_s']:.3g} s, scipy {b['scipy_s']:.3g} s "
                f"({b['scipy_bodies_run']} bodies run, scaled)",
            )
        )
    if scenes:
        got = scene_checks(repeats)
        if isinstance(got, str):
            out(f"     skipped: the scenes against MuJoCo — {got}")
        else:
            checks += got
    return checks


def main(argv: Sequence[str] | None = None, out: Callable[[str], None] = print) -> int:
    """``bodycheck bench --check [--repeats N]``: 0 when every target is met, 1 (with
    each figure below its target named) when one is not."""
    ap = argparse.ArgumentParser(prog="bodycheck bench --check")
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args(argv)
    try:
        bench_repeats(False, args.repeats)
    except ValueError as exc:
        raise SystemExit(f"bodycheck bench --check: {exc}") from None
    t0 = time.perf_counter()
    checks = run_checks(repeats=args.repeats, out=out)
    for c in checks:
        out(c.line())
    below = [c for c in checks if not c.passed]
    out(
        f"bench --check: {len(checks) - len(below)} of {len(checks)} targets met in "
        f"{time.perf_counter() - t0:.1f} s (best of {args.repeats})"
    )
    for c in below:
        m = "not measured" if c.measured is None else f"{c.measured:.3g}"
        out(f"FAILED: {c.name} is {m}, below its target {c.target:g}")
    return 1 if below else 0
