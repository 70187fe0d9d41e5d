"""API, conventions, validation and edge cases of :mod:`mechanics.impact`.

Expected values are worked out by hand from the book's equations (written next
to each), never copied from the code under test.
"""

from __future__ import annotations

import math
import pickle
import re
from fractions import Fraction

import numpy as np
import pytest

from mechanics import impact as im
from mechanics._floats import EPS
from mechanics.errors import (
    NegativeMassError,
    NonFiniteError,
    NonPhysicalInertiaError,
    NonPositiveParameterError,
    OutOfDomainError,
    RestitutionRangeError,
    ResultOverflowError,
    SeparatingContactError,
    ShapeError,
    UnknownOptionError,
    ZeroNormalError,
    ZeroTotalMassError,
)

#: the fixed axis of the hinged bodies here
Z3 = [0.0, 0.0, 1.0]

#: Hand-computed values with a handful of roundings in the code under test.
HAND_RTOL = 8 * EPS

#: Rigid-body results go through a 3 × 3 solve with well-conditioned tensors
#: (condition number ≤ 100 here): a few hundred eps covers κ times the roundings.
RIGID_RTOL = 256 * EPS


def _sphere(m, r_G, v_G=(0, 0, 0), omega=(0, 0, 0), radius=1.0):
    """A homogeneous ball: J_G = (2/5) m R² 1."""
    return im.RigidBody(m, 0.4 * m * radius**2 * np.eye(3), np.array(r_G, float), v_G, omega)


# ------------------------------------------------------------ conventions


def test_direct_impact_hand_example_body_1_behind_body_2():
    # m1 = 1, m2 = 3, ẋ1 = 5, ẋ2 = −3, e = ½: μ = ¾, Δẋ = −8,
    # S_12 = (1 + e) μ Δẋ = −9, ẋ1f = 5 − 9 = −4, ẋ2f = −3 + 9/3 = 0.
    v1f, v2f = im.direct_impact(1.0, 3.0, 5.0, -3.0, 0.5)
    assert (float(v1f), float(v2f)) == (-4.0, 0.0)
    assert float(im.impulse_direct(1.0, 3.0, 5.0, -3.0, 0.5)) == -9.0
    # Q = ½ μ (1 − e²) Δẋ² = ½ · ¾ · ¾ · 64 = 18.
    assert float(im.energy_loss_direct(1.0, 3.0, 5.0, -3.0, 0.5)) == 18.0


def test_equal_masses_elastic_swap_velocities():
    v1f, v2f = im.direct_impact(2.0, 2.0, 3.0, -1.25, 1.0)
    assert (float(v1f), float(v2f)) == (-1.25, 3.0)
    assert float(im.energy_loss_direct(2.0, 2.0, 3.0, -1.25, 1.0)) == 0.0


def test_plastic_impact_moves_both_with_the_centre_of_mass():
    # e = 0: both end at ẋ_G = (1·4 + 3·0)/4 = 1.
    v1f, v2f = im.direct_impact(1.0, 3.0, 4.0, 0.0, 0.0)
    assert (float(v1f), float(v2f)) == (1.0, 1.0)
    # Q = ½ μ Δẋ² = ½ · ¾ · 16 = 6 = T_i − T_f = 8 − 2.
    assert float(im.energy_loss_direct(1.0, 3.0, 4.0, 0.0, 0.0)) == 6.0


def test_a_massless_body_rebounds_off_the_other_with_minus_e_relative_velocity():
    # m1 = 0: the mass fraction m2/(m1 + m2) is exactly 1, body 2 does not move.
    v1f, v2f = im.direct_impact(0.0, 5.0, 12.0, 0.0, 10 / 12)
    assert float(v2f) == 0.0
    assert math.isclose(float(v1f), -10.0, rel_tol=HAND_RTOL)
    assert float(im.energy_loss_direct(0.0, 5.0, 12.0, 0.0, 0.5)) == 0.0


def test_example_6_1_ball_on_the_floor_restitution():
    # A ball at 12 m/s bounces off the floor at 10 m/s: e = 10/12.  With the
    # floor as a body 1e30 times heavier the ball's rebound is −e times 12.
    e = 10.0 / 12.0
    floor, ball = im.direct_impact(1e30, 0.5, 0.0, -12.0, e)
    assert math.isclose(float(ball), 10.0, rel_tol=1e-12)
    assert abs(float(floor)) <= 1e-28


def test_compression_and_restitution_split_example_6_3():
    # m1 = 1, m2 = 3, ẋ = (5, −3): ẋ_G = −1; S_1 = m1 (ẋ_G − ẋ1) = −6; S_2 = e S_1.
    S1, S2 = im.compression_restitution_impulses(1.0, 3.0, 5.0, -3.0, 0.25)
    assert (float(S1), float(S2)) == (-6.0, -1.5)


def test_direct_functions_broadcast_over_leading_axes():
    m1 = np.full((4, 1), 2.0)
    v2 = -np.arange(5.0)
    v1f, v2f = im.direct_impact(m1, 3.0, 1.0, v2, 0.5)
    assert v1f.shape == v2f.shape == (4, 5)
    for name in ("impulse_direct", "energy_loss_direct"):
        assert getattr(im, name)(m1, 3.0, 1.0, v2, 0.5).shape == (4, 5)
    S1, S2 = im.compression_restitution_impulses(m1, 3.0, 1.0, v2, 0.5)
    assert S1.shape == S2.shape == (4, 5)
    v1, _ = im.direct_impact(2.0, 3.0, 1.0, -2.0, 0.5)
    assert np.ndim(v1) == 0


# ---------------------------------------------------- extreme magnitudes


def test_energy_loss_does_not_overflow_for_huge_masses():
    # m1 m2 = 1e600 overflows; μ = 5e299 does not: Q = ½ · 5e299 · 1 · 4 = 1e300.
    Q = im.energy_loss_direct(1e300, 1e300, 1.0, -1.0, 0.0)
    assert math.isclose(float(Q), 1e300, rel_tol=HAND_RTOL)


def test_energy_loss_does_not_underflow_for_tiny_masses():
    # m1 m2 = 1e-600 underflows; μ = 5e-301: Q = ½ · 5e-301 · 4 = 1e-300.
    Q = im.energy_loss_direct(1e-300, 1e-300, 1.0, -1.0, 0.0)
    assert math.isclose(float(Q), 1e-300, rel_tol=HAND_RTOL)


def test_huge_velocities_are_scaled_not_overflowed():
    # Δẋ = −2e300; Δẋ² alone would overflow, Q = ½ · ½ · 4e600 does too, but
    # the velocities after are fine: equal masses, elastic: a swap.
    v1f, v2f = im.direct_impact(1.0, 1.0, 1e300, -1e300, 1.0)
    assert (float(v1f), float(v2f)) == (-1e300, 1e300)
    with pytest.raises(ResultOverflowError, match="energy loss"):
        im.energy_loss_direct(1.0, 1.0, 1e300, -1e300, 0.0)


def test_velocities_beyond_float64_raise_overflow():
    # ẋ1f = ẋ1 + 2 Δẋ ≈ 1.5e308 − 6e308 for a very light body 1.
    with pytest.raises(ResultOverflowError, match="v_1f"):
        im.direct_impact(1e-10, 1.0, 1.5e308, -1.5e308, 1.0)


def test_one_minus_e_is_exact_near_one():
    # e = 1 − 2^-40: 1 − e² = 2^-40 (2 − 2^-40) exactly representable; Q for
    # μ = ½, Δẋ = −2: ½ · ½ · 4 · 2^-40 (2 − 2^-40).
    e = 1.0 - 2.0**-40
    expected = 2.0**-40 * (2.0 - 2.0**-40)
    assert float(im.energy_loss_direct(1.0, 1.0, 1.0, -1.0, e)) == expected


# ------------------------------------------------------- direct validation


@pytest.mark.parametrize("e", [-0.1, 1.0 + 2 * EPS, 7.0])
def test_restitution_outside_zero_one_raises_naming_it(e):
    with pytest.raises(RestitutionRangeError, match=repr(e)):
        im.direct_impact(1.0, 1.0, 1.0, -1.0, e)


def test_negative_mass_raises_naming_it():
    with pytest.raises(NegativeMassError, match=r"m_2 must be >= 0; found -2\.0"):
        im.direct_impact(1.0, -2.0, 1.0, -1.0, 0.5)


@pytest.mark.parametrize("bad", [math.nan, math.inf])
def test_non_finite_input_raises(bad):
    with pytest.raises(NonFiniteError, match="v_1"):
        im.direct_impact(1.0, 1.0, bad, -1.0, 0.5)
    with pytest.raises(NonFiniteError, match="m_1"):
        im.energy_loss_direct(bad, 1.0, 1.0, -1.0, 0.5)


def test_two_massless_bodies_raise():
    with pytest.raises(ZeroTotalMassError, match="both masses are 0"):
        im.impulse_direct(0.0, 0.0, 1.0, -1.0, 0.5)


def test_separating_bodies_raise_by_default_naming_the_velocity():
    with pytest.raises(SeparatingContactError, match=re.escape("v_n = 2.0 > 0")):
        im.direct_impact(1.0, 1.0, -1.0, 1.0, 0.5)
    with pytest.raises(SeparatingContactError, match=r"index \(1,\)"):
        im.energy_loss_direct(1.0, 1.0, [2.0, -1.0], [1.0, 1.0], 0.5)


def test_separating_ignore_is_a_no_op_for_those_contacts_only():
    v1 = np.array([2.0, -1.0])
    v2 = np.array([1.0, 1.0])  # the first approaches, the second separates
    v1f, v2f = im.direct_impact(1.0, 1.0, v1, v2, 1.0, separating="ignore")
    assert v1f.tolist() == [1.0, -1.0]
    assert v2f.tolist() == [2.0, 1.0]
    assert im.impulse_direct(1.0, 1.0, v1, v2, 1.0, separating="ignore").tolist() == [-1.0, 0.0]
    Q = im.energy_loss_direct(1.0, 1.0, v1, v2, 0.0, separating="ignore")
    assert Q.tolist() == [0.25, 0.0]
    S1, S2 = im.compression_restitution_impulses(1.0, 1.0, v1, v2, 0.5, separating="ignore")
    assert S1.tolist() == [-0.5, 0.0]
    assert S2.tolist() == [-0.25, 0.0]


