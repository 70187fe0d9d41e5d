"""Mutation testing of one module of ``mechanics/``: ``make mutate MODULE=mechanics/rotation.py``.

The module's mutants (mutmut 3, configured in pyproject's ``[tool.mutmut]``) run against
the tests that cover it (``tools/mutation/modules.toml``) under ``CI=1``.  Each module gets
its own copy of the project, ``build/mutation/<module>/``, with ``only_mutate`` and the
test selection set for it, so that modules keep their results apart and a second run
only re-checks what changed.

The score counts a surviving mutant as equivalent only if it is in the reviewed list
``tools/mutation/equivalent.toml`` (mutant name → one-line reason)::

    score = killed / (mutants − equivalent)

where killed includes timeouts (the mutant made the tests hang) and every other survivor
(no test reaches it, or none fails) counts against the score.  The survivors not in the
list are printed, each with its diff (``--diff``), and so are listed names that no longer
survive (stale entries: remove them).

Usage (standard library only; mutmut must be on PATH or given with ``--mutmut``)::

    python tools/mutation/run.py mechanics/rotation.py [--max-children 1] [--diff]
    python tools/mutation/run.py mechanics/rotation.py --report   # score of the last run
    python tools/mutation/run.py mechanics/rotation.py --names NAME...  # re-run some
    python tools/mutation/run.py mechanics/impact.py --sample 300  # a random sample
    python tools/mutation/run.py mechanics/scenes --sample 40   # every module under a folder

A sample (``--sample N``, seeded) runs N mutants drawn at random from all of the
module's (those of them killed by an earlier run are not run again: tests are only ever
added; ``--recheck`` runs them too); the score then counts that sample's mutants only
(``--report --sample N --seed S`` reports it again) and says how many were not checked,
and gives the 95 % (Wilson) interval of the score that the sample's size allows.

Several modules (or a folder, meaning every module of ``modules.toml`` under it) run in one
copy of the project against the union of their tests: the tests are recorded once for all
of them, mutmut still runs each mutant against only the tests that call its function, and
a sample draws N mutants from each module.  The score is reported per module.
"""

from __future__ import annotations

import argparse
import filecmp
import json
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import time
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
MODULES = ROOT / "tools" / "mutation" / "modules.toml"
EQUIVALENT = ROOT / "tools" / "mutation" / "equivalent.toml"
WORK = ROOT / "build" / "mutation"

#: what the copy of the project holds (mutmut copies these into its mutants/ in turn)
COPIED = ("mechanics", "identities", "bench", "tests", "tools", "docs", "CHECKS.md", "README.md")
_IGNORED = shutil.ignore_patterns("__pycache__", "*.pyc", ".hypothesis", "mutants")

KILLED = frozenset({"killed", "timeout", "segfault", "caught by type check"})
_RESULT = re.compile(r"^\s+(?P<name>\S+): (?P<status>.+)$")


def load_modules(path: Path = MODULES) -> dict[str, list[str]]:
    """Module path → the test paths that cover it."""
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    return {m: list(row["tests"]) for m, row in data["modules"].items()}


def load_equivalent(path: Path = EQUIVALENT) -> dict[str, str]:
    """Mutant name → the reviewed one-line reason it is equivalent.

    Every reason must be a non-empty single line: a bare name is not a review."""
    if not path.exists():
        return {}
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    out: dict[str, str] = {}
    for module, table in data.items():
        for name, reason in table.items():
            if not isinstance(reason, str) or not reason.strip() or "\n" in reason:
                raise SystemExit(
                    f"{path.name}: [{module}] {name!r} needs a one-line reason, got {reason!r}"
                )
            out[name] = reason
    return out


def module_prefix(module: str) -> str:
    """``mechanics/rotation.py`` → ``mechanics.rotation.``, the prefix of its mutant names
    (a package's ``__init__.py``: the package's, ``mechanics.scenes.``)."""
    return module.removesuffix(".py").removesuffix("/__init__").replace("/", ".") + "."


def of_module(name: str, module: str) -> bool:
    """Is the mutant ``name`` one of ``module``'s?  mutmut names a package's own mutants
    without ``__init__`` (``mechanics.scenes.x_builtin_path__mutmut_3``): right after the
    package's prefix comes the function (``x_``) or method (``xǁ``), where a submodule's
    name would come (``mechanics.scenes.contacts.x_...``)."""
    prefix = module_prefix(module)
    if not name.startswith(prefix):
        return False
    return not module.endswith("/__init__.py") or name[len(prefix) :].startswith(("x_", "xǁ"))


def _sync(src: Path, dst: Path) -> None:
    """Copy src over dst, keeping a file's mtime where its content did not change (mutmut
    re-generates the mutants of a source whose mtime moved)."""
    if src.is_file():
        if not dst.exists() or not filecmp.cmp(src, dst, shallow=False):
            dst.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(src, dst)
        return
    for s in src.rglob("*"):
        rel = s.relative_to(src)
        if any(p in ("__pycache__", ".hypothesis", "mutants") for p in rel.parts):
            continue
        if s.is_file() and s.suffix != ".pyc":
            _sync(s, dst / rel)


