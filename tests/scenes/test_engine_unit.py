"""Unit tests of the engine's small pieces (:mod:`mechanics.scenes.engine`), each against
a hand derivation: the initial attitude R3(φ) R1(θ) R3(ψ) and the body ω from the Euler
rates (2.69) and back, a top's angles and d(cos θ)/dt = −sin θ θ̇, free flight
r0 + v0 τ + ½ g τ², the sum of gravities, the exact flow chosen for each effect set, the
whole-scene checks word for word, and the series of a short exact run."""

from __future__ import annotations

import functools
import math
from types import SimpleNamespace

import numpy as np
import pytest

from mechanics import kinematics as kin
from mechanics._floats import EPS
from mechanics.scenes import SceneError, flows, impacts, integrate, model, report
from mechanics.scenes.collision import StepFit
from mechanics.scenes.engine import Engine

from .builders import ball, box, point, scene

#: products and sums of a few sines and cosines of O(1) angles: a few roundings each
TRIG_ATOL = 8 * EPS
#: a central difference of step 1e-5: truncation h² |f'''|/6 ≈ 2e-11, rounding
#: eps/h ≈ 2e-11; 2^22 eps ≈ 9e-10 leaves a margin of 20
FD_ATOL = 2**22 * EPS
#: free flight r0 + v0 τ + ½ g τ² of O(10) numbers: three roundings of the largest term
FLIGHT_ATOL = 8 * 10 * EPS


def R1(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, s], [0.0, -s, c]])


def R3(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])


_scene = functools.partial(scene, name="unit", duration=1.0, samples=3)
#: the box of these tests: J = m (b² + c², a² + c², a² + b²)/12 = (0.05, 0.1, 0.13)
_box = functools.partial(box, "b", mass=12.0, a=0.3, b=0.2, c=0.1)


def _point(name="p", position=(0.0, 0.0, 0.0), velocity=(0.0, 0.0, 0.0), mass=1.0, **kw):
    """A point with its position and velocity always listed; ``kw``: body fields."""
    return point(name, position, velocity, mass=mass) | kw


def _ball(name="ball", position=(0.0, 0.0, 1.0), velocity=(0.0, 0.0, 0.0), radius=0.1):
    return ball(name, position, velocity, radius=radius)


GRAVITY = {"type": "gravity", "g": 9.81}
#: 0.5 kg of fuel burnt at 0.1 kg/s (burn-out at 5 s), exhaust speed 100 m/s, straight up
ROCKET = {
    "type": "thrust",
    "body": "p",
    "mass_flow": 0.1,
    "exhaust_speed": 100.0,
    "fuel_mass": 0.5,
    "direction": [0.0, 0.0, 1.0],
}


# ----------------------------------------------------------- attitudes and rates


def test_the_initial_attitude_is_r3_phi_r1_theta_r3_psi() -> None:
    want = R3(0.2) @ R1(0.5) @ R3(0.3)
    got = model.initial_attitude({"psi": 0.3, "theta": 0.5, "phi": 0.2})
    np.testing.assert_allclose(got, want, rtol=0, atol=TRIG_ATOL)
    # one angle alone is enough to leave the identity
    np.testing.assert_allclose(
        model.initial_attitude({"theta": 0.5}), R1(0.5), rtol=0, atol=TRIG_ATOL
    )
    np.testing.assert_allclose(
        model.initial_attitude({"phi": -1.0}), R3(-1.0), rtol=0, atol=TRIG_ATOL
    )
    np.testing.assert_array_equal(model.initial_attitude({}), np.eye(3))
    np.testing.assert_array_equal(model.initial_attitude({"position": [1.0, 2.0, 3.0]}), np.eye(3))


def test_the_body_omega_of_single_euler_rates() -> None:
    # θ̇ alone turns about the line of nodes, body components (cos φ, −sin φ, 0) θ̇
    np.testing.assert_allclose(
        kin.angular_velocity_from_euler_rates(0.0, 0.7, 0.0, 0.0, 2.0, 0.0),
        [2.0, 0.0, 0.0],
        rtol=0,
        atol=0,
    )
    np.testing.assert_allclose(
        kin.angular_velocity_from_euler_rates(0.0, 0.7, math.pi / 2, 0.0, 2.0, 0.0),
        [0.0, -2.0, 0.0],
        atol=TRIG_ATOL,
    )
    # φ̇ alone spins about the body axis e3
    np.testing.assert_array_equal(
        kin.angular_velocity_from_euler_rates(0.0, 0.7, 0.4, 0.0, 0.0, 3.0), [0.0, 0.0, 3.0]
    )
    # ψ̇ alone turns about the space z axis: its body components are row 3 of R
    R = model.initial_attitude({"theta": 0.7, "phi": 0.4})
    np.testing.assert_allclose(
        kin.angular_velocity_from_euler_rates(0.0, 0.7, 0.4, 1.5, 0.0, 0.0),
        1.5 * R[:, 2],
        rtol=0,
        atol=TRIG_ATOL,
    )


def test_the_body_omega_from_euler_rates_matches_the_attitude_derivative() -> None:
    """Ṙ = −[ω]× R for the passive ^A R^O: ω from a central difference of R(t) along
    ψ(t), θ(t), φ(t) moving at the given rates."""
    psi, theta, phi = 0.3, 1.1, -0.4
    psd, thd, phd = 0.9, -0.6, 2.3
    h = 1e-5

    def R(t):
        return R3(phi + phd * t) @ R1(theta + thd * t) @ R3(psi + psd * t)

    Rdot = (R(h) - R(-h)) / (2 * h)
    W = -Rdot @ R(0.0).T  # = [ω]×
    w_fd = np.array([W[2, 1], W[0, 2], W[1, 0]])
    w = kin.angular_velocity_from_euler_rates(0.0, theta, phi, psd, thd, phd)
    np.testing.assert_allclose(w, w_fd, rtol=0, atol=FD_ATOL)
    # and back: (θ̇, ψ̇, φ̇) from ω
    back = kin.euler_rates_from_angular_velocity(theta, phi, w)
    np.testing.assert_allclose(back, (psd, thd, phd), rtol=0, atol=TRIG_ATOL)
    # an initial table with rates gives that ω; with omega, omega itself
    ini = {"theta": theta, "phi": phi, "theta_dot": thd, "psi_dot": psd, "phi_dot": phd}
    np.testing.assert_allclose(model.initial_omega(ini), w, rtol=0, atol=0)
    np.testing.assert_array_equal(
        model.initial_omega({"omega": [1, 2, 3], "theta": 0.5}), [1.0, 2.0, 3.0]
    )
    np.testing.assert_array_equal(model.initial_omega({}), [0.0, 0.0, 0.0])
    # angles left out are 0: with φ = 0, ω = (θ̇, ψ̇ sin θ, ψ̇ cos θ + φ̇)
    np.testing.assert_allclose(
        model.initial_omega({"theta": theta, "theta_dot": thd, "psi_dot": psd}),
        [thd, psd * math.sin(theta), psd * math.cos(theta)],
        rtol=0,
        atol=TRIG_ATOL,
    )


def test_the_angles_of_a_top_and_the_rate_of_cos_theta() -> None:
    """Samples of R(t) = R3(φ) R1(θ) R3(ψ) with ψ passing π (unwrapped, not jumping
    by −2π), and ω from the rates: cos θ̇ = −sin θ θ̇."""
    t = np.array([0.0, 0.1, 0.2])
    psi, theta, phi = 3.0 + 1.0 * t, 1.0 + 0.5 * t, -3.0 - 1.2 * t
    R = np.array([R3(c) @ R1(b) @ R3(a) for a, b, c in zip(psi, theta, phi, strict=True)])
    w = np.array(
        [
            kin.angular_velocity_from_euler_rates(0.0, b, c, 1.0, 0.5, -1.2)
            for b, c in zip(theta, phi, strict=True)
        ]
    )
    out = report.top_angles(R, w)
    np.testing.assert_allclose(out["theta"], theta, rtol=0, atol=TRIG_ATOL)
    np.testing.assert_allclose(out["psi"], psi, rtol=0, atol=TRIG_ATOL)
    np.testing.assert_allclose(out["phi"], phi, rtol=0, atol=TRIG_ATOL)
    e3 = np.stack([np.sin(theta) * np.sin(psi), -np.sin(theta) * np.cos(psi), np.cos(theta)], -1)
    for k, c in enumerate("xyz"):
        np.testing.assert_allclose(out[f"axis_{c}"], e3[:, k], rtol=0, atol=TRIG_ATOL)
    np.testing.assert_allclose(out["cos_theta"], np.cos(theta), rtol=0, atol=TRIG_ATOL)
    np.testing.assert_allclose(out["cos_theta_dot"], -np.sin(theta) * 0.5, rtol=0, atol=TRIG_ATOL)


