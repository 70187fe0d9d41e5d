"""Chapter 4 problems 4.1–4.5, derived symbolically in the book's symbols and each
confirmed by an independent route (a second derivation, a scipy simulation,
:mod:`mechanics`, a limit).  The book's answers are withheld; these are derived here.
"""

from __future__ import annotations

import numpy as np
import sympy as sp
from scipy.integrate import solve_ivp

from identities.verify.catalogue import check
from identities.verify.proof import Derivation
from identities.verify.symbolic import cross, functions_of_time, t, vec
from mechanics import dynamics as dyn
from mechanics import inertia as inr
from mechanics._floats import EPS

#: mechanics against a float evaluation of the same exact value (a few products and sums of
#: O(1) numbers): 64 eps.
CODE_ATOL = 64 * EPS
#: solve_ivp (DOP853) with rtol = 1e-12 over a few periods of O(1) motion: the global error
#: stays below ~1e-10 relative; 2^20 eps ≈ 2.3e-10.
SIM_RTOL = 2**20 * EPS

m, g, ell, k, R, a = sp.symbols("m g ell k R a", positive=True)
x = sp.Symbol("x", positive=True)
phi, alpha = sp.symbols("phi alpha", real=True)
ez = vec(0, 0, 1)

#: Gauss–Legendre nodes: exact for the polynomial (degree ≤ 3) integrands along a rod.
_GL_X, _GL_W = np.polynomial.legendre.leggauss(4)


def _simulate(rhs, y0, t_end, t_eval=None):
    return solve_ivp(rhs, (0, t_end), y0, method="DOP853", rtol=1e-12, atol=1e-14, t_eval=t_eval)


# ----------------------------------------------------------------------------- 4.1


def _rod_section_forces():
    """N, T, M on CB (distance x from B) of the rod of Problem 4.1, from the rod's motion.

    Returns the symbolic (N, T, M) with φ̇², φ̈ of the rod released from rest at α."""
    phidot2 = 3 * g / ell * (sp.cos(phi) - sp.cos(alpha))  # energy, J_A = m ℓ²/3, h = ℓ/2
    phiddot = -3 * g / (2 * ell) * sp.sin(phi)  # (4.48)
    m_CB = m * x / ell
    s_G = ell - x / 2  # distance from A to the centre of CB
    # momentum of CB (components along e_r = A→B and e_φ): m_CB a_G = m_CB g − N e_r + T e_φ
    N = m_CB * (g * sp.cos(phi) + s_G * phidot2)
    T = m_CB * (s_G * phiddot + g * sp.sin(phi))
    # angular momentum of CB about its own G: J_G φ̈ = M + (C − G) × (T e_φ), C − G = −(x/2) e_r
    M = m_CB * x**2 / 12 * phiddot + x / 2 * T
    return N, T, M, phidot2, phiddot


