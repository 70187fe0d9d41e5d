"""Chapter 3 worked examples 3.1–3.7, re-derived from the book's definitions and
compared with the printed results.  Example 3.4 (the pole-vaulter) is qualitative:
it gets a simulated energy bookkeeping of the four kinds of work in (3.54).
Example 3.5's printed period (3.76) has its fraction inverted: an erratum.

Moments of inertia are derived here by symbolic integration over the body (not
taken from :mod:`mechanics`): disc J_z = ½ m R², solid cylinder J_G = ½ m r².
Simulations use scipy's ``solve_ivp`` (DOP853) on the equations of motion.
"""

from __future__ import annotations

import numpy as np
import sympy as sp
from scipy.integrate import solve_ivp

from identities.book.ch03.kinetic_energy import inertia_components
from identities.book.ch03.power import EPS, ODE_RTOL, particle_system
from identities.verify.catalogue import check
from identities.verify.proof import Derivation
from identities.verify.symbolic import cross, vec
from mechanics import energy as en
from mechanics import inertia as inr
from mechanics import particles as pt

#: evaluation of closed forms and mechanics at O(1)–O(100) values: 2^8 eps relative.
NUM_RTOL = 2**8 * EPS
#: a quantity read off a DOP853 solution at ODE_RTOL ≈ 1.5e-11 (an event time, a
#: speed at an event, an energy balance): global error ≲ 1e-10 relative; 2^24 eps ≈ 3.7e-9.
SIM_RTOL = 2**24 * EPS

HALF = sp.Rational(1, 2)
ez = vec(0, 0, 1)


def _disc_moment(m, R) -> sp.Expr:
    """J_z = ∫ ρ² dm over a uniform disc (areal density m/(π R²)), by integration."""
    s, a = sp.symbols("s a", positive=True)
    sigma = m / (sp.pi * R**2)
    return sp.integrate(sp.integrate(sigma * s**2 * s, (s, 0, R)), (a, 0, 2 * sp.pi))


def _cylinder_moment(m, r) -> sp.Expr:
    """J_G about the axis of a uniform solid cylinder of length b, by a volume integral."""
    s, a, z, b = sp.symbols("s a z b", positive=True)
    rho = m / (sp.pi * r**2 * b)
    return sp.integrate(rho * s**2 * s, (s, 0, r), (a, 0, 2 * sp.pi), (z, 0, b))


