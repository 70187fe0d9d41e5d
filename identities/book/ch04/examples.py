"""Chapter 4 worked examples: 4.1 (four particles with any inertia tensor), 4.2 (the
tensor in a basis turned about e3), 4.3 (the period of a rod pendulum), 4.4 (a rod
released horizontally), 4.5 (a cylinder rolling in a cylindrical track).

Each is re-derived from the book's definitions and compared with the printed results,
and confirmed through :mod:`mechanics` or a scipy simulation.
"""

from __future__ import annotations

import numpy as np
import sympy as sp
from scipy.integrate import solve_ivp

from identities.book.ch04.inertia import book_matrix, system_J
from identities.verify.catalogue import check
from identities.verify.proof import Derivation
from identities.verify.symbolic import R3, floats, functions_of_time, t, vec
from mechanics import dynamics as dyn
from mechanics import inertia as inr
from mechanics import rotation as rot
from mechanics._floats import EPS

#: mechanics against a float evaluation of the same exact value (a few products, sums and one
#: square root or one Jacobi pass on an O(1) tensor): 64 eps.
CODE_ATOL = 64 * EPS
#: solve_ivp (DOP853) with rtol = 1e-12 over a few periods of O(1) motion: global error below
#: ~1e-10; 2^20 eps ≈ 2.3e-10 (relative, multiplied by the size of the compared quantity).
SIM_RTOL = 2**20 * EPS

m, g, l = sp.symbols("m g l", positive=True)
a, b, c = sp.symbols("a b c", positive=True)
J_x, J_y, J_z = sp.symbols("J_x J_y J_z", positive=True)


@check(
    "E4.1",
    "Example 4.1: four particles of mass m/4 realise any inertia tensor",
    kind="derivation",
    covers=(
        "E4.1",
        "eq4.15",
        "eq4.16",
        "eq4.17",
        "eq4.18",
        "eq4.19",
        "eq4.20",
        "eq4.21",
        "eq4.22",
        "eq4.23",
        "eq4.24",
        "eq4.25",
        "eq4.26",
        "eq4.27",
        "eq4.28",
        "eq4.29",
    ),
    statement="particles m/4 at (±a, 0, c), (0, ±b, −c) (4.15)-(4.18) have D = 0 (4.19)-(4.21), "
    "J_x = m(b² + 2c²)/2, J_y = m(a² + 2c²)/2, J_z = m(a² + b²)/2 (4.22)-(4.25), hence "
    "(4.26)-(4.29); a = b = √2 c gives a regular tetrahedron and a spherical tensor; three "
    "particles are planar, so J_x + J_y = J_z",
)
def example_4_1(d: Derivation) -> None:
    pos = [vec(a, 0, c), vec(-a, 0, c), vec(0, b, -c), vec(0, -b, -c)]  # (4.15)-(4.18)
    masses = [m / 4] * 4
    J = book_matrix(masses, pos)
    d.prove_equal(
        vec(-J[0, 1], -J[0, 2], -J[1, 2]), vec(0, 0, 0), strategy="expand", claim="(4.19)-(4.21)"
    )
    printed = [
        m / 4 * (2 * b**2 + 4 * c**2),
        m / 4 * (2 * a**2 + 4 * c**2),
        m / 4 * (2 * a**2 + 2 * b**2),
    ]
    d.prove_equal(
        vec(J[0, 0], J[1, 1], J[2, 2]), vec(*printed), strategy="expand", claim="(4.22)-(4.24)"
    )
    p425 = [m / 2 * (b**2 + 2 * c**2), m / 2 * (a**2 + 2 * c**2), m / 2 * (a**2 + b**2)]
    d.prove_equal(vec(*printed), vec(*p425), strategy="expand", claim="(4.25)")
    Jx, Jy, Jz = p425
    d.prove_equal(Jx + Jy - Jz, 2 * m * c**2, strategy="expand", claim="(4.26)")
    d.prove_equal(Jz + Jx - Jy, m * b**2, strategy="expand", claim="(4.27)")
    d.prove_equal(Jz - Jx + Jy, m * a**2, strategy="expand", claim="(4.28)")
    d.reject(Jz + Jx - Jy, m * b**2 / 2, strategy="expand", claim="(4.27) with m b²/2")
    sol = {
        a: sp.sqrt((J_z - J_x + J_y) / m),
        b: sp.sqrt((J_z + J_x - J_y) / m),
        c: sp.sqrt((J_x + J_y - J_z) / (2 * m)),
    }  # (4.29)
    d.prove_equal(
        J.subs(sol),
        sp.diag(J_x, J_y, J_z),
        strategy="expand",
        claim="(4.29) realises diag(J_x, J_y, J_z)",
    )
    d.reject(
        J.subs({**sol, c: sp.sqrt((J_x + J_y - J_z) / m)}),
        sp.diag(J_x, J_y, J_z),
        strategy="expand",
        claim="(4.29) with c = √((J_x + J_y − J_z)/m)",
    )
    tet = {a: sp.sqrt(2) * c, b: sp.sqrt(2) * c}
    d.prove_equal(J.subs(tet), J[2, 2].subs(tet) * sp.eye(3), strategy="expand", claim="spherical")
    dists = [
        ((pos[i] - pos[j]).T * (pos[i] - pos[j]))[0].subs(tet) for i in range(4) for j in range(i)
    ]
    d.prove_equal(
        vec(*dists), vec(*[8 * c**2] * 6), strategy="expand", claim="a regular tetrahedron"
    )
    three = [vec(*sp.symbols(f"x{k} y{k}", real=True), 0) for k in range(3)]
    J3 = system_J(sp.symbols("m_1:4", positive=True), three)
    d.prove_equal(
        J3[0, 0] + J3[1, 1], J3[2, 2], strategy="expand", claim="three particles: J_x + J_y = J_z"
    )
    # mechanics: realise a general (rotated) tensor and rebuild it
    Jn = inr.rotate_inertia(np.diag([1.0, 2.0, 2.5]), rot.matrix_from_rotvec([0.4, -0.3, 1.1]))
    mk, rk = inr.four_particle_realisation(3.0, Jn)
    d.confirm(
        inr.inertia_tensor(mk, rk, about=np.zeros(3)),
        Jn,
        atol=CODE_ATOL,
        route="mechanics.four_particle_realisation → inertia_tensor about G gives J back",
    )
    pt = {J_x: 1, J_y: 2, J_z: sp.Rational(5, 2), m: 3}
    mk, rk = inr.four_particle_realisation(3.0, np.diag([1.0, 2.0, 2.5]))
    d.confirm(
        rk,
        np.array([floats(p.subs(sol), pt).ravel() for p in pos]),
        atol=CODE_ATOL,
        route="mechanics.four_particle_realisation positions are (4.15)-(4.18) with (4.29)",
    )