@check(
    "P4.1",
    "Problem 4.1: tension, shear and bending moment in a swinging rod",
    kind="derivation",
    covers=("P4.1",),
    statement="rod AB (m, ℓ) swinging about A with amplitude α; on the part CB (|CB| = x): "
    "N = (m g x/ℓ)[cos φ + 3(1 − x/(2ℓ))(cos φ − cos α)], T = (m g x/(4ℓ²))(3x − 2ℓ) sin φ, "
    "M = −m g x²(ℓ − x) sin φ/(4ℓ²)",
    reading="sign conventions (the figure is lost): e_r along the rod from A to B, e_φ in the "
    "sense of increasing φ, e_z = e_r × e_φ; the force on CB from AC is −N e_r + T e_φ (N > 0 "
    "is tension) and the couple on CB from AC is M e_z.  The rod is released from rest at φ = α.",
)
def problem_4_1(d: Derivation) -> None:
    N, T, M, phidot2, phiddot = _rod_section_forces()
    N = d.quantity("N", sp.factor(N))
    T = d.quantity("T", sp.factor(sp.expand(T)))
    M = d.quantity("M", sp.factor(sp.expand(M)))
    d.prove_equal(
        N,
        m * g * x / ell * (sp.cos(phi) + 3 * (1 - x / (2 * ell)) * (sp.cos(phi) - sp.cos(alpha))),
        strategy="expand",
        claim="N",
    )
    d.prove_equal(
        T, m * g * x * (3 * x - 2 * ell) * sp.sin(phi) / (4 * ell**2), strategy="expand", claim="T"
    )
    d.prove_equal(
        M, -m * g * x**2 * (ell - x) * sp.sin(phi) / (4 * ell**2), strategy="expand", claim="M"
    )
    d.reject(
        M, -m * g * x**2 * (ell - x) * sp.sin(phi) / (2 * ell**2), strategy="expand", claim="M ×2"
    )
    d.prove_equal(M.subs(x, ell), 0, strategy="expand", claim="no bending moment at the pivot A")
    # second route: d'Alembert, integrating the distributed loads over CB (s from A)
    s = sp.Symbol("s", positive=True)
    lam = m / ell
    s_C = ell - x
    acc_r, acc_phi = -s * phidot2, s * phiddot
    g_r, g_phi = g * sp.cos(phi), -g * sp.sin(phi)
    F_r = sp.integrate(lam * (acc_r - g_r), (s, s_C, ell))  # = −N
    F_phi = sp.integrate(lam * (acc_phi - g_phi), (s, s_C, ell))  # = T
    M_C = sp.integrate(lam * (s - s_C) * (acc_phi - g_phi), (s, s_C, ell))  # e_r × e_φ = e_z
    d.confirm_exact(vec(-F_r, F_phi, M_C), vec(N, T, M), route="d'Alembert: ∫ (a − g) dm over CB")
    # third route: at x = ℓ the section is the axis: (N, T) = (−R_ρ, R_φ) of (4.76)-(4.77)
    pt = {m: 2.0, g: 9.81, ell: 1.5, phi: 0.7, alpha: 1.2}
    E = 2.0 * 9.81 * 0.75 * (1 - np.cos(1.2))
    R_ax = dyn.pendulum_axis_reaction(0.7, 2.0 * 1.5**2 / 3, 2.0, 9.81, 0.75, E=E)
    d.confirm(
        [float(N.subs(x, ell).subs(pt)), float(T.subs(x, ell).subs(pt))],
        [-R_ax[0], R_ax[1]],
        atol=CODE_ATOL * 20,
        route="mechanics.pendulum_axis_reaction: the cut at A carries the axis reaction",
    )
    # fourth route: simulate the swing, then sum forces on Gauss points of CB at one instant
    ln, gn, mn, al = 1.5, 9.81, 2.0, 1.2
    sol = _simulate(lambda _t, y: [y[1], -1.5 * gn / ln * np.sin(y[0])], [al, 0.0], 0.4)
    ph, pd = sol.y[0, -1], sol.y[1, -1]
    pdd = -1.5 * gn / ln * np.sin(ph)
    xn = 0.6
    sn = (ln - xn) + xn * (_GL_X + 1) / 2
    wn = _GL_W * xn / 2 * mn / ln
    ar, ap = -sn * pd**2 - gn * np.cos(ph), sn * pdd + gn * np.sin(ph)
    num = [-(wn @ ar), wn @ ap, wn @ ((sn - (ln - xn)) * ap)]
    sym = [float(q.subs({m: mn, g: gn, ell: ln, x: xn, phi: ph, alpha: al})) for q in (N, T, M)]
    d.confirm(num, sym, atol=SIM_RTOL * 100, route="scipy simulation + quadrature of CB's loads")


# ----------------------------------------------------------------------------- 4.2


