"""The engine adapters' conversions and small pieces, on hand-made states.

The book's attitude is the passive ^A R^O (rows: the body axes in space components) and
ω is in body components; each engine has its own quaternion order, frames and velocity
components.  These tests build an engine state from a known rotation and check that it
comes back, read what the engine itself computes from it (its matrices, its world
velocities), run one step or a few where the motion has a closed form (free fall,
uniform spin about a principal axis), and check the adapters' own functions (reasons,
restitution laws, step plans, scene dicts) against hand derivations.  No long runs.
"""

from __future__ import annotations

import dataclasses
import math
import os

import numpy as np
import pytest

from mechanics.conformance.adapters import _engines
from mechanics.conformance.adapters._engines import (
    MissingExtraError,
    body_rows,
    check_option,
    common_unsupported,
    quiet_stdout,
    require,
    step_counts,
    unit_interval,
)
from mechanics.conformance.adapters.reference import (
    ExactAdapter,
    SceneEngineAdapter,
    scene_from_scenario,
)
from mechanics.conformance.protocol import Body, Ground, Pivot, Scenario, Shape, Thrust
from mechanics.conformance.scenarios import SCENARIOS, reference
from mechanics.errors import (
    MechanicsValueError,
    NonPositiveParameterError,
    OutOfDomainError,
    RestitutionRangeError,
    UnknownOptionError,
)

EPS = float(np.finfo(float).eps)
#: a rotation through an engine's quaternion and back: a few roundings each way
ROUNDTRIP_ATOL = 2**4 * EPS
#: an engine's one step of a closed-form motion (free fall, spin): a few roundings of
#: O(1) numbers, and the engine's own quaternion normalisation
STEP_ATOL = 2**6 * EPS
G = 9.81


def _R3(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])


def _R1(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, s], [0.0, -s, c]])


def _rows(R):
    return tuple(tuple(float(x) for x in r) for r in R)


#: a general passive attitude, R3(0.5) R1(0.7) R3(0.3), and a rotation about z by 0.8
#: whose active quaternion is (cos 0.4, 0, 0, sin 0.4): body x at (cos 0.8, sin 0.8, 0)
R_GENERAL = _R3(0.5) @ _R1(0.7) @ _R3(0.3)
R_Z = _R3(0.8)
Q_Z_WXYZ = np.array([math.cos(0.4), 0.0, 0.0, math.sin(0.4)])


def _scenario(bodies, *, duration=0.25, dt=0.125, **kw) -> Scenario:
    n = round(duration / dt)
    return Scenario(
        "made_up",
        "a made-up scenario",
        "(none)",
        tuple(bodies),
        duration,
        tuple(k * dt for k in range(n + 1)),
        **kw,
    )


def _box(**kw):
    base = dict(name="box", mass=2.0, inertia=(1.0, 2.0, 2.5), shape=Shape("box", (0.5, 0.4, 0.3)))
    base.update(kw)
    return Body(**base)


def _ball(**kw):
    # a solid sphere: J = 2/5 m r² = 0.4 · 0.5 · 0.01
    base = dict(name="ball", mass=0.5, inertia=(0.002, 0.002, 0.002), shape=Shape("sphere", (0.1,)))
    base.update(kw)
    return Body(**base)


# --------------------------------------------------------------------------- _engines


def test_check_option_returns_an_allowed_value_and_names_a_wrong_one():
    assert check_option("RK4", ("RK4", "Euler"), "integrator") == "RK4"
    with pytest.raises(UnknownOptionError) as info:
        check_option("rk4", ("RK4", "Euler"), "MuJoCo integrator")
    assert str(info.value) == "MuJoCo integrator must be one of ('RK4', 'Euler'); got 'rk4'"


def test_step_counts_are_the_whole_steps_to_each_sample():
    s = _scenario([_box()], duration=0.25, dt=0.125)
    h, n = step_counts(s, 2.0**-5)
    assert h == 2.0**-5
    assert n.dtype == np.int64
    np.testing.assert_array_equal(n, [0, 4, 8])
    # no step given: the scenario's finest
    h, n = step_counts(dataclasses.replace(s, steps=(2.0**-4, 2.0**-6, 2.0**-5)), None)
    assert h == 2.0**-6
    np.testing.assert_array_equal(n, [0, 8, 16])


