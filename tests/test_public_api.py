"""The public API is written down once (README, "What is public") and pinned here: each
public module defines ``__all__`` and every name in it exists; every other module of
``mechanics`` is private by name (a leading underscore) or an internal part of a public
package (which re-exports what users need); a new module must be classified."""

from __future__ import annotations

import importlib
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent

#: the modules a user imports (their ``__all__`` is the API)
PUBLIC = (
    "mechanics.errors",
    "mechanics.particles",
    "mechanics.rotation",
    "mechanics.kinematics",
    "mechanics.energy",
    "mechanics.inertia",
    "mechanics.dynamics",
    "mechanics.elliptic",
    "mechanics.tops",
    "mechanics.impact",
    "mechanics.open_systems",
    "mechanics.fluids",
    "mechanics.integrators",
    "mechanics.scenes",
    "mechanics.strategies",
    "mechanics.testing",
    "mechanics.pytest_plugin",
    "mechanics.conformance",
    "mechanics.conformance.adapters",
    "mechanics.conformance.adapters.mujoco",
    "mechanics.conformance.adapters.pybullet",
    "mechanics.conformance.adapters.drake",
    "mechanics.conformance.adapters.siconos",
)

#: packages whose submodules are internal: the package re-exports their public names
#: (``mechanics.scenes``: the scene engine, whose interface is the scene file and
#: ``load_scene``/``run_scene``; ``mechanics.strategies``; ``mechanics.conformance``)
INTERNAL_UNDER = ("mechanics.scenes", "mechanics.strategies", "mechanics.conformance")


def _modules() -> list[str]:
    out = []
    for path in sorted((ROOT / "mechanics").rglob("*.py")):
        parts = path.relative_to(ROOT).with_suffix("").parts
        out.append(".".join(parts[:-1] if parts[-1] == "__init__" else parts))
    return out


def _classify(name: str) -> str:
    if name in PUBLIC:
        return "public"
    if any(p.startswith("_") for p in name.split(".")):
        return "private"
    if any(name.startswith(pkg + ".") for pkg in INTERNAL_UNDER):
        return "internal"
    return "unclassified"


def test_every_module_of_mechanics_is_public_private_or_internal() -> None:
    unclassified = [m for m in _modules() if _classify(m) == "unclassified" and m != "mechanics"]
    assert not unclassified, (
        f"classify {unclassified}: add to PUBLIC (and the README's list) or make private"
    )


@pytest.mark.parametrize("name", PUBLIC)
def test_a_public_module_states_its_api_and_has_every_name(name) -> None:
    mod = importlib.import_module(name)
    assert hasattr(mod, "__all__"), f"{name} has no __all__"
    missing = [n for n in mod.__all__ if not hasattr(mod, n)]
    assert not missing, f"{name}.__all__ names {missing}, which it does not define"


def test_the_readme_lists_exactly_the_public_modules() -> None:
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    section = readme.split("### What is public", 1)[1].split("\n## ", 1)[0].split("\n### ", 1)[0]
    listed = set(re.findall(r"`(mechanics(?:\.[a-z_]+)*)`", section))
    assert set(PUBLIC) <= listed, f"README lacks {sorted(set(PUBLIC) - listed)}"
    # the section names private and internal modules too, as examples of what is not public
    extra = {m for m in listed - set(PUBLIC) if _classify(m) == "unclassified"}
    assert not extra, f"README calls {sorted(extra)} public; PUBLIC does not"


def test_the_classifier_catches_a_new_module() -> None:
    # negative control: a module nobody classified
    assert _classify("mechanics.new_concept") == "unclassified"
    assert _classify("mechanics._helper") == "private"
    assert _classify("mechanics.scenes.engine") == "internal"
