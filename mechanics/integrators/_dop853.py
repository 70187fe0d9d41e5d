"""Dormand–Prince 8(5,3): the tableau, one step, its error norm and control, the
initial step, the batched run of :func:`~mechanics.integrators.integrate`, and the
7th-order continuous extension (:class:`DenseStep`).

Part of :mod:`mechanics.integrators` (its docstring states the conventions).
"""

from __future__ import annotations

import importlib.util
import math
import sys
from pathlib import Path
from types import ModuleType

import numpy as np
import numpy.typing as npt

from .._validate import as_float_array
from ..errors import NonFiniteError, ResultOverflowError, ShapeError, StepSizeError
from ._compiled import (
    NO_EVENT,
    _free_body_args,
    _run_compiled,
    _run_user_rhs,
    _warn_user_rhs,
    is_numba_function,
)
from ._events import EVENT_XTOL, bracket_step, crosses
from ._rhs import _checked, _wrap_rhs
from ._solution import Event, EventHit, FloatArray, Rhs, Run

#: Step control of ``"dop853"``: the values of Hairer's DOP853 and of scipy.
DOP853_SAFETY = 0.9
DOP853_MIN_FACTOR = 0.2
DOP853_MAX_FACTOR = 10.0
_DOP853_EXPONENT = -1.0 / 8.0  # −1/(q + 1), q = 7 the order of the error estimator
#: The PI step control's gain β (``integrate(..., beta=β)``) at most.  With err = err_prev
#: = e the factor is 0.9 e^(1.2 β − 1/8): its steady error e* = 0.9^(1/(1/8 − 1.2 β)) is
#: 0.43 of the tolerance at β = 0, 0.26 at 0.04, 0.026 at 0.08 (measured: 1.4× the steps)
#: and 7e-10 at 0.1 (3× the steps); from β = 5/48 ≈ 0.104 there is none and the steps
#: shrink without end (β = 0.2: 386915 steps where β = 0 took 94, forced oscillator
#: from (0, 1e-12) over 14 s at rtol 1e-12).  0.08: past it, more steps and no fewer
#: rejections to win.  (Hairer's DOP853 refuses only β > 0.2.)
DOP853_MAX_BETA = 0.08
_ERR_OLD_FLOOR = 1e-4  # Hairer's DOP853: facold = max(err, 1e-4)

#: scipy's module of the DOP853 tableau (Hairer's coefficients), which needs only numpy
_SCIPY_TABLEAU = "scipy.integrate._ivp.dop853_coefficients"


def _scipy_dop853_tableau() -> ModuleType:
    """scipy's DOP853 tableau (:data:`_SCIPY_TABLEAU`), loaded from its file without
    importing ``scipy.integrate``, whose package import took 0.75 s of the 0.9 s of
    ``import mechanics.integrators`` (``python -X importtime``), paid by every process
    that integrates, although the tableau is a few arrays.  Already imported, or in a
    layout of scipy without that file: imported as usual."""
    if _SCIPY_TABLEAU in sys.modules:
        return sys.modules[_SCIPY_TABLEAU]
    scipy_spec = importlib.util.find_spec("scipy")
    if scipy_spec is not None and scipy_spec.origin is not None:
        path = Path(scipy_spec.origin).parent / "integrate" / "_ivp" / "dop853_coefficients.py"
        spec = importlib.util.spec_from_file_location("_bodycheck_scipy_dop853", path)
        if path.is_file() and spec is not None and spec.loader is not None:
            module = importlib.util.module_from_spec(spec)
            try:
                spec.loader.exec_module(module)
            except Exception:  # a file that needs its package (another scipy): import it
                pass
            else:
                return module
    return importlib.import_module(_SCIPY_TABLEAU)


