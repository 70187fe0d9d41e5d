"""Table-driven checks that a module's error messages name the parameter and the condition.

Every public function of a module is called with a valid call (the fuzz suite's entries,
:mod:`tests.fuzz.entries`) in which one parameter is broken: NaN in one entry, a wrong
trailing shape, a string, or one of the entry's unphysical values. The error must name the
parameter as a word of its own (case counts: ``omega``, not ``XXomegaXX``, ``OMEGA`` or
``omega_0``) and say the violated condition. Mutation testing (issue 16) showed that
messages no test reads drift unnoticed; users rely on them.
"""

from __future__ import annotations

import re

import numpy as np
import pytest

from mechanics.errors import MechanicsValueError, NonFiniteError, ShapeError
from tests.fuzz.entries import ENTRIES

#: what a field's message says when it returned NaN: "v(r, t) returned a non-finite value"
FIELD_NONFINITE = r"\(r, t\) returned a non-finite value at t = "


def word(name: str) -> str:
    """A regex matching ``name`` as a word of its own, case-sensitive."""
    return rf"(?<![A-Za-z0-9_]){re.escape(name)}(?![A-Za-z0-9_])"


def entries_of(module: str) -> dict:
    """The fuzz entries of ``mechanics.<module>``'s public callables, by short name."""
    prefix = f"mechanics.{module}."
    return {k.removeprefix(prefix): e for k, e in ENTRIES.items() if k.startswith(prefix)}


def valid_kwargs(module: str, fname: str) -> dict:
    return dict(entries_of(module)[fname].kw)


def _with_nan(v, tail):
    a = np.array(v, dtype=float)
    if a.ndim == 0:
        return np.nan
    a.flat[a.size // 2] = np.nan
    return a


def _wrong_tail(v):
    a = np.array(v, dtype=float)
    return a[..., :-1] if a.shape[-1] > 1 else np.concatenate([a, a], axis=-1)


def cases(module: str, conditions: dict, skip: frozenset = frozenset(), other: dict | None = None):
    """``pytest.param(fname, param, value, error, condition)`` for every broken parameter.

    ``conditions[(fname, param)]`` is the regex of the condition an unphysical value of
    the entry violates (required for every such value); ``skip`` holds ``(fname, param,
    kind)`` triples whose kind of break the function reports through another route, and
    ``other[(fname, param, kind)]`` the condition where a function words it its own way.
    """
    other = other or {}
    for fname, entry in entries_of(module).items():
        for p in entry.numeric():
            if p not in entry.kw:
                continue
            v, tail = entry.kw[p], entry.tail(p)
            kinds = [("nan", _with_nan(v, tail), NonFiniteError, r"must be finite; found nan")]
            if len(tail) >= 1:
                kinds.append(("shape", _wrong_tail(v), ShapeError, r"has shape .*expected"))
            kinds.append(("str", "1.0", ShapeError, r"has dtype <U3; a real numeric array"))
            for kind, value, error, cond in kinds:
                cond = other.get((fname, p, kind), cond)
                if (fname, p, kind) not in skip:
                    yield pytest.param(fname, p, value, error, cond, id=f"{fname}-{p}-{kind}")
        for p, bads in entry.bad.items():
            for i, bad in enumerate(bads):
                if (fname, p, f"bad{i}") in skip:
                    continue
                # a field (callable) that returns NaN is named as the call that returned it
                cond = FIELD_NONFINITE if callable(bad) else conditions[(fname, p)]
                cond = other.get((fname, p, f"bad{i}"), cond)
                yield pytest.param(
                    fname, p, bad, MechanicsValueError, cond, id=f"{fname}-{p}-bad{i}"
                )


def check_refusal(fn, kwargs: dict, param: str, error, condition: str) -> None:
    """Call ``fn(**kwargs)``: it must raise ``error`` naming ``param`` and ``condition``."""
    with pytest.raises(error) as info:
        fn(**kwargs)
    msg = str(info.value)
    assert re.search(word(param), msg), f"the message does not name {param!r}: {msg}"
    assert re.search(condition, msg), f"the message does not say {condition!r}: {msg}"
