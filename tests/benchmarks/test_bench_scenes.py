"""Cost of a step with 0, 1, 2 and 4 effects listed: only the listed effects are
assembled, so the cost of the right-hand side grows with the effects a scene calls for.

The benchmark times one evaluation of the engine's assembled right-hand side for a free
body (DOP853 takes 12 per step); ``extra_info`` records the number of effects.  Under
the default ``--benchmark-disable`` each test runs once as a correctness test (the
acceleration is checked against the sum of the listed forces); nothing asserts a time.
A scene with no effect runs its exact flow: no right-hand side is evaluated at all
(``test_a_scene_without_effects_costs_only_its_exact_flow``).
"""

from __future__ import annotations

import numpy as np
import pytest

from mechanics._floats import EPS
from mechanics.scenes import parse_scene
from mechanics.scenes.engine import Engine

M, G, K1, K2, Q, U = 2.0, 9.81, 8.0, 3.0, 0.01, 100.0
EFFECTS = [
    {"type": "gravity", "g": G},
    {"type": "spring", "body": "b", "anchor": [0.0, 0.0, 0.0], "stiffness": K1},
    {"type": "spring", "body": "b", "anchor": [1.0, 0.0, 0.0], "stiffness": K2},
    {"type": "thrust", "body": "b", "mass_flow": Q, "exhaust_speed": U, "fuel_mass": 1.0},
]


def _model(n: int, method: str = "integrate"):
    scene = parse_scene(
        {
            "scene": {"name": f"bench{n}", "duration": 1.0, "method": method},
            "bodies": [
                {"name": "b", "shape": "point", "mass": M, "initial": {"position": [0.3, 0.2, 0.1]}}
            ],
            "effects": EFFECTS[:n],
        },
        source=f"bench{n}.toml",
    )
    return Engine(scene)


def _expected_acceleration(n: int, r: np.ndarray) -> np.ndarray:
    F = np.zeros(3)
    if n >= 1:
        F += M * np.array([0.0, 0.0, -G])
    if n >= 2:
        F += -K1 * r
    if n >= 4:
        F += -K2 * (r - np.array([1.0, 0.0, 0.0])) + Q * U * np.array([0.0, 0.0, 1.0])
    return F / M


@pytest.mark.parametrize("n_effects", [0, 1, 2, 4])
def test_bench_step_cost_grows_with_the_listed_effects(benchmark, n_effects) -> None:
    model = _model(n_effects)
    assert len(model.effects) == n_effects
    y = model.y0
    out = benchmark(model.rhs, 0.0, y)
    # accelerations: sums of a few O(1) products
    np.testing.assert_allclose(
        out[3:], _expected_acceleration(n_effects, y[:3]), rtol=8 * EPS, atol=64 * EPS
    )
    traj = model.run()
    benchmark.extra_info["n_effects"] = n_effects
    benchmark.extra_info["samples"] = len(traj.t)


def test_a_scene_without_effects_costs_only_its_exact_flow(monkeypatch) -> None:
    model = _model(0, "auto")
    assert model.exact_flow() is not None

    def never(*a):
        raise AssertionError("the right-hand side ran for a scene with no effect")

    monkeypatch.setattr(model, "rhs", never)
    traj = model.run()
    assert traj.method.startswith("exact")
    assert len(traj.t) == model.scene.samples
