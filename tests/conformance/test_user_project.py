"""Issue 19's "done when": a separate project (made here with ``pytester``) that has
bodycheck installed uses its pytest plugin and profiles and runs the battery on a toy
integrator of its own, the example adapter of docs/conformance.md.

The run is a subprocess (a project of its own: its own interpreter, the plugin through
the installed distribution's entry point); ``PYTHONPATH`` puts this checkout's packages
first, so that the code under test is the code of this tree.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from identities.cli.main import main

from .toys import BROKEN, BUGS, doc_example_source, planted_source

pytest_plugins = ["pytester"]

ROOT = Path(__file__).resolve().parents[2]

PYPROJECT = """
[project]
name = "toy-engine"
version = "0"

[tool.bodycheck.conformance]
profile = "first-order"
"""

TEST_TOY = """
from hypothesis import settings

from mechanics.conformance import conformance_tests
from toy_engine import SemiImplicitEuler

# no thresholds of its own: the profile comes from pyproject.toml
test_toy = conformance_tests(SemiImplicitEuler())


def test_the_bodycheck_profile_is_loaded():
    name = getattr(settings, "get_current_profile_name", lambda: settings._current_profile)()
    assert name == "bodycheck-ci"
"""


TEST_RANDOM = """
from hypothesis import Phase, given, settings

from mechanics import strategies as ms
from mechanics.conformance import run_battery
from toy_engine import SemiImplicitEuler
from toy_attitude_untransposed import SemiImplicitEuler as Active


@settings(max_examples=3, deadline=None)
@given(ms.scenarios(kinds=["parabola", "bouncing_ball"]))
def test_the_toy_on_drawn_scenarios(scenario):
    report = run_battery(SemiImplicitEuler(), scenarios=[scenario], profile="first-order")
    assert report.passed, report.to_markdown()


# every draw fails alike: no shrinking (it would take seconds to reach the same verdict)
@settings(max_examples=3, deadline=None, phases=[Phase.generate])
@given(ms.scenarios(kinds=["parabola"]))
def test_an_active_attitude_on_drawn_scenarios(scenario):
    report = run_battery(Active(), scenarios=[scenario], profile="first-order")
    assert report.passed, report.to_markdown()
