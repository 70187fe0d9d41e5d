"""The reference adapters: the closed forms ("exact") and the project's own integrated
engine, :mod:`mechanics.scenes` ("integrated").

Examples
--------
>>> from mechanics.conformance import run_battery
>>> run_battery(SceneEngineAdapter(), scenarios=["two_body_impact"]).passed
True
"""

from __future__ import annotations

import math

import numpy as np

from ..._floats import EPS
from ..._validate import check_option
from ..protocol import SAMPLE_TIME_RTOL, Scenario, Trajectory
from ..scenarios import reference

__all__ = ["ExactAdapter", "SceneEngineAdapter", "scene_from_scenario"]

#: a colliding body's given moments must be its shape's at uniform density (2/5 m r² for
#: a sphere; the engine derives them from the shape) to rounding: a few operations, 2^4 eps
SPHERE_INERTIA_RTOL = 2**4 * EPS


class ExactAdapter:
    """The exact column: returns each scenario's closed-form reference.

    Its state errors are zero; its derived figures show the floor of reading them off
    samples (crossing times by local polynomials, ~1e-12 to 1e-10).

    Examples
    --------
    Its run is the reference, at no step of its own:

    >>> from mechanics.conformance import get_scenario
    >>> s = get_scenario("heavy_top")
    >>> a = ExactAdapter()
    >>> a.supports(s), a.takes_step
    (None, False)
    >>> bool(np.array_equal(a.run(s, None).R_A_O, reference(s).trajectory.R_A_O))
    True
    """

    name = "exact (closed forms)"
    takes_step = False

    def supports(self, scenario: Scenario) -> str | None:
        return None

    def run(self, scenario: Scenario, step: float | None) -> Trajectory:
        return reference(scenario).trajectory


def _is_solid_sphere(body) -> bool:
    if body.shape is None or body.shape.kind != "sphere":
        return False
    J = 0.4 * body.mass * body.shape.dims[0] ** 2
    return all(abs(x - J) <= SPHERE_INERTIA_RTOL * J for x in body.inertia)


def _uniform(body) -> dict | None:
    """The scene engine's body entry for a colliding body whose moments are those of
    its shape at uniform density (the engine derives them from the shape): a solid
    sphere, a box (half extents → edges) or a solid cylinder (half length → height);
    None otherwise."""
    if _is_solid_sphere(body):
        return {"shape": "solid_sphere", "radius": body.shape.dims[0]}
    if body.shape is None:
        return None
    m, d = body.mass, body.shape.dims
    if body.shape.kind == "box":
        a, b, c = d
        J = (m * (b * b + c * c) / 3, m * (a * a + c * c) / 3, m * (a * a + b * b) / 3)
        entry = {"shape": "box", "a": 2 * a, "b": 2 * b, "c": 2 * c}
    elif body.shape.kind == "cylinder":
        r, h = d
        side = m * (3 * r * r + 4 * h * h) / 12
        J = (side, side, m * r * r / 2)
        entry = {"shape": "cylinder", "radius": r, "height": 2 * h}
    else:
        return None
    ok = all(
        abs(x - y) <= SPHERE_INERTIA_RTOL * max(J) for x, y in zip(body.inertia, J, strict=True)
    )
    return entry if ok else None


