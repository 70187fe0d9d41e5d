"""Chapter 6.1–6.2: the impulse approximation and the momentum principles at impact.
Equations (6.1)–(6.6), (6.11)–(6.22).

An impact force is modelled, as in (6.1), by a pulse of duration τ and fixed impulse
S: K(t) = (S/τ) f((t - t_i)/τ) with a shape f ≥ 0 on [0, 1] of unit integral (here the
parabola f(s) = 6 s (1 - s) and the quartic f(s) = 30 s² (1 - s)²).  Ordinary forces
are smooth: a Taylor polynomial F_0 + F_1 (t - t_i) + F_2 (t - t_i)².  The momentum
and angular-momentum principles are integrated exactly over [t_i, t_i + τ] and the
limit τ → 0 is taken: every statement below is an exact identity of polynomials in τ.

The rigid-body consequence (6.19)–(6.22), an impulse at a point of a body with a
general inertia tensor, is also confirmed by a simulation: scipy integrates the
Newton–Euler equations of a rotating body through a short force pulse.
"""

from __future__ import annotations

import numpy as np
import sympy as sp
from scipy.integrate import solve_ivp

from identities.verify.catalogue import check
from identities.verify.proof import Derivation
from identities.verify.symbolic import cross, floats, vec
from mechanics._floats import EPS

#: float evaluation of a few products and one 3x3 solve of O(1) numbers: 64 eps.
CODE_ATOL = 64 * EPS

t, t_i = sp.symbols("t t_i", real=True)
tau = sp.Symbol("tau", positive=True)
s = sp.Symbol("s", real=True)
m, m_1, m_2 = sp.symbols("m m_1 m_2", positive=True)

#: unit-integral pulse shapes on [0, 1]
PULSES = {"parabolic": 6 * s * (1 - s), "quartic": 30 * s**2 * (1 - s) ** 2}


def _vsym(name: str) -> sp.Matrix:
    return vec(*sp.symbols(f"{name}_x {name}_y {name}_z", real=True))


def _pulse(S, shape) -> sp.Matrix:
    """K(t) = (S/τ) f((t - t_i)/τ): the impact force (6.1) with impulse S."""
    return sp.Matrix(S) * shape.subs(s, (t - t_i) / tau) / tau


def _integral(F) -> sp.Matrix:
    """∫_{t_i}^{t_i+τ} F dt (6.2)-(6.3), entrywise, for F polynomial in t and 1/τ.

    Substituting t = t_i + τ s (dt = τ ds) makes each entry a polynomial in s, which is
    integrated over [0, 1] term by term (exact, and much faster than ``sp.integrate``).
    """

    def one(c):
        c = sp.expand(sp.sympify(c).subs(t, t_i + tau * s) * tau)
        if not c.has(s):
            return c
        P = sp.Poly(c, s).integrate()
        return sp.expand(P.as_expr().subs(s, 1) - P.as_expr().subs(s, 0))

    return sp.Matrix(F).applyfunc(one)


def _limit0(F) -> sp.Matrix:
    """The value at τ = 0 of a rational function of τ, after cancelling (entrywise)."""
    return sp.Matrix(F).applyfunc(lambda c: sp.cancel(c).subs(tau, 0))


def _smooth_force(name: str) -> sp.Matrix:
    """An ordinary force: a quadratic Taylor polynomial about t_i with vector coefficients."""
    F0, F1, F2 = _vsym(f"{name}0"), _vsym(f"{name}1"), _vsym(f"{name}2")
    return F0 + F1 * (t - t_i) + F2 * (t - t_i) ** 2


