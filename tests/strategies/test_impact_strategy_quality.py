"""The impact strategies of :mod:`mechanics.strategies.impact` reach every regime they document.

As in ``test_strategy_quality.py``: each documented regime is *found* by
:func:`hypothesis.find` with a predicate on the value (not on the label the
strategy records); the strategies produce only valid objects (masses > 0,
e ∈ [0, 1], approaching velocities, physical inertia tensors accepted by
:mod:`mechanics.impact`, contacts that are impacts), shrink to the simple case
and reject bad arguments by quoting them.
"""

from __future__ import annotations

import functools
import math
import re

import numpy as np
import pytest
from hypothesis import example, find, given, settings
from hypothesis import strategies as st
from hypothesis.errors import InvalidArgument

from mechanics import impact as im
from mechanics import strategies as ms
from mechanics._floats import EPS
from tests.strategies.sampling import found, never, shared

#: Draws allowed to reach a regime: regimes are branches among at most six, so
#: a regime is met within a few dozen draws; 1000 leaves room for nesting.
FIND_DRAWS = 1000

#: For the tests of what the strategies shrink to.
SHRINK_SETTINGS = settings(max_examples=100, database=None)

#: Contacts are slow to draw; validity is checked on fewer examples.
CONTACT_SETTINGS = settings(max_examples=40)

#: Principal moments of a drawn tensor come back from eigvalsh within a few
#: eps of the largest; the regime predicates compare them with this slack.
MOMENT_RTOL = 64 * EPS


def _found(strategy, predicate):
    return found(strategy, predicate, FIND_DRAWS)


def _moments(J) -> np.ndarray:
    return np.linalg.eigvalsh(J)


def _close(a, b) -> bool:
    return abs(a - b) <= MOMENT_RTOL * max(abs(a), abs(b))


# -------------------------------------------------------------------- regimes

MASS_REGIMES = {
    "unit": lambda m: m == 1.0,
    "generic": lambda m: 1e-3 <= m <= 1e3 and m != 1.0,
    "tiny": lambda m: m <= 1e-6,
    "huge": lambda m: m >= 1e6,
}

MASS_PAIR_REGIMES = {
    "equal": lambda p: p == (1.0, 1.0),
    "generic": lambda p: 1e-6 <= p[0] / p[1] <= 1e6 and p != (1.0, 1.0),
    "light-1": lambda p: p[0] / p[1] <= 1e-6,
    "heavy-1": lambda p: p[0] / p[1] >= 1e6,
    "scaled": lambda p: (
        min(p) >= 1e-153 and max(p) <= 1e153 and (max(p) > 1e100 or min(p) < 1e-100)
    ),
}

RESTITUTION_REGIMES = {
    "zero": lambda e: e == 0.0,
    "one": lambda e: e == 1.0,
    "interior": lambda e: 1e-3 < e < 1 - 1e-3,
    "near-zero": lambda e: 0.0 < e <= 1e-6,
    "near-one": lambda e: 0.0 < 1.0 - e <= 1e-6,
}

DIRECT_VELOCITY_REGIMES = {
    "head-on": lambda v: v[0] > 0 > v[1],
    "chase": lambda v: v[0] * v[1] > 0 and v[0] != v[1],
    "at-rest": lambda v: v[1] == 0.0 and v[0] > 0,
    "small-relative": lambda v: 0 < abs(v[0] - v[1]) <= 1e-6 * abs(v[1]),
    "mixed-magnitude": lambda v: (
        min(abs(v[0]), abs(v[1])) > 0
        and max(abs(v[0]), abs(v[1])) > 1e100 * min(abs(v[0]), abs(v[1]))
    ),
}

INERTIA_REGIMES = {
    "sphere": lambda J: _close(_moments(J)[0], _moments(J)[2]),
    "symmetric": lambda J: (
        (_close(*_moments(J)[:2]) or _close(*_moments(J)[1:]))
        and not _close(_moments(J)[0], _moments(J)[2])
    ),
    "general": lambda J: (
        np.diff(_moments(J)).min() > 0.01 * _moments(J)[2]
        and _moments(J)[0] + _moments(J)[1] > 1.01 * _moments(J)[2]
    ),
    "lamina": lambda J: (
        _close(_moments(J)[0] + _moments(J)[1], _moments(J)[2])
        and np.diff(_moments(J)).min() > 0.01 * _moments(J)[2]
    ),
    "near-degenerate": lambda J: (
        0 < np.diff(_moments(J)).min() <= 1e-6 * _moments(J)[2]
        and np.diff(_moments(J)).min() > MOMENT_RTOL * _moments(J)[2]
    ),
    "elongated": lambda J: _moments(J)[0] <= 1e-2 * _moments(J)[2],
    "turned (not diagonal)": lambda J: (
        np.abs(J - np.diag(np.diag(J))).max() > 0.1 * np.abs(J).max()
    ),
}


