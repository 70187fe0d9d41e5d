"""Fuzz the scene loader (issue 16, part 3): every field of the schema, broken.

The fields are enumerated from the schema (``SCENE_FIELDS``, ``SHAPES``,
``INITIAL_KEYS``, ``EFFECT_FIELDS``), never listed by hand, so a new field or a new
effect joins the fuzz at once, and a field of a kind without bad values here fails
:func:`test_every_field_kind_of_the_schema_has_bad_values`. Each bad value must be
refused by :func:`parse_scene` with a :class:`SceneError` whose message names the field
(``effects[1].restitution``, ``bodies[0].radius``, ``scene.duration``); a value that
the field's kind allows but physics does not (1e300, a zero radius) is refused or runs.

What a careful user expects of the hard cases, and what is tested:

- malformed TOML, a missing file, a folder, a file that is not UTF-8: one SceneError
  naming the file;
- overlapping bodies at t = 0 (two balls in one place, a ball below the floor it is to
  bounce on): refused, naming the bodies (an impact law from inside a body is
  meaningless, and the contact search would otherwise start inside the contact);
- 1000 bodies: the run works, in bounded time (a few seconds), with the momentum
  conserved;
- 1e300 (a duration, a mass, a radius): refused with a SceneError, or a run that ends
  in bounded time with finite results.
"""

from __future__ import annotations

import copy
import math
import time
import tomllib

import numpy as np
import pytest

from mechanics._floats import EPS
from mechanics.scenes import SceneError, builtin_scenes, run_scene
from mechanics.scenes.effects import EFFECT_CLASSES
from mechanics.scenes.spec import (
    EFFECT_FIELDS,
    INITIAL_KEYS,
    SCENE_FIELDS,
    SHAPES,
    load_scene,
    parse_scene,
)
from tests.scenes.builders import ball, point, scene_data

NAN, INF = math.nan, math.inf

#: bad values for each kind of field in the schema (a kind without a row fails)
BAD_BY_KIND: dict[str, list] = {
    "number": [NAN, INF, -INF, "1.0", True, [1.0], {}],
    "positive": [0.0, -1.0, NAN, INF, "1.0", True, [1.0]],
    "nonnegative": [-1.0, NAN, INF, "1.0", True],
    "restitution": [1.5, -0.1, NAN, "0.5"],
    "vector": [[1.0, 2.0], [NAN, 0.0, 0.0], [INF, 0.0, 0.0], "x", [0.0, 0.0, "a"], 3.0, []],
    "body": ["nobody", 3, [], True],
    "bodies": [[], ["nobody"], "x", [3]],
    "planes": [
        [],
        "x",
        [3],
        [{"point": [0.0, 0.0, 0.0]}],
        [{"point": [0.0, 0.0, 0.0], "normal": [0.0, 0.0, 0.0]}],
        [{"point": [0.0, 0.0, 0.0], "normal": [0.0, 0.0, 1.0], "tilt": 1.0}],
        [{"point": [NAN, 0.0, 0.0], "normal": [0.0, 0.0, 1.0]}],
        [{"point": [1e30, 0.0, 0.0], "normal": [0.0, 0.0, 1.0]}],
    ],
    "str": [3, [], True, 1.5],
    "axis_name": ["w", 3, ""],
    "frame": ["elsewhere", 3],
    "impact_model": ["simultaneous", 3, ""],
    "integer ≥ 2": [1, 0, -5, 2.5, "201", NAN, True],
    "integer ≥ 1": [0, -5, 2.5, "201", NAN, True],
    "2, 4 or 6": [3, 8, 0, "4", 4.5],
}

_BALL = {
    "name": "ball",
    "shape": "solid_sphere",
    "mass": 1.0,
    "radius": 0.1,
    "initial": {"position": [0.0, 0.0, 1.0], "velocity": [0.0, 0.0, 0.0]},
}
_SCENE = {"name": "fuzz", "duration": 0.5, "samples": 11}


