"""Chapter 2 problems 2.1–2.7, derived symbolically in the book's symbols and each
confirmed by an independent route (numerics through :mod:`mechanics`, a second
derivation, or a limit).  The book's answers are withheld; these are derived here.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from identities.verify.catalogue import check
from identities.verify.proof import Derivation
from identities.verify.symbolic import R3, cross, euler_matrix, floats, functions_of_time, t, vec
from mechanics import kinematics as kin
from mechanics import rotation as rot
from mechanics._floats import EPS

#: numeric routes evaluate a few products and sums of O(1) numbers: 64 eps.
NUM_ATOL = 64 * EPS
ez = vec(0, 0, 1)


def _f(x) -> np.ndarray:
    return floats(x).reshape(-1)


@check(
    "P2.1",
    "Problem 2.1: the angular velocity in the fixed basis E^O",
    kind="derivation",
    covers=("P2.1",),
    statement="from (2.65), ω = ψ̇ e^O_3 + θ̇ e^C_1 + φ̇ e^A_3 in O components",
)
def problem_2_1(d: Derivation) -> None:
    psi, theta, phi = functions_of_time("psi", "theta", "phi")
    pd, td, fd = (sp.diff(x, t) for x in (psi, theta, phi))
    R = euler_matrix(psi, theta, phi)
    eC1 = R3(psi)[0, :].T  # e^C_1 in O components: first row of ^C R^O
    eA3 = R[2, :].T  # e^A_3 in O components: third row of ^A R^O
    omega_O = sp.expand(pd * ez + td * eC1 + fd * eA3)
    d.quantity("omega_O", omega_O)
    answer = vec(
        td * sp.cos(psi) + fd * sp.sin(theta) * sp.sin(psi),
        td * sp.sin(psi) - fd * sp.sin(theta) * sp.cos(psi),
        pd + fd * sp.cos(theta),
    )
    d.prove_equal(omega_O, answer, strategy="expand", claim="ω^O in closed form")
    omega_A = vec(
        pd * sp.sin(theta) * sp.sin(phi) + td * sp.cos(phi),
        pd * sp.sin(theta) * sp.cos(phi) - td * sp.sin(phi),
        pd * sp.cos(theta) + fd,
    )
    d.confirm_exact(
        R.T * omega_A,
        answer,
        strategy="trigsimp",
        route="second derivation: ω^O = (^A R^O)^T ω^A with Euler's equations (2.69)",
    )
    d.reject(
        omega_O,
        vec(answer[0], answer[1], fd + pd * sp.cos(theta)),
        strategy="expand",
        claim="the body-frame third component ψ̇ cos θ + φ̇ taken for the fixed one",
    )
    ang, rates = (0.4, 1.0, -0.7), (1.3, -0.5, 2.2)
    pt = {
        **dict(zip((pd, td, fd), rates, strict=True)),
        **dict(zip((psi, theta, phi), ang, strict=True)),
    }
    Rdot = floats(sp.diff(R, t), pt)
    d.confirm(
        kin.angular_velocity_from_matrix_rate(rot.matrix_from_euler(*ang), Rdot, basis="O"),
        _f(answer.subs(pt)),
        atol=NUM_ATOL,
        route="mechanics.angular_velocity_from_matrix_rate(basis='O') from the exact matrix rate",
    )


@check(
    "P2.2",
    "Problem 2.2: origin velocity and ω from three measured points (body basis)",
    kind="derivation",
    covers=("P2.2",),
    statement="r1 = (1,0,0)ℓ, r2 = (0,2,3)ℓ, r3 = (2,0,1)ℓ; v1 = (0,1,0)v, v2 = (0,-5,4)v, "
    "v3 = (2,3,-2)v; find v_O and ω from v_i = v_O + ω × r_i",
)
def problem_2_2(d: Derivation) -> None:
    ell, v = sp.symbols("ell v", positive=True)
    r = [vec(1, 0, 0) * ell, vec(0, 2, 3) * ell, vec(2, 0, 1) * ell]
    V = [vec(0, 1, 0) * v, vec(0, -5, 4) * v, vec(2, 3, -2) * v]
    for i, j in ((0, 1), (0, 2), (1, 2)):
        d.prove_equal(
            (V[i] - V[j]).dot(r[i] - r[j]),
            0,
            strategy="expand",
            claim=f"rigid data: (v{i + 1} - v{j + 1})·(r{i + 1} - r{j + 1}) = 0",
        )
    u = vec(*sp.symbols("u1:4", real=True))
    w = vec(*sp.symbols("w1:4", real=True))
    eqs = [e for k in range(3) for e in (V[k] - u - cross(w, r[k]))]
    sol = sp.solve(eqs, list(u) + list(w), dict=True)
    if len(sol) != 1:
        raise AssertionError(f"expected a unique solution, got {sol}")
    v_O, omega = u.subs(sol[0]), w.subs(sol[0])
    d.quantity("v_O", v_O)
    d.quantity("omega", omega)
    for k in range(3):
        d.prove_equal(
            v_O + cross(omega, r[k]), V[k], strategy="expand", claim=f"reproduces v{k + 1}"
        )
    d.reject(
        v_O + cross(r[1], omega), V[1], strategy="expand", claim="the same with r × ω (wrong order)"
    )
    rn = np.array([[1, 0, 0], [0, 2, 3], [2, 0, 1]], dtype=float)
    vn = np.array([[0, 1, 0], [0, -5, 4], [2, 3, -2]], dtype=float)
    w_num, v_c, res = kin.rigid_velocity_from_points(rn, vn)
    vO_num = kin.point_velocity(v_c, w_num, -rn.mean(axis=0))
    sub = {ell: 1, v: 1}
    d.confirm(
        w_num, _f(omega.subs(sub)), atol=NUM_ATOL, route="mechanics.rigid_velocity_from_points: ω"
    )
    d.confirm(vO_num, _f(v_O.subs(sub)), atol=NUM_ATOL, route="mechanics: v_O = v_c + ω × (O - c)")
    d.confirm(res, 0.0, atol=NUM_ATOL, route="the measured data are an exact rigid motion")


@check(
    "P2.3",
    "Problem 2.3: rolling and sliding disc",
    kind="derivation",
    covers=("P2.3",),
    statement="top point speed v1, geometric contact point speed v2 (= v_G): ω and the angular "
    "momentum about the geometric contact point",
)
def problem_2_3(d: Derivation) -> None:
    m, r = sp.symbols("m r", positive=True)
    v1, v2 = sp.symbols("v_1 v_2", real=True)
    wz = sp.Symbol("omega_z", real=True)
    # x along the motion, y up, z out of the page; G at height r, C below it on the table
    vG = vec(v2, 0, 0)  # the geometric contact point moves with the centre
    top = vG + cross(wz * ez, vec(0, r, 0))
    omega_z = sp.solve(top[0] - v1, wz)[0]
    d.quantity("omega_z", omega_z)
    d.prove_equal(
        omega_z,
        (v2 - v1) / r,
        strategy="expand",
        claim="ω = (v2 - v1)/r about e_z: clockwise, of size (v1 - v2)/r, when v1 > v2",
    )
    # J_G = (1/2) m r^2 for a uniform disc, by integrating over the disc
    rho, s, a = sp.symbols("rho s a", positive=True)
    J_G = sp.integrate(sp.integrate(rho * s**2 * s, (s, 0, r)), (a, 0, 2 * sp.pi)).subs(
        rho, m / (sp.pi * r**2)
    )
    d.prove_equal(
        J_G, m * r**2 / 2, strategy="expand", claim="J_G = ∫ s² dm = m r²/2 (uniform disc)"
    )
    L_C = J_G * omega_z * ez + cross(vec(0, r, 0), m * vG)  # L_C = L_G + CG × m v_G
    d.quantity("L_C", L_C)
    d.prove_equal(
        L_C,
        -m * r * (v1 + v2) / 2 * ez,
        strategy="expand",
        claim="L_C = -(1/2) m r (v1 + v2) e_z: clockwise, size m r (v1 + v2)/2",
    )
    d.reject(
        L_C,
        -m * r * (v1 - v2) / 2 * ez,
        strategy="expand",
        claim="L_C = -(1/2) m r (v1 - v2) e_z (C taken as fixed)",
    )
    d.confirm_exact(
        L_C.subs(v1, 2 * v2),
        -m * r * 3 * v2 / 2 * ez,
        strategy="expand",
        route="limit: pure rolling (v1 = 2 v2) gives L_C = (3/2) m r² ω, J about the contact point",
    )
    # numeric: sum (r_k - r_C) × m_k v_k over a fine polar grid of the disc
    mn, rn, v1n, v2n = 2.0, 0.5, 3.0, 1.2
    wn = (v2n - v1n) / rn
    n_r, n_a = 400, 256
    s_mid = (np.arange(n_r) + 0.5) / n_r * rn
    ang = 2 * np.pi * np.arange(n_a) / n_a
    S, A = np.meshgrid(s_mid, ang, indexing="ij")
    dm = (mn / (np.pi * rn**2)) * S * (rn / n_r) * (2 * np.pi / n_a)
    pos = np.stack([S * np.cos(A), rn + S * np.sin(A), 0 * S], axis=-1)  # C at the origin
    vel = kin.point_velocity([v2n, 0.0, 0.0], [0.0, 0.0, wn], pos - [0.0, rn, 0.0])
    L_num = np.einsum("ij,ijk->k", dm, np.cross(pos, vel))
    # the midpoint rule in s integrates s^3 with relative error 1/(2 n_r^2) (the angular
    # sum is exact for these trigonometric polynomials); 1/n_r^2 bounds it
    midpoint_rtol = 1.0 / n_r**2
    d.confirm(
        L_num,
        _f(L_C.subs({m: mn, r: rn, v1: v1n, v2: v2n})),
        atol=midpoint_rtol * mn * rn * (v1n + v2n),
        route="numeric sum of (r_k - r_C) × m_k v_k over 102400 mass elements, velocities by mechanics",
    )


@check(
    "P2.4",
    "Problem 2.4: three cog-wheels with an arrow that keeps pointing up",
    kind="derivation",
    covers=("P2.4",),
    statement="fixed wheel r_o, rolling wheels r_k and r_p on an arm: the outer wheel does not "
    "turn (ω_p = 0) for every arm rate iff r_p = r_o",
)
def problem_2_4(d: Derivation) -> None:
    ro, rk, rp = sp.symbols("r_o r_k r_p", positive=True)
    Om, wk, wp = sp.symbols("Omega omega_k omega_p", real=True)
    arm = Om * ez
    cK, cP = vec(ro + rk, 0, 0), vec(ro + 2 * rk + rp, 0, 0)
    vK, vP = cross(arm, cK), cross(arm, cP)
    contact_OK = vK + cross(wk * ez, vec(-rk, 0, 0))  # wheel K at its contact with the fixed wheel
    contact_KP_K = vK + cross(wk * ez, vec(rk, 0, 0))
    contact_KP_P = vP + cross(wp * ez, vec(-rp, 0, 0))
    sol = sp.solve([contact_OK[1], contact_KP_K[1] - contact_KP_P[1]], [wk, wp], dict=True)[0]
    omega_p = sp.factor(sol[wp])
    d.quantity("omega_k", sol[wk])
    d.quantity("omega_p", omega_p)
    d.prove_equal(omega_p, Om * (rp - ro) / rp, strategy="cancel", claim="ω_p = Ω (r_p - r_o)/r_p")
    d.quantity("condition", sp.Eq(rp, ro))
    d.prove_equal(
        omega_p.subs(rp, ro),
        0,
        strategy="cancel",
        claim="r_p = r_o: the arrow keeps its direction, any r_k",
    )
    d.reject(omega_p.subs(rp, rk), 0, strategy="cancel", claim="r_p = r_k would do")
    willis = Om + (0 - Om) * (-ro / rk) * (-rk / rp)  # (ω_p - Ω)/(ω_o - Ω) = (-r_o/r_k)(-r_k/r_p)
    d.confirm_exact(
        omega_p,
        willis,
        strategy="cancel",
        route="second derivation: Willis' train-value formula in the frame of the arm",
    )
    # numeric: with r_p = r_o the contact velocities match for ω_p = 0
    Omn, ron, rkn = 1.7, 0.3, 0.2
    wkn = Omn * (ron + rkn) / rkn
    vKn = kin.point_velocity(np.zeros(3), [0, 0, Omn], [ron + rkn, 0, 0])
    vPn = kin.point_velocity(np.zeros(3), [0, 0, Omn], [2 * ron + 2 * rkn, 0, 0])
    d.confirm(
        kin.point_velocity(vKn, [0, 0, wkn], [rkn, 0, 0]),
        kin.point_velocity(vPn, [0, 0, 0.0], [-ron, 0, 0]),
        atol=NUM_ATOL,
        route="mechanics.point_velocity: no slip between K and P with ω_p = 0 when r_p = r_o",
    )
    d.confirm(
        kin.point_velocity(vKn, [0, 0, wkn], [-rkn, 0, 0]),
        np.zeros(3),
        atol=NUM_ATOL,
        route="and no slip between K and the fixed wheel",
    )


def roller_pyramid(r, v):
    """The six rollers of Problem 2.5 (reused by Problem 3.2): their centres, the pairs in
    contact, and the angular velocities that rolling everywhere without slip forces when
    the frame translates with speed v (solved from the contact conditions)."""
    h = sp.sqrt(7) * r  # height of B above AC: sqrt((4r)^2 - (3r)^2)
    centres = {
        "A": vec(0, r, 0),
        "M_AC": vec(3 * r, r, 0),
        "C": vec(6 * r, r, 0),
        "M_AB": vec(sp.Rational(3, 2) * r, r + h / 2, 0),
        "M_BC": vec(sp.Rational(9, 2) * r, r + h / 2, 0),
        "B": vec(3 * r, r + h, 0),
    }
    contacts = [
        ("A", "M_AB"),
        ("M_AB", "B"),
        ("B", "M_BC"),
        ("M_BC", "C"),
        ("M_AB", "M_AC"),
        ("M_BC", "M_AC"),
    ]
    w = {k: sp.Symbol(f"omega_{k}", real=True) for k in centres}
    vc = vec(v, 0, 0)  # the rods translate: A and C roll on the floor, the frame cannot turn
    eqs = []
    for k in ("A", "M_AC", "C"):  # rolling on the floor
        eqs += list(vc + cross(w[k] * ez, vec(0, -r, 0)))[:2]
    for p, q in contacts:  # rolling on each other: equal material velocities at the contact
        n = (centres[q] - centres[p]) / 2
        eqs += list(cross(w[p] * ez, n) - cross(w[q] * ez, -n))[:2]
    sol = sp.solve(eqs, list(w.values()), dict=True)
    if len(sol) != 1:
        raise AssertionError(f"expected a unique set of angular velocities, got {sol}")
    return centres, contacts, {k: sol[0][w[k]] for k in centres}


@check(
    "P2.5",
    "Problem 2.5: instantaneous centres of six rollers in a pyramid",
    kind="derivation",
    covers=("P2.5",),
    statement="rollers of radius r at A, B, C (AB = BC = 4r, AC = 6r) and at the midpoints of the "
    "rods; the frame moves right with speed v; no slip anywhere",
)
def problem_2_5(d: Derivation) -> None:
    r, v = sp.symbols("r v", positive=True)
    centres, contacts, omegas = roller_pyramid(r, v)
    for p, q in contacts:
        gap = centres[p] - centres[q]
        d.prove_equal(
            gap.dot(gap), 4 * r**2, strategy="expand", claim=f"{p} and {q} touch (centres 2r apart)"
        )
    vc = vec(v, 0, 0)
    centres_C = {}
    for k, c in centres.items():
        wk = omegas[k]
        centres_C[k] = c + cross(wk * ez, vc) / wk**2  # (2.77)
        d.quantity(f"omega_{k}", wk)
        d.quantity(f"C_{k}", centres_C[k])
    for k in ("A", "M_AC", "C", "B"):
        d.prove_equal(
            centres_C[k],
            centres[k] - vec(0, r, 0),
            strategy="cancel",
            claim=f"roller {k} turns clockwise at v/r: its centre of zero velocity is the point below its axis",
        )
    for k in ("M_AB", "M_BC"):
        d.prove_equal(
            centres_C[k],
            centres[k] + vec(0, r, 0),
            strategy="cancel",
            claim=f"roller {k} turns counter-clockwise at v/r: its centre is the point above its axis",
        )
    d.reject(
        centres_C["B"],
        centres["B"] + vec(0, r, 0),
        strategy="cancel",
        claim="the top roller B turns like the middle ones",
    )
    # numeric route: least-squares no-slip solve and mechanics.instantaneous_centre_plane
    rn, vn = 1.0, 1.0
    names = list(centres)
    cn = {k: _f(c.subs(r, rn))[:2] for k, c in centres.items()}
    rows, rhs = [], []
    for k in ("A", "M_AC", "C"):  # v + ω e_z × (0, -r) = 0  ->  x: v + ω r = 0
        row = np.zeros(len(names))
        row[names.index(k)] = rn
        rows.append(row)
        rhs.append(-vn)
    for p, q in contacts:  # ω_p e_z × n + ω_q e_z × n = 0 (n from p to the contact)
        n = (cn[q] - cn[p]) / 2
        for comp in (0, 1):
            row = np.zeros(len(names))
            perp = np.array([-n[1], n[0]])[comp]
            row[names.index(p)] += perp
            row[names.index(q)] += perp
            rows.append(row)
            rhs.append(0.0)
    wn, *_ = np.linalg.lstsq(np.array(rows), np.array(rhs), rcond=None)
    got = np.array(
        [kin.instantaneous_centre_plane(cn[k], [vn, 0.0], wn[i]) for i, k in enumerate(names)]
    )
    want = np.array([_f(centres_C[k].subs({r: rn, v: vn}))[:2] for k in names])
    d.confirm(
        got,
        want,
        atol=NUM_ATOL,
        route="numeric least-squares no-slip solve + mechanics.instantaneous_centre_plane",
    )


@check(
    "P2.6",
    "Problem 2.6: a body with two points at rest",
    kind="derivation",
    covers=("P2.6",),
    statement="r0 = 0, v0 = 0; r1 = (-2, 2, ζ)ℓ, v1 = 0; r2 = (1, 3, -2)ℓ, v2 = (-4, 2, 1)v: "
    "find ζ and the velocity of r3 = (-5, 0, 5)ℓ",
)
def problem_2_6(d: Derivation) -> None:
    ell, v = sp.symbols("ell v", positive=True)
    zeta = sp.Symbol("zeta", real=True)
    r1, r2, r3 = vec(-2, 2, zeta) * ell, vec(1, 3, -2) * ell, vec(-5, 0, 5) * ell
    v2 = vec(-4, 2, 1) * v
    zeta_sol = sp.solve(v2.dot(r2 - r1), zeta)  # rigidity: |r2 - r1| constant
    if len(zeta_sol) != 1:
        raise AssertionError(f"expected one ζ, got {zeta_sol}")
    z = d.quantity("zeta", zeta_sol[0])
    d.prove_equal(z, -12, strategy="expand", claim="ζ = -12 from (v2 - v1)·(r2 - r1) = 0")
    d.prove_equal(v2.dot(r2), 0, strategy="expand", claim="consistency: (v2 - v0)·(r2 - r0) = 0")
    lam = sp.Symbol("lambda", real=True)
    omega_try = lam * r1.subs(zeta, z)  # v0 = v1 = 0: ω along P0P1
    lam_sol = sp.solve(list(cross(omega_try, r2) - v2), lam, dict=True)
    if len(lam_sol) != 1:
        raise AssertionError(f"expected one λ, got {lam_sol}")
    omega = d.quantity("omega", omega_try.subs(lam_sol[0]))
    d.prove_equal(
        omega,
        vec(sp.Rational(1, 4), -sp.Rational(1, 4), sp.Rational(3, 2)) * v / ell,
        strategy="expand",
        claim="ω = (1/4, -1/4, 3/2) v/ℓ, along P0P1",
    )
    v3 = d.quantity("v3", cross(omega, r3))
    d.prove_equal(
        v3, vec(-5, -35, -5) * v / 4, strategy="expand", claim="v3 = ω × r3 = -(5/4)(1, 7, 1) v"
    )
    d.reject(cross(r3, omega), v3, strategy="expand", claim="v3 = r3 × ω")
    rn = np.array([[0, 0, 0], [-2, 2, -12], [1, 3, -2]], dtype=float)
    vn = np.array([[0, 0, 0], [0, 0, 0], [-4, 2, 1]], dtype=float)
    w_num, v_c, res = kin.rigid_velocity_from_points(rn, vn)
    d.confirm(
        res, 0.0, atol=NUM_ATOL, route="mechanics.rigid_velocity_from_points: rigid for ζ = -12"
    )
    d.confirm(
        kin.point_velocity(v_c, w_num, [-5, 0, 5] - rn.mean(axis=0)),
        [-1.25, -8.75, -1.25],
        atol=NUM_ATOL,
        route="mechanics: v3 from the least-squares ω and the connection formula",
    )
    rn[1, 2] = -11.0
    _, _, res_bad = kin.rigid_velocity_from_points(rn, vn)
    # ζ = -11 makes P1P2 stretch at (v2 - v1)·(r2 - r1)/|r2 - r1| = -v/sqrt(91) ≈ -0.10 v;
    # the least-squares fit spreads that misfit over the points (measured residual 0.074 v)
    d.confirm(
        res_bad > 0.05,
        True,
        atol=0.0,
        route="with ζ = -11 the data are not rigid (residual > 0.05 v)",
    )


@check(
    "P2.7",
    "Problem 2.7: the sliding ladder, its polhode and herpolhode",
    kind="derivation",
    covers=("P2.7",),
    statement="ladder of length ℓ, foot A on the floor, top B on the wall, θ its angle with the wall",
)
def problem_2_7(d: Derivation) -> None:
    ell = sp.Symbol("ell", positive=True)
    (th,) = functions_of_time("theta")
    thd = sp.diff(th, t)
    A = vec(ell * sp.sin(th), 0, 0)
    B = vec(0, ell * sp.cos(th), 0)
    omega = thd  # the direction of AB makes the angle π/2 + θ with e_x
    vA = sp.diff(A, t)
    C = vec(A[0] - vA[1] / omega, A[1] + vA[0] / omega, 0)  # (2.95)
    d.quantity("r_C", C)
    d.prove_equal(
        C,
        vec(ell * sp.sin(th), ell * sp.cos(th), 0),
        strategy="cancel",
        claim="C = (ℓ sin θ, ℓ cos θ): the corner of the rectangle on the wall and the floor",
    )
    d.prove_equal(
        sp.diff(B, t) + cross(omega * ez, C - B),
        sp.zeros(3, 1),
        strategy="cancel",
        claim="B's velocity is consistent with the same C (independent of which end is used)",
    )
    x, y = sp.symbols("x y", real=True)
    d.quantity("herpolhode", sp.Eq(x**2 + y**2, ell**2))
    d.prove_equal(
        C[0] ** 2 + C[1] ** 2,
        ell**2,
        strategy="trigsimp",
        claim="(a) herpolhode: x² + y² = ℓ², a circle of radius ℓ about the corner",
    )
    M = (A + B) / 2
    e1 = (B - A) / ell
    e2 = cross(ez, e1)
    xi, eta = (C - M).dot(e1), (C - M).dot(e2)
    d.quantity("polhode", sp.Eq(x**2 + y**2, ell**2 / 4))
    d.prove_equal(
        sp.Matrix([xi, eta]),
        sp.Matrix([ell * sp.cos(2 * th) / 2, -ell * sp.sin(2 * th) / 2]),
        strategy="tan_half",
        claim="(b) polhode: C at (ℓ/2)(cos 2θ, -sin 2θ) from the ladder's midpoint",
    )
    d.reject(xi**2 + eta**2, ell**2, strategy="trigsimp", claim="the polhode has radius ℓ")
    d.prove_equal(
        M,
        C / 2,
        strategy="expand",
        claim="(c) the corner, the midpoint and C are collinear: the circles touch internally at C",
    )
    d.prove_equal(
        ell * thd,
        (ell / 2) * sp.diff(2 * th, t),
        strategy="expand",
        claim="(c) arc rates agree, ℓ θ̇ = (ℓ/2)(2 θ̇): the polhode rolls without slipping inside the herpolhode",
    )
    # numeric route: finite-difference velocities of the ends, then mechanics
    elln, th0, h = 2.0, 0.6, 1e-6
    pos = lambda a: np.array([elln * np.sin(a), 0.0])  # noqa: E731
    vA_num = (pos(th0 + h) - pos(th0 - h)) / (2 * h)  # θ̇ = 1
    Cn = kin.instantaneous_centre_plane(pos(th0), vA_num, 1.0)
    # central difference: truncation (h²/6) ℓ, rounding about ℓ eps / h
    fd_atol = elln * (h**2 + 4 * EPS / h)
    d.confirm(
        np.hypot(*Cn),
        elln,
        atol=fd_atol,
        route="mechanics.instantaneous_centre_plane lies on the herpolhode",
    )
    Mn = np.array([elln * np.sin(th0) / 2, elln * np.cos(th0) / 2])
    d.confirm(
        np.hypot(*(Cn - Mn)),
        elln / 2,
        atol=fd_atol,
        route="and at distance ℓ/2 from the midpoint (polhode)",
    )
