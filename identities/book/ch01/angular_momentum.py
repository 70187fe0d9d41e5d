"""Chapter 1.1–1.3 and 1.5: angular momentum of particle systems.  The centre-of-mass
decomposition (1.8)–(1.15), (1.42); internal moments (1.25)–(1.33), (1.40); the
connection formula and a moving base point (1.43)–(1.53); angular impulse
(1.58)–(1.61); projection on a fixed direction and cylindrical components
(1.65)–(1.77).

The systems are those of :mod:`identities.book.ch01.momentum`: N = 4 (or 3) particles with
positive symbolic masses and positions that are arbitrary functions of time; pair
forces f_jk = -f_kj free (third law only), central f_jk = φ_jk (r_j - r_k) with
φ_jk = φ_kj, or non-central ψ_jk e_z × (r_j - r_k) (third law, not central: the
negative control of the angular momentum principle).
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from identities.book.ch01.momentum import (
    CODE_ATOL,
    EPS,
    M_NUM,
    QUADRATURE_ATOL,
    R_NUM,
    SIM_ATOL,
    V_NUM,
    N,
    at_point,
    d_dt,
    external_forces,
    internal_forces,
    masses,
    msum,
    newton,
    num_angular_momentum,
    num_centre_of_mass,
    num_moment_of_forces,
    num_momentum,
    pair_forces,
    positions,
    simulate,
)
from identities.verify.catalogue import check
from identities.verify.proof import Derivation
from identities.verify.symbolic import cross, floats, functions_of_time, t, unit_vector, vec

ez = vec(0, 0, 1)


def _masses_with_total(n: int = N):
    """Masses m_2, ..., m_n and the total M as free symbols, m_1 = M - m_2 - ... - m_n:
    then r_G = Σ m_j r_j / M has the single denominator M, and an identity that needs
    Σ m_j = M reduces with ``expand`` (M · M⁻¹ = 1) instead of a slow ``cancel``."""
    M = sp.Symbol("M", positive=True)
    rest = list(sp.symbols(f"m_2:{n + 1}", positive=True))
    return [M - sum(rest), *rest], M


def _L(m, r, v, A) -> sp.Matrix:
    """L_A = Σ AP_j × m_j v_j (1.8), with absolute velocities."""
    return msum(cross(rj - A, mj * vj) for mj, rj, vj in zip(m, r, v, strict=True))


def _M(r, F, A) -> sp.Matrix:
    return msum(cross(rj - A, Fj) for rj, Fj in zip(r, F, strict=True))


def _sub_total(expr, m):
    """Numeric masses M_NUM into an expression in M, m_2, ..., m_n."""
    M = sp.Symbol("M", positive=True)
    return expr.subs({M: sp.Rational(M_NUM.sum()), **dict(zip(m[1:], M_NUM[1:], strict=True))})


@check(
    "eq1.12",
    "The two parts of the angular momentum: L_A = AG × p + L'_G, and L_G = L'_G",
    kind="proof",
    covers=("eq1.9", "eq1.10", "eq1.11", "eq1.12", "eq1.14", "eq1.15", "eq1.42"),
    defines=("eq1.8", "eq1.13"),
    statement="with r'_j = GP_j, v'_j = ṙ'_j: Σ m_j r'_j = Σ m_j v'_j = 0 (1.10), "
    "L_A = AG × m v_G + Σ r'_j × m_j v'_j (1.12) for A at rest, and L_G = L'_G (1.15)",
)
def koenig_angular_momentum(d: Derivation) -> None:
    m, mt = _masses_with_total()
    r = positions()
    v = d_dt(r)
    r_G = msum(mj * rj for mj, rj in zip(m, r, strict=True)) / mt
    v_G = sp.diff(r_G, t)
    A = vec(*sp.symbols("a_x a_y a_z", real=True))
    rel = [rj - r_G for rj in r]  # r'_j = GP_j
    vrel = d_dt(rel)  # v'_j
    d.prove_equal(
        msum(v), msum(v_G + vr for vr in vrel), strategy="expand", claim="v_j = v_G + v'_j (1.9)"
    )
    d.prove_zero(
        msum(mj * x for mj, x in zip(m, rel, strict=True)),
        strategy="expand",
        claim="Σ m_j r'_j = 0 (1.10)",
    )
    d.prove_zero(
        msum(mj * x for mj, x in zip(m, vrel, strict=True)),
        strategy="expand",
        claim="Σ m_j v'_j = 0 (1.10)",
    )
    L_A = _L(m, r, v, A)
    L_rel = _L(m, rel, vrel, sp.zeros(3, 1))  # L'_G
    d.prove_equal(
        L_A,
        _L(m, [r_G - A + x for x in rel], [v_G + x for x in vrel], sp.zeros(3, 1)),
        strategy="expand",
        claim="(1.11): L_A = Σ (AG + r'_j) × m_j (v_G + v'_j)",
    )
    d.prove_equal(
        L_A, cross(r_G - A, mt * v_G) + L_rel, strategy="expand", claim="L_A = AG × p + L'_G (1.12)"
    )
    L_G = _L(m, r, v, r_G)  # (1.13)
    d.prove_equal(L_G, L_rel, strategy="expand", claim="L_G = L'_G (1.14)-(1.15)")
    d.reject(
        L_A,
        cross(A - r_G, mt * v_G) + L_rel,
        strategy="expand",
        claim="L_A = GA × p + L'_G (sign of the external part)",
    )
    centroid = msum(r) / N
    d.reject(
        L_A,
        cross(centroid - A, mt * sp.diff(centroid, t))
        + _L(m, [rj - centroid for rj in r], d_dt([rj - centroid for rj in r]), sp.zeros(3, 1)),
        strategy="expand",
        claim="the same split about the unweighted centroid",
    )
    An = np.array([0.5, -1.0, 2.0])
    L_num, route = num_angular_momentum(M_NUM, R_NUM, V_NUM, An)
    split = _sub_total(at_point(cross(r_G - A, mt * v_G) + L_rel, r, R_NUM, V_NUM), m)
    d.confirm(
        L_num,
        floats(split, dict(zip(A, [sp.Rational(1, 2), -1, 2], strict=True))).ravel(),
        atol=CODE_ATOL,
        route=f"{route} about A = AG × p + L'_G evaluated",
    )
    G_num, route_G = num_centre_of_mass(M_NUM, R_NUM)
    LG_num, _ = num_angular_momentum(M_NUM, R_NUM, V_NUM, G_num)
    d.confirm(
        LG_num,
        floats(_sub_total(at_point(L_rel, r, R_NUM, V_NUM), m)).ravel(),
        atol=CODE_ATOL,
        route=f"{route} about {route_G} = L'_G (relative velocities)",
    )


@check(
    "eq1.31",
    "The internal moment: Newton's third law makes it independent of the base point",
    kind="proof",
    covers=("eq1.25", "eq1.26", "eq1.27", "eq1.28", "eq1.29", "eq1.30", "eq1.31"),
    statement="L̇_A = M^i_A + M^e_A (1.25)-(1.27) with M^i_A = Σ AP_j × F^i_j = "
    "(1/2) Σ_jk r_jk × f_jk = M^i (1.28)-(1.31): the same for every A",
)
def internal_moment(d: Derivation) -> None:
    m, r = masses(), positions()
    v = d_dt(r)
    A = vec(*sp.symbols("a_x a_y a_z", real=True))
    f = pair_forces(kind="third-law")
    Fi, Fe = internal_forces(f), external_forces()
    F = [x + y for x, y in zip(Fi, Fe, strict=True)]
    Ldot = newton(sp.diff(_L(m, r, v, A), t), m, r, F)
    d.prove_equal(
        Ldot,
        _M(r, Fi, A) + _M(r, Fe, A),
        strategy="expand",
        claim="L̇_A = Σ (v_j × m_j v_j + AP_j × m_j r̈_j) = M^i_A + M^e_A (1.25)-(1.27)",
    )
    half_sum = msum(cross(r[j] - r[k], f[j, k]) for j in range(N) for k in range(N)) / 2
    d.prove_equal(
        _M(r, Fi, A),
        half_sum,
        strategy="expand",
        claim="M^i_A = (1/2) Σ_jk r_jk × f_jk (1.28)-(1.31): no A left",
    )
    d.reject(
        _M(r, internal_forces(pair_forces(kind="free")), A),
        _M(r, internal_forces(pair_forces(kind="free")), sp.zeros(3, 1)),
        strategy="expand",
        claim="M^i_A independent of A without the third law",
    )
    d.reject(
        half_sum, sp.zeros(3, 1), strategy="expand", claim="the third law alone makes M^i vanish"
    )
    # numeric: non-central third-law pair forces give the same internal moment about any point
    ff = np.array([[0.5, -1.0, 2.0], [1.0, 1.0, 0.0], [-2.0, 0.5, 1.5]])  # f_12, f_13, f_23
    pairs = [(0, 1), (0, 2), (1, 2)]
    Fin = np.zeros((3, 3))
    for (j, k), fjk in zip(pairs, ff, strict=True):
        Fin[j] += fjk
        Fin[k] -= fjk
    M_about_O, route = num_moment_of_forces(R_NUM[:3], Fin, np.zeros(3))
    M_about_A, _ = num_moment_of_forces(R_NUM[:3], Fin, np.array([3.0, -2.0, 7.0]))
    d.confirm(M_about_A, M_about_O, atol=CODE_ATOL, route=f"{route}: M^i about A = M^i about O")
    M_half = sum(np.cross(R_NUM[j] - R_NUM[k], fjk) for (j, k), fjk in zip(pairs, ff, strict=True))
    d.confirm(M_about_O, M_half, atol=CODE_ATOL, route=f"{route} = Σ_(j<k) r_jk × f_jk")


@check(
    "eq1.33",
    "Central internal forces: the principle of angular momentum L̇_A = M^e_A",
    kind="proof",
    covers=("eq1.32", "eq1.33", "eq1.40"),
    statement="for f_jk = φ_jk (r_j - r_k), φ_jk = φ_kj (f_jk ∥ r_jk), M^i_A = 0 (1.32) and "
    "L̇_A = M^e_A (1.33) about a fixed A; non-central third-law forces break it",
)
def angular_momentum_principle(d: Derivation) -> None:
    m, r = masses(), positions()
    v = d_dt(r)
    A = vec(*sp.symbols("a_x a_y a_z", real=True))
    Fe = external_forces()
    Fi = internal_forces(pair_forces(kind="central", r=r))
    d.prove_zero(_M(r, Fi, A), strategy="expand", claim="M^i_A = 0 for central pair forces (1.32)")
    F = [x + y for x, y in zip(Fi, Fe, strict=True)]
    Ldot = newton(sp.diff(_L(m, r, v, A), t), m, r, F)
    d.prove_equal(Ldot, _M(r, Fe, A), strategy="expand", claim="L̇_A = M^e_A (1.33), (1.40)")
    Fi_nc = internal_forces(pair_forces(kind="non-central", r=r))
    F_nc = [x + y for x, y in zip(Fi_nc, Fe, strict=True)]
    d.reject(
        newton(sp.diff(_L(m, r, v, A), t), m, r, F_nc),
        _M(r, Fe, A),
        strategy="expand",
        claim="L̇_A = M^e_A with non-central pair forces f_jk = ψ_jk e_z × r_jk (third law holds)",
    )
    sim = simulate(external=True, noncentral=0.0)
    L_num, route = num_angular_momentum(sim["m"], sim["r"], sim["v"], np.zeros(3))
    d.confirm(
        L_num - L_num[0],
        sim["H_O"],
        atol=SIM_ATOL,
        route=f"simulation (springs, gravity, pulse): {route} changes by ∫ M^e_O dt",
    )
    sim_nc = simulate(external=True, noncentral=0.7)
    L_nc, _ = num_angular_momentum(sim_nc["m"], sim_nc["r"], sim_nc["v"], np.zeros(3))
    drift = float(np.max(np.abs(L_nc - L_nc[0] - sim_nc["H_O"])))
    d.confirm(
        drift > 1e6 * SIM_ATOL,
        True,
        atol=0.0,
        route=f"negative control: with non-central pair forces ψ = 0.7 ΔL_O - ∫ M^e_O dt = {drift:.3g}",
    )


@check(
    "eq1.46",
    "The connection formula for angular momentum",
    kind="proof",
    covers=("eq1.43", "eq1.44", "eq1.45", "eq1.46"),
    statement="L_B = L_A + BA × p for any two points A, B",
)
def connection_formula(d: Derivation) -> None:
    m, r = masses(), positions()
    v = d_dt(r)
    A = vec(*sp.symbols("a_x a_y a_z", real=True))
    B = vec(*sp.symbols("b_x b_y b_z", real=True))
    p = msum(mj * vj for mj, vj in zip(m, v, strict=True))
    L_B = _L(m, r, v, B)
    d.prove_equal(
        L_B,
        cross(A - B, p) + _L(m, r, v, A),
        strategy="expand",
        claim="L_B = Σ (BA + AP_j) × m_j v_j = BA × p + L_A (1.43)-(1.46)",
    )
    d.reject(L_B, cross(B - A, p) + _L(m, r, v, A), strategy="expand", claim="L_B = L_A + AB × p")
    An, Bn = np.array([0.5, -1.0, 2.0]), np.array([-3.0, 1.0, 0.25])
    LA, route = num_angular_momentum(M_NUM, R_NUM, V_NUM, An)
    LB, _ = num_angular_momentum(M_NUM, R_NUM, V_NUM, Bn)
    pn, route_p = num_momentum(M_NUM, V_NUM)
    d.confirm(LB, LA + np.cross(An - Bn, pn), atol=CODE_ATOL, route=f"{route}, {route_p}")


@check(
    "eq1.50",
    "The angular momentum principle for a moving base point",
    kind="proof",
    covers=("eq1.47", "eq1.48", "eq1.49", "eq1.50"),
    statement="for B(t) moving with v_B: L̇_B + v_B × p = M_B, with L_B = Σ BP_j × m_j v_j "
    "(absolute velocities)",
)
def moving_base_point(d: Derivation) -> None:
    m, r = masses(), positions()
    v = d_dt(r)
    A = vec(*sp.symbols("a_x a_y a_z", real=True))
    (B,) = positions(1, tag="B")
    v_B = sp.diff(B, t)
    Fe = external_forces()
    F = [x + y for x, y in zip(internal_forces(pair_forces(kind="central", r=r)), Fe, strict=True)]
    p = msum(mj * vj for mj, vj in zip(m, v, strict=True))
    L_A, L_B = _L(m, r, v, A), _L(m, r, v, B)
    Ldot_A, Ldot_B = sp.diff(L_A, t), sp.diff(L_B, t)
    d.prove_equal(
        Ldot_B,
        Ldot_A + cross(-v_B, p) + cross(A - B, sp.diff(p, t)),
        strategy="expand",
        claim="(1.47): d/dt of L_B = L_A + BA × p, with d(BA)/dt = -v_B",
    )
    d.prove_equal(
        Ldot_A,
        Ldot_B + cross(v_B, p) + cross(B - A, sp.diff(p, t)),
        strategy="expand",
        claim="(1.48): L̇_A = L̇_B + v_B × p + AB × ṗ",
    )
    pdot_F = newton(sp.diff(p, t), m, r, F)
    M_A, M_B = _M(r, Fe, A), _M(r, Fe, B)
    d.prove_equal(
        newton(Ldot_B + cross(v_B, p), m, r, F) + cross(B - A, pdot_F),
        M_A,
        strategy="expand",
        claim="(1.49): L̇_B + v_B × p + AB × F = M_A",
    )
    lhs = newton(Ldot_B + cross(v_B, p), m, r, F)
    d.prove_equal(lhs, M_B, strategy="expand", claim="(1.50): L̇_B + v_B × p = M_B, B moving")
    d.reject(
        newton(Ldot_B, m, r, F),
        M_B,
        strategy="expand",
        claim="L̇_B = M_B for a moving B (the v_B × p term dropped)",
    )
    d.reject(lhs - 2 * cross(v_B, p), M_B, strategy="expand", claim="L̇_B - v_B × p = M_B (sign)")
    # numeric: along the simulation, B(t) = (cos t, sin t, t/2); central-difference L̇_B
    sim = simulate(external=True, noncentral=0.0)
    ts = sim["t"]
    Bt = np.stack([np.cos(ts), np.sin(ts), ts / 2], axis=-1)
    vB = np.stack([-np.sin(ts), np.cos(ts), np.full_like(ts, 0.5)], axis=-1)
    L_B_num, route = num_angular_momentum(sim["m"], sim["r"], sim["v"], Bt)
    p_num, _ = num_momentum(sim["m"], sim["v"])
    # integrate (1.50): L_B(T) - L_B(0) = ∫ (M_B - v_B × p) dt with M_B = M_O - OB × F;
    # ∫ M_O dt is the angular impulse H_O the simulation integrates with the motion, and
    # F = ṗ is the total external force (gravity and the pulse: internal forces cancel)
    from scipy.integrate import simpson

    from identities.book.ch01.momentum import _pulse

    F_tot = sim["m"].sum() * np.array([0.0, 0.0, -9.81]) + np.array([_pulse(x) for x in ts])
    integrand = -np.cross(Bt, F_tot) - np.cross(vB, p_num)
    lhs_int = L_B_num[-1] - L_B_num[0]
    rhs_int = (sim["H_O"][-1] - sim["H_O"][0]) + simpson(integrand, x=ts, axis=0)
    d.confirm(
        lhs_int,
        rhs_int,
        atol=QUADRATURE_ATOL,
        route=f"simulation, {route} about B(t) on a helix: ΔL_B = ∫ (M_B - v_B × p) dt "
        "(Simpson on the simulation's samples)",
    )


@check(
    "eq1.51",
    "The centre of mass as base point: L̇_G = M_G, L̇'_G = M_G, L̇'_G + AG × ṗ = M_A",
    kind="proof",
    covers=("eq1.51", "eq1.52", "eq1.53"),
    statement="no correction term for B = G, however G moves; the same with L'_G (1.52); "
    "L̇'_G + AG × ṗ = M_A (1.53) for any A, moving or not",
)
def centre_of_mass_base_point(d: Derivation) -> None:
    n = 3
    m, mt = _masses_with_total(n)
    r = positions(n)
    v = d_dt(r)
    r_G = msum(mj * rj for mj, rj in zip(m, r, strict=True)) / mt
    v_G = sp.diff(r_G, t)
    Fi = internal_forces(pair_forces(n, kind="central", r=r), n)
    # Newton's law read as the external force each motion needs: F^e_j = m_j r̈_j - F^i_j
    # (every motion is possible, so an identity in r_j(t) holds for every force)
    Fe = [mj * sp.diff(rj, t, 2) - fi for mj, rj, fi in zip(m, r, Fi, strict=True)]
    M_G = _M(r, Fe, r_G)
    L_G = _L(m, r, v, r_G)
    d.prove_equal(sp.diff(L_G, t), M_G, strategy="expand", claim="L̇_G = M_G (1.51)")
    rel = [rj - r_G for rj in r]
    L_rel = _L(m, rel, d_dt(rel), sp.zeros(3, 1))
    d.prove_equal(sp.diff(L_rel, t), M_G, strategy="expand", claim="L̇'_G = M_G (1.52)")
    (A,) = positions(1, tag="A")  # any motion of A
    p = mt * v_G
    d.prove_equal(
        sp.diff(L_rel, t) + cross(r_G - A, sp.diff(p, t)),
        _M(r, Fe, A),
        strategy="expand",
        claim="L̇'_G + AG × ṗ = M_A (1.53), A(t) arbitrary",
    )
    d.reject(
        sp.diff(_L(m, r, v, A), t),
        _M(r, Fe, A),
        strategy="expand",
        claim="L̇_A = M_A for the moving A (as if A were G)",
    )
    # numeric: the simulation's G; L_G from mechanics changes by ∫ M_G dt
    sim = simulate(external=True, noncentral=0.0)
    ts = sim["t"]
    G, route_G = num_centre_of_mass(sim["m"], sim["r"])
    L_G_num, route = num_angular_momentum(sim["m"], sim["r"], sim["v"], G)
    from scipy.integrate import simpson

    Fe_n = np.zeros_like(sim["r"]) + sim["m"][None, :, None] * np.array([0.0, 0.0, -9.81])
    from identities.book.ch01.momentum import _pulse

    Fe_n[:, 0] += np.array([_pulse(x) for x in ts])
    M_G_num, route_M = num_moment_of_forces(sim["r"], Fe_n, G)
    d.confirm(
        L_G_num[-1] - L_G_num[0],
        simpson(M_G_num, x=ts, axis=0),
        atol=QUADRATURE_ATOL,
        route=f"simulation: {route} about {route_G} changes by ∫ {route_M} about G dt",
    )


@check(
    "eq1.60",
    "Angular impulse: ΔL_A = ∫ M_A dt, conserved when M_A = 0",
    kind="proof",
    covers=("eq1.58", "eq1.60", "eq1.61"),
    defines=("eq1.59",),
    statement="L_A(t2) - L_A(t1) = ∫_{t1}^{t2} M^e_A dt = H_A (1.58)-(1.60); L_A constant "
    "when M_A = 0 (1.61); central pair forces, A at rest",
)
def angular_impulse(d: Derivation) -> None:
    n = 3
    m, r = masses(n), positions(n)
    v = d_dt(r)
    A = vec(*sp.symbols("a_x a_y a_z", real=True))
    t1, tau = sp.symbols("t_1 tau", real=True)
    Fe = [vec(*functions_of_time(f"F_{j}x", f"F_{j}y", f"F_{j}z")) for j in range(1, n + 1)]
    F = [
        x + y
        for x, y in zip(internal_forces(pair_forces(n, kind="central", r=r), n), Fe, strict=True)
    ]
    L_A = _L(m, r, v, A)
    M_A = _M(r, Fe, A)
    H = M_A.applyfunc(lambda e: sp.Integral(e, (t, t1, tau)))  # (1.59)
    G = L_A.subs(t, tau) - L_A.subs(t, t1) - H  # zero iff (1.58) holds on [t1, τ]
    dG = newton(sp.diff(G, tau).subs(tau, t), m, r, F)
    d.prove_zero(dG, strategy="expand", claim="d/dτ [L_A(τ) - L_A(t1) - ∫ M_A dt] = 0")
    d.prove_zero(G.subs(tau, t1).doit(), strategy="expand", claim="... and it vanishes at τ = t1")
    d.note("so L_A(t2) - L_A(t1) = H_A (1.58)-(1.60); with M_A ≡ 0, H_A = 0: (1.61)")
    F_nc = [
        x + y
        for x, y in zip(
            internal_forces(pair_forces(n, kind="non-central", r=r), n), Fe, strict=True
        )
    ]
    d.reject(
        newton(sp.diff(G, tau).subs(tau, t), m, r, F_nc),
        sp.zeros(3, 1),
        strategy="expand",
        claim="the same with non-central pair forces",
    )
    sim = simulate(external=False, noncentral=0.0)
    L_num, route = num_angular_momentum(sim["m"], sim["r"], sim["v"], np.array([1.0, 2.0, -1.0]))
    d.confirm(
        L_num - L_num[0],
        np.zeros_like(L_num),
        atol=SIM_ATOL,
        route=f"simulation without external forces: {route} about a fixed A is constant (1.61)",
    )


@check(
    "eq1.65",
    "Projection on a fixed direction",
    kind="proof",
    covers=("eq1.65",),
    statement="for a fixed unit vector e: d/dt (L_A · e) = L̇_A · e, so L̇_Ae = M_Ae; and "
    "M_A · e is the same for every A on the axis through A along e",
)
def projection(d: Derivation) -> None:
    u, w = sp.symbols("u w", real=True)
    e = unit_vector(u, w)
    L = sp.Matrix(functions_of_time("L_1", "L_2", "L_3"))
    d.prove_equal(sp.diff(L.dot(e), t), sp.diff(L, t).dot(e), strategy="together", claim="(1.65)")
    u_t, w_t = functions_of_time("u", "w")
    e_t = unit_vector(u_t, w_t)
    d.reject(
        sp.diff(L.dot(e_t), t),
        sp.diff(L, t).dot(e_t),
        strategy="together",
        claim="the same for a turning direction e(t)",
    )
    rP = vec(*sp.symbols("x y z", real=True))
    F = vec(*sp.symbols("F_x F_y F_z", real=True))
    A0 = vec(*sp.symbols("a_x a_y a_z", real=True))
    s = sp.Symbol("s", real=True)
    d.prove_equal(
        cross(rP - A0 - s * e, F).dot(e),
        cross(rP - A0, F).dot(e),
        strategy="together",
        claim="M_A · e is the moment about the axis: any A = A0 + s e gives the same",
    )
    d.reject(
        cross(rP - A0 - s * vec(1, 0, 0), F).dot(e),
        cross(rP - A0, F).dot(e),
        strategy="together",
        claim="the same for A moved off the axis (along e_x)",
    )
    Mz = []
    for A_n in ([0.0, 0.0, 0.0], [0.0, 0.0, 5.0]):
        M, route = num_moment_of_forces(R_NUM, V_NUM, np.array(A_n))  # V_NUM as forces
        Mz.append(M[2])
    d.confirm(Mz[1], Mz[0], atol=CODE_ATOL, route=f"{route}: M_z about O and about (0, 0, 5)")


def _cylindrical(n: int):
    rho = functions_of_time(*(f"rho_{j}" for j in range(1, n + 1)))
    phi = functions_of_time(*(f"phi_{j}" for j in range(1, n + 1)))
    z = functions_of_time(*(f"z_{j}" for j in range(1, n + 1)))
    r = [vec(rh * sp.cos(ph), rh * sp.sin(ph), zz) for rh, ph, zz in zip(rho, phi, z, strict=True)]
    return rho, phi, z, r


@check(
    "eq1.69",
    "L_z in Cartesian and cylindrical components; L_Oz = J_z ω_av",
    kind="proof",
    covers=("eq1.66", "eq1.67", "eq1.68", "eq1.69", "eq1.72"),
    defines=("eq1.70", "eq1.71"),
    statement="L_Oz = Σ m_j (x_j ẏ_j - y_j ẋ_j) = Σ m_j ρ_j² φ̇_j = J_z ω_av, "
    "J_z = Σ m_j ρ_j² (1.71), ω_av = Σ m_j ρ_j² φ̇_j / J_z (1.70)",
)
def cylindrical_components(d: Derivation) -> None:
    n = 3
    m = masses(n)
    rho, phi, z, r = _cylindrical(n)
    v = d_dt(r)
    L_Oz = _L(m, r, v, sp.zeros(3, 1))[2]
    d.prove_equal(
        L_Oz,
        sum(mj * (rj[0] * vj[1] - rj[1] * vj[0]) for mj, rj, vj in zip(m, r, v, strict=True)),
        strategy="expand",
        claim="(1.66)-(1.67)",
    )
    for rh, ph, zz, rj, vj in zip(rho, phi, z, r, v, strict=True):
        e_rho = vec(sp.cos(ph), sp.sin(ph), 0)
        e_phi = vec(-sp.sin(ph), sp.cos(ph), 0)
        d.prove_equal(
            vj,
            sp.diff(rh, t) * e_rho + rh * sp.diff(ph, t) * e_phi + sp.diff(zz, t) * ez,
            strategy="expand",
            claim="ṙ_j = ρ̇_j e_ρ + ρ_j φ̇_j e_φ + ż_j e_z",
        )
        d.prove_equal(
            cross(rj, vj).dot(ez), rh**2 * sp.diff(ph, t), strategy="trigsimp", claim="(1.68)"
        )
    phidot = [sp.diff(ph, t) for ph in phi]
    J_z = sum(mj * rh**2 for mj, rh in zip(m, rho, strict=True))  # (1.71)
    omega_av = sum(mj * rh**2 * pd for mj, rh, pd in zip(m, rho, phidot, strict=True)) / J_z
    L_cyl = sum(mj * rh**2 * pd for mj, rh, pd in zip(m, rho, phidot, strict=True))
    d.prove_equal(L_Oz, L_cyl, strategy="trigsimp", claim="L_Oz = Σ m_j ρ_j² φ̇_j (1.69)")
    d.prove_equal(L_cyl, J_z * omega_av, strategy="expand", claim="L_Oz = J_z ω_av (1.72)")
    d.reject(
        L_Oz,
        sum(mj * rh * pd for mj, rh, pd in zip(m, rho, phidot, strict=True)),
        strategy="trigsimp",
        claim="L_Oz = Σ m_j ρ_j φ̇_j (one power of ρ)",
    )
    L_num, route = num_angular_momentum(M_NUM, R_NUM, V_NUM, np.zeros(3))
    rho_n = np.hypot(R_NUM[:, 0], R_NUM[:, 1])
    phidot_n = (R_NUM[:, 0] * V_NUM[:, 1] - R_NUM[:, 1] * V_NUM[:, 0]) / rho_n**2
    J = np.sum(M_NUM * rho_n**2)
    d.confirm(
        L_num[2],
        J * np.sum(M_NUM * rho_n**2 * phidot_n) / J,
        atol=CODE_ATOL,
        route=f"{route}: L_Oz = J_z ω_av with φ̇ from the velocities",
    )


@check(
    "eq1.74",
    "The z-component of the angular momentum principle: d/dt (J_z ω_av) = M_Oz",
    kind="proof",
    covers=("eq1.73", "eq1.74", "eq1.75", "eq1.76"),
    statement="J̇_z ω_av + J_z ω̇_av = M_Oz (1.74); with a common φ̇, ω_av = φ̇ and L_Oz = J_z φ̇ "
    "(1.75); with constant ρ_j also, J_z φ̈ = M_Oz (1.76)",
)
def z_principle(d: Derivation) -> None:
    n = 2
    m = masses(n)
    rho, phi, _z, r = _cylindrical(n)
    J_z = sum(mj * rh**2 for mj, rh in zip(m, rho, strict=True))
    L_cyl = sum(mj * rh**2 * sp.diff(ph, t) for mj, rh, ph in zip(m, rho, phi, strict=True))
    omega_av = L_cyl / J_z
    M_Oz = sum(mj * cross(rj, sp.diff(rj, t, 2))[2] for mj, rj in zip(m, r, strict=True))
    lhs = sp.diff(J_z, t) * omega_av + J_z * sp.diff(omega_av, t)
    d.prove_equal(lhs, sp.diff(L_cyl, t), strategy="together", claim="d/dt (J_z ω_av) = L̇_Oz")
    d.prove_equal(
        sp.diff(L_cyl, t), M_Oz, strategy="trigsimp", claim="L̇_Oz = M_Oz (1.73), so (1.74)"
    )
    d.reject(
        J_z * sp.diff(omega_av, t),
        sp.diff(L_cyl, t),
        strategy="together",
        claim="J_z ω̇_av = M_Oz while the ρ_j change",
    )
    (Phi,) = functions_of_time("Phi")
    common = {ph: Phi + sp.Symbol(f"beta_{j}", real=True) for j, ph in enumerate(phi, 1)}
    d.prove_equal(
        omega_av.subs(common).doit(),
        sp.diff(Phi, t),
        strategy="cancel",
        claim="all φ̇_j = φ̇ (ρ_j, z_j arbitrary): ω_av = φ̇, L_Oz = J_z φ̇ (1.75)",
    )
    rigid = {rh: sp.Symbol(f"rho0_{j}", positive=True) for j, rh in enumerate(rho, 1)}
    M_rigid = M_Oz.subs(common).doit().subs(rigid).doit()
    d.prove_equal(
        J_z.subs(rigid) * sp.diff(Phi, t, 2),
        M_rigid,
        strategy="trigsimp",
        claim="constant ρ_j and a common φ: J_z φ̈ = M_Oz (1.76)",
    )
    d.reject(
        J_z.subs(common) * sp.diff(Phi, t, 2),
        M_Oz.subs(common).doit(),
        strategy="trigsimp",
        claim="J_z φ̈ = M_Oz while the ρ_j change",
    )
    # numeric: a rigid three-particle body turned by a torque; simulation vs (1.76)
    from scipy.integrate import solve_ivp

    mn, rho_n = np.array([1.0, 2.0, 0.5]), np.array([0.5, 1.0, 1.5])
    J = float(np.sum(mn * rho_n**2))
    tau0 = 0.8  # M_Oz = tau0 cos t applied as tangential forces at particle 1

    def rhs(tt, y):
        return [y[1], tau0 * np.cos(tt) / J]

    sol = solve_ivp(rhs, (0, 3), [0.0, 0.2], rtol=1e-12, atol=1e-12, dense_output=True)
    phi_T, phidot_T = sol.y[:, -1]
    phis = [0.0, 2.0, 4.0]
    rT = np.array(
        [
            [rh * np.cos(phi_T + b), rh * np.sin(phi_T + b), 0.0]
            for rh, b in zip(rho_n, phis, strict=True)
        ]
    )
    vT = phidot_T * np.cross([0.0, 0.0, 1.0], rT)
    L_num, route = num_angular_momentum(mn, rT, vT, np.zeros(3))
    # rtol 1e-12 over a few radians: global error ~1e-11 in φ̇, times J ≈ 4.3
    d.confirm(
        L_num[2],
        J * 0.2 + tau0 * np.sin(3.0),
        atol=2**18 * EPS,
        route=f"rigid body under M_Oz = τ cos t integrated by scipy: {route} L_Oz(3) = L_Oz(0) + τ sin 3",
    )


@check(
    "eq1.77",
    "No moment about the axis: J_z ω_av is conserved (the figure skater)",
    kind="proof",
    covers=("eq1.77",),
    statement="central pair forces and external forces parallel to e_z (gravity): "
    "d/dt (J_z ω_av) = 0, however J_z changes",
)
def figure_skater(d: Derivation) -> None:
    m, r = masses(), positions()
    v = d_dt(r)
    Fe = [vec(0, 0, sp.Symbol(f"F_{j}z", real=True)) for j in range(1, N + 1)]
    F = [x + y for x, y in zip(internal_forces(pair_forces(kind="central", r=r)), Fe, strict=True)]
    L_Oz = _L(m, r, v, sp.zeros(3, 1))[2]
    d.prove_zero(
        newton(sp.diff(L_Oz, t), m, r, F), strategy="expand", claim="L̇_Oz = M_Oz = 0: (1.77)"
    )
    Fe_h = [vec(sp.Symbol(f"F_{j}x", real=True), 0, 0) for j in range(1, N + 1)]
    F_h = [
        x + y for x, y in zip(internal_forces(pair_forces(kind="central", r=r)), Fe_h, strict=True)
    ]
    d.reject(
        newton(sp.diff(L_Oz, t), m, r, F_h),
        0,
        strategy="expand",
        claim="the same with horizontal external forces",
    )
    sim = simulate(external=False, noncentral=0.0)  # the pulse has horizontal components
    rr, vv = sim["r"], sim["v"]
    rho2 = rr[..., 0] ** 2 + rr[..., 1] ** 2
    J_z = np.sum(sim["m"] * rho2, axis=-1)
    L_num, route = num_angular_momentum(sim["m"], rr, vv, np.zeros(3))
    omega_av = L_num[:, 2] / J_z
    d.confirm(
        J_z * omega_av - J_z[0] * omega_av[0],
        np.zeros_like(J_z),
        atol=SIM_ATOL,
        route=f"simulation of 4 particles on springs: J_z ω_av constant ({route})",
    )
    ratio = float(J_z.max() / J_z.min())
    d.confirm(
        ratio > 1.05,
        True,
        atol=0.0,
        route=f"while J_z varies by a factor {ratio:.3f} and ω_av inversely",
    )
