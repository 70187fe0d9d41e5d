"""The battery's thresholds: every figure's default bound, the keys a user may set and
their validation (issue 19), and the lookup of a figure's bound for one scenario.

Keys are a figure's name (``"velocity"``: every scenario that has it) or
``"scenario.figure"`` (``"heavy_top.nutation_period"``: that scenario only, and it wins
over the plain name); a value ``None`` reports the figure without checking it;
``order`` is a lower bound, every other figure an upper bound.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping

from .._floats import EPS
from ..errors import MechanicsValueError
from .protocol import Scenario
from .scenarios import SCENARIOS, figure_names, invariant_names

__all__ = [
    "DEFAULT_RTOL",
    "DEFAULT_THRESHOLDS",
    "STATE_FIGURES",
    "ThresholdError",
    "known_threshold_keys",
    "resolve_thresholds",
]

#: 2^-10 ≈ 0.1 %: engineering accuracy.  A convergent engine at the battery's finest
#: step stays far below it (RK4 ~1e-9, the project's DOP853 ~1e-10), a wrong law (a sign,
#: a lost e, a transposed attitude) is off by O(1); users tighten it for their engine
DEFAULT_RTOL = 2**42 * EPS

STATE_FIGURES = ("position", "velocity", "attitude", "omega", "mass")


def _defaults() -> dict[str, float | None]:
    out: dict[str, float | None] = dict.fromkeys(STATE_FIGURES, DEFAULT_RTOL)
    for s in SCENARIOS.values():
        for f in figure_names(s):
            out[f] = DEFAULT_RTOL
        for q in invariant_names(s):
            out[f"{q}_drift"] = DEFAULT_RTOL
    out["order"] = None
    return out


#: Every figure's default bound (relative unless said otherwise; ``order`` a lower bound,
#: ``None``: reported, not checked).
DEFAULT_THRESHOLDS: dict[str, float | None] = _defaults()


class ThresholdError(MechanicsValueError):
    """A threshold the battery does not know, or a value that is not a number ≥ 0."""


def _figures_of(s: Scenario) -> tuple[str, ...]:
    state = STATE_FIGURES if s.thrust is not None else STATE_FIGURES[:-1]
    drift = tuple(f"{q}_drift" for q in invariant_names(s))
    return (*state, *figure_names(s), *drift, "order")


def known_threshold_keys(scenarios: Iterable[Scenario] = ()) -> set[str]:
    """Every key a threshold dict may use: figure names and ``scenario.figure``."""
    keys = set(DEFAULT_THRESHOLDS)
    for s in [*SCENARIOS.values(), *scenarios]:
        keys.update(f"{s.name}.{f}" for f in _figures_of(s))
    return keys


def resolve_thresholds(thresholds: Mapping | None, scenarios: Iterable[Scenario] = ()) -> dict:
    """Validate a user's thresholds; return them as a plain dict of floats (or None).

    Raises :class:`ThresholdError` naming every unknown key (and the known figure names)
    or the first value that is not a finite number ≥ 0 or None.

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


def _threshold(th: dict, scenario: str, name: str):
    key = f"{scenario}.{name}"
    if key in th:
        return th[key]
    return th.get(name, DEFAULT_THRESHOLDS.get(name))