def test_grazing_contact_gives_zero_impulse_without_error():
    v1f, v2f = im.direct_impact(1.0, 2.0, 3.0, 3.0, 0.5)
    assert (float(v1f), float(v2f)) == (3.0, 3.0)
    assert float(im.energy_loss_direct(1.0, 2.0, 3.0, 3.0, 0.5)) == 0.0


def test_unknown_separating_option_raises():
    with pytest.raises(UnknownOptionError, match="'skip'"):
        im.direct_impact(1.0, 1.0, 1.0, -1.0, 0.5, separating="skip")


def test_complex_input_raises_shape_error():
    with pytest.raises(ShapeError, match="complex"):
        im.direct_impact(1.0, 1.0, 1.0 + 0j, -1.0, 0.5)


# ------------------------------------------------------------ rigid bodies


def test_central_impact_of_two_spheres_is_the_direct_impact():
    # Centres on the normal: no rotation, and the X-axis result (6.36)–(6.38).
    # Body 1 behind (−X side), n = −e_x points into body 1.
    b1 = _sphere(2.0, [-1.0, 0, 0], v_G=[3.0, 0, 0])
    b2 = _sphere(5.0, [1.0, 0, 0], v_G=[-1.0, 0, 0])
    out = im.rigid_impact(b1, b2, r_S=[0.0, 0, 0], n=[-1.0, 0, 0], e=0.6)
    v1f, v2f = im.direct_impact(2.0, 5.0, 3.0, -1.0, 0.6)
    np.testing.assert_allclose(out.body_1.v_G, [v1f, 0, 0], rtol=0, atol=RIGID_RTOL * 3)
    np.testing.assert_allclose(out.body_2.v_G, [v2f, 0, 0], rtol=0, atol=RIGID_RTOL * 3)
    assert np.abs(out.body_1.omega).max() == 0.0 == np.abs(out.body_2.omega).max()
    # S = |S_12| and the loss agree with the direct functions; μ is the reduced mass.
    assert math.isclose(out.S, -float(im.impulse_direct(2.0, 5.0, 3.0, -1.0, 0.6)), rel_tol=1e-14)
    assert math.isclose(out.mu, 10 / 7, rel_tol=1e-15)
    assert math.isclose(
        out.Q, float(im.energy_loss_direct(2.0, 5.0, 3.0, -1.0, 0.6)), rel_tol=1e-14
    )


@pytest.mark.parametrize("x_over_ell", [0.0, 0.2, 1 / 3, 0.5, 0.8, 1.0])
def test_example_6_2_bat_velocities_energy_and_point_at_rest(x_over_ell):
    # A free rod of mass m, length ℓ along X (ends at 0 and ℓ, G at ℓ/2), at
    # rest, struck perpendicular at x.  Whatever S the contact delivers:
    # v_G = S/m e_y (6.23), φ̇ = 12 S (x − ℓ/2)/(m ℓ²) (6.24),
    # T = S²/(2m) [1 + 12 (x/ℓ − ½)²] (6.26), x_C = (ℓ/3)(3x − 2ℓ)/(2x − ℓ) (6.28).
    m, ell = 3.0, 2.0
    x = x_over_ell * ell
    J_G = np.diag([1e-3 * m * ell**2, m * ell**2 / 12, m * ell**2 / 12])
    rod = im.RigidBody(m, J_G, np.array([ell / 2, 0, 0]), np.zeros(3), np.zeros(3))
    ball = _sphere(0.2, [x, -0.1, 0], v_G=[0, 4.0, 0], radius=0.1)
    out = im.rigid_impact(rod, ball, r_S=[x, 0, 0], n=[0, 1, 0], e=0.7)
    S = out.S
    after = out.body_1
    np.testing.assert_allclose(after.v_G, [0, S / m, 0], atol=RIGID_RTOL * S / m)
    phidot = 12 * S * (x - ell / 2) / (m * ell**2)
    np.testing.assert_allclose(after.omega, [0, 0, phidot], atol=RIGID_RTOL * 6 * S / (m * ell))
    T = 0.5 * m * after.v_G @ after.v_G + 0.5 * after.omega @ J_G @ after.omega
    T_book = S**2 / (2 * m) * (1 + 12 * (x / ell - 0.5) ** 2)
    assert math.isclose(T, T_book, rel_tol=RIGID_RTOL)
    if x_over_ell != 0.5:  # (6.31): x_C = ±∞ at the middle
        x_C = ell / 2 - after.v_G[1] / after.omega[2]
        x_C_book = ell / 3 * (3 * x - 2 * ell) / (2 * x - ell)
        assert math.isclose(x_C, x_C_book, rel_tol=RIGID_RTOL)


def test_planar_input_gives_planar_output():
    J = np.array([[2.0, 0.3, 0], [0.3, 1.0, 0], [0, 0, 2.5]])
    b1 = im.RigidBody(1.0, J, [0.0, 0, 0], [0.5, -1.0, 0], [0, 0, 0.3])
    b2 = im.RigidBody(2.0, 1.3 * J, [0.0, -2, 0], [0.0, 1.0, 0], [0, 0, -0.2])
    out = im.rigid_impact(b1, b2, r_S=[0.4, -1.0, 0], n=[0.1, 1.0, 0], e=0.5)
    for b in (out.body_1, out.body_2):
        assert b.v_G[2] == 0.0
        assert b.omega[0] == 0.0
        assert b.omega[1] == 0.0


def test_impact_against_a_fixed_body_reverses_the_normal_velocity():
    # A ball falling onto the floor with spin: the floor (body 2) is fixed.
    ball = _sphere(1.0, [0, 0, 1.0], v_G=[1.0, 0, -3.0], omega=[0, 2.0, 0])
    out = im.rigid_impact(ball, None, r_S=[0, 0, 0], n=[0, 0, 2.0], e=0.5)
    assert out.body_2 is None
    # Contact at the bottom: arm r = −e_z is parallel to n, so μ = m and S = 1.5 · 3.
    assert math.isclose(out.S, 4.5, rel_tol=HAND_RTOL)
    np.testing.assert_allclose(out.body_1.v_G, [1.0, 0, 1.5], atol=4 * EPS)
    np.testing.assert_array_equal(out.body_1.omega, [0, 2.0, 0])  # smooth: no friction


def test_rigid_impact_broadcasts_over_contacts():
    n = np.array([[0, 0, 1.0], [0, 0.6, 0.8], [1.0, 0, 0]])
    ball = _sphere(1.0, [0, 0, 1.0], v_G=[0.0, 0, -3.0])
    wall_v = np.array([[0, 0, 0], [0, 0, 0], [5.0, 0, 0]])
    wall = im.RigidBody(1e3, 1e3 * np.eye(3), [0, 0, -1.0], wall_v, np.zeros(3))
    out = im.rigid_impact(ball, wall, r_S=[0, 0, 0.0], n=n, e=[0.5, 0.5, 1.0])
    assert out.S.shape == (3,)
    assert out.body_1.v_G.shape == (3, 3)
    assert out.body_2.omega.shape == (3, 3)


def test_rigid_separating_contact_raises_or_is_ignored():
    ball = _sphere(1.0, [0, 0, 1.0], v_G=[0.0, 0, 3.0])
    with pytest.raises(SeparatingContactError, match=re.escape("v_n = 3.0")):
        im.rigid_impact(ball, None, r_S=[0, 0, 0], n=[0, 0, 1], e=0.5)
    out = im.rigid_impact(ball, None, r_S=[0, 0, 0], n=[0, 0, 1], e=0.5, separating="ignore")
    assert out.S == 0.0
    assert out.Q == 0.0
    np.testing.assert_array_equal(out.body_1.v_G, ball.v_G)


@pytest.mark.parametrize(
    ("J", "match"),
    [
        pytest.param(np.diag([1.0, 1.0, 3.0]), "triangle inequality", id="triangle"),
        pytest.param(np.diag([1.0, -1.0, 1.0]), "not positive semidefinite", id="indefinite"),
        pytest.param(np.diag([1.0, 1.0, 0.0]), "not positive definite", id="rod-axis"),
        pytest.param(np.array([[1, 0.5, 0], [0, 1, 0], [0, 0, 1.0]]), "not symmetric", id="asym"),
    ],
)
def test_non_physical_inertia_tensor_raises_naming_the_condition(J, match):
    with pytest.raises(NonPhysicalInertiaError, match=rf"^J_G .*{match}"):
        im.RigidBody(1.0, J, np.zeros(3), np.zeros(3), np.zeros(3))
    body = (1.0, J, np.zeros(3), np.zeros(3), np.zeros(3))  # a 5-tuple: validated by the call
    with pytest.raises(NonPhysicalInertiaError, match=rf"^body_1\.J_G .*{match}"):
        im.rigid_impact(body, None, r_S=[0, 0, -1.0], n=[0, 0, 1], e=0.5)
    with pytest.raises(NonPhysicalInertiaError, match="J_1"):
        im.effective_mass(1.0, J, [0, 0, 1.0], [1, 0, 0])


def test_a_lamina_tensor_on_the_triangle_edge_is_accepted():
    R = np.array([[0.6, 0.8, 0], [-0.8, 0.6, 0], [0, 0, 1.0]]) @ np.array(
        [[1, 0, 0], [0, 0.28, 0.96], [0, -0.96, 0.28]]
    )
    J = R.T @ np.diag([1.0, 2.0, 3.0]) @ R
    assert im.effective_mass(1.0, 0.5 * (J + J.T), [0, 0, 1.0], [1, 0, 0]) > 0


