"""The battery's thresholds: profiles by what an engine claims, the keys a user may set
and their validation, files that hold them, and baselines (issues 19 and 29).

Keys are a figure's name (``"velocity"``: every scenario that has it) or
``"scenario.figure"`` (``"heavy_top.nutation_period"``: that scenario only, and it wins
over the plain name); a value ``None`` reports the figure without checking it;
``order`` is a lower bound, every other figure an upper bound.

Profiles
--------
A profile (:data:`PROFILES`) is a full set of bounds for a class of engine: the
magnitude every figure may reach at the battery's finest step **and** a lower bound on
the order of convergence, so that a correct engine of the class passes and a wrong law
fails.  The magnitudes alone cannot tell a bug from step error (a correct first-order
engine is off by 0.5 % on the built-in free tops at 2⁻⁸ s and by up to 14 % on drawn
ones, a wrong law by 40 % or more); the order can: a wrong law's error does not shrink
with the step (the four bugs of issue 29's trial read |order| ≤ 0.02), a right one's
does at the class's rate.  The bounds hold the class's correct toys
(tests/conformance/toys.py) on the built-in scenarios and on drawn ones
(:func:`mechanics.strategies.scenarios`), with the margins below:

==============  ==  =====  ====================  =====================================
profile         p   order  bound (every figure)  measured on a correct engine of the
                    ≥                            class (built-in and 250–400 drawn)
==============  ==  =====  ====================  =====================================
first-order     1   0.5    2⁻² = 25 %            semi-implicit Euler: ≤ 14 % (a drawn
                                                 free top's attitude), order ≥ 0.68 (a
                                                 drawn bounce's events, before the
                                                 asymptotic regime)
second-order    2   1.5    2⁻⁸ ≈ 0.39 %          explicit midpoint: ≤ 5.6e-4 (drawn
                                                 free tops), order ≥ 2.00
high-order      4   3      2⁻²⁰ ≈ 9.5e-7         classical Runge–Kutta: ≤ 2.9e-8, order
                                                 ≥ 4.00
exact           —   —      2⁻²⁸ ≈ 3.7e-9         closed forms and the scene engine
                                                 (DOP853 at 1e-12): ≤ 5.4e-10, the floor
                                                 of reading periods off samples
default         —   —      2⁻¹⁰ ≈ 9.8e-4         (engineering accuracy; order reported)
==============  ==  =====  ====================  =====================================

Two exceptions, each for a reason that holds for every engine of a stepping class:

- **impacts** (``two_body_impact``, ``bouncing_ball``, ``box_landing_flat``,
  ``newtons_cradle``, ``bounce_to_rest``, ``oblique_impact_sticks``,
  ``oblique_impact_slips``): an engine that does not locate
  events bounces up to a step late, and a sample between its impact and the exact one
  sees the velocity before against the velocity after (the toy: 1.13 relative at
  2⁻⁸ s).  ``velocity`` and ``omega`` (the quantities that jump) are reported, not
  checked; position and attitude (continuous) are, and the event figures (apex heights
  and times, velocities after, the impact time) judge the law, and give the order.
- **near the separatrix** (``free_top_near_separatrix``): the motion amplifies a phase
  error (the toys' attitude error there is 14 to 55 times the other free tops'), so its
  ``attitude`` and ``omega`` get 2³ times the profile's bound (second-order 2⁻⁵: the
  midpoint toy's worst on drawn ones 2.8e-3); the drifts keep the profile's.  A
  first-order engine does not resolve the motion there at the battery's steps: on drawn
  near-separatrix tops the correct toy's attitude error reached 0.67 and its order read
  0.77, short of the asymptotic regime.  At ``first-order`` the attitude, ω, the period
  and the order are reported there, not checked; the E and L drifts keep the bound (the
  toy's E drift reached 6.6 %; a wrong gyroscopic term's L drifts 0.59 there, an
  active attitude's 1.6).
"""

