"""Outflow from a prismatic tank through a small hole in its bottom (Example 8.1, 8.37).

Conventions
-----------
- **The tank** is a body of shape ``tank`` (its cross-section ``area`` A) that does not
  move; its state is its water level h, held as √h, and the volume run out.  Its only
  effect is this one; the ``gravity`` listed drives it, g being the sum of the listed
  gravities' downward (−z) components.
- **Torricelli, quasi-steady**: the outflow speed u = √(2gh/(1 − (a/A)²)) (8.37 with
  the surface's speed kept), A ḣ = −a u.  The level is integrated as √h, whose rate
  −(a/A)√(g/(2(1 − (a/A)²))) is a constant, regular where ḣ ∝ √h is not (an
  integrator in h could not locate the emptying).
- **Event** ``empty`` where √h reaches zero (located on the steps' dense output, in
  closed form on the exact flow); the tank stays empty.
- **Exact flow**: √h = √h0 − c t up to the emptying time T (8.37 integrated).
- **Series** h, u, volume_out and volume_total = A h + volume out, which is kept.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any, ClassVar

import numpy as np

from ..trajectory import Event
from .base import (
    Context,
    Effect,
    FloatArray,
    Loads,
    SceneLike,
    Schema,
    Snapshot,
    SpecLike,
    Times,
    gravity_vector,
    register,
)
from .capabilities import HasModes

__all__ = ["TankOutflow"]


@register
class TankOutflow(Effect, HasModes):
    """Outflow through a hole of area a in the bottom of a prismatic tank of area A (8.37).

    Torricelli's u = √(2gh/(1 − (a/A)²)) (8.37, quasi-steady) and A ḣ = −a u.

    Parameters
    ----------
    spec : SpecLike
        The listed effect; its fields: ``body`` (a ``tank``, with an initial ``level``)
        and ``hole_area`` a (m², > 0, less than the tank's ``area``).
    ctx : Context or None, optional
        The scene's context (the tank's index, area and initial level, and g from the
        gravities; None: an effect built for its fields alone).

    Raises
    ------
    KeyError
        If a required field is missing from ``spec.fields`` (the parser requires it), or if
        ``body`` is not a body of ``ctx`` or lacks its ``area`` or initial ``level``.

    Examples
    --------
    Bernoulli from the surface to the jet: ½ u² (1 − (a/A)²) = g h:

    >>> from mechanics.scenes.spec import EffectSpec
    >>> hole = TankOutflow(EffectSpec("tank_outflow", 0, {"body": "tank", "hole_area": 0.5}))
    >>> u = float(hole.outflow_speed(2.0, 3.0, 1.0))  # h = 2 m, g = 3 m/s², A = 1 m²
    >>> u, 0.5 * u**2 * (1.0 - 0.5**2), 3.0 * 2.0
    (4.0, 6.0, 6.0)
    """

    type = "tank_outflow"
    schema: ClassVar[Schema] = {"body": ("body", True), "hole_area": ("positive", True)}
    units: ClassVar[dict[str, str]] = {"body": "", "hole_area": "m²"}
    example: ClassVar[dict[str, Any]] = {"type": "tank_outflow", "body": "tank", "hole_area": 0.01}

    @classmethod
    def check(cls, spec: SpecLike, scene: SceneLike, index: dict[str, int]) -> None:
        b = scene.body(spec.fields["body"])
        where = f"bodies[{index[b.name]}]"
        if b.shape != "tank":
            raise scene.error(
                f"{spec.where}.body", f"tank_outflow needs a tank body; got a {b.shape}"
            )
        if spec.fields["hole_area"] >= b.dims["area"]:
            raise scene.error(
                f"{spec.where}.hole_area",
                f"must be smaller than the tank's area {b.dims['area']!r}; "
                f"got {spec.fields['hole_area']!r}",
            )
        if not scene.effects_of("gravity"):
            raise scene.error(
                f"{spec.where}.type", "tank_outflow is driven by gravity: list a gravity effect"
            )
        if -float(gravity_vector(scene)[2]) <= 0:
            raise scene.error("effects", "gravity must point down (−z) to drain the tank")
        if "level" not in b.initial:
            raise scene.error(f"{where}.initial.level", "missing required field for a tank")
        for k in b.initial:
            if k != "level":
                raise scene.error(f"{where}.initial.{k}", "a tank takes only level")
        mine = [e for e in scene.effects_of("tank_outflow") if e.fields["body"] == b.name]
        if mine[0] is not spec:
            raise scene.error(
                f"{spec.where}.body", f"tank {b.name!r} has one hole: list one outflow"
            )

    def __init__(self, spec: SpecLike, ctx: Context | None = None) -> None:
        super().__init__(spec, ctx)
        self.a = float(self.fields["hole_area"])
        if ctx is None:
            return
        self.i = ctx.index[self.fields["body"]]
        b = ctx.scene.bodies[self.i]
        self.A = float(b.dims["area"])
        self.h0 = float(b.initial["level"])
        self.g = -float(gravity_vector(ctx.scene)[2])
        self.empty = False

    def outflow_speed(self, h: float | FloatArray, g: float, A: float) -> FloatArray:
        """u = √(2gh/(1 − (a/A)²)) (8.37 with the surface speed kept)."""
        ratio = self.a / A
        out: FloatArray = np.sqrt(2.0 * g * np.maximum(h, 0.0) / ((1.0 - ratio) * (1.0 + ratio)))
        return out

    def sqrt_level_rate(self, g: float, A: float) -> float:
        """d√h/dt = ḣ/(2√h) = −(a/A)√(g/(2(1 − (a/A)²))): regular at h = 0, where
        ḣ ∝ √h is not Lipschitz (an integrator in h cannot locate the emptying)."""
        ratio = self.a / A
        return -ratio * math.sqrt(g / (2.0 * (1.0 - ratio) * (1.0 + ratio)))

    def start(self) -> FloatArray:
        """The tank's initial state (√h0, 0)."""
        return np.array([math.sqrt(self.h0), 0.0])

    # ------------------------------------------------------------------ the flow
    def loads(self, t: float, s: Snapshot, out: Loads) -> None:
        if self.empty:
            out.rates[self.i] = np.zeros(2)
            return
        w = float(s.fluid[self.i][0])
        u = float(self.outflow_speed(w * w, self.g, self.A))
        out.rates[self.i] = np.array([self.sqrt_level_rate(self.g, self.A), self.a * u])

    def begin(self, t: float, s: Snapshot, out: Loads) -> None:
        self.empty = float(s.fluid[self.i][0]) <= 0.0

    def switch_function(self, t: float, s: Snapshot, out: Loads) -> tuple[float, float]:
        if self.empty:
            return 1.0, 1.0
        return float(s.fluid[self.i][0]), math.sqrt(self.h0)

    def switch(self, t: float, s: Snapshot, out: Loads) -> Event:
        self.empty = True
        s.fluid[self.i][0] = 0.0
        return Event(float(t), "empty", {"body": self.fields["body"]})

    def exact(self, duration: float) -> tuple[str, Callable[[Times], FloatArray], list[Event]]:
        """(how, f, events): √h = max(√h0 − c t, 0) and the volume out
        a k c (T t − t²/2) = a k t (√h0 − c t/2) up to T, k = √(2g/(1 − (a/A)²)) (8.37
        integrated)."""
        from mechanics.fluids import drain_time

        ratio = self.a / self.A
        T = float(drain_time(self.h0, g=self.g, area_ratio=ratio))
        c = math.sqrt(self.h0) / T
        k = math.sqrt(2 * self.g / ((1 - ratio) * (1 + ratio)))

        def f(t: Times) -> FloatArray:
            t = np.asarray(t, dtype=float)
            tc = np.minimum(t, T)
            w = np.maximum(math.sqrt(self.h0) - c * tc, 0.0)
            # a k c (T t − t²/2), with c T = √h0 taken out first: T t overflows for a
            # hole of 1e-308 (T ≈ 3e307 s), though the volume out is tiny
            out = self.a * k * tc * (math.sqrt(self.h0) - 0.5 * c * tc)
            return np.stack([w, out], axis=-1)

        events = [Event(T, "empty", {"body": self.fields["body"]})] if duration >= T else []
        return "exact: Torricelli outflow, level (√h0 − c t)² (8.37)", f, events

    # ------------------------------------------------------------------ results
    def series(self, s: Snapshot) -> dict[str, FloatArray]:
        w = s.fluid[self.i][..., 0]
        h = w * w
        vout = s.fluid[self.i][..., 1]
        return {
            "h": h,
            "u": self.outflow_speed(h, self.g, self.A),
            "volume_out": vout,
            "volume_total": self.A * h + vout,
        }

    def conserved(self, s: Snapshot) -> dict[str, tuple[FloatArray, float]]:
        x = self.series(s)
        size = float(self.A * np.max(x["h"]) + np.max(np.abs(x["volume_out"])))
        return {"volume_total": (x["volume_total"], size)}

    def keeps(self, quantity: str) -> bool:
        return True  # it moves no body

    def exerts_moment(self, k: int) -> bool:
        return False
