"""The models behind the scenes: each exact flow agrees with integration of the same
listed effects, and the paths without an exact flow integrate."""

from __future__ import annotations

import dataclasses
import functools
import math

import numpy as np
import pytest

from mechanics._floats import EPS
from mechanics.scenes import SceneError, run_scene

from .builders import ball, body, box, cylinder, scene

#: an exact flow evaluated at one time: a few dozen float operations on O(1) values
EXACT_ATOL = 64 * EPS
#: an event located on a DOP853 run at rtol 1e-12 (the scenes' default) against the
#: closed form: the integration error, ~1e-11 relative, with a factor of 100 to spare
EVENT_RTOL = 2**22 * EPS


_scene = functools.partial(scene, name="m", duration=3.0, samples=301)


def _both(scene):
    a = run_scene(scene)
    b = run_scene(dataclasses.replace(scene, method="integrate"))
    assert a.method.startswith("exact"), a.method
    assert b.method.startswith("integrated")
    assert a.passed
    assert b.passed
    for k, v in a.trajectory.series.items():
        scale = max(float(np.max(np.abs(v))), a.trajectory.scales.get(k, 0), 1e-12)
        assert np.max(np.abs(v - b.trajectory.series[k])) <= 1e-8 * scale + 1e-12, k
    return a, b


def test_torsion_pendulum_is_harmonic_with_period_2pi_sqrt_J_over_tau() -> None:
    disc = body("d", "disc", {"angle": 0.3, "angular_velocity": 0.4}, mass=2.0, radius=0.5)
    sc = _scene(
        [disc],
        [{"type": "fixed_axis", "body": "d"}, {"type": "torsion", "body": "d", "stiffness": 0.25}],
        duration=2 * math.pi,
    )
    a, _ = _both(sc)
    # J = ½ m R² = 0.25, τ0 = 0.25: ω = 1, so after 2π the state returns
    phi = a.trajectory.series["phi"]
    assert phi[-1] == pytest.approx(phi[0], abs=EXACT_ATOL)
    assert {c.name for c in a.conserved} == {"E"}


def test_torque_free_top_about_a_fixed_point_conserves_L_in_space() -> None:
    top = box("t", a=0.3, b=0.2, c=0.1, theta=0.7, psi=0.1, phi=0.2, theta_dot=0.5,
              psi_dot=1.0, phi_dot=3.0)  # fmt: skip
    sc = _scene([top], [{"type": "fixed_point", "body": "t", "distance": 0.05}])
    a, _ = _both(sc)
    assert {"L_x", "L_y", "L_z", "E"} <= {c.name for c in a.conserved}


def test_asymmetric_heavy_top_has_no_exact_flow_and_integrates() -> None:
    top = box("t", a=0.3, b=0.2, c=0.1, theta=0.7, phi_dot=30.0)
    eff = [{"type": "gravity", "g": 9.81}, {"type": "fixed_point", "body": "t", "distance": 0.1}]
    r = run_scene(_scene([top], eff))
    assert r.method.startswith("integrated")
    assert r.passed
    assert {"E", "L_z"} <= {c.name for c in r.conserved}
    assert "L_3" not in {c.name for c in r.conserved}, "L3 is conserved only for J1 = J2"
    with pytest.raises(SceneError, match="no exact flow"):
        run_scene(_scene([top], eff, method="exact"))


def test_track_with_an_initial_speed_integrates_and_conserves_energy() -> None:
    cyl = cylinder("c", height=0.1, angle=0.5, angular_velocity=1.0)
    eff = [
        {"type": "gravity", "g": 9.81},
        {"type": "rolling", "body": "c", "surface": "track", "track_radius": 0.6},
    ]
    r = run_scene(_scene([cyl], eff))
    assert r.method.startswith("integrated")
    assert r.passed


def test_large_amplitude_track_motion_exact_vs_integrated() -> None:
    cyl = ball("c", shape="hollow_sphere", angle=2.5)
    eff = [
        {"type": "gravity", "g": 9.81},
        {"type": "rolling", "body": "c", "surface": "track", "track_radius": 0.6},
    ]
    _both(_scene([cyl], eff))


