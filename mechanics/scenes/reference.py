"""The scene-file reference, generated from the schema itself (``bodycheck scene
--schema``, ``docs/scene-files.md``): the ``[scene]`` table, the shapes and their
dimensions, the initial keys and every effect with its fields, their kinds, units and
a minimal example, so that the documentation cannot drift from the code.
"""

from __future__ import annotations

from .effects import REGISTRY
from .spec import DIMENSION_UNITS, INITIAL_DOC, INITIAL_KEYS, SCENE_FIELDS, SHAPES

__all__ = ["scene_file_reference"]

#: what each field kind accepts
KINDS = {
    "body": "a body's name",
    "bodies": "an array of bodies' names",
    "number": "a number",
    "positive": "a number > 0",
    "nonnegative": "a number ≥ 0",
    "restitution": "a number in [0, 1]",
    "vector": "three numbers",
    "str": "a string",
    "axis_name": '"x", "y" or "z"',
    "frame": '"space" or "body"',
}


def _toml(value) -> str:
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, list):
        return "[" + ", ".join(_toml(v) for v in value) + "]"
    return repr(value)


def scene_file_reference() -> str:
    """The reference as Markdown."""
    out = [
        "# Scene files: the reference",
        "",
        "Generated from the schema by `bodycheck scene --schema` (`make checks` writes this",
        "file; a test fails when it is stale). SI units throughout; `1` is a pure number.",
        "",
        "## `[scene]`",
        "",
        "| field | kind | unit | meaning |",
        "|---|---|---|---|",
    ]
    for name, (kind, unit, meaning) in SCENE_FIELDS.items():
        out.append(f"| `{name}` | {kind} | {unit} | {meaning} |")
    out += [
        "",
        "## `[[bodies]]`",
        "",
        "`name`, `shape`, `mass` (kg; not for a tank), optional `fixed = true`, the shape's",
        "dimensions and an `initial` table.",
        "",
        "| shape | dimensions |",
        "|---|---|",
    ]
    for shape, dims in SHAPES.items():
        d = ", ".join(f"`{k}` ({DIMENSION_UNITS[k]})" for k in dims) or "none"
        out.append(f"| `{shape}` | {d} |")
    out += ["", "### `initial`", "", "| key | kind | unit | meaning |", "|---|---|---|---|"]
    for key, kind in INITIAL_KEYS.items():
        unit, meaning = INITIAL_DOC[key]
        out.append(f"| `{key}` | {kind} | {unit} | {meaning} |")
    out += ["", "## `[[effects]]`", "", "Each has a `type` and the fields below."]
    for t in sorted(REGISTRY):
        cls = REGISTRY[t]
        doc = " ".join((cls.__doc__ or "").split("\n\n")[0].split())
        out += ["", f"### `{t}`", "", doc, "", "| field | kind | required | unit |"]
        out.append("|---|---|---|---|")
        for field, (kind, required) in cls.schema.items():
            req = "yes" if required else "no"
            out.append(f"| `{field}` | {KINDS[kind]} | {req} | {cls.units[field]} |")
        example = "\n".join(f"{k} = {_toml(v)}" for k, v in cls.example.items())
        out += ["", "```toml", "[[effects]]", example, "```"]
    return "\n".join(out) + "\n"
