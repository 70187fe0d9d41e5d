"""What a lecturer asks of a scene, built-in or a user's: the derived quantities its
bodies and effects define, from the exact solution where one exists and measured from
the trajectory, both shown when both exist.

Conventions
-----------
- **A free rigid body no effect turns** (a torque-free top): its regime (which axis ω
  circulates, :class:`mechanics.tops.FreeAsymmetricTop`) and the period of ω(t),
  4K/λ (the body flips twice in it); measured: twice the mean spacing of the sign
  changes of ω about the middle axis.
- **A heavy symmetric top** (a ``fixed_point`` body with J1 = J2 about C under gravity
  along −z alone): the nutation range of θ (the roots u1, u2 of the cubic, 5.2.4) and
  the nutation period 2K(m)/κ; measured: the extremes of θ over the samples and the
  mean spacing of the maxima of cos θ (each the vertex of a parabola through three
  samples); the mean precession rate Δψ/T over a nutation period (the exact ψ(t));
  measured: ψ's advance between the first and the last maximum over their time apart.
- **Impacts**: the kinetic energy lost, summed over the impacts, against the sum of
  the Chapter 6 formula ½ μ (1 − e²) v_n² (6.41) (the impulse's work with friction).
- **A rocket** (space-fixed ``thrust``): the speed at burn-out by (7.30),
  u ln(m0/m_f) less g t_b along the thrust, against the simulated one.
- A quantity measured from fewer than two features (crossings, maxima) is left out.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, cast

import numpy as np

from mechanics import kinematics as kin

from .vectors import FloatArray

if TYPE_CHECKING:  # for annotations only
    from .effects.gravity import Gravity
    from .effects.thrust import Thrust
    from .engine import Engine
    from .trajectory import Trajectory

__all__ = ["derived_quantities"]


def _crossings(t: FloatArray, x: FloatArray) -> FloatArray:
    """Times where x changes sign, by linear interpolation between samples."""
    s = np.sign(x)
    i = np.nonzero(s[:-1] * s[1:] < 0)[0]
    out: FloatArray = t[i] - x[i] * (t[i + 1] - t[i]) / (x[i + 1] - x[i])
    return out


def _vertex(t: FloatArray, x: FloatArray, k: int) -> float:
    """The time of the extremum near sample k: the vertex of the parabola through the
    samples k − 1, k, k + 1 (evenly spaced)."""
    den = x[k - 1] - 2.0 * x[k] + x[k + 1]
    return float(t[k] + 0.5 * (t[1] - t[0]) * (x[k - 1] - x[k + 1]) / den) if den else float(t[k])


def _spacing(times: Sequence[float] | FloatArray) -> float | None:
    return float(np.mean(np.diff(times))) if len(times) >= 2 else None


def derived_quantities(
    engine: Engine, traj: Trajectory
) -> list[tuple[str, float | None, float | None]]:
    """(name, exact, measured) rows for the scene the engine ran.

    The rows the module's Conventions list, for each body or effect that defines them: a
    torque-free rigid body's regime and period of ω, a heavy symmetric top's nutation
    range, nutation period and mean precession rate, the kinetic energy lost in impacts
    (6.41), and a rocket's speed gained by burn-out (7.30).

    Parameters
    ----------
    engine : Engine
        The engine that ran the scene (:class:`mechanics.scenes.engine.Engine`).
    traj : Trajectory
        Its run (:meth:`~mechanics.scenes.engine.Engine.run`): the samples, series and
        events the measured values are taken from.

    Returns
    -------
    list of tuple of (str, float or None, float or None)
        Rows (name, exact, measured) in SI units (the name says the unit where it is not
        the quantity's SI one); None where a value has no closed form or too few
        features were sampled to measure it.  Empty for a scene that defines none.

    Raises
    ------
    ResultOverflowError
        Where a heavy top's closed form leaves float64's range (e.g. g = 1e-30 m/s²
        against a spin of 100 rad/s: ψ(t) overflows);
        :func:`~mechanics.scenes.simulate.simulate` reports it as a SceneError.
    MechanicsValueError
        Any other refusal of :class:`mechanics.tops.HeavySymmetricTop` (its Raises
        section) for a heavy top outside its closed form's domain.  (A free top's
        refusal is caught: it only leaves out its rows.)

    Examples
    --------
    The rocket of Example 7.2: its speed at burn-out by (7.30), u ln(m0/m_f) − g t_b,
    against the run's:

    >>> from mechanics.scenes import builtin_path, load_scene
    >>> from mechanics.scenes.engine import Engine
    >>> eng = Engine(load_scene(builtin_path("rocket")))
    >>> ((name, exact, measured),) = derived_quantities(eng, eng.run())
    >>> name, bool(np.isclose(exact, 2000.0 * np.log(1000.0 / 200.0) - 9.81 * 80.0))
    ('speed gained by burn-out (7.30)', True)
    >>> from mechanics._floats import EPS  # the rocket's exact flow: (7.30) to its rounding
    >>> bool(np.isclose(measured, exact, rtol=64 * EPS, atol=0.0))
    True
    """
    from mechanics.tops import FreeAsymmetricTop, HeavySymmetricTop

    rows: list[tuple[str, float | None, float | None]] = []
    lay, t, series = engine.layout, traj.t, traj.series
    pre: Callable[[int], str] = (
        (lambda i: f"{engine.names[i]}.") if engine.n > 1 else (lambda i: "")
    )
    for i in lay.rigid_bodies:
        md = engine.model  # (an impact exerts a moment only on a body of its pair)
        struck = (md.impacts[a] for a in md.impacts_of.get(i, ()))
        if lay.kinds[i] != "rigid" or any(e.exerts_moment(i) for e in (*md.forces, *struck)):
            continue
        J, w0 = lay.J[i], engine.w0[i]
        if not (np.all(J > 0) and w0.any()):
            continue
        try:
            top = FreeAsymmetricTop(J, w0, engine.R0[i])
        except Exception:  # within rounding of the separatrix: no closed form here
            continue
        mid = int(np.argsort(J)[1])
        w_mid = series[f"{pre(i)}omega{mid + 1}"]
        half = _spacing(_crossings(t, w_mid))
        period = top.flip_period()
        rows.append((f"{pre(i)}regime: {top.regime}", None, None))
        rows.append(
            (
                f"{pre(i)}period of ω (two flips)",
                float(period) if math.isfinite(period) else None,
                2.0 * half if half else None,
            )
        )
    kinds = {e.type for e in engine.effects}
    for i, (_, g, JC, _) in lay.pins.items():
        Jc = np.diag(JC)
        grav = [cast("Gravity", e) for e in engine.effects if e.type == "gravity"]
        if not (
            engine.n == 1
            and kinds == {"fixed_point", "gravity"}
            and len(grav) == 1
            and Jc[0] == Jc[1]
            and g[2] > 0
            and np.array_equal(grav[0].direction, [0.0, 0.0, -1.0])
        ):
            continue
        ini = engine.scene.bodies[i].initial
        th, ph = float(ini.get("theta", 0.0)), float(ini.get("phi", 0.0))
        if not 0.0 < th < math.pi:
            continue
        psd, thd, phd = kin.euler_rates_from_angular_velocity(th, ph, engine.w0[i])
        heavy = HeavySymmetricTop(
            Jc[0],
            Jc[2],
            float(engine.m0[i]) * grav[0].g * g[2],
            theta=th,
            theta_dot=thd,
            psi_dot=psd,
            phi_dot=phd,
        )
        theta = series[f"{pre(i)}theta"]
        u1, u2, _ = heavy.roots
        rows.append(("θ min (rad)", math.acos(min(u2, 1.0)), float(np.min(theta))))
        rows.append(("θ max (rad)", math.acos(max(u1, -1.0)), float(np.max(theta))))
        if not heavy.sleeping:
            exact = heavy.nutation_period()
            c = series[f"{pre(i)}cos_theta"]
            top_k = [k for k in range(1, len(c) - 1) if c[k] > c[k - 1] and c[k] >= c[k + 1]]
            peaks = [_vertex(t, c, k) for k in top_k]
            rows.append(("nutation period", exact, _spacing(peaks)))
            # the mean precession rate: ψ advances by the same Δψ in every nutation
            # period (5.2.5), so Δψ/T over one period is the rate over any whole number;
            # measured over the whole periods between the first and the last maximum
            rate = float(heavy.psi(exact) - heavy.psi(0.0)) / exact
            measured: float | None = None
            if len(peaks) >= 2:
                psi = series[f"{pre(i)}psi"]
                ends = np.interp([peaks[0], peaks[-1]], t, psi)
                measured = float(ends[1] - ends[0]) / (peaks[-1] - peaks[0])
            rows.append(("mean precession rate ψ̇ (rad/s)", rate, measured))
    impacts = [e.detail for e in traj.events if "energy_loss" in e.detail]
    if impacts:
        lost = sum(d["kinetic_energy_before"] - d["kinetic_energy_after"] for d in impacts)
        rows.append(
            ("kinetic energy lost in impacts (6.41)", sum(d["energy_loss"] for d in impacts), lost)
        )
    g_vec = sum(
        (cast("Gravity", e).vector for e in engine.effects if e.type == "gravity"), np.zeros(3)
    )
    for eff in engine.effects:
        e = cast("Thrust", eff)  # (its fields read where its type is "thrust")
        if e.type != "thrust" or e.body_frame or e.burn_out > engine.scene.duration:
            continue
        i, m0 = e.i, float(engine.m0[e.i])
        tb = e.burn_out
        exact = e.u * math.log(m0 / (m0 - e.q * tb)) + float(g_vec @ e.direction) * tb
        v0 = np.array(engine.scene.bodies[i].initial.get("velocity", [0.0] * 3)) @ e.direction
        st = traj.state_at(tb)
        v = np.array([st[f"{pre(i)}v{c}"] for c in "xyz"]) @ e.direction
        rows.append(("speed gained by burn-out (7.30)", exact, float(v - v0)))
    return rows
