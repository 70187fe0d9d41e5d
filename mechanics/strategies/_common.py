"""Argument checks and small building blocks shared by the strategy modules (private)."""

from __future__ import annotations

import functools
import math
import threading
from collections import OrderedDict
from collections.abc import Callable, Hashable, Iterable
from numbers import Integral, Real
from typing import ParamSpec, TypeVar

from hypothesis import strategies as st
from hypothesis.errors import InvalidArgument

_P = ParamSpec("_P")
_S = TypeVar("_S")

#: how many strategies each factory keeps (least recently used dropped first): the test
#: suite builds a few hundred distinct ones per factory at most
MEMO_SIZE = 1024


class _Unkeyable(Exception):
    """An argument that is not a plain value (a strategy, an array, a generator)."""


def _key(value: object) -> Hashable:
    """``value`` as a key that tells apart whatever the factories tell apart: the type
    with the value, a float by its bits (−0.0 is not 0.0, 1.0 is not 1 or True), a
    list from a tuple; anything but None, bool, int, float, str and lists or tuples of
    them is refused (:class:`_Unkeyable`)."""
    if value is None or isinstance(value, str | bool | int):
        return (type(value), value)
    if isinstance(value, float):
        return (type(value), value.hex())
    if isinstance(value, list | tuple):
        return (type(value), tuple(_key(v) for v in value))
    raise _Unkeyable


def memoised(factory: Callable[_P, _S]) -> Callable[_P, _S]:
    """``factory`` returning one strategy object per distinct plain arguments.

    Building a strategy costs milliseconds: each ``@st.composite`` it defines makes
    hypothesis read and parse the function's source (``rotation_matrices()`` took 22 ms),
    and a strategy built inside another's draw pays that on every draw.  A strategy is
    an immutable description, so the same arguments can share one object: what it
    draws for given choices is the same, and so are its labels.  Arguments that are not
    plain values (strategies, arrays) are built afresh each call; a call that raises is
    never kept.
    """
    cache: OrderedDict[Hashable, _S] = OrderedDict()
    lock = threading.Lock()

    @functools.wraps(factory)
    def build(*args: _P.args, **kwargs: _P.kwargs) -> _S:
        try:
            key = (_key(args), _key(sorted(kwargs.items())))
        except _Unkeyable:
            return factory(*args, **kwargs)
        with lock:
            if key in cache:
                cache.move_to_end(key)
                return cache[key]
        made = factory(*args, **kwargs)
        with lock:
            cache[key] = made
            if len(cache) > MEMO_SIZE:
                cache.popitem(last=False)
        return made

    return build


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
