"""The ``bodycheck`` command.

    bodycheck check [--chapter N] [--id ID ...] [--kind KIND] [--json] [-j N] [--timings N]
    bodycheck explain ID|TOPIC [--json] [--latex]
    bodycheck search TOPIC [--json]
    bodycheck catalogue [--write PATH]
    bodycheck scene FILE.toml [--plot OUT.png] [--html OUT.html] [--json] [--method M]
    bodycheck scene --schema
    bodycheck demo NAME [--plot OUT.png] [--html OUT.html] [--json] [--method M]
    bodycheck demo --list
    bodycheck bench [--quick] [--out DIR] [--repeats N]
    bodycheck site OUT
    bodycheck notebooks --write DIR [--execute] | --check DIR
    bodycheck conform MODULE:ADAPTER|exact|engine [--scenario NAME ...] [--json FILE] [--plot FILE]

Exit codes: 0 success, 1 a check failed (or CHECKS.md is stale, or a scene missed the
book), 2 bad usage (including a bad scene file: one line naming file, field and reason).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from collections import defaultdict
from concurrent.futures import ProcessPoolExecutor, as_completed
from pathlib import Path

from identities.cli import conform
from identities.cli.usage import UsageError
from identities.verify import catalogue
from identities.verify.catalogue import KINDS, Outcome
from mechanics._extras import missing_extra

__all__ = ["main"]


def _at_least(least, kind):
    """An argparse type: a finite number of ``kind`` ≥ ``least`` (> 0 for a float)."""

    def parse(text: str):
        try:
            value = kind(text)
        except ValueError:
            value = None
        ok = value is not None and math.isfinite(value)
        ok = ok and (value > least if kind is float else value >= least)
        if not ok:
            want = f"a number > {least}" if kind is float else f"an integer ≥ {least}"
            raise argparse.ArgumentTypeError(f"must be {want}; got {text!r}")
        return value

    parse.__name__ = kind.__name__
    return parse


class _Parser(argparse.ArgumentParser):
    def error(self, message: str):  # one line, exit 2 (argparse prints usage too)
        raise UsageError(message)


def _parser() -> argparse.ArgumentParser:
    from mechanics.scenes.budget import DEFAULT_MAX_SECONDS, DEFAULT_MAX_STEPS
    from mechanics.scenes.spec import METHODS

    p = _Parser(prog="bodycheck", description="Essén, Dynamics of Bodies: executable and checked.")
    sub = p.add_subparsers(dest="command", required=True, parser_class=_Parser)
    c = sub.add_parser("check", help="run catalogue checks")
    c.add_argument(
        "--chapter", type=int, choices=range(1, 9), metavar="N", help="only chapter N (1-8)"
    )
    c.add_argument(
        "--id",
        dest="ids",
        nargs="+",
        metavar="ID",
        help="check ids or book items (eq2.36, E2.3, P2.4)",
    )
    c.add_argument("--kind", choices=KINDS, help="only checks of this kind")
    c.add_argument("--json", action="store_true", help="print the results as JSON")
    c.add_argument(
        "-j", "--jobs", type=int, default=1, metavar="N", help="run N checks in parallel"
    )
    c.add_argument(
        "--timings",
        type=int,
        nargs="?",
        const=15,
        default=0,
        metavar="N",
        help="after the table, list the N slowest checks (default 15) with their strategies",
    )
    e = sub.add_parser("explain", help="show a check's statement and its proof step by step")
    e.add_argument(
        "id",
        metavar="ID|TOPIC",
        help="a check id, a book item (eq4.38, E6.1, P2.6) or a topic (parallel-axis)",
    )
    e.add_argument("--json", action="store_true", help="print id, status and quantities (srepr)")
    e.add_argument(
        "--latex", action="store_true", help="print the algebra as LaTeX instead of pretty text"
    )
    e.add_argument(
        "--no-cache",
        action="store_true",
        help="run the check even if a cached run of the same sources exists (identities.cli.cache)",
    )
    f = sub.add_parser("search", help="find checks by topic words or a theorem's name")
    f.add_argument(
        "topic", nargs="+", metavar="TOPIC", help='e.g. restitution, "Euler\'s equations"'
    )
    f.add_argument("--json", action="store_true", help="print [{id, kind, title}, ...]")
    g = sub.add_parser("catalogue", help="render CHECKS.md from the registry")
    g.add_argument("--write", metavar="PATH", help="write to PATH instead of stdout")
    g.add_argument(
        "--derivations",
        action="store_true",
        help="run every check and store its steps, rendered as MathML, for the site "
        "(identities/data/derivations/; make checks does this)",
    )
    g.add_argument(
        "-j",
        "--jobs",
        type=int,
        default=0,
        metavar="N",
        help="with --derivations: run N checks in parallel (default: the cores)",
    )
    sc = sub.add_parser("scene", help="run a scene file (TOML) and compare it with the book")
    sc.add_argument("file", metavar="FILE.toml", nargs="?")
    sc.add_argument(
        "--schema",
        action="store_true",
        help="print the scene-file reference (every field, kind and unit), generated from the schema",
    )
    dm = sub.add_parser("demo", help="run a built-in scene (--list lists them)")
    dm.add_argument("name", metavar="NAME", nargs="?")
    dm.add_argument("--list", action="store_true", help="list the built-in scenes")
    for q in (sc, dm):
        q.add_argument("--plot", metavar="OUT.png", help="write a plot of the run")
        q.add_argument(
            "--html",
            metavar="OUT.html",
            help="write a page that plays the run (the bodies, play, pause, a time slider)",
        )
        q.add_argument(
            "--max-samples",
            type=_at_least(2, int),
            metavar="N",
            help="allow up to N samples (default: what the memory budget holds)",
        )
        q.add_argument(
            "--max-steps",
            type=_at_least(1, int),
            metavar="N",
            help=f"allow up to N integration steps (default {DEFAULT_MAX_STEPS})",
        )
        q.add_argument(
            "--max-seconds",
            type=_at_least(0, float),
            metavar="S",
            help=f"stop a run after S seconds of wall time (default {DEFAULT_MAX_SECONDS:g})",
        )
        q.add_argument("--json", action="store_true", help="print the result as JSON")
        q.add_argument(
            "--method",
            choices=METHODS,
            help="override the scene's method (auto: the exact flow where there is one; "
            "splitting: the symplectic splitting of a conservative scene, at the sample "
            "interval and order 4)",
        )
    b = sub.add_parser("bench", help="the work-precision study: what accuracy costs in time")
    b.add_argument("--quick", action="store_true", help="short horizons, few points (< 30 s)")
    b.add_argument("--out", default="bench-results", metavar="DIR", help="output directory")
    b.add_argument(
        "--repeats",
        type=int,
        default=None,
        metavar="N",
        help="timing repeats, the median is taken (default 3; 1 with --quick)",
    )
    b.add_argument(
        "--check",
        action="store_true",
        help="only the speed targets, as ratios against scipy measured now at quick sizes "
        "(best of --repeats); exit 1 naming each figure below its target",
    )
    si = sub.add_parser("site", help="write the book as a static site (pages, MathML, plots)")
    si.add_argument("out", metavar="OUT", help="output folder (new, empty or a previous site)")
    si.add_argument(
        "--api",
        action="store_true",
        help="also build the API reference (Sphinx, docs/) into OUT/api and link it (make docs)",
    )
    nb = sub.add_parser(
        "notebooks", help="write the lecture demos as Jupyter notebooks, executed (make checks)"
    )
    todo = nb.add_mutually_exclusive_group(required=True)
    todo.add_argument(
        "--write",
        metavar="DIR",
        help="write every demo's notebook into DIR, executing those whose cells changed",
    )
    todo.add_argument(
        "--check",
        metavar="DIR",
        help="exit 1 naming each notebook in DIR that --write would change",
    )
    nb.add_argument(
        "--execute", action="store_true", help="with --write: execute every notebook again"
    )
    conform.add_parser(sub)
    return p


def _resolve(ids: list[str]) -> list[str]:
    """Check ids for the given check ids or book items; UsageError for unknown ones."""
    reg = catalogue.load_all()
    inv = catalogue.inventory()
    out: list[str] = []
    for i in ids:
        if i in reg:
            found = [i]
        elif i in inv:
            found = [c.id for c in reg.values() if i in c.items]
            if not found:
                raise UsageError(f"{i} is a book item without a check yet (pending)")
        else:
            raise UsageError(
                f"unknown id {i!r}: expected a check id or a book item such as eq2.36, E2.3, P2.4"
            )
        out += [f for f in found if f not in out]
    return out


class _Progress:
    """A progress bar on stderr: redrawn in place on a terminal, every 10% otherwise."""

    def __init__(self, total: int, stream=None) -> None:
        self.total, self.done = total, 0
        self.stream = stream if stream is not None else sys.stderr
        self.tty = self.stream.isatty()
        self._last_decile = -1

    def step(self, label: str) -> None:
        self.done += 1
        width = 30
        filled = int(width * self.done / max(self.total, 1))
        line = f"[{'#' * filled}{'.' * (width - filled)}] {self.done}/{self.total} {label}"
        if self.tty:
            self.stream.write("\r\033[K" + line)
            if self.done == self.total:
                self.stream.write("\n")
        else:
            decile = 10 * self.done // max(self.total, 1)
            if decile != self._last_decile:
                self._last_decile = decile
                self.stream.write(line + "\n")
        self.stream.flush()


def _run(ids: list[str], jobs: int) -> list[Outcome]:
    progress = _Progress(len(ids))
    results: dict[str, Outcome] = {}
    if jobs <= 1:
        reg = catalogue.load_all()
        for i in ids:
            results[i] = catalogue.run_check(reg[i])[0]
            progress.step(i)
    else:
        with ProcessPoolExecutor(max_workers=jobs) as pool:
            futures = {pool.submit(catalogue.run_by_id, i): i for i in ids}
            for f in as_completed(futures):
                o = f.result()
                results[o.id] = o
                progress.step(o.id)
    return [results[i] for i in ids]


def _summary_table(outcomes: list[Outcome], wall: float) -> str:
    by_ch: dict[str, list[Outcome]] = defaultdict(list)
    for o in outcomes:
        by_ch[str(o.chapter) if o.chapter else "named"].append(o)
    lines = [
        f"{'chapter':>7}  {'checks':>6}  {'passed':>6}  {'failed':>6}  {'erratum':>7}  {'time':>8}",
        "-" * 50,
    ]
    for ch in sorted(by_ch):
        os_ = by_ch[ch]
        lines.append(
            f"{ch:>7}  {len(os_):>6}  {sum(o.passed for o in os_):>6}  {sum(not o.passed for o in os_):>6}  "
            f"{sum(o.status == 'erratum' for o in os_):>7}  {sum(o.seconds for o in os_):>7.2f}s"
        )
    lines.append("-" * 50)
    lines.append(
        f"{'all':>7}  {len(outcomes):>6}  {sum(o.passed for o in outcomes):>6}  "
        f"{sum(not o.passed for o in outcomes):>6}  {sum(o.status == 'erratum' for o in outcomes):>7}  "
        f"{wall:>7.2f}s wall"
    )
    return "\n".join(lines)


def _cmd_check(args) -> int:
    if args.jobs < 1:
        raise UsageError(f"-j must be at least 1; got {args.jobs}")
    ids = _resolve(args.ids) if args.ids else [c.id for c in catalogue.checks()]
    sel = {c.id for c in catalogue.checks(chapter=args.chapter, kind=args.kind)}
    ids = [i for i in ids if i in sel]
    if not ids:
        raise UsageError("no check matches the given --chapter/--id/--kind")
    t0 = time.perf_counter()
    outcomes = _run(ids, args.jobs)
    wall = time.perf_counter() - t0
    failed = [o for o in outcomes if not o.passed]
    if args.json:
        print(
            json.dumps(
                {
                    "passed": len(outcomes) - len(failed),
                    "failed": len(failed),
                    "wall_seconds": round(wall, 3),
                    "checks": [
                        {
                            "id": o.id,
                            "passed": o.passed,
                            "label": o.label,
                            "status": o.status,
                            "chapter": o.chapter,
                            "seconds": round(o.seconds, 4),
                            "message": o.message,
                            "strategies": list(o.strategies),
                        }
                        for o in outcomes
                    ],
                },
                indent=1,
            )
        )
    else:
        for o in outcomes:
            mark = "ok  " if o.passed else "FAIL"
            print(
                f"{mark} {o.id:<34} {o.label or '-':<14} {o.status:<9} {o.seconds:7.2f}s"
                + (f"  {o.message}" if o.message else "")
            )
        print()
        print(_summary_table(outcomes, wall))
        if args.timings:
            print()
            print(_timings_table(outcomes, args.timings))
    return 1 if failed else 0


def _timings_table(outcomes: list[Outcome], n: int) -> str:
    """The ``n`` slowest checks: time, the strategies used, the slowest proof step."""
    total = sum(o.seconds for o in outcomes)
    lines = [
        f"slowest {min(n, len(outcomes))} of {len(outcomes)} checks "
        f"(all checks: {total:.2f} s of proving time)",
        f"{'check':<26} {'time':>8} {'share':>6}  {'strategies':<28} slowest step",
    ]
    for o in sorted(outcomes, key=lambda o: -o.seconds)[:n]:
        text, sec = o.slowest_step
        step = f"{sec:.2f} s: {text[:70]}" if text else "-"
        lines.append(
            f"{o.id:<26} {o.seconds:>7.2f}s {o.seconds / max(total, 1e-12):>6.1%}  "
            f"{', '.join(o.strategies) or '-':<28} {step}"
        )
    return "\n".join(lines)


def _pretty(expr) -> str:
    import sympy as sp

    from identities.verify.record import too_large

    return too_large(expr) or sp.pretty(expr, use_unicode=True, wrap_line=False)


def _latex(expr) -> str:
    import sympy as sp

    from identities.verify.record import too_large

    return too_large(expr) or sp.latex(expr)


def _indent(text: str, n: int) -> str:
    return "\n".join(" " * n + line for line in text.splitlines())


def _topic_matches(query: str) -> list:
    """The checks a topic names; UsageError with the nearest names when there are none."""
    from identities.verify import topics

    found = topics.search(query)
    if not found:
        near = topics.nearest(query)
        hint = f"; nearest: {', '.join(near)}" if near else ""
        raise UsageError(f"unknown id or topic {query!r}{hint}")
    return found


def _cmd_search(args) -> int:
    found = _topic_matches(" ".join(args.topic))
    if args.json:
        print(json.dumps([{"id": c.id, "kind": c.kind, "title": c.title} for c in found], indent=1))
        return 0
    for c in found:
        print(f"{c.id:32s} {c.kind:10s} {c.title}")
    return 0


def _cmd_explain(args) -> int:
    """``explain``, through the cache of :mod:`identities.cli.cache`: a second call with the
    same sources, package versions and options prints the first call's output."""
    import contextlib
    import io

    from identities.cli import cache

    options = {"id": args.id, "json": bool(args.json), "latex": bool(args.latex)}
    if not args.no_cache and (hit := cache.load("explain", options)) is not None:
        out, code, created = hit
        sys.stdout.write(out)
        when = time.strftime("%Y-%m-%d %H:%M", time.localtime(created))
        print(
            f"bodycheck: the output of a run at {when} of the same sources and package "
            "versions (cached); --no-cache runs the check again",
            file=sys.stderr,
        )
        return code
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        code = _explain(args)
    out = buf.getvalue()
    sys.stdout.write(out)
    if not args.no_cache and (problem := cache.store("explain", options, out, code)):
        print(f"bodycheck: note: {problem}", file=sys.stderr)
    return code


