"""Classical Runge–Kutta (order 4) over a grid of output times, reference and compiled.

Part of :mod:`mechanics.integrators` (its docstring states the conventions).
"""

from __future__ import annotations

import numpy as np

from ..errors import ResultOverflowError
from ._compiled import _free_body_args, _run_compiled, _run_user_rhs, is_numba_function
from ._grid import _substep_counts, _substeps
from ._rhs import _checked
from ._solution import FloatArray, Rhs, Run


def _rk4_run(
    f: Rhs,
    tk: float,
    hk: float,
    n: int,
    y: FloatArray,
    comp: FloatArray,
    kahan: bool,
    check: bool,
) -> tuple[FloatArray, FloatArray]:
    """n RK4 steps of hk from tk; stage times tk + (j + c) hk."""
    half = 0.5 * hk
    sixth = hk / 6.0
    for j in range(n):
        ts = tk + j * hk
        tm = tk + (j + 0.5) * hk
        k1 = f(ts, y)
        k2 = f(tm, y + half * k1)
        k3 = f(tm, y + half * k2)
        k4 = f(tk + (j + 1) * hk, y + hk * k3)
        dy = sixth * (k1 + 2.0 * (k2 + k3) + k4)
        if kahan:
            z = dy - comp
            y_new = y + z
            comp = (y_new - y) - z
            y = y_new
        else:
            y = y + dy
        if check and not np.isfinite(y).all():
            raise ResultOverflowError(
                f"the state overflowed in the RK4 step from t={ts!r} to "
                f"t={tk + (j + 1) * hk!r}; the solution leaves float64 there"
            )
    return y, comp


def _integrate_rk4(f: Rhs, y0: FloatArray, t: FloatArray, h: float, kahan: bool) -> Run:
    ys = np.empty((t.shape[0], *y0.shape))
    ys[0] = y0
    y = y0.copy()
    comp = np.zeros_like(y0)
    steps = 0
    for k in range(t.shape[0] - 1):
        tk = float(t[k])
        d = float(t[k + 1]) - tk
        n = _substeps(tk, float(t[k + 1]), h)
        y_start, c_start = y, comp
        y, comp = _rk4_run(f, tk, d / n, n, y, comp, kahan, check=False)
        if not np.isfinite(y).all():  # find the step and the stage, then raise
            _rk4_run(_checked(f), tk, d / n, n, y_start, c_start, kahan, check=True)
            raise ResultOverflowError(
                f"the state became non-finite between t={tk!r} and t={float(t[k + 1])!r}"
            )  # pragma: no cover
        ys[k + 1] = y
        steps += n
    return ys, steps, 4 * steps, 0


def _rk4_compiled(rhs: Rhs, y0: FloatArray, t: FloatArray, h: float) -> Run | None:
    if is_numba_function(rhs):
        return _rk4_user(rhs, y0, t, h)
    args = _free_body_args(rhs, y0)
    if args is None:
        return None
    ns = _substep_counts(t, h)
    ys = np.empty((t.shape[0], y0.size))
    done = _run_compiled("rk4_free_body", *args, t, ns, ys)
    if done is None or done[0] != 0:  # the reference raises, naming the time
        return None
    return ys.reshape(t.shape[0], *y0.shape), done[1], 4 * done[1], 0


def _rk4_user(rhs: Rhs, y0: FloatArray, t: FloatArray, h: float) -> Run | None:
    """The run on :func:`mechanics._kernels_rhs.rk4_rhs`, or None (the reference path
    then runs): ``rhs`` numba-compiled (a plain function when numba's JIT is off, as
    under mutation, where the kernel runs as Python)."""
    ns = _substep_counts(t, h)
    ys = np.empty((t.shape[0], y0.size))
    done = _run_user_rhs("rk4_rhs", rhs, y0, t, ns, ys)
    if done is None or done[0] != 0:  # the reference raises, naming the time
        return None
    return ys.reshape(t.shape[0], *y0.shape), done[1], 4 * done[1], 0
