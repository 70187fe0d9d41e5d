"""Hostile scene files: each field pushed to an extreme in an otherwise valid scene ends in
a one-line refusal (exit 2, naming the file, the field, the value and the reason) or an
honest result, never a traceback, a warning, a JSON error or a PASSED on NaN
(:mod:`mechanics.scenes.budget`, :mod:`mechanics.scenes.domain`).

The six cases are those a new user tried: samples = 10⁷ and 10⁹, a velocity of 1e154 or
1e300, a box spun at 1e200 rad/s or at 1e8 rad/s under gravity above a floor, a ball at
z = 1e300, and a duration of 1e300 s.
"""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest

from identities.cli.main import main
from mechanics.scenes import parse_scene, run_scene
from mechanics.scenes.budget import DEFAULT_MAX_MEMORY, BudgetError, Clock, memory_estimate
from mechanics.scenes.domain import ANGLE_MAX, MAGNITUDE_MAX
from mechanics.scenes.result import ConservedReport, _json_safe
from mechanics.scenes.spec import SceneError

from .builders import ball as _ball
from .builders import box as _box
from .builders import scene_data


def _ball_scene(*, samples=201, duration=1.0, position=(0, 0, 1.0), velocity=(0, 0, 0), floor=True):
    eff = [{"type": "gravity", "g": 9.81}]
    if floor:
        eff.append(
            {
                "type": "impact",
                "body": "ball",
                "plane_point": [0.0, 0.0, 0.0],
                "plane_normal": [0.0, 0.0, 1.0],
                "restitution": 0.8,
            }
        )
    ball = _ball("ball", position, velocity, mass=0.5)
    return scene_data([ball], eff, name="hostile", duration=duration, samples=samples)


def _box_scene(omega, *, floor=True):
    eff = [{"type": "gravity", "g": 9.81}]
    if floor:
        eff.append(
            {
                "type": "impact",
                "body": "box",
                "plane_point": [0.0, 0.0, 0.0],
                "plane_normal": [0.0, 0.0, 1.0],
                "restitution": 0.5,
            }
        )
    box = _box("box", [0, 0, 1.0], [0, 0, 0], omega=omega)
    return scene_data([box], eff, name="hostile_box", duration=1.0)


def _toml(data: dict) -> str:
    """A scene dict as TOML (only the forms these scenes use)."""

    def val(v):
        if isinstance(v, str):
            return json.dumps(v)
        if isinstance(v, list):
            return "[" + ", ".join(val(x) for x in v) + "]"
        if isinstance(v, float):
            return (
                repr(v) if math.isfinite(v) else {math.inf: "inf", -math.inf: "-inf"}.get(v, "nan")
            )
        return repr(v)

    def table(d):
        lines, subs = [], []
        for k, v in d.items():
            (subs if isinstance(v, dict) else lines).append((k, v))
        out = [f"{k} = {val(v)}" for k, v in lines]
        for k, v in subs:
            out.append(f"{k} = {{ " + ", ".join(f"{a} = {val(b)}" for a, b in v.items()) + " }")
        return out

    out = ["[scene]", *table(data["scene"])]
    for b in data["bodies"]:
        out += ["", "[[bodies]]", *table(b)]
    for e in data["effects"]:
        out += ["", "[[effects]]", *table(e)]
    return "\n".join(out) + "\n"


def _cli(tmp_path, capsys, data, *extra):
    path = tmp_path / "hostile.toml"
    path.write_text(_toml(data), encoding="utf-8")
    code = main(["scene", str(path), *extra])
    out, err = capsys.readouterr()
    return code, out, err, str(path)


def _assert_refused(code, out, err, path, *words):
    assert code == 2, (code, out, err)
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith(f"bodycheck: error: {path}: "), lines[0]
    for w in words:
        assert w in lines[0], (w, lines[0])
    assert out == ""


