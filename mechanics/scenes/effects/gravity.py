"""Uniform gravity g·d (g > 0, unit direction d; the book's g = −g e_z with d = (0, 0, −1)).

On free bodies: the force m g d at each centre of mass, potential −m g d·r_G.  It keeps
the momentum across d and the angular momentum about the origin along d, and the energy.
The one-degree-of-freedom models read it through the helpers below (the pendulum's
moment, the top's moment about C, the slope's drive and normal force).
"""

from __future__ import annotations

import math
from typing import ClassVar

import numpy as np

from .base import Effect, Schema, keeps_for_force_along, register, unit


@register
class Gravity(Effect):
    """Uniform gravity g·d acting on every body."""

    type = "gravity"
    schema: ClassVar[Schema] = {"g": ("positive", True), "direction": ("vector", False)}

    def __init__(self, spec, ctx=None) -> None:
        super().__init__(spec, ctx)
        self.g = float(self.fields["g"])
        self.direction = unit(self.fields.get("direction", [0.0, 0.0, -1.0]))
        self.vector = self.g * self.direction

    # free bodies
    def loads(self, t, s, out) -> None:
        out.F += s.m[:, None] * self.vector

    def potential(self, s) -> np.ndarray:
        return -(s.m * (s.r @ self.vector)).sum(-1)

    def keeps(self, quantity: str) -> bool:
        return quantity == "E" or keeps_for_force_along(self.direction, quantity)

    def exerts_moment(self, k: int) -> bool:
        return False

    # fixed axis: torque −m g⊥ h sin φ
    def axis_g_perp(self, axis) -> float:
        gp = self.vector - (self.vector @ axis) * axis
        return float(np.linalg.norm(gp))

    def axis_torque(self, m, h, axis, phi) -> np.ndarray:
        return -m * self.axis_g_perp(axis) * h * np.sin(phi)

    def axis_potential(self, m, h, axis, phi) -> np.ndarray:
        return m * self.axis_g_perp(axis) * h * 2.0 * np.sin(0.5 * phi) ** 2

    # fixed point: G at ℓ e3 of the body; moment about C, body components
    def point_torque(self, m, ell, R_A_O) -> np.ndarray:
        g_A = R_A_O @ self.vector
        return ell * m * np.array([-g_A[1], g_A[0], 0.0])  # ℓ e3 × m g_A

    def point_potential(self, m, ell, R_A_O) -> np.ndarray:
        e3_O = R_A_O[..., 2, :]
        return -m * ell * (e3_O @ self.vector)

    # rolling / sliding: generalised force on the coordinate and the potential
    def slope_force(self, m, alpha) -> float:
        return m * self.g * math.sin(alpha)

    def slope_potential(self, m, alpha, s) -> np.ndarray:
        return -m * self.g * math.sin(alpha) * s

    def normal_force(self, m, alpha) -> float:
        return m * self.g * math.cos(alpha)
