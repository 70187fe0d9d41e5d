"""The impact strategies of :mod:`mechanics.strategies.impact` reach every regime they document.

As in ``test_strategy_quality.py``: each documented regime is *found* by
:func:`hypothesis.find` with a predicate on the value (not on the label the
strategy records); the strategies produce only valid objects (masses > 0,
e ∈ [0, 1], approaching velocities, physical inertia tensors accepted by
:mod:`mechanics.impact`, contacts that are impacts), shrink to the simple case
and reject bad arguments by quoting them.
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
from hypothesis import Phase, example, find, given, settings
from hypothesis.errors import InvalidArgument

from mechanics import impact as im
from mechanics import strategies as ms

EPS = float(np.finfo(float).eps)

#: Draws allowed to reach a regime: regimes are branches among at most six, so
#: a regime is met within a few dozen draws; 1000 leaves room for nesting.
FIND_SETTINGS = settings(max_examples=1000, database=None, phases=[Phase.generate])

#: For the tests of what the strategies shrink to.
SHRINK_SETTINGS = settings(max_examples=100, database=None)

#: Contacts are slow to draw; validity is checked on fewer examples.
CONTACT_SETTINGS = settings(max_examples=40)

#: Principal moments of a drawn tensor come back from eigvalsh within a few
#: eps of the largest; the regime predicates compare them with this slack.
MOMENT_RTOL = 64 * EPS


def _found(strategy, predicate):
    value = find(strategy, predicate, settings=FIND_SETTINGS)
    assert predicate(value)
    return value


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
    _found(ms.impact_masses(), predicate)


@pytest.mark.parametrize(("regime", "predicate"), list(MASS_PAIR_REGIMES.items()))
def test_mass_pairs_reach_every_regime(regime, predicate):
    _found(ms.mass_pairs(), predicate)


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
    _found(ms.mass_pairs(), lambda p: p[0] / p[1] <= 1e-14)
    _found(ms.mass_pairs(), lambda p: p[0] / p[1] >= 1e14)


@pytest.mark.parametrize(("regime", "predicate"), list(RESTITUTION_REGIMES.items()))
def test_restitution_coefficients_reach_every_regime(regime, predicate):
    _found(ms.restitution_coefficients(), predicate)


def test_restitution_coefficients_reach_one_ulp_below_one():
    _found(ms.restitution_coefficients(), lambda e: 0 < 1.0 - e <= 1e-15)


@pytest.mark.parametrize(("regime", "predicate"), list(DIRECT_VELOCITY_REGIMES.items()))
def test_direct_velocities_reach_every_regime(regime, predicate):
    _found(ms.direct_velocities(), predicate)


@pytest.mark.parametrize(("regime", "predicate"), list(INERTIA_REGIMES.items()))
def test_impact_inertia_tensors_reach_every_regime(regime, predicate):
    _found(ms.impact_inertia_tensors(), predicate)


@pytest.mark.parametrize(("regime", "predicate"), list(CONTACT_REGIMES.items()))
def test_contacts_reach_every_regime(regime, predicate):
    _found(ms.contacts(), predicate)


@pytest.mark.parametrize(("regime", "predicate"), list(HINGED_REGIMES.items()))
def test_hinged_bodies_reach_every_regime(regime, predicate):
    _found(ms.hinged_bodies(), predicate)


def test_every_documented_regime_has_a_reachability_test():
    assert set(ms.IMPACT_MASS_REGIMES) == set(MASS_REGIMES)
    assert set(ms.MASS_PAIR_REGIMES) == set(MASS_PAIR_REGIMES)
    assert set(ms.RESTITUTION_REGIMES) == set(RESTITUTION_REGIMES)
    assert set(ms.DIRECT_VELOCITY_REGIMES) == set(DIRECT_VELOCITY_REGIMES)
    assert set(ms.IMPACT_INERTIA_REGIMES) <= set(INERTIA_REGIMES)
    assert set(ms.CONTACT_REGIMES) == set(CONTACT_REGIMES)
    assert set(ms.HINGED_REGIMES) == set(HINGED_REGIMES)


# ------------------------------------------------------------------- validity


@given(ms.impact_masses())
def test_impact_masses_are_positive_and_within_the_default_bounds(m):
    assert 1e-15 <= m <= 1e15


@given(ms.restitution_coefficients())
def test_restitution_coefficients_lie_in_zero_one(e):
    assert 0.0 <= e <= 1.0


@given(ms.direct_velocities())
def test_direct_velocities_approach(v):
    assert v[0] >= v[1]  # Δẋ = ẋ_2 − ẋ_1 <= 0
    assert max(abs(v[0]), abs(v[1])) <= 1e6


@given(ms.contact_normals())
def test_contact_normals_are_unit(n):
    assert abs(math.hypot(*n) - 1.0) <= 2 * EPS


@given(ms.impact_inertia_tensors())
def test_impact_inertia_tensors_are_physical(J):
    # Accepted by the library's own validation: symmetric, positive definite,
    # triangle inequality within its documented slack.
    im.effective_mass(1.0, J, [0.0, 0.0, 0.0], [1.0, 0.0, 0.0])
    lam = _moments(J)
    assert lam[0] > 0
    assert lam[0] + lam[1] >= lam[2] * (1 - MOMENT_RTOL)


@CONTACT_SETTINGS
@given(ms.contacts())
def test_contacts_are_impacts(c):
    v_n = im.normal_relative_velocity(c.body_1, c.body_2, r_S=c.r_S, n=c.n)
    assert v_n <= -1e-3  # approach speed >= 1e-2, rounding far below
    assert 0.0 <= c.e <= 1.0


#: J_G + m (|d|² 1 − d dᵀ) from an exact d: a few rounded products and sums per entry
PARALLEL_AXIS_RTOL = 4 * EPS


def _hinged_example(m, J_G, d, A, axis) -> ms.HingedBody:
    """A hinged body built the way the strategy builds one (J_A from the exact d)."""
    J_A = J_G + m * (float(d @ d) * np.eye(3) - np.outer(d, d))
    return ms.HingedBody(m, 0.5 * (J_A + J_A.T), A + d, A, axis, J_G)


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
def test_hinged_bodies_obey_the_parallel_axis_theorem(h):
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


# ------------------------------------------------------------------- shrinking


@pytest.mark.parametrize(
    ("strategy", "simplest"),
    [
        pytest.param(ms.impact_masses(), 1.0, id="mass-1"),
        pytest.param(ms.mass_pairs(), (1.0, 1.0), id="pair-equal"),
        pytest.param(ms.restitution_coefficients(), 0.0, id="e-0"),
        pytest.param(ms.impact_inertia_tensors(), np.eye(3).tolist(), id="sphere-identity"),
    ],
)
def test_strategies_shrink_to_the_simple_case(strategy, simplest):
    value = find(strategy, lambda x: True, settings=SHRINK_SETTINGS)
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
