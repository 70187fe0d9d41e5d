"""A structure-preserving splitting for conservative scenes (``method = "splitting"``).

Conventions
-----------
- **When.**  Only on request (``method = "splitting"``), for points and free rigid
  bodies (no joint, no tank, no fixed body) under effects that all keep the energy
  and have a potential (gravity, Newtonian gravity, undamped springs): no impacts and
  no modes, whose instants a fixed step could not locate.  Anything else is refused
  with a :class:`~mechanics.scenes.errors.SceneError` naming ``scene.method``.
- **The method.**  The scene's flow splits into the *kick* of the listed effects
  (positions and attitudes held: v += τ F/m, L_A += τ M_A, the moment about G in body
  components) and the *drift* of free bodies (r += τ v, and each spinning rigid body
  turned by its exact torque-free flow, :class:`mechanics.tops.FreeAsymmetricTop`):
  both are exact flows of their parts, so the composition is symplectic and keeps the
  total momentum (internal forces kick in equal and opposite pairs) and, for loads
  without a moment about the origin, the angular momentum, to rounding.  Strang's
  kick–drift–kick is of order 2; Yoshida's triple jump raises it to 4 and 6
  (``order``, default 4), as in :func:`mechanics.integrators.free_rigid_body_splitting`,
  whose composition helpers it uses.
- **Why.**  A splitting keeps the energy error bounded over long times (it oscillates
  at O(hᵖ) instead of drifting), where an adaptive Runge–Kutta method drifts secularly;
  it has no error control and no dense output, so the step ``step`` (default: the
  sample interval) is the user's choice, rounded down to divide the sample interval.
  The exact torque-free step costs ~0.7 ms per spinning body (elliptic functions, see
  the performance issue), which is why ``auto`` still integrates with DOP853.
- **Self-check of the energy.**  The run is repeated at half the step: the energy's
  drift must shrink like the method's order, drift(h) ≤ 2ᵖ drift(h/2) · 3/2 (plus the
  rounding allowance), which a wrong kick (an O(1) error) cannot meet.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, cast

import numpy as np

from mechanics.errors import OutOfDomainError

from .effects.capabilities import HasPotential
from .trajectory import Dense, Segment, vectorized
from .vectors import FloatArray, Times

if TYPE_CHECKING:  # for annotations only: a layer above
    from .engine import Engine

__all__ = ["ORDERS", "check", "run"]

#: the orders the composition offers
ORDERS = (2, 4, 6)


def _schedule(order: int) -> list[tuple[str, float]]:
    """(part, fraction of the step) of one step: Strang's kick–drift–kick composed by
    the triple jump up to ``order``, adjacent kicks merged."""
    from mechanics.integrators._splitting import _merge, _triple_jump

    def strang(tau: float) -> list[tuple[str, float]]:
        return [("kick", tau / 2), ("drift", tau), ("kick", tau / 2)]

    # (the integrators' helpers compose and merge any labels; they are typed for their
    # axis numbers, these are the parts' names)
    step: Callable[[float], Any] = strang
    for p in range(2, order, 2):
        step = _triple_jump(step, p)
    return cast("list[tuple[str, float]]", _merge(step(1.0)))


def check(engine: Engine) -> None:
    """Refuse, naming scene.method, what a fixed-step splitting cannot run.

    It runs points and free rigid bodies only (no joint, tank or fixed body), without
    impacts or switching effects, under effects that all keep the energy and have a
    potential, and no rigid body with a zero principal moment (the module's
    Conventions, When).

    Parameters
    ----------
    engine : Engine
        The scene assembled (:class:`mechanics.scenes.engine.Engine`): its scene,
        layout, impacts and forces.

    Raises
    ------
    SceneError
        Where the scene is not one a splitting runs: the field ``scene.method`` and the
        reason.

    Examples
    --------
    A fall runs by a splitting; the same fall onto a floor is refused (a fixed step
    cannot locate the impact):

    >>> from mechanics.scenes.engine import Engine
    >>> from mechanics.scenes.spec import parse_scene
    >>> data = {"scene": {"name": "fall", "duration": 1.0, "method": "splitting"},
    ...         "bodies": [{"name": "ball", "shape": "point", "mass": 2.0,
    ...                     "initial": {"position": [0.0, 0.0, 4.0]}}],
    ...         "effects": [{"type": "gravity", "g": 8.0}]}
    >>> check(Engine(parse_scene(data))) is None
    True
    >>> floor = {"type": "impact", "body": "ball", "plane_point": [0.0, 0.0, 0.0],
    ...          "plane_normal": [0.0, 0.0, 1.0], "restitution": 0.5}
    >>> check(Engine(parse_scene({**data, "effects": [*data["effects"], floor]})))
    Traceback (most recent call last):
    ...
    mechanics.scenes.errors.SceneError: <scene>: scene.method: 'splitting': a fixed step \
