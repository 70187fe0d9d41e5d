"""The lecture notebooks (``identities/cli/notebooks.py``): the committed ones are what
``bodycheck notebooks --write notebooks/`` writes from the demos; each runs in a fresh
kernel, shows its plot and its backing check's pass; a failing cell is reported naming
the cell; the site's demos page shows what each notebook stored.

The tests that execute a notebook need the ``notebooks`` extra (nbclient, nbformat,
ipykernel: in the lock) and skip saying how to install it where it is missing.  Each
starts its own kernel (a new process: about 1 s before the first cell runs), so xdist
spreads them over its workers; everything a kernel writes goes under ``tmp_path``.
"""

from __future__ import annotations

import base64
import importlib.util
import json
import shutil

import pytest

from identities.book.scenes.demos import LECTURE_DEMOS
from identities.cli.main import main
from identities.cli.notebooks import (
    INSTALL,
    NOTEBOOKS,
    NotebookError,
    demos_page,
    execute_notebook,
    notebook_of,
    notebook_text,
    stale_notebooks,
    stored_output,
    write_notebooks,
)

#: the first bytes of every PNG file
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"
NAMES = [d.name for d in LECTURE_DEMOS]
#: a notebook written for a demo that is gone (its metadata names it), and one that is not ours
_OLD_DEMO = json.dumps({"cells": [], "metadata": {"bodycheck": {"demo": "old_demo"}}})
_SOMEONE_ELSES = json.dumps({"cells": [], "metadata": {}, "nbformat": 4, "nbformat_minor": 5})


@pytest.fixture
def kernel():
    """Skip, naming the install command, where the extra that executes notebooks is missing."""
    missing = [
        m for m in ("nbclient", "nbformat", "ipykernel") if importlib.util.find_spec(m) is None
    ]
    if missing:
        pytest.skip(f"{', '.join(missing)} not installed: {INSTALL}")


def _outputs(nb: dict, cell_id: str) -> list[dict]:
    (cell,) = [c for c in nb["cells"] if c.get("id") == cell_id]
    return cell["outputs"]


def _text(out: dict) -> str:
    text = out.get("text", "")
    return text if isinstance(text, str) else "".join(text)


def test_the_committed_notebooks_are_what_the_demos_write():
    assert stale_notebooks(NOTEBOOKS) == [], (
        "run `make checks` (bodycheck notebooks --write notebooks/)"
    )


def test_a_notebook_that_differs_from_its_demo_is_named_stale(tmp_path):
    """The staleness check's negative control: each way a folder can differ is named."""
    shutil.copytree(NOTEBOOKS, tmp_path, dirs_exist_ok=True)
    assert stale_notebooks(tmp_path) == []
    rocket = tmp_path / "rocket.ipynb"
    nb = json.loads(rocket.read_text("utf-8"))
    nb["cells"][1]["source"] = ["print('edited by hand')\n"]
    rocket.write_text(json.dumps(nb), "utf-8")
    tank = tmp_path / "tank_draining.ipynb"
    nb = json.loads(tank.read_text("utf-8"))
    for cell in nb["cells"]:
        cell.pop("outputs", None)
        if cell["cell_type"] == "code":
            cell["outputs"] = []
    tank.write_text(json.dumps(nb), "utf-8")
    (tmp_path / "heavy_top.ipynb").unlink()
    (tmp_path / "old_demo.ipynb").write_text(_OLD_DEMO, "utf-8")
    (tmp_path / "someone_elses.ipynb").write_text(_SOMEONE_ELSES, "utf-8")  # not ours: ignored
    (tmp_path / "rod_struck.ipynb").write_text("not json", "utf-8")
    assert stale_notebooks(tmp_path) == [
        f"{tmp_path / 'heavy_top.ipynb'}: missing",
        f"{tmp_path / 'rod_struck.ipynb'}: not a notebook (unreadable JSON)",
        f"{rocket}: its cells differ from the demo's (rocket)",
        f"{tank}: no stored outputs of a passing run (plot: no, check passed: no)",
        f"{tmp_path / 'old_demo.ipynb'}: a notebook of no lecture demo",
    ]