def test_step_counts_accept_a_sample_time_within_rounding_of_a_whole_step():
    # 0.1 is not a binary fraction: 3 steps of 0.1 make 0.30000000000000004, not 0.3
    s = _scenario([_box()], duration=0.3, dt=0.1)
    _, n = step_counts(s, 0.1)
    np.testing.assert_array_equal(n, [0, 1, 2, 3])


@pytest.mark.parametrize("step", [None, 0.0, -0.01, math.nan, math.inf])
def test_step_counts_refuse_a_step_that_is_not_positive_and_finite(step):
    s = _scenario([_box()])
    with pytest.raises(NonPositiveParameterError) as info:
        step_counts(s, step)
    assert str(info.value) == (
        f"scenario 'made_up': a fixed-step engine needs a step > 0; got {step!r}"
    )


def test_step_counts_name_the_first_sample_off_the_step_grid():
    s = _scenario([_box()], duration=0.25, dt=0.125)
    with pytest.raises(MechanicsValueError) as info:
        step_counts(s, 0.1)
    assert str(info.value) == (
        "scenario 'made_up': sample time 0.125 is not a whole number of steps 0.1"
    )
    # the first sample off is named, not the last: 0.25 fits 0.0625, 0.3 does not
    s = dataclasses.replace(s, sample_times=(0.0, 0.25, 0.3, 0.33))
    with pytest.raises(
        MechanicsValueError, match=r"sample time 0.3 is not a whole number of steps 0.0625$"
    ):
        step_counts(s, 0.0625)
    # far from 1 s the tolerance is relative: 1000 + 2 eps·1000 is on the grid
    big = dataclasses.replace(s, sample_times=(0.0, 1000.0 * (1 + 2 * EPS)))
    np.testing.assert_array_equal(step_counts(big, 0.5)[1], [0, 2000])


def test_common_unsupported_says_why_in_each_case():
    assert common_unsupported(_scenario([_box()])) is None
    rocket = _scenario([_box()], thrust=Thrust(0, 0.1, 10.0, 1.0))
    assert common_unsupported(rocket) == (
        "a body's mass changes during the run (Thrust, the rocket of 7.30); the engine "
        "holds masses constant, and a constant-mass thrust is not Tsiolkovsky"
    )
    two = [_box(), _ball(name="point", shape=None)]
    assert common_unsupported(_scenario(two, pair_restitution=((0, 1, 0.5),))) == (
        "contact pair (0, 1): body 'point' has no shape"
    )
    assert common_unsupported(_scenario(two[::-1], pair_restitution=((0, 1, 0.5),))) == (
        "contact pair (0, 1): body 'point' has no shape"
    )
    assert common_unsupported(_scenario(two, pair_restitution=((0, 2, 0.5),))) == (
        "contact pair (0, 2) names no body 2"
    )
    assert common_unsupported(_scenario(two, pair_restitution=((-1, 0, 0.5),))) == (
        "contact pair (-1, 0) names no body -1"
    )
    cone = [_box(shape=Shape("cone", (1.0, 2.0)))]
    assert common_unsupported(_scenario(cone)) == (
        "body 'box' has a shape 'cone' the adapter does not know"
    )
    for kind, dims in (("sphere", (1.0,)), ("box", (1.0, 1.0, 1.0)), ("cylinder", (1.0, 2.0))):
        assert common_unsupported(_scenario([_box(shape=Shape(kind, dims))])) is None
    assert common_unsupported(_scenario([_box(shape=None)])) is None


def test_body_rows_stack_the_initial_states():
    a = _box(
        position=(1.0, 2.0, 3.0), velocity=(4.0, 5.0, 6.0), R_A_O=_rows(R_Z), omega=(7.0, 8.0, 9.0)
    )
    r, v, R, w = body_rows(_scenario([a, _ball()]))
    assert r.shape == v.shape == w.shape == (2, 3)
    assert R.shape == (2, 3, 3)
    assert r.dtype == v.dtype == R.dtype == w.dtype == np.float64
    np.testing.assert_array_equal(r, [[1, 2, 3], [0, 0, 0]])
    np.testing.assert_array_equal(v, [[4, 5, 6], [0, 0, 0]])
    np.testing.assert_array_equal(R, [R_Z, np.eye(3)])
    np.testing.assert_array_equal(w, [[7, 8, 9], [0, 0, 0]])


