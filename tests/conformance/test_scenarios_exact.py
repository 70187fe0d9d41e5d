"""The battery's scenarios (mechanics/conformance/scenarios.py) against independent routes.

Each scenario's numbers are checked against what its docstring promises (masses,
moments, shapes, gravity, restitution, pivot, thrust, times); each exact reference
against a closed form derived by hand below (parabola, impact, bounce, rocket) or a
high-accuracy ``solve_ivp`` integration of Euler's equations and Ṙ = −[ω]× R (free and
heavy tops); the figures, the invariants and every refusal's wording directly.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.linalg import expm

from mechanics._floats import EPS
from mechanics.conformance.protocol import Ground, Pivot, Shape, Thrust, Trajectory
from mechanics.conformance.scenarios import (
    FIGURES,
    INVARIANTS,
    SCENARIOS,
    UnknownScenarioError,
    _build,
    body_sizes,
    crossings,
    figure_names,
    get_scenario,
    interpolate,
    invariant_names,
    invariants,
    measure,
    reference,
)
from mechanics.errors import MechanicsValueError

#: closed forms evaluated two ways (the library's vectorised, ours term by term): a
#: handful of roundings of O(10) numbers
CLOSED_ATOL = 2**6 * EPS
#: DOP853 at rtol = atol = 1e-13 over a few seconds (≤ 20 periods) keeps the global error
#: near 1e-12; the exact references (Jacobi elliptic functions) are good to ~1e-13:
#: 2^14 eps = 3.6e-12 allows both
IVP_ATOL = 2**14 * EPS
IVP_RTOL = 1e-13
#: the near-separatrix top amplifies any error by e^{λ₀ t} (11.7 e-folds in 14 s, the
#: docstring): the same integration agrees to 5.3e4 eps there (measured); 2^18 eps
SEPARATRIX_ATOL = 2**18 * EPS
#: periods read off the integration's events (root-finding on the dense output, ~1e-12)
EVENT_RTOL = 2**14 * EPS
#: a figure read off the exact samples by local polynomials (crossings of degree 5 at
#: Δt = 1/16 s): measured 1.2e4 eps (free tops), 2.5e6 eps near the separatrix
SAMPLING_RTOL = 2**15 * EPS
SEPARATRIX_SAMPLING_RTOL = 2**23 * EPS
#: a figure read exactly (a parabola by a cubic, final velocities, a mass): a few roundings
READ_RTOL = 2**4 * EPS
#: an invariant along the exact trajectory: its terms' roundings, ≤ 3 eps of the scale
CONSERVED_RTOL = 2**3 * EPS
G = 9.81


def _fresh(name):
    """The scenario ``name`` built now: SCENARIOS is built at import, where a mutant of
    ``_build`` is not active (docs/mutation.md, "code run at import")."""
    return _build()[name]


def _R1(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, s], [0.0, -s, c]])


def _R3(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])


def _passive(psi, theta, phi):
    """^A R^O = R3(φ) R1(θ) R3(ψ), the book's z-x-z convention, by hand."""
    return _R3(phi) @ _R1(theta) @ _R3(psi)


TILT = _passive(0.3, 0.7, -0.4)


def _hat(w):
    return np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])


def _times(duration, dt):
    n = round(duration / dt)
    return tuple(k * dt for k in range(n + 1))


# --------------------------------------------------------------------------- the numbers


def test_the_battery_has_its_fifteen_scenarios_in_the_report_order():
    assert list(SCENARIOS) == [
        "free_top_axis1",
        "free_top_axis3",
        "free_top_near_separatrix",
        "heavy_top",
        "parabola",
        "two_body_impact",
        "bouncing_ball",
        "rocket",
        "box_landing_flat",
        "sliding_stop",
        "incline_rolling",
        "newtons_cradle",
        "bounce_to_rest",
        "oblique_impact_sticks",
        "oblique_impact_slips",
    ]
    kinds = [s.extra["kind"] for s in _build().values()]
    assert kinds == [
        "free_top",
        "free_top",
        "free_top",
        "heavy_top",
        "parabola",
        "impact",
        "bounce",
        "rocket",
        "bounce",
        "slide",
        "roll",
        "cradle",
        "rest",
        "oblique",
        "oblique",
    ]
    for s in SCENARIOS.values():
        assert get_scenario(s.name) is s


@pytest.mark.parametrize(
    ("name", "omega", "duration"),
    [
        ("free_top_axis1", (2.0, 0.3, 0.2), 8.0),
        ("free_top_axis3", (0.2, 0.3, 2.0), 8.0),
        ("free_top_near_separatrix", (0.04, 4.0, 0.0), 14.0),
    ],
)
def test_the_free_tops_are_the_tilted_1_kg_box_of_moments_2_3_4(name, omega, duration):
    s = _fresh(name)
    (b,) = s.bodies
    assert (b.name, b.mass, b.inertia, b.omega) == ("box", 1.0, (2.0, 3.0, 4.0), omega)
    assert b.shape.kind == "box"
    # a box of half extents (a, b, c) and mass m: J1 = m (b² + c²)/3, ... (the box's
    # moments from its shape are the scenario's)
    a2, b2, c2 = (x * x for x in b.shape.dims)
    J = np.array([(b2 + c2) / 3, (a2 + c2) / 3, (a2 + b2) / 3])
    np.testing.assert_allclose(J, b.inertia, rtol=4 * EPS, atol=0)
    np.testing.assert_allclose(np.array(b.R_A_O), TILT, rtol=0, atol=4 * EPS)
    assert b.position == b.velocity == (0.0, 0.0, 0.0)
    assert s.duration == duration
    assert s.sample_times == _times(duration, 1 / 16)
    assert s.steps == (2.0**-6, 2.0**-7, 2.0**-8)
    assert s.gravity == (0.0, 0.0, 0.0)
    assert (s.ground, s.pivot, s.thrust, s.pair_restitution) == (None, None, None, ())
    assert s.book == "(4.47), (5.85)-(5.90), Essén 5.3"


def test_the_free_tops_circulate_the_axes_their_names_say():
    # 2 E J2 - L² > 0: around axis 1 (least moment); < 0: around axis 3
    def excess(s):
        J, w = np.array(s.bodies[0].inertia), np.array(s.bodies[0].omega)
        return float((J * w * w).sum() * J[1] - ((J * w) ** 2).sum())

    assert excess(_fresh("free_top_axis1")) > 0
    assert excess(_fresh("free_top_axis3")) < 0
    # near the separatrix: L² − 2EJ₂ = (2·0.04)² + 12² − 3 (2·0.04² + 3·4²) = −3.2e-3
    assert -excess(_fresh("free_top_near_separatrix")) == pytest.approx(-3.2e-3, rel=2**10 * EPS)


def test_the_descriptions_state_the_scenarios_numbers():
    d = {n: s.description for n, s in _build().items()}
    assert d["free_top_axis1"] == (
        "torque-free asymmetric body, ω circulating the axis of least moment"
    )
    assert d["free_top_axis3"] == (
        "torque-free asymmetric body, ω circulating the axis of greatest moment"
    )
    assert d["free_top_near_separatrix"] == (
        "torque-free body spun 1 % off the intermediate axis: m1 = 1.3e-4, a flip every 8.3 s"
    )
    assert d["heavy_top"] == (
        "heavy symmetric top on a pivot 0.1 m below G, released at θ = 0.6 rad "
        "spinning 6 rad/s: nutation and precession"
    )
    assert d["parabola"] == "a spinning ball thrown under gravity: the parabola and its apex"
    assert d["two_body_impact"] == (
        "two spheres (1 kg, 3 kg) head-on along x with e = 0.6, no gravity"
    )
    assert d["bouncing_ball"] == (
        "a ball dropped from 1.275 m onto smooth ground, e = 0.8, drifting sideways: "
        "three apexes e^(2k) h0"
    )
    assert d["rocket"] == (
        "a 10 kg rocket burning 0.5 kg/s for 8 s at 20 m/s exhaust speed along its "
        "tilted axis 3, in free space"
    )
    books = {n: s.book for n, s in _build().items()}
    assert books["heavy_top"] == "(5.53), (5.55), (5.66), Essén 5.2.2-5.2.5"
    assert books["parabola"] == "ṗ = F (1.1) under uniform gravity; (4.47) with M = 0"
    assert books["two_body_impact"] == "(6.36)-(6.38), Essén 6.3"
    assert books["bouncing_ball"] == "(6.6), Example 6.1"
    assert books["rocket"] == "(7.30), Example 7.2 with g = 0"


