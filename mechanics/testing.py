"""Test assertions that know the symmetries of rotations, with tolerances in eps.

Conventions
-----------
- Rotations are compared **as matrices** (the book's passive ^A R^O, or any
  3 × 3 arrays): parameters are not unique (ψ and φ at gimbal lock, ±π e_a),
  matrices are.  Quaternions are compared **up to sign**: q and −q are the
  same rotation.
- Errors are reported in units of float64 ``EPS`` (2.2e-16), with the index of
  the worst entry, so a failure reads "5.3 eps at index (1, 2)", not
  "arrays not equal".
- NaN or an infinity in either argument fails the assertion, naming where it
  is: a NaN must never pass a closeness test by accident.
- Tolerances are named multiples of ``EPS`` with their reason; pass a larger
  multiple explicitly where an algorithm documents a larger error.
- Arguments broadcast against each other like numpy's; the reported index is
  in the broadcast shape.

Examples
--------
>>> import numpy as np
>>> from mechanics.rotation import matrix_from_quat, quat_from_rotvec
>>> q = quat_from_rotvec([0.3, -1.0, 2.0])
>>> assert_quaternions_close(q, -q)
>>> assert_rotations_close(matrix_from_quat(q), matrix_from_quat(-q))
>>> assert_allclose_eps(np.float64(1.0) + EPS, 1.0)
>>> assert_allclose_eps(1.0 + 8 * EPS, 1.0)  # doctest: +ELLIPSIS
Traceback (most recent call last):
...
AssertionError: not close: relative error 8 eps at index () exceeds 4 eps (actual ...)
"""

from __future__ import annotations

import numbers
from typing import Any

import numpy as np
import numpy.typing as npt

from .rotation import EPS, ROUNDTRIP_ATOL

__all__ = [
    "ALLCLOSE_EPS_MULTIPLE",
    "EPS",
    "QUATERNIONS_CLOSE_ATOL",
    "ROTATIONS_CLOSE_ATOL",
    "assert_allclose_eps",
    "assert_quaternions_close",
    "assert_rotations_close",
]

#: Default for :func:`assert_rotations_close`: the round-trip accuracy promised
#: by :mod:`mechanics.rotation` (``ROUNDTRIP_ATOL`` = 4 eps, max-abs): each
#: matrix entry is a sum of at most three products of numbers within an ulp.
ROTATIONS_CLOSE_ATOL = ROUNDTRIP_ATOL

#: Default for :func:`assert_quaternions_close`: 4 eps, max-abs.  A unit
#: quaternion's components are at most 1, each within an ulp or so after a
#: conversion (measured worst against the exact quaternion: 0.6 eps for
#: quat_from_rotvec, 1.0 eps for quat_from_matrix of matrix_from_rotvec); 4 eps
#: allows a round trip through two or three conversions.
QUATERNIONS_CLOSE_ATOL = 4 * EPS

#: Default for :func:`assert_allclose_eps`: a handful of roundings, each at most
#: half an ulp relative, that is 4 eps of relative error.
ALLCLOSE_EPS_MULTIPLE = 4.0


def _as_finite(x: npt.ArrayLike, name: str) -> npt.NDArray[np.float64]:
    a = np.asarray(x)
    if a.dtype.kind not in "biuf":
        raise AssertionError(f"{name} has dtype {a.dtype}; real numbers are required")
    a = a.astype(np.float64, copy=False)
    bad = ~np.isfinite(a)
    if bad.any():
        idx = tuple(int(i) for i in np.argwhere(bad)[0])
        raise AssertionError(f"{name} holds {float(a[idx])!r} at index {idx}; it must be finite")
    return a


def _broadcast(
    actual: npt.ArrayLike,
    desired: npt.ArrayLike,
    tail: tuple[int, ...],
    names: tuple[str, str] = ("actual", "desired"),
) -> tuple[npt.NDArray[np.float64], ...]:
    a = _as_finite(actual, names[0])
    d = _as_finite(desired, names[1])
    for arr, name in ((a, names[0]), (d, names[1])):
        if tail and (arr.ndim < len(tail) or arr.shape[arr.ndim - len(tail) :] != tail):
            want = "(..., " + ", ".join(map(str, tail)) + ")"
            raise AssertionError(f"{name} has shape {arr.shape}; expected {want}")
    try:
        return np.broadcast_arrays(a, d)
    except ValueError:
        raise AssertionError(
            f"shapes {a.shape} and {d.shape} do not broadcast against each other"
        ) from None


def _check_tolerance(value: float, name: str) -> float:
    # a real number only: a string such as "1e-9" or a bool is refused, not coerced
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ValueError(
            f"{name}={value!r} must be a finite number >= 0; got a {type(value).__name__}"
        )
    v = float(value)
    if not np.isfinite(v) or v < 0:
        raise ValueError(f"{name}={value!r} must be a finite number >= 0")
    return v