_d853 = _scipy_dop853_tableau()
# (scipy ships no types: the tableau's names are annotated here)
_N_STAGES: int = _d853.N_STAGES  # 12
_A: FloatArray = _d853.A[:_N_STAGES, :_N_STAGES]
_A_ROWS: list[FloatArray] = [np.ascontiguousarray(_A[s, :s]) for s in range(_N_STAGES)]
_B: FloatArray = np.ascontiguousarray(_d853.B)
_C: list[float] = [float(c) for c in _d853.C[:_N_STAGES]]
# The compiled path's copies of the same tableau (extended: 16 stages, and D)
_A_FULL: FloatArray = np.ascontiguousarray(_d853.A[:16, :16])
_C_ARRAY: FloatArray = np.ascontiguousarray(_d853.C[:16])
_E3: FloatArray = np.ascontiguousarray(_d853.E3)
_E5: FloatArray = np.ascontiguousarray(_d853.E5)
# Dense output (Hairer's contd8, as scipy's ``DOP853._dense_output_impl``): three
# extra stages K[13:16] (rows 13–15 of A, which also use K[12] = f(t_new, y_new)),
# then the 4 × 16 matrix D that gives the rows F_3 … F_6 of the interpolant.
_N_STAGES_EXTENDED: int = _d853.N_STAGES_EXTENDED  # 16
_A_EXTRA_ROWS: list[FloatArray] = [
    np.ascontiguousarray(_d853.A[s, :s]) for s in range(_N_STAGES + 1, _N_STAGES_EXTENDED)
]
_C_EXTRA: list[float] = [float(c) for c in _d853.C[_N_STAGES + 1 :]]
_D: FloatArray = _d853.D
_D_ARRAY: FloatArray = np.ascontiguousarray(_D)
#: what every DOP853 kernel takes after its tolerances and budget: A, B, C, E3, E5, D
_KERNEL_TABLEAU = (_A_FULL, _B, _C_ARRAY, _E3, _E5, _D_ARRAY)
_INTERPOLATOR_POWER: int = _d853.INTERPOLATOR_POWER  # 7
_TINY = np.finfo(np.float64).tiny


def _member_norms(v: FloatArray, nb: int) -> FloatArray:
    """RMS norm of each batch member (rows of v reshaped to (nb, -1)); one member
    in scipy's arithmetic (``common.norm``), so that the steps agree to the bit."""
    if nb == 1:
        return np.array([np.linalg.norm(v) / v.size**0.5])
    r = v.reshape(nb, -1)
    norms: FloatArray = np.sqrt((r * r).sum(axis=1) / r.shape[1])  # (sum(axis) is typed Any)
    return norms


def _dop853_step(
    f: Rhs,
    t: float,
    y: FloatArray,
    f0: FloatArray,
    h: float,
    K: FloatArray,
    Kv: FloatArray,
    shape: tuple[int, ...],
) -> FloatArray:
    """The 12 stages of one Dormand–Prince 8(5,3) step of h from (t, y): K[:12]
    filled (11 evaluations; K[0] = f0), the increment h Σ b_i k_i returned."""
    K[0] = f0.reshape(-1)
    for s in range(1, _N_STAGES):  # np.dot(K.T, a): scipy's ``rk_step``, the same sums
        dy = np.dot(K[:s].T, _A_ROWS[s])
        Kv[s] = f(t + _C[s] * h, (y + h * dy).reshape(shape))
    incr: FloatArray = h * np.dot(K[:_N_STAGES].T, _B)  # (np.dot is typed Any)
    return incr


def _dop853_error(
    K: FloatArray, h: float, y: FloatArray, y_new: FloatArray, rtol: float, atol: float, nb: int
) -> float:
    """The error norm of a step (K its 12 stages and f_new): scipy's
    ``DOP853._estimate_error_norm``, and for a batch the largest member's."""
    scale = atol + np.maximum(np.abs(y), np.abs(y_new)) * rtol
    e5 = np.dot(K.T, _E5) / scale
    e3 = np.dot(K.T, _E3) / scale
    if nb == 1:  # scipy's arithmetic, operation for operation: the steps agree to the bit
        e5n = np.linalg.norm(e5) ** 2
        e3n = np.linalg.norm(e3) ** 2
        if e5n == 0:  # (scipy tests both for 0; with e3n tiny, 0.01 e3n underflows: 0/0)
            return 0.0
        return float(abs(h) * e5n / np.sqrt((e5n + 0.01 * e3n) * e5.size))
    e5 = e5.reshape(nb, -1)
    e3 = e3.reshape(nb, -1)
    e5n = (e5 * e5).sum(axis=1)
    e3n = (e3 * e3).sum(axis=1)
    denom = np.maximum(e5n + 0.01 * e3n, _TINY)  # e5n = 0 there, so the ratio is 0
    return float((abs(h) * e5n / np.sqrt(denom * e5.shape[1])).max())


