"""``bodycheck conform``: the conformance battery on an adapter, as a table and a plot.

    bodycheck conform MODULE:ADAPTER [--scenario NAME ...] [--json FILE] [--plot FILE]
                      [--threshold NAME=VALUE ...]
    bodycheck conform exact|engine ...
    bodycheck conform all [--markdown FILE] [--plot FILE] [--json FILE]

MODULE is a dotted module (importable from the current directory too) or a path to a
``.py`` file; ADAPTER an attribute of it (dots allowed): a class (instantiated without
arguments), a factory (called without arguments) or an adapter instance.  Resolved with
importlib and getattr, never eval.  ``exact`` and ``engine`` name the reference adapters
(the closed forms; the project's integrated scene engine).  ``all`` runs the references
and every variant of MuJoCo, PyBullet, Drake, Siconos and DART that is installed
(:mod:`mechanics.conformance.compare`) into one table, scenario by scenario; its exit
code is 1 only when a reference fails (an engine failing a scenario is what the table
reports).

Exit codes: 0 every scenario passed or is unsupported, 1 a scenario failed or errored,
2 bad usage (one line naming the value).
"""

from __future__ import annotations

import importlib
import importlib.util
import inspect
import math
import os
import sys
from pathlib import Path

from identities.cli.usage import UsageError

__all__ = ["PLOT_SUFFIXES", "add_parser", "cmd_conform", "load_adapter", "parse_thresholds"]

#: formats the plot is written in, by the file's suffix
PLOT_SUFFIXES = (".svg", ".png")
BUILTIN = {"exact": "ExactAdapter", "engine": "SceneEngineAdapter"}
#: the name that runs every adapter (references and engines) into one table
ALL = "all"
#: ``conform all`` times each engine's finest run of a scenario this many times and
#: reports the least (:func:`mechanics.conformance.run_battery`'s ``repeats``)
TIMING_REPEATS = 3


def add_parser(sub) -> None:
    """Add the ``conform`` subcommand to the ``bodycheck`` parser's subparsers."""
    c = sub.add_parser(
        "conform", help="run the engine-conformance battery on an adapter (docs/conformance.md)"
    )
    c.add_argument(
        "adapter",
        metavar="MODULE:ADAPTER",
        help="MODULE a dotted module or a .py path, ADAPTER a class, factory or instance in "
        "it; 'exact' / 'engine' for the reference adapters; 'all' for the references and "
        "every installed engine variant in one table",
    )
    c.add_argument(
        "--scenario",
        dest="scenarios",
        nargs="+",
        action="extend",
        metavar="NAME",
        help="only these scenarios (default: all)",
    )
    c.add_argument("--json", metavar="FILE", help="write the report as JSON ('-': stdout)")
    c.add_argument("--markdown", metavar="FILE", help="also write the printed table to FILE")
    c.add_argument(
        "--profile",
        metavar="NAME",
        help="what the engine claims, the base of every threshold: first-order, second-order, "
        "high-order, exact or default (docs/conformance.md, 'Profiles'); default: the "
        "thresholds file's, else the adapter's profile attribute, else default",
    )
    c.add_argument(
        "--config",
        metavar="FILE",
        help="a thresholds file (TOML: profile and a [thresholds] table); default: the "
        "[tool.bodycheck.conformance] table of the nearest pyproject.toml, if any",
    )
    c.add_argument(
        "--baseline",
        metavar="FILE",
        help="write a thresholds file pinning this run's accuracy (each figure at MARGIN x "
        "its value), to use with --config",
    )
    c.add_argument(
        "--margin",
        type=float,
        default=2.0,
        help="the baseline's margin over the measured figures (>= 1; default 2)",
    )
    c.add_argument("--plot", metavar="FILE", help="write a bar chart (.svg or .png)")
    c.add_argument(
        "--threshold",
        dest="thresholds",
        nargs="+",
        action="extend",
        default=[],
        metavar="NAME=VALUE",
        help="override a threshold: a figure (velocity, E_drift, order, ...) or "
        "scenario.figure; VALUE a number or 'none' (report, do not check)",
    )


def _usage(message: str) -> UsageError:
    return UsageError(message)


