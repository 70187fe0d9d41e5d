"""Unit tests of :mod:`mechanics.scenes.result` and :mod:`mechanics.scenes.trajectory` on
hand-built results (issue 16).

Every object here is built by hand (no scene is simulated: ``run_scene`` gets a
hand-built trajectory in place of :func:`simulate`), so each expected number is a
dyadic rational worked out in the comments and compared exactly, and each expected
text is written out as the user reads it.
"""

from __future__ import annotations

import json
import math
from fractions import Fraction

import numpy as np
import pytest

from mechanics._floats import EPS
from mechanics.scenes import result as result_module
from mechanics.scenes import trajectory as trajectory_module
from mechanics.scenes.result import (
    CONSERVED_RTOL,
    CONSERVED_RTOL_INTEGRATED,
    IMPACT_RTOL,
    ORTHOGONALITY_RTOL,
    PENETRATION_RTOL,
    Comparison,
    ConservedReport,
    SceneResult,
    SelfCheck,
    conserved_tolerance,
    run_scene,
    self_checks,
)
from mechanics.scenes.spec import EffectSpec, Scene
from mechanics.scenes.trajectory import (
    Event,
    Trajectory,
    dense_from_segments,
    energy_scale,
    sample_dense,
    sample_segments,
    vectorized,
)

#: one division (rtol / 1e-12 is rounded once, times a power of two exactly)
ONE_ROUNDING = EPS
#: the floor every relative measure divides by when the scale is zero
FLOOR = 1e-300
#: a power of two below the floor: 2**-1000 ≈ 9.3e-302 (normal, exact)
TINY = 2.0**-1000
#: TINY over the floor, correctly rounded from the exact quotient (one IEEE division)
TINY_OVER_FLOOR = float(Fraction(TINY) / Fraction(FLOOR))


def scene(
    *,
    name="demo",
    title="",
    book="",
    effects=(),
    rtol=1e-12,
    atol=1e-12,
) -> Scene:
    return Scene(
        name=name,
        source=f"{name}.toml",
        duration=3.0,
        samples=4,
        method="auto",
        rtol=rtol,
        atol=atol,
        bodies=(),
        effects=tuple(EffectSpec(kind, k, {}) for k, kind in enumerate(effects)),
        title=title,
        book=book,
    )


def trajectory(
    *,
    t=(0.0, 1.0, 2.0, 3.0),
    method="exact: test",
    events=(),
    series=None,
    conserved=None,
    conserved_from=None,
    across=frozenset(),
    **fields,
) -> Trajectory:
    return Trajectory(
        t=np.asarray(t, dtype=float),
        series={} if series is None else series,
        events=list(events),
        method=method,
        state_at=lambda tt: {},
        conserved={} if conserved is None else conserved,
        conserved_from={} if conserved_from is None else conserved_from,
        conserved_across_events=across,
        **fields,
    )


def result_with(conserved=(), comparisons=(), checks=()) -> SceneResult:
    return SceneResult(scene(), trajectory(), list(conserved), list(comparisons), list(checks))


# ---------------------------------------------------------------- the tolerances


def test_tolerances_are_the_documented_multiples_of_eps() -> None:
    # EPS = 2**-52: 1024 EPS = 2**-42, 2**20 EPS = 2**-32, 256 EPS = 2**-44, 64 EPS = 2**-46
    assert CONSERVED_RTOL == 2.0**-42
    assert CONSERVED_RTOL_INTEGRATED == 2.0**-32
    assert PENETRATION_RTOL == 2.0**-44
    assert IMPACT_RTOL == 2.0**-46
    assert ORTHOGONALITY_RTOL == 2.0**-46
    assert result_module.ATTITUDE_SLACK == 16.0
    assert result_module.SPLITTING_ORDER_SLACK == 1.5


# ---------------------------------------------------------------- Comparison


@pytest.mark.parametrize(
    ("simulated", "closed_form", "difference", "relative"),
    [
        (1.5, 1.0, 0.5, 0.5),  # |1.5 − 1| / |1|
        (0.5, 1.0, -0.5, 0.5),  # the difference's sign does not count
        (-1.5, -1.0, -0.5, 0.5),  # nor the closed form's: |−0.5| / |−1|
        (3.0, 4.0, -1.0, 0.25),  # divided by the closed form, not the simulated value
        (-0.75, 0.0, -0.75, 0.75),  # a zero closed form: the absolute difference
    ],
)
def test_a_comparison_is_relative_to_the_closed_form_or_absolute_at_zero(
    simulated, closed_form, difference, relative
) -> None:
    c = Comparison("x", "E1.1", simulated, closed_form, 1.0, "why")
    assert c.difference == difference
    assert c.relative_difference == relative


def test_a_comparison_passes_at_its_tolerance_and_fails_one_ulp_beyond() -> None:
    # relative difference 0.5 exactly (1.5 against 1)
    at = Comparison("x", "E1.1", np.float64(1.5), 1.0, 0.5, "why")
    beyond = Comparison("x", "E1.1", np.float64(1.5), 1.0, math.nextafter(0.5, 0.0), "why")
    assert at.ok is True
    assert beyond.ok is False


