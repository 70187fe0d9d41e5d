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
import os
import sys
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent

#: what mutmut is told not to mutate (pyproject's [tool.mutmut] do_not_mutate): nothing
#: (the numba kernels are mutated with the JIT off, their row's env in modules.toml)
NOT_MUTATED: set[str] = set()
#: decorators mutmut 3 does mutate through
MUTATED_THROUGH = {"staticmethod", "classmethod"}


def _run_module():
    if "mutation_run" in sys.modules:
        return sys.modules["mutation_run"]
    spec = importlib.util.spec_from_file_location("mutation_run", ROOT / "tools/mutation/run.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules["mutation_run"] = mod  # dataclasses look their module up there
    spec.loader.exec_module(mod)
    return mod


def _modules() -> list[str]:
    return sorted(str(p.relative_to(ROOT)) for p in (ROOT / "mechanics").rglob("*.py"))


def test_not_mutated_is_what_pyproject_says():
    cfg = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    assert set(cfg["tool"]["mutmut"].get("do_not_mutate", [])) == NOT_MUTATED


def test_every_module_of_mechanics_has_a_row_of_tests_that_exist():
    rows = _run_module().load_modules()
    missing = sorted(set(_modules()) - NOT_MUTATED - set(rows))
    assert not missing, f"modules without a row in tools/mutation/modules.toml: {missing}"
    gone = sorted({t for tests in rows.values() for t in tests if not (ROOT / t).exists()})
    assert not gone, f"test paths in modules.toml that do not exist: {gone}"
    stale = sorted(set(rows) - set(_modules()))
    assert not stale, f"rows for modules that are gone: {stale}"


def _stub(node) -> bool:
    """A body of nothing but ``...`` (after a docstring): a protocol's member, typed only,
    with nothing mutmut could change."""
    body = node.body[1:] if ast.get_docstring(node) is not None else node.body
    return all(
        isinstance(s, ast.Expr) and isinstance(s.value, ast.Constant) and s.value.value is Ellipsis
        for s in body
    )


def _decorated(path: Path, root: Path = ROOT):
    def visit(body, owner):
        for node in body:
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                names = {ast.unparse(d).split("(")[0] for d in node.decorator_list}
                if names - MUTATED_THROUGH and not _stub(node):
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
        "\n\nclass P:\n    @property\n    def q(self) -> int: ...\n"
    )
    found = list(_decorated(src, tmp_path))
    # (P.q is a protocol's member: a body of "...", nothing to mutate)
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


# ------------------------------------------------------------------ the registered plan

#: the modules issue 35 asks to mutate in full
CORE = {
    "mechanics/rotation.py",
    "mechanics/impact.py",
    "mechanics/inertia.py",
    "mechanics/dynamics.py",
    "mechanics/tops.py",
    "mechanics/elliptic.py",
    "mechanics/particles.py",
    "mechanics/energy.py",
    "mechanics/kinematics.py",
    "mechanics/_kernels.py",
}


def test_the_plan_runs_the_core_in_full_the_rest_in_samples_of_100_then_full_runs_of_shortfalls():
    """Every module of modules.toml is run: the core once, in full; the rest first in a
    sample of at least 100, and a module of the rest may come again later (never
    before its sample) in a full run, after a review of its sample's shortfall: both
    rows are reported.  No module is sampled twice (a re-draw is what registration
    forbids hiding, so the plan has one sample per module) or run in full twice."""
    run = _run_module()
    rows = run.load_modules()
    plan = run.load_plan(run.PLAN.read_text(encoding="utf-8"))
    sampled: list[str] = []
    full: list[str] = []
    for r in plan:
        chosen = run.expand(r.modules, rows)
        if r.sample is None:
            early = sorted(set(chosen) - CORE - set(sampled))
            assert not early, f"a full run of the rest before its sample: {early}"
            full += chosen
        else:
            assert r.sample >= 100
            assert not set(chosen) & CORE
            assert not set(chosen) & set(full), f"sampled after a full run: {chosen}"
            sampled += chosen
    assert sorted(full) == sorted(set(full)), "a module in two full runs of the plan"
    assert sorted(sampled) == sorted(set(sampled)), "a module in two samples of the plan"
    assert set(full) >= CORE, f"core modules not run in full: {sorted(CORE - set(full))}"
    assert set(full) | set(sampled) == set(rows), (
        f"modules outside the plan: {sorted(set(rows) - set(full) - set(sampled))}"
    )
    seeds = [r.seed for r in plan if r.seed is not None]
    assert len(seeds) == len(set(seeds)), "two samples share a seed"


