"""Profiles, thresholds files and baselines (issue 29, item 1): a correct engine of a
class passes its class's profile and fails the next stricter one; each planted bug
fails the loosest stepping profile; the layers (profile, adapter, file, caller) win in
that order; files and bad settings are refused naming the file, the key and what is
expected."""

from __future__ import annotations

import math
import re
from typing import ClassVar

import numpy as np
import pytest

from mechanics._floats import EPS
from mechanics.conformance import SCENARIOS, ThresholdError, get_scenario, reference, run_battery
from mechanics.conformance.adapters import ExactAdapter, SceneEngineAdapter
from mechanics.conformance.battery import Run, _order
from mechanics.conformance.protocol import check_trajectory
from mechanics.conformance.scenarios import measure
from mechanics.conformance.thresholds import (
    DEFAULT_THRESHOLDS,
    PROFILES,
    Config,
    _threshold,
    baseline,
    find_config,
    get_profile,
    load_config,
)

from .toys import BROKEN, BUGS, RK4, Midpoint
from .toys import planted_toy as toy

#: a baseline's bound rounds up to three significant digits: at most one unit of the
#: third digit, 1 % of a value whose leading digit is 1
THREE_DIGITS = 1e-2


def verdicts(report) -> dict[str, str]:
    return {r.scenario: r.status for r in report.results if r.status != "unsupported"}


# -- a correct engine passes its class and fails the stricter one ----------------------

CLASSES = [
    # (engine, its class, the next stricter class, a scenario where that one fails)
    (toy, "first-order", "second-order", "free_top_axis1"),
    (Midpoint, "second-order", "high-order", "free_top_axis1"),
    (RK4, "high-order", "exact", "free_top_near_separatrix"),
]


class Remembered:
    """``engine`` with each run kept, by scenario and step: a second battery over the
    same scenario judges the same trajectories (the toys are deterministic) instead of
    stepping them again."""

    def __init__(self, engine):
        self.engine, self.name, self.takes_step = engine, engine.name, engine.takes_step
        self.runs: dict = {}

    def supports(self, scenario):
        return self.engine.supports(scenario)

    def run(self, scenario, step):
        key = (scenario.name, step)
        if key not in self.runs:
            self.runs[key] = self.engine.run(scenario, step)
        return self.runs[key]


@pytest.mark.parametrize(("make", "own", "stricter", "where"), CLASSES, ids=[c[1] for c in CLASSES])
def test_a_correct_engine_passes_its_class_and_fails_the_stricter_one(make, own, stricter, where):
    """The engine's battery at its own profile passes, reading the order on at least four
    scenarios; at the next stricter profile the scenario ``where`` fails.  That second
    verdict judges the runs of the first again (:class:`Remembered`): the profile is a
    set of bounds on the same trajectories, so stepping them again (a quarter of the
    test's time) would only repeat them."""
    engine = Remembered(make())
    report = run_battery(engine, profile=own)
    assert report.passed, report.to_markdown()
    assert report.profile == own
    ran = [s for s, v in verdicts(report).items() if v == "pass"]
    assert where in ran, ran
    assert len(ran) >= 4, ran  # not passed by skipping everything
    checked = 0
    for s in ran:  # the order is read, and checked where the profile checks it
        order = report[s].figure("order")
        assert order is not None, s
        assert order.value is not None, s
        if order.threshold is not None:
            assert order.passed is True, (s, order)
            assert order.value >= PROFILES[own].thresholds["order"]
            checked += 1
    assert checked >= 4  # not passed for want of an order
    stepped = set(engine.runs)
    strict = run_battery(engine, scenarios=[where], profile=stricter)[where]
    assert strict.status == "fail", strict.message
    assert set(engine.runs) == stepped  # the same trajectories, judged again


@pytest.mark.parametrize("adapter", [ExactAdapter, SceneEngineAdapter])
def test_closed_forms_and_the_integrated_engine_pass_the_exact_profile(adapter):
    report = run_battery(adapter(), profile="exact")
    assert report.passed, report.to_markdown()
    assert set(verdicts(report).values()) == {"pass"}
    assert len(verdicts(report)) == len(SCENARIOS)


@pytest.mark.parametrize("bug", list(BUGS))
def test_each_planted_bug_fails_the_first_order_profile_where_its_law_acts(bug):
    report = run_battery(toy(bug), profile="first-order", scenarios=BROKEN[bug])
    assert verdicts(report) == dict.fromkeys(BROKEN[bug], "fail"), report.to_markdown()


