"""Chapter 4.1: the angular momentum of a rigid body and the inertia tensor.
Equations (4.1)–(4.14), (4.32)–(4.40), and the catalogue of homogeneous bodies.

The inertia tensor is built here from its definition, particle by particle
(J = Σ m (|r|² 1 − r rᵀ), the book's (4.34)), or by integrating a homogeneous mass
distribution symbolically; the numeric code in :mod:`mechanics.inertia` is then
confirmed at exact rational points.  Rotations are the general rational rotation
of :func:`identities.verify.symbolic.general_rotation`, so every statement about "any
basis" is proved for all rotations at once with ``cancel``.

Book matrices are row-vector conventions: L = w J (4.6) with w = (ω_x ω_y ω_z).
Column components are used below (J symmetric, so L = J ω is the same statement);
a vector with components r^A in the body basis has O components r^O = (^A R^O)ᵀ r^A.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from identities.verify.catalogue import check
from identities.verify.proof import Derivation
from identities.verify.symbolic import cross, floats, general_rotation, vec
from mechanics import dynamics as dyn
from mechanics import inertia as inr
from mechanics._floats import EPS

#: mechanics against a float evaluation of the same exact rational value (a few products
#: and sums of O(1) numbers, or one Jacobi/rotation pass on an O(1) tensor): 64 eps.
CODE_ATOL = 64 * EPS

m, m_1, m_2, m_3 = sp.symbols("m m_1 m_2 m_3", positive=True)


def vsym(name: str, real: bool = True) -> sp.Matrix:
    """A column vector of three real symbols name_x, name_y, name_z."""
    return vec(*sp.symbols(f"{name}_x {name}_y {name}_z", real=real))


def particle_J(mass, r: sp.Matrix) -> sp.Matrix:
    """The inertia tensor of one particle about the origin, (4.34): m(|r|² 1 − r rᵀ)."""
    r = sp.Matrix(r)
    return mass * ((r.T * r)[0, 0] * sp.eye(3) - r * r.T)


def system_J(masses, positions) -> sp.Matrix:
    """Σ_k m_k (|r_k|² 1 − r_k r_kᵀ) (4.34)."""
    return sum((particle_J(mk, rk) for mk, rk in zip(masses, positions, strict=True)), sp.zeros(3))


def book_matrix(masses, positions) -> sp.Matrix:
    """The matrix of (4.6) from the book's moments (3.16) and products (3.17) of inertia."""
    x = [r[0] for r in positions]
    y = [r[1] for r in positions]
    z = [r[2] for r in positions]
    S = lambda f: sum(mk * f(k) for k, mk in enumerate(masses))  # noqa: E731
    J_x = S(lambda k: y[k] ** 2 + z[k] ** 2)
    J_y = S(lambda k: x[k] ** 2 + z[k] ** 2)
    J_z = S(lambda k: x[k] ** 2 + y[k] ** 2)
    D_xy, D_xz, D_yz = S(lambda k: x[k] * y[k]), S(lambda k: x[k] * z[k]), S(lambda k: y[k] * z[k])
    return sp.Matrix([[J_x, -D_xy, -D_xz], [-D_xy, J_y, -D_yz], [-D_xz, -D_yz, J_z]])


def _two_particles():
    return (m_1, m_2), (vsym("r1"), vsym("r2"))


