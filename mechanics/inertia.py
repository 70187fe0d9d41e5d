"""The inertia tensor: of particle systems and homogeneous bodies, shifted and rotated.

Conventions (Essén 1996, ch. 4.1)
---------------------------------
- **A tensor is about a named point, in a named basis.**  ``J_G`` is the inertia
  tensor about the centre of mass G, ``J_C`` about a point C; a suffix ``_A`` or
  ``_O`` on a matrix names the basis of its components where it matters
  (``J_A``: body basis A, ``J_O``: observer basis O).  Functions that need a
  point take it as a required keyword (``inertia_tensor(m, r, about=C)``).
- The matrix is the book's (4.6), (4.34), (4.37): J = J_S 1 − D with
  J_S = Σ m |r|² (4.35) and D_kl = Σ m x_k x_l (4.36), so the diagonal holds the
  moments of inertia J_x = Σ m (y² + z²) and the off-diagonal entries are *minus*
  the products of inertia, J_xy = −D_xy (3.17).  L = J ω (4.12).
- **Rotation matrices are passive**, as in :mod:`mechanics.rotation`: ``R_A_O``
  is ^A R^O, rows = the basis vectors e^A_i in O components.  (4.11):
  J^O = ^O R^A J^A ^A R^O = R_A_Oᵀ J_A R_A_O (:func:`rotate_inertia`).
- **Principal axes** (4.13)–(4.14): :func:`principal_axes` returns the moments
  J1 ≤ J2 ≤ J3 (ascending) and the proper rotation ``R_A_O`` whose rows are the
  principal axes, so that J_O = R_A_Oᵀ diag(J1, J2, J3) R_A_O.  For coincident
  moments only the eigen-*subspace* is defined: compare
  :func:`principal_subspaces` (orthogonal projectors), not individual axes.
- The homogeneous bodies (:func:`rod`, :func:`disc`, ...) are about G in their
  principal basis, with the symmetry axis (if any) along e3.
- Everything is float64 and vectorised over leading axes: masses ``(...)`` or
  ``(..., N)``, vectors ``(..., 3)``, tensors ``(..., 3, 3)``.

Physical tensors
----------------
A real mass distribution has a symmetric, positive semidefinite J whose
principal moments obey the triangle inequality J1 + J2 ≥ J3 about *every*
point (in the principal basis at that point J1 + J2 − J3 = 2 Σ m x3² ≥ 0).
:func:`check_inertia` checks those three conditions and raises
:class:`~mechanics.errors.NonPhysicalInertiaError` naming the failed one and by
how much; it never repairs.  A zero moment occurs only for an ideal line mass
(the thin :func:`rod`: J = diag(J, J, 0)) or a point; pass
``allow_singular=True`` to accept those.

Accuracy (``tests/stability/test_inertia_stability.py``, mpmath at 50 digits)
------------------------------------------------------------------------------
- :func:`parallel_axis` and the shift in :func:`inertia_tensor` are computed
  with error-free products and sums (Dekker/Knuth), so each entry of J_C is
  within 1 ulp of the exact J_G + m(|d|² 1 − d dᵀ) of the float inputs (measured
  worst 0.50 ulp: correctly rounded in practice), even where the shift and J_G
  cancel in an off-diagonal entry.  At offset/size 1e8 the shift dominates J_G
  by 1e16, so J_G lies below half an ulp of the result: accuracy there means
  that the shift itself is right to the last bit (J_G cannot be recovered from
  J_C in float64; keep J_G).  Entries whose products m d_i d_j are subnormal
  have only float64's absolute precision there.
- :func:`principal_axes` is a cyclic Jacobi method, vectorised over the batch:
  moments within 8 eps of J3 of the exact eigenvalues of the float tensor
  (measured worst 1.2 eps; ``numpy.linalg.eigh`` differs from them by up to
  8 eps), axes orthonormal to 8 eps, projectors onto eigen-subspaces within
  16 eps·J3/gap (measured 4.4), near-degenerate, flat and thin tensors included.
- Speed (``tests/benchmarks/test_bench_inertia.py``, 10^5 tensors): 0.37 s,
  0.85 of the time of ``numpy.linalg.eigh`` (0.44 s), validation included.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np
import numpy.typing as npt

from ._floats import dd_add as _dd_add
from ._floats import dd_times as _dd_times
from ._floats import two_prod as _two_prod
from ._floats import two_sum as _two_sum
from ._validate import as_float_array, as_float_scalar, broadcast_checked, finite_result
from .errors import (
    NegativeMassError,
    NonPhysicalInertiaError,
    NonPositiveParameterError,
    ResultOverflowError,
    ShapeError,
    ZeroTotalMassError,
)
from .rotation import EPS, check_rotation

__all__ = [
    "INERTIA_ATOL",
    "SUBSPACE_RTOL",
    "box",
    "check_inertia",
    "cylinder",
    "cylindrical_shell",
    "disc",
    "four_particle_realisation",
    "hollow_sphere",
    "inertia_A_from_O",
    "inertia_tensor",
    "is_physical_inertia",
    "parallel_axis",
    "principal_axes",
    "principal_subspaces",
    "rectangular_plate",
    "ring",
    "rod",
    "rotate_inertia",
    "solid_cone",
    "solid_sphere",
]

#: Tolerance of :func:`check_inertia`, relative to the largest principal moment
#: (the trace bounds it): asymmetry max |J − Jᵀ|, a negative smallest moment and
#: a violation of J1 + J2 ≥ J3.  A physical tensor that went through a rotation
#: (4.11) or a shift (4.38) in float64 is off by a few eps of ‖J‖ (each entry is
#: a sum of up to nine rounded products), and the moments computed from it carry
#: an error of a few eps of ‖J‖ again; 64 eps accepts such a tensor and rejects
#: any violation visible at 1.5e-14 of its size.
INERTIA_ATOL = 64 * EPS

#: Default of :func:`principal_subspaces`: principal moments whose gap is below
#: √eps = 2**-26 of the largest moment are treated as coincident.  An axis is
#: determined to about eps·‖J‖/gap, so every projector returned is accurate to
#: about √eps or better; a smaller threshold would separate axes that rounding
#: has already mixed.
SUBSPACE_RTOL = 2.0**-26

_JACOBI_MAX_SWEEPS = 16  # quadratic convergence: 3x3 tensors need 3 to 6 sweeps


# ------------------------------------------------------------------- validation


def _mass(m: npt.ArrayLike, name: str = "m", *, positive: bool = False) -> np.ndarray:
    a = as_float_array(m, name)
    if (a < 0).any():
        bad = a[a < 0].flat[0]
        raise NegativeMassError(f"{name} must be >= 0; found {float(bad)!r}")
    if positive and (a == 0).any():
        raise NonPositiveParameterError(f"{name} must be > 0; found 0.0")
    return a


def _length(x: npt.ArrayLike, name: str, *, allow_zero: bool = False) -> np.ndarray:
    a = as_float_array(x, name)
    bad = (a < 0) if allow_zero else (a <= 0)
    if bad.any():
        cond = ">= 0" if allow_zero else "> 0"
        raise NonPositiveParameterError(f"{name} must be {cond}; found {float(a[bad].flat[0])!r}")
    return a


def _finite_result(a: np.ndarray, what: str) -> np.ndarray:
    if not np.isfinite(a).all():
        raise ResultOverflowError(
            f"{what} overflows float64 (finite inputs, result beyond 1.8e308)"
        )
    return a


def _check_symmetric(J: np.ndarray, name: str) -> np.ndarray:
    """Reject a matrix that is not symmetric to :data:`INERTIA_ATOL` of its size."""
    asym = np.abs(J - np.swapaxes(J, -1, -2)).max(axis=(-1, -2), initial=0.0)
    size = np.abs(J).max(axis=(-1, -2), initial=0.0)
    bad = asym > INERTIA_ATOL * size
    if bad.any():
        i = tuple(int(k) for k in np.argwhere(bad)[0]) if bad.ndim else ()
        raise NonPhysicalInertiaError(
            f"{name} is not symmetric: max |J - J^T| = {float(asym[i]):.3g}, more than "
            f"{INERTIA_ATOL / EPS:.0f} eps of its largest entry (index {i})"
        )
    return J


def _sym(J: np.ndarray) -> np.ndarray:
    """(J + Jᵀ)/2: exactly symmetric, and equal to J where J already is."""
    out: np.ndarray = 0.5 * (J + np.swapaxes(J, -1, -2))
    return out


# ------------------------------------------------------- Jacobi eigen-solver


def _jacobi(J: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Eigenvalues (unsorted, (..., 3)) and eigenvector columns V of symmetric J.

    Cyclic Jacobi (Rutishauser's stable rotation, Numerical Recipes §11.1) on the
    six distinct entries as 1-D arrays over the batch.  Each rotation zeroes
    a_pq exactly; sweeps stop when every |a_pq| ≤ eps/2 √|a_pp a_qq| (the
    Demmel–Veselić test that keeps small moments relatively accurate) or is
    below eps² of the largest diagonal entry.  A zero a_pq gives t = 0, an exact
    no-op, so converged tensors are not disturbed by later sweeps.
    """
    shape = J.shape[:-2]
    A = J.reshape(-1, 3, 3)
    a = {(0, 0): A[:, 0, 0].copy(), (1, 1): A[:, 1, 1].copy(), (2, 2): A[:, 2, 2].copy()}
    # Symmetric input: take the mean of the two triangles (exact for symmetric J).
    for p, q in ((0, 1), (0, 2), (1, 2)):
        a[(p, q)] = 0.5 * (A[:, p, q] + A[:, q, p])
    n = A.shape[0]
    V = [[np.full(n, float(i == j)) for j in range(3)] for i in range(3)]

    def off(p: int, q: int) -> np.ndarray:
        return a[(p, q)] if p < q else a[(q, p)]

    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        for _ in range(_JACOBI_MAX_SWEEPS):
            big = np.maximum(np.maximum(np.abs(a[(0, 0)]), np.abs(a[(1, 1)])), np.abs(a[(2, 2)]))
            done = np.ones(n, dtype=bool)
            for p, q in ((0, 1), (0, 2), (1, 2)):
                apq = a[(p, q)]
                # √|a_pp| √|a_qq|, not √|a_pp a_qq|: the product overflows for entries
                # beyond 1e154, and an infinite bound would stop the sweeps unrotated
                geo = np.sqrt(np.abs(a[(p, p)])) * np.sqrt(np.abs(a[(q, q)]))
                small = np.abs(apq) <= np.maximum(0.5 * EPS * geo, EPS * EPS * big)
                done &= small
            if done.all():
                break
            for p, q in ((0, 1), (0, 2), (1, 2)):
                r = 3 - p - q
                apq = a[(p, q)]
                app, aqq = a[(p, p)], a[(q, q)]
                nz = apq != 0
                theta = (aqq - app) / np.where(nz, 2.0 * apq, 1.0)
                sgn = np.where(theta < 0, -1.0, 1.0)
                t = np.where(nz, sgn / (np.abs(theta) + np.hypot(theta, 1.0)), 0.0)
                t = np.where(np.isfinite(t), t, 0.0)
                c = 1.0 / np.sqrt(1.0 + t * t)
                s = t * c
                a[(p, p)] = app - t * apq
                a[(q, q)] = aqq + t * apq
                a[(p, q)] = np.zeros(n)
                arp, arq = off(r, p), off(r, q)
                new_rp = c * arp - s * arq
                new_rq = s * arp + c * arq
                a[(min(r, p), max(r, p))] = new_rp
                a[(min(r, q), max(r, q))] = new_rq
                for i in range(3):
                    vp, vq = V[i][p], V[i][q]
                    V[i][p] = c * vp - s * vq
                    V[i][q] = s * vp + c * vq
    w = np.stack([a[(0, 0)], a[(1, 1)], a[(2, 2)]], axis=-1)
    Vm = np.stack([np.stack(row, axis=-1) for row in V], axis=-2)
    return w.reshape(*shape, 3), Vm.reshape(*shape, 3, 3)


