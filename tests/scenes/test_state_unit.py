"""Unit tests of :mod:`mechanics.scenes.state`: the flat state's layout per kind of body,
gather and pack, ω from L and J, the equations of motion, the shapes' geometry and the
fixed axis (:class:`Hinge`) (issue 16).

Expected values are hand formulas (the book's catalogue of moments with numbers that make
them exact, the rotation matrices R1, R2, R3), or laws the derivative must obey whatever
its form: the space angular momentum Rᵀ L changes by the applied moment only, R Rᵀ
stays I, a hinged body's energy is conserved.
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import mpmath
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from mechanics._floats import EPS
from mechanics.scenes.effects.base import Snapshot
from mechanics.scenes.spec import Body
from mechanics.scenes.state import (
    ROUND_SHAPES,
    SPHERICAL_SHAPES,
    Guide,
    Hinge,
    Layout,
    _carousel,
    _col,
    body_inertia,
    body_radius,
    body_vertices,
    pendulum_from_rest,
    turned,
)
from mechanics.strategies import rotation_matrices

from .builders import snapshot_of

#: a product of a few O(1) factors and a sum of three: each entry within a few roundings
FEW_ROUNDINGS = 8 * EPS
#: the catalogue's moments: a product and a division, each rounded once or twice
MOMENT_RTOL = 4 * EPS
#: an O(1) angle through cos and sin (each within an ulp) and a sum of two products
TRIG_ATOL = 4 * EPS
#: an exact flow of a few terms against mpmath at 30 digits, values O(1)
FLOW_ATOL = 16 * EPS

E1, E2, E3 = np.eye(3)
#: an exact-rational rotation (rows 1/3 (2, −1, 2), 1/3 (2, 2, −1), 1/3 (−1, 2, 2))
R_PYTH = np.array([[2.0, -1.0, 2.0], [2.0, 2.0, -1.0], [-1.0, 2.0, 2.0]]) / 3.0


def skew(w) -> np.ndarray:
    """[w]×: skew(w) @ x = w × x."""
    return np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])


def R1(t):
    c, s = math.cos(t), math.sin(t)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, s], [0.0, -s, c]])


def R2(t):
    c, s = math.cos(t), math.sin(t)
    return np.array([[c, 0.0, -s], [0.0, 1.0, 0.0], [s, 0.0, c]])


def R3(t):
    c, s = math.cos(t), math.sin(t)
    return np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])


def body(shape, mass=1.0, *, fixed=False, initial=None, **dims) -> Body:
    return Body("b", shape, mass, dims, {} if initial is None else initial, fixed)


def z_hinge(h=0.5, J_a=2.0, C=(0.0, 0.0, 0.0)) -> Hinge:
    """A hinge about e3 through C, φ = 0 along e1: body axis 2 along e3, 0 toward G."""
    return Hinge(np.array(C, float), E3.copy(), E1.copy(), E2.copy(), 2, 0, 1, h, J_a)


# ---------------------------------------------------------------- turned


@pytest.mark.parametrize(
    ("a", "u0", "k", "passive"),
    [
        (E3, E1, 2, R3),  # body e3 on the axis: the book's R3(θ)
        (E1, E2, 0, R1),  # e1 on the axis, e2 at θ = 0: R1(θ)
        (E2, E3, 1, R2),  # e2 on the axis, e3 at θ = 0: R2(θ)
    ],
)
@pytest.mark.parametrize("theta", [0.0, 0.3, -2.0, math.pi / 2])
def test_a_body_turned_about_a_coordinate_axis_has_the_books_rotation_matrix(
    a, u0, k, passive, theta
) -> None:
    got = turned(a, u0, k, np.float64(theta))
    np.testing.assert_allclose(got, passive(theta), rtol=0, atol=TRIG_ATOL)


def test_turned_takes_any_shape_of_angles_and_a_general_axis() -> None:
    a = np.array([1.0, 2.0, 2.0]) / 3.0
    u0 = np.array([2.0, 1.0, -2.0]) / 3.0  # ⟂ a
    theta = np.array([[0.0, 0.25], [1.0, -3.0]])
    R = turned(a, u0, 1, theta)
    assert R.shape == (2, 2, 3, 3)
    u1 = np.cross(a, u0)
    for idx in np.ndindex(theta.shape):
        c, s = math.cos(theta[idx]), math.sin(theta[idx])
        np.testing.assert_allclose(R[idx][1], a, rtol=0, atol=0)
        np.testing.assert_allclose(R[idx][2], c * u0 + s * u1, rtol=0, atol=TRIG_ATOL)
        np.testing.assert_allclose(R[idx][0], c * u1 - s * u0, rtol=0, atol=TRIG_ATOL)
        np.testing.assert_allclose(R[idx] @ R[idx].T, np.eye(3), rtol=0, atol=TRIG_ATOL)


# ---------------------------------------------------------------- Guide, Hinge


def test_the_guide_base_class_leaves_place_and_start_to_subclasses() -> None:
    g = Guide()
    assert g.nq == 1
    with pytest.raises(NotImplementedError):
        g.place(np.zeros(1))
    with pytest.raises(NotImplementedError):
        g.start({})
    assert g.exact([], 1.0, np.zeros(1), np.zeros(1), 1.0) is None
    assert g.series(np.zeros((3, 1)), np.zeros((3, 1))) == {}
    # no bend of the path: zeros of G's shape, (..., 3) for coordinates (..., nq)
    for shape in [(2,), (4, 2), (2, 5, 1)]:
        bend = g.bend(np.ones(shape), np.ones(shape))
        assert bend.shape == (*shape[:-1], 3)
        assert not bend.any()


def test_a_hinge_places_g_on_its_circle_with_the_tangent_as_the_rate() -> None:
    # C = (1, 2, 3), h = 0.5 about e3, φ = 0.7: G = C + h (cos φ, sin φ, 0),
    # ∂G/∂φ = h (−sin φ, cos φ, 0), R_A_O = R3(φ), W = e3, M = (J_a,)
    hinge = z_hinge(h=0.5, J_a=2.0, C=(1.0, 2.0, 3.0))
    phi = 0.7
    G, E, R = hinge.place(np.array([phi]))
    c, s = math.cos(phi), math.sin(phi)
    np.testing.assert_allclose(G, [1.0 + 0.5 * c, 2.0 + 0.5 * s, 3.0], rtol=0, atol=TRIG_ATOL)
    assert E.shape == (1, 3)
    np.testing.assert_allclose(E, [[-0.5 * s, 0.5 * c, 0.0]], rtol=0, atol=TRIG_ATOL)
    np.testing.assert_allclose(R, R3(phi), rtol=0, atol=TRIG_ATOL)
    np.testing.assert_array_equal(hinge.W, [[0.0, 0.0, 1.0]])
    np.testing.assert_array_equal(hinge.M, [2.0])
    rhat, tang, R_ = hinge.frame(np.float64(phi))
    np.testing.assert_allclose(rhat, [c, s, 0.0], rtol=0, atol=TRIG_ATOL)
    np.testing.assert_allclose(tang, [-s, c, 0.0], rtol=0, atol=TRIG_ATOL)
    np.testing.assert_allclose(R_, R3(phi), rtol=0, atol=TRIG_ATOL)


def test_a_hinged_centre_bends_toward_the_axis_by_h_phidot_squared() -> None:
    # the centripetal part of a_G: −h φ̇² r̂ = −0.5 · 9 · (cos φ, sin φ, 0)
    hinge = z_hinge(h=0.5)
    phi = 0.7
    got = hinge.bend(np.array([phi]), np.array([3.0]))
    np.testing.assert_allclose(
        got, [-4.5 * math.cos(phi), -4.5 * math.sin(phi), 0.0], rtol=0, atol=8 * TRIG_ATOL
    )
    batch = hinge.bend(np.zeros((5, 1)), np.full((5, 1), 2.0))
    np.testing.assert_allclose(batch, np.tile([-2.0, 0.0, 0.0], (5, 1)), rtol=0, atol=0)


def test_a_hinge_starts_from_the_bodys_angle_and_angular_velocity() -> None:
    hinge = z_hinge()
    q, qd = hinge.start({"angle": 0.25, "angular_velocity": -1.5})
    np.testing.assert_array_equal(q, [0.25])
    np.testing.assert_array_equal(qd, [-1.5])
    q, qd = hinge.start({})
    np.testing.assert_array_equal(q, [0.0])
    np.testing.assert_array_equal(qd, [0.0])


def test_a_hinges_series_add_the_books_picture_of_g_when_it_is_off_the_axis() -> None:
    phi = np.array([[0.0], [math.pi / 6]])
    phid = np.array([[1.0], [2.0]])
    out = z_hinge(h=2.0).series(phi, phid)
    assert set(out) == {"phi", "phidot", "x_G", "y_G"}
    np.testing.assert_array_equal(out["phi"], [0.0, math.pi / 6])
    np.testing.assert_array_equal(out["phidot"], [1.0, 2.0])
    # G at h (sin φ, −cos φ): (0, −2) and (1, −√3)
    np.testing.assert_allclose(out["x_G"], [0.0, 1.0], rtol=0, atol=TRIG_ATOL)
    np.testing.assert_allclose(out["y_G"], [-2.0, -math.sqrt(3.0)], rtol=0, atol=TRIG_ATOL)
    assert set(z_hinge(h=0.5).series(phi, phid)) == {"phi", "phidot", "x_G", "y_G"}
    assert set(z_hinge(h=0.0).series(phi, phid)) == {"phi", "phidot"}


def test_a_hinges_rate_is_the_generalised_force_over_its_inertia() -> None:
    # q̈ = (E·F + W·M)/J_a at φ = 0: E = h e2 = 0.5 e2, so E·F = 0.5 · 6 = 3; W·M = 5;
    # over J_a = 2: 4; over a grown inertia 16: 1/2
    hinge = z_hinge(h=0.5, J_a=2.0)
    F, M = np.array([7.0, 6.0, 1.0]), np.array([9.0, -9.0, 5.0])
    np.testing.assert_array_equal(hinge.rate(np.array([0.0]), F, M), [4.0])
    np.testing.assert_array_equal(hinge.rate(np.array([0.0]), F, M, np.array([16.0])), [0.5])


def test_a_hinged_points_rate_is_its_velocity_per_unit_phidot() -> None:
    # at φ = 0, G = (0.5, 0, 0); the point S = (1, 0, 7) turns about e3 at distance 1:
    # velocity e3 × (1, 0, 0) = e2 per unit φ̇ (E + W × (S − G) = 0.5 e2 + 0.5 e2)
    hinge = z_hinge(h=0.5)
    u = hinge.point_rate(np.array([0.0]), np.array([1.0, 0.0, 7.0]))
    np.testing.assert_allclose(u, [[0.0, 1.0, 0.0]], rtol=0, atol=0)


def test_a_hinges_moment_about_its_point_adds_the_forces_moment_arm() -> None:
    # Rᵀ M_A + (r − C) × F with R = R_PYTH: Rᵀ e1 = R's first row (2, −1, 2)/3;
    # r − C = e1, F = 2 e2: e1 × 2 e2 = 2 e3
    hinge = z_hinge(C=(1.0, 1.0, 1.0))
    got = hinge.moment(R_PYTH, np.array([2.0, 1.0, 1.0]), 2.0 * E2, E1)
    np.testing.assert_allclose(got, [2 / 3, -1 / 3, 2 / 3 + 2.0], rtol=0, atol=FEW_ROUNDINGS)


def test_col_makes_one_coordinate_columns() -> None:
    q, qd = _col([1, 2], 3)
    assert q.dtype == float
    assert qd.dtype == float
    assert q.shape == (2, 1)
    assert qd.shape == (1,)
    np.testing.assert_array_equal(q[:, 0], [1.0, 2.0])


# ---------------------------------------------------------------- exact flows of a hinge


def fake(kind, **attrs):
    return SimpleNamespace(type=kind, **attrs)


def test_a_free_hinged_body_turns_uniformly() -> None:
    how, f, events = z_hinge().exact([], 1.0, np.array([0.5]), np.array([-2.0]), 3.0)
    assert how == "exact: uniform rotation"
    assert events == []
    q, qd = f(np.array([0.0, 1.0, 2.5]))
    # φ0 + ω t = 0.5, −1.5, −4.5; ω = −2 throughout
    np.testing.assert_array_equal(q, [[0.5], [-1.5], [-4.5]])
    np.testing.assert_array_equal(qd, [[-2.0], [-2.0], [-2.0]])


def test_a_torsion_pendulum_oscillates_harmonically_and_keeps_its_energy() -> None:
    # J φ̈ = −τ0 φ, J = 2, τ0 = 8: ω = 2; after a quarter period (t = π/4) the
    # displacement has turned into speed: φ = ω0/ω = −1.5/2, φ̇ = −φ0 ω = −0.5 · 2
    hinge = z_hinge(J_a=2.0)
    how, f, events = hinge.exact(
        [fake("torsion", tau_0=8.0)], 1.0, np.array([0.5]), np.array([-1.5]), 3.0
    )
    assert how == "exact: harmonic torsion oscillation"
    assert events == []
    t = np.array([0.0, math.pi / 4, 0.3, 1.7])
    q, qd = f(t)
    assert q.shape == qd.shape == (4, 1)
    np.testing.assert_allclose(q[:2, 0], [0.5, -0.75], rtol=0, atol=TRIG_ATOL)
    np.testing.assert_allclose(qd[:2, 0], [-1.5, -1.0], rtol=0, atol=TRIG_ATOL)
    # ½ J φ̇² + ½ τ0 φ² = ½ · 2 · 2.25 + ½ · 8 · 0.25 = 3.25 at every time
    energy = 0.5 * 2.0 * qd[:, 0] ** 2 + 0.5 * 8.0 * q[:, 0] ** 2
    np.testing.assert_allclose(energy, 3.25, rtol=FEW_ROUNDINGS, atol=0)


def carousel_phi(J0, w0, q, R, r, v, phi0, t) -> float:
    """φ(t) by quadrature of φ̇ = (J0 ω0 − r q v s)/(J0 + q R² s) (7.39), mpmath."""
    rate = lambda s: (J0 * w0 - r * q * v * s) / (J0 + q * R**2 * s)  # noqa: E731
    with mpmath.workdps(30):
        return float(phi0 + mpmath.quad(rate, [0, t]))


@pytest.mark.parametrize("q", [0.5, 0.0])
def test_the_carousel_under_fire_follows_the_angular_momentum_balance(q) -> None:
    # J0 = 2, ω0 = 3, R = 3, r = 1, v = 4: q R² = 9q, r q v = 4q, so
    # φ̇(t) = (J0 ω0 − r q v t)/(J0 + q R² t) = (6 − 4q t)/(2 + 9q t)
    flow = fake("mass_flow", q=q, R=3.0, r=1.0, v=4.0)
    hinge = z_hinge(J_a=2.0)
    how, f, events = hinge.exact([flow], 1.0, np.array([0.25]), np.array([3.0]), 5.0)
    assert how == "exact: carousel under fire, solution of (7.39)"
    assert events == []
    t = np.array([0.0, 1.0, 2.5])
    phi, w = f(t)
    assert phi.shape == w.shape == (3, 1)
    expect_w = [(6.0 - 4 * q * s) / (2.0 + 9 * q * s) for s in t]
    np.testing.assert_allclose(w[:, 0], expect_w, rtol=FEW_ROUNDINGS, atol=0)
    expect_phi = [carousel_phi(2.0, 3.0, q, 3.0, 1.0, 4.0, 0.25, s) for s in t]
    np.testing.assert_allclose(phi[:, 0], expect_phi, rtol=0, atol=FLOW_ATOL)
    assert _carousel(flow, 2.0, 0.25, 3.0)[0] == how


@pytest.mark.parametrize("phi0", [1.0, 0.5, -2.0])
def test_a_pendulum_released_from_rest_swings_through_the_bottom_at_the_energy_speed(
    phi0,
) -> None:
    # J φ̈ = −m g h sin φ, J = 2, m g h = 0.5 · 4 · 1: ω0 = 1; after a quarter period
    # K(k²)/ω0, k = sin(|φ0|/2), it passes φ = 0 at the speed of energy conservation,
    # |φ̇| = √(2 m g h (1 − cos φ0)/J) = 2 k ω0, moving back toward the other side
    gravity = fake("gravity", axis_g_perp=lambda a: 4.0 if np.array_equal(a, E3) else 0.0)
    hinge = z_hinge(h=1.0, J_a=2.0)
    how, f, events = hinge.exact([gravity], 0.5, np.array([phi0]), np.array([0.0]), 10.0)
    assert how == "exact: pendulum released from rest, Jacobi elliptic functions (4.50)"
    assert events == []
    k = math.sin(abs(phi0) / 2)
    quarter = float(mpmath.ellipk(k * k))
    q, qd = f(np.array([0.0, quarter]))
    np.testing.assert_allclose(q[:, 0], [phi0, 0.0], rtol=0, atol=FLOW_ATOL)
    np.testing.assert_allclose(qd[:, 0], [0.0, -math.copysign(2 * k, phi0)], rtol=0, atol=FLOW_ATOL)
    # at any time: ½ J φ̇² − m g h cos φ = −m g h cos φ0
    t = np.linspace(0.1, 5.0, 7)
    q, qd = f(t)
    energy = 0.5 * 2.0 * qd[:, 0] ** 2 - 2.0 * np.cos(q[:, 0])
    np.testing.assert_allclose(energy, -2.0 * math.cos(phi0), rtol=0, atol=FLOW_ATOL)


def test_pendulum_from_rest_gives_the_rate_of_the_angle_it_gives() -> None:
    # J = 3, m g h = 2 · 1.5 · 0.5: ω0 = √(1.5/3); φ̇ against a central difference of φ
    f = pendulum_from_rest(3.0, 2.0, 1.5, 0.5, 2.5)
    t = np.array([0.7, 2.0, 4.1])
    step = 2.0**-12
    (qp, _), (qm, _), (_, qd) = f(t + step), f(t - step), f(t)
    # the central difference errs by step²/6 |φ'''| (≤ 1 here) plus 2 eps/step
    fd = (qp - qm) / (2 * step)
    np.testing.assert_allclose(qd, fd, rtol=0, atol=step**2 + 4 * EPS / step)


@pytest.mark.parametrize(
    ("kinds", "w0", "phi0", "gp", "h"),
    [
        (["gravity"], 0.5, 1.0, 4.0, 1.0),  # moving at the start: no closed form here
        (["gravity"], 0.0, 3.5, 4.0, 1.0),  # beyond π
        (["gravity"], 0.0, -3.5, 4.0, 1.0),
        (["gravity"], 0.0, 1.0, 0.0, 1.0),  # gravity along the axis
        (["gravity"], 0.0, 1.0, 4.0, 0.0),  # G on the axis
        (["gravity", "torsion"], 0.0, 1.0, 4.0, 1.0),  # two effects
        (["drag"], 0.0, 1.0, 4.0, 1.0),
    ],
)
def test_a_hinge_has_no_exact_flow_outside_its_closed_forms(kinds, w0, phi0, gp, h) -> None:
    effects = [fake(k, axis_g_perp=lambda a, gp=gp: gp, tau_0=1.0) for k in kinds]
    got = z_hinge(h=h).exact(effects, 1.0, np.array([phi0]), np.array([w0]), 1.0)
    assert got is None


@pytest.mark.parametrize(
    ("phi0", "gp", "h"),
    [(math.pi, 9.81, 1.0), (-math.pi, 9.81, 1.0), (0.0, 9.81, 1.0), (1.0, 0.5, 0.25)],
)
def test_a_pendulum_released_at_its_top_or_bottom_still_has_its_closed_form(phi0, gp, h) -> None:
    gravity = fake("gravity", axis_g_perp=lambda a: gp)
    how, _, _ = z_hinge(h=h).exact([gravity], 1.0, np.array([phi0]), np.array([0.0]), 1.0)
    assert how.startswith("exact: pendulum released from rest")


def test_a_pendulum_released_next_to_its_top_passes_the_bottom_at_the_energy_speed() -> None:
    # φ0 = π − 2**-20: k' = cos(φ0/2) ≈ 5e-7, so 1 − k² must not be formed from k (it
    # would keep 3 digits); J = m g h = 1: ω0 = 1, quarter period K(k²), where
    # φ̇ = −2 k ω0 (energy: ½ φ̇² = 1 − cos φ0 = 2 k²)
    phi0 = math.pi - 2.0**-20
    f = pendulum_from_rest(1.0, 1.0, 1.0, 1.0, phi0)
    with mpmath.workdps(40):
        half = (mpmath.pi - mpmath.mpf(2) ** -20) / 2
        k, kp = mpmath.sin(half), mpmath.cos(half)
        quarter = float(mpmath.ellipk(1 - kp**2))
    _, qd = f(np.array([quarter]))
    np.testing.assert_allclose(qd[:, 0], [-2 * float(k)], rtol=FLOW_ATOL, atol=0)


# ---------------------------------------------------------------- the shapes


@pytest.mark.parametrize(
    ("shape", "mass", "dims", "moments"),
    [
        ("point", 3.0, {}, (0.0, 0.0, 0.0)),
        ("tank", 3.0, {"radius": 1.0}, (0.0, 0.0, 0.0)),
        ("custom", 3.0, {"inertia": [1, 2, 2]}, (1.0, 2.0, 2.0)),  # integers made floats
        ("rod", 12.0, {"length": 2.0}, (4.0, 4.0, 0.0)),  # m ℓ²/12
        ("ring", 2.0, {"radius": 3.0}, (9.0, 9.0, 18.0)),  # m R²/2, m R²
        ("disc", 4.0, {"radius": 1.0}, (1.0, 1.0, 2.0)),  # m R²/4, m R²/2
        ("cylinder", 12.0, {"radius": 1.0, "height": 2.0}, (7.0, 7.0, 6.0)),  # m(3R²+h²)/12
        ("cylindrical_shell", 12.0, {"radius": 1.0, "height": 2.0}, (10.0, 10.0, 12.0)),
        ("solid_sphere", 5.0, {"radius": 1.0}, (2.0, 2.0, 2.0)),  # 2/5 m R²
        ("hollow_sphere", 3.0, {"radius": 1.0}, (2.0, 2.0, 2.0)),  # 2/3 m R²
        ("rectangular_plate", 12.0, {"a": 1.0, "b": 2.0}, (4.0, 1.0, 5.0)),  # m b², m a², ...
        ("box", 12.0, {"a": 1.0, "b": 2.0, "c": 3.0}, (13.0, 10.0, 5.0)),  # m(b²+c²)/12, ...
    ],
)
def test_a_bodys_principal_moments_are_the_catalogues(shape, mass, dims, moments) -> None:
    got = body_inertia(body(shape, mass, **dims))
    assert got.shape == (3,)
    assert got.dtype == float
    np.testing.assert_allclose(got, moments, rtol=MOMENT_RTOL, atol=0)


def test_shape_families_are_as_documented() -> None:
    assert SPHERICAL_SHAPES == ("point", "solid_sphere", "hollow_sphere")
    assert ROUND_SHAPES == (
        "ring",
        "disc",
        "cylinder",
        "cylindrical_shell",
        "solid_sphere",
        "hollow_sphere",
    )


@pytest.mark.parametrize(
    ("shape", "dims", "radius"),
    [
        ("point", {}, 0.0),
        ("solid_sphere", {"radius": 0.25}, 0.25),
        ("hollow_sphere", {"radius": 3}, 3.0),
        ("disc", {"radius": 1.0}, None),
        ("box", {"a": 1.0, "b": 1.0, "c": 1.0}, None),
    ],
)
def test_only_a_point_or_a_sphere_has_a_radius(shape, dims, radius) -> None:
    got = body_radius(body(shape, **dims))
    assert got == radius
    if radius is not None:
        assert type(got) is float


def test_a_boxs_corners_are_its_half_edges_with_every_sign() -> None:
    got = body_vertices(body("box", a=2.0, b=4.0, c=6.0))
    expected = [
        [-1, -2, -3],
        [-1, -2, 3],
        [-1, 2, -3],
        [-1, 2, 3],
        [1, -2, -3],
        [1, -2, 3],
        [1, 2, -3],
        [1, 2, 3],
    ]
    np.testing.assert_array_equal(got, np.array(expected, float))


def test_a_plates_corners_lie_in_its_e1e2_plane() -> None:
    got = body_vertices(body("rectangular_plate", a=2.0, b=4.0))
    np.testing.assert_array_equal(got, [[-1, -2, 0], [-1, 2, 0], [1, -2, 0], [1, 2, 0]])


def test_a_rods_ends_lie_on_its_e3_axis() -> None:
    got = body_vertices(body("rod", length=3.0))
    np.testing.assert_array_equal(got, [[0.0, 0.0, -1.5], [0.0, 0.0, 1.5]])


@pytest.mark.parametrize("shape", ["point", "solid_sphere", "disc", "cylinder", "custom"])
def test_round_or_custom_bodies_have_no_corners(shape) -> None:
    assert body_vertices(body(shape, radius=1.0, height=1.0)) is None


# ---------------------------------------------------------------- the layout


def six_bodies():
    """A point, a box, a fixed ball, a pinned disc, a hinged rod and a tank."""
    bodies = [
        body("point", 2.0),
        body("box", 12.0, a=1.0, b=2.0, c=3.0),
        body("solid_sphere", 5.0, fixed=True, radius=1.0, initial={"position": [1, 2, 3]}),
        body("disc", 4.0, radius=1.0),
        body("rod", 12.0, length=2.0),
        body("tank", 1.0, radius=1.0),
    ]
    hinge = z_hinge(h=1.0, J_a=16.0)
    pins = {3: ([0.0, 0.0, 1.0], [0.0, 0.0, 0.5])}
    return Layout.of(bodies, pins=pins, guides={4: hinge}), hinge


def test_each_kind_of_body_takes_its_size_in_file_order() -> None:
    lay, hinge = six_bodies()
    assert lay.kinds == ("point", "rigid", "fixed", "pinned", "guided", "tank")
    # point 6, rigid 18, fixed 0, pinned 12, guided 2 nq = 2, tank 2
    assert lay.offsets == (0, 6, 24, 24, 36, 38)
    assert lay.size == 40
    assert lay.n == 6
    assert lay.fixed_bodies == (2,)
    assert lay.rigid_bodies == (1, 3, 4)
    assert lay.moving_bodies == (0, 1, 3, 4)
    assert lay.tanks == (5,)
    assert lay.guides == {4: hinge}
    # moments only for the bodies that turn (box and disc from the catalogue: 13, 10, 5
    # and 1, 1, 2; the rod 4, 4, 0); a fixed ball's are not needed
    np.testing.assert_allclose(
        lay.J,
        [[0, 0, 0], [13, 10, 5], [0, 0, 0], [1, 1, 2], [4, 4, 0], [0, 0, 0]],
        rtol=MOMENT_RTOL,
        atol=0,
    )
    np.testing.assert_array_equal(lay.r_fixed[2], [1.0, 2.0, 3.0])
    assert not np.delete(lay.r_fixed, 2, axis=0).any()


def test_a_pinned_body_stores_its_inertia_about_the_pin_by_parallel_axes() -> None:
    # J_C = J_G + m (|g|² 1 − g gᵀ), g = (0, 0, ½), m = 4: + 4 · ¼ = 1 across the axis
    lay, _ = six_bodies()
    (C, g, JC, JCinv) = lay.pins[3]
    np.testing.assert_array_equal(C, [0.0, 0.0, 1.0])
    np.testing.assert_array_equal(g, [0.0, 0.0, 0.5])
    np.testing.assert_allclose(JC, np.diag([2.0, 2.0, 2.0]), rtol=MOMENT_RTOL, atol=0)
    np.testing.assert_allclose(JCinv @ JC, np.eye(3), rtol=0, atol=FEW_ROUNDINGS)
    # a general offset: g = (1, 2, 2), m = 1, J_G = 1: |g|² = 9, J_C = 10·1 − g gᵀ
    lay = Layout.of(
        [body("custom", 1.0, inertia=[1.0, 1.0, 1.0])], pins={0: ([0, 0, 0], [1, 2, 2])}
    )
    expected = 10.0 * np.eye(3) - np.outer([1, 2, 2], [1, 2, 2])
    np.testing.assert_array_equal(lay.pins[0][2], expected)


def test_a_pins_point_and_arm_are_kept_as_float_arrays() -> None:
    lay = Layout.of([body("disc", 4.0, radius=1.0)], pins={0: ([1, 2, 3], [0, 0, 1])})
    C, g, _, _ = lay.pins[0]
    assert C.dtype == float
    assert g.dtype == float
    np.testing.assert_array_equal(C, [1.0, 2.0, 3.0])
    np.testing.assert_array_equal(g, [0.0, 0.0, 1.0])


def test_a_fixed_body_without_a_position_sits_at_the_origin() -> None:
    lay = Layout.of([body("point", fixed=True), body("point")])
    assert lay.kinds == ("fixed", "point")
    assert lay.offsets == (0, 0)
    assert lay.size == 6
    assert not lay.r_fixed.any()
    r, v, L, R = lay.gather(np.arange(6.0))
    np.testing.assert_array_equal(r, [[0, 0, 0], [0, 1, 2]])
    np.testing.assert_array_equal(v, [[0, 0, 0], [3, 4, 5]])
    np.testing.assert_array_equal(L, np.zeros((2, 3)))
    np.testing.assert_array_equal(R, np.tile(np.eye(3), (2, 1, 1)))


def test_gather_reads_each_bodys_quantities_where_the_layout_puts_them() -> None:
    lay, _ = six_bodies()
    y = np.arange(40.0) + 100.0
    r, v, L, R = lay.gather(y)
    assert r.shape == v.shape == L.shape == (6, 3)
    assert R.shape == (6, 3, 3)
    zero, I3 = np.zeros(3), np.eye(3)
    # the point: r, v at 0..5; no spin, identity attitude
    np.testing.assert_array_equal(r[0], [100, 101, 102])
    np.testing.assert_array_equal(v[0], [103, 104, 105])
    np.testing.assert_array_equal(L[0], zero)
    np.testing.assert_array_equal(R[0], I3)
    # the box: r, v, L_A, R_A_O row by row at 6..23
    np.testing.assert_array_equal(r[1], [106, 107, 108])
    np.testing.assert_array_equal(v[1], [109, 110, 111])
    np.testing.assert_array_equal(L[1], [112, 113, 114])
    np.testing.assert_array_equal(R[1], np.arange(115.0, 124.0).reshape(3, 3))
    # the fixed ball: at its position, at rest, identity
    np.testing.assert_array_equal(r[2], [1, 2, 3])
    np.testing.assert_array_equal(v[2], zero)
    np.testing.assert_array_equal(L[2], zero)
    np.testing.assert_array_equal(R[2], I3)
    # the pinned disc: L_C at 24..26, R at 27..35; r, v derived later (zeros here)
    np.testing.assert_array_equal(r[3], zero)
    np.testing.assert_array_equal(v[3], zero)
    np.testing.assert_array_equal(L[3], [124, 125, 126])
    np.testing.assert_array_equal(R[3], np.arange(127.0, 136.0).reshape(3, 3))
    # the hinged rod and the tank: all derived from their coordinates (constants here)
    for i in (4, 5):
        np.testing.assert_array_equal(r[i], zero)
        np.testing.assert_array_equal(v[i], zero)
        np.testing.assert_array_equal(L[i], zero)
        np.testing.assert_array_equal(R[i], I3)


def test_gather_takes_states_of_any_leading_shape() -> None:
    lay, _ = six_bodies()
    y = np.arange(2 * 3 * 40.0).reshape(2, 3, 40)
    r, v, L, R = lay.gather(y)
    assert r.shape == (2, 3, 6, 3)
    assert R.shape == (2, 3, 6, 3, 3)
    for idx in np.ndindex(2, 3):
        one = lay.gather(y[idx])
        for a, b in zip((r, v, L, R), one, strict=True):
            np.testing.assert_array_equal(a[idx], b)
    assert lay._index() is lay._index()  # built once


def test_pack_is_the_inverse_of_gather_on_the_stored_quantities() -> None:
    lay, _ = six_bodies()
    y = np.arange(2 * 40.0).reshape(2, 40) - 7.5
    back = lay.pack(*lay.gather(y))
    assert back.shape == (2, 40)
    # point, box and pinned disc: 0..35 (the guided and the tank's slots are the engine's)
    np.testing.assert_array_equal(back[..., :36], y[..., :36])


@settings(max_examples=20)
@given(
    r=arrays(float, (6, 3), elements=st.floats(-1e3, 1e3)),
    v=arrays(float, (6, 3), elements=st.floats(-1e3, 1e3)),
    L=arrays(float, (6, 3), elements=st.floats(-1e3, 1e3)),
    R=arrays(float, (6, 3, 3), elements=st.floats(-1e3, 1e3)),
)
def test_gather_is_the_inverse_of_pack_on_the_moving_bodies(r, v, L, R) -> None:
    lay, _ = six_bodies()
    r2, v2, L2, R2 = lay.gather(lay.pack(r, v, L, R))
    for i in (0, 1):  # point and box: r and v
        np.testing.assert_array_equal(r2[i], r[i])
        np.testing.assert_array_equal(v2[i], v[i])
    for i in (1, 3):  # box and pinned disc: L (L_C for the disc) and R
        np.testing.assert_array_equal(L2[i], L[i])
        np.testing.assert_array_equal(R2[i], R[i])


def test_points_alone_pack_without_spin_or_attitude() -> None:
    lay = Layout.of([body("point"), body("point")])
    y = lay.pack([[1, 2, 3], [4, 5, 6]], [[7, 8, 9], [10, 11, 12]], None, None)
    np.testing.assert_array_equal(y, np.arange(1.0, 13.0)[[0, 1, 2, 6, 7, 8, 3, 4, 5, 9, 10, 11]])


def test_omega_is_l_over_j_and_zero_about_a_zero_moment() -> None:
    lay = Layout.of([body("rod", 12.0, length=2.0)])
    L = np.array([[1.0, -2.0, 3.0], [4.0, 8.0, 0.0]])
    J = np.array([[2.0, 4.0, 0.0], [0.5, 0.25, 0.0]])
    np.testing.assert_array_equal(lay.omega(L, J), [[0.5, -0.5, 0.0], [8.0, 32.0, 0.0]])


# ---------------------------------------------------------------- the equations of motion


def test_a_points_state_moves_at_its_velocity_and_accelerates_at_f_over_m() -> None:
    lay = Layout.of([body("point", 4.0), body("point", 2.0, fixed=True)])
    y = np.array([1.0, 2.0, 3.0, -1.0, 0.5, 2.0])
    s = snapshot_of(lay, y, [4.0, 2.0], np.zeros((2, 3)))
    F = np.array([[2.0, -4.0, 8.0], [99.0, 99.0, 99.0]])
    dy = lay.derivative(s, F, np.zeros((2, 3)))
    np.testing.assert_array_equal(dy, [-1.0, 0.5, 2.0, 0.5, -1.0, 2.0])


def every_kind():
    """A tank, a hinged rod, a pinned disc, two fixed balls, a point, a free rigid
    body and a point, in that order: offsets 0, 2, 4, 16, 16, 16, 22, 40; size 46."""
    hinge = z_hinge(h=0.5, J_a=3.0)
    bodies = [
        body("tank", 1.0, radius=1.0),
        body("rod", 12.0, length=2.0),
        body("disc", 4.0, radius=1.0),
        body("solid_sphere", 1.0, fixed=True, radius=1.0, initial={"position": [1, 2, 3]}),
        body("solid_sphere", 1.0, fixed=True, radius=1.0, initial={"position": [4, 5, 6]}),
        body("point", 2.0),
        body("custom", 3.0, inertia=[1.0, 2.0, 4.0]),
        body("point", 5.0),
    ]
    lay = Layout.of(bodies, pins={2: ([0, 0, 1], [0.0, 0.0, 0.5])}, guides={1: hinge})
    return lay, hinge


def test_every_kind_of_body_in_any_order_is_gathered_from_its_own_slots() -> None:
    lay, _ = every_kind()
    assert lay.kinds == ("tank", "guided", "pinned", "fixed", "fixed", "point", "rigid", "point")
    assert lay.offsets == (0, 2, 4, 16, 16, 16, 22, 40)
    assert lay.size == 46
    y = np.arange(46.0) + 0.5
    r, v, L, R = lay.gather(y)
    np.testing.assert_array_equal(L[2], y[4:7])  # the pinned disc's L_C
    np.testing.assert_array_equal(R[2], y[7:16].reshape(3, 3))
    np.testing.assert_array_equal(r[3], [1, 2, 3])  # each fixed ball at its own place
    np.testing.assert_array_equal(r[4], [4, 5, 6])
    np.testing.assert_array_equal(r[5], y[16:19])
    np.testing.assert_array_equal(v[5], y[19:22])
    np.testing.assert_array_equal(r[6], y[22:25])
    np.testing.assert_array_equal(v[6], y[25:28])
    np.testing.assert_array_equal(L[6], y[28:31])
    np.testing.assert_array_equal(R[6], y[31:40].reshape(3, 3))
    np.testing.assert_array_equal(r[7], y[40:43])
    np.testing.assert_array_equal(v[7], y[43:46])
    for i in (0, 1, 3, 4):
        np.testing.assert_array_equal(R[i], np.eye(3))
        np.testing.assert_array_equal(L[i], np.zeros(3))
    back = lay.pack(r, v, L, R)
    np.testing.assert_array_equal(back[4:46], y[4:46])


def expected_rates(lay, hinge, s, F, M, rates) -> np.ndarray:
    """dy/dt by the book's equations, body by body (see the Conventions of state.py)."""
    out = np.zeros(46)
    out[0:2] = rates[0]  # the tank: the outflow effect's rates
    q, qd = s.coords[1]  # the hinge: q̈ = (E·F + a·M_O)/J_a, M_O = Rᵀ M_A
    E = 0.5 * np.array([-math.sin(q[0]), math.cos(q[0]), 0.0])
    M_O = s.R[1].T @ M[1]
    out[2:4] = qd[0], (E @ F[1] + M_O[2]) / s.inertia.get(1, np.array([3.0]))[0]
    # the pinned disc: L̇_C = L_C × ω + M_A + g × (R F) with L_C = J_C ω, Ṙ = −[ω]× R
    w, R2 = s.omega[2], s.R[2]
    L_C = np.diag([2.0, 2.0, 2.0]) @ w
    g = np.array([0.0, 0.0, 0.5])
    out[4:7] = np.cross(L_C, w) + M[2] + np.cross(g, R2 @ F[2])
    out[7:16] = (-skew(w) @ R2).ravel()
    for i, o in ((5, 16), (7, 40)):  # points: ṙ = v, v̇ = F/m
        out[o : o + 3], out[o + 3 : o + 6] = s.v[i], F[i] / s.m[i]
    # the free body: Euler's equations (4.47) and (2.52)
    w, R6 = s.omega[6], s.R[6]
    out[22:25], out[25:28] = s.v[6], F[6] / s.m[6]
    out[28:31] = np.cross(s.L_A[6], w) + M[6]
    out[31:40] = (-skew(w) @ R6).ravel()
    return out


