"""The battery's scenarios and their exact references (issue 19).

Each scenario is a :class:`~mechanics.conformance.protocol.Scenario` whose
``extra["kind"]`` names its exact solution; :func:`reference` computes, from the
scenario's own fields (so a user's variant with other numbers gets its own answer), the
exact states at the sample times and the derived figures; :func:`measure` reads the same
figures off any trajectory's samples; :func:`invariants` gives the quantities the laws
conserve in that scenario, sampled along a trajectory, with their scales.

The scenarios (:data:`SCENARIOS`)
---------------------------------
``free_top_axis1``, ``free_top_axis3``
    A torque-free asymmetric body, J = (2, 3, 4) kg m² (a box of half extents
    (√7.5, √4.5, √1.5) m, 1 kg), tilted, ω circulating the axis of least (axis1:
    L² < 2EJ₂) or of greatest moment (axis3: L² > 2EJ₂).  Exact: Jacobi elliptic
    functions (:class:`mechanics.tops.FreeAsymmetricTop`, Euler's equations (4.47),
    Poinsot (5.85)–(5.90)).  Figure: the period of ω, 4K/λ.  Conserved: E, p, L (about
    G, which stays at the origin, so also about the origin).
``free_top_near_separatrix``
    The same body spun at 4 rad/s about the intermediate axis, 0.04 rad/s off it:
    L² − 2EJ₂ = −3.2e-3 kg² m⁴ s⁻² against L² = 144, the elliptic complement m₁ = 1.3e-4;
    the body flips every 8.3 s (ω's period 16.5 s), 11.7 e-folding times 1/λ₀ of the
    unstable small motion about axis 2 (λ₀ = 4 √((J₂ − J₁)(J₃ − J₂)/(J₁J₃)) = 1.41/s).
    An energy error δE/E moves L² − 2EJ₂ by 2J₂E δE/E = 144 δE/E, so m₁ by a relative
    4.5e4 δE/E: the period and the phase test an engine's energy behaviour near the
    separatrix (Section 5.3.3).
``heavy_top``
    A heavy symmetric top on a frictionless pivot ℓ = 0.1 m below G (J₁ = J₂ = 0.3,
    J₃ = 0.5 kg m² about G, 1 kg, g = 9.81 m/s²), released at θ = 0.6 rad with spin
    φ̇ = 6 rad/s and no precession.  Exact: :class:`mechanics.tops.HeavySymmetricTop`
    (5.2.2–5.2.5).  Figures: θ(t) (largest error, relative to its range), the nutation
    period 2K/κ and the mean precession rate over whole nutation periods.  Conserved: E
    and the angular momentum about the pivot's vertical L_z (5.55), and L₃ = J₃ω₃ (5.53).
``parabola``
    A spinning ball thrown under gravity (no ground).  Exact: the parabola (ṗ = F, (1.1))
    and the free rotation.  Figures: the apex's height and time.  Conserved: E (with
    m g z) and the horizontal momentum.
``two_body_impact``
    Two spheres (1 kg and 3 kg) head-on along x, e = 0.6, no gravity.  Exact: uniform
    motion and the direct impact (6.36)–(6.38) (:func:`mechanics.impact.direct_impact`).
    Figures: the velocities after, the restitution e measured from them and the impact
    time read back from the final gap.  Conserved across the impact: p and L about the
    origin (the impulse is internal and central); E is not (6.41).
``bouncing_ball``
    A ball dropped from h₀ = 1.275 m (its lowest point) onto smooth ground, e = 0.8,
    moving sideways at 0.5 m/s.  Exact: the apex heights e^{2k} h₀ at the times
    t_f(1 + 2e + … + 2e^{k−1} + e^k), t_f = √(2h₀/g) (Example 6.1, (6.6)).  Figures:
    the three apex heights and times.  Conserved: the horizontal momentum only (smooth
    impacts); E is lost at each impact.
``rocket``
    A rocket of 10 kg burning 0.5 kg/s for 8 s at exhaust speed 20 m/s along its tilted
    body axis 3, in free space.  Exact: Tsiolkovsky's Δv = u ln(m₀/m₁) (7.30) and the
    mass m₀ − q t.  Figures: Δv and the burn-out mass.  Nothing is conserved (mass
    leaves with momentum and energy).
``box_landing_flat``
    A box (half extents 0.3, 0.2, 0.1 m) dropped flat onto rough ground, e = 0.7,
    μ = 0.5: its four corners strike at once, so it bounces as the ball does (kind
    ``bounce``: the lowest point's depth below G is the box's half height), with no spin
    and no sliding.
``sliding_stop``
    The box sliding on its face at 2 m/s, μ = 0.5: decelerated by μ g to rest at
    v₀/(μ g), v₀²/(2 μ g) from its start (it does not tip: μ h under its half length).
    Figures: the stop distance and time.  Nothing is conserved.
``incline_rolling``
    A solid ball released on a 0.3 rad incline (flat ground, gravity tilted), μ = 0.5:
    it rolls without slipping at a = g_t / (1 + J/(m r²)) = 5/7 g sin α, ω = n × v / r.
    Figures: the acceleration and the final ω r.  Conserved: E (rolling does no work).
``bounce_to_rest``
    A ball dropped from 0.41 m onto smooth ground, e = 0.5 (kind ``rest``): its impacts
    accumulate at t_f (1 + e)/(1 − e) = 0.867 s, then it rests.  Figures: the first two
    apexes (the later flights are shorter than the samples) and the rest time, the first
    sample from which the speed stays at or below ``REST_FRACTION`` of the first
    impact speed.  Conserved: the tangential momentum.
``oblique_impact_sticks``, ``oblique_impact_slips``
    A solid ball falling 0.45 m, moving sideways at 1 or 3 m/s, onto rough ground
    (e = 0.5, μ = 0.5 or 0.1; kind ``oblique``): the impulse at the contact point
    (Section 6.2) with Newton's e (6.6) on the normal part; the tangential impulse stops
    the slip where that takes at most μ P_n (the ball leaves rolling), else it is μ P_n
    against the slip (Coulomb's bound).  Figures: the tangential velocity and ω after,
    the rebound's apex height.
``newtons_cradle``
    Three equal balls, the first at 1 m/s striking the two touching at rest, each pair
    elastic: the momentum passes down the row (the direct impact with e = 1, pair by
    pair), the first two stop and the last leaves at 1 m/s.  Figures: the velocities
    after and the impact time.  Conserved: E, p, L.

Samples are uniform at binary fractions of a second (1/128 to 1/8 s) and ``steps`` are
2⁻⁶, 2⁻⁷, 2⁻⁸ s (the heavy top 2⁻⁷ … 2⁻⁹): every product n·h is exact, every sample a
whole number of steps.  Impacts fall at least 9 ms from any sample, so a sample is never
between an impact and an engine's slightly late one at the finest step (3.9 ms), the run
that is judged.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TypeVar

import numpy as np

from .._floats import EPS
from ..errors import MechanicsValueError
from ..kinematics import angular_velocity_from_euler_rates
from ..rotation import euler_from_matrix, matrix_from_euler
from .protocol import Body, Ground, Pivot, Scenario, Shape, Thrust, Trajectory

__all__ = [
    "FIGURES",
    "FLIGHT_STEPS",
    "GRID_RTOL",
    "IMPACT_MARGIN_STEPS",
    "INVARIANTS",
    "SCENARIOS",
    "Reference",
    "ScenarioRangeError",
    "UnknownScenarioError",
    "body_sizes",
    "bounce_apexes",
    "check_scenario",
    "crossings",
    "figure_names",
    "get_scenario",
    "interpolate",
    "invariant_names",
    "invariants",
    "measure",
    "reference",
]


class UnknownScenarioError(MechanicsValueError):
    """A scenario name the battery does not have, or a scenario of an unknown kind."""


@dataclass(frozen=True)
class Reference:
    """The exact answer to a scenario: the states at its sample times and derived figures.

    Parameters
    ----------
    trajectory : Trajectory
        The exact states at the scenario's sample times.
    figures : dict
        The derived figures by name (:func:`figure_names`), each a float or, for a
        sequence such as the apex heights, an array.

    Examples
    --------
    The parabola's apex time is v_z/g, thrown at 8 m/s under g = 9.81 m/s²:

    >>> s = get_scenario("parabola")
    >>> ref = reference(s)
    >>> bool(ref.figures["apex_time"] == s.bodies[0].velocity[2] / -s.gravity[2])
    True
    """

    trajectory: Trajectory
    figures: dict


# --------------------------------------------------------------------------- helpers


def _vec3(v) -> tuple[float, float, float]:
    """A 3-vector as a tuple of three floats."""
    x, y, z = (float(c) for c in v)
    return x, y, z


def _rows(R) -> tuple[tuple[float, float, float], ...]:
    return tuple(_vec3(row) for row in np.asarray(R))


def _times(duration: float, dt: float) -> tuple[float, ...]:
    n = round(duration / dt)
    return tuple(k * dt for k in range(n + 1))


def _free_rotation(body: Body, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(R_A_O, ω_A) of a torque-free body at times t, shapes (m, 3, 3), (m, 3)."""
    from ..tops import FreeAsymmetricTop

    top = FreeAsymmetricTop(body.inertia, body.omega, np.array(body.R_A_O))
    return top.attitude(t), top.omega(t)


_Part = TypeVar("_Part")


def _required(s: Scenario, what: str, part: _Part | None) -> _Part:
    """The scenario's ``part`` (its pivot, ground, thrust, a body's shape), which its kind
    needs: a MechanicsValueError naming the scenario when it is None."""
    if part is None:
        raise MechanicsValueError(
            f"scenario {s.name!r}: a scenario of kind {s.extra.get('kind')!r} needs {what}; "
            "it has none"
        )
    return part


def _stack(t, bodies, pos, vel, R, w, masses=None) -> Trajectory:
    return Trajectory(
        np.asarray(t, dtype=float),
        np.stack(pos, axis=1),
        np.stack(vel, axis=1),
        np.stack(R, axis=1),
        np.stack(w, axis=1),
        None if masses is None else np.stack(masses, axis=1),
    )


