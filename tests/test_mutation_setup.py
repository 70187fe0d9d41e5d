"""The set-up of mutation testing (issue 16; ``docs/mutation.md``) keeps its promises.

- every module of ``mechanics/`` that mutmut may change has a row of tests in
  ``tools/mutation/modules.toml``, and every test path named there exists;
- no function of ``mechanics/`` is hidden from mutation: mutmut 3 skips every function
  that carries a decorator (other than ``staticmethod``/``classmethod``), so guards,
  properties and fixtures are applied after the definition (``f = finite_result(f)``);
- the score's 95 % interval for a sample is Wilson's, as scipy computes it.
"""

from __future__ import annotations

import ast
import importlib.util
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent

#: what mutmut is told not to mutate (pyproject's [tool.mutmut] do_not_mutate), with the
#: reason there: numba compiles these functions and cannot compile mutmut's trampolines
NOT_MUTATED = {"mechanics/_kernels.py"}
#: decorators mutmut 3 does mutate through
MUTATED_THROUGH = {"staticmethod", "classmethod"}


def _run_module():
    spec = importlib.util.spec_from_file_location("mutation_run", ROOT / "tools/mutation/run.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _modules() -> list[str]:
    return sorted(str(p.relative_to(ROOT)) for p in (ROOT / "mechanics").rglob("*.py"))


def test_not_mutated_is_what_pyproject_says():
    cfg = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    assert set(cfg["tool"]["mutmut"]["do_not_mutate"]) == NOT_MUTATED


def test_every_module_of_mechanics_has_a_row_of_tests_that_exist():
    rows = _run_module().load_modules()
    missing = sorted(set(_modules()) - NOT_MUTATED - set(rows))
    assert not missing, f"modules without a row in tools/mutation/modules.toml: {missing}"
    gone = sorted({t for tests in rows.values() for t in tests if not (ROOT / t).exists()})
    assert not gone, f"test paths in modules.toml that do not exist: {gone}"
    stale = sorted(set(rows) - set(_modules()))
    assert not stale, f"rows for modules that are gone: {stale}"


def _decorated(path: Path, root: Path = ROOT):
    def visit(body, owner):
        for node in body:
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                names = {ast.unparse(d).split("(")[0] for d in node.decorator_list}
                if names - MUTATED_THROUGH:
                    yield f"{path.relative_to(root)}:{node.lineno} {owner}{node.name}"
            elif isinstance(node, ast.ClassDef):
                yield from visit(node.body, f"{owner}{node.name}.")

    yield from visit(ast.parse(path.read_text(encoding="utf-8")).body, "")


def test_no_function_of_mechanics_is_hidden_from_mutation_by_a_decorator():
    hidden = [f for m in _modules() if m not in NOT_MUTATED for f in _decorated(ROOT / m)]
    assert not hidden, (
        "mutmut does not mutate decorated functions; apply the decorator after the "
        f"definition (f = finite_result(f), p = property(p)): {hidden}"
    )


def test_the_rule_sees_a_decorator(tmp_path):
    """The negative control: the same scan finds a decorated function and a property."""
    (tmp_path / "mechanics").mkdir()
    src = tmp_path / "mechanics" / "x.py"
    src.write_text(
        "@finite_result\ndef f(x):\n    return x\n\n\nclass A:\n    @property\n    def p(self):\n"
        "        return 1\n\n    @staticmethod\n    def s():\n        return 2\n"
    )
    found = list(_decorated(src, tmp_path))
    assert found == ["mechanics/x.py:2 f", "mechanics/x.py:8 A.p"]


@pytest.mark.parametrize(("k", "n"), [(0, 10), (45, 50), (50, 50), (287, 300), (1, 1)])
def test_the_sample_interval_is_wilsons_as_scipy_computes_it(k, n):
    from scipy.stats import binomtest

    ci = binomtest(k, n).proportion_ci(confidence_level=0.95, method="wilson")
    lo, hi = _run_module().wilson(k, n)
    tol = 64 * 2.0**-52  # a few dozen roundings of the closed form; scipy solves the same
    assert abs(lo - ci.low) <= tol
    assert abs(hi - ci.high) <= tol


def test_a_folder_means_every_module_of_it_and_an_unknown_name_is_refused():
    run = _run_module()
    rows = run.load_modules()
    scenes = run.expand(["mechanics/scenes/effects/"], rows)
    assert scenes == sorted(m for m in rows if m.startswith("mechanics/scenes/effects/"))
    assert len(scenes) > 5
    with pytest.raises(SystemExit, match=r"mechanics/nothing\.py"):
        run.expand(["mechanics/nothing.py"], rows)


def test_the_score_counts_reviewed_equivalents_out_and_names_an_unmeasured_module():
    run = _run_module()
    status = {
        "mechanics.x.x_f__mutmut_1": "killed",
        "mechanics.x.x_f__mutmut_2": "survived",
        "mechanics.x.x_f__mutmut_3": "survived",
        "mechanics.x.x_f__mutmut_4": "timeout",
        "mechanics.y.x_g__mutmut_1": "survived",  # another module's: not counted
    }
    line, open_ = run.report("mechanics/x.py", status, {"mechanics.x.x_f__mutmut_3": "why"})
    assert "4 mutants, 2 killed, 1 equivalent (reviewed), 1 survived: score 66.7 %" in line
    assert open_ == ["mechanics.x.x_f__mutmut_2"]
    unchecked = {k: "not checked" for k in status}
    line, open_ = run.report("mechanics/x.py", unchecked, {})
    assert line == "mechanics/x.py: not measured (none of its 4 mutants checked)"
    assert open_ == []
    line, _ = run.report("mechanics/z.py", status, {})
    assert line == "mechanics/z.py: no mutants (nothing mutmut can change)"


def test_a_path_to_mutmut_is_made_absolute_a_bare_name_is_left_for_path(tmp_path, monkeypatch):
    # the Makefile passes .venv/bin/mutmut, relative to the project; mutmut then runs in
    # the copy under build/mutation/, where that relative path names nothing
    run = _run_module()
    monkeypatch.chdir(tmp_path)
    assert run.executable(".venv/bin/mutmut") == str(tmp_path / ".venv/bin/mutmut")
    assert run.executable("/opt/bin/mutmut") == "/opt/bin/mutmut"
    assert run.executable("mutmut") == "mutmut"


def test_a_packages_own_mutants_belong_to_its_init_and_not_to_its_submodules():
    # mutmut names the mutants of mechanics/scenes/__init__.py without __init__; the
    # report counted none of them ("no mutants") before issue 16's third session
    run = _run_module()
    own = "mechanics.scenes.x_builtin_path__mutmut_3"
    method = "mechanics.scenes.xǁScenesǁf__mutmut_1"
    sub = "mechanics.scenes.contacts.x_first_downward_crossing__mutmut_42"
    assert run.of_module(own, "mechanics/scenes/__init__.py")
    assert run.of_module(method, "mechanics/scenes/__init__.py")
    assert not run.of_module(sub, "mechanics/scenes/__init__.py")
    assert run.of_module(sub, "mechanics/scenes/contacts.py")
    assert not run.of_module(own, "mechanics/scenes/contacts.py")
    assert not run.of_module("mechanics.scenesx.x_f__mutmut_1", "mechanics/scenes/__init__.py")
    status = {own: "survived", sub: "killed"}
    line, open_ = run.report("mechanics/scenes/__init__.py", status, {})
    assert "1 mutants, 0 killed, 0 equivalent (reviewed), 1 survived" in line
    assert open_ == [own]