@pytest.mark.parametrize("samples", [10**7, 10**9])
def test_samples_beyond_the_memory_budget_are_refused_before_anything_is_allocated(
    tmp_path, capsys, samples
):
    code, out, err, path = _cli(tmp_path, capsys, _ball_scene(samples=samples), "--json")
    _assert_refused(code, out, err, path, "scene.samples", str(samples), "--max-samples")


def test_the_memory_estimate_names_its_parts_and_the_limit_holds_under_the_budget():
    scene = parse_scene(_ball_scene(samples=10**7))
    with pytest.raises(BudgetError, match=r"samples × \d+ numbers × 8 bytes") as info:
        run_scene(scene)
    assert "up to" in str(info.value)
    # the largest refused and the smallest allowed: the limit is what the budget holds
    limit = int(str(info.value).split("up to ")[1].split()[0])
    assert memory_estimate(scene, limit) <= DEFAULT_MAX_MEMORY < memory_estimate(scene, limit + 1)


def test_max_samples_lets_a_user_ask_for_more_and_caps_below_the_default(tmp_path, capsys):
    code, out, err, path = _cli(tmp_path, capsys, _ball_scene(samples=50), "--max-samples", "20")
    _assert_refused(code, out, err, path, "scene.samples", "max_samples = 20")
    code, out, err, _ = _cli(tmp_path, capsys, _ball_scene(samples=50), "--max-samples", "50")
    assert code == 0, err


@pytest.mark.parametrize(
    ("velocity", "field"),
    [([1e154, 0, -1e154], "velocity[0]"), ([0, 0, -1e300], "velocity[2]")],
)
def test_a_velocity_beyond_the_domain_is_refused_naming_field_value_and_domain(
    tmp_path, capsys, velocity, field
):
    code, out, err, path = _cli(tmp_path, capsys, _ball_scene(velocity=velocity), "--json")
    _assert_refused(code, out, err, path, f"bodies[0].initial.{field}", "too large", "2⁸⁰")


def test_a_ball_at_1e300_and_a_duration_of_1e300_are_refused(tmp_path, capsys):
    code, out, err, path = _cli(tmp_path, capsys, _ball_scene(position=[0, 0, 1e300]))
    _assert_refused(code, out, err, path, "bodies[0].initial.position[2]", "1e+300")
    code, out, err, path = _cli(tmp_path, capsys, _ball_scene(duration=1e300, floor=False))
    _assert_refused(code, out, err, path, "scene.duration", "1e+300", "too large")


def test_a_box_spun_at_1e200_is_refused_and_at_1e8_over_a_floor_is_refused_by_its_steps(
    tmp_path, capsys
):
    code, out, err, path = _cli(tmp_path, capsys, _box_scene([1e200, 0, 0]))
    _assert_refused(code, out, err, path, "bodies[0].initial.omega[0]", "1e+200")
    code, out, err, path = _cli(tmp_path, capsys, _box_scene([1e8, 1, 0]))
    _assert_refused(code, out, err, path, "scene.duration", "steps", "--max-steps")
    # torque-free, the same spin has an exact flow: no steps, a finite result
    code, out, err, _ = _cli(tmp_path, capsys, _box_scene([1e8, 1, 0], floor=False), "--json")
    assert code == 0, err
    assert '"passed": true' in out


def test_a_run_that_reaches_its_wall_time_bound_stops_with_the_time_it_reached(tmp_path, capsys):
    # the estimate passes (≈ 190 steps for 3 s); a bound of 1 ns is reached at the first step
    data = _ball_scene(duration=3.0)
    data["scene"]["method"] = "integrate"
    code, out, err, path = _cli(tmp_path, capsys, data, "--max-seconds", "1e-9")
    _assert_refused(code, out, err, path, "(run): stopped at t = 0 s of 3 s", "--max-seconds")


