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


# ------------------------------------------------ double-double helpers

#: a double-double carries 106 significant bits; each helper rounds a few times (Dekker's
#: product and division lose up to about 4 bits): a relative error of 2^-100 is their bound
DD_RELATIVE = Fraction(1, 2**100)

#: pair magnitudes as the callers scale them (<= 1), away from underflow
_unit = st.floats(2.0**-60, 1.0)
_signed_unit = st.builds(lambda m, neg: -m if neg else m, _unit, st.booleans())


def _pair(hi: float, tail: float) -> tuple[float, float]:
    """A normalised double-double hi + lo with lo a fraction of ulp(hi)/2."""
    lo = tail * np.spacing(abs(hi)) / 2
    s, e = _floats.fast_two_sum(hi, lo)
    return s, e


def _value(x) -> Fraction:
    return Fraction(x[0]) + Fraction(x[1])


def _close(got: Fraction, exact: Fraction) -> bool:
    return abs(got - exact) <= DD_RELATIVE * abs(exact)


@given(_signed_unit, st.floats(-1, 1), _signed_unit, st.floats(-1, 1))
def test_double_double_sum_product_and_quotient_carry_about_106_bits(a, ta, b, tb) -> None:
    x, y = _pair(a, ta), _pair(b, tb)
    X, Y = _value(x), _value(y)
    assert _close(_value(_floats.dd_mul(x, y)), X * Y)
    assert _close(_value(_floats.dd_times(a, *y)), Fraction(a) * Y)
    assert _close(_value(_floats.dd_div(a, y)), Fraction(a) / Y)
    total = _floats.dd_add(*x, *y)
    # a sum is exact up to one rounding of the error terms, relative to the operands
    assert abs(_value(total) - (X + Y)) <= DD_RELATIVE * (abs(X) + abs(Y))
    # float + pair, rounded to float: within half an ulp of the exact sum, plus the pair's
    # own rounding (relative 2^-100 of the operands)
    s = _floats.dd_add_float(a, y)
    assert abs(Fraction(s) - (Fraction(a) + Y)) <= Fraction(np.spacing(abs(s))) / 2 + (
        DD_RELATIVE * (abs(Fraction(a)) + abs(Y))
    )


def test_the_double_double_bound_rejects_a_product_that_drops_the_cross_terms() -> None:
    x, y = _pair(0.1, 0.9), _pair(0.3, -0.7)
    p, err = _floats.two_prod(x[0], y[0])
    dropped = _floats.fast_two_sum(p, err)  # dd_mul without a_hi b_lo + a_lo b_hi
    assert not _close(_value(dropped), _value(x) * _value(y))
    assert _close(_value(_floats.dd_mul(x, y)), _value(x) * _value(y))


# ------------------------------------------------ ulps


def test_ulps_measures_in_units_in_the_last_place_at_the_exact_value() -> None:
    assert _floats.ulps(1.0, Fraction(1)) == 0.0
    assert _floats.ulps(1.0 + 2 * _floats.EPS, Fraction(1)) == 2.0
    # below a power of two the unit is the spacing of float(exact) (above it)
    assert _floats.ulps(1.0 - _floats.EPS / 2, Fraction(1)) == 0.5  # the float below 1
    assert _floats.ulps(0.0, Fraction(0)) == 0.0
    assert _floats.ulps(5e-324, Fraction(0)) == 1.0  # at 0 the unit is the least subnormal
    # the float 0.3 against 3/10: its rounding error, exactly, in ulps
    exact_err = abs(Fraction(0.3) - Fraction(3, 10)) / Fraction(np.spacing(0.3))
    assert _floats.ulps(0.3, Fraction(3, 10)) == float(exact_err)
