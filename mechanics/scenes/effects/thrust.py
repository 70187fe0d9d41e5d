"""A rocket motor (Example 7.2): mass flows out at the rate q with the speed u relative to
the body until the fuel m_f is burnt (burn-out at T = m_f/q); the thrust q u acts at G
along a fixed space direction, or along a body-fixed direction (``frame = "body"``).

The mass is m(t) = m0 − q min(t, T).  The body's momentum and energy are not kept: the
gas carries momentum and energy away (7.24).
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

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
    register,
    unit,
)
from .capabilities import ChangesMass

if TYPE_CHECKING:
    from ..trajectory import Event


@register
class Thrust(Effect, ChangesMass):
    """Thrust q u along ``direction`` while the fuel lasts."""

    type = "thrust"
    schema: ClassVar[Schema] = {
        "body": ("body", True),
        "mass_flow": ("positive", True),
        "exhaust_speed": ("positive", True),
        "fuel_mass": ("nonnegative", True),
        "direction": ("vector", False),
        "frame": ("frame", False),
    }
    units: ClassVar[dict[str, str]] = {
        "body": "",
        "mass_flow": "kg/s",
        "exhaust_speed": "m/s",
        "fuel_mass": "kg",
        "direction": "1",
        "frame": "",
    }
    example: ClassVar[dict[str, Any]] = {
        "type": "thrust",
        "body": "ball",
        "mass_flow": 0.01,
        "exhaust_speed": 20.0,
        "fuel_mass": 0.05,
    }

    @classmethod
    def check(cls, spec: SpecLike, scene: SceneLike, index: dict[str, int]) -> None:
        f = spec.fields
        b = scene.body(f["body"])
        others = [e for e in scene.effects_of("thrust") if e.fields["body"] == b.name]
        if others[0] is not spec:
            raise scene.error(f"{spec.where}.body", f"body {b.name!r} already has a thrust")
        if f["fuel_mass"] >= b.mass:
            raise scene.error(
                f"{spec.where}.fuel_mass",
                f"the fuel mass must be less than the body's mass {b.mass!r} (the mass after "
                f"burn-out must stay > 0); got {f['fuel_mass']!r}",
            )
        if f.get("frame") == "body" and b.shape == "point":
            raise scene.error(
                f"{spec.where}.frame", f"body {b.name!r} is a point: it has no body frame"
            )

    def __init__(self, spec: SpecLike, ctx: Context) -> None:
        super().__init__(spec, ctx)
        f = self.fields
        self.i = ctx.index[f["body"]]
        self.n = len(ctx.kinds)
        self.q = float(f["mass_flow"])
        self.u = float(f["exhaust_speed"])
        self.m_f = float(f["fuel_mass"])
        self.direction = unit(f.get("direction", [0.0, 0.0, 1.0]))
        self.body_frame = f.get("frame", "space") == "body"
        self.burn_out = self.m_f / self.q

    def mass_loss(self, t: Times) -> FloatArray:
        out = np.zeros((*np.shape(t), self.n))
        out[..., self.i] = self.q * np.minimum(t, self.burn_out)
        return out

    def switch_times(self) -> list[float]:
        return [self.burn_out]

    def acts_until(self, events: Iterable[Event] = (), quantity: str | None = None) -> float:
        return self.burn_out

    def loads(self, t: float, s: Snapshot, out: Loads) -> None:
        if s.phase < self.burn_out:
            d = s.to_space(self.i, self.direction) if self.body_frame else self.direction
            out.force(self.i, self.q * self.u * d)

    def keeps(self, quantity: str) -> bool:
        # the body's momentum m v changes across d too (the gas carries q v away, 7.24)
        return False

    def exerts_moment(self, k: int) -> bool:
        return False
