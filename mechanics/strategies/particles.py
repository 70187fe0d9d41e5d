"""Hypothesis strategies for particle systems and their internal forces.

Conventions
-----------
- Shapes are those of :mod:`mechanics.particles`: masses ``(N,)``, positions
  and velocities ``(N, 3)``, pair forces ``(N, N, 3)`` with ``f[k, j]`` the
  force on k from j.  Everything is float64.
- **Valid by construction.**  Masses are drawn > 0 (so the total mass is never
  zero); pair forces are drawn for k < j and mirrored, f_jk = −f_kj (Newton's
  third law, 1.19), and a central force is a symmetric scalar times r_kj.
- **Hard regimes are explicit branches**, drawn first with ``st.sampled_from``
  (the first is the simple one, so that failures shrink toward unit masses at
  rest near the origin) and recorded with :func:`hypothesis.event` as
  ``"<strategy>: <regime>"``.  ``tests/strategies/test_particles_strategy_quality.py``
  proves every regime is reached.
- Bounds are keyword-only; bad arguments raise
  :class:`hypothesis.errors.InvalidArgument` quoting the value.

Examples
--------
>>> from hypothesis import given
>>> from mechanics.particles import centre_of_mass
>>> @given(particle_systems(max_particles=5))
... def test_centre_of_mass_is_finite(s):
...     assert np.isfinite(centre_of_mass(s.m, s.r)).all()
>>> test_centre_of_mass_is_finite()
"""

from __future__ import annotations

import math
from collections.abc import Callable, Hashable, Iterable
from typing import Any, NamedTuple, TypeAlias, TypeVar

import numpy as np
import numpy.typing as npt
from hypothesis import event
from hypothesis import strategies as st
from hypothesis.errors import InvalidArgument

from ._common import check_int, check_real, check_regimes, log_uniform, memoised

_Array: TypeAlias = npt.NDArray[np.float64]
_T = TypeVar("_T")

__all__ = [
    "FAR_OFFSET",
    "MASS_REGIMES",
    "PAIR_FORCE_REGIMES",
    "SYSTEM_REGIMES",
    "ParticleSystem",
    "masses",
    "pair_forces",
    "particle_systems",
]


#: Regimes of :func:`masses`: all 1.0; all equal to one drawn value; each
#: log-uniform in the bounds; "extreme-ratio": every mass at one of the two
#: bounds (both present when N ≥ 2), a ratio of 1e12 with the default bounds.
MASS_REGIMES = ("unit", "equal", "log-uniform", "extreme-ratio")

#: Regimes of :func:`particle_systems`: "simple" (unit masses, coordinates and
#: velocities in [−1, 1]); "generic" (masses of any :data:`MASS_REGIMES`,
#: coordinates in [−10, 10], velocities in [−10, 10]); "wide-mass-ratio" (the
#: extreme-ratio masses); "far-offset" (every particle within 1 of a point at
#: distance ~:data:`FAR_OFFSET` from the origin); "fast-translation" (a common
#: velocity of magnitude ~1e6 plus internal velocities in [−1, 1]).
SYSTEM_REGIMES = ("simple", "generic", "wide-mass-ratio", "far-offset", "fast-translation")

#: The far-offset regime puts the system this far from the origin (per
#: coordinate, in magnitude): ulp(1e8) = 1.5e-8, so positions carry only about
#: 8 significant digits of their offsets from G.
FAR_OFFSET = 1e8

_FAST_SPEED = 1e6

#: Regimes of :func:`pair_forces`: no internal forces; central forces
#: f_kj = s_kj r_kj with s symmetric (f_kj ∥ r_kj); non-central forces (a
#: central part plus a part perpendicular to r_kj of magnitude ≥ 5e-4 of the bound).
PAIR_FORCE_REGIMES = ("none", "central", "non-central")


