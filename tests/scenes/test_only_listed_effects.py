"""A scene assembles exactly the effects it lists: an effect it does not list is never
constructed nor evaluated; there is no default gravity and no hidden damping."""

from __future__ import annotations

import dataclasses
import re
import subprocess
import sys
from collections import Counter
from pathlib import Path

import numpy as np
import pytest

from mechanics._floats import EPS
from mechanics.scenes import builtin_scenes, load_scene, parse_scene, run_scene
from mechanics.scenes import effects as fx

#: DOP853 at rtol = atol = 1e-12 over ~6 periods of an O(1) oscillator: global error
#: ~1e-11 relative; 2^20 eps = 2.3e-10 leaves a factor of 20
INTEGRATED_RTOL = 2**20 * EPS
#: an event on a straight free flight (no integration error) and one closed-form impact
EVENT_RTOL = 2**10 * EPS

NAMES = list(builtin_scenes())


def _instrument(monkeypatch, listed: set[str]) -> Counter:
    """Unlisted effect classes raise on any use (even construction); listed ones count."""
    calls: Counter = Counter()
    for kind, cls in fx.EFFECT_CLASSES.items():
        for attr, fn in list(vars(cls).items()):
            if not callable(fn) or (attr.startswith("__") and attr != "__init__"):
                continue
            if kind in listed:

                def counted(*a, _fn=fn, _key=f"{kind}.{attr}", **k):
                    calls[_key] += 1
                    return _fn(*a, **k)

                monkeypatch.setattr(cls, attr, counted)
            else:

                def boom(*a, _key=f"{kind}.{attr}", **k):
                    raise AssertionError(f"unlisted effect code ran: {_key}")

                monkeypatch.setattr(cls, attr, boom)
    return calls


@pytest.mark.parametrize("name", NAMES)
@pytest.mark.parametrize("method", ["auto", "integrate"])
def test_unlisted_effects_never_run(monkeypatch, name, method) -> None:
    scene = dataclasses.replace(load_scene(builtin_scenes()[name]), method=method)
    listed = set(scene.effect_types)
    calls = _instrument(monkeypatch, listed)
    result = run_scene(scene)
    assert result.passed
    ran = {k.split(".")[0] for k in calls}
    assert ran <= listed
    # positive control: every listed effect was built (its __init__ counted)
    assert {k.split(".")[0] for k in calls if k.endswith(".__init__")} == listed


def test_the_instrument_catches_an_unlisted_effect(monkeypatch) -> None:
    """Negative control: if gravity were assembled without being listed, the test sees it."""
    scene = load_scene(builtin_scenes()["bouncing_ball"])
    _instrument(monkeypatch, {"impact"})  # pretend gravity is not listed
    with pytest.raises(AssertionError, match="unlisted effect code ran: gravity"):
        run_scene(scene)


def test_integration_calls_each_listed_force_once_per_stage(monkeypatch) -> None:
    scene = dataclasses.replace(load_scene(builtin_scenes()["rocket"]), method="integrate")
    calls = _instrument(monkeypatch, {"gravity", "thrust"})
    run_scene(scene)
    assert calls["gravity.loads"] == calls["thrust.loads"] > 100


def _free(effects, **initial):
    return parse_scene(
        {
            "scene": {"name": "t", "duration": 20.0, "samples": 401, "method": "integrate"},
            "bodies": [{"name": "b", "shape": "point", "mass": 2.0, "initial": initial}],
            "effects": effects,
        },
        source="test.toml",
    )


def test_no_effects_means_no_gravity_and_uniform_motion() -> None:
    r = run_scene(_free([], position=[0.0, 0.0, 5.0], velocity=[1.0, 0.0, 0.0]))
    s = r.trajectory.series
    assert np.all(s["z"] == 5.0), "no default gravity"
    np.testing.assert_allclose(s["x"], r.trajectory.t, rtol=1e-13, atol=1e-13)
    assert r.passed


def test_spring_oscillator_has_no_hidden_damping() -> None:
    spring = {"type": "spring", "body": "b", "anchor": [0.0, 0.0, 0.0], "stiffness": 8.0}
    r = run_scene(_free([spring], position=[1.0, 0.0, 0.0]))  # ω = 2 rad/s, ~6 periods
    x = r.trajectory.series["x"]
    E = r.trajectory.series["E"]
    assert abs(E[-1] - E[0]) <= INTEGRATED_RTOL * E[0]
    np.testing.assert_allclose(x, np.cos(2.0 * r.trajectory.t), atol=INTEGRATED_RTOL * 10)
    assert [c.name for c in r.conserved if c.name == "E"] == ["E"]


@pytest.mark.parametrize(("method", "how"), [("auto", "exact"), ("integrate", "integrated")])
def test_two_spheres_collide_as_events_with_momentum_conserved(method, how) -> None:
    scene = parse_scene(
        {
            "scene": {"name": "t", "duration": 2.0, "samples": 201},
            "bodies": [
                {
                    "name": "a",
                    "shape": "solid_sphere",
                    "mass": 1.0,
                    "radius": 0.1,
                    "initial": {"position": [0.0, 0.0, 0.0], "velocity": [1.0, 0.0, 0.0]},
                },
                {
                    "name": "b",
                    "shape": "solid_sphere",
                    "mass": 3.0,
                    "radius": 0.1,
                    "initial": {"position": [1.0, 0.0, 0.0]},
                },
            ],
            "effects": [{"type": "impact", "body": "b", "other": "a", "restitution": 0.5}],
        },
        source="two.toml",
    )
    r = run_scene(dataclasses.replace(scene, method=method))
    assert r.method.startswith(how)
    (ev,) = r.trajectory.events
    assert ev.t == pytest.approx(0.8, rel=EVENT_RTOL)  # gap 0.8 closed at 1 m/s
    s = r.trajectory.series
    assert np.all(s["b.x"] - s["a.x"] >= 0.2 - EVENT_RTOL), "never interpenetrating"
    # (6.36)–(6.38): v_a' = 1 − 1.5·3/4 = −0.125, v_b' = 1.5/4 = 0.375
    assert s["a.vx"][-1] == pytest.approx(-0.125, rel=EVENT_RTOL)
    assert s["b.vx"][-1] == pytest.approx(0.375, rel=EVENT_RTOL)
    assert {c.name for c in r.conserved} >= {"p_x", "p_y", "p_z"}
    assert r.passed


def test_mechanics_scenes_imports_neither_sympy_nor_matplotlib() -> None:
    code = (
        "import sys, mechanics.scenes as s;"
        "s.run_scene(s.load_scene(s.builtin_path('heavy_top')));"
        "bad = [m for m in ('sympy', 'matplotlib') if m in sys.modules];"
        "print(bad); sys.exit(1 if bad else 0)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stdout + out.stderr


def test_scene_code_never_evaluates_text() -> None:
    src = Path(fx.__file__).parent
    for p in src.glob("*.py"):
        text = p.read_text()
        found = re.findall(r"(?<![\w.])(?:eval|exec|compile|__import__)\(|sympify|sympy", text)
        assert not found, f"{p.name} contains {found}"