@check(
    "E3.1",
    "Example 3.1: the parallel axis theorem and König's theorem in plane motion",
    kind="derivation",
    covers=("E3.1", "eq3.31", "eq3.32", "eq3.33", "eq3.34", "eq3.35"),
    statement="C in the xy-plane of G: J^C_z = J^G_z + m|CG|² (3.32) and v_G = ω × CG (3.34) "
    "give ½ J^C_z φ̇² = ½ m v_G² + ½ J^G_z φ̇² (3.31), (3.35)",
)
def example_3_1(d: Derivation) -> None:
    m, r, _ = particle_system()
    M = sum(m)
    G = sum((mk * rk for mk, rk in zip(m, r, strict=True)), sp.zeros(3, 1)) / M
    xC, yC = sp.symbols("x_C y_C", real=True)
    C = vec(xC, yC, G[2])  # in the same xy-plane as G
    JC = inertia_components(m, [rk - C for rk in r])["J_z"]
    JG = inertia_components(m, [rk - G for rk in r])["J_z"]
    CG = G - C
    d.prove_equal(JC, JG + M * CG.dot(CG), strategy="together", claim="(3.32) parallel axes")
    C_off = vec(xC, yC, sp.Symbol("z_C", real=True))
    JC_off = inertia_components(m, [rk - C_off for rk in r])["J_z"]
    d.reject(
        JC_off,
        JG + M * (G - C_off).dot(G - C_off),
        strategy="together",
        claim="(3.32) with C off G's plane and |CG| the full distance",
    )
    phid = sp.Symbol("phidot", real=True)
    vG = cross(phid * ez, CG)  # (3.34)
    d.prove_equal(vG.dot(vG), phid**2 * CG.dot(CG), strategy="together", claim="|v_G| = |φ̇||CG|")
    lhs = HALF * JC * phid**2
    rhs = HALF * M * vG.dot(vG) + HALF * JG * phid**2
    d.quantity("T", rhs)
    d.prove_equal(lhs, rhs, strategy="together", claim="(3.31) = (3.35) as printed")
    # numeric: a random lamina turning about C
    rng = np.random.default_rng(31)
    mn = rng.uniform(0.2, 1.5, 30)
    rn = np.column_stack([rng.normal(size=(30, 2)), np.zeros(30)])
    Cn, wn = np.array([2.0, -1.0, 0.0]), 1.3
    Gn = pt.centre_of_mass(mn, rn)
    JCn = np.sum(mn * np.sum((rn - Cn)[:, :2] ** 2, axis=1))
    JGn = np.sum(mn * np.sum((rn - Gn)[:, :2] ** 2, axis=1))
    J_G_tensor = inr.inertia_tensor(mn, rn, about=Gn)  # the lamina's tensor
    d.confirm(
        J_G_tensor[2, 2] / JGn,
        1.0,
        atol=NUM_RTOL,
        route="mechanics.inertia.inertia_tensor: J^G_zz = Σ m (x² + y²) about G",
    )
    T_C = en.kinetic_energy_fixed_axis(JCn, wn)
    T_G = en.kinetic_energy_rigid(mn.sum(), np.cross([0, 0, wn], Gn - Cn), [0, 0, wn], J_G_tensor)
    d.confirm(
        [T_C / T_G, T_C / pt.kinetic_energy(mn, np.cross([0, 0, wn], rn - Cn))],
        [1.0, 1.0],
        atol=NUM_RTOL,
        route="mechanics.energy: fixed-axis ½ J^C_z φ̇² = kinetic_energy_rigid(m, v_G, ω, J^G) = "
        "particle sum, for a 30-particle lamina",
    )


@check(
    "E3.2",
    "Example 3.2: the potential energy of the weights",
    kind="derivation",
    covers=("E3.2", "eq3.55", "eq3.56"),
    statement="Φ_k = -m_k g · r_k (3.55) has -∇_k Φ_k = m_k g; Φ^e = Σ Φ_k = -m g · r_G = m g h "
    "(3.56)",
)
def example_3_2(d: Derivation) -> None:
    m, r, _ = particle_system()
    g = vec(*sp.symbols("g_x g_y g_z", real=True))
    x = r[0]
    Phi1 = -m[0] * g.dot(x)
    grad = vec(*[sp.diff(Phi1, c) for c in x])
    d.prove_equal(-grad, m[0] * g, strategy="expand", claim="-∇_k Φ_k = m_k g, the weight (3.55)")
    d.reject(grad, m[0] * g, strategy="expand", claim="Φ_k = +m_k g · r_k")
    M = sum(m)
    rG = sum((mk * rk for mk, rk in zip(m, r, strict=True)), sp.zeros(3, 1)) / M
    Phi_e = sum((-mk * g.dot(rk) for mk, rk in zip(m, r, strict=True)), sp.S.Zero)
    d.prove_equal(Phi_e, -M * g.dot(rG), strategy="together", claim="Φ^e = -m g · r_G (3.56)")
    gmag, h = sp.symbols("g h", positive=True)
    printed = M * gmag * h
    d.quantity("Phi_e", printed)
    d.prove_equal(
        (-M * g.dot(rG)).subs({g[0]: 0, g[1]: 0, g[2]: -gmag}),
        printed.subs(h, rG[2]),
        strategy="together",
        claim="g = -g e_z and h = z_G, the height of G: Φ^e = m g h as printed (3.56)",
    )
    mn = np.array([1.0, 2.5, 0.7])
    rn = np.array([[0.1, 2.0, 1.0], [3.0, -1.0, 4.0], [0.0, 0.0, -2.0]])
    hn = np.average(rn[:, 2], weights=mn)
    d.confirm(
        en.gravity_potential(mn, rn, g=[0.0, 0.0, -9.81]) / (mn.sum() * 9.81 * hn),
        1.0,
        atol=NUM_RTOL,
        route="mechanics.energy.gravity_potential against m g h",
    )


