"""Linear springs and dampers between points of two bodies, or a body and the ground.

A spring of stiffness k and rest length ℓ0 between the points P (on ``body``, at ``at``
in body components about G) and Q (on ``other`` at ``other_at``, or the fixed ground
point ``anchor``) pulls P toward Q with k (|PQ| − ℓ0) along the line PQ; a damper adds
−c (relative velocity of P along the line).  Attached off G, each exerts a moment.
Between two bodies the forces are equal, opposite and along PQ: the total momentum and
the total angular momentum about any point are kept; to the ground (anchor a) the
angular momentum about a is kept, so about the origin when a = 0.  Only an undamped
spring keeps the energy, with the potential ½ k (|PQ| − ℓ0)².
"""

from __future__ import annotations

import math
from typing import Any, ClassVar

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
    register,
)
from .capabilities import Compiles, HasPotential


class _TwoPoint(Effect, Compiles):
    """A line element between two points; the common geometry of springs and dampers."""

    #: stiffness, rest length (none for a damper) and damping, set by each subclass
    k: float = 0.0
    ell_0: float = 0.0
    c: float

    schema: ClassVar[Schema] = {
        "body": ("body", True),
        "at": ("vector", False),
        "other": ("body", False),
        "other_at": ("vector", False),
        "anchor": ("vector", False),
    }

    @classmethod
    def check(cls, spec: SpecLike, scene: SceneLike, index: dict[str, int]) -> None:
        f = spec.fields
        if "other" in f and "anchor" in f:
            raise scene.error(
                f"{spec.where}.anchor", "give either another body or a ground anchor, not both"
            )
        if f.get("other") == f["body"]:
            raise scene.error(f"{spec.where}.other", f"a {cls.type} needs two different ends")
        if "other_at" in f and "other" not in f:
            raise scene.error(f"{spec.where}.other_at", "needs an 'other' body")
        for key, who in (("at", "body"), ("other_at", "other")):
            if key in f and any(f[key]) and scene.body(f[who]).shape == "point":
                raise scene.error(
                    f"{spec.where}.{key}",
                    f"body {f[who]!r} is a point: it has no points off its centre; got {f[key]}",
                )

    def __init__(self, spec: SpecLike, ctx: Context) -> None:
        super().__init__(spec, ctx)
        f = self.fields
        self.i = ctx.index[f["body"]]
        self.j = ctx.index[f["other"]] if "other" in f else None
        self.at = np.asarray(f["at"], float) if "at" in f and any(f["at"]) else None
        self.other_at = (
            np.asarray(f["other_at"], float) if "other_at" in f and any(f["other_at"]) else None
        )
        self.anchor = np.asarray(f.get("anchor", [0.0, 0.0, 0.0]), dtype=float)

    def ends(self, s: Snapshot) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        """P, Q and their velocities (any leading shape)."""
        P, vP = s.point(self.i, self.at), s.point_velocity(self.i, self.at)
        if self.j is None:
            return P, self.anchor, vP, np.zeros(3)
        return P, s.point(self.j, self.other_at), vP, s.point_velocity(self.j, self.other_at)

    def kernel_args(self) -> tuple[int, int, list[float], list[tuple[int, int]]]:
        """stiffness, rest length, damping, P's point (has one, at), Q's (has one,
        other_at), the anchor."""
        numbers = [self.k, self.ell_0, self.c]
        for at in (self.at, self.other_at):
            numbers += [0.0, 0.0, 0.0, 0.0] if at is None else [1.0, *at.tolist()]
        numbers += self.anchor.tolist()
        j = -1 if self.j is None else self.j
        return self.i, j, numbers, []

    def _apply(self, out: Loads, f: FloatArray) -> None:
        out.force(self.i, f, self.at)
        if self.j is not None:
            out.force(self.j, -f, self.other_at)

    def exerts_moment(self, k: int) -> bool:
        return (k == self.i and self.at is not None) or (k == self.j and self.other_at is not None)

    def keeps(self, quantity: str) -> bool:
        if self.j is not None:
            return quantity != "E"
        return quantity.startswith("L_") and not self.anchor.any()


