"""Angular velocity and the velocities of the points of a rigid body.

Conventions (Essén 1996, ch. 2.5–2.6)
-------------------------------------
- ``R_A_O`` is the book's passive matrix ^A R^O (see :mod:`mechanics.rotation`);
  ``Rdot_A_O`` is its time derivative as seen from O.
- The angular-velocity matrix is ^O Ω^A = (d/dt ^A R^O) ^O R^A (2.46), which is
  antisymmetric (2.51) and holds the components of ω in the body basis A as
  Ω = [[0, ω3, −ω2], [−ω3, 0, ω1], [ω2, −ω1, 0]] (2.52).  Note the sign: this is
  minus the usual "hat" matrix, because the book's matrices act on bases.
- ``w_A`` are components of ω in the body basis A, ``w_O`` in the observer basis O;
  w_O = (^A R^O)ᵀ w_A.
- Euler angles are z-x-z, ^A R^O = R3(φ) R1(θ) R3(ψ); Euler's kinematic equations
  (2.69) give w_A from (ψ̇, θ̇, φ̇).
- Vectors are ``(..., 3)`` and all functions broadcast over leading axes.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from ._validate import as_float_array, finite_result
from .errors import (
    CollinearPointsError,
    GimbalLockError,
    ResultOverflowError,
    ShapeError,
    UnknownOptionError,
    ZeroAngularVelocityError,
)
from .rotation import EPS, check_rotation

__all__ = [
    "angular_velocity_from_euler_rates",
    "angular_velocity_from_matrix_rate",
    "euler_rates_from_angular_velocity",
    "instantaneous_axis",
    "instantaneous_centre_plane",
    "omega_matrix_from_vector",
    "point_velocity",
    "rigid_velocity_from_points",
    "vector_from_omega_matrix",
]

#: Points whose spread matrix Σ(|d|² 1 − d dᵀ) has smallest/largest eigenvalue
#: below this are treated as collinear.  For N points with coordinates of relative
#: accuracy eps the eigenvalue of an exactly collinear set comes out at most a
#: few hundred eps times the largest (measured up to N = 10^4); 1e4 eps leaves
#: room for that and still accepts points a relative 1e-6 off a line.
COLLINEAR_RTOL = 1e4 * EPS


#: |sin θ| at or below this is gimbal lock to rounding: θ is within rounding of 0
#: or π (sin(fl(π)) = 1.2e-16 = 0.55 eps), where (2.69) cannot be inverted.
GIMBAL_LOCK_ATOL = 4 * EPS


def omega_matrix_from_vector(w_A: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """The angular-velocity matrix (2.52) of the body components ``w_A``.

    Domain: any finite w_A of shape (..., 3); exact (entries are ±w_i).

    Parameters
    ----------
    w_A : array_like, shape (..., 3)
        Components of ω in the body basis A, rad/s; finite.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        Ω = [[0, ω3, −ω2], [−ω3, 0, ω1], [ω2, −ω1, 0]], antisymmetric (2.51), rad/s.

    Raises
    ------
    NonFiniteError
        Where ``w_A`` holds NaN or an infinity.
    ShapeError
        If ``w_A`` is not of shape (..., 3), or is complex or not numeric.

    Examples
    --------
    The book's sign: Ω r = r × ω, minus the usual "hat" matrix:

    >>> w, r = [1.0, 2.0, 3.0], [4.0, 5.0, 6.0]
    >>> (omega_matrix_from_vector(w) @ r).tolist(), np.cross(r, w).tolist()
    ([3.0, -6.0, 3.0], [3.0, -6.0, 3.0])
    """
    w = as_float_array(w_A, "w_A", (3,))
    w1, w2, w3 = np.moveaxis(w, -1, 0)
    z = np.zeros_like(w1)
    return np.stack(
        [np.stack(r, axis=-1) for r in ((z, w3, -w2), (-w3, z, w1), (w2, -w1, z))], axis=-2
    )


omega_matrix_from_vector = finite_result(omega_matrix_from_vector)


#: (i, j) of Ω_ij − Ω_ji for ω1, ω2, ω3 (2.52)
_UPPER, _LOWER = ([1, 2, 0], [2, 0, 1]), ([2, 0, 1], [1, 2, 0])


def _half_differences(M: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
    """(Ω_ij − Ω_ji)/2 of a finite (..., 3, 3) array, finite and correctly rounded.

    The difference is exact-then-halved (a subnormal half keeps its last bit); where the
    difference overflows, each entry is halved first, which is exact at that size.
    """
    a, b = M[..., _UPPER[0], _UPPER[1]], M[..., _LOWER[0], _LOWER[1]]
    with np.errstate(over="ignore"):  # replaced below where it overflows
        d = a - b
    half: npt.NDArray[np.float64] = np.where(np.isfinite(d), 0.5 * d, 0.5 * a - 0.5 * b)
    return half


def vector_from_omega_matrix(Omega: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Body components of ω from the angular-velocity matrix (2.52).

    Domain: any finite (..., 3, 3) matrix; only its antisymmetric part is read.  The result
    is always finite: where a difference Ω_ij − Ω_ji is beyond float64 (entries near 1e308 of
    opposite signs), each entry is halved before it is taken (exact at that size).

    Reads the antisymmetric part, (Ω − Ωᵀ)/2, so that a rounding-level symmetric
    part is ignored rather than folded into ω.

    Parameters
    ----------
    Omega : array_like, shape (..., 3, 3)
        The angular-velocity matrix ^O Ω^A, rad/s; finite.

    Returns
    -------
    ndarray, shape (..., 3)
        The components (ω1, ω2, ω3) of ω in the body basis A, rad/s.

    Raises
    ------
    NonFiniteError
        Where ``Omega`` holds NaN or an infinity.
    ShapeError
        If ``Omega`` is not of shape (..., 3, 3), or is complex or not numeric.

    Examples
    --------
    The inverse of :func:`omega_matrix_from_vector`, blind to a symmetric part:

    >>> Omega = omega_matrix_from_vector([1.0, -2.0, 3.0]) + np.ones((3, 3))
    >>> vector_from_omega_matrix(Omega).tolist()
    [1.0, -2.0, 3.0]
    """
    return _half_differences(as_float_array(Omega, "Omega", (3, 3)))