def _explain(args) -> int:
    import sympy as sp

    reg = catalogue.load_all()
    inv = catalogue.inventory()
    if args.id not in reg and args.id not in inv:  # a topic: one match is explained
        found = _topic_matches(args.id)
        if len(found) > 1:
            print(f"{len(found)} checks match {args.id!r}; explain one by its id:")
            for c in found:
                print(f"  {c.id:32s} {c.title}")
            return 0
        args.id = found[0].id
    if args.id not in reg and args.id in inv and not _covering(args.id):
        item = inv[args.id]
        if args.json:
            print(json.dumps({"id": args.id, "status": "pending", "quantities": {}}))
        else:
            print(
                f"{args.id}: chapter {item.chapter}, section {item.section}, page {item.page}: pending (no check yet)"
            )
        return 0
    check_id = _resolve([args.id])[0]
    c = reg[check_id]
    outcome, d = catalogue.run_check(c)
    status = next((r.status for r in catalogue.item_rows() if r.item.id == args.id), c.status)
    if args.json:
        print(
            json.dumps(
                {
                    "id": args.id,
                    "check": c.id,
                    "status": status,
                    "label": outcome.label,
                    "passed": outcome.passed,
                    "quantities": {k: sp.srepr(v) for k, v in d.quantities.items()},
                },
                indent=1,
            )
        )
        return 0 if outcome.passed else 1
    item = inv.get(args.id) or c.item
    ref = (
        f"chapter {item.chapter}, section {item.section}, page {item.page}"
        if item
        else "named result"
    )
    print(f"{c.id}: {c.title}")
    if check_id != args.id:
        print(f"({args.id} is covered by check {c.id})")
    print(
        f"book: Essén (1996), {ref}; covers {', '.join(c.covers) or '-'}"
        + (f"; uses definitions {', '.join(c.defines)}" if c.defines else "")
    )
    print(f"kind: {c.kind}; status: {status}; label: {outcome.label or '-'}; where: {c.where}")
    if c.statement:
        print(f"statement: {c.statement}")
    if c.reading:
        print(f"reading of the text: {c.reading}")
    if c.errata:
        print(f"printed (false): {c.printed}\ncorrected: {c.corrected}")
    print()
    from identities.verify.record import is_zero_literal, simplified

    show = _latex if args.latex else _pretty
    for n, step in enumerate(d.steps, 1):
        print(f"{n:>2}. {step.text}")
        if step.sides is not None:  # the claim's algebra: both sides, and the rule
            lhs, rhs = step.sides
            print(_indent(show(lhs), 5))
            if is_zero_literal(rhs):  # prove_zero: one side
                verb = f"reduces to 0 by {step.rule}" if step.kind == "proved" else "is not 0"
                print(f"     {verb}")
            else:
                print(f"     equals, by {step.rule}:" if step.kind == "proved" else "     is not:")
                print(_indent(show(rhs), 5))
        elif step.expr is not None:
            expr = simplified(step.expr) if step.kind == "refuted" else step.expr
            print(_indent(show(expr), 5))
    print()
    print("PASSED" if outcome.passed else f"FAILED: {outcome.message}")
    return 0 if outcome.passed else 1


