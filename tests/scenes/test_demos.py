"""The lecture demos: each names a built-in scene and the check that backs it."""

from __future__ import annotations

import json

from identities.book.scenes.demos import LECTURE_DEMOS
from identities.cli.main import main
from identities.verify import catalogue
from mechanics.scenes import builtin_scenes


def test_every_lecture_demo_is_a_built_in_scene_backed_by_a_check() -> None:
    reg, scenes = catalogue.load_all(), builtin_scenes()
    assert {d.name for d in LECTURE_DEMOS} <= set(scenes)
    assert all(d.check in reg for d in LECTURE_DEMOS)
    assert all(reg[d.check].kind == "scene" for d in LECTURE_DEMOS)


def test_the_list_shows_each_demo_with_its_paragraph_and_check(capsys) -> None:
    assert main(["demo", "--list"]) == 0
    out = capsys.readouterr().out
    for d in LECTURE_DEMOS:
        assert f"{d.name}: {d.topic}" in out
        assert d.check in out
    assert main(["demo", "--list", "--json"]) == 0
    rows = json.loads(capsys.readouterr().out)
    assert rows["rocket"]["check"] == "thm.scene-rocket"
    assert "about" not in rows["box_drop"]


def test_a_lecture_demo_says_what_to_watch_before_its_result(capsys) -> None:
    assert main(["demo", "rocket"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("the rocket equation")
    assert "scene rocket: Rocket rising under gravity" in out
