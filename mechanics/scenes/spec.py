"""The scene file: a TOML schema, parsed with :mod:`tomllib` and validated field by field.

Conventions
-----------
- **Units: SI only.**  Every value is a plain TOML number in SI units (m, kg, s, rad,
  N/m, N·m/rad, kg/s, m/s, m²).  A string such as ``"9.81 m/s^2"`` is rejected: units
  are never parsed.  An optional ``[units]`` table may say ``system = "SI"``; any other
  system is an error.
- **Nothing is evaluated as code**: no evaluation of text and no symbolic parsing;
  numbers are TOML numbers.
- Every error is a :class:`SceneError` (a ``ValueError``) whose message reads
  ``<file>: <field>: <reason>``, e.g. ``ball.toml: effects[1].restitution: must lie in
  [0, 1]; got 1.2``.
- Angles are radians; vectors are arrays of 3 numbers in the space frame O (z up unless
  the gravity effect says otherwise); ``omega`` of a free body is in body components.

Schema
------
``[scene]``: ``name`` (str), ``title`` (str, optional), ``book`` (str, optional),
``duration`` (> 0), ``samples`` (int ≥ 2, default 201), ``method`` (``"auto"``: the exact
flow where the effects have one, else integration; ``"exact"``: fail if there is none;
``"integrate"``: always integrate; ``"splitting"``: the symplectic splitting of a
conservative scene, :mod:`mechanics.scenes.splitting`, with ``step`` (> 0, default the
sample interval) and ``order`` (2, 4 or 6, default 4)), ``rtol``/``atol`` of the
integrator (default 1e-12),
``compare`` (optional: the name of a book comparison; :mod:`mechanics` carries it as
a label, the book layer :mod:`identities.book.scenes.compare` knows the comparisons).

``[[bodies]]``: ``name``, ``shape`` (one of :data:`SHAPES`) with its dimensions, ``mass``
(not for a tank), ``fixed`` (optional boolean: the body stays where it is, an immovable
partner of contacts and springs), and an ``[bodies.initial]`` table (keys in
:data:`INITIAL_KEYS`; a free rigid body's attitude by its Euler angles psi, theta, phi).

``[[effects]]``: ``type`` (one of :data:`EFFECT_FIELDS`) and its fields.  Only the listed
effects act: there is no default gravity, no damping, no position correction.
"""

from __future__ import annotations

import math
import re
import tomllib
from collections.abc import Collection, Iterable
from dataclasses import dataclass, field
from os import PathLike
from pathlib import Path
from typing import Any

from .budget import DEFAULT_MAX_SECONDS, DEFAULT_MAX_STEPS
from .domain import RTOL_MIN, check_magnitude, check_value
from .effects import EFFECT_CLASSES
from .errors import SceneError
from .state import ROUND_SHAPES, SPHERICAL_SHAPES
from .trajectory import DEFAULT_TOL as _DEFAULT_TOL

__all__ = [
    "EFFECT_FIELDS",
    "INITIAL_KEYS",
    "METHODS",
    "ROUND_SHAPES",
    "SHAPES",
    "SPHERICAL_SHAPES",
    "Body",
    "EffectSpec",
    "Scene",
    "SceneError",
    "load_scene",
    "parse_scene",
]


#: the integrator's default rtol and atol (defined with the run's result types)
DEFAULT_TOL = _DEFAULT_TOL

#: shape -> the dimensions it needs (in SI metres); "custom" takes principal moments.
SHAPES: dict[str, tuple[str, ...]] = {
    "point": (),
    "rod": ("length",),
    "ring": ("radius",),
    "disc": ("radius",),
    "cylinder": ("radius", "height"),
    "cylindrical_shell": ("radius", "height"),
    "solid_sphere": ("radius",),
    "hollow_sphere": ("radius",),
    "rectangular_plate": ("a", "b"),
    "box": ("a", "b", "c"),
    "custom": ("inertia",),
    "tank": ("area",),
}

