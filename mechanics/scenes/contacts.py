"""Contact detection for scenes: when does a gap between two bodies close?

A contact is missed only by a bug, never by the step size: where the relative motion is
a polynomial in time (free flight, uniform gravity) the contact time is the smallest
root of a polynomial, solved in closed form; inside an integrator step the state is the
step's dense-output polynomial, and the squared gap along it is searched for its first
downward crossing by isolating every extremum (roots of the derivative), so a dip below
zero is found whatever the length of the step.

Conventions
-----------
- A *gap* is signed: positive apart, zero touching, negative interpenetrating.
  Sphere–sphere: ``|r_i − r_j| − (a_i + a_j)``; sphere–plane: ``(r_i − p)·n − a_i``.
- A contact is an instant where the gap reaches zero while *closing* (the normal
  relative velocity points inward).  A zero reached while opening is the exit side of
  an interpenetration: that is reported as :class:`ContactError`, never as an impact.
- Times are measured from the start of the current flight (τ ≥ 0).  A gap that is
  already zero and closing at τ = 0 is a contact at τ = 0 (touching at the start).

References
----------
Essén (1996), Section 6.2: the impact is instantaneous; between impacts the bodies fly
freely (Chapter 1).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
import numpy.typing as npt
from numpy.polynomial import chebyshev as C

from .._floats import EPS
from .vectors import FloatArray

__all__ = [
    "ContactError",
    "chebyshev_fit",
    "first_downward_crossing",
    "plane_contact_time",
    "plane_contact_times",
    "quadratic_roots",
    "sphere_contact_time",
    "sphere_contact_times",
]


#: Chebyshev nodes per step for the positions: the dense output of DOP853 is a degree-7
#: polynomial per step (RK45's degree 4); 9 nodes interpolate up to degree 8 exactly.
STEP_NODES = 9
#: a root of the derivative counts as real when its imaginary part is below this (in the
#: step's [−1, 1] variable): eigenvalues of a companion matrix carry ~ sqrt(eps) errors
#: near a double root, so real extrema are never dropped; complex ones only add a probe
REAL_ROOT_IMAG = 64 * math.sqrt(EPS)  # ≈ 9.5e-7
#: tail Chebyshev coefficients below this fraction of Σ|c_k| are the interpolation's
#: rounding (a fit of degree 8 to a degree-7 step); dropping them changes the values by
#: less than that and keeps the companion matrix of the derivative well scaled
TRIM_RTOL = 16 * EPS
#: root refinement: brentq's smallest relative tolerance (4 eps, scipy's floor)
ROOT_RTOL = 4 * EPS


class ContactError(ValueError):
    """A contact that cannot be resolved: found on the exit side, or bodies overlapping."""


def quadratic_roots(a: float, b: float, c: float) -> list[float]:
    """Real roots of a x² + b x + c, sorted, formed without cancellation.

    q = −½ (b + sign(b) √(b² − 4ac)) gives the roots q/a and c/q, neither the difference
    of nearly equal numbers; a = 0 gives the line's root −c/b (none where b = 0 too).

    Parameters
    ----------
    a, b, c : float
        The coefficients (a double root is returned once).

    Returns
    -------
    list of float
        The real roots in increasing order: none, one or two (NaN where an input is).

    Examples
    --------
    The roots of (x − 1)(x − 2) = x² − 3x + 2, and their product c/a:

    >>> quadratic_roots(1.0, -3.0, 2.0)
    [1.0, 2.0]
    >>> x1, x2 = quadratic_roots(2.0, -6.0, 4.0)
    >>> x1 * x2 == 4.0 / 2.0
    True
    >>> quadratic_roots(1.0, 0.0, 1.0)
    []
    """
    if a == 0:
        return [-c / b] if b != 0 else []
    disc = b * b - 4 * a * c
    if disc < 0:
        return []
    q = -0.5 * (b + math.copysign(math.sqrt(disc), b))
    return sorted([q / a, c / q] if q != 0 else [0.0])


def plane_contact_time(gap: float, v_n: float, a_n: float) -> float:
    """First τ ≥ 0 at which ``gap + v_n τ + ½ a_n τ²`` reaches zero while closing.

    :func:`plane_contact_times` for one pair.

    Parameters
    ----------
    gap : float
        The signed gap at τ = 0, m (positive apart).
    v_n : float
        The normal velocity, m/s (positive away from the plane).
    a_n : float
        The normal acceleration, m/s² (positive away from the plane).

    Returns
    -------
    float
        The contact time τ, s, from the start of the flight; ``inf`` when the gap never
        closes.

    Raises
    ------
    TypeError
        If an input is an array of more than one element (use
        :func:`plane_contact_times`).
    ValueError
        If an input is not numeric.

    Examples
    --------
    A ball 1 m above the floor falling from rest at g = 9.8125 m/s² lands when
    ½ g τ² = 1:

    >>> tau = plane_contact_time(1.0, 0.0, -9.8125)
    >>> bool(np.isclose(tau, (2.0 / 9.8125) ** 0.5, rtol=EPS))
    True
    >>> plane_contact_time(1.0, -2.0, 0.0), plane_contact_time(1.0, 2.0, 0.0)
    (0.5, inf)
    """
    return float(plane_contact_times(np.array([gap]), np.array([v_n]), np.array([a_n]))[0])


def plane_contact_times(gap: npt.ArrayLike, v_n: npt.ArrayLike, a_n: npt.ArrayLike) -> FloatArray:
    """:func:`plane_contact_time` for arrays of pairs at once (the same arithmetic, per element).

    The roots of ½ a_n τ² + v_n τ + gap formed as in :func:`quadratic_roots`; the first
    τ ≥ 0 where the normal velocity v_n + a_n τ closes (< 0).

    Parameters
    ----------
    gap : array_like, shape (k,)
        The signed gaps at τ = 0, m (positive apart).
    v_n : array_like, shape (k,)
        The normal velocities, m/s (positive away from the plane).
    a_n : array_like, shape (k,)
        The normal accelerations, m/s² (positive away from the plane).

    Returns
    -------
    ndarray, shape (k,)
        The contact times τ, s; ``inf`` where the gap never closes.  (Any shapes that
        broadcast together are taken: the result has the shape of ``gap``.)

    Raises
    ------
    ValueError
        If the shapes do not broadcast together, or an input is not numeric.

    Examples
    --------
    Each element as :func:`plane_contact_time` gives it:

    >>> plane_contact_times(np.array([1.0, 1.0]), np.array([-2.0, 2.0]), np.zeros(2))
    array([0.5, inf])
    >>> taus = plane_contact_times([1.0, 2.0], [0.0, -1.0], [-2.0, -2.0])
    >>> taus.tolist() == [plane_contact_time(1.0, 0.0, -2.0), plane_contact_time(2.0, -1.0, -2.0)]
    True
    """
    gap, v_n, a_n = (np.asarray(x, dtype=float) for x in (gap, v_n, a_n))
    a = 0.5 * a_n
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):  # ±inf: no root
        disc = v_n * v_n - 4 * a * gap
        q = -0.5 * (v_n + np.copysign(np.sqrt(np.maximum(disc, 0.0)), v_n))
        quad = (a != 0) & (disc >= 0)
        # a quadratic's roots q/a and gap/q (one root 0 where q = 0); a line's −gap/v_n
        r1 = np.where(quad, np.where(q != 0, q / a, 0.0), np.where(v_n != 0, -gap / v_n, np.nan))
        r2 = np.where(quad & (q != 0), gap / q, np.nan)
        r1 = np.where((a != 0) & ~quad, np.nan, r1)
    best = np.full(np.shape(gap), math.inf)
    for tau in (r1, r2):
        ok = (tau >= 0) & (v_n + a_n * tau < 0)
        best = np.where(ok & (tau < best), tau, best)
    return best


def sphere_contact_time(d: npt.ArrayLike, w: npt.ArrayLike, size: float) -> float:
    """First τ ≥ 0 at which two spheres in uniform relative motion touch while closing.

    The relative acceleration is zero (free flight, or the same uniform gravity on both).

    Parameters
    ----------
    d : array_like, shape (3,)
        The line of centres r_i − r_j, m.
    w : array_like, shape (3,)
        The relative velocity v_i − v_j, m/s.
    size : float
        The sum of the radii, m (≥ 0).

    Returns
    -------
    float
        The contact time τ, s; ``inf`` when the spheres never touch (they separate, they
        miss, or they only graze: zero normal speed at the touch); 0 for a pair that
        already touches or overlaps while closing.

    Raises
    ------
    IndexError
        If ``d`` or ``w`` has fewer than 3 components (components beyond the third are
        not read).
    ValueError
        If ``d``, ``w`` or ``size`` is not numeric.

    Notes
    -----
    The contact solves |d + w τ|² = s², i.e. |w|² τ² + 2 (d·w) τ + (|d|² − s²) = 0.
    Both the discriminant and the constant term are formed without cancellation: by
    Lagrange's identity (d·w)² − |w|²(|d|² − s²) = (|w| s − |d × w|)(|w| s + |d × w|),
    the impact parameter |d × w|/|w| against s; and |d|² − s² = gap (|d| + s).  The entry
    root is then c / (−d·w + √disc), free of the difference of nearly equal numbers
    that the textbook formula takes when the spheres are far apart or nearly touching.

    Examples
    --------
    >>> sphere_contact_time(np.array([-0.5, 0, 0]), np.array([1.0, 0, 0]), 0.2)
    0.3
    >>> sphere_contact_time(np.array([-0.5, 0.3, 0]), np.array([1.0, 0, 0]), 0.2)  # miss
    inf
    """
    d, w = np.asarray(d, dtype=float), np.asarray(w, dtype=float)
    return float(sphere_contact_times(d[None], w[None], np.array([size]))[0])


def sphere_contact_times(d: npt.ArrayLike, w: npt.ArrayLike, size: npt.ArrayLike) -> FloatArray:
    """:func:`sphere_contact_time` for arrays of pairs at once (the same arithmetic per pair).

    Parameters
    ----------
    d : array_like, shape (k, 3)
        The lines of centres r_i − r_j, m.
    w : array_like, shape (k, 3)
        The relative velocities v_i − v_j, m/s.
    size : array_like, shape (k,)
        The sums of the radii, m (≥ 0).

    Returns
    -------
    ndarray, shape (k,)
        The contact times τ, s; ``inf`` where a pair never touches.

    Raises
    ------
    IndexError
        If ``d`` or ``w`` is not 2-D with at least 3 columns.
    ValueError
        If the pairs' counts do not broadcast together, or an input is not numeric.

    Examples
    --------
    Head on, closing at 1 m/s from 0.5 m apart with radii summing to 0.2 m: 0.3 s; the
    same pair 0.3 m off the line of approach misses:

    >>> sphere_contact_times(np.array([[-0.5, 0, 0], [-0.5, 0.3, 0]]),
    ...                      np.array([[1.0, 0, 0], [1.0, 0, 0]]), np.array([0.2, 0.2]))
    array([0.3, inf])
    """
    d, w, size = np.asarray(d, float), np.asarray(w, float), np.asarray(size, float)
    dw = d[:, 0] * w[:, 0] + d[:, 1] * w[:, 1] + d[:, 2] * w[:, 2]
    dist = np.sqrt(d[:, 0] ** 2 + d[:, 1] ** 2 + d[:, 2] ** 2)
    ws = np.sqrt(w[:, 0] ** 2 + w[:, 1] ** 2 + w[:, 2] ** 2) * size
    x = d[:, 1] * w[:, 2] - d[:, 2] * w[:, 1]
    y = d[:, 2] * w[:, 0] - d[:, 0] * w[:, 2]
    z = d[:, 0] * w[:, 1] - d[:, 1] * w[:, 0]
    cross = np.sqrt(x * x + y * y + z * z)
    # separating or moving tangentially (d·w ≥ 0), or an impact parameter of at least the
    # sum of radii: never; else the entry root (a pair touching within rounding: now)
    hit = (dw < 0) & (cross < ws)
    disc = (ws - cross) * (ws + cross)
    c = (dist - size) * (dist + size)
    with np.errstate(divide="ignore", invalid="ignore"):
        tau = np.maximum(c / (-dw + np.sqrt(np.where(hit, disc, 1.0))), 0.0)
    return np.where(hit, tau, math.inf)


def chebyshev_fit(
    fn: Callable[[FloatArray], npt.ArrayLike],
    t_a: float,
    t_b: float,
    n: int = STEP_NODES,
    *,
    ends: bool = False,
) -> FloatArray:
    """Chebyshev coefficients on [t_a, t_b] interpolating ``fn(t)``, exact for degree < n.

    The variable is x ∈ [−1, 1], t = ½ (t_a + t_b) + ½ (t_b − t_a) x. At the Chebyshev
    points of the first kind (interior); with ``ends``, at the Chebyshev–Lobatto points
    cos(πk/(n − 1)), which include both ends: a fit of a function that is not a polynomial
    along the step (a point of a turning hinge, a support point, a switch function) then
    equals it at the step's ends, where one step hands over to the next (a crossing at the
    very end is not lost to the fit's error).

    Parameters
    ----------
    fn : callable
        ``fn(t)`` with ``t`` of shape ``(n,)``, s, returning an array of shape ``(n, m)``:
        the m functions sampled at the n times.
    t_a, t_b : float
        The step's ends, s.
    n : int, optional
        The number of nodes (≥ 2), default ``STEP_NODES`` = 9: coefficients up to
        degree n − 1.
    ends : bool, optional
        Chebyshev–Lobatto points (both ends included) instead of the interior points of
        the first kind (default False).

    Returns
    -------
    ndarray, shape (n, m)
        The coefficients, row k those of T_k(x).

    Raises
    ------
    TypeError
        If ``fn`` returns other than n rows.
    ValueError
        If ``n`` < 1.

    Examples
    --------
    t² on [0, 2] at its middle t = 1 (x = 0), and sin at the end t = 2 (x = 1) of a fit
    with ``ends``:

    >>> c = chebyshev_fit(lambda t: np.stack([t * t], axis=-1), 0.0, 2.0)
    >>> bool(np.allclose(C.chebval(0.0, c[:, 0]), 1.0, rtol=0, atol=8 * EPS))
    True
    >>> c = chebyshev_fit(lambda t: np.stack([np.sin(t)], axis=-1), 0.0, 2.0, ends=True)
    >>> bool(abs(C.chebval(1.0, c[:, 0]) - np.sin(2.0)) <= 8 * EPS)
    True
    """
    k = np.arange(n)
    x = np.cos(np.pi * k / (n - 1)) if ends else np.cos(np.pi * (k + 0.5) / n)
    t = 0.5 * (t_a + t_b) + 0.5 * (t_b - t_a) * x
    return C.chebfit(x, np.asarray(fn(t), dtype=float), n - 1)


def first_downward_crossing(
    coef: FloatArray,
    *,
    start_tol: float,
    refine: Callable[[float], float] | None = None,
    after: float | None = None,
) -> float | None:
    """First x in [−1, 1] where the Chebyshev series ``coef`` goes below zero.

    ``coef`` is a polynomial with the sign of a gap along one step. The polynomial's extrema
    (real roots of its derivative) cut [−1, 1] into pieces on which it is monotone; the
    first piece that starts ≥ 0 and ends < 0 holds the crossing, refined by Brent's method
    to ``ROOT_RTOL``: on ``refine(x)`` (the gap itself, free of the polynomial's
    cancellation) when given and when its signs at the ends of the piece bracket a root,
    else on the polynomial. A value within ±``start_tol`` counts as touching (the rounding
    of a contact just resolved): the contact is *now* (the piece's start) if the polynomial
    falls from there, nothing if it rises; an interior minimum below zero by no more than
    ``start_tol`` is a graze (a tangential touch whose rounding dips below zero), not a
    contact. Returns None when the polynomial stays ≥ 0; a cheap bound c₀ − Σ|c_k| > 0 skips
    most steps without finding roots.

    With ``after`` (a point of the step where the gap is within rounding of zero but
    the pair does not approach: a touch, at the top of a tiny hop), only x > ``after``
    is searched, and only a fall below ``−start_tol`` counts: its zero crossing (or
    ``after`` itself if the gap is already below zero there) is the contact.

    Parameters
    ----------
    coef : array_like, shape (k,)
        The Chebyshev coefficients of the gap (or of a polynomial with its sign) in the
        step's variable x ∈ [−1, 1].
    start_tol : float
        The rounding of a gap at zero (≥ 0), in the polynomial's units: values within
        ±``start_tol`` count as touching.
    refine : callable, optional
        ``refine(x)``: the exact gap at x, to refine the crossing on (default None: the
        polynomial).
    after : float, optional
        A point of a touch in [−1, 1]: search only beyond it (default None: the whole
        step).

    Returns
    -------
    float or None
        The x of the contact in [−1, 1], or None where the gap stays ≥ 0 (or dips
        below zero within ``start_tol`` only).

    Raises
    ------
    ContactError
        The polynomial starts below ``−start_tol``: the bodies already interpenetrate,
        so a contact was missed before this step (a bug, never silently passed over).

    Examples
    --------
    A dip between two ends that are both positive (x² − 1/4 on [−1, 1] starts and ends
    at 3/4): sampling the ends sees nothing, the extremum at x = 0 finds the crossing.

    >>> coef = C.poly2cheb([-0.25, 0.0, 1.0])          # x² − 1/4: starts at 3/4
    >>> round(first_downward_crossing(coef, start_tol=0.0), 12)
    -0.5
    >>> first_downward_crossing(C.poly2cheb([0.1, 0.0, 1.0]), start_tol=0.0) is None
    True
    """
    coef = np.asarray(coef, dtype=float)
    size = np.abs(coef).sum()
    keep = np.nonzero(np.abs(coef) > TRIM_RTOL * size)[0]
    coef = coef[: keep[-1] + 1] if keep.size else coef[:1]
    if coef[0] - np.abs(coef[1:]).sum() > 0:
        return None
    cand = {-1.0, 1.0}
    if coef.size > 2:
        for r in C.chebroots(C.chebder(coef)):
            if abs(r.imag) <= REAL_ROOT_IMAG and -1.0 < r.real < 1.0:
                cand.add(float(r.real))
    if after is not None:
        cand = {x for x in cand if x > after} | {after}
    xs = sorted(cand)
    vals = C.chebval(np.array(xs), coef)
    if after is None and vals[0] < -start_tol:
        raise ContactError(f"the gap is already {vals[0]:.3g} < 0 at the start of the step")
    for k in range(len(xs) - 1):
        v0, v1 = vals[k], vals[k + 1]
        if after is not None:
            if not v1 < -start_tol:
                continue  # no fall beyond the rounding in this piece
            return _strict_root(coef, refine, xs[k], xs[k + 1])
        if v0 <= start_tol and v1 < v0:
            return xs[k]  # touching within rounding, and closing: the contact is now
        if v0 >= 0 > v1:
            if after is None and v1 >= -start_tol and xs[k + 1] < 1.0:
                continue  # a graze: a dip below zero within rounding, rising again
            from scipy.optimize import brentq

            f: Callable[[float], float | np.floating[Any]] = lambda x: C.chebval(x, coef)  # noqa: E731
            if refine is not None and refine(xs[k]) >= 0 > refine(xs[k + 1]):
                f = refine
            return float(brentq(f, xs[k], xs[k + 1], xtol=ROOT_RTOL, rtol=ROOT_RTOL))
    return None


def _strict_root(
    coef: FloatArray, refine: Callable[[float], float] | None, lo: float, hi: float
) -> float:
    """The first zero of the gap in (lo, hi] after a touch at lo, where the gap at hi is
    below zero beyond rounding: the gap first rises (a hop whose peak may lie closer to
    lo than any extremum the roots resolve), so a point of positive gap is sought at
    lo + (hi − lo) 2^−j; none means the gap never left zero: the contact is lo."""
    from scipy.optimize import brentq

    f: Callable[[float], float | np.floating[Any]] = (
        refine if refine is not None else (lambda x: C.chebval(x, coef))
    )
    if f(hi) >= 0:
        f = lambda x: C.chebval(x, coef)  # noqa: E731
    x_pos = lo if f(lo) > 0 else None
    j = 1
    while x_pos is None and j <= 60:
        x = lo + (hi - lo) * 2.0**-j
        if x <= lo:
            break
        if f(x) > 0:
            x_pos = x
        j += 1
    if x_pos is None:
        return lo
    return float(brentq(f, x_pos, hi, xtol=ROOT_RTOL, rtol=ROOT_RTOL))
