"""Scenes: bodies, an initial state and exactly the effects the scene lists, simulated
(by the exact flow where the effects have one) and compared with the book.

Public API: :func:`load_scene`, :func:`parse_scene`, :func:`run_scene`,
:func:`builtin_scenes`, :func:`builtin_path`, :class:`SceneError`, :class:`SceneResult`.

Examples
--------
>>> scene = load_scene(builtin_path("rolling_incline"))
>>> result = run_scene(scene)
>>> result.passed, result.method.split(":")[0]
(True, 'exact')
"""

from __future__ import annotations

from pathlib import Path

from .result import Comparison, ConservedReport, SceneResult, SelfCheck, run_scene
from .spec import Scene, SceneError, load_scene, parse_scene

__all__ = [
    "Comparison",
    "ConservedReport",
    "Scene",
    "SceneError",
    "SceneResult",
    "SelfCheck",
    "builtin_path",
    "builtin_scenes",
    "load_scene",
    "parse_scene",
    "run_scene",
]

_BUILTIN = Path(__file__).with_name("builtin")


def builtin_scenes() -> dict[str, Path]:
    """The built-in scene files by name (the file stem), sorted.

    Returns
    -------
    dict[str, pathlib.Path]
        Scene name (the file's stem) -> the path of its TOML file in the package's
        ``builtin`` folder, in sorted order of the names.

    Examples
    --------
    Each name is its file's stem, and the names come sorted:

    >>> scenes = builtin_scenes()
    >>> all(p.stem == name for name, p in scenes.items()), list(scenes) == sorted(scenes)
    (True, True)
    """
    return {p.stem: p for p in sorted(_BUILTIN.glob("*.toml"))}


def builtin_path(name: str) -> Path:
    """The path of a built-in scene, by its name.

    Parameters
    ----------
    name : str
        A built-in scene's name (a key of :func:`builtin_scenes`), e.g.
        ``"rolling_incline"``.

    Returns
    -------
    pathlib.Path
        The path of its TOML file, which :func:`load_scene` reads.

    Raises
    ------
    KeyError
        Where ``name`` is not a built-in scene (the message names the known ones).

    Examples
    --------
    The path by name is the one :func:`builtin_scenes` lists:

    >>> path = builtin_path("rolling_incline")
    >>> path.name, path == builtin_scenes()["rolling_incline"]
    ('rolling_incline.toml', True)
    """
    scenes = builtin_scenes()
    if name not in scenes:
        raise KeyError(f"unknown built-in scene {name!r} (known: {', '.join(scenes)})")
    return scenes[name]
