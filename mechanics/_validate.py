"""Input validation at the public boundary (private helpers).

``as_float_array`` is the one gate every public function passes its array inputs
through: it converts to float64 without silently truncating complex or object
input, checks the trailing shape, and rejects NaN and infinities by naming the
first offending entry.
"""

from __future__ import annotations

import numpy as np

from .errors import NonFiniteError, ShapeError


def _first_bad(a: np.ndarray) -> str:
    idx = np.argwhere(~np.isfinite(a))[0]
    return f"{a[tuple(idx)]!r} at index {tuple(int(i) for i in idx)}"


def as_float_array(x, name: str, tail: tuple[int, ...] = ()) -> np.ndarray:
    """Return ``x`` as a finite float64 array whose shape ends with ``tail``."""
    try:
        a = np.asarray(x)
    except Exception as exc:  # ragged lists and the like
        raise ShapeError(f"{name} is not an array of numbers: {exc}") from None
    if a.dtype.kind == "c":
        raise ShapeError(f"{name} is complex ({a.dtype}); a real array is required")
    if a.dtype.kind not in "biuf":
        raise ShapeError(f"{name} has dtype {a.dtype}; a real numeric array is required")
    a = a.astype(np.float64, copy=False)
    if tail and (a.ndim < len(tail) or a.shape[a.ndim - len(tail) :] != tail):
        want = "(..., " + ", ".join(map(str, tail)) + ")"
        raise ShapeError(f"{name} has shape {a.shape}; expected {want}")
    if not np.isfinite(a).all():
        raise NonFiniteError(f"{name} must be finite; found {_first_bad(a)}")
    return a
