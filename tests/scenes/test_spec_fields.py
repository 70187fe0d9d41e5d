"""Every field kind of the scene schema (:mod:`mechanics.scenes.spec`): what it accepts
(and the value it returns), its defaults, and each refusal's exact message, which names
the file, the field path and the value with the violated condition.  The boundaries are
pinned where a wrong comparison shows (0 for > 0 and ≥ 0, 0 and 1 for a restitution,
1e-3 for a tolerance, J3 = J1 + J2 for a triangle inequality, 2 samples)."""

from __future__ import annotations

import copy
import functools
import math

import pytest

from mechanics.scenes import SceneError, spec
from mechanics.scenes.spec import EFFECT_FIELDS, SHAPES, load_scene, parse_scene

from .builders import body, scene_data

SRC = "spec.toml"


def _base() -> dict:
    gravity = {"type": "gravity", "g": 9.81}
    return scene_data([body("a", "point", mass=1.0)], [gravity], name="s", duration=1.0)


def _refusal(data, source=SRC) -> SceneError:
    with pytest.raises(SceneError) as info:
        parse_scene(data, source=source)
    err = info.value
    assert str(err) == f"{source}: {err.field}: {err.reason}"
    return err


def _check_refusal(kind, value, bodies=None, where="w") -> tuple[str, str]:
    with pytest.raises(SceneError) as info:
        spec._check("f.toml", where, kind, value, bodies)
    assert info.value.source == "f.toml"
    return info.value.field, info.value.reason


# ------------------------------------------------------------------ the field kinds


@pytest.mark.parametrize(
    ("value", "name"),
    [
        ("x", "a string"),
        (True, "a boolean"),
        ({}, "a table"),
        ([], "an array"),
        (3, "int"),
        (1.5, "float"),
        (None, "NoneType"),
    ],
)
def test_type_names_read_as_toml_words(value, name) -> None:
    assert spec._type_name(value) == name


def test_a_number_is_a_finite_int_or_float_returned_as_float() -> None:
    got = spec._check("f.toml", "w", "number", 3)
    assert got == 3.0
    assert type(got) is float
    assert spec._check("f.toml", "w", "number", -2.5) == -2.5


@pytest.mark.parametrize(
    ("value", "reason"),
    [
        (True, "expected a number in SI units, got a boolean True"),
        (
            "9.81 m/s^2",
            "expected a number in SI units, got a string '9.81 m/s^2' (units are not "
            "parsed: write the value as a plain number in SI units)",
        ),
        ([1.0], "expected a number in SI units, got an array [1.0]"),
        (None, "expected a number in SI units, got NoneType None"),
        (math.nan, "must be finite; got nan"),
        (math.inf, "must be finite; got inf"),
        (-math.inf, "must be finite; got -inf"),
    ],
)
def test_a_bad_number_is_refused_naming_its_type_or_value(value, reason) -> None:
    assert _check_refusal("number", value) == ("w", reason)


@pytest.mark.parametrize(
    ("kind", "value", "reason"),
    [
        ("positive", 0.0, "must be > 0 (non-physical otherwise); got 0.0"),
        ("positive", 0, "must be > 0 (non-physical otherwise); got 0"),
        ("positive", -1.5, "must be > 0 (non-physical otherwise); got -1.5"),
        ("nonnegative", -1e-300, "must be ≥ 0 (non-physical otherwise); got -1e-300"),
        ("restitution", 1.2, "the coefficient of restitution must lie in [0, 1]; got 1.2"),
        ("restitution", -0.1, "the coefficient of restitution must lie in [0, 1]; got -0.1"),
        (
            "restitution",
            1.0000000000000002,
            "the coefficient of restitution must lie in [0, 1]; got 1.0000000000000002",
        ),
        (
            "positive",
            "1",
            "expected a number in SI units, got a string '1' (units are not "
            "parsed: write the value as a plain number in SI units)",
        ),
        ("nonnegative", math.nan, "must be finite; got nan"),
        ("restitution", math.inf, "must be finite; got inf"),
    ],
)
def test_a_number_out_of_its_range_is_refused_with_the_condition(kind, value, reason) -> None:
    assert _check_refusal(kind, value) == ("w", reason)


