"""Hypothesis strategies for inertia tensors and rigid bodies, valid by construction.

Conventions
-----------
- The objects are those of :mod:`mechanics.inertia`: principal moments
  ``(3,)`` in ascending order J1 ≤ J2 ≤ J3, inertia tensors ``(3, 3)`` (about
  G, in some basis), and rigid bodies (mass, J_G, position of G).
- **Valid by construction.**  No strategy filters: the moments are drawn as
  J1 ≤ J2, then J3 in [J2, J1 + J2] (the triangle inequality, with the sum
  computed in float64 so that fl(J1 + J2) ≥ J3 holds exactly); a tensor is
  J = Rᵀ diag(J) R for a drawn rotation (:func:`mechanics.inertia.rotate_inertia`,
  exactly symmetric).  Every drawn tensor passes
  :func:`mechanics.inertia.check_inertia`.
- **Hard regimes are explicit branches** (``st.sampled_from``, the simple one
  first so that examples shrink toward a spherical top of scale 1), recorded
  with :func:`hypothesis.event`; the constants ``*_REGIMES`` list them and
  ``tests/strategies/test_inertia_strategy_quality.py`` proves each is reached.
- Bounds are keyword-only; bad arguments raise
  :class:`hypothesis.errors.InvalidArgument` quoting the value.

Examples
--------
>>> from hypothesis import given
>>> from mechanics.inertia import is_physical_inertia
>>> @given(inertia_tensors())
... def test_drawn_tensors_are_physical(J):
...     assert is_physical_inertia(J)
>>> test_drawn_tensors_are_physical()
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import NamedTuple, TypeAlias

import numpy as np
import numpy.typing as npt
from hypothesis import event
from hypothesis import strategies as st
from hypothesis.errors import InvalidArgument

from .. import inertia as _inertia
from ._common import check_positive, check_regimes, log_uniform, memoised
from .rotation import rotation_matrices

_Array: TypeAlias = npt.NDArray[np.float64]

__all__ = [
    "CENTRE_REGIMES",
    "NEAR_DEGENERATE_RANGE",
    "PRINCIPAL_MOMENT_REGIMES",
    "THIN_RANGE",
    "WIDE_SCALE_RANGE",
    "RigidBody",
    "inertia_tensors",
    "principal_moments",
    "rigid_bodies",
]


#: Regimes of :func:`principal_moments`:
#:
#: - ``equal``: J1 = J2 = J3 (a spherical top);
#: - ``general``: J1/J2 in [0.05, 0.999], J3 = J2 + t J1 with t in [0.001, 0.999],
#:   so the gaps and the triangle slack J1 + J2 − J3 are all at least 5e-5 of J3;
#: - ``symmetric``: exactly two moments equal (J1 = J2 or J2 = J3);
#: - ``near-degenerate``: two moments differ by a relative δ in
#:   :data:`NEAR_DEGENERATE_RANGE` (axes ill-determined, subspaces not);
#: - ``flat``: J1 + J2 = J3 exactly in float64 (a plate);
#: - ``near-flat``: J3 = (J1 + J2)(1 − δ), δ in :data:`NEAR_DEGENERATE_RANGE`;
#: - ``thin``: J1/J2 in :data:`THIN_RANGE` (a needle: J2 ≈ J3 ≫ J1);
#: - ``wide-scales``: a general triple times a scale 10**(±e), e uniform in
#:   [20, 100] (:data:`WIDE_SCALE_RANGE`, within the bounds).
PRINCIPAL_MOMENT_REGIMES = (
    "equal",
    "general",
    "symmetric",
    "near-degenerate",
    "flat",
    "near-flat",
    "thin",
    "wide-scales",
)

#: Relative gaps of the near-degenerate regimes: from a few ulps (1e-15), where
#: the two axes are mixed by rounding, to 1e-6, where they are determined to
#: about 1e-10.
NEAR_DEGENERATE_RANGE = (1e-15, 1e-6)

#: J1/J2 of the thin regime: a needle of aspect ratio 1e6 to about 30.
THIN_RANGE = (1e-12, 1e-3)

#: Scales of the wide-scales regime, 1e20 … 1e100 and 1e-100 … 1e-20: far from 1
#: but far from overflow when a tensor is multiplied by ω² ~ 1e±50 or shifted
#: by a distance².
WIDE_SCALE_RANGE = (1e20, 1e100)

_SCALE_RANGE = (1e-2, 1e2)  # the scale of every other regime, within the bounds

#: Regimes of :func:`rigid_bodies` for the centre of mass G: at the origin;
#: ``general`` (|r_G| up to 10 times the body's size); ``far`` (|r_G| 1e6 … 1e10
#: times its size, where a shift (4.38) is dominated by m |r_G|²).
CENTRE_REGIMES = ("origin", "general", "far")


class RigidBody(NamedTuple):
    """A rigid body as drawn by :func:`rigid_bodies`: J_G about G, G at r_G.

    A named tuple: it unpacks as ``m, J_G, r_G``; its constructor checks nothing.

    Parameters
    ----------
    m : float
        The mass (kg), > 0.
    J_G : ndarray, shape (3, 3)
        The inertia tensor about G (kg m²), physical.
    r_G : ndarray, shape (3,)
        The position of G (m).

    Examples
    --------
    Fields by name or by position:

    >>> b = RigidBody(2.0, np.eye(3), np.zeros(3))
    >>> m, J_G, r_G = b
    >>> m == b.m == b[0], J_G is b.J_G
    (True, True)
    """

    m: float
    J_G: npt.NDArray[np.float64]
    r_G: npt.NDArray[np.float64]


def _log_scale(lo: float, hi: float) -> st.SearchStrategy[float]:
    """10**e, e uniform in [log10 lo, log10 hi], shrinking toward 1 (or the nearer bound)."""
    a, b = math.log10(lo), math.log10(hi)
    return st.floats(a, b).map(lambda e: min(hi, max(lo, 10.0**e)))


def _triple(J1: float, J2: float, J3: float) -> _Array:
    """Sorted and valid in float64: J3 is capped at fl(J1 + J2)."""
    J1, J2, J3 = sorted((J1, J2, J3))
    return np.array([J1, J2, min(J3, J1 + J2)])


def principal_moments(
    *,
    min_scale: float = 1e-100,
    max_scale: float = 1e100,
    regimes: Iterable[str] | None = None,
) -> st.SearchStrategy[npt.NDArray[np.float64]]:
    """Principal moments (J1, J2, J3), ascending, with J3 ≤ J1 + J2; shape ``(3,)``.

    The largest moment J3 lies in [``min_scale``, ``max_scale``] (up to a
    factor 2 above); the regimes (:data:`PRINCIPAL_MOMENT_REGIMES`) other than
    ``wide-scales`` draw it near 1 (1e-2 … 1e2 within the bounds).
    ``regimes`` restricts the draw.  Shrinks toward (1, 1, 1).

    Parameters
    ----------
    min_scale, max_scale : float
        Bounds of the largest moment J3 (kg m²), finite, 0 < ``min_scale`` ≤ ``max_scale``.
    regimes : iterable of str, optional
        Some of :data:`PRINCIPAL_MOMENT_REGIMES` (default all).

    Returns
    -------
    SearchStrategy of ndarray, shape (3,)
        float64 moments J1 ≤ J2 ≤ J3 ≤ J1 + J2 (kg m²), > 0.

    Raises
    ------
    InvalidArgument
        A bound not a finite real number > 0, or ``min_scale`` > ``max_scale``;
        ``regimes`` a string, empty or with an unknown name.

    Examples
    --------
    Ascending, and the triangle inequality holds exactly in float64, flat plates included:

    >>> from hypothesis import given, settings
    >>> @settings(max_examples=50, derandomize=True)
    ... @given(principal_moments())
    ... def test_triangle(J):
    ...     assert 0 < J[0] <= J[1] <= J[2] <= J[0] + J[1]
    >>> test_triangle()
    """
    lo = check_positive(min_scale, "min_scale")
    hi = check_positive(max_scale, "max_scale")
    if lo > hi:
        raise InvalidArgument(f"min_scale={min_scale!r} exceeds max_scale={max_scale!r}")
    names = check_regimes(regimes, PRINCIPAL_MOMENT_REGIMES, "principal_moments")
    near = (max(lo, _SCALE_RANGE[0]), min(hi, _SCALE_RANGE[1]))
    if near[0] > near[1]:
        near = (lo, hi)
    big = (max(lo, WIDE_SCALE_RANGE[0]), min(hi, WIDE_SCALE_RANGE[1]))
    small = (max(lo, 1.0 / WIDE_SCALE_RANGE[1]), min(hi, 1.0 / WIDE_SCALE_RANGE[0]))
    wides = [_log_scale(*r) for r in (big, small) if r[0] <= r[1]]
    wide = st.one_of(wides) if wides else _log_scale(lo, hi)
    unit = st.floats(0.0, 1.0)
    ratio = st.floats(0.05, 1.0)  # J1/J2 in the general regimes: gaps well above rounding
    delta = log_uniform(*NEAR_DEGENERATE_RANGE, shrink_to="hi")
    near_scale, thin = _log_scale(*near), log_uniform(*THIN_RANGE, shrink_to="hi")

    @st.composite
    def draw_moments(draw: st.DrawFn) -> _Array:
        regime = draw(st.sampled_from(names))
        event(f"principal_moments: {regime}")
        s = draw(wide if regime == "wide-scales" else near_scale)
        if regime == "equal":
            return np.array([s, s, s])
        J2 = s * draw(st.floats(0.5, 1.0))
        if regime in ("general", "wide-scales"):
            J1 = J2 * draw(st.floats(0.05, 0.999))
            return _triple(J1, J2, J2 + draw(st.floats(0.001, 0.999)) * J1)
        if regime == "symmetric":
            if draw(st.booleans()):  # prolate: J1 ≤ J2 = J3
                return _triple(J2 * draw(ratio), J2, J2)
            return _triple(J2, J2, J2 * (1.0 + draw(unit)))  # oblate: J1 = J2 ≤ J3
        if regime == "near-degenerate":
            d = draw(delta)
            J1 = J2 * draw(ratio)
            if draw(st.booleans()):  # J1 ≈ J2
                return _triple(J2 * (1.0 - d), J2, J2 + draw(unit) * J2 * (1.0 - d))
            return _triple(J1, J2, J2 * (1.0 + d))  # J2 ≈ J3
        if regime == "flat":
            J3 = J2 * draw(ratio) + J2  # rounded: it may exceed the exact sum ...
            J1 = J3 - J2  # ... so J1 is taken back from it, exactly (J2 ≤ J3 ≤ 2 J2)
            return np.array([J1, J2, J3])
        if regime == "near-flat":
            J1 = J2 * draw(ratio)
            return _triple(J1, J2, (J1 + J2) * (1.0 - draw(delta)))
        # thin
        J1 = J2 * draw(thin)
        return _triple(J1, J2, J2 + draw(unit) * J1)

    return draw_moments()


principal_moments = memoised(principal_moments)  # one strategy per arguments (_common.memoised)


def inertia_tensors(
    *,
    moments: st.SearchStrategy[npt.NDArray[np.float64]] | None = None,
    rotations: st.SearchStrategy[npt.NDArray[np.float64]] | None = None,
) -> st.SearchStrategy[npt.NDArray[np.float64]]:
    """Physical inertia tensors J = Rᵀ diag(J1, J2, J3) R, shape ``(3, 3)``, exactly symmetric.

    ``moments`` defaults to :func:`principal_moments` and ``rotations`` to
    :func:`mechanics.strategies.rotation_matrices`, so every regime of both is
    reached (near-degenerate moments in a general basis, flat bodies turned by
    near-π rotations, ...).  Shrinks toward the unit tensor.

    Parameters
    ----------
    moments : SearchStrategy, optional
        Principal moments of shape (3,) (default :func:`principal_moments`).
    rotations : SearchStrategy, optional
        Rotation matrices of shape (3, 3) (default
        :func:`mechanics.strategies.rotation_matrices`).

    Returns
    -------
    SearchStrategy of ndarray, shape (3, 3)
        float64 inertia tensors (kg m²) that pass :func:`mechanics.inertia.check_inertia`.

    Raises
    ------
    InvalidArgument
        ``moments`` or ``rotations`` not a hypothesis strategy.

    Examples
    --------
    The trace is the sum of the moments in any basis, and the tensor is exactly symmetric:

    >>> from hypothesis import given, settings
    >>> @settings(max_examples=30, derandomize=True)
    ... @given(inertia_tensors(moments=st.just(np.array([1.0, 2.0, 2.5]))))
    ... def test_trace(J):
    ...     assert (J == J.T).all() and abs(np.trace(J) - 5.5) <= 1e-14
    >>> test_trace()
    """
    moments = principal_moments() if moments is None else moments
    rotations = rotation_matrices() if rotations is None else rotations
    for name, s in (("moments", moments), ("rotations", rotations)):
        if not isinstance(s, st.SearchStrategy):
            raise InvalidArgument(f"{name}={s!r} must be a hypothesis strategy")
    return st.tuples(moments, rotations).map(lambda t: _inertia.rotate_inertia(np.diag(t[0]), t[1]))


inertia_tensors = memoised(inertia_tensors)  # one strategy per arguments (_common.memoised)


def rigid_bodies(
    *,
    min_mass: float = 1e-3,
    max_mass: float = 1e3,
    tensors: st.SearchStrategy[npt.NDArray[np.float64]] | None = None,
    regimes: Iterable[str] | None = None,
) -> st.SearchStrategy[RigidBody]:
    """Rigid bodies: mass m, inertia tensor J_G about G, and the position r_G of G.

    The mass is log-uniform in [``min_mass``, ``max_mass``] (shrinking toward
    1), ``tensors`` defaults to :func:`inertia_tensors` (so J_G is independent
    of m: any tensor is realised by some mass distribution of any mass,
    Example 4.1), and r_G follows the regimes :data:`CENTRE_REGIMES`, measured
    in the body's size √(J3/m).

    Parameters
    ----------
    min_mass, max_mass : float
        Bounds of the mass (kg), finite, 0 < ``min_mass`` ≤ ``max_mass``.
    tensors : SearchStrategy, optional
        Inertia tensors J_G of shape (3, 3) (default :func:`inertia_tensors`).
    regimes : iterable of str, optional
        Some of :data:`CENTRE_REGIMES` (default all).

    Returns
    -------
    SearchStrategy of RigidBody
        :class:`RigidBody` records (m, J_G, r_G).

    Raises
    ------
    InvalidArgument
        A bound not a finite real number > 0, or ``min_mass`` > ``max_mass``; ``tensors``
        not a hypothesis strategy; ``regimes`` a string, empty or with an unknown name.

    Examples
    --------
    >>> from hypothesis import given, settings
    >>> @settings(max_examples=30, derandomize=True)
    ... @given(rigid_bodies(min_mass=1.0, max_mass=2.0, regimes=["origin"]))
    ... def test_body(b):
    ...     assert 1.0 <= b.m <= 2.0 and b.r_G.tolist() == [0.0, 0.0, 0.0]
    >>> test_body()
    """
    lo = check_positive(min_mass, "min_mass")
    hi = check_positive(max_mass, "max_mass")
    if lo > hi:
        raise InvalidArgument(f"min_mass={min_mass!r} exceeds max_mass={max_mass!r}")
    tensors = inertia_tensors() if tensors is None else tensors
    if not isinstance(tensors, st.SearchStrategy):
        raise InvalidArgument(f"tensors={tensors!r} must be a hypothesis strategy")
    names = check_regimes(regimes, CENTRE_REGIMES, "rigid_bodies")
    direction = st.tuples(st.floats(-1.0, 1.0), st.floats(-math.pi, math.pi))
    mass, far = _log_scale(lo, hi), log_uniform(1e6, 1e10, shrink_to="hi")

    @st.composite
    def draw_body(draw: st.DrawFn) -> RigidBody:
        m = draw(mass)
        J = draw(tensors)
        regime = draw(st.sampled_from(names))
        event(f"rigid_bodies: {regime}")
        if regime == "origin":
            return RigidBody(m, J, np.zeros(3))
        size = math.sqrt(float(np.trace(J)) / (2.0 * m))
        dist = size * (draw(st.floats(0.0, 10.0)) if regime == "general" else draw(far))
        z, az = draw(direction)
        rho = math.sqrt((1.0 - z) * (1.0 + z))
        return RigidBody(m, J, dist * np.array([rho * math.cos(az), rho * math.sin(az), z]))

    return draw_body()


rigid_bodies = memoised(rigid_bodies)  # one strategy per arguments (_common.memoised)
