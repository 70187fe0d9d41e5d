"""Power, work, kinetic and potential energy of particle systems and rigid bodies.

Conventions (Essén 1996, ch. 3)
-------------------------------
- Vectors are ``(..., 3)`` in one fixed frame and broadcast over leading axes;
  systems of N particles or forces are ``(..., N, 3)`` (as in
  :mod:`mechanics.particles`).
- The power of forces F_k acting on points moving with v_k is P = Σ F_k · v_k
  (3.1); the work between two times is W_12 = ∫ P dt (3.36), equal to
  T(2) − T(1) (3.37) when *all* forces, internal ones included, are counted.
- ``J_G`` is an inertia tensor (3.23) about G in the *same basis* as ``omega``
  (fixed-frame or body components alike, as long as they agree); the rigid-body
  kinetic energy is T = ½ m v_G² + ½ ωᵀ J_G ω (3.7), (3.24).  The book writes
  the row form ½ w J wᵀ; it is the same number.
- Potential energies (3.47)–(3.53): uniform gravity Φ = −m g · r_G (3.55)–(3.56),
  with the gravity vector ``g`` required (no silent "down"); a linear spring
  Φ = ½ k (|r_1 − r_2| − ℓ_0)² (the rubber band of (3.57) with
  ``tension_only=True``); a torsion spring Φ = ½ τ_0 φ² (3.72).
- Forces that do no work (3.2.2): a contact force at a point of zero velocity
  (rolling without slipping, static friction) and an action–reaction pair at
  points with equal velocities along the force deliver zero power;
  :func:`contact_power` and :func:`pair_power` compute that power.

Accuracy: sums over particles use the compensated sums of
:mod:`mechanics.particles`; the quadratures are documented where they are.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt
from scipy.integrate import simpson

from ._validate import as_float_array, finite_result
from .errors import (
    MechanicsValueError,
    NegativeMassError,
    NonPhysicalInertiaError,
    NonPositiveParameterError,
    OutOfDomainError,
    ShapeError,
)
from .inertia import check_inertia
from .particles import (
    _dot,
    _finite_result,
    _first_index,
    check_masses,
)

__all__ = [
    "contact_point_velocity",
    "contact_power",
    "gravity_potential",
    "kinetic_energy_fixed_axis",
    "kinetic_energy_rigid",
    "pair_power",
    "power",
    "rigid_body_power",
    "rolling_contact_power",
    "spring_force",
    "spring_potential",
    "torsion_moment",
    "torsion_potential",
    "work_along_path",
    "work_from_power",
    "work_of_couple",
]


def _nonneg(
    x: npt.ArrayLike, name: str, error: type[MechanicsValueError] = NegativeMassError
) -> npt.NDArray[np.float64]:
    a = as_float_array(x, name)
    neg = a < 0
    if neg.any():
        idx = _first_index(neg)
        raise error(f"{name} must be >= 0; found {float(a[idx])!r} at index {idx}")
    return a


# ------------------------------------------------------------ kinetic energy


def kinetic_energy_rigid(
    m: npt.ArrayLike, v_G: npt.ArrayLike, omega: npt.ArrayLike, J_G: npt.ArrayLike
) -> npt.NDArray[np.float64]:
    """Kinetic energy of a rigid body, T = ½ m v_G² + ½ ωᵀ J_G ω (3.7), (3.24).

    Domain: m ≥ 0 (else NegativeMassError), finite v_G and omega (..., 3), J_G a physical inertia
    tensor (``check_inertia``, singular allowed: a rod); a result beyond float64 raises
    ResultOverflowError.

    Parameters
    ----------
    m : array_like, shape (...)
        Mass, kg, ≥ 0.
    v_G : array_like, shape (..., 3)
        Velocity of the centre of mass, m/s.
    omega : array_like, shape (..., 3)
        Angular velocity, rad/s, in the basis of ``J_G``.
    J_G : array_like, shape (..., 3, 3)
        Inertia tensor about G (3.23), kg m²: symmetric, positive semi-definite.

    Returns
    -------
    ndarray, shape (...)
        T, J.

    Raises
    ------
    ShapeError
        Where ``v_G`` or ``omega`` is not (..., 3), ``J_G`` not (..., 3, 3), the leading
        axes do not broadcast, or an input is not a real numeric array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    NegativeMassError
        Where ``m`` is negative.
    NonPhysicalInertiaError
        Where ``J_G`` is not symmetric, not positive semi-definite or breaks J1 + J2 ≥ J3
        (:func:`~mechanics.inertia.check_inertia` with ``allow_singular=True``).
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Examples
    --------
    Example 3.1: a disc rolling in the plane, T = ½ J_C φ̇² = ½ m v_G² + ½ J_G φ̇²
    with J_C = J_G + m |CG|² (3.31)–(3.35); m = 2, R = 1, φ̇ = 3:

    >>> J_G = np.diag([0.5, 0.5, 1.0])
    >>> float(kinetic_energy_rigid(2.0, [3.0, 0.0, 0.0], [0.0, 0.0, -3.0], J_G))
    13.5
    >>> float(kinetic_energy_fixed_axis(1.0 + 2.0 * 1.0**2, 3.0))
    13.5
    """
    mm = _nonneg(m, "m")
    v = as_float_array(v_G, "v_G", (3,))
    w = as_float_array(omega, "omega", (3,))
    J = check_inertia(J_G, allow_singular=True, name="J_G")
    rot = 0.5 * np.einsum("...i,...ij,...j->...", w, J, w)
    trans = 0.5 * mm * np.einsum("...i,...i->...", v, v)
    return _finite_result(trans + rot, "the kinetic energy")


kinetic_energy_rigid = finite_result(kinetic_energy_rigid)


def kinetic_energy_fixed_axis(
    J_axis: npt.ArrayLike, omega: npt.ArrayLike
) -> npt.NDArray[np.float64]:
    """T = ½ J φ̇² for rotation about a fixed axis (3.26), (3.27), (3.30).

    Domain: J_axis ≥ 0 (else NonPhysicalInertiaError), any finite omega; a result beyond float64
    raises ResultOverflowError.

    Parameters
    ----------
    J_axis : array_like, shape (...)
        Moment of inertia about the axis (J^G_z or J^C_z), kg m², ≥ 0.
    omega : array_like, shape (...)
        Angular velocity φ̇ about the axis, rad/s; broadcasts against ``J_axis``.

    Returns
    -------
    ndarray, shape (...)
        T, J.

    Raises
    ------
    ShapeError
        Where ``J_axis`` and ``omega`` do not broadcast, or an input is not a real numeric
        array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    NonPhysicalInertiaError
        Where ``J_axis`` is negative.
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Examples
    --------
    (3.30) from the particles: T = Σ ½ m_k ρ_k² φ̇²:

    >>> float(kinetic_energy_fixed_axis(2.0 * 1.5**2, 4.0)), 0.5 * 2.0 * (1.5 * 4.0) ** 2
    (36.0, 36.0)
    """
    J = _nonneg(J_axis, "J_axis", NonPhysicalInertiaError)
    w = as_float_array(omega, "omega")
    return _finite_result(0.5 * J * w * w, "the kinetic energy")


kinetic_energy_fixed_axis = finite_result(kinetic_energy_fixed_axis)


# --------------------------------------------------------------- power, work


def _pair(
    F: npt.ArrayLike, v: npt.ArrayLike, names: tuple[str, str] = ("F", "v")
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    FF = as_float_array(F, names[0], (3,))
    vv = as_float_array(v, names[1], (3,))
    try:
        np.broadcast_shapes(FF.shape, vv.shape)
    except ValueError:
        raise ShapeError(
            f"{names[0]} {FF.shape} and {names[1]} {vv.shape} do not broadcast"
        ) from None
    return FF, vv


def power(F: npt.ArrayLike, v: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Power of a system of forces, P = Σ_k F_k · v_k (3.1), compensated.

    Domain: finite F and v of shape (..., N, 3) (N forces; one force is (1, 3)); a result beyond
    float64 raises ResultOverflowError.

    Parameters
    ----------
    F, v : array_like, shape (..., N, 3)
        The forces and the velocities of their points of application.  One
        force is ``(1, 3)``.

    Returns
    -------
    ndarray, shape (...)
        P, W.

    Raises
    ------
    ShapeError
        Where ``F`` or ``v`` is not (..., N, 3) (a single force is ``(1, 3)``, not ``(3,)``),
        the leading axes do not broadcast, or an input is not a real numeric array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Examples
    --------
    P = dT/dt (3.4): for one particle T = ½ m v², dT/dt = m v · a = F · v.

    >>> float(power([[1.0, 2.0, 0.0], [0.0, 0.0, -1.0]], [[3.0, 0.0, 0.0], [1.0, 1.0, 2.0]]))
    1.0
    """
    FF, vv = _pair(F, v)
    if FF.ndim < 2 or vv.ndim < 2:
        raise ShapeError(f"F {FF.shape} and v {vv.shape} must be (..., N, 3); one force is (1, 3)")
    FF, vv = np.broadcast_arrays(FF, vv)
    P = _dot(FF.reshape(*FF.shape[:-2], -1), vv.reshape(*vv.shape[:-2], -1))
    return _finite_result(P, "the power")


