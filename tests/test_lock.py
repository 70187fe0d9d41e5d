"""The dependency lock: the committed one is current, and a stale or corrupted one is
refused with one line naming the file and how to refresh it (tools/lock.py)."""

from __future__ import annotations

import importlib.util
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
_spec = importlib.util.spec_from_file_location("lock_tool", ROOT / "tools" / "lock.py")
lock = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(lock)


@pytest.fixture
def project(tmp_path):
    """A copy of the lock's inputs and the lock itself, to break one at a time."""
    (tmp_path / "requirements").mkdir()
    for rel in ("pyproject.toml", "requirements/tools.in", "requirements/lock.txt"):
        (tmp_path / rel).write_text((ROOT / rel).read_text(encoding="utf-8"), encoding="utf-8")
    return tmp_path


def _check(p: Path):
    return lock.check(
        p / "requirements/lock.txt", p / "pyproject.toml", p / "requirements/tools.in"
    )


def test_the_committed_lock_is_current_and_pins_every_direct_requirement() -> None:
    pins = lock.check()
    assert {"numpy", "scipy", "sympy", "hypothesis", "pytest-xdist", "uv", "setuptools"} <= set(
        pins
    )
    assert all(v[0].isdigit() for v in pins.values())


def test_a_changed_requirement_makes_the_lock_stale(project) -> None:
    py = project / "pyproject.toml"
    py.write_text(py.read_text(encoding="utf-8").replace('"numpy>=', '"numpy>=0.1,'), "utf-8")
    with pytest.raises(lock.LockError, match=r"lock\.txt: stale: .*run `make lock`"):
        _check(project)


def test_a_comment_in_pyproject_does_not_make_the_lock_stale(project) -> None:
    py = project / "pyproject.toml"
    py.write_text(py.read_text(encoding="utf-8") + "\n# a note\n", encoding="utf-8")
    assert "numpy" in _check(project)


@pytest.mark.parametrize(
    ("damage", "message"),
    [
        (lambda t: t.replace("numpy==", "numpy>=", 1), r"lock\.txt:\d+: not a pin"),
        (lambda t: "\n".join(t.splitlines()[1:]), r"no '# inputs-sha256:' first line"),
        (lambda t: t.replace("    --hash=sha256:", "    --hash=sha256:zz", 1), r"not a pin"),
        (
            lambda t: "\n".join(ln for ln in t.splitlines() if "--hash" not in ln),
            r"has no --hash line",
        ),
    ],
    ids=["range", "no-digest", "bad-hash", "no-hashes"],
)
def test_a_corrupted_lock_is_refused(project, damage, message) -> None:
    path = project / "requirements/lock.txt"
    path.write_text(damage(path.read_text(encoding="utf-8")), encoding="utf-8")
    with pytest.raises(lock.LockError, match=message) as info:
        _check(project)
    assert "make lock" in str(info.value)


def test_a_lock_missing_a_direct_requirement_is_refused(project) -> None:
    path = project / "requirements/lock.txt"
    lines = path.read_text(encoding="utf-8").splitlines()
    start = next(k for k, ln in enumerate(lines) if ln.startswith("sympy=="))
    end = next(k for k in range(start + 1, len(lines)) if not lines[k].startswith(" "))
    path.write_text("\n".join(lines[:start] + lines[end:]) + "\n", encoding="utf-8")
    with pytest.raises(lock.LockError, match="no pin for sympy"):
        _check(project)


def test_the_check_command_prints_one_line_and_exits_1() -> None:
    ok = subprocess.run(
        [sys.executable, str(ROOT / "tools/lock.py"), "check"], capture_output=True, text=True
    )
    assert ok.returncode == 0, ok.stderr
    bad = subprocess.run(
        [sys.executable, str(ROOT / "tools/lock.py"), "bogus"], capture_output=True, text=True
    )
    assert bad.returncode == 2
    assert bad.stderr.startswith("usage:")


def test_pin_gives_the_pin_and_its_hashes() -> None:
    block = lock.pin("uv").splitlines()
    assert block[0].startswith("uv==")
    assert len(block) > 1
    assert all("--hash=sha256:" in ln for ln in block[1:])


FAKE_UV = '''#!{python}
"""A stand-in for uv: records what it was given (its arguments and the output file's
contents at the call) and writes the committed lock's pins as its resolution."""
import json, sys
argv = sys.argv[1:]
out = argv[argv.index("--output-file") + 1]
try:
    with open(out, encoding="utf-8") as f:
        given = f.read()
except FileNotFoundError:
    given = None
with open({record!r}, "w", encoding="utf-8") as f:
    json.dump({{"argv": argv, "given": given}}, f)
with open(out, "w", encoding="utf-8") as f:
    f.write({body!r})
'''


@pytest.mark.parametrize("keep", [False, True], ids=["newest", "keep"])
def test_write_hands_uv_the_current_lock_only_to_keep_its_pins(tmp_path, keep) -> None:
    """``write`` (make lock) asks uv for the newest versions (--upgrade, no output file
    to prefer); ``write --keep`` (make lock-keep) gives uv a copy of the current lock to prefer
    and no --upgrade; either way the lock is uv's output under the digest line."""
    import json

    committed = (ROOT / "requirements/lock.txt").read_text(encoding="utf-8")
    body = "".join(committed.splitlines(keepends=True)[3:])  # after the 3 header lines
    record, uv = tmp_path / "record.json", tmp_path / "uv"
    uv.write_text(FAKE_UV.format(python=sys.executable, record=str(record), body=body), "utf-8")
    uv.chmod(0o755)
    target = tmp_path / "lock.txt"
    target.write_text(committed, encoding="utf-8")
    lock.write(str(uv), target, keep=keep)
    seen = json.loads(record.read_text(encoding="utf-8"))
    assert ("--upgrade" in seen["argv"]) is not keep, seen["argv"]
    assert seen["given"] == (committed if keep else None), str(seen["given"])[:200]
    assert target.read_text(encoding="utf-8") == committed
