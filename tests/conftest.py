"""Hypothesis profiles, chosen by HYPOTHESIS_PROFILE (default: ``ci`` when CI is set).

- ``ci``: derandomised (the same examples every run), no deadline.
- ``dev``: the default locally; random, no deadline (sympy and mpmath are slow on
  first call).
- ``explore``: ten times the examples of ``ci``, random, for hunting.

``bodycheck explain`` keeps its output in a cache (:mod:`identities.cli.cache`); the
suite gives each worker a fresh cache folder, so no test reads a user's cache or another
worker's entries, and none writes into ``~/.cache``.

The report's header names every locked package whose installed version differs from
``requirements/lock.txt`` (locked → here), and a failing run repeats that line at its
end, so a failure on the newest versions (``make test-matrix``, ``make test-latest``)
shows which library moved without a bisect.
"""

from __future__ import annotations

import os
import re
import sys
from importlib import metadata
from pathlib import Path

import pytest
from hypothesis import HealthCheck, settings

_BASE = settings(deadline=None, suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("ci", _BASE, derandomize=True, max_examples=100, print_blob=True)
settings.register_profile("dev", _BASE, max_examples=100)
settings.register_profile("explore", _BASE, max_examples=1000)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci" if os.environ.get("CI") else "dev"))


@pytest.fixture(autouse=True, scope="session")
def _fresh_explain_cache(tmp_path_factory):
    old = os.environ.get("BODYCHECK_CACHE_DIR")
    os.environ["BODYCHECK_CACHE_DIR"] = str(tmp_path_factory.mktemp("bodycheck-cache"))
    yield
    if old is None:
        os.environ.pop("BODYCHECK_CACHE_DIR", None)
    else:
        os.environ["BODYCHECK_CACHE_DIR"] = old


def shared_once(tmp_path_factory, name: str, build) -> Path:
    """A folder ``name`` that ``build(folder)`` fills once per run of the suite, shared by
    every pytest-xdist worker: the first worker to ask builds it while the others wait on
    a lock (``fcntl.flock``), then all read it.  For a costly fixture that tests only read
    (the site, the quick study); a test that changes what it reads copies it first.  A
    build that fails leaves no folder behind, so the next worker to ask builds again and
    fails the same way."""
    import fcntl
    import shutil

    base = tmp_path_factory.getbasetemp()
    root = base.parent if os.environ.get("PYTEST_XDIST_WORKER") else base
    folder, done = root / f"shared-{name}", root / f"shared-{name}.done"
    with open(root / f"shared-{name}.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not done.exists():
            shutil.rmtree(folder, ignore_errors=True)
            folder.mkdir()
            try:
                build(folder)
            except BaseException:
                shutil.rmtree(folder, ignore_errors=True)
                raise
            done.touch()
    return folder


_LOCK = Path(__file__).resolve().parent.parent / "requirements" / "lock.txt"
_PIN = re.compile(r"^([A-Za-z0-9][A-Za-z0-9._-]*)(?:\[[^\]]+\])?==([^ \\]+)", re.MULTILINE)


def _normal(name: str) -> str:
    return re.sub(r"[-_.]+", "-", name).lower()


def lock_drift(lock: Path = _LOCK) -> list[str]:
    """'name locked → installed' for every package of the lock installed at another
    version (a package of the lock that is not installed is not drift)."""
    if not lock.is_file():
        return []
    out = []
    for name, locked in _PIN.findall(lock.read_text(encoding="utf-8")):
        try:
            here = metadata.version(name)
        except metadata.PackageNotFoundError:
            continue
        if _normal(here) != _normal(locked):
            out.append(f"{name} {locked} → {here}")
    return out


def _drift_line() -> str:
    drift = lock_drift()
    python = ".".join(map(str, sys.version_info[:3]))
    if not drift:
        return (
            f"bodycheck: Python {python}; every installed package of the lock at its locked version"
        )
    return (
        f"bodycheck: Python {python}; {len(drift)} packages differ from requirements/lock.txt "
        f"(locked → here): {', '.join(drift)}"
    )


def pytest_report_header(config) -> str:
    return _drift_line()


def pytest_terminal_summary(terminalreporter, exitstatus, config) -> None:
    if exitstatus not in (0, 5) and lock_drift():
        terminalreporter.write_line(
            f"the failures above ran on other versions than the lock: {_drift_line()}"
        )
