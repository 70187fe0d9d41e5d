"""The particle strategies of :mod:`mechanics.strategies` reach every regime they document.

As in ``test_strategy_quality.py``: each regime is *found* by
:func:`hypothesis.find` through a predicate on the drawn value (not on the
label the strategy records); the strategies produce only valid objects, shrink
to the simple case, and reject bad arguments by quoting them.
"""

from __future__ import annotations

import functools
import math
import re

import numpy as np
import pytest
from hypothesis import find, given, settings
from hypothesis import strategies as st
from hypothesis.errors import InvalidArgument

from mechanics import strategies as ms
from mechanics._floats import EPS
from mechanics.particles import internal_moment
from tests.strategies.sampling import found, never, shared

#: Regimes are branches among at most five; 2000 draws find each many times over.
FIND_DRAWS = 2000
SHRINK_SETTINGS = settings(max_examples=200, database=None)


def _found(strategy, predicate):
    return found(strategy, predicate, FIND_DRAWS)


MASS_REGIMES = {
    "unit": lambda m: bool(np.all(m == 1.0)) and len(m) >= 2,
    "equal": lambda m: len(m) >= 2 and bool(np.all(m == m[0])) and m[0] != 1.0,
    "log-uniform": lambda m: len(set(m.tolist())) >= 3,
    "extreme-ratio": lambda m: m.min() == 1e-6 and m.max() == 1e6,
}

SYSTEM_REGIMES = {
    "simple": lambda s: bool(np.all(s.m == 1.0)) and np.abs(s.r).max() <= 1 and len(s.m) >= 2,
    "generic": lambda s: 1 < np.abs(s.r).max() <= 10 and 1 < np.abs(s.v).max() <= 10,
    "wide-mass-ratio": lambda s: s.m.max() / s.m.min() >= 1e12,
    "far-offset": lambda s: np.abs(s.r).min() >= 1e8 - 1,
    "fast-translation": lambda s: np.abs(s.v).min() >= 1e6 - 1,
}

R3 = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 2.0, 0.5]])


def _central(f, r=R3):
    rkj = r[:, None, :] - r[None, :, :]
    return bool(np.abs(np.cross(rkj, f)).max() <= 1e-12 * max(1.0, np.abs(f).max()))


PAIR_FORCE_REGIMES = {
    "none": lambda f: not f.any(),
    "central": lambda f: f.any() and _central(f),
    "non-central": lambda f: np.abs(internal_moment(R3, f)).max() > 1e-3,
}


@pytest.mark.parametrize(("regime", "predicate"), list(MASS_REGIMES.items()))
def test_masses_reach_every_regime(regime, predicate):
    _found(shared(ms.masses), predicate)


@pytest.mark.parametrize(("regime", "predicate"), list(SYSTEM_REGIMES.items()))
def test_particle_systems_reach_every_regime(regime, predicate):
    _found(shared(ms.particle_systems), predicate)


#: one object for the regime tests below, which then read one sample (the positions are
#: an array, which sampling.shared cannot key on)
PAIR_FORCES_R3 = ms.pair_forces(R3)


@pytest.mark.parametrize(("regime", "predicate"), list(PAIR_FORCE_REGIMES.items()))
def test_pair_forces_reach_every_regime(regime, predicate):
    _found(PAIR_FORCES_R3, predicate)


def test_every_documented_regime_has_a_reachability_test():
    assert set(ms.MASS_REGIMES) == set(MASS_REGIMES)
    assert set(ms.SYSTEM_REGIMES) == set(SYSTEM_REGIMES)
    assert set(ms.PAIR_FORCE_REGIMES) == set(PAIR_FORCE_REGIMES)


def test_particle_systems_reach_fifty_particles():
    _found(shared(ms.particle_systems), lambda s: len(s.m) == 50)


@pytest.mark.parametrize("regime", ms.SYSTEM_REGIMES)
def test_particle_systems_restricted_to_one_regime_stay_in_it(regime):
    predicate = {
        "simple": lambda s: bool(np.all(s.m == 1.0)) and np.abs(s.r).max() <= 1,
        "generic": lambda s: np.abs(s.r).max() <= 10 and np.abs(s.v).max() <= 10,
        "wide-mass-ratio": lambda s: set(s.m.tolist()) <= {1e-6, 1e6},
        "far-offset": SYSTEM_REGIMES["far-offset"],
        "fast-translation": SYSTEM_REGIMES["fast-translation"],
    }[regime]

    @settings(max_examples=50)
    @given(ms.particle_systems(regimes=[regime]))
    def check(s):
        assert predicate(s), s

    check()


