"""The :class:`Solution` every integrator returns: output times, states and the work done,
and the type aliases the package shares (:data:`FloatArray`, :data:`Rhs`, :data:`Run`).

Part of :mod:`mechanics.integrators` (its docstring states the conventions).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TypeAlias

import numpy as np
import numpy.typing as npt

#: A float64 array (a state, a grid of times, a tableau).
FloatArray: TypeAlias = npt.NDArray[np.float64]
#: A right-hand side rhs(t, y) → dy/dt, of y's shape.
Rhs: TypeAlias = Callable[[float, FloatArray], FloatArray]
#: What a method's run returns: (ys, steps, rhs_evals, rejected_steps).
Run: TypeAlias = tuple[FloatArray, int, int, int]
#: An event function event(t, y) → float, whose zero crossing ends a run.
Event: TypeAlias = Callable[[float, FloatArray], float]
#: Where a run met its event: (t_event, y_event), or None.
EventHit: TypeAlias = tuple[float, FloatArray] | None


@dataclass(frozen=True)
class Solution:
    """States at the output times and the work it took.

    A frozen record the integrators build (:func:`integrate`,
    :func:`free_rigid_body_splitting`), with read-only arrays; each parameter is the
    attribute of the same name.

    Parameters
    ----------
    t : ndarray, shape (n,)
        Output times: the grid that was asked for, unchanged; with an ``event`` that
        was met, its times before ``t_event``.
    y : ndarray, shape (n,) + y0.shape
        The state at each output time; ``y[0]`` is the initial state.
    method : str
        ``"rk4"``, ``"dop853"`` or ``"splitting-<order>"``.
    steps : int
        Accepted steps.
    rhs_evals : int
        Right-hand-side calls (for the splitting: exact sub-flows, one sine and
        cosine each).
    rejected_steps : int
        Steps the adaptive method rejected (0 for fixed-step methods).
    t_event : float or None
        Where the run's ``event`` crossed zero (the run stopped there); None if no
        event was given or it was not met by ``t[-1]``.
    y_event : ndarray, shape y0.shape, or None
        The state at ``t_event``.

    Examples
    --------
    ``y`` has a row per output time, and RK4 takes 4 evaluations per step:

    >>> from mechanics.integrators import integrate, time_grid
    >>> sol = integrate(lambda t, y: -y, [1.0, 2.0], time_grid(0.0, 0.25, 4), method="rk4", h=0.25)
    >>> sol.y.shape, sol.steps, sol.rhs_evals == 4 * sol.steps, sol.rejected_steps
    ((5, 2), 4, True, 0)
    """

    t: FloatArray
    y: FloatArray
    method: str
    steps: int
    rhs_evals: int
    rejected_steps: int
    t_event: float | None = None
    y_event: FloatArray | None = None


def _solution(
    t: FloatArray,
    ys: FloatArray,
    method: str,
    steps: int,
    evals: int,
    rejected: int,
    hit: EventHit = None,
) -> Solution:
    t = t[: ys.shape[0]].copy()
    t.flags.writeable = False
    ys.flags.writeable = False
    if hit is None:
        return Solution(t, ys, method, int(steps), int(evals), int(rejected))
    y_event = hit[1]
    y_event.flags.writeable = False
    return Solution(t, ys, method, int(steps), int(evals), int(rejected), float(hit[0]), y_event)