def _normal(*shape):
    """O(1) values, as a standard normal's bulk: in [−2, 2]."""
    return arrays(float, shape, elements=st.floats(-2.0, 2.0))


@settings(max_examples=10)
@given(data=st.data())
def test_the_derivative_of_every_kind_of_body_is_the_books_equations(data) -> None:
    lay, hinge = every_kind()
    turns = st.lists(rotation_matrices(), min_size=8, max_size=8)
    for grown in (None, np.array([6.0])):  # twice: no slot may keep a former value
        y = data.draw(_normal(46))
        r, v, L, R = lay.gather(y)
        R = np.array(data.draw(turns))
        m = data.draw(arrays(float, 8, elements=st.floats(1.0, 2.0)))
        J = np.tile([1.0, 2.0, 4.0], (8, 1))
        w = lay.omega(L, J)
        w[2] = data.draw(_normal(3))  # the pinned disc's ω, J_C⁻¹ L_C in the engine
        s = Snapshot(0.0, r, v, L, R, w, m, J)
        s.coords = {1: (data.draw(_normal(1)), data.draw(_normal(1)))}
        s.inertia = {} if grown is None else {1: grown}
        F, M = data.draw(_normal(8, 3)), data.draw(_normal(8, 3))
        rates = {0: data.draw(_normal(2))}
        got = lay.derivative(s, F, M, rates)
        want = expected_rates(lay, hinge, s, F, M, rates)
        np.testing.assert_allclose(got, want, rtol=0, atol=FEW_ROUNDINGS * 16)


