"""Chapter 6.3: the coefficient of restitution.  Equations (6.35)–(6.41), and the
rigid-body impacts built on (6.19)–(6.21): two free bodies in 3-D (effective mass),
a body on a fixed axis, the centre of percussion.

The direct impact is derived from momentum conservation (6.37) and Newton's law of
restitution (6.38); the energy loss (6.41) from the kinetic energies (6.39) and
the split (6.40); the negative control is the loss with (1 - e) in place of
(1 - e²).  Each result is tied to :mod:`mechanics.impact` by a numeric comparison
with the exact rational value (mass ratios up to 1e±15), and to a simulation: scipy
integrates Newton's equations through a stiff spring–dashpot contact whose damping
is set, from the theory of the damped oscillator only, to give the coefficient e.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import sympy as sp
from scipy.integrate import solve_ivp

from identities.verify.catalogue import check
from identities.verify.proof import Derivation
from identities.verify.symbolic import cross, floats, vec
from mechanics import impact as imp
from mechanics._floats import EPS, ulps

#: mechanics.impact promises DIRECT_ULPS = 2 ulps of the exact result; comparing with
#: the exact value rounded to float64 adds ½ ulp.
DIRECT_ATOL_ULPS = imp.DIRECT_ULPS + 0.5
#: the rigid-body functions use plain float64 and a 3x3 solve of well-conditioned
#: tensors (condition number < 10) on O(1) data: 64 eps.
RIGID_ATOL = 64 * EPS
#: the spring–dashpot simulation (DOP853, rtol 1e-12) reproduces velocities to ~1e-11
#: relative; the bound is 2^16 eps ≈ 1.5e-11 times the velocity scale.
SIM_RTOL = 2**16 * EPS

m_1, m_2, m, mu = sp.symbols("m_1 m_2 m mu", positive=True)
e = sp.Symbol("e", nonnegative=True)
xdot_1i, xdot_2i, xdot_1f, xdot_2f = sp.symbols("xdot_1i xdot_2i xdot_1f xdot_2f", real=True)


def direct_impact_symbolic():
    """(6.37)-(6.38) solved for the velocities after a direct central impact."""
    sol = sp.solve(
        [
            sp.Eq(m_1 * xdot_1f + m_2 * xdot_2f, m_1 * xdot_1i + m_2 * xdot_2i),  # (6.37)
            sp.Eq(xdot_1f - xdot_2f, e * xdot_2i - e * xdot_1i),  # (6.38)
        ],
        [xdot_1f, xdot_2f],
        dict=True,
    )
    if len(sol) != 1:
        raise AssertionError(f"(6.37)-(6.38): expected one solution, got {sol}")
    return sp.cancel(sol[0][xdot_1f]), sp.cancel(sol[0][xdot_2f])


def kinetic(x1, x2):
    """(6.39): T = ½ m1 ẋ1² + ½ m2 ẋ2²."""
    return m_1 * x1**2 / 2 + m_2 * x2**2 / 2


def _exact(x) -> Fraction:
    return Fraction(float(x))


#: mass ratios and restitution coefficients for the comparison with mechanics
DIRECT_CASES = (
    (1.0, 3.0, 5.0, -3.0, 0.5),
    (1e-15, 1.0, 2.5, -0.75, 0.3),
    (1.0, 1e-15, 1.25, 0.5, 0.9),
    (7.0, 7.0e15, -0.1, -2.0, 1.0),
    (3.3, 0.7, 1.0, 1.0 - 2**-40, 0.999999999999),
    (2.0, 5.0, 3.0, -1.0, 0.0),
)


def spring_dashpot_collision(m1, m2, v1, v2, e_target, tau_contact, *, g=0.0):
    """Two bodies on an X axis, body 1 behind body 2, colliding through a linear
    spring–dashpot (Kelvin–Voigt) contact, integrated by scipy.

    The overlap δ = x1 - x2 ≥ 0 obeys μ δ̈ + c δ̇ + k δ = 0 during contact (no external
    force).  A damped oscillator that starts at δ = 0 returns to δ = 0 after half a
    damped period π/ω_d with its velocity scaled by exp(-ζ π/√(1 - ζ²)); ζ and k are
    set from that alone (ω_d = π/τ).  ``m2 = inf`` is a fixed wall; ``g`` an external
    acceleration -g on body 1 (a weight).  Returns the velocities after, the impulses
    on body 1 during compression (δ̇ > 0) and restitution, the contact time and the
    compression time (to the maximum of δ).
    """
    log_e = np.log(e_target)
    zeta = -log_e / np.sqrt(np.pi**2 + log_e**2)
    red = m1 if np.isinf(m2) else m1 * m2 / (m1 + m2)
    w_d = np.pi / tau_contact
    w_n = w_d / np.sqrt(1 - zeta**2)
    k, c = red * w_n**2, 2 * zeta * red * w_n
    inv2 = 0.0 if np.isinf(m2) else 1.0 / m2

    def contact_force(y):  # force on body 1 (pushes it back)
        return -(k * y[0] + c * y[1])

    def rhs(_t, y):  # y = (δ, δ̇, v1, v2, impulse on 1 so far, ∫ K dt during compression)
        K = contact_force(y)
        a1, a2 = K / m1 - g, -K * inv2
        return [y[1], a1 - a2, a1, a2, K, K if y[1] > 0 else 0.0]

    def separated(_t, y):
        return y[0]

    separated.terminal, separated.direction = True, -1

    def max_compression(_t, y):
        return y[1]

    max_compression.direction = -1
    sol = solve_ivp(
        rhs,
        (0.0, 10 * tau_contact),
        [0.0, v1 - v2, v1, v2, 0.0, 0.0],
        method="DOP853",
        rtol=1e-12,
        atol=1e-15 * max(abs(v1), abs(v2), 1.0),
        events=(separated, max_compression),
        max_step=tau_contact / 64,
    )
    # the event at t = 0 (δ = 0 rising) is not a separation: take the last state
    y = sol.y_events[0][-1] if sol.t_events[0].size else sol.y[:, -1]
    t_end = sol.t_events[0][-1] if sol.t_events[0].size else sol.t[-1]
    S_total = y[4]
    S_1 = y[5]
    t_max = sol.t_events[1]
    return {
        "tau_1": t_max[0] if t_max.size else np.nan,
        "v1f": y[2],
        "v2f": y[3],
        "S_1": S_1,
        "S_2": S_total - S_1,
        "tau": t_end,
        "impulse": S_total,
    }


@check(
    "eq6.40",
    "Kinetic energy of two bodies = centre-of-mass part + reduced-mass part",
    kind="proof",
    covers=("eq6.39", "eq6.40"),
    statement="½ m1 ẋ1² + ½ m2 ẋ2² = ½ (m1 + m2) ẋ_G² + ½ μ (ẋ2 - ẋ1)², "
    "ẋ_G = (m1 ẋ1 + m2 ẋ2)/(m1 + m2), μ = m1 m2/(m1 + m2)",
)
def energy_split(d: Derivation) -> None:
    x1, x2 = xdot_1i, xdot_2i
    xG = (m_1 * x1 + m_2 * x2) / (m_1 + m_2)
    mu_ = m_1 * m_2 / (m_1 + m_2)
    d.quantity("mu", mu_)
    rhs = (m_1 + m_2) * xG**2 / 2 + mu_ * (x2 - x1) ** 2 / 2
    d.prove_equal(kinetic(x1, x2), rhs, strategy="cancel", claim="(6.39) = (6.40)")
    d.reject(
        kinetic(x1, x2),
        (m_1 + m_2) * xG**2 / 2 + mu_ * (x2 + x1) ** 2 / 2,
        strategy="cancel",
        claim="the relative term with (ẋ2 + ẋ1)",
    )
    d.reject(
        kinetic(x1, x2),
        (m_1 + m_2) * xG**2 / 2 + (m_1 + m_2) * (x2 - x1) ** 2 / 8,
        strategy="cancel",
        claim="the relative term with m/4 in place of μ (right only for m1 = m2)",
    )


@check(
    "eq6.38",
    "Velocities after a direct central impact, from momentum and Newton's restitution law",
    kind="proof",
    covers=("eq6.37", "eq6.38"),
    defines=("eq6.36",),
    statement="(6.37) m1 ẋ1f + m2 ẋ2f = m1 ẋ1i + m2 ẋ2i and (6.38) ẋ1f - ẋ2f = e (ẋ2i - ẋ1i) "
    "give ẋ1f = ẋ1i + (1 + e) m2 (ẋ2i - ẋ1i)/(m1 + m2), ẋ2f = ẋ2i - (1 + e) m1 (ẋ2i - ẋ1i)/(m1 + m2)",
)
def direct_velocities(d: Derivation) -> None:
    v1f, v2f = direct_impact_symbolic()
    d.quantity("xdot_1f", v1f)
    d.quantity("xdot_2f", v2f)
    dx = xdot_2i - xdot_1i
    d.prove_equal(v1f, xdot_1i + (1 + e) * m_2 * dx / (m_1 + m_2), strategy="cancel", claim="ẋ1f")
    d.prove_equal(v2f, xdot_2i - (1 + e) * m_1 * dx / (m_1 + m_2), strategy="cancel", claim="ẋ2f")
    d.prove_equal(
        -(v2f - v1f) / (xdot_2i - xdot_1i),
        e,
        strategy="cancel",
        claim="(6.36): e = -(ẋ2f - ẋ1f)/(ẋ2i - ẋ1i) for the solution",
    )
    d.reject(
        v1f,
        xdot_1i + (1 + e) * m_1 * dx / (m_1 + m_2),
        strategy="cancel",
        claim="ẋ1f with the masses swapped",
    )
    d.reject(v2f - v1f, e * dx, strategy="cancel", claim="restitution without the reversal of sign")
    d.confirm_exact(
        sp.Matrix([v1f, v2f]).subs({e: 1, m_2: m_1}),
        sp.Matrix([xdot_2i, xdot_1i]),
        strategy="cancel",
        route="limit: equal masses, e = 1 exchange their velocities",
    )
    d.confirm_exact(
        sp.limit(v1f, m_2, sp.oo),
        -e * xdot_1i + (1 + e) * xdot_2i,
        strategy="cancel",
        route="limit m2 → ∞ (a wall moving at ẋ2i): ẋ1f - ẋ2i = -e (ẋ1i - ẋ2i)",
    )
    # mechanics.direct_impact against the exact rational solution of the float inputs
    worst = 0.0
    for case in DIRECT_CASES:
        a1, a2 = imp.direct_impact(*case)
        sub = dict(zip((m_1, m_2, xdot_1i, xdot_2i, e), map(sp.Rational, case), strict=True))
        for actual, exact in ((a1, v1f), (a2, v2f)):
            worst = max(worst, ulps(actual, Fraction(str(exact.subs(sub)))))
    d.confirm(
        worst,
        0.0,
        atol=DIRECT_ATOL_ULPS,
        route="mechanics.direct_impact within 2.5 ulps of the exact solution, mass ratios 1e±15, "
        f"e in [0, 1] (worst {worst:.2f} ulp)",
    )
    # simulation of a stiff spring–dashpot contact set to e = 0.6
    cases = [(2.0, 3.0, 1.5, -0.5), (1.0, 1e3, 2.0, 0.0)]
    for mm1, mm2, u1, u2 in cases:
        sim = spring_dashpot_collision(mm1, mm2, u1, u2, 0.6, 1e-3)
        sub = {m_1: mm1, m_2: mm2, xdot_1i: u1, xdot_2i: u2, e: 0.6}
        d.confirm(
            [sim["v1f"], sim["v2f"]],
            floats(sp.Matrix([v1f, v2f]), sub).ravel(),
            atol=SIM_RTOL * max(abs(u1), abs(u2)),
            route=f"scipy: spring–dashpot contact set to e = 0.6, m1 = {mm1}, m2 = {mm2}",
        )


@check(
    "eq6.41",
    "Energy lost in a direct impact: Q = (1 - e²) ½ μ (Δẋ_i)² ≥ 0",
    kind="proof",
    covers=("eq6.35", "eq6.41"),
    statement="Q ≡ T_i - T_f (6.35) with the velocities from (6.37)-(6.38) equals "
    "(1 - e²) ½ μ (ẋ2i - ẋ1i)², which is ≥ 0 for 0 ≤ e ≤ 1 and 0 for e = 1",
)
def energy_loss(d: Derivation) -> None:
    v1f, v2f = direct_impact_symbolic()
    Q = kinetic(xdot_1i, xdot_2i) - kinetic(v1f, v2f)
    mu_ = m_1 * m_2 / (m_1 + m_2)
    dx = xdot_2i - xdot_1i
    book = (1 - e**2) * mu_ * dx**2 / 2
    d.quantity("Q", sp.factor(Q))
    d.prove_equal(Q, book, strategy="cancel", claim="(6.41) from (6.39) and (6.37)-(6.38)")
    d.reject(Q, (1 - e) * mu_ * dx**2 / 2, strategy="cancel", claim="Q with (1 - e) for (1 - e²)")
    # second route (the book's): the centre-of-mass term of (6.40) is unchanged and the
    # relative velocity is multiplied by -e
    d.confirm_exact(
        mu_ * dx**2 / 2 - mu_ * (e * dx) ** 2 / 2,
        Q,
        strategy="cancel",
        route="(6.40): only ½ μ (Δẋ)² changes, Δẋ_f = -e Δẋ_i",
    )
    c = sp.Symbol("c", nonnegative=True)  # e = c/(1 + c) covers 0 ≤ e < 1
    nonneg = mu_ * dx**2 * (1 + 2 * c) / (2 * (1 + c) ** 2)
    d.prove_equal(
        Q.subs(e, c / (1 + c)),
        nonneg,
        strategy="cancel",
        claim="(6.35): Q = μ Δẋ² (1 + 2c)/(2 (1 + c)²) ≥ 0 with e = c/(1 + c), c ≥ 0",
    )
    d.prove_equal(Q.subs(e, 1), 0, strategy="cancel", claim="e = 1: elastic, no loss")
    d.prove_equal(
        (v2f - v1f).subs(e, 0), 0, strategy="cancel", claim="e = 0: no relative velocity after"
    )
    worst = 0.0
    for case in DIRECT_CASES:
        sub = dict(zip((m_1, m_2, xdot_1i, xdot_2i, e), map(sp.Rational, case), strict=True))
        worst = max(worst, ulps(imp.energy_loss_direct(*case), Fraction(str(book.subs(sub)))))
    d.confirm(
        worst,
        0.0,
        atol=DIRECT_ATOL_ULPS,
        route="mechanics.energy_loss_direct within 2.5 ulps of the exact Q, mass ratios 1e±15 "
        f"(worst {worst:.2f} ulp)",
    )
    mm1, mm2, u1, u2, ee = 2.0, 3.0, 1.5, -0.5, 0.6
    sim = spring_dashpot_collision(mm1, mm2, u1, u2, ee, 1e-3)
    T = lambda a, b: 0.5 * mm1 * a**2 + 0.5 * mm2 * b**2  # noqa: E731
    d.confirm(
        T(u1, u2) - T(sim["v1f"], sim["v2f"]),
        float(book.subs({m_1: mm1, m_2: mm2, xdot_1i: u1, xdot_2i: u2, e: ee})),
        atol=SIM_RTOL * T(u1, u2),
        route="scipy spring–dashpot contact (e = 0.6): T_i - T_f from the simulated velocities",
    )


def _sym_matrix(prefix: str) -> sp.Matrix:
    """A general symmetric 3x3 matrix of real symbols."""
    a, b, c, x, y, z = sp.symbols(
        f"{prefix}11 {prefix}22 {prefix}33 {prefix}23 {prefix}13 {prefix}12", real=True
    )
    return sp.Matrix([[a, z, y], [z, b, x], [y, x, c]])


def _vsym(name: str) -> sp.Matrix:
    return vec(*sp.symbols(f"{name}_x {name}_y {name}_z", real=True))


@check(
    "thm.eccentric-impact",
    "Smooth impact of two free rigid bodies in 3-D: effective mass, restitution, energy loss",
    kind="proof",
    covers=("eq6.35",),
    defines=("eq6.36",),
    statement="impulse S n on body 1 and -S n on body 2 at the point S: momentum and angular "
    "momentum about any fixed point are conserved, v_n' = v_n + S/μ with 1/μ = 1/m1 + 1/m2 + "
    "(ρ1×n)·J1⁻¹(ρ1×n) + (ρ2×n)·J2⁻¹(ρ2×n); Newton's law v_n' = -e v_n gives "
    "S = -(1 + e) μ v_n and the loss T_i - T_f = ½ μ (1 - e²) v_n² ≥ 0",
    reading="each body is described by its mass, the inverse K = J_G⁻¹ of its inertia tensor "
    "(a general symmetric matrix) and its spin h = J_G ω, so ω = K h and T = ½ m v_G² + ½ h·K h; "
    "the normal is the third axis of the frame (no loss of generality: K, ρ, v, h are general)",
)
def eccentric_impact(d: Derivation) -> None:
    n = vec(0, 0, 1)
    S = sp.Symbol("S", real=True)
    K1, K2 = _sym_matrix("K"), _sym_matrix("L")
    r_S, r_1, r_2 = _vsym("r_S"), _vsym("r_G1"), _vsym("r_G2")
    v1, v2, h1, h2 = _vsym("v1"), _vsym("v2"), _vsym("h1"), _vsym("h2")
    rho1, rho2 = r_S - r_1, r_S - r_2
    v1f, v2f = v1 + S * n / m_1, v2 - S * n / m_2  # (6.19)
    h1f, h2f = h1 + cross(rho1, S * n), h2 + cross(rho2, -S * n)  # (6.21) about G
    p = lambda a, b: m_1 * a + m_2 * b  # noqa: E731
    L_O = lambda a, b, ha, hb: (  # noqa: E731
        cross(r_1, m_1 * a) + ha + cross(r_2, m_2 * b) + hb
    )
    T = lambda a, b, ha, hb: (  # noqa: E731
        m_1 * a.dot(a) / 2 + ha.dot(K1 * ha) / 2 + m_2 * b.dot(b) / 2 + hb.dot(K2 * hb) / 2
    )
    v_n = lambda a, b, ha, hb: n.dot(  # noqa: E731
        (a + cross(K1 * ha, rho1)) - (b + cross(K2 * hb, rho2))
    )
    d.prove_equal(p(v1f, v2f), p(v1, v2), strategy="expand", claim="(6.16): momentum conserved")
    d.prove_equal(
        L_O(v1f, v2f, h1f, h2f),
        L_O(v1, v2, h1, h2),
        strategy="expand",
        claim="(6.18): angular momentum about the (fixed) origin conserved",
    )
    inv_mu = 1 / m_1 + 1 / m_2 + cross(rho1, n).dot(K1 * cross(rho1, n))
    inv_mu += cross(rho2, n).dot(K2 * cross(rho2, n))
    d.quantity("inverse_effective_mass", inv_mu)
    vn_i, vn_f = v_n(v1, v2, h1, h2), v_n(v1f, v2f, h1f, h2f)
    d.prove_equal(vn_f, vn_i + S * inv_mu, strategy="expand", claim="v_n' = v_n + S/μ")
    d.prove_equal(
        T(v1f, v2f, h1f, h2f) - T(v1, v2, h1, h2),
        S * (vn_i + vn_f) / 2,
        strategy="expand",
        claim="T_f - T_i = S (v_n + v_n')/2: the impulse times the mean normal velocity",
    )
    d.reject(
        T(v1f, v2f, h1f, h2f) - T(v1, v2, h1, h2),
        S * vn_i,
        strategy="expand",
        claim="T_f - T_i = S v_n (the impulse times the velocity before)",
    )
    # Newton's restitution law fixes S; then the loss follows from the last identity
    W, vn, Ssol = sp.symbols("W v_n S_sol", real=True)  # W = 1/μ > 0
    S_e = sp.solve(sp.Eq(vn + Ssol * W, -e * vn), Ssol)[0]
    d.quantity("S", S_e.subs(W, 1 / mu))
    d.prove_equal(S_e, -(1 + e) * vn / W, strategy="cancel", claim="S = -(1 + e) μ v_n")
    Q = -(S_e * (vn + vn + S_e * W) / 2)
    d.quantity("Q", sp.factor(Q.subs(W, 1 / mu)))
    d.prove_equal(Q, (1 - e**2) * vn**2 / (2 * W), strategy="cancel", claim="Q = ½ μ (1 - e²) v_n²")
    d.reject(Q, (1 - e) * vn**2 / (2 * W), strategy="cancel", claim="Q = ½ μ (1 - e) v_n²")
    d.note(
        "1/μ > 0: 1/m1 + 1/m2 > 0 and K1, K2 are positive definite, so Q ≥ 0 for 0 ≤ e ≤ 1 (6.35)"
    )
    # mechanics.rigid_impact against the formulas, a general 3-D configuration
    J1n = np.array([[2.0, 0.3, -0.1], [0.3, 1.5, 0.2], [-0.1, 0.2, 1.1]])
    J2n = np.array([[0.9, -0.1, 0.05], [-0.1, 1.3, 0.0], [0.05, 0.0, 1.2]])
    b1 = imp.RigidBody(1.5, J1n, [0.1, -0.2, 0.7], [0.2, 0.1, -1.0], [0.3, -0.5, 0.2])
    b2 = imp.RigidBody(2.5, J2n, [-0.3, 0.4, -0.6], [0.0, -0.2, 0.8], [-0.1, 0.4, 0.6])
    rS, nn, ee = np.array([0.05, 0.1, 0.02]), np.array([0.0, 0.0, 1.0]), 0.7
    out = imp.rigid_impact(b1, b2, r_S=rS, n=nn, e=ee)
    pt = {m_1: 1.5, m_2: 2.5}
    for M, name in ((np.linalg.inv(J1n), "K"), (np.linalg.inv(J2n), "L")):
        names = sp.symbols(f"{name}11 {name}22 {name}33 {name}23 {name}13 {name}12", real=True)
        vals = (M[0, 0], M[1, 1], M[2, 2], M[1, 2], M[0, 2], M[0, 1])
        pt.update(dict(zip(names, vals, strict=True)))
    for sym, val in (
        (r_S, rS),
        (r_1, b1.r_G),
        (r_2, b2.r_G),
        (v1, b1.v_G),
        (v2, b2.v_G),
        (h1, J1n @ np.asarray(b1.omega)),
        (h2, J2n @ np.asarray(b2.omega)),
    ):
        pt.update(dict(zip(sym, np.asarray(val, dtype=float), strict=True)))
    mu_n = 1.0 / float(inv_mu.subs(pt))
    vn_n = float(vn_i.subs(pt))
    d.confirm(
        [out.mu, out.v_n, out.S, out.Q],
        [mu_n, vn_n, -(1 + ee) * mu_n * vn_n, 0.5 * mu_n * (1 - ee**2) * vn_n**2],
        atol=RIGID_ATOL,
        route="mechanics.rigid_impact: μ, v_n, S and Q for a general 3-D pair",
    )

    def Tn(b):
        return 0.5 * b.m * np.dot(b.v_G, b.v_G) + 0.5 * np.dot(b.omega, np.asarray(b.J_G) @ b.omega)

    d.confirm(
        Tn(b1) + Tn(b2) - Tn(out.body_1) - Tn(out.body_2),
        0.5 * mu_n * (1 - ee**2) * vn_n**2,
        atol=RIGID_ATOL,
        route="kinetic energies of the bodies returned by mechanics.rigid_impact: T_i - T_f = Q",
    )
    vS = lambda b: np.asarray(b.v_G) + np.cross(b.omega, rS - np.asarray(b.r_G))  # noqa: E731
    d.confirm(
        np.dot(nn, vS(out.body_1) - vS(out.body_2)),
        -ee * vn_n,
        atol=RIGID_ATOL,
        route="normal relative velocity after mechanics.rigid_impact is -e v_n",
    )


@check(
    "thm.hinged-impact",
    "A body on a fixed axis struck by an impulse: Δω, the axis reaction and the energy loss",
    kind="proof",
    covers=("eq6.19", "eq6.21"),
    statement="axis e_z through O, inertia tensor J_O, impulse S at r_P: J_zz Δω = e_z·(r_P × S) "
    "(the frictionless axis has no moment about itself); the axis reaction R = m Δω e_z × r_G - S "
    "(6.19) and its moment M = Δω J_O e_z - r_P × S (6.21); with restitution e at P along n "
    "the loss is ½ μ_a (1 - e²) v_n², μ_a = J_zz/(n·(e_z × r_P))²",
)
def hinged_impact(d: Derivation) -> None:
    J = _sym_matrix("J")
    ez = vec(0, 0, 1)
    r_G, r_P, Sv = _vsym("r_G"), _vsym("r_P"), _vsym("S")
    w = sp.Symbol("omega", real=True)
    J_zz = J[2, 2]
    dw = ez.dot(cross(r_P, Sv)) / J_zz
    d.quantity("Delta_omega", dw)
    R = m * dw * cross(ez, r_G) - Sv
    M = dw * J * ez - cross(r_P, Sv)
    d.quantity("S_axis", R)
    d.quantity("M_axis", M)
    d.prove_equal(
        m * cross(ez * (w + dw), r_G) - m * cross(ez * w, r_G),
        Sv + R,
        strategy="cancel",
        claim="(6.19): m Δv_G = S + R",
    )
    d.prove_equal(
        J * ez * (w + dw) - J * ez * w,
        cross(r_P, Sv) + M,
        strategy="cancel",
        claim="(6.21) about O: ΔL_O = r_P × S + M (the axis passes through O)",
    )
    d.prove_equal(ez.dot(M), 0, strategy="cancel", claim="the axis takes no moment about itself")
    d.reject(
        ez.dot(dw * J * ez - cross(r_G, Sv)),
        0,
        strategy="cancel",
        claim="the same with the blow moved to G",
    )
    # restitution at P along n (a smooth contact with a fixed obstacle)
    nvec = vec(1, 0, 0)  # the normal along the first axis of the frame: r_P, J general
    S, e_ = sp.symbols("S_n e_P", real=True)
    arm = nvec.dot(cross(ez, r_P))
    v_n = w * arm
    dw_n = ez.dot(cross(r_P, S * nvec)) / J_zz
    d.prove_equal(
        (w + dw_n) * arm - v_n,
        S * arm**2 / J_zz,
        strategy="cancel",
        claim="v_n' - v_n = S/μ_a with μ_a = J_zz/(n·(e_z × r_P))²",
    )
    S_e = -(1 + e_) * v_n * J_zz / arm**2
    T = lambda om: J_zz * om**2 / 2  # noqa: E731
    Q = T(w) - T(w + dw_n.subs(S, S_e))
    d.prove_equal(
        Q,
        (1 - e_**2) * (J_zz / arm**2) * v_n**2 / 2,
        strategy="cancel",
        claim="Q = ½ μ_a (1 - e²) v_n² (the axis does no work)",
    )
    d.reject(
        Q,
        (1 - e_) * (J_zz / arm**2) * v_n**2 / 2,
        strategy="cancel",
        claim="Q = ½ μ_a (1 - e) v_n²",
    )
    # mechanics.hinged_impact and hinged_effective_mass against the formulas
    Jn = np.array([[1.3, 0.1, -0.2], [0.1, 1.7, 0.15], [-0.2, 0.15, 2.1]])
    mn, rG, rP, Sn, wn = 2.0, np.array([0.4, 0.3, -0.2]), np.array([0.6, -0.5, 0.8]), None, 1.1
    Sn = np.array([0.3, 1.2, -0.4])
    out = imp.hinged_impact(
        mn, Jn, rG, axis_point=[0, 0, 0], axis=[0, 0, 1], omega=wn, r_P=rP, S_P=Sn
    )
    pt = {m: mn, w: wn}
    names = sp.symbols("J11 J22 J33 J23 J13 J12", real=True)
    pt.update(
        dict(zip(names, (Jn[0, 0], Jn[1, 1], Jn[2, 2], Jn[1, 2], Jn[0, 2], Jn[0, 1]), strict=True))
    )
    for sym, val in ((r_G, rG), (r_P, rP), (Sv, Sn)):
        pt.update(dict(zip(sym, val, strict=True)))
    d.confirm(
        np.concatenate([[out.omega], out.S_axis, out.M_axis]),
        np.concatenate([[wn + float(dw.subs(pt))], floats(R, pt).ravel(), floats(M, pt).ravel()]),
        atol=RIGID_ATOL,
        route="mechanics.hinged_impact: ω after, axis reaction impulse and moment",
    )
    d.confirm(
        imp.hinged_effective_mass(Jn, rP, [1, 0, 0], axis_point=[0, 0, 0], axis=[0, 0, 1]),
        float((J_zz / arm**2).subs(pt)),
        atol=RIGID_ATOL,
        route="mechanics.hinged_effective_mass: μ_a = J_zz/(n·(e_z × r_P))²",
    )


@check(
    "thm.centre-of-percussion",
    "Centre of percussion: a blow at J_O/(m h) from the axis leaves the axis unloaded",
    kind="proof",
    covers=("eq6.19", "eq6.21"),
    statement="body on the axis e_z through O, G at (h, 0, 0); a blow S e_y at (x, 0, z): the axis "
    "reaction vanishes iff x = J_zz/(m h) = h + J_Gzz/(m h), and the reaction moment iff "
    "z = -x J_xz/J_zz and J_yz = 0 (J_xz, J_yz the off-diagonal entries of J_O)",
)
def centre_of_percussion(d: Derivation) -> None:
    J = _sym_matrix("J")
    h, x, z, S = sp.symbols("h x z S", real=True)
    ez = vec(0, 0, 1)
    r_G, r_P, Sv = vec(h, 0, 0), vec(x, 0, z), vec(0, S, 0)
    dw = ez.dot(cross(r_P, Sv)) / J[2, 2]
    R = m * dw * cross(ez, r_G) - Sv
    M = dw * J * ez - cross(r_P, Sv)
    x_p = J[2, 2] / (m * h)
    d.quantity("x_percussion", x_p)
    d.prove_equal(
        R.subs(x, x_p), sp.zeros(3, 1), strategy="cancel", claim="R = 0 at x = J_zz/(m h)"
    )
    d.reject(
        R.subs(x, h), sp.zeros(3, 1), strategy="cancel", claim="R = 0 for a blow at G's distance"
    )
    z_p = -x_p * J[0, 2] / J[2, 2]
    d.prove_equal(
        M.subs({x: x_p, z: z_p}),
        vec(0, dw.subs(x, x_p) * J[1, 2], 0),
        strategy="cancel",
        claim="M = Δω J_yz e_y at the centre of percussion: zero iff J_yz = 0",
    )
    J_G = sp.Symbol("J_Gzz", positive=True)
    d.confirm_exact(
        x_p.subs(J[2, 2], J_G + m * h**2),
        h + J_G / (m * h),
        strategy="cancel",
        route="parallel axes: J_zz = J_Gzz + m h² gives x = h + J_Gzz/(m h) > h",
    )
    ell = sp.Symbol("ell", positive=True)
    d.confirm_exact(
        x_p.subs({J[2, 2]: m * ell**2 / 3, h: ell / 2}),
        2 * ell / 3,
        strategy="cancel",
        route="a rod hinged at its end (Example 6.2): 2ℓ/3, where x_C(0) = 2ℓ/3 of (6.29) puts "
        "the point at rest when the blow is at the end",
    )
    Jn = np.array([[0.5, 0.0, 0.12], [0.0, 1.4, 0.0], [0.12, 0.0, 1.2]])
    mn, hn = 2.0, 0.4
    P, b = imp.centre_of_percussion(mn, Jn, [hn, 0, 0], axis_point=[0, 0, 0], axis=[0, 0, 1])
    d.confirm(
        np.concatenate([P, b]),
        [Jn[2, 2] / (mn * hn), 0.0, -Jn[0, 2] / (mn * hn), 0.0, 1.0, 0.0],
        atol=RIGID_ATOL,
        route="mechanics.centre_of_percussion: point (J_zz/(m h), 0, -J_xz/(m h)), direction e_y",
    )
    out = imp.hinged_impact(
        mn, Jn, [hn, 0, 0], axis_point=[0, 0, 0], axis=[0, 0, 1], omega=0.3, r_P=P, S_P=2.0 * b
    )
    d.confirm(
        np.concatenate([out.S_axis, out.M_axis]),
        np.zeros(6),
        atol=RIGID_ATOL,
        route="mechanics.hinged_impact: a blow at the centre of percussion loads the axis with "
        "no impulse and no moment",
    )
