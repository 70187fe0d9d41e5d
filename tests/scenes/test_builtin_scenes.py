"""Every built-in scene reproduces the book's closed form within its stated tolerance,
by the exact flow and by integration, and conserves what its effects imply (the
comparisons are the book layer's, :mod:`identities.book.scenes.compare`)."""

from __future__ import annotations

import dataclasses
import itertools

import numpy as np
import pytest

from identities.book.scenes.compare import INTEGRATED_RTOL, run_book_scene
from mechanics._floats import EPS
from mechanics.scenes import builtin_scenes, load_scene
from mechanics.scenes import effects as fx

#: the speed at the next impact after a free flight, by the exact flow or by DOP853 at
#: rtol 1e-12 with event location: the integration error, ~1e-12 relative
FLIGHT_RTOL = 2**14 * EPS
#: one impact in closed form ((6.36)-(6.41)): a handful of float operations
IMPACT_RTOL = 64 * EPS

NAMES = list(builtin_scenes())
#: what each built-in scene must compare (the issue's list) and conserve
EXPECTED = {
    "bouncing_ball": ({"E6.1"}, {"E"}),
    "rolling_incline": ({"E3.6 (3.80)"}, {"E"}),
    "physical_pendulum": ({"E4.4 (4.59)"}, {"E"}),
    "physical_pendulum_small": ({"E4.3 (4.53)"}, {"E"}),
    "cylinder_in_track": ({"E4.5 (4.65)"}, {"E"}),
    "heavy_top": ({"5.2: root u1 of f(u)", "5.2: root u2 of f(u)"}, {"E", "L_z", "L_3"}),
    "free_top_flip": ({"5.3.3: 4K(m)/λ (derived)"}, {"E"}),
    "rocket": ({"E7.2 (7.30)"}, set()),
    "carousel": ({"E7.3 (7.40)"}, {"L_axis + r q v t"}),
    "tank_draining": ({"E8.1 (8.37)"}, {"volume_total"}),
    "sliding_ball": ({"t* = 2v0/(7μg)", "5 v0/7"}, {"E", "L_contact"}),
    "rod_struck": ({"E6.2 (6.29): 2ℓ/3"}, {"p_x", "p_y", "L_z", "E"}),
    "newtons_cradle": ({"(6.38): the first ball's velocity"}, {"p_x", "E"}),
    "flip_after_push": ({"5.3.3: 4K(m)/λ (derived)"}, {"E", "L_x", "L_y", "L_z"}),
    "rocket_drag": ({"7.24 with drag (mpmath Taylor)"}, set()),
    "box_drop": ({"(6.36)", "(6.41): ½ μ (1 − e²) v_n²"}, {"E", "p_x", "p_y", "L_z"}),
    "box_drop_friction": ({"(6.36)", "(6.21)", "Coulomb slip: μ"}, {"E"}),
    "top_hits_floor": ({"5.2: the heavy top's θ(t), elliptic functions", "(6.36)"}, {"E"}),
}
#: scenes whose effects have no exact flow (rigid-body contacts at corners, loads that
#: turn a body, drag): ``auto`` integrates them too
NO_EXACT_FLOW = {
    "rod_struck",
    "flip_after_push",
    "rocket_drag",
    "box_drop",
    "box_drop_friction",
    "top_hits_floor",
}


def _run(name: str, method: str):
    scene = dataclasses.replace(load_scene(builtin_scenes()[name]), method=method)
    return run_book_scene(scene)


def test_the_issue_s_built_in_scenes_are_all_there() -> None:
    assert set(NAMES) == set(EXPECTED)


class _Runs(dict):
    """(name, method) → the scene's result, run on first use: a worker runs only the
    scenes of the tests it was given (the module's tests share each run)."""

    def __missing__(self, key):
        self[key] = _run(*key)
        return self[key]


@pytest.fixture(scope="module")
def results():
    return _Runs()


@pytest.mark.parametrize("name", NAMES)
@pytest.mark.parametrize("method", ["auto", "integrate"])
def test_scene_matches_the_book_and_conserves_what_its_effects_imply(results, name, method) -> None:
    r = results[name, method]
    books, conserved = EXPECTED[name]
    assert r.comparisons, "every built-in scene compares with the book"
    for c in r.comparisons:
        assert c.ok, f"{c.name}: {c.relative_difference:.3e} > {c.tolerance:.1e}"
        assert c.tolerance <= 1e-3, "a stated, tight tolerance"
    assert books <= {c.book for c in r.comparisons}
    assert conserved <= {c.name for c in r.conserved}
    for c in r.conserved:
        assert c.ok, f"{c.name} drifts by {c.drift:.2e}"
    assert r.passed


@pytest.mark.parametrize("name", sorted(NO_EXACT_FLOW))
def test_auto_integrates_where_no_exact_flow_exists(results, name) -> None:
    assert results[name, "auto"].method.startswith("integrated")