@check(
    "P4.2",
    "Problem 4.2: a rod hanging in two strings: the largest amplitude with taut strings",
    kind="derivation",
    covers=("P4.2",),
    statement="|AB| : |AO| = 6 : 5: the strings stay taut iff tan α ≤ a J_O/(h J_G) = 19/4, "
    "α_max = arctan(19/4) ≈ 78.1°",
    reading="the rod with taut strings is a rigid physical pendulum about O; a = |AB|/2, h = "
    "√(|AO|² − a²) is the distance O–G; released from rest at φ = α.  The string on the side "
    "the rod swings toward loses tension first, at the turning point.",
)
def problem_4_2(d: Derivation) -> None:
    L_s, h = sp.symbols("L_s h", positive=True)  # string length, distance O-G
    T_A, T_B = sp.symbols("T_A T_B", real=True)
    J_G = m * a**2 / 3  # rod of length 2a
    J_O = J_G + m * h**2  # (4.54)
    phidot2 = 2 * m * g * h / J_O * (sp.cos(phi) - sp.cos(alpha))  # (4.75), from rest at α
    phiddot = -m * g * h / J_O * sp.sin(phi)  # (4.73)
    # components along (e_ρ, e_φ, e_z): e_ρ from O toward G, e_φ in the sense of increasing φ
    e_rho, e_phi = vec(1, 0, 0), vec(0, 1, 0)
    A, B = h * e_rho - a * e_phi, h * e_rho + a * e_phi
    u_A, u_B = -A / L_s, -B / L_s  # along the strings toward O
    a_G = -h * phidot2 * e_rho + h * phiddot * e_phi  # (4.70)
    grav = m * g * (sp.cos(phi) * e_rho - sp.sin(phi) * e_phi)  # (4.72)
    eqs = m * a_G - (T_A * u_A + T_B * u_B + grav)
    sol = sp.solve([eqs[0], eqs[1]], [T_A, T_B], dict=True)[0]
    TA, TB = sp.factor(sol[T_A]), sp.factor(sol[T_B])
    d.quantity("T_A", TA)
    d.quantity("T_B", TB)
    # second route: the angular momentum of the rod about G gives T_A − T_B
    mom = (cross(A - h * e_rho, T_A * u_A) + cross(B - h * e_rho, T_B * u_B))[2]
    d.confirm_exact(
        (J_G * phiddot - mom).subs(sol),
        0,
        route="L̇_G = M_G for the rod about its centre, with the tensions from the momentum",
        strategy="cancel",
    )
    TB_turn = TB.subs(phi, alpha)
    d.prove_equal(
        TB_turn,
        L_s * m * g * (sp.cos(alpha) / h - sp.sin(alpha) * J_G / (a * J_O)) / 2,
        strategy="trigsimp",
        claim="at the turning point T_B = (L_s m g/2)(cos α/h − sin α J_G/(a J_O))",
    )
    tan_max = a * J_O / (h * J_G)
    d.prove_equal(
        TB_turn.subs(sp.sin(alpha), sp.cos(alpha) * tan_max),
        0,
        strategy="expand",
        claim="T_B = 0 at the turning point iff tan α = a J_O/(h J_G)",
    )
    dTB = sp.diff(TB, phi)
    d.prove_equal(
        dTB,
        -L_s
        * m
        * g
        / 2
        * (sp.sin(phi) * (1 / h + 2 * m * h / J_O) + sp.cos(phi) * J_G / (a * J_O)),
        strategy="trigsimp",
        claim="dT_B/dφ < 0 on [0, π/2]: T_B is least at the turning point",
    )
    ratio = {a: 3, h: 4, L_s: 5}  # |AB| = 6, |AO| = 5, so h = √(25 − 9) = 4
    tan_n = sp.nsimplify(tan_max.subs(ratio))
    d.quantity("tan_alpha_max", tan_n)
    d.prove_equal(tan_n, sp.Rational(19, 4), strategy="expand", claim="tan α_max = 19/4")
    d.reject(
        tan_n,
        sp.Rational(4, 3),
        strategy="expand",
        claim="tan α_max = h/a = 4/3 (the strings' own inclination)",
    )
    alpha_max = sp.atan(sp.Rational(19, 4))
    d.quantity("alpha_max", alpha_max)
    d.quantity("alpha_max_degrees", sp.N(alpha_max * 180 / sp.pi, 4))
    # simulation: tensions along the motion for α just below / above α_max
    TB_f = sp.lambdify((phi, alpha), (TB / (m * g)).subs(ratio), "numpy")
    TA_f = sp.lambdify((phi, alpha), (TA / (m * g)).subs(ratio), "numpy")
    Jr = sp.lambdify(g, (m * g * h / J_O).subs(ratio).subs(m, 1), "numpy")(9.81)
    am = float(alpha_max)
    mins = []
    for al in (0.99 * am, 1.01 * am):
        sim = _simulate(
            lambda _t, y: [y[1], -Jr * np.sin(y[0])], [al, 0.0], 4.0, np.linspace(0, 4.0, 4001)
        )
        mins.append(min(TA_f(sim.y[0], al).min(), TB_f(sim.y[0], al).min()))
    d.note(
        f"least tension/(m g) over 4 s: {mins[0]:.3g} at 0.99 α_max, {mins[1]:.3g} at 1.01 α_max"
    )
    d.confirm(
        [float(mins[0] > 0), float(mins[1] < 0)],
        [1.0, 1.0],
        atol=0.0,
        route="scipy: simulated swings keep both strings taut just below α_max, not just above",
    )


# ----------------------------------------------------------------------------- 4.3


