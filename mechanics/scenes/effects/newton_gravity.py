"""Newtonian gravity between bodies: F_ij = −G m_i m_j (r_i − r_j)/|r_i − r_j|³ on body i.

Each body attracts as a point mass at its centre of mass (exact for spheres and points;
the monopole term for other shapes: no tidal moments).  Internal and central: it keeps
the total momentum, the total angular momentum about any point and the energy, with the
potential −Σ_{i<j} G m_i m_j/|r_i − r_j|.
"""

from __future__ import annotations

from typing import Any, ClassVar

import numpy as np

from .base import (
    Context,
    Effect,
    FloatArray,
    Loads,
    SceneLike,
    Schema,
    Snapshot,
    SpecLike,
    register,
)
from .capabilities import Compiles, HasPotential

#: CODATA 2018, m³ kg⁻¹ s⁻²
G_NEWTON = 6.67430e-11


@register
class NewtonGravity(Effect, HasPotential, Compiles):
    """Mutual attraction of the listed bodies (default: every body).

    Parameters
    ----------
    spec : SpecLike
        The listed effect; its fields: ``G`` (m³/(kg s²), > 0; default
        ``G_NEWTON``) and ``bodies`` (at least two distinct names; default every
        body).
    ctx : Context
        The scene's context (the bodies' indices, and the scene for the default list).

    Raises
    ------
    KeyError
        If a listed body is not a body of ``ctx``.
    AttributeError
        If ``ctx`` is None.

    Examples
    --------
    Two masses 2 m apart: F = G m₁ m₂/d², equal and opposite; U = −G m₁ m₂/d:

    >>> from mechanics.scenes.engine import Engine
    >>> from mechanics.scenes.spec import parse_scene
    >>> a = {"name": "a", "shape": "point", "mass": 2.0}
    >>> b = {"name": "b", "shape": "point", "mass": 3.0, "initial": {"position": [2.0, 0, 0]}}
    >>> eng = Engine(parse_scene({"scene": {"name": "x", "duration": 1.0}, "bodies": [a, b],
    ...                           "effects": [{"type": "newton_gravity", "G": 1.0}]}))
    >>> s = eng.snapshot(0.0, eng.y0)
    >>> eng.loads(0.0, s)[0].tolist(), 2.0 * 3.0 / 2.0**2
    ([[1.5, 0.0, 0.0], [-1.5, 0.0, 0.0]], 1.5)
    >>> float(eng.effects[0].potential(s)), -2.0 * 3.0 / 2.0
    (-3.0, -3.0)
    """

    type = "newton_gravity"
    schema: ClassVar[Schema] = {"G": ("positive", False), "bodies": ("bodies", False)}
    units: ClassVar[dict[str, str]] = {"G": "m³/(kg s²)", "bodies": ""}
    example: ClassVar[dict[str, Any]] = {"type": "newton_gravity", "G": 1.0}

    @classmethod
    def check(cls, spec: SpecLike, scene: SceneLike, index: dict[str, int]) -> None:
        names = spec.fields.get("bodies", [b.name for b in scene.bodies])
        if len(set(names)) < 2:
            raise scene.error(f"{spec.where}.bodies", f"needs at least two bodies; got {names}")
        if len(set(names)) != len(names):
            raise scene.error(f"{spec.where}.bodies", f"a body is listed twice: {names}")

    def __init__(self, spec: SpecLike, ctx: Context) -> None:
        super().__init__(spec, ctx)
        self.G = float(self.fields.get("G", G_NEWTON))
        names = self.fields.get("bodies", [b.name for b in ctx.scene.bodies])
        idx = [ctx.index[n] for n in names]
        self.pairs = np.array([(a, b) for k, a in enumerate(idx) for b in idx[k + 1 :]])

    def loads(self, t: float, s: Snapshot, out: Loads) -> None:
        i, j = self.pairs[:, 0], self.pairs[:, 1]
        d = s.r[i] - s.r[j]
        dist = np.sqrt((d * d).sum(-1))
        f = -(self.G * s.m[i] * s.m[j] / dist**3)[:, None] * d
        np.add.at(out.F, i, f)
        np.add.at(out.F, j, -f)

    def kernel_args(self) -> tuple[int, int, list[float], list[tuple[int, int]]]:
        return -1, -1, [self.G], [(int(a), int(b)) for a, b in self.pairs]

    def potential(self, s: Snapshot) -> FloatArray:
        i, j = self.pairs[:, 0], self.pairs[:, 1]
        d = s.r[..., i, :] - s.r[..., j, :]
        dist = np.sqrt((d * d).sum(-1))
        out: FloatArray = -(self.G * s.m[..., i] * s.m[..., j] / dist).sum(-1)
        return out

    def keeps(self, quantity: str) -> bool:
        return True

    def exerts_moment(self, k: int) -> bool:
        return False
