"""``conformance_tests``: the battery as a pytest parametrisation, checked in this process
(tests/conformance/test_user_project.py runs it in a user's project; mutmut cannot run
that one, so these are what hold the parametrisation's promises under mutation testing)."""

from __future__ import annotations

import dataclasses

import pytest

from mechanics.conformance import conformance_tests
from mechanics.conformance.adapters import ExactAdapter
from mechanics.conformance.battery import DEFAULT_THRESHOLDS
from mechanics.conformance.scenarios import SCENARIOS

#: a position error far beyond the battery's default threshold (2^-10, relative)
OFFSET = 0.5


def _marks(test):
    (mark,) = [m for m in test.pytestmark if m.name == "parametrize"]
    return mark


class _Unsupported(ExactAdapter):
    name = "cannot"

    def supports(self, scenario):
        return "no such joint here"


class _Raising(ExactAdapter):
    name = "raising"

    def run(self, scenario, step):
        raise RuntimeError("engine exploded")


class _Offset(ExactAdapter):
    name = "offset"

    def run(self, scenario, step):
        tr = super().run(scenario, step)
        return dataclasses.replace(tr, position=tr.position + OFFSET)


class _Nameless:
    takes_step = False
    supports = ExactAdapter.supports
    run = ExactAdapter.run


def _params(mark) -> list[tuple[str, str, list]]:
    """(value, id, marks) per parameter of a parametrize mark."""
    assert mark.args[0] == "scenario_name"
    assert mark.kwargs == {}
    return [(p.values[0], p.id, list(p.marks)) for p in mark.args[1]]


def test_one_test_per_scenario_named_by_it_and_every_scenario_by_default():
    names = list(SCENARIOS)
    assert _params(_marks(conformance_tests(ExactAdapter()))) == [(n, n, []) for n in names]
    chosen = _marks(conformance_tests(ExactAdapter(), scenarios=["parabola"]))
    assert _params(chosen) == [("parabola", "parabola", [])]


def test_an_unsupported_scenario_is_marked_skip_at_collection_so_pytest_names_the_users_test():
    ((value, ident, marks),) = _params(
        _marks(conformance_tests(_Unsupported(), scenarios=["rocket"]))
    )
    assert (value, ident) == ("rocket", "rocket")
    assert [m.name for m in marks] == ["skip"]
    assert marks[0].kwargs == {"reason": "cannot does not support rocket: no such joint here"}
    # an adapter whose supports() raises is not marked: the run reports the error
    raising = type("R", (ExactAdapter,), {"supports": lambda self, s: 1 / 0})()
    assert _params(_marks(conformance_tests(raising, scenarios=["rocket"]))) == [
        ("rocket", "rocket", [])
    ]


def test_the_exact_adapter_passes_and_the_test_says_what_it_runs():
    test = conformance_tests(ExactAdapter(), scenarios=["parabola"])
    assert test("parabola") is None
    assert test.__doc__ == "The conformance battery on exact (closed forms), one scenario per test."
    assert test.__name__ == "test_conformance"


def test_an_unsupported_scenario_is_skipped_with_the_adapters_reason():
    test = conformance_tests(_Unsupported(), scenarios=["parabola"])
    with pytest.raises(pytest.skip.Exception) as info:
        test("parabola")
    assert str(info.value) == "cannot does not support parabola: no such joint here"


def test_an_adapter_that_raises_fails_naming_the_scenario_and_the_error():
    test = conformance_tests(_Raising(), scenarios=["parabola"])
    with pytest.raises(pytest.fail.Exception) as info:
        test("parabola")
    msg = str(info.value)
    assert msg.startswith("raising, scenario parabola: adapter error: ")
    assert "RuntimeError" in msg
    assert "engine exploded" in msg
    assert info.value.pytrace is False


