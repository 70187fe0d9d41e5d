"""API, conventions and edge cases of :mod:`mechanics.kinematics`.

Reference values come from the book (Examples 2.2 and 2.3, (2.52), (2.53),
(2.69), (2.73)–(2.80), (2.95)), from hand computation, from a central finite
difference, and from exact matrix rates built here by the chain rule with
derivatives of the basic matrices (2.30) worked out by hand.
"""

from __future__ import annotations

import re
from fractions import Fraction

import numpy as np
import pytest
from numpy.testing import assert_allclose, assert_array_equal

from mechanics import kinematics as kin
from mechanics import rotation as rot
from mechanics._floats import EPS
from mechanics.errors import (
    CollinearPointsError,
    GimbalLockError,
    MechanicsValueError,
    NonFiniteError,
    NotARotationError,
    ResultOverflowError,
    ShapeError,
    ZeroAngularVelocityError,
)

from ._naming import cases, check_refusal, valid_kwargs

# ω from an exact matrix rate: entries of Ṙ Rᵀ are sums of nine products of
# numbers of size ≤ |rates|₁, each rounded once: 32 eps × the rate scale.
RATE_ATOL = 32 * EPS

# Central difference step: balances truncation h²/6 |R'''| against rounding eps/h.
FD_STEP = EPS ** (1 / 3)

# Inputs to the vectorised calls are compared with scalar calls; numpy's SIMD and
# scalar sin/cos may differ by an ulp.
VECTORISE_ATOL = 4 * EPS

RNG_SEED = 20240918


# ---------------------------------------------------------------- local helpers


def _basic(c, s, which):
    o, z = np.ones_like(c), np.zeros_like(c)
    rows = {
        # (2.30) and their derivatives d/dα, worked out by hand.
        "R1": ((o, z, z), (z, c, s), (z, -s, c)),
        "dR1": ((z, z, z), (z, -s, c), (z, -c, -s)),
        "R3": ((c, s, z), (-s, c, z), (z, z, o)),
        "dR3": ((-s, c, z), (-c, -s, z), (z, z, z)),
    }[which]
    return np.stack([np.stack(r, axis=-1) for r in rows], axis=-2)


def _euler_matrix_and_rate(angles, rates):
    """R = R3(φ) R1(θ) R3(ψ) and its exact time derivative by the product rule."""
    angles, rates = np.broadcast_arrays(np.asarray(angles, float), np.asarray(rates, float))
    (psi, theta, phi), (psid, thetad, phid) = np.moveaxis(angles, -1, 0), np.moveaxis(rates, -1, 0)
    cp, sp = np.cos(psi), np.sin(psi)
    ct, st = np.cos(theta), np.sin(theta)
    cf, sf = np.cos(phi), np.sin(phi)
    A3, dA3 = _basic(cf, sf, "R3"), _basic(cf, sf, "dR3")
    B1, dB1 = _basic(ct, st, "R1"), _basic(ct, st, "dR1")
    C3, dC3 = _basic(cp, sp, "R3"), _basic(cp, sp, "dR3")
    R = A3 @ B1 @ C3
    Rdot = (
        phid[..., None, None] * (dA3 @ B1 @ C3)
        + thetad[..., None, None] * (A3 @ dB1 @ C3)
        + psid[..., None, None] * (A3 @ B1 @ dC3)
    )
    return R, Rdot


def _book_omega_matrix(w):
    """(2.52): [[0, ω3, −ω2], [−ω3, 0, ω1], [ω2, −ω1, 0]]."""
    w1, w2, w3 = w
    return np.array([[0, w3, -w2], [-w3, 0, w1], [w2, -w1, 0]])


def _random_euler_and_rates(n, *, theta_margin=0.05, max_rate=3.0):
    rng = np.random.default_rng(RNG_SEED)
    angles = np.stack(
        [
            rng.uniform(-np.pi, np.pi, n),
            rng.uniform(theta_margin, np.pi - theta_margin, n),
            rng.uniform(-np.pi, np.pi, n),
        ],
        axis=-1,
    )
    rates = rng.uniform(-max_rate, max_rate, (n, 3))
    return angles, rates


# ------------------------------------------------ angular velocity from a matrix rate


@pytest.mark.parametrize(("psi", "psidot"), [(0.4, 2.0), (-2.5, -0.3), (np.pi, 1e-3)])
def test_example_2_2_R3_turning_has_omega_psidot_e3(psi, psidot):
    # (2.56)–(2.58): Ṙ = ψ̇ [[−sin ψ, cos ψ, 0], [−cos ψ, −sin ψ, 0], [0, 0, 0]].
    Rdot = psidot * np.array(
        [[-np.sin(psi), np.cos(psi), 0], [-np.cos(psi), -np.sin(psi), 0], [0, 0, 0]]
    )
    expected = [0.0, 0.0, psidot]
    atol = RATE_ATOL * abs(psidot)
    assert_allclose(
        kin.angular_velocity_from_matrix_rate(rot.R3(psi), Rdot), expected, atol=atol, rtol=0
    )
    assert_allclose(
        kin.angular_velocity_from_matrix_rate(rot.R3(psi), Rdot, basis="O"),
        expected,
        atol=atol,
        rtol=0,
    )


def test_angular_velocity_from_matrix_rate_agrees_with_eulers_kinematic_equations():
    angles, rates = _random_euler_and_rates(500)
    R, Rdot = _euler_matrix_and_rate(angles, rates)
    from_matrix = kin.angular_velocity_from_matrix_rate(R, Rdot)
    from_euler = kin.angular_velocity_from_euler_rates(*angles.T, *rates.T)
    scale = np.abs(rates).sum(axis=-1, keepdims=True)
    assert (np.abs(from_matrix - from_euler) <= RATE_ATOL * scale).all()


def test_eulers_kinematic_equations_are_2_69_written_out():
    # (2.69) by hand for ψ = 0.3, θ = 1.1, φ = −0.7 and rates (2, −1, 0.5).
    psi, theta, phi, psid, thetad, phid = 0.3, 1.1, -0.7, 2.0, -1.0, 0.5
    expected = [
        psid * np.sin(theta) * np.sin(phi) + thetad * np.cos(phi),
        psid * np.sin(theta) * np.cos(phi) - thetad * np.sin(phi),
        psid * np.cos(theta) + phid,
    ]
    assert_allclose(
        kin.angular_velocity_from_euler_rates(psi, theta, phi, psid, thetad, phid),
        expected,
        atol=8 * EPS,
        rtol=0,
    )


@pytest.mark.parametrize("case", range(20))
def test_angular_velocity_from_matrix_rate_agrees_with_a_central_difference(case):
    angles, rates = _random_euler_and_rates(20)
    a, w = angles[case], rates[case]

    def R(t):
        return rot.matrix_from_euler(*(a + w * t))

    Rdot_fd = (R(FD_STEP) - R(-FD_STEP)) / (2 * FD_STEP)
    # Truncation: h²/6 max|R'''| ≤ h²/6 (Σ|rates|)³ per entry; rounding:
    # a few eps / h.  Ṙ Rᵀ sums three such entries, ω reads one.
    s = np.abs(w).sum()
    atol = 3 * (FD_STEP**2 / 6 * s**3 + 4 * EPS / FD_STEP)
    R0 = R(0.0)
    w_fd = kin.angular_velocity_from_matrix_rate(R0, Rdot_fd)
    assert_allclose(w_fd, kin.angular_velocity_from_euler_rates(*a, *w), atol=atol, rtol=0)
    w_fd_O = kin.angular_velocity_from_matrix_rate(R0, Rdot_fd, basis="O")
    assert_allclose(w_fd_O, R0.T @ w_fd, atol=atol, rtol=0)


