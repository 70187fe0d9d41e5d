"""Many bodies (issue 27, item 3): an ``impact`` effect naming a ``group`` of bodies and
``planes`` makes every pair of them collide; the contact search looks only at the pairs
a broad phase lets through (:meth:`mechanics.scenes.collision.Collision.near`), and the
exact free flight keeps each pair's next contact time between events
(:class:`mechanics.scenes.flows.Calendar`).

Expected values are closed forms derived here: two equal elastic spheres meeting head
on exchange their velocities at t = (d − 2a)/(2v); a ball crossing a box of width W
bounces off its walls every (W − 2a)/|v|.  The group is checked against the same pairs
listed one by one (bit for bit), the broad phase and the calendar against the search
without them (bit for bit), and the exact flow against the integrated run (an
independent route: closed-form contact times against the dense output's root search).
"""

from __future__ import annotations

import dataclasses
import functools
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mechanics._floats import EPS
from mechanics.scenes import SceneError, run_scene
from mechanics.scenes import collision as collision_module
from mechanics.scenes import flows as flows_module

from ._effects import WALLS
from .builders import ball, scene

#: a contact time or velocity in closed form: a quotient of sums of a few O(1) terms
CLOSED_RTOL = 16 * EPS
#: event times of the exact flow against the integrated run: DOP853 at rtol 1e-12, the
#: contact refined to 4 eps of its step (as the engine tests' EVENT_RTOL)
EVENT_RTOL = 2**20 * EPS


_ball = functools.partial(ball, radius=0.05)
_scene = functools.partial(scene, name="group", duration=1.0, samples=21, method="auto")


def _group(names, planes=WALLS, e=1.0, **kw):
    out = {"type": "impact", "group": list(names), "restitution": e, **kw}
    return out if planes is None else out | {"planes": planes}


def _balls_in_box(n, rng, radius=0.05):
    """n balls on a grid of the unit box (no overlap), random velocities."""
    k = math.ceil(n ** (1 / 3))
    h = 1.0 / k
    cells = [(i, j, m) for i in range(k) for j in range(k) for m in range(k)][:n]
    out = []
    for c, cell in enumerate(cells):
        jitter = rng.uniform(-1, 1, 3) * (h / 2 - radius) * 0.5
        p = (np.array(cell) + 0.5) * h + jitter
        out.append(_ball(f"b{c}", p, rng.normal(size=3), radius=radius))
    return out


# ------------------------------------------------------------------ closed forms


def test_two_equal_elastic_spheres_of_a_group_exchange_velocities_head_on() -> None:
    a, d, v = 0.05, 0.6, 1.5
    bodies = [_ball("p", (0.2, 0.5, 0.5), (v, 0, 0)), _ball("q", (0.2 + d, 0.5, 0.5), (-v, 0, 0))]
    res = run_scene(_scene(bodies, [_group(["p", "q"], planes=None)], duration=0.5))
    assert res.passed, res.summary()
    (ev,) = [e for e in res.trajectory.events if e.kind == "impact"]
    assert ev.detail["bodies"] == ["p", "q"]
    assert ev.t == pytest.approx((d - 2 * a) / (2 * v), rel=CLOSED_RTOL)
    s = res.trajectory.state_at(0.5)
    np.testing.assert_allclose([s["p.vx"], s["q.vx"]], [-v, v], rtol=CLOSED_RTOL)


def test_a_ball_crossing_the_box_bounces_off_each_wall_on_the_clock() -> None:
    a, v, x0 = 0.05, 2.0, 0.3
    bodies = [_ball("b", (x0, 0.5, 0.5), (v, 0, 0))]
    res = run_scene(_scene(bodies, [_group(["b"])], duration=1.0))
    assert res.passed, res.summary()
    hits = [e for e in res.trajectory.events if e.kind == "impact"]
    first = (1.0 - a - x0) / v
    period = (1.0 - 2 * a) / v
    expected = [first + k * period for k in range(4) if first + k * period <= 1.0]
    assert [e.t for e in hits] == pytest.approx(expected, rel=CLOSED_RTOL)
    # it meets the far wall (planes[1]) first, then the near one (planes[0]), in turn
    assert [e.detail["feature"].split(" and ")[1] for e in hits] == [
        f"effects[0].planes[{1 - k % 2}]" for k in range(len(hits))
    ]


# ------------------------------------------------------ the group is its pairs