def _covering(item_id: str) -> list[str]:
    return [c.id for c in catalogue.load_all().values() if item_id in c.items]


def _cmd_catalogue(args) -> int:
    from identities.verify.render import render_checks_md

    if args.derivations:
        return _write_derivations(args.jobs or os.cpu_count() or 1)
    text = render_checks_md()
    if args.write:
        Path(args.write).write_text(text, encoding="utf-8")
        print(f"wrote {args.write} ({text.count(chr(10))} lines)", file=sys.stderr)
    else:
        sys.stdout.write(text)
    return 0


def _write_derivations(jobs: int) -> int:
    """``catalogue --derivations``: every check's record (identities.verify.record)."""
    from identities.verify import record

    if jobs < 1:
        raise UsageError(f"--jobs must be at least 1, got {jobs}")
    t0 = time.perf_counter()
    regs = catalogue.checks()
    records = record.record_all([c.id for c in regs], jobs)
    failed = [cid for cid, r in records.items() if not r["passed"]]
    if failed:
        print(
            f"bodycheck: error: checks failed, nothing written: {', '.join(failed)}",
            file=sys.stderr,
        )
        return 1
    files = record.write_records(records, {c.id: c.chapter for c in regs})
    shown = sum(record.mathml_count(r) for r in records.values())
    text = [f for r in records.values() for f in record.fallbacks(r)]
    print(
        f"wrote {len(records)} records to {len(files)} files in {record.DATA} in "
        f"{time.perf_counter() - t0:.0f} s: {shown} MathML pieces, {len(text)} shown as text",
        file=sys.stderr,
    )
    return 0


