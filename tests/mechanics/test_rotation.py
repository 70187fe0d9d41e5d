"""API, conventions and edge cases of :mod:`mechanics.rotation`.

The conventions are pinned two ways: against the book (Essén 1996, ch. 2.2–2.4:
(2.11), (2.20), (2.21), (2.30), (2.34)–(2.36)) and against scipy's
``Rotation``, used here only as an independent reference.  scipy's matrices are
*active* (they turn vectors); the book's ^A R^O is their transpose, and scipy's
quaternions are scalar *last*.
"""

from __future__ import annotations

import math
import re
from fractions import Fraction

import numpy as np
import pytest
from numpy.testing import assert_allclose, assert_array_equal
from scipy.linalg import polar
from scipy.spatial.transform import Rotation

from mechanics import rotation as rot
from mechanics._floats import EPS
from mechanics.errors import (
    MechanicsValueError,
    NonFiniteError,
    NonPositiveParameterError,
    NotARotationError,
    OutOfDomainError,
    ResultOverflowError,
    ShapeError,
    ZeroAxisError,
)

# One rounding of cos or sin: cos(π/2) = 6.1e-17 instead of 0, etc.
TRIG_ATOL = EPS

# numpy's SIMD and scalar loops for sin/cos may round an element differently by
# an ulp, so a batched call and a scalar call can differ by that much.
VECTORISE_ATOL = 4 * EPS

# Each library's matrix is within about 7 eps of the exact one (measured on 2e5
# random rotations: ours 6.3 eps, scipy 5.0 eps max-abs, against an 80-bit
# reference), so the two differ by at most the sum.
SCIPY_ATOL = 16 * EPS

# Euler angles read back from a matrix are conditioned like 1/sin θ for ψ and φ;
# on the test grid sin θ ≥ sin 0.1 ≈ 0.1, so 10 × SCIPY_ATOL bounds the angle
# difference (measured: 6 eps).
EULER_ANGLE_ATOL = 10 * SCIPY_ATOL

# A rotation vector with angle ≤ π − 0.1 is conditioned by at most
# φ / (2 sin(φ/2)) < 1.6 relative to the matrix; 2 × SCIPY_ATOL × π bounds the
# difference of the two libraries' vectors (measured: 6 eps).
ROTVEC_ATOL = 2 * np.pi * SCIPY_ATOL

RNG_SEED = 20240917

#: ψ and φ read back one by one close to gimbal lock: each is an atan2 of
#: products of entries carried to full relative precision (θ normal), a few
#: roundings of order-one angles.
GIMBAL_SPLIT_ATOL = 8 * EPS


def _scipy_passive(r: Rotation) -> np.ndarray:
    """The book's ^A R^O of a scipy rotation: the transpose of its active matrix."""
    return np.swapaxes(r.as_matrix(), -1, -2)


def _random_euler(n: int, *, theta_margin: float = 0.0) -> np.ndarray:
    rng = np.random.default_rng(RNG_SEED)
    psi = rng.uniform(-np.pi, np.pi, n)
    theta = rng.uniform(theta_margin, np.pi - theta_margin, n)
    phi = rng.uniform(-np.pi, np.pi, n)
    return np.stack([psi, theta, phi], axis=-1)


def _random_rotvecs(n: int, *, max_angle: float = np.pi) -> np.ndarray:
    rng = np.random.default_rng(RNG_SEED + 1)
    axis = rng.normal(size=(n, 3))
    axis /= np.linalg.norm(axis, axis=-1, keepdims=True)
    return axis * rng.uniform(0.0, max_angle, n)[:, None]


def _wrapped(a: np.ndarray) -> np.ndarray:
    """Angle differences folded into (−π, π]."""
    return np.angle(np.exp(1j * np.asarray(a)))


# ------------------------------------------------------------ basic matrices (2.30)

ANGLES = [0.0, 0.3, -1.2, np.pi / 2, 2.5, np.pi, -np.pi, 7.0]


@pytest.mark.parametrize("psi", ANGLES)
def test_R3_rows_are_the_turned_basis_vectors_of_example_2_1(psi):
    # Example 2.1: e^A_1 = cos ψ e1 + sin ψ e2, e^A_2 = −sin ψ e1 + cos ψ e2, e^A_3 = e3.
    R = rot.R3(psi)
    c, s = np.cos(psi), np.sin(psi)
    assert_array_equal(R[0], [c, s, 0.0])
    assert_array_equal(R[1], [-s, c, 0.0])
    assert_array_equal(R[2], [0.0, 0.0, 1.0])


@pytest.mark.parametrize("alpha", ANGLES)
def test_R1_R2_R3_are_exactly_the_matrices_of_2_30(alpha):
    c, s = np.cos(alpha), np.sin(alpha)
    assert_array_equal(rot.R1(alpha), [[1, 0, 0], [0, c, s], [0, -s, c]])
    assert_array_equal(rot.R2(alpha), [[c, 0, -s], [0, 1, 0], [s, 0, c]])
    assert_array_equal(rot.R3(alpha), [[c, s, 0], [-s, c, 0], [0, 0, 1]])


def test_R3_quarter_turn_maps_the_basis_as_in_figure_2_2():
    # Turning the basis by +90° about e3: e^A_1 = e^O_2, e^A_2 = −e^O_1.
    assert_allclose(rot.R3(np.pi / 2), [[0, 1, 0], [-1, 0, 0], [0, 0, 1]], atol=TRIG_ATOL, rtol=0)


@pytest.mark.parametrize(("basic", "axis"), [(rot.R1, 0), (rot.R2, 1), (rot.R3, 2)])
@pytest.mark.parametrize("alpha", [0.4, -2.0, 3.0])
def test_basic_matrices_are_positive_turns_about_their_axis(basic, axis, alpha):
    e = np.zeros(3)
    e[axis] = 1.0
    assert_allclose(basic(alpha), rot.matrix_from_axis_angle(e, alpha), atol=SCIPY_ATOL, rtol=0)
    assert_allclose(
        basic(alpha), _scipy_passive(Rotation.from_rotvec(alpha * e)), atol=SCIPY_ATOL, rtol=0
    )


# --------------------------------------------------------------- Euler angles (2.35)


def test_matrix_from_euler_is_scipy_intrinsic_ZXZ_transposed():
    angles = _random_euler(2000)
    ours = rot.matrix_from_euler(angles[:, 0], angles[:, 1], angles[:, 2])
    ref = _scipy_passive(Rotation.from_euler("ZXZ", angles))
    assert_allclose(ours, ref, atol=SCIPY_ATOL, rtol=0)


@pytest.mark.parametrize(
    "angles",
    [(0.0, 0.0, 0.0), (0.3, 0.0, -0.5), (0.3, np.pi, -0.5), (np.pi, 1.0, -np.pi), (-2.0, 3.0, 2.9)],
)
def test_matrix_from_euler_is_the_product_2_35(angles):
    psi, theta, phi = angles
    product = rot.R3(phi) @ rot.R1(theta) @ rot.R3(psi)
    assert_allclose(rot.matrix_from_euler(psi, theta, phi), product, atol=4 * EPS, rtol=0)


def test_euler_from_matrix_agrees_with_scipy_away_from_gimbal_lock():
    angles = _random_euler(2000, theta_margin=0.1)
    M = rot.matrix_from_euler(angles[:, 0], angles[:, 1], angles[:, 2])
    psi, theta, phi = rot.euler_from_matrix(M)
    ref = Rotation.from_matrix(np.swapaxes(M, -1, -2)).as_euler("ZXZ")
    ours = np.stack([psi, theta, phi], axis=-1)
    assert np.abs(_wrapped(ours - ref)).max() <= EULER_ANGLE_ATOL
    # and both are the input angles
    assert np.abs(_wrapped(ours - angles)).max() <= EULER_ANGLE_ATOL


def test_euler_from_matrix_ranges():
    angles = _random_euler(5000)
    psi, theta, phi = rot.euler_from_matrix(
        rot.matrix_from_euler(angles[:, 0], angles[:, 1], angles[:, 2])
    )
    assert ((psi > -np.pi) & (psi <= np.pi)).all()
    assert ((phi > -np.pi) & (phi <= np.pi)).all()
    assert ((theta >= 0) & (theta <= np.pi)).all()