@check(
    "E4.2",
    "Example 4.2: the inertia tensor in a basis turned by ψ about e3",
    kind="derivation",
    covers=("E4.2", "eq4.30", "eq4.31"),
    statement="J^O = ^O R^A J' ^A R^O with ^A R^O = R3(ψ) is (4.30); D^O_xy = −cos ψ sin ψ "
    "(J'_x − J'_y) (4.31), zero for a symmetric top",
)
def example_4_2(d: Derivation) -> None:
    psi = sp.Symbol("psi", real=True)
    Jp = sp.diag(J_x, J_y, J_z)
    C, S = sp.cos(psi), sp.sin(psi)
    R_O_A_printed = sp.Matrix([[C, -S, 0], [S, C, 0], [0, 0, 1]])
    d.prove_equal(R_O_A_printed, R3(psi).T, strategy="expand", claim="the printed ^O R^A is R3(ψ)ᵀ")
    J_O = R3(psi).T * Jp * R3(psi)
    printed = sp.Matrix(
        [
            [C**2 * J_x + S**2 * J_y, C * S * (J_x - J_y), 0],
            [C * S * (J_x - J_y), S**2 * J_x + C**2 * J_y, 0],
            [0, 0, J_z],
        ]
    )
    d.prove_equal(J_O, printed, strategy="expand", claim="(4.30)")
    d.reject(
        R3(psi) * Jp * R3(psi).T, printed, strategy="expand", claim="(4.30) with R and Rᵀ swapped"
    )
    D_xy = -J_O[0, 1]  # J_xy = −D_xy (4.6)
    d.quantity("D_xy", D_xy)
    d.prove_equal(D_xy, -C * S * (J_x - J_y), strategy="expand", claim="(4.31)")
    d.prove_equal(D_xy.subs(J_y, J_x), 0, strategy="expand", claim="symmetric top: D_xy ≡ 0")
    R_n = floats(R3(psi), {psi: sp.Rational(7, 10)})
    d.confirm(
        inr.rotate_inertia(np.diag([1.0, 2.0, 2.5]), R_n),
        floats(printed, {psi: sp.Rational(7, 10), J_x: 1, J_y: 2, J_z: sp.Rational(5, 2)}),
        atol=CODE_ATOL,
        route="mechanics.rotate_inertia(diag, R3(0.7)) equals (4.30)",
    )


