"""The one interface of an effect, the snapshot of the bodies it reads, and the loads it adds.

Conventions
-----------
- **Registered by name.**  An effect is a class with a ``type`` (the name a scene file
  lists) and a ``schema`` ``{field: (kind, required)}`` that the scene file's parser
  checks (kinds: see ``mechanics.scenes.spec.check_field``).  :func:`register`
  adds it to :data:`REGISTRY`.  An object is built only for an effect the scene
  lists; no code of an unlisted effect runs.
- **What an effect may contribute** (each optional, the base class contributes
  nothing): :meth:`Effect.loads` adds forces (in the space basis O, at a point given in
  body components about G, or at G) and moments to a :class:`Loads`; a potential
  energy, mass lost, inertia added, modes or a guide, each declared by a protocol of
  :mod:`.capabilities` among the class's bases; ``keeps`` says which of the total
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
    """A body of the scene (:class:`mechanics.scenes.spec.Body`), as the effects read it.

    Its read-only members: ``name``, ``shape``, ``mass`` (kg), ``dims`` (m), ``initial``
    (the body's initial table, SI) and ``fixed``.

    Examples
    --------
    The parser's Body has every member the effects read:

    >>> from mechanics.scenes.spec import Body
    >>> b = Body("ball", "point", 2.0, {}, {})
    >>> [k for k in ("name", "shape", "mass", "dims", "initial", "fixed") if not hasattr(b, k)]
    []
    >>> BodyLike()
    Traceback (most recent call last):
    ...
    TypeError: Protocols cannot be instantiated
    """

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
    """One listed effect (:class:`mechanics.scenes.spec.EffectSpec`), as the effects read it.

    Its read-only members: ``type`` (the effect's registered name), ``index`` (its
    position in the scene file's effects), ``fields`` (its table, SI) and ``where`` (the
    field path its errors name, ``effects[index]``).

    Examples
    --------
    >>> from mechanics.scenes.spec import EffectSpec
    >>> spec = EffectSpec("gravity", 2, {"g": 9.81})
    >>> spec.where, f"effects[{spec.index}]"
    ('effects[2]', 'effects[2]')
    """

    @property
    def type(self) -> str: ...
    @property
    def index(self) -> int: ...
    @property
    def fields(self) -> dict[str, Any]: ...
    @property
    def where(self) -> str: ...


class SceneLike(Protocol):
    """A validated scene (:class:`mechanics.scenes.spec.Scene`), as the effects read it.

    Its members: ``bodies``, ``effects``, ``body(name)``, ``effects_of(kind)`` (the
    listed effects of one type) and ``error(field, reason)`` (the exception to raise,
    naming the scene file, the field and the reason).

    Examples
    --------
    >>> from mechanics.scenes.spec import parse_scene
    >>> sc = parse_scene({"scene": {"name": "x", "duration": 1.0},
    ...                   "bodies": [{"name": "ball", "shape": "point", "mass": 2.0}]})
    >>> sc.body("ball") is sc.bodies[0], sc.effects_of("gravity")
    (True, [])
    """

    @property
    def bodies(self) -> Sequence[BodyLike]: ...
    @property
    def effects(self) -> Sequence[SpecLike]: ...
    def body(self, name: str, /) -> BodyLike: ...
    def effects_of(self, kind: str, /) -> Sequence[SpecLike]: ...
    def error(self, field_: str, reason: str, /) -> Exception: ...


def register(cls: _E) -> _E:
    """Class decorator: make an effect type known by its ``type`` name.

    The decorated class ``cls`` (an :class:`Effect`) carries its ``type``, the name a
    scene file lists.

    Returns
    -------
    type[Effect]
        ``cls`` itself, now in :data:`REGISTRY` under ``cls.type``.

    Raises
    ------
    RuntimeError
        If an effect of that ``type`` is registered already (a programming error).

    Examples
    --------
    >>> from mechanics.scenes.effects.gravity import Gravity
    >>> REGISTRY["gravity"] is Gravity, Gravity.type
    (True, 'gravity')
    >>> register(Gravity)
    Traceback (most recent call last):
    ...
    RuntimeError: effect type 'gravity' registered twice
    """
    if cls.type in REGISTRY:  # pragma: no cover - a programming error
        raise RuntimeError(f"effect type {cls.type!r} registered twice")
    REGISTRY[cls.type] = cls
    return cls


def unit(v: npt.ArrayLike) -> FloatArray:
    """The unit vector v / |v| of a nonzero vector of any finite size.

    Where the largest component is outside 1e-150 < |v_i| < 1e150, the vector is scaled by
    it before the norm is taken, so that a subnormal or a huge direction (the parser takes
    any nonzero one, up to float64's largest) neither underflows nor overflows in the norm
    (for k < 1e8 components: k·1e300 fits float64).

    Parameters
    ----------
    v : array_like, shape (k,)
        A nonzero, finite vector (a direction; any unit, k ≥ 1).

    Returns
    -------
    ndarray, shape (k,)
        v / |v|, of norm 1 to rounding.

    Raises
    ------
    ValueError
        Where ``v`` is a string that is not a number, or ragged (numpy's conversion).
    TypeError
        Where ``v`` is of a type that has no float value (numpy's conversion).

    Warns
    -----
    RuntimeWarning
        For a zero vector (invalid division: the result is nan); never for a nonzero one.

    Examples
    --------
    A 3-4-5 direction, tiny or not, gives the same unit vector:

    >>> unit([3.0, 0.0, 4.0]).tolist(), unit([3e-300, 0.0, 4e-300]).tolist()
    ([0.6, 0.0, 0.8], [0.6, 0.0, 0.8])
    >>> unit([3e300, 0.0, 4e300]).tolist()
    [0.6, 0.0, 0.8]
    """
    a = np.asarray(v, dtype=float)
    m = np.max(np.abs(a))
    if 1e-150 < m < 1e150:  # the largest square is a normal float, no sum overflows
        out: FloatArray = a / np.linalg.norm(a)
        return out
    a = a / m  # the largest component is ±1: the norm is between 1 and √k
    out = a / np.linalg.norm(a)
    return out


@dataclass(frozen=True)
class Context:
    """What an effect may know of its scene: its bodies, their index, kinds, pins and guides.

    The scene (its bodies, and its errors), the bodies' index by name, the layout's
    kinds (point, rigid, fixed, ...), and the pinned and guided bodies (built by the engine's
    model, :class:`mechanics.scenes.model.Model`).

    Parameters
    ----------
    scene : SceneLike
        The validated scene.
    index : dict[str, int]
        Body name -> its index in ``scene.bodies``.
    kinds : tuple[str, ...]
        Each body's kind in the layout: ``"point"``, ``"rigid"``, ``"pinned"``,
        ``"guided"``, ``"tank"`` or ``"fixed"``.
    pins : dict[int, Pin], optional
        Pinned bodies: index -> (C, g_A, J_C, J_C⁻¹). Default none.
    guides : dict[int, Guide], optional
        Guided bodies (a fixed axis, rolling, sliding): index -> their guide. Default none.
    carried : ndarray, shape (n,), optional
        Per body, the speeds (m/s) the run's impulses have changed its points by
        (Σ |Δv_G| + |Δω| |arm|). Default an empty array.

    Examples
    --------
    >>> from mechanics.scenes.spec import parse_scene
    >>> sc = parse_scene({"scene": {"name": "x", "duration": 1.0},
    ...                   "bodies": [{"name": "ball", "shape": "point", "mass": 2.0}]})
    >>> ctx = Context(sc, {"ball": 0}, ("point",))
    >>> ctx.body("ball") is sc.bodies[0], ctx.fixed
    (True, frozenset())
    """

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
    """The n bodies at one time, or at many (leading axes): their positions, velocities, spins.

    r, v (O), L_A, ω_A (body components), R_A_O, masses m and principal moments J.
    Shapes (..., n, 3), (..., n, 3, 3), (..., n).  Loads that switch on or off read
    ``phase``, not t.  The arrays are stored as given (not copied, not checked).

    Parameters
    ----------
    t : float or ndarray, shape (...)
        The time(s), s.
    r : ndarray, shape (..., n, 3)
        Positions of the centres of mass G (space components, m).
    v : ndarray, shape (..., n, 3)
        Velocities of G (space components, m/s).
    L_A : ndarray, shape (..., n, 3)
        Angular momenta about G (body components, kg m²/s).
    R : ndarray, shape (..., n, 3, 3)
        Attitudes R_A_O (passive: body components R x of a space vector x).
    omega : ndarray, shape (..., n, 3)
        Angular velocities ω (body components, rad/s).
    m : ndarray, shape (..., n)
        Masses, kg.
    J : ndarray, shape (..., n, 3)
        Principal moments of inertia about G, kg m².
    phase : float or ndarray, shape (...), optional
        The time that decides which loads are switched on (default t).
    angle : ndarray, shape (..., n), optional
        A guided body's first coordinate (a hinged body's angle φ, rad); default 0.

    Examples
    --------
    The velocity of a body point is v_G + ω × (R_A_Oᵀ at) (2.66):

    >>> z = np.zeros((1, 3))
    >>> w = np.array([[0.0, 0.0, 2.0]])
    >>> s = Snapshot(0.0, z, z, z, np.eye(3)[None], w, np.ones(1), z + 1.0)
    >>> s.point_velocity(0, [1.0, 0.0, 0.0]).tolist(), np.cross(w[0], [1.0, 0.0, 0.0]).tolist()
    ([0.0, 2.0, 0.0], [0.0, 2.0, 0.0])
    """

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
    """The forces at G and moments about G on n bodies, summed over the effects at one time.

    ``F`` (n, 3): forces at G, space components (N); ``M_A`` (n, 3): moments about G,
    body components (N m); ``rates``: a tank's state rates.  Both start at zero.

    Parameters
    ----------
    n : int
        The number of bodies, ≥ 0.
    snap : Snapshot
        The bodies at that time (its attitudes turn the moments into body components).

    Raises
    ------
    ValueError
        If ``n`` < 0 (numpy's zeros).
    TypeError
        If ``n`` is not an integer.

    Examples
    --------
    A force F at the body point ``at`` has the moment at × F about G (identity attitude):

    >>> z = np.zeros((1, 3))
    >>> out = Loads(1, Snapshot(0.0, z, z, z, np.eye(3)[None], z, np.ones(1), z + 1.0))
    >>> out.force(0, [0.0, 3.0, 0.0], at_A=[2.0, 0.0, 0.0])
    >>> out.M_A[0].tolist(), np.cross([2.0, 0.0, 0.0], [0.0, 3.0, 0.0]).tolist()
    ([0.0, 0.0, 6.0], [0.0, 0.0, 6.0])
    """

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
    """Base class of the effects: holds the listed effect's spec; contributes nothing itself.

    Parameters
    ----------
    spec : SpecLike
        The listed effect (its ``type``, ``index`` and ``fields``, checked by the parser).
    ctx : Context or None, optional
        The scene's context (None: an effect built for its geometry alone, as the
        joints' checks do).

    Examples
    --------
    The base class adds no load, keeps nothing and never switches:

    >>> from mechanics.scenes.spec import EffectSpec
    >>> e = Effect(EffectSpec("none", 3, {}))
    >>> e.where, e.keeps("E"), e.switch_times(), e.acts_until()
    ('effects[3]', False, [], inf)
    """

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
    """The checks every joint makes of its body: rigid, moving, no thrust, only its keys.

    A rigid, moving body; no thrust (its mass cannot change); and, when ``keys`` is
    given, only those initial keys (the joint decides the rest).  (A joint listed twice
    is refused with the other constraints, in :func:`mechanics.scenes.engine.validate`.)

    Parameters
    ----------
    spec : SpecLike
        The joint's listed effect (its field ``body`` names the body).
    scene : SceneLike
        The scene.
    index : dict[str, int]
        Body name -> index (for the field path of an initial key).
    what : str
        What the joint cannot do with a point, a tank or a fixed body (the error's words).
    keys : tuple of str or None
        The initial keys a body on this joint takes (None: any).

    Raises
    ------
    SceneError
        The exception ``scene.error`` makes (a :class:`SceneError` for a parsed scene):
        for a point, a tank or a fixed body; a thrust on the body; an initial key not in
        ``keys``.

    Examples
    --------
    >>> from mechanics.scenes.spec import EffectSpec, parse_scene
    >>> sc = parse_scene({"scene": {"name": "x", "duration": 1.0},
    ...                   "bodies": [{"name": "ball", "shape": "point", "mass": 2.0}]})
    >>> spec = EffectSpec("fixed_point", 0, {"body": "ball"})
    >>> check_joint_body(spec, sc, {"ball": 0}, what="it cannot be pinned", keys=None)
    Traceback (most recent call last):
    ...
    mechanics.scenes.errors.SceneError: <scene>: effects[0].body: body 'ball' is a point: it \
cannot be pinned
    """
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
    """The sum g·d of the scene's listed gravity effects, read from their fields.

    Read before any effect object exists: the joints' guides and checks use it.

    Parameters
    ----------
    scene : SceneLike
        The scene; its ``gravity`` effects have ``g`` (m/s², > 0) and an optional
        nonzero ``direction`` (default (0, 0, −1)).

    Returns
    -------
    ndarray, shape (3,)
        Σ g d/|d| over the listed gravities, m/s² (zero if none is listed).

    Raises
    ------
    KeyError
        If a gravity effect has no ``g`` (the parser requires it).

    Examples
    --------
    Two gravities add (the weights of a body add):

    >>> from mechanics.scenes.spec import parse_scene
    >>> sc = parse_scene({"scene": {"name": "x", "duration": 1.0},
    ...                   "bodies": [{"name": "ball", "shape": "point", "mass": 2.0}],
    ...                   "effects": [{"type": "gravity", "g": 9.75},
    ...                               {"type": "gravity", "g": 0.25, "direction": [0, 0, -2]}]})
    >>> gravity_vector(sc).tolist()
    [0.0, 0.0, -10.0]
    """
    g = np.zeros(3)
    for e in scene.effects_of("gravity"):
        d = np.asarray(e.fields.get("direction", [0.0, 0.0, -1.0]), dtype=float)
        g = g + float(e.fields["g"]) * d / float(np.linalg.norm(d))
    return g


def check_on_fixed_axis(spec: SpecLike, scene: SceneLike, *, what: str) -> None:
    """Refuse an effect that acts on a body turning on a fixed axis where none is listed.

    A torsion spring or mass flowing in needs a ``fixed_axis`` for that body.

    Parameters
    ----------
    spec : SpecLike
        The effect (its field ``body`` names the body).
    scene : SceneLike
        The scene.
    what : str
        What the effect does (the error's words).

    Raises
    ------
    SceneError
        The exception ``scene.error`` makes (a :class:`SceneError` for a parsed scene),
        where no ``fixed_axis`` holds the body.

    Examples
    --------
    >>> from mechanics.scenes.spec import EffectSpec, parse_scene
    >>> sc = parse_scene({"scene": {"name": "x", "duration": 1.0},
    ...                   "bodies": [{"name": "ball", "shape": "point", "mass": 2.0}]})
    >>> check_on_fixed_axis(EffectSpec("torsion", 0, {"body": "ball"}), sc, what="it twists")
    Traceback (most recent call last):
    ...
    mechanics.scenes.errors.SceneError: <scene>: effects[0].type: it twists: list a fixed_axis \
for 'ball'
    """
    name = spec.fields["body"]
    if not any(e.fields["body"] == name for e in scene.effects_of("fixed_axis")):
        raise scene.error(f"{spec.where}.type", f"{what}: list a fixed_axis for {name!r}")


def _axis_index(q: str) -> int:
    return "xyz".index(q[-1])


def keeps_for_force_along(direction: npt.ArrayLike, quantity: str) -> bool:
    """Do forces along one fixed ``direction``, wherever they act, keep ``quantity``?

    They keep the momentum components across it, and the angular momentum about the
    origin along it (a moment r × F d is ⟂ d).  Energy: not by this rule.

    Parameters
    ----------
    direction : array_like, shape (3,)
        The forces' direction, nonzero (any length).
    quantity : str
        One of :data:`CONSERVED`: ``p_x``, ``p_y``, ``p_z``, ``L_x``, ``L_y``, ``L_z``,
        ``E``.

    Returns
    -------
    bool
        True where the quantity is kept (never for ``E``, or a name that is not a
        component).

    Raises
    ------
    ValueError
        For a name ``p_…`` or ``L_…`` that does not end in x, y or z.

    Examples
    --------
    A vertical force keeps p_x, p_y and L_z, and not p_z, L_x:

    >>> [q for q in CONSERVED if keeps_for_force_along([0.0, 0.0, -1.0], q)]
    ['p_x', 'p_y', 'L_z']
    """
    d = unit(direction)
    if quantity.startswith("p_"):
        return bool(abs(d[_axis_index(quantity)]) == 0.0)
    if quantity.startswith("L_"):  # (Σ m r) × F d is ⟂ d: only the component along d
        k = _axis_index(quantity)
        return bool(np.all(np.delete(d, k) == 0.0))
    return False