@pytest.mark.parametrize("name", sorted(set(NAMES) - NO_EXACT_FLOW))
def test_auto_uses_the_exact_flow_and_agrees_with_integration(results, name) -> None:
    exact, integ = results[name, "auto"], results[name, "integrate"]
    assert exact.method.startswith("exact"), exact.method
    assert integ.method.startswith("integrated"), integ.method
    assert [e.kind for e in exact.trajectory.events] == [e.kind for e in integ.trajectory.events]
    for a, b in zip(exact.trajectory.events, integ.trajectory.events, strict=True):
        assert abs(a.t - b.t) <= 1e-9 * max(1.0, a.t)
    for key, v in exact.trajectory.series.items():
        w = integ.trajectory.series[key]
        scales = exact.trajectory.scales
        scale = max(float(np.max(np.abs(v))), scales.get(key, 0.0), 1e-300)
        assert np.max(np.abs(v - w)) <= 64 * INTEGRATED_RTOL * scale, key


def test_bouncing_ball_never_penetrates_and_loses_energy_by_e_squared(results) -> None:
    for method in ("auto", "integrate"):
        r = results["bouncing_ball", method]
        z = r.trajectory.series["z"]
        assert z.min() >= 0.1 - FLIGHT_RTOL * 10.0, "the ball's surface never goes below the floor"
        impacts = [e for e in r.trajectory.events if e.kind == "impact"]
        assert len(impacts) == 5
        e = 5 / 6
        for a, b in itertools.pairwise(impacts):
            assert b.detail["normal_speed_before"] == pytest.approx(
                a.detail["normal_speed_after"], rel=FLIGHT_RTOL
            ), "free flight between impacts: the speed returns"
            assert b.detail["normal_speed_after"] == pytest.approx(
                e * b.detail["normal_speed_before"], rel=IMPACT_RTOL
            )
            assert a.detail["energy_loss"] == pytest.approx(
                0.5 * 0.5 * (1 - e * e) * a.detail["normal_speed_before"] ** 2, rel=IMPACT_RTOL
            )


def test_sliding_ball_switches_once_and_then_rolls(results) -> None:
    r = results["sliding_ball", "auto"]
    (ev,) = r.trajectory.events
    slip = r.trajectory.series["slip"]
    t = r.trajectory.t
    assert np.all(slip[t < ev.t] > 0)
    assert np.all(np.abs(slip[t > ev.t]) <= 1e-14)


def test_a_wrong_model_fails_the_comparison(monkeypatch) -> None:
    """Negative control: the comparisons can fail.  A cylinder that rolls as if its
    moment of inertia were m r² (a ring) does not reach √(4gh/3)."""

    def ring_like(self, m, J_G, r):
        return 2.0 * m

    monkeypatch.setattr(fx.Rolling, "effective_mass", ring_like)
    r = _run("rolling_incline", "auto")
    assert not r.passed
    assert not any(c.ok for c in r.comparisons)


def test_a_wrong_restitution_fails_example_6_1(tmp_path) -> None:
    text = (
        builtin_scenes()["bouncing_ball"]
        .read_text()
        .replace("restitution = 0.8333333333333334", "restitution = 0.8")
    )
    p = tmp_path / "ball.toml"
    p.write_text(text)
    r = run_book_scene(load_scene(p))
    bad = {c.name for c in r.comparisons if not c.ok}
    assert "speed after the first impact" in bad
    assert "apex ratio" not in " ".join(bad), "the ratio e² holds for any e"


def test_a_tank_with_the_smallest_normal_hole_reports_a_finite_volume_out():
    """Found by the whole-scene fuzz: with a hole of 2.2e-308 m² the drain time is
    ~3e307 s, and the exact volume out a k c (T t − t²/2) overflowed in T t though the
    volume is ~1e-307 m³; written a k t (√h0 − c t/2) it stays finite."""
    import math as _m

    from mechanics.scenes import parse_scene
    from mechanics.scenes.simulate import simulate

    scene = parse_scene(
        {
            "scene": {"name": "tiny_hole", "duration": 30.0, "samples": 2},
            "bodies": [{"name": "tank", "shape": "tank", "area": 1.0, "initial": {"level": 2.0}}],
            "effects": [
                {"type": "gravity", "g": 9.81},
                {"type": "tank_outflow", "body": "tank", "hole_area": 2.2250738585072014e-308},
            ],
        }
    )
    tr = simulate(scene)
    out = np.asarray(tr.series["volume_out"], dtype=float)
    total = np.asarray(tr.conserved["volume_total"], dtype=float)
    assert np.all(np.isfinite(out))
    assert np.all(np.isfinite(total))
    # the flow over 30 s: a √(2 g h0) t to first order, about 4.2e-306 m³
    assert 0 < out[-1] <= 2.2250738585072014e-308 * _m.sqrt(2 * 9.81 * 2.0) * 30.0
