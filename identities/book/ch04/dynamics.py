"""Chapter 4.2–4.3: Euler's dynamic equations, the physical pendulum, reaction forces.
Equations (4.41)–(4.57) and (4.66)–(4.85).

Euler's equations are derived from L̇ = M with the rotating-frame derivative (4.44),
and confirmed by a simulation that integrates the attitude with them and finds L
fixed in space.  The pendulum and the reactions are derived from the momentum and
angular-momentum principles written in Cartesian components, and confirmed against
:mod:`mechanics.dynamics` and by a particle model of the rotating body.
"""

from __future__ import annotations

import numpy as np
import sympy as sp
from scipy.integrate import solve_ivp
from scipy.optimize import minimize_scalar

from identities.verify.catalogue import check
from identities.verify.proof import Derivation
from identities.verify.symbolic import (
    cross,
    functions_of_time,
    general_rotation,
    omega_matrix,
    t,
    vec,
)
from mechanics import dynamics as dyn
from mechanics import inertia as inr
from mechanics._floats import EPS

#: mechanics against a float evaluation of the same exact value (a few products, sums and one
#: square root or elliptic integral of O(1) numbers): 64 eps.
CODE_ATOL = 64 * EPS
#: solve_ivp (DOP853) with rtol = 1e-12, atol = 1e-14 over a few periods of O(1) motion: the
#: global error stays below ~1e-10; 2^20 eps ≈ 2.3e-10.
SIM_ATOL = 2**20 * EPS
SIM_RTOL = 1e-12  # the integrator's requested local relative tolerance (see SIM_ATOL)

m, g, h, ell, J_z = sp.symbols("m g h ell J_z", positive=True)
phi, phidot, phiddot = sp.symbols("phi phidot phiddot", real=True)
ex, ey, ez = vec(1, 0, 0), vec(0, 1, 0), vec(0, 0, 1)


# ------------------------------------------------------------------------ Euler (4.47)