@pytest.mark.parametrize(
    ("kind", "value"),
    [
        ("positive", 1e-300),
        ("positive", 5),
        ("nonnegative", 0.0),
        ("nonnegative", 2),
        ("restitution", 0.0),
        ("restitution", 1.0),
        ("restitution", 0.5),
    ],
)
def test_a_number_at_the_edge_of_its_range_is_accepted_as_float(kind, value) -> None:
    got = spec._check("f.toml", "w", kind, value)
    assert got == value
    assert type(got) is float


def test_a_vector_is_an_array_of_three_numbers() -> None:
    got = spec._check("f.toml", "w", "vector", [1, 2.5, -3])
    assert got == [1.0, 2.5, -3.0]
    assert all(type(x) is float for x in got)
    want = "expected an array of 3 numbers (SI), got "
    assert _check_refusal("vector", [1.0, 2.0]) == ("w", want + "[1.0, 2.0]")
    assert _check_refusal("vector", [1.0, 2.0, 3.0, 4.0]) == ("w", want + "[1.0, 2.0, 3.0, 4.0]")
    assert _check_refusal("vector", "x") == ("w", want + "'x'")
    assert _check_refusal("vector", (1.0, 2.0, 3.0)) == ("w", want + "(1.0, 2.0, 3.0)")
    # a bad component is named by its index
    assert _check_refusal("vector", [0.0, "a", 0.0]) == (
        "w[1]",
        "expected a number in SI units, got a string 'a' (units are not parsed: write the "
        "value as a plain number in SI units)",
    )
    assert _check_refusal("vector", [0.0, 0.0, math.nan]) == ("w[2]", "must be finite; got nan")


def test_strings_axis_names_and_frames() -> None:
    assert spec._check("f.toml", "w", "str", "") == ""
    assert _check_refusal("str", 3) == ("w", "expected a string, got int 3")
    assert _check_refusal("str", True) == ("w", "expected a string, got a boolean True")
    assert _check_refusal("str", [1]) == ("w", "expected a string, got an array [1]")
    for axis in ("x", "y", "z"):
        assert spec._check("f.toml", "w", "axis_name", axis) == axis
    assert _check_refusal("axis_name", "w") == ("w", "expected one of 'x', 'y', 'z'; got 'w'")
    assert _check_refusal("axis_name", 1) == ("w", "expected one of 'x', 'y', 'z'; got 1")
    for frame in ("space", "body"):
        assert spec._check("f.toml", "w", "frame", frame) == frame
    assert _check_refusal("frame", "world") == ("w", "expected 'space' or 'body'; got 'world'")


def test_body_names_are_checked_against_the_bodies() -> None:
    names = {"b", "a"}
    assert spec._check("f.toml", "w", "body", "a", names) == "a"
    assert spec._check("f.toml", "w", "body", "anything", None) == "anything"
    assert _check_refusal("body", "c", names) == ("w", "unknown body 'c' (bodies: a, b)")
    assert _check_refusal("body", "c", set()) == ("w", "unknown body 'c' (bodies: none)")
    assert _check_refusal("body", 3, names) == ("w", "expected a body name (string), got int")
    assert spec._check("f.toml", "w", "bodies", ["b", "a"], names) == ["b", "a"]
    want = "expected a non-empty array of body names, got "
    assert _check_refusal("bodies", [], names) == ("w", want + "[]")
    assert _check_refusal("bodies", "a", names) == ("w", want + "'a'")
    assert _check_refusal("bodies", ["a", "z"], names) == (
        "w[1]",
        "unknown body 'z' (bodies: a, b)",
    )


def test_an_unknown_kind_is_a_schema_typo() -> None:
    with pytest.raises(AssertionError, match=r"^no_such_kind$"):
        spec._check("f.toml", "w", "no_such_kind", 1.0)


