"""Chapter 6 problems 6.1–6.6, derived symbolically in the book's symbols and each
confirmed by an independent route (a scipy simulation, :mod:`mechanics.impact`, a
second derivation, a limit).  The book's answers are withheld; these are derived here.
Numeric problems report their numbers with units (``sympy.physics.units``).
"""

from __future__ import annotations

import numpy as np
import sympy as sp
from scipy.integrate import solve_ivp
from scipy.optimize import brentq
from sympy.physics import units as u

from identities.book.ch06.restitution import (
    SIM_RTOL,
    direct_impact_symbolic,
    spring_dashpot_collision,
    xdot_1i,
    xdot_2i,
)
from identities.book.ch06.restitution import e as e_r
from identities.book.ch06.restitution import m_1 as m_1r
from identities.book.ch06.restitution import m_2 as m_2r
from identities.verify.catalogue import check
from identities.verify.proof import Derivation
from identities.verify.symbolic import cross, vec
from mechanics import impact as imp
from mechanics._floats import EPS

#: float evaluation of a few products and quotients of O(1) numbers: 64 eps.
NUM_ATOL = 64 * EPS
#: scipy event location with rtol 1e-12 on O(1) times: the threshold found by bisection on
#: simulated landing times is good to ~1e-9 relative; 2^24 eps ≈ 3.7e-9.
EVENT_RTOL = 2**24 * EPS

ex, ey, ez = vec(1, 0, 0), vec(0, 1, 0), vec(0, 0, 1)
knot = sp.Rational(1852, 3600) * u.meter / u.second  # 1 knot = 1852 m/h
tonne = 1000 * u.kilogram


def _si(q) -> float:
    q = u.convert_to(q, [u.meter, u.kilogram, u.second])
    return float(q.subs({u.meter: 1, u.kilogram: 1, u.second: 1}))


# ----------------------------------------------------------------------------- 6.1
def _rod_flight(omega0, ell, g, vx=0.0):
    """Free flight of a rod that leaves the ground standing (G at ℓ/2, vertical), turning at
    ω0: scipy integrates ẍ_G = 0, ÿ_G = -g, θ̈ = 0 and returns the first downward
    crossing of y = 0 by the top end and by the bottom end (times)."""

    def rhs(_t, y):
        return [y[3], y[4], y[5], 0.0, -g, 0.0]

    def bottom(_t, y):
        return y[1] - ell / 2 * np.cos(y[2])

    def top(_t, y):
        return y[1] + ell / 2 * np.cos(y[2])

    bottom.direction = top.direction = -1
    bottom.terminal = top.terminal = False
    t_max = 4 * np.sqrt(ell / g) + 4 * np.pi / abs(omega0)
    sol = solve_ivp(
        rhs,
        (0.0, t_max),
        [0.0, ell / 2, 0.0, vx, 0.0, omega0],
        method="DOP853",
        rtol=1e-12,
        atol=1e-14,
        events=(top, bottom),
    )
    t_top = sol.t_events[0][0] if sol.t_events[0].size else np.inf
    t_bot = [t for t in sol.t_events[1] if t > 1e-9]
    return t_top, (t_bot[0] if t_bot else np.inf)


