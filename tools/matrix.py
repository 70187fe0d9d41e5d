"""The support matrix: the suite on every Python that ``requires-python`` admits and that
this machine has, each with the newest versions pyproject allows (``make test-matrix``).

For each CPython minor version from requires-python's floor to ``NEWEST_MINOR``, the
interpreter ``python3.X`` is looked up on PATH; an absent one is reported with a line and
skipped.  A present one gets its own venv (``.venv-matrix/3.X``), ``-e '.[test]'`` installed
by uv with ``--upgrade`` (no lock), and the suite's command line (the Makefile's
PYTEST_ARGS).  A venv that cannot be built (no ``venv`` module, no wheel for a package) is
reported with uv's words naming the package, and the matrix goes on.  At the end, one row
per version: the interpreter, the key packages' versions, the suite's counts and time; and
whether pyproject's ``Programming Language :: Python :: 3.X`` classifiers list exactly the
versions that passed.

Usage (standard library only; ``make test-matrix`` passes the venv's uv)::

    python tools/matrix.py --uv .venv/bin/uv            # every version found
    python tools/matrix.py --uv .venv/bin/uv 3.12 3.13  # only these (each must be admitted)

Exit status: 0 when every version found passed, 1 when one failed or could not be set up,
2 for a version asked for that requires-python does not admit.
"""

from __future__ import annotations

import argparse
import os
import re
import shlex
import shutil
import subprocess
import sys
import time
import tomllib
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PYPROJECT = ROOT / "pyproject.toml"
VENVS = ROOT / ".venv-matrix"
#: the newest CPython minor version released when this was written (3.15.0: October 2026)
NEWEST_MINOR = 15
#: the packages whose versions each row shows (the suite's numerics and its tools)
KEY_PACKAGES = ("numpy", "scipy", "sympy", "mpmath", "numba", "hypothesis", "matplotlib", "mujoco")
_SUMMARY = re.compile(r"=+ (?P<body>.*?) in (?P<secs>[0-9.]+)s")
_CLASSIFIER = re.compile(r"^Programming Language :: Python :: 3\.(\d+)$")


class MatrixError(Exception):
    """A request the matrix refuses (a version requires-python does not admit)."""


@dataclass
class Leg:
    minor: int
    status: str  # "passed", "failed", "absent", "setup failed"
    detail: str = ""
    versions: str = ""
    counts: str = ""
    seconds: float = 0.0


def requires_floor(pyproject: Path = PYPROJECT) -> int:
    """The lowest 3.X minor admitted by requires-python (only ``>=3.X`` forms are used here)."""
    spec = tomllib.loads(pyproject.read_text(encoding="utf-8"))["project"]["requires-python"]
    m = re.fullmatch(r"\s*>=\s*3\.(\d+)\s*", spec)
    if m is None:
        raise MatrixError(f"requires-python {spec!r}: the matrix reads only the form '>=3.X'")
    return int(m.group(1))


def classified_minors(pyproject: Path = PYPROJECT) -> set[int]:
    """The 3.X minors that pyproject's classifiers list."""
    project = tomllib.loads(pyproject.read_text(encoding="utf-8"))["project"]
    out = set()
    for c in project.get("classifiers", []):
        m = _CLASSIFIER.match(c)
        if m:
            out.add(int(m.group(1)))
    return out


def parse_minor(text: str, floor: int) -> int:
    """'3.12' → 12; a version below requires-python's floor is refused."""
    m = re.fullmatch(r"3\.(\d+)", text)
    if m is None:
        raise MatrixError(f"Python version {text!r}: expected the form 3.X, e.g. 3.12")
    minor = int(m.group(1))
    if minor < floor:
        raise MatrixError(
            f"Python {text} is older than requires-python '>=3.{floor}' (pyproject.toml): "
            "bodycheck does not support it, so the matrix does not test it"
        )
    return minor


def _run(cmd: list[str], **kw) -> subprocess.CompletedProcess:
    return subprocess.run(cmd, cwd=ROOT, text=True, capture_output=True, check=False, **kw)


def _last_lines(text: str, n: int = 3) -> str:
    lines = [ln.strip() for ln in text.strip().splitlines() if ln.strip()]
    return " | ".join(lines[-n:])


def interpreters(minor: int) -> list[str]:
    """Candidates for python3.X: the one on PATH, then pyenv's installed versions (a pyenv
    shim on PATH answers only for the versions pyenv has activated)."""
    found = [exe] if (exe := shutil.which(f"python3.{minor}")) else []
    pyenv_root = Path(os.environ.get("PYENV_ROOT", Path.home() / ".pyenv"))
    found += sorted(
        str(p) for p in pyenv_root.glob(f"versions/3.{minor}.*/bin/python3.{minor}") if p.is_file()
    )[::-1]  # the newest patch release first
    return found


