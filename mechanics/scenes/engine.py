"""The one engine of every scene: it assembles exactly the listed effects, uses the exact
flow where their set has one, integrates otherwise, and finds every contact and switch.

The engine orchestrates its rooms, each one job:

- :mod:`.model`: the scene compiled once (the bodies' layout in the state, the effects
  by what they contribute, the initial state) and its checks as a whole;
- :mod:`.forward`: the state seen as bodies, the loads, the state's rate, the
  accelerations and the joints' reactions; :mod:`.compiled` the same rate, reactions and
  DOP853 steps compiled (numba, :mod:`._kernels`) for the models whose bodies and loads
  all compile, the Python path their reference;
- :mod:`.flows`: the exact flows, each provider saying when it applies;
- :mod:`.collision`: each contact feature's gap along a step, the first contact;
- :mod:`.impacts`: the impact law at a contact, the simultaneous ones after it;
- :mod:`.support`: resting contact, the support forces of bodies resting on planes;
- :mod:`.modes`: the effects that switch (stick and slip, a tank that empties);
- :mod:`.integrate`: the adaptive DOP853 loop over those event detectors;
- :mod:`.report`: the result (series, invariants, their scales);
- :mod:`.splitting`: the fixed-step splitting, for ``method = "splitting"``.

Conventions
-----------
- **State**: :mod:`mechanics.scenes.state` (points, rigid bodies with L_A and ^A R^O,
  pinned bodies with L_C and ^A R^O, guided bodies with the coordinates (q, q̇) of
  their joint's :class:`~mechanics.scenes.state.Guide`, tanks, fixed bodies).  A rigid
  body starts with the attitude ^A R^O = R3(φ) R1(θ) R3(ψ) of its initial Euler angles
  ``psi``, ``theta``, ``phi`` (z-x-z, default 0: the body axes along the space axes)
  and the angular velocity ``omega`` in body components (a pinned body: or the Euler
  rates, by (2.69)).
- **Effects**: :mod:`mechanics.scenes.effects`; the right-hand side sums the
  :meth:`~mechanics.scenes.effects.base.Effect.loads` of the listed effects and
  nothing else (no default gravity, no damping, no position correction).
- **Exact flows** (``method = "auto"`` or ``"exact"``): see :mod:`.flows`.
- **Integration** otherwise (or ``method = "integrate"``): see :mod:`.integrate`.
- **Contacts**: a contact is a gap reaching zero while closing, resolved by the
  Chapter 6 impulse (:mod:`mechanics.scenes.effects.impact`); simultaneous contacts as
  :mod:`.impacts` says.  A body on a plane at rest at t = 0, or whose impacts
  accumulate (or e = 0), rests on it with its support force (:mod:`.support`) until
  that force would pull.  A contact found on the exit side, a pair interpenetrating at
  a step's start, or a rest the model cannot treat (two bodies on each other,
  Painlevé's paradox) stops the run with a
  :class:`~mechanics.scenes.errors.SceneError` naming the pair and the time.
- **Series and invariants**: see :mod:`.report`.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from . import budget, flows, model
from .collision import Collision, check_initial_overlap
from .effects import Snapshot
from .forward import Forward
from .impacts import Resolver
from .integrate import HOW, integrate
from .modes import Modes
from .report import finish
from .support import Support
from .trajectory import Event, Segment, Trajectory
from .vectors import FloatArray, Times

if TYPE_CHECKING:  # for annotations only: a layer above
    from .spec import Scene

__all__ = ["Engine", "validate"]


def validate(scene: Scene) -> None:
    """Check a scene as a whole (:func:`.model.check`) and, with impacts, its overlaps at t = 0.

    With impacts, no two features of a listed pair may overlap at t = 0
    (:func:`.collision.check_initial_overlap`).  :func:`.spec.parse_scene` calls it
    (through :func:`.simulate.validate`) on every scene it returns.

    Parameters
    ----------
    scene : Scene
        The parsed scene (:class:`mechanics.scenes.spec.Scene`; each field already checked
        by the parser).

    Raises
    ------
    SceneError
        Where the combination is refused (:func:`.model.check`: two joints on one body, an
        initial key the body does not take, a spin about a zero principal moment, ...), a
        pair is listed twice, or a pair overlaps at t = 0; the message names the field.

    Examples
    --------
    A point has no attitude: the scene that gives one an initial spin is refused.

    >>> from dataclasses import replace
    >>> from mechanics.scenes.spec import parse_scene
    >>> sc = parse_scene({"scene": {"name": "x", "duration": 1.0},
    ...                   "bodies": [{"name": "ball", "shape": "point", "mass": 2.0}]})
    >>> validate(sc) is None
    True
    >>> validate(replace(sc, bodies=(replace(sc.bodies[0], initial={"omega": [1.0, 0.0, 0.0]}),)))
    Traceback (most recent call last):
    ...
    mechanics.scenes.errors.SceneError: <scene>: bodies[0].initial.omega: a point has no \