def test_zero_normal_and_zero_mass_raise():
    ball = _sphere(1.0, [0, 0, 1.0], v_G=[0.0, 0, -3.0])
    with pytest.raises(ZeroNormalError, match=r"n must be a non-zero vector; found \[0.0, 0.0"):
        im.rigid_impact(ball, None, r_S=[0, 0, 0], n=[0, 0, 0], e=0.5)
    with pytest.raises(NonPositiveParameterError, match=r"^m must be > 0 for a rigid body"):
        ball._replace(m=0.0)  # a RigidBody is validated when built
    massless = (0.0, *ball[1:])  # a 5-tuple is validated by the call
    with pytest.raises(NonPositiveParameterError, match=re.escape("body_1.m must be > 0")):
        im.rigid_impact(massless, None, r_S=[0, 0, 0], n=[0, 0, 1], e=0.5)
    with pytest.raises(NegativeMassError, match=re.escape("body_2.m")):
        im.rigid_impact(ball, (-1.0, *ball[1:]), r_S=[0, 0, 0], n=[0, 0, 1], e=0.5)
    with pytest.raises(RestitutionRangeError):
        im.rigid_impact(ball, None, r_S=[0, 0, 0], n=[0, 0, 1], e=1.5)


def test_a_body_that_is_not_a_rigid_body_record_raises():
    with pytest.raises(OutOfDomainError, match="RigidBody"):
        im.rigid_impact((1.0, np.eye(3)), None, r_S=[0, 0, 0], n=[0, 0, 1], e=0.5)


def test_effective_mass_needs_all_of_body_2_or_none():
    with pytest.raises(
        OutOfDomainError, match=r"^body 2 needs all of m_2, J_2 and r_2, or none of them$"
    ):
        im.effective_mass(1.0, np.eye(3), [0, 0, 0], [1, 0, 0], m_2=2.0)


def test_effective_mass_of_an_eccentric_contact_on_a_sphere():
    # Solid ball m, radius R, hit tangentially at the equator: u = r × n has
    # |u| = R, 1/μ = 1/m + R²/(⅖ m R²) = 7/(2m).
    m, R = 2.0, 0.5
    mu = im.effective_mass(m, 0.4 * m * R**2 * np.eye(3), [R, 0, 0], [0, 1, 0])
    assert math.isclose(float(mu), 2 * m / 7, rel_tol=HAND_RTOL)


# ------------------------------------------------------------ hinged bodies


def _rod_on_axis(m=3.0, ell=2.0):
    """A rod along X hinged at the origin about e_z: J_A = m ℓ²/3 about e_z."""
    J_A = np.diag([1e-3 * m * ell**2, m * ell**2 / 3, m * ell**2 / 3])
    return m, J_A, np.array([ell / 2, 0, 0])


def test_hinged_rod_struck_at_x_turns_with_x_S_over_J():
    # Δω = x S/J_A; the axis reacts with m Δω ℓ/2 − S along e_y (momentum).
    m, J_A, r_G = _rod_on_axis()
    out = im.hinged_impact(
        m, J_A, r_G, axis_point=[0, 0, 0], axis=[0, 0, 1], omega=1.0, r_P=[0.5, 0, 0], S_P=[0, 2, 0]
    )
    dw = 0.5 * 2 / 4.0
    assert math.isclose(float(out.omega), 1.0 + dw, rel_tol=HAND_RTOL)
    np.testing.assert_allclose(out.S_axis, [0, m * dw * 1.0 - 2.0, 0], atol=4 * EPS)
    np.testing.assert_allclose(out.M_axis, 0.0, atol=4 * EPS)
    assert out.S_bearings is None


def test_hinged_rod_centre_of_percussion_at_two_thirds():
    m, J_A, r_G = _rod_on_axis(ell=3.0)
    P, b = im.centre_of_percussion(m, J_A, r_G, axis_point=[0, 0, 0], axis=[0, 0, 1])
    np.testing.assert_allclose(P, [2.0, 0, 0], atol=4 * EPS)
    np.testing.assert_array_equal(b, [0, 1.0, 0])


def test_centre_of_percussion_of_a_mass_on_the_axis_raises():
    with pytest.raises(OutOfDomainError, match="lies on the axis"):
        im.centre_of_percussion(1.0, np.eye(3), [0, 0, 2.0], axis_point=[0, 0, 0], axis=[0, 0, 1])


def test_door_bearings_share_the_reaction_problem_6_5_setting():
    # A door leaf in the XZ plane: width along X (0..b), height along the axis
    # e_z (0..h), hinges 0.25 from the edges, mass m.  Struck at the lower edge
    # at distance y from the axis so that it stops: S_C = J_a ω/y along −e_y.
    m, b, h = 10.0, 0.8, 2.0
    J_G = m / 12 * np.diag([h**2, b**2 + h**2, b**2])
    d = np.array([b / 2, 0, h / 2])
    J_A = J_G + m * (d @ d * np.eye(3) - np.outer(d, d))
    J_aa = J_A[2, 2]  # m b²/3
    assert math.isclose(J_aa, m * b**2 / 3, rel_tol=HAND_RTOL)
    omega, y = 2.0, 0.6
    S_C = J_aa * omega / y  # along −e_y at (y, 0, 0)
    out = im.hinged_impact(
        m,
        J_A,
        d,
        axis_point=[0, 0, 0],
        axis=[0, 0, 1],
        omega=omega,
        r_P=[y, 0, 0],
        S_P=[0, -S_C, 0],
        bearings=(0.25, h - 0.25),
    )
    assert abs(float(out.omega)) <= 16 * EPS * omega
    S_A, S_B = out.S_bearings
    # Bearings carry all of the reaction: the sums by (6.19) and (6.21).
    np.testing.assert_allclose(S_A + S_B, out.S_axis, atol=16 * EPS * S_C)
    moment = np.cross([0, 0, 0.25], S_A) + np.cross([0, 0, h - 0.25], S_B)
    np.testing.assert_allclose(moment, out.M_axis, atol=16 * EPS * S_C * h)
    # Hand value: m Δv_G = −m ω b/2 e_y = −S_C e_y + S_axis.
    total = -m * omega * b / 2 + S_C
    assert math.isclose(float(out.S_axis[1]), total, rel_tol=1e-13)


def test_bearings_at_the_same_place_raise():
    m, J_A, r_G = _rod_on_axis()
    with pytest.raises(OutOfDomainError, match="different axial positions"):
        im.hinged_impact(
            m,
            J_A,
            r_G,
            axis_point=[0, 0, 0],
            axis=[0, 0, 1],
            omega=0.0,
            r_P=[1, 0, 0],
            S_P=[0, 1, 0],
            bearings=(1.0, 1.0),
        )


def test_hinged_zero_axis_raises():
    m, J_A, r_G = _rod_on_axis()
    with pytest.raises(ZeroNormalError, match="axis"):
        im.hinged_impact(
            m,
            J_A,
            r_G,
            axis_point=[0, 0, 0],
            axis=[0, 0, 0],
            omega=0.0,
            r_P=[1, 0, 0],
            S_P=[0, 1, 0],
        )


@pytest.mark.parametrize(
    ("r_P", "n"),
    [
        pytest.param([1.0, 0, 0], [1.0, 0, 0], id="n-in-the-plane-of-axis-and-P"),
        pytest.param([0.0, 0, 0], [0, 1.0, 0], id="P-at-A"),
        pytest.param([0.0, 0, 2.5], [0, 1.0, 0], id="P-on-the-axis"),
        pytest.param([1e-300 * 0.0, 0, 0], [0, 1.0, 0], id="P-at-A-times-1e-300"),
    ],
)
def test_hinged_effective_mass_refuses_a_blow_without_lever_arm_naming_r_P(r_P, n):
    _, J_A, _ = _rod_on_axis()
    with pytest.raises(OutOfDomainError, match=r"^r_P gives the blow no lever arm about the axis"):
        im.hinged_effective_mass(J_A, r_P, n, axis_point=[0, 0, 0], axis=[0, 0, 1])


def test_hinged_effective_mass_beyond_float64_is_a_result_overflow_error():
    # a lever arm of 5e-301: mu = J_a/arm**2 ~ 1e601
    _, J_A, _ = _rod_on_axis()
    with pytest.raises(ResultOverflowError, match=r"^hinged_effective_mass: the result is not"):
        im.hinged_effective_mass(J_A, [5e-301, 0, 0], [0, 1.0, 0], axis_point=[0] * 3, axis=Z3)


def test_hinged_effective_mass_is_right_where_the_squared_arm_overflows():
    # arm = 5e199, arm**2 = 2.5e399 overflows, mu = 4e300/2.5e399 = 1.6e-99 does not
    J_A = 1e300 * np.diag([1.0, 4.0, 4.0])
    mu = im.hinged_effective_mass(J_A, [5e199, 0, 0], [0, 1.0, 0], axis_point=[0] * 3, axis=Z3)
    exact = Fraction(float(J_A[2, 2])) / Fraction(5e199) ** 2
    assert abs(Fraction(float(mu)) - exact) <= 2 * (EPS / 2) * exact  # two roundings


# ------------------------------------- promises checked where they are not trivial


def _tilted_hinge():
    """A general body on a tilted axis: J_A, G, A and a with no zero components."""
    R = np.array([[0.36, 0.48, -0.8], [-0.8, 0.6, 0.0], [0.48, 0.64, 0.6]])  # a rotation
    J_A = R.T @ np.diag([2.0, 3.0, 4.5]) @ R
    return (
        2.5,
        J_A,
        np.array([0.7, -0.2, 0.4]),
        np.array([0.1, 0.3, -0.2]),
        np.array([1.0, 2.0, 2.0]),
    )