def test_the_heavy_top_stands_on_its_pivot_0_1_m_below_g_at_theta_0_6():
    s = _fresh("heavy_top")
    (b,) = s.bodies
    assert (b.name, b.mass, b.inertia, b.omega) == ("top", 1.0, (0.3, 0.3, 0.5), (0.0, 0.0, 6.0))
    assert b.shape == Shape("cylinder", (1.0, math.sqrt(0.15)))
    R = np.array(b.R_A_O)
    np.testing.assert_allclose(R, _passive(0.0, 0.6, 0.0), rtol=0, atol=4 * EPS)
    # G sits ℓ = 0.1 along body axis 3 (row 3 of ^A R^O, in space components)
    np.testing.assert_allclose(b.position, 0.1 * R[2], rtol=0, atol=4 * EPS)
    assert b.velocity == (0.0, 0.0, 0.0)  # ω along axis 3 and G on it: G at rest
    assert s.pivot == Pivot(0, (0.0, 0.0, -0.1), (0.0, 0.0, 0.0))
    assert s.gravity == (0.0, 0.0, -9.81)
    assert s.duration == 2.0
    assert s.sample_times == _times(2.0, 2.0**-7)
    assert s.steps == (2.0**-7, 2.0**-8, 2.0**-9)
    assert (s.ground, s.thrust, s.pair_restitution) == (None, None, ())


def test_the_parabola_throws_a_spinning_solid_ball():
    s = _fresh("parabola")
    (b,) = s.bodies
    assert (b.name, b.mass, b.shape) == ("ball", 0.5, Shape("sphere", (0.1,)))
    assert b.inertia == pytest.approx((0.4 * 0.5 * 0.01,) * 3, rel=4 * EPS)  # 2/5 m r²
    assert (b.position, b.velocity, b.omega) == ((0.0, 0.0, 1.0), (3.0, 1.0, 8.0), (1.0, -2.0, 3.0))
    np.testing.assert_allclose(np.array(b.R_A_O), TILT, rtol=0, atol=4 * EPS)
    assert s.gravity == (0.0, 0.0, -9.81)
    assert s.duration == 1.5
    assert s.sample_times == _times(1.5, 2.0**-5)
    assert s.steps == (2.0**-6, 2.0**-7, 2.0**-8)
    assert (s.ground, s.pivot, s.thrust, s.pair_restitution) == (None, None, None, ())


def test_the_impact_is_two_solid_spheres_head_on_with_e_0_6():
    s = _fresh("two_body_impact")
    a, b = s.bodies
    assert (a.name, a.mass, a.shape, a.position, a.velocity) == (
        "a",
        1.0,
        Shape("sphere", (0.1,)),
        (-1.0, 0.0, 0.0),
        (2.0, 0.0, 0.0),
    )
    assert (b.name, b.mass, b.shape, b.position, b.velocity) == (
        "b",
        3.0,
        Shape("sphere", (0.15,)),
        (0.5, 0.0, 0.0),
        (-1.0, 0.0, 0.0),
    )
    assert a.inertia == pytest.approx((0.4 * 1.0 * 0.1**2,) * 3, rel=4 * EPS)
    assert b.inertia == pytest.approx((0.4 * 3.0 * 0.15**2,) * 3, rel=4 * EPS)
    assert a.omega == b.omega == (0.0, 0.0, 0.0)
    assert s.pair_restitution == ((0, 1, 0.6),)
    assert s.gravity == (0.0, 0.0, 0.0)
    assert s.duration == 1.0
    assert s.sample_times == _times(1.0, 2.0**-5)
    assert s.steps == (2.0**-6, 2.0**-7, 2.0**-8)
    assert (s.ground, s.pivot, s.thrust) == (None, None, None)


def test_the_bouncing_ball_drops_from_1_275_m_onto_ground_of_e_0_8():
    s = _fresh("bouncing_ball")
    (b,) = s.bodies
    assert (b.name, b.mass, b.shape) == ("ball", 0.5, Shape("sphere", (0.1,)))
    assert b.inertia == pytest.approx((0.002,) * 3, rel=4 * EPS)
    assert (b.position, b.velocity, b.omega) == ((0.0, 0.0, 1.375), (0.5, 0.0, 0.0), (0.0,) * 3)
    assert b.position[2] - b.shape.dims[0] == 1.275  # h0, the lowest point's height
    assert s.ground == Ground(0.8, (0.0, 0.0, 1.0), 0.0)
    assert s.gravity == (0.0, 0.0, -9.81)
    assert s.duration == 2.375
    assert s.sample_times == _times(2.375, 2.0**-5)
    assert s.steps == (2.0**-6, 2.0**-7, 2.0**-8)
    assert (s.pivot, s.thrust, s.pair_restitution) == (None, None, ())


def test_the_rocket_burns_4_kg_of_its_10_along_its_tilted_axis_3():
    s = _fresh("rocket")
    (b,) = s.bodies
    assert (b.name, b.mass, b.inertia, b.shape) == ("rocket", 10.0, (0.1, 0.1, 0.05), None)
    assert (b.position, b.velocity, b.omega) == ((0.0,) * 3, (0.0,) * 3, (0.0,) * 3)
    np.testing.assert_allclose(np.array(b.R_A_O), TILT, rtol=0, atol=4 * EPS)
    assert s.thrust == Thrust(0, 0.5, 20.0, 8.0, (0.0, 0.0, 1.0))
    assert s.duration == 10.0
    assert s.sample_times == _times(10.0, 2.0**-3)
    assert s.steps == (2.0**-6, 2.0**-7, 2.0**-8)
    assert s.gravity == (0.0, 0.0, 0.0)
    assert (s.ground, s.pivot, s.pair_restitution) == (None, None, ())


def test_impacts_fall_at_least_9_ms_from_every_sample():
    # two bodies: gap 1.5 − 0.25 m closed at 3 m/s: t = 5/12 s; the ball: t_f = √(2 h0/g)
    # then t_f (1 + 2e + ... + 2e^(k−1))
    tf = math.sqrt(2 * 1.275 / G)
    bounce = [tf * (1 + 2 * sum(0.8**j for j in range(1, k + 1))) for k in range(4)]
    for name, impacts in (("two_body_impact", [5 / 12]), ("bouncing_ball", bounce)):
        t = np.array(_fresh(name).sample_times)
        for ti in impacts:
            if ti <= t[-1]:
                assert np.abs(t - ti).min() >= 9e-3, (name, ti)


# --------------------------------------------------------------------------- closed forms


def test_parabola_reference_is_the_parabola_with_the_free_spin_of_a_round_body():
    s = _fresh("parabola")
    ref = reference(s)
    t = np.array(s.sample_times)
    tr = ref.trajectory
    np.testing.assert_array_equal(tr.t, t)
    x0, v0 = np.array([0.0, 0.0, 1.0]), np.array([3.0, 1.0, 8.0])
    g = np.array([0.0, 0.0, -G])
    for k, tk in enumerate(t):
        np.testing.assert_allclose(
            tr.position[k, 0], x0 + v0 * tk + 0.5 * g * tk * tk, atol=CLOSED_ATOL, rtol=0
        )
        np.testing.assert_allclose(tr.velocity[k, 0], v0 + g * tk, atol=CLOSED_ATOL, rtol=0)
    # equal moments: ω (body) constant, Ṙ = −[ω]× R, so R(t) = exp(−[ω]× t) R(0)
    w = np.array([1.0, -2.0, 3.0])
    for k in (0, 7, 24, 48):
        np.testing.assert_allclose(
            tr.R_A_O[k, 0], expm(-_hat(w) * t[k]) @ TILT, atol=CLOSED_ATOL, rtol=0
        )
    np.testing.assert_allclose(
        tr.omega[:, 0], np.broadcast_to(w, (t.size, 3)), atol=CLOSED_ATOL, rtol=0
    )
    assert tr.masses is None
    # the apex: v_z = 8 − g t = 0 at t = 8/g, at height 1 + 8²/(2g)
    assert ref.figures["apex_time"] == pytest.approx(8 / G, rel=2 * EPS)
    assert ref.figures["apex_height"] == pytest.approx(1 + 32 / G, rel=2 * EPS)