@check(
    "P6.1",
    "Problem 6.1: a standing rod struck horizontally: when does its top end land first?",
    kind="derivation",
    covers=("P6.1",),
    statement="rod m = 75 kg, ℓ = 180 cm standing on the ground, horizontal impulse S at height "
    "h: the top end lands first iff the rod leaves the ground at once and turns past the "
    "horizontal before landing: ω0² > π² g/(4ℓ), i.e. S |h - ℓ/2| > π m √(g ℓ³)/24",
    reading="the ground gives no impulse (the struck rod's foot moves horizontally), so v_G = "
    "S/m, ω0 = 12 S (h - ℓ/2)/(m ℓ²); for ω0² > 2g/ℓ the foot lifts off at once (free flight: "
    "friction is irrelevant); g = 9.81 m/s².",
)
def problem_6_1(d: Derivation) -> None:
    m, ell, g, S = sp.symbols("m ell g S", positive=True)
    h, s = sp.symbols("h s", real=True)
    w0 = sp.Symbol("omega_0", positive=True)
    J_G = m * ell**2 / 12
    omega = S * (h - ell / 2) / J_G  # (6.21) about G, about the horizontal axis
    d.quantity("v_G", S / m)
    d.quantity("omega_0", omega)
    foot = (S / m) * ex + cross(omega * ez, -(ell / 2) * ey)
    d.prove_equal(
        foot[1], 0, strategy="expand", claim="the foot moves horizontally: no ground impulse"
    )
    # free flight: height of G ℓ/2 - g t²/2, angle s = ω0 t; the lower end
    lower = ell / 2 * (1 - sp.cos(s)) - g * s**2 / (2 * w0**2)  # the foot, 0 ≤ s ≤ π/2
    d.prove_equal(
        sp.diff(lower, s, 2).subs(s, 0),
        ell / 2 - g / w0**2,
        strategy="expand",
        claim="the foot rises at once iff ω0² > 2g/ℓ (its initial acceleration is ℓ ω0²/2 - g)",
    )
    flat = lower.subs(s, sp.pi / 2)
    threshold = sp.pi**2 * g / (4 * ell)
    d.prove_equal(
        flat.subs(w0, sp.sqrt(threshold)),
        0,
        strategy="expand",
        claim="the rod is horizontal exactly on the ground when ω0² = π² g/(4ℓ)",
    )
    d.reject(
        flat.subs(w0, sp.sqrt(2 * g / ell)),
        0,
        strategy="expand",
        claim="the lift-off threshold ω0² = 2g/ℓ is the landing threshold",
    )
    d.note(
        "(1 - cos s)/s² decreases on (0, π/2], so the foot stays above the ground until the "
        "rod is horizontal iff it is above the ground then: ω0² > π² g/(4ℓ) > 2g/ℓ; after "
        "that the top end is the lower one and lands (before s = π) first"
    )
    S_min = sp.pi * m * sp.sqrt(g * ell**3) / (24 * sp.Abs(h - ell / 2))
    d.quantity("condition", sp.Gt(S * sp.Abs(h - ell / 2), sp.pi * m * sp.sqrt(g * ell**3) / 24))
    d.quantity("S_min", S_min)
    d.prove_equal(
        (omega**2).subs(S, S_min),
        threshold,
        strategy="expand",
        claim="S = S_min(h) gives ω0² = π² g/(4ℓ)",
    )
    nums = {m: 75, ell: sp.Rational(18, 10), g: sp.Rational(981, 100)}
    product = (sp.pi * m * sp.sqrt(g * ell**3) / 24).subs(nums)
    d.quantity("S_times_lever_min", product.evalf(4) * u.newton * u.second * u.meter)
    d.quantity(
        "S_min_at_top", S_min.subs(nums).subs(h, sp.Rational(18, 10)).evalf(4) * u.newton * u.second
    )
    # dimensions: [S][L] = M L T⁻¹ L and m √(g ℓ³) = M (L T⁻² L³)^½ = M L² T⁻¹
    dims = {m: u.kilogram, ell: u.meter, g: u.meter / u.second**2}
    d.confirm_exact(
        sp.simplify((sp.sqrt(g * ell**3) * m).subs(dims) / (u.kilogram * u.meter**2 / u.second)),
        1,
        route="dimensions: π m √(g ℓ³)/24 is an impulse times a length (kg m² s⁻¹)",
    )
    # simulation: which end lands first, and the threshold found by bisection on the landings
    mn, ln, gn, hn = 75.0, 1.8, 9.81, 1.8
    S_formula = float(S_min.subs(nums).subs(h, hn))

    def w_of(Sv):
        return 12 * Sv * (hn - ln / 2) / (mn * ln**2)

    t_top, t_bot = _rod_flight(w_of(1.02 * S_formula), ln, gn)
    d.confirm(
        float(t_top < t_bot),
        1.0,
        atol=0.0,
        route="scipy free flight: at 1.02 S_min the top lands first",
    )
    t_top, t_bot = _rod_flight(w_of(0.98 * S_formula), ln, gn)
    d.confirm(
        float(t_bot < t_top),
        1.0,
        atol=0.0,
        route="scipy free flight: at 0.98 S_min the foot lands first",
    )
    S_sim = brentq(
        lambda Sv: np.subtract(*_rod_flight(w_of(Sv), ln, gn)),
        0.95 * S_formula,  # 0.95² π²/4 > 2: the rod still lifts off at once
        1.05 * S_formula,
        xtol=1e-12 * S_formula,
    )
    d.confirm(
        S_sim,
        S_formula,
        atol=EVENT_RTOL * S_formula,
        route=f"bisection on simulated landing times: S_min(h = ℓ) = {S_sim:.6f} N s",
    )


