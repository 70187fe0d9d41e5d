"""MuJoCo, PyBullet and Drake side by side on three problems with exact answers
(issue 19, part 3): what each variant of :mod:`mechanics.conformance.adapters` gets.

``python -m bench.engines`` prints one table per problem (a variant whose engine is not
installed is listed as such):

(a) torque-free asymmetric top, J = (1, 2, 3), 4 s, against
    :class:`mechanics.tops.FreeAsymmetricTop`: largest attitude error (max-abs of
    ^A R^O), relative energy drift, wall time;
(b) a ball dropped 1 m onto the ground with e = 0.8: the rebound ratio measured at the
    height of first touch (energy of the free flight before and after) and the deepest
    penetration;
(c) a heavy symmetric top on a pivot (θ between 0.7 and ~1.3 rad), 2 s: the nutation
    period from the θ(t) samples against :meth:`HeavySymmetricTop.nutation_period`.

The scenarios and measurements are also used by ``tests/conformance/test_engines.py``.
"""

from __future__ import annotations

import math
import time

import numpy as np

from mechanics.conformance.protocol import Body, Ground, Pivot, Scenario, Shape, Trajectory
from mechanics.rotation import matrix_from_euler
from mechanics.tops import FreeAsymmetricTop, HeavySymmetricTop

__all__ = [
    "ball_drop",
    "free_top",
    "heavy_top",
    "main",
    "nutation_period",
    "rebound",
]

G = 9.81


def _rows(R) -> tuple:
    return tuple(tuple(float(x) for x in r) for r in R)


def free_top(
    duration: float = 4.0, samples: int = 41, steps=(1e-2, 5e-3, 2.5e-3)
) -> tuple[Scenario, FreeAsymmetricTop]:
    """A box-shaped free body with J = (1, 2, 3) tumbling near its middle axis, moving
    uniformly, no gravity; and its exact motion."""
    R = matrix_from_euler(0.3, 0.7, 0.2)
    body = Body(
        "top",
        1.5,
        (1.0, 2.0, 3.0),
        Shape("box", (0.1, 0.2, 0.3)),
        position=(0.1, 0.2, 0.3),
        velocity=(0.1, -0.2, 0.3),
        R_A_O=_rows(R),
        omega=(1.0, 0.1, 0.5),
    )
    s = Scenario(
        "free_top",
        "torque-free asymmetric top J = (1, 2, 3)",
        "(4.47), (5.85)",
        (body,),
        duration,
        tuple(np.linspace(0.0, duration, samples)),
        steps=tuple(steps),
    )
    return s, FreeAsymmetricTop(body.inertia, body.omega, R)


BALL_RADIUS = 0.1
DROP_HEIGHT = 1.0  # of the ball's lowest point above the ground


def ball_drop(e: float = 0.8, steps=(1e-4, 1e-5), *, fine: float = 1e-4) -> Scenario:
    """A ball (m = 1, r = 0.1) dropped from rest DROP_HEIGHT above the ground: it
    touches at t = √(2H/g) = 0.4515 s with v = √(2gH) = 4.43 m/s.  Samples every ms,
    every ``fine`` (≥ 0.1 ms, a divisor of 1 ms) from 0.44 to 0.50 s (the contact),
    until 0.7 s."""
    coarse = np.round(np.arange(0, 701) * 1e-3, 12)
    k = round(1e-3 / fine)
    dense = np.round(np.arange(440 * k, 500 * k + 1) * (1e-3 / k), 12)
    times = np.unique(np.concatenate([coarse, dense]))
    J = 0.4 * BALL_RADIUS**2
    ball = Body(
        "ball",
        1.0,
        (J, J, J),
        Shape("sphere", (BALL_RADIUS,)),
        position=(0.0, 0.0, BALL_RADIUS + DROP_HEIGHT),
    )
    return Scenario(
        f"ball_drop_e{e:g}",
        f"a ball dropped {DROP_HEIGHT} m onto the ground, e = {e}",
        "(6.6)",
        (ball,),
        float(times[-1]),
        tuple(float(t) for t in times),
        gravity=(0.0, 0.0, -G),
        ground=Ground(e),
        steps=tuple(steps),
    )


def rebound(scenario: Scenario, tr: Trajectory) -> tuple[float, float]:
    """(rebound ratio, deepest penetration) of the first bounce of ``ball_drop``.

    The ratio compares the speeds at the height of first touch, from the last sample
    before the contact and the first after it with the ball clear of the ground, by
    energy in free flight: v² + 2 g (z − r) is constant there."""
    r = scenario.bodies[0].shape.dims[0]
    g = -scenario.gravity[2]
    z, vz = tr.position[:, 0, 2], tr.velocity[:, 0, 2]
    gap = z - r
    touch = int(np.argmax(gap <= 0)) if (gap <= 0).any() else int(np.argmax(vz > 0))
    before = touch - 1
    after = touch + int(np.argmax((gap[touch:] > 0) & (vz[touch:] > 0)))
    if after == touch and not (gap[touch] > 0 and vz[touch] > 0):
        return 0.0, float(-gap.min())  # it never came back out
    v_before = math.sqrt(vz[before] ** 2 + 2 * g * gap[before])
    v_after = math.sqrt(vz[after] ** 2 + 2 * g * gap[after])
    return v_after / v_before, float(max(0.0, -gap[: after + 1].min()))


