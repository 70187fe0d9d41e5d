"""Bad scene files: each gives a SceneError naming the file, the field and the reason;
nothing in a file is evaluated as code."""

from __future__ import annotations

import pytest

from mechanics.scenes import SceneError, builtin_scenes, load_scene

BALL = builtin_scenes()["bouncing_ball"].read_text()
TRACK = builtin_scenes()["cylinder_in_track"].read_text()
ROCKET = builtin_scenes()["rocket"].read_text()
CAROUSEL = builtin_scenes()["carousel"].read_text()

#: (id, base text, replace this, with that, field, reason)
CASES = [
    (
        "unknown effect",
        BALL,
        'type = "gravity"',
        'type = "magnetism"',
        "effects[0].type",
        "unknown effect 'magnetism'",
    ),
    (
        "unknown body shape",
        BALL,
        'shape = "solid_sphere"',
        'shape = "blob"',
        "bodies[0].shape",
        "unknown body shape 'blob'",
    ),
    (
        "unknown body name",
        BALL,
        'body = "ball"',
        'body = "bal"',
        "effects[1].body",
        "unknown body 'bal'",
    ),
    ("missing field", BALL, "duration = 8.0\n", "", "scene.duration", "missing required field"),
    (
        "missing effect field",
        BALL,
        "restitution = 0.8333333333333334\n",
        "",
        "effects[1].restitution",
        "missing required field",
    ),
    (
        "wrong type",
        BALL,
        "mass = 0.5",
        'mass = "heavy"',
        "bodies[0].mass",
        "expected a number in SI units, got a string 'heavy'",
    ),
    (
        "units in a string",
        BALL,
        "g = 9.81",
        'g = "9.81 m/s^2"',
        "effects[0].g",
        "units are not parsed",
    ),
    (
        "wrong unit system",
        BALL,
        'system = "SI"',
        'system = "CGS"',
        "units.system",
        "only SI units are supported",
    ),
    (
        "vector of wrong length",
        BALL,
        "plane_normal = [0.0, 0.0, 1.0]",
        "plane_normal = [0.0, 1.0]",
        "effects[1].plane_normal",
        "expected an array of 3 numbers",
    ),
    ("negative mass", BALL, "mass = 0.5", "mass = -0.5", "bodies[0].mass", "must be > 0"),
    ("zero gravity", BALL, "g = 9.81", "g = 0.0", "effects[0].g", "must be > 0"),
    (
        "restitution above 1",
        BALL,
        "restitution = 0.8333333333333334",
        "restitution = 1.2",
        "effects[1].restitution",
        "must lie in [0, 1]; got 1.2",
    ),
    (
        "restitution below 0",
        BALL,
        "restitution = 0.8333333333333334",
        "restitution = -0.1",
        "effects[1].restitution",
        "must lie in [0, 1]; got -0.1",
    ),
    (
        "unknown field (typo)",
        BALL,
        "restitution = 0.8333333333333334",
        "restitutoin = 0.8",
        "effects[1].restitutoin",
        "unknown field",
    ),
    ("start inside the floor", BALL, "7.439449541284404", "0.05", "effects[1]", "overlap at t = 0"),
    (
        "track smaller than the body",
        TRACK,
        "track_radius = 0.5",
        "track_radius = 0.05",
        "effects[1].track_radius",
        "must exceed the body's radius",
    ),
    (
        "fuel heavier than the rocket",
        ROCKET,
        "fuel_mass = 800.0",
        "fuel_mass = 1000.0",
        "effects[1].fuel_mass",
        "must be less than the body's mass",
    ),
    (
        "bullets from inside",
        CAROUSEL,
        "rate = 0.1",
        "rate = -0.1",
        "effects[1].rate",
        "must be ≥ 0",
    ),
    (
        "incompatible effects",
        BALL,
        "restitution = 0.8333333333333334\n",
        'restitution = 0.8333333333333334\n\n[[effects]]\ntype = "fixed_axis"\nbody = "ball"\n'
        '\n[[effects]]\ntype = "fixed_point"\nbody = "ball"\ndistance = 0.1\n',
        "effects[3].type",
        "cannot be combined with 'fixed_axis'",
    ),
    (
        "non-physical inertia",
        BALL,
        'shape = "solid_sphere"\nmass = 0.5\nradius = 0.1',
        'shape = "custom"\nmass = 0.5\ninertia = [1.0, 1.0, 3.0]',
        "bodies[0].inertia",
        "triangle inequality",
    ),
    (
        "code in a value",
        BALL,
        "g = 9.81",
        "g = \"__import__('os').system('echo hi')\"",
        "effects[0].g",
        "expected a number",
    ),
    ("bad TOML", BALL, "[scene]", "[scene", "(syntax)", "invalid TOML"),
]


@pytest.mark.parametrize(
    ("base", "old", "new", "field", "reason"), [c[1:] for c in CASES], ids=[c[0] for c in CASES]
)
def test_bad_scene_file_names_file_field_and_reason(
    tmp_path, base, old, new, field, reason
) -> None:
    assert old in base, "the case must change the file"
    p = tmp_path / "bad_scene.toml"
    p.write_text(base.replace(old, new, 1))
    with pytest.raises(SceneError) as info:
        load_scene(p)
    err = info.value
    assert err.source == str(p)
    assert err.field == field
    assert reason in err.reason
    assert str(err).startswith(f"{p}: {field}: ")
    assert "\n" not in str(err)


def test_the_unmodified_files_are_valid(tmp_path) -> None:
    for text in (BALL, TRACK, ROCKET, CAROUSEL):
        p = tmp_path / "ok.toml"
        p.write_text(text)
        load_scene(p)


def test_code_in_a_string_is_never_run(tmp_path) -> None:
    marker = tmp_path / "pwned"
    p = tmp_path / "evil.toml"
    p.write_text(
        BALL.replace("g = 9.81", f"g = \"__import__('pathlib').Path('{marker}').touch()\"")
    )
    with pytest.raises(SceneError):
        load_scene(p)
    assert not marker.exists()


def test_missing_file_is_a_scene_error(tmp_path) -> None:
    with pytest.raises(SceneError, match="cannot read"):
        load_scene(tmp_path / "nope.toml")


def test_exact_requested_without_an_exact_flow(tmp_path) -> None:
    text = BALL.replace("samples = 801", 'samples = 801\nmethod = "exact"').replace(
        '[[effects]]\ntype = "impact"',
        '[[effects]]\ntype = "spring"\nbody = "ball"\nstiffness = 1.0\n\n[[effects]]\ntype = "impact"',
    )
    p = tmp_path / "s.toml"
    p.write_text(text.replace('compare = "E6.1"\n', ""))
    from mechanics.scenes import run_scene

    with pytest.raises(SceneError, match=r"scene\.method: 'exact' requested"):
        run_scene(load_scene(p))
