"""The book's closed forms, and the simulated scene quantities measured against them.

The book layer's half of the scenes: :mod:`mechanics.scenes` simulates and checks a run
on its own output; this module knows the book's examples and compares.

Conventions
-----------
Each comparison takes a scene and its trajectory, *measures* a quantity on the
simulated motion (an event's instant or speed, a turning point or a zero crossing
located on the dense solution with ``brentq``/``minimize_scalar``) and sets it against
the book's closed form, written here from the book's printed formula (or derived,
where the book gives only the equation of motion; the derivation is in the docstring).
The measured value never comes from the closed form it is compared with.

Tolerances (relative) are named multiples of eps with a reason:

- ``EXACT_RTOL``: an exact flow against the closed form computed by another route;
- ``INTEGRATED_RTOL``: DOP853 at rtol = atol = 1e-12 plus event location;
- small-oscillation formulas hold to O(amplitude²): the tolerance is the first
  correction, θ0²/16 for the period (the series T = T0 (1 + θ0²/16 + ...)), plus
  ``INTEGRATED_RTOL``.
"""

from __future__ import annotations

import functools
import itertools
import math

import numpy as np

from mechanics.scenes import Comparison, Scene, SceneError, load_scene, run_scene
from mechanics.scenes.simulate import EPS, Trajectory, body_inertia

__all__ = [
    "COMPARISONS",
    "EXACT_RTOL",
    "INTEGRATED_RTOL",
    "book_comparison",
    "load_book_scene",
    "run_book_scene",
]

#: closed forms by another route (log1p vs log, elliptic functions vs integrals,
#: root location by brentq at xtol = 4 eps): a few hundred roundings at most
EXACT_RTOL = 1024 * EPS  # ≈ 2.3e-13
#: DOP853 at rtol = atol = 1e-12 over a scene (measured worst ≈ 3e-11), with events
INTEGRATED_RTOL = 2**22 * EPS  # ≈ 9.3e-10


def _tol(tr: Trajectory) -> tuple[float, str]:
    if tr.method.startswith("integrated"):
        return INTEGRATED_RTOL, "integrated (DOP853, rtol 1e-12)"
    return EXACT_RTOL, "exact flow vs closed form"


def _need(scene: Scene, cond: bool, what: str) -> None:
    if not cond:
        raise scene.error("scene.compare", f"comparison {scene.compare!r} needs {what}")


def _gravity(scene: Scene) -> float:
    gs = scene.effects_of("gravity")
    _need(scene, len(gs) == 1, "exactly one gravity effect")
    return float(gs[0].fields["g"])


def _plane_impact(scene: Scene) -> dict:
    """The fields of the scene's one impact, which must be against a plane."""
    imp = scene.effects_of("impact")
    _need(scene, len(imp) == 1 and "other" not in imp[0].fields, "one impact against a plane")
    return imp[0].fields


def _zeros(tr: Trajectory, key: str, n: int, t_lo: float = 0.0, down: bool = False) -> list[float]:
    """The first n zero crossings of state_at(t)[key] after t_lo (only from + to − if
    ``down``), bracketed by the samples and located by brentq on the dense solution."""
    from scipy.optimize import brentq

    def f(t):
        return tr.state_at(t)[key]

    out, t = [], tr.t
    vals = np.asarray(tr.series[key])
    for k in range(len(t) - 1):
        if t[k + 1] <= t_lo or (down and not vals[k + 1] < 0):
            continue
        if vals[k] == 0 and t[k] > t_lo:
            out.append(float(t[k]))
        elif vals[k] * vals[k + 1] < 0 and f(max(t[k], t_lo)) * f(t[k + 1]) < 0:
            out.append(brentq(f, max(t[k], t_lo), t[k + 1], xtol=4 * EPS * t[k + 1], rtol=4 * EPS))
        if len(out) == n:
            return out
    raise RuntimeError(f"fewer than {n} zeros of {key} within the duration")


# ------------------------------------------------------------------ Example 6.1


def bouncing_ball(scene: Scene, tr: Trajectory):
    """Example 6.1: 12 m/s before, 10 m/s after, e = 5/6; apex heights fall by e².

    Between impacts the ball flies freely, so an apex at height H above the contact
    level follows a rebound at speed v with H = v²/(2g); the next rebound speed is e v,
    hence H_{k+1}/H_k = e² and the flight time 2 e v/g.
    """
    g = _gravity(scene)
    e = _plane_impact(scene)["restitution"]
    impacts = [ev for ev in tr.events if ev.kind == "impact"]
    _need(scene, len(impacts) >= 3, "at least three impacts within the duration")
    tol, why = _tol(tr)
    out = [
        Comparison(
            "speed before the first impact",
            "E6.1",
            impacts[0].detail["normal_speed_before"],
            12.0,
            tol,
            why,
        ),
        Comparison(
            "speed after the first impact",
            "E6.1",
            impacts[0].detail["normal_speed_after"],
            10.0,
            tol,
            why,
        ),
        Comparison(
            "e = after/before",
            "E6.1, (6.40)",
            impacts[0].detail["normal_speed_after"] / impacts[0].detail["normal_speed_before"],
            5.0 / 6.0,
            tol,
            why,
        ),
    ]
    r = float(scene.bodies[0].dims.get("radius", 0.0))
    apexes = []
    for a, b in itertools.pairwise(impacts):
        (tz,) = _zeros(tr, "vz", 1, a.t, down=True)
        _need(scene, tz < b.t, "an apex between impacts")
        apexes.append(tr.state_at(tz)["z"] - r)
    worst = max(range(1, len(apexes)), key=lambda k: abs(apexes[k] / apexes[k - 1] - e * e))
    out.append(
        Comparison(
            f"apex ratio H{worst + 1}/H{worst} (worst)",
            "E6.1: e²",
            apexes[worst] / apexes[worst - 1],
            e * e,
            tol,
            why,
        )
    )
    dt = [b.t - a.t for a, b in itertools.pairwise(impacts)]
    out.append(Comparison("flight time after bounce 1", "2 e v/g", dt[0], 2 * 10.0 / g, tol, why))
    return out


