"""Chapter 6 worked examples: 6.1 (a bouncing ball: weight against the mean impact
force), 6.2 (a bat struck by a ball), 6.3 (compression and restitution impulses).

Each is re-derived from the book's principles and compared with the printed results;
the numbers of Example 6.1 carry their units (``sympy.physics.units``).  Example 6.3
prints ẋ_A(-δ1) in the compression impulse on B (6.44): an erratum.
"""

from __future__ import annotations

import numpy as np
import sympy as sp
from sympy.physics import units as u

from identities.book.ch06.restitution import (
    SIM_RTOL,
    direct_impact_symbolic,
    spring_dashpot_collision,
)
from identities.verify.catalogue import check
from identities.verify.proof import Derivation
from identities.verify.symbolic import cross, vec
from mechanics import impact as imp
from mechanics import kinematics as kin
from mechanics._floats import EPS

#: float evaluation of a few products and quotients of O(1) numbers: 64 eps.
CODE_ATOL = 64 * EPS
#: mechanics.impact's direct-impact functions promise 2 ulps; relative to O(1) results
#: that is ≤ 2 eps, and the reference is a float evaluation of the same closed form
#: (a few more roundings): 16 eps.
DIRECT_ATOL = 16 * EPS

ex, ey, ez = vec(1, 0, 0), vec(0, 1, 0), vec(0, 0, 1)


def _si(q) -> float:
    """The number of a quantity in SI base units (m, kg, s)."""
    q = u.convert_to(q, [u.meter, u.kilogram, u.second])
    return float(q.subs({u.meter: 1, u.kilogram: 1, u.second: 1}))