def _check_output(flag: str, value: str | None) -> None:
    """An output file's path must name a file in a folder that exists (the battery runs
    for seconds to minutes before the file is written, so a path that cannot be written
    is refused first, naming the flag and the path); ``-`` (stdout) passes."""
    if not value or value == "-":
        return
    path = Path(value)
    if path.is_dir():
        raise _usage(f"--{flag} {value!r}: is a folder; give a file's path")
    parent = path.parent
    if not parent.is_dir():
        what = "is not a folder" if parent.exists() else "does not exist"
        raise _usage(f"--{flag} {value!r}: its folder {str(parent)!r} {what}")


def parse_thresholds(items: list[str]) -> dict:
    """NAME=VALUE strings to a dict (VALUE a float or ``none``); UsageError otherwise."""
    out: dict = {}
    for item in items:
        name, sep, value = item.partition("=")
        if not sep or not name:
            raise _usage(f"--threshold {item!r}: expected NAME=VALUE, e.g. velocity=1e-4")
        if value.strip().lower() == "none":
            out[name] = None
            continue
        try:
            out[name] = float(value)
        except ValueError:
            raise _usage(
                f"--threshold {item!r}: VALUE must be a number or 'none'; got {value!r}"
            ) from None
    return out


def _import(module: str):
    from mechanics.conformance.adapters import MissingExtraError

    looks_like_path = module.endswith(".py") or "/" in module or "\\" in module
    try:
        if looks_like_path:
            path = Path(module)
            if not path.is_file():
                raise _usage(f"adapter module file {module!r} does not exist")
            dotted, root = _package_module(path)
            if dotted is not None:  # inside a package: imported as its module, so that
                sys.path.insert(0, str(root))  # its relative imports resolve
                try:
                    return importlib.import_module(dotted)
                finally:
                    sys.path.remove(str(root))
            name = f"_bodycheck_conform_{path.stem}"
            spec = importlib.util.spec_from_file_location(name, path)
            if spec is None or spec.loader is None:
                raise _usage(f"adapter module file {module!r} cannot be imported")
            mod = importlib.util.module_from_spec(spec)
            sys.modules[name] = mod
            spec.loader.exec_module(mod)
            return mod
        here = os.getcwd()  # searched first, as `python -m` does, for this import only
        sys.path.insert(0, here)
        try:
            return importlib.import_module(module)
        finally:
            sys.path.remove(here)
    except MissingExtraError as exc:
        raise _usage(str(exc)) from None
    except ModuleNotFoundError as exc:
        if exc.name and module.startswith(exc.name):
            raise _usage(
                f"unknown adapter module {module!r} (no module named {exc.name!r})"
            ) from None
        raise _usage(f"importing adapter module {module!r} failed: {exc}") from None
    except Exception as exc:
        if isinstance(exc, UsageError):
            raise
        raise _usage(
            f"importing adapter module {module!r} raised {type(exc).__name__}: {exc}"
        ) from None


def _package_module(path: Path) -> tuple[str | None, Path]:
    """For a file inside a package (its folder has an ``__init__.py``): its dotted name
    and the folder that holds the outermost package; else (None, its folder)."""
    path = path.resolve()
    parts = [path.stem] if path.name != "__init__.py" else []
    folder = path.parent
    while (folder / "__init__.py").is_file():
        parts.insert(0, folder.name)
        folder = folder.parent
    if not parts or folder == path.parent:
        return None, path.parent
    return ".".join(parts), folder


def load_adapter(spec: str):
    """The adapter named by ``MODULE:ADAPTER``, ``exact`` or ``engine``; UsageError
    naming the value for anything else."""
    from mechanics.conformance import adapters

    if spec in BUILTIN:
        return getattr(adapters, BUILTIN[spec])()
    module, sep, attr = spec.rpartition(":")
    if not sep or not module or not attr:
        raise _usage(
            f"adapter {spec!r}: expected MODULE:ADAPTER (e.g. my_engine.adapter:MyAdapter or "
            "path/to/adapter.py:MyAdapter), 'exact' or 'engine'"
        )
    obj = _import(module)
    for part in attr.split("."):
        if not part.isidentifier() or not hasattr(obj, part):
            raise _usage(f"adapter {spec!r}: module {module!r} has no attribute {attr!r}")
        obj = getattr(obj, part)
    if inspect.isclass(obj) or (callable(obj) and not hasattr(obj, "run")):
        what = "class" if inspect.isclass(obj) else "factory"
        try:
            obj = obj()
        except Exception as exc:
            raise _usage(
                f"adapter {spec!r}: the {what} could not be called without arguments: "
                f"{type(exc).__name__}: {exc}"
            ) from None
    missing = [a for a in ("name", "takes_step", "supports", "run") if not hasattr(obj, a)]
    if missing:
        raise _usage(
            f"adapter {spec!r} is not an adapter ({type(obj).__name__} lacks "
            f"{', '.join(missing)}): it needs name, takes_step, supports(scenario) and "
            "run(scenario, step)"
        )
    return obj


