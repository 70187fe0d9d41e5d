"""Fuzz every public callable of :mod:`mechanics` (issue 16, part 3).

The rule, one for the whole surface
-----------------------------------
Each parameter of a valid call (:mod:`tests.fuzz.entries`) is replaced in turn by

- NaN, +inf, -inf (one entry of an array, the rest valid),
- a wrong shape (a wrong trailing dimension; a ragged list for a scalar),
- a string, a complex number, ``None``,
- the entry's unphysical values (negative mass, e = 1.5, a zero axis, ...),
- for an option (``basis=``, ``separating=``...), an unknown value,

and the call must raise a :class:`mechanics.errors.MechanicsValueError` whose message
names the parameter. **Wrong types are ValueErrors too**: a string, a complex number or
``None`` is bad *data* (``np.asarray`` takes them all), so the gate ``as_float_array``
refuses them with a ``ShapeError``; a ``TypeError`` is not accepted. ``None`` for a
parameter whose default is ``None`` is a valid call. Then each numeric parameter takes
the extremes 0, -1, 1e-300, 1e300, -1e300 (an array: scaled by them), where either a
finite result or a ``MechanicsValueError`` is right. Never anything else: no silent NaN,
no ``IndexError``/``ZeroDivisionError``/``LinAlgError``, no numpy warning (the suite
turns warnings into errors).

Two parameters given batches of different lengths (2 and 3 along a new leading axis)
must be refused with a ``ShapeError`` too, not numpy's bare broadcasting ``ValueError``.
"""

from __future__ import annotations

import dataclasses
import inspect
import math
import os
import re
import warnings

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from mechanics.errors import MechanicsValueError, UnknownOptionError

from .entries import ENTRIES, EXEMPT, Entry, _body
from .surface import public_callables

SURFACE = public_callables()

#: (entry, parameter) pairs that fail the rule in modules this branch may not change:
#: ``xfail(strict=True)``, so a fix turns them into failures to clean up here.  Empty: the
#: last known failures (of dynamics, impact, inertia and rotation, issue 16) are fixed; a
#: failure found later and not fixed at once gets a line here, with its reason
KNOWN: dict[tuple[str, str], str] = {}


def test_every_public_callable_has_a_fuzz_entry_or_a_stated_exemption():
    missing = sorted(set(SURFACE) - set(ENTRIES) - set(EXEMPT))
    assert not missing, f"public callables without a fuzz entry (add them to entries.py): {missing}"


def test_no_fuzz_entry_names_a_callable_that_is_gone():
    stale = sorted((set(ENTRIES) | set(EXEMPT)) - set(SURFACE))
    assert not stale, f"fuzz entries for names no longer public: {stale}"


def test_every_entry_is_a_valid_call_with_a_finite_result():
    failures = []
    for name, entry in ENTRIES.items():
        try:
            _check_finite(_call(name, entry, {}), name)
        except Exception as exc:  # report them all at once
            failures.append(f"{name}: {type(exc).__name__}: {exc}")
    assert not failures, "\n".join(failures)


def test_every_parameter_of_an_entry_is_a_parameter_of_its_callable():
    wrong = []
    for name, entry in ENTRIES.items():
        params = inspect.signature(SURFACE[name]).parameters
        wrong += [f"{name}({p})" for p in entry.kw if p not in params]
    assert not wrong, wrong


# ------------------------------------------------------------------------------ helpers


def _call(name: str, entry: Entry, override: dict):
    fn = SURFACE[name]
    kw = {k: _materialise(v) for k, v in entry.kw.items()} | override
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        out = fn(**kw)
        if entry.post is not None:
            out = (out, entry.post(out))
    return out


def _materialise(v):
    return _body() if isinstance(v, str) and v == "body" else v


