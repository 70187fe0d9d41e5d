"""A torsion spring on a fixed axis (3.76): the couple −τ0 φ about the axis of a hinged
body (its angle φ from the engine's hinge), with the potential ½ τ0 φ²."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, ClassVar, cast

from .base import (
    Context,
    Effect,
    FloatArray,
    Loads,
    SceneLike,
    Schema,
    Snapshot,
    SpecLike,
    check_on_fixed_axis,
    register,
)
from .capabilities import Compiles, HasPotential

if TYPE_CHECKING:
    from ..state import Hinge


@register
class Torsion(Effect, HasPotential, Compiles):
    """A torsion spring on a fixed axis: moment −τ0 φ (3.1, the torsion pendulum).

    Parameters
    ----------
    spec : SpecLike
        The listed effect; its fields: ``body`` (turning on a ``fixed_axis``) and
        ``stiffness`` τ0 (N m/rad, > 0).
    ctx : Context or None, optional
        The scene's context (the body's index and its hinge; None: an effect built for
        its fields alone).

    Raises
    ------
    KeyError
        If a required field is missing from ``spec.fields`` (the parser requires it), or if
        ``body`` is not a body of ``ctx``.

    Examples
    --------
    A rod turned by φ = 0.5 rad: the couple τ0 φ and the potential ½ τ0 φ²:

    >>> from mechanics.scenes.engine import Engine
    >>> from mechanics.scenes.spec import parse_scene
    >>> rod = {"name": "rod", "shape": "rod", "mass": 3.0, "length": 2.0,
    ...        "initial": {"angle": 0.5}}
    >>> eng = Engine(parse_scene({"scene": {"name": "x", "duration": 1.0}, "bodies": [rod],
    ...     "effects": [{"type": "fixed_axis", "body": "rod", "body_axis": "y"},
    ...                 {"type": "torsion", "body": "rod", "stiffness": 2.0}]}))
    >>> s = eng.snapshot(0.0, eng.y0)
    >>> F, M_A = eng.loads(0.0, s)
    >>> M_A[0].tolist(), -2.0 * 0.5  # −τ0 φ along the body's y, the axis
    ([0.0, -1.0, 0.0], -1.0)
    >>> float(eng.effects[1].potential(s)), 0.5 * 2.0 * 0.5**2
    (0.25, 0.25)
    """

    type = "torsion"
    schema: ClassVar[Schema] = {"body": ("body", True), "stiffness": ("positive", True)}
    units: ClassVar[dict[str, str]] = {"body": "", "stiffness": "N m/rad"}
    example: ClassVar[dict[str, Any]] = {"type": "torsion", "body": "rod", "stiffness": 2.0}

    @classmethod
    def check(cls, spec: SpecLike, scene: SceneLike, index: dict[str, int]) -> None:
        check_on_fixed_axis(spec, scene, what="a torsion spring twists a body about its axis")

    def __init__(self, spec: SpecLike, ctx: Context | None = None) -> None:
        super().__init__(spec, ctx)
        self.tau_0 = float(self.fields["stiffness"])
        self.i = ctx.index[self.fields["body"]] if ctx is not None else 0
        #: the body's guide: a Hinge (the check requires a fixed_axis for the body)
        self.hinge = cast("Hinge | None", ctx.guides.get(self.i) if ctx is not None else None)

    def loads(self, t: float, s: Snapshot, out: Loads) -> None:
        hinge = self.hinge
        assert hinge is not None, "a torsion spring's loads need its hinge (built with a ctx)"
        out.moment(self.i, -self.tau_0 * s.angle[self.i] * hinge.a)

    def kernel_args(self) -> tuple[int, int, list[float], list[tuple[int, int]]]:
        hinge = self.hinge
        assert hinge is not None, "a torsion spring's kernel needs its hinge (built with a ctx)"
        return self.i, -1, [self.tau_0, *hinge.a.tolist()], []

    def potential(self, s: Snapshot) -> FloatArray:
        return 0.5 * self.tau_0 * s.angle[..., self.i] ** 2

    def keeps(self, quantity: str) -> bool:
        return quantity == "E" or quantity.startswith("p_")  # a couple: no force

    def exerts_moment(self, k: int) -> bool:
        return k == self.i
