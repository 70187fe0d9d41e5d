"""The property checks (kind ``property``, :mod:`identities.verify.properties`): the
search finds what is false, accepts what is true, is the same on every run, and a
property check without a negative control fails the catalogue's structure rule."""

from __future__ import annotations

import pytest
from hypothesis import strategies as st

from identities.verify.catalogue import Check, checks, run_check
from identities.verify.proof import CheckFailure, Derivation
from identities.verify.properties import search_counterexample

#: integers drawn in [0, 1000]; "n < 700" is false for about 30 % of them
INTS = st.tuples(st.integers(0, 1000))


def _below_700(n: int) -> None:
    assert n < 700, f"{n} is not below 700"


def _never_negative(n: int) -> None:
    assert n >= 0


def test_the_search_finds_a_counterexample_and_shrinks_it_to_the_boundary() -> None:
    found = search_counterexample(_below_700, INTS, examples=200, seed=1)
    assert found is not None
    assert found.arguments == (700,)  # shrunk to the smallest failing integer
    assert "700 is not below 700" in found.message


def test_the_search_accepts_a_true_property() -> None:
    assert search_counterexample(_never_negative, INTS, examples=200, seed=1) is None


def test_the_same_seed_draws_the_same_unshrunk_counterexample() -> None:
    runs = {
        search_counterexample(_below_700, INTS, examples=200, seed=7, shrink=False).arguments
        for _ in range(3)
    }
    assert len(runs) == 1


def test_a_crash_or_a_numpy_warning_on_a_drawn_example_is_a_counterexample() -> None:
    import numpy as np

    def divides(n: int) -> None:
        np.float64(1.0) / np.float64(n)  # n = 0: a RuntimeWarning, turned into a failure

    found = search_counterexample(divides, INTS, examples=200, seed=1)
    assert found is not None
    assert found.arguments == (0,)
    assert "RuntimeWarning" in found.message


def test_holds_for_examples_fails_with_the_counterexample() -> None:
    with pytest.raises(CheckFailure, match=r"fails for \(700,\)"):
        Derivation().holds_for_examples(_below_700, INTS, examples=200, claim="n < 700")


def test_a_negative_control_that_holds_is_caught() -> None:
    with pytest.raises(CheckFailure, match="negative control accepted"):
        Derivation().reject_property(_never_negative, INTS, examples=200, claim="n ≥ 0")


def test_a_property_check_without_a_negative_control_fails() -> None:
    def only_positive(d: Derivation) -> None:
        d.holds_for_examples(_never_negative, INTS, examples=50, claim="n ≥ 0")

    outcome, _ = run_check(Check("thm.fake", "fake", "property", only_positive))
    assert not outcome.passed
    assert "negative control" in outcome.message


def test_the_catalogue_runs_the_randomised_invariants_as_property_checks() -> None:
    # the list: momentum, energy, restitution, rotation orthogonality, parallel axis
    props = {c.id: c for c in checks(kind="property")}
    assert {
        "thm.impact-momentum",
        "thm.impact-energy-loss",
        "thm.impact-restitution",
        "thm.rotation-orthogonal",
        "thm.parallel-axis",
    } <= set(props)
    for c in props.values():
        assert c.covers, f"{c.id} backs no book item"
