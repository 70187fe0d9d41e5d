"""Properties of the scene engine itself (issue 27, item 4), over random scenes built
from random bodies (points, spheres, boxes), effects (gravity, springs between bodies
or to the ground, impacts with the floor and between bodies; a box strikes bodies, not
the floor: see :func:`scenes`) and initial states:

- a rigid motion of the whole scene (rotation Q and translation b, gravity, planes and
  anchors included) moves the result by the same motion;
- a Galilean boost (no gravity, no planes, no ground anchors) adds the boost;
- listing the bodies and the effects in another order changes nothing;
- a conservative scene (e = 1, no damping; impacts of spheres and points with the
  floor only, see :func:`scenes`) run to its end and back returns to its start;
- a scene reflected in a plane gives the reflected result, and the flat box moving in
  its plane of symmetry stays symmetric.

The bound, derived: DOP853 at rtol = atol = 1e-12 keeps each step's local error below
1e-12 of the state; over a run of ≲ 10³ steps the two runs compared (each within its own
tolerance of the exact motion, their step sequences differing by rounding) differ by at
most ~2 × 10³ × 1e-12 relative, and an impact passes a difference δ in its contact time
on as v δ (times the impulse's condition, O(1) for a sphere, up to ~10 for a box's
corner). So 2^28 eps ≈ 6e-8 of the scene's size (its largest |position| and |velocity|
times the duration) bounds them, with the steps' count and the impacts' gain of ~10
each inside it. A scene the engine refuses (a rest it cannot treat, a box landing on an
edge) is no counterexample: both runs must then refuse it.
"""

from __future__ import annotations

import re

import numpy as np
import pytest
from hypothesis import assume, event, example, given, settings
from hypothesis import strategies as st

from mechanics._floats import EPS
from mechanics.rotation import euler_from_matrix, matrix_from_euler, nearest_rotation
from mechanics.scenes import SceneError, parse_scene, run_scene

#: see the module docstring
PROPERTY_RTOL = 2**28 * EPS
#: 1000 examples under the explore profile, a smoke run of 20 otherwise (each example
#: runs two scenes)
EXAMPLES = 1000 if settings.default.max_examples >= 1000 else 20
DURATION = 0.5

_u = st.floats


def _vec(lo, hi):
    return st.lists(_u(lo, hi), min_size=3, max_size=3)


@st.composite
def scenes(draw, *, ground=True, conservative=False, well_posed=False, boxes_on_planes=False):
    """A random scene as a dict (see the module docstring); ``ground``: gravity, the
    floor and ground anchors may appear; ``well_posed``: impacts only of spheres and
    points with the floor.  Impacts of two convex bodies disperse (Sinai's billiard):
    each multiplies a difference of the states by a factor above 1, so a run and its
    reverse part by more than any bound in eps over a chain of them (measured: six
    impacts of a ball with a spinning box's corners in 0.09 s parted them by 5e-7);
    impacts with a plane do not disperse.  ``boxes_on_planes``: a box may strike the
    floor.  Off by default: a box can meet a plane with two corners within rounding of
    each other, and whether they are then one impact problem (simultaneous) or two
    (sequential) is decided by that rounding; the two models move the box differently,
    so a rigid motion of the scene (which changes only the rounding) can change the
    events (found by the rigid-motion property: a box bouncing with e = 0.5 took 11
    more events moved than not).  A discontinuity of the contact model, left open in
    issue 27's note."""
    n = draw(st.integers(1, 3))
    bodies = []
    for k in range(n):
        shape = draw(st.sampled_from(["point", "solid_sphere", "box"]))
        b = {"name": f"b{k}", "shape": shape, "mass": draw(_u(0.5, 2.0))}
        initial = {
            "position": [1.0 * k, draw(_u(-0.2, 0.2)), draw(_u(0.6, 1.0))],
            "velocity": draw(_vec(-1.0, 1.0)),
        }
        if shape == "solid_sphere":
            b["radius"] = 0.1
        if shape == "box":
            b.update(a=draw(_u(0.1, 0.3)), b=draw(_u(0.1, 0.3)), c=draw(_u(0.1, 0.3)))
            for key in ("psi", "theta", "phi"):
                initial[key] = draw(_u(0.1, 3.0))
        if shape != "point":
            initial["omega"] = draw(_vec(-2.0, 2.0))
        b["initial"] = initial
        bodies.append(b)
    effects = []
    if ground and draw(st.booleans()):
        effects.append({"type": "gravity", "g": draw(_u(1.0, 10.0))})
    names = [b["name"] for b in bodies]
    shapes = {b["name"]: b["shape"] for b in bodies}
    for k, x in enumerate(names):
        for y in names[k + 1 :]:
            if draw(st.booleans()):
                effects.append(
                    {
                        "type": "spring",
                        "body": x,
                        "other": y,
                        "stiffness": draw(_u(1.0, 20.0)),
                        "rest_length": 1.0,
                    }
                )
            # (two boxes' contacts are not modelled)
            if {shapes[x], shapes[y]} != {"box"} and not well_posed:
                effects.append(
                    {"type": "impact", "body": x, "other": y, "restitution": _e(draw, conservative)}
                )
        if ground and draw(st.booleans()):
            effects.append(
                {"type": "spring", "body": x, "anchor": draw(_vec(-1.0, 1.0)), "stiffness": 5.0}
            )
        box_ok = boxes_on_planes and not well_posed
        if ground and draw(st.booleans()) and (shapes[x] != "box" or box_ok):
            effects.append({"type": "impact", "body": x, "restitution": _e(draw, conservative)})
    return {
        "scene": {"name": "prop", "duration": DURATION, "samples": 11},
        "bodies": bodies,
        "effects": effects,
    }