from __future__ import annotations

import math
import os
import tomllib
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType
from typing import Any

from .._floats import EPS
from ..errors import MechanicsValueError
from .protocol import Scenario
from .scenarios import SCENARIOS, figure_names, invariant_names

__all__ = [
    "DEFAULT_PROFILE",
    "DEFAULT_RTOL",
    "DEFAULT_THRESHOLDS",
    "PROFILES",
    "PYPROJECT_TABLE",
    "STATE_FIGURES",
    "Config",
    "Profile",
    "ThresholdError",
    "baseline",
    "find_config",
    "get_profile",
    "known_threshold_keys",
    "load_config",
    "resolve_thresholds",
]

#: 2^-10 ≈ 0.1 %: engineering accuracy.  A convergent engine at the battery's finest
#: step stays far below it (RK4 ~1e-9, the project's DOP853 ~1e-10), a wrong law (a sign,
#: a lost e, a transposed attitude) is off by O(1); users tighten it for their engine
DEFAULT_RTOL = 2**42 * EPS

STATE_FIGURES = ("position", "velocity", "attitude", "omega", "mass")


def _defaults(rtol: float = DEFAULT_RTOL, order: float | None = None) -> dict[str, float | None]:
    out: dict[str, float | None] = dict.fromkeys(STATE_FIGURES, rtol)
    for s in SCENARIOS.values():
        for f in figure_names(s):
            out[f] = rtol
        for q in invariant_names(s):
            out[f"{q}_drift"] = rtol
    out["order"] = order
    return out


#: Every figure's default bound (relative unless said otherwise; ``order`` a lower bound,
#: ``None``: reported, not checked).
DEFAULT_THRESHOLDS: dict[str, float | None] = _defaults()


class ThresholdError(MechanicsValueError):
    """A threshold the battery does not know, a value that is not a number ≥ 0, or a
    profile that does not exist."""


#: the scenarios with impacts, whose velocity and omega jump at an event
_IMPACT_SCENARIOS = (
    "two_body_impact",
    "bouncing_ball",
    "box_landing_flat",
    "newtons_cradle",
    "bounce_to_rest",
    "oblique_impact_sticks",
    "oblique_impact_slips",
)
#: how much looser the near-separatrix phase figures are than the profile's bound
_SEPARATRIX_FACTOR = 2.0**3


@dataclass(frozen=True)
class Profile:
    """A class of engine: the order it claims and the bound on every figure.

    Parameters
    ----------
    name : str
        The profile's name, a key of :data:`PROFILES`.
    order : float or None
        The order of convergence the class claims (None: none is read).
    rtol : float
        The bound on every figure at the finest step (relative), > 0.
    description : str
        One line on the class.
    thresholds : Mapping of str to float or None
        Every figure's bound (plain and ``scenario.figure`` keys; None: reported, not
        checked); ``order`` is a lower bound.

    Examples
    --------
    A second-order engine is judged at 2⁻⁸ and an order of at least 1.5:

    >>> p = get_profile("second-order")
    >>> p.order, p.rtol == 2.0**-8 == p.thresholds["velocity"], p.thresholds["order"]
    (2.0, True, 1.5)
    """

    name: str
    order: float | None
    rtol: float
    description: str
    thresholds: Mapping[str, float | None] = field(repr=False)


def _profile(
    name: str, order: float | None, least: float | None, rtol: float, description: str
) -> Profile:
    th = _defaults(rtol, least)
    if order is not None:  # a stepping class: the exceptions of the module's docstring
        for s in _IMPACT_SCENARIOS:
            th[f"{s}.velocity"] = th[f"{s}.omega"] = None
        near = "free_top_near_separatrix"
        if order > 1:
            for f in ("attitude", "omega"):
                th[f"{near}.{f}"] = _SEPARATRIX_FACTOR * rtol
        else:  # a first-order engine does not resolve the phase there: see the docstring
            for f in ("attitude", "omega", "omega_period", "order"):
                th[f"{near}.{f}"] = None
    return Profile(name, order, rtol, description, MappingProxyType(th))


