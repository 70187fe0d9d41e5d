"""The public API is written down once (docs/guide/use-in-your-project.md, "What is
public", linked from the README) and pinned here: each public module defines ``__all__``
and every name in it exists; every other module of ``mechanics`` is private by name (a
leading underscore) or an internal part of a public package (which re-exports what users
need); a new module must be classified."""

from __future__ import annotations

import importlib
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
#: the guide page whose section "What is public" lists the public modules
GUIDE = ROOT / "docs" / "guide" / "use-in-your-project.md"

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
        f"classify {unclassified}: add to PUBLIC (and the guide's list) or make private"
    )


@pytest.mark.parametrize("name", PUBLIC)
def test_a_public_module_states_its_api_and_has_every_name(name) -> None:
    mod = importlib.import_module(name)
    assert hasattr(mod, "__all__"), f"{name} has no __all__"
    missing = [n for n in mod.__all__ if not hasattr(mod, n)]
    assert not missing, f"{name}.__all__ names {missing}, which it does not define"


def _listed(text: str) -> set[str]:
    """The modules named in the section "What is public" of a page (up to the next heading)."""
    section = text.split("## What is public", 1)[1].split("\n#", 1)[0]
    return set(re.findall(r"`(mechanics(?:\.[a-z_]+)*)`", section))


def _listing_problems(listed: set[str]) -> list[str]:
    """What is wrong with a list of public modules: a public module missing, or a module
    called public that PUBLIC does not know."""
    problems = []
    if not set(PUBLIC) <= listed:
        problems.append(f"the guide lacks {sorted(set(PUBLIC) - listed)}")
    # the section names private and internal modules too, as examples of what is not public
    extra = {m for m in listed - set(PUBLIC) if _classify(m) == "unclassified"}
    if extra:
        problems.append(f"the guide calls {sorted(extra)} public; PUBLIC does not")
    return problems


def test_the_guide_lists_exactly_the_public_modules() -> None:
    listed = _listed(GUIDE.read_text(encoding="utf-8"))
    assert not _listing_problems(listed), _listing_problems(listed)


def test_the_readme_links_the_guide_that_lists_them() -> None:
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert "(docs/guide/use-in-your-project.md)" in readme


def test_the_listing_check_catches_a_missing_and_an_unknown_module() -> None:
    # negative control: the guide's section with one public module taken out, and with a
    # module nobody classified added, is rejected naming each
    text = GUIDE.read_text(encoding="utf-8")
    section = text.split("## What is public", 1)[1]
    assert "`mechanics.tops`" in section
    without = text.replace("`mechanics.tops`", "`mechanics.tops_gone`")
    assert _listing_problems(_listed(without)) == [
        "the guide lacks ['mechanics.tops']",
        "the guide calls ['mechanics.tops_gone'] public; PUBLIC does not",
    ]
    # the section ends at the next heading: a module named after it does not count
    assert "mechanics.new_concept" not in _listed(text + "\n## Later\n\n`mechanics.new_concept`\n")


def test_the_classifier_catches_a_new_module() -> None:
    # negative control: a module nobody classified
    assert _classify("mechanics.new_concept") == "unclassified"
    assert _classify("mechanics._helper") == "private"
    assert _classify("mechanics.scenes.engine") == "internal"