@check(
    "E3.3",
    "Example 3.3: the elastic energy of a rubber band; spring potentials give the forces",
    kind="derivation",
    covers=("E3.3", "eq3.57"),
    statement="F = k Δℓ for stretching, no compressive force: Φ^i = ½ k Δℓ² for Δℓ > 0, 0 for "
    "Δℓ ≤ 0 (3.57); for a linear spring Φ = ½ k (|r_1 - r_2| - ℓ_0)², -∇_1 Φ is the spring force",
)
def example_3_3(d: Derivation) -> None:
    k = sp.Symbol("k", positive=True)
    dl, s = sp.symbols("Delta_ell s", real=True)
    force = sp.Piecewise((k * s, s > 0), (0, True))  # tension only
    work = sp.integrate(force, (s, 0, dl))  # work done against the band while stretching
    printed = sp.Piecewise((k * dl**2 / 2, dl > 0), (0, True))
    d.quantity("Phi_i", printed)
    pos = sp.Symbol("a", positive=True)
    d.prove_equal(work.subs(dl, pos), printed.subs(dl, pos), strategy="expand", claim="Δℓ > 0")
    d.prove_equal(work.subs(dl, -pos), printed.subs(dl, -pos), strategy="expand", claim="Δℓ < 0")
    d.reject(work.subs(dl, pos), k * pos**2, strategy="expand", claim="Φ^i = k Δℓ² (no ½)")
    # a linear spring in space: the gradient gives the central spring force
    r1, r2 = (vec(*sp.symbols(f"x_{j} y_{j} z_{j}", real=True)) for j in (1, 2))
    ell0 = sp.Symbol("ell_0", positive=True)
    dist = sp.sqrt((r1 - r2).dot(r1 - r2))
    Phi = HALF * k * (dist - ell0) ** 2
    F1 = -vec(*[sp.diff(Phi, c) for c in r1])
    d.prove_equal(
        F1,
        -k * (dist - ell0) * (r1 - r2) / dist,
        strategy="together",
        claim="-∇_1 Φ = -k (|r_12| - ℓ_0) r_12/|r_12|: pulls when stretched, pushes when compressed",
    )
    d.prove_equal(
        F1 + (-vec(*[sp.diff(Phi, c) for c in r2])),
        sp.zeros(3, 1),
        strategy="together",
        claim="the forces on the two ends are opposite (internal, third law)",
    )
    pts = (np.array([0.3, -0.2, 1.0]), np.array([1.5, 0.4, 0.2]))
    h = 2.0**-17
    fd = np.array(
        [
            -(
                en.spring_potential(4.0, 0.8, pts[0] + h * e, pts[1])
                - en.spring_potential(4.0, 0.8, pts[0] - h * e, pts[1])
            )
            / (2 * h)
            for e in np.eye(3)
        ]
    )
    d.confirm(
        fd,
        en.spring_force(4.0, 0.8, *pts),
        # central difference: truncation (h²/6)|Φ'''| ≈ 1e-10, rounding eps|Φ|/h ≈ 1e-11
        atol=2**20 * EPS,
        route="mechanics.energy: -∇_1 spring_potential by central differences = spring_force",
    )
    ends = (np.zeros(3), np.array([0.0, 0.0, 1.3]))
    d.confirm(
        [
            en.spring_potential(5.0, 1.0, *ends, tension_only=True),
            en.spring_potential(5.0, 1.6, *ends, tension_only=True),
        ],
        [0.5 * 5.0 * 0.3**2, 0.0],
        atol=NUM_RTOL,
        route="mechanics.energy.spring_potential(tension_only=True) at Δℓ = ±0.3 against (3.57)",
    )


