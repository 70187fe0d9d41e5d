"""The one interface of an effect, the snapshot of the bodies it reads, and the loads it adds.

Conventions
-----------
- **Registered by name.**  An effect is a class with a ``type`` (the name a scene file
  lists) and a ``schema`` ``{field: (kind, required)}`` that the scene file's parser
  checks (kinds: see :func:`mechanics.scenes.spec.check_field`).  :func:`register`
  adds it to :data:`REGISTRY`.  An object is built only for an effect the scene
  lists; no code of an unlisted effect runs.
- **What an effect may contribute** (each optional, the base class contributes
  nothing): :meth:`Effect.loads` adds forces (in the space basis O, at a point given in
  body components about G, or at G) and moments to a :class:`Loads`; a potential
  energy, mass lost, inertia added, modes or a guide, each declared by a protocol of
  :mod:`.capabilities` among the class's bases; :meth:`keeps` says which of the total
  momentum p_x, p_y,
  p_z, the total angular momentum about the origin L_x, L_y, L_z and the total energy
  E it leaves unchanged (the engine reports as conserved exactly the quantities every
  listed effect keeps).  Contacts (the ``impact`` effect) add events instead.
- **Joints** (a fixed point, a fixed axis, rolling, sliding on a plane) hold a body;
  a joint that guides its body gives the :class:`~mechanics.scenes.state.Guide` whose
  coordinates are the body's state (:class:`~.capabilities.GuidesBody`).  Effects with
  **modes** (stick and slip, a tank that empties) switch them at events the engine
  locates (:class:`~.capabilities.HasModes`); an effect may report **series** and
  **conserved** quantities
  of its own physics.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, Any, ClassVar, Protocol, TypeAlias, TypeVar

import numpy as np
import numpy.typing as npt

from ..state import CoordFlow as CoordFlow
from ..state import ExactCoords as ExactCoords
from ..state import Pin as Pin
from ..vectors import FloatArray as FloatArray
from ..vectors import Times as Times
from ..vectors import cross

if TYPE_CHECKING:
    from ..state import Guide
    from ..trajectory import Event

__all__ = [
    "CONSERVED",
    "REGISTRY",
    "BodyLike",
    "Context",
    "CoordFlow",
    "Effect",
    "ExactCoords",
    "FloatArray",
    "Loads",
    "Pin",
    "SceneLike",
    "Schema",
    "Snapshot",
    "SpecLike",
    "Times",
    "check_joint_body",
    "check_on_fixed_axis",
    "gravity_vector",
    "keeps_for_force_along",
    "register",
    "unit",
]

#: the quantities an effect may keep (see :meth:`Effect.keeps`)
CONSERVED = ("p_x", "p_y", "p_z", "L_x", "L_y", "L_z", "E")

REGISTRY: dict[str, type[Effect]] = {}
#: an effect's fields: name -> (kind, required)
Schema: TypeAlias = dict[str, tuple[str, bool]]

_E = TypeVar("_E", bound="type[Effect]")


# What an effect reads of the scene file's parse (:mod:`mechanics.scenes.spec`, a higher
# layer that effects do not import, even for the type checker: tests/scenes/test_layers.py):
# the parts of its Body, EffectSpec and Scene that the effects use, as protocols.
class BodyLike(Protocol):
    """A body of the scene (:class:`mechanics.scenes.spec.Body`)."""

    @property
    def name(self) -> str: ...
    @property
    def shape(self) -> str: ...
    @property
    def mass(self) -> float: ...
    @property
    def dims(self) -> dict[str, Any]: ...
    @property
    def initial(self) -> dict[str, Any]: ...
    @property
    def fixed(self) -> bool: ...


class SpecLike(Protocol):
    """One listed effect (:class:`mechanics.scenes.spec.EffectSpec`)."""

    @property
    def type(self) -> str: ...
    @property
    def index(self) -> int: ...
    @property
    def fields(self) -> dict[str, Any]: ...
    @property
    def where(self) -> str: ...


class SceneLike(Protocol):
    """A validated scene (:class:`mechanics.scenes.spec.Scene`)."""

    @property
    def bodies(self) -> Sequence[BodyLike]: ...
    @property
    def effects(self) -> Sequence[SpecLike]: ...
    def body(self, name: str, /) -> BodyLike: ...
    def effects_of(self, kind: str, /) -> Sequence[SpecLike]: ...
    def error(self, field_: str, reason: str, /) -> Exception: ...


def register(cls: _E) -> _E:
    """Class decorator: make an effect type known by its ``type`` name."""
    if cls.type in REGISTRY:  # pragma: no cover - a programming error
        raise RuntimeError(f"effect type {cls.type!r} registered twice")
    REGISTRY[cls.type] = cls
    return cls


def unit(v: npt.ArrayLike) -> FloatArray:
    """v / |v| for a nonzero vector of any finite size: scaled by its largest component
    first, so that a subnormal or a huge direction (the parser takes any nonzero one)
    neither underflows nor overflows in the norm."""
    a = np.asarray(v, dtype=float)
    n = np.linalg.norm(a)
    if 1e-150 < n < 1e150:  # the squares are normal floats: the plain quotient
        out: FloatArray = a / n
        return out
    a = a / np.max(np.abs(a))
    out = a / np.linalg.norm(a)
    return out


@dataclass(frozen=True)
class Context:
    """What an effect may know of its scene: the bodies, their index by name, the
    layout's kinds (point, rigid, fixed) and the scene (for its errors)."""

    scene: SceneLike
    index: dict[str, int]
    kinds: tuple[str, ...]
    #: pinned bodies: index -> (C, g_A, J_C, J_C⁻¹), see :class:`~..state.Layout`
    pins: dict[int, Pin] = field(default_factory=dict)
    #: guided bodies (a fixed axis, rolling, sliding): index -> :class:`~..state.Guide`
    guides: dict[int, Guide] = field(default_factory=dict)
    #: per body, the speeds the impulses of the run so far have changed its points' by
    #: (Σ |Δv_G| + |Δω| |arm|): its velocities carry their rounding (the contacts'
    #: :meth:`~.impact.Impact.speed_scale`); zeroed when a run starts
    carried: FloatArray = field(default_factory=lambda: np.zeros(0))

    def body(self, name: str) -> BodyLike:
        return self.scene.bodies[self.index[name]]

    def _get_fixed(self) -> frozenset[int]:
        """The indices of the fixed bodies (worked out once: a group's pairs each ask)."""
        return frozenset(k for k, kind in enumerate(self.kinds) if kind == "fixed")

    fixed = cached_property(_get_fixed)