# ----------------------------------------------------------------------------- 6.2
@check(
    "P6.2",
    "Problem 6.2: a tugboat jerks a ship into motion through a rope (an impact with e = 0.5)",
    kind="derivation",
    covers=("P6.2",),
    errata=("P6.2",),
    statement="tug 800 t at 3 knots, ship 23000 t at rest, e = 0.5: the ship's speed after, "
    "and the mean rope force while the rope spurts water (its tension rising, the "
    "compression phase of Example 6.3, lasting 1.5 s) as a mass K_av/g",
    printed="g = 9.8 kg/s²",
    corrected="g = 9.8 m/s² (K_av divided by kg/s² would be a length, not a mass)",
    reading="b) asks for 'the average force in the rope while it spurts water if this goes on "
    "for 1.5 s': a wet rope spurts water while it is being stretched, that is while its "
    "tension increases, which is the compression phase [−δ₁, 0] of Example 6.3 (the bodies' "
    "relative velocity along the rope falls to zero); while the tension falls the rope "
    "shortens and spurts no more.  So Δt = δ₁ = 1.5 s and K_av = S₁/Δt with S₁ the "
    "compression impulse.  The other reading, the whole impulse S = S₁ + S₂ averaged over "
    "1.5 s, is kept below as a labelled variant; it is (1 + e) times larger.  The rope "
    "(375 kg, 1.6e-5 of the total) is neglected; its effect is shown below 1e-3.  3 knots = "
    "5.556 km/h (the book rounds to 5.5 km/h); 1 knot = 1852 m/h.  The rope reverses the "
    "relative velocity of tug and ship: (6.37)-(6.38) with body 1 the tug.",
)
def problem_6_2(d: Derivation) -> None:
    m_t, m_s, v_0, e, dt = sp.symbols("m_t m_s v_0 e Delta_t", positive=True)
    v1f, v2f = direct_impact_symbolic()
    sub = {m_1r: m_t, m_2r: m_s, xdot_1i: v_0, xdot_2i: 0, e_r: e}
    v_ship, v_tug = sp.factor(v2f.subs(sub)), sp.factor(v1f.subs(sub))
    d.quantity("v_ship", v_ship)
    d.quantity("v_tug", v_tug)
    d.prove_equal(v_ship, (1 + e) * m_t * v_0 / (m_t + m_s), strategy="cancel", claim="v_ship")
    d.reject(v_ship, m_t * v_0 / (m_t + m_s), strategy="cancel", claim="a plastic jerk (e = 0)")
    S = m_s * v_ship  # (6.19) for the ship: the whole impulse of the rope on it
    S_1 = d.quantity("S_1", sp.factor(S / (1 + e)))  # (6.42): S₂ = e S₁, so S = (1 + e) S₁
    d.prove_equal(
        S_1,
        m_s * v2f.subs(sub).subs(e, 0),
        strategy="cancel",
        claim="S₁ = m_s v_c: at the end of compression the two move together with the plastic "
        "impact's common velocity v_c = m_t v_0/(m_t + m_s)",
    )
    K_av = d.quantity("K_av", S_1 / dt)  # (6.6) over the compression phase
    d.reject(K_av, S / dt, strategy="cancel", claim="the whole impulse over the 1.5 s (variant)")
    nums = {m_t: 800 * tonne, m_s: 23000 * tonne, v_0: 3 * knot, e: sp.Rational(1, 2)}
    ship = v_ship.subs(nums)
    d.quantity("v_ship_knots", sp.nsimplify(ship / knot) * sp.Symbol("knot"))
    d.prove_equal(
        ship / knot, sp.Rational(18, 119), strategy="expand", claim="v_ship = 18/119 knot"
    )
    tug = v_tug.subs(nums)
    d.quantity("v_tug_knots", sp.nsimplify(tug / knot) * sp.Symbol("knot"))
    d.prove_equal(
        tug / knot, sp.Rational(-321, 238), strategy="expand", claim="the tug recoils at 1.35 knots"
    )

    def newtons(force):
        return u.convert_to(force.subs(nums).subs(dt, sp.Rational(3, 2) * u.second), u.newton)

    F_N = newtons(K_av) / u.newton
    d.prove_equal(
        F_N,
        sp.Rational(23 * 10**6 * 12 * 1852, 119 * 3600) / sp.Rational(3, 2),
        strategy="expand",
        claim="K_av = m_s v_c/Δt in newtons, with v_c = (12/119)(1852/3600) m/s",
    )
    F_si = float(F_N)
    d.quantity("K_av_value", sp.Float(F_si, 4) * u.newton)
    mass_eq = sp.Rational(F_N) / sp.Rational(98, 10)  # kg, with g = 9.8 m/s²
    d.quantity("K_av_over_g", sp.Float(float(mass_eq) / 1000, 4) * tonne)
    # variant: the whole impulse averaged over the same 1.5 s
    d.note(
        "variant, not the book's reading: averaged over the whole impact, K_av' = S/Δt; by "
        "(6.42) S = S₁ + S₂ = (1 + e) S₁, so over the same Δt the two averages differ by the "
        "factor 1 + e (the restitution phase's impulse e S₁ is added)"
    )
    K_whole = d.quantity("K_av_variant_whole_impact", S / dt)
    d.prove_equal(K_whole / K_av, 1 + e, strategy="cancel", claim="K_av' / K_av = 1 + e")
    F_whole_N = newtons(K_whole) / u.newton
    F_whole = float(F_whole_N)
    d.quantity("K_av_variant_whole_impact_value", sp.Float(F_whole, 4) * u.newton)
    mass_whole = sp.Rational(F_whole_N) / sp.Rational(98, 10)
    d.quantity("K_av_variant_whole_impact_over_g", sp.Float(float(mass_whole) / 1000, 4) * tonne)
    # the quoted values are rounded: each within half a unit of its last digit
    for value, quoted, half_unit, what in (
        (float(ship / knot), 0.1513, 0.5e-4, "v_ship = 0.1513 knot"),
        (F_si, 7.954e5, 0.5e2, "K_av = 7.954e5 N"),
        (float(mass_eq) / 1e3, 81.17, 0.005, "K_av/g = 81.17 t"),
        (F_whole, 1.193e6, 0.5e3, "variant: K_av' = 1.193e6 N"),
        (float(mass_whole) / 1e3, 121.8, 0.05, "variant: K_av'/g = 121.8 t"),
    ):
        d.numeric_close(value, quoted, atol=half_unit, claim=f"as quoted: {what}")

    # the printed unit of g: exponents of (kg, m, s) of a product of powers of units
    def dim(q):
        powers = sp.sympify(q).as_powers_dict()
        return sp.Matrix([powers.get(b, 0) for b in (u.kilogram, u.meter, u.second)])

    newton_si = u.kilogram * u.meter / u.second**2
    d.refute(
        dim(newton_si / (u.kilogram / u.second**2)),
        dim(u.kilogram),
        claim="K_av/g with g in kg/s² (printed) is a mass",
    )
    d.prove_equal(
        dim(newton_si / (u.meter / u.second**2)),
        dim(u.kilogram),
        strategy="expand",
        claim="with g in m/s², K_av/g is a mass",
    )
    # independent routes
    mt, ms, v0 = 800e3, 23e6, _si(3 * knot)
    a1, a2 = imp.direct_impact(mt, ms, v0, 0.0, 0.5)
    d.confirm(
        [a2 / 0.5144444444444445, a1 / 0.5144444444444445],
        [18 / 119, -321 / 238],
        atol=NUM_ATOL,
        route="mechanics.direct_impact(tug, ship): speeds in knots",
    )
    v_c = imp.direct_impact(mt, ms, v0, 0.0, 0.0)[1]
    d.confirm(
        ms * v_c / 1.5,
        F_si,
        atol=NUM_ATOL * F_si,
        route="mechanics.direct_impact with e = 0 (the state at maximal stretch): m_s v_c/1.5 s",
    )
    # the rope as a spring–dashpot set to e = 0.5; the contact time is scaled so that the
    # phase of rising tension (to the maximal stretch) lasts 1.5 s (a linear contact's phases
    # scale with its time)
    tau_1 = spring_dashpot_collision(mt, ms, v0, 0.0, 0.5, 1.5)["tau_1"]
    sim = spring_dashpot_collision(mt, ms, v0, 0.0, 0.5, 1.5 * 1.5 / tau_1)
    d.confirm(
        [sim["v2f"] / _si(ship), abs(sim["S_1"]) / sim["tau_1"] / F_si, sim["tau_1"] / 1.5],
        [1.0, 1.0, 1.0],
        atol=SIM_RTOL,
        route="scipy: the rope as a spring–dashpot (set to e = 0.5) whose tension rises for "
        "1.5 s: ship speed, mean force while the tension rises, that phase's length",
    )
    whole = spring_dashpot_collision(mt, ms, v0, 0.0, 0.5, 1.5)
    d.confirm(
        abs(whole["impulse"]) / whole["tau"] / F_whole,
        1.0,
        atol=SIM_RTOL,
        route="scipy, variant: the same rope taut for 1.5 s in all: mean force over the impact",
    )
    with_rope = imp.direct_impact(mt + 375.0, ms, v0, 0.0, 0.5)[1]
    d.confirm(
        abs(with_rope / a2 - 1) < 1e-3,
        True,
        atol=0,
        route="adding the rope's 375 kg to the tug changes v_ship by < 1e-3 (relative; 375/800000 ≈ 5e-4)",
    )
    d.confirm_exact(
        sp.limit(v_ship, m_s, sp.oo),
        0,
        route="limit: an immovable ship does not move",
    )