def _window(n: int, k: int, size: int) -> slice:
    """``size`` consecutive indices around the interval [k, k + 1], inside [0, n)."""
    lo = min(max(k - (size - 2) // 2, 0), max(n - size, 0))
    return slice(lo, min(lo + size, n))


def _local_poly(t, y, k, deg):
    """The polynomial through the samples around the interval [t_k, t_k+1] (k < n − 1),
    in x = (t − t_k)/h with h that interval's length."""
    s = _window(t.size, k, deg + 1)
    h = t[k + 1] - t[k]
    x = (t[s] - t[k]) / h
    coef = np.polynomial.polynomial.polyfit(x, y[s], min(deg, x.size - 1))
    return coef, h


def interpolate(t, y, tau: float, deg: int = 5) -> float:
    """y at time tau by the polynomial of degree ``deg`` through the nearest samples.

    Parameters
    ----------
    t : array_like, shape (m,)
        Sample times, increasing, m ≥ 2.
    y : array_like, shape (m,)
        The samples.
    tau : float
        The time to interpolate at (outside [t₀, t_m−1]: the end polynomial extrapolates).
    deg : int, optional
        The polynomial's degree, ≥ 0, through the ``deg + 1`` nearest samples (fewer when
        there are fewer); default 5.

    Returns
    -------
    float
        The polynomial's value at ``tau``.

    Raises
    ------
    TypeError
        Where ``t`` and ``y`` differ in length, or ``y`` is not one-dimensional (numpy's
        polynomial fit; the function validates nothing itself).
    ValueError
        Where ``deg`` < 0 or a sample is not a number.
    IndexError
        Where ``t`` is empty (with one sample numpy's fit fails instead: a RuntimeWarning
        of a division by zero, then ``numpy.linalg.LinAlgError``).

    Examples
    --------
    A cubic through its samples, read back at 0.3:

    >>> t = np.linspace(0.0, 1.0, 9)
    >>> round(interpolate(t, t**3, 0.3), 12) == round(0.3**3, 12)
    True
    """
    t, y = np.asarray(t, dtype=float), np.asarray(y, dtype=float)
    k = int(np.clip(np.searchsorted(t, tau) - 1, 0, t.size - 2))
    coef, h = _local_poly(t, y, k, deg)
    return float(np.polynomial.polynomial.polyval((tau - t[k]) / h, coef))


#: the error of a local polynomial's coefficients (in x = (t − t_k)/h, nodes within −4 … 5),
#: relative to the largest sample of its window: measured ≤ 12 eps over 3000 random quintics
#: sampled at spacings 2^-5 … 1 against the exact interpolant (fractions); 2^6 eps bounds it
#: with a margin of 5 and also covers Horner's (deg + 1) eps of the evaluation
_FIT_NOISE = 2**6 * EPS
#: Newton steps on a derivative's simple root from the bisected root: quadratic convergence
#: from within the sign change's rounding cluster reaches rounding in ≤ 6
_NEWTON_STEPS = 8


def _sign_change(coef, s0: float) -> float:
    """The point of [0, 1] where the polynomial ``coef`` changes sign, by bisection to the
    last bit; the sign at 0 is ``s0`` (the sample's, so a sample below the fit's rounding
    keeps its side) and the sign at 1 its opposite."""
    P = np.polynomial.polynomial
    lo, hi = 0.0, 1.0
    while True:
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            return lo if abs(P.polyval(lo, coef)) <= abs(P.polyval(hi, coef)) else hi
        v = P.polyval(mid, coef)
        if v == 0:
            return mid
        if (v > 0) == (s0 > 0):
            lo = mid
        else:
            hi = mid


def _root_of_any_multiplicity(coef, s0: float, y_scale: float) -> float:
    """The root in [0, 1] of the polynomial ``coef`` where it changes sign from ``s0``'s,
    of any multiplicity m.

    Bisection finds the sign change of the computed polynomial, which for a root of
    multiplicity m lies anywhere in a cluster of width ~ (rounding)^(1/m) around the root.
    A root of multiplicity m is a simple root of the (m − 1)-th derivative, where Newton's
    method converges quadratically and to rounding: for m = 2, 3, … the derivative's root
    near the bisected point is taken while every lower derivative vanishes there to the
    fit's rounding (``_FIT_NOISE`` times the window's sample scale, weighted by the
    derivative's factors), so the multiplicity is the largest m that the values allow.
    """
    P = np.polynomial.polynomial
    x_hat = _sign_change(coef, s0)
    derivs = [np.asarray(coef, dtype=float)]
    while derivs[-1].size > 1:
        derivs.append(P.polyder(derivs[-1]))
    deg = len(derivs) - 1
    # |P^(j)(x)| on [0, 1] is uncertain by Σ_{i ≥ j} i!/(i − j)! times a coefficient's error
    noise = [
        _FIT_NOISE * (y_scale * sum(math.perm(i, j) for i in range(j, deg + 1)) + np.abs(d).sum())
        for j, d in enumerate(derivs)
    ]
    best = x_hat
    for m in range(2, deg + 1):
        d, dd = derivs[m - 1], derivs[m]
        x = x_hat
        for _ in range(_NEWTON_STEPS):
            slope = P.polyval(x, dd)
            if slope == 0:
                break
            x = x - P.polyval(x, d) / slope
            if not 0.0 <= x <= 1.0:
                return best
        if not all(abs(P.polyval(x, derivs[j])) <= noise[j] for j in range(m - 1)):
            return best
        best = x
    return best


def crossings(t, y, *, deg: int = 5, direction: int = 0) -> np.ndarray:
    """Times where the sampled y changes sign, each a root of a local interpolating polynomial.

    ``direction`` +1: rising only, −1: falling only.  Each time is the root of the
    interpolating polynomial of degree ``deg`` through the nearest ``deg + 1`` samples
    (error O(Δt^{deg+1}) for a smooth y).

    A sample that is exactly zero is the crossing's time (it counts on the side it ends, so
    a tangency that touches zero at a sample counts once).  A root of any multiplicity is
    found to rounding by :func:`_root_of_any_multiplicity`: for samples of a polynomial of
    degree ≤ ``deg`` with a root of multiplicity m ≤ 3 (and its other roots at least Δt
    away), the time is within 2^3 eps·max(|t|, Δt) of the root, at a sample or between
    two (measured ≤ 1.7; ``tests/conformance/test_crossings.py``).

    Parameters
    ----------
    t : array_like, shape (m,)
        Sample times, increasing.
    y : array_like, shape (m,)
        The samples.
    deg : int, optional
        The degree of the local polynomials, ≥ 0 (default 5).
    direction : {0, 1, -1}, optional
        0 (default): every sign change; > 0: rising only; < 0: falling only.

    Returns
    -------
    ndarray, shape (k,)
        The crossing times, in order.

    Raises
    ------
    TypeError
        Where ``t`` and ``y`` differ in length (numpy's polynomial fit; the function
        validates nothing itself).
    ValueError
        Where ``deg`` < 0 or a sample is not a number.

    Examples
    --------
    The roots of (t − 0.3)(t − 0.7), sampled at steps of 1/8; falling through 0 at 0.3:

    >>> t = np.linspace(0.0, 1.0, 9)
    >>> [round(float(x), 12) for x in crossings(t, (t - 0.3) * (t - 0.7))]
    [0.3, 0.7]
    >>> crossings(t, (t - 0.3) * (t - 0.7), direction=-1).round(12).tolist()
    [0.3]
    """
    t, y = np.asarray(t, dtype=float), np.asarray(y, dtype=float)
    rises = (y[:-1] < 0) & (y[1:] >= 0)  # a zero at a sample counts on the side it ends
    falls = (y[:-1] > 0) & (y[1:] <= 0)
    want = rises | falls if direction == 0 else (rises if direction > 0 else falls)
    out = []
    for k in np.nonzero(want)[0]:
        if y[k + 1] == 0:
            out.append(t[k + 1])
            continue
        coef, h = _local_poly(t, y, int(k), deg)
        y_scale = float(np.max(np.abs(y[_window(t.size, int(k), deg + 1)])))
        out.append(t[k] + h * _root_of_any_multiplicity(coef, y[k], y_scale))
    return np.array(out)


def _gravity(s: Scenario) -> np.ndarray:
    return np.asarray(s.gravity, dtype=float)


def _kinetic(s: Scenario, tr: Trajectory) -> np.ndarray:
    m = np.array([b.mass for b in s.bodies]) if tr.masses is None else tr.masses
    J = np.array([b.inertia for b in s.bodies])
    T = 0.5 * m * (tr.velocity**2).sum(-1) + 0.5 * (J * tr.omega**2).sum(-1)
    return T.sum(-1)


def _energy(s: Scenario, tr: Trajectory) -> tuple[np.ndarray, float]:
    """Kinetic (½ m v² + ½ Σ J_i ω_i², (5.85)) plus potential −m g·r energy, and its
    scale: the largest of the kinetic and the potential parts' sizes."""
    m = np.array([b.mass for b in s.bodies])
    T = _kinetic(s, tr)
    V = -(m[None, :, None] * _gravity(s) * tr.position).sum((-1, -2))
    scale = max(float(np.max(np.abs(T))), float(np.max(np.abs(V))), 1e-300)
    return T + V, scale


def body_sizes(s: Scenario) -> np.ndarray:
    """Each body's size: the larger of √(max J / m) and the norm of its shape's dimensions.

    The first is the body's largest radius of gyration.

    Parameters
    ----------
    s : Scenario
        The scenario whose bodies to measure.

    Returns
    -------
    ndarray, shape (n,)
        The sizes, m, one per body.

    Raises
    ------
    ZeroDivisionError
        Where a body's mass is 0 (the scenario is not validated here).
    ValueError
        Where a body's max J / m is negative (``math.sqrt``'s domain).

    Examples
    --------
    The bouncing ball (r = 0.1 m, J = 2/5 m r² < m r²) measures its radius:

    >>> s = get_scenario("bouncing_ball")
    >>> body_sizes(s).tolist() == [s.bodies[0].shape.dims[0]]
    True
    """
    out = []
    for b in s.bodies:
        size = math.sqrt(max(b.inertia) / b.mass)
        if b.shape is not None:
            size = max(size, float(np.linalg.norm(b.shape.dims)))
        out.append(size)
    return np.array(out)


def _momentum(s: Scenario, tr: Trajectory) -> tuple[np.ndarray, float]:
    """Total momentum; scale: the largest Σ m|v|, or, where nothing translates (a free
    top), Σ m·size·max|ω|, the momentum of the bodies' points."""
    m = np.array([b.mass for b in s.bodies])
    P = (m[None, :, None] * tr.velocity).sum(1)
    scale = float(np.max((m[None, :] * np.linalg.norm(tr.velocity, axis=-1)).sum(-1)))
    spin = m * body_sizes(s) * np.max(np.linalg.norm(tr.omega, axis=-1), axis=0)
    return P, max(scale, float(spin.sum()), 1e-300)


def _angular_momentum(s: Scenario, tr: Trajectory, about) -> tuple[np.ndarray, float]:
    """L about the fixed point ``about``: orbital (r − about) × m v plus the spins about
    G, R_A_Oᵀ J ω, summed over the bodies; scale: the largest sum of the parts' sizes,
    |r − about| m |v| + |J ω| (not of the cross product, zero for a head-on motion
    through the point)."""
    m = np.array([b.mass for b in s.bodies])
    J = np.array([b.inertia for b in s.bodies])
    r = tr.position - np.asarray(about, dtype=float)
    orb = np.cross(r, m[None, :, None] * tr.velocity)
    spin = np.einsum("tbji,tbj->tbi", tr.R_A_O, J * tr.omega)
    L = (orb + spin).sum(1)
    size = np.linalg.norm(r, axis=-1) * m * np.linalg.norm(tr.velocity, axis=-1)
    scale = float(np.max((size + np.linalg.norm(spin, axis=-1)).sum(-1)))
    return L, max(scale, 1e-300)


# --------------------------------------------------------------------------- free tops


def _ref_free(s: Scenario) -> Reference:
    t = np.asarray(s.sample_times)
    pos, vel, Rs, ws = [], [], [], []
    for b in s.bodies:
        R, w = _free_rotation(b, t)
        v0 = np.asarray(b.velocity, dtype=float)
        pos.append(np.asarray(b.position) + t[:, None] * v0)
        vel.append(np.broadcast_to(v0, (t.size, 3)))
        Rs.append(R)
        ws.append(w)
    from ..tops import FreeAsymmetricTop

    b = s.bodies[0]
    top = FreeAsymmetricTop(b.inertia, b.omega, np.array(b.R_A_O))
    return Reference(_stack(t, s.bodies, pos, vel, Rs, ws), {"omega_period": top.flip_period()})


def _measure_free(s: Scenario, tr: Trajectory) -> dict:
    b = s.bodies[0]
    mid = int(np.argsort(b.inertia, kind="stable")[1])
    z = crossings(tr.t, tr.omega[:, 0, mid])
    if z.size < 2:
        return {
            "omega_period": f"ω{mid + 1} crosses zero {z.size} time(s) in the samples; "
            "2 are needed for the period"
        }
    return {"omega_period": 2.0 * (z[-1] - z[0]) / (z.size - 1)}


def _inv_free(s: Scenario, tr: Trajectory) -> dict:
    return {
        "E": _energy(s, tr),
        "p": _momentum(s, tr),
        "L": _angular_momentum(s, tr, (0.0, 0.0, 0.0)),
    }


# --------------------------------------------------------------------------- heavy top


def _heavy_top(s: Scenario):
    from ..tops import HeavySymmetricTop

    pv = _required(s, "a pivot", s.pivot)
    b = s.bodies[pv.body]
    J1, J2, J3 = b.inertia
    g = _gravity(s)
    ell = -pv.point[2]
    if J1 != J2 or pv.point[0] != 0 or pv.point[1] != 0 or ell <= 0:
        raise MechanicsValueError(
            f"scenario {s.name!r}: the heavy top needs J1 = J2 and the pivot on axis 3 below "
            f"G; got inertia {b.inertia}, pivot point {pv.point}"
        )
    if g[0] != 0 or g[1] != 0 or g[2] >= 0:
        raise MechanicsValueError(f"scenario {s.name!r}: gravity must point along −z; got {g}")
    R0 = np.array(b.R_A_O)
    psi, theta, phi = (float(x) for x in euler_from_matrix(R0))
    w = np.asarray(b.omega, dtype=float)
    st, ct, sp, cp = math.sin(theta), math.cos(theta), math.sin(phi), math.cos(phi)
    psi_dot = (w[0] * sp + w[1] * cp) / st
    theta_dot = w[0] * cp - w[1] * sp
    phi_dot = w[2] - psi_dot * ct
    top = HeavySymmetricTop(
        J1 + b.mass * ell * ell,
        J3,
        b.mass * -g[2] * ell,
        theta=theta,
        psi=psi,
        phi=phi,
        theta_dot=theta_dot,
        psi_dot=psi_dot,
        phi_dot=phi_dot,
    )
    return top


def _ref_heavy(s: Scenario) -> Reference:
    t = np.asarray(s.sample_times)
    top = _heavy_top(s)
    psi, theta, phi = top.psi(t), top.theta(t), top.phi(t)
    thd, psid, phid = top.rates(t)
    R = matrix_from_euler(psi, theta, phi)
    w = angular_velocity_from_euler_rates(psi, theta, phi, psid, thd, phid)  # (2.69)
    pv = _required(s, "a pivot", s.pivot)
    rho = -np.einsum("tji,j->ti", R, np.asarray(pv.point, dtype=float))  # G − C, space
    pos = np.asarray(pv.anchor, dtype=float) + rho
    w_O = np.einsum("tji,tj->ti", R, w)
    vel = np.cross(w_O, rho)
    T = top.nutation_period()
    rate = float(top.psi(T) - top.psi(0.0)) / T
    figs = {"nutation_period": T, "precession_rate": rate, "theta": theta}
    return Reference(_stack(t, s.bodies, [pos], [vel], [R], [w]), figs)


def _u_dot(tr: Trajectory, i: int) -> np.ndarray:
    """d(cos θ)/dt = d(R₃₃)/dt from the passive attitude and body ω: Ṙ = −[ω]× R."""
    R, w = tr.R_A_O[:, i], tr.omega[:, i]
    return w[:, 1] * R[:, 0, 2] - w[:, 0] * R[:, 1, 2]


def _measure_heavy(s: Scenario, tr: Trajectory) -> dict:
    i = _required(s, "a pivot", s.pivot).body
    R = tr.R_A_O[:, i]
    out: dict = {"theta": np.arctan2(np.hypot(R[:, 2, 0], R[:, 2, 1]), R[:, 2, 2])}
    turns = crossings(tr.t, _u_dot(tr, i))
    if turns.size < 3:
        msg = f"θ turns {turns.size} time(s) in the samples; 3 are needed for a period"
        out["nutation_period"] = out["precession_rate"] = msg
        return out
    n = (turns.size - 1) // 2 * 2  # whole periods: turning points of one kind
    out["nutation_period"] = 2.0 * (turns[n] - turns[0]) / n
    # ψ = atan2(R31, −R32): body axis 3 in space is (sθ sψ, −sθ cψ, cθ)
    psi = np.unwrap(np.arctan2(R[:, 2, 0], -R[:, 2, 1]))
    a, b = interpolate(tr.t, psi, turns[0]), interpolate(tr.t, psi, turns[n])
    out["precession_rate"] = (b - a) / (turns[n] - turns[0])
    return out


def _inv_heavy(s: Scenario, tr: Trajectory) -> dict:
    pv = _required(s, "a pivot", s.pivot)
    i = pv.body
    b = s.bodies[i]
    L, scale = _angular_momentum(s, tr, pv.anchor)
    E, Escale = _energy(s, tr)
    L3 = b.inertia[2] * tr.omega[:, i, 2]
    return {
        "E": (E, Escale),
        "L_z": (L[:, 2], scale),
        "L_3": (L3, max(float(np.max(np.abs(L3))), 1e-300)),
    }


# --------------------------------------------------------------------------- parabola


def _ballistic(s: Scenario, t: np.ndarray):
    g = _gravity(s)
    pos, vel, Rs, ws = [], [], [], []
    for b in s.bodies:
        x0, v0 = np.asarray(b.position, dtype=float), np.asarray(b.velocity, dtype=float)
        pos.append(x0 + t[:, None] * v0 + 0.5 * t[:, None] ** 2 * g)
        vel.append(v0 + t[:, None] * g)
        R, w = _free_rotation(b, t)
        Rs.append(R)
        ws.append(w)
    return pos, vel, Rs, ws


def _ref_parabola(s: Scenario) -> Reference:
    t = np.asarray(s.sample_times)
    pos, vel, Rs, ws = _ballistic(s, t)
    b, gz = s.bodies[0], _gravity(s)[2]
    t_apex = -b.velocity[2] / gz
    h = b.position[2] - 0.5 * b.velocity[2] ** 2 / gz
    return Reference(_stack(t, s.bodies, pos, vel, Rs, ws), {"apex_height": h, "apex_time": t_apex})


def _measure_parabola(s: Scenario, tr: Trajectory) -> dict:
    z = crossings(tr.t, tr.velocity[:, 0, 2], deg=3, direction=-1)
    if z.size != 1:
        msg = f"v_z falls through zero {z.size} times in the samples; expected once (the apex)"
        return {"apex_height": msg, "apex_time": msg}
    return {
        "apex_time": float(z[0]),
        "apex_height": interpolate(tr.t, tr.position[:, 0, 2], float(z[0]), deg=3),
    }


def _inv_parabola(s: Scenario, tr: Trajectory) -> dict:
    P, scale = _momentum(s, tr)
    return {"E": _energy(s, tr), "p_horizontal": (P[:, :2], scale)}


# --------------------------------------------------------------------------- impact


def _ref_impact(s: Scenario) -> Reference:
    from ..impact import direct_impact

    t = np.asarray(s.sample_times)
    ((i, j, e),) = s.pair_restitution
    a, b = s.bodies[i], s.bodies[j]
    x1, x2 = np.asarray(a.position), np.asarray(b.position)
    v1, v2 = np.asarray(a.velocity), np.asarray(b.velocity)
    d = x2 - x1
    n = d / np.linalg.norm(d)
    if np.linalg.norm(np.cross(d, v2 - v1)) > 2**6 * EPS * np.linalg.norm(d) * np.linalg.norm(
        v2 - v1
    ):
        raise MechanicsValueError(f"scenario {s.name!r}: the impact must be head-on")
    ra = _required(s, f"a shape for body {a.name!r}", a.shape).dims[0]
    rb = _required(s, f"a shape for body {b.name!r}", b.shape).dims[0]
    gap = float(np.linalg.norm(d)) - ra - rb
    closing = float(np.dot(v1 - v2, n))
    tc = gap / closing
    u1, u2 = (float(np.dot(v, n)) for v in (v1, v2))
    w1, w2 = direct_impact(a.mass, b.mass, u1, u2, e)
    v1f, v2f = v1 + (float(w1) - u1) * n, v2 + (float(w2) - u2) * n
    after = t > tc
    dt = (t - tc)[:, None]
    pos1 = np.where(after[:, None], x1 + tc * v1 + dt * v1f, x1 + t[:, None] * v1)
    pos2 = np.where(after[:, None], x2 + tc * v2 + dt * v2f, x2 + t[:, None] * v2)
    vel1 = np.where(after[:, None], v1f, v1)
    vel2 = np.where(after[:, None], v2f, v2)
    pos, vel = {i: pos1, j: pos2}, {i: vel1, j: vel2}  # by body index
    R, w = zip(*(_free_rotation(bb, t) for bb in s.bodies), strict=True)
    figs = {"v1_after": v1f, "v2_after": v2f, "restitution": e, "impact_time": tc}
    return Reference(
        _stack(t, s.bodies, [pos[0], pos[1]], [vel[0], vel[1]], list(R), list(w)), figs
    )


def _measure_impact(s: Scenario, tr: Trajectory) -> dict:
    ((i, j, _),) = s.pair_restitution
    a, b = s.bodies[i], s.bodies[j]
    n = np.asarray(b.position) - np.asarray(a.position)
    n = n / np.linalg.norm(n)
    v1f, v2f = tr.velocity[-1, i], tr.velocity[-1, j]
    v1, v2 = tr.velocity[0, i], tr.velocity[0, j]
    sep = float(np.dot(v2f - v1f, n))
    out = {"v1_after": v1f, "v2_after": v2f, "restitution": sep / float(np.dot(v1 - v2, n))}
    gap = float(np.linalg.norm(tr.position[-1, j] - tr.position[-1, i])) - (
        _required(s, f"a shape for body {a.name!r}", a.shape).dims[0]
        + _required(s, f"a shape for body {b.name!r}", b.shape).dims[0]
    )
    out["impact_time"] = (
        tr.t[-1] - gap / sep if sep > 0 else "the bodies do not separate at the end"
    )
    return out


def _inv_impact(s: Scenario, tr: Trajectory) -> dict:
    return {"p": _momentum(s, tr), "L": _angular_momentum(s, tr, (0.0, 0.0, 0.0))}


# --------------------------------------------------------------------------- bounce


#: a face lies flat when its normal is the ground's to 2^4 eps (rounding of a few
#: products: the built-in boxes are axis-aligned, exactly flat)
FLAT_RTOL = 2**4 * EPS


def _lowest(s: Scenario, b: Body, nrm: np.ndarray) -> float:
    """How far the body's lowest point lies below G along the ground's normal ``nrm``:
    a sphere's radius; for a box or a cylinder, its extent along the normal when it lies
    flat on a face and does not turn (then all the face's corners strike at once, and
    the landing is a bounce: no torque, the same impulse as a ball's).  Friction needs
    no tangential motion at the contact (a sliding or spinning body is not a bounce)."""
    shape = _required(s, f"a shape for body {b.name!r}", b.shape)
    gr = _required(s, "a ground", s.ground)
    v = np.asarray(b.velocity, dtype=float)
    v_t = v - np.dot(v, nrm) * nrm
    if gr.friction > 0 and (np.any(v_t) or np.any(b.omega)):
        raise MechanicsValueError(
            f"scenario {s.name!r}: on rough ground (friction {gr.friction!r}) a bounce's "
            f"reference needs no sliding and no spin; got velocity {b.velocity}, omega "
            f"{b.omega}"
        )
    if shape.kind == "sphere":
        return float(shape.dims[0])
    n_body = np.array(b.R_A_O, dtype=float) @ nrm
    axis = 2 if shape.kind == "cylinder" else int(np.argmax(np.abs(n_body)))
    flat = abs(abs(n_body[axis]) - 1.0) <= FLAT_RTOL
    if shape.kind not in ("box", "cylinder") or not flat or np.any(b.omega):
        raise MechanicsValueError(
            f"scenario {s.name!r}: a {shape.kind} lands as a bounce only lying flat on a "
            f"face (a box's, a cylinder's end) and not turning; got the ground's normal "
            f"{tuple(float(x) for x in n_body)} in body axes, omega {b.omega}"
        )
    if shape.kind == "cylinder":
        return float(shape.dims[1])
    return float(shape.dims[axis])


def _bounce_numbers(s: Scenario):
    b, gr = s.bodies[0], _required(s, "a ground", s.ground)
    g = -float(np.dot(_gravity(s), gr.normal))
    r = _lowest(s, b, np.asarray(gr.normal, dtype=float))
    h0 = float(np.dot(b.position, gr.normal)) - gr.height - r
    if np.dot(b.velocity, gr.normal) != 0 or h0 <= 0 or g <= 0:
        raise MechanicsValueError(
            f"scenario {s.name!r}: the bouncing ball's reference starts at rest along the "
            f"normal, above the ground, gravity pressing it down; got height {h0}, velocity "
            f"{b.velocity}, gravity {s.gravity}"
        )
    tf = math.sqrt(2.0 * h0 / g)
    return g, r, h0, tf, gr.restitution


def _bounce_impacts(s: Scenario) -> tuple[list[float], float]:
    """The impact times up to the first past the last sample, and the time the ball
    comes to rest (inf for e ≥ 1)."""
    _, _, _, tf, e = _bounce_numbers(s)
    end = s.sample_times[-1]
    # impacts at tf (1 + 2e + … + 2e^{k−1}); between them free flight.  For e < 1 they
    # accumulate at t_rest = tf (1 + e)/(1 − e) (infinitely many; at once for e = 0), after
    # which the ball rests on the ground: the list stops where the next impact no longer
    # moves the time in float64 (issue 16: the loop ran forever past t_rest)
    t_rest = math.inf if e >= 1 else tf * (1.0 + e) / (1.0 - e)
    impacts = [tf]
    while impacts[-1] <= end:
        following = impacts[-1] + 2.0 * tf * e ** len(impacts)
        if following == impacts[-1]:
            break
        impacts.append(following)
    return impacts, t_rest


def _ref_bounce(s: Scenario) -> Reference:
    t = np.asarray(s.sample_times)
    b, gr = s.bodies[0], _required(s, "a ground", s.ground)
    g, r, h0, tf, e = _bounce_numbers(s)
    nrm = np.asarray(gr.normal, dtype=float)
    impacts, t_rest = _bounce_impacts(s)
    n_apex = sum(1 for k in range(1, len(impacts)) if impacts[k - 1] + tf * e**k <= t[-1])
    apex_t = np.array([impacts[k - 1] + tf * e**k for k in range(1, n_apex + 1)])
    apex_h = h0 * e ** (2.0 * np.arange(1, n_apex + 1))
    # the normal coordinate above the lowest point and its rate, per sample
    k = np.searchsorted(np.array(impacts), t, side="left")  # impacts before each sample
    start = np.where(k == 0, 0.0, np.array([0.0, *impacts])[k])
    v_up = np.where(k == 0, 0.0, g * tf * e**k)
    z0 = np.where(k == 0, h0, 0.0)
    tau = t - start
    at_rest = t >= t_rest
    zn = np.where(at_rest, 0.0, z0 + v_up * tau - 0.5 * g * tau**2)
    vn = np.where(at_rest, 0.0, v_up - g * tau)
    v0 = np.asarray(b.velocity, dtype=float)
    v_t = v0 - np.dot(v0, nrm) * nrm  # tangential, kept by the smooth impacts
    base = np.asarray(b.position, dtype=float) - (np.dot(b.position, nrm) - gr.height - r) * nrm
    pos = base + t[:, None] * v_t + (zn + 0.0)[:, None] * nrm
    vel = v_t + vn[:, None] * nrm
    R, w = _free_rotation(b, t)
    figs = {"apex_heights": apex_h, "apex_times": apex_t}
    return Reference(_stack(t, s.bodies, [pos], [vel], [R], [w]), figs)


def bounce_apexes(s: Scenario, tr: Trajectory) -> tuple[np.ndarray, np.ndarray]:
    """The apexes of a bouncing ball's trajectory, every one in the samples.

    Their times are where v·n falls through 0 (:func:`crossings`), their heights those of
    the ball's lowest point above the ground (:func:`interpolate`), both read by
    quadratics through the samples.

    Parameters
    ----------
    s : Scenario
        A scenario with a ground, whose first body bounces on it.
    tr : Trajectory
        A (validated) trajectory of ``s``.

    Returns
    -------
    times : ndarray, shape (k,)
        The apex times, s.
    heights : ndarray, shape (k,)
        The heights of the ball's lowest point above the ground at them, m.

    Raises
    ------
    MechanicsValueError
        Where the scenario has no ground or the ball no shape, or the ball cannot bounce
        (on rough ground a sliding or spinning ball; a box or cylinder not lying flat).

    Examples
    --------
    Read off the exact samples, the heights are the reference's, falling by e² = 0.64:

    >>> s = get_scenario("bouncing_ball")
    >>> ref = reference(s)
    >>> times, heights = bounce_apexes(s, ref.trajectory)
    >>> bool(np.allclose(heights, ref.figures["apex_heights"], rtol=2**-40, atol=0))
    True
    >>> round(float(heights[1] / heights[0]), 12), s.ground.restitution**2
    (0.64, 0.6400000000000001)
    """
    gr = _required(s, "a ground", s.ground)
    nrm = np.asarray(gr.normal, dtype=float)
    r = _lowest(s, s.bodies[0], nrm)
    vn = tr.velocity[:, 0] @ nrm
    zn = tr.position[:, 0] @ nrm - gr.height - r
    apex = crossings(tr.t, vn, deg=2, direction=-1)
    return apex, np.array([interpolate(tr.t, zn, a, deg=2) for a in apex])


def _first(values, unit: str, n: int = 3) -> str:
    shown = ", ".join(f"{v:.3g}" for v in values[:n])
    return f"{shown}{', ...' if len(values) > n else ''} {unit}"


def _measure_bounce(s: Scenario, tr: Trajectory) -> dict:
    apex, h = bounce_apexes(s, tr)
    ref = _ref_bounce(s).figures
    expected = ref["apex_times"].size
    if apex.size != expected:
        msg = (
            f"found {apex.size} apexes (v·n falling through 0) in the samples; expected "
            f"{expected}: heights {_first(h, 'm')} at {_first(apex, 's')}, exact "
            f"{_first(ref['apex_heights'], 'm')} at {_first(ref['apex_times'], 's')}"
        )
        return {"apex_heights": msg, "apex_times": msg}
    return {"apex_heights": h, "apex_times": apex}


def _inv_bounce(s: Scenario, tr: Trajectory) -> dict:
    nrm = np.asarray(_required(s, "a ground", s.ground).normal, dtype=float)
    P, scale = _momentum(s, tr)
    return {"p_tangential": (P - np.outer(P @ nrm, nrm), scale)}


# --------------------------------------------------------------------------- rocket


def _rocket_numbers(s: Scenario):
    th = _required(s, "a thrust", s.thrust)
    b = s.bodies[th.body]
    m0, q, u, T = b.mass, th.mass_rate, th.exhaust_speed, th.burn_time
    d = np.array(b.R_A_O).T @ np.asarray(th.axis, dtype=float)  # the axis in space
    if np.any(b.omega) or np.any(_gravity(s)) or len(s.bodies) != 1:
        raise MechanicsValueError(
            f"scenario {s.name!r}: the rocket's reference is for one non-spinning body in "
            "free space"
        )
    return b, m0, q, u, T, d


def _ref_rocket(s: Scenario) -> Reference:
    from ..open_systems import rocket_height, rocket_velocity

    t = np.asarray(s.sample_times)
    b, m0, q, u, T, d = _rocket_numbers(s)
    kw = dict(m_0=m0, q=q, u=u, m_f=q * T, g=0.0, after_burn_out="coast")
    v0 = np.asarray(b.velocity, dtype=float)
    pos = np.asarray(b.position) + t[:, None] * v0 + rocket_height(t, **kw)[:, None] * d
    vel = v0 + rocket_velocity(t, **kw)[:, None] * d
    m = m0 - q * np.minimum(t, T)
    R, w = _free_rotation(b, t)
    figs = {"delta_v": u * math.log(m0 / (m0 - q * T)), "burnout_mass": m0 - q * T}
    return Reference(_stack(t, s.bodies, [pos], [vel], [R], [w], [m]), figs)


def _measure_rocket(s: Scenario, tr: Trajectory) -> dict:
    d = _rocket_numbers(s)[-1]
    i = _required(s, "a thrust", s.thrust).body
    out: dict[str, float | str] = {
        "delta_v": float(np.dot(tr.velocity[-1, i] - tr.velocity[0, i], d))
    }
    out["burnout_mass"] = (
        float(tr.masses[-1, i])
        if tr.masses is not None
        else "the trajectory has no masses (field 'masses' is required with thrust)"
    )
    return out


# --------------------------------------------------------------------------- contacts


def _isotropic(s: Scenario, b: Body) -> float:
    """The ball's one moment J (its three equal to 2^4 eps): a sphere whose ω after a
    contact stays constant in flight, as the references below assume."""
    J = np.asarray(b.inertia, dtype=float)
    if float(J.max() - J.min()) > FLAT_RTOL * float(J.max()):
        raise MechanicsValueError(
            f"scenario {s.name!r}: the ball's principal moments must be equal (a uniform "
            f"ball or a shell), so that its spin stays constant in flight; got {b.inertia}"
        )
    return float(J.max())


def _unit(v) -> np.ndarray:
    v = np.asarray(v, dtype=float)
    return v / float(np.linalg.norm(v))


def _on_ground(s: Scenario, b: Body, nrm: np.ndarray, what: str) -> None:
    """Refuse a body that does not rest on the ground (its lowest point at the ground's
    height, no velocity along the normal): ``what`` names the reference."""
    gr = _required(s, "a ground", s.ground)
    gap = float(np.dot(b.position, nrm)) - gr.height - _lowest_resting(s, b, nrm)
    size = float(body_sizes(s).max())
    if abs(gap) > FLAT_RTOL * max(size, abs(gr.height), float(np.linalg.norm(b.position))) or (
        float(np.dot(b.velocity, nrm)) != 0
    ):
        raise MechanicsValueError(
            f"scenario {s.name!r}: {what} starts with the body resting on the ground; its "
            f"lowest point is {gap!r} m above it, its normal velocity "
            f"{float(np.dot(b.velocity, nrm))!r} m/s"
        )


def _lowest_resting(s: Scenario, b: Body, nrm: np.ndarray) -> float:
    """The lowest point's depth below G of a sphere or a box lying flat (any motion)."""
    shape = _required(s, f"a shape for body {b.name!r}", b.shape)
    if shape.kind == "sphere":
        return float(shape.dims[0])
    n_body = np.array(b.R_A_O, dtype=float) @ nrm
    axis = int(np.argmax(np.abs(n_body)))
    if shape.kind != "box" or abs(abs(n_body[axis]) - 1.0) > FLAT_RTOL:
        raise MechanicsValueError(
            f"scenario {s.name!r}: the body must be a sphere or a box lying flat on a face; "
            f"got a {shape.kind} with the ground's normal {tuple(map(float, n_body))} in "
            "body axes"
        )
    return float(shape.dims[axis])


def _slide_numbers(s: Scenario):
    """(body, unit direction d, initial speed v0, deceleration μ g_n, stop time, stop
    distance) of a box sliding on its face over rough flat ground."""
    b, gr = s.bodies[0], _required(s, "a ground", s.ground)
    nrm = np.asarray(gr.normal, dtype=float)
    g = _gravity(s)
    g_n = -float(np.dot(g, nrm))
    v = np.asarray(b.velocity, dtype=float)
    shape = _required(s, f"a shape for body {b.name!r}", b.shape)
    if (
        len(s.bodies) != 1
        or shape.kind != "box"
        or np.any(b.omega)
        or g_n <= 0
        or np.linalg.norm(g + g_n * nrm) > FLAT_RTOL * g_n
        or not gr.friction > 0
        or not np.any(v)
    ):
        raise MechanicsValueError(
            f"scenario {s.name!r}: the sliding box's reference is one box, not turning, "
            "sliding over rough ground (friction > 0) with gravity along the normal; got "
            f"{len(s.bodies)} bodies, shape {shape.kind!r}, omega {b.omega}, gravity "
            f"{s.gravity}, friction {gr.friction!r}, velocity {b.velocity}"
        )
    _on_ground(s, b, nrm, "the sliding box's reference")
    d = _unit(v)
    # the normal forces' resultant stays inside the face (the box does not tip): friction
    # at the face, μ m g_n, turns it about G with arm h (the half height), balanced by
    # shifting the normal resultant μ h along d, at most the half length along d
    n_body, d_body = np.array(b.R_A_O) @ nrm, np.array(b.R_A_O) @ d
    h = float(np.abs(n_body) @ np.asarray(shape.dims))
    half = float(np.abs(d_body) @ np.asarray(shape.dims))
    if gr.friction * h >= half:
        raise MechanicsValueError(
            f"scenario {s.name!r}: the box tips over (μ h = {gr.friction * h:.4g} m is not "
            f"under its half length {half:.4g} m along the motion): the sliding box's "
            "reference holds only while it slides flat"
        )
    v0 = float(np.linalg.norm(v))
    a = gr.friction * g_n
    return b, d, v0, a, v0 / a, v0 * v0 / (2.0 * a)


def _ref_slide(s: Scenario) -> Reference:
    t = np.asarray(s.sample_times)
    b, d, v0, a, t_s, dist = _slide_numbers(s)
    tau = np.minimum(t, t_s)
    along = v0 * tau - 0.5 * a * tau**2
    speed = np.maximum(v0 - a * t, 0.0)
    pos = np.asarray(b.position, dtype=float) + along[:, None] * d
    vel = speed[:, None] * d
    R, w = _free_rotation(b, t)
    return Reference(
        _stack(t, s.bodies, [pos], [vel], [R], [w]), {"stop_distance": dist, "stop_time": t_s}
    )


#: a body whose speed falls below this fraction of its initial speed has stopped (2^-10:
#: far above an integrated engine's resting jitter, far below any speed on the way)
STOP_FRACTION = 2.0**-10


def _measure_slide(s: Scenario, tr: Trajectory) -> dict:
    _, d, v0, _, _, _ = _slide_numbers(s)
    speed = tr.velocity[:, 0] @ d
    stopped = np.nonzero(speed <= STOP_FRACTION * v0)[0]
    out: dict[str, float | str] = {
        "stop_distance": float((tr.position[-1, 0] - tr.position[0, 0]) @ d)
    }
    k = int(stopped[0]) - 1 if stopped.size else speed.size  # the last sample still moving
    if not 1 <= k < speed.size:
        out["stop_time"] = (
            "the box does not stop within the samples"
            if k == speed.size
            else "the box stops before the second sample: no deceleration to read"
        )
        return out
    # v falls linearly while sliding: extend the last two moving samples' line to v = 0
    decel = (speed[k - 1] - speed[k]) / (tr.t[k] - tr.t[k - 1])
    out["stop_time"] = float(tr.t[k] + speed[k] / decel) if decel > 0 else "the speed does not fall"
    return out


def _roll_numbers(s: Scenario):
    """(body, radius, unit normal, unit downhill d, acceleration a, v0 along d) of a
    solid ball rolling without slipping on rough ground, gravity having a component
    g_t along the ground (an incline: the ground flat, gravity tilted)."""
    b, gr = s.bodies[0], _required(s, "a ground", s.ground)
    nrm = np.asarray(gr.normal, dtype=float)
    g = _gravity(s)
    g_n = -float(np.dot(g, nrm))
    g_t = g + g_n * nrm
    r = _lowest_resting(s, b, nrm)
    sphere = b.shape is not None and b.shape.kind == "sphere"
    v = np.asarray(b.velocity, dtype=float)
    if len(s.bodies) != 1 or not sphere or g_n <= 0 or not np.any(g_t):
        raise MechanicsValueError(
            f"scenario {s.name!r}: the rolling ball's reference is one ball on the ground, "
            f"gravity pressing it down and along the ground; got {len(s.bodies)} bodies, "
            f"gravity {s.gravity}"
        )
    _on_ground(s, b, nrm, "the rolling ball's reference")
    d = _unit(g_t)
    v0 = float(v @ d)
    w_space = np.array(b.R_A_O).T @ np.asarray(b.omega, dtype=float)
    rolling = np.cross(nrm, v) / r
    scale = max(float(np.linalg.norm(v)), r * float(np.linalg.norm(w_space)), 1e-300)
    if (
        np.linalg.norm(v - v0 * d) > FLAT_RTOL * scale
        or np.linalg.norm(w_space - rolling) * r > FLAT_RTOL * scale
    ):
        raise MechanicsValueError(
            f"scenario {s.name!r}: the rolling ball starts rolling downhill, ω = n × v / r "
            f"= {tuple(map(float, rolling))} rad/s with v along the slope "
            f"{tuple(map(float, d))}; got v {b.velocity}, ω in space "
            f"{tuple(map(float, w_space))}"
        )
    # J a / r² + m a = m g_t with the friction f = J a / r²; f ≤ μ m g_n keeps it rolling
    k = _isotropic(s, b) / (b.mass * r * r)  # 2/5 for a solid ball
    a = float(np.linalg.norm(g_t)) / (1.0 + k)
    if k * a > gr.friction * g_n:
        raise MechanicsValueError(
            f"scenario {s.name!r}: the ball slips: rolling needs friction "
            f"{k * a / g_n:.4g} ≥ J/(m r²) a/g_n, the ground has {gr.friction!r}"
        )
    return b, r, nrm, d, a, v0


def _rodrigues(axis: np.ndarray, angle: np.ndarray) -> np.ndarray:
    """Active rotations by ``angle`` (m,) about the unit ``axis``: (m, 3, 3)."""
    K = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]])
    c, s_ = np.cos(angle)[:, None, None], np.sin(angle)[:, None, None]
    return np.eye(3) + s_ * K + (1.0 - c) * (K @ K)