def test_the_cells_import_the_library_and_name_their_demo_and_check():
    for demo in LECTURE_DEMOS:
        nb = notebook_of(demo)
        about, scene, check = ("".join(c["source"]) for c in nb["cells"])
        assert demo.paragraph in about, demo.name
        assert demo.check in about, demo.name
        assert f'builtin_path("{demo.name}")' in scene
        assert "from identities." in scene, scene
        assert "def " not in scene, scene  # nothing of the library copied into a cell
        assert f'backing_check("{demo.check}")' in check
        assert "assert outcome.passed" in check
        assert notebook_text(nb) == notebook_text(json.loads(notebook_text(nb)))


@pytest.mark.parametrize("name", NAMES)
def test_each_notebook_runs_in_a_fresh_kernel_and_shows_its_plot_and_its_checks_pass(
    kernel, tmp_path, name
):
    """One fresh kernel per notebook (the point of the test: nothing shared between
    notebooks), so each pays a kernel's start, the imports (matplotlib; sympy, which the
    check machinery needs) and the scene run three times (once for the plot, twice in the
    check: exact flow and integrated).  Measured 6-10 s per notebook on the shared 2-core
    machine at a load average of 6 to 12 (about 3.5 runnable processes per core), so
    about 2-3 s on an idle one; xdist spreads the six over its workers."""
    (demo,) = [d for d in LECTURE_DEMOS if d.name == name]
    nb = execute_notebook(notebook_of(demo), tmp_path, name=name)
    scene = _outputs(nb, "scene")
    pngs = [
        base64.b64decode(o["data"]["image/png"]) for o in scene if "image/png" in o.get("data", {})
    ]
    assert len(pngs) == 1, [o.get("output_type") for o in scene]
    assert pngs[0].startswith(PNG_MAGIC)
    assert "against the book:" in "".join(_text(o) for o in scene)
    report = "".join(_text(o) for o in _outputs(nb, "check") if o.get("name") == "stdout")
    assert report.startswith(f"{demo.check} "), report[:200]
    assert report.rstrip().splitlines()[-1] == "PASSED", report[-500:]
    assert stored_output(nb).passed
    # nothing on stderr (a warning would show in the lecture) and no error output
    stray = [o for c in nb["cells"] for o in c.get("outputs", []) if o.get("name") == "stderr" or o["output_type"] == "error"]  # fmt: skip
    assert stray == []
    assert [p.name for p in tmp_path.iterdir() if not p.name.startswith("kernel")] == []


def test_a_failing_cell_is_reported_naming_the_cell_and_its_error(kernel, tmp_path):
    nb = {
        "cells": [
            {"cell_type": "code", "id": "fine", "metadata": {}, "source": "x = 1",
             "execution_count": None, "outputs": []},
            {"cell_type": "code", "id": "planted", "metadata": {}, "source":
             "raise AssertionError(f'planted failure, x = {x}')", "execution_count": None,
             "outputs": []},
            {"cell_type": "code", "id": "after", "metadata": {}, "source":
             "open('after-ran', 'w').close()", "execution_count": None, "outputs": []},
        ],
        "metadata": {"kernelspec": {"name": "python3", "display_name": "Python 3",
                                    "language": "python"}},
        "nbformat": 4,
        "nbformat_minor": 5,
    }  # fmt: skip
    with pytest.raises(NotebookError) as info:
        execute_notebook(nb, tmp_path, name="planted.ipynb")
    assert str(info.value) == (
        "planted.ipynb: cell 1 (id 'planted') failed: AssertionError: planted failure, x = 1"
    )
    assert not (tmp_path / "after-ran").exists()  # the cells after a failure do not run


def test_a_failing_backing_check_fails_its_notebooks_check_cell(kernel, tmp_path):
    """The check cell's assertion can fail: a cell planted before it swaps the rocket's
    check for one whose claim is false; the check cell prints FAILED and raises."""
    (demo,) = [d for d in LECTURE_DEMOS if d.name == "rocket"]
    nb = notebook_of(demo)
    plant = (
        "import dataclasses\n"
        "import identities.book.scenes.checks  # registers the scenes' checks\n"
        "from identities.verify import catalogue\n"
        f"c = catalogue.REGISTRY[{demo.check!r}]\n"
        "def wrong(d):\n"
        "    d.numeric_close(1.0, 0.0, atol=0.5, claim='a planted wrong claim')\n"
        "catalogue.REGISTRY[c.id] = dataclasses.replace(c, func=wrong)\n"
    )
    cell = {"cell_type": "code", "id": "plant", "metadata": {}, "source": plant,
            "execution_count": None, "outputs": []}  # fmt: skip
    nb["cells"] = [nb["cells"][0], cell, nb["cells"][2]]  # the scene cell is not needed
    with pytest.raises(NotebookError) as info:
        execute_notebook(nb, tmp_path, name="rocket.ipynb")
    assert str(info.value).startswith(
        "rocket.ipynb: cell 2 (id 'check') failed: AssertionError: a planted wrong claim: "
        "max error 1 > atol 0.5"
    ), str(info.value)