vector_from_omega_matrix = finite_result(vector_from_omega_matrix)


#: The power of two by which angular_velocity_from_matrix_rate scales a rate matrix whose
#: ω overflows on the way: with max|Rdot| <= 2**1021, |Ω_ij| and |ω_k| are at most
#: √3·2**1021 and every partial sum of Rᵀ ω at most |ω| <= 3·2**1021, all below 2**1024.
_RATE_SHIFT = 3


def _omega_from_rate(
    R: npt.NDArray[np.float64], Rdot: npt.NDArray[np.float64], basis: str, shift: int
) -> npt.NDArray[np.float64]:
    """ω in ``basis`` from (2**-shift Rdot) Rᵀ, scaled back by 2**shift; not finite where
    it overflows."""
    with np.errstate(over="ignore", invalid="ignore"):  # the caller checks the result
        w = _half_differences(np.ldexp(Rdot, -shift) @ np.swapaxes(R, -1, -2))
        if basis == "O":
            w = np.einsum("...ji,...j->...i", R, w)
        out: npt.NDArray[np.float64] = np.ldexp(w, shift)
    return out


def angular_velocity_from_matrix_rate(
    R_A_O: npt.ArrayLike, Rdot_A_O: npt.ArrayLike, *, basis: str = "A"
) -> npt.NDArray[np.float64]:
    """ω of the body A relative to O from ^A R^O and its rate, (2.45)–(2.52).

    Domain: R_A_O a rotation (``check_rotation``'s tolerance, else NotARotationError), any finite
    Rdot_A_O (only the part Rdot R^T antisymmetric is read); basis "A" or "O" (else
    UnknownOptionError).  An entry of Rdot R^T beyond float64 does not fail: the rate is
    scaled by a power of two there; only a component of ω itself beyond float64 raises
    ResultOverflowError, naming R_A_O and Rdot_A_O of its row.

    Parameters
    ----------
    R_A_O : array_like, shape (..., 3, 3)
        The book's rotation matrix ^A R^O.
    Rdot_A_O : array_like, shape (..., 3, 3)
        Its time derivative as seen from O, 1/s.
    basis : {"A", "O"}, optional
        Return components in the body basis A (as the book's (2.52)) or in O; default "A".

    Returns
    -------
    ndarray, shape (..., 3)
        The components of ω in the basis ``basis``, rad/s.

    Raises
    ------
    NotARotationError
        Where ``R_A_O`` is not orthogonal with det +1 within
        :data:`~mechanics.rotation.ROTATION_ATOL`.
    UnknownOptionError
        If ``basis`` is neither "A" nor "O".
    NonFiniteError
        Where ``R_A_O`` or ``Rdot_A_O`` holds NaN or an infinity.
    ShapeError
        If an input is not of shape (..., 3, 3), is complex or not numeric, or the leading axes do
        not broadcast.
    ResultOverflowError
        Where a component of ω in the basis ``basis`` is beyond float64; the message names
        ``R_A_O`` and ``Rdot_A_O`` of the first such row.

    Examples
    --------
    Example 2.2: R3(ψ(t)) turns with ω = ψ̇ e3.

    >>> from mechanics.rotation import R3
    >>> psi, psidot = 0.4, 2.0
    >>> Rdot = psidot * np.array([[-np.sin(psi), np.cos(psi), 0],
    ...                           [-np.cos(psi), -np.sin(psi), 0], [0, 0, 0]])
    >>> angular_velocity_from_matrix_rate(R3(psi), Rdot).round(12).tolist()
    [0.0, 0.0, 2.0]
    """
    if basis not in ("A", "O"):
        raise UnknownOptionError(f"basis must be 'A' or 'O'; got {basis!r}")
    R = check_rotation(R_A_O)
    Rdot = as_float_array(Rdot_A_O, "Rdot_A_O", (3, 3))
    w = _omega_from_rate(R, Rdot, basis, 0)
    # |Ω_ij| <= |row i of Rdot| <= √3 max|Rdot| (rows of R are unit vectors), so Ω, ω or a
    # partial sum of Rᵀ ω overflows only where max|Rdot| is near 2**1023.  Those rows are
    # redone with Rdot scaled by 2**-_RATE_SHIFT (exact at that size) and ω scaled back;
    # other rows are not scaled, so their subnormal entries stay exact.
    big = ~np.isfinite(w).all(axis=-1, keepdims=True)
    if big.any():
        w = np.where(big, _omega_from_rate(R, Rdot, basis, _RATE_SHIFT), w)
    bad = ~np.isfinite(w).all(axis=-1)
    if bad.any():
        idx = _first_index(bad)
        Rb, Rdotb = np.broadcast_arrays(R, Rdot)
        raise ResultOverflowError(
            f"the angular velocity of R_A_O = {Rb[idx].tolist()}, "
            f"Rdot_A_O = {Rdotb[idx].tolist()} (index {idx}) is beyond float64: "
            f"a component of omega in basis {basis!r} exceeds 1.8e308"
        )
    return w