@check(
    "eq4.47",
    "Euler's dynamic equations J1 ω̇1 + (J3 − J2) ω2 ω3 = M1, ...",
    kind="proof",
    covers=("eq4.44", "eq4.45", "eq4.46", "eq4.47"),
    defines=("eq4.41", "eq4.42", "eq4.43"),
    statement="with L = J1ω1 e1 + J2ω2 e2 + J3ω3 e3 in the principal body basis (4.45), "
    "L̇ = ^A d/dt L + ω × L (4.44), (4.46), and L̇ = M (4.42)-(4.43) gives (4.47)",
)
def euler_equations(d: Derivation) -> None:
    # (4.44): for any motion R(t) = ^A R^O(t) with dR/dt = Ω R (Ω of (2.52)), and any body
    # components L^A(t), the O components of L are R^T L^A.
    a, b, c, e = sp.symbols("a b c e", real=True)
    R = general_rotation(a, b, c, e)
    w = vec(*sp.symbols("omega_1 omega_2 omega_3", real=True))
    Rdot = omega_matrix(w) * R
    LA, LAdot = vec(*sp.symbols("L_1 L_2 L_3", real=True)), vec(*sp.symbols("Ldot_1:4", real=True))
    lhs = Rdot.T * LA + R.T * LAdot  # ^O d/dt (R^T L^A)
    d.prove_equal(
        lhs,
        R.T * (LAdot + cross(w, LA)),
        strategy="numerator",
        claim="(4.44): ^O d/dt L = ^A d/dt L + ω × L, for every rotation and rate",
    )
    d.reject(
        lhs,
        R.T * (LAdot - cross(w, LA)),
        strategy="numerator",
        claim="(4.44) with − ω × L",
    )
    J_1, J_2, J_3 = sp.symbols("J_1 J_2 J_3", positive=True)
    om = sp.Matrix(functions_of_time("omega_1", "omega_2", "omega_3"))
    M = vec(*sp.symbols("M_1 M_2 M_3", real=True))
    L = sp.diag(J_1, J_2, J_3) * om  # (4.45)
    Ldot = sp.diff(L, t) + cross(om, L)  # (4.46)
    euler = [
        J_1 * om[0].diff(t) + (J_3 - J_2) * om[1] * om[2],
        J_2 * om[1].diff(t) + (J_1 - J_3) * om[2] * om[0],
        J_3 * om[2].diff(t) + (J_2 - J_1) * om[0] * om[1],
    ]
    d.prove_equal(Ldot, vec(*euler), strategy="expand", claim="(4.46) componentwise is (4.47)")
    d.reject(
        Ldot[0],
        J_1 * om[0].diff(t) + (J_2 - J_3) * om[1] * om[2],
        strategy="expand",
        claim="(4.47) with (J_2 − J_3) in the first equation",
    )
    # mechanics: ω̇ from (4.47) at a rational point
    pt = {J_1: 1, J_2: 2, J_3: sp.Rational(5, 2), M[0]: sp.Rational(1, 3), M[1]: -1, M[2]: 2}
    wv = [sp.Rational(1, 2), -1, sp.Rational(3, 4)]
    wdot = [
        ((M[i] - (euler[i] - [J_1, J_2, J_3][i] * om[i].diff(t))) / [J_1, J_2, J_3][i])
        .subs(dict(zip(om, wv, strict=True)))
        .subs(pt)
        for i in range(3)
    ]
    d.confirm(
        dyn.euler_equations_rhs([1.0, 2.0, 2.5], [float(v) for v in wv], [1 / 3, -1.0, 2.0]),
        [float(v) for v in wdot],
        atol=CODE_ATOL,
        route="mechanics.euler_equations_rhs equals ω̇ solved from (4.47)",
    )
    # simulation: attitude dR/dt = Ω(ω) R with ω from (4.47), M = 0; L^O = R^T J ω is fixed
    Jn = np.array([1.0, 2.0, 2.5])

    def rhs(_t, y):
        Rm, wn = y[:9].reshape(3, 3), y[9:]
        Om = np.array([[0, wn[2], -wn[1]], [-wn[2], 0, wn[0]], [wn[1], -wn[0], 0]])
        wdot_n = np.array(
            [
                -(Jn[2] - Jn[1]) * wn[1] * wn[2] / Jn[0],
                -(Jn[0] - Jn[2]) * wn[2] * wn[0] / Jn[1],
                -(Jn[1] - Jn[0]) * wn[0] * wn[1] / Jn[2],
            ]
        )
        return np.concatenate([(Om @ Rm).ravel(), wdot_n])

    y0 = np.concatenate([np.eye(3).ravel(), [0.3, 1.0, -0.4]])
    sol = solve_ivp(
        rhs, (0, 20.0), y0, method="DOP853", rtol=SIM_RTOL, atol=1e-14, dense_output=True
    )
    L_O = np.array(
        [sol.sol(tt)[:9].reshape(3, 3).T @ (Jn * sol.sol(tt)[9:]) for tt in (0, 7.0, 20.0)]
    )
    d.confirm(
        L_O - L_O[0],
        np.zeros((3, 3)),
        atol=SIM_ATOL,
        route="scipy: attitude integrated with (4.47) and M = 0 keeps L = ^O R^A J ω fixed in space",
    )
    Jbad = Jn[[1, 0, 2]]  # a wrong inertia in the attitude's L shows the route can fail

    L_bad = np.array(
        [sol.sol(tt)[:9].reshape(3, 3).T @ (Jbad * sol.sol(tt)[9:]) for tt in (0, 20.0)]
    )
    d.note(
        "control: with J1, J2 swapped in L the 'conserved' L moves by "
        f"{float(np.max(np.abs(L_bad[1] - L_bad[0]))):.2g}"
    )


# ------------------------------------------------------------------ physical pendulum


def _pendulum_rhs(J, mm, gg, hh):
    return lambda _t, y: [y[1], -mm * gg * hh * np.sin(y[0]) / J]


