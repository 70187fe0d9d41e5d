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
    """Bytes of arrays a run of ``scene`` holds at its peak (an over-estimate).

    ``samples × numbers per sample × 8 bytes × COPIES``, with ``SERIES_PER_BODY`` numbers
    per body and ``SERIES_PER_SCENE`` for the scene's own (see the Conventions).

    Parameters
    ----------
    scene : Scene
        The parsed scene (:func:`mechanics.scenes.spec.parse_scene`).
    samples : int, optional
        The samples to count (≥ 0); default the scene's ``samples``.

    Returns
    -------
    int
        The estimate, bytes.

    Examples
    --------
    >>> from mechanics.scenes.spec import parse_scene
    >>> sc = parse_scene({"scene": {"name": "x", "duration": 2.0, "samples": 201},
    ...                   "bodies": [{"name": "ball", "shape": "point", "mass": 2.0}]})
    >>> memory_estimate(sc) == 201 * (SERIES_PER_BODY + SERIES_PER_SCENE) * 8 * COPIES
    True
    >>> memory_estimate(sc, 1) * 201 == memory_estimate(sc)
    True
    """
    n = scene.samples if samples is None else samples
    return n * numbers_per_sample(scene) * 8 * COPIES


def sample_limit(scene: Scene) -> int:
    """The samples the scene may have: its ``max_samples``, else what the memory budget holds.

    The memory budget holds ``DEFAULT_MAX_MEMORY // (bytes per sample)`` samples, the
    bytes per sample as in :func:`memory_estimate`.

    Parameters
    ----------
    scene : Scene
        The parsed scene (:func:`mechanics.scenes.spec.parse_scene`).

    Returns
    -------
    int
        The largest number of samples a run of ``scene`` may hold.

    Examples
    --------
    >>> from mechanics.scenes.spec import parse_scene
    >>> sc = parse_scene({"scene": {"name": "x", "duration": 2.0, "samples": 201},
    ...                   "bodies": [{"name": "ball", "shape": "point", "mass": 2.0}]})
    >>> sample_limit(sc) == DEFAULT_MAX_MEMORY // memory_estimate(sc, 1)
    True
    >>> sample_limit(sc)
    200000
    """
    if scene.max_samples is not None:
        return scene.max_samples
    return DEFAULT_MAX_MEMORY // (numbers_per_sample(scene) * 8 * COPIES)


def check_memory(scene: Scene) -> None:
    """Refuse a scene whose samples exceed its limit, before anything is allocated.

    The limit is :func:`sample_limit`: the scene's ``max_samples``, else what the memory
    budget ``DEFAULT_MAX_MEMORY`` holds.

    Parameters
    ----------
    scene : Scene
        The parsed scene (:func:`mechanics.scenes.spec.parse_scene`).

    Raises
    ------
    BudgetError
        If ``scene.samples`` exceeds :func:`sample_limit` (one line naming the file, the
        field ``scene.samples``, the estimate and the option that raises the limit).

    Examples
    --------
    >>> from mechanics.scenes.spec import parse_scene
    >>> body = [{"name": "ball", "shape": "point", "mass": 2.0}]
    >>> check_memory(parse_scene({"scene": {"name": "x", "duration": 1.0}, "bodies": body}))
    >>> check_memory(parse_scene({"scene": {"name": "x", "duration": 1.0, "samples": 201,
    ...                                     "max_samples": 200}, "bodies": body}))
    Traceback (most recent call last):
    ...
    mechanics.scenes.budget.BudgetError: <scene>: scene.samples: 201 samples: more than ...
    """
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
    """λ (1/s): the largest initial spin |ω| and spring frequency √(k/m) of the scene.

    A spring's frequency takes the lighter body of the two it joins (the one body of a
    spring to an anchor); a massless end is left out.

    Parameters
    ----------
    scene : Scene
        The parsed scene (:func:`mechanics.scenes.spec.parse_scene`).
    w0 : array_like, shape (n, 3)
        The bodies' initial angular velocities, rad/s (body components; zeros for a
        body that does not turn).

    Returns
    -------
    float
        λ, 1/s (≥ 0; 0 for a scene with no spin and no spring).

    Raises
    ------
    ValueError
        If ``w0`` is not an array of numbers (numpy's conversion to float).

    Examples
    --------
    A spring of stiffness 8 N/m between 2 kg and 8 kg: √(8/2) = 2 /s, unless a spin is
    faster:

    >>> from mechanics.scenes.spec import parse_scene
    >>> sc = parse_scene({"scene": {"name": "x", "duration": 2.0},
    ...                   "bodies": [{"name": "a", "shape": "point", "mass": 2.0},
    ...                              {"name": "b", "shape": "point", "mass": 8.0,
    ...                               "initial": {"position": [1.0, 0.0, 0.0]}}],
    ...                   "effects": [{"type": "spring", "body": "a", "other": "b",
    ...                                "stiffness": 8.0}]})
    >>> fastest_rate(sc, np.zeros((2, 3))), fastest_rate(sc, [[0, 0, 3.0], [0, 0, 0]])
    (2.0, 3.0)
    """
    rate = float(np.max(np.linalg.norm(np.asarray(w0, dtype=float), axis=-1), initial=0.0))
    masses = {b.name: b.mass for b in scene.bodies}
    for spec in scene.effects_of("spring"):
        ends = [spec.fields["body"], spec.fields.get("other")]
        m = min(masses[b] for b in ends if b is not None and masses[b] > 0)
        rate = max(rate, (spec.fields["stiffness"] / m) ** 0.5)
    return rate