HEAVY = {"m": 1.0, "ell": 0.1, "J1_G": 0.004, "J3": 0.006, "theta": 0.7, "phi_dot": 40.0}


def heavy_top(
    duration: float = 2.0, samples: int = 2001, steps=(1e-3, 5e-4, 2.5e-4)
) -> tuple[Scenario, HeavySymmetricTop]:
    """A symmetric top (m = 1, G 0.1 m up its axis from the pivot) released at θ = 0.7
    with spin 40 rad/s and no precession; and its exact motion (5.66)."""
    m, ell, th, spin = HEAVY["m"], HEAVY["ell"], HEAVY["theta"], HEAVY["phi_dot"]
    R = matrix_from_euler(0.0, th, 0.0)
    omega = (0.0, 0.0, spin)
    G_O = R.T @ np.array([0.0, 0.0, ell])  # the pivot is at the origin
    body = Body(
        "top",
        m,
        (HEAVY["J1_G"], HEAVY["J1_G"], HEAVY["J3"]),
        Shape("cylinder", (0.03, 0.02)),
        position=tuple(G_O),
        velocity=tuple(np.cross(R.T @ np.array(omega), G_O)),
        R_A_O=_rows(R),
        omega=omega,
    )
    s = Scenario(
        "heavy_top",
        "heavy symmetric top on a pivot",
        "(5.66)",
        (body,),
        duration,
        tuple(np.linspace(0.0, duration, samples)),
        gravity=(0.0, 0.0, -G),
        pivot=Pivot(0, (0.0, 0.0, -ell)),
        steps=tuple(steps),
    )
    exact = HeavySymmetricTop(
        HEAVY["J1_G"] + m * ell**2,
        HEAVY["J3"],
        m * G * ell,
        theta=th,
        phi_dot=spin,
    )
    return s, exact


def theta_of(tr: Trajectory) -> np.ndarray:
    """θ(t), the symmetry axis' angle from the vertical (row 3 of ^A R^O)."""
    e3 = tr.R_A_O[:, 0, 2, :]
    return np.arctan2(np.hypot(e3[:, 0], e3[:, 1]), e3[:, 2])


def nutation_period(t: np.ndarray, theta: np.ndarray) -> float:
    """Mean spacing of the maxima of θ(t), each located by the parabola through the
    largest sample and its two neighbours; nan with fewer than two maxima."""
    k = np.flatnonzero((theta[1:-1] > theta[:-2]) & (theta[1:-1] >= theta[2:])) + 1
    peaks = []
    for i in k:
        y0, y1, y2 = theta[i - 1], theta[i], theta[i + 1]
        den = y0 - 2 * y1 + y2
        peaks.append(t[i] + (0.5 * (y0 - y2) / den if den != 0 else 0.0) * (t[i + 1] - t[i]))
    if len(peaks) < 2:
        return math.nan
    return float((peaks[-1] - peaks[0]) / (len(peaks) - 1))


def _adapters():
    from mechanics.conformance.adapters import drake, mujoco, pybullet

    out = []
    for mod, extra in ((mujoco, "mujoco"), (pybullet, "pybullet"), (drake, "drake")):
        try:
            out += mod.variants()
        except ImportError:
            print(f"({extra} not installed: pip install 'bodycheck[{extra}]')")
    return out


def _timed(adapter, scenario, step):
    t0 = time.perf_counter()
    tr = adapter.run(scenario, step if adapter.takes_step else None)
    return tr, time.perf_counter() - t0


def main() -> None:
    adapters = _adapters()
    s, exact = free_top()
    t = np.asarray(s.sample_times)
    R_ex = exact.attitude(t)
    J = np.asarray(s.bodies[0].inertia)
    print("(a) free asymmetric top J = (1, 2, 3), 4 s: attitude error, energy drift, time")
    for a in adapters:
        for h in s.steps if a.takes_step else [None]:
            tr, dt = _timed(a, s, h)
            err = np.abs(tr.R_A_O[:, 0] - R_ex).max()
            E = 0.5 * (J * tr.omega[:, 0] ** 2).sum(-1)
            drift = np.abs(E / exact.energy - 1).max()
            print(f"  {a.name:60s} h={h!s:8s} {err:9.2e} {drift:9.2e} {dt:7.3f} s")
    print("(b) ball dropped 1 m, e = 0.8: rebound ratio at first touch, depth, time")
    for a in adapters:
        for h in (1e-3, 1e-4, 1e-5) if a.takes_step else [None]:
            b = ball_drop(0.8, fine=max(h or 1e-4, 1e-4))
            tr, dt = _timed(a, b, h)
            e, depth = rebound(b, tr)
            print(f"  {a.name:60s} h={h!s:8s} e={e:.4f} depth={depth * 1e3:8.3f} mm {dt:7.3f} s")
    print("(c) heavy symmetric top on a pivot, 2 s: nutation period error, θ error, time")
    s, exact = heavy_top()
    t = np.asarray(s.sample_times)
    T = exact.nutation_period()
    for a in adapters:
        for h in s.steps if a.takes_step else [None]:
            tr, dt = _timed(a, s, h)
            th = theta_of(tr)
            dT = nutation_period(t, th) / T - 1
            err = np.abs(th - exact.theta(t)).max()
            print(f"  {a.name:60s} h={h!s:8s} dT/T={dT:10.2e} θ err={err:9.2e} {dt:7.3f} s")
    print(f"  exact nutation period {T:.6f} s")


if __name__ == "__main__":
    main()