# ------------------------------------------------------------------ Example 3.6


def rolling_incline(scene: Scene, tr: Trajectory):
    """Example 3.6: a homogeneous cylinder rolling from rest has v = √(4gh/3) (3.80)."""
    g = _gravity(scene)
    b = scene.bodies[0]
    _need(scene, b.shape in ("cylinder", "disc"), "a homogeneous cylinder (or disc)")
    _need(scene, b.initial.get("speed", 0.0) == 0.0, "a start from rest")
    tol, why = _tol(tr)
    out = []
    for frac in (0.5, 1.0):
        tt = frac * scene.duration
        st = tr.state_at(tt)
        alpha = scene.effects_of("rolling")[0].fields.get("angle", 0.0)
        h = (st["s"] - b.initial.get("distance", 0.0)) * math.sin(alpha)
        out.append(
            Comparison(
                f"speed after sinking h = {h:.6g} m",
                "E3.6 (3.80)",
                st["v"],
                math.sqrt(4 * g * h / 3),
                tol,
                why,
            )
        )
    return out


# ------------------------------------------------------------------ Examples 4.3–4.4


def _rod_pendulum(scene):
    g = _gravity(scene)
    b = scene.bodies[0]
    ax = scene.effects_of("fixed_axis")
    _need(scene, b.shape == "rod" and len(ax) == 1, "a rod on a fixed axis")
    ell = b.dims["length"]
    _need(
        scene,
        abs(ax[0].fields.get("distance", 0.0) - ell / 2) <= 4 * EPS * ell,
        "the axis at one end of the rod (distance = length/2)",
    )
    _need(scene, ax[0].fields.get("body_axis", "z") in ("x", "y"), "the axis across the rod")
    _need(scene, b.initial.get("angular_velocity", 0.0) == 0.0, "a release from rest")
    return g, ell, float(b.initial.get("angle", 0.0))


def pendulum_horizontal(scene: Scene, tr: Trajectory):
    """Examples 4.3–4.4: rod about one end, released from the horizontal.

    φ̇ at the vertical is √(3g/ℓ) (4.59).  The exact period (from the energy 4.57,
    derived): T = 4 K(k²) √(J_z/(m g h)) = 4 K(sin²(φ0/2)) √(2ℓ/(3g)); for small φ0 it
    tends to 2π√(2ℓ/(3g)) (4.53).
    """
    from scipy.special import ellipk

    g, ell, phi0 = _rod_pendulum(scene)
    tol, why = _tol(tr)
    z = _zeros(tr, "phi", 3)
    out = [
        Comparison(
            "|φ̇| at the vertical",
            "E4.4 (4.59)",
            abs(tr.state_at(z[0])["phidot"]),
            math.sqrt(3 * g / ell),
            tol,
            why,
        )
    ]
    T = 4 * ellipk(math.sin(abs(phi0) / 2) ** 2) * math.sqrt(2 * ell / (3 * g))
    out.append(
        Comparison("period (large amplitude)", "from (4.57): 4K√(2ℓ/3g)", z[2] - z[0], T, tol, why)
    )
    st = tr.state_at(z[0])
    if "reaction_z" in st and abs(phi0) == math.pi / 2:
        # (4.71) at the vertical: R_ρ = −m h φ̇² − F_ρ with F_ρ = m g (down, outward) and
        # φ̇² = 3g/ℓ (4.59), h = ℓ/2: the axis pulls up with m g + 3mg/2 = 5mg/2 (derived)
        m = scene.bodies[0].mass
        out.append(
            Comparison(
                "axis force at the vertical (up)",
                "(4.71) with (4.59): 5mg/2 (derived)",
                st["reaction_z"],
                2.5 * m * g,
                tol,
                why + ", the engine's bearing reaction",
            )
        )
    return out


