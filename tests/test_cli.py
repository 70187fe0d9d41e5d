"""The ``bodycheck`` command: options, exit codes, output formats."""

from __future__ import annotations

import dataclasses
import json

import pytest

from identities.cli.main import main
from identities.verify import catalogue


@pytest.fixture
def pending_item(monkeypatch) -> str:
    """A book item without a check: the inventory plus an invented eq8.38 (the book's
    chapter 8 ends at 8.37), so the pending paths stay testable once every chapter is done."""
    inv = dict(catalogue.inventory())
    inv["eq8.38"] = dataclasses.replace(inv["eq8.37"], id="eq8.38")
    monkeypatch.setattr(catalogue, "inventory", lambda: inv)
    return "eq8.38"


def test_check_one_chapter_item_prints_a_summary(capsys) -> None:
    assert main(["check", "--id", "eq2.37", "E2.1"]) == 0
    out, err = capsys.readouterr()
    assert "eq2.37" in out
    assert "E2.1" in out
    assert "all" in out
    assert "wall" in out
    assert "2/2" in err, "progress bar on stderr"


def test_check_accepts_a_book_item_covered_by_another_check(capsys) -> None:
    """Book items that are no check's id run the check that holds them: eq2.31, one of
    the definitions eq2.36 builds on (its ``defines``), and eq2.34, one of the items it
    proves (its ``covers``); the check runs once.  (eq2.36 proves in 0.02 s; the
    definition eq2.12 of eq2.16, asked before, made the test run eq2.16's 2.5 s proof,
    which tests/test_catalogue.py runs as well.)"""
    assert main(["check", "--id", "eq2.31", "eq2.34", "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert [c["id"] for c in result["checks"]] == ["eq2.36"]
    assert result["failed"] == 0


def test_check_by_kind_and_chapter_in_json(capsys) -> None:
    assert main(["check", "--chapter", "2", "--kind", "derivation", "--json", "-j", "2"]) == 0
    result = json.loads(capsys.readouterr().out)
    ids = {c["id"] for c in result["checks"]}
    assert ids == {"E2.1", "E2.2", "E2.3", *(f"P2.{n}" for n in range(1, 8))}
    assert {c["status"] for c in result["checks"] if c["id"] == "E2.3"} == {"erratum"}


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["check", "--id", "eq9.1"], "unknown id 'eq9.1'"),
        (["check", "--chapter", "12"], "invalid choice"),
        (["check", "--kind", "lemma"], "invalid choice"),
        (["check", "-j", "0"], "-j must be at least 1"),
        (["check", "--chapter", "2", "--kind", "scene"], "no check matches"),
        (["explain", "nonsense"], "unknown id"),
        (["frobnicate"], "invalid choice"),
    ],
)
def test_bad_usage_is_one_line_and_exit_code_2(argv, message: str, capsys) -> None:
    assert main(argv) == 2
    out, err = capsys.readouterr()
    assert out == ""
    assert err.count("\n") == 1
    assert message in err


def test_explain_prints_statement_reference_and_steps(capsys) -> None:
    assert main(["explain", "eq2.36"]) == 0
    out = capsys.readouterr().out
    assert "section 2.4, page 28" in out or "section 2.4" in out
    assert "proved (expand" in out
    assert "rejected wrong variant" in out
    assert "cos(φ)" in out or "cos(phi)" in out  # pretty-printed matrix


def test_explain_json_gives_quantities_as_srepr(capsys) -> None:
    assert main(["explain", "P2.6", "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["id"] == "P2.6"
    assert result["status"] == "verified"
    assert set(result["quantities"]) == {"zeta", "omega", "v3"}
    assert result["quantities"]["zeta"] == "Integer(-12)"
    assert result["quantities"]["v3"].startswith("ImmutableDenseMatrix(")


def test_explain_an_erratum_shows_both_forms(capsys) -> None:
    assert main(["explain", "eq2.92"]) == 0
    out = capsys.readouterr().out
    assert "status: erratum" in out
    assert "printed (false)" in out
    assert "corrected" in out


def test_a_pending_item_is_reported_as_such(pending_item: str, capsys) -> None:
    assert main(["explain", pending_item, "--json"]) == 0
    assert json.loads(capsys.readouterr().out) == {
        "id": pending_item,
        "status": "pending",
        "quantities": {},
    }
    assert main(["check", "--id", pending_item]) == 2
    out, err = capsys.readouterr()
    assert out == ""
    assert "without a check yet" in err


def test_timings_lists_the_slowest_checks_with_their_strategies(capsys) -> None:
    assert main(["check", "--id", "eq8.6", "eq8.8", "E8.1", "--timings", "2"]) == 0
    out = capsys.readouterr().out
    table = out[out.index("slowest 2 of 3 checks") :].splitlines()
    assert len(table) == 2 + 2  # title, header, two rows
    rows = {line.split()[0]: line for line in table[2:]}
    assert set(rows) < {"eq8.6", "eq8.8", "E8.1"}
    assert all("expand" in line and "proved (expand" in line for line in rows.values())


def test_bench_runs_the_study_with_its_arguments_and_prints_its_summary(
    tmp_path, capsys, monkeypatch
) -> None:
    """The command's wiring: what it passes to the study and what it prints.  The study
    itself (its files, its figures, its power to fail) is tests/test_workprecision.py's."""
    import bench.workprecision as wp
    import bench.workprecision.study as study_module

    calls: list[dict] = []
    study = {
        "total_time_s": 1.5,
        "headline": {
            "targets": [{"status": "met", "name": "a target", "measured": 2.5, "goal": "≥ 2"}]
        },
    }

    def run_study(**kwargs):
        calls.append(kwargs)
        return study

    monkeypatch.setattr(study_module, "run_study", run_study)
    assert main(["bench", "--quick", "--out", str(tmp_path)]) == 0
    assert calls == [dict(quick=True, out_dir=tmp_path, repeats=1, progress=True)]
    assert capsys.readouterr().out.splitlines() == wp.summary_lines(study, str(tmp_path))
    assert main(["bench", "--out", str(tmp_path), "--repeats", "2"]) == 0
    assert calls[-1] == dict(quick=False, out_dir=tmp_path, repeats=2, progress=True)
    capsys.readouterr()
    assert main(["bench", "--quick", "--repeats", "0", "--out", str(tmp_path)]) == 2
    assert "--repeats must be at least 1; got 0" in capsys.readouterr().err
    assert len(calls) == 2, "a refused command runs nothing"
