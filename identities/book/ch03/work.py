"""Chapter 3.2.1–3.2.2: the work on a rigid body, and forces that do no work.
Equations (3.60)–(3.71), and the rolling constraint (3.77) of section 3.2.2.

Work is proved in its differential form: the work in a displacement dr_A and an
infinitesimal rotation δφ of a rigid body (3.60), or, per unit time, the power
with v_A and ω; the line integrals (3.65), (3.68)–(3.70) are sums of these along
the motion.  Forces and positions are general symbols (three particles); the
numeric routes use :mod:`mechanics.energy`.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from identities.book.ch03.power import EPS, particle_system
from identities.verify.catalogue import check
from identities.verify.proof import Derivation
from identities.verify.symbolic import cross, vec
from mechanics import energy as en
from mechanics import kinematics as kin

#: powers and works of O(1) forces and velocities summed over ≤ 40 terms: 2^8 eps.
NUM_ATOL = 2**8 * EPS
#: trapezoid rule on circular arcs of K = 2001 samples: error ≈ (Δφ)²/12 per unit
#: work with Δφ = π/2000, i.e. ≈ 2e-7; 2^32 eps ≈ 9.5e-7 bounds it.
ARC_ATOL = 2**32 * EPS

HALF = sp.Rational(1, 2)
DPHI = vec(*sp.symbols("dphi_x dphi_y dphi_z", real=True))  # δφ
N = 3


def _forces(tag: str = "", n: int = N) -> list[sp.Matrix]:
    return [vec(*sp.symbols(f"F{k}x{tag} F{k}y{tag} F{k}z{tag}", real=True)) for k in range(n)]


@check(
    "eq3.62",
    "The work on a rigid body: F · dr_A + M_A · δφ",
    kind="proof",
    covers=("eq3.60", "eq3.61", "eq3.62", "eq3.65", "eq3.68"),
    defines=("eq3.63",),
    statement="dr_k = dr_A + (r_A - r_k) × δφ (3.60) gives Σ F_k · dr_k = F · dr_A + M_A · δφ "
    "(3.61)-(3.62) with F = Σ F_k and M_A = Σ (r_k - r_A) × F_k (3.63); A = G gives (3.68)",
)
def rigid_body_work(d: Derivation) -> None:
    _, r, _ = particle_system()
    F = _forces()
    rA = vec(*sp.symbols("x_A y_A z_A", real=True))
    drA = vec(*sp.symbols("dx_A dy_A dz_A", real=True))
    d.prove_equal(
        drA + cross(rA - r[0], DPHI),
        drA + cross(DPHI, r[0] - rA),
        strategy="expand",
        claim="(3.60) is (2.74), v_k = v_A + ω × (r_k - r_A), times dt with δφ = ω dt",
    )
    dr = [drA + cross(rA - rk, DPHI) for rk in r]  # (3.60)
    Fsum = sum(F, sp.zeros(3, 1))
    M_A = sum((cross(rk - rA, Fk) for rk, Fk in zip(r, F, strict=True)), sp.zeros(3, 1))  # (3.63)
    dW = sum((Fk.dot(drk) for Fk, drk in zip(F, dr, strict=True)), sp.S.Zero)
    d.prove_equal(
        dW,
        Fsum.dot(drA) + M_A.dot(DPHI),
        strategy="expand",
        claim="Σ F_k · dr_k = F · dr_A + M_A · δφ (3.61)-(3.62), hence (3.65) and, at A = G, (3.68)",
    )
    M_wrong = sum((cross(rA - rk, Fk) for rk, Fk in zip(r, F, strict=True)), sp.zeros(3, 1))
    d.reject(
        dW,
        Fsum.dot(drA) + M_wrong.dot(DPHI),
        strategy="expand",
        claim="the moment taken as Σ (r_A - r_k) × F_k",
    )
    # numeric: the power of point forces on a moving rigid body, about two base points
    rng = np.random.default_rng(21)
    rn, Fn = rng.normal(size=(6, 3)), rng.normal(size=(6, 3))
    vG, w = np.array([0.3, -1.0, 0.2]), np.array([1.1, 0.4, -0.7])
    G = rn.mean(axis=0)
    v_points = kin.point_velocity(vG, w, rn - G)
    P_points = en.power(Fn, v_points)
    for A in (G, np.array([5.0, -3.0, 2.0])):
        vA = kin.point_velocity(vG, w, A - G)
        M_A_n = np.cross(rn - A, Fn).sum(axis=0)
        d.confirm(
            en.rigid_body_power(Fn.sum(axis=0), M_A_n, vA, w),
            P_points,
            atol=NUM_ATOL,
            route=f"mechanics.energy.rigid_body_power about A = {np.round(A, 2).tolist()} "
            "against Σ F_k · v_k (mechanics.energy.power)",
        )


@check(
    "eq3.64",
    "Internal forces do no work in a rigid body",
    kind="proof",
    covers=("eq3.64", "eq3.66", "eq3.67"),
    statement="dr_kj = δφ × r_kj (3.66); for central pair forces f_kj = λ_kj r_kj (λ_kj = λ_jk) "
    "½ Σ f_kj · (δφ × r_kj) = 0 (3.67), and F^i = 0, M^i = 0 give W^i = 0 (3.64)",
)
def rigid_internal_work(d: Derivation) -> None:
    _, r, _ = particle_system()
    rA = vec(*sp.symbols("x_A y_A z_A", real=True))
    drA = vec(*sp.symbols("dx_A dy_A dz_A", real=True))
    dr = [drA + cross(rA - rk, DPHI) for rk in r]
    d.prove_equal(
        dr[0] - dr[1],
        cross(DPHI, r[0] - r[1]),
        strategy="expand",
        claim="dr_kj = δφ × r_kj (3.66)",
    )
    idx = range(N)
    lam = {}
    for k in idx:
        for j in idx:
            if k < j:
                lam[k, j] = lam[j, k] = sp.Symbol(f"lambda_{k + 1}{j + 1}", real=True)
    f = {(k, j): lam[k, j] * (r[k] - r[j]) for (k, j) in lam}  # central, third law
    dWi = HALF * sum((f[k, j].dot(cross(DPHI, r[k] - r[j])) for (k, j) in f), sp.S.Zero)
    d.prove_zero(dWi, strategy="expand", claim="central pair forces: ½ Σ f_kj · (δφ × r_kj) = 0")
    Fi = sum(f.values(), sp.zeros(3, 1))
    Mi = sum((cross(r[k] - rA, f[k, j]) for (k, j) in f), sp.zeros(3, 1))
    d.prove_zero(Fi, strategy="expand", claim="F^i = 0 (1.23)")
    d.prove_zero(Mi, strategy="expand", claim="M^i_A = 0 for central forces (1.32)")
    d.prove_zero(
        sum((f[k, j].dot(dr[k]) for (k, j) in f), sp.S.Zero),
        strategy="expand",
        claim="W^i = F^i · dr_A + M^i_A · δφ = 0 (3.64), summed directly over the particles",
    )
    g = {}
    for k in idx:
        for j in idx:
            if k < j:
                g[k, j] = vec(*sp.symbols(f"g{k + 1}{j + 1}x g{k + 1}{j + 1}y g{k + 1}{j + 1}z"))
                g[j, k] = -g[k, j]
    dWg = HALF * sum((g[k, j].dot(cross(DPHI, r[k] - r[j])) for (k, j) in g), sp.S.Zero)
    d.reject(
        dWg, 0, strategy="expand", claim="third-law but non-central pair forces do no work either"
    )
    # numeric: springs between all pairs of a rigidly moving body deliver zero power
    rng = np.random.default_rng(8)
    rn = rng.normal(size=(5, 3))
    vG, w = np.array([0.5, 0.1, -0.3]), np.array([0.2, -1.4, 0.9])
    v = kin.point_velocity(vG, w, rn - rn.mean(axis=0))
    F_int = np.zeros_like(rn)
    for k in range(5):
        for j in range(5):
            if k != j:
                F_int[k] += en.spring_force(3.0, 0.5, rn[k], rn[j])
    d.confirm(
        en.power(F_int, v),
        0.0,
        atol=NUM_ATOL,
        route="mechanics.energy.spring_force between all pairs, mechanics.energy.power: zero "
        "for a rigid velocity field",
    )


@check(
    "eq3.69",
    "The work of gravity on a rigid body",
    kind="proof",
    covers=("eq3.69",),
    statement="M_G = Σ (r_k - r_G) × m_k g = 0, so W^grav = -[Φ(r_G(t2)) - Φ(r_G(t1))] "
    "with Φ = -m g · r_G (3.56)",
)
def gravity_work_rigid(d: Derivation) -> None:
    m, r, _ = particle_system()
    g = vec(*sp.symbols("g_x g_y g_z", real=True))
    M = sum(m)
    G = sum((mk * rk for mk, rk in zip(m, r, strict=True)), sp.zeros(3, 1)) / M
    M_G = sum((cross(rk - G, mk * g) for mk, rk in zip(m, r, strict=True)), sp.zeros(3, 1))
    d.prove_zero(M_G, strategy="together", claim="M_G = 0 for uniform gravity")
    M_O = sum((cross(rk, mk * g) for mk, rk in zip(m, r, strict=True)), sp.zeros(3, 1))
    d.reject(M_O, sp.zeros(3, 1), strategy="together", claim="the moment about the origin vanishes")
    drG = vec(*sp.symbols("dx_G dy_G dz_G", real=True))
    rp = [vec(*sp.symbols(f"xp_{k} yp_{k} zp_{k}", real=True)) for k in range(N)]  # r′_k
    dW = sum((mk * g.dot(drG + cross(DPHI, x)) for mk, x in zip(m, rp, strict=True)), sp.S.Zero)
    S = sum((mk * x for mk, x in zip(m, rp, strict=True)), sp.zeros(3, 1))
    d.prove_equal(
        dW,
        M * g.dot(drG) + g.dot(cross(DPHI, S)),
        strategy="expand",
        claim="in a rigid displacement dr_k = dr_G + δφ × r′_k gravity's work is "
        "m g · dr_G + g · (δφ × Σ m_k r′_k) = m g · dr_G = -dΦ (Σ m_k r′_k = 0, as in M_G); (3.69)",
    )
    mn = np.array([1.0, 2.0, 0.5, 3.0])
    rng = np.random.default_rng(2)
    rn = rng.normal(size=(4, 3))
    gn = np.array([0.0, 0.0, -9.81])
    vG, w = np.array([0.3, 0.0, 1.2]), np.array([0.5, -0.8, 2.0])
    Gn = np.average(rn, axis=0, weights=mn)
    v = kin.point_velocity(vG, w, rn - Gn)
    # Φ is linear in r_G, so its change over a unit step along v_G is exactly dΦ/dt
    dPhi_n = en.gravity_potential(mn, rn + vG, g=gn) - en.gravity_potential(mn, rn, g=gn)
    d.confirm(
        en.power(mn[:, None] * gn, v),
        -dPhi_n,
        atol=NUM_ATOL * 100,  # Φ ≈ 100 here: rounding of the two potentials, 2^8 eps each
        route="mechanics.energy.power of the weights on a turning body = -dΦ/dt from "
        "mechanics.energy.gravity_potential",
    )


@check(
    "eq3.70",
    "The work of a couple and the rotational potential energy",
    kind="proof",
    covers=("eq3.70", "eq3.71"),
    statement="a couple (F at P_1, -F at P_2) does work (P_2P_1 × F) · δφ, independent of the base "
    "point; about a fixed axis δφ = dφ e_z and W_rot = ∫ M_z dφ (3.70); M_z = M_z(φ) has "
    "Φ_rot = -∫ M_z dφ (3.71); a torsion moment -τ_0 φ has Φ_rot = ½ τ_0 φ²",
)
def couple_work(d: Derivation) -> None:
    r1, r2 = (vec(*sp.symbols(f"x_{k} y_{k} z_{k}", real=True)) for k in (1, 2))
    F = vec(*sp.symbols("F_x F_y F_z", real=True))
    rA = vec(*sp.symbols("x_A y_A z_A", real=True))
    drA = vec(*sp.symbols("dx_A dy_A dz_A", real=True))
    dW = F.dot(drA + cross(rA - r1, DPHI)) - F.dot(drA + cross(rA - r2, DPHI))
    M = cross(r1 - r2, F)
    d.prove_equal(dW, M.dot(DPHI), strategy="expand", claim="dW of a couple = M · δφ, no dr_A term")
    d.reject(dW, M.dot(DPHI) + F.dot(drA), strategy="expand", claim="a couple also works with dr_A")
    phi, phip, tau0 = sp.symbols("phi phi' tau_0", real=True)
    Mz = sp.Function("M_z")
    d.prove_equal(
        M.dot(vec(0, 0, 1) * sp.Symbol("dphi")),
        M[2] * sp.Symbol("dphi"),
        strategy="expand",
        claim="δφ = dφ e_z: dW = M_z dφ (3.70)",
    )
    Phi_rot = -sp.Integral(Mz(phip), (phip, 0, phi))
    d.prove_equal(
        -sp.diff(Phi_rot, phi),
        Mz(phi),
        strategy="expand",
        claim="Φ_rot = -∫ M_z dφ′ (3.71): -dΦ_rot/dφ = M_z, so W_rot = -ΔΦ_rot",
    )
    torsion = -sp.integrate(-tau0 * phip, (phip, 0, phi))
    d.prove_equal(torsion, tau0 * phi**2 / 2, strategy="expand", claim="torsion: Φ_rot = ½ τ_0 φ²")
    d.reject(torsion, tau0 * phi**2, strategy="expand", claim="torsion: Φ_rot = τ_0 φ²")
    # numeric: two opposite follower forces in the xy-plane, turning with the body by π/2
    # about e_z (so the moment's z component stays constant)
    p1, p2 = np.array([0.8, 0.1, 0.3]), np.array([-0.2, 0.5, -0.4])
    F0 = np.array([0.3, -1.2, 0.0])
    ang = np.linspace(0.0, np.pi / 2, 2001)
    c, s = np.cos(ang)[:, None], np.sin(ang)[:, None]

    def turned(p):
        return np.concatenate([c * p[0] - s * p[1], s * p[0] + c * p[1], 0 * c + p[2]], axis=1)

    F_t = turned(F0)
    W_paths = en.work_along_path(F_t, turned(p1)) + en.work_along_path(-F_t, turned(p2))
    d.confirm(
        en.work_of_couple(np.cross(p1 - p2, F0), [0.0, 0.0, np.pi / 2]),
        W_paths,
        atol=ARC_ATOL,
        route="mechanics.energy.work_of_couple against the two forces' line integrals along "
        "their arcs (mechanics.energy.work_along_path)",
    )
    h = 2.0**-20
    fd = -(en.torsion_potential(2.5, 0.7 + h) - en.torsion_potential(2.5, 0.7 - h)) / (2 * h)
    d.confirm(
        fd,
        en.torsion_moment(2.5, 0.7),
        atol=2**24 * EPS,  # central difference of a quadratic: exact up to rounding eps/h
        route="mechanics.energy: -dΦ_rot/dφ by a central difference = torsion_moment",
    )


@check(
    "thm.rolling-does-no-work",
    "Rolling without slipping: contact forces do no work",
    kind="proof",
    covers=("eq3.77",),
    statement="a body rolling on a fixed surface has v_C = v_G + ω × GC = 0, so a contact force "
    "(normal force plus static friction) at C has power F · v_G + (GC × F) · ω = 0; for the "
    "cylinder of Example 3.6 the constraint is ẋ = r φ̇ (3.77); between two moving bodies the "
    "normal force and its reaction do no net work",
)
def rolling_no_work(d: Derivation) -> None:
    F = vec(*sp.symbols("F_x F_y F_z", real=True))
    w = vec(*sp.symbols("omega_x omega_y omega_z", real=True))
    c = vec(*sp.symbols("c_x c_y c_z", real=True))  # GC, from G to the contact point
    vG = -cross(w, c)  # rolling: v_C = v_G + ω × GC = 0
    P = F.dot(vG) + cross(c, F).dot(w)  # (3.65) per unit time, base point G
    d.prove_zero(
        P, strategy="expand", claim="power of any contact force at C on a rolling body = 0"
    )
    slip = vec(*sp.symbols("s_x s_y s_z", real=True))
    P_slip = F.dot(vG + slip) + cross(c, F).dot(w)
    d.reject(P_slip, 0, strategy="expand", claim="the same when the contact slips (v_C = s ≠ 0)")
    d.prove_equal(P_slip, F.dot(slip), strategy="expand", claim="slipping: P = F · v_C")
    # the cylinder on the incline: x along the slope, y out of it, z out of the page
    x, phi, r = sp.symbols("xdot phidot r", real=True)
    v_C = vec(x, 0, 0) + cross(vec(0, 0, -phi), vec(0, -r, 0))
    d.prove_equal(v_C[0], x - r * phi, strategy="expand", claim="contact velocity ẋ - r φ̇")
    d.prove_zero(v_C.subs(x, r * phi), strategy="expand", claim="(3.77) ẋ = r φ̇ gives v_C = 0")
    # two moving bodies: normal force N n on body 1, -N n on body 2, equal normal velocities
    n = vec(*sp.symbols("n_x n_y n_z", real=True))
    Nn = sp.Symbol("N", real=True)
    v1, t2 = vec(*sp.symbols("v1x v1y v1z", real=True)), vec(*sp.symbols("t_x t_y t_z", real=True))
    tang = t2 - t2.dot(n) / n.dot(n) * n  # any velocity difference tangent to the surface
    d.prove_zero(
        (Nn * n).dot(v1) + (-Nn * n).dot(v1 - tang),
        strategy="together",
        claim="normal force and reaction: net power N n · (v_1 - v_2) = 0 when v_1 - v_2 ⟂ n",
    )
    vG_n, w_n, GC = np.array([1.2, 0.0, 0.0]), np.array([0.0, 0.0, -2.4]), np.array([0, -0.5, 0])
    Fc = np.array([-3.0, 40.0, 0.0])
    d.confirm(
        [en.contact_power(Fc, vG_n, w_n, GC), en.rolling_contact_power(Fc, vG_n, w_n, GC)],
        [0.0, 0.0],
        atol=NUM_ATOL,
        route="mechanics.energy.contact_power and rolling_contact_power: zero when rolling",
    )
    n_hat, v1n = np.array([0.6, 0.8, 0.0]), np.array([1.0, -2.0, 0.5])
    d.confirm(
        en.pair_power(7.0 * n_hat, v1n, v1n - 0.9 * np.array([-0.8, 0.6, 0.0])),
        0.0,
        atol=NUM_ATOL,
        route="mechanics.energy.pair_power: normal force and reaction, tangential relative velocity",
    )
    d.confirm(
        en.contact_power(Fc, vG_n + np.array([0.5, 0, 0]), w_n, GC),
        Fc @ [0.5, 0, 0],
        atol=NUM_ATOL,
        route="mechanics.energy.contact_power = F · v_C when the contact slips",
    )