@check(
    "eq4.5",
    "Angular momentum of a rigid body: L = Σ r × m(ω × r) = J ω",
    kind="proof",
    covers=("eq4.3", "eq4.4", "eq4.5", "eq4.6"),
    defines=("eq4.1", "eq4.2"),
    statement="with v_k = ω × r_k (4.2), L = Σ r_k × m_k v_k (4.1) = Σ [ω m_k r_k² − m_k (ω·r_k) "
    "r_k] (4.4), whose components are L_x = J_x ω_x − D_xy ω_y − D_xz ω_z, ... (4.5), i.e. "
    "L = w J with J the symmetric matrix of (4.6)",
    reading="(4.5)-(4.6) hold for any number of particles: both sides are sums of one-particle "
    "terms, so two particles with symbolic masses and positions prove the general case.",
)
def angular_momentum_rigid(d: Derivation) -> None:
    masses, pos = _two_particles()
    w = vsym("omega")
    L_41 = sum(
        (cross(r, mk * cross(w, r)) for mk, r in zip(masses, pos, strict=True)), sp.zeros(3, 1)
    )  # (4.3)
    L_44 = sum(
        (w * mk * (r.T * r)[0] - mk * (w.T * r)[0] * r for mk, r in zip(masses, pos, strict=True)),
        sp.zeros(3, 1),
    )
    d.prove_equal(L_41, L_44, strategy="expand", claim="(4.3) → (4.4): the triple vector product")
    J = book_matrix(masses, pos)
    d.prove_equal(L_44, J * w, strategy="expand", claim="(4.4) → (4.5): components with J, D")
    d.prove_equal(
        (w.T * J).T, J * w, strategy="expand", claim="(4.6): L = w J, J symmetric (row form)"
    )
    d.prove_equal(J, system_J(masses, pos), strategy="expand", claim="J of (4.6) = Σ m(r²1 − rrᵀ)")
    J_wrong = J.copy()
    J_wrong[0, 1] = -J_wrong[0, 1]
    d.reject(L_44, J_wrong * w, strategy="expand", claim="L_x = J_x ω_x + D_xy ω_y − D_xz ω_z")
    d.reject(
        L_41,
        sum(
            (
                mk * (r.T * r)[0] * w + mk * (w.T * r)[0] * r
                for mk, r in zip(masses, pos, strict=True)
            ),
            vec(0, 0, 0),
        ),
        strategy="expand",
        claim="(4.4) with + (ω·r) r",
    )
    pt = {
        s: sp.Rational(v)
        for s, v in zip(
            [*masses, *pos[0], *pos[1], *w],
            ["3/2", "1/3", "1", "-2", "1/2", "3/4", "-1/5", "2", "1/7", "-3/2", "5/4"],
            strict=True,
        )
    }
    m_n = np.array([float(pt[mk]) for mk in masses])
    r_n = np.array([floats(r, pt).ravel() for r in pos])
    J_n = inr.inertia_tensor(m_n, r_n, about=np.zeros(3))
    d.confirm(
        dyn.angular_momentum_rigid(J_n, floats(w, pt).ravel()),
        floats(L_41, pt).ravel(),
        atol=CODE_ATOL,
        route="mechanics.angular_momentum_rigid(inertia_tensor(m, r, about=0), ω) equals Σ r × "
        "m(ω × r) evaluated exactly",
    )


def _generic_matrix() -> sp.Matrix:
    """A 3×3 matrix of nine independent real symbols (any matrix: orthogonality not assumed)."""
    return sp.Matrix(3, 3, sp.symbols("q11 q12 q13 q21 q22 q23 q31 q32 q33", real=True))


def _prove_orthogonal(d: Derivation, R: sp.Matrix) -> None:
    d.prove_equal(R * R.T, sp.eye(3), strategy="numerator", claim="^A R^O ^O R^A = 1")
    d.prove_equal(R.T * R, sp.eye(3), strategy="numerator", claim="^O R^A ^A R^O = 1")


