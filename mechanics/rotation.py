"""Rotation matrices, Euler angles, rotation vectors and unit quaternions.

Conventions (Essén 1996, ch. 2.2–2.4)
-------------------------------------
- **Passive (basis) matrices, as the book writes them.**  ``R_A_O`` is the book's
  ^A R^O: its rows are the new basis vectors e^A_i in old (O) components, so that
  E_A = ^A R^O E_O (2.10).  Every function named ``matrix_*`` returns or takes this
  matrix.  Frame-subscripted names read target first: ``R_A_O`` maps O to A.
- The basic matrices (2.30) are R3(ψ) = [[cos ψ, sin ψ, 0], [−sin ψ, cos ψ, 0],
  [0, 0, 1]] and likewise ``R1``, ``R2``: a *positive* turn of the basis about the
  axis.
- **Euler angles z-x-z**, ^A R^O(ψ, θ, φ) = R3(φ) R1(θ) R3(ψ) (2.35), with
  ψ, φ in (−π, π] and θ in [0, π] on output.  Gimbal lock is at θ ∈ {0, π}.
- **Rotation vector** φ = φ e_a (2.4): the turn of the basis by φ about e_a in the
  positive (right-hand) sense; ``matrix_from_rotvec`` returns ^A R^O(φ) of
  (2.28)–(2.29).  ``rotvec_from_matrix`` returns φ in [0, π].
- **Active operator.**  The operator that turns a vector with the basis,
  R_{O→A} of (2.21), has the matrix (in O components, acting on columns) equal to
  the *transpose* of ^A R^O: :func:`active_from_passive` and
  :func:`passive_from_active` say so by name; :func:`rotate_vector` applies it and
  :func:`components_A_from_O` applies (2.20).
- **Quaternions are scalar first**, q = (w, x, y, z) = (cos φ/2, sin φ/2 e_a),
  and describe the active operator: R_{O→A} r = q r q*.  q and −q are the same
  rotation; functions return w ≥ 0.  (scipy's ``Rotation`` is scalar *last*.)
- **Composition** follows the book's chain rule (2.34): ^B R^O = ^B R^A ^A R^O,
  :func:`compose`.
- Everything is float64 and vectorised over leading axes: angles ``(...)``,
  vectors ``(..., 3)``, quaternions ``(..., 4)``, matrices ``(..., 3, 3)``.

Accuracy (measured by ``tests/stability/test_rotation_stability.py`` against
mpmath at 50 digits): every conversion between matrix, rotation vector,
quaternion and Euler angles is within ``ROUNDTRIP_ATOL`` (4 eps, max-abs) of the
matrix, measured both ways (forward: the float matrix against the exact matrix
of the float parameters; backward: the exact matrix of the converted value
against the input), the gimbal-lock band included; measured worst 2.5 eps.
The rotation angle extracted from a matrix is within 4 ulps relative (measured
worst 3.0) for angles from 1e-300 to π.  (A scan of 4.5e6 random rotation
vectors in nine regimes against an 80-bit reference found 3.1 eps, backward
through Euler angles, and 3.2 ulps.)  To get there, norms of rotation vectors
and ratios are carried in double-double (error-free transformations, see
:func:`_norm_dd`), and no formula rounds a quantity where the book's form
would cancel.  The matrices are unbiased: products of many rotations drift from
orthogonality like a random walk.

Speed (``tests/benchmarks``, 10^6 rotations, against scipy's ``Rotation``): the
batched conversions run block by block on one array per matrix entry (see
:func:`_by_blocks`).  Matrix to rotation vector takes 0.15 and matrix to Euler
angles 0.34 of scipy's time, Euler angles to matrix 0.09; rotation vector to
matrix takes 2.7 times scipy's: the double-double angle, three sines and
cosines and |q|² without rounding error, which keep the accuracy above, cost
that much in numpy.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from typing import TypeAlias

import numpy as np
import numpy.typing as npt

from ._floats import EPS, Floats
from ._floats import split as _split
from ._floats import two_sum as _two_sum
from ._validate import as_float_array, as_float_scalar, broadcast_checked, finite_result
from .errors import NonPositiveParameterError, NotARotationError, OutOfDomainError, ZeroAxisError

__all__ = [
    "EPS",
    "R1",
    "R2",
    "R3",
    "ROTATION_ATOL",
    "ROUNDTRIP_ATOL",
    "active_from_passive",
    "check_rotation",
    "components_A_from_O",
    "compose",
    "compose_quat",
    "euler_from_matrix",
    "euler_near_gimbal_lock",
    "is_rotation",
    "matrix_from_axis_angle",
    "matrix_from_euler",
    "matrix_from_quat",
    "matrix_from_rotvec",
    "nearest_rotation",
    "passive_from_active",
    "quat_from_matrix",
    "quat_from_rotvec",
    "quat_multiply",
    "rotate_vector",
    "rotvec_from_matrix",
    "rotvec_from_quat",
]


#: Accepted deviation of a rotation matrix from orthogonality, max |R Rᵀ − 1| and
#: |det R − 1|.  A product of n different float64 rotations drifts like a random
#: walk (measured: 10^3, 10^4, 10^5 products of random rotations 18, 77, 400 eps);
#: 256 eps accepts such matrices and still rejects anything visibly
#: non-orthogonal.  The n-th power of one matrix S drifts like n ‖S Sᵀ − 1‖, up to
#: about n eps (tests/stability).  Repair larger drift with :func:`nearest_rotation`.
ROTATION_ATOL = 256 * EPS

#: Round-trip accuracy promised for every conversion pair, as a max-abs matrix
#: difference.  Each matrix entry is a sum of at most three products of numbers
#: with relative error ≤ 1 ulp, so 4 eps bounds it; the stability tests enforce it.
ROUNDTRIP_ATOL = 4 * EPS

_QUAT_NORM_ATOL = 64 * EPS  # |q| − 1 accepted before "not a unit quaternion" is raised

#: Singular values of a 3 × 3 from LAPACK are within a few eps of the largest, s1: gaps
#: (s2 − 0, or s2 − s3) below 8 eps·s1 are rounding, and :func:`nearest_rotation` refuses
#: them as "no unique nearest rotation"
_SINGULAR_RTOL = 8 * EPS

#: float64 arrays: the columns of a block of rows (see :func:`_by_blocks`) and the results
_Array: TypeAlias = npt.NDArray[np.float64]
#: a kernel of :func:`_by_blocks`: the columns of a block in, as many columns out
_Kernel: TypeAlias = Callable[..., Sequence[_Array]]
#: a double-double norm (r_hi, r_mid, r_lo) of :func:`_norm_dd`
_Norm: TypeAlias = tuple[_Array, _Array, _Array]
#: the (v_hi, v_lo) of a part, split by :func:`_norm_dd`
_Split: TypeAlias = tuple[_Array, _Array]
#: (q, q_lo, q_hi, q_mid) of :func:`_ratio_dd`
_Ratio: TypeAlias = tuple[_Array, _Array, Floats, Floats]


# --------------------------------------------------------------------------- basics


def _trig(alpha: npt.ArrayLike, name: str) -> tuple[_Array, _Array]:
    a = as_float_array(alpha, name)
    return np.cos(a), np.sin(a)


def _stack(rows: Sequence[Sequence[_Array]]) -> _Array:
    out: _Array = np.stack([np.stack(r, axis=-1) for r in rows], axis=-2)
    return out


def R1(alpha: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Basis rotation by ``alpha`` about the first axis, (2.30).

    Domain: any finite angle ``alpha``, scalar or array (...), giving (..., 3, 3); NaN or inf raise
    NonFiniteError, a complex or non-numeric ``alpha`` ShapeError.  Huge angles are accepted, but
    a rounding of the input then moves the angle by up to ulp(alpha).

    Parameters
    ----------
    alpha : array_like, shape (...)
        The angle of the turn of the basis about e^O_1, rad; finite.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        ^A R^O = [[1, 0, 0], [0, cos α, sin α], [0, −sin α, cos α]], a positive turn of the basis.

    Raises
    ------
    NonFiniteError
        Where ``alpha`` holds NaN or an infinity.
    ShapeError
        If ``alpha`` is complex or not numeric.

    Examples
    --------
    >>> import numpy as np
    >>> bool(np.allclose(R1(0.3) @ R1(0.3).T, np.eye(3), atol=1e-15, rtol=0))
    True
    """
    c, s = _trig(alpha, "alpha")
    o, z = np.ones_like(c), np.zeros_like(c)
    return _stack([(o, z, z), (z, c, s), (z, -s, c)])