def _run_scene_file(path, args) -> int:
    import dataclasses

    from identities.book.scenes.compare import load_book_scene, run_book_scene
    from mechanics.scenes import SceneError

    try:
        scene = load_book_scene(path)
        if args.method:
            scene = dataclasses.replace(scene, method=args.method)
        limits = {
            "max_samples": args.max_samples,
            "max_steps": args.max_steps,
            "max_seconds": args.max_seconds,
        }
        scene = dataclasses.replace(scene, **{k: v for k, v in limits.items() if v is not None})
        result = run_book_scene(scene)
    except SceneError as exc:
        raise UsageError(str(exc)) from None
    if args.plot:
        from identities.cli.scene_plots import plot_result

        try:
            plot_result(result, args.plot)
        except (OSError, ValueError) as exc:  # a folder that is missing, a format unknown
            raise UsageError(f"--plot {args.plot}: cannot write the plot: {exc}") from None
    if args.html:
        from identities.cli.scene_player import player_page

        try:
            Path(args.html).write_text(player_page(result), encoding="utf-8")
        except OSError as exc:  # a folder that is missing, a file that cannot be written
            raise UsageError(f"--html {args.html}: cannot write the page: {exc}") from None
    if args.json:
        print(result.to_json())
    else:
        print(result.summary())
        if args.plot:
            print(f"plot: {args.plot}")
        if args.html:
            print(f"page: {args.html}")
    return 0 if result.passed else 1


