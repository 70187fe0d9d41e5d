"""The pytest plugin (:mod:`mechanics.pytest_plugin`), proved from outside with ``pytester``.

Each test writes a small project into a temporary directory and runs pytest on it.  Most
runs are in-process (fast; the plugin comes through its entry point there too, since
pytest loads ``pytest11`` entry points on every run); the ones about installation run
in a subprocess.  An in-process run can load a hypothesis profile into this process, so
every test here restores the profile that was loaded before it.
"""

from __future__ import annotations

import argparse
import json
import math
import re
import subprocess
import sys
import types
from importlib.metadata import version

import numpy as np
import pytest
from hypothesis import HealthCheck, Phase, Verbosity, settings

from mechanics import pytest_plugin as plugin
from mechanics._floats import EPS

pytest_plugins = ["pytester"]

# What the plugin's docstring and docs/guide/use-in-your-project.md promise (not read from the code):
# "bodycheck-ci (derandomised, 100 examples), bodycheck-dev (random, 100) or
# bodycheck-explore (random, 1000); none has a deadline" or the too_slow health check;
# ci prints a @reproduce_failure blob; all derive from hypothesis' default profile.
PROMISED_PROFILES = {
    "bodycheck-ci": {"derandomize": True, "max_examples": 100, "print_blob": True},
    "bodycheck-dev": {"derandomize": False, "max_examples": 100},
    "bodycheck-explore": {"derandomize": False, "max_examples": 1000},
}
#: hypothesis settings the profiles leave as the default profile has them
INHERITED = (
    "database",
    "verbosity",
    "phases",
    "stateful_step_count",
    "report_multiple_bugs",
    "print_blob",
    "backend",
)
#: the documented default of eps_close and its two methods: 4 eps
EPS_CLOSE_DEFAULT = 4

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


# -- in process: the profiles, the configure hook, the options, the fixtures ----------
#
# The runs above go through pytester; the tests below call the plugin's functions in this
# process, so that a change to them is seen whatever pytest did at start-up.


@pytest.fixture
def other_profile_loaded():
    """A loaded profile unlike hypothesis' default (the autouse fixture restores the old)."""
    settings.register_profile(
        "bodycheck-test-not-default",
        max_examples=3,
        derandomize=True,
        deadline=1234,
        verbosity=Verbosity.quiet,
        stateful_step_count=7,
        report_multiple_bugs=False,
        print_blob=True,
        phases=[Phase.explicit, Phase.generate],
        suppress_health_check=[HealthCheck.filter_too_much],
    )
    settings.load_profile("bodycheck-test-not-default")


def test_register_profiles_registers_the_three_documented_names_and_no_other(monkeypatch):
    import hypothesis

    seen = []

    class Spy:  # hypothesis' settings class is immutable: stand in for it where it is imported
        get_profile = staticmethod(settings.get_profile)

        def __call__(self, *args, **kwargs):
            return settings(*args, **kwargs)

        def register_profile(self, name, parent=None, **kwargs):
            seen.append(name)
            settings.register_profile(name, parent, **kwargs)

    monkeypatch.setattr(hypothesis, "settings", Spy())
    plugin.register_profiles()
    assert sorted(seen) == sorted(PROMISED_PROFILES)
    assert sorted(plugin.PROFILE_NAMES) == sorted(PROMISED_PROFILES)


@pytest.mark.parametrize("name", list(PROMISED_PROFILES))
def test_each_profile_has_the_documented_settings_whatever_profile_is_loaded(
    other_profile_loaded, name
):
    plugin.register_profiles()
    s = settings.get_profile(name)
    default = settings.get_profile("default")
    promised = PROMISED_PROFILES[name]
    for key, value in promised.items():
        assert getattr(s, key) == value, key
    assert s.deadline is None
    assert set(s.suppress_health_check) == {*default.suppress_health_check, HealthCheck.too_slow}
    for key in INHERITED:
        if key == "database" and s.derandomize:
            continue  # hypothesis keeps no example database for a derandomised profile
        if key not in promised and hasattr(default, key):
            assert _same(getattr(s, key), getattr(default, key)), key
    assert current_profile() == "bodycheck-test-not-default", "registering loads nothing"