def test_tables_and_unknown_fields() -> None:
    assert spec._table("f.toml", "t", {"k": 1}) == {"k": 1}
    with pytest.raises(SceneError) as info:
        spec._table("f.toml", "t", [1])
    assert (info.value.field, info.value.reason) == ("t", "expected a table, got an array")
    spec._unknown("f.toml", "t", ["a"], {"a", "b"})  # known: nothing raised
    with pytest.raises(SceneError) as info:
        spec._unknown("f.toml", "t", ["a", "zz"], {"b", "a", "c"})
    assert (info.value.field, info.value.reason) == ("t.zz", "unknown field (allowed: a, b, c)")
    with pytest.raises(SceneError) as info:
        spec._unknown("f.toml", "", ["zz"], {"a"})
    assert info.value.field == "zz"  # at the top level: the key alone


# --------------------------------------------------------------------- the [scene]


def test_the_defaults_of_a_minimal_scene() -> None:
    s = parse_scene(_base())
    assert (s.name, s.source, s.duration) == ("s", "<scene>", 1.0)
    assert (s.samples, s.method, s.rtol, s.atol) == (201, "auto", 1e-12, 1e-12)
    assert (s.title, s.book, s.compare, s.step, s.order) == ("", "", "", None, 4)
    assert s.raw == _base()
    (b,) = s.bodies
    assert (b.name, b.shape, b.mass, b.dims, b.initial, b.fixed) == (
        "a",
        "point",
        1.0,
        {},
        {},
        False,
    )
    (e,) = s.effects
    assert (e.type, e.index, e.fields, e.where) == ("gravity", 0, {"g": 9.81}, "effects[0]")
    assert s.effect_types == ("gravity",)


def test_every_scene_field_is_read() -> None:
    d = _base()
    d["scene"].update(
        title="T",
        book="E6.1",
        compare="E6.1",
        samples=2,
        method="splitting",
        rtol=1e-3,
        atol=1e-6,
        step=0.25,
        order=6,
    )
    d["units"] = {"system": "SI"}
    s = parse_scene(d, source="x.toml")
    assert (s.title, s.book, s.compare, s.samples, s.method) == (
        "T",
        "E6.1",
        "E6.1",
        2,
        "splitting",
    )
    assert (s.rtol, s.atol, s.step, s.order, s.source) == (1e-3, 1e-6, 0.25, 6, "x.toml")
    d["scene"]["order"] = 2.0  # a float equal to an order is that order
    assert parse_scene(d).order == 2
    assert type(parse_scene(d).order) is int
    for method in ("exact", "integrate"):
        d = _base()
        d["scene"]["method"] = method
        assert parse_scene(d).method == method


def _with(path, value):
    d = _base()
    node = d
    for k in path[:-1]:
        node = node[k]
    node[path[-1]] = value
    return d


def _without(path):
    d = _base()
    node = d
    for k in path[:-1]:
        node = node[k]
    del node[path[-1]]
    return d


METHODS = "('auto', 'exact', 'integrate', 'splitting')"

