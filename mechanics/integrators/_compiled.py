"""The compiled path's loader: :mod:`mechanics._kernels` (the free rigid body) and
:mod:`mechanics._kernels_rhs` (a user's numba-compiled right-hand side) imported on first
use, one :class:`CompiledPathWarning` if that fails, and the kernels' arguments.

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
# the module mechanics._kernels_rhs once imported; False after a failure
_RHS_KERNELS: ModuleType | Literal[False] | None = None


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


def is_numba_function(rhs: object) -> bool:
    """``rhs`` is a numba dispatcher (``@numba.njit``), told without importing numba."""
    return type(rhs).__module__.startswith("numba.") and hasattr(rhs, "py_func")


def _warn_user_rhs(rhs: object, why: str, stacklevel: int = 6) -> None:
    """One CompiledPathWarning saying why a numba-compiled ``rhs`` runs on the reference
    path; ``stacklevel`` counts the frames up to the caller of ``integrate`` (6 from the
    kernel runners: here, :func:`_run_user_rhs`, the method's runner, its dispatch,
    ``integrate``)."""
    name = getattr(rhs, "__name__", type(rhs).__name__)
    warnings.warn(
        f"the numba-compiled rhs {name!r} runs on the reference path (compiled to Python "
        f"calls, slower): {why}",
        CompiledPathWarning,
        stacklevel=stacklevel,
    )


#: An argument of :func:`_run_user_rhs` that stands for the kernels' ``no_event`` (the
#: event function of a run without one: a kernel's function argument cannot be None).
NO_EVENT = object()


def _run_user_rhs(name: str, rhs: Rhs, y0: FloatArray, *args: Any) -> tuple[int, ...] | None:
    """kernels_rhs.<name>(rhs, y0, *args) for a numba-compiled ``rhs``, or None after one
    warning saying why not (a state of another shape than (n,), numba's typing of the
    ``rhs`` against :data:`mechanics._kernels_rhs.RHS_SIGNATURE` failing, numba missing):
    the caller then runs the reference path, which calls ``rhs`` from Python."""
    global _RHS_KERNELS
    if y0.ndim != 1:
        _warn_user_rhs(
            rhs, f"the compiled path takes a state of shape (n,); y0 has shape {y0.shape}"
        )
        return None
    if _RHS_KERNELS is None:
        try:
            _RHS_KERNELS = importlib.import_module(".._kernels_rhs", __package__)
        except Exception as exc:  # numba missing or broken: the reference path
            _RHS_KERNELS = False
            missing = (
                missing_extra(exc, "the compiled steppers")
                if isinstance(exc, ImportError)
                else None
            )
            _warn_user_rhs(
                rhs, str(missing) if missing is not None else f"{type(exc).__name__}: {exc}"
            )
            return None
    if _RHS_KERNELS is False:
        _warn_user_rhs(rhs, "the compiled steppers failed to load earlier in this process")
        return None
    kernels = _RHS_KERNELS
    with_event = name == "dop853_rhs" and not any(a is NO_EVENT for a in args)
    args = tuple(kernels.no_event if a is NO_EVENT else a for a in args)
    try:
        done: tuple[int, ...] = getattr(kernels, name)(rhs, y0, *args)
        return done
    except Exception as exc:  # numba's typing or lowering errors are not one class
        first = str(exc).strip().splitlines()[0] if str(exc).strip() else ""
        event = " (or its event as event(t, y) -> float64)" if with_event else ""
        _warn_user_rhs(
            rhs,
            f"it does not compile as rhs(t: float64, y: float64[::1]) -> float64[::1]{event} "
            f"({type(exc).__name__}: {first})",
        )
        return None