def _dop853_initial_step(
    f: Rhs,
    t0: float,
    y: FloatArray,
    f0: FloatArray,
    t_end: float,
    rtol: float,
    atol: float,
    nb: int,
    max_step: float = math.inf,
) -> float:
    """Hairer's starting step (as scipy's ``select_initial_step``), batch-aware:
    the state's size by its smallest member, the rates by their largest; at most
    the span t_end − t0 and ``max_step``."""
    scale = atol + np.abs(y) * rtol
    d0 = float(_member_norms(y / scale, nb).min())
    d1 = float(_member_norms(f0.reshape(-1) / scale, nb).max())
    h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
    h0 = min(h0, t_end - t0)
    if not h0 > 0.0:  # d1 = inf: rates beyond float64 once scaled by the tolerances
        raise StepSizeError(
            f"dop853: the starting step at t={t0!r} underflows to {h0!r}: the rates there, "
            f"scaled by rtol={rtol!r} and atol={atol!r}, have RMS norm {d1!r}; "
            f"give a step h or loosen the tolerances"
        )
    f1 = f(t0 + h0, (y + h0 * f0.reshape(-1)).reshape(f0.shape))
    d2 = float(_member_norms((f1.reshape(-1) - f0.reshape(-1)) / scale, nb).max()) / h0
    if d1 <= 1e-15 and d2 <= 1e-15:
        h1 = max(1e-6, h0 * 1e-3)
    else:
        h1 = (0.01 / max(d1, d2)) ** (1.0 / 8.0)
    return min(100 * h0, h1, t_end - t0, max_step)


def _dop853_advance(
    f: Rhs,
    tc: float,
    y: FloatArray,
    f0: FloatArray,
    h_abs: float,
    t_end: float,
    max_step: float,
    K: FloatArray,
    Kv: FloatArray,
    shape: tuple[int, ...],
    rtol: float,
    atol: float,
    nb: int,
    comp: FloatArray | None,
    beta: float = 0.0,
    err_old: float = 1.0,
) -> tuple[float, FloatArray, FloatArray, float, float, int, int, FloatArray | None, float]:
    """One accepted DOP853 step from ``tc`` towards ``t_end``, rejected attempts inside.

    The step control of scipy's ``RungeKutta._step_impl``: the proposed ``h_abs`` is
    capped at ``max_step`` and raised to 10 ulp(tc), each attempt is truncated so
    that it ends exactly on ``t_end``, a rejected attempt shrinks the step by
    max(0.2, 0.9 err^(−1/8)) and an accepted one proposes hh · min(10, 0.9 err^(−1/8))
    (at most hh right after a rejection).  ``comp`` is the Kahan compensation (or
    None): the increment added is then z = incr − comp.  With ``beta`` = β > 0 the
    control is Gustafsson's PI control as in Hairer's DOP853: err^(−1/8 + 0.2 β) in
    place of err^(−1/8), and an accepted step's factor times ``err_old``^β, the error
    of the last accepted step (at least 1e-4); β = 0 is the control above, exactly.

    Returns
    -------
    t_new, y_new, f_new, hh, h_next, evals, rejected, z, err
        The accepted step hh = t_new − tc (K holds its 12 stages and K[12] =
        f_new), the next proposal, the evaluations and rejections it took, z
        (None without compensation), and the ``err_old`` of the next step.
    """
    min_step = 10.0 * math.ulp(tc)
    if max_step < min_step:  # scipy fails here only if the proposal exceeds max_step
        raise StepSizeError(
            f"dop853: max_step={max_step!r} is below the rounding of t={tc!r} "
            f"(10 ulp = {min_step!r})"
        )
    if h_abs > max_step:
        h_abs = max_step
    elif h_abs < min_step:
        h_abs = min_step
    was_rejected = False
    evals = rejected = 0
    z: FloatArray | None = None
    while True:
        t_new = tc + h_abs
        if t_new >= t_end:
            t_new = t_end
        hh = t_new - tc
        incr = _dop853_step(f, tc, y, f0, hh, K, Kv, shape)
        evals += _N_STAGES
        if comp is None:
            y_new = y + incr
        else:
            z = incr - comp
            y_new = y + z
        f_new = f(t_new, y_new.reshape(shape))
        K[_N_STAGES] = f_new.reshape(-1)
        err = _dop853_error(K, hh, y, y_new, rtol, atol, nb)
        if not math.isfinite(err):
            _dop853_step(_checked(f), tc, y, f0, hh, K, Kv, shape)
            _checked(f)(t_new, y_new.reshape(shape))
            raise ResultOverflowError(
                f"dop853: the state overflowed in the step from t={tc!r} to t={t_new!r}"
            )
        if err < 1.0:
            if err == 0.0:
                factor = DOP853_MAX_FACTOR
            else:  # (β = 0: err^(−1/8) · 1, scipy's factor to the bit)
                factor = min(
                    DOP853_MAX_FACTOR,
                    DOP853_SAFETY * err ** (_DOP853_EXPONENT + 0.2 * beta) * err_old**beta,
                )
            if was_rejected:
                factor = min(1.0, factor)
            # An infinite y_new makes its scale infinite and so the error norm 0, which
            # would pass (scipy accepts such a step): refuse it.
            if not np.isfinite(y_new).all():
                raise ResultOverflowError(
                    f"dop853: the state overflowed in the step from t={tc!r} to t={t_new!r} "
                    f"(|y| beyond the float64 range, the rates finite)"
                )
            err_next = max(err, _ERR_OLD_FLOOR)
            return t_new, y_new, f_new, hh, hh * factor, evals, rejected, z, err_next
        rejected += 1
        was_rejected = True
        h_abs = hh * max(DOP853_MIN_FACTOR, DOP853_SAFETY * err ** (_DOP853_EXPONENT + 0.2 * beta))
        if h_abs < min_step:
            raise StepSizeError(
                f"dop853: the step fell to {h_abs!r}, below the rounding of t={tc!r}; "
                f"rtol={rtol!r}, atol={atol!r} cannot be met there"
            )


