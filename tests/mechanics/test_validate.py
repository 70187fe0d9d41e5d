"""The shared validation's messages read as the user wrote the value."""

from __future__ import annotations

import math

import numpy as np
import pytest

from mechanics._validate import as_float_array
from mechanics.errors import NonFiniteError


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
