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
    """Check the combination of bodies and effects; raise a SceneError naming the field.

    Each field is checked by the parser; this checks the scene as a whole (one joint
    per body, a tank under its outflow only, each body's initial keys, no spin about a
    zero principal moment, each effect's check of its combination) and, with impacts,
    that no two features overlap at t = 0.  :func:`~.spec.parse_scene` calls it.

    Parameters
    ----------
    scene : Scene
        A scene whose fields are each valid (:class:`mechanics.scenes.spec.Scene`).

    Raises
    ------
    SceneError
        Where the combination is refused: the message names the file, the field and
        the reason.

    Examples
    --------
    A parsed scene passes; the same point given a spin is refused:

    >>> from mechanics.scenes.spec import parse_scene
    >>> sc = parse_scene({"scene": {"name": "fall", "duration": 1.0, "samples": 3},
    ...                   "bodies": [{"name": "ball", "shape": "point", "mass": 2.0,
    ...                               "initial": {"position": [0.0, 0.0, 4.0]}}],
    ...                   "effects": [{"type": "gravity", "g": 8.0}]})
    >>> import dataclasses
    >>> spun = dataclasses.replace(sc.bodies[0], initial={"omega": [0.0, 0.0, 1.0]})
    >>> validate(dataclasses.replace(sc, bodies=(spun,)))
    Traceback (most recent call last):
    ...
    mechanics.scenes.errors.SceneError: <scene>: bodies[0].initial.omega: a point has no \
attitude and no rotation
    >>> validate(sc) is None
    True
    """
    engine.validate(scene)


def simulate(scene: Scene) -> Trajectory:
    """Run the scene with exactly the listed effects and return its trajectory.

    The derived quantities its bodies and effects define go into ``derived``
    (:mod:`.derived`).  The memory the samples take is checked first (:mod:`.budget`);
    numpy's floating-point warnings are silenced during the run (see the module's
    docstring).

    Parameters
    ----------
    scene : Scene
        A validated scene (:func:`~.spec.parse_scene`, :func:`~.spec.load_scene`).

    Returns
    -------
    Trajectory
        The samples, the dense state, the events and the conserved quantities
        (:class:`~.trajectory.Trajectory`).

    Raises
    ------
    SceneError
        Where the samples exceed the scene's memory limit, or the run its steps or wall
        time (a ``BudgetError``, its subclass, naming ``scene.samples``,
        ``scene.duration`` for the estimated steps, or ``(run)``); where the run leaves
        float64's range or reaches a value outside a library function's domain (naming
        ``(run)``); where ``method = "exact"`` has no exact flow or the run meets what
        the engine refuses (a resting contact it cannot resolve, a splitting near a
        separatrix).

    Examples
    --------
    A point falling from 4 m under g = 8 m/s²: z = 4 − ½ g t² = 0 at t = 1 s, and
    v = −g t = −8 m/s:

    >>> from mechanics.scenes.spec import parse_scene
    >>> sc = parse_scene({"scene": {"name": "fall", "duration": 1.0, "samples": 3},
    ...                   "bodies": [{"name": "ball", "shape": "point", "mass": 2.0,
    ...                               "initial": {"position": [0.0, 0.0, 4.0]}}],
    ...                   "effects": [{"type": "gravity", "g": 8.0}]})
    >>> tr = simulate(sc)
    >>> tr.method, tr.series["z"].tolist(), bool(tr.series["vz"][-1] == -8.0 * tr.t[-1])
    ('exact: free flight under uniform gravity', [4.0, 3.0, 0.0], True)
    """
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