def test_impact_reference_is_uniform_motion_and_newtons_law_at_five_twelfths_s():
    s = _fresh("two_body_impact")
    ref = reference(s)
    t = np.array(s.sample_times)
    # by hand: P = 1·2 + 3·(−1) = −1, v_cm = −1/4, closing speed 3; after:
    # v1 = v_cm − e (m2/M) 3 = −1.6, v2 = v_cm + e (m1/M) 3 = 0.2; gap 1.25 m at 3 m/s
    tc = 5 / 12
    x1 = np.where(t <= tc, -1 + 2 * t, -1 / 6 - 1.6 * (t - tc))
    x2 = np.where(t <= tc, 0.5 - t, 1 / 12 + 0.2 * (t - tc))
    tr = ref.trajectory
    np.testing.assert_allclose(tr.position[:, 0, 0], x1, atol=CLOSED_ATOL, rtol=0)
    np.testing.assert_allclose(tr.position[:, 1, 0], x2, atol=CLOSED_ATOL, rtol=0)
    np.testing.assert_array_equal(tr.position[:, :, 1:], 0.0)
    np.testing.assert_allclose(
        tr.velocity[:, 0, 0], np.where(t <= tc, 2.0, -1.6), atol=CLOSED_ATOL, rtol=0
    )
    np.testing.assert_allclose(
        tr.velocity[:, 1, 0], np.where(t <= tc, -1.0, 0.2), atol=CLOSED_ATOL, rtol=0
    )
    np.testing.assert_array_equal(tr.velocity[:, :, 1:], 0.0)
    np.testing.assert_array_equal(tr.R_A_O, np.broadcast_to(np.eye(3), (t.size, 2, 3, 3)))
    np.testing.assert_array_equal(tr.omega, 0.0)
    f = ref.figures
    np.testing.assert_allclose(f["v1_after"], [-1.6, 0, 0], atol=CLOSED_ATOL, rtol=0)
    np.testing.assert_allclose(f["v2_after"], [0.2, 0, 0], atol=CLOSED_ATOL, rtol=0)
    assert f["restitution"] == 0.6
    assert f["impact_time"] == pytest.approx(tc, rel=2 * EPS)


def _bounce_by_hand(t, h0, e, g):
    """Height of the lowest point and its rate, bounce by bounce."""
    z, v = np.empty_like(t), np.empty_like(t)
    for n, tk in enumerate(t):
        start, z0, up = 0.0, h0, 0.0
        flight = math.sqrt(2 * h0 / g)  # the first fall
        speed = g * flight
        while tk > start + flight:  # passes the next impact
            start += flight
            speed *= e
            z0, up = 0.0, speed
            flight = 2 * speed / g
        tau = tk - start
        z[n], v[n] = z0 + up * tau - 0.5 * g * tau * tau, up - g * tau
    return z, v


def test_bounce_reference_follows_each_flight_and_its_apexes_e_to_the_2k_h0():
    s = _fresh("bouncing_ball")
    ref = reference(s)
    t = np.array(s.sample_times)
    z, vz = _bounce_by_hand(t, 1.275, 0.8, G)
    tr = ref.trajectory
    np.testing.assert_allclose(tr.position[:, 0, 2], 0.1 + z, atol=CLOSED_ATOL, rtol=0)
    np.testing.assert_allclose(tr.velocity[:, 0, 2], vz, atol=CLOSED_ATOL, rtol=0)
    np.testing.assert_allclose(tr.position[:, 0, 0], 0.5 * t, atol=CLOSED_ATOL, rtol=0)
    np.testing.assert_array_equal(tr.velocity[:, 0, 0], 0.5)
    np.testing.assert_array_equal(tr.position[:, 0, 1], 0.0)
    np.testing.assert_array_equal(tr.R_A_O[:, 0], np.broadcast_to(np.eye(3), (t.size, 3, 3)))
    tf = math.sqrt(2 * 1.275 / G)
    e = 0.8
    # apex k at t_f (1 + 2e + … + 2e^(k−1) + e^k), height e^(2k) h0: three before 2.375 s
    times = [tf * (1 + 2 * sum(e**j for j in range(1, k)) + e**k) for k in (1, 2, 3)]
    assert tf * (1 + 2 * (e + e**2 + e**3) + e**4) > 2.375  # the fourth is after the end
    np.testing.assert_allclose(ref.figures["apex_times"], times, rtol=2**4 * EPS, atol=0)
    np.testing.assert_allclose(
        ref.figures["apex_heights"],
        [1.275 * e ** (2 * k) for k in (1, 2, 3)],
        rtol=2**4 * EPS,
        atol=0,
    )


def test_rocket_reference_is_tsiolkovsky_along_the_tilted_axis_then_coasting():
    s = _fresh("rocket")
    ref = reference(s)
    t = np.array(s.sample_times)
    d = TILT[2]  # body axis 3 in space components: row 3 of ^A R^O
    m0, q, u, T = 10.0, 0.5, 20.0, 8.0
    tb = np.minimum(t, T)
    m = m0 - q * tb
    # v = u ln(m0/m); x = ∫ v = u (t − (m/q) ln(m0/m)) while burning, then uniform
    v = u * np.log(m0 / m)
    x = u * (tb - (m / q) * np.log(m0 / m)) + v * (t - tb)
    tr = ref.trajectory
    np.testing.assert_allclose(tr.velocity[:, 0], v[:, None] * d, atol=2**3 * CLOSED_ATOL, rtol=0)
    np.testing.assert_allclose(tr.position[:, 0], x[:, None] * d, atol=2**5 * CLOSED_ATOL, rtol=0)
    np.testing.assert_allclose(tr.masses[:, 0], m, atol=CLOSED_ATOL, rtol=0)
    np.testing.assert_allclose(
        tr.R_A_O[:, 0], np.broadcast_to(TILT, (t.size, 3, 3)), atol=4 * EPS, rtol=0
    )
    np.testing.assert_array_equal(tr.omega, 0.0)
    assert ref.figures["delta_v"] == pytest.approx(20 * math.log(10 / 6), rel=2 * EPS)
    assert ref.figures["burnout_mass"] == 6.0


# --------------------------------------------------------------------------- integrated


def _rigid_rhs(J, torque=None):
    """Euler's equations (4.47) J ω̇ = (J ω) × ω + M and Ṙ = −[ω]× R (passive ^A R^O,
    body ω), state (R row-major, ω)."""

    def rhs(_t, y):
        R, w = y[:9].reshape(3, 3), y[9:]
        M = np.zeros(3) if torque is None else torque(R)
        dw = (np.cross(J * w, w) + M) / J
        return np.concatenate([(-_hat(w) @ R).ravel(), dw])

    return rhs


def _integrate(J, R0, w0, t, torque=None, **kw):
    y0 = np.concatenate([np.asarray(R0, dtype=float).ravel(), w0])
    return solve_ivp(
        _rigid_rhs(np.asarray(J, dtype=float), torque),
        (0.0, float(t[-1])),
        y0,
        method="DOP853",
        t_eval=t,
        rtol=IVP_RTOL,
        atol=IVP_RTOL,
        dense_output=True,
        **kw,
    )


@pytest.mark.parametrize(
    ("name", "atol"),
    [
        ("free_top_axis1", IVP_ATOL),
        ("free_top_axis3", IVP_ATOL),
        ("free_top_near_separatrix", SEPARATRIX_ATOL),
    ],
)
def test_free_top_reference_agrees_with_eulers_equations_integrated(name, atol):
    s = _fresh(name)
    b = s.bodies[0]
    t = np.array(s.sample_times)
    ref = reference(s)
    tr = ref.trajectory
    sol = _integrate(b.inertia, b.R_A_O, np.array(b.omega), t)
    np.testing.assert_allclose(tr.R_A_O[:, 0].reshape(-1, 9), sol.y[:9].T, atol=atol, rtol=0)
    np.testing.assert_allclose(tr.omega[:, 0], sol.y[9:].T, atol=atol, rtol=0)
    np.testing.assert_array_equal(tr.position, 0.0)
    np.testing.assert_array_equal(tr.velocity, 0.0)
    np.testing.assert_array_equal(tr.t, t)
    assert tr.masses is None


@pytest.mark.parametrize("name", ["free_top_axis1", "free_top_axis3"])
def test_free_top_omega_period_is_every_second_zero_of_the_intermediate_component(name):
    s = _fresh(name)
    b = s.bodies[0]

    def omega2(_t, y):
        return y[10]

    t = np.array([0.0, 3 * reference(s).figures["omega_period"]])
    sol = _integrate(b.inertia, b.R_A_O, np.array(b.omega), t, events=omega2)
    z = sol.t_events[0]
    assert z.size >= 5
    assert reference(s).figures["omega_period"] == pytest.approx(z[4] - z[2], rel=EVENT_RTOL)
    # measured off the exact samples (degree-5 crossings at Δt = 1/16 s): the same period
    got = measure(s, reference(s).trajectory)["omega_period"]
    assert got == pytest.approx(z[4] - z[2], rel=SAMPLING_RTOL)


def _heavy_torque(R):
    # about the pivot, body components: ρ × m g with ρ = (0, 0, ℓ) (G above the pivot
    # along axis 3) and g in body components R g
    return np.cross([0.0, 0.0, 0.1], 1.0 * (R @ np.array([0.0, 0.0, -G])))