@check(
    "eq4.11",
    "Transformation of the inertia tensor under rotation: J^O = ^O R^A J^A ^A R^O",
    kind="proof",
    covers=("eq4.8", "eq4.9", "eq4.10", "eq4.11", "eq4.12"),
    defines=("eq4.7",),
    statement="a particle with body components r^A has O components r^O = ^O R^A r^A; the "
    "tensor built from r^O is ^O R^A J^A ^A R^O (4.11) for every rotation, and L = w^O J^O E^O "
    "= w^A J^A E^A (4.8)-(4.10): one operator J with L = J ω (4.12)",
)
def inertia_transformation(d: Derivation) -> None:
    d.note(
        "for any matrix Q the differences below are proved equal to terms in QQᵀ − 1 and QᵀQ − "
        "1 (a polynomial identity, by expand); both vanish for every rotation (the general "
        "rational rotation, by numerator), so the statements hold for every rotation"
    )
    Q = _generic_matrix()  # stands for ^A R^O
    one = sp.eye(3)
    r_A = vsym("r")
    J_A = particle_J(m, r_A)
    J_O = particle_J(m, Q.T * r_A)
    defect = m * ((r_A.T * (Q * Q.T - one) * r_A)[0] * one - (r_A.T * r_A)[0] * (Q.T * Q - one))
    d.prove_equal(
        J_O - Q.T * J_A * Q,
        defect,
        strategy="expand",
        claim="J(^O R^A r^A) − ^O R^A J^A ^A R^O = m[rᵀ(QQᵀ − 1)r 1 − r²(QᵀQ − 1)]",
    )
    d.reject(
        J_O - Q * J_A * Q.T,
        defect,
        strategy="expand",
        claim="the same with the rotation matrices swapped: J^O = ^A R^O J^A ^O R^A",
    )
    a, b, c, e = sp.symbols("a b c e", real=True)
    R_A_O = general_rotation(a, b, c, e)  # ^A R^O, passive
    _prove_orthogonal(d, R_A_O)
    d.note(
        "so (4.11): J^O = ^O R^A J^A ^A R^O for the tensor of a particle, hence of a body (the "
        "tensor is a sum over particles), for every rotation"
    )
    w_A = vsym("omega")
    d.prove_equal(
        Q.T * (J_A * w_A) - (Q.T * J_A * Q) * (Q.T * w_A),
        Q.T * J_A * (one - Q * Q.T) * w_A,
        strategy="expand",
        claim="(4.8)-(4.10): ^O R^A (J^A ω^A) − J^O ω^O = ^O R^A J^A (1 − QQᵀ) ω^A = 0: L = J ω "
        "in every basis, one linear operator J (4.12)",
    )
    d.reject(
        Q.T * (J_A * w_A) - J_A * (Q.T * w_A),
        Q.T * J_A * (one - Q * Q.T) * w_A,
        strategy="expand",
        claim="the component matrix is the same in every basis (J^O = J^A)",
    )
    pt = {a: 1, b: sp.Rational(1, 2), c: -2, e: sp.Rational(3, 4), m: sp.Rational(5, 3)}
    pt.update(dict(zip(r_A, [sp.Rational(1, 3), -1, sp.Rational(7, 5)], strict=True)))
    R_n = floats(R_A_O, pt)
    d.confirm(
        inr.rotate_inertia(floats(J_A, pt), R_n),
        floats(particle_J(m, R_A_O.T * r_A), pt),
        atol=CODE_ATOL,
        route="mechanics.rotate_inertia(J_A, R_A_O) equals the tensor built from rotated positions",
    )


@check(
    "eq4.14",
    "Principal axes: the rows of ^A R^O are eigenvectors, the matrix is diagonal there",
    kind="proof",
    covers=("eq4.13", "eq4.14"),
    statement="if J^O = ^O R^A diag(J1, J2, J3) ^A R^O then J e^A_i = J_i e^A_i (4.13) with "
    "e^A_i the rows of ^A R^O, and in the principal basis the matrix is diag (4.14); rule (I): a "
    "plane of symmetry z → −z makes e_z a principal axis",
    reading="the existence of an orthonormal eigenbasis for a real symmetric matrix is the "
    "spectral theorem (cited, not re-proved); what is proved is that the rotated diagonal form "
    "has the rows of the rotation as eigenvectors, and rule (I) for a mirror-symmetric body.",
)
def principal_axes(d: Derivation) -> None:
    J_1, J_2, J_3 = sp.symbols("J_1 J_2 J_3", positive=True)
    Q = _generic_matrix()
    one = sp.eye(3)
    Jp = sp.diag(J_1, J_2, J_3)
    J_O = Q.T * Jp * Q
    for i, Ji in enumerate((J_1, J_2, J_3)):
        e_i = Q[i, :].T
        d.prove_equal(
            J_O * e_i - Ji * e_i,
            Q.T * Jp * (Q * Q.T - one)[:, i],
            strategy="expand",
            claim=f"(4.13): J e^A_{i + 1} − J_{i + 1} e^A_{i + 1} = Qᵀ diag (QQᵀ − 1) "
            "e_i, zero for a rotation",
        )
    d.reject(
        J_O * Q[0, :].T - J_2 * Q[0, :].T,
        Q.T * Jp * (Q * Q.T - one)[:, 0],
        strategy="expand",
        claim="e^A_1 belongs to the eigenvalue J_2",
    )
    d.prove_equal(
        Q * J_O * Q.T - Jp,
        (Q * Q.T) * Jp * (Q * Q.T) - Jp,
        strategy="expand",
        claim="(4.14): ^A R^O J^O ^O R^A = (QQᵀ) diag (QQᵀ) = diag for a rotation",
    )
    a, b, c, e = sp.symbols("a b c e", real=True)
    R_A_O = general_rotation(a, b, c, e)
    _prove_orthogonal(d, R_A_O)
    # rule (I): mirror pairs (x, y, ±z) of equal mass
    pos = [vsym("r1"), vsym("r2")]
    mirror = [vec(r[0], r[1], -r[2]) for r in pos]
    J = system_J([m_1, m_2, m_1, m_2], [*pos, *mirror])
    d.prove_equal(
        J * vec(0, 0, 1),
        J[2, 2] * vec(0, 0, 1),
        strategy="expand",
        claim="rule (I): a body symmetric under z → −z has e_z as a principal axis (D_xz = D_yz = 0)",
    )
    d.reject(
        system_J([m_1, m_2, m_2, m_1], [*pos, *mirror]) * vec(0, 0, 1),
        J[2, 2] * vec(0, 0, 1),
        strategy="expand",
        claim="rule (I) when the mirrored particles have different masses",
    )
    pt = {a: 2, b: sp.Rational(-1, 3), c: sp.Rational(1, 2), e: 1}
    R_x = floats(R_A_O, pt)
    J_n = R_x.T @ np.diag([1.0, 2.0, 2.5]) @ R_x
    moments, R_n = inr.principal_axes(J_n)
    d.confirm(moments, [1.0, 2.0, 2.5], atol=CODE_ATOL, route="mechanics.principal_axes: moments")
    d.confirm(
        np.abs(R_n @ R_x.T),
        np.eye(3),
        atol=CODE_ATOL,
        route="mechanics.principal_axes: each axis is ± the row of ^A R^O (simple moments)",
    )


