"""Systems of particles: mass, centre of mass, momentum, angular momentum, kinetic energy.

Conventions (Essén 1996, ch. 1 and 3.1)
---------------------------------------
- A system of N particles is given by masses ``m`` of shape ``(..., N)``,
  positions ``r`` and velocities ``v`` of shape ``(..., N, 3)`` in one fixed
  (inertial) frame; leading axes are batch axes and broadcast.  The masses
  broadcast against ``r[..., 0]``, so one mass vector ``(N,)`` serves a batch of
  configurations ``(B, N, 3)``.
- Masses are ≥ 0 (a zero mass is allowed, a negative one raises
  :class:`~mechanics.errors.NegativeMassError`); anything divided by the total
  mass raises :class:`~mechanics.errors.ZeroTotalMassError` for a massless system.
- **The base point is a required keyword** (``about=A``), never a silent origin.
  ``L_A`` is the book's (1.8), L_A = Σ AP_j × m_j v_j, with the *absolute*
  velocities v_j of the particles, whether A is fixed or moves: that is the
  quantity of the connection formula (1.46) and of the principle for a moving
  base point (1.50), dL_B/dt + v_B × p = M_B.  The angular momentum with the
  velocities *relative to A* is asked for by passing ``about_velocity=v_A``
  (for A = G it is the book's L'_G of (1.12), equal to L_G by (1.15)).
- Pair forces ``f`` have shape ``(..., N, N, 3)``: ``f[..., k, j, :]`` is f_kj,
  the force on particle k from particle j (1.17); Newton's third law is
  f_jk = −f_kj (1.19).
- G is the centre of mass (1.5); primes are quantities relative to G:
  r'_j = GP_j, v'_j = v_j − v_G (1.9).

Accuracy
--------
Every sum over the particles is *compensated*: each product m_j x_j is split
into its rounded value and its exact rounding error (Dekker's TwoProduct), and
the N values are added pairwise with Knuth's TwoSum, the rounding errors of each
addition carried along and added at the end.  The computed sum is then within
one rounding of the exact one plus O((log₂N · eps)²) Σ|m_j x_j| (Ogita, Rump &
Oishi 2005, "Accurate sum and dot product", Sum2/Dot2 with a pairwise tree),
so that the centre of mass of 10^6 particles 1e8 away from the origin, and
their momentum when it nearly cancels, are within 2 ulps of the exact value
(``tests/stability/test_particles_stability.py``, against exact rational
arithmetic: measured 0.21 and 0.44 ulps, where plain ``m @ r / m.sum()`` and
``m @ v`` are off by 96 and 227 ulps; L_O 0.86 ulps against 281).  The price is
time: 0.15 s for 10^6 particles against numpy's 0.008 s
(``tests/benchmarks/test_bench_particles.py``); the sums run block by block so
that their temporaries stay in cache.  Inputs are first scaled by powers of two (exact)
so that the splitting cannot overflow; a result beyond float64 raises
:class:`~mechanics.errors.ResultOverflowError`.  The decompositions of L and T
(Koenig's theorem) are computed from centred quantities r − r_G and v − v_G,
which makes L_G and T_G insensitive, to first order, to the rounding of r_G and
v_G: they stay accurate at offsets of 1e8 where T − ½ m v_G² would cancel.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from ._floats import EPS
from ._floats import split as _split
from ._validate import as_float_array, finite_result
from .errors import (
    NegativeMassError,
    NonPositiveParameterError,
    OutOfDomainError,
    ResultOverflowError,
    ShapeError,
    ZeroAxisError,
    ZeroTotalMassError,
)

__all__ = [
    "EPS",
    "Cylindrical",
    "angular_momentum",
    "angular_momentum_decomposition",
    "angular_momentum_rate",
    "average_angular_velocity",
    "axial_component",
    "centre_of_mass",
    "centre_of_mass_velocity",
    "check_masses",
    "continuous_angular_momentum",
    "continuous_centre_of_mass",
    "continuous_momentum",
    "cylindrical_components",
    "internal_forces",
    "internal_moment",
    "kinetic_energy",
    "kinetic_energy_decomposition",
    "masses_from_density",
    "moment_of_forces",
    "moment_of_inertia_about_axis",
    "momentum",
    "moving_base_point_term",
    "total_mass",
]


# ------------------------------------------------------------ compensated sums


def _tree(x: np.ndarray, c: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Pairwise TwoSum over the last axis: (s, c) with Σx + Σc ≈ s + c.

    Each addition s = a + b is error-free transformed, s + e = a + b exactly
    (Knuth), and the errors e are added up along the same tree together with
    the compensation terms c already given.
    """
    while x.shape[-1] > 1:
        n = x.shape[-1]
        if n % 2:
            pad = [(0, 0)] * (x.ndim - 1) + [(0, 1)]
            x, c = np.pad(x, pad), np.pad(c, pad)
            n += 1
        h = n // 2
        a, b = x[..., :h], x[..., h:]
        s = a + b
        bb = s - a
        e = (a - (s - bb)) + (b - bb)
        c = (c[..., :h] + c[..., h:]) + e
        x = s
    return x[..., 0], c[..., 0]


def _two_sum_tree(x: np.ndarray, c: np.ndarray) -> np.ndarray:
    """Σ over the last axis of x, plus the compensation terms c, pairwise with TwoSum."""
    s, c = _tree(x, c)
    out: np.ndarray = s + c
    return out


#: Elements per block in the compensated sums: the temporaries of a block
#: (a dozen arrays) stay in cache and are reused, where arrays of 10^6 floats
#: would each be freshly allocated and page-faulted (measured 4× slower).
_BLOCK_ELEMENTS = 2**16


def _exponent(a: np.ndarray) -> np.ndarray:
    """k with max |a| over the last axis in [2**(k−1), 2**k) (k = 0 where all are 0); keepdims."""
    out: np.ndarray = np.frexp(np.max(np.abs(a), axis=-1, keepdims=True))[1]
    return out


def _scale(a: np.ndarray, k: np.ndarray) -> np.ndarray:
    """a 2**−k, exact (save for results below 2**−1022), by two multiplications.

    Much faster than ``np.ldexp`` on large arrays (measured 25×); two factors,
    because 2**−k alone is beyond float64 for k < −1023.
    """
    h = k // 2
    out: np.ndarray = a * np.ldexp(1.0, -h) * np.ldexp(1.0, h - k)
    return out