class ParticleSystem(NamedTuple):
    """Masses ``(N,)``, positions ``(N, 3)`` and velocities ``(N, 3)``.

    A named tuple, as :func:`particle_systems` draws it: it unpacks as ``m, r, v``; its
    constructor checks nothing.

    Parameters
    ----------
    m : ndarray, shape (N,)
        Masses (kg), > 0.
    r : ndarray, shape (N, 3)
        Positions (m).
    v : ndarray, shape (N, 3)
        Velocities (m/s).

    Examples
    --------
    >>> s = ParticleSystem(np.ones(2), np.zeros((2, 3)), np.zeros((2, 3)))
    >>> m, r, v = s
    >>> m is s.m is s[0], r.shape
    (True, (2, 3))
    """

    m: npt.NDArray[np.float64]
    r: npt.NDArray[np.float64]
    v: npt.NDArray[np.float64]


# ------------------------------------------------------------------ validation


def _check_mass_bounds(
    min_value: float, max_value: float, names: tuple[str, str]
) -> tuple[float, float]:
    """The bounds as floats, 0 < lo ≤ hi; errors name the caller's parameters ``names``."""
    lo_name, hi_name = names
    lo = check_real(min_value, lo_name)
    hi = check_real(max_value, hi_name)
    if lo <= 0:
        raise InvalidArgument(f"{lo_name}={min_value!r} must be > 0 (masses are drawn positive)")
    if lo > hi:
        raise InvalidArgument(f"{lo_name}={min_value!r} exceeds {hi_name}={max_value!r}")
    return lo, hi


def _signed_units(k: int) -> st.SearchStrategy[_Array]:
    """k floats in [−1, 1), from one draw of 8k bytes (int64 / 2**63).

    One ``st.binary`` draw instead of k ``st.floats`` draws: 50 particles need
    hundreds of coordinates, and per-float draws made generation the slowest
    part of the property tests (hypothesis' too_slow health check).  Zero bytes
    give 0, so examples shrink toward the origin.
    """
    return st.binary(min_size=8 * k, max_size=8 * k).map(
        lambda bs: np.frombuffer(bs, dtype="<i8").astype(np.float64) * 2.0**-63
    )


def _vectors(n: int, bound: float) -> st.SearchStrategy[_Array]:
    """(n, 3) arrays of floats in [−bound, bound), shrinking toward 0."""
    return _signed_units(3 * n).map(lambda u: bound * u.reshape(n, 3))


def _log_uniform_array(n: int, lo: float, hi: float) -> st.SearchStrategy[_Array]:
    """n floats in [lo, hi], log-uniform, from one byte draw (shrinking toward ``lo``)."""
    a, b = math.log10(lo), math.log10(hi)
    return _signed_units(n).map(lambda u: np.clip(10.0 ** (a + (b - a) * np.abs(u)), lo, hi))


def _equal_masses(lo: float, hi: float) -> st.SearchStrategy[float]:
    """The one mass of the ``equal`` regime, log-uniform in [lo, hi], shrinking toward lo."""
    return log_uniform(lo, hi, shrink_to="lo")


class _Built:
    """The strategies a factory's draws need for a drawn size n, built once per size and
    factory (not per draw: a strategy built in a draw costs more than the draw; nor
    shared between factories, so each strategy object stays independent)."""

    def __init__(self) -> None:
        self._made: dict[tuple[Hashable, ...], st.SearchStrategy[Any]] = {}

    def get(
        self, make: Callable[..., st.SearchStrategy[_T]], *args: Hashable
    ) -> st.SearchStrategy[_T]:
        key = (make, *args)
        s = self._made.get(key)
        if s is None:
            s = self._made[key] = make(*args)
        return s


# ---------------------------------------------------------------------- masses


def _mass_array(
    draw: st.DrawFn, built: _Built, n: int, lo: float, hi: float, regime: str
) -> _Array:
    if regime == "unit":
        return np.ones(n)
    if regime == "equal":
        return np.full(n, draw(built.get(_equal_masses, lo, hi)))
    if regime == "log-uniform":
        return draw(built.get(_log_uniform_array, n, lo, hi))
    # extreme-ratio: each at a bound; the first two differ, so both are present.
    m = np.where(draw(built.get(_signed_units, n)) < 0, hi, lo)
    if n >= 2:
        m[0], m[1] = lo, hi
    return m