@check(
    "E3.4",
    "Example 3.4: the pole-vaulter's energy bookkeeping (numeric demonstration)",
    kind="derivation",
    covers=("E3.4",),
    statement="run (W^in > 0 becomes T), pole (T becomes Φ^i, then Φ^e), flight (Φ^e highest "
    "at the top), landing (W^en < 0 removes the energy); at every instant "
    "E_m(t) - E_m(0) = W^in + W^en (3.58)",
    reading="a point-mass athlete (70 kg, centre of mass at the grip height 2.2 m): a constant "
    "horizontal muscle force for the run "
    "(internal, non-conservative); the glass-fibre pole as a compression-only linear spring "
    "from the planting box to the athlete (internal, conservative Φ^i); a damped spring mat "
    "(its damping external and non-conservative, its spring counted in Φ^e). The book's "
    "'all energy has become Φ^e' at the top is approximate: a little horizontal speed remains.",
)
def example_3_4(d: Derivation) -> None:
    sim = _pole_vault()
    Em = sim["T"] + sim["Phi_e"] + sim["Phi_i"]
    scale = float(np.max(sim["T"]))
    d.numeric_close(
        (Em - Em[0] - sim["W_in"] - sim["W_en"]) / scale,
        np.zeros_like(Em),
        atol=SIM_RTOL,
        claim="E_m(t) - E_m(0) = W^in(t) + W^en(t) along the whole vault (3.58), relative",
    )
    ph = sim["phase"]
    run_end = np.flatnonzero(ph == 0)[-1]
    d.quantity("W_in_run", sp.Float(sim["W_in"][run_end], 6))
    d.confirm(
        sim["T"][run_end] / sim["W_in"][run_end],
        1.0,
        atol=SIM_RTOL,
        route="the run: the muscle work W^in has all become kinetic energy",
    )
    pole = ph == 1
    Phi_i_max = float(np.max(sim["Phi_i"][pole]))
    d.quantity("Phi_i_max", sp.Float(Phi_i_max, 6))
    top = int(np.argmax(np.where(ph == 2, sim["y"], -np.inf)))
    dPhi_e = sim["Phi_e"][top] - sim["Phi_e"][0]
    d.quantity("Phi_e_gain_at_top", sp.Float(dPhi_e, 6))
    d.quantity("W_en_landing", sp.Float(sim["W_en"][-1], 6))
    d.confirm(
        [
            Phi_i_max / sim["T"][run_end] > 0.3,  # the pole stores a good part of T
            sim["Phi_i"][top] == 0.0,  # released: Φ^i given back
            dPhi_e / sim["W_in"][run_end] > 0.8,  # most of the run's work is height at the top
            sim["x"][top] > 0.0,  # over the box: the pole has carried the athlete across
            sim["T"][-1] / sim["T"][run_end] < 1e-6,  # at rest on the mat at the end
        ],
        [True, True, True, True, True],
        atol=0.0,
        route="the sequence W^in → T → Φ^i → Φ^e → T → W^en of the book, by the numbers",
    )
    land = np.flatnonzero(ph == 3)[0]
    d.confirm(
        (sim["W_en"][-1] - (Em[-1] - Em[land])) / scale,
        0.0,
        atol=SIM_RTOL,
        route="the landing: the mat's work W^en is the mechanical energy lost on the mat",
    )


