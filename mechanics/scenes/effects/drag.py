"""Drag of a body moving through still air: linear and quadratic in the speed, on the
translation (at G) and on the rotation (a resisting moment).

F = −(b₁ + b₂ |v|) v at G and M = −(c₁ + c₂ |ω|) ω about G.  Dissipative: it keeps
nothing.
"""

from __future__ import annotations

from typing import Any, ClassVar

import numpy as np

from .base import Context, Effect, Loads, SceneLike, Schema, Snapshot, SpecLike, register
from .capabilities import Compiles


@register
class Drag(Effect, Compiles):
    """Linear (N·s/m) and quadratic (N·s²/m²) drag, and their rotational counterparts.

    Parameters
    ----------
    spec : SpecLike
        The listed effect; its fields: ``body``, and ≥ 0 coefficients ``linear`` b₁
        (N s/m), ``quadratic`` b₂ (N s²/m²), ``angular_linear`` c₁ (N m s),
        ``angular_quadratic`` c₂ (N m s²), each default 0, one of them > 0.
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
    F = −(b₁ + b₂ |v|) v: at |v| = 5 m/s its size is (b₁ + 5 b₂) 5.

    >>> from mechanics.scenes.engine import Engine
    >>> from mechanics.scenes.spec import parse_scene
    >>> ball = {"name": "ball", "shape": "point", "mass": 2.0,
    ...         "initial": {"velocity": [3.0, 0.0, 4.0]}}
    >>> eng = Engine(parse_scene({"scene": {"name": "x", "duration": 1.0}, "bodies": [ball],
    ...     "effects": [{"type": "drag", "body": "ball", "linear": 0.5, "quadratic": 0.25}]}))
    >>> F, M_A = eng.loads(0.0, eng.snapshot(0.0, eng.y0))
    >>> float(np.linalg.norm(F[0])), (0.5 + 0.25 * 5.0) * 5.0
    (8.75, 8.75)
    """

    type = "drag"
    dissipative = True
    schema: ClassVar[Schema] = {
        "body": ("body", True),
        "linear": ("nonnegative", False),
        "quadratic": ("nonnegative", False),
        "angular_linear": ("nonnegative", False),
        "angular_quadratic": ("nonnegative", False),
    }
    units: ClassVar[dict[str, str]] = {
        "body": "",
        "linear": "N s/m",
        "quadratic": "N s²/m²",
        "angular_linear": "N m s",
        "angular_quadratic": "N m s²",
    }
    example: ClassVar[dict[str, Any]] = {"type": "drag", "body": "ball", "quadratic": 0.01}

    @classmethod
    def check(cls, spec: SpecLike, scene: SceneLike, index: dict[str, int]) -> None:
        f = spec.fields
        keys = ("linear", "quadratic", "angular_linear", "angular_quadratic")
        if not any(f.get(k, 0.0) for k in keys):
            raise scene.error(spec.where, f"a drag needs one of {keys} > 0")
        body = scene.body(f["body"])
        for k in ("angular_linear", "angular_quadratic"):
            if f.get(k) and body.shape == "point":
                raise scene.error(
                    f"{spec.where}.{k}", f"body {body.name!r} is a point: it has no rotation"
                )

    def __init__(self, spec: SpecLike, ctx: Context) -> None:
        super().__init__(spec, ctx)
        f = self.fields
        self.i = ctx.index[f["body"]]
        self.b1, self.b2 = float(f.get("linear", 0.0)), float(f.get("quadratic", 0.0))
        self.c1 = float(f.get("angular_linear", 0.0))
        self.c2 = float(f.get("angular_quadratic", 0.0))

    def loads(self, t: float, s: Snapshot, out: Loads) -> None:
        v = s.v[self.i]
        out.force(self.i, -(self.b1 + self.b2 * np.sqrt(v @ v)) * v)
        if self.c1 or self.c2:
            w_O = s.to_space(self.i, s.omega[self.i])
            out.moment(self.i, -(self.c1 + self.c2 * np.sqrt(w_O @ w_O)) * w_O)

    def kernel_args(self) -> tuple[int, int, list[float], list[tuple[int, int]]]:
        return self.i, -1, [self.b1, self.b2, self.c1, self.c2], []

    def exerts_moment(self, k: int) -> bool:
        return k == self.i and bool(self.c1 or self.c2)