def test_a_group_runs_bit_for_bit_as_its_pairs_listed_one_by_one() -> None:
    rng = np.random.default_rng(7)
    bodies = _balls_in_box(8, rng)
    names = [b["name"] for b in bodies]
    grouped = _scene(bodies, [_group(names, e=0.9)], duration=0.6)
    law = {"type": "impact", "restitution": 0.9}
    pairs = [{**law, "body": x, "other": y} for k, x in enumerate(names) for y in names[k + 1 :]]
    walls = [
        {**law, "body": x, "plane_point": pl["point"], "plane_normal": pl["normal"]}
        for x in names
        for pl in WALLS
    ]
    listed = _scene(bodies, pairs + walls, duration=0.6)
    for method in ("exact", "integrate"):
        r1 = run_scene(dataclasses.replace(grouped, method=method))
        r2 = run_scene(dataclasses.replace(listed, method=method))
        assert r1.passed, r1.summary()
        assert r2.passed, r2.summary()
        e1 = [(e.t, e.detail.get("bodies", e.detail.get("body"))) for e in r1.trajectory.events]
        e2 = [(e.t, e.detail.get("bodies", e.detail.get("body"))) for e in r2.trajectory.events]
        assert e1 == e2
        assert len(e1) > 10  # the scene is busy: walls and pairs both hit
        assert r1.trajectory.state_at(0.6) == r2.trajectory.state_at(0.6)


def test_fixed_bodies_of_a_group_meet_the_others_only() -> None:
    bodies = [
        _ball("post", (0.5, 0.5, 0.5), (0, 0, 0)) | {"fixed": True},
        _ball("post2", (0.8, 0.8, 0.8), (0, 0, 0)) | {"fixed": True},
        _ball("b", (0.2, 0.5, 0.5), (1.0, 0, 0)),
    ]
    res = run_scene(_scene(bodies, [_group(["post", "post2", "b"])], duration=0.5))
    assert res.passed, res.summary()
    labels = {imp.label for imp in _engine(res).impacts}
    assert "bodies 'post' and 'post2'" not in labels  # two fixed bodies never meet
    assert not any(lab.startswith("body 'post") for lab in labels)  # nor a fixed one a wall
    (ev,) = [e for e in res.trajectory.events if e.kind == "impact"]
    assert ev.detail["bodies"] == ["post", "b"]
    assert ev.t == pytest.approx((0.5 - 0.2 - 0.1) / 1.0, rel=CLOSED_RTOL)


def _engine(res):
    from mechanics.scenes.engine import Engine

    return Engine(res.scene)


# ------------------------------------------------ broad phase and calendar


def _without_broad_phase(monkeypatch) -> None:
    def everything(self, fit):
        near, sums = original(self, fit)
        return np.ones_like(near), sums

    original = collision_module.Collision.near
    monkeypatch.setattr(collision_module.Collision, "near", everything)


@settings(max_examples=20, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(2, 7), e=st.sampled_from([1.0, 0.8]))
def test_the_broad_phase_leaves_the_run_unchanged_bit_for_bit(seed, n, e) -> None:
    """Random balls in the box, integrated with and without the broad phase: the same
    events at the same times and the same end state (it only skips pairs that cannot
    touch, so nothing the narrow phase would find is lost)."""
    bodies = _balls_in_box(n, np.random.default_rng(seed))
    sc = _scene(
        bodies, [_group([b["name"] for b in bodies], e=e)], duration=0.3, method="integrate"
    )
    with pytest.MonkeyPatch.context() as mp:
        _without_broad_phase(mp)
        ref = run_scene(sc)
    res = run_scene(sc)
    assert ref.passed, ref.summary()
    assert res.passed, res.summary()
    assert [(ev.t, ev.kind) for ev in res.trajectory.events] == [
        (ev.t, ev.kind) for ev in ref.trajectory.events
    ]
    assert res.trajectory.state_at(0.3) == ref.trajectory.state_at(0.3)


def test_the_broad_phase_skips_pairs_far_apart_and_keeps_those_that_meet() -> None:
    """Its negative control: a pair that does meet on a step is let through, and most
    pairs of a sparse box are left out."""
    from mechanics.scenes.engine import Engine

    bodies = _balls_in_box(27, np.random.default_rng(3))
    eng = Engine(_scene(bodies, [_group([b["name"] for b in bodies])], method="integrate"))
    seen = []
    original = collision_module.Collision.near

    def spy(self, fit):
        near, sums = original(self, fit)
        seen.append(float(near.mean()))
        return near, sums

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(collision_module.Collision, "near", spy)
        res = eng.run()
    assert max(seen) < 0.5  # a sparse box: most of its 513 pairs cannot touch on a step
    hits = [ev for ev in res.events if ev.kind == "impact"]
    assert hits  # and the contacts are still found (checked bit for bit above)


