"""Run the conformance battery against an adapter and report, per scenario, how far the
engine is from the book (issue 19).

For each scenario of :data:`~mechanics.conformance.scenarios.SCENARIOS` (or the ones
given) the battery

1. asks ``adapter.supports(scenario)``: a reason makes it **unsupported** (shown, never
   passed by omission);
2. runs it, once with ``step=None`` or, when ``adapter.takes_step``, at each of the
   scenario's ``steps`` (coarse to fine), timing each run (wall time, ``perf_counter``);
   an adapter that raises, or returns what :func:`~.protocol.check_trajectory` refuses,
   makes the scenario an **error** with the exception's type and message (the battery
   goes on with the next scenario);
3. compares the finest run with the exact reference
   (:func:`~mechanics.conformance.scenarios.reference`): the state errors ``position``,
   ``velocity``, ``omega`` (relative to the motion's scales, see :func:`state_errors`),
   ``attitude`` (absolute, the largest entry of R − R_exact) and ``mass`` (with thrust);
   the scenario's derived figures measured from the samples (periods, rates, apexes,
   e, Δv; relative errors); the drift of each conserved quantity,
   max |Q(t) − Q(0)| / scale (``E_drift``, ``p_drift``, ``L_drift``, about the point
   where each is conserved: the pivot's vertical ``L_z_drift`` for the heavy top);
4. with two or more steps, the **order of convergence**: the slope of log(error) against
   log(step) through the runs whose error is above rounding (:data:`ORDER_FLOOR`), the
   error being the largest state error, or for a scenario with impacts the largest
   error of its event figures (a sample between an impact and an engine's late one
   sees a jump that does not shrink with the step);
5. marks the scenario **pass** when every checked figure is within its threshold, else
   **fail** naming each figure, its value and the threshold, followed by what the
   figures imply (:mod:`~mechanics.conformance.diagnosis`).

The thresholds come from a profile (:mod:`~mechanics.conformance.thresholds`), the
adapter's own ``profile`` and ``thresholds``, a thresholds file and the caller, each
overriding the one before.

Thresholds
----------
:data:`DEFAULT_THRESHOLDS` maps a figure name to its bound; a user's dict overrides it
with keys ``"figure"`` (every scenario that has the figure) or ``"scenario.figure"``
(one scenario; it wins over the plain name).  A value ``None`` reports the figure
without checking it.  ``order`` is a lower bound (default ``None``: reported only); all
the others are upper bounds.  Unknown keys are refused, naming them.

Conserved quantities claimed (and why no others): free tops E, p, L; the heavy top E,
L_z about the pivot's vertical and L₃ (5.53, 5.55, 5.66); the parabola E and the
horizontal momentum; the two-body impact p and L about the origin, kept by the internal
central impulse (E is lost, 6.41); the bouncing ball the tangential momentum (smooth
ground; E is lost at each impact, p_z reversed); the rocket nothing (mass leaves with its
momentum and energy).
"""

from __future__ import annotations

import json
import math
import time
from collections.abc import Mapping
from dataclasses import asdict, dataclass, field

import numpy as np

from .._floats import EPS
from .diagnosis import diagnose
from .protocol import ConformanceError, Scenario, Trajectory, check_trajectory
from .scenarios import (
    SCENARIOS,
    UnknownScenarioError,
    body_sizes,
    check_scenario,
    get_scenario,
    invariants,
    measure,
    reference,
)
from .thresholds import (
    DEFAULT_PROFILE,
    DEFAULT_RTOL,
    DEFAULT_THRESHOLDS,
    STATE_FIGURES,
    Config,
    ThresholdError,
    _threshold,
    get_profile,
    known_threshold_keys,
    resolve_thresholds,
)

__all__ = [
    "DEFAULT_RTOL",
    "DEFAULT_THRESHOLDS",
    "ORDER_FLOOR",
    "STATE_FIGURES",
    "STATUSES",
    "Figure",
    "Report",
    "Run",
    "ScenarioResult",
    "ThresholdError",
    "known_threshold_keys",
    "resolve_thresholds",
    "run_battery",
    "state_errors",
]

#: state errors below 2^10 eps of their scale are rounding: no order is read from them
ORDER_FLOOR = 2**10 * EPS

STATUSES = ("pass", "fail", "unsupported", "error")


# --------------------------------------------------------------------------- results