@pytest.mark.parametrize(
    ("body", "says"),
    [
        ('modules = ["m.py"]\nsample = 100\n', "both its size and its seed"),
        ('modules = ["m.py"]\nseed = 3\n', "both its size and its seed"),
        ('modules = ["m.py"]\nsample = 40\nseed = 3\n', "a sample of 40 mutants; at least 100"),
        ("sample = 100\nseed = 3\n", "a run has modules"),
        ('modules = ["m.py"]\nseeds = 3\n', "a run has modules, and sample and seed"),
    ],
)
def test_a_plan_run_without_its_seed_or_below_100_mutants_is_refused(body, says):
    with pytest.raises(SystemExit, match=says):
        _run_module().load_plan("[[run]]\n" + body)


def _git(root, *args):
    import subprocess

    env = {
        "GIT_AUTHOR_NAME": "t",
        "GIT_AUTHOR_EMAIL": "t@t",
        "GIT_COMMITTER_NAME": "t",
        "GIT_COMMITTER_EMAIL": "t@t",
        "PATH": "/usr/bin:/bin",
    }
    subprocess.run(["git", *args], cwd=root, env=env, check=True, capture_output=True)


def test_a_sample_is_registered_by_its_commit_and_counts_only_the_equivalents_listed_then(
    tmp_path,
):
    run = _run_module()
    (tmp_path / "tools" / "mutation").mkdir(parents=True)
    plan = tmp_path / "tools" / "mutation" / "plan.toml"
    equivalent = tmp_path / "tools" / "mutation" / "equivalent.toml"
    first = '[[run]]\nmodules = ["mechanics/a.py"]\n\n'
    second = '[[run]]\nmodules = ["mechanics/b.py"]\nsample = 100\nseed = 7\n'
    _git(tmp_path, "init", "-q")
    equivalent.write_text('["a"]\n"mechanics.a.x_f__mutmut_1" = "reviewed before"\n')
    plan.write_text(first)
    _git(tmp_path, "add", ".")
    _git(tmp_path, "commit", "-qm", "one")
    plan.write_text(first + second)
    runs = run.load_plan(plan.read_text())
    assert [r.lines for r in runs] == [(1, 2), (4, 7)]
    assert run.registration(runs[1].lines, tmp_path) is None  # not committed: refused
    _git(tmp_path, "commit", "-qam", "register b")
    commit = run.registration(runs[1].lines, tmp_path)
    assert commit is not None
    assert commit != run.registration(runs[0].lines, tmp_path)
    # a run whose lines come from two commits is registered by the newer
    assert run.registration((1, 7), tmp_path) == commit
    # reviewed after the registration: counts for the next sample, not for this one
    equivalent.write_text(
        equivalent.read_text() + '"mechanics.b.x_g__mutmut_2" = "reviewed after the sample"\n'
    )
    _git(tmp_path, "commit", "-qam", "review")
    assert set(run.equivalent_at(commit, tmp_path)) == {"mechanics.a.x_f__mutmut_1"}
    current = run.load_equivalent(equivalent)
    assert len(current) == 2
    assert set(run.sample_equivalents(current, commit, tmp_path)) == {"mechanics.a.x_f__mutmut_1"}
    # an entry retracted since the registration (found to change a rounding) stops counting
    retracted = {k: v for k, v in current.items() if k != "mechanics.a.x_f__mutmut_1"}
    assert run.sample_equivalents(retracted, commit, tmp_path) == {}
    assert run.sample_equivalents(current, None, tmp_path) == {}
    # a changed seed is a new registration
    plan.write_text(first + second.replace("seed = 7", "seed = 8"))
    assert run.registration(runs[1].lines, tmp_path) is None