def test_heavy_top_reference_agrees_with_the_rigid_body_about_its_pivot_integrated():
    s = _fresh("heavy_top")
    b = s.bodies[0]
    t = np.array(s.sample_times)
    ref = reference(s)
    tr = ref.trajectory
    J_pivot = np.array([0.3 + 0.01, 0.3 + 0.01, 0.5])  # parallel axes, m ℓ² = 0.01
    sol = _integrate(J_pivot, b.R_A_O, np.array(b.omega), t, torque=_heavy_torque)
    R = sol.y[:9].T.reshape(-1, 3, 3)
    w = sol.y[9:].T
    np.testing.assert_allclose(tr.R_A_O[:, 0], R, atol=IVP_ATOL, rtol=0)
    np.testing.assert_allclose(tr.omega[:, 0], w, atol=IVP_ATOL, rtol=0)
    # G = anchor + ℓ (row 3 of R); v_G = ω_space × (G − anchor)
    rho = 0.1 * R[:, 2]
    np.testing.assert_allclose(tr.position[:, 0], rho, atol=IVP_ATOL, rtol=0)
    w_O = np.einsum("tji,tj->ti", R, w)
    np.testing.assert_allclose(tr.velocity[:, 0], np.cross(w_O, rho), atol=IVP_ATOL, rtol=0)
    np.testing.assert_allclose(
        ref.figures["theta"], np.arccos(R[:, 2, 2]), atol=2**4 * IVP_ATOL, rtol=0
    )


def test_heavy_top_nutation_period_and_precession_rate_from_the_integration():
    s = _fresh("heavy_top")
    b = s.bodies[0]
    f = reference(s).figures
    T = f["nutation_period"]

    def theta_turns(_t, y):  # d(cos θ)/dt = d R33/dt = (−[ω]× R)_33 = ω2 R13 − ω1 R23
        return y[10] * y[2] - y[9] * y[5]

    J_pivot = np.array([0.31, 0.31, 0.5])
    sol = _integrate(
        J_pivot,
        b.R_A_O,
        np.array(b.omega),
        np.array([0.0, 2.5 * T]),
        torque=_heavy_torque,
        events=theta_turns,
    )
    turns = sol.t_events[0]
    assert turns.size >= 4
    # released with no θ̇: t = 0 is a turning point, and so is every half period
    assert f["nutation_period"] == pytest.approx(turns[2] - turns[0], rel=EVENT_RTOL)

    def psi(tk):  # body axis 3 in space: (sθ sψ, −sθ cψ, cθ)
        R = sol.sol(tk)[:9].reshape(3, 3)
        return math.atan2(R[2, 0], -R[2, 1])

    advance = (psi(turns[2]) - psi(turns[0]) + math.pi) % (2 * math.pi) - math.pi
    assert f["precession_rate"] == pytest.approx(advance / (turns[2] - turns[0]), rel=EVENT_RTOL)


# --------------------------------------------------------------------------- figures


_FIGURE_RTOL = {
    "free_top_axis1": SAMPLING_RTOL,
    "free_top_axis3": SAMPLING_RTOL,
    "free_top_near_separatrix": SEPARATRIX_SAMPLING_RTOL,
    "heavy_top": SAMPLING_RTOL,
}


@pytest.mark.parametrize("name", list(SCENARIOS))
def test_the_figures_read_off_the_exact_samples_are_the_reference_figures(name):
    s = _fresh(name)
    ref = reference(s)
    got = measure(s, ref.trajectory)
    assert set(got) == set(ref.figures) == set(figure_names(s)) == set(FIGURES[s.extra["kind"]])
    rtol = _FIGURE_RTOL.get(name, READ_RTOL)
    for k, want in ref.figures.items():
        np.testing.assert_allclose(got[k], want, rtol=rtol, atol=0, err_msg=k)


@pytest.mark.parametrize("name", list(SCENARIOS))
def test_the_exact_trajectory_conserves_what_the_scenario_says_it_conserves(name):
    s = _fresh(name)
    inv = invariants(s, reference(s).trajectory)
    assert tuple(inv) == invariant_names(s) == INVARIANTS[s.extra["kind"]]
    for k, (values, scale) in inv.items():
        assert np.abs(values - values[0]).max() <= CONSERVED_RTOL * scale, k


def test_the_invariant_names_of_each_kind():
    assert INVARIANTS == {
        "free_top": ("E", "p", "L"),
        "heavy_top": ("E", "L_z", "L_3"),
        "parabola": ("E", "p_horizontal"),
        "impact": ("p", "L"),
        "bounce": ("p_tangential",),
        "rocket": (),
        "slide": (),
        "roll": ("E",),
        "cradle": ("E", "p", "L"),
        "rest": ("p_tangential",),
        "oblique": (),
    }


def _short(name, duration, dt):
    s = _fresh(name)
    return dataclasses.replace(s, duration=duration, sample_times=_times(duration, dt))


def test_a_figure_that_cannot_be_read_says_why():
    # free top: ω2 crosses zero once in 4 s (at 2.95 s; its period is 7.7 s)
    s = _short("free_top_axis1", 4.0, 1 / 16)
    assert measure(s, reference(s).trajectory) == {
        "omega_period": "ω2 crosses zero 1 time(s) in the samples; 2 are needed for the period"
    }
    # the intermediate moment first in the list: it is ω1 that must cross
    b = s.bodies[0]
    swapped = dataclasses.replace(
        s, bodies=(dataclasses.replace(b, inertia=(3.0, 2.0, 4.0), omega=(0.0, 2.0, 0.2)),)
    )
    tr = reference(s).trajectory
    tr = dataclasses.replace(tr, omega=np.ones_like(tr.omega))
    assert measure(swapped, tr)["omega_period"] == (
        "ω1 crosses zero 0 time(s) in the samples; 2 are needed for the period"
    )
    # heavy top: θ turns every half period (0.34 s), at 0 (not a crossing: it starts at
    # rest) and twice more in 0.75 s
    h = _short("heavy_top", 0.75, 2.0**-7)
    got = measure(h, reference(h).trajectory)
    msg = "θ turns 2 time(s) in the samples; 3 are needed for a period"
    assert got["nutation_period"] == got["precession_rate"] == msg
    np.testing.assert_allclose(got["theta"], reference(h).figures["theta"], atol=2**3 * EPS, rtol=0)
    # parabola: cut before the apex (8/g = 0.82 s)
    p = _short("parabola", 0.5, 2.0**-5)
    msg = "v_z falls through zero 0 times in the samples; expected once (the apex)"
    assert measure(p, reference(p).trajectory) == {"apex_height": msg, "apex_time": msg}
    # bounce: a trajectory with two apexes (the third is at 2.24 s) for a scenario of three
    tr = reference(_short("bouncing_ball", 2.0, 2.0**-5)).trajectory
    msg = (  # the apexes found and the exact ones, three of each at most
        "found 2 apexes (v·n falling through 0) in the samples; expected 3: heights 0.816, "
        "0.522 m at 0.918, 1.65 s, exact 0.816, 0.522, 0.334 m at 0.918, 1.65, 2.24 s"
    )
    assert measure(_fresh("bouncing_ball"), tr) == {"apex_heights": msg, "apex_times": msg}
    # impact: cut before the impact (5/12 s): the bodies still approach
    i = _short("two_body_impact", 0.375, 2.0**-5)
    got = measure(i, reference(i).trajectory)
    assert got["impact_time"] == "the bodies do not separate at the end"
    # rocket: a trajectory without masses
    r = _fresh("rocket")
    tr = dataclasses.replace(reference(r).trajectory, masses=None)
    assert measure(r, tr)["burnout_mass"] == (
        "the trajectory has no masses (field 'masses' is required with thrust)"
    )


def test_impact_figures_are_read_from_the_first_and_last_samples_of_a_made_up_motion():
    s = _fresh("two_body_impact")
    # by hand: bodies 1 and 2 at ±x, separating at 0.5 m/s from an approach at 2 m/s
    t = np.array([0.0, 1.0])
    pos = np.array([[[-1.0, 0, 0], [1.0, 0, 0]], [[-1.0, 0, 0], [0.75, 0, 0]]])
    vel = np.array([[[1.5, 0, 0], [-0.5, 0, 0]], [[-0.25, 0, 0], [0.25, 0, 0]]])
    R = np.broadcast_to(np.eye(3), (2, 2, 3, 3))
    tr = Trajectory(t, pos, vel, R, np.zeros((2, 2, 3)))
    got = measure(s, tr)
    np.testing.assert_array_equal(got["v1_after"], [-0.25, 0, 0])
    np.testing.assert_array_equal(got["v2_after"], [0.25, 0, 0])
    assert got["restitution"] == 0.25  # 0.5 / 2
    # gap at the end 1.75 − 0.25 = 1.5 m, opened at 0.5 m/s: contact 3 s before t = 1
    assert got["impact_time"] == 1.0 - 3.0


def test_rocket_figures_are_the_velocity_gained_along_the_axis_and_the_last_mass():
    s = _fresh("rocket")
    d = TILT[2]
    side = np.cross(d, [1.0, 0.0, 0.0])  # a velocity across the axis does not count
    t = np.array([0.0, 1.0])
    vel = np.array([[[0.0, 0.0, 0.0]], [2.0 * d + side]])
    tr = Trajectory(
        t,
        np.zeros((2, 1, 3)),
        vel,
        np.broadcast_to(TILT, (2, 1, 3, 3)),
        np.zeros((2, 1, 3)),
        np.array([[10.0], [7.0]]),
    )
    got = measure(s, tr)
    assert got["delta_v"] == pytest.approx(2.0, rel=4 * EPS)
    assert got["burnout_mass"] == 7.0


