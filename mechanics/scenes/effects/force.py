"""Applied loads: a force at a body point, or a couple, constant in the space basis or
fixed in the body, acting during a time window [start, end).

A body-fixed force turns with the body (a thruster on a hull); a space-fixed one keeps
its direction (a push from outside).  Applied off G, a force exerts the moment
(Rᵀ at) × F about G.  Applied loads do work: they keep the momentum across a constant
space-fixed force and nothing else.
"""

from __future__ import annotations

import math
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
    keeps_for_force_along,
    register,
)
from .capabilities import Compiles

if TYPE_CHECKING:
    from ..trajectory import Event

FRAMES = ("space", "body")


class _Applied(Effect, Compiles):
    #: the force or couple (its subclass's field), and a force's point (None: G)
    value: FloatArray
    at: FloatArray | None = None
    schema: ClassVar[Schema] = {
        "body": ("body", True),
        "frame": ("frame", False),
        "start": ("nonnegative", False),
        "end": ("positive", False),
    }

    @classmethod
    def check(cls, spec: SpecLike, scene: SceneLike, index: dict[str, int]) -> None:
        f = spec.fields
        if f.get("end", math.inf) <= f.get("start", 0.0):
            raise scene.error(
                f"{spec.where}.end",
                f"must be after start {f.get('start', 0.0)!r}; got {f['end']!r}",
            )
        body = scene.body(f["body"])
        if body.shape == "point" and (any(f.get("at", [0.0])) or cls.type == "torque"):
            raise scene.error(
                f"{spec.where}.{'at' if cls.type == 'force' else 'type'}",
                f"body {body.name!r} is a point: it has no rotation (no points off G, no couple)",
            )

    def __init__(self, spec: SpecLike, ctx: Context) -> None:
        super().__init__(spec, ctx)
        f = self.fields
        self.i = ctx.index[f["body"]]
        self.body_frame = f.get("frame", "space") == "body"
        self.start, self.end = float(f.get("start", 0.0)), float(f.get("end", math.inf))

    def active(self, t: Times) -> bool:
        """Is the load on at the (one) time t?"""
        return bool(self.start <= t < self.end)

    def switch_times(self) -> list[float]:
        """The instants where the load switches on or off: step boundaries."""
        return [x for x in (self.start, self.end) if 0 < x < math.inf]

    def acts_until(self, events: Iterable[Event] = (), quantity: str | None = None) -> float:
        return self.end

    def kernel_args(self) -> tuple[int, int, list[float], list[tuple[int, int]]]:
        """start, end, the frame (1: body), the value (3), then a force's point."""
        head = [self.start, self.end, float(self.body_frame), *self.value.tolist()]
        if self.type == "force":
            head += [0.0, 0.0, 0.0, 0.0] if self.at is None else [1.0, *self.at.tolist()]
        return self.i, -1, head, []