def _integrate_dop853(
    f: Rhs,
    y0: FloatArray,
    t: FloatArray,
    h: float | None,
    rtol: float,
    atol: float,
    kahan: bool,
    batch_ndim: int,
    max_steps: int,
    beta: float = 0.0,
    event: Event | None = None,
    direction: float = 0.0,
) -> tuple[Run, EventHit]:
    """Steps chosen by the error control alone, towards t[-1]; the outputs inside a
    step come from its 7th-order continuous extension (3 more evaluations for a
    step that holds any), an output on a step's end is that step's state.  With an
    ``event``, the run stops where it first crosses zero in ``direction``: the outputs
    before it, and (t_event, y_event) located on the step's extension."""
    shape = y0.shape
    nb = int(np.prod(shape[:batch_ndim], dtype=np.int64)) if batch_ndim else 1
    nt = t.shape[0]
    ys = np.empty((nt, *shape))
    ys[0] = y0
    y = y0.reshape(-1).copy()
    comp = np.zeros_like(y) if kahan else None
    K_ext = np.empty((_N_STAGES_EXTENDED, y.size))
    K = K_ext[: _N_STAGES + 1]
    Kv = K.reshape(_N_STAGES + 1, *shape)
    tc = float(t[0])
    t_final = float(t[-1])
    f0 = _checked(f)(tc, y0)
    evals = 1
    if h is None:
        h_abs = _dop853_initial_step(f, tc, y, f0, t_final, rtol, atol, nb)
        evals += 1
    else:
        h_abs = h
    tl = t.tolist()
    g_old = _event_value(event, tc, y0) if event is not None else 0.0

    def f_flat(tt: float, yy: FloatArray) -> FloatArray:
        return f(tt, yy.reshape(shape)).reshape(-1)

    steps = rejected = 0
    err_old = 1.0
    k = 1  # the next output
    while k < nt:
        t_new, y_new, f0, hh, h_abs, ev, rej, z, err_old = _dop853_advance(
            f,
            tc,
            y,
            f0,
            h_abs,
            t_final,
            math.inf,
            K,
            Kv,
            shape,
            rtol,
            atol,
            nb,
            comp,
            beta,
            err_old,
        )
        evals += ev
        rejected += rej
        steps += 1
        hit = False
        g_new = 0.0
        if event is not None:
            g_new = _event_value(event, t_new, y_new.reshape(shape))
            hit = crosses(g_old, g_new, direction)
        j = k
        while j < nt and tl[j] < t_new:
            j += 1
        dense: DenseStep | None = None
        if j > k or hit:  # outputs strictly inside the step, an event: its extension
            F = _dop853_dense(f_flat, tc, y, y_new, hh, K_ext)
            evals += _N_STAGES_EXTENDED - _N_STAGES - 1
            if not np.isfinite(F).all():
                _dop853_dense(_checked(f_flat), tc, y, y_new, hh, K_ext)
                raise ResultOverflowError(
                    f"dop853: the dense output of the step from t={tc!r} to t={t_new!r} overflowed"
                )
            dense = DenseStep(tc, t_new, y, F)
        if hit and event is not None:
            t_ev, y_ev = _locate_event(event, dense, g_old, g_new, y_new, shape)
            j = k
            while j < nt and tl[j] < t_ev:
                j += 1
            if j > k and dense is not None:
                ys[k:j] = dense(t[k:j]).T.reshape(j - k, *shape)
            return (ys[:j], steps, evals, rejected), (t_ev, y_ev)
        if j > k and dense is not None:
            ys[k:j] = dense(t[k:j]).T.reshape(j - k, *shape)
        if j < nt and tl[j] == t_new:
            ys[j] = y_new.reshape(shape)
            j += 1
        k = j
        if z is not None:  # None exactly when comp is (no compensation)
            comp = (y_new - y) - z
        y, tc = y_new, t_new
        g_old = g_new
        if steps >= max_steps and k < nt:
            raise StepSizeError(
                f"dop853: {steps} steps reached t={tc!r} of {t_final!r}; "
                f"raise max_steps={max_steps} or loosen rtol={rtol!r}"
            )
    return (ys, steps, evals, rejected), None