def _ref_roll(s: Scenario) -> Reference:
    t = np.asarray(s.sample_times)
    b, r, nrm, d, a, v0 = _roll_numbers(s)
    along = v0 * t + 0.5 * a * t**2
    speed = v0 + a * t
    pos = np.asarray(b.position, dtype=float) + along[:, None] * d
    vel = speed[:, None] * d
    axis = np.cross(nrm, d)  # ω = n × v / r
    # passive R(t) = R(0) Q(t)ᵀ, Q the active turn by along / r about the axis
    R = np.asarray(b.R_A_O, dtype=float) @ np.swapaxes(_rodrigues(axis, along / r), -1, -2)
    w = np.einsum("tij,j->ti", R, axis) * (speed / r)[:, None]
    figs = {"acceleration": a, "roll_speed": float(speed[-1])}
    return Reference(_stack(t, s.bodies, [pos], [vel], [R], [w]), figs)


def _measure_roll(s: Scenario, tr: Trajectory) -> dict:
    _, r, nrm, d, _, _ = _roll_numbers(s)
    along = (tr.position[:, 0] - tr.position[0, 0]) @ d
    # s(t) is a parabola: its least-squares quadratic's second derivative
    acc = 2.0 * float(np.polyfit(tr.t, along, 2)[0])
    w_space = tr.R_A_O[-1, 0].T @ tr.omega[-1, 0]
    return {"acceleration": acc, "roll_speed": float(np.cross(w_space, nrm) @ d) * r}