def test_a_rigid_bodys_rates_obey_eulers_equations_and_turn_its_attitude() -> None:
    # J = (1, 2, 4), L_A = (2, 3, −1): ω_A = (2, 1.5, −0.25); M_A = (0.25, 0.5, −1),
    # F = (2, 0, −6) on m = 2
    lay = Layout.of([body("custom", 2.0, inertia=[1.0, 2.0, 4.0])])
    L, w, M = np.array([2.0, 3.0, -1.0]), np.array([2.0, 1.5, -0.25]), np.array([0.25, 0.5, -1.0])
    y = lay.pack([[0.0, 0.0, 0.0]], [[1.0, 2.0, 3.0]], [L], [R_PYTH])
    s = snapshot_of(lay, y, [2.0], lay.J.copy())
    np.testing.assert_array_equal(s.omega[0], w)
    dy = lay.derivative(s, np.array([[2.0, 0.0, -6.0]]), M[None, :])
    np.testing.assert_array_equal(dy[0:3], [1.0, 2.0, 3.0])  # ṙ = v
    np.testing.assert_array_equal(dy[3:6], [1.0, 0.0, -3.0])  # v̇ = F/m
    Ld, Rd = dy[6:9], dy[9:18].reshape(3, 3)
    # (4.47): L̇_A = L_A × ω_A + M_A = (3·(−¼) − (−1)·1.5, (−1)·2 − 2·(−¼), 2·1.5 − 3·2) + M_A
    np.testing.assert_array_equal(Ld, [0.75 + 0.25, -1.5 + 0.5, -3.0 - 1.0])
    # (2.52): Ṙ = −[ω]× R
    np.testing.assert_allclose(Rd, -skew(w) @ R_PYTH, rtol=0, atol=FEW_ROUNDINGS)
    # and what they mean: the space angular momentum Rᵀ L_A changes by the moment
    # Rᵀ M_A alone, and R stays orthonormal (Ṙ Rᵀ skew)
    np.testing.assert_allclose(
        Rd.T @ L + R_PYTH.T @ Ld, R_PYTH.T @ M, rtol=0, atol=4 * FEW_ROUNDINGS
    )
    np.testing.assert_allclose(Rd @ R_PYTH.T + R_PYTH @ Rd.T, 0.0, rtol=0, atol=FEW_ROUNDINGS)