#: the SI unit of each body dimension
DIMENSION_UNITS = {
    "length": "m",
    "radius": "m",
    "height": "m",
    "a": "m",
    "b": "m",
    "c": "m",
    "inertia": "kg m²",
    "area": "m²",
}

#: the [scene] table's fields: name -> (kind, unit, meaning)
SCENE_FIELDS: dict[str, tuple[str, str, str]] = {
    "name": ("str", "", "required: the scene's name"),
    "title": ("str", "", "a title for plots and reports"),
    "book": ("str", "", "the book reference it illustrates"),
    "compare": ("str", "", "the book comparison to run (identities.book.scenes.compare)"),
    "duration": ("positive", "s", "required: the simulated time"),
    "samples": ("integer ≥ 2", "1", "samples over [0, duration] (default 201)"),
    "method": ("str", "", "auto (default), exact, integrate or splitting"),
    "rtol": ("positive", "1", "the integrator's relative tolerance (default 1e-12)"),
    "atol": ("positive", "(state units)", "its absolute tolerance (default 1e-12)"),
    "step": ("positive", "s", "the splitting's step (default: the sample interval)"),
    "order": ("2, 4 or 6", "1", "the splitting's order (default 4)"),
    "max_samples": (
        "integer ≥ 2",
        "1",
        "the samples a run may hold (default: what the memory budget of "
        "mechanics.scenes.budget holds); --max-samples overrides it",
    ),
    "max_steps": (
        "integer ≥ 1",
        "1",
        f"the steps an integrated run may take (default {DEFAULT_MAX_STEPS}); --max-steps",
    ),
    "max_seconds": (
        "positive",
        "s",
        f"the wall time a run may take (default {DEFAULT_MAX_SECONDS:g}); --max-seconds",
    ),
}

#: initial-state keys: name -> (unit, meaning)
INITIAL_DOC: dict[str, tuple[str, str]] = {
    "position": ("m", "a free body: its centre of mass"),
    "velocity": ("m/s", "a free body: the velocity of its centre of mass"),
    "omega": ("rad/s", "a free rigid body: angular velocity, body components"),
    "angle": ("rad", "a fixed axis: φ from gravity's direction; a track: ψ"),
    "angular_velocity": ("rad/s", "a fixed axis: φ̇; a track: ψ̇"),
    "distance": ("m", "rolling or sliding: along the plane"),
    "speed": ("m/s", "rolling or sliding: of G along the plane"),
    "spin": ("rad/s", "sliding: ω (positive: the rolling sense)"),
    "theta": ("rad", "Euler angles z-x-z of a rigid body (a top: from the vertical)"),
    "psi": ("rad", "Euler angle ψ"),
    "phi": ("rad", "Euler angle φ"),
    "theta_dot": ("rad/s", "a top's Euler rate θ̇ (instead of omega)"),
    "psi_dot": ("rad/s", "a top's Euler rate ψ̇"),
    "phi_dot": ("rad/s", "a top's Euler rate φ̇"),
    "level": ("m", "a tank: the surface's height above the hole"),
}

#: initial-state keys: name -> kind
INITIAL_KEYS: dict[str, str] = {
    "position": "vector",  # free body: centre of mass, m
    "velocity": "vector",  # free body: m/s
    "omega": "vector",  # free body: angular velocity, body components, rad/s
    "angle": "number",  # fixed axis: φ from the downward vertical; track: ψ
    "angular_velocity": "number",  # fixed axis φ̇, track ψ̇
    "distance": "number",  # rolling/sliding: along the plane, m
    "speed": "number",  # rolling/sliding: speed of G along the plane
    "spin": "number",  # sliding: ω (positive = the rolling sense)
    "theta": "number",  # fixed point, free rigid body: Euler angles z-x-z (and rates)
    "psi": "number",
    "phi": "number",
    "theta_dot": "number",
    "psi_dot": "number",
    "phi_dot": "number",
    "level": "number",  # tank: height of the surface above the hole, m
}

