"""Chapter 2 of Essén (1996), kinematics of rigid bodies, as property tests.

Each test states one book statement for every input hypothesis draws, with the
book's worked examples pinned on top.  Inputs come from small local strategies
(bounded floats, no NaN); rotation matrices are built from Euler angles, whose
conversion is pinned against scipy in ``tests/mechanics/test_rotation.py``.
Matrix rates are exact, by the product rule with derivatives of (2.30) worked
out by hand, so that no finite-difference error hides a wrong sign.
"""

from __future__ import annotations

from functools import partial

import numpy as np
from hypothesis import example, given
from hypothesis import strategies as st

from identities.properties.rotation import is_orthogonal_with_det_one
from mechanics import kinematics as kin
from mechanics import rotation as rot
from mechanics._floats import EPS

# A rotation matrix entry from sin/cos products carries ≲ 8 eps (measured 6.3 eps
# against an 80-bit reference); a product of two such matrices doubles it.
MATRIX_ATOL = 16 * EPS

# Exact rates: Ṙ has entries that are sums of a few products of numbers of size
# ≤ Σ|rates|, each rounded; Ṙ Rᵀ and the chain rule multiply that by ~3 each.
RATE_ATOL = 64 * EPS

# Vectors of size ≤ 10√3 turned or crossed: a few roundings of numbers ≤ 100.
VECTOR_ATOL = 64 * EPS


# ------------------------------------------------------------------- strategies

finite = partial(st.floats, allow_nan=False, allow_infinity=False)
angles = finite(-np.pi, np.pi)
middle_angles = finite(0.0, np.pi)
away_from_lock = finite(0.1, np.pi - 0.1)
rates = finite(-5.0, 5.0)
coords = finite(-10.0, 10.0)
vectors = st.tuples(coords, coords, coords).map(np.array)
small_vectors = st.tuples(finite(-1.0, 1.0), finite(-1.0, 1.0), finite(-1.0, 1.0)).map(np.array)
eulers = st.tuples(angles, middle_angles, angles)
euler_rates = st.tuples(rates, rates, rates)


@st.composite
def unit_vectors(draw):
    """A direction from its spherical angles: unit length by construction."""
    polar, azimuth = draw(finite(0.0, np.pi)), draw(angles)
    return np.array(
        [np.sin(polar) * np.cos(azimuth), np.sin(polar) * np.sin(azimuth), np.cos(polar)]
    )


# |ω| ≥ 1e-3 by construction: a direction times a magnitude.
nonzero_vectors = st.builds(lambda e, m: e * m, unit_vectors(), finite(1e-3, 10.0))


@st.composite
def non_collinear_triples(draw):
    """Three points r1, r1 + L1 u, r1 + L2 (cos α u + sin α w) with u ⟂ w, α ∈ [0.3, π − 0.3]."""
    r1 = draw(vectors)
    u = draw(unit_vectors())
    helper = np.eye(3)[np.argmin(np.abs(u))]
    w = np.cross(u, helper)
    w /= np.linalg.norm(w)
    turn = draw(angles)  # w turned about u: any direction normal to u
    w = np.cos(turn) * w + np.sin(turn) * np.cross(u, w)
    L1, L2 = draw(finite(0.5, 3.0)), draw(finite(0.5, 3.0))
    alpha = draw(finite(0.3, np.pi - 0.3))
    return np.stack([r1, r1 + L1 * u, r1 + L2 * (np.cos(alpha) * u + np.sin(alpha) * w)])


# --------------------------------------------------------------- local helpers


def _basic(c, s, which):
    rows = {
        # (2.30) and their derivatives d/dα, worked out by hand.
        "R1": ((1, 0, 0), (0, c, s), (0, -s, c)),
        "dR1": ((0, 0, 0), (0, -s, c), (0, -c, -s)),
        "R3": ((c, s, 0), (-s, c, 0), (0, 0, 1)),
        "dR3": ((-s, c, 0), (-c, -s, 0), (0, 0, 0)),
    }[which]
    return np.array(rows, dtype=float)


def _euler_matrix_and_rate(euler, rate):
    """^A R^O = R3(φ) R1(θ) R3(ψ) and its exact time derivative (product rule)."""
    (psi, theta, phi), (psid, thetad, phid) = euler, rate
    A, dA = _basic(np.cos(phi), np.sin(phi), "R3"), _basic(np.cos(phi), np.sin(phi), "dR3")
    B, dB = _basic(np.cos(theta), np.sin(theta), "R1"), _basic(np.cos(theta), np.sin(theta), "dR1")
    C, dC = _basic(np.cos(psi), np.sin(psi), "R3"), _basic(np.cos(psi), np.sin(psi), "dR3")
    return A @ B @ C, phid * dA @ B @ C + thetad * A @ dB @ C + psid * A @ B @ dC


