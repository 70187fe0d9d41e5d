"""The public surface of :mod:`mechanics`: every callable named in a module's ``__all__``.

The surface is enumerated, never listed by hand: :func:`public_callables` walks the
package with :mod:`pkgutil`, so a new module, or a new name in an ``__all__``, joins it
at once (and the fuzz suite fails until the name has an entry in
:mod:`tests.fuzz.entries`).
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil
import types

import mechanics


def public_callables() -> dict[str, object]:
    """``{"module.name": obj}`` for every callable in the ``__all__`` of a mechanics module
    (not of a private one, whose name has a part with a leading underscore).

    A name re-exported by a package (``mechanics.scenes.load_scene``) is keyed by the
    module that defines it, so each object appears once; where that module is private
    (``mechanics.integrators._integrate``), by the public module that lists it.
    Exception classes are left out: they are raised, not called; so are type aliases
    (``Schema = dict[...]``).
    """
    out: dict[str, object] = {}
    for info in pkgutil.walk_packages(mechanics.__path__, "mechanics."):
        if any(part.startswith("_") for part in info.name.split(".")):
            continue  # private modules (docs/guide/use-in-your-project.md, "What is public"): their callers validate
        mod = importlib.import_module(info.name)
        for name in getattr(mod, "__all__", ()):
            obj = getattr(mod, name)
            if not callable(obj) or isinstance(obj, types.GenericAlias):
                continue
            if inspect.isclass(obj) and issubclass(obj, BaseException):
                continue
            home = getattr(obj, "__module__", None) or info.name
            if not home.startswith("mechanics"):
                home = info.name  # typing aliases and the like: keyed where listed
            elif any(part.startswith("_") for part in home.split(".")):
                home = info.name  # defined in a private module of a package: keyed where public
            key = f"{home}.{getattr(obj, '__name__', name)}"
            out.setdefault(key, obj)
    return dict(sorted(out.items()))
