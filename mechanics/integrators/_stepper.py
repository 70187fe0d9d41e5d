""":class:`DOP853Stepper`: DOP853 one accepted step at a time (scipy's stepping
interface), for a caller that inspects every step.

Part of :mod:`mechanics.integrators` (its docstring states the conventions).
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from .._validate import as_float_array
from ..errors import (
    NonPositiveParameterError,
    OutOfDomainError,
    ResultOverflowError,
    ShapeError,
    UnknownOptionError,
)
from ._dop853 import (
    _N_STAGES,
    _N_STAGES_EXTENDED,
    DenseStep,
    _dop853_advance,
    _dop853_dense,
    _dop853_initial_step,
)
from ._grid import _positive_scalar
from ._rhs import _checked, _wrap_rhs
from ._solution import Rhs


def _scalar(x: npt.ArrayLike, name: str) -> float:
    a = as_float_array(x, name)
    if a.shape != ():
        raise ShapeError(f"{name} must be a scalar; got shape {a.shape}")
    return float(a)


def _check_max_step(max_step: float) -> float:
    """max_step > 0, +inf allowed (no cap); NaN, −inf, arrays and non-numbers refused."""
    try:
        a = np.asarray(max_step, dtype=np.float64)
    except (TypeError, ValueError):
        raise ShapeError(f"max_step must be a real number; got {max_step!r}") from None
    if a.shape != ():
        raise ShapeError(f"max_step must be a scalar; got shape {a.shape}")
    v = float(a)
    if not v > 0:
        raise NonPositiveParameterError(f"max_step must be > 0 (inf for no cap); got {v!r}")
    return v


class DOP853Stepper:
    """Dormand–Prince 8(5,3) one accepted step at a time, with dense output.

    Domain: finite t0 < t_bound, y0 1-D finite with n ≥ 1 entries, rtol > 0 and atol > 0,
    first_step > 0 and max_step > 0 (inf allowed) (else a ShapeError, NonFiniteError,
    OutOfDomainError or NonPositiveParameterError naming them); rhs must return finite arrays
    of y0's shape.

    The stepping interface of scipy's ``scipy.integrate.DOP853`` (``step``,
    ``dense_output``, ``t``, ``y``, ``t_old``, ``status``) on this module's tableau
    and step control, for a caller that inspects every step, such as a scene
    engine locating contact events on each step's polynomial.  The steps are
    scipy's (same initial step, acceptance, factors, ``max_step`` cap), up to the
    rounding of the dot products and norms.

    Parameters
    ----------
    rhs : callable
        ``rhs(t, y)``: float and array of shape (n,) → array of shape (n,).
    t0 : float
        Initial time.
    y0 : array_like, shape (n,)
        Initial state, 1-D (flatten a structured state), finite, n ≥ 1.
    t_bound : float, > t0
        The end: no step passes it, and the last one ends on it exactly.
    rtol, atol : float, > 0
        Error per step at most atol + rtol·|y| in the RMS norm (as
        :func:`integrate`).  Unlike scipy, rtol below 100 eps is kept, not raised
        to 100 eps.
    first_step : float, > 0, optional
        The first attempted step; default Hairer's estimate (2 evaluations).
    max_step : float, > 0
        Cap on every step (``inf``: none).

    Attributes
    ----------
    t : float
        The current time.
    y : ndarray, shape (n,)
        The current state (a new array after every step; the stepper never writes
        into it).
    t_old : float or None
        The start of the last step (None before the first).
    t_bound : float
    status : {"running", "finished"}
        "finished" once ``t == t_bound``.
    steps, rhs_evals, rejected_steps : int
        Accepted steps, right-hand-side calls (including the initial-step
        estimate and the 3 of each dense output), rejected attempts.
    h_abs : float
        The next step proposed by the controller (before the ``max_step`` cap
        and the truncation at ``t_bound``).

    Raises
    ------
    UnknownOptionError
        ``rhs`` not callable.
    ShapeError
        ``y0`` not 1-D with n ≥ 1 entries, ``t0``/``t_bound``/``max_step`` not scalars, or
        ``rhs`` returning the wrong shape at ``t0``.
    NonFiniteError
        NaN or an infinity in ``y0``, ``t0`` or ``t_bound``, or ``rhs`` returning one at
        ``t0``.
    OutOfDomainError
        ``t_bound ≤ t0``.
    NonPositiveParameterError
        ``rtol``, ``atol``, ``first_step`` or ``max_step`` ≤ 0 (``max_step`` NaN too).

    Examples
    --------
    Step q'' = −q to t = 1 and read the solution half-way through the last step:

    >>> osc = lambda t, y: np.array([y[1], -y[0]])
    >>> s = DOP853Stepper(osc, 0.0, [1.0, 0.0], 1.0, rtol=1e-10, atol=1e-10)
    >>> while s.status == "running":
    ...     s.step()
    >>> s.t, s.steps
    (1.0, 4)
    >>> dense = s.dense_output()
    >>> tm = 0.5 * (dense.t_old + dense.t)
    >>> bool(np.abs(dense(tm) - [np.cos(tm), -np.sin(tm)]).max() < 1e-10)
    True
    """

    def __init__(
        self,
        rhs: Rhs,
        t0: float,
        y0: npt.ArrayLike,
        t_bound: float,
        *,
        rtol: float = 1e-12,
        atol: float = 1e-12,
        first_step: float | None = None,
        max_step: float = math.inf,
    ) -> None:
        if not callable(rhs):
            raise UnknownOptionError(f"rhs must be callable rhs(t, y); got {type(rhs).__name__}")
        y = np.array(as_float_array(y0, "y0"), dtype=np.float64, copy=True)
        if y.ndim != 1 or y.shape[0] == 0:
            raise ShapeError(f"y0 must be a non-empty 1-D state (flatten it); got shape {y.shape}")
        t0f = _scalar(t0, "t0")
        tb = _scalar(t_bound, "t_bound")
        if not tb > t0f:
            raise OutOfDomainError(f"t_bound must be > t0; got t_bound={tb!r} ≤ t0={t0f!r}")
        self.rtol = _positive_scalar(rtol, "rtol")
        self.atol = _positive_scalar(atol, "atol")
        self.max_step = _check_max_step(max_step)
        h0 = None if first_step is None else _positive_scalar(first_step, "first_step")
        self._f = _wrap_rhs(rhs, y.shape)
        self.t, self.y, self.t_bound = t0f, y, tb
        self.t_old: float | None = None
        self.status = "running"
        self.steps = self.rejected_steps = 0
        self._K_ext = np.empty((_N_STAGES_EXTENDED, y.shape[0]))
        self._K = self._K_ext[: _N_STAGES + 1]
        self._y_old = y
        self._h = 0.0
        self._dense: DenseStep | None = None
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            self._fy = np.array(_checked(self._f)(t0f, y), dtype=np.float64)
            self.rhs_evals = 1
            if h0 is None:
                h0 = _dop853_initial_step(
                    self._f, t0f, y, self._fy, tb, self.rtol, self.atol, 1, self.max_step
                )
                self.rhs_evals += 1
        self.h_abs = h0

    def step(self) -> None:
        """Take one accepted step (rejected attempts inside), never past ``t_bound``.

        Raises
        ------
        OutOfDomainError
            The stepper has finished (``t == t_bound``).
        StepSizeError
            The step fell below 10 ulp(t) (the tolerance cannot be met there) or
            ``max_step`` is below it; the state is left unchanged.
        ResultOverflowError, NonFiniteError
            The state overflowed, or ``rhs`` returned NaN/inf (naming the time).
        """
        if self.status != "running":
            raise OutOfDomainError(
                f"the stepper has finished: t = t_bound = {self.t!r}; step() needs t < t_bound"
            )
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            t_new, y_new, _, hh, h_next, evals, rejected, _, _ = _dop853_advance(
                self._f,
                self.t,
                self.y,
                self._fy,
                self.h_abs,
                self.t_bound,
                self.max_step,
                self._K,
                self._K,
                self.y.shape,
                self.rtol,
                self.atol,
                1,
                None,
            )
        self.rhs_evals += evals
        self.rejected_steps += rejected
        self.steps += 1
        self.t_old, self._y_old, self._h = self.t, self.y, hh
        self.t, self.y, self.h_abs = t_new, y_new, h_next
        # f(t, y) from K[12], not the array rhs returned: an rhs that reuses its
        # output buffer would overwrite that one in the dense output's evaluations
        self._fy = self._K[_N_STAGES].copy()
        self._dense = None
        if t_new >= self.t_bound:
            self.status = "finished"

    def dense_output(self) -> DenseStep:
        """The continuous extension over the last step [t_old, t] (3 evaluations the
        first time it is asked for after a step, none after that).

        Raises
        ------
        OutOfDomainError
            No step has been taken yet.
        NonFiniteError, ResultOverflowError
            ``rhs`` returned NaN/inf in an extra stage (naming the time), or the
            interpolant's coefficients overflowed.
        """
        if self.t_old is None:
            raise OutOfDomainError("dense_output() needs a step: t_old is None, call step() first")
        if self._dense is None:
            args = (self.t_old, self._y_old, self.y, self._h, self._K_ext)
            with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
                F = _dop853_dense(self._f, *args)
                if not np.isfinite(F).all():  # find the stage and name its time, else:
                    _dop853_dense(_checked(self._f), *args)
                    raise ResultOverflowError(
                        f"dop853: the dense output of the step from t={self.t_old!r} to "
                        f"t={self.t!r} overflowed"
                    )
            self.rhs_evals += _N_STAGES_EXTENDED - _N_STAGES - 1
            self._dense = DenseStep(self.t_old, self.t, self._y_old, F)
        return self._dense

    def __repr__(self) -> str:
        return (
            f"DOP853Stepper(t={self.t!r}, t_bound={self.t_bound!r}, status={self.status!r}, "
            f"steps={self.steps}, rhs_evals={self.rhs_evals})"
        )