def test_bearings_carry_an_axial_blow_on_the_first_bearing():
    # A blow with a component along the axis: the axial part of S_axis (statically
    # indeterminate) goes to bearing 1, and the two bearings still sum to S_axis and
    # give M_axis about A.
    m, J_A, r_G, A, axis = _tilted_hinge()
    a = axis / 3.0
    S_P = np.array([0.5, -1.0, 2.0])
    s1, s2 = -0.4, 1.3
    out = im.hinged_impact(
        m,
        J_A,
        r_G,
        axis_point=A,
        axis=axis,
        omega=0.7,
        r_P=[1.0, 0.5, -0.3],
        S_P=S_P,
        bearings=(s1, s2),
    )
    B1, B2 = out.S_bearings
    assert abs(out.S_axis @ a) > 0.1  # the reaction has an axial part
    np.testing.assert_allclose(B1 + B2, out.S_axis, atol=RIGID_RTOL * 4)
    np.testing.assert_allclose(B1 @ a, out.S_axis @ a, atol=RIGID_RTOL * 4)
    np.testing.assert_allclose(B2 @ a, 0.0, atol=RIGID_RTOL * 4)
    moment = np.cross(s1 * a, B1) + np.cross(s2 * a, B2)
    np.testing.assert_allclose(moment, out.M_axis, atol=RIGID_RTOL * 4)


def test_hinge_functions_broadcast_over_leading_axes():
    # Batched inputs give, row by row, what the unbatched calls give.
    _, J_A, r_G, A, axis = _tilted_hinge()
    rP = np.array([[1.0, 0.5, -0.3], [0.2, -1.0, 0.8], [-0.6, 0.4, 1.1]])
    SP = np.array([[0.5, -1.0, 2.0], [1.0, 0.0, 0.0], [0.0, 0.3, -0.4]])
    omegas = np.array([0.7, -1.0, 0.0])
    masses = np.array([2.5, 1.0, 4.0])
    bear = (np.array([-0.4, 0.0, 1.0]), np.array([1.3, 2.0, -1.0]))
    batched = im.hinged_impact(
        masses, J_A, r_G, axis_point=A, axis=axis, omega=omegas, r_P=rP, S_P=SP, bearings=bear
    )
    mus = im.hinged_effective_mass(J_A, rP, SP, axis_point=A, axis=axis)
    for i in range(3):
        one = im.hinged_impact(
            masses[i],
            J_A,
            r_G,
            axis_point=A,
            axis=axis,
            omega=omegas[i],
            r_P=rP[i],
            S_P=SP[i],
            bearings=(bear[0][i], bear[1][i]),
        )
        np.testing.assert_allclose(batched.omega[i], one.omega, rtol=HAND_RTOL, atol=0)
        np.testing.assert_allclose(batched.S_axis[i], one.S_axis, rtol=0, atol=HAND_RTOL * 4)
        np.testing.assert_allclose(batched.M_axis[i], one.M_axis, rtol=0, atol=HAND_RTOL * 4)
        np.testing.assert_allclose(
            batched.S_bearings[i], one.S_bearings, rtol=0, atol=HAND_RTOL * 16
        )
        mu = im.hinged_effective_mass(J_A, rP[i], SP[i], axis_point=A, axis=axis)
        np.testing.assert_allclose(mus[i], mu, rtol=HAND_RTOL, atol=0)
    assert batched.S_bearings.shape == (3, 2, 3)
    points = np.array([[0.0, 0, 0], [0.1, 0.3, -0.2], [1.0, -1.0, 0.5]])
    P, b = im.centre_of_percussion(masses, J_A, r_G, axis_point=points, axis=axis)
    assert P.shape == b.shape == (3, 3)
    for i in range(3):
        P1, b1 = im.centre_of_percussion(masses[i], J_A, r_G, axis_point=points[i], axis=axis)
        np.testing.assert_allclose(P[i], P1, rtol=0, atol=HAND_RTOL * 8)
        np.testing.assert_allclose(b[i], b1, rtol=0, atol=HAND_RTOL)


_HINGE_KW = dict(axis_point=[0, 0, 0], axis=[0, 0, 1])


@pytest.mark.parametrize(
    ("call", "error", "match"),
    [
        pytest.param(
            lambda: im.effective_mass(0.0, np.eye(3), [0, 0, 1.0], [1.0, 0, 0]),
            NonPositiveParameterError,
            r"^m_1 must be > 0 for a rigid body; found 0\.0",
            id="effective-m1",
        ),
        pytest.param(
            lambda: im.effective_mass(
                1.0, np.eye(3), [0, 0, 1.0], [1.0, 0, 0], 0.0, np.eye(3), [0, 0, 1.0]
            ),
            NonPositiveParameterError,
            r"^m_2 must be > 0 for a rigid body; found 0\.0",
            id="effective-m2",
        ),
        pytest.param(
            lambda: im.hinged_impact(
                0.0, np.eye(3), [1.0, 0, 0], **_HINGE_KW, omega=0.0, r_P=[1, 0, 0], S_P=[0, 1, 0]
            ),
            NonPositiveParameterError,
            r"^m must be > 0 for a rigid body; found 0\.0 at index \(\)",
            id="hinged-m",
        ),
        pytest.param(
            lambda: im.hinged_impact(
                [1.0, -2.0],
                np.eye(3),
                [1.0, 0, 0],
                **_HINGE_KW,
                omega=0.0,
                r_P=[1, 0, 0],
                S_P=[0, 1, 0],
            ),
            NegativeMassError,
            r"^m must be >= 0; found -2\.0 at index \(1,\)",
            id="hinged-negative-m",
        ),
        pytest.param(
            lambda: im.centre_of_percussion(0.0, np.eye(3), [1.0, 0, 0], **_HINGE_KW),
            NonPositiveParameterError,
            r"^m must be > 0 for a rigid body; found 0\.0",
            id="percussion-m",
        ),
        pytest.param(
            lambda: im.hinged_impact(
                1.0, np.eye(3), [1.0, 0], **_HINGE_KW, omega=0.0, r_P=[1, 0, 0], S_P=[0, 1, 0]
            ),
            ShapeError,
            r"^r_G has shape \(2,\); expected \(\.\.\., 3\)",
            id="hinged-r_G-shape",
        ),
        pytest.param(
            lambda: im.hinged_impact(
                1.0,
                np.eye(3),
                [1.0, 0, 0],
                axis_point=[0, 0],
                axis=[0, 0, 1],
                omega=0.0,
                r_P=[1, 0, 0],
                S_P=[0, 1, 0],
            ),
            ShapeError,
            r"^axis_point has shape \(2,\)",
            id="hinged-axis-point-shape",
        ),
        pytest.param(
            lambda: im.hinged_impact(
                1.0, np.eye(3), [1.0, 0, 0], **_HINGE_KW, omega=0.0, r_P=[1, 0], S_P=[0, 1, 0]
            ),
            ShapeError,
            r"^r_P has shape \(2,\)",
            id="hinged-r_P-shape",
        ),
        pytest.param(
            lambda: im.hinged_impact(
                1.0, np.eye(3), [1.0, 0, 0], **_HINGE_KW, omega=0.0, r_P=[1, 0, 0], S_P=[0, 1]
            ),
            ShapeError,
            r"^S_P has shape \(2,\)",
            id="hinged-S_P-shape",
        ),
        pytest.param(
            lambda: im.hinged_impact(
                1.0, np.eye(3), [1.0, 0, 0], **_HINGE_KW, omega=np.nan, r_P=[1, 0, 0], S_P=[0, 1, 0]
            ),
            NonFiniteError,
            r"^omega must be finite",
            id="hinged-omega-nan",
        ),
        pytest.param(
            lambda: im.hinged_impact(
                1.0,
                np.eye(3),
                [1.0, 0, 0],
                **_HINGE_KW,
                omega=0.0,
                r_P=[1, 0, 0],
                S_P=[0, 1, 0],
                bearings=(0.0, np.inf),
            ),
            NonFiniteError,
            r"^bearings\[1\] must be finite",
            id="hinged-bearing-inf",
        ),
        pytest.param(
            lambda: im.hinged_impact(
                1.0,
                np.eye(3),
                [1.0, 0, 0],
                **_HINGE_KW,
                omega=0.0,
                r_P=[1, 0, 0],
                S_P=[0, 1, 0],
                bearings=(np.nan, 1.0),
            ),
            NonFiniteError,
            r"^bearings\[0\] must be finite",
            id="hinged-bearing-nan",
        ),
        pytest.param(
            lambda: im.hinged_impact(
                1.0,
                np.eye(3),
                [1.0, 0, 0],
                **_HINGE_KW,
                omega=0.0,
                r_P=[1, 0, 0],
                S_P=[0, 1, 0],
                bearings=(1.0,),
            ),
            OutOfDomainError,
            r"^bearings must be two axial positions; got \(1\.0,\)",
            id="hinged-one-bearing",
        ),
        pytest.param(
            lambda: im.hinged_effective_mass(np.eye(3), [1.0, 0], [0, 1.0, 0], **_HINGE_KW),
            ShapeError,
            r"^r_P has shape \(2,\)",
            id="hinged-mu-r_P-shape",
        ),
        pytest.param(
            lambda: im.hinged_effective_mass(np.eye(3), [1.0, 0, 0], [0, 0, 0], **_HINGE_KW),
            ZeroNormalError,
            r"^n must be a non-zero vector; found \[0\.0, 0\.0, 0\.0\]",
            id="hinged-mu-zero-n",
        ),
        pytest.param(
            lambda: im.hinged_effective_mass(
                np.diag([1.0, 1.0, -1.0]), [1.0, 0, 0], [0, 1.0, 0], **_HINGE_KW
            ),
            NonPhysicalInertiaError,
            r"J_A",
            id="hinged-mu-bad-J",
        ),
        pytest.param(
            lambda: im.centre_of_percussion(1.0, np.eye(3), [0.0, 0, 2.0], **_HINGE_KW),
            OutOfDomainError,
            r"^the centre of mass lies on the axis \(distance h = 0\.0 at index \(\)\)",
            id="percussion-on-axis",
        ),
    ],
)
def test_each_function_validates_its_own_inputs_naming_value_and_condition(call, error, match):
    with pytest.raises(error, match=match):
        call()


