"""The integration loop: the project's adaptive Dormand–Prince 8(5,3) stepper
(:class:`mechanics.integrators.DOP853Stepper`, or its compiled twin
:class:`.compiled.CompiledStepper` where the model compiles:
:meth:`.forward.Forward.stepper`) at the scene's ``rtol``/``atol``, over the event
detectors.

After every step each contact feature's gap (:meth:`.collision.Collision.first_contact`)
each mode's switch function (:meth:`.modes.Modes.first_switch`) and each resting
contact's (:meth:`.support.Support.first_switch`) are searched along
the step's dense polynomial, so an event is found whatever the step size; the step is
cut at the earliest, the event is applied (:meth:`.impacts.Resolver.resolve`,
:meth:`.modes.Modes.switch`) and the integration restarts.  Switch times of the loads
(burn-out, the window of an applied load) are step boundaries, where a mode beyond its
limit switches at once.  The steps and the wall time are bounded (:mod:`.budget`).
"""

from __future__ import annotations

import itertools
from collections.abc import Iterable
from typing import TYPE_CHECKING, cast

import numpy as np

from . import budget
from .collision import Hit, StepFit
from .trajectory import Dense, Event, Segment, vectorized
from .vectors import FloatArray, Times

if TYPE_CHECKING:  # for annotations only
    from .collision import Collision
    from .effects.impact import Impact
    from .effects.thrust import Thrust
    from .forward import Forward
    from .impacts import Resolver
    from .model import Model
    from .modes import Modes
    from .support import Support

__all__ = ["HOW", "integrate", "rows"]

#: how an integrated run is described in its result
HOW = "integrated: DOP853 (mechanics.integrators), contacts located on each step's dense polynomial"


