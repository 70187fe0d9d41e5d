"""Simulate a scene: every scene runs on the one engine (:mod:`.engine`), which returns a
:class:`~.trajectory.Trajectory`.

Before the run, its memory is estimated and refused beyond the scene's limit
(:mod:`.budget`).  During the run numpy's floating-point warnings are silenced: a
quantity that overflows becomes inf or NaN, which :func:`.result.run_scene` reports as
a failure naming it (never a warning); an arithmetic error raised on the way (a
division by zero of Python floats, a library function's overflow, a right-hand side that
is no longer finite) ends the run with one :class:`~.errors.SceneError`, and so does a
library function's refusal of a value the run reached (a
:class:`~mechanics.errors.MechanicsValueError`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..errors import MechanicsValueError, NonFiniteError, ResultOverflowError
from . import budget, engine
from .derived import derived_quantities
from .state import body_inertia, body_radius
from .trajectory import EPS, Event, Trajectory

if TYPE_CHECKING:  # for annotations only: a layer above
    from .spec import Scene

__all__ = ["EPS", "Event", "Trajectory", "body_inertia", "body_radius", "simulate", "validate"]


def validate(scene: Scene) -> None:
    """Check the combination of bodies and effects; raise a SceneError naming the field."""
    engine.validate(scene)


def simulate(scene: Scene) -> Trajectory:
    """Run the scene with exactly the listed effects; the derived quantities its bodies
    and effects define go into ``derived`` (:mod:`.derived`)."""
    budget.check_memory(scene)
    with np.errstate(all="ignore"):
        try:
            eng = engine.Engine(scene)
            tr = eng.run()
            tr.derived = derived_quantities(eng, tr)
        except (ArithmeticError, NonFiniteError, ResultOverflowError) as exc:
            raise scene.error(
                "(run)",
                f"the run left float64's range ({type(exc).__name__}: {exc}); bring the "
                "scene's numbers nearer 1 in SI units",
            ) from None
        except MechanicsValueError as exc:  # a library function refused a value of the run
            raise scene.error(
                "(run)",
                f"a value of the run is outside the domain of the library function that "
                f"takes it ({type(exc).__name__}: {exc})",
            ) from None
    return tr