#: effect type -> {field: (kind, required)}, from each effect's ``schema``; kinds: body,
#: bodies (an array of body names), planes (an array of {point, normal} tables),
#: number, positive, nonnegative, restitution, vector,
#: str, axis_name, frame ("space" or "body"), impact_model ("auto" or "sequential")
EFFECT_FIELDS: dict[str, dict[str, tuple[str, bool]]] = {
    t: cls.schema for t, cls in EFFECT_CLASSES.items()
}

METHODS = ("auto", "exact", "integrate", "splitting")
#: the orders of the splitting (:mod:`mechanics.scenes.splitting`)
SPLITTING_ORDERS = (2, 4, 6)
_NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_\-]*$")


@dataclass(frozen=True)
class Body:
    """A body of the scene: its shape, mass, dimensions and initial state (SI).

    Built by :func:`parse_scene`, which checks each field; the constructor stores what
    it is given and checks nothing.

    Parameters
    ----------
    name : str
        The body's name (an identifier, unique in the scene).
    shape : str
        One of :data:`SHAPES`.
    mass : float
        The mass, kg, > 0 (0 for a tank, which has none).
    dims : dict[str, Any]
        The dimensions the shape needs (:data:`SHAPES`), in SI units
        (``DIMENSION_UNITS``: m; a custom body's principal moments, kg m²).
    initial : dict[str, Any]
        The initial state, keys in :data:`INITIAL_KEYS` (units: ``INITIAL_DOC``).
    fixed : bool, optional
        The body stays where it is, an immovable partner of contacts and springs.
        Default False.

    Examples
    --------
    The body a scene's table describes, and the same built directly:

    >>> sc = parse_scene({"scene": {"name": "fall", "duration": 1.0, "samples": 3},
    ...                   "bodies": [{"name": "ball", "shape": "point", "mass": 2.0,
    ...                               "initial": {"position": [0.0, 0.0, 4.0]}}],
    ...                   "effects": [{"type": "gravity", "g": 8.0}]})
    >>> sc.bodies[0] == Body("ball", "point", 2.0, {}, {"position": [0.0, 0.0, 4.0]})
    True
    """

    name: str
    shape: str
    mass: float
    dims: dict[str, Any]
    initial: dict[str, Any]
    fixed: bool = False


@dataclass(frozen=True)
class EffectSpec:
    """One listed effect: its type, its position in the file and its fields.

    Built by :func:`parse_scene`, which checks each field against the effect's schema
    (:data:`EFFECT_FIELDS`); the constructor stores what it is given and checks nothing.

    Parameters
    ----------
    type : str
        The effect's type, a key of :data:`EFFECT_FIELDS` (``"gravity"``, ``"impact"``,
        ...).
    index : int
        Its position in the file's ``[[effects]]`` array, ≥ 0 (errors name
        ``effects[index]``).
    fields : dict[str, Any]
        Its fields, checked and in SI units (the effect's ``units``).

    Examples
    --------
    The effect a scene lists, and the same built directly; errors name it by its
    place:

    >>> sc = parse_scene({"scene": {"name": "fall", "duration": 1.0, "samples": 3},
    ...                   "bodies": [{"name": "ball", "shape": "point", "mass": 2.0,
    ...                               "initial": {"position": [0.0, 0.0, 4.0]}}],
    ...                   "effects": [{"type": "gravity", "g": 8.0}]})
    >>> spec = EffectSpec("gravity", 0, {"g": 8.0})
    >>> sc.effects[0] == spec, spec.where
    (True, 'effects[0]')
    """

    type: str
    index: int
    fields: dict[str, Any]

    def _get_where(self) -> str:
        return f"effects[{self.index}]"

    where = property(_get_where)


