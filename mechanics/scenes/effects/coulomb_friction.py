"""Coulomb friction of a round body sliding on a plane: its own model."""

from __future__ import annotations

import math
from typing import ClassVar

from .base import Effect, Schema, register


@register
class CoulombFriction(Effect):
    """Coulomb friction μN at the contact of a round body with a plane of slope α: while
    the contact point slips, the friction opposes the slip; when the slip velocity
    reaches zero (an event) the body rolls if static friction suffices."""

    type = "coulomb_friction"
    engine = False
    schema: ClassVar[Schema] = {
        "body": ("body", True),
        "mu": ("positive", True),
        "angle": ("number", False),
        "body_axis": ("axis_name", False),
    }

    def __init__(self, spec, ctx=None) -> None:
        super().__init__(spec, ctx)
        self.mu = float(self.fields["mu"])
        self.alpha = float(self.fields.get("angle", 0.0))
        self.body_axis = "xyz".index(self.fields.get("body_axis", "z"))

    def friction(self, N, slip) -> float:
        """Friction force on G along the slope: −μ N sign(slip)."""
        return -self.mu * N * math.copysign(1.0, slip) if slip != 0 else 0.0

    def can_roll(self, N, m, J, r, drive) -> bool:
        """Rolling needs |F| = |drive| J/(J + m r²) ≤ μ N (drive: force along the slope)."""
        return abs(drive) * J / (J + m * r * r) <= self.mu * N