@register
class Spring(_TwoPoint, HasPotential):
    """A linear spring (optionally with a dashpot of coefficient ``damping``).

    It pulls P toward Q with k (|PQ| − ℓ0) along PQ, with the potential ½ k (|PQ| − ℓ0)².

    Parameters
    ----------
    spec : SpecLike
        The listed effect; its fields: ``body`` and ``at`` (P, m, body components about
        G; default G); the other end, either ``other`` (a body) with ``other_at`` (Q, m,
        about its G; default G), or ``anchor`` (Q, a fixed point of space, m; default
        the origin); ``stiffness`` k (N/m, > 0), ``rest_length`` ℓ0 (m, ≥ 0;
        default 0) and ``damping`` c (N s/m, ≥ 0; default 0).
    ctx : Context
        The scene's context (the bodies' indices).

    Raises
    ------
    KeyError
        If a required field is missing from ``spec.fields`` (the parser requires it), or if
        a body is not a body of ``ctx``.
    AttributeError
        If ``ctx`` is None (the body's index is read from it).

    Examples
    --------
    Stretched by 2 m beyond its rest length, the force k·2 and the potential ½ k 2²:

    >>> from mechanics.scenes.engine import Engine
    >>> from mechanics.scenes.spec import parse_scene
    >>> ball = {"name": "ball", "shape": "point", "mass": 2.0}
    >>> spring = {"type": "spring", "body": "ball", "anchor": [0.0, 0.0, 3.0],
    ...           "stiffness": 4.0, "rest_length": 1.0}
    >>> eng = Engine(parse_scene({"scene": {"name": "x", "duration": 1.0}, "bodies": [ball],
    ...                           "effects": [spring]}))
    >>> s = eng.snapshot(0.0, eng.y0)
    >>> eng.loads(0.0, s)[0][0].tolist(), float(eng.effects[0].potential(s)), 0.5 * 4.0 * 2.0**2
    ([0.0, 0.0, 8.0], 8.0, 8.0)
    """

    type = "spring"
    schema: ClassVar[Schema] = {
        **_TwoPoint.schema,
        "stiffness": ("positive", True),
        "rest_length": ("nonnegative", False),
        "damping": ("nonnegative", False),
    }
    units: ClassVar[dict[str, str]] = {
        "body": "",
        "at": "m",
        "other": "",
        "other_at": "m",
        "anchor": "m",
        "stiffness": "N/m",
        "rest_length": "m",
        "damping": "N s/m",
    }
    example: ClassVar[dict[str, Any]] = {
        "type": "spring",
        "body": "ball",
        "anchor": [0.0, 0.0, 2.0],
        "stiffness": 10.0,
        "rest_length": 0.5,
    }

    def __init__(self, spec: SpecLike, ctx: Context) -> None:
        super().__init__(spec, ctx)
        self.k = float(self.fields["stiffness"])
        self.ell_0 = float(self.fields.get("rest_length", 0.0))
        self.c = float(self.fields.get("damping", 0.0))

    def loads(self, t: float, s: Snapshot, out: Loads) -> None:
        P, Q, vP, vQ = self.ends(s)
        d = P - Q
        L = math.sqrt(d @ d)
        if L > 0:
            u = d / L
            f = -(self.k * (L - self.ell_0) + self.c * ((vP - vQ) @ u)) * u
        else:  # zero length: the direction is undefined, and so is the rest length's pull
            f = -self.k * d - self.c * (vP - vQ)
        self._apply(out, f)

    def potential(self, s: Snapshot) -> FloatArray:
        P, Q, _, _ = self.ends(s)
        L = np.linalg.norm(P - Q, axis=-1)
        out: FloatArray = 0.5 * self.k * (L - self.ell_0) ** 2
        return out

    def keeps(self, quantity: str) -> bool:
        if quantity == "E":
            return self.c == 0
        return super().keeps(quantity)


@register
class Damper(_TwoPoint):
    """A linear dashpot: −c (relative velocity along the line) on P, the opposite on Q.

    Parameters
    ----------
    spec : SpecLike
        The listed effect; its fields: ``body`` and ``at`` (P, m, body components about
        G; default G); the other end, either ``other`` (a body) with ``other_at`` (Q, m,
        about its G; default G), or ``anchor`` (Q, a fixed point of space, m; default
        the origin); ``damping`` c (N s/m, > 0).
    ctx : Context
        The scene's context (the bodies' indices).

    Raises
    ------
    KeyError
        If a required field is missing from ``spec.fields`` (the parser requires it), or if
        a body is not a body of ``ctx``.
    AttributeError
        If ``ctx`` is None (the body's index is read from it).

    Examples
    --------
    Only the velocity along the line PQ is damped: −c v_z along a vertical line:

    >>> from mechanics.scenes.engine import Engine
    >>> from mechanics.scenes.spec import parse_scene
    >>> ball = {"name": "ball", "shape": "point", "mass": 2.0,
    ...         "initial": {"velocity": [1.0, 0.0, -2.0]}}
    >>> damper = {"type": "damper", "body": "ball", "anchor": [0.0, 0.0, 3.0], "damping": 0.5}
    >>> eng = Engine(parse_scene({"scene": {"name": "x", "duration": 1.0}, "bodies": [ball],
    ...                           "effects": [damper]}))
    >>> eng.loads(0.0, eng.snapshot(0.0, eng.y0))[0][0].tolist(), -0.5 * -2.0
    ([0.0, 0.0, 1.0], 1.0)
    """

    type = "damper"
    schema: ClassVar[Schema] = {**_TwoPoint.schema, "damping": ("positive", True)}
    units: ClassVar[dict[str, str]] = {
        "body": "",
        "at": "m",
        "other": "",
        "other_at": "m",
        "anchor": "m",
        "damping": "N s/m",
    }
    example: ClassVar[dict[str, Any]] = {
        "type": "damper",
        "body": "ball",
        "anchor": [0.0, 0.0, 1.0],
        "damping": 0.5,
    }

    def __init__(self, spec: SpecLike, ctx: Context) -> None:
        super().__init__(spec, ctx)
        self.c = float(self.fields["damping"])

    def loads(self, t: float, s: Snapshot, out: Loads) -> None:
        P, Q, vP, vQ = self.ends(s)
        d = P - Q
        L = math.sqrt(d @ d)
        u = d / L if L > 0 else np.zeros(3)
        self._apply(out, -self.c * ((vP - vQ) @ u) * u)
