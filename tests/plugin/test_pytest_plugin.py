"""The pytest plugin (:mod:`mechanics.pytest_plugin`), proved from outside with ``pytester``.

Each test writes a small project into a temporary directory and runs pytest on it.  Most
runs are in-process (fast; the plugin comes through its entry point there too, since
pytest loads ``pytest11`` entry points on every run); the ones about installation run
in a subprocess.  An in-process run can load a hypothesis profile into this process, so
every test here restores the profile that was loaded before it.
"""

from __future__ import annotations

import json
import re
import subprocess
import sys
from importlib.metadata import version

import numpy as np
import pytest
from hypothesis import settings

pytest_plugins = ["pytester"]

UNKNOWN_PROFILE = (
    "ERROR: {source} is {name!r}, which is not a bodycheck profile; choose one of "
    "bodycheck-ci, bodycheck-dev, bodycheck-explore"
)

# A test that prints the hypothesis profile it runs under (the run passes `-s`).
PRINT_PROFILE = """
from hypothesis import settings

def test_profile():
    s = settings.default
    name = getattr(settings, "get_current_profile_name", lambda: settings._current_profile)()
    print("PROFILE", name, s.max_examples, s.derandomize)
"""


def current_profile() -> str:
    """The loaded profile's name (hypothesis < 6.1xx has no get_current_profile_name:
    `make test-oldest` runs 6.92, where the class attribute holds it)."""
    get = getattr(settings, "get_current_profile_name", None)
    return get() if get is not None else settings._current_profile


@pytest.fixture(autouse=True)
def _restore_hypothesis_profile():
    name = current_profile()
    yield
    settings.load_profile(name)


# -- hypothesis profiles -------------------------------------------------------------


@pytest.mark.parametrize(
    ("name", "max_examples", "derandomize"),
    [
        ("bodycheck-ci", 100, True),
        ("bodycheck-dev", 100, False),
        ("bodycheck-explore", 1000, False),
    ],
)
def test_profile_option_loads_the_named_profile(pytester, name, max_examples, derandomize):
    pytester.makepyfile(
        f"""
        from hypothesis import HealthCheck, settings

        def test_profile():
            s = settings.default
            assert getattr(settings, "get_current_profile_name", lambda: settings._current_profile)() == {name!r}
            assert s.max_examples == {max_examples}
            assert s.derandomize is {derandomize}
            assert s.deadline is None
            assert HealthCheck.too_slow in s.suppress_health_check
        """
    )
    result = pytester.runpytest("--bodycheck-profile", name)
    result.assert_outcomes(passed=1)
    result.stdout.fnmatch_lines(
        [f"bodycheck: hypothesis profile {name!r} (from --bodycheck-profile)"]
    )


def test_without_the_option_the_projects_own_settings_stand(pytester):
    pytester.makeconftest(
        """
        from hypothesis import settings

        settings.register_profile("mine", max_examples=7, deadline=1234)
        settings.load_profile("mine")
        """
    )
    pytester.makepyfile(
        """
        from hypothesis import settings

        def test_settings_untouched():
            assert getattr(settings, "get_current_profile_name", lambda: settings._current_profile)() == "mine"
            assert settings.default.max_examples == 7
            assert settings.default.deadline.total_seconds() == 1.234
            # registered alongside, so hypothesis' own option can name them
            assert settings.get_profile("bodycheck-ci").derandomize
        """
    )
    result = pytester.runpytest()
    result.assert_outcomes(passed=1)
    result.stdout.no_fnmatch_line("*bodycheck: hypothesis profile*")