#: (id, data, field, reason)
SCENE_CASES = [
    ("top level not a table", [1], "(top level)", "expected a table, got an array"),
    (
        "unknown top-level table",
        {**_base(), "colour": {}},
        "colour",
        "unknown field (allowed: bodies, effects, scene, units)",
    ),
    ("units not a table", {**_base(), "units": "SI"}, "units", "expected a table, got a string"),
    (
        "unknown units field",
        {**_base(), "units": {"system": "SI", "scale": 1}},
        "units.scale",
        "unknown field (allowed: system)",
    ),
    (
        "units without a system",
        {**_base(), "units": {}},
        "units.system",
        "only SI units are supported; got None",
    ),
    (
        "CGS units",
        {**_base(), "units": {"system": "CGS"}},
        "units.system",
        "only SI units are supported; got 'CGS'",
    ),
    ("no scene", _without(["scene"]), "scene", "missing required table [scene]"),
    ("scene not a table", _with(["scene"], 3), "scene", "expected a table, got int"),
    (
        "unknown scene field",
        _with(["scene", "durations"], 1.0),
        "scene.durations",
        "unknown field (allowed: atol, book, compare, duration, max_samples, max_seconds, "
        "max_steps, method, name, order, rtol, samples, step, title)",
    ),
    ("no name", _without(["scene", "name"]), "scene.name", "missing required field"),
    ("no duration", _without(["scene", "duration"]), "scene.duration", "missing required field"),
    (
        "name not a string",
        _with(["scene", "name"], 1),
        "scene.name",
        "expected a string, got int 1",
    ),
    (
        "zero duration",
        _with(["scene", "duration"], 0.0),
        "scene.duration",
        "must be > 0 (non-physical otherwise); got 0.0",
    ),
    (
        "one sample",
        _with(["scene", "samples"], 1),
        "scene.samples",
        "expected an integer ≥ 2; got 1",
    ),
    (
        "float samples",
        _with(["scene", "samples"], 2.0),
        "scene.samples",
        "expected an integer ≥ 2; got 2.0",
    ),
    (
        "boolean samples",
        _with(["scene", "samples"], True),
        "scene.samples",
        "expected an integer ≥ 2; got True",
    ),
    (
        "unknown method",
        _with(["scene", "method"], "fast"),
        "scene.method",
        f"expected one of {METHODS}; got 'fast'",
    ),
    (
        "method not a string",
        _with(["scene", "method"], 2),
        "scene.method",
        "expected a string, got int 2",
    ),
    (
        "step without splitting",
        _with(["scene", "step"], 0.1),
        "scene.step",
        "only with method 'splitting'; got 'auto'",
    ),
    (
        "order without splitting",
        {**_base(), "scene": {**_base()["scene"], "method": "integrate", "order": 4}},
        "scene.order",
        "only with method 'splitting'; got 'integrate'",
    ),
    (
        "zero step",
        {**_base(), "scene": {**_base()["scene"], "method": "splitting", "step": 0.0}},
        "scene.step",
        "must be > 0 (non-physical otherwise); got 0.0",
    ),
    (
        "order 3",
        {**_base(), "scene": {**_base()["scene"], "method": "splitting", "order": 3}},
        "scene.order",
        "expected one of (2, 4, 6); got 3",
    ),
    (
        "boolean order",
        {**_base(), "scene": {**_base()["scene"], "method": "splitting", "order": True}},
        "scene.order",
        "expected one of (2, 4, 6); got True",
    ),
    (
        "rtol above 1e-3",
        _with(["scene", "rtol"], 0.0011),
        "scene.rtol",
        "must be ≤ 1e-3; got 0.0011",
    ),
    ("atol above 1e-3", _with(["scene", "atol"], 0.5), "scene.atol", "must be ≤ 1e-3; got 0.5"),
    (
        "zero rtol",
        _with(["scene", "rtol"], 0.0),
        "scene.rtol",
        "must be > 0 (non-physical otherwise); got 0.0",
    ),
    (
        "negative atol",
        _with(["scene", "atol"], -1e-9),
        "scene.atol",
        "must be > 0 (non-physical otherwise); got -1e-09",
    ),
    (
        "title not a string",
        _with(["scene", "title"], 1),
        "scene.title",
        "expected a string, got int 1",
    ),
    (
        "book not a string",
        _with(["scene", "book"], 2),
        "scene.book",
        "expected a string, got int 2",
    ),
    (
        "compare not a string",
        _with(["scene", "compare"], 3),
        "scene.compare",
        "expected a string, got int 3",
    ),
    ("no bodies", _without(["bodies"]), "bodies", "expected at least one [[bodies]] table"),
    ("empty bodies", _with(["bodies"], []), "bodies", "expected at least one [[bodies]] table"),
    (
        "bodies a table",
        _with(["bodies"], {"name": "a"}),
        "bodies",
        "expected at least one [[bodies]] table",
    ),
    (
        "duplicate body",
        _with(["bodies"], [{"name": "a", "shape": "point", "mass": 1.0}] * 2),
        "bodies[1].name",
        "duplicate body name 'a'",
    ),
    (
        "effects a table",
        _with(["effects"], {"type": "gravity"}),
        "effects",
        "expected an array of [[effects]] tables",
    ),
]