def test_angular_velocity_matrix_has_the_layout_of_2_52():
    angles, rates = _random_euler_and_rates(50)
    R, Rdot = _euler_matrix_and_rate(angles, rates)
    w = kin.angular_velocity_from_matrix_rate(R, Rdot)
    for i in range(len(w)):
        scale = np.abs(rates[i]).sum()
        assert_allclose(Rdot[i] @ R[i].T, _book_omega_matrix(w[i]), atol=RATE_ATOL * scale, rtol=0)


def test_basis_O_gives_the_omega_whose_cross_product_moves_the_body_basis_2_53():
    # d/dt e^A_i = ω × e^A_i: row i of Ṙ equals w_O × (row i of R), all in O components.
    angles, rates = _random_euler_and_rates(200)
    R, Rdot = _euler_matrix_and_rate(angles, rates)
    w_O = kin.angular_velocity_from_matrix_rate(R, Rdot, basis="O")
    moved = np.cross(w_O[:, None, :], R)
    scale = np.abs(rates).sum(axis=-1)[:, None, None]
    assert (np.abs(moved - Rdot) <= RATE_ATOL * scale).all()
    # and the two bases are related by (2.20)
    w_A = kin.angular_velocity_from_matrix_rate(R, Rdot)
    assert (np.abs(rot.components_A_from_O(R, w_O) - w_A) <= RATE_ATOL * scale[..., 0]).all()


def test_a_matrix_rate_whose_product_overflows_still_gives_an_omega_that_fits():
    # Ṙ = c 1 1ᵀ with R = R3(π/4): Ṙ Rᵀ = c 1 (R 1)ᵀ has rows c (√2, 0, 1), and √2 c is
    # beyond float64 for c = 1.7e308, but ω = (c/2, (√2 − 1) c/2, −√2 c/2) (2.52) fits.
    # Entries of Ṙ Rᵀ are sums of three products each rounded once: RATE_ATOL × c.
    c = 1.7e308
    R = rot.R3(np.pi / 4)
    expected = np.array([0.5, (np.sqrt(2) - 1) / 2, -np.sqrt(2) / 2]) * c
    w_A = kin.angular_velocity_from_matrix_rate(R, np.full((3, 3), c))
    assert_allclose(w_A, expected, atol=RATE_ATOL * c, rtol=0)
    # ω in O, Rᵀ ω_A: the same vector, |ω_O| = |ω_A|
    w_O = kin.angular_velocity_from_matrix_rate(R, np.full((3, 3), c), basis="O")
    assert_allclose(w_O, R.T @ (expected / c) * c, atol=RATE_ATOL * c, rtol=0)


def test_an_omega_beyond_float64_names_the_arguments_of_its_own_row():
    # Row 1: R = R3(π/4) (rows (s, s, 0), (−s, s, 0), e3 with s = √½) and Ṙ rows c (−1, 1, 0),
    # c (−1, −1, 0): Ω_01 = √2 c, Ω_10 = −√2 c, so ω3 = √2 c = 2.4e308 is beyond float64.
    c = 1.7e308
    R = rot.R3(np.pi / 4)
    Rdot = np.array([np.zeros((3, 3)), [[-c, c, 0.0], [-c, -c, 0.0], [0.0, 0.0, 0.0]]])
    with pytest.raises(ResultOverflowError) as info:
        kin.angular_velocity_from_matrix_rate(R, Rdot)
    msg = str(info.value)
    assert msg.startswith(
        f"the angular velocity of R_A_O = {R.tolist()}, Rdot_A_O = {Rdot[1].tolist()} "
        "(index (1,)) is beyond float64: a component of omega in basis 'A' exceeds 1.8e308"
    ), msg
    assert "vector_from_omega_matrix" not in msg


def test_an_unknown_basis_raises_a_mechanics_error_naming_it():
    # The package promises a specific MechanicsValueError subclass for every bad
    # input (errors.py, ARCHITECTURE.md).  A bare ValueError escapes
    # ``except MechanicsValueError``.
    with pytest.raises(MechanicsValueError, match="basis must be 'A' or 'O'; got 'X'"):
        kin.angular_velocity_from_matrix_rate(np.eye(3), np.zeros((3, 3)), basis="X")


def test_angular_velocity_from_matrix_rate_validates_its_inputs():
    with pytest.raises(NotARotationError, match=r"R_A_O is not a rotation: .*reflection"):
        kin.angular_velocity_from_matrix_rate(np.diag([1.0, 1, -1]), np.zeros((3, 3)))
    with pytest.raises(ShapeError, match=r"Rdot_A_O has shape \(3,\)"):
        kin.angular_velocity_from_matrix_rate(np.eye(3), np.zeros(3))
    Rdot = np.zeros((3, 3))
    Rdot[1, 2] = np.nan
    with pytest.raises(
        NonFiniteError, match=r"Rdot_A_O must be finite; found .*nan.* at index \(1, 2\)"
    ):
        kin.angular_velocity_from_matrix_rate(np.eye(3), Rdot)


# ----------------------------------------------------------------- Ω and ω (2.52)


def test_omega_matrix_from_vector_has_the_layout_of_2_52_and_inverts():
    w = np.array([1.5, -2.0, 0.25])
    assert_array_equal(kin.omega_matrix_from_vector(w), _book_omega_matrix(w))
    assert_array_equal(kin.vector_from_omega_matrix(_book_omega_matrix(w)), w)


def test_vector_from_omega_matrix_ignores_a_symmetric_part():
    S = np.array([[1.0, 2, 3], [2, 4, 5], [3, 5, 6]])
    w = np.array([0.5, -1.0, 2.0])
    assert_allclose(
        kin.vector_from_omega_matrix(_book_omega_matrix(w) + S), w, atol=4 * EPS, rtol=0
    )


def test_vector_from_omega_matrix_halves_first_where_the_difference_overflows():
    # Ω_01 − Ω_10 = 3e308 is beyond float64, its half ω3 = 1.5e308 is not: halving each
    # entry first is exact at this size (no bit below 2**−1022 is lost), so ω3 is exact.
    big = 1.5e308
    Omega = np.array([[0.0, big, 0.0], [-big, 0.0, 0.0], [0.0, 0.0, 0.0]])
    assert_array_equal(kin.vector_from_omega_matrix(Omega), [0.0, 0.0, big])
    # the largest float on both sides: ω3 = max, exactly
    top = np.finfo(np.float64).max
    assert_array_equal(
        kin.vector_from_omega_matrix([[0.0, top, 0.0], [-top, 0.0, 0.0], [0.0, 0.0, 0.0]]),
        [0.0, 0.0, top],
    )