# ----------------------------------------------------------------------------- 6.3
@check(
    "P6.3",
    "Problem 6.3: a bat turning about its handle hits a ball at rest at distance x",
    kind="derivation",
    covers=("P6.3",),
    statement="angular momentum about the handle axis J ω = J ω' + m v x and restitution "
    "v - ω' x = e ω x give v = (1 + e) J ω x/(J + m x²) ≤ (1 + e) ω x; the bound (1 + e) ω x "
    "is the maximal speed (a light ball, m x² ≪ J)",
    reading="the ball's mass, not given, is named m; 'the maximal speed as a function of x' is "
    "read as the largest speed over ball masses, v_max(x) = (1 + e) ω x (0 < x ≤ ℓ).  For a "
    "given m the best x is √(J/m) (if ≤ ℓ), v = (1 + e) ω √(J/m)/2.",
)
def problem_6_3(d: Derivation) -> None:
    J, m = sp.symbols("J m", positive=True)
    x, omega = sp.symbols("x omega", positive=True)
    e = sp.Symbol("e", nonnegative=True)
    v, w1 = sp.symbols("v omega_1", real=True)
    sol = sp.solve(
        [sp.Eq(J * omega, J * w1 + m * v * x), sp.Eq(v - w1 * x, e * omega * x)], [v, w1], dict=True
    )[0]
    v_ball = sp.factor(sol[v])
    d.quantity("v_ball", v_ball)
    d.quantity("omega_after", sp.factor(sol[w1]))
    d.prove_equal(v_ball, (1 + e) * J * omega * x / (J + m * x**2), strategy="cancel", claim="v(x)")
    v_max = (1 + e) * omega * x
    d.quantity("v_max", v_max)
    d.prove_equal(
        v_max - v_ball,
        (1 + e) * omega * x * m * x**2 / (J + m * x**2),
        strategy="cancel",
        claim="v_max - v = (1 + e) ω x · m x²/(J + m x²) ≥ 0: v < (1 + e) ω x for every ball",
    )
    d.confirm_exact(sp.limit(v_ball, m, 0), v_max, route="limit m → 0 attains (1 + e) ω x")
    d.reject(
        v_ball,
        (1 + e) * omega * x / 2,
        strategy="cancel",
        claim="the equal-mass free-body result (1 + e) ω x/2",
    )
    x_best = sp.sqrt(J / m)
    d.quantity("x_best", x_best)
    d.prove_equal(
        sp.diff(v_ball, x).subs(x, x_best), 0, strategy="cancel", claim="dv/dx = 0 at √(J/m)"
    )
    d.quantity("v_best", sp.simplify(v_ball.subs(x, x_best)))
    d.prove_equal(
        v_ball.subs(x, x_best),
        v_max.subs(x, x_best) / 2,
        strategy="cancel",
        claim="v(√(J/m)) = (1+e) ω √(J/m)/2",
    )
    # independent routes
    T_before = J * omega**2 / 2
    T_after = (J * sol[w1] ** 2 + m * sol[v] ** 2) / 2
    d.confirm_exact(
        (T_before - T_after).subs(e, 1), 0, strategy="cancel", route="e = 1 conserves the energy"
    )
    Jn, mn, xn, wn, en = 0.25, 0.145, 0.7, 30.0, 0.55
    mu_a = imp.hinged_effective_mass(
        np.diag([Jn, Jn, Jn]), [xn, 0, 0], [0, 1, 0], axis_point=[0, 0, 0], axis=[0, 0, 1]
    )
    _, vb = imp.direct_impact(mu_a, mn, wn * xn, 0.0, en)
    d.confirm(
        vb,
        float(v_ball.subs({J: Jn, m: mn, x: xn, omega: wn, e: en})),
        atol=NUM_ATOL * wn * xn,
        route="mechanics: hinged_effective_mass J/x² at x, then direct_impact with the ball",
    )