def pendulum_small(scene: Scene, tr: Trajectory):
    """Example 4.3: small oscillations of a rod about one end, T = 2π√(2ℓ/(3g)) (4.53)."""
    g, ell, phi0 = _rod_pendulum(scene)
    tol, why = _tol(tr)
    z = _zeros(tr, "phi", 3)
    amp = phi0 * phi0 / 16 * 1.01  # the first correction of T(θ0), with 1 % slack
    return [
        Comparison(
            "small-oscillation period",
            "E4.3 (4.53)",
            z[2] - z[0],
            2 * math.pi * math.sqrt(2 * ell / (3 * g)),
            tol + amp,
            f"{why} + amplitude correction θ0²/16 = {phi0 * phi0 / 16:.1e}",
        )
    ]


# ------------------------------------------------------------------ Example 4.5


def cylinder_in_track(scene: Scene, tr: Trajectory):
    """Example 4.5: small oscillations in a track, T = π√(6(R − r)/g) (4.65)
    = 2π√(3(R − r)/(2g))."""
    g = _gravity(scene)
    b = scene.bodies[0]
    roll = scene.effects_of("rolling")
    _need(
        scene,
        b.shape in ("cylinder", "disc") and roll and roll[0].fields["surface"] == "track",
        "a homogeneous cylinder rolling in a track",
    )
    R, r = roll[0].fields["track_radius"], b.dims["radius"]
    psi0 = float(b.initial.get("angle", 0.0))
    tol, why = _tol(tr)
    z = _zeros(tr, "psi", 3)
    amp = psi0 * psi0 / 16 * 1.01
    return [
        Comparison(
            "small-oscillation period",
            "E4.5 (4.65)",
            z[2] - z[0],
            math.pi * math.sqrt(6 * (R - r) / g),
            tol + amp,
            f"{why} + amplitude correction ψ0²/16 = {psi0 * psi0 / 16:.1e}",
        )
    ]


# ------------------------------------------------------------------ 5.2 heavy top


def heavy_top(scene: Scene, tr: Trajectory):
    """5.2: the top nutates between the roots u1 ≤ u2 of the cubic
    f(u) = (e − βu)(1 − u²) − (a − bu)² in u = cos θ (5.66–5.71), with β = 2mgℓ/J'1,
    a = L_z/J'1, b = L3/J'1, e = (2E − L3²/J3)/J'1 from the initial state; with
    u = u1 + (u2 − u1) sn²(κt | m), κ = √(β(u3 − u1))/2, m = (u2 − u1)/(u3 − u1)
    (derived) the nutation period is 2K(m)/κ."""
    from scipy.special import ellipk

    g = _gravity(scene)
    b = scene.bodies[0]
    fp = scene.effects_of("fixed_point")
    _need(scene, bool(fp), "a fixed point")
    J = body_inertia(b)
    _need(scene, J[0] == J[1], "a symmetric body (J1 = J2)")
    J1 = J[0] + b.mass * fp[0].fields["distance"] ** 2
    J3 = J[2]
    mgl = b.mass * g * fp[0].fields["distance"]
    ini = {k: float(b.initial.get(k, 0.0)) for k in ("theta", "theta_dot", "psi_dot", "phi_dot")}
    th = ini["theta"]
    u0 = math.cos(th)
    L3 = J3 * (ini["psi_dot"] * u0 + ini["phi_dot"])
    Lz = J1 * math.sin(th) ** 2 * ini["psi_dot"] + L3 * u0
    E = (
        0.5 * J1 * (ini["theta_dot"] ** 2 + (ini["psi_dot"] * math.sin(th)) ** 2)
        + L3**2 / (2 * J3)
        + mgl * u0
    )
    beta, a, bb = 2 * mgl / J1, Lz / J1, L3 / J1
    e = (2 * E - L3**2 / J3) / J1
    # f(u) = βu³ − (e + b²)u² + (2ab − β)u + (e − a²)
    roots = np.sort(np.roots([beta, -(e + bb * bb), 2 * a * bb - beta, e - a * a]).real)
    u1, u2, u3 = roots
    tol, why = _tol(tr)
    # at a turning point u is stationary; the roots of the cubic by numpy.roots carry
    # an error ~ eps·cond, measured ≤ 2e-15 here
    tol_u = max(tol, 2**12 * EPS)
    # turning points: zeros of d(cos θ)/dt, alternately a lowest and a highest u
    z = _zeros(tr, "cos_theta_dot", 4)
    u_at = [tr.state_at(x)["cos_theta"] for x in z]
    lo, hi = (0, 1) if u_at[0] < u_at[1] else (1, 0)
    kappa = 0.5 * math.sqrt(beta * (u3 - u1))
    T = 2 * ellipk((u2 - u1) / (u3 - u1)) / kappa
    return [
        Comparison(
            "lowest cos θ (turning point)",
            "5.2: root u1 of f(u)",
            u_at[lo],
            u1,
            tol_u,
            why + ", cubic roots by numpy.roots",
        ),
        Comparison(
            "highest cos θ (turning point)",
            "5.2: root u2 of f(u)",
            u_at[hi],
            u2,
            tol_u,
            why + ", cubic roots by numpy.roots",
        ),
        Comparison(
            "nutation period",
            "5.2: 2K(m)/κ (derived)",
            z[2] - z[0],
            T,
            max(tol, 2**12 * EPS),
            why + ", turning points by brentq",
        ),
    ]