def _cradle_numbers(s: Scenario):
    """(direction d, speed v, time of the first contact) of Newton's cradle: equal
    balls in a row along d, touching but for the first, which approaches the row at v;
    every neighbouring pair elastic (e = 1), no gravity, no ground."""
    bodies = s.bodies
    n = len(bodies)
    pairs = {(i, j): e for i, j, e in s.pair_restitution}
    ok = (
        n >= 3
        and s.ground is None
        and not np.any(_gravity(s))
        and pairs == {(i, i + 1): 1.0 for i in range(n - 1)}
        and all(b.shape is not None and b.shape.kind == "sphere" for b in bodies)
        and len({(b.mass, b.shape.dims) for b in bodies if b.shape is not None}) == 1
        and not any(np.any(b.omega) for b in bodies)
        and not any(np.any(b.velocity) for b in bodies[1:])
        and np.any(bodies[0].velocity)
    )
    if not ok:
        raise MechanicsValueError(
            f"scenario {s.name!r}: Newton's cradle's reference is 3 or more equal balls, "
            "not spinning, each pair of neighbours elastic (i, i+1, 1.0), the first moving "
            "and the others at rest, no gravity, no ground"
        )
    r = float(bodies[0].shape.dims[0])  # type: ignore[union-attr]
    v = np.asarray(bodies[0].velocity, dtype=float)
    d = _unit(v)
    x = np.array([b.position for b in bodies], dtype=float)
    rel = x - x[0]
    off_line = np.linalg.norm(rel - np.outer(rel @ d, d), axis=-1)
    gaps = np.diff(x @ d) - 2.0 * r
    size = max(float(np.abs(x).max()), r)
    if np.any(off_line > FLAT_RTOL * size) or np.any(np.abs(gaps[1:]) > FLAT_RTOL * size):
        raise MechanicsValueError(
            f"scenario {s.name!r}: the cradle's balls lie on the line of the first's motion "
            f"and the others touch; got offsets {off_line.tolist()} m from the line, gaps "
            f"{gaps.tolist()} m"
        )
    if not gaps[0] > 0:
        raise MechanicsValueError(
            f"scenario {s.name!r}: the first ball starts apart from the row; gap {gaps[0]!r} m"
        )
    speed = float(np.linalg.norm(v))
    return d, speed, float(gaps[0]) / speed


