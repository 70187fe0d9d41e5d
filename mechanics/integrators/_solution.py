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


@dataclass(frozen=True)
class Solution:
    """States at the output times and the work it took.

    Attributes
    ----------
    t : ndarray, shape (n,)
        Output times (the grid that was asked for, unchanged).
    y : ndarray, shape (n, *y0.shape)
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
    """

    t: FloatArray
    y: FloatArray
    method: str
    steps: int
    rhs_evals: int
    rejected_steps: int


def _solution(
    t: FloatArray, ys: FloatArray, method: str, steps: int, evals: int, rejected: int
) -> Solution:
    t = t.copy()
    t.flags.writeable = False
    ys.flags.writeable = False
    return Solution(t, ys, method, int(steps), int(evals), int(rejected))