def _plot(report, path: Path) -> None:
    import matplotlib
    import matplotlib.ticker

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    res = report.results
    names = [r.scenario for r in res]
    y = range(len(res))
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 0.45 * len(res) + 1.8), sharey=True)
    colours = {"pass": "tab:green", "fail": "tab:red", "error": "black", "unsupported": "grey"}
    worst = [r.worst for r in res]
    err = [w.value if w is not None and w.value > 0 else float("nan") for w in worst]
    ax1.barh(y, err, color=[colours[r.status] for r in res])
    for k, w in enumerate(worst):
        if w is not None and w.threshold:
            ax1.plot([w.threshold] * 2, [k - 0.4, k + 0.4], color="black", lw=1)
        label = w.name if w is not None else res[k].status
        if res[k].unmeasured:  # an unmatched event has no bar of its own: say so
            label += f", +{len(res[k].unmeasured)} not measured"
        if res[k].status == "fail":
            label += " (fail)"
        ax1.annotate(
            label,
            (0, k),
            xycoords=("axes fraction", "data"),
            xytext=(3, 0),
            textcoords="offset points",
            va="center",
            fontsize=7,
        )
    ax1.set_xscale("log")
    ax1.set_xlabel("worst figure (relative error or drift); bar: threshold")
    ax1.set_yticks(list(y), names)
    # every row in view, the first on top (a row without a bar does not widen the axis)
    ax1.set_ylim(len(res) - 0.5, -0.5)
    wall = [r.wall_time for r in res]
    ax2.barh(y, wall, color="tab:blue")
    ax2.set_xscale("log")
    ax2.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())  # labels overlapped
    ax2.set_xlabel("wall time of the finest run (s)")
    fig.suptitle(f"Conformance: {report.adapter}")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def cmd_conform(args) -> int:
    """Run the battery; print the table; write JSON and the plot if asked."""
    from mechanics.conformance import SCENARIOS, run_battery
    from mechanics.conformance.thresholds import (
        Config,
        ThresholdError,
        baseline,
        find_config,
        get_profile,
        load_config,
        resolve_thresholds,
    )

    for flag in ("json", "markdown", "plot"):  # said before the battery runs, not after
        _check_output(flag, getattr(args, flag, None))
    if args.plot and Path(args.plot).suffix.lower() not in PLOT_SUFFIXES:
        raise _usage(f"--plot {args.plot!r}: the file must end in .svg or .png")
    if args.plot:  # said before the battery runs, not after
        from mechanics._extras import MissingExtraError, require_extra

        try:
            require_extra("matplotlib", "bodycheck conform --plot")
        except MissingExtraError as exc:
            raise _usage(str(exc)) from None
    for name in args.scenarios or ():
        if name not in SCENARIOS:
            raise _usage(f"unknown scenario {name!r} (known: {', '.join(SCENARIOS)})")
    if args.baseline is not None:
        if args.adapter == ALL:
            raise _usage("--baseline pins one adapter's accuracy; name the adapter, not 'all'")
        if Path(args.baseline).name == "pyproject.toml":
            raise _usage(
                f"--baseline {args.baseline!r}: the baseline is a thresholds file of its own "
                "(use it with --config, or copy its table under [tool.bodycheck.conformance])"
            )
        if not (args.margin >= 1 and math.isfinite(args.margin)):
            raise _usage(f"--margin {args.margin!r}: the margin must be a number >= 1")
    try:
        thresholds = resolve_thresholds(parse_thresholds(args.thresholds))
        if args.profile is not None:
            get_profile(args.profile)
        path = args.config if args.config is not None else find_config()
        config = Config() if path is None else load_config(path)
    except ThresholdError as exc:
        raise _usage(str(exc)) from None
    if args.adapter == ALL:
        return _conform_all(args, thresholds, config)
    adapter = load_adapter(args.adapter)
    try:
        report = run_battery(
            adapter,
            scenarios=args.scenarios,
            thresholds=thresholds,
            profile=args.profile,
            config=config,
        )
    except ThresholdError as exc:  # the adapter's own profile or thresholds
        raise _usage(f"adapter {args.adapter!r}: {exc}") from None
    table = report.to_markdown()
    if args.json == "-":
        print(report.to_json())
    else:
        print(table, end="")
        if args.json:
            Path(args.json).write_text(report.to_json() + "\n", encoding="utf-8")
    if args.markdown:
        Path(args.markdown).write_text(table, encoding="utf-8")
    if args.plot:
        _plot(report, Path(args.plot))
    if args.baseline is not None:
        Path(args.baseline).write_text(baseline(report, args.margin), encoding="utf-8")
        print(f"wrote the baseline {args.baseline} (use it with --config {args.baseline})")
        return 0
    return 0 if report.passed else 1