class Snapshot:
    """The bodies at one time, or at many (leading axes): r, v (O), L_A, ω_A (body
    components), R_A_O, masses m and principal moments J.  Shapes (..., n, 3),
    (..., n, 3, 3), (..., n).  Loads that switch on or off read ``phase``, not t."""

    __slots__ = (
        "J",
        "L_A",
        "R",
        "angle",
        "coords",
        "fluid",
        "inertia",
        "m",
        "omega",
        "phase",
        "r",
        "t",
        "v",
    )

    def __init__(
        self,
        t: Times,
        r: FloatArray,
        v: FloatArray,
        L_A: FloatArray,
        R: FloatArray,
        omega: FloatArray,
        m: FloatArray,
        J: FloatArray,
        phase: Times | None = None,
        angle: FloatArray | None = None,
    ) -> None:
        self.t, self.r, self.v, self.L_A, self.R = t, r, v, L_A, R
        self.omega, self.m, self.J = omega, m, J
        #: a guided body's first coordinate (a hinged body's angle φ about its axis; 0
        #: for the others), shape (..., n)
        self.angle = np.zeros(np.shape(m)) if angle is None else angle
        #: guided bodies: index -> (q, q̇), shapes (..., nq)
        self.coords: dict[int, tuple[FloatArray, FloatArray]] = {}
        #: guided bodies whose inertias M_k vary (mass flowing in): index -> M (..., nq)
        self.inertia: dict[int, FloatArray] = {}
        #: tanks: index -> their state (√h, volume out), shape (..., 2)
        self.fluid: dict[int, FloatArray] = {}
        #: the time that decides which loads are switched on: inside an integration
        #: segment between switch times, its midpoint (a stage at the segment's end
        #: still belongs to it); else t
        self.phase: Times = t if phase is None else phase

    def to_space(self, i: int, x_A: npt.ArrayLike) -> FloatArray:
        """Space components of a vector with body components x_A (R_A_Oᵀ x_A)."""
        out: FloatArray = np.einsum(
            "...ji,...j->...i", self.R[..., i, :, :], np.asarray(x_A, float)
        )
        return out

    def to_body(self, i: int, x_O: npt.ArrayLike) -> FloatArray:
        """Body components of a vector with space components x_O (R_A_O x_O)."""
        out: FloatArray = np.einsum(
            "...ij,...j->...i", self.R[..., i, :, :], np.asarray(x_O, float)
        )
        return out

    def point(self, i: int, at_A: npt.ArrayLike | None = None) -> FloatArray:
        """Position of the body point with body components ``at_A`` about G (None: G)."""
        if at_A is None:
            return self.r[..., i, :]
        return self.r[..., i, :] + self.to_space(i, at_A)

    def point_velocity(self, i: int, at_A: npt.ArrayLike | None = None) -> FloatArray:
        """Velocity of that body point: v_G + ω × (R_A_Oᵀ at_A) (2.66)."""
        if at_A is None:
            return self.v[..., i, :]
        w_O = self.to_space(i, self.omega[..., i, :])
        out: FloatArray = self.v[..., i, :] + cross(w_O, self.to_space(i, at_A))
        return out


