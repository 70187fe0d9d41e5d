"""Hypothesis strategies for rotations, valid by construction, with the hard regimes.

Conventions
-----------
- The objects are those of :mod:`mechanics.rotation`: unit vectors ``(3,)``,
  rotation angles in [0, π], rotation vectors φ e_a ``(3,)``, Euler angles
  (ψ, θ, φ) z-x-z, unit quaternions ``(4,)`` scalar first (w, x, y, z), and the
  book's passive matrices ^A R^O ``(3, 3)``.  Everything is float64.
- Rotation vectors are not confined to angles in [0, π]: a rotation vector of
  any length is valid (the angle is taken modulo 2π), and the code has branches
  for tiny, ordinary and huge lengths; :data:`ROTVEC_REGIMES` reaches them all.
- **Valid by construction.**  No strategy filters: a unit vector is built from a
  height and an azimuth, an angle near π is π minus a drawn offset, a matrix is
  the image of drawn parameters under :mod:`mechanics.rotation`.
- **Hard regimes are explicit branches.**  Each strategy first draws the name of
  a regime with ``st.sampled_from`` (the first regime is the simple one, so
  failing examples shrink toward the identity and zero), then draws inside it.
  The regimes are listed per strategy below and in the module constants
  ``*_REGIMES``; ``tests/strategies/test_strategy_quality.py`` proves every one is
  reached.
- **Which regime was drawn** is recorded with :func:`hypothesis.event` as
  ``"<strategy>: <regime>"``; ``pytest --hypothesis-show-statistics`` prints
  how often each was taken.
- Bounds are keyword-only; bad arguments raise
  :class:`hypothesis.errors.InvalidArgument` quoting the value.

Importing this module imports hypothesis; ``import mechanics`` does not.

Examples
--------
>>> from hypothesis import given
>>> from mechanics.rotation import matrix_from_rotvec, is_rotation
>>> @given(rotvecs())
... def test_rotvec_gives_rotation(v):
...     assert is_rotation(matrix_from_rotvec(v))
>>> test_rotvec_gives_rotation()
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import TypeAlias

import numpy as np
import numpy.typing as npt
from hypothesis import event
from hypothesis import strategies as st
from hypothesis.errors import InvalidArgument

from .. import rotation as _rot
from ._common import check_real, check_regimes, log_uniform, memoised

_Array: TypeAlias = npt.NDArray[np.float64]

__all__ = [
    "ANGLE_REGIMES",
    "BEYOND_PI_RANGE",
    "EULER_REGIMES",
    "HUGE_LENGTH_RANGE",
    "MATRIX_REGIMES",
    "NEAR_PI_WIDTH",
    "QUATERNION_REGIMES",
    "ROTVEC_REGIMES",
    "TINY_ANGLE_RANGE",
    "UNIT_VECTOR_REGIMES",
    "euler_angles",
    "quaternions",
    "rotation_angles",
    "rotation_matrices",
    "rotvecs",
    "unit_vectors",
]


#: Regimes of :func:`unit_vectors`: a signed coordinate axis; a general direction
#: (height uniform in [−1, 1], azimuth uniform); a direction within 1e-12 … 1e-3
#: of a coordinate axis (components down to 1e-12 of the others).
UNIT_VECTOR_REGIMES = ("axis", "general", "near-axis")

#: Regimes of :func:`rotation_angles`: exactly 0; generic (any float in the
#: bounds, hypothesis' nasty floats included); tiny, log-uniform in
#: :data:`TINY_ANGLE_RANGE`; within :data:`NEAR_PI_WIDTH` below π; exactly
#: ``math.pi``.
ANGLE_REGIMES = ("zero", "generic", "tiny", "near-pi", "pi")

#: Tiny rotation angles, drawn log-uniformly: from where float64 still holds the
#: products of the angle with axis components as normal numbers (1e-300) up to
#: 1e-6, where the φ² terms are below 1e-12 of the matrix, so that formulas which
#: cancel (1 − cos φ, arccos of the trace) lose at least half of their digits.
TINY_ANGLE_RANGE = (1e-300, 1e-6)

#: Width of the band below π for the "near-pi" regimes: π − δ with δ log-uniform
#: from one ulp of π up to this width.  sin φ ≈ δ, so the antisymmetric part of
#: the matrix, which carries the sense of the axis, is of size δ there.
NEAR_PI_WIDTH = 1e-8

_PI_ULP = math.ulp(math.pi)  # 4.4e-16: the smallest δ with fl(π − δ) < π

#: Regimes of :func:`rotvecs`: ``axis-angle``, a :func:`unit_vectors` direction
#: times a :func:`rotation_angles` angle in [0, π] (all their regimes);
#: ``beyond-pi``, a :func:`unit_vectors` direction times a length log-uniform in
#: :data:`BEYOND_PI_RANGE`; ``tiny-general``, a length log-uniform in
#: :data:`TINY_ANGLE_RANGE` along a direction whose three components are all
#: non-zero (1/8 to 1 of the largest, either sign), so that no component's error
#: hides behind a zero; ``huge``, a :func:`unit_vectors` direction (exact axes
#: included) times a length log-uniform in :data:`HUGE_LENGTH_RANGE`; ``mixed``,
#: three components of independent magnitudes log-uniform over 1e-300 … 1e300
#: (either sign), so that one rotation vector spans the whole float range.
ROTVEC_REGIMES = ("axis-angle", "beyond-pi", "tiny-general", "huge", "mixed")

#: Lengths of the ``beyond-pi`` rotation vectors: from just above π to 2**26
#: (= 6.7e7), where the angle modulo 2π can still be formed to an ulp (beyond it a
#: rounding of the input moves the angle by more than the matrix can show).
BEYOND_PI_RANGE = (math.pi * (1.0 + 2.0**-50), 2.0**26)

#: Lengths of the ``huge`` rotation vectors: from 2**26 to 1e308, where the
#: squared length overflows.
HUGE_LENGTH_RANGE = (2.0**26, 1e308)

_MIXED_RANGE = (1e-300, 1e300)

#: Regimes of :func:`euler_angles`: all zero; generic (ψ, φ in [−π, π], θ in
#: [0, π]); gimbal lock θ = 0 and θ = π exactly; θ within 1e-12 … 1e-6 of 0 and
#: of π (log-uniform).  In the four gimbal regimes ψ and φ are non-zero
#: (magnitude in [1e-3, π], either sign), so that ψ + φ and ψ − φ differ.
EULER_REGIMES = ("zero", "generic", "theta-zero", "theta-pi", "theta-near-zero", "theta-near-pi")

_GIMBAL_BAND = (1e-12, 1e-6)
_OUTER_MIN = 1e-3

#: Regimes of :func:`quaternions`: the identity (1, 0, 0, 0); a half turn
#: (0, e_a) about a drawn axis, w = 0 exactly (the quaternion of π e_a computed
#: in float64 has w = cos(fl(π)/2) = 6e-17, never 0); the quaternion of a drawn
#: rotation vector (all regimes of :func:`rotvecs`).  Each is negated half of the
#: time (q ≡ −q).
QUATERNION_REGIMES = ("identity", "half-turn", "from-rotvec")

#: Regimes of :func:`rotation_matrices`: the identity; a signed permutation
#: matrix (a turn by a multiple of π/2 about coordinate axes, exact in float64);
#: a sign flip: a half turn about an axis in a coordinate plane, the matrix
#: 2 n nᵀ − 1 with its zeros and the −1 on the diagonal exact (Euler θ exactly 0
#: or π when the plane is the x-y plane: gimbal lock with a general ψ − φ, which
#: :func:`~mechanics.rotation.matrix_from_euler` never gives exactly, as
#: sin(fl(π)) ≠ 0); the image of :func:`rotvecs`, of :func:`euler_angles`
#: (gimbal lock included) and of :func:`quaternions` under :mod:`mechanics.rotation`.
MATRIX_REGIMES = (
    "identity",
    "signed-permutation",
    "sign-flip",
    "rotvec",
    "euler",
    "quaternion",
)


# ------------------------------------------------------------------ validation


# --------------------------------------------------------------------- vectors


def unit_vectors() -> st.SearchStrategy[npt.NDArray[np.float64]]:
    """Unit vectors, shape ``(3,)``, in all directions.

    Regimes (:data:`UNIT_VECTOR_REGIMES`): ``axis`` (±e1, ±e2, ±e3, shrinking to
    e1), ``general`` (height z uniform in [−1, 1], azimuth uniform in [−π, π]:
    uniform on the sphere), ``near-axis`` (a coordinate axis tilted by 1e-12 …
    1e-3, so that two components are tiny).  The norm is 1 within one ulp.

    Returns
    -------
    SearchStrategy of ndarray, shape (3,)
        float64 unit vectors; shrinks toward e1.

    Examples
    --------
    The norm is 1 within one ulp:

    >>> from hypothesis import given, settings
    >>> @settings(max_examples=50, derandomize=True)
    ... @given(unit_vectors())
    ... def test_unit(u):
    ...     assert abs(math.hypot(*u) - 1.0) <= math.ulp(1.0)
    >>> test_unit()
    """

    tilts = log_uniform(1e-12, 1e-3, shrink_to="hi")

    @st.composite
    def draw_unit_vector(draw: st.DrawFn) -> _Array:
        regime = draw(st.sampled_from(UNIT_VECTOR_REGIMES))
        event(f"unit_vectors: {regime}")
        if regime == "axis":
            u = np.zeros(3)
            u[draw(st.integers(0, 2))] = draw(st.sampled_from((1.0, -1.0)))
            return u
        if regime == "general":
            z = draw(st.floats(-1.0, 1.0))
            rho = math.sqrt((1.0 - z) * (1.0 + z))
        else:  # sin of the tilt, not sqrt(1 - z²): cos(1e-12) rounds to 1
            tilt = draw(tilts)
            z = math.cos(tilt) * draw(st.sampled_from((1.0, -1.0)))
            rho = math.sin(tilt)
        azimuth = draw(st.floats(-math.pi, math.pi))
        u = np.array([rho * math.cos(azimuth), rho * math.sin(azimuth), z])
        if regime == "near-axis":
            u = np.roll(u, draw(st.integers(0, 2)))  # tilt off e3, e1 or e2
        return u / math.hypot(math.hypot(u[0], u[1]), u[2])

    return draw_unit_vector()


unit_vectors = memoised(unit_vectors)  # one strategy per arguments (_common.memoised)


# ---------------------------------------------------------------------- angles


def rotation_angles(
    *, min_value: float = 0.0, max_value: float = math.pi, regimes: Iterable[str] | None = None
) -> st.SearchStrategy[float]:
    """Rotation angles φ in [``min_value``, ``max_value``] ⊆ [0, π].

    Regimes (:data:`ANGLE_REGIMES`), each used when it meets the bounds:
    ``zero`` (exactly 0), ``generic`` (``st.floats`` in the bounds, subnormals
    excluded), ``tiny`` (log-uniform in :data:`TINY_ANGLE_RANGE`), ``near-pi``
    (π − δ, δ log-uniform from one ulp of π to :data:`NEAR_PI_WIDTH`) and ``pi``
    (exactly ``math.pi``).  ``regimes`` restricts the draw to some of them.
    Shrinks toward 0 (the identity), or the lower bound.

    Parameters
    ----------
    min_value, max_value : float
        The bounds (rad), finite, 0 ≤ ``min_value`` ≤ ``max_value`` ≤ π.
    regimes : iterable of str, optional
        Some of :data:`ANGLE_REGIMES` (default all); those that cannot meet the bounds
        are left out.

    Returns
    -------
    SearchStrategy of float
        Angles φ (rad) in [``min_value``, ``max_value``].

    Raises
    ------
    InvalidArgument
        A bound not a finite real number, ``min_value`` < 0, ``max_value`` > π or
        ``min_value`` > ``max_value``; ``regimes`` a string, empty, with an unknown name,
        or with none reachable in the bounds.

    Examples
    --------
    The tiny regime alone, inside its range:

    >>> from hypothesis import given, settings
    >>> @settings(max_examples=30, derandomize=True)
    ... @given(rotation_angles(regimes=["tiny"]))
    ... def test_tiny(phi):
    ...     assert TINY_ANGLE_RANGE[0] <= phi <= TINY_ANGLE_RANGE[1]
    >>> test_tiny()
    """
    lo = check_real(min_value, "min_value")
    hi = check_real(max_value, "max_value")
    if lo < 0:
        raise InvalidArgument(f"min_value={min_value!r} must be >= 0")
    if hi > math.pi:
        raise InvalidArgument(f"max_value={max_value!r} must be <= math.pi")
    if lo > hi:
        raise InvalidArgument(f"min_value={min_value!r} exceeds max_value={max_value!r}")
    wanted = check_regimes(regimes, ANGLE_REGIMES, "rotation_angles")

    tiny = (max(lo, TINY_ANGLE_RANGE[0]), min(hi, TINY_ANGLE_RANGE[1]))
    below_pi = math.nextafter(math.pi, 0.0)
    near = (max(lo, math.pi - NEAR_PI_WIDTH), min(hi, below_pi))
    branches: dict[str, st.SearchStrategy[float]] = {}
    if lo == 0.0:
        branches["zero"] = st.just(0.0)
    branches["generic"] = st.floats(lo, hi, allow_subnormal=False)
    if tiny[0] <= tiny[1]:
        branches["tiny"] = log_uniform(*tiny, shrink_to="hi")
    if near[0] <= near[1]:
        d_hi = math.pi - near[0]
        d_lo = max(_PI_ULP, math.pi - near[1])
        branches["near-pi"] = log_uniform(d_lo, d_hi, shrink_to="hi").map(
            lambda d: min(near[1], max(near[0], math.pi - d))
        )
    if lo <= math.pi <= hi:
        branches["pi"] = st.just(math.pi)
    names = tuple(r for r in wanted if r in branches)
    if not names:
        raise InvalidArgument(
            f"regimes={regimes!r}: none reachable in [{min_value!r}, {max_value!r}]"
        )

    @st.composite
    def draw_angle(draw: st.DrawFn) -> float:
        regime = draw(st.sampled_from(names))
        event(f"rotation_angles: {regime}")
        return draw(branches[regime])

    return draw_angle()


rotation_angles = memoised(rotation_angles)  # one strategy per arguments (_common.memoised)


def rotvecs(
    *,
    axes: st.SearchStrategy[npt.NDArray[np.float64]] | None = None,
    angles: st.SearchStrategy[float] | None = None,
    regimes: Iterable[str] | None = None,
) -> st.SearchStrategy[npt.NDArray[np.float64]]:
    """Rotation vectors φ e_a, shape ``(3,)``, of any length.

    Regimes (:data:`ROTVEC_REGIMES`): ``axis-angle`` (a direction from ``axes``,
    default :func:`unit_vectors`, times an angle from ``angles``, default
    :func:`rotation_angles`: zero, tiny, generic, near-π and exactly-π angles;
    the norm is the angle within an ulp or two), ``beyond-pi`` (lengths in
    :data:`BEYOND_PI_RANGE`), ``tiny-general`` (lengths in
    :data:`TINY_ANGLE_RANGE`, every component non-zero), ``huge`` (lengths in
    :data:`HUGE_LENGTH_RANGE`, along exact axes too) and ``mixed`` (components of
    independent magnitudes over 1e-300 … 1e300).  ``regimes`` restricts the draw;
    when ``axes`` or ``angles`` is given and ``regimes`` is not, only
    ``axis-angle`` is drawn (the one regime they shape).  Shrinks toward zero.

    Parameters
    ----------
    axes : SearchStrategy, optional
        Unit vectors of shape (3,) for ``axis-angle`` (default :func:`unit_vectors`).
    angles : SearchStrategy, optional
        Angles (rad) for ``axis-angle`` (default :func:`rotation_angles`).
    regimes : iterable of str, optional
        Some of :data:`ROTVEC_REGIMES` (default all, or ``axis-angle`` alone when
        ``axes`` or ``angles`` is given).

    Returns
    -------
    SearchStrategy of ndarray, shape (3,)
        float64 rotation vectors φ e_a (rad).

    Raises
    ------
    InvalidArgument
        ``axes`` or ``angles`` not a hypothesis strategy; ``regimes`` a string, empty or
        with an unknown name.

    Examples
    --------
    The norm is the drawn angle within an ulp or two:

    >>> from hypothesis import given, settings
    >>> @settings(max_examples=30, derandomize=True)
    ... @given(rotvecs(angles=st.just(math.pi)))
    ... def test_half_turns(v):
    ...     assert abs(math.hypot(*v) - math.pi) <= 2 * math.ulp(math.pi)
    >>> test_half_turns()
    """
    for name, s in (("axes", axes), ("angles", angles)):
        if s is not None and not isinstance(s, st.SearchStrategy):
            raise InvalidArgument(f"{name}={s!r} must be a hypothesis strategy")
    if regimes is None and (axes is not None or angles is not None):
        regimes = ("axis-angle",)
    names = check_regimes(regimes, ROTVEC_REGIMES, "rotvecs")
    axes = unit_vectors() if axes is None else axes
    angles = rotation_angles() if angles is None else angles
    signs = st.sampled_from((1.0, -1.0))
    general = st.tuples(
        *(st.tuples(st.floats(0.125, 1.0), signs).map(lambda t: t[0] * t[1]),) * 3
    ).map(lambda c: np.array(c) / math.hypot(*c))
    lengths = {
        "beyond-pi": log_uniform(*BEYOND_PI_RANGE, shrink_to="lo"),
        "tiny-general": log_uniform(*TINY_ANGLE_RANGE, shrink_to="hi"),
        "huge": log_uniform(*HUGE_LENGTH_RANGE, shrink_to="lo"),
    }
    mixed = st.tuples(
        *(st.tuples(log_uniform(*_MIXED_RANGE, shrink_to="lo"), signs).map(lambda t: t[0] * t[1]),)
        * 3
    ).map(np.array)

    @st.composite
    def draw_rotvec(draw: st.DrawFn) -> _Array:
        regime = draw(st.sampled_from(names))
        event(f"rotvecs: {regime}")
        if regime == "axis-angle":
            return draw(axes) * draw(angles)
        if regime == "mixed":
            return draw(mixed)
        direction = draw(general if regime == "tiny-general" else axes)
        return direction * draw(lengths[regime])

    return draw_rotvec()


rotvecs = memoised(rotvecs)  # one strategy per arguments (_common.memoised)


def euler_angles(
    *, regimes: Iterable[str] | None = None
) -> st.SearchStrategy[tuple[float, float, float]]:
    """Euler angles (ψ, θ, φ), z-x-z, as a tuple of floats.

    Regimes (:data:`EULER_REGIMES`): ``zero``; ``generic`` (ψ, φ in [−π, π], θ
    in [0, π]); ``theta-zero`` and ``theta-pi`` (θ exactly 0 or ``math.pi``);
    ``theta-near-zero`` and ``theta-near-pi`` (θ or π − θ log-uniform in
    1e-12 … 1e-6).  In the gimbal regimes the outer angles ψ, φ are non-zero
    (magnitude in [1e-3, π], either sign): at gimbal lock only ψ + φ (θ = 0) or
    ψ − φ (θ = π) is defined, and zero outer angles would hide a wrong split.
    ``regimes`` restricts the draw to some of them.  Shrinks toward (0, 0, 0).

    Parameters
    ----------
    regimes : iterable of str, optional
        Some of :data:`EULER_REGIMES` (default all).

    Returns
    -------
    SearchStrategy of tuple of float
        (ψ, θ, φ) (rad).

    Raises
    ------
    InvalidArgument
        ``regimes`` a string, empty or with an unknown name.

    Examples
    --------
    At θ = 0 only ψ + φ is defined: the matrix of (ψ, 0, φ) is that of (ψ + φ, 0, 0).

    >>> from hypothesis import given, settings
    >>> from mechanics.testing import assert_rotations_close
    >>> @settings(max_examples=30, derandomize=True)
    ... @given(euler_angles(regimes=["theta-zero"]))
    ... def test_gimbal_lock(a):
    ...     psi, theta, phi = a
    ...     assert_rotations_close(_rot.matrix_from_euler(psi, theta, phi),
    ...                            _rot.matrix_from_euler(psi + phi, 0.0, 0.0))
    >>> test_gimbal_lock()
    """
    names = check_regimes(regimes, EULER_REGIMES, "euler_angles")
    outer = st.tuples(st.floats(_OUTER_MIN, math.pi), st.sampled_from((1.0, -1.0))).map(
        lambda t: t[0] * t[1]
    )
    band = log_uniform(*_GIMBAL_BAND, shrink_to="hi")
    thetas = {
        "theta-zero": st.just(0.0),
        "theta-pi": st.just(math.pi),
        "theta-near-zero": band,
        "theta-near-pi": band.map(lambda d: math.pi - d),
    }

    @st.composite
    def draw_euler(draw: st.DrawFn) -> tuple[float, float, float]:
        regime = draw(st.sampled_from(names))
        event(f"euler_angles: {regime}")
        if regime == "zero":
            return (0.0, 0.0, 0.0)
        if regime == "generic":
            psi = draw(st.floats(-math.pi, math.pi))
            theta = draw(st.floats(0.0, math.pi))
            phi = draw(st.floats(-math.pi, math.pi))
            return (psi, theta, phi)
        psi, phi = draw(outer), draw(outer)
        return (psi, draw(thetas[regime]), phi)

    return draw_euler()


euler_angles = memoised(euler_angles)  # one strategy per arguments (_common.memoised)


# ---------------------------------------------------------- quaternions, matrices


def quaternions() -> st.SearchStrategy[npt.NDArray[np.float64]]:
    """Unit quaternions (w, x, y, z), scalar first, shape ``(4,)``.

    Regimes (:data:`QUATERNION_REGIMES`): ``identity`` (1, 0, 0, 0);
    ``half-turn`` (0, e_a), w = 0 exactly, about a drawn :func:`unit_vectors`;
    ``from-rotvec``: :func:`mechanics.rotation.quat_from_rotvec` of a drawn
    :func:`rotvecs` (tiny angles, w near 0).  Each is negated half of the time,
    since q and −q are the same rotation.  The norm is 1 within a few ulps.
    Shrinks toward the identity.

    Returns
    -------
    SearchStrategy of ndarray, shape (4,)
        float64 unit quaternions (w, x, y, z).

    Examples
    --------
    q and −q give the same matrix, to the bit:

    >>> from hypothesis import given, settings
    >>> @settings(max_examples=50, derandomize=True)
    ... @given(quaternions())
    ... def test_sign(q):
    ...     assert (_rot.matrix_from_quat(q) == _rot.matrix_from_quat(-q)).all()
    >>> test_sign()
    """
    signs = st.sampled_from((1.0, -1.0))
    # built once, not per draw (a strategy built inside a draw costs more than the draw)
    axes, vecs = unit_vectors(), rotvecs()

    @st.composite
    def draw_quaternion(draw: st.DrawFn) -> _Array:
        regime = draw(st.sampled_from(QUATERNION_REGIMES))
        event(f"quaternions: {regime}")
        if regime == "identity":
            q = np.array([1.0, 0.0, 0.0, 0.0])
        elif regime == "half-turn":
            q = np.concatenate([[0.0], draw(axes)])
        else:
            q = _rot.quat_from_rotvec(draw(vecs))
        return draw(signs) * q

    return draw_quaternion()


quaternions = memoised(quaternions)  # one strategy per arguments (_common.memoised)


def rotation_matrices() -> st.SearchStrategy[npt.NDArray[np.float64]]:
    """The book's passive rotation matrices ^A R^O, shape ``(3, 3)``.

    Regimes (:data:`MATRIX_REGIMES`): ``identity``; ``signed-permutation`` (an
    exact turn by a multiple of π/2: a permutation matrix with signs and
    determinant +1); ``sign-flip`` (a half turn 2 n nᵀ − 1 about an axis n in a
    coordinate plane, exact zeros: gimbal lock θ = π exactly when the plane is
    x-y); ``rotvec``, ``euler`` and ``quaternion``: the matrix of a
    drawn :func:`rotvecs`, :func:`euler_angles` or :func:`quaternions` by
    :func:`~mechanics.rotation.matrix_from_rotvec`,
    :func:`~mechanics.rotation.matrix_from_euler` or
    :func:`~mechanics.rotation.matrix_from_quat`, so every hard regime of those
    strategies reaches the matrices.  Shrinks toward the identity.

    Returns
    -------
    SearchStrategy of ndarray, shape (3, 3)
        float64 rotation matrices ^A R^O.

    Examples
    --------
    A matrix and the matrix of its quaternion agree within the round-trip accuracy:

    >>> from hypothesis import given, settings
    >>> from mechanics.testing import assert_rotations_close
    >>> @settings(max_examples=50, derandomize=True)
    ... @given(rotation_matrices())
    ... def test_round_trip(R):
    ...     assert_rotations_close(_rot.matrix_from_quat(_rot.quat_from_matrix(R)), R)
    >>> test_round_trip()
    """
    perms = st.permutations([0, 1, 2])
    signs = st.tuples(*(st.sampled_from((1.0, -1.0)),) * 2)
    vecs, eulers, quats = rotvecs(), euler_angles(), quaternions()  # built once, not per draw

    @st.composite
    def draw_matrix(draw: st.DrawFn) -> _Array:
        regime = draw(st.sampled_from(MATRIX_REGIMES))
        event(f"rotation_matrices: {regime}")
        if regime == "identity":
            return np.eye(3)
        if regime == "signed-permutation":
            P = np.eye(3)[draw(perms)]
            s1, s2 = draw(signs)
            # The third sign makes det = +1: valid by construction.
            s3 = s1 * s2 * float(np.linalg.det(P))
            return np.diag([s1, s2, s3]) @ P
        if regime == "sign-flip":
            # 2 n nᵀ − 1 for n = (cos α, sin α, 0) rolled into a coordinate plane: a
            # half turn whose off-plane zeros and −1 are exact, the block symmetric.
            alpha = draw(st.floats(-math.pi, math.pi))
            c, s = math.cos(alpha), math.sin(alpha)
            R = np.array(
                [[2 * c * c - 1, 2 * c * s, 0.0], [2 * c * s, 2 * s * s - 1, 0.0], [0.0, 0.0, -1.0]]
            )
            k = draw(st.integers(0, 2))
            return np.roll(R, (k, k), axis=(0, 1))
        if regime == "rotvec":
            return _rot.matrix_from_rotvec(draw(vecs))
        if regime == "euler":
            return _rot.matrix_from_euler(*draw(eulers))
        return _rot.matrix_from_quat(draw(quats))

    return draw_matrix()


rotation_matrices = memoised(rotation_matrices)  # one strategy per arguments (_common.memoised)