def integrate(
    model: Model,
    forward: Forward,
    collision: Collision,
    modes: Modes,
    resolver: Resolver,
    t_end: float,
    events: Iterable[Event] = (),
) -> tuple[list[Segment], list[Event]]:
    """Integrate the model from its initial state to ``t_end``: the segments and the events.

    DOP853 at the scene's ``rtol``/``atol`` over the event detectors (see the module's
    docstring); the switch times of the loads are step boundaries.

    Parameters
    ----------
    model : Model
        The compiled scene (:class:`mechanics.scenes.model.Model`), from ``y0`` at t = 0.
    forward : Forward
        Its forward dynamics (:class:`mechanics.scenes.forward.Forward`; its ``support``
        the resting contacts, or None); its ``phase`` is set per segment and reset to
        None at the end.
    collision : Collision
        Its contact search (:class:`mechanics.scenes.collision.Collision`).
    modes : Modes
        Its switching effects (:class:`mechanics.scenes.modes.Modes`).
    resolver : Resolver
        Its impact law (:class:`mechanics.scenes.impacts.Resolver`).
    t_end : float
        The end time, s (the scene's duration).
    events : Iterable[Event], optional
        The events at the start (the bodies resting there: :meth:`.support.Support.begin`).

    Returns
    -------
    segs : list[Segment]
        The steps ``(t0, t1, state_at)``, ``state_at`` the step's dense output (flat
        states, :func:`rows`), in time order.
    events : list[Event]
        ``events`` and those found (impacts, switches of modes and of resting contacts,
        burn-outs), sorted by time.

    Raises
    ------
    SceneError
        Where the estimated steps exceed the scene's ``max_steps`` or the run its
        ``max_seconds`` (a :class:`~mechanics.scenes.budget.BudgetError`), the step size
        stalls (``scene.rtol``), the impacts accumulate beyond :data:`.impacts.MAX_EVENTS`,
        a contact is found on the exit side, or a pair comes to a rest the model cannot
        treat; the message names the field and the time.

    Examples
    --------
    A point thrown at 1 m/s under g = 2 m/s²: after 1 s, x = 1 m, z = 5 − g/2 = 4 m,
    v_z = −2 m/s, to the integration's tolerance:

    >>> from mechanics.scenes.engine import Engine
    >>> from mechanics.scenes.spec import parse_scene
    >>> eng = Engine(parse_scene({"scene": {"name": "x", "duration": 1.0, "method": "integrate"},
    ...     "bodies": [{"name": "ball", "shape": "point", "mass": 2.0,
    ...                 "initial": {"position": [0.0, 0.0, 5.0], "velocity": [1.0, 0.0, 0.0]}}],
    ...     "effects": [{"type": "gravity", "g": 2.0}]}))
    >>> segs, events = integrate(eng.model, eng.forward, eng.collision, eng.modes,
    ...                          eng.resolver, 1.0)
    >>> segs[-1][1], events, bool(np.allclose(segs[-1][2](1.0), [1.0, 0.0, 4.0, 1.0, 0.0, -2.0]))
    (1.0, [], True)
    """
    from mechanics.errors import StepSizeError

    s = model.scene
    collision.reach.clear()  # a run starts with no sizes, releases or switches seen
    collision.released.clear()
    collision.held.clear()
    modes.switched.clear()
    switches = sorted({x for e in model.forces for x in e.switch_times() if 0 < x < t_end})
    support = forward.support
    segs: list[Segment]
    segs, events = [], list(events)
    t, y = 0.0, model.y0.copy()
    rate = budget.fastest_rate(s, model.w0)
    budget.check_steps(
        s,
        budget.step_estimate(s, model.w0),
        f"{budget.STEPS_PER_RADIAN:g} per radian of the fastest rate {rate:.3g} 1/s at "
        f"rtol 1e-12, over {t_end:g} s",
    )
    clock = budget.Clock(s)
    for start, stop in itertools.pairwise([0.0, *switches, t_end]):
        forward.phase = 0.5 * (start + stop)
        if start > 0:  # a load switched on or off: a mode may have to switch with it
            y = modes.switch_now(t, y, events)
            if support is not None and support.rests:
                y = support.switch(t, y, events)
        while t < stop:
            solver = forward.stepper(t, y, stop, s.rtol, s.atol)
            hit: Hit | None = None
            while solver.status == "running" and hit is None:
                clock.step(solver.t)
                try:
                    solver.step()
                except StepSizeError as exc:
                    raise s.error(
                        "scene.rtol",
                        f"the integration stalled at t = {solver.t:.17g} s (a singular "
                        f"force, e.g. bodies meeting under newton_gravity?): {exc}",
                    ) from None
                t_old = cast(float, solver.t_old)  # (set: a step was taken)
                fit = StepFit(solver.dense_output(), t_old, solver.t)
                hit = collision.first_contact(fit)
                sw = modes.first_switch(fit)
                if sw is not None and (hit is None or sw.t < hit.t):
                    hit = sw
                sp = support.first_switch(fit) if support is not None else None
                if sp is not None and (hit is None or sp.t < hit.t):
                    hit = sp
                segs.append((t_old, solver.t if hit is None else hit.t, rows(fit.dense)))
            if hit is None:
                t, y = float(solver.t), np.array(solver.y, dtype=float)
                break
            t = hit.t
            y = np.asarray(fit.dense(t), dtype=float)
            if hit.effect is support:  # a resting contact lets go, sticks or slips
                y = support.switch(t, y, events)
                continue
            if hit.feature is None:  # an effect switches its mode (stick and slip)
                y = modes.switch(t, y, hit.effect, events)
                continue
            if hit.rest:  # touching with no approach speed and falling in: it rests
                press = resolver.pressed(hit.effect, hit.feature, t, y)
                last = _last_impact(events, hit.effect)
                # (a contact falls in to rest only where there is a support: Collision)
                y = cast("Support", support).rest(
                    t, y, hit.effect, hit.feature, last, press, events
                )
                continue
            # the search found it within its rounding, relative to the largest size the
            # features' positions have had (Collision.reach): the gap's scale is that
            a = model.impacts.index(hit.effect)
            reach = max(v for (i, _), v in collision.reach.items() if i == a)
            y = resolver.resolve(t, y, hit.effect, hit.feature, events, reach)
        for e in model.forces:
            burn = cast("Thrust", e)  # (its fields read where its type is "thrust")
            if e.type == "thrust" and burn.burn_out == stop and stop < t_end:
                events.append(Event(stop, "burn_out", {"body": model.names[burn.i]}))
    forward.phase = None
    # a rest is dated at its accumulation time, a little after the impact that began it
    events.sort(key=lambda ev: ev.t)
    return segs, events


def _last_impact(events: list[Event], imp: Impact) -> dict[str, float]:
    """The last impact of the pair ``imp`` (its time and rebound: where the bounces
    that accumulate began their last hop), or {} if none."""
    for ev in reversed(events):
        if ev.kind == "impact" and imp.label in ev.detail.get("feature", ""):
            return {"t": ev.t, "normal_speed_after": ev.detail["normal_speed_after"]}
    return {}


def rows(dense: Dense) -> Dense:
    """A step's dense output in scipy's convention as a vectorised function of rows.

    Scipy's convention is (size, k) for k times; the function returned gives (k, size),
    and (size,) for one time, and is marked vectorised (:func:`.trajectory.vectorized`).

    Parameters
    ----------
    dense : Dense
        The step's dense output: time(s) t (s) to states of shape (size, k), or (size,)
        for one time.

    Returns
    -------
    Dense
        The function of the time(s) returning states of shape (k, size), or (size,).

    Examples
    --------
    >>> at = rows(lambda t: np.array([np.asarray(t), 2.0 * np.asarray(t)]))
    >>> at(np.array([1.0, 2.0])).tolist(), at(3.0).tolist(), at.vectorized
    ([[1.0, 2.0], [2.0, 4.0]], [3.0, 6.0], True)
    """

    @vectorized
    def at(t: Times) -> FloatArray:
        return np.asarray(dense(t)).T

    return at
