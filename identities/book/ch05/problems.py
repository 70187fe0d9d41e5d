"""Chapter 5 problems 5.1–5.4, derived symbolically in the book's symbols and each confirmed
by an independent route (a scipy simulation, :mod:`mechanics`, a second derivation in the
space frame, units).  The book's answers are withheld; these are derived here.
"""

from __future__ import annotations

import numpy as np
import sympy as sp
from scipy.integrate import solve_ivp
from sympy.physics import units as u

from identities.book.ch05.symmetric_top import _rotate
from identities.verify.catalogue import check
from identities.verify.proof import Derivation
from identities.verify.symbolic import cross, vec
from mechanics import inertia as inr
from mechanics import tops
from mechanics._floats import EPS

#: float evaluation of a few products and quotients of O(1) numbers: 64 eps.
CODE_ATOL = 64 * EPS
#: scipy DOP853 at rtol = atol = 1e-12, with event location, over O(1) times: ≤ 1e-10
#: measured; 2^24 eps ≈ 3.7e-9.
SIM_ATOL = 2**24 * EPS

ex, ey, ez = vec(1, 0, 0), vec(0, 1, 0), vec(0, 0, 1)
m, R, g, a, l, r = sp.symbols("m R g a l r", positive=True)
v0, w0, Omega, phid = sp.symbols("v_0 omega_0 Omega phidot", real=True)


def _si(q) -> float:
    q = u.convert_to(q, [u.meter, u.kilogram, u.second])
    return q.subs({u.meter: 1, u.kilogram: 1, u.second: 1})


# ----------------------------------------------------------------------------- 5.1
@check(
    "P5.1",
    "Problem 5.1: a bowling ball launched sliding and spinning about its velocity",
    kind="derivation",
    covers=("P5.1",),
    statement="solid sphere, v(0) = v0 e_x, ω(0) = ω0 e_x on a rough floor: v when rolling starts",
    reading="L_C about the contact point is conserved while sliding: friction and the normal "
    "force act at C, the weight's moment about C vanishes (vertical through G), and C moves "
    "with v_G ∥ p.",
)
def problem_5_1(d: Derivation) -> None:
    J = sp.Rational(2, 5) * m * R**2
    vx, vy, wx, wy, wz = sp.symbols("v_x v_y omega_x omega_y omega_z", real=True)
    L_C = lambda v, w: cross(R * ez, m * v) + J * w  # noqa: E731
    L0 = L_C(vec(v0, 0, 0), vec(w0, 0, 0))
    v_f, w_f = vec(vx, vy, 0), vec(wx, wy, wz)
    rolling = list(v_f + cross(w_f, -R * ez))  # v_C = 0
    sol = sp.solve([*list(L_C(v_f, w_f) - L0), *rolling[:2]], [vx, vy, wx, wy, wz], dict=True)[0]
    v = d.quantity("v", vec(sol[vx], sol[vy], 0))
    d.quantity("omega", vec(sol[wx], sol[wy], sol[wz]))
    d.prove_equal(
        v,
        vec(sp.Rational(5, 7) * v0, -sp.Rational(2, 7) * R * w0, 0),
        strategy="cancel",
        claim="v = (5/7) v0 e_x − (2/7) R ω0 e_y",
    )
    d.reject(
        v,
        vec(sp.Rational(5, 7) * v0, sp.Rational(2, 7) * R * w0, 0),
        strategy="cancel",
        claim="the sideways drift with the opposite sign",
    )
    # simulation: Coulomb friction −μ m g ŝ opposite the slip until the slip vanishes
    mn, Rn, v0n, w0n, mu, gn = 7.0, 0.11, 8.0, 30.0, 0.15, 9.81
    Jn = 0.4 * mn * Rn**2

    def slip(y):
        return y[:2] + np.cross(y[2:], [0.0, 0.0, -Rn])[:2]

    s0 = slip(np.array([v0n, 0.0, w0n, 0.0, 0.0]))

    def rhs(_t, y):
        s = slip(y)
        F = -mu * mn * gn * s / np.linalg.norm(s)
        tau = np.cross([0.0, 0.0, -Rn], [F[0], F[1], 0.0])
        return [*(F / mn), *(tau / Jn)]

    def stop(_t, y):
        return slip(y) @ s0

    stop.terminal = True
    out = solve_ivp(
        rhs,
        (0, 100),
        [v0n, 0.0, w0n, 0.0, 0.0],
        events=stop,
        rtol=1e-12,
        atol=1e-12,
        method="DOP853",
    )
    yend = out.y_events[0][0]
    d.confirm(
        yend[:2],
        [float(v[0].subs({v0: v0n})), float(v[1].subs({R: Rn, w0: w0n}))],
        atol=SIM_ATOL * 8,  # velocities ~8 m/s: the bound relative to their size
        route="scipy simulation of sliding with Coulomb friction (μ = 0.15) until the slip "
        "vanishes: the final velocity does not depend on μ",
    )