def test_a_pinned_bodys_angular_momentum_about_the_pin_changes_by_the_moment_there() -> None:
    # a disc (J_G = (1, 1, 2)) pinned with g = (0, 0, ½): J_C = (2, 2, 2) (above);
    # ω = (1, −½, 2): L_C = (2, −1, 4); F = (1, 0, −3) at G and M_A = (0.5, 0.25, 0)
    lay = Layout.of([body("disc", 4.0, radius=1.0)], pins={0: ([0, 0, 1], [0.0, 0.0, 0.5])})
    L_C, M_A, F = np.array([2.0, -1.0, 4.0]), np.array([0.5, 0.25, 0.0]), np.array([1, 0, -3.0])
    y = lay.pack(np.zeros((1, 3)), np.zeros((1, 3)), [L_C], [R_PYTH])
    s = snapshot_of(lay, y, [4.0], lay.J.copy())
    s.omega = np.array([[1.0, -0.5, 2.0]])  # J_C⁻¹ L_C, as the engine gives it
    dy = lay.derivative(s, F[None, :], M_A[None, :])
    assert dy.shape == (12,)
    Ld, Rd = dy[0:3], dy[3:12].reshape(3, 3)
    w = s.omega[0]
    np.testing.assert_allclose(Rd, -skew(w) @ R_PYTH, rtol=0, atol=FEW_ROUNDINGS)
    # space components: d/dt (Rᵀ L_C) = Rᵀ M_A + ρ × F, ρ = Rᵀ g the pin-to-G arm
    rho = R_PYTH.T @ np.array([0.0, 0.0, 0.5])
    np.testing.assert_allclose(
        Rd.T @ L_C + R_PYTH.T @ Ld,
        R_PYTH.T @ M_A + np.cross(rho, F),
        rtol=0,
        atol=4 * FEW_ROUNDINGS,
    )