@check(
    "P4.3",
    "Problem 4.3: a disc hanging in a string and a spring: T = π √(3m/(2k))",
    kind="derivation",
    covers=("P4.3",),
    statement="the disc rolls on the string from A: the spring stretches by 2x (Fig. 4.9); "
    "kinetic energy ¾ m ẋ², potential ½ k (2x)² about equilibrium: ω0² = 8k/(3m), "
    "T = 2π √(3m/(8k)) = π √(3m/(2k))",
    reading="x is the downward displacement of the disc's centre; both string ends are vertical "
    "(A and B are 2R apart); the string does not slip on the disc and is inextensible.",
)
def problem_4_3(d: Derivation) -> None:
    xf = functions_of_time("x")[0]
    xd = xf.diff(t)
    w = sp.Symbol("omega", real=True)
    v_G = vec(0, -xd, 0)
    v_left = v_G + cross(w * ez, vec(-R, 0, 0))
    w_sol = sp.solve(v_left[1], w)[0]  # the point on the fixed string is at rest
    v_right = (v_G + cross(w * ez, vec(R, 0, 0))).subs(w, w_sol)
    d.prove_equal(v_right[1], -2 * xd, strategy="expand", claim="the right side moves down at 2ẋ")
    d.reject(v_right[1], -xd, strategy="expand", claim="the spring stretches by x")
    J_G = m * R**2 / 2
    T_kin = m * xd**2 / 2 + J_G * w_sol**2 / 2
    d.prove_equal(T_kin, sp.Rational(3, 4) * m * xd**2, strategy="expand", claim="T = ¾ m ẋ²")
    delta0 = m * g / (2 * k)  # equilibrium stretch: m g = 2 k δ0 (two vertical string forces)
    V = -m * g * xf + k * (delta0 + 2 * xf) ** 2 / 2
    eom = sp.expand(sp.diff(T_kin + V, t) / xd)
    xdd = sp.solve(eom, xf.diff(t, 2))[0]
    w0_sq = -sp.diff(xdd, xf)
    d.prove_equal(xdd.subs(xf, 0), 0, strategy="expand", claim="x = 0 is the equilibrium")
    w0_sq = d.quantity("omega_0_squared", sp.simplify(w0_sq))
    d.prove_equal(w0_sq, 8 * k / (3 * m), strategy="cancel", claim="ω0² = 8k/(3m)")
    T_p = d.quantity("T_p", 2 * sp.pi / sp.sqrt(w0_sq))
    d.prove_equal(T_p**2, sp.pi**2 * 3 * m / (2 * k), strategy="cancel", claim="T = π√(3m/(2k))")
    d.reject(T_p**2, sp.pi**2 * 4 * m / k, strategy="cancel", claim="a mass on the spring alone")
    # second route: Newton–Euler with the string force S1 (at A's side) and the spring force F
    S1, xdd_s = sp.symbols("S_1 xddot", real=True)
    Fsp = k * (delta0 + 2 * xf)
    ne = sp.solve(
        [m * xdd_s - (m * g - S1 - Fsp), J_G * (-xdd_s / R) - (-R * S1 + R * Fsp)], [S1, xdd_s]
    )
    d.confirm_exact(
        -sp.diff(ne[xdd_s], xf),
        8 * k / (3 * m),
        route="Newton–Euler for the disc",
        strategy="cancel",
    )
    # third route: simulate Newton–Euler (with gravity and preload) and time the period
    mn, kn, gn = 0.5, 20.0, 9.81
    acc = sp.lambdify(xf, ne[xdd_s].subs({m: mn, k: kn, g: gn, R: 0.1}), "numpy")

    def up(_t, y):
        return y[1]

    up.direction, up.terminal = 1, True
    sim = solve_ivp(
        lambda _t, y: [y[1], acc(y[0])],
        (0, 5.0),
        [0.01, 0.0],
        method="DOP853",
        rtol=1e-12,
        atol=1e-14,
        events=up,
    )
    T_ref = float(np.pi * np.sqrt(3 * mn / (2 * kn)))
    d.confirm(2 * sim.t_events[0][0], T_ref, atol=SIM_RTOL * T_ref, route="scipy: the period")
    d.confirm(
        inr.disc(mn, 0.1)[2, 2], mn * 0.1**2 / 2, atol=CODE_ATOL, route="mechanics.disc: J = mR²/2"
    )


# ----------------------------------------------------------------------------- 4.4


