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
    """One effect object per listed effect, in file order (a group of impacts: one per
    pair it names, :meth:`.impact.Impact.expand`); nothing else."""
    return [
        EFFECT_CLASSES[spec.type](one, ctx)
        for spec in scene.effects
        for one in EFFECT_CLASSES[spec.type].expand(spec, scene)
    ]