def test_a_wrong_answer_fails_with_the_figure_and_its_threshold():
    test = conformance_tests(_Offset(), scenarios=["parabola"])
    with pytest.raises(pytest.fail.Exception) as info:
        test("parabola")
    msg = str(info.value)
    assert msg.startswith("offset, scenario parabola: ")
    assert " violates threshold <= " in msg  # the figure, its value and the threshold
    assert info.value.pytrace is False


def test_an_adapter_without_a_name_is_called_by_its_class():
    test = conformance_tests(_Nameless(), scenarios=["parabola"])
    assert test.__doc__ == "The conformance battery on _Nameless, one scenario per test."


def test_thresholds_and_scenario_names_are_checked_when_the_tests_are_made():
    with pytest.raises(ValueError, match="no-such-scenario"):
        conformance_tests(ExactAdapter(), scenarios=["no-such-scenario"])
    with pytest.raises(ValueError, match="no-such-figure"):
        conformance_tests(ExactAdapter(), thresholds={"no-such-figure": 1.0})


class _OnlyParabola(ExactAdapter):
    """Runs the parabola only: any other scenario is unsupported."""

    name = "parabola-only"

    def supports(self, scenario):
        return None if scenario.name == "parabola" else "only the parabola here"


def _lob():
    """The parabola under another name: a user's own Scenario, not in SCENARIOS."""
    return dataclasses.replace(SCENARIOS["parabola"], name="lob")


def test_a_users_own_scenario_object_is_taken_as_it_is_not_looked_up_by_name():
    lob = _lob()
    test = conformance_tests(ExactAdapter(), scenarios=[lob])
    assert _params(_marks(test)) == [("lob", "lob", [])]
    assert test("lob") is None  # get_scenario("lob") would raise: the battery has no lob


def test_each_test_runs_its_own_scenario_only():
    # the adapter supports the parabola alone: were the test to run another scenario
    # (the first of the list, or the whole battery), it would be skipped
    test = conformance_tests(_OnlyParabola(), scenarios=["free_top_axis1", "parabola"])
    assert test("parabola") is None
    with pytest.raises(pytest.skip.Exception) as info:
        test("free_top_axis1")
    assert str(info.value) == (
        "parabola-only does not support free_top_axis1: only the parabola here"
    )


def test_the_users_thresholds_reach_the_battery_including_keys_of_their_own_scenarios():
    # None reports without checking: with every figure unchecked, the offset parabola
    # (0.5 m off, far beyond the default bounds) passes; with the defaults it fails
    lob = _lob()
    unchecked = dict.fromkeys(DEFAULT_THRESHOLDS)
    unchecked["lob.apex_height"] = None  # a key only the user's scenario makes known
    test = conformance_tests(_Offset(), thresholds=unchecked, scenarios=[lob])
    assert test("lob") is None
    with pytest.raises(pytest.fail.Exception):
        conformance_tests(_Offset(), scenarios=[lob])("lob")


def test_the_package_gives_conformance_tests_lazily_and_refuses_other_names():
    # mechanics.conformance imports pytest only when conformance_tests is asked for: its
    # module __getattr__ hands it out (called here at test time, not at import)
    import mechanics.conformance as conf
    import mechanics.conformance.adapters as adapters
    from mechanics.conformance import parametrize
    from mechanics.conformance.adapters import reference as reference_adapters

    assert conf.__getattr__("conformance_tests") is parametrize.conformance_tests
    with pytest.raises(AttributeError) as info:
        conf.__getattr__("conformance_test")
    assert str(info.value) == ("module 'mechanics.conformance' has no attribute 'conformance_test'")
    assert adapters.__getattr__("ExactAdapter") is reference_adapters.ExactAdapter
    assert adapters.__getattr__("SceneEngineAdapter") is reference_adapters.SceneEngineAdapter
    with pytest.raises(AttributeError) as info:
        adapters.__getattr__("MuJoCoAdapter")
    assert str(info.value) == (
        "module 'mechanics.conformance.adapters' has no attribute 'MuJoCoAdapter'"
    )