def _pole_vault() -> dict[str, np.ndarray]:
    """Simulate the four phases; returns samples of T, Φ^e, Φ^i, W^in, W^en, y and the phase."""
    m, g = 70.0, 9.81
    F_run, t_run = 200.0, 3.3
    y0, ell0, k_pole = 2.2, 4.5, 1000.0
    y_mat, k_mat, c_mat = 0.7, 2.0e4, 2.4e3
    a0 = np.sqrt(ell0**2 - y0**2)

    def Phi_e(y):
        return m * g * y + np.where(y < y_mat, 0.5 * k_mat * (y - y_mat) ** 2, 0.0)

    def Phi_i(x, y):
        ext = np.hypot(x, y) - ell0
        return np.where(ext < 0, 0.5 * k_pole * ext**2, 0.0)

    def run(_, s):  # x, y, vx, vy, W_in, W_en
        return [s[2], 0.0, F_run / m, 0.0, F_run * s[2], 0.0]

    def vault(_, s):
        rr = np.hypot(s[0], s[1])
        f = -k_pole * min(rr - ell0, 0.0) / rr
        return [s[2], s[3], f * s[0] / m, f * s[1] / m - g, 0.0, 0.0]

    def fly(_, s):
        return [s[2], s[3], 0.0, -g, 0.0, 0.0]

    def mat(_, s):
        pen = min(s[1] - y_mat, 0.0)
        fx, fy_d = -c_mat * s[2], -c_mat * s[3] * (pen < 0)
        return [s[2], s[3], fx / m, (-k_mat * pen + fy_d) / m - g, 0.0, fx * s[2] + fy_d * s[3]]

    def released(_, s):
        return np.hypot(s[0], s[1]) - ell0

    released.terminal, released.direction = True, 1

    def landed(_, s):
        return s[1] - y_mat

    landed.terminal, landed.direction = True, -1

    opts = {"method": "DOP853", "rtol": ODE_RTOL, "atol": ODE_RTOL}
    s0 = np.array([-a0 - 0.5 * F_run / m * t_run**2, y0, 0.0, 0.0, 0.0, 0.0])
    parts, t0 = [], 0.0
    for phase, (f, ev, dur) in enumerate(
        [(run, None, t_run), (vault, released, 10.0), (fly, landed, 10.0), (mat, None, 3.0)]
    ):
        sol = solve_ivp(f, (t0, t0 + dur), s0, events=ev, dense_output=True, **opts)
        t_end = sol.t[-1]
        ts = np.linspace(t0, t_end, 400)
        parts.append((phase, sol.sol(ts)))
        s0, t0 = sol.y[:, -1], t_end
    ph = np.concatenate([np.full(p[1].shape[1], p[0]) for p in parts])
    S = np.concatenate([p[1] for p in parts], axis=1)
    x, y, vx, vy, W_in, W_en = S
    return {
        "phase": ph,
        "x": x,
        "y": y,
        "T": 0.5 * m * (vx**2 + vy**2),
        "Phi_e": Phi_e(y),
        "Phi_i": np.where(ph == 1, Phi_i(x, y), 0.0),  # the pole is held only while vaulting
        "W_in": W_in,
        "W_en": W_en,
    }


