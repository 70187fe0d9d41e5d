"""The scene-file reference is generated from the schema: current in docs/, complete in
its units, and every example it shows is a valid effect."""

from __future__ import annotations

from pathlib import Path

import pytest

from mechanics.scenes import parse_scene
from mechanics.scenes.effects import REGISTRY
from mechanics.scenes.reference import scene_file_reference
from mechanics.scenes.spec import INITIAL_DOC, INITIAL_KEYS

DOC = Path(__file__).resolve().parents[2] / "docs" / "scene-files.md"


def test_the_reference_in_docs_is_current() -> None:
    assert DOC.read_text(encoding="utf-8") == scene_file_reference(), (
        "docs/scene-files.md is stale: run `make checks`"
    )


@pytest.mark.parametrize("kind", sorted(REGISTRY))
def test_every_field_has_a_unit(kind) -> None:
    cls = REGISTRY[kind]
    assert set(cls.units) == set(cls.schema), kind


def test_every_initial_key_is_documented() -> None:
    assert set(INITIAL_DOC) == set(INITIAL_KEYS)


#: what each example needs beside it (the bodies it names, a gravity, a joint)
BALL = {"name": "ball", "shape": "solid_sphere", "mass": 1.0, "radius": 0.1}
ROD = {"name": "rod", "shape": "rod", "mass": 1.0, "length": 1.0}
TOP = {"name": "top", "shape": "box", "mass": 1.0, "a": 0.1, "b": 0.1, "c": 0.2}
TANK = {"name": "tank", "shape": "tank", "area": 1.0, "initial": {"level": 1.0}}
HINGE = {
    "type": "fixed_axis",
    "body": "rod",
    "axis": [0.0, 1.0, 0.0],
    "distance": 0.5,
    "body_axis": "y",
}
CONTEXT = {
    "torsion": ([ROD], [HINGE]),
    "mass_flow": ([ROD], [HINGE]),
    "fixed_axis": ([ROD], []),
    "fixed_point": ([TOP | {"initial": {"theta": 0.5}}], []),
    "torque": ([ROD], []),
    "tank_outflow": ([TANK], []),
    "newton_gravity": ([BALL, BALL | {"name": "moon", "initial": {"position": [1.0, 0, 0]}}], []),
    "impact": ([BALL | {"initial": {"position": [0.0, 0.0, 1.0]}}], []),
}


@pytest.mark.parametrize("kind", sorted(REGISTRY))
def test_every_example_is_a_valid_effect(kind) -> None:
    bodies, extra = CONTEXT.get(kind, ([BALL], []))
    effects = [{"type": "gravity", "g": 9.81}, *extra, REGISTRY[kind].example]
    scene = parse_scene(
        {"scene": {"name": "ex", "duration": 1.0}, "bodies": bodies, "effects": effects},
        source="example.toml",
    )
    assert scene.effects[-1].type == kind