@pytest.mark.parametrize(
    "axis",
    [[1, 0, 0], [0, 1, 0], [0, 0, 1], [0, 0.6, 0.8], [0, 0.8, 0.6], [0.6, 0, 0.8], [0.8, 0.6, 0]],
)
def test_euler_angles_of_an_exact_half_turn_are_in_range_and_reproduce_it(axis):
    # A half turn about n is 2 n nᵀ − 1 (symmetric: its quaternion has w = 0 exactly,
    # the sign of q is then a free choice).  Whatever the choice, ψ, φ in (−π, π] and
    # θ in [0, π], as documented; ψ = ±π must come out as +π.
    n = np.array(axis, dtype=float)
    M = 2.0 * np.outer(n, n) - np.eye(3)
    psi, theta, phi = rot.euler_from_matrix(M)
    assert -np.pi < psi <= np.pi
    assert -np.pi < phi <= np.pi
    assert 0.0 <= theta <= np.pi
    assert_allclose(rot.matrix_from_euler(psi, theta, phi), M, atol=4 * EPS, rtol=0)


def test_euler_from_matrix_of_a_negative_middle_angle_folds_theta_into_0_pi():
    # R3(φ) R1(−θ) R3(ψ) = R3(φ + π) R1(θ) R3(ψ + π): the same matrix with θ > 0.
    psi, theta, phi = rot.euler_from_matrix(rot.matrix_from_euler(0.2, -0.7, 0.4))
    assert_allclose(float(theta), 0.7, atol=4 * EPS, rtol=0)
    assert_allclose(_wrapped(psi - (0.2 + np.pi)), 0.0, atol=4 * EPS)
    assert_allclose(_wrapped(phi - (0.4 + np.pi)), 0.0, atol=4 * EPS)


def test_euler_from_matrix_at_theta_zero_splits_psi_plus_phi_equally():
    # At θ = 0 only ψ + φ is defined (2.37); the documented choice is ψ = φ.
    psi, theta, phi = rot.euler_from_matrix(rot.R3(0.8))
    assert float(theta) == 0.0
    assert_allclose([float(psi), float(phi)], [0.4, 0.4], atol=2 * EPS, rtol=0)


@pytest.mark.parametrize("theta", [0.0, 1e-9, np.pi - 1e-9, np.pi])
def test_euler_from_matrix_reproduces_the_matrix_at_gimbal_lock(theta):
    M = rot.matrix_from_euler(1.1, theta, -2.3)
    back = rot.matrix_from_euler(*rot.euler_from_matrix(M))
    assert_allclose(back, M, atol=SCIPY_ATOL, rtol=0)


def test_euler_near_gimbal_lock_flags_sin_theta_below_atol():
    theta = np.array([0.0, 1e-7, 0.5, np.pi / 2, np.pi - 1e-7, np.pi, 1e-5])
    assert_array_equal(
        rot.euler_near_gimbal_lock(theta), [True, True, False, False, True, True, False]
    )
    assert_array_equal(rot.euler_near_gimbal_lock(1e-5, atol=1e-4), True)


# ------------------------------------------------------- rotation vectors (2.28–2.29)


def test_matrix_from_rotvec_is_scipy_from_rotvec_transposed():
    v = _random_rotvecs(2000)
    assert_allclose(
        rot.matrix_from_rotvec(v), _scipy_passive(Rotation.from_rotvec(v)), atol=SCIPY_ATOL, rtol=0
    )


@pytest.mark.parametrize("angle", [1e-300, 1e-12, 0.3, 2.0, np.pi])
def test_matrix_from_rotvec_is_the_split_form_2_29(angle):
    e = np.array([2.0, -1.0, 2.0]) / 3.0  # a unit vector, exactly representable ratios
    c1, c2, c3 = e
    anti = np.array([[0, c3, -c2], [-c3, 0, c1], [c2, -c1, 0]])
    # 1 − cos φ as 2 sin²(φ/2), which keeps its relative accuracy for tiny φ.
    book = (
        np.cos(angle) * np.eye(3)
        + np.sin(angle) * anti
        + 2 * np.sin(angle / 2) ** 2 * np.outer(e, e)
    )
    assert_allclose(rot.matrix_from_rotvec(angle * e), book, atol=SCIPY_ATOL, rtol=0)
    assert_allclose(rot.matrix_from_axis_angle(3 * e, angle), book, atol=SCIPY_ATOL, rtol=0)


def test_matrix_from_rotvec_keeps_tiny_angles_relative_accuracy():
    # (2.39): for δφ = 1e-200 e3 the off-diagonal entries are ±1e-200.
    M = rot.matrix_from_rotvec([0.0, 0.0, 1e-200])
    assert_allclose([M[0, 1], M[1, 0]], [1e-200, -1e-200], rtol=2 * EPS, atol=0)
    assert_array_equal(rot.matrix_from_rotvec([0.0, 0.0, 0.0]), np.eye(3))


def test_rotvec_from_matrix_agrees_with_scipy_below_pi():
    v = _random_rotvecs(2000, max_angle=np.pi - 0.1)
    M = rot.matrix_from_rotvec(v)
    ours = rot.rotvec_from_matrix(M)
    assert_allclose(
        ours, Rotation.from_matrix(np.swapaxes(M, -1, -2)).as_rotvec(), atol=ROTVEC_ATOL, rtol=0
    )
    assert_allclose(ours, v, atol=ROTVEC_ATOL, rtol=0)


@pytest.mark.parametrize("axis", [[1, 0, 0], [0, 0, 1], [1, 2, -2], [-3, 0.5, 1]])
def test_rotvec_from_matrix_at_pi_returns_either_sign_of_a_half_turn(axis):
    e = np.asarray(axis, float) / np.linalg.norm(axis)
    M = rot.matrix_from_axis_angle(e, np.pi)
    v = rot.rotvec_from_matrix(M)
    assert_allclose(np.linalg.norm(v), np.pi, rtol=4 * EPS)
    assert min(np.abs(v - np.pi * e).max(), np.abs(v + np.pi * e).max()) <= ROTVEC_ATOL


def test_rotvec_from_matrix_of_the_identity_is_zero():
    assert_array_equal(rot.rotvec_from_matrix(np.eye(3)), [0.0, 0.0, 0.0])


def test_matrix_from_axis_angle_divides_out_the_axis_length():
    assert_allclose(
        rot.matrix_from_axis_angle([0, 0, 5.0], 0.7), rot.R3(0.7), atol=SCIPY_ATOL, rtol=0
    )
    # A tiny but non-zero axis is still a direction.
    assert_allclose(
        rot.matrix_from_axis_angle([0, 0, 1e-300], 0.7), rot.R3(0.7), atol=SCIPY_ATOL, rtol=0
    )


@pytest.mark.parametrize("power", [-1074 + 7, -1060, -1040, -1000, -600, 600, 1015])
def test_matrix_from_axis_angle_of_an_axis_scaled_by_a_power_of_two_gives_the_same_bits(power):
    """s·axis is the same direction for s = 2**power (exact for these integer axes, subnormal
    ones included): the same matrix, bit for bit.  Before the fix a subnormal axis lost its
    direction (hypot of a subnormal vector keeps its few bits: 5.8e12 eps off at 2**-1068)."""
    rng = np.random.default_rng(RNG_SEED)
    axes = rng.integers(-50, 51, (64, 3)).astype(float)
    axes = axes[np.abs(axes).max(axis=-1) > 0]
    angles = rng.uniform(-4.0, 4.0, len(axes))
    scaled = np.ldexp(axes, power)
    assert_array_equal(np.ldexp(scaled, -power), axes)  # the scaling is exact
    got = rot.matrix_from_axis_angle(scaled, angles)
    assert_array_equal(got, rot.matrix_from_axis_angle(axes, angles))
    # and that matrix is (2.29): cos φ 1 + (1 − cos φ) e eᵀ − sin φ [e]×, by mpmath (40 digits)
    import mpmath

    with mpmath.workdps(40):
        for a, phi, R in zip(axes[:8].tolist(), angles[:8].tolist(), got[:8], strict=True):
            n = mpmath.sqrt(sum(mpmath.mpf(x) ** 2 for x in a))
            e = [mpmath.mpf(x) / n for x in a]
            c, s_ = mpmath.cos(phi), mpmath.sin(phi)
            skew = [[0, -e[2], e[1]], [e[2], 0, -e[0]], [-e[1], e[0], 0]]
            want = [
                [(c if i == j else 0) + (1 - c) * e[i] * e[j] - s_ * skew[i][j] for j in range(3)]
                for i in range(3)
            ]
            assert np.abs(R - np.array(want, dtype=float)).max() <= SCIPY_ATOL


# ------------------------------------------------------------------- quaternions