angular_velocity_from_matrix_rate = finite_result(angular_velocity_from_matrix_rate)


def angular_velocity_from_euler_rates(
    psi: npt.ArrayLike,
    theta: npt.ArrayLike,
    phi: npt.ArrayLike,
    psidot: npt.ArrayLike,
    thetadot: npt.ArrayLike,
    phidot: npt.ArrayLike,
) -> npt.NDArray[np.float64]:
    """Body components of ω from Euler angles and rates: Euler's kinematic equations (2.69).

    Domain: all six finite and broadcasting; no singularity in this direction (gimbal lock only
    hides the rates); a result beyond float64 raises ResultOverflowError.

    Parameters
    ----------
    psi, theta, phi : array_like, shape (...)
        The z-x-z Euler angles ψ, θ, φ, rad; finite.
    psidot, thetadot, phidot : array_like, shape (...)
        Their rates ψ̇, θ̇, φ̇, rad/s; finite.

    Returns
    -------
    ndarray, shape (..., 3)
        ω in the body basis A: (ψ̇ sin θ sin φ + θ̇ cos φ, ψ̇ sin θ cos φ − θ̇ sin φ,
        ψ̇ cos θ + φ̇), rad/s, with the broadcast shape of the six inputs.

    Raises
    ------
    NonFiniteError
        Where an input holds NaN or an infinity.
    ShapeError
        If an input is complex or not numeric, or their leading axes do not broadcast.
    ResultOverflowError
        Where a component of ω is beyond float64.

    Examples
    --------
    A pure spin φ̇ about the body axis e^A_3:

    >>> angular_velocity_from_euler_rates(0.1, 0.2, 0.3, 0.0, 0.0, 5.0).tolist()
    [0.0, 0.0, 5.0]
    """
    names = ("psi", "theta", "phi", "psidot", "thetadot", "phidot")
    args = [
        as_float_array(v, n)
        for v, n in zip((psi, theta, phi, psidot, thetadot, phidot), names, strict=True)
    ]
    _, th, ph, psd, thd, phd = np.broadcast_arrays(*args)
    sth, cth, sph, cph = np.sin(th), np.cos(th), np.sin(ph), np.cos(ph)
    return np.stack(
        [psd * sth * sph + thd * cph, psd * sth * cph - thd * sph, psd * cth + phd], axis=-1
    )


