"""The battery on several adapters at once (:mod:`mechanics.conformance.compare`,
``bodycheck conform all``): one row per scenario and adapter, engines that cannot run
named with the reason, a failing reference fails the command."""

from __future__ import annotations

import json

import pytest

from identities.cli.main import main
from mechanics.conformance.adapters import ExactAdapter
from mechanics.conformance.battery import Figure, Report, Run, ScenarioResult
from mechanics.conformance.compare import Comparison, compare, engine_adapters

from .toys import Crashes, gravity_sign_error


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
    for engine in ("MuJoCo", "PyBullet", "Drake", "Siconos", "DART"):
        assert engine in families  # each variant, or once with the extra to install


def test_conform_all_writes_the_table_the_plot_and_the_json(capsys, tmp_path, monkeypatch) -> None:
    """``conform all`` prints the table and writes it, the grid plot and the JSON, with
    exit code 0 while the references pass, whatever the engines do.

    The adapters are one of each kind of row the writers handle: a reference that passes
    (the closed forms), an engine that fails, one that raises (its reason under "Not
    run:"), one not installed.  The installed engines (20 variants: their imports,
    Siconos's interpreter per run, three timings of each finest run) and the integrated
    engine (its compiled kernels' first load) take 6 to 24 s, and no assertion reads
    their rows (an engine that raises is a row like "Mine"'s): the engines' adapters are
    checked against exact motions in their own tests (test_engines.py, test_siconos.py,
    test_dart.py), the integrated engine's battery at the exact profile in
    test_thresholds.py, and the list ``conform all`` takes by
    test_every_engine_variant_or_its_missing_extra_is_listed."""
    import mechanics.conformance.compare as cmp

    adapters = [
        ("reference", ExactAdapter()),
        ("Toy", gravity_sign_error()),
        ("Mine", Crashes(["parabola"])),
        ("DART", "pip install 'bodycheck[dart]'"),
    ]
    monkeypatch.setattr(cmp, "engine_adapters", lambda: adapters, raising=True)
    md, svg, js = tmp_path / "t.md", tmp_path / "t.svg", tmp_path / "t.json"
    files = ["--markdown", str(md), "--plot", str(svg), "--json", str(js)]
    code = main(["conform", "all", "--scenario", "parabola", *files])
    assert code == 0
    out = capsys.readouterr().out
    assert md.read_text(encoding="utf-8").endswith(out)
    assert md.read_text(encoding="utf-8").startswith("# The conformance battery")
    assert "exact (closed forms)" in out
    assert "- DART: pip install 'bodycheck[dart]'" in out
    assert "- crashes raised an error in parabola: run raised RuntimeError: boom in parabola" in out
    assert svg.read_text(encoding="utf-8").lstrip().startswith(("<?xml", "<svg"))
    data = json.loads(js.read_text(encoding="utf-8"))
    assert {r["scenario"] for r in data["rows"]} == {"parabola"}
    assert [(r["family"], r["status"]) for r in data["rows"]] == [
        ("reference", "pass"),
        ("Toy", "fail"),
        ("Mine", "error"),
    ]
    assert data["missing"] == [["DART", "pip install 'bodycheck[dart]'"]]


def test_conform_all_fails_when_a_reference_fails(capsys, monkeypatch) -> None:
    import mechanics.conformance.compare as cmp

    monkeypatch.setattr(
        cmp, "engine_adapters", lambda: [("reference", gravity_sign_error())], raising=True
    )
    assert main(["conform", "all", "--scenario", "parabola"]) == 1


def test_markdown_writes_one_adapters_printed_table_too(capsys, tmp_path) -> None:
    md = tmp_path / "x.md"
    assert main(["conform", "exact", "--scenario", "parabola", "--markdown", str(md)]) == 0
    printed = capsys.readouterr().out
    assert printed.startswith("# Conformance: exact (closed forms)")
    assert md.read_text(encoding="utf-8") == printed


@pytest.mark.parametrize("bad", ["all", "exact"])
def test_an_unknown_scenario_is_named_for_every_adapter_name(capsys, bad) -> None:
    assert main(["conform", bad, "--scenario", "nope"]) == 2
    assert "unknown scenario 'nope'" in capsys.readouterr().err