def expand(names: list[str], modules: dict[str, list[str]]) -> list[str]:
    """The modules meant by the command line: a module path, or a folder meaning every
    module of ``modules.toml`` under it; an unknown name is refused with the known ones."""
    out: list[str] = []
    for raw in names:
        name = raw.removeprefix("./").rstrip("/")
        if name in modules:
            found = [name]
        else:
            found = sorted(m for m in modules if m.startswith(name + "/"))
        if not found:
            known = ", ".join(sorted(modules))
            raise SystemExit(f"{raw!r} has no row in {MODULES.name} (known: {known})")
        out += [m for m in found if m not in out]
    return out


def workdir(modules: list[str]) -> Path:
    """The copy of the project for one module or for a set of them."""
    if len(modules) == 1:
        return WORK / modules[0].removesuffix(".py").replace("/", "_")
    return WORK / ("group_" + "_".join(Path(m).stem.strip("_") for m in modules))[:120]


def prepare(modules: list[str], tests: list[str]) -> Path:
    """The copy of the project, its pyproject's mutmut table set for the modules."""
    work = workdir(modules)
    work.mkdir(parents=True, exist_ok=True)
    for name in COPIED:
        if (ROOT / name).exists():
            _sync(ROOT / name, work / name)
    text = (ROOT / "pyproject.toml").read_text(encoding="utf-8")
    selection = "pytest_add_cli_args_test_selection = " + _toml_list(tests)
    text, n = re.subn(r"(?m)^pytest_add_cli_args_test_selection = .*$", selection, text)
    if n != 1:
        raise SystemExit(
            "pyproject.toml: [tool.mutmut] needs one pytest_add_cli_args_test_selection line"
        )
    only = f"[tool.mutmut]\nonly_mutate = {_toml_list(modules)}\n"
    text = text.replace("[tool.mutmut]\n", only, 1)
    target = work / "pyproject.toml"
    if not target.exists() or target.read_text(encoding="utf-8") != text:
        target.write_text(text, encoding="utf-8")
        # a new test selection makes mutmut forget every verdict of this copy
        (work / "mutants" / "mutmut-stats.json").unlink(missing_ok=True)
        shutil.rmtree(work / "mutants", ignore_errors=True)
    return work


def _toml_list(items: list[str]) -> str:
    return "[" + ", ".join(f'"{i}"' for i in items) + "]"


def results(work: Path, mutmut: str) -> dict[str, str]:
    """Mutant name → status, as ``mutmut results --all true`` reports them."""
    out = subprocess.run(
        [mutmut, "results", "--all", "true"], cwd=work, capture_output=True, text=True, check=True
    ).stdout
    found = {}
    for line in out.splitlines():
        m = _RESULT.match(line)
        if m:
            found[m["name"]] = m["status"].strip()
    return found


def report(
    module: str, status: dict[str, str], equivalent: dict[str, str]
) -> tuple[str, list[str]]:
    """The score line and the survivors that are not in the reviewed list."""
    everything = {k: v for k, v in status.items() if of_module(k, module)}
    mine = {k: v for k, v in everything.items() if v != "not checked"}
    unchecked = len(everything) - len(mine)
    killed = sum(v in KILLED for v in mine.values())
    survivors = sorted(k for k, v in mine.items() if v not in KILLED)
    equiv = [k for k in survivors if k in equivalent]
    open_ = [k for k in survivors if k not in equivalent]
    total = len(mine)
    denom = total - len(equiv)
    score = 100.0 * killed / denom if denom else 100.0
    line = (
        f"{module}: {total} mutants, {killed} killed, {len(equiv)} equivalent (reviewed), "
        f"{len(open_)} survived: score {score:.1f} % = killed / (mutants - equivalent)"
    )
    if not everything:
        line = f"{module}: no mutants (nothing mutmut can change)"
    elif not mine:
        line = f"{module}: not measured (none of its {len(everything)} mutants checked)"
    elif unchecked:
        lo, hi = wilson(killed, denom)
        line += (
            f"  [{unchecked} of {len(everything)} mutants not checked: a sample;"
            f" 95 % interval {100 * lo:.0f}-{100 * hi:.0f} %]"
        )
    return line, open_


def wilson(k: int, n: int, z: float = 1.959963984540054) -> tuple[float, float]:
    """The 95 % Wilson score interval of a proportion k/n (0..1 when n is 0)."""
    if n == 0:
        return 0.0, 1.0
    p = k / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * ((p * (1 - p) / n + z * z / (4 * n * n)) ** 0.5) / (1 + z * z / n)
    return max(0.0, centre - half), min(1.0, centre + half)