def test_quaternions_are_scalar_first_where_scipy_is_scalar_last():
    v = _random_rotvecs(2000)
    M = rot.matrix_from_rotvec(v)
    ref = np.roll(Rotation.from_matrix(np.swapaxes(M, -1, -2)).as_quat(canonical=True), 1, axis=-1)
    assert_allclose(rot.quat_from_matrix(M), ref, atol=SCIPY_ATOL, rtol=0)
    q = rot.quat_from_rotvec(v)
    assert_allclose(
        q, np.roll(Rotation.from_rotvec(v).as_quat(), 1, axis=-1), atol=SCIPY_ATOL, rtol=0
    )
    assert_allclose(
        rot.matrix_from_quat(q),
        _scipy_passive(Rotation.from_quat(np.roll(q, -1, axis=-1))),
        atol=SCIPY_ATOL,
        rtol=0,
    )


def test_quaternion_of_a_turn_about_e3_is_cos_half_then_sin_half_e3():
    phi = 1.3
    q = rot.quat_from_rotvec([0.0, 0.0, phi])
    assert_allclose(q, [np.cos(phi / 2), 0, 0, np.sin(phi / 2)], atol=TRIG_ATOL, rtol=0)
    assert_allclose(rot.quat_from_matrix(rot.R3(phi)), q, atol=SCIPY_ATOL, rtol=0)


def test_quat_from_matrix_is_canonical_with_w_nonnegative():
    v = _random_rotvecs(2000)
    q = rot.quat_from_matrix(rot.matrix_from_rotvec(v))
    assert (q[:, 0] >= 0).all()
    assert_allclose(np.linalg.norm(q, axis=-1), 1.0, atol=4 * EPS, rtol=0)


def test_quaternions_q_and_minus_q_are_the_same_rotation():
    q = rot.quat_from_rotvec([0.3, -1.0, 2.0])
    assert_allclose(rot.matrix_from_quat(-q), rot.matrix_from_quat(q), atol=2 * EPS, rtol=0)
    assert_allclose(rot.rotvec_from_quat(-q), rot.rotvec_from_quat(q), atol=4 * EPS, rtol=0)


def test_quat_multiply_is_the_hamilton_product():
    one, i, j, k = np.eye(4)
    assert_array_equal(rot.quat_multiply(i, j), k)
    assert_array_equal(rot.quat_multiply(j, i), -k)
    assert_array_equal(rot.quat_multiply(i, i), -one)
    p, q = rot.quat_from_rotvec(_random_rotvecs(2))
    # scipy: (P * Q) applies Q first; its quaternion is the Hamilton product p ⊗ q.
    ref = (Rotation.from_quat(np.roll(p, -1)) * Rotation.from_quat(np.roll(q, -1))).as_quat()
    assert_allclose(rot.quat_multiply(p, q), np.roll(ref, 1), atol=4 * EPS, rtol=0)


def test_compose_quat_follows_the_matrix_chain_2_34():
    v = _random_rotvecs(400)
    q_B_A, q_A_O = rot.quat_from_rotvec(v[:200]), rot.quat_from_rotvec(v[200:])
    R_B_O = rot.compose(rot.matrix_from_quat(q_B_A), rot.matrix_from_quat(q_A_O))
    q_B_O = rot.compose_quat(q_B_A, q_A_O)
    assert (q_B_O[:, 0] >= 0).all()
    assert_allclose(rot.matrix_from_quat(q_B_O), R_B_O, atol=SCIPY_ATOL, rtol=0)


@pytest.mark.parametrize(
    "q",
    [
        [0.0, 1.0, 0.0, 0.0],  # half turns: w = 0, and −q has w = −0, also "≥ 0"
        [0.0, 0.0, 0.6, 0.8],
        [0.5, 0.5, -0.5, 0.5],
        [1.0, 0.0, 0.0, 0.0],
    ],
)
def test_composing_with_the_identity_returns_a_canonical_quaternion_as_it_is(q):
    # q ⊗ 1 = q (the Hamilton product with (1, 0, 0, 0) is exact); a q that already
    # has w ≥ 0 is canonical, so it comes back as q itself and not as −q.
    one = [1.0, 0.0, 0.0, 0.0]
    assert_array_equal(rot.compose_quat(q, one), q)
    assert_array_equal(rot.compose_quat(one, q), q)


def test_rotvec_from_quat_returns_angles_in_0_pi():
    q = rot.quat_from_rotvec(_random_rotvecs(2000) * 1.9)  # angles up to 1.9 π
    v = rot.rotvec_from_quat(q)
    assert (np.linalg.norm(v, axis=-1) <= np.pi * (1 + 2 * EPS)).all()
    assert_allclose(rot.matrix_from_rotvec(v), rot.matrix_from_quat(q), atol=SCIPY_ATOL, rtol=0)


# ------------------------------------------------- composition, active and passive


def test_compose_is_the_chain_of_basis_changes_2_34():
    psi, theta, phi = 0.7, 1.2, -2.1
    R_C_O, R_B_C, R_A_B = rot.R3(psi), rot.R1(theta), rot.R3(phi)
    R_A_O = rot.compose(R_A_B, rot.compose(R_B_C, R_C_O))
    assert_array_equal(R_A_O, R_A_B @ (R_B_C @ R_C_O))
    assert_allclose(R_A_O, rot.matrix_from_euler(psi, theta, phi), atol=4 * EPS, rtol=0)
    # E_A = ^A R^O E_O: the rows of R_A_O are the A basis in O components, so
    # composing with the identity on either side changes nothing.
    assert_array_equal(rot.compose(np.eye(3), R_A_O), R_A_O)
    assert_array_equal(rot.compose(R_A_O, np.eye(3)), R_A_O)


def test_compose_order_matters_for_finite_rotations_2_38():
    a, b = rot.R3(np.pi / 2), rot.R1(np.pi / 2)
    # R3(π/2) R1(π/2) and R1(π/2) R3(π/2) differ by entries of size 1 (figure 2.7).
    assert np.abs(rot.compose(a, b) - rot.compose(b, a)).max() > 0.5


def test_active_from_passive_is_the_transpose_and_scipys_matrix():
    v = _random_rotvecs(50)
    R_A_O = rot.matrix_from_rotvec(v)
    active = rot.active_from_passive(R_A_O)
    assert_array_equal(active, np.swapaxes(R_A_O, -1, -2))
    assert_allclose(active, Rotation.from_rotvec(v).as_matrix(), atol=SCIPY_ATOL, rtol=0)
    assert_array_equal(rot.passive_from_active(active), R_A_O)


def test_rotate_vector_turns_e1_into_e2_for_a_quarter_turn_about_e3():
    assert_allclose(
        rot.rotate_vector(rot.R3(np.pi / 2), [1, 0, 0]), [0, 1, 0], atol=TRIG_ATOL, rtol=0
    )
    assert_allclose(
        rot.rotate_vector(rot.R3(np.pi / 2), [0, 1, 0]), [-1, 0, 0], atol=TRIG_ATOL, rtol=0
    )


def test_rotate_vector_is_the_book_rotation_operator_2_23():
    # r' = (r·e)e + cos φ (e × r) × e + sin φ e × r, turned with the right-hand rule.
    e = np.array([1.0, -2.0, 2.0]) / 3.0
    phi = 2.2
    r = np.array([0.5, 3.0, -1.0])
    book = (r @ e) * e + np.cos(phi) * np.cross(np.cross(e, r), e) + np.sin(phi) * np.cross(e, r)
    assert_allclose(
        rot.rotate_vector(rot.matrix_from_axis_angle(e, phi), r), book, atol=8 * SCIPY_ATOL, rtol=0
    )
    assert_allclose(Rotation.from_rotvec(phi * e).apply(r), book, atol=8 * SCIPY_ATOL, rtol=0)


def test_rotated_vector_has_the_old_components_in_the_new_basis_2_21():
    # r' = r^O E_A: the A components of r' are the O components of r.
    R_A_O = rot.matrix_from_euler(0.3, 2.0, -1.0)
    r = np.array([1.0, -2.0, 0.25])
    turned = rot.rotate_vector(R_A_O, r)
    assert_allclose(rot.components_A_from_O(R_A_O, turned), r, atol=8 * EPS, rtol=0)


def test_components_A_from_O_2_20():
    R_A_O = rot.matrix_from_euler(-0.4, 0.9, 2.5)
    # Each body basis vector e^A_i (row i of R_A_O in O components) has A components δ_i.
    for i in range(3):
        assert_allclose(
            rot.components_A_from_O(R_A_O, R_A_O[i]), np.eye(3)[i], atol=4 * EPS, rtol=0
        )
    # The vector itself is unchanged: r = r^A E_A = r^O E_O.
    r_O = np.array([2.0, -1.0, 0.5])
    r_A = rot.components_A_from_O(R_A_O, r_O)
    assert_allclose(r_A @ R_A_O, r_O, atol=8 * EPS, rtol=0)
    # For R3(π/2), e^O_1 = −e^A_2.
    assert_allclose(
        rot.components_A_from_O(rot.R3(np.pi / 2), [1, 0, 0]), [0, -1, 0], atol=TRIG_ATOL, rtol=0
    )


