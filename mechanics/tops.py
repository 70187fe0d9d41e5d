"""Exact motions of tops: spherical, free symmetric, heavy symmetric, free asymmetric.

Conventions (Essén 1996, ch. 5)
-------------------------------
- **Body frame A** is a principal-axes frame with moments (J1, J2, J3) (any order
  for the free asymmetric top; the tops sort them internally by a proper signed
  permutation).  **Space frame O** is inertial.  Attitudes are the book's passive
  matrices ``R_A_O`` = ^A R^O of :mod:`mechanics.rotation` (rows: body axes in
  space components), so body components are ``v_A = R_A_O @ v_O`` and the
  attitude obeys dR_A_O/dt = −[ω_A]× R_A_O.
- **Euler angles z-x-z** as in :mod:`mechanics.rotation`: ^A R^O = R3(φ) R1(θ) R3(ψ)
  with ψ the precession about e^O_3, θ the nutation, φ the spin (the book's
  figures 5.2–5.3; ψ̇ = precession rate, φ̇ = spin rate relative to the B frame).
- Angular velocity ``omega`` is ω_A (body components) unless the name says ``_O``.
- The heavy top's J_1 is the transverse moment **about the fixed point C**
  (the book's J'1 = J1 + mℓ², (5.46)); ``m_g_ell`` is m g ℓ > 0.
- The elliptic parameter is m = k² with its complement m1 computed exactly
  (see :mod:`mechanics.elliptic`).

The free asymmetric top (5.3)
-----------------------------
With J1 < J2 < J3 sorted, the signs of D = L² − 2EJ2 = J3(J3−J2)ω3² − J1(J2−J1)ω1²
pick the side of the separatrix: D > 0, ω circulates about axis 3,
ω = (σa1 cn, σs3 a2 sn, s3 a3 dn)(λt + u0); D < 0, about axis 1,
ω = (s1 a1 dn, s1 a2 sn, a3 cn)(λt + u0); D = 0, the separatrix m = 1
(sn = tanh, cn = dn = sech).  The quantities A = 2EJ3 − L², B = L² − 2EJ1, D
and the parameter m and its complement m1 = (J3−J1)|D|/(…) are computed in
exact rational arithmetic from the float inputs (on integers: a float is an integer
times a power of two) and rounded once, so that the
distance from the separatrix is never lost to cancellation.  The attitude:
L is fixed in space; in a body frame whose third axis (the pole) is axis 1 or 3
(L never reaches either: it circulates one and stays off the other), the unit vector
L_A/|L| fixes θ and φ, and the precession about L is the closed form
ψ(t) = ψ(0) + |L| t/J_c ± (C/λ)[G(u) − G(u0)], G(u) = ∫₀^u n sn²/(1 − n sn²) dv,
the elliptic integral of the third kind in Jacobi's form (Carlson's R_J,
:func:`mechanics.elliptic.ellippi_jacobi`), not a quadrature.  The two poles' n
multiply to m; the pole of the smaller |n| is taken, where ψ is nearest uniform: the
axis ω does not circulate, except for a nearly symmetric body, whose symmetry axis
it is (n = 0 exactly for a symmetric one; the other choice cancels, 2e-9 of the
attitude lost for J_mid 4 ulps from J_max).
Steady rotations (ω along a principal axis or in a degenerate plane, the
spherical top, ω = 0) are exact constant-ω motions, never NaN.

Accuracy (``tests/stability/test_tops_stability.py``): ω(t) against mpmath's
Taylor ODE solver at 40 digits (no elliptic function involved) for tops within
1e-16 of the separatrix, on it, and away from it, to t = 20: worst 0.51 eps of
|ω0| per unit of elliptic phase (1 + λt); the attitude 3.95 eps per unit phase;
against mpmath's elliptic functions at the exact parameters with m1 down to
1e-280 (hypothesis, 1000 examples): 1.39 eps.  The heavy top's roots u1, u2 are within 4.2 eps
of mpmath's, the double root of steady precession included.
Cost (``tests/benchmarks/test_bench_compiled.py`` and ``test_bench_tops.py``, a
shared 2-core machine, issues 15 and 30): one instant given as a Python float takes the
one-instant path (the array path's steps on floats with :mod:`math`; K, the AGM of
p ≤ 1/2 and Π − K computed once per top): ``state(t)`` (ω and the attitude
together) 14 µs, ``omega(t)`` 3.5 µs, where the array path takes 0.11 ms (0.32 ms
before issue 15).  Over 10^6 times ``state`` costs 0.76–1.2 µs per time (by the
machine's load; 3.8 times less than one pass over all times, 2.8–4.7 µs), in chunks of
2^14 times whose temporaries stay in the cache; ``omega`` 0.16 µs: ω and the precession
angle share one reduction of the elliptic argument, Π − K is not re-evaluated per time,
and the attitude's products are one matrix product per chunk; the R_J of the precession
angle is about half of the rest.  The two paths agree within 32 eps (measured 5.9) and meet
the mpmath oracles above with the same worst errors (both are tested).  Building a top
(issue 30) takes the exact rationals on Python integers (:func:`_dyadic`: the floats
Fraction arithmetic gives, at a tenth of its cost) and everything else on Python floats:
85–135 µs for the free asymmetric top (1.3 ms before), 16–25 µs for the free symmetric
top, 28–70 µs for the heavy top, under the same load.  :class:`FreeTopBatch` evaluates
many tops at one instant each in one call, the array path's steps over the tops: 1.3–2.2
µs per top for 10^4 tops, 39 times less than their one-instant calls one by one.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction

import numpy as np
import numpy.typing as npt
import scipy.special as sc

from . import elliptic
from ._floats import EPS
from ._validate import as_float_array, as_float_scalar, as_positive_scalar, finite_result
from .errors import (
    GimbalLockError,
    MechanicsValueError,
    NonPhysicalInertiaError,
    OutOfDomainError,
    ResultOverflowError,
    ShapeError,
    UnknownOptionError,
)
from .rotation import R3, check_rotation, matrix_from_rotvec

__all__ = [
    "BATCH_EPS",
    "EPS",
    "FreeAsymmetricTop",
    "FreeSymmetricTop",
    "FreeTopBatch",
    "HeavySymmetricTop",
    "StabilityResult",
    "check_principal_moments",
    "principal_axis_stability",
    "sleeping_top_is_stable",
    "spherical_top_on_incline",
    "steady_precession_rates",
]


# --------------------------------------------------------------------------- helpers


def check_principal_moments(J: npt.ArrayLike, *, name: str = "J") -> npt.NDArray[np.float64]:
    """Validate principal moments (J1, J2, J3): positive and J_i ≤ J_j + J_k.

    Domain: any finite positive moments (1e-300 … 1e300 and beyond: the check compares moments, it
    does not square them).

    The triangle inequality is checked exactly (on the rationals of the floats).

    Parameters
    ----------
    J : array_like, shape (3,)
        Principal moments (J1, J2, J3), kg m², in any order.
    name : str
        The name used in error messages.

    Returns
    -------
    ndarray, shape (3,)
        The moments as float64, unchanged.

    Raises
    ------
    NonPhysicalInertiaError
        Naming the violated condition and by how much.
    NonFiniteError
        If a moment is NaN or infinite.
    ShapeError
        If ``J`` is not a real numeric array of shape (3,).

    Examples
    --------
    A flat body, J1 + J2 = J3 exactly, passes; one beyond it does not:

    >>> check_principal_moments([1.0, 2.0, 3.0]).tolist()
    [1.0, 2.0, 3.0]
    >>> check_principal_moments([1.0, 2.0, 4.0])  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    mechanics.errors.NonPhysicalInertiaError: J breaks the triangle inequality J1 + J2 ≥ J3: ...
    """
    J = as_float_array(J, name, (3,))
    if J.shape != (3,):
        raise ShapeError(f"{name} must have shape (3,); got {J.shape}")
    for i in range(3):
        if not J[i] > 0:
            raise NonPhysicalInertiaError(
                f"{name} must be positive: {name}{i + 1} = {float(J[i])!r} ≤ 0"
            )
    for i in range(3):
        j, k = (i + 1) % 3, (i + 2) % 3
        excess = Fraction(J[i]) - Fraction(J[j]) - Fraction(J[k])
        if excess > 0:
            a, b = sorted((j + 1, k + 1))
            raise NonPhysicalInertiaError(
                f"{name} breaks the triangle inequality {name}{a} + {name}{b} ≥ {name}{i + 1}: "
                f"{name}{i + 1} exceeds {name}{a} + {name}{b} by {float(excess):.6g} "
                f"(moments {J.tolist()})"
            )
    return J


check_principal_moments = finite_result(check_principal_moments)


def _vec3(x: npt.ArrayLike, name: str) -> npt.NDArray[np.float64]:
    a = as_float_array(x, name, (3,))
    if a.shape != (3,):
        raise ShapeError(f"{name} must have shape (3,); got {a.shape}")
    return a


def _skew(w: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
    return np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])


def _mul3(A: list[list[float]], B: list[list[float]]) -> list[list[float]]:
    """The product of two 3×3 matrices given as nested lists (row times column, left
    to right)."""
    return [
        [A[i][0] * B[0][j] + A[i][1] * B[1][j] + A[i][2] * B[2][j] for j in range(3)]
        for i in range(3)
    ]


def _dyadic(xs: list[float]) -> tuple[list[int], int]:
    """Integers n_i and one exponent e with x_i = n_i 2^e exactly for three floats (a float
    is a dyadic rational): sums and products of such numbers are exact on the integers."""
    (n0, d0), (n1, d1), (n2, d2) = (x.as_integer_ratio() for x in xs)
    d = max(d0, d1, d2)  # denominators are powers of two: d is a multiple of each
    return [n0 * (d // d0), n1 * (d // d1), n2 * (d // d2)], 1 - d.bit_length()


def _float_of(num: int, den: int, e: int = 0) -> float:
    """num/den · 2^e rounded once, the float of ``Fraction(num, den) * 2**e``: Python's
    division of integers is correctly rounded (and raises OverflowError beyond float64,
    as ``float(Fraction)`` does)."""
    if e >= 0:
        return (num << e) / den
    return num / (den << -e)


def _sqrt_of(num: int, den: int, e: int = 0) -> float:
    """√(num/den · 2^e) of a non-negative rational, without under- or overflow: the
    quotient scaled by 4^-k into [1/4, 4), rounded once, its root scaled back by 2^k (the
    same float for any such k: scaling by a power of two commutes with the roundings)."""
    if num == 0:
        return 0.0
    k = (num.bit_length() - den.bit_length() + e) // 2
    return math.ldexp(math.sqrt(_float_of(num, den, e - 2 * k)), k)


def _floats3(x: object) -> list[float] | None:
    """Three finite Python floats from a float64 array of shape (3,) or a list or tuple of
    three floats; None for anything else (the caller validates it the long way)."""
    if isinstance(x, np.ndarray) and type(x) is np.ndarray:
        if x.dtype != np.float64 or x.shape != (3,):
            return None
        xs: list[float] = x.tolist()
    elif isinstance(x, (list, tuple)) and type(x) in (list, tuple) and len(x) == 3:
        xs = list(x)
        if not all(type(v) is float for v in xs):
            return None
    else:
        return None
    return xs if all(math.isfinite(v) for v in xs) else None


def _vec3_list(x: npt.ArrayLike, name: str) -> list[float]:
    """:func:`_vec3` as a list of Python floats (without numpy for three floats)."""
    xs = _floats3(x)
    return xs if xs is not None else _vec3(x, name).tolist()


def _principal_moments_list(J: npt.ArrayLike, name: str) -> list[float]:
    """:func:`check_principal_moments` as a list of Python floats.  Three positive floats
    that pass the triangle inequality with room (J_i < fl(J_j + J_k)(1 − 2⁻⁵²), which
    implies J_i < J_j + J_k exactly: fl's relative error is below 2⁻⁵³), or exactly on
    the integers of :func:`_dyadic` (an equality J3 = J1 + J2), are taken as they are;
    anything else goes the long way, which names what is wrong."""
    xs = _floats3(J)
    if xs is not None and all(v > 0 for v in xs):
        a, b, c = xs
        room = 1.0 - 2.0**-52
        if a < (b + c) * room and b < (c + a) * room and c < (a + b) * room:
            return xs
        (ia, ib, ic), _ = _dyadic(xs)  # near equality (a flat body): exactly
        if ia <= ib + ic and ib <= ic + ia and ic <= ia + ib:
            return xs
    return check_principal_moments(J, name=name).tolist()  # type: ignore[no-any-return]  # a float64 array's tolist


@dataclass(frozen=True)
class _Permutation:
    """The proper signed permutation P taking the moments to ascending order (ω' = P ω)
    and the products with it the free top needs, one per order of the moments."""

    P: npt.NDArray[np.float64]
    signs: tuple[float, float, float]  # (P ω)_i = signs_i ω_{order_i}


def _permutation(order: tuple[int, ...]) -> _Permutation:
    P = np.zeros((3, 3))
    P[np.arange(3), order] = 1.0
    if np.linalg.det(P) < 0:
        P[1] *= -1.0
    P.setflags(write=False)
    return _Permutation(P, (1.0, float(P[1, order[1]]), 1.0))


_PERMUTATIONS = {order: _permutation(order) for order in itertools.permutations(range(3))}


@dataclass(frozen=True)
class _Front:
    """For P of an order of the moments and the pole's axis (Q: the pole frame's axes):
    front = Pᵀ Qᵀ, a signed permutation, as a list and as its rows' columns and signs;
    the columns of Q P as (source row, sign); P as a list."""

    front: list[list[float]]
    rows: npt.NDArray[np.intp]
    signs: npt.NDArray[np.float64]
    qp_columns: tuple[tuple[int, float], ...]
    P_list: list[list[float]]


def _front(order: tuple[int, ...], pole_first: bool) -> _Front:
    P = _PERMUTATIONS[order].P
    Q = np.eye(3)[[1, 2, 0]] if pole_first else np.eye(3)
    front = P.T @ Q.T
    rows = np.abs(front).argmax(axis=1)
    signs = front[np.arange(3), rows]
    rows.setflags(write=False)
    signs.setflags(write=False)
    QP = Q @ P
    src = np.abs(QP).argmax(axis=0)
    qp_columns = tuple((int(k), float(QP[k, j])) for j, k in enumerate(src))
    return _Front(front.tolist(), rows, signs, qp_columns, P.tolist())


_FRONTS = {(o, f): _front(o, f) for o in _PERMUTATIONS for f in (False, True)}


#: below this, (nx, ny) are scaled by 2^600 before their direction is taken
_TINY_POLE = 2.0**-900
#: instants per chunk of :meth:`FreeAsymmetricTop.state` over many times: its ~30 temporaries
#: of this length stay in a 2-core machine's cache (over 10^6 times: 0.82 s in chunks of
#: 2^14, 0.97 s of 2^13, 2.6 s of 2^16 and 1.6–2.8 s in one pass, page faults and memory
#: traffic; measured on the shared machine of issue 30)
_CHUNK = 2**14
#: the smallest normal float64: a circulating amplitude below it is refused
_NORMAL_MIN = float(np.finfo(np.float64).tiny)


def _pole_frame(
    nx: npt.NDArray[np.float64], ny: npt.NDArray[np.float64], nz: npt.NDArray[np.float64]
) -> npt.NDArray[np.float64]:
    """W = R3(φ) R1(θ) whose third column is the unit vector (nx, ny, nz) (arrays).

    (nx, ny) of subnormal size carry fewer significant bits than 53, and so would their
    hypot and the quotients by it (a pole 1.4e-313 off the axis gave a frame 3e-11 off
    orthogonal: found by the scene engine's reversal property): below _TINY_POLE they
    are scaled by 2^600 first, exactly (a power of two); larger ones are taken as they
    are, so those frames are unchanged bit for bit."""
    s = np.hypot(nx, ny)
    up = np.where(np.maximum(np.abs(nx), np.abs(ny)) < _TINY_POLE, 2.0**600, 1.0)
    xs, ys = nx * up, ny * up
    hs = np.hypot(xs, ys)
    sphi, cphi = xs / hs, ys / hs
    z = np.zeros_like(nx)
    return np.stack(
        [
            np.stack([cphi, sphi * nz, sphi * s], axis=-1),
            np.stack([-sphi, cphi * nz, cphi * s], axis=-1),
            np.stack([z, -s, nz], axis=-1),
        ],
        axis=-2,
    )


def _positive_float(x: object) -> bool:
    """x is a Python float, finite and > 0 (the common case, checked without numpy)."""
    return type(x) is float and 0.0 < x < math.inf


def _pole_frame_list(nx: float, ny: float, nz: float) -> list[list[float]]:
    """:func:`_pole_frame` of one unit vector, on Python floats (numpy's hypot, so that
    the frame is the same float for float)."""
    sxy = float(np.hypot(nx, ny))
    up = 2.0**600 if max(abs(nx), abs(ny)) < _TINY_POLE else 1.0
    hs = sxy if up == 1.0 else float(np.hypot(nx * up, ny * up))
    sphi, cphi = nx * up / hs, ny * up / hs
    return [[cphi, sphi * nz, sphi * sxy], [-sphi, cphi * nz, cphi * sxy], [0.0, -sxy, nz]]


# --------------------------------------------------------------------------- free asymmetric top


class FreeAsymmetricTop:
    """The exact torque-free motion of a rigid body (Euler's equations 4.47 with M = 0).

    Domain: principal moments J > 0 that obey the triangle inequality, of any magnitude from 1e-300
    to 1e300 (the motion is computed from J scaled by a power of two, so s·J moves exactly as J; L
    is scaled back, E, |L| and L² − 2EJ2 are the exact values in the units given rounded once:
    an E of 1e-64 or 1e303 beside an ω of 2^∓600 is an ordinary float); any finite ω_0 (0: at
    rest) while |L| and E fit float64 (else ResultOverflowError); within ~1e-150 |ω| of the
    separatrix the complementary parameter underflows (OutOfDomainError), and a circulating
    amplitude below float64's normal range (2.2e-308) beside one within it would carry the
    attitude to fewer than 53 bits (OutOfDomainError; all of them subnormal, the body barely
    turns and is followed).

    Parameters
    ----------
    J : array_like, shape (3,)
        Principal moments about the centre of mass, kg m² (any order, equalities
        allowed).
    omega_0 : array_like, shape (3,)
        Initial angular velocity, body components, rad/s.
    R_A_O_0 : array_like, shape (3, 3), optional
        Initial attitude ^A R^O (default identity).

    Attributes
    ----------
    energy : float
        E = ½ Σ J_i ω_i² (5.85).
    angular_momentum_norm : float
        |L|.
    angular_momentum_space : ndarray, shape (3,)
        L_O, constant.
    m, m1 : float
        Elliptic parameter and its complement (0 and 1 for steady motions).
    regime : str
        ``"rest"``, ``"steady"``, ``"axis3"`` (L² > 2EJ2: ω circulates the axis of
        largest moment), ``"axis1"`` (L² < 2EJ2) or ``"separatrix"``.

    Raises
    ------
    NonPhysicalInertiaError
        If a moment is ≤ 0 or the moments break the triangle inequality.
    OutOfDomainError
        Within ~1e-150 |ω| of the separatrix (m1 underflows), or where a circulating
        amplitude is subnormal beside a normal one.
    ResultOverflowError
        If |L| or E exceeds float64's range.
    NotARotationError
        If ``R_A_O_0`` is not a proper rotation matrix.
    NonFiniteError
        If an input is NaN or infinite.
    ShapeError
        If ``J`` or ``omega_0`` is not of shape (3,), or ``R_A_O_0`` not of shape (3, 3).

    Notes
    -----
    See the module docstring.  ``omega(t)`` and ``attitude(t)`` are vectorised over
    any shape of times.

    Examples
    --------
    Energy and |L| are conserved, and L stays fixed in space:

    >>> top = FreeAsymmetricTop([1.0, 2.0, 3.0], [1.0, 0.1, 0.5])
    >>> w = top.omega([0.0, 7.5])
    >>> bool(np.allclose(0.5 * (w**2 * [1.0, 2.0, 3.0]).sum(-1), top.energy, rtol=1e-14))
    True
    >>> R = top.attitude(7.5)
    >>> L_O = R.T @ (np.array([1.0, 2.0, 3.0]) * w[1])
    >>> bool(np.allclose(L_O, top.angular_momentum_space, rtol=0, atol=1e-13))
    True
    """

    def __init__(
        self, J: npt.ArrayLike, omega_0: npt.ArrayLike, R_A_O_0: npt.ArrayLike | None = None
    ) -> None:
        Jl = _principal_moments_list(J, "J")
        wl = _vec3_list(omega_0, "omega_0")
        self.J = np.array(Jl)
        self.omega_0 = np.array(wl)
        if R_A_O_0 is None:
            self.R_A_O_0 = np.eye(3)
        else:
            R0 = check_rotation(R_A_O_0, name="R_A_O_0")
            if R0.shape != (3, 3):
                raise ShapeError(f"R_A_O_0 must have shape (3, 3); got {R0.shape}")
            self.R_A_O_0 = R0.copy()
        self._setup(Jl, wl, R_A_O_0 is not None)

    __init__ = finite_result(__init__)

    def _setup(self, Jl: list[float], wl: list[float], rotated: bool) -> None:
        """The constants of the motion from validated moments and rates (Python floats).

        The quantities the branch and the elliptic parameter hang on (A, B, D, m, m1,
        the amplitudes, λ, n, C) are exact rationals rounded once, as the module
        docstring says; they are computed on integers (a float is an integer times a
        power of two, :func:`_dyadic`), so that each is the same float that
        ``fractions.Fraction`` arithmetic gives, bit for bit (the constructor takes a tenth
        of the time it took with Fraction)."""
        # The motion depends on J only through its ratios: work with J / 2^k (exact, the
        # largest moment in [1/2, 1)) and scale E, |L| and L back by 2^k at the end, so
        # moments from 1e-300 to 1e300 give the same ω(t) and attitude (issue 16, part 4)
        k = math.frexp(max(Jl))[1]
        self._scale_exp = k
        Jn = [math.ldexp(x, -k) for x in Jl]
        # proper signed permutation P to sorted moments: ω' = P ω, J' sorted
        order = tuple(sorted(range(3), key=Jn.__getitem__))
        perm = _PERMUTATIONS[order]
        self._P = perm.P
        ws = [perm.signs[i] * wl[order[i]] for i in range(3)]
        Jsl = [Jn[i] for i in order]
        self._Js = np.array(Jsl)
        (J1, J2, J3), eJ = _dyadic(Jsl)
        (w1, w2, w3), ew = _dyadic(ws)
        q1, q2, q3 = w1 * w1, w2 * w2, w3 * w3
        e2 = 2 * eJ + 2 * ew  # the exponent of A, B, D and L²
        E2 = J1 * q1 + J2 * q2 + J3 * q3
        L2 = J1 * J1 * q1 + J2 * J2 * q2 + J3 * J3 * q3
        # E and |L| in the units given rounded once from the exact integers with the moments'
        # 2^k folded in: the scaled E (~ω²) under- or overflowed for ω beyond 2^±511 although
        # E fitted (J = 2^990 (1, 2, 3), ω = 2^-600 w gave E = 0 for 5.4e-64)
        self.energy = _float_of(E2, 1, eJ + 2 * ew - 1 + k)
        self._Lm = _sqrt_of(L2, 1, e2)  # |L| of the scaled moments
        self.angular_momentum_norm = _sqrt_of(L2, 1, e2 + 2 * k)
        Lv = [a * b for a, b in zip(Jn, wl, strict=True)]
        if rotated:
            Lv = (self.R_A_O_0.T @ Lv).tolist()
        try:
            Lv = [math.ldexp(x, k) for x in Lv]
        except OverflowError:
            Lv = [math.inf]
        self.angular_momentum_space = np.array(Lv)
        if not all(math.isfinite(x) for x in Lv):
            raise ResultOverflowError(
                f"the angular momentum J ω exceeds float64's range (|L| = "
                f"{self.angular_momentum_norm!r}); rescale J or omega_0 (choose units)"
            )
        A = J1 * (J3 - J1) * q1 + J2 * (J3 - J2) * q2  # 2EJ3 − L²
        B = J2 * (J2 - J1) * q2 + J3 * (J3 - J1) * q3  # L² − 2EJ1
        D = J3 * (J3 - J2) * q3 - J1 * (J2 - J1) * q1  # L² − 2EJ2
        self._separatrix = (D, e2)  # L² − 2EJ2 of the scaled moments: D 2^e2, exact

        nz = [i for i in range(3) if ws[i] != 0]
        steady = all(Jsl[i] == Jsl[nz[0]] for i in nz) if nz else True
        self.m, self.m1 = 0.0, 1.0
        if not nz:
            self.regime = "rest"
        elif steady:
            self.regime = "steady"
        else:
            self._branch3 = D >= 0
            # The pole (third axis of the Euler angles) is axis 1 or axis 3: with pole 1,
            # ψ = L t/J3 − (C/λ)(G − G0); with pole 3, ψ = L t/J1 + (C/λ)(G − G0), G the
            # excess of the third kind (:func:`mechanics.elliptic._third_kind_excess`) of
            # characteristic n1 or n3, where ψ̇ = L (J_a ω_a² + J_b ω_b²)/(J_a² ω_a² +
            # J_b² ω_b²) over the other two axes a, b puts its denominator in the form
            # 1 − n sn².  n1 n3 = m: the pole of the smaller |n| is taken, for which ψ
            # is nearest uniform (n = 0 for a symmetric body: its symmetry axis, the
            # uniform precession).  The other one cancels: for J_mid a few ulps from J_max,
            # n3 ≈ −1e12 and L t/J1 and (C/λ) G agreed to 3e-9 of a turn (issue 16).
            # Each rational is a pair (numerator, denominator) of integers, denominators
            # positive; A, B, D carry 2^e2, the moments 2^eJ, so m, m1 and n are plain
            # quotients, the squared amplitudes and λ² carry 2^(2 ew) and C 2^(−eJ)
            if D >= 0:
                self.regime = "separatrix" if D == 0 else "axis3"
                m = ((J2 - J1) * A, (J3 - J2) * B)
                m1 = ((J3 - J1) * D, (J3 - J2) * B)
                amp = ((A, J1 * (J3 - J1)), (A, J2 * (J3 - J2)), (B, J3 * (J3 - J1)))
                lam2 = ((J3 - J2) * B, J1 * J2 * J3)
                n1 = (-J1 * A, J3 * B)
                n3 = (-J3 * (J2 - J1), J1 * (J3 - J2))
                s_circ = 1 if w3 > 0 else -1
                sigma = (1 if w1 > 0 else -1) if D == 0 else 1
                self._pole_first = abs(n1[0]) * n3[1] <= abs(n3[0]) * n1[1]
            else:
                self.regime = "axis1"
                m = ((J3 - J2) * B, (J2 - J1) * A)
                m1 = ((J3 - J1) * (-D), (J2 - J1) * A)
                amp = ((A, J1 * (J3 - J1)), (B, J2 * (J2 - J1)), (B, J3 * (J3 - J1)))
                lam2 = ((J2 - J1) * A, J1 * J2 * J3)
                n1 = (-J1 * (J3 - J2), J3 * (J2 - J1))
                n3 = (-J3 * B, J1 * A)
                s_circ = 1 if w1 > 0 else -1
                sigma = 1
                self._pole_first = abs(n1[0]) * n3[1] < abs(n3[0]) * n1[1]
            n = n1 if self._pole_first else n3
            self._uniform = n[0] == 0
            self._uniform_rate = 1.0 / (Jsl[2] if self._pole_first else Jsl[0])
            self.m, self.m1 = _float_of(*m), _float_of(*m1)
            if m1[0] > 0 and self.m1 < 2.0**-1022:
                r = Fraction(*m1)
                e2m = r.numerator.bit_length() - r.denominator.bit_length()
                raise OutOfDomainError(
                    f"the motion is within m1 ≈ 2^{e2m} of the separatrix: the "
                    "complementary parameter m1 underflows float64 "
                    "(the transverse components are below ~1e-150 of |ω|); set them to zero "
                    "for the steady rotation or scale them up"
                )
            amps = [_sqrt_of(a, b, 2 * ew) for a, b in amp]
            self._amp = np.array(amps)
            circ = [a for a in amps if a > 0]
            if min(circ) < _NORMAL_MIN <= max(circ):  # (all subnormal: it barely turns)
                raise OutOfDomainError(
                    "a component of ω circulates with an amplitude below float64's normal "
                    f"range ({min(amps):.3g} rad/s after scaling; subnormal "
                    "floats carry fewer than 53 bits, and the pole's azimuth with them: an "
                    "attitude 3e-11 off for 2e-313, 0.24 rad off for 5e-324); set it to zero "
                    "for the steady rotation, or choose units that scale ω up"
                )
            self._lam = _sqrt_of(*lam2, 2 * ew)
            self._n = 0.0 if self._uniform else _float_of(*n)
            self._C = _float_of(J3 - J1, J1 * J3, -eJ) * self._Lm
            self._s, self._sigma = s_circ, sigma
            a1, a2, a3 = amps
            if self._branch3:
                sn0, cn0, dn0 = s_circ * sigma * ws[1] / a2, sigma * ws[0] / a1, abs(ws[2]) / a3
            else:
                sn0, cn0, dn0 = s_circ * ws[1] / a2, ws[2] / a3, abs(ws[0]) / a1
            # constants of the top (issue 15): K, the AGM of p ≤ 1/2, Π − K
            self._K = float(sc.ellipkm1(self.m1))  # elliptic._quarter_period's; inf at m1 = 0
            self._u0 = self._initial_argument(sn0, cn0, dn0)
            self._trig_agm = (
                elliptic._agm_ratios_scalar(self.m, self.m1, False, 0.0) if self.m <= 0.5 else None
            )
            self._full, self._G0 = self._third_kind_constants()
        self._set_attitude_offset(ws, Jsl, order, rotated)

    # -- construction helpers
    def _initial_argument(self, sn0: float, cn0: float, dn0: float) -> float:
        """u0 with sn(u0) = sn0, cn(u0) = cn0, dn(u0) = dn0 (|u0| ≤ 2K)."""
        f = sn0 * float(sc.elliprf(cn0 * cn0, dn0 * dn0, 1.0)) if sn0 != 0 else 0.0
        if cn0 >= 0:
            return f
        return math.copysign(2.0 * self._K, sn0 if sn0 != 0 else 1.0) - f

    def _excess(
        self,
        u: npt.NDArray[np.float64],
        reduced: elliptic._Reduction | None = None,
    ) -> npt.NDArray[np.float64]:
        """G(u) of flat u: :func:`mechanics.elliptic._third_kind_excess` with this top's
        constant n and m, Π − K taken once per top and the reduction of u shared
        with ω when given (the same arithmetic)."""
        if self.m1 <= 0:
            n = np.full_like(u, self._n)
            m, m1 = np.full_like(u, self.m), np.full_like(u, self.m1)
            return elliptic._third_kind_excess(u, n, m, m1)
        if reduced is None:
            reduced = self._reduce(u)
        j, s, snx, cnx, dnx, _ = reduced
        tail = elliptic._third_kind_tail_reduced(s * snx, cnx, dnx, np.full_like(u, self._n))
        return tail + 2.0 * j * np.where(j != 0, self._full, 0.0)

    def _reduce(self, flat: npt.NDArray[np.float64]) -> elliptic._Reduction:
        return elliptic._reduced(flat, np.full_like(flat, self.m), np.full_like(flat, self.m1))

    def _sorted_omega(
        self, t: npt.NDArray[np.float64], with_reduced: bool = False
    ) -> (
        npt.NDArray[np.float64]
        | tuple[
            npt.NDArray[np.float64],
            elliptic._Reduction,
        ]
    ):
        """ω in the sorted frame, shape t.shape + (3,) (and the reduction of λt + u0)."""
        if self.regime in ("rest", "steady"):
            return np.broadcast_to(self._P @ self.omega_0, (*t.shape, 3)).copy()
        u = self._lam * t + self._u0
        red = self._reduce(np.ascontiguousarray(u, dtype=np.float64).ravel())
        j, sr, snx, cnx, dnx, _ = red  # ellipj's steps for 0 ≤ m ≤ 1
        sign = 1.0 - 2.0 * np.mod(j, 2.0)
        sn = (sign * sr * snx).reshape(u.shape)
        cn = (sign * cnx).reshape(u.shape)
        dn = dnx.reshape(u.shape)
        a1, a2, a3 = self._amp
        s, sg = self._s, self._sigma
        if self._branch3:
            w = (sg * a1 * cn, sg * s * a2 * sn, s * a3 * dn)
        else:
            w = (s * a1 * dn, s * a2 * sn, a3 * cn)
        return (np.stack(w, axis=-1), red) if with_reduced else np.stack(w, axis=-1)

    def _pole_vector(self, ws: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        """L in the pole frame (third axis = the axis ω does not circulate), normalised;
        ω is scaled by its largest component first (J ω of a subnormal ω underflows)."""
        ws = ws / np.abs(ws).max(axis=-1, keepdims=True)
        L = self._Js * ws
        if self._pole_first:
            L = L[..., [1, 2, 0]]
        L = L / np.abs(L).max(axis=-1, keepdims=True)  # no underflow in the norm
        return L / np.linalg.norm(L, axis=-1, keepdims=True)  # type: ignore[no-any-return]  # numpy types norm(axis=) as Any

    def _third_kind_constants(self) -> tuple[float, float]:
        """(Π − K of the top's n, G(u0)): :func:`mechanics.elliptic._complete_tail` and
        :meth:`_excess` at u0 on Python floats, their two R_J in one call of scipy's."""
        n, m, m1 = self._n, self.m, self.m1
        if n == 0:
            return 0.0, 0.0
        if m1 <= 0:  # the separatrix: G in closed form; Π − K (infinite) is never used
            a = math.sqrt(abs(n))
            th = math.tanh(self._u0)
            neg = a * math.atan(a * th) if n < 0 else -a * math.atanh(a * th)
            return float(elliptic._complete_tail(n, m1)), (n * self._u0 + neg) / (1.0 - n)
        j, s, snx, cnx, dnx = elliptic._reduced_scalar(self._u0, m, m1, self._K, self._trig_agm)
        S = s * snx
        x, y, p = cnx * cnx, dnx * dnx, 1.0 - n * (S * S)
        if m1 < elliptic._RJ_TINY or max(x, y) < elliptic._RJ_TINY:
            # near the separatrix: elliptic's R_J for tiny arguments (scipy's is inf at
            # R_J(0, m1, 1, p) for m1 ≲ 7e-308), and near u = K by cn and dn themselves
            # (their squares subnormal): as elliptic._third_kind_excess_scalar
            rj_full = elliptic._rj_scalar(0.0, m1, 1.0, 1.0 - n)
            if dnx < elliptic._RJ_TINY_ROOT:
                rj = float(elliptic._rj_of_roots(cnx, dnx, 1.0, p))
            else:
                rj = elliptic._rj_scalar(x, y, 1.0, p)
        else:
            args = np.array([[0.0, x], [m1, y], [1.0 - n, p]])  # one array, not three
            rj_full, rj = sc.elliprj(args[0], args[1], 1.0, args[2]).tolist()
        full = (n / 3.0) * rj_full
        tail = 0.0 if S == 0 else (n / 3.0) * (S * S) * S * rj
        return full, (tail + 2.0 * j * full if j != 0 else tail + 0.0)

    def _set_attitude_offset(
        self, ws: list[float], Jsl: list[float], order: tuple[int, ...], rotated: bool
    ) -> None:
        """M0 = W0ᵀ Q P R0 (W0 the pole frame at t = 0) and the constant products of the
        attitude; :meth:`_pole_vector` and :func:`_pole_frame`'s steps on Python floats."""
        if self.regime in ("rest", "steady"):
            self._M0 = None
            return
        fr = _FRONTS[order, self._pole_first]
        mx = max(abs(ws[0]), abs(ws[1]), abs(ws[2]))
        L = [Jsl[i] * (ws[i] / mx) for i in range(3)]
        if self._pole_first:
            L = [L[1], L[2], L[0]]
        mx = max(abs(L[0]), abs(L[1]), abs(L[2]))
        L = [x / mx for x in L]
        nrm = math.sqrt(L[0] * L[0] + L[1] * L[1] + L[2] * L[2])
        nx, ny, nz = (x / nrm for x in L)
        W0 = _pole_frame_list(nx, ny, nz)
        # W0ᵀ Q P: Q P is a signed permutation, so each column is a column of W0ᵀ (a row
        # of W0) times ±1, exactly
        M0 = [[W0[k][i] * sign for k, sign in fr.qp_columns] for i in range(3)]
        if rotated:
            self._M0 = np.array(M0) @ self.R_A_O_0
            self._M0_list = self._M0.tolist()
        else:
            self._M0, self._M0_list = np.array(M0), M0
        self._front = fr.front
        self._front_rows = fr.rows
        self._front_signs = fr.signs
        self._P_list = fr.P_list

    # -- one instant in Python floats (issue 15): the array path's steps, without
    # numpy's per-call overhead; the same values within ONE_INSTANT_EPS
    def _sorted_omega_scalar(self, t: float) -> tuple[tuple[float, float, float], float]:
        u = self._lam * t + self._u0
        sn, cn, dn = elliptic._ellipj_scalar(u, self.m, self.m1, self._K, self._trig_agm)
        a1, a2, a3 = self._amp.tolist()
        s, sg = self._s, self._sigma
        if self._branch3:
            return (sg * a1 * cn, sg * s * a2 * sn, s * a3 * dn), u
        return (s * a1 * dn, s * a2 * sn, a3 * cn), u

    def _omega_scalar(self, ws: tuple[float, float, float]) -> npt.NDArray[np.float64]:
        P = self._P_list
        return np.array([ws[0] * P[0][i] + ws[1] * P[1][i] + ws[2] * P[2][i] for i in range(3)])

    def _attitude_scalar(
        self, t: float, ws: tuple[float, float, float], u: float
    ) -> npt.NDArray[np.float64]:
        m = max(abs(ws[0]), abs(ws[1]), abs(ws[2]))
        Js = self._Js.tolist()
        L = [Js[i] * (ws[i] / m) for i in range(3)]
        if self._pole_first:
            L = [L[1], L[2], L[0]]
        m = max(abs(L[0]), abs(L[1]), abs(L[2]))
        L = [x / m for x in L]
        nrm = math.sqrt(L[0] * L[0] + L[1] * L[1] + L[2] * L[2])
        nx, ny, nz = (x / nrm for x in L)
        sxy = math.hypot(nx, ny)
        up = 2.0**600 if max(abs(nx), abs(ny)) < _TINY_POLE else 1.0  # see _pole_frame
        hs = math.hypot(nx * up, ny * up)
        sphi, cphi = nx * up / hs, ny * up / hs
        W = [[cphi, sphi * nz, sphi * sxy], [-sphi, cphi * nz, cphi * sxy], [0.0, -sxy, nz]]
        Lm = self._Lm  # the scaled moments' |L|: ψ is invariant under J → s J
        if self._uniform:
            psi = Lm * self._uniform_rate * t
        else:
            G = elliptic._third_kind_excess_scalar(
                u, self._n, self.m, self.m1, self._K, self._trig_agm, self._full
            )
            J1, J3 = Js[0], Js[2]
            if self._pole_first:
                psi = Lm * t / J3 - (self._C / self._lam) * (G - self._G0)
            else:
                psi = Lm * t / J1 + (self._C / self._lam) * (G - self._G0)
        c, s = math.cos(psi), math.sin(psi)
        R = [[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]]
        out = _mul3(_mul3(_mul3(self._front, W), R), self._M0_list)
        return np.array(out)

    # -- public API
    def _get_separatrix_distance(self) -> float:
        """L² − 2 E J_mid in the units given: its sign gives the regime, zero on the
        separatrix; the exact value (an integer times a power of two, for the moments scaled
        by 2^-k) rounded once with 4^k folded in.  A
        :class:`~mechanics.errors.ResultOverflowError` when it is beyond float64 (moments
        and rates with L² beyond ~1e308)."""
        D, e = self._separatrix
        try:
            return _float_of(D, 1, e + 2 * self._scale_exp)
        except OverflowError:
            raise ResultOverflowError(
                "separatrix_distance: L² − 2 E J_mid overflows float64 for these moments "
                f"(|L² − 2 E J_mid| ≥ 2^{abs(D).bit_length() - 1 + e + 2 * self._scale_exp}, "
                f"|L| = {self.angular_momentum_norm!r})"
            ) from None

    # applied after the definition, so that mutmut mutates the function (it skips decorated ones)
    separatrix_distance = property(_get_separatrix_distance)

    def omega(self, t: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """Angular velocity ω_A(t), body components, shape ``t.shape + (3,)``."""
        if type(t) is float and math.isfinite(t) and self._M0 is not None:
            return self._omega_scalar(self._sorted_omega_scalar(t)[0])
        t = as_float_array(t, "t")
        return self._sorted_omega(t) @ self._P  # Pᵀ ω' as a row-vector product

    omega = finite_result(omega)

    def state(self, t: npt.ArrayLike) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
        """(ω_A(t), ^A R^O(t)) together, sharing the elliptic functions of ω: shapes
        ``t.shape + (3,)`` and ``t.shape + (3, 3)``."""
        if type(t) is float and math.isfinite(t) and self._M0 is not None:
            ws, u = self._sorted_omega_scalar(t)
            return self._omega_scalar(ws), self._attitude_scalar(t, ws, u)
        t = as_float_array(t, "t")
        if self._M0 is None:
            return self.omega(t), self.attitude(t)
        if t.size <= _CHUNK:
            ws, red = self._sorted_omega(t, with_reduced=True)
            return ws @ self._P, self._attitude_from(t, ws, red)
        # many instants: in chunks, whose temporaries stay in the cache (elementwise, the
        # same values as one pass, up to the hyperbolic AGM's step count, set per chunk)
        flat = t.ravel()
        w_out = np.empty((flat.size, 3))
        R_out = np.empty((flat.size, 3, 3))
        for i in range(0, flat.size, _CHUNK):
            tc = flat[i : i + _CHUNK]
            ws, red = self._sorted_omega(tc, with_reduced=True)
            np.matmul(ws, self._P, out=w_out[i : i + _CHUNK])
            self._attitude_from(tc, ws, red, out=R_out[i : i + _CHUNK])
        return w_out.reshape(*t.shape, 3), R_out.reshape(*t.shape, 3, 3)

    state = finite_result(state)

    def angular_momentum_body(self, t: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """L_A(t) = J ω_A(t)."""
        return self.J * self.omega(t)

    angular_momentum_body = finite_result(angular_momentum_body)

    def precession_angle(
        self,
        t: npt.ArrayLike,
        _reduced: elliptic._Reduction | None = None,
    ) -> npt.NDArray[np.float64]:
        """ψ(t) − ψ(0), the turn of the body about the fixed L (closed form, third kind);
        0 at rest and for a steady rotation, where ω ∥ L and the whole turn is spin about
        the pole, which then lies along L (the attitude is exp(t ω))."""
        t = as_float_array(t, "t")
        if self.regime in ("rest", "steady"):
            return np.zeros_like(t)
        Lm = self._Lm  # the scaled moments' |L|: ψ is invariant under J → s J
        if self._uniform:
            return Lm * self._uniform_rate * t
        u = self._lam * t + self._u0
        G: npt.NDArray[np.float64] = self._excess(
            np.ascontiguousarray(u).ravel(), _reduced
        ).reshape(u.shape)
        J1: float
        J3: float
        J1, _, J3 = self._Js
        if self._pole_first:
            return Lm * t / J3 - (self._C / self._lam) * (G - self._G0)
        return Lm * t / J1 + (self._C / self._lam) * (G - self._G0)

    precession_angle = finite_result(precession_angle)

    def attitude(self, t: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """The attitude ^A R^O(t), shape ``t.shape + (3, 3)``."""
        if type(t) is float and math.isfinite(t) and self._M0 is not None:
            return self._attitude_scalar(t, *self._sorted_omega_scalar(t))
        t = as_float_array(t, "t")
        if self.regime in ("rest", "steady"):
            rv = t[..., None] * self.omega_0
            return matrix_from_rotvec(rv) @ self.R_A_O_0
        return self._attitude_from(t, self._sorted_omega(t))  # type: ignore[arg-type]  # without with_reduced: an array

    attitude = finite_result(attitude)

    def _attitude_from(
        self,
        t: npt.NDArray[np.float64],
        ws: npt.NDArray[np.float64],
        reduced: elliptic._Reduction | None = None,
        out: npt.NDArray[np.float64] | None = None,
    ) -> npt.NDArray[np.float64]:
        nvec = self._pole_vector(ws).reshape(-1, 3)
        psi = self.precession_angle(t, reduced).reshape(-1)
        # W = R3(φ) R1(θ) of :func:`_pole_frame` (its steps, the rows of W written in place),
        # then front W R3(ψ) M0 with front a signed permutation (exact on any side): the rows
        # of W R3(ψ) taken in front's order and sign, then one matrix product with M0
        nx, ny, nz = nvec[:, 0], nvec[:, 1], nvec[:, 2]
        sxy = np.hypot(nx, ny)
        if np.any(np.maximum(np.abs(nx), np.abs(ny)) < _TINY_POLE):
            W = _pole_frame(nx, ny, nz)
        else:  # _pole_frame's scaling by 1: its hypot is sxy, its quotients these
            sphi, cphi = nx / sxy, ny / sxy
            W = np.empty((nx.size, 3, 3))
            W[:, 0, 0], W[:, 1, 0], W[:, 2, 0] = cphi, -sphi, 0.0
            np.multiply(sphi, nz, out=W[:, 0, 1])
            np.multiply(cphi, nz, out=W[:, 1, 1])
            np.negative(sxy, out=W[:, 2, 1])
            np.multiply(sphi, sxy, out=W[:, 0, 2])
            np.multiply(cphi, sxy, out=W[:, 1, 2])
            W[:, 2, 2] = nz
        c, s = np.cos(psi), np.sin(psi)
        X = np.empty(W.shape)
        tmp = np.empty_like(c)
        for r in range(3):
            row, sign = self._front_rows[r], self._front_signs[r]
            w0, w1 = W[:, row, 0], W[:, row, 1]
            np.multiply(c, w0, out=X[:, r, 0])
            np.multiply(s, w1, out=tmp)
            np.subtract(X[:, r, 0], tmp, out=X[:, r, 0])
            np.multiply(s, w0, out=X[:, r, 1])
            np.multiply(c, w1, out=tmp)
            np.add(X[:, r, 1], tmp, out=X[:, r, 1])
            X[:, r, 2] = W[:, row, 2]
            if sign < 0:
                np.negative(X[:, r], out=X[:, r])
        shape = (*np.shape(t), 3, 3)
        if out is None:
            out = np.empty(shape)
        M0: npt.NDArray[np.float64] = self._M0  # type: ignore[assignment]  # set off rest and steady motion, the only callers
        np.matmul(X.reshape(-1, 3), M0, out=out.reshape(-1, 3))
        return out

    def omega_space(self, t: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """ω_O(t) = Rᵀ ω_A, space components."""
        R = self.attitude(t)
        return np.einsum("...ji,...j->...i", R, self.omega(t))  # type: ignore[no-any-return]  # numpy types einsum as Any

    omega_space = finite_result(omega_space)

    def flip_period(self) -> float:
        """The period of ω(t), 4K/λ (the body flips twice in it; inf for steady motion
        and on the separatrix)."""
        if self.regime in ("rest", "steady", "separatrix"):
            return math.inf
        K = float(elliptic.ellipk(self.m, m1=self.m1))
        return 4.0 * K / self._lam

    def poinsot_residuals(
        self, t: npt.ArrayLike
    ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
        """(ω·Jω − 2E, L_O·ω_O − 2E): ω on the inertia ellipsoid and on the invariable
        plane (5.85), (5.90); both zero for the exact motion."""
        w = self.omega(t)
        ell = (self.J * w * w).sum(-1) - 2.0 * self.energy  # self.J: the moments as given
        w_O = np.einsum("...ji,...j->...i", self.attitude(t), w)
        plane = w_O @ self.angular_momentum_space - 2.0 * self.energy
        return ell, plane

    poinsot_residuals = finite_result(poinsot_residuals)


# --------------------------------------------------------------------------- many free tops


#: FreeTopBatch.state against each top's own array path (FreeAsymmetricTop.state of an
#: array), in eps per unit of elliptic phase 1 + λ|t| (of |ω0| for ω, absolute in the
#: attitude).  Each top is built by the same code (the same constants, bit for bit) and
#: evaluated by the same steps over the batch; what may differ is numpy's order of work
#: (the AGM's step count set by the batch's largest argument, the per-top 3×3 products in
#: numpy's matmul loop instead of BLAS).  Two evaluations each within the module's 3.95
#: eps per unit phase of the exact motion are within 8 of each other.  Measured: 0, bit
#: for bit, on 3271 drawn tops in batches of 1 to 30 at |t| ≤ 20 (issue 30).
BATCH_EPS = 8.0


class FreeTopBatch:
    """Many free asymmetric tops, each evaluated at its instant in one vectorised call.

    Domain: J, omega_0 (and R_A_O_0) of shapes (..., 3), (..., 3) (and (..., 3, 3)) whose
    leading (batch) shapes broadcast (else ShapeError naming the argument); each top within
    :class:`FreeAsymmetricTop`'s domain (else its error, naming the index of the top).

    Each top is built as :class:`FreeAsymmetricTop` builds it (the same constants, bit for
    bit); :meth:`state` then evaluates every top at once with numpy, the one-top array
    path's steps over the batch, within :data:`BATCH_EPS` eps per unit of elliptic phase
    of each top's own ``state``.

    Parameters
    ----------
    J : array_like, shape (..., 3)
        Principal moments of each top (any order).
    omega_0 : array_like, shape (..., 3)
        Initial angular velocities, body components.
    R_A_O_0 : array_like, shape (..., 3, 3), optional
        Initial attitudes (default identity).

    Attributes
    ----------
    shape : tuple of int
        The batch shape.
    tops : list of FreeAsymmetricTop
        The tops, in C order of the batch.
    energy, angular_momentum_norm : ndarray, shape (...)
    angular_momentum_space : ndarray, shape (..., 3)

    Raises
    ------
    ShapeError
        If an input has the wrong trailing shape or is not numeric, or the batch
        shapes do not broadcast.
    NonPhysicalInertiaError
        If a top's moments are not physical (the message names the top).
    OutOfDomainError
        If a top lies outside :class:`FreeAsymmetricTop`'s domain (named likewise).
    ResultOverflowError
        If a top's |L| or E exceeds float64's range.
    NotARotationError
        If ``R_A_O_0`` is not a proper rotation matrix.
    NonFiniteError
        If an input is NaN or infinite.

    Examples
    --------
    Three tops at one instant, each as it moves alone:

    >>> J = [[1.0, 2.0, 3.0], [2.0, 2.5, 4.0], [1.0, 1.0, 1.5]]
    >>> w0 = [[0.4, 0.2, 1.0], [1.0, -0.3, 0.1], [0.2, 0.0, 1.0]]
    >>> batch = FreeTopBatch(J, w0)
    >>> w, R = batch.state(7.5)
    >>> w.shape, R.shape
    ((3, 3), (3, 3, 3))
    >>> w1, R1 = FreeAsymmetricTop(J[1], w0[1]).state(np.array(7.5))
    >>> bool(np.abs(w[1] - w1).max() < 1e-14), bool(np.abs(R[1] - R1).max() < 1e-14)
    (True, True)
    """

    def __init__(
        self, J: npt.ArrayLike, omega_0: npt.ArrayLike, R_A_O_0: npt.ArrayLike | None = None
    ) -> None:
        Ja = as_float_array(J, "J", (3,))
        wa = as_float_array(omega_0, "omega_0", (3,))
        Ra = None if R_A_O_0 is None else check_rotation(R_A_O_0, name="R_A_O_0")
        shapes = {"J": Ja.shape[:-1], "omega_0": wa.shape[:-1]}
        if Ra is not None:
            shapes["R_A_O_0"] = Ra.shape[:-2]
        shape = ()
        for name, s in shapes.items():
            try:
                shape = np.broadcast_shapes(shape, s)
            except ValueError:
                others = ", ".join(f"{k} {v}" for k, v in shapes.items() if k != name)
                raise ShapeError(
                    f"{name} has batch shape {s}, which does not broadcast with {others} "
                    "(the leading axes of J, omega_0 and R_A_O_0 list the tops)"
                ) from None
        self.shape: tuple[int, ...] = shape
        Jb = np.broadcast_to(Ja, (*shape, 3)).reshape(-1, 3)
        wb = np.broadcast_to(wa, (*shape, 3)).reshape(-1, 3)
        Rb = None if Ra is None else np.broadcast_to(Ra, (*shape, 3, 3)).reshape(-1, 3, 3)
        self.tops: list[FreeAsymmetricTop] = []
        for i, (Ji, wi) in enumerate(zip(Jb.tolist(), wb.tolist(), strict=True)):
            top = FreeAsymmetricTop.__new__(FreeAsymmetricTop)
            try:
                Jl = _principal_moments_list(Ji, "J")
                top.J, top.omega_0 = np.array(Jl), np.array(wi)
                top.R_A_O_0 = np.eye(3) if Rb is None else Rb[i].copy()
                top._setup(Jl, wi, Rb is not None)
            except MechanicsValueError as exc:
                where = tuple(int(k) for k in np.unravel_index(i, shape)) if shape else ()
                raise type(exc)(f"top {where}: {exc}") from None
            self.tops.append(top)
        self._gather()

    __init__ = finite_result(__init__)

    def _gather(self) -> None:
        """The tops' constants as arrays over the batch (flat)."""
        tops = self.tops
        n = len(tops)

        def col(name: str, default: float = 0.0) -> npt.NDArray[np.float64]:
            return np.array([getattr(t, name, default) for t in tops], dtype=float)

        self.energy = col("energy").reshape(self.shape)
        self.angular_momentum_norm = col("angular_momentum_norm").reshape(self.shape)
        self.angular_momentum_space = np.array([t.angular_momentum_space for t in tops]).reshape(
            *self.shape, 3
        )
        moving = np.array([t._M0 is not None for t in tops], dtype=bool)
        self._moving = np.flatnonzero(moving)
        self._still = np.flatnonzero(~moving)
        mv = [tops[i] for i in self._moving]

        def mcol(name: str) -> npt.NDArray[np.float64]:
            return np.array([getattr(t, name) for t in mv], dtype=float)

        self._lam, self._u0 = mcol("_lam"), mcol("_u0")
        self._m, self._m1 = mcol("m"), mcol("m1")
        self._amp = np.array([t._amp for t in mv]).reshape(-1, 3)
        self._s, self._sigma = mcol("_s"), mcol("_sigma")
        self._branch3 = np.array([t._branch3 for t in mv], dtype=bool)
        self._pole_first = np.array([t._pole_first for t in mv], dtype=bool)
        self._uniform = np.array([t._uniform for t in mv], dtype=bool)
        self._uniform_rate, self._n = mcol("_uniform_rate"), mcol("_n")
        self._C, self._Lm = mcol("_C"), mcol("_Lm")
        self._G0, self._full = mcol("_G0"), mcol("_full")
        self._Js = np.array([t._Js for t in mv]).reshape(-1, 3)
        self._P = np.array([t._P for t in mv]).reshape(-1, 3, 3)
        self._M0 = np.array([t._M0 for t in mv]).reshape(-1, 3, 3)
        self._front_rows = np.array([t._front_rows for t in mv], dtype=np.intp).reshape(-1, 3)
        self._front_signs = np.array([t._front_signs for t in mv]).reshape(-1, 3)
        self._w_still = np.array([tops[i].omega_0 for i in self._still]).reshape(-1, 3)
        self._R_still = np.array([tops[i].R_A_O_0 for i in self._still]).reshape(-1, 3, 3)
        self._n_tops = n

    def state(self, t: npt.ArrayLike) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
        """(ω_A, ^A R^O) of every top at ``t`` (a scalar, or an array broadcasting with the
        batch shape: each top at its own instant): shapes (..., 3) and (..., 3, 3)."""
        t = as_float_array(t, "t")
        try:
            tb = np.broadcast_to(t, self.shape).reshape(-1)
        except ValueError:
            raise ShapeError(
                f"t has shape {t.shape}, which does not broadcast with the batch shape {self.shape}"
            ) from None
        w_out = np.empty((self._n_tops, 3))
        R_out = np.empty((self._n_tops, 3, 3))
        if self._still.size:
            ts = tb[self._still]
            w_out[self._still] = self._w_still
            R_out[self._still] = matrix_from_rotvec(ts[:, None] * self._w_still) @ self._R_still
        if self._moving.size:
            w, R = self._moving_state(tb[self._moving])
            w_out[self._moving], R_out[self._moving] = w, R
        return w_out.reshape(*self.shape, 3), R_out.reshape(*self.shape, 3, 3)

    state = finite_result(state)

    def omega(self, t: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """ω_A of every top at ``t`` (as :meth:`state`), shape (..., 3)."""
        return self.state(t)[0]

    omega = finite_result(omega)

    def _moving_state(
        self, t: npt.NDArray[np.float64]
    ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
        """:meth:`FreeAsymmetricTop._sorted_omega` and ``_attitude_from``, their steps
        over the tops that move (one instant each)."""
        u = self._lam * t + self._u0
        red = elliptic._reduced(u, self._m, self._m1)
        j, sr, snx, cnx, dnx, _ = red
        sign = 1.0 - 2.0 * np.mod(j, 2.0)
        sn, cn, dn = sign * sr * snx, sign * cnx, dnx
        a1, a2, a3 = self._amp[:, 0], self._amp[:, 1], self._amp[:, 2]
        s, sg = self._s, self._sigma
        ws = np.where(
            self._branch3[:, None],
            np.stack([sg * a1 * cn, sg * s * a2 * sn, s * a3 * dn], axis=-1),
            np.stack([s * a1 * dn, s * a2 * sn, a3 * cn], axis=-1),
        )
        w = np.einsum("ni,nij->nj", ws, self._P)  # Pᵀ ω' (exact: a signed permutation)
        # the pole vector (FreeAsymmetricTop._pole_vector's steps)
        wn = ws / np.abs(ws).max(axis=-1, keepdims=True)
        L = self._Js * wn
        L = np.where(self._pole_first[:, None], L[:, [1, 2, 0]], L)
        L = L / np.abs(L).max(axis=-1, keepdims=True)
        L = L / np.linalg.norm(L, axis=-1, keepdims=True)
        W = _pole_frame(L[:, 0], L[:, 1], L[:, 2])
        # ψ (FreeAsymmetricTop.precession_angle's steps); G by _excess's
        G = np.zeros_like(t)
        circ = ~self._uniform
        sep = circ & (self._m1 <= 0)
        if sep.any():
            G[sep] = elliptic._third_kind_excess(u[sep], self._n[sep], self._m[sep], self._m1[sep])
        rest = circ & ~sep
        if rest.any():
            jr = j[rest]
            tail = elliptic._third_kind_tail_reduced(
                (sr * snx)[rest], cnx[rest], dnx[rest], self._n[rest]
            )
            G[rest] = tail + 2.0 * jr * np.where(jr != 0, self._full[rest], 0.0)
        J1, J3 = self._Js[:, 0], self._Js[:, 2]
        k = (self._C / self._lam) * (G - self._G0)
        psi = np.where(
            self._uniform,
            self._Lm * self._uniform_rate * t,
            np.where(self._pole_first, self._Lm * t / J3 - k, self._Lm * t / J1 + k),
        )
        c, s_ = np.cos(psi)[:, None], np.sin(psi)[:, None]
        X = np.empty(W.shape)
        X[..., 0] = c * W[..., 0] - s_ * W[..., 1]
        X[..., 1] = s_ * W[..., 0] + c * W[..., 1]
        X[..., 2] = W[..., 2]
        X = np.take_along_axis(X, self._front_rows[:, :, None], axis=1)
        X *= self._front_signs[:, :, None]
        return w, X @ self._M0


# --------------------------------------------------------------------------- stability (5.3.3)


@dataclass(frozen=True)
class StabilityResult:
    """Linear stability of steady rotation about a principal axis (5.102).

    The frozen record :func:`principal_axis_stability` returns; it validates nothing.

    Parameters
    ----------
    kind : str
        ``"stable"``, ``"unstable"`` or ``"neutral"``.
    rate : float
        Oscillation angular frequency or growth rate, rad/s (1/time).
    CiCk : float
        C_i C_k ω0², 1/s²: its sign decides.

    Examples
    --------
    The rate is the square root of |C_i C_k ω0²|:

    >>> r = principal_axis_stability([1.0, 2.0, 3.0], 3, omega=2.0)
    >>> r.kind, r.rate, float(r.CiCk), bool(r.rate**2 == -r.CiCk)
    ('stable', 2.0, -4.0, True)
    """

    kind: str
    """``"stable"`` (oscillation), ``"unstable"`` (exponential growth) or ``"neutral"``."""
    rate: float
    """Oscillation angular frequency (stable) or growth rate (unstable), 1/time."""
    CiCk: float
    """The product C_i C_k of (5.102) times ω0² (its sign decides)."""


def principal_axis_stability(J: npt.ArrayLike, axis: int, *, omega: float = 1.0) -> StabilityResult:
    """Stability of rotation at rate ``omega`` about principal ``axis`` (1, 2 or 3), (5.102).

    Domain: J as :func:`check_principal_moments` (only ratios enter: any scale); axis 1, 2 or 3; a
    finite scalar omega with C_i C_k ω² within float64 (else ResultOverflowError).

    δω̈_i = C_i C_k ω0² δω_i with C_i = (J_j − J_k)/J_i cyclic (Euler's equations
    5.91 written as ω̇_i = C_i ω_j ω_k).  ω0² is never formed (it over- or underflows for
    |ω0| beyond 1e154 or below 1e-154): the kind is the sign of C_i C_k, the rate
    |ω0| √|C_i C_k|, and C_i C_k ω0² is scaled from ω0's mantissa.

    Parameters
    ----------
    J : array_like, shape (3,)
        Principal moments (J1, J2, J3), kg m².
    axis : int
        The principal axis of the rotation: 1, 2 or 3.
    omega : float
        The rate of the steady rotation ω0, rad/s, finite.

    Returns
    -------
    StabilityResult
        ``kind``, ``rate`` (rad/s) and ``CiCk`` = C_i C_k ω0².

    Raises
    ------
    NonPhysicalInertiaError
        If ``J`` is not physical (:func:`check_principal_moments`).
    UnknownOptionError
        If ``axis`` is not the integer 1, 2 or 3.
    ResultOverflowError
        If C_i C_k ω0² exceeds float64's range.
    NonFiniteError
        If an input is NaN or infinite.
    ShapeError
        If ``J`` is not of shape (3,) or ``omega`` is not a scalar.

    Examples
    --------
    The middle axis is unstable, the others stable:

    >>> [principal_axis_stability([1.0, 2.0, 3.0], a).kind for a in (1, 2, 3)]
    ['stable', 'unstable', 'stable']
    >>> r = principal_axis_stability([1.0, 2.0, 3.0], 2)
    >>> bool(abs(r.rate - np.sqrt((3 - 2) / 1 * (2 - 1) / 3)) < 1e-15)
    True
    """
    J = check_principal_moments(J)
    w = as_float_array(omega, "omega")
    if w.shape != ():
        raise ShapeError("omega must be a scalar")
    if isinstance(axis, bool) or not isinstance(axis, (int, np.integer)) or axis not in (1, 2, 3):
        raise UnknownOptionError(f"axis must be 1, 2 or 3; got {axis!r}")
    j = axis - 1
    i, k = (j + 1) % 3, (j + 2) % 3
    Ci = (J[j] - J[k]) / J[i]  # ω̇_i = C_i ω_j ω_k with (i, j, k) cyclic: C_i = (J_j − J_k)/J_i
    Ck = (J[i] - J[j]) / J[k]
    return _stability_of(Ci * Ck, float(w))


principal_axis_stability = finite_result(principal_axis_stability)


def _stability_of(c: float, w: float) -> StabilityResult:
    """The kind, rate |ω| √|c| and c ω² of δω̈ = c ω² δω, c = C_i C_k.

    |C_i| ≤ 1 by the triangle inequality and ≥ 2⁻⁵⁴ unless 0, so c neither under- nor
    overflows; ω² may (ω = 1e160, 1e-160), so the kind is c's sign, the rate is taken from √|c|
    and c ω² is scaled from ω's mantissa once (an overflow raises OverflowError)."""
    f, e = math.frexp(w)
    prod = math.ldexp(c * f * f, 2 * e)
    if w == 0.0 or c == 0.0:
        return StabilityResult("neutral", 0.0, 0.0)
    rate = math.sqrt(abs(c)) * abs(w)
    return StabilityResult("unstable" if c > 0 else "stable", rate, prod)


# --------------------------------------------------------------------------- free symmetric top


class FreeSymmetricTop:
    """The free symmetric top in closed form (5.2.1, Example 5.2).

    Domain: J1, J3 > 0 with J3 ≤ 2 J1 (the triangle inequality), from 1e-300 to 1e300 (computed from
    the moments scaled by a power of two: s·J moves exactly as J); any finite ω_0 while |L| and E
    fit float64 (else ResultOverflowError); one attitude R_A_O_0 of shape (3, 3), a rotation
    (else ShapeError or NotARotationError).

    Parameters
    ----------
    J1 : float
        The two equal moments, kg m², > 0.
    J3 : float
        The moment about the symmetry axis (body axis 3), kg m², 0 < J3 ≤ 2 J1.
    omega_0 : array_like, shape (3,)
        Initial ω_A, rad/s.
    R_A_O_0 : array_like, shape (3, 3), optional
        Initial attitude ^A R^O (default identity).

    Raises
    ------
    NonPhysicalInertiaError
        If J1 or J3 is ≤ 0, or J3 > 2 J1.
    ResultOverflowError
        If |L| or E exceeds float64's range.
    NotARotationError
        If ``R_A_O_0`` is not a proper rotation matrix.
    NonFiniteError
        If an input is NaN or infinite.
    ShapeError
        If J1 or J3 is not a scalar, ``omega_0`` not of shape (3,), or ``R_A_O_0`` not of
        shape (3, 3).

    Notes
    -----
    ω3 is constant (5.37); ω1 + iω2 = A e^{iβt}, β = (J3 − J1) ω3 / J1 (5.40)–(5.45):
    the body-frame precession rate.  The symmetry axis precesses about the fixed L at
    ψ̇ = |L|/J1 (5.34) at the constant angle θ0, cos θ0 = J3 ω3/|L|, and the spin
    relative to the precessing frame is φ̇ = (|L|/J1) cos θ0 (J1 − J3)/J3 (5.35)
    = −β.

    Examples
    --------
    >>> top = FreeSymmetricTop(2.0, 1.0, [0.3, 0.0, 1.0])
    >>> top.body_precession_rate
    -0.5
    >>> bool(abs(top.spin_rate + top.body_precession_rate) < 1e-15)
    True
    """

    def __init__(
        self,
        J1: float,
        J3: float,
        omega_0: npt.ArrayLike,
        R_A_O_0: npt.ArrayLike | None = None,
    ) -> None:
        if _positive_float(J1) and _positive_float(J3) and J3 <= 2.0 * J1:
            self.J1, self.J3 = J1, J3  # two positive floats J3 ≤ 2 J1: J = (J1, J1, J3) is valid
        else:
            for x, name in ((J1, "J1"), (J3, "J3")):
                a = as_float_array(x, name)
                if a.shape != ():
                    raise ShapeError(f"{name} must be a scalar moment of inertia; got {x!r}")
                if not a > 0:
                    raise NonPhysicalInertiaError(
                        f"{name} must be positive: {name} = {float(a)!r} ≤ 0"
                    )
            if float(J3) > 2.0 * float(J1):
                raise NonPhysicalInertiaError(
                    f"J3 = {float(J3)!r} exceeds 2 J1 = {2.0 * float(J1)!r}: the moments of a "
                    "symmetric body obey the triangle inequality J3 ≤ J1 + J2 = 2 J1"
                )
            J = check_principal_moments([J1, J1, J3], name="J")  # the checks above passed
            self.J1, self.J3 = float(J[0]), float(J[2])
        wl = _vec3_list(omega_0, "omega_0")
        self.omega_0 = np.array(wl)
        rotated = R_A_O_0 is not None
        R0 = np.eye(3) if R_A_O_0 is None else check_rotation(R_A_O_0, name="R_A_O_0")
        if R0.shape != (3, 3):
            raise ShapeError(f"R_A_O_0 must have shape (3, 3); got {R0.shape}")
        self.R_A_O_0 = R0.copy() if rotated else R0
        # the motion depends on J1, J3 and ω only through J3/J1 and ω: compute with the
        # moments scaled by 2^-k (exact) and scale |L|, L and E back (issue 16, part 4)
        k = math.frexp(max(self.J1, self.J3))[1]
        j1, j3 = math.ldexp(self.J1, -k), math.ldexp(self.J3, -k)
        wmax = max(abs(wl[0]), abs(wl[1]), abs(wl[2]))
        kw = math.frexp(wmax)[1] if wmax > 0 else 0
        wn = [math.ldexp(x, -kw) for x in wl]  # ω scaled too for the directions
        Ln = [j1 * wn[0], j1 * wn[1], j3 * wn[2]]
        Lh = math.hypot(*Ln)
        self.angular_momentum_norm = math.ldexp(Lh, k + kw)
        Ls = (self.R_A_O_0.T @ Ln).tolist() if rotated else Ln
        try:
            Ls = [math.ldexp(x, k + kw) for x in Ls]
        except OverflowError:
            Ls = [math.inf]
        self.angular_momentum_space = np.array(Ls)
        self.energy = math.ldexp(
            0.5 * math.fsum([j1 * wn[0] * wn[0], j1 * wn[1] * wn[1], j3 * wn[2] * wn[2]]),
            k + 2 * kw,
        )
        if not all(math.isfinite(x) for x in Ls):
            raise ResultOverflowError(
                f"the angular momentum J ω exceeds float64's range (|L| = "
                f"{self.angular_momentum_norm!r}); rescale J1, J3 or omega_0 (choose units)"
            )
        self.body_precession_rate = (j3 - j1) * wl[2] / j1
        # |L|/J1 = |(ω1, ω2, (J3/J1) ω3)|, from the scaled vector
        self.space_precession_rate = math.ldexp(Lh / j1, kw)
        self.nutation_angle = math.atan2(j1 * math.hypot(wn[0], wn[1]), j3 * wn[2])
        # φ̇ = (|L|/J1) cos θ0 (J1 − J3)/J3 = ω3 (J1 − J3)/J1 = −β: cos θ0 = J3 ω3/|L| through
        # cos(atan2(...)) kept only the rounding of π/2 near a flat nutation (1e-6 relative off
        # at cos θ0 = 5e-11; 6e283 for 1e-10 at J3 = 1e-300 J1)
        self.spin_rate = -self.body_precession_rate
        self._steady = wl[0] == 0 and wl[1] == 0
        if not self._steady:
            W0 = _pole_frame_list(Ln[0] / Lh, Ln[1] / Lh, Ln[2] / Lh)
            self._W0 = np.array(W0)
            self._M0 = self._W0.T @ R0 if rotated else self._W0.T.copy()

    __init__ = finite_result(__init__)

    def omega(self, t: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """ω_A(t) = (|A| cos(βt + α), |A| sin(βt + α), ω3) (5.44)–(5.45)."""
        t = as_float_array(t, "t")
        w1, w2, w3 = self.omega_0
        c, s = np.cos(self.body_precession_rate * t), np.sin(self.body_precession_rate * t)
        return np.stack([w1 * c - w2 * s, w1 * s + w2 * c, np.full_like(c, w3)], axis=-1)

    omega = finite_result(omega)

    def attitude(self, t: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """^A R^O(t) = R3(φ̇t) R3(φ0) R1(θ0) R3(ψ̇t) R3(ψ0) ^S R^O, L along e^S_3.

        The spin φ̇ (5.35) and the precession ψ̇ (5.34) are uniform; R3(φ0) R1(θ0)
        is the frame whose third column is L_A(0)/|L|."""
        t = as_float_array(t, "t")
        if self._steady:
            return matrix_from_rotvec(t[..., None] * self.omega_0) @ self.R_A_O_0
        return R3(self.spin_rate * t) @ self._W0 @ R3(self.space_precession_rate * t) @ self._M0  # type: ignore[no-any-return]  # numpy types a chain of @ as Any

    attitude = finite_result(attitude)


# --------------------------------------------------------------------------- heavy symmetric top


def sleeping_top_is_stable(J_1: float, L_3: float, m_g_ell: float) -> bool:
    """Example 5.3: the vertical (sleeping) top is stable iff L3² > 4 J'1 m g ℓ (5.72).

    Domain: J'1, m g ℓ > 0, any finite L3: the criterion is homogeneous and evaluated on the three
    scaled by a power of two, so no square over- or underflows.

    Parameters
    ----------
    J_1 : float
        Transverse moment about the fixed point, J'1, kg m², > 0.
    L_3 : float
        Angular momentum about the symmetry axis, kg m²/s.
    m_g_ell : float
        m g ℓ, N m, > 0.

    Returns
    -------
    bool
        Whether L3² > 4 J'1 m g ℓ.

    Raises
    ------
    NonPositiveParameterError
        If ``J_1`` or ``m_g_ell`` is ≤ 0.
    NonFiniteError
        If an input is NaN or infinite.
    ShapeError
        If an input is not a real scalar.

    Examples
    --------
    On either side of the threshold L3 = 2 √(J'1 m g ℓ) = 2:

    >>> sleeping_top_is_stable(1.0, 2.1, 1.0), sleeping_top_is_stable(1.0, 1.9, 1.0)
    (True, False)
    """
    J_1, mgl, L3 = _scaled(
        _positive(J_1, "J_1"), _positive(m_g_ell, "m_g_ell"), as_float_scalar(L_3, "L_3")
    )
    margin = L3 * L3 - 4.0 * J_1 * mgl
    return bool(margin > 0)


sleeping_top_is_stable = finite_result(sleeping_top_is_stable)


def _scaled(*xs: float) -> tuple[float, ...]:
    """xs / 2^k with the largest |x| in [1/2, 1): exact, for homogeneous formulas (the
    rates of a top depend on J'1, L3, m g ℓ only through their ratios)."""
    k = math.frexp(max(abs(x) for x in xs))[1]
    return tuple(math.ldexp(x, -k) for x in xs)


#: the documented floor of a top's parameter against the largest (J'1, J3, m g ℓ; for
#: the steady precession J'1, |L3|, m g ℓ): below it the ratio leaves float64's normal
#: range, and the top would be computed on digits lost to underflow
RATIO_FLOOR = 1e-308


def _scale_exponent(largest: float, smallest: float) -> int:
    """k for homogeneous formulas evaluated on xs / 2^k (exact: the rates of a top depend
    on J'1, J3, L3, m g ℓ only through their ratios): the largest in [1/2, 1), unless the
    smallest positive one would then fall below float64's normal range; then the
    smallest at 2^-1022 and the largest below 8 (their ratio ≥ RATIO_FLOOR > 2^-1024)."""
    return min(math.frexp(largest)[1], math.frexp(smallest)[1] + 1021)


def _ratio_below_floor(x: float, largest: float) -> bool:
    """x (> 0) below RATIO_FLOOR of ``largest``: the quotient, not a product that
    underflows for a small ``largest``."""
    return x / largest < RATIO_FLOOR


_positive = as_positive_scalar


def steady_precession_rates(
    J_1: float, L_3: float, m_g_ell: float, theta: float
) -> tuple[float, float]:
    """The two steady precession rates Ω (slow, fast) at nutation angle θ (5.60).

    Domain: J'1, m g ℓ > 0, finite L3 and θ with L3² ≥ 4 J'1 m g ℓ cos θ (else OutOfDomainError);
    any common scale of J'1, L3, mgℓ (evaluated scaled by a power of two); the fast rate is inf at
    cos θ = 0 (documented below).

    Roots of J'1 cos θ Ω² − L3 Ω + m g ℓ = 0, the slow one as 2mgℓ/(L3 + √disc) (no
    cancellation).  At cos θ = 0 the fast one is inf (one finite root mgℓ/L3).

    Parameters
    ----------
    J_1 : float
        Transverse moment about the fixed point, J'1, kg m², > 0.
    L_3 : float
        Angular momentum about the symmetry axis, kg m²/s.
    m_g_ell : float
        m g ℓ, N m, > 0.
    theta : float
        Nutation angle θ, rad.

    Returns
    -------
    slow, fast : float
        The two rates Ω, rad/s, the smaller in magnitude first.  For L3 = 0 they
        are ∓√(mgℓ/(−J'1 cos θ)), returned as ∓inf where that overflows.

    Raises
    ------
    OutOfDomainError
        If L3² < 4 J'1 m g ℓ cos θ: no steady precession at that angle; or if J'1 or
        m g ℓ is below 1e-308 of the largest of J'1, |L3|, m g ℓ.
    ResultOverflowError
        If L3 ≠ 0 and the fast rate L3/(J'1 cos θ) exceeds float64's range.
    NonPositiveParameterError
        If ``J_1`` or ``m_g_ell`` is ≤ 0.
    NonFiniteError
        If an input is NaN or infinite.
    ShapeError
        If an input is not a real scalar.

    Examples
    --------
    Both rates are roots of the quadratic, and their product is mgℓ/(J'1 cos θ):

    >>> slow, fast = steady_precession_rates(1.0, 10.0, 1.0, 0.5)
    >>> J1, L3, mgl, c = 1.0, 10.0, 1.0, np.cos(0.5)
    >>> bool(abs(J1 * c * slow**2 - L3 * slow + mgl) < 1e-14)
    True
    >>> bool(abs(slow * fast - mgl / (J1 * c)) < 32 * EPS)
    True
    """
    given = {
        "J_1": _positive(J_1, "J_1"),
        "m_g_ell": _positive(m_g_ell, "m_g_ell"),
        "L_3": as_float_scalar(L_3, "L_3"),
    }
    largest = max(abs(v) for v in given.values())
    for name in ("J_1", "m_g_ell"):
        if _ratio_below_floor(given[name], largest):
            raise OutOfDomainError(
                f"{name} = {given[name]!r} is below 1e-308 of the largest of J_1, |L_3|, "
                f"m_g_ell ({largest!r}): the ratio underflows float64 (rescale, or treat the "
                "top as free)"
            )
    k = _scale_exponent(largest, min(given["J_1"], given["m_g_ell"]))
    J_1, mgl, L3 = (math.ldexp(x, -k) for x in given.values())
    c = math.cos(as_float_scalar(theta, "theta"))
    disc = L3 * L3 - 4.0 * J_1 * mgl * c
    if disc < 0:
        # the discriminant of the values given: 2^2k times the scaled one (exact), or,
        # where that leaves float64, the scaled one with its power of two
        try:
            given_disc = math.ldexp(disc, 2 * k)
        except OverflowError:
            given_disc = 0.0
        shown = f"{given_disc:.6g}" if given_disc != 0 else f"{disc:.6g} × 2^{2 * k}"
        raise OutOfDomainError(f"no steady precession: L3² − 4 J'1 m g ℓ cos θ = {shown} < 0")
    if L3 == 0:
        r = math.sqrt(mgl / (-J_1 * c))
        return (-r, r)
    q = L3 + math.copysign(math.sqrt(disc), L3)
    slow = 2.0 * mgl / q
    fast = q / (2.0 * J_1 * c) if c != 0 else math.copysign(math.inf, L3)
    if c != 0 and not math.isfinite(fast):
        raise ResultOverflowError(
            f"the fast precession rate L3/(J'1 cos θ) exceeds float64's range (J_1 = {J_1!r} "
            f"scaled, cos θ = {c!r}); rescale (choose units)"
        )
    return (slow, fast) if abs(slow) <= abs(fast) else (fast, slow)


#: x3 = u3 − u0 above which the heavy top's quadratic factor takes p from the product of
#: Vieta's formulas: the sum c2/β + x3 has an error ~ eps x3, the product ~ eps (|p| +
#: |q|/x3) with |p|, |q| ≤ 4 (|x1|, |x2| ≤ 2), so beyond 8 the product is the better
_DEFLATE_BY_PRODUCT = 8.0


def _root_from_above(rising: Callable[[float], tuple[float, float]], lo: float, hi: float) -> float:
    """The root in [lo, hi] of a function that rises through it (``rising(y)`` gives its
    value and slope; ≤ 0 at lo, > 0 at hi), to its rounding: Newton's method from hi
    (monotone there for the heavy top's convex cubic), bisecting the bracket where a
    step leaves it; ends where the steps stop moving or the bracket is two floats, at
    the point of least |value| seen."""
    y, (v, d) = hi, rising(hi)
    best, best_v = y, abs(v)
    while True:
        nxt = y - v / d if d > 0 else math.nan  # (NaN fails the test below: bisect)
        if not lo < nxt < hi:
            nxt = lo + 0.5 * (hi - lo)
            if not lo < nxt < hi:
                return best
        if nxt == y:
            return best
        y, (v, d) = nxt, rising(nxt)
        if abs(v) < best_v:
            best, best_v = y, abs(v)
        if v == 0:
            return y
        if v > 0:
            hi = y
        else:
            lo = y


class HeavySymmetricTop:
    """The heavy symmetric top about a fixed point (5.2.2–5.2.5), exact motion.

    Domain: J'1, J3, m g ℓ > 0 with J3 ≤ 2 J'1, jointly from 1e-300 to 1e300 (the motion depends on
    their ratios: computed from them scaled by a power of two, so s·(J'1, J3, mgℓ) moves exactly as
    (J'1, J3, mgℓ)), each at least 1e-308 of the largest (else OutOfDomainError: for mgℓ,
    gravity is negligible, a free top); θ in [0, π] (0 or π only with θ̇ = 0, the sleeping
    top); finite rates whose squares times J'1/mgℓ fit float64 (else ResultOverflowError,
    or OutOfDomainError where the cubic's values overflow on the way to its root).

    Parameters
    ----------
    J_1 : float
        Transverse moment about the fixed point C (the book's J'1, (5.46)), kg m², > 0.
    J_3 : float
        Moment about the symmetry axis, kg m², 0 < J_3 ≤ 2 J_1.
    m_g_ell : float
        m g ℓ > 0, N m.
    theta, psi, phi : float
        Initial Euler angles (z-x-z; ψ precession, θ nutation, φ spin), 0 < θ < π.
    theta_dot, psi_dot, phi_dot : float
        Initial rates.

    Attributes
    ----------
    L_z, L_3, energy : float
        The conserved quantities (5.55), (5.53), (5.66).
    roots : tuple of float
        u1 ≤ u2 ≤ u3 of f(u) = u̇² (nutation between u1 and u2, u = cos θ).

    Raises
    ------
    NonPositiveParameterError
        If ``J_1``, ``J_3`` or ``m_g_ell`` is ≤ 0.
    NonPhysicalInertiaError
        If J_3 > 2 J_1.
    OutOfDomainError
        If one of J_1, J_3, m_g_ell is below 1e-308 of the largest, θ lies outside
        [0, π], or the search for the turning points of θ overflows float64 (the
        factored cubic is inf − inf at the bracket's end: rates near 1e77 and beyond).
    GimbalLockError
        If θ = 0 or π with θ̇ ≠ 0 (the Euler angles are singular).
    ResultOverflowError
        If a conserved quantity or an intermediate exceeds float64's range, or the
        largest turning point u3 does (θ̇0² J'1/mgℓ beyond float64).
    NonFiniteError
        If an input is NaN or infinite.
    ShapeError
        If an input is not a real scalar.

    Notes
    -----
    u̇² = f(u) = (e − βu)(1 − u²) − (a − bu)², β = 2mgℓ/J'1, a = L_z/J'1,
    b = L3/J'1, e = (2E − L3²/J3)/J'1.  The cubic is written about the initial u0,
    f = β x³ + c2 x² + c1 x + θ̇0² sin²θ0 (x = u − u0), its large root u3 found
    by Newton's method from above a bracket (monotone there, bisecting where a step
    leaves the bracket; beyond u = 2 on f/(u − 1)², which does not overflow
    where u3 ~ 1/mgℓ), the pair u1 ≤ u0 ≤ u2 by deflation to a quadratic with
    roots of opposite signs (no cancellation near the double root of steady
    precession; its linear coefficient by Vieta's product where u3 is large), each
    polished by a Newton step.  Then
    u(t) = u1 + (u2 − u1) sn²(κt + w0 | m), κ = √(β(u3 − u1))/2,
    m = (u2 − u1)/(u3 − u1); ψ and φ by the third-kind integral in Jacobi's form.

    Examples
    --------
    >>> top = HeavySymmetricTop(1.0, 0.5, 1.0, theta=1.0, psi=0.0, phi=0.0,
    ...                         theta_dot=0.0, psi_dot=0.3, phi_dot=20.0)
    >>> u1, u2, u3 = top.roots
    >>> bool(u1 <= np.cos(1.0) <= u2 <= 1.0 <= u3)
    True
    >>> E = top.energy_at(np.array([0.0, 3.7]))
    >>> bool(abs(E[1] - E[0]) < 1e-12 * abs(E[0]))
    True
    """

    def __init__(
        self,
        J_1: float,
        J_3: float,
        m_g_ell: float,
        *,
        theta: float,
        psi: float = 0.0,
        phi: float = 0.0,
        theta_dot: float = 0.0,
        psi_dot: float = 0.0,
        phi_dot: float = 0.0,
    ) -> None:
        self.J_1 = J_1 if _positive_float(J_1) else _positive(J_1, "J_1")
        self.J_3 = J_3 if _positive_float(J_3) else _positive(J_3, "J_3")
        if self.J_3 > 2.0 * self.J_1:
            raise NonPhysicalInertiaError(
                f"J_3 = {self.J_3!r} exceeds 2 J_1 = {2.0 * self.J_1!r}: the moments of a "
                "symmetric body obey the triangle inequality J_3 ≤ J_1 + J_2 = 2 J_1 (about G, "
                "and so about any point of the axis)"
            )
        self.m_g_ell = m_g_ell if _positive_float(m_g_ell) else _positive(m_g_ell, "m_g_ell")
        # The motion depends on J'1, J3 and m g ℓ only through their ratios: the
        # computation runs on them scaled by 2^-k (exact; the largest in [1/2, 1)), and
        # L3, Lz, E and the energies are scaled back by 2^k (issue 16, part 4: moments
        # from 1e-300 to 1e300 give the same θ(t), ψ(t), φ(t)).
        largest = max(self.J_1, self.J_3, self.m_g_ell)
        for name in ("J_1", "J_3", "m_g_ell"):
            if _ratio_below_floor(getattr(self, name), largest):
                raise OutOfDomainError(
                    f"{name} = {getattr(self, name)!r} is below 1e-308 of the largest of J_1, "
                    f"J_3, m_g_ell ({max(self.J_1, self.J_3, self.m_g_ell)!r}): the ratio "
                    "underflows float64 (for m_g_ell: gravity is negligible, use "
                    "FreeSymmetricTop)"
                )
        self._k = _scale_exponent(largest, min(self.J_1, self.J_3, self.m_g_ell))
        self._J1n, self._J3n, self._mgln = (
            math.ldexp(x, -self._k) for x in (self.J_1, self.J_3, self.m_g_ell)
        )
        vals = {}
        for k, v in dict(
            theta=theta, psi=psi, phi=phi, theta_dot=theta_dot, psi_dot=psi_dot, phi_dot=phi_dot
        ).items():
            if type(v) is float and math.isfinite(v):
                vals[k] = v
                continue
            a = as_float_array(v, k)
            if a.shape != ():
                raise ShapeError(f"{k} must be a scalar; got shape {a.shape}")
            vals[k] = float(a)
        th = vals["theta"]
        if not 0.0 <= th <= math.pi:
            raise OutOfDomainError(f"theta must lie in [0, π]; got {th!r}")
        self.theta0, self.psi0, self.phi0 = th, vals["psi"], vals["phi"]
        self.theta_dot0, self.psi_dot0, self.phi_dot0 = (
            vals["theta_dot"],
            vals["psi_dot"],
            vals["phi_dot"],
        )
        J1, J3, mgl = self._J1n, self._J3n, self._mgln
        u0, S = math.cos(th), math.sin(th)
        self.u0 = u0
        self._L3n = J3 * (self.psi_dot0 * u0 + self.phi_dot0)
        self._Lzn = J1 * S * S * self.psi_dot0 + self._L3n * u0
        self._En = (
            0.5 * J1 * (self.theta_dot0**2 + (self.psi_dot0 * S) ** 2)
            + self._L3n**2 / (2 * J3)
            + mgl * u0
        )
        self._beta = 2.0 * mgl / J1
        self._b = self._L3n / J1
        #: L3, Lz (about the fixed point) and E in the units given
        self.L_3, self.L_z, self.energy = (
            math.ldexp(x, self._k) for x in (self._L3n, self._Lzn, self._En)
        )
        if S == 0.0:
            if self.theta_dot0 != 0:
                raise GimbalLockError(
                    "theta = 0 or π with theta_dot ≠ 0: the Euler angles are singular; "
                    "start the top at a small θ > 0 instead"
                )
            self.sleeping = True
            self.roots = (u0, u0, math.inf)
            return
        self.sleeping = False
        # a − b and a + b without cancellation: (Lz ∓ L3)/J1
        self._amb = S * S * self.psi_dot0 - self._b * 2.0 * math.sin(th / 2) ** 2
        self._apb = S * S * self.psi_dot0 + self._b * 2.0 * math.cos(th / 2) ** 2
        T0 = self.theta_dot0**2 + (self.psi_dot0 * S) ** 2
        c0 = self.psi_dot0 * S * S
        beta, b = self._beta, self._b
        self._coef = (
            beta,
            -T0 + 2 * beta * u0 - b * b,
            -2 * u0 * T0 - beta * S * S + 2 * b * c0,
            (self.theta_dot0 * S) ** 2,
        )
        # u3 ≥ 1 (f(1) = −(a − b)² ≤ 0), searched as y = u3 − 1 ≥ 0 on f in factored form:
        # f = (1 − u)[(e − βu)(1 + u) − 2(a − b)b − b²(1 − u)] − (a − b)², with 1 − u = −y,
        # 1 + u = 2 + y and e − βu = T0 − β(1 − u0) − βy.  Its rounding shrinks with y, so a
        # root at or near the vertical is not lost in the cubic's rounding noise there (the
        # cubic about u0 rounds to 0 at points a few ulps off a root u2 = 1, and a root
        # search on it returned u3 = 1 for a top that swings over the vertical)
        c2h, s2h = 2.0 * math.cos(0.5 * th) ** 2, 2.0 * math.sin(0.5 * th) ** 2
        amb, lo = self._amb, 1.0 - u0
        vertical = amb * amb == 0.0  # a = b (to the square's range): u = 1 is a root
        ebeta = T0 - beta * s2h  # e − β: how far the energy is above the vertical's

        def h(y: float) -> float:
            return (2.0 + y) * (ebeta - beta * y) - 2.0 * amb * b + b * b * y

        def F(y: float) -> float:
            return -y * h(y) - amb * amb

        if vertical and h(0.0) <= 0:
            y3 = 0.0  # u = 1 is the largest root: the top reaches the vertical and turns
        else:
            # a = b: u = 1 is a root of f, and u3 one of h = f/(1 − u); else u3 is F's root.
            # Below u3, h > 0 and F < 0; above, the reverse
            g, sign = (h, -1.0) if vertical else (F, 1.0)

            def rising(y: float) -> tuple[float, float]:
                """±g and its slope (− below u3); beyond y = 1, F/y² (the same sign and
                root; F ~ βy³ overflows where u3 ~ 1/β, gravity weak against the spin)."""
                dh = ebeta - beta * y - beta * (2.0 + y) + b * b
                if vertical:
                    return -h(y), -dh
                if y > 1.0:
                    hy, ay = h(y), amb / y
                    return -hy / y - ay * ay, -(dh - hy / y) / y + 2.0 * ay * ay / y
                return F(y), -h(y) - y * dh

            hi = max(lo, 1.0)
            while sign * g(hi) <= 0:
                hi *= 2.0
            rates = (
                f"theta_dot = {self.theta_dot0!r}, psi_dot = {self.psi_dot0!r}, "
                f"phi_dot = {self.phi_dot0!r}, m_g_ell = {self.m_g_ell!r}"
            )
            if hi == math.inf:  # g ≤ 0 up to float64's largest: so is u3 − 1
                raise ResultOverflowError(
                    f"the largest turning point of cos θ exceeds float64's range ({rates}): "
                    "a rate's square times J_1/m_g_ell is beyond ~1.8e308; rescale (choose "
                    "units)"
                )
            if math.isnan(g(hi)):  # the bracket's end overflows to inf − inf: no search
                raise OutOfDomainError(
                    f"the turning points of θ are beyond float64: the search for the "
                    f"largest root overflows at 1 − u = {hi!r} ({rates}); rescale (choose "
                    "units) so that the rates' squares stay within float64"
                )
            y3 = _root_from_above(rising, 0.0, hi)
        x3 = s2h + y3
        # the quadratic factor x² + p x + q of f/(β(x − x3)), by Vieta: p = c2/β + x3 sums
        # terms ≈ ∓x3 to the pair's −(x1 + x2) (|x1|, |x2| ≤ 2), cancelling where x3 is
        # large (gravity weak against the spin: u3 ~ 1e100 for mgℓ ~ 1e-100 J'1 ψ̇² lost
        # the nutation band); there p = −(c1 + c0/x3)/(β x3) from c1 = β(q − p x3)
        if x3 > _DEFLATE_BY_PRODUCT:
            p = -(self._coef[2] + self._coef[3] / x3) / (beta * x3)
        else:
            p = self._coef[1] / beta + x3
        q = -self._coef[3] / (beta * x3)
        disc = math.sqrt(p * p - 4 * q)
        r = -0.5 * (p + math.copysign(disc, p))
        xa, xb = (r, q / r) if r != 0 else (0.0, -p)
        x1, x2 = min(xa, xb, 0.0), max(xa, xb, 0.0)
        x1, x2 = self._polish(x1, max(-1.0 - u0, x1 - 1.0), 0.0), self._polish(x2, 0.0, lo)
        # 1 + u1 and 1 − u2 without cancellation.  Near the vertical they come from
        # f(∓1) = −(a ± b)² = β(∓1 − u1)(∓1 − u2)(∓1 − u3):
        # 1 + u1 = (a + b)²/(β(1 + u2)(1 + u3)), 1 − u2 = (a − b)²/(β(1 − u1)(u3 − 1)),
        # whose other factors carry no cancellation (exactly 0 when the top passes ∓1)
        opu1 = c2h + x1
        if opu1 < 1e-3:
            opu1 = self._apb**2 / (beta * (c2h + x2) * (c2h + x3))
            x1 = opu1 - c2h
        omu2 = s2h - x2
        u3m1 = y3
        # (a = b: exactly 0 where u3 > 1, however near; 1 − u2 > 0 is then u3 = 1's other side)
        if omu2 < 1e-3 and u3m1 > 0 and (u3m1 > 1e-3 or vertical):
            omu2 = self._amb**2 / (beta * (s2h - x1) * u3m1)
            x2 = s2h - omu2
        self._opu1, self._omu2 = max(opu1, 0.0), max(omu2, 0.0)
        self.roots = (
            -1.0 + self._opu1 if self._opu1 < 1e-3 else u0 + x1,
            1.0 - self._omu2 if self._omu2 < 1e-3 else u0 + x2,
            u0 + x3,
        )
        d21 = x2 - x1
        self._d21 = d21
        self._m = d21 / (x3 - x1)
        self._m1 = (x3 - x2) / (x3 - x1)
        self._kappa = 0.5 * math.sqrt(beta * (x3 - x1))
        if d21 <= 0:
            self._w0 = 0.0
        else:
            s2 = min(max(-x1 / d21, 0.0), 1.0)
            sg = -1.0 if self.theta_dot0 > 0 else 1.0  # u̇ = −sin θ θ̇
            s = math.sqrt(s2)
            c = math.sqrt(min(max(x2 / d21, 0.0), 1.0))
            dn2 = c * c + self._m1 * s2
            self._w0 = sg * s * float(sc.elliprf(c * c, dn2, 1.0)) if s else 0.0
        # n± of 1 ∓ u = (1 ∓ u1)(1 − n± sn²); the a ∓ b terms vanish where 1 ∓ u1 = 0
        one_minus_u1 = self._omu2 + d21
        self._npl = d21 / one_minus_u1 if one_minus_u1 > 0 else 0.0
        self._nmi = -d21 / self._opu1 if self._opu1 > 0 else 0.0

    __init__ = finite_result(__init__)

    def _f(self, x: float) -> float:
        b3, c2, c1, c0 = self._coef
        return ((b3 * x + c2) * x + c1) * x + c0

    def _polish(self, x: float, lo: float, hi: float) -> float:
        b3, c2, c1, _ = self._coef
        fx = self._f(x)
        d = (3 * b3 * x + 2 * c2) * x + c1
        if d != 0:
            y = x - fx / d
            if lo <= y <= hi and abs(self._f(y)) < abs(fx):
                return y
        return x

    def f(self, u: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """The cubic f(u) = u̇² (the book's 5.66–5.71 in u = cos θ)."""
        u = as_float_array(u, "u")
        a = self._Lzn / self._J1n
        e = (2 * self._En - self._L3n**2 / self._J3n) / self._J1n
        return (e - self._beta * u) * (1 - u * u) - (a - self._b * u) ** 2

    f = finite_result(f)

    def effective_potential(self, theta: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """Φ_eff(θ) = (L_z − L3 cos θ)²/(2J'1 sin²θ) − mgℓ(1 − cos θ) (5.70)."""
        th = as_float_array(theta, "theta")
        s = np.sin(th)
        with np.errstate(divide="ignore"):
            phi = (self._Lzn - self._L3n * np.cos(th)) ** 2 / (
                2 * self._J1n * s * s
            ) - self._mgln * 2.0 * np.sin(th / 2) ** 2
        return np.ldexp(phi, self._k)

    effective_potential = finite_result(effective_potential)

    def _get_reduced_energy(self) -> float:
        """E' = E − L3²/(2J3) − mgℓ (5.69)."""
        return math.ldexp(self._En - self._L3n**2 / (2 * self._J3n) - self._mgln, self._k)

    # applied after the definition, so that mutmut mutates the function (it skips decorated ones)
    reduced_energy = property(_get_reduced_energy)

    def _arg(self, t: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        return self._kappa * t + self._w0

    def nutation_period(self) -> float:
        """The period of θ(t), 2K(m)/κ (u = u1 + (u2 − u1) sn²(κt + w0 | m)); inf for a
        sleeping top, whose θ stays put."""
        if self.sleeping:
            return math.inf
        return 2.0 * float(elliptic._quarter_period(np.float64(self._m1))) / self._kappa

    def u(self, t: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """u(t) = cos θ(t) = u1 + (u2 − u1) sn²(κt + w0 | m)."""
        t = as_float_array(t, "t")
        if self.sleeping:
            return np.full_like(t, self.u0)
        sn, _, _, _ = elliptic.ellipj(self._arg(t), self._m, m1=self._m1)
        return self.roots[0] + self._d21 * sn * sn

    u = finite_result(u)

    def theta(self, t: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """θ(t) from u(t), as atan2(sin θ, cos θ) with sin θ = √((1 − u)(1 + u))."""
        u = self.u(t)
        return np.arctan2(np.sqrt(np.maximum((1 - u) * (1 + u), 0.0)), u)

    theta = finite_result(theta)

    def _integral(self, n: float, t: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        """∫₀^t dt'/(1 − n sn²(κt' + w0)) = t + [G(w) − G(w0)]/κ."""
        w = np.ascontiguousarray(self._arg(t)).ravel()
        ww = np.concatenate([w, [self._w0]])
        G = elliptic._third_kind_excess(
            ww, np.full_like(ww, n), np.full_like(ww, self._m), np.full_like(ww, self._m1)
        )
        return t + ((G[:-1] - G[-1]) / self._kappa).reshape(np.shape(t))  # type: ignore[no-any-return]  # numpy: an element (G[-1]) is Any

    def psi(self, t: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """Precession angle ψ(t): ψ̇ = (a − bu)/(1 − u²) (5.67) integrated in closed form."""
        t = as_float_array(t, "t")
        if self.sleeping:
            return self.psi0 + self.psi_dot0 * t
        out = self.psi0 + 0.0 * t
        if self._amb != 0:
            out = out + 0.5 * self._amb / (self._omu2 + self._d21) * self._integral(self._npl, t)
        if self._apb != 0:
            out = out + 0.5 * self._apb / self._opu1 * self._integral(self._nmi, t)
        return out

    psi = finite_result(psi)

    def phi(self, t: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """Spin angle φ(t): φ̇ = L3/J3 − u ψ̇ (5.53), in closed form."""
        t = as_float_array(t, "t")
        if self.sleeping:
            return self.phi0 + self.phi_dot0 * t
        out = self.phi0 + (self._L3n / self._J3n - self._b) * t
        if self._amb != 0:
            out = out - 0.5 * self._amb / (self._omu2 + self._d21) * self._integral(self._npl, t)
        if self._apb != 0:
            out = out + 0.5 * self._apb / self._opu1 * self._integral(self._nmi, t)
        return out

    phi = finite_result(phi)

    def rates(
        self, t: npt.ArrayLike
    ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.float64]]:
        """(θ̇, ψ̇, φ̇)(t) along the exact motion.

        1 ± u are carried as (1 + u1) + (u2 − u1) sn² and (1 − u2) + (u2 − u1) cn², and
        ψ̇ = ½[(a − b)/(1 − u) + (a + b)/(1 + u)], so that nothing cancels when the top
        passes near θ = 0 or π (the Euler angles' own singularity remains at the instant
        sin θ = 0)."""
        t = as_float_array(t, "t")
        if self.sleeping:
            return np.zeros_like(t), np.full_like(t, self.psi_dot0), np.full_like(t, self.phi_dot0)
        sn, cn, dn, _ = elliptic.ellipj(self._arg(t), self._m, m1=self._m1)
        opu = self._opu1 + self._d21 * sn * sn
        omu = self._omu2 + self._d21 * cn * cn
        u = self.roots[0] + self._d21 * sn * sn
        with np.errstate(divide="ignore", invalid="ignore"):
            tp = np.where(self._amb != 0, self._amb / omu, 0.0)
            tm = np.where(self._apb != 0, self._apb / opu, 0.0)
        psid = 0.5 * (tp + tm)
        phid = self._L3n / self._J3n - u * psid
        udot = 2 * self._d21 * sn * cn * dn * self._kappa
        thd = -udot / np.sqrt(omu * opu)
        return thd, psid, phid

    rates = finite_result(rates)

    def energy_at(self, t: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """E(t) from the exact motion (5.66); constant."""
        return self.integrals_at(t)[2]

    energy_at = finite_result(energy_at)

    def integrals_at(self, t: npt.ArrayLike) -> tuple[npt.NDArray[np.float64], ...]:
        """(L_z, L_3, E) evaluated along the exact motion, (5.55), (5.53), (5.66)."""
        thd, psid, phid = self.rates(t)
        u = self.u(t)
        S2 = (1 - u) * (1 + u)
        L3 = self._J3n * (psid * u + phid)
        Lz = self._J1n * S2 * psid + L3 * u
        E = 0.5 * self._J1n * (thd**2 + psid**2 * S2) + L3**2 / (2 * self._J3n) + self._mgln * u
        return tuple(np.ldexp(x, self._k) for x in (Lz, L3, E))

    integrals_at = finite_result(integrals_at)


# --------------------------------------------------------------------------- Example 5.1


def spherical_top_on_incline(
    t: npt.ArrayLike,
    *,
    m: float,
    R: float,
    J: float,
    beta: float,
    g: float,
    x0: float = 0.0,
    y0: float = 0.0,
    omega_0: npt.ArrayLike = (0.0, 0.0, 0.0),
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """Sphere rolling without slipping on a rough incline (Example 5.1).

    Domain: m, R, J, g > 0, β in [0, π/2], finite t, x0, y0, ω0; a result beyond float64 raises
    ResultOverflowError.

    X down the incline, Z the plane's normal.  Returns ``(x, y, omega)`` with
    x(t) = x0 + R ω_y(0) t + ½ R α t², α = R m g sin β/(J + mR²) (5.15), (5.22),
    y(t) = y0 − R ω_x(0) t (5.23), ω = (ω_x(0), ω_y(0) + αt, ω_z(0)) (5.16)–(5.18).

    Parameters
    ----------
    t : array_like, shape (...)
        Times, s.
    m : float
        Mass, kg, > 0.
    R : float
        Radius, m, > 0.
    J : float
        Moment of inertia about a diameter, kg m², > 0.
    beta : float
        Inclination β of the plane, rad, in [0, π/2].
    g : float
        Gravitational acceleration, m/s², > 0.
    x0, y0 : float
        Initial position of the contact point in the plane, m.
    omega_0 : array_like, shape (3,)
        Initial angular velocity (X, Y, Z components), rad/s.

    Returns
    -------
    x, y : ndarray, shape (...)
        Position in the plane at the times ``t``, m.
    omega : ndarray, shape (..., 3)
        Angular velocity at the times ``t``, rad/s.

    Raises
    ------
    NonPositiveParameterError
        If ``m``, ``R``, ``J`` or ``g`` is ≤ 0.
    OutOfDomainError
        If β lies outside [0, π/2].
    ResultOverflowError
        If a result exceeds float64's range.
    NonFiniteError
        If an input is NaN or infinite.
    ShapeError
        If a scalar parameter is not a real scalar, or ``omega_0`` not of shape (3,).

    Examples
    --------
    A uniform solid sphere (J = 2mR²/5) accelerates at (5/7) g sin β:

    >>> x, y, w = spherical_top_on_incline(1.0, m=1.0, R=1.0, J=0.4, beta=0.5, g=9.81)
    >>> bool(abs(x - 0.5 * 5 / 7 * 9.81 * np.sin(0.5)) < 1e-14)
    True
    """
    t = as_float_array(t, "t")
    m, R, J, g = (_positive(v, k) for k, v in dict(m=m, R=R, J=J, g=g).items())
    beta = as_float_scalar(beta, "beta")
    if not 0.0 <= beta <= math.pi / 2:
        raise OutOfDomainError(f"beta must lie in [0, π/2]; got {beta!r}")
    w0 = _vec3(omega_0, "omega_0")
    x0 = as_float_scalar(x0, "x0")
    y0 = as_float_scalar(y0, "y0")
    alpha = R * m * g * math.sin(beta) / (J + m * R * R)
    x = x0 + R * w0[1] * t + 0.5 * R * alpha * t * t
    y = y0 - R * w0[0] * t
    omega = np.stack([np.full_like(t, w0[0]), w0[1] + alpha * t, np.full_like(t, w0[2])], -1)
    return x, y, omega


spherical_top_on_incline = finite_result(spherical_top_on_incline)