# ------------------------------------------------------------ small engine pieces


def test_free_flight_is_r0_plus_v0_tau_plus_half_g_tau_squared() -> None:
    eng = Engine(_scene([_point(position=(1.0, 2.0, 3.0), velocity=(4.0, -1.0, 2.0))], [GRAVITY]))
    g = np.array([0.0, 0.0, -9.81])
    np.testing.assert_array_equal(eng.model.uniform_gravity(), g)
    at = flows.free_flight(eng.model, 0.5, eng.y0, g, {})
    r, v, _, _ = eng.layout.gather(at(1.5))  # τ = 1
    np.testing.assert_allclose(r[0], [5.0, 1.0, 5.0 - 4.905], rtol=0, atol=FLIGHT_ATOL)
    np.testing.assert_allclose(v[0], [4.0, -1.0, 2.0 - 9.81], rtol=0, atol=FLIGHT_ATOL)
    both = at(np.array([0.5, 1.5]))
    assert both.shape == (2, eng.y0.size)
    np.testing.assert_array_equal(both[0], eng.y0)


def test_the_gravities_of_a_scene_add_up() -> None:
    down = {"type": "gravity", "g": 2.0}
    side = {"type": "gravity", "g": 3.0, "direction": [1.0, 0.0, 0.0]}
    eng = Engine(_scene([_point()], [down, side]))
    np.testing.assert_allclose(eng.model.uniform_gravity(), [3.0, 0.0, -2.0], rtol=0, atol=0)
    np.testing.assert_array_equal(Engine(_scene([_point()])).model.uniform_gravity(), np.zeros(3))


def test_masses_stay_m0_without_mass_loss() -> None:
    eng = Engine(_scene([_point(mass=2.0), _point("q", position=(5, 0, 0), mass=3.0)]))
    np.testing.assert_array_equal(eng.masses(0.7), [2.0, 3.0])
    np.testing.assert_array_equal(eng.masses(np.array([0.0, 1.0])), [[2.0, 3.0], [2.0, 3.0]])


def test_the_closed_form_contact_time_of_a_falling_ball() -> None:
    # gap 1 − 0.1 above the floor z = 0, from rest, g = 9.81: τ = √(2·0.9/9.81)
    scene = _scene([_ball()], [GRAVITY, {"type": "impact", "body": "ball", "restitution": 0.5}])
    eng = Engine(scene)
    imp = eng.impacts[0]
    s = eng.snapshot(0.0, eng.y0)
    tau = eng.resolver.contact_time(imp, imp.features[0], s, eng.model.uniform_gravity())
    assert tau == pytest.approx(math.sqrt(2 * 0.9 / 9.81), rel=4 * EPS, abs=0)
    # two spheres closing head on: τ = (gap between surfaces)/(relative speed)
    two = _scene(
        [_ball("a", (0, 0, 0), (1, 0, 0)), _ball("b", (1.2, 0, 0), (-1, 0, 0))],
        [{"type": "impact", "body": "a", "other": "b", "restitution": 1.0}],
    )
    eng = Engine(two)
    imp = eng.impacts[0]
    tau = eng.resolver.contact_time(imp, imp.features[0], eng.snapshot(0.0, eng.y0), np.zeros(3))
    assert tau == pytest.approx(0.5, rel=4 * EPS, abs=0)


def test_the_messages_of_a_resting_contact_and_of_a_fall_in() -> None:
    scene = _scene([_point()], duration=2.5)
    err = impacts.zeno(scene, 1.25, "impact effects[1]")
    assert (err.source, err.field) == ("unit.toml", "scene.duration")
    assert err.reason == (
        "impact effects[1] come to rest in contact (the impacts accumulate, or e = 0) near "
        "t = 1.25 s before the end 2.5 s, in more events than "
        f"{impacts.MAX_EVENTS} that it can follow: shorten the duration"
    )
    assert impacts.zeno(scene, 1.0).reason.startswith("the bodies come to rest in contact")
    imp, ft = SimpleNamespace(where="effects[0]"), SimpleNamespace(label="'a' and 'b'")
    err = impacts.falls_in(scene, imp, ft, 0.5)
    assert (err.field, err.reason) == (
        "effects[0]",
        "'a' and 'b' touch at t = 0.5 s and then fall in, with no separation that float64 "
        "can resolve: a resting contact, which this pair cannot have (two bodies on each "
        "other, a rim, or a body held by a joint; shorten the duration)",
    )


def test_rows_turn_a_dense_output_into_time_major_rows() -> None:
    at = integrate.rows(lambda t: np.array([np.asarray(t) * 1.0, np.asarray(t) * 2.0]))
    assert at.vectorized
    np.testing.assert_array_equal(at(np.array([1.0, 3.0])), [[1.0, 2.0], [3.0, 6.0]])
    np.testing.assert_array_equal(at(2.0), [2.0, 4.0])


# ------------------------------------------------------------------ the exact flows


@pytest.mark.parametrize(
    ("bodies", "effects", "how"),
    [
        ([_point()], [], "exact: uniform motion"),
        ([_point()], [GRAVITY], "exact: free flight under uniform gravity"),
        (
            [_ball()],
            [GRAVITY, {"type": "impact", "body": "ball", "restitution": 0.5}],
            "exact: free flight under uniform gravity, impacts solved in closed form",
        ),
        (
            [_box(omega=[0.0, 0.0, 1.0])],
            [],
            "exact: uniform motion; torque-free rotation (Jacobi elliptic functions)",
        ),
        (
            [_point()],
            [
                GRAVITY,
                ROCKET,
            ],
            "exact: rocket flight (7.30) with uniform gravity",
        ),
        ([_point()], [{"type": "drag", "body": "p", "linear": 0.1}], None),
        (
            [_point()],
            [{"type": "spring", "body": "p", "anchor": [0.0, 0.0, 1.0], "stiffness": 1.0}],
            None,
        ),
        # a rigid body on a plane touches it at a corner, not through its centre
        ([_box(position=[0, 0, 1.0])], [{"type": "impact", "body": "b", "restitution": 0.5}], None),
        # friction at the impact: no closed form
        (
            [_ball()],
            [GRAVITY, {"type": "impact", "body": "ball", "restitution": 0.5, "friction": 0.3}],
            None,
        ),
        # a fixed body among free ones
        ([_point(), _point("w", position=(3, 0, 0), fixed=True)], [], None),
    ],
    ids=[
        "uniform",
        "gravity",
        "impacts",
        "spinning",
        "rocket",
        "drag",
        "spring",
        "box on plane",
        "friction",
        "fixed body",
    ],
)
def test_the_exact_flow_is_chosen_by_the_effect_set(bodies, effects, how) -> None:
    assert Engine(_scene(bodies, effects)).exact_flow() == how


def test_a_rocket_steered_in_body_frame_has_no_exact_flow() -> None:
    thrust = {**ROCKET, "body": "b", "frame": "body"}
    assert Engine(_scene([_box()], [thrust])).exact_flow() is None