@pytest.mark.parametrize(
    ("data", "field", "reason"), [c[1:] for c in SCENE_CASES], ids=[c[0] for c in SCENE_CASES]
)
def test_a_bad_scene_table_is_refused_naming_field_and_reason(data, field, reason) -> None:
    err = _refusal(copy.deepcopy(data))
    assert (err.source, err.field, err.reason) == (SRC, field, reason)


def test_the_tolerance_limit_and_two_samples_are_accepted() -> None:
    s = parse_scene(_with(["scene", "rtol"], 1e-3))
    assert s.rtol == 1e-3
    s = parse_scene(_with(["scene", "atol"], 1e-3))
    assert s.atol == 1e-3
    assert parse_scene(_with(["scene", "samples"], 2)).samples == 2
    assert parse_scene(_with(["effects"], [])).effects == ()  # no effect at all: free flight
    assert parse_scene(_without(["effects"])).effects == ()


# --------------------------------------------------------------------- [[bodies]]


def _body(**fields):
    return _with(["bodies"], [fields])


_ball = functools.partial(body, "a", "solid_sphere", mass=2.0, radius=0.5)


BODY_CASES = [
    ("body not a table", _with(["bodies"], ["a"]), "bodies[0]", "expected a table, got a string"),
    ("no name", _body(shape="point", mass=1.0), "bodies[0].name", "missing required field"),
    ("no shape", _body(name="a", mass=1.0), "bodies[0].shape", "missing required field"),
    (
        "name not a string",
        _body(name=3, shape="point", mass=1.0),
        "bodies[0].name",
        "expected a string, got int 3",
    ),
    (
        "name not an identifier",
        _body(name="1ball", shape="point", mass=1.0),
        "bodies[0].name",
        "must be an identifier; got '1ball'",
    ),
    (
        "shape not a string",
        _body(name="a", shape=3, mass=1.0),
        "bodies[0].shape",
        "expected a string, got int 3",
    ),
    (
        "unknown shape",
        _body(name="a", shape="torus", mass=1.0),
        "bodies[0].shape",
        f"unknown body shape 'torus' (known: {', '.join(SHAPES)})",
    ),
    (
        "unknown body field",
        _body(**_ball(colour="red")),
        "bodies[0].colour",
        "unknown field (allowed: fixed, initial, mass, name, radius, shape)",
    ),
    (
        "a tank has no mass",
        _body(name="a", shape="tank", area=1.0, mass=1.0),
        "bodies[0].mass",
        "unknown field (allowed: area, fixed, initial, name, shape)",
    ),
    ("no mass", _body(name="a", shape="point"), "bodies[0].mass", "missing required field"),
    (
        "zero mass",
        _body(name="a", shape="point", mass=0.0),
        "bodies[0].mass",
        "must be > 0 (non-physical otherwise); got 0.0",
    ),
    (
        "no radius",
        _body(name="a", shape="solid_sphere", mass=1.0),
        "bodies[0].radius",
        "missing required field (a solid_sphere needs it)",
    ),
    (
        "no height",
        _body(name="a", shape="cylinder", mass=1.0, radius=1.0),
        "bodies[0].height",
        "missing required field (a cylinder needs it)",
    ),
    (
        "zero radius",
        _body(**_ball(radius=0.0)),
        "bodies[0].radius",
        "must be > 0 (non-physical otherwise); got 0.0",
    ),
    (
        "a mass beyond the domain",
        _body(**_ball(mass=1e200, radius=1.0)),
        "bodies[0].mass",
        "1e+200 is too large: a scene's numbers have magnitude at most 2⁸⁰ ≈ 1.2e+24 (SI), "
        "where the engine's float64 arithmetic stays finite; choose units that bring it into "
        "range",
    ),
    (
        "principal moments beyond the domain",
        _body(name="a", shape="custom", mass=1.0, inertia=[1e30, 1e30, 1e30]),
        "bodies[0].inertia[0]",
        "1e+30 is too large: a scene's numbers have magnitude at most 2⁸⁰ ≈ 1.2e+24 (SI), "
        "where the engine's float64 arithmetic stays finite; choose units that bring it into "
        "range",
    ),
    (
        "a zero principal moment",
        _body(name="a", shape="custom", mass=1.0, inertia=[1.0, 0, 1.0]),
        "bodies[0].inertia",
        "principal moments must be > 0; got [1.0, 0.0, 1.0]",
    ),
    (
        "inertia of two numbers",
        _body(name="a", shape="custom", mass=1.0, inertia=[1.0, 1.0]),
        "bodies[0].inertia",
        "expected an array of 3 numbers (SI), got [1.0, 1.0]",
    ),
    (
        "triangle inequality",
        _body(name="a", shape="custom", mass=1.0, inertia=[3.0, 1.0, 1.5]),
        "bodies[0].inertia",
        "principal moments violate the triangle inequality J3 ≤ J1 + J2; got [3.0, 1.0, 1.5]",
    ),
    (
        "triangle inequality by 1e-11",
        _body(name="a", shape="custom", mass=1.0, inertia=[1.0, 1.0, 2.00000000001]),
        "bodies[0].inertia",
        "principal moments violate the triangle inequality J3 ≤ J1 + J2; "
        "got [1.0, 1.0, 2.00000000001]",
    ),
    (
        "initial not a table",
        _body(name="a", shape="point", mass=1.0, initial=[0.0, 0.0, 1.0]),
        "bodies[0].initial",
        "expected a table, got an array",
    ),
    (
        "unknown initial key",
        _body(name="a", shape="point", mass=1.0, initial={"spin_rate": 1.0}),
        "bodies[0].initial.spin_rate",
        "unknown field (allowed: angle, angular_velocity, distance, level, omega, phi, "
        "phi_dot, position, psi, psi_dot, speed, spin, theta, theta_dot, velocity)",
    ),
    (
        "bad initial component",
        _body(name="a", shape="point", mass=1.0, initial={"velocity": [0.0, math.inf, 0.0]}),
        "bodies[0].initial.velocity[1]",
        "must be finite; got inf",
    ),
    (
        "bad initial number",
        _body(name="a", shape="point", mass=1.0, initial={"theta": "0.5 rad"}),
        "bodies[0].initial.theta",
        "expected a number in SI units, got a string '0.5 rad' (units are not parsed: write "
        "the value as a plain number in SI units)",
    ),
    (
        "zero level",
        _body(name="a", shape="point", mass=1.0, initial={"level": 0.0}),
        "bodies[0].initial.level",
        "must be > 0; got 0.0",
    ),
    (
        "negative level",
        _body(name="a", shape="point", mass=1.0, initial={"level": -2}),
        "bodies[0].initial.level",
        "must be > 0; got -2.0",
    ),
    (
        "fixed not a boolean",
        _body(name="a", shape="point", mass=1.0, fixed="yes"),
        "bodies[0].fixed",
        "expected true or false, got 'yes'",
    ),
    (
        "fixed a number",
        _body(name="a", shape="point", mass=1.0, fixed=1),
        "bodies[0].fixed",
        "expected true or false, got 1",
    ),
]


