"""Dormand–Prince 8(5,3): the tableau, one step, its error norm and control, the
initial step, the batched run of :func:`~mechanics.integrators.integrate`, and the
7th-order continuous extension (:class:`DenseStep`).

Part of :mod:`mechanics.integrators` (its docstring states the conventions).
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt
from scipy.integrate._ivp import dop853_coefficients as _d853

from .._validate import as_float_array
from ..errors import ResultOverflowError, ShapeError, StepSizeError
from ._compiled import _free_body_args, _run_compiled
from ._rhs import _checked
from ._solution import FloatArray, Rhs, Run

#: Step control of ``"dop853"``: the values of Hairer's DOP853 and of scipy.
DOP853_SAFETY = 0.9
DOP853_MIN_FACTOR = 0.2
DOP853_MAX_FACTOR = 10.0
_DOP853_EXPONENT = -1.0 / 8.0  # −1/(q + 1), q = 7 the order of the error estimator

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
) -> tuple[float, FloatArray, FloatArray, float, float, int, int, FloatArray | None]:
    """One accepted DOP853 step from ``tc`` towards ``t_end``, rejected attempts inside.

    The step control of scipy's ``RungeKutta._step_impl``: the proposed ``h_abs`` is
    capped at ``max_step`` and raised to 10 ulp(tc), each attempt is truncated so
    that it ends exactly on ``t_end``, a rejected attempt shrinks the step by
    max(0.2, 0.9 err^(−1/8)) and an accepted one proposes hh · min(10, 0.9 err^(−1/8))
    (at most hh right after a rejection).  ``comp`` is the Kahan compensation (or
    None): the increment added is then z = incr − comp.

    Returns
    -------
    t_new, y_new, f_new, hh, h_next, evals, rejected, z
        The accepted step hh = t_new − tc (K holds its 12 stages and K[12] =
        f_new), the next proposal, the evaluations and rejections it took, and z
        (None without compensation).
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
            else:
                factor = min(DOP853_MAX_FACTOR, DOP853_SAFETY * err**_DOP853_EXPONENT)
            if was_rejected:
                factor = min(1.0, factor)
            # An infinite y_new makes its scale infinite and so the error norm 0, which
            # would pass (scipy accepts such a step): refuse it.
            if not np.isfinite(y_new).all():
                raise ResultOverflowError(
                    f"dop853: the state overflowed in the step from t={tc!r} to t={t_new!r} "
                    f"(|y| beyond the float64 range, the rates finite)"
                )
            return t_new, y_new, f_new, hh, hh * factor, evals, rejected, z
        rejected += 1
        was_rejected = True
        h_abs = hh * max(DOP853_MIN_FACTOR, DOP853_SAFETY * err**_DOP853_EXPONENT)
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
) -> Run:
    """Steps chosen by the error control alone, towards t[-1]; the outputs inside a
    step come from its 7th-order continuous extension (3 more evaluations for a
    step that holds any), an output on a step's end is that step's state."""
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

    def f_flat(tt: float, yy: FloatArray) -> FloatArray:
        return f(tt, yy.reshape(shape)).reshape(-1)

    steps = rejected = 0
    k = 1  # the next output
    while k < nt:
        t_new, y_new, f0, hh, h_abs, ev, rej, z = _dop853_advance(
            f, tc, y, f0, h_abs, t_final, math.inf, K, Kv, shape, rtol, atol, nb, comp
        )
        evals += ev
        rejected += rej
        steps += 1
        j = k
        while j < nt and tl[j] < t_new:
            j += 1
        if j > k:  # outputs strictly inside the step: its continuous extension
            F = _dop853_dense(f_flat, tc, y, y_new, hh, K_ext)
            evals += _N_STAGES_EXTENDED - _N_STAGES - 1
            if not np.isfinite(F).all():
                _dop853_dense(_checked(f_flat), tc, y, y_new, hh, K_ext)
                raise ResultOverflowError(
                    f"dop853: the dense output of the step from t={tc!r} to t={t_new!r} overflowed"
                )
            ys[k:j] = DenseStep(tc, t_new, y, F)(t[k:j]).T.reshape(j - k, *shape)
        if j < nt and tl[j] == t_new:
            ys[j] = y_new.reshape(shape)
            j += 1
        k = j
        if z is not None:  # None exactly when comp is (no compensation)
            comp = (y_new - y) - z
        y, tc = y_new, t_new
        if steps >= max_steps and k < nt:
            raise StepSizeError(
                f"dop853: {steps} steps reached t={tc!r} of {t_final!r}; "
                f"raise max_steps={max_steps} or loosen rtol={rtol!r}"
            )
    return ys, steps, evals, rejected


class DenseStep:
    """The 7th-order continuous extension of one DOP853 step over [t_old, t].

    Hairer's ``contd8`` as scipy's ``Dop853DenseOutput``: with x = (τ − t_old)/h,
    h = t − t_old, and the rows F_0 … F_6 of :attr:`F`,

    y(τ) = y_old + x (F_0 + (1 − x) (F_1 + x (F_2 + (1 − x) (F_3 + x (F_4 + (1 − x)
    (F_5 + x F_6)))))),

    evaluated in that order (so that it agrees with scipy's to the last bit).  At
    x = 0 it is y_old exactly; at x = 1 it is y_old + (y − y_old), within one
    rounding of y.  Evaluation outside [t_old, t] extrapolates (not accurate).

    Attributes
    ----------
    t_old, t : float
        The step's ends.
    y_old : ndarray, shape (n,)
        The state at ``t_old`` (read-only).
    F : ndarray, shape (7, n)
        The interpolant's coefficients (read-only).
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
) -> Run | None:
    args = _free_body_args(rhs, y0)
    if args is None:
        return None
    nb = int(np.prod(y0.shape[:batch_ndim], dtype=np.int64)) if batch_ndim else 1
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
        _A_FULL,
        _B,
        _C_ARRAY,
        _E3,
        _E5,
        _D_ARRAY,
        ctrl,
        ys,
    )
    if done is None or done[0] != 0:  # the reference raises, naming the time
        return None
    return ys.reshape(t.shape[0], *y0.shape), done[1], done[2], done[3]