def _e(draw, conservative):
    return 1.0 if conservative else draw(st.sampled_from([1.0, 0.5]))


def _run(data):
    """The run's result, or the refusal's reason (a scene the engine cannot treat)."""
    try:
        res = run_scene(parse_scene(data, source="prop.toml"))
    except SceneError as exc:
        event("refused")
        return exc.reason
    event(res.method.split(":")[0])
    return res


def _end(res):
    """Per body name: position, velocity, attitude R_A_O and body ω at the end."""
    s = res.trajectory.snapshot
    out = {}
    for i, b in enumerate(res.scene.bodies):
        turns = b.shape != "point"  # (a point has no attitude: none to compare)
        out[b.name] = (s.r[-1, i], s.v[-1, i], *((s.R[-1, i], s.omega[-1, i]) if turns else ()))
    return out


def _size(res) -> float:
    s = res.trajectory.snapshot
    return float(np.max(np.abs(s.r)) + DURATION * np.max(np.abs(s.v)) + 1.0)


def _impacts(res):
    return [
        (ev.t, ev.detail.get("feature", ""))
        for ev in res.trajectory.events
        if ev.kind in ("impact", "rest", "lift_off")
    ]


def _same(a, b, moved=lambda x: x, relabel=lambda f: f):
    """Both refused for the same reason, or both ran, passed and end alike (b's end
    against ``moved`` of a's: (r, v, R, ω) → the same quantities moved; b's events'
    features against ``relabel`` of a's)."""
    if isinstance(a, str) or isinstance(b, str):  # refused alike (the times it names
        assert _words(a) == _words(b)  # may differ by rounding)
        return
    assert a.passed, a.summary()
    assert b.passed, b.summary()
    tol = PROPERTY_RTOL * _size(a)
    ia, ib = _impacts(a), _impacts(b)
    assert [relabel(f) for _, f in ia] == [f for _, f in ib]
    for (ta, _), (tb, _) in zip(ia, ib, strict=True):
        assert tb == pytest.approx(ta, abs=tol)
    ea, eb = _end(a), _end(b)
    for name, qa in ea.items():
        for x, y in zip(moved(qa), eb[name], strict=True):
            np.testing.assert_allclose(y, x, rtol=0, atol=tol)


def _words(x) -> str:
    """A refusal's reason without its numbers (or the result's type)."""
    return re.sub(r"[-+]?\d[\d.e+-]*", "#", x) if isinstance(x, str) else type(x).__name__


def _rotation(q) -> np.ndarray:
    """The rotation of the unit quaternion q (w, x, y, z)."""
    w, x, y, z = q / np.linalg.norm(q)
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )


