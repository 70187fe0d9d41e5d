"""``bodycheck explain``'s cache (:mod:`identities.cli.cache`): a second call prints the
first call's output without running the check; any change of the sources, the package
versions or the options misses; ``--no-cache`` reruns; a broken or unwritable cache is
never fatal and never silent."""

from __future__ import annotations

import json
import re

import pytest

from identities.cli import cache
from identities.cli.main import main
from identities.verify import catalogue

ITEM = "eq4.38"  # the parallel-axis theorem: a short proof


def _untimed(text: str) -> str:
    """The output without the step times (two runs differ in them)."""
    return re.sub(r"\d+\.\d+ s\b", "<t> s", text)


@pytest.fixture
def fresh(monkeypatch, tmp_path):
    monkeypatch.setenv("BODYCHECK_CACHE_DIR", str(tmp_path / "cache"))
    return tmp_path / "cache"


def _forbid_running(monkeypatch) -> None:
    def refuse(c):
        raise AssertionError(f"the check {c.id} ran although its output is cached")

    monkeypatch.setattr(catalogue, "run_check", refuse)


def test_a_second_explain_prints_the_first_ones_output_without_running(
    fresh, monkeypatch, capsys
) -> None:
    assert main(["explain", ITEM]) == 0
    first = capsys.readouterr()
    assert "PASSED" in first.out
    assert "cached" not in first.err
    _forbid_running(monkeypatch)
    assert main(["explain", ITEM]) == 0
    second = capsys.readouterr()
    assert second.out == first.out
    assert "cached" in second.err
    assert "--no-cache" in second.err


def test_options_are_part_of_the_key(fresh, monkeypatch, capsys) -> None:
    assert main(["explain", ITEM]) == 0
    plain = capsys.readouterr().out
    calls = []
    real = catalogue.run_check
    monkeypatch.setattr(catalogue, "run_check", lambda c: calls.append(c.id) or real(c))
    assert main(["explain", ITEM, "--latex"]) == 0
    assert calls, "--latex was answered from the plain output's entry"
    assert capsys.readouterr().out != plain


def test_changed_sources_miss_the_cache(fresh, monkeypatch, capsys) -> None:
    assert main(["explain", ITEM]) == 0
    capsys.readouterr()
    monkeypatch.setattr(cache, "source_digest", lambda: "another version of the code")
    calls = []
    real = catalogue.run_check
    monkeypatch.setattr(catalogue, "run_check", lambda c: calls.append(c.id) or real(c))
    assert main(["explain", ITEM]) == 0
    assert calls


def test_no_cache_runs_the_check_again(fresh, monkeypatch, capsys) -> None:
    assert main(["explain", ITEM]) == 0
    calls = []
    real = catalogue.run_check
    monkeypatch.setattr(catalogue, "run_check", lambda c: calls.append(c.id) or real(c))
    assert main(["explain", ITEM, "--no-cache"]) == 0
    assert calls
    assert "cached" not in capsys.readouterr().err


def test_a_corrupt_entry_is_a_miss_and_is_rewritten(fresh, capsys) -> None:
    assert main(["explain", ITEM]) == 0
    good = capsys.readouterr().out
    (entry,) = fresh.glob("explain-*.json")
    entry.write_text("{ not json", encoding="utf-8")
    assert main(["explain", ITEM]) == 0
    rerun = capsys.readouterr().out
    assert _untimed(rerun) == _untimed(good)
    assert json.loads(entry.read_text(encoding="utf-8"))["stdout"] == rerun


def test_an_unwritable_cache_is_reported_and_the_output_still_printed(
    monkeypatch, tmp_path, capsys
) -> None:
    blocker = tmp_path / "a-file"
    blocker.write_text("not a folder", encoding="utf-8")
    monkeypatch.setenv("BODYCHECK_CACHE_DIR", str(blocker))
    assert main(["explain", ITEM]) == 0
    out = capsys.readouterr()
    assert "PASSED" in out.out
    assert "was not written" in out.err
    assert str(blocker) in out.err


def test_the_digest_sees_every_source_edit(tmp_path) -> None:
    (tmp_path / "identities").mkdir()
    src = tmp_path / "identities" / "m.py"
    src.write_text("x = 1\n", encoding="utf-8")
    before = cache.tree_digest(tmp_path)
    assert cache.tree_digest(tmp_path) == before
    src.write_text("x = 2\n", encoding="utf-8")
    assert cache.tree_digest(tmp_path) != before
    src.write_text("x = 1\n", encoding="utf-8")
    (tmp_path / "identities" / "data.json").write_text("{}", encoding="utf-8")
    assert cache.tree_digest(tmp_path) != before
