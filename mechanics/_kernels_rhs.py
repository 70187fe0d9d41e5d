"""numba-compiled steppers for a user's compiled right-hand side (issue 30).

Private: :func:`mechanics.integrators.integrate` validates every input, imports this module
on the first call with a numba-compiled ``rhs`` (so ``import mechanics`` never pays for
numba) and falls back to its pure-numpy reference path, with one warning naming why, if
numba is missing, the ``rhs`` cannot be compiled for the signature below, or a kernel fails
to compile.

Conventions
-----------
- **The right-hand side** is a numba dispatcher (``@numba.njit``) of the signature
  :data:`RHS_SIGNATURE`, ``rhs(t: float64, y: float64[::1]) -> float64[::1]``: a 1-D
  state, a fresh (or any C-contiguous) array of the same length returned.  It arrives as a
  first-class function (``numba.types.FunctionType``), so each kernel below is compiled
  once for every right-hand side and cached on disk (``cache=True``, one entry); numba
  converts the dispatcher at each call (tens of µs, paid once per :func:`integrate`).
- **The same steps as the reference.**  RK4 and DOP853 here are the loops of
  :mod:`mechanics._kernels` (the free body's kernels) with the right-hand side called at
  the stage times t + c h: the tableau, the step-control constants, the error norm and the
  initial step are the reference's, passed in as arguments or shared with
  :mod:`mechanics._kernels` (one source of truth).
- **Status codes** instead of exceptions, as in :mod:`mechanics._kernels`, and one more:
  4, the right-hand side returned an array of another length.  On any code but 0 the
  caller re-runs the reference path, which raises the error naming the time.
- Compiled eagerly for :data:`RHS_SIGNATURE` when this module is imported (from the disk
  cache after the first time), with ``njit(sig, cache=True, error_model="numpy")`` applied
  after each definition, not as a decorator, so that mutmut mutates the kernels: under
  mutation (``NUMBA_DISABLE_JIT=1``) the kernels run as plain Python.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any, TypeVar, cast

import numpy as np
import numpy.typing as npt
from numba import njit, types
from numba.core.typing.templates import Signature

from ._kernels import (
    STATUS_MAX_STEPS,
    STATUS_NONFINITE,
    STATUS_OK,
    STATUS_STEP_TOO_SMALL,
    _all_finite,
    _error_norm,
)
from .integrators import _events

STATUS_SHAPE = 4

_ARRAY = types.float64[::1]
_MATRIX = types.float64[:, ::1]
#: The right-hand side's signature: rhs(t, y) → dy/dt, y and dy/dt C-contiguous 1-D.
RHS_SIGNATURE = _ARRAY(types.float64, _ARRAY)
_RHS = types.FunctionType(RHS_SIGNATURE)

F = TypeVar("F", bound=Callable[..., Any])


def _compile(sig: Signature) -> Callable[[F], F]:
    """``njit`` for one signature, cached on disk (the kernels' one compile setting); the
    dispatcher it returns is called as the function it compiles.  For the kernels, whose
    function arguments must be typed as :data:`RHS_SIGNATURE`'s first-class functions:
    compiled (or loaded from the cache) when this module is imported."""
    return cast(Callable[[F], F], njit(sig, cache=True, error_model="numpy"))


def _helper(fn: F) -> F:
    """``njit`` without a signature, for the helpers the kernels call: compiled into each
    kernel that calls them, so that loading a kernel from the cache loads no helper."""
    return cast(F, njit(cache=True, error_model="numpy")(fn))


def _eval(
    rhs: Callable[..., npt.NDArray[np.float64]],
    t: float,
    y: npt.NDArray[np.float64],
    out: npt.NDArray[np.float64],
) -> bool:  # pragma: no cover
    """out[:] = rhs(t, y); False if rhs returned an array of another length."""
    k = rhs(t, y)
    if k.size != out.size:
        return False
    for i in range(out.size):
        out[i] = k[i]
    return True


_eval = _helper(_eval)


def rk4_rhs(
    rhs: Callable[..., npt.NDArray[np.float64]],
    y0: npt.NDArray[np.float64],
    t: npt.NDArray[np.float64],
    ns: npt.NDArray[np.int64],
    ys: npt.NDArray[np.float64],
) -> tuple[int, int]:  # pragma: no cover
    """RK4: ns[k] equal steps over [t[k], t[k+1]], stage times t_k + (j + c) h_k (the
    reference's ``_rk4_run``); the states at the output times go into ys (len(t), n).
    Returns (status, steps)."""
    n = y0.size
    y = y0.copy()
    k1 = np.empty(n)
    k2 = np.empty(n)
    k3 = np.empty(n)
    k4 = np.empty(n)
    tmp = np.empty(n)
    ys[0] = y
    steps = 0
    for k in range(t.size - 1):
        m = ns[k]
        tk = t[k]
        hk = (t[k + 1] - tk) / m
        half = 0.5 * hk
        sixth = hk / 6.0
        for j in range(m):
            tm = tk + (j + 0.5) * hk
            if not _eval(rhs, tk + j * hk, y, k1):
                return STATUS_SHAPE, steps
            for i in range(n):
                tmp[i] = y[i] + half * k1[i]
            if not _eval(rhs, tm, tmp, k2):
                return STATUS_SHAPE, steps
            for i in range(n):
                tmp[i] = y[i] + half * k2[i]
            if not _eval(rhs, tm, tmp, k3):
                return STATUS_SHAPE, steps
            for i in range(n):
                tmp[i] = y[i] + hk * k3[i]
            if not _eval(rhs, tk + (j + 1) * hk, tmp, k4):
                return STATUS_SHAPE, steps
            for i in range(n):
                y[i] = y[i] + sixth * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i])
        steps += m
        if not _all_finite(y):
            return STATUS_NONFINITE, steps
        ys[k + 1] = y
    return STATUS_OK, steps


rk4_rhs = _compile(types.UniTuple(types.int64, 2)(_RHS, _ARRAY, _ARRAY, types.int64[::1], _MATRIX))(
    rk4_rhs
)


def _stage_input(
    K: npt.NDArray[np.float64],
    A: npt.NDArray[np.float64],
    s: int,
    y: npt.NDArray[np.float64],
    hh: float,
    out: npt.NDArray[np.float64],
) -> None:  # pragma: no cover
    """out = y + hh Σ_{j<s} a_sj k_j: the state stage s is evaluated at (the sum in the
    order of :mod:`mechanics._kernels`' loops)."""
    for i in range(y.size):
        acc = 0.0
        for j in range(s):
            acc += K[j, i] * A[s, j]
        out[i] = y[i] + hh * acc


_stage_input = _helper(_stage_input)


def _dense(
    rhs: Callable[..., npt.NDArray[np.float64]],
    tc: float,
    hh: float,
    y: npt.NDArray[np.float64],
    y_new: npt.NDArray[np.float64],
    K: npt.NDArray[np.float64],
    A: npt.NDArray[np.float64],
    C: npt.NDArray[np.float64],
    D: npt.NDArray[np.float64],
    ns: int,
    tmp: npt.NDArray[np.float64],
    F: npt.NDArray[np.float64],
) -> int:  # pragma: no cover
    """The interpolant's rows F (7, n) of the step of hh from (tc, y) to y_new, K holding
    its 12 stages and K[12] = f_new: the 3 extra stages go into K[13:16] (the reference's
    ``_dop853_dense``).  Returns a status (OK, SHAPE or NONFINITE)."""
    n = y.size
    n_ext = A.shape[0]
    for q in range(ns + 1, n_ext):
        _stage_input(K, A, q, y, hh, tmp)
        if not _eval(rhs, tc + C[q] * hh, tmp, K[q]):
            return STATUS_SHAPE
    for i in range(n):
        dlt = y_new[i] - y[i]
        F[0, i] = dlt
        F[1, i] = hh * K[0, i] - dlt
        F[2, i] = 2 * dlt - hh * (K[ns, i] + K[0, i])
        for r in range(D.shape[0]):
            acc = 0.0
            for q in range(n_ext):
                acc += D[r, q] * K[q, i]
            F[3 + r, i] = hh * acc
    if not _all_finite(F.ravel()):
        return STATUS_NONFINITE
    return STATUS_OK


_dense = _helper(_dense)


def _interpolate(
    F: npt.NDArray[np.float64],
    y: npt.NDArray[np.float64],
    x: float,
    out: npt.NDArray[np.float64],
) -> None:  # pragma: no cover
    """out = the interpolant at x = (τ − t_old)/h (the reference's :class:`DenseStep`,
    Horner in the same order)."""
    for i in range(y.size):
        v = 0.0
        for r in range(7):
            v += F[6 - r, i]
            v *= x if r % 2 == 0 else 1.0 - x
        out[i] = v + y[i]


_interpolate = _helper(_interpolate)


crosses = _helper(_events.crosses)
bracket_step = _helper(_events.bracket_step)


def dop853_rhs(
    rhs: Callable[..., npt.NDArray[np.float64]],
    y0: npt.NDArray[np.float64],
    t: npt.NDArray[np.float64],
    h0: float,
    rtol: float,
    atol: float,
    groups: int,
    max_steps: int,
    A: npt.NDArray[np.float64],
    B: npt.NDArray[np.float64],
    C: npt.NDArray[np.float64],
    E3: npt.NDArray[np.float64],
    E5: npt.NDArray[np.float64],
    D: npt.NDArray[np.float64],
    ctrl: npt.NDArray[np.float64],
    ys: npt.NDArray[np.float64],
    event: Callable[..., float],
    has_event: bool,
    direction: float,
    xtol: float,
    ev: npt.NDArray[np.float64],
) -> tuple[int, int, int, int, int]:  # pragma: no cover
    """DOP853 (the reference's ``_integrate_dop853``): steps set by the error control
    towards t[-1], outputs inside a step from its 7th-order continuous extension.  A
    (16, 16), C (16,) the extended tableau, D (4, 16) the interpolant's matrix.  h0 > 0 the
    first step (the caller computes Hairer's).  ctrl = (safety, min factor, max factor,
    exponent, β): β = 0 the reference's control, β > 0 Gustafsson's PI control as in
    Hairer's DOP853.

    With ``has_event``, the run stops where ``event(t, y)`` first crosses zero in
    ``direction`` (``_events.crosses``, checked at the end of each accepted step), located
    on the step's interpolant by ``_events.bracket_step`` to a bracket of ``xtol`` · max(|t|, h)
    whose right end, on or past the crossing, is the event: ev = (t_event, y_event...).
    Returns (status, steps, evals, rejected, outputs filled)."""
    n = y0.size
    ns = B.size  # 12 stages
    n_ext = A.shape[0]  # 16: the dense output's 3 extra stages after f_new
    F = np.empty((7, n))
    safety, min_factor, max_factor, exponent = ctrl[0], ctrl[1], ctrl[2], ctrl[3]
    beta = ctrl[4]  # the PI controller's proportional gain; 0: the reference's control
    err_old = 1.0  # the last accepted step's error (Hairer's facold)
    y = y0.copy()
    y_new = np.empty(n)
    tmp = np.empty(n)
    K = np.empty((n_ext, n))
    f0 = np.empty(n)
    ys[0] = y
    tc = t[0]
    if not _eval(rhs, tc, y, f0):
        return STATUS_SHAPE, 0, 1, 0, 1
    evals = 1
    if not _all_finite(f0):
        return STATUS_NONFINITE, 0, evals, 0, 1
    g_old = event(tc, y) if has_event else 0.0
    if not math.isfinite(g_old):  # the reference raises NonFiniteError, naming t
        return STATUS_NONFINITE, 0, evals, 0, 1
    h_abs = h0
    steps = 0
    rejected = 0
    nt = t.size
    t_end = t[nt - 1]
    k = 1  # the next output
    while k < nt:
        min_step = 10.0 * (np.nextafter(abs(tc), np.inf) - abs(tc))
        if h_abs < min_step:
            h_abs = min_step
        was_rejected = False
        while True:
            t_new = tc + h_abs
            if t_new >= t_end:
                t_new = t_end
            hh = t_new - tc
            for i in range(n):
                K[0, i] = f0[i]
            for s in range(1, ns):
                _stage_input(K, A, s, y, hh, tmp)
                if not _eval(rhs, tc + C[s] * hh, tmp, K[s]):
                    return STATUS_SHAPE, steps, evals + s, rejected, k
            for i in range(n):
                acc = 0.0
                for j in range(ns):
                    acc += K[j, i] * B[j]
                y_new[i] = y[i] + hh * acc
            if not _eval(rhs, t_new, y_new, K[ns]):
                return STATUS_SHAPE, steps, evals + ns, rejected, k
            evals += ns
            err = _error_norm(K[: ns + 1], E5, E3, hh, y, y_new, rtol, atol, groups)
            if not math.isfinite(err):
                return STATUS_NONFINITE, steps, evals, rejected, k
            if err < 1.0:
                if err == 0.0:
                    factor = max_factor
                else:  # Gustafsson's PI: err^(−1/8 + 0.2 β) err_old^β; β = 0: scipy's
                    factor = min(
                        max_factor, safety * err ** (exponent + 0.2 * beta) * err_old**beta
                    )
                err_old = max(err, 1e-4)
                if was_rejected:
                    factor = min(1.0, factor)
                if not _all_finite(y_new):
                    return STATUS_NONFINITE, steps, evals, rejected, k
                h_abs = hh * factor
                break
            rejected += 1
            was_rejected = True
            h_abs = hh * max(min_factor, safety * err ** (exponent + 0.2 * beta))
            if h_abs < min_step:
                return STATUS_STEP_TOO_SMALL, steps, evals, rejected, k
        steps += 1
        hit = False
        g_new = 0.0
        if has_event:
            g_new = event(t_new, y_new)
            if not math.isfinite(g_new):
                return STATUS_NONFINITE, steps, evals, rejected, k
            hit = crosses(g_old, g_new, direction)
        j = k
        while j < nt and t[j] < t_new:
            j += 1
        if j > k or hit:  # outputs inside the step or an event: its continuous extension
            status = _dense(rhs, tc, hh, y, y_new, K, A, C, D, ns, tmp, F)
            evals += n_ext - ns - 1
            if status != STATUS_OK:
                return status, steps, evals, rejected, k
        if hit:
            a, ga, b, gb = tc, g_old, t_new, g_new
            tol = xtol * max(abs(t_new), hh)
            side = 0
            it = 0
            while b - a > tol and gb != 0.0:
                m = bracket_step(a, ga, b, gb, tol, it)
                _interpolate(F, y, (m - tc) / hh, tmp)
                gm = event(m, tmp)
                if not math.isfinite(gm):
                    return STATUS_NONFINITE, steps, evals, rejected, k
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
            ev[0] = b
            if b == t_new:
                for i in range(n):
                    ev[1 + i] = y_new[i]
            else:
                _interpolate(F, y, (b - tc) / hh, tmp)
                for i in range(n):
                    ev[1 + i] = tmp[i]
            j = k  # the outputs before the event
            while j < nt and t[j] < b:
                j += 1
        for m in range(k, j):  # (outputs inside the step: its extension was built above)
            _interpolate(F, y, (t[m] - tc) / hh, tmp)
            for i in range(n):
                ys[m, i] = tmp[i]
        if hit:
            return STATUS_OK, steps, evals, rejected, j
        if j < nt and t[j] == t_new:
            for i in range(n):
                ys[j, i] = y_new[i]
            j += 1
        k = j
        for i in range(n):
            y[i] = y_new[i]
            f0[i] = K[ns, i]
        tc = t_new
        g_old = g_new
        if steps >= max_steps and k < nt:
            return STATUS_MAX_STEPS, steps, evals, rejected, k
    return STATUS_OK, steps, evals, rejected, nt


#: An event function's signature: event(t, y) → float, y C-contiguous 1-D.
EVENT_SIGNATURE = types.float64(types.float64, _ARRAY)
_EVENT = types.FunctionType(EVENT_SIGNATURE)

dop853_rhs = _compile(
    types.UniTuple(types.int64, 5)(
        _RHS,
        _ARRAY,
        _ARRAY,
        types.float64,
        types.float64,
        types.float64,
        types.int64,
        types.int64,
        _MATRIX,
        _ARRAY,
        _ARRAY,
        _ARRAY,
        _ARRAY,
        _MATRIX,
        _ARRAY,
        _MATRIX,
        _EVENT,
        types.boolean,
        types.float64,
        types.float64,
        _ARRAY,
    )
)(dop853_rhs)


def no_event(t: float, y: npt.NDArray[np.float64]) -> float:  # pragma: no cover
    """The event argument of a run without an event (never called)."""
    return 1.0


no_event = _compile(EVENT_SIGNATURE)(no_event)
