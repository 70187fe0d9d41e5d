"""Coulomb friction of a round body on a plane: it slides, and rolls once the slip
vanishes where static friction suffices (chapter 3, the sliding ball).

Conventions
-----------
- **The joint.**  The body is guided on the incline of slope ``angle`` α
  (:func:`~mechanics.scenes.effects.rolling.slope_frame`: normal n, down-slope t̂,
  a = n × t̂ = e_y) with two coordinates: the distance s down the slope (G at
  r n + s t̂) and the angle θ its ``body_axis`` (default z, along a) has turned; the
  spin is ω = θ̇ and the slip, the velocity of the contact point along t̂, is
  ṡ − r θ̇.  Initial keys ``distance``, ``speed``, ``spin``.  Series s, v, omega, slip.
- **The normal force** N = −n·Σ F of the other loads (the plane holds G at height r);
  N ≤ 0 (the body would leave the plane: no lift-off is modelled) stops the run with
  a :class:`~mechanics.scenes.errors.SceneError`.
- **The friction** F t̂ acts at the contact point −r n.  *Slipping* (mode σ = ±1, the
  sign of the slip): F = −μ N σ.  *Rolling* (stick): F is what keeps the slip zero,
  F = (m r Q_θ − J Q_s)/(J + m r²) with the other loads' generalised forces Q_s along
  t̂ and Q_θ about a, J the moment about ``body_axis``; it holds while |F| ≤ μ N.
- **Switches** (events, located on each step's dense output): slipping, the slip
  reaches zero: ``rolling`` when |F_stick| ≤ μ N there, else ``slip_zero`` and it
  slips on the other way, in the direction the loads drive it (σ = −sign F_stick);
  rolling, |F_stick| reaches μ N: ``slip``.  At the start with zero slip the same rule
  decides.  The state is projected onto zero slip (θ̇ = ṡ/r) at a switch to rolling.
- **Exact flow** under uniform gravity alone: constant accelerations in each phase,
  the switch time solved exactly.
- **Invariants**: the energy from the last switch to rolling on (stick friction does
  no work); on a level plane with only gravity, the angular momentum about the contact
  line, m r v + J ω (friction and the normal force pass through that line, the weight
  through G above it).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar, cast

import numpy as np

from ..state import Guide, body_inertia, turned
from ..trajectory import Event
from .base import (
    Context,
    Effect,
    ExactCoords,
    FloatArray,
    Loads,
    SceneLike,
    Schema,
    Snapshot,
    SpecLike,
    Times,
    check_joint_body,
    register,
)
from .capabilities import GuidesBody, HasModes
from .rolling import check_round_on_slope, slope_frame

if TYPE_CHECKING:
    from .gravity import Gravity

__all__ = ["CoulombFriction", "Slide"]


@dataclass(frozen=True, eq=False)
class Slide(Guide):
    """A round body of radius r on the incline (n, t̂, a) with friction μ: q = (s, θ).

    G is at r n + s t̂; the body has turned by θ about a; the slip is ṡ − r θ̇.  Made by
    :meth:`CoulombFriction.make_guide`.

    Parameters
    ----------
    n : ndarray, shape (3,)
        The incline's outward unit normal (:func:`~.rolling.slope_frame`).
    t : ndarray, shape (3,)
        The unit down-slope direction t̂.
    a : ndarray, shape (3,)
        The horizontal a = n × t̂, the axis the body turns about.
    r : float
        The body's radius, m (> 0).
    m : float
        Its mass, kg.
    k : int
        The body axis (0, 1, 2: x, y, z) along a.
    M : ndarray, shape (2,)
        The inertias of s and θ: (m in kg, J about the body axis in kg m²).
    mu : float
        The friction coefficient μ (> 0).

    Examples
    --------
    The stick force F keeps the slip zero: s̈ = (Q_s + F)/m equals r θ̈ = −r² F/J:

    >>> from mechanics.scenes.spec import parse_scene
    >>> cyl = {"name": "cyl", "shape": "cylinder", "mass": 2.0, "radius": 0.5, "height": 0.2}
    >>> sc = parse_scene({"scene": {"name": "x", "duration": 1.0}, "bodies": [cyl],
    ...     "effects": [{"type": "gravity", "g": 9.75},
    ...                 {"type": "coulomb_friction", "body": "cyl", "mu": 0.25}]})
    >>> slide = CoulombFriction.make_guide(sc.effects[1], sc, np.array([0.0, 0.0, -9.75]))
    >>> F = float(slide.stick_force(6.0, 0.0))
    >>> slide.M.tolist(), F, (6.0 + F) / 2.0, -(0.5**2) * F / 0.25
    ([2.0, 0.25], -2.0, 2.0, 2.0)
    """

    n: FloatArray
    t: FloatArray
    a: FloatArray
    r: float
    m: float
    k: int
    M: FloatArray  # (m, J)
    mu: float
    nq = 2

    def _get_W(self) -> FloatArray:
        return np.stack([np.zeros(3), self.a])

    W = property(_get_W)

    def place(self, q: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        s, th = q[..., 0], q[..., 1]
        G = self.r * self.n + s[..., None] * self.t
        E = np.zeros((*s.shape, 2, 3))
        E[..., 0, :] = self.t
        return G, E, turned(self.a, self.n, self.k, th)

    def start(self, initial: Mapping[str, Any]) -> tuple[FloatArray, FloatArray]:
        return (
            np.array([float(initial.get("distance", 0.0)), 0.0]),
            np.array([float(initial.get("speed", 0.0)), float(initial.get("spin", 0.0))]),
        )

    def series(self, q: FloatArray, qd: FloatArray) -> dict[str, FloatArray]:
        v, w = qd[..., 0], qd[..., 1]
        return {"s": q[..., 0], "v": v, "omega": w, "slip": v - w * self.r}

    def stick_force(self, Q_s: float, Q_th: float) -> float:
        """The friction that keeps the slip zero against the generalised forces Q_s, Q_θ."""
        m, J = self.M
        F: float = (m * self.r * Q_th - J * Q_s) / (J + m * self.r * self.r)
        return F

    def exact(
        self,
        effects: Sequence[Effect],
        m: float,
        q0: FloatArray,
        qd0: FloatArray,
        duration: float,
    ) -> ExactCoords | None:
        """Under uniform gravity alone the loads are constant: each phase has constant
        accelerations, and the slip, linear in t, vanishes at a time solved exactly."""
        if not effects or any(e.type != "gravity" for e in effects):
            return None
        g = cast("FloatArray", sum(cast("Gravity", e).vector for e in effects))
        N, D = -m * float(g @ self.n), m * float(g @ self.t)
        if not N > 0:
            return None  # the engine's run reports the lift-off
        mJ = self.M
        F_stick = self.stick_force(D, 0.0)

        def acc(mode: float) -> FloatArray:  # (s̈, θ̈) with friction F: Q_s = D + F, Q_θ = −r F
            F = F_stick if mode == 0 else -self.mu * N * mode
            return np.array([(D + F) / mJ[0], -self.r * F / mJ[1]])

        def decide() -> float:  # at zero slip: roll, or slip the way the loads drive
            return 0 if abs(F_stick) <= self.mu * N else -math.copysign(1.0, F_stick)

        slip0 = float(qd0[0] - self.r * qd0[1])
        mode = decide() if slip0 == 0 else math.copysign(1.0, slip0)
        phases = [(0.0, np.array(q0, float), np.array(qd0, float), acc(mode))]
        events: list[Event] = []
        if mode != 0:
            a = acc(mode)
            rate = a[0] - self.r * a[1]
            # the slip falls toward zero where its rate opposes it (signs compared, not
            # their product: that underflows to −0 for a subnormal slip, found by
            # hypothesis, and the slip then ran on through zero with the friction unturned)
            falls = rate != 0 and (rate < 0) != (slip0 < 0)
            ts = -slip0 / rate if falls else math.inf
            if ts <= duration:
                q1 = q0 + qd0 * ts + 0.5 * a * ts * ts
                qd1 = qd0 + a * ts
                qd1[1] = qd1[0] / self.r  # the slip is zero exactly at the switch
                mode = decide()
                events.append(_event(ts, mode, float(qd1[0])))
                phases.append((ts, q1, qd1, acc(mode)))
        starts = np.array([p[0] for p in phases])

        def f(t: Times) -> tuple[FloatArray, FloatArray]:
            t = np.asarray(t, dtype=float)
            k = np.maximum(np.searchsorted(starts, t, side="right") - 1, 0)
            t0 = starts[k][..., None]
            Q0, QD0, A = (np.stack([p[j] for p in phases])[k] for j in (1, 2, 3))
            tau = t[..., None] - t0
            return Q0 + QD0 * tau + 0.5 * A * tau * tau, QD0 + A * tau

        return "exact: constant accelerations in each phase, the switch solved exactly", f, events


def _event(t: float, mode: float, speed: float) -> Event:
    kind = "rolling" if mode == 0 else "slip_zero"
    return Event(t, kind, {"speed": speed})


@register
class CoulombFriction(Effect, HasModes, GuidesBody):
    """Coulomb friction μN at the contact of a round body with a plane of slope α.

    While the contact point slips, the friction opposes the slip; when the slip
    velocity reaches zero (an event) the body rolls if static friction suffices.

    Parameters
    ----------
    spec : SpecLike
        The listed effect; its fields: ``body`` (round), ``mu`` μ (> 0), ``angle`` (the
        slope α, rad, in [0, π/2); default 0) and ``body_axis`` (``"x"``, ``"y"`` or
        ``"z"``, the axis it turns about; default ``"z"``).
    ctx : Context or None, optional
        The scene's context (the body's index, its slide and the scene's other effects;
        None: an effect built for its fields alone).

    Raises
    ------
    KeyError
        If a required field is missing from ``spec.fields`` (the parser requires it), or if
        ``body`` is not a body of ``ctx``.

    Examples
    --------
    A cylinder sent sliding without spin on a level floor rolls from the speed at which
    m r v + J ω about the contact line (kept) is m r v0: v0/(1 + J/(m r²)):

    >>> from mechanics.scenes.engine import Engine
    >>> from mechanics.scenes.spec import parse_scene
    >>> cyl = {"name": "cyl", "shape": "cylinder", "mass": 2.0, "radius": 0.5, "height": 0.2,
    ...        "initial": {"speed": 3.0}}
    >>> eng = Engine(parse_scene({"scene": {"name": "x", "duration": 2.0}, "bodies": [cyl],
    ...     "effects": [{"type": "gravity", "g": 9.75},
    ...                 {"type": "coulomb_friction", "body": "cyl", "mu": 0.25}]}))
    >>> first = eng.run().events[0]
    >>> first.kind, first.detail["speed"], 3.0 / (1 + 0.25 / (2.0 * 0.5**2))
    ('rolling', 2.0, 2.0)
    """

    type = "coulomb_friction"
    dissipative = True
    #: it reads the other loads (the normal force, the force that keeps it rolling)
    after_loads = True
    schema: ClassVar[Schema] = {
        "body": ("body", True),
        "mu": ("positive", True),
        "angle": ("number", False),
        "body_axis": ("axis_name", False),
    }
    units: ClassVar[dict[str, str]] = {"body": "", "mu": "1", "angle": "rad", "body_axis": ""}
    example: ClassVar[dict[str, Any]] = {"type": "coulomb_friction", "body": "ball", "mu": 0.2}

    @classmethod
    def check(cls, spec: SpecLike, scene: SceneLike, index: dict[str, int]) -> None:
        check_round_on_slope(spec, scene)
        if not scene.effects_of("gravity"):
            raise scene.error(
                f"{spec.where}.type",
                "coulomb_friction on a plane needs a gravity effect to press the body on it "
                "(the normal force); none is listed",
            )
        check_joint_body(
            spec, scene, index, what="it cannot slide", keys=("distance", "speed", "spin")
        )

    @classmethod
    def make_guide(cls, spec: SpecLike, scene: SceneLike, g_vector: FloatArray) -> Slide:
        f, b = spec.fields, scene.body(spec.fields["body"])
        k = "xyz".index(f.get("body_axis", "z"))
        n, t, a = slope_frame(float(f.get("angle", 0.0)))
        M = np.array([float(b.mass), float(body_inertia(b)[k])])
        return Slide(n, t, a, float(b.dims["radius"]), float(b.mass), k, M, float(f["mu"]))

    def __init__(self, spec: SpecLike, ctx: Context | None = None) -> None:
        super().__init__(spec, ctx)
        self.mu = float(self.fields["mu"])
        self.alpha = float(self.fields.get("angle", 0.0))
        self.i = ctx.index[self.fields["body"]] if ctx is not None else 0
        #: the body's guide: a Slide (:meth:`make_guide` made it)
        self.guide = cast("Slide | None", ctx.guides.get(self.i) if ctx is not None else None)
        #: 0 rolling, ±1 slipping that way; set by :meth:`begin` and :meth:`switch`
        self.mode = 0.0
        self.mode0 = 0.0
        others = {e.type for e in ctx.scene.effects} if ctx is not None else set()
        self._flat = self.alpha == 0 and others <= {"gravity", self.type}

    def _slide(self) -> Slide:
        """The body's slide: the engine builds the effect with its context, whose guides
        hold it (:meth:`make_guide`); only an effect built without one has none."""
        gd = self.guide
        assert gd is not None, "coulomb_friction's motion needs its slide (built with a ctx)"
        return gd

    # ------------------------------------------------------------------ the forces
    def _parts(self, s: Snapshot, out: Loads) -> tuple[float, float, float]:
        """(N, F_stick, Q scale) from the other loads already in ``out``."""
        i, gd = self.i, self._slide()
        F_o = out.F[i]
        N = -float(F_o @ gd.n)
        Q_s = float(F_o @ gd.t)
        Q_th = float(gd.a @ s.to_space(i, out.M_A[i]))
        return N, gd.stick_force(Q_s, Q_th), abs(Q_s) + abs(Q_th) / gd.r

    def loads(self, t: float, s: Snapshot, out: Loads) -> None:
        N, F_stick, _ = self._parts(s, out)
        if not N > 0:
            ctx = self.ctx  # (set: _parts read the slide, which only a ctx brings)
            assert ctx is not None, "coulomb_friction's loads need its context"
            raise ctx.scene.error(
                f"{self.where}.body",
                f"body {self.fields['body']!r} would leave the plane at t = {float(t):.6g} s "
                f"(the normal force {N:.3g} N ≤ 0; no lift-off is modelled)",
            )
        F = F_stick if self.mode == 0 else -self.mu * N * self.mode
        gd = self._slide()
        at = s.to_body(self.i, -gd.r * gd.n)
        out.force(self.i, F * gd.t, at)

    # ------------------------------------------------------------------ the switches
    def _slip(self, s: Snapshot) -> tuple[float, float]:
        qd, r = s.coords[self.i][1], self._slide().r
        return float(qd[0] - r * qd[1]), abs(float(qd[0])) + abs(r * qd[1])

    def _decide(self, t: float, s: Snapshot, out: Loads) -> float:
        N, F_stick, _ = self._parts(s, out)
        return 0.0 if abs(F_stick) <= self.mu * N else -math.copysign(1.0, F_stick)

    def begin(self, t: float, s: Snapshot, out: Loads) -> None:
        """The mode at the start: the sign of the slip, or at zero slip the rule."""
        slip, _ = self._slip(s)
        self.mode = self._decide(t, s, out) if slip == 0 else math.copysign(1.0, slip)
        self.mode0 = self.mode

    def switch_function(self, t: float, s: Snapshot, out: Loads) -> tuple[float, float]:
        """(g, size): g falls through zero at the next switch; size is its terms'."""
        if self.mode != 0:
            slip, size = self._slip(s)
            return self.mode * slip, size
        N, F_stick, Q = self._parts(s, out)
        return self.mu * N - abs(F_stick), self.mu * abs(N) + Q

    def switch(self, t: float, s: Snapshot, out: Loads) -> Event:
        """Change the mode at a switch found at t; project onto zero slip on rolling."""
        if self.mode != 0:
            q, qd = s.coords[self.i]
            qd = qd.copy()
            qd[1] = qd[0] / self._slide().r
            s.coords[self.i] = (q, qd)
            self.mode = self._decide(t, s, out)
            return _event(t, self.mode, float(qd[0]))
        _, F_stick, _ = self._parts(s, out)
        self.mode = -math.copysign(1.0, F_stick)
        return Event(t, "slip", {"speed": float(s.coords[self.i][1][0])})

    # ------------------------------------------------------------------ invariants
    def acts_until(self, events: Iterable[Event] = (), quantity: str | None = None) -> float:
        """Friction pushes to the end; it does work (changes E) until the last switch to
        rolling, if it rolls from then on."""
        if quantity != "E":
            return math.inf
        last = None
        for ev in events:
            if ev.kind in ("rolling", "slip_zero", "slip"):
                last = ev
        if last is None:
            return 0.0 if self.mode0 == 0 else math.inf
        return last.t if last.kind == "rolling" else math.inf

    def conserved(self, s: Snapshot) -> dict[str, tuple[FloatArray, float]]:
        """On a level plane under gravity alone: m r v + J ω about the contact line."""
        if not self._flat:
            return {}
        _, qd = s.coords[self.i]
        gd = self._slide()
        m, J = gd.M
        L = m * gd.r * qd[..., 0] + J * qd[..., 1]
        scale = float(np.max(m * gd.r * np.abs(qd[..., 0]) + J * np.abs(qd[..., 1])))
        return {"L_contact": (L, scale)}

    def exerts_moment(self, k: int) -> bool:
        return k == self.i
