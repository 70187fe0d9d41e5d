"""The lean install (issue 29, item 6): ``pip install bodycheck`` brings numpy, scipy,
hypothesis and pytest, and the plugin, the strategies, the testing helpers, the
mechanics library and the conformance battery work with those alone; a part that needs
an extra says which extra when it is missing.

The absent extras are simulated: each child process starts with an import hook that
refuses sympy, mpmath, matplotlib and numba (as a venv without them would), so the
test needs no second venv and no network.  The install sizes and times of both
installs are measured by hand and stated in docs/guide/use-in-your-project.md (they need
the registry).
"""

from __future__ import annotations

import ast
import subprocess
import sys
import textwrap
import tomllib
from pathlib import Path

import pytest

from mechanics._extras import EXTRA_OF, MissingExtraError, missing_extra, require_extra

ROOT = Path(__file__).resolve().parent.parent
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
CORE = {"numpy", "scipy", "hypothesis", "pytest"}

#: the child's first lines: every optional package of EXTRA_OF is absent
BLOCK = textwrap.dedent(
    f"""
    import importlib.abc, sys
    class _Absent(importlib.abc.MetaPathFinder):
        def find_spec(self, name, path, target=None):
            if name.split(".")[0] in {sorted(EXTRA_OF)!r}:
                raise ModuleNotFoundError(f"No module named {{name!r}}", name=name)
    sys.meta_path.insert(0, _Absent())
    """
)


def _lean(code: str, *args: str, cwd: Path = ROOT) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-c", BLOCK + textwrap.dedent(code), *args],
        capture_output=True,
        text=True,
        timeout=600,
        cwd=cwd,
        check=False,
    )


def _name(req: str) -> str:
    return req.split(">")[0].split("=")[0].split("[")[0].strip().lower()


def test_the_core_dependencies_are_the_four_and_each_extra_installs_its_packages():
    assert {_name(r) for r in PYPROJECT["project"]["dependencies"]} == CORE
    extras = PYPROJECT["project"]["optional-dependencies"]
    for package, extra in EXTRA_OF.items():
        assert package in {_name(r) for r in extras[extra]}, (package, extra)
    (everything,) = extras["all"]
    assert everything.startswith("bodycheck[")
    assert set(everything.removeprefix("bodycheck[").rstrip("]").split(",")) == set(
        EXTRA_OF.values()
    )
    assert "bodycheck[all]" in extras["test"]  # so the lock (make test, make run) has all


def _third_party_imports(path: Path) -> set[str]:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    names = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names |= {a.name.split(".")[0] for a in node.names}
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            names.add(node.module.split(".")[0])
    return names - set(sys.stdlib_module_names) - {"mechanics", "__future__"}


def test_the_library_imports_nothing_beyond_the_core_but_the_compiled_kernels():
    outside = {}
    for path in sorted((ROOT / "mechanics").rglob("*.py")):
        extra = _third_party_imports(path) - CORE
        if extra:
            outside[str(path.relative_to(ROOT))] = sorted(extra)
    # numba is imported only by the kernels, loaded on first use with a fallback; siconos
    # only by the worker that runs under Debian's python3 (the engines import through
    # adapters.require, naming their extras)
    assert outside == {
        "mechanics/_kernels.py": ["numba"],
        "mechanics/_kernels_rhs.py": ["numba"],
        "mechanics/scenes/_kernels.py": ["numba"],
        "mechanics/conformance/adapters/_siconos_worker.py": ["siconos"],
    }


def test_the_plugin_strategies_and_battery_run_without_any_extra():
    proc = _lean(
        """
        import warnings
        import mechanics, mechanics.pytest_plugin, mechanics.testing
        from hypothesis import find
        from mechanics import strategies as ms
        from mechanics.conformance import get_scenario, run_battery
        from mechanics.conformance.adapters import ExactAdapter, SceneEngineAdapter
        s = find(ms.scenarios(kinds=["parabola"]), lambda s: True)
        warnings.simplefilter("error")  # the battery may not fall back, noisily or not
        for adapter in (ExactAdapter(), SceneEngineAdapter()):
            r = run_battery(adapter, scenarios=[get_scenario("bouncing_ball"), s], profile="exact")
            assert r.passed, r.to_markdown()
        absent = [m for m in ("sympy", "mpmath", "matplotlib", "numba") if m in sys.modules]
        assert not absent, absent
        print("ran")
        """
    )
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.strip() == "ran"


