"""``bodycheck scene`` and ``bodycheck demo``: output formats, plots, exit codes."""

from __future__ import annotations

import json

import pytest

from identities.cli.main import main
from mechanics._floats import EPS
from mechanics.scenes import builtin_scenes

#: the drop height is chosen in the scene file for 12 m/s: the exact flow's √(2 g h)
EXACT_RTOL = 64 * EPS


def test_demo_list_names_every_built_in_scene(capsys) -> None:
    assert main(["demo", "--list"]) == 0
    out = capsys.readouterr().out
    for name in builtin_scenes():
        assert name in out
    assert "Example 6.1" in out


def test_demo_list_json(capsys) -> None:
    assert main(["demo", "--list", "--json"]) == 0
    assert set(json.loads(capsys.readouterr().out)) == set(builtin_scenes())


@pytest.mark.parametrize("name", list(builtin_scenes()))
def test_every_demo_runs_from_the_command_line_and_matches_the_book(name, capsys) -> None:
    assert main(["demo", name]) == 0
    out = capsys.readouterr().out
    assert out.rstrip().endswith("PASSED")
    assert "against the book:" in out


def test_scene_json_is_machine_readable(capsys) -> None:
    path = str(builtin_scenes()["bouncing_ball"])
    assert main(["scene", path, "--json"]) == 0
    r = json.loads(capsys.readouterr().out)
    assert r["scene"] == "bouncing_ball"
    assert r["passed"] is True
    assert r["effects"] == ["gravity", "impact"]
    assert r["method"].startswith("exact")
    assert [e["kind"] for e in r["events"]] == ["impact"] * 5
    assert r["events"][0]["normal_speed_before"] == pytest.approx(12.0, rel=EXACT_RTOL)
    comps = {c["name"]: c for c in r["comparisons"]}
    assert comps["e = after/before"]["closed_form"] == pytest.approx(5 / 6)
    assert all(c["ok"] and c["relative_difference"] <= c["tolerance"] for c in comps.values())
    assert {c["name"] for c in r["conserved"]} >= {"E"}
    assert len(r["samples"]["t"]) == len(r["samples"]["z"]) == 801


def test_method_override_integrates(capsys) -> None:
    assert main(["demo", "rocket", "--json", "--method", "integrate"]) == 0
    r = json.loads(capsys.readouterr().out)
    assert r["method"].startswith("integrated")
    assert r["passed"]


@pytest.mark.parametrize("name", ["heavy_top", "free_top_flip", "bouncing_ball", "tank_draining"])
def test_plot_writes_a_png(tmp_path, name, capsys) -> None:
    out = tmp_path / f"{name}.png"
    assert main(["demo", name, "--plot", str(out)]) == 0
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert out.stat().st_size > 10_000
    assert f"plot: {out}" in capsys.readouterr().out


def test_scene_plot_with_json(tmp_path, capsys) -> None:
    out = tmp_path / "p.png"
    path = str(builtin_scenes()["sliding_ball"])
    assert main(["scene", path, "--plot", str(out), "--json"]) == 0
    json.loads(capsys.readouterr().out)
    assert out.exists()


def test_bad_scene_file_is_one_line_with_exit_code_2(tmp_path, capsys) -> None:
    p = tmp_path / "ball.toml"
    p.write_text(
        builtin_scenes()["bouncing_ball"]
        .read_text()
        .replace("restitution = 0.8333333333333334", "restitution = 1.5")
    )
    assert main(["scene", str(p)]) == 2
    out, err = capsys.readouterr()
    assert out == ""
    assert err.count("\n") == 1
    assert str(p) in err
    assert "effects[1].restitution" in err
    assert "must lie in [0, 1]" in err


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["demo", "nonesuch"], "unknown demo 'nonesuch'"),
        (["demo"], "demo needs a NAME or --list"),
        (["scene", "/nonexistent/scene.toml"], "cannot read"),
        (["demo", "rocket", "--method", "magic"], "invalid choice"),
    ],
)
def test_bad_scene_usage_exit_code_2(argv, message, capsys) -> None:
    assert main(argv) == 2
    out, err = capsys.readouterr()
    assert out == ""
    assert err.count("\n") == 1
    assert message in err


def test_a_scene_that_misses_the_book_exits_1(tmp_path, capsys) -> None:
    p = tmp_path / "ball.toml"
    p.write_text(
        builtin_scenes()["bouncing_ball"]
        .read_text()
        .replace("restitution = 0.8333333333333334", "restitution = 0.8")
    )
    assert main(["scene", str(p)]) == 1
    assert "FAILED" in capsys.readouterr().out


_ROD = """[scene]
name = "leaning_rod"
duration = 0.05

[[bodies]]
name = "rod"
shape = "rod"
mass = 1.0
length = 1.0
initial = {{ position = [0.0, 0.0, 0.3535533905932738], theta = 0.7853981633974483, velocity = [0.0, {slide}, 0.0] }}

[[effects]]
type = "gravity"
g = 9.81

[[effects]]
type = "impact"
body = "rod"
restitution = 0.0
friction = 2.0
"""


def test_a_rest_that_cannot_be_resolved_is_one_line_with_exit_code_2(tmp_path, capsys) -> None:
    """Painlevé's paradox (the rod of tests/scenes/test_resting.py, its end slipping
    with μ = 2 ≥ 5/3): one line naming the file, the impact, the pair, the time and
    the reason; nothing printed on stdout (nothing half-run)."""
    p = tmp_path / "rod.toml"
    p.write_text(_ROD.format(slide=1.0))
    assert main(["scene", str(p)]) == 2
    out, err = capsys.readouterr()
    assert out == ""
    assert err.count("\n") == 1
    assert f"{p}: effects[1]: body 'rod' and the plane come to rest at t = 0 s" in err
    assert "Painlevé's paradox" in err
    # the other way, no paradox: the rod rests on its end and the run passes
    p.write_text(_ROD.format(slide=-1.0))
    assert main(["scene", str(p)]) == 0
    assert "PASSED" in capsys.readouterr().out