#: the profiles by name (see the module's docstring for their figures)
PROFILES: Mapping[str, Profile] = MappingProxyType(
    {
        p.name: p
        for p in (
            _profile("first-order", 1.0, 0.5, 2.0**-2, "an engine of order 1 (explicit or "
                     "semi-implicit Euler), judged at 2^-2 and order >= 0.5"),
            _profile("second-order", 2.0, 1.5, 2.0**-8, "an engine of order 2 (midpoint, "
                     "Verlet, Moreau-Jean at theta 1/2), judged at 2^-8 and order >= 1.5"),
            _profile("high-order", 4.0, 3.0, 2.0**-20, "an engine of order 4 or more (classical "
                     "Runge-Kutta), judged at 2^-20 and order >= 3"),
            _profile("exact", None, None, 2.0**-28, "closed forms, or an integrator run to near "
                     "rounding (error control at 1e-12), judged at 2^-28; no order"),
            Profile("default", None, DEFAULT_RTOL, "engineering accuracy 2^-10 on every "
                    "figure; the order reported, not checked", MappingProxyType(_defaults())),
        )
    }
)  # fmt: skip
#: the profile used when none is named (by the caller, the file or the adapter)
DEFAULT_PROFILE = "default"


def get_profile(name: str) -> Profile:
    """The profile called ``name``; :class:`ThresholdError` naming it and the known ones.

    Parameters
    ----------
    name : str
        A key of :data:`PROFILES`.

    Returns
    -------
    Profile
        The profile.

    Raises
    ------
    ThresholdError
        Where ``name`` is not a profile's name (the message lists the known ones).

    Examples
    --------
    >>> get_profile("exact").rtol == PROFILES["exact"].rtol == 2.0**-28
    True
    >>> get_profile("fourth-order")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    mechanics.conformance.thresholds.ThresholdError: unknown conformance profile ...
    """
    p = PROFILES.get(name) if isinstance(name, str) else None
    if p is None:
        raise ThresholdError(f"unknown conformance profile {name!r}; known: {', '.join(PROFILES)}")
    return p


def _figures_of(s: Scenario) -> tuple[str, ...]:
    state = STATE_FIGURES if s.thrust is not None else STATE_FIGURES[:-1]
    drift = tuple(f"{q}_drift" for q in invariant_names(s))
    return (*state, *figure_names(s), *drift, "order")


def known_threshold_keys(scenarios: Iterable[Scenario] = ()) -> set[str]:
    """Every key a threshold dict may use: figure names and ``scenario.figure``.

    Parameters
    ----------
    scenarios : iterable of Scenario, optional
        Scenarios beyond the battery's own whose ``scenario.figure`` keys to add.

    Returns
    -------
    set of str
        The plain figure names and every ``scenario.figure`` of the battery's scenarios
        and of ``scenarios``.

    Raises
    ------
    UnknownScenarioError
        Where a scenario of ``scenarios`` is of an unknown kind (``extra["kind"]``).

    Examples
    --------
    >>> keys = known_threshold_keys()
    >>> {"velocity", "parabola.apex_height", "parabola.order"} <= keys, "apex" in keys
    (True, False)
    """
    keys = set(DEFAULT_THRESHOLDS)
    for s in [*SCENARIOS.values(), *scenarios]:
        keys.update(f"{s.name}.{f}" for f in _figures_of(s))
    return keys


