"""API, validation and edge cases of :mod:`mechanics.dynamics`.

Each result is checked by a route independent of the code under test: the
particle sums behind L = J ω, the vector form (4.46) behind Euler's component
equations (4.47), the momentum principle behind the reactions, a numerical
integration (scipy DOP853) behind the exact pendulum motion, and the book's
worked Examples 4.3 and 4.4 with their printed results.
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from mechanics import dynamics as D
from mechanics import inertia as I
from mechanics._floats import ulps
from mechanics.errors import (
    NegativeMassError,
    NonFiniteError,
    NonPhysicalInertiaError,
    NonPositiveParameterError,
    OutOfDomainError,
    ShapeError,
    UnknownOptionError,
)
from mechanics.rotation import EPS, matrix_from_rotvec

#: A short sum of rounded products (J ω, Euler's right-hand side): 8 eps of
#: the largest term.
SUM_ATOL = 8 * EPS

#: DOP853 at rtol = atol = 1e-13 over two periods: the global error of the
#: integrated pendulum angle, amplified near the separatrix (θ0 = 3.1: measured
#: 1.1e-9; θ0 ≤ 2: below 1e-11).  The exact motion itself is within a few eps
#: of mpmath (tests/stability); this bounds the integrator.
ODE_ATOL = 1e-8

G_EARTH = 9.81


# ------------------------------------------------------------ angular momentum


def test_angular_momentum_rigid_equals_the_particle_sum_4_1():
    rng = np.random.default_rng(4)
    m = rng.uniform(0.5, 2.0, 6)
    r = rng.normal(size=(6, 3))
    w = rng.normal(size=3)
    J = I.inertia_tensor(m, r, about=np.zeros(3))
    L_sum = np.sum(m[:, None] * np.cross(r, np.cross(w, r)), axis=0)
    L = D.angular_momentum_rigid(J, w)
    np.testing.assert_allclose(L, L_sum, rtol=0, atol=64 * EPS * np.abs(L_sum).max())


def test_angular_momentum_rigid_of_a_rod_about_its_axis_is_zero():
    L = D.angular_momentum_rigid(I.rod(1.0, 2.0), [0.0, 0.0, 5.0])
    assert L.tolist() == [0.0, 0.0, 0.0]


def test_angular_momentum_rigid_broadcasts_and_validates():
    J = np.broadcast_to(np.eye(3), (4, 3, 3))
    assert D.angular_momentum_rigid(J, np.ones(3)).shape == (4, 3)
    with pytest.raises(NonPhysicalInertiaError):
        D.angular_momentum_rigid(np.diag([1.0, 1.0, 3.0]), np.ones(3))
    with pytest.raises(ShapeError):
        D.angular_momentum_rigid(np.eye(3), np.ones(2))
    with pytest.raises(NonFiniteError):
        D.angular_momentum_rigid(np.eye(3), [np.nan, 0, 0])


def test_rotational_kinetic_energy_is_half_omega_dot_L():
    J = I.rotate_inertia(np.diag([1.0, 2.0, 2.5]), matrix_from_rotvec([0.4, 0.2, -1.0]))
    w = np.array([0.3, -1.1, 0.8])
    T = D.rotational_kinetic_energy(J, w)
    assert pytest.approx(0.5 * w @ D.angular_momentum_rigid(J, w), rel=SUM_ATOL) == T


# ------------------------------------------------------------ Euler's equations


def test_euler_equations_match_the_vector_form_4_46():
    # In the body basis, dL/dt = J ω̇ + ω × J ω = M (4.44)-(4.46).
    rng = np.random.default_rng(5)
    J = np.array([1.0, 2.0, 2.5])
    w = rng.normal(size=(20, 3))
    M = rng.normal(size=(20, 3))
    wdot = D.euler_equations_rhs(J, w, M)
    residual = J * wdot + np.cross(w, J * w) - M
    assert np.abs(residual).max() <= 16 * EPS * (np.abs(M).max() + 2.5 * np.abs(w).max() ** 2)


def test_euler_equations_of_a_spherical_top_give_omega_dot_M_over_J():
    wdot = D.euler_equations_rhs([2.0, 2.0, 2.0], [1.0, -3.0, 0.5], [0.2, 0.4, 0.6])
    np.testing.assert_array_equal(wdot, [0.1, 0.2, 0.3])


def test_euler_equations_steady_rotation_about_a_principal_axis():
    assert D.euler_equations_rhs([1.0, 2.0, 2.5], [0.0, 3.0, 0.0], np.zeros(3)).tolist() == [
        0.0,
        0.0,
        0.0,
    ]


@pytest.mark.parametrize(
    ("J", "error", "text"),
    [
        pytest.param([0.0, 1.0, 1.0], NonPositiveParameterError, "> 0", id="rod"),
        pytest.param([-1.0, 1.0, 1.0], NonPositiveParameterError, "> 0", id="negative"),
        pytest.param([1.0, 1.0, 3.0], NonPhysicalInertiaError, "triangle", id="triangle"),
        pytest.param([1.0, 1.0], ShapeError, "shape", id="shape"),
    ],
)
def test_euler_equations_reject_bad_moments(J, error, text):
    with pytest.raises(error, match=text):
        D.euler_equations_rhs(J, np.ones(3), np.zeros(3))


def test_fixed_axis_angular_acceleration():
    assert D.fixed_axis_angular_acceleration(4.0, 2.0) == 0.5
    with pytest.raises(NonPositiveParameterError):
        D.fixed_axis_angular_acceleration(0.0, 1.0)


# ----------------------------------------------------------------- the pendulum


def test_example_4_3_rod_about_its_end():
    # a) T = 2π √(2l/(3g)) (4.53); b) the simple pendulum of length 2l/3.
    m, l = 1.7, 0.9
    # The rod lies along e3; it swings about the e1 axis through its end.
    J = I.parallel_axis(I.rod(m, l), m, [0.0, 0.0, l / 2], allow_singular=True)[0, 0]
    assert pytest.approx(m * l**2 / 3, rel=2 * EPS) == J
    T = D.pendulum_small_period(J, m, G_EARTH, l / 2)
    assert pytest.approx(2 * math.pi * math.sqrt(2 * l / (3 * G_EARTH)), rel=4 * EPS) == T
    assert D.reduced_length(J, m, l / 2) == pytest.approx(2 * l / 3, rel=4 * EPS)
    # A point mass at the reduced length has the same period (4.49)-(4.50).
    ell = 2 * l / 3
    assert D.pendulum_small_period(m * ell**2, m, G_EARTH, ell) == pytest.approx(T, rel=4 * EPS)


def test_small_period_is_least_when_h_is_the_radius_of_gyration_4_56():
    m, d_G = 2.0, 0.3
    h = np.linspace(0.05, 1.0, 1901)
    T = D.pendulum_small_period(m * d_G**2 + m * h**2, m, G_EARTH, h)  # (4.54)-(4.55)
    h_min = h[np.argmin(T)]
    assert abs(h_min - d_G) <= 0.5e-3
    T_min = D.pendulum_small_period(2 * m * d_G**2, m, G_EARTH, d_G)
    assert T_min == pytest.approx(2 * math.pi * math.sqrt(2 * d_G / G_EARTH), rel=4 * EPS)


def test_example_4_4_angular_velocity_of_the_falling_rod():
    m, l = 1.3, 0.8
    w = D.pendulum_angular_velocity_at(0.0, m * l**2 / 3, m, G_EARTH, l / 2, math.pi / 2)
    assert w == pytest.approx(math.sqrt(3 * G_EARTH / l), rel=4 * EPS)  # (4.59)


def test_angular_velocity_at_agrees_with_energy_4_57():
    J, m, h, t0 = 0.7, 1.1, 0.4, 2.5
    th = np.linspace(-t0, t0, 41)
    w = D.pendulum_angular_velocity_at(th, J, m, G_EARTH, h, t0)
    E = 0.5 * J * w**2 - m * G_EARTH * h * np.cos(th)
    np.testing.assert_allclose(E, -m * G_EARTH * h * math.cos(t0), rtol=0, atol=1e-14 * m * h * 10)
    assert w[0] == 0.0
    assert w[-1] == 0.0


def test_angular_velocity_beyond_the_amplitude_is_out_of_domain():
    with pytest.raises(OutOfDomainError, match="beyond the amplitude"):
        D.pendulum_angular_velocity_at(1.0, 1.0, 1.0, 1.0, 1.0, 0.5)


def test_period_small_amplitude_series():
    # T = T0 (1 + θ0²/16 + 11 θ0⁴/3072 + ...), from K(m) = π/2 (1 + m/4 + 9m²/64 + ...).
    T0 = D.pendulum_small_period(1.0, 1.0, 1.0, 1.0)
    for t0 in (1e-3, 1e-2, 0.05):
        T = D.pendulum_period(1.0, 1.0, 1.0, 1.0, t0)
        series = T0 * (1 + t0**2 / 16 + 11 * t0**4 / 3072)
        assert pytest.approx(series, rel=t0**6 / 50 + 4 * EPS) == T
    assert D.pendulum_period(1.0, 1.0, 1.0, 1.0, 0.0) == pytest.approx(T0, rel=EPS)


def test_period_near_pi_follows_the_logarithm():
    # K(m) = ln(4/k') + O(k'² ln k'), k' = cos(θ0/2) ≈ (π − θ0)/2.
    for delta in (1e-6, 1e-10, 1e-14):
        T = D.pendulum_period(1.0, 1.0, 1.0, 1.0, math.pi - delta)
        d = math.pi - (math.pi - delta) + 1.2246467991473532e-16  # the float's π − θ0
        assert pytest.approx(4 * math.log(8 / d), rel=1e-10) == T


def test_period_is_even_finite_at_float_pi_and_out_of_domain_beyond():
    assert D.pendulum_period(1, 1, 1, 1, -2.0) == D.pendulum_period(1, 1, 1, 1, 2.0)
    assert math.isfinite(D.pendulum_period(1, 1, 1, 1, math.pi))
    with pytest.raises(OutOfDomainError, match="beyond pi"):
        D.pendulum_period(1, 1, 1, 1, 3.2)


@pytest.mark.parametrize(
    ("args", "error"),
    [
        pytest.param((0.0, 1.0, 1.0, 1.0), NonPositiveParameterError, id="J"),
        pytest.param((1.0, -1.0, 1.0, 1.0), NonPositiveParameterError, id="m"),
        pytest.param((1.0, 1.0, 0.0, 1.0), NonPositiveParameterError, id="g"),
        pytest.param((1.0, 1.0, 1.0, 0.0), NonPositiveParameterError, id="h"),
        pytest.param((1.0, 1.0, np.nan, 1.0), NonFiniteError, id="nan"),
    ],
)
def test_pendulum_parameters_are_validated(args, error):
    with pytest.raises(error):
        D.pendulum_small_period(*args)
    with pytest.raises(error):
        D.pendulum_period(*args, 1.0)
    with pytest.raises(error):
        D.pendulum_motion(0.5, *args, 1.0)


def _integrated(t_end, J, m, h, t0):
    w0 = m * G_EARTH * h / J
    sol = solve_ivp(
        lambda t, y: [y[1], -w0 * math.sin(y[0])],  # (4.48)
        (0.0, t_end),
        [t0, 0.0],
        method="DOP853",
        rtol=1e-13,
        atol=1e-13,
        dense_output=True,
    )
    return sol.sol


@pytest.mark.parametrize("theta_0", [0.3, 2.0, 3.1])
def test_pendulum_motion_agrees_with_numerical_integration(theta_0):
    J, m, h = 0.7, 1.1, 0.4
    T = D.pendulum_period(J, m, G_EARTH, h, theta_0)
    t = np.linspace(0.0, 2.0 * T, 101)
    exact = D.pendulum_motion(t, J, m, G_EARTH, h, theta_0)
    numeric = _integrated(2.0 * T, J, m, h, theta_0)(t)[0]
    np.testing.assert_allclose(exact, numeric, rtol=0, atol=ODE_ATOL)


def test_pendulum_motion_turns_at_plus_and_minus_the_amplitude():
    t0 = 2.9
    T = D.pendulum_period(1.0, 1.0, 1.0, 1.0, t0)
    phi = D.pendulum_motion(np.array([0.0, 0.5, 1.0, -0.5]) * T, 1.0, 1.0, 1.0, 1.0, t0)
    np.testing.assert_allclose(phi, [t0, -t0, t0, -t0], rtol=0, atol=64 * EPS * T)


def test_pendulum_motion_mirrors_a_negative_amplitude_and_rests_at_zero():
    t = np.linspace(0, 5, 7)
    np.testing.assert_array_equal(
        D.pendulum_motion(t, 1, 1, 1, 1, -1.0), -D.pendulum_motion(t, 1, 1, 1, 1, 1.0)
    )
    np.testing.assert_array_equal(D.pendulum_motion(t, 1, 1, 1, 1, 0.0), np.zeros(7))


# -------------------------------------------------------------------- reactions


def test_axis_reaction_formula_4_76_agrees_with_the_momentum_principle_4_71():
    J, m, h, t0 = 0.7, 1.1, 0.4, 2.2
    E = m * G_EARTH * h * (1 - math.cos(t0))  # (4.74), released from rest at t0
    phi = np.linspace(-t0, t0, 31)
    phidot = D.pendulum_angular_velocity_at(phi, J, m, G_EARTH, h, t0)
    phiddot = -m * G_EARTH * h / J * np.sin(phi)  # (4.73)
    F_rho, F_phi = m * G_EARTH * np.cos(phi), -m * G_EARTH * np.sin(phi)  # (4.72)
    generic = D.axis_reaction(m, h, phidot, phiddot, F_a_rho=F_rho, F_a_phi=F_phi)
    book = D.pendulum_axis_reaction(phi, J, m, G_EARTH, h, E=E)
    np.testing.assert_allclose(book, generic, rtol=0, atol=64 * EPS * m * G_EARTH * 4)


def test_axis_reaction_of_a_body_balanced_on_its_axis_is_minus_the_applied_force():
    R = D.axis_reaction(2.0, 0.0, 7.0, 3.0, F_a_rho=1.5, F_a_phi=-0.5)
    assert R.tolist() == [-1.5, 0.5]


def test_pendulum_axis_reaction_rejects_an_unreachable_angle():
    with pytest.raises(OutOfDomainError):
        D.pendulum_axis_reaction(1.0, 1.0, 1.0, 1.0, 1.0, E=0.1)


def _newton_euler_residual(J_O, m, r_G, w, a, z_A, F, M, R1, R2):
    """m a_G − (F + R1 + R2) and the x, y parts of dL_O/dt − (M + r_A × R1)."""
    omega = np.array([0.0, 0.0, w])
    alpha = np.array([0.0, 0.0, a])
    a_G = np.cross(alpha, r_G) + np.cross(omega, np.cross(omega, r_G))
    Ldot = J_O @ alpha + np.cross(omega, J_O @ omega)  # (4.44) in the body basis
    moment = M + np.cross([0.0, 0.0, z_A], R1)
    return m * a_G - (F + R1 + R2), (Ldot - moment)[:2]


@pytest.mark.parametrize("axial_at", ["O", "A"])
def test_bearing_reactions_satisfy_both_momentum_principles(axial_at):
    rng = np.random.default_rng(6)
    for _ in range(20):
        J_G = I.rotate_inertia(np.diag([1.0, 2.0, 2.5]), matrix_from_rotvec(rng.normal(size=3)))
        m = rng.uniform(0.5, 2)
        r_G = rng.normal(size=3)
        J_O = I.parallel_axis(J_G, m, -r_G)  # O is at −r_G from G
        w, a, z_A = rng.normal(), rng.normal(), rng.uniform(0.5, 2)
        F, M = rng.normal(size=3), rng.normal(size=3)
        R1, R2 = D.bearing_reactions(J_O, m, r_G, w, a, z_A, F_a=F, M_a=M, axial_at=axial_at)
        force, moment = _newton_euler_residual(J_O, m, r_G, w, a, z_A, F, M, R1, R2)
        assert np.abs(force).max() <= 1e-13
        assert np.abs(moment).max() <= 1e-13
        assert (R1[2] if axial_at == "O" else R2[2]) == 0.0


def test_bearing_reactions_of_the_book_geometry_4_84_4_85():
    # r_G = (h, 0, z_G): (4.78) with the book's D_xz, D_yz.
    m, h, Dxz, Dyz, w, a, zA = 2.0, 0.3, 0.05, -0.02, 4.0, 1.5, 0.8
    J_O = np.array([[1.0, 0.0, -Dxz], [0.0, 1.2, -Dyz], [-Dxz, -Dyz, 0.9]])
    R1, R2 = D.bearing_reactions(
        J_O, m, [h, 0.0, 0.2], w, a, zA, F_a=[0.0, 0.0, 0.0], M_a=[0.0, 0.0, 0.0]
    )
    assert R1[1] == pytest.approx((Dxz * a - Dyz * w**2) / zA, rel=4 * EPS)
    assert R1[0] == pytest.approx(-(Dyz * a + Dxz * w**2) / zA, rel=4 * EPS)
    assert R1[0] + R2[0] == pytest.approx(-m * h * w**2, rel=4 * EPS)
    assert R1[1] + R2[1] == pytest.approx(m * h * a, rel=4 * EPS)


def test_bearing_reactions_validate():
    args = (np.eye(3), 1.0, [0, 0, 0], 1.0, 0.0)
    kw = {"F_a": [0, 0, 0], "M_a": [0, 0, 0]}
    with pytest.raises(UnknownOptionError):
        D.bearing_reactions(*args, 1.0, axial_at="B", **kw)
    with pytest.raises(NonPositiveParameterError, match="coincide"):
        D.bearing_reactions(*args, 0.0, **kw)
    with pytest.raises(NonPhysicalInertiaError):
        D.bearing_reactions(np.diag([1.0, 1.0, 3.0]), *args[1:], 1.0, **kw)
    with pytest.raises(NonPositiveParameterError):
        D.bearing_reactions(np.eye(3), -1.0, *args[2:], 1.0, **kw)


def test_masses_must_not_be_negative_for_the_body_helpers():
    with pytest.raises(NegativeMassError):
        I.disc(-1.0, 1.0)


def test_fixed_axis_angular_momentum_has_the_components_4_79():
    # ω = φ̇ e_z: L = (−D_xz φ̇, −D_yz φ̇, J_z φ̇) with D the products of inertia.
    rng = np.random.default_rng(7)
    m, r = rng.uniform(0.5, 2, 5), rng.normal(size=(5, 3))
    J_O = I.inertia_tensor(m, r, about=np.zeros(3))
    Dxz, Dyz = (m * r[:, 0] * r[:, 2]).sum(), (m * r[:, 1] * r[:, 2]).sum()
    Jz = (m * (r[:, 0] ** 2 + r[:, 1] ** 2)).sum()
    phidot = 1.7
    L = D.angular_momentum_rigid(J_O, [0.0, 0.0, phidot])
    np.testing.assert_allclose(L, [-Dxz * phidot, -Dyz * phidot, Jz * phidot], rtol=1e-14)


def test_example_1_1_skew_rod_is_statically_but_not_dynamically_balanced():
    # Two balls m at ±R(sin ϑ, 0, cos ϑ) turning at constant ω about e_z: the
    # axis must supply M = 2 m R² ω² sin ϑ cos ϑ (sin ωt, −cos ωt, 0) (1.38), here
    # at t = 0 in the body axes, as a couple of the two bearing forces.
    m, R, theta, omega, z_A = 0.3, 0.8, 0.4, 5.0, 1.5
    r1 = R * np.array([math.sin(theta), 0.0, math.cos(theta)])
    J_O = I.inertia_tensor([m, m], [r1, -r1], about=np.zeros(3))
    zero = np.zeros(3)
    R1, R2 = D.bearing_reactions(J_O, 2 * m, zero, omega, 0.0, z_A, F_a=zero, M_a=zero)
    M_book = 2 * m * R**2 * omega**2 * math.sin(theta) * math.cos(theta) * np.array([0, -1, 0])
    np.testing.assert_allclose(np.cross([0.0, 0.0, z_A], R1), M_book, rtol=1e-14, atol=1e-15)
    np.testing.assert_allclose(R1 + R2, zero, atol=1e-15)  # p = 0 (1.36)
    assert np.abs(R1).max() > 0.1  # not dynamically balanced: D_xz ≠ 0


def test_overflow_is_reported_not_returned_as_inf():
    from mechanics.errors import ResultOverflowError

    with pytest.raises(ResultOverflowError):
        D.euler_equations_rhs([1.0, 2.0, 2.5], [1e200, 1e200, 0.0], np.zeros(3))
    with pytest.raises(ResultOverflowError):
        D.rotational_kinetic_energy(np.eye(3), [1e200, 0.0, 0.0])


# ------------------------------------------------ the hinge functions broadcast


def test_bearing_reactions_broadcast_over_bodies_and_states():
    # A batch of three bodies (J_O, m, r_G) and states: row by row as one at a time,
    # and the axial load −F_z on the named bearing.
    J_O = np.array(
        [
            I.rotate_inertia(np.diag([1.0, 2.0, 2.5]), matrix_from_rotvec(v))
            for v in ([0.3, -0.2, 0.9], [1.0, 0.5, 0.0], [-0.4, 0.8, 0.2])
        ]
    )
    m = np.array([1.0, 2.0, 0.5])
    r_G = np.array([[0.3, 0.0, 0.2], [0.1, -0.4, 0.5], [0.0, 0.2, -0.3]])
    w, a, z_A = np.array([4.0, -1.0, 0.5]), np.array([1.5, 0.0, -2.0]), np.array([0.8, 1.0, -1.2])
    F = np.array([[0.0, 1.0, -2.0], [0.5, 0.0, 3.0], [1.0, -1.0, 0.25]])
    M = np.array([[0.1, 0.2, 0.3], [0.0, -0.5, 0.0], [0.4, 0.0, -0.1]])
    for axial_at in ("O", "A"):
        R1, R2 = D.bearing_reactions(J_O, m, r_G, w, a, z_A, F_a=F, M_a=M, axial_at=axial_at)
        assert R1.shape == R2.shape == (3, 3)
        for i in range(3):
            r1, r2 = D.bearing_reactions(
                J_O[i], m[i], r_G[i], w[i], a[i], z_A[i], F_a=F[i], M_a=M[i], axial_at=axial_at
            )
            np.testing.assert_array_equal(R1[i], r1)
            np.testing.assert_array_equal(R2[i], r2)
        axial = R2[:, 2] if axial_at == "O" else R1[:, 2]
        np.testing.assert_array_equal(axial, -F[:, 2])


def test_axis_reactions_broadcast_over_states():
    m, h = np.array([2.0, 1.0]), np.array([0.5, 0.0])
    phidot, phiddot = np.array([[1.0], [3.0]]), np.array([0.5, -2.0])  # (2, 1) with (2,)
    R = D.axis_reaction(m, h, phidot, phiddot, F_a_rho=1.5, F_a_phi=-0.5)
    assert R.shape == (2, 2, 2)
    for i in range(2):
        for j in range(2):
            want = D.axis_reaction(m[j], h[j], phidot[i, 0], phiddot[j], F_a_rho=1.5, F_a_phi=-0.5)
            np.testing.assert_array_equal(R[i, j], want)
    phi = np.array([0.0, 0.4, -1.0])
    Rp = D.pendulum_axis_reaction(phi, 1.0, 2.0, G_EARTH, 0.5, E=np.array([20.0, 10.0, 15.0]))
    assert Rp.shape == (3, 2)
    one = D.pendulum_axis_reaction(phi[1], 1.0, 2.0, G_EARTH, 0.5, E=10.0)
    np.testing.assert_array_equal(Rp[1], one)


def test_axis_reaction_rejects_a_negative_distance_naming_it():
    with pytest.raises(NonPositiveParameterError, match=r"^h must be >= 0; found -0\.5"):
        D.axis_reaction(1.0, [0.2, -0.5], 1.0, 0.0, F_a_rho=0.0, F_a_phi=0.0)
    # h = 0 (G on the axis) is allowed: the message names the negative one after it
    with pytest.raises(NonPositiveParameterError, match=r"^h must be >= 0; found -0\.5$"):
        D.axis_reaction(1.0, [0.0, -0.5], 1.0, 0.0, F_a_rho=0.0, F_a_phi=0.0)


def test_bearing_reactions_name_the_bad_argument():
    args = (np.eye(3), 1.0, [0, 0, 0], 1.0, 0.0)
    kw = {"F_a": [0, 0, 0], "M_a": [0, 0, 0]}
    with pytest.raises(UnknownOptionError, match=r"^axial_at='B'; expected 'O' or 'A'"):
        D.bearing_reactions(*args, 1.0, axial_at="B", **kw)
    with pytest.raises(NonPositiveParameterError, match=r"^z_A must be non-zero"):
        D.bearing_reactions(*args, [1.0, 0.0], **kw)
    with pytest.raises(ShapeError, match=r"^r_G has shape \(2,\)"):
        D.bearing_reactions(np.eye(3), 1.0, [0, 0], 1.0, 0.0, 1.0, **kw)
    with pytest.raises(ShapeError, match=r"^F_a has shape \(2,\)"):
        D.bearing_reactions(*args, 1.0, F_a=[0, 0], M_a=[0, 0, 0])
    with pytest.raises(ShapeError, match=r"^M_a has shape \(2,\)"):
        D.bearing_reactions(*args, 1.0, F_a=[0, 0, 0], M_a=[0, 0])
    with pytest.raises(
        NonPhysicalInertiaError,
        match=r"^J_O breaks the triangle inequality J1 \+ J2 >= J3 about the given point: ",
    ):
        D.bearing_reactions(np.diag([1.0, 1.0, 3.0]), *args[1:], 1.0, **kw)


def _overflow_error():
    from mechanics.errors import ResultOverflowError

    return ResultOverflowError


_NAN = float("nan")
_BR = {"F_a": [0, 0, 0.0], "M_a": [0, 0, 0.0]}
_AR = {"F_a_rho": 0.0, "F_a_phi": 0.0}


@pytest.mark.parametrize(
    ("call", "error", "match"),
    [
        pytest.param(
            lambda: D.pendulum_period(1.0, 1.0, 9.81, 0.5, 4.0),
            OutOfDomainError,
            r"^theta_0 = 4\.0 is beyond pi: a pendulum released from rest oscillates with amplitude \|theta_0\| <= pi$",
            id="amplitude",
        ),
        pytest.param(
            lambda: D.pendulum_period(1.0, 1.0, 9.81, 0.5, _NAN),
            NonFiniteError,
            r"^theta_0 must be finite",
            id="amplitude-nan",
        ),
        pytest.param(
            lambda: D.pendulum_small_period(1.0, 0.0, 9.81, 0.5),
            NonPositiveParameterError,
            r"^m must be > 0; found 0\.0$",
            id="pendulum-m",
        ),
        pytest.param(
            lambda: D.pendulum_small_period(1.0, 1.0, -9.81, 0.5),
            NonPositiveParameterError,
            r"^g must be > 0; found -9\.81$",
            id="pendulum-g",
        ),
        pytest.param(
            lambda: D.pendulum_small_period(1.0, 1.0, 9.81, 0.0),
            NonPositiveParameterError,
            r"^h must be > 0; found 0\.0$",
            id="pendulum-h",
        ),
        pytest.param(
            lambda: D.pendulum_small_period(0.0, 1.0, 9.81, 0.5),
            NonPositiveParameterError,
            r"^J_axis must be > 0; found 0\.0$",
            id="pendulum-J",
        ),
        pytest.param(
            lambda: D.pendulum_small_period(1.0, _NAN, 9.81, 0.5),
            NonFiniteError,
            r"^m must be finite",
            id="pendulum-m-nan",
        ),
        pytest.param(
            lambda: D.euler_equations_rhs([1.0, 2.0], [0, 0, 1.0], [0, 0, 0.0]),
            ShapeError,
            r"^J_principal has shape \(2,\); expected \(\.\.\., 3\)$",
            id="euler-J-shape",
        ),
        pytest.param(
            lambda: D.euler_equations_rhs(
                [[1.0, 2.0, 2.5], [1.0, 1.0, 3.0]], [0, 0, 1.0], [0, 0, 0.0]
            ),
            NonPhysicalInertiaError,
            r"^J_principal breaks the triangle inequality: \[1\.0, 1\.0, 3\.0\] has J_j \+ J_k - J_i = -1 < 0 for i = 3$",
            id="euler-J-triangle-batched",
        ),
        pytest.param(
            lambda: D.euler_equations_rhs([0.0, 3.0, 4.0], [0, 0, 1.0], [0, 0, 0.0]),
            NonPositiveParameterError,
            r"^J_principal must be > 0 \(each principal moment; .*\); found 0\.0$",
            id="euler-J-zero",
        ),
        pytest.param(
            lambda: D.euler_equations_rhs(
                [[1.0, 2.0, 2.5], [1.0, -2.0, 2.5]], [0, 0, 1.0], [0, 0, 0.0]
            ),
            NonPositiveParameterError,
            r"^J_principal must be > 0 .*; found -2\.0$",
            id="euler-J-negative-batched",
        ),
        pytest.param(
            lambda: D.euler_equations_rhs([1.0, 2.0, 2.5], [0, 1.0], [0, 0, 0.0]),
            ShapeError,
            r"^omega has shape \(2,\); expected \(\.\.\., 3\)$",
            id="euler-omega-shape",
        ),
        pytest.param(
            lambda: D.euler_equations_rhs([1.0, 2.0, 2.5], [0, _NAN, 1.0], [0, 0, 0.0]),
            NonFiniteError,
            r"^omega must be finite; found .*nan.* at index \(1,\)$",
            id="euler-omega-nan",
        ),
        pytest.param(
            lambda: D.euler_equations_rhs([1.0, 2.0, 2.5], [0, 0, 1.0], [0, _NAN, 0.0]),
            NonFiniteError,
            r"^M must be finite",
            id="euler-M-nan",
        ),
        pytest.param(
            lambda: D.euler_equations_rhs([1.0, 2.0, 2.5], [1e200, 1e200, 1e200], [0, 0, 0.0]),
            _overflow_error(),
            r"^d omega/dt overflows float64",
            id="euler-overflow",
        ),
        pytest.param(
            lambda: D.angular_momentum_rigid(np.eye(3), [0, _NAN, 0]),
            NonFiniteError,
            r"^omega must be finite",
            id="L-omega-nan",
        ),
        pytest.param(
            lambda: D.angular_momentum_rigid(1e300 * np.eye(3), [1e300, 0, 0]),
            _overflow_error(),
            r"^L = J omega overflows float64",
            id="L-overflow",
        ),
        pytest.param(
            lambda: D.rotational_kinetic_energy(1e300 * np.eye(3), [1e300, 0, 0]),
            _overflow_error(),
            r"^T overflows float64",
            id="T-overflow",
        ),
        pytest.param(
            lambda: D.rotational_kinetic_energy(
                np.diag([0.0, 1.0, 1.0]), [1.0, 0, 0], allow_singular=False
            ),
            NonPhysicalInertiaError,
            r"^J is not positive definite",
            id="T-singular-refused",
        ),
        pytest.param(
            lambda: D.rotational_kinetic_energy(np.diag([1.0, 1.0, 3.0]), [1.0, 0, 0]),
            NonPhysicalInertiaError,
            r"^J breaks the triangle inequality J1 \+ J2 >= J3 about the given point",
            id="T-triangle-about-point",
        ),
        pytest.param(
            lambda: D.fixed_axis_angular_acceleration(0.0, 1.0),
            NonPositiveParameterError,
            r"^J_axis must be > 0",
            id="fixed-axis-J",
        ),
        pytest.param(
            lambda: D.fixed_axis_angular_acceleration(1.0, _NAN),
            NonFiniteError,
            r"^M_axis must be finite",
            id="fixed-axis-M",
        ),
        pytest.param(
            lambda: D.axis_reaction(1.0, _NAN, 1.0, 0.0, **_AR),
            NonFiniteError,
            r"^h must be finite",
            id="axis-h-nan",
        ),
        pytest.param(
            lambda: D.axis_reaction(0.0, 1.0, 1.0, 0.0, **_AR),
            NonPositiveParameterError,
            r"^m must be > 0; found 0\.0$",
            id="axis-m",
        ),
        pytest.param(
            lambda: D.axis_reaction(1.0, 1.0, _NAN, 0.0, **_AR),
            NonFiniteError,
            r"^phidot must be finite",
            id="axis-phidot",
        ),
        pytest.param(
            lambda: D.axis_reaction(1.0, 1.0, 1.0, _NAN, **_AR),
            NonFiniteError,
            r"^phiddot must be finite",
            id="axis-phiddot",
        ),
        pytest.param(
            lambda: D.axis_reaction(1.0, 1.0, 1.0, 0.0, F_a_rho=_NAN, F_a_phi=0.0),
            NonFiniteError,
            r"^F_a_rho must be finite",
            id="axis-F-rho",
        ),
        pytest.param(
            lambda: D.axis_reaction(1.0, 1.0, 1.0, 0.0, F_a_rho=0.0, F_a_phi=_NAN),
            NonFiniteError,
            r"^F_a_phi must be finite",
            id="axis-F-phi",
        ),
        pytest.param(
            lambda: D.bearing_reactions(np.eye(3), 0.0, [0, 0, 0.0], 1.0, 0.0, 1.0, **_BR),
            NonPositiveParameterError,
            r"^m must be > 0; found 0\.0$",
            id="bearing-m",
        ),
        pytest.param(
            lambda: D.bearing_reactions(np.eye(3), 1.0, [0, 0, 0.0], _NAN, 0.0, 1.0, **_BR),
            NonFiniteError,
            r"^phidot must be finite",
            id="bearing-phidot",
        ),
        pytest.param(
            lambda: D.bearing_reactions(np.eye(3), 1.0, [0, 0, 0.0], 1.0, _NAN, 1.0, **_BR),
            NonFiniteError,
            r"^phiddot must be finite",
            id="bearing-phiddot",
        ),
        pytest.param(
            lambda: D.bearing_reactions(np.eye(3), 1.0, [0, 0, 0.0], 1.0, 0.0, _NAN, **_BR),
            NonFiniteError,
            r"^z_A must be finite",
            id="bearing-z_A",
        ),
        pytest.param(
            lambda: D.pendulum_angular_velocity_at(_NAN, 1.0, 1.0, 9.81, 0.5, 1.0),
            NonFiniteError,
            r"^theta must be finite",
            id="velocity-theta-nan",
        ),
        pytest.param(
            lambda: D.pendulum_angular_velocity_at([0.1, 1.5], 1.0, 1.0, 9.81, 0.5, 1.0),
            OutOfDomainError,
            r"^theta = 1\.5 lies beyond the amplitude \|theta_0\| = 1\.0$",
            id="velocity-beyond-batched",
        ),
        pytest.param(
            lambda: D.pendulum_axis_reaction(_NAN, 1.0, 2.0, 9.81, 0.5, E=0.0),
            NonFiniteError,
            r"^phi must be finite",
            id="reaction-phi-nan",
        ),
        pytest.param(
            lambda: D.pendulum_axis_reaction(1.0, 1.0, 1.0, 1.0, 1.0, E=0.1),
            OutOfDomainError,
            r"^E is below the potential energy m g h \(1 - cos phi\) at phi: the pendulum does not reach phi \(first at index \(\)\)$",
            id="reaction-E",
        ),
        pytest.param(
            lambda: D.pendulum_motion(_NAN, 1.0, 1.0, 9.81, 0.5, 1.0),
            NonFiniteError,
            r"^t must be finite",
            id="motion-t-nan",
        ),
        pytest.param(
            lambda: D.reduced_length(0.0, 1.0, 0.5),
            NonPositiveParameterError,
            r"^J_axis must be > 0",
            id="reduced-J",
        ),
        pytest.param(
            lambda: D.reduced_length(1.0, 0.0, 0.5),
            NonPositiveParameterError,
            r"^m must be > 0",
            id="reduced-m",
        ),
        pytest.param(
            lambda: D.reduced_length(1.0, 1.0, 0.0),
            NonPositiveParameterError,
            r"^h must be > 0; found 0\.0$",
            id="reduced-h",
        ),
        pytest.param(
            lambda: D.angular_momentum_rigid(np.eye(3), [1.0, 0.0]),
            ShapeError,
            r"^omega has shape \(2,\); expected \(\.\.\., 3\)$",
            id="L-omega-shape",
        ),
        pytest.param(
            lambda: D.angular_momentum_rigid(np.diag([1.0, 1.0, 3.0]), [1.0, 0, 0]),
            NonPhysicalInertiaError,
            r"^J breaks the triangle inequality J1 \+ J2 >= J3 about the given point: ",
            id="L-triangle-about-point",
        ),
        pytest.param(
            lambda: D.rotational_kinetic_energy(np.eye(3), [1.0, 0.0]),
            ShapeError,
            r"^omega has shape \(2,\); expected \(\.\.\., 3\)$",
            id="T-omega-shape",
        ),
        pytest.param(
            lambda: D.rotational_kinetic_energy(np.eye(3), [0, _NAN, 0]),
            NonFiniteError,
            r"^omega must be finite; found nan at index \(1,\)$",
            id="T-omega-nan",
        ),
        pytest.param(
            lambda: D.euler_equations_rhs([1.0, 2.0, 2.5], [0, 0, 1.0], [0.0, 0.0]),
            ShapeError,
            r"^M has shape \(2,\); expected \(\.\.\., 3\)$",
            id="euler-M-shape",
        ),
        pytest.param(
            lambda: D.pendulum_axis_reaction(0.5, 1.0, 2.0, 9.81, 0.5, E=_NAN),
            NonFiniteError,
            r"^E must be finite; found nan at index \(\)$",
            id="reaction-E-nan",
        ),
        pytest.param(
            # φ = π/2 needs E ≥ m g h (1 − cos φ) = m g h = 1: E = 3/4 is refused, at index 1
            lambda: D.pendulum_axis_reaction([0.0, np.pi / 2], 1.0, 0.5, 8.0, 0.25, E=[0.0, 0.75]),
            OutOfDomainError,
            r"^E is below the potential energy m g h \(1 - cos phi\) at phi: the pendulum does "
            r"not reach phi \(first at index \(1,\)\)$",
            id="reaction-E-batched",
        ),
    ],
)
def test_dynamics_messages_name_the_argument_the_value_and_the_condition(call, error, match):
    with pytest.raises(error, match=match):
        call()


def test_principal_moment_checks_judge_each_row_of_a_batch():
    # a batch of principal moments: the triangle tolerance is relative to each row's
    # own largest moment, and totals per row
    J = np.array([[1.0, 2.0, 2.5], [1e-6, 2e-6, 3e-6 * (1 + 1e-14)], [2.0, 3.0, 4.0]])
    out = D.euler_equations_rhs(J, [0.1, 0.2, 0.3], [0.0, 0.0, 0.0])
    assert out.shape == (3, 3)
    for i in range(3):
        np.testing.assert_array_equal(
            out[i], D.euler_equations_rhs(J[i], [0.1, 0.2, 0.3], [0.0, 0.0, 0.0])
        )


#: (1/2, 1/2 − n eps, 1): J1 + J2 − J3 = −n eps exactly, whatever the order of the sums
#: (every partial sum, 1 − n eps, 3/2 − n eps, 2 − n eps, is a float: ulp 2 eps in [1, 2))
def _broken_by(n):
    return np.array([0.5, 0.5 - n * EPS, 1.0])


@pytest.mark.parametrize("scale", [1.0, 2.0**-30, 2.0**40])
def test_principal_moments_may_break_the_triangle_by_64_eps_of_the_largest_and_no_more(scale):
    """The documented tolerance of Euler's equations: J1 + J2 − J3 ≥ −64 eps · J3 is taken, at
    exactly −64 eps too, and −65 eps is refused with its value; scaled by a power of two
    (exact), the tolerance scales with the largest moment."""
    w, M = [0.3, -1.0, 0.7], [0.0, 0.0, 0.0]
    edge, beyond = _broken_by(64) * scale, _broken_by(65) * scale
    wdot = D.euler_equations_rhs(edge, w, M)
    assert np.isfinite(wdot).all()
    want = re.escape(
        f"J_principal breaks the triangle inequality: {beyond.tolist()} has "
        f"J_j + J_k - J_i = {-65 * EPS * scale:.6g} < 0 for i = 3"
    )
    with pytest.raises(NonPhysicalInertiaError, match=f"^{want}$"):
        D.euler_equations_rhs(beyond, w, M)


def test_principal_moments_tolerance_is_each_rows_own_not_the_batchs_largest():
    # row 0 breaks the triangle by 65 eps of its own largest moment 1; against row 1's
    # largest moment 4 it would be within 64 eps (256 eps of 1)
    J = np.stack([_broken_by(65), [4.0, 4.0, 4.0]])
    want = re.escape(f"{J[0].tolist()} has J_j + J_k - J_i = {-65 * EPS:.6g} < 0 for i = 3")
    with pytest.raises(NonPhysicalInertiaError, match=f"^J_principal .*: {want}$"):
        D.euler_equations_rhs(J, [0.3, -1.0, 0.7], [0.0, 0.0, 0.0])


def test_pendulum_axis_reaction_takes_an_energy_down_to_8_eps_below_the_potential():
    """The reach of (4.74): E ≥ m g h (1 − cos φ) to 8 eps.  At φ = fl(π), with m g h =
    0.5 · 8 · 0.25 = 1 exactly, 1 − cos φ = 2 sin²(φ/2) = 2 (sin(fl(π)/2) = 1 − 4e-33 rounds
    to 1): the potential is 2 and its edge 2 (1 − 8 eps) = 2 − 2**-48, a float.  There the
    pendulum rests at the top and the axis holds up its weight: R = (m g, 0) = (4, 0)."""
    m, g, h = 0.5, 8.0, 0.25
    R = D.pendulum_axis_reaction(np.pi, 1.0, m, g, h, E=2.0 * (1 - 8 * EPS))
    # R_ρ = 4 + 4 eps (E is 16 eps below 2 m g h, times 2 m h/J = 1/4); R_φ ∝ sin fl(π) ≈ 1e-16
    np.testing.assert_allclose(R, [m * g, 0.0], rtol=0, atol=16 * EPS * m * g)
    # the next float below the edge, 2 (1 − 8.5 eps) = 2 − 2**-48 − 2**-52, is refused
    with pytest.raises(OutOfDomainError, match=r"^E is below the potential energy"):
        D.pendulum_axis_reaction(np.pi, 1.0, m, g, h, E=2.0 * (1 - 8.5 * EPS))


def test_kinetic_energy_accepts_a_singular_tensor_by_default():
    assert D.rotational_kinetic_energy(np.diag([0.0, 1.0, 1.0]), [0.0, 2.0, 0.0]) == 2.0


# ------------------------------------------------- issue 16: the last known bad inputs


def test_batches_that_do_not_broadcast_raise_a_shape_error_listing_each_shape():
    with pytest.raises(ShapeError, match=r"reduced_length: .* J_axis \(2,\), m \(3,\), h \(\)$"):
        D.reduced_length([1.0, 1.0], [1.0, 1.0, 1.0], 1.0)
    with pytest.raises(ShapeError, match=r"J \(2, 3, 3\), omega \(3, 3\)"):
        D.angular_momentum_rigid(np.stack([np.eye(3)] * 2), np.ones((3, 3)))


def test_no_domain_says_batches_end_in_numpys_bare_value_error():
    """The Domain: paragraphs state what now happens (a ShapeError), not issue 16's old
    failure."""
    text = " ".join((getattr(D, n).__doc__ or "").replace("\n", " ") for n in D.__all__)
    assert "bare ValueError" not in " ".join(text.split())


#: (J_axis, m, g, h) whose m g h (or m h) underflows and whose J/(m g h) overflows on the way,
#: while every result below is representable: the powers of two 2^-600, 2^-300, 2^-800
_TINY = (3.7 * 2.0**-600, 1.3 * 2.0**-300, 9.81, 0.9 * 2.0**-800)
_UNIT = (3.7, 1.3, 9.81, 0.9)


def test_reduced_length_of_mixed_magnitudes_is_that_of_the_mantissas_times_a_power_of_two():
    J, m, _, h = _TINY
    # exact route: l = (3.7/(1.3 0.9)) 2^(-600 + 300 + 800) = l(3.7, 1.3, 0.9) 2^500, bit for bit
    assert D.reduced_length(J, m, h) == np.ldexp(D.reduced_length(3.7, 1.3, 0.9), 500)


@pytest.mark.parametrize(
    ("f", "extra", "power"),
    [
        pytest.param(D.pendulum_small_period, (), 250, id="small-period"),
        pytest.param(D.pendulum_period, (2.5,), 250, id="period"),
        pytest.param(lambda *a: D.pendulum_angular_velocity_at(0.3, *a), (2.5,), -250, id="phidot"),
    ],
)
def test_pendulum_of_mixed_magnitudes_scales_by_the_exact_power_of_two(f, extra, power):
    """J/(m g h) = (3.7/(1.3 · 9.81 · 0.9)) 2^500 exactly: periods scale by 2^250 and φ̇ by
    2^-250, bit for bit (the plain formula underflowed m g h to 0: period inf, φ̇ 0)."""
    assert f(*_TINY, *extra) == np.ldexp(f(*_UNIT, *extra), power)


def test_the_pendulums_phase_is_exact_for_mixed_magnitudes():
    # ω0 t with ω0 = ω0(unit) 2^-250 and t = t_unit 2^250: the same phase, the same angle
    t = np.array([0.1, 0.7, 2.0])
    phi = D.pendulum_motion(np.ldexp(t, 250), *_TINY, 2.5)
    np.testing.assert_array_equal(phi, D.pendulum_motion(t, *_UNIT, 2.5))


@pytest.mark.parametrize(
    ("call", "match"),
    [
        pytest.param(
            lambda: D.pendulum_small_period(1e300, 1e-300, 1e-300, 1e-300),
            r"^pendulum_small_period: the result is not finite",
            id="period-1e600",
        ),
        pytest.param(
            lambda: D.pendulum_period(1e300, 1e-300, 1e-300, 1e-300, 0.5),
            r"^pendulum_period: the result is not finite",
            id="exact-period-1e600",
        ),
        pytest.param(
            lambda: D.pendulum_angular_velocity_at(0.0, 1e-300, 1e300, 1e300, 1.0, 0.5),
            r"^pendulum_angular_velocity_at: the result is not finite",
            id="phidot-1e450",
        ),
        pytest.param(
            lambda: D.pendulum_motion(1e300, 1e-300, 1.0, 9.81, 1.0, 0.5),
            r"^pendulum_motion: the phase omega0 t = sqrt\(m g h/J_axis\) t exceeds float64's "
            r"range \(~1\.8e308\); rescale the inputs \(choose units\)$",
            id="phase-1e450",
        ),
        pytest.param(
            lambda: D.reduced_length(1e300, 1e-300, 1.0),
            r"^reduced_length: the result is not finite",
            id="reduced-length-1e600",
        ),
        pytest.param(
            lambda: D.fixed_axis_angular_acceleration(1e-300, 1e300),
            r"^fixed_axis_angular_acceleration: the result is not finite",
            id="phiddot-1e600",
        ),
        pytest.param(
            lambda: D.pendulum_axis_reaction(1e-300, 1.0, 1e300, 9.81, 1e300, E=1e300),
            r"^pendulum_axis_reaction: the result is not finite",
            id="reaction-m-h-1e300",
        ),
    ],
)
def test_a_result_beyond_float64_is_a_result_overflow_error_not_a_warning(call, match):
    with pytest.raises(_overflow_error(), match=match):
        call()


def test_moments_near_float64s_limit_are_taken_and_overflowing_products_refused():
    J = np.diag([1e308] * 3)
    np.testing.assert_array_equal(D.angular_momentum_rigid(J, [1.0, 0.5, 0]), [1e308, 5e307, 0])
    assert D.rotational_kinetic_energy(J, [1.0, 0, 0]) == 5e307
    with pytest.raises(_overflow_error(), match=r"^L = J omega overflows float64"):
        D.angular_momentum_rigid(J, [2.0, 0, 0])


def test_euler_equations_take_moments_up_to_float64s_limit_and_refuse_a_broken_triangle_by_its_size():
    """Moments near 1.7e308: the triangle check must not overflow (J1 + J2 + J3 and 2 J_i
    are beyond float64 there); a spherical top's ω̇ is M/J, and a moment 9e307 against 2 and
    2.5 breaks the triangle inequality by -9e307, not by -inf."""
    from mechanics.errors import NonPhysicalInertiaError

    big = 1.7e308
    wdot = D.euler_equations_rhs([big] * 3, [0.3, -1.0, 0.7], [0.1, 0.2, 0.3])
    np.testing.assert_array_equal(wdot, np.array([0.1, 0.2, 0.3]) / big)
    with pytest.raises(NonPhysicalInertiaError, match=r"J_principal .* = -8\.98847e\+307 < 0"):
        D.euler_equations_rhs([8.98846567431158e307, 2.0, 2.5], [0.3, -1.0, 0.7], [0.0] * 3)


# ------------------------------------- Euler's equations at any scale (the hunt, 29 Nov 2026)

#: Euler's equations with M = 0 round four times (J_k − J_j, ω_j ω_k, their product, the
#: quotient by J_i): within 4 ulps of the exact rational value, a bound with room to spare
EULER_ULPS = 4


def _euler_exact(J, w, M):
    """(M_i − (J_k − J_j) ω_j ω_k)/J_i in exact rationals, the cyclic (i, j, k) of (4.47)."""
    from fractions import Fraction

    J, w, M = ([Fraction(float(x)) for x in v] for v in (J, w, M))
    return [
        (M[i] - (J[k] - J[j]) * w[j] * w[k]) / J[i] for i, j, k in ((0, 1, 2), (1, 2, 0), (2, 0, 1))
    ]


@pytest.mark.parametrize(
    ("J", "w"),
    [
        # subnormal moments: (J3 − J2) ω2 ω3 = 0.18 · 2**-1074 rounded to 0 before the quotient,
        # so the old route gave ω̇ = (0, 0, 0) for the exact (−0.06, 0.072, −0.0257)
        pytest.param(np.array([3.0, 5.0, 7.0]) * 2.0**-1074, [0.3, 0.3, 0.3], id="subnormal"),
        # (J3 − J2) ω2 ω3 = 2**-52 · 2**1040: ω2 ω3 overflowed (ResultOverflowError) where ω̇1
        # = −2**988 is a float
        pytest.param([1.0, 1.0, 1.0 + EPS], [0.0, 2.0**520, 2.0**520], id="product-overflow"),
        # J2 = J3: 0 · inf was NaN (ResultOverflowError) for the exact ω̇ = 0
        pytest.param([1.0, 2.0, 2.0], [0.0, 1e200, 1e200], id="zero-times-inf"),
        # moments near float64's limit: (J3 − J2) ω2 ω3 = 2e317 overflowed, ω̇1 = −2e9
        pytest.param([1e308, 1.5e308, 1.7e308], [1.0, 1e5, 1e5], id="huge-moments"),
    ],
)
def test_euler_equations_are_exact_for_subnormal_and_huge_products(J, w):
    wdot = D.euler_equations_rhs(J, w, [0.0, 0.0, 0.0])
    for got, want in zip(wdot.tolist(), _euler_exact(J, w, [0.0, 0.0, 0.0]), strict=True):
        assert ulps(got, want) <= EULER_ULPS, (got, float(want))


@pytest.mark.parametrize("power", [-1000, -600, 600, 1000])
def test_euler_equations_scaled_by_a_power_of_two_give_the_same_bits(power):
    """J and M scaled together by 2**power leave ω̇ unchanged (exact scaling: M = (3, −1, 2)
    2**-35 stays exact even as a subnormal).  Before the powers of two were carried apart,
    2**-1000 made (J3 − J2) ω2 ω3 ≈ 1e-311 subnormal: ω̇ came out 371 to 464 ulps off (0.34
    to 1.01 unscaled and now at every scale)."""
    J, w, M = np.array([1.0, 2.0, 2.5]), [1e-5, -2e-5, 3e-5], np.array([3.0, -1.0, 2.0]) * 2.0**-35
    want = D.euler_equations_rhs(J, w, M)
    got = D.euler_equations_rhs(np.ldexp(J, power), w, np.ldexp(M, power))
    np.testing.assert_array_equal(got, want)
    exact = _euler_exact(J, w, M)
    assert max(ulps(g, e) for g, e in zip(want.tolist(), exact, strict=True)) <= EULER_ULPS


#: |φ̇| near the turning point against mpmath: two sines of exact or once-rounded
#: arguments, their product, 4 m g h/J_z (a few roundings) and a square root (which halves
#: the relative error): measured ≤ 0.36 eps on the cases below; 8 eps
TURNING_EPS = 8


@pytest.mark.parametrize("gap_exp", [-4, -20, -30, -45])
@pytest.mark.parametrize("theta_0", [1.0, 3.0, -2.5])
def test_pendulum_angular_velocity_near_the_turning_point_against_mpmath(theta_0, gap_exp):
    """φ = θ0 ∓ 2**gap_exp (toward the bottom): φ̇² ∝ cos φ − cos θ0, which (s0 − s)(s0 + s)
    of the rounded half-angle sines lost near θ0 (3e8 eps at a gap of 2⁻³⁰); the form
    sin((|θ0| − |φ|)/2) sin((|θ0| + |φ|)/2) keeps it, its difference exact."""
    import mpmath

    theta = math.copysign(abs(theta_0) - 2.0**gap_exp, theta_0)
    J, m, g, h = 0.3, 1.2, 9.81, 0.4
    got = float(D.pendulum_angular_velocity_at(theta, J, m, g, h, theta_0))
    with mpmath.workdps(50):
        w2 = 2 * mpmath.mpf(m) * g * h / J * (mpmath.cos(theta) - mpmath.cos(theta_0))
        exact = mpmath.sqrt(w2)
        assert float(abs(mpmath.mpf(got) / exact - 1)) <= TURNING_EPS * EPS
