"""The :class:`Solution` every integrator returns: output times, states and the work done.

Part of :mod:`mechanics.integrators` (its docstring states the conventions).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


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

    t: np.ndarray
    y: np.ndarray
    method: str
    steps: int
    rhs_evals: int
    rejected_steps: int


def _solution(t, ys, method, steps, evals, rejected) -> Solution:
    t = t.copy()
    t.flags.writeable = False
    ys.flags.writeable = False
    return Solution(t, ys, method, int(steps), int(evals), int(rejected))