@check(
    "eq6.5",
    "The impulse approximation: Δp = ∫(F_a + K) dt → S as τ → 0",
    kind="proof",
    covers=("eq6.3", "eq6.4", "eq6.5"),
    defines=("eq6.1", "eq6.2", "eq6.6"),
    statement="for a pulse K of impulse S and duration τ and a smooth ordinary force F_a, "
    "Δp = ∫(F_a + K) dt = F_a(t_i) τ + S + O(τ²) (6.3)-(6.4), and Δp → S as τ → 0 (6.5); "
    "K_av = S/τ (6.6)",
    reading="(6.4) is read as an approximation to first order in τ; the O(τ²) remainder is "
    "computed exactly here.",
)
def impulse_approximation(d: Derivation) -> None:
    S = _vsym("S")
    Fa = _smooth_force("F")
    F0 = _vsym("F0")
    for name, f in PULSES.items():
        d.prove_equal(
            sp.integrate(f, (s, 0, 1)), 1, strategy="expand", claim=f"{name} shape: ∫₀¹ f = 1"
        )
        K = _pulse(S, f)
        d.prove_equal(_integral(K), S, strategy="cancel", claim=f"(6.2): ∫ K dt = S ({name})")
        dp = _integral(Fa + K)
        d.note(f"(6.3)-(6.4), {name} pulse: Δp =", dp)
        d.prove_equal(
            dp - (Fa.subs(t, t_i) * tau + S),
            _integral(Fa - Fa.subs(t, t_i)),
            strategy="cancel",
            claim="(6.4): Δp - [F_a(t_i) τ + S] = ∫ (F_a(t) - F_a(t_i)) dt, which is O(τ²)",
        )
        d.prove_equal(
            _limit0(dp),
            S,
            strategy="expand",
            claim=f"(6.5): Δp → S as τ → 0 ({name} pulse)",
        )
    d.reject(
        _integral(Fa + _pulse(S, PULSES["parabolic"])),
        F0 * tau + S,
        strategy="cancel",
        claim="(6.4) as an exact equality for a time-dependent F_a (the F_1 τ²/2 term is lost)",
    )
    bounded = sp.Matrix(S) * PULSES["parabolic"].subs(s, (t - t_i) / tau)  # no 1/τ: not 'large'
    d.reject(
        _limit0(_integral(Fa + bounded)),
        S,
        strategy="expand",
        claim="a force of bounded size (not growing like 1/τ) still delivers S as τ → 0",
    )
    K_av = S / tau
    d.prove_equal(
        _integral(K_av) / tau,
        K_av,
        strategy="cancel",
        claim="(6.6): a constant force of the value K_av = S/τ has the impulse S",
    )
    d.note("the parabolic pulse peaks at 3/2 K_av, the quartic one at 15/8 K_av")
    # numeric: quadrature of the pulse plus a smooth force, with τ small
    Sn, F0n, F1n, taun = np.array([2.0, -1.0, 0.5]), np.array([0.3, 0.1, -9.81]), 5.0, 1e-3
    tt = np.linspace(0.0, taun, 2001)
    Kn = 6 * (tt / taun) * (1 - tt / taun) / taun
    integrand = Kn[:, None] * Sn + F0n + F1n * tt[:, None]
    dp_num = np.trapezoid(integrand, tt, axis=0)
    # trapezoid error for the quadratic pulse: S τ h²/12 · max|f''|/τ³ = S/(2 (n-1)²) per component
    trap_tol = float(np.max(np.abs(Sn))) / (2000**2)
    d.confirm(
        dp_num,
        Sn + F0n * taun + F1n * taun**2 / 2,
        atol=trap_tol + 16 * EPS * float(np.max(np.abs(Sn))),
        route="trapezoid quadrature of F_a + K over 2000 steps equals S + F_a(t_i) τ + F_1 τ²/2",
    )