def test_figure_and_invariant_names_of_an_unknown_kind_are_refused():
    s = dataclasses.replace(_fresh("parabola"), extra={"kind": "spring"})
    msg = (
        "scenario 'parabola': extra['kind'] must be one of "
        "['bounce', 'cradle', 'free_top', 'heavy_top', 'impact', 'oblique', 'parabola', 'rest', "
        "'rocket', 'roll', 'slide']; got 'spring'"
    )
    for f in (figure_names, invariant_names, reference):
        with pytest.raises(UnknownScenarioError) as info:
            f(s)
        assert str(info.value) == msg
    tr = reference(_fresh("parabola")).trajectory
    for f in (measure, invariants):
        with pytest.raises(UnknownScenarioError, match=r"must be one of .*got 'spring'"):
            f(s, tr)
    with pytest.raises(UnknownScenarioError, match=r"got None"):
        figure_names(dataclasses.replace(s, extra={}))
    assert issubclass(UnknownScenarioError, MechanicsValueError)


def test_an_unknown_scenario_name_lists_the_batterys():
    with pytest.raises(UnknownScenarioError) as info:
        get_scenario("pendulum")
    assert str(info.value) == (
        "unknown scenario 'pendulum'; the battery has free_top_axis1, free_top_axis3, "
        "free_top_near_separatrix, heavy_top, parabola, two_body_impact, bouncing_ball, rocket, "
        "box_landing_flat, sliding_stop, incline_rolling, newtons_cradle, bounce_to_rest, "
        "oblique_impact_sticks, oblique_impact_slips"
    )


# --------------------------------------------------------------------------- refusals


def _heavy(**changes):
    s = _fresh("heavy_top")
    body = {k: v for k, v in changes.items() if k in ("inertia",)}
    scen = {k: v for k, v in changes.items() if k not in body}
    if body:
        scen["bodies"] = (dataclasses.replace(s.bodies[0], **body),)
    return dataclasses.replace(s, **scen)


@pytest.mark.parametrize(
    ("changes", "detail"),
    [
        ({"inertia": (0.3, 0.31, 0.5)}, "inertia (0.3, 0.31, 0.5), pivot point (0.0, 0.0, -0.1)"),
        (
            {"pivot": Pivot(0, (0.01, 0.0, -0.1))},
            "inertia (0.3, 0.3, 0.5), pivot point (0.01, 0.0, -0.1)",
        ),
        (
            {"pivot": Pivot(0, (0.0, -0.01, -0.1))},
            "inertia (0.3, 0.3, 0.5), pivot point (0.0, -0.01, -0.1)",
        ),
        (
            {"pivot": Pivot(0, (0.0, 0.0, 0.1))},
            "inertia (0.3, 0.3, 0.5), pivot point (0.0, 0.0, 0.1)",
        ),
        (
            {"pivot": Pivot(0, (0.0, 0.0, 0.0))},
            "inertia (0.3, 0.3, 0.5), pivot point (0.0, 0.0, 0.0)",
        ),
    ],
)
def test_the_heavy_top_reference_refuses_an_asymmetric_or_off_axis_top(changes, detail):
    with pytest.raises(MechanicsValueError) as info:
        reference(_heavy(**changes))
    assert str(info.value) == (
        "scenario 'heavy_top': the heavy top needs J1 = J2 and the pivot on axis 3 below G; "
        f"got {detail}"
    )


@pytest.mark.parametrize(
    "gravity", [(0.0, 0.0, 9.81), (0.0, 0.0, 0.0), (0.1, 0.0, -9.81), (0.0, 0.1, -9.81)]
)
def test_the_heavy_top_reference_needs_gravity_down_z(gravity):
    with pytest.raises(MechanicsValueError) as info:
        reference(_heavy(gravity=gravity))
    assert str(info.value) == (
        f"scenario 'heavy_top': gravity must point along −z; got {np.asarray(gravity)}"
    )


def test_the_heavy_top_reference_takes_its_numbers_from_the_scenario():
    # another gravity and a heavier top: the nutation of a heavy symmetric top depends on
    # m g ℓ; the integration of the same body must agree with the reference
    s = dataclasses.replace(
        _heavy(gravity=(0.0, 0.0, -4.0)),
        bodies=(dataclasses.replace(_fresh("heavy_top").bodies[0], mass=2.0),),
        pivot=Pivot(0, (0.0, 0.0, -0.1), (0.5, -0.25, 1.0)),
        duration=0.5,
        sample_times=_times(0.5, 2.0**-4),
    )
    b = s.bodies[0]
    t = np.array(s.sample_times)
    tr = reference(s).trajectory

    def torque(R):
        return np.cross([0.0, 0.0, 0.1], 2.0 * (R @ np.array([0.0, 0.0, -4.0])))

    sol = _integrate(np.array([0.32, 0.32, 0.5]), b.R_A_O, np.array(b.omega), t, torque=torque)
    R = sol.y[:9].T.reshape(-1, 3, 3)
    np.testing.assert_allclose(tr.R_A_O[:, 0], R, atol=IVP_ATOL, rtol=0)
    np.testing.assert_allclose(tr.omega[:, 0], sol.y[9:].T, atol=IVP_ATOL, rtol=0)
    np.testing.assert_allclose(
        tr.position[:, 0], [0.5, -0.25, 1.0] + 0.1 * R[:, 2], atol=IVP_ATOL, rtol=0
    )


def test_the_bouncing_ball_reference_refuses_what_it_does_not_describe():
    s = _fresh("bouncing_ball")
    b = s.bodies[0]
    head = "scenario 'bouncing_ball': the bouncing ball's reference starts at rest along the normal, above the ground, gravity pressing it down; got "
    thrown = dataclasses.replace(s, bodies=(dataclasses.replace(b, velocity=(0.5, 0.0, -1.0)),))
    with pytest.raises(MechanicsValueError) as info:
        reference(thrown)
    assert (
        str(info.value)
        == head + "height 1.275, velocity (0.5, 0.0, -1.0), gravity (0.0, 0.0, -9.81)"
    )
    low = dataclasses.replace(s, bodies=(dataclasses.replace(b, position=(0.0, 0.0, 0.1)),))
    with pytest.raises(MechanicsValueError) as info:
        reference(low)
    assert (
        str(info.value) == head + "height 0.0, velocity (0.5, 0.0, 0.0), gravity (0.0, 0.0, -9.81)"
    )
    for g in ((0.0, 0.0, 9.81), (0.0, 0.0, 0.0)):
        with pytest.raises(MechanicsValueError) as info:
            reference(dataclasses.replace(s, gravity=g))
        assert str(info.value) == head + f"height 1.275, velocity (0.5, 0.0, 0.0), gravity {g}"


def test_the_bouncing_ball_reference_reads_the_ground_plane_and_gravity_of_the_scenario():
    # the same drop on a ground at height 2 along the normal (0, 0, 2) (not unit: the
    # plane n·x = height is z = 1), under g = 4, e = 0.5: the first impact at √(2 h0/g)
    s = _fresh("bouncing_ball")
    b = s.bodies[0]
    s = dataclasses.replace(
        s,
        bodies=(dataclasses.replace(b, position=(0.0, 0.0, 1.0 + 0.1 + 2.0)),),
        ground=Ground(0.5, (0.0, 0.0, 1.0), 1.0),
        gravity=(0.0, 0.0, -4.0),
        duration=2.5,
        sample_times=_times(2.5, 2.0**-5),
    )
    ref = reference(s)
    t = np.array(s.sample_times)
    z, vz = _bounce_by_hand(t, 2.0, 0.5, 4.0)
    np.testing.assert_allclose(ref.trajectory.position[:, 0, 2], 1.1 + z, atol=CLOSED_ATOL, rtol=0)
    np.testing.assert_allclose(ref.trajectory.velocity[:, 0, 2], vz, atol=CLOSED_ATOL, rtol=0)
    tf = 1.0  # √(2·2/4)
    np.testing.assert_allclose(ref.figures["apex_times"], [1.5, 2.25], rtol=READ_RTOL, atol=0)
    np.testing.assert_allclose(ref.figures["apex_heights"], [0.5, 0.125], rtol=READ_RTOL, atol=0)
    assert tf * (1 + 2 * 0.5 + 2 * 0.25 + 0.125) > 2.5  # the third apex is after the end


class _Hung(Exception):
    pass


def _reference_within_half_a_second(s):
    """reference(s), or _Hung: a run past the rest time once looped forever (issue 16)."""
    import signal

    def hung(*_):
        raise _Hung("reference() still running after 0.5 s (it takes milliseconds)")

    old = signal.signal(signal.SIGALRM, hung)
    signal.setitimer(signal.ITIMER_REAL, 0.5)
    try:
        return reference(s)
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0.0)
        signal.signal(signal.SIGALRM, old)