# ----------------------------------------------------------------------------- 5.2
@check(
    "P5.2",
    "Problem 5.2: precession of a free spinning square plate at θ = π/4",
    kind="derivation",
    covers=("P5.2",),
    statement="thin homogeneous square; axial component of ω = φ̇, axis at θ = π/4 to the "
    "fixed L: the precession rate",
    reading="'the component of the angular velocity around the axis' is ω3 = ψ̇ cos θ + φ̇ "
    "of (5.30), called φ̇ in the problem; were φ̇ the spin relative to the B frame (5.35), the "
    "rate would be −2√2 φ̇ (same magnitude, opposite sense), also derived.",
)
def problem_5_2(d: Derivation) -> None:
    x, y = sp.symbols("x y", real=True)
    sigma = m / a**2
    lim = ((x, -a / 2, a / 2), (y, -a / 2, a / 2))
    J1 = sp.integrate(sigma * y**2, *lim)  # in-plane axis e1: distance² = y² (+ z² = 0)
    J3 = sp.integrate(sigma * (x**2 + y**2), *lim)
    d.prove_equal(vec(J1, J3), vec(m * a**2 / 12, m * a**2 / 6), claim="J1 = ma²/12, J3 = ma²/6")
    d.confirm(
        np.diag(inr.rectangular_plate(2.0, 0.5, 0.5)),
        [float(e.subs({m: 2.0, a: 0.5})) for e in (J1, J1, J3)],
        atol=CODE_ATOL,
        route="mechanics.inertia.rectangular_plate",
    )
    th = sp.pi / 4
    L = J3 * phid / sp.cos(th)  # (5.33c): L cos θ = J3 ω3
    psid = d.quantity("psi_dot", sp.nsimplify(sp.simplify(L / J1)))  # (5.34)
    d.prove_equal(psid, 2 * sp.sqrt(2) * phid, strategy="cancel", claim="ψ̇ = 2√2 φ̇")
    d.reject(psid, sp.sqrt(2) * phid, strategy="cancel", claim="ψ̇ = √2 φ̇ (J1 = J3 would give)")
    spin = sp.Symbol("phidot_spin", real=True)
    L_ = sp.Symbol("L", positive=True)
    L_alt = sp.solve(sp.Eq(spin, L_ / J1 * sp.cos(th) * (J1 - J3) / J3), L_)[0]  # (5.35)
    d.quantity("psi_dot_if_phidot_is_the_spin_rate", sp.simplify(L_alt / J1))
    d.confirm_exact(
        sp.simplify(L_alt / J1), -2 * sp.sqrt(2) * spin, route="(5.34)-(5.35) with φ̇ the spin"
    )
    # numeric: the exact free symmetric top and a scipy integration of the attitude
    J1n, J3n, w3 = 1.0 / 12, 1.0 / 6, 0.9
    w_0 = np.array([J3n / J1n * w3, 0.0, w3])  # tan θ = J1|ω⊥|/(J3 ω3) = 1
    top = tops.FreeSymmetricTop(J1n, J3n, w_0)
    d.confirm(
        [top.nutation_angle, top.space_precession_rate],
        [np.pi / 4, float(psid.subs(phid, w3))],
        atol=CODE_ATOL,
        route="mechanics.tops.FreeSymmetricTop: nutation angle and precession rate",
    )
    Jv = np.array([J1n, J1n, J3n])

    def rhs(_t, yy):
        om, Rm = yy[:3], yy[3:].reshape(3, 3)
        W = np.array([[0, -om[2], om[1]], [om[2], 0, -om[0]], [-om[1], om[0], 0]])
        omd = (
            np.array(
                [
                    (Jv[1] - Jv[2]) * om[1] * om[2],
                    (Jv[2] - Jv[0]) * om[2] * om[0],
                    (Jv[0] - Jv[1]) * om[0] * om[1],
                ]
            )
            / Jv
        )
        return np.concatenate([omd, (-W @ Rm).ravel()])

    T = 2.0
    out = solve_ivp(
        rhs,
        (0, T),
        np.concatenate([w_0, np.eye(3).ravel()]),
        rtol=1e-12,
        atol=1e-12,
        method="DOP853",
    )
    L_O = Jv * w_0
    n = L_O / np.linalg.norm(L_O)
    d.confirm(
        out.y[3:, -1].reshape(3, 3)[2],
        _rotate(np.array([0.0, 0.0, 1.0]), n, float(psid.subs(phid, w3)) * T),
        atol=SIM_ATOL,
        route="scipy integration of Euler's equations and the attitude: the plate's normal "
        "turns about L at 2√2 ω3",
    )