@check(
    "E6.1",
    "Example 6.1: a bouncing ball, weight against the mean impact force",
    kind="derivation",
    covers=("E6.1", "eq6.7", "eq6.8", "eq6.9", "eq6.10"),
    statement="speed 12 m/s down before, 10 m/s up after, contact τ = 10⁻³ s: "
    "-g + K_av/m = 22·10³ m/s² (6.9) and m g/K_av ≈ 0.4·10⁻³ (6.10)",
    reading="(6.10) neglects g beside 22·10³ m/s²; the exact ratio g/(22·10³ m/s² + g) = "
    "4.457·10⁻⁴ agrees with the printed 0.4·10⁻³ to the one digit printed.",
)
def example_6_1(d: Derivation) -> None:
    tau, m, g = sp.symbols("tau m g", positive=True)
    v_i, v_f, S = sp.symbols("xdot_i xdot_f S", real=True)
    s = sp.Symbol("s", real=True)
    K = S * 6 * s * (1 - s) / tau  # an impact pulse of impulse S, s = (t - t_i)/τ
    # (6.7) m ẍ = -m g + K integrated over [t_i, t_i + τ] (dt = τ ds)
    rhs = sp.integrate((-m * g + K) * tau, (s, 0, 1))
    K_av = S / tau  # (6.6)
    d.prove_equal(rhs, -m * g * tau + K_av * tau, strategy="expand", claim="(6.7) → (6.8)")
    d.reject(rhs, K_av * tau, strategy="expand", claim="(6.8) without the weight's impulse")
    # (6.9): m (ẋ_f - ẋ_i) = -m g τ + K_av τ with the book's numbers
    vel_i, vel_f, tau_n = -12 * u.meter / u.second, 10 * u.meter / u.second, u.second / 1000
    g_n = sp.Rational(981, 100) * u.meter / u.second**2
    K_av_over_m = sp.solve(sp.Eq(v_f - v_i, (-g + sp.Symbol("k")) * tau), sp.Symbol("k"))[0]
    accel = (vel_f - vel_i) / tau_n
    d.quantity("minus_g_plus_Kav_over_m", accel)
    d.prove_equal(
        accel,
        22 * 10**3 * u.meter / u.second**2,
        strategy="expand",
        claim="(6.9): -g + K_av/m = [10 - (-12)]/10⁻³ m/s² = 22·10³ m/s²",
    )
    d.reject(
        _si((vel_f + vel_i) / tau_n),
        22 * 10**3,
        strategy="expand",
        claim="the speeds subtracted without their signs (-2·10³ m/s²)",
    )
    kav_m = K_av_over_m.subs(
        {v_f: 10, v_i: -12, tau: sp.Rational(1, 1000), g: sp.Rational(981, 100)}
    )
    d.quantity("Kav_over_m", kav_m * u.meter / u.second**2)
    ratio = sp.Rational(981, 100) / kav_m  # m g/K_av
    d.quantity("m_g_over_Kav", ratio)
    d.prove_equal(ratio, sp.Rational(981, 2200981), strategy="expand", claim="m g/K_av exactly")
    d.numeric_close(
        float(ratio),
        0.4e-3,
        atol=0.05e-3,  # the printed value has one significant digit: half a unit of it
        claim="(6.10): m g/K_av = 4.457·10⁻⁴ ≈ 0.4·10⁻³ as printed",
    )
    d.reject(ratio, sp.Rational(4, 10**4), strategy="expand", claim="(6.10) as an exact equality")
    # independent route: a ball on a spring–dashpot floor, with its weight, simulated by scipy
    mass = 0.45  # kg; the ratio does not depend on it
    # the simulation's X axis points down, toward the floor (body 2, infinitely heavy): the
    # ball arrives at +12 m/s and its weight is an acceleration +g; back to the book's
    # upward X: ẋ = -x_sim', K = -K_sim
    sim = spring_dashpot_collision(mass, np.inf, -_si(vel_i), 0.0, 10 / 12, _si(tau_n), g=-_si(g_n))
    K_av_sim = -sim["impulse"] / sim["tau"]
    xdot_f_sim = -sim["v1f"]
    d.confirm(
        mass * (xdot_f_sim - _si(vel_i)),
        -mass * _si(g_n) * sim["tau"] + K_av_sim * sim["tau"],
        atol=SIM_RTOL * mass * 12,
        route="scipy: ball with its weight on a spring–dashpot floor obeys (6.8) through the "
        "contact",
    )
    # the weight perturbs the rebound and the contact time by O(g τ/v) ≈ 1e-3 relative
    d.confirm(
        mass * _si(g_n) / K_av_sim,
        float(ratio),
        atol=4 * _si(g_n) * _si(tau_n) / 10 * float(ratio),
        route=f"scipy: the simulated contact gives m g/K_av = {mass * _si(g_n) / K_av_sim:.4e} "
        f"(rebound {xdot_f_sim:.4f} m/s, contact {sim['tau']:.4e} s)",
    )


