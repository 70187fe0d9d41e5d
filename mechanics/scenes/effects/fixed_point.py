"""A fixed point (a ball joint): the body's point C, on its symmetry axis e3 at the
distance ℓ below G, held at a point of space (the top of 5.2).

The joint makes the body *pinned* (:mod:`mechanics.scenes.state`): no force is needed to
hold C, the reaction is read off the motion, F_C = m a_G − Σ F (the bearing reaction of
4.4).  A lone top with no effect but gravity has an exact flow in the engine: the
torque-free top about C, or the heavy symmetric top (5.2).
The joint does no work (E kept) and its reaction has no moment about C: it keeps the
angular momentum about the origin when C is the origin; never the momentum.
"""

from __future__ import annotations

from typing import Any, ClassVar

import numpy as np

from .base import (
    Context,
    Effect,
    FloatArray,
    SceneLike,
    Schema,
    SpecLike,
    check_joint_body,
    register,
)
from .capabilities import Compiles


@register
class FixedPoint(Effect, Compiles):
    """A fixed point C on the body's symmetry (z) axis at distance ℓ from G (5.2).

    Parameters
    ----------
    spec : SpecLike
        The listed effect; its fields: ``body`` (rigid, moving), ``distance`` ℓ (m, ≥ 0:
        G at ℓ e3 from C) and ``point`` (the pivot C in space, m; default the origin).
    ctx : Context or None, optional
        The scene's context (the body's index; None: an effect built for its fields alone).

    Raises
    ------
    KeyError
        If a required field is missing from ``spec.fields`` (the parser requires it), or if
        ``body`` is not a body of ``ctx``.

    Examples
    --------
    The pin (C, g_A); with C off the origin the joint keeps only the energy:

    >>> from mechanics.scenes.spec import EffectSpec
    >>> fp = FixedPoint(EffectSpec("fixed_point", 0,
    ...                            {"body": "top", "distance": 0.25, "point": [0.0, 0.0, 1.0]}))
    >>> [x.tolist() for x in fp.pin()], [q for q in ("p_z", "L_z", "E") if fp.keeps(q)]
    ([[0.0, 0.0, 1.0], [0.0, 0.0, 0.25]], ['E'])
    """

    type = "fixed_point"
    dissipative = True
    schema: ClassVar[Schema] = {
        "body": ("body", True),
        "distance": ("nonnegative", True),
        "point": ("vector", False),
    }
    units: ClassVar[dict[str, str]] = {"body": "", "distance": "m", "point": "m"}
    example: ClassVar[dict[str, Any]] = {"type": "fixed_point", "body": "top", "distance": 0.1}

    @classmethod
    def check(cls, spec: SpecLike, scene: SceneLike, index: dict[str, int]) -> None:
        check_joint_body(spec, scene, index, what="it cannot be pinned", keys=None)
        b = scene.body(spec.fields["body"])
        for k in ("position", "velocity"):
            if k in b.initial:
                raise scene.error(
                    f"bodies[{index[b.name]}].initial.{k}",
                    "a pinned body's centre follows from its attitude: give psi, theta, phi",
                )

    def __init__(self, spec: SpecLike, ctx: Context | None = None) -> None:
        super().__init__(spec, ctx)
        self.ell = float(self.fields["distance"])
        self.point = np.asarray(self.fields.get("point", [0.0, 0.0, 0.0]), dtype=float)
        self.i = ctx.index[self.fields["body"]] if ctx is not None else 0

    def pin(self) -> tuple[FloatArray, FloatArray]:
        """(C, g_A): the pivot in space and G relative to it in body components."""
        return self.point, np.array([0.0, 0.0, self.ell])

    def kernel_args(self) -> tuple[int, int, list[float], list[tuple[int, int]]]:
        return self.i, -1, [], []  # no load: the layout pins the body

    def keeps(self, quantity: str) -> bool:
        if quantity == "E":
            return True
        return quantity.startswith("L_") and not self.point.any()

    def exerts_moment(self, k: int) -> bool:
        return k == self.i