def _ref_cradle(s: Scenario) -> Reference:
    t = np.asarray(s.sample_times)
    d, v, tc = _cradle_numbers(s)
    n = len(s.bodies)
    pos, vel, Rs, ws = [], [], [], []
    for i, b in enumerate(s.bodies):
        x0 = np.asarray(b.position, dtype=float)
        if i == 0:  # moves until the contact, then rests
            travel = v * np.minimum(t, tc)
            speed = np.where(t < tc, v, 0.0)
        elif i == n - 1:  # the momentum passes down the row: the last leaves at v
            travel = v * np.maximum(t - tc, 0.0)
            speed = np.where(t > tc, v, 0.0)
        else:
            travel = speed = np.zeros_like(t)
        pos.append(x0 + travel[:, None] * d)
        vel.append(speed[:, None] * d)
        R, w = _free_rotation(b, t)
        Rs.append(R)
        ws.append(w)
    after = np.zeros(n)
    after[-1] = v
    figs = {"velocities_after": after, "impact_time": tc}
    return Reference(_stack(t, s.bodies, pos, vel, Rs, ws), figs)


def _measure_cradle(s: Scenario, tr: Trajectory) -> dict:
    d, _, _ = _cradle_numbers(s)
    after = tr.velocity[-1] @ d
    out: dict[str, object] = {"velocities_after": after}
    # the last ball's departure, read back from its final displacement and speed
    moved = float((tr.position[-1, -1] - tr.position[0, -1]) @ d)
    out["impact_time"] = (
        float(tr.t[-1] - moved / after[-1])
        if after[-1] > 0
        else "the last ball does not leave the row"
    )
    return out


def _inv_cradle(s: Scenario, tr: Trajectory) -> dict:
    return {
        "E": _energy(s, tr),
        "p": _momentum(s, tr),
        "L": _angular_momentum(s, tr, (0.0, 0.0, 0.0)),
    }


def _inv_roll(s: Scenario, tr: Trajectory) -> dict:
    return {"E": _energy(s, tr)}


#: a bouncing ball is at rest once its speed stays at or below this fraction of its
#: first impact speed (2^-10: far below a bounce the samples resolve, far above an
#: integrated engine's resting jitter)
REST_FRACTION = 2.0**-10
#: the apexes a ball bouncing to rest is judged on: the first two (the later flights
#: shrink below any sample spacing as the impacts accumulate: the built-in ball's third
#: lasts 0.072 s, two samples of 2^-5 s, and reads 11 % off its exact height)
REST_APEXES = 2