def _same(a, b) -> bool:
    """Equal settings values; an example database is the same where its class and
    directory are (hypothesis compares databases by value only from 6.131.18: before,
    two objects for one directory compared unequal, and the lower bound is 6.92)."""
    path = getattr(a, "path", None)
    if path is not None and type(a) is type(b):
        return path == getattr(b, "path", None)
    return a == b


def test_same_tells_example_databases_by_class_and_directory(tmp_path):
    """_same's negative controls: another directory, another class, another value."""
    from hypothesis.database import DirectoryBasedExampleDatabase, InMemoryExampleDatabase

    here = DirectoryBasedExampleDatabase(tmp_path / "a")
    assert _same(here, DirectoryBasedExampleDatabase(tmp_path / "a"))
    assert not _same(here, DirectoryBasedExampleDatabase(tmp_path / "b"))
    assert not _same(here, InMemoryExampleDatabase())
    assert _same(100, 100)
    assert not _same(100, 200)


def _configure(pytester, monkeypatch, args, hypothesis_imported):
    """Run the plugin's pytest_configure on a freshly parsed config; did it register?"""
    config = pytester.parseconfig(*args)
    calls = []
    real = plugin.register_profiles

    def counting():
        calls.append(1)
        real()

    monkeypatch.setattr(plugin, "register_profiles", counting)
    if not hypothesis_imported:  # as in a run whose conftests never import hypothesis
        monkeypatch.setattr(plugin, "sys", types.SimpleNamespace(modules={}))
    plugin.pytest_configure(config)
    return config, bool(calls)


INI = "the ini setting bodycheck_profile"


@pytest.mark.parametrize(
    ("args", "hypothesis_imported", "registers", "loads", "source"),
    [
        ([], True, True, None, None),
        ([], False, False, None, None),
        (["-o", "bodycheck_profile="], False, False, None, None),
        (
            ["--bodycheck-profile=bodycheck-explore"],
            False,
            True,
            "bodycheck-explore",
            "--bodycheck-profile",
        ),
        (["--bodycheck-profile=bodycheck-ci"], True, True, "bodycheck-ci", "--bodycheck-profile"),
        (["--hypothesis-profile=bodycheck-dev"], False, True, None, None),
        # without hypothesis' own plugin (its option then does not exist)
        (
            ["-p", "no:hypothesispytest", "--bodycheck-profile=bodycheck-dev"],
            True,
            True,
            "bodycheck-dev",
            "--bodycheck-profile",
        ),
        (["-o", "bodycheck_profile=bodycheck-ci"], False, True, "bodycheck-ci", INI),
        (
            ["-o", "bodycheck_profile=bodycheck-ci", "--bodycheck-profile=bodycheck-dev"],
            False,
            True,
            "bodycheck-dev",
            "--bodycheck-profile",
        ),
        (
            ["-o", "bodycheck_profile=bodycheck-ci", "--hypothesis-profile=default"],
            True,
            True,
            None,
            None,
        ),
    ],
)
def test_configure_registers_when_asked_or_hypothesis_is_imported_and_loads_what_wins(
    pytester, monkeypatch, args, hypothesis_imported, registers, loads, source
):
    before = current_profile()
    config, registered = _configure(pytester, monkeypatch, args, hypothesis_imported)
    assert registered is registers
    assert current_profile() == (loads or before)
    header = plugin.pytest_report_header(config)
    if loads is None:
        assert header is None
    else:
        assert header == f"bodycheck: hypothesis profile {loads!r} (from {source})"


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (
            ["--bodycheck-profile=bodycheck-fast"],
            UNKNOWN_PROFILE.format(source="--bodycheck-profile", name="bodycheck-fast"),
        ),
        (["-o", "bodycheck_profile=ci"], UNKNOWN_PROFILE.format(source=INI, name="ci")),
        (
            ["--bodycheck-profile=bodycheck-ci", "--hypothesis-profile=default"],
            "ERROR: --bodycheck-profile='bodycheck-ci' and --hypothesis-profile='default' "
            "were both given; give one",
        ),
    ],
)
def test_configure_refuses_an_unknown_profile_or_both_options_naming_them(pytester, args, message):
    config = pytester.parseconfig(*args)
    with pytest.raises(pytest.UsageError, match="profile") as info:
        plugin.pytest_configure(config)
    assert "ERROR: " + str(info.value) == message


