"""The free rigid body's state (L_A, rows of ^A R^O), its right-hand side (4.47), (2.52)
and the SO(3) exponential step (2.29).

Part of :mod:`mechanics.integrators` (its docstring states the conventions).
"""

from __future__ import annotations

from typing import Protocol, cast

import numpy as np
import numpy.typing as npt

from .._validate import as_float_array, broadcast_checked
from ..errors import NonPhysicalInertiaError, ResultOverflowError, ShapeError
from ..rotation import check_rotation, matrix_from_rotvec
from ._grid import _positive_scalar
from ._solution import FloatArray

# The free rigid body's right-hand side as one gather per factor, dy = y[IA] w[WA] − y[IB] w[WB]:
# (L × ω)_i = L_{i+1} ω_{i+2} − L_{i+2} ω_{i+1}, and row r of Ω R (2.52) is
# ω_{r+2} R_{r+1} − ω_{r+1} R_{r+2} (indices mod 3; R's rows stored flat after L).
_P1, _P2 = (1, 2, 0), (2, 0, 1)
_IA = np.array([*_P1, *(3 + 3 * _P1[r] + c for r in range(3) for c in range(3))])
_IB = np.array([*_P2, *(3 + 3 * _P2[r] + c for r in range(3) for c in range(3))])
_WA = np.array([*_P2, *(_P2[r] for r in range(3) for _ in range(3))])
_WB = np.array([*_P1, *(_P1[r] for r in range(3) for _ in range(3))])


def _check_moments(J: npt.ArrayLike) -> FloatArray:
    Jm = as_float_array(J, "J", (3,))
    if not (Jm > 0).all():
        idx = tuple(int(i) for i in np.argwhere(~(Jm > 0))[0])
        raise NonPhysicalInertiaError(
            f"J (the principal moments) must be > 0; J{idx[-1] + 1} = {float(Jm[idx])!r} "
            f"at index {idx}"
        )
    for i in range(3):
        j, k = (i + 1) % 3, (i + 2) % 3
        bad = Jm[..., i] > Jm[..., j] + Jm[..., k]
        if bad.any():
            idx = tuple(int(x) for x in np.argwhere(bad)[0])
            Ji = Jm[idx] if Jm.ndim > 1 else Jm
            raise NonPhysicalInertiaError(
                f"J breaks the triangle inequality J{j + 1} + J{k + 1} ≥ J{i + 1}: "
                f"moments {Ji.tolist()}"
            )
    return Jm


def rigid_body_state(L_A: npt.ArrayLike, R_A_O: npt.ArrayLike) -> FloatArray:
    """The 12-vector (L_A, rows of ^A R^O) of a free rigid body, shape (..., 12).

    Domain: finite L_A (..., 3) and R_A_O (..., 3, 3) that broadcast (else ShapeError or
    NonFiniteError); R_A_O a rotation within :func:`~mechanics.rotation.check_rotation`'s
    default atol, 256 eps (else NotARotationError: a drifted attitude is refused here, project
    it with :func:`~mechanics.rotation.nearest_rotation` first; :func:`rigid_body_parts` takes
    any state).

    Parameters
    ----------
    L_A : array_like, shape (..., 3)
        Angular momentum about G, body components (kg m²/s).
    R_A_O : array_like, shape (..., 3, 3)
        The attitude, the book's passive matrix ^A R^O (a rotation).

    Returns
    -------
    ndarray, shape (..., 12)
        L_A, then the rows of R_A_O, on the broadcast leading axes.

    Raises
    ------
    NotARotationError
        ``R_A_O`` is not a rotation within 256 eps.
    ShapeError
        A trailing shape other than (3,) or (3, 3), or leading axes that do not broadcast.
    NonFiniteError
        NaN or an infinity in ``L_A`` or ``R_A_O``.

    Examples
    --------
    >>> y = rigid_body_state([1.0, 2.0, 3.0], np.eye(3))
    >>> y.shape, y[:4].tolist()
    ((12,), [1.0, 2.0, 3.0, 1.0])
    """
    L = as_float_array(L_A, "L_A", (3,))
    R = check_rotation(R_A_O)
    batch = np.broadcast_shapes(L.shape[:-1], R.shape[:-2])
    L = np.broadcast_to(L, (*batch, 3))
    R = np.broadcast_to(R, (*batch, 3, 3)).reshape(*batch, 9)
    return np.concatenate([L, R], axis=-1)