def _raw() -> dict[str, dict]:
    return {n: tomllib.loads(p.read_text(encoding="utf-8")) for n, p in builtin_scenes().items()}


RAW = _raw()


def _extra_bases() -> dict[str, dict]:
    """Valid scenes for effects that no built-in scene uses."""
    ex = {t: dict(c.example) for t, c in EFFECT_CLASSES.items()}
    box = {
        "name": "rod",
        "shape": "box",
        "mass": 1.0,
        "a": 1.0,
        "b": 0.5,
        "c": 0.2,
        "initial": {"position": [0.0, 0.0, 0.0], "velocity": [0.0, 0.0, 0.0], "omega": [0, 0, 1.0]},
    }
    two = [
        dict(_BALL, name="a"),
        dict(_BALL, name="b", initial={"position": [3.0, 0, 0], "velocity": [0, 1.0, 0]}),
    ]
    pendulum = copy.deepcopy(RAW["physical_pendulum"])
    (axis,) = [e for e in pendulum["effects"] if e["type"] == "fixed_axis"]
    pendulum["effects"].append({"type": "torsion", "body": axis["body"], "stiffness": 2.0})
    return {
        "buoyancy": {
            "scene": _SCENE,
            "bodies": [_BALL],
            "effects": [{"type": "gravity", "g": 9.81}, ex["buoyancy"]],
        },
        "damper": {"scene": _SCENE, "bodies": [_BALL], "effects": [ex["damper"]]},
        "spring": {"scene": _SCENE, "bodies": [_BALL], "effects": [ex["spring"]]},
        "newton_gravity": {"scene": _SCENE, "bodies": two, "effects": [ex["newton_gravity"]]},
        "torque": {"scene": _SCENE, "bodies": [box], "effects": [ex["torque"]]},
        "torsion": pendulum,
    }


EXTRA = _extra_bases()


def base_for(effect_type: str) -> tuple[dict, int]:
    """A valid scene (as a dict) that lists ``effect_type``, and the effect's index."""
    if effect_type in EXTRA:
        data = EXTRA[effect_type]
    else:
        data = next(
            r for r in RAW.values() if any(e["type"] == effect_type for e in r.get("effects", ()))
        )
    data = copy.deepcopy(data)
    i = next(k for k, e in enumerate(data["effects"]) if e["type"] == effect_type)
    return data, i


def _kinds() -> set[str]:
    kinds = {k for f in EFFECT_FIELDS.values() for k, _ in f.values()}
    kinds |= {k for k, _, _ in SCENE_FIELDS.values()}
    kinds |= {"vector" if k == "vector" else "number" for k in INITIAL_KEYS.values()}
    return kinds | {"positive"}  # body dimensions and mass


def test_every_field_kind_of_the_schema_has_bad_values():
    missing = sorted(_kinds() - set(BAD_BY_KIND))
    assert not missing, f"field kinds without bad values in BAD_BY_KIND: {missing}"


@pytest.mark.parametrize("effect_type", sorted(EFFECT_FIELDS))
def test_every_effect_has_a_valid_base_scene(effect_type):
    data, i = base_for(effect_type)
    scene = parse_scene(data)
    assert scene.effects[i].type == effect_type


def _refused_naming(data: dict, field: str) -> str | None:
    """None if parse_scene refuses ``data`` naming ``field``; else what went wrong."""
    try:
        parse_scene(data, source="fuzz.toml")
    except SceneError as exc:
        msg = str(exc)
        if field not in msg:
            return f"refused, but the message does not name {field}: {msg}"
        if not msg.startswith("fuzz.toml: "):
            return f"the message does not start with the file: {msg}"
        return None
    except Exception as exc:  # anything but a SceneError is a bug
        return f"{type(exc).__name__}: {exc}"
    return "accepted"