@check(
    "E6.2",
    "Example 6.2: a bat (a rod) struck at x: energy, the point at rest, the speed of the blow",
    kind="derivation",
    covers=("E6.2", *(f"eq6.{n}" for n in range(23, 35))),
    statement="S e_y = m v_G (6.23), (x - ℓ/2) e_x × S e_y = J_G φ̇ e_z (6.24), J_G = mℓ²/12: "
    "T(x) = S²/(2m)[1 + 12(x/ℓ - 1/2)²] (6.26), x_C = ℓ(3x - 2ℓ)/(3(2x - ℓ)) (6.28), "
    "ẏ_P = (S/m)[1 + 12(x/ℓ - 1/2)(x_P/ℓ - 1/2)] (6.33), largest at x = 0, ℓ (6.34)",
)
def example_6_2(d: Derivation) -> None:
    m, ell, S = sp.symbols("m ell S", positive=True)
    x, x_P, xi = sp.symbols("x x_P xi", real=True)
    v_G, phidot = sp.symbols("v_G phidot", real=True)
    J_G = sp.integrate((xi - ell / 2) ** 2 * m / ell, (xi, 0, ell))
    d.prove_equal(J_G, m * ell**2 / 12, strategy="expand", claim="J_G = ∫ (ξ - ℓ/2)² m/ℓ dξ")
    sol = sp.solve(
        list(S * ey - m * v_G * ey) + list(cross((x - ell / 2) * ex, S * ey) - J_G * phidot * ez),
        [v_G, phidot],
        dict=True,
    )[0]
    vG, w = sol[v_G], sol[phidot]
    d.quantity("v_G", vG)
    d.quantity("phidot", w)
    d.prove_equal(vG, S / m, strategy="expand", claim="(6.23): v_G = S/m")
    d.prove_equal(w, 12 * S * (x - ell / 2) / (m * ell**2), strategy="cancel", claim="(6.24)")
    T = m * vG**2 / 2 + J_G * w**2 / 2  # (6.25)
    T_book = S**2 / (2 * m) * (1 + 12 * (x / ell - sp.Rational(1, 2)) ** 2)
    d.quantity("T", T_book)
    d.prove_equal(T, T_book, strategy="cancel", claim="(6.25) → (6.26)")
    d.reject(
        T,
        S**2 / (2 * m) * (1 + 3 * (x / ell - sp.Rational(1, 2)) ** 2),
        strategy="cancel",
        claim="(6.26) with J = mℓ²/3 (about the end) for J_G",
    )
    d.prove_equal(
        sp.solve(sp.diff(T_book, x), x)[0], ell / 2, strategy="expand", claim="T is least at ℓ/2"
    )
    # (b): the point of the rod (y = 0 line) at rest, (6.27)-(6.31)
    x_C = ell / 2 - vG / w  # (6.27): x_C = x_G - ẏ_G/φ̇
    x_C_book = ell / 3 * (3 * x - 2 * ell) / (2 * x - ell)
    d.quantity("x_C", x_C_book)
    velocity_at_C = vG * ey + cross(w * ez, (x_C - ell / 2) * ex)
    d.prove_equal(
        velocity_at_C, sp.zeros(3, 1), strategy="cancel", claim="(6.27): C has zero velocity"
    )
    d.prove_equal(x_C, x_C_book, strategy="cancel", claim="(6.28)")
    d.reject(x_C, ell / 2 + vG / w, strategy="cancel", claim="(6.27) with + ẏ_G/φ̇")
    d.prove_equal(x_C_book.subs(x, 0), 2 * ell / 3, strategy="cancel", claim="(6.29)")
    d.prove_equal(x_C_book.subs(x, ell / 3), ell, strategy="cancel", claim="(6.30)")
    d.prove_equal(
        sp.cancel(x_C_book * (2 * x - ell)).subs(x, ell / 2),
        -(ell**2) / 6,
        strategy="expand",
        claim="(6.31): x_C has a simple pole at ℓ/2 with (2x - ℓ) x_C → -ℓ²/6 ≠ 0, so "
        "x_C → +∞ as x → ℓ/2 from below and -∞ from above",
    )
    d.prove_equal(
        x_C_book.subs(x, 2 * ell / 5) - ell,
        ell / 3,
        strategy="cancel",
        claim="ℓ/3 < x < ℓ/2 puts C beyond the rod: x_C(2ℓ/5) = 4ℓ/3 > ℓ",
    )
    # (c): velocities along the rod, (6.32)-(6.34)
    v_P = vG * ey + cross((ell / 2 - x_P) * ex, w * ez)  # v_G + PG × ω
    d.prove_equal(v_P, (S / m - (ell / 2 - x_P) * w) * ey, strategy="cancel", claim="(6.32)")
    yP_book = S / m * (1 + 12 * (x / ell - sp.Rational(1, 2)) * (x_P / ell - sp.Rational(1, 2)))
    d.quantity("ydot_P", yP_book)
    d.prove_equal(v_P[1], yP_book, strategy="cancel", claim="(6.33)")
    y_hit = yP_book.subs(x_P, x)
    d.quantity("ydot_impact_point", y_hit)
    d.prove_equal(
        y_hit,
        S / m * (1 + 12 * (x / ell - sp.Rational(1, 2)) ** 2),
        strategy="cancel",
        claim="(6.34)",
    )
    d.prove_equal(
        sp.Matrix([y_hit.subs(x, 0), y_hit.subs(x, ell)]),
        sp.Matrix([4 * S / m, 4 * S / m]),
        strategy="cancel",
        claim="(6.34) is a parabola with its minimum at ℓ/2: the largest value 4S/m at x = 0 and ℓ",
    )
    d.prove_equal(
        T_book - S * y_hit / 2, 0, strategy="cancel", claim="T = ½ S ẏ(x): the work of the blow"
    )
    # independent route: a rod of 4000 equal point masses, momentum and angular momentum summed
    mn, ln, Sn, xn = 0.9, 0.84, 2.5, 0.15
    N = 4000
    xs = (np.arange(N) + 0.5) / N * ln
    dm = mn / N
    J_num = dm * np.sum((xs - ln / 2) ** 2)
    vG_num = Sn / mn
    w_num = (xn - ln / 2) * Sn / J_num
    vel = kin.point_velocity(
        [0.0, vG_num, 0.0], [0.0, 0.0, w_num], np.stack([xs - ln / 2, 0 * xs, 0 * xs], axis=-1)
    )
    T_num = 0.5 * dm * np.sum(vel**2)
    sub = {m: mn, ell: ln, S: Sn, x: xn}
    # the midpoint sum of (ξ - ℓ/2)² is low by m ℓ²/(12 N²): relative 1/N² in J_G
    d.confirm(
        T_num,
        float(T_book.subs(sub)),
        atol=float(T_book.subs(sub)) * 2 / N**2,
        route="4000 point masses: T = Σ ½ dm v_k², velocities by mechanics.point_velocity",
    )
    r_GC, _ = kin.instantaneous_axis([0.0, vG_num, 0.0], [0.0, 0.0, w_num])
    d.confirm(
        ln / 2 + r_GC[0],
        float(x_C_book.subs(sub)),
        atol=float(abs(x_C_book.subs(sub))) * 4 / N**2,
        route="mechanics.instantaneous_axis from G: the point at rest x_C",
    )