# ------------------------------------------------------------------ 5.3.3 flip


def _flip_period(J, w) -> float:
    """The period 4K(m)/λ of ω2's reversals for body ω (derived; see
    :func:`intermediate_axis_flip`)."""
    from scipy.special import ellipk

    J1, J2, J3 = J
    E2, L2 = float((J * w * w).sum()), float((J * J * w * w).sum())
    if L2 < E2 * J2:
        lam2 = (J2 - J1) * (E2 * J3 - L2) / (J1 * J2 * J3)
        m = (J3 - J2) * (L2 - E2 * J1) / ((J2 - J1) * (E2 * J3 - L2))
    else:
        lam2 = (J3 - J2) * (L2 - E2 * J1) / (J1 * J2 * J3)
        m = (J2 - J1) * (E2 * J3 - L2) / ((J3 - J2) * (L2 - E2 * J1))
    return 4 * ellipk(m) / math.sqrt(lam2)


def intermediate_axis_flip(scene: Scene, tr: Trajectory):
    """5.3.3: rotation about the intermediate axis is unstable; ω2 reverses sign twice
    per period 4K(m)/λ of the Jacobi solution of (5.91) (derived): with L² and 2E from
    the initial ω and J1 < J2 < J3, for L² < 2EJ2 (ω circulates axis 1)
    λ² = (J2 − J1)(2EJ3 − L²)/(J1J2J3), m = (J3 − J2)(L² − 2EJ1)/((J2 − J1)(2EJ3 − L²)),
    and with the indices 1 ↔ 3 exchanged otherwise."""
    b = scene.bodies[0]
    _need(scene, not scene.effects, "a free body without effects")
    J = np.asarray(body_inertia(b))
    _need(scene, J[0] < J[1] < J[2], "principal moments J1 < J2 < J3")
    w = np.asarray(b.initial.get("omega", [0.0, 0.0, 0.0]))
    return [_flip_comparison(tr, J, w, "flip period (ω2 back to its sign)", 0.0)]


def flip_after_push(scene: Scene, tr: Trajectory):
    """5.3.3 started by a push: after the push's window ends the body is torque-free, so
    ω2 reverses with the period 4K(m)/λ of the ω it has then (read off the motion at
    the window's end; :func:`intermediate_axis_flip` for the formula)."""
    b = scene.bodies[0]
    pushes = [e for e in scene.effects if e.type in ("force", "torque")]
    _need(scene, len(pushes) == len(scene.effects) >= 1, "only pushes (force or torque effects)")
    _need(scene, all("end" in p.fields for p in pushes), "pushes that end")
    J = np.asarray(body_inertia(b))
    _need(scene, J[0] < J[1] < J[2], "principal moments J1 < J2 < J3")
    t_end = max(p.fields["end"] for p in pushes)
    st = tr.state_at(t_end)
    w = np.array([st[f"omega{k}"] for k in (1, 2, 3)])
    return [_flip_comparison(tr, J, w, "flip period after the push", t_end)]


def _flip_comparison(tr: Trajectory, J, w, name: str, t_lo: float) -> Comparison:
    """The time between the 1st and 3rd zeros of ω2 after t_lo against 4K(m)/λ of the
    body ω ``w`` (zeros located by brentq: a few thousand eps of the period at most)."""
    tol, why = _tol(tr)
    z = _zeros(tr, "omega2", 3, t_lo=t_lo)
    return Comparison(
        name,
        "5.3.3: 4K(m)/λ (derived)",
        z[2] - z[0],
        _flip_period(J, w),
        max(tol, 2**12 * EPS),
        why + ", zeros by brentq",
    )


# ------------------------------------------------------------------ Example 7.2


def rocket(scene: Scene, tr: Trajectory):
    """Example 7.2: v(t) = u ln(m0/(m0 − q t)) − g t (7.30), from rest, vertical."""
    g = _gravity(scene)
    th = scene.effects_of("thrust")
    _need(scene, len(th) == 1, "one thrust")
    f = th[0].fields
    b = scene.body(f["body"])
    _need(scene, not any(b.initial.get("velocity", [0, 0, 0])), "a start from rest")
    m0, q, u = b.mass, f["mass_flow"], f["exhaust_speed"]
    T = min(f["fuel_mass"] / q, scene.duration)
    tol, why = _tol(tr)
    out = []
    for frac in (0.25, 1.0):
        t = frac * T
        out.append(
            Comparison(
                f"v at t = {t:.6g} s",
                "E7.2 (7.30)",
                tr.state_at(t)["vz"],
                u * math.log(m0 / (m0 - q * t)) - g * t,
                tol,
                why,
            )
        )
    return out


# ------------------------------------------------------------------ Example 7.3