def _effect_cases():
    for t, fields in sorted(EFFECT_FIELDS.items()):
        for name, (kind, _required) in fields.items():
            yield pytest.param(t, name, kind, id=f"{t}.{name}")


@pytest.mark.parametrize(("effect_type", "field", "kind"), list(_effect_cases()))
def test_a_bad_effect_field_is_refused_naming_it(effect_type, field, kind):
    problems = []
    for bad in BAD_BY_KIND[kind]:
        data, i = base_for(effect_type)
        data["effects"][i][field] = bad
        why = _refused_naming(data, f"effects[{i}].{field}")
        if why:
            problems.append(f"{field} = {bad!r}: {why}")
    assert not problems, "\n".join(problems)


@pytest.mark.parametrize("effect_type", sorted(EFFECT_FIELDS))
def test_an_unknown_or_missing_effect_field_is_refused_naming_it(effect_type):
    data, i = base_for(effect_type)
    data["effects"][i]["no_such_field"] = 1.0
    assert _refused_naming(data, f"effects[{i}].no_such_field") is None
    for name, (_kind, required) in EFFECT_FIELDS[effect_type].items():
        if required:
            data, i = base_for(effect_type)
            del data["effects"][i][name]
            why = _refused_naming(data, f"effects[{i}].{name}")
            assert why is None, f"{name} missing: {why}"


@pytest.mark.parametrize(("field", "kind"), [(f, k) for f, (k, _, _) in SCENE_FIELDS.items()])
def test_a_bad_scene_field_is_refused_naming_it(field, kind):
    problems = []
    for bad in BAD_BY_KIND[kind]:
        data, _ = base_for("gravity")
        data["scene"][field] = bad
        if field in ("step", "order"):
            data["scene"]["method"] = "splitting"
        why = _refused_naming(data, f"scene.{field}")
        if why:
            problems.append(f"{field} = {bad!r}: {why}")
    assert not problems, "\n".join(problems)


@pytest.mark.parametrize("shape", sorted(SHAPES))
def test_a_bad_body_dimension_or_mass_is_refused_naming_it(shape):
    data, _ = base_for("gravity")
    problems = []
    for dim in SHAPES[shape] + (("mass",) if shape != "tank" else ()):
        bads = BAD_BY_KIND["positive"]
        if dim == "inertia":
            bads = [[1.0, 1.0], [1.0, 1.0, 3.0], [0.0, 1.0, 1.0], [NAN, 1.0, 1.0], "x"]
        for bad in bads:
            d = copy.deepcopy(data)
            body = d["bodies"][0]
            for k in ("radius", "length", "height", "a", "b", "c", "inertia", "area"):
                body.pop(k, None)
            body["shape"] = shape
            body.update({k: 1.0 for k in SHAPES[shape]})
            if shape == "tank":  # a tank has no mass field; its error may come first
                body.pop("mass")
            if shape == "custom":
                body["inertia"] = [1.0, 1.0, 1.0]
            body[dim] = bad
            why = _refused_naming(d, f"bodies[0].{dim}")
            if why:
                problems.append(f"{shape}.{dim} = {bad!r}: {why}")
    assert not problems, "\n".join(problems)


@pytest.mark.parametrize(("key", "kind"), sorted(INITIAL_KEYS.items()))
def test_a_bad_initial_value_is_refused_naming_it(key, kind):
    problems = []
    for bad in BAD_BY_KIND["vector" if kind == "vector" else "number"]:
        data, _ = base_for("gravity")
        data["bodies"][0]["initial"][key] = bad
        why = _refused_naming(data, f"bodies[0].initial.{key}")
        if why:
            problems.append(f"initial.{key} = {bad!r}: {why}")
    assert not problems, "\n".join(problems)


#: the fields every body has besides its dimensions, mass and initial state (the rest of
#: the [[bodies]] schema: spec._parse_body's "allowed" set)
BODY_FIELDS_BAD = {
    "name": [3, "", "two words", "1ball", True],
    "shape": ["torus", 3, ""],
    "fixed": ["yes", 1, 0.0],
    "initial": ["at rest", [0.0, 0.0, 1.0], 3],
}