rigid_body_state = broadcast_checked(rigid_body_state)


def rigid_body_parts(y: npt.ArrayLike) -> tuple[FloatArray, FloatArray]:
    """(L_A, R_A_O) of rigid-body states ``y`` of shape (..., 12), as views.

    Not checked for orthogonality: an integrator's R may have drifted, which is the point.

    Domain: any finite y of shape (..., 12) (else ShapeError or NonFiniteError).

    Parameters
    ----------
    y : array_like, shape (..., 12)
        States of :func:`rigid_body_state`: L_A, then the rows of ^A R^O.

    Returns
    -------
    L_A : ndarray, shape (..., 3)
        Angular momentum about G, body components (kg m²/s).
    R_A_O : ndarray, shape (..., 3, 3)
        The attitude ^A R^O (views of ``y`` when it is a float64 array).

    Raises
    ------
    ShapeError
        ``y`` not of shape (..., 12), or not an array of real numbers.
    NonFiniteError
        NaN or an infinity in ``y``.

    Examples
    --------
    The inverse of :func:`rigid_body_state`, exactly:

    >>> from mechanics.rotation import R3
    >>> L, R = rigid_body_parts(rigid_body_state([1.0, -2.0, 0.5], R3(0.5)))
    >>> L.tolist(), bool((R == R3(0.5)).all())
    ([1.0, -2.0, 0.5], True)
    """
    a = as_float_array(y, "y", (12,))
    return a[..., :3], a[..., 3:].reshape(*a.shape[:-1], 3, 3)


class _FreeBodyRhs(Protocol):
    """:func:`free_rigid_body_rhs`'s rhs(t, y), carrying its moments for the compiled path."""

    free_body_moments: FloatArray

    def __call__(self, t: float, y: FloatArray, /) -> FloatArray: ...


def free_rigid_body_rhs(J: npt.ArrayLike) -> _FreeBodyRhs:
    """The right-hand side rhs(t, y) of the torque-free rigid body for :func:`integrate`.

    Domain: principal moments J > 0 obeying the triangle inequality (else NonPhysicalInertiaError),
    shape (..., 3); the returned rhs takes finite states.

    dL_A/dt = L_A × ω_A (Euler's equations (4.47) with M = 0, ω_i = L_i/J_i) and
    dR_A_O/dt = Ω R_A_O with the book's Ω of ω_A (2.52); ``y`` is the state of
    :func:`rigid_body_state`, shape (..., 12), and ``J`` broadcasts against its
    leading axes.

    Parameters
    ----------
    J : array_like, shape (..., 3)
        Principal moments (J1, J2, J3) about G (kg m²), > 0, each at most the sum of the
        other two.

    Returns
    -------
    callable
        ``rhs(t, y)`` → dy/dt, an ndarray of ``y``'s shape (..., 12); a ``y`` of another
        trailing shape raises ShapeError.  It carries ``J`` as its ``free_body_moments``
        attribute, by which :func:`integrate` recognises it for the compiled path.

    Raises
    ------
    NonPhysicalInertiaError
        A moment ≤ 0, or one larger than the sum of the other two.
    ShapeError
        ``J`` not of shape (..., 3), or not an array of real numbers.
    NonFiniteError
        NaN or an infinity in ``J``.

    Examples
    --------
    d/dt of 2T = Σ L_i²/J_i vanishes:

    >>> J = np.array([1.0, 2.0, 2.5])
    >>> y = rigid_body_state([0.3, -1.0, 0.7], np.eye(3))
    >>> dy = free_rigid_body_rhs(J)(0.0, y)
    >>> bool(abs(np.sum(y[:3] / J * dy[:3])) < 1e-15)
    True
    """
    Jm = _check_moments(J)

    def rhs(t: float, y: FloatArray) -> FloatArray:
        if y.shape[-1:] != (12,):
            raise ShapeError(f"rigid-body state must have shape (..., 12); got {y.shape}")
        w = y[..., :3] / Jm
        return y.take(_IA, axis=-1) * w.take(_WA, axis=-1) - y.take(_IB, axis=-1) * w.take(
            _WB, axis=-1
        )

    out = cast(_FreeBodyRhs, rhs)  # a function given an attribute (mypy cannot type that)
    out.free_body_moments = Jm  # what integrate's compiled path recognises
    return out