@check(
    "E6.3",
    "Example 6.3: the restitution impulse is e times the compression impulse",
    kind="derivation",
    covers=("E6.3", *(f"eq6.{n}" for n in range(42, 51))),
    errata=("eq6.44",),
    statement="S_A1 = m_A[ẋ_A(0) - ẋ_A(-δ1)], S_A2 = m_A[ẋ_A(δ2) - ẋ_A(0)] and the same for B; "
    "with ẋ_A(0) = ẋ_B(0) = v_G and the velocities after from (6.37)-(6.38): "
    "S_A2/S_A1 = S_B2/S_B1 = e (6.42)",
    printed="(6.44): S_B1 = m_B[ẋ_B(0) - ẋ_A(-δ1)]",
    corrected="S_B1 = m_B[ẋ_B(0) - ẋ_B(-δ1)] (the impulse-momentum law (6.19) for body B)",
)
def example_6_3(d: Derivation) -> None:
    mA, mB = sp.symbols("m_A m_B", positive=True)
    vA, vB, e = sp.symbols("xdot_A xdot_B e", real=True)  # velocities at t = -δ1
    from identities.book.ch06.restitution import e as e_r
    from identities.book.ch06.restitution import m_1, m_2, xdot_1i, xdot_2i

    v1f, v2f = direct_impact_symbolic()
    sub = {m_1: mA, m_2: mB, xdot_1i: vA, xdot_2i: vB, e_r: e}
    vAf, vBf = v1f.subs(sub), v2f.subs(sub)  # velocities at t = δ2
    vG = (mA * vA + mB * vB) / (mA + mB)  # common velocity at t = 0
    SA1, SA2 = mA * (vG - vA), mA * (vAf - vG)  # (6.43)
    SB1, SB2 = mB * (vG - vB), mB * (vBf - vG)  # (6.44) corrected
    for name, val in (("S_A1", SA1), ("S_A2", SA2), ("S_B1", SB1), ("S_B2", SB2)):
        d.quantity(name, sp.factor(val))
    d.prove_equal(
        sp.Matrix([SA1 + SB1, SA2 + SB2]),
        sp.zeros(2, 1),
        strategy="cancel",
        claim="(6.46): S_A1 + S_B1 = 0 and S_A2 + S_B2 = 0",
    )
    SB1_printed = mB * (vG - vA)
    d.refute(SB1_printed, SB1, claim="(6.44) as printed, with ẋ_A(-δ1)")
    d.refute(SA1 + SB1_printed, 0, claim="the printed S_B1 breaks action and reaction (6.46)")
    d.prove_equal(
        -(vAf - vBf) / (vA - vB), e, strategy="cancel", claim="(6.45): e from the velocities"
    )
    d.prove_equal(SA2 / SA1, e, strategy="cancel", claim="(6.42): S_A2/S_A1 = e")
    d.prove_equal(SB2 / SB1, e, strategy="cancel", claim="(6.42): S_B2/S_B1 = e")
    d.prove_equal(SA2 / SA1, (-SB2) / (-SB1), strategy="cancel", claim="(6.47)")
    d.prove_equal(-SA2 / SA1, (vAf - vG) / (vA - vG), strategy="cancel", claim="(6.48)-(6.49)")
    d.prove_equal((vAf - vG) / (vA - vG), (vBf - vG) / (vB - vG), strategy="cancel", claim="(6.49)")
    d.reject(SA2 / SA1, e**2, strategy="cancel", claim="S_A2/S_A1 = e² (the energy ratio)")
    a, b, k = sp.symbols("a b k", real=True)
    d.prove_equal(
        (a - k * a) / (b - k * b),
        a / b,
        strategy="cancel",
        claim="the lemma: a/b = c/d = 1/k·... ⇒ (a - c)/(b - d) = a/b (c = k a, d = k b, k ≠ 1)",
    )
    d.reject((a + k * a) / (b - k * b), a / b, strategy="cancel", claim="the lemma with (a + c)")
    d.prove_equal(
        (vAf - vG - (vBf - vG)) / (vA - vG - (vB - vG)),
        -e,
        strategy="cancel",
        claim="(6.50): the lemma applied gives -S_A2/S_A1 = -e",
    )
    # mechanics: body A behind B (ẋ_A > ẋ_B), impulses from B on A
    args = (1.0, 3.0, 5.0, -3.0, 0.5)
    S1, S2 = imp.compression_restitution_impulses(*args)
    num = {mA: 1.0, mB: 3.0, vA: 5.0, vB: -3.0, e: 0.5}
    d.confirm(
        [S1, S2, S2 / S1],
        [float(SA1.subs(num)), float(SA2.subs(num)), 0.5],
        atol=DIRECT_ATOL,
        route="mechanics.compression_restitution_impulses",
    )
    # simulation: split the contact impulse at the moment of greatest compression
    for mm1, mm2, ee in ((2.0, 3.0, 0.6), (1.0, 50.0, 0.25), (4.0, 1.0, 0.95)):
        sim = spring_dashpot_collision(mm1, mm2, 1.5, -0.5, ee, 1e-3)
        d.confirm(
            sim["S_2"] / sim["S_1"],
            ee,
            atol=SIM_RTOL * 100,  # a ratio of two integrals switched at an event: 100x looser
            route=f"scipy spring–dashpot contact (m_A = {mm1}, m_B = {mm2}, e = {ee}): "
            "restitution/compression impulse",
        )