def test_unit_interval_takes_0_to_1_and_names_the_value_outside():
    assert unit_interval(0, "e", "x") == 0.0
    assert unit_interval(1, "e", "x") == 1.0
    assert unit_interval(0.25, "e", "x") == 0.25
    with pytest.raises(OutOfDomainError) as info:
        unit_interval(1.5, "zeta", "a damping ratio")
    assert str(info.value) == "zeta (a damping ratio) must lie in [0, 1]; got 1.5"
    with pytest.raises(RestitutionRangeError, match=r"^e \(c\) must lie in \[0, 1\]; got -0.5$"):
        unit_interval(-0.5, "e", "c", error=RestitutionRangeError)
    with pytest.raises(MechanicsValueError, match=r"\bzeta\b"):
        unit_interval(math.nan, "zeta", "a damping ratio")


def test_require_imports_or_names_the_extra_and_the_package():
    assert require("math", "none") is math
    assert require("math", "none", quiet=True) is math
    with pytest.raises(MissingExtraError) as info:
        require("no_such_engine_here", "engines")
    assert str(info.value) == (
        "the no_such_engine_here adapter needs the engines package: "
        "pip install 'bodycheck[engines]'"
    )
    with pytest.raises(MissingExtraError) as info:
        require("no_such_engine_here", "engines", quiet=True)
    assert "needs the engines package" in str(info.value)


def test_quiet_stdout_silences_the_descriptors_and_restores_them(tmp_path, monkeypatch):
    import sys

    out = open(tmp_path / "out", "w")  # noqa: SIM115 (closed below)
    err = open(tmp_path / "err", "w")  # noqa: SIM115
    monkeypatch.setattr(sys, "stdout", out)
    monkeypatch.setattr(sys, "stderr", err)
    print("before")  # buffered: flushed before the descriptors are moved
    with quiet_stdout():
        os.write(out.fileno(), b"hidden-out\n")
        os.write(err.fileno(), b"hidden-err\n")
        print("hidden-print")  # buffered: flushed while still silenced
        print("hidden-err-print", file=sys.stderr)
    print("after")
    os.write(err.fileno(), b"err-after\n")
    out.close()
    err.close()
    assert (tmp_path / "out").read_text() == "before\nafter\n"
    assert (tmp_path / "err").read_text() == "err-after\n"


def test_quiet_stdout_leaves_a_stream_without_a_descriptor_alone(monkeypatch):
    import io
    import sys

    fake = io.StringIO()
    monkeypatch.setattr(sys, "stdout", fake)
    with quiet_stdout():
        print("kept")
    assert fake.getvalue() == "kept\n"
    _engines._flush_c_stdio()  # callable at any time, returns nothing


# --------------------------------------------------------------------------- reference.py

#: the scene engine's exact flows ("auto") against the closed forms: measured ≤ 3e-16;
#: a few dozen roundings
SCENE_ATOL = 2**6 * EPS


def _short(name, duration, dt):
    s = SCENARIOS[name]
    n = round(duration / dt)
    return dataclasses.replace(
        s, duration=duration, sample_times=tuple(k * dt for k in range(n + 1))
    )


def test_the_exact_adapter_returns_the_reference_and_supports_everything():
    a = ExactAdapter()
    assert a.name == "exact (closed forms)"
    assert a.takes_step is False
    s = _short("parabola", 0.25, 0.125)
    assert a.supports(s) is None
    tr = a.run(s, None)
    np.testing.assert_array_equal(tr.position, reference(s).trajectory.position)
    # the parabola by hand at t = 0.25: z = 1 + 8·0.25 − 9.81·0.25²/2
    assert tr.position[-1, 0, 2] == pytest.approx(1 + 2 - G / 32, rel=4 * EPS)