@settings(max_examples=20, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(2, 7))
def test_the_calendar_gives_the_run_of_a_full_search_at_every_event(seed, n) -> None:
    """The exact free flight with its calendar (only the moved bodies' pairs computed
    again) against computing every pair at every event: the same events, the same end."""
    bodies = _balls_in_box(n, np.random.default_rng(seed))
    sc = _scene(bodies, [_group([b["name"] for b in bodies], e=0.9)], duration=0.5, method="exact")
    res = run_scene(sc)
    original = flows_module.Calendar.pairs_of
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(flows_module.Calendar, "pairs_of", lambda self, bodies: None)
        ref = run_scene(sc)
    assert original is flows_module.Calendar.pairs_of
    assert res.passed, res.summary()
    assert [(ev.t, ev.detail.get("feature")) for ev in res.trajectory.events] == [
        (ev.t, ev.detail.get("feature")) for ev in ref.trajectory.events
    ]


@settings(max_examples=10, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(2, 6))
def test_the_exact_flow_of_a_group_agrees_with_its_integration(seed, n) -> None:
    """Closed-form contact times (the calendar) against contacts located on DOP853's
    dense output: the same impacts, at the same times to the integration's accuracy."""
    bodies = _balls_in_box(n, np.random.default_rng(seed))
    sc = _scene(bodies, [_group([b["name"] for b in bodies])], duration=0.3)
    a = run_scene(dataclasses.replace(sc, method="exact"))
    b = run_scene(dataclasses.replace(sc, method="integrate"))
    assert a.passed, a.summary()
    assert b.passed, b.summary()
    ea = [ev for ev in a.trajectory.events if ev.kind == "impact"]
    eb = [ev for ev in b.trajectory.events if ev.kind == "impact"]
    assert [ev.detail["feature"] for ev in ea] == [ev.detail["feature"] for ev in eb]
    for x, y in zip(ea, eb, strict=True):
        assert y.t == pytest.approx(x.t, rel=EVENT_RTOL, abs=EVENT_RTOL)


def test_many_pairs_share_one_interpenetration_check_naming_the_deepest() -> None:
    bodies = _balls_in_box(8, np.random.default_rng(1))
    res = run_scene(_scene(bodies, [_group([b["name"] for b in bodies])], duration=0.2))
    names = [c.name for c in res.self_checks if c.name.startswith("no interpenetration")]
    # 28 pairs and 48 wall contacts: more than MANY_PAIRS, one line
    assert len(names) == 1
    assert names[0].startswith("no interpenetration of 76 pairs (deepest: ")


# ------------------------------------------------------------------ bad input


def _refused(bodies, effect, match, field):
    with pytest.raises(SceneError, match=match) as info:
        _scene(bodies, [effect])
    assert info.value.field == field


BALLS = [_ball("p", (0.2, 0.5, 0.5), (1, 0, 0)), _ball("q", (0.7, 0.5, 0.5), (0, 0, 0))]


@pytest.mark.parametrize(
    ("change", "match", "field"),
    [
        ({"body": "p"}, "a group .* or a single pair", "effects[0].body"),
        ({"plane_normal": [0, 0, 1]}, "a group .* or a single pair", "effects[0].plane_normal"),
        (
            {"group": ["p", "q", "p"]},
            r"'p' is listed twice \(first at group\[0\]\)",
            "effects[0].group[2]",
        ),
        (
            {"group": ["p"], "planes": None},
            "a group of one body .* meets nothing",
            "effects[0].group",
        ),
        ({"group": ["p", "nobody"]}, "unknown body 'nobody'", "effects[0].group[1]"),
    ],
)
def test_a_bad_group_is_refused_naming_the_field(change, match, field) -> None:
    eff = _group(["p", "q"])
    eff.update(change)
    eff = {k: v for k, v in eff.items() if v is not None}
    _refused(BALLS, eff, match, field)