def test_vector_from_omega_matrix_keeps_the_last_bit_of_a_subnormal_result():
    # Ω_01 − Ω_10 = 3·2**−1074 is exact and its half 1.5·2**−1074 rounds (to even) to
    # 2·2**−1074; halving each entry first would give 2**−1074 − 0 (−2**−1075 rounds to 0),
    # a bit short.  Rows whose difference does not overflow take it first, then halve.
    tiny = 2.0**-1074
    Omega = np.array([[0.0, 2 * tiny, 0.0], [-tiny, 0.0, 0.0], [0.0, 0.0, 0.0]])
    assert_array_equal(kin.vector_from_omega_matrix(Omega), [0.0, 0.0, 1.5 * tiny])
    # one overflowing row next to a subnormal one: each row takes its own path
    rows = np.stack([Omega, np.array([[0.0, 1e308, 0], [-1e308, 0, 0], [0, 0, 0]])])
    assert_array_equal(
        kin.vector_from_omega_matrix(rows), [[0.0, 0.0, 1.5 * tiny], [0.0, 0.0, 1e308]]
    )


def test_omega_matrix_is_minus_the_usual_hat_matrix():
    # Ω r = −ω × r = r × ω, because the book's matrices act on bases.
    w, r = np.array([0.3, -1.0, 2.0]), np.array([1.0, 2.0, -0.5])
    assert_allclose(kin.omega_matrix_from_vector(w) @ r, np.cross(r, w), atol=4 * EPS, rtol=0)


# ---------------------------------------------------- Euler rates from ω, gimbal lock


def test_euler_rates_from_angular_velocity_inverts_the_kinematic_equations():
    angles, rates = _random_euler_and_rates(500, theta_margin=0.1)
    w = kin.angular_velocity_from_euler_rates(*angles.T, *rates.T)
    back = kin.euler_rates_from_angular_velocity(angles[:, 1], angles[:, 2], w)
    # Dividing by sin θ ≥ sin 0.1 amplifies the rounding of w by at most 1/sin 0.1 ≈ 10.
    scale = np.abs(rates).sum(axis=-1, keepdims=True) / np.sin(0.1)
    assert (np.abs(back - rates) <= 16 * EPS * scale).all()


def test_euler_rates_close_to_gimbal_lock_are_large_but_finite():
    theta = 1e-10
    w = kin.angular_velocity_from_euler_rates(0.0, theta, 0.3, 1.0, 0.0, 0.0)
    rates = kin.euler_rates_from_angular_velocity(theta, 0.3, w)
    assert np.isfinite(rates).all()
    # ψ̇ = (w1 sin φ + w2 cos φ)/sin θ; here w1, w2 are O(1e-10) but carry their
    # ψ̇ sin θ factor with relative accuracy, so ψ̇ comes back to a few roundings.
    assert_allclose(rates[0], 1.0, rtol=8 * EPS)


@pytest.mark.parametrize(
    ("theta", "shown"),
    [
        (0.0, "0.0"),
        (np.pi, "3.141592653589793"),
        (-np.pi, "-3.141592653589793"),
        (2 * np.pi, "6.283185307179586"),
    ],
)
def test_gimbal_lock_raises_naming_theta(theta, shown):
    with pytest.raises(
        GimbalLockError,
        match=rf"^theta = {re.escape(shown)} gives \|sin\(theta\)\| <= .*gimbal lock",
    ):
        kin.euler_rates_from_angular_velocity(theta, 0.2, [1.0, 2.0, 3.0])


def test_gimbal_lock_in_a_batch_names_the_first_locked_theta():
    with pytest.raises(GimbalLockError, match=r"^theta = 3\.14159"):
        kin.euler_rates_from_angular_velocity([0.5, 1.0, np.pi], 0.2, [1.0, 2.0, 3.0])


# -------------------------------------------------------- connection formula (2.73)


def test_point_velocity_of_a_turning_wheel_by_hand():
    # ω = 2 e3 about A at rest: the point e1 moves with 2 e2, the point e2 with −2 e1.
    assert_array_equal(kin.point_velocity([0, 0, 0], [0, 0, 2.0], [1.0, 0, 0]), [0, 2.0, 0])
    assert_array_equal(kin.point_velocity([0, 0, 0], [0, 0, 2.0], [0, 1.0, 0]), [-2.0, 0, 0])
    assert_array_equal(kin.point_velocity([1.0, 0, 0], [0, 0, 2.0], [0, 1.0, 0]), [-1.0, 0, 0])


def test_point_velocity_is_the_connection_formula_2_74():
    # v_B = v_A + BA × ω with BA = −AB, on Example 2.3's points.
    v1, omega = np.array([1.0, 1, -3]), np.array([1.0, 0, -1])
    r1, r2, r3 = np.array([0.0, 0, 1]), np.array([0.0, 2, 0]), np.array([1.0, 0, 1])
    assert_array_equal(kin.point_velocity(v1, omega, r2 - r1), [3.0, 2, -1])
    assert_array_equal(kin.point_velocity(v1, omega, r3 - r1), [1.0, 0, -3])
    assert_array_equal(kin.point_velocity(v1, omega, r2 - r1), v1 + np.cross(r1 - r2, omega))


def test_point_velocity_broadcasts():
    rng = np.random.default_rng(RNG_SEED)
    r_AB = rng.normal(size=(4, 5, 3))
    v = kin.point_velocity([1.0, 0, 0], [0, 0, 1.0], r_AB)
    assert v.shape == (4, 5, 3)
    assert_allclose(v[2, 3], [1 - r_AB[2, 3, 1], r_AB[2, 3, 0], 0.0], atol=2 * EPS, rtol=0)


# ------------------------------------------------- instantaneous axis (2.77)–(2.80)


def test_instantaneous_axis_of_example_2_3():
    # (2.93): v_C = 2√2 v along e_ω = (1, 0, −1)/√2.
    # (2.92) as printed, P1C = (1, 0, 1)ℓ/2 and C = (1, 0, 2)ℓ, is an arithmetic
    # slip: (1, 0, −1) × (1, 1, −3) = (1, 2, 1), so P1C = (1, 2, 1)ℓ/2 and
    # C = (1/2, 1, 3/2)ℓ.  Checked below: the printed point does not move along ω.
    omega, v1 = np.array([1.0, 0, -1]), np.array([1.0, 1, -3])
    r_AC, v_C = kin.instantaneous_axis(v1, omega)
    assert_allclose(r_AC, [0.5, 1.0, 0.5], atol=2 * EPS, rtol=0)
    assert_allclose(v_C, [2.0, 0, -2.0], atol=4 * EPS, rtol=0)
    assert_allclose(np.linalg.norm(v_C), 2 * np.sqrt(2), rtol=4 * EPS)
    assert_allclose(np.array([0.0, 0, 1]) + r_AC, [0.5, 1.0, 1.5], atol=2 * EPS, rtol=0)
    # the corrected C moves along ω; the printed one does not
    assert_array_equal(np.cross(kin.point_velocity(v1, omega, [0.5, 1.0, 0.5]), omega), [0, 0, 0])
    printed = kin.point_velocity(v1, omega, [0.5, 0.0, 0.5])
    assert np.linalg.norm(np.cross(printed, omega)) > 1.0