def test_a_comparisons_dict_holds_plain_floats_and_its_verdict() -> None:
    c = Comparison("period", "E4.5", np.float64(3.0), np.float64(4.0), np.float64(0.5), "dt")
    d = c.as_dict()
    assert d == {
        "name": "period",
        "book": "E4.5",
        "simulated": 3.0,
        "closed_form": 4.0,
        "difference": -1.0,
        "relative_difference": 0.25,  # |3 − 4| / 4
        "tolerance": 0.5,
        "reason": "dt",
        "ok": True,
    }
    for key in ("simulated", "closed_form", "difference", "relative_difference", "tolerance"):
        assert type(d[key]) is float, key
    assert d["ok"] is True


# ---------------------------------------------------------------- ConservedReport, SelfCheck


def test_a_conserved_quantity_passes_at_its_tolerance_and_fails_one_ulp_beyond() -> None:
    tol = np.float64(2.0**-42)
    assert ConservedReport("E", 1.0, tol, tol).ok is True
    assert ConservedReport("E", 1.0, np.nextafter(tol, 1.0), tol).ok is False


def test_a_conserved_report_holds_its_relative_drift_and_the_time_it_holds_from() -> None:
    c = ConservedReport("E", np.float64(-2.5), np.float64(0.25), np.float64(0.5), np.float64(1.5))
    d = c.as_dict()
    assert d == {
        "name": "E",
        "value": -2.5,
        "relative_drift": 0.25,
        "tolerance": 0.5,
        "since": 1.5,
        "ok": True,
    }
    for key in ("value", "relative_drift", "tolerance", "since"):
        assert type(d[key]) is float, key
    assert d["ok"] is True
    assert ConservedReport("E", 1.0, 0.0, 1.0).since == 0.0


def test_a_self_check_passes_at_its_tolerance_and_fails_one_ulp_beyond() -> None:
    tol = np.float64(2.0**-44)
    assert SelfCheck("gap", tol, tol, "r").ok is True
    assert SelfCheck("gap", np.nextafter(tol, 1.0), tol, "r").ok is False


def test_a_self_checks_dict_holds_plain_floats_and_its_verdict() -> None:
    d = SelfCheck("gap", np.float64(0.75), np.float64(0.5), "gap ≥ 0").as_dict()
    assert d == {
        "name": "gap",
        "violation": 0.75,
        "tolerance": 0.5,
        "reason": "gap ≥ 0",
        "ok": False,
    }
    assert type(d["violation"]) is float
    assert type(d["tolerance"]) is float
    assert d["ok"] is False


# ---------------------------------------------------------------- SceneResult.passed


GOOD_C = ConservedReport("E", 1.0, 0.0, 1.0)
BAD_C = ConservedReport("E", 1.0, 2.0, 1.0)
GOOD_X = Comparison("x", "b", 1.0, 1.0, 0.0, "r")
BAD_X = Comparison("x", "b", 2.0, 1.0, 0.5, "r")
GOOD_S = SelfCheck("s", 0.0, 1.0, "r")
BAD_S = SelfCheck("s", 2.0, 1.0, "r")


@pytest.mark.parametrize(
    ("conserved", "comparisons", "checks", "passed"),
    [
        ((), (), (), True),
        ((GOOD_C,), (GOOD_X,), (GOOD_S,), True),
        ((GOOD_C, BAD_C), (GOOD_X,), (GOOD_S,), False),
        ((GOOD_C,), (BAD_X, GOOD_X), (GOOD_S,), False),
        ((GOOD_C,), (GOOD_X,), (GOOD_S, BAD_S), False),
    ],
)
def test_a_run_passes_only_if_every_conserved_comparison_and_self_check_does(
    conserved, comparisons, checks, passed
) -> None:
    r = result_with(conserved, comparisons, checks)
    assert r.passed is passed
    assert r.summary().endswith("\nPASSED" if passed else "\nFAILED")
    assert r.as_dict()["passed"] is passed


def test_a_result_reports_the_trajectorys_method() -> None:
    r = SceneResult(scene(), trajectory(method="integrated: DOP853"), [])
    assert r.method == "integrated: DOP853"


# ---------------------------------------------------------------- as_dict, to_json


def test_the_results_dict_holds_the_scene_the_events_and_the_samples() -> None:
    events = [
        Event(0.5, "impact", {"pair": "a-b", "speed": np.float64(2.5), "n": np.int64(3)}),
        Event(1.0, "burn_out"),
    ]
    derived = [("regime: axis 3", None, None), ("period", 6.5, 6.25)]
    series = {"x": np.array([0.0, 0.5, 1.0, 1.5]), "E": [1.0, 1.0, 1.0, 1.0]}
    tr = trajectory(method="exact: m", events=events, series=series, derived=derived)
    s = scene(title="T", book="E6.1", effects=("gravity", "impact"))
    r = SceneResult(s, tr, [GOOD_C], [GOOD_X], [GOOD_S])
    d = r.as_dict()
    assert d == {
        "scene": "demo",
        "title": "T",
        "book": "E6.1",
        "source": "demo.toml",
        "effects": ["gravity", "impact"],
        "method": "exact: m",
        "passed": True,
        "events": [
            {"t": 0.5, "kind": "impact", "pair": "a-b", "speed": 2.5, "n": 3},
            {"t": 1.0, "kind": "burn_out"},
        ],
        "conserved": [GOOD_C.as_dict()],
        "comparisons": [GOOD_X.as_dict()],
        "self_checks": [GOOD_S.as_dict()],
        "derived": [
            {"name": "regime: axis 3", "exact": None, "measured": None},
            {"name": "period", "exact": 6.5, "measured": 6.25},
        ],
        "samples": {
            "t": [0.0, 1.0, 2.0, 3.0],
            "x": [0.0, 0.5, 1.0, 1.5],
            "E": [1.0, 1.0, 1.0, 1.0],
        },
    }
    # numpy scalars in an event's detail become Python's (json cannot write an int64)
    assert type(d["events"][0]["speed"]) is float
    assert type(d["events"][0]["n"]) is int
    assert type(d["effects"]) is list
    assert type(d["samples"]["t"]) is list
    assert type(d["samples"]["x"]) is list
    # and the text reads back to the same record
    text = r.to_json()
    assert json.loads(text) == d
    assert text.startswith('{\n "scene": "demo",\n "title": "T",')  # indent = 1