attitude and no rotation
    """
    model.check(scene)
    if scene.effects_of("impact"):  # (the model and its forward dynamics suffice)
        md = model.Model(scene)
        check_initial_overlap(md, Forward(md))


class Engine:
    """A scene, assembled from its listed effects: the model and the rooms that run it.

    :meth:`run` uses the exact flow where the listed effects have one (:mod:`.flows`,
    ``method = "auto"`` or ``"exact"``), else integrates (:mod:`.integrate`) or splits
    (``method = "splitting"``), and assembles the result (:mod:`.report`).

    Parameters
    ----------
    scene : Scene
        The parsed and validated scene (:func:`mechanics.scenes.spec.parse_scene`).

    Raises
    ------
    SceneError
        Where two impact effects list the same pair (the same two bodies, or one body and
        the same plane), in building the :class:`~.model.Model`.
    ZeroDivisionError
        Where a rolling body's r² underflows to 0 (a radius of 1e-320 m, which the parser
        accepts): its M_eff = m + J/r² (3.79); :func:`.simulate.simulate` reports it as a
        SceneError.

    Examples
    --------
    A point dropped from rest under g = 2 m/s² falls g t²/2 = 1 m in 1 s:

    >>> from mechanics.scenes.spec import parse_scene
    >>> eng = Engine(parse_scene({"scene": {"name": "drop", "duration": 1.0},
    ...     "bodies": [{"name": "ball", "shape": "point", "mass": 2.0,
    ...                 "initial": {"position": [0.0, 0.0, 5.0]}}],
    ...     "effects": [{"type": "gravity", "g": 2.0}]}))
    >>> eng.exact_flow()
    'exact: free flight under uniform gravity'
    >>> tr = eng.run()
    >>> float(tr.series["z"][-1]), 5.0 - 2.0 * 1.0**2 / 2
    (4.0, 4.0)
    """

    def __init__(self, scene: Scene) -> None:
        md = self.model = model.Model(scene)
        self.forward = Forward(md)
        self.support = Support(md, self.forward)
        self.forward.support = self.support
        self.resolver = Resolver(md, self.forward, self.support)
        self.collision = Collision(md, self.forward, self.resolver)
        self.modes = Modes(md, self.forward)
        #: the exact flow found by :meth:`exact_flow` (None: none, or not asked yet)
        self.flow: flows.Flow | None = None
        # the model's fields most read from an engine (by :mod:`.splitting`,
        # :mod:`.derived` and the tests)
        self.scene, self.layout, self.n, self.names = md.scene, md.layout, md.n, md.names
        self.effects, self.impacts, self.forces = md.effects, md.impacts, md.forces
        self.switching, self.rigid = md.switching, md.rigid
        self.m0, self.y0, self.w0, self.R0 = md.m0, md.y0, md.w0, md.R0

    # ------------------------------------------------- the forward dynamics
    def masses(self, t: Times) -> FloatArray:
        return self.forward.masses(t)

    def snapshot(self, t: Times, y: npt.ArrayLike, *, copy: bool = True) -> Snapshot:
        """The bodies at time(s) t from state(s) y (:meth:`.forward.Forward.snapshot`)."""
        return self.forward.snapshot(t, y, copy=copy)

    def pack(self, s: Snapshot) -> FloatArray:
        return self.forward.pack(s)

    def loads(self, t: float, s: Snapshot) -> tuple[FloatArray, FloatArray]:
        return self.forward.loads(t, s)

    def rhs(self, t: float, y: FloatArray) -> FloatArray:
        return self.forward.rhs(t, y)

    # ------------------------------------------------------------------ run
    def exact_flow(self) -> str | None:
        """How the scene's exact flow is computed, or None where it has none here."""
        self.flow = flows.find(self.model, self.forward, self.resolver)
        return None if self.flow is None else self.flow.how

    def run(self) -> Trajectory:
        """Run the scene over its duration: its trajectory (samples, events, gaps)."""
        s = self.scene
        self.model.carried[:] = 0.0  # no impulse yet (see Context.carried)
        t = np.linspace(0.0, s.duration, s.samples)
        self.modes.begin()
        if s.method == "splitting":
            return self._split(t)
        exact = self.exact_flow()
        if s.method == "exact" and exact is None:
            kinds = sorted(self.model.kinds)
            raise s.error(
                "scene.method",
                f"'exact' requested but the effects {kinds} of this scene have no "
                "exact flow here; use 'auto' or 'integrate'",
            )
        if self.flow is not None and s.method != "integrate":
            start = self.support.begin()
            try:
                segs, events = self.flow.run()
            except flows.NotExact as exc:  # found on the way (a body comes to rest)
                if s.method == "exact":
                    raise s.error("scene.method", f"'exact' requested but {exc}") from None
            else:
                return self._finish(
                    t, segs, sorted(start + events, key=lambda e: e.t), self.flow.how
                )
        start = self.support.begin()
        segs, events = integrate(
            self.model, self.forward, self.collision, self.modes, self.resolver, s.duration, start
        )
        return self._finish(t, segs, events, f"{HOW}; {self.forward.path()}")

    def _finish(
        self, t: FloatArray, segs: list[Segment], events: list[Event], how: str
    ) -> Trajectory:
        return finish(self.model, self.forward, t, segs, events, how)

    def _split(self, t: FloatArray) -> Trajectory:
        """The splitting (:mod:`.splitting`), run again at half the step: the energy's
        drift must shrink by the method's order."""
        from . import splitting

        s = self.scene
        splitting.check(self)
        gap = s.duration / (s.samples - 1)  # splitting.run's steps: k per sample interval
        k = max(1, math.ceil(gap / s.step)) if s.step is not None else 1
        # the run at the step and at half of it: three times its steps
        budget.check_steps(
            s, 3 * k * (s.samples - 1), f"a splitting at step {gap / k:.3g} s, and at half of it"
        )
        segs, h = splitting.run(self, s.order, s.step)
        how = (
            f"integrated: splitting of order {s.order} (kicks of the loads, exact free "
            f"flight and torque-free rotation), step {h:.6g} s"
        )
        traj = self._finish(t, segs, [], how)
        half, _ = splitting.run(self, s.order, 0.5 * h)
        E = self._finish(t, half, [], how).series["E"]
        traj.splitting = {"order": s.order, "step": h, "E_drift_half": float(np.ptp(E))}
        return traj
