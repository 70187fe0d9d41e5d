"""The model: a scene compiled once into what every later stage reads and none changes.

The model holds the bodies' layout in the state vector
(:class:`~mechanics.scenes.state.Layout`), the listed effects built once and grouped by
what they contribute (loads, impacts, modes, mass lost, inertia added, potentials, a
tank's outflow), and the initial state ``y0``.  The grouping is read off the protocols each effect's
class declares (:mod:`.effects.capabilities`), never by an effect's type name or by
probing for attributes.
:func:`check` validates the scene as a whole before a model is built (each field is
checked by the parser).  What changes during a run lives in the stages that read the
model: :mod:`.forward` (the loads' phase), :mod:`.collision`, :mod:`.modes`.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any, cast

import numpy as np

from mechanics import kinematics as kin

from .effects import REGISTRY, Context, build_effects
from .effects.base import gravity_vector
from .effects.capabilities import AddsInertia, ChangesMass, GuidesBody, HasModes, HasPotential
from .effects.gravity import Gravity
from .effects.impact import Impact
from .effects.tank_outflow import TankOutflow
from .state import Guide, Layout, body_inertia
from .vectors import FloatArray

if TYPE_CHECKING:  # for annotations only: a layer above
    from .spec import Scene

__all__ = ["FREE_INITIAL", "JOINTS", "RATES", "Model", "check", "initial_attitude", "initial_omega"]

FREE_INITIAL = ("position", "velocity", "omega", "psi", "theta", "phi")
#: the effects that hold a body (one per body)
JOINTS = ("fixed_point", "fixed_axis", "rolling", "coulomb_friction")
#: a pinned body may give its initial ω as the Euler angles' rates instead
RATES = ("theta_dot", "psi_dot", "phi_dot")


def initial_attitude(initial: Mapping[str, Any]) -> FloatArray:
    """The initial attitude ^A R^O = R3(φ) R1(θ) R3(ψ) of a body's Euler angles.

    The angles are z-x-z (:func:`mechanics.rotation.matrix_from_euler`); each defaults to
    0, and all three 0 give the identity (the body axes along the space axes).

    Parameters
    ----------
    initial : Mapping[str, Any]
        A body's ``initial`` table; its keys ``psi``, ``theta`` and ``phi`` (rad, finite)
        are read, the others ignored.

    Returns
    -------
    ndarray, shape (3, 3)
        ^A R^O, the rotation from space to body components.

    Raises
    ------
    TypeError
        Where an angle is neither a number nor a string (``float()`` refuses it).
    ValueError
        Where an angle is a string that is not a number.
    NonFiniteError
        Where an angle is NaN or infinite (:func:`~mechanics.rotation.matrix_from_euler`).

    Examples
    --------
    Row 3 of ^A R^O is (sin θ sin ψ, −sin θ cos ψ, cos θ):

    >>> R = initial_attitude({"psi": 0.3, "theta": 0.5, "phi": 0.7})
    >>> bool(np.allclose(R[2], [np.sin(0.5) * np.sin(0.3), -np.sin(0.5) * np.cos(0.3),
    ...                         np.cos(0.5)]))
    True
    >>> initial_attitude({}).tolist()
    [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    """
    from mechanics.rotation import matrix_from_euler

    e = [float(initial.get(k, 0.0)) for k in ("psi", "theta", "phi")]
    return matrix_from_euler(*e) if any(e) else np.eye(3)


def initial_omega(initial: Mapping[str, Any]) -> FloatArray:
    """A body's initial angular velocity ω in body components, given or from Euler rates.

    ``omega`` as given, or from the z-x-z Euler rates ``psi_dot``, ``theta_dot``,
    ``phi_dot`` (default 0) at ``theta``, ``phi`` by Euler's kinematic equations (2.69)
    (:func:`mechanics.kinematics.angular_velocity_from_euler_rates`).

    Parameters
    ----------
    initial : Mapping[str, Any]
        A body's ``initial`` table: ``omega`` (rad/s, three numbers; not checked here: the
        parser checks it), or the rates (rad/s) and the angles ``theta``, ``phi`` (rad).

    Returns
    -------
    ndarray, shape (3,)
        ω in body components, rad/s.

    Raises
    ------
    TypeError
        Where an angle or rate is neither a number nor a string (``float()`` refuses it).
    ValueError
        Where ``omega``, an angle or a rate is a string that is not a number.
    NonFiniteError
        Where an angle or rate is NaN or infinite (the kinematic equations refuse it).

    Examples
    --------
    |ω|² = θ̇² + ψ̇² + φ̇² + 2 ψ̇ φ̇ cos θ, and ω3 = ψ̇ cos θ + φ̇ (2.69):

    >>> w = initial_omega({"theta": 0.5, "psi_dot": 2.0, "phi_dot": 3.0})
    >>> bool(np.isclose(w @ w, 4.0 + 9.0 + 12.0 * np.cos(0.5)))
    True
    >>> bool(np.isclose(w[2], 2.0 * np.cos(0.5) + 3.0))
    True
    >>> initial_omega({"omega": [1.0, 2.0, 3.0]}).tolist()
    [1.0, 2.0, 3.0]
    """
    if "omega" in initial:
        return np.asarray(initial["omega"], dtype=float)
    th, ph = float(initial.get("theta", 0.0)), float(initial.get("phi", 0.0))
    thd, psd, phd = (float(initial.get(k, 0.0)) for k in RATES)
    return kin.angular_velocity_from_euler_rates(0.0, th, ph, psd, thd, phd)


def _pins(scene: Scene, index: Mapping[str, int]) -> dict[int, tuple[FloatArray, FloatArray]]:
    """The pinned bodies (a fixed_point joint) -> (C, g_A)."""
    from .effects.fixed_point import FixedPoint

    return {
        index[spec.fields["body"]]: FixedPoint(spec).pin()
        for spec in scene.effects_of("fixed_point")
    }


def _guides(scene: Scene, index: Mapping[str, int]) -> dict[int, Guide]:
    """The guided bodies (a fixed axis, rolling, sliding on a plane) -> their Guide."""
    g = gravity_vector(scene)
    out: dict[int, Guide] = {}
    for spec in scene.effects:
        cls = REGISTRY[spec.type]
        if issubclass(cls, GuidesBody):
            out[index[spec.fields["body"]]] = cls.make_guide(spec, scene, g)
    return out


def check(scene: Scene) -> None:
    """Check a scene as a whole, before a model is built (each field is the parser's).

    The checks: one joint per body, a tank acted on by its outflow only, each body's
    initial keys (a free body's, and a pinned body's Euler rates; omega or the rates, not
    both), a fixed body at rest, a point without attitude or spin, no spin about a zero
    principal moment, and each effect's own check of its combination
    (:meth:`~mechanics.scenes.effects.base.Effect.check`).

    Parameters
    ----------
    scene : Scene
        The parsed scene (:class:`mechanics.scenes.spec.Scene`).

    Raises
    ------
    SceneError
        At the first check that fails; the message names the scene file, the field and
        the reason.

    Examples
    --------
    A point has no attitude and no rotation: an initial spin is refused.

    >>> from dataclasses import replace
    >>> from mechanics.scenes.spec import parse_scene
    >>> sc = parse_scene({"scene": {"name": "x", "duration": 1.0},
    ...                   "bodies": [{"name": "ball", "shape": "point", "mass": 2.0}]})
    >>> check(sc) is None
    True
    >>> check(replace(sc, bodies=(replace(sc.bodies[0], initial={"omega": [0.0, 0.0, 1.0]}),)))
    Traceback (most recent call last):
    ...
    mechanics.scenes.errors.SceneError: <scene>: bodies[0].initial.omega: a point has no \
attitude and no rotation
    """
    index = {b.name: i for i, b in enumerate(scene.bodies)}
    held: dict[str, Any] = {}  # body -> the joint (a spec.EffectSpec) that holds it
    for spec in scene.effects:
        if spec.type not in JOINTS:
            continue
        other = held.setdefault(spec.fields["body"], spec)
        if other is not spec:
            why = (
                f"{spec.type!r} is listed twice for body {spec.fields['body']!r}"
                if other.type == spec.type
                else f"{spec.type!r} cannot be combined with {other.type!r} ({other.where}) "
                f"on body {spec.fields['body']!r}: one joint per body"
            )
            raise scene.error(f"{spec.where}.type", why)
    tanks = {b.name for b in scene.bodies if b.shape == "tank"}
    for spec in scene.effects:
        named = [spec.fields.get(k) for k in ("body", "other")] + spec.fields.get("group", [])
        if spec.type != "tank_outflow" and tanks.intersection(named):
            raise scene.error(
                f"{spec.where}.type",
                f"a tank's only effect is its tank_outflow; a {spec.type!r} cannot act on it",
            )
    pinned = _pins(scene, index)
    guided = {
        index[e.fields["body"]] for e in scene.effects if issubclass(REGISTRY[e.type], GuidesBody)
    }
    drained = {e.fields["body"] for e in scene.effects_of("tank_outflow")}
    for i, b in enumerate(scene.bodies):
        where = f"bodies[{i}]"
        if b.shape == "tank":
            if b.name not in drained:
                raise scene.error(f"{where}.shape", "a tank needs a tank_outflow effect")
            continue  # its initial keys: the outflow's check
        if i in guided:
            continue  # its initial keys: its joint's check
        keys = FREE_INITIAL + (RATES if i in pinned else ())
        for k in b.initial:
            if k not in keys:
                raise scene.error(f"{where}.initial.{k}", f"a free body takes {', '.join(keys)}")
        if "omega" in b.initial and any(k in b.initial for k in RATES):
            raise scene.error(f"{where}.initial.omega", "give either omega or the Euler rates")
        w = initial_omega(b.initial)
        if b.fixed:
            for k in ("velocity", "omega"):
                if any(b.initial.get(k, [0.0])):
                    raise scene.error(f"{where}.initial.{k}", "a fixed body stays at rest")
        elif b.shape == "point":
            if w.any() or any(b.initial.get(k, 0.0) for k in ("psi", "theta", "phi")):
                key = "omega" if w.any() else "psi"
                raise scene.error(
                    f"{where}.initial.{key}", "a point has no attitude and no rotation"
                )
        else:
            J = body_inertia(b)
            if np.any((J <= 0) & (w != 0)):
                raise scene.error(
                    f"{where}.initial.omega",
                    f"a {b.shape} has a zero principal moment {J.tolist()}: it cannot spin "
                    f"about that axis; got omega = {w.tolist()}",
                )
    for spec in scene.effects:
        REGISTRY[spec.type].check(spec, scene, index)


def _check_pairs_once(scene: Scene, impacts: Sequence[Impact]) -> None:
    """Each pair meets by one law: two impacts of the same two bodies, or of one body and
    the same plane (the same unit normal and offset n·p, as written), are refused with one
    line naming both (a group's pairs included); which law would act was undefined."""
    seen: dict[tuple[float, ...], Impact] = {}
    key: tuple[float, ...]
    for imp in impacts:
        if imp.j is not None:
            key = (min(imp.i, imp.j), max(imp.i, imp.j))
        else:
            key = (imp.i, *imp.normal.tolist(), float(imp.normal @ imp.point))
        first = seen.setdefault(key, imp)
        if first is not imp:
            raise scene.error(
                imp.where,
                f"{imp.label} already collide by {first.where} (a pair is listed once: "
                "one law for its contacts)",
            )


class Model:
    """A scene compiled: the layout, the effects by what they contribute, the initial state.

    Built once per run; nothing here changes during it (but :attr:`carried`, the speeds
    the impulses have changed, which a run resets at its start).

    Parameters
    ----------
    scene : Scene
        The parsed and validated scene (:func:`mechanics.scenes.spec.parse_scene`;
        :func:`check` is not repeated here).

    Raises
    ------
    SceneError
        Where two impact effects list the same pair (the same two bodies, or one body and
        the same plane, a group's pairs included): which law would act is undefined.
    ZeroDivisionError
        Where a rolling body's r² underflows to 0 (a radius of 1e-320 m, which the parser
        accepts): its M_eff = m + J/r² (3.79); :func:`.simulate.simulate` reports it as a
        SceneError.

    Examples
    --------
    The initial state packs the initial position and velocity, which the layout reads
    back:

    >>> from mechanics.scenes.spec import parse_scene
    >>> md = Model(parse_scene({"scene": {"name": "x", "duration": 1.0},
    ...     "bodies": [{"name": "ball", "shape": "point", "mass": 2.0,
    ...                 "initial": {"position": [0.0, 0.0, 5.0], "velocity": [1.0, 0.0, 0.0]}}],
    ...     "effects": [{"type": "gravity", "g": 9.81}]}))
    >>> md.y0.tolist(), sorted(md.kinds)
    ([0.0, 0.0, 5.0, 1.0, 0.0, 0.0], ['gravity'])
    >>> [a.tolist() for a in md.layout.gather(md.y0)[:2]]
    [[[0.0, 0.0, 5.0]], [[1.0, 0.0, 0.0]]]
    """

    def __init__(self, scene: Scene) -> None:
        self.scene = scene
        index = {b.name: i for i, b in enumerate(scene.bodies)}
        self.layout = Layout.of(scene.bodies, _pins(scene, index), _guides(scene, index))
        self.n = self.layout.n
        self.names = [b.name for b in scene.bodies]
        #: the speeds each body's impulses have changed (see Context.carried)
        self.carried = np.zeros(self.n)
        ctx = Context(
            scene, index, self.layout.kinds, self.layout.pins, self.layout.guides, self.carried
        )
        #: every listed effect, in the file's order
        self.effects = build_effects(scene, ctx)
        #: the contacts (events, not loads)
        self.impacts: list[Impact] = [e for e in self.effects if isinstance(e, Impact)]
        _check_pairs_once(scene, self.impacts)
        #: body index -> the positions in ``impacts`` of the pairs it belongs to
        self.impacts_of: dict[int, list[int]] = {}
        for a, imp in enumerate(self.impacts):
            for k in {imp.i, imp.j} - {None}:
                self.impacts_of.setdefault(cast(int, k), []).append(a)  # (None taken out)
        #: the effects that add loads; one that reads the others' loads comes after
        #: them (a stable sort)
        self.forces = sorted(
            (e for e in self.effects if not isinstance(e, Impact)), key=lambda e: e.after_loads
        )
        #: the effects with modes (stick and slip, a tank that empties)
        self.switching = [e for e in self.forces if isinstance(e, HasModes)]
        #: the effects with a potential energy
        self.potentials = [e for e in self.forces if isinstance(e, HasPotential)]
        #: the effects that take mass from a body (thrust)
        self.losing = [e for e in self.forces if isinstance(e, ChangesMass)]
        #: the effects that add inertia to a guided body (mass flowing onto it)
        self.growing = [e for e in self.forces if isinstance(e, AddsInertia)]
        #: a tank's outflow: its state is the tank's
        self.outflows = [e for e in self.effects if isinstance(e, TankOutflow)]
        #: the effect types listed (what an exact flow is chosen by)
        self.kinds = frozenset(e.type for e in self.effects)
        self.m0 = np.array([b.mass for b in scene.bodies], dtype=float)
        b0 = scene.bodies
        r0 = np.array([b.initial.get("position", [0.0] * 3) for b in b0], float)
        v0 = np.array([b.initial.get("velocity", [0.0] * 3) for b in b0], float)
        w0 = np.array([initial_omega(b.initial) for b in b0], float)
        R0 = np.array([initial_attitude(b.initial) for b in b0])
        self.w0, self.R0 = w0, R0
        L0 = self.layout.J * w0
        for i, (_, _, JC, _) in self.layout.pins.items():
            L0[i] = JC @ w0[i]  # a pinned body stores its angular momentum about C
        self.y0 = self.layout.pack(r0, v0, L0, R0)
        for i, gd in self.layout.guides.items():
            o = self.layout.offsets[i]
            self.y0[o : o + 2 * gd.nq] = np.concatenate(gd.start(b0[i].initial))
        for e in self.outflows:
            o = self.layout.offsets[e.i]
            self.y0[o : o + 2] = e.start()
        self.rigid = self.layout.rigid_bodies

    def spinning(self) -> list[int]:
        """The rigid bodies with an initial spin."""
        return [i for i in self.rigid if self.w0[i].any()]

    def uniform_gravity(self) -> FloatArray:
        """The sum of the listed uniform gravity fields (zero without one)."""
        g = np.zeros(3)
        for e in self.effects:
            if isinstance(e, Gravity):  # (the effect of type "gravity")
                g = g + e.vector
        return g