@check(
    "E3.5",
    "Example 3.5: the torsion pendulum",
    kind="derivation",
    covers=("E3.5", "eq3.72", "eq3.73", "eq3.74", "eq3.75", "eq3.76"),
    errata=("eq3.76",),
    statement="J_z = ½ m R², Φ = ½ τ_0 φ² (3.72), E_m = ½ J_z φ̇² + ½ τ_0 φ² (3.73), "
    "J_z φ̈ + τ_0 φ = 0 (3.74)-(3.75), ω_0 = √(τ_0/J_z), period T_p = 2π/ω_0",
    printed="T_p = 2π/ω_0 = 2π √(τ_0/J_z) = 2π √(2τ_0/(m R²))  (3.76)",
    corrected="T_p = 2π/ω_0 = 2π √(J_z/τ_0) = 2π √(m R²/(2τ_0)) = π R √(2m/τ_0)",
    reading="the extraction flattens fractions numerator first: (3.75) 'τ0Jz' is τ_0/J_z and "
    "ω_0 = √(τ_0/J_z) is right; the same reading of (3.76) gives 2π √(τ_0/J_z), which has the "
    "dimension 1/time and is 2π ω_0, not 2π/ω_0",
)
def example_3_5(d: Derivation) -> None:
    m, R, tau0, tt = sp.symbols("m R tau_0 t", positive=True)
    Jz = _disc_moment(m, R)
    d.prove_equal(
        Jz, m * R**2 / 2, strategy="expand", claim="J_z = ∫ ρ² dm = ½ m R² (uniform disc)"
    )
    phi, phip = sp.symbols("phi phi'", real=True)
    Phi = -sp.integrate(-tau0 * phip, (phip, 0, phi))
    d.prove_equal(Phi, tau0 * phi**2 / 2, strategy="expand", claim="Φ(φ) = ½ τ_0 φ² (3.72)")
    f = sp.Function("phi", real=True)(tt)
    Em = HALF * Jz * sp.diff(f, tt) ** 2 + Phi.subs(phi, f)  # (3.73)
    d.prove_equal(
        sp.diff(Em, tt),
        sp.diff(f, tt) * (Jz * sp.diff(f, tt, 2) + tau0 * f),
        strategy="expand",
        claim="dE_m/dt = φ̇ (J_z φ̈ + τ_0 φ) (3.74): E_m constant ⇔ (3.75) while φ̇ ≠ 0",
    )
    w0 = sp.sqrt(tau0 / Jz)
    A, B = sp.symbols("A B", real=True)
    sol = A * sp.cos(w0 * tt) + B * sp.sin(w0 * tt)
    d.prove_zero(
        sp.diff(sol, tt, 2) + tau0 / Jz * sol,
        strategy="expand",
        claim="φ = A cos ω_0 t + B sin ω_0 t solves (3.75) with ω_0 = √(τ_0/J_z)",
    )
    Tp = d.quantity("T_p", 2 * sp.pi / w0)
    d.prove_equal(Tp, 2 * sp.pi * sp.sqrt(m * R**2 / (2 * tau0)), strategy="expand", claim="T_p")
    d.prove_equal(sol.subs(tt, tt + Tp), sol, strategy="expand_trig", claim="φ(t + T_p) = φ(t)")
    d.refute(Tp, 2 * sp.pi * sp.sqrt(tau0 / Jz), claim="printed T_p = 2π √(τ_0/J_z)")
    d.refute(Tp, 2 * sp.pi * sp.sqrt(2 * tau0 / (m * R**2)), claim="printed 2π √(2τ_0/(m R²))")
    d.reject(
        sol.subs(tt, tt + 2 * sp.pi * sp.sqrt(tau0 / Jz)),
        sol,
        strategy="expand_trig",
        claim="the printed T_p is a period of the motion",
    )
    # simulation: J_z φ̈ = M(φ) from mechanics.energy.torsion_moment; period from crossings
    mn, Rn, tn = 2.0, 0.3, 0.05
    Jn = 0.5 * mn * Rn**2

    def rhs(_, s):
        return [s[1], float(en.torsion_moment(tn, s[0])) / Jn]

    def upward(_, s):
        return s[0]

    upward.direction = 1
    sim = solve_ivp(
        rhs,
        (0, 60.0),
        [0.4, 0.0],
        method="DOP853",
        rtol=ODE_RTOL,
        atol=ODE_RTOL,
        events=upward,
        dense_output=True,
    )
    crossings = sim.t_events[0]
    period = float(np.mean(np.diff(crossings)))
    Tp_n = float(Tp.subs({m: mn, R: Rn, tau0: tn}))
    d.confirm(
        period / Tp_n,
        1.0,
        atol=SIM_RTOL,
        route=f"scipy simulation: mean spacing of {len(crossings)} upward zero crossings",
    )
    ts = np.linspace(0, 60.0, 300)
    ph, phd = sim.sol(ts)
    E = en.kinetic_energy_fixed_axis(Jn, phd) + en.torsion_potential(tn, ph)
    d.confirm(
        (E - E[0]) / E[0],
        np.zeros_like(E),
        atol=SIM_RTOL,
        route="mechanics.energy: E_m = kinetic_energy_fixed_axis + torsion_potential is constant",
    )


