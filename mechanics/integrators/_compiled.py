"""The compiled path's loader: :mod:`mechanics._kernels` imported on first use, one
:class:`CompiledPathWarning` if that fails, and the free rigid body's arguments.

Part of :mod:`mechanics.integrators` (its docstring states the conventions).
"""

from __future__ import annotations

import importlib
import warnings
from types import ModuleType
from typing import Any, Literal

import numpy as np

from .._extras import missing_extra
from ._solution import FloatArray, Rhs


class CompiledPathWarning(RuntimeWarning):
    """The compiled path is unavailable (numba missing or a compilation failed): the
    pure-numpy reference path runs instead, with the same results, only slower."""


# the module mechanics._kernels once imported; False after a failure
_KERNELS: ModuleType | Literal[False] | None = None


def _kernels() -> ModuleType | None:
    """mechanics._kernels, imported on first use (numba's import is not paid by
    ``import mechanics``), or None with one CompiledPathWarning if that fails."""
    global _KERNELS
    if _KERNELS is None:
        try:
            kernels = importlib.import_module(".._kernels", __package__)
        except Exception as exc:  # numba missing or broken: the reference path
            _compiled_failed(exc)
        else:
            _KERNELS = kernels
    return _KERNELS or None


def _compiled_failed(exc: BaseException) -> None:
    """Give up the compiled path for this process, saying why once."""
    global _KERNELS
    _KERNELS = False
    missing = missing_extra(exc, "the compiled steppers") if isinstance(exc, ImportError) else None
    why = str(missing) if missing is not None else f"{type(exc).__name__}: {exc}"
    warnings.warn(
        f"the compiled steppers are unavailable ({why}); "
        f"mechanics.integrators runs its pure-numpy reference path instead (same "
        f"results, slower)",
        CompiledPathWarning,
        stacklevel=3,
    )


def _run_compiled(name: str, *args: Any) -> tuple[int, ...] | None:
    """kernels.<name>(*args), or None (after one warning) if the kernel cannot be
    compiled or loaded: the caller then runs the reference path."""
    k = _kernels()
    if k is None:
        return None
    try:
        done: tuple[int, ...] = getattr(k, name)(*args)  # the kernel's status and counts
        return done
    except Exception as exc:  # a failed JIT (numba's errors are not one class)
        _compiled_failed(exc)
        return None


def _free_body_args(rhs: Rhs, y0: FloatArray) -> tuple[FloatArray, FloatArray] | None:
    """(J per body (bodies, 3), flat y0) if ``rhs`` is :func:`free_rigid_body_rhs`'s and
    its moments broadcast onto y0's bodies; else None (the reference path runs)."""
    Jm = getattr(rhs, "free_body_moments", None)
    if Jm is None or y0.shape[-1:] != (12,):
        return None
    try:
        Jb = np.broadcast_to(Jm, (*y0.shape[:-1], 3))
    except ValueError:
        return None  # the reference raises the ShapeError
    return np.ascontiguousarray(Jb.reshape(-1, 3)), np.ascontiguousarray(y0.reshape(-1))
