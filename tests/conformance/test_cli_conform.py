"""``bodycheck conform``: the table, the JSON, the plot, adapters named every way, and
bad input as one line on stderr with exit code 2."""

from __future__ import annotations

import json
import os

import pytest

from identities.cli.main import main
from mechanics.conformance import SCENARIOS

from .toys import doc_example_source

ADAPTERS = """
from mechanics.conformance.adapters import ExactAdapter


class Exact(ExactAdapter):
    name = "user exact"


def make():
    return Exact()


instance = Exact()


class Broken:
    name = "broken"


class NeedsArgs(ExactAdapter):
    def __init__(self, x):
        self.x = x


class Fast(ExactAdapter):
    profile = "fast"
"""


@pytest.fixture
def project(tmp_path, monkeypatch):
    """A directory with the doc's toy engine and a few adapters, as the current one."""
    (tmp_path / "toy_engine_cli.py").write_text(doc_example_source(), encoding="utf-8")
    (tmp_path / "conform_adapters_cli.py").write_text(ADAPTERS, encoding="utf-8")
    monkeypatch.chdir(tmp_path)
    return tmp_path


def run(capsys, *args):
    code = main(["conform", *args])
    out, err = capsys.readouterr()
    return code, out, err


def test_exact_prints_the_table_with_every_scenario_passing(capsys):
    code, out, err = run(capsys, "exact")
    assert code == 0
    assert err == ""
    assert out.startswith(
        "# Conformance: exact (closed forms)\n\nProfile default: engineering accuracy 2^-10 "
        "on every figure; the order reported, not checked.\n\n"
        f"{len(SCENARIOS)} pass, 0 fail, 0 unsupported"
    )
    for name in SCENARIOS:
        assert f"| {name} | pass | " in out


def test_engine_runs_the_projects_integrated_engine(capsys):
    code, out, _ = run(capsys, "engine", "--scenario", "heavy_top", "rocket")
    assert code == 0
    assert "# Conformance: bodycheck scene engine (integrate)" in out
    assert "| heavy_top | pass |" in out
    assert "| rocket | pass |" in out
    assert "parabola" not in out


def test_json_and_plots_are_written(capsys, tmp_path):
    js, svg, png = tmp_path / "r.json", tmp_path / "r.svg", tmp_path / "r.png"
    code, out, _ = run(
        capsys, "exact", "--scenario", "parabola", "--json", str(js), "--plot", str(svg)
    )
    assert code == 0
    assert "| parabola | pass |" in out
    d = json.loads(js.read_text())
    assert [s["scenario"] for s in d["scenarios"]] == ["parabola"]
    assert d["passed"] is True
    assert "<svg" in svg.read_text()[:500]
    code, _, _ = run(capsys, "exact", "--scenario", "rocket", "--plot", str(png))
    assert code == 0
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_json_to_stdout(capsys):
    code, out, _ = run(capsys, "exact", "--scenario", "rocket", "--json", "-")
    assert code == 0
    assert json.loads(out)["counts"]["pass"] == 1


@pytest.mark.parametrize(
    "spec",
    [
        "conform_adapters_cli:Exact",
        "conform_adapters_cli:make",
        "conform_adapters_cli:instance",
        "conform_adapters_cli.py:Exact",
    ],
)
def test_an_adapter_is_a_class_a_factory_or_an_instance_in_a_module_or_file(capsys, project, spec):
    code, out, _ = run(capsys, spec, "--scenario", "two_body_impact")
    assert code == 0
    assert "# Conformance: user exact" in out