def carousel(scene: Scene, tr: Trajectory):
    """Example 7.3: (J0 + q R² t) φ̈ = −r q v − q R² φ̇ (7.39); solved (derived) with
    φ̇(0) = φ̇0: φ̇(t) = (J0 φ̇0 − r q v t)/(J0 + q R² t); the limit is −r v/R² (7.40),
    approached as φ̇ − φ̇_lim = (J0 φ̇0 + r v J0/R²)/(J0 + q R² t)."""
    b = scene.bodies[0]
    mf = scene.effects_of("mass_flow")
    ax = scene.effects_of("fixed_axis")
    _need(scene, len(mf) == 1 and len(ax) == 1, "one fixed_axis and one mass_flow")
    from mechanics.scenes.effects import FixedAxis

    J0 = FixedAxis(ax[0]).moment_of_inertia(b.mass, np.diag(body_inertia(b)))
    f = mf[0].fields
    q, v, r, R = f["rate"], f["speed"], f["offset"], f["radius"]
    w0 = float(b.initial.get("angular_velocity", 0.0))
    T = scene.duration
    tol, why = _tol(tr)
    lim = -r * v / R**2
    w = tr.state_at(T)["phidot"]
    rest = (J0 * w0 + r * v * J0 / R**2) / (J0 + q * R**2 * T)
    return [
        Comparison(
            "φ̇ at the end",
            "E7.3: solution of (7.39)",
            w,
            (J0 * w0 - r * q * v * T) / (J0 + q * R**2 * T),
            tol,
            why,
        ),
        Comparison(
            "φ̇ − φ̇_lim at the end",
            "E7.3 (7.40)",
            w - lim,
            rest,
            tol * abs(lim / rest),
            why + " (relative to |φ̇_lim|: the difference cancels)",
        ),
    ]


# ------------------------------------------------------------------ Example 8.1


def tank(scene: Scene, tr: Trajectory):
    """Example 8.1: u = √(2gh) (8.37) for a still surface; with A ḣ = −a u the level
    falls as √h = √h0 − (a/A)√(g/2) t (derived).  The simulation keeps the surface speed
    (quasi-steady Bernoulli, u² (1 − (a/A)²) = 2gh), which differs by O((a/A)²)."""
    g = _gravity(scene)
    b = scene.bodies[0]
    A, a = b.dims["area"], scene.effects_of("tank_outflow")[0].fields["hole_area"]
    rho = a / A
    h0 = b.initial["level"]
    T = scene.duration
    st = tr.state_at(T)
    c = rho * math.sqrt(g / 2)
    h_book = (math.sqrt(h0) - c * T) ** 2
    _need(scene, c * T < math.sqrt(h0), "the tank not yet empty at the end")
    tol, why = _tol(tr)
    corr = rho * rho
    u_sim = math.sqrt(2 * g * st["h"] / ((1 - rho) * (1 + rho)))
    return [
        Comparison(
            "outflow speed at the end",
            "E8.1 (8.37)",
            u_sim,
            math.sqrt(2 * g * st["h"]),
            tol + corr,
            f"{why} + surface speed (a/A)² = {corr:.1e}",
        ),
        Comparison(
            "level at the end",
            "E8.1 + continuity",
            st["h"],
            h_book,
            tol + 2 * corr * max(1.0, c * T / (math.sqrt(h0) - c * T)),
            f"{why} + surface speed 2(a/A)²·ct/(√h0 − ct)",
        ),
    ]


# ------------------------------------------------------------------ sliding ball


def sliding_ball(scene: Scene, tr: Trajectory):
    """A solid sphere launched without spin on a rough horizontal plane: friction μmg
    decelerates v = v0 − μgt and spins up ω = (5μg/(2r)) t; the slip v − ωr vanishes at
    t* = 2v0/(7μg), after which it rolls at 5v0/7 (derived from m v̇ = −μmg,
    (2/5)m r² ω̇ = μ m g r; equivalently from L about the contact line)."""
    g = _gravity(scene)
    b = scene.bodies[0]
    fr = scene.effects_of("coulomb_friction")[0].fields
    _need(
        scene,
        b.shape == "solid_sphere"
        and fr.get("angle", 0.0) == 0.0
        and not b.initial.get("spin", 0.0),
        "a solid sphere without spin on a horizontal plane",
    )
    v0, mu = b.initial["speed"], fr["mu"]
    ev = [e for e in tr.events if e.kind == "rolling"]
    _need(scene, len(ev) == 1, "the switch to rolling within the duration")
    tol, why = _tol(tr)
    return [
        Comparison(
            "switch to rolling at", "t* = 2v0/(7μg)", ev[0].t, 2 * v0 / (7 * mu * g), tol, why
        ),
        Comparison("final speed", "5 v0/7", tr.state_at(scene.duration)["v"], 5 * v0 / 7, tol, why),
    ]


# ------------------------------------------------------------------ Example 6.2


