"""What a run returns: samples, a dense state, events and the quantities its effects
conserve.  Used by the engine and the effects; imports nothing
from the package.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, TypeAlias, TypeVar

import numpy as np
import numpy.typing as npt

from .._floats import EPS
from .vectors import FloatArray, Times

if TYPE_CHECKING:  # for annotations only: a layer above
    from .spec import Scene

#: a dense solution: the state at a time, (size,), or at an array of k times, (k, size)
Dense: TypeAlias = Callable[[Times], FloatArray]
#: one piece of a run's dense solution: (t_a, t_b, dense)
Segment: TypeAlias = tuple[float, float, Dense]
_F = TypeVar("_F", bound=Callable[..., Any])

__all__ = [
    "CONSERVED_RTOL_INTEGRATED",
    "EPS",
    "Event",
    "Trajectory",
    "dense_from_segments",
    "energy_scale",
    "sample_dense",
    "sample_segments",
    "tolerance_scale",
    "vectorized",
]

#: the integrator's default rtol and atol (the tolerances of conserved quantities in
#: :mod:`mechanics.scenes.result` are measured at this setting and scale with it)
DEFAULT_TOL = 1e-12
#: DOP853 at rtol = atol = 1e-12 over the scene's duration (measured worst ≈ 1e-11); a
#: scene with looser rtol/atol gets this × (its tolerance / 1e-12), :func:`tolerance_scale`:
#: the drift grows in proportion (measured 14 × rtol for a spring oscillator at rtol 1e-8)
CONSERVED_RTOL_INTEGRATED = 2**20 * EPS  # ≈ 2.3e-10


def tolerance_scale(scene: Scene) -> float:
    """How much looser than the default the scene's integration is.

    The larger of 1, rtol / 1e-12 and atol / 1e-12 (the integration's drifts grow in
    proportion: the conserved tolerance ``CONSERVED_RTOL_INTEGRATED`` is scaled by it).

    Parameters
    ----------
    scene : Scene
        The validated scene (:class:`mechanics.scenes.spec.Scene`): its ``rtol`` and
        ``atol``, each in (0, 1e-3].

    Returns
    -------
    float
        max(1, rtol / 1e-12, atol / 1e-12), ≥ 1 (dimensionless).

    Examples
    --------
    The default tolerances give 1; an rtol of 1e-10 gives 1e-10 / 1e-12 = 100:

    >>> from mechanics.scenes.spec import parse_scene
    >>> sc = parse_scene({"scene": {"name": "fall", "duration": 1.0, "samples": 3},
    ...                   "bodies": [{"name": "ball", "shape": "point", "mass": 2.0,
    ...                               "initial": {"position": [0.0, 0.0, 4.0]}}],
    ...                   "effects": [{"type": "gravity", "g": 8.0}]})
    >>> loose = parse_scene({**sc.raw, "scene": {**sc.raw["scene"], "rtol": 1e-10}})
    >>> tolerance_scale(sc), round(tolerance_scale(loose), 9)
    (1.0, 100.0)
    """
    return max(1.0, scene.rtol / DEFAULT_TOL, scene.atol / DEFAULT_TOL)


@dataclass
class Event:
    """An event of the run: its time, kind (impact, burn_out, rolling, ...) and details.

    Parameters
    ----------
    t : float
        The time of the event, s, in [0, duration].
    kind : str
        What happened: ``"impact"``, ``"burn_out"``, ``"rolling"``, ``"rest"``,
        ``"lift_off"``, ...
    detail : dict[str, Any], optional
        The event's fields (for an impact: the speeds, the energies and momenta before
        and after, ...), written to the run's record. Default empty.

    Examples
    --------
    A point dropped from 4.905 m under g = 9.81 m/s² reaches the floor at
    t = √(2 h / g) = 1 s:

    >>> from mechanics.scenes.spec import parse_scene
    >>> from mechanics.scenes.simulate import simulate
    >>> sc = parse_scene({"scene": {"name": "drop", "duration": 1.5, "samples": 4},
    ...     "bodies": [{"name": "ball", "shape": "point", "mass": 2.0,
    ...                 "initial": {"position": [0.0, 0.0, 4.905]}}],
    ...     "effects": [{"type": "gravity", "g": 9.81}, {"type": "impact", "body": "ball",
    ...         "plane_point": [0.0, 0.0, 0.0], "plane_normal": [0.0, 0.0, 1.0],
    ...         "restitution": 0.5}]})
    >>> [(e.t, e.kind) for e in simulate(sc).events], Event(1.0, "impact").detail
    ([(1.0, 'impact')], {})
    """

    t: float
    kind: str
    detail: dict[str, Any] = field(default_factory=dict)


@dataclass
class Trajectory:
    """Samples, a dense state, events and the conserved quantities of a run.

    ``conserved`` maps a name to its samples; each is checked within the segments
    between events, except those in ``conserved_across_events`` (which every impulse
    keeps too, e.g. the momentum of two bodies that collide), checked over the run.
    The engine (:func:`mechanics.scenes.simulate.simulate`) builds it; the constructor
    stores what it is given and checks nothing.

    Parameters
    ----------
    t : ndarray, shape (k,)
        The sample times, s, increasing from 0 to the scene's duration.
    series : dict[str, ndarray], each of shape (k, ...)
        Named series of the state at the samples (``"z"``, ``"vz"``, ``"E"``, ...), in
        SI units.
    events : list[Event]
        The run's events in time order.
    method : str
        How the run was computed, e.g. ``"exact: free flight under uniform gravity"``
        or ``"integrated: DOP853 ..."``.
    state_at : Callable[[float], dict[str, float]]
        The dense state: a time (s) -> the named coordinates there.
    conserved : dict[str, ndarray], each of shape (k,), optional
        Each quantity the effects conserve -> its samples. Default none.
    conserved_from : dict[str, float], optional
        The time (s) from which a conserved quantity holds (energy once rolling);
        default 0 for each.
    conserved_across_events : frozenset[str], optional
        The conserved quantities every impulse keeps too (checked over the whole run).
        Default none.
    scales : dict[str, float], optional
        The size of the terms of each conserved quantity and reaction (what its drift
        and rounding are relative to). Default none.
    snapshot : Snapshot or None, optional
        Every body's r, v, R_A_O, ω_A and m at the sample times (for
        :mod:`mechanics.conformance`). Default None.
    gaps : dict[str, ndarray], each of shape (k,), optional
        Each impact pair -> its smallest gap (m) at every sample. Default none.
    resting_gaps : dict[str, float], optional
        Each impact pair that rests at some sample -> the largest |gap| (m) of its
        resting contacts there. Default none.
    support_law : dict[str, float], optional
        Each resting pair -> its worst breach of the support's law (presses, inside the
        cone), relative. Default none.
    energy_rise : float or None, optional
        The largest rise of E(t) (J) over any earlier sample where only potentials and
        effects that never add energy act; None (default): no such claim.
    length_scale : float, optional
        The largest |coordinate| plus the largest radius and body extent, m (what the
        gaps round relative to). Default 0.
    orthogonality : float or None, optional
        max |R Rᵀ − 1| of the rigid bodies' attitudes; None (default): no rigid body.
    derived : list[tuple[str, float or None, float or None]], optional
        (name, exact, measured) rows of the derived quantities (:mod:`.derived`).
        Default none.
    splitting : dict[str, float] or None, optional
        A splitting's ``order``, ``step`` and ``E_drift_half`` (the energy drift at half
        the step); None (default) for any other method.

    Examples
    --------
    A point falling from 4 m under g = 8 m/s²: z = 4 − 4 t², sampled and read off the
    dense state at t = 0.5 s; its energy m g z + ½ m v² = 64 J throughout:

    >>> from mechanics.scenes.spec import parse_scene
    >>> sc = parse_scene({"scene": {"name": "fall", "duration": 1.0, "samples": 3},
    ...                   "bodies": [{"name": "ball", "shape": "point", "mass": 2.0,
    ...                               "initial": {"position": [0.0, 0.0, 4.0]}}],
    ...                   "effects": [{"type": "gravity", "g": 8.0}]})
    >>> from mechanics.scenes.simulate import simulate
    >>> tr = simulate(sc)
    >>> tr.series["z"].tolist(), tr.state_at(0.5)["z"], tr.conserved["E"].tolist()
    ([4.0, 3.0, 0.0], 3.0, [64.0, 64.0, 64.0])
    """

    t: FloatArray
    series: dict[str, FloatArray]
    events: list[Event]
    method: str
    state_at: Callable[[float], dict[str, float]]
    conserved: dict[str, FloatArray] = field(default_factory=dict)
    #: time from which a conserved quantity holds (e.g. energy once rolling); default 0
    conserved_from: dict[str, float] = field(default_factory=dict)
    conserved_across_events: frozenset[str] = frozenset()
    #: the size of the terms of each conserved quantity and reaction (what its drift
    #: and rounding are relative to)
    scales: dict[str, float] = field(default_factory=dict)
    #: every body's r, v, R_A_O, ω_A and m at the sample times (for mechanics.conformance)
    snapshot: Any = None
    #: each impact pair's smallest gap at every sample (its interpenetration check)
    gaps: dict[str, FloatArray] = field(default_factory=dict)
    #: each impact pair that rests at some sample: the largest |gap| of its resting
    #: contacts there (held at zero by the support: their self-check)
    resting_gaps: dict[str, float] = field(default_factory=dict)
    #: each resting pair's worst breach of the support's law (presses, inside the cone)
    support_law: dict[str, float] = field(default_factory=dict)
    #: the largest rise of E(t) over any earlier sample, where only potentials and
    #: effects that never add energy act (None: the scene makes no such claim)
    energy_rise: float | None = None
    #: the largest |coordinate| plus the largest radius and body extent (what the gaps
    #: round relative to)
    length_scale: float = 0.0
    #: max |R Rᵀ − 1| of the rigid bodies' attitudes (None: no rigid body)
    orthogonality: float | None = None
    #: (name, exact, measured) rows of the derived quantities (:mod:`.derived`)
    derived: list[tuple[str, float | None, float | None]] = field(default_factory=list)
    #: a splitting's order, step and the energy drift at half the step (None otherwise)
    splitting: dict[str, float] | None = None

    def segments(self, name: str = "") -> list[tuple[float, float]]:
        """The intervals over which ``name`` must be constant: between events, or the
        whole run for a quantity the events keep too."""
        if name in self.conserved_across_events:
            return [(0.0, math.inf)]
        cuts = [0.0, *sorted(e.t for e in self.events), math.inf]
        return list(itertools.pairwise(cuts))


def dense_from_segments(segs: Sequence[Segment]) -> Dense:
    """One dense function from (t_a, t_b, dense) pieces in time order.

    Parameters
    ----------
    segs : Sequence[Segment]
        The pieces ``(t_a, t_b, dense)`` in time order, at least one; ``dense`` maps a
        time (s) to the state there.

    Returns
    -------
    Dense
        t -> the state of the piece whose start is the last at or before t (the first
        piece before its start); not vectorised (one time a call).

    Examples
    --------
    Two pieces meeting at t = 1: each time is answered by its own piece.

    >>> f = dense_from_segments([(0.0, 1.0, lambda t: np.array([t])),
    ...                          (1.0, 2.0, lambda t: np.array([10.0 * t]))])
    >>> f(0.5).tolist(), f(1.5).tolist(), f(1.0).tolist()
    ([0.5], [15.0], [10.0])
    """
    starts = np.array([a for a, _, _ in segs])

    def at(t: Times) -> FloatArray:
        k = max(int(np.searchsorted(starts, t, side="right")) - 1, 0)
        return segs[k][2](t)

    return at


def vectorized(f: _F) -> _F:
    """Mark a dense function as taking an array of times (one call for all samples).

    A decorator: :func:`sample_dense` then calls it once with all the times.

    Parameters
    ----------
    f : Callable
        A dense function that takes an array of times (k,) and returns the states
        (k, size).

    Returns
    -------
    Callable
        ``f`` itself, with the attribute ``vectorized = True``.

    Raises
    ------
    AttributeError
        Where ``f`` takes no attributes (a builtin function).

    Examples
    --------
    Sampled in one call or time by time, the same samples:

    >>> f = vectorized(lambda t: np.stack([t, 2.0 * t], axis=-1))
    >>> t = np.array([0.0, 0.5, 1.0])
    >>> bool(np.array_equal(sample_dense(f, t), [f(x) for x in t])), f.vectorized
    (True, True)
    """
    f.vectorized = True  # type: ignore[attr-defined]  # a function given an attribute
    return f


def sample_dense(dense: Dense, t: FloatArray) -> FloatArray:
    """Samples of a dense solution, shape (len(t), n): one call if it is vectorised.

    Parameters
    ----------
    dense : Dense
        The dense solution: a time (s) -> the state (n,), or, marked by
        :func:`vectorized`, an array of times -> the states.
    t : ndarray, shape (k,)
        The sample times, s.

    Returns
    -------
    ndarray, shape (k, n)
        The states at the times ``t``.

    Raises
    ------
    TypeError
        Where ``t`` is a scalar and ``dense`` is not vectorised (it is iterated).

    Examples
    --------
    A state (t, t²) sampled time by time, and by one vectorised call:

    >>> t = np.array([0.0, 0.5, 1.0])
    >>> one = lambda x: np.array([x, x * x])
    >>> sample_dense(one, t).tolist()
    [[0.0, 0.0], [0.5, 0.25], [1.0, 1.0]]
    >>> bool(np.array_equal(sample_dense(vectorized(np.vectorize(one, signature="()->(n)")), t),
    ...                     sample_dense(one, t)))
    True
    """
    if getattr(dense, "vectorized", False):
        return np.asarray(dense(t), dtype=float)
    return np.array([dense(tt) for tt in t])


def sample_segments(segs: Sequence[Segment], t: npt.ArrayLike) -> FloatArray | None:
    """Samples (len(t), size) of (t_a, t_b, dense) pieces, each from the piece it falls in.

    The last piece also takes t_b (and a time before the first piece's start goes to
    the first piece); one call per vectorised piece (:func:`vectorized`).

    Parameters
    ----------
    segs : Sequence[Segment]
        The pieces ``(t_a, t_b, dense)`` in time order, at least one.
    t : array_like, shape (k,)
        The sample times, s.

    Returns
    -------
    ndarray, shape (k, size), or None
        The states at the times ``t``; None for no times (a scene has at least 2
        samples).

    Raises
    ------
    IndexError
        Where ``segs`` is empty and ``t`` is not.

    Examples
    --------
    The same samples as :func:`dense_from_segments` gives time by time:

    >>> segs = [(0.0, 1.0, lambda t: np.array([t])),
    ...         (1.0, 2.0, vectorized(lambda t: 10.0 * np.asarray(t)[..., None]))]
    >>> t = [0.0, 0.5, 1.5, 2.0]
    >>> sample_segments(segs, t).tolist()
    [[0.0], [0.5], [15.0], [20.0]]
    >>> f = dense_from_segments(segs)
    >>> bool(np.array_equal(sample_segments(segs, t), [f(x) for x in t]))
    True
    """
    t = np.asarray(t, dtype=float)
    starts = np.array([a for a, _, _ in segs])
    which = np.maximum(np.searchsorted(starts, t, side="right") - 1, 0)
    out: FloatArray | None = None
    for k in np.unique(which):
        sel = np.nonzero(which == k)[0]
        vals = sample_dense(segs[k][2], t[sel])
        if out is None:
            out = np.empty((t.size, vals.shape[-1]))
        out[sel] = vals
    return out


def energy_scale(KE: FloatArray, E: npt.ArrayLike) -> float:
    """max |T| + max |V|: the size of the terms whose sum is the energy.

    What an energy's drift and rounding are relative to (V = E − T at each sample).

    Parameters
    ----------
    KE : ndarray, shape (k,)
        The kinetic energy T at the samples, J.
    E : array_like, shape (k,)
        The total energy E = T + V at the same samples, J.

    Returns
    -------
    float
        max |T| + max |E − T|, J, ≥ 0.

    Raises
    ------
    ValueError
        Where there are no samples (k = 0) or the shapes do not broadcast.

    Examples
    --------
    A fall from 4 m: T grows from 0 to 64 J while V falls from 64 J to 0, at E = 64 J:

    >>> T = np.array([0.0, 16.0, 64.0])
    >>> energy_scale(T, [64.0, 64.0, 64.0]), float(np.max(T) + np.max(64.0 - T))
    (128.0, 128.0)
    """
    return float(np.max(np.abs(KE)) + np.max(np.abs(np.asarray(E) - KE)))