@check(
    "E4.3",
    "Example 4.3: a rod swinging about its end has T = 2π √(2l/(3g)), like a pendulum of 2l/3",
    kind="derivation",
    covers=("E4.3", "eq4.53"),
    statement="J_z = m l²/3, h = l/2 in (4.52): T = 2π √(2l/(3g)) (4.53); a simple pendulum "
    "of length 2l/3 has the same period, whatever the mass",
)
def example_4_3(d: Derivation) -> None:
    J_end = m * l**2 / 12 + m * (l / 2) ** 2  # rod about G (catalogue) moved by (4.40)
    d.prove_equal(J_end, m * l**2 / 3, strategy="expand", claim="J_z = m l²/3 about the end")
    T = 2 * sp.pi * sp.sqrt(J_end / (m * g * l / 2))
    d.quantity("T", T)
    d.prove_equal(T**2, (2 * sp.pi) ** 2 * 2 * l / (3 * g), strategy="expand", claim="(4.53)")
    d.reject(T**2, (2 * sp.pi) ** 2 * l / (3 * g), strategy="expand", claim="T = 2π√(l/(3g))")
    ell = J_end / (m * l / 2)  # (4.49)
    d.quantity("ell", ell)
    d.prove_equal(ell, 2 * l / 3, strategy="expand", claim="the equivalent length 2l/3, no m")
    J_n = inr.parallel_axis(inr.rod(2.0, 1.2), 2.0, [0.0, 0.0, 0.6], allow_singular=True)[0, 0]
    T_ref = float(T.subs({m: 2, l: sp.Rational(6, 5), g: sp.Rational(981, 100)}))
    d.confirm(
        dyn.pendulum_small_period(J_n, 2.0, 9.81, 0.6),
        T_ref,
        atol=CODE_ATOL * T_ref,
        route="mechanics: parallel_axis(rod) about the end, then pendulum_small_period",
    )
    d.confirm(
        dyn.reduced_length(J_n, 2.0, 0.6), 0.8, atol=CODE_ATOL, route="mechanics.reduced_length"
    )


@check(
    "E4.4",
    "Example 4.4: a rod released horizontally passes the vertical with φ̇ = √(3g/l)",
    kind="derivation",
    covers=("E4.4", "eq4.58", "eq4.59"),
    statement="E = 0 from φ(0) = π/2, φ̇(0) = 0 in (4.57); at φ = 0: ½(ml²/3)φ̇² − mg l/2 = 0 "
    "(4.58), φ̇ = √(3g/l) (4.59)",
)
def example_4_4(d: Derivation) -> None:
    w = sp.Symbol("phidot", positive=True)
    J = m * l**2 / 3
    E = lambda p, pd: J * pd**2 / 2 - m * g * l / 2 * sp.cos(p)  # noqa: E731 (4.57)
    d.prove_equal(E(sp.pi / 2, 0), 0, strategy="expand", claim="E = 0")
    eq458 = E(0, w)
    d.prove_equal(
        eq458,
        sp.Rational(1, 2) * (m * l**2 / 3) * w**2 - m * g * l / 2,
        strategy="expand",
        claim="(4.58)",
    )
    sol = sp.solve(eq458, w)
    d.quantity("phidot", sol[0])
    d.prove_equal(sol[0] ** 2, 3 * g / l, strategy="expand", claim="(4.59): φ̇ = √(3g/l)")
    d.reject(sol[0] ** 2, 3 * g / (2 * l), strategy="expand", claim="φ̇ = √(3g/(2l))")
    ln, gn = 1.2, 9.81
    d.confirm(
        dyn.pendulum_angular_velocity_at(0.0, ln**2 / 3, 1.0, gn, ln / 2, np.pi / 2),
        np.sqrt(3 * gn / ln),
        atol=CODE_ATOL,
        route="mechanics.pendulum_angular_velocity_at",
    )

    def bottom(_t, y):
        return y[0]

    bottom.terminal = True
    bottom.direction = -1
    sim = solve_ivp(
        lambda _t, y: [y[1], -1.5 * gn / ln * np.sin(y[0])],
        (0, 10.0),
        [np.pi / 2, 0.0],
        method="DOP853",
        rtol=1e-12,
        atol=1e-14,
        events=bottom,
    )
    d.confirm(
        abs(sim.y_events[0][0][1]),
        np.sqrt(3 * gn / ln),
        atol=SIM_RTOL * np.sqrt(3 * gn / ln),
        route="scipy: (4.48) integrated from the horizontal to the vertical",
    )