angular_velocity_from_euler_rates = finite_result(angular_velocity_from_euler_rates)


def euler_rates_from_angular_velocity(
    theta: npt.ArrayLike, phi: npt.ArrayLike, w_A: npt.ArrayLike
) -> npt.NDArray[np.float64]:
    """(ψ̇, θ̇, φ̇) from the body components of ω: (2.69) inverted.

    Domain: finite θ, φ, w_A with |sin θ| > ``GIMBAL_LOCK_ATOL`` (else GimbalLockError: at θ = 0 or
    π only ψ̇ ± φ̇ is determined); a rate beyond float64 raises ResultOverflowError.

    Close to gimbal lock the rates grow like 1/sin θ;
    :func:`mechanics.rotation.euler_near_gimbal_lock` tells.

    Parameters
    ----------
    theta, phi : array_like, shape (...)
        The Euler angles θ and φ, rad; finite, |sin θ| > ``GIMBAL_LOCK_ATOL`` (4 eps).
    w_A : array_like, shape (..., 3)
        Components of ω in the body basis A, rad/s; finite.

    Returns
    -------
    ndarray, shape (..., 3)
        The rates (ψ̇, θ̇, φ̇), rad/s.

    Raises
    ------
    GimbalLockError
        Where |sin θ| ≤ ``GIMBAL_LOCK_ATOL``, where the rates are not determined (only
        ψ̇ + φ̇ or ψ̇ − φ̇ is).
    NonFiniteError
        Where an input holds NaN or an infinity.
    ShapeError
        If ``w_A`` is not of shape (..., 3), an input is complex or not numeric, or the leading
        axes do not broadcast.
    ResultOverflowError
        Where a rate is beyond float64.

    Examples
    --------
    The inverse of :func:`angular_velocity_from_euler_rates`:

    >>> w_A = angular_velocity_from_euler_rates(0.1, 0.7, 0.3, 1.0, -2.0, 0.5)
    >>> euler_rates_from_angular_velocity(0.7, 0.3, w_A).round(12).tolist()
    [1.0, -2.0, 0.5]
    """
    th = as_float_array(theta, "theta")
    ph = as_float_array(phi, "phi")
    w = as_float_array(w_A, "w_A", (3,))
    sth = np.sin(th)
    locked = np.abs(sth) <= GIMBAL_LOCK_ATOL
    if locked.any():
        bad = float(np.broadcast_to(th, locked.shape)[locked].flat[0])
        raise GimbalLockError(
            f"theta = {bad!r} gives |sin(theta)| <= {GIMBAL_LOCK_ATOL:.3g}: Euler-angle rates "
            "are undefined at gimbal lock (only psidot + phidot or psidot - phidot is determined)"
        )
    w1, w2, w3 = np.moveaxis(w, -1, 0)
    sph, cph = np.sin(ph), np.cos(ph)
    psidot = (w1 * sph + w2 * cph) / sth
    thetadot = w1 * cph - w2 * sph
    phidot = w3 - psidot * np.cos(th)
    return np.stack(np.broadcast_arrays(psidot, thetadot, phidot), axis=-1)