def _ball(**kw):
    fields = dict(m=1.0, J_G=0.4 * np.eye(3), r_G=[0, 0, 1.0], v_G=[0, 0, -1.0], omega=[0, 0, 0.0])
    fields.update(kw)
    return im.RigidBody(**fields)


def _ball_tuple(**kw):
    """The fields of :func:`_ball` as a plain 5-tuple: validated by the function it is given
    to, whose errors name ``body_1.field``."""
    fields = dict(m=1.0, J_G=0.4 * np.eye(3), r_G=[0, 0, 1.0], v_G=[0, 0, -1.0], omega=[0, 0, 0.0])
    fields.update(kw)
    return tuple(fields[k] for k in ("m", "J_G", "r_G", "v_G", "omega"))


_RIGID_KW = dict(r_S=[0, 0, 0.0], n=[0, 0, 1.0])


@pytest.mark.parametrize(
    ("call", "error", "match"),
    [
        pytest.param(
            lambda: im.direct_impact(1.0, 1.0, 1.0, np.nan, 0.5),
            NonFiniteError,
            r"^v_2 must be finite; found .*nan.* at index \(\)",
            id="direct-v2-nan",
        ),
        pytest.param(
            lambda: im.direct_impact(1.0, 1.0, 1.0, 0.0, np.inf),
            NonFiniteError,
            r"^e must be finite; found .*inf.* at index \(\)",
            id="direct-e-inf",
        ),
        pytest.param(
            lambda: im.impulse_direct(1e308, 1e308, 1e308, -1e308, 1.0),
            ResultOverflowError,
            r"^the impulse S_12 overflows float64 at index \(\) \(finite input\)$",
            id="impulse-overflow",
        ),
        pytest.param(
            lambda: im.impulse_direct(
                [1.0, 1e308], [1.0, 1e308], [1.0, 1e308], [-1.0, -1e308], 1.0
            ),
            ResultOverflowError,
            r"^the impulse S_12 overflows float64 at index \(1,\)",
            id="impulse-overflow-batched",
        ),
        pytest.param(
            lambda: im.energy_loss_direct(1e300, 1e300, 1e300, -1e300, 0.0),
            ResultOverflowError,
            r"^the energy loss Q overflows float64 at index \(\)",
            id="energy-overflow",
        ),
        pytest.param(
            lambda: im.compression_restitution_impulses(1e308, 1e308, 1e308, -1e308, 1.0),
            ResultOverflowError,
            r"^S_1 overflows float64 at index \(\)",
            id="compression-overflow",
        ),
        pytest.param(
            lambda: im.effective_mass(1.0, np.eye(3), [0, 0, 1.0], [[1.0, 0, 0], [0, 0, 0]]),
            ZeroNormalError,
            r"^n must be a non-zero vector; found \[0\.0, 0\.0, 0\.0\]",
            id="effective-zero-n-batched",
        ),
        pytest.param(
            lambda: im.effective_mass(1.0, np.eye(3), [0, 0, 1.0], [1.0, 0]),
            ShapeError,
            r"^n has shape \(2,\); expected \(\.\.\., 3\)",
            id="effective-n-shape",
        ),
        pytest.param(
            lambda: im.effective_mass(1.0, np.diag([1.0, 1.0, 3.0]), [0, 0, 1.0], [1.0, 0, 0]),
            NonPhysicalInertiaError,
            r"^J_1 ",
            id="effective-J1",
        ),
        pytest.param(
            lambda: im.effective_mass(1.0, np.eye(3), [0, 1.0], [1.0, 0, 0]),
            ShapeError,
            r"^r_1 has shape \(2,\); expected \(\.\.\., 3\)",
            id="effective-r1-shape",
        ),
        pytest.param(
            lambda: im.effective_mass(
                1.0, np.eye(3), [0, 0, 1.0], [1.0, 0, 0], 1.0, np.diag([1.0, 1.0, 3.0]), [0, 0, 1.0]
            ),
            NonPhysicalInertiaError,
            r"^J_2 ",
            id="effective-J2",
        ),
        pytest.param(
            lambda: im.effective_mass(
                1.0, np.eye(3), [0, 0, 1.0], [1.0, 0, 0], 1.0, np.eye(3), [0, 1.0]
            ),
            ShapeError,
            r"^r_2 has shape \(2,\); expected \(\.\.\., 3\)",
            id="effective-r2-shape",
        ),
        pytest.param(
            lambda: im.normal_relative_velocity(_ball_tuple(r_G=[0, 1.0]), None, **_RIGID_KW),
            ShapeError,
            r"^body_1\.r_G has shape \(2,\)",
            id="nrv-body1-r_G",
        ),
        pytest.param(
            lambda: im.normal_relative_velocity(_ball(), _ball_tuple(v_G=[0, 1.0]), **_RIGID_KW),
            ShapeError,
            r"^body_2\.v_G has shape \(2,\)",
            id="nrv-body2-v_G",
        ),
        pytest.param(
            lambda: im.normal_relative_velocity(
                _ball_tuple(omega=[0, np.nan, 0]), None, **_RIGID_KW
            ),
            NonFiniteError,
            r"^body_1\.omega must be finite",
            id="nrv-omega-nan",
        ),
        pytest.param(
            lambda: im.normal_relative_velocity(_ball(), None, r_S=[0, 0], n=[0, 0, 1.0]),
            ShapeError,
            r"^r_S has shape \(2,\); expected \(\.\.\., 3\)",
            id="nrv-r_S-shape",
        ),
        pytest.param(
            lambda: im.rigid_impact(_ball(), None, r_S=[0, 0], n=[0, 0, 1.0], e=0.5),
            ShapeError,
            r"^r_S has shape \(2,\); expected \(\.\.\., 3\)",
            id="rigid-r_S-shape",
        ),
        pytest.param(
            lambda: im.rigid_impact(_ball(), None, r_S=[0, 0, 0.0], n=[0, 0, 1.0], e=np.nan),
            NonFiniteError,
            r"^e must be finite",
            id="rigid-e-nan",
        ),
        pytest.param(
            lambda: im.hinged_impact(
                1.0,
                np.eye(3),
                [1.0, 0, 0],
                axis_point=[0, 0, 0],
                axis=[0, 0, 0],
                omega=0.0,
                r_P=[1, 0, 0],
                S_P=[0, 1, 0],
            ),
            ZeroNormalError,
            r"^axis must be a non-zero vector; found \[0\.0, 0\.0, 0\.0\]",
            id="hinged-zero-axis",
        ),
        pytest.param(
            lambda: im.centre_of_percussion(
                1.0, np.eye(3), [[1.0, 0, 0], [0, 0, 2.0]], axis_point=[0, 0, 0], axis=[0, 0, 1]
            ),
            OutOfDomainError,
            r"^the centre of mass lies on the axis \(distance h = 0\.0 at index \(1,\)\)",
            id="percussion-on-axis-batched",
        ),
    ],
)
def test_every_message_names_the_argument_the_value_and_the_condition(call, error, match):
    with pytest.raises(error, match=match):
        call()


def test_effective_mass_broadcasts_one_contact_over_a_batch_of_tensors():
    J = np.array([np.eye(3), np.diag([1.0, 2.0, 2.5]), np.diag([0.5, 0.5, 0.9])])
    mu = im.effective_mass(1.5, J, [0.3, 0.0, 1.0], [1.0, 0.0, 0.0])
    assert mu.shape == (3,)
    for i in range(3):
        assert mu[i] == im.effective_mass(1.5, J[i], [0.3, 0.0, 1.0], [1.0, 0.0, 0.0])


@pytest.mark.parametrize(
    ("call", "error", "match"),
    [
        pytest.param(
            lambda: im.direct_impact(-1.0, 1.0, 1.0, 0.0, 0.5),
            NegativeMassError,
            r"^m_1 must be >= 0; found -1\.0",
            id="direct-m1-negative",
        ),
        pytest.param(
            lambda: im.direct_impact(1.0, 1.0, np.nan, 0.0, 0.5),
            NonFiniteError,
            r"^v_1 must be finite",
            id="direct-v1-nan",
        ),
        pytest.param(
            lambda: im.direct_impact([1.0, 0.0], [1.0, 0.0], 1.0, 0.0, 0.5),
            ZeroTotalMassError,
            r"^m_1 \+ m_2 must be > 0; both masses are 0 at index \(1,\)$",
            id="direct-zero-total-batched",
        ),
        pytest.param(
            lambda: im.direct_impact(1.0, 1.0, 1.0, 0.0, [0.5, 1.5]),
            RestitutionRangeError,
            r"^coefficient of restitution e must lie in \[0, 1\]; found 1\.5 at index \(1,\)$",
            id="direct-e-batched",
        ),
        pytest.param(
            lambda: im.direct_impact(1e-10, 1.0, 1e308, -1e308, 1.0),
            ResultOverflowError,
            r"^v_1f overflows float64 at index \(\)",
            id="direct-v1f-overflow",
        ),
        pytest.param(
            lambda: im.direct_impact(1.0, 1e-10, 1e308, -1e308, 1.0),
            ResultOverflowError,
            r"^v_2f overflows float64 at index \(\)",
            id="direct-v2f-overflow",
        ),
        pytest.param(
            lambda: im.hinged_impact(
                [1.0, 0.0],
                np.eye(3),
                [1.0, 0, 0],
                axis_point=[0, 0, 0],
                axis=[0, 0, 1],
                omega=0.0,
                r_P=[1, 0, 0],
                S_P=[0, 1, 0],
            ),
            NonPositiveParameterError,
            r"^m must be > 0 for a rigid body; found 0\.0 at index \(1,\)$",
            id="hinged-zero-m-batched",
        ),
        pytest.param(
            lambda: im.rigid_impact(
                _ball_tuple(J_G=np.diag([1.0, 1.0, 3.0])), None, r_S=[0, 0, 0], n=[0, 0, 1.0], e=0.5
            ),
            NonPhysicalInertiaError,
            r"^body_1\.J_G ",
            id="rigid-J_G",
        ),
        pytest.param(
            lambda: im.rigid_impact(
                _ball_tuple(omega=[0, 1.0]), None, r_S=[0, 0, 0.0], n=[0, 0, 1.0], e=0.5
            ),
            ShapeError,
            r"^body_1\.omega has shape \(2,\)",
            id="rigid-omega-shape",
        ),
        pytest.param(
            lambda: im.hinged_effective_mass(
                np.diag([1.0, 1.0, 3.0]),
                [1.0, 0, 0],
                [0, 1.0, 0],
                axis_point=[0, 0, 0],
                axis=[0, 0, 1],
            ),
            NonPhysicalInertiaError,
            r"^J_A ",
            id="hinged-J_A",
        ),
        pytest.param(
            lambda: im.normal_relative_velocity(_ball(), None, r_S=[0, 0, 0.0], n=[0, 0, 0.0]),
            ZeroNormalError,
            r"^n must be a non-zero vector; found \[0\.0, 0\.0, 0\.0\]",
            id="nrv-zero-n",
        ),
        pytest.param(
            lambda: im.centre_of_percussion(
                1.0, np.eye(3), [4 * EPS, 0, 1.0], axis_point=[0, 0, 0], axis=[0, 0, 1]
            ),
            OutOfDomainError,
            r"^the centre of mass lies on the axis",
            id="percussion-h-at-4-eps",
        ),
        pytest.param(
            lambda: im.centre_of_percussion(
                1.0, np.eye(3), [1e-7, 0, 1e10], axis_point=[0, 0, 0], axis=[0, 0, 1]
            ),
            OutOfDomainError,
            r"^the centre of mass lies on the axis \(distance h = 1e-07",
            id="percussion-far-G-near-axis",
        ),
    ],
)
def test_more_messages_name_the_argument_the_value_and_the_condition(call, error, match):
    with pytest.raises(error, match=match):
        call()