def _principal(J: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Ascending moments and the proper rotation R_A_O (rows = axes), sign-fixed."""
    w, V = _jacobi(J)
    order = np.argsort(w, axis=-1, kind="stable")
    moments = np.take_along_axis(w, order, axis=-1)
    R = np.take_along_axis(np.swapaxes(V, -1, -2), order[..., :, None], axis=-2)
    # Deterministic signs: the largest component of rows 1 and 2 is positive
    # (first such on ties); row 3 then gets the sign that makes det R = +1.
    for i in (0, 1):
        row = R[..., i, :]
        k = np.argmax(np.abs(row), axis=-1)
        s = np.where(np.take_along_axis(row, k[..., None], axis=-1)[..., 0] < 0, -1.0, 1.0)
        R[..., i, :] = row * s[..., None]
    det = np.einsum("...i,...i->...", np.cross(R[..., 0, :], R[..., 1, :]), R[..., 2, :])
    R[..., 2, :] *= np.where(det < 0, -1.0, 1.0)[..., None]
    return moments, R


# ------------------------------------------------------------------ validation


def _scale(moments: np.ndarray) -> np.ndarray:
    out: np.ndarray = np.maximum(np.abs(moments).max(axis=-1), np.finfo(np.float64).tiny)
    return out


def _sqrt_quotient(x: np.ndarray, y: np.ndarray, k: np.ndarray) -> np.ndarray:
    """√(x·2**k / y) for x ≥ 0, y > 0, integer k: the quotient of the mantissas (the plain
    quotient's rounding) and the exponent halved exactly, so that neither x·2**k nor the
    quotient can overflow or underflow on the way (x given in units of 2**k, as by
    :func:`_unit_scaled`)."""
    (fx, ex), (fy, ey) = np.frexp(x), np.frexp(y)
    h, odd = np.divmod(ex - ey + k, 2)
    out: np.ndarray = np.ldexp(np.sqrt(np.ldexp(fx / fy, odd)), h)
    return out


def _first(mask: np.ndarray) -> tuple[int, ...]:
    return tuple(int(i) for i in np.argwhere(mask)[0]) if mask.ndim else ()


def _unit_scaled(a: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(a/2**k, k), k per matrix so that its largest |entry| lies in [1/2, 1) (a zero matrix
    keeps k = 0).  The scaling is exact, and the checks are homogeneous in J, so they decide
    exactly as on ``a``; but no sum of moments can overflow (near 1e308) or underflow."""
    _, k = np.frexp(np.abs(a).max(axis=(-1, -2), initial=0.0))
    return np.ldexp(a, -k[..., None, None]), k


def _check_parts(
    J: np.ndarray,
    moments: np.ndarray,
    *,
    allow_singular: bool,
    where: str,
    name: str,
    k: np.ndarray | None = None,
) -> None:
    """The conditions of :func:`check_inertia` on ``J`` and its ``moments``, both given in
    units of 2**k (:func:`_unit_scaled`; the messages print values in the caller's units)."""
    k = np.zeros(moments.shape[:-1], dtype=int) if k is None else k

    def unscaled(x: np.ndarray, i: tuple[int, ...]) -> object:
        with np.errstate(over="ignore"):  # a value beyond float64 is printed as inf
            return np.ldexp(x[i], k[i]).tolist()

    scale = _scale(moments)
    asym = np.abs(J - np.swapaxes(J, -1, -2)).max(axis=(-1, -2))
    bad = asym > INERTIA_ATOL * scale
    if bad.any():
        i = _first(bad)
        raise NonPhysicalInertiaError(
            f"{name} is not symmetric: max |J - J^T| = {unscaled(asym, i):.3g} = "
            f"{asym[i] / (EPS * scale[i]):.3g} eps of the largest moment, more than "
            f"{INERTIA_ATOL / EPS:.0f} eps (index {i})"
        )
    j_min = moments[..., 0]
    tol = INERTIA_ATOL * scale
    bad = j_min < -tol
    if bad.any():
        i = _first(bad)
        raise NonPhysicalInertiaError(
            f"{name} is not positive semidefinite: smallest principal moment J1 = "
            f"{unscaled(j_min, i):.6g} < 0 (by {-j_min[i] / scale[i]:.3g} of the largest moment; "
            f"index {i})"
        )
    if not allow_singular:
        bad = j_min <= tol
        if bad.any():
            i = _first(bad)
            raise NonPhysicalInertiaError(
                f"{name} is not positive definite: smallest principal moment J1 = "
                f"{unscaled(j_min, i):.6g} is zero to rounding ({j_min[i] / scale[i]:.3g} of the "
                f"largest moment, index {i}); an ideal line mass or point has this: pass "
                "allow_singular=True to accept it"
            )
    slack = moments[..., 0] + moments[..., 1] - moments[..., 2]
    bad = slack < -tol
    if bad.any():
        i = _first(bad)
        raise NonPhysicalInertiaError(
            f"{name} breaks the triangle inequality J1 + J2 >= J3{where}: principal "
            f"moments {unscaled(moments, i)} give J1 + J2 - J3 = {unscaled(slack, i):.6g} "
            f"({slack[i] / scale[i]:.3g} of J3; index {i})"
        )


def check_inertia(
    J: npt.ArrayLike,
    *,
    about_centre_of_mass: bool = True,
    allow_singular: bool = False,
    name: str = "J",
) -> np.ndarray:
    """Validate an inertia tensor and return it as a float64 array, unchanged.

    Domain: any finite array (..., 3, 3) (else NonFiniteError or ShapeError); it is refused with
    NonPhysicalInertiaError when not symmetric, not positive definite (semidefinite with
    ``allow_singular``) or breaking J1 + J2 ≥ J3 by more than :data:`INERTIA_ATOL` of the largest
    moment.  Any magnitudes, subnormal to float64's limit (moments near 1e308 included): the checks
    run on ``J`` scaled by a power of two, exactly, its largest entry in [1/2, 1).

    Parameters
    ----------
    J : array_like, shape (..., 3, 3)
        The tensor (any basis).
    about_centre_of_mass : bool
        Whether ``J`` is about G; it only changes the error message.  The
        conditions are the same about every point: in the principal basis at
        any point J1 + J2 − J3 = 2 Σ m x3² ≥ 0, so the triangle inequality holds
        for a tensor about G and about any other point alike (a shift (4.38)
        adds the tensor of a point mass, which obeys it too).
    allow_singular : bool
        Accept a zero smallest moment (an ideal line mass, J = diag(J, J, 0),
        or a point, J = 0).  Default: positive definite is required.
    name : str
        The name used in error messages.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        ``J`` as float64, not symmetrised or otherwise changed.

    Raises
    ------
    NonPhysicalInertiaError
        Not symmetric, not positive (semi)definite, or J1 + J2 < J3 beyond
        :data:`INERTIA_ATOL` of the largest moment; the message names the
        condition, the amount and the index.
    NonFiniteError
        NaN or infinite entries.
    ShapeError
        A shape not ending in (3, 3), or not an array of real numbers.

    Examples
    --------
    The triangle inequality holds with equality for a flat body (a plate):

    >>> J = rectangular_plate(2.0, 3.0, 1.0)
    >>> bool(J[0, 0] + J[1, 1] == J[2, 2])
    True
    >>> check_inertia(np.diag([1.0, 1.0, 3.0]))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    mechanics.errors.NonPhysicalInertiaError: J breaks the triangle inequality ... = -1 ...
    """
    a = as_float_array(J, name, (3, 3))
    s, k = _unit_scaled(a)
    moments = np.linalg.eigvalsh(_sym(s)) if a.size else np.zeros((*a.shape[:-2], 3))
    where = " about G" if about_centre_of_mass else " about the given point"
    _check_parts(s, moments, allow_singular=allow_singular, where=where, name=name, k=k)
    return a


def is_physical_inertia(J: npt.ArrayLike, *, allow_singular: bool = False) -> np.ndarray:
    """Elementwise: does ``J`` (..., 3, 3) pass :func:`check_inertia`?  Shape (...).

    Domain: any finite array (..., 3, 3) (else NonFiniteError or ShapeError); the answer (...) is
    False, never an error, for a tensor :func:`check_inertia` refuses; any magnitudes (checked on
    ``J`` scaled by a power of two, as there).

    Parameters
    ----------
    J : array_like, shape (..., 3, 3)
        Inertia tensors (kg m², any basis, about any point), finite.
    allow_singular : bool
        Accept a zero smallest moment (an ideal line mass or a point), as in
        :func:`check_inertia`.  Default: positive definite is required.

    Returns
    -------
    ndarray of bool, shape (...)
        True where the tensor is symmetric, positive definite (semidefinite with
        ``allow_singular``) and obeys J1 + J2 ≥ J3, each to :data:`INERTIA_ATOL` of
        its largest moment; False where :func:`check_inertia` would raise.

    Raises
    ------
    NonFiniteError
        ``J`` has a NaN or infinite entry.
    ShapeError
        ``J`` has a shape not ending in (3, 3), or is not an array of real numbers.

    Examples
    --------
    The answer is :func:`check_inertia`'s, tensor by tensor (J1 + J2 < J3 for the second);
    a thin rod's singular tensor passes only with ``allow_singular``:

    >>> is_physical_inertia([np.eye(3), np.diag([1.0, 1.0, 2.5])]).tolist()
    [True, False]
    >>> [bool(is_physical_inertia(rod(12.0, 1.0), allow_singular=s)) for s in (False, True)]
    [False, True]
    """
    a, _ = _unit_scaled(as_float_array(J, "J", (3, 3)))
    m = np.linalg.eigvalsh(_sym(a))
    scale = _scale(m)
    tol = INERTIA_ATOL * scale
    ok: np.ndarray = np.abs(a - np.swapaxes(a, -1, -2)).max(axis=(-1, -2)) <= tol
    ok &= m[..., 0] >= -tol if allow_singular else m[..., 0] > tol
    ok &= m[..., 0] + m[..., 1] - m[..., 2] >= -tol
    return ok


# ------------------------------------------------------------- particle systems


def inertia_tensor(m: npt.ArrayLike, r: npt.ArrayLike, *, about: npt.ArrayLike) -> np.ndarray:
    """The inertia tensor J_C of particles about the point C = ``about`` (4.34).

    Domain: masses ``m`` (..., N) ≥ 0 (else NegativeMassError) with a positive total and N ≥ 1 (else
    ZeroTotalMassError), positions ``r`` (..., N, 3) matching ``m`` (else ShapeError), ``about`` any
    finite (..., 3); a tensor beyond float64 raises ResultOverflowError (positions near 1e300,
    whose squares m s² overflow, included).

    Built in centre-of-mass coordinates: G is found relative to the heaviest
    particle, J_G = Σ m (|s|² 1 − s sᵀ) with s = r − G (diagonal entries as
    Σ m (s_j² + s_k²), which cannot cancel), then shifted to C by
    :func:`parallel_axis` (4.38).  So a compact system far from the origin
    keeps all its digits.

    Parameters
    ----------
    m : array_like, shape (..., N)
        Masses (kg), >= 0, with a positive total.
    r : array_like, shape (..., N, 3)
        Positions (m), finite.
    about : array_like, shape (..., 3)
        The point C (m, same coordinates as ``r``).  Required: there is no silent
        origin.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        J_C (kg m²) in the basis of ``r``; exactly symmetric.

    Raises
    ------
    NegativeMassError
        A mass is negative.
    ZeroTotalMassError
        The total mass is 0, or there are no particles (N = 0).
    ShapeError
        ``r`` not (..., N, 3) with the N and batch shape of ``m``, ``about`` not ending in 3,
        batches of the systems and of ``about`` that do not broadcast, or an input that is not
        an array of real numbers.
    NonFiniteError
        A NaN or infinite mass, position or ``about``.
    ResultOverflowError
        An entry of J_C beyond float64 (positions near 1e300, whose squares overflow).

    Examples
    --------
    Two unit masses at ±e1: J about the midpoint, computed directly and from
    the tensor about one of them by the parallel-axis theorem:

    >>> r = [[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]]
    >>> J_G = inertia_tensor([1.0, 1.0], r, about=[0.0, 0.0, 0.0])
    >>> np.diag(J_G).tolist()
    [0.0, 2.0, 2.0]
    >>> J_1 = inertia_tensor([1.0, 1.0], r, about=[1.0, 0.0, 0.0])
    >>> bool(np.array_equal(J_1, parallel_axis(J_G, 2.0, [1.0, 0.0, 0.0], allow_singular=True)))
    True
    """
    J_G, M, G = _centre_of_mass_tensor(m, r)
    C = as_float_array(about, "about", (3,))
    return _shift(J_G, M, C - G)


inertia_tensor = finite_result(inertia_tensor)


def _centre_of_mass_tensor(
    m: npt.ArrayLike, r: npt.ArrayLike
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    mm = _mass(m, "m")
    rr = as_float_array(r, "r", (3,))
    if rr.ndim < 2 or mm.shape != rr.shape[:-1]:
        raise ShapeError(
            f"m has shape {mm.shape} and r {rr.shape}; expected (..., N) and (..., N, 3)"
        )
    if mm.shape[-1] == 0:
        raise ZeroTotalMassError("no particles: the centre of mass is undefined")
    M = mm.sum(axis=-1)
    if (M <= 0).any():
        raise ZeroTotalMassError(f"total mass is 0 (index {_first(M <= 0)}): G is undefined")
    # reference: the heaviest particle, which is closest to G in the mass-weighted sense,
    # so G = ref + G_rel adds a small correction (a light far particle as reference would
    # make G a difference of two large numbers when the masses differ by many orders)
    heaviest = np.argmax(mm, axis=-1)[..., None, None]
    ref = np.take_along_axis(rr, np.broadcast_to(heaviest, (*rr.shape[:-2], 1, 3)), axis=-2)
    rel = rr - ref
    G_rel = np.einsum("...n,...ni->...i", mm, rel) / M[..., None]
    s = rel - G_rel[..., None, :]
    D = np.einsum("...n,...ni,...nj->...ij", mm, s, s)
    sq = mm[..., None] * s * s
    Sx, Sy, Sz = (sq[..., k].sum(axis=-1) for k in range(3))
    J = -D
    J[..., 0, 0], J[..., 1, 1], J[..., 2, 2] = Sy + Sz, Sx + Sz, Sx + Sy
    return _sym(J), M, ref[..., 0, :] + G_rel


def parallel_axis(
    J_G: npt.ArrayLike, m: npt.ArrayLike, d: npt.ArrayLike, *, allow_singular: bool = False
) -> np.ndarray:
    """The parallel-axis (Steiner) theorem in tensor form: J_C = J_G + m(|d|² 1 − d dᵀ) (4.38).

    Domain: ``J_G`` (..., 3, 3) as :func:`check_inertia` (``allow_singular`` passed on; else
    NonPhysicalInertiaError), ``m`` ≥ 0 (else NegativeMassError), any finite ``d`` (..., 3),
    broadcast together; any magnitudes (error-free products, the plain formula near the overflow
    threshold), a result beyond float64 raising ResultOverflowError.

    Parameters
    ----------
    J_G : array_like, shape (..., 3, 3)
        Inertia tensor about the centre of mass G (kg m²; validated by
        :func:`check_inertia`).
    m : array_like, shape (...)
        Total mass (kg), >= 0.
    d : array_like, shape (..., 3)
        The vector GC from G to the new point C (m; the book's R), same basis as J_G.
    allow_singular : bool
        Passed to :func:`check_inertia` for ``J_G`` (a thin rod is singular).

    Returns
    -------
    ndarray, shape (..., 3, 3)
        J_C, exactly symmetric.  Each entry within about 1 ulp of the exact
        value for the float inputs: diagonal m(d_j² + d_k²) (never |d|² − d_i²,
        which cancels), off-diagonal −m d_i d_j, both with error-free products,
        added to J_G with one final rounding.  At |d|/size = 1e8 the shift
        dominates J_G by 1e16 and the result is the shift, correct to the last
        bit, with J_G below half an ulp.

    Raises
    ------
    NonPhysicalInertiaError
        ``J_G`` is refused by :func:`check_inertia` (not symmetric, not positive definite
        (semidefinite with ``allow_singular``), or J1 + J2 < J3).
    NegativeMassError
        ``m`` has a negative entry.
    NonFiniteError
        A NaN or infinite entry in any input.
    ShapeError
        ``J_G`` not ending in (3, 3), ``d`` not ending in 3, batch axes that do not
        broadcast (the message lists each argument's shape), or an input that is not an
        array of real numbers.
    ResultOverflowError
        An entry of J_C beyond float64.

    Examples
    --------
    A rod about its end: m ℓ²/12 + m (ℓ/2)² = m ℓ²/3 (Example 4.3):

    >>> J = parallel_axis(rod(3.0, 2.0), 3.0, [0.0, 0.0, 1.0], allow_singular=True)
    >>> float(J[0, 0]), 3.0 * 2.0**2 / 3
    (4.0, 4.0)
    """
    JG = check_inertia(J_G, allow_singular=allow_singular, name="J_G")
    return _shift(JG, _mass(m, "m"), as_float_array(d, "d", (3,)))


parallel_axis = broadcast_checked(parallel_axis)


def _shift(JG: np.ndarray, mm: np.ndarray, dd: np.ndarray) -> np.ndarray:
    """J_G + m(|d|² 1 − d dᵀ) with error-free products and sums (validated inputs)."""
    shape = np.broadcast_shapes(JG.shape[:-2], mm.shape, dd.shape[:-1])
    JG = np.broadcast_to(JG, (*shape, 3, 3))
    mm = np.broadcast_to(mm, shape)
    dd = np.broadcast_to(dd, (*shape, 3))
    x = [dd[..., k] for k in range(3)]
    out = np.empty((*shape, 3, 3))
    with np.errstate(over="ignore", invalid="ignore"):
        sq = [_two_prod(x[k], x[k]) for k in range(3)]
        for i in range(3):
            j, k = (i + 1) % 3, (i + 2) % 3
            sh, sl = _dd_add(*sq[j], *sq[k])
            ph, pl = _dd_times(mm, sh, sl)
            s, e = _two_sum(JG[..., i, i], ph)
            out[..., i, i] = s + (e + pl)
        for i, j in ((0, 1), (0, 2), (1, 2)):
            ph, pl = _two_prod(x[i], x[j])
            qh, ql = _dd_times(mm, ph, pl)
            jg = 0.5 * (JG[..., i, j] + JG[..., j, i])
            s, e = _two_sum(jg, -qh)
            out[..., i, j] = out[..., j, i] = s + (e - ql)
        # Near the overflow threshold (a mass or product beyond 2**996) Dekker's
        # splitting overflows although the product does not: there the plain
        # formula, one rounding more, is used.
        if not np.isfinite(out).all():
            plain = JG + mm[..., None, None] * (
                np.einsum("...k,...k->...", dd, dd)[..., None, None] * np.eye(3)
                - dd[..., :, None] * dd[..., None, :]
            )
            out = np.where(np.isfinite(out), out, _sym(plain))
    return _finite_result(out, "the shifted inertia tensor")


# ---------------------------------------------------------------------- rotation


def rotate_inertia(J_A: npt.ArrayLike, R_A_O: npt.ArrayLike) -> np.ndarray:
    """The tensor's components in O from those in A: J^O = ^O R^A J^A ^A R^O (4.11).

    Domain: ``J_A`` (..., 3, 3) symmetric to :data:`INERTIA_ATOL` of its largest entry (else
    NonPhysicalInertiaError), not necessarily physical; ``R_A_O`` a rotation as
    :func:`~mechanics.rotation.check_rotation` (else NotARotationError); a result beyond float64
    raises ResultOverflowError.  Batches that do not broadcast (2 against 3) raise ShapeError
    listing each argument's shape.

    ``R_A_O`` is the book's passive ^A R^O (rows: the e^A_i in O components).
    ``J_A`` must be symmetric (to :data:`INERTIA_ATOL` of its largest entry,
    else :class:`~mechanics.errors.NonPhysicalInertiaError`) but need not be
    physical: the products D of (4.37) transform the same way.  The result is
    exactly symmetric: the product is formed once and averaged with its
    transpose (which changes nothing beyond rounding).  The inverse, J^A from
    J^O, is :func:`inertia_A_from_O`.

    Parameters
    ----------
    J_A : array_like, shape (..., 3, 3)
        The tensor's components in the basis A (kg m²), symmetric.
    R_A_O : array_like, shape (..., 3, 3)
        The rotation ^A R^O (rows: the e^A_i in O components), proper and orthonormal.

    Returns
    -------
    J_O : ndarray, shape (..., 3, 3)
        The components J^O = R_A_Oᵀ J_A R_A_O (kg m²) in the basis O, exactly symmetric.

    Raises
    ------
    NonPhysicalInertiaError
        ``J_A`` not symmetric to :data:`INERTIA_ATOL` of its largest entry.
    NotARotationError
        ``R_A_O`` not a proper rotation (:func:`~mechanics.rotation.check_rotation`).
    NonFiniteError
        A NaN or infinite entry in ``J_A`` or ``R_A_O``.
    ShapeError
        ``J_A`` or ``R_A_O`` not ending in (3, 3), batch axes that do not broadcast (the
        message lists each argument's shape), or an input that is not an array of real numbers.
    ResultOverflowError
        An entry of the result beyond float64.

    Examples
    --------
    Example 4.2: turning the principal basis by ψ about e3 gives the product of
    inertia D_xy = −cos ψ sin ψ (J_x − J_y) (4.31), i.e. J^O_xy = −D_xy:

    >>> from mechanics.rotation import R3
    >>> psi = 0.3
    >>> J_O = rotate_inertia(np.diag([1.0, 2.0, 3.0]), R3(psi))
    >>> bool(np.isclose(J_O[0, 1], np.cos(psi) * np.sin(psi) * (1.0 - 2.0), rtol=4e-16, atol=0))
    True
    """
    J = _check_symmetric(as_float_array(J_A, "J_A", (3, 3)), "J_A")
    R = check_rotation(R_A_O)
    with np.errstate(over="ignore", invalid="ignore"):
        out = _sym(np.swapaxes(R, -1, -2) @ J @ R)
    return _finite_result(out, "the rotated inertia tensor")


rotate_inertia = broadcast_checked(rotate_inertia)


def inertia_A_from_O(J_O: npt.ArrayLike, R_A_O: npt.ArrayLike) -> np.ndarray:
    """The tensor's components in A from those in O: J^A = ^A R^O J^O ^O R^A.

    Domain: as :func:`rotate_inertia`: ``J_O`` symmetric (else NonPhysicalInertiaError), ``R_A_O`` a
    rotation (else NotARotationError), a result beyond float64 raising ResultOverflowError;
    batches that do not broadcast raise ShapeError listing each argument's shape.

    Parameters
    ----------
    J_O : array_like, shape (..., 3, 3)
        The tensor's components in the basis O (kg m²), symmetric.
    R_A_O : array_like, shape (..., 3, 3)
        The rotation ^A R^O (rows: the e^A_i in O components), proper and orthonormal.

    Returns
    -------
    J_A : ndarray, shape (..., 3, 3)
        The components J^A = R_A_O J_O R_A_Oᵀ (kg m²) in the basis A, exactly symmetric.

    Raises
    ------
    NonPhysicalInertiaError
        ``J_O`` not symmetric to :data:`INERTIA_ATOL` of its largest entry.
    NotARotationError
        ``R_A_O`` not a proper rotation (:func:`~mechanics.rotation.check_rotation`).
    NonFiniteError
        A NaN or infinite entry in ``J_O`` or ``R_A_O``.
    ShapeError
        ``J_O`` or ``R_A_O`` not ending in (3, 3), batch axes that do not broadcast (the
        message lists each argument's shape), or an input that is not an array of real numbers.
    ResultOverflowError
        An entry of the result beyond float64.

    Examples
    --------
    The inverse of :func:`rotate_inertia` (4.11):

    >>> from mechanics.rotation import matrix_from_rotvec
    >>> R = matrix_from_rotvec([0.3, -0.2, 1.0])
    >>> J = np.diag([1.0, 2.0, 2.5])
    >>> bool(np.allclose(inertia_A_from_O(rotate_inertia(J, R), R), J, rtol=0, atol=1e-15))
    True
    """
    J = _check_symmetric(as_float_array(J_O, "J_O", (3, 3)), "J_O")
    R = check_rotation(R_A_O)
    with np.errstate(over="ignore", invalid="ignore"):
        out = _sym(R @ J @ np.swapaxes(R, -1, -2))
    return _finite_result(out, "the rotated inertia tensor")


inertia_A_from_O = broadcast_checked(inertia_A_from_O)


# ---------------------------------------------------------------- principal axes


def principal_axes(
    J: npt.ArrayLike, *, allow_singular: bool = True
) -> tuple[np.ndarray, np.ndarray]:
    """Principal moments (ascending) and principal axes of ``J`` (4.13)–(4.14).

    Domain: ``J`` (..., 3, 3) as :func:`check_inertia` (singular allowed by default; else
    NonPhysicalInertiaError, NonFiniteError, ShapeError), any magnitudes: the moments and the
    check are computed on ``J`` scaled by a power of two (exactly; bit for bit the scaled results),
    so entries near 1e308 are taken; a moment beyond float64 raises ResultOverflowError.

    Parameters
    ----------
    J : array_like, shape (..., 3, 3)
        A physical inertia tensor (kg m²; validated as by :func:`check_inertia`; a thin
        rod's singular tensor is accepted by default).
    allow_singular : bool
        Accept a zero smallest moment (default True).

    Returns
    -------
    moments : ndarray, shape (..., 3)
        The principal moments J1 ≤ J2 ≤ J3 (kg m²).
    R_A_O : ndarray, shape (..., 3, 3)
        A proper rotation whose rows are the principal axes e^A_i in the
        components of ``J``, so J = R_A_Oᵀ diag(moments) R_A_O.  Signs are
        fixed (the largest component of rows 1 and 2 is positive).  Where
        moments coincide only the eigen-subspace is defined and the rows
        spanning it are one arbitrary orthonormal basis of it: compare
        :func:`principal_subspaces`, not rows.

    Raises
    ------
    NonPhysicalInertiaError
        ``J`` refused as by :func:`check_inertia`: not symmetric, not positive
        semidefinite (definite with ``allow_singular=False``), or J1 + J2 < J3.
    NonFiniteError
        A NaN or infinite entry.
    ShapeError
        A shape not ending in (3, 3), or not an array of real numbers.
    ResultOverflowError
        A moment beyond float64 (entries at float64's limit whose eigenvalue exceeds it).

    Notes
    -----
    Cyclic Jacobi rotations on the whole batch at once (vectorised; see the
    module docstring for accuracy).  Degenerate and near-degenerate moments
    need no special case: a rotation with a_pp = a_qq turns by π/4.

    Examples
    --------
    The moments are the eigenvalues, and J is rebuilt from them (4.11):

    >>> from mechanics.rotation import matrix_from_rotvec
    >>> J = rotate_inertia(np.diag([1.0, 2.0, 2.5]), matrix_from_rotvec([0.4, 0.1, -0.7]))
    >>> moments, R = principal_axes(J)
    >>> bool(np.allclose(moments, [1.0, 2.0, 2.5], rtol=0, atol=4e-15))
    True
    >>> bool(np.allclose(rotate_inertia(np.diag(moments), R), J, rtol=0, atol=4e-15))
    True
    """
    s, k = _unit_scaled(as_float_array(J, "J", (3, 3)))
    moments_s, R = _principal(s)
    _check_parts(s, moments_s, allow_singular=allow_singular, where="", name="J", k=k)
    with np.errstate(over="ignore"):
        moments = np.ldexp(moments_s, k[..., None])
    _finite_result(moments, "the principal moments (entries near the float64 limit)")
    return moments, R


def principal_subspaces(
    J: npt.ArrayLike, *, rtol: float = SUBSPACE_RTOL
) -> tuple[np.ndarray, np.ndarray]:
    """Moments and the orthogonal projectors onto their eigen-subspaces.

    Domain: ``J`` as :func:`principal_axes` (physical, singular allowed), ``rtol`` a finite number ≥
    0 (NaN, inf, a non-number: NonFiniteError or ShapeError; a negative one
    NonPositiveParameterError, each naming ``rtol``).

    Moments J_i, J_{i+1} whose gap is at most ``rtol`` times the largest moment
    belong to one subspace (chained: three moments within two small gaps form
    one).  Unlike the axes, the projectors are unique, so two computations of
    the principal axes of one tensor can be compared through them.

    Parameters
    ----------
    J : array_like, shape (..., 3, 3)
        A physical inertia tensor (kg m²), validated as by :func:`principal_axes`
        (singular allowed).
    rtol : float
        Gap below which two moments count as one, relative to the largest moment;
        finite, ≥ 0 (default :data:`SUBSPACE_RTOL` = 2**-26).

    Returns
    -------
    moments : ndarray, shape (..., 3)
        The principal moments (kg m²), ascending.
    P : ndarray, shape (..., 3, 3, 3)
        ``P[..., i, :, :]`` projects onto the subspace of moment i: Σ e_j e_jᵀ over
        the axes j coincident with i.  A simple moment's projector has rank 1;
        a spherical top's is the identity.

    Raises
    ------
    NonPositiveParameterError
        ``rtol`` negative.
    NonPhysicalInertiaError
        ``J`` refused as by :func:`principal_axes`.
    NonFiniteError
        A NaN or infinite entry of ``J``, or ``rtol`` NaN or infinite.
    ShapeError
        ``J`` not ending in (3, 3), or not an array of real numbers; ``rtol`` not a scalar,
        or complex or not numeric.
    ResultOverflowError
        A moment beyond float64 (as :func:`principal_axes`).

    Examples
    --------
    A symmetric top (J1 = J2): the projector of J1 and of J2 is the one onto the
    plane normal to the symmetry axis, 1 − e3 e3ᵀ, whichever axes span it:

    >>> moments, P = principal_subspaces(np.diag([2.0, 2.0, 3.0]))
    >>> np.diag(P[0]).tolist(), np.diag(P[2]).tolist()
    ([1.0, 1.0, 0.0], [0.0, 0.0, 1.0])
    """
    rt = as_float_scalar(rtol, "rtol")
    if not rt >= 0:
        raise NonPositiveParameterError(f"rtol must be a finite number >= 0; got {rt!r}")
    moments, R = principal_axes(J)
    scale = _scale(moments)
    g01 = moments[..., 1] - moments[..., 0] <= rt * scale
    g12 = moments[..., 2] - moments[..., 1] <= rt * scale
    one = np.ones_like(g01)
    same = np.stack(
        [
            np.stack([one, g01, g01 & g12], axis=-1),
            np.stack([g01, one, g12], axis=-1),
            np.stack([g01 & g12, g12, one], axis=-1),
        ],
        axis=-2,
    ).astype(np.float64)
    P = np.einsum("...ij,...ja,...jb->...iab", same, R, R)
    return moments, P


# ------------------------------------------------------------- Example 4.1


def four_particle_realisation(m: npt.ArrayLike, J: npt.ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Four particles of mass m/4 with total mass m and inertia tensor J about G (Example 4.1).

    Domain: ``m`` > 0 (else NegativeMassError or NonPositiveParameterError), ``J`` (..., 3, 3) as
    :func:`check_inertia` with a singular tensor allowed (else NonPhysicalInertiaError).  Any
    magnitudes, subnormal to float64's limit (moments beyond 1.8e308 included): the principal
    axes are computed on ``J`` scaled by a power of two (exactly, as in :func:`principal_axes`),
    and the squared distances J/m are formed with their powers of two apart, so J near 1e300 over
    m near 1e-300 gives distances near 1e300, not an overflow (a distance beyond float64 raises
    ResultOverflowError).  Scaling ``m`` and ``J`` by one power of two (exactly) leaves the
    positions unchanged, bit for bit.  Batches that do not broadcast raise ShapeError listing
    each argument's shape.

    In the principal basis, with J_x ≤ J_y ≤ J_z the principal moments, the
    particles are at (±a, 0, c) and (0, ±b, −c) (4.15)–(4.18) with
    m a² = J_z − J_x + J_y, m b² = J_z + J_x − J_y, 2 m c² = J_x + J_y − J_z
    (4.26)–(4.29); the positions are then turned into the basis of ``J``.

    Parameters
    ----------
    m : array_like, shape (...)
        Total mass (kg), > 0.
    J : array_like, shape (..., 3, 3)
        A physical inertia tensor about G (kg m²; :func:`check_inertia`, singular
        allowed: a line mass is realised with b = 0 and c = 0).

    Returns
    -------
    masses : ndarray, shape (..., 4)
        m/4 each (kg).
    r : ndarray, shape (..., 4, 3)
        Positions relative to G (m), in the basis of ``J``; their centre of mass is G.
        A rounding-level negative a², b², c² (allowed by the tolerance of
        :func:`check_inertia`) is taken as 0.

    Raises
    ------
    NegativeMassError
        ``m`` has a negative entry.
    NonPositiveParameterError
        ``m`` has a zero entry.
    NonPhysicalInertiaError
        ``J`` refused by :func:`check_inertia` (singular allowed).
    NonFiniteError
        A NaN or infinite entry of ``m`` or ``J``.
    ShapeError
        ``J`` not ending in (3, 3), batch axes of ``m`` and ``J`` that do not broadcast (the
        message lists each argument's shape), or an input that is not an array of real numbers.
    ResultOverflowError
        A distance beyond float64 (the result is not finite for finite inputs).

    Examples
    --------
    The particles have the tensor they were built from (4.34):

    >>> J = np.diag([1.0, 2.0, 2.5])
    >>> masses, r = four_particle_realisation(4.0, J)
    >>> bool(np.allclose(inertia_tensor(masses, r, about=[0.0, 0.0, 0.0]), J, rtol=0, atol=1e-15))
    True
    """
    mm = _mass(m, "m", positive=True)
    # Jacobi on J/2**k, its largest entry in [1/2, 1) (exact), as in principal_axes: on J itself
    # a subnormal tensor loses digits and moments beyond float64 overflow
    s, k = _unit_scaled(check_inertia(J, allow_singular=True))
    moments, R = _principal(s)
    Jx, Jy, Jz = (moments[..., i] for i in range(3))
    shape = np.broadcast_shapes(mm.shape, Jx.shape)
    mm, k = np.broadcast_to(mm, shape), np.broadcast_to(k, shape)
    # √(x 2**k / m) with the powers of two apart: J/m may overflow (J 1e300, m 1e-300) where √
    # does not; c² = x 2**(k-1)/m, not x/(2 m): 2 m overflows for m near 1e308
    a = _sqrt_quotient(np.maximum((Jz - Jx) + Jy, 0.0), mm, k)
    b = _sqrt_quotient(np.maximum((Jz - Jy) + Jx, 0.0), mm, k)
    c = _sqrt_quotient(np.maximum((Jx + Jy) - Jz, 0.0), mm, k - 1)
    z = np.zeros(shape)
    r_A = np.stack(
        [
            np.stack([a, z, c], axis=-1),
            np.stack([-a, z, c], axis=-1),
            np.stack([z, b, -c], axis=-1),
            np.stack([z, -b, -c], axis=-1),
        ],
        axis=-2,
    )
    r_O = r_A @ np.broadcast_to(R, (*shape, 3, 3))  # rows: r_O = R_A_Oᵀ r_A
    return np.repeat((mm / 4.0)[..., None], 4, axis=-1), r_O


four_particle_realisation = finite_result(four_particle_realisation)


# -------------------------------------------------------------- homogeneous bodies


def _diag(
    m: npt.ArrayLike,
    name_values: Sequence[tuple[str, npt.ArrayLike]],
    f1: Callable[..., npt.ArrayLike],
    f2: Callable[..., npt.ArrayLike],
    f3: Callable[..., npt.ArrayLike],
) -> np.ndarray:
    mm = _mass(m, "m")
    vals = [_length(v, n) for n, v in name_values]
    shape = np.broadcast_shapes(mm.shape, *(v.shape for v in vals))
    mm = np.broadcast_to(mm, shape)
    vals = [np.broadcast_to(v, shape) for v in vals]
    out = np.zeros((*shape, 3, 3))
    with np.errstate(over="ignore"):  # an overflow is reported by _finite_result
        out[..., 0, 0] = f1(mm, *vals)
        out[..., 1, 1] = f2(mm, *vals)
        out[..., 2, 2] = f3(mm, *vals)
    return _finite_result(out, "the inertia tensor")


def rod(m: npt.ArrayLike, ell: npt.ArrayLike) -> np.ndarray:
    """Thin homogeneous rod of mass m and length ℓ along e3, about G: diag(mℓ²/12, mℓ²/12, 0).

    Domain: ``m`` ≥ 0 (else NegativeMassError) and ``ell`` > 0 (else NonPositiveParameterError),
    finite (else NonFiniteError), broadcast together; a tensor beyond float64 (m ℓ² near 1e308)
    raises ResultOverflowError.  Batches that do not broadcast (2 against 3) raise ShapeError
    listing each argument's shape.

    The tensor is singular (an ideal line mass): validate it with
    ``check_inertia(J, allow_singular=True)``.

    Parameters
    ----------
    m : array_like, shape (...)
        Mass (kg), ≥ 0 (a zero mass gives the zero tensor).
    ell : array_like, shape (...)
        Length ℓ (m), > 0.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        diag(mℓ²/12, mℓ²/12, 0) (kg m²), about G, broadcast over the inputs' shape.

    Raises
    ------
    NegativeMassError
        ``m`` has a negative entry.
    NonPositiveParameterError
        ``ell`` has an entry ≤ 0 (the message names it).
    NonFiniteError
        A NaN or infinite input.
    ShapeError
        Inputs whose shapes do not broadcast (the message lists each argument's shape), or an
        input that is not an array of real numbers.
    ResultOverflowError
        An entry beyond float64 (m times a squared length near 1e308).

    Examples
    --------
    m ℓ²/12, and the thin limit of a :func:`cylinder`:

    >>> float(rod(12.0, 1.0)[0, 0]), 12.0 * 1.0**2 / 12
    (1.0, 1.0)
    >>> bool(np.allclose(cylinder(1.0, 1e-9, 1.0), rod(1.0, 1.0), rtol=EPS / 4, atol=EPS / 32))
    True
    """
    return _diag(m, [("ell", ell)], *(lambda m, l: m * l * l / 12.0,) * 2, lambda m, l: 0.0 * m)


rod = broadcast_checked(rod)


def ring(m: npt.ArrayLike, R: npt.ArrayLike) -> np.ndarray:
    """Thin ring (hoop) of radius R in the e1e2-plane, about G: diag(mR²/2, mR²/2, mR²).

    Domain: ``m`` ≥ 0 (else NegativeMassError) and ``R`` > 0 (else NonPositiveParameterError),
    finite, broadcast together; m R² beyond float64 raises ResultOverflowError; batches that do not
    broadcast raise ShapeError listing each argument's shape.

    Parameters
    ----------
    m : array_like, shape (...)
        Mass (kg), ≥ 0 (a zero mass gives the zero tensor).
    R : array_like, shape (...)
        Radius (m), > 0.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        diag(mR²/2, mR²/2, mR²) (kg m²), about G, broadcast over the inputs' shape.

    Raises
    ------
    NegativeMassError
        ``m`` has a negative entry.
    NonPositiveParameterError
        ``R`` has an entry ≤ 0 (the message names it).
    NonFiniteError
        A NaN or infinite input.
    ShapeError
        Inputs whose shapes do not broadcast (the message lists each argument's shape), or an
        input that is not an array of real numbers.
    ResultOverflowError
        An entry beyond float64 (m times a squared length near 1e308).

    Examples
    --------
    Flat: J1 + J2 = J3.

    >>> J = ring(2.0, 3.0)
    >>> float(J[0, 0] + J[1, 1]), float(J[2, 2])
    (18.0, 18.0)
    """
    return _diag(m, [("R", R)], *(lambda m, r: m * r * r / 2.0,) * 2, lambda m, r: m * r * r)


ring = broadcast_checked(ring)


def disc(m: npt.ArrayLike, R: npt.ArrayLike) -> np.ndarray:
    """Thin homogeneous disc of radius R in the e1e2-plane, about G: diag(mR²/4, mR²/4, mR²/2).

    Domain: as :func:`ring`: ``m`` ≥ 0, ``R`` > 0 (NegativeMassError, NonPositiveParameterError), a
    result beyond float64 raising ResultOverflowError; batches that do not broadcast raise
    ShapeError listing each argument's shape.

    Parameters
    ----------
    m : array_like, shape (...)
        Mass (kg), ≥ 0 (a zero mass gives the zero tensor).
    R : array_like, shape (...)
        Radius (m), > 0.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        diag(mR²/4, mR²/4, mR²/2) (kg m²), about G, broadcast over the inputs' shape.

    Raises
    ------
    NegativeMassError
        ``m`` has a negative entry.
    NonPositiveParameterError
        ``R`` has an entry ≤ 0 (the message names it).
    NonFiniteError
        A NaN or infinite input.
    ShapeError
        Inputs whose shapes do not broadcast (the message lists each argument's shape), or an
        input that is not an array of real numbers.
    ResultOverflowError
        An entry beyond float64 (m times a squared length near 1e308).

    Examples
    --------
    >>> J = disc(4.0, 1.0)
    >>> float(J[0, 0] + J[1, 1]), float(J[2, 2])
    (2.0, 2.0)
    """
    return _diag(m, [("R", R)], *(lambda m, r: m * r * r / 4.0,) * 2, lambda m, r: m * r * r / 2.0)


disc = broadcast_checked(disc)


def cylinder(m: npt.ArrayLike, R: npt.ArrayLike, h: npt.ArrayLike) -> np.ndarray:
    """Solid homogeneous circular cylinder, radius R, height h, axis e3, about G.

    Domain: ``m`` ≥ 0 (else NegativeMassError), ``R``, ``h`` > 0 (else NonPositiveParameterError
    naming it), finite, broadcast together; a result beyond float64 raises ResultOverflowError;
    batches that do not broadcast raise ShapeError listing each argument's shape.

    diag(m(3R² + h²)/12, m(3R² + h²)/12, mR²/2).

    Parameters
    ----------
    m : array_like, shape (...)
        Mass (kg), ≥ 0 (a zero mass gives the zero tensor).
    R : array_like, shape (...)
        Radius (m), > 0.
    h : array_like, shape (...)
        Height along e3 (m), > 0.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        diag(m(3R² + h²)/12, m(3R² + h²)/12, mR²/2) (kg m²), about G.

    Raises
    ------
    NegativeMassError
        ``m`` has a negative entry.
    NonPositiveParameterError
        ``R`` or ``h`` has an entry ≤ 0 (the message names it).
    NonFiniteError
        A NaN or infinite input.
    ShapeError
        Inputs whose shapes do not broadcast (the message lists each argument's shape), or an
        input that is not an array of real numbers.
    ResultOverflowError
        An entry beyond float64 (m times a squared length near 1e308).

    Examples
    --------
    A very flat cylinder is a disc:

    >>> bool(np.allclose(cylinder(1.0, 1.0, 1e-9), disc(1.0, 1.0), rtol=1e-16, atol=0))
    True
    """

    def f(m: np.ndarray, r: np.ndarray, h: np.ndarray) -> np.ndarray:
        out: np.ndarray = m * (3.0 * r * r + h * h) / 12.0
        return out

    return _diag(m, [("R", R), ("h", h)], f, f, lambda m, r, h: m * r * r / 2.0)


cylinder = broadcast_checked(cylinder)


def cylindrical_shell(m: npt.ArrayLike, R: npt.ArrayLike, h: npt.ArrayLike) -> np.ndarray:
    """Thin-walled open cylindrical shell (tube), radius R, height h, axis e3, about G.

    Domain: as :func:`cylinder`: ``m`` ≥ 0, ``R``, ``h`` > 0, a result beyond float64 raising
    ResultOverflowError; batches that do not broadcast raise ShapeError listing each argument's
    shape.

    diag(m(6R² + h²)/12, m(6R² + h²)/12, mR²); Problem 3.3's hollow wheels.

    Parameters
    ----------
    m : array_like, shape (...)
        Mass (kg), ≥ 0 (a zero mass gives the zero tensor).
    R : array_like, shape (...)
        Radius (m), > 0.
    h : array_like, shape (...)
        Height along e3 (m), > 0.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        diag(m(6R² + h²)/12, m(6R² + h²)/12, mR²) (kg m²), about G.

    Raises
    ------
    NegativeMassError
        ``m`` has a negative entry.
    NonPositiveParameterError
        ``R`` or ``h`` has an entry ≤ 0 (the message names it).
    NonFiniteError
        A NaN or infinite input.
    ShapeError
        Inputs whose shapes do not broadcast (the message lists each argument's shape), or an
        input that is not an array of real numbers.
    ResultOverflowError
        An entry beyond float64 (m times a squared length near 1e308).

    Examples
    --------
    A very short shell is a ring:

    >>> bool(np.allclose(cylindrical_shell(1.0, 1.0, 1e-9), ring(1.0, 1.0), rtol=1e-16, atol=0))
    True
    """

    def f(m: np.ndarray, r: np.ndarray, h: np.ndarray) -> np.ndarray:
        out: np.ndarray = m * (6.0 * r * r + h * h) / 12.0
        return out

    return _diag(m, [("R", R), ("h", h)], f, f, lambda m, r, h: m * r * r)


cylindrical_shell = broadcast_checked(cylindrical_shell)


def solid_sphere(m: npt.ArrayLike, R: npt.ArrayLike) -> np.ndarray:
    """Homogeneous solid sphere about its centre: (2/5) m R² 1.

    Domain: as :func:`ring`: ``m`` ≥ 0, ``R`` > 0 (NegativeMassError, NonPositiveParameterError), a
    result beyond float64 raising ResultOverflowError; batches that do not broadcast raise
    ShapeError listing each argument's shape.

    Parameters
    ----------
    m : array_like, shape (...)
        Mass (kg), ≥ 0 (a zero mass gives the zero tensor).
    R : array_like, shape (...)
        Radius (m), > 0.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        (2/5) m R² 1 (kg m²), about the centre.

    Raises
    ------
    NegativeMassError
        ``m`` has a negative entry.
    NonPositiveParameterError
        ``R`` has an entry ≤ 0 (the message names it).
    NonFiniteError
        A NaN or infinite input.
    ShapeError
        Inputs whose shapes do not broadcast (the message lists each argument's shape), or an
        input that is not an array of real numbers.
    ResultOverflowError
        An entry beyond float64 (m times a squared length near 1e308).

    Examples
    --------
    tr J = 2 J_S (4.35) with J_S = Σ m |r|² = (3/5) m R² for a ball:

    >>> float(solid_sphere(5.0, 1.0)[1, 1])
    2.0
    >>> float(np.trace(solid_sphere(5.0, 1.0))), 2 * 3.0 * 5.0 / 5
    (6.0, 6.0)
    """
    f = lambda m, r: 0.4 * m * r * r  # noqa: E731
    return _diag(m, [("R", R)], f, f, f)


solid_sphere = broadcast_checked(solid_sphere)


def hollow_sphere(m: npt.ArrayLike, R: npt.ArrayLike) -> np.ndarray:
    """Thin homogeneous spherical shell about its centre: (2/3) m R² 1.

    Domain: as :func:`ring`: ``m`` ≥ 0, ``R`` > 0 (NegativeMassError, NonPositiveParameterError), a
    result beyond float64 raising ResultOverflowError; batches that do not broadcast raise
    ShapeError listing each argument's shape.

    Parameters
    ----------
    m : array_like, shape (...)
        Mass (kg), ≥ 0 (a zero mass gives the zero tensor).
    R : array_like, shape (...)
        Radius (m), > 0.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        (2/3) m R² 1 (kg m²), about the centre.

    Raises
    ------
    NegativeMassError
        ``m`` has a negative entry.
    NonPositiveParameterError
        ``R`` has an entry ≤ 0 (the message names it).
    NonFiniteError
        A NaN or infinite input.
    ShapeError
        Inputs whose shapes do not broadcast (the message lists each argument's shape), or an
        input that is not an array of real numbers.
    ResultOverflowError
        An entry beyond float64 (m times a squared length near 1e308).

    Examples
    --------
    tr J = 2 J_S (4.35) with J_S = m R²: all the mass is at distance R:

    >>> float(hollow_sphere(3.0, 1.0)[2, 2])
    2.0
    >>> float(np.trace(hollow_sphere(3.0, 1.0))), 2 * 3.0 * 1.0**2
    (6.0, 6.0)
    """
    f = lambda m, r: 2.0 * m * r * r / 3.0  # noqa: E731
    return _diag(m, [("R", R)], f, f, f)


hollow_sphere = broadcast_checked(hollow_sphere)


def rectangular_plate(m: npt.ArrayLike, a: npt.ArrayLike, b: npt.ArrayLike) -> np.ndarray:
    """Thin rectangular plate, side a along e1 and b along e2, about G.

    Domain: ``m`` ≥ 0 (else NegativeMassError), ``a``, ``b`` > 0 (else NonPositiveParameterError
    naming it), finite, broadcast together; a result beyond float64 raises ResultOverflowError;
    batches that do not broadcast raise ShapeError listing each argument's shape.

    diag(m b²/12, m a²/12, m(a² + b²)/12).

    Parameters
    ----------
    m : array_like, shape (...)
        Mass (kg), ≥ 0 (a zero mass gives the zero tensor).
    a : array_like, shape (...)
        Side along e1 (m), > 0.
    b : array_like, shape (...)
        Side along e2 (m), > 0.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        diag(m b²/12, m a²/12, m(a² + b²)/12) (kg m²), about G.

    Raises
    ------
    NegativeMassError
        ``m`` has a negative entry.
    NonPositiveParameterError
        ``a`` or ``b`` has an entry ≤ 0 (the message names it).
    NonFiniteError
        A NaN or infinite input.
    ShapeError
        Inputs whose shapes do not broadcast (the message lists each argument's shape), or an
        input that is not an array of real numbers.
    ResultOverflowError
        An entry beyond float64 (m times a squared length near 1e308).

    Examples
    --------
    A square plate: J1 = J2 = J3/2.

    >>> np.diag(rectangular_plate(12.0, 1.0, 1.0)).tolist()
    [1.0, 1.0, 2.0]
    """
    return _diag(
        m,
        [("a", a), ("b", b)],
        lambda m, a, b: m * b * b / 12.0,
        lambda m, a, b: m * a * a / 12.0,
        lambda m, a, b: m * (a * a + b * b) / 12.0,
    )


rectangular_plate = broadcast_checked(rectangular_plate)


def box(m: npt.ArrayLike, a: npt.ArrayLike, b: npt.ArrayLike, c: npt.ArrayLike) -> np.ndarray:
    """Homogeneous rectangular box (cuboid), sides a, b, c along e1, e2, e3, about G.

    Domain: ``m`` ≥ 0 (else NegativeMassError), ``a``, ``b``, ``c`` > 0 (else
    NonPositiveParameterError naming it), finite, broadcast together; a result beyond float64 raises
    ResultOverflowError; batches that do not broadcast raise ShapeError listing each argument's
    shape.

    diag(m(b² + c²)/12, m(a² + c²)/12, m(a² + b²)/12).  A cube of side 2a
    (Problem 4.4) has (2/3) m a² 1.

    Parameters
    ----------
    m : array_like, shape (...)
        Mass (kg), ≥ 0 (a zero mass gives the zero tensor).
    a : array_like, shape (...)
        Side along e1 (m), > 0.
    b : array_like, shape (...)
        Side along e2 (m), > 0.
    c : array_like, shape (...)
        Side along e3 (m), > 0.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        diag(m(b² + c²)/12, m(a² + c²)/12, m(a² + b²)/12) (kg m²), about G.

    Raises
    ------
    NegativeMassError
        ``m`` has a negative entry.
    NonPositiveParameterError
        ``a``, ``b`` or ``c`` has an entry ≤ 0 (the message names it).
    NonFiniteError
        A NaN or infinite input.
    ShapeError
        Inputs whose shapes do not broadcast (the message lists each argument's shape), or an
        input that is not an array of real numbers.
    ResultOverflowError
        An entry beyond float64 (m times a squared length near 1e308).

    Examples
    --------
    >>> float(box(3.0, 2.0, 2.0, 2.0)[0, 0]), 2.0 / 3.0 * 3.0 * 1.0**2
    (2.0, 2.0)
    """
    return _diag(
        m,
        [("a", a), ("b", b), ("c", c)],
        lambda m, a, b, c: m * (b * b + c * c) / 12.0,
        lambda m, a, b, c: m * (a * a + c * c) / 12.0,
        lambda m, a, b, c: m * (a * a + b * b) / 12.0,
    )


box = broadcast_checked(box)


def solid_cone(m: npt.ArrayLike, R: npt.ArrayLike, h: npt.ArrayLike) -> np.ndarray:
    """Homogeneous solid right circular cone, base radius R, height h, axis e3, about G.

    Domain: as :func:`cylinder`: ``m`` ≥ 0, ``R``, ``h`` > 0 (NegativeMassError,
    NonPositiveParameterError), a result beyond float64 raising ResultOverflowError; batches that do
    not broadcast raise ShapeError listing each argument's shape.

    G lies on the axis at h/4 above the base.  diag(3m(4R² + h²)/80,
    3m(4R² + h²)/80, 3mR²/10).

    Parameters
    ----------
    m : array_like, shape (...)
        Mass (kg), ≥ 0 (a zero mass gives the zero tensor).
    R : array_like, shape (...)
        Base radius (m), > 0.
    h : array_like, shape (...)
        Height along e3 (m), > 0.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        diag(3m(4R² + h²)/80, 3m(4R² + h²)/80, 3mR²/10) (kg m²), about G.

    Raises
    ------
    NegativeMassError
        ``m`` has a negative entry.
    NonPositiveParameterError
        ``R`` or ``h`` has an entry ≤ 0 (the message names it).
    NonFiniteError
        A NaN or infinite input.
    ShapeError
        Inputs whose shapes do not broadcast (the message lists each argument's shape), or an
        input that is not an array of real numbers.
    ResultOverflowError
        An entry beyond float64 (m times a squared length near 1e308).

    Examples
    --------
    About the apex (3h/4 from G) the transverse moment is 3m(R²/4 + h²)/5:

    >>> J = parallel_axis(solid_cone(1.0, 1.0, 2.0), 1.0, [0.0, 0.0, 1.5])
    >>> bool(np.isclose(J[0, 0], 3.0 * (0.25 + 4.0) / 5.0, rtol=4e-16, atol=0))
    True
    """

    def f(m: np.ndarray, r: np.ndarray, h: np.ndarray) -> np.ndarray:
        out: np.ndarray = 3.0 * m * (4.0 * r * r + h * h) / 80.0
        return out

    return _diag(m, [("R", R), ("h", h)], f, f, lambda m, r, h: 0.3 * m * r * r)


solid_cone = broadcast_checked(solid_cone)
