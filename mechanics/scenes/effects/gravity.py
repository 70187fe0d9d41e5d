"""Uniform gravity g·d (g > 0, unit direction d; the book's g = −g e_z with d = (0, 0, −1)).

On free bodies: the force m g d at each centre of mass, potential −m g d·r_G.  It keeps
the momentum across d and the angular momentum about the origin along d, and the energy.
On a guided body (a hinge, rolling) it enters through its generalised force.
"""

from __future__ import annotations

from typing import Any, ClassVar

import numpy as np

from .base import (
    Context,
    Effect,
    FloatArray,
    Loads,
    Schema,
    Snapshot,
    SpecLike,
    keeps_for_force_along,
    register,
    unit,
)
from .capabilities import Compiles, HasPotential


@register
class Gravity(Effect, HasPotential, Compiles):
    """Uniform gravity g·d acting on every body: the force m g d at each G.

    Parameters
    ----------
    spec : SpecLike
        The listed effect; its fields: ``g`` (m/s², > 0) and ``direction`` (nonzero,
        any length; default (0, 0, −1)).
    ctx : Context or None, optional
        The scene's context (unused: gravity acts on every body).

    Raises
    ------
    KeyError
        If a required field is missing from ``spec.fields`` (the parser requires it).

    Examples
    --------
    The potential −m g d·r_G rises by m g h over a height h (the work of the weight):

    >>> from mechanics.scenes.spec import EffectSpec
    >>> grav = Gravity(EffectSpec("gravity", 0, {"g": 9.75}))
    >>> r = np.array([[[0.0, 0.0, 0.0]], [[0.0, 0.0, 1.0]]])  # one body at two heights
    >>> U = grav.potential(Snapshot(0.0, r, None, None, None, None, np.full((2, 1), 2.0), None))
    >>> float(U[1] - U[0]), 2.0 * 9.75 * 1.0
    (19.5, 19.5)
    """

    type = "gravity"
    schema: ClassVar[Schema] = {"g": ("positive", True), "direction": ("vector", False)}
    units: ClassVar[dict[str, str]] = {"g": "m/s²", "direction": "1"}
    example: ClassVar[dict[str, Any]] = {"type": "gravity", "g": 9.81}

    def __init__(self, spec: SpecLike, ctx: Context | None = None) -> None:
        super().__init__(spec, ctx)
        self.g = float(self.fields["g"])
        self.direction = unit(self.fields.get("direction", [0.0, 0.0, -1.0]))
        self.vector = self.g * self.direction

    # free bodies
    def loads(self, t: float, s: Snapshot, out: Loads) -> None:
        out.F += s.m[:, None] * self.vector

    def kernel_args(self) -> tuple[int, int, list[float], list[tuple[int, int]]]:
        return -1, -1, self.vector.tolist(), []

    def potential(self, s: Snapshot) -> FloatArray:
        out: FloatArray = -(s.m * (s.r @ self.vector)).sum(-1)
        return out

    def keeps(self, quantity: str) -> bool:
        return quantity == "E" or keeps_for_force_along(self.direction, quantity)

    def exerts_moment(self, k: int) -> bool:
        return False

    # a fixed axis: the pendulum's exact flow reads g⊥, gravity across the axis
    def axis_g_perp(self, axis: FloatArray) -> float:
        gp = self.vector - (self.vector @ axis) * axis
        return float(np.linalg.norm(gp))