def _arm(c, body):
    return c.r_S - body.r_G


CONTACT_REGIMES = {
    "fixed-body-2": lambda c: c.body_2 is None,
    "free-free": lambda c: (
        c.body_2 is not None
        and np.linalg.norm(np.cross(_arm(c, c.body_1), c.n)) > 0.1
        and np.linalg.norm(np.cross(_arm(c, c.body_2), c.n)) > 0.1
    ),
    "central": lambda c: (
        c.body_2 is not None
        and np.linalg.norm(np.cross(_arm(c, c.body_1), c.n)) <= 1e-12
        and np.linalg.norm(np.cross(_arm(c, c.body_2), c.n)) <= 1e-12
    ),
    "planar": lambda c: (
        c.body_2 is not None
        and all(
            b.r_G[2] == 0 and b.v_G[2] == 0 and b.omega[0] == b.omega[1] == 0
            for b in (c.body_1, c.body_2)
        )
        and c.n[2] == 0.0
        and c.body_1.omega[2] != 0
    ),
    "mass-ratio": lambda c: c.body_2 is not None and not 1e-6 < c.body_1.m / c.body_2.m < 1e6,
}

HINGED_REGIMES = {
    "planar": lambda h: h.axis.tolist() == [0.0, 0.0, 1.0] and h.r_G[2] == 0.0,
    "general": lambda h: bool(np.all(np.abs(h.axis) > 0.1)) and abs(h.r_G[2]) > 0.1,
}


@pytest.mark.parametrize(("regime", "predicate"), list(MASS_REGIMES.items()))
def test_impact_masses_reach_every_regime(regime, predicate):
    _found(shared(ms.impact_masses), predicate)


@pytest.mark.parametrize(("regime", "predicate"), list(MASS_PAIR_REGIMES.items()))
def test_mass_pairs_reach_every_regime(regime, predicate):
    _found(shared(ms.mass_pairs), predicate)


@pytest.mark.parametrize(
    "predicate",
    [
        pytest.param(lambda v: v[0] > 1e290 and 0 < -v[1] < 1e-200, id="huge-behind-tiny-ahead"),
        pytest.param(lambda v: v[0] == 0.0 and v[1] < -1e290, id="at-rest-hit-by-huge"),
        pytest.param(lambda v: v[0] > 1e290 and 0 < v[1] < 1e-200, id="huge-chasing-tiny"),
    ],
)
def test_direct_velocities_span_the_float_range_with_a_huge_max_speed(predicate):
    _found(ms.direct_velocities(max_speed=1e302, regimes=["mixed-magnitude"]), predicate)


def test_mass_pairs_reach_the_extreme_ratios_1e15():
    _found(shared(ms.mass_pairs), lambda p: p[0] / p[1] <= 1e-14)
    _found(shared(ms.mass_pairs), lambda p: p[0] / p[1] >= 1e14)


@pytest.mark.parametrize(("regime", "predicate"), list(RESTITUTION_REGIMES.items()))
def test_restitution_coefficients_reach_every_regime(regime, predicate):
    _found(shared(ms.restitution_coefficients), predicate)


def test_restitution_coefficients_reach_one_ulp_below_one():
    _found(shared(ms.restitution_coefficients), lambda e: 0 < 1.0 - e <= 1e-15)


@pytest.mark.parametrize(("regime", "predicate"), list(DIRECT_VELOCITY_REGIMES.items()))
def test_direct_velocities_reach_every_regime(regime, predicate):
    _found(shared(ms.direct_velocities), predicate)


@pytest.mark.parametrize(("regime", "predicate"), list(INERTIA_REGIMES.items()))
def test_impact_inertia_tensors_reach_every_regime(regime, predicate):
    _found(shared(ms.impact_inertia_tensors), predicate)


@pytest.mark.parametrize(("regime", "predicate"), list(CONTACT_REGIMES.items()))
def test_contacts_reach_every_regime(regime, predicate):
    _found(shared(ms.contacts), predicate)


@pytest.mark.parametrize(("regime", "predicate"), list(HINGED_REGIMES.items()))
def test_hinged_bodies_reach_every_regime(regime, predicate):
    _found(shared(ms.hinged_bodies), predicate)