@dataclass
class Figure:
    """One figure of a scenario: its value, its threshold and whether it passed.

    Parameters
    ----------
    name : str
        The figure's name (``"velocity"``, ``"E_drift"``, ``"apex_height"``, ``"order"``).
    kind : {"error", "drift", "order"}
        ``"error"`` (relative unless ``attitude``), ``"drift"`` (relative to the
        quantity's scale) or ``"order"`` (of convergence; its threshold a lower bound).
    value : float or None
        The measured value (inf: could not be read, see ``note``; None: no value).
    threshold : float or None
        Its bound (None: reported, not checked).
    passed : bool or None
        Whether the value is within the bound; None when the figure is not checked.
    note : str, optional
        Why a value could not be read, or how it was (default "").

    Examples
    --------
    >>> f = Figure("velocity", "error", 2**-11, 2**-10, True)
    >>> f.passed == (f.value <= f.threshold), f.describe()
    (True, 'velocity 0.000488 within threshold <= 0.000977')
    """

    name: str
    kind: str
    value: float | None
    threshold: float | None
    passed: bool | None
    note: str = ""

    def describe(self) -> str:
        v = "n/a" if self.value is None else f"{self.value:.3g}"
        if self.threshold is None:
            return f"{self.name} {v}"
        rel = ">=" if self.kind == "order" else "<="
        if self.passed is None:  # a threshold, but no value to judge (e.g. no order)
            word = "not checked against"
        else:
            word = "within" if self.passed else "violates"
        text = f"{self.name} {v} {word} threshold {rel} {self.threshold:.3g}"
        return f"{text} ({self.note})" if self.note else text


@dataclass
class Run:
    """One run of the adapter: the step, the wall time and the largest relative error.

    Parameters
    ----------
    step : float or None
        The fixed step, s (None: the engine chose its own).
    wall_time : float
        The run's wall time, s (``perf_counter``).
    error : float
        The largest relative state error of the run (for a scenario with impacts, the
        largest error of its event figures).

    Examples
    --------
    The exact column runs once, at its own step, with no error:

    >>> from mechanics.conformance.adapters import ExactAdapter
    >>> (run,) = run_battery(ExactAdapter(), scenarios=["parabola"]).results[0].runs
    >>> run.step, run.error, run.wall_time >= 0
    (None, 0.0, True)
    """

    step: float | None
    wall_time: float
    error: float


@dataclass
class ScenarioResult:
    """A scenario's verdict: its status, the reason, its figures and runs.

    Parameters
    ----------
    scenario : str
        The scenario's name.
    description : str
        Its one-line description.
    book : str
        What its reference comes from.
    status : {"pass", "fail", "unsupported", "error"}
        The verdict (:data:`STATUSES`).
    message : str, optional
        The reason: the failed figures, the adapter's exception, its unsupported reason
        (default "").
    figures : list of Figure, optional
        Every figure judged (default none).
    runs : list of Run, optional
        The runs, coarse to fine (default none).
    diagnosis : list of str, optional
        What the failing figures imply (:mod:`~mechanics.conformance.diagnosis`).

    Examples
    --------
    The worst figure is the one nearest its bound:

    >>> from mechanics.conformance.adapters import ExactAdapter
    >>> r = run_battery(ExactAdapter(), scenarios=["parabola"]).results[0]
    >>> ratio = {f.name: f.value / f.threshold for f in r.figures if f.kind != "order"}
    >>> r.status, r.worst.name == max(ratio, key=ratio.get)
    ('pass', True)
    """

    scenario: str
    description: str
    book: str
    status: str
    message: str = ""
    figures: list[Figure] = field(default_factory=list)
    runs: list[Run] = field(default_factory=list)
    #: what the failing figures imply (:mod:`~mechanics.conformance.diagnosis`)
    diagnosis: list[str] = field(default_factory=list)

    def _get_wall_time(self) -> float:
        """Wall time of the finest (last) run, s; nan when nothing ran."""
        return self.runs[-1].wall_time if self.runs else math.nan

    # applied after the definition, so that mutmut mutates the function (it skips decorated ones)
    wall_time = property(_get_wall_time)

    def _get_order(self) -> float | None:
        f = self.figure("order")
        return None if f is None else f.value

    # applied after the definition, so that mutmut mutates the function (it skips decorated ones)
    order = property(_get_order)

    def figure(self, name: str) -> Figure | None:
        return next((f for f in self.figures if f.name == name), None)

    def _get_worst(self) -> Figure | None:
        """The checked error or drift figure nearest to (or furthest beyond) its bound,
        among those measured (a finite value: see :attr:`unmeasured`)."""
        checked = [
            (f, f.value / f.threshold)
            for f in self.figures
            if f.kind != "order" and f.threshold and f.value is not None
            if math.isfinite(f.value)
        ]
        best = max(checked, key=lambda pair: pair[1], default=None)
        return None if best is None else best[0]

    # applied after the definition, so that mutmut mutates the function (it skips decorated ones)
    worst = property(_get_worst)

    def _get_unmeasured(self) -> list[Figure]:
        """The figures that could not be read off the samples (an unmatched event: the
        value is inf and the note says why)."""
        return [f for f in self.figures if f.value is not None and not math.isfinite(f.value)]

    # applied after the definition, so that mutmut mutates the function (it skips decorated ones)
    unmeasured = property(_get_unmeasured)