def test_centre_of_percussion_just_beyond_rounding_of_the_axis_is_found():
    # h = 4.5 eps (|AG| = 1): G is off the axis by more than the rounding bound
    P, _ = im.centre_of_percussion(
        1.0, np.eye(3), [4.5 * EPS, 0, 1.0], axis_point=[0, 0, 0], axis=[0, 0, 1]
    )
    assert np.isfinite(P).all()
    np.testing.assert_allclose(P[0], 1.0 / (4.5 * EPS), rtol=HAND_RTOL)  # J_zz/(m h)


def test_a_huge_or_tiny_normal_is_the_same_direction():
    args = (1.0, np.diag([1.0, 2.0, 2.5]), [0.3, -0.2, 1.0])
    mu = im.effective_mass(*args, [1.0, 0.0, 1.0])
    for scale in (1e300, 1e-300):
        assert im.effective_mass(*args, [scale, 0.0, scale]) == pytest.approx(mu, rel=HAND_RTOL)


def test_rigid_impact_reports_the_normal_relative_velocity_before():
    ball = _ball(v_G=[0.5, 0, -2.0], omega=[0.0, 1.0, 0])
    out = im.rigid_impact(ball, None, r_S=[0, 0, 0.0], n=[0, 0, 1.0], e=0.5)
    v_n = im.normal_relative_velocity(ball, None, r_S=[0, 0, 0.0], n=[0, 0, 1.0])
    assert out.v_n == v_n
    assert float(v_n) == -2.0  # v_G + ω × (S − G) = (0.5 − 1, 0, −2): its e_z part


# ------------------------------------------------- issue 16: the last known bad inputs


def test_batches_that_do_not_broadcast_raise_a_shape_error_listing_each_shape():
    with pytest.raises(ShapeError, match=r"direct_impact: .* m_1 \(2,\), m_2 \(3,\), v_1 \(\)"):
        im.direct_impact([1.0, 1.0], [1.0, 1.0, 1.0], 1.0, -1.0, 0.5)


def test_no_domain_says_batches_end_in_numpys_bare_value_error():
    text = " ".join((getattr(im, n).__doc__ or "") for n in im.__all__ if n != "DIRECT_ULPS")
    assert "bare ValueError" not in " ".join(text.split())


_FIELDS = dict(
    m=2.0, J_G=np.diag([1.0, 2.0, 2.5]), r_G=[0.1, 0, 0], v_G=[0, 0, -1.0], omega=[0] * 3
)


@pytest.mark.parametrize("field", list(_FIELDS))
@pytest.mark.parametrize(
    ("bad", "error", "match"),
    [
        pytest.param(np.nan, NonFiniteError, "must be finite; found nan", id="nan"),
        pytest.param(np.inf, NonFiniteError, "must be finite; found inf", id="inf"),
        pytest.param("1.0", ShapeError, "has dtype <U3; a real numeric array", id="string"),
        pytest.param(None, ShapeError, "has dtype object; a real numeric array", id="None"),
    ],
)
def test_a_rigid_body_is_validated_when_built_naming_the_field(field, bad, error, match):
    v = np.array(_FIELDS[field], dtype=float)
    value = bad if isinstance(bad, str) or bad is None else np.where(v == v.flat[0], bad, v)
    with pytest.raises(error, match=rf"^{field} {match}"):
        im.RigidBody(**(_FIELDS | {field: value}))


@pytest.mark.parametrize(
    ("kw", "error", "match"),
    [
        pytest.param({"m": 0.0}, NonPositiveParameterError, r"^m must be > 0", id="zero-m"),
        pytest.param({"m": -1.0}, NegativeMassError, r"^m must be >= 0", id="negative-m"),
        pytest.param(
            {"J_G": np.diag([1.0, 1.0, 3.0])}, NonPhysicalInertiaError, r"^J_G ", id="J_G-triangle"
        ),
        pytest.param({"v_G": [0, 1.0]}, ShapeError, r"^v_G has shape \(2,\)", id="v_G-shape"),
        pytest.param(
            {"m": [1.0, 1.0], "omega": np.zeros((3, 3))},
            ShapeError,
            r"^the batch axes of the rigid body's fields do not broadcast: m \(2,\), "
            r"J_G \(3, 3\), r_G \(3,\), v_G \(3,\), omega \(3, 3\)$",
            id="batches-2-against-3",
        ),
    ],
)
def test_a_rigid_body_refuses_unphysical_fields_and_batches_that_do_not_broadcast(kw, error, match):
    with pytest.raises(error, match=match):
        im.RigidBody(**(_FIELDS | kw))
    good = im.RigidBody(**_FIELDS)
    with pytest.raises(error, match=match):
        good._replace(**kw)  # namedtuple's _replace goes through the same checks
    with pytest.raises(error, match=match):
        im.RigidBody._make((_FIELDS | kw).values())


def test_a_rigid_body_keeps_its_fields_as_float64_arrays_and_unpacks_as_a_tuple():
    b = im.RigidBody(2, [[1, 0, 0], [0, 2, 0], [0, 0, 3]], [1, 2, 3], [0, 0, -1], [0, 1, 0])
    m, J, r, v, w = b
    assert all(isinstance(f, np.ndarray) and f.dtype == np.float64 for f in b)
    assert m == 2.0
    assert r.tolist() == [1.0, 2.0, 3.0]
    assert w.tolist() == [0.0, 1.0, 0.0]
    assert_equal = np.testing.assert_array_equal
    assert_equal(J, np.diag([1.0, 2.0, 3.0]))
    assert_equal(v, [0.0, 0.0, -1.0])
    assert_equal(pickle.loads(pickle.dumps(b)).J_G, J)
    # a batch of bodies that broadcasts: one tensor for three velocities
    assert im.RigidBody(1.0, np.eye(3), [0, 0, 0], np.zeros((3, 3)), [0, 0, 0]).v_G.shape == (3, 3)


@pytest.mark.parametrize(
    "body",
    [
        pytest.param(_FIELDS | {"m": 1e300, "v_G": [0, 0, -1e300]}, id="m-and-v_G-1e300"),
        pytest.param(
            _FIELDS | {"omega": [1e300, 0, 0], "r_G": [0, -1e300, 0]}, id="omega-arm-1e300"
        ),
        pytest.param(_FIELDS | {"J_G": 1e-300 * np.eye(3), "v_G": [0, 0, -1.0]}, id="J_G-1e-300"),
    ],
)
def test_rigid_impact_beyond_float64_is_a_result_overflow_error_not_a_warning(body):
    r_S = [1e300, 0, 0] if body["J_G"][0][0] < 1 else [0.1, 0, 0]  # a 1e300 arm over J_G 1e-300
    with pytest.raises(
        ResultOverflowError, match=r"^rigid_impact: (the result is not finite|the norm|1/μ = 1/m)"
    ):
        im.rigid_impact(im.RigidBody(**body), None, r_S=r_S, n=[0, 0, 1.0], e=0.5)


def test_normal_relative_velocity_beyond_float64_is_a_result_overflow_error():
    spinning = im.RigidBody(**(_FIELDS | {"omega": [1e300, 0, 0]}))
    with pytest.raises(ResultOverflowError, match=r"^normal_relative_velocity: the result is"):
        im.normal_relative_velocity(spinning, r_S=[0, 1e300, 0], n=[0, 0, 1.0])


def test_rigid_impact_batches_that_do_not_broadcast_name_each_argument_and_body():
    two = im.RigidBody(**(_FIELDS | {"m": [1.0, 2.0]}))
    with pytest.raises(
        ShapeError,
        match=r"^rigid_impact: the batch axes of the arguments do not broadcast: "
        r"body_1 \(2,\), r_S \(3,\), n \(\), e \(\)$",
    ):
        im.rigid_impact(two, None, r_S=np.zeros((3, 3)), n=[0, 0, 1.0], e=0.5)


def test_hinged_impact_batches_of_omega_that_do_not_broadcast_are_a_shape_error():
    # omega enters only ω', m only S_axis: without the check the two came out unbroadcast
    with pytest.raises(ShapeError, match=r"^hinged_impact: .* m \(2,\), .* omega \(3,\)"):
        im.hinged_impact(
            [1.0, 2.0], np.eye(3), [1.0, 0, 0], axis_point=[0] * 3, axis=Z3,
            omega=[0.0, 1.0, 2.0], r_P=[1.0, 0, 0], S_P=[0, 1.0, 0],
        )  # fmt: skip


