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
    """Thrust q u along ``direction`` while the fuel lasts (Example 7.2).

    Parameters
    ----------
    spec : SpecLike
        The listed effect; its fields: ``body`` (not held by a joint), ``mass_flow`` q
        (kg/s, > 0), ``exhaust_speed`` u (m/s, > 0), ``fuel_mass`` m_f (kg, ≥ 0, less
        than the body's mass), ``direction`` (nonzero; default (0, 0, 1)) and ``frame``
        (``"space"``, the default, or ``"body"``).
    ctx : Context
        The scene's context (the body's index and the number of bodies).

    Raises
    ------
    KeyError
        If a required field is missing from ``spec.fields`` (the parser requires it), or if
        ``body`` is not a body of ``ctx``.
    AttributeError
        If ``ctx`` is None (the body's index is read from it).

    Examples
    --------
    The fuel burns out at T = m_f/q; the mass lost is q min(t, T), so m_f from then on:

    >>> from mechanics.scenes.engine import Engine
    >>> from mechanics.scenes.spec import parse_scene
    >>> rocket = {"name": "rocket", "shape": "point", "mass": 2.0}
    >>> motor = {"type": "thrust", "body": "rocket", "mass_flow": 0.25, "exhaust_speed": 8.0,
    ...          "fuel_mass": 1.0}
    >>> eng = Engine(parse_scene({"scene": {"name": "x", "duration": 10.0},
    ...                           "bodies": [rocket], "effects": [motor]}))
    >>> th = eng.effects[0]
    >>> th.burn_out, th.mass_loss(np.array([2.0, 4.0, 10.0]))[:, 0].tolist()
    (4.0, [0.5, 1.0, 1.0])
    >>> eng.loads(0.0, eng.snapshot(0.0, eng.y0))[0][0].tolist(), 0.25 * 8.0  # q u
    ([0.0, 0.0, 2.0], 2.0)
    """

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