# ------------------------------------------------------------------ vectorisation


SHAPES = [(), (5,), (2, 3)]


def _euler_of_shape(shape):
    n = int(np.prod(shape, dtype=int))
    return _random_euler(n).reshape(*shape, 3)


@pytest.mark.parametrize("shape", SHAPES)
def test_functions_vectorise_over_leading_axes(shape):
    angles = _euler_of_shape(shape)
    psi, theta, phi = np.moveaxis(angles, -1, 0)
    M = rot.matrix_from_euler(psi, theta, phi)
    assert M.shape == (*shape, 3, 3)
    for basic in (rot.R1, rot.R2, rot.R3):
        assert basic(psi).shape == (*shape, 3, 3)
    v = rot.rotvec_from_matrix(M)
    q = rot.quat_from_matrix(M)
    e = rot.euler_from_matrix(M)
    r = rot.rotate_vector(M, np.ones((*shape, 3)))
    assert v.shape == (*shape, 3)
    assert q.shape == (*shape, 4)
    assert [np.shape(x) for x in e] == [shape] * 3
    assert r.shape == (*shape, 3)
    assert rot.matrix_from_rotvec(v).shape == (*shape, 3, 3)
    assert rot.matrix_from_quat(q).shape == (*shape, 3, 3)
    assert rot.quat_from_rotvec(v).shape == (*shape, 4)
    assert rot.rotvec_from_quat(q).shape == (*shape, 3)
    assert rot.check_rotation(M).shape == (*shape, 3, 3)
    assert np.shape(rot.is_rotation(M)) == shape
    assert rot.nearest_rotation(M).shape == (*shape, 3, 3)
    assert rot.matrix_from_axis_angle(np.ones((*shape, 3)), psi).shape == (*shape, 3, 3)
    # every element equals the scalar call
    for idx in np.ndindex(*shape):
        assert_allclose(M[idx], rot.matrix_from_euler(*angles[idx]), atol=VECTORISE_ATOL, rtol=0)
        assert_allclose(v[idx], rot.rotvec_from_matrix(M[idx]), atol=VECTORISE_ATOL, rtol=0)
        assert_allclose(q[idx], rot.quat_from_matrix(M[idx]), atol=VECTORISE_ATOL, rtol=0)


def test_inputs_broadcast_against_each_other():
    psi = np.linspace(-1, 1, 5)
    phi = np.array([[0.1], [0.2]])
    M = rot.matrix_from_euler(psi, 0.4, phi)
    assert M.shape == (2, 5, 3, 3)
    assert_allclose(M[1, 3], rot.matrix_from_euler(psi[3], 0.4, 0.2), atol=VECTORISE_ATOL, rtol=0)

    R = rot.R3(psi)  # (5, 3, 3)
    assert rot.rotate_vector(R, [1.0, 0, 0]).shape == (5, 3)
    assert rot.rotate_vector(rot.R3(0.3), np.ones((4, 3))).shape == (4, 3)
    assert rot.components_A_from_O(R, np.ones((2, 1, 3))).shape == (2, 5, 3)
    assert rot.compose(R, rot.R1(0.3)).shape == (5, 3, 3)

    axis_angle = rot.matrix_from_axis_angle([0, 0, 1.0], psi)
    assert_allclose(axis_angle, R, atol=SCIPY_ATOL, rtol=0)


# ---------------------------------------------------------------- check_rotation


def test_check_rotation_returns_a_float64_copy_of_a_valid_matrix():
    out = rot.check_rotation([[1, 0, 0], [0, 1, 0], [0, 0, 1]])
    assert out.dtype == np.float64
    assert_array_equal(out, np.eye(3))


@pytest.mark.parametrize("n", [1000, 10_000])
def test_check_rotation_accepts_the_drift_of_long_products(n):
    # ROTATION_ATOL is chosen to accept the drift of long products of different
    # rotations (a random walk).  Regression: when matrix_from_rotvec produced
    # rows long by ~0.1 eps on average, the drift grew like n instead (1e4
    # products: ~1000 eps) and this product was rejected.
    rng = np.random.default_rng(RNG_SEED + 3)
    R = np.eye(3)
    for step in rot.matrix_from_rotvec(rng.normal(size=(n, 3))):
        R = R @ step
    assert_array_equal(rot.check_rotation(R), R)


def test_check_rotation_names_the_orthogonality_deviation():
    with pytest.raises(NotARotationError, match=re.escape("max |R R^T - 1| = 3 exceeds atol")):
        rot.check_rotation(2 * np.eye(3))
    M = np.eye(3)
    M[0, 1] = 1e-9
    with pytest.raises(NotARotationError, match=r"max \|R R\^T - 1\| = 1e-09 .*nearest_rotation"):
        rot.check_rotation(M)


def test_check_rotation_names_a_reflection():
    with pytest.raises(NotARotationError, match=r"\|det R - 1\| = 2 exceeds .*reflection"):
        rot.check_rotation(np.diag([1.0, 1.0, -1.0]))
    with pytest.raises(NotARotationError, match="reflection"):
        rot.check_rotation(-np.eye(3))


def test_check_rotation_names_the_index_of_the_first_bad_matrix_and_the_argument():
    stack = np.stack([np.eye(3), np.eye(3), 1.5 * np.eye(3)]).reshape(3, 1, 3, 3)
    with pytest.raises(
        NotARotationError,
        match=re.escape(
            "R_A_O is not a rotation: max |R R^T - 1| = 1.25 exceeds atol = 5.68e-14 (index (2, 0))"
        ),
    ):
        rot.check_rotation(stack)
    with pytest.raises(NotARotationError, match=r"^R_B_A is not a rotation"):
        rot.check_rotation(2 * np.eye(3), name="R_B_A")


def test_check_rotation_atol_is_the_threshold():
    M = np.eye(3)
    M[0, 1] = 1e-10
    assert_array_equal(rot.check_rotation(M, atol=1e-9), M)
    with pytest.raises(NotARotationError, match=r"atol = 1e-11"):
        rot.check_rotation(M, atol=1e-11)


def test_is_rotation_is_elementwise():
    stack = np.stack([np.eye(3), 2 * np.eye(3), np.diag([1.0, -1, 1]), rot.R2(0.4)])
    assert_array_equal(rot.is_rotation(stack), [True, False, False, True])


# --------------------------------------------------------------- nearest_rotation


def test_nearest_rotation_is_the_polar_factor():
    rng = np.random.default_rng(RNG_SEED + 2)
    R = rot.matrix_from_rotvec(_random_rotvecs(20))
    M = R + 1e-3 * rng.normal(size=R.shape)
    N = rot.nearest_rotation(M)
    assert rot.is_rotation(N).all()
    for m, n in zip(M, N, strict=True):
        u, _ = polar(m)
        assert_allclose(n, u, atol=SCIPY_ATOL, rtol=0)


def test_nearest_rotation_leaves_a_rotation_alone():
    R = rot.matrix_from_euler(0.3, 2.0, -1.0)
    assert_allclose(rot.nearest_rotation(R), R, atol=SCIPY_ATOL, rtol=0)


def test_nearest_rotation_of_a_reflection_flips_the_smallest_singular_direction():
    # diag(3, 2, −1): distances² to the rotations diag(1,1,1), diag(1,−1,−1),
    # diag(−1,1,−1) are 9, 13, 17, so the identity is nearest.
    assert_allclose(
        rot.nearest_rotation(np.diag([3.0, 2.0, -1.0])), np.eye(3), atol=4 * EPS, rtol=0
    )


@pytest.mark.parametrize(
    ("M", "index", "why"),
    [
        pytest.param(np.zeros((3, 3)), r"\(\)", "two of its singular values are zero", id="zero"),
        pytest.param(1e-300 * np.zeros((3, 3)), r"\(\)", "two of its singular", id="zero-1e-300"),
        pytest.param(
            np.outer([1.0, 2.0, 3.0], [0.0, 1.0, 1.0]), r"\(\)", "two of its singular", id="rank-1"
        ),
        pytest.param(
            [np.eye(3), np.zeros((3, 3))], r"\(1,\)", "two of its singular", id="zero-in-batch"
        ),
        pytest.param(-np.eye(3), r"\(\)", r"det M < 0 and its two smallest", id="minus-identity"),
    ],
)
def test_nearest_rotation_refuses_a_matrix_without_a_unique_nearest_rotation(M, index, why):
    with pytest.raises(
        OutOfDomainError,
        match=rf"^M has no unique nearest rotation: {why}.*"
        rf"at index {index}$",
    ):
        rot.nearest_rotation(M)