def test_centre_of_percussion_far_from_the_axis_is_that_of_the_scaled_body_exactly():
    # m = 2^-600, |AG| = 1.5 2^600: m h = 1.5 as for m = 1, |AG| = 1.5; |AG|² overflowed before
    J_A = np.diag([1e-3, 4.0, 4.0])
    far = im.centre_of_percussion(
        2.0**-600, J_A, [1.5 * 2.0**600, 0, 0], axis_point=[0] * 3, axis=Z3
    )
    near = im.centre_of_percussion(1.0, J_A, [1.5, 0, 0], axis_point=[0] * 3, axis=Z3)
    np.testing.assert_array_equal(far.point, near.point)
    np.testing.assert_array_equal(far.direction, near.direction)


# ------------------------------------ issue 35: every batch axis and every branch checked


def _batch_of_two(field):
    """The value of ``field`` of :func:`_ball` for a batch of two bodies (each still valid)."""
    one = dict(J_G=0.4 * np.eye(3), r_G=[0, 0, 1.0], v_G=[0, 0, -1.0], omega=[0, 0, 0.0])[field]
    return np.stack([np.asarray(one, float)] * 2)


@pytest.mark.parametrize(
    ("fields", "listed"),
    [
        pytest.param(
            {"J_G": np.stack([np.eye(3)] * 2), "v_G": np.zeros((3, 3))},
            r"J_G \(2, 3, 3\), r_G \(3,\), v_G \(3, 3\), omega \(3,\)",
            id="J_G-2-against-v_G-3",
        ),
        pytest.param(
            {"r_G": np.zeros((2, 3)), "omega": np.zeros((3, 3))},
            r"J_G \(3, 3\), r_G \(2, 3\), v_G \(3,\), omega \(3, 3\)",
            id="r_G-2-against-omega-3",
        ),
    ],
)
def test_a_rigid_body_compares_the_batch_axes_of_every_field(fields, listed):
    # the batch axes are m's shape, J_G's without its (3, 3) and r_G's, v_G's, omega's without
    # their 3: a batch of 2 in J_G or r_G against 3 in another field is refused
    head = r"^the batch axes of the rigid body's fields do not broadcast: m \(\), "
    with pytest.raises(ShapeError, match=head + listed + "$"):
        im.RigidBody(**(_FIELDS | fields))


@pytest.mark.parametrize("field", ["J_G", "r_G", "v_G", "omega"])
@pytest.mark.parametrize("which", ["body_1", "body_2"])
def test_a_bodys_batch_is_that_of_each_of_its_fields_and_is_named(field, which):
    # a batch of two bodies, the batch in one field only, against three contact points
    batched = _ball(**{field: _batch_of_two(field)})
    bodies = (batched, None) if which == "body_1" else (_ball(), batched)
    listed = "body_1 (2,)" if which == "body_1" else "body_1 (), body_2 (2,)"
    r_S = np.zeros((3, 3))
    head = "the batch axes of the arguments do not broadcast: " + listed + ", r_S (3,), n ()"
    with pytest.raises(
        ShapeError, match="^" + re.escape("normal_relative_velocity: " + head) + "$"
    ):
        im.normal_relative_velocity(*bodies, r_S=r_S, n=[0, 0, 1.0])
    with pytest.raises(ShapeError, match="^" + re.escape("rigid_impact: " + head + ", e ()") + "$"):
        im.rigid_impact(*bodies, r_S=r_S, n=[0, 0, 1.0], e=0.5)


def test_contact_points_and_normals_are_batches_of_their_own():
    # r_S (3, 3) is a batch of 3 points, n (2, 3) a batch of 2 normals: refused, each named
    head = "the batch axes of the arguments do not broadcast: body_1 (), r_S (3,), n (2,)"
    r_S, n = np.zeros((3, 3)), np.array([[0, 0, 1.0], [0, 1.0, 0]])
    with pytest.raises(
        ShapeError, match="^" + re.escape("normal_relative_velocity: " + head) + "$"
    ):
        im.normal_relative_velocity(_ball(), r_S=r_S, n=n)
    with pytest.raises(ShapeError, match="^" + re.escape("rigid_impact: " + head + ", e ()") + "$"):
        im.rigid_impact(_ball(), r_S=r_S, n=n, e=0.5)


def test_one_contact_point_serves_a_batch_of_normals_and_one_normal_a_batch_of_points():
    # _ball: G at e_z, v_G = −e_z, no spin: every contact point moves at −e_z.
    # Normals e_z and e_y at the one point r_S = 0: v_n = (−1, 0).
    n = np.array([[0, 0, 1.0], [0, 1.0, 0]])
    assert im.normal_relative_velocity(_ball(), r_S=[0, 0, 0.0], n=n).tolist() == [-1.0, 0.0]
    # one normal e_z, two points (the bottom and the side of the ball): v_n = (−1, −1)
    r_S = np.array([[0, 0, 0.0], [1.0, 0, 1.0]])
    assert im.normal_relative_velocity(_ball(), r_S=r_S, n=[0, 0, 1.0]).tolist() == [-1.0, -1.0]
    # rigid_impact at the bottom, n = e_z: arm −e_z ∥ n, μ = m = 1, S = (1 + e)·1 = 1.5;
    # along e_y the contact grazes (v_n = 0): no impulse
    out = im.rigid_impact(_ball(), r_S=[0, 0, 0.0], n=n, e=0.5)
    assert out.S.tolist() == [1.5, 0.0]
    assert out.body_1.v_G.tolist() == [[0, 0, 0.5], [0, 0, -1.0]]
    out = im.rigid_impact(_ball(), r_S=r_S[:1].repeat(2, axis=0), n=[0, 0, 1.0], e=0.5)
    assert out.S.tolist() == [1.5, 1.5]


def test_rigid_impact_names_a_normal_relative_velocity_beyond_float64():
    # v_G = −1.5e308 (e_y + e_z), n = (e_y + e_z)/√2: v_n = −3e308/√2 ≈ −2.1e308 overflows
    fast = im.RigidBody(1.0, np.eye(3), [0, 0, 1.0], [0, -1.5e308, -1.5e308], [0, 0, 0.0])
    with pytest.raises(
        ResultOverflowError,
        match="^"
        + re.escape(
            "rigid_impact: the normal relative velocity v_n exceeds float64's range (~1.8e308) "
            "for these finite inputs; rescale the inputs (choose units)"
        )
        + "$",
    ):
        im.rigid_impact(fast, r_S=[0, 0, 0.0], n=[0, 1.0, 1.0], e=0.5)


_HINGED = dict(
    m=2.0,
    J_A=np.diag([30.0, 30.0, 49.0]),
    r_G=[0.5, 0, 0],
    axis_point=[0, 0, 0.0],
    axis=[0, 0, 1.0],
    omega=0.0,
    r_P=[1.0, 0, 0],
    S_P=[0, 1.0, 0],
)


def test_hinged_impact_broadcasts_one_vector_of_each_kind_over_a_batch_of_masses():
    # Δω = a·(AP × S_P)/J_a = 1/49 whatever the mass; S_axis = m Δω a × AG − S_P with
    # a × AG = 0.5 e_y: (m/98 − 1) e_y, for m = 2 and 4
    out = im.hinged_impact(**(_HINGED | {"m": [2.0, 4.0], "omega": [0.0, 1.0]}))
    dw = 1 / 49
    assert out.omega.tolist() == [dw, 1.0 + dw]
    np.testing.assert_allclose(out.S_axis[:, 1], [2 / 98 - 1, 4 / 98 - 1], rtol=HAND_RTOL)


_HINGED_BATCHES = {
    "J_A": np.stack([np.diag([30.0, 30.0, 49.0])] * 3),
    "r_G": np.tile([0.5, 0, 0], (3, 1)),
    "axis_point": np.zeros((3, 3)),
    "axis": np.tile([0, 0, 1.0], (3, 1)),
    "r_P": np.tile([1.0, 0, 0], (3, 1)),
    "S_P": np.tile([0, 1.0, 0], (3, 1)),
}


@pytest.mark.parametrize("name", list(_HINGED_BATCHES))
def test_hinged_impact_names_each_argument_whose_batch_does_not_broadcast(name):
    # a batch of 2 masses against a batch of 3 in one of the vectors or tensors
    shapes = dict.fromkeys(["J_A", "r_G", "axis_point", "axis", "omega", "r_P", "S_P"], "()")
    shapes[name] = "(3,)"
    if name == "axis_point":  # r_G and r_P are taken relative to it: AG, AP carry its batch
        shapes["r_G"] = shapes["r_P"] = "(3,)"
    listed = ", ".join(f"{k} {v}" for k, v in shapes.items())
    message = f"hinged_impact: the batch axes of the arguments do not broadcast: m (2,), {listed}"
    with pytest.raises(ShapeError, match="^" + re.escape(message) + "$"):
        im.hinged_impact(**(_HINGED | {"m": [2.0, 4.0], name: _HINGED_BATCHES[name]}))


def test_hinged_impact_leaves_no_moment_about_the_axis_not_even_a_rounding():
    # J_a = 49, AP × S_P = e_z: Δω = fl(1/49), and fl(fl(1/49)·49) = 1 − 2^-53 ≠ 1, so
    # Δω J_A a − AP × S_P has a rounding 2^-53 along the axis; frictionless bearings take
    # no moment about it, and with a = e_z its removal is exact: M_axis = 0 (J_A a ∥ a).
    assert (1 / 49) * 49 != 1.0  # the rounding is there to remove
    out = im.hinged_impact(**_HINGED)
    assert float(out.omega) == 1 / 49
    assert out.M_axis.tolist() == [0.0, 0.0, 0.0]