"""


def _module(bug: str) -> str:
    return "toy_" + bug.replace(" ", "_").replace("-", "_")


def _bug_tests() -> str:
    """One parametrised test per planted bug, over the scenarios where its law acts."""
    lines = ["from mechanics.conformance import conformance_tests", ""]
    for bug, scenarios in BROKEN.items():
        m = _module(bug)
        lines += [
            f"from {m} import SemiImplicitEuler as {m}",
            f"test_{m} = conformance_tests({m}(), scenarios={scenarios!r})",
        ]
    return "\n".join(lines) + "\n"


@pytest.fixture
def project(pytester, monkeypatch):
    pytester.makepyfile(
        toy_engine=doc_example_source(),
        test_toy=TEST_TOY,
        test_bugs=_bug_tests(),
        test_random=TEST_RANDOM,
        **{_module(bug): planted_source(bug) for bug in BUGS},
    )
    (pytester.path / "pyproject.toml").write_text(PYPROJECT, encoding="utf-8")
    monkeypatch.setenv("PYTHONPATH", str(ROOT))
    monkeypatch.delenv("PYTEST_ADDOPTS", raising=False)
    return pytester


def test_a_separate_project_passes_a_correct_first_order_engine_and_fails_each_planted_bug(
    project,
):
    """Issue 29's outside trial: at the profile its pyproject.toml names, with no
    threshold of its own, the doc's correct first-order toy passes every scenario it
    supports, and each of four bugs planted in it fails where its law acts; a @given test
    over ms.scenarios() passes the toy and fails the active attitude."""
    result = project.runpytest_subprocess(
        "--bodycheck-profile", "bodycheck-ci", "-p", "no:randomly", "-rfs", "-v"
    )
    result.assert_outcomes(passed=8, failed=5, skipped=9)
    result.stdout.fnmatch_lines_random(
        [
            "bodycheck: hypothesis profile 'bodycheck-ci' (from --bodycheck-profile)",
            *(f"*test_toy[[]{s}[]] PASSED*" for s in SUPPORTED),
            "*test_the_bodycheck_profile_is_loaded PASSED*",
            "*test_the_toy_on_drawn_scenarios PASSED*",
            "*test_an_active_attitude_on_drawn_scenarios FAILED*",
            "*scenario=Scenario(name='parabola',*",  # hypothesis' falsifying example
            *(
                f"*test_{_module(bug)}[[]{scenarios[0]}[]] FAILED*"
                for bug, scenarios in BROKEN.items()
            ),
            "SKIPPED [[]1[]] test_toy.py:*: toy semi-implicit Euler does not support heavy_top: the toy has "
            "no joints, no thrust and no body-body contacts",
            "SKIPPED*two_body_impact*",
            "SKIPPED*rocket*",
            "SKIPPED*box_landing_flat: the toy's ground is smooth and meets spheres only",
            "SKIPPED*sliding_stop: the toy's ground is smooth and meets spheres only",
            "SKIPPED*incline_rolling: the toy's ground is smooth and meets spheres only",
            "SKIPPED*newtons_cradle: the toy has no joints, no thrust and no body-body contacts",
            "SKIPPED*oblique_impact_sticks: the toy's ground is smooth and meets spheres only",
            "SKIPPED*oblique_impact_slips: the toy's ground is smooth and meets spheres only",
            "*scenario free_top_axis1: attitude 0.449 violates threshold <= 0.25; * order "
            "0.00142 violates threshold >= 0.5. The error does not shrink with the step "
            "(order 0.0014): a law is wrong, not the step size. Angular momentum drifts "
            "(L_drift 0.358) while energy holds (E_drift 0.00374): the rotational dynamics "
            "are wrong; check the gyroscopic term *",
            "*scenario free_top_axis3: * Angular momentum drifts (L_drift 0.109) while energy "
            "holds (E_drift 0): the rotational dynamics are wrong*",
            "*scenario bouncing_ball: * apex_heights inf violates threshold <= 0.25 (found 6 "
            "apexes (v·n falling through 0) in the samples; expected 3: heights 0.501, 0.192, "
            "0.0737, ... m at 0.839, 1.37, 1.69, ... s, exact 0.816, 0.522, 0.334 m at 0.918, "
            "1.65, 2.24 s)* e_m = 0.586 * ≈ e² = 0.64: restitution applied twice or squared.",
            "*scenario parabola: attitude 1.66 violates * its transpose matches the exact one "
            "to 3.55e-15: the engine returns its active (body-to-world) matrix*",
        ]
    )


#: the scenarios the doc's toy supports
SUPPORTED = ["free_top_axis1", "free_top_axis3", "free_top_near_separatrix", "parabola",
             "bouncing_ball", "bounce_to_rest"]  # fmt: skip


def test_the_command_gives_the_same_verdicts_from_the_same_pyproject(project, monkeypatch, capsys):
    """``bodycheck conform`` in the project's folder reads the same pyproject.toml (run
    in process: the command's code is the same, without five interpreters' start-up)."""
    monkeypatch.chdir(project.path)
    for module, scenarios, code in [
        ("toy_engine", SUPPORTED, 0),
        *((_module(bug), s, 1) for bug, s in BROKEN.items()),
    ]:
        args = ["conform", f"{module}.py:SemiImplicitEuler", "--json", "-", "--scenario"]
        assert main([*args, *scenarios]) == code, module
        report = json.loads(capsys.readouterr().out)
        assert report["profile"] == "first-order"
        assert report["config"] == f"{project.path / 'pyproject.toml'} [tool.bodycheck.conformance]"
        want = "pass" if code == 0 else "fail"
        got = {r["scenario"]: r["status"] for r in report["scenarios"]}
        assert got == dict.fromkeys(scenarios, want), module


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