def test_every_documented_regime_has_a_reachability_test():
    assert set(ms.IMPACT_MASS_REGIMES) == set(MASS_REGIMES)
    assert set(ms.MASS_PAIR_REGIMES) == set(MASS_PAIR_REGIMES)
    assert set(ms.RESTITUTION_REGIMES) == set(RESTITUTION_REGIMES)
    assert set(ms.DIRECT_VELOCITY_REGIMES) == set(DIRECT_VELOCITY_REGIMES)
    assert set(ms.IMPACT_INERTIA_REGIMES) <= set(INERTIA_REGIMES)
    assert set(ms.CONTACT_REGIMES) == set(CONTACT_REGIMES)
    assert set(ms.HINGED_REGIMES) == set(HINGED_REGIMES)


# ------------------------------------------------------------------- validity


def test_impact_masses_are_positive_and_within_the_default_bounds():
    @given(ms.impact_masses())
    def check(m):
        assert 1e-15 <= m <= 1e15

    check()


def test_restitution_coefficients_lie_in_zero_one():
    @given(ms.restitution_coefficients())
    def check(e):
        assert 0.0 <= e <= 1.0

    check()


def test_direct_velocities_approach():
    @given(ms.direct_velocities())
    def check(v):
        assert v[0] >= v[1]  # Δẋ = ẋ_2 − ẋ_1 <= 0
        assert max(abs(v[0]), abs(v[1])) <= 1e6

    check()


def test_contact_normals_are_unit():
    @given(ms.contact_normals())
    def check(n):
        assert abs(math.hypot(*n) - 1.0) <= 2 * EPS

    check()


def test_impact_inertia_tensors_are_physical():
    @given(ms.impact_inertia_tensors())
    def check(J):
        # Accepted by the library's own validation: symmetric, positive definite,
        # triangle inequality within its documented slack.
        im.effective_mass(1.0, J, [0.0, 0.0, 0.0], [1.0, 0.0, 0.0])
        lam = _moments(J)
        assert lam[0] > 0
        assert lam[0] + lam[1] >= lam[2] * (1 - MOMENT_RTOL)

    check()


def test_contacts_are_impacts():
    @CONTACT_SETTINGS
    @given(ms.contacts())
    def check(c):
        v_n = im.normal_relative_velocity(c.body_1, c.body_2, r_S=c.r_S, n=c.n)
        assert v_n <= -1e-3  # approach speed >= 1e-2, rounding far below
        assert 0.0 <= c.e <= 1.0

    check()


#: J_G + m (|d|² 1 − d dᵀ) from an exact d: a few rounded products and sums per entry
PARALLEL_AXIS_RTOL = 4 * EPS


def _hinged_example(m, J_G, d, A, axis) -> ms.HingedBody:
    """A hinged body built the way the strategy builds one (J_A from the exact d)."""
    J_A = J_G + m * (float(d @ d) * np.eye(3) - np.outer(d, d))
    return ms.HingedBody(m, 0.5 * (J_A + J_A.T), A + d, A, axis, J_G)


def test_hinged_bodies_obey_the_parallel_axis_theorem():
    @CONTACT_SETTINGS
    @given(ms.hinged_bodies())
    @example(  # found on a fresh clone: r_G = 1 + 0.1 rounds, and r_G − A ≠ 0.1 by 1e-17
        _hinged_example(
            1.0,
            1e-3 * np.eye(3),
            np.array([0.0, 0.0, 0.1]),
            np.array([0.0, 0, 1]),
            np.array([1.0, 0, 0]),
        )
    )
    def check(h):
        d = h.r_G - h.axis_point
        expected = h.J_G + h.m * (float(d @ d) * np.eye(3) - np.outer(d, d))
        # d is formed here from the rounded r_G = A + d₀ (one rounding of the strategy's
        # sum) and rounds once more in the subtraction: |d − d₀| ≤ δ = eps (|r_G| + |d|).
        # The tensor then moves by at most m (4 |d| δ + 2 δ²) in each entry.
        delta = EPS * (np.linalg.norm(h.r_G) + np.linalg.norm(d))
        input_rounding = h.m * (4 * np.linalg.norm(d) * delta + 2 * delta * delta)
        tol = PARALLEL_AXIS_RTOL * np.abs(expected).max() + input_rounding
        assert np.abs(h.J_A - expected).max() <= tol
        assert abs(math.hypot(*h.axis) - 1.0) <= 2 * EPS
        # G is off the axis: a centre of percussion exists.
        perp = d - (d @ h.axis) * h.axis
        assert np.linalg.norm(perp) >= 0.1 * (1 - 1e-12)

    check()


# ------------------------------------------------------------------- shrinking