@check(
    "E3.6",
    "Example 3.6: a cylinder rolling down an incline",
    kind="derivation",
    covers=("E3.6", "eq3.77", "eq3.78", "eq3.79", "eq3.80"),
    statement="x = r φ (3.77), E = ½ m ẋ² + ½ J_G φ̇² - m g x sin α (3.78) with J_G = ½ m r², "
    "from rest E = 0, h = x sin α (3.79): ẋ = √(4 g h / 3) (3.80)",
)
def example_3_6(d: Derivation) -> None:
    m, r, g, h, alpha = sp.symbols("m r g h alpha", positive=True)
    JG = _cylinder_moment(m, r)
    d.prove_equal(JG, m * r**2 / 2, strategy="expand", claim="J_G = ½ m r² (uniform cylinder)")
    xd = sp.Symbol("xdot", positive=True)
    E = HALF * m * xd**2 + HALF * JG * (xd / r) ** 2 - m * g * h  # (3.78)-(3.79), φ̇ = ẋ/r
    d.prove_equal(
        E,
        HALF * m * xd**2 + HALF * HALF * m * r**2 * (xd / r) ** 2 - m * g * h,
        strategy="expand",
        claim="(3.79) as printed",
    )
    sols = sp.solve(E, xd)
    if len(sols) != 1:
        raise AssertionError(f"expected one positive speed, got {sols}")
    v = d.quantity("xdot", sols[0])
    d.prove_equal(v**2, 4 * g * h / 3, strategy="expand", claim="ẋ = √(4gh/3) (3.80)")
    d.reject(v**2, 2 * g * h, strategy="expand", claim="ẋ = √(2gh) (sliding without rolling)")
    # Newton–Euler with the friction force f unknown: m ẍ = m g sin α - f, J_G φ̈ = f r
    xdd, f = sp.symbols("xddot f", real=True)
    ne = sp.solve([m * xdd - m * g * sp.sin(alpha) + f, JG * xdd / r - f * r], [xdd, f], dict=True)[
        0
    ]
    d.confirm_exact(
        ne[xdd],
        2 * g * sp.sin(alpha) / 3,
        route="Newton–Euler: ẍ = (2/3) g sin α, so ẋ² = 2 ẍ x = (4/3) g h",
    )
    mn, rn, gn, an, hn = 3.0, 0.2, 9.81, 0.4, 1.5
    f_n = float(ne[f].subs({m: mn, g: gn, alpha: an}))

    def rhs(_, s):  # x, φ, ẋ, φ̇ with the friction force of the rolling solution
        return [s[2], s[3], gn * np.sin(an) - f_n / mn, f_n * rn / (0.5 * mn * rn**2)]

    def sunk(_, s):
        return s[0] * np.sin(an) - hn

    sunk.terminal = True
    sim = solve_ivp(
        rhs, (0, 10), [0, 0, 0, 0], method="DOP853", rtol=ODE_RTOL, atol=ODE_RTOL, events=sunk
    )
    x_e, phi_e, xd_e, phid_e = sim.y_events[0][0]
    d.confirm(
        xd_e / np.sqrt(4 * gn * hn / 3),
        1.0,
        atol=SIM_RTOL,
        route="scipy simulation of Newton–Euler: speed after sinking h",
    )
    d.confirm(
        [x_e - rn * phi_e, xd_e - rn * phid_e],
        [0.0, 0.0],
        atol=SIM_RTOL,
        route="the simulated motion keeps the rolling constraint x = r φ (3.77)",
    )
    F_contact = np.array([-f_n, mn * gn * np.cos(an), 0.0])  # friction up the slope, normal
    d.confirm(
        en.rolling_contact_power(F_contact, [xd_e, 0, 0], [0, 0, -phid_e], [0, -rn, 0]),
        0.0,
        atol=SIM_RTOL * mn * gn * xd_e,
        route="mechanics.energy.rolling_contact_power of friction and normal force is zero",
    )