def _book_antisym(v):
    """The antisymmetric matrix of (2.39) and (2.52)."""
    v1, v2, v3 = v
    return np.array([[0.0, v3, -v2], [-v3, 0.0, v1], [v2, -v1, 0.0]])


def _scale(*xs):
    return 1.0 + sum(float(np.abs(x).sum()) for x in xs)


# ------------------------------------------------------ 2.1–2.3: rotations, (2.1)


@given(eulers, vectors, vectors)
@example((np.pi / 2, 0.0, 0.0), np.array([1.0, 0, 0]), np.array([0.0, 1, 0]))  # Example 2.1
def test_rotation_preserves_distances(euler, r1, r2):
    # (2.1): a rotation is a rigid displacement, |r'_i − r'_j| = |r_i − r_j|.
    R_A_O = rot.matrix_from_euler(*euler)
    turned = rot.rotate_vector(R_A_O, np.stack([r1, r2]))
    d0, d1 = np.linalg.norm(r1 - r2), np.linalg.norm(turned[0] - turned[1])
    assert abs(d1 - d0) <= VECTOR_ATOL * _scale(r1, r2)
    # and the components in the new basis have the same length (2.20)
    assert abs(
        np.linalg.norm(rot.components_A_from_O(R_A_O, r1)) - np.linalg.norm(r1)
    ) <= VECTOR_ATOL * _scale(r1)


@given(eulers)
def test_rotation_matrices_are_orthogonal_with_inverse_equal_to_transpose(euler):
    # (2.15), (2.16): ^A R^O (^A R^O)ᵀ = 1, det = +1 (identities.properties.rotation
    # states it for every way of building an attitude, as a catalogue property)
    is_orthogonal_with_det_one(rot.matrix_from_euler(*euler))


@given(unit_vectors(), finite(0.0, np.pi), vectors)
@example(np.array([0.0, 0, 1]), np.pi / 2, np.array([1.0, 0, 0]))  # e1 → e2
def test_rotation_operator_turns_vectors_by_the_cone_formula_2_23(e, phi, r):
    # r' = (r·e)e + cos φ (e × r) × e + sin φ e × r, the right-hand turn about e.
    book = (r @ e) * e + np.cos(phi) * np.cross(np.cross(e, r), e) + np.sin(phi) * np.cross(e, r)
    turned = rot.rotate_vector(rot.matrix_from_axis_angle(e, phi), r)
    assert np.abs(turned - book).max() <= VECTOR_ATOL * _scale(r)
    # the axis is left where it is
    assert np.abs(rot.rotate_vector(rot.matrix_from_rotvec(phi * e), e) - e).max() <= MATRIX_ATOL


@given(unit_vectors(), finite(0.0, np.pi))
def test_rotation_matrix_of_a_rotation_vector_is_the_split_form_2_29(e, phi):
    # cos φ 1 + sin φ (antisymmetric) + (1 − cos φ) e eᵀ, with 1 − cos φ = 2 sin²(φ/2).
    book = (
        np.cos(phi) * np.eye(3)
        + np.sin(phi) * _book_antisym(e)
        + 2 * np.sin(phi / 2) ** 2 * np.outer(e, e)
    )
    assert np.abs(rot.matrix_from_rotvec(phi * e) - book).max() <= MATRIX_ATOL


# ------------------------------------------------------ 2.4: Euler angles, (2.35)


@given(eulers)
@example((0.0, 0.0, 0.0))
@example((np.pi / 2, np.pi / 2, np.pi / 2))
def test_euler_matrix_written_out_2_36_is_the_product_2_35(euler):
    psi, theta, phi = euler
    cf, sf, ct, st_, cp, sp = (
        np.cos(phi),
        np.sin(phi),
        np.cos(theta),
        np.sin(theta),
        np.cos(psi),
        np.sin(psi),
    )
    written_out = np.array(
        [
            [cf * cp - sf * ct * sp, cf * sp + sf * ct * cp, sf * st_],
            [-sf * cp - cf * ct * sp, -sf * sp + cf * ct * cp, cf * st_],
            [st_ * sp, -st_ * cp, ct],
        ]
    )
    product = rot.R3(phi) @ rot.R1(theta) @ rot.R3(psi)
    assert np.abs(written_out - product).max() <= MATRIX_ATOL
    assert np.abs(rot.matrix_from_euler(*euler) - written_out).max() <= MATRIX_ATOL