def _event_value(event: Event, t: float, y: FloatArray) -> float:
    """event(t, y) as a float: a ShapeError if it is not one real number, a
    NonFiniteError if it is NaN or infinite, both naming the time."""
    v = event(t, y)
    if np.ndim(v) != 0 or isinstance(v, (bool, np.bool_)):
        raise ShapeError(f"event returned {v!r} at t={t!r}; expected one real number")
    try:
        g = float(v)
    except (TypeError, ValueError):
        raise ShapeError(f"event returned {v!r} at t={t!r}; expected one real number") from None
    if not math.isfinite(g):
        raise NonFiniteError(f"event returned {g!r} at t={t!r}")
    return g


def _locate_event(
    event: Event,
    dense: DenseStep | None,
    g_old: float,
    g_new: float,
    y_new: FloatArray,
    shape: tuple[int, ...],
) -> tuple[float, FloatArray]:
    """The crossing in the step ``dense`` covers, bracketed on its interpolant to
    EVENT_XTOL · max(|t|, h) (the kernel's loop, step for step): the bracket's right
    end, on or past the crossing, and the state there."""
    assert dense is not None  # the caller built the step's extension
    a, ga, b, gb = dense.t_old, g_old, dense.t, g_new
    t_new = b
    tol = EVENT_XTOL * max(abs(t_new), dense.h)
    side = it = 0
    while b - a > tol and gb != 0.0:
        m = bracket_step(a, ga, b, gb, tol, it)
        gm = _event_value(event, m, dense(m).reshape(shape))
        if gm > 0.0 if g_old > 0.0 else gm < 0.0:  # still before the crossing
            a, ga = m, gm
            if side == -1:
                gb *= 0.5  # Illinois
            side = -1
        else:
            b, gb = m, gm
            if side == 1:
                ga *= 0.5
            side = 1
        it += 1
    y_ev = y_new if b == t_new else dense(b)
    return b, y_ev.reshape(shape).copy()