class Loads:
    """Forces at G in O (n, 3) and moments about G in body components (n, 3), summed
    over the listed effects for one time."""

    __slots__ = ("F", "M_A", "rates", "snap")

    def __init__(self, n: int, snap: Snapshot) -> None:
        self.F = np.zeros((n, 3))
        self.M_A = np.zeros((n, 3))
        self.snap = snap
        #: a tank's state rates: index -> (d√h/dt, d(volume out)/dt)
        self.rates: dict[int, FloatArray] = {}

    def force(self, i: int, F_O: npt.ArrayLike, at_A: npt.ArrayLike | None = None) -> None:
        """Add the force F_O (space components) on body i, at the body point at_A (body
        components about G; None: at G).  Its moment about G is (Rᵀ at_A) × F_O, in body
        components at_A × (R F_O)."""
        F_O = np.asarray(F_O, dtype=float)
        self.F[i] += F_O
        if at_A is not None:
            self.M_A[i] += cross(at_A, self.snap.to_body(i, F_O))

    def moment(self, i: int, M_O: npt.ArrayLike) -> None:
        """Add a pure moment (a couple) with space components M_O on body i."""
        self.M_A[i] += self.snap.to_body(i, M_O)

    def moment_body(self, i: int, M_A: npt.ArrayLike) -> None:
        """Add a pure moment with body components M_A on body i."""
        self.M_A[i] += np.asarray(M_A, dtype=float)


class Effect:
    """Base class: holds the listed effect's spec; contributes nothing by itself."""

    type: ClassVar[str] = ""
    schema: ClassVar[Schema] = {}
    #: the SI unit of each field ("1": a pure number; "": a name or a word), and a
    #: minimal valid effect table: the scene-file reference is generated from these
    #: (:func:`mechanics.scenes.reference.scene_file_reference`)
    units: ClassVar[dict[str, str]] = {}
    example: ClassVar[dict[str, Any]] = {}

    def __init__(self, spec: SpecLike, ctx: Context | None = None) -> None:
        self.spec = spec
        self.fields = spec.fields
        self.ctx = ctx

    def _get_where(self) -> str:
        return self.spec.where

    where = property(_get_where)

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.fields})"

    @classmethod
    def expand(cls, spec: SpecLike, scene: SceneLike) -> list[SpecLike]:
        """The specs this listed one stands for (one effect object each): itself, unless
        it names a group (:meth:`.impact.Impact.expand`)."""
        return [spec]

    @classmethod
    def check(cls, spec: SpecLike, scene: SceneLike, index: dict[str, int]) -> None:
        """Validate the combination of this effect with the scene (fields are checked
        one by one by the parser); raise ``scene.error(field, reason)``."""

    #: it never adds mechanical energy: it takes some (friction, drag) or does no work (an
    #: ideal joint); with only such effects and potentials, E(t) may not rise
    #: (the self-check "energy never rises")
    dissipative: ClassVar[bool] = False

    #: an effect that reads the other effects' loads (a friction that needs the normal
    #: force) sets this: the engine sums it after all the others
    after_loads: ClassVar[bool] = False

    def series(self, s: Snapshot) -> dict[str, FloatArray]:
        """Named series of this effect's own state (a tank's level), from snapshots."""
        return {}

    def conserved(self, s: Snapshot) -> dict[str, tuple[FloatArray, float]]:
        """Quantities of this effect's own physics that the run conserves: name ->
        (samples, the size of their terms)."""
        return {}

    # contributions (the engine calls them only on listed effects)
    def loads(self, t: float, s: Snapshot, out: Loads) -> None:
        """Add this effect's forces and moments at time t."""

    def keeps(self, quantity: str) -> bool:
        """Does this effect leave ``quantity`` (one of :data:`CONSERVED`) unchanged?"""
        return False

    def exerts_moment(self, k: int) -> bool:
        """Can this effect exert a moment about the centre of mass of body k?  (The
        default claims nothing: yes.)  A body no listed effect turns keeps its spin
        angular momentum about G."""
        return True

    def switch_times(self) -> list[float]:
        """Instants where the effect switches on or off (step boundaries)."""
        return []

    def acts_until(self, events: Iterable[Event] = (), quantity: str | None = None) -> float:
        """The time after which this effect no longer acts (inf: to the end), given the
        run's ``events``; what it breaks is conserved from then on.  With ``quantity``:
        after which it no longer changes that quantity (a friction that sticks still
        pushes, but does no work)."""
        return math.inf


