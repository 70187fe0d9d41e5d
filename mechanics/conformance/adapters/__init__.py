"""Adapters: the book's own two columns, and the helper other engines' adapters use.

- :class:`~.reference.ExactAdapter`: the closed forms themselves (the "exact" column:
  every scenario passes with its figures at rounding or at the sampling floor).
- :class:`~.reference.SceneEngineAdapter`: the project's integrated engine,
  :mod:`mechanics.scenes` (the "integrated" column).
- :func:`require`: import an optional engine's package, or raise
  :class:`MissingExtraError` naming the extra that installs it.

This package imports nothing heavy: the adapters load on first use, and an engine's
adapter module imports its engine through :func:`require` when it is used.
"""

from __future__ import annotations

import importlib

__all__ = ["ENGINE_NAMES", "ExactAdapter", "MissingExtraError", "SceneEngineAdapter", "require"]

#: how the message names an engine's adapter, by its top-level module
ENGINE_NAMES = {
    "mujoco": "MuJoCo",
    "pybullet": "PyBullet",
    "pydrake": "Drake",
    "siconos": "Siconos",
}


# one class for every optional package, engines and bodycheck's own extras alike
from ..._extras import MissingExtraError  # noqa: E402


def require(module: str, extra: str, *, engine: str | None = None, package: str | None = None):
    """Import ``module`` or raise :class:`MissingExtraError` naming ``extra``.

    Parameters
    ----------
    module : str
        The package to import, e.g. ``"mujoco"``.
    extra : str
        The bodycheck extra that installs it, e.g. ``"mujoco"``.
    engine : str, optional
        The engine's name in the message (default from :data:`ENGINE_NAMES`, else
        ``module``).
    package : str, optional
        The distribution that provides ``module``, as the message names it (default:
        ``module``'s top level; Drake's ``pydrake`` comes with the ``drake`` package).

    Returns
    -------
    module
        The imported module.

    Raises
    ------
    MissingExtraError
        Where ``module`` (its top-level package) is not installed; the message names the
        extra and the ``pip install`` that installs it.
    ImportError
        Where the package is there but broken (it fails to import another module): its
        own error, shown as it is.

    Examples
    --------
    >>> require("math", "none").sqrt(4.0)
    2.0
    >>> require("mujoco_is_not_here", "mujoco", engine="MuJoCo")
    Traceback (most recent call last):
    ...
    mechanics._extras.MissingExtraError: the MuJoCo adapter needs the \
mujoco_is_not_here package: pip install 'bodycheck[mujoco]'
    """
    try:
        return importlib.import_module(module)
    except ImportError as exc:
        top = module.split(".")[0]
        if exc.name is not None and exc.name.split(".")[0] != top:
            raise  # the package is there but is broken: show its own error
        name = engine or ENGINE_NAMES.get(top, module)
        raise MissingExtraError(
            f"the {name} adapter needs the {package or top} package: "
            f"pip install 'bodycheck[{extra}]'",
            name=module,
        ) from None


def __getattr__(name: str):
    if name in ("ExactAdapter", "SceneEngineAdapter"):
        from . import reference

        return getattr(reference, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