def test_exact_requested_where_there_is_none_names_the_effects() -> None:
    scene = _scene(
        [_point()],
        [{"type": "drag", "body": "p", "linear": 0.1}, GRAVITY],
        method="exact",
    )
    with pytest.raises(SceneError) as info:
        Engine(scene).run()
    assert (info.value.field, info.value.reason) == (
        "scene.method",
        "'exact' requested but the effects ['drag', 'gravity'] of this scene have no exact "
        "flow here; use 'auto' or 'integrate'",
    )


# --------------------------------------------------------------- whole-scene checks


def _refusal(bodies, effects) -> tuple[str, str]:
    with pytest.raises(SceneError) as info:
        _scene(bodies, effects)
    assert str(info.value).startswith("unit.toml: ")
    return info.value.field, info.value.reason


def test_one_joint_per_body() -> None:
    fp = {"type": "fixed_point", "body": "b", "distance": 0.1}
    fa = {"type": "fixed_axis", "body": "b"}
    assert _refusal([_box()], [fp, dict(fp)]) == (
        "effects[1].type",
        "'fixed_point' is listed twice for body 'b'",
    )
    assert _refusal([_box()], [fa, fp]) == (
        "effects[1].type",
        "'fixed_point' cannot be combined with 'fixed_axis' (effects[0]) on body 'b': one "
        "joint per body",
    )


def test_a_tank_takes_its_outflow_only() -> None:
    tank = {"name": "t", "shape": "tank", "area": 1.0, "initial": {"level": 1.0}}
    out = {"type": "tank_outflow", "body": "t", "hole_area": 0.01}
    assert _refusal([tank], [GRAVITY]) == ("bodies[0].shape", "a tank needs a tank_outflow effect")
    assert _refusal([tank], [GRAVITY, out, {"type": "torsion", "body": "t", "stiffness": 1.0}]) == (
        "effects[2].type",
        "a tank's only effect is its tank_outflow; a 'torsion' cannot act on it",
    )


def test_the_initial_state_of_a_free_body() -> None:
    keys = "position, velocity, omega, psi, theta, phi"
    assert _refusal([_box(angle=0.5)], []) == (
        "bodies[0].initial.angle",
        f"a free body takes {keys}",
    )
    # a pinned body may give Euler rates instead of omega, but not both
    fp = {"type": "fixed_point", "body": "b", "distance": 0.1}
    assert _refusal([_box(theta_dot=1.0)], []) == (
        "bodies[0].initial.theta_dot",
        f"a free body takes {keys}",
    )
    assert _refusal([_box(omega=[0, 0, 1.0], psi_dot=1.0)], [fp]) == (
        "bodies[0].initial.omega",
        "give either omega or the Euler rates",
    )
    _scene([_box(theta=0.5, psi_dot=1.0, phi_dot=2.0)], [fp])  # accepted


def test_a_fixed_body_stays_at_rest_and_a_point_does_not_turn() -> None:
    wall = _point("w", velocity=(1.0, 0.0, 0.0), fixed=True)
    assert _refusal([wall], []) == ("bodies[0].initial.velocity", "a fixed body stays at rest")
    still = _box(omega=[0.0, 0.5, 0.0])
    still["fixed"] = True
    assert _refusal([still], []) == ("bodies[0].initial.omega", "a fixed body stays at rest")
    _scene([_point("w", fixed=True)])  # at rest: accepted
    spin = _point()
    spin["initial"]["omega"] = [0.0, 0.0, 1.0]
    assert _refusal([spin], []) == (
        "bodies[0].initial.omega",
        "a point has no attitude and no rotation",
    )
    turned = _point()
    turned["initial"]["theta"] = 0.5
    assert _refusal([turned], []) == (
        "bodies[0].initial.psi",
        "a point has no attitude and no rotation",
    )


def test_a_body_cannot_spin_about_an_axis_of_zero_moment() -> None:
    rod = {"name": "r", "shape": "rod", "mass": 1.0, "length": 1.0}
    _scene([{**rod, "initial": {"omega": [1.0, 0.0, 0.0]}}])  # across the rod: fine
    assert _refusal([{**rod, "initial": {"omega": [0.0, 0.0, 2.0]}}], []) == (
        "bodies[0].initial.omega",
        "a rod has a zero principal moment [0.08333333333333333, 0.08333333333333333, 0.0]: "
        "it cannot spin about that axis; got omega = [0.0, 0.0, 2.0]",
    )


def test_bodies_overlapping_at_the_start_are_named() -> None:
    field, reason = _refusal(
        [_ball("a", (0, 0, 0)), _ball("b", (0.15, 0, 0))],
        [{"type": "impact", "body": "a", "other": "b", "restitution": 0.5}],
    )
    assert field == "effects[0]"
    assert reason == "bodies 'a' and 'b' overlap at t = 0 s (gap -0.05 m < 0)"
    # exactly touching is no overlap
    _scene(
        [_ball("a", (0, 0, 0)), _ball("b", (0.25, 0, 0), radius=0.15)],
        [{"type": "impact", "body": "a", "other": "b", "restitution": 0.5}],
    )


# ------------------------------------------------------------------ the series


def test_the_series_and_invariants_of_two_points_in_uniform_motion() -> None:
    """a (1 kg) at (1, 0, 0) with v (0, 1, 0), b (2 kg) at (0, 2, 0) with v (0.5, 0, 0):
    E = ½(1 + 2·¼) = 3/4, p = (1, 1, 0), L = (1, t, 0) × (0, 1, 0) + (t/2, 2, 0) × (1, 0, 0)
    = (0, 0, 1 − 2), all constant."""
    a = _point("a", (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), mass=1.0)
    b = _point("b", (0.0, 2.0, 0.0), (0.5, 0.0, 0.0), mass=2.0)
    tr = Engine(_scene([a, b])).run()
    assert tr.method == "exact: uniform motion"
    np.testing.assert_array_equal(tr.t, [0.0, 0.5, 1.0])
    per_body = [f"{n}.{k}" for n in "ab" for k in ("x", "y", "z", "vx", "vy", "vz")]
    totals = ["E"] + [f"{q}_{c}" for q in "pL" for c in "xyz"]
    assert set(tr.series) == set(per_body + totals)
    t = tr.t
    want = {
        "a.x": 1.0 + 0 * t,
        "a.y": t,
        "a.vy": 1.0 + 0 * t,
        "b.x": 0.5 * t,
        "b.y": 2.0 + 0 * t,
        "b.vx": 0.5 + 0 * t,
        "a.z": 0 * t,
        "b.vy": 0 * t,
        "E": 0.75 + 0 * t,
        "p_x": 1.0 + 0 * t,
        "p_y": 1.0 + 0 * t,
        "p_z": 0 * t,
        "L_x": 0 * t,
        "L_z": -1.0 + 0 * t,
    }
    for k, v in want.items():
        np.testing.assert_allclose(tr.series[k], v, rtol=0, atol=TRIG_ATOL, err_msg=k)
    assert set(tr.conserved) == set(totals)  # no effect: everything is kept
    assert tr.conserved_across_events == frozenset(totals)
    assert tr.conserved_from == {}
    scales = tr.scales
    assert scales["E"] == 0.75  # max |T| + max |E − T|
    assert scales["p_x"] == scales["p_z"] == 2.0  # Σ m |v| = 1 + 1
    # Σ |r| m |v| at its largest (t = 1): √2·1·1 + √(1/4 + 4)·2·½
    assert scales["L_y"] == pytest.approx(math.sqrt(2.0) + math.sqrt(4.25), rel=4 * EPS)
    assert tr.length_scale == 2.0  # the largest |coordinate|, no radii
    assert tr.gaps == {}
    assert tr.orthogonality is None
    state = tr.state_at(0.5)
    assert set(state) == set(per_body)
    assert state["a.y"] == pytest.approx(0.5, abs=TRIG_ATOL)
    assert state["b.x"] == pytest.approx(0.25, abs=TRIG_ATOL)


