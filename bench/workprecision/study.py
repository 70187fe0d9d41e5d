"""The driver: run the whole study, write its JSON, tables and plots, and summarise it
(``bodycheck bench``).

Part of :mod:`bench.workprecision` (its docstring states the conventions).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import time
from pathlib import Path

import numpy as np

from .problems import Problem, reference_problems
from .report import format_value, headline, write_markdown, write_plots
from .settings import BUDGET_S, SCHEMA
from .sweeps import (
    _finite_or_none,
    _Progress,
    batched,
    batched_vs_scipy,
    energy_drift,
    exact_evaluation,
    mujoco_peer,
    sweep,
    warm_compiled,
)


def run_study(
    *,
    quick: bool,
    out_dir: Path,
    repeats: int,
    progress: bool = True,
    problems: list[Problem] | None = None,
) -> dict:
    """Run the whole study, write its four files into ``out_dir``, return the JSON dict.

    ``problems`` replaces the reference problems (tests inject a broken method this
    way); by default the four problems of the module docstring."""
    t_start = time.perf_counter()
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    if problems is None:
        problems = reference_problems(quick)
    total = (
        sum(len(ps) + (p.target is not None) for p in problems for _, ps, _ in p.methods.values())
        + 5  # energy drift
        + 2  # batched
        + 2  # batch against scipy
        + 3  # the MuJoCo peer
    )
    bar = _Progress(total, progress)
    budget = BUDGET_S[quick]
    study: dict = {
        "schema": SCHEMA,
        "quick": quick,
        "repeats": repeats,
        "command": "bodycheck bench" + (" --quick" if quick else "") + f" --repeats {repeats}",
        "machine": {
            "python": platform.python_version(),
            "platform": platform.platform(),
            "cpus": os.cpu_count(),
            "numpy": np.__version__,
        },
        "problems": {},
    }
    warm_compiled()
    try:
        for p in problems:
            study["problems"][p.name] = sweep(p, repeats=repeats, budget=budget, progress=bar)
        study["energy_drift"] = energy_drift(quick, bar)
        study["batched"] = batched(quick, repeats, bar)
        study["batched_vs_scipy"] = batched_vs_scipy(quick, repeats, bar)
        study["exact_evaluation"] = exact_evaluation(repeats)
        study["mujoco"] = mujoco_peer(quick, repeats, bar)
    finally:
        bar.close()
    study["total_time_s"] = time.perf_counter() - t_start
    if "free_top" in study["problems"]:
        study["headline"] = headline(study)
    (out_dir / "workprecision.json").write_text(
        json.dumps(_jsonable(study), indent=1, allow_nan=False), encoding="utf-8"
    )
    if "headline" in study:
        write_markdown(study, out_dir / "workprecision.md")
    write_plots(study, out_dir)
    return study


def _jsonable(x):
    if isinstance(x, dict):
        return {str(k): _jsonable(v) for k, v in x.items()}
    if isinstance(x, list | tuple):
        return [_jsonable(v) for v in x]
    if isinstance(x, float | np.floating):
        return _finite_or_none(x)
    if isinstance(x, np.integer):
        return int(x)
    return x


def main_bench(argv=None) -> int:
    """``bodycheck bench [--quick] [--out DIR] [--repeats N]``."""
    ap = argparse.ArgumentParser(prog="bodycheck bench", description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="short horizons, few points (<30 s)")
    ap.add_argument("--out", default="bench-results", help="output directory")
    ap.add_argument(
        "--repeats",
        type=int,
        default=None,
        help="timing repeats, median taken (default 3; 1 with --quick)",
    )
    args = ap.parse_args(argv)
    try:
        repeats = bench_repeats(args.quick, args.repeats)
    except ValueError as exc:
        ap.error(str(exc))
    return run_bench(quick=args.quick, out=args.out, repeats=repeats)


def bench_repeats(quick: bool, repeats: int | None) -> int:
    """The timing repeats of ``bodycheck bench``: ``--repeats`` as given, else 3 (1 with
    ``--quick``); fewer than 1 is a ValueError naming the value."""
    n = repeats if repeats is not None else (1 if quick else 3)
    if n < 1:
        raise ValueError(f"--repeats must be at least 1; got {n}")
    return n


def run_bench(*, quick: bool, out, repeats: int) -> int:
    """Run the study as ``bodycheck bench`` does (progress shown) and print its summary."""
    study = run_study(quick=quick, out_dir=Path(out), repeats=repeats, progress=True)
    print("\n".join(summary_lines(study, out)))
    return 0


def summary_lines(study: dict, out) -> list[str]:
    """What ``bodycheck bench`` prints when the study is done: where it wrote, and each
    target's status, measured value and goal."""
    lines = [
        f"wrote {out}/workprecision.{{json,md,png}} and energy_drift.png "
        f"in {study['total_time_s']:.1f} s"
    ]
    for r in study["headline"]["targets"]:
        m = r["measured"]
        m = format_value(m, ".3g") if not isinstance(m, str) else m
        lines.append(f"{r['status']:>20}: {r['name']}: {m} (goal {r['goal']})")
    return lines