def _rest_numbers(s: Scenario):
    """(first impact speed v1, index k of the first impact whose rebound is at or below
    REST_FRACTION v1, its time t_k, the accumulation time t_rest) of a ball bouncing to
    rest: impacts at t_f (1 + 2e + … + 2e^{k−1}), rebounds e^k v1, accumulating at
    t_rest = t_f (1 + e)/(1 − e) (Example 6.1's law (6.6) applied at every impact).  A
    ball with e ≥ 1 never rests: k, t_k and t_rest are infinite."""
    g, _, _, tf, e = _bounce_numbers(s)
    if e >= 1:
        return g * tf, math.inf, math.inf, math.inf
    k = 1 if e == 0 else math.ceil(math.log(REST_FRACTION) / math.log(e))
    t_k = tf * (1.0 + 2.0 * e * (1.0 - e ** (k - 1)) / (1.0 - e))
    return g * tf, k, t_k, tf * (1.0 + e) / (1.0 - e)


def _rest_time(t: np.ndarray, speed: np.ndarray, v1: float) -> float | str:
    """The first sample from which the speed stays at or below REST_FRACTION v1."""
    moving = np.nonzero(speed > REST_FRACTION * v1)[0]
    k = int(moving[-1]) + 1 if moving.size else 0
    if k >= t.size:
        return (
            "the ball does not come to rest within the samples (its speed is above "
            f"{REST_FRACTION * v1:.3g} m/s at the end)"
        )
    return float(t[k])


def _ref_rest(s: Scenario) -> Reference:
    ref = _ref_bounce(s)
    _, _, t_k, _ = _rest_numbers(s)
    t = np.asarray(s.sample_times)
    after = t[t >= t_k]
    figs = {
        "apex_heights": ref.figures["apex_heights"][:REST_APEXES],
        "apex_times": ref.figures["apex_times"][:REST_APEXES],
        "rest_time": float(after[0]) if after.size else math.inf,
    }
    return Reference(ref.trajectory, figs)


def _measure_rest(s: Scenario, tr: Trajectory) -> dict:
    v1 = _rest_numbers(s)[0]
    apex, h = bounce_apexes(s, tr)
    out: dict[str, object] = {}
    if apex.size < REST_APEXES:
        msg = (
            f"found {apex.size} apexes (v·n falling through 0) in the samples; the first "
            f"{REST_APEXES} are judged: heights {_first(h, 'm')} at {_first(apex, 's')}"
        )
        out["apex_heights"] = out["apex_times"] = msg
    else:
        out["apex_heights"], out["apex_times"] = h[:REST_APEXES], apex[:REST_APEXES]
    out["rest_time"] = _rest_time(tr.t, np.linalg.norm(tr.velocity[:, 0], axis=-1), v1)
    return out


def _oblique_numbers(s: Scenario):
    """The oblique impact of a solid ball on rough ground (Coulomb friction μ, Newton's
    e), gravity along the normal: (body, r, n, t1 the impact time, v and ω (space) just
    before, v' and ω' just after, whether the contact sticks).

    At the impact (Section 6.2's momentum principles for an impulse P at the contact
    point −r n): m Δv = P, J Δω = (−r n) × P.  Newton's law (6.6) on the normal part gives
    P_n = m (1 + e)|v_n| (the contact normal passes through G: friction does not change
    it).  The slip u = v_t + ω × (−r n) is stopped by the tangential impulse
    −m u k/(1 + k), k = J/(m r²) (2/5 for a solid ball); where that exceeds μ P_n the
    contact slips throughout and the impulse is −μ P_n û (Coulomb's bound)."""
    b, gr = s.bodies[0], _required(s, "a ground", s.ground)
    nrm = np.asarray(gr.normal, dtype=float)
    g = _gravity(s)
    g_n = -float(np.dot(g, nrm))
    shape = _required(s, f"a shape for body {b.name!r}", b.shape)
    if (
        len(s.bodies) != 1
        or shape.kind != "sphere"
        or g_n <= 0
        or np.linalg.norm(g + g_n * nrm) > FLAT_RTOL * g_n
        or not gr.friction > 0
    ):
        raise MechanicsValueError(
            f"scenario {s.name!r}: the oblique impact's reference is one ball dropped on "
            "rough ground (friction > 0), gravity along the normal; got "
            f"{len(s.bodies)} bodies, shape {shape.kind!r}, gravity {s.gravity}, friction "
            f"{gr.friction!r}"
        )
    r = float(shape.dims[0])
    x0, v0 = np.asarray(b.position, dtype=float), np.asarray(b.velocity, dtype=float)
    h = float(x0 @ nrm) - gr.height - r
    vn0 = float(v0 @ nrm)
    if h <= 0:
        raise MechanicsValueError(
            f"scenario {s.name!r}: the ball starts above the ground; its lowest point is "
            f"{h!r} m above it"
        )
    if vn0 > 0:
        raise MechanicsValueError(
            f"scenario {s.name!r}: the ball starts falling or at rest along the normal (its "
            f"one apex is the rebound's); got normal velocity {vn0!r} m/s"
        )
    t1 = (vn0 + math.sqrt(vn0 * vn0 + 2.0 * g_n * h)) / g_n  # h + vn0 t − ½ g_n t² = 0
    v1 = v0 + t1 * g
    w = np.array(b.R_A_O, dtype=float).T @ np.asarray(b.omega, dtype=float)  # space
    m = b.mass
    k = _isotropic(s, b) / (m * r * r)
    v_n = float(v1 @ nrm)
    u = v1 - v_n * nrm + np.cross(w, -r * nrm)
    P_n = m * (1.0 + gr.restitution) * -v_n
    stick_impulse = m * k / (1.0 + k) * float(np.linalg.norm(u))
    sticks = stick_impulse <= gr.friction * P_n
    # sticking: the impulse that stops the slip; slipping: Coulomb's μ P_n against it
    P_t = -m * k / (1.0 + k) * u if sticks else -gr.friction * P_n * u / float(np.linalg.norm(u))
    v_after = v1 + (P_n * nrm + P_t) / m
    w_after = w + np.cross(-r * nrm, P_t) / _isotropic(s, b)
    return b, r, nrm, t1, v1, w, v_after, w_after, sticks


def _rot_space(R0: np.ndarray, w_space: np.ndarray, tau: np.ndarray) -> np.ndarray:
    """Passive attitudes of a body turning at the constant space ω from R0, after tau."""
    speed = float(np.linalg.norm(w_space))
    if speed == 0:
        return np.broadcast_to(R0, (tau.size, 3, 3)).copy()
    return R0 @ np.swapaxes(_rodrigues(w_space / speed, speed * tau), -1, -2)


def _ref_oblique(s: Scenario) -> Reference:
    t = np.asarray(s.sample_times)
    b, _, nrm, t1, _, w, v_after, w_after, _ = _oblique_numbers(s)
    g = _gravity(s)
    x0, v0 = np.asarray(b.position, dtype=float), np.asarray(b.velocity, dtype=float)
    x1 = x0 + t1 * v0 + 0.5 * t1 * t1 * g
    before = t <= t1
    tau = np.where(before, t, t - t1)[:, None]
    pos = np.where(
        before[:, None], x0 + tau * v0 + 0.5 * tau**2 * g, x1 + tau * v_after + 0.5 * tau**2 * g
    )
    vel = np.where(before[:, None], v0 + tau * g, v_after + tau * g)
    R0 = np.array(b.R_A_O, dtype=float)
    R1 = _rot_space(R0, w, np.array([t1]))[0]
    R = np.where(
        before[:, None, None],
        _rot_space(R0, w, np.where(before, t, 0.0)),
        _rot_space(R1, w_after, np.where(before, 0.0, t - t1)),
    )
    w_t = np.where(before[:, None], w, w_after)
    omega = np.einsum("tij,tj->ti", R, w_t)
    g_n = -float(g @ nrm)
    v_n = float(v_after @ nrm)
    figs = {
        "v_tangential_after": v_after - v_n * nrm,
        "omega_after": w_after,
        "apex_height_after": v_n * v_n / (2.0 * g_n),
    }
    return Reference(_stack(t, s.bodies, [pos], [vel], [R], [omega]), figs)


def _measure_oblique(s: Scenario, tr: Trajectory) -> dict:
    _, r, nrm, _, _, _, _, _, _ = _oblique_numbers(s)
    gr = _required(s, "a ground", s.ground)
    # after the impact the ball flies: its tangential velocity and its ω are constant,
    # its normal velocity falls through zero once, at the rebound's apex
    v_end = tr.velocity[-1, 0]
    out: dict[str, object] = {
        "v_tangential_after": v_end - float(v_end @ nrm) * nrm,
        "omega_after": tr.R_A_O[-1, 0].T @ tr.omega[-1, 0],
    }
    apex = crossings(tr.t, tr.velocity[:, 0] @ nrm, deg=2, direction=-1)
    if apex.size != 1:
        out["apex_height_after"] = (
            f"v·n falls through zero {apex.size} times in the samples; expected once (the "
            "rebound's apex)"
        )
    else:
        zn = tr.position[:, 0] @ nrm - gr.height - r
        out["apex_height_after"] = interpolate(tr.t, zn, float(apex[0]), deg=2)
    return out


# --------------------------------------------------------------------------- registry

#: per kind: the derived figures and the conserved quantities (names of the report)
FIGURES = {
    "free_top": ("omega_period",),
    "heavy_top": ("theta", "nutation_period", "precession_rate"),
    "parabola": ("apex_height", "apex_time"),
    "impact": ("v1_after", "v2_after", "restitution", "impact_time"),
    "bounce": ("apex_heights", "apex_times"),
    "rocket": ("delta_v", "burnout_mass"),
    "slide": ("stop_distance", "stop_time"),
    "roll": ("acceleration", "roll_speed"),
    "cradle": ("velocities_after", "impact_time"),
    "rest": ("apex_heights", "apex_times", "rest_time"),
    "oblique": ("v_tangential_after", "omega_after", "apex_height_after"),
}
INVARIANTS = {
    "free_top": ("E", "p", "L"),
    "heavy_top": ("E", "L_z", "L_3"),
    "parabola": ("E", "p_horizontal"),
    "impact": ("p", "L"),
    "bounce": ("p_tangential",),
    "rocket": (),
    "slide": (),
    "roll": ("E",),
    "cradle": ("E", "p", "L"),
    "rest": ("p_tangential",),
    "oblique": (),
}

_KINDS = {
    "free_top": (_ref_free, _measure_free, _inv_free),
    "heavy_top": (_ref_heavy, _measure_heavy, _inv_heavy),
    "parabola": (_ref_parabola, _measure_parabola, _inv_parabola),
    "impact": (_ref_impact, _measure_impact, _inv_impact),
    "bounce": (_ref_bounce, _measure_bounce, _inv_bounce),
    "rocket": (_ref_rocket, _measure_rocket, lambda s, tr: {}),
    "slide": (_ref_slide, _measure_slide, lambda s, tr: {}),
    "roll": (_ref_roll, _measure_roll, _inv_roll),
    "cradle": (_ref_cradle, _measure_cradle, _inv_cradle),
    "rest": (_ref_rest, _measure_rest, _inv_bounce),
    "oblique": (_ref_oblique, _measure_oblique, lambda s, tr: {}),
}


def _kind(scenario: Scenario):
    kind = scenario.extra.get("kind")
    if kind not in _KINDS:
        raise UnknownScenarioError(
            f"scenario {scenario.name!r}: extra['kind'] must be one of {sorted(_KINDS)}; "
            f"got {kind!r}"
        )
    return _KINDS[kind]


def figure_names(scenario: Scenario) -> tuple[str, ...]:
    """The derived figures of the scenario's kind.

    Parameters
    ----------
    scenario : Scenario
        A scenario of a known kind (``extra["kind"]``).

    Returns
    -------
    tuple of str
        The figures' names, the keys of :func:`reference`'s ``figures``.

    Raises
    ------
    UnknownScenarioError
        Where the scenario's kind is unknown.

    Examples
    --------
    >>> s = get_scenario("parabola")
    >>> figure_names(s), tuple(sorted(reference(s).figures)) == figure_names(s)
    (('apex_height', 'apex_time'), True)
    """
    _kind(scenario)
    return FIGURES[scenario.extra["kind"]]