def _probe(minor: int) -> tuple[str, str] | Leg:
    """(path, full version) of a working python3.X with a venv module, or the failed Leg."""
    tried = interpreters(minor)
    if not tried:
        return Leg(minor, "absent", f"no python3.{minor} on PATH or in pyenv's versions")
    why = []
    for exe in tried:
        probe = _run([exe, "-c", "import sys, venv; print(sys.version.split()[0])"])
        full = probe.stdout.strip()
        if probe.returncode == 0 and full.startswith(f"3.{minor}."):
            return exe, full
        why.append(f"{exe}: {_last_lines(probe.stderr, 1) or 'reports ' + full}")
    return Leg(minor, "setup failed", "; ".join(why))


def run_leg(minor: int, uv: str, pytest_args: list[str]) -> Leg:
    found = _probe(minor)
    if isinstance(found, Leg):
        return found
    exe, full = found
    venv = VENVS / f"3.{minor}"
    shutil.rmtree(venv, ignore_errors=True)
    made = _run([exe, "-m", "venv", str(venv)])
    if made.returncode != 0:
        return Leg(minor, "setup failed", f"venv for {full}: {_last_lines(made.stderr)}")
    py = str(venv / "bin" / "python")
    inst = _run([uv, "pip", "install", "--quiet", "--python", py, "--upgrade", "-e", ".[test]"])
    if inst.returncode != 0:
        # uv names the package that has no wheel or no version for this interpreter
        return Leg(minor, "setup failed", f"install on {full}: {_last_lines(inst.stderr, 4)}")
    freeze = _run([py, "-m", "pip", "list", "--format=freeze"]).stdout
    pins = dict(ln.split("==", 1) for ln in freeze.splitlines() if "==" in ln)
    lower = {k.lower(): v for k, v in pins.items()}
    versions = " ".join(f"{p} {lower[p]}" for p in KEY_PACKAGES if p in lower)
    print(f"matrix: Python {full}: {versions}; running the suite", flush=True)
    t0 = time.perf_counter()
    test = subprocess.run(
        [py, "-m", "pytest", *pytest_args, "-p", "no:cacheprovider"], cwd=ROOT, check=False
    )
    secs = time.perf_counter() - t0
    leg = Leg(minor, "passed" if test.returncode == 0 else "failed", versions=versions)
    leg.detail, leg.seconds = f"Python {full}", secs
    return leg


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("versions", nargs="*", help="3.X versions to run (default: every one found)")
    ap.add_argument("--uv", default="uv", help="the uv binary that installs each venv")
    ap.add_argument("--pytest-args", default="-n auto", help="the suite's command line")
    args = ap.parse_args(argv)
    try:
        floor = requires_floor()
        minors = (
            [parse_minor(v, floor) for v in args.versions]
            if args.versions
            else list(range(floor, NEWEST_MINOR + 1))
        )
    except MatrixError as exc:
        print(f"matrix: {exc}", file=sys.stderr)
        return 2
    legs = []
    for minor in minors:
        leg = run_leg(minor, args.uv, shlex.split(args.pytest_args))
        if leg.status in ("absent", "setup failed"):
            print(f"matrix: Python 3.{minor}: {leg.status}: {leg.detail}", flush=True)
        legs.append(leg)
    print("\nmatrix: the suite on every Python found, newest versions pyproject allows")
    for leg in legs:
        took = f" in {leg.seconds:.0f} s" if leg.seconds else ""
        what = f"{leg.detail}; {leg.versions}" if leg.versions else leg.detail
        print(f"  3.{leg.minor}: {leg.status}{took}: {what}")
    passed = {leg.minor for leg in legs if leg.status == "passed"}
    bad = [leg for leg in legs if leg.status in ("failed", "setup failed")]
    classified = classified_minors()
    wrong = sorted(m for m in classified if m in {leg.minor for leg in bad})
    missing = sorted(passed - classified)
    if wrong:
        names = ", ".join(f"3.{m}" for m in wrong)
        print(f"matrix: pyproject's classifiers list {names} as supported, and it failed here")
    if missing:
        names = ", ".join(f"3.{m}" for m in missing)
        print(f"matrix: {names} passed, but pyproject's classifiers do not list it")
    return 1 if bad or wrong or missing else 0


if __name__ == "__main__":
    sys.exit(main())