def test_the_series_of_a_spinning_box_name_its_spin() -> None:
    """ω = (0, 0, 2) about the principal axis e3 (J3 = 0.13), v = (1, 0, 0) from the
    origin: E = ½·12·1 + ½·0.13·4, the spin L = (0, 0, 0.26) kept, ω in space the same."""
    tr = Engine(_scene([_box(omega=[0.0, 0.0, 2.0], velocity=[1.0, 0.0, 0.0])])).run()
    assert tr.method == "exact: uniform motion; torque-free rotation (Jacobi elliptic functions)"
    s = tr.series
    for k, v in {"omega3": 2.0, "wz": 2.0, "omega1": 0.0, "wx": 0.0, "vx": 1.0}.items():
        np.testing.assert_allclose(s[k], v, rtol=0, atol=32 * EPS, err_msg=k)
    np.testing.assert_allclose(s["x"], tr.t, rtol=0, atol=TRIG_ATOL)
    np.testing.assert_allclose(s["E"], 6.0 + 0.26, rtol=16 * EPS)
    np.testing.assert_allclose(s["L_z"], 0.26, rtol=32 * EPS)
    np.testing.assert_allclose(s["p_x"], 12.0, rtol=0, atol=0)
    spin = [f"L_{c} (spin about G)" for c in "xyz"]
    assert set(spin) <= set(tr.conserved)
    assert set(spin) <= tr.conserved_across_events
    np.testing.assert_allclose(tr.conserved["L_z (spin about G)"], 0.26, rtol=32 * EPS)
    assert tr.scales["L_z (spin about G)"] == pytest.approx(0.26, rel=32 * EPS)
    assert 0.0 <= tr.orthogonality <= 16 * EPS
    state = tr.state_at(0.25)
    assert state["omega3"] == pytest.approx(2.0, abs=32 * EPS)
    assert state["wz"] == pytest.approx(2.0, abs=32 * EPS)
    assert state["x"] == pytest.approx(0.25, abs=TRIG_ATOL)


def test_gravity_keeps_the_horizontal_momentum_and_the_vertical_angular_momentum() -> None:
    # a force along −z: p_x, p_y and L_z about the origin are kept, and E with the
    # potential m g z; p_z and L_x, L_y change
    p = _point("a", (1.0, 0.0, 0.0), (0.0, 1.0, 0.0))
    q = _point("b", (0.0, 1.0, 0.0), (1.0, 0.0, 0.0))
    tr = Engine(_scene([p, q], [GRAVITY])).run()
    assert set(tr.conserved) == {"E", "p_x", "p_y", "L_z"}
    np.testing.assert_allclose(tr.series["p_z"], -2 * 9.81 * tr.t, rtol=4 * EPS)


def test_a_push_that_ends_breaks_the_momentum_only_until_then() -> None:
    push = {"type": "force", "body": "p", "force": [1.0, 0.0, 0.0], "end": 0.5}
    tr = Engine(_scene([_point()], [push])).run()
    assert tr.method == (
        "integrated: DOP853 (mechanics.integrators), contacts located on each step's "
        "dense polynomial; right-hand side compiled (numba: mechanics.scenes._kernels)"
    )
    assert tr.conserved_from["p_x"] == 0.5
    assert {"p_x", "p_y", "p_z"} <= set(tr.conserved)
    # v = t until 0.5, then 0.5: at t = 1, x = 1/8 + 1/4
    np.testing.assert_allclose(tr.series["vx"][-1], 0.5, rtol=0, atol=FLIGHT_ATOL)
    np.testing.assert_allclose(tr.series["x"][-1], 0.375, rtol=0, atol=2**20 * EPS)


def test_the_splitting_reports_its_step_order_and_the_half_step_drift() -> None:
    spring = {"type": "spring", "body": "p", "anchor": [0.0, 0.0, 0.0], "stiffness": 8.0}
    p = _point(position=(1.0, 0.0, 0.0), velocity=(0.0, 0.5, 0.0), mass=2.0)
    tr = Engine(_scene([p], [spring], method="splitting", order=2, step=0.25)).run()
    assert tr.method == (
        "integrated: splitting of order 2 (kicks of the loads, exact free flight and "
        "torque-free rotation), step 0.25 s"
    )
    info = tr.splitting
    assert (info["order"], info["step"]) == (2, 0.25)
    # Strang's energy error is O(h²): at half the step about a quarter of the swing
    ratio = float(np.ptp(tr.series["E"])) / info["E_drift_half"]
    assert 3.0 <= ratio <= 5.0, ratio


# ------------------------------------------------------------------ simulate


def test_simulate_runs_the_engine_and_adds_the_derived_quantities() -> None:
    """A rocket of 1.5 kg with 0.5 kg of fuel burnt at 0.1 kg/s (burn-out at 5 s),
    exhaust speed 100 m/s, straight up against g = 9.81: the speed gained by burn-out
    is u ln(m0/m_f) − g t_b = 100 ln 1.5 − 49.05 (7.30), in the exact flow too."""
    from mechanics.scenes import simulate

    scene = _scene([_point(mass=1.5)], [GRAVITY, ROCKET], duration=6.0)
    tr = simulate.simulate(scene)
    assert tr.method == "exact: rocket flight (7.30) with uniform gravity"
    ((name, exact, measured),) = tr.derived
    assert name == "speed gained by burn-out (7.30)"
    want = 100.0 * math.log(1.5) - 9.81 * 5.0
    assert exact == pytest.approx(want, rel=8 * EPS)
    assert measured == pytest.approx(want, rel=2**10 * EPS)  # the sampled flow at t_b
    assert [(e.t, e.kind) for e in tr.events] == [(pytest.approx(5.0, rel=4 * EPS), "burn_out")]
    assert tr.events[0].detail == {"body": "p"}  # whose fuel ran out
    # the mass series: m0 − q t until burn-out, then m_f (samples at 0, 3, 6 s)
    np.testing.assert_allclose(tr.series["mass"], [1.5, 1.2, 1.0], rtol=4 * EPS, atol=0)


def test_simulate_validate_checks_the_combination() -> None:
    import dataclasses

    from mechanics.scenes import simulate

    scene = _scene([_point()])
    assert simulate.validate(scene) is None
    body = dataclasses.replace(scene.bodies[0], initial={"omega": [0.0, 0.0, 1.0]})
    with pytest.raises(SceneError, match="a point has no attitude and no rotation"):
        simulate.validate(dataclasses.replace(scene, bodies=(body,)))


# ------------------------------------------------------ accelerations and pressing


def test_point_accelerations_are_a_g_plus_alpha_cross_rho_plus_centripetal() -> None:
    """A box (m = 12, J3 = 0.13) spinning at ω = 2 about e3, pushed by F = (1, 0, 0) at
    G and turned by a body torque (0, 0, 0.13): a_G = F/m = (1/12, 0, 0), α = (0, 0, 1);
    at ρ = (0.15, 0, 0) from G: α × ρ = (0, 0.15, 0), ω × (ω × ρ) = −4 ρ = (−0.6, 0, 0)."""
    push = {"type": "force", "body": "b", "force": [1.0, 0.0, 0.0]}
    turn = {"type": "torque", "body": "b", "torque": [0.0, 0.0, 0.13], "frame": "body"}
    eng = Engine(_scene([_box(omega=[0.0, 0.0, 2.0])], [push, turn]))
    s = eng.snapshot(0.0, eng.y0)
    acc = eng.forward.point_accelerations(0.0, eng.y0, s, {0: np.array([0.15, 0.0, 0.0]), None: 0})
    assert set(acc) == {0}
    np.testing.assert_allclose(acc[0], [1 / 12 - 0.6, 0.15, 0.0], rtol=0, atol=TRIG_ATOL)
    origin, base, w, alpha = eng.forward.kinematics(s, eng.rhs(0.0, eng.y0), 0)
    np.testing.assert_array_equal(origin, [0.0, 0.0, 0.0])
    np.testing.assert_allclose(base, [1 / 12, 0.0, 0.0], rtol=0, atol=TRIG_ATOL)
    np.testing.assert_allclose(w, [0.0, 0.0, 2.0], rtol=0, atol=TRIG_ATOL)
    np.testing.assert_allclose(alpha, [0.0, 0.0, 1.0], rtol=0, atol=TRIG_ATOL)