def _moved_scene(data, Q, b):
    """The scene moved rigidly: x → Q x + b for points, Q v for directions; a body's
    attitude R_A_O → R Qᵀ (its body components unchanged), so ω (body) is unchanged."""
    out = {"scene": data["scene"], "bodies": [], "effects": []}
    for body in data["bodies"]:
        body = dict(body)
        ini = dict(body["initial"])
        ini["position"] = (Q @ ini["position"] + b).tolist()
        ini["velocity"] = (Q @ ini["velocity"]).tolist()
        if body["shape"] != "point":
            R = matrix_from_euler(*(ini.get(k, 0.0) for k in ("psi", "theta", "phi"))) @ Q.T
            ini.update(zip(("psi", "theta", "phi"), map(float, euler_from_matrix(R)), strict=True))
        body["initial"] = ini
        out["bodies"].append(body)
    for e in data["effects"]:
        e = dict(e)
        if e["type"] == "gravity":
            e["direction"] = (Q @ [0.0, 0.0, -1.0]).tolist()
        if "anchor" in e:
            e["anchor"] = (Q @ e["anchor"] + b).tolist()
        if e["type"] == "impact" and "other" not in e:
            e["plane_point"] = b.tolist()
            e["plane_normal"] = (Q @ [0.0, 0.0, 1.0]).tolist()
        out["effects"].append(e)
    return out


def _mirrored_scene(data, m):
    """The scene reflected in the plane through the origin with unit normal m:
    P = I − 2 m mᵀ on points and directions (gravity, anchors, the floor).  A body's
    axes (the rows of R_A_O) reflect to a left-handed triad: its first axis is taken
    reversed, R_A_O → D R P with D = diag(−1, 1, 1), the same box or sphere (both are
    symmetric in their own axes).  ω is an axial vector: in space ω → −P ω, so in body
    components ω → D R P (−P ω_O) = −D ω_A = diag(1, −1, −1) ω_A."""
    P = np.eye(3) - 2.0 * np.outer(m, m)
    D = np.diag([-1.0, 1.0, 1.0])
    out = {"scene": data["scene"], "bodies": [], "effects": []}
    for body in data["bodies"]:
        ini = dict(body["initial"])
        ini["position"] = (P @ ini["position"]).tolist()
        ini["velocity"] = (P @ ini["velocity"]).tolist()
        if body["shape"] != "point":
            R = D @ matrix_from_euler(*(ini.get(k, 0.0) for k in ("psi", "theta", "phi"))) @ P
            ini.update(zip(("psi", "theta", "phi"), map(float, euler_from_matrix(R)), strict=True))
            ini["omega"] = (-D @ ini.get("omega", [0.0, 0.0, 0.0])).tolist()
        out["bodies"].append({**body, "initial": ini})
    for e in data["effects"]:
        e = dict(e)
        if e["type"] == "gravity":
            e["direction"] = (P @ [0.0, 0.0, -1.0]).tolist()
        if "anchor" in e:
            e["anchor"] = (P @ e["anchor"]).tolist()
        if e["type"] == "impact" and "other" not in e:
            e["plane_point"] = [0.0, 0.0, 0.0]
            e["plane_normal"] = (P @ [0.0, 0.0, 1.0]).tolist()
        out["effects"].append(e)
    return out, P, D


