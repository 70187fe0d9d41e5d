"""The result of a scene run: samples, events, conserved quantities, self-checks, and the
comparisons a caller asks for (the book layer's, :mod:`identities.book.scenes.compare`).

Conventions
-----------
- A conserved quantity is reported by its drift: the largest change within a segment
  between events (impacts change the energy; between them it must hold), relative to
  the scale of the quantity (its largest magnitude over the run, or of its parts,
  at least 1e-300).  It passes when the drift is within ``CONSERVED_RTOL`` for an exact
  flow, ``CONSERVED_RTOL_INTEGRATED`` for an integrated one.
- A comparison holds the simulated value, the book's closed form, their relative
  difference and the tolerance with its reason.
- Self-checks: what a run can verify on its own output, whatever the scene.  No two
  bodies of an impact pair interpenetrate at any sample (beyond ``PENETRATION_RTOL`` of
  the positions' size); at every impact the kinetic energy read off the velocities drops
  by the loss formula ½ μ (1 − e²) v_n² (6.41), and a two-body impact keeps the momentum
  (6.37) and every two-body impact the angular momentum about the contact point (6.21);
  every impulse acts where the gap is zero (within ``PENETRATION_RTOL``); a resting
  contact stays at zero gap (within the conserved tolerance: its gap is held by its
  acceleration) and its support presses, inside the friction cone (``SUPPORT_RTOL``);
  a rigid body's attitude stays orthogonal (R Rᵀ = I within ``ORTHOGONALITY_RTOL`` for
  an exact flow, the conserved tolerance for an integrated one).  A violation fails the
  run: a wrong motion never reports PASSED.
- **Non-finite is failure.**  Every reported number (the times, the state's series, the
  conserved quantities, the derived quantities, the events' fields) is checked: the first
  NaN or infinity fails the run (the self-check "every reported number finite" names the
  quantity and the first time it went non-finite), and a conserved quantity whose value
  or drift is not finite is never ok.
- ``to_json`` writes a non-finite number as the string ``"nan"``, ``"inf"`` or
  ``"-inf"`` (JSON has no such numbers), so a failed run's record is still written whole.
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any, TypeAlias

import numpy as np
import numpy.typing as npt

from .impacts import LAW_RTOL
from .simulate import simulate
from .spec import Scene
from .trajectory import CONSERVED_RTOL_INTEGRATED, EPS, Trajectory, tolerance_scale
from .vectors import FloatArray

__all__ = [
    "CONSERVED_RTOL",
    "CONSERVED_RTOL_INTEGRATED",
    "IMPACT_RTOL",
    "ORTHOGONALITY_RTOL",
    "PENETRATION_RTOL",
    "SUPPORT_RTOL",
    "Comparison",
    "ConservedReport",
    "SceneResult",
    "SelfCheck",
    "run_scene",
]

#: exact flows: each sample is a closed form, rounding grows with the terms (≤ ~100 ops)
CONSERVED_RTOL = 1024 * EPS
#: more impact pairs than this (a group's) share one interpenetration check, naming
#: the deepest
MANY_PAIRS = 16
#: a gap below zero by more than this × (max |position| + the radii) is an
#: interpenetration: contacts are located to 4 eps of the time and the positions are
#: sums of a few dozen rounded terms, so a resolved contact leaves a few eps at most
PENETRATION_RTOL = 256 * EPS
#: the impact's loss formula against the velocities (relative to the kinetic energy or
#: momentum scale before): direct_impact is within a few ulps, the update adds one
#: rounding per component, the sums over ≤ 2 bodies a few more
IMPACT_RTOL = 64 * EPS
#: the support's law at the samples (relative to its forces' terms): the forces are a
#: least-norm solve of a few dozen rounded products (mechanics.scenes.support)
SUPPORT_RTOL = 2**10 * EPS
#: the impact checks' allowance per unit of an attitude's departure from orthonormality
#: (measured: 3.9 at a pinned top's corner impacts, |R Rᵀ − I| = 1e-12; 16 leaves 4×)
ATTITUDE_SLACK = 16.0
#: an exact attitude (the elliptic flow's product of rotations, a few dozen roundings)
ORTHOGONALITY_RTOL = 64 * EPS
#: a splitting's energy drift at half the step, × 2ᵖ, over its drift at the step: 1 in
#: the asymptotic regime; half again for the next order's term (measured 1.00–1.02 on
#: the spring-driven box at h = 0.025, 0.0125, orders 2 and 4)
SPLITTING_ORDER_SLACK = 1.5

#: the book's comparisons of a run: ``compare(scene, trajectory) -> [Comparison]``
Compare: TypeAlias = "Callable[[Scene, Trajectory], Iterable[Comparison]]"


@dataclass(frozen=True)
class Comparison:
    """A simulated quantity against the book's closed form.

    It holds (``ok``) where the relative difference |simulated − closed_form| /
    |closed_form| (the absolute one where the closed form is 0) is within
    ``tolerance``; a non-finite side never holds.  The constructor stores what it is
    given and checks nothing.

    Parameters
    ----------
    name : str
        What is compared, e.g. ``"speed at t = 2 s"``.
    book : str
        The book's reference for the closed form, e.g. ``"(3.80)"``.
    simulated : float
        The value the run gives (SI units).
    closed_form : float
        The book's value, in the same units.
    tolerance : float
        The relative difference allowed, ≥ 0.
    reason : str
        Where the tolerance comes from.

    Examples
    --------
    1.5 against 1.0: a difference of 0.5, relative 0.5, within a tolerance of 0.6:

    >>> c = Comparison("v(2 s)", "(3.80)", 1.5, 1.0, 0.6, "a test")
    >>> c.difference, c.relative_difference, c.ok
    (0.5, 0.5, True)
    >>> Comparison("v", "(3.80)", float("nan"), 1.0, 1.0, "a test").ok
    False
    """

    name: str
    book: str
    simulated: float
    closed_form: float
    tolerance: float
    reason: str

    def _get_difference(self) -> float:
        return float(self.simulated) - float(self.closed_form)

    difference = property(_get_difference)

    def _get_relative_difference(self) -> float:
        d: float
        d, cf = abs(self.difference), abs(float(self.closed_form))  # Python floats: no warning
        return d / cf if cf != 0 else d

    relative_difference = property(_get_relative_difference)

    def _get_ok(self) -> bool:
        # NaN compares false, so a comparison with a non-finite side is never ok
        return bool(self.relative_difference <= self.tolerance)

    ok = property(_get_ok)

    def as_dict(self) -> dict[str, Any]:
        return {
            "name": self.name,
            "book": self.book,
            "simulated": float(self.simulated),
            "closed_form": float(self.closed_form),
            "difference": float(self.difference),
            "relative_difference": float(self.relative_difference),
            "tolerance": float(self.tolerance),
            "reason": self.reason,
            "ok": self.ok,
        }


@dataclass(frozen=True)
class ConservedReport:
    """The drift of a quantity the effects conserve.

    It holds (``ok``) where the value and the drift are finite and the drift is within
    ``tolerance`` (see the module's Conventions).  The constructor stores what it is
    given and checks nothing.

    Parameters
    ----------
    name : str
        The quantity, e.g. ``"E"`` or ``"p_x"``.
    value : float
        Its value at the end of the run (SI units).
    drift : float
        Its largest change within a segment between events, relative to its scale.
    tolerance : float
        The relative drift allowed, ≥ 0.
    since : float, optional
        The time (s) from which it is conserved (energy once rolling). Default 0.

    Examples
    --------
    The energy of a point falling from 4 m: m g z0 = 2 × 8 × 4 = 64 J, kept to the bit:

    >>> from mechanics.scenes.spec import parse_scene
    >>> sc = parse_scene({"scene": {"name": "fall", "duration": 1.0, "samples": 3},
    ...                   "bodies": [{"name": "ball", "shape": "point", "mass": 2.0,
    ...                               "initial": {"position": [0.0, 0.0, 4.0]}}],
    ...                   "effects": [{"type": "gravity", "g": 8.0}]})
    >>> E = {c.name: c for c in run_scene(sc).conserved}["E"]
    >>> E.value, E.drift, E.ok, ConservedReport("E", 64.0, float("nan"), 1.0).ok
    (64.0, 0.0, True, False)
    """

    name: str
    value: float
    drift: float
    tolerance: float
    since: float = 0.0

    def _get_ok(self) -> bool:
        finite = math.isfinite(self.value) and math.isfinite(self.drift)
        return bool(finite and self.drift <= self.tolerance)

    ok = property(_get_ok)

    def as_dict(self) -> dict[str, Any]:
        return {
            "name": self.name,
            "value": float(self.value),
            "relative_drift": float(self.drift),
            "tolerance": float(self.tolerance),
            "since": float(self.since),
            "ok": self.ok,
        }


@dataclass(frozen=True)
class SelfCheck:
    """A property the run verifies on its own output, its worst violation and tolerance.

    The properties (no interpenetration, the impact laws, ...) are the module's
    Conventions; it holds (``ok``) where the violation is within the tolerance (a NaN
    never is).  The constructor stores what it is given and checks nothing.

    Parameters
    ----------
    name : str
        The property, e.g. ``"no interpenetration of body 'ball' and the plane"``.
    violation : float
        Its worst relative violation over the run.
    tolerance : float
        The violation allowed, ≥ 0.
    reason : str
        What is measured.

    Examples
    --------
    Every run checks that the numbers it reports are finite:

    >>> from mechanics.scenes.spec import parse_scene
    >>> sc = parse_scene({"scene": {"name": "fall", "duration": 1.0, "samples": 3},
    ...                   "bodies": [{"name": "ball", "shape": "point", "mass": 2.0,
    ...                               "initial": {"position": [0.0, 0.0, 4.0]}}],
    ...                   "effects": [{"type": "gravity", "g": 8.0}]})
    >>> first = run_scene(sc).self_checks[0]
    >>> first.name, first.violation, first.ok
    ('every reported number finite', 0.0, True)
    >>> SelfCheck("gap ≥ 0", 2.0, 1.0, "a test").ok
    False
    """

    name: str
    violation: float
    tolerance: float
    reason: str

    def _get_ok(self) -> bool:
        return bool(self.violation <= self.tolerance)

    ok = property(_get_ok)

    def as_dict(self) -> dict[str, Any]:
        return {
            "name": self.name,
            "violation": float(self.violation),
            "tolerance": float(self.tolerance),
            "reason": self.reason,
            "ok": self.ok,
        }


@dataclass
class SceneResult:
    """A scene run: the trajectory, the conserved quantities and the book comparisons.

    It passes (``passed``) where every conserved quantity, comparison and self-check
    holds; ``as_dict``, ``to_json`` and ``summary`` write its record.  Built by
    :func:`run_scene`; the constructor stores what it is given and checks nothing.

    Parameters
    ----------
    scene : Scene
        The scene that was run.
    trajectory : Trajectory
        Its run (:func:`mechanics.scenes.simulate.simulate`).
    conserved : list[ConservedReport]
        The drifts of the quantities its effects conserve.
    comparisons : list[Comparison], optional
        The comparisons with the book. Default none.
    self_checks : list[SelfCheck], optional
        What the run verified on its own output. Default none.

    Examples
    --------
    A run passes where each of its checks holds:

    >>> from mechanics.scenes.spec import parse_scene
    >>> sc = parse_scene({"scene": {"name": "fall", "duration": 1.0, "samples": 3},
    ...                   "bodies": [{"name": "ball", "shape": "point", "mass": 2.0,
    ...                               "initial": {"position": [0.0, 0.0, 4.0]}}],
    ...                   "effects": [{"type": "gravity", "g": 8.0}]})
    >>> res = run_scene(sc)
    >>> res.passed, all(c.ok for c in [*res.conserved, *res.self_checks])
    (True, True)
    >>> res.method == res.trajectory.method, res.summary().splitlines()[-1]
    (True, 'PASSED')
    """

    scene: Scene
    trajectory: Trajectory
    conserved: list[ConservedReport]
    comparisons: list[Comparison] = field(default_factory=list)
    self_checks: list[SelfCheck] = field(default_factory=list)

    def _get_passed(self) -> bool:
        checks: list[ConservedReport | Comparison | SelfCheck] = [
            *self.conserved,
            *self.comparisons,
            *self.self_checks,
        ]
        return all(c.ok for c in checks)

    passed = property(_get_passed)

    def _get_method(self) -> str:
        return self.trajectory.method

    method = property(_get_method)

    def as_dict(self) -> dict[str, Any]:
        tr = self.trajectory
        return {
            "scene": self.scene.name,
            "title": self.scene.title,
            "book": self.scene.book,
            "source": self.scene.source,
            "effects": list(self.scene.effect_types),
            "method": tr.method,
            "passed": self.passed,
            "events": [{"t": e.t, "kind": e.kind, **_plain(e.detail)} for e in tr.events],
            "conserved": [c.as_dict() for c in self.conserved],
            "comparisons": [c.as_dict() for c in self.comparisons],
            "self_checks": [c.as_dict() for c in self.self_checks],
            "derived": [
                {"name": n, "exact": x, "measured": m} for n, x, m in self.trajectory.derived
            ],
            "samples": {
                "t": tr.t.tolist(),
                **{k: np.asarray(v).tolist() for k, v in tr.series.items()},
            },
        }

    def to_json(self) -> str:
        return json.dumps(_json_safe(self.as_dict()), indent=1, allow_nan=False)

    def summary(self) -> str:
        s, tr = self.scene, self.trajectory
        lines = [
            f"scene {s.name}"
            + (f": {s.title}" if s.title else "")
            + (f" ({s.book})" if s.book else ""),
            f"effects: {', '.join(s.effect_types) or 'none'}",
            f"method: {tr.method}",
            f"events: {len(tr.events)}"
            + (
                "  ("
                + ", ".join(f"{e.kind} at t={e.t:.6g}" for e in tr.events[:4])
                + (", ..." if len(tr.events) > 4 else "")
                + ")"
                if tr.events
                else ""
            ),
        ]
        if self.conserved:
            lines.append("conserved (relative drift within segments between events):")
            for c in self.conserved:
                since = f" from t={c.since:.6g}" if c.since else ""
                lines.append(
                    f"  {'ok  ' if c.ok else 'FAIL'} {c.name:<24} {c.value:>+.12g}  "
                    f"drift {c.drift:.2e} ≤ {c.tolerance:.1e}{since}"
                )
        if self.self_checks:
            lines.append("self-checks (worst relative violation):")
            for sc in self.self_checks:
                lines.append(
                    f"  {'ok  ' if sc.ok else 'FAIL'} {sc.name:<48} {sc.violation:.2e} ≤ "
                    f"{sc.tolerance:.1e}  [{sc.reason}]"
                )
        derived = self.trajectory.derived
        if derived:
            lines.append("derived (exact | measured from the motion):")
            for n, x, m in derived:
                fx = f"{x:.10g}" if x is not None else "-"
                fm = f"{m:.10g}" if m is not None else "-"
                lines.append(f"  {n:<40} {fx:>18} | {fm}" if (x, m) != (None, None) else f"  {n}")
        if self.comparisons:
            lines.append("against the book:")
            for cmp in self.comparisons:
                lines.append(
                    f"  {'ok  ' if cmp.ok else 'FAIL'} {cmp.name:<34} sim {cmp.simulated:>+.15g}  "
                    f"book {cmp.closed_form:>+.15g}  rel {cmp.relative_difference:.2e} ≤ "
                    f"{cmp.tolerance:.1e}  [{cmp.book}; {cmp.reason}]"
                )
        lines.append("PASSED" if self.passed else "FAILED")
        return "\n".join(lines)


def _json_safe(x: object) -> object:
    """``x`` with every non-finite float replaced by "nan", "inf" or "-inf"."""
    if isinstance(x, dict):
        return {k: _json_safe(v) for k, v in x.items()}
    if isinstance(x, list | tuple):
        return [_json_safe(v) for v in x]
    if isinstance(x, float | np.floating) and not math.isfinite(x):
        return "nan" if math.isnan(x) else ("inf" if x > 0 else "-inf")
    return x


def _first_non_finite(tr: Trajectory) -> tuple[str, float] | None:
    """(quantity, time) of the first non-finite number the run reports, or None."""
    t = np.asarray(tr.t, dtype=float)
    if not np.all(np.isfinite(t)):
        return "the sample times", float("nan")
    named = [*tr.series.items(), *((f"conserved {k}", v) for k, v in tr.conserved.items())]
    worst = None
    for name, vals in named:
        v = np.asarray(vals, dtype=float).reshape(t.size, -1)
        bad = ~np.all(np.isfinite(v), axis=1)
        if bad.any():
            i = int(np.argmax(bad))
            if worst is None or t[i] < worst[1]:
                worst = (name, float(t[i]))
    if worst is not None:
        return worst
    for e in tr.events:
        for k, v in e.detail.items():
            arr = np.asarray(v) if isinstance(v, float | int | list | tuple | np.ndarray) else None
            if arr is not None and arr.dtype.kind in "fi" and not np.all(np.isfinite(arr)):
                return f"the {e.kind} event's {k}", float(e.t)
    for n, x, m in tr.derived:
        for value in (x, m):
            if isinstance(value, float) and not math.isfinite(value):
                return f"the derived {n}", float("nan")
    return None


def _finite_check(tr: Trajectory) -> SelfCheck:
    """The self-check "every reported number finite" (see the Conventions)."""
    found = _first_non_finite(tr)
    if found is None:
        return SelfCheck(
            "every reported number finite",
            0.0,
            0.0,
            "times, series, conserved and derived quantities, events",
        )
    name, at = found
    when = f" from t = {at:.6g} s" if math.isfinite(at) else ""
    return SelfCheck("every reported number finite", 1.0, 0.0, f"{name} is not finite{when}")


def _plain(d: Mapping[str, Any]) -> dict[str, Any]:
    out: dict[str, Any] = {}
    for k, v in d.items():
        if isinstance(v, np.generic):
            v = v.item()
        out[k] = v
    return out


def _drift(
    values: npt.ArrayLike,
    t: FloatArray,
    segments: Iterable[tuple[float, float]],
    since: float,
    scale: float = 0.0,
) -> float:
    worst = 0.0
    v = np.asarray(values, dtype=float)
    if not np.all(np.isfinite(v)):
        return math.nan  # a drift of numbers that are not finite is not a drift: never ok
    scale = max(float(np.max(np.abs(v))), scale, 1e-300)
    for a, b in segments:
        m = (t >= max(a, since)) & (t < b) if math.isfinite(b) else (t >= max(a, since))
        if m.sum() >= 2:
            seg = v[m]
            worst = max(worst, float(seg.max() - seg.min()) / scale)
    return worst


def run_scene(scene: Scene, compare: Compare | None = None) -> SceneResult:
    """Simulate the scene and report its conserved quantities, self-checks and comparisons.

    With ``compare`` (a function ``(scene, trajectory) -> list[Comparison]``), also the
    comparisons it makes (the book's: :func:`identities.book.scenes.compare.run_book_scene`).
    A number the run reports that is not finite fails it by name (the module's
    Conventions), never with a warning.

    Parameters
    ----------
    scene : Scene
        A validated scene (:func:`~.spec.parse_scene`, :func:`~.spec.load_scene`).
    compare : Compare or None, optional
        The comparisons to make of the run: ``(scene, trajectory) -> Iterable[Comparison]``.
        Default None: none.

    Returns
    -------
    SceneResult
        The trajectory, the conserved quantities' drifts, the comparisons and the
        self-checks.

    Raises
    ------
    SceneError
        Where the run is refused or stopped (:func:`mechanics.scenes.simulate.simulate`:
        its budget, float64's range, a library function's domain).

    Examples
    --------
    A fall from 4 m under g = 8 m/s², compared with z(1 s) = 4 − ½ g t² = 0:

    >>> from mechanics.scenes.spec import parse_scene
    >>> sc = parse_scene({"scene": {"name": "fall", "duration": 1.0, "samples": 3},
    ...                   "bodies": [{"name": "ball", "shape": "point", "mass": 2.0,
    ...                               "initial": {"position": [0.0, 0.0, 4.0]}}],
    ...                   "effects": [{"type": "gravity", "g": 8.0}]})
    >>> def compare(scene, tr):
    ...     return [Comparison("z(1 s)", "free fall", tr.series["z"][-1], 4.0 - 0.5 * 8.0,
    ...                        0.0, "exact arithmetic")]
    >>> res = run_scene(sc, compare)
    >>> res.passed, res.comparisons[0].difference
    (True, 0.0)
    """
    tr = simulate(scene)
    with np.errstate(all="ignore"):  # a non-finite number fails the run by name
        return _report(scene, tr, compare)


def _report(scene: Scene, tr: Trajectory, compare: Compare | None) -> SceneResult:
    tol = conserved_tolerance(scene, tr)
    conserved = []
    scales = tr.scales
    split = tr.splitting
    for name, vals in tr.conserved.items():
        since = tr.conserved_from.get(name, 0.0)
        allowed = tol
        if split is not None and name == "E":
            # a splitting's energy oscillates at O(hᵖ), its truncation error: allowed
            # 2ᵖ × its drift at half the step (half again to spare); that this drift is
            # the method's, shrinking at order p, is the self-check "energy error at
            # order p" (a wrong kick's does not shrink)
            size = max(scales.get(name, 0.0), float(np.max(np.abs(vals))), 1e-300)
            allowed = max(tol, 1.5 * 2.0 ** split["order"] * split["E_drift_half"] / size)
        conserved.append(
            ConservedReport(
                name,
                float(np.asarray(vals)[-1]),
                _drift(vals, tr.t, tr.segments(name), since, scales.get(name, 0.0)),
                allowed,
                since,
            )
        )
    comparisons = list(compare(scene, tr)) if compare is not None else []
    checks = [_finite_check(tr), *self_checks(tr, tol)]
    return SceneResult(scene, tr, conserved, comparisons, checks)


def conserved_tolerance(scene: Scene, tr: Trajectory) -> float:
    """The relative drift allowed a conserved quantity (see the module Conventions)."""
    if tr.method.startswith("integrated"):  # measured at the default; looser asks more
        return CONSERVED_RTOL_INTEGRATED * tolerance_scale(scene)
    return CONSERVED_RTOL


def self_checks(tr: Trajectory, tol: float = CONSERVED_RTOL) -> list[SelfCheck]:
    """What the run can verify on its own output (see the module Conventions); ``tol``
    is the conserved quantities' tolerance (an integrated attitude drifts like them)."""
    out = []
    split = tr.splitting
    if split is not None and "E" in tr.series:
        p, E = split["order"], np.asarray(tr.series["E"])
        drift = float(np.ptp(E))
        size = max(tr.scales.get("E", 0.0), float(np.max(np.abs(E))), 1e-300)
        # beyond rounding, the drift at h/2 must be 2⁻ᵖ of that at h (3/2 to spare)
        ratio = 2.0**p * split["E_drift_half"] / drift if drift > tol * size else 0.0
        out.append(
            SelfCheck(
                f"energy error at order {p}",
                ratio,
                SPLITTING_ORDER_SLACK,
                "2ᵖ × drift of E at h/2 over its drift at h (a wrong kick does not shrink)",
            )
        )
    if tr.orthogonality is not None:
        exact = not tr.method.startswith("integrated")
        out.append(
            SelfCheck(
                "attitudes orthogonal",
                tr.orthogonality,
                ORTHOGONALITY_RTOL if exact else tol,
                "max |R Rᵀ − I|",
            )
        )
    scale = tr.length_scale
    depths = {
        pair: max(0.0, -float(np.min(gaps, initial=0.0))) / max(scale, 1e-300)
        for pair, gaps in tr.gaps.items()
    }
    if len(depths) > MANY_PAIRS:  # one line for them all, naming the deepest
        pair = max(depths, key=depths.__getitem__)
        depths = {f"{len(depths)} pairs (deepest: {pair})": depths[pair]}
    for pair, depth in depths.items():
        out.append(
            SelfCheck(
                f"no interpenetration of {pair}",
                depth,
                PENETRATION_RTOL,
                "gap ≥ 0 at every sample",
            )
        )
    if tr.energy_rise is not None:
        size = max(tr.scales.get("E", 0.0), float(np.max(np.abs(tr.series["E"]))), 1e-300)
        allowed = tol  # E's own error, as where it is conserved (a splitting's: its order's)
        if split is not None and "E_drift_half" in split:
            allowed = max(tol, 1.5 * 2.0 ** split["order"] * split["E_drift_half"] / size)
        out.append(
            SelfCheck(
                "energy never rises",
                tr.energy_rise / size,
                allowed,
                "E(t) ≤ E at every earlier sample: friction, drag and impacts only take "
                "energy, ideal joints and the support do no work",
            )
        )
    for pair, held in tr.resting_gaps.items():
        # held at zero by its support's acceleration: the integration's error, no more
        out.append(
            SelfCheck(
                f"resting contacts of {pair} stay in contact",
                held / max(scale, 1e-300),
                max(PENETRATION_RTOL, tol),
                "|gap| of every resting contact at every sample",
            )
        )
    for pair, breach in tr.support_law.items():
        out.append(
            SelfCheck(
                f"support of {pair} presses, inside its friction cone",
                breach,
                SUPPORT_RTOL,
                "F·n ≥ 0 and |F_t| ≤ μ F·n at every sample where it rests",
            )
        )
    impacts = [e.detail for e in tr.events if "kinetic_energy_before" in e.detail]
    at_contact = [d for d in impacts if "gap" in d]
    if at_contact:
        out.append(
            SelfCheck(
                f"impacts at contact ({_count(len(at_contact), 'impact')})",
                max(abs(d["gap"]) / max(d["gap_scale"], 1e-300) for d in at_contact),
                PENETRATION_RTOL,
                "the gap is zero where an impulse acts",
            )
        )
    if impacts:
        # beyond the rounding, each impact may differ by ATTITUDE_SLACK × its attitudes'
        # departure from orthonormality (the impulse is formed with R_A_O, and a pinned
        # body's velocities are derived through it)
        worst = max(
            abs(d["kinetic_energy_before"] - d["kinetic_energy_after"] - d["energy_loss"])
            / max(d["kinetic_energy_before"], 1e-300)
            - ATTITUDE_SLACK * d.get("attitude_defect", 0.0)
            for d in impacts
        )
        out.append(
            SelfCheck(
                f"impact energy loss ({_count(len(impacts), 'impact')})",
                worst,
                IMPACT_RTOL,
                "T_before − T_after = ½ μ (1 − e²) v_n² (6.41), the impulse's work with friction",
            )
        )
        worst = max(-d["energy_loss"] / max(d["kinetic_energy_before"], 1e-300) for d in impacts)
        out.append(
            SelfCheck(
                f"impacts dissipate ({_count(len(impacts), 'impact')})",
                max(worst, 0.0),
                IMPACT_RTOL,
                "energy lost ≥ 0 at every impact (Newton's e with friction can gain: Kane)",
            )
        )
    lawful = [d for d in impacts if "law_residual" in d]
    if lawful:
        worst = max(lawful, key=lambda d: d["law_residual"])
        where = worst.get("law_worst_contact", worst.get("feature", ""))
        out.append(
            SelfCheck(
                f"impact law at every contact ({_count(len(lawful), 'impact')}; worst: {where})",
                worst["law_residual"],
                LAW_RTOL,
                "separation speed = e × approach speed where an impulse acts, not less "
                "where none does (Newton's law per contact, 6.36)",
            )
        )
    pairs = [d for d in impacts if "bodies" in d and "external_impulse" not in d]
    for what, key, law in (
        ("momentum", "momentum", "Σ m v unchanged by the impulses (6.37)"),
        (
            "angular momentum",
            "angular_momentum",
            "Σ (ρ × m v + Rᵀ L_A) about the contact point unchanged (6.21)",
        ),
    ):
        if pairs:
            # the angular momentum's spins Rᵀ L_A and the impulse's moment are formed with
            # R_A_O: the same allowance for its departure from orthonormality as the
            # energy's (found by a property test: 2.9e-14 at a box's corner, integrated)
            slack = ATTITUDE_SLACK if key == "angular_momentum" else 0.0
            worst = max(
                float(np.linalg.norm(np.subtract(d[f"{key}_after"], d[f"{key}_before"])))
                / max(d[f"{key}_scale"], 1e-300)
                - slack * d.get("attitude_defect", 0.0)
                for d in pairs
            )
            out.append(
                SelfCheck(
                    f"{what} across two-body impacts ({_count(len(pairs), 'impact')})",
                    worst,
                    IMPACT_RTOL,
                    law,
                )
            )
    return out


def _count(n: int, word: str) -> str:
    return f"{n} {word}{'' if n == 1 else 's'}"