def test_a_point_has_no_rotation_and_a_fixed_body_no_acceleration() -> None:
    p = _point("p", position=(1.0, 2.0, 3.0), velocity=(1.0, 0.0, 0.0))
    wall = _point("w", position=(5.0, 0.0, 0.0), fixed=True)
    eng = Engine(_scene([p, wall], [GRAVITY]))
    s = eng.snapshot(0.0, eng.y0)
    origin, base, w, alpha = eng.forward.kinematics(s, eng.rhs(0.0, eng.y0), 0)
    np.testing.assert_array_equal(origin, [1.0, 2.0, 3.0])  # a point's origin: itself
    np.testing.assert_array_equal(base, [0.0, 0.0, -9.81])
    np.testing.assert_array_equal([w, alpha], np.zeros((2, 3)))
    acc = eng.forward.point_accelerations(0.0, eng.y0, s, {0: s.r[0], 1: s.r[1]})
    assert set(acc) == {0}  # the fixed body is left out
    np.testing.assert_array_equal(acc[0], [0.0, 0.0, -9.81])


def _resting_ball(effects):
    ball = _ball(position=(0.0, 0.0, 0.1))  # radius 0.1: touching the floor z = 0
    eng = Engine(_scene([ball], [*effects, {"type": "impact", "body": "ball", "restitution": 0.5}]))
    imp = eng.impacts[0]
    return eng, imp, imp.features[0]


def test_a_ball_on_the_floor_is_pressed_by_gravity_alone() -> None:
    eng, imp, ft = _resting_ball([GRAVITY])
    assert eng.resolver.pressed(imp, ft, 0.0, eng.y0) == pytest.approx(9.81, rel=4 * EPS)
    eng, imp, ft = _resting_ball([])
    assert eng.resolver.pressed(imp, ft, 0.0, eng.y0) == 0.0


@pytest.mark.parametrize(
    ("after", "before", "gap_scale", "stalls"),
    [
        (1.9e-9, 1.0, 0.0, True),  # below ZENO_SPEED (1 + |v before|) = 2e-9
        (2e-9, 1.0, 0.0, False),  # at it: followed (a hop above the gap's rounding)
        (1e-6, 0.0, 1.0, True),  # a hop v²/2a = 5e-14 below 2^8 eps of a 1 m gap
        (1e-6, 0.0, 1e-6, False),  # the same hop above the rounding of a 1 µm gap
        (1.0, 1.0, 1.0, False),
    ],
)
def test_impacts_stall_when_the_rebound_is_too_slow_to_follow(after, before, gap_scale, stalls):
    eng, imp, ft = _resting_ball([GRAVITY])
    detail = {"normal_speed_after": after, "normal_speed_before": before, "gap_scale": gap_scale}
    assert eng.resolver.stalls(imp, ft, 0.0, eng.y0, detail) is stalls
    # not pressed (no gravity): never a stall, however slow
    eng, imp, ft = _resting_ball([])
    assert eng.resolver.stalls(imp, ft, 0.0, eng.y0, detail) is False


def test_a_contact_found_on_its_exit_side_is_refused_with_its_time_and_the_cause() -> None:
    """The ball touches the floor but leaves it at 3 m/s: no impulse can be applied, and
    the scene error names the impact, the feature, the time to the last digit and the
    separating speed."""
    ball = _ball(position=(0.0, 0.0, 0.1), velocity=(0.0, 0.0, 3.0))
    eng = Engine(_scene([ball], [{"type": "impact", "body": "ball", "restitution": 0.5}]))
    imp = eng.impacts[0]
    ft = imp.features[0]
    events: list = []
    with pytest.raises(SceneError) as info:
        eng.resolver.resolve(1 / 3, eng.y0, imp, ft, events)
    assert info.value.field == imp.where == "effects[0]"
    assert info.value.reason == (
        f"{ft.label}: the contact at t = 0.33333333333333331 s was found on the exit side "
        "(the bodies separate there): the contact separates (v_n = 3.0 ≥ 0)"
    )
    assert events == []


def test_the_reactions_evaluate_the_loads_at_each_samples_own_time(monkeypatch) -> None:
    """An effect's loads are a function of (t, state): the joints' reactions at the
    samples hand each effect the sample's own time, as a float.  (Of the built-in
    effects only friction's lift-off message reads t, so the time is checked where it is
    handed over.)  The reaction itself: the top held at rest at θ = 0.5 has
    F_C = m a_G − m g with a_G = α × (G − C), α = J_C⁻¹ (G − C) × m g."""
    top = {**_top(), "initial": {"theta": 0.5, "omega": [0.0, 0.0, 0.0]}}
    eng = Engine(_scene([top], [PIN, GRAVITY]))
    eng.forward.compiled = "the Python path, whose calls of the loads this test watches"
    (grav,) = [e for e in eng.forces if e.type == "gravity"]
    seen, loads = [], grav.loads
    monkeypatch.setattr(grav, "loads", lambda t, s, out: (seen.append(t), loads(t, s, out)))
    out, size = eng.forward.reactions(np.array([0.0, 0.5]), np.stack([eng.y0, eng.y0]))
    # (the rates behind a_G evaluate the loads too, at the same time)
    assert all(type(t) is float for t in seen)
    assert sorted(set(seen)) == [0.0, 0.5]
    # by hand: R = R1(θ) (ψ = φ = 0), whose third row is e3 = (0, −sin θ, cos θ) in space
    th, m, ell = 0.5, 1.0, 0.2
    J1 = m * (3 * 0.1**2 + 0.4**2) / 12 + m * ell**2  # a cylinder's J across e3, about C
    rho = ell * np.array([0.0, -math.sin(th), math.cos(th)])
    weight = np.array([0.0, 0.0, -9.81 * m])
    alpha = np.cross(rho, weight) / J1  # about e_x, which is a principal axis at C
    want = m * np.cross(alpha, rho) - weight
    scale = 2**6 * EPS * 9.81
    for row in out[0]["reaction"]:
        np.testing.assert_allclose(row, want, rtol=0, atol=scale)
    # the size its rounding is relative to: |m a_G| + |m g|
    a_G = float(np.linalg.norm(m * np.cross(alpha, rho)))
    assert abs(size[0]["reaction"] - (a_G + 9.81 * m)) <= scale


def test_a_guided_bodys_frame_is_fitted_through_the_steps_ends() -> None:
    """A rod on a fixed axis (e_y, G 0.5 from it) turning at 4 rad/s: along a step of
    1.5 s (6 rad) its centre and attitude are far from polynomials of degree 8, yet the
    fit of the frame at the step's Chebyshev–Lobatto points equals them at both ends,
    where one step hands over to the next (the interior points carry the fit's error)."""
    from numpy.polynomial import chebyshev as C

    rod = {"name": "r", "shape": "rod", "mass": 1.0, "length": 2.0,
           "initial": {"angle": 0.0, "angular_velocity": 4.0}}  # fmt: skip
    axis = {"type": "fixed_axis", "body": "r", "axis": [0.0, 1.0, 0.0], "distance": 0.5,
            "body_axis": "y"}  # fmt: skip
    eng = Engine(_scene([rod], [axis]))
    o = eng.layout.offsets[0]

    def dense(tt):  # the exact uniform turn φ = 4 t as the step's dense output
        tt = np.atleast_1d(np.asarray(tt, dtype=float))
        Y = np.repeat(eng.y0[:, None], tt.size, axis=1)
        Y[o], Y[o + 1] = 4.0 * tt, 4.0
        return Y

    def frame(t):
        ss = eng.snapshot(np.array([t]), dense(t).T)
        return ss.r[0, 0], ss.R[0, 0]

    coef_r, coef_R = eng.collision.frame_coef(StepFit(dense, 0.0, 1.5), 0)
    for x, t in ((-1.0, 0.0), (1.0, 1.5)):
        r, R = frame(t)
        # a sum of 9 coefficients of O(1): a few roundings each
        np.testing.assert_allclose(C.chebval(x, coef_r), r, rtol=0, atol=32 * EPS)
        np.testing.assert_allclose(C.chebval(x, coef_R), R, rtol=0, atol=32 * EPS)
    r_mid, _ = frame(0.6)
    assert np.abs(C.chebval(-0.2, coef_r) - r_mid).max() > 2**10 * EPS  # not a polynomial