#: how a message shows an error too large for float64
_BEYOND = f"beyond {np.finfo(np.float64).max:.3g}"


def _worst(err: npt.NDArray[np.float64]) -> tuple[int, ...]:
    return tuple(int(i) for i in np.unravel_index(int(np.argmax(err)), err.shape))


def assert_rotations_close(
    R1: npt.ArrayLike, R2: npt.ArrayLike, *, atol: float = ROTATIONS_CLOSE_ATOL, err_msg: str = ""
) -> None:
    """Assert two rotation matrices (..., 3, 3) agree entrywise within ``atol``.

    Compares matrices, not parameters, so it holds across the ambiguities of
    Euler angles at gimbal lock and of ±π rotation vectors.  The message names
    the worst entry and its error in eps.

    Parameters
    ----------
    R1, R2 : array_like, shape (..., 3, 3)
        The matrices (any 3 × 3 arrays), leading axes broadcasting against each other.
    atol : float
        The largest allowed |R1 − R2| of an entry, a finite number ≥ 0 (default
        :data:`ROTATIONS_CLOSE_ATOL`, 4 eps).
    err_msg : str
        Prepended to the failure message.

    Raises
    ------
    AssertionError
        An entry differs by more than ``atol`` (naming the worst entry, its error in eps
        and the two values), or an argument is not real, not finite (naming where), not
        of shape (..., 3, 3), or the two do not broadcast.
    ValueError
        ``atol`` not a finite real number ≥ 0 (a string or a bool is refused).

    Examples
    --------
    At gimbal lock θ = 0 only ψ + φ is defined: (0.3, 0, 0.5) and (0.8, 0, 0) are one
    rotation.

    >>> from mechanics.rotation import matrix_from_euler
    >>> assert_rotations_close(matrix_from_euler(0.3, 0.0, 0.5),
    ...                        matrix_from_euler(0.8, 0.0, 0.0))
    """
    __tracebackhide__ = True  # under pytest, a failure points at the caller
    tol = _check_tolerance(atol, "atol")
    a, b = _broadcast(R1, R2, (3, 3), ("R1", "R2"))
    err = np.abs(a - b)
    if err.size == 0 or not err.max() > tol:
        return
    idx = _worst(err)
    prefix = f"{err_msg}: " if err_msg else ""
    raise AssertionError(
        f"{prefix}rotations differ by {err[idx] / EPS:.3g} eps at entry {idx}, "
        f"more than atol = {tol / EPS:.3g} eps (R1 {float(a[idx])!r}, R2 {float(b[idx])!r})"
    )


def assert_quaternions_close(
    q1: npt.ArrayLike,
    q2: npt.ArrayLike,
    *,
    atol: float = QUATERNIONS_CLOSE_ATOL,
    err_msg: str = "",
) -> None:
    """Assert two quaternions (..., 4) describe the same rotation within ``atol``.

    For each quaternion the distance is min(max |q1 − q2|, max |q1 + q2|): q and
    −q are the same rotation.  The message names the worst quaternion, its
    distance in eps and the sign that was closer.

    Parameters
    ----------
    q1, q2 : array_like, shape (..., 4)
        The quaternions (w, x, y, z), leading axes broadcasting against each other.
    atol : float
        The largest allowed distance, a finite number ≥ 0 (default
        :data:`QUATERNIONS_CLOSE_ATOL`, 4 eps).
    err_msg : str
        Prepended to the failure message.

    Raises
    ------
    AssertionError
        A distance exceeds ``atol`` (naming the worst quaternion, its distance in eps and
        the closer sign), or an argument is not real, not finite (naming where), not of
        shape (..., 4), or the two do not broadcast.
    ValueError
        ``atol`` not a finite real number ≥ 0 (a string or a bool is refused).

    Examples
    --------
    >>> import numpy as np
    >>> assert_quaternions_close([0.0, 1.0, 0.0, 0.0], [0.0, -1.0, 0.0, 0.0])
    >>> assert_quaternions_close([1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0])
    ... # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    AssertionError: quaternions differ by 4.5e+15 eps (up to sign, closer with q2) at index ()...
    """
    __tracebackhide__ = True  # under pytest, a failure points at the caller
    tol = _check_tolerance(atol, "atol")
    a, b = _broadcast(q1, q2, (4,), ("q1", "q2"))
    plus = np.abs(a - b).max(axis=-1)
    minus = np.abs(a + b).max(axis=-1)
    err = np.minimum(plus, minus)
    if err.size == 0 or not err.max() > tol:
        return
    idx = _worst(err)
    sign = "q2" if plus[idx] <= minus[idx] else "-q2"
    prefix = f"{err_msg}: " if err_msg else ""
    raise AssertionError(
        f"{prefix}quaternions differ by {err[idx] / EPS:.3g} eps (up to sign, closer with "
        f"{sign}) at index {idx}, more than atol = {tol / EPS:.3g} eps "
        f"(q1 {a[idx].tolist()}, q2 {b[idx].tolist()})"
    )


