"""A disk cache of ``bodycheck explain``'s output, keyed by everything that decides it.

``explain`` runs a check (sympy: seconds) to show its steps.  The output depends only on
the check's code, the machinery it runs on, the library it calls and the versions of the
packages involved; all checks are deterministic (fixed seeds).  So the cache key is a
digest of

- the options that shape the output (the id, ``--json``, ``--latex``);
- the source of every module and data file of ``identities`` and ``mechanics``;
- the versions of Python, sympy, mpmath, numpy, scipy and hypothesis.

Any edit to the code or an upgrade misses the cache, and a hit prints exactly what the
run printed (stdout) with its exit code; a line on stderr says that it is a cached run
and how to rerun (``--no-cache``).  Entries are JSON files written atomically (a
temporary file renamed), so parallel runs never read half an entry; an unreadable entry
is a miss.

Where: ``$BODYCHECK_CACHE_DIR``, else ``$XDG_CACHE_HOME/bodycheck``, else
``~/.cache/bodycheck``.
"""

from __future__ import annotations

import hashlib
import json
import os
import platform
import tempfile
import time
from functools import cache
from importlib import metadata
from pathlib import Path

__all__ = ["cache_dir", "load", "source_digest", "store", "tree_digest"]

#: the packages whose versions can change what a check prints
PACKAGES = ("sympy", "mpmath", "numpy", "scipy", "hypothesis")
#: the source trees whose files decide a check's output (relative to the repository)
_ROOTS = ("identities", "mechanics")
_SUFFIXES = (".py", ".json", ".toml")
#: bump when the entry format changes
FORMAT = 1


def cache_dir() -> Path:
    """The cache folder (not created here)."""
    if env := os.environ.get("BODYCHECK_CACHE_DIR"):
        return Path(env)
    base = os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
    return Path(base) / "bodycheck"


def tree_digest(top: Path, roots=_ROOTS) -> str:
    """sha256 of every source and data file under ``top/root`` for each root (names and
    contents, in sorted order) and of the versions of :data:`PACKAGES`."""
    h = hashlib.sha256()
    h.update(f"format {FORMAT}; python {platform.python_version()}".encode())
    for name in PACKAGES:
        try:
            version = metadata.version(name)
        except metadata.PackageNotFoundError:
            version = "absent"
        h.update(f"; {name} {version}".encode())
    for root in roots:
        for path in sorted((top / root).rglob("*")):
            if path.suffix in _SUFFIXES and "__pycache__" not in path.parts:
                h.update(str(path.relative_to(top)).encode() + b"\0")
                h.update(path.read_bytes() + b"\0")
    return h.hexdigest()


@cache
def source_digest() -> str:
    """:func:`tree_digest` of the installed ``identities`` and ``mechanics`` (about 10 ms
    for ~250 files)."""
    import identities

    return tree_digest(Path(identities.__file__).resolve().parent.parent)


def _path(kind: str, options: dict) -> Path:
    key = json.dumps({"kind": kind, "options": options, "source": source_digest()}, sort_keys=True)
    return cache_dir() / f"{kind}-{hashlib.sha256(key.encode()).hexdigest()[:32]}.json"


def load(kind: str, options: dict) -> tuple[str, int, float] | None:
    """(stdout, exit code, when it was run) of a cached run, or None (a miss; an
    unreadable or malformed entry is a miss too)."""
    try:
        entry = json.loads(_path(kind, options).read_text(encoding="utf-8"))
        return str(entry["stdout"]), int(entry["code"]), float(entry["created"])
    except (OSError, ValueError, KeyError, TypeError):
        return None


def store(kind: str, options: dict, stdout: str, code: int) -> str | None:
    """Keep a run's output; None, or why the cache could not be written (the caller says
    so; the run itself has printed)."""
    path = _path(kind, options)
    entry = {"stdout": stdout, "code": code, "created": time.time(), "options": options}
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".tmp-", suffix=".json")
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            json.dump(entry, f)
        os.replace(tmp, path)
    except OSError as exc:
        return f"the explain cache was not written to {path.parent}: {exc.strerror or exc}"
    return None