@register
class Force(_Applied):
    """A force (N) at a body point ``at`` (body components about G; default G).

    Parameters
    ----------
    spec : SpecLike
        The listed effect; its fields: ``body``, ``force`` (N), ``at`` (m, body
        components about G; default G), ``frame`` (``"space"``, the default, or
        ``"body"``: the force turns with the body), ``start`` (s, ≥ 0; default 0) and
        ``end`` (s, > start; default never): it acts for start ≤ t < end.
    ctx : Context
        The scene's context (the body's index).

    Raises
    ------
    KeyError
        If a required field is missing from ``spec.fields`` (the parser requires it), or if
        ``body`` is not a body of ``ctx``.
    AttributeError
        If ``ctx`` is None (the body's index is read from it).

    Examples
    --------
    Off G, the force F at ``at`` exerts the moment at × F about G (identity attitude):

    >>> from mechanics.scenes.engine import Engine
    >>> from mechanics.scenes.spec import parse_scene
    >>> box = {"name": "box", "shape": "box", "mass": 2.0, "a": 1.0, "b": 1.0, "c": 1.0}
    >>> push = {"type": "force", "body": "box", "force": [0.0, 3.0, 0.0], "at": [2.0, 0.0, 0.0]}
    >>> eng = Engine(parse_scene({"scene": {"name": "x", "duration": 1.0}, "bodies": [box],
    ...                           "effects": [push]}))
    >>> F, M_A = eng.loads(0.0, eng.snapshot(0.0, eng.y0))
    >>> M_A[0].tolist(), np.cross([2.0, 0.0, 0.0], F[0]).tolist()
    ([0.0, 0.0, 6.0], [0.0, 0.0, 6.0])
    """

    type = "force"
    schema: ClassVar[Schema] = {
        **_Applied.schema,
        "force": ("vector", True),
        "at": ("vector", False),
    }
    units: ClassVar[dict[str, str]] = {
        "body": "",
        "frame": "",
        "start": "s",
        "end": "s",
        "force": "N",
        "at": "m",
    }
    example: ClassVar[dict[str, Any]] = {
        "type": "force",
        "body": "ball",
        "force": [1.0, 0.0, 0.0],
        "end": 0.1,
    }

    def __init__(self, spec: SpecLike, ctx: Context) -> None:
        super().__init__(spec, ctx)
        self.value = np.asarray(self.fields["force"], dtype=float)
        at = self.fields.get("at")
        self.at = np.asarray(at, float) if at is not None and any(at) else None

    def loads(self, t: float, s: Snapshot, out: Loads) -> None:
        if self.active(s.phase):
            F = s.to_space(self.i, self.value) if self.body_frame else self.value
            out.force(self.i, F, self.at)

    def exerts_moment(self, k: int) -> bool:
        return k == self.i and self.at is not None

    def keeps(self, quantity: str) -> bool:
        if not self.value.any():
            return True
        if self.body_frame or quantity == "E":
            return False
        return keeps_for_force_along(self.value, quantity)


@register
class Torque(_Applied):
    """A couple (N·m) on a body, in space or body components.

    Parameters
    ----------
    spec : SpecLike
        The listed effect; its fields: ``body`` (not a point), ``torque`` (N m),
        ``frame`` (``"space"``, the default, or ``"body"``), ``start`` (s, ≥ 0; default 0)
        and ``end`` (s, > start; default never): it acts for start ≤ t < end.
    ctx : Context
        The scene's context (the body's index).

    Raises
    ------
    KeyError
        If a required field is missing from ``spec.fields`` (the parser requires it), or if
        ``body`` is not a body of ``ctx``.
    AttributeError
        If ``ctx`` is None (the body's index is read from it).

    Examples
    --------
    A couple adds no force: it keeps the momentum, and only that:

    >>> from mechanics.scenes.engine import Engine
    >>> from mechanics.scenes.spec import parse_scene
    >>> box = {"name": "box", "shape": "box", "mass": 2.0, "a": 1.0, "b": 1.0, "c": 1.0}
    >>> turn = {"type": "torque", "body": "box", "torque": [0.0, 0.0, 1.5], "end": 0.5}
    >>> eng = Engine(parse_scene({"scene": {"name": "x", "duration": 1.0}, "bodies": [box],
    ...                           "effects": [turn]}))
    >>> F, M_A = eng.loads(0.0, eng.snapshot(0.0, eng.y0))
    >>> F[0].tolist(), M_A[0].tolist(), eng.effects[0].switch_times()
    ([0.0, 0.0, 0.0], [0.0, 0.0, 1.5], [0.5])
    >>> [q for q in ("p_x", "p_y", "p_z", "L_z", "E") if eng.effects[0].keeps(q)]
    ['p_x', 'p_y', 'p_z']
    """

    type = "torque"
    schema: ClassVar[Schema] = {**_Applied.schema, "torque": ("vector", True)}
    units: ClassVar[dict[str, str]] = {
        "body": "",
        "frame": "",
        "start": "s",
        "end": "s",
        "torque": "N m",
    }
    example: ClassVar[dict[str, Any]] = {
        "type": "torque",
        "body": "rod",
        "torque": [0.0, 0.0, 0.1],
        "frame": "body",
    }

    def __init__(self, spec: SpecLike, ctx: Context) -> None:
        super().__init__(spec, ctx)
        self.value = np.asarray(self.fields["torque"], dtype=float)

    def loads(self, t: float, s: Snapshot, out: Loads) -> None:
        if self.active(s.phase):
            if self.body_frame:
                out.moment_body(self.i, self.value)
            else:
                out.moment(self.i, self.value)

    def exerts_moment(self, k: int) -> bool:
        return k == self.i

    def keeps(self, quantity: str) -> bool:
        return quantity.startswith("p_")