def test_a_hinged_body_and_a_tank_take_their_rates_from_the_guide_and_the_effects() -> None:
    # the hinge of J_a = 16 about e3 at φ = 0, G at h = 1: E = e2; F = (0, 8, 0) and
    # a moment M_A = (0, 0, 8) about e3 (R = 1): q̈ = (8 + 8)/16 = 1; grown to 32: ½
    rod = body("rod", 12.0, length=2.0)
    hinge = z_hinge(h=1.0, J_a=16.0)
    lay = Layout.of([rod, body("tank", 1.0, radius=1.0)], guides={0: hinge})
    assert lay.offsets == (0, 2)
    assert lay.size == 4
    y = np.array([0.0, 3.0, 0.5, 0.25])
    F, M = np.array([[0.0, 8.0, 0.0], [0, 0, 0]]), np.array([[0.0, 0.0, 8.0], [0, 0, 0]])
    coords = {0: (np.array([0.0]), np.array([3.0]))}
    s = snapshot_of(lay, y, [12.0, 1.0], lay.J.copy(), coords)
    rates = {1: np.array([-0.125, 2.0])}
    np.testing.assert_array_equal(lay.derivative(s, F, M, rates), [3.0, 1.0, -0.125, 2.0])
    coords = {0: (np.array([0.0]), np.array([-5.0]))}
    s = snapshot_of(lay, y, [12.0, 1.0], lay.J.copy(), coords, {0: np.array([32.0])})
    rates = {1: np.array([0.75, -1.0])}
    np.testing.assert_array_equal(lay.derivative(s, F, M, rates), [-5.0, 0.5, 0.75, -1.0])


def test_a_hinged_bodys_moment_is_taken_to_space_components_first() -> None:
    # attitude R_PYTH: the body moment 24 e1 has space components Rᵀ 24 e1 = 24 × (first
    # row) = 8 (2, −1, 2), whose part along the axis e3 is 16: q̈ = 16/16 (G on the axis)
    hinge = z_hinge(h=0.0, J_a=16.0)
    lay = Layout.of([body("rod", 12.0, length=2.0)], guides={0: hinge})
    zeros = np.zeros((1, 3))
    s = Snapshot(0.0, zeros, zeros, zeros, R_PYTH[None], zeros, np.ones(1), zeros)
    s.coords = {0: (np.array([0.3]), np.array([-2.0]))}
    dy = lay.derivative(s, zeros, np.array([[24.0, 0.0, 0.0]]))
    np.testing.assert_allclose(dy, [-2.0, 1.0], rtol=0, atol=FEW_ROUNDINGS)