def test_the_body_fields_fuzzed_are_those_of_the_schema():
    """name, shape, fixed and initial, plus the dimensions of SHAPES and mass, are all
    the fields a body may have (an unknown one is refused: see below)."""
    data, _ = base_for("gravity")
    data["bodies"][0]["fixed"] = False
    allowed = set(data["bodies"][0]) - {"mass", "radius"}
    assert allowed == set(BODY_FIELDS_BAD)


@pytest.mark.parametrize("field", sorted(BODY_FIELDS_BAD))
def test_a_bad_body_field_is_refused_naming_it(field):
    problems = []
    for bad in BODY_FIELDS_BAD[field]:
        data, _ = base_for("gravity")
        data["bodies"][0][field] = bad
        why = _refused_naming(data, f"bodies[0].{field}")
        if why:
            problems.append(f"{field} = {bad!r}: {why}")
    assert not problems, "\n".join(problems)


def test_unknown_tables_bodies_fields_and_initial_keys_are_refused_naming_them():
    cases = []
    d, _ = base_for("gravity")
    d["bodies"][0]["colour"] = "red"
    cases.append((d, "bodies[0].colour"))
    d, _ = base_for("gravity")
    d["bodies"][0]["initial"]["spin_rate"] = 1.0
    cases.append((d, "bodies[0].initial.spin_rate"))
    d, _ = base_for("gravity")
    d["scene"]["durations"] = 1.0
    cases.append((d, "scene.durations"))
    d, _ = base_for("gravity")
    d["effects"][0]["type"] = "magnetism"
    cases.append((d, "effects[0].type"))
    d, _ = base_for("gravity")
    d["effects"][0] = "gravity"
    cases.append((d, "effects[0]"))
    d, _ = base_for("gravity")
    d["bodies"] = {"name": "ball"}
    cases.append((d, "bodies"))
    d, _ = base_for("gravity")
    d["bodies"][0]["shape"] = "torus"
    cases.append((d, "bodies[0].shape"))
    d, _ = base_for("gravity")
    d["units"] = {"system": "imperial"}
    cases.append((d, "units"))
    problems = [f"{f}: {w}" for d, f in cases if (w := _refused_naming(d, f))]
    assert not problems, "\n".join(problems)


# ------------------------------------------------------------------------- files


@pytest.mark.parametrize(
    ("content", "reason"),
    [
        (b"[scene\nname = 1\n", "(syntax)"),
        (b'[scene]\nname = "x"\nduration = \n', "(syntax)"),
        (b"\xff\xfe[scene]", "(file)"),
        (b'[scene]\nname = "caf\xe9"\n', "(file)"),
        (b"", "scene"),
        (b'scene = "not a table"\n', "scene"),
        (b'[scene]\nname = "x"\nduration = nan\n[[bodies]]\nname = "b"\n', "scene.duration"),
        (b'[scene]\nname = "x"\nduration = -1.0\n[[bodies]]\nname = "b"\n', "scene.duration"),
    ],
    ids=[
        "unclosed table",
        "missing value",
        "binary",
        "latin-1",
        "empty",
        "scene not a table",
        "nan",
        "negative duration",
    ],
)
def test_a_malformed_file_is_one_scene_error_naming_file_and_place(tmp_path, content, reason):
    p = tmp_path / "bad.toml"
    p.write_bytes(content)
    with pytest.raises(SceneError) as info:
        load_scene(p)
    msg = str(info.value)
    assert msg.startswith(str(p)), msg
    assert reason in msg, msg
    assert "\n" not in msg.strip(), msg


def test_a_missing_file_or_a_folder_is_a_scene_error_naming_it(tmp_path):
    for path in (tmp_path / "missing.toml", tmp_path, tmp_path / "x" / "y.toml"):
        with pytest.raises(SceneError, match="cannot read") as info:
            load_scene(path)
        assert str(path) in str(info.value)