def test_a_result_without_derived_rows_has_an_empty_list() -> None:
    assert result_with().as_dict()["derived"] == []


def test_a_non_finite_number_in_the_result_is_written_as_its_name_and_fails() -> None:
    r = result_with(conserved=[ConservedReport("E", math.nan, 0.0, 1.0)])
    record = json.loads(r.to_json())
    assert record["conserved"][0]["value"] == "nan"
    assert record["conserved"][0]["ok"] is False
    assert record["passed"] is False


# ---------------------------------------------------------------- summary


def pad(text: str, width: int) -> str:
    """``text`` followed by spaces up to ``width`` columns (a left-aligned field)."""
    return text + " " * (width - len(text))


def test_the_summary_of_a_bare_run_says_none_for_the_effects_and_counts_no_events() -> None:
    r = SceneResult(scene(name="quiet"), trajectory(method="exact: uniform motion"), [])
    assert r.summary() == (
        "scene quiet\neffects: none\nmethod: exact: uniform motion\nevents: 0\nPASSED"
    )


def test_the_summary_lists_the_first_four_events_and_marks_more() -> None:
    five = [Event(0.5 * (k + 1), "impact") for k in range(5)]
    r = SceneResult(scene(), trajectory(events=five), [])
    line = r.summary().splitlines()[3]
    assert line == (
        "events: 5  (impact at t=0.5, impact at t=1, impact at t=1.5, impact at t=2, ...)"
    )
    r4 = SceneResult(scene(), trajectory(events=five[:4]), [])
    assert r4.summary().splitlines()[3] == (
        "events: 4  (impact at t=0.5, impact at t=1, impact at t=1.5, impact at t=2)"
    )
    r1 = SceneResult(scene(), trajectory(events=[Event(0.123456789, "burn_out")]), [])
    assert r1.summary().splitlines()[3] == "events: 1  (burn_out at t=0.123457)"


def test_the_summary_shows_each_figure_against_its_bound_and_the_verdict() -> None:
    conserved = [
        ConservedReport("E", 2.5, 0.25, 0.25),  # drift at its bound: ok
        ConservedReport("p_x", -0.125, 0.5, 0.25, since=0.75),  # beyond: FAIL
    ]
    checks = [
        SelfCheck("no interpenetration of a-b", 0.0, 2.0**-44, "gap ≥ 0 at every sample"),
        SelfCheck("impacts dissipate (1 impact)", 0.125, 2.0**-46, "energy lost ≥ 0"),
    ]
    comparisons = [
        Comparison("height", "E6.1", 1.5, 1.0, 0.5, "dt²"),  # rel 0.5 ≤ 0.5: ok
        Comparison("speed", "eq6.41", -3.0, 4.0, 0.25, "rounding"),  # rel 7/4: FAIL
    ]
    derived = [
        ("regime: axis 3", None, None),
        ("period of ω (two flips)", 2 * math.pi, 6.3),
        ("θ min (rad)", None, 0.5),
        ("θ max (rad)", 1.25, None),
    ]
    tr = trajectory(
        method="integrated: DOP853",
        events=[Event(0.5, "impact"), Event(1.5, "burn_out")],
        derived=derived,
    )
    s = scene(title="A demo", book="E6.1", effects=("gravity", "impact"))
    r = SceneResult(s, tr, conserved, comparisons, checks)
    # 2.0**-44 ≈ 5.684e-14 and 2.0**-46 ≈ 1.421e-14 at one decimal: 5.7e-14, 1.4e-14;
    # 2π = 6.283185307179586 at ten significant digits: 6.283185307
    expected = [
        "scene demo: A demo (E6.1)",
        "effects: gravity, impact",
        "method: integrated: DOP853",
        "events: 2  (impact at t=0.5, burn_out at t=1.5)",
        "conserved (relative drift within segments between events):",
        "  ok   " + pad("E", 24) + " +2.5  drift 2.50e-01 ≤ 2.5e-01",
        "  FAIL " + pad("p_x", 24) + " -0.125  drift 5.00e-01 ≤ 2.5e-01 from t=0.75",
        "self-checks (worst relative violation):",
        "  ok   "
        + pad("no interpenetration of a-b", 48)
        + " 0.00e+00 ≤ 5.7e-14  [gap ≥ 0 at every sample]",
        "  FAIL "
        + pad("impacts dissipate (1 impact)", 48)
        + " 1.25e-01 ≤ 1.4e-14  [energy lost ≥ 0]",
        "derived (exact | measured from the motion):",
        "  regime: axis 3",
        "  " + pad("period of ω (two flips)", 40) + " " + " " * 7 + "6.283185307 | 6.3",
        "  " + pad("θ min (rad)", 40) + " " + " " * 17 + "- | 0.5",
        "  " + pad("θ max (rad)", 40) + " " + " " * 14 + "1.25 | -",
        "against the book:",
        "  ok   " + pad("height", 34) + " sim +1.5  book +1  rel 5.00e-01 ≤ 5.0e-01  [E6.1; dt²]",
        "  FAIL "
        + pad("speed", 34)
        + " sim -3  book +4  rel 1.75e+00 ≤ 2.5e-01  [eq6.41; rounding]",
        "FAILED",
    ]
    assert r.summary().splitlines() == expected


