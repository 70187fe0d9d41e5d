"""Shared set-up of the effects' unit tests: a tiny scene parsed from tables, the
engine's effect objects built from it, a refusal and its words; the walls of the unit
box (the groups' tests and the balls-in-a-box benchmark)."""

from __future__ import annotations

import re

import pytest

from mechanics.scenes import SceneError
from mechanics.scenes.engine import Engine

from .builders import scene

#: the six walls of the unit box [0, 1]³, normals inward (an impact group's ``planes``)
WALLS = [
    {"point": [0.0, 0.0, 0.0], "normal": [1.0, 0.0, 0.0]},
    {"point": [1.0, 0.0, 0.0], "normal": [-1.0, 0.0, 0.0]},
    {"point": [0.0, 0.0, 0.0], "normal": [0.0, 1.0, 0.0]},
    {"point": [0.0, 1.0, 0.0], "normal": [0.0, -1.0, 0.0]},
    {"point": [0.0, 0.0, 0.0], "normal": [0.0, 0.0, 1.0]},
    {"point": [0.0, 0.0, 1.0], "normal": [0.0, 0.0, -1.0]},
]


def scene_of(bodies, effects, *, duration=1.0):
    """The scene of ``bodies`` and ``effects`` read from the file unit.toml."""
    return scene(bodies, effects, name="unit", duration=duration)


def build(bodies, effects):
    """The engine's effect objects, and the engine (its layout, its guides)."""
    eng = Engine(scene_of(bodies, effects))
    return eng.effects, eng


def refusal(bodies, effects, *, duration=1.0) -> SceneError:
    """The scene's refusal, which names the scene file first."""
    with pytest.raises(SceneError) as info:
        scene_of(bodies, effects, duration=duration)
    assert str(info.value).startswith("unit.toml: ")
    return info.value


def word(text: str) -> str:
    return rf"(?<![A-Za-z0-9_]){re.escape(text)}(?![A-Za-z0-9_])"


def assert_says(err: SceneError, field: str, *phrases: str) -> None:
    """The error names exactly ``field`` and says each phrase as words of its own."""
    assert err.field == field
    for p in phrases:
        assert re.search(word(p), err.reason), (p, err.reason)
