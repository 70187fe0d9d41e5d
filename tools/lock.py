"""The dependency lock: write it (``make lock``), check it before every install.

``requirements/lock.txt`` pins every direct and transitive dependency of bodycheck's
``test``, ``engines``, ``mutation``, ``notebooks`` and ``docs`` extras, the build backend
and the installer (``requirements/tools.in``), each with its hashes, as ``uv pip compile``
writes them for Python 3.11.  Its first line records a digest of what it was compiled from
(pyproject's requirements and tools.in), so that a lock older than its inputs is refused
with a message saying how to refresh it, rather than installed.

Usage (standard library only; run with the machine's Python before any venv exists)::

    python tools/lock.py check             # exit 1 with one line if stale or corrupted
    python tools/lock.py write UV          # compile with the uv binary UV, add the digest:
                                           # every pin the newest allowed (make lock)
    python tools/lock.py write UV --keep   # the same, keeping every pin of the current lock
                                           # that still satisfies the inputs (only new or
                                           # changed requirements are resolved afresh)
    python tools/lock.py pin NAME          # the lock's lines for NAME (pin and hashes)
"""

from __future__ import annotations

import hashlib
import json
import re
import shutil
import subprocess
import sys
import tempfile
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
LOCK = ROOT / "requirements" / "lock.txt"
TOOLS = ROOT / "requirements" / "tools.in"
PYPROJECT = ROOT / "pyproject.toml"
PYTHON_VERSION = "3.11"
EXTRAS = ("test", "engines", "mutation", "notebooks", "docs")

DIGEST_PREFIX = "# inputs-sha256: "
_PIN = re.compile(
    r"^(?P<name>[A-Za-z0-9][A-Za-z0-9._-]*)(\[[^\]]+\])?==(?P<ver>[A-Za-z0-9.+!_-]+)( \\)?$"
)
_HASH = re.compile(r"^ +--hash=sha256:[0-9a-f]{64}( \\)?$")
_NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9._-]*")


class LockError(Exception):
    """The lock cannot be used: the message says why and how to refresh it."""


def _normal(name: str) -> str:
    return re.sub(r"[-_.]+", "-", name).lower()


def inputs_digest(pyproject: Path = PYPROJECT, tools: Path = TOOLS) -> str:
    """sha256 of what the lock is compiled from: pyproject's requirements, requires-python,
    build requirements, and tools.in (comments and blank lines ignored)."""
    data = tomllib.loads(pyproject.read_text(encoding="utf-8"))
    project = data.get("project", {})
    tool_lines = [
        ln.strip()
        for ln in tools.read_text(encoding="utf-8").splitlines()
        if ln.strip() and not ln.strip().startswith("#")
    ]
    payload = {
        "dependencies": project.get("dependencies", []),
        # every extra: the locked ones may name others ("bodycheck[mujoco,drake]")
        "optional": project.get("optional-dependencies", {}),
        "requires-python": project.get("requires-python", ""),
        "build": data.get("build-system", {}).get("requires", []),
        "tools": tool_lines,
        "python": PYTHON_VERSION,
    }
    return hashlib.sha256(json.dumps(payload, sort_keys=True).encode()).hexdigest()


def direct_names(pyproject: Path = PYPROJECT, tools: Path = TOOLS) -> set[str]:
    """Normalised names of the direct requirements the lock must pin."""
    data = tomllib.loads(pyproject.read_text(encoding="utf-8"))
    project = data.get("project", {})
    reqs = list(project.get("dependencies", []))
    extras = project.get("optional-dependencies", {})
    todo, seen = list(EXTRAS), set()
    while todo:  # an extra may name others of this project: "bodycheck[a,b]"
        k = todo.pop()
        if k in seen:
            continue
        seen.add(k)
        for r in extras.get(k, []):
            own = re.match(rf"^{re.escape(project.get('name', ''))}\[([^\]]+)\]", r.strip())
            if own:
                todo += [e.strip() for e in own.group(1).split(",")]
            else:
                reqs.append(r)
    reqs += [
        ln.strip()
        for ln in tools.read_text(encoding="utf-8").splitlines()
        if ln.strip() and not ln.strip().startswith("#")
    ]
    return {_normal(m.group(0)) for r in reqs if (m := _NAME.match(r.strip()))}


def parse_lock(text: str, where: str) -> dict[str, str]:
    """The pins of a lock, {normalised name: version}; LockError on any line that is not
    a pin, a hash of the pin above, a comment or blank."""
    pins: dict[str, str] = {}
    current, hashes = None, 0
    for k, line in enumerate(text.splitlines(), start=1):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        if m := _PIN.match(line):
            if current is not None and hashes == 0:
                raise LockError(f"{where}:{k - 1}: {current!r} has no --hash line")
            current, hashes = _normal(m["name"]), 0
            pins[current] = m["ver"]
        elif _HASH.match(line) and current is not None:
            hashes += 1
        else:
            raise LockError(f"{where}:{k}: not a pin, a hash or a comment: {line.strip()[:60]!r}")
    if current is not None and hashes == 0:
        raise LockError(f"{where}: {current!r} has no --hash line")
    return pins


