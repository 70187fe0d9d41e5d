"""Mass flowing onto a body on a fixed axis (Example 7.3, the carousel under fire).

Bullets of mass flow q ≥ 0 and speed v, along a line at the signed distance r from the
axis, stick at the radius R.  The body's moment of inertia about its axis grows,
J(t) = J_a + q R² t, and the angular momentum about the axis changes by the flux the
bullets bring, d(J φ̇)/dt = −r q v + (the other loads' moment) (7.36–7.39): the effect
adds the moment (−r q v − q R² φ̇) a, and :meth:`MassFlow.inertia_added` the growth of
J.  The mass of the body (and so its weight and the bearings' force) is its own: the
bullets' momentum along their line is not among the loads, so no bearing reaction is
reported.  With no other moment about the axis, L_a + r q v t = J φ̇ + r q v t is kept.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, ClassVar, cast

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
    Times,
    check_on_fixed_axis,
    register,
)
from .capabilities import AddsInertia

if TYPE_CHECKING:
    from ..state import Hinge


@register
class MassFlow(Effect, AddsInertia):
    """Mass flow q ≥ 0 *into* a body on a fixed axis: Example 7.3, (7.36)–(7.39).

    Bullets of speed v along a line at the signed distance r from the axis stick at the
    radius R.

    Parameters
    ----------
    spec : SpecLike
        The listed effect; its fields: ``body`` (turning on a ``fixed_axis``), ``rate``
        q (kg/s, ≥ 0), ``speed`` v (m/s), ``offset`` r (m, |r| ≤ R) and ``radius`` R
        (m, > 0).
    ctx : Context
        The scene's context (the body's index, its hinge and the scene's other effects).

    Raises
    ------
    KeyError
        If a required field is missing from ``spec.fields`` (the parser requires it), or if
        ``body`` is not a body of ``ctx``.
    AttributeError
        If ``ctx`` is None (the body's index is read from it).

    Examples
    --------
    The moment of inertia grows by q R² t (7.37), for this body only:

    >>> from mechanics.scenes.engine import Engine
    >>> from mechanics.scenes.spec import parse_scene
    >>> disc = {"name": "disc", "shape": "disc", "mass": 500.0, "radius": 2.0}
    >>> fire = {"type": "mass_flow", "body": "disc", "rate": 0.25, "speed": 400.0,
    ...         "offset": 1.5, "radius": 2.0}
    >>> eng = Engine(parse_scene({"scene": {"name": "x", "duration": 1.0}, "bodies": [disc],
    ...     "effects": [{"type": "fixed_axis", "body": "disc"}, fire]}))
    >>> mf = eng.effects[1]
    >>> mf.inertia_added(10.0, 0).tolist(), 0.25 * 2.0**2 * 10.0, mf.inertia_added(10.0, 1)
    ([10.0], 10.0, 0.0)
    """

    type = "mass_flow"
    schema: ClassVar[Schema] = {
        "body": ("body", True),
        "rate": ("nonnegative", True),
        "speed": ("number", True),
        "offset": ("number", True),
        "radius": ("positive", True),
    }
    units: ClassVar[dict[str, str]] = {
        "body": "",
        "rate": "kg/s",
        "speed": "m/s",
        "offset": "m",
        "radius": "m",
    }
    example: ClassVar[dict[str, Any]] = {
        "type": "mass_flow",
        "body": "rod",
        "rate": 0.1,
        "speed": 400.0,
        "offset": 0.3,
        "radius": 0.5,
    }

    @classmethod
    def check(cls, spec: SpecLike, scene: SceneLike, index: dict[str, int]) -> None:
        check_on_fixed_axis(spec, scene, what="mass flows onto a body turning on a fixed axis")
        r, R = spec.fields["offset"], spec.fields["radius"]
        if not abs(r) <= R:
            raise scene.error(
                f"{spec.where}.offset",
                f"the flow must reach the rim: |offset| ≤ radius; got offset {r!r} with "
                f"radius {R!r}",
            )

    def __init__(self, spec: SpecLike, ctx: Context) -> None:
        super().__init__(spec, ctx)
        self.q = float(self.fields["rate"])
        self.v = float(self.fields["speed"])
        self.r = float(self.fields["offset"])
        self.R = float(self.fields["radius"])
        self.i = ctx.index[self.fields["body"]]
        #: the body's guide: a Hinge (the check requires a fixed_axis for the body)
        self.hinge = cast("Hinge | None", ctx.guides.get(self.i))
        self._alone = {e.type for e in ctx.scene.effects} <= {"fixed_axis", self.type}

    def inertia_added(self, t: Times, i: int) -> FloatArray | float:
        """q R² t, shape (..., 1), added to the axis inertia of body i (0 for the others)."""
        if i != self.i:
            return 0.0
        out: FloatArray = self.q * self.R**2 * np.asarray(t, dtype=float)[..., None]
        return out

    def loads(self, t: float, s: Snapshot, out: Loads) -> None:
        hinge = self.hinge
        assert hinge is not None, "mass_flow's loads need the body's hinge (its fixed_axis)"
        phidot = float(s.coords[self.i][1][0])
        out.moment(self.i, (-self.r * self.q * self.v - self.q * self.R**2 * phidot) * hinge.a)

    def exerts_moment(self, k: int) -> bool:
        return k == self.i

    def conserved(self, s: Snapshot) -> dict[str, tuple[FloatArray, float]]:
        """J(t) φ̇ + r q v t, with no other moment about the axis (7.39 integrated)."""
        if not self._alone:
            return {}
        t = np.asarray(s.t, dtype=float)
        L = s.inertia[self.i][..., 0] * s.coords[self.i][1][..., 0]
        flux = self.r * self.q * self.v * t
        return {"L_axis + r q v t": (L + flux, float(np.max(np.abs(L)) + np.max(np.abs(flux))))}
