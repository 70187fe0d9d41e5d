"""The effects a scene may list, one module per effect type, registered by name.

Every effect acts in the one engine (:mod:`mechanics.scenes.engine`).  Loads:
``gravity``, ``newton_gravity``, ``spring``, ``damper``, ``drag``, ``force``,
``torque``, ``thrust``, ``torsion`` (on a fixed axis), ``mass_flow`` (onto a body on a
fixed axis), ``buoyancy`` (of a sphere in a liquid).  Contacts: ``impact``.  Joints,
one per body: ``fixed_point``, ``fixed_axis``, ``rolling``, ``coulomb_friction``
(sliding and rolling on a plane).
A tank's outflow: ``tank_outflow``.

Adding an effect: one module here with one class (``type``, ``schema``, the
contributions it makes; see :mod:`.base`), imported below, and its tests.
"""

from __future__ import annotations

from . import (  # noqa: F401  (each import registers its effect)
    buoyancy,
    coulomb_friction,
    drag,
    fixed_axis,
    fixed_point,
    force,
    gravity,
    impact,
    mass_flow,
    newton_gravity,
    rolling,
    spring,
    tank_outflow,
    thrust,
    torsion,
)
from .base import CONSERVED, REGISTRY, Context, Effect, Loads, SceneLike, Snapshot, register
from .coulomb_friction import CoulombFriction
from .drag import Drag
from .fixed_axis import FixedAxis
from .fixed_point import FixedPoint
from .force import Force, Torque
from .gravity import Gravity
from .impact import Impact
from .mass_flow import MassFlow
from .newton_gravity import NewtonGravity
from .rolling import Rolling
from .spring import Damper, Spring
from .tank_outflow import TankOutflow
from .thrust import Thrust
from .torsion import Torsion

#: effect type -> class (the registry, in a stable order)
EFFECT_CLASSES = dict(sorted(REGISTRY.items()))

__all__ = [
    "CONSERVED",
    "EFFECT_CLASSES",
    "REGISTRY",
    "Context",
    "CoulombFriction",
    "Damper",
    "Drag",
    "Effect",
    "FixedAxis",
    "FixedPoint",
    "Force",
    "Gravity",
    "Impact",
    "Loads",
    "MassFlow",
    "NewtonGravity",
    "Rolling",
    "Snapshot",
    "Spring",
    "TankOutflow",
    "Thrust",
    "Torque",
    "Torsion",
    "build_effects",
    "register",
]


def build_effects(scene: SceneLike, ctx: Context) -> list[Effect]:
    """One effect object per listed effect, in file order; nothing else.

    A group of impacts gives one object per pair it names
    (:meth:`.impact.Impact.expand`).

    Parameters
    ----------
    scene : SceneLike
        The validated scene (its ``effects``, each of a registered ``type``).
    ctx : Context
        The scene's context, given to every effect.

    Returns
    -------
    list of Effect
        The effect objects, in the order of ``scene.effects``.

    Raises
    ------
    KeyError
        For an effect type that is not registered (the parser refuses it first), or an
        effect field a constructor reads that the parser would have required.

    Examples
    --------
    >>> from mechanics.scenes.spec import parse_scene
    >>> sc = parse_scene({"scene": {"name": "x", "duration": 1.0},
    ...                   "bodies": [{"name": "ball", "shape": "point", "mass": 2.0}],
    ...                   "effects": [{"type": "gravity", "g": 9.81}]})
    >>> build_effects(sc, Context(sc, {"ball": 0}, ("point",)))
    [Gravity({'g': 9.81})]
    """
    return [
        EFFECT_CLASSES[spec.type](one, ctx)
        for spec in scene.effects
        for one in EFFECT_CLASSES[spec.type].expand(spec, scene)
    ]