# ------------------------------------------------------------------- validity


def test_particle_systems_are_valid():
    @given(ms.particle_systems())
    def check(s):
        n = len(s.m)
        assert 1 <= n <= 50
        assert s.r.shape == (n, 3)
        assert s.v.shape == (n, 3)
        assert np.all((s.m >= 1e-6) & (s.m <= 1e6))
        assert np.isfinite(s.r).all()
        assert np.isfinite(s.v).all()

    check()


def test_pair_forces_obey_newtons_third_law_and_their_bound():
    @given(
        ms.particle_systems(max_particles=12).flatmap(
            lambda s: st.tuples(st.just(s), ms.pair_forces(s.r))
        )
    )
    def check(data):
        s, f = data
        n = len(s.m)
        assert f.shape == (n, n, 3)
        assert np.array_equal(f, -np.swapaxes(f, 0, 1))  # f_jk = −f_kj exactly (1.19)
        assert not np.diagonal(f, axis1=0, axis2=1).any()
        assert np.linalg.norm(f, axis=-1).max(initial=0.0) <= 1e3

    check()


def test_central_pair_forces_are_parallel_to_the_particle_separation():
    @given(
        ms.particle_systems(max_particles=12).flatmap(
            lambda s: st.tuples(st.just(s), ms.pair_forces(s.r, regimes=["central"]))
        )
    )
    def check(data):
        s, f = data
        rkj = s.r[:, None, :] - s.r[None, :, :]
        cross = np.linalg.norm(np.cross(rkj, f), axis=-1)
        size = np.linalg.norm(rkj, axis=-1) * np.linalg.norm(f, axis=-1)
        assert np.all(cross <= 8 * EPS * size + 1e-300)

    check()


def test_masses_respect_the_particle_count_bounds():
    @given(st.integers(1, 10), st.integers(0, 10), st.data())
    def check(lo, extra, data):
        m = data.draw(ms.masses(min_particles=lo, max_particles=lo + extra))
        assert lo <= len(m) <= lo + extra
        assert np.all((m >= 1e-6) & (m <= 1e6))

    check()


# ------------------------------------------------------------------- shrinking


def test_particle_systems_shrink_to_one_unit_mass_at_rest_at_the_origin():
    s = find(ms.particle_systems(), lambda s: True, settings=SHRINK_SETTINGS)
    assert s.m.tolist() == [1.0]
    assert not s.r.any()
    assert not s.v.any()


def test_pair_forces_shrink_to_no_force():
    f = find(ms.pair_forces(R3), lambda f: True, settings=SHRINK_SETTINGS)
    assert not f.any()


# -------------------------------------------------------------- bad arguments


@pytest.mark.parametrize(
    ("kwargs", "quoted"),
    [
        pytest.param({"min_mass": 0.0}, "0.0", id="zero-min-mass"),
        pytest.param({"min_mass": -1.0}, "-1.0", id="negative-min-mass"),
        pytest.param({"min_mass": 2.0, "max_mass": 1.0}, "2.0", id="min-above-max"),
        pytest.param({"max_mass": float("inf")}, "inf", id="infinite"),
        pytest.param({"min_particles": 0}, "0", id="no-particles"),
        pytest.param({"min_particles": 5, "max_particles": 2}, "5", id="min-above-max-n"),
        pytest.param({"max_particles": 2.5}, "2.5", id="non-integer"),
        pytest.param({"regimes": ["huge"]}, "huge", id="unknown-regime"),
        pytest.param({"regimes": "simple"}, "'simple'", id="regimes-as-string"),
    ],
)
def test_particle_systems_reject_bad_arguments_quoting_them(kwargs, quoted):
    with pytest.raises(InvalidArgument, match=re.escape(quoted)):
        ms.particle_systems(**kwargs)