def _plot_all(comparison, path: Path) -> None:
    """A grid, scenario by adapter: colour = log10 of the worst checked figure over its
    threshold (green within, red beyond), the status written in each cell."""
    import math

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    reports = comparison.reports
    scenarios = [r.scenario for r in reports[0][1].results]
    grid = np.full((len(scenarios), len(reports)), np.nan)
    fig, ax = plt.subplots(figsize=(1.0 * len(reports) + 3, 0.5 * len(scenarios) + 2.5))
    for j, (_, rep) in enumerate(reports):
        for i, r in enumerate(rep.results):
            w = r.worst
            if r.status in ("pass", "fail") and w is not None and w.threshold:
                # 0 (an exact figure) at the colour scale's floor, inf at its top
                ratio = max(w.value, 1e-16) / w.threshold
                grid[i, j] = math.log10(ratio) if math.isfinite(ratio) else 8.0
            text = {"pass": "pass", "fail": "fail", "error": "error"}.get(r.status, "n/a")
            ax.text(j, i, text, ha="center", va="center", fontsize=7)
    im = ax.imshow(grid, cmap="RdYlGn_r", vmin=-8, vmax=8, aspect="auto")
    ax.set_xticks(range(len(reports)), [rep.adapter for _, rep in reports], rotation=60,
                  ha="right", fontsize=7)  # fmt: skip
    ax.set_yticks(range(len(scenarios)), scenarios, fontsize=8)
    fig.colorbar(im, ax=ax, label="log10(worst figure / threshold)")
    ax.set_title("Conformance battery: every adapter (n/a: cannot express the scenario)")
    fig.savefig(path, dpi=100, bbox_inches="tight")
    plt.close(fig)


def _conform_all(args, thresholds, config) -> int:
    from mechanics.conformance.compare import compare

    comparison = compare(
        scenarios=args.scenarios,
        thresholds=thresholds,
        profile=args.profile,
        config=config,
        repeats=TIMING_REPEATS,
    )
    table = comparison.to_markdown()
    if args.json == "-":
        print(comparison.to_json())
    else:
        print(table, end="")
        if args.json:
            Path(args.json).write_text(comparison.to_json() + "\n", encoding="utf-8")
    if args.markdown:
        parts = ["bodycheck conform all"]
        parts += [f"--scenario {n}" for n in args.scenarios or ()]
        parts += [f"--threshold {t}" for t in args.thresholds]
        parts += [f"--markdown {args.markdown}"] + ([f"--plot {args.plot}"] if args.plot else [])
        command = " ".join(parts)
        head = (
            "# The conformance battery on every engine\n\n"
            f"Written by `{command}` (docs/conformance.md: the scenarios, figures and "
            "thresholds; each engine's adapter module: how it maps the scenario).\n\n"
        )
        Path(args.markdown).write_text(head + table, encoding="utf-8")
    if args.plot:
        _plot_all(comparison, Path(args.plot))
    references = [rep for family, rep in comparison.reports if family == "reference"]
    return 0 if all(rep.passed for rep in references) else 1