def _cmd_scene(args) -> int:
    if args.schema:
        from mechanics.scenes.reference import scene_file_reference

        print(scene_file_reference(), end="")
        return 0
    if args.file is None:
        raise UsageError("give a scene file FILE.toml (or --schema for the reference)")
    return _run_scene_file(args.file, args)


def _cmd_demo(args) -> int:
    import textwrap

    from identities.book.scenes.demos import LECTURE_DEMOS
    from mechanics.scenes import builtin_scenes, load_scene

    scenes = builtin_scenes()
    lectures = {d.name: d for d in LECTURE_DEMOS}
    if args.list:
        if args.json:
            rows = {
                n: {"title": load_scene(p).title, "book": load_scene(p).book}
                | (
                    {"topic": lectures[n].topic, "about": lectures[n].paragraph}
                    | {"check": lectures[n].check}
                    if n in lectures
                    else {}
                )
                for n, p in scenes.items()
            }
            print(json.dumps(rows, indent=1, ensure_ascii=False))
            return 0
        print("Lecture demos (bodycheck demo NAME --plot NAME.png):\n")
        for d in LECTURE_DEMOS:
            sc = load_scene(scenes[d.name])
            print(f"{d.name}: {d.topic} ({sc.book}; backed by the check {d.check})")
            print(textwrap.indent(textwrap.fill(d.paragraph, 84), "    ") + "\n")
        print("All built-in scenes:\n")
        for n, p in scenes.items():
            sc = load_scene(p)
            print(f"{n:<26} {sc.book:<18} {sc.title}")
        return 0
    if not args.name:
        raise UsageError("demo needs a NAME or --list")
    if args.name not in scenes:
        raise UsageError(f"unknown demo {args.name!r} (known: {', '.join(scenes)})")
    if args.name in lectures and not args.json:
        d = lectures[args.name]
        print(f"{d.topic} ({d.check}):\n{textwrap.fill(d.paragraph, 88)}\n")
    return _run_scene_file(scenes[args.name], args)


