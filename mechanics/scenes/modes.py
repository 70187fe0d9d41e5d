"""Modes: the effects that switch (stick and slip, a tank that empties), located on each
step like a contact.

An effect with modes has a switch function (see :mod:`.effects.base`); its next switch
is where the function falls through zero.  :meth:`Modes.first_switch` fits it along a
step's dense output at the Chebyshev nodes and searches the fit as a gap is searched
(:func:`contacts.first_downward_crossing`, refined on the function itself); a value
within :data:`SWITCH_ROUNDING` × its terms' size at the step's start is zero.  At a step
boundary where a load switches on or off, :meth:`Modes.switch_now` switches at once
every mode already beyond its limit (a push that starts makes a rolling body slip).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, cast

import numpy as np
import numpy.typing as npt

from . import contacts, impacts
from .collision import Hit, StepFit
from .trajectory import EPS, Event
from .vectors import FloatArray

if TYPE_CHECKING:  # for annotations only
    from .effects import Effect
    from .effects.capabilities import HasModes
    from .forward import Forward
    from .model import Model

__all__ = ["SWITCH_ROUNDING", "Modes"]

#: a switch function (stick and slip) within this multiple of eps × the size of its
#: terms at a step's start is zero: the rounding of the switch just made there
SWITCH_ROUNDING = 64 * EPS


class Modes:
    """The switching effects of a :class:`~mechanics.scenes.model.Model`.

    Its constructor only stores the model and its forward dynamics; :meth:`begin` lets
    the effects choose their initial modes.

    Parameters
    ----------
    model : Model
        The compiled scene (:class:`mechanics.scenes.model.Model`); its ``switching``
        effects are the ones followed.
    forward : Forward
        The model's forward dynamics (:class:`mechanics.scenes.forward.Forward`), whose
        loads the switch functions read.

    Examples
    --------
    A ball launched at 3 m/s without spin slides forward (mode +1); the switch function
    of Coulomb friction while it slides is the slip speed v − ω r:

    >>> from mechanics.scenes.engine import Engine
    >>> from mechanics.scenes.spec import parse_scene
    >>> eng = Engine(parse_scene({"scene": {"name": "x", "duration": 1.0},
    ...     "bodies": [{"name": "ball", "shape": "solid_sphere", "mass": 1.0, "radius": 0.5,
    ...                 "initial": {"speed": 3.0, "spin": 0.0}}],
    ...     "effects": [{"type": "gravity", "g": 10.0},
    ...                 {"type": "coulomb_friction", "body": "ball", "mu": 0.5}]}))
    >>> modes = Modes(eng.model, eng.forward)
    >>> modes.begin()
    >>> friction = eng.model.switching[0]
    >>> friction.mode, modes.value(friction, 0.0, [0.0, 0.0, 3.0, 2.0])[0], 3.0 - 2.0 * 0.5
    (1.0, 2.0, 2.0)
    """

    def __init__(self, model: Model, forward: Forward) -> None:
        self.model = model
        self.forward = forward
        #: effect -> the time of its last switch
        self.switched: dict[Effect, float] = {}

    def begin(self) -> None:
        """Let the effects with modes choose theirs from the initial state."""
        md, fwd = self.model, self.forward
        if md.switching:
            s = fwd.snapshot(0.0, md.y0)
            for e in md.switching:
                e.begin(0.0, s, fwd.loads_before(0.0, s, e))

    def switch(self, t: float, y: FloatArray, effect: Any, events: list[Event]) -> FloatArray:
        """Switch ``effect``'s mode at (t, y); record the event; return the new state.
        (``effect``: one of :attr:`~.model.Model.switching`, an effect with modes.)"""
        fwd = self.forward
        sn = fwd.snapshot(t, y)
        sn.phase = cast(float, fwd.phase)  # (set: inside an integration segment)
        events.append(effect.switch(t, sn, fwd.loads_before(t, sn, effect)))
        self.switched[effect] = t
        if len(events) > impacts.MAX_EVENTS:  # (read here: a test may lower it)
            raise impacts.zeno(self.model.scene, t, effect.where)
        return fwd.pack(sn)

    def switch_now(self, t: float, y: FloatArray, events: list[Event]) -> FloatArray:
        """At a switch time of the loads: switch every mode whose switch function is
        below zero beyond its rounding (a push that starts makes a rolling body slip)."""
        fwd = self.forward
        for e in self.model.switching:
            g, size = self.value(e, t, y)
            if g < -SWITCH_ROUNDING * size:
                sn = fwd.snapshot(t, y)
                sn.phase = cast(float, fwd.phase)  # (set: inside an integration segment)
                events.append(e.switch(t, sn, fwd.loads_before(t, sn, e)))
                self.switched[e] = t
                y = fwd.pack(sn)
        return y

    def value(self, e: HasModes, t: float, y: npt.ArrayLike) -> tuple[float, float]:
        """The switch function of ``e`` at (t, y), and the size of its terms."""
        fwd = self.forward
        s = fwd.snapshot(t, np.asarray(y, dtype=float))
        if fwd.phase is not None:  # the loads of the segment being integrated
            s.phase = fwd.phase
        return e.switch_function(t, s, fwd.loads_before(t, s, e))

    def first_switch(self, fit: StepFit) -> Hit | None:
        """The earliest switch of an effect's mode within one step (a :class:`Hit` with
        no feature), or None (see the module's docstring)."""
        t_a, t_b, dense = fit.t_a, fit.t_b, fit.dense
        best: Hit | None = None
        for e in self.model.switching if t_b > t_a else ():
            sizes: list[float] = []

            def g(tt: FloatArray, e: HasModes = e, sizes: list[float] = sizes) -> FloatArray:
                vals = [self.value(e, float(x), dense(float(x))) for x in tt]
                sizes.extend(size for _, size in vals)
                return np.array([[v] for v, _ in vals])

            def refine(xx: float, e: HasModes = e) -> float:
                tt = fit.time(xx)
                return self.value(e, tt, dense(tt))[0]

            coef = contacts.chebyshev_fit(g, t_a, t_b, ends=True)[:, 0]
            # just switched here: the new mode starts at its limit (a slip that starts
            # from zero speed), so only a fall beyond the rounding switches it back
            after = -1.0 if self.switched.get(e) == t_a else None
            try:
                xc = contacts.first_downward_crossing(
                    coef, start_tol=SWITCH_ROUNDING * max(sizes), refine=refine, after=after
                )
            except contacts.ContactError as exc:  # pragma: no cover - a switch was missed
                raise self.model.scene.error(
                    e.where, f"a switch of its mode was missed before t = {t_a:.17g} s ({exc})"
                ) from None
            if xc is not None:
                tc = t_a if xc == -1.0 else min(fit.time(xc), t_b)
                if best is None or tc < best.t:
                    best = Hit(tc, e)
        return best
