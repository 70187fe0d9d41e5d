"""Argument checks and small building blocks shared by the strategy modules (private)."""

from __future__ import annotations

import math
from collections.abc import Iterable
from numbers import Integral, Real

from hypothesis import strategies as st
from hypothesis.errors import InvalidArgument


def check_real(value: object, name: str) -> float:
    """A finite real bound, else InvalidArgument quoting it."""
    if isinstance(value, bool) or not isinstance(value, Real):
        raise InvalidArgument(f"{name}={value!r} must be a real number")
    v = float(value)
    if not math.isfinite(v):
        raise InvalidArgument(f"{name}={value!r} must be finite")
    return v


def check_positive(value: object, name: str) -> float:
    """A finite bound > 0, else InvalidArgument quoting it."""
    v = check_real(value, name)
    if not v > 0:
        raise InvalidArgument(f"{name}={value!r} must be finite and > 0")
    return v


def check_int(value: object, name: str, minimum: int) -> int:
    """An integer ≥ ``minimum``, else InvalidArgument quoting it."""
    if isinstance(value, bool) or not isinstance(value, Integral):
        raise InvalidArgument(f"{name}={value!r} must be an integer")
    if value < minimum:
        raise InvalidArgument(f"{name}={value!r} must be >= {minimum}")
    return int(value)


def check_regimes(
    regimes: Iterable[str] | None, allowed: tuple[str, ...], name: str
) -> tuple[str, ...]:
    """The chosen regimes (all by default), in the documented order: simplest first."""
    if regimes is None:
        return allowed
    if isinstance(regimes, str):
        raise InvalidArgument(f"regimes={regimes!r} must be a collection of names, not a string")
    chosen = tuple(regimes)
    unknown = [r for r in chosen if r not in allowed]
    if unknown:
        raise InvalidArgument(f"regimes={regimes!r}: unknown {unknown}; {name} has {allowed}")
    if not chosen:
        raise InvalidArgument(f"regimes={regimes!r} is empty; choose from {allowed}")
    return tuple(r for r in allowed if r in chosen)


def log_uniform(lo: float, hi: float, *, shrink_to: str) -> st.SearchStrategy[float]:
    """Floats in [lo, hi] (0 < lo ≤ hi), log-uniform, shrinking toward ``"lo"`` or ``"hi"``.

    Any other ``shrink_to`` is refused (``ValueError``): a misspelt ``"low"`` used to
    shrink silently toward ``hi``.
    """
    if shrink_to not in ("lo", "hi"):
        raise ValueError(f"shrink_to={shrink_to!r} must be 'lo' or 'hi'")
    a, b = math.log10(lo), math.log10(hi)
    if shrink_to == "lo":
        return st.floats(0.0, 1.0).map(lambda t: min(hi, max(lo, 10.0 ** (a + (b - a) * t))))
    return st.floats(0.0, 1.0).map(lambda t: min(hi, max(lo, 10.0 ** (b - (b - a) * t))))