def test_a_survivor_accepted_in_writing_still_counts_against_the_score():
    run = _run_module()
    status = {
        "mechanics.x.x_f__mutmut_1": "killed",
        "mechanics.x.x_f__mutmut_2": "survived",
        "mechanics.x.x_f__mutmut_3": "survived",
        "mechanics.x.x_f__mutmut_4": "survived",
    }
    equivalent = {"mechanics.x.x_f__mutmut_3": "why"}
    accepted = {"mechanics.x.x_f__mutmut_4": "a rounding of the last place"}
    line, open_ = run.report("mechanics/x.py", status, equivalent, accepted)
    assert "4 mutants, 1 killed, 1 equivalent (reviewed), 2 survived: score 33.3 %" in line
    assert "1 of the survivors accepted in writing" in line
    assert open_ == ["mechanics.x.x_f__mutmut_2"]


def test_the_table_row_of_a_sample_gives_its_wilson_interval_and_registration(tmp_path):
    run = _run_module()
    status = {f"mechanics.x.x_f__mutmut_{i}": "killed" for i in range(95)}
    status |= {f"mechanics.x.x_g__mutmut_{i}": "survived" for i in range(5)}
    status |= {f"mechanics.x.x_h__mutmut_{i}": "not checked" for i in range(300)}
    t = run.tally("mechanics/x.py", status, {"mechanics.x.x_g__mutmut_0": "why"}, {})
    plan_run = run.PlanRun(["mechanics/x.py"], 100, 41, (1, 4))
    row = run.table_row(t, plan_run, "0123456789abcdef")
    lo, hi = run.wilson(95, 99)
    assert row == (
        f"| `mechanics/x.py` | 100 of 400 (seed 41) | 95 | 1 | 4 (0 accepted) | 96.0 % | "
        f"{100 * lo:.1f}–{100 * hi:.1f} % | `012345678` |"
    )
    full = run.tally("mechanics/x.py", {k: v for k, v in status.items() if "x_h" not in k}, {})
    row = run.table_row(full, run.PlanRun(["mechanics/x.py"], None, None, (1, 2)), None)
    assert "| 100 (all) | 95 | 0 | 5 (0 accepted) | 95.0 % | every mutant | uncommitted |" in row
    # a full run stopped before its end gives no score
    row = run.table_row(t, run.PlanRun(["mechanics/x.py"], None, None, (1, 2)), None)
    assert "| 100 of 400 (unfinished) | 95 | 1 | 4 (0 accepted) | | | uncommitted |" in row
    # so does a sample stopped before its end (it once showed a score of what had run, and
    # 100.0 % over 0.0–100.0 % for a module none of whose drawn mutants had run)
    for checked in (0, 37):
        part = run.tally(
            "mechanics/x.py",
            {f"mechanics.x.x_f__mutmut_{i}": "killed" for i in range(checked)}
            | {f"mechanics.x.x_h__mutmut_{i}": "not checked" for i in range(400 - checked)},
            {},
            {},
        )
        row = run.table_row(part, plan_run, "0123456789abcdef")
        assert row == (
            f"| `mechanics/x.py` | {checked} of 100 drawn of 400 (seed 41) (unfinished) | "
            f"{checked} | 0 | 0 (0 accepted) | | | `012345678` |"
        )
        # and the table, read back, keeps it under its seed
        doc = tmp_path / "mutation.md"
        doc.write_text(f"<!-- SCORES -->\n{run.TABLE_HEAD}\n{row}\n<!-- /SCORES -->\n")
        previous = run.previous_rows(doc)
        assert run.kept_row(previous, "mechanics/x.py", 41, "`x`") == row


def test_a_copys_verdicts_survive_a_change_of_pyproject_outside_mutmut_and_pytest():
    run = _run_module()
    base = '[project]\ndependencies = ["numpy"]\n\n[tool.mutmut]\nonly_mutate = ["a.py"]\n'
    pinned = base.replace('"numpy"', '"numpy>=2"')
    assert run._verdict_key(base) == run._verdict_key(pinned)
    other = base.replace('"a.py"', '"b.py"')
    assert run._verdict_key(base) != run._verdict_key(other)
    pytest_cfg = base + '\n[tool.pytest.ini_options]\naddopts = "-x"\n'
    assert run._verdict_key(base) != run._verdict_key(pytest_cfg)