def generate(work: Path, module: str, mutmut: str, env: dict, others: tuple = ()) -> list[str]:
    """Every mutant name of the module: let ``mutmut run`` write its mutants and their
    list (``mutants/<module>.meta``, and those of ``others`` run in the same copy), then
    stop it before it runs them."""
    meta = work / "mutants" / (module + ".meta")
    metas = [meta, *(work / "mutants" / (m + ".meta") for m in others)]
    if not all(m.exists() for m in metas):
        proc = subprocess.Popen(
            [mutmut, "run", "--max-children", "1"],
            cwd=work,
            env=env,
            start_new_session=True,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        try:
            while not all(m.exists() for m in metas) and proc.poll() is None:
                time.sleep(0.5)
        finally:
            if proc.poll() is None:
                os.killpg(proc.pid, signal.SIGTERM)
                proc.wait()
        time.sleep(0.5)
    if not meta.exists():
        return []
    data = json.loads(meta.read_text(encoding="utf-8"))
    return sorted(data["exit_code_by_key"])


def executable(path: str) -> str:
    """mutmut runs in the copy of the project: a path to it (``.venv/bin/mutmut``, as the
    Makefile gives it) is made absolute; a bare name is looked up on PATH as it is."""
    return str(Path(path).resolve()) if os.sep in path else path


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument(
        "modules", nargs="+", help="e.g. mechanics/rotation.py, or a folder: mechanics/scenes"
    )
    ap.add_argument("--max-children", type=int, default=1)
    beside = Path(sys.executable).parent / "mutmut"  # the venv's, when run by its python
    ap.add_argument(
        "--mutmut", default=shutil.which("mutmut") or (str(beside) if beside.exists() else "mutmut")
    )
    ap.add_argument("--report", action="store_true", help="only report the last run")
    ap.add_argument("--diff", action="store_true", help="show each open survivor's diff")
    ap.add_argument("--names", nargs="+", help="run only these mutants")
    ap.add_argument("--sample", type=int, help="run this many mutants drawn at random")
    ap.add_argument("--seed", type=int, default=16, help="seed of --sample")
    ap.add_argument(
        "--recheck",
        action="store_true",
        help="with --sample: run again the sampled mutants already killed",
    )
    ap.add_argument(
        "--restat",
        action="store_true",
        help="record again which tests call which function (after changing tests)",
    )
    args = ap.parse_args(argv)
    args.mutmut = executable(args.mutmut)

    rows = load_modules()
    chosen = expand(args.modules, rows)
    tests = sorted({t for m in chosen for t in rows[m]})
    equivalent = load_equivalent()
    work = prepare(chosen, tests)
    env = {**os.environ, "CI": "1"}
    env.pop("HYPOTHESIS_PROFILE", None)
    if args.restat:
        (work / "mutants" / "mutmut-stats.json").unlink(missing_ok=True)
    names = list(args.names or [])
    sample: set[str] | None = None
    if args.sample:
        drawn_all: list[str] = []
        for module in chosen:
            every = generate(work, module, args.mutmut, env, tuple(chosen))
            drawn = sorted(random.Random(args.seed).sample(every, min(args.sample, len(every))))
            print(f"{module}: a sample of {len(drawn)} of {len(every)} mutants (seed {args.seed})")
            drawn_all += drawn
        sample = set(drawn_all)
    if sample is not None and not args.report:
        names = sorted(sample)
        if not args.recheck:  # a killed mutant stays killed while its tests stay
            known = results(work, args.mutmut) if (work / "mutants").exists() else {}
            done = [n for n in names if known.get(n) in KILLED]
            names = [n for n in names if n not in done]
            if done:
                print(f"{len(done)} of the sample killed before: not run again (--recheck does)")
        if not names:
            print("no mutants to run")
    if not args.report and (names or not args.sample):
        cmd = [args.mutmut, "run", "--max-children", str(args.max_children), *names]
        shown = cmd if len(names) <= 5 else [*cmd[: len(cmd) - len(names)], f"<{len(names)} names>"]
        print("$ (cd", work.relative_to(ROOT), "&&", " ".join(shown) + ")", flush=True)
        rc = subprocess.run(cmd, cwd=work, env=env).returncode
        if rc:
            print(f"mutmut run exited with {rc}", file=sys.stderr)
            return rc
    status = results(work, args.mutmut)
    if sample is not None:  # the score of this sample only, not of earlier runs' mutants
        status = {k: (v if k in sample else "not checked") for k, v in status.items()}
    for module in chosen:
        report_module(module, status, equivalent, work, args)
    return 0


def report_module(
    module: str, status: dict[str, str], equivalent: dict[str, str], work: Path, args
) -> None:
    """Print the module's score line, its open survivors (with diffs on ``--diff``) and
    the stale entries of the reviewed list."""
    line, open_ = report(module, status, equivalent)
    stale = sorted(
        k for k in equivalent if of_module(k, module) and status.get(k, "gone") in KILLED | {"gone"}
    )
    print()
    print(line)
    if open_:
        print(f"survivors not in {EQUIVALENT.relative_to(ROOT)} ({len(open_)}):")
        for name in open_:
            print(f"  {name}: {status[name]}")
            if args.diff:
                diff = subprocess.run(
                    [args.mutmut, "show", name], cwd=work, capture_output=True, text=True
                ).stdout
                print("    " + "\n    ".join(diff.splitlines()[1:]))
    if stale:
        print(f"listed as equivalent but killed or gone (remove them): {', '.join(stale)}")


if __name__ == "__main__":
    sys.exit(main())