@check(
    "E4.5",
    "Example 4.5: a cylinder rolling in a cylindrical track, T_p = π √(6(R − r)/g)",
    kind="derivation",
    covers=("E4.5", "eq4.60", "eq4.61", "eq4.62", "eq4.63", "eq4.64", "eq4.65"),
    statement="Rψ = rφ (4.60), h = (R − r)(1 − cos ψ) (4.61), ω = φ̇ − ψ̇ = (1 − r/R)φ̇ (4.62), "
    "T = ½(3/2 m r²)(1 − r/R)² φ̇² (4.63), E (4.64); small oscillations have T_p = π √(6(R − "
    "r)/g) (4.65), → ∞ as R → ∞",
)
def example_4_5(d: Derivation) -> None:
    r, R = sp.symbols("r R", positive=True)
    (f,) = functions_of_time("phi")
    psi = r * f / R  # (4.60)
    omega = f.diff(t) - psi.diff(t)  # (4.62)
    d.prove_equal(omega, (1 - r / R) * f.diff(t), strategy="expand", claim="(4.62)")
    # second route for ω: the centre moves at (R − r) ψ̇, rolling makes v_G = r ω
    d.confirm_exact(
        (R - r) * psi.diff(t) / r, omega, route="rolling: ω = v_G/r = (R − r)ψ̇/r", strategy="cancel"
    )
    # G on the circle of radius R − r about the track centre, angle ψ from the downward vertical
    G = (R - r) * vec(sp.sin(psi), 1 - sp.cos(psi), 0)  # height measured from the lowest point
    d.prove_equal(G[1], (R - r) * (1 - sp.cos(psi)), strategy="expand", claim="(4.61)")
    J_C = m * r**2 + m * r**2 / 2  # about the contact line: (4.40) with the cylinder's m r²/2
    T_kin = J_C * omega**2 / 2
    d.prove_equal(
        T_kin,
        sp.Rational(1, 2) * (m * r**2 + m * r**2 / 2) * (1 - r / R) ** 2 * f.diff(t) ** 2,
        strategy="expand",
        claim="(4.63)",
    )
    konig = m * (G.diff(t).T * G.diff(t))[0] / 2 + (m * r**2 / 2) * omega**2 / 2
    d.confirm_exact(konig, T_kin, route="König: ½ m v_G² + ½ J_G ω²", strategy="trigsimp")
    E_m = T_kin + m * g * G[1]
    E_464 = sp.Rational(1, 2) * (sp.Rational(3, 2) * m * r**2) * (1 - r / R) ** 2 * f.diff(
        t
    ) ** 2 + m * g * (R - r) * (1 - sp.cos(r * f / R))
    d.prove_equal(E_m, E_464, strategy="expand", claim="(4.64)")
    # differentiate, divide by φ̇: the equation of motion; then sin x ≈ x
    eom = sp.expand(sp.diff(E_m, t) / f.diff(t))
    fdd = sp.solve(eom, f.diff(t, 2))[0]
    lin = sp.diff(fdd, f).subs(f, 0)  # φ̈ = lin · φ for small φ
    w0_sq = sp.cancel(-lin)
    d.quantity("omega_0_squared", w0_sq)
    d.prove_equal(w0_sq, 2 * g / (3 * (R - r)), strategy="cancel", claim="ω0² = 2g/(3(R − r))")
    T_p = 2 * sp.pi / sp.sqrt(w0_sq)
    d.quantity("T_p", T_p)
    d.prove_equal(T_p**2, sp.pi**2 * 6 * (R - r) / g, strategy="cancel", claim="(4.65)")
    d.reject(T_p**2, sp.pi**2 * 3 * (R - r) / g, strategy="cancel", claim="T_p = π √(3(R − r)/g)")
    d.prove_equal(sp.limit(1 / T_p, R, sp.oo), 0, strategy="expand", claim="T_p → ∞ as R → ∞")
    # simulation of the exact equation of motion at a small amplitude
    num = {r: sp.Rational(1, 5), R: 1, g: sp.Rational(981, 100), m: 1}
    acc = sp.lambdify((f, f.diff(t)), fdd.subs(num), "numpy")

    def turn(_t, y):
        return y[1]

    turn.direction = 1
    turn.terminal = True
    sim = solve_ivp(
        lambda _t, y: [y[1], acc(y[0], y[1])],
        (0, 20.0),
        [1e-3, 0.0],
        method="DOP853",
        rtol=1e-12,
        atol=1e-16,
        events=turn,
    )
    T_ref = float(T_p.subs(num))
    # at φ amplitude 1e-3 (ψ = r φ/R = 2e-4) the pendulum-like anharmonic correction of the
    # period is ψ0²/16 ≈ 2.5e-9 relative; allow twice that plus the integration error
    anharmonic = 2 * (float(num[r] / num[R]) * 1e-3) ** 2 / 16
    d.confirm(
        2 * sim.t_events[0][0],
        T_ref,
        atol=(anharmonic + SIM_RTOL) * T_ref,
        route="scipy: the exact energy equation of motion, amplitude 1e-3, has the period (4.65)",
    )