def _drop(e, duration):
    # h0 = 2 (r = 0.1 above z = 0), g = 4: t_f = 1, impacts at 1, 1 + 2e, 1 + 2e + 2e², ...
    s = _fresh("bouncing_ball")
    return dataclasses.replace(
        s,
        bodies=(dataclasses.replace(s.bodies[0], position=(0.0, 0.0, 2.1)),),
        ground=Ground(e),
        gravity=(0.0, 0.0, -4.0),
        duration=duration,
        sample_times=_times(duration, 2.0**-3),
    )


def test_the_bouncing_ball_comes_to_rest_at_tf_1_plus_e_over_1_minus_e():
    # e = 0.5: the impacts accumulate at t_f (1 + e)/(1 − e) = 3 s (a geometric series);
    # after it the ball lies on the ground (it looped forever there before issue 16)
    s = _drop(0.5, 3.5)
    ref = _reference_within_half_a_second(s)
    t = np.array(s.sample_times)
    tr = ref.trajectory
    before = t < 2.75  # by hand, flight by flight, up to the fourth impact
    z, vz = _bounce_by_hand(t[before], 2.0, 0.5, 4.0)
    np.testing.assert_allclose(tr.position[before, 0, 2], 0.1 + z, atol=CLOSED_ATOL, rtol=0)
    np.testing.assert_allclose(tr.velocity[before, 0, 2], vz, atol=CLOSED_ATOL, rtol=0)
    rest = t >= 3.0
    assert rest.sum() == 5  # 3, 3.125, ..., 3.5
    np.testing.assert_allclose(tr.position[rest, 0, 2], 0.1, atol=CLOSED_ATOL, rtol=0)
    assert np.all(tr.velocity[rest, 0, 2] == 0.0)
    # the apexes e^(2k) h0 at 1 + 2e + … + e^k: 0.5 at 1.5, 0.125 at 2.25, …, all before 3
    apex_t, apex_h = ref.figures["apex_times"], ref.figures["apex_heights"]
    np.testing.assert_allclose(apex_t[:2], [1.5, 2.25], rtol=READ_RTOL, atol=0)
    np.testing.assert_allclose(apex_h[:2], [0.5, 0.125], rtol=READ_RTOL, atol=0)
    assert np.all(apex_t < 3.0)
    assert np.all(np.diff(apex_t) > 0)


def test_a_ball_that_does_not_rebound_rests_from_its_first_impact():
    # e = 0: one impact at t_f = 1, then at rest (the list of impacts stood still at t_f)
    s = _drop(0.0, 2.0)
    ref = _reference_within_half_a_second(s)
    t = np.array(s.sample_times)
    z = ref.trajectory.position[:, 0, 2]
    vz = ref.trajectory.velocity[:, 0, 2]
    np.testing.assert_allclose(z[t < 1], 2.1 - 2.0 * t[t < 1] ** 2, atol=CLOSED_ATOL, rtol=0)
    np.testing.assert_allclose(z[t >= 1], 0.1, atol=CLOSED_ATOL, rtol=0)
    assert np.all(vz[t >= 1] == 0.0)
    assert ref.figures["apex_times"].size == 0


@pytest.mark.parametrize(
    "change",
    [
        {"omega": (0.0, 0.0, 0.1)},
        {"gravity": (0.0, 0.0, -9.81)},
        {"bodies": 2},
    ],
)
def test_the_rocket_reference_is_for_one_non_spinning_body_in_free_space(change):
    s = _fresh("rocket")
    b = s.bodies[0]
    if "omega" in change:
        s = dataclasses.replace(s, bodies=(dataclasses.replace(b, omega=change["omega"]),))
    elif "gravity" in change:
        s = dataclasses.replace(s, gravity=change["gravity"])
    else:
        s = dataclasses.replace(s, bodies=(b, dataclasses.replace(b, name="other")))
    with pytest.raises(MechanicsValueError) as info:
        reference(s)
    assert str(info.value) == (
        "scenario 'rocket': the rocket's reference is for one non-spinning body in free space"
    )


def test_the_impact_reference_refuses_a_glancing_impact():
    s = _fresh("two_body_impact")
    a, b = s.bodies
    glancing = dataclasses.replace(s, bodies=(a, dataclasses.replace(b, position=(0.5, 0.1, 0.0))))
    with pytest.raises(MechanicsValueError) as info:
        reference(glancing)
    assert str(info.value) == "scenario 'two_body_impact': the impact must be head-on"


def test_the_impact_reference_follows_the_bodies_along_any_line_and_listed_in_any_order():
    # the same impact along (0, 3, 4)/5, the pair listed (1, 0): nothing but the axis changes
    s = _fresh("two_body_impact")
    a, b = s.bodies
    n = np.array([0.0, 0.6, 0.8])
    moved = dataclasses.replace(
        s,
        bodies=(
            dataclasses.replace(b, position=tuple(0.5 * n), velocity=tuple(-1.0 * n)),
            dataclasses.replace(a, position=tuple(-1.0 * n), velocity=tuple(2.0 * n)),
        ),
        pair_restitution=((1, 0, 0.6),),
    )
    ref = reference(moved)
    base = reference(s)
    np.testing.assert_allclose(
        ref.trajectory.position[:, 1],
        base.trajectory.position[:, 0, :1] * n,
        atol=CLOSED_ATOL,
        rtol=0,
    )
    np.testing.assert_allclose(
        ref.trajectory.position[:, 0],
        base.trajectory.position[:, 1, :1] * n,
        atol=CLOSED_ATOL,
        rtol=0,
    )
    np.testing.assert_allclose(
        ref.trajectory.velocity[:, 1],
        base.trajectory.velocity[:, 0, :1] * n,
        atol=CLOSED_ATOL,
        rtol=0,
    )
    assert ref.figures["impact_time"] == pytest.approx(5 / 12, rel=READ_RTOL)
    # (1, 0): "v1" is the first of the pair, body 1 (the 1 kg sphere)
    np.testing.assert_allclose(ref.figures["v1_after"], -1.6 * n, atol=CLOSED_ATOL, rtol=0)
    np.testing.assert_allclose(ref.figures["v2_after"], 0.2 * n, atol=CLOSED_ATOL, rtol=0)
    got = measure(moved, ref.trajectory)
    np.testing.assert_allclose(got["v1_after"], -1.6 * n, atol=CLOSED_ATOL, rtol=0)
    assert got["restitution"] == pytest.approx(0.6, rel=READ_RTOL)
    assert got["impact_time"] == pytest.approx(5 / 12, rel=READ_RTOL)


# --------------------------------------------------------------------------- invariants


def _two_bodies(kind, **changes):
    """Two spheres (1 kg r 0.1, 3 kg r 0.15) of the impact, relabelled ``kind``."""
    return dataclasses.replace(_fresh("two_body_impact"), extra={"kind": kind}, **changes)


def _made_up(masses=None):
    """Two samples of two bodies, every component different, by hand."""
    t = np.array([0.0, 1.0])
    pos = np.array([[[1.0, 2.0, 3.0], [-1.0, 0.5, 2.0]], [[0.0, 1.0, -2.0], [2.0, -1.0, 0.5]]])
    vel = np.array([[[0.5, -1.0, 2.0], [1.0, 0.0, -0.5]], [[-2.0, 1.0, 0.0], [0.25, 0.5, 1.0]]])
    Rz = _R3(0.4)
    Rx = _R1(-0.3)
    R = np.array([[Rz, Rx], [Rx @ Rz, np.eye(3)]])
    w = np.array([[[1.0, -2.0, 0.5], [0.0, 3.0, 1.0]], [[2.0, 0.0, -1.0], [-1.0, 1.0, 2.0]]])
    return Trajectory(t, pos, vel, R, w, masses)