@pytest.mark.parametrize(
    ("M", "why", "values"),
    [
        pytest.param(
            np.zeros((3, 3)),
            "two of its singular values are zero (rank <= 1: every turn about the remaining "
            "direction is equally near)",
            "[0.0, 0.0, 0.0]",
            id="zero",
        ),
        pytest.param(
            np.diag([1.0, 1.0, -1.0]),
            "det M < 0 and its two smallest singular values are equal (several half turns "
            "are equally near)",
            "[1.0, 1.0, 1.0]",
            id="reflection",
        ),
    ],
)
def test_nearest_rotation_refusal_says_why_to_what_tolerance_and_the_singular_values(
    M, why, values
):
    # the singular values of a diagonal matrix are its |entries|, exactly
    with pytest.raises(OutOfDomainError) as info:
        rot.nearest_rotation(M)
    assert str(info.value) == (
        f"M has no unique nearest rotation: {why}, to 8 eps of the largest; "
        f"singular values {values} at index ()"
    )


@pytest.mark.parametrize(
    ("diagonal", "unique"),
    [
        # "zero" is s2 ≤ 8 eps s1, inclusive, relative to the largest s1
        pytest.param([1.0, 8 * EPS, 0.0], False, id="s2-at-8-eps"),
        pytest.param([1.0, 4 * EPS, 0.0], False, id="s2-at-4-eps"),
        pytest.param([1.0, 9 * EPS, 0.0], True, id="s2-at-9-eps"),
        pytest.param([2.0**40, 2.0**40 * 9 * EPS, 0.0], True, id="s2-at-9-eps-scaled"),
        # "equal" (with det M < 0) is s2 − s3 ≤ 8 eps s1, inclusive
        pytest.param([1.0, 1.0, -(1.0 - 8 * EPS)], False, id="s2-s3-at-8-eps"),
        pytest.param([1.0, 1.0, -(1.0 - 16 * EPS)], True, id="s2-s3-at-16-eps"),
    ],
)
def test_nearest_rotation_tolerances_are_8_eps_of_the_largest_singular_value(diagonal, unique):
    # For diag(a, b, ±c) with a ≥ b > c ≥ 0 the nearest rotation is the identity (the
    # smallest direction flipped if det < 0); exact singular values a, b, c.
    M = np.diag(diagonal)
    if unique:
        assert_allclose(rot.nearest_rotation(M), np.eye(3), atol=4 * EPS, rtol=0)
    else:
        with pytest.raises(OutOfDomainError, match=r"^M has no unique nearest rotation"):
            rot.nearest_rotation(M)


def test_nearest_rotation_of_a_rank_2_matrix_is_unique_and_returned():
    # diag(2, 1, 0): tr(Q^T M) <= 3 with equality only at Q = 1, the nearest rotation
    assert_allclose(rot.nearest_rotation(np.diag([2.0, 1.0, 0.0])), np.eye(3), atol=4 * EPS, rtol=0)


# ---------------------------------------------------------------------- bad input

_REFLECTION = np.diag([1.0, -1.0, 1.0])

