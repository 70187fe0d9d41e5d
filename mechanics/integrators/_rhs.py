"""A user's right-hand side wrapped: its output's shape checked on every call, and a
non-finite value reported with the time.

Part of :mod:`mechanics.integrators` (its docstring states the conventions).
"""

from __future__ import annotations

import numpy as np

from ..errors import NonFiniteError, ShapeError
from ._solution import FloatArray, Rhs


def _wrap_rhs(rhs: Rhs, shape: tuple[int, ...]) -> Rhs:
    """rhs with its output's shape checked on every call (a cheap attribute test)."""

    def f(t: float, y: FloatArray) -> FloatArray:
        k = rhs(t, y)
        if getattr(k, "shape", None) != shape:
            try:
                k = np.asarray(k, dtype=np.float64)
            except (TypeError, ValueError) as exc:
                raise ShapeError(f"rhs returned a non-numeric value at t={t!r}: {exc}") from None
            if k.shape != shape:
                raise ShapeError(
                    f"rhs returned shape {k.shape} at t={t!r}; expected y0's shape {shape}"
                )
        return k

    return f


def _checked(f: Rhs) -> Rhs:
    """f that raises NonFiniteError naming the time where it returns NaN or inf."""

    def g(t: float, y: FloatArray) -> FloatArray:
        k = f(t, y)
        if not np.isfinite(k).all():
            idx = tuple(int(i) for i in np.argwhere(~np.isfinite(k))[0])
            raise NonFiniteError(
                f"rhs returned a non-finite value at t={float(t)!r}: "
                f"{float(np.asarray(k)[idx])!r} at index {idx}"
            )
        return k

    return g