def masses(
    *,
    min_particles: int = 1,
    max_particles: int = 50,
    min_value: float = 1e-6,
    max_value: float = 1e6,
    regimes: Iterable[str] | None = None,
) -> st.SearchStrategy[npt.NDArray[np.float64]]:
    """Mass vectors ``(N,)``, each mass in [``min_value``, ``max_value``] (> 0).

    Regimes (:data:`MASS_REGIMES`): ``unit`` (all 1.0, when 1 is in the
    bounds), ``equal``, ``log-uniform``, ``extreme-ratio`` (masses at the two
    bounds: 1e-6 and 1e6 by default).  Shrinks toward one unit mass.

    Parameters
    ----------
    min_particles, max_particles : int
        Bounds of N, 1 ≤ ``min_particles`` ≤ ``max_particles``.
    min_value, max_value : float
        Bounds of each mass (kg), finite, 0 < ``min_value`` ≤ ``max_value``.
    regimes : iterable of str, optional
        Some of :data:`MASS_REGIMES` (default all; ``unit`` only where 1 is in the bounds).

    Returns
    -------
    SearchStrategy of ndarray, shape (N,)
        float64 masses (kg).

    Raises
    ------
    InvalidArgument
        A count not an integer ≥ 1, or ``min_particles`` > ``max_particles``; a mass bound
        not a finite real number, ``min_value`` ≤ 0 or ``min_value`` > ``max_value``;
        ``regimes`` a string, empty, with an unknown name, or ``unit`` alone without 1 in
        the bounds.

    Examples
    --------
    >>> from hypothesis import given, settings
    >>> @settings(max_examples=30, derandomize=True)
    ... @given(masses(max_particles=4, min_value=1.0, max_value=2.0))
    ... def test_bounds(m):
    ...     assert 1 <= m.shape[0] <= 4 and ((1.0 <= m) & (m <= 2.0)).all()
    >>> test_bounds()
    """
    nlo = check_int(min_particles, "min_particles", 1)
    nhi = check_int(max_particles, "max_particles", 1)
    if nlo > nhi:
        raise InvalidArgument(
            f"min_particles={min_particles!r} exceeds max_particles={max_particles!r}"
        )
    lo, hi = _check_mass_bounds(min_value, max_value, ("min_value", "max_value"))
    names = check_regimes(regimes, MASS_REGIMES, "masses")
    if not lo <= 1.0 <= hi:
        names = tuple(r for r in names if r != "unit")
        if not names:
            raise InvalidArgument(f"regimes={regimes!r}: 'unit' needs 1.0 in [{lo}, {hi}]")

    built = _Built()

    @st.composite
    def draw_masses(draw: st.DrawFn) -> _Array:
        n = draw(st.integers(nlo, nhi))
        regime = draw(st.sampled_from(names))
        event(f"masses: {regime}")
        return _mass_array(draw, built, n, lo, hi, regime)

    return draw_masses()


masses = memoised(masses)  # one strategy per arguments (_common.memoised)


# ------------------------------------------------------------ particle systems