def _dot_scaled(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(s, k) with Σ_j a_j b_j = s 2**k over the last axis, compensated (Dot2, pairwise tree).

    a and b are scaled by powers of two to max |·| in [1/2, 1) first (exact), so
    that Dekker's split (which multiplies by 2**27) cannot overflow and |s| ≤ N.
    Long axes are done block by block; the blocks' sums and compensations are
    then added by the same tree.
    """
    a, b = np.broadcast_arrays(a, b)
    n = a.shape[-1]
    if n == 0:
        return np.zeros(a.shape[:-1]), np.zeros(a.shape[:-1], dtype=int)
    ka, kb = _exponent(a), _exponent(b)
    rows = max(1, a.size // n)
    step = max(256, _BLOCK_ELEMENTS // rows)
    sums, comps = [], []
    for lo in range(0, n, step):
        u = _scale(a[..., lo : lo + step], ka)
        w = _scale(b[..., lo : lo + step], kb)
        p = u * w
        uh, ul = _split(u)
        wh, wl = _split(w)
        err = ((uh * wh - p) + uh * wl + ul * wh) + ul * wl
        s, c = _tree(p, err)
        sums.append(s)
        comps.append(c)
    if len(sums) == 1:
        return sums[0] + comps[0], (ka + kb)[..., 0]
    return _two_sum_tree(np.stack(sums, -1), np.stack(comps, -1)), (ka + kb)[..., 0]


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Σ_j a_j b_j over the last axis, compensated; inf where beyond float64."""
    s, k = _dot_scaled(a, b)
    with np.errstate(over="ignore"):
        out: np.ndarray = np.ldexp(s, k)
        return out


def _sum_scaled(a: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(s, k) with Σ a = s 2**k over the last axis, compensated."""
    return _dot_scaled(a, np.ones(a.shape[-1:]))


def _sum(a: np.ndarray) -> np.ndarray:
    """Σ over the last axis, compensated; inf where beyond float64."""
    s, k = _sum_scaled(a)
    with np.errstate(over="ignore"):
        out: np.ndarray = np.ldexp(s, k)
        return out


def _weighted_sum(m: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Σ_j m_j x_j for m (..., N) and x (..., N, 3) → (..., 3), compensated."""
    X = np.moveaxis(x, -1, -2)  # (..., 3, N)
    return _dot(m[..., None, :], X)


def _cross_sum(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Σ_j a_j × b_j for a, b (..., N, 3) → (..., 3), compensated.

    Each component is one compensated dot product of length 2N, e.g.
    Σ (a_y b_z − a_z b_y), so that the two products are not rounded against
    each other before the sum.
    """
    a, b = np.broadcast_arrays(a, b)
    out = []
    for j, k in ((1, 2), (2, 0), (0, 1)):
        u = np.concatenate([a[..., j], -a[..., k]], axis=-1)
        w = np.concatenate([b[..., k], b[..., j]], axis=-1)
        out.append(_dot(u, w))
    return np.stack(out, axis=-1)


def _first_index(mask: np.ndarray | np.bool_) -> tuple[int, ...]:
    return tuple(int(i) for i in np.argwhere(mask)[0]) if np.ndim(mask) else ()


def _finite_result(x: np.ndarray, what: str) -> np.ndarray:
    bad = ~np.isfinite(x)
    if bad.any():
        raise ResultOverflowError(
            f"{what} is beyond float64 (index {_first_index(bad)}): the exact result "
            "exceeds 1.8e308 in magnitude"
        )
    return x


# ------------------------------------------------------------------ validation


def check_masses(m: npt.ArrayLike, name: str = "m") -> np.ndarray:
    """Return masses ``(..., N)`` as a finite float64 array, all ≥ 0, N ≥ 1.

    Domain: any finite m ≥ 0 of shape (..., N), N ≥ 1 (else NegativeMassError or ShapeError).

    Parameters
    ----------
    m : array_like, shape (..., N)
        Masses, kg: finite, ≥ 0 (a zero mass is allowed).
    name : str, optional
        The name the error messages give the masses (default ``"m"``).

    Returns
    -------
    ndarray, shape (..., N)
        The masses as float64, unchanged (``m`` itself when it is a float64 array).

    Raises
    ------
    ShapeError
        For a scalar (a system needs a particle axis), N = 0, or an input that is not a
        real numeric array.
    NonFiniteError
        For NaN or an infinity, naming the first.
    NegativeMassError
        For a negative mass, naming it and its index.

    Examples
    --------
    >>> check_masses([1, 2.5]).tolist()
    [1.0, 2.5]
    >>> check_masses([1.0, -2.0])
    Traceback (most recent call last):
    ...
    mechanics.errors.NegativeMassError: m must be >= 0; found -2.0 at index (1,)
    """
    a = as_float_array(m, name)
    if a.ndim < 1 or a.shape[-1] == 0:
        raise ShapeError(f"{name} has shape {a.shape}; expected (..., N) with N >= 1 particles")
    neg = a < 0
    if neg.any():
        idx = _first_index(neg)
        raise NegativeMassError(f"{name} must be >= 0; found {float(a[idx])!r} at index {idx}")
    return a


check_masses = finite_result(check_masses)


def _system(
    m: npt.ArrayLike,
    r: npt.ArrayLike,
    rname: str = "r",
    *,
    particle_arrays: Sequence[tuple[npt.ArrayLike, str]] = (),
) -> tuple[np.ndarray, ...]:
    """Validate masses (..., N) and vectors (..., N, 3); broadcast leading axes."""
    mm = check_masses(m)
    arrays = [as_float_array(r, rname, (3,))]
    for x, name in particle_arrays:
        arrays.append(as_float_array(x, name, (3,)))
    names = [rname] + [n for _, n in particle_arrays]
    for a, name in zip(arrays, names, strict=True):
        if a.ndim < 2 or a.shape[-2] != mm.shape[-1]:
            raise ShapeError(
                f"{name} has shape {a.shape} but m has shape {mm.shape}: expected "
                f"{name} of shape (..., N, 3) with N = {mm.shape[-1]} particles"
            )
    try:
        lead = np.broadcast_shapes(mm.shape[:-1], *(a.shape[:-2] for a in arrays))
    except ValueError:
        shapes = ", ".join(f"{n} {a.shape}" for n, a in zip(names, arrays, strict=True))
        raise ShapeError(f"leading (batch) axes do not broadcast: m {mm.shape}, {shapes}") from None
    n = mm.shape[-1]
    mm = np.broadcast_to(mm, (*lead, n))
    arrays = [np.broadcast_to(a, (*lead, n, 3)) for a in arrays]
    return (mm, *arrays)


def _point(p: npt.ArrayLike, name: str, lead: tuple[int, ...]) -> np.ndarray:
    a = as_float_array(p, name, (3,))
    try:
        np.broadcast_shapes(a.shape[:-1], lead)
    except ValueError:
        raise ShapeError(
            f"{name} has shape {a.shape}; its leading axes do not broadcast against "
            f"the system's {lead}"
        ) from None
    return a


def _nonzero_mass(M: np.ndarray) -> None:
    zero = M == 0
    if zero.any():
        raise ZeroTotalMassError(
            f"the total mass of m is 0 (index {_first_index(zero)}): the centre of mass of a "
            "massless system is undefined"
        )


# --------------------------------------------------------------- mass, centre


def total_mass(m: npt.ArrayLike) -> np.ndarray:
    """Total mass m = Σ m_j (1.4), compensated.

    Domain: masses m ≥ 0 of shape (..., N), N ≥ 1 (``check_masses``: else NegativeMassError or
    ShapeError); a result beyond float64 raises ResultOverflowError.

    Parameters
    ----------
    m : array_like, shape (..., N)
        Masses, kg, ≥ 0.

    Returns
    -------
    ndarray, shape (...)
        The total mass, kg.

    Raises
    ------
    ShapeError
        Where ``m`` is not (..., N) with N ≥ 1, or not a real numeric array.
    NonFiniteError
        Where a mass is NaN or infinite.
    NegativeMassError
        Where a mass is negative.
    ResultOverflowError
        Where the sum is beyond float64 (~1.8e308).

    Examples
    --------
    Ten particles of 0.1 (not exact in binary) weigh the correctly rounded sum of
    their stored values, 1.0 (the exact sum, by fractions), where a plain running sum,
    one IEEE rounding per addition, loses the last digit:

    >>> from fractions import Fraction
    >>> exact = float(sum(Fraction(0.1) for _ in range(10)))
    >>> running = 0.0
    >>> for _ in range(10):
    ...     running += 0.1
    >>> float(total_mass([0.1] * 10)), exact, running
    (1.0, 1.0, 0.9999999999999999)
    """
    return _finite_result(_sum(check_masses(m)), "the total mass")


total_mass = finite_result(total_mass)


def centre_of_mass(m: npt.ArrayLike, r: npt.ArrayLike) -> np.ndarray:
    """Centre of mass r_G = Σ m_j r_j / Σ m_j (1.5).

    Domain: masses m ≥ 0 of shape (..., N), N ≥ 1 (``check_masses``: else NegativeMassError or
    ShapeError), finite vectors of shape (..., N, 3) with the same N, leading axes broadcasting
    (else ShapeError); a total mass > 0 (else ZeroTotalMassError); any magnitudes (the sums are
    scaled by powers of two).

    Parameters
    ----------
    m : array_like, shape (..., N)
        Masses, kg, ≥ 0, not all zero.
    r : array_like, shape (..., N, 3)
        Positions in the fixed frame, m.

    Returns
    -------
    ndarray, shape (..., 3)
        The centre of mass r_G, m; each component between the particles' least and greatest.

    Raises
    ------
    ShapeError
        Where ``m`` is not (..., N) with N ≥ 1, ``r`` not (..., N, 3) with the same N, the
        leading axes do not broadcast, or an input is not a real numeric array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    NegativeMassError
        Where a mass is negative.
    ZeroTotalMassError
        Where all masses are 0.

    Notes
    -----
    Both sums are compensated (see the module's Accuracy), so r_G is within
    about 1.5 ulps of the exact centre of mass of the float inputs, at any
    offset from the origin.

    Examples
    --------
    Σ m_j r'_j = 0 (1.10): the centre of mass of the particles seen from G is G.

    >>> m = [1.0, 3.0]
    >>> r = np.array([[0.0, 0.0, 0.0], [4.0, 8.0, 0.0]])
    >>> rG = centre_of_mass(m, r)
    >>> rG.tolist(), centre_of_mass(m, r - rG).tolist()
    ([3.0, 6.0, 0.0], [0.0, 0.0, 0.0])
    """
    mm, rr = _system(m, r)
    sM, kM = _sum_scaled(mm)
    _nonzero_mass(sM)
    # r_G = (s_S 2**k_S)/(s_M 2**k_M): the ratio of the scaled sums, then the
    # exponent, so that Σ m_j r_j may exceed float64 where r_G does not.
    sS, kS = _dot_scaled(mm[..., None, :], np.moveaxis(rr, -1, -2))
    with np.errstate(over="ignore"):
        rG = np.ldexp(sS / sM[..., None], kS - kM[..., None])
    # a mean with weights ≥ 0 lies within the range of the positions: clip the rounding of
    # the ratio back into it (particles all at 1.79e308 would otherwise round to inf, and
    # coincident particles off their common position by an ulp) (issue 16)
    rG = np.clip(rG, rr.min(axis=-2), rr.max(axis=-2))
    return _finite_result(rG, "the centre of mass")


centre_of_mass = finite_result(centre_of_mass)


def centre_of_mass_velocity(m: npt.ArrayLike, v: npt.ArrayLike) -> np.ndarray:
    """Velocity of the centre of mass v_G = Σ m_j v_j / Σ m_j (1.6).

    Domain: masses m ≥ 0 of shape (..., N), N ≥ 1 (``check_masses``: else NegativeMassError or
    ShapeError), finite vectors of shape (..., N, 3) with the same N, leading axes broadcasting
    (else ShapeError); a total mass > 0 (else ZeroTotalMassError).

    Parameters
    ----------
    m : array_like, shape (..., N)
        Masses, kg, ≥ 0, not all zero.
    v : array_like, shape (..., N, 3)
        Velocities in the fixed frame, m/s.

    Returns
    -------
    ndarray, shape (..., 3)
        The velocity v_G of the centre of mass, m/s.

    Raises
    ------
    ShapeError
        Where ``m`` is not (..., N) with N ≥ 1, ``v`` not (..., N, 3) with the same N, the
        leading axes do not broadcast, or an input is not a real numeric array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    NegativeMassError
        Where a mass is negative.
    ZeroTotalMassError
        Where all masses are 0 (the centre of mass is undefined).

    Examples
    --------
    p = m v_G (1.7), with both sides computed independently:

    >>> m, v = [2.0, 6.0], [[1.0, 0.0, 0.0], [-1.0, 2.0, 0.0]]
    >>> (total_mass(m) * centre_of_mass_velocity(m, v)).tolist(), momentum(m, v).tolist()
    ([-4.0, 12.0, 0.0], [-4.0, 12.0, 0.0])
    """
    mm, vv = _system(m, v, "v")  # errors name v, not centre_of_mass's r
    return centre_of_mass(mm, vv)


centre_of_mass_velocity = finite_result(centre_of_mass_velocity)


def momentum(m: npt.ArrayLike, v: npt.ArrayLike) -> np.ndarray:
    """Linear momentum p = Σ m_j v_j (1.3), compensated.

    Domain: masses m ≥ 0 of shape (..., N), N ≥ 1 (``check_masses``: else NegativeMassError or
    ShapeError), finite vectors of shape (..., N, 3) with the same N, leading axes broadcasting
    (else ShapeError); a result beyond float64 raises ResultOverflowError.

    Parameters
    ----------
    m : array_like, shape (..., N)
        Masses, kg, ≥ 0.
    v : array_like, shape (..., N, 3)
        Velocities in the fixed frame, m/s.

    Returns
    -------
    ndarray, shape (..., 3)
        The momentum p, kg m/s.

    Raises
    ------
    ShapeError
        Where ``m`` is not (..., N) with N ≥ 1, ``v`` not (..., N, 3) with the same N, the
        leading axes do not broadcast, or an input is not a real numeric array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    NegativeMassError
        Where a mass is negative.
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Examples
    --------
    Example 1.1: two equal balls at r_1 = −r_2 with v_2 = −v_1 have p = 0 (1.36).

    >>> v1 = np.array([0.3, -1.2, 0.0])
    >>> momentum([2.0, 2.0], [v1, -v1]).tolist()
    [0.0, 0.0, 0.0]
    """
    mm, vv = _system(m, v, "v")
    return _finite_result(_weighted_sum(mm, vv), "the momentum")


momentum = finite_result(momentum)


# ---------------------------------------------------------- angular momentum


def _offsets(r: np.ndarray, A: np.ndarray, name: str) -> np.ndarray:
    with np.errstate(over="ignore", invalid="ignore"):
        d = r - A[..., None, :]
    return _finite_result(d, f"the offsets r - {name}")


def angular_momentum(
    m: npt.ArrayLike,
    r: npt.ArrayLike,
    v: npt.ArrayLike,
    *,
    about: npt.ArrayLike,
    about_velocity: npt.ArrayLike | None = None,
) -> np.ndarray:
    """Angular momentum about the point A: L_A = Σ AP_j × m_j v_j (1.8).

    Domain: masses m ≥ 0 of shape (..., N), N ≥ 1 (``check_masses``: else NegativeMassError or
    ShapeError), finite vectors of shape (..., N, 3) with the same N, leading axes broadcasting
    (else ShapeError); finite about (and about_velocity) (..., 3); a result beyond float64 raises
    ResultOverflowError.

    Parameters
    ----------
    m : array_like, shape (..., N)
        Masses, kg, ≥ 0.
    r, v : array_like, shape (..., N, 3)
        Positions (m) and (absolute) velocities (m/s) in the fixed frame.
    about : array_like, shape (..., 3)
        The base point A, m (required: there is no default origin).
    about_velocity : array_like, shape (..., 3), optional
        Omitted (the book's definition): the absolute velocities v_j are used,
        for a fixed or a moving A alike; this L_A obeys the connection formula
        L_B = L_A + BA × p (1.46) and, for a moving base point B,
        dL_B/dt + v_B × p = M_B (1.50) (see :func:`moving_base_point_term`).
        Given as v_A: the velocities relative to A are used,
        Σ AP_j × m_j (v_j − v_A) = L_A − AG × m v_A; for A = G and v_A = v_G
        this is the book's L'_G (1.12), equal to L_G (1.15).

    Returns
    -------
    ndarray, shape (..., 3)
        L_A, kg m²/s.

    Raises
    ------
    ShapeError
        Where ``m`` is not (..., N) with N ≥ 1, ``r`` or ``v`` not (..., N, 3) with the same N,
        ``about`` or ``about_velocity`` not (..., 3), the leading axes do not broadcast, or an
        input is not a real numeric array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    NegativeMassError
        Where a mass is negative.
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Notes
    -----
    Each component, e.g. Σ_j (y_j (m_j v_zj) − z_j (m_j v_yj)) with y, z the
    components of AP_j, is one compensated dot product of length 2N.

    Examples
    --------
    The connection formula (1.46), L_B = L_A + BA × p:

    >>> m = [1.0, 2.0, 0.5]
    >>> r = [[1.0, 0.0, 0.0], [0.0, 2.0, 1.0], [-1.0, 1.0, 3.0]]
    >>> v = [[0.0, 1.0, 0.0], [1.0, 0.0, -1.0], [2.0, 2.0, 0.0]]
    >>> A, B = np.array([0.0, 0.0, 0.0]), np.array([1.0, -1.0, 2.0])
    >>> L_B = angular_momentum(m, r, v, about=B)
    >>> L_B.tolist()
    [-5.0, -3.0, -10.0]
    >>> (angular_momentum(m, r, v, about=A) + np.cross(A - B, momentum(m, v))).tolist()
    [-5.0, -3.0, -10.0]
    """
    mm, rr, vv = _system(m, r, particle_arrays=[(v, "v")])
    lead = mm.shape[:-1]
    A = _point(about, "about", lead)
    d = _offsets(rr, A, "about")
    if about_velocity is not None:
        vA = _point(about_velocity, "about_velocity", lead)
        vv = _offsets(vv, vA, "about_velocity")
    with np.errstate(over="ignore"):
        md = mm[..., None] * d
    md = _finite_result(md, "m_j AP_j")
    return _finite_result(_cross_sum(md, vv), "the angular momentum")


angular_momentum = finite_result(angular_momentum)


def angular_momentum_decomposition(
    m: npt.ArrayLike, r: npt.ArrayLike, v: npt.ArrayLike, *, about: npt.ArrayLike
) -> tuple[np.ndarray, np.ndarray]:
    """The two parts of L_A (1.12): L_A = L_G + AG × m v_G.

    Domain: masses m ≥ 0 of shape (..., N), N ≥ 1 (``check_masses``: else NegativeMassError or
    ShapeError), finite vectors of shape (..., N, 3) with the same N, leading axes broadcasting
    (else ShapeError); finite about (..., 3); a total mass > 0 (else ZeroTotalMassError); a result
    beyond float64 raises ResultOverflowError.

    Parameters
    ----------
    m : array_like, shape (..., N)
        Masses, kg, ≥ 0, not all zero.
    r, v : array_like, shape (..., N, 3)
        Positions (m) and velocities (m/s) in the fixed frame.
    about : array_like, shape (..., 3)
        The base point A, m (required: there is no default origin).

    Returns
    -------
    L_G : ndarray, shape (..., 3)
        The internal part, Σ r'_j × m_j v'_j with r'_j = r_j − r_G and
        v'_j = v_j − v_G: the book's L'_G, equal to L_G by (1.13)–(1.15).
    L_ext : ndarray, shape (..., 3)
        The external part AG × p, p = m v_G (1.7).

    Raises
    ------
    ShapeError
        Where ``m`` is not (..., N) with N ≥ 1, ``r`` or ``v`` not (..., N, 3) with the same N,
        ``about`` not (..., 3), the leading axes do not broadcast, or an input is not a real
        numeric array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    NegativeMassError
        Where a mass is negative.
    ZeroTotalMassError
        Where all masses are 0 (the centre of mass is undefined).
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Notes
    -----
    L_G is formed from centred positions *and* centred velocities: an error δ
    in the computed r_G changes it by δ × Σ m_j v'_j, which is zero, and an
    error in v_G by Σ m_j r'_j × δ, also zero.  So L_G stays accurate where the
    system is 1e8 away from the origin and L_A − AG × p would cancel.

    Examples
    --------
    The two parts add up to L_A computed directly (1.8):

    >>> m = [1.0, 2.0, 0.5]
    >>> r = [[1.0, 0.0, 0.0], [0.0, 2.0, 1.0], [-1.0, 1.0, 3.0]]
    >>> v = [[0.0, 1.0, 0.0], [1.0, 0.0, -1.0], [2.0, 2.0, 0.0]]
    >>> L_G, L_ext = angular_momentum_decomposition(m, r, v, about=[1.0, -1.0, 2.0])
    >>> (L_G + L_ext).round(12).tolist()
    [-5.0, -3.0, -10.0]
    """
    mm, rr, vv = _system(m, r, particle_arrays=[(v, "v")])
    lead = mm.shape[:-1]
    A = _point(about, "about", lead)
    rG = centre_of_mass(mm, rr)
    vG = centre_of_mass(mm, vv)
    p = _finite_result(_weighted_sum(mm, vv), "the momentum")
    d = _offsets(rr, rG, "r_G")
    w = _offsets(vv, vG, "v_G")
    L_G = _finite_result(_cross_sum(mm[..., None] * d, w), "L_G")
    with np.errstate(over="ignore", invalid="ignore"):
        L_ext = np.cross(rG - A, p)
    return L_G, _finite_result(L_ext, "AG x p")


angular_momentum_decomposition = finite_result(angular_momentum_decomposition)


def moving_base_point_term(
    m: npt.ArrayLike, v: npt.ArrayLike, *, about_velocity: npt.ArrayLike
) -> np.ndarray:
    """The extra term v_B × p of the principle for a moving base point (1.50).

    Domain: masses m ≥ 0 of shape (..., N), N ≥ 1 (``check_masses``: else NegativeMassError or
    ShapeError), finite vectors of shape (..., N, 3) with the same N, leading axes broadcasting
    (else ShapeError); finite about_velocity (..., 3); a result beyond float64 raises
    ResultOverflowError.

    dL_B/dt + v_B × p = M_B, with L_B the book's angular momentum about B
    (absolute velocities, :func:`angular_momentum` without ``about_velocity``).
    It vanishes when p = 0 or v_B ∥ v_G, in particular for B = G (1.51).

    Parameters
    ----------
    m : array_like, shape (..., N)
        Masses, kg, ≥ 0.
    v : array_like, shape (..., N, 3)
        Velocities of the particles in the fixed frame, m/s.
    about_velocity : array_like, shape (..., 3)
        The velocity v_B of the base point B, m/s.

    Returns
    -------
    ndarray, shape (..., 3)
        v_B × p, kg m²/s² (N m).

    Raises
    ------
    ShapeError
        Where ``m`` is not (..., N) with N ≥ 1, ``v`` not (..., N, 3) with the same N,
        ``about_velocity`` not (..., 3), the leading axes do not broadcast, or an input is not a
        real numeric array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    NegativeMassError
        Where a mass is negative.
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Examples
    --------
    >>> m, v = [1.0, 1.0], [[1.0, 0.0, 0.0], [1.0, 2.0, 0.0]]
    >>> moving_base_point_term(m, v, about_velocity=[0.0, 0.0, 1.0]).tolist()
    [-2.0, 2.0, 0.0]
    >>> np.cross([0.0, 0.0, 1.0], momentum(m, v)).tolist()
    [-2.0, 2.0, 0.0]
    """
    p = momentum(m, v)
    vB = _point(about_velocity, "about_velocity", p.shape[:-1])
    return _finite_result(np.cross(vB, p), "v_B x p")


moving_base_point_term = finite_result(moving_base_point_term)


def angular_momentum_rate(
    m: npt.ArrayLike,
    r: npt.ArrayLike,
    v: npt.ArrayLike,
    a: npt.ArrayLike,
    *,
    about: npt.ArrayLike,
    about_velocity: npt.ArrayLike,
) -> np.ndarray:
    """dL_B/dt of the book's L_B (1.8) for a base point B moving with velocity v_B.

    Domain: masses m ≥ 0 of shape (..., N), N ≥ 1 (``check_masses``: else NegativeMassError or
    ShapeError), finite vectors of shape (..., N, 3) with the same N, leading axes broadcasting
    (else ShapeError); finite about and about_velocity (..., 3); a result beyond float64 raises
    ResultOverflowError.

    dL_B/dt = Σ (v_j − v_B) × m_j v_j + Σ BP_j × m_j a_j = −v_B × p + Σ BP_j × m_j a_j,
    the time derivative in (1.47)–(1.50) (the term v_j × m_j v_j vanishes).

    Parameters
    ----------
    m : array_like, shape (..., N)
        Masses, kg, ≥ 0.
    r, v : array_like, shape (..., N, 3)
        Positions (m) and velocities (m/s) of the particles in the fixed frame.
    a : array_like, shape (..., N, 3)
        Accelerations of the particles, m/s².
    about, about_velocity : array_like, shape (..., 3)
        Position (m) and velocity (m/s) of B at this instant.

    Returns
    -------
    ndarray, shape (..., 3)
        dL_B/dt, kg m²/s² (N m).

    Raises
    ------
    ShapeError
        Where ``m`` is not (..., N) with N ≥ 1, ``r``, ``v`` or ``a`` not (..., N, 3) with the
        same N, ``about`` or ``about_velocity`` not (..., 3), the leading axes do not broadcast,
        or an input is not a real numeric array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    NegativeMassError
        Where a mass is negative.
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Examples
    --------
    With m_j a_j = F_j, the principle (1.50): dL_B/dt + v_B × p = M_B.

    >>> m = [2.0, 1.0]
    >>> r, v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], [[0.0, 1.0, 0.0], [3.0, 0.0, 1.0]]
    >>> F = np.array([[0.0, 0.0, 2.0], [1.0, 1.0, 0.0]])
    >>> a = F / np.array(m)[:, None]
    >>> B, vB = [0.0, 0.0, 1.0], [1.0, 1.0, 0.0]
    >>> lhs = angular_momentum_rate(m, r, v, a, about=B, about_velocity=vB)
    >>> (lhs + moving_base_point_term(m, v, about_velocity=vB)).tolist()
    [1.0, -3.0, -1.0]
    >>> moment_of_forces(r, F, about=B).tolist()
    [1.0, -3.0, -1.0]
    """
    mm, rr, vv, aa = _system(m, r, particle_arrays=[(v, "v"), (a, "a")])
    lead = mm.shape[:-1]
    B = _point(about, "about", lead)
    vB = _point(about_velocity, "about_velocity", lead)
    d = _offsets(rr, B, "about")
    with np.errstate(over="ignore"):
        ma = mm[..., None] * aa
        mv = mm[..., None] * vv
    ma = _finite_result(ma, "m_j a_j")
    # Σ (v_j − v_B) × m_j v_j = −v_B × p exactly, but is formed as one sum with
    # the force moment so that nothing cancels between separately rounded parts.
    rel = _offsets(vv, vB, "about_velocity")
    both_a = np.concatenate([d, rel], axis=-2)
    both_b = np.concatenate([ma, _finite_result(mv, "m_j v_j")], axis=-2)
    return _finite_result(_cross_sum(both_a, both_b), "dL_B/dt")


angular_momentum_rate = finite_result(angular_momentum_rate)


def moment_of_forces(r: npt.ArrayLike, F: npt.ArrayLike, *, about: npt.ArrayLike) -> np.ndarray:
    """Moment of forces F_j acting at r_j about A: M_A = Σ (r_j − r_A) × F_j (3.63).

    Domain: finite r and F of shape (..., N, 3), finite about (..., 3); a result beyond float64
    raises ResultOverflowError.

    Parameters
    ----------
    r, F : array_like, shape (..., N, 3)
        The points of application (m) and the forces (N), the same N.
    about : array_like, shape (..., 3)
        The base point A, m (required: there is no default origin).

    Returns
    -------
    ndarray, shape (..., 3)
        M_A, N m.

    Raises
    ------
    ShapeError
        Where ``r`` and ``F`` are not both (..., N, 3) with the same N, ``about`` is not
        (..., 3), the leading axes do not broadcast, or an input is not a real numeric array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Examples
    --------
    The connection formula for moments, M_B = M_A + BA × F:

    >>> r, F = [[1.0, 0.0, 0.0], [0.0, 2.0, 0.0]], [[0.0, 1.0, 0.0], [1.0, 0.0, 1.0]]
    >>> moment_of_forces(r, F, about=[0.0, 0.0, 1.0]).tolist()
    [3.0, -1.0, -1.0]
    >>> (moment_of_forces(r, F, about=[0.0, 0.0, 0.0])
    ...  + np.cross([0.0, 0.0, -1.0], np.sum(F, axis=0))).tolist()
    [3.0, -1.0, -1.0]
    """
    rr = as_float_array(r, "r", (3,))
    FF = as_float_array(F, "F", (3,))
    if rr.ndim < 2 or FF.ndim < 2 or rr.shape[-2] != FF.shape[-2]:
        raise ShapeError(
            f"r and F must both have shape (..., N, 3) with the same N; got {rr.shape} "
            f"and {FF.shape}"
        )
    try:
        lead = np.broadcast_shapes(rr.shape[:-2], FF.shape[:-2])
    except ValueError:
        raise ShapeError(
            f"leading axes of r {rr.shape} and F {FF.shape} do not broadcast"
        ) from None
    A = _point(about, "about", lead)
    d = _offsets(rr, A, "about")
    return _finite_result(_cross_sum(d, FF), "the moment")


moment_of_forces = finite_result(moment_of_forces)


def _pair_forces(f: npt.ArrayLike) -> np.ndarray:
    ff = as_float_array(f, "f", (3,))
    if ff.ndim < 3 or ff.shape[-3] != ff.shape[-2]:
        raise ShapeError(f"f has shape {ff.shape}; expected (..., N, N, 3) (f[k, j] = f_kj)")
    return ff


def internal_forces(f: npt.ArrayLike) -> np.ndarray:
    """Internal force on each particle, F^i_k = Σ_j f_kj (1.18).

    Domain: finite f of shape (..., N, N, 3) (f[k, j] the force on k from j; any, Newton's third law
    is not required); a result beyond float64 raises ResultOverflowError.

    Parameters
    ----------
    f : array_like, shape (..., N, N, 3)
        f[..., k, j, :] is the force on k from j.

    Returns
    -------
    ndarray, shape (..., N, 3)
        F^i_k, the resultant internal force on each particle k, N.

    Raises
    ------
    ShapeError
        Where ``f`` is not (..., N, N, 3), or not a real numeric array.
    NonFiniteError
        Where ``f`` holds NaN or an infinity.
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Examples
    --------
    With Newton's third law the internal forces add up to zero (1.23):

    >>> f = np.zeros((2, 2, 3)); f[0, 1] = [1.0, 2.0, 0.0]; f[1, 0] = -f[0, 1]
    >>> internal_forces(f).sum(axis=0).tolist()
    [0.0, 0.0, 0.0]
    """
    ff = _pair_forces(f)
    return _finite_result(_sum(np.moveaxis(ff, -2, -1)), "the internal forces")


internal_forces = finite_result(internal_forces)


def internal_moment(r: npt.ArrayLike, f: npt.ArrayLike) -> np.ndarray:
    """The moment of the internal forces, M^i = ½ Σ_kj r_jk × f_jk (1.31).

    Domain: finite r (..., N, 3) and f (..., N, N, 3) with the same N (else ShapeError); a result
    beyond float64 raises ResultOverflowError.

    Equal to Σ_j AP_j × F^i_j about any A when f obeys Newton's third law
    (1.28)–(1.31); zero when, in addition, each f_jk ∥ r_jk (central forces).

    Parameters
    ----------
    r : array_like, shape (..., N, 3)
        Positions of the particles, m.
    f : array_like, shape (..., N, N, 3)
        Pair forces, N: f[..., k, j, :] is the force on k from j.

    Returns
    -------
    ndarray, shape (..., 3)
        M^i, N m.

    Raises
    ------
    ShapeError
        Where ``r`` is not (..., N, 3) or ``f`` not (..., N, N, 3) with the same N, the
        leading axes do not broadcast, or an input is not a real numeric array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Examples
    --------
    A non-central pair (figure 1.2, right) has a non-zero internal moment, equal
    to the moment of the internal forces about the origin:

    >>> r = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
    >>> f = np.zeros((2, 2, 3)); f[1, 0] = [0.0, 1.0, 0.0]; f[0, 1] = -f[1, 0]
    >>> internal_moment(r, f).tolist()
    [0.0, 0.0, 1.0]
    >>> moment_of_forces(r, internal_forces(f), about=[0.0, 0.0, 0.0]).tolist()
    [0.0, 0.0, 1.0]
    """
    rr = as_float_array(r, "r", (3,))
    ff = _pair_forces(f)
    if rr.ndim < 2 or rr.shape[-2] != ff.shape[-2]:
        raise ShapeError(f"r has shape {rr.shape} but f has shape {ff.shape}: N must agree")
    with np.errstate(over="ignore", invalid="ignore"):
        rjk = rr[..., :, None, :] - rr[..., None, :, :]
    rjk = _finite_result(rjk, "r_jk")
    n = rr.shape[-2]
    a = rjk.reshape(*rjk.shape[:-3], n * n, 3)
    b = ff.reshape(*ff.shape[:-3], n * n, 3)
    return _finite_result(0.5 * _cross_sum(a, b), "the internal moment")


internal_moment = finite_result(internal_moment)


# --------------------------------------------------------------- kinetic energy


def kinetic_energy(m: npt.ArrayLike, v: npt.ArrayLike) -> np.ndarray:
    """Kinetic energy T = ½ Σ m_j v_j · v_j (3.2), compensated.

    Domain: masses m ≥ 0 of shape (..., N), N ≥ 1 (``check_masses``: else NegativeMassError or
    ShapeError), finite vectors of shape (..., N, 3) with the same N, leading axes broadcasting
    (else ShapeError); a result beyond float64 raises ResultOverflowError.

    Parameters
    ----------
    m : array_like, shape (..., N)
        Masses, kg, ≥ 0.
    v : array_like, shape (..., N, 3)
        Velocities in the fixed (inertial) frame, m/s.

    Returns
    -------
    ndarray, shape (...)
        T, J.

    Raises
    ------
    ShapeError
        Where ``m`` is not (..., N) with N ≥ 1, ``v`` not (..., N, 3) with the same N, the
        leading axes do not broadcast, or an input is not a real numeric array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    NegativeMassError
        Where a mass is negative.
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Examples
    --------
    Koenig's theorem (3.7): T = T' + ½ m v_G².

    >>> m, v = [1.0, 3.0], [[2.0, 0.0, 0.0], [0.0, 2.0, 0.0]]
    >>> float(kinetic_energy(m, v))
    8.0
    >>> T_G, T_cm = kinetic_energy_decomposition(m, v)
    >>> float(T_G + T_cm)
    8.0
    """
    mm, vv = _system(m, v, "v")
    with np.errstate(over="ignore"):
        v2 = vv * vv
    v2 = _finite_result(v2, "v_j^2")
    T = 0.5 * _dot(np.repeat(mm, 3, axis=-1), v2.reshape(*v2.shape[:-2], -1))
    return _finite_result(T, "the kinetic energy")


kinetic_energy = finite_result(kinetic_energy)


def kinetic_energy_decomposition(
    m: npt.ArrayLike, v: npt.ArrayLike
) -> tuple[np.ndarray, np.ndarray]:
    """The two parts of the kinetic energy (3.7): T = T' + ½ m v_G².

    Domain: masses m ≥ 0 of shape (..., N), N ≥ 1 (``check_masses``: else NegativeMassError or
    ShapeError), finite vectors of shape (..., N, 3) with the same N, leading axes broadcasting
    (else ShapeError); a total mass > 0 (else ZeroTotalMassError); a result beyond float64 raises
    ResultOverflowError.

    Parameters
    ----------
    m : array_like, shape (..., N)
        Masses, kg, ≥ 0, not all zero.
    v : array_like, shape (..., N, 3)
        Velocities in the fixed (inertial) frame, m/s.

    Returns
    -------
    T_G : ndarray, shape (...)
        The internal part T' = ½ Σ m_j |v_j − v_G|², from centred velocities
        (accurate where T − ½ m v_G² would cancel, e.g. a system moving at
        1e8 with internal speeds of 1).
    T_cm : ndarray, shape (...)
        ½ m v_G², the translation of the centre of mass.

    Raises
    ------
    ShapeError
        Where ``m`` is not (..., N) with N ≥ 1, ``v`` not (..., N, 3) with the same N, the
        leading axes do not broadcast, or an input is not a real numeric array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    NegativeMassError
        Where a mass is negative.
    ZeroTotalMassError
        Where all masses are 0 (the centre of mass is undefined).
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Examples
    --------
    >>> m, v = [1.0, 1.0], [[1e8 + 1.0, 0.0, 0.0], [1e8 - 1.0, 0.0, 0.0]]
    >>> [float(x) for x in kinetic_energy_decomposition(m, v)]
    [1.0, 1e+16]
    """
    mm, vv = _system(m, v, "v")
    M = _sum(mm)
    vG = centre_of_mass(mm, vv)
    w = _offsets(vv, vG, "v_G")
    T_G = kinetic_energy(mm, w)
    with np.errstate(over="ignore"):
        T_cm = 0.5 * M * _sum(vG * vG)
    return T_G, _finite_result(T_cm, "1/2 m v_G^2")


kinetic_energy_decomposition = finite_result(kinetic_energy_decomposition)


# ------------------------------------------------- fixed direction, cylindrical


def _unit(axis: npt.ArrayLike, lead: tuple[int, ...]) -> np.ndarray:
    e = _point(axis, "axis", lead)
    norm = np.sqrt(np.sum(np.ldexp(e, -_exponent(e)) ** 2, axis=-1, keepdims=True))
    zero = ~e.any(axis=-1)
    if zero.any():
        raise ZeroAxisError(f"axis = {e[*_first_index(zero)].tolist()} has zero length")
    out: np.ndarray = np.ldexp(e, -_exponent(e)) / norm
    return out


def axial_component(x: npt.ArrayLike, *, axis: npt.ArrayLike) -> np.ndarray:
    """The component x · e of a vector along the fixed direction e (1.65).

    Domain: finite x (..., 3) and a nonzero axis (..., 3) (else ZeroAxisError); a result beyond
    float64 raises ResultOverflowError.

    ``axis`` need not be unit: it is normalised.

    Parameters
    ----------
    x : array_like, shape (..., 3)
        The vector (any unit).
    axis : array_like, shape (..., 3)
        The direction e, nonzero, any length.

    Returns
    -------
    ndarray, shape (...)
        x · e/|e|, in the unit of ``x``.

    Raises
    ------
    ShapeError
        Where ``x`` or ``axis`` is not (..., 3), their leading axes do not broadcast, or an
        input is not a real numeric array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    ZeroAxisError
        Where ``axis`` is the zero vector.
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Examples
    --------
    >>> float(axial_component([1.0, 2.0, 3.0], axis=[0.0, 0.0, 5.0]))
    3.0
    """
    xx = as_float_array(x, "x", (3,))
    e = _unit(axis, xx.shape[:-1])
    out: np.ndarray = np.sum(xx * e, axis=-1)
    return out


axial_component = finite_result(axial_component)


class Cylindrical(NamedTuple):
    """Cylindrical coordinates and their rates (ρ, ϕ, z, ρ̇, ϕ̇, ż) of (1.68).

    The result of :func:`cylindrical_components`, a named tuple: it unpacks as
    ``rho, phi, z, rhodot, phidot, zdot = c``.  The constructor checks nothing.

    Parameters
    ----------
    rho : ndarray, shape (...)
        Distance ρ from the axis, m.
    phi : ndarray, shape (...)
        Azimuth ϕ about the axis, rad, in [−π, π].
    z : ndarray, shape (...)
        Coordinate along the axis, from the base point, m.
    rhodot, phidot, zdot : ndarray, shape (...)
        The rates ρ̇ (m/s), ϕ̇ (rad/s) and ż (m/s).

    Examples
    --------
    The speed from the rates, v² = ρ̇² + ρ² ϕ̇² + ż²:

    >>> v = [-1.0, 7.0, 1.0]
    >>> c = cylindrical_components([3.0, 4.0, 0.0], v, about=[0, 0, 0], axis=[0, 0, 1])
    >>> float(c.rhodot**2 + c.rho**2 * c.phidot**2 + c.zdot**2), float(np.dot(v, v))
    (51.0, 51.0)
    """

    rho: np.ndarray
    phi: np.ndarray
    z: np.ndarray
    rhodot: np.ndarray
    phidot: np.ndarray
    zdot: np.ndarray


def _reference_direction(e: np.ndarray) -> np.ndarray:
    """The direction from which ϕ is measured: e_x for e = e_z (the book's choice);
    in general the coordinate axis least aligned with e, with its e-part removed."""
    idx = np.argmin(np.abs(e), axis=-1)
    c = np.zeros_like(e)
    np.put_along_axis(c, idx[..., None], 1.0, axis=-1)
    c = c - np.sum(c * e, axis=-1, keepdims=True) * e
    out: np.ndarray = c / np.linalg.norm(c, axis=-1, keepdims=True)
    return out


def cylindrical_components(
    r: npt.ArrayLike, v: npt.ArrayLike, *, about: npt.ArrayLike, axis: npt.ArrayLike
) -> Cylindrical:
    """Cylindrical coordinates of points about the axis through A along e (1.68).

    Domain: finite r, v (..., 3), about (..., 3), a nonzero axis (else ZeroAxisError); no point on
    the axis (ρ = 0: else OutOfDomainError, φ is undefined); a result beyond float64 raises
    ResultOverflowError.

    Parameters
    ----------
    r, v : array_like, shape (..., 3)
        Positions (m) and velocities (m/s).
    about : array_like, shape (..., 3)
        A point A on the axis, m (the book puts the origin there).
    axis : array_like, shape (..., 3)
        The fixed direction e_z, nonzero (normalised here).

    Returns
    -------
    Cylindrical
        ρ, ϕ, z and ρ̇, ϕ̇, ż.  ϕ is measured from e_x when e = e_z; for another
        axis from the coordinate axis least aligned with e, projected on the
        plane normal to e, positive by the right-hand rule about e.

    Raises
    ------
    ShapeError
        Where ``r``, ``v``, ``about`` or ``axis`` is not (..., 3), their leading axes do not
        broadcast, or an input is not a real numeric array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    ZeroAxisError
        Where ``axis`` is the zero vector.
    OutOfDomainError
        For a point on the axis (ρ = 0), where ϕ and ϕ̇ are undefined.
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Examples
    --------
    (1.68): (r × v) · e_z = ρ² ϕ̇.

    >>> c = cylindrical_components([1.0, 1.0, 2.0], [0.0, 3.0, 1.0],
    ...                            about=[0.0, 0.0, 0.0], axis=[0.0, 0.0, 1.0])
    >>> float(c.rho ** 2 * c.phidot), float(np.cross([1.0, 1.0, 2.0], [0.0, 3.0, 1.0])[2])
    (3.0, 3.0)
    """
    rr = as_float_array(r, "r", (3,))
    vv = as_float_array(v, "v", (3,))
    try:
        lead = np.broadcast_shapes(rr.shape[:-1], vv.shape[:-1])
    except ValueError:
        raise ShapeError(f"r {rr.shape} and v {vv.shape} do not broadcast") from None
    A = _point(about, "about", lead)
    e = _unit(axis, lead)
    d = rr - A
    z = np.sum(d * e, axis=-1)
    zdot = np.sum(vv * e, axis=-1)
    ex = _reference_direction(np.broadcast_to(e, np.broadcast_shapes(e.shape, d.shape)))
    ey = np.cross(e, ex)
    x, y = np.sum(d * ex, axis=-1), np.sum(d * ey, axis=-1)
    xdot, ydot = np.sum(vv * ex, axis=-1), np.sum(vv * ey, axis=-1)
    rho = np.hypot(x, y)
    on_axis = rho == 0
    if on_axis.any():
        raise OutOfDomainError(
            f"point {np.broadcast_to(rr, d.shape)[_first_index(on_axis)].tolist()} lies on the "
            "axis (rho = 0): phi and phidot are undefined there"
        )
    phi = np.arctan2(y, x)
    rhodot = (x * xdot + y * ydot) / rho
    phidot = (x * ydot - y * xdot) / rho / rho  # not / rho**2: that underflows at rho ~ 1e-160
    return Cylindrical(rho, phi, z, rhodot, phidot, zdot)


cylindrical_components = finite_result(cylindrical_components)


def moment_of_inertia_about_axis(
    m: npt.ArrayLike, r: npt.ArrayLike, *, about: npt.ArrayLike, axis: npt.ArrayLike
) -> np.ndarray:
    """J_z = Σ m_j ρ_j² (1.71), ρ_j the distance of particle j from the axis.

    Domain: masses m ≥ 0 of shape (..., N), N ≥ 1 (``check_masses``: else NegativeMassError or
    ShapeError), finite vectors of shape (..., N, 3) with the same N, leading axes broadcasting
    (else ShapeError); finite about (..., 3), a nonzero axis (else ZeroAxisError); a result beyond
    float64 raises ResultOverflowError.

    Parameters
    ----------
    m : array_like, shape (..., N)
        Masses, kg, ≥ 0.
    r : array_like, shape (..., N, 3)
        Positions, m.
    about : array_like, shape (..., 3)
        A point A on the axis, m.
    axis : array_like, shape (..., 3)
        The direction e of the axis, nonzero (normalised here).

    Returns
    -------
    ndarray, shape (...)
        J_z, kg m².

    Raises
    ------
    ShapeError
        Where ``m`` is not (..., N) with N ≥ 1, ``r`` not (..., N, 3) with the same N, ``about``
        or ``axis`` not (..., 3), the leading axes do not broadcast, or an input is not a real
        numeric array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    NegativeMassError
        Where a mass is negative.
    ZeroAxisError
        Where ``axis`` is the zero vector.
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Examples
    --------
    >>> float(moment_of_inertia_about_axis([2.0, 1.0], [[1.0, 0.0, 5.0], [0.0, 3.0, 0.0]],
    ...                                    about=[0.0, 0.0, 0.0], axis=[0.0, 0.0, 1.0]))
    11.0
    """
    mm, rr = _system(m, r)
    lead = mm.shape[:-1]
    A = _point(about, "about", lead)
    e = _unit(axis, lead)[..., None, :]
    d = _offsets(rr, A, "about")
    perp = d - np.sum(d * e, axis=-1, keepdims=True) * e
    rho2 = np.sum(perp * perp, axis=-1)
    return _finite_result(_dot(mm, rho2), "J_z")


moment_of_inertia_about_axis = finite_result(moment_of_inertia_about_axis)


def average_angular_velocity(
    m: npt.ArrayLike,
    r: npt.ArrayLike,
    v: npt.ArrayLike,
    *,
    about: npt.ArrayLike,
    axis: npt.ArrayLike,
) -> np.ndarray:
    """ω_av = Σ m_j ρ_j² ϕ̇_j / Σ m_j ρ_j² = L_Az / J_z (1.70), (1.72).

    Domain: masses m ≥ 0 of shape (..., N), N ≥ 1 (``check_masses``: else NegativeMassError or
    ShapeError), finite vectors of shape (..., N, 3) with the same N, leading axes broadcasting
    (else ShapeError); finite about, a nonzero axis; J_z > 0 (not all mass on the axis: else
    OutOfDomainError); a result beyond float64 raises ResultOverflowError.

    Parameters
    ----------
    m : array_like, shape (..., N)
        Masses, kg, ≥ 0, not all on the axis.
    r, v : array_like, shape (..., N, 3)
        Positions (m) and velocities (m/s) in the fixed frame.
    about : array_like, shape (..., 3)
        A point A on the axis, m.
    axis : array_like, shape (..., 3)
        The direction e_z of the fixed axis, nonzero (normalised here).

    Returns
    -------
    ndarray, shape (...)
        ω_av, rad/s, positive by the right-hand rule about ``axis``.

    Raises
    ------
    ShapeError
        Where ``m`` is not (..., N) with N ≥ 1, ``r`` or ``v`` not (..., N, 3) with the same N,
        ``about`` or ``axis`` not (..., 3), the leading axes do not broadcast, or an input is
        not a real numeric array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    NegativeMassError
        Where a mass is negative.
    ZeroAxisError
        Where ``axis`` is the zero vector.
    OutOfDomainError
        Where J_z = 0: all mass on the axis, or J_z below float64's range (ρ_j ≲ 1e-162).
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Examples
    --------
    A rigid rotation ϕ̇ = 2 about e_z gives ω_av = 2 (1.75):

    >>> r = np.array([[1.0, 0.0, 0.0], [0.0, -2.0, 1.0]])
    >>> v = np.cross([0.0, 0.0, 2.0], r)
    >>> float(average_angular_velocity([1.0, 3.0], r, v, about=[0, 0, 0], axis=[0, 0, 1]))
    2.0
    """
    mm, rr, vv = _system(m, r, particle_arrays=[(v, "v")])
    lead = mm.shape[:-1]
    Jz = moment_of_inertia_about_axis(mm, rr, about=about, axis=axis)
    zero = Jz == 0
    if zero.any():
        raise OutOfDomainError(
            f"J_z = 0 at index {_first_index(zero)}: all mass is on the axis, omega_av is undefined"
        )
    L = angular_momentum(mm, rr, vv, about=about)
    out: np.ndarray = axial_component(L, axis=np.broadcast_to(_unit(axis, lead), L.shape)) / Jz
    return out


average_angular_velocity = finite_result(average_angular_velocity)


# ------------------------------------------------------ continuous distributions


def masses_from_density(rho: npt.ArrayLike, *, cell_volume: npt.ArrayLike) -> np.ndarray:
    """Masses dm = ρ dV of a density sampled at the centres of equal cells (1.62–1.64).

    Domain: finite rho ≥ 0 of shape (..., N) (else NegativeMassError), a scalar cell_volume > 0
    (else NonPositiveParameterError); a result beyond float64 raises ResultOverflowError.

    The continuous distributions of section 1.4 are handled as particle systems
    by the midpoint rule: ρ sampled at the centre of each cell of volume dV
    (or length, or area), m_j = ρ_j dV.  The integrals (1.62)–(1.64) of a
    smooth density over a box become the sums of this module with an error
    O(h²) in the cell size h; they are exact for the centre of mass of a
    density that is constant on the cells (a uniform body made of cells).

    Parameters
    ----------
    rho : array_like, shape (..., N)
        Density at the cell centres, ≥ 0: kg/m³ (kg/m², kg/m for areas and lines).
    cell_volume : float
        The volume dV of each cell, > 0: m³ (m², m).

    Returns
    -------
    ndarray, shape (..., N)
        The masses m_j = ρ_j dV, kg.

    Raises
    ------
    ShapeError
        Where ``rho`` is not (..., N) with N ≥ 1, ``cell_volume`` is not a scalar, or an
        input is not a real numeric array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    NegativeMassError
        For a negative density sample.
    NonPositiveParameterError
        For ``cell_volume`` ≤ 0.
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Examples
    --------
    A uniform rod of length 2 sampled in 4 cells:

    >>> masses_from_density([3.0] * 4, cell_volume=0.5).tolist()
    [1.5, 1.5, 1.5, 1.5]
    """
    dVa = as_float_array(cell_volume, "cell_volume")
    if dVa.shape != ():
        raise ShapeError(f"cell_volume must be a scalar; got shape {dVa.shape}")
    dV = float(dVa)
    if not dV > 0:
        raise NonPositiveParameterError(f"cell_volume = {cell_volume!r} must be > 0")
    return check_masses(rho, "rho") * dV


masses_from_density = finite_result(masses_from_density)


def continuous_centre_of_mass(
    rho: npt.ArrayLike, points: npt.ArrayLike, *, cell_volume: npt.ArrayLike
) -> np.ndarray:
    """r_G = ∫ r ρ dV / ∫ ρ dV (1.62) by the midpoint rule on equal cells.

    Domain: rho and cell_volume as :func:`masses_from_density`, finite points (..., N, 3); rho not
    zero everywhere (else ZeroTotalMassError).

    Parameters
    ----------
    rho : array_like, shape (..., N)
        Density at the cell centres, ≥ 0, not zero everywhere (as :func:`masses_from_density`).
    points : array_like, shape (..., N, 3)
        The cell centres, m.
    cell_volume : float
        The volume dV of each cell, > 0 (as :func:`masses_from_density`).

    Returns
    -------
    ndarray, shape (..., 3)
        r_G, m.

    Raises
    ------
    ShapeError
        Where ``rho`` is not (..., N) with N ≥ 1, ``points`` not (..., N, 3) with the same N,
        ``cell_volume`` not a scalar, the leading axes do not broadcast, or an input is not a
        real numeric array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    NegativeMassError
        For a negative density sample.
    NonPositiveParameterError
        For ``cell_volume`` ≤ 0.
    ZeroTotalMassError
        Where ``rho`` is zero everywhere.
    ResultOverflowError
        Where a mass ρ_j dV is beyond float64 (~1.8e308).

    Examples
    --------
    A rod on [0, 2] with density ρ(x) = x: r_G = ∫x² dx / ∫x dx = (8/3)/2 = 4/3.
    The midpoint rule is exact for the mass ∫x dx and errs by −h²/6 on ∫x² dx,
    so 1000 cells (h = 0.002) give r_G within 4e-7:

    >>> n = 1000
    >>> x = (np.arange(n) + 0.5) * (2.0 / n)
    >>> pts = np.stack([x, 0 * x, 0 * x], axis=-1)
    >>> rG = continuous_centre_of_mass(x, pts, cell_volume=2.0 / n)
    >>> bool(abs(rG[0] - 4 / 3) < 4e-7)
    True
    """
    mm, pp = _system(masses_from_density(rho, cell_volume=cell_volume), points, "points")
    if not (mm.sum(axis=-1) > 0).all():
        raise ZeroTotalMassError(
            "rho is zero everywhere: the total mass is 0 and the centre of "
            "mass of a massless body is undefined"
        )
    return centre_of_mass(mm, pp)


continuous_centre_of_mass = finite_result(continuous_centre_of_mass)


def continuous_momentum(
    rho: npt.ArrayLike, velocity: npt.ArrayLike, *, cell_volume: npt.ArrayLike
) -> np.ndarray:
    """p = ∫ v ρ dV (1.63) by the midpoint rule on equal cells.

    Domain: rho and cell_volume as :func:`masses_from_density`, finite velocity (..., N, 3); a
    result beyond float64 raises ResultOverflowError.

    Parameters
    ----------
    rho : array_like, shape (..., N)
        Density at the cell centres, ≥ 0 (as :func:`masses_from_density`).
    velocity : array_like, shape (..., N, 3)
        The velocity at the cell centres, m/s.
    cell_volume : float
        The volume dV of each cell, > 0 (as :func:`masses_from_density`).

    Returns
    -------
    ndarray, shape (..., 3)
        p, kg m/s.

    Raises
    ------
    ShapeError
        Where ``rho`` is not (..., N) with N ≥ 1, ``velocity`` not (..., N, 3) with the same
        N, ``cell_volume`` not a scalar, the leading axes do not broadcast, or an input is not
        a real numeric array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    NegativeMassError
        For a negative density sample.
    NonPositiveParameterError
        For ``cell_volume`` ≤ 0.
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Examples
    --------
    A uniform disc of mass 1 turning rigidly about its centre has p = 0:

    >>> g = (np.arange(40) + 0.5) / 20 - 1
    >>> X, Y = np.meshgrid(g, g)
    >>> inside = X**2 + Y**2 <= 1
    >>> pts = np.stack([X[inside], Y[inside], 0 * X[inside]], axis=-1)
    >>> vel = np.cross([0.0, 0.0, 3.0], pts)
    >>> bool(np.abs(continuous_momentum(np.ones(len(pts)), vel, cell_volume=0.0025)).max() < 1e-13)
    True
    """
    mm, vv = _system(masses_from_density(rho, cell_volume=cell_volume), velocity, "velocity")
    return momentum(mm, vv)


continuous_momentum = finite_result(continuous_momentum)


def continuous_angular_momentum(
    rho: npt.ArrayLike,
    points: npt.ArrayLike,
    velocity: npt.ArrayLike,
    *,
    cell_volume: npt.ArrayLike,
    about: npt.ArrayLike,
) -> np.ndarray:
    """L_A = ∫ (r − r_A) × v ρ dV (1.64) by the midpoint rule on equal cells.

    Domain: rho and cell_volume as :func:`masses_from_density`, finite points and velocity (..., N,
    3), finite about (..., 3); a result beyond float64 raises ResultOverflowError.

    Parameters
    ----------
    rho : array_like, shape (..., N)
        Density at the cell centres, ≥ 0 (as :func:`masses_from_density`).
    points, velocity : array_like, shape (..., N, 3)
        The cell centres (m) and the velocity there (m/s).
    cell_volume : float
        The volume dV of each cell, > 0 (as :func:`masses_from_density`).
    about : array_like, shape (..., 3)
        The base point A, m (required: there is no default origin).

    Returns
    -------
    ndarray, shape (..., 3)
        L_A, kg m²/s.

    Raises
    ------
    ShapeError
        Where ``rho`` is not (..., N) with N ≥ 1, ``points`` or ``velocity`` not (..., N, 3)
        with the same N, ``cell_volume`` not a scalar, ``about`` not (..., 3), the leading
        axes do not broadcast, or an input is not a real numeric array.
    NonFiniteError
        Where an input holds NaN or an infinity.
    NegativeMassError
        For a negative density sample.
    NonPositiveParameterError
        For ``cell_volume`` ≤ 0.
    ResultOverflowError
        Where the result, or an intermediate, is beyond float64 (~1.8e308).

    Examples
    --------
    A uniform rod of mass 1 and length 2 spinning at ω about its centre:
    L = J ω with J = m ℓ²/12 = 1/3, up to the midpoint rule's O(h²):

    >>> n = 2000
    >>> x = (np.arange(n) + 0.5) * (2.0 / n) - 1.0
    >>> pts = np.stack([x, 0 * x, 0 * x], axis=-1)
    >>> vel = np.cross([0.0, 0.0, 3.0], pts)
    >>> L = continuous_angular_momentum(np.full(n, 0.5), pts, vel, cell_volume=2.0 / n,
    ...                                 about=[0.0, 0.0, 0.0])
    >>> bool(abs(L[2] - 3.0 / 3.0) < 1e-6)
    True
    """
    m = masses_from_density(rho, cell_volume=cell_volume)
    mm, pp, vv = _system(m, points, "points", particle_arrays=((velocity, "velocity"),))
    return angular_momentum(mm, pp, vv, about=about)


continuous_angular_momentum = finite_result(continuous_angular_momentum)
