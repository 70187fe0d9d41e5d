"""A torsion spring on a fixed axis (3.76): an effect of the fixed-axis model."""

from __future__ import annotations

from typing import ClassVar

import numpy as np

from .base import Effect, Schema, register


@register
class Torsion(Effect):
    """A torsion spring on a fixed axis: moment −τ0 φ (3.1, the torsion pendulum)."""

    type = "torsion"
    engine = False
    schema: ClassVar[Schema] = {"body": ("body", True), "stiffness": ("positive", True)}

    def __init__(self, spec, ctx=None) -> None:
        super().__init__(spec, ctx)
        self.tau_0 = float(self.fields["stiffness"])

    def axis_torque(self, m, h, axis, phi) -> np.ndarray:
        return -self.tau_0 * phi

    def axis_potential(self, m, h, axis, phi) -> np.ndarray:
        return 0.5 * self.tau_0 * phi**2