def test_ini_setting_loads_a_profile_and_the_command_line_wins(pytester):
    pytester.makeini("[pytest]\nbodycheck_profile = bodycheck-explore\n")
    pytester.makepyfile(PRINT_PROFILE)
    # first, while this process' own profile is loaded (the runs are in-process)
    unset = pytester.runpytest("-s", "-o", "bodycheck_profile=")
    unset.assert_outcomes(passed=1)
    unset.stdout.fnmatch_lines([f"*PROFILE {current_profile()} *"])
    unset.stdout.no_fnmatch_line("bodycheck: hypothesis profile*")
    from_ini = pytester.runpytest("-s")
    from_ini.assert_outcomes(passed=1)
    from_ini.stdout.fnmatch_lines(
        [
            "bodycheck: hypothesis profile 'bodycheck-explore' (from the ini setting bodycheck_profile)",
            "*PROFILE bodycheck-explore 1000 False",
        ]
    )
    ours = pytester.runpytest("-s", "--bodycheck-profile=bodycheck-ci")
    ours.assert_outcomes(passed=1)
    ours.stdout.fnmatch_lines(["*PROFILE bodycheck-ci 100 True"])
    theirs = pytester.runpytest("-s", "--hypothesis-profile=bodycheck-dev")
    theirs.assert_outcomes(passed=1)
    theirs.stdout.fnmatch_lines(["*PROFILE bodycheck-dev 100 False"])
    theirs.stdout.no_fnmatch_line("bodycheck: hypothesis profile*")


@pytest.mark.parametrize(
    ("args", "ini", "message"),
    [
        (
            ["--bodycheck-profile=bodycheck-fast"],
            "",
            UNKNOWN_PROFILE.format(source="--bodycheck-profile", name="bodycheck-fast"),
        ),
        (
            ["--bodycheck-profile="],
            "bodycheck_profile = bodycheck-ci",
            UNKNOWN_PROFILE.format(source="--bodycheck-profile", name=""),
        ),
        (
            [],
            "bodycheck_profile = ci",
            UNKNOWN_PROFILE.format(source="the ini setting bodycheck_profile", name="ci"),
        ),
        (
            ["--hypothesis-profile=default"],
            "bodycheck_profile = bodycheck-CI",
            UNKNOWN_PROFILE.format(source="the ini setting bodycheck_profile", name="bodycheck-CI"),
        ),
        (
            ["--bodycheck-profile=bodycheck-ci", "--hypothesis-profile=default"],
            "",
            "ERROR: --bodycheck-profile='bodycheck-ci' and --hypothesis-profile='default' "
            "were both given; give one",
        ),
        (
            ["--bodycheck-seed=-1"],
            "",
            "*error: argument --bodycheck-seed: '-1' is not an integer >= 0",
        ),
        (
            ["--bodycheck-seed=0x2"],
            "",
            "*error: argument --bodycheck-seed: '0x2' is not an integer >= 0",
        ),
    ],
)
def test_bad_option_is_a_usage_error_naming_the_value(pytester, args, ini, message):
    pytester.makeini(f"[pytest]\n{ini}\n")
    pytester.makepyfile(PRINT_PROFILE)
    result = pytester.runpytest(*args)
    assert result.ret == pytest.ExitCode.USAGE_ERROR
    result.stderr.fnmatch_lines([message])
    result.stdout.no_fnmatch_line("*PROFILE*")


# -- bodycheck_rng -------------------------------------------------------------------

RNG_TESTS = """
import pytest

def test_one(bodycheck_rng):
    print("DRAW one", bodycheck_rng.integers(2**62, size=4).tolist())

@pytest.mark.parametrize("k", [1, 2])
def test_two(bodycheck_rng, k):
    print(f"DRAW two{k}", bodycheck_rng.integers(2**62, size=4).tolist())
"""


def _draws(result) -> dict[str, list[int]]:
    result.assert_outcomes(passed=3)
    text = result.stdout.str()
    draws = dict(re.findall(r"DRAW (\w+) (\[[^]]*\])", text))
    assert sorted(draws) == ["one", "two1", "two2"], text
    return {k: json.loads(v) for k, v in draws.items()}


def test_bodycheck_rng_is_seeded_per_test_and_by_the_seed_option(pytester):
    pytester.makepyfile(RNG_TESTS)
    first = _draws(pytester.runpytest("-s"))  # pytest-randomly shuffles the tests
    again = _draws(pytester.runpytest("-s", "-p", "no:randomly"))
    assert first == again, "the same test draws the same numbers on every run, in any order"
    assert len({tuple(d) for d in first.values()}) == 3, "each test, each parametrisation, its own"
    seeded = _draws(pytester.runpytest("-s", "--bodycheck-seed=1"))
    assert all(seeded[k] != first[k] for k in first), "--bodycheck-seed changes every stream"