def test_the_first_order_profile_separates_a_bug_that_magnitudes_alone_cannot():
    """At 2^-4 the dropped gyroscopic term's attitude error would pass on its own near a
    looser bound; the order (≈ 0: the error does not shrink with the step) fails it."""
    r = run_battery(toy("gyroscopic term dropped"), profile="first-order",
                    scenarios=["free_top_axis1"], thresholds={"attitude": 1.0, "omega": 1.0,
                    "omega_period": None, "L_drift": None})["free_top_axis1"]  # fmt: skip
    assert r.status == "fail"
    assert re.match(
        r"order -?\d\.\d+e-\d+ violates threshold >= 0\.5\. The error does not shrink with "
        r"the step \(order -?\d\.?\d*e-\d+\): a law is wrong, not the step size\. ",
        r.message,
    ), r.message
    assert [f.name for f in r.figures if f.passed is False] == ["order"]


# -- the order of an impact scenario is read from its event figures --------------------


def test_the_bounces_order_is_the_slope_of_the_event_figures_errors():
    s = get_scenario("bouncing_ball")
    engine, ref = toy(), reference(s)
    errors = []
    for h in s.steps:  # independently of the battery: the apex errors at each step
        m = measure(s, check_trajectory(s, engine.run(s, h)))
        errors.append(
            max(
                float(np.max(np.abs(np.subtract(m[k], v))) / np.max(np.abs(v)))
                for k, v in ref.figures.items()
            )
        )
    slope = np.polyfit(np.log(s.steps), np.log(errors), 1)[0]
    r = run_battery(engine, scenarios=[s], profile="first-order")[s.name]
    order = r.figure("order")
    assert order.note == "read from the event figures"
    assert order.value == pytest.approx(slope, rel=2**-20)
    assert 0.8 <= order.value < 1.0  # first order, read a little low before the asymptote


def test_an_unreadable_event_figure_leaves_no_order_and_says_at_which_step():
    runs = [Run(2.0**-6, 0.0, 0.5), Run(2.0**-7, 0.0, math.inf), Run(2.0**-8, 0.0, 0.1)]
    assert _order(runs) == (None, "an event figure could not be read at step 0.0078125 s: no order")
    r = run_battery(toy("restitution squared"), scenarios=["bouncing_ball"], profile="first-order")
    order = r["bouncing_ball"].figure("order")
    assert order.value is None
    assert order.note.startswith("an event figure could not be read")


# -- the profiles' bounds -----------------------------------------------------------------


def test_each_stepping_profile_bounds_every_figure_and_the_order():
    near = "free_top_near_separatrix"
    for name, least, rtol in [("first-order", 0.5, 2**-2), ("second-order", 1.5, 2**-8),
                              ("high-order", 3.0, 2**-20)]:  # fmt: skip
        p = get_profile(name)
        th = dict(p.thresholds)
        assert th.pop("order") == least
        plain = {k: v for k, v in th.items() if "." not in k}
        assert set(plain) == set(DEFAULT_THRESHOLDS) - {"order"}
        assert set(plain.values()) == {rtol}
        special = {k: v for k, v in th.items() if "." in k}
        impacts = {
            "two_body_impact.velocity": None,
            "two_body_impact.omega": None,
            "bouncing_ball.velocity": None,
            "bouncing_ball.omega": None,
            "box_landing_flat.velocity": None,
            "box_landing_flat.omega": None,
            "newtons_cradle.velocity": None,
            "newtons_cradle.omega": None,
            "bounce_to_rest.velocity": None,
            "bounce_to_rest.omega": None,
            "oblique_impact_sticks.velocity": None,
            "oblique_impact_sticks.omega": None,
            "oblique_impact_slips.velocity": None,
            "oblique_impact_slips.omega": None,
        }
        if name == "first-order":  # the phase near the separatrix is not resolved
            separatrix = dict.fromkeys(
                (f"{near}.attitude", f"{near}.omega", f"{near}.omega_period", f"{near}.order")
            )
        else:
            separatrix = {f"{near}.attitude": 8 * rtol, f"{near}.omega": 8 * rtol}
        assert special == {**impacts, **separatrix}
    exact = dict(get_profile("exact").thresholds)
    assert exact.pop("order") is None
    assert set(exact.values()) == {2**-28}
    assert dict(get_profile("default").thresholds) == DEFAULT_THRESHOLDS


def test_an_unknown_profile_is_refused_naming_it_and_the_known_ones():
    known = "first-order, second-order, high-order, exact, default"
    for bad in ("first order", "", None, 1):
        with pytest.raises(ThresholdError) as e:
            get_profile(bad)
        assert str(e.value) == f"unknown conformance profile {bad!r}; known: {known}"
    with pytest.raises(ThresholdError, match=r"^unknown conformance profile 'fast'"):
        run_battery(ExactAdapter(), scenarios=["parabola"], profile="fast")