@pytest.mark.parametrize(
    ("args", "kwargs", "quoted"),
    [
        pytest.param((np.zeros((2, 2)),), {}, "(2, 2)", id="bad-shape"),
        pytest.param((R3,), {"max_magnitude": -1.0}, "-1.0", id="negative-bound"),
        pytest.param((R3,), {"regimes": ["magnetic"]}, "magnetic", id="unknown-regime"),
    ],
)
def test_pair_forces_reject_bad_arguments_quoting_them(args, kwargs, quoted):
    with pytest.raises(InvalidArgument, match=re.escape(quoted)):
        ms.pair_forces(*args, **kwargs)


def test_masses_reject_a_unit_regime_outside_the_bounds():
    with pytest.raises(InvalidArgument, match="'unit'"):
        ms.masses(min_value=2.0, max_value=3.0, regimes=["unit"])


# ------------------------------------------------------- each regime's bounds
#
# Each regime drawn alone stays within the bounds its docstring states and reaches both
# ends of them.  The strategies are built inside the tests.

NEVER_DRAWS = 500


def _never(strategy, predicate) -> None:
    never(strategy, predicate, NEVER_DRAWS)


@pytest.mark.parametrize(("lo", "hi"), [(1e-6, 1e6), (0.3, 5.0), (2.0, 3.0)])
def test_masses_each_regime_stays_within_the_bounds(lo, hi):
    @functools.cache  # one strategy, so one sample, per regime for all its questions
    def regime(r):
        return ms.masses(min_value=lo, max_value=hi, regimes=[r])

    def inside(m):
        return bool(np.all((m >= lo) & (m <= hi)))

    if lo <= 1.0 <= hi:
        _never(regime("unit"), lambda m: not np.all(m == 1.0))
    _never(regime("equal"), lambda m: not (inside(m) and np.all(m == m[0])))
    _found(regime("equal"), lambda m: m[0] <= lo * 1.1)
    _found(regime("equal"), lambda m: m[0] >= hi / 1.1)
    _never(regime("log-uniform"), lambda m: not inside(m))
    _found(regime("log-uniform"), lambda m: len(set(m.tolist())) >= 3)
    _found(regime("log-uniform"), lambda m: m.min() <= lo * 1.1)
    _found(regime("log-uniform"), lambda m: m.max() >= hi / 1.1)
    # extreme-ratio: every mass at a bound, both bounds present from two particles on
    ends = {lo, hi}
    _never(regime("extreme-ratio"), lambda m: not set(m.tolist()) <= ends)
    _never(regime("extreme-ratio"), lambda m: len(m) >= 2 and set(m.tolist()) != ends)
    _found(regime("extreme-ratio"), lambda m: len(m) >= 3 and (m == hi).sum() >= 2)
    _found(regime("extreme-ratio"), lambda m: len(m) >= 3 and (m == lo).sum() >= 2)
    # all regimes together, unit left out when 1 is outside the bounds
    _never(ms.masses(min_value=lo, max_value=hi), lambda m: not inside(m))


def test_log_uniform_masses_at_the_extreme_unit_draws_are_exactly_the_bounds(monkeypatch):
    # 10**log10(5.0) rounds above 5.0 and 10**log10(0.3) below 0.3: the bounds must clip.
    lo, hi = 0.3, 5.0
    assert 10.0 ** math.log10(hi) > hi
    assert 10.0 ** math.log10(lo) < lo
    for u, expected in ((-1.0, hi), (0.0, lo)):
        monkeypatch.setattr(ms.particles, "_signed_units", lambda k, u=u: st.just(np.full(k, u)))
        # built afresh (``__wrapped__``: the factory itself, not its memoised objects),
        # so that the patched _signed_units is the one its first draw builds from
        strategy = ms.masses.__wrapped__(min_value=lo, max_value=hi, regimes=["log-uniform"])
        m = find(strategy, lambda m: True, settings=SHRINK_SETTINGS)
        assert m.tolist() == [expected] * len(m)


@pytest.mark.parametrize(("lo", "hi"), [(0.5, 1.0), (1.0, 2.0)])
def test_the_unit_regime_is_kept_when_one_is_a_bound(lo, hi):
    _never(ms.masses(min_value=lo, max_value=hi, regimes=["unit"]), lambda m: not np.all(m == 1))
    systems = ms.particle_systems(min_mass=lo, max_mass=hi, regimes=["simple"])
    _never(systems, lambda s: not np.all(s.m == 1.0))
    generic = ms.particle_systems(min_mass=lo, max_mass=hi, regimes=["generic"])
    _found(generic, lambda s: len(s.m) >= 2 and bool(np.all(s.m == 1.0)))