def test_hinged_effective_mass_names_the_index_of_a_blow_without_lever_arm():
    _, J_A, _ = _rod_on_axis()
    r_P = np.array([[1.0, 0, 0], [0, 0, 2.5]])  # the second on the axis
    message = (
        "r_P gives the blow no lever arm about the axis (a.(AP x n) = 0 at index {}: P on the "
        "axis, or n in the plane of the axis and P); the blow cannot turn the body and its "
        "effective mass is infinite"
    )
    with pytest.raises(OutOfDomainError, match="^" + re.escape(message.format("(1,)")) + "$"):
        im.hinged_effective_mass(J_A, r_P, [0, 1.0, 0], axis_point=[0, 0, 0], axis=Z3)
    with pytest.raises(OutOfDomainError, match="^" + re.escape(message.format("()")) + "$"):
        im.hinged_effective_mass(J_A, r_P[1], [0, 1.0, 0], axis_point=[0, 0, 0], axis=Z3)


def test_centre_of_percussion_scales_each_body_of_a_batch_by_its_own_distance():
    # rows 2^±600 apart: scaled by one common power of two the near row would underflow.
    # Each row is the rod of the scalar case with m h = 1.5 exactly: P = (J_zz/(m h)) e_x =
    # (4/1.5) e_x for both, to the bit.
    J_A = np.diag([1e-3, 4.0, 4.0])
    m = np.array([2.0**-600, 2.0**600])
    r_G = np.array([[1.5 * 2.0**600, 0, 0], [1.5 * 2.0**-600, 0, 0]])
    P, b = im.centre_of_percussion(m, J_A, r_G, axis_point=[0] * 3, axis=Z3)
    near = im.centre_of_percussion(1.0, J_A, [1.5, 0, 0], axis_point=[0] * 3, axis=Z3)
    np.testing.assert_array_equal(P, [near.point] * 2)
    np.testing.assert_array_equal(b, [near.direction] * 2)
    assert math.isclose(float(near.point[0]), 4 / 1.5, rel_tol=HAND_RTOL)


def _asymmetric_inertia():
    """A tensor of entries in [1, 2) (off the diagonal in [0.1, 0.2)) that is symmetric but
    for one pair, 16 eps of its largest entry apart (check_inertia accepts 64 eps)."""
    J = np.array([[1.0, 0.15, -0.125], [0.15, 1.25, 0.1875], [-0.125, 0.1875, 1.5]])
    J[1, 0] += 16 * EPS * 1.5
    return J


@pytest.mark.parametrize("batched", [False, True], ids=["one", "batch"])
@pytest.mark.parametrize(
    ("k", "arm"),
    [
        pytest.param(0, 0, id="unit-tensor"),
        # J 2^1023: J + Jᵀ overflows on the diagonal; the arm 2^511 keeps J⁻¹ (r × n) normal
        pytest.param(1023, 511, id="tensor-near-1.8e308"),
    ],
)
def test_rigid_impact_reads_a_tensor_through_its_symmetric_part(batched, k, arm):
    # J, Jᵀ and the exact mean (J + Jᵀ)/2 rounded once are the same tensor to the solves:
    # the impacts agree to the bit, also where J + Jᵀ overflows float64
    J = np.ldexp(_asymmetric_inertia(), k)
    mean = np.array(
        [[float((Fraction(J[i, j]) + Fraction(J[j, i])) / 2) for j in range(3)] for i in range(3)]
    )
    r_S = np.ldexp(np.array([0.3, -0.2, 0.5]), arm)

    def impact(tensor):
        tensor = np.stack([tensor] * 2) if batched else tensor
        body = im.RigidBody(1.0, tensor, [0, 0, 0], [0, 0, -1.0], [0, 0, 0])
        return im.rigid_impact(body, None, r_S=r_S, n=[0.0, 0.6, 0.8], e=0.5)

    want = impact(mean)
    assert np.all(want.body_1.omega != 0)  # the asymmetric entries reach the result
    assert np.isfinite(want.body_1.omega).all()
    for tensor in (J, J.T):
        got = impact(tensor)
        for name in ("S", "mu", "v_n", "Q"):
            np.testing.assert_array_equal(getattr(got, name), getattr(want, name), err_msg=name)
        for name in ("v_G", "omega", "J_G"):
            np.testing.assert_array_equal(
                getattr(got.body_1, name), getattr(want.body_1, name), err_msg=name
            )


def test_the_restitution_impulse_of_a_compression_impulse_near_1e305_is_finite():
    # Found by the full mutation run of issue 35: S_2 = e S_1 was formed by Dekker's split
    # (a product with 2**27 + 1), which overflowed for |S_1| above ~1.34e300 and raised a
    # false "S_2 overflows float64".
    # m_1 = m_2 = 2: μ = 1, Δẋ = −1e305: S_1 = μ Δẋ = −1e305; e = ½: S_2 = e S_1, exact
    S1, S2 = im.compression_restitution_impulses(2.0, 2.0, 1e305, 0.0, 0.5)
    assert float(S1) == -1e305
    assert float(S2) == 0.5 * -1e305


def _exact_solve(J, u):
    """J⁻¹ u in exact rationals (Cramer's rule on the floats' values)."""
    J = [[Fraction(x) for x in row] for row in J]
    u = [Fraction(x) for x in u]

    def det(M):
        return (
            M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1])
            - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0])
            + M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0])
        )

    d = det(J)
    return [
        det([[u[i] if c == k else J[i][c] for c in range(3)] for i in range(3)]) / d
        for k in range(3)
    ]


#: μ and ω' of a body whose tensor's entries are subnormal, against exact rationals: a 3×3
#: solve of a tensor of condition ~2.3, a dot of three, a sum and a reciprocal (then a
#: product and a sum for ω'): each a few roundings, measured ≤ 1.5 eps; 16 eps
TINY_TENSOR_EPS = 16


@pytest.mark.parametrize(
    ("p_m", "p_J", "p_r"),
    [(-1000, -1040, -20), (-1000, -1052, -26), (-1020, -1062, -22), (0, 0, 0), (600, 640, 20)],
)
def test_effective_mass_and_impact_of_a_tensor_at_any_scale_against_exact_rationals(p_m, p_J, p_r):
    """m = 2^p_m, J = 2^p_J J0, arm 2^p_r r0: μ and ω' are normal floats however small the
    tensor's entries (subnormal at 2^-1052 and 2^-1062).  The tensor is solved scaled by a
    power of two: unscaled, μ came out 5.5 % off at 2^-1040 and 0 at 2^-1052."""
    J0 = np.array([[2.0, 0.5, 0.0], [0.5, 3.0, 0.25], [0.0, 0.25, 4.0]])
    m, J = 2.0**p_m, J0 * 2.0**p_J
    r = np.array([1.0, 0.5, 0.25]) * 2.0**p_r
    n = np.array([0.0, 0.0, 1.0])
    u = np.cross(r, n)  # exact: products by 0 and 1
    x = _exact_solve(J, u)
    inv = 1 / Fraction(m) + sum(Fraction(a) * b for a, b in zip(u, x, strict=True))
    mu = 1 / inv
    got = float(im.effective_mass(m, J, r, n))
    assert abs(Fraction(got) / mu - 1) <= TINY_TENSOR_EPS * Fraction(EPS)
    # the impact against a fixed body, v_n = −1, e = 1/2: S = 3/2 μ, ω' = S J⁻¹u (ω = 0)
    body = im.RigidBody(m, J, [0.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 0.0, 0.0])
    out = im.rigid_impact(body, None, r_S=r, n=n, e=0.5)
    S = Fraction(3, 2) * mu
    assert abs(Fraction(float(out.S)) / S - 1) <= TINY_TENSOR_EPS * Fraction(EPS)
    w = [S * c for c in x]
    size = max(abs(c) for c in w)
    for got_c, want_c in zip(out.body_1.omega.tolist(), w, strict=True):
        assert abs(Fraction(got_c) - want_c) <= TINY_TENSOR_EPS * Fraction(EPS) * size


def test_a_batch_of_contacts_at_very_different_scales_gives_each_its_own_mu():
    """Each contact's tensor and arm are scaled by their own powers of two: a batch of a
    tiny body with a tiny arm (m = 2^1000, J = 2^-1000 J0, r = 2^-600 r0: μ ≈ 2^200) beside
    an ordinary one gives each the μ it has alone, bit for bit (one scale for the whole
    batch would flush the first's arm or tensor to zero)."""
    J0 = np.array([[2.0, 0.5, 0.0], [0.5, 3.0, 0.25], [0.0, 0.25, 4.0]])
    r0 = np.array([1.0, 0.5, 0.25])
    m = np.array([2.0**1000, 1.0])
    J = np.stack([J0 * 2.0**-1000, J0 * 2.0**100])
    r = np.stack([r0 * 2.0**-600, r0 * 2.0**500])
    n = [0.0, 0.0, 1.0]
    batch = im.effective_mass(m, J, r, n)
    alone = [float(im.effective_mass(m[i], J[i], r[i], n)) for i in range(2)]
    assert batch.tolist() == alone
    assert 2.0**190 < alone[0] < 2.0**210  # the tiny arm's μ, far from m = 2^1000


def test_rigid_impact_refuses_an_inverse_effective_mass_beyond_float64_by_name():
    """An arm of 1e300 on a unit tensor: 1/μ ~ 1e600, so μ and the impulse underflow and the
    change of ω they make is lost: refused, with the whole reason."""
    body = im.RigidBody(1.0, np.eye(3), [0.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 0.0, 0.0])
    with pytest.raises(ResultOverflowError) as info:
        im.rigid_impact(body, None, r_S=[1e300, 0.0, 0.0], n=[0.0, 0.0, 1.0], e=0.5)
    assert str(info.value) == (
        "rigid_impact: 1/μ = 1/m + (r × n)·J⁻¹(r × n) exceeds float64's range (~1.8e308: an "
        "arm beyond ~1e154 radii of gyration, or 1e300 and 1e-300 mixed), so μ and the "
        "impulse underflow and the change of ω they make (finite) is lost; rescale the "
        "inputs (choose units)"
    )