@pytest.mark.parametrize(
    ("strategy", "simplest"),
    [
        pytest.param(ms.impact_masses, 1.0, id="mass-1"),
        pytest.param(ms.mass_pairs, (1.0, 1.0), id="pair-equal"),
        pytest.param(ms.restitution_coefficients, 0.0, id="e-0"),
        pytest.param(ms.impact_inertia_tensors, np.eye(3).tolist(), id="sphere-identity"),
    ],
)
def test_strategies_shrink_to_the_simple_case(strategy, simplest):
    value = find(strategy(), lambda x: True, settings=SHRINK_SETTINGS)
    got = value if isinstance(value, tuple | float) else np.asarray(value).tolist()
    if isinstance(simplest, list):  # a unit sphere tensor: J2 shrinks to the top of its range
        got = (np.asarray(got) / np.asarray(got)[0][0]).tolist()
    assert got == simplest


# -------------------------------------------------------------- bad arguments


@pytest.mark.parametrize(
    ("factory", "kwargs", "quoted"),
    [
        pytest.param(ms.impact_masses, {"min_value": 0.0}, "0.0", id="mass-min-zero"),
        pytest.param(ms.impact_masses, {"min_value": 2.0, "max_value": 1.0}, "2.0", id="min>max"),
        pytest.param(ms.impact_masses, {"max_value": float("nan")}, "nan", id="mass-nan"),
        pytest.param(ms.impact_masses, {"regimes": ["heavy"]}, "heavy", id="mass-regime"),
        pytest.param(
            ms.impact_masses,
            {"min_value": 1.0, "max_value": 2.0, "regimes": ["tiny"]},
            "['tiny']",
            id="mass-unreachable",
        ),
        pytest.param(ms.mass_pairs, {"max_ratio": 10.0}, "10.0", id="ratio-small"),
        pytest.param(ms.restitution_coefficients, {"regimes": ["two"]}, "two", id="e-regime"),
        pytest.param(ms.direct_velocities, {"max_speed": 0.5}, "0.5", id="speed"),
        pytest.param(ms.impact_inertia_tensors, {"rotations": 3}, "rotations=3", id="rot"),
        pytest.param(ms.contacts, {"regimes": "planar"}, "'planar'", id="contact-str"),
        pytest.param(ms.contacts, {"restitution": 0.5}, "restitution=0.5", id="contact-e"),
        pytest.param(ms.hinged_bodies, {"regimes": ["door"]}, "door", id="hinged-regime"),
    ],
)
def test_impact_strategies_reject_bad_arguments_quoting_them(factory, kwargs, quoted):
    with pytest.raises(InvalidArgument, match=re.escape(quoted)):
        factory(**kwargs)


# ------------------------------------------------------- each regime's bounds
#
# Each regime, drawn alone, stays within the bounds its docstring states and reaches
# both ends of them (within a decade of a log-uniform end, or a tenth of a linear
# one).  The strategies are built inside the tests.

#: Searches that must fail (a value outside the documented bounds): every branch is
#: drawn hundreds of times.
NEVER_DRAWS = 600

#: A ratio of two floats drawn as m_2 / r (or m_2 r) comes back within a few roundings.
RATIO_RTOL = 4 * EPS


def _never(strategy, predicate) -> None:
    never(strategy, predicate, NEVER_DRAWS)


def _spans(lo, hi):
    """The documented span of each mass regime inside [lo, hi] (IMPACT_MASS_REGIMES)."""
    return {
        "unit": (1.0, 1.0),
        "generic": (max(lo, 1e-3), min(hi, 1e3)),
        "tiny": (lo, min(hi, 1e-6)),
        "huge": (max(lo, 1e6), hi),
    }


@pytest.mark.parametrize(("lo", "hi"), [(1e-15, 1e15), (1e-9, 1e9)])
@pytest.mark.parametrize("regime", ms.IMPACT_MASS_REGIMES)
def test_impact_masses_each_regime_spans_its_documented_interval(regime, lo, hi):
    a, b = _spans(lo, hi)[regime]
    strategy = ms.impact_masses(min_value=lo, max_value=hi, regimes=[regime])
    _never(strategy, lambda m: not a <= m <= b)
    _found(strategy, lambda m: m <= 10 * a)
    _found(strategy, lambda m: m >= b / 10)


def test_impact_masses_drop_the_regimes_outside_the_bounds():
    strategy = ms.impact_masses(min_value=2.0, max_value=3.0)
    _never(strategy, lambda m: not 2.0 <= m <= 3.0)
    assert 2.0 <= find(strategy, lambda m: True, settings=SHRINK_SETTINGS) <= 3.0