def _cmd_bench(args) -> int:
    from bench.workprecision.study import bench_repeats, run_bench

    if args.check and args.quick:
        raise UsageError("--check always runs the quick sizes; leave out --quick")
    try:  # (--check's default is 3 repeats, as the full study's)
        repeats = bench_repeats(args.quick, args.repeats)
    except ValueError as exc:
        raise UsageError(str(exc)) from None
    if args.check:
        from bench.check import main as check_main

        return check_main(["--repeats", str(repeats)])
    return run_bench(quick=args.quick, out=args.out, repeats=repeats)


def _cmd_site(args) -> int:
    from identities.cli.site import SiteError, build_site

    t0 = time.perf_counter()
    listed: list[str] = []
    try:
        pages = build_site(args.out, listed=listed, jobs=min(2, os.cpu_count() or 1), api=args.api)
    except SiteError as exc:
        raise UsageError(str(exc)) from None
    print(
        f"wrote {len(pages)} pages to {args.out}"
        + (f" and the API reference to {Path(args.out) / 'api'}" if args.api else "")
        + f" in {time.perf_counter() - t0:.1f} s; open {Path(args.out) / 'index.html'}"
    )
    if listed:
        print(f"{len(listed)} pieces of algebra shown as text ({Path(args.out) / 'as-text.html'}):")
        for line in listed[:5]:
            print(f"  {line}")
        if len(listed) > 5:
            print(f"  ... and {len(listed) - 5} more")
    return 0


