"""The scenes' imports point one way: spec → simulate → engine → its rooms (integrate →
modes, support, collision → impacts → forward → model) → effects → state → errors, with no
cycle; mechanics never imports the book layer (identities)."""

from __future__ import annotations

import ast
import functools
from pathlib import Path

import pytest

import mechanics
import mechanics.scenes

SCENES = Path(mechanics.scenes.__file__).parent
#: each module of mechanics/scenes with its layer: a module may import only lower layers
LAYERS = {
    "vectors": 0,
    "errors": 1,
    "trajectory": 1,
    "contacts": 1,
    "bodies": 1,
    "_kernels": 1,
    "state": 2,
    "budget": 2,
    "domain": 2,
    "effects": 3,
    "splitting": 4,
    "model": 4,
    "compiled": 4,
    "forward": 5,
    "impacts": 6,
    "report": 6,
    "collision": 7,
    "modes": 8,
    "support": 8,
    "flows": 8,
    "integrate": 9,
    "engine": 10,
    "derived": 11,
    "simulate": 12,
    "spec": 13,
    "result": 14,
    "reference": 14,
    "__init__": 15,
}


def _module_of(path: Path) -> str:
    rel = path.relative_to(SCENES)
    return (
        rel.parts[0].removesuffix(".py")
        if len(rel.parts) == 1 or rel.parts[0] != "effects"
        else "effects"
    )


def _type_checking(test: ast.expr) -> bool:
    """Is this the test of an ``if TYPE_CHECKING:`` (or ``typing.TYPE_CHECKING``)?"""
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"
    )


def _scene_imports(path: Path) -> set[str]:
    """The sibling modules of mechanics/scenes that a file imports at run time (at any
    depth; an import under ``if TYPE_CHECKING:``, for annotations only, is not one)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    for node in list(ast.walk(tree)):
        if isinstance(node, ast.If) and _type_checking(node.test):
            node.body = []
    inside_effects = path.parent.name == "effects"
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            mod = node.module or ""
            if node.level == 0 and mod.startswith("mechanics.scenes."):
                out.add(mod.split(".")[2])
            elif node.level == 1 and not inside_effects:
                out.update([mod.split(".")[0]] if mod else [a.name for a in node.names])
            elif node.level == 1 and inside_effects:
                out.add("effects")
            elif node.level == 2 and inside_effects:  # (from scenes/: mechanics itself)
                out.add(mod.split(".")[0])
        elif isinstance(node, ast.Import):
            for a in node.names:
                if a.name.startswith("mechanics.scenes."):
                    out.add(a.name.split(".")[2])
    return out


@functools.cache
def _graph() -> dict[str, set[str]]:
    """Each module's run-time imports of its siblings (parsed once per worker: read, never
    changed, by the tests below)."""
    g: dict[str, set[str]] = {}
    for p in SCENES.rglob("*.py"):
        m = _module_of(p)
        g.setdefault(m, set()).update(_scene_imports(p) - {m})
    return g


def test_every_scenes_module_has_a_layer() -> None:
    assert set(_graph()) == set(LAYERS)


@pytest.mark.parametrize("module", sorted(LAYERS))
def test_scenes_modules_import_only_lower_layers(module) -> None:
    up = {m for m in _graph()[module] if LAYERS[m] >= LAYERS[module]}
    assert not up, f"{module} imports {up} (layer {LAYERS[module]})"


def test_the_layer_check_sees_an_upward_import(tmp_path) -> None:
    """Negative control: an effect importing the engine is found."""
    p = tmp_path / "effects" / "bad.py"
    p.parent.mkdir()
    p.write_text("from ..engine import Engine\nfrom .base import Effect\n")
    assert _scene_imports(p) == {"engine", "effects"}


def test_the_layer_check_passes_an_import_for_annotations_only(tmp_path) -> None:
    """An import under ``if TYPE_CHECKING:`` never runs: annotations may name any layer
    (and one outside the block is still seen)."""
    p = tmp_path / "bad.py"
    p.write_text(
        "from typing import TYPE_CHECKING\nfrom .vectors import cross\n"
        "if TYPE_CHECKING:\n    from .engine import Engine\n"
    )
    assert _scene_imports(p) == {"vectors"}


def test_mechanics_never_imports_identities() -> None:
    root = Path(mechanics.__file__).parent
    for p in root.rglob("*.py"):
        for node in ast.walk(ast.parse(p.read_text(encoding="utf-8"))):
            names = []
            if isinstance(node, ast.ImportFrom) and node.level == 0:
                names = [node.module or ""]
            elif isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            assert not any(n.split(".")[0] == "identities" for n in names), p