def resolve_thresholds(thresholds: Mapping | None, scenarios: Iterable[Scenario] = ()) -> dict:
    """Validate a user's thresholds; return them as a plain dict of floats (or None).

    Parameters
    ----------
    thresholds : Mapping or None
        ``{"figure": bound}`` or ``{"scenario.figure": bound}``, each bound a finite number
        ≥ 0 or None (reported, not checked); None: no thresholds.
    scenarios : iterable of Scenario, optional
        Scenarios beyond the battery's own whose ``scenario.figure`` keys are allowed.

    Returns
    -------
    dict
        The same keys, each bound as a float or None (``{}`` for None).

    Raises
    ------
    ThresholdError
        Where ``thresholds`` is not a mapping, naming every unknown key (and the known
        figure names), or the first value that is not a finite number ≥ 0 or None.
    UnknownScenarioError
        Where a scenario of ``scenarios`` is of an unknown kind.

    Examples
    --------
    >>> resolve_thresholds({"velocity": 1e-2, "parabola.apex_height": None})
    {'velocity': 0.01, 'parabola.apex_height': None}
    >>> resolve_thresholds({"velocty": 1e-2})  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    mechanics.conformance.thresholds.ThresholdError: unknown threshold key(s) 'velocty'; ...
    """
    if thresholds is None:
        return {}
    if not isinstance(thresholds, Mapping):
        raise ThresholdError(
            f"thresholds must be a dict of figure name -> number; got {type(thresholds).__name__}"
        )
    known = known_threshold_keys(scenarios)
    unknown = sorted(str(k) for k in thresholds if k not in known)
    if unknown:
        raise ThresholdError(
            f"unknown threshold key(s) {', '.join(repr(k) for k in unknown)}; a key is a "
            f"figure ({', '.join(sorted(DEFAULT_THRESHOLDS))}) or 'scenario.figure'"
        )
    out = {}
    for k, v in thresholds.items():
        if v is not None:
            try:
                x = float(v)
            except (TypeError, ValueError):
                x = math.nan
            if not (math.isfinite(x) and x >= 0) or isinstance(v, bool):
                raise ThresholdError(
                    f"threshold {k!r} must be a finite number >= 0 (or None); got {v!r}"
                )
            v = x
        out[k] = v
    return out


def _threshold(layers: Sequence[Mapping], scenario: str, name: str):
    """The bound of figure ``name`` in ``scenario``: the last layer (profile, adapter,
    file, caller) that sets it wins, and within a layer ``scenario.figure`` wins over
    ``figure`` (so a user's plain ``attitude`` overrides a profile's per-scenario one)."""
    key = f"{scenario}.{name}"
    for layer in reversed(layers):
        if key in layer:
            return layer[key]
        if name in layer:
            return layer[name]
    return DEFAULT_THRESHOLDS.get(name)


# --------------------------------------------------------------------------- files

#: the table of a project's pyproject.toml that holds the battery's settings
PYPROJECT_TABLE = ("tool", "bodycheck", "conformance")
_TABLE_NAME = "[" + ".".join(PYPROJECT_TABLE) + "]"


@dataclass(frozen=True)
class Config:
    """The battery's settings read from a file: a profile, thresholds and their source.

    Parameters
    ----------
    profile : str or None, optional
        A profile's name (:data:`PROFILES`), or None (default) when the file names none.
    thresholds : Mapping of str to float or None, optional
        The thresholds it sets (default none).
    source : str, optional
        The file and table they came from ("" when no file was read, the default).

    Examples
    --------
    The settings of no file change nothing:

    >>> cfg = Config()
    >>> cfg.profile, dict(cfg.thresholds), cfg.source
    (None, {}, '')
    """

    profile: str | None = None
    thresholds: Mapping[str, float | None] = field(default_factory=dict)
    source: str = ""


