"""Many bodies: n = 10, 100 and 1000 elastic balls in a box of six planes, one ``impact``
group (issue 27, item 3), run by the exact free flight (closed-form contact times kept
in a calendar, :class:`mechanics.scenes.flows.Calendar`).

Each run is verified before it is timed: it passes its own self-checks (energy kept to
the exact flows' 2¹⁰ eps, momentum across every two-ball impact, the impact law at every
contact, no interpenetration of any pair at any sample) and has impacts of both kinds.
``extra_info`` records the impacts and the impacts per second of wall time.  The peer
timed in the same run is the same scene with every pair's next contact computed again
at every event (what the calendar saves; n = 100), since scipy has no event-driven
hard-sphere solver to race.  Under the default ``--benchmark-disable`` the n = 1000 case
is skipped (its scene alone holds 500 000 pairs: a minute to build and check); ``make
bench`` runs it.
"""

from __future__ import annotations

import dataclasses
import math
import time

import numpy as np
import pytest

from mechanics.scenes import flows as flows_module
from mechanics.scenes import parse_scene, run_scene
from tests.scenes._effects import WALLS

#: (balls, radius, duration): about a few hundred impacts each
SIZES = {10: (0.05, 2.0), 100: (0.03, 0.4), 1000: (0.02, 0.02)}


def balls_in_a_box(n: int, *, seed: int = 2026):
    """n balls on a grid of the unit box (no overlap), Gaussian velocities (1 m/s)."""
    radius, duration = SIZES[n]
    rng = np.random.default_rng(seed)
    k = math.ceil(n ** (1 / 3))
    h = 1.0 / k
    cells = [(i, j, m) for i in range(k) for j in range(k) for m in range(k)][:n]
    bodies = []
    for c, cell in enumerate(cells):
        p = (np.array(cell) + 0.5) * h + rng.uniform(-1, 1, 3) * (h / 2 - radius) * 0.5
        bodies.append(
            {
                "name": f"b{c}",
                "shape": "solid_sphere",
                "mass": 1.0,
                "radius": radius,
                "initial": {"position": p.tolist(), "velocity": rng.normal(size=3).tolist()},
            }
        )
    group = [b["name"] for b in bodies]
    return parse_scene(
        {
            "scene": {"name": f"balls{n}", "duration": duration, "samples": 5, "method": "exact"},
            "bodies": bodies,
            "effects": [{"type": "impact", "group": group, "planes": WALLS, "restitution": 1.0}],
        },
        source=f"balls{n}.toml",
    )


def _verified(res) -> int:
    """The run's impacts, after checking it (see the module docstring)."""
    assert res.passed, res.summary()
    hits = [ev for ev in res.trajectory.events if ev.kind == "impact"]
    assert any("bodies" in ev.detail for ev in hits), "no two balls met"
    assert any("body" in ev.detail for ev in hits), "no ball met a wall"
    names = {c.name.split(" (")[0] for c in res.self_checks}
    assert {"impact law at every contact", "momentum across two-body impacts"} <= names
    assert any(c.name == "E" for c in res.conserved)
    return len(hits)


@pytest.mark.parametrize("n", sorted(SIZES))
def test_bench_balls_in_a_box(benchmark, request, n) -> None:
    if n == 1000 and benchmark.disabled:
        pytest.skip("500 000 pairs: run by make bench (--benchmark-enable) only")
    scene = balls_in_a_box(n)
    rounds = 1 if n == 1000 else 3  # (n ≤ 100: after a warm-up run, imports paid)
    t0 = time.perf_counter()
    res = benchmark.pedantic(
        run_scene, args=(scene,), rounds=rounds, iterations=1, warmup_rounds=int(n < 1000)
    )
    wall = time.perf_counter() - t0
    impacts = _verified(res)
    stats = getattr(benchmark, "stats", None)
    median = stats.stats.median if stats is not None else wall
    benchmark.extra_info.update(n=n, impacts=impacts, impacts_per_second=impacts / median)
    if benchmark.disabled:
        return
    # the run's fixed cost (compiling the pairs, the report) against its cost per impact:
    # the same balls over twice the time, the extra impacts over the extra wall time
    longer = dataclasses.replace(scene, duration=2 * scene.duration)
    t0 = time.perf_counter()
    res2 = run_scene(longer)
    wall2 = time.perf_counter() - t0
    extra = _verified(res2) - impacts
    assert extra > 0
    benchmark.extra_info.update(
        impacts_doubled=impacts + extra,
        marginal_impacts_per_second=extra / max(wall2 - median, 1e-9),
    )


def test_bench_the_calendar_against_a_full_search_at_every_event(benchmark, monkeypatch) -> None:
    """The peer: the same 100 balls with every pair's next contact computed again at every
    event (O(n²) per event instead of O(n)); the same impacts either way."""
    scene = balls_in_a_box(100)
    ref = run_scene(scene)
    monkeypatch.setattr(flows_module.Calendar, "pairs_of", lambda self, bodies: None)
    res = benchmark.pedantic(run_scene, args=(scene,), rounds=3, iterations=1, warmup_rounds=1)
    assert [ev.t for ev in res.trajectory.events] == [ev.t for ev in ref.trajectory.events]
    benchmark.extra_info.update(n=100, impacts=_verified(res))
