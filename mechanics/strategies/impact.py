"""Hypothesis strategies for impact, valid by construction, with the hard regimes.

Conventions
-----------
- The objects are those of :mod:`mechanics.impact`: masses (floats > 0),
  coefficients of restitution e ∈ [0, 1], unit contact_normals ``(3,)``, velocity pairs
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
    """A drawn contact: the two bodies (``body_2`` ``None`` = fixed), the
    contact point ``r_S``, the unit normal ``n`` into body 1 and ``e``."""

    body_1: RigidBody
    body_2: RigidBody | None
    r_S: npt.NDArray[np.float64]
    n: npt.NDArray[np.float64]
    e: float


class HingedBody(NamedTuple):
    """A drawn hinged body: mass, inertia tensor about the axis point, position
    of G, the axis point and unit axis, as :func:`mechanics.impact.hinged_impact`
    takes them; ``J_G`` is the tensor about G it was built from."""

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
    """Unit contact contact_normals ``(3,)``: :func:`mechanics.strategies.unit_vectors`
    (regimes axis, general, near-axis)."""
    return unit_vectors()


contact_normals = memoised(contact_normals)  # one strategy per arguments (_common.memoised)


def direct_velocities(
    *, max_speed: float = 1e6, regimes: Iterable[str] | None = None
) -> st.SearchStrategy[tuple[float, float]]:
    """Approaching velocity pairs (ẋ_1, ẋ_2), ẋ_1 ≥ ẋ_2, |ẋ| ≤ ``max_speed``.

    Regimes (:data:`DIRECT_VELOCITY_REGIMES`).  Body 1 is behind body 2 on the
    X axis, so the relative velocity Δẋ = ẋ_2 − ẋ_1 ≤ 0 (computed in float64,
    ẋ_1 = fl(ẋ_2 + s) ≥ ẋ_2 for s ≥ 0).  Shrinks toward a head-on (1, −1).
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