def test_instantaneous_axis_velocity_is_parallel_to_omega_and_that_of_the_point_C():
    rng = np.random.default_rng(RNG_SEED + 1)
    v_A = rng.normal(size=(300, 3))
    omega = rng.normal(size=(300, 3))
    r_AC, v_C = kin.instantaneous_axis(v_A, omega)
    scale = (np.linalg.norm(v_A, axis=-1) * np.linalg.norm(omega, axis=-1))[:, None]
    # v_C ∥ ω (2.80)
    assert (np.abs(np.cross(v_C, omega)) <= 16 * EPS * scale).all()
    # v_C is the velocity of the body point at C: v_A + ω × AC (2.73)
    assert_allclose(v_C, kin.point_velocity(v_A, omega, r_AC), atol=16 * EPS * scale.max(), rtol=0)
    # C lies in the plane through A normal to ω
    assert (
        np.abs(np.einsum("...i,...i", r_AC, omega)) <= 16 * EPS * np.linalg.norm(v_A, axis=-1)
    ).all()


def test_instantaneous_axis_of_a_pure_rotation_passes_through_the_fixed_point():
    # Rotation about the line through (0, 2, 0) parallel to e3: v_A at the origin
    # is ω × (A − P) = 3 e3 × (0, −2, 0) = (6, 0, 0).
    r_AC, v_C = kin.instantaneous_axis([6.0, 0, 0], [0, 0, 3.0])
    assert_allclose(r_AC, [0, 2.0, 0], atol=2 * EPS, rtol=0)
    assert_array_equal(v_C, [0.0, 0.0, 0.0])


def test_instantaneous_axis_of_a_translation_raises():
    with pytest.raises(
        ZeroAngularVelocityError, match=re.escape("omega = [0.0, 0.0, 0.0] is zero")
    ):
        kin.instantaneous_axis([1.0, 0, 0], [0.0, 0, 0])
    with pytest.raises(ZeroAngularVelocityError, match="no instantaneous axis"):
        kin.instantaneous_axis([1.0, 0, 0], [[0.0, 0, 1], [0.0, 0, 0]])


def test_instantaneous_axis_of_a_very_fast_spin_keeps_the_axial_velocity():
    # v_A ∥ ω, so by (2.80) v_C = v_A and C = A.  Found: ω² overflows to inf and
    # v_C = (v·ω/ω²) ω comes back as 0 with no error.
    r_AC, v_C = kin.instantaneous_axis([0.0, 0, 1.0], [0.0, 0, 1e200])
    assert_array_equal(r_AC, [0.0, 0.0, 0.0])
    assert_allclose(v_C, [0.0, 0.0, 1.0], rtol=4 * EPS, atol=0)


@pytest.mark.parametrize("w", [1e-160, 1e-200])
def test_instantaneous_axis_of_a_very_slow_spin_is_far_but_representable(w):
    # (2.77): AC = (ω × v_A)/ω² = (w e3 × e1)/w² = e2 / w, representable for these w.
    # Found: ω² underflows (to a subnormal, or to 0, which raises "omega is zero").
    r_AC, v_C = kin.instantaneous_axis([1.0, 0, 0], [0.0, 0, w])
    assert_allclose(r_AC, [0.0, 1.0 / w, 0.0], rtol=4 * EPS, atol=0)
    assert_array_equal(v_C, [0.0, 0.0, 0.0])


# ----------------------------------------------------------- plane motion (2.95)


def test_instantaneous_centre_of_a_rolling_wheel_is_the_contact_point():
    # Wheel of radius 2 centred at (5, 2) rolling to +x with speed 3: ω_z = −3/2.
    assert_allclose(
        kin.instantaneous_centre_plane([5.0, 2.0], [3.0, 0.0], -1.5),
        [5.0, 0.0],
        atol=4 * EPS,
        rtol=0,
    )


def test_instantaneous_centre_has_zero_velocity():
    rng = np.random.default_rng(RNG_SEED + 2)
    r_A = rng.normal(size=(200, 2))
    v_A = rng.normal(size=(200, 2))
    w = rng.uniform(0.2, 3.0, 200) * rng.choice([-1.0, 1.0], 200)
    r_C = kin.instantaneous_centre_plane(r_A, v_A, w)
    AC = np.concatenate([r_C - r_A, np.zeros((200, 1))], axis=-1)
    v3 = np.concatenate([v_A, np.zeros((200, 1))], axis=-1)
    omega = np.stack([np.zeros(200), np.zeros(200), w], axis=-1)
    v_C = kin.point_velocity(v3, omega, AC)
    assert (np.abs(v_C) <= 16 * EPS * np.linalg.norm(v_A, axis=-1, keepdims=True)).all()
    # (2.96): v_A = AC × ω
    assert_allclose(np.cross(AC, omega), v3, atol=16 * EPS * np.abs(v3).max(), rtol=0)


def test_instantaneous_centre_plane_validates_its_inputs():
    with pytest.raises(ZeroAngularVelocityError, match="omega_z = 0"):
        kin.instantaneous_centre_plane([0.0, 0], [1.0, 0], 0.0)
    with pytest.raises(ZeroAngularVelocityError, match="omega_z = 0"):
        kin.instantaneous_centre_plane([0.0, 0], [1.0, 0], [1.0, 0.0])
    with pytest.raises(ShapeError, match=r"r_A has shape \(3,\); expected \(\.\.\., 2\)"):
        kin.instantaneous_centre_plane([0.0, 0, 0], [1.0, 0], 1.0)
    with pytest.raises(NonFiniteError, match=r"omega_z must be finite"):
        kin.instantaneous_centre_plane([0.0, 0], [1.0, 0], np.inf)


# ---------------------------------------------------- rigid velocity from points


EXAMPLE_2_3_R = np.array([[0.0, 0, 1], [0, 2, 0], [1, 0, 1]])
EXAMPLE_2_3_V = np.array([[1.0, 1, -3], [3, 2, -1], [1, 0, -3]])


@pytest.mark.parametrize(("ell", "v"), [(1.0, 1.0), (2.0, 3.0), (0.5, -4.0)])
def test_rigid_velocity_of_example_2_3(ell, v):
    # (2.89): ω = (1, 0, −1) v/ℓ.  Centroid (1, 2, 2)ℓ/3 moves with the mean
    # velocity (5/3, 1, −7/3) v (by hand: v1 + ω × (c − r1)).
    omega, v_c, residual = kin.rigid_velocity_from_points(ell * EXAMPLE_2_3_R, v * EXAMPLE_2_3_V)
    assert_allclose(omega, np.array([1.0, 0, -1]) * v / ell, atol=32 * EPS * abs(v / ell), rtol=0)
    assert_allclose(v_c, np.array([5 / 3, 1, -7 / 3]) * v, atol=8 * EPS * abs(v), rtol=0)
    assert residual <= 32 * EPS * abs(v)


