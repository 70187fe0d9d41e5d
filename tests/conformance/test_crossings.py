"""``crossings`` at roots of any multiplicity: samples of random polynomials with a root of
multiplicity 1, 2 or 3 at a sample or between two, against the root itself.

The samples are the float64 values of an exactly known polynomial, so the root is known
exactly; the interpolating quintic reproduces the polynomial (degree ≤ 5) up to the
samples' rounding.  A double root between samples is not a crossing (the samples never
change sign); a double root at a sample is a zero touched once.
"""

from __future__ import annotations

import numpy as np
from hypothesis import example, given
from hypothesis import strategies as st

from mechanics._floats import EPS
from mechanics.conformance.scenarios import crossings

#: the crossing's time against the root, in eps of the larger of |t| and the spacing h:
#: measured ≤ 1.7 over 2·10^4 random polynomials of this family (numpy 2.4, Python 3.11;
#: the old fixed eight Newton steps missed double roots at a sample by up to 2e-3 h on
#: numpy 2.5); 2^3 leaves a margin of 4.  A triple root is found as the simple root of the
#: second derivative, so its bound is the simple root's.
ROOT_ULPS = 2**3
N_SAMPLES = 24


@st.composite
def sampled_roots(draw):
    """(t, y, root, multiplicity, at_sample): y = a (t − r)^m (t − q) sampled on a uniform
    grid of spacing h = 2^-p, r at a sample or inside an interval, q at least 1.5 h from r
    (so a sample lies between them and the samples change sign at r)."""
    m = draw(st.integers(1, 3))
    h = 2.0 ** -draw(st.integers(0, 6))
    t = (draw(st.integers(0, 400)) + np.arange(N_SAMPLES)) * h
    j = draw(st.integers(3, N_SAMPLES - 4))
    at_sample = draw(st.booleans())
    r = t[j] if at_sample else t[j] + h * draw(st.floats(0.05, 0.95))
    a = draw(st.sampled_from([-1.0, 1.0])) * 10.0 ** draw(st.floats(-3, 3))
    q = r + draw(st.sampled_from([-1.0, 1.0])) * h * draw(st.floats(1.5, 3.0))
    return t, a * (t - r) ** m * (t - q), r, m, at_sample


@given(sampled_roots())
@example((np.arange(9) / 4, (np.arange(9) / 4 - 1.0) ** 2, 1.0, 2, True))
def test_a_root_of_multiplicity_one_to_three_is_found_to_rounding(case) -> None:
    t, y, r, m, at_sample = case
    h = t[1] - t[0]
    near = crossings(t, y)
    near = near[np.abs(near - r) < 0.9 * h]  # the other factor's root is ≥ 1.5 h away
    if m == 2 and not at_sample:
        assert near.size == 0, f"a double root between samples is no crossing: {near}"
        return
    assert near.size == 1, f"multiplicity {m} at {r!r}: crossings near it {near}"
    assert abs(near[0] - r) <= ROOT_ULPS * EPS * max(abs(r), h), (m, at_sample, near[0] - r)


def test_a_triple_root_between_samples_is_the_second_derivatives_root_not_the_bisection():
    # y = (t − 1.1)³ on a grid of 1/4: bisection of the sampled quintic alone stops
    # anywhere in a cluster of width ~ (rounding)^(1/3) ≈ 6e-6 around the root
    t = np.arange(12) / 4
    r = 1.1
    z = crossings(t, (t - r) ** 3)
    assert z.size == 1
    assert abs(z[0] - r) <= ROOT_ULPS * EPS * r


def test_a_sample_that_is_exactly_zero_is_the_crossing_time_exactly():
    # t[k] + h·x with x = 1 need not round to t[k + 1]; the sample's own time is returned
    t = np.array([0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7])
    y = np.array([3.0, 2.0, 1.0, 0.0, -1.0, -2.0, -3.0])
    assert crossings(t, y).tolist() == [0.4]