@check(
    "eq6.12",
    "Idealisations of an impact: Δr → 0, Δv finite and non-zero, |a| → ∞ as τ → 0",
    kind="proof",
    covers=("eq6.11", "eq6.12", "eq6.13"),
    statement="a particle of mass m hit by a pulse of impulse S: Δr = r_f - r_i → 0 (6.11), "
    "Δv → S/m ≠ 0 (6.12), max |a| ~ 1/τ → ∞ (6.13)",
    reading="(6.12) is printed '|Δv| = |v_f - v_i| = 0'; the sentence after it says 'finite "
    "change in velocity', so the relation sign lost in the extraction is ≠: |Δv| ≠ 0.",
)
def idealisations(d: Derivation) -> None:
    S, v_i, F0 = sp.Symbol("S", real=True), sp.Symbol("v_i", real=True), sp.Symbol("F0", real=True)
    f = PULSES["parabolic"]
    u = sp.Symbol("u", real=True)
    a = (F0 + S * f.subs(s, (t - t_i) / tau) / tau) / m
    v = v_i + sp.integrate(a.subs(t, u), (u, t_i, t))
    x = sp.integrate(v.subs(t, u), (u, t_i, t))
    dx = sp.cancel(x.subs(t, t_i + tau))
    dv = sp.cancel(v.subs(t, t_i + tau) - v_i)
    d.quantity("Delta_r", dx)
    d.quantity("Delta_v", dv)
    d.prove_equal(dx.subs(tau, 0), 0, strategy="expand", claim="(6.11): Δr → 0 as τ → 0")
    dv0 = dv.subs(tau, 0)
    d.prove_equal(dv0, S / m, strategy="expand", claim="(6.12): Δv → S/m as τ → 0")
    d.witness_unequal(dv0, 0, {S: 1, m: 1}, claim="(6.12): |Δv| ≠ 0: a finite change")
    d.reject(dv0, 0, strategy="expand", claim="(6.12) read literally: |Δv| = 0")
    a_peak = a.subs(t, t_i + tau / 2)
    d.prove_equal(
        sp.cancel(a_peak * tau).subs(tau, 0),
        sp.Rational(3, 2) * S / m,
        strategy="expand",
        claim="(6.13): τ · a(t_i + τ/2) → 3S/(2m) ≠ 0, so |a| grows like 1/τ → ∞",
    )
    d.reject(
        sp.cancel(a_peak * tau).subs(tau, 0),
        0,
        strategy="expand",
        claim="the acceleration stays bounded as τ → 0",
    )


@check(
    "eq6.16",
    "Total momentum is conserved through an impact",
    kind="proof",
    covers=("eq6.14", "eq6.15", "eq6.16"),
    statement="d(p1 + p2)/dt = F_e (6.14): the impact forces K12 = -K21 cancel, so "
    "Δ(p1 + p2) = ∫ F_e dt → 0 as τ → 0 (6.15)-(6.16)",
)
def momentum_conservation(d: Derivation) -> None:
    S = _vsym("S")
    K12 = _pulse(S, PULSES["quartic"])
    K21 = -K12  # Newton's third law
    F1e, F2e = _smooth_force("Fa"), _smooth_force("Fb")
    rate = (F1e + K12) + (F2e + K21)  # dp1/dt + dp2/dt, each body's momentum principle
    d.prove_equal(rate, F1e + F2e, strategy="expand", claim="(6.14): d(p1 + p2)/dt = F_e")
    dP = _integral(rate)
    d.prove_equal(_limit0(dP), sp.zeros(3, 1), strategy="expand", claim="(6.15)-(6.16)")
    d.prove_equal(
        _limit0(_integral(F1e + K12)) + _limit0(_integral(F2e + K21)),
        sp.zeros(3, 1),
        strategy="cancel",
        claim="(6.16): p1f + p2f = p1i + p2i, from (6.5) for each body",
    )
    d.reject(
        _limit0(_integral((F1e + K12) + (F2e + K12))),
        sp.zeros(3, 1),
        strategy="cancel",
        claim="the same without Newton's third law (K21 = +K12)",
    )