def find_config(start: str | os.PathLike[str] | None = None) -> Path | None:
    """The nearest ``pyproject.toml`` from ``start`` (default: the working directory) upwards.

    Parameters
    ----------
    start : str or path-like, optional
        The folder to start from (default: the working directory).

    Returns
    -------
    Path or None
        The first ``pyproject.toml`` in ``start`` or one of its parents, or None.

    Raises
    ------
    TypeError
        Where ``start`` is not a str or path-like (:class:`pathlib.Path`'s).

    Examples
    --------
    From a folder and from a file of the folder: the same file.

    >>> import pathlib, tempfile
    >>> top = pathlib.Path(tempfile.mkdtemp()).resolve()
    >>> _ = (top / "pyproject.toml").write_text("")
    >>> (top / "src").mkdir()
    >>> find_config(top / "src") == find_config(top) == top / "pyproject.toml"
    True
    """
    here = Path.cwd() if start is None else Path(start)
    for folder in (here, *here.resolve().parents):
        candidate = folder / "pyproject.toml"
        if candidate.is_file():
            return candidate
    return None


def _file_value(where: str, key: str, value: object) -> float | None:
    if isinstance(value, str) and value.strip().lower() == "none":
        return None
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise ThresholdError(
            f'{where}: threshold {key!r} must be a number >= 0 or "none"; got {value!r}'
        )
    return float(value)


def load_config(path: str | os.PathLike[str], scenarios: Iterable[Scenario] = ()) -> Config:
    r"""Read the battery's settings from ``path``.

    A ``pyproject.toml`` holds them in its table ``[tool.bodycheck.conformance]`` (none
    there: an empty :class:`Config`); any other TOML file at its top level.  Either way
    the keys are ``profile`` (a name of :data:`PROFILES`) and ``thresholds`` (a table
    of figure or ``"scenario.figure"`` keys to numbers, or ``"none"`` to report a
    figure without checking it).  Anything else is a :class:`ThresholdError` naming
    the file, the key and what is expected.

    Parameters
    ----------
    path : str or path-like
        A TOML file: a ``pyproject.toml`` or a thresholds file.
    scenarios : iterable of Scenario, optional
        Scenarios beyond the battery's own whose ``scenario.figure`` keys are allowed.

    Returns
    -------
    Config
        The profile, the thresholds (validated by :func:`resolve_thresholds`) and the
        file (and table) they came from.

    Raises
    ------
    ThresholdError
        Where the file does not exist or is not valid TOML, has an unknown key, an
        unknown profile, a ``thresholds`` that is not a table, or a threshold that is
        not a number ≥ 0 or ``"none"`` (naming the file, the key and what is expected).

    Examples
    --------
    A file's thresholds, read back; ``"none"`` reports a figure without checking it:

    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "bounds.toml"
    >>> _ = path.write_text('profile = "exact"\n[thresholds]\nvelocity = 0.25\norder = "none"\n')
    >>> cfg = load_config(path)
    >>> cfg.profile, dict(cfg.thresholds)
    ('exact', {'velocity': 0.25, 'order': None})
    """
    p = Path(path)
    if not p.is_file():
        why = "is not a file" if p.exists() else "does not exist"
        raise ThresholdError(f"thresholds file {str(p)!r} {why}")
    try:
        data: object = tomllib.loads(p.read_text(encoding="utf-8"))
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise ThresholdError(f"thresholds file {str(p)!r} is not valid TOML: {exc}") from None
    where = str(p)
    if p.name == "pyproject.toml":
        for part in PYPROJECT_TABLE:
            data = data.get(part) if isinstance(data, dict) else None
            if data is None:
                return Config()
        where = f"{p} {_TABLE_NAME}"
    if not isinstance(data, dict):
        raise ThresholdError(f"{where} must be a table")
    unknown = sorted(set(data) - {"profile", "thresholds"})
    if unknown:
        raise ThresholdError(
            f"{where}: unknown key(s) {', '.join(repr(k) for k in unknown)}; expected "
            "'profile' and a table 'thresholds'"
        )
    profile = data.get("profile")
    if profile is not None:
        try:
            get_profile(profile)
        except ThresholdError as exc:
            raise ThresholdError(f"{where}: {exc}") from None
    raw = data.get("thresholds", {})
    if not isinstance(raw, dict):
        raise ThresholdError(
            f"{where}: 'thresholds' must be a table of figure = number; got {raw!r}"
        )
    values = {k: _file_value(where, k, v) for k, v in raw.items()}
    try:
        th = resolve_thresholds(values, scenarios)
    except ThresholdError as exc:
        raise ThresholdError(f"{where}: {exc}") from None
    return Config(profile, MappingProxyType(th), where)