@dataclass(frozen=True)
class Scene:
    """A validated scene: its bodies, its effects and how it is run.

    Built by :func:`parse_scene` (or :func:`load_scene`), which checks each field and
    their combination; the constructor stores what it is given and checks nothing.  The
    fields are those of the ``[scene]`` table (``SCENE_FIELDS``).

    Parameters
    ----------
    name : str
        The scene's name.
    source : str
        Where it was read from (a file's path, or ``"<scene>"``): errors name it.
    duration : float
        The simulated time, s, > 0.
    samples : int
        Samples over [0, duration], ≥ 2.
    method : str
        One of :data:`METHODS`: ``"auto"``, ``"exact"``, ``"integrate"`` or
        ``"splitting"``.
    rtol : float
        The integrator's relative tolerance, in [100 eps, 1e-3].
    atol : float
        Its absolute tolerance (state units), in (0, 1e-3].
    bodies : tuple[Body, ...]
        The bodies, in file order, at least one.
    effects : tuple[EffectSpec, ...]
        The listed effects, in file order (the only ones that act).
    title : str, optional
        A title for plots and reports. Default empty.
    book : str, optional
        The book reference it illustrates. Default empty.
    compare : str, optional
        The name of a book comparison (:mod:`identities.book.scenes.compare`). Default
        empty.
    raw : dict[str, Any], optional
        The parsed TOML it was validated from (not compared). Default empty.
    step : float or None, optional
        The splitting's step, s, > 0; None (default): the sample interval.
    order : int, optional
        The splitting's order, 2, 4 or 6. Default 4.
    max_samples : int or None, optional
        The samples a run may hold, ≥ 2; None (default): what the memory budget holds
        (:mod:`.budget`).
    max_steps : int, optional
        The steps an integrated run may take, ≥ 1. Default ``DEFAULT_MAX_STEPS``.
    max_seconds : float, optional
        The wall time a run may take, s, > 0. Default ``DEFAULT_MAX_SECONDS``.

    Examples
    --------
    The scene parsed from its tables, and the same built directly:

    >>> sc = parse_scene({"scene": {"name": "fall", "duration": 1.0, "samples": 3},
    ...                   "bodies": [{"name": "ball", "shape": "point", "mass": 2.0,
    ...                               "initial": {"position": [0.0, 0.0, 4.0]}}],
    ...                   "effects": [{"type": "gravity", "g": 8.0}]})
    >>> Scene("fall", "<scene>", 1.0, 3, "auto", 1e-12, 1e-12, sc.bodies, sc.effects) == sc
    True
    >>> sc.body("ball") is sc.bodies[0], str(sc.error("scene.duration", "too long"))
    (True, '<scene>: scene.duration: too long')
    """

    name: str
    source: str
    duration: float
    samples: int
    method: str
    rtol: float
    atol: float
    bodies: tuple[Body, ...]
    effects: tuple[EffectSpec, ...]
    title: str = ""
    book: str = ""
    compare: str = ""
    raw: dict[str, Any] = field(default_factory=dict, compare=False, repr=False)
    #: the splitting's step (None: the sample interval) and order
    step: float | None = None
    order: int = 4
    #: the run's limits (:mod:`.budget`): samples (None: what the memory budget holds),
    #: steps and wall time
    max_samples: int | None = None
    max_steps: int = DEFAULT_MAX_STEPS
    max_seconds: float = DEFAULT_MAX_SECONDS

    def body(self, name: str) -> Body:
        return next(b for b in self.bodies if b.name == name)

    def effects_of(self, kind: str) -> list[EffectSpec]:
        return [e for e in self.effects if e.type == kind]

    def _get_effect_types(self) -> tuple[str, ...]:
        return tuple(e.type for e in self.effects)

    effect_types = property(_get_effect_types)

    def error(self, field_: str, reason: str) -> SceneError:
        return SceneError(self.source, field_, reason)


# ------------------------------------------------------------------ field checks


def _type_name(v: Any) -> str:
    return {str: "a string", bool: "a boolean", dict: "a table", list: "an array"}.get(
        type(v), type(v).__name__
    )


def _number(src: str, where: str, v: Any) -> float:
    if isinstance(v, bool) or not isinstance(v, int | float):
        hint = ""
        if isinstance(v, str):
            hint = " (units are not parsed: write the value as a plain number in SI units)"
        raise SceneError(
            src, where, f"expected a number in SI units, got {_type_name(v)} {v!r}{hint}"
        )
    x = float(v)
    if not math.isfinite(x):
        raise SceneError(src, where, f"must be finite; got {v!r}")
    return x