@check(
    "eq4.32",
    "Kinetic energy and angular momentum in a principal basis",
    kind="proof",
    covers=("eq4.32", "eq4.33"),
    statement="T = ½ Σ m |ω × r|² = ½ ωᵀ J ω, which is ½(J_x ω_x² + J_y ω_y² + J_z ω_z²) (4.32) "
    "in the principal basis, where L = (J_x ω_x, J_y ω_y, J_z ω_z) (4.33)",
)
def energy_principal(d: Derivation) -> None:
    masses, pos = _two_particles()
    w = vsym("omega")
    T = sum(
        (mk * (cross(w, r).T * cross(w, r))[0] / 2 for mk, r in zip(masses, pos, strict=True)), 0
    )
    J = system_J(masses, pos)
    d.prove_equal(T, (w.T * J * w)[0] / 2, strategy="expand", claim="T = ½ ωᵀ J ω (3.15), (4.6)")
    d.reject(T, (w.T * J * w)[0], strategy="expand", claim="T = ωᵀ J ω (factor ½ lost)")
    J_x, J_y, J_z = sp.symbols("J_x J_y J_z", positive=True)
    Jp = sp.diag(J_x, J_y, J_z)
    T_432 = (J_x * w[0] ** 2 + J_y * w[1] ** 2 + J_z * w[2] ** 2) / 2
    d.prove_equal((w.T * Jp * w)[0] / 2, T_432, strategy="expand", claim="(4.32)")
    d.prove_equal(
        Jp * w, vec(J_x * w[0], J_y * w[1], J_z * w[2]), strategy="expand", claim="(4.33)"
    )
    d.reject(
        Jp * w, vec(J_x * w[0], J_y * w[1], J_y * w[2]), strategy="expand", claim="L_z = J_y ω_z"
    )
    d.confirm(
        dyn.rotational_kinetic_energy(np.diag([1.0, 2.0, 3.0]), [1.0, -1.0, 2.0]),
        float(T_432.subs({J_x: 1, J_y: 2, J_z: 3, w[0]: 1, w[1]: -1, w[2]: 2})),
        atol=CODE_ATOL,
        route="mechanics.rotational_kinetic_energy at a principal point",
    )


