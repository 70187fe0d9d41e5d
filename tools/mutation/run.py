"""Mutation testing of one module of ``mechanics/``: ``make mutate MODULE=mechanics/rotation.py``.

The module's mutants (mutmut 3, configured in pyproject's ``[tool.mutmut]``) run against
the tests that cover it (``tools/mutation/modules.toml``) under ``CI=1``.  Each module gets
its own copy of the project, ``build/mutation/<module>/`` (a sample's
``<module>_sample<seed>/``), with ``only_mutate`` and the test selection set for it, so
that modules keep their results apart, a full run after a sample leaves the sample's
verdicts alone, and a second run only re-checks what changed.

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
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
MODULES = ROOT / "tools" / "mutation" / "modules.toml"
EQUIVALENT = ROOT / "tools" / "mutation" / "equivalent.toml"
ACCEPTED = ROOT / "tools" / "mutation" / "accepted.toml"
PLAN = ROOT / "tools" / "mutation" / "plan.toml"
TABLES = (ROOT / "docs" / "mutation.md",)
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


def load_envs(path: Path = MODULES) -> dict[str, dict[str, str]]:
    """Module path → the environment its tests run in under mutation (a row's ``env``;
    ``mechanics/_kernels.py`` runs with numba's JIT off, so that its mutants run)."""
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    return {m: dict(row.get("env", {})) for m, row in data["modules"].items()}


def load_equivalent(path: Path = EQUIVALENT, text: str | None = None) -> dict[str, str]:
    """Mutant name → the reviewed one-line reason it is equivalent (or, read from
    ``accepted.toml``, the reason a survivor is accepted in writing).

    Every reason must be a non-empty single line: a bare name is not a review."""
    if text is None:
        if not path.exists():
            return {}
        text = path.read_text(encoding="utf-8")
    data = tomllib.loads(text)
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


def _sync(src: Path, dst: Path) -> list[Path]:
    """Copy src over dst, keeping a file's mtime where its content did not change (mutmut
    re-generates the mutants of a source whose mtime moved); the files copied."""
    if src.is_file():
        if not dst.exists() or not filecmp.cmp(src, dst, shallow=False):
            dst.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(src, dst)
            return [dst]
        return []
    changed: list[Path] = []
    for s in src.rglob("*"):
        rel = s.relative_to(src)
        if any(p in ("__pycache__", ".hypothesis", "mutants") for p in rel.parts):
            continue
        if s.is_file() and s.suffix != ".pyc":
            changed += _sync(s, dst / rel)
    return changed


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


def workdir(modules: list[str], seed: int | None = None) -> Path:
    """The copy of the project for one module or for a set of them; a sample's (drawn by
    ``seed``) apart from a full run's, so that a full run after a short sample (plan.toml)
    leaves the sample's verdicts, and its row of the table, as they were."""
    if len(modules) == 1:
        name = modules[0].removesuffix(".py").replace("/", "_")
    else:
        name = ("group_" + "_".join(Path(m).stem.strip("_") for m in modules))[:120]
    return WORK / (name if seed is None else f"{name}_sample{seed}")


def _verdict_key(pyproject: str) -> tuple:
    """What mutmut's verdicts in a copy depend on besides the code and the tests: the
    mutated modules, the test selection and arguments, pytest's own configuration.  (Not
    the rest of pyproject: a new dependency pin or a linter's setting changes no verdict.)"""
    cfg = tomllib.loads(pyproject).get("tool", {})
    mm = cfg.get("mutmut", {})
    keys = ("only_mutate", "pytest_add_cli_args", "pytest_add_cli_args_test_selection")
    return (*(repr(mm.get(k)) for k in keys), repr(cfg.get("pytest", {})))


def prepare(
    modules: list[str], tests: list[str], *, sync: bool = True, seed: int | None = None
) -> tuple[Path, bool]:
    """The copy of the project, its pyproject's mutmut table set for the modules; and
    whether a test file changed since the copy was last made (then mutmut's record of
    which tests call which function is deleted: it is recorded again).  ``sync=False``
    (a report) leaves an existing copy as it is: a run may be going on in it.  ``seed``:
    a sample's copy (:func:`workdir`)."""
    work = workdir(modules, seed)
    if not sync and (work / "mutants").exists():
        return work, False
    work.mkdir(parents=True, exist_ok=True)
    changed: list[Path] = []
    for name in COPIED:
        if (ROOT / name).exists():
            changed += _sync(ROOT / name, work / name)
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
    old = target.read_text(encoding="utf-8") if target.exists() else None
    if old != text:
        target.write_text(text, encoding="utf-8")
        if old is None or _verdict_key(old) != _verdict_key(text):
            # a new test selection makes mutmut forget every verdict of this copy
            shutil.rmtree(work / "mutants", ignore_errors=True)
    tests_changed = any((work / "tests") in p.parents for p in changed)
    if tests_changed:
        (work / "mutants" / "mutmut-stats.json").unlink(missing_ok=True)
    return work, tests_changed


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


@dataclass
class Tally:
    """One module's verdicts: its mutants (checked ones; ``unchecked`` more in the module
    when a sample ran), how many were killed, the survivors counted out as reviewed
    equivalents, those accepted in writing (still survivors) and the open ones."""

    module: str
    mutants: int
    unchecked: int
    killed: int
    equivalent: list[str]
    accepted: list[str]
    open: list[str]

    @property
    def denominator(self) -> int:
        return self.mutants - len(self.equivalent)

    @property
    def score(self) -> float:
        return 100.0 * self.killed / self.denominator if self.denominator else 100.0


def tally(
    module: str,
    status: dict[str, str],
    equivalent: dict[str, str],
    accepted: dict[str, str] | None = None,
) -> Tally:
    """Count the module's verdicts (see :class:`Tally`)."""
    accepted = accepted or {}
    everything = {k: v for k, v in status.items() if of_module(k, module)}
    mine = {k: v for k, v in everything.items() if v != "not checked"}
    survivors = sorted(k for k, v in mine.items() if v not in KILLED)
    equiv = [k for k in survivors if k in equivalent]
    taken = [k for k in survivors if k not in equivalent and k in accepted]
    open_ = [k for k in survivors if k not in equivalent and k not in accepted]
    killed = sum(v in KILLED for v in mine.values())
    return Tally(module, len(mine), len(everything) - len(mine), killed, equiv, taken, open_)


def report(
    module: str,
    status: dict[str, str],
    equivalent: dict[str, str],
    accepted: dict[str, str] | None = None,
) -> tuple[str, list[str]]:
    """The score line and the survivors neither reviewed as equivalent nor accepted in
    writing.  Accepted survivors count against the score like any survivor."""
    t = tally(module, status, equivalent, accepted)
    line = (
        f"{module}: {t.mutants} mutants, {t.killed} killed, {len(t.equivalent)} equivalent "
        f"(reviewed), {len(t.open) + len(t.accepted)} survived: score {t.score:.1f} % = "
        "killed / (mutants - equivalent)"
    )
    if t.accepted:
        line += f"  [{len(t.accepted)} of the survivors accepted in writing]"
    if not t.mutants and not t.unchecked:
        line = f"{module}: no mutants (nothing mutmut can change)"
    elif not t.mutants:
        line = f"{module}: not measured (none of its {t.unchecked} mutants checked)"
    elif t.unchecked:
        lo, hi = wilson(t.killed, t.denominator)
        line += (
            f"  [{t.unchecked} of {t.mutants + t.unchecked} mutants not checked: a sample;"
            f" 95 % interval {100 * lo:.0f}-{100 * hi:.0f} %]"
        )
    return line, t.open


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
        "modules",
        nargs="*",
        help="e.g. mechanics/rotation.py, or a folder: mechanics/scenes (none with --plan)",
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
    ap.add_argument(
        "--plan",
        action="store_true",
        help="run every run of tools/mutation/plan.toml (committed first) and write the "
        "table of docs/mutation.md",
    )
    args = ap.parse_args(argv)
    args.mutmut = executable(args.mutmut)
    if args.plan:
        if args.modules or args.names or args.sample:
            ap.error("--plan runs the plan's modules: give no modules, --names or --sample")
        return run_plan(args)
    if not args.modules:
        ap.error("name a module (or a folder), or give --plan")
    rows = load_modules()
    chosen = expand(args.modules, rows)
    status, work, rc = run_modules(chosen, args)
    if rc:
        return rc
    equivalent = load_equivalent()
    accepted = load_equivalent(ACCEPTED)
    for module in chosen:
        report_module(module, status, equivalent, accepted, work, args)
    return 0


def environment(chosen: list[str]) -> dict[str, str]:
    """The mutants' environment: CI=1 (derandomised hypothesis) and the rows' ``env``;
    modules whose rows ask for different environments cannot share a copy."""
    envs = load_envs()
    wanted = {tuple(sorted(envs[m].items())) for m in chosen}
    if len(wanted) > 1:
        raise SystemExit(f"{chosen} need different environments ({sorted(wanted)}): run apart")
    env = {**os.environ, "CI": "1", **dict(wanted.pop() if wanted else ())}
    env.pop("HYPOTHESIS_PROFILE", None)
    return env


def run_modules(
    chosen: list[str], args, *, rerun_survivors: bool = False, registered: bool = False
) -> tuple[dict[str, str], Path, int]:
    """Run the chosen modules' mutants (all, ``args.names`` or a sample of
    ``args.sample`` per module at ``args.seed``) in their copy of the project: (mutant →
    status, with the mutants outside a sample "not checked"; the copy; mutmut's exit
    code).  ``rerun_survivors``: after a full run, run the survivors again when a test
    changed since their verdict (mutmut keeps a verdict until told to re-run it).
    ``registered``: the sample is the plan's, whose figure is that of its first run (a
    test written after seeing its survivors must not raise it): only sampled mutants
    without a verdict run."""
    rows = load_modules()
    tests = sorted({t for m in chosen for t in rows[m]})
    seed = args.seed if args.sample else None
    work, tests_changed = prepare(chosen, tests, sync=not args.report, seed=seed)
    env = environment(chosen)
    if args.restat:
        (work / "mutants" / "mutmut-stats.json").unlink(missing_ok=True)
    names = list(args.names or [])
    sample: set[str] | None = None
    if args.sample:
        drawn_all: list[str] = []
        for module in chosen:
            every = generate(work, module, args.mutmut, env, tuple(chosen))
            drawn = draw(every, args.sample, args.seed)
            print(f"{module}: a sample of {len(drawn)} of {len(every)} mutants (seed {args.seed})")
            drawn_all += drawn
        sample = set(drawn_all)
    if sample is not None and not args.report:
        known = results(work, args.mutmut) if (work / "mutants").exists() else {}
        names, why = sample_to_run(sorted(sample), known, registered, args.recheck)
        if why:
            print(why)
        if not names:
            print("no mutants to run")
    if not args.report and (names or not args.sample):
        rc = _mutmut_run(work, args, env, names)
        if rc:
            return {}, work, rc
        if rerun_survivors and tests_changed and not names:
            known = results(work, args.mutmut)
            again = sorted(k for k, v in known.items() if v not in KILLED)
            if again:
                print(f"tests changed since the last run: {len(again)} survivors run again")
                rc = _mutmut_run(work, args, env, again)
                if rc:
                    return {}, work, rc
    status = results(work, args.mutmut)
    if sample is not None:  # the score of this sample only, not of earlier runs' mutants
        status = {k: (v if k in sample else "not checked") for k, v in status.items()}
    return status, work, 0


def sample_to_run(
    names: list[str], known: dict[str, str], registered: bool, recheck: bool
) -> tuple[list[str], str]:
    """Which of a sample's mutants run, and what is said of the others.  A registered
    sample's figure is that of its first run: a mutant with a verdict keeps it, a
    survivor too (a test written after seeing it must not raise the figure).  Otherwise
    a killed mutant stays killed while its tests stay (``recheck`` runs it again) and
    survivors run again."""
    if registered:
        done = [n for n in names if known.get(n, "not checked") != "not checked"]
        said = f"{len(done)} of the registered sample run before: their verdicts stand"
    elif not recheck:
        done = [n for n in names if known.get(n) in KILLED]
        said = f"{len(done)} of the sample killed before: not run again (--recheck does)"
    else:
        done = []
    return [n for n in names if n not in done], (said if done else "")


def draw(every: list[str], size: int, seed: int) -> list[str]:
    """The sample: ``size`` of a module's mutant names (all if it has fewer), drawn by
    ``seed`` from the sorted list."""
    return sorted(random.Random(seed).sample(sorted(every), min(size, len(every))))


def _mutmut_run(work: Path, args, env: dict[str, str], names: list[str]) -> int:
    cmd = [args.mutmut, "run", "--max-children", str(args.max_children), *names]
    shown = cmd if len(names) <= 5 else [*cmd[: len(cmd) - len(names)], f"<{len(names)} names>"]
    print("$ (cd", work.relative_to(ROOT), "&&", " ".join(shown) + ")", flush=True)
    rc = subprocess.run(cmd, cwd=work, env=env).returncode
    if rc:
        print(f"mutmut run exited with {rc}", file=sys.stderr)
    return rc


# ------------------------------------------------------------------ the plan


@dataclass
class PlanRun:
    """One ``[[run]]`` of ``plan.toml``: modules (or folders) run in one copy, in full
    (``sample`` None) or a sample of ``sample`` mutants per module drawn by ``seed``;
    ``lines`` are its lines in the file (1-based, inclusive), which date its
    registration."""

    modules: list[str]
    sample: int | None
    seed: int | None
    lines: tuple[int, int]


def load_plan(text: str) -> list[PlanRun]:
    """The runs of ``plan.toml``; a sample needs its size (at least 100, or every mutant
    of a smaller module) and its seed, a full run neither."""
    data = tomllib.loads(text)
    starts = [i + 1 for i, line in enumerate(text.splitlines()) if line.strip() == "[[run]]"]
    runs = data.get("run", [])
    if len(starts) != len(runs):
        raise SystemExit(f"{PLAN.name}: write each run as its own [[run]] line")
    lines = text.splitlines()
    ends = []
    for nxt in [*starts[1:], len(lines) + 1]:
        end = nxt - 1  # a run's lines end at its last setting: the comments and blank
        while lines[end - 1].strip() == "" or lines[end - 1].lstrip().startswith("#"):
            end -= 1  # lines before the next run are that run's (they date it, not this)
        ends.append(end)
    out = []
    for run, start, end in zip(runs, starts, ends, strict=True):
        unknown = set(run) - {"modules", "sample", "seed"}
        if unknown or not run.get("modules"):
            raise SystemExit(f"{PLAN.name}:{start}: a run has modules, and sample and seed")
        sample, seed = run.get("sample"), run.get("seed")
        if (sample is None) != (seed is None):
            raise SystemExit(f"{PLAN.name}:{start}: a sample needs both its size and its seed")
        if sample is not None and sample < MIN_SAMPLE:
            raise SystemExit(
                f"{PLAN.name}:{start}: a sample of {sample} mutants; at least {MIN_SAMPLE}"
            )
        out.append(PlanRun(list(run["modules"]), sample, seed, (start, end)))
    return out


#: the smallest sample the plan accepts (issue 35): its 95 % interval is ±4–6 points
MIN_SAMPLE = 100


def registration(lines: tuple[int, int], root: Path = ROOT) -> str | None:
    """The commit that registered a run: the newest commit among its lines of the plan
    (``git blame``); None while any of them is not committed."""
    plan = PLAN.relative_to(ROOT).as_posix()
    out = _git(root, "blame", "--porcelain", "-L", f"{lines[0]},{lines[1]}", "--", plan)
    if out is None:
        return None
    shas = {ln.split()[0] for ln in out.splitlines() if re.match(r"^[0-9a-f]{40} ", ln)}
    if not shas or any(set(sha) == {"0"} for sha in shas):
        return None
    # the newest: the one every other is an ancestor of
    for sha in shas:
        if all(_git(root, "merge-base", "--is-ancestor", o, sha) is not None for o in shas):
            return sha
    return None


def equivalent_at(commit: str, root: Path = ROOT) -> dict[str, str]:
    """The reviewed equivalents as they stood at ``commit`` (none if the list did not
    exist then)."""
    text = _git(root, "show", f"{commit}:{EQUIVALENT.relative_to(ROOT).as_posix()}")
    return load_equivalent(text=text) if text is not None else {}


def sample_equivalents(
    current: dict[str, str], commit: str | None, root: Path = ROOT
) -> dict[str, str]:
    """The equivalents a sample registered at ``commit`` counts out: those listed then and
    still listed now (an entry retracted since, moved to ``accepted.toml`` say, no
    longer counts; one added since counts for the next sample only)."""
    before = equivalent_at(commit, root) if commit else {}
    return {k: v for k, v in current.items() if k in before}


def _git(root: Path, *args: str) -> str | None:
    """git's output in ``root``, or None if git fails."""
    out = subprocess.run(["git", *args], cwd=root, capture_output=True, text=True)
    return out.stdout if out.returncode == 0 else None


def run_plan(args) -> int:
    """Run the plan, print each module's line, and write the table into
    ``docs/mutation.md``.  A full run counts out every reviewed equivalent; a sample only
    those reviewed before it was registered (equivalents found in a sample count for
    the next one; an entry since retracted, moved to ``accepted.toml`` say, does not
    count), and it must be registered (committed) before it runs."""
    text = PLAN.read_text(encoding="utf-8")
    plan = load_plan(text)
    rows = load_modules()
    equivalent = load_equivalent()
    accepted = load_equivalent(ACCEPTED)
    table: list[str] = []
    previous = previous_rows()
    for run in plan:
        chosen = expand(run.modules, rows)
        commit = registration(run.lines)
        if run.sample is not None and commit is None:
            raise SystemExit(
                f"{PLAN.name}:{run.lines[0]}: the sample of {run.modules} is not registered: "
                "commit the plan before running it"
            )
        if args.report and not (workdir(chosen, run.seed) / "mutants").exists():
            # no copy of this run here (a fresh checkout): the row the table had stays
            reg = f"`{commit[:9]}`" if commit else "uncommitted"
            for m in chosen:
                row = kept_row(previous, m, run.seed, reg)
                table.append(row)
                print(f"{m}: {'not run yet' if NOT_RUN in row else 'no copy here, its row kept'}")
            continue
        args.sample, args.seed, args.names = run.sample, run.seed, None
        status, work, rc = run_modules(
            chosen, args, rerun_survivors=run.sample is None, registered=run.sample is not None
        )
        if rc:
            return rc
        counted = equivalent if run.sample is None else sample_equivalents(equivalent, commit)
        for module in chosen:
            report_module(module, status, counted, accepted, work, args)
            table.append(table_row(tally(module, status, counted, accepted), run, commit))
    write_table(table)
    return 0


def table_row(t: Tally, run: PlanRun, commit: str | None) -> str:
    """The module's row of the table in docs/mutation.md."""
    total = t.mutants + t.unchecked
    if not total:
        return f"| `{t.module}` | 0 | | | | no mutants (nothing to change) | | |"
    survived = len(t.open) + len(t.accepted)
    reg = f"`{commit[:9]}`" if commit else "uncommitted"
    if t.unchecked and run.sample is None:  # a full run still going (or stopped)
        return (
            f"| `{t.module}` | {t.mutants} of {total} (unfinished) | {t.killed} | "
            f"{len(t.equivalent)} | {survived} ({len(t.accepted)} accepted) | | | {reg} |"
        )
    drawn = min(run.sample or total, total)  # the sample's size in this module
    if t.unchecked and t.mutants < drawn:  # a sample still going (or stopped): no score
        return (
            f"| `{t.module}` | {t.mutants} of {drawn} drawn of {total} (seed {run.seed}) "
            f"(unfinished) | {t.killed} | {len(t.equivalent)} | {survived} "
            f"({len(t.accepted)} accepted) | | | {reg} |"
        )
    if t.unchecked:
        lo, hi = wilson(t.killed, t.denominator)
        run_ = f"{t.mutants} of {total} (seed {run.seed})"
        interval = f"{100 * lo:.1f}–{100 * hi:.1f} %"
    else:
        run_ = f"{total} (all)"
        interval = "every mutant"
    return (
        f"| `{t.module}` | {run_} | {t.killed} | {len(t.equivalent)} | {survived} "
        f"({len(t.accepted)} accepted) | {t.score:.1f} % | {interval} | {reg} |"
    )


TABLE_HEAD = (
    "| module | mutants run | killed | equivalent | survived (accepted in writing) | score "
    "| 95 % interval | registered |\n|---|---:|---:|---:|---:|---:|---|---|"
)


def write_table(rows: list[str], paths: tuple[Path, ...] = TABLES) -> None:
    """Replace the table between ``<!-- SCORES -->`` and ``<!-- /SCORES -->`` in each of
    ``paths`` (docs/mutation.md)."""
    body = TABLE_HEAD + "\n" + "\n".join(rows) + "\n"
    for path in paths:
        doc = path.read_text(encoding="utf-8")
        a, b = doc.index("<!-- SCORES -->\n"), doc.index("<!-- /SCORES -->")
        path.write_text(doc[: a + len("<!-- SCORES -->\n")] + body + doc[b:], encoding="utf-8")
        print(f"wrote the table of {path.relative_to(ROOT)} ({len(rows)} modules)")


#: the cell of a row whose run is registered but not made yet
NOT_RUN = "| not run yet |"


def kept_row(
    previous: dict[tuple[str, int | str | None], str], module: str, seed: int | None, reg: str
) -> str:
    """The row of ``module`` in a run (of ``seed``, registered by ``reg``) whose copy is not
    here: the row the table had, or, for a run not made yet, a new such row with this
    run's registration (a module in two runs not made yet, a folder's sample and its own
    full run, has two such rows, which :func:`previous_rows` cannot tell apart)."""
    kept = previous.get((module, seed)) or previous.get((module, "any"))
    if kept is None or NOT_RUN in kept:
        return f"| `{module}` {NOT_RUN} | | | | | {reg} |"
    return kept


def previous_rows(path: Path = TABLES[0]) -> dict[tuple[str, int | str | None], str]:
    """The table's rows as last written, by (module, the sample's seed): None for a full
    run's row, "any" for a row of no mutants or of a run not made yet."""
    out: dict[tuple[str, int | str | None], str] = {}
    for line in scores_block(path.read_text(encoding="utf-8")).splitlines():
        m = re.match(r"^\| `([^`]+)` \| ([^|]*)\|", line)
        if m is None:
            continue
        seed = re.search(r"\(seed (\d+)\)", m.group(2))
        full = "(all)" in m.group(2) or "(unfinished)" in m.group(2)
        out[(m.group(1), int(seed.group(1)) if seed else None if full else "any")] = line
    return out


def scores_block(text: str) -> str:
    """The table between the SCORES markers of a document."""
    return text[text.index("<!-- SCORES -->\n") : text.index("<!-- /SCORES -->")]


def report_module(
    module: str,
    status: dict[str, str],
    equivalent: dict[str, str],
    accepted: dict[str, str],
    work: Path,
    args,
) -> None:
    """Print the module's score line, its open survivors (with diffs on ``--diff``) and
    the stale entries of the reviewed lists."""
    line, open_ = report(module, status, equivalent, accepted)
    stale = sorted(
        k
        for k in (*equivalent, *accepted)
        if of_module(k, module) and status.get(k, "gone") in KILLED | {"gone"}
    )
    print()
    print(line)
    if open_:
        lists = f"{EQUIVALENT.relative_to(ROOT)} or {ACCEPTED.name}"
        print(f"survivors not in {lists} ({len(open_)}):")
        for name in open_:
            print(f"  {name}: {status[name]}")
            if args.diff:
                diff = subprocess.run(
                    [args.mutmut, "show", name], cwd=work, capture_output=True, text=True
                ).stdout
                print("    " + "\n    ".join(diff.splitlines()[1:]))
    if stale:
        print(
            f"listed as equivalent or accepted but killed or gone (remove them): {', '.join(stale)}"
        )


if __name__ == "__main__":
    sys.exit(main())