# -- the layers: profile < adapter < file < caller; scenario.figure over figure ---------


def test_the_last_layer_that_sets_a_figure_wins_and_a_plain_key_overrides_a_profiles_special():
    profile = {"attitude": 1.0, "near.attitude": 8.0, "order": 0.8}
    adapter = {"attitude": 2.0}
    file = {"near.attitude": 3.0}
    caller = {"order": None}
    layers = [profile, adapter, file, caller]
    assert _threshold(layers, "near", "attitude") == 3.0
    assert _threshold(layers, "other", "attitude") == 2.0
    assert _threshold(layers, "near", "order") is None
    assert _threshold([profile, adapter], "near", "attitude") == 2.0  # plain beats special
    assert _threshold([profile], "near", "attitude") == 8.0
    assert _threshold([{}], "x", "velocity") == DEFAULT_THRESHOLDS["velocity"]


class Claims(ExactAdapter):
    """The exact adapter claiming a profile and thresholds of its own."""

    name = "claims"
    profile = "first-order"
    thresholds: ClassVar = {"position": 0.5}


def test_the_adapter_says_what_it_claims_and_the_caller_and_file_win_over_it():
    r = run_battery(Claims(), scenarios=["parabola"])
    assert r.profile == "first-order"
    assert r["parabola"].figure("position").threshold == 0.5
    assert r["parabola"].figure("velocity").threshold == 2**-2
    cfg = Config("second-order", {"position": 0.25}, "f.toml")
    r = run_battery(Claims(), scenarios=["parabola"], config=cfg)
    assert (r.profile, r.config) == ("second-order", "f.toml")
    assert r["parabola"].figure("position").threshold == 0.25
    r = run_battery(Claims(), scenarios=["parabola"], config=cfg, profile="exact",
                    thresholds={"position": 0.125})  # fmt: skip
    assert r.profile == "exact"
    assert r["parabola"].figure("position").threshold == 0.125
    assert r["parabola"].figure("velocity").threshold == 2**-28
    assert r.thresholds == {"position": 0.125}


@pytest.mark.parametrize(
    ("attrs", "message"),
    [
        ({"profile": "fast"}, "unknown conformance profile 'fast'; known: "),
        ({"profile": 1}, "the adapter's profile must be a profile's name (a str); got 1"),
        ({"thresholds": {"velocty": 1}}, "the adapter's thresholds: unknown threshold key(s) 'velocty'"),
        ({"thresholds": [1]}, "the adapter's thresholds: thresholds must be a dict of figure name -> number; got list"),
    ],
)  # fmt: skip
def test_an_adapters_bad_claim_is_refused_saying_it_came_from_the_adapter(attrs, message):
    adapter = type("Bad", (ExactAdapter,), attrs)()
    with pytest.raises(ThresholdError) as e:
        run_battery(adapter, scenarios=["parabola"])
    assert str(e.value).startswith(message)


# -- files -----------------------------------------------------------------------------


def test_a_pyproject_table_and_a_file_of_its_own_read_alike(tmp_path):
    (tmp_path / "pyproject.toml").write_text(
        '[project]\nname = "x"\n\n[tool.bodycheck.conformance]\nprofile = "first-order"\n\n'
        "[tool.bodycheck.conformance.thresholds]\nvelocity = 1e-3\n"
        '"heavy_top.nutation_period" = "none"\norder = 1\n',
        encoding="utf-8",
    )
    (tmp_path / "th.toml").write_text(
        'profile = "first-order"\n[thresholds]\nvelocity = 1e-3\n'
        '"heavy_top.nutation_period" = "None"\norder = 1\n',
        encoding="utf-8",
    )
    a, b = load_config(tmp_path / "pyproject.toml"), load_config(tmp_path / "th.toml")
    want = {"velocity": 1e-3, "heavy_top.nutation_period": None, "order": 1.0}
    assert (
        (a.profile, dict(a.thresholds)) == (b.profile, dict(b.thresholds)) == ("first-order", want)
    )
    assert a.source == f"{tmp_path / 'pyproject.toml'} [tool.bodycheck.conformance]"
    assert b.source == str(tmp_path / "th.toml")