@given(angles, angles)
def test_turns_about_one_axis_commute_and_add_2_37(a, b):
    assert np.abs(rot.R3(a) @ rot.R3(b) - rot.R3(b) @ rot.R3(a)).max() <= MATRIX_ATOL
    assert np.abs(rot.R3(a) @ rot.R3(b) - rot.R3(a + b)).max() <= MATRIX_ATOL


@given(
    away_from_lock,
    away_from_lock,
    angles,
    small_vectors,
    small_vectors,
    st.sampled_from([1e-2, 1e-3, 1e-4]),
)
@example(
    np.pi / 2, np.pi / 2, 0.0, np.array([0.0, 0, 1]), np.array([1.0, 0, 0]), 1e-3
)  # figure 2.7
def test_finite_rotations_do_not_commute_but_small_ones_do_to_first_order(
    theta, phi, psi, a, b, eps
):
    # (2.38): R3(φ) R1(θ) R3(ψ) ≠ R1(θ) R3(φ) R3(ψ).  By hand, entry (1, 3) of
    # R3(φ)R1(θ) − R1(θ)R3(φ) is sin φ sin θ, and the orthogonal R3(ψ) keeps the
    # Frobenius norm, so the two differ by at least |sin φ sin θ| ≥ sin²(0.1).
    lhs = rot.R3(phi) @ rot.R1(theta) @ rot.R3(psi)
    rhs = rot.R1(theta) @ rot.R3(phi) @ rot.R3(psi)
    assert np.linalg.norm(lhs - rhs) >= abs(np.sin(phi) * np.sin(theta)) - MATRIX_ATOL

    # (2.42): for rotation vectors εa, εb the commutator is ε² [K_a, K_b] + O(ε³),
    # K the antisymmetric matrix of (2.39).  R(x) = exp(K(x)) (Rodrigues), so the
    # remainder is at most Σ_{k≥3} 2 s^k / k! ≤ e^s s³ / 3 with s = ε(|a| + |b|).
    commutator = rot.matrix_from_rotvec(eps * a) @ rot.matrix_from_rotvec(
        eps * b
    ) - rot.matrix_from_rotvec(eps * b) @ rot.matrix_from_rotvec(eps * a)
    Ka, Kb = _book_antisym(a), _book_antisym(b)
    s = eps * (np.linalg.norm(a) + np.linalg.norm(b))
    bound = np.exp(s) * s**3 / 3 + 4 * MATRIX_ATOL
    assert np.abs(commutator - eps**2 * (Ka @ Kb - Kb @ Ka)).max() <= bound
    # so it is second order: |commutator| ≤ ε² |a||b| · 2 + remainder
    assert np.abs(commutator).max() <= 2 * eps**2 * np.linalg.norm(a) * np.linalg.norm(b) + bound


@given(small_vectors, small_vectors, st.sampled_from([1e-2, 1e-3, 1e-5]))
def test_small_rotations_add_like_vectors_to_first_order_2_39_2_42(a, b, eps):
    # R(δφ) = 1 + K(δφ) + O(δφ²) (2.39) and R(δφ1) R(δφ2) = R(δφ1 + δφ2) + O(δφ²)
    # (2.42).  With R = exp(K): |e^A − 1 − A| ≤ s² e^s / 2 and
    # |e^A e^B − e^{A+B}| ≤ s² e^s for s = |A| + |B|.
    s = eps * (np.linalg.norm(a) + np.linalg.norm(b))
    small = rot.matrix_from_rotvec(eps * a)
    assert (
        np.abs(small - np.eye(3) - _book_antisym(eps * a)).max()
        <= s**2 * np.exp(s) / 2 + MATRIX_ATOL
    )
    product = small @ rot.matrix_from_rotvec(eps * b)
    assert (
        np.abs(product - rot.matrix_from_rotvec(eps * (a + b))).max()
        <= s**2 * np.exp(s) + 2 * MATRIX_ATOL
    )


# ------------------------------------------- 2.5: angular velocity, (2.46)–(2.69)


@given(eulers, euler_rates)
@example((0.4, 0.0, 0.0), (2.0, 0.0, 0.0))  # Example 2.2
def test_angular_velocity_matrix_is_antisymmetric_2_51(euler, rate):
    R, Rdot = _euler_matrix_and_rate(euler, rate)
    Omega = Rdot @ R.T  # (2.46)
    tol = RATE_ATOL * _scale(rate)
    assert np.abs(Omega + Omega.T).max() <= tol
    # and it is the matrix (2.52) of the ω the library reads off it
    w_A = kin.angular_velocity_from_matrix_rate(R, Rdot)
    assert np.abs(Omega - _book_antisym(w_A)).max() <= tol


