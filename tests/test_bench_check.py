"""``bodycheck bench --check`` (issue 30, item 5): the speed targets as ratios measured in
one run, failing with the figure and the target.

The ratios themselves are not asserted here (speed targets belong to ``make bench`` and
to ``make bench-check``, the CI step): these tests hold the check's logic — a method
slower than scipy, or one that never reaches scipy's error, fails and is named — with a
clock that advances by a fixed cost per run, and run the real check once for its shape.
"""

from __future__ import annotations

import math

import pytest

import bench.check as check
from bench.workprecision.problems import Problem, Run
from identities.cli.main import main as cli


class _Clock:
    """A stand-in for time.perf_counter that each fake run advances by its cost."""

    def __init__(self):
        self.now = 0.0

    def __call__(self):
        return self.now


def _problem(clock: _Clock, name: str, ours_cost: float, ours_error: float) -> Problem:
    """scipy's LSODA (cost 1, error 1e-6) and DOP853 (cost 2, error 1e-8) at any rtol; ours
    (``dop853``) at a cost and an error that do not depend on its rtol."""

    def runner(cost, error):
        def run(p):
            clock.now += cost
            return Run(error, 1, 1, 0)

        return run

    methods = {
        "scipy-LSODA": ("rtol", [1e-6], runner(1.0, 1e-6)),
        "scipy-DOP853": ("rtol", [1e-6], runner(2.0, 1e-8)),
        "dop853": ("rtol", [1e-6], runner(ours_cost, ours_error)),
    }
    return Problem(name, name, "", 1.0, "", methods)


@pytest.fixture
def clock(monkeypatch):
    c = _Clock()
    monkeypatch.setattr(check.time, "perf_counter", c)
    return c


def test_a_faster_method_meets_its_target_and_a_slower_one_does_not(clock):
    fast = _problem(clock, "fast", 0.25, 1e-7)  # reaches LSODA's 1e-6, 4× faster
    slow = _problem(clock, "slow", 4.0, 1e-7)
    got = check.run_checks([fast, slow], repeats=2, batch=False, scenes=False)
    assert [c.measured for c in got] == [4.0, 0.25]
    assert [c.passed for c in got] == [True, False]
    assert "scipy-LSODA rtol 1e-09: 1.00e-06 in 1 s" in got[0].detail


def test_ours_must_reach_scipys_error_to_count(clock):
    """Ours at 1e-5 never reaches LSODA's 1e-6 (scipy's fastest): not measured, failed."""
    got = check.run_checks(
        [_problem(clock, "coarse", 0.01, 1e-5)], repeats=1, batch=False, scenes=False
    )
    assert got[0].measured is None
    assert not got[0].passed
    assert "none of ours reaches it" in got[0].detail


def test_the_free_top_is_held_against_scipy_dop853_and_the_stepper_goal(clock):
    top = _problem(clock, "free_top", 0.5, 1e-9)
    (c,) = check.run_checks([top], repeats=1, batch=False, scenes=False)
    assert c.measured == 4.0  # DOP853's cost 2 over ours 0.5, not LSODA's 1
    assert c.target == check.STEPPER_GOAL
    assert not c.passed


def test_the_command_fails_naming_each_figure_below_its_target(monkeypatch):
    got = [
        check.Check("one", 3.0, 1.0, "d1"),
        check.Check("two", 0.5, 1.0, "d2"),
        check.Check("three", None, 10.0, "d3"),
    ]
    monkeypatch.setattr(check, "run_checks", lambda **kw: got)
    lines: list[str] = []
    assert check.main(["--repeats", "1"], out=lines.append) == 1
    assert "FAILED: two is 0.5, below its target 1" in lines
    assert "FAILED: three is not measured, below its target 10" in lines
    assert any(line.startswith("bench --check: 1 of 3 targets met") for line in lines)
    monkeypatch.setattr(check, "run_checks", lambda **kw: got[:1])
    assert check.main(["--repeats", "1"], out=lines.append) == 0