@pytest.mark.parametrize("max_ratio", [1e15, 1e8])
def test_mass_pairs_each_regime_keeps_its_documented_ratio(max_ratio):
    def pairs(regime):
        return ms.mass_pairs(max_ratio=max_ratio, regimes=[regime])

    def in_base(m):
        return 1e-3 <= m <= 1e3

    _never(pairs("equal"), lambda p: p != (1.0, 1.0))
    _never(pairs("generic"), lambda p: not (in_base(p[0]) and in_base(p[1])))
    for regime in ("light-1", "heavy-1"):
        strategy = pairs(regime)
        q = (lambda p: p[0] / p[1]) if regime == "light-1" else (lambda p: p[1] / p[0])
        lo, hi = 1 / max_ratio * (1 - RATIO_RTOL), 1e-6 * (1 + RATIO_RTOL)
        _never(strategy, lambda p, q=q, lo=lo, hi=hi: not (in_base(p[1]) or in_base(p[0])))
        _never(strategy, lambda p, q=q, lo=lo, hi=hi: not lo <= q(p) <= hi)
        _found(strategy, lambda p, q=q: q(p) <= 10 / max_ratio)
        _found(strategy, lambda p, q=q: q(p) >= 1e-7)
    scaled = pairs("scaled")
    _never(scaled, lambda p: not 1e-6 * (1 - RATIO_RTOL) <= p[0] / p[1] <= 1e6 * (1 + RATIO_RTOL))
    _never(scaled, lambda p: not 1e-153 <= min(p) <= max(p) <= 1e153)
    _found(scaled, lambda p: max(p) >= 1e148)
    _found(scaled, lambda p: min(p) <= 1e-148)


def test_mass_pairs_generic_masses_reach_both_ends_of_1e_minus_3_to_1e3():
    strategy = ms.mass_pairs(regimes=["generic"])
    _found(strategy, lambda p: min(p) <= 1e-2)
    _found(strategy, lambda p: max(p) >= 1e2)


def test_mass_pairs_shrink_to_equal_unit_masses_and_generic_pairs_to_the_top_of_1e3():
    # Alone, the generic regime shrinks to its log-uniform's "hi" end: both masses 1e3.
    pair = find(ms.mass_pairs(regimes=["generic"]), lambda p: True, settings=SHRINK_SETTINGS)
    assert pair == (1e3, 1e3)
    assert find(ms.mass_pairs(), lambda p: True, settings=SHRINK_SETTINGS) == (1.0, 1.0)


RESTITUTION_SPANS = {
    "zero": (0.0, 0.0),
    "one": (1.0, 1.0),
    "interior": (0.0, 1.0),
    "near-zero": (1e-15, 1e-6),
    "near-one": (1.0 - 1e-6, math.nextafter(1.0, 0.0)),
}


@pytest.mark.parametrize("regime", ms.RESTITUTION_REGIMES)
def test_restitution_coefficients_each_regime_spans_its_documented_interval(regime):
    a, b = RESTITUTION_SPANS[regime]
    strategy = ms.restitution_coefficients(regimes=[regime])
    _never(strategy, lambda e: not a <= e <= b)
    if regime == "near-zero":
        _found(strategy, lambda e: e <= 1e-14)
        _found(strategy, lambda e: e >= 1e-7)
        assert find(strategy, lambda e: True, settings=SHRINK_SETTINGS) == 1e-6
    if regime == "interior":
        _found(strategy, lambda e: 0 < e <= 0.1)
        _found(strategy, lambda e: 0.9 <= e < 1)
    if regime == "near-one":
        _found(strategy, lambda e: e == b)
        _found(strategy, lambda e: e <= 1 - 1e-7)
        assert find(strategy, lambda e: True, settings=SHRINK_SETTINGS) == 1.0 - 1e-6