# a point reaching the floor in exact free flight: its gap rounded relative to its size
# there (2.2e-16), not to its height before (found by the explore profile)
_FALLING_POINT = {
    "scene": {"name": "prop", "duration": 0.5, "samples": 11},
    "bodies": [
        {
            "name": "b0",
            "shape": "point",
            "mass": 1.0,
            "initial": {"position": [0.0, 0.0, 0.78125], "velocity": [0.0, 0.0, 0.0]},
        },
        {
            "name": "b1",
            "shape": "solid_sphere",
            "radius": 0.1,
            "mass": 1.0,
            "initial": {"position": [1.0, 0.0, 1.0], "velocity": [0.0, 0.0, 0.0]},
        },
    ],
    "effects": [
        {"type": "gravity", "g": 6.9375},
        {"type": "impact", "body": "b0", "other": "b1", "restitution": 1.0},
        {"type": "impact", "body": "b0", "restitution": 1.0},
    ],
}
# a box spinning about its symmetry axis with a subnormal transverse ω: the exact flow's
# frame was 3e-11 off orthogonal (found by the explore profile; now refused by the top,
# and integrated)
_SUBNORMAL_SPIN = {
    "scene": {"name": "prop", "duration": 0.5, "samples": 11},
    "bodies": [
        {
            "name": "b0",
            "shape": "box",
            "mass": 1.0,
            "a": 0.125,
            "b": 0.25,
            "c": 0.25,
            "initial": {
                "position": [0.0, 0.0, 1.0],
                "velocity": [0.0, 0.0, 0.0],
                "psi": 1.0,
                "theta": 1.0,
                "phi": 1.0,
                "omega": [1.0, 2.2250738585e-313, 0.0],
            },
        },
    ],
    "effects": [],
}


@settings(max_examples=EXAMPLES, deadline=None)
@example(data=_FALLING_POINT, q=[0.0, 0.0, 0.0, 1.0], b=[0.0, 0.0, 0.0])
@given(
    data=scenes(),
    q=st.lists(_u(-1.0, 1.0), min_size=4, max_size=4).filter(lambda q: np.linalg.norm(q) > 0.1),
    b=_vec(-5.0, 5.0),
)
def test_a_rigid_motion_of_the_scene_moves_its_result_alike(data, q, b) -> None:
    Q, b = _rotation(np.array(q)), np.array(b)
    base = _run(data)
    moved = _run(_moved_scene(data, Q, b))

    def move(x):  # (r, v[, R, ω]) → (Q r + b, Q v[, R Qᵀ, ω])
        r, v, *turn = x
        return (Q @ r + b, Q @ v, *((turn[0] @ Q.T, turn[1]) if turn else ()))

    _same(base, moved, move)


@settings(max_examples=EXAMPLES, deadline=None)
@given(data=scenes(ground=False), u=_vec(-2.0, 2.0))
def test_a_galilean_boost_adds_the_boost(data, u) -> None:
    u = np.array(u)
    boosted = {**data, "bodies": []}
    for body in data["bodies"]:
        ini = dict(body["initial"])
        ini["velocity"] = (np.array(ini["velocity"]) + u).tolist()
        boosted["bodies"].append({**body, "initial": ini})
    _same(_run(data), _run(boosted), lambda x: (x[0] + u * DURATION, x[1] + u, *x[2:]))


@settings(max_examples=EXAMPLES, deadline=None)
@given(data=scenes(), orders=st.data())
def test_listing_bodies_and_effects_in_another_order_changes_nothing(data, orders) -> None:
    shuffled = {
        **data,
        "bodies": orders.draw(st.permutations(data["bodies"]), label="bodies"),
        "effects": orders.draw(st.permutations(data["effects"]), label="effects"),
    }
    assume(shuffled != data)
    a, b = _run(data), _run(shuffled)
    if isinstance(a, str) or isinstance(b, str):  # refused: both (the reason may name
        assert isinstance(a, str), b  # another index of the reordered lists)
        assert isinstance(b, str), a
        return
    _same(a, b)


@settings(max_examples=EXAMPLES, deadline=None)
@example(data=_SUBNORMAL_SPIN)
@given(data=scenes(conservative=True, well_posed=True))
def test_a_conservative_scene_run_back_returns_to_its_start(data) -> None:
    fwd = _run(data)
    assume(not isinstance(fwd, str))
    assert fwd.passed, fwd.summary()
    back = {**data, "bodies": []}
    for body, (r, v, *turn) in zip(data["bodies"], _end(fwd).values(), strict=True):
        ini = {"position": r.tolist(), "velocity": (-v).tolist()}
        if turn:
            R, w = turn  # (integrated, R is orthogonal to the tolerance: projected)
            angles = euler_from_matrix(nearest_rotation(R))
            ini.update(zip(("psi", "theta", "phi"), map(float, angles), strict=True))
            ini["omega"] = (-w).tolist()
        back["bodies"].append({**body, "initial": ini})
    rev = _run(back)
    assert not isinstance(rev, str), rev
    assert rev.passed, rev.summary()
    tol = PROPERTY_RTOL * _size(fwd)
    for body, (r, v, *turn) in zip(data["bodies"], _end(rev).values(), strict=True):
        ini = body["initial"]
        np.testing.assert_allclose(r, ini["position"], rtol=0, atol=tol)
        np.testing.assert_allclose(-v, ini["velocity"], rtol=0, atol=tol)
        if turn:
            R, w = turn
            R0 = matrix_from_euler(*(ini.get(k, 0.0) for k in ("psi", "theta", "phi")))
            np.testing.assert_allclose(R, R0, rtol=0, atol=tol)
            np.testing.assert_allclose(-w, ini["omega"], rtol=0, atol=tol)