def test_particle_systems_outside_unit_bounds_draw_equal_simple_masses_within_them():
    simple = ms.particle_systems(min_mass=2.0, max_mass=3.0, regimes=["simple"])
    _never(simple, lambda s: not (np.all(s.m == s.m[0]) and 2.0 <= s.m[0] <= 3.0))
    every = ms.particle_systems(min_mass=2.0, max_mass=3.0)
    _never(every, lambda s: not np.all((s.m >= 2.0) & (s.m <= 3.0)))


def test_generic_particle_systems_draw_masses_of_every_mass_regime():
    generic = ms.particle_systems(regimes=["generic"])
    for predicate in MASS_REGIMES.values():
        _found(generic, lambda s, p=predicate: p(s.m))


@pytest.mark.parametrize(
    ("regime", "field", "centre"),
    [
        ("far-offset", "r", ms.FAR_OFFSET),
        ("fast-translation", "v", 1e6),
    ],
)
def test_far_and_fast_systems_are_offset_by_the_documented_magnitude_either_way(
    regime, field, centre
):
    # each coordinate within 1 of ±(1 … 2) × the offset, with signs drawn per coordinate
    strategy = ms.particle_systems(regimes=[regime])

    def x(s):
        return getattr(s, field)

    _never(
        strategy,
        lambda s: not np.all((np.abs(x(s)) >= centre - 1) & (np.abs(x(s)) <= 2 * centre + 1)),
    )
    for k in range(3):
        _found(strategy, lambda s, k=k: x(s)[0, k] > 0)
        _found(strategy, lambda s, k=k: x(s)[0, k] < 0)
    _found(strategy, lambda s: np.abs(x(s)).max() >= 1.9 * centre)
    _found(strategy, lambda s: np.abs(x(s)).min() <= 1.1 * centre)
    other = "v" if field == "r" else "r"
    bound = 1.0 if field == "r" else 10.0
    _never(strategy, lambda s: np.abs(getattr(s, other)).max() > bound)
    _found(strategy, lambda s: np.abs(getattr(s, other)).max() >= 0.9 * bound)


#: Perpendicular part of a pair force, measured by subtracting its projection on e_kj:
#: a few roundings of the whole force, |f| ≤ max_magnitude (so relative to that bound).
PERP_ATOL = 2**4 * EPS


@pytest.mark.parametrize("fmax", [1e3, 2.0])
def test_pair_forces_keep_the_documented_magnitudes(fmax):
    rkj = R3[:, None, :] - R3[None, :, :]
    apart = ~np.eye(3, dtype=bool)
    e = rkj[apart] / np.linalg.norm(rkj[apart], axis=-1, keepdims=True)

    def perp(f):
        g = f[apart]
        return np.linalg.norm(g - (g * e).sum(-1, keepdims=True) * e, axis=-1)

    central = ms.pair_forces(R3, max_magnitude=fmax, regimes=["central"])
    _never(central, lambda f: np.linalg.norm(f, axis=-1).max() > fmax)
    _found(central, lambda f: np.linalg.norm(f, axis=-1).max() >= 0.4 * fmax)
    non_central = ms.pair_forces(R3, max_magnitude=fmax, regimes=["non-central"])
    _never(non_central, lambda f: np.linalg.norm(f, axis=-1).max() > fmax)
    _never(
        non_central,
        lambda f: (
            not np.all(
                (perp(f) >= (5e-4 - PERP_ATOL) * fmax) & (perp(f) <= (0.25 + PERP_ATOL) * fmax)
            )
        ),
    )
    _found(non_central, lambda f: perp(f).min() <= 1e-3 * fmax)
    _found(non_central, lambda f: perp(f).max() >= 0.2 * fmax)
    _never(ms.pair_forces(R3, max_magnitude=fmax, regimes=["none"]), lambda f: f.any())


def test_pair_forces_between_coincident_particles_are_zero_when_central():
    r = np.zeros((2, 3))
    _never(ms.pair_forces(r, regimes=["central"]), lambda f: f.any())
    _found(ms.pair_forces(r, regimes=["non-central"]), lambda f: f.any())
