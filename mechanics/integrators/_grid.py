"""Output times and fixed steps: the grid's validation, the steps between outputs
(never accumulated) and the step budget.

Part of :mod:`mechanics.integrators` (its docstring states the conventions).
"""

from __future__ import annotations

import itertools
import math
from numbers import Integral

import numpy as np
import numpy.typing as npt

from .._floats import EPS
from .._validate import as_float_array, as_float_scalar, as_positive_scalar, finite_result
from ..errors import NonPositiveParameterError, OutOfDomainError, ShapeError, StepSizeError
from ._solution import FloatArray

#: An interval of n·h that rounds to slightly above n steps still takes n steps:
#: the quotient (t_{k+1} − t_k)/h carries a few roundings (8 eps relative covers
#: them), and the grid points themselves half an ulp each (see :func:`_substeps`).
_GRID_RTOL = 8 * EPS


_positive_scalar = as_positive_scalar


def _check_times(t: npt.ArrayLike) -> FloatArray:
    tt = as_float_array(t, "t")
    if tt.ndim != 1 or tt.shape[0] < 2:
        raise ShapeError(
            f"t must be a 1-D grid of at least two output times (a span (t0, t1)); "
            f"got shape {tt.shape}"
        )
    steps = np.diff(tt)
    if not (steps > 0).all():
        k = int(np.argmax(~(steps > 0)))
        a, b = float(tt[k + 1]), float(tt[k])
        raise OutOfDomainError(
            f"t must be strictly increasing; t[{k + 1}] = {a!r} ≤ t[{k}] = {b!r}"
        )
    return tt


def _substeps(ta: float, tb: float, h: float) -> int:
    """Equal steps of at most h (up to the rounding of ta and tb) covering [ta, tb].

    On a grid t0 + k h each point is rounded once, so tb − ta = h within an ulp of
    each end; that slack is forgiven, so the grid takes exactly one step per point.
    """
    slack = math.ulp(ta) + math.ulp(tb)
    return max(1, math.ceil((tb - ta) / h * (1.0 - _GRID_RTOL) - slack / h))


#: the fixed-step methods' default budget of steps (the adaptive one's max_steps default)
MAX_STEPS = 10**7


def _check_step_budget(t: FloatArray, h: float, max_steps: int) -> None:
    """StepSizeError before a fixed-step run that would take more than max_steps steps
    (a span of 1e300 at h = 0.1 would otherwise run for ever, or overflow the count)."""
    n = (float(t[-1]) - float(t[0])) / h
    if not n <= max_steps:  # also catches n = inf
        raise StepSizeError(
            f"h = {h!r} over t = [{float(t[0])!r}, {float(t[-1])!r}] takes {n:.3g} steps, "
            f"more than max_steps = {max_steps}; raise h (or max_steps) or shorten the span"
        )


def _substep_counts(t: FloatArray, h: float) -> npt.NDArray[np.int64]:
    """:func:`_substeps` of every interval of the grid t, as int64."""
    return np.array([_substeps(a, b, h) for a, b in itertools.pairwise(t.tolist())], np.int64)


def time_grid(t0: float, h: float, n: int) -> FloatArray:
    """The grid t0 + k h, k = 0 … n (each entry rounded once, never accumulated).

    Domain: finite scalars t0 and h > 0, an integer n ≥ 1 (else NonPositiveParameterError); the grid
    has n + 1 entries in memory.

    Parameters
    ----------
    t0 : float
        The first time (s), finite.
    h : float
        The step (s), finite and > 0.
    n : int
        The number of steps, ≥ 1 (an ``int``, not a float or a bool).

    Returns
    -------
    ndarray, shape (n + 1,)
        t0 + k h for k = 0 … n (s), each entry one multiplication and one addition.

    Raises
    ------
    NonPositiveParameterError
        ``h`` ≤ 0, or ``n`` not an integer ≥ 1.
    ShapeError
        ``t0`` or ``h`` not a real scalar.
    NonFiniteError
        ``t0`` or ``h`` NaN or infinite.
    ResultOverflowError
        The last time t0 + n h is beyond float64's range.

    Examples
    --------
    Ten million steps of 0.1 end where they should; a running sum does not:

    >>> float(time_grid(0.0, 0.1, 10**7)[-1])
    1000000.0
    >>> s = 0.0
    >>> for _ in range(10**5):
    ...     s += 0.1
    >>> s == 10000.0
    False
    """
    t0f = as_float_scalar(t0, "t0")
    hf = _positive_scalar(h, "h")
    if isinstance(n, bool) or not isinstance(n, Integral) or n < 1:
        raise NonPositiveParameterError(f"n must be an integer ≥ 1; got {n!r}")
    return t0f + hf * np.arange(int(n) + 1, dtype=np.float64)


time_grid = finite_result(time_grid)