def test_random_rigid_motions_are_recovered():
    rng = np.random.default_rng(RNG_SEED + 3)
    n_cases, n_points = 50, 7
    r = rng.normal(size=(n_cases, n_points, 3))
    omega = rng.normal(size=(n_cases, 3))
    P = rng.normal(size=(n_cases, 3))
    v_P = rng.normal(size=(n_cases, 3))
    v = v_P[:, None, :] + np.cross(omega[:, None, :], r - P[:, None, :])
    w_fit, v_c, residual = kin.rigid_velocity_from_points(r, v)
    c = r.mean(axis=-2)
    # A few hundred eps: the spread matrix of 7 random points has condition ≲ 100.
    atol = 1024 * EPS * (1 + np.abs(v).max())
    assert_allclose(w_fit, omega, atol=atol, rtol=0)
    assert_allclose(v_c, v_P + np.cross(omega, c - P), atol=atol, rtol=0)
    assert (residual <= atol).all()


def test_rigidity_residual_is_large_for_a_uniform_expansion():
    # v_i = r_i is not rigid: the best rigid fit is ω = 0, v_c = c, and the
    # residual is max |r_i − c| = |(−1, 4, −2)/3| = √21/3 for Example 2.3's points.
    omega, v_c, residual = kin.rigid_velocity_from_points(EXAMPLE_2_3_R, EXAMPLE_2_3_R)
    assert_allclose(omega, 0.0, atol=8 * EPS, rtol=0)
    assert_allclose(v_c, [1 / 3, 2 / 3, 2 / 3], atol=2 * EPS, rtol=0)
    assert_allclose(residual, np.sqrt(21) / 3, rtol=8 * EPS)


def test_rigid_velocity_from_points_broadcasts_over_leading_axes():
    r = np.broadcast_to(EXAMPLE_2_3_R, (2, 4, 3, 3))
    v = np.broadcast_to(EXAMPLE_2_3_V, (2, 4, 3, 3))
    omega, v_c, residual = kin.rigid_velocity_from_points(r, v)
    assert omega.shape == (2, 4, 3)
    assert v_c.shape == (2, 4, 3)
    assert residual.shape == (2, 4)
    assert_allclose(omega, np.broadcast_to([1.0, 0, -1], (2, 4, 3)), atol=32 * EPS, rtol=0)


def test_nearly_collinear_points_are_still_accepted():
    r = np.array([[0.0, 0, 0], [1, 0, 0], [2, 1e-3, 0]])
    omega = np.array([0.2, -0.5, 1.0])
    v = np.cross(omega, r)
    w_fit, _, _ = kin.rigid_velocity_from_points(r, v)
    # conditioned like 1/(1e-3)² = 1e6: relative 1e6 eps
    assert_allclose(w_fit, omega, atol=1e6 * 16 * EPS, rtol=0)


@pytest.mark.parametrize(
    ("r", "match"),
    [
        pytest.param(
            [[0.0, 0, 0], [1, 1, 1], [2, 2, 2]],
            r"the points r are collinear .*spread matrix",
            id="line",
        ),
        pytest.param(
            [[1.0, 2, 3]] * 4, r"the points r are collinear \(or coincide\)", id="coincide"
        ),
        pytest.param(
            [[0.0, 0, 0], [1, 1, 1]],
            r"^2 point\(s\) given; at least 3 non-collinear points are needed",
            id="two",
        ),
        pytest.param([[0.0, 0, 0]], r"^1 point\(s\) given", id="one"),
    ],
)
def test_too_few_or_collinear_points_raise(r, match):
    with pytest.raises(CollinearPointsError, match=match):
        kin.rigid_velocity_from_points(r, np.zeros_like(r, dtype=float))


def test_rigid_velocity_from_points_names_mismatched_shapes():
    with pytest.raises(
        ShapeError,
        match=re.escape("r and v must both have shape (..., N, 3); got (3, 3) and (4, 3)"),
    ):
        kin.rigid_velocity_from_points(EXAMPLE_2_3_R, np.zeros((4, 3)))
    with pytest.raises(ShapeError, match=r"got \(3,\) and \(3,\)"):
        kin.rigid_velocity_from_points([0.0, 0, 0], [0.0, 0, 0])
    with pytest.raises(ShapeError, match=r"^v has shape \(3, 2\)"):
        kin.rigid_velocity_from_points(EXAMPLE_2_3_R, np.zeros((3, 2)))
    r = EXAMPLE_2_3_R.copy()
    r[1, 2] = np.nan
    with pytest.raises(NonFiniteError, match=r"^r must be finite; found .*nan.* at index \(1, 2\)"):
        kin.rigid_velocity_from_points(r, EXAMPLE_2_3_V)


@pytest.mark.parametrize("scale", [1e-170, 1e160])
def test_rigid_velocity_from_points_is_scale_invariant(scale):
    # Scaling positions and velocities by the same factor leaves ω unchanged;
    # both scaled inputs are ordinary finite floats.  Found: the spread matrix
    # Σ|d|² underflows to 0 at 1e-170 (a false CollinearPointsError) and
    # overflows at 1e160 (RuntimeWarning, then numpy LinAlgError).
    omega, _, _ = kin.rigid_velocity_from_points(scale * EXAMPLE_2_3_R, scale * EXAMPLE_2_3_V)
    assert_allclose(omega, [1.0, 0, -1], atol=32 * EPS, rtol=0)


# ------------------------------------------------------------------ vectorisation


@pytest.mark.parametrize("shape", [(), (5,), (2, 3)])
def test_kinematics_functions_vectorise_over_leading_axes(shape):
    n = int(np.prod(shape, dtype=int))
    angles, rates = _random_euler_and_rates(n)
    angles, rates = angles.reshape(*shape, 3), rates.reshape(*shape, 3)
    R, Rdot = _euler_matrix_and_rate(angles, rates)
    w_A = kin.angular_velocity_from_matrix_rate(R, Rdot)
    w_O = kin.angular_velocity_from_matrix_rate(R, Rdot, basis="O")
    w_E = kin.angular_velocity_from_euler_rates(
        *np.moveaxis(angles, -1, 0), *np.moveaxis(rates, -1, 0)
    )
    back = kin.euler_rates_from_angular_velocity(angles[..., 1], angles[..., 2], w_E)
    v = kin.point_velocity(rates, w_A, angles)
    r_AC, v_C = kin.instantaneous_axis(rates, w_A)
    centre = kin.instantaneous_centre_plane(angles[..., :2], rates[..., :2], rates[..., 0] + 10)
    for out in (w_A, w_O, w_E, back, v, r_AC, v_C):
        assert out.shape == (*shape, 3)
    assert centre.shape == (*shape, 2)
    assert kin.omega_matrix_from_vector(w_A).shape == (*shape, 3, 3)
    assert kin.vector_from_omega_matrix(kin.omega_matrix_from_vector(w_A)).shape == (*shape, 3)
    for idx in np.ndindex(*shape):
        assert_allclose(
            w_A[idx],
            kin.angular_velocity_from_matrix_rate(R[idx], Rdot[idx]),
            atol=VECTORISE_ATOL * 10,
            rtol=0,
        )
        assert_allclose(
            w_E[idx],
            kin.angular_velocity_from_euler_rates(*angles[idx], *rates[idx]),
            atol=VECTORISE_ATOL * 10,
            rtol=0,
        )


def test_euler_rate_inputs_broadcast():
    w = kin.angular_velocity_from_euler_rates(np.zeros(4), 0.5, [[0.1], [0.2]], 1.0, 0.0, 0.0)
    assert w.shape == (2, 4, 3)
    rates = kin.euler_rates_from_angular_velocity(0.5, np.zeros(4), [0.0, 0.0, 1.0])
    assert rates.shape == (4, 3)