# --------------------------------------------------------------------------- baselines


def _rounded_up(x: float) -> str:
    """x to three significant digits, never below x (a bound must hold what it pins)."""
    text = f"{x:.3g}"
    if float(text) >= x:
        return text
    unit = 10.0 ** (math.floor(math.log10(x)) - 2)  # the third digit's place
    return f"{math.ceil(x / unit) * unit:.3g}"


def baseline(report: Any, margin: float = 2.0) -> str:
    """A thresholds file (TOML) that pins ``report``'s accuracy with ``margin``.

    ``report`` is a :class:`~.battery.Report`, read by its fields (this module sits below
    the battery).  Every checked error and drift figure of each scenario that ran is bounded at
    ``margin`` times its measured value (at least 2¹⁰ eps, rounding), under its
    ``scenario.figure`` key; the order's lower bound is the measured order less
    log(margin) / log(h_coarse / h_fine), the order the runs would read had the finest
    run's error grown by the margin.  Figures the profile leaves unchecked stay so; one
    that could not be measured (an unmatched event) is written ``"none"`` with the
    reason.  The profile is the report's.  Load it with :func:`load_config` (or the
    command's ``--config``).

    Parameters
    ----------
    report : Report
        The battery's report to pin.
    margin : float, optional
        How many times its measured value each figure may reach, finite, ≥ 1 (default 2).

    Returns
    -------
    str
        The TOML text: ``profile`` and a table ``[thresholds]`` of ``scenario.figure``
        keys; scenarios that did not run are listed as comments.

    Raises
    ------
    ThresholdError
        Where ``margin`` is not a finite number ≥ 1.

    Examples
    --------
    The baseline, read back, holds the report that made it:

    >>> import pathlib, tempfile
    >>> from mechanics.conformance import run_battery
    >>> from mechanics.conformance.adapters import ExactAdapter
    >>> report = run_battery(ExactAdapter(), scenarios=["parabola"], profile="exact")
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "baseline.toml"
    >>> _ = path.write_text(baseline(report))
    >>> th = load_config(path).thresholds
    >>> all(f.value <= th[f"parabola.{f.name}"] for f in report["parabola"].figures)
    True
    """
    if not (isinstance(margin, int | float) and math.isfinite(margin) and margin >= 1):
        raise ThresholdError(f"the baseline's margin must be a number >= 1; got {margin!r}")
    lines = [
        f"# The conformance battery's baseline for {report.adapter!r}: profile",
        f"# {report.profile}, each figure at {margin:g} x its measured value (at least 2^10 eps),",
        "# the order at its measured value less log(margin)/log(h_coarse/h_fine).",
        f'profile = "{report.profile}"',
        "",
        "[thresholds]",
    ]
    skipped = []
    for r in report.results:
        if r.status not in ("pass", "fail"):
            skipped.append(f"# {r.scenario}: {r.status}, not pinned ({r.message})")
            continue
        for f in r.figures:
            if f.threshold is None or f.value is None:
                continue
            key = f'"{r.scenario}.{f.name}"'
            if f.kind == "order":
                steps = [run.step for run in r.runs if run.step is not None]
                drop = math.log(margin) / math.log(max(steps) / min(steps))
                lines.append(f"{key} = {max(f.value - drop, 0.0):.3g}")
            elif not math.isfinite(f.value):
                lines.append(f'{key} = "none"  # not measured: {f.note}')
            else:
                lines.append(f"{key} = {_rounded_up(max(margin * f.value, 2**10 * EPS))}")
    return "\n".join([*lines, *skipped]) + "\n"
