"""A scene's run as a page that plays it (issue 31, item 2:
``identities/cli/scene_player.py``, ``bodycheck scene|demo ... --html OUT.html``, the
site's scenes page).  Pure Python here; tests/test_site.py opens the pages in Chromium.
"""

from __future__ import annotations

import json
import re

import numpy as np
import pytest

from identities.book.scenes.compare import load_book_scene, run_book_scene
from identities.cli.main import main as cli
from identities.cli.scene_player import MAX_FRAMES, player_data, player_page
from mechanics._floats import EPS
from mechanics.scenes import builtin_scenes

#: a projected coordinate is a few products of O(1) numbers and one affine map, rounded
#: to 0.01 of an SVG unit on output: the rounding bounds the residual of a linear fit
SVG_ROUNDING = 0.01


def _run(name: str):
    return run_book_scene(load_book_scene(builtin_scenes()[name]))


@pytest.fixture(scope="module")
def ball():
    return _run("bouncing_ball")


def test_a_ball_moving_along_z_is_drawn_on_one_vertical_line_of_the_screen(ball):
    """The bouncing ball moves along the space z axis only: its outline's centre moves
    on one line of the drawing, up as z rises (SVG's y points down), affinely in z,
    and its radius is the same on every frame (an orthographic view keeps lengths)."""
    data = player_data(ball)
    snap = ball.trajectory.snapshot
    t = np.asarray(ball.trajectory.t)
    z = np.asarray(snap.r)[:, 0, 2]
    shown = np.searchsorted(t, data["t"])
    circles = np.array([f[0]["c"] for f in data["frames"]])
    assert len(data["frames"]) <= MAX_FRAMES
    assert data["t"][0] == t[0]
    assert data["t"][-1] == t[-1]
    x, y, r = circles.T
    assert np.ptp(x) <= SVG_ROUNDING
    assert np.ptp(r) <= SVG_ROUNDING
    slope, cut = np.polyfit(z[shown], y, 1)
    assert slope < 0
    assert np.abs(y - (slope * z[shown] + cut)).max() <= 2 * SVG_ROUNDING
    # its events on the timeline: the run's impacts, at their times
    assert [e["t"] for e in data["events"]] == [e.t for e in ball.trajectory.events]


def test_a_box_is_drawn_as_its_twelve_edges_and_a_floor_it_strikes():
    data = player_data(_run("box_drop"))
    first = data["frames"][0]
    points = sum(len(s["p"]) // 2 for s in first)
    assert len(first) == 6  # two loops of five points, four edges of two
    assert points == 2 * 5 + 4 * 2
    assert len(data["planes"]) == 1
    assert len(data["planes"][0]) == 8  # a quadrilateral


def test_a_run_that_does_not_fit_in_the_frames_is_shown_evenly():
    result = _run("free_top_flip")
    tr, data = result.trajectory, player_data(result)
    assert len(tr.t) > MAX_FRAMES
    assert len(data["t"]) == MAX_FRAMES
    gaps = np.diff(data["t"])
    # the gaps differ by one sample at most (differences of times, each rounded
    # relative to the run's length)
    assert np.ptp(gaps) <= (tr.t[1] - tr.t[0]) + 2**4 * EPS * tr.t[-1]


def test_the_page_holds_its_data_script_and_tables(ball):
    page = player_page(ball)
    assert page.startswith("<!DOCTYPE html>")
    data = re.search(r"<script type='application/json' class='scene-data'>(.*?)</script>", page)
    assert data is not None
    assert json.loads(data.group(1)) == json.loads(json.dumps(player_data(ball)))
    assert "function setup(root)" in page  # the player's script, inline
    assert "<table class='invariants'>" in page
    assert "E</td>" in page


def test_demo_and_scene_write_the_page_and_refuse_a_path_they_cannot_write(tmp_path, capsys):
    out = tmp_path / "box.html"
    assert cli(["demo", "box_drop", "--html", str(out)]) == 0
    assert f"page: {out}" in capsys.readouterr().out
    assert "class='scene-data'" in out.read_text("utf-8")
    scene = builtin_scenes()["rod_struck"]
    assert cli(["scene", str(scene), "--html", str(tmp_path / "rod.html")]) == 0
    assert (tmp_path / "rod.html").is_file()
    assert cli(["demo", "box_drop", "--html", str(tmp_path / "missing" / "x.html")]) == 2
    err = capsys.readouterr().err
    assert f"--html {tmp_path / 'missing' / 'x.html'}: cannot write the page" in err