def rod_struck(scene: Scene, tr: Trajectory):
    """Example 6.2: a rod (the bat) at rest, struck perpendicular to it at its end (x = 0):
    just after the hit the point at distance 2ℓ/3 from the struck end is at rest (6.28),
    (6.29), and the rod's kinetic energy is T(0) = (S²/2m)(1 + 12 (0 − 1/2)²) = 2S²/m
    (6.26), with S the impulse the ball gave (read off the ball's change of momentum)."""
    rods = [b for b in scene.bodies if b.shape == "rod"]
    _need(scene, len(rods) == 1 and len(scene.bodies) == 2, "a rod and one striker")
    rod = rods[0]
    ball = next(b for b in scene.bodies if b is not rod)
    hits = [e for e in tr.events if e.kind == "impact"]
    _need(scene, len(hits) >= 1, "an impact within the duration")
    t_hit, ell, m = hits[0].t, rod.dims["length"], rod.mass
    after = tr.state_at(t_hit)  # the piece that starts at the impact: just after it
    r_before = np.array(rod.initial.get("position", [0.0] * 3))
    v0_ball = np.array(ball.initial.get("velocity", [0.0] * 3))
    p = f"{rod.name}."
    v_G = np.array([after[p + c] for c in ("vx", "vy", "vz")])
    w = np.array([after[p + c] for c in ("wx", "wy", "wz")])
    v_ball = np.array([after[f"{ball.name}.{c}"] for c in ("vx", "vy", "vz")])
    S = ball.mass * float(np.linalg.norm(v_ball - v0_ball))
    # the struck end and the rod's direction from it, from the contact point of the event
    end = np.array(hits[0].detail["contact_point"])
    u = (r_before - end) / np.linalg.norm(r_before - end)
    # points P = end + ξ u move with v_G + ω × (P − G); along the blow's line they stop at
    # ξ where the component along the blow vanishes (v_G ⟂ u; ω ⟂ u)
    n = v_G / np.linalg.norm(v_G)
    rate = float(np.cross(w, u) @ n)  # d(v·n)/dξ
    xi = (float(v_G @ n) + rate * (float((end - r_before) @ u))) / -rate
    T_rod = 0.5 * m * float(v_G @ v_G) + 0.5 * (m * ell * ell / 12.0) * float(w @ w)
    tol, why = _tol(tr)
    return [
        Comparison(
            "point at rest, from the struck end", "E6.2 (6.29): 2ℓ/3", xi, 2 * ell / 3, tol, why
        ),
        Comparison(
            "kinetic energy of the bat after the hit",
            "E6.2 (6.26): (S²/2m)(1 + 12(x/ℓ − 1/2)²), x = 0",
            T_rod,
            S * S / (2 * m) * (1 + 12 * 0.25),
            tol,
            why,
        ),
    ]


def cradle(scene: Scene, tr: Trajectory):
    """(6.36)–(6.38) with e = 1 and equal masses: a direct elastic impact exchanges the
    velocities, so in a row of touching balls the first one's velocity passes down the
    row and only the last ball moves on."""
    names = [b.name for b in scene.bodies]
    _need(scene, len({b.mass for b in scene.bodies}) == 1, "equal masses")
    _need(
        scene,
        all(e.fields["restitution"] == 1.0 for e in scene.effects_of("impact")),
        "elastic impacts (e = 1)",
    )
    v0 = float(scene.bodies[0].initial["velocity"][0])
    end = tr.state_at(scene.duration)
    tol, why = _tol(tr)
    out = [
        Comparison(
            f"{names[-1]} leaves with",
            "(6.38): the first ball's velocity",
            end[f"{names[-1]}.vx"],
            v0,
            tol,
            why,
        )
    ]
    out += [
        Comparison(
            f"{n} at rest after", "(6.38): velocities exchanged", end[f"{n}.vx"], 0.0, tol, why
        )
        for n in names[:-1]
    ]
    return out


def rocket_drag(scene: Scene, tr: Trajectory):
    """Example 7.2 with quadratic drag: m(t) v' = q u − m(t) g − c v|v|, m(t) = m0 − q t,
    from rest (the equation of motion (7.24) with the drag added).  No closed form: the
    reference is mpmath's Taylor-series solver at 30 digits, an independent route."""
    g = _gravity(scene)
    th = scene.effects_of("thrust")
    dr = scene.effects_of("drag")
    _need(scene, len(th) == 1 and len(dr) == 1, "one thrust and one drag")
    f, c = th[0].fields, dr[0].fields.get("quadratic", 0.0)
    _need(scene, not dr[0].fields.get("linear"), "quadratic drag only")
    b = scene.body(f["body"])
    _need(scene, not any(b.initial.get("velocity", [0, 0, 0])), "a start from rest")
    m0, q, u = b.mass, f["mass_flow"], f["exhaust_speed"]
    T = min(f["fuel_mass"] / q, scene.duration)
    ref = _rocket_drag_reference(m0, q, u, c, g, (0.25 * T, T))
    tol, why = _tol(tr)
    out = []
    for tt, (z, v) in ref.items():
        st = tr.state_at(tt)
        out.append(
            Comparison(
                f"v at t = {tt:.6g} s", "7.24 with drag (mpmath Taylor)", st["vz"], v, tol, why
            )
        )
        out.append(
            Comparison(
                f"z at t = {tt:.6g} s", "7.24 with drag (mpmath Taylor)", st["z"], z, tol, why
            )
        )
    return out