def test_the_summary_of_a_scene_with_a_book_but_no_title() -> None:
    r = SceneResult(scene(name="b", book="P6.3"), trajectory(), [])
    assert r.summary().splitlines()[0] == "scene b (P6.3)"
    r = SceneResult(scene(name="b", title="Only a title"), trajectory(), [])
    assert r.summary().splitlines()[0] == "scene b: Only a title"


# ---------------------------------------------------------------- the drift


def test_the_drift_is_the_largest_change_within_a_segment_over_the_scale() -> None:
    t = np.array([0.0, 1.0, 2.0, 3.0])
    v = np.array([4.0, 4.0, 5.0, 5.0])
    # the jump at t = 2 falls between segments: no drift within either
    assert result_module._drift(v, t, [(0.0, 2.0), (2.0, math.inf)], 0.0) == 0.0
    # one segment: (5 − 4) / max |v| = 1/5
    assert result_module._drift(v, t, [(0.0, math.inf)], 0.0) == 1.0 / 5.0
    # a segment ends before its end time: (0, 1.5) holds 4, 4
    assert result_module._drift(v, t, [(0.0, 1.5)], 0.0) == 0.0
    # (0, 2) does not hold the sample at t = 2 either (half-open)
    assert result_module._drift(v, t, [(0.0, 2.0)], 0.0) == 0.0
    # (1, 3) holds 4, 5: 1/5
    assert result_module._drift(v, t, [(1.0, 3.0)], 0.0) == 1.0 / 5.0


def test_the_drift_starts_at_since_and_needs_two_samples_in_a_segment() -> None:
    t = np.array([0.0, 1.0, 2.0, 3.0])
    v = np.array([8.0, 2.0, 3.0, 3.0])
    assert result_module._drift(v, t, [(0.0, math.inf)], 2.0) == 0.0  # 3, 3
    assert result_module._drift(v, t, [(0.0, math.inf)], 1.0) == 1.0 / 8.0  # 2, 3, 3
    # since before a segment's start: the segment's start counts (from t = 2: 3, 3)
    assert result_module._drift(v, t, [(2.0, math.inf)], 1.0) == 0.0
    # exactly two samples are enough: (0, 2) holds 8, 2: 6/8
    assert result_module._drift(v, t, [(0.0, 2.0)], 0.0) == 0.75
    # the worst segment counts: (0, 2) gives 6/8, (2, ∞) 0
    assert result_module._drift(v, t, [(0.0, 2.0), (2.0, math.inf)], 0.0) == 0.75
    assert result_module._drift(v, t, [(2.0, math.inf), (0.0, 2.0)], 0.0) == 0.75


def test_the_drift_is_relative_to_the_larger_of_the_given_scale_and_the_values() -> None:
    t = np.array([0.0, 1.0])
    v = np.array([-1.0, -2.0])
    assert result_module._drift(v, t, [(0.0, math.inf)], 0.0, 8.0) == 1.0 / 8.0
    assert result_module._drift(v, t, [(0.0, math.inf)], 0.0, 0.5) == 1.0 / 2.0  # |−2|
    # all below the floor: 2**-1000 / 1e-300
    tiny = np.array([0.0, TINY])
    assert result_module._drift(tiny, t, [(0.0, math.inf)], 0.0) == TINY_OVER_FLOOR


# ---------------------------------------------------------------- conserved_tolerance


@pytest.mark.parametrize(
    ("method", "rtol", "atol", "expected"),
    [
        ("exact: ballistic flight", 1e-6, 1e-6, 2.0**-42),  # an exact flow ignores rtol
        ("integrated: DOP853", 1e-12, 1e-12, 2.0**-32),
        ("integrated: DOP853", 1e-14, 1e-15, 2.0**-32),  # tighter asks no less
        ("integrated: DOP853", 1e-8, 1e-12, 2.0**-32 * 1e4),
        ("integrated: DOP853", 1e-12, 1e-6, 2.0**-32 * 1e6),
        ("integrated: splitting of order 4", 1e-9, 1e-10, 2.0**-32 * 1e3),
    ],
)
def test_the_conserved_tolerance_grows_with_a_looser_integration_only(
    method, rtol, atol, expected
) -> None:
    got = conserved_tolerance(scene(rtol=rtol, atol=atol), trajectory(method=method))
    assert got == pytest.approx(expected, rel=ONE_ROUNDING, abs=0.0)


# ---------------------------------------------------------------- run_scene


