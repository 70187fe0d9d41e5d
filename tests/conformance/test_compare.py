"""The battery on several adapters at once (:mod:`mechanics.conformance.compare`,
``bodycheck conform all``): one row per scenario and adapter, engines that cannot run
named with the reason, a failing reference fails the command."""

from __future__ import annotations

import json

import pytest

from identities.cli.main import main
from mechanics.conformance.adapters import ExactAdapter
from mechanics.conformance.compare import compare, engine_adapters

from .toys import gravity_sign_error


def test_one_row_per_scenario_and_adapter_with_the_worst_figures() -> None:
    c = compare(
        [("reference", ExactAdapter()), ("toy", gravity_sign_error()), ("Absent", "not here")],
        scenarios=["parabola", "rocket"],
    )
    rows = c.rows()
    assert [(r["scenario"], r["family"]) for r in rows] == [
        ("parabola", "reference"),
        ("parabola", "toy"),
        ("rocket", "reference"),
        ("rocket", "toy"),
    ]
    exact, toy = rows[0], rows[1]
    assert exact["status"] == "pass"
    assert exact["error"][1] < 1e-12
    assert toy["status"] == "fail"
    assert toy["error"][1] > 1e-3  # gravity the wrong way: the parabola is far off
    md = c.to_markdown()
    assert md.startswith("| scenario | adapter |")
    assert md.count("\n| ") == len(rows)  # after the header, a line per row
    assert "- Absent: not here" in md
    assert json.loads(c.to_json())["missing"] == [["Absent", "not here"]]


def test_every_engine_variant_or_its_missing_extra_is_listed() -> None:
    families = [f for f, _ in engine_adapters()]
    assert families[:2] == ["reference", "reference"]
    for engine in ("MuJoCo", "PyBullet", "Drake"):
        assert engine in families  # each variant, or once with the extra to install


def test_conform_all_writes_the_table_the_plot_and_the_json(capsys, tmp_path) -> None:
    md, svg, js = tmp_path / "t.md", tmp_path / "t.svg", tmp_path / "t.json"
    files = ["--markdown", str(md), "--plot", str(svg), "--json", str(js)]
    code = main(["conform", "all", "--scenario", "parabola", *files])
    assert code == 0
    out = capsys.readouterr().out
    assert md.read_text(encoding="utf-8").endswith(out)
    assert md.read_text(encoding="utf-8").startswith("# The conformance battery")
    assert "exact (closed forms)" in out
    assert svg.read_text(encoding="utf-8").lstrip().startswith(("<?xml", "<svg"))
    assert {r["scenario"] for r in json.loads(js.read_text(encoding="utf-8"))["rows"]} == {
        "parabola"
    }


def test_conform_all_fails_when_a_reference_fails(capsys, monkeypatch) -> None:
    import mechanics.conformance.compare as cmp

    monkeypatch.setattr(
        cmp, "engine_adapters", lambda: [("reference", gravity_sign_error())], raising=True
    )
    assert main(["conform", "all", "--scenario", "parabola"]) == 1


def test_markdown_is_only_for_all(capsys, tmp_path) -> None:
    assert main(["conform", "exact", "--markdown", str(tmp_path / "x.md")]) == 2
    assert "--markdown is for" in capsys.readouterr().err


@pytest.mark.parametrize("bad", ["all", "exact"])
def test_an_unknown_scenario_is_named_for_every_adapter_name(capsys, bad) -> None:
    assert main(["conform", bad, "--scenario", "nope"]) == 2
    assert "unknown scenario 'nope'" in capsys.readouterr().err