# ----------------------------------------------------------------------------- 6.4
def _ball_sliding(v0, omega0, r, J_over_m, mu_k, g):
    """A ball sliding on the ground with Coulomb friction μ_k g until it rolls (scipy)."""

    def slip(_t, y):
        return y[0] + y[1] * r  # contact-point velocity, ω about e_z (rolling: ω = -v/r)

    def rhs(t, y):
        f = -np.sign(slip(t, y)) * mu_k * g  # friction per unit mass, on the contact point
        return [f, f * r / J_over_m]  # dv/dt, dω/dt: torque (−r e_y) × (f e_x) = f r e_z

    slip.terminal = True
    sol = solve_ivp(
        rhs, (0.0, 100.0), [v0, omega0], method="DOP853", rtol=1e-12, atol=1e-14, events=slip
    )
    return sol.y[:, -1]


@check(
    "P6.4",
    "Problem 6.4: a kicked football (a spherical shell): pure translation, then rolling",
    kind="derivation",
    covers=("P6.4",),
    statement="a) the kick leaves no rotation iff its line passes through G: h = r; "
    "b) angular momentum about the ground line is conserved while it slides, so it rolls at "
    "v = 3 S h/(5 m r); the kinetic energy kept is 6h²/(5(2r² + 3(h - r)²)), 3/5 for h = r",
    reading="b) is answered for the kick of a) (h = r) and also for any h",
)
def problem_6_4(d: Derivation) -> None:
    m, r, S = sp.symbols("m r S", positive=True)
    h, th, ph = sp.symbols("h theta phi", real=True)
    # J_G of a uniform spherical shell, ∫ (x² + y²) dm over the sphere
    sigma = m / (4 * sp.pi * r**2)
    J_G = sp.integrate(
        sp.integrate(sigma * (r * sp.sin(th)) ** 2 * r**2 * sp.sin(th), (th, 0, sp.pi)),
        (ph, 0, 2 * sp.pi),
    )
    d.prove_equal(J_G, 2 * m * r**2 / 3, strategy="expand", claim="J_G = (2/3) m r² (shell)")
    v0 = S / m
    w0 = -(h - r) * S / J_G  # ω about e_z; moment (h - r) e_y × S e_x
    d.quantity("omega_0", w0)
    d.quantity("h_translation", r)
    d.prove_equal(w0.subs(h, r), 0, strategy="expand", claim="a) no rotation when h = r")
    d.reject(w0.subs(h, 2 * r / 3), 0, strategy="expand", claim="a) h = 2r/3")
    vf = sp.Symbol("v_f", real=True)
    L = lambda v, w: -m * r * v + J_G * w  # noqa: E731  about a fixed point of the ground line
    v_roll = sp.solve(sp.Eq(L(vf, -vf / r), L(v0, w0)), vf)[0]
    d.quantity("v_rolling", v_roll)
    d.prove_equal(v_roll, 3 * S * h / (5 * m * r), strategy="cancel", claim="v = 3 S h/(5 m r)")
    T0 = m * v0**2 / 2 + J_G * w0**2 / 2
    Tf = m * v_roll**2 / 2 + J_G * (v_roll / r) ** 2 / 2
    frac = sp.factor(Tf / T0)
    d.quantity("fraction", frac)
    d.prove_equal(
        frac, 6 * h**2 / (5 * (2 * r**2 + 3 * (h - r) ** 2)), strategy="cancel", claim="T_f/T_0"
    )
    d.quantity("fraction_translation", frac.subs(h, r))
    d.prove_equal(frac.subs(h, r), sp.Rational(3, 5), strategy="cancel", claim="b) 3/5 for h = r")
    d.reject(
        frac.subs(h, r),
        sp.Rational(5, 7),
        strategy="cancel",
        claim="5/7 (the solid ball's value, J = (2/5) m r²)",
    )
    d.confirm_exact(
        frac.subs(h, 5 * r / 3),
        1,
        strategy="cancel",
        route="limit: a kick at 5r/3 makes it roll at once, nothing is lost",
    )
    # simulation with Coulomb friction (any μ_k) until the slip stops
    mn, rn, Sn, g = 0.43, 0.11, 2.0, 9.81
    for hn in (0.11, 0.05, 0.2):
        vf_n, wf_n = _ball_sliding(
            Sn / mn, -(hn - rn) * Sn / (2 / 3 * mn * rn**2), rn, 2 / 3 * rn**2, 0.3, g
        )
        T0n = (
            0.5 * mn * (Sn / mn) ** 2
            + 0.5 * (2 / 3 * mn * rn**2) * ((hn - rn) * Sn / (2 / 3 * mn * rn**2)) ** 2
        )
        Tfn = 0.5 * mn * vf_n**2 + 0.5 * (2 / 3 * mn * rn**2) * wf_n**2
        d.confirm(
            Tfn / T0n,
            float(frac.subs({r: rn, h: hn})),
            atol=2**20 * EPS,  # event location at rtol 1e-12 in a velocity of O(1): ~1e-10
            route=f"scipy: a shell sliding with Coulomb friction μ = 0.3 until it rolls, h = {hn} m",
        )


