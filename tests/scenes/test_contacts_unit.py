"""Unit tests of :mod:`mechanics.scenes.contacts`, each against a hand derivation: the
real roots of a quadratic, the closed-form contact times of a body and a plane and of two
spheres in uniform relative motion (|d + w τ| = s), the Chebyshev fit's nodes, and the
search of a step's gap polynomial for its first downward crossing (a dip, a graze, a
touch, a fall after a touch), at the boundaries where a wrong comparison shows."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.polynomial import chebyshev as C

from mechanics._floats import EPS
from mechanics.scenes import contacts as ct

#: a root of a quadratic formed without cancellation: the square root and one division,
#: each rounded once, on O(1) numbers
ROOT_RTOL = 4 * EPS
#: brentq refined to xtol = rtol = 4 eps (scipy's floor), plus the rounding of the
#: polynomial's evaluation at O(1) arguments; its default xtol (2e-12) is 190 eps off
#: on the polynomial below, so a dropped xtol shows
BRENT_ATOL = 8 * EPS
#: the interpolation of a degree-8 polynomial at 9 Chebyshev nodes: a linear solve of
#: condition ~ 10 on values of size 3⁸; the coefficients are compared relative to Σ|c|
FIT_RTOL = 2**8 * EPS


def _cheb(*power_coefs: float) -> np.ndarray:
    """Chebyshev coefficients of c0 + c1 x + c2 x² + ... (numpy's exact conversion for
    these small integers and binary fractions)."""
    return C.poly2cheb(np.array(power_coefs, dtype=float))


# --------------------------------------------------------------------- quadratic_roots


@pytest.mark.parametrize(
    ("a", "b", "c", "roots"),
    [
        # (x − 1)(x − 2) = x² − 3x + 2
        (1.0, -3.0, 2.0, [1.0, 2.0]),
        # (x + 1)(x + 2) = x² + 3x + 2: b > 0 takes the other sign of the square root
        (1.0, 3.0, 2.0, [-2.0, -1.0]),
        # 2(x − 1)(x − 2) = 2x² − 6x + 4: q = −(b + sign(b)√disc)/2 = 4, roots q/a = 2, c/q = 1
        (2.0, -6.0, 4.0, [1.0, 2.0]),
        # −(x − 1)(x − 2) = −x² + 3x − 2: a < 0
        (-1.0, 3.0, -2.0, [1.0, 2.0]),
        # a double root (disc = 0): (x − 1)² = x² − 2x + 1, both copies
        (1.0, -2.0, 1.0, [1.0, 1.0]),
        # x² = 0: q = 0, the one root 0 (no division by q)
        (1.0, 0.0, 0.0, [0.0]),
        # (x − 3)(x + 5) = x² + 2x − 15: roots of opposite signs, sorted
        (1.0, 2.0, -15.0, [-5.0, 3.0]),
        # linear (a = 0): 2x − 4 = 0 at x = −c/b = 2
        (0.0, 2.0, -4.0, [2.0]),
        # constant: no root (not a division by zero)
        (0.0, 0.0, 1.0, []),
        # x² + 1: disc = −4 < 0
        (1.0, 0.0, 1.0, []),
        # x² + x + 1: disc = 1 − 4 = −3 < 0
        (1.0, 1.0, 1.0, []),
    ],
)
def test_quadratic_roots_are_the_real_roots_sorted(a, b, c, roots) -> None:
    assert ct.quadratic_roots(a, b, c) == roots


def test_quadratic_roots_use_four_a_c_in_the_discriminant() -> None:
    # x² + 2x + 0.9 (disc = 4 − 3.6 = 0.4): with 3ac or 5ac the discriminant moves
    # (1.3 or −0.5) and the roots with it; the roots −1 ± √0.1 by hand
    got = ct.quadratic_roots(1.0, 2.0, 0.9)
    want = [-1.0 - math.sqrt(0.1), -1.0 + math.sqrt(0.1)]
    assert got == pytest.approx(want, rel=ROOT_RTOL * 8, abs=0)


# ------------------------------------------------------------------ plane_contact_time


def test_a_body_thrown_up_lands_on_the_closing_root() -> None:
    # 1 + 10 τ − 5 τ² = 0: τ = 1 ± √1.2; the negative root is in the past, the
    # positive one is the landing, with v_n + a_n τ = 10 − 10(1 + √1.2) < 0 (closing)
    tau = ct.plane_contact_time(1.0, 10.0, -10.0)
    assert tau == pytest.approx(1.0 + math.sqrt(1.2), rel=ROOT_RTOL, abs=0)


def test_a_body_falling_from_rest_lands_at_the_free_fall_time() -> None:
    # 5 − 5 τ² = 0 (gap 5 m, g = 10): τ = 1, not −1 (in the past)
    assert ct.plane_contact_time(5.0, 0.0, -10.0) == 1.0
    # the half in ½ a τ²: gap 2, a = −1: τ = 2 (with 1.5 a instead: √(4/3))
    assert ct.plane_contact_time(2.0, 0.0, -1.0) == 2.0


def test_of_two_future_roots_the_first_closing_one_is_the_contact() -> None:
    # 1 − 3τ + τ² (a_n = 2 upward, v_n = −3): roots (3 ∓ √5)/2 = 0.382, 2.618; the
    # first is closing (−3 + 2·0.382 < 0), the second opening
    tau = ct.plane_contact_time(1.0, -3.0, 2.0)
    assert tau == pytest.approx((3.0 - math.sqrt(5.0)) / 2.0, rel=ROOT_RTOL, abs=0)


def test_roots_in_the_past_are_never_contacts() -> None:
    # 1 + 3τ + τ²: both roots (−3 ± √5)/2 < 0, one of them closing (v_n + a_n τ =
    # 3 + 2(−2.618) < 0): a body moving away from the plane never reaches it
    assert ct.plane_contact_time(1.0, 3.0, 2.0) == math.inf
    # leaving the plane: v_n > 0 from a zero gap, no force
    assert ct.plane_contact_time(0.0, 1.0, 0.0) == math.inf
    # moving parallel to it: no root at all
    assert ct.plane_contact_time(1.0, 0.0, 0.0) == math.inf


def test_touching_and_closing_at_the_start_is_a_contact_now() -> None:
    assert ct.plane_contact_time(0.0, -1.0, 0.0) == 0.0
    # uniform approach: 2 − 4 τ = 0 at τ = 0.5
    assert ct.plane_contact_time(2.0, -4.0, 0.0) == 0.5


def test_a_gap_that_only_touches_at_its_apex_is_no_contact() -> None:
    # 1 − 2τ + τ² = (1 − τ)²: touches at τ = 1 with zero normal speed (−2 + 2·1 = 0):
    # a graze, not a closing contact
    assert ct.plane_contact_time(1.0, -2.0, 2.0) == math.inf


# ------------------------------------------------------------------ sphere_contact_time


def test_an_oblique_approach_touches_at_the_entry_root() -> None:
    # d = (−5, 3, 0), w = (2, 0, 0), s = 5: (−5 + 2τ)² + 9 = 25, so 2τ − 5 = ±4:
    # entry at τ = 1/2, exit at 9/2.  d·w = −10, |w| s = 10, |d × w| = 6, disc = 4·16
    # exactly; c = (√34 − 5)(√34 + 5) = 9 up to the rounding of √34: τ = 9/(10 + 8)
    tau = ct.sphere_contact_time(np.array([-5.0, 3.0, 0.0]), np.array([2.0, 0.0, 0.0]), 5.0)
    assert tau == pytest.approx(0.5, rel=ROOT_RTOL, abs=0)


def test_a_head_on_approach_touches_after_the_gap_over_the_speed() -> None:
    # centres 3 apart along y, closing at 4 m/s, radii summing to 1: τ = (3 − 1)/4
    d, w = np.array([0.0, 3.0, 0.0]), np.array([0.0, -4.0, 0.0])
    assert ct.sphere_contact_time(d, w, 1.0) == 0.5


def test_an_impact_parameter_equal_to_the_sum_of_radii_is_a_graze() -> None:
    # d = (−3, 1, 0), w = (1, 0, 0), s = 1: |d × w| = 1 = |w| s exactly; the spheres
    # touch at τ = 3 with zero normal speed: no contact
    d, w = np.array([-3.0, 1.0, 0.0]), np.array([1.0, 0.0, 0.0])
    assert ct.sphere_contact_time(d, w, 1.0) == math.inf
    # just inside (impact parameter 0.5): a contact at τ = 3 − √(1 − 0.25)
    tau = ct.sphere_contact_time(np.array([-3.0, 0.5, 0.0]), w, 1.0)
    assert tau == pytest.approx(3.0 - math.sqrt(0.75), rel=ROOT_RTOL, abs=0)


def test_separating_or_tangential_spheres_never_touch() -> None:
    w = np.array([1.0, 0.0, 0.0])
    assert ct.sphere_contact_time(np.array([2.0, 0.0, 0.0]), w, 1.0) == math.inf  # receding
    # d·w = 0 exactly: moving across the line of centres
    assert ct.sphere_contact_time(np.array([0.0, 2.0, 0.0]), w, 1.0) == math.inf
    # at rest relative to each other
    assert ct.sphere_contact_time(np.array([-2.0, 0.0, 0.0]), 0 * w, 1.0) == math.inf


def test_spheres_overlapping_within_rounding_and_closing_touch_now() -> None:
    # d = (−0.4, 0, 0), s = 0.5: c = (0.4 − 0.5)(0.4 + 0.5) < 0, the root −0.1 is in
    # the past; closing, the contact is now (τ = 0), not later
    d, w = np.array([-0.4, 0.0, 0.0]), np.array([1.0, 0.0, 0.0])
    assert ct.sphere_contact_time(d, w, 0.5) == 0.0


# ------------------------------------------------------------------ chebyshev_fit


def test_the_fit_samples_the_chebyshev_points_of_the_first_kind_by_default() -> None:
    seen = []

    def fn(t):
        seen.append(np.array(t))
        return np.stack([t], axis=-1)

    coef = ct.chebyshev_fit(fn, 1.0, 3.0)
    (t,) = seen
    k = np.arange(9)  # STEP_NODES: a degree-7 step is interpolated with room to spare
    want = 2.0 + np.cos(np.pi * (2 * k + 1) / 18)  # x_k = cos(π(k + ½)/n), t = 2 + x
    np.testing.assert_allclose(t, want, rtol=0, atol=2 * EPS)
    assert coef.shape == (9, 1)
    # t = 2 + x: the coefficients (2, 1, 0, ...)
    np.testing.assert_allclose(coef[:, 0], [2.0, 1.0] + [0.0] * 7, rtol=0, atol=16 * EPS)


def test_the_fit_with_ends_samples_the_lobatto_points_including_both_ends() -> None:
    seen = []

    def fn(t):
        seen.append(np.array(t))
        return np.stack([t, t * t], axis=-1)

    coef = ct.chebyshev_fit(fn, 1.0, 3.0, n=5, ends=True)
    (t,) = seen
    # cos(π k/4), k = 0..4: 1, √½, 0, −√½, −1, mapped by t = 2 + x
    want = 2.0 + np.array([1.0, math.sqrt(0.5), 0.0, -math.sqrt(0.5), -1.0])
    np.testing.assert_allclose(t, want, rtol=0, atol=2 * EPS)
    assert (t[0], t[-1]) == (3.0, 1.0)  # both ends exactly: a crossing there is not lost
    assert coef.shape == (5, 2)
    # t² = (2 + x)² = 4 + 4x + x² = 4.5 T0 + 4 T1 + 0.5 T2
    want = [4.5, 4.0, 0.5, 0.0, 0.0]
    np.testing.assert_allclose(coef[:, 1], want, rtol=0, atol=FIT_RTOL * np.abs(want).sum())


def test_the_fit_interpolates_a_degree_eight_polynomial_exactly() -> None:
    # t⁸ on [1, 3]: t = 2 + x, (2 + x)⁸ = Σ C(8, j) 2^(8−j) x^j, converted by numpy
    power = [math.comb(8, j) * 2.0 ** (8 - j) for j in range(9)]
    want = C.poly2cheb(power)
    for ends in (False, True):
        coef = ct.chebyshev_fit(lambda t: np.stack([t**8], axis=-1), 1.0, 3.0, ends=ends)
        scale = np.abs(want).sum()
        np.testing.assert_allclose(coef[:, 0], want, rtol=0, atol=FIT_RTOL * scale)


# ------------------------------------------------------------ first_downward_crossing


def test_a_linear_fall_crosses_at_its_root() -> None:
    # 0.5 − x: the cheap bound c0 − Σ|c_k| = 0.5 − 1 < 0 does not skip it
    x = ct.first_downward_crossing(_cheb(0.5, -1.0), start_tol=0.0)
    assert x == pytest.approx(0.5, rel=0, abs=BRENT_ATOL)


def test_the_crossing_is_refined_to_a_few_eps() -> None:
    # 1 − 2x − x² = 2 − (x + 1)²: from 2 at x = −1 down to −2 at x = 1, crossing at √2 − 1
    x = ct.first_downward_crossing(_cheb(1.0, -2.0, -1.0), start_tol=0.0)
    assert x == pytest.approx(math.sqrt(2.0) - 1.0, rel=0, abs=BRENT_ATOL)


def test_a_polynomial_bounded_away_from_zero_has_no_crossing() -> None:
    # 1 + 0.5 T1 + 0.25 T2 ≥ 1 − 0.75 > 0 everywhere
    assert ct.first_downward_crossing(np.array([1.0, 0.5, 0.25]), start_tol=0.0) is None
    # a rising line from 0: never below zero
    assert ct.first_downward_crossing(_cheb(1.0, 1.0), start_tol=0.0) is None


def test_a_dip_between_positive_ends_is_found_at_its_first_zero() -> None:
    # x² − 1/4: 3/4 at both ends, −1/4 at the extremum x = 0, zeros at ∓1/2
    x = ct.first_downward_crossing(_cheb(-0.25, 0.0, 1.0), start_tol=0.0)
    assert x == pytest.approx(-0.5, rel=0, abs=BRENT_ATOL)


def test_a_dip_below_zero_by_exactly_the_tolerance_is_a_graze() -> None:
    # x² − 1/4 with start_tol 1/4: the minimum −1/4 lies within the rounding (≥ −tol),
    # inside the step, and rises again: a tangential touch, no contact
    assert ct.first_downward_crossing(_cheb(-0.25, 0.0, 1.0), start_tol=0.25) is None
    # beyond the tolerance it is a contact
    x = ct.first_downward_crossing(_cheb(-0.25, 0.0, 1.0), start_tol=0.125)
    assert x == pytest.approx(-0.5, rel=0, abs=BRENT_ATOL)


def test_a_fall_within_the_tolerance_at_the_end_of_the_step_is_a_contact() -> None:
    # ½(1 − x) − 1/8: from 7/8 down to −1/8 at x = 1, within start_tol = 1/4 of zero;
    # not a graze (it does not rise again inside the step): the crossing at x = 3/4
    x = ct.first_downward_crossing(_cheb(0.375, -0.5), start_tol=0.25)
    assert x == pytest.approx(0.75, rel=0, abs=BRENT_ATOL)


def test_extrema_outside_the_step_are_not_searched() -> None:
    # (x + 1.5)² − 0.01 has its minimum at x = −1.5, outside [−1, 1], where it is
    # negative; on the step it rises from 0.24: no crossing, no error
    p = _cheb(1.5**2 - 0.01, 3.0, 1.0)
    assert ct.first_downward_crossing(p, start_tol=0.0) is None
    # (x − 1.5)² − 0.01: falls over the step to 0.24 at x = 1, then past it: no crossing
    q = _cheb(1.5**2 - 0.01, -3.0, 1.0)
    assert ct.first_downward_crossing(q, start_tol=0.0) is None


def test_a_start_within_the_tolerance_and_falling_is_a_contact_now() -> None:
    # −x/2 − 1/4: 1/4 at x = −1, exactly start_tol: touching, and closing
    assert ct.first_downward_crossing(_cheb(-0.25, -0.5), start_tol=0.25) == -1.0
    # −1/4 at the start, exactly −start_tol, and falling: within rounding, now
    assert ct.first_downward_crossing(_cheb(-0.75, -0.5), start_tol=0.25) == -1.0


def test_a_start_within_the_tolerance_falling_to_exactly_zero_is_a_contact_now() -> None:
    # ¼(1 − x): ½ at the start (within start_tol ½), 0 at the end: c0 − Σ|c_k| = 0, the
    # cheap bound does not rule it out; touching and closing: the contact is now
    assert ct.first_downward_crossing(_cheb(0.25, -0.25), start_tol=0.5) == -1.0
    # the same fall from beyond the tolerance reaches zero only at the end: no crossing
    assert ct.first_downward_crossing(_cheb(0.25, -0.25), start_tol=0.25) is None


def test_past_a_graze_the_search_goes_on_to_the_crossing_after_it() -> None:
    # (x + ½)²(½ − x) − 1e-10: a dip to −1e-10 at x = −½ (within start_tol 1e-9, and
    # rising again: a graze), then the fall through zero at ½ − 1e-10 (to first order:
    # q'(½) = −1)
    p = _cheb(0.125 - 1e-10, 0.25, -0.5, -1.0)
    x = ct.first_downward_crossing(p, start_tol=1e-9)
    assert x == pytest.approx(0.5 - 1e-10, rel=0, abs=BRENT_ATOL)
    # with a tolerance below the dip, the dip itself is the first crossing, near
    # −½ − 1e-5 (the double root split by the dip): mpmath's root at 30 digits; the
    # slope there is only ~2e-5, so the polynomial's 8 eps of rounding move it by
    # 8 eps / 2e-5
    import mpmath

    with mpmath.workdps(30):
        want = float(mpmath.findroot(lambda x: (x + 0.5) ** 2 * (0.5 - x) - 1e-10, -0.50001))
    x = ct.first_downward_crossing(p, start_tol=1e-11)
    assert x == pytest.approx(want, rel=0, abs=8 * EPS / 2e-5)


def test_a_gap_that_stays_exactly_zero_is_no_contact() -> None:
    # bodies moving together: the gap is 0 all along, neither falling nor below zero
    assert ct.first_downward_crossing(np.zeros(3), start_tol=0.0) is None
    # rising from a touch: no contact
    assert ct.first_downward_crossing(_cheb(0.5, 0.5), start_tol=1e-12) is None


def test_a_start_below_the_tolerance_is_a_missed_contact_naming_the_gap() -> None:
    # −1/4 − (x + 1)/2 with start_tol 1/8: already −0.25 < 0 at x = −1
    with pytest.raises(ct.ContactError, match=r"^the gap is already -0\.25 < 0 at the start"):
        ct.first_downward_crossing(_cheb(-0.75, -0.5), start_tol=0.125)
    assert issubclass(ct.ContactError, ValueError)


def test_refine_is_used_where_it_brackets_the_piece() -> None:
    poly = _cheb(0.5, -1.0)  # its own root: 0.5
    # the exact gap 0.4 − x brackets [−1, 1] (1.4 ≥ 0 > −0.6): its root, not the poly's
    x = ct.first_downward_crossing(poly, start_tol=0.0, refine=lambda x: 0.4 - x)
    assert x == pytest.approx(0.4, rel=0, abs=BRENT_ATOL)
    # 2 − x does not bracket it (it stays ≥ 1): the polynomial's root
    x = ct.first_downward_crossing(poly, start_tol=0.0, refine=lambda x: 2.0 - x)
    assert x == pytest.approx(0.5, rel=0, abs=BRENT_ATOL)
    # −(x + 1)/2 is exactly 0 at the start (≥ 0) and −1 at the end: it brackets
    x = ct.first_downward_crossing(poly, start_tol=0.0, refine=lambda x: -0.5 * (x + 1.0))
    assert x == -1.0


# ------------------------------------------------------- the search after a touch


def test_after_a_touch_the_fall_past_the_hop_is_the_contact() -> None:
    # x(1/2 − x): 0 at the touch x = 0, up to 1/16 at 1/4, down through 0 at x = 1/2
    # to −1/2 at x = 1; below zero before the touch (x < 0) does not matter
    p = _cheb(0.0, 0.5, -1.0)
    x = ct.first_downward_crossing(p, start_tol=1e-12, after=0.0)
    assert x == pytest.approx(0.5, rel=0, abs=BRENT_ATOL)
    # the same with the exact gap to refine on: its root 0.6 (it brackets (1/4, 1])
    x = ct.first_downward_crossing(p, start_tol=1e-12, after=0.0, refine=lambda x: 0.6 - x)
    assert x == pytest.approx(0.6, rel=0, abs=BRENT_ATOL)


def test_after_a_touch_a_fall_within_rounding_is_not_a_contact() -> None:
    # x(1/2 − x)/8: its lowest value −1/16 on (0, 1] lies within start_tol = 1/8
    p = _cheb(0.0, 0.0625, -0.125)
    assert ct.first_downward_crossing(p, start_tol=0.125, after=0.0) is None
    # x(1/2 − x) ends at −1/2, exactly −start_tol: still within the rounding
    assert ct.first_downward_crossing(_cheb(0.0, 0.5, -1.0), start_tol=0.5, after=0.0) is None
    # a gap that only rises after the touch
    assert ct.first_downward_crossing(_cheb(0.0, 1.0), start_tol=1e-12, after=0.0) is None


def test_strict_root_starts_from_a_positive_gap() -> None:
    p = _cheb(0.0, 0.5, -1.0)  # x(1/2 − x)
    # the gap is positive at lo = 1/4: the root in (1/4, 1] directly
    assert ct._strict_root(p, None, 0.25, 1.0) == pytest.approx(0.5, rel=0, abs=BRENT_ATOL)
    # zero at lo = 0 and at lo + 1/2: the first positive point halving towards lo is
    # 1/4; the root 1/2 follows
    assert ct._strict_root(p, None, 0.0, 1.0) == pytest.approx(0.5, rel=0, abs=BRENT_ATOL)


def test_strict_root_probes_the_midpoint_first() -> None:
    # −x(x − 3/8)(x − 3/4) = −x³ + 9/8 x² − 9/32 x: zero at lo = 0, negative at 1/4
    # (−1/64), 1/8, ... (≈ −9/32 x) but positive at 1/2 (1/64): only the first probe
    # lo + (hi − lo)/2 finds the hop, whose fall crosses at 3/4
    p = _cheb(0.0, -9 / 32, 9 / 8, -1.0)
    assert ct._strict_root(p, None, 0.0, 1.0) == pytest.approx(0.75, rel=0, abs=BRENT_ATOL)


def test_strict_root_of_a_gap_that_never_left_zero_is_the_touch() -> None:
    # −x²: never positive on (0, 1]: the contact is at lo
    assert ct._strict_root(_cheb(0.0, 0.0, -1.0), None, 0.0, 1.0) == 0.0
    # the probes reach lo itself (ulp of 1/2 at j = 53) before running out
    assert ct._strict_root(_cheb(-0.25, 0.0, -1.0), None, 0.5, 1.0) == 0.5


def test_strict_root_refines_on_the_exact_gap_only_if_it_is_negative_at_hi() -> None:
    p = _cheb(0.0, 0.5, -1.0)  # x(1/2 − x), root 1/2
    got = ct._strict_root(p, lambda x: 0.3 - x, 0.25, 1.0)  # negative at hi: used
    assert got == pytest.approx(0.3, rel=0, abs=BRENT_ATOL)
    # exactly zero at hi (not below): the polynomial is used instead
    got = ct._strict_root(p, lambda x: 1.0 - x, 0.25, 1.0)
    assert got == pytest.approx(0.5, rel=0, abs=BRENT_ATOL)


def test_refine_must_bracket_the_piece_that_holds_the_crossing() -> None:
    # x² − 1/4 falls through zero on the piece [−1, 0] (the extremum at 0 cuts the step);
    # the exact gap x² − 1/5 brackets that piece (4/5 ≥ 0 > −1/5): its root −√(1/5)
    x = ct.first_downward_crossing(
        _cheb(-0.25, 0.0, 1.0), start_tol=0.0, refine=lambda x: x * x - 0.2
    )
    assert x == pytest.approx(-math.sqrt(0.2), rel=0, abs=BRENT_ATOL)


def test_strict_root_probes_no_closer_than_two_to_the_minus_sixty() -> None:
    # x(2^−60.5 − x): positive only below 2^−60.5 of the piece, which the last probe
    # lo + 2^−60 (hi − lo) misses: the gap is taken as never having left zero
    c = 2.0**-60.5
    assert ct._strict_root(_cheb(0.0, c, -1.0), None, 0.0, 1.0) == 0.0


def test_strict_root_probes_down_to_two_to_the_minus_sixty() -> None:
    # x(2^−59.5 − x): positive below 2^−59.5 of the piece, which the last probe
    # lo + 2^−60 (hi − lo) reaches: a root found (to brentq's absolute 4 eps), not lo
    x = ct._strict_root(_cheb(0.0, 2.0**-59.5, -1.0), None, 0.0, 1.0)
    assert 0.0 < x <= BRENT_ATOL


def test_strict_root_skips_a_probe_where_the_gap_only_touches_zero() -> None:
    # x (x − 1/2)² (3/4 − x): a touch at the probe 1/2 (zero, not positive), positive at
    # the next probe 1/4, the fall through zero at 3/4 (the refined gap itself)
    def gap(x):
        return x * (x - 0.5) ** 2 * (0.75 - x)

    x = ct._strict_root(_cheb(0.0, 1.0, -1.0), gap, 0.0, 1.0)
    assert x == pytest.approx(0.75, rel=0, abs=BRENT_ATOL)


# ------------------------------------------------- many pairs at once, against mpmath
#: the contact time of a well-conditioned case (a closing speed of at least 1e-3 of the
#: terms, roots formed without cancellation) against the exact root: a few roundings
TIMES_RTOL = 64 * EPS


def _first_closing_root(gap, v, a):
    """The first τ ≥ 0 with gap + v τ + a τ²/2 = 0 and v + a τ < 0, in 50 digits."""
    import mpmath

    with mpmath.workdps(50):
        g, vv, aa = (mpmath.mpf(x) for x in (gap, v, a))
        # (a/2) τ² + v τ + g = 0 by the cancellation-free pair q/(a/2), g/q: a tiny gap
        # against O(1) speeds would cancel even in 50 digits in the textbook form
        if aa == 0:
            roots = [-g / vv] if vv != 0 else []
        else:
            disc = vv * vv - 2 * aa * g
            if disc < 0:
                roots = []
            else:
                q = -(vv + mpmath.sign(vv) * mpmath.sqrt(disc)) / 2 if vv != 0 else None
                if q is None or q == 0:
                    roots = [r * mpmath.sqrt(-2 * g / aa) for r in (1, -1)] if -g / aa >= 0 else []
                else:
                    roots = [q / (aa / 2), g / q]
        ok = [r for r in roots if r >= 0 and vv + aa * r < 0]
        return float(min(ok)) if ok else math.inf


#: magnitudes whose squares stay normal floats (a discriminant of speeds below 1e-154
#: underflows: the scene domain's stated loss below 2⁻¹⁰²², mechanics.scenes.domain)
_mag = st.floats(1e-150, 10.0)
_num = st.one_of(st.just(0.0), _mag, _mag.map(lambda x: -x))


@settings(max_examples=300)
@given(st.lists(st.tuples(st.one_of(st.just(0.0), _mag), _num, _num), min_size=1, max_size=8))
def test_plane_contact_times_are_the_first_closing_roots(cases) -> None:
    gap, v, a = (np.array(x) for x in zip(*cases, strict=True))
    tau = ct.plane_contact_times(gap, v, a)
    for k, (g, vk, ak) in enumerate(cases):
        exact = _first_closing_root(g, vk, ak)
        closing = abs(vk + ak * exact) if exact < math.inf else 0.0
        if exact < math.inf and closing < 1e-3 * (abs(vk) + abs(ak) * exact):
            continue  # a graze: the closing speed is itself rounding there
        assert tau[k] == pytest.approx(exact, rel=TIMES_RTOL, abs=TIMES_RTOL * g), (g, vk, ak)
        assert ct.plane_contact_time(g, vk, ak) == tau[k]  # one arithmetic for one and many


def _sphere_time(d, w, s):
    """|d + w τ| = s entered while closing, in 50 digits (inf: never)."""
    import mpmath

    with mpmath.workdps(50):
        d, w = [mpmath.mpf(x) for x in d], [mpmath.mpf(x) for x in w]
        A = sum(x * x for x in w)
        B = 2 * sum(x * y for x, y in zip(d, w, strict=True))
        Cc = sum(x * x for x in d) - mpmath.mpf(s) ** 2
        if A == 0 or B >= 0:
            return math.inf
        disc = B * B - 4 * A * Cc
        if disc <= 0:
            return math.inf
        return float(max((-B - mpmath.sqrt(disc)) / (2 * A), 0))


_vec = st.lists(
    st.one_of(st.just(0.0), st.floats(1e-100, 2.0), st.floats(-2.0, -1e-100)),
    min_size=3,
    max_size=3,
)


@settings(max_examples=300)
@given(st.lists(st.tuples(_vec, _vec, st.floats(0.01, 1.0)), min_size=1, max_size=8))
def test_sphere_contact_times_are_the_entry_roots(cases) -> None:
    d = np.array([c[0] for c in cases])
    w = np.array([c[1] for c in cases])
    s = np.array([c[2] for c in cases])
    tau = ct.sphere_contact_times(d, w, s)
    for k, (dk, wk, sk) in enumerate(cases):
        if np.linalg.norm(dk) < sk:
            continue  # overlapping: not a case the engine asks
        exact = _sphere_time(dk, wk, sk)
        dk, wk = np.array(dk), np.array(wk)
        b = float(np.linalg.norm(np.cross(dk, wk)))
        ws = float(np.linalg.norm(wk)) * sk
        if abs(ws - b) < 1e-3 * ws:
            continue  # a graze: the impact parameter within 1e-3 of the sum of radii
        assert tau[k] == pytest.approx(exact, rel=TIMES_RTOL, abs=TIMES_RTOL), (dk, wk, sk)
        assert ct.sphere_contact_time(dk, wk, sk) == tau[k]
