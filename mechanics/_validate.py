"""Input validation at the public boundary (private helpers).

``as_float_array`` is the one gate every public function passes its array inputs
through: it converts to float64 without silently truncating complex or object
input, checks the trailing shape, and rejects NaN and infinities by naming the
first offending entry.
"""

from __future__ import annotations

import dataclasses
import functools
import inspect
import re
from collections.abc import Callable
from typing import Any, TypeVar, cast

import numpy as np
import numpy.typing as npt

from .errors import (
    MechanicsValueError,
    NonFiniteError,
    NonPositiveParameterError,
    ResultOverflowError,
    ShapeError,
    UnknownOptionError,
)


def _first_bad(a: np.ndarray) -> str:
    idx = np.argwhere(~np.isfinite(a))[0]
    # a Python float's repr: "nan", "inf", "-inf" (numpy 2's scalar repr would print
    # "np.float64(nan)" into the user's message)
    return f"{float(a[tuple(idx)])!r} at index {tuple(int(i) for i in idx)}"


def as_float_array(x: object, name: str, tail: tuple[int, ...] = ()) -> npt.NDArray[np.float64]:
    """Return ``x`` as a finite float64 array whose shape ends with ``tail``."""
    try:
        a = np.asarray(x)
    except Exception as exc:  # ragged lists and the like
        raise ShapeError(f"{name} is not an array of numbers: {exc}") from None
    if a.dtype.kind == "c":
        raise ShapeError(f"{name} is complex ({a.dtype}); a real array is required")
    if a.dtype.kind not in "biuf":
        raise ShapeError(f"{name} has dtype {a.dtype}; a real numeric array is required")
    a = a.astype(np.float64, copy=False)
    if tail and (a.ndim < len(tail) or a.shape[a.ndim - len(tail) :] != tail):
        want = "(..., " + ", ".join(map(str, tail)) + ")"
        raise ShapeError(f"{name} has shape {a.shape}; expected {want}")
    if not np.isfinite(a).all():
        raise NonFiniteError(f"{name} must be finite; found {_first_bad(a)}")
    return a


def check_option(value: object, allowed: tuple[str, ...], what: str) -> str:
    """``value`` if it is one of ``allowed``, else :class:`UnknownOptionError` naming it
    and the choices."""
    if value not in allowed:
        raise UnknownOptionError(f"{what} must be one of {allowed}; got {value!r}")
    return allowed[allowed.index(value)]  # the allowed string itself


def as_float_scalar(x: object, name: str) -> float:
    """Return ``x`` as a finite Python float; a ShapeError naming ``name`` if not a scalar."""
    a = as_float_array(x, name)
    if a.shape != ():
        raise ShapeError(f"{name} must be a scalar; got shape {a.shape}")
    return float(a)


def as_positive_scalar(x: object, name: str) -> float:
    """Return ``x`` as a finite Python float > 0; a ShapeError, NonFiniteError or
    NonPositiveParameterError naming ``name`` otherwise."""
    v = as_float_scalar(x, name)
    if not v > 0:
        raise NonPositiveParameterError(f"{name} must be > 0; got {v!r}")
    return v


def _nonfinite(x: object) -> bool:
    """True if a result (array, number, tuple, dataclass) holds NaN or an infinity."""
    if isinstance(x, (bool, np.bool_, str, type(None))):
        return False
    if isinstance(x, (int, float, np.number)):
        return not np.isfinite(x)
    if isinstance(x, np.ndarray):
        return x.dtype.kind in "fc" and not np.isfinite(x).all()
    if isinstance(x, (tuple, list)):
        return any(_nonfinite(v) for v in x)
    if dataclasses.is_dataclass(x) and not isinstance(x, type):
        return any(_nonfinite(getattr(x, f.name)) for f in dataclasses.fields(x))
    return False


#: numpy's messages for arrays whose shapes do not broadcast
_BROADCAST = re.compile(r"could not be broadcast|cannot be broadcast|shape mismatch")


def _shapes(sig: inspect.Signature, args: tuple[Any, ...], kwargs: dict[str, Any]) -> str:
    """ "name shape, ..." of the array-like arguments of a call (for a ShapeError)."""
    try:
        bound = sig.bind(*args, **kwargs)
    except TypeError:
        return "(arguments not bound)"
    out: list[str] = []
    for name, v in bound.arguments.items():
        if isinstance(v, (np.ndarray, list, tuple, float, int)) and not isinstance(v, bool):
            try:
                out.append(f"{name} {np.shape(v)}")
            except ValueError:  # ragged
                out.append(f"{name} (ragged)")
    return ", ".join(out)


_F = TypeVar("_F", bound=Callable[..., Any])


def finite_result(fn: _F) -> _F:
    """Decorator: a function of finite inputs returns a finite result, or raises.

    Every public function validates its inputs as finite (:func:`as_float_array`), so
    a non-finite result can only come from an intermediate beyond float64's range
    (~1.8e308: a velocity of 1e300 squared, say; Python's float arithmetic raises
    ``OverflowError`` there instead). Both are reported as a
    :class:`~mechanics.errors.ResultOverflowError` naming the function, never as a
    silent ``inf``/``NaN`` or a numpy ``RuntimeWarning``. Division by zero is not
    masked: each function refuses its own zero denominators by name. Arguments whose
    batch axes do not broadcast raise a :class:`~mechanics.errors.ShapeError` listing
    each argument's shape, not numpy's bare ``ValueError``.

    Apply it after the definition, ``f = finite_result(f)``, not as ``@finite_result``:
    mutmut does not mutate decorated functions, and every body of ``mechanics`` is
    mutation-tested (``docs/mutation.md``; ``tests/test_mutation_setup.py`` holds the rule).
    """

    sig = inspect.signature(fn)

    @functools.wraps(fn)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        try:
            with np.errstate(over="ignore", invalid="ignore"):
                out = fn(*args, **kwargs)
        except OverflowError:  # Python float arithmetic (x**2, math.exp) raises instead
            raise ResultOverflowError(
                f"{fn.__name__}: an intermediate exceeds float64's range (~1.8e308) for these "
                "finite inputs; rescale the inputs (choose units)"
            ) from None
        except ValueError as exc:
            if isinstance(exc, MechanicsValueError) or not _BROADCAST.search(str(exc)):
                raise
            raise ShapeError(
                f"{fn.__name__}: the leading (batch) axes of the arguments do not broadcast: "
                + _shapes(sig, args, kwargs)
            ) from None
        if _nonfinite(out):
            raise ResultOverflowError(
                f"{fn.__name__}: the result is not finite for finite inputs: an intermediate "
                "exceeds float64's range (~1.8e308); rescale the inputs (choose units)"
            )
        return out

    return cast(_F, wrapper)


def broadcast_checked(fn: _F) -> _F:
    """Decorator: arguments whose batch axes do not broadcast raise a ShapeError.

    For functions whose non-finite results are documented (``ellipk(1) = inf``) and so
    cannot take :func:`finite_result`: only numpy's bare broadcasting ``ValueError`` is
    turned into a :class:`~mechanics.errors.ShapeError` listing each argument's shape.
    Applied after the definition, like :func:`finite_result`.
    """
    sig = inspect.signature(fn)

    @functools.wraps(fn)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        try:
            return fn(*args, **kwargs)
        except ValueError as exc:
            if isinstance(exc, MechanicsValueError) or not _BROADCAST.search(str(exc)):
                raise
            raise ShapeError(
                f"{fn.__name__}: the leading (batch) axes of the arguments do not broadcast: "
                + _shapes(sig, args, kwargs)
            ) from None

    return cast(_F, wrapper)
