"""Chapter 3.1.1–3.1.3: the kinetic energy of rigid bodies.
Equations (3.8)–(3.30).

The rigid body is a general particle system: N = 3 particles of positive symbolic
masses at free symbolic positions (T and J are sums over particles, so the
per-particle identities proved alongside carry over to any N), moving with the
velocity field v_k = v_G + ω × r′_k of the connection formula (2.74).  The
inertia tensor is built from the particles by the book's definitions
(3.16)–(3.17), (3.23), never taken from :mod:`mechanics`; the numeric routes
compare :mod:`mechanics.energy` with a direct particle sum.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from identities.book.ch03.power import EPS, particle_system
from identities.verify.catalogue import check
from identities.verify.proof import Derivation
from identities.verify.symbolic import cross, vec
from mechanics import energy as en
from mechanics import particles as pt

#: a particle sum of ~100 terms of size O(10) against a quadratic form with a
#: 3×3 tensor: rounding of a few ulp per term, relative 2^8 eps.
SUM_RTOL = 2**8 * EPS

HALF = sp.Rational(1, 2)
W = vec(*sp.symbols("omega_x omega_y omega_z", real=True))
V_G = vec(*sp.symbols("v_Gx v_Gy v_Gz", real=True))


def inertia_components(m, r) -> dict[str, sp.Expr]:
    """Moments J_x, J_y, J_z (3.16) and products D_xy, D_xz, D_yz (3.17) of particles."""
    x, y, z = ([rk[i] for rk in r] for i in range(3))

    def s(f):
        return sum((mk * f(k) for k, mk in enumerate(m)), sp.S.Zero)

    return {
        "J_x": s(lambda k: y[k] ** 2 + z[k] ** 2),
        "J_y": s(lambda k: z[k] ** 2 + x[k] ** 2),
        "J_z": s(lambda k: x[k] ** 2 + y[k] ** 2),
        "D_xy": s(lambda k: x[k] * y[k]),
        "D_xz": s(lambda k: x[k] * z[k]),
        "D_yz": s(lambda k: y[k] * z[k]),
    }


def inertia_matrix(c: dict[str, sp.Expr]) -> sp.Matrix:
    """The inertia tensor (3.23) from its components."""
    return sp.Matrix(
        [
            [c["J_x"], -c["D_xy"], -c["D_xz"]],
            [-c["D_xy"], c["J_y"], -c["D_yz"]],
            [-c["D_xz"], -c["D_yz"], c["J_z"]],
        ]
    )


def quadratic_form(c: dict[str, sp.Expr], w=W) -> sp.Expr:
    """The right side of (3.15) / (3.21)."""
    wx, wy, wz = w
    return (
        HALF * c["J_x"] * wx**2
        + HALF * c["J_y"] * wy**2
        + HALF * c["J_z"] * wz**2
        - c["D_xy"] * wx * wy
        - c["D_xz"] * wx * wz
        - c["D_yz"] * wy * wz
    )


def _centred(m, r):
    M = sum(m)
    G = sum((mk * rk for mk, rk in zip(m, r, strict=True)), sp.zeros(3, 1)) / M
    return M, [rk - G for rk in r]


def _random_body(seed: int, n: int = 40, offset=(0.0, 0.0, 0.0)):
    rng = np.random.default_rng(seed)
    m = rng.uniform(0.1, 2.0, n)
    r = rng.normal(size=(n, 3)) * [1.0, 0.6, 0.3] + offset
    return m, r


def _inertia_numeric(m, r_rel) -> np.ndarray:
    """(3.16)-(3.17), (3.23) by numpy: Σ m (|r|² 1 - r rᵀ)."""
    rr = np.einsum("k,ki,kj->ij", m, r_rel, r_rel)
    return np.trace(rr) * np.eye(3) - rr


@check(
    "eq3.14",
    "The internal kinetic energy of a rigid body as a sum of (ω·ω)(r′·r′) - (ω·r′)²",
    kind="proof",
    covers=("eq3.10", "eq3.11", "eq3.12", "eq3.13", "eq3.14"),
    defines=("eq3.8", "eq3.9"),
    statement="v′_k = ω × r′_k (3.9) gives T′ = Σ ½ m_k (ω × r′_k)² (3.10) and "
    "(ω × r)·(ω × r) = |ω|²|r|² sin² = (ω·ω)(r·r) - (ω·r)² (3.11)-(3.13), hence (3.14)",
)
def lagrange_identity(d: Derivation) -> None:
    r = vec(*sp.symbols("x y z", real=True))
    wr = cross(W, r)
    d.prove_equal(
        wr.dot(wr),
        W.dot(W) * r.dot(r) - W.dot(r) ** 2,
        strategy="expand",
        claim="(ω × r)·(ω × r) = (ω·ω)(r·r) - (ω·r)² (3.13)",
    )
    cos2 = W.dot(r) ** 2 / (W.dot(W) * r.dot(r))  # cos²[ω, r]
    d.prove_equal(
        W.dot(W) * r.dot(r) * (1 - cos2),
        W.dot(W) * r.dot(r) - W.dot(r) ** 2,
        strategy="cancel",
        claim="|ω|²|r|²(1 - cos²) = (ω·ω)(r·r) - (ω·r)² (3.11)-(3.12)",
    )
    d.reject(
        wr.dot(wr),
        W.dot(W) * r.dot(r) + W.dot(r) ** 2,
        strategy="expand",
        claim="|ω × r|² = (ω·ω)(r·r) + (ω·r)²",
    )
    m, rp, _ = particle_system()  # r′_k: the identity holds for any vectors, centred or not
    Tp = sum((HALF * mk * cross(W, rk).dot(cross(W, rk)) for mk, rk in zip(m, rp, strict=True)))
    book = HALF * sum((mk * rk.dot(rk) for mk, rk in zip(m, rp, strict=True))) * W.dot(
        W
    ) - HALF * sum((mk * W.dot(rk) ** 2 for mk, rk in zip(m, rp, strict=True)))
    d.prove_equal(Tp, book, strategy="expand", claim="(3.10) = (3.14) for a particle system")
    mn, rn = _random_body(11)
    rn = rn - np.average(rn, axis=0, weights=mn)
    wn = np.array([0.4, -1.3, 2.1])
    v_rel = np.cross(wn, rn)  # (3.9)
    T_num = pt.kinetic_energy(mn, v_rel)
    T_314 = 0.5 * np.sum(mn * np.sum(rn * rn, 1)) * wn @ wn - 0.5 * np.sum(mn * (rn @ wn) ** 2)
    d.confirm(
        T_314 / T_num,
        1.0,
        atol=SUM_RTOL,
        route="mechanics.particles.kinetic_energy of ω × r′_k against (3.14) by numpy (40 particles)",
    )


@check(
    "eq3.24",
    "Rigid body kinetic energy in matrix form: T = ½ m v_G² + ½ ωᵀ J^G ω",
    kind="proof",
    covers=("eq3.15", "eq3.22", "eq3.23", "eq3.24"),
    defines=("eq3.16", "eq3.17"),
    statement="for v_k = v_G + ω × r′_k (3.8): Σ ½ m_k v_k² = ½ m v_G² + T′ with "
    "T′ = ½ J_x ω_x² + ½ J_y ω_y² + ½ J_z ω_z² - D_xy ω_x ω_y - D_xz ω_x ω_z - D_yz ω_y ω_z "
    "(3.15) = ½ w J^G wᵀ (3.24), J^G the matrix (3.23) of (3.16)-(3.17)",
)
def rigid_kinetic_energy_matrix(d: Derivation) -> None:
    # one particle: the per-particle identity behind any N
    mk = sp.Symbol("m_k", positive=True)
    rk = vec(*sp.symbols("x_k y_k z_k", real=True))
    vk = V_G + cross(W, rk)
    Jk = inertia_matrix(inertia_components([mk], [rk]))
    d.prove_equal(
        HALF * mk * vk.dot(vk),
        HALF * mk * V_G.dot(V_G) + mk * V_G.dot(cross(W, rk)) + HALF * (W.T * Jk * W)[0],
        strategy="expand",
        claim="per particle: ½ m_k v_k² = ½ m_k v_G² + m_k v_G·(ω × r′_k) + ½ ωᵀ J_k ω; "
        "summed, the middle terms give v_G·(ω × Σ m_k r′_k) = 0 by (1.10)",
    )
    m, r, _ = particle_system()
    M, rp = _centred(m, r)
    v = [V_G + cross(W, x) for x in rp]  # (3.8)
    T = sum((HALF * a * b.dot(b) for a, b in zip(m, v, strict=True)), sp.S.Zero)  # (3.2)
    c = inertia_components(m, rp)
    J = inertia_matrix(c)
    cs = {k: sp.Symbol(k, real=True) for k in c}
    d.prove_equal(
        quadratic_form(cs),
        HALF * (W.T * inertia_matrix(cs) * W)[0],
        strategy="expand",
        claim="(3.15) = ½ w J wᵀ (3.24) with J from (3.23), for any moments and products",
    )
    d.prove_equal(
        T,
        HALF * M * V_G.dot(V_G) + HALF * (W.T * J * W)[0],
        strategy="numerator",
        claim="T = ½ m v_G² + ½ ωᵀ J^G ω for a general rigid particle system",
    )
    wrong = sp.Matrix(3, 3, lambda i, j: J[i, j] if i == j else -J[i, j])
    d.reject(
        T,
        HALF * M * V_G.dot(V_G) + HALF * (W.T * wrong * W)[0],
        strategy="numerator",
        claim="the inertia tensor with +D off the diagonal",
    )
    # a general symmetric matrix: the quadratic form reads off moments and products
    a = sp.symbols("a_11 a_12 a_13 a_22 a_23 a_33", real=True)
    S = sp.Matrix([[a[0], a[1], a[2]], [a[1], a[3], a[4]], [a[2], a[4], a[5]]])
    cS = {"J_x": a[0], "J_y": a[3], "J_z": a[5], "D_xy": -a[1], "D_xz": -a[2], "D_yz": -a[4]}
    d.prove_equal(
        HALF * (W.T * S * W)[0],
        quadratic_form(cS),
        strategy="expand",
        claim="½ wSwᵀ of any symmetric S is (3.15) with J = diagonal, D = -off-diagonal",
    )
    # numeric: 40 particles far from the origin, moving rigidly
    mn, rn = _random_body(7, offset=(1e3, -2e3, 5e2))
    Gn = pt.centre_of_mass(mn, rn)
    wn, vGn = np.array([0.7, -0.2, 1.5]), np.array([3.0, -1.0, 0.5])
    vel = vGn + np.cross(wn, rn - Gn)  # (3.8)
    T_particles = pt.kinetic_energy(mn, vel)
    J_num = _inertia_numeric(mn, rn - Gn)
    d.confirm(
        en.kinetic_energy_rigid(mn.sum(), vGn, wn, J_num) / T_particles,
        1.0,
        atol=SUM_RTOL,
        route="mechanics.energy.kinetic_energy_rigid with J^G by numpy against the particle sum "
        "(mechanics.particles.kinetic_energy), body 2e3 from the origin",
    )


@check(
    "eq3.21",
    "Kinetic energy of a rigid body turning about a point C at rest",
    kind="proof",
    covers=("eq3.18", "eq3.19", "eq3.20", "eq3.21"),
    statement="v_k = ω × CP_k (3.18)-(3.19) gives T = Σ ½ m_k (ω × r_k)² (3.20) = "
    "½ J^C_x ω_x² + ½ J^C_y ω_y² + ½ J^C_z ω_z² - D^C_xy ω_x ω_y - D^C_xz ω_x ω_z - D^C_yz ω_y ω_z",
)
def pure_rotation_kinetic_energy(d: Derivation) -> None:
    m, r, _ = particle_system()
    C = vec(*sp.symbols("x_C y_C z_C", real=True))
    rC = [rk - C for rk in r]  # origin at C
    v = [cross(W, x) for x in rC]  # (3.19)
    T = sum((HALF * a * b.dot(b) for a, b in zip(m, v, strict=True)), sp.S.Zero)
    c = inertia_components(m, rC)
    d.prove_equal(T, quadratic_form(c), strategy="expand", claim="(3.20) = (3.21)")
    d.reject(
        T,
        quadratic_form({**c, "D_xy": -c["D_xy"]}),
        strategy="expand",
        claim="(3.21) with +D_xy ω_x ω_y",
    )
    d.reject(
        T,
        quadratic_form(inertia_components(m, r)),
        strategy="expand",
        claim="moments about the origin instead of about C",
    )
    mn, rn = _random_body(5)
    Cn = np.array([0.3, 1.0, -0.4])
    wn = np.array([-1.1, 0.6, 0.9])
    d.confirm(
        en.kinetic_energy_rigid(mn.sum(), np.zeros(3), wn, _inertia_numeric(mn, rn - Cn))
        / pt.kinetic_energy(mn, np.cross(wn, rn - Cn)),
        1.0,
        atol=SUM_RTOL,
        route="mechanics.energy.kinetic_energy_rigid(m, 0, ω, J^C) against the particle sum",
    )


@check(
    "eq3.27",
    "Kinetic energy for a fixed axis direction",
    kind="proof",
    covers=("eq3.26", "eq3.27", "eq3.28", "eq3.29", "eq3.30"),
    defines=("eq3.25",),
    statement="ω = φ̇ e_z (3.25): T′ = ½ J^G_z φ̇² (3.26), T = ½ J^C_z φ̇² (3.27); directly, "
    "v_k = φ̇ ρ_k e_φ (3.28) and T = ½ (Σ m_k ρ_k²) φ̇² (3.29)-(3.30)",
)
def fixed_axis_kinetic_energy(d: Derivation) -> None:
    phid = sp.Symbol("phidot", real=True)
    w = vec(0, 0, phid)
    m, r, _ = particle_system()
    _, rp = _centred(m, r)
    cG, cC = inertia_components(m, rp), inertia_components(m, r)
    d.prove_equal(
        quadratic_form(cG, w),
        HALF * cG["J_z"] * phid**2,
        strategy="expand",
        claim="(3.15) with ω = φ̇ e_z: T′ = ½ J^G_z φ̇² (3.26)",
    )
    d.prove_equal(
        quadratic_form(cC, w),
        HALF * cC["J_z"] * phid**2,
        strategy="expand",
        claim="(3.21) with ω = φ̇ e_z: T = ½ J^C_z φ̇² (3.27)",
    )
    rho, ang, z = sp.symbols("rho varphi z", real=True)
    e_rho = vec(sp.cos(ang), sp.sin(ang), 0)
    e_phi = vec(-sp.sin(ang), sp.cos(ang), 0)
    d.prove_equal(
        cross(w, rho * e_rho + z * vec(0, 0, 1)),
        phid * rho * e_phi,
        strategy="expand",
        claim="v_k = φ̇ e_z × (ρ_k e_ρ + z_k e_z) = φ̇ ρ_k e_φ (3.28)",
    )
    vk = phid * rho * e_phi
    d.prove_equal(
        vk.dot(vk), phid**2 * rho**2, strategy="trigsimp", claim="(φ̇ ρ e_φ)² = φ̇² ρ² (3.29)"
    )
    d.prove_equal(
        cC["J_z"],
        sum((mk * (rk[0] ** 2 + rk[1] ** 2) for mk, rk in zip(m, r, strict=True))),
        strategy="expand",
        claim="J^C_z = Σ m_k ρ_k² (3.30)",
    )
    d.reject(
        quadratic_form(cC, w),
        HALF * cC["J_x"] * phid**2,
        strategy="expand",
        claim="T = ½ J^C_x φ̇² (the wrong axis)",
    )
    mn, rn = _random_body(9)
    pn = 1.7
    rho2 = rn[:, 0] ** 2 + rn[:, 1] ** 2
    d.confirm(
        en.kinetic_energy_fixed_axis(np.sum(mn * rho2), pn)
        / pt.kinetic_energy(mn, np.cross([0.0, 0.0, pn], rn)),
        1.0,
        atol=SUM_RTOL,
        route="mechanics.energy.kinetic_energy_fixed_axis(Σ m ρ², φ̇) against the particle sum",
    )