# ------------------------------------------------------------------- hard scenes


def test_two_balls_overlapping_at_t0_are_refused_naming_both():
    bodies = [
        ball("left", (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)),
        ball("right", (0.05, 0.0, 0.0), (-1.0, 0.0, 0.0)),
    ]
    hit = {"type": "impact", "body": "left", "other": "right", "restitution": 1.0}
    data = scene_data(bodies, [hit], name="overlap", duration=1.0, samples=11)
    with pytest.raises(SceneError, match="overlap") as info:
        parse_scene(data, source="overlap.toml")
    assert "left" in str(info.value)
    assert "right" in str(info.value)


def test_a_ball_starting_below_its_floor_is_refused_naming_it():
    data = copy.deepcopy(RAW["bouncing_ball"])
    data["bodies"][0]["initial"]["position"] = [0.0, 0.0, 0.05]  # radius 0.1: inside
    with pytest.raises(SceneError, match="overlap") as info:
        parse_scene(data, source="below.toml")
    assert "ball" in str(info.value)


#: a thousand bodies must run within this wall time (measured ~1 s on one core of the
#: 2-core CI machine; the bound leaves room for a loaded machine)
THOUSAND_BODIES_SECONDS = 30.0
#: x0 + v t of size 100 after one second of integration at rtol 1e-12 (the default)
POSITION_ATOL = 2**20 * 100 * EPS


def test_a_thousand_free_bodies_run_in_bounded_time_on_straight_lines():
    rng = np.random.default_rng(16)
    pos = rng.uniform(-100.0, 100.0, (1000, 3))
    vel = rng.uniform(-1.0, 1.0, (1000, 3))
    bodies = [
        point(f"p{k}", p.tolist(), v.tolist())
        for k, (p, v) in enumerate(zip(pos, vel, strict=True))
    ]
    data = scene_data(bodies, name="crowd", duration=1.0, samples=11)
    t0 = time.perf_counter()
    result = run_scene(parse_scene(data, source="crowd.toml"))
    wall = time.perf_counter() - t0
    assert wall < THOUSAND_BODIES_SECONDS, f"1000 free bodies took {wall:.1f} s"
    series = result.trajectory.series
    assert all(np.isfinite(v).all() for v in series.values())
    # no force acts: each body moves on its straight line, x(t) = x0 + v t
    end = np.array([[series[f"p{k}.{c}"][-1] for c in "xyz"] for k in range(1000)])
    np.testing.assert_allclose(end, pos + vel, rtol=0, atol=POSITION_ATOL)


@pytest.mark.parametrize(
    ("where", "value"),
    [
        (("scene", "duration"), 1e300),
        (("bodies", 0, "mass"), 1e300),
        (("bodies", 0, "radius"), 1e300),
        (("bodies", 0, "radius"), 1e-300),
        (("effects", 0, "g"), 1e300),
    ],
    ids=["duration", "mass", "radius", "tiny radius", "g"],
)
def test_1e300_is_refused_or_runs_in_bounded_time(where, value):
    data = copy.deepcopy(RAW["bouncing_ball"])
    node = data
    for k in where[:-1]:
        node = node[k]
    node[where[-1]] = value
    t0 = time.perf_counter()
    outcome = _run_or_refusal(data, "huge.toml")
    assert time.perf_counter() - t0 < HUGE_SECONDS
    if isinstance(outcome, SceneError):
        assert str(outcome).startswith("huge.toml: "), outcome
    else:
        assert all(np.isfinite(v).all() for v in outcome.trajectory.series.values())


#: a refusal is immediate; a run of the bouncing ball takes ~1 s
HUGE_SECONDS = 60.0


def _run_or_refusal(data: dict, source: str):
    try:
        return run_scene(parse_scene(data, source=source))
    except SceneError as exc:
        return exc