# ----------------------------------------------------------------------------- 6.5
@check(
    "P6.5",
    "Problem 6.5: a door stopped by a door stop: reaction impulses at the hinges",
    kind="derivation",
    covers=("P6.5",),
    statement="door h = 2 m, b = 0.8 m, hinges A (upper) and B (lower) at ±d = ±0.75 m from "
    "the middle, turning at ω, stopped by a blow S_C at distance y along the lower edge: "
    "S_C = m b² ω/(3y), S_A = m ω b (3y - 2b + h b/d)/(12 y), S_B = m ω b (3y - 2b - h b/d)/(12 y)",
    reading="X normal to the door, Y along its width from the axis, Z up the axis from the "
    "height of G; impulses are X-components, positive along S_C (against the door's motion).  "
    "b) S_B = 0 needs y = 14b/9 > b (off the door), S_A ≠ 0: no.  c) |S_A| = |S_B| at "
    "y = 2b/3 (the centre of percussion), where S_A = -S_B = m ω h b/(8d).",
)
def problem_6_5(d: Derivation) -> None:
    m, h, b, dd, y, omega = sp.symbols("m h b d y omega", positive=True)
    S_A, S_B, S_C = sp.symbols("S_A S_B S_C", real=True)
    # inertia about O (on the axis at the height of G): a lamina in the plane x = 0
    Y, Z = sp.symbols("Y Z", real=True)
    rho = m / (b * h)
    J = lambda f: sp.integrate(sp.integrate(rho * f, (Y, 0, b)), (Z, -h / 2, h / 2))  # noqa: E731
    J_O = sp.Matrix([[J(Y**2 + Z**2), 0, 0], [0, J(Z**2), -J(Y * Z)], [0, -J(Y * Z), J(Y**2)]])
    d.prove_equal(
        J_O * ez, vec(0, 0, m * b**2 / 3), strategy="expand", claim="J_O e_z = (m b²/3) e_z"
    )
    r_A, r_B, r_C = vec(0, 0, dd), vec(0, 0, -dd), vec(0, y, -h / 2)
    impulses = ((r_A, S_A * ex), (r_B, S_B * ex), (r_C, S_C * ex))
    dp = m * (sp.zeros(3, 1) - cross(omega * ez, vec(0, b / 2, 0)))  # the door stops
    dL = J_O * (sp.zeros(3, 1) - omega * ez)
    eqs = list(dp - sum((Si for _, Si in impulses), sp.zeros(3, 1)))
    eqs += list(dL - sum((cross(ri, Si) for ri, Si in impulses), sp.zeros(3, 1)))
    sol = sp.solve([q for q in eqs if q != 0], [S_A, S_B, S_C], dict=True)
    if len(sol) != 1:
        raise AssertionError(f"expected one solution, got {sol}")
    sA, sB, sC = (sp.factor(sol[0][k]) for k in (S_A, S_B, S_C))
    d.quantity("S_C", sC)
    d.quantity("S_A", sA)
    d.quantity("S_B", sB)
    d.prove_equal(sC, m * b**2 * omega / (3 * y), strategy="cancel", claim="S_C")
    d.prove_equal(
        sA, m * omega * b * (3 * y - 2 * b + h * b / dd) / (12 * y), strategy="cancel", claim="S_A"
    )
    d.prove_equal(
        sB, m * omega * b * (3 * y - 2 * b - h * b / dd) / (12 * y), strategy="cancel", claim="S_B"
    )
    d.reject(sA, sB, strategy="cancel", claim="equal hinge impulses for every y")
    nums = {h: 2, b: sp.Rational(4, 5), dd: sp.Rational(3, 4)}
    d.quantity("S_A_door", sp.factor(sA.subs(nums)))
    d.quantity("S_B_door", sp.factor(sB.subs(nums)))
    yB = sp.solve(sB.subs(nums), y)
    d.quantity("y_for_S_B_zero", yB[0] * u.meter)
    d.prove_equal(
        yB[0],
        sp.Rational(14, 9) * sp.Rational(4, 5),
        strategy="expand",
        claim="b) S_B = 0 only at y = 14b/9 = 1.244 m > b",
    )
    d.quantity("S_B_can_vanish", sp.false)
    yC = sp.solve(sp.Eq(sA + sB, 0), y)[0]
    d.quantity("y_equal_magnitudes", yC.subs(nums) * u.meter)
    d.prove_equal(yC, 2 * b / 3, strategy="cancel", claim="c) S_A = -S_B at y = 2b/3")
    d.quantity("S_A_at_equal", sp.factor(sA.subs(y, yC)))
    d.prove_equal(
        sA.subs(y, yC),
        m * omega * h * b / (8 * dd),
        strategy="cancel",
        claim="c) |S_A| = |S_B| = m ω h b/(8d)",
    )
    # second derivation: moments about the lower hinge B (product of inertia J_yz^B ≠ 0 there)
    J_B_yz = -sp.integrate(sp.integrate(rho * Y * (Z + dd), (Y, 0, b)), (Z, -h / 2, h / 2))
    d.confirm_exact(
        2 * dd * sA + (dd - h / 2) * sC,
        J_B_yz * (0 - omega),
        strategy="cancel",
        route="moments about the lower hinge B: 2d S_A + (d - h/2) S_C = ΔL_B,y = J_yz^B Δω",
    )
    # mechanics.hinged_impact with two bearings
    mn, wn, yn = 12.0, 2.0, 0.5
    J_num = np.array(sp.Matrix(J_O).subs({**nums, m: mn}).evalf(20).tolist(), dtype=float)
    Sc = float(sC.subs({**nums, m: mn, omega: wn, y: yn}))
    out = imp.hinged_impact(
        mn,
        J_num,
        [0, 0.4, 0],
        axis_point=[0, 0, 0],
        axis=[0, 0, 1],
        omega=wn,
        r_P=[0, yn, -1.0],
        S_P=[Sc, 0, 0],
        bearings=(0.75, -0.75),
    )
    d.confirm(
        [out.omega, out.S_bearings[0, 0], out.S_bearings[1, 0]],
        [
            0.0,
            float(sA.subs({**nums, m: mn, omega: wn, y: yn})),
            float(sB.subs({**nums, m: mn, omega: wn, y: yn})),
        ],
        atol=NUM_ATOL * mn * wn,
        route="mechanics.hinged_impact with bearings at ±0.75 m: the door stops; S_A, S_B",
    )