@pytest.mark.parametrize(("depth", "refused"), [(0.9, False), (1.1, True)])
def test_a_face_below_the_floor_at_a_steps_start_is_rounding_only_up_to_gap_rounding(
    depth, refused
) -> None:
    """A cylinder (radius ½, height 1) at rest lying flat, its lower face ``depth`` × the
    allowed rounding below the floor at a step's start.  The allowance is GAP_ROUNDING ×
    the size the face's positions are made of: Σ|G| = ½ and the rim's a + |z_c| = 1, so
    1.5 GAP_ROUNDING: within it the face touches (the rounding of a contact just
    resolved, no new contact); beyond it the bodies interpenetrate, a contact missed
    before this step, refused by name."""
    from mechanics.scenes.impacts import GAP_ROUNDING

    cyl = {"name": "c", "shape": "cylinder", "mass": 1.0, "radius": 0.5, "height": 1.0,
           "initial": {"position": [0.0, 0.0, 0.6]}}  # fmt: skip
    eng = Engine(_scene([cyl], [{"type": "impact", "body": "c", "restitution": 0.5}]))
    assert eng.collision.reach == {}  # as at the start of a run
    y = eng.y0.copy()
    y[2] = 0.5 - depth * 1.5 * GAP_ROUNDING  # G's height: the face at −depth × allowance

    def dense(tt):  # at rest along the step
        return np.repeat(y[:, None], np.size(tt), axis=1) if np.ndim(tt) else y

    if not refused:
        assert eng.collision.first_contact(StepFit(dense, 0.0, 0.1)) is None
        return
    with pytest.raises(SceneError) as info:
        eng.collision.first_contact(StepFit(dense, 0.0, 0.1))
    assert info.value.field == "effects[0]"
    assert "interpenetrate at t = 0 s" in info.value.reason
    assert "a contact was missed before this step" in info.value.reason


def test_the_momentum_scale_is_the_largest_sum_of_m_v_of_the_run() -> None:
    """A point of 0.5 kg moving at 0.2 m/s: p is kept relative to Σ m|v| = 0.1 (not to a
    floor of 1 N s, under which a small momentum's drift would pass unseen)."""
    tr = Engine(_scene([_point(mass=0.5, velocity=(0.2, 0.0, 0.0))])).run()
    assert [tr.scales[f"p_{c}"] for c in "xyz"] == [0.1, 0.1, 0.1]


def test_the_run_reports_each_pairs_smallest_gap_at_every_sample() -> None:
    """A box (edge c = 0.1 along z) falling from rest at z = 1 over the floor: its lowest
    corners are the pair's gap, z(t) − c/2 = 0.95 − g t²/2 at t = 0, 0.1, 0.2 (before
    it lands), one value per sample."""
    box = _box(position=[0.0, 0.0, 1.0])
    hit = {"type": "impact", "body": "b", "restitution": 0.5}
    tr = Engine(_scene([box], [GRAVITY, hit], duration=0.2)).run()
    (gaps,) = tr.gaps.values()
    want = 0.95 - 0.5 * 9.81 * np.array([0.0, 0.1, 0.2]) ** 2
    assert np.shape(gaps) == (3,)
    # DOP853 on a quadratic: exact but for the rounding of O(1) positions
    np.testing.assert_allclose(gaps, want, rtol=0, atol=16 * EPS)


def test_a_ball_dropped_on_a_fixed_ball_rebounds_from_the_top_of_it() -> None:
    """A ball (radius ½) falls from rest at z = 2 onto a fixed ball (radius ½) at the
    origin: the centres touch at distance 1, at t = √(2·1/g), speed √(2g); e = ½ sends it
    back up at half that speed (a fixed body takes any impulse)."""
    mover, wall = _ball("a", position=(0.0, 0.0, 2.0), radius=0.5), _ball("w", radius=0.5)
    wall = {**wall, "initial": {"position": [0.0, 0.0, 0.0]}, "fixed": True}
    hit = {"type": "impact", "body": "a", "other": "w", "restitution": 0.5}
    scene = _scene([mover, wall], [GRAVITY, hit], duration=0.5)
    tr = Engine(scene).run()
    (ev,) = [e for e in tr.events if e.kind == "impact"]
    t_c, v_c = math.sqrt(2.0 / 9.81), math.sqrt(2.0 * 9.81)
    stepped = 2**10 * EPS  # the crossing refined on DOP853's dense output of a quadratic
    assert ev.t == pytest.approx(t_c, rel=stepped)
    assert ev.detail["normal_speed_before"] == pytest.approx(v_c, rel=stepped)
    assert ev.detail["normal_speed_after"] == pytest.approx(0.5 * v_c, rel=stepped)
    np.testing.assert_allclose(ev.detail["contact_point"], [0.0, 0.0, 0.5], rtol=0, atol=stepped)


def test_pressing_evaluates_the_loads_at_the_time_asked(monkeypatch) -> None:
    """A disc (radius ½) standing on its rim on the floor at rest: gravity presses the
    rim's lowest point down at g.  The loads behind that acceleration are evaluated at
    the time asked (an effect's loads are a function of (t, state))."""
    disc = {"name": "d", "shape": "disc", "mass": 1.0, "radius": 0.5,
            "initial": {"position": [0.0, 0.0, 0.5], "theta": math.pi / 2}}  # fmt: skip
    eng = Engine(_scene([disc], [GRAVITY, {"type": "impact", "body": "d", "restitution": 0.5}]))
    imp = eng.impacts[0]
    (ft,) = imp.features
    assert ft.support is not None  # the rim circle, not a flat face
    eng.forward.compiled = "the Python path, whose calls of the loads this test watches"
    (grav,) = [e for e in eng.forces if e.type == "gravity"]
    seen, loads = [], grav.loads
    monkeypatch.setattr(grav, "loads", lambda t, s, out: (seen.append(t), loads(t, s, out)))
    assert eng.resolver.pressed(imp, ft, 0.7, eng.y0) == pytest.approx(9.81, rel=8 * EPS)
    assert seen
    assert set(seen) == {0.7}


@pytest.mark.parametrize(
    ("body", "scale"),
    [
        (_ball(position=(0.0, 0.0, 1.0), radius=0.1), 1.1),  # |r| + the radius
        (_box(position=[0.0, 0.0, 1.0]), 1.15),  # |r| + the farthest vertex (0.15, ·, ·)
    ],
    ids=["ball", "box"],
)
def test_the_length_scale_of_the_no_interpenetration_check(body, scale) -> None:
    """At rest 1 m above the floor: the depth of an interpenetration is judged relative
    to the largest |r| plus the largest radius and the farthest vertex from G."""
    hit = {"type": "impact", "body": body["name"], "restitution": 0.5}
    tr = Engine(_scene([body], [hit])).run()
    assert tr.length_scale == scale


def test_a_pinned_symmetric_top_among_other_bodies_keeps_its_own_named_l3() -> None:
    """A cylinder on its pivot beside a falling point: the moments about C (gravity's and
    the pivot's) are perpendicular to e3, so its L_3 = J3 ω3 = 0.005 × 20 = 0.1 is kept,
    reported under the top's own name."""
    p = _point("p", position=(1.0, 0.0, 0.0))
    tr = Engine(_scene([_top(), p], [PIN, GRAVITY], duration=0.2)).run()
    assert "L_3" not in tr.series
    assert "top.L_3" in tr.conserved
    # DOP853 keeps it to its tolerance (rtol 1e-12 of L_C, ~0.1): a few roundings here
    np.testing.assert_allclose(tr.series["top.L_3"], 0.1, rtol=2**10 * EPS)