def _check(src: str, where: str, kind: str, v: Any, bodies: set[str] | None = None) -> Any:
    if kind == "number":
        return _number(src, where, v)
    if kind == "positive":
        x = _number(src, where, v)
        if x <= 0:
            raise SceneError(src, where, f"must be > 0 (non-physical otherwise); got {v!r}")
        return x
    if kind == "nonnegative":
        x = _number(src, where, v)
        if x < 0:
            raise SceneError(src, where, f"must be ≥ 0 (non-physical otherwise); got {v!r}")
        return x
    if kind == "restitution":
        x = _number(src, where, v)
        if not 0.0 <= x <= 1.0:
            raise SceneError(
                src, where, f"the coefficient of restitution must lie in [0, 1]; got {v!r}"
            )
        return x
    if kind == "vector":
        if not isinstance(v, list) or len(v) != 3:
            raise SceneError(src, where, f"expected an array of 3 numbers (SI), got {v!r}")
        return [_number(src, f"{where}[{i}]", x) for i, x in enumerate(v)]
    if kind == "str":
        if not isinstance(v, str):
            raise SceneError(src, where, f"expected a string, got {_type_name(v)} {v!r}")
        return v
    if kind == "axis_name":
        if v not in ("x", "y", "z"):
            raise SceneError(src, where, f"expected one of 'x', 'y', 'z'; got {v!r}")
        return v
    if kind == "impact_model":
        if v not in ("auto", "sequential"):
            raise SceneError(src, where, f"expected 'auto' or 'sequential'; got {v!r}")
        return v
    if kind == "frame":
        if v not in ("space", "body"):
            raise SceneError(src, where, f"expected 'space' or 'body'; got {v!r}")
        return v
    if kind == "planes":
        if not isinstance(v, list) or not v:
            raise SceneError(
                src, where, f"expected a non-empty array of planes {{point, normal}}, got {v!r}"
            )
        out = []
        for i, pl in enumerate(v):
            pw = f"{where}[{i}]"
            pl = _table(src, pw, pl)
            _unknown(src, pw, pl, {"point", "normal"})
            for k in ("point", "normal"):
                if k not in pl:
                    raise SceneError(src, f"{pw}.{k}", "missing required field (a plane has both)")
            plane = {
                k: check_value(src, f"{pw}.{k}", _check(src, f"{pw}.{k}", "vector", pl[k]), u)
                for k, u in (("point", "m"), ("normal", "1"))
            }
            if math.hypot(*plane["normal"]) == 0:
                raise SceneError(src, f"{pw}.normal", "must be a nonzero vector")
            out.append(plane)
        return out
    if kind == "bodies":
        if not isinstance(v, list) or not v:
            raise SceneError(src, where, f"expected a non-empty array of body names, got {v!r}")
        return [_check(src, f"{where}[{i}]", "body", x, bodies) for i, x in enumerate(v)]
    if kind == "body":
        if not isinstance(v, str):
            raise SceneError(src, where, f"expected a body name (string), got {_type_name(v)}")
        if bodies is not None and v not in bodies:
            known = ", ".join(sorted(bodies)) or "none"
            raise SceneError(src, where, f"unknown body {v!r} (bodies: {known})")
        return v
    raise AssertionError(kind)  # pragma: no cover - schema typo


def _integer(src: str, where: str, v: Any, least: int) -> int:
    if isinstance(v, bool) or not isinstance(v, int) or v < least:
        raise SceneError(src, where, f"expected an integer ≥ {least}; got {v!r}")
    return v


def _table(src: str, where: str, v: Any) -> dict[str, Any]:
    if not isinstance(v, dict):
        raise SceneError(src, where, f"expected a table, got {_type_name(v)}")
    return v


def _unknown(src: str, where: str, keys: Iterable[str], allowed: Collection[str]) -> None:
    for k in keys:
        if k not in allowed:
            raise SceneError(
                src,
                f"{where}.{k}" if where else k,
                f"unknown field (allowed: {', '.join(sorted(allowed))})",
            )