@check(
    "eq4.37",
    "The inertia tensor as J_S 1 − D; J_S 1 is invariant, so D fixes the principal axes",
    kind="proof",
    covers=("eq4.34", "eq4.37"),
    defines=("eq4.35", "eq4.36"),
    statement="J_kl = [Σ m r²] δ_kl − Σ m x_k x_l (4.34) = J_S 1 − D (4.37) with J_S = Σ m r·r "
    "(4.35), D_xx = Σ m x x (4.36); J_S and J_S 1 are unchanged by (4.11), so J and D have the "
    "same eigenvectors with eigenvalues J_i = J_S − D_i",
)
def spherical_decomposition(d: Derivation) -> None:
    masses, pos = _two_particles()
    J_S = sum((mk * (r.T * r)[0] for mk, r in zip(masses, pos, strict=True)), 0)  # (4.35)
    D = sum(
        (mk * r * r.T for mk, r in zip(masses, pos, strict=True)), sp.zeros(3)
    )  # (4.36), (3.17)
    J_434 = sp.Matrix(3, 3, lambda k, l: J_S * (1 if k == l else 0) - D[k, l])
    d.prove_equal(
        J_434, book_matrix(masses, pos), strategy="expand", claim="(4.34) = matrix of (4.6)"
    )
    d.prove_equal(J_434, J_S * sp.eye(3) - D, strategy="expand", claim="(4.37): J = J_S 1 − D")
    d.reject(J_434, J_S * sp.eye(3) + D, strategy="expand", claim="J = J_S 1 + D")
    d.prove_equal(J_S, (J_434.trace()) / 2, strategy="expand", claim="J_S = ½ tr J (so invariant)")
    a, b, c, e = sp.symbols("a b c e", real=True)
    R = general_rotation(a, b, c, e)
    d.prove_equal(
        R.T * (J_S * sp.eye(3)) * R,
        J_S * sp.eye(3),
        strategy="cancel",
        claim="J_S 1 is invariant under (4.11)",
    )
    rO = [R.T * r for r in pos]
    d.prove_equal(
        sum((mk * (r.T * r)[0] for mk, r in zip(masses, rO, strict=True)), 0),
        J_S,
        strategy="cancel",
        claim="J_S computed from rotated positions is the same number",
    )
    d.reject(
        R.T * sp.diag(1, 1, 2) * R,
        sp.diag(1, 1, 2),
        strategy="cancel",
        claim="a non-spherical matrix is invariant too",
    )
    v, lam = vsym("v"), sp.Symbol("lambda", real=True)
    d.prove_equal(
        J_434 * v - (J_S - lam) * v,
        -(D * v - lam * v),
        strategy="expand",
        claim="J v = (J_S − λ) v ⇔ D v = λ v: same eigenvectors",
    )
    J_n = inr.inertia_tensor(
        [1.0, 2.0], [[1.0, 0.5, -1.0], [0.25, -2.0, 0.75]], about=[0.0, 0.0, 0.0]
    )
    mom, _ = inr.principal_axes(J_n)
    D_n = 0.5 * np.trace(J_n) * np.eye(3) - J_n
    d.confirm(
        np.sort(0.5 * np.trace(J_n) - np.linalg.eigvalsh(D_n)),
        mom,
        atol=CODE_ATOL,
        route="numpy eigvalsh of D = J_S 1 − J: J_S − D_i are mechanics.principal_axes moments",
    )


