"""Simulate a scene: every scene runs on the one engine (:mod:`.engine`), which returns a
:class:`~.trajectory.Trajectory`.
"""

from __future__ import annotations

from . import engine
from .derived import derived_quantities
from .state import body_inertia, body_radius
from .trajectory import EPS, Event, Trajectory

__all__ = ["EPS", "Event", "Trajectory", "body_inertia", "body_radius", "simulate", "validate"]


def validate(scene) -> None:
    """Check the combination of bodies and effects; raise a SceneError naming the field."""
    engine.validate(scene)


def simulate(scene) -> Trajectory:
    """Run the scene with exactly the listed effects; the derived quantities its bodies
    and effects define go into ``extra["derived"]`` (:mod:`.derived`)."""
    eng = engine.Engine(scene)
    tr = eng.run()
    tr.extra["derived"] = derived_quantities(eng, tr)
    return tr