# ---------------------------------------------------------------------- bad input

BAD_INPUT = [
    pytest.param(
        kin.omega_matrix_from_vector,
        ([1.0, 2.0],),
        ShapeError,
        r"^w_A has shape \(2,\)",
        id="omega-matrix-shape",
    ),
    pytest.param(
        kin.vector_from_omega_matrix,
        (np.zeros((3, 3)) * 1j,),
        ShapeError,
        r"^Omega is complex",
        id="omega-vector-complex",
    ),
    pytest.param(
        kin.angular_velocity_from_euler_rates,
        (0, 0, 0, np.nan, 0, 0),
        NonFiniteError,
        r"^psidot must be finite",
        id="euler-rates-nan",
    ),
    pytest.param(
        kin.angular_velocity_from_euler_rates,
        (0, 0, 0, 0, "x", 0),
        ShapeError,
        r"^thetadot has dtype",
        id="euler-rates-str",
    ),
    pytest.param(
        kin.euler_rates_from_angular_velocity,
        (0.5, 0.1, [1.0, 2.0]),
        ShapeError,
        r"^w_A has shape \(2,\)",
        id="inverse-shape",
    ),
    pytest.param(
        kin.euler_rates_from_angular_velocity,
        (np.inf, 0.1, [1.0, 2.0, 3.0]),
        NonFiniteError,
        r"^theta must be finite",
        id="inverse-inf",
    ),
    pytest.param(
        kin.point_velocity,
        ([0.0, 0, 0], [0.0, 0, 1], [1.0, 0]),
        ShapeError,
        r"^r_AB has shape \(2,\)",
        id="point-shape",
    ),
    pytest.param(
        kin.point_velocity,
        ([0.0, 0, np.nan], [0.0, 0, 1], [1.0, 0, 0]),
        NonFiniteError,
        r"^v_A must be finite",
        id="point-nan",
    ),
    pytest.param(
        kin.point_velocity,
        ([0.0, 0, 0], np.array([0, 0, 1], dtype=object), [1.0, 0, 0]),
        ShapeError,
        r"^omega has dtype object",
        id="point-object",
    ),
    pytest.param(
        kin.instantaneous_axis,
        ([0.0, 0, 0], [0.0, 1]),
        ShapeError,
        r"^omega has shape \(2,\)",
        id="axis-shape",
    ),
    pytest.param(
        kin.instantaneous_axis,
        ([np.inf, 0, 0], [0.0, 0, 1]),
        NonFiniteError,
        r"^v_A must be finite",
        id="axis-inf",
    ),
]


@pytest.mark.parametrize(("func", "args", "error", "match"), BAD_INPUT)
def test_bad_input_raises_the_specific_error_naming_the_condition(func, args, error, match):
    with pytest.raises(error, match=match) as info:
        func(*args)
    assert isinstance(info.value, MechanicsValueError)


def test_instantaneous_centre_plane_avoids_intermediate_overflow():
    # x_C = x_A - ydot_A/ω = 1.5e308 - 2e308 = -5e307: representable although
    # ydot_A/ω alone is not.
    assert_allclose(
        kin.instantaneous_centre_plane([1.5e308, 0.0], [0.0, 1e308], 0.5),
        [-5e307, 0.0],
        rtol=4 * EPS,
        atol=0,
    )


def test_instantaneous_centre_plane_beyond_float64_raises_naming_the_inputs():
    # y_C = xdot_A/ω = 1e500: not representable, so an error, never inf.
    with pytest.raises(ResultOverflowError, match="1e-200"):
        kin.instantaneous_centre_plane([0.0, 0.0], [1e300, 0.0], 1e-200)


# ------------------------------------------- every parameter named, every overflow named
#: the condition an unphysical value of each fuzz entry violates (tests.fuzz.entries)
_CONDITIONS = {
    ("angular_velocity_from_matrix_rate", "R_A_O"): (
        r"is not a rotation: max \|R R\^T - 1\| = 3 exceeds atol"
    ),
    ("euler_rates_from_angular_velocity", "theta"): (
        r"theta = (0\.0|3\.14159\d*) gives \|sin\(theta\)\| <= .*: Euler-angle rates are "
        r"undefined at gimbal lock"
    ),
    ("instantaneous_axis", "omega"): (
        r"omega = \[0\.0, 0\.0, 0\.0\] is zero: a translating body has no instantaneous axis"
    ),
    ("instantaneous_centre_plane", "omega_z"): (
        r"omega_z = 0: a translating body has no instantaneous centre"
    ),
    ("rigid_velocity_from_points", "r"): r"the points r are collinear \(or coincide\)",
}


@pytest.mark.parametrize(
    ("fname", "param", "value", "error", "condition"), list(cases("kinematics", _CONDITIONS))
)
def test_every_parameter_of_every_function_is_named_with_the_condition_it_breaks(
    fname, param, value, error, condition
):
    kw = valid_kwargs("kinematics", fname) | {param: value}
    check_refusal(getattr(kin, fname), kw, param, error, condition)


def test_an_instantaneous_axis_beyond_float64_names_the_inputs_of_its_own_row():
    # row 1 of the batch: |AC| = |v_A|/|omega| = 1e300/1e-300 is beyond float64; row 0 is fine
    v = [[1.0, 0.0, 0.0], [0.0, 1e300, 0.0]]
    w = [[0.0, 0.0, 1.0], [0.0, 0.0, 1e-300]]
    with pytest.raises(ResultOverflowError) as info:
        kin.instantaneous_axis(v, w)
    msg = str(info.value)
    assert msg.startswith(
        "the instantaneous axis of v_A = [0.0, 1e+300, 0.0], omega = [0.0, 0.0, 1e-300] "
        "(index (1,)) is beyond float64"
    ), msg


def test_an_instantaneous_centre_beyond_float64_names_the_inputs_of_its_own_row():
    # row 1: y_C = xdot_A/omega = 1e300/1e-200 is beyond float64
    with pytest.raises(ResultOverflowError) as info:
        kin.instantaneous_centre_plane(
            [[0.0, 0.0], [1.0, 2.0]], [[1.0, 0.0], [1e300, 0.0]], [2.0, 1e-200]
        )
    msg = str(info.value)
    assert msg.startswith(
        "the instantaneous centre of r_A = [1.0, 2.0], v_A = [1e+300, 0.0], omega_z = 1e-200 "
        "(index (1,)) is beyond float64"
    ), msg


# --------------------------------------------- guards at their edges, rows of a batch

#: 2**−1074, the smallest subnormal: offsets of this size are exact only if never halved.
TINY = 2.0**-1074


