"""Chapter 2.1–2.5 (first part): rotation matrices, rotation of vectors, Euler angles,
infinitesimal rotations.  Equations (2.1)–(2.44).

Each check builds both sides from the book's definitions (:mod:`identities.verify.symbolic`),
reduces the difference with a named strategy, rejects a wrong variant with the same
strategy, and confirms that :mod:`mechanics` computes the same thing.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from identities.verify.catalogue import check
from identities.verify.proof import Derivation
from identities.verify.symbolic import (
    R1,
    R2,
    R3,
    cross,
    euler_matrix,
    floats,
    general_rotation,
    omega_matrix,
    rotvec_matrix,
    rotvec_matrix_explicit,
    unit_vector,
    vec,
)
from mechanics import rotation as rot
from mechanics._floats import EPS

#: mechanics against a float evaluation of the same closed form: both sides are
#: sums of ≤ 3 products of correctly rounded trig values, so ≤ 8 eps apart.
CODE_ATOL = 8 * EPS

a, b, c, d = sp.symbols("a b c d", real=True)
u, v = sp.symbols("u v", real=True)
psi, theta, phi, alpha = sp.symbols("psi theta phi alpha", real=True)
x1, x2, x3 = sp.symbols("x1 x2 x3", real=True)
G = general_rotation(a, b, c, d)


@check(
    "eq2.1",
    "Translations and rotations keep all distances in a body",
    kind="proof",
    covers=("eq2.1", "eq2.2"),
    defines=("eq2.3", "eq2.4"),
    statement="|r'_i - r'_j| = |r_i - r_j| for r' = R r + d, R any rotation (2.1)-(2.2)",
)
def distances_preserved(d_: Derivation) -> None:
    ri = vec(*sp.symbols("p1 p2 p3", real=True))
    rj = vec(*sp.symbols("q1 q2 q3", real=True))
    dd = vec(*sp.symbols("d1 d2 d3", real=True))
    move = lambda r, M: M.T * r + dd  # noqa: E731  (active operator: the transpose)
    dist2 = lambda x, y: ((x - y).T * (x - y))[0]  # noqa: E731
    d_.note("A general rotation: Euler–Rodrigues matrix of (a, b, c, d) ≠ 0", G)
    d_.prove_equal(
        dist2(move(ri, G), move(rj, G)),
        dist2(ri, rj),
        strategy="cancel",
        claim="|R r_i + d - (R r_j + d)|^2 = |r_i - r_j|^2 for every rotation R",
    )
    stretch = sp.diag(1, 1, 2)
    d_.reject(
        dist2(move(ri, stretch), move(rj, stretch)),
        dist2(ri, rj),
        strategy="cancel",
        claim="a stretch diag(1, 1, 2) keeps distances",
    )


@check(
    "eq2.16",
    "Rotation matrices are orthogonal with det +1: (R)^-1 = R^T",
    kind="proof",
    covers=("eq2.13", "eq2.14", "eq2.15", "eq2.16"),
    defines=("eq2.5", "eq2.6", "eq2.7", "eq2.8", "eq2.9", "eq2.10", "eq2.12"),
    statement="R R^T = R^T R = 1 and det R = 1 for the Euler matrix (2.35), the "
    "rotation-vector matrix (2.29) and a general rotation",
)
def orthogonality(d: Derivation) -> None:
    E = euler_matrix(psi, theta, phi)
    d.prove_equal(E * E.T, sp.eye(3), strategy="tan_half", claim="Euler matrix: R R^T = 1 (2.16)")
    d.prove_equal(
        E.T * E,
        sp.eye(3),
        strategy="tan_half",
        claim="Euler matrix: R^T R = 1, so R^-1 = R^T (2.14)-(2.15)",
    )
    d.prove_equal(E.det(), 1, strategy="tan_half", claim="Euler matrix: det R = 1")
    P = rotvec_matrix(alpha, unit_vector(u, v))
    d.prove_equal(P * P.T, sp.eye(3), strategy="tan_half", claim="(2.29), any unit axis: R R^T = 1")
    d.prove_equal(P.det(), 1, strategy="tan_half", claim="(2.29): det R = 1")
    d.prove_equal(
        G * G.T,
        sp.eye(3),
        strategy="cancel",
        claim="general rotation: R R^T = 1 (the six conditions (2.13))",
    )
    wrong = E.copy()
    wrong[0, 1] = -wrong[0, 1]
    d.reject(
        wrong * wrong.T,
        sp.eye(3),
        strategy="tan_half",
        claim="Euler matrix with the sign of R12 flipped is orthogonal",
    )
    M = rot.matrix_from_euler(0.3, 1.2, -2.1)
    d.confirm(
        M @ M.T,
        np.eye(3),
        atol=CODE_ATOL,
        route="mechanics.matrix_from_euler is orthogonal to rounding",
    )


@check(
    "eq2.20",
    "Components transform with the transpose: r^A = r^O (^A R^O)^T",
    kind="proof",
    covers=("eq2.20",),
    defines=("eq2.17", "eq2.18", "eq2.19"),
    statement="r = r^O E^O = r^A E^A with E^A = ^A R^O E^O gives r^A = r^O ^O R^A (2.20)",
)
def component_transformation(d: Derivation) -> None:
    rO = sp.Matrix([[x1, x2, x3]])  # a row of components (2.17)
    rA = rO * G.T
    d.note(
        "r^A := r^O (^A R^O)^T; the vector is r^A E^A = r^A ^A R^O E^O, so its O-components are r^A ^A R^O"
    )
    d.prove_equal(rA * G, rO, strategy="cancel", claim="r^A E^A = r^O E^O for every rotation")
    d.reject(rO * G * G, rO, strategy="cancel", claim="r^A = r^O ^A R^O (without the transpose)")
    R = rot.matrix_from_euler(0.4, 0.9, 2.0)
    r = np.array([1.0, -2.0, 0.5])
    d.confirm(
        rot.components_A_from_O(R, r) @ R,
        r,
        atol=CODE_ATOL,
        route="mechanics.components_A_from_O then back to O",
    )


@check(
    "eq2.23",
    "The rotated vector (2.23) is the active operator of the matrix (2.28)",
    kind="proof",
    covers=("eq2.21", "eq2.22", "eq2.23", "eq2.26", "eq2.27"),
    defines=("eq2.24", "eq2.25"),
    statement="r' = (r·e_a)e_a + cos φ (e_a×r)×e_a + sin φ e_a×r equals r^O ^A R^O(φ) E^O",
)
def rotated_vector(d: Derivation) -> None:
    e = unit_vector(u, v)
    r = vec(x1, x2, x3)
    d.note("unit axis e_a = (2u, 2v, 1-u^2-v^2)/(1+u^2+v^2), all directions but one", e)
    d.prove_equal(
        (r.dot(e)) * e + cross(cross(e, r), e),
        r,
        strategy="cancel",
        claim="(2.22): r = (r·e_a) e_a + (e_a × r) × e_a",
    )
    r_rot = r.dot(e) * e + sp.cos(alpha) * cross(cross(e, r), e) + sp.sin(alpha) * cross(e, r)
    M = rotvec_matrix(alpha, e)
    d.prove_equal(
        r_rot.T,
        r.T * M,
        strategy="tan_half",
        claim="(2.23) = (2.26)-(2.27): r' = r^O ^A R^O(φ) E^O, the operator of (2.21)",
    )
    wrong = r.dot(e) * e + sp.cos(alpha) * cross(cross(e, r), e) - sp.sin(alpha) * cross(e, r)
    d.reject(
        wrong.T,
        r.T * M,
        strategy="tan_half",
        claim="the turn in the negative sense, -sin φ e_a × r",
    )
    ax = np.array([0.36, -0.48, 0.8])
    rv = np.array([0.3, -1.1, 2.0])
    expected = (
        (rv @ ax) * ax
        + np.cos(1.3) * np.cross(np.cross(ax, rv), ax)
        + np.sin(1.3) * np.cross(ax, rv)
    )
    d.confirm(
        rot.rotate_vector(rot.matrix_from_rotvec(1.3 * ax), rv),
        expected,
        atol=CODE_ATOL,
        route="mechanics.rotate_vector(matrix_from_rotvec) against (2.23) in floats",
    )


@check(
    "eq2.28",
    "The rotation-vector matrix: (2.28) equals (2.29)",
    kind="proof",
    covers=("eq2.28", "eq2.29"),
    statement="(2.28) entry by entry = cos φ 1 + sin φ [antisymmetric] + (1 - cos φ) cos α_i cos α_j",
)
def rotvec_matrix_forms(d: Derivation) -> None:
    cs = sp.symbols("c1 c2 c3", real=True)
    d.prove_equal(
        rotvec_matrix_explicit(alpha, cs),
        rotvec_matrix(alpha, cs),
        strategy="expand",
        claim="(2.28) = (2.29) for any direction cosines",
    )
    wrong = rotvec_matrix_explicit(alpha, cs)
    wrong[1, 0] = (1 - sp.cos(alpha)) * cs[1] * cs[0] + sp.sin(alpha) * cs[2]
    d.reject(
        wrong,
        rotvec_matrix(alpha, cs),
        strategy="expand",
        claim="(2.28) with +sin φ cos α_3 in entry (2,1)",
    )
    ax = np.array([2.0, -1.0, 2.0]) / 3.0
    P = floats(
        rotvec_matrix(alpha, sp.Matrix([sp.Rational(2, 3), -sp.Rational(1, 3), sp.Rational(2, 3)])),
        {alpha: sp.Rational(7, 10)},
    )
    d.confirm(
        rot.matrix_from_rotvec(0.7 * ax),
        P,
        atol=CODE_ATOL,
        route="mechanics.matrix_from_rotvec against (2.29) at φ = 0.7, e_a = (2, -1, 2)/3",
    )
    d.confirm(
        rot.matrix_from_axis_angle([2.0, -1.0, 2.0], 0.7),
        P,
        atol=CODE_ATOL,
        route="mechanics.matrix_from_axis_angle (unnormalised axis) against (2.29)",
    )


@check(
    "eq2.30",
    "R1, R2, R3 are (2.29) about the coordinate axes",
    kind="proof",
    covers=("eq2.30",),
    statement="R_i(α) = ^A R^O(α e_i) of (2.29), i = 1, 2, 3",
)
def basic_rotations(d: Derivation) -> None:
    axes = [(1, 0, 0), (0, 1, 0), (0, 0, 1)]
    for name, Ri, ax in zip(("R1", "R2", "R3"), (R1, R2, R3), axes, strict=True):
        d.prove_equal(
            Ri(alpha),
            rotvec_matrix(alpha, ax),
            strategy="expand",
            claim=f"{name}(α) of (2.30) = (2.29) with e_a = e{ax.index(1) + 1}",
        )
    R2_wrong = sp.Matrix(
        [[sp.cos(alpha), 0, sp.sin(alpha)], [0, 1, 0], [-sp.sin(alpha), 0, sp.cos(alpha)]]
    )
    d.reject(
        R2_wrong,
        rotvec_matrix(alpha, (0, 1, 0)),
        strategy="expand",
        claim="R2 with the sign pattern of R1 and R3 (sin in entry (1,3))",
    )
    for Ri, fn in ((R1, rot.R1), (R2, rot.R2), (R3, rot.R3)):
        d.confirm(
            fn(0.9),
            floats(Ri(alpha), {alpha: sp.Rational(9, 10)}),
            atol=CODE_ATOL,
            route=f"mechanics.{fn.__name__}(0.9) against (2.30)",
        )


@check(
    "eq2.36",
    "Euler angles: the product R3(φ) R1(θ) R3(ψ) written out",
    kind="proof",
    covers=("eq2.34", "eq2.35", "eq2.36"),
    defines=("eq2.31", "eq2.32", "eq2.33"),
    statement="^A R^O(ψ, θ, φ) = R3(φ) R1(θ) R3(ψ) = the explicit matrix (2.36)",
)
def euler_explicit(d: Derivation) -> None:
    sps, cps, sth, cth, sph, cph = (
        sp.sin(psi),
        sp.cos(psi),
        sp.sin(theta),
        sp.cos(theta),
        sp.sin(phi),
        sp.cos(phi),
    )
    printed = sp.Matrix(
        [
            [cph * cps - sph * cth * sps, cph * sps + sph * cth * cps, sph * sth],
            [-sph * cps - cph * cth * sps, -sph * sps + cph * cth * cps, cph * sth],
            [sth * sps, -sth * cps, cth],
        ]
    )
    d.quantity("R_A_O", printed)
    d.prove_equal(
        R3(phi) * R1(theta) * R3(psi), printed, strategy="expand", claim="(2.35) = (2.36)"
    )
    d.reject(
        R3(psi) * R1(theta) * R3(phi),
        printed,
        strategy="expand",
        claim="the reversed product R3(ψ) R1(θ) R3(φ) = (2.36)",
    )
    pt = {psi: sp.Rational(3, 10), theta: sp.Rational(6, 5), phi: -sp.Rational(21, 10)}
    d.confirm(
        rot.matrix_from_euler(0.3, 1.2, -2.1),
        floats(printed, pt),
        atol=CODE_ATOL,
        route="mechanics.matrix_from_euler against (2.36)",
    )


@check(
    "eq2.37",
    "Rotations about one fixed axis commute and add",
    kind="proof",
    covers=("eq2.37",),
    statement="R3(φ) R3(ψ) = R3(ψ) R3(φ) = R3(φ + ψ)",
)
def same_axis_commute(d: Derivation) -> None:
    d.prove_equal(
        R3(phi) * R3(psi), R3(psi) * R3(phi), strategy="expand", claim="R3(φ) R3(ψ) = R3(ψ) R3(φ)"
    )
    d.prove_equal(
        R3(phi) * R3(psi), R3(phi + psi), strategy="expand_trig", claim="R3(φ) R3(ψ) = R3(φ + ψ)"
    )
    d.reject(
        R3(phi) * R3(psi), R3(phi - psi), strategy="expand_trig", claim="R3(φ) R3(ψ) = R3(φ - ψ)"
    )
    d.confirm(
        rot.compose(rot.R3(0.4), rot.R3(1.1)),
        rot.R3(1.5),
        atol=CODE_ATOL,
        route="mechanics.compose(R3(0.4), R3(1.1)) = R3(1.5)",
    )


@check(
    "eq2.38",
    "Finite rotations do not commute",
    kind="proof",
    covers=("eq2.38",),
    statement="R3(φ) R1(θ) R3(ψ) ≠ R1(θ) R3(φ) R3(ψ) in general",
    reading="The extraction prints '=' in (2.38); the text ('This, however, makes it obvious "
    "that ...', non-commutation) shows the book's sign is '≠', lost in extraction.",
)
def non_commutation(d: Derivation) -> None:
    lhs = R3(phi) * R1(theta) * R3(psi)
    rhs = R1(theta) * R3(phi) * R3(psi)
    pt = {phi: sp.pi / 2, theta: sp.pi / 2, psi: 0}
    d.witness_unequal(lhs, rhs, pt, claim="at φ = θ = π/2, ψ = 0 the two products differ")
    d.reject_witness(R3(phi) * R3(psi), R3(psi) * R3(phi), pt, claim="R3(φ) R3(ψ) vs R3(ψ) R3(φ)")
    A = rot.compose(rot.R3(np.pi / 2), rot.R1(np.pi / 2))
    B = rot.compose(rot.R1(np.pi / 2), rot.R3(np.pi / 2))
    d.confirm(
        np.abs(A - B).max() > 0.5,
        True,
        atol=0.0,
        route="mechanics.compose in the two orders differs",
    )


eps_ = sp.Symbol("epsilon", real=True)
k1, k2 = sp.symbols("k1 k2", real=True)
u2, v2 = sp.symbols("u2 v2", real=True)


def _small(k, uu, vv) -> sp.Matrix:
    """^A R^O(ε k e) of (2.29), e = unit_vector(uu, vv): a rotation vector of size ε k."""
    return rotvec_matrix(eps_ * k, unit_vector(uu, vv))


@check(
    "eq2.39",
    "Small rotations: 1 plus an antisymmetric matrix, to first order",
    kind="proof",
    covers=("eq2.39",),
    defines=("eq2.40",),
    statement="^A R^O(δφ) = 1 + [[0, δφ3, -δφ2], [-δφ3, 0, δφ1], [δφ2, -δφ1, 0]] + O(δφ^2)",
)
def infinitesimal_rotation(d: Derivation) -> None:
    e = unit_vector(u, v)
    R = _small(k1, u, v)
    d.prove_equal(R.subs(eps_, 0), sp.eye(3), strategy="expand", claim="R(0) = 1")
    d.prove_equal(
        sp.diff(R, eps_).subs(eps_, 0),
        omega_matrix(k1 * e),
        strategy="cancel",
        claim="dR/dε at 0 is the antisymmetric matrix of δφ/ε = k e_a (2.39)",
    )
    d.reject(
        sp.diff(R, eps_).subs(eps_, 0),
        omega_matrix(k1 * e).T,
        strategy="cancel",
        claim="the first-order term with the opposite sign (the transpose)",
    )
    h = 1e-7
    ax = np.array([0.0, 0.6, 0.8])
    d.confirm(
        (rot.matrix_from_rotvec(h * ax) - np.eye(3)) / h,
        np.array([[0, 0.8, -0.6], [-0.8, 0, 0], [0.6, 0, 0]]),
        # truncation: the second-order term, ≤ h/2; rounding: O(1) entries to eps, over h
        atol=h + 4 * EPS / h,
        route="mechanics.matrix_from_rotvec(δφ) - 1 ≈ antisym(δφ), error O(δφ)",
    )


@check(
    "eq2.42",
    "Infinitesimal rotations commute and add (to first order)",
    kind="proof",
    covers=("eq2.41", "eq2.42"),
    statement="R(δφ1) R(δφ2) = R(δφ2) R(δφ1) = R(δφ1 + δφ2) + O(δφ^2)",
)
def infinitesimal_commute(d: Derivation) -> None:
    A = _small(k1, u, v)
    B = _small(k2, u2, v2)
    comm = A * B - B * A
    d.prove_equal(
        comm.subs(eps_, 0), sp.zeros(3), strategy="expand", claim="commutator vanishes at ε = 0"
    )
    d.prove_equal(
        sp.diff(comm, eps_).subs(eps_, 0),
        sp.zeros(3),
        strategy="cancel",
        claim="d/dε of the commutator vanishes at ε = 0: commute to first order (2.42)",
    )
    first = sp.diff(A * B, eps_).subs(eps_, 0)
    sum_vec = k1 * unit_vector(u, v) + k2 * unit_vector(u2, v2)
    d.prove_equal(
        first,
        omega_matrix(sum_vec),
        strategy="cancel",
        claim="first-order term of R(δφ1)R(δφ2) is that of δφ1 + δφ2 (2.41)",
    )
    d.reject(
        sp.diff(comm, eps_, 2).subs(eps_, 0),
        sp.zeros(3),
        strategy="cancel",
        claim="the commutator vanishes to second order too (it does not: it is O(ε^2) exactly)",
    )
    small = 1e-5
    a1, a2 = np.array([small, 0, 0]), np.array([0, small, 0])
    P, Q = rot.matrix_from_rotvec(a1), rot.matrix_from_rotvec(a2)
    d.confirm(
        np.abs(P @ Q - Q @ P).max() / small**2,
        1.0,
        # the largest entry is sin²δφ = δφ²(1 - δφ²/3 + ...); products of O(1) entries
        # carry a few eps of rounding, which the division by δφ² amplifies
        atol=small**2 + 8 * EPS / small**2,
        route="mechanics: |[R(δφ1), R(δφ2)]| / δφ^2 -> 1 for perpendicular axes",
    )


@check(
    "eq2.44",
    "A small rotation changes the basis by a vector product: δE = δφ × E",
    kind="proof",
    covers=("eq2.43", "eq2.44"),
    statement="the antisymmetric matrix of (2.39) applied to E^O gives δφ × e^O_i",
)
def basis_change_cross(d: Derivation) -> None:
    w = sp.Matrix(sp.symbols("dphi1 dphi2 dphi3", real=True))
    basis = [sp.Matrix([1, 0, 0]), sp.Matrix([0, 1, 0]), sp.Matrix([0, 0, 1])]
    A = omega_matrix(w)
    rows = sp.Matrix.hstack(*[cross(w, e) for e in basis]).T
    d.prove_equal(
        A, rows, strategy="expand", claim="row i of the antisymmetric matrix = δφ × e_i (2.43)"
    )
    rows_wrong = sp.Matrix.hstack(*[cross(e, w) for e in basis]).T
    d.reject(A, rows_wrong, strategy="expand", claim="row i = e_i × δφ")
    dp = np.array([1e-8, -2e-8, 3e-8])
    d.confirm(
        rot.matrix_from_rotvec(dp) - np.eye(3),
        np.cross(dp, np.eye(3)),
        # the neglected second-order term is ≤ |δφ|²/2; 1 - (...) rounds to ≤ 2 eps
        atol=float(dp @ dp) + 2 * EPS,
        route="mechanics.matrix_from_rotvec(δφ) - 1 = rows δφ × e_i to O(δφ^2)",
    )