def particle_systems(
    *,
    min_particles: int = 1,
    max_particles: int = 50,
    min_mass: float = 1e-6,
    max_mass: float = 1e6,
    regimes: Iterable[str] | None = None,
) -> st.SearchStrategy[ParticleSystem]:
    """Particle systems (m, r, v) with 1 … 50 particles, masses 1e-6 … 1e6.

    Regimes (:data:`SYSTEM_REGIMES`): ``simple``, ``generic``,
    ``wide-mass-ratio``, ``far-offset`` (within 1 of a point whose coordinates
    have magnitude :data:`FAR_OFFSET`, signs drawn) and ``fast-translation``
    (common velocity of magnitude ~1e6).  ``regimes`` restricts the draw.
    Shrinks toward one unit mass at rest at the origin.

    Parameters
    ----------
    min_particles, max_particles : int
        Bounds of N, 1 ≤ ``min_particles`` ≤ ``max_particles`` (default 1 … 50).
    min_mass, max_mass : float
        Bounds of each mass (kg), finite, 0 < ``min_mass`` ≤ ``max_mass``.
    regimes : iterable of str, optional
        Some of :data:`SYSTEM_REGIMES` (default all).

    Returns
    -------
    SearchStrategy of ParticleSystem
        :class:`ParticleSystem` records (m, r, v).

    Raises
    ------
    InvalidArgument
        A count not an integer ≥ 1, or ``min_particles`` > ``max_particles``; a mass bound
        not a finite real number, ``min_mass`` ≤ 0 or ``min_mass`` > ``max_mass``;
        ``regimes`` a string, empty or with an unknown name.

    Examples
    --------
    p = M v_G (1.7), the two sides computed apart:

    >>> from hypothesis import given, settings
    >>> from mechanics.particles import centre_of_mass_velocity, momentum, total_mass
    >>> @settings(max_examples=30, derandomize=True)
    ... @given(particle_systems(max_particles=5, regimes=["simple", "generic"]))
    ... def test_momentum(s):
    ...     p = momentum(s.m, s.v)
    ...     assert np.allclose(total_mass(s.m) * centre_of_mass_velocity(s.m, s.v), p)
    >>> test_momentum()
    """
    nlo = check_int(min_particles, "min_particles", 1)
    nhi = check_int(max_particles, "max_particles", 1)
    if nlo > nhi:
        raise InvalidArgument(
            f"min_particles={min_particles!r} exceeds max_particles={max_particles!r}"
        )
    lo, hi = _check_mass_bounds(min_mass, max_mass, ("min_mass", "max_mass"))
    names = check_regimes(regimes, SYSTEM_REGIMES, "particle_systems")
    signs = st.tuples(*(st.sampled_from((1.0, -1.0)),) * 3).map(np.array)
    unit_ok = lo <= 1.0 <= hi
    mass_regimes = tuple(r for r in MASS_REGIMES if unit_ok or r != "unit")
    built = _Built()

    def vectors(n: int, bound: float) -> st.SearchStrategy[_Array]:
        return built.get(_vectors, n, bound)

    @st.composite
    def draw_system(draw: st.DrawFn) -> ParticleSystem:
        n = draw(st.integers(nlo, nhi))
        regime = draw(st.sampled_from(names))
        event(f"particle_systems: {regime}")
        if regime == "simple":
            m = _mass_array(draw, built, n, lo, hi, "unit" if unit_ok else "equal")
            return ParticleSystem(m, draw(vectors(n, 1.0)), draw(vectors(n, 1.0)))
        if regime == "wide-mass-ratio":
            m = _mass_array(draw, built, n, lo, hi, "extreme-ratio")
        else:
            m = _mass_array(draw, built, n, lo, hi, draw(st.sampled_from(mass_regimes)))
        if regime == "far-offset":
            centre = FAR_OFFSET * draw(signs) * draw(st.floats(1.0, 2.0))
            return ParticleSystem(m, centre + draw(vectors(n, 1.0)), draw(vectors(n, 1.0)))
        if regime == "fast-translation":
            V = _FAST_SPEED * draw(signs) * draw(st.floats(1.0, 2.0))
            return ParticleSystem(m, draw(vectors(n, 10.0)), V + draw(vectors(n, 1.0)))
        return ParticleSystem(m, draw(vectors(n, 10.0)), draw(vectors(n, 10.0)))

    return draw_system()


particle_systems = memoised(particle_systems)  # one strategy per arguments (_common.memoised)


# ------------------------------------------------------------------ pair forces