euler_rates_from_angular_velocity = finite_result(euler_rates_from_angular_velocity)


def point_velocity(
    v_A: npt.ArrayLike, omega: npt.ArrayLike, r_AB: npt.ArrayLike
) -> npt.NDArray[np.float64]:
    """Velocity of the body point B: v_B = v_A + ω × AB, the connection formula (2.73).

    Domain: any finite v_A, omega, r_AB of shape (..., 3) that broadcast; a result beyond float64
    raises ResultOverflowError.

    Parameters
    ----------
    v_A : array_like, shape (..., 3)
        Velocity of the body point A, m/s; finite.
    omega : array_like, shape (..., 3)
        The body's angular velocity ω, rad/s, in the same basis; finite.
    r_AB : array_like, shape (..., 3)
        The vector AB from A to B, m; finite.

    Returns
    -------
    ndarray, shape (..., 3)
        The velocity v_B of the body point B, m/s.

    Raises
    ------
    NonFiniteError
        Where an input holds NaN or an infinity.
    ShapeError
        If an input is not of shape (..., 3), is complex or not numeric, or the leading axes do
        not broadcast.
    ResultOverflowError
        Where a component of v_B is beyond float64.

    Examples
    --------
    >>> point_velocity([1, 0, 0], [0, 0, 2], [0, 1, 0]).tolist()
    [-1.0, 0.0, 0.0]
    """
    v = as_float_array(v_A, "v_A", (3,))
    w = as_float_array(omega, "omega", (3,))
    r = as_float_array(r_AB, "r_AB", (3,))
    return v + np.cross(w, r)


point_velocity = finite_result(point_velocity)


def _exponent(a: npt.NDArray[np.float64], axis: int | tuple[int, ...]) -> npt.NDArray[np.intc]:
    """k with max |a| over ``axis`` in [2**(k−1), 2**k) (k = 0 where all are 0); keepdims."""
    k: npt.NDArray[np.intc] = np.frexp(np.max(np.abs(a), axis=axis, keepdims=True))[1]
    return k


def _first_index(mask: np.ndarray | np.bool_) -> tuple[int, ...]:
    return tuple(int(i) for i in np.argwhere(mask)[0]) if np.ndim(mask) else ()