@dataclass
class Report:
    """The battery's results for one adapter, in scenario order.

    Parameters
    ----------
    adapter : str
        The adapter's name.
    results : list of ScenarioResult
        One per scenario, in the order run.
    thresholds : dict
        The thresholds set over the profile's (the adapter's, the file's, the caller's).
    profile : str, optional
        The profile's name (default ``"default"``).
    config : str, optional
        The file (and table) the settings came from; "" (default) when none was read.

    Examples
    --------
    Its counts add up to its scenarios, and its JSON says the same:

    >>> import json
    >>> from mechanics.conformance.adapters import ExactAdapter
    >>> report = run_battery(ExactAdapter(), scenarios=["parabola", "rocket"])
    >>> sum(report.counts().values()) == len(report.results), report["rocket"].status
    (True, 'pass')
    >>> json.loads(report.to_json())["counts"] == report.counts()
    True
    """

    adapter: str
    results: list[ScenarioResult]
    thresholds: dict
    profile: str = DEFAULT_PROFILE
    #: the file (and table) the settings came from; "" when none was read
    config: str = ""

    def __getitem__(self, name: str) -> ScenarioResult:
        for r in self.results:
            if r.scenario == name:
                return r
        raise KeyError(name)

    def _get_passed(self) -> bool:
        """No scenario failed or errored (unsupported ones are listed, not failures)."""
        return all(r.status in ("pass", "unsupported") for r in self.results)

    # applied after the definition, so that mutmut mutates the function (it skips decorated ones)
    passed = property(_get_passed)

    def counts(self) -> dict[str, int]:
        return {s: sum(r.status == s for r in self.results) for s in STATUSES}

    def as_dict(self) -> dict:
        def clean(x):
            if isinstance(x, float) and not math.isfinite(x):
                return None if math.isnan(x) else ("inf" if x > 0 else "-inf")
            if isinstance(x, dict):
                return {k: clean(v) for k, v in x.items()}
            if isinstance(x, list):
                return [clean(v) for v in x]
            return x

        out = {
            "adapter": self.adapter,
            "passed": self.passed,
            "counts": self.counts(),
            "profile": self.profile,
            "config": self.config,
            "thresholds": self.thresholds,
            "scenarios": [
                {**asdict(r), "wall_time": r.wall_time, "order": r.order} for r in self.results
            ],
        }
        return clean(out)

    def to_json(self) -> str:
        """The report as JSON (non-finite numbers as null or "inf")."""
        return json.dumps(self.as_dict(), indent=2)

    def to_markdown(self) -> str:
        """A table: scenario, status, the worst figure against its threshold, the order,
        the wall time; then one line per failed, errored or unsupported scenario."""
        c = self.counts()
        lines = [
            f"# Conformance: {self.adapter}",
            "",
            f"Profile {self.profile}: {get_profile(self.profile).description}."
            + (f" Thresholds from {self.config}." if self.config else ""),
            "",
            ", ".join(f"{n} {s}" for s, n in c.items()),
            "",
            "| scenario | status | worst figure | threshold | order | wall time (s) |",
            "|---|---|---|---|---|---|",
        ]
        for r in self.results:
            w = r.worst
            fig = f"{w.name} {w.value:.3g}" if w is not None else ""
            if r.unmeasured:
                fig += f" (+{len(r.unmeasured)} not measured)"
            thr = f"{w.threshold:.3g}" if w is not None else ""
            order = f"{r.order:.2f}" if r.order is not None else ""
            wall = f"{r.wall_time:.3g}" if r.runs else ""
            lines.append(f"| {r.scenario} | {r.status} | {fig} | {thr} | {order} | {wall} |")
        notes = [f"- {r.scenario} ({r.status}): {r.message}" for r in self.results if r.message]
        if notes:
            lines += ["", *notes]
        return "\n".join(lines) + "\n"