def R2(alpha: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Basis rotation by ``alpha`` about the second axis, (2.30).

    Domain: as :func:`R1`: any finite ``alpha`` (...), else NonFiniteError or ShapeError.

    Parameters
    ----------
    alpha : array_like, shape (...)
        The angle of the turn of the basis about e^O_2, rad; finite.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        ^A R^O = [[cos α, 0, −sin α], [0, 1, 0], [sin α, 0, cos α]], a positive turn of the basis.

    Raises
    ------
    NonFiniteError
        Where ``alpha`` holds NaN or an infinity.
    ShapeError
        If ``alpha`` is complex or not numeric.

    Examples
    --------
    Two turns about the same axis add their angles (2.34):

    >>> bool(np.allclose(R2(0.3) @ R2(0.4), R2(0.7), atol=4 * EPS, rtol=0))
    True
    """
    c, s = _trig(alpha, "alpha")
    o, z = np.ones_like(c), np.zeros_like(c)
    return _stack([(c, z, -s), (z, o, z), (s, z, c)])


def R3(alpha: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Basis rotation by ``alpha`` about the third axis, (2.11) and (2.30).

    Domain: as :func:`R1`: any finite ``alpha`` (...), else NonFiniteError or ShapeError.

    Parameters
    ----------
    alpha : array_like, shape (...)
        The angle of the turn of the basis about e^O_3, rad; finite.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        ^A R^O = [[cos α, sin α, 0], [−sin α, cos α, 0], [0, 0, 1]], a positive turn of the basis.

    Raises
    ------
    NonFiniteError
        Where ``alpha`` holds NaN or an infinity.
    ShapeError
        If ``alpha`` is complex or not numeric.

    Examples
    --------
    The first row is e^A_1 = cos ψ e^O_1 + sin ψ e^O_2 (Example 2.1):

    >>> R3(np.pi / 2)[0].round(12).tolist()
    [0.0, 1.0, 0.0]
    """
    c, s = _trig(alpha, "alpha")
    o, z = np.ones_like(c), np.zeros_like(c)
    return _stack([(c, s, z), (-s, c, z), (z, z, o)])


def active_from_passive(R_A_O: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """The active operator R_{O→A} (2.21) in O components: the transpose of ^A R^O.

    Domain: a rotation matrix (..., 3, 3), orthogonal with det +1 within :data:`ROTATION_ATOL`
    (:func:`check_rotation`: else NotARotationError naming the deviation; NonFiniteError,
    ShapeError).

    Parameters
    ----------
    R_A_O : array_like, shape (..., 3, 3)
        The book's basis matrix ^A R^O, a rotation.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        (^A R^O)ᵀ, the matrix that turns a column of O components with the basis.

    Raises
    ------
    NotARotationError
        Where ``R_A_O`` is not orthogonal with det +1 within :data:`ROTATION_ATOL`.
    NonFiniteError
        Where ``R_A_O`` holds NaN or an infinity.
    ShapeError
        If ``R_A_O`` is not of shape (..., 3, 3), or is complex or not numeric.

    Examples
    --------
    The operator carries e^O_1 to e^A_1, whose O components are the first row of ^A R^O
    (2.10):

    >>> R = matrix_from_euler(0.3, 1.1, -2.0)
    >>> (active_from_passive(R) @ [1.0, 0.0, 0.0]).tolist() == R[0].tolist()
    True
    """
    return np.swapaxes(check_rotation(R_A_O), -1, -2)


def passive_from_active(R_active: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """The book's basis matrix ^A R^O of an active operator: its transpose.

    Domain: a rotation matrix (..., 3, 3) as :func:`check_rotation` (else NotARotationError naming
    ``R_active``; NonFiniteError, ShapeError).

    Parameters
    ----------
    R_active : array_like, shape (..., 3, 3)
        The matrix R_{O→A} (2.21) of the active operator in O components, a rotation.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        ^A R^O = R_activeᵀ.

    Raises
    ------
    NotARotationError
        Where ``R_active`` is not orthogonal with det +1 within :data:`ROTATION_ATOL`.
    NonFiniteError
        Where ``R_active`` holds NaN or an infinity.
    ShapeError
        If ``R_active`` is not of shape (..., 3, 3), or is complex or not numeric.

    Examples
    --------
    The inverse of :func:`active_from_passive`:

    >>> R = matrix_from_euler(0.3, 1.1, -2.0)
    >>> bool((passive_from_active(active_from_passive(R)) == R).all())
    True
    """
    return np.swapaxes(check_rotation(R_active, name="R_active"), -1, -2)


def rotate_vector(R_A_O: npt.ArrayLike, r_O: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Turn ``r`` with the basis, r' = R_{O→A} r (2.21); components in O in and out.

    Domain: ``R_A_O`` a rotation as :func:`check_rotation` (else NotARotationError), ``r_O`` any
    finite (..., 3); the leading axes broadcast, and batches that do not (2 against 3) raise
    ShapeError listing each argument's shape.  A component beyond float64 (``r_O`` near 1e308
    turned by 45°) raises ResultOverflowError.

    Parameters
    ----------
    R_A_O : array_like, shape (..., 3, 3)
        The book's basis matrix ^A R^O, a rotation.
    r_O : array_like, shape (..., 3)
        The vector's components in O, finite.

    Returns
    -------
    ndarray, shape (..., 3)
        The turned vector r' = (^A R^O)ᵀ r in O components.

    Raises
    ------
    NotARotationError
        Where ``R_A_O`` is not orthogonal with det +1 within :data:`ROTATION_ATOL`.
    NonFiniteError
        Where an input holds NaN or an infinity.
    ShapeError
        If a trailing shape is wrong, an input is complex or not numeric, or the leading axes do
        not broadcast.
    ResultOverflowError
        Where a component of r' is beyond float64.

    Examples
    --------
    Turning the basis by +90° about e3 carries e1 to e2:

    >>> rotate_vector(R3(np.pi / 2), [1.0, 0.0, 0.0]).round(12).tolist()
    [0.0, 1.0, 0.0]
    """
    R = check_rotation(R_A_O)
    r = as_float_array(r_O, "r_O", (3,))
    out: npt.NDArray[np.float64] = np.einsum("...ji,...j->...i", R, r)
    return out


rotate_vector = finite_result(rotate_vector)


def components_A_from_O(R_A_O: npt.ArrayLike, r_O: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Components in the basis A of a vector given in O: r^A = ^A R^O r^O (2.20).

    Domain: as :func:`rotate_vector`: a rotation ``R_A_O`` (else NotARotationError) and any finite
    ``r_O`` (..., 3); batches that do not broadcast raise ShapeError listing each argument's shape.
    A component beyond float64 raises ResultOverflowError, as in :func:`rotate_vector`.

    Parameters
    ----------
    R_A_O : array_like, shape (..., 3, 3)
        The book's basis matrix ^A R^O, a rotation.
    r_O : array_like, shape (..., 3)
        The vector's components in O, finite.

    Returns
    -------
    ndarray, shape (..., 3)
        The same vector's components r^A in the basis A.

    Raises
    ------
    NotARotationError
        Where ``R_A_O`` is not orthogonal with det +1 within :data:`ROTATION_ATOL`.
    NonFiniteError
        Where an input holds NaN or an infinity.
    ShapeError
        If a trailing shape is wrong, an input is complex or not numeric, or the leading axes do
        not broadcast.
    ResultOverflowError
        Where a component of r^A is beyond float64.

    Examples
    --------
    A vector turned with the basis (:func:`rotate_vector`) has in A the components it had in O:

    >>> R, r = matrix_from_euler(0.3, 1.1, -2.0), [1.0, 2.0, 3.0]
    >>> bool(np.allclose(components_A_from_O(R, rotate_vector(R, r)), r, atol=32 * EPS, rtol=0))
    True
    """
    R = check_rotation(R_A_O)
    r = as_float_array(r_O, "r_O", (3,))
    out: npt.NDArray[np.float64] = np.einsum("...ij,...j->...i", R, r)
    return out


components_A_from_O = finite_result(components_A_from_O)


def compose(R_B_A: npt.ArrayLike, R_A_O: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """^B R^O = ^B R^A ^A R^O, the chain of basis changes (2.34).

    Domain: two rotations (..., 3, 3) as :func:`check_rotation` (else NotARotationError naming
    ``R_B_A`` or ``R_A_O``); the leading axes broadcast, and batches that do not raise ShapeError
    listing each argument's shape.

    Parameters
    ----------
    R_B_A : array_like, shape (..., 3, 3)
        The second basis change ^B R^A, a rotation.
    R_A_O : array_like, shape (..., 3, 3)
        The first basis change ^A R^O, a rotation.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        The product ^B R^O = ^B R^A ^A R^O.

    Raises
    ------
    NotARotationError
        Where ``R_B_A`` or ``R_A_O`` is not orthogonal with det +1 within :data:`ROTATION_ATOL`.
    NonFiniteError
        Where an input holds NaN or an infinity.
    ShapeError
        If an input is not of shape (..., 3, 3), is complex or not numeric, or the leading axes do
        not broadcast.

    Examples
    --------
    Two turns about the same axis add their angles:

    >>> bool(np.allclose(compose(R3(0.4), R3(0.3)), R3(0.7), atol=4 * EPS, rtol=0))
    True
    """
    out: npt.NDArray[np.float64] = check_rotation(R_B_A, name="R_B_A") @ check_rotation(
        R_A_O, name="R_A_O"
    )
    return out


compose = broadcast_checked(compose)


# ---------------------------------------------------------------- batched kernels
#
# The conversions are written as kernels on the columns of a block of rows (one
# 1-D array per entry or component), run block by block.  Two reasons: numpy's
# temporaries of one block stay in cache, and a kernel can treat the rare rows
# that need a special formula (tiny or huge angles, gimbal lock) apart from the
# common ones, which then pay nothing for them.

#: Rows per block.  A kernel makes up to ~60 temporaries of one block; at this
#: size (128 KiB each) they stay in cache, where an add costs about 0.4 ms per
#: 10^6 elements instead of 1.2 ms for whole 10^6-row arrays streamed through
#: memory.  Measured on 10^6 rotations: 4096 rows 20 % slower, 8192 rows 6 %
#: slower, 32768 rows no faster.
_BLOCK = 16384


def _by_blocks(kernel: _Kernel, a: _Array, width: int) -> _Array:
    """``kernel`` applied to the rows of ``a`` (..., m) in blocks: (..., width).

    ``kernel`` takes the m columns of a block (1-D arrays) and returns ``width``
    columns of the same length.
    """
    rows = a.reshape(-1, a.shape[-1])
    out = np.empty((rows.shape[0], width))
    for start in range(0, rows.shape[0], _BLOCK):
        block = rows[start : start + _BLOCK]
        columns = np.ascontiguousarray(block.T)  # contiguous columns: faster loops
        np.stack(kernel(*columns), axis=-1, out=out[start : start + _BLOCK])
    return out.reshape(*a.shape[:-1], width)


def _by_subsets(
    kernels: Sequence[_Kernel],
    masks: Sequence[npt.NDArray[np.bool_]],
    columns: Sequence[_Array],
    width: int,
) -> tuple[_Array, ...]:
    """Each ``kernels[i]`` applied to the rows selected by ``masks[i]`` (a partition)."""
    out = np.empty((width, columns[0].shape[0]))
    for kernel, mask in zip(kernels, masks, strict=True):
        if mask.any():
            out[:, mask] = kernel(*(c[mask] for c in columns))
    return tuple(out)


# ---------------------------------------------------------------------- validation


def _deviation_columns(
    a: _Array,
    b: _Array,
    c: _Array,
    d: _Array,
    e: _Array,
    f: _Array,
    g: _Array,
    h: _Array,
    i: _Array,
) -> tuple[_Array, _Array]:
    """max |R Rᵀ − 1| and |det R − 1| of R = [[a, b, c], [d, e, f], [g, h, i]].

    Written out entry by entry (six row products, the cofactor determinant):
    batched ``R @ R.T`` and ``np.linalg.det`` are slow for 3 × 3 matrices
    (measured on 10^6 matrices: 45 ms in all against 500 ms).
    """
    ortho = np.abs(a * a + b * b + c * c - 1.0)
    for dev in (
        d * d + e * e + f * f - 1.0,
        g * g + h * h + i * i - 1.0,
        a * d + b * e + c * f,
        a * g + b * h + c * i,
        d * g + e * h + f * i,
    ):
        ortho = np.maximum(ortho, np.abs(dev))
    det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g)
    return ortho, np.abs(det - 1.0)


def _rotation_deviation(R: _Array) -> tuple[_Array, _Array]:
    # Entries beyond 1e154 overflow the products: inf (or nan) marks them as bad.
    with np.errstate(over="ignore", invalid="ignore"):
        dev = _by_blocks(_deviation_columns, R.reshape(*R.shape[:-2], 9), 2)
    return dev[..., 0], dev[..., 1]


def _atol(atol: float) -> float:
    """``atol`` as a finite Python float ≥ 0, else an error naming ``atol``."""
    v = as_float_scalar(atol, "atol")
    if not v >= 0:
        raise NonPositiveParameterError(f"atol must be >= 0 (a tolerance); got {v!r}")
    return v


def check_rotation(
    R: npt.ArrayLike, *, atol: float = ROTATION_ATOL, name: str = "R_A_O"
) -> npt.NDArray[np.float64]:
    """Validate a rotation matrix and return it as a float64 array.

    Domain: any finite array of shape (..., 3, 3) (else NonFiniteError or ShapeError); the check is
    the domain test of every function taking a matrix here.  Entries beyond about 1e154 overflow its
    products to inf and are refused as not a rotation, without a numpy warning.  ``atol`` a finite
    number ≥ 0 (NaN, inf, a non-number: NonFiniteError or ShapeError; a negative one
    NonPositiveParameterError, each naming ``atol``).

    Parameters
    ----------
    R : array_like, shape (..., 3, 3)
        The matrix to check, finite.
    atol : float, optional
        The accepted max |R Rᵀ − 1| and |det R − 1|, finite and ≥ 0; default
        :data:`ROTATION_ATOL` (256 eps).
    name : str, optional
        The argument's name in error messages; default ``"R_A_O"``.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        ``R`` as float64, unchanged (``R`` itself when it already is a float64 array).

    Raises
    ------
    NotARotationError
        Naming the measured deviation, when max |R Rᵀ − 1| or |det R − 1| exceeds ``atol``
        for some matrix of the batch.
    NonFiniteError
        Where ``R`` or ``atol`` holds NaN or an infinity.
    ShapeError
        If ``R`` is not of shape (..., 3, 3), ``atol`` is not a scalar, or either is complex or not
        numeric.
    NonPositiveParameterError
        If ``atol`` < 0.

    Examples
    --------
    >>> check_rotation(np.diag([1.0, 1.0, -1.0]))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    mechanics.errors.NotARotationError: R_A_O is not a rotation: |det R - 1| = 2 ... a reflection
    """
    atol = _atol(atol)
    a = as_float_array(R, name, (3, 3))
    ortho, det = _rotation_deviation(a)
    bad = ~((ortho <= atol) & (det <= atol))
    if bad.any():
        idx = tuple(int(i) for i in np.argwhere(bad)[0]) if bad.ndim else ()
        o, d = float(ortho[idx]), float(det[idx])
        if not o <= atol:
            what = f"max |R R^T - 1| = {o:.3g} exceeds atol = {atol:.3g}"
        else:
            what = f"|det R - 1| = {d:.3g} exceeds atol = {atol:.3g}"
        hint = (
            "; it is a reflection"
            if d > 1.5 and o <= atol
            else "; use nearest_rotation() to project it"
        )
        raise NotARotationError(f"{name} is not a rotation: {what} (index {idx}){hint}")
    return a


def is_rotation(R: npt.ArrayLike, *, atol: float = ROTATION_ATOL) -> npt.NDArray[np.bool_]:
    """Elementwise predicate: orthogonal with det +1 within ``atol``.

    Domain: any finite array (..., 3, 3) (else NonFiniteError or ShapeError); the answer, a bool
    array (...), is False and never an error for a matrix that is not a rotation, entries beyond
    1e154 included.  ``atol`` as in :func:`check_rotation`: a finite number ≥ 0, else an error
    naming it.

    Parameters
    ----------
    R : array_like, shape (..., 3, 3)
        The matrices to test, finite.
    atol : float, optional
        The accepted max |R Rᵀ − 1| and |det R − 1|, finite and ≥ 0; default
        :data:`ROTATION_ATOL` (256 eps).

    Returns
    -------
    ndarray of bool, shape (...)
        True where both deviations are within ``atol``.

    Raises
    ------
    NonFiniteError
        Where ``R`` or ``atol`` holds NaN or an infinity.
    ShapeError
        If ``R`` is not of shape (..., 3, 3), ``atol`` is not a scalar, or either is complex or not
        numeric.
    NonPositiveParameterError
        If ``atol`` < 0.

    Examples
    --------
    A product of rotations is one (2.34); a rotation's negative is a reflection (det −1):

    >>> is_rotation(np.stack([compose(R1(0.3), R3(1.2)), -R3(1.2)])).tolist()
    [True, False]
    """
    atol = _atol(atol)
    a = as_float_array(R, "R", (3, 3))
    ortho, det = _rotation_deviation(a)
    return (ortho <= atol) & (det <= atol)


def nearest_rotation(M: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """The rotation closest to ``M`` in the Frobenius norm (polar factor, by SVD).

    Domain: any finite (..., 3, 3) (else NonFiniteError or ShapeError), entries up to 1e300, whose
    nearest rotation is unique; else OutOfDomainError naming ``M`` and the condition.  With
    singular values s1 ≥ s2 ≥ s3 it is unique unless two of them are zero (s2 = 0: rank ≤ 1, the
    zero matrix included; every turn about the direction of s1 is equally near), or det M < 0 and
    s2 = s3 (−1, say; the half turns about any axis in the plane of s2, s3 are equally near); "zero"
    and "equal" to 8 eps of s1, the rounding of the singular values.

    Repairs the drift of long products of rotation matrices.  A matrix whose
    determinant is negative (with s2 > s3) has the rotation that flips the direction of the
    smallest singular value as its unique nearest rotation.

    Parameters
    ----------
    M : array_like, shape (..., 3, 3)
        Any finite matrices.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        The nearest rotation Q = U Vᵀ (det +1), orthogonal to about 2 eps.

    Raises
    ------
    OutOfDomainError
        Where the nearest rotation is not unique: s2 = 0, or det M < 0 and s2 = s3 (to 8 eps of
        s1).
    NonFiniteError
        Where ``M`` holds NaN or an infinity.
    ShapeError
        If ``M`` is not of shape (..., 3, 3), or is complex or not numeric.

    Notes
    -----
    U Vᵀ from the SVD is orthogonal only to the accuracy of LAPACK's factors
    (measured: max |Q Qᵀ − 1| up to 13 eps); one Newton–Schulz step
    Q ← Q − ½ (Q Qᵀ − 1) Q, which converges quadratically to the polar factor,
    brings it to 2 eps (``tests/stability``) and moves Q by a few eps only.

    Examples
    --------
    A rotation scaled by 2 has that rotation as its polar factor:

    >>> R = matrix_from_euler(0.3, 1.1, -2.0)
    >>> bool(np.allclose(nearest_rotation(2.0 * R), R, atol=4 * EPS, rtol=0))
    True
    """
    a = as_float_array(M, "M", (3, 3))
    U, s, Vt = np.linalg.svd(a)
    d = np.sign(np.linalg.det(U @ Vt))
    d = np.where(d == 0, 1.0, d)
    tol = _SINGULAR_RTOL * s[..., 0]
    rank1 = s[..., 1] <= tol
    tie = (d < 0) & (s[..., 1] - s[..., 2] <= tol)
    if np.any(rank1 | tie):
        i = tuple(int(k) for k in np.argwhere(rank1 | tie)[0]) if rank1.ndim else ()
        why = (
            "two of its singular values are zero (rank <= 1: every turn about the remaining "
            "direction is equally near)"
            if rank1[i]
            else "det M < 0 and its two smallest singular values are equal (several half turns "
            "are equally near)"
        )
        raise OutOfDomainError(
            f"M has no unique nearest rotation: {why}, to {_SINGULAR_RTOL / EPS:.0f} eps of the "
            f"largest; singular values {s[i].tolist()} at index {i}"
        )
    U = U.copy()
    U[..., :, 2] *= d[..., None]
    Q = U @ Vt
    E = Q @ np.swapaxes(Q, -1, -2) - np.eye(3)
    out: npt.NDArray[np.float64] = Q - 0.5 * (E @ Q)
    return out


# ------------------------------------------------------------ error-free arithmetic
#
# With error-free transformations a norm or a sum costs about one rounding instead
# of three or four, which is what keeps the conversions within 4 eps near π and the
# extracted angle within a few ulps (measured before these: up to 6 eps and 5.4
# ulps; see tests/stability).  They cost 5 to 40 numpy operations each, so they
# are used only where a plain rounding would break those bounds.


def _sum4(a: Floats, b: Floats, c: Floats, d: Floats) -> Floats:
    """a + b + c + d with compensation: about one rounding in all."""
    s, e1 = _two_sum(a, b)
    s, e2 = _two_sum(s, c)
    s, e3 = _two_sum(s, d)
    return s + ((e1 + e2) + e3)


_EXPONENT_BITS = np.int64(0x7FF0000000000000)
_HALF_BIT = np.int64(0x0008000000000000)  # the first mantissa bit: 1.5 * 2**e


def _grid_splitter(r: _Array) -> _Array:
    """1.5 * 2**(e + 27) for r in [2**e, 2**(e+1)), from the bits of r (normal r > 0).

    Adding and subtracting it rounds any |a| ≤ r to a multiple of g = 2**(e − 25),
    the same grid for all components (see :func:`_norm_dd`).
    """
    return ((r.view(np.int64) & _EXPONENT_BITS) | _HALF_BIT).view(np.float64) * 2.0**27


def _norm_dd(parts: Iterable[_Array], r: _Array) -> tuple[_Norm, list[_Split]]:
    """The norm |v| of v = ``parts`` as a double-double, for r = fl(√(Σ v_i²)).

    Returns ``(r_hi, r_mid, r_lo), splits``: r = r_hi + r_mid exactly and
    |v| = r + r_lo to about 2**-75 relative; ``splits`` are the (v_hi, v_lo) of
    the parts, for :func:`_times_dd`.  One Newton step, r_lo = (Σ v_i² − r²)/(2r),
    with the residual formed exactly: every v_i and r are split on one grid g,
    v = v_hi + v_lo with v_hi a multiple of g below 2**26 g (so v_hi² and their
    sums are exact) and |v_lo| ≤ g/2.  About 40 operations for three parts, half
    of Dekker's products with compensated sums.  Valid for 2**-480 ≤ r ≤ 2**500
    (r_lo underflows below, the splitter overflows above); the callers treat
    other rows apart.
    """
    C = _grid_splitter(r)
    r_hi = (r + C) - C
    r_mid = r - r_hi
    hh, hl, ll = -(r_hi * r_hi), -(r_hi * r_mid), -(r_mid * r_mid)
    splits = []
    for a in parts:
        a_hi = (a + C) - C
        a_lo = a - a_hi
        hh = hh + a_hi * a_hi
        hl = hl + a_hi * a_lo
        ll = ll + a_lo * a_lo
        splits.append((a_hi, a_lo))
    return (r_hi, r_mid, (hh + (2.0 * hl + ll)) / (2.0 * r)), splits


def _ratio_dd(num: Floats, norm: _Norm, r: _Array) -> _Ratio:
    """(q, q_lo, q_hi, q_mid): q + q_lo = num/|v| to about 2**-75 relative.

    ``norm`` = (r_hi, r_mid, r_lo) of :func:`_norm_dd`; q = fl(num/r) = q_hi + q_mid
    (Veltkamp).  The remainder num − q r is exact: q_hi r_hi has 26 + 27 bits
    and is within a factor 2 of num (Sterbenz); the other products are 2**-26
    smaller and round far below what q_lo needs.
    """
    r_hi, r_mid, r_lo = norm
    q = num / r
    q_hi, q_mid = _split(q)
    e = (((num - q_hi * r_hi) - q_hi * r_mid) - q_mid * r_hi) - q_mid * r_mid
    return q, (e - q * r_lo) / r, q_hi, q_mid


def _times_dd(a: _Array, split: _Split, ratio: _Ratio) -> _Array:
    """a (q + q_lo) with about one rounding: Dekker's product of a q, plus a q_lo.

    ``split`` = (a_hi, a_lo) from :func:`_norm_dd` (a_hi has at most 27 bits, so
    a_hi q_hi is exact) and ``ratio`` from :func:`_ratio_dd`.
    """
    a_hi, a_lo = split
    q, q_lo, q_hi, q_mid = ratio
    p = a * q
    err = ((a_hi * q_hi - p) + a_hi * q_mid + a_lo * q_hi) + a_lo * q_mid
    return p + (err + a * q_lo)


# ---------------------------------------------------------------------- Euler angles


def matrix_from_euler(
    psi: npt.ArrayLike, theta: npt.ArrayLike, phi: npt.ArrayLike
) -> npt.NDArray[np.float64]:
    """^A R^O(ψ, θ, φ) = R3(φ) R1(θ) R3(ψ), written out as in (2.36).

    Domain: any finite ``psi``, ``theta``, ``phi`` (...), broadcast together (else NonFiniteError;
    batches that do not broadcast raise ShapeError listing each argument's shape); ``theta`` need
    not lie in [0, π].

    Parameters
    ----------
    psi, theta, phi : array_like, shape (...)
        The z-x-z Euler angles ψ (precession), θ (nutation) and φ (spin), rad; finite.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        ^A R^O of (2.36), with the broadcast shape of the three angles.

    Raises
    ------
    NonFiniteError
        Where an angle holds NaN or an infinity.
    ShapeError
        If an angle is complex or not numeric, or their leading axes do not broadcast.

    Examples
    --------
    The explicit form equals the product of (2.35):

    >>> a = (0.3, 1.1, -2.0)
    >>> bool(np.allclose(matrix_from_euler(*a), R3(a[2]) @ R1(a[1]) @ R3(a[0]),
    ...                  atol=4 * EPS, rtol=0))
    True
    """
    cps, sps = _trig(psi, "psi")
    cth, sth = _trig(theta, "theta")
    cph, sph = _trig(phi, "phi")
    cps, sps, cth, sth, cph, sph = np.broadcast_arrays(cps, sps, cth, sth, cph, sph)
    return _stack(
        [
            (cph * cps - sph * cth * sps, cph * sps + sph * cth * cps, sph * sth),
            (-sph * cps - cph * cth * sps, -sph * sps + cph * cth * cps, cph * sth),
            (sth * sps, -sth * cps, cth),
        ]
    )


matrix_from_euler = broadcast_checked(matrix_from_euler)


def euler_from_matrix(
    R_A_O: npt.ArrayLike,
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """Euler angles (ψ, θ, φ) of ^A R^O, the inverse of :func:`matrix_from_euler`.

    Domain: a rotation (..., 3, 3) as :func:`check_rotation` (else NotARotationError); gimbal lock
    (θ = 0 or π) included.

    Parameters
    ----------
    R_A_O : array_like, shape (..., 3, 3)
        The book's basis matrix ^A R^O, a rotation.

    Returns
    -------
    psi : ndarray, shape (...)
        ψ in (−π, π], rad.
    theta : ndarray, shape (...)
        θ in [0, π], rad.
    phi : ndarray, shape (...)
        φ in (−π, π], rad.

    Raises
    ------
    NotARotationError
        Where ``R_A_O`` is not orthogonal with det +1 within :data:`ROTATION_ATOL`.
    NonFiniteError
        Where ``R_A_O`` holds NaN or an infinity.
    ShapeError
        If ``R_A_O`` is not of shape (..., 3, 3), or is complex or not numeric.

    Notes
    -----
    Read off the quaternion (w ≥ 0, by Shepperd's method, unnormalised: all
    that follows is scale-free) rather than the matrix entries.  The active
    operator is R_z(ψ) R_x(θ) R_z(φ), so with half angles ψ', θ', φ'

        w = cos θ' cos(ψ' + φ'),  z = cos θ' sin(ψ' + φ'),
        x = sin θ' cos(ψ' − φ'),  y = sin θ' sin(ψ' − φ'),

    and θ = 2 atan2(hypot(x, y), hypot(w, z)), ψ = arg((w + iz)(x + iy)),
    φ = arg((w + iz)(x − iy)): one atan2 per angle, no sum of two rounded
    angles and no wrap into (−π, π].  The complex products are accurate
    relative to their size even where one factor is tiny, which is exactly
    where the matrix does not depend on the split (gimbal lock: θ = 0 leaves
    only ψ + φ, θ = π only ψ − φ).  So the angles reproduce the matrix within
    4 eps at and near gimbal lock too (unlike arccos of R33).  At θ = 0 exactly,
    ψ = φ = half the sum; at θ = π exactly, ψ = −φ = half the difference.

    Examples
    --------
    >>> psi, theta, phi = euler_from_matrix(matrix_from_euler(0.5, 1.0, -2.5))
    >>> [round(float(x), 12) for x in (psi, theta, phi)]
    [0.5, 1.0, -2.5]
    """
    R = check_rotation(R_A_O)
    angles = _by_blocks(_euler_columns, R.reshape(*R.shape[:-2], 9), 3)
    return angles[..., 0], angles[..., 1], angles[..., 2]


#: A factor (w + iz or x + iy) of the complex products in :func:`_euler_columns`
#: smaller than this is scaled to order 1 first.  Its products round in the
#: subnormal range and lose digits (found at θ ~ 1e-311: 79 eps); above it they
#: cost at most 2**-1074 against an atan2 argument of at least 2**-901 (the other
#: factor holds the Shepperd pivot, ≥ 1).
_EULER_SCALE_BELOW = 2.0**-900


def _euler_columns(*R: _Array) -> tuple[_Array, _Array, _Array]:
    w, x, y, z = _shepperd_columns(*R)
    theta = 2.0 * np.arctan2(np.hypot(x, y), np.hypot(w, z))
    # The arguments do not change when a factor is scaled, so near gimbal lock
    # (one factor tiny, down to subnormal) it is brought to order 1 by a power of
    # two (exact), keeping the digits that make ψ + φ (or ψ − φ) exact.
    tiny_wz = np.maximum(np.abs(w), np.abs(z)) < _EULER_SCALE_BELOW
    tiny_xy = np.maximum(np.abs(x), np.abs(y)) < _EULER_SCALE_BELOW
    if tiny_wz.any() or tiny_xy.any():
        w, z = _unit_scale_where(tiny_wz, w, z)
        x, y = _unit_scale_where(tiny_xy, x, y)
    psi = np.arctan2(w * y + z * x, w * x - z * y)
    phi = np.arctan2(z * x - w * y, w * x + z * y)
    # Gimbal lock exactly: one factor is 0, so is the product; split evenly.
    at_zero = (x == 0) & (y == 0)
    at_pi = (w == 0) & (z == 0)
    if at_zero.any():
        psi[at_zero] = phi[at_zero] = np.arctan2(z[at_zero], w[at_zero])
    if at_pi.any():
        psi[at_pi] = np.arctan2(y[at_pi], x[at_pi])
        phi[at_pi] = -psi[at_pi]
    return psi, theta, phi


def _unit_scale_where(mask: npt.NDArray[np.bool_], a: _Array, b: _Array) -> tuple[_Array, _Array]:
    """(a, b) with the rows in ``mask`` divided by 2**k, max(|a|, |b|) in [1/2, 1)."""
    a, b = a.copy(), b.copy()
    _, k = np.frexp(np.maximum(np.abs(a[mask]), np.abs(b[mask])))
    a[mask], b[mask] = np.ldexp(a[mask], -k), np.ldexp(b[mask], -k)
    return a, b


def euler_near_gimbal_lock(theta: npt.ArrayLike, *, atol: float = 1e-6) -> npt.NDArray[np.bool_]:
    """True where |sin θ| < ``atol``: Euler-angle rates are ill-conditioned there.

    Domain: any finite ``theta`` (...) (else NonFiniteError); ``atol`` a finite number ≥ 0 (else
    NonFiniteError, ShapeError or NonPositiveParameterError naming ``atol``).

    The default 1e-6 is where (2.69) inverted amplifies a rate error by 1e6.

    Parameters
    ----------
    theta : array_like, shape (...)
        The middle (nutation) Euler angle θ, rad; finite.
    atol : float, optional
        The threshold on |sin θ|, finite and ≥ 0; default 1e-6.

    Returns
    -------
    ndarray of bool, shape (...)
        True where |sin θ| < ``atol``.

    Raises
    ------
    NonFiniteError
        Where ``theta`` or ``atol`` holds NaN or an infinity.
    ShapeError
        If ``atol`` is not a scalar, or an input is complex or not numeric.
    NonPositiveParameterError
        If ``atol`` < 0.

    Examples
    --------
    θ near 0 and near π alike (sin(fl(π)) = 1.2e-16):

    >>> euler_near_gimbal_lock([0.0, 1e-7, 0.5, np.pi - 1e-7, np.pi]).tolist()
    [True, True, False, True, True]
    """
    atol = _atol(atol)
    t = as_float_array(theta, "theta")
    near: npt.NDArray[np.bool_] = np.abs(np.sin(t)) < atol
    return near


# ------------------------------------------------------------------- quaternions


def _norm3(v: _Array) -> _Array:
    """Euclidean norm of (..., 3) without underflow or overflow (tiny angles)."""
    n: _Array = np.hypot(np.hypot(v[..., 0], v[..., 1]), v[..., 2])
    return n


def _scaled_to_unit_exponent(v: _Array) -> _Array:
    """v (..., 3) times the power of two that brings its largest component into [1/2, 1): the
    same direction, exact where v is subnormal, so that its norm and v/|v| keep 53 bits (the
    hypot of a subnormal vector has only its few: an axis 2**-1068 (1, 1, 0) came out 5.8e12
    eps off).  A zero vector stays zero."""
    e = np.frexp(np.abs(v).max(axis=-1))[1]
    scaled: _Array = np.ldexp(v, -e[..., None])
    return scaled


def _check_quat_raw(q: npt.ArrayLike, name: str = "q") -> _Array:
    """Validate a unit quaternion and return it as given (not renormalised)."""
    a = as_float_array(q, name, (4,))
    # |q|² plainly (a few eps off, far inside the tolerance); an over- or
    # underflow makes it inf or 0, which fails the test as it should.
    with np.errstate(over="ignore", under="ignore"):
        n = np.sqrt(np.einsum("...i,...i->...", a, a))
    bad = ~(np.abs(n - 1.0) <= _QUAT_NORM_ATOL)
    if bad.any():
        if not a.any(axis=-1).all():
            raise ZeroAxisError(f"{name} has zero length; a unit quaternion is required")
        idx = tuple(int(i) for i in np.argwhere(bad)[0]) if bad.ndim else ()
        raise NotARotationError(
            f"{name} is not a unit quaternion: |q| = {math.hypot(*a[idx])!r} at index {idx} "
            f"(|q| - 1 must be within {_QUAT_NORM_ATOL:.3g}); normalise it first"
        )
    return a


def _check_quat(q: npt.ArrayLike, name: str = "q") -> _Array:
    """Validate a unit quaternion and return it normalised."""
    a = _check_quat_raw(q, name)
    unit: _Array = a / np.sqrt(np.einsum("...i,...i->...", a, a))[..., None]
    return unit


def quat_multiply(p: npt.ArrayLike, q: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Hamilton product p ⊗ q (scalar first); the operator of p after that of q.

    Domain: any finite ``p``, ``q`` of shape (..., 4), unit or not (no check of length); the leading
    axes broadcast (batches that do not raise ShapeError listing each argument's shape).  Products
    beyond float64 on the way (components near 1e300, or 1e200 times 1e200) raise
    ResultOverflowError.

    Parameters
    ----------
    p, q : array_like, shape (..., 4)
        Quaternions (w, x, y, z), finite, of any length.

    Returns
    -------
    ndarray, shape (..., 4)
        p ⊗ q = (p_w q_w − p_v · q_v, p_w q_v + q_w p_v + p_v × q_v), p_v and q_v the vector
        parts.

    Raises
    ------
    NonFiniteError
        Where ``p`` or ``q`` holds NaN or an infinity.
    ShapeError
        If ``p`` or ``q`` is not of shape (..., 4), is complex or not numeric, or their leading axes
        do not broadcast.
    ResultOverflowError
        Where a component of the product is beyond float64 on the way.

    Examples
    --------
    The length of a product is the product of the lengths (|p|² = 30, |q|² = 6):

    >>> pq = quat_multiply([1.0, 2.0, 3.0, 4.0], [2.0, 0.0, 1.0, -1.0])
    >>> float(pq @ pq), 30.0 * 6.0
    (180.0, 180.0)
    """
    p = as_float_array(p, "p", (4,))
    q = as_float_array(q, "q", (4,))
    pw, px, py, pz = np.moveaxis(p, -1, 0)
    qw, qx, qy, qz = np.moveaxis(q, -1, 0)
    return np.stack(
        [
            pw * qw - px * qx - py * qy - pz * qz,
            pw * qx + px * qw + py * qz - pz * qy,
            pw * qy - px * qz + py * qw + pz * qx,
            pw * qz + px * qy - py * qx + pz * qw,
        ],
        axis=-1,
    )


quat_multiply = finite_result(quat_multiply)


def compose_quat(q_B_A: npt.ArrayLike, q_A_O: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Quaternion of ^B R^O from those of ^B R^A and ^A R^O (as :func:`compose`).

    Domain: two unit quaternions (..., 4) with |q| − 1 within 64 eps (else NotARotationError; a zero
    quaternion ZeroAxisError), renormalised before use; batches that do not broadcast raise
    ShapeError listing each argument's shape.

    The active operators compose in the opposite order to the basis matrices:
    R_{O→B} = R_{O→A} R_{A→B}, so q_B_O = q_A_O ⊗ q_B_A; returned with w ≥ 0.

    Parameters
    ----------
    q_B_A : array_like, shape (..., 4)
        Unit quaternion (w, x, y, z) of ^B R^A.
    q_A_O : array_like, shape (..., 4)
        Unit quaternion (w, x, y, z) of ^A R^O.

    Returns
    -------
    ndarray, shape (..., 4)
        The unit quaternion q_B_O of ^B R^O, with w ≥ 0.

    Raises
    ------
    NotARotationError
        Where |q| − 1 of ``q_B_A`` or ``q_A_O`` exceeds 64 eps.
    ZeroAxisError
        Where ``q_B_A`` or ``q_A_O`` has zero length.
    NonFiniteError
        Where an input holds NaN or an infinity.
    ShapeError
        If an input is not of shape (..., 4), is complex or not numeric, or the leading axes do not
        broadcast.

    Examples
    --------
    The quaternions compose as the matrices do (2.34):

    >>> RB, RA = R1(0.3), R3(1.2)
    >>> q = compose_quat(quat_from_matrix(RB), quat_from_matrix(RA))
    >>> bool(np.allclose(matrix_from_quat(q), compose(RB, RA), atol=4 * EPS, rtol=0))
    True
    """
    a, b = _check_quat(q_A_O, "q_A_O"), _check_quat(q_B_A, "q_B_A")
    np.broadcast_shapes(a.shape, b.shape)  # a ShapeError naming q_A_O and q_B_A, not p and q
    return _canonical(quat_multiply(a, b))


compose_quat = broadcast_checked(compose_quat)


def _canonical(q: _Array) -> _Array:
    out: _Array = np.where(q[..., :1] < 0, -q, q)
    return out


def _matrix_columns(
    w: _Array,
    x: _Array,
    y: _Array,
    z: _Array,
    f: Floats,
    S: Sequence[_Array] | None = None,
) -> list[_Array]:
    """The nine entries of ^A R^O (row by row) from quaternion parts, over |q|².

    Rows are e^A_i in O components: the transpose of the familiar active
    matrix.  An off-diagonal entry is a symmetric part 2 x_i x_j plus or minus an
    antisymmetric part S_k = 2 w x_k = sin φ e_a,k; the diagonal is
    w² + x² − y² − z² and its like, rather than 1 − 2(y² + z²), which near a half
    turn loses 1.5 eps in entries near −1.  ``f`` = δ/(1 + δ), δ = |q|² − 1
    (:func:`_length_correction`), divides out the length of q as t − t f = t/|q|²:
    of the symmetric parts and the diagonal, and of w alone in 2 w x_k.  ``S``,
    if given, is sin φ e_a formed directly from the angle (and so not divided).
    The antisymmetric part, all of an entry for a small angle, is thus rounded
    once or twice before the sum: its relative accuracy carries the angle of a
    round trip (dividing the whole entry instead, one rounding more, gave 4.3
    ulps worst instead of 3; measured on 5e5 rotation vectors).
    """
    x2, y2, z2 = x + x, y + y, z + z
    if S is None:
        w1 = w - w * f
        S = w1 * x2, w1 * y2, w1 * z2
    Sx, Sy, Sz = S
    xy, xz, yz = x2 * y, x2 * z, y2 * z
    xy, xz, yz = xy - xy * f, xz - xz * f, yz - yz * f
    ww, xx, yy, zz = w * w, x * x, y * y, z * z
    d1, d2, d3 = (ww + xx) - (yy + zz), (ww + yy) - (xx + zz), (ww + zz) - (xx + yy)
    d1, d2, d3 = d1 - d1 * f, d2 - d2 * f, d3 - d3 * f
    return [
        d1, xy + Sz, xz - Sy,
        xy - Sz, d2, yz + Sx,
        xz + Sy, yz - Sx, d3,
    ]  # fmt: skip


#: Splitter for numbers below 1 in size: a + C − C rounds a to a multiple of
#: 2**-25 (26 bits), whose squares and their sums below 2 are exact.
_UNIT_SPLITTER = 1.5 * 2.0**27


def _length_correction(*parts: _Array) -> Floats:
    """f = δ/(1 + δ) with δ = Σ q_i² − 1 to about 2**-75, for |q_i| < 2.

    The parts are split on the grid 2**-25 (as in :func:`_norm_dd`), so Σ q_hi² − 1
    is exact and the rest is small.  Used to divide out |q|², see
    :func:`matrix_from_quat`.
    """
    hh: Floats = -1.0
    hl: Floats = 0.0
    ll: Floats = 0.0
    for a in parts:
        a_hi = (a + _UNIT_SPLITTER) - _UNIT_SPLITTER
        a_lo = a - a_hi
        hh = hh + a_hi * a_hi
        hl = hl + a_hi * a_lo
        ll = ll + a_lo * a_lo
    delta = hh + (2.0 * hl + ll)
    return delta / (1.0 + delta)


def matrix_from_quat(q: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """^A R^O of the unit quaternion ``q`` = (w, x, y, z) of the active operator.

    Domain: a unit quaternion (..., 4), |q| − 1 within 64 eps (else NotARotationError; a zero
    quaternion ZeroAxisError); its length is divided out.

    Parameters
    ----------
    q : array_like, shape (..., 4)
        Unit quaternion (w, x, y, z), scalar first; q and −q give the same matrix.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        The book's basis matrix ^A R^O (rows e^A_i in O components).

    Raises
    ------
    NotARotationError
        Where |q| − 1 exceeds 64 eps.
    ZeroAxisError
        Where ``q`` has zero length.
    NonFiniteError
        Where ``q`` holds NaN or an infinity.
    ShapeError
        If ``q`` is not of shape (..., 4), or is complex or not numeric.

    Notes
    -----
    The diagonal is (w² + x² − y² − z²)/|q|² and its like, rather than
    1 − 2(y² + z²): near a half turn that form loses 1.5 eps in entries near −1.
    The quaternion's own length is divided out as 1/|q|² = 1 − δ/(1 + δ), with
    δ = |q|² − 1 formed without rounding error.  Dividing by a rounded |q|² instead
    biases the matrix: its rows come out long by 0.09 eps on average (measured
    over 2e5 rotation vectors), so a product of n different rotations drifts
    from orthogonality like 0.1 n eps instead of like sqrt(n).  Measured forward
    error at most 1.2 eps (``tests/stability``).

    Examples
    --------
    (cos φ/2, sin φ/2 e3) is the turn R3(φ):

    >>> q = [np.cos(0.35), 0.0, 0.0, np.sin(0.35)]
    >>> bool(np.allclose(matrix_from_quat(q), R3(0.7), atol=2 * EPS, rtol=0))
    True
    """
    a = _check_quat_raw(q)

    def kernel(w: _Array, x: _Array, y: _Array, z: _Array) -> list[_Array]:
        return _matrix_columns(w, x, y, z, _length_correction(w, x, y, z))

    return _by_blocks(kernel, a, 9).reshape(*a.shape[:-1], 3, 3)


def _shepperd_columns(
    r11: _Array,
    r12: _Array,
    r13: _Array,
    r21: _Array,
    r22: _Array,
    r23: _Array,
    r31: _Array,
    r32: _Array,
    r33: _Array,
) -> tuple[_Array, _Array, _Array, _Array]:
    """A positive multiple (w, x, y, z), w ≥ 0, of the quaternion of ^A R^O (entries r_ij).

    For an exact rotation the symmetric matrix K with diagonal P = (1 + tr,
    1 + 2 a_11 − tr, ...) and off-diagonal sums and differences of the active
    matrix a = ^A R^Oᵀ equals 4 q qᵀ; its row with the largest diagonal entry is
    4 q_k q, a multiple of q with q_k² ≥ 1/4 (Shepperd's pivot).  So no square
    root and no division is needed, and each entry costs one rounding.  The
    pivot is chosen on plain sums (P_k > P_0 exactly when a_kk > tr, and a near
    tie makes either row a good one); only the chosen diagonal entry is summed
    with compensation.
    """
    # One-hot pivot (m0, m1, m2, m3) as 0.0/1.0: the row is then a sum of products,
    # branch-free (np.where on unpredictable masks is three times slower).
    tr = (r11 + r22) + r33
    pick0 = tr >= np.maximum(np.maximum(r11, r22), r33)
    pick1 = ~pick0 & (r11 >= np.maximum(r22, r33))
    pick2 = ~(pick0 | pick1) & (r22 >= r33)
    m0, m1, m2 = pick0.astype(float), pick1.astype(float), pick2.astype(float)
    m3 = 1.0 - ((m0 + m1) + m2)
    # The pivot P_k = 1 ± a_11 ± a_22 ± a_33, signs (+++), (+−−), (−+−), (−−+).
    P = _sum4(
        1.0,
        ((m0 + m1) - (m2 + m3)) * r11,
        ((m0 + m2) - (m1 + m3)) * r22,
        ((m0 + m3) - (m1 + m2)) * r33,
    )
    # a_ij = r_ji: s_x = a_32 − a_23, p_xy = a_12 + a_21, ...
    s_x, s_y, s_z = r23 - r32, r31 - r13, r12 - r21
    p_xy, p_xz, p_yz = r12 + r21, r13 + r31, r23 + r32

    def row(k0: Floats, k1: Floats, k2: Floats, k3: Floats) -> _Array:
        out: _Array = (m0 * k0 + m1 * k1) + (m2 * k2 + m3 * k3)
        return out

    w = row(P, s_x, s_y, s_z)
    sign = np.copysign(1.0, w)  # w ≥ 0 (q ≡ −q)
    return (
        w * sign,
        row(s_x, P, p_xy, p_xz) * sign,
        row(s_y, p_xy, P, p_yz) * sign,
        row(s_z, p_xz, p_yz, P) * sign,
    )


def quat_from_matrix(R_A_O: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Unit quaternion (w ≥ 0) of ^A R^O, by Shepperd's largest-pivot method.

    Domain: a rotation (..., 3, 3) as :func:`check_rotation` (else NotARotationError).

    The Shepperd row is divided by its double-double length (:func:`_norm_dd`;
    r ≥ 1 there, the pivot entry), each part with about one rounding.

    Parameters
    ----------
    R_A_O : array_like, shape (..., 3, 3)
        The book's basis matrix ^A R^O, a rotation.

    Returns
    -------
    ndarray, shape (..., 4)
        The unit quaternion (w, x, y, z) of the active operator, w ≥ 0.

    Raises
    ------
    NotARotationError
        Where ``R_A_O`` is not orthogonal with det +1 within :data:`ROTATION_ATOL`.
    NonFiniteError
        Where ``R_A_O`` holds NaN or an infinity.
    ShapeError
        If ``R_A_O`` is not of shape (..., 3, 3), or is complex or not numeric.

    Examples
    --------
    The turn R3(φ) has the quaternion (cos φ/2, 0, 0, sin φ/2):

    >>> q = [np.cos(0.35), 0.0, 0.0, np.sin(0.35)]
    >>> bool(np.allclose(quat_from_matrix(R3(0.7)), q, atol=2 * EPS, rtol=0))
    True
    """
    R = check_rotation(R_A_O)

    def kernel(*entries: _Array) -> list[_Array]:
        q = _shepperd_columns(*entries)
        r = np.sqrt(sum(a * a for a in q))
        norm, splits = _norm_dd(q, r)
        ratio = _ratio_dd(1.0, norm, r)
        return [_times_dd(a, split, ratio) for a, split in zip(q, splits, strict=True)]

    return _by_blocks(kernel, R.reshape(*R.shape[:-2], 9), 4)


# --------------------------------------------------------------- rotation vectors

#: Below this angle the quaternion is (1, φ e_a/2) within half an ulp:
#: cos(φ/2) = 1 − φ²/8 + ... and sin(φ/2)/φ = (1 − φ²/24 + ...)/2 differ from 1 and
#: 1/2 by less than 2**-57.  Such rotation vectors need no norm, no trig and no
#: scaling, down to subnormal components.  Likewise atan(t)/t = 1 − t²/3 + ...
#: rounds to 1 for t < 2**-27 on the way back.
_TINY_ANGLE = 2.0**-27

#: Above this angle the low part of φ is not used: the first-order correction
#: cos(h + h_lo) ≈ cos h − h_lo sin h is good to eps only while h_lo² < eps, that
#: is h < 2**26 (h_lo ≤ h eps/2), and beyond it a rounding of the input alone
#: moves the angle modulo 2π by more than the correction.
_HUGE_ANGLE = 2.0**26


def _quat_columns_from_rotvec(
    x: _Array, y: _Array, z: _Array, *, with_sin: bool = False
) -> Sequence[_Array]:
    """The quaternion (w, qx, qy, qz) = (cos φ/2, sin(φ/2) e_a) of rotation vectors
    φ e_a (columns), followed by S = sin φ e_a (three more columns) if ``with_sin``.
    """
    with np.errstate(over="ignore"):  # s = inf marks a huge vector, treated apart
        s = x * x + y * y + z * z
    tiny = s < _TINY_ANGLE**2
    huge = s > _HUGE_ANGLE**2
    kernels = [_quat_from_rotvec_normal, _quat_from_rotvec_tiny, _quat_from_rotvec_huge]
    if not (tiny.any() or huge.any()):
        return kernels[0](x, y, z, s, with_sin)
    return _by_subsets(
        [lambda *c, k=k: k(*c, with_sin) for k in kernels],
        [~(tiny | huge), tiny, huge],
        (x, y, z, s),
        7 if with_sin else 4,
    )


def _quat_from_rotvec_normal(
    x: _Array, y: _Array, z: _Array, s: _Array, with_sin: bool
) -> list[_Array]:
    # φ = r + r_lo in double-double: an angle error of one ulp would cost up to
    # π eps in the matrix near a half turn, and one ulp in the round trip.
    r = np.sqrt(s)
    norm, splits = _norm_dd((x, y, z), r)
    r_lo = norm[2]
    h, h_lo = 0.5 * r, 0.5 * r_lo
    c, sn = np.cos(h), np.sin(h)
    # cos and sin of h + h_lo to first order (h_lo² ≤ (h eps)² is negligible).
    w = c - sn * h_lo
    half = _ratio_dd(sn + c * h_lo, norm, r)  # sin(φ/2)/φ
    parts = [w] + [_times_dd(a, split, half) for a, split in zip((x, y, z), splits, strict=True)]
    if with_sin:
        # sin φ e_a from sin φ itself, rather than as 2 w x: each rounding of w,
        # sin(φ/2) and their product shows in the angle of a round trip
        # (measured on 5e5 rotation vectors: worst 3.9 ulps that way, 3.2 this
        # way).  cos φ multiplies the tiny r_lo only, so (c − sn)(c + sn) will do.
        full = _ratio_dd(np.sin(r) + ((c - sn) * (c + sn)) * r_lo, norm, r)  # sin φ/φ
        parts += [_times_dd(a, split, full) for a, split in zip((x, y, z), splits, strict=True)]
    return parts


def _quat_from_rotvec_tiny(
    x: _Array, y: _Array, z: _Array, s: _Array, with_sin: bool
) -> list[_Array]:
    parts = [np.ones_like(s), 0.5 * x, 0.5 * y, 0.5 * z]
    return [*parts, x, y, z] if with_sin else parts


def _quat_from_rotvec_huge(
    x: _Array, y: _Array, z: _Array, s: _Array, with_sin: bool
) -> list[_Array]:
    # s may have overflowed: the norm of v / 2**k, with max |v_i| / 2**k in [1/2, 1).
    k = np.frexp(np.maximum(np.maximum(np.abs(x), np.abs(y)), np.abs(z)))[1]
    x, y, z = np.ldexp(x, -k), np.ldexp(y, -k), np.ldexp(z, -k)
    r = np.sqrt(x * x + y * y + z * z)
    h = np.ldexp(r, k - 1)
    ratio = np.sin(h) / r
    w = np.cos(h)
    parts = [w, ratio * x, ratio * y, ratio * z]
    if with_sin:
        S = 2.0 * w * ratio
        parts += [S * x, S * y, S * z]
    return parts


def quat_from_rotvec(rotvec: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Unit quaternion (cos φ/2, sin φ/2 e_a) of the rotation vector φ e_a (2.4).

    Domain: as :func:`matrix_from_rotvec`: any finite rotation vector (..., 3), subnormal to near
    1e308 in length, else NonFiniteError.

    Returned as computed (w may be negative for φ > π; q ≡ −q).  The angle
    φ = |φ e_a| is formed in double-double, so it adds no rounding of its own,
    and tiny angles (down to subnormal) keep full relative accuracy.

    Parameters
    ----------
    rotvec : array_like, shape (..., 3)
        The rotation vector φ e_a, rad; finite, of any length.

    Returns
    -------
    ndarray, shape (..., 4)
        The unit quaternion (w, x, y, z) = (cos φ/2, sin φ/2 e_a).

    Raises
    ------
    NonFiniteError
        Where ``rotvec`` holds NaN or an infinity.
    ShapeError
        If ``rotvec`` is not of shape (..., 3), or is complex or not numeric.

    Examples
    --------
    φ = 0.5 about e_a = (0.6, 0, 0.8):

    >>> s = np.sin(0.25)
    >>> q = quat_from_rotvec([0.3, 0.0, 0.4])
    >>> bool(np.allclose(q, [np.cos(0.25), 0.6 * s, 0.0, 0.8 * s], atol=2 * EPS, rtol=0))
    True
    """
    v = as_float_array(rotvec, "rotvec", (3,))
    return _by_blocks(_quat_columns_from_rotvec, v, 4)


def _rotvec_columns_from_quat(w: _Array, x: _Array, y: _Array, z: _Array) -> Sequence[_Array]:
    """φ e_a of quaternions (w ≥ 0) of any length (columns); every step is scale-free."""
    s = x * x + y * y + z * z
    # t = |(x, y, z)|/w < 2**-27: atan(t)/t = 1 − t²/3 rounds to 1, so φ e_a = 2 (x, y, z)/w.
    tiny = s < _TINY_ANGLE**2 * (w * w)
    if not tiny.any():
        return _rotvec_from_quat_normal(w, x, y, z, s)
    return _by_subsets(
        [_rotvec_from_quat_normal, _rotvec_from_quat_tiny], [~tiny, tiny], (w, x, y, z, s), 3
    )


def _rotvec_from_quat_normal(
    w: _Array, x: _Array, y: _Array, z: _Array, s: _Array
) -> tuple[_Array, ...]:
    # Here |(x, y, z)| ≥ 2**-27 w, and w or |(x, y, z)| is of order 1 (a unit
    # quaternion, or a Shepperd row with its pivot ≥ 1): within range of _norm_dd.
    r = np.sqrt(s)
    norm, splits = _norm_dd((x, y, z), r)
    # atan2(r + r_lo, w) to first order: d/dr atan2(r, w) = w/(r² + w²).
    angle = np.arctan2(r, w) + norm[2] * w / (s + w * w)
    ratio = _ratio_dd(angle + angle, norm, r)  # φ/|(x, y, z)|
    return tuple(_times_dd(a, split, ratio) for a, split in zip((x, y, z), splits, strict=True))


def _rotvec_from_quat_tiny(
    w: _Array, x: _Array, y: _Array, z: _Array, s: _Array
) -> tuple[_Array, _Array, _Array]:
    return (x + x) / w, (y + y) / w, (z + z) / w


def rotvec_from_quat(q: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Rotation vector φ e_a with φ in [0, π] of the unit quaternion ``q``.

    Domain: a unit quaternion (..., 4), |q| − 1 within 64 eps (else NotARotationError; a zero
    quaternion ZeroAxisError).

    Parameters
    ----------
    q : array_like, shape (..., 4)
        Unit quaternion (w, x, y, z), scalar first; q and −q give the same vector.

    Returns
    -------
    ndarray, shape (..., 3)
        The rotation vector φ e_a, φ in [0, π], rad.

    Raises
    ------
    NotARotationError
        Where |q| − 1 exceeds 64 eps.
    ZeroAxisError
        Where ``q`` has zero length.
    NonFiniteError
        Where ``q`` holds NaN or an infinity.
    ShapeError
        If ``q`` is not of shape (..., 4), or is complex or not numeric.

    Examples
    --------
    A turn by 4 rad about e3 comes back as the same turn by 4 − 2π:

    >>> round(float(rotvec_from_quat(quat_from_rotvec([0.0, 0.0, 4.0]))[2] + 2 * np.pi), 12)
    4.0
    """
    a = _canonical(_check_quat_raw(q))
    return _by_blocks(_rotvec_columns_from_quat, a, 3)


def matrix_from_rotvec(rotvec: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """^A R^O(φ) of the rotation vector φ = φ e_a, (2.28)–(2.29).

    Domain: any finite rotation vector (..., 3), from subnormal to near 1e308 in length (tiny and
    huge angles are computed apart, without overflow); beyond 2**26 rad the angle modulo 2π is only
    as good as the input's rounding.  NaN or inf raise NonFiniteError.

    Computed through the quaternion (cos φ/2, sin(φ/2) e_a) (the symmetric part
    and the diagonal) and sin φ e_a (the antisymmetric part), with the angle
    φ = |φ e_a| in double-double, so that near a half turn the matrix is within
    2 eps and tiny angles (down to subnormal) keep full relative accuracy in the
    off-diagonal entries; the angle survives the round trip through
    :func:`rotvec_from_matrix` within a few ulps.

    Parameters
    ----------
    rotvec : array_like, shape (..., 3)
        The rotation vector φ e_a, rad; finite, of any length.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        The book's basis matrix ^A R^O(φ): a turn of the basis by φ about e_a.

    Raises
    ------
    NonFiniteError
        Where ``rotvec`` holds NaN or an infinity.
    ShapeError
        If ``rotvec`` is not of shape (..., 3), or is complex or not numeric.

    Examples
    --------
    (2.29) for e_a = e3 is R3 (Example 2.1):

    >>> bool(np.allclose(matrix_from_rotvec([0, 0, 0.7]), R3(0.7), atol=2 * EPS, rtol=0))
    True
    """
    v = as_float_array(rotvec, "rotvec", (3,))

    def kernel(x: _Array, y: _Array, z: _Array) -> list[_Array]:
        w, qx, qy, qz, *S = _quat_columns_from_rotvec(x, y, z, with_sin=True)
        return _matrix_columns(w, qx, qy, qz, _length_correction(w, qx, qy, qz), S)

    return _by_blocks(kernel, v, 9).reshape(*v.shape[:-1], 3, 3)


def rotvec_from_matrix(R_A_O: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Rotation vector φ e_a, φ in [0, π], of ^A R^O (inverse of (2.28)).

    Domain: a rotation (..., 3, 3) as :func:`check_rotation` (else NotARotationError).

    At φ = π both ±π e_a describe the rotation; either may be returned.
    Read off the unnormalised Shepperd quaternion: for φ < π/2 that is
    (1 + tr, a_32 − a_23, ...), so φ = 2 atan2(|s|, 1 + tr) with no square root.

    Parameters
    ----------
    R_A_O : array_like, shape (..., 3, 3)
        The book's basis matrix ^A R^O, a rotation.

    Returns
    -------
    ndarray, shape (..., 3)
        The rotation vector φ e_a, φ in [0, π], rad.

    Raises
    ------
    NotARotationError
        Where ``R_A_O`` is not orthogonal with det +1 within :data:`ROTATION_ATOL`.
    NonFiniteError
        Where ``R_A_O`` holds NaN or an infinity.
    ShapeError
        If ``R_A_O`` is not of shape (..., 3, 3), or is complex or not numeric.

    Examples
    --------
    The inverse of :func:`matrix_from_rotvec`:

    >>> v = [0.3, -0.2, 0.4]
    >>> bool(np.allclose(rotvec_from_matrix(matrix_from_rotvec(v)), v, atol=4 * EPS, rtol=0))
    True
    """
    R = check_rotation(R_A_O)

    def kernel(*entries: _Array) -> Sequence[_Array]:
        return _rotvec_columns_from_quat(*_shepperd_columns(*entries))

    return _by_blocks(kernel, R.reshape(*R.shape[:-2], 9), 3)


def matrix_from_axis_angle(axis: npt.ArrayLike, angle: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """^A R^O for a turn ``angle`` about the direction ``axis`` (2.29).

    Domain: ``axis`` any finite non-zero (..., 3) of any length, subnormal to 1e308 (scaled by a
    power of two before its norm is taken by hypot, so s·axis gives the same matrix for s a power
    of two; a zero axis raises ZeroAxisError), ``angle`` any finite (...); their leading
    axes broadcast (batches that do not raise ShapeError listing each argument's shape).

    ``axis`` is a direction: its length is divided out; a zero axis raises
    :class:`~mechanics.errors.ZeroAxisError`.

    Parameters
    ----------
    axis : array_like, shape (..., 3)
        The direction e_a of the axis, finite and non-zero, of any length.
    angle : array_like, shape (...)
        The angle φ of the turn of the basis, rad; finite.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        ^A R^O of the rotation vector φ e_a, as :func:`matrix_from_rotvec`.

    Raises
    ------
    ZeroAxisError
        Where ``axis`` has zero length.
    NonFiniteError
        Where ``axis`` or ``angle`` holds NaN or an infinity.
    ShapeError
        If ``axis`` is not of shape (..., 3), an input is complex or not numeric, or the leading
        axes do not broadcast.

    Examples
    --------
    The axis' length does not matter: a turn about 5 e3 is R3:

    >>> R = matrix_from_axis_angle([0.0, 0.0, 5.0], 0.7)
    >>> bool(np.allclose(R, R3(0.7), atol=2 * EPS, rtol=0))
    True
    """
    a = _scaled_to_unit_exponent(as_float_array(axis, "axis", (3,)))
    n = _norm3(a)
    if (n == 0).any():
        idx = tuple(int(i) for i in np.argwhere(n == 0)[0]) if n.ndim else ()
        raise ZeroAxisError(f"axis has zero length at index {idx}; a direction is required")
    phi = as_float_array(angle, "angle")
    return matrix_from_rotvec(a / n[..., None] * phi[..., None])


matrix_from_axis_angle = broadcast_checked(matrix_from_axis_angle)