power = finite_result(power)


def work_from_power(P: npt.ArrayLike, t: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """W_12 = ∫ P dt (3.36) from samples of the power, by composite Simpson.

    Domain: t of shape (K,), K ≥ 2, strictly increasing (else NonPositiveParameterError), finite P
    of shape (..., K); a result beyond float64 raises ResultOverflowError.

    Parameters
    ----------
    P : array_like, shape (..., K)
        Power at the sample times (the last axis), W.
    t : array_like, shape (K,)
        Strictly increasing times, s, K ≥ 2.

    Returns
    -------
    ndarray, shape (...)
        W_12, J.

    Raises
    ------
    ShapeError
        Where ``t`` is not (K,) with K ≥ 2, ``P`` not (..., K), or an input is not a real
        numeric array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    NonPositiveParameterError
        Where ``t`` is not strictly increasing.
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Notes
    -----
    :func:`scipy.integrate.simpson`: error O(h⁴) for a smooth P (exact for a
    cubic in t on equal steps); K = 2 falls back to the trapezoid.

    Examples
    --------
    P = 3t² on [0, 1] gives W = 1, exactly on five samples:

    >>> t = np.linspace(0.0, 1.0, 5)
    >>> float(work_from_power(3 * t**2, t))
    1.0
    """
    PP = as_float_array(P, "P")
    tt = as_float_array(t, "t")
    if tt.ndim != 1 or tt.shape[0] < 2 or PP.ndim < 1 or PP.shape[-1] != tt.shape[0]:
        raise ShapeError(
            f"t must be (K,) with K >= 2 and P (..., K); got t {tt.shape}, P {PP.shape}"
        )
    if not (np.diff(tt) > 0).all():
        raise NonPositiveParameterError("t must be strictly increasing (every step > 0)")
    return _finite_result(np.asarray(simpson(PP, x=tt, axis=-1)), "the work")


work_from_power = finite_result(work_from_power)


def work_along_path(F: npt.ArrayLike, r: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Work of a force along a sampled path, W = ∫ F · dr (3.38), by the trapezoid rule.

    Domain: finite F and r of shape (..., K, 3) with K ≥ 2 samples (else ShapeError); a result
    beyond float64 raises ResultOverflowError.

    Parameters
    ----------
    F, r : array_like, shape (..., K, 3)
        The force at the K path samples (N) and the samples r_0, …, r_{K−1} (m).

    Returns
    -------
    ndarray, shape (...)
        Σ_i ½ (F_i + F_{i+1}) · (r_{i+1} − r_i), J.

    Raises
    ------
    ShapeError
        Where ``F`` or ``r`` is not (..., K, 3) with K ≥ 2 samples, the leading axes do not
        broadcast, or an input is not a real numeric array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Notes
    -----
    The trapezoid rule in the path parameter: exact where the path is straight
    between samples and F is affine along each segment (a constant force, a
    linear spring on a straight path); error O(h²) in the step for a smooth
    force along a smooth path.  For the work of a *conservative* force this
    converges to −ΔΦ, independent of the path (3.50).

    Examples
    --------
    A constant force does the work F · Δr along any path:

    >>> s = np.linspace(0.0, 1.0, 50)
    >>> path = np.stack([np.cos(3 * s), np.sin(3 * s), s], axis=-1)
    >>> F = np.broadcast_to([0.0, 0.0, -9.8], path.shape)
    >>> float(work_along_path(F, path)), float(-9.8 * (path[-1, 2] - path[0, 2]))
    (-9.8, -9.8)
    """
    FF, rr = _pair(F, r, ("F", "r"))
    if FF.ndim < 2 or rr.ndim < 2 or rr.shape[-2] < 2:
        raise ShapeError(f"F {FF.shape} and r {rr.shape} must be (..., K, 3) with K >= 2 samples")
    FF, rr = np.broadcast_arrays(FF, rr)
    Fm = 0.5 * (FF[..., 1:, :] + FF[..., :-1, :])
    dr = rr[..., 1:, :] - rr[..., :-1, :]
    W = _dot(Fm.reshape(*Fm.shape[:-2], -1), dr.reshape(*dr.shape[:-2], -1))
    return _finite_result(W, "the work")


work_along_path = finite_result(work_along_path)


def work_of_couple(M: npt.ArrayLike, dphi: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Work of a constant moment M over a rotation δφ about a fixed axis: W = M · δφ (3.70).

    Domain: finite M and dphi of shape (..., 3); a result beyond float64 raises ResultOverflowError.

    For a fixed rotation axis e_z, δφ = Δφ e_z and W = M_z Δφ; the work of a
    couple is independent of the base point, because a couple has zero
    resultant (3.65 with F = 0).

    Parameters
    ----------
    M : array_like, shape (..., 3)
        The moment of the couple, N m.
    dphi : array_like, shape (..., 3)
        The rotation vector δφ = Δφ e, rad.

    Returns
    -------
    ndarray, shape (...)
        W, J.

    Raises
    ------
    ShapeError
        Where an input is not (..., 3), the leading axes do not broadcast, or an input is
        not a real numeric array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Examples
    --------
    >>> float(work_of_couple([0.0, 1.0, 2.0], [0.0, 0.0, 0.5 * np.pi]) / np.pi)
    1.0
    """
    MM, dd = _pair(M, dphi, ("M", "dphi"))
    return _finite_result(np.einsum("...i,...i->...", MM, dd), "the work")


work_of_couple = finite_result(work_of_couple)


def rigid_body_power(
    F: npt.ArrayLike, M_A: npt.ArrayLike, v_A: npt.ArrayLike, omega: npt.ArrayLike
) -> npt.NDArray[np.float64]:
    """Power of the forces on a rigid body, P = F · v_A + M_A · ω (3.65 per unit time).

    Domain: finite F, M_A, v_A, omega of shape (..., 3); a result beyond float64 raises
    ResultOverflowError.

    F is the resultant, M_A the moment about the body point A moving with v_A;
    the result does not depend on which body point is chosen.

    Parameters
    ----------
    F : array_like, shape (..., 3)
        The resultant force, N.
    M_A : array_like, shape (..., 3)
        The moment of the forces about the body point A, N m.
    v_A : array_like, shape (..., 3)
        The velocity of A, m/s.
    omega : array_like, shape (..., 3)
        The angular velocity of the body, rad/s.

    Returns
    -------
    ndarray, shape (...)
        P, W.

    Raises
    ------
    ShapeError
        Where an input is not (..., 3), the leading axes do not broadcast, or an input is
        not a real numeric array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Examples
    --------
    A force F at the body point P: F · v_P = F · v_A + M_A · ω.

    >>> F, AP = np.array([1.0, 2.0, 0.5]), np.array([0.0, 1.0, -1.0])
    >>> v_A, w = np.array([0.5, 0.0, 1.0]), np.array([0.0, 2.0, 1.0])
    >>> float(rigid_body_power(F, np.cross(AP, F), v_A, w)), float(F @ (v_A + np.cross(w, AP)))
    (-2.0, -2.0)
    """
    FF, vv = _pair(F, v_A, ("F", "v_A"))
    MM, ww = _pair(M_A, omega, ("M_A", "omega"))
    P = np.einsum("...i,...i->...", FF, vv) + np.einsum("...i,...i->...", MM, ww)
    return _finite_result(P, "the power")


rigid_body_power = finite_result(rigid_body_power)


# ------------------------------------------------------------------ potentials


def gravity_potential(
    m: npt.ArrayLike, r: npt.ArrayLike, *, g: npt.ArrayLike
) -> npt.NDArray[np.float64]:
    """Potential energy of uniform gravity, Φ^e = −Σ m_k g · r_k = −m g · r_G (3.55)–(3.56).

    Domain: masses m ≥ 0 of shape (..., N) (``check_masses``), finite r (..., N, 3) and g (..., 3);
    a result beyond float64 raises ResultOverflowError.

    Parameters
    ----------
    m : array_like, shape (..., N)
        Masses, kg, ≥ 0.
    r : array_like, shape (..., N, 3)
        Positions, m.
    g : array_like, shape (..., 3)
        The gravity vector, m/s² (required; e.g. ``[0, 0, -9.81]`` with z up).

    Returns
    -------
    ndarray, shape (...)
        Φ^e, J (zero at the origin).

    Raises
    ------
    ShapeError
        Where ``m`` is not (..., N) with N ≥ 1, ``r`` not (..., N, 3) with the same N, ``g``
        not (..., 3), the leading axes do not broadcast, or an input is not a real numeric
        array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    NegativeMassError
        Where a mass is negative.
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Examples
    --------
    Example 3.2, Φ^e = m g h with h the height of G:

    >>> m, r = [1.0, 3.0], [[0.0, 0.0, 2.0], [5.0, 1.0, 6.0]]
    >>> float(gravity_potential(m, r, g=[0.0, 0.0, -10.0])), 4.0 * 10.0 * 5.0
    (200.0, 200.0)
    """
    mm = check_masses(m)
    rr = as_float_array(r, "r", (3,))
    gg = as_float_array(g, "g", (3,))
    if rr.ndim < 2 or rr.shape[-2] != mm.shape[-1]:
        raise ShapeError(f"r has shape {rr.shape} but m has shape {mm.shape}")
    with np.errstate(over="ignore", invalid="ignore"):
        mg = mm[..., None] * gg[..., None, :]
    mg, rr = np.broadcast_arrays(_finite_result(mg, "m g"), rr)
    Phi = -_dot(mg.reshape(*mg.shape[:-2], -1), rr.reshape(*rr.shape[:-2], -1))
    return _finite_result(Phi, "the potential energy")


gravity_potential = finite_result(gravity_potential)


def _spring_args(
    k: npt.ArrayLike, ell_0: npt.ArrayLike, r_1: npt.ArrayLike, r_2: npt.ArrayLike
) -> tuple[
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
]:
    kk = as_float_array(k, "k")
    if (kk < 0).any():
        raise OutOfDomainError(f"spring constant k = {k!r} must be >= 0")
    ll = as_float_array(ell_0, "ell_0")
    if (ll < 0).any():
        raise OutOfDomainError(f"natural length ell_0 = {ell_0!r} must be >= 0")
    a, b = _pair(r_1, r_2, ("r_1", "r_2"))
    d = a - b
    return kk, ll, d, _length(d)


def _length(d: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
    """|d| over the last axis, of d scaled by a power of two to a largest entry in [1/2, 1)
    (exact) and scaled back once: the same bits as the plain √(d·d) wherever its squares
    neither under- nor overflow.  The plain norm overflowed beyond |d| ~ 1e154 (a spring
    force 1e160 refused as an overflow) and underflowed below 1e-154 (ends 1e-170 apart
    refused as coincident)."""
    k = np.frexp(np.max(np.abs(d), axis=-1))[1]
    s = np.ldexp(d, -k[..., None])
    out: npt.NDArray[np.float64] = np.ldexp(np.sqrt(np.sum(s * s, axis=-1)), k)
    return out


def _half_k_squared(
    k: npt.NDArray[np.float64], x: npt.NDArray[np.float64]
) -> npt.NDArray[np.float64]:
    """½ k x² of the mantissas, f_k f_x f_x, scaled once by 2**(e_k + 2 e_x − 1): the same
    bits as the plain product wherever it neither under- nor overflows on the way.  The plain
    (½ k) x x rounded a subnormal ½ k first (k = 3 · 2**-1074, x = 2**40: 4 · 2**-995, 33 %
    above the exact 3 · 2**-995)."""
    fk, ek = np.frexp(k)
    fx, ex = np.frexp(x)
    with np.errstate(over="ignore"):  # the caller checks the result
        out: npt.NDArray[np.float64] = np.ldexp(fk * fx * fx, ek + 2 * ex - 1)
    return out


def spring_potential(
    k: npt.ArrayLike,
    ell_0: npt.ArrayLike,
    r_1: npt.ArrayLike,
    r_2: npt.ArrayLike,
    *,
    tension_only: bool = False,
) -> npt.NDArray[np.float64]:
    """Φ = ½ k (|r_1 − r_2| − ℓ_0)² of a linear spring between two points (3.53).

    Domain: k ≥ 0 and ℓ_0 ≥ 0 (else OutOfDomainError), finite r_1, r_2 (..., 3); a result beyond
    float64 raises ResultOverflowError.

    With ``tension_only=True`` the rubber band of Example 3.3 (3.57): Φ = 0
    while slack, |r_1 − r_2| ≤ ℓ_0.

    Parameters
    ----------
    k : array_like, shape (...)
        The spring constant, N/m, ≥ 0.
    ell_0 : array_like, shape (...)
        The natural length ℓ_0, m, ≥ 0.
    r_1, r_2 : array_like, shape (..., 3)
        The two end points, m.
    tension_only : bool, optional
        A rubber band (3.57): no energy while slack.  Default False.

    Returns
    -------
    ndarray, shape (...)
        Φ, J.

    Raises
    ------
    ShapeError
        Where ``r_1`` or ``r_2`` is not (..., 3), the leading axes do not broadcast, or an
        input is not a real numeric array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    OutOfDomainError
        Where ``k`` or ``ell_0`` is negative.
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Examples
    --------
    >>> float(spring_potential(4.0, 1.0, [0, 0, 0], [3.0, 4.0, 0.0])), 0.5 * 4.0 * (5.0 - 1.0) ** 2
    (32.0, 32.0)
    >>> float(spring_potential(4.0, 1.0, [0, 0, 0], [0.5, 0, 0], tension_only=True))
    0.0
    """
    kk, ll, _, dist = _spring_args(k, ell_0, r_1, r_2)
    ext = dist - ll
    if tension_only:
        ext = np.maximum(ext, 0.0)
    return _finite_result(_half_k_squared(kk, ext), "the spring energy")


spring_potential = finite_result(spring_potential)


def spring_force(
    k: npt.ArrayLike,
    ell_0: npt.ArrayLike,
    r_1: npt.ArrayLike,
    r_2: npt.ArrayLike,
    *,
    tension_only: bool = False,
) -> npt.NDArray[np.float64]:
    """Force on point 1 from the spring: −∇_1 Φ = −k (|r_12| − ℓ_0) r_12/|r_12| (3.48).

    Domain: k ≥ 0, ℓ_0 ≥ 0, finite r_1 ≠ r_2 (coincident ends: NonPositiveParameterError, the
    direction is undefined); a result beyond float64 raises ResultOverflowError.

    The force on point 2 is its negative (Newton's third law, central).

    Parameters
    ----------
    k : array_like, shape (...)
        The spring constant, N/m, ≥ 0.
    ell_0 : array_like, shape (...)
        The natural length ℓ_0, m, ≥ 0.
    r_1, r_2 : array_like, shape (..., 3)
        The two end points, m, distinct.
    tension_only : bool, optional
        A rubber band (3.57): no force while slack.  Default False.

    Returns
    -------
    ndarray, shape (..., 3)
        The force on point 1, N.

    Raises
    ------
    ShapeError
        Where ``r_1`` or ``r_2`` is not (..., 3), the leading axes do not broadcast, or an
        input is not a real numeric array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    OutOfDomainError
        Where ``k`` or ``ell_0`` is negative.
    NonPositiveParameterError
        For coincident points, |r_1 − r_2| = 0, whatever ℓ_0 (the direction is undefined).
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Examples
    --------
    The force is minus the gradient of :func:`spring_potential` (a central difference):

    >>> r1, r2, h = np.array([1.0, 2.0, 0.5]), np.zeros(3), 1e-6
    >>> F = spring_force(3.0, 1.0, r1, r2)
    >>> dPhi = (spring_potential(3.0, 1.0, r1 + [h, 0, 0], r2)
    ...         - spring_potential(3.0, 1.0, r1 - [h, 0, 0], r2)) / (2 * h)
    >>> bool(abs(F[0] + dPhi) < 1e-8)
    True
    """
    kk, ll, d, dist = _spring_args(k, ell_0, r_1, r_2)
    zero = dist == 0
    if zero.any():
        raise NonPositiveParameterError(
            f"the spring's end points coincide (index {_first_index(zero)}): |r_1 - r_2| = 0, "
            "its direction is undefined"
        )
    ext = dist - ll
    if tension_only:
        ext = np.maximum(ext, 0.0)
    return _finite_result(-(kk * ext / dist)[..., None] * d, "the spring force")


spring_force = finite_result(spring_force)


def torsion_potential(tau_0: npt.ArrayLike, phi: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Φ(φ) = ½ τ_0 φ² of a torsion spring with moment M = −τ_0 φ (3.71)–(3.72).

    Domain: τ_0 ≥ 0 (else OutOfDomainError), any finite φ; a result beyond float64 raises
    ResultOverflowError.

    Parameters
    ----------
    tau_0 : array_like, shape (...)
        The torsion constant τ_0, N m/rad, ≥ 0.
    phi : array_like, shape (...)
        The twist angle φ from the unstrained position, rad.

    Returns
    -------
    ndarray, shape (...)
        Φ, J.

    Raises
    ------
    ShapeError
        Where ``tau_0`` and ``phi`` do not broadcast, or an input is not a real numeric
        array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    OutOfDomainError
        Where ``tau_0`` is negative.
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Examples
    --------
    Φ(φ) = −∫₀^φ M dφ' (3.71), by the trapezoid rule (exact for a linear M):

    >>> s = np.linspace(0.0, 0.8, 9)
    >>> float(torsion_potential(2.5, 0.8)), float(-np.trapezoid(torsion_moment(2.5, s), s))
    (0.8, 0.8)
    """
    tt = as_float_array(tau_0, "tau_0")
    if (tt < 0).any():
        raise OutOfDomainError(f"torsion constant tau_0 = {tau_0!r} must be >= 0")
    pp = as_float_array(phi, "phi")
    return _finite_result(_half_k_squared(tt, pp), "the torsion energy")


torsion_potential = finite_result(torsion_potential)


def torsion_moment(tau_0: npt.ArrayLike, phi: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """The restoring moment M(φ) = −τ_0 φ of a torsion spring (Example 3.5).

    Domain: τ_0 ≥ 0 (else OutOfDomainError), any finite φ; a result beyond float64 raises
    ResultOverflowError.

    Parameters
    ----------
    tau_0 : array_like, shape (...)
        The torsion constant τ_0, N m/rad, ≥ 0.
    phi : array_like, shape (...)
        The twist angle φ from the unstrained position, rad.

    Returns
    -------
    ndarray, shape (...)
        M, N m.

    Raises
    ------
    ShapeError
        Where ``tau_0`` and ``phi`` do not broadcast, or an input is not a real numeric
        array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    OutOfDomainError
        Where ``tau_0`` is negative.
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Examples
    --------
    M = −dΦ/dφ (3.71); a central difference is exact for the quadratic Φ:

    >>> h = 0.5
    >>> dPhi = torsion_potential(2.0, 1.5 + h) - torsion_potential(2.0, 1.5 - h)
    >>> float(torsion_moment(2.0, 1.5)), float(-dPhi / (2 * h))
    (-3.0, -3.0)
    """
    tt = as_float_array(tau_0, "tau_0")
    if (tt < 0).any():
        raise OutOfDomainError(f"torsion constant tau_0 = {tau_0!r} must be >= 0")
    M: npt.NDArray[np.float64] = -tt * as_float_array(phi, "phi")
    return M


torsion_moment = finite_result(torsion_moment)


# ------------------------------------------------------- forces that do no work


def contact_point_velocity(
    v_G: npt.ArrayLike, omega: npt.ArrayLike, r_GC: npt.ArrayLike
) -> npt.NDArray[np.float64]:
    """Velocity of the body point at the contact C, v_C = v_G + ω × GC (2.73).

    Domain: finite v_G, omega, r_GC of shape (..., 3); a result beyond float64 raises
    ResultOverflowError.

    Parameters
    ----------
    v_G : array_like, shape (..., 3)
        Velocity of the centre of mass, m/s.
    omega : array_like, shape (..., 3)
        Angular velocity of the body, rad/s.
    r_GC : array_like, shape (..., 3)
        The vector GC from G to the contact point C, m.

    Returns
    -------
    ndarray, shape (..., 3)
        v_C, m/s.

    Raises
    ------
    ShapeError
        Where an input is not (..., 3), the leading axes do not broadcast, or an input is
        not a real numeric array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Examples
    --------
    A disc of radius 1 rolling with v_G = 2 e_x and ω = −2 e_z on the x-axis:

    >>> contact_point_velocity([2.0, 0.0, 0.0], [0.0, 0.0, -2.0], [0.0, -1.0, 0.0]).tolist()
    [0.0, 0.0, 0.0]
    """
    v, w = _pair(v_G, omega, ("v_G", "omega"))
    rr = as_float_array(r_GC, "r_GC", (3,))
    return v + np.cross(w, rr)


contact_point_velocity = finite_result(contact_point_velocity)


def contact_power(
    F_contact: npt.ArrayLike, v_G: npt.ArrayLike, omega: npt.ArrayLike, r_GC: npt.ArrayLike
) -> npt.NDArray[np.float64]:
    """Power of a contact force acting on the body point C: P = F · (v_G + ω × GC).

    Domain: finite F_contact, v_G, omega, r_GC of shape (..., 3); a result beyond float64 raises
    ResultOverflowError.

    Parameters
    ----------
    F_contact : array_like, shape (..., 3)
        The contact force on the body, N.
    v_G : array_like, shape (..., 3)
        Velocity of the centre of mass, m/s.
    omega : array_like, shape (..., 3)
        Angular velocity of the body, rad/s.
    r_GC : array_like, shape (..., 3)
        The vector GC from G to the contact point C, m.

    Returns
    -------
    ndarray, shape (...)
        P, W.

    Raises
    ------
    ShapeError
        Where an input is not (..., 3), the leading axes do not broadcast, or an input is
        not a real numeric array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Examples
    --------
    The same force does work on a sliding body (v_C ≠ 0):

    >>> float(contact_power([-1.0, 5.0, 0.0], [2.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, -1.0, 0.0]))
    -2.0
    """
    FF = as_float_array(F_contact, "F_contact", (3,))
    vC = contact_point_velocity(v_G, omega, r_GC)
    return _finite_result(np.einsum("...i,...i->...", FF, vC), "the power")


contact_power = finite_result(contact_power)


def rolling_contact_power(
    F_contact: npt.ArrayLike, v_G: npt.ArrayLike, omega: npt.ArrayLike, r_GC: npt.ArrayLike
) -> npt.NDArray[np.float64]:
    """Power of the contact force (normal force plus static friction) on a rolling body (3.2.2).

    Domain: finite F_contact, v_G, omega, r_GC of shape (..., 3); a result beyond float64 raises
    ResultOverflowError.

    Rolling without slipping means the body point at the contact has zero
    velocity, v_G + ω × GC = 0; the power F · v_C is then zero whatever F is.
    This function computes F · v_C (like :func:`contact_power`) and is the
    book's statement when the motion rolls; it does not assume it.

    Parameters
    ----------
    F_contact : array_like, shape (..., 3)
        The contact force on the body (normal force plus friction), N.
    v_G : array_like, shape (..., 3)
        Velocity of the centre of mass, m/s.
    omega : array_like, shape (..., 3)
        Angular velocity of the body, rad/s.
    r_GC : array_like, shape (..., 3)
        The vector GC from G to the contact point C, m.

    Returns
    -------
    ndarray, shape (...)
        P, W: zero when the body rolls without slipping.

    Raises
    ------
    ShapeError
        Where an input is not (..., 3), the leading axes do not broadcast, or an input is
        not a real numeric array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Examples
    --------
    Example 3.6, a cylinder (r = 0.5) rolling down an incline: the friction
    and normal force deliver no power, gravity delivers m g · v_G.

    >>> v_G, w, GC = [1.2, 0.0, 0.0], [0.0, 0.0, -2.4], [0.0, -0.5, 0.0]
    >>> float(rolling_contact_power([-3.0, 40.0, 0.0], v_G, w, GC))
    0.0
    """
    return contact_power(F_contact, v_G, omega, r_GC)


rolling_contact_power = finite_result(rolling_contact_power)


def pair_power(N: npt.ArrayLike, v_1: npt.ArrayLike, v_2: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Net power of a force N on body 1 and its reaction −N on body 2: N · (v_1 − v_2).

    Domain: finite N, v_1, v_2 of shape (..., 3); a result beyond float64 raises
    ResultOverflowError.

    Zero when the contact points have the same velocity component along N
    (a normal force between moving bodies), or the same velocity (static
    friction), 3.2.2.

    Parameters
    ----------
    N : array_like, shape (..., 3)
        The force on body 1, N (its reaction −N acts on body 2).
    v_1, v_2 : array_like, shape (..., 3)
        The velocities of the points of application on body 1 and on body 2, m/s.

    Returns
    -------
    ndarray, shape (...)
        P, W.

    Raises
    ------
    ShapeError
        Where an input is not (..., 3), the leading axes do not broadcast, or an input is
        not a real numeric array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Examples
    --------
    >>> float(pair_power([0.0, 3.0, 0.0], [1.0, 2.0, 0.0], [-4.0, 2.0, 7.0]))
    0.0
    """
    NN = as_float_array(N, "N", (3,))
    a, b = _pair(v_1, v_2, ("v_1", "v_2"))
    return _finite_result(np.einsum("...i,...i->...", NN, a - b), "the power")


pair_power = finite_result(pair_power)
