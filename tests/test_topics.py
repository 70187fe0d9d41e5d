"""Finding checks by topic (``bodycheck search``, ``bodycheck explain TOPIC``)."""

from __future__ import annotations

import json

import pytest

from identities.cli.main import main
from identities.verify import catalogue, topics


def _ids(query: str) -> list[str]:
    return [c.id for c in topics.search(query)]


def test_every_name_points_at_registered_checks() -> None:
    reg = catalogue.load_all()
    missing = {n: [i for i in ids if i not in reg] for n, ids in topics.NAMES.items()}
    assert not any(missing.values()), missing


@pytest.mark.parametrize(
    ("query", "first"),
    [
        ("parallel-axis", ["eq4.38", "E3.1"]),  # the name's checks first
        ("Steiner", ["eq4.38", "E3.1"]),
        ("Euler's equations", ["eq4.47", "eq5.91", "E5.2"]),
        ("tennis racket", ["eq5.102"]),
        ("Tsiolkovsky", ["E7.2"]),
    ],
)
def test_a_theorems_name_finds_its_checks_first(query, first) -> None:
    assert _ids(query)[: len(first)] == first


def test_topic_words_come_from_titles_statements_and_the_books_headings() -> None:
    assert {"eq6.38", "E6.3"} <= set(_ids("restitution"))  # titles
    assert "eq3.7" in _ids("König")  # accents either way
    assert "eq3.7" in _ids("konig")
    # Example 4.4 names no pendulum; it stands in 4.3.1 "The Physical Pendulum"
    assert "E4.4" in _ids("physical pendulum")


def test_words_must_all_match() -> None:
    assert "eq6.38" not in _ids("restitution pendulum")
    assert _ids("xyzzy") == []


def test_an_unknown_topic_suggests_the_nearest_names(capsys) -> None:
    assert "parallel" in topics.nearest("paralel")
    assert main(["explain", "paralel"]) == 2
    err = capsys.readouterr().err
    assert "unknown id or topic 'paralel'" in err
    assert "nearest: parallel" in err


def test_search_prints_every_match_and_explain_one(capsys) -> None:
    assert main(["search", "poinsot", "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)
    assert [r["id"] for r in rows][:1] == ["eq5.90"]
    assert main(["explain", "centre of percussion"]) == 0  # two checks: listed
    out = capsys.readouterr().out
    assert "2 checks match" in out
    assert "thm.centre-of-percussion" in out
    assert main(["explain", "poinsot"]) == 0  # one check: explained
    assert capsys.readouterr().out.startswith("eq5.90: The inertia ellipsoid")
