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
    """a × b of two 3-vectors (1-D), written out.

    The engine's per-contact products, where ``np.cross`` costs ~15 µs of axis handling
    for 3 products (measured: a support switch search spent a third of its time there).
    The inputs are not checked: only their first three components are read.

    Parameters
    ----------
    a : ndarray, shape (3,)
        The first factor (any units).
    b : ndarray, shape (3,)
        The second factor (any units).

    Returns
    -------
    ndarray, shape (3,)
        a × b, the same bits as ``np.cross(a, b)``; its unit the product of theirs.

    Raises
    ------
    IndexError
        Where ``a`` or ``b`` has fewer than 3 components.
    TypeError
        Where a component is not a scalar (an array of more than one axis).

    Examples
    --------
    e1 × e2 = e3, and the same bits as ``np.cross``:

    >>> a, b = np.array([1.0, 2.0, 3.0]), np.array([4.0, 5.0, 6.0])
    >>> cross3(np.eye(3)[0], np.eye(3)[1]).tolist(), cross3(a, b).tolist()
    ([0.0, 0.0, 1.0], [-3.0, 6.0, -3.0])
    >>> bool(np.array_equal(cross3(a, b), np.cross(a, b)))
    True
    """
    a0, a1, a2 = float(a[0]), float(a[1]), float(a[2])
    b0, b1, b2 = float(b[0]), float(b[1]), float(b[2])
    return np.array([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0])


def cross(a: npt.ArrayLike, b: npt.ArrayLike) -> FloatArray:
    """a × b over the last axis (length 3) of two float arrays that broadcast.

    As ``np.cross(a, b)``: the same shape and the same bits (two 1-D vectors go to
    :func:`cross3`).

    Parameters
    ----------
    a : array_like, shape (..., 3)
        The first factor (any units), real numbers.
    b : array_like, shape (..., 3)
        The second factor; its leading axes broadcast with those of ``a``.

    Returns
    -------
    ndarray, shape (..., 3)
        a × b over the last axis, the leading axes broadcast; float64.

    Raises
    ------
    ValueError
        Where the last axis of ``a`` or ``b`` is not of length 3, where the leading axes
        do not broadcast, or where an input does not convert to float.
    IndexError
        Where an input is a scalar (it has no last axis).

    Examples
    --------
    e1 × e2 = e3 and e1 × e3 = −e2, the same bits as ``np.cross``:

    >>> b = [[0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    >>> cross([1.0, 0.0, 0.0], b).tolist()
    [[0.0, 0.0, 1.0], [0.0, -1.0, 0.0]]
    >>> bool(np.array_equal(cross([1.0, 0.0, 0.0], b), np.cross([1.0, 0.0, 0.0], b)))
    True
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