def pair_forces(
    r: npt.ArrayLike, *, max_magnitude: float = 1e3, regimes: Iterable[str] | None = None
) -> st.SearchStrategy[npt.NDArray[np.float64]]:
    """Internal pair forces ``(N, N, 3)`` between particles at ``r`` ``(N, 3)``.

    ``f[k, j]`` is the force on k from j; f_jk = −f_kj and f_kk = 0 by
    construction (1.19).  Regimes (:data:`PAIR_FORCE_REGIMES`): ``none``;
    ``central``: f_kj = s_kj r_kj, s symmetric, |f_kj| ≤ ``max_magnitude``
    (zero for coincident particles); ``non-central``: a central part plus a
    part perpendicular to r_kj of magnitude in [5e-4, 0.25] × ``max_magnitude``
    (along any direction for coincident particles).  Shrinks toward no force.

    Parameters
    ----------
    r : array_like, shape (N, 3)
        Positions of the particles (m), finite, N ≥ 1.
    max_magnitude : float
        The bound on |f_kj| (N), finite and > 0.
    regimes : iterable of str, optional
        Some of :data:`PAIR_FORCE_REGIMES` (default all).

    Returns
    -------
    SearchStrategy of ndarray, shape (N, N, 3)
        float64 forces, ``f[k, j]`` on k from j (N).

    Raises
    ------
    InvalidArgument
        ``r`` not of shape (N, 3) with N ≥ 1 or not finite; ``max_magnitude`` not a finite
        real number > 0; ``regimes`` a string, empty or with an unknown name.

    Examples
    --------
    Newton's third law (1.19), exactly:

    >>> from hypothesis import given, settings
    >>> r = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 2.0, 0.0]]
    >>> @settings(max_examples=30, derandomize=True)
    ... @given(pair_forces(r))
    ... def test_third_law(f):
    ...     assert (f == -np.swapaxes(f, 0, 1)).all()
    >>> test_third_law()
    """
    rr = np.asarray(r, dtype=np.float64)
    if rr.ndim != 2 or rr.shape[1] != 3 or rr.shape[0] < 1:
        raise InvalidArgument(f"r with shape {rr.shape!r} must be (N, 3) with N >= 1")
    if not np.isfinite(rr).all():
        raise InvalidArgument(f"r={rr.tolist()!r} must be finite")
    fmax = check_real(max_magnitude, "max_magnitude")
    if fmax <= 0:
        raise InvalidArgument(f"max_magnitude={max_magnitude!r} must be > 0")
    names = check_regimes(regimes, PAIR_FORCE_REGIMES, "pair_forces")
    n = rr.shape[0]
    units = _signed_units(n)  # built once, not per draw

    @st.composite
    def draw_forces(draw: st.DrawFn) -> _Array:
        regime = draw(st.sampled_from(names))
        event(f"pair_forces: {regime}")
        if regime == "none":
            return np.zeros((n, n, 3))
        # Symmetric pair parameters from per-particle draws (O(N) draws, not
        # O(N²)): t_kj = (u_k + u_j)/2 in [−1, 1], the same for (k, j) and (j, k).
        u = draw(units)
        if regime == "non-central":
            w = 1e-3 + (0.5 - 1e-3) * np.abs(draw(units))
            ang = math.pi * draw(units)
        d = rr[:, None, :] - rr[None, :, :]  # r_kj
        dist = np.linalg.norm(d, axis=-1)
        apart = dist > 0
        e = np.where(apart[..., None], d / np.where(apart, dist, 1.0)[..., None], [1.0, 0.0, 0.0])
        t = 0.5 * (u[:, None] + u[None, :])
        f = np.where(apart[..., None], (0.5 * fmax * t)[..., None] * e, 0.0)
        if regime == "non-central":
            # Unit vectors normal to e: e × (the coordinate axis least aligned with e).
            a = np.zeros_like(e)
            np.put_along_axis(a, np.argmin(np.abs(e), axis=-1)[..., None], 1.0, axis=-1)
            n1 = np.cross(e, a)
            n1 /= np.linalg.norm(n1, axis=-1, keepdims=True)
            n2 = np.cross(e, n1)
            phi = (ang[:, None] + ang[None, :])[..., None]
            mag = (0.5 * fmax * 0.5 * (w[:, None] + w[None, :]))[..., None]
            f = f + mag * (np.cos(phi) * n1 + np.sin(phi) * n2)
        # Newton's third law by construction: keep k < j, mirror to j > k.
        upper = np.triu(np.ones((n, n), dtype=bool), 1)[..., None]
        f = np.where(upper, f, 0.0)
        return f - np.swapaxes(f, 0, 1)

    return draw_forces()


pair_forces = memoised(pair_forces)  # one strategy per arguments (_common.memoised)