def test_a_user_suite_runs_under_pytest_with_the_plugin_and_no_extra(tmp_path):
    (tmp_path / "test_user.py").write_text(
        textwrap.dedent(
            """
            from hypothesis import given
            from mechanics import strategies as ms
            from mechanics.conformance import conformance_tests
            from mechanics.conformance.adapters import ExactAdapter

            test_exact = conformance_tests(ExactAdapter(), scenarios=["parabola", "rocket"])

            @given(ms.principal_moments())
            def test_moments(J):
                assert J[0] + J[1] >= J[2] * (1 - 2**-40)

            def test_rng(bodycheck_rng):
                assert 0.0 <= bodycheck_rng.random() < 1.0
            """
        ),
        encoding="utf-8",
    )
    proc = _lean(
        """
        import pytest
        sys.exit(pytest.main(["-q", "-p", "no:randomly", "-p", "no:cacheprovider", "test_user.py"]))
        """,
        cwd=tmp_path,
    )
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "4 passed" in proc.stdout, proc.stdout


CLI = """
from identities.cli.main import main
sys.exit(main(sys.argv[1:]))
"""


@pytest.mark.parametrize(
    ("argv", "needs"),
    [
        (["check", "--help"], None),
        (["check"], "bodycheck check needs sympy, which is not installed: pip install 'bodycheck[proofs]'"),
        (["conform", "engine", "--scenario", "parabola", "--plot", "x.svg"],
         "bodycheck conform --plot needs matplotlib, which is not installed: "
         "pip install 'bodycheck[plots]'"),
    ],
)  # fmt: skip
def test_the_command_names_the_extra_a_command_needs(argv, needs, tmp_path):
    proc = _lean(CLI, *argv, cwd=tmp_path)
    if needs is None:
        assert proc.returncode == 0, proc.stderr
    else:
        assert proc.returncode == 2, proc.stdout + proc.stderr
        assert proc.stderr.strip() == f"bodycheck: error: {needs}"
        assert not (tmp_path / "x.svg").exists()
        assert "| parabola |" not in proc.stdout  # said before the battery runs


def test_the_battery_runs_from_the_command_without_any_extra(tmp_path):
    proc = _lean(CLI, "conform", "engine", "--scenario", "parabola", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert "| parabola | pass |" in proc.stdout


def test_the_steppers_fall_back_without_numba_naming_the_extra():
    proc = _lean(
        """
        import warnings
        import numpy as np
        from mechanics.integrators import CompiledPathWarning, free_rigid_body_rhs, integrate
        with warnings.catch_warnings(record=True) as seen:
            warnings.simplefilter("always")
            y0 = np.r_[np.eye(3).ravel(), 0.1, 0.2, 0.3]
            integrate(free_rigid_body_rhs([1.0, 2.0, 3.0]), y0, [0.0, 1.0], method="rk4", h=0.01)
        msgs = [str(w.message) for w in seen if issubclass(w.category, CompiledPathWarning)]
        assert len(msgs) == 1, msgs
        print(msgs[0])
        """
    )
    assert proc.returncode == 0, proc.stderr
    assert (
        "the compiled steppers needs numba, which is not installed: "
        "pip install 'bodycheck[fast]'" in proc.stdout
    ), proc.stdout


def test_missing_extra_reads_only_an_absent_optional_package():
    absent = ModuleNotFoundError("No module named 'matplotlib'", name="matplotlib")
    err = missing_extra(absent, "the plot")
    assert isinstance(err, MissingExtraError)
    assert (
        str(err)
        == "the plot needs matplotlib, which is not installed: pip install 'bodycheck[plots]'"
    )
    # a core package, a broken optional one (its submodule missing), another error: shown as is
    assert missing_extra(ModuleNotFoundError("x", name="numpy"), "y") is None
    assert missing_extra(ModuleNotFoundError("x", name="sympy.core"), "y") is None
    assert missing_extra(ImportError("x", name="sympy"), "y") is None
    assert missing_extra(ModuleNotFoundError("x"), "y") is None


def test_require_extra_refuses_a_package_that_is_not_optional():
    with pytest.raises(
        ValueError, match=r"module 'numpy': not an optional package \(\['matplotlib'"
    ):
        require_extra("numpy", "x")
