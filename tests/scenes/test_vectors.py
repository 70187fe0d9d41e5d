"""mechanics/scenes/vectors.py: the engine's written-out cross products are np.cross,
bit for bit, in every shape the engine uses (one vector, stacks, broadcasting)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

from mechanics.scenes.vectors import cross, cross3

#: any finite float, subnormals and huge magnitudes included (products may overflow to
#: inf and differences to nan: then both must agree on that too)
_FLOATS = st.floats(allow_nan=False, allow_infinity=False)


@st.composite
def _pairs(draw):
    """Two float arrays ending in 3 whose leading shapes broadcast."""
    shape = draw(hnp.array_shapes(min_dims=0, max_dims=2, max_side=4))
    shapes = draw(hnp.mutually_broadcastable_shapes(num_shapes=2, base_shape=shape))
    a = draw(hnp.arrays(np.float64, (*shapes.input_shapes[0], 3), elements=_FLOATS))
    b = draw(hnp.arrays(np.float64, (*shapes.input_shapes[1], 3), elements=_FLOATS))
    return a, b


@given(_pairs())
def test_cross_is_np_cross_bit_for_bit(pair) -> None:
    a, b = pair
    with np.errstate(over="ignore", invalid="ignore"):
        got, want = cross(a, b), np.cross(a, b)
    assert got.shape == want.shape
    assert np.array_equal(got, want, equal_nan=True)


@given(hnp.arrays(np.float64, 3, elements=_FLOATS), hnp.arrays(np.float64, 3, elements=_FLOATS))
def test_cross3_is_np_cross_bit_for_bit(a, b) -> None:
    with np.errstate(over="ignore", invalid="ignore"):
        assert np.array_equal(cross3(a, b), np.cross(a, b), equal_nan=True)


def test_the_comparison_sees_a_wrong_sign() -> None:
    """Negative control: a product with one term's sign flipped is told apart."""
    a, b = np.array([1.0, 2.0, 3.0]), np.array([-4.0, 5.0, 0.5])
    wrong = np.array([a[1] * b[2] + a[2] * b[1], *np.cross(a, b)[1:]])
    assert not np.array_equal(wrong, cross(a, b))


def test_a_shape_not_ending_in_3_is_refused() -> None:
    with pytest.raises(ValueError, match=r"shapes \(2,\) and \(3,\) must end in 3"):
        cross([1.0, 2.0], [1.0, 2.0, 3.0])