@pytest.fixture
def run(monkeypatch):
    """``run(tr, s)``: run_scene(s) on the hand-built trajectory tr (in place of
    simulate, which must be given the very scene run_scene was given)."""

    def go(tr, s, compare=None):
        def simulate(given):
            assert given is s, "simulate must be given the scene run_scene was given"
            return tr

        monkeypatch.setattr(result_module, "simulate", simulate)
        return run_scene(s, compare)

    return go


def test_run_scene_reports_each_conserved_quantity_against_its_scale(run) -> None:
    # E has a scale of 4 (its scales): drift (1.5 − 1)/4 = 1/8, not 0.5/1.5;
    # p has none: it holds from t = 1 on (2, 3, 3: a change of 1), over its largest
    # magnitude over the whole run, |−9| (the sample before `since` still sets it): 1/9;
    # L has none and is below 1: (0.5 − 0.25)/0.5 = 1/2
    tr = trajectory(
        conserved={
            "E": [1.0, 1.5, 1.0, 1.25],
            "p": [-9.0, 2.0, 3.0, 3.0],
            "L": [0.5, 0.25, 0.25, 0.25],
        },
        conserved_from={"p": 1.0},
        scales={"E": 4.0},
    )
    s = scene()
    r = run(tr, s)
    assert r.trajectory is tr
    assert r.scene is s
    assert r.conserved == [
        ConservedReport("E", 1.25, 0.125, 2.0**-42, 0.0),
        ConservedReport("p", 3.0, 1.0 / 9.0, 2.0**-42, 1.0),
        ConservedReport("L", 0.25, 0.5, 2.0**-42, 0.0),
    ]
    assert type(r.conserved[0].value) is float
    assert r.comparisons == []
    (finite,) = r.self_checks  # only the check that every reported number is finite
    assert (finite.name, finite.ok) == ("every reported number finite", True)


def test_run_scene_checks_a_quantity_kept_across_events_over_the_whole_run(run) -> None:
    # an impact at t = 1.5 splits [0, 1.5), [1.5, ∞) for E (drift 0 in each), but p is
    # kept across it: (4 − 2)/4 over the run
    tr = trajectory(
        events=[Event(1.5, "impact")],
        conserved={"E": [2.0, 2.0, 1.0, 1.0], "p": [2.0, 2.0, 4.0, 4.0]},
        across=frozenset({"p"}),
    )
    r = run(tr, scene())
    assert [(c.name, c.drift) for c in r.conserved] == [("E", 0.0), ("p", 0.5)]


def test_run_scene_gives_an_integrated_run_the_integrated_tolerance(run) -> None:
    tr = trajectory(method="integrated: DOP853", conserved={"E": [1.0, 1.0, 1.0, 1.0]})
    (c,) = run(tr, scene(rtol=1e-10, atol=1e-12)).conserved
    assert c.tolerance == pytest.approx(2.0**-32 * 100, rel=ONE_ROUNDING, abs=0.0)


@pytest.mark.parametrize(
    ("scales", "E", "size"),
    [
        ({"E": 8.0}, [2.0, -1.0, 2.0, 2.0], 8.0),  # the scale given
        ({}, [2.0, -4.0, 2.0, 2.0], 4.0),  # none: the energy's largest magnitude
        ({"E": 0.5}, [2.0, -4.0, 2.0, 2.0], 4.0),  # the larger of the two
    ],
)
def test_a_splittings_energy_is_allowed_its_order_times_its_half_step_drift(
    run, scales, E, size
) -> None:
    # allowed = max(tol, 1.5 · 2ᵖ · drift_half / size); order 4, drift_half 2**-20:
    # 1.5 · 16 · 2**-20 / size = 24 · 2**-20 / size, far above 2**-32
    half = 2.0**-20
    tr = trajectory(
        method="integrated: splitting of order 4",
        series={"E": np.array(E)},
        conserved={"E": E, "p": [1.0, 1.0, 1.0, 1.0]},
        scales=scales,
        splitting={"order": 4, "E_drift_half": half},
    )
    r = run(tr, scene())
    by_name = {c.name: c for c in r.conserved}
    assert by_name["E"].tolerance == 24.0 * half / size
    assert by_name["p"].tolerance == 2.0**-32  # only the energy gets the splitting's
    # the order check sees the drift at h, ptp(E) = 3 or 6, against the half step's
    finite, order = r.self_checks
    assert finite.ok
    assert order.name == "energy error at order 4"
    assert order.violation == 16.0 * half / float(np.ptp(E))


def test_a_splittings_energy_of_zero_size_is_measured_against_the_floor(run) -> None:
    # E ≡ 0, no scale: size 1e-300, allowed 1.5 · 16 · TINY / 1e-300 (24 TINY is exact,
    # the division rounds once)
    tr = trajectory(
        method="integrated: splitting of order 4",
        conserved={"E": [0.0, 0.0, 0.0, 0.0]},
        splitting={"order": 4, "E_drift_half": TINY},
    )
    (c,) = run(tr, scene()).conserved
    assert c.tolerance == float(Fraction(24 * TINY) / Fraction(FLOOR))


def test_a_splittings_energy_keeps_the_conserved_tolerance_when_it_is_larger(run) -> None:
    tr = trajectory(
        method="integrated: splitting of order 2",
        conserved={"E": [1.0, 1.0, 1.0, 1.0]},
        splitting={"order": 2, "E_drift_half": 0.0},
    )
    (c,) = run(tr, scene()).conserved
    assert c.tolerance == 2.0**-32