def instantaneous_axis(
    v_A: npt.ArrayLike, omega: npt.ArrayLike
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """The instantaneous axis of rotation (2.77).

    Domain: finite v_A, omega of shape (..., 3) with omega ≠ 0 (else ZeroAngularVelocityError); a
    point beyond float64 (|ω| tiny against |v|), or an axial velocity v_C beyond it (|v_A|
    near float64's limit), raises ResultOverflowError naming which.

    Parameters
    ----------
    v_A : array_like, shape (..., 3)
        Velocity of a body point A, m/s; finite.
    omega : array_like, shape (..., 3)
        The body's angular velocity ω, rad/s; finite and non-zero.

    Returns
    -------
    r_AC : ndarray, shape (..., 3)
        AC = (ω × v_A)/ω², the point C of the axis in the plane through A normal to ω.
    v_C : ndarray, shape (..., 3)
        The velocity of the axis points, v_C = (v_A · e_ω) e_ω, parallel to ω (2.80).

    Raises
    ------
    ZeroAngularVelocityError
        Where every component of ω is 0 (a translation has no axis).
    ResultOverflowError
        Where |AC| = |v_A⊥|/|ω| is beyond float64 (a finite but extremely slow spin).
    NonFiniteError
        Where ``v_A`` or ``omega`` holds NaN or an infinity.
    ShapeError
        If an input is not of shape (..., 3), is complex or not numeric, or the leading axes do
        not broadcast.

    Notes
    -----
    ω and v_A are first divided by powers of two, ω = u 2**k and v_A = s 2**j, with
    the largest component of u and of s in [1/2, 1) (exact).  Then u·u ∈ [1/4, 3)
    cannot overflow or underflow, as ω² does for |ω| beyond 1e154 or below 1e-154,
    and AC = (u × s)/(u·u) 2**(j−k), v_C = ((s·u)/(u·u)) u 2**j round as (2.77)
    and (2.80) would in the normal range, at any scale.

    Examples
    --------
    The point C moves with v_C, along the axis (2.73):

    >>> v_A, omega = [1.0, 2.0, 3.0], [0.0, 0.0, 2.0]
    >>> r_AC, v_C = instantaneous_axis(v_A, omega)
    >>> r_AC.tolist(), v_C.tolist(), point_velocity(v_A, omega, r_AC).tolist()
    ([-1.0, 0.5, 0.0], [0.0, 0.0, 3.0], [0.0, 0.0, 3.0])
    """
    v = as_float_array(v_A, "v_A", (3,))
    w = as_float_array(omega, "omega", (3,))
    zero = ~w.any(axis=-1)
    if zero.any():
        raise ZeroAngularVelocityError(
            f"omega = {w[*_first_index(zero)].tolist()} is zero: "
            "a translating body has no instantaneous axis or centre"
        )
    k, j = _exponent(w, -1), _exponent(v, -1)
    u, s = np.ldexp(w, -k), np.ldexp(v, -j)
    uu = np.einsum("...i,...i->...", u, u)[..., None]
    with np.errstate(over="ignore"):  # checked below
        r_AC = np.ldexp(np.cross(u, s) / uu, j - k)
        v_C = np.ldexp(np.einsum("...i,...i->...", s, u)[..., None] / uu * u, j)
    bad = ~(np.isfinite(r_AC).all(axis=-1) & np.isfinite(v_C).all(axis=-1))
    if bad.any():
        idx = _first_index(bad)
        vb, wb = np.broadcast_arrays(v, w)
        what = (
            "|AC| = |v_A x omega|/omega^2"
            if not np.isfinite(r_AC[idx]).all()
            else "|v_C| = |v_A . omega| |omega|/omega^2"
        )
        raise ResultOverflowError(
            f"the instantaneous axis of v_A = {vb[idx].tolist()}, omega = {wb[idx].tolist()} "
            f"(index {idx}) is beyond float64: {what} exceeds 1.8e308"
        )
    return r_AC, v_C


instantaneous_axis = finite_result(instantaneous_axis)


def _minus_ratio(
    a: npt.NDArray[np.float64], b: npt.NDArray[np.float64], c: npt.NDArray[np.float64]
) -> npt.NDArray[np.float64]:
    """a − b/c, inf only where the exact value is beyond float64 (c ≠ 0).

    b/c alone overflows for |b/c| > 1.8e308 even where a cancels most of it, and
    underflows where it is tiny.  So b/c = q 2**m with q = mant(b)/mant(c) in
    (1/2, 2), and both terms are brought to a common exponent e that leaves them
    below 1 (exact, save for parts below 2**−1074 of the larger term).  In the
    normal range this rounds exactly as a − b/c.  A zero term has no exponent (frexp
    gives 0): it takes the other term's, so that the other is not scaled away.
    """
    mb, kb = np.frexp(b)
    mc, kc = np.frexp(c)
    q, m = mb / mc, kb - kc
    ka = np.frexp(a)[1]
    e = np.maximum(np.where(a == 0, m, ka), np.where(b == 0, ka, m)) + 1
    with np.errstate(over="ignore"):  # the caller checks
        out: npt.NDArray[np.float64] = np.ldexp(np.ldexp(a, -e) - np.ldexp(q, m - e), e)
        return out


def instantaneous_centre_plane(
    r_A: npt.ArrayLike, v_A: npt.ArrayLike, omega_z: npt.ArrayLike
) -> npt.NDArray[np.float64]:
    """Instantaneous centre of zero velocity in plane motion (2.95).

    Domain: finite r_A, v_A of shape (..., 2) and omega_z ≠ 0 (else ZeroAngularVelocityError); a
    centre beyond float64 raises ResultOverflowError.

    x_C = x_A − ẏ_A/ω, y_C = y_A + ẋ_A/ω, for ω = ω e_z (the text's dots on
    ẋ_A, ẏ_A are lost in the extraction; (2.77) fixes them).

    Parameters
    ----------
    r_A, v_A : array_like, shape (..., 2)
        Position (m) and velocity (m/s) of a body point A in the plane.
    omega_z : array_like, shape (...)
        The angular velocity about e_z, rad/s; must be non-zero.

    Returns
    -------
    ndarray, shape (..., 2)
        The position (x_C, y_C) of the instantaneous centre C, m.

    Raises
    ------
    ZeroAngularVelocityError
        Where ω = 0.
    ResultOverflowError
        Where a coordinate of C is beyond float64; the quotients v/ω are formed
        so that they do not overflow on their own where x_A cancels them.
    NonFiniteError
        Where an input holds NaN or an infinity.
    ShapeError
        If ``r_A`` or ``v_A`` is not of shape (..., 2), an input is complex or not numeric, or the
        leading axes do not broadcast.

    Examples
    --------
    C is at rest: v_A + ω × AC = 0 (2.73):

    >>> r_C = instantaneous_centre_plane([1.0, 2.0], [2.0, 4.0], 2.0)
    >>> AC = np.append(r_C - [1.0, 2.0], 0.0)
    >>> r_C.tolist(), point_velocity([2.0, 4.0, 0.0], [0.0, 0.0, 2.0], AC).tolist()
    ([-1.0, 3.0], [0.0, 0.0, 0.0])
    """
    r = as_float_array(r_A, "r_A", (2,))
    v = as_float_array(v_A, "v_A", (2,))
    w = as_float_array(omega_z, "omega_z")
    if (w == 0).any():
        raise ZeroAngularVelocityError(
            "omega_z = 0: a translating body has no instantaneous centre"
        )
    r_C = np.stack(
        [_minus_ratio(r[..., 0], v[..., 1], w), _minus_ratio(r[..., 1], -v[..., 0], w)], axis=-1
    )
    bad = ~np.isfinite(r_C).all(axis=-1)
    if bad.any():
        idx = _first_index(bad)
        rb, vb, wb = np.broadcast_arrays(r, v, w[..., None])
        raise ResultOverflowError(
            f"the instantaneous centre of r_A = {rb[idx].tolist()}, v_A = {vb[idx].tolist()}, "
            f"omega_z = {float(wb[idx][0])!r} (index {idx}) is beyond float64: "
            "|r_A + e_z x v_A/omega_z| exceeds 1.8e308"
        )
    return r_C


instantaneous_centre_plane = finite_result(instantaneous_centre_plane)


def _centred(
    X: npt.NDArray[np.float64],
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.intc]]:
    """(mean, D, k) of points X (..., N, 3): X − mean = D 2**k, max |D| in [1/2, 1).

    Scale-free at any magnitude.  A sum of N numbers below 2**(1023 − g), g =
    ceil(log2 N) + 1, cannot overflow, so only point sets with a larger entry are
    divided by 2**g before averaging (exact, save for parts below 2**−1074 of
    the largest entry); the offsets are then scaled to order 1, so that their
    squares neither underflow (1e-170) nor overflow (1e160).
    """
    g = int(np.ceil(np.log2(X.shape[-2]))) + 1
    shift = np.where(_exponent(X, (-2, -1)) > 1023 - g, g, 0)
    Xs = np.ldexp(X, -shift)
    mean = Xs.mean(axis=-2, keepdims=True)
    offsets = Xs - mean
    k = _exponent(offsets, (-2, -1))
    return np.ldexp(mean, shift)[..., 0, :], np.ldexp(offsets, -k), k + shift