def invariant_names(scenario: Scenario) -> tuple[str, ...]:
    """The quantities conserved in the scenario (the keys of :func:`invariants`).

    Parameters
    ----------
    scenario : Scenario
        A scenario of a known kind (``extra["kind"]``).

    Returns
    -------
    tuple of str
        The names, e.g. ``"E"``, ``"p"``, ``"L"``, ``"p_horizontal"``.

    Raises
    ------
    UnknownScenarioError
        Where the scenario's kind is unknown.

    Examples
    --------
    >>> s = get_scenario("parabola")
    >>> invariant_names(s), tuple(invariants(s, reference(s).trajectory)) == invariant_names(s)
    (('E', 'p_horizontal'), True)
    """
    _kind(scenario)
    return INVARIANTS[scenario.extra["kind"]]


def reference(scenario: Scenario) -> Reference:
    """The exact states at the scenario's sample times and its derived figures.

    Parameters
    ----------
    scenario : Scenario
        A scenario of a known kind (``extra["kind"]``), built in or a variant.

    Returns
    -------
    Reference
        The exact trajectory and the figures of :func:`figure_names`.

    Raises
    ------
    UnknownScenarioError
        Where the scenario's kind is unknown.
    MechanicsValueError
        Where the scenario lacks what its kind needs (a ground, a pivot, a thrust, a
        body's shape), or its bodies cannot do what the kind's closed form assumes.

    Examples
    --------
    The parabola at its last sample: x = x₀ + v_x t (no horizontal force):

    >>> s = get_scenario("parabola")
    >>> tr = reference(s).trajectory
    >>> float(tr.position[-1, 0, 0]) == s.bodies[0].position[0] + 3.0 * s.duration
    True
    """
    return _kind(scenario)[0](scenario)


def measure(scenario: Scenario, trajectory: Trajectory) -> dict:
    """The derived figures read off a (validated) trajectory's samples.

    They are keyed as in :func:`reference`; a figure that cannot be read (too few
    crossings, no masses) is a string saying why.

    Parameters
    ----------
    scenario : Scenario
        A scenario of a known kind.
    trajectory : Trajectory
        A trajectory of it, validated (:func:`~.protocol.check_trajectory`).

    Returns
    -------
    dict
        Figure name → its value (a float or an array), or a string saying why it cannot
        be read.

    Raises
    ------
    UnknownScenarioError
        Where the scenario's kind is unknown.
    MechanicsValueError
        Where the scenario lacks what its kind needs (a ground, a body's shape).

    Examples
    --------
    Read off the exact samples, the apex time is the exact one to within 2⁻²⁸:

    >>> s = get_scenario("parabola")
    >>> ref = reference(s)
    >>> bool(abs(measure(s, ref.trajectory)["apex_time"] / ref.figures["apex_time"] - 1) < 2**-28)
    True
    """
    return _kind(scenario)[1](scenario, trajectory)


def invariants(scenario: Scenario, trajectory: Trajectory) -> dict:
    """The quantities conserved in the scenario, sampled along a trajectory.

    The battery takes the scales from the exact trajectory, so that a run-away engine
    cannot inflate them.

    Parameters
    ----------
    scenario : Scenario
        A scenario of a known kind.
    trajectory : Trajectory
        A trajectory of it, validated (:func:`~.protocol.check_trajectory`).

    Returns
    -------
    dict
        Name (:func:`invariant_names`) → (samples, an ndarray of shape (m,) or (m, k);
        the scale of its relative drift, a float).

    Raises
    ------
    UnknownScenarioError
        Where the scenario's kind is unknown.
    MechanicsValueError
        Where the scenario lacks what its kind needs (a pivot, a ground).

    Examples
    --------
    The parabola's energy (5.85 with no rotation) along the exact motion keeps to rounding:

    >>> s = get_scenario("parabola")
    >>> E, scale = invariants(s, reference(s).trajectory)["E"]
    >>> E.shape, float(np.max(np.abs(E - E[0]))) / scale < 2**-40
    ((49,), True)
    """
    return _kind(scenario)[2](scenario, trajectory)


# --------------------------------------------------------------------------- valid range

#: a step divides a sample time when their ratio is a whole number within 2⁴ eps of it
#: (rounding in the division; the built-in grids are binary fractions, exact)
GRID_RTOL = 2**4 * EPS
#: an impact stays this many of the scenario's finest steps from every sample, so that no
#: sample falls between an impact and an engine's one step late (the built-in scenarios
#: keep 9 ms at 2⁻⁸ s: 2.3 steps)
IMPACT_MARGIN_STEPS = 2.0
#: a figure read off a scenario's exact samples is within this of the exact figure
#: (relative), or the samples are too sparse to judge an engine on it: the exact profile's
#: bound, 2^-28 (thresholds.PROFILES["exact"].rtol, which imports this module; a test
#: holds the two equal)
READ_RTOL = 2.0**-28
#: a bounce's flight lasts at least this many of the coarsest steps, so that an engine
#: sees its apex (the built-in ball's shortest flight holds 33 steps of 2⁻⁶ s)
FLIGHT_STEPS = 8.0


class ScenarioRangeError(MechanicsValueError):
    """A scenario (a variant of a known kind) outside the range its reference and the
    battery's figures hold for."""


def _impact_times(s: Scenario) -> list[float]:
    kind = s.extra.get("kind")
    if kind == "bounce":
        impacts, _ = _bounce_impacts(s)
        return [t for t in impacts if t <= s.sample_times[-1]]
    if kind in ("impact", "cradle"):
        t = reference(s).figures["impact_time"]
        return [t] if t <= s.sample_times[-1] else []
    if kind == "oblique":
        t = _oblique_numbers(s)[3]
        return [t] if t <= s.sample_times[-1] else []
    if kind == "rest":  # those a step resolves, and the one from which the ball rests
        impacts, _ = _bounce_impacts(s)
        coarse = max(s.steps, default=0.0)
        flights = np.diff(impacts)
        resolved = [t for t, f in zip(impacts, flights, strict=False) if f >= FLIGHT_STEPS * coarse]
        return [*resolved, _rest_numbers(s)[2]]
    return []


def check_scenario(s: Scenario) -> None:
    """Refuse a scenario outside its valid range, naming it and the reason.

    - its kind is known, its samples start at 0, increase and end at the duration, and
      each step divides every sample time;
    - a bouncing ball does not come to rest within the duration (its last bounces would
      be shorter than any step), each flight lasts :data:`FLIGHT_STEPS` coarsest steps;
    - the battery's own reading of its exact samples gives every figure (the apex, the
      periods, the impact: otherwise no engine can be judged on them), each within
      ``READ_RTOL`` of the exact figure;
    - a ball bouncing to rest comes to rest within the duration; an oblique impact's run
      ends between the rebound's apex and the second impact;
    - every impact is :data:`IMPACT_MARGIN_STEPS` finest steps from every sample.

    Parameters
    ----------
    s : Scenario
        The scenario, a variant of a built-in kind.

    Raises
    ------
    ScenarioRangeError
        Where the scenario is outside its valid range (the message says which rule).
    UnknownScenarioError
        Where its kind (``extra["kind"]``) is unknown.
    MechanicsValueError
        Where it lacks what its kind needs (a ground, a pivot, a body's shape).

    Examples
    --------
    A built-in scenario is valid; run twice as long, its last sample is not its end:

    >>> import dataclasses
    >>> s = get_scenario("parabola")
    >>> check_scenario(s) is None
    True
    >>> check_scenario(dataclasses.replace(s, duration=2 * s.duration))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    mechanics.conformance.scenarios.ScenarioRangeError: scenario 'parabola' is outside ...
    """

    def refuse(why: str) -> ScenarioRangeError:
        return ScenarioRangeError(f"scenario {s.name!r} is outside its valid range: {why}")

    _kind(s)
    t = np.asarray(s.sample_times, dtype=float)
    if t.ndim != 1 or t.size < 2 or t[0] != 0 or np.any(np.diff(t) <= 0):
        raise refuse("its sample times must start at 0 and increase")
    if abs(t[-1] - s.duration) > GRID_RTOL * s.duration:
        raise refuse(f"its last sample {float(t[-1])!r} is not its duration {s.duration!r}")
    for h in s.steps:
        n = t / h
        if not (h > 0 and np.all(np.abs(n - np.round(n)) <= GRID_RTOL * np.maximum(n, 1))):
            raise refuse(f"the step {h!r} does not divide every sample time")
    if s.extra.get("kind") == "bounce":
        impacts, t_rest = _bounce_impacts(s)
        if t_rest <= s.duration:
            raise refuse(
                f"the ball comes to rest at t_f (1 + e)/(1 − e) = {t_rest:.4g} s, within the "
                f"duration {s.duration:g} s: its last bounces are shorter than any step"
            )
        coarse = max(s.steps, default=0.0)
        starts = np.array(impacts[:-1])
        flights = np.diff(impacts)[starts <= s.duration]  # those that start in the run
        short = flights[flights < FLIGHT_STEPS * coarse]
        if short.size:
            raise refuse(
                f"a flight between bounces lasts {short[0]:.3g} s, under {FLIGHT_STEPS:g} "
                f"of its coarsest steps ({coarse:g} s)"
            )
    if s.extra.get("kind") == "rest":
        _, _, t_k, t_rest = _rest_numbers(s)
        if math.isinf(t_k):
            e = _required(s, "a ground", s.ground).restitution
            raise refuse(f"a ball with e = {e:g} never comes to rest")
        if not t_k < s.duration:
            raise refuse(
                f"the ball's rebounds fall below {REST_FRACTION:g} of its first impact speed "
                f"at {t_k:.4g} s (accumulating at {t_rest:.4g} s), after the duration "
                f"{s.duration:g} s: it does not come to rest within the run"
            )
    if s.extra.get("kind") == "oblique":
        _, _, nrm, t1, _, _, v_after, _, _ = _oblique_numbers(s)
        g_n = -float(_gravity(s) @ nrm)
        rise = float(v_after @ nrm) / g_n
        if not t1 + rise < s.duration < t1 + 2.0 * rise:
            raise refuse(
                f"the run must end between the rebound's apex ({t1 + rise:.4g} s) and the "
                f"second impact ({t1 + 2.0 * rise:.4g} s); its duration is {s.duration:g} s"
            )
    ref = reference(s)
    floor = READ_RTOL
    for name, value in measure(s, ref.trajectory).items():
        if isinstance(value, str):
            raise refuse(f"the figure {name!r} cannot be read off its exact samples: {value}")
        exact = ref.figures[name]
        scale = float(np.max(np.abs(exact)))
        off = float(np.max(np.abs(np.asarray(value) - exact))) / (scale if scale > 0 else 1.0)
        if not off <= floor:
            raise refuse(
                f"the figure {name!r} read off its exact samples is {off:.3g} off (relative), "
                f"above the exact profile's {floor:.3g}: its samples are too sparse to read it"
            )
    fine = min(s.steps, default=0.0)
    for ti in _impact_times(s):
        gap = float(np.min(np.abs(t - ti)))
        if gap < IMPACT_MARGIN_STEPS * fine:
            raise refuse(
                f"an impact at {ti:.6g} s falls {gap:.3g} s from a sample, under "
                f"{IMPACT_MARGIN_STEPS:g} of its finest steps ({fine:g} s)"
            )


# --------------------------------------------------------------------------- scenarios

_STEPS = (2.0**-6, 2.0**-7, 2.0**-8)
_J = (2.0, 3.0, 4.0)
_BOX = Shape("box", (math.sqrt(7.5), math.sqrt(4.5), math.sqrt(1.5)))  # J = (2, 3, 4) at 1 kg
_TILT = _rows(matrix_from_euler(0.3, 0.7, -0.4))