@pytest.mark.parametrize(
    ("data", "field", "reason"), [c[1:] for c in BODY_CASES], ids=[c[0] for c in BODY_CASES]
)
def test_a_bad_body_is_refused_naming_field_and_reason(data, field, reason) -> None:
    err = _refusal(copy.deepcopy(data))
    assert (err.field, err.reason) == (field, reason)


def test_a_body_reads_its_shape_dimensions_initial_state_and_fixed_flag() -> None:
    s = parse_scene(
        _body(**_ball(initial={"position": [0, 0, 1], "velocity": [1, 0, 0], "omega": [0, 0, 2]}))
    )
    (b,) = s.bodies
    assert (b.name, b.shape, b.mass, b.dims, b.fixed) == (
        "a",
        "solid_sphere",
        2.0,
        {"radius": 0.5},
        False,
    )
    assert b.initial == {
        "position": [0.0, 0.0, 1.0],
        "velocity": [1.0, 0.0, 0.0],
        "omega": [0.0, 0.0, 2.0],
    }
    assert s.body("a") is b
    box = parse_scene(_body(name="b_1-x", shape="box", mass=1.0, a=0.3, b=0.2, c=0.1)).bodies[0]
    assert box.dims == {"a": 0.3, "b": 0.2, "c": 0.1}
    wall = parse_scene(
        {**_body(name="w", shape="point", mass=1.0, fixed=True), "effects": []}
    ).bodies[0]
    assert wall.fixed is True


