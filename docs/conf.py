"""Sphinx configuration of bodycheck's API reference (issue 34): ``make docs``.

The reference is built from the docstrings (numpydoc) and the Markdown pages of ``docs/``
(myst-parser).  Its pages per public module are written at every build, from the
modules' ``__all__`` (:func:`write_module_pages`, into ``docs/api/``, which git ignores):
a module's docstring (its conventions block) introduces the page, a table lists its
public names, then each is documented on the page of the module that defines it (a name
re-exported by a package links there).  Nothing is fetched: no intersphinx inventories
(the machines reach only the package registries), so a reference to numpy, scipy or
another outside name is left as text (:data:`nitpick_ignore_regex`), while a broken
reference to bodycheck's own names fails the build (``-n -W``).

A docstring's citation of the book, ``(4.38)`` or ``eq. (4.38)``, links to that
equation on the book's pages (``bodycheck site``, one folder up from the reference when
``make docs`` builds both): :func:`link_equations`.
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil
import re
import sys
import types
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT))

import mechanics  # noqa: E402

project = "bodycheck"
author = "the bodycheck developers"
copyright = "2026, the bodycheck developers"
release = version = "reference"

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "numpydoc",
    "myst_parser",
]
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
#: the folders of docs/ that are not pages of the reference
exclude_patterns = ["site", "site-screens", "_build", "**/README.md"]
html_theme = "alabaster"
html_title = "bodycheck: API reference"
html_static_path: list[str] = []
html_show_sourcelink = False
html_show_sphinx = False  # its footer links out: the pages work offline
#: wide enough for the module names in the sidebar (mechanics.scenes.effects.coulomb_friction)
html_theme_options = {"page_width": "1240px", "sidebar_width": "330px"}
html_copy_source = False

#: numpydoc: the Parameters, Returns, Raises and Examples sections; a class's members are
#: documented by autodoc's own member list, not numpydoc's tables
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
autodoc_member_order = "bysource"
autodoc_typehints = "none"  # the docstrings' types are the reference
autosummary_generate = False  # the pages are written below

myst_heading_anchors = 3
#: every reference must resolve...
nitpicky = True
#: ...except to outside packages (no inventories are fetched) and to private names
nitpick_ignore_regex = [
    (r"py:.*", r"(numpy|np|scipy|sympy|mpmath|hypothesis|pytest|matplotlib|mujoco|numba)\b.*"),
    (r"py:.*", r"(.*\.)?_[A-Za-z0-9_]*(\..*)?"),
    (r"py:.*", r"(int|float|str|bool|bytes|list|tuple|dict|set|None|object|callable|type)"),
    # the standard library (no inventory fetched either)
    (r"py:.*", r"(math|time|tomllib|typing|collections|functools|dataclasses|pathlib)\b.*"),
    # the book layer (identities): on the book's pages, not in this reference
    (r"py:.*", r"identities\b.*"),
]

#: the public modules: every module of mechanics but the private ones (a part of the name
#: starting with an underscore)
PUBLIC = [
    "mechanics",
    *sorted(
        info.name
        for info in pkgutil.walk_packages(mechanics.__path__, "mechanics.")
        if not any(part.startswith("_") for part in info.name.split("."))
    ),
]


def _kind(obj) -> str:
    """How a public name is documented: a class, an exception, a routine, or data (a
    constant or a type alias)."""
    if inspect.isclass(obj) and not isinstance(obj, types.GenericAlias):
        return "exception" if issubclass(obj, BaseException) else "class"
    if inspect.isroutine(obj) or (callable(obj) and hasattr(obj, "__wrapped__")):
        return "function"
    return "data"


def canonical_paths() -> dict[str, dict[str, str]]:
    """For each public module, each name of its ``__all__`` → the public path where it
    is documented: the shortest one that lists the same object (what a user imports:
    ``mechanics.scenes.run_scene``, ``mechanics.strategies.rotvecs``), on a tie the
    module that defines it, else the first in order."""
    listed: dict[tuple[str, int], list[str]] = {}
    pages: dict[str, dict[str, object]] = {}
    for name in PUBLIC:
        mod = importlib.import_module(name)
        pages[name] = {n: getattr(mod, n) for n in getattr(mod, "__all__", ())}
        for n, obj in pages[name].items():
            listed.setdefault((n, id(obj)), []).append(f"{name}.{n}")
    out: dict[str, dict[str, str]] = {}
    for name, names in pages.items():
        out[name] = {}
        for n, obj in names.items():
            paths = listed[(n, id(obj))]
            home = getattr(obj, "__module__", "")
            out[name][n] = min(
                paths, key=lambda p: (p.count("."), p.rpartition(".")[0] != home, paths.index(p))
            )
    return out


def write_module_pages(out: Path = HERE / "api") -> list[str]:
    """One page per public module into ``out`` (stale pages removed); the modules."""
    out.mkdir(exist_ok=True)
    for old in out.glob("*.rst"):
        old.unlink()
    where = canonical_paths()
    for name in PUBLIC:
        mod = importlib.import_module(name)
        title = f"``{name}``"
        lines = [title, "=" * len(title), "", f".. automodule:: {name}", "   :no-members:", ""]
        names = where[name]
        table = [n for n in names if _kind(getattr(mod, n)) != "data"]
        if table:
            lines += [f".. currentmodule:: {name}", "", ".. autosummary::", ""]
            lines += [f"   {n if names[n] == f'{name}.{n}' else '~' + names[n]}" for n in table]
            lines += [""]
        for n, path in names.items():
            obj = getattr(mod, n)
            kind = _kind(obj)
            if path != f"{name}.{n}":
                if kind == "data":
                    lines += [f"``{n}``: see :py:obj:`{path}`.", ""]
            elif kind == "data":
                text = " ".join(repr(obj).split())
                text = text if len(text) <= 120 else text[:117] + "..."
                lines += [f".. py:data:: {name}.{n}", f"   :value: {text}", ""]
            else:
                lines += [f".. auto{kind}:: {path}"]
                lines += ["   :members:", ""] if kind == "class" else [""]
        (out / f"{name}.rst").write_text("\n".join(lines), encoding="utf-8")
    return PUBLIC


#: a citation of the book's equation in a docstring: (4.38), eq. (4.38), eqs. (4.38)
EQUATION = re.compile(r"(?<![\w.])\(([1-8])\.(\d{1,3})\)")
#: where the book's pages are, relative to a page of the reference (make docs puts the
#: reference in api/ of the site)
BOOK_PAGES = "../../"


def _known_equations() -> frozenset[str]:
    """The equations the book numbers (each has its anchor on its chapter's page)."""
    from identities.verify.catalogue import inventory

    return frozenset(i for i in inventory() if i.startswith("eq"))


KNOWN = _known_equations()


def link_equations(app, what, name, obj, options, lines) -> None:
    """autodoc-process-docstring: each citation of an equation the book numbers becomes a
    link to it on the book's pages (``ch4.html#eq4.38``); in examples and literals it
    stays text."""
    known = KNOWN

    def link(m: re.Match) -> str:
        item = f"eq{m.group(1)}.{m.group(2)}"
        if item not in known:
            return m.group(0)
        return f"(`{m.group(1)}.{m.group(2)} <{BOOK_PAGES}ch{m.group(1)}.html#{item}>`__)"

    in_example = False
    for k, line in enumerate(lines):
        stripped = line.lstrip()
        if stripped.startswith((">>>", "...")):
            in_example = True
        elif not stripped:
            in_example = False
        underlined = k + 1 < len(lines) and re.fullmatch(r"\s*([-=~^])\1{2,}\s*", lines[k + 1])
        if in_example or underlined:  # a title keeps its length (its underline's)
            continue
        parts = LITERAL.split(line)  # odd parts are ``literals`` and roles: left alone
        for j in range(0, len(parts), 2):
            text = BAR.sub(r"\|", parts[j])  # |x| is a norm in these docstrings
            parts[j] = EQUATION.sub(link, text)
        lines[k] = "".join(parts)


#: what the prose of a docstring may hold that is not reStructuredText markup: ``...``
#: literals and :role:`...` targets, kept as they are
LITERAL = re.compile(r"(``.*?``|:[a-z:]+:`[^`]*`|`[^`]*`_*)")
#: the bars of |x| (a norm or absolute value: no docstring here uses substitutions)
BAR = re.compile(r"(?<!\\)\|")


#: the kinds of object each role may name
ROLE_TYPES = {
    "func": {"function", "method", "classmethod", "staticmethod"},
    "meth": {"method", "classmethod", "staticmethod", "property"},
    "class": {"class", "exception"},
    "exc": {"exception", "class"},
    "data": {"data", "attribute"},
    "attr": {"attribute", "property", "data"},
    "const": {"data", "attribute"},
}


def _shared_prefix(a: str, b: str) -> int:
    n = 0
    for x, y in zip(a.split("."), b.split("."), strict=False):
        if x != y:
            break
        n += 1
    return n


def resolve_by_suffix(app, env, node, contnode):
    """missing-reference: a reference to a name of bodycheck written as in its own
    module (``:data:`CONSERVED```, ``:func:`impact.apply```) resolves to the documented
    object of the role's kind whose full name ends with the longest tail of it that
    names one object (a name documented where a package re-exports it:
    effects.base.Effect.loads → Effect.loads); where several do, the one nearest the
    referring module; else it stays a broken reference (an error of the build)."""
    from sphinx.util.nodes import make_refnode

    if node.get("refdomain") != "py":
        return None
    parts = node["reftarget"].lstrip("~.").split(".")
    kinds = ROLE_TYPES.get(node.get("reftype", ""))
    here = node.get("py:module") or ""
    objects = {
        name: e
        for name, e in env.get_domain("py").objects.items()
        if not e.aliased and (kinds is None or e.objtype in kinds)
    }
    for k in range(len(parts)):
        tail = "." + ".".join(parts[k:])
        found = [name for name in objects if name.endswith(tail)]
        if not found:
            continue
        best = max(_shared_prefix(here, name) for name in found)
        found = [name for name in found if _shared_prefix(here, name) == best]
        if len(found) == 1:
            entry = objects[found[0]]
            return make_refnode(app.builder, node["refdoc"], entry.docname, entry.node_id, contnode)
        return None
    return None


def setup(app):
    write_module_pages()
    app.connect("autodoc-process-docstring", link_equations)
    app.connect("missing-reference", resolve_by_suffix)
