"""The scene-file reference, generated from the schema itself (``bodycheck scene
--schema``, ``docs/scene-files.md``): the ``[scene]`` table, the shapes and their
dimensions, the initial keys and every effect with its fields, their kinds, units and
a minimal example, so that the documentation cannot drift from the code.
"""

from __future__ import annotations

import inspect
import re

from . import budget, domain
from .effects import REGISTRY
from .spec import DIMENSION_UNITS, INITIAL_DOC, INITIAL_KEYS, SCENE_FIELDS, SHAPES

#: numeric field kinds (their values have a domain); the rest are names and choices
_NUMERIC = {"number", "positive", "nonnegative", "restitution", "vector"}


def _domain(kind: str, unit: str) -> str:
    if kind not in _NUMERIC:
        return ""
    if kind == "restitution":
        return "[0, 1]"
    return domain.domain_of(unit, kind)


#: the [scene] fields' domains (the others are names, choices or integers with their kind)
_SCENE_DOMAINS = {
    "duration": domain.domain_of("s", "positive"),
    "step": domain.domain_of("s", "positive"),
    "rtol": "100 eps ≤ x ≤ 1e-3",
    "atol": "0 < x ≤ 1e-3",
    "max_seconds": "x > 0",
}

__all__ = ["scene_file_reference"]

#: what each field kind accepts
KINDS = {
    "body": "a body's name",
    "bodies": "an array of bodies' names",
    "planes": "an array of planes, each a table {point (m), normal}",
    "number": "a number",
    "positive": "a number > 0",
    "nonnegative": "a number ≥ 0",
    "restitution": "a number in [0, 1]",
    "vector": "three numbers",
    "str": "a string",
    "axis_name": '"x", "y" or "z"',
    "frame": '"space" or "body"',
    "impact_model": '"auto" or "sequential"',
}


def _bullets(doc: str) -> list[str]:
    """A module docstring's Conventions list as Markdown bullets, one line each, with
    Sphinx roles and double backquotes turned into plain code spans."""
    text = doc.split("Conventions\n-----------\n")[1]
    items = [" ".join(chunk.split()) for chunk in ("\n" + text).split("\n- ") if chunk.strip()]
    out = []
    for item in items:
        item = re.sub(r":\w+:`~?\.?([^`]+)`", r"`\1`", item).replace("``", "`")
        out.append(f"- {item}")
    return out


def _toml(value: object) -> str:
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, list):
        return "[" + ", ".join(_toml(v) for v in value) + "]"
    return repr(value)


def _description(cls: type) -> str:
    """An effect's description: its docstring's summary and the paragraphs after it, up
    to its first numpydoc section (Parameters, Raises, ...), as one paragraph."""
    doc = inspect.getdoc(cls) or ""
    head = re.split(r"^\S[^\n]*\n-{3,}$", doc, maxsplit=1, flags=re.M)[0]
    return re.sub(r":[a-z]+:`~?([^`]+)`", r"`\1`", " ".join(head.split()))  # roles: code


def scene_file_reference() -> str:
    """The scene-file reference as Markdown, generated from the schema.

    The ``[scene]`` fields, the shapes and their dimensions, the ``initial`` keys and
    every registered effect with its fields (kind, required, unit, domain) and a minimal
    example; the domain and budget Conventions of :mod:`.domain` and :mod:`.budget`.

    Returns
    -------
    str
        The Markdown text (``docs/scene-files.md``), ending in a newline.

    Examples
    --------
    One section per registered effect, and one for the ``initial`` keys:

    >>> from mechanics.scenes.effects import REGISTRY
    >>> text = scene_file_reference()
    >>> lines = text.splitlines()
    >>> lines[0], sum(line.startswith("### `") for line in lines) == len(REGISTRY) + 1
    ('# Scene files: the reference', True)
    """
    out = [
        "# Scene files: the reference",
        "",
        "Generated from the schema by `bodycheck scene --schema` (`make checks` writes this",
        "file; a test fails when it is stale). SI units throughout; `1` is a pure number.",
        "",
        "## The domain of a number",
        "",
        *_bullets(domain.__doc__),
        "",
        "## What a run may cost",
        "",
        *_bullets(budget.__doc__),
        "",
        f"Defaults: memory {budget.DEFAULT_MAX_MEMORY // 10**6} MB of samples, "
        f"{budget.DEFAULT_MAX_STEPS} steps, {budget.DEFAULT_MAX_SECONDS:g} s of wall time.",
        "",
        "## `[scene]`",
        "",
        "| field | kind | unit | domain | meaning |",
        "|---|---|---|---|---|",
    ]
    for name, (kind, unit, meaning) in SCENE_FIELDS.items():
        out.append(f"| `{name}` | {kind} | {unit} | {_SCENE_DOMAINS.get(name, '')} | {meaning} |")
    out += [
        "",
        "## `[[bodies]]`",
        "",
        "`name`, `shape`, `mass` (kg; not for a tank), optional `fixed = true`, the shape's",
        "dimensions and an `initial` table.",
        "",
        f"`mass` and every dimension: {domain.domain_of('kg', 'positive')}.",
        "",
        "| shape | dimensions |",
        "|---|---|",
    ]
    for shape, dims in SHAPES.items():
        d = ", ".join(f"`{k}` ({DIMENSION_UNITS[k]})" for k in dims) or "none"
        out.append(f"| `{shape}` | {d} |")
    out += [
        "",
        "### `initial`",
        "",
        "| key | kind | unit | domain | meaning |",
        "|---|---|---|---|---|",
    ]
    for key, kind in INITIAL_KEYS.items():
        unit, meaning = INITIAL_DOC[key]
        out.append(f"| `{key}` | {kind} | {unit} | {_domain(kind, unit)} | {meaning} |")
    out += ["", "## `[[effects]]`", "", "Each has a `type` and the fields below."]
    for t in sorted(REGISTRY):
        cls = REGISTRY[t]
        doc = _description(cls)
        out += ["", f"### `{t}`", "", doc, "", "| field | kind | required | unit | domain |"]
        out.append("|---|---|---|---|---|")
        for field, (kind, required) in cls.schema.items():
            req = "yes" if required else "no"
            unit = cls.units[field]
            out.append(f"| `{field}` | {KINDS[kind]} | {req} | {unit} | {_domain(kind, unit)} |")
        example = "\n".join(f"{k} = {_toml(v)}" for k, v in cls.example.items())
        out += ["", "```toml", "[[effects]]", example, "```"]
    return "\n".join(out) + "\n"