def test_gimbal_lock_is_refused_at_sin_theta_equal_to_the_tolerance_and_not_beyond():
    # GIMBAL_LOCK_ATOL = 4 eps = 2**-50.  sin(2**-50) = 2**-50 − 2**-150/6 + ..., and the
    # float below 2**-50 is 2**-50 − 2**-103, so sin rounds to 2**-50 exactly (mpmath:
    # sin(2**-50) − 2**-50 = −1.17e-46): |sin θ| <= atol holds with equality.
    edge = 4 * EPS
    assert kin.GIMBAL_LOCK_ATOL == edge == 2.0**-50
    for theta in (edge, -edge):
        with pytest.raises(GimbalLockError, match=rf"^theta = {re.escape(repr(theta))} gives"):
            kin.euler_rates_from_angular_velocity(theta, 0.0, [0.0, 1.0, 0.0])
    # One float above, sin θ = θ again (θ³/6 is 1e-31 of θ, far below half an ulp): accepted,
    # and ψ̇ = (w1 sin φ + w2 cos φ)/sin θ = 1/θ for w = e2, φ = 0 (2.69 inverted).
    above = np.nextafter(edge, 1.0)
    rates = kin.euler_rates_from_angular_velocity(above, 0.0, [0.0, 1.0, 0.0])
    assert rates[0] == 1.0 / above


def test_a_zero_omega_in_a_batch_is_named_by_its_own_row():
    with pytest.raises(
        ZeroAngularVelocityError,
        match=r"^omega = \[0\.0, 0\.0, 0\.0\] is zero: a translating body has no",
    ):
        kin.instantaneous_axis([1.0, 0, 0], [[0.0, 0, 2.0], [0.0, 0, 0]])


def test_instantaneous_axis_scales_each_row_of_a_batch_on_its_own():
    # ω = e3: AC = (ω × v_A)/ω² = e3 × (x e1) = x e2, exact for any x.  A row with
    # |v_A| = 1e-300 next to one with 1e300 must not be scaled by the other's power of two
    # (1e-300 / 2**997 would underflow to 0).
    v = [[1e-300, 0.0, 0.0], [1e300, 0.0, 0.0]]
    r_AC, v_C = kin.instantaneous_axis(v, [0.0, 0.0, 1.0])
    assert_array_equal(r_AC, [[0.0, 1e-300, 0.0], [0.0, 1e300, 0.0]])
    assert_array_equal(v_C, np.zeros((2, 3)))


def test_an_axial_velocity_beyond_float64_names_its_own_row():
    # Row 1: ω = (1, 2, 0), v_A = (1.5, 1.5, 0) 1e308.  AC = (ω × v_A)/ω² = (0, 0, −0.3e308)
    # is representable, but v_C = (v_A·ω/ω²) ω = 0.9e308 (1, 2, 0) has 1.8e308 > 1.797e308.
    v = [[1.0, 0.0, 0.0], [1.5e308, 1.5e308, 0.0]]
    w = [[0.0, 0.0, 1.0], [1.0, 2.0, 0.0]]
    with pytest.raises(ResultOverflowError) as info:
        kin.instantaneous_axis(v, w)
    # the message names what overflowed: v_C, not AC (it named |AC| before issue 35's
    # third session, though |AC| = 3e307 is finite here)
    assert str(info.value) == (
        "the instantaneous axis of v_A = [1.5e+308, 1.5e+308, 0.0], omega = [1.0, 2.0, 0.0] "
        "(index (1,)) is beyond float64: |v_C| = |v_A . omega| |omega|/omega^2 exceeds 1.8e308"
    )


def test_the_instantaneous_centre_overflow_message_states_the_condition():
    # y_C = y_A + xdot_A/ω = 1e300/1e-200 = 1e500 is beyond float64 (row 0 of one)
    with pytest.raises(ResultOverflowError) as info:
        kin.instantaneous_centre_plane([0.0, 0.0], [1e300, 0.0], 1e-200)
    assert str(info.value) == (
        "the instantaneous centre of r_A = [0.0, 0.0], v_A = [1e+300, 0.0], omega_z = 1e-200 "
        "(index ()) is beyond float64: |r_A + e_z x v_A/omega_z| exceeds 1.8e308"
    )


@pytest.mark.parametrize(
    ("x", "omega_z"),
    [
        pytest.param(3 * TINY, 1.0, id="subnormal-x-unit-spin"),
        pytest.param(3 * TINY, -2.0, id="subnormal-x-fast-spin"),
        pytest.param(1.0, 3.0, id="ordinary"),
        pytest.param(
            3 * TINY,
            0.25,
            id="subnormal-x-slow-spin",
        ),
        pytest.param(
            1e-200,
            1e-200,
            id="small-x-slow-spin",
        ),
    ],
)
def test_the_centre_of_a_body_whose_point_A_is_at_rest_is_A_itself(x, omega_z):
    # Found by the full mutation run of issue 35 (then a strict xfail): _minus_ratio took
    # frexp(0)'s exponent 0 for a zero term and scaled the other term away.
    # (2.95) with v_A = 0: x_C = x_A − 0/ω, y_C = y_A + 0/ω, exactly (A has zero velocity).
    r_C = kin.instantaneous_centre_plane([x, -x], [0.0, 0.0], omega_z)
    assert_array_equal(r_C, [x, -x])


@pytest.mark.parametrize(
    ("n", "omega_z"),
    [
        pytest.param(3, 0.5, id="quotient-6-tiny"),
        pytest.param(2, 1.0, id="quotient-2-tiny"),
        pytest.param(3, -0.25, id="quotient-minus-12-tiny"),
        pytest.param(
            4,
            4.0,
            id="quotient-1-tiny",
        ),
    ],
)
def test_the_centre_seen_from_the_origin_is_the_exact_quotient(n, omega_z):
    # (2.95) with A at the origin: x_C = −ẏ_A/ω, y_C = ẋ_A/ω.  With ẋ_A = ẏ_A = n·2**-1074
    # and ω a power of two the quotient n/ω·2**-1074 is a multiple of 2**-1074: exact.
    q = Fraction(n) / Fraction(omega_z)
    assert q.denominator == 1
    expected = float(q) * TINY
    r_C = kin.instantaneous_centre_plane([0.0, 0.0], [n * TINY, n * TINY], omega_z)
    assert_array_equal(r_C, [-expected, expected])


# rigid motion with ω = (1, 2, 3) of the four points c ± h e2, c ± h e3: ω × (±h e2) =
# ±h (−3, 0, 1), ω × (±h e3) = ±h (2, −1, 0), exact for h a power of two (v_c = 0).
_SPIN = np.array([1.0, 2.0, 3.0])


def _cross_of_four(c, h):
    d = h * np.array([[0.0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]])
    v = h * np.array([[-3.0, 0, 1], [3, 0, -1], [2, -1, 0], [-2, 1, 0]])
    return np.array([c, 0.0, 0.0]) + d, v


@pytest.mark.parametrize(
    ("c", "h"),
    [
        # at the origin, offsets of the smallest subnormal: never shifted, never halved
        pytest.param(0.0, TINY, id="subnormal-at-origin"),
        # max entry 2**1019 has exponent 1020 = 1023 − g (g = ⌈log2 4⌉ + 1 = 3): a sum of
        # four cannot overflow, so the set is not divided by 2**g and the offsets stay exact
        pytest.param(2.0**1019, TINY, id="at-the-shift-threshold"),
        # max entry 1.5·2**1023: four of them overflow (6·2**1023); divided by 2**3 first
        pytest.param(1.5 * 2.0**1023, 1.0, id="huge-coordinate"),
        pytest.param(1.5 * 2.0**1023, 2.0**-30, id="huge-coordinate-small-offsets"),
    ],
)
def test_rigid_velocity_from_points_at_the_edges_of_the_range(c, h):
    r, v = _cross_of_four(c, h)
    omega, v_c, residual = kin.rigid_velocity_from_points(r, v)
    # every step is exact here: offsets and velocities are ±h times small integers, the
    # spread matrix is diag(4, 2, 2) h², and ω is a power-of-two rescaling of its solution
    assert_array_equal(omega, _SPIN)
    assert_array_equal(v_c, [0.0, 0.0, 0.0])
    assert residual == 0.0