def check(lock: Path = LOCK, pyproject: Path = PYPROJECT, tools: Path = TOOLS) -> dict[str, str]:
    """Validate the lock against its inputs; returns its pins or raises LockError."""
    where = str(lock.relative_to(ROOT)) if lock.is_relative_to(ROOT) else str(lock)
    refresh = "run `make lock` to refresh it"
    if not lock.exists():
        raise LockError(f"{where}: missing; {refresh}")
    text = lock.read_text(encoding="utf-8")
    first = text.splitlines()[0] if text else ""
    if not first.startswith(DIGEST_PREFIX):
        raise LockError(f"{where}: corrupted (no '{DIGEST_PREFIX.strip()}' first line); {refresh}")
    if first[len(DIGEST_PREFIX) :].strip() != inputs_digest(pyproject, tools):
        raise LockError(
            f"{where}: stale: pyproject.toml or {tools.name} changed since it was written; "
            f"{refresh}"
        )
    try:
        pins = parse_lock(text, where)
    except LockError as exc:
        raise LockError(f"{exc}; corrupted, {refresh}") from None
    missing = sorted(direct_names(pyproject, tools) - set(pins))
    if missing:
        raise LockError(f"{where}: corrupted: no pin for {', '.join(missing)}; {refresh}")
    return pins


def write(uv: str, lock: Path = LOCK, *, keep: bool = False) -> None:
    """Compile the lock with uv (hashes, Python 3.11) and put the digest line first.

    By default every pin is the newest version the inputs allow (``uv pip compile
    --upgrade``).  With ``keep``, uv is given the current lock as its output file, whose
    pins it prefers (uv's documented behaviour for an existing ``--output-file``): a pin
    that still satisfies the inputs stays, and only what is new or no longer satisfied is
    resolved, so adding an extra leaves every existing pin as it was.
    """
    extras = [a for e in EXTRAS for a in ("--extra", e)]
    with tempfile.TemporaryDirectory() as tmp:
        # uv writes the file it is given: a copy of the lock, never the lock itself
        out_file = Path(tmp) / "lock.txt"
        if keep and lock.is_file():
            shutil.copyfile(lock, out_file)
        subprocess.run(
            [uv, "pip", "compile", str(PYPROJECT.relative_to(ROOT)), str(TOOLS.relative_to(ROOT)),
             *extras, "--python-version", PYTHON_VERSION, "--generate-hashes", "--quiet",
             "--no-header", "--output-file", str(out_file), *([] if keep else ["--upgrade"])],
            cwd=ROOT, check=True, capture_output=True, text=True,
        )  # fmt: skip
        body = out_file.read_text(encoding="utf-8")
    header = (
        f"{DIGEST_PREFIX}{inputs_digest()}\n"
        "# Written by `make lock` (tools/lock.py: uv pip compile pyproject.toml\n"
        f"# requirements/tools.in {' '.join('--extra ' + e for e in EXTRAS)}"
        f" --python-version {PYTHON_VERSION}"
        " --generate-hashes); do not edit.\n"
    )
    lock.write_text(header + body, encoding="utf-8")
    check(lock)


def pin(name: str, lock: Path = LOCK) -> str:
    """The lock's block for one package: its pin line and hash lines."""
    lines, keep = [], False
    for line in lock.read_text(encoding="utf-8").splitlines():
        if m := _PIN.match(line):
            keep = _normal(m["name"]) == _normal(name)
        if keep and (_PIN.match(line) or _HASH.match(line)):
            lines.append(line)
    if not lines:
        raise LockError(f"{lock}: no pin for {name!r}; run `make lock` to refresh it")
    return "\n".join(lines) + "\n"


def main(argv: list[str]) -> int:
    try:
        if argv[:1] == ["check"] and len(argv) == 1:
            check()
        elif argv[:1] == ["write"] and len(argv) == 2:
            write(argv[1])
        elif argv[:1] == ["write"] and len(argv) == 3 and argv[2] == "--keep":
            write(argv[1], keep=True)
        elif argv[:1] == ["pin"] and len(argv) == 2:
            sys.stdout.write(pin(argv[1]))
        else:
            print("usage: lock.py check | write UV [--keep] | pin NAME", file=sys.stderr)
            return 2
    except LockError as exc:
        print(f"lock: {exc}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
