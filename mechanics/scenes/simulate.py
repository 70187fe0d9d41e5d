"""Simulate a scene: a scene with a one-degree-of-freedom constraint (fixed axis, fixed
point, rolling, sliding, tank) goes to its model (:mod:`.models`); a scene of free bodies
to the engine (:mod:`.engine`).  Both return a :class:`~.trajectory.Trajectory`.
"""

from __future__ import annotations

from . import engine, models
from .state import body_inertia, body_radius
from .trajectory import EPS, Event, Trajectory

__all__ = ["EPS", "Event", "Trajectory", "body_inertia", "body_radius", "simulate", "validate"]


def validate(scene) -> None:
    """Check the combination of bodies and effects; raise a SceneError naming the field."""
    if models.select_model(scene) is None:
        engine.validate(scene)


def simulate(scene) -> Trajectory:
    """Run the scene with exactly the listed effects."""
    cls = models.select_model(scene)
    if cls is None:
        return engine.Engine(scene).run()
    return cls(scene).run()