@pytest.mark.parametrize("top", [1e6, 1e3])
@pytest.mark.parametrize("regime", ["head-on", "chase", "at-rest", "small-relative"])
def test_direct_velocities_speeds_span_1e_minus_6_to_half_the_max_speed(regime, top):
    strategy = ms.direct_velocities(max_speed=top, regimes=[regime])
    signs = {
        "head-on": lambda v: v[0] > 0 > v[1],
        # v_1 = v_2 + s, s in [0, |v_2|]: same sign, or body 1 brought to rest (s = |v_2|)
        "chase": lambda v: v[0] * v[1] >= 0 and v[1] != 0 and abs(v[0]) <= 2 * abs(v[1]),
        "at-rest": lambda v: v[0] > 0 and v[1] == 0.0,
        # v_1 = fl(v_2 + s), s/|v_2| in [1e-12, 1e-6]: the sum's rounding is ≤ eps |v_1|
        "small-relative": lambda v: (
            1e-12 * abs(v[1]) - EPS * abs(v[0]) <= v[0] - v[1] <= 1e-6 * abs(v[1]) + EPS * abs(v[0])
        ),
    }[regime]
    speeds = {  # the drawn speed(s): |v| of body 2 (of body 1 at rest)
        "head-on": lambda v: (v[0], -v[1]),
        "chase": lambda v: (abs(v[1]),),
        "at-rest": lambda v: (v[0],),
        "small-relative": lambda v: (abs(v[1]),),
    }[regime]
    _never(strategy, lambda v: not (v[0] >= v[1] and signs(v)))
    _never(strategy, lambda v: not all(1e-6 <= s <= top / 2 for s in speeds(v)))
    _found(strategy, lambda v: min(speeds(v)) <= 1e-5)
    _found(strategy, lambda v: max(speeds(v)) >= top / 20)


def test_direct_velocities_each_regime_shrinks_to_its_largest_speed():
    # log-uniform speeds shrink to the top of [1e-6, max_speed/2] (10**log10(5e5) rounds
    # one ulp below 5e5)
    top = 5e5 * (1 - EPS)
    cases = {"head-on": (top, -top), "at-rest": (top, 0.0), "chase": (top, top)}
    for regime, simplest in cases.items():
        strategy = ms.direct_velocities(regimes=[regime])
        v = find(strategy, lambda v: True, settings=SHRINK_SETTINGS)
        assert v == pytest.approx(simplest, rel=2 * EPS), regime


@pytest.mark.parametrize("top", [1.0, 1e6, 1e302])
def test_direct_velocities_mixed_magnitudes_come_from_the_documented_tiers(top):
    tiers = [(0.0, 0.0), (1e-250, 1e-100), (1e-3, min(1e3, top / 2)), (top / 2e10, top / 2)]
    strategy = ms.direct_velocities(max_speed=top, regimes=["mixed-magnitude"])

    def tier_of(x):
        return [a <= abs(x) <= b for a, b in tiers]

    _never(strategy, lambda v: not (v[0] >= v[1] and any(tier_of(v[0])) and any(tier_of(v[1]))))
    for a, b in tiers[1:]:
        _found(strategy, lambda v, a=a: any(a <= abs(x) <= 10 * a for x in v))
        _found(strategy, lambda v, a=a, b=b: any(b / 10 <= abs(x) <= b for x in v))


#: Principal moments, each drawn on the diagonal of an unturned tensor (R = 1 exactly):
#: (J1, J2, J3) as the regime constructs them, J1 ≤ J2, scale J2 in [1e-3, 1e3].
#: (one object per regime, so the questions below read one sample of it)
@functools.cache
def _diagonal(regime):
    return ms.impact_inertia_tensors(regimes=[regime], rotations=st.just(np.eye(3)))


IMPACT_MOMENT_RELATIONS = {
    "sphere": lambda J1, J2, J3: J1 == J2 == J3,
    "symmetric": lambda J1, J2, J3: J1 == J2 and 1e-2 * J2 <= J3 <= 2.0 * J2,
    "general": lambda J1, J2, J3: (
        1e-2 * J2 <= J1 <= J2 and max(J2 - J1, 1e-2 * J2) <= J3 <= (J1 + J2) * (1 + EPS)
    ),
    "lamina": lambda J1, J2, J3: J1 <= J2 and J3 == J1 + J2 and J1 >= 1e-2 * J2,
    "near-degenerate": lambda J1, J2, J3: (
        1e-12 * (1 - RATIO_RTOL) <= J2 / J1 - 1 <= 1e-6 * (1 + RATIO_RTOL)
        and max(J2 - J1, 1e-2 * J2) <= J3 <= (J1 + J2) * (1 + EPS)
    ),
    "elongated": lambda J1, J2, J3: (
        1e-6 * (1 - RATIO_RTOL) <= J1 / J2 <= 1e-2 * (1 + RATIO_RTOL)
        and abs(J3 - J2) <= J1 + 2 * EPS * J2  # J3 = J2 + u J1, u in [-1, 1], one rounding
    ),
}


@pytest.mark.parametrize("regime", ms.IMPACT_INERTIA_REGIMES)
def test_impact_inertia_tensors_each_regime_builds_its_documented_moments(regime):
    relation = IMPACT_MOMENT_RELATIONS[regime]
    strategy = _diagonal(regime)
    _never(strategy, lambda J: np.count_nonzero(J - np.diag(np.diag(J))) > 0)
    _never(strategy, lambda J: not relation(*np.diag(J)))
    _never(strategy, lambda J: not 1e-3 <= J[1, 1] <= 1e3)
    _found(strategy, lambda J: J[1, 1] <= 1e-2)
    _found(strategy, lambda J: J[1, 1] >= 1e2)