def test_a_pyproject_without_the_table_sets_nothing_and_is_found_from_below(tmp_path):
    (tmp_path / "pyproject.toml").write_text('[project]\nname = "x"\n', encoding="utf-8")
    assert load_config(tmp_path / "pyproject.toml") == Config()
    below = tmp_path / "a" / "b"
    below.mkdir(parents=True)
    assert find_config(below) == tmp_path / "pyproject.toml"
    assert find_config(tmp_path) == tmp_path / "pyproject.toml"


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ('profle = "exact"\n', "F: unknown key(s) 'profle'; expected 'profile' and a table 'thresholds'"),
        ('profile = "fast"\n', "F: unknown conformance profile 'fast'; known: first-order, second-order, high-order, exact, default"),
        ("thresholds = 3\n", "F: 'thresholds' must be a table of figure = number; got 3"),
        ("[thresholds]\nvelocty = 1e-3\n", "F: unknown threshold key(s) 'velocty'; a key is a figure"),
        ('[thresholds]\nvelocity = "small"\n', "F: threshold 'velocity' must be a number >= 0 or \"none\"; got 'small'"),
        ("[thresholds]\nvelocity = true\n", "F: threshold 'velocity' must be a number >= 0 or \"none\"; got True"),
        ("[thresholds]\nvelocity = -1.0\n", "F: threshold 'velocity' must be a finite number >= 0 (or None); got -1.0"),
        ("[thresholds]\nvelocity = inf\n", "F: threshold 'velocity' must be a finite number >= 0 (or None); got inf"),
        ("velocity = = 1\n", "thresholds file 'F' is not valid TOML: "),
    ],
)  # fmt: skip
def test_a_bad_thresholds_file_is_refused_naming_the_file_the_key_and_what_is_expected(
    tmp_path, text, message
):
    f = tmp_path / "th.toml"
    f.write_text(text, encoding="utf-8")
    with pytest.raises(ThresholdError) as e:
        load_config(f)
    assert str(e.value).startswith(message.replace("F", str(f))), str(e.value)


def test_a_missing_thresholds_file_is_named(tmp_path):
    with pytest.raises(ThresholdError, match=r"^thresholds file '.*nope\.toml' does not exist$"):
        load_config(tmp_path / "nope.toml")
    with pytest.raises(ThresholdError, match=r"^thresholds file '.*' is not a file$"):
        load_config(tmp_path)


# -- baselines -------------------------------------------------------------------------


def test_a_baseline_pins_todays_accuracy_and_a_regression_fails_it(tmp_path):
    scenarios = ["free_top_axis1", "parabola"]
    report = run_battery(toy(), scenarios=scenarios, profile="second-order")
    assert not report.passed  # a first-order engine at the second-order profile
    f = tmp_path / "base.toml"
    f.write_text(baseline(report), encoding="utf-8")
    cfg = load_config(f)
    assert cfg.profile == "second-order"
    for r in report.results:
        for fig in r.figures:
            bound = cfg.thresholds.get(f"{r.scenario}.{fig.name}")
            if fig.kind == "order":  # the order less log 2 / log 4 (steps 2^-6 .. 2^-8)
                assert bound == pytest.approx(fig.value - 0.5, abs=5e-3)
            elif fig.threshold is not None:
                pinned = max(2 * fig.value, 2**10 * EPS)  # the margin, above rounding
                assert pinned <= bound <= pinned * (1 + THREE_DIGITS)
    again = run_battery(toy(), scenarios=scenarios, config=cfg)
    assert again.passed, again.to_markdown()
    worse = run_battery(toy("attitude untransposed"), scenarios=["parabola"], config=cfg)
    assert verdicts(worse) == {"parabola": "fail"}


def test_a_baseline_bound_is_rounded_up_to_three_digits_never_below_what_it_pins():
    from mechanics.conformance.thresholds import _rounded_up

    assert _rounded_up(0.001742943685981558) == "0.00175"  # 3 digits round down: up
    assert _rounded_up(0.00174) == "0.00174"
    assert _rounded_up(2.5e-13) == "2.5e-13"
    for x in np.geomspace(1e-15, 1e3, 997):
        assert x <= float(_rounded_up(x)) <= x * (1 + THREE_DIGITS)


def test_a_baseline_writes_an_unmatched_event_as_none_with_its_reason_and_skips_what_did_not_run():
    report = run_battery(toy("restitution squared"), scenarios=["bouncing_ball", "rocket"])
    text = baseline(report, margin=4)
    assert '"bouncing_ball.apex_heights" = "none"  # not measured: found 6 apexes' in text
    assert "# rocket: unsupported, not pinned (the toy has no joints" in text
    assert "each figure at 4 x its measured value" in text
    for bad in (0.5, math.nan, math.inf, "2"):
        with pytest.raises(
            ThresholdError, match=r"^the baseline's margin must be a number >= 1; got "
        ):
            baseline(report, bad)