@given(eulers, euler_rates)
@example((0.4, 0.0, 0.0), (2.0, 0.0, 0.0))  # Example 2.2: ω = ψ̇ e3
def test_eulers_kinematic_equations_2_69_follow_from_the_matrix_rate(euler, rate):
    R, Rdot = _euler_matrix_and_rate(euler, rate)
    from_matrix = kin.angular_velocity_from_matrix_rate(R, Rdot)
    from_2_69 = kin.angular_velocity_from_euler_rates(*euler, *rate)
    assert np.abs(from_matrix - from_2_69).max() <= RATE_ATOL * _scale(rate)


@given(eulers, euler_rates)
def test_angular_velocity_is_the_sum_of_the_three_euler_turns_2_65(euler, rate):
    # ω = ψ̇ e^C_3 + θ̇ e^B_1 + φ̇ e^A_3, each basis vector a row of its matrix (2.31)–(2.33).
    psi, theta, phi = euler
    R_C_O = rot.R3(psi)
    R_B_O = rot.R1(theta) @ R_C_O
    R_A_O = rot.R3(phi) @ R_B_O
    w_O = rate[0] * R_C_O[2] + rate[1] * R_B_O[0] + rate[2] * R_A_O[2]
    R, Rdot = _euler_matrix_and_rate(euler, rate)
    assert np.abs(
        kin.angular_velocity_from_matrix_rate(R, Rdot, basis="O") - w_O
    ).max() <= RATE_ATOL * _scale(rate)


@given(eulers, euler_rates, vectors, vectors)
def test_derivative_in_the_observer_frame_adds_omega_cross_r_2_61(euler, rate, r_A, u_A):
    # r(t) with body components r^A + t u^A: r^O = (^A R^O)ᵀ r^A, so
    # ^O d/dt r = Ṙᵀ r^A + Rᵀ u^A must equal ^A d/dt r + ω × r = Rᵀ u^A + ω × r.
    R, Rdot = _euler_matrix_and_rate(euler, rate)
    w_O = kin.angular_velocity_from_matrix_rate(R, Rdot, basis="O")
    observed = Rdot.T @ r_A + R.T @ u_A
    assert np.abs(observed - (R.T @ u_A + np.cross(w_O, R.T @ r_A))).max() <= RATE_ATOL * _scale(
        rate
    ) * _scale(r_A, u_A)


@given(eulers, euler_rates, eulers, euler_rates)
@example(
    (0.3, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 0.0, 0.5), (0.0, 0.0, 2.0)
)  # two turns about e3 add
def test_angular_velocities_add_across_intermediate_frames(euler_B, rate_B, euler_A, rate_A):
    # (2.63): ^O ω^A = ^O ω^B + ^B ω^A.  R_B_O(t), R_A_B(t) have Euler angles linear
    # in t; R_A_O = R_A_B R_B_O and its rate follows by the product rule.
    R_B_O, Rdot_B_O = _euler_matrix_and_rate(euler_B, rate_B)
    R_A_B, Rdot_A_B = _euler_matrix_and_rate(euler_A, rate_A)
    R_A_O = R_A_B @ R_B_O
    Rdot_A_O = Rdot_A_B @ R_B_O + R_A_B @ Rdot_B_O
    w_OA = kin.angular_velocity_from_matrix_rate(R_A_O, Rdot_A_O, basis="O")
    w_OB = kin.angular_velocity_from_matrix_rate(R_B_O, Rdot_B_O, basis="O")
    w_BA_in_A = kin.angular_velocity_from_matrix_rate(R_A_B, Rdot_A_B)  # components in A
    w_BA = R_A_O.T @ w_BA_in_A  # the same vector in O components (2.20)
    assert np.abs(w_OA - (w_OB + w_BA)).max() <= 2 * RATE_ATOL * _scale(rate_A, rate_B)


# ------------------------------------------ 2.6: velocities of points, (2.70)–(2.96)


@given(eulers, euler_rates, vectors, vectors)
def test_connection_formula_gives_the_velocity_of_every_body_point_2_72(euler, rate, v_A, a_A):
    # r_i(t) = r_A(t) + (^A R^O(t))ᵀ a^A_i (2.71), a^A_i constant: differentiating
    # gives v_i = v_A + Ṙᵀ a^A, which must be v_A + ω × a_i (2.72), (2.73).
    R, Rdot = _euler_matrix_and_rate(euler, rate)
    w_O = kin.angular_velocity_from_matrix_rate(R, Rdot, basis="O")
    exact = v_A + Rdot.T @ a_A
    assert np.abs(kin.point_velocity(v_A, w_O, R.T @ a_A) - exact).max() <= RATE_ATOL * _scale(
        rate
    ) * _scale(a_A, v_A)


