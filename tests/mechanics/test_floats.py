"""The shared error-free transformations (mechanics._floats, issue 35): each result is
checked in exact rational arithmetic (fractions.Fraction), an independent route; a
negative control shows the check rejects a transformation that drops its error term."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from mechanics import _floats

#: operands whose products and sums stay within float64's range and the splits'
#: domain (|a| < 2^996), and whose error terms do not underflow (|a| > 2^-400)
_mag = st.floats(2.0**-400, 2.0**400)
_f = st.builds(lambda m, neg: -m if neg else m, _mag, st.booleans())


@given(_f, _f)
def test_two_sum_is_exact(a, b) -> None:
    s, e = _floats.two_sum(a, b)
    assert s == a + b
    assert Fraction(s) + Fraction(e) == Fraction(a) + Fraction(b)


@given(_f, _f)
def test_fast_two_sum_is_exact_for_the_larger_first(a, b) -> None:
    a, b = (a, b) if abs(a) >= abs(b) else (b, a)
    s, e = _floats.fast_two_sum(a, b)
    assert Fraction(s) + Fraction(e) == Fraction(a) + Fraction(b)


@given(_f)
def test_split_is_exact_with_a_26_bit_head(a) -> None:
    hi, lo = _floats.split(a)
    assert Fraction(hi) + Fraction(lo) == Fraction(a)
    m, _ = np.frexp(hi)  # hi = m 2^k with 0.5 <= |m| < 1: 26 significant bits at most
    assert float(m) * 2.0**26 == round(float(m) * 2.0**26)


@given(_f, _f)
def test_two_prod_is_exact(a, b) -> None:
    p, e = _floats.two_prod(a, b)
    assert p == a * b
    assert Fraction(p) + Fraction(e) == Fraction(a) * Fraction(b)


def test_the_exactness_check_rejects_a_dropped_error_term() -> None:
    a, b = 0.1, 0.2  # their float sum rounds: the error term is not zero
    s, e = _floats.two_sum(a, b)
    assert e != 0.0
    assert Fraction(s) + 0 != Fraction(a) + Fraction(b)  # what e = 0 would claim
    assert _floats.EPS == 2.0**-52
    assert _floats.SPLITTER == 2.0**27 + 1.0


def test_arrays_are_transformed_elementwise() -> None:
    a = np.array([0.1, 1e300, -3.0])
    b = np.array([0.2, 1e-300, 7.0])
    s, e = _floats.two_sum(a, b)
    for k in range(3):
        assert Fraction(s[k]) + Fraction(e[k]) == Fraction(a[k]) + Fraction(b[k])