def _parse_body(src: str, i: int, b: Any) -> Body:
    where = f"bodies[{i}]"
    b = _table(src, where, b)
    for req in ("name", "shape"):
        if req not in b:
            raise SceneError(src, f"{where}.{req}", "missing required field")
    name = _check(src, f"{where}.name", "str", b["name"])
    if not _NAME.match(name):
        raise SceneError(src, f"{where}.name", f"must be an identifier; got {name!r}")
    shape = _check(src, f"{where}.shape", "str", b["shape"])
    if shape not in SHAPES:
        raise SceneError(
            src, f"{where}.shape", f"unknown body shape {shape!r} (known: {', '.join(SHAPES)})"
        )
    dims_needed = SHAPES[shape]
    allowed = {"name", "shape", "initial", "fixed", *dims_needed} | (
        {"mass"} if shape != "tank" else set()
    )
    _unknown(src, where, b, allowed)
    mass = 0.0
    if shape != "tank":
        if "mass" not in b:
            raise SceneError(src, f"{where}.mass", "missing required field")
        mass = check_magnitude(
            src, f"{where}.mass", _check(src, f"{where}.mass", "positive", b["mass"])
        )
    dims: dict[str, Any] = {}
    for d in dims_needed:
        if d not in b:
            raise SceneError(src, f"{where}.{d}", f"missing required field (a {shape} needs it)")
        if d == "inertia":
            J = check_value(
                src, f"{where}.inertia", _check(src, f"{where}.inertia", "vector", b[d]), ""
            )
            if min(J) <= 0:
                raise SceneError(src, f"{where}.inertia", f"principal moments must be > 0; got {J}")
            s = sorted(J)
            if s[2] > s[0] + s[1] * (1 + 1e-15):  # triangle inequality (4.30), rounding slack
                raise SceneError(
                    src,
                    f"{where}.inertia",
                    f"principal moments violate the triangle inequality J3 ≤ J1 + J2; got {J}",
                )
            dims[d] = J
        else:
            dims[d] = check_magnitude(
                src, f"{where}.{d}", _check(src, f"{where}.{d}", "positive", b[d])
            )
    initial = {}
    if "initial" in b:
        ini = _table(src, f"{where}.initial", b["initial"])
        _unknown(src, f"{where}.initial", ini, INITIAL_KEYS)
        for k, v in ini.items():
            initial[k] = check_value(
                src,
                f"{where}.initial.{k}",
                _check(src, f"{where}.initial.{k}", INITIAL_KEYS[k], v),
                INITIAL_DOC[k][0],
            )
        if "level" in initial and initial["level"] <= 0:
            raise SceneError(
                src, f"{where}.initial.level", f"must be > 0; got {initial['level']!r}"
            )
    fixed = b.get("fixed", False)
    if not isinstance(fixed, bool):
        raise SceneError(src, f"{where}.fixed", f"expected true or false, got {fixed!r}")
    return Body(name, shape, mass, dims, initial, fixed)


def _parse_effect(src: str, i: int, e: Any, bodies: set[str]) -> EffectSpec:
    where = f"effects[{i}]"
    e = _table(src, where, e)
    if "type" not in e:
        raise SceneError(src, f"{where}.type", "missing required field")
    kind = _check(src, f"{where}.type", "str", e["type"])
    if kind not in EFFECT_FIELDS:
        raise SceneError(
            src, f"{where}.type", f"unknown effect {kind!r} (known: {', '.join(EFFECT_FIELDS)})"
        )
    schema = EFFECT_FIELDS[kind]
    units = EFFECT_CLASSES[kind].units
    _unknown(src, where, e, {"type", *schema})
    out: dict[str, Any] = {}
    for k, (fk, required) in schema.items():
        if k in e:
            value = _check(src, f"{where}.{k}", fk, e[k], bodies)
            out[k] = check_value(src, f"{where}.{k}", value, units.get(k, ""))
        elif required:
            raise SceneError(
                src, f"{where}.{k}", f"missing required field (a {kind} effect needs it)"
            )
    for k in ("direction", "axis", "plane_normal"):
        if k in out and math.hypot(*out[k]) == 0:
            raise SceneError(src, f"{where}.{k}", "must be a nonzero vector")
    return EffectSpec(kind, i, out)