BAD_INPUT = [
    pytest.param(
        rot.R1,
        (np.nan,),
        NonFiniteError,
        r"alpha must be finite; found .*nan.* at index \(\)",
        id="R1-nan",
    ),
    pytest.param(
        rot.R3,
        ([0.0, np.inf],),
        NonFiniteError,
        r"alpha must be finite; found .*inf.* at index \(1,\)",
        id="R3-inf",
    ),
    pytest.param(rot.R2, (1j,), ShapeError, r"alpha is complex", id="R2-complex"),
    pytest.param(
        rot.R2,
        ("x",),
        ShapeError,
        r"alpha has dtype <U1; a real numeric array is required",
        id="R2-str",
    ),
    pytest.param(
        rot.matrix_from_euler,
        (0.0, np.nan, 0.0),
        NonFiniteError,
        r"^theta must be finite",
        id="euler-nan",
    ),
    pytest.param(
        rot.matrix_from_euler,
        (0.0, 0.0, -np.inf),
        NonFiniteError,
        r"^phi must be finite; found .*inf",
        id="euler-inf",
    ),
    pytest.param(
        rot.matrix_from_rotvec,
        ([1.0, np.inf, 0.0],),
        NonFiniteError,
        r"rotvec must be finite; found .*inf.* at index \(1,\)",
        id="rotvec-inf",
    ),
    pytest.param(
        rot.matrix_from_rotvec,
        ([1.0, 2.0],),
        ShapeError,
        r"rotvec has shape \(2,\); expected \(\.\.\., 3\)",
        id="rotvec-shape",
    ),
    pytest.param(
        rot.matrix_from_rotvec,
        (np.array([1, 2, 3], dtype=object),),
        ShapeError,
        r"rotvec has dtype object",
        id="rotvec-object",
    ),
    pytest.param(
        rot.matrix_from_rotvec,
        ([1.0, 2.0, 3.0 + 0j],),
        ShapeError,
        r"rotvec is complex \(complex128\)",
        id="rotvec-complex",
    ),
    pytest.param(
        rot.matrix_from_rotvec,
        ([[1.0, 2.0, 3.0], [1.0]],),
        ShapeError,
        r"rotvec is not an array of numbers",
        id="rotvec-ragged",
    ),
    pytest.param(
        rot.check_rotation,
        (np.eye(2),),
        ShapeError,
        r"R_A_O has shape \(2, 2\); expected \(\.\.\., 3, 3\)",
        id="check-shape",
    ),
    pytest.param(
        rot.check_rotation,
        (np.eye(3) * (1 + 0j),),
        ShapeError,
        r"R_A_O is complex",
        id="check-complex",
    ),
    pytest.param(
        rot.check_rotation,
        (np.eye(3).astype(object),),
        ShapeError,
        r"R_A_O has dtype object",
        id="check-object",
    ),
    pytest.param(
        rot.check_rotation,
        (np.where(np.eye(3) == 1, np.nan, 0.0),),
        NonFiniteError,
        r"R_A_O must be finite; found .*nan.* at index \(0, 0\)",
        id="check-nan",
    ),
    pytest.param(
        rot.rotvec_from_matrix,
        (2 * np.eye(3),),
        NotARotationError,
        r"R_A_O is not a rotation: max \|R R\^T - 1\| = 3",
        id="rotvec-not-rotation",
    ),
    pytest.param(
        rot.euler_from_matrix,
        (_REFLECTION,),
        NotARotationError,
        r"reflection",
        id="euler-reflection",
    ),
    pytest.param(
        rot.quat_from_matrix,
        (_REFLECTION,),
        NotARotationError,
        r"\|det R - 1\| = 2",
        id="quat-reflection",
    ),
    pytest.param(
        rot.active_from_passive,
        (_REFLECTION,),
        NotARotationError,
        r"^R_A_O is not a rotation",
        id="active-reflection",
    ),
    pytest.param(
        rot.passive_from_active,
        (2 * np.eye(3),),
        NotARotationError,
        r"^R_active is not a rotation",
        id="passive-not-rotation",
    ),
    pytest.param(
        rot.compose,
        (2 * np.eye(3), np.eye(3)),
        NotARotationError,
        r"^R_B_A is not a rotation",
        id="compose-left",
    ),
    pytest.param(
        rot.compose,
        (np.eye(3), _REFLECTION),
        NotARotationError,
        r"^R_A_O is not a rotation",
        id="compose-right",
    ),
    pytest.param(
        rot.rotate_vector,
        (_REFLECTION, [1.0, 0, 0]),
        NotARotationError,
        r"reflection",
        id="rotate-reflection",
    ),
    pytest.param(
        rot.rotate_vector,
        (np.eye(3), [1.0, 0]),
        ShapeError,
        r"r_O has shape \(2,\)",
        id="rotate-shape",
    ),
    pytest.param(
        rot.components_A_from_O,
        (np.eye(3), [np.nan, 0, 0]),
        NonFiniteError,
        r"r_O must be finite",
        id="components-nan",
    ),
    pytest.param(
        rot.matrix_from_axis_angle,
        ([0.0, 0.0, 0.0], 1.0),
        ZeroAxisError,
        r"axis has zero length at index \(\); a direction is required",
        id="axis-zero",
    ),
    pytest.param(
        rot.matrix_from_axis_angle,
        ([[0, 0, 1.0], [0, 0, 0]], 1.0),
        ZeroAxisError,
        r"axis has zero length at index \(1,\)",
        id="axis-zero-batched",
    ),
    pytest.param(
        rot.matrix_from_axis_angle,
        ([0, 0, 1.0], np.nan),
        NonFiniteError,
        r"angle must be finite",
        id="axis-angle-nan",
    ),
    pytest.param(
        rot.matrix_from_quat,
        ([2.0, 0, 0, 0],),
        NotARotationError,
        r"q is not a unit quaternion: \|q\| = 2\.0 at index \(\)",
        id="quat-non-unit",
    ),
    pytest.param(
        rot.matrix_from_quat,
        ([[1.0, 0, 0, 0], [0, 0.5, 0, 0]],),
        NotARotationError,
        r"\|q\| = 0\.5 at index \(1,\)",
        id="quat-non-unit-batched",
    ),
    pytest.param(
        rot.matrix_from_quat,
        ([0.0, 0, 0, 0],),
        ZeroAxisError,
        r"q has zero length; a unit quaternion is required",
        id="quat-zero",
    ),
    pytest.param(
        rot.rotvec_from_quat,
        ([0.0, 0, 0, 0],),
        ZeroAxisError,
        r"q has zero length",
        id="rotvec-from-quat-zero",
    ),
    pytest.param(
        rot.matrix_from_quat,
        ([1.0, 0, 0],),
        ShapeError,
        r"q has shape \(3,\); expected \(\.\.\., 4\)",
        id="quat-shape",
    ),
    pytest.param(
        rot.compose_quat,
        ([1.0, 0, 0, 0], [0.0, 0, 0, 3.0]),
        NotARotationError,
        r"q_A_O is not a unit quaternion: \|q\| = 3\.0",
        id="compose-quat-non-unit",
    ),
    pytest.param(
        rot.quat_multiply,
        ([1.0, 0, 0], [1.0, 0, 0, 0]),
        ShapeError,
        r"^p has shape \(3,\)",
        id="quat-multiply-shape",
    ),
    pytest.param(
        rot.quat_multiply,
        ([1.0, 0, 0, 0], [1.0, 0, 0]),
        ShapeError,
        r"^q has shape \(3,\); expected \(\.\.\., 4\)",
        id="quat-multiply-shape-right",
    ),
    pytest.param(
        rot.quat_multiply,
        ([1.0, 0, 0, 0], [1.0, np.nan, 0, 0]),
        NonFiniteError,
        r"^q must be finite; found .*nan.* at index \(1,\)",
        id="quat-multiply-nan-right",
    ),
    pytest.param(
        rot.compose_quat,
        ([0.0, 0, 0, 0.5], [1.0, 0, 0, 0]),
        NotARotationError,
        r"^q_B_A is not a unit quaternion: \|q\| = 0\.5",
        id="compose-quat-non-unit-left",
    ),
    pytest.param(
        rot.components_A_from_O,
        (np.eye(3), [1.0, 0]),
        ShapeError,
        r"^r_O has shape \(2,\); expected \(\.\.\., 3\)",
        id="components-shape",
    ),
    pytest.param(
        rot.nearest_rotation,
        (np.eye(2),),
        ShapeError,
        r"^M has shape \(2, 2\); expected \(\.\.\., 3, 3\)",
        id="nearest-shape",
    ),
    pytest.param(
        rot.matrix_from_axis_angle,
        ([1.0, 0], 1.0),
        ShapeError,
        r"^axis has shape \(2,\); expected \(\.\.\., 3\)",
        id="axis-shape",
    ),
    pytest.param(
        rot.matrix_from_axis_angle,
        ([1.0, np.inf, 0], 1.0),
        NonFiniteError,
        r"^axis must be finite; found .*inf.* at index \(1,\)",
        id="axis-inf",
    ),
    pytest.param(
        rot.quat_from_rotvec,
        ([1.0, 2.0],),
        ShapeError,
        r"^rotvec has shape \(2,\); expected \(\.\.\., 3\)",
        id="quat-from-rotvec-shape",
    ),
    pytest.param(
        rot.quat_from_rotvec,
        ([1.0, -np.inf, 0],),
        NonFiniteError,
        r"^rotvec must be finite; found .*inf.* at index \(1,\)",
        id="quat-from-rotvec-inf",
    ),
    pytest.param(
        rot.matrix_from_euler,
        (np.nan, 0.0, 0.0),
        NonFiniteError,
        r"^psi must be finite; found .*nan",
        id="euler-psi-nan",
    ),
    pytest.param(
        rot.check_rotation,
        (2 * np.eye(3),),
        NotARotationError,
        r"^R_A_O is not a rotation: max \|R R\^T - 1\| = 3 exceeds atol = .* \(index \(\)\); "
        r"use nearest_rotation\(\) to project it$",
        id="check-hint-nearest",
    ),
    pytest.param(
        rot.check_rotation,
        (_REFLECTION,),
        NotARotationError,
        r"^R_A_O is not a rotation: \|det R - 1\| = 2 exceeds atol = .* \(index \(\)\); "
        r"it is a reflection$",
        id="check-hint-reflection",
    ),
    pytest.param(
        lambda R: rot.check_rotation(R, atol=0.0),
        (_REFLECTION,),
        NotARotationError,
        r"^R_A_O is not a rotation: \|det R - 1\| = 2 exceeds atol = 0 \(index \(\)\); "
        r"it is a reflection$",
        id="check-reflection-atol-zero",
    ),
    pytest.param(
        lambda R: rot.check_rotation(R, atol=1.0),
        (np.diag([1.0, 1.0, -0.5]),),
        NotARotationError,
        r"\|det R - 1\| = 1\.5 exceeds atol = 1 \(index \(\)\); use nearest_rotation\(\) to project it$",
        id="check-det-1.5-not-a-reflection",
    ),
    pytest.param(
        rot.check_rotation,
        (1e200 * np.eye(3),),
        NotARotationError,
        r"^R_A_O is not a rotation: max \|R R\^T - 1\| = inf",
        id="check-overflow",
    ),
    pytest.param(
        rot.check_rotation,
        (np.array([[1e200, 1e200, 0], [1e200, -1e200, 0], [0, 0, 1.0]]),),
        NotARotationError,
        r"^R_A_O is not a rotation: max \|R R\^T - 1\| = (inf|nan)",
        id="check-overflow-inf-minus-inf",
    ),
    pytest.param(
        rot.matrix_from_quat,
        ([1e200, 0, 0, 0],),
        NotARotationError,
        r"^q is not a unit quaternion: \|q\| = 1e\+200 at index \(\)",
        id="quat-overflow",
    ),
    pytest.param(
        rot.matrix_from_quat,
        ([[1.0, 0, 0, 0], [0, 0, 0, 0]],),
        ZeroAxisError,
        r"^q has zero length; a unit quaternion is required",
        id="quat-zero-in-batch",
    ),
    pytest.param(
        rot.nearest_rotation,
        (np.full((3, 3), np.inf),),
        NonFiniteError,
        r"^M must be finite",
        id="nearest-inf",
    ),
    pytest.param(
        rot.is_rotation,
        (np.ones((3, 2)),),
        ShapeError,
        r"^R has shape \(3, 2\)",
        id="is-rotation-shape",
    ),
    pytest.param(
        rot.euler_near_gimbal_lock,
        (np.nan,),
        NonFiniteError,
        r"^theta must be finite",
        id="gimbal-nan",
    ),
]


@pytest.mark.parametrize(("func", "args", "error", "match"), BAD_INPUT)
def test_bad_input_raises_the_specific_error_naming_the_condition(func, args, error, match):
    with pytest.raises(error, match=match) as info:
        func(*args)
    assert isinstance(info.value, MechanicsValueError)
    assert isinstance(info.value, ValueError)


def test_no_nan_leaves_for_extreme_but_finite_input():
    # Huge rotation vectors are valid (the angle is taken modulo 2π by sin/cos).
    M = rot.matrix_from_rotvec([1e300, 1e300, 0.0])
    assert np.isfinite(M).all()
    assert rot.is_rotation(M)


# ------------------------------------------------------------ documented accuracy


