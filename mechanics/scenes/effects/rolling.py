"""Rolling without slipping on an incline or in a track (3.77, 4.60): its own model."""

from __future__ import annotations

from typing import ClassVar

from .base import Effect, Schema, register


@register
class Rolling(Effect):
    """Rolling without slipping of a round body on an incline or inside a cylindrical
    track (3.77, 4.60): one degree of freedom; the contact force does no work."""

    type = "rolling"
    engine = False
    schema: ClassVar[Schema] = {
        "body": ("body", True),
        "surface": ("str", True),
        "angle": ("number", False),
        "track_radius": ("positive", False),
        "body_axis": ("axis_name", False),
    }

    def __init__(self, spec, ctx=None) -> None:
        super().__init__(spec, ctx)
        self.surface = self.fields["surface"]
        self.alpha = float(self.fields.get("angle", 0.0))
        self.track_radius = self.fields.get("track_radius")
        self.body_axis = "xyz".index(self.fields.get("body_axis", "z"))

    def effective_mass(self, m, J_G, r) -> float:
        """m + J/r²: the kinetic energy is ½ (m + J/r²) v² when v = ω r (3.79)."""
        return m + float(J_G[self.body_axis, self.body_axis]) / r**2