def so3_exp_step(R_A_O: npt.ArrayLike, w_A: npt.ArrayLike, h: float) -> FloatArray:
    """^A R^O after a time h of constant body angular velocity ω_A: exp(h Ω) ^A R^O.

    Domain: finite R_A_O (..., 3, 3), a rotation (else NotARotationError), and w_A (..., 3) that
    broadcast (else ShapeError); a finite scalar h > 0 (else NonPositiveParameterError); any
    rotation angle h|ω| (reduced modulo 2π by :func:`~mechanics.rotation.matrix_from_rotvec`)
    whose rotation vector h ω_A fits float64 (else ResultOverflowError naming h and w_A).

    dR/dt = Ω R with the book's Ω (2.46), (2.52) integrates for constant ω_A to
    exp(h Ω) R, and exp(h Ω) is the passive matrix ^A R^O(h ω_A) of the rotation
    vector h ω_A (2.29) (:func:`mechanics.rotation.matrix_from_rotvec`).  The
    result is a rotation to rounding; n steps drift from orthogonality like a
    random walk of n roundings, never secularly.

    Parameters
    ----------
    R_A_O : array_like, shape (..., 3, 3)
        The attitude ^A R^O at the start of the step, a rotation.
    w_A : array_like, shape (..., 3)
        Body components of ω (rad/s).
    h : float, > 0
        The time step (s), a scalar.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        ^A R^O(h ω_A) ^A R^O, the attitude after the step.

    Raises
    ------
    NotARotationError
        ``R_A_O`` is not a rotation within 256 eps.
    NonPositiveParameterError
        ``h`` ≤ 0.
    ShapeError
        Trailing shapes other than (3, 3) and (3,), leading axes that do not broadcast, or
        an ``h`` that is not a scalar.
    NonFiniteError
        NaN or an infinity in an input.
    ResultOverflowError
        A component of h ω_A beyond float64's range; the message names ``h`` and the
        ``w_A`` of the first such row.

    Examples
    --------
    Example 2.2: R3(ψ) turning with ω = ψ̇ e3 is R3(ψ + h ψ̇) after h.

    >>> from mechanics.rotation import EPS, R3
    >>> R = so3_exp_step(R3(0.4), [0.0, 0.0, 2.0], 0.1)
    >>> bool(np.abs(R - R3(0.6)).max() < 4 * EPS)
    True
    """
    R = check_rotation(R_A_O)
    w = as_float_array(w_A, "w_A", (3,))
    hf = _positive_scalar(h, "h")
    with np.errstate(over="ignore"):  # checked below
        rotvec = hf * w
    bad = ~np.isfinite(rotvec).all(axis=-1)
    if bad.any():
        idx = tuple(int(i) for i in np.argwhere(bad)[0])
        raise ResultOverflowError(
            f"the rotation vector h w_A of h = {hf!r}, w_A = {w[idx].tolist()} (index {idx}) "
            "is beyond float64: |h w_A_i| exceeds 1.8e308"
        )
    R_new: FloatArray = matrix_from_rotvec(rotvec) @ R  # (the product is typed Any)
    return R_new


so3_exp_step = broadcast_checked(so3_exp_step)