@check(
    "eq6.18",
    "Total angular momentum is conserved through an impact, about any continuously moving point",
    kind="proof",
    covers=("eq6.17", "eq6.18"),
    statement="dL_A/dt + v_A × p = M_A (1.50) for the pair; the impact forces act at the same "
    "point S and cancel in M_A; ∫ (M_e - v_A × p) dt → 0, so L1f + L2f = L1i + L2i (6.18)",
)
def angular_momentum_conservation(d: Derivation) -> None:
    S = _vsym("S")
    f = PULSES["parabolic"]
    K12 = _pulse(S, f)
    r_S, r_A0, v_A0, a_A = _vsym("r_S"), _vsym("rA0"), _vsym("vA0"), _vsym("aA")
    v_A = v_A0 + a_A * (t - t_i)  # a base point moving continuously
    r_A = r_A0 + v_A0 * (t - t_i) + a_A * (t - t_i) ** 2 / 2
    M_e = _smooth_force("M")  # the moment of the ordinary external forces: smooth
    p_i = _vsym("p")
    u = sp.Symbol("u", real=True)
    # total momentum during the impact: internal forces cancel, only F_e (smooth) changes it
    F_e = _smooth_force("F")
    p = p_i + sp.Matrix([sp.integrate(c.subs(t, u), (u, t_i, t)) for c in F_e])
    internal = cross(r_S - r_A, K12) + cross(r_S - r_A, -K12)
    d.prove_equal(
        internal, sp.zeros(3, 1), strategy="expand", claim="impact forces at S have no net moment"
    )
    rate = M_e + internal - cross(v_A, p)  # dL_A/dt from (1.50)
    dL = _integral(rate)
    d.note("(6.17) integrated over the impact: ΔL_A =", dL)
    d.prove_equal(_limit0(dL), sp.zeros(3, 1), strategy="expand", claim="(6.18): ΔL_A → 0 as τ → 0")
    r_S2 = _vsym("r_T")  # a (wrong) second point of application
    wrong = _limit0(_integral(cross(r_S - r_A, K12) + cross(r_S2 - r_A, -K12)))
    d.reject(
        wrong,
        sp.zeros(3, 1),
        strategy="cancel",
        claim="the same with the two impact forces applied at different points",
    )


def _pulse_rigid_body(mass, J_body, r_G, v_G, omega, rho_body, S, tau_, n_sub=40):
    """Newton–Euler through a parabolic force pulse at the body point G + R ρ (scipy).

    State: r_G, v_G, R (body-to-world, rows of ^A R^O transposed), L_G.  Returns v_G, ω
    after the pulse.  The point of application moves with the body during the pulse.
    """

    def rhs(tt, y):
        R = y[6:15].reshape(3, 3)
        L = y[15:18]
        J = R @ J_body @ R.T
        w = np.linalg.solve(J, L)
        K = S * 6 * (tt / tau_) * (1 - tt / tau_) / tau_
        rho = R @ rho_body
        W = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])
        return np.concatenate([y[3:6], K / mass, (W @ R).ravel(), np.cross(rho, K)])

    R0 = np.eye(3)
    L0 = J_body @ omega
    y0 = np.concatenate([r_G, v_G, R0.ravel(), L0])
    sol = solve_ivp(
        rhs, (0.0, tau_), y0, method="DOP853", rtol=1e-12, atol=1e-14, max_step=tau_ / n_sub
    )
    y = sol.y[:, -1]
    R = y[6:15].reshape(3, 3)
    return y[3:6], np.linalg.solve(R @ J_body @ R.T, y[15:18])