# ----------------------------------------------------------------------------- 6.6
@check(
    "P6.6",
    "Problem 6.6: two hinged rods, AB on a track, an impulse S at A: the hinge impulse",
    kind="derivation",
    covers=("P6.6",),
    statement="AB (mass m_1) slides only along its own line; BC (mass m_2, length ℓ) makes the "
    "angle β with AB; S at A at the angle α: the impulse of AB on BC at B is "
    "R = S m_2 cos α [(1 + 3cos²β) e_AB + 3 sin β cos β e_⊥]/(4 m_1 + m_2 (1 + 3cos²β)); "
    "β = 0 (rods in line): R = m_2 S cos α/(m_1 + m_2) along the rods",
    reading="the figure is lost: the angle β between the rods is kept general (the track "
    "along AB takes the component S sin α and any moment on AB); e_AB points from A to B.",
)
def problem_6_6(d: Derivation) -> None:
    m_1, m_2, ell, S = sp.symbols("m_1 m_2 ell S", positive=True)
    alpha, beta = sp.symbols("alpha beta", real=True)
    u_, vx, vy, w, Rx, Ry = sp.symbols("u v_x v_y omega R_x R_y", real=True)
    T = sp.Symbol("T", real=True)  # T = tan(β/2): the solve stays rational (fast)
    c = vec((1 - T**2) / (1 + T**2), 2 * T / (1 + T**2), 0)
    R, vG = vec(Rx, Ry, 0), vec(vx, vy, 0)
    arm = -(ell / 2) * c  # from G_2 to B
    eqs = list(m_2 * vG - R)[:2]  # (6.19) for BC
    eqs += [m_2 * ell**2 / 12 * w - cross(arm, R)[2]]  # (6.21) about G_2
    vB = vG + cross(w * ez, arm)
    eqs += [vB[0] - u_, vB[1]]  # the hinge: B moves with AB, along the track
    eqs += [m_1 * u_ - (S * sp.cos(alpha) - Rx)]  # (6.19) for AB along the track
    sol = sp.solve(eqs, [u_, vx, vy, w, Rx, Ry], dict=True)[0]
    den = 4 * m_1 + m_2 * (1 + 3 * sp.cos(beta) ** 2)
    Rx_b = S * m_2 * sp.cos(alpha) * (1 + 3 * sp.cos(beta) ** 2) / den
    Ry_b = 3 * S * m_2 * sp.cos(alpha) * sp.sin(beta) * sp.cos(beta) / den
    d.quantity("R_x", Rx_b)
    d.quantity("R_y", Ry_b)
    to_T = {sp.cos(beta): c[0], sp.sin(beta): c[1]}
    d.prove_equal(sol[Rx], Rx_b.subs(to_T), strategy="cancel", claim="R along AB")
    d.prove_equal(sol[Ry], Ry_b.subs(to_T), strategy="cancel", claim="R across AB")
    R_line = m_2 * S * sp.cos(alpha) / (m_1 + m_2)
    d.quantity("R_in_line", R_line)
    d.prove_equal(
        Rx_b.subs(beta, 0), R_line, strategy="cancel", claim="β = 0: R = m_2 S cos α/(m_1 + m_2)"
    )
    d.prove_equal(Ry_b.subs(beta, 0), 0, strategy="expand", claim="β = 0: no transverse part")
    d.quantity("R_perpendicular", sp.factor(Rx_b.subs(beta, sp.pi / 2)))
    d.reject(
        Rx_b.subs(beta, 0),
        m_2 * S / (m_1 + m_2),
        strategy="cancel",
        claim="the whole impulse S, not S cos α, drives the rods",
    )
    d.reject(
        Rx_b.subs(beta, sp.pi / 2),
        R_line,
        strategy="cancel",
        claim="a perpendicular BC reacts like one in line",
    )
    # independent route: Lagrange's impulsive equations M Δq̇ = Q in q = (x_A, β) (numpy)
    m1n, m2n, ln, Sn, an, bn = 1.3, 0.8, 0.9, 2.0, 0.6, 0.7
    cb, sb = np.cos(bn), np.sin(bn)
    # v_G2 = (u, 0) + β̇ (ℓ/2)(-sin β, cos β); T = ½ m_1 u² + ½ m_2 |v_G2|² + ½ (m_2 ℓ²/12) β̇²
    Jv = np.array([[1.0, -ln / 2 * sb], [0.0, ln / 2 * cb]])  # v_G2 = Jv (u, β̇)
    M = np.diag([m1n, m2n * ln**2 / 12]) + m2n * Jv.T @ Jv
    Q = np.array([Sn * np.cos(an), 0.0])  # S·∂r_A/∂x_A, S·∂r_A/∂β = 0
    qdot = np.linalg.solve(M, Q)
    R_lagrange = m2n * Jv @ qdot  # the only impulse on BC is R
    pt = {m_1: m1n, m_2: m2n, ell: ln, S: Sn, alpha: an, beta: bn}
    d.confirm(
        R_lagrange,
        [float(Rx_b.subs(pt)), float(Ry_b.subs(pt))],
        atol=NUM_ATOL * Sn,
        route="Lagrange's impulsive equations in (x_A, β), solved with numpy; R = m_2 Δv_G2",
    )