@check(
    "P4.4",
    "Problem 4.4: a cube rocking on a rough semi-cylinder: T = 2π √(5a²/(3g(R − a)))",
    kind="derivation",
    covers=("P4.4",),
    statement="a cube of side 2a rolling without slipping on a cylinder of radius R: ω0² = "
    "3g(R − a)/(5a²), T = 2π a √(5/(3g(R − a))); the equilibrium is stable only for R > a",
    reading="θ is the cube's tilt (= the angle of the contact point on the cylinder); rolling "
    "means the contact has moved Rθ along the bottom face.",
)
def problem_4_4(d: Derivation) -> None:
    th = functions_of_time("theta")[0]
    thd = th.diff(t)
    G = vec(
        (R + a) * sp.sin(th) - R * th * sp.cos(th), (R + a) * sp.cos(th) + R * th * sp.sin(th), 0
    )
    P = R * vec(sp.sin(th), sp.cos(th), 0)
    v_P = G.diff(t) + cross(-thd * ez, P - G)  # the cube turns clockwise by θ
    d.prove_equal(
        v_P, vec(0, 0, 0), strategy="trigsimp", claim="rolling: the contact point is at rest"
    )
    J_G = 2 * m * a**2 / 3  # cube of side 2a: m((2a)² + (2a)²)/12
    T_kin = m * (G.diff(t).T * G.diff(t))[0] / 2 + J_G * thd**2 / 2
    V = m * g * G[1]
    Lag = T_kin - V
    q, qd, qdd = sp.symbols("q qd qdd", real=True)
    L_s = Lag.subs(th.diff(t), qd).subs(th, q)
    eq = sp.diff(sp.diff(L_s, qd), qd) * qdd + sp.diff(sp.diff(L_s, qd), q) * qd - sp.diff(L_s, q)
    qdd_sol = sp.solve(eq, qdd)[0]
    lin = sp.diff(qdd_sol, q).subs({q: 0, qd: 0})
    w0_sq = d.quantity("omega_0_squared", sp.simplify(-lin))
    d.prove_equal(
        w0_sq, 3 * g * (R - a) / (5 * a**2), strategy="cancel", claim="ω0² = 3g(R − a)/(5a²)"
    )
    d.reject(w0_sq, 3 * g * (R - a) / (2 * a**2), strategy="cancel", claim="ω0² with J_G alone")
    T_p = d.quantity("T_p", 2 * sp.pi * a * sp.sqrt(5 / (3 * g * (R - a))))
    d.prove_equal(T_p**2, (2 * sp.pi) ** 2 / w0_sq, strategy="cancel", claim="T = 2π/ω0")
    d.quantity("stability_condition", sp.Gt(R, a))
    # second route: the potential to second order and the moment about the contact point
    V2 = sp.series(G[1].subs(th, q), q, 0, 3).removeO()
    d.confirm_exact(
        V2, R + a + (R - a) * q**2 / 2, route="y_G ≈ R + a + (R − a)θ²/2", strategy="expand"
    )
    J_P = J_G + m * a**2
    d.confirm_exact(
        m * g * (R - a) / J_P,
        w0_sq,
        route="ω0² = m g (R − a)/J_P (rocking about the contact)",
        strategy="cancel",
    )
    d.confirm(
        inr.box(3.0, 2.0, 2.0, 2.0)[0, 0], 2.0, atol=CODE_ATOL, route="mechanics.box: J_G = 2ma²/3"
    )

    # simulation of the exact Lagrange equation: period for R > a, escape for R < a
    def simulate(Rn, theta_0=1e-3, **kw):
        f = sp.lambdify((q, qd), qdd_sol.subs({R: Rn, a: 0.5, g: 9.81, m: 1}), "numpy")
        return solve_ivp(
            lambda _t, y: [y[1], f(y[0], y[1])],
            (0, 10.0),
            [theta_0, 0.0],
            method="DOP853",
            rtol=1e-12,
            atol=1e-16,
            **kw,
        )

    def turn(_t, y):
        return y[1]

    turn.direction, turn.terminal = 1, True
    T_ref = float(T_p.subs({R: 1, a: sp.Rational(1, 2), g: sp.Rational(981, 100)}))
    # the period at amplitude θ0 is T0 (1 + c θ0² + O(θ0⁴)); Richardson's extrapolation from
    # θ0 = 1e-3 and 5e-4 removes the θ0² term and leaves O(θ0⁴) = 1e-12 ≪ SIM_RTOL
    half_periods = [simulate(1.0, th0, events=turn).t_events[0][0] for th0 in (1e-3, 5e-4)]
    d.confirm(
        2 * (4 * half_periods[1] - half_periods[0]) / 3,
        T_ref,
        atol=SIM_RTOL * T_ref,
        route="scipy: the exact rolling motion (R = 2a), its period extrapolated to zero amplitude, is T_p",
    )

    def away(_t, y):
        return y[0] - 0.1

    away.terminal = True
    esc = simulate(0.4, events=away, dense_output=True)
    tt = np.linspace(1e-3, esc.t[-1], 200)
    d.confirm(
        float(esc.t_events[0].size == 1 and np.all(esc.sol(tt)[1] > 0)),
        1.0,
        atol=0.0,
        route="scipy: for R < a (R = 0.8a) the cube tilts away monotonically to θ = 0.1 (unstable)",
    )