def test_the_scene_of_the_parabola_by_hand():
    s = SCENARIOS["parabola"]
    scene = scene_from_scenario(s)
    assert scene["scene"] == {
        "name": "parabola",
        "duration": 1.5,
        "samples": 49,
        "method": "integrate",
    }
    (b,) = scene["bodies"]
    init = b.pop("initial")
    assert b == {
        "name": "b0_ball",
        "mass": 0.5,
        "shape": "custom",
        "inertia": [0.002, 0.002, 0.002],
    }
    # the tilt R3(φ) R1(θ) R3(ψ) with ψ = 0.3, θ = 0.7, φ = −0.4
    assert init["psi"] == pytest.approx(0.3, abs=4 * EPS)
    assert init["theta"] == pytest.approx(0.7, abs=4 * EPS)
    assert init["phi"] == pytest.approx(-0.4, abs=4 * EPS)
    assert init["omega"] == [1.0, -2.0, 3.0]
    assert init["position"] == [0.0, 0.0, 1.0]
    assert init["velocity"] == [3.0, 1.0, 8.0]
    (grav,) = scene["effects"]
    assert grav["type"] == "gravity"
    assert grav["g"] == 9.81
    np.testing.assert_array_equal(grav["direction"], [0.0, 0.0, -1.0])
    tuned = scene_from_scenario(s, method="auto", rtol=1e-9, atol=1e-12)["scene"]
    assert tuned == {
        "name": "parabola",
        "duration": 1.5,
        "samples": 49,
        "method": "auto",
        "rtol": 1e-9,
        "atol": 1e-12,
    }


def test_the_scene_of_the_heavy_top_holds_its_point_below_g_at_the_anchor():
    s = dataclasses.replace(
        SCENARIOS["heavy_top"], pivot=Pivot(0, (0.0, 0.0, -0.1), (1.0, 2.0, 3.0))
    )
    scene = scene_from_scenario(s)
    (b,) = scene["bodies"]
    assert "position" not in b["initial"]
    assert "velocity" not in b["initial"]
    assert b["initial"]["theta"] == pytest.approx(0.6, abs=4 * EPS)
    assert b["initial"]["omega"] == [0.0, 0.0, 6.0]
    assert scene["effects"][1] == {
        "type": "fixed_point",
        "body": "b0_top",
        "distance": 0.1,
        "point": [1.0, 2.0, 3.0],
    }


def test_the_scene_of_the_bounce_and_of_the_impact_collide_solid_spheres():
    s = dataclasses.replace(SCENARIOS["bouncing_ball"], ground=Ground(0.7, (0.0, 0.0, 2.0), 3.0))
    scene = scene_from_scenario(s)
    (b,) = scene["bodies"]
    assert (b["name"], b["shape"], b["radius"], b["mass"]) == ("b0_ball", "solid_sphere", 0.1, 0.5)
    imp = scene["effects"][1]
    assert (imp["type"], imp["body"], imp["restitution"]) == ("impact", "b0_ball", 0.7)
    # the plane n·x = 3 with n = (0, 0, 2): the point 3 n/|n|² = (0, 0, 1.5)
    np.testing.assert_array_equal(imp["plane_point"], [0.0, 0.0, 1.5])
    np.testing.assert_array_equal(imp["plane_normal"], [0.0, 0.0, 2.0])
    scene = scene_from_scenario(SCENARIOS["two_body_impact"])
    assert [b["name"] for b in scene["bodies"]] == ["b0_a", "b1_b"]
    assert [b["radius"] for b in scene["bodies"]] == [0.1, 0.15]
    assert scene["effects"] == [
        {"type": "impact", "body": "b1_b", "other": "b0_a", "restitution": 0.6}
    ]


def test_the_scene_of_the_rocket_is_a_point_pushed_along_its_axis_in_space():
    scene = scene_from_scenario(SCENARIOS["rocket"])
    (b,) = scene["bodies"]
    assert b == {
        "name": "b0_rocket",
        "mass": 10.0,
        "shape": "point",
        "initial": {"position": [0.0, 0.0, 0.0], "velocity": [0.0, 0.0, 0.0]},
    }
    (th,) = scene["effects"]
    d = th.pop("direction")
    assert th == {
        "type": "thrust",
        "body": "b0_rocket",
        "mass_flow": 0.5,
        "exhaust_speed": 20.0,
        "fuel_mass": 4.0,
        "frame": "space",
    }
    # body axis 3 in space: row 3 of ^A R^O = R3(−0.4) R1(0.7) R3(0.3)
    np.testing.assert_allclose(d, (_R3(-0.4) @ _R1(0.7) @ _R3(0.3))[2], atol=4 * EPS, rtol=0)