@check(
    "eq4.38",
    "The parallel-axis theorem in tensor form: J_C = J_G + m(R² 1 − R ⊗ R)",
    kind="proof",
    covers=("eq4.38", "eq4.40"),
    defines=("eq4.39",),
    statement="for every particle system of total mass m, with R = GC, J_C = J_G + m(R² 1 − "
    "R⊗R) (4.38), R⊗R = R Rᵀ (4.39); its zz-entry is Steiner's J^C_z = J^G_z + m(R_x² + R_y²) "
    "(4.40)",
    reading="any number N of particles: the difference Δ(ρ) = J(about C) − J(about G) of one "
    "particle is affine in its position ρ, so Σ m_k Δ(ρ_k) = m Δ(G) (Σ m_k ρ_k = m G), and Δ(G) "
    "is the particle tensor m(R² 1 − R Rᵀ); each step is proved below, and the case N = 3 also "
    "directly.",
)
def parallel_axis(d: Derivation) -> None:
    rho, C, G = vsym("rho"), vsym("C"), vsym("G")
    Delta = particle_J(1, rho - C) - particle_J(1, rho - G)
    for k in range(3):
        d.prove_zero(
            Delta.diff(rho[k], rho[k]),
            strategy="expand",
            claim=f"Δ(ρ) has no ρ_{k + 1}² term",
        )
    for k, l in ((0, 1), (0, 2), (1, 2)):
        d.prove_zero(
            Delta.diff(rho[k], rho[l]),
            strategy="expand",
            claim=f"Δ(ρ) has no ρ_{k + 1} ρ_{l + 1} term: Δ is affine in ρ",
        )
    Rv = C - G
    d.prove_equal(
        Delta.subs(dict(zip(rho, G, strict=True))),
        particle_J(1, Rv),
        strategy="expand",
        claim="Δ(G) = R² 1 − R⊗R, R = GC",
    )
    # direct proof, three particles
    masses = (m_1, m_2, m_3)
    pos = [vsym("r1"), vsym("r2"), vsym("r3")]
    M = sum(masses)
    G3 = sum((mk * r for mk, r in zip(masses, pos, strict=True)), sp.zeros(3, 1)) / M
    J_C = system_J(masses, [r - C for r in pos])
    J_G = system_J(masses, [r - G3 for r in pos])
    R3 = C - G3
    RR = R3 * R3.T  # (4.39)
    d.prove_equal(
        J_C,
        J_G + M * ((R3.T * R3)[0] * sp.eye(3) - RR),
        strategy="numerator",
        claim="(4.38) for three particles, G their centre of mass",
    )
    d.reject(
        J_C,
        J_G + M * ((R3.T * R3)[0] * sp.eye(3) + RR),
        strategy="numerator",
        claim="(4.38) with + R⊗R",
    )
    C0 = vec(0, 0, 0)
    d.reject(
        system_J(masses, [r - C0 for r in pos]),
        system_J(masses, pos) + M * particle_J(1, C - C0),
        strategy="numerator",
        claim="(4.38) about a point that is not the centre of mass (origin instead of G)",
    )
    d.prove_equal(
        J_C[2, 2],
        J_G[2, 2] + M * (R3[0] ** 2 + R3[1] ** 2),
        strategy="numerator",
        claim="(4.40): J^C_z = J^G_z + m(R_x² + R_y²)",
    )
    pt = {m_1: 1, m_2: sp.Rational(3, 2), m_3: sp.Rational(1, 4)}
    vals = [1, -2, sp.Rational(1, 2), sp.Rational(3, 4), 0, -1, 2, 1, sp.Rational(1, 3)]
    for s, v in zip([*pos[0], *pos[1], *pos[2]], vals, strict=True):
        pt[s] = v
    pt.update(dict(zip(C, [sp.Rational(5, 2), -1, 3], strict=True)))
    m_n = np.array([float(pt[mk]) for mk in masses])
    r_n = np.array([floats(r, pt).ravel() for r in pos])
    C_n = floats(C, pt).ravel()
    G_n = floats(G3, pt).ravel()
    d.confirm(
        inr.parallel_axis(floats(J_G, pt), float(M.subs(pt)), C_n - G_n),
        floats(J_C, pt),
        atol=CODE_ATOL * 16,
        route="mechanics.parallel_axis(J_G, m, GC) equals the exact J_C",
    )
    d.confirm(
        inr.inertia_tensor(m_n, r_n, about=C_n),
        floats(J_C, pt),
        atol=CODE_ATOL * 16,
        route="mechanics.inertia_tensor(m, r, about=C) equals the exact J_C",
    )


# ------------------------------------------------------------------ homogeneous bodies

x, y, z, s, u, th, rr = sp.symbols("x y z s u theta rho", real=True)
R, h, ell, a_, b_, c_ = sp.symbols("R h ell a b c", positive=True)


def _integrate(f, limits):
    """Iterated definite integral of an expanded integrand (first limit innermost)."""
    return sp.integrate(sp.expand(f), *limits)


def _body_tensor(r: sp.Matrix, density, jacobian, limits) -> tuple[sp.Expr, sp.Matrix]:
    """Mass and inertia tensor about the origin of a homogeneous body r(params)."""
    mass = sp.simplify(_integrate(density * jacobian, limits))
    J = particle_J(1, r).applyfunc(lambda e: sp.factor(_integrate(e * density * jacobian, limits)))
    return mass, J