@given(vectors, vectors, vectors)
def test_connection_formula_keeps_body_distances_fixed(v_A, omega, r_AB):
    # d/dt |AB|² = 2 (v_B − v_A) · AB = 2 (ω × AB) · AB = 0, as (2.1) requires.
    v_B = kin.point_velocity(v_A, omega, r_AB)
    assert abs((v_B - v_A) @ r_AB) <= VECTOR_ATOL * _scale(omega) * _scale(r_AB) ** 2
    # (2.74): the same velocity written with BA × ω
    assert np.abs(v_B - (v_A + np.cross(-r_AB, omega))).max() <= VECTOR_ATOL * _scale(
        omega, r_AB, v_A
    )


@given(vectors, vectors, vectors)
@example(np.array([1.0, 1, -3]), np.array([1.0, 0, -1]), np.array([0.0, 2, -1]))  # Example 2.3 b
def test_velocity_along_omega_is_the_same_for_every_body_point(v_A, omega, r_AB):
    # (2.84), (2.91): ω · v_B = ω · v_A.
    v_B = kin.point_velocity(v_A, omega, r_AB)
    assert abs(omega @ v_B - omega @ v_A) <= VECTOR_ATOL * _scale(omega) * _scale(
        v_A, r_AB
    ) * _scale(omega)


@given(vectors, nonzero_vectors, finite(-10.0, 10.0))
@example(np.array([1.0, 1, -3]), np.array([1.0, 0, -1]), 0.0)  # Example 2.3 c, d
def test_points_on_the_instantaneous_axis_move_along_omega(v_A, omega, s):
    # (2.77)–(2.80): C = A + (ω × v_A)/ω² and every point C + s ω moves with
    # v_C = (v_A · e_ω) e_ω, parallel to ω.
    r_AC, v_C = kin.instantaneous_axis(v_A, omega)
    w2 = omega @ omega
    tol = VECTOR_ATOL * _scale(v_A) * _scale(omega) ** 2 / min(w2, 1.0)
    on_axis = kin.point_velocity(v_A, omega, r_AC + s * omega)
    assert np.abs(on_axis - v_C).max() <= tol
    assert np.abs(v_C - (v_A @ omega) / w2 * omega).max() <= tol
    assert np.abs(np.cross(v_C, omega)).max() <= tol * _scale(omega)


@given(
    st.tuples(coords, coords).map(np.array),
    st.tuples(coords, coords).map(np.array),
    st.one_of(finite(0.1, 10.0), finite(-10.0, -0.1)),
)
@example(
    np.array([5.0, 2.0]), np.array([3.0, 0.0]), -1.5
)  # a wheel rolling: C is the contact point
def test_plane_motion_has_an_instantaneous_centre_of_zero_velocity_2_95(r_A, v_A, omega_z):
    r_C = kin.instantaneous_centre_plane(r_A, v_A, omega_z)
    AC = np.append(r_C - r_A, 0.0)
    omega = np.array([0.0, 0.0, omega_z])
    v3 = np.append(v_A, 0.0)
    tol = VECTOR_ATOL * _scale(v_A) * _scale(omega) / abs(omega_z)
    assert np.abs(kin.point_velocity(v3, omega, AC)).max() <= tol
    # (2.96): v_A = AC × ω
    assert np.abs(np.cross(AC, omega) - v3).max() <= tol


@given(non_collinear_triples(), vectors, vectors)
@example(
    np.array([[0.0, 0, 1], [0, 2, 0], [1, 0, 1]]), np.array([1.0, 0, -1]), np.array([1.0, 1, -3])
)  # Example 2.3: ω = (1, 0, −1) v/ℓ
def test_three_non_collinear_points_fix_the_velocity_state_2_85(r, omega, v_1):
    # (2.85), (2.86): v_i = v_1 + ω × (r_i − r_1) for three points determines ω.
    v = kin.point_velocity(v_1, omega, r - r[0])
    w_fit, v_c, residual = kin.rigid_velocity_from_points(r, v)
    d = r - r.mean(axis=0)
    J = (d * d).sum() * np.eye(3) - d.T @ d
    tol = 64 * EPS * np.linalg.cond(J) * _scale(omega, v_1) * _scale(r)
    assert np.abs(w_fit - omega).max() <= tol
    assert np.abs(
        v_c - kin.point_velocity(v_1, omega, r.mean(axis=0) - r[0])
    ).max() <= tol * _scale(r)
    assert residual <= tol * _scale(r)