@pytest.mark.parametrize(
    ("rotvec", "through"),
    [
        pytest.param([2.1, 1.2, -0.4], "rotvec", id="rotvec"),
        pytest.param([-2.3, -1.0, -0.5], "quat", id="quat"),
        pytest.param([-1.4, -1.7, -1.4], "euler", id="euler"),
    ],
)
def test_round_trips_reproduce_the_matrix_within_the_documented_ROUNDTRIP_ATOL(rotvec, through):
    # The module docstring promises: "every round trip between matrix, rotation
    # vector, quaternion and Euler angles reproduces the matrix within
    # ROUNDTRIP_ATOL (4 eps, max-abs)".  These inputs, found by a scan of
    # rotation vectors with components k/10, gave 6, 5 and 5.6 eps before the
    # double-double rewrite of the conversions; kept as regression cases.
    M = rot.matrix_from_rotvec(rotvec)
    if through == "rotvec":
        back = rot.matrix_from_rotvec(rot.rotvec_from_matrix(M))
    elif through == "quat":
        back = rot.matrix_from_quat(rot.quat_from_matrix(M))
    else:
        back = rot.matrix_from_euler(*rot.euler_from_matrix(M))
    err = np.abs(back - M).max()
    assert err <= rot.ROUNDTRIP_ATOL, (
        f"round trip error {err / EPS:.2f} eps > ROUNDTRIP_ATOL = 4 eps"
    )


# ------------------------------------------------- tolerances, exact arithmetic


def test_rotation_tolerance_is_inclusive_for_both_deviations():
    # "within atol" means ≤: a matrix whose deviation equals atol is accepted.
    stretched = np.diag([1.0, 1.0, 1.5])  # max |R Rᵀ − 1| = 1.25, |det R − 1| = 0.5
    reflection = np.diag([1.0, 1.0, -1.0])  # max |R Rᵀ − 1| = 0, |det R − 1| = 2
    assert rot.is_rotation(stretched, atol=1.25)
    assert not rot.is_rotation(stretched, atol=np.nextafter(1.25, 0))
    assert rot.is_rotation(reflection, atol=2.0)
    assert not rot.is_rotation(reflection, atol=np.nextafter(2.0, 0))
    assert_array_equal(rot.check_rotation(stretched, atol=1.25), stretched)
    assert_array_equal(rot.check_rotation(reflection, atol=2.0), reflection)


def test_gimbal_lock_predicate_is_strict_at_atol():
    theta = 0.5
    assert not rot.euler_near_gimbal_lock(theta, atol=float(np.sin(theta)))
    assert rot.euler_near_gimbal_lock(theta, atol=float(np.nextafter(np.sin(theta), 1.0)))


@pytest.mark.parametrize(
    ("a", "b"), [(1.0, 2.0**-53), (1.0, -(2.0**-54)), (3.0, 1e-17), (1e16, 1.0), (0.1, 0.2)]
)
def test_two_sum_is_error_free(a, b):
    s, e = rot._two_sum(a, b)
    assert s == a + b
    assert Fraction(s) + Fraction(e) == Fraction(a) + Fraction(b)


@pytest.mark.parametrize(
    "parts",
    [
        (1.0, 2.0**-53, 2.0**-53, 0.0),
        (1.0, 2.0**-53, 0.0, 2.0**-53),
        (1.0, 0.0, 2.0**-53, 2.0**-53),
        (1.0, -(2.0**-54), -(2.0**-54), 0.0),
    ],
)
def test_compensated_sum_of_four_rounds_once(parts):
    # Each case loses its small parts to rounding when summed plainly.
    exact = float(sum(map(Fraction, parts)))
    assert ((parts[0] + parts[1]) + parts[2]) + parts[3] != exact
    assert rot._sum4(*parts) == exact


def test_compose_quat_normalises_quaternions_accepted_off_unit_length():
    q = np.array([0.6, 0.0, 0.8, 0.0]) * (1 + 32 * EPS)  # |q| − 1 within the tolerance
    out = rot.compose_quat(q, [1.0, 0.0, 0.0, 0.0])
    assert abs(np.linalg.norm(out) - 1.0) <= 2 * EPS
    assert_allclose(out, [0.6, 0.0, 0.8, 0.0], rtol=0, atol=2 * EPS)


def _half_turn_about_xy_direction(alpha: float) -> np.ndarray:
    c, s = np.cos(alpha), np.sin(alpha)
    return np.array([[2 * c * c - 1, 2 * c * s, 0], [2 * c * s, 2 * s * s - 1, 0], [0, 0, -1.0]])


@pytest.mark.parametrize("alpha", [0.0, 0.4, -1.3, np.pi / 2, 2.9])
def test_euler_angles_of_an_exact_sign_flip_are_theta_pi_and_reproduce_it(alpha):
    # θ = π exactly (R33 = −1, zeros exact): only ψ − φ is defined; split evenly.
    R = _half_turn_about_xy_direction(alpha)
    psi, theta, phi = rot.euler_from_matrix(R)
    assert np.isfinite([psi, theta, phi]).all()
    assert theta == np.pi
    assert psi == -phi
    assert np.abs(rot.matrix_from_euler(psi, theta, phi) - R).max() <= rot.ROUNDTRIP_ATOL


@pytest.mark.parametrize("e", [(0.5, 1e-300, 1.0), (-2.0, 3e-280, 0.25), (0.5, np.pi - 1e-15, 1.0)])
def test_euler_angles_are_recovered_one_by_one_close_to_gimbal_lock(e):
    # θ is a normal number, so ψ and φ are each defined and carried by the entries
    # of size θ (or π − θ): the split must come back, not only ψ ± φ.
    psi, theta, phi = rot.euler_from_matrix(rot.matrix_from_euler(*e))
    assert_allclose([psi, phi], [e[0], e[2]], rtol=0, atol=GIMBAL_SPLIT_ATOL)
    assert_allclose(theta, e[1], rtol=GIMBAL_SPLIT_ATOL, atol=0)


def test_quat_from_rotvec_keeps_every_component_of_a_tiny_vector():
    # Below 2**-27 the quaternion is (1, v/2) to within v²/48 relative: exact halves.
    for v in ([0.0, 0.0, 1e-9], [2e-9, -1e-9, 3e-9], [1e-300, -2e-300, 3e-300]):
        q = rot.quat_from_rotvec(v)
        assert q[0] == 1.0
        assert_array_equal(q[1:], 0.5 * np.array(v))


@pytest.mark.parametrize(
    "v",
    [[0.0, 0.0, 1e300], [0.0, -1e308, 0.0], [1e300, -1e299, 3e300], [1e300, 1e300, 0.0]],
)
def test_huge_rotation_vectors_give_unit_quaternions_along_their_axis(v):
    q = rot.quat_from_rotvec(v)
    assert np.isfinite(q).all()
    assert abs(np.linalg.norm(q) - 1.0) <= 4 * EPS
    u = np.asarray(v) / np.linalg.norm(np.asarray(v) / 1e300) / 1e300
    # the vector part is sin(φ/2) e_a: parallel to v, same sense as sin(φ/2)
    assert_allclose(np.cross(q[1:], u), 0.0, atol=4 * EPS)


#: The double-double norm and ratio promise about 2**-75 relative; 2**-70 leaves
#: room for the few roundings of the correction terms.
DD_RTOL = 2.0**-70


def _dd_cases():
    rng = np.random.default_rng(RNG_SEED + 7)
    u = rng.normal(size=(300, 3))
    scale = 10.0 ** rng.uniform(-100, 100, size=(300, 1))
    v = u * scale
    v[:100] = u[:100] * rng.uniform(3.0, 40.0, size=(100, 1))  # the angles of rotations
    return v


def test_double_double_norm_and_ratio_keep_2_to_the_minus_70():
    # _norm_dd: |v| = r + r_lo; _ratio_dd: num/|v| = q + q_lo; _times_dd: a (q + q_lo)
    # rounded once.  Exact references in mpmath.
    mpmath = pytest.importorskip("mpmath")
    v = _dd_cases()
    x, y, z = v.T.copy()
    r = np.sqrt(x * x + y * y + z * z)
    norm, splits = rot._norm_dd((x, y, z), r)
    assert_array_equal(norm[0] + norm[1], r)  # r split exactly
    num = np.sin(0.5 * r)
    ratio = rot._ratio_dd(num, norm, r)
    prod = rot._times_dd(x, splits[0], ratio)
    with mpmath.workdps(60):
        for i in range(len(r)):
            n = mpmath.sqrt(sum(mpmath.mpf(float(c)) ** 2 for c in v[i]))
            got = mpmath.mpf(float(r[i])) + mpmath.mpf(float(norm[2][i]))
            assert abs(got - n) <= DD_RTOL * n, ("norm", i, v[i])
            want = mpmath.mpf(float(num[i])) / n
            q = mpmath.mpf(float(ratio[0][i])) + mpmath.mpf(float(ratio[1][i]))
            assert abs(q - want) <= DD_RTOL * abs(want), ("ratio", i, v[i])
            exact = mpmath.mpf(float(x[i])) * want
            assert abs(mpmath.mpf(float(prod[i])) - exact) <= EPS * abs(exact), ("times", i)