def parse_scene(data: dict[str, Any], *, source: str = "<scene>") -> Scene:
    """Validate a scene given as a dict (the parsed TOML); raise :class:`SceneError`.

    Each field is checked against the schema (the module's docstring: SI numbers, no
    units, nothing evaluated), then the combination of bodies and effects
    (:func:`mechanics.scenes.simulate.validate`).

    Parameters
    ----------
    data : dict[str, Any]
        The scene's tables: ``scene`` (required), ``bodies`` (at least one), ``effects``
        and ``units`` (optional).
    source : str, optional
        Where the data came from, named by every error. Default ``"<scene>"``.

    Returns
    -------
    Scene
        The validated scene, its numbers as floats in SI units.

    Raises
    ------
    SceneError
        Where a table or field is missing, unknown or invalid (not a number in SI units,
        not finite, out of its range or beyond magnitude 2⁸⁰, an unknown shape, effect or
        body), or the combination of bodies and effects is refused: the message names
        ``source``, the field and the reason.

    Examples
    --------
    >>> s = parse_scene({"scene": {"name": "drop", "duration": 1.0},
    ...                  "bodies": [{"name": "ball", "shape": "point", "mass": 1.0}],
    ...                  "effects": [{"type": "gravity", "g": 9.81}]})
    >>> s.effect_types
    ('gravity',)
    >>> parse_scene({"scene": {"name": "x", "duration": "2 s"}})
    Traceback (most recent call last):
    ...
    mechanics.scenes.errors.SceneError: <scene>: scene.duration: expected a number in SI units, \
got a string '2 s' (units are not parsed: write the value as a plain number in SI units)
    """
    src = source
    data = _table(src, "(top level)", data)
    _unknown(src, "", data, {"scene", "units", "bodies", "effects"})
    if "units" in data:
        u = _table(src, "units", data["units"])
        _unknown(src, "units", u, {"system"})
        if u.get("system") != "SI":
            raise SceneError(
                src, "units.system", f"only SI units are supported; got {u.get('system')!r}"
            )
    if "scene" not in data:
        raise SceneError(src, "scene", "missing required table [scene]")
    s = _table(src, "scene", data["scene"])
    _unknown(
        src,
        "scene",
        s,
        {
            "name",
            "title",
            "book",
            "duration",
            "samples",
            "method",
            "rtol",
            "atol",
            "compare",
            "step",
            "order",
            "max_samples",
            "max_steps",
            "max_seconds",
        },
    )
    for req in ("name", "duration"):
        if req not in s:
            raise SceneError(src, f"scene.{req}", "missing required field")
    name = _check(src, "scene.name", "str", s["name"])
    duration = check_magnitude(
        src, "scene.duration", _check(src, "scene.duration", "positive", s["duration"])
    )
    samples = _integer(src, "scene.samples", s.get("samples", 201), 2)
    limits: dict[str, Any] = {}
    if "max_samples" in s:
        limits["max_samples"] = _integer(src, "scene.max_samples", s["max_samples"], 2)
    if "max_steps" in s:
        limits["max_steps"] = _integer(src, "scene.max_steps", s["max_steps"], 1)
    if "max_seconds" in s:
        limits["max_seconds"] = _check(src, "scene.max_seconds", "positive", s["max_seconds"])
    method = _check(src, "scene.method", "str", s.get("method", "auto"))
    if method not in METHODS:
        raise SceneError(src, "scene.method", f"expected one of {METHODS}; got {method!r}")
    split: dict[str, Any] = {}  # step (float), order (int)
    for k in ("step", "order"):
        if k in s and method != "splitting":
            raise SceneError(src, f"scene.{k}", f"only with method 'splitting'; got {method!r}")
    if "step" in s:
        split["step"] = check_magnitude(
            src, "scene.step", _check(src, "scene.step", "positive", s["step"])
        )
    if "order" in s:
        order = s["order"]
        if isinstance(order, bool) or order not in SPLITTING_ORDERS:
            raise SceneError(
                src, "scene.order", f"expected one of {SPLITTING_ORDERS}; got {order!r}"
            )
        split["order"] = int(order)
    tols = {}
    for k in ("rtol", "atol"):
        tols[k] = _check(src, f"scene.{k}", "positive", s.get(k, DEFAULT_TOL))
        if tols[k] > 1e-3:
            raise SceneError(src, f"scene.{k}", f"must be ≤ 1e-3; got {tols[k]!r}")
    if tols["rtol"] < RTOL_MIN:
        raise SceneError(
            src,
            "scene.rtol",
            f"must be ≥ 100 eps = {RTOL_MIN:.3g} (DOP853 cannot hold a tighter relative "
            f"tolerance); got {tols['rtol']!r}",
        )
    check_magnitude(src, "scene.atol", tols["atol"])
    title = _check(src, "scene.title", "str", s.get("title", ""))
    book = _check(src, "scene.book", "str", s.get("book", ""))
    compare = _check(src, "scene.compare", "str", s.get("compare", ""))
    raw_bodies = data.get("bodies", [])
    if not isinstance(raw_bodies, list) or not raw_bodies:
        raise SceneError(src, "bodies", "expected at least one [[bodies]] table")
    bodies = tuple(_parse_body(src, i, b) for i, b in enumerate(raw_bodies))
    names = [b.name for b in bodies]
    for i, n in enumerate(names):
        if n in names[:i]:
            raise SceneError(src, f"bodies[{i}].name", f"duplicate body name {n!r}")
    raw_effects = data.get("effects", [])
    if not isinstance(raw_effects, list):
        raise SceneError(src, "effects", "expected an array of [[effects]] tables")
    effects = tuple(_parse_effect(src, i, e, set(names)) for i, e in enumerate(raw_effects))
    scene = Scene(
        name=name,
        source=src,
        duration=duration,
        samples=samples,
        method=method,
        bodies=bodies,
        effects=effects,
        title=title,
        book=book,
        compare=compare,
        raw=data,
        **tols,
        **split,
        **limits,
    )
    from .simulate import validate  # the combination of bodies and effects must make sense

    validate(scene)
    return scene


