"""Mass flow into a body on a fixed axis (Example 7.3): the fixed-axis model."""

from __future__ import annotations

from typing import ClassVar

import numpy as np

from .base import Effect, Schema, register


@register
class MassFlow(Effect):
    """Mass flow q ≥ 0 *into* a body on a fixed axis (bullets of speed v along a line at
    signed distance r from the axis, stuck at radius R): Example 7.3, (7.36)–(7.39)."""

    type = "mass_flow"
    engine = False
    schema: ClassVar[Schema] = {
        "body": ("body", True),
        "rate": ("nonnegative", True),
        "speed": ("number", True),
        "offset": ("number", True),
        "radius": ("positive", True),
    }

    def __init__(self, spec, ctx=None) -> None:
        super().__init__(spec, ctx)
        self.q = float(self.fields["rate"])
        self.v = float(self.fields["speed"])
        self.r = float(self.fields["offset"])
        self.R = float(self.fields["radius"])

    def inertia_added(self, t) -> np.ndarray:
        return self.q * self.R**2 * np.asarray(t, dtype=float)

    def axis_torque_flux(self, phidot) -> np.ndarray:
        """−r q v − q R² φ̇: the angular momentum flux in, minus the spin-up of new mass."""
        return -self.r * self.q * self.v - self.q * self.R**2 * phidot