@check(
    "E3.7",
    "Example 3.7: a pearl sliding on a free semicircular wire",
    kind="derivation",
    covers=(
        "E3.7",
        "eq3.81",
        "eq3.82",
        "eq3.83",
        "eq3.84",
        "eq3.85",
        "eq3.86",
        "eq3.87",
        "eq3.88",
        "eq3.89",
    ),
    statement="x_G = r/4 (3.81), x_w = (r - x)/3 (3.82), (x - x_w)² + y² = r² (3.83)-(3.84) is the "
    "ellipse ((x - r/4)/(3r/4))² + (y/r)² = 1 (3.85); energy (3.86)-(3.88) gives v = √(3gr/2) "
    "(3.89) at the lowest point",
    reading="y points down; 'at its lowest position the pearl has vertical velocity' is read as "
    "ẏ = 0 there (the velocity is horizontal), as the book's next clause ẏ = 0 says",
)
def example_3_7(d: Derivation) -> None:
    m, r, g = sp.symbols("m r g", positive=True)
    x, y, xw = sp.symbols("x y x_w", real=True)
    xG = (m * x + 3 * m * xw) / (4 * m)
    d.prove_equal(xG.subs({x: r, xw: 0}), r / 4, strategy="expand", claim="x_G = r/4 (3.81)")
    xw_sol = sp.solve(sp.Eq(xG, r / 4), xw)[0]
    d.prove_equal(xw_sol, (r - x) / 3, strategy="expand", claim="x_w = (r - x)/3 (3.82)")
    circle = (x - xw) ** 2 + y**2 - r**2  # (3.83)
    e384 = circle.subs(xw, xw_sol)  # (3.84)
    ellipse = ((x - r / 4) / (3 * r / 4)) ** 2 + (y / r) ** 2 - 1  # (3.85)
    d.prove_equal(
        e384,
        r**2 * ellipse,
        strategy="expand",
        claim="(3.84) - r² = r² × ((3.85) - 1): the same curve",
    )
    d.reject(
        e384,
        r**2 * (((x - r / 4) / (3 * r / 4)) ** 2 + (y / (3 * r / 4)) ** 2 - 1),
        strategy="expand",
        claim="a circle of radius 3r/4 about (r/4, 0)",
    )
    xd, yd, v = sp.symbols("xdot ydot v", real=True)
    E = HALF * m * (xd**2 + yd**2) + HALF * 3 * m * (-xd / 3) ** 2 - m * g * y  # (3.86)-(3.87)
    d.prove_equal(
        E,
        HALF * m * (xd**2 + yd**2) + HALF * 3 * m * xd**2 / 9 - m * g * y,
        strategy="expand",
        claim="(3.87) with ẋ_w = -ẋ/3",
    )
    low = E.subs({yd: 0, y: r, xd: v})
    d.prove_equal(low, HALF * m * (v**2 + v**2 / 3) - m * g * r, strategy="expand", claim="(3.88)")
    vs = [s for s in sp.solve(low, v) if s.is_positive]
    vq = d.quantity("v", vs[0])
    d.prove_equal(vq**2, 3 * g * r / 2, strategy="expand", claim="v = √(3gr/2) (3.89)")
    d.reject(vq**2, 2 * g * r, strategy="expand", claim="v = √(2gr) (the wire held fixed)")
    # Lagrange in (x_w, θ), the wire free: no momentum conservation imposed
    th, thd, xwd = sp.symbols("theta thetadot xwdot", real=True)
    pxd = xwd - r * sp.sin(th) * thd
    pyd = r * sp.cos(th) * thd
    L = HALF * m * (pxd**2 + pyd**2) + HALF * 3 * m * xwd**2 + m * g * r * sp.sin(th)
    qd = [xwd, thd]
    Mmat = sp.hessian(L, qd)
    forcing = sp.Matrix([sp.diff(L, xw), sp.diff(L, th)]) - sp.Matrix(
        [sum(sp.diff(L, a, b) * c for b, c in ((th, thd),)) for a in qd]
    )
    acc = sp.lambdify((th, thd, xwd, m, r, g), Mmat.LUsolve(forcing), "numpy")
    mn, rn, gn = 0.1, 0.5, 9.81

    def rhs(_, s):  # x_w, θ, ẋ_w, θ̇
        a = np.asarray(acc(s[1], s[3], s[2], mn, rn, gn), dtype=float).ravel()
        return [s[2], s[3], a[0], a[1]]

    def lowest(_, s):
        return s[1] - np.pi / 2

    lowest.terminal = True
    sim = solve_ivp(
        rhs,
        (0, 5),
        [0.0, 0.0, 0.0, 0.0],
        method="DOP853",
        rtol=ODE_RTOL,
        atol=ODE_RTOL,
        events=lowest,
        dense_output=True,
    )
    _, th_e, xwd_e, thd_e = sim.y_events[0][0]
    v_pearl = np.hypot(xwd_e - rn * np.sin(th_e) * thd_e, rn * np.cos(th_e) * thd_e)
    d.confirm(
        v_pearl / float(vq.subs({g: gn, r: rn})),
        1.0,
        atol=SIM_RTOL,
        route="scipy simulation of Lagrange's equations in (x_w, θ), wire free: pearl speed at θ = π/2",
    )
    ts = np.linspace(0, sim.t[-1], 50)
    xw_t, th_t = sim.sol(ts)[:2]
    xp, yp = xw_t + rn * np.cos(th_t), rn * np.sin(th_t)
    d.confirm(
        ((xp - rn / 4) / (0.75 * rn)) ** 2 + (yp / rn) ** 2,
        np.ones_like(xp),
        atol=SIM_RTOL,
        route="the simulated pearl stays on the ellipse (3.85) (momentum conservation not imposed)",
    )