def test_a_failing_adapter_exits_1_and_thresholds_override(capsys, project):
    args = ["toy_engine_cli.py:SemiImplicitEuler", "--scenario", "parabola"]
    code, out, _ = run(capsys, *args)
    assert code == 1
    assert "| parabola | fail |" in out
    assert "position 0.00553 violates threshold <= 0.000977" in out
    loose = [f"--threshold={k}=0.015625" for k in ("position", "apex_height", "E_drift")]
    code, out, _ = run(capsys, *args, *loose, "--threshold", "order=0.9")
    assert code == 0
    assert "| parabola | pass |" in out
    assert "| 1.00 |" in out


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["nocolon"], "adapter 'nocolon': expected MODULE:ADAPTER"),
        (["no_such_module_xyz:A"], "unknown adapter module 'no_such_module_xyz'"),
        (["missing_file.py:A"], "adapter module file 'missing_file.py' does not exist"),
        (["conform_adapters_cli:Nope"], "module 'conform_adapters_cli' has no attribute 'Nope'"),
        (["conform_adapters_cli:Broken"], "is not an adapter (Broken lacks takes_step,"),
        (["conform_adapters_cli:NeedsArgs"], "the class could not be called without arguments"),
        (["exact", "--scenario", "paraboloid"], "unknown scenario 'paraboloid'"),
        (["exact", "--threshold", "velocty=1"], "unknown threshold key(s) 'velocty'"),
        (["exact", "--threshold", "velocity=tight"], "VALUE must be a number or 'none'"),
        (["exact", "--threshold", "velocity"], "--threshold 'velocity': expected NAME=VALUE"),
        (["exact", "--threshold", "velocity=-1"], "threshold 'velocity' must be a finite"),
        (["exact", "--plot", "out.pdf"], "--plot 'out.pdf': the file must end in .svg or .png"),
        (["all", "--markdown", "nowhere/t.md"], "--markdown 'nowhere/t.md': its folder 'nowhere' does not exist"),
        (["exact", "--json", "bad.toml/r.json"], "--json 'bad.toml/r.json': its folder 'bad.toml' is not a folder"),
        (["all", "--plot", "."], "--plot '.': is a folder; give a file's path"),
        (["engine_needing_extra:A"], "pip install 'bodycheck[mujoco]'"),
        (["exact", "--profile", "fast"], "unknown conformance profile 'fast'; known: first-order"),
        (["exact", "--config", "nope.toml"], "thresholds file 'nope.toml' does not exist"),
        (["exact", "--config", "bad.toml"], "bad.toml: unknown key(s) 'profle'; expected 'profile'"),
        (["exact", "--baseline", "pyproject.toml"], "the baseline is a thresholds file of its own"),
        (["all", "--baseline", "b.toml"], "--baseline pins one adapter's accuracy; name the adapter"),
        (["exact", "--baseline", "b.toml", "--margin", "0.5"], "--margin 0.5: the margin must be a number >= 1"),
        (["exact", "--baseline", "b.toml", "--margin", "nan"], "--margin nan: the margin must be"),
        (["conform_adapters_cli:Fast"], "adapter 'conform_adapters_cli:Fast': unknown conformance profile 'fast'"),
    ],
)  # fmt: skip
def test_bad_input_is_one_line_naming_the_value_with_exit_2(capsys, project, args, message):
    (project / "bad.toml").write_text('profle = "exact"\n', encoding="utf-8")
    (project / "engine_needing_extra.py").write_text(
        "from mechanics.conformance.adapters import require\n"
        "require('no_such_engine_pkg_xyz', 'mujoco', engine='MuJoCo')\n",
        encoding="utf-8",
    )
    code, out, err = run(capsys, *args)
    assert code == 2
    assert out == ""
    assert err.count("\n") == 1, err
    assert err.startswith("bodycheck: error: "), err
    assert message in err, err


def test_the_profile_comes_from_the_option_the_nearest_pyproject_or_the_adapter(capsys, project):
    args = ["toy_engine_cli.py:SemiImplicitEuler", "--scenario", "parabola"]
    code, out, _ = run(capsys, *args, "--profile", "first-order")
    assert code == 0
    assert "Profile first-order: an engine of order 1" in out
    assert "Thresholds from" not in out
    (project / "pyproject.toml").write_text(
        '[tool.bodycheck.conformance]\nprofile = "second-order"\n', encoding="utf-8"
    )
    below = project / "sub"
    below.mkdir()
    os.chdir(below)  # the fixture's monkeypatch restores the working directory
    code, out, _ = run(capsys, "../toy_engine_cli.py:SemiImplicitEuler", "--scenario", "parabola")
    assert code == 1
    assert "Profile second-order: " in out
    assert f"Thresholds from {project / 'pyproject.toml'} [tool.bodycheck.conformance]." in out
    code, out, _ = run(capsys, "../toy_engine_cli.py:SemiImplicitEuler", "--scenario",
                       "parabola", "--profile", "first-order")  # fmt: skip
    assert code == 0  # the option wins over the file


def test_a_baseline_is_written_and_then_passes_with_config(capsys, project):
    args = ["toy_engine_cli.py:SemiImplicitEuler", "--scenario", "parabola", "free_top_axis1"]
    code, out, _ = run(capsys, *args, "--baseline", "base.toml", "--margin", "3")
    assert code == 0  # the run fails at the default profile; the baseline is written
    assert "| parabola | fail |" in out
    assert out.endswith("wrote the baseline base.toml (use it with --config base.toml)\n")
    text = (project / "base.toml").read_text(encoding="utf-8")
    assert 'profile = "default"' in text
    assert "each figure at 3 x its measured value" in text
    code, out, _ = run(capsys, *args, "--config", "base.toml")
    assert code == 0, out
    assert "Thresholds from base.toml." in out
    code, out, _ = run(capsys, *args, "--config", "base.toml", "--threshold", "position=1e-3")
    assert code == 1  # the command line wins over the file


def test_a_file_inside_a_package_is_imported_as_its_module_so_relative_imports_resolve(
    capsys, project
):
    pkg = project / "my_engine" / "sub"
    pkg.mkdir(parents=True)
    (project / "my_engine" / "__init__.py").write_text("", encoding="utf-8")
    (pkg / "__init__.py").write_text("", encoding="utf-8")
    (pkg / "core.py").write_text("NAME = 'packaged exact'\n", encoding="utf-8")
    (pkg / "adapter.py").write_text(
        "from mechanics.conformance.adapters import ExactAdapter\n"
        "from .core import NAME\n\n\n"
        "class Packaged(ExactAdapter):\n    name = NAME\n",
        encoding="utf-8",
    )
    code, out, err = run(capsys, "my_engine/sub/adapter.py:Packaged", "--scenario", "parabola")
    assert (code, err) == (0, "")
    assert out.startswith("# Conformance: packaged exact\n")
    import sys

    assert str(project.resolve()) not in sys.path  # on the path for the import only