def test_bodycheck_rng_prints_a_seed_that_reproduces_it(pytester):
    pytester.makepyfile(
        """
        def test_one(bodycheck_rng):
            print("DRAW", bodycheck_rng.integers(2**62, size=4).tolist())
            assert False
        """
    )
    result = pytester.runpytest("--bodycheck-seed=5")
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines(
        [
            "*Captured stdout setup*",
            "bodycheck_rng: numpy.random.default_rng(*) (--bodycheck-seed=5)",
            "*Captured stdout call*",
            "DRAW *",
        ]
    )
    text = result.stdout.str()
    seed = int(re.search(r"default_rng\((\d+)\)", text).group(1))
    drawn = re.search(r"DRAW (\[[^]]*\])", text).group(1)
    assert drawn == str(np.random.default_rng(seed).integers(2**62, size=4).tolist())


# -- eps_close -----------------------------------------------------------------------


def test_eps_close_passes_within_the_tolerance_and_fails_in_eps_with_the_worst_index(pytester):
    pytester.makepyfile(
        """
        import numpy as np

        EPS = np.finfo(np.float64).eps

        def test_within(eps_close):
            eps_close([1.0, 2.0, 3.0], [1.0, 2.0 * (1 + 3 * EPS), 3.0])
            eps_close(1.0 + 7 * EPS, 1.0, eps=8)
            eps_close(1e-20, 0.0, scale=1.0)
            eps_close.rotations(np.eye(3), np.eye(3) + 3 * EPS)
            eps_close.quaternions([0.0, 1.0, 0.0, 0.0], [0.0, -1.0, 0.0, 0.0])

        def test_far(eps_close):
            eps_close([[1.0, 2.0], [3.0, 4.0]], [[1.0, 2.0], [3.0, 4.0 + 1e-12]], eps=8)

        def test_far_rotation(eps_close):
            eps_close.rotations(np.eye(3), np.diag([1.0, 1.0 + 1e-12, 1.0]), eps=16)

        def test_far_quaternion(eps_close):
            eps_close.quaternions([[1.0, 0, 0, 0], [0, 1.0, 0, 0]], [[1.0, 0, 0, 0], [0, 0, 1.0, 0]])

        def test_bad_eps(eps_close):
            eps_close(1.0, 1.0, eps=-1)
        """
    )
    result = pytester.runpytest("-p", "no:randomly")
    result.assert_outcomes(passed=1, failed=4)
    result.stdout.fnmatch_lines(
        [
            "*_ test_far _*",
            ">*eps_close(*",
            "E*AssertionError: not close: relative error 1.13e+03 eps at index (1, 1) exceeds 8 eps "
            "(actual 4.0, desired 4.000000000001)",
            "*_ test_far_rotation _*",
            "E*AssertionError: rotations differ by 4.5e+03 eps at entry (1, 1), more than "
            "atol = 16 eps*",
            "*_ test_far_quaternion _*",
            "E*AssertionError: quaternions differ by 4.5e+15 eps * at index (1,), more than "
            "atol = 4 eps*",
            "*_ test_bad_eps _*",
            "E*ValueError: eps=-1 must be a finite number >= 0",
        ]
    )


# -- installation --------------------------------------------------------------------


def test_an_installed_bodycheck_brings_the_plugin_through_its_entry_point(pytester):
    pytester.makepyfile(
        """
        def test_fixtures(bodycheck_rng, eps_close):
            eps_close(bodycheck_rng.random(), bodycheck_rng.random(), scale=1.0, eps=2**53)
        """
    )
    loaded = pytester.runpytest_subprocess("--bodycheck-profile=bodycheck-ci")
    loaded.assert_outcomes(passed=1)
    loaded.stdout.fnmatch_lines(
        [
            "bodycheck: hypothesis profile 'bodycheck-ci' (from --bodycheck-profile)",
            f"plugins:*bodycheck-{version('bodycheck')}*",
        ]
    )
    off = pytester.runpytest_subprocess("-p", "no:bodycheck")
    off.assert_outcomes(errors=1)
    off.stdout.fnmatch_lines(["*fixture 'bodycheck_rng' not found*"])


def test_the_plugin_imports_nothing_heavy():
    code = (
        "import sys, mechanics.pytest_plugin; "
        "heavy = ('numpy', 'hypothesis', 'sympy', 'matplotlib', 'identities'); "
        "print([m for m in sys.modules if m.split('.')[0] in heavy])"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert proc.stdout.strip() == "[]", proc.stdout + proc.stderr