def test_principal_moments_on_the_triangle_inequality_are_accepted() -> None:
    for J in ([1.0, 1.0, 2.0], [2.0, 1.0, 1.0], [0.5, 0.25, 0.75]):  # J3 = J1 + J2, flat
        b = parse_scene(_body(name="a", shape="custom", mass=1.0, inertia=J)).bodies[0]
        assert b.dims == {"inertia": J}
    # beyond J1 + J2 by an ulp of 2: within the slack 1e-15 for the rounding of sums
    J = [1.0, 1.0, math.nextafter(2.0, 3.0)]
    assert parse_scene(_body(name="a", shape="custom", mass=1.0, inertia=J)).bodies[0].dims == {
        "inertia": J
    }


def test_a_tank_has_no_mass_and_its_area_is_in_the_domain_up_to_its_edge() -> None:
    d = {
        "scene": {"name": "t", "duration": 1.0},
        "bodies": [{"name": "t", "shape": "tank", "area": 2.0**80, "initial": {"level": 1.0}}],
        "effects": [
            {"type": "gravity", "g": 9.81},
            {"type": "tank_outflow", "body": "t", "hole_area": 1e-3},
        ],
    }
    (b,) = parse_scene(d).bodies
    assert (b.mass, b.dims, b.initial) == (0.0, {"area": 2.0**80}, {"level": 1.0})
    d["bodies"][0]["area"] = 1e300
    with pytest.raises(SceneError, match=r"bodies\[0\]\.area: 1e\+300 is too large"):
        parse_scene(d)


# --------------------------------------------------------------------- [[effects]]


def _effect(**fields):
    return _with(["effects"], [fields])


EFFECT_CASES = [
    (
        "effect not a table",
        _with(["effects"], ["gravity"]),
        "effects[0]",
        "expected a table, got a string",
    ),
    ("no type", _effect(g=9.81), "effects[0].type", "missing required field"),
    ("type not a string", _effect(type=1), "effects[0].type", "expected a string, got int 1"),
    (
        "unknown effect",
        _effect(type="magnetism"),
        "effects[0].type",
        f"unknown effect 'magnetism' (known: {', '.join(EFFECT_FIELDS)})",
    ),
    (
        "unknown effect field",
        _effect(type="gravity", g=9.81, colour="red"),
        "effects[0].colour",
        "unknown field (allowed: direction, g, type)",
    ),
    (
        "missing effect field",
        _effect(type="spring", body="a"),
        "effects[0].stiffness",
        "missing required field (a spring effect needs it)",
    ),
    (
        "bad effect value",
        _effect(type="gravity", g=-9.81),
        "effects[0].g",
        "must be > 0 (non-physical otherwise); got -9.81",
    ),
    (
        "unknown body",
        _effect(type="torsion", body="z", stiffness=1.0),
        "effects[0].body",
        "unknown body 'z' (bodies: a)",
    ),
    (
        "zero direction",
        _effect(type="gravity", g=9.81, direction=[0, 0, 0]),
        "effects[0].direction",
        "must be a nonzero vector",
    ),
    (
        "zero axis",
        _effect(type="fixed_axis", body="a", axis=[0.0, 0.0, 0.0]),
        "effects[0].axis",
        "must be a nonzero vector",
    ),
    (
        "zero plane normal",
        _effect(type="impact", body="a", restitution=0.5, plane_normal=[0, 0, 0]),
        "effects[0].plane_normal",
        "must be a nonzero vector",
    ),
]


