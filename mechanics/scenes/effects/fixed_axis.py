"""A fixed axis (a hinge, 4.3): the body turns about a space axis a through the origin
(or ``point``), its principal axis ``body_axis`` along it, G at the distance h from it.

The joint makes the body *hinged* (:mod:`mechanics.scenes.state`): one coordinate, the
angle φ, measured from the direction of gravity's component across the axis (the
book's ϕ of the physical pendulum).  The bearings' reaction is read off the motion:
the force F_R = m a_G − Σ F and the moment about C, perpendicular to the axis,
M_R = J_a φ̈ a − M_C (the bearing reactions of 4.4).  The joint does no work (E kept);
its reaction has no moment about C along a: it keeps the angular momentum about the
origin along its axis when C is the origin and a is a coordinate axis; never the
momentum.  Mass flowing onto the body (``mass_flow``, the carousel of Example 7.3)
makes its moment of inertia grow (:mod:`.mass_flow`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np
import numpy.typing as npt

from ..vectors import cross
from .base import (
    Context,
    Effect,
    FloatArray,
    SceneLike,
    Schema,
    SpecLike,
    check_joint_body,
    register,
    unit,
)
from .capabilities import Compiles, GuidesBody

if TYPE_CHECKING:
    from ..state import Hinge


@register
class FixedAxis(Effect, GuidesBody, Compiles):
    """A fixed axis (a hinge) through the body: one degree of freedom φ (4.3).

    Parameters
    ----------
    spec : SpecLike
        The listed effect; its fields: ``body`` (rigid, moving), ``axis`` (the space
        direction a, nonzero; default (0, 0, 1)), ``distance`` h (m, ≥ 0: G's distance
        from the axis; default 0), ``body_axis`` (``"x"``, ``"y"`` or ``"z"``, the
        principal axis along a; default ``"z"``) and ``point`` (a point of the axis, m;
        default the origin).
    ctx : Context or None, optional
        The scene's context (the body's index; None: an effect built for its fields alone).

    Raises
    ------
    KeyError
        If a required field is missing from ``spec.fields`` (the parser requires it), or if
        ``body`` is not a body of ``ctx``.
    ValueError
        If ``body_axis`` is not one of x, y, z (the parser refuses it first).

    Examples
    --------
    The moment of inertia about the axis, J_a = J_G + m h² (parallel axes, 4.54):

    >>> from mechanics.scenes.spec import EffectSpec
    >>> hinge = FixedAxis(EffectSpec("fixed_axis", 0, {"body": "rod", "distance": 0.5}))
    >>> hinge.moment_of_inertia(3.0, np.diag([1.0, 1.0, 2.0])), 2.0 + 3.0 * 0.5**2
    (2.75, 2.75)
    >>> hinge.reference([0.0, 0.0, -9.81]).tolist()  # φ = 0 across a vertical axis: e_x
    [1.0, 0.0, 0.0]
    """

    type = "fixed_axis"
    dissipative = True
    schema: ClassVar[Schema] = {
        "body": ("body", True),
        "axis": ("vector", False),
        "distance": ("nonnegative", False),
        "body_axis": ("axis_name", False),
        "point": ("vector", False),
    }
    units: ClassVar[dict[str, str]] = {
        "body": "",
        "axis": "1",
        "distance": "m",
        "body_axis": "",
        "point": "m",
    }
    example: ClassVar[dict[str, Any]] = {
        "type": "fixed_axis",
        "body": "rod",
        "axis": [0.0, 1.0, 0.0],
        "distance": 0.5,
        "body_axis": "y",
    }

    @classmethod
    def check(cls, spec: SpecLike, scene: SceneLike, index: dict[str, int]) -> None:
        from ..state import body_inertia

        check_joint_body(
            spec, scene, index, what="it cannot turn on an axis", keys=("angle", "angular_velocity")
        )
        b = scene.body(spec.fields["body"])
        if cls(spec).moment_of_inertia(b.mass, np.diag(body_inertia(b))) <= 0:
            raise scene.error(
                f"{spec.where}.body_axis",
                f"the moment of inertia about this axis is zero for a {b.shape}",
            )

    def __init__(self, spec: SpecLike, ctx: Context | None = None) -> None:
        super().__init__(spec, ctx)
        self.axis = unit(self.fields.get("axis", [0.0, 0.0, 1.0]))
        self.h = float(self.fields.get("distance", 0.0))
        self.body_axis = "xyz".index(self.fields.get("body_axis", "z"))
        self.point = np.asarray(self.fields.get("point", [0.0, 0.0, 0.0]), dtype=float)
        self.i = ctx.index[self.fields["body"]] if ctx is not None else 0

    @classmethod
    def make_guide(cls, spec: SpecLike, scene: SceneLike, g_vector: FloatArray) -> Hinge:
        """The :class:`~mechanics.scenes.state.Hinge` of the body on this axis."""
        from ..state import Hinge, body_inertia

        ax = cls(spec)
        b = scene.body(spec.fields["body"])
        k = ax.body_axis
        u0 = ax.reference(g_vector)
        J_a = ax.moment_of_inertia(b.mass, np.diag(body_inertia(b)))
        return Hinge(
            ax.point, ax.axis, u0, cross(ax.axis, u0), k, (k + 1) % 3, (k + 2) % 3, ax.h, J_a
        )

    def moment_of_inertia(self, m: float, J_G: FloatArray) -> float:
        """J_z = J_G + m h² (parallel axes, 4.54)."""
        return float(J_G[self.body_axis, self.body_axis]) + m * self.h**2

    def reference(self, g_vector: npt.ArrayLike) -> FloatArray:
        """u0: the unit direction across the axis where φ = 0, gravity's component
        across it (4.3), else the axis' first perpendicular among e_x, e_y."""
        a = self.axis
        for d in (np.asarray(g_vector, dtype=float), np.array([1.0, 0, 0]), np.array([0, 1.0, 0])):
            across = d - (d @ a) * a
            # a second projection ("twice is enough", Kahan-Parlett): the first leaves a
            # part along a of ~eps |d| / |across| of it, 2e-9 rad of R's orthogonality
            # for e_x within 2e-8 rad of the axis (found by hypothesis)
            across -= (across @ a) * a
            n = float(np.linalg.norm(across))
            if n > 1e-8 * max(float(np.linalg.norm(d)), 1e-300):  # not along the axis
                return across / n
        raise AssertionError("no direction across the axis")  # pragma: no cover

    def kernel_args(self) -> tuple[int, int, list[float], list[tuple[int, int]]]:
        return self.i, -1, [], []  # no load: the layout guides the body

    def keeps(self, quantity: str) -> bool:
        if quantity == "E":
            return True
        if quantity.startswith("L_") and not self.point.any():
            k = "xyz".index(quantity[-1])
            return bool(np.all(np.delete(self.axis, k) == 0.0))
        return False

    def exerts_moment(self, k: int) -> bool:
        return k == self.i