def _numbers(x, seen=None):
    """Every number in a result: arrays, scalars, tuples, dataclasses, dicts."""
    if isinstance(x, (bool, np.bool_, str, type(None))) or callable(x):
        return
    if isinstance(x, (int, float, np.number)):
        yield float(x)
    elif isinstance(x, np.ndarray):
        if x.dtype.kind in "biuf":
            yield from x.astype(float).ravel()
    elif isinstance(x, dict):
        for v in x.values():
            yield from _numbers(v)
    elif isinstance(x, (tuple, list)):
        for v in x:
            yield from _numbers(v)
    elif dataclasses.is_dataclass(x):
        for f in dataclasses.fields(x):
            yield from _numbers(getattr(x, f.name))


def _check_finite(out, what: str) -> None:
    bad = [v for v in _numbers(out) if not math.isfinite(v)]
    assert not bad, f"{what}: a non-finite result leaked silently: {bad[:3]}"


def _nan_like(v, tail, fill):
    a = np.array(v, dtype=float)
    if a.ndim == 0:
        return fill
    a.flat[a.size // 2] = fill
    return a


#: 1-D parameters of any length N (masses, densities, samples): their wrong shape is ragged
FREE_LENGTH = frozenset({"m", "rho", "P", "t", "s", "y0"})


def _wrong_shape(v, tail, param=""):
    if not tail or (len(tail) == 1 and param in FREE_LENGTH):
        return [[1.0, 2.0], [3.0]]  # ragged
    a = np.array(v, dtype=float)
    return a[..., :-1] if a.shape[-1] > 1 else np.concatenate([a, a], axis=-1)


def _default(name: str, param: str):
    p = inspect.signature(SURFACE[name]).parameters[param]
    return p.default


def names(message: str, param: str) -> bool:
    """Whether an error message names ``param`` as a word of its own: ``omega`` in "omega
    must be finite" or "body.omega[1]", not in "XXomegaXX" or "omega_0" (case counts)."""
    return re.search(rf"(?<![A-Za-z0-9_]){re.escape(param)}(?![A-Za-z0-9_])", message) is not None


def _reject_cases(name: str, entry: Entry, param: str):
    """(label, value) pairs that must be refused naming ``param``."""
    v, tail = entry.kw.get(param), entry.tail(param)
    if param in entry.numeric():
        yield "nan", _nan_like(v, tail, np.nan)
        yield "+inf", _nan_like(v, tail, np.inf)
        yield "-inf", _nan_like(v, tail, -np.inf)
        yield "wrong shape", _wrong_shape(v, tail, param)
        yield "a string", "1.0"
        yield "complex", np.array(v, dtype=float) + 1j
        if _default(name, param) is not None:
            yield "None", None
    for i, bad in enumerate(entry.bad.get(param, ())):
        yield f"unphysical[{i}] {bad!r}"[:60], bad
    if param in entry.opts:
        yield "unknown option", "no-such-option"


def _extreme_cases(entry: Entry, param: str):
    """(label, value) pairs where a finite result or a MechanicsValueError is right."""
    v = np.array(entry.kw[param], dtype=float)
    for s in (0.0, -1.0, 1e-300, 1e300, -1e300):
        yield f"x{s:g}", (s if v.ndim == 0 else v * s)


def _params_of(entry: Entry) -> list[str]:
    return list(dict.fromkeys([*entry.numeric(), *entry.bad, *entry.opts]))


def _cases():
    for name, entry in ENTRIES.items():
        for p in _params_of(entry):
            marks = []
            if (name, p) in KNOWN:
                marks = [pytest.mark.xfail(strict=True, reason=KNOWN[(name, p)])]
            yield pytest.param(name, p, id=f"{name.removeprefix('mechanics.')}:{p}", marks=marks)


def _outcome(name, entry, param, value):
    """None if the call returned a finite result, else the exception."""
    try:
        out = _call(name, entry, {param: value})
    except Exception as exc:
        return exc
    _check_finite(out, f"{name}({param}={value!r})")
    return None


@pytest.mark.parametrize(("name", "param"), list(_cases()))
def test_bad_input_is_refused_naming_the_parameter(name, param):
    entry = ENTRIES[name]
    problems = []
    for label, value in _reject_cases(name, entry, param):
        exc = _outcome(name, entry, param, value)
        if exc is None:
            problems.append(f"{label}: accepted (returned a finite result)")
        elif not isinstance(exc, MechanicsValueError):
            problems.append(f"{label}: {type(exc).__name__}: {exc}")
        elif label == "unknown option" and not isinstance(exc, UnknownOptionError):
            problems.append(f"{label}: {type(exc).__name__}, not UnknownOptionError: {exc}")
        elif not names(str(exc), param):
            problems.append(f"{label}: the message does not name {param!r}: {exc}")
    if param in entry.numeric():
        for label, value in _extreme_cases(entry, param):
            try:
                exc = _outcome(name, entry, param, value)
            except AssertionError as leak:
                problems.append(f"{label}: {leak}")
                continue
            if exc is not None and not isinstance(exc, MechanicsValueError):
                problems.append(f"{label}: {type(exc).__name__}: {exc}")
    assert not problems, f"{name}, parameter {param}:\n  " + "\n  ".join(problems)


def _batch_cases():
    for name, entry in ENTRIES.items():
        arr = [p for p in entry.numeric() if p in entry.kw]
        if len(arr) >= 2 and entry.batch:
            marks = []
            if (name, "<batch>") in KNOWN:
                marks = [pytest.mark.xfail(strict=True, reason=KNOWN[(name, "<batch>")])]
            yield pytest.param(
                name, arr[0], arr[1], id=name.removeprefix("mechanics."), marks=marks
            )


@pytest.mark.parametrize(("name", "p1", "p2"), list(_batch_cases()))
def test_batches_of_different_lengths_are_refused_with_a_shape_error(name, p1, p2):
    entry = ENTRIES[name]
    a = np.stack([np.asarray(entry.kw[p1], dtype=float)] * 2)
    b = np.stack([np.asarray(entry.kw[p2], dtype=float)] * 3)
    exc = None
    try:
        _call(name, entry, {p1: a, p2: b})
    except MechanicsValueError as e:
        exc = e
    assert isinstance(exc, MechanicsValueError), f"{name}: batches of 2 and 3 accepted"
    assert names(str(exc), p1) or names(str(exc), p2), f"{name}: the message names neither: {exc}"


# -------------------------------------------------------------------- hypothesis: any float
#: parameters whose failures for some floats come from the mutation helper's modules
#: parameters that take one float only where a number of another kind is meant
NOT_A_FLOAT = {
    ("mechanics.elliptic.ellipk", "m"),  # K(1) = inf: the true value, documented
    ("mechanics.integrators.time_grid", "n"),  # an integer count
}
_SCALAR_CASES = [
    (name, p)
    for name, entry in ENTRIES.items()
    for p in entry.numeric()
    if p in entry.kw and (name, p) not in KNOWN and (name, p) not in NOT_A_FLOAT
]


@settings(
    max_examples=int(os.environ.get("FUZZ_EXAMPLES", "300")),
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow],
)
@given(
    case=st.sampled_from(_SCALAR_CASES),
    x=st.floats(allow_nan=True, allow_infinity=True, allow_subnormal=True),
)
def test_any_float_in_any_numeric_parameter_gives_a_finite_result_or_a_mechanics_error(case, x):
    """One entry of a parameter (a scalar, or one component of an array) set to any
    float64, subnormals, ±0, ±inf and NaN included: a finite result or a
    MechanicsValueError, never a silent NaN, a numpy warning or another exception."""
    name, param = case
    entry = ENTRIES[name]
    value = _nan_like(entry.kw[param], entry.tail(param), x)
    exc = _outcome(name, entry, param, value)
    assert exc is None or isinstance(exc, MechanicsValueError), f"{type(exc).__name__}: {exc}"
    if not math.isfinite(x):
        assert exc is not None, f"{name}({param}={value!r}) accepted a non-finite input"