@pytest.mark.parametrize("speed", [0.0, -1.5])
def test_rolling_down_an_incline_exact_vs_integrated(speed) -> None:
    disc = body("d", "disc", {"distance": 0.5, "speed": speed}, mass=1.0, radius=0.2)
    eff = [
        {"type": "gravity", "g": 9.81},
        {"type": "rolling", "body": "d", "surface": "incline", "angle": 0.3},
    ]
    a, _ = _both(_scene([disc], eff))
    # a disc: J = m r²/2, so a = g sin α / (1 + 1/2) (3.80)
    v = a.trajectory.series["v"]
    assert v[-1] - v[0] == pytest.approx(9.81 * math.sin(0.3) / 1.5 * 3.0, rel=EXACT_ATOL)


@pytest.mark.parametrize(
    ("alpha", "mu", "spin", "rolls"),
    [
        (0.0, 0.3, -40.0, True),  # backspin: slides, then rolls
        (0.2, 0.5, 0.0, True),  # from rest on a gentle incline: rolls at once
        (0.6, 0.05, 0.0, False),  # steep and slippery: keeps sliding
    ],
)
def test_sliding_on_a_plane_exact_vs_integrated(alpha, mu, spin, rolls) -> None:
    rolled = ball("b", speed=2.0 if spin else 0.0, spin=spin)
    eff = [
        {"type": "gravity", "g": 9.81},
        {"type": "coulomb_friction", "body": "b", "mu": mu, "angle": alpha},
    ]
    a, _ = _both(_scene([rolled], eff, duration=2.0))
    slip = a.trajectory.series["slip"]
    assert (abs(slip[-1]) < 1e-12) == rolls
    if alpha == 0:
        assert "L_contact" in {c.name for c in a.conserved}


def test_a_ball_thrown_up_a_slippery_incline_slips_on_the_other_way() -> None:
    """Up a steep slope with μ too small to roll (J D/(J + m r²) > μ N): the slip
    vanishes once and the ball slips on downward (a ``slip_zero`` event, no rolling)."""
    thrown = ball("b", speed=-2.0)
    eff = [
        {"type": "gravity", "g": 9.81},
        {"type": "coulomb_friction", "body": "b", "mu": 0.05, "angle": 0.6},
    ]
    a, b = _both(_scene([thrown], eff, duration=2.0))
    (ea,), (eb,) = a.trajectory.events, b.trajectory.events
    assert ea.kind == eb.kind == "slip_zero"
    assert eb.t == pytest.approx(ea.t, rel=EVENT_RTOL)
    assert a.trajectory.series["slip"][-1] > 0


def test_tank_integrated_reaches_empty_as_an_event() -> None:
    tank = body("t", "tank", {"level": 1.0}, area=1.0)
    eff = [{"type": "gravity", "g": 9.81}, {"type": "tank_outflow", "body": "t", "hole_area": 0.05}]
    a, b = _both(_scene([tank], eff, duration=20.0))
    (ea,), (eb,) = a.trajectory.events, b.trajectory.events
    assert ea.kind == eb.kind == "empty"
    assert eb.t == pytest.approx(ea.t, rel=EVENT_RTOL)
    assert a.trajectory.series["h"][-1] == 0.0


def test_spinning_ball_bounces_with_its_spin_unchanged() -> None:
    spun = ball("b", [0.0, 0.0, 1.0], [1.0, 0.0, 0.0], omega=[0.0, 0.0, 5.0])
    eff = [{"type": "gravity", "g": 9.81}, {"type": "impact", "body": "b", "restitution": 1.0}]
    a, _ = _both(_scene([spun], eff, duration=2.0))
    assert len(a.trajectory.events) >= 2
    assert np.all(a.trajectory.series["omega3"] == 5.0)
    assert a.conserved[[c.name for c in a.conserved].index("E")].drift < 1e-14, "e = 1"
