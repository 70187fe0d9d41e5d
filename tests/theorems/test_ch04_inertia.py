"""Chapter 4 as properties: the inertia tensor, its transformations, Euler's equations.

Each test states a statement of the book and checks it for drawn particle
systems, tensors and motions (``mechanics.strategies``), the worked examples
pinned with ``@example``.  Tolerances are multiples of eps times the natural
scale of the quantity (the trace of the tensor, the largest moment).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

from identities.properties.inertia import SUM_ATOL, parallel_axis_theorem_holds, points
from mechanics import dynamics as D
from mechanics import inertia as I
from mechanics import strategies as ms
from mechanics.errors import NonPhysicalInertiaError
from mechanics.rotation import EPS, R3

#: Principal moments against the moments a tensor was built from: the built
#: tensor carries ~4 eps·J3 of rounding from the rotation, the Jacobi moments
#: another ~4 eps·J3 (measured worst 3.4 eps over 1e5 tensors).
MOMENT_ATOL = 16 * EPS

#: DOP853 at rtol = 1e-12: the drift of T and |L|² over 8 turns stays near the
#: tolerance times the number of steps; 1e-9 relative allows that with margin.
CONSERVATION_RTOL = 1e-9

#: Regimes of principal_moments without a needle-thin body, whose fast
#: rotation about the thin axis makes the integration stiff and slow.
NON_THIN = tuple(r for r in ms.PRINCIPAL_MOMENT_REGIMES if r not in ("thin", "wide-scales"))


# ------------------------------------------------------------ parallel axes


@given(ms.particle_systems(max_particles=6), points)
@example(
    ms.ParticleSystem(np.ones(2), np.array([[1.0, 0, 0], [-1.0, 0, 0]]), np.zeros((2, 3))),
    np.array([0.0, 0.0, 5.0]),
)
@example(  # found by the explore profile: |C|² = 7e-326 underflows to 0 in float64
    ms.ParticleSystem(np.array([1e-6, 1e6]), np.zeros((2, 3)), np.zeros((2, 3))),
    np.array([0.0, 0.0, 2.7229738264047844e-163]),
)
def test_parallel_axis_theorem_holds_about_any_point_4_38(system, C):
    parallel_axis_theorem_holds(system, C)  # stated in identities.properties.inertia


@given(ms.rigid_bodies(), points, points)
def test_transfer_between_two_points_goes_through_G(body, A, B):
    # J_B − J_A = m(|b|² 1 − b bᵀ) − m(|a|² 1 − a aᵀ), a, b from G: the tensor
    # about any point follows from the one about any other.
    m, J_G, G = body
    J_A = I.parallel_axis(J_G, m, A - G)
    J_B = I.parallel_axis(J_G, m, B - G)
    a, b = A - G, B - G
    pa = m * (a @ a * np.eye(3) - np.outer(a, a))
    pb = m * (b @ b * np.eye(3) - np.outer(b, b))
    scale = np.trace(J_G) + m * (a @ a + b @ b)
    assert np.abs((J_B - J_A) - (pb - pa)).max() <= SUM_ATOL * scale


@given(ms.rigid_bodies(), points)
def test_the_triangle_inequality_holds_about_every_point(body, C):
    m, J_G, G = body
    # allow_singular: at 1e10 sizes from G the moment about the line GC is 1e-20
    # of the others, zero to rounding; the claim here is the triangle inequality.
    J_C = I.parallel_axis(J_G, m, C - G)
    I.check_inertia(J_C, about_centre_of_mass=False, allow_singular=True)


# ------------------------------------------------------------ rotation (4.11)


@given(ms.particle_systems(max_particles=6), ms.rotation_matrices())
def test_rotating_the_particles_rotates_the_tensor_4_11(system, R_A_O):
    m, r_A = system.m, system.r
    G = (m[:, None] * r_A).sum(0) / m.sum()
    r_A = r_A - G  # about G, so the scale is the body's own
    r_O = r_A @ R_A_O  # r^O = ^O R^A r^A: rows times ^A R^O
    J_A = I.inertia_tensor(m, r_A, about=np.zeros(3))
    J_O = I.inertia_tensor(m, r_O, about=np.zeros(3))
    scale = float((m * (r_A * r_A).sum(-1)).sum())
    assert np.abs(I.rotate_inertia(J_A, R_A_O) - J_O).max() <= SUM_ATOL * scale


@given(ms.principal_moments(), st.floats(-math.pi, math.pi))
def test_example_4_2_product_of_inertia_4_31(moments, psi):
    J_O = I.rotate_inertia(np.diag(moments), R3(psi))
    D_xy = -J_O[0, 1]
    expected = -math.cos(psi) * math.sin(psi) * (moments[0] - moments[1])
    assert abs(D_xy - expected) <= 8 * EPS * moments[2]


# ---------------------------------------------------------------- principal axes


def _projectors(moments, R, rtol):
    scale = moments[2]
    groups = [[0]]
    for i in (1, 2):
        if moments[i] - moments[i - 1] <= rtol * scale:
            groups[-1].append(i)
        else:
            groups.append([i])
    P = np.zeros((3, 3, 3))
    for g in groups:
        Pg = sum(np.outer(R[j], R[j]) for j in g)
        for j in g:
            P[j] = Pg
    return P, groups


@given(ms.principal_moments(), ms.rotation_matrices())
@example(np.array([1.0, 1.0, 1.0]), np.eye(3))
@example(np.array([1.0, 1.0 + 1e-15, 1.5]), R3(0.3))
def test_principal_axes_diagonalise_and_agree_with_eigh_by_subspaces_4_14(moments, R_true):
    J = I.rotate_inertia(np.diag(moments), R_true)
    J3 = moments[2]
    got, R = I.principal_axes(J)
    assert np.all(np.diff(got) >= 0)
    assert np.abs(got - moments).max() <= MOMENT_ATOL * J3
    assert abs(np.linalg.det(R) - 1.0) <= 8 * EPS
    assert np.abs(R @ R.T - np.eye(3)).max() <= 16 * EPS
    rebuilt = I.rotate_inertia(np.diag(got), R)
    assert np.abs(rebuilt - J).max() <= MOMENT_ATOL * J3
    # Subspaces, not axes: compare the projectors with numpy's eigh, grouping
    # moments closer than √eps; each projector is then known to eps·J3/gap.
    w, V = np.linalg.eigh(J)
    P_ours, groups = _projectors(got, R, I.SUBSPACE_RTOL)
    P_eigh, groups_eigh = _projectors(w, V.T, I.SUBSPACE_RTOL)
    assume(groups == groups_eigh)  # a gap right at the threshold may split either way
    gaps = [got[g[0]] - got[g[0] - 1] for g in groups[1:]]
    gap = min(gaps) if gaps else J3
    assert np.abs(P_ours - P_eigh).max() <= 64 * EPS * J3 / gap


@given(ms.inertia_tensors())
def test_principal_subspaces_are_orthogonal_projectors_that_resolve_the_identity(J):
    _moments, P = I.principal_subspaces(J)
    for Pi in P:
        assert np.abs(Pi @ Pi - Pi).max() <= 64 * EPS
        assert np.abs(Pi - Pi.T).max() <= 8 * EPS
    # A subspace of dimension k appears k times (once per moment in it), and
    # its projector has trace k: Σ_i P_i / tr P_i sums each subspace once.
    ranks = np.trace(P, axis1=-2, axis2=-1)
    assert np.all(np.abs(ranks - np.round(ranks)) <= 64 * EPS)
    total = (P / np.round(ranks)[:, None, None]).sum(0)
    assert np.abs(total - np.eye(3)).max() <= 64 * EPS


# --------------------------------------------------------------- Example 4.1


@given(ms.rigid_bodies(tensors=ms.inertia_tensors()))
@example(ms.RigidBody(1.0, np.eye(3), np.zeros(3)))
@example(ms.RigidBody(2.0, np.diag([1.0, 2.0, 3.0]), np.zeros(3)))
def test_every_inertia_tensor_is_realised_by_four_particles_of_mass_m_over_4(body):
    m, J, _ = body
    masses, r = I.four_particle_realisation(m, J)
    assert np.all(masses == m / 4)
    size = math.sqrt(np.trace(J) / m)
    assert np.abs(masses @ r).max() <= 16 * EPS * m * size  # G stays at the origin
    J4 = I.inertia_tensor(masses, r, about=np.zeros(3))
    assert np.abs(J4 - J).max() <= SUM_ATOL * np.trace(J)


# ------------------------------------------------------------- check_inertia


@given(ms.principal_moments(), ms.rotation_matrices(), st.floats(1e-10, 1.0))
def test_check_inertia_rejects_an_asymmetric_tensor(moments, R, eps_rel):
    J = I.rotate_inertia(np.diag(moments), R)
    J[0, 1] += eps_rel * moments[2]
    with pytest.raises(NonPhysicalInertiaError, match="not symmetric"):
        I.check_inertia(J)


@given(ms.principal_moments(), ms.rotation_matrices(), st.floats(1e-10, 1.0))
def test_check_inertia_rejects_a_negative_moment(moments, R, delta):
    J = I.rotate_inertia(np.diag([-delta * moments[2], moments[1], moments[2]]), R)
    with pytest.raises(NonPhysicalInertiaError, match="not positive semidefinite"):
        I.check_inertia(J)


@given(ms.principal_moments(), ms.rotation_matrices(), st.floats(1e-10, 1.0))
def test_check_inertia_rejects_a_broken_triangle_inequality(moments, R, delta):
    J1, J2, _ = moments
    J = I.rotate_inertia(np.diag([J1, J2, (J1 + J2) * (1 + delta)]), R)
    with pytest.raises(NonPhysicalInertiaError, match="triangle inequality") as info:
        I.check_inertia(J)
    assert "J1 + J2 - J3 = -" in str(info.value)


@given(ms.inertia_tensors())
def test_check_inertia_accepts_every_drawn_tensor_unchanged(J):
    np.testing.assert_array_equal(I.check_inertia(J), J)


# ----------------------------------------------------------- Euler's equations


@settings(max_examples=20)
@given(
    ms.principal_moments(min_scale=0.1, max_scale=10.0, regimes=NON_THIN),
    # Components 0 or at least 1e-6 in size: subnormal rates make scipy's
    # error norm divide 0 by 0.
    st.tuples(*(st.one_of(st.just(0.0), st.floats(1e-6, 1.0), st.floats(-1.0, -1e-6)),) * 3).map(
        np.array
    ),
)
@example(np.array([1.0, 2.0, 2.5]), np.array([0.01, 1.0, 0.01]))  # near the middle axis
def test_torque_free_euler_equations_conserve_T_and_L_4_47(J, w0):
    assume(np.abs(w0).max() > 0.05)
    zero = np.zeros(3)
    turns = 8.0
    t_end = turns * 2 * math.pi / float(np.linalg.norm(w0))
    sol = solve_ivp(
        lambda t, w: D.euler_equations_rhs(J, w, zero),
        (0.0, t_end),
        w0,
        method="DOP853",
        rtol=1e-12,
        atol=1e-14,
    )
    assert sol.success
    w = sol.y.T
    T = 0.5 * (J * w * w).sum(-1)
    L2 = ((J * w) ** 2).sum(-1)
    assert np.abs(T / T[0] - 1).max() <= CONSERVATION_RTOL
    assert np.abs(L2 / L2[0] - 1).max() <= CONSERVATION_RTOL