def test_a_group_of_two_boxes_is_refused_naming_them() -> None:
    box = {"shape": "box", "mass": 1.0, "a": 0.1, "b": 0.1, "c": 0.1}
    bodies = [
        {"name": "u", **box, "initial": {"position": [0.2, 0.5, 0.5]}},
        {"name": "w", **box, "initial": {"position": [0.7, 0.5, 0.5]}},
    ]
    _refused(bodies, _group(["u", "w"]), "two polyhedral bodies .*'u'.*'w'", "effects[0].group[1]")


def test_planes_without_a_group_and_an_impact_without_a_body_are_refused() -> None:
    _refused(
        BALLS,
        {"type": "impact", "body": "p", "planes": WALLS, "restitution": 1.0},
        "planes go with a group",
        "effects[0].planes",
    )
    _refused(
        BALLS, {"type": "impact", "restitution": 1.0}, "needs a body or a group", "effects[0].body"
    )


def test_balls_of_a_group_overlapping_at_the_start_are_refused() -> None:
    bodies = [_ball("p", (0.5, 0.5, 0.5), (0, 0, 0)), _ball("q", (0.55, 0.5, 0.5), (0, 0, 0))]
    with pytest.raises(SceneError, match=r"bodies 'p' and 'q' overlap at t = 0"):
        _scene(bodies, [_group(["p", "q"])])


@pytest.mark.parametrize(
    ("effects", "who"),
    [
        (  # the same two bodies, in either order
            [
                {"type": "impact", "body": "p", "other": "q", "restitution": 1.0},
                {"type": "impact", "body": "q", "other": "p", "restitution": 0.5},
            ],
            "bodies 'q' and 'p'",
        ),
        (  # the floor twice, its normal written at another length
            [
                {"type": "impact", "body": "p", "restitution": 1.0},
                {"type": "impact", "body": "p", "restitution": 0.5, "plane_normal": [0, 0, 2]},
            ],
            "body 'p' and the plane",
        ),
        (  # a pair of a group listed again by itself
            [
                _group(["p", "q"], planes=None),
                {"type": "impact", "body": "p", "other": "q", "restitution": 0.5},
            ],
            "bodies 'p' and 'q'",
        ),
        (  # a plane of a group listed again for one of its bodies
            [
                _group(["p", "q"]),
                {"type": "impact", "body": "q", "restitution": 0.5, "plane_normal": [0, 0, 1]},
            ],
            "body 'q' and the plane",
        ),
    ],
)
def test_a_pair_listed_twice_is_refused_naming_both(effects, who) -> None:
    """Which of two laws would act at a contact was undefined (before: the first listed
    took every impact, silently)."""
    with pytest.raises(SceneError, match="already collide by effects\\[0\\]") as info:
        _scene(BALLS, effects)
    assert info.value.field == "effects[1]"
    assert str(info.value).startswith(f"group.toml: effects[1]: {who} already collide")


def test_the_same_body_with_two_parallel_planes_is_not_a_pair_listed_twice() -> None:
    floor = {"type": "impact", "body": "p", "restitution": 1.0}
    ceiling = {**floor, "plane_point": [0, 0, 1], "plane_normal": [0, 0, -1]}
    raised = {**floor, "plane_point": [0, 0, 0.25]}
    for other in (ceiling, raised):  # another plane: another pair, accepted
        sc = _scene(BALLS, [floor, other])
        assert [e.type for e in sc.effects] == ["impact", "impact"]


def test_two_points_are_refused_as_a_pair_and_left_out_of_a_group() -> None:
    """Two points meet only where their paths cross exactly: their gap |r1 − r2| is zero
    there and never negative, so no sign change locates the contact (found by the
    engine's rigid-motion property: an impulse applied 1e-9 of the scene's size early).
    A pair of them is refused; in a group they are left out, like two fixed bodies."""
    pts = [
        _ball("p", (0.2, 0.5, 0.5), (1, 0, 0), shape="point"),
        _ball("q", (0.7, 0.5, 0.5), (0, 0, 0), shape="point"),
    ]
    for b in pts:
        del b["radius"]
    pair = {"type": "impact", "body": "p", "other": "q", "restitution": 1.0}
    with pytest.raises(SceneError, match="two points meet only where their paths cross") as info:
        _scene(pts, [pair])
    assert info.value.field == "effects[0].other"
    ball = _ball("s", (0.5, 0.2, 0.5), (0, 0, 0))
    from mechanics.scenes.model import Model

    model = Model(_scene([*pts, ball], [_group(["p", "q", "s"], planes=None)]))
    assert sorted(imp.label for imp in model.impacts) == [
        "bodies 'p' and 's'",
        "bodies 'q' and 's'",
    ]