def test_the_site_page_shows_each_notebooks_stored_plot_and_verdict(tmp_path):
    body = demos_page(tmp_path, NOTEBOOKS, check_href=lambda i: f"named.html#{i}")
    for demo in LECTURE_DEMOS:
        section = body.split(f"<section id='{demo.name}'>")[1].split("</section>")[0]
        assert f"href='notebooks/{demo.name}.ipynb'" in section
        assert f"href='named.html#{demo.check}'" in section
        assert f"href='scenes.html#{demo.name}'" in section
        assert f"src='demo-{demo.name}.png'" in section
        assert "<span class='verified'>passed</span>" in section
        copied = tmp_path / "notebooks" / f"{demo.name}.ipynb"
        assert copied.read_bytes() == (NOTEBOOKS / f"{demo.name}.ipynb").read_bytes()
        stored = stored_output(json.loads(copied.read_text("utf-8")))
        assert (tmp_path / f"demo-{demo.name}.png").read_bytes() == stored.png
        assert stored.png.startswith(PNG_MAGIC)
    assert "not current" not in body


def test_the_site_page_says_when_a_notebook_stored_no_output(tmp_path):
    folder = tmp_path / "nb"
    shutil.copytree(NOTEBOOKS, folder)
    (folder / "rocket.ipynb").write_text(notebook_text(notebook_of(LECTURE_DEMOS[4])), "utf-8")
    assert LECTURE_DEMOS[4].name == "rocket"
    (folder / "heavy_top.ipynb").unlink()
    out = tmp_path / "site"
    out.mkdir()
    body = demos_page(out, folder)
    assert "The notebooks are not current (run <code>make checks</code>)" in body
    rocket = body.split("<section id='rocket'>")[1].split("</section>")[0]
    assert "<img" not in rocket
    assert "href='notebooks/rocket.ipynb'" in rocket
    heavy = body.split("<section id='heavy_top'>")[1].split("</section>")[0]
    assert "no notebook (run <code>make checks</code>)" in heavy
    assert "href='notebooks/heavy_top.ipynb'" not in heavy
    assert "the check thm.scene-heavy-top" in heavy  # no link without check_href


def test_the_command_checks_the_folder_and_leaves_current_notebooks_as_they_are(tmp_path, capsys):
    folder = tmp_path / "nb"
    shutil.copytree(NOTEBOOKS, folder)
    before = {p.name: p.read_bytes() for p in folder.iterdir()}
    assert main(["notebooks", "--check", str(folder)]) == 0
    assert main(["notebooks", "--write", str(folder)]) == 0  # all current: nothing runs
    assert "wrote 0 notebooks" in capsys.readouterr().out
    assert {p.name: p.read_bytes() for p in folder.iterdir()} == before
    (folder / "rocket.ipynb").unlink()
    assert main(["notebooks", "--check", str(folder)]) == 1
    out = capsys.readouterr()
    assert out.out == f"{folder / 'rocket.ipynb'}: missing\n"
    assert "make checks" in out.err
    assert main(["notebooks", "--check", str(folder), "--execute"]) == 2
    assert "--execute goes with --write" in capsys.readouterr().err


def test_write_executes_a_stale_notebook_and_removes_one_of_no_demo(kernel, tmp_path):
    """One kernel (the rocket's notebook: 10 s at a load average of 12, see above); the
    other five are current and kept as they are."""
    folder = tmp_path / "nb"
    shutil.copytree(NOTEBOOKS, folder)
    (folder / "rocket.ipynb").write_text(notebook_text(notebook_of(LECTURE_DEMOS[4])), "utf-8")
    (folder / "old_demo.ipynb").write_text(_OLD_DEMO, "utf-8")
    (folder / "someone_elses.ipynb").write_text(_SOMEONE_ELSES, "utf-8")
    assert [p.name for p in write_notebooks(folder)] == ["rocket.ipynb"]
    assert stale_notebooks(folder) == []
    assert not (folder / "old_demo.ipynb").exists()
    assert (folder / "someone_elses.ipynb").read_text("utf-8") == _SOMEONE_ELSES