# --------------------------------------------------------------------------- measuring


def state_errors(s: Scenario, ref: Trajectory, tr: Trajectory) -> dict[str, float]:
    """Largest errors of a trajectory against the exact one over samples and bodies.

    position: |Δr| / L, L the larger of the largest |r| and the bodies' sizes;
    velocity: |Δv| / V, V the larger of the largest |v| and L·max|ω|;
    omega: |Δω| / max|ω| (V/L for bodies that do not turn);
    attitude: max |ΔR_ij| (absolute: the entries of a rotation are at most 1);
    mass: |Δm| / m₀, where the scenario has thrust (inf when no masses are returned).

    Parameters
    ----------
    s : Scenario
        The scenario.
    ref : Trajectory
        Its exact trajectory (:func:`~.scenarios.reference`): the scales come from it.
    tr : Trajectory
        The engine's trajectory, validated (:func:`~.protocol.check_trajectory`).

    Returns
    -------
    dict of str to float
        ``position``, ``velocity``, ``attitude``, ``omega`` and, with thrust, ``mass``.

    Raises
    ------
    ValueError
        Where the two trajectories' arrays do not broadcast (nothing is validated here:
        the battery validates ``tr`` first).
    ZeroDivisionError
        Where a body's mass is 0 (:func:`~.scenarios.body_sizes`).

    Examples
    --------
    The exact trajectory against itself:

    >>> from mechanics.conformance import get_scenario, reference
    >>> s = get_scenario("free_top_axis3")
    >>> ref = reference(s).trajectory
    >>> state_errors(s, ref, ref)
    {'position': 0.0, 'velocity': 0.0, 'attitude': 0.0, 'omega': 0.0}
    """
    L = max(float(np.max(np.linalg.norm(ref.position, axis=-1))), float(body_sizes(s).max()))
    W = float(np.max(np.linalg.norm(ref.omega, axis=-1)))
    V = max(float(np.max(np.linalg.norm(ref.velocity, axis=-1))), L * W)
    V = V if V > 0 else 1.0
    W = W if W > 0 else V / L

    def worst(a, b, scale):
        return float(np.max(np.linalg.norm(a - b, axis=-1))) / scale

    out = {
        "position": worst(tr.position, ref.position, L),
        "velocity": worst(tr.velocity, ref.velocity, V),
        "attitude": float(np.max(np.abs(tr.R_A_O - ref.R_A_O))),
        "omega": worst(tr.omega, ref.omega, W),
    }
    if s.thrust is not None:
        m0 = np.array([b.mass for b in s.bodies])
        out["mass"] = (
            math.inf if tr.masses is None else float(np.max(np.abs(tr.masses - ref.masses) / m0))
        )
    return out


def _relative(measured, exact) -> float:
    m, e = np.asarray(measured, dtype=float), np.asarray(exact, dtype=float)
    scale = float(np.max(np.abs(e)))
    diff = float(np.max(np.abs(m - e))) if m.shape == e.shape else math.inf
    return diff / scale if scale > 0 else diff


_ROUNDING = "errors at rounding level: no order to read"


def _order(runs: list[Run]) -> tuple[float | None, str]:
    use = [(r.step, r.error) for r in runs if r.step is not None and r.error > ORDER_FLOOR]
    if len(runs) < 2:
        return None, ""
    unread = next((step for step, error in use if not math.isfinite(error)), None)
    if unread is not None:
        return None, f"an event figure could not be read at step {unread:g} s: no order"
    if len(use) < 2:
        return None, _ROUNDING
    x = np.log([step for step, _ in use])
    y = np.log([error for _, error in use])
    return float(np.polyfit(x, y, 1)[0]), ""


def _judge(name, kind, value, threshold, note="") -> Figure:
    if threshold is None:
        return Figure(name, kind, value, None, None, note)
    if value is None:
        return Figure(name, kind, None, threshold, None, note)
    ok = value >= threshold if kind == "order" else value <= threshold
    return Figure(name, kind, value, threshold, bool(ok), note)