def test_run_scene_adds_the_comparisons_asked_for(run) -> None:
    tr, s = trajectory(), scene()
    seen = []

    def compare(sc, t):
        seen.append((sc, t))
        return (GOOD_X, BAD_X)

    r = run(tr, s, compare)
    assert seen == [(s, tr)]
    assert r.comparisons == [GOOD_X, BAD_X]
    assert r.passed is False


def test_run_scene_adds_the_self_checks_at_the_runs_tolerance(run) -> None:
    # an integrated attitude is held to the conserved tolerance (2**-32 · 10 here)
    tr = trajectory(method="integrated: DOP853", orthogonality=2.0**-40)
    finite, c = run(tr, scene(rtol=1e-11)).self_checks
    assert finite.ok
    assert c.name == "attitudes orthogonal"
    assert c.tolerance == pytest.approx(2.0**-32 * 10, rel=ONE_ROUNDING, abs=0.0)


# ---------------------------------------------------------------- self_checks


def test_a_run_without_anything_to_check_has_no_self_checks() -> None:
    assert self_checks(trajectory(series={"E": np.array([1.0, 2.0])})) == []


@pytest.mark.parametrize("method", ["exact: torque-free top", "integrated: DOP853"])
def test_attitudes_are_held_to_the_exact_or_the_integrated_tolerance(method) -> None:
    tr = trajectory(method=method, orthogonality=2.0**-50)
    exact = method.startswith("exact")
    assert self_checks(tr, 2.0**-30) == [
        SelfCheck(
            "attitudes orthogonal", 2.0**-50, 2.0**-46 if exact else 2.0**-30, "max |R Rᵀ − I|"
        )
    ]


def test_the_splitting_order_check_compares_the_half_step_drift_with_the_steps() -> None:
    # ptp(E) = 1 over a size max(scale 4, |E| 3) = 4; at tol = 1/4, drift = tol · size:
    # rounding only, ratio 0; one ulp below that tol, ratio 2ᵖ · half / drift
    E = np.array([2.0, 3.0, 2.0])
    split = {"order": 3, "E_drift_half": 2.0**-6}
    tr = trajectory(t=(0.0, 1.0, 2.0), series={"E": E}, splitting=split, scales={"E": 4.0})
    reason = "2ᵖ × drift of E at h/2 over its drift at h (a wrong kick does not shrink)"
    assert self_checks(tr, 0.25) == [SelfCheck("energy error at order 3", 0.0, 1.5, reason)]
    # 2**3 · 2**-6 / 1 = 1/8
    below = math.nextafter(0.25, 0.0)
    assert self_checks(tr, below) == [SelfCheck("energy error at order 3", 0.125, 1.5, reason)]
    # without the scale, the size is max |E| = 3: 1 > ¼ · 3, so the ratio counts at ¼,
    # not at ½ (1 < ½ · 3)
    tr3 = trajectory(t=(0.0, 1.0, 2.0), series={"E": E}, splitting=split)
    assert self_checks(tr3, 0.25)[0].violation == 0.125
    assert self_checks(tr3, 0.5)[0].violation == 0.0


def test_the_splitting_order_check_of_an_energy_below_the_floor() -> None:
    # E = (0, TINY), no scale: size max(TINY, 1e-300) = 1e-300; the drift TINY counts
    # beyond 0.05 · 1e-300 (ratio 2³ · (TINY/8) / TINY = 1), not beyond ¼ · 1e-300
    split = {"order": 3, "E_drift_half": TINY / 8}
    tr = trajectory(t=(0.0, 1.0), series={"E": np.array([0.0, TINY])}, splitting=split)
    assert self_checks(tr, 0.05)[0].violation == 1.0
    assert self_checks(tr, 0.25)[0].violation == 0.0


def test_the_splitting_order_check_needs_the_energy_series() -> None:
    split = {"order": 2, "E_drift_half": 1.0}
    assert self_checks(trajectory(splitting=split)) == []


def test_interpenetration_is_the_deepest_negative_gap_over_the_length_scale() -> None:
    gaps = {
        "a-b": np.array([0.5, -0.25, -0.125, 1.0]),  # 0.25 / 2
        "a-c": np.array([0.5, 0.25]),  # apart: 0
        "b-c": np.array([]),  # never sampled: 0
    }
    tr = trajectory(gaps=gaps, length_scale=2.0)
    reason = "gap ≥ 0 at every sample"
    assert self_checks(tr) == [
        SelfCheck("no interpenetration of a-b", 0.125, 2.0**-44, reason),
        SelfCheck("no interpenetration of a-c", 0.0, 2.0**-44, reason),
        SelfCheck("no interpenetration of b-c", 0.0, 2.0**-44, reason),
    ]


def test_interpenetration_without_a_length_scale_is_measured_against_the_floor() -> None:
    tr = trajectory(gaps={"a-b": np.array([1.0, -TINY])})
    (c,) = self_checks(tr)
    assert c.violation == TINY_OVER_FLOOR


def impact(Tb, Ta, loss, **more) -> Event:
    return Event(
        1.0,
        "impact",
        {"kinetic_energy_before": Tb, "kinetic_energy_after": Ta, "energy_loss": loss, **more},
    )