def test_bad_options_are_usage_errors(capsys):
    assert cli(["bench", "--check", "--repeats", "0"]) == 2
    assert "--repeats must be at least 1; got 0" in capsys.readouterr().err
    assert cli(["bench", "--check", "--quick"]) == 2
    assert "leave out --quick" in capsys.readouterr().err


def test_the_real_check_measures_every_target():
    """One real run (repeats 1): every target measured and finite, whatever it shows."""
    got = check.run_checks(repeats=1)
    names = [c.name.split(",")[0] for c in got]
    assert names == [
        "free top",
        "heavy_top",
        "pendulum",
        "impact",
        "batch of 1000 free bodies",
        *check.SMOOTH_SCENARIOS,
    ]
    for c in got:
        assert c.measured is not None, c
        assert math.isfinite(c.measured), c
        assert c.measured > 0, c


# ---------------------------------------------------------------- scenes against MuJoCo


def _scene_runs(monkeypatch, table):
    """Stand-in battery runs: ``table[(adapter, scenario)]`` is (wall time, error) or None
    (not passed); the adapters are names ("mujoco", or the engine's (method, rtol))."""
    seen = []

    def fake(adapter, name, repeats):
        seen.append((adapter, name))
        return table.get((adapter, name))

    monkeypatch.setattr(check, "_battery_run", fake)
    monkeypatch.setattr(check, "SMOOTH_SCENARIOS", ("s",))
    return seen


def test_a_scene_counts_at_the_first_tolerance_that_reaches_mujocos_error(monkeypatch):
    seen = _scene_runs(
        monkeypatch,
        {
            ("mujoco", "s"): (0.04, 1e-11),
            (("integrate", 1e-12), "s"): (0.005, 2e-11),  # faster, but not as accurate
            (("integrate", 1e-13), "s"): (0.01, 5e-13),
        },
    )
    (c,) = check.scene_checks(3, mujoco="mujoco", engine=lambda m, r: (m, r))
    assert c.measured == 4.0
    assert c.passed
    assert "ours (integrate rtol 1e-13) 5.00e-13 in 0.01 s" in c.detail
    assert seen == [("mujoco", "s"), (("integrate", 1e-12), "s"), (("integrate", 1e-13), "s")]


def test_a_scene_the_integration_cannot_match_counts_with_its_exact_flow(monkeypatch):
    _scene_runs(
        monkeypatch,
        {
            ("mujoco", "s"): (0.02, 1e-14),
            (("integrate", 1e-12), "s"): (0.005, 1e-12),
            (("integrate", 1e-13), "s"): (0.005, 1e-13),
            (("integrate", 3e-14), "s"): (0.005, 4e-14),
            (("auto", None), "s"): (0.04, 1e-16),  # exact, but slower than MuJoCo
        },
    )
    (c,) = check.scene_checks(3, mujoco="mujoco", engine=lambda m, r: (m, r))
    assert c.measured == 0.5
    assert not c.passed
    assert "ours (auto) 1.00e-16 in 0.04 s" in c.detail


def test_a_scene_never_matched_or_failed_by_mujoco_is_not_measured(monkeypatch):
    _scene_runs(monkeypatch, {("mujoco", "s"): (0.02, 1e-16)})
    (c,) = check.scene_checks(3, mujoco="mujoco", engine=lambda m, r: (m, r))
    assert c.measured is None
    assert "the scene engine never reaches it" in c.detail
    _scene_runs(monkeypatch, {})
    (c,) = check.scene_checks(3, mujoco="mujoco", engine=lambda m, r: (m, r))
    assert c.measured is None
    assert c.detail == "MuJoCo fails it"


def test_without_mujoco_the_scenes_are_skipped_saying_so(monkeypatch):
    monkeypatch.setattr(check, "scene_checks", lambda repeats: "MuJoCo is not installed (x)")
    lines: list[str] = []
    got = check.run_checks([], repeats=1, batch=False, out=lines.append)
    assert got == []
    assert lines == ["     skipped: the scenes against MuJoCo — MuJoCo is not installed (x)"]