def test_the_scene_engine_says_what_it_cannot_run():
    p = SCENARIOS["parabola"]
    assert scene_from_scenario(dataclasses.replace(p, sample_times=(0.0, 0.5, 1.5))) == (
        "the scene engine samples uniformly from 0 to the duration"
    )
    assert scene_from_scenario(dataclasses.replace(p, sample_times=(0.0,))) == (
        "the scene engine samples uniformly from 0 to the duration"
    )
    assert scene_from_scenario(dataclasses.replace(p, sample_times=(0.0, 0.75, 1.4))) == (
        "the scene engine samples uniformly from 0 to the duration"
    )
    r = SCENARIOS["rocket"]
    spinning = dataclasses.replace(
        r, bodies=(dataclasses.replace(r.bodies[0], omega=(0.0, 0.0, 1.0)),)
    )
    assert scene_from_scenario(spinning) == (
        "the scene engine's thrust is space-fixed: the rocket must not spin"
    )
    b = SCENARIOS["bouncing_ball"]
    boxy = dataclasses.replace(b, bodies=(_box(position=(0.0, 0.0, 2.0)),))
    assert (
        scene_from_scenario(boxy)
        == "body 'box' collides: the scene engine collides solid spheres only"
    )
    # a sphere whose moments are not 2/5 m r² (a hollow one, 2/3 m r²) is not solid
    hollow = dataclasses.replace(
        b, bodies=(_ball(inertia=(2 / 3 * 0.005,) * 3, position=(0.0, 0.0, 2.0)),)
    )
    assert (
        scene_from_scenario(hollow)
        == "body 'ball' collides: the scene engine collides solid spheres only"
    )
    nearly = dataclasses.replace(
        b, bodies=(_ball(inertia=(0.002 * (1 + 4 * EPS),) * 3, position=(0.0, 0.0, 2.0)),)
    )
    assert isinstance(scene_from_scenario(nearly), dict)  # 2/5 m r² to rounding
    h = SCENARIOS["heavy_top"]
    for point in ((0.01, 0.0, -0.1), (0.0, 0.01, -0.1), (0.0, 0.0, 0.1), (0.0, 0.0, 0.0)):
        assert scene_from_scenario(dataclasses.replace(h, pivot=Pivot(0, point))) == (
            "the scene engine's fixed point lies on body axis 3 below G"
        )


def test_the_scene_engine_adapter_runs_the_exact_flows_to_rounding():
    a = SceneEngineAdapter("auto")
    assert a.name == "bodycheck scene engine (auto)"
    assert SceneEngineAdapter().name == "bodycheck scene engine (integrate)"
    assert a.takes_step is False
    for name, duration, dt in (("heavy_top", 0.25, 0.125), ("two_body_impact", 0.5, 0.25)):
        s = _short(name, duration, dt)
        assert a.supports(s) is None
        tr = a.run(s, None)
        ref = reference(s).trajectory
        np.testing.assert_array_equal(tr.t, ref.t)
        for got, want in (
            (tr.position, ref.position),
            (tr.velocity, ref.velocity),
            (tr.R_A_O, ref.R_A_O),
            (tr.omega, ref.omega),
        ):
            np.testing.assert_allclose(got, want, atol=SCENE_ATOL, rtol=0)
        assert tr.masses is None


def test_the_scene_engine_adapter_keeps_a_point_bodys_attitude_and_reports_its_mass():
    s = _short("rocket", 1.0, 0.5)
    tr = SceneEngineAdapter("auto").run(s, None)
    np.testing.assert_array_equal(
        tr.R_A_O[:, 0], np.broadcast_to(np.array(s.bodies[0].R_A_O), (3, 3, 3))
    )
    np.testing.assert_array_equal(tr.omega, 0.0)
    np.testing.assert_allclose(tr.masses[:, 0], [10.0, 9.75, 9.5], atol=SCENE_ATOL, rtol=0)
    d = np.array(s.bodies[0].R_A_O)[2]
    # Tsiolkovsky: v = u ln(m0/m) along the axis
    np.testing.assert_allclose(
        tr.velocity[-1, 0], 20 * math.log(10 / 9.5) * d, atol=SCENE_ATOL, rtol=0
    )


def test_the_scene_engine_adapter_refuses_to_run_what_it_does_not_support():
    a = SceneEngineAdapter("auto")
    bad = dataclasses.replace(SCENARIOS["parabola"], sample_times=(0.0, 0.5, 1.5))
    assert a.supports(bad) == "the scene engine samples uniformly from 0 to the duration"
    with pytest.raises(
        ValueError, match=r"^the scene engine samples uniformly from 0 to the duration$"
    ):
        a.run(bad, None)
