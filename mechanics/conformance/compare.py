"""The battery on several engines at once: one table, scenario by scenario, engine by engine.

:func:`engine_adapters` lists the reference columns (the closed forms, the project's
integrated scene engine) and every variant of each engine with an adapter here (MuJoCo's
integrators and contacts, PyBullet's steps and contacts, Drake's discrete and continuous
plants with point and hydroelastic contact, Siconos's Moreau–Jean at θ = 1/2 and 1,
DART's Dantzig and PGS boxed LCP); an
engine that is not installed is listed
once with the extra that installs it.  :func:`compare` runs the battery on each and
:meth:`Comparison.to_markdown` writes the table: per scenario and adapter its status,
worst error, worst drift (each with the figure's name), order of convergence and the
wall time of its finest run (the least of ``repeats`` timings).  ``bodycheck conform
all`` prints it, the least of 3 (``--markdown``, ``--plot`` and ``--json`` write it).
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field

from .battery import Figure, Report, ScenarioResult, run_battery

__all__ = ["ENGINE_MODULES", "Comparison", "compare", "engine_adapters"]

#: the engines with an adapter here: (adapter module, the engine's name, its extra)
ENGINE_MODULES = (
    ("mujoco", "MuJoCo", "mujoco"),
    ("pybullet", "PyBullet", "pybullet"),
    ("drake", "Drake", "drake"),
    ("siconos", "Siconos", "python3-siconos (Debian's python3)"),
    ("dart", "DART", "dart"),
)


def engine_adapters() -> list[tuple[str, object]]:
    """(family, adapter) for the references and each engine variant, or why an engine is missing.

    For an engine that is not installed the list holds (family, the reason as a string)
    once, in place of its variants.

    Returns
    -------
    list of (str, Adapter or str)
        The family (``"reference"`` or the engine's name, :data:`ENGINE_MODULES`) and an
        adapter, or the reason the engine cannot run.

    Examples
    --------
    The two references first, then every engine, installed or not:

    >>> adapters = engine_adapters()
    >>> [a.name for _, a in adapters[:2]]
    ['exact (closed forms)', 'bodycheck scene engine (integrate)']
    >>> {family for family, _ in adapters} == {"reference", *(e for _, e, _ in ENGINE_MODULES)}
    True
    """
    import importlib

    from .adapters import ExactAdapter, MissingExtraError, SceneEngineAdapter

    out: list[tuple[str, object]] = [
        ("reference", ExactAdapter()),
        ("reference", SceneEngineAdapter()),
    ]
    for module, engine, _extra in ENGINE_MODULES:
        mod = importlib.import_module(f"mechanics.conformance.adapters.{module}")
        try:
            out += [(engine, a) for a in mod.variants()]
        except MissingExtraError as exc:
            out.append((engine, str(exc)))
    return out


def _worst(r: ScenarioResult, kind: str) -> Figure | None:
    """The worst measured figure of ``kind`` (by value over threshold where checked):
    an unmeasured one (inf) is counted apart, never shown as the worst."""
    figs = [
        (f, f.value)
        for f in r.figures
        if f.kind == kind and f.value is not None and math.isfinite(f.value)
    ]
    if not figs:
        return None
    checked = [(f, value / f.threshold) for f, value in figs if f.threshold]
    if checked:
        return max(checked, key=lambda pair: pair[1])[0]
    return max(figs, key=lambda pair: pair[1])[0]


@dataclass
class Comparison:
    """Reports per adapter (in the order run) and the engines that could not run.

    Parameters
    ----------
    reports : list of (str, Report)
        (family, the battery's report) per adapter, each over the same scenarios in the
        same order.
    missing : list of (str, str), optional
        (family, reason) for each engine that could not run (default none).

    Examples
    --------
    One row per scenario and adapter:

    >>> from mechanics.conformance.adapters import ExactAdapter
    >>> report = run_battery(ExactAdapter(), scenarios=["parabola", "rocket"])
    >>> c = Comparison([("reference", report)])
    >>> [(row["scenario"], row["status"]) for row in c.rows()]
    [('parabola', 'pass'), ('rocket', 'pass')]
    """

    reports: list[tuple[str, Report]]
    missing: list[tuple[str, str]] = field(default_factory=list)

    def rows(self) -> list[dict]:
        """One dict per (scenario, adapter): the table's cells as values."""
        out: list[dict] = []
        if not self.reports:
            return out
        for k, scenario in enumerate(r.scenario for r in self.reports[0][1].results):
            for family, rep in self.reports:
                r = rep.results[k]
                assert r.scenario == scenario, "every report runs the scenarios in one order"
                err, drift = _worst(r, "error"), _worst(r, "drift")
                out.append(
                    {
                        "scenario": scenario,
                        "family": family,
                        "adapter": rep.adapter,
                        "status": r.status,
                        "error": None if err is None else [err.name, err.value],
                        "drift": None if drift is None else [drift.name, drift.value],
                        "unmeasured": len(r.unmeasured),
                        "order": r.order,
                        "wall_time": r.wall_time if r.runs else None,
                        "message": r.message if r.status in ("unsupported", "error") else "",
                    }
                )
        return out

    def to_markdown(self) -> str:
        """The table, then the engines that are not installed and the reasons given."""
        lines = [
            "| scenario | adapter | status | worst error | worst drift | order | wall time (s) |",
            "|---|---|---|---|---|---|---|",
        ]
        rows = self.rows()
        last = None
        for row in rows:
            scenario = row["scenario"] if row["scenario"] != last else ""
            last = row["scenario"]
            err = "" if row["error"] is None else f"{row['error'][1]:.2g} ({row['error'][0]})"
            if row["unmeasured"]:
                err += f" +{row['unmeasured']} not measured"
            drift = "" if row["drift"] is None else f"{row['drift'][1]:.2g} ({row['drift'][0]})"
            order = "" if row["order"] is None else f"{row['order']:.2f}"
            wall = "" if row["wall_time"] is None else f"{row['wall_time']:.2g}"
            status = row["status"]
            if status == "unsupported":
                status = "cannot express"
            lines.append(
                f"| {scenario} | {row['adapter']} | {status} | {err} | {drift} | {order} | {wall} |"
            )
        why: dict[tuple[str, str, str], list[str]] = {}
        for r in rows:
            if r["status"] in ("unsupported", "error") and r["message"]:
                key = (r["scenario"], r["status"], r["message"])
                why.setdefault(key, []).append(r["adapter"])
        if why or self.missing:
            lines += ["", "Not run:", ""]
            lines += [f"- {family}: {reason}" for family, reason in self.missing]
            for (scenario, status, message), names in why.items():
                verb = "cannot express" if status == "unsupported" else "raised an error in"
                lines.append(f"- {', '.join(names)} {verb} {scenario}: {message}")
        return "\n".join(lines) + "\n"

    def to_json(self) -> str:
        return json.dumps(
            {"rows": self.rows(), "missing": [list(m) for m in self.missing]}, indent=1
        )


def compare(
    adapters=None, *, scenarios=None, thresholds=None, profile=None, config=None, repeats=1
) -> Comparison:
    """Run the battery on each of ``adapters``, each with the same settings.

    Parameters
    ----------
    adapters : iterable of (str, Adapter or str), optional
        (family, adapter) pairs, or (family, reason) for an engine that cannot run
        (listed in ``Comparison.missing``); default :func:`engine_adapters`.
    scenarios : iterable of str or Scenario, optional
        As for :func:`~.battery.run_battery` (default all).
    thresholds : dict, optional
        As for :func:`~.battery.run_battery`.
    profile : str, optional
        As for :func:`~.battery.run_battery`.
    config : Config, optional
        As for :func:`~.battery.run_battery`.
    repeats : int, optional
        How many times each finest run is timed (default 1).

    Returns
    -------
    Comparison
        The reports in the order given and the engines that could not run.

    Raises
    ------
    ConformanceError
        Where an adapter lacks a member of the protocol, or ``repeats`` is not an int ≥ 1.
    UnknownScenarioError
        Where a scenario is unknown (by name or kind) or neither a name nor a scenario.
    ScenarioRangeError
        Where a user's scenario is outside its valid range.
    ThresholdError
        Where a threshold or the profile is refused.

    Examples
    --------
    >>> from mechanics.conformance.adapters import ExactAdapter
    >>> pairs = [("reference", ExactAdapter()), ("Nope", "not installed")]
    >>> c = compare(pairs, scenarios=["parabola"])
    >>> [row["status"] for row in c.rows()], c.missing
    (['pass'], [('Nope', 'not installed')])
    """
    adapters = engine_adapters() if adapters is None else adapters
    reports, missing = [], []
    for family, adapter in adapters:
        if isinstance(adapter, str):
            missing.append((family, adapter))
            continue
        report = run_battery(
            adapter,
            scenarios=scenarios,
            thresholds=thresholds,
            profile=profile,
            config=config,
            repeats=repeats,
        )
        reports.append((family, report))
    return Comparison(reports, missing)
