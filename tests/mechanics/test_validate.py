"""The shared validation's messages read as the user wrote the value."""

from __future__ import annotations

import inspect
import math

import numpy as np
import pytest

from mechanics._validate import (
    _shapes,
    as_float_array,
    as_float_scalar,
    as_positive_scalar,
    broadcast_checked,
    finite_result,
)
from mechanics.errors import (
    NonFiniteError,
    NonPositiveParameterError,
    ResultOverflowError,
    ShapeError,
)


@pytest.mark.parametrize(
    ("value", "shown", "index"),
    [
        (math.nan, "nan", "()"),
        ([1.0, math.inf], "inf", "(1,)"),
        (np.array([[0.0, -np.inf]]), "-inf", "(0, 1)"),
    ],
)
def test_a_non_finite_value_is_named_plainly_with_its_index(value, shown, index) -> None:
    with pytest.raises(NonFiniteError) as info:
        as_float_array(value, "x")
    assert str(info.value) == f"x must be finite; found {shown} at index {index}"
    assert "np.float64" not in str(info.value)


# ------------------------------------------------- the decorators, on functions of the test
def _add(a, b):
    return np.asarray(a, float) + np.asarray(b, float)


def _square(x):
    return float(x) ** 2  # Python float arithmetic raises OverflowError


def test_finite_result_lists_each_arguments_shape_when_batches_do_not_broadcast():
    add = finite_result(_add)
    with pytest.raises(ShapeError) as info:
        add(np.ones((2, 3)), b=[[1.0, 2.0, 3.0]] * 3)
    assert str(info.value) == (
        "_add: the leading (batch) axes of the arguments do not broadcast: a (2, 3), b (3, 3)"
    )


def test_broadcast_checked_lists_each_arguments_shape_and_keeps_a_documented_inf():
    add = broadcast_checked(_add)
    with pytest.raises(ShapeError) as info:
        add(np.ones(2), np.ones(3))
    assert str(info.value) == (
        "_add: the leading (batch) axes of the arguments do not broadcast: a (2,), b (3,)"
    )
    assert add(np.inf, 1.0) == np.inf  # only the broadcasting error is translated


def test_finite_result_reports_a_non_finite_result_or_a_python_overflow_naming_the_function():
    add = finite_result(_add)
    with pytest.raises(ResultOverflowError) as info:
        add(1.7e308, 1.7e308)
    assert str(info.value).startswith("_add: the result is not finite for finite inputs")
    with pytest.raises(ResultOverflowError) as info:
        finite_result(_square)(1e200)
    assert str(info.value).startswith("_square: an intermediate exceeds float64's range")
    assert add(1.0, 2.0) == 3.0


def test_finite_result_passes_other_errors_through_unchanged():
    def refuse(x):
        raise NonFiniteError("x must be finite; found nan at index ()")

    def other(x):
        raise ValueError("not a broadcasting problem")

    with pytest.raises(NonFiniteError, match=r"^x must be finite; found nan at index \(\)$"):
        finite_result(refuse)(1.0)
    with pytest.raises(ValueError, match=r"^not a broadcasting problem$") as info:
        finite_result(other)(1.0)
    assert not isinstance(info.value, ShapeError)


def test_the_shapes_of_a_call_name_each_array_argument_and_say_when_they_do_not_bind():
    sig = inspect.signature(_add)
    assert _shapes(sig, (np.ones((2, 3)), 1.5), {}) == "a (2, 3), b ()"
    assert _shapes(sig, ([[1.0, 2.0], [3.0]], True), {}) == "a (ragged)"  # a bool is no array
    assert _shapes(sig, (1.0, 2.0, 3.0), {}) == "(arguments not bound)"


@pytest.mark.parametrize(
    ("call", "error", "message"),
    [
        (
            lambda: as_float_scalar([1.0, 2.0], "h"),
            ShapeError,
            "h must be a scalar; got shape (2,)",
        ),
        (lambda: as_positive_scalar(0.0, "g"), NonPositiveParameterError, "g must be > 0; got 0.0"),
        (
            lambda: as_positive_scalar(-2, "rho"),
            NonPositiveParameterError,
            "rho must be > 0; got -2.0",
        ),
        (
            lambda: as_float_array([1.0, 2.0], "v", (3,)),
            ShapeError,
            "v has shape (2,); expected (..., 3)",
        ),
        (
            lambda: as_float_array(np.ones((2, 3)), "J", (3, 3)),
            ShapeError,
            "J has shape (2, 3); expected (..., 3, 3)",
        ),
        (
            lambda: as_float_array(1j, "w"),
            ShapeError,
            "w is complex (complex128); a real array is required",
        ),
        (
            lambda: as_float_array("x", "m"),
            ShapeError,
            "m has dtype <U1; a real numeric array is required",
        ),
    ],
)
def test_each_gate_names_the_value_and_the_condition(call, error, message):
    with pytest.raises(error) as info:
        call()
    assert str(info.value) == message