def test_the_clock_stops_at_the_step_bound_naming_the_time_reached():
    scene = parse_scene(_ball_scene(), source="c.toml")
    scene = dataclasses.replace(scene, max_steps=3)
    clock = Clock(scene)
    for t in (0.1, 0.2, 0.3):
        clock.step(t)
    with pytest.raises(
        BudgetError, match=r"^c\.toml: \(run\): stopped at t = 0\.4 s of 1 s after 3 steps"
    ):
        clock.step(0.4)


def test_a_bad_budget_option_is_refused_in_one_line(tmp_path, capsys):
    for opt, bad in (("--max-samples", "1"), ("--max-steps", "0"), ("--max-seconds", "-1")):
        code, _out, err, _ = _cli(tmp_path, capsys, _ball_scene(), opt, bad)
        assert code == 2
        assert len(err.strip().splitlines()) == 1
        assert opt in err
        assert bad in err


@pytest.mark.parametrize(("where", "value"), [("mass", MAGNITUDE_MAX * 2), ("radius", 1e30)])
def test_a_body_number_beyond_the_magnitude_domain_is_refused(where, value):
    data = _ball_scene(floor=False)
    data["bodies"][0][where] = value
    with pytest.raises(SceneError, match="too large") as info:
        parse_scene(data, source="d.toml")
    assert str(info.value).startswith(f"d.toml: bodies[0].{where}: {value!r}")


def test_zero_subnormals_and_the_domains_edge_are_accepted_and_run_finite():
    data = _ball_scene(floor=False, velocity=[0.0, 5e-324, -MAGNITUDE_MAX])
    data["bodies"][0]["mass"] = MAGNITUDE_MAX
    result = run_scene(parse_scene(data))
    assert result.self_checks[0].name == "every reported number finite"
    assert result.self_checks[0].ok, result.self_checks[0].reason


def test_an_angle_beyond_its_domain_is_refused_and_at_its_edge_accepted():
    data = _box_scene([0, 0, 1.0], floor=False)
    data["bodies"][0]["initial"]["theta"] = ANGLE_MAX
    parse_scene(data)
    data["bodies"][0]["initial"]["theta"] = 2 * ANGLE_MAX
    with pytest.raises(SceneError, match="angles' domain"):
        parse_scene(data)


def test_rtol_below_dop853s_floor_is_refused():
    data = _ball_scene()
    data["scene"]["rtol"] = 1e-15
    with pytest.raises(SceneError, match=r"scene\.rtol"):
        parse_scene(data)


def test_a_nan_conserved_value_or_drift_is_never_ok():
    assert not ConservedReport("E", math.nan, 0.0, 1e-12).ok
    assert not ConservedReport("E", 1.0, math.nan, 1e-12).ok
    assert not ConservedReport("E", math.inf, 0.0, 1e-12).ok
    assert ConservedReport("E", 1.0, 0.0, 1e-12).ok


def test_json_names_a_non_finite_number_instead_of_failing():
    safe = _json_safe({"a": [1.0, math.nan], "b": {"c": -math.inf}, "d": np.float64(math.inf)})
    assert safe == {"a": [1.0, "nan"], "b": {"c": "-inf"}, "d": "inf"}
    json.dumps(safe, allow_nan=False)


def test_a_book_comparison_whose_closed_form_is_not_finite_is_refused(tmp_path, capsys):
    # found by the whole-scene fuzz: the flip at ω2 = 6.9e15 rad/s (within the domain) puts
    # the closed form 4K(m)/λ beyond float64 (NaN); the run is refused, not printed with NaN
    data = {
        "scene": {"name": "flip", "compare": "5.3.3", "duration": 50.0, "samples": 4},
        "bodies": [
            {
                "name": "body",
                "shape": "custom",
                "mass": 1.0,
                "inertia": [1.0, 2.0, 3.0],
                "initial": {"omega": [0.02, 6921845621499839.0, 0.0]},
            }
        ],
        "effects": [],
    }
    code, out, err, path = _cli(tmp_path, capsys, data, "--json")
    _assert_refused(code, out, err, path, "scene.compare", "closed form", "nan")