def _simulated_period(J, mm, gg, hh, theta_0) -> float:
    """Twice the time between successive downward zero crossings... the time to the first
    upward crossing of φ̇ = 0 after release is half a period."""

    def turn(_t, y):
        return y[1]

    turn.direction = 1
    turn.terminal = True
    sol = solve_ivp(
        _pendulum_rhs(J, mm, gg, hh),
        (0, 100.0),
        [theta_0, 0.0],
        method="DOP853",
        rtol=SIM_RTOL,
        atol=1e-14,
        events=turn,
    )
    return 2 * float(sol.t_events[0][0])


@check(
    "eq4.52",
    "The physical pendulum: J_z φ̈ = −m g h sin φ, ω0 = √(g/ℓ), T_p = 2π √(J_z/(m g h))",
    kind="proof",
    covers=("eq4.48", "eq4.50", "eq4.51", "eq4.52"),
    defines=("eq4.49",),
    statement="gravity at G = h(sin φ, −cos φ, 0) gives M_z = −m g h sin φ, so J_z φ̈ = −m g h "
    "sin φ (4.48); with ℓ = J_z/(m h) (4.49) φ̈ = −(g/ℓ) sin φ (4.50); for small φ the angular "
    "frequency is √(g/ℓ) (4.51) and the period 2π √(ℓ/g) = 2π √(J_z/(m g h)) (4.52)",
)
def physical_pendulum(d: Derivation) -> None:
    r_G = h * vec(sp.sin(phi), -sp.cos(phi), 0)
    M_z = cross(r_G, vec(0, -m * g, 0))[2]
    d.prove_equal(M_z, -m * g * h * sp.sin(phi), strategy="expand", claim="M_z = −m g h sin φ")
    d.reject(M_z, m * g * h * sp.sin(phi), strategy="expand", claim="M_z = +m g h sin φ")
    L_z = cross(r_G, m * sp.diff(r_G, phi) * phidot)[2]
    d.prove_equal(
        L_z,
        m * h**2 * phidot,
        strategy="trigsimp",
        claim="a particle at G contributes m h² φ̇ to L_z: J_z = Σ m ρ² is the axis moment",
    )
    phiddot_448 = -m * g * h * sp.sin(phi) / J_z
    ell_449 = J_z / (m * h)
    d.prove_equal(
        phiddot_448, -(g / ell_449) * sp.sin(phi), strategy="cancel", claim="(4.48) → (4.50)"
    )
    # small oscillations: φ = A cos(ω0 t) solves the linearised (4.50) iff ω0² = g/ℓ
    A, w0 = sp.Symbol("A", positive=True), sp.Symbol("omega_0", positive=True)
    lin = sp.diff(A * sp.cos(w0 * t), t, 2) + (g / ell) * A * sp.cos(w0 * t)
    d.prove_equal(lin.subs(w0, sp.sqrt(g / ell)), 0, strategy="expand", claim="(4.51): ω0 = √(g/ℓ)")
    d.reject(lin.subs(w0, sp.sqrt(ell / g)), 0, strategy="expand", claim="ω0 = √(ℓ/g)")
    d.prove_equal(
        sp.series(sp.sin(phi), phi, 0, 3).removeO(), phi, strategy="expand", claim="sin φ ≈ φ"
    )
    T_p = 2 * sp.pi / sp.sqrt(g / ell_449)
    d.prove_equal(T_p**2, (2 * sp.pi) ** 2 * J_z / (m * g * h), strategy="cancel", claim="(4.52)")
    pt = {J_z: sp.Rational(4, 3), m: 2, g: sp.Rational(981, 100), h: sp.Rational(1, 2)}
    T_exact = float(sp.N(T_p.subs(pt), 30))
    d.confirm(
        dyn.pendulum_small_period(4 / 3, 2.0, 9.81, 0.5),
        T_exact,
        atol=CODE_ATOL * T_exact,
        route="mechanics.pendulum_small_period",
    )
    theta_0 = 1e-3
    # the exact period is T0 (1 + θ0²/16 + O(θ0⁴)): at θ0 = 1e-3 the correction is 6.25e-8
    T_sim = _simulated_period(4 / 3, 2.0, 9.81, 0.5, theta_0)
    d.confirm(
        T_sim,
        T_exact * (1 + theta_0**2 / 16),
        atol=SIM_ATOL * T_exact,
        route="scipy: the simulated (4.48) at amplitude 1e-3 has the period T_p (1 + θ0²/16)",
    )
    d.confirm(
        dyn.pendulum_period(4 / 3, 2.0, 9.81, 0.5, 2.0),
        _simulated_period(4 / 3, 2.0, 9.81, 0.5, 2.0),
        atol=SIM_ATOL * T_exact,
        route="scipy: at amplitude 2 rad the simulated (4.48) period equals "
        "mechanics.pendulum_period (4K(sin²1)/ω0)",
    )


