""":func:`integrate`: one interface to the fixed-step and adaptive methods.

Part of :mod:`mechanics.integrators` (its docstring states the conventions).
"""

from __future__ import annotations

from numbers import Integral

import numpy as np
import numpy.typing as npt

from .._validate import as_float_array
from ..errors import NonPositiveParameterError, OutOfDomainError, ShapeError, UnknownOptionError
from ._dop853 import DOP853_MAX_BETA, _dop853_compiled, _integrate_dop853
from ._grid import _check_step_budget, _check_times, _positive_scalar
from ._rhs import _wrap_rhs
from ._rk4 import _integrate_rk4, _rk4_compiled
from ._solution import Event, Rhs, Solution, _solution

#: The methods of :func:`integrate`.
METHODS = ("rk4", "dop853")


def integrate(
    rhs: Rhs,
    y0: npt.ArrayLike,
    t: npt.ArrayLike,
    *,
    method: str,
    h: float | None = None,
    rtol: float | None = None,
    atol: float | None = None,
    kahan: bool = False,
    batch_ndim: int = 0,
    max_steps: int = 10**7,
    compiled: bool = True,
    beta: float = 0.0,
    event: Event | None = None,
    event_direction: float = 0.0,
) -> Solution:
    """Integrate dy/dt = rhs(t, y) from y(t[0]) = y0, returning y at the times ``t``.

    Domain: finite y0, t strictly increasing with n ≥ 2 entries, method "rk4" (h > 0, at most
    max_steps steps: else StepSizeError before any work) or "dop853" (rtol > 0, atol > 0,
    0 ≤ beta ≤ 0.08; StepSizeError beyond max_steps or below the rounding of t); rhs finite.

    Parameters
    ----------
    rhs : callable
        ``rhs(t, y)``: float and array of ``y0``'s shape → array of that shape.  A
        numba-compiled function (``@numba.njit``, see the module Conventions, *A
        compiled right-hand side*) with a state of shape (n,) runs the whole stepper
        compiled.
    y0 : float or array_like, any shape
        Initial state; its ``batch_ndim`` leading axes may be a batch.
    t : array_like, shape (n,), n ≥ 2
        Strictly increasing output times; ``(t0, t1)`` is a span.
    method : {"rk4", "dop853"}
    h : float, optional
        Largest step of ``"rk4"`` (required); initial step of ``"dop853"``
        (optional, else Hairer's estimate).
    rtol, atol : float, optional
        Tolerances of ``"dop853"`` (``rtol`` required, ``atol`` defaults to
        ``rtol``, i.e. components are measured against max(|y|, 1)); the error
        per step is at most atol + rtol·|y| in the RMS norm, as in scipy.
    kahan : bool
        Compensated (Kahan) addition of each step's increment.
    batch_ndim : int
        Leading axes of ``y0`` that index independent members of a batch
        (``"dop853"``: the error norm is the max over members).
    max_steps : int
        At most this many steps, ≥ 1: ``"rk4"`` raises
        :class:`~mechanics.errors.StepSizeError` before any work if it would take more,
        ``"dop853"`` when it reaches it.
    compiled : bool
        Run :func:`free_rigid_body_rhs`'s problem, or a numba-compiled ``rhs``, on the
        compiled path (the default; see the module Conventions); False forces the
        pure-numpy reference path.
    beta : float
        ``"dop853"``'s step control: 0 (the default) is scipy's; β in (0, 0.08] is
        Gustafsson's PI control as in Hairer's DOP853 (fewer rejected steps).
    event : callable, optional
        ``"dop853"`` only, without a batch: ``event(t, y)`` → float.  The run stops at
        the first zero crossing of ``event`` (checked at the end of each step, so two
        crossings within one step are not seen), located on the step's continuous
        extension to 4 ulps of its time; ``Solution.t_event`` and ``y_event`` hold
        it, and ``t``, ``y`` the outputs before it.  Numba-compiled, with a
        compiled ``rhs``, it runs in the kernel.
    event_direction : {-1, 0, 1}
        Stop only where ``event`` falls through zero (−1), rises (1), or either (0).

    Returns
    -------
    Solution

    Raises
    ------
    UnknownOptionError
        An unknown ``method`` (naming the choices) or an option the method lacks; ``rhs``
        or ``event`` not callable; an ``event`` with a batch.
    NonPositiveParameterError
        ``h``, ``rtol`` or ``atol`` ≤ 0, or a required one missing; ``max_steps`` not an
        integer ≥ 1.
    OutOfDomainError
        ``t`` not strictly increasing; ``beta`` outside [0, 0.08] (``DOP853_MAX_BETA``);
        ``event_direction`` not −1, 0 or 1.
    NonFiniteError
        NaN or an infinity in ``y0`` or ``t``, or ``rhs`` returning one (naming t).
    ShapeError
        ``t`` not 1-D with at least two entries; ``batch_ndim`` not an integer in
        [0, y0.ndim]; ``rhs`` returning the wrong shape (naming t).
    ResultOverflowError
        The state overflowed.
    StepSizeError
        ``"rk4"``: more than ``max_steps`` steps; ``"dop853"``: the step fell below the
        rounding of t (the tolerance cannot be met there) or ``max_steps`` was reached.

    Examples
    --------
    y' = −y to t = 1 by RK4 with h = 0.01: error ≈ h⁴/120 e⁻¹ ≈ 3e-11.

    >>> sol = integrate(lambda t, y: -y, 1.0, (0.0, 1.0), method="rk4", h=0.01)
    >>> bool(abs(sol.y[-1] - np.exp(-1.0)) < 1e-10), sol.steps, sol.rhs_evals
    (True, 100, 400)
    >>> sol = integrate(lambda t, y: -y, 1.0, (0.0, 1.0), method="dop853", rtol=1e-12)
    >>> bool(abs(sol.y[-1] - np.exp(-1.0)) < 1e-11)
    True

    An event: y'' = −y from (1, 0) is cos t, which falls through 0 at π/2; the run stops
    there, with the outputs before it.

    >>> osc = lambda t, y: np.array([y[1], -y[0]])
    >>> sol = integrate(osc, [1.0, 0.0], np.linspace(0.0, 10.0, 11), method="dop853",
    ...                 rtol=1e-12, event=lambda t, y: y[0], event_direction=-1)
    >>> bool(abs(sol.t_event - np.pi / 2) < 1e-10), sol.t.tolist()
    (True, [0.0, 1.0])
    """
    if method not in METHODS:
        raise UnknownOptionError(f"method must be one of {METHODS}; got {method!r}")
    if not callable(rhs):
        raise UnknownOptionError(f"rhs must be callable rhs(t, y); got {type(rhs).__name__}")
    y0a = np.array(as_float_array(y0, "y0"), dtype=np.float64, copy=True)
    tt = _check_times(t)
    if isinstance(batch_ndim, bool) or not isinstance(batch_ndim, Integral):
        raise ShapeError(f"batch_ndim must be an integer; got {batch_ndim!r}")
    if not 0 <= batch_ndim <= y0a.ndim:
        raise ShapeError(f"batch_ndim={batch_ndim} must lie in [0, y0.ndim = {y0a.ndim}]")
    if isinstance(max_steps, bool) or not isinstance(max_steps, Integral) or max_steps < 1:
        raise NonPositiveParameterError(f"max_steps must be an integer ≥ 1; got {max_steps!r}")
    f = _wrap_rhs(rhs, y0a.shape)
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        if method == "rk4":
            if rtol is not None or atol is not None or beta != 0.0 or event is not None:
                raise UnknownOptionError(
                    "rtol/atol/beta/event are options of the adaptive method 'dop853'; "
                    "'rk4' takes a fixed step h"
                )
            if h is None:
                raise NonPositiveParameterError("method 'rk4' needs a step h > 0; got None")
            hh = _positive_scalar(h, "h")
            _check_step_budget(tt, hh, max_steps)
            out = _rk4_compiled(rhs, y0a, tt, hh) if compiled and not kahan else None
            if out is None:
                out = _integrate_rk4(f, y0a, tt, hh, bool(kahan))
        else:
            if rtol is None:
                raise NonPositiveParameterError("method 'dop853' needs rtol > 0; got None")
            r = _positive_scalar(rtol, "rtol")
            a = r if atol is None else _positive_scalar(atol, "atol")
            hh = None if h is None else _positive_scalar(h, "h")
            b = _check_beta(beta)
            d = _check_event(event, event_direction, batch_ndim)
            done = None
            if compiled and not kahan:
                done = _dop853_compiled(
                    rhs, y0a, tt, hh, r, a, int(batch_ndim), int(max_steps), b, event, d
                )
            if done is None:
                done = _integrate_dop853(
                    f,
                    y0a,
                    tt,
                    hh,
                    r,
                    a,
                    bool(kahan),
                    int(batch_ndim),
                    int(max_steps),
                    b,
                    event,
                    d,
                )
            out, hit = done
            ys, steps, evals, rej = out
            return _solution(tt, ys, method, steps, evals, rej, hit)
    ys, steps, evals, rej = out
    return _solution(tt, ys, method, steps, evals, rej)


def _check_beta(beta: object) -> float:
    """The PI gain β as a float in [0, DOP853_MAX_BETA], or OutOfDomainError naming it."""
    if isinstance(beta, bool) or not isinstance(beta, (int, float, np.floating, np.integer)):
        raise OutOfDomainError(
            f"beta must be a real number in [0, {DOP853_MAX_BETA}]; got {beta!r}"
        )
    b = float(beta)
    if not 0.0 <= b <= DOP853_MAX_BETA:  # NaN fails too
        raise OutOfDomainError(f"beta must lie in [0, {DOP853_MAX_BETA}]; got {beta!r}")
    return b


def _check_event(event: object, direction: float, batch_ndim: int) -> float:
    """The event's direction as a float (−1, 0 or 1), the event callable and alone."""
    if event is not None and not callable(event):
        raise UnknownOptionError(f"event must be callable event(t, y); got {type(event).__name__}")
    if event is not None and batch_ndim:
        raise UnknownOptionError(
            f"an event stops one run; it takes batch_ndim=0, got batch_ndim={batch_ndim}"
        )
    if isinstance(direction, bool) or direction not in (-1, 0, 1):
        raise OutOfDomainError(f"event_direction must be -1, 0 or 1; got {direction!r}")
    return float(direction)
