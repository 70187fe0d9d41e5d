"""Jacobi elliptic functions and elliptic integrals, accurate for every parameter.

Conventions
-----------
- **Parameter m = k²**, as mpmath and scipy say it (not the modulus k).  Every
  function also takes the **complementary parameter** ``m1 = 1 − m`` as a keyword.
  Near m = 1 the functions depend on m only through m1, and a float m within
  1e-12 of 1 carries m1 to about 4 digits at best: give m1 whenever you have it
  (the free top computes it exactly from its initial data).  When ``m1`` is
  given it is authoritative; ``m`` must agree with ``1 − m1`` to rounding, else
  :class:`~mechanics.errors.OutOfDomainError`.
- ``ellipj(u, m)`` returns ``(sn, cn, dn, am)`` for every real m: 0 ≤ m ≤ 1
  directly, m > 1 by the reciprocal-modulus transformation
  sn(u|m) = sn(√m u | 1/m)/√m, cn(u|m) = dn(√m u | 1/m), dn(u|m) = cn(√m u | 1/m)
  (DLMF 22.17.2–4), and m < 0 by the imaginary-modulus transformation
  sn(u|m) = sd(v|μ)/√m1, cn(u|m) = cd(v|μ), dn(u|m) = nd(v|μ), v = √m1 u,
  μ = −m/m1 (Abramowitz & Stegun 16.10).  am = atan2(sn, cn) continued so
  that it is continuous in u (for m > 1 it stays in (−π/2, π/2)).
- Incomplete integrals in Legendre's form with the amplitude φ:
  F(φ|m) = ∫₀^φ dθ/Δ, Π(n; φ|m) = ∫₀^φ dθ/((1 − n sin²θ) Δ),
  Δ = √(1 − m sin²θ), extended quasi-periodically,
  F(φ + jπ) = F(φ) + 2jK (mpmath's convention).  ``ellippi_jacobi(u, n, m)`` is
  the same third-kind integral in Jacobi's form, ∫₀^u dv/(1 − n sn²v) =
  Π(n; am u | m), which is what the tops need.

Method
------
The argument is reduced by the period 2K (K from ``scipy.special.ellipkm1`` of
the exact m1, u − 2jK with an error-free product), and by the quarter-period
shift sn(K − y) = cd(y), cn(K − y) = k' sd(y), dn(K − y) = k' nd(y) to
0 ≤ y ≤ K/2.  There, for m ≤ 1/2 the descending Landen (AGM) recurrence of the
amplitude (A&S 16.4) gives sn = sin φ₀, cn = cos φ₀; for m > 1/2 the same
recurrence runs on the *complementary* AGM in hyperbolic form
(Jacobi's imaginary transformation): ψ_{n−1} = (ψ_n + asinh(c_n/a_n sinh ψ_n))/2,
sn = tanh ψ₀, cn = sech ψ₀ — so that cn and dn = √(m1 + m cn²) keep full
*relative* accuracy where they are tiny (u near K, m near 1), which cos φ₀ cannot.
The AGM terms use c_{n+1} = c_n²/(4a_{n+1}), free of cancellation.  The
integrals use Carlson's R_F and R_J (``scipy.special.elliprf``/``elliprj``) with
Δ² = cos²φ + m1 sin²φ written without cancellation.

Accuracy (``tests/stability/test_elliptic_stability.py``, mpmath at 50 digits,
``tests/data/elliptic_reference.json``): the error of sn, cn, dn, am is measured in
units of eps · (|f| + |u f'(u)|), the size of the change of f when u is rounded
(so a relative error where f is well-conditioned, and the unavoidable u·eps
phase error at large u); the promise is :data:`ELLIPJ_EPS` = 64 eps for every real
m.  Measured worst: 1.34 eps over the reference grid (m ∈ {−1e10, −10, −1, −1e-15,
0, 1e-300, 1/2, 1 − 1e-6, 1 − 1e-12, 1 − 1e-15, 1 − 1e-100 and 1 − 1e-300 through
m1, 1, 1 + 1e-15, 1.5, 10, 1e10}, |u| from 1e-10 to 1e4), 2.3 eps in a
1000-example hypothesis search over the same regimes.  scipy's ``ellipj`` in
the same metric: 25 eps at m = 1/2 (|u| ≤ 30), 2e4 eps at m = 1 − 1e-6 and up to
1e14 eps (wrong values) for 1 − 1e-9 ≥ m ≥ 1 − 1e-15; NaN outside [0, 1].

Speed (``tests/benchmarks/test_bench_tops.py``, 10^4 arguments, one m): about
0.3–0.4 µs per argument, 1.2 times scipy's time at m = 1/2 and about 4 times at
m = 1 − 1e-12 (where scipy's fast path is the inaccurate one).
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt
import scipy.special as sc

from ._floats import EPS
from ._floats import two_prod_or_zero as _two_prod_or_zero
from ._floats import two_prod_or_zero_scalar as _two_prod_or_zero_scalar
from ._validate import as_float_array, broadcast_checked, finite_result
from .errors import OutOfDomainError, ResultOverflowError

__all__ = [
    "ELLIPJ_EPS",
    "EPS",
    "ellipe",
    "ellipf",
    "ellipj",
    "ellipk",
    "ellippi",
    "ellippi_jacobi",
]

ELLIPJ_EPS = 64.0
"""Stated accuracy of :func:`ellipj` in eps (conditioned scale, see module docstring)."""

_N_AGM = 6
"""AGM steps: from c₀/a₀ ≤ √(1/2) (the worst case, m = 1/2) the ratio falls as
0.17, 7e-3, 1.4e-5, 5e-11, 6e-22, 9e-44: six steps leave nothing at float64."""


def _params(
    m: npt.ArrayLike, m1: npt.ArrayLike | None, name: str = "m"
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """Validated, broadcast (m, m1) with m1 = 1 − m exact where given."""
    m = as_float_array(m, name)
    if m1 is None:
        return m, 1.0 - m
    m1 = as_float_array(m1, "m1")
    m, m1 = np.broadcast_arrays(m, m1)
    gap = np.abs((m - 1.0) + m1)
    tol = 8 * EPS * np.maximum(1.0, np.maximum(np.abs(m), np.abs(m1)))
    if np.any(gap > tol):
        i = np.unravel_index(np.argmax(gap - tol), gap.shape)
        raise OutOfDomainError(
            f"m1 must equal 1 − m to rounding; got m = {float(m[i])!r}, "
            f"m1 = {float(m1[i])!r} (m + m1 − 1 = {float(gap[i]):.3g})"
        )
    return m.astype(np.float64), m1.astype(np.float64)


def _no_overflow(
    out: npt.NDArray[np.float64], m1: npt.ArrayLike, name: str
) -> npt.NDArray[np.float64]:
    """``out``, or ResultOverflowError where it is not finite though m < 1 (m1 > 0): there
    the value is finite, ~φ·2K/π, and only a |φ| near float64's limit overflows it; at
    m = 1 (m1 = 0) an infinite value is the true one, K(1) = inf (documented)."""
    bad = ~np.isfinite(out) & (np.broadcast_to(m1, np.shape(out)) > 0)
    if np.any(bad):
        raise ResultOverflowError(
            f"{name}: the integral exceeds float64's range (~1.8e308) for an argument this large"
        )
    return out


def _quarter_period(p1: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """K for parameter p = 1 − p1 ≥ 0 given p1 exactly (inf at p1 = 0)."""
    with np.errstate(divide="ignore"):
        return sc.ellipkm1(p1)  # type: ignore[no-any-return]  # scipy ships no types


def _asinh_r_sinh(
    r: float | npt.NDArray[np.float64], psi: npt.NDArray[np.float64]
) -> npt.NDArray[np.float64]:
    """asinh(r · sinh ψ) for r ≥ 0, ψ ≥ 0, without overflow for large ψ."""
    big = psi > 350.0
    if not np.any(big):
        return np.arcsinh(r * np.sinh(psi))
    out = np.arcsinh(r * np.sinh(np.minimum(psi, 350.0)))
    with np.errstate(divide="ignore"):
        logy = np.log(r) + psi - np.log(2.0)  # log(r sinh ψ), e^{-2ψ} < 1e-300 dropped
    huge = logy > 40.0
    small_val = np.arcsinh(np.exp(np.minimum(logy, 40.0)))
    big_val = np.where(huge, logy + np.log(2.0), small_val)
    return np.where(big, big_val, out)


def _agm_ratios(
    p: npt.NDArray[np.float64], p1: npt.NDArray[np.float64], hyper: bool, ymax: float
) -> tuple[npt.NDArray[np.float64], list[npt.NDArray[np.float64]]]:
    """a_N and the ratios c_n/a_n (n = 1..N) of the AGM for the amplitude recurrence.

    Trig: AGM(1, √p1) with c0 = √p; hyperbolic: AGM(1, √p) with c0 = √p1.  A constant
    parameter (the usual case: one m, many u) is iterated once as a scalar; the
    iteration stops once every next term is below 2⁻⁶⁴ of φ: r_n |sin φ_n| ≤ r_n (trig) or
    r_n sinh ψ_n ≤ r_n e^{2ⁿ a_n y_max} (hyperbolic, where ψ_n can be large), at most
    :data:`_N_AGM` steps.
    """
    if p.size > 1 and np.all(p == p.flat[0]) and np.all(p1 == p1.flat[0]):
        a, ratios = _agm_ratios(p[:1], p1[:1], hyper, ymax)
        return a[0], [r[0] for r in ratios]
    a = np.ones_like(p)
    b = np.sqrt(p) if hyper else np.sqrt(p1)
    c = np.sqrt(p1) if hyper else np.sqrt(p)
    ratios = []
    for _ in range(_N_AGM):
        a_new = 0.5 * (a + b)
        b = np.sqrt(a * b)
        c = c * c / (4.0 * a_new)
        a = a_new
        ratios.append(c / a)
        grow = np.exp(np.minimum(2.0 ** len(ratios) * a * ymax, 700.0)) if hyper else 1.0
        if np.all(ratios[-1] * grow < 2.0**-64):
            break
    return a, ratios


def _core(
    y: npt.NDArray[np.float64], p: npt.NDArray[np.float64], p1: npt.NDArray[np.float64]
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """sn, cn, dn of 0 ≤ y ≤ K/2 for 0 ≤ p ≤ 1 (relative accuracy)."""
    sn = np.empty_like(y)
    cn = np.empty_like(y)
    dn = np.empty_like(y)
    trig = p <= 0.5
    for mask, hyper in ((trig, False), (~trig, True)):
        if not mask.any():
            continue
        yy, pp, qq = y[mask], p[mask], p1[mask]
        a, ratios = _agm_ratios(pp, qq, hyper, float(yy.max()))
        phi = (2.0 ** len(ratios)) * a * yy
        if hyper:
            for r in reversed(ratios):
                phi = 0.5 * (phi + _asinh_r_sinh(r, phi))
            with np.errstate(over="ignore"):
                s_ = np.tanh(phi)
                c_ = 1.0 / np.cosh(phi)
            # √(m1 + m cn²) as a hypotenuse: cn² underflows for cn below ~1e-154 (at
            # m = 1, |u| ≳ 355) while dn = √m |cn| is still a normal float
            d_ = np.hypot(np.sqrt(qq), np.sqrt(pp) * c_)
        else:
            for r in reversed(ratios):
                phi = 0.5 * (phi + np.arcsin(r * np.sin(phi)))
            s_ = np.sin(phi)
            c_ = np.cos(phi)
            d_ = np.sqrt(1.0 - pp * s_ * s_)
        sn[mask], cn[mask], dn[mask] = s_, c_, d_
    return sn, cn, dn


#: what :func:`_reduced` returns: (j, s, sn x, cn x, dn x, K), each an array of u's shape
_Reduction = tuple[
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
]


def _reduced(
    u: npt.NDArray[np.float64], p: npt.NDArray[np.float64], p1: npt.NDArray[np.float64]
) -> _Reduction:
    """Reduce u = 2jK + s·x (0 ≤ x ≤ K) and evaluate at x.

    Returns (j, s, snx, cnx, dnx, K) with snx, cnx ≥ 0 the functions at x.
    """
    K = _quarter_period(p1)
    finite = np.isfinite(K)
    K2 = np.where(finite, 2.0 * K, 1.0)
    j = np.where(finite, np.rint(u / K2), 0.0)
    prod, err = _two_prod_or_zero(j, K2)
    r = np.where(finite, (u - prod) - err, u)
    s = np.where(r < 0, -1.0, 1.0)
    x = np.abs(r)
    Kf = np.where(finite, K, np.inf)
    x = np.minimum(x, Kf)
    flip = x > 0.5 * Kf
    y = np.where(flip, Kf - x, x)
    sy, cy, dy = _core(y, p, p1)
    kp = np.sqrt(p1)
    with np.errstate(divide="ignore", invalid="ignore"):  # dy = 0 only off the flip branch
        snx = np.where(flip, cy / dy, sy)
        cnx = np.where(flip, kp * sy / dy, cy)
        dnx = np.where(flip, kp / dy, dy)
    return j, s, snx, cnx, dnx, K


def _scaled(u: npt.NDArray[np.float64], rt: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
    """u·√|m| or u·√(1 − m) for the transformations; refuse what overflows float64."""
    with np.errstate(over="ignore"):
        v = u * rt
    if not np.isfinite(v).all():
        i = np.argmax(~np.isfinite(v))
        raise OutOfDomainError(
            f"ellipj needs |u|·√max(|m|, 1 − m) < 1.8e308 for the modulus transformation; "
            f"got u = {float(u[i])!r} with scale {float(rt[i])!r}"
        )
    return v


def ellipj(
    u: npt.ArrayLike, m: npt.ArrayLike, *, m1: npt.ArrayLike | None = None
) -> tuple[npt.NDArray[np.float64], ...]:
    """Jacobi elliptic functions sn, cn, dn and the amplitude am, for every real m.

    Domain: every finite u and every finite m (m > 1 by the reciprocal modulus, m < 0 by the
    imaginary modulus); results are finite there. The phase is reduced modulo the period 4K: for |u|
    ≳ 4K/eps (~1e16) it is lost (finite, meaningless values).

    Parameters
    ----------
    u : array_like, shape (...)
        Argument, finite.
    m : array_like, shape (...)
        Parameter m = k², any finite real number (broadcast against ``u``).
    m1 : array_like, shape (...), optional
        Complementary parameter 1 − m, given exactly (authoritative near m = 1).

    Returns
    -------
    sn, cn, dn, am : ndarray, shape (...)
        The broadcast shape of ``u``, ``m`` (and ``m1``); ``am`` in rad.

    Raises
    ------
    NonFiniteError
        If an input is NaN or infinite.
    OutOfDomainError
        If ``m1`` disagrees with ``1 − m``, or |u|·√|m| (m > 1) or |u|·√(1 − m)
        (m < 0) overflows.
    ShapeError
        If an input is not a real numeric array, or the shapes do not broadcast.

    Notes
    -----
    See the module docstring for the method and the measured accuracy.  At
    m = 1 (m1 = 0): sn = tanh u, cn = dn = sech u, am = gd u.

    Examples
    --------
    sn² + cn² = 1 and dn² + m sn² = 1, here just below the separatrix value m = 1:

    >>> sn, cn, dn, am = ellipj(10.0, 1 - 1e-15, m1=1e-15)
    >>> bool(abs(sn**2 + cn**2 - 1) < 1e-15), bool(abs(dn**2 + (1 - 1e-15) * sn**2 - 1) < 1e-15)
    (True, True)
    >>> float(ellipj(0.3, 0.0)[0]) == float(np.sin(0.3))
    True
    """
    u = as_float_array(u, "u")
    m, m1 = _params(m, m1)
    u, m, m1 = np.broadcast_arrays(u, m, m1)
    shape = u.shape
    u, m, m1 = (np.ascontiguousarray(a, dtype=np.float64).ravel() for a in (u, m, m1))
    sn = np.empty_like(u)
    cn = np.empty_like(u)
    dn = np.empty_like(u)
    am = np.empty_like(u)

    mid = (m >= 0) & (m <= 1)
    if mid.any():
        j, s, snx, cnx, dnx, _ = _reduced(u[mid], m[mid], m1[mid])
        sign = 1.0 - 2.0 * np.mod(j, 2.0)
        sn[mid] = sign * s * snx
        cn[mid] = sign * cnx
        dn[mid] = dnx
        am[mid] = j * np.pi + s * np.arctan2(snx, cnx)

    hi = m > 1
    if hi.any():
        mm, q = m[hi], m1[hi]
        rt = np.sqrt(mm)
        j, s, snx, cnx, dnx, _ = _reduced(_scaled(u[hi], rt), 1.0 / mm, -q / mm)
        sign = 1.0 - 2.0 * np.mod(j, 2.0)
        sv = sign * s * snx
        sn[hi] = sv / rt
        cn[hi] = dnx
        dn[hi] = sign * cnx
        am[hi] = np.arctan2(sn[hi], cn[hi])

    lo = m < 0
    if lo.any():
        mm, q = m[lo], m1[lo]  # q = 1 − m > 1
        rt = np.sqrt(q)
        j, s, snx, cnx, dnx, _ = _reduced(_scaled(u[lo], rt), -mm / q, 1.0 / q)
        sign = 1.0 - 2.0 * np.mod(j, 2.0)
        sn[lo] = sign * s * snx / (dnx * rt)
        cn[lo] = sign * cnx / dnx
        dn[lo] = 1.0 / dnx
        am[lo] = j * np.pi + s * np.arctan2(snx, rt * cnx)

    return tuple(a.reshape(shape) for a in (sn, cn, dn, am))


ellipj = finite_result(ellipj)


def ellipk(m: npt.ArrayLike, *, m1: npt.ArrayLike | None = None) -> npt.NDArray[np.float64]:
    """Complete elliptic integral of the first kind K(m) for m ≤ 1 (K(1) = inf).

    Domain: every float64 m ≤ 1 (down to −1.8e308: K ~ ln(4√−m)/√−m); K(1) = inf is the one
    non-finite value, documented; m > 1 raises OutOfDomainError.

    Parameters
    ----------
    m : array_like, shape (...)
        Parameter, m ≤ 1.
    m1 : array_like, shape (...), optional
        1 − m given exactly (use it near m = 1: K ≈ ln(4/√m1)).

    Returns
    -------
    K : ndarray, shape (...)
        K(m), the broadcast shape of ``m`` (and ``m1``); inf where m = 1.

    Raises
    ------
    OutOfDomainError
        If m > 1 (K is not real there), or ``m1`` disagrees with ``1 − m``.
    NonFiniteError
        If an input is NaN or infinite.
    ShapeError
        If an input is not a real numeric array, or ``m`` and ``m1`` do not broadcast.

    Examples
    --------
    K(0) = π/2, and near m = 1 the complement gives K ≈ ln(4/√m1):

    >>> bool(abs(ellipk(0.0) - np.pi / 2) < 1e-15)
    True
    >>> round(float(ellipk(1.0, m1=1e-300)), 6)  # ln(4e150) = 346.774058...
    346.774058
    """
    m, m1 = _params(m, m1)
    if np.any(m > 1):
        raise OutOfDomainError(f"ellipk needs m ≤ 1; got m = {float(m[m > 1].flat[0])!r}")
    return _quarter_period(np.maximum(m1, 0.0))


ellipk = broadcast_checked(ellipk)


def ellipe(m: npt.ArrayLike, *, m1: npt.ArrayLike | None = None) -> npt.NDArray[np.float64]:
    """Complete elliptic integral of the second kind E(m) for m ≤ 1.

    Domain: every float64 m ≤ 1 (E(1) = 1); m > 1 raises OutOfDomainError.

    Computed as 2 R_G(0, m1, 1) (Carlson, DLMF 19.25.1) from the exact m1.

    Parameters
    ----------
    m : array_like, shape (...)
        Parameter, m ≤ 1.
    m1 : array_like, shape (...), optional
        1 − m given exactly (authoritative near m = 1).

    Returns
    -------
    E : ndarray, shape (...)
        E(m), the broadcast shape of ``m`` (and ``m1``); E(1) = 1.

    Raises
    ------
    OutOfDomainError
        If m > 1, or ``m1`` disagrees with ``1 − m``.
    NonFiniteError
        If an input is NaN or infinite.
    ShapeError
        If an input is not a real numeric array, or ``m`` and ``m1`` do not broadcast.

    Examples
    --------
    >>> bool(abs(ellipe(1.0) - 1.0) < 1e-15), bool(abs(ellipe(0.0) - np.pi / 2) < 1e-15)
    (True, True)

    Legendre's relation E K' + E' K − K K' = π/2 (DLMF 19.7.1), at m = 1/2 where
    K' = K and E' = E:

    >>> K, E = ellipk(0.5), ellipe(0.5)
    >>> round(float(2 * E * K - K * K), 12), round(np.pi / 2, 12)
    (1.570796326795, 1.570796326795)
    """
    m, m1 = _params(m, m1)
    if np.any(m > 1):
        raise OutOfDomainError(f"ellipe needs m ≤ 1; got m = {float(m[m > 1].flat[0])!r}")
    m1 = np.maximum(m1, 0.0)
    out = 2.0 * sc.elliprg(0.0, m1, 1.0)
    return np.where(m1 == 0, 1.0, out)


ellipe = broadcast_checked(ellipe)


def _amplitude(
    phi: npt.NDArray[np.float64], m: npt.NDArray[np.float64], m1: npt.NDArray[np.float64], name: str
) -> tuple[
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
]:
    """Reduce φ = jπ + φr, |φr| ≤ π/2; return (j, sin φr, cos φr, Δ²)."""
    j = np.rint(phi / np.pi)
    pr, err = _two_prod_or_zero(j, np.pi)
    # π = fl(π) + 1.2246e-16: carry the tail so that large φ keep their value
    r = ((phi - pr) - err) - j * 1.2246467991473532e-16
    s, c = np.sin(r), np.cos(r)
    s2 = s * s
    delta2 = np.where(m > 0.5, c * c + m1 * s2, 1.0 - m * s2)
    if np.any(delta2 < 0):
        i = np.argmin(delta2)
        raise OutOfDomainError(
            f"{name} needs m sin²φ ≤ 1 (real integrand); got m = {float(m.flat[i])!r}, "
            f"φ = {float(phi.flat[i])!r}"
        )
    hi = (m > 1) & (j != 0)
    if np.any(hi):
        raise OutOfDomainError(f"{name} for m > 1 needs |φ| ≤ asin(1/√m) < π/2; got larger φ")
    return j, s, c, np.maximum(delta2, 0.0)


def ellipf(
    phi: npt.ArrayLike, m: npt.ArrayLike, *, m1: npt.ArrayLike | None = None
) -> npt.NDArray[np.float64]:
    """Incomplete elliptic integral of the first kind F(φ|m).

    Domain: any finite φ for m ≤ 1 (φ = ±π/2 at m = 1 is the logarithmic singularity); for m > 1,
    |φ| ≤ asin(1/√m) (else OutOfDomainError); m down to −1.8e308.

    F(φ|m) = sin φ R_F(cos²φ, Δ², 1) on |φ| ≤ π/2, F(φ + jπ) = F(φ) + 2jK.

    Parameters
    ----------
    phi : array_like, shape (...)
        Amplitude φ, rad, finite.
    m : array_like, shape (...)
        Parameter m = k², finite (broadcast against ``phi``).
    m1 : array_like, shape (...), optional
        1 − m given exactly (authoritative near m = 1).

    Returns
    -------
    F : ndarray, shape (...)
        F(φ|m), the broadcast shape of ``phi``, ``m`` (and ``m1``); ±inf only at
        m = 1 beyond |φ| = π/2 (the logarithmic singularity).

    Raises
    ------
    OutOfDomainError
        If m > 1 and |φ| > asin(1/√m) (m sin²φ > 1: a complex integrand), or ``m1``
        disagrees with ``1 − m``.
    ResultOverflowError
        If m < 1 and the integral exceeds float64 (|φ| near 1.8e308).
    NonFiniteError
        If an input is NaN or infinite.
    ShapeError
        If an input is not a real numeric array, or the shapes do not broadcast.

    Examples
    --------
    F inverts the amplitude:

    >>> sn, cn, dn, am = ellipj(2.5, 0.9)
    >>> bool(abs(ellipf(am, 0.9) - 2.5) < 1e-14)
    True
    """
    phi = as_float_array(phi, "phi")
    m, m1 = _params(m, m1)
    phi, m, m1 = np.broadcast_arrays(phi, m, m1)
    j, s, c, d2 = _amplitude(phi, m, m1, "ellipf")
    with np.errstate(divide="ignore", invalid="ignore"):
        f = s * sc.elliprf(c * c, d2, 1.0)
    f = np.where(s == 0, 0.0, f)
    kk = np.where(j != 0, _quarter_period(np.maximum(m1, 0.0)), 0.0)
    with np.errstate(over="ignore"):
        out = f + 2.0 * j * kk
    return _no_overflow(out, m1, "ellipf")


ellipf = broadcast_checked(ellipf)


#: below this, both of R_J's first two arguments lose scipy's R_J its accuracy (measured
#: with scipy 1.17 against mpmath, z = 1: 3e7 eps at x = y/2 = 1e-160, 7e12 eps at 1e-170;
#: right to 2 eps down to 1e-150, and whenever one of the two is above 1e-150), and a 0
#: beside a subnormal makes it inf (elliprj(0, 1e-310, 1, 0.5); mpmath: 2142.2)
_RJ_TINY = 2.0**-400


#: √:data:`_RJ_TINY`: where dn < this, dn² and cn² (≤ dn²/m) are below it, and near u = K at
#: m1 ≲ 1e-308 they lose their digits as subnormals (or underflow to 0)
_RJ_TINY_ROOT = 2.0**-200


def _duplication_step(
    sx: float | npt.NDArray[np.float64],
    sy: float | npt.NDArray[np.float64],
    sz: float | npt.NDArray[np.float64],
    p: float | npt.NDArray[np.float64],
) -> tuple[float | npt.NDArray[np.float64], ...]:
    """One step of Carlson's duplication theorem (Carlson 1995, eq. 2.22; DLMF 19.26.20),
    from the square roots sx = √x, sy = √y, sz = √z:
    R_J(x, y, z, p) = 2 R_J(x + λ, y + λ, z + λ, p + λ) + 3 R_C(α², β²) with
    λ = √x√y + √y√z + √z√x, α = p(√x + √y + √z) + √x√y√z, β = √p (p + λ); it holds for
    x = 0 or y = 0 too.  Returns (x + λ, y + λ, z + λ, p + λ, 3 R_C(α², β²)); x = sx² only
    enters beside λ ≥ sx·sz, so its underflow for a tiny sx costs nothing where z ~ 1."""
    lam = sx * sy + sy * sz + sz * sx
    alpha = p * (sx + sy + sz) + sx * sy * sz
    beta = np.sqrt(p) * (p + lam)
    rc = 3.0 * sc.elliprc(alpha * alpha, beta * beta)
    return sx * sx + lam, sy * sy + lam, sz * sz + lam, p + lam, rc


def _rj_of_roots(
    sx: float | npt.NDArray[np.float64],
    sy: float | npt.NDArray[np.float64],
    sz: float | npt.NDArray[np.float64],
    p: float | npt.NDArray[np.float64],
) -> float | npt.NDArray[np.float64]:
    """R_J(sx², sy², sz², p) by two steps of :func:`_duplication_step`, then scipy's R_J:
    R_J = 4 R_J(x₂, y₂, z₂, p₂) + 2·3 R_C(α₁², β₁²) + 3 R_C(α₀², β₀²).
    For x, y ≪ z a step lifts them to about √(max(x, y) z): with z = 1, from 5e-324 to
    2e-162 and then to 1e-81, where scipy's R_J is accurate (one step is not enough where
    both are subnormal: it lands them in 1e-162–1e-157, where scipy is off by up to 1e13
    eps; measured 1e10 eps at x, y = 1.4e-322, 9.6e-322)."""
    x1, y1, z1, p1, rc0 = _duplication_step(sx, sy, sz, p)
    x2, y2, z2, p2, rc1 = _duplication_step(np.sqrt(x1), np.sqrt(y1), np.sqrt(z1), p1)
    return 4.0 * sc.elliprj(x2, y2, z2, p2) + 2.0 * rc1 + rc0  # type: ignore[no-any-return]  # scipy: no types


def _rj_duplicated(
    x: float | npt.NDArray[np.float64],
    y: float | npt.NDArray[np.float64],
    z: float | npt.NDArray[np.float64],
    p: float | npt.NDArray[np.float64],
) -> float | npt.NDArray[np.float64]:
    """R_J by :func:`_rj_of_roots` (two duplication steps), for x, y ≪ z."""
    return _rj_of_roots(np.sqrt(x), np.sqrt(y), np.sqrt(z), p)


def _rj(
    x: npt.NDArray[np.float64],
    y: npt.NDArray[np.float64],
    z: npt.NDArray[np.float64],
    p: npt.NDArray[np.float64],
) -> float | npt.NDArray[np.float64]:
    """scipy's R_J, but by :func:`_rj_duplicated` where x and y are both below
    :data:`_RJ_TINY`, not negative and not both 0 (cn² and dn² near u = K with m1 below
    ~1e-160; R_J(0, m1, 1, 1 − n) at a subnormal m1)."""
    x, y, z, p = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (x, y, z, p)))
    out: float | npt.NDArray[np.float64] = sc.elliprj(x, y, z, p)
    hi = np.maximum(x, y)
    tiny = (np.minimum(x, y) >= 0) & (hi > 0) & (hi < _RJ_TINY)
    if tiny.any():
        out = np.array(out, dtype=float)  # a 0-d result too
        out[tiny] = _rj_duplicated(x[tiny], y[tiny], z[tiny], p[tiny])
    return out


def _rj_scalar(x: float, y: float, z: float, p: float) -> float:
    """:func:`_rj` of Python floats (the one-instant path)."""
    if min(x, y) >= 0.0 and 0.0 < max(x, y) < _RJ_TINY:
        return float(_rj_duplicated(x, y, z, p))
    return float(sc.elliprj(x, y, z, p))


def _third_kind_tail(
    s: npt.NDArray[np.float64],
    c: npt.NDArray[np.float64],
    d2: npt.NDArray[np.float64],
    n: npt.NDArray[np.float64],
) -> npt.NDArray[np.float64]:
    """(n/3) sin³φ R_J(cos²φ, Δ², 1, 1 − n sin²φ), zero at sin φ = 0."""
    s2 = s * s
    # R_J is homogeneous of degree −3/2: for m ≪ −1 (Δ² up to 1e300) scale its arguments
    # by λ = 1/√Δ², which brings them to [1e-150, 1e150] where scipy's R_J stays finite
    # (unscaled it returns NaN; found by the fuzz suite)
    lam = 1.0 / np.sqrt(np.maximum(d2, 1.0))
    with np.errstate(divide="ignore", invalid="ignore", under="ignore"):
        rj = _rj(c * c * lam, d2 * lam, lam, (1.0 - n * s2) * lam) * lam * np.sqrt(lam)
        t = (n / 3.0) * s2 * s * rj
    return np.where((s == 0) | (n == 0), 0.0, t)


def _third_kind_tail_of_roots(
    s: npt.NDArray[np.float64],
    c: npt.NDArray[np.float64],
    d: npt.NDArray[np.float64],
    n: npt.NDArray[np.float64],
) -> npt.NDArray[np.float64]:
    """:func:`_third_kind_tail` for 0 ≤ m ≤ 1 from c = |cn| and d = dn < :data:`_RJ_TINY_ROOT`
    (near u = K at m1 ≲ 1e-308), whose squares are subnormal or 0: (n/3) s³ R_J(c², d², 1, p)
    by :func:`_rj_of_roots`, which needs c and d only."""
    s2 = s * s
    t = (n / 3.0) * s2 * s * _rj_of_roots(c, d, 1.0, 1.0 - n * s2)
    return np.where((s == 0) | (n == 0), 0.0, t)


def _third_kind_tail_reduced(
    S: npt.NDArray[np.float64],
    cn: npt.NDArray[np.float64],
    dn: npt.NDArray[np.float64],
    n: npt.NDArray[np.float64],
) -> npt.NDArray[np.float64]:
    """:func:`_third_kind_tail` of S = ±sn and cn, dn ≥ 0 at a reduced argument: from cn² and
    dn², or, where dn < :data:`_RJ_TINY_ROOT` (cn², dn² subnormal), by
    :func:`_third_kind_tail_of_roots` from cn and dn themselves."""
    tail = _third_kind_tail(S, cn, dn * dn, n)
    near_k = dn < _RJ_TINY_ROOT
    if near_k.any():
        tail[near_k] = _third_kind_tail_of_roots(S[near_k], cn[near_k], dn[near_k], n[near_k])
    return tail


def _complete_tail(
    n: float | npt.NDArray[np.float64], m1: float | npt.NDArray[np.float64]
) -> npt.NDArray[np.float64]:
    """(n/3) R_J(0, m1, 1, 1 − n): Π(n|m) − K(m).

    R_J is homogeneous of degree −3/2: for m ≪ −1 (m1 up to 1.8e308) its arguments are
    scaled by λ = 1/√m1, to (0, √m1, 1/√m1, (1 − n)/√m1), as :func:`_third_kind_tail` does
    (unscaled, scipy's R_J is NaN for m1 ≳ 1e200); λ = 1 for m1 ≤ 1, where :func:`_rj`
    handles a subnormal m1 (scipy's R_J(0, m1, 1, p) is inf there)."""
    lam = 1.0 / np.sqrt(np.maximum(m1, 1.0))
    with np.errstate(divide="ignore", invalid="ignore", under="ignore"):
        rj = _rj(np.zeros_like(lam), m1 * lam, lam, (1.0 - n) * lam) * lam * np.sqrt(lam)
        t = (n / 3.0) * rj
    return np.where(n == 0, 0.0, t)


def _check_characteristic(n: npt.NDArray[np.float64], limit_ok: npt.NDArray[np.bool_]) -> None:
    if np.any(~limit_ok):
        raise OutOfDomainError(
            "the characteristic n must satisfy n sin²φ < 1 (and n < 1 beyond |φ| = π/2); "
            f"got n = {float(np.asarray(n)[~limit_ok].flat[0])!r}"
        )


def ellippi(
    n: npt.ArrayLike,
    phi: npt.ArrayLike,
    m: npt.ArrayLike,
    *,
    m1: npt.ArrayLike | None = None,
) -> npt.NDArray[np.float64]:
    """Incomplete elliptic integral of the third kind Π(n; φ|m) (mpmath's order).

    Domain: n sin²φ < 1, and n < 1 beyond |φ| = π/2 (else OutOfDomainError); the φ and m of
    :func:`ellipf`. For n ≪ −1 (|n| ≳ 1e8) F and the R_J tail cancel: the relative accuracy drops to
    ~|n|·eps.

    Π(n; φ|m) = F(φ|m) + (n/3) sin³φ R_J(cos²φ, Δ², 1, 1 − n sin²φ) on
    |φ| ≤ π/2 (DLMF 19.25.14), continued by Π(n; φ + jπ) = Π(n; φ) + 2jΠ(n|m).

    Parameters
    ----------
    n : array_like, shape (...)
        Characteristic, finite, n sin²φ < 1 (n < 1 beyond |φ| = π/2).
    phi : array_like, shape (...)
        Amplitude φ, rad, finite.
    m : array_like, shape (...)
        Parameter m = k², finite, as for :func:`ellipf`.
    m1 : array_like, shape (...), optional
        1 − m given exactly (authoritative near m = 1).

    Returns
    -------
    Pi : ndarray, shape (...)
        Π(n; φ|m), the broadcast shape of the inputs; ±inf only at m = 1 beyond
        |φ| = π/2, as F.

    Raises
    ------
    OutOfDomainError
        If n sin²φ ≥ 1, or n ≥ 1 beyond |φ| = π/2, or φ and m outside :func:`ellipf`'s
        domain, or ``m1`` disagrees with ``1 − m``.
    ResultOverflowError
        If m < 1 and the integral exceeds float64 (|φ| near 1.8e308; the message
        names ``ellipf``).
    NonFiniteError
        If an input is NaN or infinite.
    ShapeError
        If an input is not a real numeric array, or the shapes do not broadcast.

    Examples
    --------
    At n = 0 it is F:

    >>> bool(ellippi(0.0, 1.2, 0.7) == ellipf(1.2, 0.7))
    True
    """
    n = as_float_array(n, "n")
    phi = as_float_array(phi, "phi")
    m, m1 = _params(m, m1)
    n, phi, m, m1 = np.broadcast_arrays(n, phi, m, m1)
    j, s, c, d2 = _amplitude(phi, m, m1, "ellippi")
    _check_characteristic(n, (1.0 - n * s * s > 0) & ((j == 0) | (n < 1)))
    f = ellipf(phi, m, m1=m1)
    tail = _third_kind_tail(s, c, d2, n)
    # at m = 1 beyond |φ| = π/2 the value is ±inf (Π(n|1) = +inf for every n < 1: its
    # integrand grows as 1/cos θ at π/2), carried by F's 2jK; Π − K = −inf for n < 0 would
    # make it inf − inf = NaN (issue 16)
    sep = (m1 <= 0) & (j != 0)
    full = np.where((j != 0) & ~sep, _complete_tail(n, np.maximum(m1, 0.0)), 0.0)
    with np.errstate(over="ignore"):
        out = f + tail + 2.0 * j * full
    return _no_overflow(out, m1, "ellippi")


ellippi = broadcast_checked(ellippi)


def ellippi_jacobi(
    u: npt.ArrayLike,
    n: npt.ArrayLike,
    m: npt.ArrayLike,
    *,
    m1: npt.ArrayLike | None = None,
) -> npt.NDArray[np.float64]:
    """Third-kind integral in Jacobi's form, ∫₀^u dv / (1 − n sn²(v|m)) = Π(n; am u | m).

    Domain: 0 ≤ m ≤ 1 and n < 1, any finite u (else OutOfDomainError).  Evaluated from the reduced
    sn, cn, dn of :func:`ellipj` (so Δ = dn keeps its relative accuracy near m = 1), u + (n/3) sn³
    R_J(cn², dn², 1, 1 − n sn²) on the reduced argument plus 2j (Π(n|m) − K); at m = 1 in closed
    form, u + [n u + √−n atan(√−n tanh u)]/(1 − n) − u for n < 0 (and the atanh form for 0 < n < 1).

    Parameters
    ----------
    u : array_like, shape (...)
        Argument, finite.
    n : array_like, shape (...)
        Characteristic, n < 1.
    m : array_like, shape (...)
        Parameter m = k², 0 ≤ m ≤ 1.
    m1 : array_like, shape (...), optional
        1 − m given exactly (authoritative near m = 1).

    Returns
    -------
    Pi : ndarray, shape (...)
        ∫₀^u dv / (1 − n sn²(v|m)), the broadcast shape of the inputs.

    Raises
    ------
    OutOfDomainError
        If m < 0, m > 1 or n ≥ 1, or ``m1`` disagrees with ``1 − m``.
    ResultOverflowError
        If the integral exceeds float64 (0 < n < 1 and |u| near 1.8e308).
    NonFiniteError
        If an input is NaN or infinite.
    ShapeError
        If an input is not a real numeric array, or the shapes do not broadcast.

    Examples
    --------
    At n = 0 it is u; it agrees with Legendre's form:

    >>> float(ellippi_jacobi(2.0, 0.0, 0.5))
    2.0
    >>> am = ellipj(3.0, 0.8)[3]
    >>> bool(abs(ellippi_jacobi(3.0, -2.0, 0.8) - ellippi(-2.0, am, 0.8)) < 1e-14)
    True
    """
    u = as_float_array(u, "u")
    n = as_float_array(n, "n")
    m, m1 = _params(m, m1)
    if np.any((m < 0) | (m > 1)):
        raise OutOfDomainError("ellippi_jacobi needs 0 ≤ m ≤ 1")
    _check_characteristic(n, n < 1)
    u, n, m, m1 = np.broadcast_arrays(u, n, m, m1)
    shape = u.shape
    u, n, m, m1 = (np.ascontiguousarray(a, dtype=np.float64).ravel() for a in (u, n, m, m1))
    with np.errstate(over="ignore"):
        out = (u + _third_kind_excess(u, n, m, m1)).reshape(shape)
    return _no_overflow(out, 1.0, "ellippi_jacobi")  # m ≤ 1 and n < 1: always finite


ellippi_jacobi = broadcast_checked(ellippi_jacobi)


def _third_kind_excess(
    u: npt.NDArray[np.float64],
    n: npt.NDArray[np.float64],
    m: npt.NDArray[np.float64],
    m1: npt.NDArray[np.float64],
) -> npt.NDArray[np.float64]:
    """G(u) = ∫₀^u n sn²/(1 − n sn²) dv (flat arrays, 0 ≤ m ≤ 1, n < 1)."""
    out = np.empty_like(u)
    sep = m1 <= 0
    if sep.any():
        uu, nn = u[sep], n[sep]
        a = np.sqrt(np.abs(nn))
        th = np.tanh(uu)
        with np.errstate(divide="ignore", invalid="ignore"):  # both branches evaluated
            neg = np.where(nn < 0, a * np.arctan(a * th), -a * np.arctanh(a * th))
        out[sep] = (nn * uu + neg) / (1.0 - nn)
    rest = ~sep
    if rest.any():
        uu, nn, mm, qq = u[rest], n[rest], m[rest], m1[rest]
        j, s, snx, cnx, dnx, _ = _reduced(uu, mm, qq)
        tail = _third_kind_tail_reduced(s * snx, cnx, dnx, nn)
        full = np.where(j != 0, _complete_tail(nn, qq), 0.0)
        with np.errstate(over="ignore"):  # |u| near 1e308: the caller raises
            out[rest] = tail + 2.0 * j * full
    return out


# ------------------------------------------------ one argument in Python floats (issue 15)
#
# The same steps as the array functions above, operation for operation, on one float:
# :class:`mechanics.tops.FreeAsymmetricTop` evaluates one instant ~20× faster through
# them (numpy's per-call overhead, not arithmetic, is the cost of one instant).  Only
# 0 ≤ m ≤ 1 with m1 given, as the top needs; ``K`` (``_quarter_period(p1)``) and the
# trigonometric AGM ratios are the caller's, computed once per parameter.


def _agm_ratios_scalar(p: float, p1: float, hyper: bool, ymax: float) -> tuple[float, list[float]]:
    """:func:`_agm_ratios` of one parameter."""
    a = 1.0
    b = math.sqrt(p) if hyper else math.sqrt(p1)
    c = math.sqrt(p1) if hyper else math.sqrt(p)
    ratios = []
    for _ in range(_N_AGM):
        a_new = 0.5 * (a + b)
        b = math.sqrt(a * b)
        c = c * c / (4.0 * a_new)
        a = a_new
        ratios.append(c / a)
        grow = math.exp(min(2.0 ** len(ratios) * a * ymax, 700.0)) if hyper else 1.0
        if ratios[-1] * grow < 2.0**-64:
            break
    return a, ratios


def _asinh_r_sinh_scalar(r: float, psi: float) -> float:
    if psi <= 350.0:
        return math.asinh(r * math.sinh(psi))
    logy = (math.log(r) if r > 0 else -math.inf) + psi - math.log(2.0)
    return logy + math.log(2.0) if logy > 40.0 else math.asinh(math.exp(logy))


def _core_scalar(
    y: float, p: float, p1: float, trig_agm: tuple[float, list[float]] | None
) -> tuple[float, float, float]:
    """:func:`_core` of one argument; ``trig_agm`` the (a, ratios) of p ≤ 1/2."""
    if p <= 0.5:
        a, ratios = trig_agm  # type: ignore[misc]  # the caller gives it whenever p ≤ 1/2
        phi = (2.0 ** len(ratios)) * a * y
        for r in reversed(ratios):
            phi = 0.5 * (phi + math.asin(r * math.sin(phi)))
        s_ = math.sin(phi)
        return s_, math.cos(phi), math.sqrt(1.0 - p * s_ * s_)
    a, ratios = _agm_ratios_scalar(p, p1, True, y)
    phi = (2.0 ** len(ratios)) * a * y
    for r in reversed(ratios):
        phi = 0.5 * (phi + _asinh_r_sinh_scalar(r, phi))
    s_ = math.tanh(phi)
    c_ = 1.0 / math.cosh(phi) if phi < 710.0 else 0.0
    return s_, c_, math.hypot(math.sqrt(p1), math.sqrt(p) * c_)  # see _core


def _reduced_scalar(
    u: float, p: float, p1: float, K: float, trig_agm: tuple[float, list[float]] | None
) -> tuple[float, float, float, float, float]:
    """:func:`_reduced` of one argument: (j, s, snx, cnx, dnx)."""
    finite = math.isfinite(K)
    if finite:
        K2 = 2.0 * K
        j = float(round(u / K2))
        prod, err = _two_prod_or_zero_scalar(j, K2)
        r = (u - prod) - err
    else:
        j, r = 0.0, u
    s = -1.0 if r < 0 else 1.0
    Kf = K if finite else math.inf
    x = min(abs(r), Kf)
    flip = x > 0.5 * Kf
    y = Kf - x if flip else x
    sy, cy, dy = _core_scalar(y, p, p1, trig_agm)
    if flip:
        kp = math.sqrt(p1)
        return j, s, cy / dy, kp * sy / dy, kp / dy
    return j, s, sy, cy, dy


def _ellipj_scalar(
    u: float, p: float, p1: float, K: float, trig_agm: tuple[float, list[float]] | None
) -> tuple[float, float, float]:
    """sn, cn, dn of one argument, 0 ≤ p ≤ 1 (:func:`ellipj`'s middle branch)."""
    j, s, snx, cnx, dnx = _reduced_scalar(u, p, p1, K, trig_agm)
    sign = 1.0 - 2.0 * (j % 2.0)
    return sign * s * snx, sign * cnx, dnx


def _third_kind_excess_scalar(
    u: float,
    n: float,
    p: float,
    p1: float,
    K: float,
    trig_agm: tuple[float, list[float]] | None,
    full: float,
) -> float:
    """:func:`_third_kind_excess` of one argument; ``full`` = _complete_tail(n, p1)."""
    if p1 <= 0:
        a = math.sqrt(abs(n))
        th = math.tanh(u)
        neg = a * math.atan(a * th) if n < 0 else -a * math.atanh(a * th)
        return (n * u + neg) / (1.0 - n)
    j, s, snx, cnx, dnx = _reduced_scalar(u, p, p1, K, trig_agm)
    S = s * snx
    if S == 0 or n == 0:
        tail = 0.0
    else:
        s2 = S * S
        if dnx < _RJ_TINY_ROOT:  # cn², dn² subnormal: see _third_kind_tail_of_roots
            rj = float(_rj_of_roots(cnx, dnx, 1.0, 1.0 - n * s2))
        else:
            rj = _rj_scalar(cnx * cnx, dnx * dnx, 1.0, 1.0 - n * s2)
        tail = (n / 3.0) * s2 * S * rj
    return tail + 2.0 * j * (full if j != 0 else 0.0)
