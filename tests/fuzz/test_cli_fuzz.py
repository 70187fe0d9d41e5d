"""Fuzz the ``bodycheck`` command line (issue 16, part 3): bad input is one line, exit 2.

Every subcommand is listed from the parser itself, so a new subcommand without a row in
:data:`BAD_ARGV` fails :func:`test_every_subcommand_has_fuzz_cases`. Each bad command
line (unknown ids, bad numbers, missing or unreadable files, a directory for a file,
a file for a directory) must return exit code 2 with exactly one line on stderr,
``bodycheck: error: ...``, and no traceback. The CLI runs in-process (``main(argv)``);
two cases run end to end in a subprocess (slow: the sympy import).
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from identities.cli.main import _parser, main

#: placeholders expanded per test: {missing} a path that does not exist, {dir} a
#: folder, {file} an existing ordinary file, {bad_toml} a malformed TOML file,
#: {latin1} a file that is not UTF-8, {in_file} a path below an ordinary file
BAD_ARGV: dict[str, list[list[str]]] = {
    "check": [
        ["check", "--id", "no-such-check"],
        ["check", "--id", "eq99.99"],
        ["check", "--chapter", "9"],
        ["check", "--chapter", "two"],
        ["check", "--chapter", "nan"],
        ["check", "--kind", "nonsense"],
        ["check", "-j", "0", "--id", "eq2.37"],
        ["check", "-j", "-4", "--id", "eq2.37"],
        ["check", "-j", "1e3", "--id", "eq2.37"],
        ["check", "--timings", "many"],
        ["check", "--chapter", "1", "--kind", "scene", "--id", "eq2.37"],
    ],
    "explain": [
        ["explain", "no-such-check"],
        ["explain", ""],
        ["explain"],
    ],
    "search": [
        ["search"],
    ],
    "catalogue": [
        ["catalogue", "--write", "{dir}"],
        ["catalogue", "--write", "{in_file}"],
        ["catalogue", "--write", "{missing}/sub/CHECKS.md"],
    ],
    "scene": [
        ["scene"],
        ["scene", "{missing}"],
        ["scene", "{dir}"],
        ["scene", "{bad_toml}"],
        ["scene", "{latin1}"],
        ["scene", "{file}"],
        ["scene", "{bad_toml}", "--method", "bogus"],
        ["scene", "{in_file}"],
    ],
    "demo": [
        ["demo"],
        ["demo", "no-such-demo"],
        ["demo", ""],
        ["demo", "bouncing_ball", "--method", "bogus"],
    ],
    "bench": [
        ["bench", "--repeats", "0"],
        ["bench", "--repeats", "-2"],
        ["bench", "--repeats", "three"],
        ["bench", "--quick", "--out", "{file}"],
        ["bench", "--quick", "--out", "{in_file}"],
    ],
    "conform": [
        ["conform"],
        ["conform", "no-colon"],
        ["conform", "no_such_module_here:Adapter"],
        ["conform", "math:no_such_attribute"],
        ["conform", "math:pi"],
        ["conform", "{missing}.py:Adapter"],
        ["conform", "{dir}:Adapter"],
        ["conform", "{latin1}:Adapter"],
        ["conform", "exact", "--scenario", "no_such_scenario"],
        ["conform", "exact", "--threshold", "velocity=abc"],
        ["conform", "exact", "--threshold", "=1"],
        ["conform", "exact", "--threshold", "no_such_figure=1"],
        ["conform", "exact", "--plot", "report.pdf"],
        ["conform", "exact", "--scenario", "parabola", "--markdown", "{in_file}"],
        ["conform", "exact", "--profile", "no-such-profile"],
        ["conform", "exact", "--config", "{missing}.toml"],
        ["conform", "exact", "--config", "{latin1}"],
        ["conform", "exact", "--config", "{dir}"],
        ["conform", "exact", "--baseline", "pyproject.toml"],
        ["conform", "exact", "--baseline", "b.toml", "--margin", "-1"],
        ["conform", "exact", "--baseline", "b.toml", "--margin", "x"],
        ["conform", "exact", "--scenario", "parabola", "--json", "{in_file}"],
        ["conform", "all", "--scenario", "parabola", "--markdown", "{in_file}"],
    ],
    "site": [
        ["site"],
        ["site", "{file}"],
        ["site", "{in_file}"],
    ],
    "notebooks": [
        ["notebooks"],
        ["notebooks", "--write", "{file}"],
        ["notebooks", "--write", "{in_file}"],
        ["notebooks", "--check", "{file}"],
        ["notebooks", "--check", "{missing}"],
        ["notebooks", "--check", "{dir}", "--execute"],
        ["notebooks", "--check", "{dir}", "--write", "{dir}"],
        ["notebooks", "--execute"],
    ],
}


def _subcommands() -> list[str]:
    p = _parser()
    (sub,) = [a for a in p._actions if a.__class__.__name__ == "_SubParsersAction"]
    return sorted(sub.choices)


def test_every_subcommand_has_fuzz_cases():
    missing = sorted(set(_subcommands()) - set(BAD_ARGV))
    assert not missing, f"subcommands without CLI fuzz cases (add them to BAD_ARGV): {missing}"
    stale = sorted(set(BAD_ARGV) - set(_subcommands()))
    assert not stale, f"CLI fuzz cases for subcommands that are gone: {stale}"


@pytest.fixture
def paths(tmp_path: Path) -> dict[str, str]:
    f = tmp_path / "plain.txt"
    f.write_text("just text, not TOML [\n", encoding="utf-8")
    bad = tmp_path / "bad.toml"
    bad.write_text('[scene]\nname = "x"\nduration = \n', encoding="utf-8")
    latin = tmp_path / "latin1.toml"
    latin.write_bytes('[scene]\nname = "café"\n'.encode("latin-1"))
    folder = tmp_path / "folder"
    folder.mkdir()
    return {
        "missing": str(tmp_path / "does-not-exist"),
        "dir": str(folder),
        "file": str(f),
        "bad_toml": str(bad),
        "latin1": str(latin),
        "in_file": str(f / "below-a-file"),
    }


def _cases():
    for cmd, argvs in BAD_ARGV.items():
        for argv in argvs:
            yield pytest.param(argv, id=" ".join(argv) or cmd)


@pytest.mark.parametrize("argv", list(_cases()))
def test_bad_command_line_is_one_line_and_exit_code_2(argv, paths, capsys):
    argv = [a.format(**paths) for a in argv]
    code = main(argv)
    out, err = capsys.readouterr()
    assert code == 2, f"exit code {code} for {argv}; stderr: {err!r}"
    lines = err.strip().splitlines()
    assert len(lines) == 1, f"{argv}: expected one line on stderr, got {err!r}"
    assert lines[0].startswith("bodycheck: error: "), lines[0]
    assert "Traceback" not in err + out


def test_an_unknown_subcommand_is_one_line_and_exit_code_2(capsys):
    assert main(["no-such-subcommand"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1
    assert err[0].startswith("bodycheck: error: ")


def test_end_to_end_a_missing_scene_file_exits_2_without_a_traceback():
    proc = subprocess.run(
        [sys.executable, "-m", "identities.cli", "scene", "/no/such/scene.toml"],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
    )
    assert proc.returncode == 2, proc.stderr
    assert "Traceback" not in proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1, proc.stderr
