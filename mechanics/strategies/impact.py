"""Hypothesis strategies for impact, valid by construction, with the hard regimes.

Conventions
-----------
- The objects are those of :mod:`mechanics.impact`: masses (floats > 0),
  coefficients of restitution e ∈ [0, 1], unit contact normals ``(3,)``, velocity pairs
  (ẋ_1, ẋ_2) that approach (ẋ_1 ≥ ẋ_2: body 1 is behind body 2 on the X axis),
  inertia tensors ``(3, 3)``, :class:`~mechanics.impact.RigidBody` records and
  whole contacts (:class:`Contact`) whose contact points approach.
- **Valid by construction.**  No strategy filters: an inertia tensor is built
  from principal moments J1 ≤ J2 and J3 ∈ [J2 − J1, J1 + J2] turned by a drawn
  rotation; an approaching contact gets body 1's velocity shifted along n so
  that its normal relative velocity is minus a drawn approach speed.
- **Hard regimes are explicit branches**, drawn first with ``st.sampled_from``
  (the first regime is the simple one, so failures shrink toward unit masses,
  e = 0, spheres, axes), recorded with :func:`hypothesis.event`, listed in the
  ``*_REGIMES`` constants; ``tests/strategies/test_impact_strategy_quality.py``
  proves every one is reached.
- Bounds are keyword-only; bad arguments raise
  :class:`hypothesis.errors.InvalidArgument` quoting the value.

Importing this module imports hypothesis; ``import mechanics`` does not.

Examples
--------
The momentum m v of tiny masses at tiny speeds can fall below the normal range
(5e-67 kg at 1e-250 m/s), where a float rounds to an absolute 2⁻¹⁰⁷⁴ ≈ 5e-324, not
relative to its size: the bound allows both.

>>> import math
>>> from hypothesis import given
>>> from mechanics.impact import direct_impact
>>> @given(mass_pairs(), direct_velocities(), restitution_coefficients())
... def test_momentum_is_conserved(masses, velocities, e):
...     (m1, m2), (v1, v2) = masses, velocities
...     v1f, v2f = direct_impact(m1, m2, v1, v2, e)
...     scale = abs(m1 * v1) + abs(m2 * v2)
...     bound = 16 * 2.3e-16 * scale + 8 * math.ulp(0.0)
...     assert abs((m1 * v1f + m2 * v2f) - (m1 * v1 + m2 * v2)) <= bound
>>> test_momentum_is_conserved()
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

from .. import rotation as _rot
from ..impact import RigidBody
from ._common import check_real, check_regimes, log_uniform, memoised
from .rotation import rotation_matrices, unit_vectors

_Array: TypeAlias = npt.NDArray[np.float64]

__all__ = [
    "CONTACT_REGIMES",
    "DIRECT_VELOCITY_REGIMES",
    "HINGED_REGIMES",
    "IMPACT_INERTIA_REGIMES",
    "IMPACT_MASS_REGIMES",
    "MASS_PAIR_REGIMES",
    "RESTITUTION_REGIMES",
    "Contact",
    "HingedBody",
    "contact_normals",
    "contacts",
    "direct_velocities",
    "hinged_bodies",
    "impact_bodies",
    "impact_inertia_tensors",
    "impact_masses",
    "mass_pairs",
    "restitution_coefficients",
]

#: Regimes of :func:`impact_masses`: exactly 1; log-uniform in [1e-3, 1e3]; tiny
#: (log-uniform from the lower bound up to 1e-6); huge (from 1e6 up to the
#: upper bound).
IMPACT_MASS_REGIMES = ("unit", "generic", "tiny", "huge")

#: Regimes of :func:`mass_pairs` (m_1, m_2): equal (both 1); generic (each
#: log-uniform in [1e-3, 1e3]); body 1 light (m_1/m_2 log-uniform in
#: [1/max_ratio, 1e-6]); body 1 heavy (m_1/m_2 in [1e6, max_ratio]).  The
#: extreme ratios are where m_1 m_2/(m_1 + m_2) and the mass fractions lose
#: digits or overflow when written naively; scaled (a generic pair times a common
#: factor log-uniform in 1e-150 … 1e150: masses far from 1, the internal scaling
#: must follow both, while m v² still fits in float64 for speeds up to 1e6).
MASS_PAIR_REGIMES = ("equal", "generic", "light-1", "heavy-1", "scaled")

_MASS_SCALES = (1e-150, 1e150)

#: Regimes of :func:`restitution_coefficients`: e = 0 (plastic), e = 1
#: (elastic), interior (uniform in [0, 1]), near 0 (log-uniform 1e-15 … 1e-6),
#: near 1 (1 − δ, δ log-uniform from one ulp below 1 to 1e-6; 1 − e² = (1 − e)
#: (1 + e) cancels there when written as 1 − e*e).
RESTITUTION_REGIMES = ("zero", "one", "interior", "near-zero", "near-one")

#: Regimes of :func:`direct_velocities` (ẋ_1, ẋ_2), ẋ_1 ≥ ẋ_2: head-on
#: (opposite signs); chase (same sign); body 2 at rest; a relative velocity
#: 1e-12 … 1e-6 of the velocities themselves (Δẋ cancels); mixed magnitudes
#: (|ẋ_1| and |ẋ_2| drawn independently from the tiers 0, 1e-250 … 1e-100,
#: 1e-3 … min(1e3, ``max_speed``/2) and the top ten decades below ``max_speed``/2,
#: head-on or chase: with ``max_speed`` = 1e302 they span the float range, and a
#: scaling that follows only one of them overflows).  The tiny tier stops at 1e-250 so that the
#: velocities after, down to 1e-15 of it, are normal numbers.
DIRECT_VELOCITY_REGIMES = ("head-on", "chase", "at-rest", "small-relative", "mixed-magnitude")

#: Regimes of :func:`impact_inertia_tensors` (principal moments J1 ≤ J2, J3): a sphere
#: (J1 = J2 = J3); symmetric (J1 = J2 ≠ J3, a top); general; a flat lamina
#: (J3 = J1 + J2 exactly, the triangle inequality's edge); near-degenerate
#: (J2/J1 − 1 in 1e-12 … 1e-6); elongated (J1/J2 in 1e-6 … 1e-2, J3 ≈ J2: a
#: rod, condition number up to 1e6).  Each is turned by a drawn rotation.
IMPACT_INERTIA_REGIMES = (
    "sphere",
    "symmetric",
    "general",
    "lamina",
    "near-degenerate",
    "elongated",
)

#: Regimes of :func:`contacts`: a body against a fixed body 2; two free bodies;
#: central (both centres of mass on the normal through S: the arms are
#: parallel to n); planar (every vector in the XY plane, e_z a principal axis);
#: extreme mass ratio of the two bodies (1e6 … 1e12 either way).
CONTACT_REGIMES = ("fixed-body-2", "free-free", "central", "planar", "mass-ratio")

#: Regimes of :func:`hinged_bodies`: planar (axis e_z through the origin, G in
#: the XY plane, e_z principal axis of J_G) and general (any axis, point, body).
HINGED_REGIMES = ("planar", "general")

_SIGNS = st.sampled_from((1.0, -1.0))


class Contact(NamedTuple):
    """A drawn contact: two bodies, the contact point, the normal into body 1 and e.

    A named tuple, as :func:`contacts` draws it; its constructor checks nothing.

    Parameters
    ----------
    body_1 : RigidBody
        The body the normal points into (:class:`mechanics.impact.RigidBody`).
    body_2 : RigidBody or None
        The other body; ``None``: fixed (infinite mass).
    r_S : ndarray, shape (3,)
        The contact point S (m).
    n : ndarray, shape (3,)
        The unit normal at S, into body 1.
    e : float
        The coefficient of restitution, in [0, 1].

    Examples
    --------
    >>> Contact._fields
    ('body_1', 'body_2', 'r_S', 'n', 'e')
    """

    body_1: RigidBody
    body_2: RigidBody | None
    r_S: npt.NDArray[np.float64]
    n: npt.NDArray[np.float64]
    e: float


class HingedBody(NamedTuple):
    """A drawn hinged body: mass, J_A, r_G, the axis point and unit axis, and J_G.

    Mass, inertia tensor about the axis point, position of G, the axis point and unit
    axis, as :func:`mechanics.impact.hinged_impact` takes them; ``J_G`` is the tensor
    about G it was built from.  A named tuple, as :func:`hinged_bodies` draws it; its
    constructor checks nothing.

    Parameters
    ----------
    m : float
        The mass (kg), > 0.
    J_A : ndarray, shape (3, 3)
        The inertia tensor about the axis point A (kg m²).
    r_G : ndarray, shape (3,)
        The position of G (m).
    axis_point : ndarray, shape (3,)
        A point A of the fixed axis (m).
    axis : ndarray, shape (3,)
        The unit vector along the axis.
    J_G : ndarray, shape (3, 3)
        The inertia tensor about G (kg m²).

    Examples
    --------
    The first five fields are :func:`~mechanics.impact.hinged_impact`'s first five
    parameters:

    >>> import inspect
    >>> from mechanics.impact import hinged_impact
    >>> list(HingedBody._fields[:5]) == list(inspect.signature(hinged_impact).parameters)[:5]
    True
    """

    m: float
    J_A: npt.NDArray[np.float64]
    r_G: npt.NDArray[np.float64]
    axis_point: npt.NDArray[np.float64]
    axis: npt.NDArray[np.float64]
    J_G: npt.NDArray[np.float64]


# ------------------------------------------------------------------ scalars


def impact_masses(
    *, min_value: float = 1e-15, max_value: float = 1e15, regimes: Iterable[str] | None = None
) -> st.SearchStrategy[float]:
    """Masses > 0 in [``min_value``, ``max_value``] (defaults 1e-15 … 1e15).

    Regimes (:data:`IMPACT_MASS_REGIMES`), each used when it meets the bounds.
    Shrinks toward 1 (or the nearest bound).

    Parameters
    ----------
    min_value, max_value : float
        The bounds (kg), finite, 0 < ``min_value`` ≤ ``max_value``.
    regimes : iterable of str, optional
        Some of :data:`IMPACT_MASS_REGIMES` (default all); those that cannot meet the
        bounds are left out.

    Returns
    -------
    SearchStrategy of float
        Masses (kg) in [``min_value``, ``max_value``].

    Raises
    ------
    InvalidArgument
        A bound not a finite real number, ``min_value`` ≤ 0 or ``min_value`` >
        ``max_value``; ``regimes`` a string, empty, with an unknown name, or with none
        reachable in the bounds.

    Examples
    --------
    >>> from hypothesis import given, settings
    >>> @settings(max_examples=30, derandomize=True)
    ... @given(impact_masses(regimes=["tiny"]))
    ... def test_tiny(m):
    ...     assert 1e-15 <= m <= 1e-6
    >>> test_tiny()
    """
    lo = check_real(min_value, "min_value")
    hi = check_real(max_value, "max_value")
    if lo <= 0:
        raise InvalidArgument(f"min_value={min_value!r} must be > 0")
    if lo > hi:
        raise InvalidArgument(f"min_value={min_value!r} exceeds max_value={max_value!r}")
    wanted = check_regimes(regimes, IMPACT_MASS_REGIMES, "impact_masses")
    spans = {
        "unit": (max(lo, 1.0), min(hi, 1.0)),
        "generic": (max(lo, 1e-3), min(hi, 1e3)),
        "tiny": (lo, min(hi, 1e-6)),
        "huge": (max(lo, 1e6), hi),
    }
    names = tuple(r for r in wanted if spans[r][0] <= spans[r][1])
    if not names:
        raise InvalidArgument(
            f"regimes={regimes!r}: none reachable in [{min_value!r}, {max_value!r}]"
        )

    branches = {r: log_uniform(*spans[r], shrink_to="hi") for r in names}

    @st.composite
    def draw_mass(draw: st.DrawFn) -> float:
        regime = draw(st.sampled_from(names))
        event(f"impact_masses: {regime}")
        return draw(branches[regime])

    return draw_mass()


impact_masses = memoised(impact_masses)  # one strategy per arguments (_common.memoised)


def mass_pairs(
    *, max_ratio: float = 1e15, regimes: Iterable[str] | None = None
) -> st.SearchStrategy[tuple[float, float]]:
    """Pairs (m_1, m_2) of masses > 0 with m_1/m_2 within [1/max_ratio, max_ratio].

    Regimes (:data:`MASS_PAIR_REGIMES`); ``max_ratio`` ≥ 1e6 keeps the extreme
    regimes reachable.  Shrinks toward (1, 1).

    Parameters
    ----------
    max_ratio : float
        The largest m_1/m_2 and m_2/m_1, finite and ≥ 1e6.
    regimes : iterable of str, optional
        Some of :data:`MASS_PAIR_REGIMES` (default all).

    Returns
    -------
    SearchStrategy of tuple of float
        (m_1, m_2) (kg).

    Raises
    ------
    InvalidArgument
        ``max_ratio`` not a finite real number ≥ 1e6; ``regimes`` a string, empty or with
        an unknown name.

    Examples
    --------
    >>> from hypothesis import given, settings
    >>> @settings(max_examples=30, derandomize=True)
    ... @given(mass_pairs(regimes=["light-1"]))
    ... def test_light(pair):
    ...     m1, m2 = pair
    ...     assert 0 < m1 <= 1e-6 * m2 * (1 + 1e-15)
    >>> test_light()
    """
    r = check_real(max_ratio, "max_ratio")
    if r < 1e6:
        raise InvalidArgument(f"max_ratio={max_ratio!r} must be >= 1e6")
    names = check_regimes(regimes, MASS_PAIR_REGIMES, "mass_pairs")
    base = log_uniform(1e-3, 1e3, shrink_to="hi")
    scales, ratios = log_uniform(*_MASS_SCALES, shrink_to="hi"), log_uniform(1e6, r, shrink_to="hi")

    @st.composite
    def draw_pair(draw: st.DrawFn) -> tuple[float, float]:
        regime = draw(st.sampled_from(names))
        event(f"mass_pairs: {regime}")
        if regime == "equal":
            return (1.0, 1.0)
        if regime == "generic":
            return (draw(base), draw(base))
        if regime == "scaled":
            k = draw(scales)
            return (draw(base) * k, draw(base) * k)
        m2 = draw(base)
        ratio = draw(ratios)
        return (m2 / ratio, m2) if regime == "light-1" else (m2 * ratio, m2)

    return draw_pair()


mass_pairs = memoised(mass_pairs)  # one strategy per arguments (_common.memoised)


def restitution_coefficients(*, regimes: Iterable[str] | None = None) -> st.SearchStrategy[float]:
    """Coefficients of restitution e ∈ [0, 1] (:data:`RESTITUTION_REGIMES`).

    Shrinks toward 0.

    Parameters
    ----------
    regimes : iterable of str, optional
        Some of :data:`RESTITUTION_REGIMES` (default all).

    Returns
    -------
    SearchStrategy of float
        e in [0, 1].

    Raises
    ------
    InvalidArgument
        ``regimes`` a string, empty or with an unknown name.

    Examples
    --------
    Near 1: e < 1, and 1 − e (exact in float64, Sterbenz's lemma) is at most about 1e-6:

    >>> from hypothesis import given, settings
    >>> @settings(max_examples=30, derandomize=True)
    ... @given(restitution_coefficients(regimes=["near-one"]))
    ... def test_near_one(e):
    ...     assert 0.0 < 1.0 - e <= 1.0001e-6
    >>> test_near_one()
    """
    names = check_regimes(regimes, RESTITUTION_REGIMES, "restitution_coefficients")
    below_one = 1.0 - math.nextafter(1.0, 0.0)  # 1.1e-16, the spacing below 1
    branches = {
        "zero": st.just(0.0),
        "one": st.just(1.0),
        "interior": st.floats(0.0, 1.0),
        "near-zero": log_uniform(1e-15, 1e-6, shrink_to="hi"),
        "near-one": log_uniform(below_one, 1e-6, shrink_to="hi").map(lambda d: 1.0 - d),
    }

    @st.composite
    def draw_e(draw: st.DrawFn) -> float:
        regime = draw(st.sampled_from(names))
        event(f"restitution_coefficients: {regime}")
        return draw(branches[regime])

    return draw_e()


restitution_coefficients = memoised(
    restitution_coefficients
)  # one strategy per arguments (_common.memoised)


def contact_normals() -> st.SearchStrategy[npt.NDArray[np.float64]]:
    """Unit contact normals ``(3,)``: :func:`mechanics.strategies.unit_vectors`.

    Its regimes: axis, general, near-axis.

    Returns
    -------
    SearchStrategy of ndarray, shape (3,)
        float64 unit vectors.

    Examples
    --------
    The same strategy object:

    >>> contact_normals() is unit_vectors()
    True
    """
    return unit_vectors()


contact_normals = memoised(contact_normals)  # one strategy per arguments (_common.memoised)


def direct_velocities(
    *, max_speed: float = 1e6, regimes: Iterable[str] | None = None
) -> st.SearchStrategy[tuple[float, float]]:
    """Approaching velocity pairs (ẋ_1, ẋ_2), ẋ_1 ≥ ẋ_2, |ẋ| ≤ ``max_speed``.

    Regimes (:data:`DIRECT_VELOCITY_REGIMES`).  Body 1 is behind body 2 on the
    X axis, so the relative velocity Δẋ = ẋ_2 − ẋ_1 ≤ 0 (computed in float64,
    ẋ_1 = fl(ẋ_2 + s) ≥ ẋ_2 for s ≥ 0).  Shrinks toward a head-on (1, −1).

    Parameters
    ----------
    max_speed : float
        The bound on |ẋ| (m/s), finite and ≥ 1.
    regimes : iterable of str, optional
        Some of :data:`DIRECT_VELOCITY_REGIMES` (default all).

    Returns
    -------
    SearchStrategy of tuple of float
        (ẋ_1, ẋ_2) (m/s), ẋ_1 ≥ ẋ_2.

    Raises
    ------
    InvalidArgument
        ``max_speed`` not a finite real number ≥ 1; ``regimes`` a string, empty or with an
        unknown name.

    Examples
    --------
    >>> from hypothesis import given, settings
    >>> @settings(max_examples=50, derandomize=True)
    ... @given(direct_velocities())
    ... def test_approach(v):
    ...     assert v[0] >= v[1] and max(abs(v[0]), abs(v[1])) <= 1e6
    >>> test_approach()
    """
    top = check_real(max_speed, "max_speed")
    if top < 1.0:
        raise InvalidArgument(f"max_speed={max_speed!r} must be >= 1")
    names = check_regimes(regimes, DIRECT_VELOCITY_REGIMES, "direct_velocities")
    speed = log_uniform(1e-6, top / 2, shrink_to="hi")
    # tiers, so that extremes meet in one pair: 0, tiny, order 1, the top ten decades
    any_speed = st.one_of(
        # capped at max_speed/2 like every tier (it drew up to 1e3 for a max_speed of 1)
        log_uniform(1e-3, min(1e3, top / 2), shrink_to="hi"),
        st.just(0.0),
        # not below 1e-250: times a mass fraction down to 1e-15 the velocities
        # after stay normal numbers, where relative accuracy is promised
        log_uniform(1e-250, 1e-100, shrink_to="hi"),
        log_uniform(top / 2e10, top / 2, shrink_to="lo"),
    )

    @st.composite
    def draw_pair(draw: st.DrawFn) -> tuple[float, float]:
        regime = draw(st.sampled_from(names))
        event(f"direct_velocities: {regime}")
        if regime == "mixed-magnitude":
            a, b = draw(any_speed), draw(any_speed)
            return (a, -b) if draw(st.booleans()) else (max(a, b), min(a, b))
        if regime == "head-on":
            return (draw(speed), -draw(speed))
        if regime == "at-rest":
            return (draw(speed), 0.0)
        sign = draw(_SIGNS)
        v2 = sign * draw(speed)
        if regime == "chase":
            s = draw(st.floats(0.0, 1.0)) * abs(v2)  # v1 = v2 + s keeps the sign of v2
        else:
            s = abs(v2) * draw(log_uniform(1e-12, 1e-6, shrink_to="hi"))
        return (v2 + s, v2)

    return draw_pair()


direct_velocities = memoised(direct_velocities)  # one strategy per arguments (_common.memoised)


# ------------------------------------------------------------ rigid bodies


def _vectors(max_norm: float) -> st.SearchStrategy[_Array]:
    comp = st.floats(-max_norm, max_norm, allow_subnormal=False)
    return st.tuples(comp, comp, comp).map(np.array)


_MOMENT_SCALES = log_uniform(1e-3, 1e3, shrink_to="hi")
_DEGENERATE_GAPS = log_uniform(1e-12, 1e-6, shrink_to="hi")
_ELONGATIONS = log_uniform(1e-6, 1e-2, shrink_to="hi")
_UNIT_INTERVAL = st.floats(0.0, 1.0)
_SYMMETRIC_RATIOS = st.floats(1e-2, 2.0)
_GENERAL_RATIOS = st.floats(1e-2, 1.0)
_SIGNED_UNIT = st.floats(-1.0, 1.0)
_ANGLES = st.floats(-math.pi, math.pi)


def _principal_moments(draw: st.DrawFn, regime: str) -> tuple[float, float, float]:
    """J1 ≤ J2 and J3 ∈ [J2 − J1, J1 + J2], scale log-uniform in [1e-3, 1e3]."""
    J2 = draw(_MOMENT_SCALES)
    if regime == "sphere":
        return (J2, J2, J2)
    if regime == "symmetric":
        return (J2, J2, J2 * draw(_SYMMETRIC_RATIOS))
    if regime == "near-degenerate":
        J1 = J2 / (1.0 + draw(_DEGENERATE_GAPS))
    elif regime == "elongated":
        J1 = J2 * draw(_ELONGATIONS)
    else:
        J1 = J2 * draw(_GENERAL_RATIOS)
    if regime == "lamina":
        return (J1, J2, J1 + J2)
    if regime == "elongated":
        return (J1, J2, J2 + J1 * draw(_SIGNED_UNIT))
    t = draw(_UNIT_INTERVAL)
    # At least 1e-2 J2: J1 ≈ J2 and t = 0 would give J3 = 0 (a rod's axis), not
    # positive definite; the floor stays inside [J2 − J1, J1 + J2].
    return (J1, J2, max((J2 - J1) + t * (2.0 * J1), 1e-2 * J2))


def _turned(moments: tuple[float, float, float], R: _Array) -> _Array:
    """The tensor with principal moments along the rows of R, in O: Rᵀ D R, symmetrised."""
    J = R.T @ np.diag(moments) @ R
    return 0.5 * (J + J.T)


def impact_inertia_tensors(
    *,
    regimes: Iterable[str] | None = None,
    rotations: st.SearchStrategy[npt.NDArray[np.float64]] | None = None,
) -> st.SearchStrategy[npt.NDArray[np.float64]]:
    """Inertia tensors ``(3, 3)`` about the centre of mass, in the fixed basis O.

    Principal moments (:data:`IMPACT_INERTIA_REGIMES`), scale 1e-3 … 1e3, are put on
    the rows of a drawn ^A R^O (``rotations``, default
    :func:`mechanics.strategies.rotation_matrices`): J_O = Rᵀ diag(J) R.
    Shrinks toward an unturned sphere tensor (a multiple of the identity).

    Parameters
    ----------
    regimes : iterable of str, optional
        Some of :data:`IMPACT_INERTIA_REGIMES` (default all).
    rotations : SearchStrategy, optional
        Rotation matrices of shape (3, 3) (default
        :func:`mechanics.strategies.rotation_matrices`).

    Returns
    -------
    SearchStrategy of ndarray, shape (3, 3)
        float64 tensors (kg m²), exactly symmetric.

    Raises
    ------
    InvalidArgument
        ``regimes`` a string, empty or with an unknown name; ``rotations`` not a
        hypothesis strategy.

    Examples
    --------
    A sphere's tensor is the same in every basis:

    >>> from hypothesis import given, settings
    >>> @settings(max_examples=30, derandomize=True)
    ... @given(impact_inertia_tensors(regimes=["sphere"]))
    ... def test_sphere(J):
    ...     assert np.allclose(J, J[0, 0] * np.eye(3), rtol=0, atol=1e-14 * J[0, 0])
    >>> test_sphere()
    """
    names = check_regimes(regimes, IMPACT_INERTIA_REGIMES, "impact_inertia_tensors")
    rotations = rotation_matrices() if rotations is None else rotations
    if not isinstance(rotations, st.SearchStrategy):
        raise InvalidArgument(f"rotations={rotations!r} must be a hypothesis strategy")

    @st.composite
    def draw_tensor(draw: st.DrawFn) -> _Array:
        regime = draw(st.sampled_from(names))
        event(f"impact_inertia_tensors: {regime}")
        return _turned(_principal_moments(draw, regime), draw(rotations))

    return draw_tensor()


impact_inertia_tensors = memoised(
    impact_inertia_tensors
)  # one strategy per arguments (_common.memoised)


def impact_bodies(
    *,
    masses_: st.SearchStrategy[float] | None = None,
    tensors: st.SearchStrategy[npt.NDArray[np.float64]] | None = None,
    max_position: float = 10.0,
    max_speed: float = 10.0,
) -> st.SearchStrategy[RigidBody]:
    """:class:`~mechanics.impact.RigidBody` records.

    Mass from ``masses_`` (default :func:`impact_masses` in 1e-6 … 1e6), inertia
    tensor from ``tensors`` (default :func:`impact_inertia_tensors`) scaled by the mass
    (so J_G/m is a squared length of 1e-3 … 1e3), position of G with components
    within ``max_position``, v_G and ω with components within ``max_speed``.

    Parameters
    ----------
    masses_ : SearchStrategy, optional
        Masses (kg) (default :func:`impact_masses` in 1e-6 … 1e6).
    tensors : SearchStrategy, optional
        Tensors of shape (3, 3) per unit mass (m²) (default :func:`impact_inertia_tensors`).
    max_position : float
        The bound on each component of r_G (m), finite.
    max_speed : float
        The bound on each component of v_G (m/s) and ω (rad/s), finite.

    Returns
    -------
    SearchStrategy of RigidBody
        :class:`mechanics.impact.RigidBody` records (m, J_G, r_G, v_G, omega).

    Raises
    ------
    InvalidArgument
        ``max_position`` or ``max_speed`` not a finite real number (at the call); a
        negative one, or ``masses_`` or ``tensors`` not a hypothesis strategy, only when
        drawing, with hypothesis' own message (which does not name the argument).

    Examples
    --------
    >>> from hypothesis import given, settings
    >>> @settings(max_examples=30, derandomize=True)
    ... @given(impact_bodies(max_position=1.0))
    ... def test_bounds(b):
    ...     assert 1e-6 <= b.m <= 1e6 and np.abs(b.r_G).max() <= 1.0
    >>> test_bounds()
    """
    masses_ = impact_masses(min_value=1e-6, max_value=1e6) if masses_ is None else masses_
    tensors = impact_inertia_tensors() if tensors is None else tensors
    pos = check_real(max_position, "max_position")
    spd = check_real(max_speed, "max_speed")
    return st.builds(
        lambda m, J, r, v, w: RigidBody(m, m * J, r, v, w),
        masses_,
        tensors,
        _vectors(pos),
        _vectors(spd),
        _vectors(spd),
    )


impact_bodies = memoised(impact_bodies)  # one strategy per arguments (_common.memoised)


def _approaching(
    b1: RigidBody, b2: RigidBody | None, r_S: _Array, n: _Array, speed: float
) -> RigidBody:
    """Shift body 1's v_G along n so that v_n = −speed (to rounding)."""
    rel = b1.v_G + np.cross(b1.omega, r_S - b1.r_G)
    if b2 is not None:
        rel = rel - (b2.v_G + np.cross(b2.omega, r_S - b2.r_G))
    v_n = float(n @ rel)
    return b1._replace(v_G=b1.v_G - (v_n + speed) * n)


def contacts(
    *, regimes: Iterable[str] | None = None, restitution: st.SearchStrategy[float] | None = None
) -> st.SearchStrategy[Contact]:
    """Approaching contacts of rigid bodies, :class:`Contact` records.

    Regimes (:data:`CONTACT_REGIMES`).  The normal relative velocity is minus
    an approach speed in [1e-2, 1e2] (velocities are at most ~1e2 in
    magnitude, so rounding leaves it at least 1e-2 below 0): every drawn
    contact is an impact.  ``restitution`` defaults to
    :func:`restitution_coefficients`.

    Parameters
    ----------
    regimes : iterable of str, optional
        Some of :data:`CONTACT_REGIMES` (default all).
    restitution : SearchStrategy, optional
        Coefficients e in [0, 1] (default :func:`restitution_coefficients`).

    Returns
    -------
    SearchStrategy of Contact
        :class:`Contact` records whose contact points approach.

    Raises
    ------
    InvalidArgument
        ``regimes`` a string, empty or with an unknown name; ``restitution`` not a
        hypothesis strategy.

    Examples
    --------
    The normal relative velocity of S is negative (against a fixed body 2: body 1's alone):

    >>> from hypothesis import given, settings
    >>> @settings(max_examples=30, derandomize=True)
    ... @given(contacts(regimes=["fixed-body-2"]))
    ... def test_approach(c):
    ...     b = c.body_1
    ...     assert c.body_2 is None and c.n @ (b.v_G + np.cross(b.omega, c.r_S - b.r_G)) < 0
    >>> test_approach()
    """
    names = check_regimes(regimes, CONTACT_REGIMES, "contacts")
    es = restitution_coefficients() if restitution is None else restitution
    if not isinstance(es, st.SearchStrategy):
        raise InvalidArgument(f"restitution={restitution!r} must be a hypothesis strategy")
    speeds = log_uniform(1e-2, 1e2, shrink_to="hi")
    arms = st.floats(0.05, 3.0)
    bodies = impact_bodies()
    plane_masses = impact_masses(min_value=1e-3, max_value=1e3)
    plane_regimes = st.sampled_from(IMPACT_INERTIA_REGIMES)
    ratios = log_uniform(1e6, 1e12, shrink_to="hi")
    offsets, positions, velocities = _vectors(3.0), _vectors(10.0), _vectors(10.0)
    spins = st.floats(-10.0, 10.0)
    in_plane = np.array([1.0, 1.0, 0.0])
    z = np.array([0.0, 0.0, 1.0])
    unit_normals = contact_normals()

    def plane_body(draw: st.DrawFn) -> RigidBody:
        m = draw(plane_masses)
        J = _turned(_principal_moments(draw, draw(plane_regimes)), _rot.R3(draw(_ANGLES)))
        r, v = draw(positions) * in_plane, draw(velocities) * in_plane
        return RigidBody(m, m * J, r, v, draw(spins) * z)

    @st.composite
    def draw_contact(draw: st.DrawFn) -> Contact:
        regime = draw(st.sampled_from(names))
        event(f"contacts: {regime}")
        e = draw(es)
        b2: RigidBody | None
        if regime == "planar":
            phi = draw(_ANGLES)
            n = np.array([math.cos(phi), math.sin(phi), 0.0])
            b1, b2 = plane_body(draw), plane_body(draw)
            r_S = b1.r_G + draw(offsets) * in_plane
            return Contact(_approaching(b1, b2, r_S, n, draw(speeds)), b2, r_S, n, e)
        n = draw(unit_normals)
        b1 = draw(bodies)
        if regime == "fixed-body-2":  # body 2 fixed (infinite mass): S off G1
            r_S = b1.r_G + draw(offsets)
            return Contact(_approaching(b1, None, r_S, n, draw(speeds)), None, r_S, n, e)
        b2 = draw(bodies)
        if regime == "mass-ratio":
            # Rescale body 1 (mass and tensor together) to m_2 times a ratio 1e±6 … 1e±12.
            k = draw(ratios)
            m1 = b2.m * k if draw(_SIGNS) > 0 else b2.m / k
            b1 = b1._replace(m=m1, J_G=b1.J_G * (m1 / b1.m))
        if regime == "central":
            # G1 behind S along n (n points into body 1), G2 on the other side.
            r_S = b1.r_G - draw(arms) * n
            b2 = b2._replace(r_G=r_S - draw(arms) * n)
        else:
            r_S = b1.r_G + draw(offsets)
        return Contact(_approaching(b1, b2, r_S, n, draw(speeds)), b2, r_S, n, e)

    return draw_contact()


contacts = memoised(contacts)  # one strategy per arguments (_common.memoised)


def hinged_bodies(*, regimes: Iterable[str] | None = None) -> st.SearchStrategy[HingedBody]:
    """Bodies on a fixed axis, :class:`HingedBody` records (:data:`HINGED_REGIMES`).

    J_A is built from J_G (:func:`impact_inertia_tensors` scaled by the mass) by the
    parallel-axis theorem, J_A = J_G + m (|d|² 1 − d dᵀ), d = r_G − A, so it is
    valid by construction.  G is 0.1 … 5 from the axis.

    Parameters
    ----------
    regimes : iterable of str, optional
        Some of :data:`HINGED_REGIMES` (default all).

    Returns
    -------
    SearchStrategy of HingedBody
        :class:`HingedBody` records.

    Raises
    ------
    InvalidArgument
        ``regimes`` a string, empty or with an unknown name.

    Examples
    --------
    The parallel-axis theorem (4.38) read back: J_A − J_G = m (|d|² 1 − d dᵀ), d = r_G − A.

    >>> from hypothesis import given, settings
    >>> @settings(max_examples=30, derandomize=True)
    ... @given(hinged_bodies(regimes=["planar"]))
    ... def test_shift(h):
    ...     d = h.r_G - h.axis_point
    ...     shift = h.m * (float(d @ d) * np.eye(3) - np.outer(d, d))
    ...     assert np.allclose(h.J_A - h.J_G, shift, rtol=0, atol=1e-12 * np.abs(h.J_A).max())
    >>> test_shift()
    """
    names = check_regimes(regimes, HINGED_REGIMES, "hinged_bodies")
    body_masses = impact_masses(min_value=1e-3, max_value=1e3)
    distances = st.floats(0.1, 5.0)
    tensors = impact_inertia_tensors()
    plane_regimes = st.sampled_from(IMPACT_INERTIA_REGIMES)
    points, unit_axes, axial = _vectors(5.0), contact_normals(), st.floats(-5.0, 5.0)

    @st.composite
    def draw_hinged(draw: st.DrawFn) -> HingedBody:
        regime = draw(st.sampled_from(names))
        event(f"hinged_bodies: {regime}")
        m = draw(body_masses)
        h = draw(distances)
        if regime == "planar":
            A = np.zeros(3)
            axis = np.array([0.0, 0.0, 1.0])
            phi = draw(_ANGLES)
            d = h * np.array([math.cos(phi), math.sin(phi), 0.0])
            R = _rot.R3(draw(_ANGLES))
            J_G = m * _turned(_principal_moments(draw, draw(plane_regimes)), R)
        else:
            A = draw(points)
            axis = draw(unit_axes)
            # A unit vector perpendicular to the axis: cross with the coordinate
            # axis least aligned with it (norm >= sqrt(2/3)), turned by a drawn angle.
            u0 = np.cross(axis, np.eye(3)[int(np.argmin(np.abs(axis)))])
            u0 = u0 / np.linalg.norm(u0)
            phi = draw(_ANGLES)
            u = math.cos(phi) * u0 + math.sin(phi) * np.cross(axis, u0)
            d = h * u + draw(axial) * axis
            J_G = m * draw(tensors)
        J_A = J_G + m * (float(d @ d) * np.eye(3) - np.outer(d, d))
        return HingedBody(m, 0.5 * (J_A + J_A.T), A + d, A, axis, J_G)

    return draw_hinged()


hinged_bodies = memoised(hinged_bodies)  # one strategy per arguments (_common.memoised)