@check(
    "eq6.21",
    "A rigid body hit at a point: S12 = Δp1, r_S × S12 = ΔL1, and L about S is conserved",
    kind="proof",
    covers=("eq6.19", "eq6.20", "eq6.21", "eq6.22"),
    statement="v_Gf = v_Gi + S/m (6.19), J_G (ω_f - ω_i) = (r_S - r_G) × S; then "
    "L_O,f - L_O,i = r_S × S (6.20)-(6.21) and L_S,f = L_S,i (6.22), for a general J_G",
    reading="coordinates along the principal axes of the body at G (J_G diagonal); r_G, r_S, "
    "S, v, ω are general, so the vector statements hold for every inertia tensor",
)
def rigid_body_impulse(d: Derivation) -> None:
    # principal axes of the body at G as the coordinate frame: every statement below is a
    # vector equation, so this choice loses no generality and keeps J_G⁻¹ diagonal
    J = sp.diag(*sp.symbols("J_1 J_2 J_3", positive=True))
    S, r_G, r_S = _vsym("S"), _vsym("r_G"), _vsym("r_S")
    v_i, w_i = _vsym("v"), _vsym("w")
    rho = r_S - r_G
    v_f = v_i + S / m  # (6.19)
    w_f = w_i + J.inv() * cross(rho, S)  # (6.21) about G
    d.quantity("v_Gf", v_f)
    d.quantity("omega_f", w_f)

    def L_about(point, v_G, w):
        return cross(r_G - point, m * v_G) + J * w  # L_P = PG × m v_G + J_G ω

    O = sp.zeros(3, 1)
    d.prove_equal(m * v_f - m * v_i, S, strategy="expand", claim="(6.19): S12 = p1f - p1i")
    d.prove_equal(
        L_about(O, v_f, w_f) - L_about(O, v_i, w_i),
        cross(r_S, S),
        strategy="cancel",
        claim="(6.21): L1f - L1i = r_S × S12 about the origin",
    )
    # (6.20) integrated: the moment of the impact force about O during a pulse
    K = _pulse(S, PULSES["parabolic"])
    M_a = _smooth_force("M")
    d.prove_equal(
        _limit0(_integral(M_a + cross(r_S, K))),
        cross(r_S, S),
        strategy="cancel",
        claim="(6.20) integrated over the impact, τ → 0: ΔL1 = r_S × S12 (r_S fixed)",
    )
    d.prove_equal(
        L_about(r_S, v_f, w_f),
        L_about(r_S, v_i, w_i),
        strategy="cancel",
        claim="(6.22): L_S1f = L_S1i about the point of impact",
    )
    d.reject(
        L_about(r_G, v_f, w_f),
        L_about(r_G, v_i, w_i),
        strategy="cancel",
        claim="the spin L_G is conserved too",
    )
    d.reject(
        L_about(O, v_f, w_f) - L_about(O, v_i, w_i),
        cross(r_G, S),
        strategy="cancel",
        claim="ΔL1 = r_G × S12 (the impulse moved to the centre of mass)",
    )
    # independent route: integrate Newton–Euler through a short pulse (scipy), 3-D body
    Jb = np.diag([2.0, 1.5, 1.1])  # principal moments; the body turns during the pulse
    mass, rho_b = 1.7, np.array([0.4, -0.3, 0.25])
    vG, w0, Sv = np.array([0.5, -0.2, 0.1]), np.array([0.3, -0.4, 0.2]), np.array([-1.0, 2.0, 0.7])
    tau_n = 1e-7
    v_sim, w_sim = _pulse_rigid_body(mass, Jb, np.zeros(3), vG, w0, rho_b, Sv, tau_n)
    pt = {m: mass}
    pt.update(dict(zip(sp.symbols("J_1 J_2 J_3", positive=True), np.diag(Jb), strict=True)))
    pt.update(dict(zip(_vsym("S"), Sv, strict=True)))
    pt.update(dict(zip(_vsym("r_G"), np.zeros(3), strict=True)))
    pt.update(dict(zip(_vsym("r_S"), rho_b, strict=True)))
    pt.update(dict(zip(_vsym("v"), vG, strict=True)))
    pt.update(dict(zip(_vsym("w"), w0, strict=True)))
    # the pulse lasts τ = 1e-7: the body turns by |ω| τ ~ 1e-7 during it, so the point of
    # application moves by O(|ω| |ρ| τ) and the result differs by O(τ |ω| |S|) ≲ 1e-6
    pulse_tol = 4 * tau_n * float(np.linalg.norm(w0) * (np.linalg.norm(Sv) + 1.0))
    d.confirm(
        np.concatenate([v_sim, w_sim]),
        np.concatenate([floats(v_f, pt).ravel(), floats(w_f, pt).ravel()]),
        atol=pulse_tol,
        route="scipy DOP853 integration of Newton–Euler for a rotating 3-D body through a "
        "1e-7 s force pulse at the body point",
    )
