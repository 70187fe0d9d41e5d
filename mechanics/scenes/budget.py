"""What a run may cost: its memory and its work estimated before it starts and refused
beyond the limits, and its step count and wall time bounded while it runs.

Conventions
-----------
- **Memory.**  A run holds its samples several times over (the dense rows, the sampled
  state, the series, the conserved quantities and their drifts).  The estimate is
  ``samples × numbers per sample × 8 bytes × COPIES``, with ``SERIES_PER_BODY`` numbers per
  body and ``SERIES_PER_SCENE`` for the scene's own quantities; beyond
  ``DEFAULT_MAX_MEMORY`` the run is refused before it starts, naming the estimate and the
  samples it could hold.  ``max_samples`` (the scene field or ``--max-samples``) sets the
  number of samples allowed instead.
- **Work.**  An integrated run estimates its steps from the scene's fastest rate λ (the
  largest initial spin |ω| and spring frequency √(k/m)): ``STEPS_PER_RADIAN × λ ×
  duration``, scaled by (1e-12/rtol)^(1/8) (DOP853's step grows as rtol^(1/8)).  The
  estimate is a lower one (measured 2.9 to 13 steps per radian on the built-in scenes
  at rtol 1e-12, against 2), so it refuses only what could not fit; a splitting counts
  its steps exactly (run twice: at its step and at half of it).  Beyond ``max_steps``
  the run is refused before it starts.
- **While running**, the integration counts its steps and reads the wall clock: beyond
  ``max_steps`` steps or ``max_seconds`` seconds it stops with the time it reached.
- Every refusal is a :class:`BudgetError` (a :class:`SceneError`): one line naming the
  file, the field, the estimate and the option that raises the limit.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from .errors import SceneError

if TYPE_CHECKING:  # for annotations only: spec imports this module (a layer above it)
    from .spec import Scene

__all__ = [
    "COPIES",
    "DEFAULT_MAX_MEMORY",
    "DEFAULT_MAX_SECONDS",
    "DEFAULT_MAX_STEPS",
    "STEPS_PER_RADIAN",
    "BudgetError",
    "Clock",
    "check_memory",
    "check_steps",
    "fastest_rate",
    "memory_estimate",
    "sample_limit",
    "step_estimate",
]

#: bytes of sample arrays a run may hold by default: the estimate below is about twice
#: the measured peak, so a run at the limit stays near 200 MB beside the ~150 MB of the
#: imported libraries, under the 500 MB a scene file may cost
DEFAULT_MAX_MEMORY = 384 * 10**6
#: numbers per body in a sample (position, velocity, ω, R, their series and conserved
#: parts): measured 13.4 per body for five spheres, 19 for one box with the scene's own
SERIES_PER_BODY = 20
#: the scene's own numbers per sample (t, E, p, L, derived series)
SERIES_PER_SCENE = 10
#: the peak of a run's arrays over its numbers per sample × 8 bytes × samples: measured
#: 3.2 (heavy top) to 6.7 (Newton's cradle) at 10⁵ samples (tracemalloc)
COPIES = 8
#: the steps an integrated run may take by default.  A run keeps each step's dense rows
#: and contact data: measured 2.9 kB (a box pushed over) to 20 kB (the heavy top) held per
#: step, at 0.3 to 3.5 ms a step, so 2·10⁴ steps hold at most ~400 MB and take at most
#: ~70 s; the built-in scenes, integrated, take 5 to 1443
DEFAULT_MAX_STEPS = 20_000
#: steps per radian of the fastest rate at rtol 1e-12: a lower bound of the measured 2.9
#: (a top striking the floor) to 13 (a box dropped on a corner) on the built-in scenes
STEPS_PER_RADIAN = 2.0
#: the rtol at which STEPS_PER_RADIAN was measured (the scenes' default)
CALIBRATION_RTOL = 1e-12
#: the wall time a run may take by default, in seconds
DEFAULT_MAX_SECONDS = 600.0


class BudgetError(SceneError):
    """A run refused before it starts, or stopped at a bound, for its cost."""


def _bytes(n: float) -> str:
    for unit, size in (("GB", 1e9), ("MB", 1e6), ("kB", 1e3)):
        if n >= size:
            return f"{n / size:.3g} {unit}"
    return f"{n:.0f} bytes"


def numbers_per_sample(scene: Scene) -> int:
    return SERIES_PER_BODY * len(scene.bodies) + SERIES_PER_SCENE


def memory_estimate(scene: Scene, samples: int | None = None) -> int:
    """Bytes of arrays a run of ``scene`` holds at its peak (an over-estimate)."""
    n = scene.samples if samples is None else samples
    return n * numbers_per_sample(scene) * 8 * COPIES


def sample_limit(scene: Scene) -> int:
    """The samples the scene may have: its ``max_samples``, else what the memory budget
    holds."""
    if scene.max_samples is not None:
        return scene.max_samples
    return DEFAULT_MAX_MEMORY // (numbers_per_sample(scene) * 8 * COPIES)


def check_memory(scene: Scene) -> None:
    """Refuse a scene whose samples exceed its limit, before anything is allocated."""
    limit = sample_limit(scene)
    if scene.samples <= limit:
        return
    per = numbers_per_sample(scene)
    if scene.max_samples is not None:
        why = f"more than max_samples = {scene.max_samples}"
    else:
        why = (
            f"{scene.samples} samples × {per} numbers × 8 bytes × {COPIES} copies ≈ "
            f"{_bytes(memory_estimate(scene))}, beyond the memory budget of "
            f"{_bytes(DEFAULT_MAX_MEMORY)} (up to {limit} samples for this scene)"
        )
    raise BudgetError(
        scene.source,
        "scene.samples",
        f"{scene.samples} samples: {why}; lower samples, or allow more with --max-samples N "
        "(or max_samples in [scene])",
    )


def fastest_rate(scene: Scene, w0: npt.ArrayLike) -> float:
    """λ (1/s): the largest initial spin |ω| (``w0``, body components, shape (n, 3)) and
    spring frequency √(k/m) of the scene (the lighter body of a spring between two)."""
    rate = float(np.max(np.linalg.norm(np.asarray(w0, dtype=float), axis=-1), initial=0.0))
    masses = {b.name: b.mass for b in scene.bodies}
    for spec in scene.effects_of("spring"):
        ends = [spec.fields["body"], spec.fields.get("other")]
        m = min(masses[b] for b in ends if b is not None and masses[b] > 0)
        rate = max(rate, (spec.fields["stiffness"] / m) ** 0.5)
    return rate


def step_estimate(scene: Scene, w0: npt.ArrayLike) -> float:
    """The steps an integrated run of ``scene`` takes at least (see the Conventions)."""
    per: float = STEPS_PER_RADIAN * (CALIBRATION_RTOL / scene.rtol) ** 0.125
    return per * fastest_rate(scene, w0) * scene.duration


def check_steps(scene: Scene, estimate: float, how: str) -> None:
    """Refuse a run whose estimated steps exceed ``max_steps`` before it starts."""
    if estimate <= scene.max_steps:
        return
    raise BudgetError(
        scene.source,
        "scene.duration",
        f"the run would take about {estimate:.3g} steps ({how}), beyond max_steps = "
        f"{scene.max_steps}; shorten the duration, or allow more with --max-steps N (or "
        "max_steps in [scene])",
    )


@dataclass
class Clock:
    """The step count and wall time of a run, against its limits."""

    scene: Scene  # (spec imports this module: a layer above it)
    started: float = 0.0
    steps: int = 0

    def __post_init__(self) -> None:
        self.started = time.perf_counter()

    def step(self, t: float) -> None:
        """One more step, ending at time ``t``: stop the run at a bound."""
        self.steps += 1
        s = self.scene
        if self.steps > s.max_steps:
            reason = f"{self.steps - 1} steps, max_steps (raise it with --max-steps N)"
        elif (spent := time.perf_counter() - self.started) > s.max_seconds:
            reason = (
                f"{spent:.1f} s of wall time, max_seconds = {s.max_seconds:g} (raise it with "
                "--max-seconds S)"
            )
        else:
            return
        raise BudgetError(
            s.source,
            "(run)",
            f"stopped at t = {t:.6g} s of {s.duration:.6g} s after {reason}",
        )