def test_the_angular_momentum_scale_adds_each_bodys_spin_magnitude() -> None:
    """The box (J = (0.05, 0.1, 0.13)) at rest at the origin spinning at ω = (2, 1, 0):
    no orbital term; its spin J ω = (0.1, 0.1, 0) has |J ω| = 0.1 √2 at every sample
    (the free top keeps |L|), the size L's components are rounded relative to."""
    tr = Engine(_scene([_box(omega=[2.0, 1.0, 0.0])])).run()
    assert tr.scales["L_x"] == pytest.approx(0.1 * math.sqrt(2.0), rel=8 * EPS)


def test_a_switch_is_searched_and_refined_at_the_steps_own_times(monkeypatch) -> None:
    """A tank (A = 1, hole ½, g = 3, h0 = 2) empties at T = 2 (√h = √2 − (√2/2) t): on a
    step [0, 3] the switch function √h is fitted and its zero refined to T, every
    evaluation at a time of the step (a switch function is one of (t, state))."""
    tank = {"name": "tank", "shape": "tank", "area": 1.0, "initial": {"level": 2.0}}
    drain = [
        {"type": "gravity", "g": 3.0},
        {"type": "tank_outflow", "body": "tank", "hole_area": 0.5},
    ]
    eng = Engine(_scene([tank], drain, duration=3.0))
    assert (eng.modes.switched, eng.forward.phase) == ({}, None)  # as at a run's start
    (e,) = eng.switching
    o = eng.layout.offsets[0]

    def dense(tt):  # √h falling through zero at t = 2 (the exact flow, continued below 0)
        y = eng.y0.copy()
        y[o] = math.sqrt(2.0) * (1.0 - 0.5 * tt)
        return y

    seen, switch = [], e.switch_function
    monkeypatch.setattr(
        e, "switch_function", lambda t, s, out: (seen.append(t), switch(t, s, out))[1]
    )
    hit = eng.modes.first_switch(StepFit(dense, 0.0, 3.0))
    tc = hit.t
    assert hit.effect is e
    assert hit.feature is None  # a switch, not a contact
    assert tc == pytest.approx(2.0, rel=0, abs=2**4 * EPS)  # brentq to 4 eps of the step
    assert seen
    assert all(type(t) is float and 0.0 <= t <= 3.0 for t in seen)


# --------------------------------------------------------------- a top's exact flow


def _top(theta=0.5, shape=None):
    body = shape or {"name": "top", "shape": "cylinder", "mass": 1.0, "radius": 0.1, "height": 0.4}
    return {**body, "initial": {"theta": theta, "omega": [0.0, 0.0, 20.0]}}


PIN = {"type": "fixed_point", "body": "top", "distance": 0.2}


@pytest.mark.parametrize(
    ("body", "effects", "how"),
    [
        (_top(), [PIN], "exact: torque-free top about C, Jacobi elliptic functions (5.3)"),
        (_top(), [PIN, GRAVITY], "exact: heavy symmetric top, elliptic integrals (5.2.2–5.2.5)"),
        (_top(), [PIN, GRAVITY, {"type": "gravity", "g": 1.0}], None),  # two gravities
        (_top(), [PIN, {**GRAVITY, "direction": [1.0, 0.0, 0.0]}], None),  # not along −z
        (_top(), [PIN, {**GRAVITY, "direction": [0.0, 0.0, 1.0]}], None),  # along +z
        (_top(theta=0.0), [PIN, GRAVITY], None),  # upright: θ0 not in (0, π)
        (_top(theta=math.pi), [PIN, GRAVITY], None),
        (
            _top(shape={"name": "top", "shape": "box", "mass": 1.0, "a": 0.3, "b": 0.2, "c": 0.1}),
            [PIN, GRAVITY],
            None,  # J1 ≠ J2: not symmetric
        ),
        (_top(), [PIN, {"type": "drag", "body": "top", "angular_linear": 0.1}], None),
    ],
    ids=[
        "free",
        "heavy",
        "two gravities",
        "sideways",
        "upward",
        "upright",
        "hanging",
        "box",
        "drag",
    ],
)
def test_the_exact_flow_of_a_top_on_its_fixed_point(body, effects, how) -> None:
    assert Engine(_scene([body], effects)).exact_flow() == how


@pytest.mark.parametrize("kind", ["free", "heavy"])
def test_a_tops_exact_flow_starts_from_the_scenes_initial_state_and_follows_its_motion(kind):
    """Every initial angle and rate is handed to the exact top: at t = 0 its flat state
    (L_C, R_A_O) is the scene's own y0 (ψ0 = 0.4 and a nutation rate θ̇0 ≠ 0 from an ω
    off e3); at t = 0.3 it agrees with DOP853 on the engine's general equations of a
    pinned body (a route with no elliptic function)."""
    top = {
        **_top(),
        "initial": {"psi": 0.4, "theta": 0.5, "phi": 0.2, "omega": [1.5, -0.7, 20.0]},
    }
    eng = Engine(_scene([top], [PIN] if kind == "free" else [PIN, GRAVITY]))
    assert eng.exact_flow().startswith("exact: ")
    ((t_a, t_b, at),), _ = eng.flow.run()
    assert (t_a, t_b) == (0.0, 1.0)
    y = at(np.array([0.0, 0.3]))
    # L_C of O(0.1) and R of O(1): the exact flow at t = 0 to a few roundings of each
    # (measured 2.3 eps)
    np.testing.assert_allclose(y[0], eng.y0, rtol=0, atol=16 * EPS)
    from scipy.integrate import solve_ivp

    sol = solve_ivp(eng.rhs, (0.0, 0.3), eng.y0, method="DOP853", rtol=1e-13, atol=1e-15)
    # DOP853 over about one turn of the spin (6 rad): measured 5.4e-14 of the O(1)
    # state; 2^10 eps = 2.3e-13 leaves a margin of 4
    np.testing.assert_allclose(y[1], sol.y[:, -1], rtol=0, atol=2**10 * EPS)


def test_a_pinned_bodys_frame_along_a_step_is_its_pivot_and_attitude_columns() -> None:
    """The heavy top's exact flow as a step's dense output, fitted at the Chebyshev nodes:
    at a node, the frame's fit gives the snapshot's centre G and attitude R_A_O there
    (R from the state's own columns, G from the pivot and the arm)."""
    from numpy.polynomial import chebyshev as C

    from mechanics.scenes import contacts

    eng = Engine(_scene([_top()], [PIN, GRAVITY]))
    eng.exact_flow()
    ((_, _, at),), _ = eng.flow.run()
    coef_y = contacts.chebyshev_fit(at, 0.0, 0.05)
    fit = StepFit(lambda tt: at(tt).T, 0.0, 0.05)  # scipy's convention: (size, k)
    np.testing.assert_array_equal(fit.coef, coef_y)
    coef_r, coef_R = eng.collision.frame_coef(fit, 0)
    n = coef_y.shape[0]
    x = math.cos(math.pi * 3.5 / n)  # a node of the first kind: the fit equals the data
    tt = 0.025 + 0.025 * x
    s = eng.snapshot(tt, at(tt))
    # an interpolant at its node: the data to a few roundings of the O(1) entries
    np.testing.assert_allclose(C.chebval(x, coef_R), s.R[0], rtol=0, atol=2**6 * EPS)
    np.testing.assert_allclose(C.chebval(x, coef_r), s.r[0], rtol=0, atol=2**6 * EPS)


def test_two_pinned_tops_have_no_exact_flow() -> None:
    other = {**_top(), "name": "second"}
    pin2 = {**PIN, "body": "second"}
    assert Engine(_scene([_top(), other], [PIN, pin2])).exact_flow() is None