def test_impact_inertia_tensors_regimes_reach_the_ends_of_their_ratios():
    _found(_diagonal("near-degenerate"), lambda J: J[1, 1] / J[0, 0] - 1 <= 1e-11)
    _found(_diagonal("near-degenerate"), lambda J: J[1, 1] / J[0, 0] - 1 >= 1e-7)
    _found(_diagonal("elongated"), lambda J: J[0, 0] / J[1, 1] <= 1e-5)
    _found(_diagonal("elongated"), lambda J: J[0, 0] / J[1, 1] >= 1e-3)
    _found(_diagonal("elongated"), lambda J: J[2, 2] < J[1, 1])
    _found(_diagonal("elongated"), lambda J: J[2, 2] > J[1, 1])
    _found(_diagonal("symmetric"), lambda J: J[2, 2] >= 1.9 * J[1, 1])
    _found(_diagonal("symmetric"), lambda J: J[2, 2] <= 0.1 * J[1, 1])
    _found(_diagonal("general"), lambda J: J[0, 0] <= 0.05 * J[1, 1])
    # J3 = max(J2 − J1 + 2 t J1, J2/100): from the floor J2/100 to the edge J1 + J2
    for regime in ("general", "near-degenerate"):
        _found(_diagonal(regime), lambda J: J[2, 2] <= 0.05 * J[1, 1])
        _found(_diagonal(regime), lambda J: J[2, 2] >= 0.99 * (J[0, 0] + J[1, 1]))


def _perp(c, body):
    """|(G − S) × n|: the distance of G from the normal through S."""
    return float(np.linalg.norm(np.cross(body.r_G - c.r_S, c.n)))


def _along(c, body):
    """(G − S)·n: positive on body 1's side (n points into body 1)."""
    return float((body.r_G - c.r_S) @ c.n)


#: r_S = fl(r_G + offset) with |r_G| ≤ 10: r_S − r_G is the offset to a few ulps of 10.
POSITION_SLACK = 2**4 * EPS * 10

#: G_2 = S − a_2 n = G_1 − (a_1 + a_2) n: the arms come back to a few ulps of 16.
ARM_SLACK = 2**4 * EPS * 16

#: v_n is set to −speed by one shift of v_G along n: the rounding is a few eps of the
#: velocities involved (|v| up to ~1e2 with ω ~ 10 and arms ~ 5).
APPROACH_ATOL = 2**10 * EPS * 1e2