# -- the table's exact text, from a comparison built by hand (no engine runs) ---------
#
# docs/conformance-engines.md shows the format: a row per (scenario, adapter), the
# scenario named on its first row only; the worst error and drift as "value (name)" at two
# significant digits, the order at two decimals, the wall time of the finest run at two
# significant digits, a blank cell where there is none; "unsupported" shown as "cannot
# express"; then "Not run:" with the engines that are not installed and, grouped by
# (scenario, status, message), the adapters that cannot express or raised in a scenario.

BOUND = 2.0**-10  # a checked figure's threshold in these hand-built results


def _result(scenario, status, message="", figures=(), runs=()):
    return ScenarioResult(scenario, "", "", status, message, list(figures), list(runs))


def _hand_built(missing=(("Drake", "pip install 'bodycheck[drake]'"),)) -> Comparison:
    exact = Report(
        "exact",
        [
            _result(
                "parabola",
                "pass",
                figures=[
                    # checked figures are ranked by value / threshold: position's 3e-13
                    # of 2^-10 beats velocity's 1e-12 of 1 and the unchecked apex
                    Figure("position", "error", 3e-13, BOUND, True),
                    Figure("velocity", "error", 1e-12, 1.0, True),
                    Figure("apex_height", "error", 5e-10, None, None),
                    Figure("omega", "error", None, BOUND, None),  # not measured: skipped
                    Figure("E_drift", "drift", 1.5e-15, BOUND, True),
                    Figure("p_drift", "drift", 2e-15, None, None),
                    Figure("order", "order", 3.996, None, None),
                ],
                runs=[Run(0.1, 0.5, 1e-3), Run(0.05, 0.0123, 1e-4)],
            ),
            _result("rocket", "unsupported", "constant masses"),
        ],
        {},
    )
    toy = Report(
        "toy",
        [
            _result(
                "parabola",
                "fail",
                "position 0.5 violates threshold <= 0.000977",
                figures=[
                    Figure("position", "error", 0.5, BOUND, False),
                    # only unchecked drifts: the largest value is the worst
                    Figure("p_drift", "drift", 0.125, None, None),
                    Figure("L_drift", "drift", 0.25, None, None),
                ],
                runs=[Run(None, 1.5, 0.5)],
            ),
            _result("rocket", "unsupported", "constant masses"),
        ],
        {},
    )
    mine = Report(
        "mine",
        [
            _result("parabola", "error", "run raised RuntimeError: boom"),
            _result("rocket", "error", ""),  # no message: nothing to list under "Not run:"
        ],
        {},
    )
    return Comparison([("reference", exact), ("Toy", toy), ("Mine", mine)], list(missing))


HAND_BUILT_MARKDOWN = """\
| scenario | adapter | status | worst error | worst drift | order | wall time (s) |
|---|---|---|---|---|---|---|
| parabola | exact | pass | 3e-13 (position) | 1.5e-15 (E_drift) | 4.00 | 0.012 |
|  | toy | fail | 0.5 (position) | 0.25 (L_drift) |  | 1.5 |
|  | mine | error |  |  |  |  |
| rocket | exact | cannot express |  |  |  |  |
|  | toy | cannot express |  |  |  |  |
|  | mine | error |  |  |  |  |

Not run:

- Drake: pip install 'bodycheck[drake]'
- mine raised an error in parabola: run raised RuntimeError: boom
- exact, toy cannot express rocket: constant masses
"""


def test_markdown_of_a_hand_built_comparison_is_the_documented_table() -> None:
    assert _hand_built().to_markdown() == HAND_BUILT_MARKDOWN


def test_markdown_lists_not_run_only_when_something_did_not_run() -> None:
    passed = Report("exact", [_result("parabola", "pass", runs=[Run(None, 2.0, 0.0)])], {})
    table = (
        "| scenario | adapter | status | worst error | worst drift | order | wall time (s) |\n"
        "|---|---|---|---|---|---|---|\n"
        "| parabola | exact | pass |  |  |  | 2 |\n"
    )
    assert Comparison([("reference", passed)]).to_markdown() == table
    # an engine missing alone is enough for the section
    alone = Comparison([("reference", passed)], [("MuJoCo", "no mujoco")]).to_markdown()
    assert alone == table + "\nNot run:\n\n- MuJoCo: no mujoco\n"
    # so is an unsupported scenario alone
    unsupported = Report("u", [_result("parabola", "unsupported", "no gravity")], {})
    assert (
        Comparison([("U", unsupported)])
        .to_markdown()
        .endswith(
            "| parabola | u | cannot express |  |  |  |  |\n\nNot run:\n\n"
            "- u cannot express parabola: no gravity\n"
        )
    )