def test_the_impact_laws_are_checked_at_every_impact() -> None:
    events = [
        # |4 − 3.5 − 0.75| / 4 = 1/16, less 16 × 2**-10 for the attitude: 3/64; it
        # dissipates 0.75/4; its gap 2**-50 over 2**-4 is 2**-46
        impact(4.0, 3.5, 0.75, attitude_defect=2.0**-10, gap=-(2.0**-50), gap_scale=2.0**-4),
        # exact: 0; it gains 0.25 of 2: dissipation violated by 1/8; no gap recorded
        impact(2.0, 2.25, -0.25),
        # a rolling switch, not an impact: no kinetic energy recorded
        Event(2.0, "rolling", {"gap": 1.0, "gap_scale": 1.0}),
    ]
    checks = self_checks(trajectory(events=events))
    assert checks == [
        SelfCheck(
            "impacts at contact (1 impact)",
            2.0**-46,
            2.0**-44,
            "the gap is zero where an impulse acts",
        ),
        SelfCheck(
            "impact energy loss (2 impacts)",
            3.0 / 64.0,
            2.0**-46,
            "T_before − T_after = ½ μ (1 − e²) v_n² (6.41), the impulse's work with friction",
        ),
        SelfCheck(
            "impacts dissipate (2 impacts)",
            0.125,
            2.0**-46,
            "energy lost ≥ 0 at every impact (Newton's e with friction can gain: Kane)",
        ),
    ]


def test_impacts_that_dissipate_are_not_negative_violations() -> None:
    # both lose energy by the formula: −loss/T is −0.25/2 = −1/8 and −0.5/4 = −1/8,
    # reported as no violation (0), not as a negative one
    checks = self_checks(trajectory(events=[impact(2.0, 1.75, 0.25), impact(4.0, 3.5, 0.5)]))
    assert [(c.name, c.violation) for c in checks] == [
        ("impact energy loss (2 impacts)", 0.0),
        ("impacts dissipate (2 impacts)", 0.0),
    ]


def test_impact_measures_of_a_body_at_rest_divide_by_the_floor() -> None:
    # T_before = 0 and a gap scale of 0: each measure divides by 1e-300
    ev = impact(0.0, 0.0, -TINY, gap=TINY, gap_scale=0.0)
    by_name = {c.name: c.violation for c in self_checks(trajectory(events=[ev]))}
    assert by_name == {
        "impacts at contact (1 impact)": TINY_OVER_FLOOR,
        "impact energy loss (1 impact)": TINY_OVER_FLOOR,  # |0 − 0 + TINY| / 1e-300
        "impacts dissipate (1 impact)": TINY_OVER_FLOOR,  # −(−TINY) / 1e-300
    }


def test_momentum_and_angular_momentum_are_checked_across_two_body_impacts_only() -> None:
    q = 2.0**-10
    pair = impact(
        1.0,
        1.0,
        0.0,
        bodies=("a", "b"),
        # |(0, 3q, 4q)| = 5q over a scale 20q: 1/4
        momentum_before=[1.0, 2.0, 2.0],
        momentum_after=[1.0, 2.0 + 3 * q, 2.0 - 4 * q],
        momentum_scale=20 * q,
        # |(q, 0, 0)| over a scale 1: q
        angular_momentum_before=np.array([0.0, 0.0, 1.0]),
        angular_momentum_after=np.array([q, 0.0, 1.0]),
        angular_momentum_scale=1.0,
    )
    # against a joint's bearing the momentum changes: not counted
    pinned = impact(
        1.0,
        1.0,
        0.0,
        bodies=("a", "ground"),
        external_impulse="the pivot",
        momentum_before=[0.0, 0.0, 0.0],
        momentum_after=[9.0, 9.0, 9.0],
        momentum_scale=1.0,
        angular_momentum_before=[0.0, 0.0, 0.0],
        angular_momentum_after=[9.0, 9.0, 9.0],
        angular_momentum_scale=1.0,
    )
    lone = impact(1.0, 1.0, 0.0)  # a body against a fixed one: no pair recorded
    checks = self_checks(trajectory(events=[pair, pinned, lone]))
    tail = checks[-2:]
    assert tail == [
        SelfCheck(
            "momentum across two-body impacts (1 impact)",
            0.25,
            2.0**-46,
            "Σ m v unchanged by the impulses (6.37)",
        ),
        SelfCheck(
            "angular momentum across two-body impacts (1 impact)",
            q,
            2.0**-46,
            "Σ (ρ × m v + Rᵀ L_A) about the contact point unchanged (6.21)",
        ),
    ]
    assert [c.name for c in checks[:-2]] == [
        "impact energy loss (3 impacts)",
        "impacts dissipate (3 impacts)",
    ]


def test_two_body_impacts_with_zero_scales_divide_by_the_floor() -> None:
    # a change of norm 1 over a zero scale: 1 / 1e-300, one IEEE division (a change
    # below the floor would underflow in the norm, whose squares are below 2**-1074)
    over_floor = float(1 / Fraction(FLOOR))
    pair = impact(
        1.0,
        1.0,
        0.0,
        bodies=("a", "b"),
        momentum_before=[0.0, 0.0, 0.0],
        momentum_after=[0.0, 0.0, 1.0],
        momentum_scale=0.0,
        angular_momentum_before=[0.0, 0.0, 0.0],
        angular_momentum_after=[-1.0, 0.0, 0.0],
        angular_momentum_scale=0.0,
    )
    checks = self_checks(trajectory(events=[pair, pair]))
    assert [(c.name, c.violation) for c in checks[-2:]] == [
        ("momentum across two-body impacts (2 impacts)", over_floor),
        ("angular momentum across two-body impacts (2 impacts)", over_floor),
    ]