def test_norm_dd_splits_every_part_on_one_grid_of_2_to_the_e_minus_25():
    # r in [2**e, 2**(e+1)): the splitter is 1.5 * 2**(e + 27), so every part and r
    # itself split into a multiple of g = 2**(e − 25), below 2**26 g, and a remainder
    # of at most g/2 (so the squares of the high parts and their sums are exact).
    rng = np.random.default_rng(RNG_SEED + 11)
    v = rng.normal(size=(200, 3)) * 10.0 ** rng.uniform(-100, 100, size=(200, 1))
    x, y, z = v.T.copy()
    r = np.sqrt(x * x + y * y + z * z)
    e = np.frexp(r)[1] - 1  # r = m 2**e with m in [1, 2)
    assert_array_equal(rot._grid_splitter(r), np.ldexp(1.5, e + 27))
    (r_hi, r_mid, _), splits = rot._norm_dd((x, y, z), r)
    for hi, lo in [(r_hi, r_mid), *splits]:
        units = np.ldexp(hi, 25 - e)  # hi / g, exact
        assert_array_equal(units, np.round(units))
        assert (np.abs(units) <= 2.0**26).all()
        assert (np.abs(lo) <= np.ldexp(0.5, e - 25)).all()


#: Angles whose sin φ, rebuilt as 2 cos(φ/2) sin(φ/2) from rounded halves, is 1.5 ulps
#: off (a scan of 6000 angles); sin φ itself is within half an ulp and more.
_SIN_HARD_ANGLES = [2.8203351711612186, 2.6753595900118, 0.006867616399000689, 0.029750776118053046]


@pytest.mark.parametrize("axis", range(3))
def test_matrix_from_rotvec_about_a_coordinate_axis_has_sin_phi_within_an_ulp(axis):
    # R_k(φ) of (2.30): the off-diagonal pair is ±sin φ.  |v| = φ exactly, so the
    # antisymmetric part, formed from sin φ itself (one rounding, a faithful library
    # sin), is within an ulp of the exact sin φ (mpmath).
    phi = np.array(_SIN_HARD_ANGLES)
    v = np.zeros((phi.size, 3))
    v[:, axis] = phi
    R = rot.matrix_from_rotvec(v)
    i, j = (axis + 1) % 3, (axis + 2) % 3
    mpmath = pytest.importorskip("mpmath")
    with mpmath.workdps(40):
        for n, p in enumerate(phi):
            exact = mpmath.sin(mpmath.mpf(float(p)))
            for got in (R[n, i, j], -R[n, j, i]):
                assert abs(mpmath.mpf(float(got)) - exact) <= math.ulp(float(exact)), (p, got)


def test_unit_quaternion_tolerance_is_inclusive():
    # |q| − 1 = _QUAT_NORM_ATOL exactly (64 eps) is accepted, 65 eps is not.
    g = np.array([0.5, 0.5, 0.5, 0.5])
    rot.matrix_from_quat(g * (1 + 64 * EPS))
    with pytest.raises(NotARotationError, match="not a unit quaternion"):
        rot.matrix_from_quat(g * (1 + 65 * EPS))


@pytest.mark.parametrize("k", [-60, -16, 16, 60])
def test_matrix_from_quat_divides_out_an_accepted_length(k):
    # A quaternion off unit length by k eps (accepted) gives the rotation of q/|q|:
    # its length is divided out exactly (1/|q|² = 1 − δ/(1 + δ)), so the matrix is
    # orthogonal to the forward accuracy of a unit quaternion, 4 eps.
    from identities.stability.rotation import error_in_eps, exact_matrix_from_quat

    q = np.array([0.36, -0.48, 0.64, 0.48]) * (1 + k * EPS)
    assert error_in_eps(rot.matrix_from_quat(q), exact_matrix_from_quat(q)) <= 4.0


def test_conversions_of_a_batch_larger_than_one_block_reach_every_row():
    # _BLOCK rows are converted at a time: the rows after the first block must be
    # converted too, each as alone.
    n = rot._BLOCK + 5
    rng = np.random.default_rng(RNG_SEED + 3)
    v = rng.normal(size=(n, 3))
    R = rot.matrix_from_rotvec(v)
    for i in (0, rot._BLOCK - 1, rot._BLOCK, n - 1):
        assert_allclose(R[i], rot.matrix_from_rotvec(v[i]), rtol=0, atol=VECTORISE_ATOL)
    back = rot.rotvec_from_matrix(R)
    assert_allclose(back[-1], rot.rotvec_from_matrix(R[-1]), rtol=0, atol=VECTORISE_ATOL)


# ------------------------------------------------- issue 16: the last known bad inputs


def test_batches_that_do_not_broadcast_raise_a_shape_error_listing_each_shape():
    with pytest.raises(ShapeError, match=r"compose: .* R_B_A \(2, 3, 3\), R_A_O \(3, 3, 3\)$"):
        rot.compose(np.stack([np.eye(3)] * 2), np.stack([np.eye(3)] * 3))
    # compose_quat names its own arguments, not those of the quat_multiply it calls
    one = np.array([1.0, 0.0, 0.0, 0.0])
    with pytest.raises(ShapeError, match=r"compose_quat: .* q_B_A \(2, 4\), q_A_O \(3, 4\)$"):
        rot.compose_quat(np.stack([one] * 2), np.stack([one] * 3))


def test_no_domain_says_batches_end_in_numpys_bare_value_error():
    text = " ".join(
        (getattr(rot, n).__doc__ or "") for n in rot.__all__ if callable(getattr(rot, n))
    )
    assert "bare ValueError" not in " ".join(text.split())


_ATOL_TAKERS = [
    pytest.param(lambda atol: rot.check_rotation(np.eye(3), atol=atol), id="check_rotation"),
    pytest.param(lambda atol: rot.is_rotation(np.eye(3), atol=atol), id="is_rotation"),
    pytest.param(lambda atol: rot.euler_near_gimbal_lock(0.1, atol=atol), id="gimbal_lock"),
]


@pytest.mark.parametrize("call", _ATOL_TAKERS)
@pytest.mark.parametrize(
    ("atol", "error", "match"),
    [
        pytest.param(np.nan, NonFiniteError, r"^atol must be finite; found nan", id="nan"),
        pytest.param(np.inf, NonFiniteError, r"^atol must be finite; found inf", id="inf"),
        pytest.param(
            -1e-9,
            NonPositiveParameterError,
            r"^atol must be >= 0 \(a tolerance\); got -1e-09$",
            id="negative",
        ),
        pytest.param("1e-9", ShapeError, r"^atol has dtype <U4; a real numeric", id="string"),
        pytest.param(None, ShapeError, r"^atol has dtype object", id="None"),
        pytest.param([1e-9, 1e-9], ShapeError, r"^atol must be a scalar; got shape", id="array"),
    ],
)
def test_a_tolerance_that_is_not_a_finite_number_ge_0_is_refused_naming_atol(
    call, atol, error, match
):
    with pytest.raises(error, match=match):
        call(atol)


def test_a_zero_tolerance_is_a_valid_exact_test():
    # the identity is exactly orthogonal; R3(0.3) is not, to the last bit
    assert_array_equal(rot.check_rotation(np.eye(3), atol=0.0), np.eye(3))
    assert bool(rot.is_rotation(np.eye(3), atol=0))
    assert not bool(rot.is_rotation(rot.R3(0.3) * (1 + EPS), atol=0.0))
    assert not bool(rot.euler_near_gimbal_lock(0.0, atol=0.0))  # |sin 0| < 0 is false


@pytest.mark.parametrize(
    "call",
    [
        pytest.param(
            lambda: rot.rotate_vector(rot.R3(np.pi / 4), [1.7e308, 1.7e308, 0]), id="rotate"
        ),
        pytest.param(
            lambda: rot.components_A_from_O(rot.R3(np.pi / 4), [1.7e308, -1.7e308, 0]),
            id="components",
        ),
        pytest.param(lambda: rot.quat_multiply([1e200, 1e200, 0, 0], [1e200, 0, 0, 0]), id="quat"),
    ],
)
def test_a_result_beyond_float64_is_a_result_overflow_error_not_inf(call):
    with pytest.raises(ResultOverflowError, match=r"^\w+: the result is not finite"):
        call()


def test_huge_but_representable_products_are_returned():
    # |r| = 1.7e308 turned by 90°: no component grows; quaternions of 2^500 multiply to 2^1000
    assert_array_equal(
        rot.rotate_vector(rot.R3(np.pi / 2).round(), [1.7e308, 0, 0]), [0, 1.7e308, 0]
    )
    big = 2.0**500
    assert_array_equal(rot.quat_multiply([big, 0, 0, 0], [0, big, 0, 0]), [0, big * big, 0, 0])
