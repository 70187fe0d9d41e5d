"""Cross products of 3-vectors, written out: the engine's hot paths call them tens of
thousands of times per run, where ``np.cross`` spends ~15–20 µs on axis handling
(``moveaxis``, ``normalize_axis_tuple``) for three products and three differences
(measured: half of a heavy top's integration went there).

Both compute each component as numpy does, ``a1 b2 − a2 b1`` and so on (a product,
a product, a difference: no fused operations), so the results are the same bits as
``np.cross``.
"""

from __future__ import annotations

from typing import TypeAlias

import numpy as np
import numpy.typing as npt

__all__ = ["FloatArray", "IntArray", "Times", "cross", "cross3"]

#: A float64 array (a vector, a state, samples): the scene engine's arrays.
FloatArray: TypeAlias = npt.NDArray[np.float64]
#: An int64 array (indices into a state).
IntArray: TypeAlias = npt.NDArray[np.int64]
#: Time(s): one, or an array of them.
Times: TypeAlias = FloatArray | float


def cross3(a: FloatArray, b: FloatArray) -> FloatArray:
    """a × b of two 3-vectors (1-D), written out: the engine's per-contact products,
    where ``np.cross`` costs ~15 µs of axis handling for 3 products (measured: a
    support switch search spent a third of its time there)."""
    a0, a1, a2 = float(a[0]), float(a[1]), float(a[2])
    b0, b1, b2 = float(b[0]), float(b[1]), float(b[2])
    return np.array([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0])


def cross(a: npt.ArrayLike, b: npt.ArrayLike) -> FloatArray:
    """a × b over the last axis (length 3) of two float arrays that broadcast, as
    ``np.cross(a, b)``: the same shape and the same bits.

    >>> cross([1.0, 0.0, 0.0], [[0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]).tolist()
    [[0.0, 0.0, 1.0], [0.0, -1.0, 0.0]]
    """
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    if a.shape[-1] != 3 or b.shape[-1] != 3:
        raise ValueError(f"cross: shapes {a.shape} and {b.shape} must end in 3")
    if a.ndim == 1 and b.ndim == 1:
        return cross3(a, b)
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    return np.stack([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0], axis=-1)