def step_estimate(scene: Scene, w0: npt.ArrayLike) -> float:
    """The steps an integrated run of ``scene`` takes at least (see the Conventions).

    ``STEPS_PER_RADIAN × λ × duration`` at rtol 1e-12, scaled by (1e-12/rtol)^(1/8),
    with λ the :func:`fastest_rate`: a lower estimate (measured 2.9 to 13 steps per
    radian on the built-in scenes, against 2).

    Parameters
    ----------
    scene : Scene
        The parsed scene (:func:`mechanics.scenes.spec.parse_scene`).
    w0 : array_like, shape (n, 3)
        The bodies' initial angular velocities, rad/s (body components).

    Returns
    -------
    float
        The estimated number of steps (≥ 0).

    Raises
    ------
    ValueError
        If ``w0`` is not an array of numbers (numpy's conversion to float).

    Examples
    --------
    λ = 2 /s over 2 s at the default rtol 1e-12: 2 steps per radian × 4 rad:

    >>> from mechanics.scenes.spec import parse_scene
    >>> sc = parse_scene({"scene": {"name": "x", "duration": 2.0},
    ...                   "bodies": [{"name": "a", "shape": "point", "mass": 2.0},
    ...                              {"name": "b", "shape": "point", "mass": 8.0,
    ...                               "initial": {"position": [1.0, 0.0, 0.0]}}],
    ...                   "effects": [{"type": "spring", "body": "a", "other": "b",
    ...                                "stiffness": 8.0}]})
    >>> w0 = np.zeros((2, 3))
    >>> step_estimate(sc, w0) == STEPS_PER_RADIAN * fastest_rate(sc, w0) * sc.duration
    True
    >>> step_estimate(sc, np.zeros((2, 3)))
    8.0
    """
    per: float = STEPS_PER_RADIAN * (CALIBRATION_RTOL / scene.rtol) ** 0.125
    return per * fastest_rate(scene, w0) * scene.duration


def check_steps(scene: Scene, estimate: float, how: str) -> None:
    """Refuse a run whose estimated steps exceed ``max_steps`` before it starts.

    Parameters
    ----------
    scene : Scene
        The parsed scene (:func:`mechanics.scenes.spec.parse_scene`): its ``max_steps``.
    estimate : float
        The estimated steps of the run (:func:`step_estimate`, or a splitting's exact
        count).
    how : str
        How the run steps, named in the message (e.g. ``"a splitting at step 0.01 s"``).

    Raises
    ------
    BudgetError
        If ``estimate`` > ``scene.max_steps`` (one line naming the file, the field
        ``scene.duration``, the estimate and the option ``--max-steps``).

    Examples
    --------
    >>> from mechanics.scenes.spec import parse_scene
    >>> sc = parse_scene({"scene": {"name": "x", "duration": 2.0, "samples": 201},
    ...                   "bodies": [{"name": "ball", "shape": "point", "mass": 2.0}]})
    >>> check_steps(sc, sc.max_steps, "at most the limit")
    >>> check_steps(sc, sc.max_steps + 1, "one step too many")
    Traceback (most recent call last):
    ...
    mechanics.scenes.budget.BudgetError: <scene>: scene.duration: the run would take about ...
    """
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
    """The step count and wall time of a run, against its limits.

    The clock starts when it is made (``started`` is then set to
    :func:`time.perf_counter`); :meth:`step` counts a step and raises a
    :class:`BudgetError` beyond ``scene.max_steps`` steps or ``scene.max_seconds`` of wall
    time.

    Parameters
    ----------
    scene : Scene
        The parsed scene (:func:`mechanics.scenes.spec.parse_scene`): its limits.
    started : float, optional
        Overwritten at construction by the current :func:`time.perf_counter`, s.
    steps : int, optional
        The steps counted so far (default 0).

    Raises
    ------
    BudgetError
        From :meth:`step`, beyond ``scene.max_steps`` steps or ``scene.max_seconds`` of
        wall time (naming the time the run reached).  The constructor checks nothing.

    Examples
    --------
    >>> from mechanics.scenes.spec import parse_scene
    >>> sc = parse_scene({"scene": {"name": "x", "duration": 2.0, "samples": 201},
    ...                   "bodies": [{"name": "ball", "shape": "point", "mass": 2.0}]})
    >>> clock = Clock(sc)
    >>> for k in range(3):
    ...     clock.step(0.1 * k)
    >>> clock.steps
    3
    >>> clock.steps = sc.max_steps
    >>> clock.step(0.5)
    Traceback (most recent call last):
    ...
    mechanics.scenes.budget.BudgetError: <scene>: (run): stopped at t = 0.5 s of 2 s after ...
    """

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