#: name → (position r, density, Jacobian, limits, catalogue tensor about G, mechanics call,
#:         rational point, a wrong catalogue variant for the negative control)
BODIES = {
    "rod": (
        vec(0, 0, s),
        m / ell,
        1,
        [(s, -ell / 2, ell / 2)],
        sp.diag(m * ell**2 / 12, m * ell**2 / 12, 0),
        lambda p: inr.rod(p[m], p[ell]),
        {m: 3, ell: sp.Rational(5, 2)},
        sp.diag(m * ell**2 / 3, m * ell**2 / 3, 0),
    ),
    "ring": (
        vec(R * sp.cos(u), R * sp.sin(u), 0),
        m / (2 * sp.pi * R),
        R,
        [(u, 0, 2 * sp.pi)],
        sp.diag(m * R**2 / 2, m * R**2 / 2, m * R**2),
        lambda p: inr.ring(p[m], p[R]),
        {m: 2, R: sp.Rational(3, 2)},
        sp.diag(m * R**2, m * R**2, m * R**2),
    ),
    "disc": (
        vec(rr * sp.cos(u), rr * sp.sin(u), 0),
        m / (sp.pi * R**2),
        rr,
        [(u, 0, 2 * sp.pi), (rr, 0, R)],
        sp.diag(m * R**2 / 4, m * R**2 / 4, m * R**2 / 2),
        lambda p: inr.disc(p[m], p[R]),
        {m: 2, R: sp.Rational(3, 2)},
        sp.diag(m * R**2 / 2, m * R**2 / 2, m * R**2 / 2),
    ),
    "cylinder": (
        vec(rr * sp.cos(u), rr * sp.sin(u), z),
        m / (sp.pi * R**2 * h),
        rr,
        [(u, 0, 2 * sp.pi), (rr, 0, R), (z, -h / 2, h / 2)],
        sp.diag(m * (3 * R**2 + h**2) / 12, m * (3 * R**2 + h**2) / 12, m * R**2 / 2),
        lambda p: inr.cylinder(p[m], p[R], p[h]),
        {m: 2, R: sp.Rational(3, 2), h: 5},
        sp.diag(m * (R**2 + h**2) / 12, m * (R**2 + h**2) / 12, m * R**2 / 2),
    ),
    "cylindrical_shell": (
        vec(R * sp.cos(u), R * sp.sin(u), z),
        m / (2 * sp.pi * R * h),
        R,
        [(u, 0, 2 * sp.pi), (z, -h / 2, h / 2)],
        sp.diag(m * (6 * R**2 + h**2) / 12, m * (6 * R**2 + h**2) / 12, m * R**2),
        lambda p: inr.cylindrical_shell(p[m], p[R], p[h]),
        {m: 2, R: sp.Rational(3, 2), h: 5},
        sp.diag(m * (3 * R**2 + h**2) / 12, m * (3 * R**2 + h**2) / 12, m * R**2),
    ),
    "solid_sphere": (
        vec(rr * sp.sin(th) * sp.cos(u), rr * sp.sin(th) * sp.sin(u), rr * sp.cos(th)),
        m / (sp.Rational(4, 3) * sp.pi * R**3),
        rr**2 * sp.sin(th),
        [(u, 0, 2 * sp.pi), (th, 0, sp.pi), (rr, 0, R)],
        sp.eye(3) * 2 * m * R**2 / 5,
        lambda p: inr.solid_sphere(p[m], p[R]),
        {m: 5, R: sp.Rational(3, 2)},
        sp.eye(3) * 2 * m * R**2 / 3,
    ),
    "hollow_sphere": (
        vec(R * sp.sin(th) * sp.cos(u), R * sp.sin(th) * sp.sin(u), R * sp.cos(th)),
        m / (4 * sp.pi * R**2),
        R**2 * sp.sin(th),
        [(u, 0, 2 * sp.pi), (th, 0, sp.pi)],
        sp.eye(3) * 2 * m * R**2 / 3,
        lambda p: inr.hollow_sphere(p[m], p[R]),
        {m: 5, R: sp.Rational(3, 2)},
        sp.eye(3) * 2 * m * R**2 / 5,
    ),
    "rectangular_plate": (
        vec(x, y, 0),
        m / (a_ * b_),
        1,
        [(x, -a_ / 2, a_ / 2), (y, -b_ / 2, b_ / 2)],
        sp.diag(m * b_**2 / 12, m * a_**2 / 12, m * (a_**2 + b_**2) / 12),
        lambda p: inr.rectangular_plate(p[m], p[a_], p[b_]),
        {m: 2, a_: 3, b_: sp.Rational(1, 2)},
        sp.diag(m * a_**2 / 12, m * b_**2 / 12, m * (a_**2 + b_**2) / 12),
    ),
    "box": (
        vec(x, y, z),
        m / (a_ * b_ * c_),
        1,
        [(x, -a_ / 2, a_ / 2), (y, -b_ / 2, b_ / 2), (z, -c_ / 2, c_ / 2)],
        sp.diag(m * (b_**2 + c_**2) / 12, m * (a_**2 + c_**2) / 12, m * (a_**2 + b_**2) / 12),
        lambda p: inr.box(p[m], p[a_], p[b_], p[c_]),
        {m: 2, a_: 3, b_: sp.Rational(1, 2), c_: 2},
        sp.diag(m * (b_**2 + c_**2) / 3, m * (a_**2 + c_**2) / 3, m * (a_**2 + b_**2) / 3),
    ),
}