@check(
    "eq4.56",
    "The smallest pendulum period: h_min = d_Gz, T_p = 2π √(2 d_Gz/g)",
    kind="proof",
    covers=("eq4.54", "eq4.55", "eq4.56"),
    statement="J_z = m d_Gz² + m h² (4.54) gives T_p(h) = 2π √((d_Gz² + h²)/(g h)) (4.55), "
    "infinite as h → 0 and h → ∞, least at h = d_Gz with T_p = 2π √(2 d_Gz/g) (4.56)",
)
def minimum_period(d: Derivation) -> None:
    d_G = sp.Symbol("d_Gz", positive=True)
    J_axis = m * d_G**2 + m * h**2  # (4.54), the parallel-axis theorem (4.40)
    T2 = (2 * sp.pi) ** 2 * J_axis / (m * g * h)
    d.prove_equal(
        T2, (2 * sp.pi) ** 2 * (d_G**2 + h**2) / (g * h), strategy="cancel", claim="(4.55)"
    )
    T = 2 * sp.pi * sp.sqrt((d_G**2 + h**2) / (g * h))
    d.prove_equal(sp.limit(1 / T, h, 0, "+"), 0, strategy="expand", claim="1/T_p → 0 as h → 0")
    d.prove_equal(sp.limit(1 / T, h, sp.oo), 0, strategy="expand", claim="1/T_p → 0 as h → ∞")
    dT2 = sp.diff(T2, h)
    d.prove_equal(dT2.subs(h, d_G), 0, strategy="cancel", claim="dT_p²/dh = 0 at h = d_Gz")
    d.reject(dT2.subs(h, d_G / 2), 0, strategy="cancel", claim="the minimum at h = d_Gz/2")
    d.prove_equal(
        dT2,
        4 * sp.pi**2 * (h**2 - d_G**2) / (g * h**2),
        strategy="cancel",
        claim="dT_p²/dh has the sign of h² − d_Gz²: a single minimum",
    )
    d.prove_equal(
        T.subs(h, d_G) ** 2, (2 * sp.pi) ** 2 * 2 * d_G / g, strategy="cancel", claim="(4.56)"
    )
    d.reject(
        T.subs(h, d_G) ** 2, (2 * sp.pi) ** 2 * d_G / g, strategy="cancel", claim="T = 2π√(d/g)"
    )
    dn, mn, gn = 0.3, 2.0, 9.81
    res = minimize_scalar(
        lambda hh: dyn.pendulum_small_period(mn * (dn**2 + hh**2), mn, gn, hh),
        bounds=(0.01, 3.0),
        method="bounded",
        options={"xatol": 1e-10},
    )
    # the minimum is quadratic: T(h) − T_min ~ eps·T puts h within √eps·d of d_Gz
    d.confirm(
        res.x, dn, atol=2**-24 * dn * 8, route="scipy: minimising mechanics' period gives h = d_Gz"
    )
    d.confirm(
        res.fun,
        2 * np.pi * np.sqrt(2 * dn / gn),
        atol=CODE_ATOL,
        route="scipy: the least period of mechanics.pendulum_small_period is (4.56)",
    )


