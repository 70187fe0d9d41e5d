"""The support matrix (tools/matrix.py, ``make test-matrix``) and the lock-drift line of
the report header (tests/conftest.py): what they refuse, find and say, without running
the suite on other interpreters (``make test-matrix`` does that)."""

from __future__ import annotations

import importlib.util
import subprocess
import sys
from importlib import metadata
from pathlib import Path

import pytest

from tests.conftest import lock_drift

ROOT = Path(__file__).resolve().parent.parent
_spec = importlib.util.spec_from_file_location("matrix_tool", ROOT / "tools" / "matrix.py")
matrix = importlib.util.module_from_spec(_spec)
sys.modules["matrix_tool"] = matrix  # its dataclasses look their module up
_spec.loader.exec_module(matrix)


def test_a_python_older_than_requires_python_is_refused_with_one_line() -> None:
    run = subprocess.run(
        [sys.executable, str(ROOT / "tools" / "matrix.py"), "3.10"],
        capture_output=True,
        text=True,
        check=False,
    )
    assert run.returncode == 2
    assert run.stdout == ""
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 1
    assert "Python 3.10 is older than requires-python '>=3.11'" in lines[0]


@pytest.mark.parametrize("text", ["3", "3.x", "2.7", "python3.12", "3.12.1", "3.9"])
def test_a_version_not_of_the_form_3_x_or_below_the_floor_is_refused(text) -> None:
    with pytest.raises(matrix.MatrixError, match=text.replace(".", r"\.")):
        matrix.parse_minor(text, 11)


def test_the_floor_is_read_from_pyproject_and_the_classifiers_start_there() -> None:
    floor = matrix.requires_floor()
    assert floor == 11
    listed = matrix.classified_minors()
    # a contiguous range from the floor: the versions the matrix passed (the closing note of
    # the issue that made it lists each run)
    assert listed == set(range(floor, max(listed) + 1))


def test_a_python_that_is_nowhere_on_the_machine_is_reported_absent(monkeypatch, tmp_path) -> None:
    monkeypatch.setenv("PATH", str(tmp_path))
    monkeypatch.setenv("PYENV_ROOT", str(tmp_path))
    leg = matrix.run_leg(99, "uv", [])
    assert leg.status == "absent"
    assert "python3.99" in leg.detail


def test_an_interpreter_that_cannot_start_is_reported_with_its_error(tmp_path, monkeypatch) -> None:
    fake = tmp_path / "python3.98"
    fake.write_text("#!/bin/sh\necho 'no module named venv' >&2\nexit 1\n")
    fake.chmod(0o755)
    monkeypatch.setenv("PATH", str(tmp_path))
    monkeypatch.setenv("PYENV_ROOT", str(tmp_path / "none"))
    leg = matrix.run_leg(98, "uv", [])
    assert leg.status == "setup failed"
    assert "no module named venv" in leg.detail


def test_the_drift_line_names_each_package_with_its_locked_and_installed_versions(tmp_path) -> None:
    here = metadata.version("numpy")
    lock = tmp_path / "lock.txt"
    lock.write_text(
        "numpy==0.0.1 \\\n    --hash=sha256:00\n"
        f"scipy=={metadata.version('scipy')} \\\n"
        "not-installed-anywhere==1.0\n"
    )
    assert lock_drift(lock) == [f"numpy 0.0.1 → {here}"]
    assert lock_drift(tmp_path / "absent.txt") == []