def test_options_default_to_seed_0_and_no_profile(pytester):
    config = pytester.parseconfig()
    assert config.getoption("bodycheck_seed") == 0  # "--bodycheck-seed (default 0)"
    assert config.getoption("bodycheck_profile") is None
    assert config.getini("bodycheck_profile") == ""  # an unset string ini reads as ""
    assert pytester.parseconfig("--bodycheck-seed", "7").getoption("bodycheck_seed") == 7


def test_help_lists_the_options_in_their_group_with_their_metavars(pytester):
    # a project's conftest can add its own options to the group by its name, bodycheck
    pytester.makeconftest(
        """
        def pytest_addoption(parser):
            parser.getgroup("bodycheck").addoption("--my-extra", help="a project's own")
        """
    )
    result = pytester.runpytest("--help")
    assert result.ret == pytest.ExitCode.OK
    lines = result.stdout.lines
    start = lines.index("bodycheck (mechanics testing):")
    section = lines[start + 1 : lines.index("", start)]  # the group, up to its blank line
    options = [line.split()[0] for line in section if line.startswith("  --")]
    assert options == ["--bodycheck-profile=NAME", "--bodycheck-seed=N", "--my-extra=MY_EXTRA"]
    text = " ".join(result.stdout.str().split())
    names = "bodycheck-ci, bodycheck-dev, bodycheck-explore"
    assert (
        f"--bodycheck-profile=NAME load a bodycheck hypothesis profile: {names} "
        "(overrides the ini setting bodycheck_profile)" in text
    )
    assert (
        "--bodycheck-seed=N an integer >= 0 mixed into every bodycheck_rng seed (default 0)" in text
    )
    assert f"bodycheck_profile (string): a bodycheck hypothesis profile to load: {names}" in text


@pytest.mark.parametrize(("text", "value"), [("0", 0), ("7", 7), (str(2**64 - 1), 2**64 - 1)])
def test_the_seed_option_takes_an_integer_from_0(text, value):
    assert plugin._seed_arg(text) == value


@pytest.mark.parametrize("text", ["-1", "0x2", "1.5", "", "seven"])
def test_the_seed_option_refuses_anything_else_naming_it(text):
    with pytest.raises(argparse.ArgumentTypeError, match="is not an integer >= 0") as info:
        plugin._seed_arg(text)
    assert str(info.value) == f"{text!r} is not an integer >= 0"


def test_seeds_are_64_bit_the_same_every_time_and_differ_by_node_id_and_base():
    ids = [f"tests/test_x.py::test_{i}" for i in range(64)]
    seeds = [plugin._seed(i, 0) for i in ids]
    assert all(isinstance(s, int) and 0 <= s < 2**64 for s in seeds)
    assert max(seeds) >= 2**63, "the top bit is used (64 seeds all below 2**63: odds 2**-64)"
    assert len(set(seeds)) == len(ids)
    assert [plugin._seed(i, 0) for i in ids] == seeds
    assert all(plugin._seed(i, 1) != s for i, s in zip(ids, seeds, strict=True))


def test_bodycheck_rng_is_the_generator_of_the_seed_it_prints(capsys, bodycheck_rng, request):
    printed = capsys.readouterr().out
    m = re.fullmatch(
        r"bodycheck_rng: numpy\.random\.default_rng\((\d+)\) \(--bodycheck-seed=(\d+)\)\n",
        printed,
    )
    assert m, printed
    assert int(m.group(2)) == request.config.getoption("bodycheck_seed")
    again = np.random.default_rng(int(m.group(1)))
    assert bodycheck_rng.integers(2**62, size=8).tolist() == again.integers(2**62, size=8).tolist()