def test_the_series_of_a_heavy_symmetric_top() -> None:
    """A cylinder (m = 1, a = 0.1: J3 = m a²/2 = 0.005) on its pivot 0.2 below G, θ0 =
    0.5, spinning at 20 about e3: L_3 = J3 ω3 = 0.1 is kept (the moments about C are
    perpendicular to e3); the angles start at θ = 0.5, ψ = φ = 0; a reaction is reported."""
    tr = Engine(_scene([_top()], [PIN, GRAVITY])).run()
    s = tr.series
    np.testing.assert_allclose(s["L_3"], 0.1, rtol=8 * EPS)
    assert "L_3" in tr.conserved
    assert "L_3" in tr.conserved_across_events
    # the scale: the largest |L_A| over the samples, 0.1 at the start, more as it nutates
    assert tr.scales["L_3"] >= 0.1 * (1 - 8 * EPS)
    # θ(0) by the top's elliptic solution, through R and atan2 again (measured 9 eps)
    top_atol = 64 * EPS
    assert (s["theta"][0], s["psi"][0], s["phi"][0]) == pytest.approx((0.5, 0.0, 0.0), abs=top_atol)
    np.testing.assert_allclose(s["cos_theta"], np.cos(s["theta"]), rtol=0, atol=8 * EPS)
    assert {"reaction_x", "reaction_y", "reaction_z"} <= set(s)
    assert tr.scales["reaction_z"] > 0
    state = tr.state_at(0.0)
    assert state["cos_theta"] == pytest.approx(math.cos(0.5), abs=top_atol)
    assert state["cos_theta_dot"] == pytest.approx(0.0, abs=top_atol)  # θ̇ = 0 at the start


# ------------------------------------------------------------ runaway event counts


def test_a_run_whose_modes_switch_too_often_stops_naming_the_effect(monkeypatch) -> None:
    """A tank emptying (one switch of its mode, integrated): with MAX_EVENTS lowered to 0
    that one switch is already too many: one line naming scene.duration and the effect."""
    tank = {"name": "t", "shape": "tank", "area": 1.0, "initial": {"level": 1.0}}
    out = {"type": "tank_outflow", "body": "t", "hole_area": 0.1}
    scene = _scene([tank], [GRAVITY, out], duration=10.0, method="integrate")
    monkeypatch.setattr(impacts, "MAX_EVENTS", 0)
    with pytest.raises(SceneError) as info:
        Engine(scene).run()
    assert info.value.field == "scene.duration"
    assert info.value.reason.startswith("effects[1] come to rest in contact")


@pytest.mark.parametrize("method", ["auto", "integrate"])
def test_a_run_with_too_many_impacts_stops_naming_the_impact(monkeypatch, method) -> None:
    # a ball dropped on the floor: its first bounce is already more than MAX_EVENTS = 0
    scene = _scene(
        [_ball(position=(0.0, 0.0, 1.0))],
        [GRAVITY, {"type": "impact", "body": "ball", "restitution": 0.5}],
        method=method,
    )
    monkeypatch.setattr(impacts, "MAX_EVENTS", 0)
    with pytest.raises(SceneError) as info:
        Engine(scene).run()
    assert info.value.field == "scene.duration"
    assert "come to rest in contact" in info.value.reason
    assert "'ball'" in info.value.reason


def test_too_many_rounds_of_simultaneous_impacts_stop_with_one_line(monkeypatch) -> None:
    """A Newton's cradle: a at 1 m/s onto b touching c needs two rounds of impulses at
    t = 0.5 s (a on b, then b on c); with MAX_SWEEPS = 1 the second is one too many."""
    balls = [
        _ball("a", (0.0, 0.0, 0.0), (1.0, 0.0, 0.0)),
        _ball("b", (0.7, 0.0, 0.0)),
        _ball("c", (0.9, 0.0, 0.0)),
    ]
    pairs = [
        {"type": "impact", "body": "a", "other": "b", "restitution": 1.0},
        {"type": "impact", "body": "b", "other": "c", "restitution": 1.0},
    ]
    monkeypatch.setattr(impacts, "MAX_SWEEPS", 1)
    with pytest.raises(SceneError) as info:
        Engine(_scene(balls, pairs)).run()
    assert (info.value.field, info.value.reason) == (
        "effects",
        "more than 1 rounds of simultaneous impacts at t = 0.5 s",
    )
    monkeypatch.setattr(impacts, "MAX_SWEEPS", 2)  # two rounds: a stops, c leaves at 1 m/s
    tr = Engine(_scene(balls, pairs)).run()
    assert [e.detail["bodies"] for e in tr.events] == [["a", "b"], ["b", "c"]]
    np.testing.assert_allclose(
        [tr.series[f"{n}.vx"][-1] for n in "abc"], [0.0, 0.0, 1.0], rtol=0, atol=4 * EPS
    )


# ------------------------------------------------------- a rim on a hinged body


def test_a_coin_turning_on_a_hinge_strikes_the_floor_with_its_rim() -> None:
    """A disc (a = 0.5) turning at Ω = 2 about a horizontal diameter through G at
    height 1, flat at the start, over a floor at 0.75: its rim reaches down a sin φ, so
    it strikes at sin φc = 0.25/0.5, t_c = (π/6)/Ω, with normal speed a cos φc Ω; the
    hinge takes the impulse's other components, so ω' = −e Ω (e = 1/2) and the normal
    speed after is e times that before (Chapter 6)."""
    scene = _scene(
        [
            {
                "name": "d",
                "shape": "disc",
                "mass": 1.0,
                "radius": 0.5,
                "initial": {"angle": 0.0, "angular_velocity": 2.0},
            }
        ],
        [
            {
                "type": "fixed_axis",
                "body": "d",
                "axis": [1.0, 0.0, 0.0],
                "body_axis": "x",
                "point": [0.0, 0.0, 1.0],
            },
            {"type": "impact", "body": "d", "restitution": 0.5, "plane_point": [0.0, 0.0, 0.75]},
        ],
        duration=0.5,
    )
    tr = Engine(scene).run()
    assert tr.method.startswith("integrated: DOP853")
    (ev,) = tr.events
    stepped = 2**10 * EPS  # DOP853 on a uniform turn, the crossing refined to 4 eps
    assert ev.t == pytest.approx(math.pi / 12, rel=stepped)
    v_n = 0.5 * math.cos(math.pi / 6) * 2.0
    assert ev.detail["normal_speed_before"] == pytest.approx(v_n, rel=stepped)
    assert ev.detail["normal_speed_after"] == pytest.approx(0.5 * v_n, rel=stepped)
    assert tr.series["phidot"][-1] == pytest.approx(-1.0, rel=stepped)
    # φ = π/6 at the strike, then back at 1 rad/s for 0.5 − π/12 s
    assert tr.series["phi"][-1] == pytest.approx(math.pi / 6 - (0.5 - math.pi / 12), rel=stepped)


def test_the_touching_pair_that_closes_fastest_is_resolved_first() -> None:
    """b at rest between a (touching it, closing at 1 m/s) and c (touching it, closing
    at 2 m/s): the sequential impulses take b–c first; a pair closing from afar, or
    touching at rest, is not resolved now."""
    impacts = [
        {"type": "impact", "body": "a", "other": "b", "restitution": 1.0},
        {"type": "impact", "body": "b", "other": "c", "restitution": 1.0},
    ]

    def closing(va, vc, xc=0.4):
        balls = [
            _ball("a", (0.0, 0.0, 0.0), (va, 0.0, 0.0)),
            _ball("b", (0.2, 0.0, 0.0)),
            _ball("c", (xc, 0.0, 0.0), (vc, 0.0, 0.0)),
        ]
        eng = Engine(_scene(balls, impacts))
        found = eng.resolver.closing_now(eng.snapshot(0.0, eng.y0))
        return None if found is None else found[0].where

    assert closing(1.0, -2.0) == "effects[1]"
    assert closing(2.0, -1.0) == "effects[0]"
    assert closing(0.0, 0.0) is None  # touching at rest: no impact
    assert closing(0.0, -2.0, xc=0.5) is None  # c closes from 0.1 m away: not now
    assert closing(-1.0, 2.0) is None  # both separating
