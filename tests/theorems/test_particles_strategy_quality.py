"""The particle strategies of :mod:`mechanics.strategies` reach every regime they document.

As in ``test_strategy_quality.py``: each regime is *found* by
:func:`hypothesis.find` through a predicate on the drawn value (not on the
label the strategy records); the strategies produce only valid objects, shrink
to the simple case, and reject bad arguments by quoting them.
"""

from __future__ import annotations

import re

import numpy as np
import pytest
from hypothesis import Phase, find, given, settings
from hypothesis import strategies as st
from hypothesis.errors import InvalidArgument

from mechanics import strategies as ms
from mechanics.particles import internal_moment

#: Regimes are branches among at most five; 2000 draws find each many times over.
FIND_SETTINGS = settings(max_examples=2000, database=None, phases=[Phase.generate])
SHRINK_SETTINGS = settings(max_examples=200, database=None)


def _found(strategy, predicate):
    value = find(strategy, predicate, settings=FIND_SETTINGS)
    assert predicate(value)
    return value


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
    _found(ms.masses(), predicate)


@pytest.mark.parametrize(("regime", "predicate"), list(SYSTEM_REGIMES.items()))
def test_particle_systems_reach_every_regime(regime, predicate):
    _found(ms.particle_systems(), predicate)


@pytest.mark.parametrize(("regime", "predicate"), list(PAIR_FORCE_REGIMES.items()))
def test_pair_forces_reach_every_regime(regime, predicate):
    _found(ms.pair_forces(R3), predicate)


def test_every_documented_regime_has_a_reachability_test():
    assert set(ms.MASS_REGIMES) == set(MASS_REGIMES)
    assert set(ms.SYSTEM_REGIMES) == set(SYSTEM_REGIMES)
    assert set(ms.PAIR_FORCE_REGIMES) == set(PAIR_FORCE_REGIMES)


def test_particle_systems_reach_fifty_particles():
    _found(ms.particle_systems(), lambda s: len(s.m) == 50)


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


@given(ms.particle_systems())
def test_particle_systems_are_valid(s):
    n = len(s.m)
    assert 1 <= n <= 50
    assert s.r.shape == (n, 3)
    assert s.v.shape == (n, 3)
    assert np.all((s.m >= 1e-6) & (s.m <= 1e6))
    assert np.isfinite(s.r).all()
    assert np.isfinite(s.v).all()


@given(
    ms.particle_systems(max_particles=12).flatmap(
        lambda s: st.tuples(st.just(s), ms.pair_forces(s.r))
    )
)
def test_pair_forces_obey_newtons_third_law_and_their_bound(data):
    s, f = data
    n = len(s.m)
    assert f.shape == (n, n, 3)
    assert np.array_equal(f, -np.swapaxes(f, 0, 1))  # f_jk = −f_kj exactly (1.19)
    assert not np.diagonal(f, axis1=0, axis2=1).any()
    assert np.linalg.norm(f, axis=-1).max(initial=0.0) <= 1e3


@given(
    ms.particle_systems(max_particles=12).flatmap(
        lambda s: st.tuples(st.just(s), ms.pair_forces(s.r, regimes=["central"]))
    )
)
def test_central_pair_forces_are_parallel_to_the_particle_separation(data):
    s, f = data
    rkj = s.r[:, None, :] - s.r[None, :, :]
    cross = np.linalg.norm(np.cross(rkj, f), axis=-1)
    size = np.linalg.norm(rkj, axis=-1) * np.linalg.norm(f, axis=-1)
    assert np.all(cross <= 8 * np.finfo(float).eps * size + 1e-300)


@given(st.integers(1, 10), st.integers(0, 10), st.data())
def test_masses_respect_the_particle_count_bounds(lo, extra, data):
    m = data.draw(ms.masses(min_particles=lo, max_particles=lo + extra))
    assert lo <= len(m) <= lo + extra
    assert np.all((m >= 1e-6) & (m <= 1e6))


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