def load_scene(path: str | PathLike[str]) -> Scene:
    """Read and validate a scene file (TOML); errors name the file, field and reason.

    Parameters
    ----------
    path : str or os.PathLike
        The scene file: UTF-8 TOML (the module's docstring gives the schema).

    Returns
    -------
    Scene
        The validated scene (:func:`parse_scene` of its tables), its ``source`` the
        path.

    Raises
    ------
    SceneError
        Where the file cannot be read (field ``(file)``), is not UTF-8, is not valid
        TOML (field ``(syntax)``), or its scene is invalid (:func:`parse_scene`).

    Examples
    --------
    A built-in scene read from its file, and parsed from its tables:

    >>> from mechanics.scenes import builtin_path
    >>> path = builtin_path("rolling_incline")
    >>> sc = load_scene(path)
    >>> sc == parse_scene(tomllib.loads(path.read_text("utf-8")), source=str(path))
    True
    >>> load_scene(path.with_name("no_such_scene.toml"))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    mechanics.scenes.errors.SceneError: ...no_such_scene.toml: (file): cannot read: ...
    """
    p = Path(path)
    try:
        text = p.read_bytes()
    except OSError as exc:
        raise SceneError(str(path), "(file)", f"cannot read: {exc.strerror}") from None
    try:
        data = tomllib.loads(text.decode("utf-8"))
    except UnicodeDecodeError:
        raise SceneError(str(path), "(file)", "not UTF-8 text") from None
    except tomllib.TOMLDecodeError as exc:
        raise SceneError(str(path), "(syntax)", f"invalid TOML: {exc}") from None
    return parse_scene(data, source=str(path))