@functools.lru_cache(maxsize=8)
def _rocket_drag_reference(m0, q, u, c, g, times) -> dict[float, list[float]]:
    """(z, v) at the times by mpmath's Taylor-series ODE solver at 20 digits (cached: the
    exact and the integrated run compare with the same reference).  20 digits leave the
    reference ~1e-20 relative off, against the comparison's 9.3e-10 (and the run's ~1e-13):
    its floats at t = 20 and 80 s are those of 30 digits bit for bit, in 2.0 s instead of
    4.9 s (measured with mpmath.odefun on Example 7.2's numbers)."""
    import mpmath

    with mpmath.workdps(20):
        sol = mpmath.odefun(
            lambda t, y: [y[1], (q * u - c * y[1] * abs(y[1])) / (m0 - q * t) - g], 0, [0, 0]
        )
        return {tt: [float(x) for x in sol(tt)] for tt in times}


def corner_impacts(scene: Scene, tr: Trajectory):
    """6.2–6.3 at a corner: each impact reverses the corner's normal velocity with the
    factor e (6.36), and the kinetic energy drops by ½ μ (1 − e²) v_n² (6.41) with the
    effective mass 1/μ = 1/m + (ρ × n)·J⁻¹(ρ × n) at the contact (6.19), (6.21),
    computed here by :func:`mechanics.impact.effective_mass` from the body's state."""
    from mechanics.impact import effective_mass

    e = _plane_impact(scene)["restitution"]
    hits = [ev for ev in tr.events if ev.kind == "impact"]
    _need(scene, len(hits) >= 1, "an impact within the duration")
    tol, why = _tol(tr)
    out = []
    for k, ev in enumerate(hits[:3]):
        d = ev.detail
        (bd,) = d["bodies_before"]
        rho = np.subtract(d["contact_point"], bd["r_G"])
        mu = float(effective_mass(bd["m"], bd["J_G"], rho, d["normal"]))
        vn = d["normal_speed_before"]
        out.append(
            Comparison(
                f"impact {k + 1}: e = after/before",
                "(6.36)",
                d["normal_speed_after"] / vn,
                e,
                tol,
                why,
            )
        )
        out.append(
            Comparison(
                f"impact {k + 1}: energy lost",
                "(6.41): ½ μ (1 − e²) v_n²",
                d["kinetic_energy_before"] - d["kinetic_energy_after"],
                0.5 * mu * (1 - e * e) * vn * vn,
                max(tol, 2**10 * EPS),
                why + "; T read off the velocities",
            )
        )
    return out


def corner_impacts_friction(scene: Scene, tr: Trajectory):
    """6.2–6.3 with Coulomb friction at a corner: the corner's normal velocity reverses
    with the factor e (6.36); the impulse, read off the box's change of momentum
    S = m Δv_G (6.19), lies in the friction cone; if the corner sticks its tangential
    velocity after the impact is zero, if it slips |S_t| = μ S_n; and the change of the
    spin matches the moment of that impulse about G, J Δω = ρ × S (6.21)."""
    imp = _plane_impact(scene)
    e, mu = imp["restitution"], imp.get("friction", 0.0)
    _need(scene, mu > 0, "friction on the impulse")
    hits = [ev for ev in tr.events if ev.kind == "impact"]
    _need(scene, len(hits) >= 1, "an impact within the duration")
    tol, why = _tol(tr)
    out = []
    for k, ev in enumerate(hits[:3]):
        d = ev.detail
        (b0,), (b1,) = d["bodies_before"], d["bodies_after"]
        n, S_pt = np.array(d["normal"]), np.array(d["contact_point"])
        rho = S_pt - np.array(b1["r_G"])
        S = b1["m"] * (np.subtract(b1["v_G"], b0["v_G"]))
        S_n = float(S @ n)
        S_t = float(np.linalg.norm(S - S_n * n))

        def corner_velocity(b, rho=rho):
            return np.array(b["v_G"]) + np.cross(b["omega"], rho)

        u0, u1 = corner_velocity(b0), corner_velocity(b1)
        out.append(
            Comparison(
                f"impact {k + 1}: e = after/before", "(6.36)", -(u1 @ n) / (u0 @ n), e, tol, why
            )
        )
        if d["friction"] == "stick":
            t1 = u1 - (u1 @ n) * n
            out.append(
                Comparison(
                    f"impact {k + 1}: sticks, corner's sliding speed after",
                    "Coulomb stick: 0 (relative to |u| before)",
                    float(np.linalg.norm(t1)) / float(np.linalg.norm(u0)),
                    0.0,
                    tol,
                    why,
                )
            )
            out.append(
                Comparison(
                    f"impact {k + 1}: sticks, excess over the cone S_t/(μ S_n) − 1",
                    "Coulomb stick: |S_t| ≤ μ S_n, so ≤ 0",
                    max(S_t / (mu * S_n) - 1.0, 0.0),
                    0.0,
                    tol,
                    why,
                )
            )
        else:
            out.append(
                Comparison(
                    f"impact {k + 1}: slips, S_t/S_n", "Coulomb slip: μ", S_t / S_n, mu, tol, why
                )
            )
        J0, J1 = np.array(b0["J_G"]), np.array(b1["J_G"])
        dL = J1 @ np.array(b1["omega"]) - J0 @ np.array(b0["omega"])
        M = np.cross(rho, S)
        out.append(
            Comparison(
                f"impact {k + 1}: |J Δω − ρ × S| / |ρ × S|",
                "(6.21)",
                float(np.linalg.norm(dL - M)) / float(np.linalg.norm(M)),
                0.0,
                tol,
                why,
            )
        )
    return out


