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
import itertools
import math
import os

import numpy as np
import pytest

from mechanics._floats import EPS
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
from mechanics.scenes.spec import METHODS

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


#: the body ω the attitude round trips below give each engine
SPIN = np.array([0.3, -0.2, 1.1])


def _spun_box():
    """The box turned by R_Z, spinning at SPIN (body), at (1, 2, 3) moving at (½, 0, −1)."""
    return _box(
        R_A_O=_rows(R_Z), omega=tuple(SPIN), position=(1.0, 2.0, 3.0), velocity=(0.5, 0.0, -1.0)
    )


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
    # an ImportError that names the missing module, as Python's own do
    assert info.value.name == "no_such_engine_here"


def test_require_leaves_the_descriptors_alone_unless_asked_to_be_quiet(monkeypatch):
    """Only pybullet's import is silenced (its C banner): by default nothing redirects
    stdout and stderr, so what a user's engine prints on import still shows."""
    calls = []

    def spy():
        calls.append(1)
        return quiet_stdout()

    monkeypatch.setattr(_engines, "quiet_stdout", spy)
    assert _engines.require("math", "none") is math
    assert calls == []
    assert _engines.require("math", "none", quiet=True) is math
    assert calls == [1]


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
    s = dataclasses.replace(SCENARIOS["bouncing_ball"], ground=Ground(0.7, (0.0, 0.0, 1.0), 3.0))
    scene = scene_from_scenario(s)
    (b,) = scene["bodies"]
    assert (b["name"], b["shape"], b["radius"], b["mass"]) == ("b0_ball", "solid_sphere", 0.1, 0.5)
    imp = scene["effects"][1]
    assert (imp["type"], imp["body"], imp["restitution"]) == ("impact", "b0_ball", 0.7)
    # the plane n·x = 3 with n = (0, 0, 1): the point 3 n = (0, 0, 3)
    np.testing.assert_array_equal(imp["plane_point"], [0.0, 0.0, 3.0])
    np.testing.assert_array_equal(imp["plane_normal"], [0.0, 0.0, 1.0])
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
    # uniform within SAMPLE_TIME_RTOL × max(duration, 1) = 1.5 of it for T = 1.5
    from mechanics.conformance.protocol import SAMPLE_TIME_RTOL

    assert p.duration == 1.5
    for off, uniform in ((1.25, True), (1.75, False)):
        times = (0.0, 0.75 + off * SAMPLE_TIME_RTOL, 1.5)
        got = scene_from_scenario(dataclasses.replace(p, sample_times=times))
        assert isinstance(got, dict) is uniform, (off, got)
    # two samples, the start and the end, are uniform
    ends = scene_from_scenario(dataclasses.replace(p, sample_times=(0.0, 1.5)))
    assert ends["scene"]["samples"] == 2
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
        == "body 'box' collides: the scene engine collides solid spheres, boxes and cylinders of uniform density (their moments from the shape)"
    )
    # a sphere whose moments are not 2/5 m r² (a hollow one, 2/3 m r²) is not solid
    hollow = dataclasses.replace(
        b, bodies=(_ball(inertia=(2 / 3 * 0.005,) * 3, position=(0.0, 0.0, 2.0)),)
    )
    assert (
        scene_from_scenario(hollow)
        == "body 'ball' collides: the scene engine collides solid spheres, boxes and cylinders of uniform density (their moments from the shape)"
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


def test_the_scene_engine_adapter_refuses_an_unknown_method_when_it_is_made():
    # not at run time, where the battery would mark every scenario "error": the choices
    # are the scene parser's METHODS
    with pytest.raises(
        UnknownOptionError,
        match=r"^scene engine method must be one of \('auto', 'exact', 'integrate', "
        r"'splitting'\); got 'bogus'$",
    ):
        SceneEngineAdapter("bogus")
    for method in METHODS:
        assert SceneEngineAdapter(method).method == method


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


# --------------------------------------------------------------------------- MuJoCo


def _mujoco():
    return pytest.importorskip(
        "mujoco", reason="MuJoCo is not installed: pip install 'bodycheck[mujoco]'"
    )


def test_mujoco_no_tension_restitution_by_its_closed_form():
    from mechanics.conformance.adapters.mujoco import restitution_without_tension

    assert restitution_without_tension(0.0) == 1.0
    # ζ = 1/2: the body lets go at ω_d t = π − 2 arcsin ½ = 2π/3, e = exp(−½ (2π/3)/√(3/4))
    assert restitution_without_tension(0.5) == pytest.approx(
        math.exp(-math.pi / (3 * math.sqrt(0.75))), rel=8 * EPS
    )
    z = 0.2
    want = math.exp(-z * (math.pi - 2 * math.asin(z)) / math.sqrt(1 - z * z))
    assert restitution_without_tension(z) == pytest.approx(want, rel=8 * EPS)
    with pytest.raises(
        OutOfDomainError, match=r"^zeta \(a damping ratio\) must lie in \[0, 1\]; got 1.5$"
    ):
        restitution_without_tension(1.5)


def test_mujoco_zeta_without_tension_is_bisected_to_the_last_bit():
    from mechanics.conformance.adapters.mujoco import (
        restitution_without_tension,
        zeta_without_tension,
    )

    assert zeta_without_tension(1.0) == 0.0
    assert zeta_without_tension(math.exp(-2)) == 1.0  # the least e: critical damping
    for e in (0.2, 0.5, 0.8, 0.99):  # above e^-2, the law's floor (the next test)
        z = zeta_without_tension(e)
        # e(ζ) decreases: the neighbours of ζ bracket e
        assert restitution_without_tension(np.nextafter(z, 0.0)) >= e - 2 * EPS
        assert restitution_without_tension(np.nextafter(z, 1.0)) <= e + 2 * EPS
        assert restitution_without_tension(z) == pytest.approx(e, abs=4 * EPS)
    with pytest.raises(
        RestitutionRangeError,
        match=r"^e \(a coefficient of restitution\) must lie in \[0, 1\]; got -0.1$",
    ):
        zeta_without_tension(-0.1)


def test_mujoco_no_tension_restitution_is_continuous_at_critical_damping():
    # (a library bug found in issue 16: e(1) was 0, and zeta_without_tension(0.1) gave 1)
    from mechanics.conformance.adapters.mujoco import restitution_without_tension

    # ζ = 1: x = v t e^(−ωt), ẋ = v (1 − ωt) e^(−ωt); the force ω² x + 2ω ẋ vanishes at
    # ωt = 2, where ẋ = −v e^(−2).  Near ζ = 1, with ε = 1 − ζ: π − 2 arcsin ζ ≈ 2√(2ε),
    # √(1 − ζ²) ≈ √(2ε), so e ≈ exp(−2ζ(1 + ε/3)) to O(ε²): within 2^-60 at ε = 2^-40
    z = 1 - 2.0**-40
    assert restitution_without_tension(z) == pytest.approx(
        math.exp(-2 * z * (1 + 2.0**-40 / 3)), rel=2**6 * EPS
    )
    assert restitution_without_tension(1.0) == math.exp(-2)
    # e(ζ) keeps falling up to ζ = 1 (its floor is approached from above)
    zs = 1 - np.array([2.0**-10, 2.0**-20, 2.0**-30, 0.0])
    es = [restitution_without_tension(float(x)) for x in zs]
    assert all(a > b for a, b in itertools.pairwise(es))


@pytest.mark.parametrize("e", [0.0, 0.1, math.exp(-2) * (1 - 2 * EPS)])
def test_mujoco_zeta_without_tension_refuses_a_restitution_below_its_floor(e):
    from mechanics.conformance.adapters.mujoco import zeta_without_tension

    with pytest.raises(OutOfDomainError) as info:
        zeta_without_tension(e)
    assert str(info.value) == (
        f"e = {e!r} is below e^-2 = 0.135335: a spring-damper that cannot pull rebounds at "
        "least that fast for any damping ratio zeta <= 1"
    )


def test_mujoco_tuned_contact_does_not_support_a_restitution_below_its_floor():
    _mujoco()
    from mechanics.conformance.adapters.mujoco import MuJoCoAdapter

    ball = SCENARIOS["bouncing_ball"]
    low = dataclasses.replace(ball, ground=Ground(0.1))
    assert MuJoCoAdapter("RK4", "tuned").supports(ball) is None
    assert MuJoCoAdapter("RK4", "tuned").supports(low) == (
        "a restitution e = 0.1 below e^-2 = 0.1353: the tuned contact (a spring-damper that "
        "cannot pull, zeta <= 1) rebounds faster; the default contact takes it"
    )
    assert MuJoCoAdapter("RK4", "default").supports(low) is None
    pair = dataclasses.replace(SCENARIOS["two_body_impact"], pair_restitution=((0, 1, 0.05),))
    assert "e = 0.05 below e^-2" in MuJoCoAdapter("Euler", "tuned").supports(pair)


def test_mujoco_textbook_zeta_by_hand():
    from mechanics.conformance.adapters.mujoco import zeta_textbook

    assert zeta_textbook(0.0) == 1.0
    assert zeta_textbook(1.0) == 0.0
    # e = exp(−π): ζ = π/√(π² + π²) = 1/√2
    assert zeta_textbook(math.exp(-math.pi)) == pytest.approx(1 / math.sqrt(2), rel=4 * EPS)
    with pytest.raises(
        RestitutionRangeError,
        match=r"^e \(a coefficient of restitution\) must lie in \[0, 1\]; got 2.0$",
    ):
        zeta_textbook(2.0)


def test_mujoco_contact_parameters_of_each_setting():
    _mujoco()
    from mechanics.conformance.adapters.mujoco import (
        MuJoCoAdapter,
        zeta_textbook,
        zeta_without_tension,
    )

    default, tuned = MuJoCoAdapter("RK4", "default"), MuJoCoAdapter("RK4", "tuned")
    assert default._solref(0.5, 1e-3) == (f"0.02 {zeta_textbook(0.5)!r}", "0.9 0.95 0.001 0.5 2")
    # tuned: τ = max(2 ms, 20 h), the no-tension ζ, the impedance held at 0.9999
    assert tuned._solref(0.5, 1e-5) == (
        f"0.002 {zeta_without_tension(0.5)!r}",
        "0.9999 0.9999 0.001 0.5 2",
    )
    assert tuned._solref(0.5, 1e-3) == (
        f"0.02 {zeta_without_tension(0.5)!r}",
        "0.9999 0.9999 0.001 0.5 2",
    )
    # e = 1: the direct form (−1/τ², 0)
    assert tuned._solref(1.0, 1e-5) == ("-250000.0 0", "0.9999 0.9999 0.001 0.5 2")
    assert default._solref(1.0, 1e-5) == ("-2500.0 0", "0.9 0.95 0.001 0.5 2")
    assert default._solref(0.0, 1e-5)[0] == "0.02 1.0"


def test_mujoco_adapter_names_itself_and_its_variants():
    mj = _mujoco()
    from mechanics.conformance.adapters.mujoco import MuJoCoAdapter, variants

    a = MuJoCoAdapter("Euler", "default")
    assert a.name == f"MuJoCo {mj.__version__} Euler, default contact"
    assert repr(a) == "MuJoCoAdapter('Euler', 'default')"
    assert a.takes_step is True
    assert MuJoCoAdapter().name == f"MuJoCo {mj.__version__} RK4, tuned contact"
    assert [(v.integrator, v.contact) for v in variants()] == [
        ("RK4", "default"),
        ("RK4", "tuned"),
        ("Euler", "default"),
        ("Euler", "tuned"),
        ("implicitfast", "default"),
        ("implicitfast", "tuned"),
    ]


def test_mujoco_model_text_of_a_ball_over_the_ground_and_a_pair():
    _mujoco()
    from mechanics.conformance.adapters.mujoco import MuJoCoAdapter

    s = _scenario(
        [
            _ball(position=(0.0, 0.0, 1.0)),
            _ball(name="other", position=(1.0, 0.0, 1.0)),
            _box(name="bare", shape=None, position=(3.0, 0.0, 1.0)),  # touches nothing
        ],
        gravity=(0.0, 0.0, -9.81),
        ground=Ground(0.5, (0.0, 0.0, 1.0), 1.0),
        pair_restitution=((0, 1, 0.8),),
    )
    xml = MuJoCoAdapter("Euler").mjcf(s, 0.001)
    assert '<option integrator="Euler" timestep="0.001" gravity="0.0 0.0 -9.81"/>' in xml
    # the plane n·x = 1 with n = (0, 0, 1): through (0, 0, 1), zaxis the normal
    assert (
        '<geom name="ground" type="plane" size="0 0 1" pos="0.0 0.0 1.0" zaxis="0.0 0.0 1.0" contype="0" conaffinity="0"/>'
        in xml
    )
    assert '<body name="b0" pos="0.0 0.0 1.0" quat="1.0 0.0 0.0 0.0">' in xml
    assert '<inertial pos="0 0 0" mass="0.5" diaginertia="0.002 0.002 0.002"/>' in xml
    assert '<geom name="g1" type="sphere" size="0.1" contype="0" conaffinity="0"/>' in xml
    assert xml.count("<freejoint/>") == 3
    assert xml.count("</body>") == 3
    assert 'name="g2"' not in xml
    assert xml.count('<pair geom1="ground" geom2="g') == 2
    assert '<pair geom1="g0" geom2="g1" condim="1" solref=' in xml
    assert xml.startswith("<mujoco>\n")
    assert xml.endswith("  </contact>\n</mujoco>")


def test_mujoco_model_of_a_pivot_is_a_ball_joint_at_the_anchor_with_g_off_it():
    _mujoco()
    from mechanics.conformance.adapters.mujoco import MuJoCoAdapter

    s = _scenario([_box()], pivot=Pivot(0, (0.0, 0.0, -0.25), (1.0, 2.0, 3.0)))
    xml = MuJoCoAdapter().mjcf(s, 0.01)
    assert '<body name="b0" pos="1.0 2.0 3.0">' in xml
    assert '<joint name="pivot" type="ball" pos="0 0 0"/>' in xml
    assert '<inertial pos="-0.0 -0.0 0.25" mass="2.0" diaginertia="1.0 2.0 2.5"/>' in xml
    assert 'type="box" size="0.5 0.4 0.3" pos="-0.0 -0.0 0.25"' in xml
    assert "<contact>" not in xml


def test_mujoco_reads_a_pivoted_body_beside_a_free_one_by_its_own_joint():
    # qpos holds the ball joint's 4 numbers, then the free joint's 7: each body's state
    # is read from its own slice (a slice one too long would take the next joint's x)
    _mujoco()
    from mechanics.conformance.adapters.mujoco import MuJoCoAdapter

    top = _box(R_A_O=_rows(R_GENERAL), omega=(0.0, 0.0, 2.0), position=(1.0, 2.0, 3.0))
    free = _ball(name="free", position=(5.0, 0.0, 0.0), velocity=(0.0, 1.0, 0.0))
    arm = (0.0, 0.0, -0.25)
    anchor = tuple(np.asarray(top.position) + R_GENERAL.T @ np.asarray(arm))
    s = _scenario([top, free], pivot=Pivot(0, arm, anchor))
    tr = MuJoCoAdapter("RK4").run(s, 0.125)
    np.testing.assert_allclose(tr.R_A_O[0, 0], R_GENERAL, atol=ROUNDTRIP_ATOL, rtol=0)
    np.testing.assert_allclose(tr.position[0, 0], top.position, atol=ROUNDTRIP_ATOL, rtol=0)
    np.testing.assert_allclose(tr.omega[0, 0], top.omega, atol=ROUNDTRIP_ATOL, rtol=0)
    # the free ball in free space: uniform motion, exact under RK4
    np.testing.assert_allclose(
        tr.position[:, 1],
        [[5.0, 0.0, 0.0], [5.0, 0.125, 0.0], [5.0, 0.25, 0.0]],
        atol=ROUNDTRIP_ATOL,
        rtol=0,
    )
    np.testing.assert_allclose(
        tr.R_A_O[:, 1], np.broadcast_to(np.eye(3), (3, 3, 3)), atol=ROUNDTRIP_ATOL, rtol=0
    )


def test_mujoco_holds_the_attitude_and_body_omega_it_is_given():
    mj = _mujoco()
    from mechanics.conformance.adapters.mujoco import MuJoCoAdapter

    w = SPIN
    s = _scenario([_spun_box()])
    a = MuJoCoAdapter()
    model, data = a.build(s, 0.01)
    # MuJoCo's own view: its quaternion is the active (cos 0.4, 0, 0, sin 0.4), its
    # matrix has the body axes as columns: (^A R^O)ᵀ
    np.testing.assert_allclose(data.xquat[1], Q_Z_WXYZ, atol=ROUNDTRIP_ATOL, rtol=0)
    np.testing.assert_allclose(data.xmat[1].reshape(3, 3), R_Z.T, atol=ROUNDTRIP_ATOL, rtol=0)
    vel = np.zeros(6)
    mj.mj_objectVelocity(model, data, mj.mjtObj.mjOBJ_BODY, 1, vel, 0)  # world frame
    np.testing.assert_allclose(vel[:3], R_Z.T @ w, atol=ROUNDTRIP_ATOL, rtol=0)
    np.testing.assert_allclose(vel[3:], [0.5, 0.0, -1.0], atol=ROUNDTRIP_ATOL, rtol=0)
    pos, v, R, om = a._read(s, model, data)
    np.testing.assert_allclose(R[0], R_Z, atol=ROUNDTRIP_ATOL, rtol=0)
    np.testing.assert_allclose(om[0], w, atol=ROUNDTRIP_ATOL, rtol=0)
    np.testing.assert_allclose(pos[0], [1.0, 2.0, 3.0], atol=ROUNDTRIP_ATOL, rtol=0)
    np.testing.assert_allclose(v[0], [0.5, 0.0, -1.0], atol=ROUNDTRIP_ATOL, rtol=0)


def test_mujoco_reads_a_pivoted_body_from_its_joint():
    _mujoco()
    from mechanics.conformance.adapters.mujoco import MuJoCoAdapter

    w = np.array([0.0, 0.5, 2.0])
    s = _scenario(
        [_box(R_A_O=_rows(R_GENERAL), omega=tuple(w))],
        pivot=Pivot(0, (0.0, 0.0, -0.25), (1.0, 2.0, 3.0)),
    )
    a = MuJoCoAdapter()
    model, data = a.build(s, 0.01)
    pos, v, R, om = a._read(s, model, data)
    arm = R_GENERAL.T @ [0.0, 0.0, 0.25]  # pivot to G in space
    np.testing.assert_allclose(R[0], R_GENERAL, atol=ROUNDTRIP_ATOL, rtol=0)
    np.testing.assert_allclose(om[0], w, atol=ROUNDTRIP_ATOL, rtol=0)
    np.testing.assert_allclose(pos[0], np.array([1.0, 2.0, 3.0]) + arm, atol=ROUNDTRIP_ATOL, rtol=0)
    np.testing.assert_allclose(v[0], np.cross(R_GENERAL.T @ w, arm), atol=ROUNDTRIP_ATOL, rtol=0)
    # MuJoCo puts G where the adapter says
    np.testing.assert_allclose(
        data.xipos[1], np.array([1.0, 2.0, 3.0]) + arm, atol=ROUNDTRIP_ATOL, rtol=0
    )


def test_mujoco_free_fall_and_spin_about_a_principal_axis_in_a_few_rk4_steps():
    _mujoco()
    from mechanics.conformance.adapters.mujoco import MuJoCoAdapter

    # RK4 is exact for x0 + v0 t + g t²/2; a spin ω about body axis 3 (principal) stays
    # ω and turns ^A R^O into R3(ω t) R(0)
    s = _scenario(
        [
            _box(
                R_A_O=_rows(R_GENERAL),
                omega=(0.0, 0.0, 2.0),
                position=(1.0, 2.0, 3.0),
                velocity=(0.5, 0.0, 4.0),
            )
        ],
        duration=0.25,
        dt=0.125,
        gravity=(0.0, 0.0, -9.81),
    )
    tr = MuJoCoAdapter("RK4").run(s, 2.0**-5)
    t = np.array(s.sample_times)
    np.testing.assert_allclose(
        tr.velocity[:, 0], [[0.5, 0.0, 4.0 - G * tk] for tk in t], atol=STEP_ATOL, rtol=0
    )
    np.testing.assert_allclose(
        tr.position[:, 0],
        [[1.0 + 0.5 * tk, 2.0, 3.0 + 4.0 * tk - G * tk * tk / 2] for tk in t],
        atol=STEP_ATOL,
        rtol=0,
    )
    np.testing.assert_allclose(tr.omega[:, 0], [[0.0, 0.0, 2.0]] * 3, atol=STEP_ATOL, rtol=0)
    for k, tk in enumerate(t):
        np.testing.assert_allclose(
            tr.R_A_O[k, 0], _R3(2.0 * tk) @ R_GENERAL, atol=STEP_ATOL, rtol=0
        )


def test_mujoco_refuses_to_run_a_rocket_saying_why():
    _mujoco()
    from mechanics.conformance.adapters.mujoco import MuJoCoAdapter

    s = _scenario([_box()], thrust=Thrust(0, 0.1, 10.0, 1.0))
    with pytest.raises(MechanicsValueError) as info:
        MuJoCoAdapter().run(s, 0.125)
    assert str(info.value) == "scenario 'made_up': MuJoCo cannot run it: " + common_unsupported(s)


# --------------------------------------------------------------------------- PyBullet


def _pybullet():
    with quiet_stdout():
        return pytest.importorskip(
            "pybullet", reason="PyBullet is not installed: pip install 'bodycheck[pybullet]'"
        )


def test_pybullet_quaternions_are_scalar_last():
    from mechanics.conformance.adapters.pybullet import _R_A_O, _xyzw

    assert _xyzw(Q_Z_WXYZ) == [0.0, 0.0, math.sin(0.4), math.cos(0.4)]
    assert _xyzw([1.0, 2.0, 3.0, 4.0]) == [2.0, 3.0, 4.0, 1.0]
    np.testing.assert_allclose(
        _R_A_O([0.0, 0.0, math.sin(0.4), math.cos(0.4)]), R_Z, atol=ROUNDTRIP_ATOL, rtol=0
    )
    np.testing.assert_array_equal(_R_A_O([0.0, 0.0, 0.0, 1.0]), np.eye(3))


def test_pybullet_per_body_restitutions_whose_products_give_each_contact():
    from mechanics.conformance.adapters.pybullet import _restitutions

    shaped, bare = _ball(), _ball(name="bare", shape=None)
    # the ground's e on every body with a shape (the plane gets 1), 1 on the others
    assert _restitutions(_scenario([shaped, bare], ground=Ground(0.6))) == ([0.6, 1.0], None)
    # a pair alone: √e each
    r, why = _restitutions(_scenario([shaped, shaped], pair_restitution=((0, 1, 0.25),)))
    assert (r, why) == ([0.5, 0.5], None)
    # a third body paired with one already set: e / r
    r, why = _restitutions(_scenario([shaped] * 3, pair_restitution=((0, 1, 0.25), (1, 2, 0.125))))
    assert why is None
    assert r == pytest.approx([0.5, 0.5, 0.25], rel=4 * EPS)
    r, why = _restitutions(_scenario([shaped] * 3, pair_restitution=((0, 1, 0.25), (2, 1, 0.125))))
    assert why is None
    assert r == pytest.approx([0.5, 0.5, 0.25], rel=4 * EPS)
    # a partner of restitution 0 makes any e; the body then takes 0
    r, why = _restitutions(
        _scenario([shaped, bare, shaped], ground=Ground(0.0), pair_restitution=((0, 1, 0.0),))
    )
    assert (r, why) == ([0.0, 0.0, 0.0], None)
    r, why = _restitutions(
        _scenario([bare, shaped], ground=Ground(0.0), pair_restitution=((0, 1, 0.0),))
    )
    assert (r, why) == ([0.0, 0.0], None)
    # no per-body values: the ground's 0.5 on both and a pair of 0.9
    r, why = _restitutions(
        _scenario([shaped, shaped], ground=Ground(0.5), pair_restitution=((0, 1, 0.9),))
    )
    assert r is None
    assert why == (
        "PyBullet restitutes a contact with the product of the two bodies' coefficients; no "
        "per-body values give pair (0, 1) its e = 0.9 together with the scenario's other contacts"
    )
    # e / r above 1: refused too
    r, why = _restitutions(
        _scenario([shaped, bare], ground=Ground(0.25), pair_restitution=((0, 1, 0.5),))
    )
    assert r is None
    assert "pair (0, 1) its e = 0.5" in why


def test_pybullet_says_why_it_cannot_run_a_scenario():
    _pybullet()
    from mechanics.conformance.adapters.pybullet import PyBulletAdapter

    a = PyBulletAdapter()
    rocket = _scenario([_box()], thrust=Thrust(0, 0.1, 10.0, 1.0))
    assert a.supports(rocket) == common_unsupported(rocket)
    clash = _scenario([_ball(), _ball()], ground=Ground(0.5), pair_restitution=((0, 1, 0.9),))
    assert a.supports(clash).startswith("PyBullet restitutes a contact with the product")
    assert a.supports(_scenario([_ball()], ground=Ground(0.5))) is None
    with pytest.raises(MechanicsValueError) as info:
        a.run(clash, 0.125)
    assert str(info.value) == "scenario 'made_up': PyBullet cannot run it: " + a.supports(clash)
    with pytest.raises(MechanicsValueError) as info:
        a.build(clash, 0.125)
    assert str(info.value) == "scenario 'made_up': " + a.supports(clash)


def test_pybullet_adapter_names_itself_and_its_variants():
    _pybullet()
    from mechanics.conformance.adapters.pybullet import PyBulletAdapter, pybullet_version, variants

    v = pybullet_version()
    assert v[0].isdigit()
    assert (
        PyBulletAdapter().name == f"PyBullet {v} default (one step, 50 iterations), tuned contact"
    )
    a = PyBulletAdapter("fine", "default")
    assert a.name == f"PyBullet {v} fine (8 substeps, 200 iterations), default contact"
    assert repr(a) == "PyBulletAdapter('fine', 'default')"
    assert a.takes_step is True
    assert [(x.variant, x.contact) for x in variants()] == [
        ("default", "default"),
        ("default", "tuned"),
        ("fine", "default"),
        ("fine", "tuned"),
    ]


def test_pybullet_holds_the_attitude_the_space_omega_and_no_damping():
    p = _pybullet()
    from mechanics.conformance.adapters.pybullet import PyBulletAdapter

    w = SPIN
    s = _scenario(
        [_spun_box()],
        ground=Ground(0.5),
    )
    a = PyBulletAdapter("default", "tuned")
    other = p.connect(p.DIRECT)  # a second server: each call must name the adapter's
    try:
        cid, ids = a.build(s, 0.01)
    finally:
        p.disconnect(other)
    assert cid != other
    try:
        ((uid, link),) = ids
        assert link == -1
        x, q = p.getBasePositionAndOrientation(uid, physicsClientId=cid)
        np.testing.assert_allclose(x, [1.0, 2.0, 3.0], atol=ROUNDTRIP_ATOL, rtol=0)
        np.testing.assert_allclose(
            q, [0.0, 0.0, math.sin(0.4), math.cos(0.4)], atol=ROUNDTRIP_ATOL, rtol=0
        )
        # PyBullet's matrix, row-major, has the body axes as columns: (^A R^O)ᵀ
        M = np.array(p.getMatrixFromQuaternion(q)).reshape(3, 3)
        np.testing.assert_allclose(M, R_Z.T, atol=ROUNDTRIP_ATOL, rtol=0)
        v, w_O = p.getBaseVelocity(uid, physicsClientId=cid)
        np.testing.assert_allclose(w_O, R_Z.T @ w, atol=ROUNDTRIP_ATOL, rtol=0)
        np.testing.assert_allclose(v, [0.5, 0.0, -1.0], atol=ROUNDTRIP_ATOL, rtol=0)
        info = p.getDynamicsInfo(uid, -1, physicsClientId=cid)
        assert info[0] == 2.0
        assert info[1] == 0.0  # lateral friction
        np.testing.assert_array_equal(info[2], [1.0, 2.0, 2.5])
        assert info[5] == 0.5  # the ground's e on the body
        assert info[6] == info[7] == 0.0  # rolling and spinning friction
        pos, vel, R, om = a._read(cid, ids)
        np.testing.assert_allclose(R[0], R_Z, atol=ROUNDTRIP_ATOL, rtol=0)
        np.testing.assert_allclose(om[0], w, atol=ROUNDTRIP_ATOL, rtol=0)
        np.testing.assert_allclose(pos[0], [1.0, 2.0, 3.0], atol=ROUNDTRIP_ATOL, rtol=0)
        np.testing.assert_allclose(vel[0], [0.5, 0.0, -1.0], atol=ROUNDTRIP_ATOL, rtol=0)
    finally:
        p.disconnect(cid)


def test_pybullet_free_fall_and_principal_spin_by_semi_implicit_euler():
    _pybullet()
    from mechanics.conformance.adapters.pybullet import PyBulletAdapter

    # v_{n+1} = v_n + g h, x_{n+1} = x_n + h v_{n+1}: after n steps v0 + g n h and
    # x0 + v0 n h + g h² n(n + 1)/2; no damping: the spin about axis 3 stays 2 rad/s
    h = 2.0**-5
    s = _scenario(
        [
            _box(
                R_A_O=_rows(R_GENERAL),
                omega=(0.0, 0.0, 2.0),
                position=(1.0, 2.0, 3.0),
                velocity=(0.5, 0.0, 4.0),
            )
        ],
        gravity=(0.0, 0.0, -9.81),
    )
    tr = PyBulletAdapter().run(s, h)
    n = np.array([0, 4, 8])
    np.testing.assert_allclose(tr.velocity[:, 0, 2], 4.0 - G * n * h, atol=STEP_ATOL, rtol=0)
    np.testing.assert_allclose(tr.velocity[:, 0, :2], [[0.5, 0.0]] * 3, atol=STEP_ATOL, rtol=0)
    np.testing.assert_allclose(
        tr.position[:, 0, 2],
        3.0 + 4.0 * n * h - G * h * h * n * (n + 1) / 2,
        atol=STEP_ATOL,
        rtol=0,
    )
    np.testing.assert_allclose(tr.omega[:, 0], [[0.0, 0.0, 2.0]] * 3, atol=2**4 * STEP_ATOL, rtol=0)
    for k, tk in enumerate(n * h):
        np.testing.assert_allclose(
            tr.R_A_O[k, 0], _R3(2.0 * tk) @ R_GENERAL, atol=2**4 * STEP_ATOL, rtol=0
        )


def test_pybullet_pivoted_link_starts_with_its_body_omega():
    p = _pybullet()
    from mechanics.conformance.adapters.pybullet import PyBulletAdapter

    w = np.array([0.0, 0.5, 2.0])
    s = _scenario(
        [_box(R_A_O=_rows(R_GENERAL), omega=tuple(w))],
        pivot=Pivot(0, (0.0, 0.0, -0.25), (1.0, 2.0, 3.0)),
    )
    a = PyBulletAdapter()
    cid, ids = a.build(s, 0.01)
    try:
        assert ids[0][1] == 0
        pos, vel, R, om = a._read(cid, ids)
    finally:
        p.disconnect(cid)
    arm = R_GENERAL.T @ [0.0, 0.0, 0.25]
    np.testing.assert_allclose(R[0], R_GENERAL, atol=ROUNDTRIP_ATOL, rtol=0)
    np.testing.assert_allclose(om[0], w, atol=ROUNDTRIP_ATOL, rtol=0)
    np.testing.assert_allclose(pos[0], np.array([1.0, 2.0, 3.0]) + arm, atol=ROUNDTRIP_ATOL, rtol=0)
    np.testing.assert_allclose(vel[0], np.cross(R_GENERAL.T @ w, arm), atol=ROUNDTRIP_ATOL, rtol=0)


# --------------------------------------------------------------------------- Drake


def _drake():
    return pytest.importorskip(
        "pydrake.all", reason="Drake is not installed: pip install 'bodycheck[drake]'"
    )


def _hc_law(c, e):
    """ln((1 + c)/(1 − c e)) − c (1 + e): zero at the Hunt–Crossley c of restitution e."""
    return math.log((1 + c) / (1 - c * e)) - c * (1 + e)


def test_hunt_crossley_dissipation_solves_its_law_and_scales_with_the_speed():
    from mechanics.conformance.adapters.drake import E_FLOOR, hunt_crossley_dissipation

    for e in (0.2, 0.5, 0.8, 0.999):
        c = hunt_crossley_dissipation(e, 1.0)
        assert 0 < c < 1 / e
        # bisected to the last bit: the law changes sign across c's neighbours (to the
        # rounding of log((1 + c)/(1 − c e)), steep near c = 1/e: 1 − c e = 0.016 at e = 0.2)
        assert _hc_law(np.nextafter(c, 0.0), e) <= 2**8 * EPS
        assert _hc_law(np.nextafter(c, np.inf), e) >= -(2**8) * EPS
        assert abs(_hc_law(c, e)) <= 2**8 * EPS
        assert hunt_crossley_dissipation(e, 4.0) == pytest.approx(c / 4.0, rel=2 * EPS)
    # near e = 1 the first order c = (3/2)(1 − e)
    # (second order: a relative δ = 2^-10)
    assert hunt_crossley_dissipation(1 - 2**-10, 1.0) == pytest.approx(1.5 * 2**-10, rel=2**-8)
    assert hunt_crossley_dissipation(1.0, 3.0) == 0.0
    assert hunt_crossley_dissipation(0.0, 1.0) == hunt_crossley_dissipation(E_FLOOR, 1.0)
    assert E_FLOOR == 2.0**-20


def test_hunt_crossley_dissipation_refuses_by_name():
    from mechanics.conformance.adapters.drake import hunt_crossley_dissipation
    from mechanics.errors import ResultOverflowError

    with pytest.raises(
        RestitutionRangeError,
        match=r"^e \(a coefficient of restitution\) must lie in \[0, 1\]; got 1.5$",
    ):
        hunt_crossley_dissipation(1.5, 1.0)
    with pytest.raises(MechanicsValueError, match=r"\bv_ref\b"):
        hunt_crossley_dissipation(0.5, 0.0)
    with pytest.raises(ResultOverflowError) as info:
        hunt_crossley_dissipation(0.5, 5e-324)
    assert str(info.value) == "hunt_crossley_dissipation: d = c/v_ref overflows for v_ref = 5e-324"


def test_support_distance_of_each_shape_along_a_normal():
    from mechanics.conformance.adapters.drake import _support_distance

    n = np.array([0.0, 0.0, 1.0])
    assert _support_distance(Shape("sphere", (0.3,)), R_GENERAL, n) == 0.3
    # a box reaches Σ |n_i| a_i with n in body components (R n)
    nb = R_GENERAL @ n
    box = Shape("box", (0.5, 0.4, 0.3))
    assert _support_distance(box, R_GENERAL, n) == pytest.approx(
        np.abs(nb) @ [0.5, 0.4, 0.3], rel=4 * EPS
    )
    assert _support_distance(box, np.eye(3), n) == 0.3
    assert _support_distance(box, np.eye(3), np.array([1.0, 0.0, 0.0])) == 0.5
    # a cylinder: the rim r √(1 − n3²) plus the half length h |n3|
    cyl = Shape("cylinder", (0.2, 0.7))
    assert _support_distance(cyl, R_GENERAL, n) == pytest.approx(
        0.2 * math.sqrt(1 - nb[2] ** 2) + 0.7 * abs(nb[2]), rel=4 * EPS
    )
    assert _support_distance(cyl, np.eye(3), n) == 0.7
    assert _support_distance(cyl, np.eye(3), np.array([0.0, 1.0, 0.0])) == 0.2


def test_approach_speeds_of_a_fall_a_throw_and_a_pair():
    from mechanics.conformance.adapters.drake import _approach_speeds

    # a ball whose lowest point is 1 m above the ground z = 0.5, at rest: √(2 g · 1)
    fall = _scenario(
        [_ball(position=(0.0, 0.0, 1.6))],
        gravity=(0.0, 0.0, -9.81),
        ground=Ground(0.7, (0.0, 0.0, 1.0), 0.5),
    )
    ((i, j, e, v),) = _approach_speeds(fall)
    assert (i, j, e) == (0, -1, 0.7)
    assert v == pytest.approx(math.sqrt(2 * G), rel=4 * EPS)
    # thrown down at 3 m/s without gravity: 3; thrown up: never arrives, the 1 m/s default
    down = _scenario(
        [_ball(position=(0.0, 0.0, 2.0), velocity=(1.0, 0.0, -3.0))], ground=Ground(0.7)
    )
    assert _approach_speeds(down) == [(0, -1, 0.7, 3.0)]
    up = _scenario([_ball(position=(0.0, 0.0, 2.0), velocity=(0.0, 0.0, 3.0))], ground=Ground(0.7))
    assert _approach_speeds(up) == [(0, -1, 0.7, 1.0)]
    # a box: the gap to its lowest point
    box = _box(position=(0.0, 0.0, 2.0))
    tilted = _scenario([box], gravity=(0.0, 0.0, -4.0), ground=Ground(0.5, (0.0, 0.0, 1.0), 0.0))
    ((_, _, _, v),) = _approach_speeds(tilted)
    assert v == pytest.approx(math.sqrt(2 * 4.0 * (2.0 - 0.3)), rel=4 * EPS)
    # shapeless and pivoted bodies do not touch the ground; a pair: the relative speed
    two = _scenario(
        [
            _ball(velocity=(1.0, 0.0, 0.0)),
            _ball(position=(1.0, 0.0, 0.0), velocity=(-2.0, 4.0, 0.0)),
            _ball(shape=None),
        ],
        ground=Ground(0.5),
        pair_restitution=((0, 1, 0.9),),
        pivot=Pivot(1, (0.0, 0.0, -0.1)),
    )
    assert _approach_speeds(two) == [(0, -1, 0.5, 1.0), (0, 1, 0.9, 5.0)]
    still = _scenario([_ball(), _ball(position=(1.0, 0.0, 0.0))], pair_restitution=((0, 1, 0.9),))
    assert _approach_speeds(still) == [(0, 1, 0.9, 1.0)]


def test_frame_with_axis_is_right_handed_with_the_axis_in_its_place():
    from mechanics.conformance.adapters.drake import _frame_with_axis

    for a in ([0.0, 0.0, 2.0], [1.0, -2.0, 0.5], [3.0, 0.0, 0.0]):
        for k in range(3):
            F = _frame_with_axis(np.array(a), k)
            np.testing.assert_allclose(
                F[:, k], np.array(a) / np.linalg.norm(a), atol=4 * EPS, rtol=0
            )
            np.testing.assert_allclose(F.T @ F, np.eye(3), atol=4 * EPS, rtol=0)
            assert np.linalg.det(F) == pytest.approx(1.0, abs=4 * EPS)


def test_drake_refuses_a_pivot_line_along_gravity_and_names_itself():
    _drake()
    from mechanics.conformance.adapters.drake import DrakeAdapter, _version, variants

    a = DrakeAdapter()
    reason = (
        "the pivot's line to G starts along gravity, where Drake's only ball joint "
        "(BallRpyJoint, roll-pitch-yaw) is singular"
    )
    hanging = _scenario([_box()], gravity=(0.0, 0.0, -9.81), pivot=Pivot(0, (0.0, 0.0, 0.3)))
    assert a.supports(hanging) == reason
    # without gravity the joint's F z axis is space z: the same line is singular
    assert a.supports(dataclasses.replace(hanging, gravity=(0.0, 0.0, 0.0))) == reason
    # gravity along x: a line along z is fine, along x is not
    sideways = dataclasses.replace(hanging, gravity=(-9.81, 0.0, 0.0))
    assert a.supports(sideways) is None
    assert a.supports(dataclasses.replace(sideways, pivot=Pivot(0, (0.3, 0.0, 0.0)))) == reason
    # 2e-3 rad off the line: supported (the limit is 1e-3)
    off = (0.3 * math.sin(2e-3), 0.0, -0.3 * math.cos(2e-3))
    assert a.supports(dataclasses.replace(hanging, pivot=Pivot(0, off))) is None
    # a pivot at G: no line
    assert a.supports(dataclasses.replace(hanging, pivot=Pivot(0, (0.0, 0.0, 0.0)))) is None
    rocket = _scenario([_box()], thrust=Thrust(0, 0.1, 10.0, 1.0), pivot=Pivot(0, (0.0, 0.0, 0.3)))
    assert a.supports(rocket) == common_unsupported(rocket)
    with pytest.raises(MechanicsValueError) as info:
        a.run(hanging, 0.125)
    assert str(info.value) == "scenario 'made_up': Drake cannot run it: " + reason
    v = _version()
    assert a.name == f"Drake {v} discrete (lagged), point contact"
    c = DrakeAdapter("continuous", "hydroelastic")
    assert c.name == f"Drake {v} continuous (RK3, accuracy 1e-08), hydroelastic contact"
    assert (a.takes_step, c.takes_step) == (True, False)
    assert repr(c) == "DrakeAdapter('continuous', 'hydroelastic')"
    assert [(x.mode, x.contact) for x in variants()] == [
        ("discrete", "point"),
        ("discrete", "hydroelastic"),
        ("continuous", "point"),
        ("continuous", "hydroelastic"),
    ]


def test_drake_holds_the_attitude_and_world_omega_it_is_given():
    _drake()
    from mechanics.conformance.adapters.drake import DrakeAdapter

    w = SPIN
    s = _scenario([_spun_box()])
    a = DrakeAdapter()
    sim, plant, bodies = a.build(s, 0.125)
    ctx = plant.GetMyContextFromRoot(sim.get_context())
    X = plant.EvalBodyPoseInWorld(ctx, bodies[0])
    # Drake's R_WB has the body axes as columns: (^A R^O)ᵀ; its velocity is in world
    np.testing.assert_allclose(X.rotation().matrix(), R_Z.T, atol=ROUNDTRIP_ATOL, rtol=0)
    np.testing.assert_allclose(
        X.rotation().ToQuaternion().wxyz(), Q_Z_WXYZ, atol=ROUNDTRIP_ATOL, rtol=0
    )
    np.testing.assert_allclose(X.translation(), [1.0, 2.0, 3.0], atol=ROUNDTRIP_ATOL, rtol=0)
    V = plant.EvalBodySpatialVelocityInWorld(ctx, bodies[0])
    np.testing.assert_allclose(V.rotational(), R_Z.T @ w, atol=ROUNDTRIP_ATOL, rtol=0)
    np.testing.assert_allclose(V.translational(), [0.5, 0.0, -1.0], atol=ROUNDTRIP_ATOL, rtol=0)
    pos, vel, R, om = a._read(plant, ctx, bodies)
    np.testing.assert_allclose(R[0], R_Z, atol=ROUNDTRIP_ATOL, rtol=0)
    np.testing.assert_allclose(om[0], w, atol=ROUNDTRIP_ATOL, rtol=0)
    np.testing.assert_allclose(pos[0], [1.0, 2.0, 3.0], atol=ROUNDTRIP_ATOL, rtol=0)
    np.testing.assert_allclose(vel[0], [0.5, 0.0, -1.0], atol=ROUNDTRIP_ATOL, rtol=0)


def test_drake_discrete_free_fall_and_the_work_of_a_continuous_run():
    _drake()
    from mechanics.conformance.adapters.drake import DrakeAdapter

    # the discrete update v ← v + h g, x ← x + h v (the new v): after n steps
    # v0 + g n h and x0 + v0 n h + g h² n(n + 1)/2
    h = 2.0**-5
    s = _scenario(
        [_box(position=(1.0, 2.0, 3.0), velocity=(0.5, 0.0, 4.0))], gravity=(0.0, 0.0, -9.81)
    )
    a = DrakeAdapter()
    tr = a.run(s, h)
    n = np.array([0, 4, 8])
    np.testing.assert_allclose(tr.velocity[:, 0, 2], 4.0 - G * n * h, atol=STEP_ATOL, rtol=0)
    np.testing.assert_allclose(
        tr.position[:, 0, 2],
        3.0 + 4.0 * n * h - G * h * h * n * (n + 1) / 2,
        atol=STEP_ATOL,
        rtol=0,
    )
    np.testing.assert_allclose(tr.position[:, 0, 0], 1.0 + 0.5 * n * h, atol=STEP_ATOL, rtol=0)
    assert a.last_stats == {}
    c = DrakeAdapter("continuous")
    tr = c.run(s, None)
    t = np.array(s.sample_times)
    np.testing.assert_allclose(
        tr.position[:, 0, 2], 3.0 + 4.0 * t - G * t * t / 2, atol=2**10 * STEP_ATOL, rtol=0
    )
    assert set(c.last_stats) == {"steps", "derivative_evaluations"}
    assert 0 < c.last_stats["steps"] < c.last_stats["derivative_evaluations"]


def test_drake_drops_only_its_deformable_half_space_notice(monkeypatch):
    import logging

    # start from a drake logger without filters: another test may have built an adapter
    monkeypatch.setattr(logging.getLogger("drake"), "filters", [])

    from mechanics.conformance.adapters.drake import (
        _DEFORMABLE_NOTICE,
        _DropDeformableNotice,
        _quiet_deformable_notice,
    )

    f = _DropDeformableNotice()

    def record(msg):
        return logging.LogRecord("drake", logging.WARNING, __file__, 1, msg, None, None)

    assert f.filter(record(f"x {_DEFORMABLE_NOTICE} y")) is False
    assert f.filter(record("another warning")) is True
    _quiet_deformable_notice()
    _quiet_deformable_notice()
    log = logging.getLogger("drake")
    assert sum(isinstance(x, _DropDeformableNotice) for x in log.filters) == 1


#: the dissipation Drake holds against our own root of the Hunt–Crossley law (brentq to
#: 1e-15 on c ~ 0.5, the mean of up to three values): 2^12 eps
HC_RTOL = 2**12 * EPS


def _hc_by_brentq(e, v):
    from scipy.optimize import brentq

    # the law is −(1 − e²) c²/2 + O(c³) near 0 and → +∞ at 1/e; e ≤ 0.8 roots are > 0.1
    c = brentq(lambda c: _hc_law(c, e), 0.01, (1 - 1e-12) / e, xtol=1e-16, rtol=4 * EPS)
    return c / v


@pytest.mark.parametrize("contact", ["point", "hydroelastic"])
def test_drake_geometry_sizes_dissipations_and_filters(contact):
    pd = _drake()
    from mechanics.conformance.adapters.drake import HYDRO_MODULUS, RESOLUTION_HINT, DrakeAdapter

    bodies = (
        Body("a", 1.0, (1.0, 2.0, 2.5), Shape("box", (0.5, 0.4, 0.3)), position=(0.0, 0.0, 2.0)),
        Body("b", 1.0, (1.0, 1.0, 2.0), Shape("cylinder", (0.2, 0.7)), position=(2.0, 0.0, 2.0)),
        Body("c", 0.5, (0.002,) * 3, Shape("sphere", (0.1,)), position=(4.0, 0.0, 2.0)),
    )
    s = _scenario(
        bodies,
        gravity=(0.0, 0.0, -9.81),
        ground=Ground(0.5, (0.0, 0.0, 1.0), 0.25),
        pair_restitution=((0, 2, 0.8),),
    )
    sim, _, _ = DrakeAdapter("discrete", contact).build(s, 0.125)
    (sg,) = [x for x in sim.get_system().GetSystems() if isinstance(x, pd.SceneGraph)]
    insp = sg.model_inspector()
    gid = {insp.GetName(g): g for g in insp.GetAllGeometryIds()}
    box, cyl, sph = (insp.GetShape(gid[k]) for k in ("g0", "g1", "g2"))
    assert (box.width(), box.depth(), box.height()) == (1.0, 0.8, 0.6)  # full widths
    assert (cyl.radius(), cyl.length()) == (0.2, 1.4)
    assert sph.radius() == 0.1
    ground = insp.GetPoseInFrame(gid["ground"])
    np.testing.assert_allclose(ground.translation(), [0.0, 0.0, 0.25], atol=4 * EPS, rtol=0)
    np.testing.assert_allclose(
        ground.rotation().matrix()[:, 2], [0.0, 0.0, 1.0], atol=4 * EPS, rtol=0
    )
    # the approach speeds by hand: each body's lowest point falls to the plane z = 0.25
    fall = {
        k: math.sqrt(2 * G * (2.0 - 0.25 - reach))
        for k, reach in (("g0", 0.3), ("g1", 0.7), ("g2", 0.1))
    }
    ground_d = {k: _hc_by_brentq(0.5, v) for k, v in fall.items()}
    pair_d = _hc_by_brentq(0.8, 1.0)  # the pair starts at the same velocity: 1 m/s
    want = {
        "g0": (ground_d["g0"] + pair_d) / 2,
        "g1": ground_d["g1"],
        "g2": (ground_d["g2"] + pair_d) / 2,
        "ground": sum(ground_d.values()) / 3,
    }
    for name, d in want.items():
        props = insp.GetProximityProperties(gid[name])
        assert props.GetProperty("material", "hunt_crossley_dissipation") == pytest.approx(
            d, rel=HC_RTOL
        ), name
        assert props.GetProperty("material", "coulomb_friction").static_friction() == 0.0
        assert props.GetProperty("material", "coulomb_friction").dynamic_friction() == 0.0
        compliant = props.HasProperty("hydroelastic", "hydroelastic_modulus")
        assert compliant == (contact == "hydroelastic" and name != "ground"), name
        if compliant:
            assert props.GetProperty("hydroelastic", "hydroelastic_modulus") == HYDRO_MODULUS
            assert props.GetProperty("hydroelastic", "resolution_hint") == RESOLUTION_HINT
        assert props.HasProperty("hydroelastic", "compliance_type") == (contact == "hydroelastic")
    # only the listed pair and the ground touch
    assert insp.CollisionFiltered(gid["g0"], gid["g1"])
    assert insp.CollisionFiltered(gid["g1"], gid["g2"])
    assert not insp.CollisionFiltered(gid["g0"], gid["g2"])
    assert not any(insp.CollisionFiltered(gid[k], gid["ground"]) for k in ("g0", "g1", "g2"))


@pytest.mark.parametrize(
    ("variant", "substeps", "iterations"), [("default", 0, 50), ("fine", 8, 200)]
)
def test_pybullet_engine_parameters_of_each_variant(variant, substeps, iterations):
    p = _pybullet()
    from mechanics.conformance.adapters.pybullet import PyBulletAdapter

    s = _scenario([_ball(position=(0.0, 0.0, 1.0))], gravity=(0.5, -1.0, -9.81), ground=Ground(0.5))
    other = p.connect(p.DIRECT)
    try:
        cid, _ = PyBulletAdapter(variant).build(s, 2.0**-7)
    finally:
        p.disconnect(other)
    try:
        got = p.getPhysicsEngineParameters(physicsClientId=cid)
    finally:
        p.disconnect(cid)
    assert got["fixedTimeStep"] == 2.0**-7
    assert got["numSubSteps"] == substeps
    assert got["numSolverIterations"] == iterations
    assert (
        got["gravityAccelerationX"],
        got["gravityAccelerationY"],
        got["gravityAccelerationZ"],
    ) == (
        0.5,
        -1.0,
        -9.81,
    )


def test_pybullet_shapes_ground_restitutions_and_contact_filters():
    p = _pybullet()
    from mechanics.conformance.adapters.pybullet import PyBulletAdapter

    bodies = (
        Body("a", 1.0, (1.0, 2.0, 2.5), Shape("box", (0.5, 0.4, 0.3)), position=(0.0, 0.0, 2.0)),
        Body("b", 1.0, (1.0, 1.0, 2.0), Shape("cylinder", (0.2, 0.7)), position=(0.1, 0.0, 2.0)),
        Body("c", 0.5, (0.002,) * 3, Shape("sphere", (0.1,)), position=(0.0, 0.1, 2.0)),
    )
    # all three overlap; only (0, 2) is listed: e 0.25 = 0.5 · 0.5 with the ground's 0.5
    s = _scenario(
        bodies, ground=Ground(0.5, (0.0, 0.0, 1.0), 0.25), pair_restitution=((0, 2, 0.25),)
    )
    cid, ids = PyBulletAdapter().build(s, 0.01)
    try:
        kw = {"physicsClientId": cid}
        shapes = [p.getCollisionShapeData(uid, link, **kw)[0] for uid, link in ids]
        assert [(x[2], x[3]) for x in shapes] == [
            (p.GEOM_BOX, (1.0, 0.8, 0.6)),  # full extents
            (p.GEOM_CYLINDER, (1.4, 0.2, 0.0)),  # length 2h, radius
            (p.GEOM_SPHERE, (0.1, 0.1, 0.1)),
        ]
        assert [p.getDynamicsInfo(uid, link, **kw)[5] for uid, link in ids] == [0.5, 0.5, 0.5]
        ground = p.getNumBodies(**kw) - len(ids) - 1  # the ground is made first
        plane = p.getCollisionShapeData(ground, -1, **kw)[0]
        assert (plane[2], plane[3]) == (p.GEOM_PLANE, (0.0, 0.0, 1.0))
        assert p.getBasePositionAndOrientation(ground, **kw)[0] == (0.0, 0.0, 0.25)
        assert p.getDynamicsInfo(ground, -1, **kw)[5] == 1.0
        p.performCollisionDetection(**kw)
        (a, _), (b, _), (c, _) = ids
        assert p.getContactPoints(a, c, **kw)
        assert not p.getContactPoints(a, b, **kw)
        assert not p.getContactPoints(b, c, **kw)
    finally:
        p.disconnect(cid)


def test_pybullet_pivot_is_a_free_spherical_joint_with_g_off_the_link_frame():
    p = _pybullet()
    from mechanics.conformance.adapters.pybullet import PyBulletAdapter

    s = _scenario(
        [_box()], gravity=(0.0, 0.0, -9.81), pivot=Pivot(0, (0.0, 0.0, -0.25), (1.0, 2.0, 3.0))
    )
    cid, ((uid, link),) = PyBulletAdapter().build(s, 0.01)
    try:
        kw = {"physicsClientId": cid}
        assert link == 0
        assert p.getBasePositionAndOrientation(uid, **kw)[0] == (1.0, 2.0, 3.0)
        info = p.getDynamicsInfo(uid, 0, **kw)
        assert info[0] == 2.0
        np.testing.assert_array_equal(info[2], [1.0, 2.0, 2.5])
        np.testing.assert_array_equal(info[3], [0.0, 0.0, 0.25])  # G = −point
        joint = p.getJointInfo(uid, 0, **kw)
        assert joint[2] == p.JOINT_SPHERICAL
        assert joint[6] == 0.0  # no joint damping
        assert p.getDynamicsInfo(uid, -1, **kw)[0] == 0.0  # a fixed, massless base
    finally:
        p.disconnect(cid)


def test_mujoco_fails_loudly_when_its_model_does_not_hold_the_scenarios_body():
    _mujoco()
    from mechanics.conformance.adapters.mujoco import MuJoCoAdapter
    from mechanics.conformance.protocol import ConformanceError

    class Altered(MuJoCoAdapter):
        def __init__(self, old, new):
            super().__init__()
            self.old, self.new = old, new

        def mjcf(self, scenario, step):
            return super().mjcf(scenario, step).replace(self.old, self.new)

    s = _scenario([_box(position=(0.0, 0.0, 1.0))])
    for old, new in (
        ('diaginertia="1.0 2.0 2.5"', 'diaginertia="1.0 2.0 2.6"'),
        ('mass="2.0"', 'mass="2.5"'),
        ('diaginertia="1.0 2.0 2.5"', 'fullinertia="1.0 2.0 2.5 0.1 0 0"'),
    ):
        with pytest.raises(ConformanceError) as info:
            Altered(old, new).build(s, 0.125)
        msg = str(info.value)
        assert msg.startswith(
            "scenario 'made_up': MuJoCo changed body 'box''s mass or principal inertia: mass "
        )
        assert msg.endswith("; the scenario's are 2.0, [1.  2.  2.5]")
    # within 4 eps: the same model
    model, _ = Altered('mass="2.0"', f'mass="{2.0 * (1 + 2 * EPS)!r}"').build(s, 0.125)
    assert model.body_mass[1] == 2.0 * (1 + 2 * EPS)
    # an inertia off by exactly 4 eps of the largest moment (2.5 + 10 eps, exact in
    # binary: five ulps of 2.5) is still the same model
    J3 = 2.5 + 10 * EPS
    model, _ = Altered('diaginertia="1.0 2.0 2.5"', f'diaginertia="1.0 2.0 {J3!r}"').build(s, 0.125)
    assert model.body_inertia[1][2] == J3


def test_pybullet_fails_loudly_and_disconnects_when_it_does_not_hold_the_body():
    p = _pybullet()
    from mechanics.conformance.adapters.pybullet import PyBulletAdapter
    from mechanics.conformance.protocol import ConformanceError

    class Heavier:
        """pybullet, but its dynamics info reports the mass 1 % off (or the inertia)."""

        def __init__(self, which):
            self.which, self.clients = which, []

        def __getattr__(self, name):
            return getattr(p, name)

        def connect(self, *args, **kw):
            self.clients.append(p.connect(*args, **kw))
            return self.clients[-1]

        def getDynamicsInfo(self, *args, **kw):
            info = list(p.getDynamicsInfo(*args, **kw))
            if self.which == "mass":
                info[0] *= 1.01
            else:
                info[2] = (info[2][0], info[2][1], info[2][2] * 1.01)
            return tuple(info)

    s = _scenario([_box(position=(0.0, 0.0, 1.0))])
    for which, held in (
        ("mass", "mass 2.02 and inertia (1.0, 2.0, 2.5)"),
        ("inertia", "mass 2.0 and inertia (1.0, 2.0, 2.525)"),
    ):
        a = PyBulletAdapter()
        a._p = Heavier(which)
        with pytest.raises(ConformanceError) as info:
            a.build(s, 0.125)
        assert str(info.value) == (
            f"scenario 'made_up': PyBullet holds body 'box' with {held}, not the scenario's 2.0, [1.  2.  2.5]"
        )
        (cid,) = a._p.clients
        assert p.getConnectionInfo(cid)["isConnected"] == 0


def test_pybullet_names_its_own_client_in_every_call():
    """Every call the adapter makes after connecting names that client
    (physicsClientId): a user's own simulation in the same process, on PyBullet's default
    client, is never touched, the tuned contact's settings included."""
    p = _pybullet()
    from mechanics.conformance.adapters.pybullet import PyBulletAdapter

    class Spy:
        def __init__(self):
            self.calls = []

        def __getattr__(self, name):
            f = getattr(p, name)
            if not callable(f):
                return f

            def call(*args, **kw):
                rest = {k: v for k, v in kw.items() if k != "physicsClientId"}
                self.calls.append((name, kw.get("physicsClientId"), args, rest))
                return f(*args, **kw)

            return call

    s = _scenario([_box(position=(0.0, 0.0, 1.0))], ground=Ground(0.5))
    a = PyBulletAdapter("default", "tuned")
    a._p = spy = Spy()
    cid, _ = a.build(s, 0.125)
    try:
        named = [c[:2] for c in spy.calls if c[0] != "connect"]
        assert ("setPhysicsEngineParameter", cid) in named
        assert [c for c in named if c[1] != cid] == []
        # the tuned contact: no contact processing margin on the ground's base (link −1)
        assert ("changeDynamics", cid, (0, -1), {"contactProcessingThreshold": 0.0}) in spy.calls
    finally:
        p.disconnect(cid)


def test_pybullet_lays_a_tilted_ground_along_its_normal_at_its_height():
    """Ground n·x = 0.5 with n = (0.6, 0, 0.8): PyBullet's plane shape carries that normal
    and its base sits at height·n = (0.3, 0, 0.4), a point of the plane."""
    p = _pybullet()
    from mechanics.conformance.adapters.pybullet import PyBulletAdapter

    s = _scenario(
        [_box(position=(0.0, 0.0, 3.0))], ground=Ground(0.5, normal=(0.6, 0.0, 0.8), height=0.5)
    )
    cid, ids = PyBulletAdapter().build(s, 0.125)
    try:
        ((uid, _),) = ids
        (ground,) = [b for b in range(p.getNumBodies(physicsClientId=cid)) if b != uid]
        ((_, _, kind, normal, *_),) = p.getCollisionShapeData(ground, -1, physicsClientId=cid)
        assert kind == p.GEOM_PLANE
        np.testing.assert_allclose(normal, [0.6, 0.0, 0.8], rtol=0, atol=ROUNDTRIP_ATOL)
        x, _ = p.getBasePositionAndOrientation(ground, physicsClientId=cid)
        np.testing.assert_allclose(x, [0.3, 0.0, 0.4], rtol=0, atol=ROUNDTRIP_ATOL)
    finally:
        p.disconnect(cid)


def test_the_mjcf_closes_its_world_body_on_a_line_of_its_own():
    _mujoco()
    from mechanics.conformance.adapters.mujoco import MuJoCoAdapter

    text = MuJoCoAdapter().mjcf(_scenario([_box(position=(0.0, 0.0, 1.0))]), 0.125)
    lines = text.splitlines()
    assert lines.count("  <worldbody>") == lines.count("  </worldbody>") == 1
    assert lines[-1] == "</mujoco>"


def test_drake_fails_loudly_when_its_plant_does_not_hold_the_body():
    pd = _drake()
    from mechanics.conformance.adapters.drake import DrakeAdapter
    from mechanics.conformance.protocol import ConformanceError

    class Off:
        """pydrake, but the moments it is given come out 1 % off on axis 3."""

        def __getattr__(self, name):
            return getattr(pd, name)

        @staticmethod
        def RotationalInertia(a, b, c):
            return pd.RotationalInertia(a, b, c * 1.01)

    a = DrakeAdapter()
    a._pd = Off()
    with pytest.raises(ConformanceError) as info:
        a.build(_scenario([_box(position=(0.0, 0.0, 1.0))]), 0.125)
    msg = str(info.value)
    assert msg.startswith(
        "scenario 'made_up': Drake holds body 'box' with mass 2.0 and inertia [1. "
    )
    assert "2.525" in msg
    assert msg.endswith(", not the scenario's 2.0, [1.  2.  2.5]")


@pytest.mark.parametrize(
    ("mode", "contact"), [("discrete", "point"), ("continuous", "hydroelastic")]
)
def test_drake_plant_settings_of_each_mode(mode, contact):
    pd = _drake()
    from mechanics.conformance.adapters.drake import CONTINUOUS_ACCURACY, DrakeAdapter

    s = _scenario([_ball(position=(0.0, 0.0, 1.0))], gravity=(0.5, -1.0, -9.81))
    sim, plant, _ = DrakeAdapter(mode, contact).build(s, 2.0**-7)
    np.testing.assert_array_equal(plant.gravity_field().gravity_vector(), [0.5, -1.0, -9.81])
    if mode == "discrete":
        assert plant.time_step() == 2.0**-7
        assert plant.get_contact_model() == pd.ContactModel.kPoint
    else:
        assert plant.time_step() == 0.0
        assert plant.get_contact_model() == pd.ContactModel.kHydroelasticWithFallback
        assert sim.get_integrator().get_target_accuracy() == CONTINUOUS_ACCURACY
    assert sim.get_context().get_time() == 0.0


def test_the_scene_engine_takes_sample_times_uniform_to_rounding_only():
    p = SCENARIOS["parabola"]
    # 2^6 eps of max(duration, 1): 4 eps off the end is uniform, 1e-12 is not
    near = dataclasses.replace(p, sample_times=(0.0, 0.75, 1.5 * (1 + 4 * EPS)))
    assert isinstance(scene_from_scenario(near), dict)
    far = dataclasses.replace(p, sample_times=(0.0, 0.75, 1.5 + 1e-12))
    assert scene_from_scenario(far) == "the scene engine samples uniformly from 0 to the duration"
    # a short run: the tolerance is 2^6 eps absolute (of 1 s), not of its 0.25 s
    short = dataclasses.replace(p, duration=0.25, sample_times=(0.0, 0.125, 0.25 + 2**5 * EPS))
    assert isinstance(scene_from_scenario(short), dict)


def test_the_scene_engine_adapter_keeps_its_method_and_tolerances():
    a = SceneEngineAdapter("integrate", rtol=1e-9, atol=1e-12)
    assert (a.method, a.rtol, a.atol) == ("integrate", 1e-9, 1e-12)
    b = SceneEngineAdapter()
    assert (b.method, b.rtol, b.atol) == ("integrate", None, None)


def test_step_counts_tolerance_is_2_to_the_6_eps_of_a_second_below_one_second():
    s = _scenario([_box()])
    # near 0.5 s the allowance is 2^6 eps absolute (of max(T, 1) = 1 s)
    ok = dataclasses.replace(s, sample_times=(0.0, 0.5 + 32 * EPS))
    np.testing.assert_array_equal(step_counts(ok, 0.5)[1], [0, 1])
    off = dataclasses.replace(s, sample_times=(0.0, 0.5 + 100 * EPS))
    with pytest.raises(MechanicsValueError, match=r"is not a whole number of steps 0.5$"):
        step_counts(off, 0.5)


def test_body_rows_are_float_arrays_whatever_numbers_the_bodies_hold():
    b = Body(
        "ints",
        1,
        (1, 2, 3),
        position=(1, 2, 3),
        velocity=(4, 5, 6),
        R_A_O=((1, 0, 0), (0, 1, 0), (0, 0, 1)),
        omega=(0, 0, 7),
    )
    rows = body_rows(_scenario([b]))
    assert [x.dtype for x in rows] == [np.float64] * 4
    assert [x.shape for x in rows] == [(1, 3), (1, 3), (1, 3, 3), (1, 3)]


def test_drake_takes_integer_numbers_and_returns_float_times():
    _drake()
    from mechanics.conformance.adapters.drake import DrakeAdapter

    # a pivot point, sample times and a duration written as integers
    # body axis 3 along −y (row 3 of ^A R^O): G at (0, −1, 0), the arm horizontal
    top = Body("top", 1, (1, 1, 2), position=(0, -1, 0), R_A_O=((1, 0, 0), (0, 0, 1), (0, -1, 0)))
    s = Scenario(
        "ints",
        "integers",
        "(none)",
        (top,),
        1,
        (0, 1),
        gravity=(0, 0, -10),
        pivot=Pivot(0, (0, 0, -1)),
    )
    tr = DrakeAdapter().run(s, 0.5)
    assert tr.t.dtype == np.float64
    np.testing.assert_array_equal(tr.t, [0.0, 1.0])
    np.testing.assert_allclose(tr.position[0, 0], [0.0, -1.0, 0.0], atol=ROUNDTRIP_ATOL, rtol=0)


def test_pybullet_builds_a_cylinder_on_its_own_server_with_another_open():
    # the cylinder's collision shape, like every call, names the adapter's server: made on
    # the other one, the body would get no shape (or another server's) of its own
    p = _pybullet()
    from mechanics.conformance.adapters.pybullet import PyBulletAdapter

    cyl = Body("c", 1.0, (1.0, 1.0, 2.0), Shape("cylinder", (0.2, 0.7)), position=(0.0, 0.0, 2.0))
    s = _scenario([cyl], ground=Ground(0.5))
    a = PyBulletAdapter("default", "tuned")
    other = p.connect(p.DIRECT)
    try:
        cid, ids = a.build(s, 0.01)
    finally:
        p.disconnect(other)
    try:
        ((uid, _),) = ids
        (shape,) = p.getCollisionShapeData(uid, -1, physicsClientId=cid)
        assert shape[2] == p.GEOM_CYLINDER
        # PyBullet reports a cylinder's (length, radius, 0): the full length 2h = 1.4
        np.testing.assert_allclose(shape[3][:2], [1.4, 0.2], atol=ROUNDTRIP_ATOL, rtol=0)
    finally:
        p.disconnect(cid)


@pytest.mark.parametrize(("field", "value"), [("variant", "coarse"), ("contact", "soft")])
def test_pybullet_refuses_an_unknown_option_naming_the_engine_and_the_choices(field, value):
    _pybullet()
    from mechanics.conformance.adapters.pybullet import CONTACTS, VARIANTS, PyBulletAdapter

    allowed = VARIANTS if field == "variant" else CONTACTS
    with pytest.raises(UnknownOptionError) as info:
        PyBulletAdapter(**{field: value})
    assert str(info.value) == f"PyBullet {field} must be one of {allowed}; got {value!r}"


def test_the_scene_engine_adapter_takes_a_scenario_with_integer_fields():
    # a user's scenario may be written with integers (a ground normal (0, 0, 1), g = -10,
    # whole seconds): the scene built from it holds floats, which the scene file's parser
    # requires, and the run's times come back as floats
    ball = SCENARIOS["bouncing_ball"]
    s = dataclasses.replace(
        ball,
        ground=Ground(1, (0, 0, 1), 0),
        gravity=(0, 0, -10),
        duration=1,
        sample_times=(0, 1),
    )
    scene = scene_from_scenario(s)
    (imp,) = [e for e in scene["effects"] if e["type"] == "impact"]
    assert all(isinstance(x, float) for x in imp["plane_normal"])
    assert all(isinstance(x, float) for x in imp["plane_point"])
    tr = SceneEngineAdapter().run(s, None)
    assert tr.t.dtype == np.float64
    np.testing.assert_array_equal(tr.t, [0.0, 1.0])


def test_uniform_boxes_and_cylinders_collide_in_the_scene_engine_with_their_edges():
    """A colliding box or cylinder maps to the scene engine's shape (edges 2a, 2b, 2c;
    height 2h) where its moments are its shape's at uniform density; else refused."""
    b = SCENARIOS["bouncing_ball"]
    a, bb, c, m = 0.1, 0.2, 0.3, 2.0
    J = (m * (bb * bb + c * c) / 3, m * (a * a + c * c) / 3, m * (a * a + bb * bb) / 3)
    box = _box(mass=m, inertia=J, shape=Shape("box", (a, bb, c)), position=(0.0, 0.0, 2.0))
    scene = scene_from_scenario(dataclasses.replace(b, bodies=(box,)))
    (entry,) = scene["bodies"]
    assert (entry["shape"], entry["a"], entry["b"], entry["c"]) == ("box", 2 * a, 2 * bb, 2 * c)
    r, h = 0.2, 0.05
    side = m * (3 * r * r + 4 * h * h) / 12
    cyl = _box(mass=m, inertia=(side, side, m * r * r / 2), shape=Shape("cylinder", (r, h)))
    cyl = dataclasses.replace(cyl, position=(0.0, 0.0, 2.0))
    (entry,) = scene_from_scenario(dataclasses.replace(b, bodies=(cyl,)))["bodies"]
    assert (entry["shape"], entry["radius"], entry["height"]) == ("cylinder", r, 2 * h)
    off = dataclasses.replace(cyl, inertia=(side, side, m * r * r / 3))
    assert "of uniform density" in scene_from_scenario(dataclasses.replace(b, bodies=(off,)))
