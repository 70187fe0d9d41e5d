"""Issue 19's "done when": a separate project (made here with ``pytester``) that has
bodycheck installed uses its pytest plugin and profiles and runs the battery on a toy
integrator of its own, the example adapter of docs/conformance.md.

The run is a subprocess (a project of its own: its own interpreter, the plugin through
the installed distribution's entry point); ``PYTHONPATH`` puts this checkout's packages
first, so that the code under test is the code of this tree.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from .toys import doc_example_source

pytest_plugins = ["pytester"]

ROOT = Path(__file__).resolve().parents[2]

TEST_TOY = """
from hypothesis import settings

from mechanics.conformance import conformance_tests
from toy_engine import SemiImplicitEuler

# loose bounds for a first-order engine at 2^-8 s, and a lower bound on its order
THRESHOLDS = {
    "position": 2.0**-6, "attitude": 2.0**-6, "omega": 2.0**-6, "apex_height": 2.0**-6,
    "E_drift": 2.0**-6, "L_drift": 2.0**-6, "order": 0.9,
}

test_toy = conformance_tests(SemiImplicitEuler(), thresholds=THRESHOLDS)


def test_the_bodycheck_profile_is_loaded():
    name = getattr(settings, "get_current_profile_name", lambda: settings._current_profile)()
    assert name == "bodycheck-ci"
"""


@pytest.fixture
def project(pytester, monkeypatch):
    pytester.makepyfile(toy_engine=doc_example_source(), test_toy=TEST_TOY)
    monkeypatch.setenv("PYTHONPATH", str(ROOT))
    monkeypatch.delenv("PYTEST_ADDOPTS", raising=False)
    return pytester


def test_a_separate_project_runs_the_battery_on_its_own_toy_integrator(project):
    result = project.runpytest_subprocess(
        "--bodycheck-profile", "bodycheck-ci", "-p", "no:randomly", "-rfs", "-v"
    )
    result.assert_outcomes(passed=4, failed=2, skipped=3)
    result.stdout.fnmatch_lines_random(
        [
            "bodycheck: hypothesis profile 'bodycheck-ci' (from --bodycheck-profile)",
            "*test_toy[[]free_top_axis1[]] PASSED*",
            "*test_toy[[]free_top_axis3[]] PASSED*",
            "*test_toy[[]parabola[]] PASSED*",
            "*test_the_bodycheck_profile_is_loaded PASSED*",
            "*test_toy[[]free_top_near_separatrix[]] FAILED*",
            "*test_toy[[]bouncing_ball[]] FAILED*",
            "toy semi-implicit Euler, scenario free_top_near_separatrix: attitude 0.24 "
            "violates threshold <= 0.0156; E_drift 0.0223 violates threshold <= 0.0156",
            "toy semi-implicit Euler, scenario bouncing_ball: *; order 0.154 violates "
            "threshold >= 0.9",
            "FAILED test_toy.py::test_toy[[]free_top_near_separatrix[]] - Failed: toy*",
            "SKIPPED [[]1[]] *toy semi-implicit Euler does not support heavy_top: the toy has "
            "no joints, no thrust and no body-body contacts",
            "SKIPPED*two_body_impact*",
            "SKIPPED*rocket*",
        ]
    )


def test_the_parametrisation_checks_thresholds_when_the_module_is_collected(project):
    project.makepyfile(
        test_bad="""
        from mechanics.conformance import conformance_tests
        from toy_engine import SemiImplicitEuler

        test_bad = conformance_tests(SemiImplicitEuler(), thresholds={"velocty": 1e-3})
        """
    )
    result = project.runpytest_subprocess("test_bad.py")
    result.assert_outcomes(errors=1)
    result.stdout.fnmatch_lines(["*ThresholdError: unknown threshold key(s) 'velocty'*"])