def top_until_floor(scene: Scene, tr: Trajectory):
    """5.2 until the first contact: on its fixed point, before any impact, the top moves
    as the heavy symmetric top whose nutation the book solves with elliptic functions;
    its centre's height over the pivot is ℓ cos θ(t) with θ(t) from
    :class:`mechanics.tops.HeavySymmetricTop` (J1' = J1 + m ℓ² (5.46), J3, m g ℓ).  Then
    every impact restitutes the corner's normal velocity by e (6.36)."""
    from mechanics.tops import HeavySymmetricTop

    fp = scene.effects_of("fixed_point")
    _need(
        scene,
        len(fp) == 1 and not any(fp[0].fields.get("point", [0, 0, 0])),
        "one fixed point at the origin",
    )
    g = _gravity(scene)
    b = scene.body(fp[0].fields["body"])
    ell = fp[0].fields["distance"]
    J = np.asarray(body_inertia(b))
    _need(scene, J[0] == J[1], "a symmetric body (J1 = J2)")
    keys = ("theta", "psi", "phi", "theta_dot", "psi_dot", "phi_dot")
    top = HeavySymmetricTop(
        J[0] + b.mass * ell**2,
        J[2],
        b.mass * g * ell,
        **{k: float(b.initial.get(k, 0.0)) for k in keys},
    )
    hits = [ev for ev in tr.events if ev.kind == "impact"]
    _need(scene, len(hits) >= 1, "an impact within the duration")
    tol, why = _tol(tr)
    out = []
    for frac in (0.5, 1.0):
        t = frac * hits[0].t
        out.append(
            Comparison(
                f"z_G/ℓ = cos θ at t = {t:.6g} s (before the floor)",
                "5.2: the heavy top's θ(t), elliptic functions",
                tr.state_at(t)["z"] / ell,
                float(np.cos(top.theta(t))),
                tol,
                why,
            )
        )
    e = scene.effects_of("impact")[0].fields["restitution"]
    for k, ev in enumerate(hits[:3]):
        d = ev.detail
        out.append(
            Comparison(
                f"impact {k + 1}: e = after/before",
                "(6.36)",
                d["normal_speed_after"] / d["normal_speed_before"],
                e,
                tol,
                why,
            )
        )
    return out


COMPARISONS = {
    "E6.1": bouncing_ball,
    "E3.6": rolling_incline,
    "E4.3-E4.4": pendulum_horizontal,
    "E4.3": pendulum_small,
    "E4.5": cylinder_in_track,
    "5.2": heavy_top,
    "5.3.3": intermediate_axis_flip,
    "5.3.3-push": flip_after_push,
    "E6.2": rod_struck,
    "cradle": cradle,
    "rocket-drag": rocket_drag,
    "corner-impacts": corner_impacts,
    "corner-impacts-friction": corner_impacts_friction,
    "top-until-floor": top_until_floor,
    "E7.2": rocket,
    "E7.3": carousel,
    "E8.1": tank,
    "sliding": sliding_ball,
}


def book_comparison(scene: Scene):
    """The comparison a scene names (``scene.compare``), or None; SceneError naming the
    file and field when the name is unknown."""
    if not scene.compare:
        return None
    if scene.compare not in COMPARISONS:
        raise SceneError(
            scene.source,
            "scene.compare",
            f"unknown comparison {scene.compare!r} (known: {', '.join(COMPARISONS)})",
        )
    return COMPARISONS[scene.compare]


def run_book_scene(scene: Scene):
    """Run a scene and compare it with the book where it names a comparison.  A
    comparison that cannot be read off the run (too few samples or too short a duration
    for the crossings it measures) is a SceneError naming ``scene.compare``."""
    compare = book_comparison(scene)
    if compare is None:
        return run_scene(scene)

    def guarded(sc, tr):
        try:
            rows = list(compare(sc, tr))
        except SceneError:
            raise
        except (RuntimeError, ValueError, ArithmeticError) as exc:
            raise sc.error(
                "scene.compare",
                f"the comparison {sc.compare!r} cannot be read off this run ({exc}); give "
                "it more samples or the duration of the built-in scene",
            ) from None
        for c in rows:
            for side, x in (
                ("simulated", c.simulated),
                ("book's closed form", c.closed_form),
                ("tolerance of", c.tolerance),
            ):
                if not math.isfinite(x):
                    raise sc.error(
                        "scene.compare",
                        f"the comparison {sc.compare!r}: the {side} {c.name} is {float(x)!r} for this "
                        "scene (its numbers are beyond the closed form's reach in float64); "
                        "bring them nearer the built-in scene's",
                    )
        return rows

    return run_scene(scene, compare=guarded)


def load_book_scene(path) -> Scene:
    """Load a scene file and check that the comparison it names is known."""
    scene = load_scene(path)
    book_comparison(scene)
    return scene