def test_modules_whose_rows_need_different_environments_do_not_share_a_copy():
    run = _run_module()
    assert run.environment(["mechanics/_kernels.py"])["NUMBA_DISABLE_JIT"] == "1"
    plain = run.environment(["mechanics/rotation.py"])
    assert plain.get("NUMBA_DISABLE_JIT") == os.environ.get("NUMBA_DISABLE_JIT")
    assert plain["CI"] == "1"
    with pytest.raises(SystemExit, match="different environments"):
        run.environment(["mechanics/_kernels.py", "mechanics/rotation.py"])


def test_a_registered_samples_verdicts_stand_and_an_ad_hoc_sample_reruns_its_survivors():
    run = _run_module()
    names = ["a", "b", "c", "d"]
    known = {"a": "killed", "b": "survived", "c": "not checked"}
    assert run.sample_to_run(names, known, True, False)[0] == ["c", "d"]
    assert run.sample_to_run(names, known, False, False)[0] == ["b", "c", "d"]
    assert run.sample_to_run(names, known, False, True)[0] == names
    assert (
        "2 of the registered sample run before" in run.sample_to_run(names, known, True, False)[1]
    )


def test_the_table_is_written_between_its_markers_and_nothing_else_changes(tmp_path, monkeypatch):
    run = _run_module()
    monkeypatch.setattr(run, "ROOT", tmp_path)
    a, b = tmp_path / "a.md", tmp_path / "b.md"
    a.write_text("intro\n<!-- SCORES -->\nold\n<!-- /SCORES -->\nrest\n")
    b.write_text("other\n<!-- SCORES -->\n<!-- /SCORES -->\n")
    run.write_table(["| `m` | row |"], (a, b))
    assert (
        a.read_text()
        == "intro\n<!-- SCORES -->\n" + run.TABLE_HEAD + "\n| `m` | row |\n<!-- /SCORES -->\nrest\n"
    )
    assert run.scores_block(a.read_text()) == run.scores_block(b.read_text())


def test_a_runs_lines_end_at_its_last_setting_not_at_the_next_runs_comment():
    """The lines of a run date its registration (git blame): a comment written later
    above the next run must not move it."""
    text = (
        "# the plan\n[[run]]\nmodules = ['a.py']\nsample = 100\nseed = 1\n\n"
        "# a later comment, about the next run\n\n[[run]]\nmodules = ['b.py']\n\n# tail\n"
    )
    first, second = _run_module().load_plan(text)
    assert (first.lines, second.lines) == ((2, 5), (9, 10))


def test_a_report_without_a_runs_copy_keeps_the_row_the_table_had(tmp_path):
    """A fresh checkout has no build/mutation/: --report keeps each row as last written,
    a sample's by its seed, a full run's apart from it (fluids has both)."""
    run = _run_module()
    full = "| `m.py` | 784 (all) | 700 | 0 | 84 (0 accepted) | 89.3 % | every mutant | `abc` |"
    unfinished = "| `k.py` | 615 of 1060 (unfinished) | 529 | 0 | 86 (0 accepted) | | | `abc` |"
    sampled = "| `m.py` | 100 of 784 (seed 3501) | 89 | 0 | 11 (0 accepted) | 89.0 % | x | `abc` |"
    empty = "| `e.py` | 0 | | | | no mutants (nothing to change) | | |"
    waiting = "| `w.py` | not run yet | | | | | | `abc` |"
    doc = tmp_path / "d.md"
    rows = "\n".join([run.TABLE_HEAD, full, unfinished, sampled, empty, waiting])
    doc.write_text(f"intro\n<!-- SCORES -->\n{rows}\n<!-- /SCORES -->\n", encoding="utf-8")
    assert run.previous_rows(doc) == {
        ("m.py", None): full,
        ("k.py", None): unfinished,
        ("m.py", 3501): sampled,
        ("e.py", "any"): empty,
        ("w.py", "any"): waiting,
    }


