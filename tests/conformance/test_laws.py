"""law_violations (issue 29, item 3): the laws a trajectory keeps, checked on any
engine's trajectory of a scenario and named with the book's equation; the exact motion
keeps them all, a correct engine within its step error, and each wrong law is named."""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings

from mechanics import strategies as ms
from mechanics._floats import EPS
from mechanics.conformance import ConformanceError, get_scenario, law_violations, reference

from .toys import ignores_restitution, planted_toy

#: the exact motion keeps every law to rounding: 2^10 eps of the law's scale
ROUNDING = 2**10 * EPS
#: the first-order toy's drifts at 2^-8 s stay below 2^-4 (measured: 2.2 % at most)
FIRST_ORDER = 2.0**-4


@settings(deadline=None, max_examples=30)
@given(ms.scenarios())
def test_the_exact_motion_keeps_every_law_of_any_drawn_scenario(s):
    assert law_violations(s, reference(s).trajectory, rtol=ROUNDING) == []


@pytest.mark.parametrize("name", ["free_top_axis1", "parabola", "bouncing_ball"])
def test_a_correct_engine_keeps_them_within_its_step_error_and_breaks_a_tight_bound(name):
    s = get_scenario(name)
    tr = planted_toy().run(s, 2.0**-8)
    assert law_violations(s, tr, rtol=FIRST_ORDER) == []
    tight = law_violations(s, tr, rtol=ROUNDING)
    assert tight  # step error is not rounding: the check can fail
    assert all(" (" in v for v in tight)  # each names its law


def test_each_wrong_law_is_named_with_its_equation():
    s = get_scenario("free_top_axis1")
    for bug in ("world-frame inertia in the gyroscopic term", "gyroscopic term dropped"):
        got = law_violations(s, planted_toy(bug).run(s, 2.0**-8), rtol=FIRST_ORDER)
        assert len(got) == 1
        assert got[0].startswith("L is not conserved: it drifts ")
        assert got[0].endswith(
            "(the angular momentum principle with no external moment (Chapter 1))"
        )
    b = get_scenario("bouncing_ball")
    squared = law_violations(b, planted_toy("restitution squared").run(b, 2.0**-8), rtol=2**-4)
    assert squared == [
        "the rebounds restitute e = 0.586 (the median of √(h_k+1/h_k) over 5 rebound(s)), "
        "not the scenario's 0.8 (Newton's law of restitution, 6.6)"
    ]
    elastic = ignores_restitution()
    i = get_scenario("two_body_impact")
    assert law_violations(i, elastic.run(i, None), rtol=2**-10) == [
        "the impact restitutes e = 1, not the scenario's 0.6 (the separation speed is e "
        "times the approach speed, 6.6, 6.36-6.38)"
    ]
    assert law_violations(b, elastic.run(b, None), rtol=2**-10)[0].startswith(
        "the rebounds restitute e = 1 "
    )


def test_a_bad_trajectory_or_rtol_is_refused():
    s = get_scenario("parabola")
    tr = reference(s).trajectory
    with pytest.raises(ConformanceError, match=r"^scenario 'parabola': the adapter must"):
        law_violations(s, {"t": tr.t}, rtol=1e-3)
    for bad in (-1.0, math.nan, math.inf, "1e-3", None):
        with pytest.raises(ValueError, match=r"^rtol must be a finite number >= 0; got "):
            law_violations(s, tr, rtol=bad)
