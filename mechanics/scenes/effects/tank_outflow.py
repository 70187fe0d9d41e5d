"""Outflow from a prismatic tank (Example 8.1, 8.37): its own model."""

from __future__ import annotations

import math
from typing import ClassVar

import numpy as np

from .base import Effect, Schema, register


@register
class TankOutflow(Effect):
    """Outflow through a small hole of area a in the bottom of a prismatic tank of area A:
    Torricelli's u = √(2gh/(1 − (a/A)²)) (8.37, quasi-steady) and A ḣ = −a u."""

    type = "tank_outflow"
    engine = False
    schema: ClassVar[Schema] = {"body": ("body", True), "hole_area": ("positive", True)}

    def __init__(self, spec, ctx=None) -> None:
        super().__init__(spec, ctx)
        self.a = float(self.fields["hole_area"])

    def outflow_speed(self, h, g, A) -> np.ndarray:
        """u = √(2gh/(1 − (a/A)²)) (8.37 with the surface speed kept)."""
        ratio = self.a / A
        return np.sqrt(2.0 * g * np.maximum(h, 0.0) / ((1.0 - ratio) * (1.0 + ratio)))

    def level_rate(self, h, g, A) -> np.ndarray:
        """ḣ = −(a/A) u."""
        return -(self.a / A) * self.outflow_speed(h, g, A)

    def sqrt_level_rate(self, g, A) -> float:
        """d√h/dt = ḣ/(2√h) = −(a/A)√(g/(2(1 − (a/A)²))): regular at h = 0, where
        ḣ ∝ √h is not Lipschitz (an integrator in h cannot locate the emptying)."""
        ratio = self.a / A
        return -ratio * math.sqrt(g / (2.0 * (1.0 - ratio) * (1.0 + ratio)))