cannot locate impacts or switches: use 'auto' or 'integrate'
    """
    scene, lay = engine.scene, engine.layout
    why = None
    if any(k not in ("point", "rigid") for k in lay.kinds):
        why = "it takes points and free rigid bodies only (no joint, tank or fixed body)"
    elif engine.impacts or engine.switching:
        why = "a fixed step cannot locate impacts or switches: use 'auto' or 'integrate'"
    else:
        for e in engine.forces:
            if not e.keeps("E") or not isinstance(e, HasPotential):
                why = f"the {e.type!r} effect is not conservative (no potential energy)"
                break
        for i in lay.rigid_bodies:
            if not np.all(lay.J[i] > 0):
                name = scene.bodies[i].name
                why = f"body {name!r} has a zero principal moment (no torque-free flow)"
    if why is not None:
        raise scene.error("scene.method", f"'splitting': {why}")


def run(engine: Engine, order: int, step: float | None) -> tuple[list[Segment], float]:
    """(segments, step used): the states at the samples, each interval a dense segment.

    Each sample interval is a segment whose dense function takes partial steps from its
    start; the step is ``step`` rounded down to divide the sample interval (the module's
    Conventions, The method).

    Parameters
    ----------
    engine : Engine
        The scene assembled (:class:`mechanics.scenes.engine.Engine`), one that
        :func:`check` passes.
    order : int
        The composition's order: 2 (Strang), 4 or 6 (Yoshida's triple jump).
    step : float or None
        The largest step, s, > 0; None: the sample interval.

    Returns
    -------
    segments : list[Segment]
        ``(t_a, t_b, dense)`` for each sample interval, in time order; ``dense`` is
        vectorised (:func:`~.trajectory.vectorized`) and gives the flat state(s).
    h : float
        The step used, s: the sample interval divided by ⌈interval / step⌉.

    Raises
    ------
    SceneError
        Where a rigid body turns within float64's reach of the separatrix, where the
        torque-free flow is not resolved (field ``scene.method``).

    Examples
    --------
    Under uniform gravity Strang's kick–drift–kick is exact: the fall z = 4 − 4 t²,
    v = −8 t, at the samples and between them (the state is r, v):

    >>> from mechanics.scenes.engine import Engine
    >>> from mechanics.scenes.spec import parse_scene
    >>> eng = Engine(parse_scene({"scene": {"name": "fall", "duration": 1.0, "samples": 3},
    ...     "bodies": [{"name": "ball", "shape": "point", "mass": 2.0,
    ...                 "initial": {"position": [0.0, 0.0, 4.0]}}],
    ...     "effects": [{"type": "gravity", "g": 8.0}]}))
    >>> segs, h = run(eng, 2, None)
    >>> h, segs[1][2](1.0).tolist(), segs[0][2](0.25).tolist()
    (0.5, [0.0, 0.0, 0.0, 0.0, 0.0, -8.0], [0.0, 0.0, 3.75, 0.0, 0.0, -2.0])
    """
    scene, lay = engine.scene, engine.layout
    t = np.linspace(0.0, scene.duration, scene.samples)
    gap = float(t[1] - t[0])
    k = max(1, math.ceil(gap / step)) if step is not None else 1
    h = gap / k
    sched = _schedule(order)
    rigid = list(lay.rigid_bodies)
    m = engine.m0[:, None]

    def advance(y: FloatArray, tau: float) -> FloatArray:
        r, v, L, R = (np.array(a) for a in lay.gather(y))
        for part, c in sched:
            if part == "kick":
                s = engine.snapshot(0.0, lay.pack(r, v, L, R))
                F, M = engine.loads(0.0, s)
                v += (c * tau) * F / m
                L += (c * tau) * M
            else:
                r += (c * tau) * v
                for i in rigid:
                    L[i], R[i] = _turn(engine, lay.J[i], L[i], R[i], c * tau)
        return lay.pack(r, v, L, R)

    ys = [engine.y0.copy()]
    for _ in range(len(t) - 1):
        y = ys[-1]
        for _ in range(k):
            y = advance(y, h)
        ys.append(y)

    def piece(t0: float, y0: FloatArray) -> Dense:
        @vectorized
        def at(tt: Times) -> FloatArray:
            scalar = np.ndim(tt) == 0
            out = []
            for x in np.atleast_1d(np.asarray(tt, dtype=float)):
                y, rest = y0, x - t0
                full = min(int(rest / h), k)  # whole steps, then the part of one
                for _ in range(full):
                    y = advance(y, h)
                rest -= full * h
                out.append(advance(y, rest) if rest > 0 else y)
            return out[0] if scalar else np.array(out)

        return at

    segs = [(float(t[j]), float(t[j + 1]), piece(float(t[j]), ys[j])) for j in range(len(t) - 1)]
    return segs, h


def _turn(
    engine: Engine, J: FloatArray, L: FloatArray, R: FloatArray, tau: float
) -> tuple[FloatArray, FloatArray]:
    """The exact torque-free flow of one rigid body over τ: (L_A, R_A_O)."""
    from mechanics.tops import FreeAsymmetricTop

    w = L / J
    if not w.any():
        return L, R
    try:
        top = FreeAsymmetricTop(J, w, R)
    except OutOfDomainError:
        raise engine.scene.error(
            "scene.method",
            "'splitting': a body turns within float64's reach of the separatrix, where the "
            "torque-free flow is not resolved: use 'integrate'",
        ) from None
    return J * top.omega(tau), top.attitude(tau)