def scene_from_scenario(s: Scenario, *, method: str = "integrate", rtol=None, atol=None):
    """The scene that runs ``s`` on the project's engine, or a string saying why it cannot.

    The scene is a dict for :func:`mechanics.scenes.parse_scene`.

    Parameters
    ----------
    s : Scenario
        The scenario.
    method : str, optional
        The scene's ``method`` (default ``"integrate"``; the scene parser checks it).
    rtol, atol : float, optional
        The scene's tolerances (default: the scene's own).

    Returns
    -------
    dict or str
        The scene (``scene``, ``bodies``, ``effects``), or the reason the engine cannot
        run ``s`` (its samples not uniform from 0, a spinning rocket, a colliding body
        that is not a solid sphere, box or cylinder of uniform density, a pivot off body
        axis 3 below G).

    Raises
    ------
    NotARotationError
        Where a body's ``R_A_O`` is not a rotation (read as Euler angles).

    Examples
    --------
    Each body's name carries its index; samples off the uniform grid are refused:

    >>> import dataclasses
    >>> from mechanics.conformance import get_scenario
    >>> s = get_scenario("two_body_impact")
    >>> [b["name"] for b in scene_from_scenario(s)["bodies"]] == [
    ...     f"b{i}_{b.name}" for i, b in enumerate(s.bodies)]
    True
    >>> scene_from_scenario(dataclasses.replace(s, sample_times=(0.0, 0.1, s.duration)))
    'the scene engine samples uniformly from 0 to the duration'
    """
    from ...rotation import euler_from_matrix

    T = np.asarray(s.sample_times, dtype=float)
    if T.size < 2 or not np.allclose(
        T, np.linspace(0.0, s.duration, T.size), rtol=0, atol=SAMPLE_TIME_RTOL * max(s.duration, 1)
    ):
        return "the scene engine samples uniformly from 0 to the duration"
    colliding = {i for i, j, _ in s.pair_restitution} | {j for _, j, _ in s.pair_restitution}
    if s.ground is not None:
        colliding |= set(range(len(s.bodies)))
    names = [f"b{i}_{b.name}" for i, b in enumerate(s.bodies)]
    bodies, effects = [], []
    for i, b in enumerate(s.bodies):
        still = not any(b.omega)
        entry: dict | None  # the body's entry; None: the engine cannot collide the body
        if s.thrust is not None and s.thrust.body == i:
            if not still:
                return "the scene engine's thrust is space-fixed: the rocket must not spin"
            entry = {"shape": "point"}
        elif i in colliding:
            entry = _uniform(b)
            if entry is None:
                return (
                    f"body {b.name!r} collides: the scene engine collides solid spheres, "
                    "boxes and cylinders of uniform density (their moments from the shape)"
                )
        else:
            entry = {"shape": "custom", "inertia": list(b.inertia)}
        init: dict = {}
        if entry["shape"] != "point":
            psi, theta, phi = (float(x) for x in euler_from_matrix(np.array(b.R_A_O)))
            init.update(psi=psi, theta=theta, phi=phi, omega=list(b.omega))
        if s.pivot is None or s.pivot.body != i:
            init.update(position=list(b.position), velocity=list(b.velocity))
        bodies.append({"name": names[i], "mass": b.mass, **entry, "initial": init})
    g = np.asarray(s.gravity, dtype=float)
    if g.any():
        gn = float(np.linalg.norm(g))
        effects.append({"type": "gravity", "g": gn, "direction": list(g / gn)})
    if s.pivot is not None:
        p = s.pivot
        if p.point[0] != 0 or p.point[1] != 0 or p.point[2] >= 0:
            return "the scene engine's fixed point lies on body axis 3 below G"
        effects.append(
            {
                "type": "fixed_point",
                "body": names[p.body],
                "distance": -p.point[2],
                "point": list(p.anchor),
            }
        )
    if s.ground is not None:
        n = np.asarray(s.ground.normal, dtype=float)
        for i in range(len(s.bodies)):
            effects.append(
                {
                    "type": "impact",
                    "body": names[i],
                    "plane_point": list(s.ground.height * n / float(n @ n)),
                    "plane_normal": list(n),
                    "restitution": s.ground.restitution,
                    **({"friction": s.ground.friction} if s.ground.friction > 0 else {}),
                }
            )
    for i, j, e in s.pair_restitution:
        effects.append({"type": "impact", "body": names[j], "other": names[i], "restitution": e})
    if s.thrust is not None:
        th = s.thrust
        d = np.array(s.bodies[th.body].R_A_O).T @ np.asarray(th.axis, dtype=float)
        effects.append(
            {
                "type": "thrust",
                "body": names[th.body],
                "mass_flow": th.mass_rate,
                "exhaust_speed": th.exhaust_speed,
                "fuel_mass": th.mass_rate * th.burn_time,
                "direction": list(d),
                "frame": "space",
            }
        )
    head = {"name": s.name, "duration": s.duration, "samples": int(T.size), "method": method}
    if rtol is not None:
        head["rtol"] = rtol
    if atol is not None:
        head["atol"] = atol
    return {"scene": head, "bodies": bodies, "effects": effects}


