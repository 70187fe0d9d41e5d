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
    """How much looser than the default the scene's integration is: the larger of 1,
    rtol / 1e-12 and atol / 1e-12 (the integration's drifts grow in proportion)."""
    return max(1.0, scene.rtol / DEFAULT_TOL, scene.atol / DEFAULT_TOL)


@dataclass
class Event:
    """An event of the run: its time, kind (impact, burn_out, rolling, ...) and details."""

    t: float
    kind: str
    detail: dict[str, Any] = field(default_factory=dict)


@dataclass
class Trajectory:
    """Samples, a dense state, events and the conserved quantities of a run.

    ``conserved`` maps a name to its samples; each is checked within the segments
    between events, except those in ``conserved_across_events`` (which every impulse
    keeps too, e.g. the momentum of two bodies that collide), checked over the run.
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
    """One dense function from (t_a, t_b, dense) pieces in time order."""
    starts = np.array([a for a, _, _ in segs])

    def at(t: Times) -> FloatArray:
        k = max(int(np.searchsorted(starts, t, side="right")) - 1, 0)
        return segs[k][2](t)

    return at


def vectorized(f: _F) -> _F:
    """Mark a dense function as taking an array of times (one call for all samples)."""
    f.vectorized = True  # type: ignore[attr-defined]  # a function given an attribute
    return f


def sample_dense(dense: Dense, t: FloatArray) -> FloatArray:
    """Samples of a dense solution, shape (len(t), n): one call if it is vectorised."""
    if getattr(dense, "vectorized", False):
        return np.asarray(dense(t), dtype=float)
    return np.array([dense(tt) for tt in t])


def sample_segments(segs: Sequence[Segment], t: npt.ArrayLike) -> FloatArray | None:
    """Samples (len(t), size) of (t_a, t_b, dense) pieces: each sample from the piece it
    falls in (the last piece also takes t_b), one call per vectorised piece; None for no
    times (a scene has at least 2 samples)."""
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
    """max |T| + max |V|: the size of the terms whose sum is the energy."""
    return float(np.max(np.abs(KE)) + np.max(np.abs(np.asarray(E) - KE)))
