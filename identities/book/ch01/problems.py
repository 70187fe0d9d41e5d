"""Chapter 1 problems 1.1–1.11, derived symbolically in the book's symbols and each
confirmed by an independent route (numerics through :mod:`mechanics.particles` where it
exists, a scipy simulation, a second derivation, or a limit).  The book's answers are
withheld; these are derived here.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from identities.book.ch01.momentum import CODE_ATOL, EPS, num_angular_momentum, num_moment_of_forces
from identities.verify.catalogue import check
from identities.verify.proof import Derivation
from identities.verify.symbolic import cross, floats, t, vec

#: scipy solve_ivp at rtol = atol = 1e-12 over O(1)–O(10) times on O(1) states:
#: global errors measured ≲ 1e-10; 2**20 eps ≈ 2.3e-10.
SIM_ATOL = 2**20 * EPS
ez = vec(0, 0, 1)


def _f(x, subs=None) -> np.ndarray:
    return floats(x, subs).ravel()


@check(
    "P1.1",
    "Problem 1.1: a particle in uniform circular motion, L_A and M_A about any point",
    kind="derivation",
    covers=("P1.1",),
    statement="r_P = r (cos θ, sin θ, 0), θ = v t/r; A = (a, b, c): L_A, M_A = L̇_A; M_A ≡ 0 "
    "only for A = O, so the force points at the centre",
)
def problem_1_1(d: Derivation) -> None:
    m, v, r = sp.symbols("m v r", positive=True)
    a, b, c = sp.symbols("a b c", real=True)
    th = v * t / r
    P = r * vec(sp.cos(th), sp.sin(th), 0)
    A = vec(a, b, c)
    vP = sp.diff(P, t)
    L_A = d.quantity("L_A", sp.expand(cross(P - A, m * vP)))
    d.prove_equal(
        L_A,
        m * v * vec(c * sp.cos(th), c * sp.sin(th), r - a * sp.cos(th) - b * sp.sin(th)),
        strategy="trigsimp",
        claim="L_A = m v (c cos θ, c sin θ, r - a cos θ - b sin θ)",
    )
    M_A = d.quantity("M_A", sp.expand(sp.diff(L_A, t)))
    d.confirm_exact(
        M_A,
        cross(P - A, m * sp.diff(P, t, 2)),
        strategy="trigsimp",
        route="second derivation: M_A = AP × m a_P with the centripetal acceleration",
    )
    coeffs = []
    for comp in M_A:
        e = sp.expand(comp)
        coeffs += [e.coeff(sp.sin(th)), e.coeff(sp.cos(th))]
    sol = sp.solve(coeffs, [a, b, c], dict=True)
    if sol != [{a: 0, b: 0, c: 0}]:
        raise AssertionError(f"expected only A = O, got {sol}")
    d.quantity("A_with_M_A_zero", vec(0, 0, 0))
    d.prove_zero(M_A.subs({a: 0, b: 0, c: 0}), strategy="expand", claim="M_O = 0")
    d.reject(
        M_A.subs({a: 0, b: 0}), sp.zeros(3, 1), strategy="trigsimp", claim="M_A = 0 on the axis"
    )
    F = d.quantity("F", m * sp.diff(P, t, 2))
    d.prove_equal(F, -(m * v**2 / r**2) * P, strategy="expand", claim="(c) F = -(m v²/r) e_r")
    pt = {
        m: 2,
        v: 3,
        r: sp.Rational(3, 2),
        a: 1,
        b: -1,
        c: sp.Rational(1, 2),
        t: sp.Rational(7, 10),
    }
    L_num, route = num_angular_momentum([2.0], _f(P, pt)[None], _f(vP, pt)[None], [1.0, -1.0, 0.5])
    d.confirm(L_num, _f(L_A, pt), atol=CODE_ATOL, route=f"{route} at a point of the orbit")
    M_num, route_M = num_moment_of_forces(_f(P, pt)[None], _f(F, pt)[None], [1.0, -1.0, 0.5])
    d.confirm(M_num, _f(M_A, pt), atol=CODE_ATOL, route=f"{route_M} of F = m a about A")


@check(
    "P1.2",
    "Problem 1.2: total force and moment on a three-particle system",
    kind="derivation",
    covers=("P1.2",),
    statement="masses 3m, m, 5m at (t, -2, 3t²), (t - 1, t³, 5), (2 - t², t, t³): "
    "F = Σ m_j r̈_j, M_O = Σ r_j × m_j r̈_j",
)
def problem_1_2(d: Derivation) -> None:
    m = sp.Symbol("m", positive=True)
    ms = [3 * m, m, 5 * m]
    rs = [vec(t, -2, 3 * t**2), vec(t - 1, t**3, 5), vec(2 - t**2, t, t**3)]
    acc = [sp.diff(x, t, 2) for x in rs]
    F = d.quantity("F", sum((mj * aj for mj, aj in zip(ms, acc, strict=True)), sp.zeros(3, 1)))
    d.prove_equal(
        F, m * vec(-10, 6 * t, 18 + 30 * t), strategy="expand", claim="F = m (-10, 6t, 18 + 30t)"
    )
    M_O = d.quantity(
        "M_O",
        sp.expand(
            sum((cross(x, mj * aj) for x, mj, aj in zip(rs, ms, acc, strict=True)), sp.zeros(3, 1))
        ),
    )
    p = sum((mj * sp.diff(x, t) for mj, x in zip(ms, rs, strict=True)), sp.zeros(3, 1))
    L_O = sum((cross(x, mj * sp.diff(x, t)) for mj, x in zip(ms, rs, strict=True)), sp.zeros(3, 1))
    d.confirm_exact(sp.diff(p, t), F, route="second derivation: F = ṗ")
    d.confirm_exact(sp.diff(L_O, t), M_O, route="second derivation: M_O = L̇_O (origin fixed)")
    d.reject(
        M_O,
        sum((cross(mj * aj, x) for x, mj, aj in zip(rs, ms, acc, strict=True)), sp.zeros(3, 1)),
        claim="M_O = Σ F_j × r_j",
    )
    tn = 1.5
    pos = np.array([_f(x, {t: tn}) for x in rs])
    Fj = np.array([_f(mj * aj, {t: tn, m: 1}) for mj, aj in zip(ms, acc, strict=True)])
    M_num, route = num_moment_of_forces(pos, Fj, np.zeros(3))
    d.confirm(M_num, _f(M_O, {t: tn, m: 1}), atol=CODE_ATOL, route=f"{route} at t = 1.5, m = 1")


@check(
    "P1.3",
    "Problem 1.3: the rotating rod with zero angular momentum about the Z-axis",
    kind="derivation",
    covers=("P1.3",),
    statement="rod from x = c - a to c + b, turning at ω about the vertical axis x = c: "
    "L_z = 0 for c = 2(a³ + b³)/(3(a² - b²)) = 2(a² - ab + b²)/(3(a - b)), a > b",
    reading="the rod's mass m is not given: L_z = 0 does not depend on it; c > 0 needs a > b",
)
def problem_1_3(d: Derivation) -> None:
    a, b, m, omega = sp.symbols("a b m omega", positive=True)
    c, s = sp.symbols("c s", real=True)
    lam = m / (a + b)
    # (a) integration along the rod: element at x = c + s has velocity ω s e_y
    L_z_a = d.quantity("L_z", sp.integrate((c + s) * omega * s * lam, (s, -a, b)))
    c_sol = sp.solve(L_z_a, c)
    if len(c_sol) != 1:
        raise AssertionError(f"expected one c, got {c_sol}")
    c_star = d.quantity("c", sp.factor(c_sol[0]))
    d.prove_equal(
        c_star,
        2 * (a**2 - a * b + b**2) / (3 * (a - b)),
        strategy="cancel",
        claim="c = 2(a² - ab + b²)/(3(a - b))",
    )
    # (b) connection formula: L_O = L_A + OA × p, A on the axis, J_A = λ(a³ + b³)/3
    J_A = lam * (a**3 + b**3) / 3
    v_G = omega * (b - a) / 2 * vec(0, 1, 0)
    L_z_b = J_A * omega + cross(vec(c, 0, 0), m * v_G)[2]
    d.confirm_exact(L_z_b, L_z_a, strategy="cancel", route="(b) connection formula (1.46)")
    d.reject(L_z_b, J_A * omega, strategy="cancel", claim="L_z = J_A ω (the OA × p term dropped)")
    an, bn, mn, wn = 1.0, 0.4, 2.0, 1.5
    cn = float(c_star.subs({a: an, b: bn}))
    n = 2000
    s_mid = -an + (np.arange(n) + 0.5) * (an + bn) / n
    pos = np.stack([cn + s_mid, 0 * s_mid, 0 * s_mid], axis=-1)
    vel = np.stack([0 * s_mid, wn * s_mid, 0 * s_mid], axis=-1)
    L_num, route = num_angular_momentum(np.full(n, mn / n), pos, vel, np.zeros(3))
    # midpoint rule on the quadratic λ ω s (c + s): error (a + b)² m ω/(12 n²); twice that
    d.confirm(
        L_num[2],
        0.0,
        atol=(an + bn) ** 3 / (6 * n**2) * mn / (an + bn) * wn,
        route=f"{route} of 2000 rod elements at c*",
    )


@check(
    "P1.4",
    "Problem 1.4: measuring a rotor's moment of inertia with a falling weight",
    kind="derivation",
    covers=("P1.4",),
    statement="M falls x in time T from rest, string on an axle of radius r: "
    "J_L = M r² (g T²/(2x) - 1)",
)
def problem_1_4(d: Derivation) -> None:
    M, r, g, x, T, J_L, S, acc = sp.symbols("M r g x T J_L S a", positive=True)
    # angular momentum principle about L for rotor + weight: d/dt (J_L ω + M v r) = M g r
    a_sol = sp.solve(sp.Eq((J_L + M * r**2) * acc / r, M * g * r), acc)[0]
    J = d.quantity("J_L", sp.solve(sp.Eq(a_sol * T**2 / 2, x), J_L)[0])
    d.prove_equal(
        J, M * r**2 * (g * T**2 / (2 * x) - 1), strategy="cancel", claim="J_L = M r² (g T²/2x - 1)"
    )
    # second derivation: Newton for M and the rotor separately, S the string tension
    sol = sp.solve([M * acc - (M * g - S), J_L * acc / r - S * r], [acc, S], dict=True)[0]
    d.confirm_exact(sol[acc], a_sol, strategy="cancel", route="Newton for M, L̇ = M for the rotor")
    d.confirm_exact(
        (M * g * x - M * (a_sol * T) ** 2 / 2 - J_L * (a_sol * T / r) ** 2 / 2).subs(
            x, a_sol * T**2 / 2
        ),
        0,
        strategy="cancel",
        route="energy: M g x = (1/2) M v² + (1/2) J_L ω² at time T",
    )
    from scipy.integrate import solve_ivp

    Mn, rn, gn, xn, Tn = 0.5, 0.02, 9.81, 0.8, 3.0
    Jn = float(J.subs({M: Mn, r: rn, g: gn, x: xn, T: Tn}))
    sol_n = solve_ivp(
        lambda tt, y: [y[1], Mn * gn * rn**2 / (Jn + Mn * rn**2)],
        (0, Tn),
        [0, 0],
        rtol=1e-12,
        atol=1e-14,
    )
    d.confirm(
        sol_n.y[0, -1], xn, atol=SIM_ATOL, route="scipy: with this J_L the weight falls x in T"
    )


@check(
    "P1.5",
    "Problem 1.5: looking backwards on a free platform",
    kind="derivation",
    covers=("P1.5",),
    statement="J1 α + J2 β = 0 from L = 0: α = J2 (α - β)/(J1 + J2)",
)
def problem_1_5(d: Derivation) -> None:
    J_1, J_2 = sp.symbols("J_1 J_2", positive=True)
    alpha, beta, twist = sp.symbols("alpha beta theta", real=True)
    sol = sp.solve([J_1 * alpha + J_2 * beta, alpha - beta - twist], [alpha, beta], dict=True)[0]
    al = d.quantity("alpha", sol[alpha])
    d.prove_equal(
        al, J_2 * twist / (J_1 + J_2), strategy="cancel", claim="α = J2 (α - β)/(J1 + J2)"
    )
    d.reject(al, J_1 * twist / (J_1 + J_2), strategy="cancel", claim="α = J1 (α - β)/(J1 + J2)")
    d.confirm_exact(
        sp.limit(al, J_2, sp.oo), twist, route="limit J2 → ∞ (platform fixed): α = α - β"
    )
    from scipy.integrate import solve_ivp

    J1n, J2n = 1.2, 3.5

    def rhs(tt, y):  # internal torque τ(t) of the waist: J1 α̈ = τ, J2 β̈ = -τ
        tau = np.sin(3 * tt) + 0.5
        return [y[1], tau / J1n, y[3], -tau / J2n]

    s = solve_ivp(rhs, (0, 2.0), [0, 0, 0, 0], rtol=1e-12, atol=1e-14)
    a_n, b_n = s.y[0, -1], s.y[2, -1]
    d.confirm(
        a_n,
        float(al.subs({J_1: J1n, J_2: J2n, twist: a_n - b_n})),
        atol=SIM_ATOL,
        route="scipy: two bodies and an internal torque",
    )


@check(
    "P1.6",
    "Problem 1.6: the disc, the motor and the balanced lever arm",
    kind="derivation",
    covers=("P1.6",),
    statement="L about the fixed axis: (1/2) M R² ω = [(1/2) M R² + (M + m) a² + m_B b²] Ω with the "
    "counterweight m_B b = (M + m) a: Ω = M R² ω / (M R² + 2 (M + m) a (a + b))",
    reading="motor and counterweight are particles, the lever arm is light; the induction "
    "torque acts until the disc turns with the arm (final state)",
)
def problem_1_6(d: Derivation) -> None:
    M, R, m, a, b, omega = sp.symbols("M R m a b omega", positive=True)
    m_B = (M + m) * a / b
    J_disc = M * R**2 / 2
    J_all = J_disc + (M + m) * a**2 + m_B * b**2
    Om = d.quantity("Omega", sp.factor(J_disc * omega / J_all))
    d.prove_equal(
        Om, M * R**2 * omega / (M * R**2 + 2 * (M + m) * a * (a + b)), strategy="cancel", claim="Ω"
    )
    d.reject(
        Om,
        J_disc * omega / (J_disc + (M + m) * a**2),
        strategy="cancel",
        claim="counterweight forgotten",
    )
    d.confirm_exact(
        Om.subs(a, 0),
        omega,
        strategy="cancel",
        route="limit a → 0: the disc on the fixed axis keeps ω",
    )
    from scipy.integrate import solve_ivp

    vals = {M: 2.0, R: 0.3, m: 0.5, a: 0.4, b: 0.8, omega: 10.0}
    Jd, Ja = float(J_disc.subs(vals)), float((J_all - J_disc).subs(vals))
    k = 0.05  # induction: τ = k (ω_d - Ω_arm), internal to disc + arm

    def rhs(tt, y):
        tau = k * (y[0] - y[1])
        return [-tau / Jd, tau / Ja]

    s = solve_ivp(rhs, (0, 200.0), [10.0, 0.0], rtol=1e-12, atol=1e-14)
    d.confirm(
        s.y[:, -1],
        [float(Om.subs(vals))] * 2,
        atol=SIM_ATOL * 10,
        route="scipy: induction torque until disc and arm co-rotate",
    )


@check(
    "P1.7",
    "Problem 1.7: two balls shot out of a channel in a spinning sphere",
    kind="derivation",
    covers=("P1.7",),
    statement="(2/5) M R² ω0 = ((2/5) M R² + 2 m R²) ω1: Δω = -5 m ω0/(M + 5m), independent of v",
)
def problem_1_7(d: Derivation) -> None:
    M, R, m, w0 = sp.symbols("M R m omega_0", positive=True)
    J = sp.Rational(2, 5) * M * R**2
    w1 = d.quantity("omega_1", sp.factor(J * w0 / (J + 2 * m * R**2)))
    dw = d.quantity("Delta_omega", sp.factor(w1 - w0))
    d.prove_equal(dw, -5 * m * w0 / (M + 5 * m), strategy="cancel", claim="Δω = -5 m ω0/(M + 5m)")
    d.reject(dw, -2 * m * w0 / (M + 2 * m), strategy="cancel", claim="a thin shell J = M R²")
    d.note(
        "how: the smooth channel walls push each ball sideways (the normal force gives it the "
        "tangential speed ω r, Coriolis); the reaction on the sphere brakes it"
    )
    from scipy.integrate import solve_ivp

    Mn, Rn, mn, w0n, vn = 3.0, 0.5, 0.2, 4.0, 2.0
    Jn = 0.4 * Mn * Rn**2

    def rhs(tt, y):  # y = (r, ṙ, ω); wall force N = m (r ω̇ + 2 ṙ ω) on each ball, -2 N r on J
        r_, rd, w = y
        wd = -4 * mn * r_ * rd * w / (Jn + 2 * mn * r_**2)
        return [rd, r_ * w**2, wd]

    def out(tt, y):
        return y[0] - Rn

    out.terminal = True
    s = solve_ivp(rhs, (0, 10), [0.0, vn, w0n], rtol=1e-12, atol=1e-14, events=out)
    d.confirm(
        s.y[2, -1] - w0n,
        float(dw.subs({M: Mn, m: mn, w0: w0n})),
        atol=SIM_ATOL,
        route="scipy: balls in the channel, wall forces from Newton",
    )


@check(
    "P1.8",
    "Problem 1.8: a closed walk on a free platform turns it",
    kind="derivation",
    covers=("P1.8",),
    statement="with (1.82), J_z = m R²/2: +90° at R, in, -90° at R/2, out: "
    "Δα = -(3π/2) m M/((2m + M)(m + 2M))",
)
def problem_1_8(d: Derivation) -> None:
    m, M, R = sp.symbols("m M R", positive=True)
    Jz = m * R**2 / 2

    def arc(rho, dphi):  # (1.83); radial legs have dφ = 0
        return -M * rho**2 * dphi / (Jz + M * rho**2)

    Da = d.quantity("Delta_alpha", sp.factor(arc(R, sp.pi / 2) + arc(R / 2, -sp.pi / 2)))
    d.prove_equal(
        Da, -3 * sp.pi * m * M / (2 * (2 * m + M) * (m + 2 * M)), strategy="cancel", claim="Δα"
    )
    d.reject(Da, 0, strategy="cancel", claim="a closed walk leaves the platform where it was")
    from scipy.integrate import solve_ivp

    mn, Mn, Rn = 100.0, 70.0, 2.0
    legs = [
        (Rn, Rn, 0, np.pi / 2),
        (Rn, Rn / 2, np.pi / 2, np.pi / 2),
        (Rn / 2, Rn / 2, np.pi / 2, 0),
        (Rn / 2, Rn, 0, 0),
    ]
    alpha = 0.0
    for r0, r1, f0, f1 in legs:  # each leg in unit time, linear in ρ and φ

        def rhs(tt, y, r0=r0, r1=r1, f0=f0, f1=f1):
            rho = r0 + (r1 - r0) * tt
            return [-Mn * rho**2 * (f1 - f0) / (mn * Rn**2 / 2 + Mn * rho**2)]

        alpha = solve_ivp(rhs, (0, 1), [alpha], rtol=1e-12, atol=1e-14).y[0, -1]
    d.confirm(
        alpha,
        float(Da.subs({m: mn, M: Mn, R: Rn})),
        atol=SIM_ATOL,
        route="scipy: (1.80) along the four legs",
    )


@check(
    "P1.9",
    "Problem 1.9: the string tension just after the other string burns",
    kind="derivation",
    covers=("P1.9",),
    statement="before: S = m g/2; just after: S' = m g/4; ratio S/S' = 2",
)
def problem_1_9(d: Derivation) -> None:
    m, g, ell = sp.symbols("m g ell", positive=True)
    S, aGy, alpha = sp.symbols("S a_Gy alpha", real=True)
    S_before = d.quantity("S_before", m * g / 2)
    # bar from A (x = 0) to B (x = ℓ), at rest; A moves horizontally only (a_Ay = 0)
    eqs = [
        m * aGy - (S - m * g),
        m * ell**2 / 12 * alpha - cross(vec(-ell / 2, 0, 0), vec(0, S, 0))[2],
        aGy + cross(alpha * ez, vec(-ell / 2, 0, 0))[1],
    ]
    sol = sp.solve(eqs, [S, aGy, alpha], dict=True)[0]
    S_after = d.quantity("S_after", sol[S])
    d.prove_equal(S_after, m * g / 4, strategy="expand", claim="S' = m g/4")
    ratio = d.quantity("ratio", S_before / S_after)
    d.prove_equal(ratio, 2, strategy="cancel", claim="S/S' = 2")
    d.reject(S_after, m * g / 2, strategy="expand", claim="the tension does not change")
    al = -m * g * ell / 2 / (m * ell**2 / 3)  # about A at rest (1.50, v_A = 0): J_A α = M_A
    d.confirm_exact(
        m * g + m * al * ell / 2,
        S_after,
        strategy="cancel",
        route="second derivation about A: J_A = mℓ²/3",
    )
    # numeric: 20 particles on a rigid bar; solve Newton-Euler numerically
    n, mn, ln_, gn = 20, 1.0, 2.0, 9.81
    xs = (np.arange(n) + 0.5) * ln_ / n
    J_G = float(np.sum(mn / n * (xs - ln_ / 2) ** 2))
    Amat = np.array(
        [[mn, -1.0, 0.0], [0.0, ln_ / 2, J_G], [1.0, 0.0, -ln_ / 2]]
    )  # unknowns a_Gy, S, α
    _, S_, _ = np.linalg.solve(Amat, [-mn * gn, 0.0, 0.0])
    # the discretised J_G = m ℓ²/12 (1 - 1/n²) shifts S' by about 3 m g/(16 n²) < m g/n²
    d.confirm(S_, mn * gn / 4, atol=mn * gn / n**2, route="numpy: 20-particle bar, Newton-Euler")


@check(
    "P1.10",
    "Problem 1.10: a spinning pipe with two particles on springs (qualitative)",
    kind="derivation",
    covers=("P1.10",),
    statement="G stays at rest; (J + 2 m r²) φ̇ = const with J = M a²/12, r the particles' "
    "distance; r̈ = r φ̇² - (k/m)(r - L): the pipe turns with a periodically varying rate, "
    "fastest when the particles are innermost",
)
def problem_1_10(d: Derivation) -> None:
    M, a, m, k, L, b, w0 = sp.symbols("M a m k L b omega_0", positive=True)
    r = sp.Symbol("r", positive=True)
    J = M * a**2 / 12
    w = d.quantity("omega_of_r", w0 * (J + 2 * m * (L + b) ** 2) / (J + 2 * m * r**2))
    d.quantity("r_ddot", r * w**2 - k / m * (r - L))
    d.quantity("v_G", vec(0, 0, 0))
    d.prove_equal(
        sp.diff(w, r) * r,
        -4 * m * r**2 * w / (J + 2 * m * r**2),
        strategy="cancel",
        claim="ω decreases as r grows",
    )
    from scipy.integrate import solve_ivp

    vals = {M: 1.0, a: 2.0, m: 0.3, k: 20.0, L: 0.4, b: 0.2, w0: 3.0}
    Jn = float(J.subs(vals))

    def rhs(tt, y):  # y = (r, ṙ, φ, φ̇) from Newton: radial and tangential (wall force)
        r_, rd, _, fd = y
        fdd = -4 * 0.3 * r_ * rd * fd / (Jn + 2 * 0.3 * r_**2)
        return [rd, r_ * fd**2 - 20.0 / 0.3 * (r_ - 0.4), fd, fdd]

    s = solve_ivp(rhs, (0, 10), [0.6, 0.0, 0.0, 3.0], rtol=1e-12, atol=1e-14, dense_output=True)
    ts = np.linspace(0, 10, 2001)
    rr, fd = s.sol(ts)[0], s.sol(ts)[3]
    wf = sp.lambdify(r, w.subs(vals))
    d.confirm(
        fd, wf(rr), atol=SIM_ATOL, route="scipy: φ̇(t) follows ω(r(t)) (angular momentum conserved)"
    )
    d.confirm(
        bool(fd.min() > 0 and np.ptp(fd) > 0.1),
        True,
        atol=0.0,
        route=f"φ̇ stays positive and varies between {fd.min():.3f} and {fd.max():.3f}",
    )
    d.confirm(
        bool(abs(fd[np.argmin(rr)] - fd.max()) < 1e-6),
        True,
        atol=0.0,
        route="fastest at the smallest r",
    )


@check(
    "P1.11",
    "Problem 1.11: the back-spun cylinder that comes back",
    kind="derivation",
    covers=("P1.11",),
    statement="slip ends at t1 = (v + ω r)/(3 f g) with v1 = (2v - ω r)/3; it returns iff ω > 2v/r "
    "(back-spin)",
    reading="ω is the back-spin (the contact point moves forward at v + ω r)",
)
def problem_1_11(d: Derivation) -> None:
    m, r, v, w, f, g = sp.symbols("m r v omega f g", positive=True)
    J = m * r**2 / 2
    # slipping: m v̇ = -f m g; J ω̇ = -f m g r (friction against the slip v + ω r > 0)
    vt = v - f * g * t
    wt = w - f * m * g * r / J * t
    t1 = d.quantity("t_1", sp.solve(vt + wt * r, t)[0])
    d.prove_equal(t1, (v + w * r) / (3 * f * g), strategy="cancel", claim="t1")
    v1 = d.quantity("v_1", sp.expand(vt.subs(t, t1)))
    d.prove_equal(v1, (2 * v - w * r) / 3, strategy="expand", claim="v1 = (2v - ωr)/3")
    wc = d.quantity("omega_min", sp.solve(v1, w)[0])
    d.prove_equal(wc, 2 * v / r, strategy="expand", claim="returns iff ω > 2v/r")
    d.reject(wc, v / r, strategy="expand", claim="ω > v/r suffices")
    # second derivation: angular momentum about the contact point is conserved while slipping
    L_C = J * w - m * v * r  # L_z about a floor point, back-spin counter-clockwise
    d.confirm_exact(
        -L_C / (m * r + J / r),
        v1,
        strategy="cancel",
        route="second derivation: L about a floor point is conserved (friction passes through it): "
        "J ω - m v r = -(J/r + m r) v1",
    )
    from scipy.integrate import solve_ivp

    def run(wn, vn=1.0, rn=0.2, fn=0.3, gn=9.81):
        def rhs(tt, y):
            slip = y[1] + y[2] * rn
            s_ = np.sign(slip) if abs(slip) > 1e-12 else 0.0
            return [y[1], -s_ * fn * gn, -s_ * 2 * fn * gn / rn]

        def stick(tt, y):
            return y[1] + y[2] * rn

        stick.terminal = True
        s = solve_ivp(rhs, (0, 10), [0.0, vn, wn], events=stick, rtol=1e-12, atol=1e-14)
        return s.y[1, -1]

    wcn = 2 * 1.0 / 0.2
    d.confirm(
        run(wcn * 1.05) < 0 < run(wcn * 0.95),
        True,
        atol=0.0,
        route="scipy: rolls back just above 2v/r, not below",
    )
    d.confirm(
        run(7.0),
        (2 * 1.0 - 7.0 * 0.2) / 3,
        atol=SIM_ATOL,
        route="scipy: rolling speed after slip = (2v - ωr)/3",
    )