class DenseStep:
    """The 7th-order continuous extension of one DOP853 step over [t_old, t].

    Hairer's ``contd8`` as scipy's ``Dop853DenseOutput``: with x = (τ − t_old)/h,
    h = t − t_old, and the rows F_0 … F_6 of ``F``,

    y(τ) = y_old + x (F_0 + (1 − x) (F_1 + x (F_2 + (1 − x) (F_3 + x (F_4 + (1 − x)
    (F_5 + x F_6)))))),

    evaluated in that order (so that it agrees with scipy's to the last bit).  At
    x = 0 it is y_old exactly; at x = 1 it is y_old + (y − y_old), within one
    rounding of y.  Evaluation outside [t_old, t] extrapolates (not accurate).

    :meth:`DOP853Stepper.dense_output` builds it; calling it at a scalar time gives shape
    (n,), at a 1-D array of k times shape (n, k) (scipy's convention), and a time array of
    more dimensions raises ShapeError.

    Parameters
    ----------
    t_old, t : float
        The step's ends (s), t ≠ t_old.
    y_old : array_like, shape (n,)
        The state at ``t_old`` (copied, and read-only as an attribute).
    F : array_like, shape (7, n)
        The interpolant's coefficients (copied, and read-only as an attribute).

    Attributes
    ----------
    t_old, t : float
        The step's ends.
    h : float
        t − t_old.
    y_old : ndarray, shape (n,)
        The state at ``t_old`` (read-only).
    F : ndarray, shape (7, n)
        The interpolant's coefficients (read-only).

    Raises
    ------
    TypeError
        ``t_old`` or ``t`` not a number, or ``y_old`` or ``F`` an object numpy cannot
        convert (from ``float`` and ``np.array``: nothing is validated, the stepper builds
        it).
    ValueError
        A string that is not a number, or a ragged ``y_old`` or ``F`` (the same).

    Examples
    --------
    At the step's start the interpolant is y_old exactly, at its end the step's state:

    >>> from mechanics.integrators import DOP853Stepper
    >>> s = DOP853Stepper(lambda t, y: -y, 0.0, [1.0, 2.0], 1.0, rtol=1e-8, atol=1e-8)
    >>> s.step()
    >>> d = s.dense_output()
    >>> from mechanics._floats import EPS  # the interpolant's end: the step, to its rounding
    >>> bool((d(d.t_old) == d.y_old).all()), bool(np.allclose(d(d.t), s.y, rtol=EPS, atol=0))
    (True, True)
    """

    __slots__ = ("F", "_rev", "h", "t", "t_old", "y_old")

    def __init__(self, t_old: float, t: float, y_old: npt.ArrayLike, F: npt.ArrayLike) -> None:
        self.t_old, self.t = float(t_old), float(t)
        self.h = self.t - self.t_old
        self.y_old = np.array(y_old, dtype=np.float64)
        self.F = np.array(F, dtype=np.float64)
        self.y_old.flags.writeable = False
        self.F.flags.writeable = False
        self._rev: list[FloatArray] = list(reversed(self.F))

    def __call__(self, t: npt.ArrayLike) -> FloatArray:
        """The interpolated state: shape (n,) for a scalar ``t``, (n, k) for a 1-D
        array of k times (scipy's convention)."""
        if type(t) is float and math.isfinite(t):  # the event search's hot path
            x = (t - self.t_old) / self.h
            y = self._rev[0] * x
            for i, f in enumerate(self._rev[1:], start=1):
                y += f
                y *= x if i % 2 == 0 else 1.0 - x
            return y + self.y_old
        ta = as_float_array(t, "t")
        if ta.ndim > 1:
            raise ShapeError(f"t must be a scalar or a 1-D array of times; got shape {ta.shape}")
        if ta.ndim == 0:
            return self(float(ta))
        xs = (ta - self.t_old) / self.h
        ys = np.zeros((self.y_old.shape[0], ta.shape[0]))
        for i, f in enumerate(self._rev):
            ys += f[:, None]
            ys *= xs if i % 2 == 0 else 1.0 - xs
        return ys + self.y_old[:, None]

    def __repr__(self) -> str:
        return f"DenseStep(t_old={self.t_old!r}, t={self.t!r}, n={self.y_old.shape[0]})"


def _dop853_dense(
    f: Rhs, t_old: float, y_old: FloatArray, y: FloatArray, h: float, K: FloatArray
) -> FloatArray:
    """The coefficients F (7, n) of the interpolant over the step of h from (t_old,
    y_old) to y, K (16, n) holding its 12 stages and K[12] = f(t_old + h, y): the
    3 extra stages (3 evaluations) go into K[13:16] (scipy's ``_dense_output_impl``)."""
    for j, s in enumerate(range(_N_STAGES + 1, _N_STAGES_EXTENDED)):
        dy = _A_EXTRA_ROWS[j] @ K[:s]
        K[s] = f(t_old + _C_EXTRA[j] * h, y_old + h * dy)
    F = np.empty((_INTERPOLATOR_POWER, y.shape[0]))
    f_old, f_new = K[0], K[_N_STAGES]
    delta_y = y - y_old
    F[0] = delta_y
    F[1] = h * f_old - delta_y
    F[2] = 2 * delta_y - h * (f_new + f_old)
    F[3:] = h * (_D @ K)
    return F


