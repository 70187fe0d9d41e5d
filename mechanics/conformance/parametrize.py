"""The battery as a pytest parametrisation a user drops into their suite.

>>> from mechanics.conformance.adapters import ExactAdapter
>>> test_exact = conformance_tests(ExactAdapter(), scenarios=["parabola"])
>>> test_exact("parabola")  # passes: returns None

In a test module::

    from mechanics.conformance import conformance_tests
    from my_engine.bodycheck_adapter import MyAdapter

    test_my_engine = conformance_tests(MyAdapter(), thresholds={"velocity": 1e-4})

gives one test per scenario (ids = the scenario names): it passes, fails with the
figure, its value and the threshold, fails with the adapter's exception (type and
message) or with what the protocol refused in its answer, or is skipped with the
adapter's reason when the adapter does not support the scenario (asked at collection,
so that pytest reports the skip at the user's test).  Thresholds and
scenario names are checked when the module is collected.  pytest is imported here only
when :func:`conformance_tests` is called (not by :mod:`mechanics.conformance`).
"""

from __future__ import annotations

import inspect
import types

from .battery import run_battery
from .protocol import Scenario
from .scenarios import SCENARIOS, check_scenario, get_scenario
from .thresholds import Config, find_config, get_profile, load_config, resolve_thresholds

__all__ = ["conformance_tests"]


def conformance_tests(adapter, *, thresholds=None, scenarios=None, profile=None, config=None):
    """A test function parametrised over the battery's scenarios for ``adapter``.

    Parameters
    ----------
    adapter : Adapter
        The engine under test (an instance).
    thresholds : dict, optional
        As for :func:`~mechanics.conformance.battery.run_battery`; checked now.
    scenarios : iterable of str or Scenario, optional
        Default: all of :data:`~mechanics.conformance.scenarios.SCENARIOS`.
    profile : str, optional
        What the engine claims (``"first-order"``, ``"second-order"``, ``"high-order"``,
        ``"exact"``; :data:`~mechanics.conformance.thresholds.PROFILES`), as for
        :func:`~mechanics.conformance.battery.run_battery`; checked now.
    config : path or False, optional
        A thresholds file (:func:`~mechanics.conformance.thresholds.load_config`); by
        default the nearest ``pyproject.toml`` from the working directory up (its table
        ``[tool.bodycheck.conformance]``, if it has one), as ``bodycheck conform``
        reads it; ``False``: none.  Read and checked now.

    Returns
    -------
    function
        ``test(scenario_name)`` decorated with ``pytest.mark.parametrize``; assign it
        to a module-level name starting with ``test``.

    Raises
    ------
    UnknownScenarioError
        Where a scenario is unknown (by name or kind).
    ScenarioRangeError
        Where a user's scenario is outside its valid range.
    ThresholdError
        Where a threshold or the profile is refused, or the thresholds file is (missing,
        not TOML, an unknown key or value).
    ImportError
        Where pytest is not installed.

    Examples
    --------
    One parametrised test; run by hand it passes (returns None):

    >>> from mechanics.conformance.adapters import ExactAdapter
    >>> test_exact = conformance_tests(ExactAdapter(), scenarios=["parabola"], config=False)
    >>> [m.name for m in test_exact.pytestmark], test_exact("parabola")
    (['parametrize'], None)
    """
    import pytest

    chosen = [
        x if isinstance(x, Scenario) else get_scenario(x)
        for x in (SCENARIOS if scenarios is None else scenarios)
    ]
    for s in chosen:
        if s not in SCENARIOS.values():  # a user's variant: inside its valid range?
            check_scenario(s)
    th = resolve_thresholds(thresholds, chosen)
    if profile is not None:
        get_profile(profile)
    if config is False:
        cfg = Config()
    else:
        path = find_config() if config is None else config
        cfg = Config() if path is None else load_config(path, chosen)
    by_name = {s.name: s for s in chosen}
    label = getattr(adapter, "name", type(adapter).__name__)

    def param(s):
        """The scenario as a parameter, marked skip where the adapter says it cannot run
        it: a mark is reported at the user's test (a skip raised here would name this
        file).  An adapter whose supports() raises is left to the run, which reports it."""
        try:
            why = adapter.supports(s)
        except Exception:
            why = None
        if not why:
            return pytest.param(s.name, id=s.name)
        skip = pytest.mark.skip(reason=f"{label} does not support {s.name}: {why}")
        return pytest.param(s.name, id=s.name, marks=skip)

    def check(scenario_name):
        one = [by_name[scenario_name]]
        report = run_battery(adapter, scenarios=one, thresholds=th, profile=profile, config=cfg)
        r = report.results[0]
        if r.status == "unsupported":  # supports() changed its mind between collection and run
            pytest.skip(f"{label} does not support {scenario_name}: {r.message}")
        if r.status == "error":
            pytest.fail(f"{label}, scenario {scenario_name}: adapter error: {r.message}", False)
        if r.status == "fail":
            pytest.fail(f"{label}, scenario {scenario_name}: {r.message}", pytrace=False)

    def test_conformance(scenario_name):
        check(scenario_name)

    # pytest places a test (its skips, its failures) where its function's code is: the
    # code of this one-line function is placed at the line that called conformance_tests,
    # in the user's test module, not here (its body, check, stays here)
    caller = inspect.stack(0)[1]
    code = test_conformance.__code__.replace(
        co_filename=caller.filename, co_firstlineno=caller.lineno
    )
    test_conformance = types.FunctionType(
        code, test_conformance.__globals__, "test_conformance", None, test_conformance.__closure__
    )
    test_conformance.__doc__ = f"The conformance battery on {label}, one scenario per test."
    return pytest.mark.parametrize("scenario_name", [param(s) for s in chosen])(test_conformance)