def _free_top(name, omega, duration, description) -> Scenario:
    return Scenario(
        name,
        description,
        "(4.47), (5.85)-(5.90), Essén 5.3",
        (Body("box", 1.0, _J, _BOX, R_A_O=_TILT, omega=omega),),
        duration=duration,
        sample_times=_times(duration, 2.0**-4),
        steps=_STEPS,
        extra={"kind": "free_top"},
    )


def _build() -> dict[str, Scenario]:
    out = [
        _free_top(
            "free_top_axis1",
            (2.0, 0.3, 0.2),
            8.0,
            "torque-free asymmetric body, ω circulating the axis of least moment",
        ),
        _free_top(
            "free_top_axis3",
            (0.2, 0.3, 2.0),
            8.0,
            "torque-free asymmetric body, ω circulating the axis of greatest moment",
        ),
        _free_top(
            "free_top_near_separatrix",
            (0.04, 4.0, 0.0),
            14.0,
            "torque-free body spun 1 % off the intermediate axis: m1 = 1.3e-4, a flip every 8.3 s",
        ),
    ]
    ell, m = 0.1, 1.0
    top = Body(
        "top",
        m,
        (0.3, 0.3, 0.5),
        Shape("cylinder", (1.0, math.sqrt(0.15))),
        R_A_O=_rows(matrix_from_euler(0.0, 0.6, 0.0)),
        omega=(0.0, 0.0, 6.0),
    )
    R0 = np.array(top.R_A_O)
    top = Body(
        top.name,
        m,
        top.inertia,
        top.shape,
        position=_vec3(R0.T @ (0.0, 0.0, ell)),
        R_A_O=top.R_A_O,
        omega=top.omega,
    )
    out.append(
        Scenario(
            "heavy_top",
            "heavy symmetric top on a pivot 0.1 m below G, released at θ = 0.6 rad "
            "spinning 6 rad/s: nutation and precession",
            "(5.53), (5.55), (5.66), Essén 5.2.2-5.2.5",
            (top,),
            duration=2.0,
            sample_times=_times(2.0, 2.0**-7),
            gravity=(0.0, 0.0, -9.81),
            pivot=Pivot(0, (0.0, 0.0, -ell)),
            steps=(2.0**-7, 2.0**-8, 2.0**-9),
            extra={"kind": "heavy_top"},
        )
    )
    ball = Body(
        "ball",
        0.5,
        (0.002, 0.002, 0.002),
        Shape("sphere", (0.1,)),
        position=(0.0, 0.0, 1.0),
        velocity=(3.0, 1.0, 8.0),
        R_A_O=_TILT,
        omega=(1.0, -2.0, 3.0),
    )
    out.append(
        Scenario(
            "parabola",
            "a spinning ball thrown under gravity: the parabola and its apex",
            "ṗ = F (1.1) under uniform gravity; (4.47) with M = 0",
            (ball,),
            duration=1.5,
            sample_times=_times(1.5, 2.0**-5),
            gravity=(0.0, 0.0, -9.81),
            steps=_STEPS,
            extra={"kind": "parabola"},
        )
    )
    out.append(
        Scenario(
            "two_body_impact",
            "two spheres (1 kg, 3 kg) head-on along x with e = 0.6, no gravity",
            "(6.36)-(6.38), Essén 6.3",
            (
                Body(
                    "a",
                    1.0,
                    (0.004, 0.004, 0.004),
                    Shape("sphere", (0.1,)),
                    position=(-1.0, 0.0, 0.0),
                    velocity=(2.0, 0.0, 0.0),
                ),
                Body(
                    "b",
                    3.0,
                    (0.027, 0.027, 0.027),
                    Shape("sphere", (0.15,)),
                    position=(0.5, 0.0, 0.0),
                    velocity=(-1.0, 0.0, 0.0),
                ),
            ),
            duration=1.0,
            sample_times=_times(1.0, 2.0**-5),
            pair_restitution=((0, 1, 0.6),),
            steps=_STEPS,
            extra={"kind": "impact"},
        )
    )
    out.append(
        Scenario(
            "bouncing_ball",
            "a ball dropped from 1.275 m onto smooth ground, e = 0.8, drifting sideways: "
            "three apexes e^(2k) h0",
            "(6.6), Example 6.1",
            (
                Body(
                    "ball",
                    0.5,
                    (0.002, 0.002, 0.002),
                    Shape("sphere", (0.1,)),
                    position=(0.0, 0.0, 1.375),
                    velocity=(0.5, 0.0, 0.0),
                ),
            ),
            duration=2.375,
            sample_times=_times(2.375, 2.0**-5),
            gravity=(0.0, 0.0, -9.81),
            ground=Ground(0.8),
            steps=_STEPS,
            extra={"kind": "bounce"},
        )
    )
    out.append(
        Scenario(
            "rocket",
            "a 10 kg rocket burning 0.5 kg/s for 8 s at 20 m/s exhaust speed along its "
            "tilted axis 3, in free space",
            "(7.30), Example 7.2 with g = 0",
            (Body("rocket", 10.0, (0.1, 0.1, 0.05), R_A_O=_TILT),),
            duration=10.0,
            sample_times=_times(10.0, 2.0**-3),
            thrust=Thrust(0, 0.5, 20.0, 8.0),
            steps=_STEPS,
            extra={"kind": "rocket"},
        )
    )
    out += _contact_scenarios()
    return {s.name: s for s in out}


def _box_inertia(m: float, dims) -> tuple[float, float, float]:
    a, b, c = dims
    return (m * (b * b + c * c) / 3, m * (a * a + c * c) / 3, m * (a * a + b * b) / 3)


def _contact_scenarios() -> list[Scenario]:
    g = 9.81
    slab = (0.3, 0.2, 0.1)  # half extents: lying on its largest face, 0.1 m high
    box = Body("box", 1.0, _box_inertia(1.0, slab), Shape("box", slab))
    r = 0.1
    ball = Body("ball", 1.0, (0.4 * r * r,) * 3, Shape("sphere", (r,)))
    alpha = 0.3
    out = [
        Scenario(
            "box_landing_flat",
            "a box dropped flat onto rough ground (e = 0.7, μ = 0.5): its four corners "
            "strike at once, and it bounces without turning or sliding",
            "(6.6), Example 6.1; simultaneous contacts",
            (Body(box.name, box.mass, box.inertia, box.shape, position=(0.0, 0.0, 0.52)),),
            duration=1.125,
            sample_times=_times(1.125, 2.0**-5),
            gravity=(0.0, 0.0, -g),
            ground=Ground(0.7, friction=0.5),
            steps=_STEPS,
            extra={"kind": "bounce"},
        ),
        Scenario(
            "sliding_stop",
            "a box sliding on its face at 2 m/s over ground with μ = 0.5: it stops after "
            "v0/(μ g) at v0²/(2 μ g)",
            "Coulomb friction, ṗ = F (1.1)",
            (
                Body(
                    box.name,
                    box.mass,
                    box.inertia,
                    box.shape,
                    position=(0.0, 0.0, slab[2]),
                    velocity=(2.0, 0.0, 0.0),
                ),
            ),
            duration=0.75,
            sample_times=_times(0.75, 2.0**-5),
            gravity=(0.0, 0.0, -g),
            ground=Ground(0.5, friction=0.5),
            steps=_STEPS,
            extra={"kind": "slide"},
        ),
        Scenario(
            "incline_rolling",
            "a solid ball released on a 0.3 rad incline (gravity tilted over flat ground, "
            "μ = 0.5): it rolls without slipping at a = 5/7 g sin α",
            "Example 5.1 (a sphere rolling on a rough incline), Example 3.6",
            (Body(ball.name, ball.mass, ball.inertia, ball.shape, position=(0.0, 0.0, r)),),
            duration=1.0,
            sample_times=_times(1.0, 2.0**-5),
            gravity=(g * math.sin(alpha), 0.0, -g * math.cos(alpha)),
            ground=Ground(0.5, friction=0.5),
            steps=_STEPS,
            extra={"kind": "roll"},
        ),
        Scenario(
            "newtons_cradle",
            "Newton's cradle: a ball at 1 m/s strikes two touching equal balls, every "
            "pair elastic: the textbook answer, the first two stop and the last leaves at "
            "1 m/s",
            "(6.36)-(6.38) with e = 1, applied down the row; Essén 6.3",
            (
                Body(
                    "b0",
                    ball.mass,
                    ball.inertia,
                    ball.shape,
                    position=(-0.51, 0.0, 0.0),
                    velocity=(1.0, 0.0, 0.0),
                ),
                Body("b1", ball.mass, ball.inertia, ball.shape, position=(0.2, 0.0, 0.0)),
                Body("b2", ball.mass, ball.inertia, ball.shape, position=(0.4, 0.0, 0.0)),
            ),
            duration=1.0,
            sample_times=_times(1.0, 2.0**-5),
            pair_restitution=((0, 1, 1.0), (1, 2, 1.0)),
            steps=_STEPS,
            extra={"kind": "cradle"},
        ),
        Scenario(
            "bounce_to_rest",
            "a ball dropped from 0.41 m onto smooth ground, e = 0.5: its impacts accumulate "
            "at t_f (1 + e)/(1 − e) = 0.867 s, and it rests",
            "(6.6), Example 6.1",
            (Body(ball.name, ball.mass, ball.inertia, ball.shape, position=(0.0, 0.0, 0.51)),),
            duration=1.25,
            sample_times=_times(1.25, 2.0**-5),
            gravity=(0.0, 0.0, -g),
            ground=Ground(0.5),
            steps=_STEPS,
            extra={"kind": "rest"},
        ),
        _oblique(
            "oblique_impact_sticks",
            "sticks: the friction stops the slip within the impact (μ = 0.5), the ball "
            "leaves rolling",
            speed=1.0,
            mu=0.5,
        ),
        _oblique(
            "oblique_impact_slips",
            "slips: Coulomb's bound μ P_n (μ = 0.1) cannot stop the slip, the ball leaves "
            "sliding and spinning",
            speed=3.0,
            mu=0.1,
        ),
    ]
    return out


def _oblique(name: str, what: str, *, speed: float, mu: float) -> Scenario:
    r = 0.1
    ball = Body(
        "ball",
        1.0,
        (0.4 * r * r,) * 3,
        Shape("sphere", (r,)),
        position=(0.0, 0.0, r + 0.45),
        velocity=(speed, 0.0, 0.0),
    )
    return Scenario(
        name,
        f"a ball falling 0.45 m at {speed:g} m/s sideways onto rough ground (e = 0.5) {what}",
        "impulse and angular impulse (Section 6.2), Newton's e (6.6), Coulomb's bound",
        (ball,),
        duration=0.5,
        sample_times=_times(0.5, 2.0**-5),
        gravity=(0.0, 0.0, -9.81),
        ground=Ground(0.5, friction=mu),
        steps=_STEPS,
        extra={"kind": "oblique"},
    )


#: The battery, by name, in the order of the report.
SCENARIOS: dict[str, Scenario] = _build()


def get_scenario(name: str) -> Scenario:
    """The battery's scenario ``name``; :class:`UnknownScenarioError` naming the known ones.

    Parameters
    ----------
    name : str
        A key of :data:`SCENARIOS`.

    Returns
    -------
    Scenario
        The built-in scenario.

    Raises
    ------
    UnknownScenarioError
        Where ``name`` is not a scenario of the battery (the message lists them).

    Examples
    --------
    >>> get_scenario("heavy_top") is SCENARIOS["heavy_top"]
    True
    >>> get_scenario("heavy_tops")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    mechanics.conformance.scenarios.UnknownScenarioError: unknown scenario 'heavy_tops'; ...
    """
    if name not in SCENARIOS:
        raise UnknownScenarioError(
            f"unknown scenario {name!r}; the battery has {', '.join(SCENARIOS)}"
        )
    return SCENARIOS[name]