@check(
    "eq4.57",
    "Energy of the physical pendulum is conserved",
    kind="proof",
    covers=("eq4.57", "eq4.74"),
    statement="½ J_z φ̇² − m g h cos φ = E (4.57) is constant along (4.48); so is E of (4.74), "
    "½ J_z φ̇² + m g h (1 − cos φ), which differs by the constant m g h",
)
def pendulum_energy(d: Derivation) -> None:
    (f,) = functions_of_time("phi")
    E_457 = J_z * f.diff(t) ** 2 / 2 - m * g * h * sp.cos(f)
    E_474 = J_z * f.diff(t) ** 2 / 2 + m * g * h * (1 - sp.cos(f))
    eom = {f.diff(t, 2): -m * g * h * sp.sin(f) / J_z}
    d.prove_equal(E_457.diff(t).subs(eom), 0, strategy="expand", claim="dE/dt = 0 along (4.48)")
    d.reject(
        (J_z * f.diff(t) ** 2 / 2 + m * g * h * sp.cos(f)).diff(t).subs(eom),
        0,
        strategy="expand",
        claim="½ J_z φ̇² + m g h cos φ is conserved",
    )
    d.prove_equal(E_474 - E_457, m * g * h, strategy="expand", claim="(4.74) = (4.57) + m g h")
    sol = solve_ivp(
        _pendulum_rhs(4 / 3, 2.0, 9.81, 0.5),
        (0, 10.0),
        [2.5, 0.0],
        method="DOP853",
        rtol=SIM_RTOL,
        atol=1e-14,
    )
    E_n = 0.5 * 4 / 3 * sol.y[1] ** 2 - 2.0 * 9.81 * 0.5 * np.cos(sol.y[0])
    d.confirm(
        E_n - E_n[0], np.zeros_like(E_n), atol=SIM_ATOL * 10, route="scipy: E constant along (4.48)"
    )
    w_end = abs(sol.y[1, -1])
    d.confirm(
        dyn.pendulum_angular_velocity_at(sol.y[0, -1], 4 / 3, 2.0, 9.81, 0.5, 2.5),
        w_end,
        atol=SIM_ATOL * 10,
        route="mechanics.pendulum_angular_velocity_at (energy) equals the simulated |φ̇|",
    )


# --------------------------------------------------------------------- axis reaction