def _cmd_notebooks(args) -> int:
    from identities.cli.notebooks import NotebookError, stale_notebooks, write_notebooks

    if args.check:
        if args.execute:
            raise UsageError("--execute goes with --write, not --check")
        if not Path(args.check).is_dir():
            raise UsageError(f"--check {args.check}: not a folder")
        problems = stale_notebooks(args.check)
        for p in problems:
            print(p)
        if problems:
            print(f"run `bodycheck notebooks --write {args.check}` (make checks)", file=sys.stderr)
        return 1 if problems else 0
    try:
        written = write_notebooks(args.write, execute=args.execute)
    except NotebookError as exc:
        print(f"bodycheck: notebook failed: {exc}", file=sys.stderr)
        return 1
    except ModuleNotFoundError as exc:
        if exc.name in {"nbclient", "nbformat", "ipykernel"}:
            raise UsageError(str(exc)) from None
        raise
    print(
        f"wrote {len(written)} notebooks to {args.write}"
        + (f": {', '.join(p.name for p in written)}" if written else " (all current)")
    )
    return 0


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``bodycheck`` console script."""
    command = "?"
    try:
        args = _parser().parse_args(argv)
        command = args.command
        handler = {
            "check": _cmd_check,
            "explain": _cmd_explain,
            "search": _cmd_search,
            "catalogue": _cmd_catalogue,
            "scene": _cmd_scene,
            "demo": _cmd_demo,
            "bench": _cmd_bench,
            "site": _cmd_site,
            "notebooks": _cmd_notebooks,
            "conform": conform.cmd_conform,
        }[args.command]
        return handler(args)
    except UsageError as exc:
        print(f"bodycheck: error: {exc}", file=sys.stderr)
        return 2
    except ModuleNotFoundError as exc:  # an optional part (mechanics/_extras.py) not installed
        missing = missing_extra(exc, f"bodycheck {command}")
        if missing is None:
            raise
        print(f"bodycheck: error: {missing}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        return 130
    except BrokenPipeError:  # e.g. `bodycheck explain ID | head`: stop quietly
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 0
    except OSError as exc:  # a path from the command line: missing, a folder for a file, ...
        where = f"{exc.filename}: " if exc.filename else ""
        print(f"bodycheck: error: {where}{exc.strerror or exc}", file=sys.stderr)
        return 2