def _describe_exc(exc: BaseException) -> str:
    return f"{type(exc).__name__}: {exc}"


def _has_impacts(s: Scenario) -> bool:
    return s.ground is not None or bool(s.pair_restitution)


def _figure_errors(s: Scenario, ref, measured: dict) -> dict[str, tuple[float, str]]:
    """Each derived figure's relative error against the exact one, with the reason where
    it could not be read (then inf)."""
    out = {}
    for name, exact in ref.figures.items():
        m = measured[name]
        out[name] = (math.inf, m) if isinstance(m, str) else (_relative(m, exact), "")
    return out


def _run_one(adapter, s: Scenario, th: list[Mapping], repeats: int = 1) -> ScenarioResult:
    res = ScenarioResult(s.name, s.description, s.book, "error")
    try:
        why = adapter.supports(s)
    except Exception as exc:  # a crashing adapter fails its scenario, not the battery
        res.message = f"supports() raised {_describe_exc(exc)}"
        return res
    if why:
        res.status, res.message = "unsupported", str(why)
        return res
    ref = reference(s)
    steps = tuple(s.steps) if adapter.takes_step and s.steps else (None,)
    tr = None
    for h in steps:
        t0 = time.perf_counter()
        try:
            raw = adapter.run(s, h)
        except Exception as exc:
            at = "" if h is None else f" at step {h:g} s"
            res.message = f"run{at} raised {_describe_exc(exc)}"
            return res
        wall = time.perf_counter() - t0
        try:
            tr = check_trajectory(s, raw)
        except ConformanceError as exc:
            res.message = str(exc)
            return res
        errs = state_errors(s, ref.trajectory, tr)
        measured = measure(s, tr)
        events = _figure_errors(s, ref, measured)
        if _has_impacts(s):  # a sample between two impacts sees a jump: the events judge
            error = max(v for v, _ in events.values())
        else:
            error = max(v for k, v in errs.items() if k != "mass")
        res.runs.append(Run(h, wall, error))
    if tr is None:  # steps holds at least one step (None: the engine's own)
        raise AssertionError(f"scenario {s.name!r}: the battery ran no step")
    last = res.runs[-1]
    for _ in range(repeats - 1):  # the finest run again, for its time only
        t0 = time.perf_counter()
        try:
            adapter.run(s, last.step)
        except Exception as exc:  # as the first run's: the scenario fails, not the battery
            at = "" if last.step is None else f" at step {last.step:g} s"
            res.message = f"run{at}, repeated for its time, raised {_describe_exc(exc)}"
            return res
        res.runs[-1] = Run(
            last.step, min(res.runs[-1].wall_time, time.perf_counter() - t0), last.error
        )
    figs = [_judge(k, "error", v, _threshold(th, s.name, k)) for k, v in errs.items()]
    for name, (value, note) in events.items():
        figs.append(_judge(name, "error", value, _threshold(th, s.name, name), note))
    scales = {k: v[1] for k, v in invariants(s, ref.trajectory).items()}
    for name, (q, _) in invariants(s, tr).items():
        q, scale = np.asarray(q, dtype=float), scales[name]
        drift = float(np.max(np.abs(q - q[0]))) / scale
        key = f"{name}_drift"
        figs.append(_judge(key, "drift", drift, _threshold(th, s.name, key)))
    order, note = _order(res.runs)
    if order is not None and _has_impacts(s):
        note = "read from the event figures"
    thr = _threshold(th, s.name, "order")
    if order is None and note == _ROUNDING and thr is not None:  # nothing to converge
        figs.append(Figure("order", "order", None, thr, True, note))
    elif adapter.takes_step:
        figs.append(_judge("order", "order", order, thr, note))
    res.figures = figs
    bad = [f for f in figs if f.passed is False]
    res.status = "fail" if bad else "pass"
    res.message = "; ".join(f.describe() for f in bad)
    if bad:
        by_name = {f.name: f for f in figs}
        res.diagnosis = diagnose(s, ref.trajectory, tr, by_name, measured)
        if res.diagnosis:
            res.message += ". " + " ".join(res.diagnosis)
    return res