#: eps_multiple not given (None is a value it refuses, as before)
_UNSET: Any = object()


def assert_allclose_eps(
    actual: npt.ArrayLike,
    desired: npt.ArrayLike,
    *,
    eps: float | None = None,
    rtol: float | None = None,
    scale: npt.ArrayLike | None = None,
    err_msg: str = "",
    eps_multiple: Any = _UNSET,
) -> None:
    """Assert |actual − desired| ≤ eps · EPS · scale (or ≤ rtol · scale), entrywise.

    Parameters
    ----------
    actual, desired : array_like, any shapes that broadcast
        The values compared, real and finite.
    eps : float, optional
        The allowed error in units of float64's eps (default
        :data:`ALLCLOSE_EPS_MULTIPLE`).  ``eps_multiple`` is the same, its older name.
    rtol : float, optional
        The allowed error as a plain fraction instead (``rtol=1e-2``: 1 %); the message
        then states the error as a fraction too.  Give ``eps`` or ``rtol``, not both.
    scale : array_like, optional, shape broadcasting to the shape of actual and desired
        The size the error is measured against, ≥ 0.  Default: ``|desired|``
        entrywise, a relative test (a zero ``desired`` then needs an exact
        zero).  Pass ``scale=1`` for an absolute test in units of eps.
    err_msg : str
        Prepended to the failure message.
    eps_multiple : float, optional
        The older name of ``eps`` (give one of ``eps``, ``rtol``, ``eps_multiple``).

    Raises
    ------
    AssertionError
        Naming the worst entry, its error in eps (relative or scaled), and the
        two values; or an argument that is not real, not finite (naming where), or
        shapes that do not broadcast.
    TypeError
        More than one of ``eps``, ``rtol`` and ``eps_multiple`` given.
    ValueError
        A tolerance that is not a finite real number ≥ 0, or a negative ``scale``.

    Examples
    --------
    0.1 + 0.2 is 0.3 within one rounding (0.83 eps relative), and 355/113 is π within
    8.5e-8:

    >>> assert_allclose_eps(0.1 + 0.2, 0.3)
    >>> assert_allclose_eps(355 / 113, np.pi, rtol=1e-7)

    An absolute test in units of eps: ``scale=1``.

    >>> assert_allclose_eps(1e-20, 0.0, scale=1)
    """
    __tracebackhide__ = True  # under pytest, a failure points at the caller
    named = {"eps": eps is not None, "rtol": rtol is not None}
    named["eps_multiple"] = eps_multiple is not _UNSET
    given = [n for n, v in named.items() if v]
    if len(given) > 1:
        raise TypeError(f"give one tolerance, eps or rtol; got {' and '.join(given)}")
    if rtol is not None:
        k = _check_tolerance(rtol, "rtol") / EPS
    elif eps_multiple is not _UNSET:
        k = _check_tolerance(eps_multiple, "eps_multiple")
    else:
        k = ALLCLOSE_EPS_MULTIPLE if eps is None else _check_tolerance(eps, "eps")
    a, d = _broadcast(actual, desired, ())
    if scale is None:
        s, kind = np.abs(d), "relative error"
    else:
        s = np.broadcast_to(_as_finite(scale, "scale"), a.shape)
        if (s < 0).any():
            raise ValueError(f"scale must be >= 0; got {scale!r}")
        kind = "error"
    # In units of eps·scale; a zero scale allows only an exact match.  Two huge values
    # of opposite signs differ by more than float64 holds: their halves' difference (exact
    # halving, as both are huge) gives the units then.  Units beyond float64's range
    # (a huge error against a tiny scale) are inf, and reported as beyond that range.
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        diff = np.abs(a - d)
        huge = np.isinf(diff)
        if huge.any():
            diff = np.where(huge, np.abs(0.5 * a - 0.5 * d), diff)
        units = np.where(diff == 0, 0.0, np.where(s > 0, diff / (EPS * s), np.inf))
        units = np.where(huge, 2.0 * units, units)
    if units.size == 0 or not units.max() > k:
        return
    idx = _worst(units)
    if s[idx] == 0:
        what = f"{float(diff[idx])!r} (scale 0)" if not huge[idx] else f"{_BEYOND} (scale 0)"
    elif not np.isfinite(units[idx]):
        what = f"{_BEYOND}" + ("" if rtol is not None else " eps")
    elif rtol is not None:  # the error as the fraction the tolerance was given in
        what = f"{units[idx] * EPS:.3g}"
    else:
        what = f"{units[idx]:.3g} eps"
    bound = f"rtol {rtol:.3g}" if rtol is not None else f"{k:.3g} eps"
    prefix = f"{err_msg}: " if err_msg else ""
    raise AssertionError(
        f"{prefix}not close: {kind} {what} at index {idx} exceeds {bound} "
        f"(actual {float(a[idx])!r}, desired {float(d[idx])!r})"
    )
