"""Buoyancy of a sphere in a liquid at rest (Archimedes, Chapter 8: the pressure of a
fluid in equilibrium, p = p0 + ρ g depth, integrated over the wetted surface).

Conventions
-----------
- **The liquid** of density ``density`` fills the half-space below the level
  z = ``level`` (default 0); gravity is the listed gravities' sum, which must point
  down (−z), g its size.
- **The body** is a sphere (``solid_sphere`` or ``hollow_sphere``, radius a: the
  volume it displaces is the ball's).  Immersed to the depth d = level − (z_G − a)
  (0 ≤ d ≤ 2a), the displaced volume is the cap V(d) = π d² (3a − d)/3 (all of
  4πa³/3 below), and the lift ρ g V(d) acts upward through the cap's centroid, on the
  vertical through G: no moment about G.
- **Potential**: ρ g W(d) with W(d) = ∫₀ᵈ V = π (a d³/3 − d⁴/12) (beyond 2a:
  W(2a) + (4πa³/3)(d − 2a)), so the lift is −∂U/∂z and the energy is kept.  The liquid
  exerts no drag (an ideal fluid at rest; list a ``drag`` for a viscous one).
"""

from __future__ import annotations

import math
from typing import Any, ClassVar

import numpy as np

from ..state import SPHERICAL_SHAPES
from .base import (
    Context,
    Effect,
    FloatArray,
    Loads,
    SceneLike,
    Schema,
    Snapshot,
    SpecLike,
    gravity_vector,
    keeps_for_force_along,
    register,
)
from .capabilities import HasPotential

__all__ = ["Buoyancy"]


@register
class Buoyancy(Effect, HasPotential):
    """The lift ρ g V_displaced on a sphere in a liquid below the level z = level.

    Parameters
    ----------
    spec : SpecLike
        The listed effect; its fields: ``body`` (a ``solid_sphere`` or
        ``hollow_sphere``, not fixed), ``density`` ρ (kg/m³, > 0) and ``level`` (m;
        default 0).
    ctx : Context or None, optional
        The scene's context (the body's index and radius, and g from the listed
        gravities; None: an effect built for its fields alone).

    Raises
    ------
    KeyError
        If a required field is missing from ``spec.fields`` (the parser requires it), or if
        ``body`` is not a body of ``ctx`` or has no ``radius``.

    Examples
    --------
    Immersed to its centre (d = a) a ball displaces half its volume 4πa³/3:

    >>> from mechanics.scenes.engine import Engine
    >>> from mechanics.scenes.spec import parse_scene
    >>> ball = {"name": "ball", "shape": "solid_sphere", "mass": 2.0, "radius": 0.5}
    >>> eng = Engine(parse_scene({"scene": {"name": "x", "duration": 1.0}, "bodies": [ball],
    ...     "effects": [{"type": "gravity", "g": 9.81},
    ...                 {"type": "buoyancy", "body": "ball", "density": 1000.0}]}))
    >>> V = eng.effects[1].volume
    >>> bool(2.0 * V(0.5) == V(1.0) == V(3.0)), bool(np.isclose(V(1.0), 4 * np.pi * 0.5**3 / 3))
    (True, True)
    """

    type = "buoyancy"
    schema: ClassVar[Schema] = {
        "body": ("body", True),
        "density": ("positive", True),
        "level": ("number", False),
    }
    units: ClassVar[dict[str, str]] = {"body": "", "density": "kg/m³", "level": "m"}
    example: ClassVar[dict[str, Any]] = {"type": "buoyancy", "body": "ball", "density": 1000.0}

    @classmethod
    def check(cls, spec: SpecLike, scene: SceneLike, index: dict[str, int]) -> None:
        b = scene.body(spec.fields["body"])
        if b.shape not in SPHERICAL_SHAPES or b.shape == "point":
            raise scene.error(
                f"{spec.where}.body",
                f"buoyancy is modelled for spheres (solid_sphere, hollow_sphere); "
                f"{b.name!r} is a {b.shape}",
            )
        if b.fixed:
            raise scene.error(f"{spec.where}.body", f"body {b.name!r} is fixed: it cannot float")
        g = gravity_vector(scene)
        if not (g[0] == 0.0 and g[1] == 0.0 and g[2] < 0.0):
            raise scene.error(
                f"{spec.where}.type",
                f"buoyancy needs gravity along −z (the liquid's level is horizontal); the "
                f"listed gravity is {g.tolist()}",
            )

    def __init__(self, spec: SpecLike, ctx: Context | None = None) -> None:
        super().__init__(spec, ctx)
        self.rho = float(self.fields["density"])
        self.level = float(self.fields.get("level", 0.0))
        if ctx is None:
            return
        self.i = ctx.index[self.fields["body"]]
        self.a = float(ctx.scene.bodies[self.i].dims["radius"])
        self.g = -float(gravity_vector(ctx.scene)[2])

    def _depth(self, z: float | FloatArray) -> FloatArray:
        out: FloatArray = np.clip(self.level - (z - self.a), 0.0, None)
        return out

    def volume(self, d: float | FloatArray) -> FloatArray:
        """The displaced volume at the immersion depth d: the cap, or the whole ball."""
        a, d = self.a, np.minimum(d, 2.0 * self.a)
        out: FloatArray = math.pi * d * d * (3.0 * a - d) / 3.0
        return out

    def loads(self, t: float, s: Snapshot, out: Loads) -> None:
        d = self._depth(float(s.r[self.i, 2]))
        out.F[self.i, 2] += self.rho * self.g * float(self.volume(d))

    def potential(self, s: Snapshot) -> FloatArray:
        a = self.a
        d = self._depth(s.r[..., self.i, 2])
        cap = np.minimum(d, 2.0 * a)
        W = math.pi * (a * cap**3 / 3.0 - cap**4 / 12.0)
        W = W + (4.0 * math.pi * a**3 / 3.0) * np.maximum(d - 2.0 * a, 0.0)
        out: FloatArray = self.rho * self.g * W
        return out

    def keeps(self, quantity: str) -> bool:
        return quantity == "E" or keeps_for_force_along([0.0, 0.0, 1.0], quantity)

    def exerts_moment(self, k: int) -> bool:
        return False