def test_an_empty_comparison_has_no_rows_and_only_the_header() -> None:
    c = Comparison([])
    assert c.rows() == []
    assert c.to_markdown() == (
        "| scenario | adapter | status | worst error | worst drift | order | wall time (s) |\n"
        "|---|---|---|---|---|---|---|\n"
    )
    assert c.to_json() == '{\n "rows": [],\n "missing": []\n}'


def test_json_of_a_hand_built_comparison_carries_every_cell_and_only_the_reasons() -> None:
    text = _hand_built().to_json()
    # one-space indentation, keys in the documented order
    assert text.startswith('{\n "rows": [\n  {\n   "scenario": "parabola",\n   "family": ')
    assert text.endswith(
        ' "missing": [\n  [\n   "Drake",\n   "pip install \'bodycheck[drake]\'"\n  ]\n ]\n}'
    )
    data = json.loads(text)
    assert data["missing"] == [["Drake", "pip install 'bodycheck[drake]'"]]
    cells = ("scenario", "family", "adapter", "status", "error", "drift", "order")
    assert [tuple(r[k] for k in cells) for r in data["rows"]] == [
        (
            "parabola",
            "reference",
            "exact",
            "pass",
            ["position", 3e-13],
            ["E_drift", 1.5e-15],
            3.996,
        ),
        ("parabola", "Toy", "toy", "fail", ["position", 0.5], ["L_drift", 0.25], None),
        ("parabola", "Mine", "mine", "error", None, None, None),
        ("rocket", "reference", "exact", "unsupported", None, None, None),
        ("rocket", "Toy", "toy", "unsupported", None, None, None),
        ("rocket", "Mine", "mine", "error", None, None, None),
    ]
    # the finest run's wall time, None where nothing ran
    assert [r["wall_time"] for r in data["rows"]] == [0.0123, 1.5, None, None, None, None]
    # a reason only for what did not run: a failure's figures are in its cells already
    assert [r["message"] for r in data["rows"]] == [
        "",
        "",
        "run raised RuntimeError: boom",
        "constant masses",
        "constant masses",
        "",
    ]
    keys = ["scenario", "family", "adapter", "status", "error", "drift", "unmeasured", "order"]
    assert [list(r) for r in data["rows"]] == [[*keys, "wall_time", "message"]] * 6
    assert [r["unmeasured"] for r in data["rows"]] == [0] * 6


#: the adapter modules of ENGINE_MODULES, written out
ENGINES = ("mujoco", "pybullet", "drake", "siconos", "dart")


def test_engine_adapters_list_each_variant_or_the_missing_engines_reason_once(
    monkeypatch,
) -> None:
    import importlib

    from mechanics.conformance.adapters import MissingExtraError, SceneEngineAdapter

    def missing(extra):
        def variants():
            raise MissingExtraError(f"pip install 'bodycheck[{extra}]'")

        return variants

    mods = {m: importlib.import_module(f"mechanics.conformance.adapters.{m}") for m in ENGINES}
    monkeypatch.setattr(mods["mujoco"], "variants", lambda: ["mj-a", "mj-b"])
    monkeypatch.setattr(mods["pybullet"], "variants", missing("pybullet"))
    monkeypatch.setattr(mods["drake"], "variants", lambda: ["dk"])
    monkeypatch.setattr(mods["siconos"], "variants", missing("siconos"))
    monkeypatch.setattr(mods["dart"], "variants", lambda: ["dart-a"])
    got = engine_adapters()
    assert [type(a) for _, a in got[:2]] == [ExactAdapter, SceneEngineAdapter]
    assert got[2:] == [
        ("MuJoCo", "mj-a"),
        ("MuJoCo", "mj-b"),
        ("PyBullet", "pip install 'bodycheck[pybullet]'"),
        ("Drake", "dk"),
        ("Siconos", "pip install 'bodycheck[siconos]'"),
        ("DART", "dart-a"),
    ]
    # compare() runs no battery for a reason: it lists the engine as not run
    c = compare([("PyBullet", "pip install 'bodycheck[pybullet]'")], scenarios=["parabola"])
    assert c.reports == []
    assert c.missing == [("PyBullet", "pip install 'bodycheck[pybullet]'")]