@pytest.mark.parametrize("regime", ms.CONTACT_REGIMES)
def test_contacts_each_regime_builds_its_documented_geometry(regime):
    strategy = ms.contacts(regimes=[regime], restitution=st.just(0.5))

    def v_n(c):
        return im.normal_relative_velocity(c.body_1, c.body_2, r_S=c.r_S, n=c.n)

    # The approach speed is in [1e-2, 1e2], both ends reached.
    _never(strategy, lambda c: not 1e-2 - APPROACH_ATOL <= -v_n(c) <= 1e2 + APPROACH_ATOL)
    _found(strategy, lambda c: -v_n(c) <= 2e-2)
    _found(strategy, lambda c: -v_n(c) >= 50.0)
    _never(strategy, lambda c: c.e != 0.5)
    if regime == "fixed-body-2":
        _never(strategy, lambda c: c.body_2 is not None)
        return
    _never(strategy, lambda c: c.body_2 is None)
    if regime == "central":
        _never(strategy, lambda c: max(_perp(c, c.body_1), _perp(c, c.body_2)) > 1e-12)
        _never(strategy, lambda c: not (_along(c, c.body_1) > 0 > _along(c, c.body_2)))
        # the arms |G − S| are 0.05 … 3 for each body
        arms = lambda c: (_along(c, c.body_1), -_along(c, c.body_2))  # noqa: E731
        _never(
            strategy, lambda c: not all(0.05 - ARM_SLACK <= a <= 3.0 + ARM_SLACK for a in arms(c))
        )
        _found(strategy, lambda c: min(arms(c)) <= 0.1)
        _found(strategy, lambda c: max(arms(c)) >= 2.9)
        return
    # G1 is off the normal: r_S − G1 is an offset with components within 3, and every
    # position of G within the default 10 of impact_bodies.
    _never(strategy, lambda c: np.abs(c.r_S - c.body_1.r_G).max() > 3.0 + POSITION_SLACK)
    _found(strategy, lambda c: np.abs(c.r_S - c.body_1.r_G).max() >= 2.5)
    _never(strategy, lambda c: max(np.abs(b.r_G).max() for b in (c.body_1, c.body_2)) > 10.0)
    if regime == "planar":
        _never(strategy, lambda c: c.n[2] != 0.0 or (c.r_S - c.body_1.r_G)[2] != 0.0)
        for k in (0, 1):
            _found(strategy, lambda c, k=k: abs((c.r_S - c.body_1.r_G)[k]) >= 2.5)
            _found(strategy, lambda c, k=k: abs(c.body_2.r_G[k]) >= 9.0)
            _found(strategy, lambda c, k=k: abs(c.body_2.v_G[k]) >= 9.0)
        _never(strategy, lambda c: np.abs(c.body_2.v_G).max() > 10.0)
        _never(strategy, lambda c: min(c.body_1.m, c.body_2.m) < 1e-3)
        _never(strategy, lambda c: max(c.body_1.m, c.body_2.m) > 1e3)
        _never(strategy, lambda c: abs(c.body_2.omega[2]) > 10.0)
        _found(strategy, lambda c: abs(c.body_2.omega[2]) >= 9.0)
    if regime == "mass-ratio":
        ratio = lambda c: c.body_1.m / c.body_2.m  # noqa: E731
        _never(
            strategy,
            lambda c: (
                not (
                    1e6 * (1 - RATIO_RTOL) <= ratio(c) <= 1e12 * (1 + RATIO_RTOL)
                    or 1e-12 * (1 - RATIO_RTOL) <= ratio(c) <= 1e-6 * (1 + RATIO_RTOL)
                )
            ),
        )
        _found(strategy, lambda c: ratio(c) >= 1e11)
        _found(strategy, lambda c: ratio(c) <= 1e-11)
        _found(strategy, lambda c: 1e6 <= ratio(c) <= 1e7)
        _found(strategy, lambda c: 1e-7 <= ratio(c) <= 1e-6)
        # body 1's tensor follows its mass: J_G/m keeps the body's size
        size = lambda b: np.trace(b.J_G) / b.m  # noqa: E731
        _never(strategy, lambda c: not 1e-9 <= size(c.body_1) <= 1e4)


@pytest.mark.parametrize("regime", ms.HINGED_REGIMES)
def test_hinged_bodies_keep_g_within_their_documented_distances(regime):
    strategy = ms.hinged_bodies(regimes=[regime])

    def parts(h):
        d = h.r_G - h.axis_point
        axial = float(d @ h.axis)
        return axial, float(np.linalg.norm(d - axial * h.axis))

    # G is 0.1 … 5 from the axis (to the rounding of r_G = A + d).
    slack = POSITION_SLACK
    _never(strategy, lambda h: not 0.1 - slack <= parts(h)[1] <= 5.0 + slack)
    _found(strategy, lambda h: parts(h)[1] <= 0.2)
    _found(strategy, lambda h: parts(h)[1] >= 4.5)
    _never(strategy, lambda h: not 1e-3 <= h.m <= 1e3)
    _found(strategy, lambda h: h.m <= 1e-2)
    _found(strategy, lambda h: h.m >= 1e2)
    # J_G is the mass times a tensor of scale J2 in 1e-3 … 1e3, whose largest moment is
    # in [J2, 2 J2] (J3 ≤ J1 + J2 ≤ 2 J2)
    _never(
        strategy,
        lambda h: (
            not 1e-3 * (1 - MOMENT_RTOL)  # eigvalsh of the turned tensor rounds, both ways
            <= np.linalg.eigvalsh(h.J_G / h.m)[2]
            <= 2e3 * (1 + MOMENT_RTOL)
        ),
    )
    if regime == "planar":
        _never(strategy, lambda h: h.axis_point.any() or h.axis.tolist() != [0.0, 0.0, 1.0])
        _never(strategy, lambda h: h.r_G[2] != 0.0 or h.J_G[0, 2] != 0 or h.J_G[1, 2] != 0)
        return
    # along the axis, G is within 5 of A either way; A has components within 5
    _never(strategy, lambda h: abs(parts(h)[0]) > 5.0 + slack)
    _found(strategy, lambda h: parts(h)[0] >= 4.5)
    _found(strategy, lambda h: parts(h)[0] <= -4.5)
    _never(strategy, lambda h: np.abs(h.axis_point).max() > 5.0)
    _found(strategy, lambda h: np.abs(h.axis_point).max() >= 4.5)