@pytest.mark.parametrize(
    ("data", "field", "reason"), [c[1:] for c in EFFECT_CASES], ids=[c[0] for c in EFFECT_CASES]
)
def test_a_bad_effect_is_refused_naming_field_and_reason(data, field, reason) -> None:
    err = _refusal(copy.deepcopy(data))
    assert (err.field, err.reason) == (field, reason)


def test_effects_keep_their_index_fields_and_order() -> None:
    d = _base()
    d["bodies"][0]["initial"] = {"position": [0.0, 0.0, 1.0]}
    d["effects"] = [
        {"type": "gravity", "g": 9.81, "direction": [0, 0, -2]},
        {"type": "spring", "body": "a", "stiffness": 2, "anchor": [0, 0, 3]},
        {"type": "gravity", "g": 1.0},
    ]
    s = parse_scene(d)
    assert s.effect_types == ("gravity", "spring", "gravity")
    assert [e.where for e in s.effects] == ["effects[0]", "effects[1]", "effects[2]"]
    assert s.effects[0].fields == {"g": 9.81, "direction": [0.0, 0.0, -2.0]}
    assert s.effects[1].fields == {"body": "a", "stiffness": 2.0, "anchor": [0.0, 0.0, 3.0]}
    assert [e.index for e in s.effects_of("gravity")] == [0, 2]
    assert s.effects_of("drag") == []
    err = s.error("scene.duration", "too long")
    assert (err.source, err.field, err.reason) == ("<scene>", "scene.duration", "too long")


def test_the_combination_is_validated_after_the_fields() -> None:
    # every field is fine, the combination is not (a point cannot spin)
    err = _refusal(_body(name="a", shape="point", mass=1.0, initial={"omega": [0, 0, 1.0]}))
    assert (err.field, err.reason) == (
        "bodies[0].initial.omega",
        "a point has no attitude and no rotation",
    )


# --------------------------------------------------------------------------- files


def test_a_scene_file_is_read_as_toml_and_named_by_its_path(tmp_path) -> None:
    p = tmp_path / "drop.toml"
    p.write_text(
        '[scene]\nname = "drop"\nduration = 2.0\n\n[[bodies]]\nname = "b"\nshape = "point"\n'
        'mass = 1.0\n\n[[effects]]\ntype = "gravity"\ng = 9.81\n',
        encoding="utf-8",
    )
    s = load_scene(p)
    assert (s.name, s.source, s.duration, s.effect_types) == ("drop", str(p), 2.0, ("gravity",))
    p.write_text('[scene]\nname = "drop"\nduration = -2.0\n', encoding="utf-8")
    with pytest.raises(SceneError) as info:
        load_scene(p)
    assert (info.value.source, info.value.field) == (str(p), "scene.duration")


def test_an_unreadable_file_is_named_with_the_reason(tmp_path) -> None:
    missing = tmp_path / "nope.toml"
    with pytest.raises(SceneError) as info:
        load_scene(missing)
    err = info.value
    assert (err.source, err.field, err.reason) == (
        str(missing),
        "(file)",
        "cannot read: No such file or directory",
    )
    assert err.__suppress_context__
    with pytest.raises(SceneError) as info:
        load_scene(tmp_path)
    assert (info.value.field, info.value.reason) == ("(file)", "cannot read: Is a directory")


def test_a_file_that_is_not_utf8_or_not_toml_is_named(tmp_path) -> None:
    p = tmp_path / "bin.toml"
    p.write_bytes(b'[scene]\nname = "caf\xe9"\n')
    with pytest.raises(SceneError) as info:
        load_scene(p)
    assert (info.value.source, info.value.field, info.value.reason) == (
        str(p),
        "(file)",
        "not UTF-8 text",
    )
    assert info.value.__suppress_context__
    p.write_text("[scene\n", encoding="utf-8")
    with pytest.raises(SceneError) as info:
        load_scene(p)
    assert (info.value.source, info.value.field) == (str(p), "(syntax)")
    assert info.value.reason.startswith("invalid TOML: ")
    assert "line 1" in info.value.reason  # tomllib's own account of where
    assert info.value.__suppress_context__