def test_a_run_not_made_yet_keeps_its_own_registration_beside_another_of_the_module():
    """A module in two runs not made yet (a folder's sample, then its own full run) had
    both rows under one key: the later run's registration was written into the
    earlier run's row.  Each run's row now names its own."""
    run = _run_module()
    waiting = "| `w.py` | not run yet | | | | | | `late` |"
    done = "| `m.py` | 100 of 784 (seed 3501) | 89 | 0 | 11 (0 accepted) | 89.0 % | x | `abc` |"
    previous = {("w.py", "any"): waiting, ("m.py", 3501): done}
    assert run.kept_row(previous, "w.py", 3505, "`early`") == (
        "| `w.py` | not run yet | | | | | | `early` |"
    )
    assert run.kept_row(previous, "w.py", None, "`late`") == waiting
    assert run.kept_row(previous, "m.py", 3501, "`other`") == done
    assert run.kept_row(previous, "n.py", None, "`x`") == "| `n.py` | not run yet | | | | | | `x` |"


def test_a_copy_is_left_alone_by_a_report_and_forgets_only_what_a_change_invalidates(
    tmp_path, monkeypatch
):
    run = _run_module()
    root = tmp_path / "project"
    (root / "mechanics").mkdir(parents=True)
    (root / "tests").mkdir()
    (root / "mechanics" / "a.py").write_text("def f():\n    return 1\n")
    (root / "tests" / "test_a.py").write_text("def test_f():\n    pass\n")
    pyproject = root / "pyproject.toml"
    pyproject.write_text(
        '[project]\ndependencies = ["numpy"]\n\n[tool.mutmut]\n'
        'pytest_add_cli_args_test_selection = ["tests"]\n'
    )
    monkeypatch.setattr(run, "ROOT", root)
    monkeypatch.setattr(run, "WORK", tmp_path / "work")
    work, changed = run.prepare(["mechanics/a.py"], ["tests/test_a.py"])
    assert changed  # a fresh copy: every test file is new
    text = (work / "pyproject.toml").read_text()
    assert 'only_mutate = ["mechanics/a.py"]' in text
    assert 'pytest_add_cli_args_test_selection = ["tests/test_a.py"]' in text
    stats = work / "mutants" / "mutmut-stats.json"
    stats.parent.mkdir()
    stats.write_text("{}")
    (root / "tests" / "test_a.py").write_text("def test_f():\n    assert True\n")
    # a report (sync=False) touches nothing, a run may be going on in the copy
    assert run.prepare(["mechanics/a.py"], ["tests/test_a.py"], sync=False) == (work, False)
    assert stats.exists()
    assert "assert True" not in (work / "tests" / "test_a.py").read_text()
    # a run syncs: the changed test makes mutmut record its tests again, verdicts stay
    assert run.prepare(["mechanics/a.py"], ["tests/test_a.py"]) == (work, True)
    assert not stats.exists()
    assert (work / "mutants").exists()
    # a new pin changes no verdict; a new test selection forgets them all
    pyproject.write_text(pyproject.read_text().replace('"numpy"', '"numpy>=2"'))
    assert run.prepare(["mechanics/a.py"], ["tests/test_a.py"]) == (work, False)
    assert (work / "mutants").exists()
    run.prepare(["mechanics/a.py"], ["tests"])
    assert not (work / "mutants").exists()


def test_every_row_of_the_table_has_the_heads_number_of_cells():
    run = _run_module()
    heads = run.TABLE_HEAD.splitlines()[0].count("|")
    rows = run.scores_block(run.TABLES[0].read_text(encoding="utf-8")).splitlines()[3:]
    empty = run.tally("mechanics/x.py", {}, {})
    rows.append(run.table_row(empty, run.PlanRun(["mechanics/x.py"], None, None, (1, 2)), None))
    assert rows
    assert all(r.count("|") == heads for r in rows), [r for r in rows if r.count("|") != heads]


def test_a_sample_and_a_full_run_of_one_module_have_copies_of_their_own(tmp_path, monkeypatch):
    """A full run after a short sample (plan.toml) shared the sample's copy: its verdicts
    would replace the sample's, and a later report would rewrite the registered sample's
    row from them.  A sample's copy is named by its seed."""
    run = _run_module()
    monkeypatch.setattr(run, "WORK", tmp_path)
    full, sample = run.workdir(["mechanics/a.py"]), run.workdir(["mechanics/a.py"], 3507)
    assert full == tmp_path / "mechanics_a"
    assert sample == tmp_path / "mechanics_a_sample3507"
    assert run.workdir(["mechanics/a.py"], 3508) != sample
    group = run.workdir(["mechanics/a.py", "mechanics/b.py"], 3501)
    assert group == tmp_path / "group_a_b_sample3501"