# ----------------------------------------------------------------------------- 4.5


@check(
    "P4.5",
    "Problem 4.5: a falling chimney breaks one third up, its top lagging behind",
    kind="derivation",
    covers=("P4.5",),
    statement="with Problem 4.1's M = −m g x²(ℓ − x) sin φ/(4ℓ²) (released upright, α = π), |M| "
    "is largest at x = 2ℓ/3 from the top, i.e. ℓ/3 above the base, at every instant; the couple "
    "on the upper part acts in the direction of the fall (M φ̇ > 0), so without it the top lags: "
    "the brick opens on the side facing the ground, the chimney bending backwards",
    reading="a uniform chimney modelled as the rod of Problem 4.1 pivoted at its base A, φ from "
    "the downward vertical (upright: φ = π), falling with φ decreasing; brick breaks where the "
    "bending moment is largest (it takes little tension).",
)
def problem_4_5(d: Derivation) -> None:
    _, _, M, _, _ = _rod_section_forces()
    M = sp.factor(sp.expand(M))
    dM = sp.diff(M, x)
    crit = sp.solve(sp.factor(dM / (m * g * sp.sin(phi))), x)
    x_break = next(c for c in crit if c != 0)
    d.quantity("x_break_from_top", x_break)
    d.quantity("height_of_break", ell - x_break)
    d.prove_equal(x_break, 2 * ell / 3, strategy="expand", claim="dM/dx = 0 at x = 2ℓ/3")
    d.reject(x_break, ell / 2, strategy="expand", claim="the break at mid-height")
    d.prove_equal(
        sp.diff(M, x, 2).subs(x, x_break),
        m * g * sp.sin(phi) / (2 * ell),
        strategy="expand",
        claim="M'' has the sign of sin φ there: an extremum of |M| (M itself has the sign of −sin φ)",
    )
    d.quantity("M_max", sp.factor(M.subs(x, x_break)))
    d.prove_equal(
        M.subs(x, x_break),
        -m * g * ell * sp.sin(phi) / 27,
        strategy="expand",
        claim="|M|max = mgℓ sinφ/27",
    )
    d.quantity("couple_direction", sp.Symbol("along_the_fall"))
    # numeric demonstration: simulate the fall; bending moment along the chimney by quadrature
    ln, gn, mn = 30.0, 9.81, 1.0
    sol = _simulate(
        lambda _t, y: [y[1], -1.5 * gn / ln * np.sin(y[0])],
        [np.pi - 1e-3, 0.0],
        6.0,
        np.linspace(3.0, 6.0, 7),
    )
    xs = np.linspace(0.0, ln, 301)
    ok_pos, ok_dir = [], []
    for ph, pd in zip(sol.y[0], sol.y[1], strict=True):
        if ph < np.pi / 2:
            continue  # hits the ground at φ = π/2
        pdd = -1.5 * gn / ln * np.sin(ph)
        Ms = []
        for xn in xs:
            sn = (ln - xn) + xn * (_GL_X + 1) / 2
            wn = _GL_W * xn / 2 * mn / ln
            Ms.append(wn @ ((sn - (ln - xn)) * (sn * pdd + gn * np.sin(ph))))
        Ms = np.array(Ms)
        ok_pos.append(xs[np.argmax(np.abs(Ms))])
        ok_dir.append(float(np.all(Ms[1:-1] * pd > 0)))
    d.note(f"instants checked while falling: {len(ok_pos)}")
    d.confirm(
        ok_pos,
        [2 * ln / 3] * len(ok_pos),
        atol=ln / 300,
        route="scipy: the simulated fall's bending moment (quadrature of the loads) peaks at "
        "2ℓ/3 from the top (grid step ℓ/300)",
    )
    d.confirm(
        ok_dir,
        [1.0] * len(ok_dir),
        atol=0.0,
        route="scipy: the couple on the upper part acts along the fall at every x and instant",
    )
