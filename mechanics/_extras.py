"""bodycheck's optional parts and the extras that install them (issue 29, item 6).

``pip install bodycheck`` brings what the pytest plugin, the strategies, the testing
helpers, the mechanics library and the conformance battery need: numpy, scipy,
hypothesis and pytest.  The rest comes with an extra:

========== ====================== ==================================================
extra      packages               what needs them
========== ====================== ==================================================
proofs     sympy, mpmath          :mod:`identities`: the catalogue's proofs, ``bodycheck
                                  check``, ``explain``, ``catalogue``, ``site``
plots      matplotlib             plots: ``--plot``, ``bodycheck bench``, ``demo``, ``site``
fast       numba                  the compiled steppers and scene dynamics (without it
                                  the pure-numpy reference path runs, with one warning;
                                  a scene's run names it in its ``how``)
all        the three above        ``make run`` and ``make test`` install it (the lock)
========== ====================== ==================================================

The engines under test have their own extras (``mujoco``, ``pybullet``, ``drake``;
:func:`mechanics.conformance.adapters.require`).  So does executing the lecture
notebooks (``notebooks``: nbclient, nbformat, ipykernel; ``bodycheck notebooks --write``
and ``tests/test_notebooks.py`` name it when it is missing); so does building the API
reference (``docs``: Sphinx, numpydoc, myst-parser; ``bodycheck site --api`` and ``make
docs`` name it when it is missing).  Neither is part of ``all``.
"""

from __future__ import annotations

import importlib
from types import ModuleType

__all__ = ["EXTRA_OF", "MissingExtraError", "missing_extra", "require_extra"]

#: the extra that installs each optional top-level package
EXTRA_OF = {"sympy": "proofs", "mpmath": "proofs", "matplotlib": "plots", "numba": "fast"}


class MissingExtraError(ImportError):
    """An optional package is not installed; the message names the extra to install."""


def missing_extra(exc: ImportError, who: str) -> MissingExtraError | None:
    """The :class:`MissingExtraError` that ``exc`` means for ``who`` (e.g. ``"bodycheck
    check"``) if it is the import of an optional package of :data:`EXTRA_OF` failing
    because the package is absent; None for any other import error (a broken package,
    a missing core one), which should be shown as it is.

    >>> missing_extra(ModuleNotFoundError("No module named 'sympy'", name="sympy"), "x")
    MissingExtraError("x needs sympy, which is not installed: pip install 'bodycheck[proofs]'")
    >>> missing_extra(ModuleNotFoundError("No module named 'numpy'", name="numpy"), "x") is None
    True
    """
    if not isinstance(exc, ModuleNotFoundError) or exc.name is None:
        return None
    top = exc.name.split(".")[0]
    extra = EXTRA_OF.get(top)
    if extra is None or exc.name != top:  # a submodule missing: the package is broken
        return None
    err = MissingExtraError(
        f"{who} needs {top}, which is not installed: pip install 'bodycheck[{extra}]'",
        name=top,
    )
    return err


def require_extra(module: str, who: str) -> ModuleType:
    """Import ``module`` (a package of :data:`EXTRA_OF` or one of its submodules) or
    raise :class:`MissingExtraError` naming ``who`` and the extra that installs it.

    >>> require_extra("matplotlib", "the plot").__name__
    'matplotlib'
    """
    top = module.split(".")[0]
    if top not in EXTRA_OF:
        raise ValueError(f"module {module!r}: not an optional package ({sorted(EXTRA_OF)})")
    try:
        return importlib.import_module(module)
    except ModuleNotFoundError as exc:
        err = missing_extra(exc, who)
        if err is None:
            raise
        raise err from None