def check_joint_body(
    spec: SpecLike,
    scene: SceneLike,
    index: dict[str, int],
    *,
    what: str,
    keys: tuple[str, ...] | None,
) -> None:
    """The checks every joint makes of its body: a rigid, moving body; no thrust (its
    mass cannot change); and, when ``keys`` is given, only those initial keys (the joint
    decides the rest).  (A joint listed twice is refused with the other constraints, in
    :func:`mechanics.scenes.engine.validate`.)"""
    b = scene.body(spec.fields["body"])
    if b.shape in ("point", "tank") or b.fixed:
        kind = "fixed" if b.fixed else f"a {b.shape}"
        raise scene.error(f"{spec.where}.body", f"body {b.name!r} is {kind}: {what}")
    for e in scene.effects:
        if e.type == "thrust" and e.fields["body"] == b.name:
            raise scene.error(
                f"{e.where}.body", f"body {b.name!r} is held by a joint: its mass cannot change"
            )
    if keys is not None:
        for k in b.initial:
            if k not in keys:
                raise scene.error(
                    f"bodies[{index[b.name]}].initial.{k}",
                    f"a body on a {spec.type} takes {', '.join(keys)}",
                )


def gravity_vector(scene: SceneLike) -> FloatArray:
    """The sum g·d of the scene's listed gravity effects, from their fields (before any
    effect object exists: the joints' guides and checks read it)."""
    g = np.zeros(3)
    for e in scene.effects_of("gravity"):
        d = np.asarray(e.fields.get("direction", [0.0, 0.0, -1.0]), dtype=float)
        g = g + float(e.fields["g"]) * d / float(np.linalg.norm(d))
    return g


def check_on_fixed_axis(spec: SpecLike, scene: SceneLike, *, what: str) -> None:
    """An effect that acts on a body turning on a fixed axis (a torsion spring, mass
    flowing in) needs a ``fixed_axis`` for that body; ``what`` says what it does."""
    name = spec.fields["body"]
    if not any(e.fields["body"] == name for e in scene.effects_of("fixed_axis")):
        raise scene.error(f"{spec.where}.type", f"{what}: list a fixed_axis for {name!r}")


def _axis_index(q: str) -> int:
    return "xyz".index(q[-1])


def keeps_for_force_along(direction: npt.ArrayLike, quantity: str) -> bool:
    """What forces along one fixed ``direction`` keep, wherever they act: the momentum
    components across it, and the angular momentum about the origin along it (a moment
    r × F d is ⟂ d).  Energy: not by this rule."""
    d = unit(direction)
    if quantity.startswith("p_"):
        return bool(abs(d[_axis_index(quantity)]) == 0.0)
    if quantity.startswith("L_"):  # (Σ m r) × F d is ⟂ d: only the component along d
        k = _axis_index(quantity)
        return bool(np.all(np.delete(d, k) == 0.0))
    return False