# ----------------------------------------------------------------------------- 5.3
@check(
    "P5.3",
    "Problem 5.3: the minimum Ω for a wheel to roll on the underside of a rough plane",
    kind="derivation",
    covers=("P5.3",),
    statement="disc (m, a) on a light horizontal axle of length l hinged to a vertical axis "
    "turning at Ω, a below the plane; rolling on the plane needs N ≥ 0",
    reading="the axle is horizontal (G at the hinge's level touches the plane a above); the "
    "hinge carries the centripetal force m l Ω² (friction at the contact has no radial "
    "component); the wheel turns freely on the axle (M3 = 0).",
)
def problem_5_3(d: Derivation) -> None:
    N = sp.Symbol("N", real=True)
    J3 = m * a**2 / 2
    J1p = m * a**2 / 4 + m * l**2
    # frame B of figure 5.3 with θ = π/2: e^B_3 along the axle, e^B_2 up, e^B_1 = e^B_2 × e^B_3
    w = vec(0, Omega, phid)  # ω = Ω e^B_2 + φ̇ e^B_3 (5.73)
    v_P = cross(w, l * vec(0, 0, 1) + a * vec(0, 1, 0))
    sol_phid = sp.solve(v_P[0], phid)[0]
    d.quantity("phi_dot", sol_phid)
    d.prove_equal(sol_phid, Omega * l / a, strategy="cancel", claim="rolling: φ̇ = Ω l/a")
    M1 = (J3 - J1p) * Omega * 0 + J3 * Omega * sol_phid  # (5.77a) with Ω1 = Ω3 = 0
    moment = cross(l * vec(0, 0, 1), -m * g * vec(0, 1, 0)) + cross(
        l * vec(0, 0, 1) + a * vec(0, 1, 0), -N * vec(0, 1, 0)
    )
    N_sol = sp.solve(sp.Eq(M1, moment[0]), N)[0]
    d.quantity("N", N_sol)
    d.prove_equal(
        N_sol,
        m * a * Omega**2 / 2 - m * g,
        strategy="cancel",
        claim="N = J3Ω²/a − mg = maΩ²/2 − mg",
    )
    Om_min = d.quantity("Omega_min", sp.sqrt(2 * g / a))
    d.prove_equal(
        N_sol.subs(Omega, Om_min),
        0,
        strategy="cancel",
        claim="N = 0 at Ω_min = √(2g/a): N ≥ 0 iff |Ω| ≥ √(2g/a), for any l",
    )
    d.reject(N_sol.subs(Omega, sp.sqrt(g / a)), 0, strategy="cancel", claim="Ω_min = √(g/a)")
    # second route: L about the hinge in the space frame, differentiated
    tt = sp.Symbol("t", real=True)
    er = vec(sp.cos(Omega * tt), sp.sin(Omega * tt), 0)
    etan = cross(ez, er)
    Ls = J1p * Omega * ez + J3 * sol_phid * er
    Ms = cross(l * er, -m * g * ez) + cross(l * er + a * ez, -N * ez)
    N2 = sp.solve(sp.trigsimp((sp.diff(Ls, tt) - Ms).dot(etan)), N)[0]
    d.confirm_exact(N2, N_sol, route="dL_H/dt = M_H in the space frame", strategy="cancel")
    # mechanics: at N = 0 the wheel is a heavy top in steady precession at θ = π/2 (5.60)
    mn, an, ln, gn = 2.0, 0.3, 0.8, 9.81
    Omn = float(Om_min.subs({g: gn, a: an}))
    L3n = float((J3 * sol_phid).subs({m: mn, a: an, l: ln, Omega: Omn}))
    rate = min(
        tops.steady_precession_rates(
            float(J1p.subs({m: mn, a: an, l: ln})), L3n, mn * gn * ln, np.pi / 2
        ),
        key=abs,
    )
    d.confirm(
        rate,
        Omn,
        atol=CODE_ATOL * 4,
        route="mechanics.tops.steady_precession_rates: with N = 0 the rolling spin "
        "L3 = J3 Ω l/a precesses at exactly Ω_min (5.60)",
    )
    dims = _si(sp.sqrt(2 * u.acceleration_due_to_gravity / u.meter) * u.second)
    d.confirm(
        float(dims),
        float(sp.sqrt(2 * 9.80665)),
        atol=CODE_ATOL,
        route="units: √(2g/a) is an angular velocity (a = 1 m gives √(2g)/s)",
    )