def test_rigid_velocity_from_points_scales_each_point_set_of_a_batch_on_its_own():
    # set 0 needs the overflow shift (coordinates 1.5·2**1023); set 1 has subnormal offsets
    # that a shift by 2**3, or set 0's exponent, would round to 0 (a false "coincide")
    r0, v0 = _cross_of_four(1.5 * 2.0**1023, 1.0)
    r1, v1 = _cross_of_four(0.0, TINY)
    omega, v_c, residual = kin.rigid_velocity_from_points(np.stack([r0, r1]), np.stack([v0, v1]))
    assert_array_equal(omega, [_SPIN, _SPIN])
    assert_array_equal(v_c, np.zeros((2, 3)))
    assert_array_equal(residual, [0.0, 0.0])


def test_the_rigidity_residual_is_per_point_set():
    # set 0 is the exact rigid motion above (residual 0); set 1 is a uniform expansion
    # v_i = d_i of the same points, whose best rigid fit is ω = 0, v_c = 0 and whose
    # residual is max |d_i| = 1
    r, v = _cross_of_four(0.0, 1.0)
    omega, _, residual = kin.rigid_velocity_from_points(np.stack([r, r]), np.stack([v, r]))
    assert_array_equal(residual, [0.0, 1.0])
    assert_array_equal(omega, [_SPIN, [0.0, 0.0, 0.0]])


def test_an_angular_velocity_beyond_float64_names_its_point_set_and_spreads():
    # set 1: ω = 2**1030 e3 (beyond float64) turning the points ±2**-10 e1, ±2**-10 e2:
    # v = ω × d = ±2**1020 e2, ∓2**1020 e1, all finite.  Spreads: max |v_i − u| = 2**1020
    # ∈ [2**1020, 2**1021), so 2**1021; max |d_i| = 2**-10 ∈ [2**-10, 2**-9), so 2**-9.
    # The rigidity residual is 0: only ω overflows.
    h, big = 2.0**-10, 2.0**1020
    r1 = h * np.array([[1.0, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0]])
    v1 = big * np.array([[0.0, 1, 0], [0, -1, 0], [-1, 0, 0], [1, 0, 0]])
    r0, v0 = _cross_of_four(0.0, 1.0)
    with pytest.raises(ResultOverflowError) as info:
        kin.rigid_velocity_from_points(np.stack([r0, r1]), np.stack([v0, v1]))
    assert str(info.value) == (
        "the angular velocity of the point set at index (1,) is beyond float64: "
        "velocity spread 2**1021 over position spread 2**-9 exceeds 1.8e308"
    )


def test_points_off_their_line_by_a_little_more_than_the_tolerance_are_accepted():
    # Points ±e1, ±b e2 with b = 2**-19: J = Σ(|d|² 1 − d dᵀ) = diag(2b², 2, 2 + 2b²), so the
    # eigenvalue ratio is b²/(1 + b²) = 2**-38 (1 − 2**-38) ≈ 1.64 COLLINEAR_RTOL
    # (COLLINEAR_RTOL = 1e4 eps = 0.61·2**-38): accepted, and, every step being exact
    # (diagonal J of powers of two), ω = (1, 2, 3) comes back exactly.
    b = 2.0**-19
    assert kin.COLLINEAR_RTOL < b**2 / (1 + b**2) < 2 * kin.COLLINEAR_RTOL
    r = np.array([[1.0, 0, 0], [-1, 0, 0], [0, b, 0], [0, -b, 0]])
    v = np.array([[0.0, 3, -2], [0, -3, 2], [-3 * b, 0, b], [3 * b, 0, -b]])  # ω × r
    omega, v_c, residual = kin.rigid_velocity_from_points(r, v)
    assert_array_equal(omega, _SPIN)
    assert_array_equal(v_c, [0.0, 0.0, 0.0])
    assert residual == 0.0


def _points_with_ratio(y):
    # Points ±x_j e1 (x = 2**24 − 1, 5791, 134, 13) and ±y e2: Σx² = 2(2**48 − 625) and
    # Σy² = 2y², so J = diag(2y², Σx², Σx² + 2y²) exactly (integers below 2**53).
    xs = (2**24 - 1, 5791, 134, 13)
    assert sum(x * x for x in xs) == 2**48 - 625
    pts = [[s * x, 0, 0] for x in xs for s in (1, -1)] + [[0, y, 0], [0, -y, 0]]
    return np.array(pts, dtype=float)


def test_the_collinearity_tolerance_refuses_a_ratio_equal_to_it():
    # y = 25: 2y² = 1250, λ_max = 2**49 − 1250 + 1250 = 2**49, so the eigenvalue ratio is
    # 1250/2**49 = 10000·2**-52 = COLLINEAR_RTOL exactly (1e4 eps, a power-of-two scaling
    # of 10000): the documented bound is "> COLLINEAR_RTOL", so this set is refused.
    assert Fraction(1250, 2**49) == Fraction(kin.COLLINEAR_RTOL)
    r = _points_with_ratio(25)
    with pytest.raises(
        CollinearPointsError, match=r"spread matrix is 2\.22e-12 <= 2\.22e-12; the rotation"
    ):
        kin.rigid_velocity_from_points(r, np.zeros_like(r))
    # y = 26: ratio 1352/(2**49 + 102) = 1.08 COLLINEAR_RTOL, accepted (at rest: ω = 0)
    r = _points_with_ratio(26)
    omega, _, _ = kin.rigid_velocity_from_points(r, np.zeros_like(r))
    assert_array_equal(omega, [0.0, 0.0, 0.0])


def test_the_collinear_message_states_the_condition():
    r = [[0.0, 0, 0], [1, 1, 1], [2, 2, 2]]
    with pytest.raises(CollinearPointsError) as info:
        kin.rigid_velocity_from_points(r, np.zeros((3, 3)))
    assert str(info.value).endswith("; the rotation about their line is undetermined")


def test_an_axis_distance_beyond_float64_is_named_as_ac():
    # v_A = 1e300 e_x, ω = 1e-10 e_z: AC = (ω × v_A)/ω² = 1e310 e_y is beyond float64,
    # while v_C = (v_A·ω/ω²) ω = 0 is not: the message names |AC|
    with pytest.raises(ResultOverflowError) as info:
        kin.instantaneous_axis([1e300, 0.0, 0.0], [0.0, 0.0, 1e-10])
    assert str(info.value) == (
        "the instantaneous axis of v_A = [1e+300, 0.0, 0.0], omega = [0.0, 0.0, 1e-10] "
        "(index ()) is beyond float64: |AC| = |v_A x omega|/omega^2 exceeds 1.8e308"
    )