def _body_check(name: str):
    r, dens, jac, limits, J_cat, call, pt, J_wrong = BODIES[name]

    def run(d: Derivation) -> None:
        mass, J = _body_tensor(r, dens, jac, limits)
        d.prove_equal(mass, m, strategy="cancel", claim=f"{name}: ∫ density = m")
        first = [sp.integrate(sp.expand(ri * dens * jac), *limits) for ri in r]
        d.prove_zero(vec(*first), strategy="expand", claim=f"{name}: ∫ r dm = 0: G at the origin")
        d.note(f"{name}: ∫ (r² 1 − r rᵀ) dm =", J)
        d.prove_equal(J, J_cat, strategy="cancel", claim=f"{name}: the catalogue tensor about G")
        d.reject(J, J_wrong, strategy="cancel", claim=f"{name}: a wrong catalogue tensor")
        d.confirm(
            call({k: float(v) for k, v in pt.items()}),
            floats(J_cat, pt),
            atol=CODE_ATOL,
            route=f"mechanics.inertia.{name} at a rational point",
        )

    run.__name__ = run.__qualname__ = f"body_{name}"
    return run


for _name in BODIES:
    check(
        f"thm.inertia-{_name.replace('_', '-')}",
        f"Homogeneous {_name.replace('_', ' ')}: inertia tensor about G by integrating the mass",
        kind="proof",
        defines=("eq4.34",),
        statement=f"J = ∫ (|r|² 1 − r rᵀ) dm over the homogeneous {_name.replace('_', ' ')} "
        "equals the catalogue tensor of mechanics.inertia",
    )(_body_check(_name))


@check(
    "thm.inertia-solid-cone",
    "Homogeneous solid cone: centre of mass at h/4 above the base, tensor about G",
    kind="proof",
    defines=("eq4.34",),
    statement="cone of base radius R and height h: G on the axis at 3h/4 from the apex, "
    "J_G = diag(3m(4R² + h²)/80, 3m(4R² + h²)/80, 3mR²/10); obtained about the apex by "
    "integration and moved to G by (4.38)",
)
def body_solid_cone(d: Derivation) -> None:
    dens = m / (sp.pi * R**2 * h / 3)
    r = vec(rr * sp.cos(u), rr * sp.sin(u), z)  # apex at the origin, axis e3
    limits = [(u, 0, 2 * sp.pi), (rr, 0, R * z / h), (z, 0, h)]
    mass, J_apex = _body_tensor(r, dens, rr, limits)
    d.prove_equal(mass, m, strategy="cancel", claim="∫ density = m")
    z_G = sp.integrate(sp.expand(z * dens * rr), *limits) / m
    d.prove_equal(z_G, 3 * h / 4, strategy="cancel", claim="G at 3h/4 from the apex")
    d.reject(z_G, 2 * h / 3, strategy="cancel", claim="G at 2h/3 (the triangle's centroid)")
    J_G = J_apex - m * particle_J(1, vec(0, 0, z_G))  # (4.38) backwards
    J_cat = sp.diag(
        3 * m * (4 * R**2 + h**2) / 80, 3 * m * (4 * R**2 + h**2) / 80, 3 * m * R**2 / 10
    )
    d.prove_equal(J_G, J_cat, strategy="cancel", claim="J_G of the catalogue")
    d.reject(J_apex, J_cat, strategy="cancel", claim="the tensor about the apex is J_G")
    d.confirm(
        inr.solid_cone(2.0, 1.5, 4.0),
        floats(J_cat, {m: 2, R: sp.Rational(3, 2), h: 4}),
        atol=CODE_ATOL,
        route="mechanics.inertia.solid_cone at a rational point",
    )