def _off_by(k, kind):
    """Arguments for eps_close's `kind` whose error is exactly k eps."""
    if kind == "call":  # relative error |1 + k eps - 1| / 1
        return 1.0 + k * EPS, 1.0
    if kind == "rotations":
        R2 = np.eye(3)
        R2[2, 0] = -k * EPS
        return np.eye(3), R2
    return [0.0, 0.0, 1.0, 0.0], [0.0, k * EPS, -1.0, 0.0]  # closer with -q2


def _method(eps_close, kind):
    return eps_close if kind == "call" else getattr(eps_close, kind)


KINDS = ["call", "rotations", "quaternions"]


@pytest.mark.parametrize("kind", KINDS)
def test_eps_close_defaults_to_four_eps(eps_close, kind):
    f = _method(eps_close, kind)
    f(*_off_by(EPS_CLOSE_DEFAULT, kind))
    with pytest.raises(AssertionError, match=rf"\b{EPS_CLOSE_DEFAULT + 1} eps\b.*\b4 eps\b"):
        f(*_off_by(EPS_CLOSE_DEFAULT + 1, kind))


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("eps", [0, 16, 256.0])
def test_eps_close_takes_eps_as_the_tolerance_in_units_of_eps(eps_close, kind, eps):
    f = _method(eps_close, kind)
    f(*_off_by(eps, kind), eps=eps)
    with pytest.raises(AssertionError, match=rf"\b{eps + 1:g} eps\b.*\b{eps:g} eps\b"):
        f(*_off_by(eps + 1, kind), eps=eps)


@pytest.mark.parametrize("kind", KINDS)
def test_eps_close_prefixes_err_msg(eps_close, kind):
    with pytest.raises(AssertionError) as info:
        _method(eps_close, kind)(*_off_by(100, kind), err_msg="step 3")
    assert str(info.value).startswith("step 3: ")
    assert "100 eps" in str(info.value)


def test_eps_close_passes_scale_on():
    # 6 eps absolute against scale 1 is 12 eps relative to 0.5
    eps_close = plugin.EpsClose()
    eps_close(0.5 + 6 * EPS, 0.5, scale=1, eps=6)
    with pytest.raises(AssertionError, match=r"relative error 12 eps at index \(\)"):
        eps_close(0.5 + 6 * EPS, 0.5, eps=6)


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize(("eps", "shown"), [(-1, "-1"), (math.nan, "nan"), (math.inf, "inf")])
def test_eps_close_refuses_a_bad_eps_naming_it(eps_close, kind, eps, shown):
    with pytest.raises(ValueError, match=r"^eps=") as info:
        _method(eps_close, kind)(*_off_by(0, kind), eps=eps)
    assert str(info.value) == f"eps={shown} must be a finite number >= 0"


@pytest.mark.parametrize("kind", KINDS)
def test_eps_close_failures_point_at_the_caller_not_the_plugin(eps_close, kind):
    """pytest leaves out a frame whose locals set ``__tracebackhide__`` (its documented
    mechanism): no frame of the plugin is shown for a failed eps_close."""
    with pytest.raises(AssertionError) as info:
        _method(eps_close, kind)(*_off_by(100, kind))
    own = []
    tb = info.value.__traceback__
    while tb is not None:
        if tb.tb_frame.f_code.co_filename == plugin.__file__:
            own.append(bool(tb.tb_frame.f_locals.get("__tracebackhide__")))
        tb = tb.tb_next
    assert own, "no frame of mechanics/pytest_plugin.py in the traceback"
    assert all(own), f"a frame of mechanics/pytest_plugin.py is shown by pytest: {own}"


def test_eps_close_takes_rtol_as_assert_allclose_eps_does(eps_close):
    eps_close([1.0, 2.0], [1.0, 2.0 * (1 - 0.0099)], rtol=1e-2)
    with pytest.raises(AssertionError) as e:
        eps_close(2.0, 1.95, rtol=1e-2)
    assert str(e.value) == (
        f"not close: relative error {0.05 / 1.95:.3g} at index () exceeds rtol 0.01 "
        "(actual 2.0, desired 1.95)"
    )
