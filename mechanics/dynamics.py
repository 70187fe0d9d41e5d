"""Rigid-body dynamics: angular momentum, Euler's equations, fixed-axis rotation, pendulum.

Conventions (Essén 1996, ch. 4)
-------------------------------
- **Points and bases as in** :mod:`mechanics.inertia`: ``J`` is the inertia
  tensor about the base point (the centre of mass G or a fixed point C of the
  body) in some basis, and ``omega`` has its components in the same basis;
  L = J ω (4.6), (4.12).
- **Euler's equations** (4.47) are in the principal body basis A:
  ``J_principal`` = (J1, J2, J3) are the principal moments (any order, not
  only ascending), ``omega`` and ``M`` the body components of ω and of the
  moment about G or C.
- **Fixed-axis rotation** (4.3): the axis is the body's z-axis, the rotation
  angle is φ (the book's ϕ), positive counter-clockwise about e_z.  For the
  physical pendulum φ is measured from the downward vertical, ``h`` is the
  distance from the axis to G (the book's h) and ``J_axis`` the moment of
  inertia about the axis (the book's J_z).  The reduced length is ℓ = J_z/(m h)
  (4.49).  Energy (4.74): E = ½ J_z φ̇² + m g h (1 − cos φ), zero at rest at the
  bottom.
- **Elliptic functions**: parameter m = k² (as mpmath and scipy write it) and
  complementary parameter m1 = k'² = 1 − m, always computed without
  cancellation and passed as such near m = 1 (scipy's ``ellipkm1``).  For the
  pendulum released from rest at φ0, k = sin(φ0/2) and k' = cos(φ0/2).
- Reactions: ``axis_reaction`` in the polar components (ρ, φ) of the book's
  (4.70)–(4.77), e_ρ from the axis toward G; ``bearing_reactions`` in body
  axes (x, y, z) with the bearing O at the origin and A at z = z_A (4.78)–(4.85).
- Everything float64, vectorised over leading axes.

Accuracy
--------
Measured against mpmath at 50 digits in ``tests/stability/test_inertia_stability.py``
(explore profile).  ``pendulum_period`` is within 4 eps, relative, for every
amplitude from 0 to fl(π) (measured worst 1.2 eps); the complementary parameter
cos²(φ0/2) is formed from π − φ0 carried to 2·53 bits, so amplitudes within
1e-15 of π keep their digits.  ``pendulum_motion`` evaluates
tan(φ/2) = k cn(ω0 t)/k' with :func:`mechanics.elliptic.ellipj` (given k'²
directly): within 8 eps·(|φ| + |t φ̇|), the change of φ when t is rounded
(measured worst 1.05), near the separatrix too.  The amplitude argument is
named ``theta_0`` (φ0 above).
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt
from scipy import special

from ._validate import as_float_array, broadcast_checked, finite_result
from .errors import (
    NonPhysicalInertiaError,
    NonPositiveParameterError,
    OutOfDomainError,
    ResultOverflowError,
    UnknownOptionError,
)
from .inertia import check_inertia
from .rotation import EPS

__all__ = [
    "angular_momentum_rigid",
    "axis_reaction",
    "bearing_reactions",
    "euler_equations_rhs",
    "fixed_axis_angular_acceleration",
    "pendulum_angular_velocity_at",
    "pendulum_axis_reaction",
    "pendulum_motion",
    "pendulum_period",
    "pendulum_small_period",
    "reduced_length",
    "rotational_kinetic_energy",
]

_PI_HI = math.pi
_PI_LO = 1.2246467991473532e-16  # π − fl(π), so π = _PI_HI + _PI_LO to 2·53 bits


# ------------------------------------------------------------------- validation


def _finite(out: npt.NDArray[np.float64], what: str) -> npt.NDArray[np.float64]:
    if not np.isfinite(out).all():
        raise ResultOverflowError(
            f"{what} overflows float64 (finite inputs, result beyond 1.8e308)"
        )
    return out


def _positive(x: npt.ArrayLike, name: str) -> npt.NDArray[np.float64]:
    a = as_float_array(x, name)
    bad = ~(a > 0)
    if bad.any():
        raise NonPositiveParameterError(f"{name} must be > 0; found {float(a[bad].flat[0])!r}")
    return a


def _principal_moments(J_principal: npt.ArrayLike) -> npt.NDArray[np.float64]:
    J = as_float_array(J_principal, "J_principal", (3,))
    bad = ~(J > 0)
    if bad.any():
        raise NonPositiveParameterError(
            f"J_principal must be > 0 (each principal moment; a moment 0 makes d omega/dt "
            f"undefined in Euler's equations); found {float(J[bad].flat[0])!r}"
        )
    # J_j + J_k − J_i for each i, of the moments over 4 where they near float64's limit (a
    # power of two: exact), so that neither the sum nor 2 J_i overflows
    scale = np.where(J.max(axis=-1, keepdims=True) > 2.0**1020, 0.25, 1.0)
    Js = J * scale
    slack = Js.sum(axis=-1, keepdims=True) - 2.0 * Js
    bad = slack < -64 * EPS * Js.max(axis=-1, keepdims=True)
    if bad.any():
        idx = tuple(int(i) for i in np.argwhere(bad)[0])
        value = float(slack[idx]) / float(scale[(*idx[:-1], 0)])
        raise NonPhysicalInertiaError(
            f"J_principal breaks the triangle inequality: {J[idx[:-1]].tolist()} has "
            f"J_j + J_k - J_i = {value:.6g} < 0 for i = {idx[-1] + 1}"
        )
    return J


# ----------------------------------------------------------- angular momentum


def angular_momentum_rigid(
    J: npt.ArrayLike, omega: npt.ArrayLike, *, allow_singular: bool = True
) -> npt.NDArray[np.float64]:
    """L = J ω (4.6), (4.12): about the point ``J`` refers to (G or a fixed point C).

    Domain: ``J`` (..., 3, 3) a physical inertia tensor as :func:`~mechanics.inertia.check_inertia`
    (symmetric, positive semidefinite, J1 + J2 ≥ J3; else NonPhysicalInertiaError;
    ``allow_singular=False`` also refuses a zero moment), ``omega`` any finite (..., 3); a result
    beyond float64 raises ResultOverflowError.  Moments up to float64's limit (near 1e308) are
    checked without overflow.  Batches that do not broadcast (2 against 3) raise ShapeError listing
    each argument's shape.

    Parameters
    ----------
    J : array_like, shape (..., 3, 3)
        Inertia tensor about G or a fixed point C (kg m²; validated by
        :func:`~mechanics.inertia.check_inertia`; a thin rod is accepted).
    omega : array_like, shape (..., 3)
        Angular velocity (rad/s), components in the basis of ``J``.
    allow_singular : bool
        Accept a tensor with a zero smallest moment (a line mass or a point; default
        True); False refuses it with NonPhysicalInertiaError.

    Returns
    -------
    L : ndarray, shape (..., 3)
        The angular momentum J ω (kg m²/s) about the point ``J`` refers to, in the basis
        of ``J``.

    Raises
    ------
    NonPhysicalInertiaError
        ``J`` refused by :func:`~mechanics.inertia.check_inertia` (not symmetric, not
        positive semidefinite, J1 + J2 < J3; a zero moment with ``allow_singular=False``).
    NonFiniteError
        A NaN or infinite entry of ``J`` or ``omega``.
    ShapeError
        ``J`` not ending in (3, 3), ``omega`` not ending in 3, batch axes that do not
        broadcast (the message lists each argument's shape), or an input that is not an
        array of real numbers.
    ResultOverflowError
        A component of L beyond float64.

    Examples
    --------
    The sum over particles (4.1), L = Σ r × m (ω × r), equals J ω:

    >>> from mechanics.inertia import inertia_tensor
    >>> m, r = np.array([1.0, 2.0]), np.array([[1.0, 0.0, 0.5], [-0.5, 0.0, -0.25]])
    >>> w = np.array([0.1, 0.2, 0.3])
    >>> L_sum = sum(mk * np.cross(rk, np.cross(w, rk)) for mk, rk in zip(m, r))
    >>> L = angular_momentum_rigid(inertia_tensor(m, r, about=[0.0, 0.0, 0.0]), w)
    >>> bool(np.allclose(L, L_sum, rtol=0, atol=1e-16))
    True
    """
    Jc = check_inertia(J, allow_singular=allow_singular, about_centre_of_mass=False)
    w = as_float_array(omega, "omega", (3,))
    with np.errstate(over="ignore", invalid="ignore"):
        return _finite(np.einsum("...ij,...j->...i", Jc, w), "L = J omega")


angular_momentum_rigid = broadcast_checked(angular_momentum_rigid)


def rotational_kinetic_energy(
    J: npt.ArrayLike, omega: npt.ArrayLike, *, allow_singular: bool = True
) -> npt.NDArray[np.float64]:
    """T = ½ ωᵀ J ω (3.15), (4.32), about G (plus ½ m v_G² for the total) or a fixed point.

    Domain: as :func:`angular_momentum_rigid`: ``J`` physical (check_inertia, else
    NonPhysicalInertiaError), ``omega`` finite (..., 3); a T beyond float64 raises
    ResultOverflowError; moments up to float64's limit are checked without overflow; batches that
    do not broadcast (2 against 3) raise ShapeError listing each argument's shape.

    Parameters
    ----------
    J : array_like, shape (..., 3, 3)
        Inertia tensor about G or a fixed point (kg m²; validated by
        :func:`~mechanics.inertia.check_inertia`; a thin rod is accepted).
    omega : array_like, shape (..., 3)
        Angular velocity (rad/s), components in the basis of ``J``.
    allow_singular : bool
        Accept a tensor with a zero smallest moment (default True); False refuses it
        with NonPhysicalInertiaError.

    Returns
    -------
    T : ndarray, shape (...)
        The rotational kinetic energy ½ ωᵀ J ω (J), ≥ 0.

    Raises
    ------
    NonPhysicalInertiaError
        ``J`` refused by :func:`~mechanics.inertia.check_inertia` (not symmetric, not
        positive semidefinite, J1 + J2 < J3; a zero moment with ``allow_singular=False``).
    NonFiniteError
        A NaN or infinite entry of ``J`` or ``omega``.
    ShapeError
        ``J`` not ending in (3, 3), ``omega`` not ending in 3, batch axes that do not
        broadcast (the message lists each argument's shape), or an input that is not an
        array of real numbers.
    ResultOverflowError
        A T beyond float64.

    Examples
    --------
    In the principal basis T = ½ (J1 ω1² + J2 ω2² + J3 ω3²) (4.32), and T = ½ ω·L:

    >>> J, w = np.diag([1.0, 2.0, 3.0]), [1.0, 1.0, 2.0]
    >>> float(rotational_kinetic_energy(J, w)), float(0.5 * np.dot(w, angular_momentum_rigid(J, w)))
    (7.5, 7.5)
    """
    Jc = check_inertia(J, allow_singular=allow_singular, about_centre_of_mass=False)
    w = as_float_array(omega, "omega", (3,))
    with np.errstate(over="ignore", invalid="ignore"):
        return _finite(0.5 * np.einsum("...i,...ij,...j->...", w, Jc, w), "T")


rotational_kinetic_energy = broadcast_checked(rotational_kinetic_energy)


def _euler_component(
    M: npt.NDArray[np.float64],
    d: npt.NDArray[np.float64],
    a: npt.NDArray[np.float64],
    b: npt.NDArray[np.float64],
    J: npt.NDArray[np.float64],
) -> npt.NDArray[np.float64]:
    """(M − d a b)/J with the powers of two carried apart: inf only where the exact value
    is beyond float64.

    d (a b) = p 2**e with p = f_d (f_a f_b) of the mantissas (the plain product's roundings);
    M and p 2**e are brought to one exponent E that leaves both below 1/2 (exact, save for
    parts below 2**-1074 of the larger), their difference divided by J's mantissa and
    scaled once.  The same bits as the plain (M − (J_k − J_j)(ω_j ω_k))/J_i wherever that
    neither under- nor overflows; unlike it, subnormal moments keep their digits (J =
    (3, 5, 7) 2**-1074, ω = 0.3 (1, 1, 1) gave 0, not −0.06) and d a b beyond float64 is
    no overflow where J brings it back (or where d = 0: 0 · inf was NaN).
    """
    fd, ed = np.frexp(d)
    fa, ea = np.frexp(a)
    fb, eb = np.frexp(b)
    fM, eM = np.frexp(M)
    fJ, eJ = np.frexp(J)
    p, e = fd * (fa * fb), ed + ea + eb
    # a zero term has no exponent (frexp gives 0): it takes the other's
    E = np.maximum(np.where(M == 0, e, eM), np.where(p == 0, eM, e)) + 1
    diff = np.ldexp(fM, eM - E) - np.ldexp(p, e - E)
    out: npt.NDArray[np.float64] = np.ldexp(diff / fJ, E - eJ)
    return out


def euler_equations_rhs(
    J_principal: npt.ArrayLike, omega: npt.ArrayLike, M: npt.ArrayLike
) -> npt.NDArray[np.float64]:
    """dω/dt from Euler's dynamic equations (4.47), body principal components.

    Domain: ``J_principal`` (..., 3) each > 0 (else NonPositiveParameterError naming it) and
    obeying the triangle inequality to 64 eps of the largest (else NonPhysicalInertiaError); any
    finite ``omega``, ``M`` (..., 3); a result beyond float64 raises ResultOverflowError (moments
    and rates of any magnitude, subnormal to near 1e308: (J_k − J_j) ω_j ω_k is formed with its
    powers of two apart, so it neither underflows nor overflows on the way).  Batches that do
    not broadcast raise ShapeError listing each argument's shape.

    J1 ω̇1 + (J3 − J2) ω2 ω3 = M1, and cyclically.

    Parameters
    ----------
    J_principal : array_like, shape (..., 3)
        Principal moments (J1, J2, J3) about G or a fixed point (kg m²), each > 0 and
        obeying the triangle inequality.
    omega : array_like, shape (..., 3)
        Body components of the angular velocity ω (rad/s).
    M : array_like, shape (..., 3)
        Body components of the moment M (N m) about the same point.

    Returns
    -------
    omega_dot : ndarray, shape (..., 3)
        Body components of dω/dt (rad/s²).

    Raises
    ------
    NonPositiveParameterError
        A principal moment ≤ 0.
    NonPhysicalInertiaError
        ``J_principal`` breaks J_j + J_k ≥ J_i by more than 64 eps of the largest moment.
    NonFiniteError
        A NaN or infinite input.
    ShapeError
        An input not ending in 3, batch axes that do not broadcast (the message lists each
        argument's shape), or an input that is not an array of real numbers.
    ResultOverflowError
        A component of dω/dt beyond float64.

    Examples
    --------
    Torque-free: d/dt of 2T = Σ J_i ω_i² is 2 Σ J_i ω_i ω̇_i = 0:

    >>> J, w = np.array([1.0, 2.0, 2.5]), np.array([0.3, -1.0, 0.7])
    >>> wdot = euler_equations_rhs(J, w, [0.0, 0.0, 0.0])
    >>> bool(abs(np.sum(J * w * wdot)) < 1e-15)
    True
    """
    J = _principal_moments(J_principal)
    w = as_float_array(omega, "omega", (3,))
    Mm = as_float_array(M, "M", (3,))
    # the three components at once: (M_i − (J_k − J_j) ω_j ω_k)/J_i, (i, j, k) cyclic
    j, k = [1, 2, 0], [2, 0, 1]
    with np.errstate(over="ignore", invalid="ignore"):
        out = _euler_component(Mm, J[..., k] - J[..., j], w[..., j], w[..., k], J)
    return _finite(out, "d omega/dt")


euler_equations_rhs = finite_result(euler_equations_rhs)


def fixed_axis_angular_acceleration(
    J_axis: npt.ArrayLike, M_axis: npt.ArrayLike
) -> npt.NDArray[np.float64]:
    """φ̈ = M_z / J_z for rotation about a fixed axis (the z-component of (4.42); (4.48)).

    Domain: ``J_axis`` > 0 (else NonPositiveParameterError), any finite ``M_axis``, broadcast
    together (else ShapeError listing each argument's shape).  A quotient beyond float64
    (1e300/1e-300) raises ResultOverflowError.

    Parameters
    ----------
    J_axis : array_like, shape (...)
        Moment of inertia about the axis, J_z (kg m²), > 0.
    M_axis : array_like, shape (...)
        Moment about the axis, M_z (N m), finite.

    Returns
    -------
    phiddot : ndarray, shape (...)
        The angular acceleration φ̈ (rad/s²), over the broadcast shape of the inputs.

    Raises
    ------
    NonPositiveParameterError
        ``J_axis`` has an entry ≤ 0.
    NonFiniteError
        A NaN or infinite input.
    ShapeError
        Inputs whose shapes do not broadcast (the message lists each argument's shape), or an
        input that is not an array of real numbers.
    ResultOverflowError
        A quotient beyond float64.

    Examples
    --------
    The z-component of Euler's equations (4.47) for a rotation about a principal axis:

    >>> float(fixed_axis_angular_acceleration(2.0, -3.0))
    -1.5
    >>> float(euler_equations_rhs([1.0, 1.0, 2.0], [0.0, 0.0, 5.0], [0.0, 0.0, -3.0])[2])
    -1.5

    The physical pendulum (4.48), M_z = −m g h sin φ:

    >>> float(fixed_axis_angular_acceleration(2.0, -1.0 * 9.81 * 0.5 * np.sin(0.3)))
    ... # doctest: +ELLIPSIS
    -0.72...
    """
    J = _positive(J_axis, "J_axis")
    Mz = as_float_array(M_axis, "M_axis")
    return Mz / J


fixed_axis_angular_acceleration = finite_result(fixed_axis_angular_acceleration)


# --------------------------------------------------------- the physical pendulum


def _pendulum(
    J_axis: npt.ArrayLike, m: npt.ArrayLike, g: npt.ArrayLike, h: npt.ArrayLike
) -> tuple[
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
]:
    J = _positive(J_axis, "J_axis")
    mm = _positive(m, "m")
    gg = _positive(g, "g")
    hh = _positive(h, "h")
    return J, mm, gg, hh


def _split(
    *xs: npt.NDArray[np.float64],
) -> list[tuple[npt.NDArray[np.float64], npt.NDArray[np.intc]]]:
    """Each x as (f, e) with x = f 2**e, f in [1/2, 1) (exact)."""
    return [np.frexp(x) for x in xs]


def _omega0_squared(
    J: npt.NDArray[np.float64],
    m: npt.NDArray[np.float64],
    g: npt.NDArray[np.float64],
    h: npt.NDArray[np.float64],
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.intc]]:
    """ω0² = m g h/J_z (4.51) as (q, e), ω0² = q 2**e: q = (m' g' h')/J' of the mantissas,
    the same roundings as the plain quotient, with the powers of two carried apart (exactly),
    so that no intermediate overflows or underflows (q lies in (1/8, 2))."""
    (fJ, eJ), (fm, em), (fg, eg), (fh, eh) = _split(J, m, g, h)
    return (fm * fg) * fh / fJ, em + eg + eh - eJ


def _sqrt_parts(
    q: npt.NDArray[np.float64], e: npt.NDArray[np.intc]
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.intc]]:
    """√(q 2**e) as (s, k), = s 2**k with s = √(q 2**(e mod 2)): the exponent halved exactly."""
    k, odd = np.divmod(e, 2)
    return np.sqrt(np.ldexp(q, odd)), k


def reduced_length(
    J_axis: npt.ArrayLike, m: npt.ArrayLike, h: npt.ArrayLike
) -> npt.NDArray[np.float64]:
    """The reduced length ℓ = J_z/(m h) of a physical pendulum (4.49).

    Domain: ``J_axis``, ``m``, ``h`` > 0 (else NonPositiveParameterError naming it), broadcast
    together (else ShapeError listing each argument's shape).  Any magnitudes: the powers of two
    are carried apart, so m h cannot overflow or underflow on the way; an ℓ beyond float64
    (1e300/(1e-300 · 1)) raises ResultOverflowError.

    Parameters
    ----------
    J_axis : array_like, shape (...)
        Moment of inertia about the axis, the book's J_z (kg m²), > 0.
    m : array_like, shape (...)
        Mass (kg), > 0.
    h : array_like, shape (...)
        Distance from the axis to G, the book's h (m), > 0.

    Returns
    -------
    ell : ndarray, shape (...)
        The reduced length ℓ (m), the length of the simple pendulum with the same small
        period, over the broadcast shape of the inputs.

    Raises
    ------
    NonPositiveParameterError
        ``J_axis``, ``m`` or ``h`` has an entry ≤ 0 (the message names it).
    NonFiniteError
        A NaN or infinite input.
    ShapeError
        Inputs whose shapes do not broadcast (the message lists each argument's shape), or an
        input that is not an array of real numbers.
    ResultOverflowError
        An ℓ beyond float64.

    Examples
    --------
    A rod of length l about its end (Example 4.3): ℓ = (m l²/3)/(m l/2) = 2l/3:

    >>> float(reduced_length(1.0 / 3.0, 1.0, 0.5)), 2.0 / 3.0
    (0.6666666666666666, 0.6666666666666666)
    """
    (fJ, eJ), (fm, em), (fh, eh) = _split(
        _positive(J_axis, "J_axis"), _positive(m, "m"), _positive(h, "h")
    )
    ell: npt.NDArray[np.float64] = np.ldexp(fJ / (fm * fh), eJ - em - eh)
    return ell


reduced_length = finite_result(reduced_length)


def _omega0(
    J: npt.NDArray[np.float64],
    m: npt.NDArray[np.float64],
    g: npt.NDArray[np.float64],
    h: npt.NDArray[np.float64],
) -> npt.NDArray[np.float64]:
    s, k = _sqrt_parts(*_omega0_squared(J, m, g, h))
    return np.ldexp(s, k)


def pendulum_small_period(
    J_axis: npt.ArrayLike, m: npt.ArrayLike, g: npt.ArrayLike, h: npt.ArrayLike
) -> npt.NDArray[np.float64]:
    """Small-oscillation period T_p = 2π √(J_z/(m g h)) = 2π √(ℓ/g) (4.51)–(4.52).

    Domain: ``J_axis``, ``m``, ``g``, ``h`` > 0 (else NonPositiveParameterError naming it),
    broadcast together (else ShapeError listing each argument's shape).  Any magnitudes (1e-300
    and 1e300 mixed): m g h/J_z is formed with its powers of two apart, so nothing overflows or
    underflows on the way; a period beyond float64 raises ResultOverflowError (one below the
    subnormals is 0, its rounded value).

    ``h`` is the distance from the axis to G (the book's h).

    Parameters
    ----------
    J_axis : array_like, shape (...)
        Moment of inertia about the axis, the book's J_z (kg m²), > 0.
    m : array_like, shape (...)
        Mass (kg), > 0.
    g : array_like, shape (...)
        Gravitational acceleration (m/s²), > 0.
    h : array_like, shape (...)
        Distance from the axis to G, the book's h (m), > 0.

    Returns
    -------
    T_p : ndarray, shape (...)
        The small-oscillation period (s), over the broadcast shape of the inputs.

    Raises
    ------
    NonPositiveParameterError
        ``J_axis``, ``m``, ``g`` or ``h`` has an entry ≤ 0 (the message names it).
    NonFiniteError
        A NaN or infinite input.
    ShapeError
        Inputs whose shapes do not broadcast (the message lists each argument's shape), or an
        input that is not an array of real numbers.
    ResultOverflowError
        A period beyond float64.

    Examples
    --------
    Example 4.3: a rod about its end, T = 2π √(2l/(3g)) (4.53):

    >>> l, g = 1.2, 9.81
    >>> T = pendulum_small_period(l**2 / 3.0, 1.0, g, l / 2.0)
    >>> bool(np.isclose(T, 2 * np.pi * np.sqrt(2 * l / (3 * g)), rtol=4e-16, atol=0))
    True
    """
    J, mm, gg, hh = _pendulum(J_axis, m, g, h)
    s, k = _sqrt_parts(*_omega0_squared(J, mm, gg, hh))
    return np.ldexp(2.0 * np.pi / s, -k)


pendulum_small_period = finite_result(pendulum_small_period)


def _half_angle_sin_cos(
    theta_0: npt.NDArray[np.float64],
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """k = sin(|θ0|/2) and k' = cos(|θ0|/2), k' from π − |θ0| without cancellation."""
    a = np.abs(theta_0)
    k = np.sin(0.5 * a)
    # π − a exactly as (π_hi − a) + π_lo; π_hi − a is exact for a in [π/2, π] (Sterbenz).
    delta = (_PI_HI - a) + _PI_LO
    kp = np.where(a > 0.5 * _PI_HI, np.sin(0.5 * delta), np.cos(0.5 * a))
    return k, kp


def _amplitude(theta_0: npt.ArrayLike) -> npt.NDArray[np.float64]:
    t0 = as_float_array(theta_0, "theta_0")
    bad = np.abs(t0) > _PI_HI
    if bad.any():
        raise OutOfDomainError(
            f"theta_0 = {float(t0[bad].flat[0])!r} is beyond pi: a pendulum released from "
            "rest oscillates with amplitude |theta_0| <= pi"
        )
    return t0


def pendulum_period(
    J_axis: npt.ArrayLike,
    m: npt.ArrayLike,
    g: npt.ArrayLike,
    h: npt.ArrayLike,
    theta_0: npt.ArrayLike,
) -> npt.NDArray[np.float64]:
    """Exact period T = 4 K(k²)/ω0 of a physical pendulum with amplitude θ0 (from (4.50)).

    Domain: as :func:`pendulum_small_period` for ``J_axis``, ``m``, ``g``, ``h`` (> 0, else
    NonPositiveParameterError; any magnitudes, a period beyond float64 raising
    ResultOverflowError), and ``theta_0`` in [−π, π] (else OutOfDomainError); |θ0| = fl(π) gives a
    finite period.

    k = sin(θ0/2), ω0 = √(m g h/J_z) (4.51).  K is evaluated as
    ``scipy.special.ellipkm1(k'²)`` with the complementary parameter
    k'² = cos²(θ0/2) formed from π − θ0 without cancellation, so the period
    stays accurate as θ0 → π (it grows like (4/ω0) ln(8/(π − θ0))).

    Parameters
    ----------
    J_axis : array_like, shape (...)
        Moment of inertia about the axis, the book's J_z (kg m²), > 0.
    m : array_like, shape (...)
        Mass (kg), > 0.
    g : array_like, shape (...)
        Gravitational acceleration (m/s²), > 0.
    h : array_like, shape (...)
        Distance from the axis to G, the book's h (m), > 0.
    theta_0 : array_like, shape (...)
        Amplitude θ0, the angle of release from rest (rad), in [−π, π]; |θ0| = fl(π) is
        allowed and gives a finite period.

    Returns
    -------
    T : ndarray, shape (...)
        The period (s), over the broadcast shape of the inputs; finite for |θ0| ≤ fl(π).

    Raises
    ------
    NonPositiveParameterError
        ``J_axis``, ``m``, ``g`` or ``h`` has an entry ≤ 0 (the message names it).
    OutOfDomainError
        |θ0| > π (``theta_0`` beyond π: no oscillation from rest).
    NonFiniteError
        A NaN or infinite input.
    ShapeError
        Inputs whose shapes do not broadcast (the message lists each argument's shape), or an
        input that is not an array of real numbers.
    ResultOverflowError
        A period beyond float64.

    Examples
    --------
    The small-amplitude limit is (4.52), and T(θ0) = T0 (1 + θ0²/16 + ...):

    >>> T0 = pendulum_small_period(1.0, 1.0, 1.0, 1.0)
    >>> T = pendulum_period(1.0, 1.0, 1.0, 1.0, 1e-3)
    >>> bool(np.isclose(T, T0 * (1 + 1e-6 / 16), rtol=1e-13, atol=0))
    True
    """
    J, mm, gg, hh = _pendulum(J_axis, m, g, h)
    t0 = _amplitude(theta_0)
    _, kp = _half_angle_sin_cos(t0)
    K = special.ellipkm1(kp * kp)
    s, k = _sqrt_parts(*_omega0_squared(J, mm, gg, hh))
    T: npt.NDArray[np.float64] = np.ldexp(4.0 * K / s, -k)  # K: scipy ships no types
    return T


pendulum_period = finite_result(pendulum_period)


def pendulum_motion(
    t: npt.ArrayLike,
    J_axis: npt.ArrayLike,
    m: npt.ArrayLike,
    g: npt.ArrayLike,
    h: npt.ArrayLike,
    theta_0: npt.ArrayLike,
) -> npt.NDArray[np.float64]:
    """Exact angle φ(t) of a physical pendulum released from rest at φ(0) = θ0 (4.50).

    Domain: ``J_axis``, ``m``, ``g``, ``h``, ``theta_0`` as :func:`pendulum_period` (> 0, else
    NonPositiveParameterError; |θ0| ≤ π, else OutOfDomainError) and any finite ``t``, all broadcast
    together (else ShapeError listing each argument's shape).  ω0 is formed without intermediate
    overflow (as in :func:`pendulum_small_period`); a phase ω0 t beyond float64 raises
    ResultOverflowError.  The error grows like eps·|ω0 t|.

    sin(φ/2) = k cd(ω0 t | k²), k = sin(θ0/2), written without the arcsine as
    tan(φ/2) = k cn(ω0 t | k²)/k' (since dn² − k² cn² = k'²), with
    :func:`mechanics.elliptic.ellipj` given the complementary parameter
    k'² = cos²(θ0/2) computed without cancellation.

    Parameters
    ----------
    t : array_like, shape (...)
        Times since the release (s), any sign, finite, broadcast against the parameters.
    J_axis : array_like, shape (...)
        Moment of inertia about the axis, the book's J_z (kg m²), > 0.
    m : array_like, shape (...)
        Mass (kg), > 0.
    g : array_like, shape (...)
        Gravitational acceleration (m/s²), > 0.
    h : array_like, shape (...)
        Distance from the axis to G, the book's h (m), > 0.
    theta_0 : array_like, shape (...)
        Amplitude θ0, the angle of release from rest (rad), in [−π, π] (|θ0| = fl(π)
        allowed).

    Returns
    -------
    phi : ndarray, shape (...)
        φ(t) (rad) in [−|θ0|, |θ0|], over the broadcast shape of the inputs.  The error
        is that of cn (see :mod:`mechanics.elliptic`): relative to the change of φ when
        ω0 t is rounded, so it grows like eps·|ω0 t|·|φ̇| at long times.

    Raises
    ------
    NonPositiveParameterError
        ``J_axis``, ``m``, ``g`` or ``h`` has an entry ≤ 0 (the message names it).
    OutOfDomainError
        |θ0| > π (``theta_0`` beyond π: no oscillation from rest).
    NonFiniteError
        A NaN or infinite input.
    ShapeError
        Inputs whose shapes do not broadcast (the message lists each argument's shape;
        where ``theta_0`` alone fails to broadcast against the others, the error comes from
        :func:`mechanics.elliptic.ellipj` and lists its arguments u, m, m1 instead), or an
        input that is not an array of real numbers.
    ResultOverflowError
        The phase ω0 t beyond float64.

    Examples
    --------
    A quarter period after release the pendulum passes the bottom, and half a
    period later it is at −θ0:

    >>> T = pendulum_period(1.0, 1.0, 9.81, 1.0, 2.0)
    >>> phi = pendulum_motion(np.array([0.25, 0.5]) * T, 1.0, 1.0, 9.81, 1.0, 2.0)
    >>> bool(abs(phi[0]) < 1e-14 and abs(phi[1] + 2.0) < 1e-14)
    True
    """
    J, mm, gg, hh = _pendulum(J_axis, m, g, h)
    t0 = _amplitude(theta_0)
    tt = as_float_array(t, "t")
    from .elliptic import ellipj  # lazy: keeps ``import mechanics.dynamics`` light

    k, kp = _half_angle_sin_cos(t0)
    with np.errstate(over="ignore"):
        u = _omega0(J, mm, gg, hh) * tt
    if not np.isfinite(u).all():
        raise ResultOverflowError(
            "pendulum_motion: the phase omega0 t = sqrt(m g h/J_axis) t exceeds float64's range "
            "(~1.8e308); rescale the inputs (choose units)"
        )
    _, cn, _, _ = ellipj(u, k * k, m1=kp * kp)
    phi = 2.0 * np.arctan2(k * cn, kp)
    phi_t: npt.NDArray[np.float64] = np.where(t0 < 0, -phi, phi)
    return phi_t


pendulum_motion = finite_result(pendulum_motion)


def pendulum_angular_velocity_at(
    theta: npt.ArrayLike,
    J_axis: npt.ArrayLike,
    m: npt.ArrayLike,
    g: npt.ArrayLike,
    h: npt.ArrayLike,
    theta_0: npt.ArrayLike,
) -> npt.NDArray[np.float64]:
    """|φ̇| at angle φ = ``theta`` for a pendulum released from rest at θ0, by energy (4.57).

    Domain: as :func:`pendulum_period` (> 0, else NonPositiveParameterError; |θ0| ≤ π, else
    OutOfDomainError), with a finite ``theta`` of |θ| ≤ |θ0| (else OutOfDomainError).  Any
    magnitudes: 4 m g h/J_z is formed with its powers of two apart, so nothing overflows on the
    way; a |φ̇| beyond float64 raises ResultOverflowError.  Batches that do not broadcast (2
    against 3) raise ShapeError listing each argument's shape.

    φ̇² = (2 m g h/J_z)(cos φ − cos θ0) = (4 m g h/J_z)(s0² − s²), with
    s = sin(|φ|/2), s0 = sin(|θ0|/2), and s0² − s² = sin((|θ0| − |φ|)/2) sin((|θ0| + |φ|)/2):
    the difference of cosines without cancellation, also near the turning point φ → θ0
    (where (s0 − s)(s0 + s) of the rounded sines lost its digits: 3e8 eps at
    |θ0| − |φ| = 2⁻³⁰).  The sign of φ̇ is not determined by the energy; the
    magnitude is returned.

    Parameters
    ----------
    theta : array_like, shape (...)
        The angle φ (rad) where |φ̇| is wanted, finite, |φ| ≤ |θ0|.
    J_axis : array_like, shape (...)
        Moment of inertia about the axis, the book's J_z (kg m²), > 0.
    m : array_like, shape (...)
        Mass (kg), > 0.
    g : array_like, shape (...)
        Gravitational acceleration (m/s²), > 0.
    h : array_like, shape (...)
        Distance from the axis to G, the book's h (m), > 0.
    theta_0 : array_like, shape (...)
        Amplitude θ0, the angle of release from rest (rad), in [−π, π] (|θ0| = fl(π)
        allowed).

    Returns
    -------
    phidot : ndarray, shape (...)
        |φ̇| (rad/s), ≥ 0, over the broadcast shape of the inputs.

    Raises
    ------
    NonPositiveParameterError
        ``J_axis``, ``m``, ``g`` or ``h`` has an entry ≤ 0 (the message names it).
    OutOfDomainError
        If |φ| > |θ0| (the pendulum never gets there), or |θ0| > π.
    NonFiniteError
        A NaN or infinite input.
    ShapeError
        Inputs whose shapes do not broadcast (the message lists each argument's shape), or an
        input that is not an array of real numbers.
    ResultOverflowError
        A |φ̇| beyond float64.

    Examples
    --------
    Example 4.4: a rod of length l released horizontally passes the vertical
    with φ̇ = √(3g/l) (4.59):

    >>> l, g = 0.8, 9.81
    >>> w = pendulum_angular_velocity_at(0.0, l**2 / 3, 1.0, g, l / 2, np.pi / 2)
    >>> bool(np.isclose(w, np.sqrt(3 * g / l), rtol=4e-16, atol=0))
    True
    """
    J, mm, gg, hh = _pendulum(J_axis, m, g, h)
    t0 = _amplitude(theta_0)
    th = as_float_array(theta, "theta")
    bad = np.abs(th) > np.abs(t0)
    if bad.any():
        i = tuple(int(j) for j in np.argwhere(bad)[0]) if bad.ndim else ()
        raise OutOfDomainError(
            f"theta = {float(np.broadcast_to(th, bad.shape)[i])!r} lies beyond the amplitude "
            f"|theta_0| = {float(np.abs(np.broadcast_to(t0, bad.shape)[i]))!r}"
        )
    a, a0 = np.abs(th), np.abs(t0)
    # s0² − s² = sin((|θ0| − |φ|)/2) sin((|θ0| + |φ|)/2): |θ0| − |φ| is exact near the
    # turning point (Sterbenz), where (s0 − s) of the rounded sines lost its digits
    diff = np.sin(0.5 * (a0 - a)) * np.sin(0.5 * (a0 + a))
    q, e = _omega0_squared(J, mm, gg, hh)
    r, k = _sqrt_parts((4.0 * q) * np.maximum(diff, 0.0), e)
    return np.ldexp(r, k)


pendulum_angular_velocity_at = finite_result(pendulum_angular_velocity_at)


# ---------------------------------------------------------------------- reactions


def axis_reaction(
    m: npt.ArrayLike,
    h: npt.ArrayLike,
    phidot: npt.ArrayLike,
    phiddot: npt.ArrayLike,
    *,
    F_a_rho: npt.ArrayLike,
    F_a_phi: npt.ArrayLike,
) -> npt.NDArray[np.float64]:
    """Reaction R from a fixed axis, polar components (R_ρ, R_φ) (4.70)–(4.71).

    Domain: ``m`` > 0, ``h`` ≥ 0 (else NonPositiveParameterError), any finite ``phidot``,
    ``phiddot``, ``F_a_rho``, ``F_a_phi``, broadcast together (else ShapeError listing each
    argument's shape).  A result beyond float64 (m h φ̇² with ``phidot`` near 1e300) raises
    ResultOverflowError.

    R_ρ = −m h φ̇² − F^a_ρ,  R_φ = m h φ̈ − F^a_φ: the momentum principle (4.66)
    with the acceleration of G on its circle of radius h (4.70).

    Parameters
    ----------
    m : array_like, shape (...)
        Mass (kg), > 0.
    h : array_like, shape (...)
        Distance from the axis to G (m), >= 0.
    phidot : array_like, shape (...)
        Angular velocity φ̇ (rad/s), finite.
    phiddot : array_like, shape (...)
        Angular acceleration φ̈ (rad/s²), finite.
    F_a_rho : array_like, shape (...)
        Radial component F^a_ρ of the applied force (N), e_ρ from the axis toward G.
    F_a_phi : array_like, shape (...)
        Azimuthal component F^a_φ of the applied force (N).

    Returns
    -------
    ndarray, shape (..., 2)
        (R_ρ, R_φ) (N), the force of the axis on the body; the leading shape is the
        broadcast shape of the inputs.

    Raises
    ------
    NonPositiveParameterError
        ``m`` has an entry ≤ 0, or ``h`` an entry < 0 (the message names it).
    NonFiniteError
        A NaN or infinite input.
    ShapeError
        Inputs whose shapes do not broadcast (the message lists each argument's shape), or an
        input that is not an array of real numbers.
    ResultOverflowError
        A component beyond float64 (m h φ̇² with ``phidot`` near 1e300).

    Examples
    --------
    At rest at the bottom the axis carries the weight: R_ρ = −m g
    (gravity along +e_ρ there):

    >>> axis_reaction(2.0, 0.5, 0.0, 0.0, F_a_rho=2.0 * 9.81, F_a_phi=0.0).tolist()
    [-19.62, 0.0]
    """
    mm = _positive(m, "m")
    hh = as_float_array(h, "h")
    if (hh < 0).any():
        raise NonPositiveParameterError(f"h must be >= 0; found {float(hh[hh < 0].flat[0])!r}")
    w = as_float_array(phidot, "phidot")
    a = as_float_array(phiddot, "phiddot")
    Fr = as_float_array(F_a_rho, "F_a_rho")
    Fp = as_float_array(F_a_phi, "F_a_phi")
    return np.stack(np.broadcast_arrays(-mm * hh * w * w - Fr, mm * hh * a - Fp), axis=-1)


axis_reaction = finite_result(axis_reaction)


def pendulum_axis_reaction(
    phi: npt.ArrayLike,
    J_axis: npt.ArrayLike,
    m: npt.ArrayLike,
    g: npt.ArrayLike,
    h: npt.ArrayLike,
    *,
    E: npt.ArrayLike,
) -> npt.NDArray[np.float64]:
    """Axis reaction of the physical pendulum as a function of φ and E (4.76)–(4.77).

    Domain: ``J_axis``, ``m``, ``g``, ``h`` > 0 (else NonPositiveParameterError), any finite ``phi``
    and an energy ``E`` ≥ m g h (1 − cos φ) to 8 eps (else OutOfDomainError).  Products beyond
    float64 on the way (parameters near 1e300, or 1e300 and 1e-300 mixed) raise
    ResultOverflowError, even where the exact reaction would be representable; batches that do not
    broadcast (2 against 3) raise ShapeError listing each argument's shape.

    R_ρ = (2 m h/J_z)(m g h − E) − (1 + 2 m h²/J_z) m g cos φ,
    R_φ = (1 − m h²/J_z) m g sin φ, with E of (4.74).  No small-amplitude
    approximation.

    Parameters
    ----------
    phi : array_like, shape (...)
        The angle φ from the downward vertical (rad), finite.
    J_axis : array_like, shape (...)
        Moment of inertia about the axis, the book's J_z (kg m²), > 0.
    m : array_like, shape (...)
        Mass (kg), > 0.
    g : array_like, shape (...)
        Gravitational acceleration (m/s²), > 0.
    h : array_like, shape (...)
        Distance from the axis to G, the book's h (m), > 0.
    E : array_like, shape (...)
        The energy (4.74) (J), zero at rest at the bottom, ≥ m g h (1 − cos φ).

    Returns
    -------
    ndarray, shape (..., 2)
        (R_ρ, R_φ) (N), the force of the axis on the body, e_ρ from the axis toward G;
        the leading shape is the broadcast shape of the inputs.

    Raises
    ------
    NonPositiveParameterError
        ``J_axis``, ``m``, ``g`` or ``h`` has an entry ≤ 0 (the message names it).
    OutOfDomainError
        If E < m g h (1 − cos φ) (to 8 eps): the pendulum cannot reach φ with that energy.
    NonFiniteError
        A NaN or infinite input.
    ShapeError
        Inputs whose shapes do not broadcast (the message lists each argument's shape), or an
        input that is not an array of real numbers.
    ResultOverflowError
        A product beyond float64 on the way (parameters near 1e300, or 1e300 and 1e-300
        mixed), even where the exact reaction would be representable.

    Examples
    --------
    Hanging at rest (E = 0, φ = 0): R = (−m g, 0).

    >>> pendulum_axis_reaction(0.0, 1.0, 2.0, 9.81, 0.5, E=0.0).tolist()
    [-19.62, 0.0]

    The same reaction from :func:`axis_reaction`, with φ̇² from the energy (4.74), φ̈ from
    (4.48) and gravity's polar components (m g cos φ, −m g sin φ):

    >>> J, m, g, h, phi, E = 2.0, 1.0, 10.0, 0.5, 0.5, 10.0
    >>> R = pendulum_axis_reaction(phi, J, m, g, h, E=E)
    >>> w = np.sqrt(2.0 * (E - m * g * h * (1.0 - np.cos(phi))) / J)
    >>> R_b = axis_reaction(m, h, w, -m * g * h * np.sin(phi) / J,
    ...                     F_a_rho=m * g * np.cos(phi), F_a_phi=-m * g * np.sin(phi))
    >>> bool(np.allclose(R, R_b, rtol=4 * EPS, atol=0))
    True
    """
    J, mm, gg, hh = _pendulum(J_axis, m, g, h)
    p = as_float_array(phi, "phi")
    En = as_float_array(E, "E")
    need = mm * gg * hh * 2.0 * np.sin(0.5 * p) ** 2
    bad = En < need * (1.0 - 8 * EPS)
    if np.any(bad):
        raise OutOfDomainError(
            "E is below the potential energy m g h (1 - cos phi) at phi: the pendulum "
            f"does not reach phi (first at index {tuple(int(i) for i in np.argwhere(bad)[0])})"
        )
    mg = mm * gg
    R_rho = (2.0 * mm * hh / J) * (mg * hh - En) - (1.0 + 2.0 * mm * hh * hh / J) * mg * np.cos(p)
    R_phi = (1.0 - mm * hh * hh / J) * mg * np.sin(p)
    return np.stack(np.broadcast_arrays(R_rho, R_phi), axis=-1)


pendulum_axis_reaction = finite_result(pendulum_axis_reaction)


def bearing_reactions(
    J_O: npt.ArrayLike,
    m: npt.ArrayLike,
    r_G: npt.ArrayLike,
    phidot: npt.ArrayLike,
    phiddot: npt.ArrayLike,
    z_A: npt.ArrayLike,
    *,
    F_a: npt.ArrayLike,
    M_a: npt.ArrayLike,
    axial_at: str = "O",
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """Reactions R1 at bearing A and R2 at bearing O of a body turning about e_z (4.78)–(4.85).

    Domain: ``J_O`` (..., 3, 3) as :func:`~mechanics.inertia.check_inertia` about a point, singular
    allowed (else NonPhysicalInertiaError), ``m`` > 0 (else NonPositiveParameterError), ``z_A`` ≠ 0
    (else NonPositiveParameterError), any finite ``r_G``, ``F_a``, ``M_a`` (..., 3) and ``phidot``,
    ``phiddot``; ``axial_at`` 'O' or 'A' (else UnknownOptionError).  A result beyond float64 (φ̇²
    terms with ``phidot`` near 1e300) raises ResultOverflowError; batches that do not broadcast (2
    against 3) raise ShapeError listing each argument's shape.

    Body axes, O at the origin, A at (0, 0, z_A); ω = φ̇ e_z.  The book's
    choice r_G = (h, 0, z_G) gives (4.78), (4.84), (4.85) exactly; any r_G is
    accepted (the acceleration of G is then φ̈ e_z × r_G − φ̇² (x_G, y_G, 0)).
    The products of inertia are read from the tensor: D_xz = −J_O[0, 2],
    D_yz = −J_O[1, 2].

    R1_y = (D_xz φ̈ − D_yz φ̇² + M^a_x)/z_A,  R1_x = −(D_yz φ̈ + D_xz φ̇² + M^a_y)/z_A,
    and R2 = m a_G − F^a − R1.  The axial force −F^a_z (the book: statically
    indeterminate if both bearings take it) is given to the bearing ``axial_at``.

    Parameters
    ----------
    J_O : array_like, shape (..., 3, 3)
        Inertia tensor about O in body axes.
    m : array_like, shape (...)
        Mass (kg), > 0.
    r_G : array_like, shape (..., 3)
        Centre of mass in body axes (m).
    phidot : array_like, shape (...)
        Angular velocity φ̇ (rad/s).
    phiddot : array_like, shape (...)
        Angular acceleration φ̈ (rad/s²); φ̈ = M_z/J_z is not imposed: give the actual one.
    z_A : array_like, shape (...)
        Position of bearing A on the axis (m); non-zero, either sign.
    F_a : array_like, shape (..., 3)
        Applied force (N, body axes).
    M_a : array_like, shape (..., 3)
        Applied moment about O (N m, body axes); only its x, y components enter.
    axial_at : {"O", "A"}
        The bearing that takes the axial force −F^a_z (default "O").

    Returns
    -------
    R1, R2 : ndarray, shape (..., 3)
        The forces on the body from bearings A and O (N, body axes).

    Raises
    ------
    UnknownOptionError
        ``axial_at`` is not 'O' or 'A'.
    NonPhysicalInertiaError
        ``J_O`` refused by :func:`~mechanics.inertia.check_inertia` (singular allowed).
    NonPositiveParameterError
        ``m`` has an entry ≤ 0, or ``z_A`` an entry 0 (the bearings coincide).
    NonFiniteError
        A NaN or infinite input.
    ShapeError
        ``J_O`` not ending in (3, 3), ``r_G``, ``F_a`` or ``M_a`` not ending in 3, batch axes
        that do not broadcast (the message lists each argument's shape), or an input that is
        not an array of real numbers.
    ResultOverflowError
        A component beyond float64 (φ̇² terms with ``phidot`` near 1e300).

    Examples
    --------
    A statically and dynamically balanced body (G on the axis, the axis a
    principal axis) needs no bearing force beyond the applied load:

    >>> R1, R2 = bearing_reactions(np.diag([2.0, 2.0, 1.0]), 1.0, [0.0, 0.0, 0.5], 10.0, 0.0,
    ...                            1.0, F_a=[0.0, 0.0, 0.0], M_a=[0.0, 0.0, 0.0])
    >>> (R1 + 0.0).tolist(), (R2 + 0.0).tolist()
    ([0.0, 0.0, 0.0], [0.0, 0.0, 0.0])
    """
    if axial_at not in ("O", "A"):
        raise UnknownOptionError(f"axial_at={axial_at!r}; expected 'O' or 'A'")
    J = check_inertia(J_O, allow_singular=True, about_centre_of_mass=False, name="J_O")
    mm = _positive(m, "m")
    rG = as_float_array(r_G, "r_G", (3,))
    w = as_float_array(phidot, "phidot")
    a = as_float_array(phiddot, "phiddot")
    zA = as_float_array(z_A, "z_A")
    if (zA == 0).any():
        raise NonPositiveParameterError("z_A must be non-zero: the two bearings coincide")
    F = as_float_array(F_a, "F_a", (3,))
    M = as_float_array(M_a, "M_a", (3,))
    Dxz, Dyz = -J[..., 0, 2], -J[..., 1, 2]
    R1y = (Dxz * a - Dyz * w * w + M[..., 0]) / zA
    R1x = -(Dyz * a + Dxz * w * w + M[..., 1]) / zA
    xG, yG = rG[..., 0], rG[..., 1]
    aGx = -w * w * xG - a * yG
    aGy = -w * w * yG + a * xG
    Rx = mm * aGx - F[..., 0]
    Ry = mm * aGy - F[..., 1]
    Rz = -F[..., 2]
    shape = np.broadcast_shapes(*(np.shape(v) for v in (R1x, R1y, Rx, Ry, Rz)))
    R1x, R1y, Rx, Ry, Rz = (np.broadcast_to(v, shape) for v in (R1x, R1y, Rx, Ry, Rz))
    zero = np.zeros(shape)
    R1z, R2z = (zero, Rz) if axial_at == "O" else (Rz, zero)
    R1 = np.stack([R1x, R1y, R1z], axis=-1)
    R2 = np.stack([Rx - R1x, Ry - R1y, R2z], axis=-1)
    return R1, R2


bearing_reactions = finite_result(bearing_reactions)