def _adapter_settings(adapter) -> tuple[str | None, dict]:
    """The adapter's own ``profile`` and ``thresholds`` attributes (both optional),
    validated; errors say they came from the adapter."""
    name = getattr(adapter, "profile", None)
    if name is not None and not isinstance(name, str):
        raise ThresholdError(
            f"the adapter's profile must be a profile's name (a str); got {name!r}"
        )
    try:
        th = resolve_thresholds(getattr(adapter, "thresholds", None))
    except ThresholdError as exc:
        raise ThresholdError(f"the adapter's thresholds: {exc}") from None
    return name, th


def run_battery(
    adapter, *, scenarios=None, thresholds=None, profile=None, config=None, repeats: int = 1
) -> Report:
    """Run the battery against ``adapter`` (see :class:`~.protocol.Adapter`).

    Parameters
    ----------
    adapter : Adapter
        The engine under test.  It may say what it claims: a ``profile`` attribute (a
        name of :data:`~.thresholds.PROFILES`) and a ``thresholds`` attribute (a dict as
        below), used where the caller does not say otherwise.
    scenarios : iterable of str or Scenario, optional
        Names from :data:`~.scenarios.SCENARIOS`, or scenarios (of a known kind) built
        by the user; default all of them, in order.
    thresholds : dict, optional
        Overrides: ``{"figure": bound}`` or ``{"scenario.figure": bound}``; ``None``
        reports without checking.  They win over the adapter's, which win over the
        profile's.
    profile : str, optional
        The profile whose bounds are the base (:data:`~.thresholds.PROFILES`); default
        the file's (``config``), else the adapter's ``profile``, else ``"default"``.
    config : Config, optional
        Settings read from a file (:func:`~.thresholds.load_config`): its thresholds
        win over the adapter's, the caller's over the file's.
    repeats : int, optional
        How many times the finest run of each scenario is timed: its wall time is the
        least of them (a shared machine's noise only adds time; the other runs give
        nothing else).  Default 1; ``bodycheck conform all`` takes 3.

    Returns
    -------
    Report
        One :class:`ScenarioResult` per scenario.

    Raises
    ------
    ConformanceError
        Where the adapter lacks ``name``, ``takes_step``, ``supports`` or ``run``, or
        ``repeats`` is not an int ≥ 1.  (An adapter that raises, or returns what the
        protocol refuses, makes its scenario an ``"error"``: the battery goes on.)
    UnknownScenarioError
        Where a scenario is neither a name nor a :class:`~.protocol.Scenario`, or is an
        unknown name or kind.
    ScenarioRangeError
        Where a user's scenario is outside its valid range
        (:func:`~.scenarios.check_scenario`).
    ThresholdError
        Where a threshold (the caller's or the adapter's) is unknown or not a number ≥ 0,
        or a profile does not exist.

    Examples
    --------
    >>> from mechanics.conformance.adapters import ExactAdapter
    >>> report = run_battery(ExactAdapter(), scenarios=["parabola"], profile="exact")
    >>> report["parabola"].status, report.passed, report.profile
    ('pass', True, 'exact')
    """
    for attr in ("name", "takes_step", "supports", "run"):
        if not hasattr(adapter, attr):
            raise ConformanceError(
                f"the adapter {adapter!r} has no {attr!r}: an adapter needs name, takes_step, "
                "supports(scenario) and run(scenario, step)"
            )
    chosen = []
    for x in SCENARIOS if scenarios is None else scenarios:
        if isinstance(x, Scenario):
            if x not in SCENARIOS.values():  # a user's variant: inside its valid range?
                check_scenario(x)
            chosen.append(x)
        elif isinstance(x, str):
            chosen.append(get_scenario(x))
        else:
            raise UnknownScenarioError(
                f"a scenario must be a name or a Scenario; got {type(x).__name__} {x!r}"
            )
    if isinstance(repeats, bool) or not isinstance(repeats, int) or repeats < 1:
        raise ConformanceError(f"repeats must be an int >= 1 (timings of a run); got {repeats!r}")
    own_profile, own = _adapter_settings(adapter)
    cfg = Config() if config is None else config
    chosen_profile = get_profile(profile or cfg.profile or own_profile or DEFAULT_PROFILE)
    th = resolve_thresholds(thresholds, chosen)
    layers = [chosen_profile.thresholds, own, dict(cfg.thresholds), th]
    results = [_run_one(adapter, s, layers, repeats) for s in chosen]
    merged = {**own, **cfg.thresholds, **th}
    return Report(str(adapter.name), results, merged, chosen_profile.name, cfg.source)