def rigid_velocity_from_points(
    r: npt.ArrayLike, v: npt.ArrayLike
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """ω and the velocity of the centroid from positions and velocities of N ≥ 3 points.

    Domain: finite r, v of one shape (..., N, 3), N ≥ 3 points not collinear (the spread matrix's
    eigenvalue ratio > ``COLLINEAR_RTOL``, else CollinearPointsError); offsets and velocities of any
    magnitude (each is scaled by a power of two).

    Solves v_i = u + ω × (r_i − c) in the least-squares sense, c the centroid,
    from the connection formula (2.74).

    Parameters
    ----------
    r, v : array_like, shape (..., N, 3)
        Positions and velocities of the points.

    Returns
    -------
    omega : ndarray, shape (..., 3)
    v_c : ndarray, shape (..., 3)
        Velocity of the body point at the centroid c; v_P = v_c + ω × (r_P − c).
    residual : ndarray, shape (...)
        Rigidity residual max_i |v_i − v_c − ω × (r_i − c)|: zero for exact rigid
        data; a large value means the data are not a rigid motion.

    Raises
    ------
    CollinearPointsError
        When fewer than three points, or (nearly) collinear ones, leave the
        rotation about their common line undetermined.
    ResultOverflowError
        When ω is beyond float64 (velocity spread / position spread > 1.8e308).

    Notes
    -----
    With d_i = r_i − c one has Σ d_i = 0, so u = mean(v) and
    ω = J⁻¹ Σ d_i × (v_i − u), J = Σ (|d_i|² 1 − d_i d_iᵀ), the "inertia tensor"
    of unit masses; J is singular exactly when the points are collinear.  The
    offsets and relative velocities are scaled to order 1 by powers of two
    first, so the result is scale invariant: J neither underflows (a false
    "collinear" at 1e-170) nor overflows (1e160).

    Examples
    --------
    Example 2.3 of the book (ℓ = v = 1): ω = (1, 0, −1).

    >>> r = [[0, 0, 1], [0, 2, 0], [1, 0, 1]]
    >>> v = [[1, 1, -3], [3, 2, -1], [1, 0, -3]]
    >>> omega, v_c, res = rigid_velocity_from_points(r, v)
    >>> omega.round(12).tolist(), float(res) < 1e-14
    ([1.0, 0.0, -1.0], True)
    """
    R = as_float_array(r, "r", (3,))
    V = as_float_array(v, "v", (3,))
    if R.ndim < 2 or V.shape != R.shape:
        raise ShapeError(f"r and v must both have shape (..., N, 3); got {R.shape} and {V.shape}")
    n = R.shape[-2]
    if n < 3:
        raise CollinearPointsError(
            f"{n} point(s) given; at least 3 non-collinear points are needed"
        )
    # Offsets d_i = d'_i 2**k and velocities v_i − u = w'_i 2**m, each scaled to
    # order 1 (see _centred): J' = J 2**−2k, b' = b 2**−(k+m) and the eigenvalue
    # ratio are scale-free, and ω = J'⁻¹ b' 2**(m−k).
    _, d, k = _centred(R)
    u, w, m = _centred(V)
    dd = np.einsum("...ni,...ni->...", d, d)
    J = dd[..., None, None] * np.eye(3) - np.einsum("...ni,...nj->...ij", d, d)
    lam = np.linalg.eigvalsh(J)
    ratio = lam[..., 0] / np.where(lam[..., 2] > 0, lam[..., 2], 1.0)
    if (ratio <= COLLINEAR_RTOL).any():
        worst = float(np.min(ratio))
        raise CollinearPointsError(
            f"the points r are collinear (or coincide): smallest/largest eigenvalue of their "
            f"spread matrix is {worst:.3g} <= {COLLINEAR_RTOL:.3g}; the rotation about their "
            "line is undetermined"
        )
    b = np.einsum("...ni->...i", np.cross(d, w))
    omega = np.linalg.solve(J, b[..., None])[..., 0]
    misfit = w - np.cross(omega[..., None, :], d)
    residual = np.sqrt(np.einsum("...ni,...ni->...n", misfit, misfit)).max(axis=-1)
    with np.errstate(over="ignore"):  # checked below
        omega = np.ldexp(omega, (m - k)[..., 0])
        residual = np.ldexp(residual, m[..., 0, 0])
    bad = ~(np.isfinite(omega).all(axis=-1) & np.isfinite(residual))
    if bad.any():
        idx = _first_index(bad)
        raise ResultOverflowError(
            f"the angular velocity of the point set at index {idx} is beyond float64: "
            f"velocity spread 2**{int(m[idx][0, 0])} over position spread "
            f"2**{int(k[idx][0, 0])} exceeds 1.8e308"
        )
    return omega, u, residual


rigid_velocity_from_points = finite_result(rigid_velocity_from_points)
