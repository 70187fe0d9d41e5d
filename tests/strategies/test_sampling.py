"""The shared sample of tests/strategies/sampling.py answers as the ``find`` runs it
replaced did: ``never`` fails on a draw that satisfies the predicate, ``found`` fails
when no draw does, and each question reads the draws already made."""

from __future__ import annotations

import pytest
from hypothesis import strategies as st

from tests.strategies import sampling
from tests.strategies.sampling import drawn_from, found, never, sample, shared


def test_never_names_a_draw_that_satisfies_the_predicate() -> None:
    never(st.integers(0, 10), lambda x: x > 10, 200)
    with pytest.raises(AssertionError, match="never should: 1"):
        never(st.just(1), lambda x: x == 1, 10)


def test_found_returns_a_satisfying_draw_and_fails_when_none_is_drawn() -> None:
    assert found(st.integers(0, 10), lambda x: x == 7, 500) == 7
    with pytest.raises(AssertionError, match="none of 50 draws"):
        found(st.integers(0, 10**6), lambda x: x > 10**6, 50)


def test_a_strategy_is_drawn_once_and_grown_only_as_far_as_asked() -> None:
    s = st.integers(-(10**9), 10**9)
    first = sample(s, 150)
    assert len(first) == 150
    assert sample(s, 100) == first[:100]  # read, not drawn again
    assert sample(s, 300)[:150] == first  # grown, the first draws kept


@pytest.mark.parametrize("derandomize", [True, False])
def test_the_runs_of_a_grown_sample_are_new_draws(derandomize, monkeypatch) -> None:
    """Each run of ``find`` draws anew, under the ``ci`` profile's derandomisation too
    (where every run used to repeat the first: a sample of 400 held ~100 values)."""
    monkeypatch.setattr(sampling, "_derandomized", lambda: derandomize)
    # a new strategy object (hypothesis caches st.integers(...) by its arguments, and a
    # sample lives as long as its object): this test's draws are its own
    first = sample(st.integers(-(2**62), 2**62).map(int), 400)
    assert len(set(first)) >= 360  # hypothesis repeats a few small and boundary values
    # another process (another random base): under ci the same sample, else new draws
    monkeypatch.setattr(sampling, "_RANDOM_BASE", sampling._RANDOM_BASE + 10**6)
    again = sample(st.integers(-(2**62), 2**62).map(int), 400)
    if derandomize:
        assert again == first
    else:
        assert len(set(again) - set(first)) >= 300


def test_shared_gives_one_object_per_factory_and_arguments() -> None:
    def factory(lo=0, hi=10):
        return st.integers(lo, hi).map(int)  # a new object on every call

    a = shared(factory, lo=1, hi=5)
    assert shared(factory, hi=5, lo=1) is a  # the same arguments, in any order
    assert shared(factory, lo=1, hi=6) is not a
    assert factory(lo=1, hi=5) is not a


def test_a_sample_is_the_same_however_it_was_grown(monkeypatch) -> None:
    """A shared sample may be grown by any test first: the draws must not depend on the
    order of the questions (runs of a fixed size, each seeded by its index)."""
    monkeypatch.setattr(sampling, "_derandomized", lambda: True)
    a, b = st.integers(0, 2**60).map(int), st.integers(0, 2**60).map(int)
    sample(a, 150)  # grown in steps: 150, then 270 more
    grown = sample(a, 420)
    assert sample(b, 420) == grown  # grown at once


def test_drawn_from_picks_among_the_first_draws_of_the_shared_sample() -> None:
    """A part given as ``drawn_from(s)`` takes only s's own first draws, read from its
    sample (not drawn again), and reaches many of them."""
    s = st.integers(-(2**62), 2**62).map(int)
    first = sample(s, 100)
    picked = sample(drawn_from(s), 300)
    assert set(picked) <= set(first)
    assert len(set(picked)) >= 50
    assert sample(s, 100) == first
    assert set(sample(drawn_from(s, 20), 200)) <= set(first[:20])