# ---------------------------------------------------------------- the trajectory


def test_eps_is_float64s() -> None:
    assert trajectory_module.EPS == 2.0**-52
    assert type(trajectory_module.EPS) is float


def test_a_quantity_is_checked_between_events_in_time_order() -> None:
    tr = trajectory(events=[Event(2.0, "impact"), Event(0.5, "impact")])
    assert tr.segments("E") == [(0.0, 0.5), (0.5, 2.0), (2.0, math.inf)]
    assert tr.segments() == [(0.0, 0.5), (0.5, 2.0), (2.0, math.inf)]
    assert trajectory().segments("E") == [(0.0, math.inf)]


def test_a_quantity_the_events_keep_is_checked_over_the_whole_run() -> None:
    tr = trajectory(events=[Event(1.0, "impact")], across=frozenset({"p_x"}))
    assert tr.segments("p_x") == [(0.0, math.inf)]
    assert tr.segments("E") == [(0.0, 1.0), (1.0, math.inf)]


def test_each_event_has_its_own_details() -> None:
    a, b = Event(1.0, "impact"), Event(2.0, "impact")
    a.detail["x"] = 1
    assert b.detail == {}


def pieces():
    """Three pieces [0, 1), [1, 2), [2, 3] whose dense functions say which they are."""
    return [(float(k), float(k + 1), lambda t, k=k: np.array([k, 10.0 * t])) for k in range(3)]


def test_a_dense_function_from_pieces_uses_the_piece_a_time_falls_in() -> None:
    at = dense_from_segments(pieces())
    # before the first piece: the first; at a piece's start: that piece; past the end: the last
    for t, k in [(-1.0, 0), (0.0, 0), (0.5, 0), (1.0, 1), (1.999, 1), (2.0, 2), (3.0, 2), (7.0, 2)]:
        np.testing.assert_array_equal(at(t), [k, 10.0 * t])


def test_vectorized_marks_a_function_and_returns_it() -> None:
    def f(t):
        return t

    assert vectorized(f) is f
    assert f.vectorized is True


def test_sampling_a_dense_function_calls_a_vectorised_one_once() -> None:
    calls = []

    def dense(t):
        calls.append(np.array(t, copy=True))
        return np.stack([t, 2 * t], axis=-1)

    t = np.array([0.0, 0.5, 1.0])
    out = sample_dense(vectorized(dense), t)
    np.testing.assert_array_equal(out, [[0.0, 0.0], [0.5, 1.0], [1.0, 2.0]])
    assert out.dtype == float
    assert len(calls) == 1
    np.testing.assert_array_equal(calls[0], t)


def test_sampling_a_scalar_dense_function_calls_it_per_time() -> None:
    calls = []

    def dense(t):
        calls.append(t)
        return [t, 2 * t]

    out = sample_dense(dense, np.array([0.0, 0.5, 1.0]))
    np.testing.assert_array_equal(out, [[0.0, 0.0], [0.5, 1.0], [1.0, 2.0]])
    assert calls == [0.0, 0.5, 1.0]


def test_sampling_pieces_takes_each_sample_from_its_piece_and_the_end_from_the_last() -> None:
    calls = []

    def piece(k):
        def dense(t):
            calls.append((k, np.array(t, copy=True)))
            return np.stack([np.full_like(t, k), t, -t], axis=-1)

        return vectorized(dense)

    segs = [(0.0, 1.0, piece(0)), (1.0, 2.0, piece(1))]
    t = np.array([0.0, 0.5, 1.0, 1.5, 2.0])
    out = sample_segments(segs, t)
    np.testing.assert_array_equal(
        out, [[0, 0.0, -0.0], [0, 0.5, -0.5], [1, 1.0, -1.0], [1, 1.5, -1.5], [1, 2.0, -2.0]]
    )
    assert [k for k, _ in calls] == [0, 1]  # one call per piece
    np.testing.assert_array_equal(calls[0][1], [0.0, 0.5])
    np.testing.assert_array_equal(calls[1][1], [1.0, 1.5, 2.0])
    # a time before the first piece falls in it; an unvectorised piece is sampled per time
    segs = [(0.0, 1.0, lambda tt: [tt, 1.0]), (1.0, 2.0, lambda tt: [tt, 2.0])]
    np.testing.assert_array_equal(sample_segments(segs, [-0.5, 1.25]), [[-0.5, 1.0], [1.25, 2.0]])


def test_the_energy_scale_is_the_largest_kinetic_plus_the_largest_potential_energy() -> None:
    # T = (1, 3, 2), E = (−1, 0, 0.5): V = E − T = (−2, −3, −1.5); 3 + 3
    assert energy_scale(np.array([1.0, 3.0, 2.0]), [-1.0, 0.0, 0.5]) == 6.0
    # T = (0.5, 0.25), E = (4.5, 0.25): V = (4, 0); 0.5 + 4
    assert energy_scale(np.array([0.5, 0.25]), [4.5, 0.25]) == 4.5
    assert type(energy_scale(np.array([1.0]), [1.0])) is float
