"""A fixed axis (hinge): the one-degree-of-freedom model of 4.3."""

from __future__ import annotations

from typing import ClassVar

from .base import Effect, Schema, register, unit


@register
class FixedAxis(Effect):
    """A fixed axis (a hinge) through the body: one degree of freedom φ (4.3)."""

    type = "fixed_axis"
    engine = False
    schema: ClassVar[Schema] = {
        "body": ("body", True),
        "axis": ("vector", False),
        "distance": ("nonnegative", False),
        "body_axis": ("axis_name", False),
    }

    def __init__(self, spec, ctx=None) -> None:
        super().__init__(spec, ctx)
        self.axis = unit(self.fields.get("axis", [0.0, 0.0, 1.0]))
        self.h = float(self.fields.get("distance", 0.0))
        self.body_axis = "xyz".index(self.fields.get("body_axis", "z"))

    def moment_of_inertia(self, m, J_G) -> float:
        """J_z = J_G + m h² (parallel axes, 4.54)."""
        return float(J_G[self.body_axis, self.body_axis]) + m * self.h**2
