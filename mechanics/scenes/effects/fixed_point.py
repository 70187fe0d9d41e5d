"""A fixed point on the symmetry axis: the top of 5.2 (its own model)."""

from __future__ import annotations

from typing import ClassVar

import numpy as np

from .base import Effect, Schema, register


@register
class FixedPoint(Effect):
    """A fixed point C on the body's symmetry (z) axis at distance ℓ from G (5.2)."""

    type = "fixed_point"
    engine = False
    schema: ClassVar[Schema] = {"body": ("body", True), "distance": ("nonnegative", True)}

    def __init__(self, spec, ctx=None) -> None:
        super().__init__(spec, ctx)
        self.ell = float(self.fields["distance"])

    def moments(self, m, J_G) -> np.ndarray:
        """Principal moments about C: J'1 = J1 + m ℓ², J'2 = J2 + m ℓ², J3 (5.46)."""
        J = np.diag(J_G).astype(float).copy()
        J[:2] += m * self.ell**2
        return J