def test_energy_momentum_and_angular_momentum_of_a_made_up_motion_by_hand():
    s = _two_bodies("free_top", gravity=(0.5, -1.0, -9.0))
    tr = _made_up()
    inv = invariants(s, tr)
    m = np.array([1.0, 3.0])
    J = np.array([0.004, 0.027])
    g = np.array([0.5, -1.0, -9.0])
    E, T, V, P, L, p_sizes, L_sizes = [], [], [], [], [], [], []
    for k in range(2):
        Tk = Vk = 0.0
        Pk, Lk = np.zeros(3), np.zeros(3)
        ps = ls = 0.0
        for i in range(2):
            r, v, R, w = tr.position[k, i], tr.velocity[k, i], tr.R_A_O[k, i], tr.omega[k, i]
            Tk += 0.5 * m[i] * v @ v + 0.5 * J[i] * w @ w
            Vk -= m[i] * g @ r
            Pk += m[i] * v
            spin = R.T @ (J[i] * w)  # J ω in space components
            Lk += np.cross(r, m[i] * v) + spin
            ps += m[i] * np.linalg.norm(v)
            ls += np.linalg.norm(r) * m[i] * np.linalg.norm(v) + np.linalg.norm(spin)
        T.append(Tk)
        V.append(Vk)
        E.append(Tk + Vk)
        P.append(Pk)
        L.append(Lk)
        p_sizes.append(ps)
        L_sizes.append(ls)
    values, scale = inv["E"]
    np.testing.assert_allclose(values, E, rtol=CLOSED_ATOL, atol=0)
    assert scale == pytest.approx(max(np.abs(T).max(), np.abs(V).max()), rel=CLOSED_ATOL)
    values, scale = inv["p"]
    np.testing.assert_allclose(values, P, rtol=CLOSED_ATOL, atol=0)
    # the bodies' spin momentum m · size · max |ω| is smaller here than Σ m |v|
    assert scale == pytest.approx(max(p_sizes), rel=CLOSED_ATOL)
    values, scale = inv["L"]
    np.testing.assert_allclose(values, L, rtol=CLOSED_ATOL, atol=CLOSED_ATOL)
    assert scale == pytest.approx(max(L_sizes), rel=CLOSED_ATOL)
    # the impact conserves the same p and L about the origin (no gravity in its sums)
    impact = invariants(_two_bodies("impact"), tr)
    assert tuple(impact) == ("p", "L")
    np.testing.assert_allclose(impact["p"][0], P, rtol=CLOSED_ATOL, atol=0)
    np.testing.assert_allclose(impact["L"][0], L, rtol=CLOSED_ATOL, atol=CLOSED_ATOL)
    assert impact["L"][1] == pytest.approx(max(L_sizes), rel=CLOSED_ATOL)


def test_a_trajectorys_own_masses_make_its_kinetic_energy():
    s = _two_bodies("free_top")
    tr = _made_up(masses=np.array([[1.0, 3.0], [0.5, 2.0]]))
    E, _ = invariants(s, tr)["E"]
    # at t = 1 the masses are 0.5 and 2: ½ 0.5 |v1|² + ½ 2 |v2|² + the spins (no gravity)
    v1, v2 = tr.velocity[1]
    spins = (
        0.5 * 0.004 * tr.omega[1, 0] @ tr.omega[1, 0]
        + 0.5 * 0.027 * tr.omega[1, 1] @ tr.omega[1, 1]
    )
    assert E[1] == pytest.approx(0.25 * v1 @ v1 + v2 @ v2 + spins, rel=CLOSED_ATOL)


def test_the_momentum_scale_of_bodies_that_only_turn_is_their_points_momentum():
    # a free top at rest in translation: the scale is m · size · max |ω| with the size the
    # larger of √(max J/m) and |shape dims|: for the 1 kg box, |(√7.5, √4.5, √1.5)| = √13.5
    s = _fresh("free_top_axis1")
    tr = reference(s).trajectory
    _, scale = invariants(s, tr)["p"]
    w_max = np.linalg.norm(tr.omega[:, 0], axis=-1).max()
    assert scale == pytest.approx(math.sqrt(13.5) * w_max, rel=CLOSED_ATOL)
    np.testing.assert_allclose(body_sizes(s), [math.sqrt(13.5)], rtol=4 * EPS, atol=0)
    # without a shape, the radius of gyration √(max J/m); a shape smaller than that: the same
    r = _fresh("rocket")
    np.testing.assert_allclose(body_sizes(r), [math.sqrt(0.1 / 10.0)], rtol=4 * EPS, atol=0)
    tiny = dataclasses.replace(r.bodies[0], shape=Shape("sphere", (0.01,)))
    np.testing.assert_allclose(
        body_sizes(dataclasses.replace(r, bodies=(tiny,))), [0.1], rtol=4 * EPS, atol=0
    )


def test_nothing_moving_has_invariant_scales_of_1e_minus_300_not_zero():
    s = _two_bodies("free_top")
    t = np.array([0.0, 1.0])
    still = Trajectory(
        t,
        np.zeros((2, 2, 3)),
        np.zeros((2, 2, 3)),
        np.broadcast_to(np.eye(3), (2, 2, 3, 3)),
        np.zeros((2, 2, 3)),
    )
    inv = invariants(s, still)
    assert [inv[k][1] for k in ("E", "p", "L")] == [1e-300, 1e-300, 1e-300]
    h = _fresh("heavy_top")
    one = Trajectory(
        t,
        np.zeros((2, 1, 3)),
        np.zeros((2, 1, 3)),
        np.broadcast_to(np.eye(3), (2, 1, 3, 3)),
        np.zeros((2, 1, 3)),
    )
    inv = invariants(h, one)
    assert inv["L_3"][1] == 1e-300
    assert inv["L_z"][1] == 1e-300


def test_heavy_top_invariants_are_about_the_pivots_anchor():
    s = dataclasses.replace(_fresh("heavy_top"), pivot=Pivot(0, (0.0, 0.0, -0.1), (1.0, 2.0, 0.0)))
    t = np.array([0.0])
    # G at (1, 2.5, 0) moving along x at 2 m/s, body axes = space axes, ω = (0, 1, 4)
    tr = Trajectory(
        t,
        np.array([[[1.0, 2.5, 0.0]]]),
        np.array([[[2.0, 0.0, 0.0]]]),
        np.eye(3)[None, None],
        np.array([[[0.0, 1.0, 4.0]]]),
    )
    inv = invariants(s, tr)
    # L_z about the anchor: (r − a) × m v = (0, 0.5, 0) × (2, 0, 0) = (0, 0, −1), plus J3 ω3 = 2
    assert inv["L_z"][0][0] == pytest.approx(-1.0 + 2.0, rel=CLOSED_ATOL)
    assert inv["L_3"][0][0] == 0.5 * 4.0
    assert inv["L_3"][1] == 2.0
    # E = ½ m v² + ½ (0.3·1 + 0.5·16) − m g·r = 2 + 4.15 + 0 (z = 0)
    assert inv["E"][0][0] == pytest.approx(2.0 + 4.15, rel=CLOSED_ATOL)


def test_the_parabolas_and_bounces_momentum_invariants_are_the_parts_along_the_ground():
    tr = _made_up()
    P = 1.0 * tr.velocity[:, 0] + 3.0 * tr.velocity[:, 1]
    inv = invariants(_two_bodies("parabola"), tr)
    np.testing.assert_allclose(inv["p_horizontal"][0], P[:, :2], rtol=CLOSED_ATOL, atol=0)
    n = np.array([0.0, 0.6, 0.8])
    s = _two_bodies("bounce", ground=Ground(0.5, tuple(n)))
    got, _ = invariants(s, tr)["p_tangential"]
    np.testing.assert_allclose(got, P - np.outer(P @ n, n), rtol=0, atol=CLOSED_ATOL)
    assert invariants(_fresh("rocket"), reference(_fresh("rocket")).trajectory) == {}


# --------------------------------------------------------------------------- helpers


def test_crossings_are_the_roots_of_a_sampled_polynomial_to_rounding():
    # y = (t − 0.3)(t − 1.1)(t − 2.05): a cubic, reproduced exactly by the degree-5 local
    # polynomial; rising at 0.3 and 2.05, falling at 1.1
    t = np.arange(0, 41) / 16
    y = (t - 0.3) * (t - 1.1) * (t - 2.05)
    np.testing.assert_allclose(crossings(t, y), [0.3, 1.1, 2.05], rtol=0, atol=2**4 * EPS)
    np.testing.assert_allclose(crossings(t, y, direction=1), [0.3, 2.05], rtol=0, atol=2**4 * EPS)
    np.testing.assert_allclose(crossings(t, y, direction=-1), [1.1], rtol=0, atol=2**4 * EPS)
    # a degree of 1 keeps the secant through the two samples: not the root of the cubic
    lin = crossings(t, y, deg=1)
    assert np.abs(lin - [0.3, 1.1, 2.05]).max() > 1e-4
    # the secant's root is exact for a line, whatever the degree
    np.testing.assert_allclose(crossings(t, 0.7 - t), [0.7], rtol=0, atol=4 * EPS)


def test_a_zero_at_a_sample_counts_once_on_the_side_it_ends():
    t = np.arange(0, 9) / 4
    y = t - 1.0  # zero at the sample t = 1: rises through it once
    np.testing.assert_allclose(crossings(t, y), [1.0], rtol=0, atol=4 * EPS)
    np.testing.assert_allclose(crossings(t, -y), [1.0], rtol=0, atol=4 * EPS)
    assert crossings(t, -y, direction=1).size == 0
    # touching zero from above at a sample and going back up: a fall into 0, no rise
    np.testing.assert_allclose(crossings(t, (t - 1.0) ** 2), [1.0], rtol=0, atol=4 * EPS)
    assert crossings(t, (t - 1.0) ** 2, direction=1).size == 0
    assert crossings(t, t + 1.0).size == 0


