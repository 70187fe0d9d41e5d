"""The import direction of the rooms (the README's "Where things are"): read from the
source with ast, every import statement anywhere in a module (also inside functions).

- ``mechanics`` never imports ``identities`` or ``bench``;
- the checks (``identities.book``, ``identities.properties``, ``identities.stability``) and the machinery
  (``identities.verify``) never import the command line, matplotlib or argparse;
- the machinery imports no check; ``bench`` never imports ``identities``;
- ``import mechanics`` (every module of it) loads neither sympy nor matplotlib.

``mechanics/scenes`` keeps its own layers: ``tests/scenes/test_layers.py``.
"""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent

#: room (module prefix) -> the module prefixes it must not import, and why
RULES = {
    "mechanics": (("identities", "bench"), "the library knows no book and no study"),
    "identities.book": (("identities.cli", "matplotlib", "argparse"), "a check is not the CLI"),
    "identities.properties": (
        ("identities.cli", "matplotlib", "argparse"),
        "a check is not the CLI",
    ),
    "identities.stability": (
        ("identities.cli", "matplotlib", "argparse"),
        "a check is not the CLI",
    ),
    "identities.verify": (
        ("identities.cli", "identities.book", "identities.stability", "matplotlib", "argparse"),
        "the machinery serves the checks, not the reverse",
    ),
    "bench": (("identities",), "the study measures mechanics, not the book"),
}


def module_name(path: Path) -> str:
    parts = path.relative_to(ROOT).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _from_module(node: ast.ImportFrom, package: str) -> str:
    """The module a ``from ... import`` names, a relative one resolved against ``package``."""
    base = node.module or ""
    if node.level:
        anchor = package.split(".")
        anchor = anchor[: len(anchor) - (node.level - 1)]
        base = ".".join([*anchor, base] if base else anchor)
    return base


def imported(module: str, source: str, *, is_package: bool = False) -> set[str]:
    """Every module an import statement in ``source`` names (relative ones resolved
    against ``module``), with the line: {"name:line"}."""
    out = set()
    package = module if is_package else module.rpartition(".")[0]
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            out |= {f"{a.name}:{node.lineno}" for a in node.names}
        elif isinstance(node, ast.ImportFrom):
            base = _from_module(node, package)
            out.add(f"{base}:{node.lineno}")
            out |= {f"{base}.{a.name}:{node.lineno}" for a in node.names}
    return out


def violations(module: str, source: str, *, is_package: bool = False) -> list[str]:
    """The imports of ``module`` that its room forbids, with the rule's reason."""
    bad = []
    for room, (forbidden, why) in RULES.items():
        if module != room and not module.startswith(room + "."):
            continue
        for entry in sorted(imported(module, source, is_package=is_package)):
            name = entry.rpartition(":")[0]
            if any(name == f or name.startswith(f + ".") for f in forbidden):
                bad.append(f"{module} imports {entry} ({why})")
    return bad


def _sources():
    for top in ("mechanics", "identities", "bench"):
        yield from sorted((ROOT / top).rglob("*.py"))


@pytest.mark.parametrize("path", list(_sources()), ids=lambda p: str(p.relative_to(ROOT)))
def test_every_module_imports_only_down(path: Path) -> None:
    bad = violations(
        module_name(path), path.read_text(encoding="utf-8"), is_package=path.name == "__init__.py"
    )
    assert not bad, "\n".join(bad)


@pytest.mark.parametrize(
    ("module", "source"),
    [
        ("mechanics.scenes.engine", "from identities.book.scenes import compare\n"),
        ("mechanics.rotation", "def f():\n    import identities.verify.proof\n"),
        ("identities.book.ch04.inertia", "import matplotlib.pyplot as plt\n"),
        ("identities.book.ch06.problems", "from ...cli import main\n"),
        ("identities.verify.render", "from ..book.ch01 import momentum\n"),
        ("bench.workprecision", "from identities.verify.catalogue import check\n"),
    ],
)
def test_a_deliberate_back_import_is_caught(module, source) -> None:
    """Negative control: the same procedure flags an import against the direction,
    absolute, relative or inside a function."""
    assert violations(module, source)


def test_a_down_import_is_not_flagged() -> None:
    src = "from mechanics import rotation\nfrom identities.verify.catalogue import check\n"
    assert violations("identities.book.ch02.rotations", src) == []


def test_import_mechanics_loads_neither_sympy_nor_matplotlib() -> None:
    code = (
        "import importlib, pkgutil, sys, mechanics\n"
        "for m in pkgutil.walk_packages(mechanics.__path__, 'mechanics.'):\n"
        "    importlib.import_module(m.name)\n"
        "bad = sorted(k for k in sys.modules if k.split('.')[0] in ('sympy', 'matplotlib'))\n"
        "print(bad)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "[]", out.stdout


def import_graph(sources: dict[str, tuple[str, bool]]) -> dict[str, set[str]]:
    """module -> the modules of ``sources`` it imports at run time (``from P import m``
    names the module P.m where that is one, else P; an import under ``if
    TYPE_CHECKING:``, for annotations only, never runs), from {module: (source,
    is_package)}."""
    graph = {}
    for module, (source, is_package) in sources.items():
        package = module if is_package else module.rpartition(".")[0]
        out = set()
        tree = ast.parse(source)
        for node in list(ast.walk(tree)):
            if isinstance(node, ast.If) and (
                (isinstance(node.test, ast.Name) and node.test.id == "TYPE_CHECKING")
                or (isinstance(node.test, ast.Attribute) and node.test.attr == "TYPE_CHECKING")
            ):
                node.body = []
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                out |= {a.name for a in node.names if a.name in sources}
            elif isinstance(node, ast.ImportFrom):
                base = _from_module(node, package)
                for a in node.names:
                    if f"{base}.{a.name}" in sources:
                        out.add(f"{base}.{a.name}")
                    elif base in sources:
                        out.add(base)
        graph[module] = out - {module}
    return graph


def circles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The groups of modules that import each other around a circle (Tarjan's strongly
    connected components of more than one module), each sorted."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    found = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        for w in sorted(graph[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            group = []
            while not group or group[-1] != v:
                group.append(stack.pop())
            if len(group) > 1:
                found.append(sorted(group))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return found


def test_no_modules_import_each_other_in_a_circle() -> None:
    sources = {
        module_name(p): (p.read_text(encoding="utf-8"), p.name == "__init__.py") for p in _sources()
    }
    assert circles(import_graph(sources)) == []


def test_a_circle_of_imports_is_caught() -> None:
    """Negative control: the CLI's old circle (main imports conform, conform imports
    UsageError from main inside a function) and a three-module one are found."""
    sources = {
        "identities.cli.main": ("from identities.cli import conform\n", False),
        "identities.cli.conform": ("def f():\n    from .main import UsageError\n", False),
        "identities.cli": ("from .main import main\n", True),
        "a": ("import b\n", False),
        "b": ("from c import x\n", False),
        "c": ("def g():\n    from a import x\n", False),
        # for annotations only: never imported at run time, no circle
        "d": ("from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    import e\n", False),
        "e": ("import d\n", False),
    }
    assert circles(import_graph(sources)) == [
        ["a", "b", "c"],
        ["identities.cli.conform", "identities.cli.main"],
    ]