# ----------------------------------------------------------------------------- 5.4
@check(
    "P5.4",
    "Problem 5.4: a millstone rolling on the ground, its axis turning at Ω about the vertical",
    kind="derivation",
    covers=("P5.4",),
    statement="wheel (r, m, J3 about OG, J about perpendicular axes through O) on a light axis "
    "OG at β = π/3 to the vertical, rolling so that the contact A is at r from the point "
    "below O: ω, M_O and the ground force N",
    reading="OG points down and out at β from the downward vertical; A is the lowest rim point; "
    "the ground force is vertical (figure 5.7; a radial friction component would be "
    "statically indeterminate with N).  General β is derived, then β = π/3; the thin "
    "uniform disc (J3 = mr²/2, J = mr²/4 + m|OG|²) gives N in Ω, β, mg and r.",
)
def problem_5_4(d: Derivation) -> None:
    b = sp.Symbol("beta", positive=True)
    J, J3, Lg = sp.symbols("J J_3 L_G", positive=True)
    tt = sp.Symbol("t", real=True)
    N = sp.Symbol("N", real=True)
    e3 = vec(sp.sin(b) * sp.cos(Omega * tt), sp.sin(b) * sp.sin(Omega * tt), -sp.cos(b))
    er = vec(sp.cos(Omega * tt), sp.sin(Omega * tt), 0)
    et = cross(ez, er)
    n_low = -vec(sp.cos(b) * er[0], sp.cos(b) * er[1], sp.sin(b))  # lowest rim direction
    d.prove_equal(
        vec(n_low.dot(e3), n_low.dot(n_low)),
        vec(0, 1),
        strategy="trigsimp",
        claim="the lowest rim direction is a unit vector in the wheel plane",
    )
    A = Lg * e3 + r * n_low
    Lg_sol = sp.solve(sp.Eq(sp.trigsimp(A.dot(er)), r), Lg)[0]
    d.quantity("OG", Lg_sol)
    d.prove_equal(
        Lg_sol,
        r * (1 + sp.cos(b)) / sp.sin(b),
        strategy="cancel",
        claim="|OG| = r(1 + cos β)/sin β (contact circle of radius r)",
    )
    A = A.subs(Lg, Lg_sol)
    spin = sp.Symbol("s", real=True)
    w = Omega * ez + spin * e3
    s_sol = sp.solve(sp.trigsimp(cross(w, A).dot(et)), spin)[0]
    d.prove_equal(s_sol, -Omega, strategy="tan_half", claim="rolling (v_A = ω × OA = 0): φ̇ = −Ω")
    d.prove_zero(
        sp.simplify(cross(w.subs(spin, -Omega), A)),
        strategy="trigsimp",
        claim="ω = Ω(e_z − e3) is along OA: A is at rest",
    )
    wmag = d.quantity("omega", 2 * Omega * sp.cos(b / 2))
    wsq = (w.subs(spin, -Omega)).dot(w.subs(spin, -Omega))
    d.prove_equal(
        wsq, 2 * Omega**2 * (1 + sp.cos(b)), strategy="trigsimp", claim="|ω|² = 2Ω²(1 + cos β)"
    )
    h = sp.Symbol("h", positive=True)  # β = 2h
    d.prove_equal(
        (wmag**2).subs(b, 2 * h),
        2 * Omega**2 * (1 + sp.cos(2 * h)),
        strategy="expand_trig",
        claim="|ω| = 2Ω cos(β/2)",
    )
    d.quantity("omega_at_pi_3", sp.sqrt(3) * Omega)
    d.prove_equal(wmag.subs(b, sp.pi / 3), sp.sqrt(3) * Omega, claim="ω = √3 Ω at β = π/3")
    # b) Resal (5.77) with θ = π − β, Ω_B = (0, Ω sin θ, Ω cos θ), φ̇ = −Ω, J1 → J
    thB = sp.pi - b
    O2, O3 = Omega * sp.sin(thB), Omega * sp.cos(thB)
    M1 = (J3 - J) * O2 * O3 + J3 * O2 * (-Omega)
    M1g = d.quantity("M_1", sp.expand(Omega**2 * sp.sin(b) * ((J - J3) * sp.cos(b) - J3)))
    d.prove_equal(M1, M1g, claim="M = Ω² sin β[(J − J3) cos β − J3] e^B_1, e^B_1 = e_z × e_r")
    Mpi3 = d.quantity("M_1_at_pi_3", sp.sqrt(3) / 4 * (J - 3 * J3) * Omega**2)
    d.prove_equal(M1g.subs(b, sp.pi / 3), Mpi3, claim="M = (√3/4)(J − 3J3)Ω² at β = π/3")
    d.reject(
        M1g.subs(b, sp.pi / 3),
        sp.sqrt(3) / 4 * (J + 3 * J3) * Omega**2,
        claim="the spin term with the wrong sign",
    )
    # second route: L_O = J ω + (J3 − J)(ω·e3) e3 in the space frame, differentiated
    ws = w.subs(spin, -Omega)
    L_O = J * ws + (J3 - J) * ws.dot(e3) * e3
    dL = sp.diff(L_O, tt)
    d.confirm_exact(
        sp.trigsimp(dL.dot(et)),
        M1g,
        route="dL_O/dt in the space frame, e_t component",
        strategy="tan_half",
    )
    d.confirm_exact(
        vec(sp.trigsimp(dL.dot(er)), sp.trigsimp(dL.dot(ez))),
        vec(0, 0),
        route="dL_O/dt has no radial or vertical component (M ∥ e^B_1)",
        strategy="tan_half",
    )
    # c) moment balance about O along e_t: weight at G, vertical N at A
    MO = cross(Lg_sol * e3, -m * g * ez) + cross(A, N * ez)
    N_sol = sp.solve(sp.Eq(sp.trigsimp(MO.dot(et)), M1g), N)[0]
    N_gen = d.quantity("N", N_sol)
    d.prove_equal(
        N_gen,
        m * g * (1 + sp.cos(b)) - Omega**2 / r * sp.sin(b) * ((J - J3) * sp.cos(b) - J3),
        strategy="tan_half",
        claim="N = mg(1 + cos β) − (Ω²/r) sin β[(J − J3) cos β − J3]",
    )
    N3 = d.quantity(
        "N_at_pi_3", sp.Rational(3, 2) * m * g - sp.sqrt(3) * Omega**2 / (4 * r) * (J - 3 * J3)
    )
    d.prove_equal(N_gen.subs(b, sp.pi / 3), N3, strategy="cancel", claim="N at β = π/3")
    disc = {J3: m * r**2 / 2, J: m * r**2 / 4 + m * Lg_sol.subs(b, sp.pi / 3) ** 2}
    Nd = d.quantity(
        "N_thin_disc", sp.Rational(3, 2) * m * g - 7 * sp.sqrt(3) / 16 * m * r * Omega**2
    )
    d.prove_equal(
        N3.subs(disc),
        Nd,
        strategy="cancel",
        claim="thin uniform disc: N = (3/2)mg − (7√3/16) m r Ω²",
    )
    d.confirm_exact(
        N_gen.subs(Omega, 0),
        m * g * (1 + sp.cos(b)),
        route="limit Ω → 0: the static load mg(1 + cos β)",
    )
    # numeric: numpy cross products at one instant with mechanics' inertia of a disc
    bn, rn, mn, gn, On = np.pi / 3, 0.5, 40.0, 9.81, 1.7
    Lgn = rn * (1 + np.cos(bn)) / np.sin(bn)
    e3n = np.array([np.sin(bn), 0.0, -np.cos(bn)])
    JG = inr.disc(mn, rn)  # about G, axis e3 = body 3
    JO_body = inr.parallel_axis(JG, mn, [0.0, 0.0, -Lgn])
    Jn, J3n = JO_body[0, 0], JO_body[2, 2]
    wn = On * np.array([0.0, 0.0, 1.0]) - On * e3n
    An = Lgn * e3n + rn * -np.array([np.cos(bn), 0.0, np.sin(bn)])
    LOn = Jn * wn + (J3n - Jn) * (wn @ e3n) * e3n
    dLn = np.cross(On * np.array([0.0, 0.0, 1.0]), LOn)  # L_O turns rigidly with the axis
    Mg = np.cross(Lgn * e3n, [0.0, 0.0, -mn * gn])
    Nn = (Mg[1] - dLn[1]) / An[0]  # e_t = e_y here; OA × N e_z has e_y component −A_x N
    d.confirm(
        [np.linalg.norm(np.cross(wn, An)), Nn],
        [0.0, float(Nd.subs({m: mn, g: gn, r: rn, Omega: On}))],
        atol=SIM_ATOL,
        route="numpy: ω × OA = 0 and N from dL_O/dt = Ω e_z × L_O with the disc's inertia "
        "from mechanics.inertia.disc + parallel_axis",
    )