def _dop853_compiled(
    rhs: Rhs,
    y0: FloatArray,
    t: FloatArray,
    h: float | None,
    rtol: float,
    atol: float,
    batch_ndim: int,
    max_steps: int,
    beta: float = 0.0,
    event: Event | None = None,
    direction: float = 0.0,
) -> tuple[Run, EventHit] | None:
    """The run on a compiled kernel, or None: the reference path runs (it also raises the
    error, naming the time, of a kernel that stopped on a non-finite value)."""
    nb = int(np.prod(y0.shape[:batch_ndim], dtype=np.int64)) if batch_ndim else 1
    if is_numba_function(rhs):
        if event is not None and not is_numba_function(event):
            _warn_user_rhs(rhs, "its event function is not numba-compiled", stacklevel=4)
            return None
        return _dop853_user(rhs, y0, t, h, rtol, atol, nb, max_steps, beta, event, direction)
    args = _free_body_args(rhs, y0)
    if args is None or beta != 0.0 or event is not None:  # the free body's kernel: neither
        return None
    ys = np.empty((t.shape[0], y0.size))
    ctrl = np.array([DOP853_SAFETY, DOP853_MIN_FACTOR, DOP853_MAX_FACTOR, _DOP853_EXPONENT])
    done = _run_compiled(
        "dop853_free_body",
        *args,
        t,
        -1.0 if h is None else h,
        rtol,
        atol,
        nb,
        max_steps,
        *_KERNEL_TABLEAU,
        ctrl,
        ys,
    )
    if done is None or done[0] != 0:  # the reference raises, naming the time
        return None
    return (ys.reshape(t.shape[0], *y0.shape), done[1], done[2], done[3]), None


def _dop853_user(
    rhs: Rhs,
    y0: FloatArray,
    t: FloatArray,
    h: float | None,
    rtol: float,
    atol: float,
    nb: int,
    max_steps: int,
    beta: float,
    event: Event | None,
    direction: float,
) -> tuple[Run, EventHit] | None:
    """The run on :func:`mechanics._kernels_rhs.dop853_rhs`, or None (the reference path
    then runs): ``rhs`` and ``event`` numba-compiled (plain functions when numba's JIT is
    off, as under mutation, where the kernel runs as Python).  Hairer's starting step is
    the reference's own :func:`_dop853_initial_step`, called from here (one rate more
    than the kernel counts), so that both paths start with the same step to the bit."""
    probe = 0
    if h is None and y0.ndim == 1:  # (another shape: the kernel's runner refuses it)
        f = _wrap_rhs(rhs, y0.shape)
        t0 = float(t[0])
        h = _dop853_initial_step(f, t0, y0, _checked(f)(t0, y0), float(t[-1]), rtol, atol, nb)
        probe = 1
    ys = np.empty((t.shape[0], y0.size))
    ev = np.empty(y0.size + 1)
    ctrl = np.array([DOP853_SAFETY, DOP853_MIN_FACTOR, DOP853_MAX_FACTOR, _DOP853_EXPONENT, beta])
    done = _run_user_rhs(
        "dop853_rhs",
        rhs,
        y0,
        t,
        h,
        rtol,
        atol,
        nb,
        max_steps,
        *_KERNEL_TABLEAU,
        ctrl,
        ys,
        NO_EVENT if event is None else event,
        event is not None,
        direction,
        EVENT_XTOL,
        ev,
    )
    if done is None or done[0] != 0:  # the reference raises, naming the time
        return None
    n_out = done[4]
    run = ys[:n_out].reshape(n_out, *y0.shape), done[1], done[2] + probe, done[3]
    # an event drops the outputs from t_event on, t[-1] among them (t_event ≤ t[-1])
    met = n_out < t.shape[0]
    return run, ((float(ev[0]), ev[1:].reshape(y0.shape).copy()) if met else None)