@settings(max_examples=EXAMPLES, deadline=None)
@given(
    data=scenes(),
    polar=_u(0.0, np.pi),
    azimuth=_u(0.0, 2 * np.pi),
)
def test_a_mirrored_scene_gives_the_mirrored_result(data, polar, azimuth) -> None:
    m = np.array([np.sin(polar) * np.cos(azimuth), np.sin(polar) * np.sin(azimuth), np.cos(polar)])
    mirrored, P, D = _mirrored_scene(data, m)

    def mirror(x):  # (r, v[, R, ω]) → (P r, P v[, D R P, −D ω])
        r, v, *turn = x
        return (P @ r, P @ v, *((D @ turn[0] @ P, -D @ turn[1]) if turn else ()))

    def relabel(feature):  # a box's corners are (±a/2, ±b/2, ±c/2) with the first sign
        # the highest bit of their index (mechanics.scenes.state.body_vertices): its
        # first axis reversed, corner k is corner k ^ 4
        return re.sub(r"corner (\d) of", lambda c: f"corner {int(c.group(1)) ^ 4} of", feature)

    _same(_run(data), _run(mirrored), mirror, relabel)


@settings(max_examples=EXAMPLES, deadline=None)
@given(
    vy=_u(-1.0, 1.0),
    vz=_u(-2.0, 0.0),
    wx=_u(-2.0, 2.0),
    e=st.sampled_from([0.0, 0.5, 1.0]),
    mu=st.sampled_from([0.0, 0.3, 1.0]),
)
def test_a_mirror_symmetric_box_stays_mirror_symmetric(vy, vz, wx, e, mu) -> None:
    """The flat box of the issue: unrotated, over the floor, moving in the plane x = 0
    and spinning about x, is its own mirror image in that plane (D R P = R for R = I,
    −D ω = ω for ω along x); so is every state of its motion: x = v_x = 0, ω_y = ω_z = 0
    and the attitude a turn about x, at every sample, to the properties' bound (the
    engine's sums need not be symmetric in their order)."""
    data = {
        "scene": {"name": "mirror", "duration": DURATION, "samples": 11},
        "bodies": [
            {
                "name": "box",
                "shape": "box",
                "mass": 1.0,
                "a": 0.2,
                "b": 0.4,
                "c": 0.6,
                "initial": {
                    "position": [0.0, 0.0, 0.5],
                    "velocity": [0.0, vy, vz],
                    "omega": [wx, 0.0, 0.0],
                },
            }
        ],
        "effects": [
            {"type": "gravity", "g": 9.81},
            {"type": "impact", "body": "box", "restitution": e, "friction": mu},
        ],
    }
    res = _run(data)
    if isinstance(res, str):  # refused (e.g. an edge landing that slides): not run
        return
    assert res.passed, res.summary()
    s = res.trajectory.snapshot
    tol = PROPERTY_RTOL * _size(res)
    off_plane = [s.r[:, 0, 0], s.v[:, 0, 0], s.omega[:, 0, 1], s.omega[:, 0, 2]]
    off_plane += [s.R[:, 0, 0, 1], s.R[:, 0, 0, 2], s.R[:, 0, 1, 0], s.R[:, 0, 2, 0]]
    for x in off_plane:
        np.testing.assert_allclose(x, 0.0, rtol=0, atol=tol)