@check(
    "eq4.76",
    "The reaction from the axis of the physical pendulum, R_ρ(φ) and R_φ(φ)",
    kind="proof",
    covers=(
        "eq4.67",
        "eq4.68",
        "eq4.69",
        "eq4.70",
        "eq4.71",
        "eq4.72",
        "eq4.73",
        "eq4.75",
        "eq4.76",
        "eq4.77",
    ),
    defines=("eq4.66",),
    statement="m r̈_G = F^a + R (4.66)-(4.69); r̈_G = −h φ̇² e_ρ + h φ̈ e_φ (4.70), so R_ρ = "
    "−m h φ̇² − F^a_ρ, R_φ = m h φ̈ − F^a_φ (4.71); with gravity (4.72), φ̈ (4.73) and φ̇² "
    "(4.75): R_ρ = (2mh/J_z)(mgh − E) − (1 + 2mh²/J_z) m g cos φ (4.76), R_φ = (1 − m h²/J_z) "
    "m g sin φ (4.77)",
)
def axis_reaction(d: Derivation) -> None:
    (f,) = functions_of_time("phi")
    e_rho = vec(sp.sin(f), -sp.cos(f), 0)  # from the axis toward G, φ from the downward vertical
    e_phi = vec(sp.cos(f), sp.sin(f), 0)
    r_G = h * e_rho + vec(0, 0, sp.Symbol("z_G", real=True))
    a_G = r_G.diff(t, 2)
    F_a = vec(*sp.symbols("F_x F_y F_z", real=True))
    R_cart = m * a_G - F_a  # (4.66)-(4.69)
    d.prove_equal(R_cart[2], -F_a[2], strategy="expand", claim="(4.69): R_z = −F^a_z")
    d.prove_equal(
        a_G,
        -h * f.diff(t) ** 2 * e_rho + h * f.diff(t, 2) * e_phi,
        strategy="expand",
        claim="(4.70): r̈_G = −h φ̇² e_ρ + h φ̈ e_φ",
    )
    d.reject(
        a_G,
        h * f.diff(t) ** 2 * e_rho + h * f.diff(t, 2) * e_phi,
        strategy="expand",
        claim="(4.70) with a centrifugal + h φ̇² e_ρ",
    )
    F_rho, F_phi = sp.symbols("F_rho F_phi", real=True)
    F_polar = F_rho * e_rho + F_phi * e_phi
    R_polar = m * a_G - F_polar
    d.prove_equal(
        vec((R_polar.T * e_rho)[0], (R_polar.T * e_phi)[0]),
        vec(-m * h * f.diff(t) ** 2 - F_rho, m * h * f.diff(t, 2) - F_phi),
        strategy="trigsimp",
        claim="(4.71): R_ρ = −m h φ̇² − F^a_ρ, R_φ = m h φ̈ − F^a_φ",
    )
    grav = m * vec(0, -g, 0)
    d.prove_equal(
        grav,
        m * g * (sp.cos(f) * e_rho - sp.sin(f) * e_phi),
        strategy="trigsimp",
        claim="(4.72): m g = m g (cos φ e_ρ − sin φ e_φ)",
    )
    E = sp.Symbol("E", real=True)
    phiddot_473 = -m * g * h * sp.sin(phi) / J_z  # (4.73), from (4.48)
    phidot2_475 = 2 / J_z * (E - m * g * h * (1 - sp.cos(phi)))
    d.prove_equal(
        (J_z * phidot**2 / 2 + m * g * h * (1 - sp.cos(phi))).subs(phidot**2, phidot2_475),
        E,
        strategy="expand",
        claim="(4.75) solves (4.74) for φ̇²",
    )
    R_rho = -m * h * phidot2_475 - m * g * sp.cos(phi)
    R_phi = m * h * phiddot_473 + m * g * sp.sin(phi)
    R_476 = 2 * m * h / J_z * (m * g * h - E) - (1 + 2 * m * h**2 / J_z) * m * g * sp.cos(phi)
    R_477 = (1 - m * h**2 / J_z) * m * g * sp.sin(phi)
    d.quantity("R_rho", R_476)
    d.quantity("R_phi", R_477)
    d.prove_equal(R_rho, R_476, strategy="expand", claim="(4.76)")
    d.prove_equal(R_phi, R_477, strategy="expand", claim="(4.77)")
    d.reject(
        R_rho,
        2 * m * h / J_z * (m * g * h - E) - (1 + m * h**2 / J_z) * m * g * sp.cos(phi),
        strategy="expand",
        claim="(4.76) with 1 + m h²/J_z",
    )
    # a second route: the Cartesian (4.67)-(4.68) with gravity, then projected
    sub = {f.diff(t, 2): phiddot_473, f.diff(t): sp.sqrt(phidot2_475), f: phi}
    R_c = (m * a_G - grav).subs(sub)
    e_r, e_p = e_rho.subs(f, phi), e_phi.subs(f, phi)
    d.confirm_exact(
        vec((R_c.T * e_r)[0], (R_c.T * e_p)[0]),
        vec(R_476, R_477),
        strategy="trigsimp",
        route="Cartesian components (4.67)-(4.68) projected on e_ρ, e_φ",
    )
    pt = {
        m: 2,
        g: sp.Rational(981, 100),
        h: sp.Rational(1, 2),
        J_z: sp.Rational(4, 3),
        phi: 1,
        E: 12,
    }
    d.confirm(
        dyn.pendulum_axis_reaction(1.0, 4 / 3, 2.0, 9.81, 0.5, E=12.0),
        [float(R_476.subs(pt)), float(R_477.subs(pt))],
        atol=CODE_ATOL * 20,
        route="mechanics.pendulum_axis_reaction equals (4.76)-(4.77)",
    )
    pd2, pdd = float(phidot2_475.subs(pt)), float(phiddot_473.subs(pt))
    d.confirm(
        dyn.axis_reaction(
            2.0,
            0.5,
            np.sqrt(pd2),
            pdd,
            F_a_rho=2 * 9.81 * np.cos(1.0),
            F_a_phi=-2 * 9.81 * np.sin(1.0),
        ),
        [float(R_476.subs(pt)), float(R_477.subs(pt))],
        atol=CODE_ATOL * 20,
        route="mechanics.axis_reaction with the φ̇, φ̈ of (4.73), (4.75)",
    )