class SceneEngineAdapter:
    """The integrated column: the scenario as a scene on :mod:`mechanics.scenes`.

    The scene is run by the engine's adaptive DOP853 (``method="integrate"``; ``"auto"``
    takes the engine's exact flows where it has them) at the scene's default tolerances
    or the given ones.  The engine chooses its own steps (``takes_step`` is False).

    Parameters
    ----------
    method : {"integrate", "auto", "exact", "splitting"}, optional
        The scene's ``method`` (default ``"integrate"``), one of the scene parser's
        :data:`~mechanics.scenes.spec.METHODS`.
    rtol, atol : float, optional
        The integrator's tolerances (default: the scene's own).

    Raises
    ------
    UnknownOptionError
        Where ``method`` is not one of :data:`~mechanics.scenes.spec.METHODS` (checked when
        the adapter is made, not when a scenario is run).

    Examples
    --------
    >>> from mechanics.conformance import run_battery
    >>> a = SceneEngineAdapter()
    >>> a.name, run_battery(a, scenarios=["parabola"])["parabola"].status
    ('bodycheck scene engine (integrate)', 'pass')
    >>> SceneEngineAdapter("bogus")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    mechanics.errors.UnknownOptionError: scene engine method must be one of (...); got 'bogus'
    """

    takes_step = False

    def __init__(self, method: str = "integrate", *, rtol=None, atol=None) -> None:
        from ...scenes.spec import METHODS

        self.method = check_option(method, METHODS, "scene engine method")
        self.rtol, self.atol = rtol, atol
        self.name = f"bodycheck scene engine ({method})"

    def supports(self, scenario: Scenario) -> str | None:
        """Why the engine cannot run ``scenario``, or None.  Loads its compiled kernels
        first (:func:`mechanics.scenes.compiled.warm`: numba's import and its cache, once
        per process), so that a timed run times the run, as for the other engines."""
        from ...scenes.compiled import warm

        scene = scene_from_scenario(scenario, method=self.method)
        if isinstance(scene, str):
            return scene
        warm()
        return None

    def run(self, scenario: Scenario, step: float | None) -> Trajectory:
        from ...rotation import nearest_rotation
        from ...scenes import parse_scene
        from ...scenes.simulate import simulate

        data = scene_from_scenario(scenario, method=self.method, rtol=self.rtol, atol=self.atol)
        if isinstance(data, str):
            raise ValueError(data)
        tr = simulate(parse_scene(data, source=f"scenario {scenario.name}"))
        snap = tr.snapshot
        m = np.asarray(snap.m, dtype=float)
        # the engine integrates R's nine entries at its tolerance (off SO(3) by ~1e-11
        # after a few turns): the protocol asks for rotations, so project (polar factor)
        R = nearest_rotation(np.array(snap.R, dtype=float))
        w = np.array(snap.omega, dtype=float)
        for i, b in enumerate(scenario.bodies):
            if data["bodies"][i]["shape"] == "point":  # no attitude in the engine: it keeps
                R[:, i] = np.array(b.R_A_O)  # the initial one, never turning
                w[:, i] = 0.0
        masses = m if scenario.thrust is not None else None
        t = np.asarray(scenario.sample_times, dtype=float)
        pos, vel = np.asarray(snap.r, dtype=float), np.asarray(snap.v, dtype=float)
        if not math.isclose(float(tr.t[-1]), float(t[-1]), rel_tol=SAMPLE_TIME_RTOL):
            raise ValueError(f"the engine sampled to {tr.t[-1]}, not {t[-1]}")
        return Trajectory(t, pos, vel, R, w, masses)