def test_interpolate_reproduces_a_polynomial_of_its_degree_anywhere_in_the_samples():
    t = np.arange(0, 33) / 8
    y = 1.0 - 2.0 * t + 0.5 * t**3 - 0.125 * t**5

    def p(x):
        return 1.0 - 2.0 * x + 0.5 * x**3 - 0.125 * x**5

    for tau in (0.0, 0.01, 1.3, 2.0, 3.99, 4.0):
        assert interpolate(t, y, tau) == pytest.approx(p(tau), rel=2**8 * EPS, abs=2**8 * EPS)
    # degree 2 through three samples: exact for a parabola, not for the quintic
    q = 3.0 - t + 0.25 * t**2
    assert interpolate(t, q, 2.3, deg=2) == pytest.approx(3.0 - 2.3 + 0.25 * 2.3**2, rel=2**4 * EPS)
    assert abs(interpolate(t, y, 2.3, deg=2) - p(2.3)) > 1e-4


def test_interpolate_uses_the_samples_next_to_the_time():
    # sin 3t at 64 samples per unit: the local quintic's remainder is 3⁶/6! |Π (t − t_i)|
    # ≤ 3.5 h⁶ = 5e-11 inside, ~1e-10 at the ends (the window held inside the samples);
    # 2^-33 = 1.2e-10 bounds both, a window away from τ does far worse
    t = np.arange(0, 513) / 64
    y = np.sin(3.0 * t)
    for tau in (0.003, 0.03, 2.51, 4.0, 7.97, 7.999):
        assert abs(interpolate(t, y, tau) - math.sin(3.0 * tau)) < 2**-33, tau
    z = crossings(t, y)
    np.testing.assert_allclose(z, np.arange(1, 8) * math.pi / 3, rtol=0, atol=2**-33)


# --------------------------------------------------------------------------- variants


def test_a_heavy_top_released_with_a_general_spin_agrees_with_the_integration():
    # every Euler angle and every body component of ω non-zero: the reference turns them
    # into Euler rates (2.69) and back; the integration starts from them directly
    s = _fresh("heavy_top")
    R0 = _passive(0.3, 0.6, 0.5)
    w0 = np.array([0.7, -0.4, 6.0])
    b = dataclasses.replace(s.bodies[0], R_A_O=tuple(map(tuple, R0)), omega=tuple(w0))
    s = dataclasses.replace(s, bodies=(b,), duration=0.5, sample_times=_times(0.5, 2.0**-4))
    t = np.array(s.sample_times)
    tr = reference(s).trajectory
    sol = _integrate(np.array([0.31, 0.31, 0.5]), R0, w0, t, torque=_heavy_torque)
    R = sol.y[:9].T.reshape(-1, 3, 3)
    np.testing.assert_allclose(tr.R_A_O[:, 0], R, atol=IVP_ATOL, rtol=0)
    np.testing.assert_allclose(tr.omega[:, 0], sol.y[9:].T, atol=IVP_ATOL, rtol=0)
    rho = 0.1 * R[:, 2]
    w_O = np.einsum("tji,tj->ti", R, sol.y[9:].T)
    np.testing.assert_allclose(tr.velocity[:, 0], np.cross(w_O, rho), atol=IVP_ATOL, rtol=0)


def test_a_free_top_that_also_drifts_moves_its_centre_uniformly():
    s = _fresh("free_top_axis3")
    b = dataclasses.replace(s.bodies[0], position=(1.0, 2.0, 3.0), velocity=(0.5, -1.0, 2.0))
    s = dataclasses.replace(s, bodies=(b,), duration=1.0, sample_times=_times(1.0, 0.25))
    tr = reference(s).trajectory
    t = np.array(s.sample_times)
    np.testing.assert_allclose(
        tr.position[:, 0],
        np.array([1.0, 2.0, 3.0]) + np.outer(t, [0.5, -1.0, 2.0]),
        atol=CLOSED_ATOL,
        rtol=0,
    )
    np.testing.assert_array_equal(tr.velocity[:, 0], np.broadcast_to([0.5, -1.0, 2.0], (t.size, 3)))


def test_a_rocket_that_starts_moving_adds_its_initial_motion():
    s = _fresh("rocket")
    b = dataclasses.replace(s.bodies[0], position=(1.0, 2.0, 3.0), velocity=(0.5, -1.0, 2.0))
    s = dataclasses.replace(s, bodies=(b,), duration=1.0, sample_times=_times(1.0, 0.5))
    tr = reference(s).trajectory
    d = TILT[2]
    t = np.array(s.sample_times)
    m = 10.0 - 0.5 * t
    v = 20.0 * np.log(10.0 / m)
    x = 20.0 * (t - (m / 0.5) * np.log(10.0 / m))
    v0, x0 = np.array([0.5, -1.0, 2.0]), np.array([1.0, 2.0, 3.0])
    np.testing.assert_allclose(
        tr.velocity[:, 0], v0 + v[:, None] * d, atol=2**3 * CLOSED_ATOL, rtol=0
    )
    np.testing.assert_allclose(
        tr.position[:, 0], x0 + np.outer(t, v0) + x[:, None] * d, atol=2**3 * CLOSED_ATOL, rtol=0
    )
    got = measure(s, tr)
    assert got["delta_v"] == pytest.approx(20.0 * math.log(10.0 / 9.5), rel=READ_RTOL)


def test_a_bounce_on_a_tilted_ground_follows_its_normal_and_keeps_the_drift_along_it():
    # the ground n·x = 0.5 with n = (0.6, 0, 0.8), gravity −9.81 n, a drift along y (v·n = 0
    # exactly) and a start off along (0.8, 0, −0.6)
    n = np.array([0.6, 0.0, 0.8])
    tang = np.array([0.0, 1.0, 0.0])
    s = _fresh("bouncing_ball")
    p0 = (0.5 + 0.1 + 1.275) * n + 2.0 * np.array([0.8, 0.0, -0.6])  # lowest point 1.275 up
    b = dataclasses.replace(s.bodies[0], position=tuple(p0), velocity=tuple(0.5 * tang))
    s = dataclasses.replace(
        s, bodies=(b,), ground=Ground(0.8, tuple(n), 0.5), gravity=tuple(-G * n)
    )
    ref = reference(s)
    t = np.array(s.sample_times)
    z, vz = _bounce_by_hand(t, 1.275, 0.8, G)
    want = p0 + np.outer(t, 0.5 * tang) + np.outer(z - 1.275, n)
    np.testing.assert_allclose(ref.trajectory.position[:, 0], want, atol=2**3 * CLOSED_ATOL, rtol=0)
    np.testing.assert_allclose(
        ref.trajectory.velocity[:, 0], 0.5 * tang + np.outer(vz, n), atol=2**3 * CLOSED_ATOL, rtol=0
    )
    got = measure(s, ref.trajectory)
    np.testing.assert_allclose(
        got["apex_heights"], [1.275 * 0.8 ** (2 * k) for k in (1, 2, 3)], rtol=2**8 * EPS, atol=0
    )
    np.testing.assert_allclose(
        got["apex_times"], ref.figures["apex_times"], rtol=2**8 * EPS, atol=0
    )


def test_spinning_spheres_keep_their_free_rotation_through_the_impact():
    s = _fresh("two_body_impact")
    a, b = s.bodies
    w = np.array([0.0, 1.0, 2.0])
    s = dataclasses.replace(s, bodies=(dataclasses.replace(a, omega=tuple(w)), b))
    tr = reference(s).trajectory
    t = np.array(s.sample_times)
    for k in (0, 13, 14, 32):
        np.testing.assert_allclose(tr.R_A_O[k, 0], expm(-_hat(w) * t[k]), atol=CLOSED_ATOL, rtol=0)
    np.testing.assert_allclose(
        tr.omega[:, 0], np.broadcast_to(w, (t.size, 3)), atol=CLOSED_ATOL, rtol=0
    )
    np.testing.assert_array_equal(tr.R_A_O[:, 1], np.broadcast_to(np.eye(3), (t.size, 3, 3)))


def test_head_on_means_within_2_to_the_6_eps_of_the_line():
    # d = (1.5, δ, 0), Δv = (−3, 0, 0): |d × Δv| = 3δ against 2^6 eps |d| |Δv| = 2^6 eps 4.5,
    # so δ up to 96 eps is head-on (rounding), 120 eps is not
    s = _fresh("two_body_impact")
    a, b = s.bodies
    for dy, ok in ((80 * EPS, True), (120 * EPS, False)):
        moved = dataclasses.replace(s, bodies=(a, dataclasses.replace(b, position=(0.5, dy, 0.0))))
        if ok:
            assert reference(moved).figures["restitution"] == 0.6
        else:
            with pytest.raises(MechanicsValueError, match="the impact must be head-on"):
                reference(moved)