# ------------------------------------------------------------------ bearing reactions


def _particle_reactions(mk, rk, phidot_n, phiddot_n, z_A, F_a, M_a):
    """R1 (at A = (0, 0, z_A)) and R2 (at O) on a rigid particle body turning about e_z,
    from Σ m a = F_a + R1 + R2 and Σ r × m a = M_a + r_A × R1 (x, y components) at the
    instant when body and space axes coincide; the axial force goes to O."""
    w = np.array([0.0, 0.0, phidot_n])
    al = np.array([0.0, 0.0, phiddot_n])
    acc = np.cross(al, rk) + np.cross(w, np.cross(w, rk))
    P = (mk[:, None] * acc).sum(axis=0)
    H = (np.cross(rk, mk[:, None] * acc)).sum(axis=0)
    rhs = H - M_a  # = r_A × R1 = (−z_A R1y, z_A R1x, 0)
    R1 = np.array([rhs[1] / z_A, -rhs[0] / z_A, 0.0])
    return R1, P - F_a - R1


@check(
    "eq4.85",
    "Reaction forces at two bearings of a body turning about a fixed axis",
    kind="proof",
    covers=(
        "eq4.78",
        "eq4.79",
        "eq4.80",
        "eq4.81",
        "eq4.82",
        "eq4.83",
        "eq4.84",
        "eq4.85",
    ),
    statement="body axes with G = (h, 0, z_G), ω = φ̇ e_z: R1 + R2 = m a_G − F^a (4.78); L = "
    "(−D_xz φ̇, −D_yz φ̇, J_z φ̇) (4.79); L̇_x = −D_xz φ̈ + D_yz φ̇², L̇_y = −D_yz φ̈ − D_xz φ̇² "
    "(4.80)-(4.81); M = M^a + z_A e_z × R1 (4.82)-(4.83); R1_y = (D_xz φ̈ − D_yz φ̇² + M^a_x)/z_A "
    "(4.84), R1_x = −(D_yz φ̈ + D_xz φ̇² + M^a_y)/z_A (4.85)",
)
def bearing_reactions(d: Derivation) -> None:
    J_x, J_y = sp.symbols("J_x J_y", positive=True)
    D_xy, D_xz, D_yz = sp.symbols("D_xy D_xz D_yz", real=True)
    J = sp.Matrix([[J_x, -D_xy, -D_xz], [-D_xy, J_y, -D_yz], [-D_xz, -D_yz, J_z]])
    (f,) = functions_of_time("phi")
    w = vec(0, 0, f.diff(t))
    L = J * w
    d.prove_equal(
        L,
        vec(-D_xz * f.diff(t), -D_yz * f.diff(t), J_z * f.diff(t)),
        strategy="expand",
        claim="(4.79)",
    )
    Ldot = L.diff(t) + cross(w, L)  # (4.44), body axes: J constant
    d.prove_equal(
        Ldot[0], -D_xz * f.diff(t, 2) + D_yz * f.diff(t) ** 2, strategy="expand", claim="(4.80)"
    )
    d.prove_equal(
        Ldot[1], -D_yz * f.diff(t, 2) - D_xz * f.diff(t) ** 2, strategy="expand", claim="(4.81)"
    )
    d.reject(
        Ldot[0],
        -D_xz * f.diff(t, 2) - D_yz * f.diff(t) ** 2,
        strategy="expand",
        claim="(4.80) with − D_yz φ̇²",
    )
    z_A = sp.Symbol("z_A", positive=True)
    R1 = vec(*sp.symbols("R_1x R_1y R_1z", real=True))
    M_a = vec(*sp.symbols("M_x^a M_y^a M_z^a", real=True))
    M_tot = M_a + cross(z_A * ez, R1)
    d.prove_equal(M_tot[0], M_a[0] - z_A * R1[1], strategy="expand", claim="(4.82)")
    d.prove_equal(M_tot[1], M_a[1] + z_A * R1[0], strategy="expand", claim="(4.83)")
    sol = sp.solve([Ldot[0] - M_tot[0], Ldot[1] - M_tot[1]], [R1[0], R1[1]], dict=True)[0]
    R1y_484 = (D_xz * f.diff(t, 2) - D_yz * f.diff(t) ** 2 + M_a[0]) / z_A
    R1x_485 = -(D_yz * f.diff(t, 2) + D_xz * f.diff(t) ** 2 + M_a[1]) / z_A
    d.prove_equal(sol[R1[1]], R1y_484, strategy="cancel", claim="(4.84)")
    d.prove_equal(sol[R1[0]], R1x_485, strategy="cancel", claim="(4.85)")
    d.reject(
        sol[R1[0]],
        -(D_yz * f.diff(t, 2) - D_xz * f.diff(t) ** 2 + M_a[1]) / z_A,
        strategy="cancel",
        claim="(4.85) with − D_xz φ̇²",
    )
    z_G = sp.Symbol("z_G", real=True)
    r_G = vec(h, 0, z_G)
    a_G = cross(f.diff(t, 2) * ez, r_G) + cross(w, cross(w, r_G))
    F_a = vec(*sp.symbols("F_x^a F_y^a F_z^a", real=True))
    d.prove_equal(
        (m * a_G - F_a)[:2, 0],
        vec(-m * h * f.diff(t) ** 2 - F_a[0], m * h * f.diff(t, 2) - F_a[1]),
        strategy="expand",
        claim="(4.78): R1 + R2 in body axes, G in the xz-plane",
    )
    d.note(
        "balanced: h = 0 makes R1 + R2 = −F^a; D_xz = D_yz = 0 as well (the axis principal) "
        "leaves R1 = (−M^a_y, M^a_x, ·)/z_A, independent of the rotation"
    )
    # numeric: mechanics and an independent particle model of the body
    rng = np.random.default_rng(4)
    mk = rng.uniform(0.5, 2.0, 5)
    rk = rng.uniform(-1.0, 1.0, (5, 3))
    J_O = inr.inertia_tensor(mk, rk, about=np.zeros(3))
    G_n = (mk[:, None] * rk).sum(axis=0) / mk.sum()
    F_n, M_n = np.array([0.3, -1.2, -9.0]), np.array([0.5, 0.25, -0.1])
    R1_m, R2_m = dyn.bearing_reactions(J_O, mk.sum(), G_n, 3.0, -1.5, 1.75, F_a=F_n, M_a=M_n)
    R1_p, R2_p = _particle_reactions(mk, rk, 3.0, -1.5, 1.75, F_n, M_n)
    R2_p[2] = -F_n[2]
    d.confirm(
        np.concatenate([R1_m, R2_m]),
        np.concatenate([R1_p, R2_p]),
        atol=CODE_ATOL * 20,
        route="mechanics.bearing_reactions equals the force and moment balance of a 5-particle "
        "body (Σ m a, Σ r × m a at the instant)",
    )
    pt = {
        D_xz: float(-J_O[0, 2]),
        D_yz: float(-J_O[1, 2]),
        z_A: 1.75,
        M_a[0]: 0.5,
        M_a[1]: 0.25,
    }
    der = {f.diff(t, 2): -1.5, f.diff(t): 3.0}
    d.confirm(
        [float(R1x_485.subs(der).subs(pt)), float(R1y_484.subs(der).subs(pt))],
        R1_p[:2],
        atol=CODE_ATOL * 20,
        route="(4.84)-(4.85) evaluated with the particle body's D_xz, D_yz equal its force balance",
    )
