"""The lecture demos as Jupyter notebooks (issue 31, item 3): one notebook per demo of
:data:`identities.book.scenes.demos.LECTURE_DEMOS`, written from the demo's definition,
executed by the tests, and shown by the site.

Conventions
-----------
- **One source of truth.**  ``notebooks/NAME.ipynb`` (nbformat 4.5) is written by
  ``bodycheck notebooks --write notebooks/`` (``make checks``) from the demo's entry in
  ``identities/book/scenes/demos.py``: edit there, never the notebook.  A test fails
  when the committed cells differ from the ones written now (:func:`stale_notebooks`).
- **Three cells**, each importing the library and copying none of it: the demo's topic,
  book reference and paragraph (markdown); the scene run and compared with the book
  (``run_book_scene``), its summary and its plot (``plot_result``'s figure, shown inline
  as PNG by :class:`ScenePlot`); the catalogue check that backs the demo
  (:func:`backing_check`), its steps and verdict (:func:`check_report`), asserted.
- **Stored outputs.**  The committed notebooks carry the outputs of their last
  execution (the plot and the check's report): a reader sees them without running
  anything, and the site shows them without executing a notebook (its build stays
  within its time budget).  ``--write`` executes a notebook only when its cells changed
  or it has no outputs (``--execute``: every one), so writing again leaves an unchanged
  notebook byte for byte.  The stored outputs are a picture, not the evidence: the
  tests execute every notebook afresh (``tests/test_notebooks.py``).
- **Executing** needs the ``notebooks`` extra (nbclient, nbformat, ipykernel).  Each
  notebook gets a fresh kernel: ipykernel's own ``python3``, started with this Python
  (no kernelspec folder is searched), talking over IPC sockets in a private temporary
  folder that also holds its connection file and IPython profile, so nothing is written
  to the user's jupyter or IPython folders and no user startup file runs.  Writing the
  cells and reading the stored outputs need only the standard library.
"""

from __future__ import annotations

import html
import json
import os
import shutil
import tempfile
from dataclasses import dataclass
from pathlib import Path

from identities.book.scenes.demos import LECTURE_DEMOS, Demo

__all__ = [
    "CELL_TIMEOUT_S",
    "INSTALL",
    "NOTEBOOKS",
    "NotebookError",
    "ScenePlot",
    "StoredOutput",
    "backing_check",
    "check_report",
    "demos_page",
    "execute_notebook",
    "notebook_of",
    "notebook_text",
    "plot_of",
    "stale_notebooks",
    "stored_output",
    "write_notebooks",
]

#: the committed notebooks (a checkout's ``notebooks/``; absent from an installed wheel)
NOTEBOOKS = Path(__file__).resolve().parents[2] / "notebooks"
#: what to install for executing them
INSTALL = "pip install 'bodycheck[notebooks]'"
#: a cell running longer is hung: the slowest cell (free_top_flip's check: the scene by
#: its exact flow and integrated) took 3.7 s on a loaded 2-core machine
CELL_TIMEOUT_S = 300
#: the ids of the three cells, stable so that a regenerated notebook diffs cleanly
_CELL_IDS = ("about", "scene", "check")
#: the line the check cell prints last when the check passed
_PASSED = "PASSED"


class NotebookError(RuntimeError):
    """A notebook could not be executed, or one of its cells failed (the message names
    the notebook, the cell's index and id, and the error)."""


def _lines(text: str) -> list[str]:
    """``text`` as nbformat stores a multi-line string on disk: its lines, ends kept."""
    return text.splitlines(keepends=True)


def _markdown(demo: Demo) -> str:
    from mechanics.scenes import builtin_path, load_scene

    scene = load_scene(builtin_path(demo.name))
    return (
        f"# {demo.topic[:1].upper()}{demo.topic[1:]}\n"
        "\n"
        f"*{scene.title}*: H. Essén, *Dynamics of Bodies* (KTH, 1996), {scene.book}.\n"
        "\n"
        f"{demo.paragraph}\n"
        "\n"
        f"Backed by the catalogue check `{demo.check}` (`bodycheck explain {demo.check}`); "
        f"from the command line: `bodycheck demo {demo.name} --plot {demo.name}.png`.\n"
        "\n"
        "Written by `bodycheck notebooks --write notebooks/` (`make checks`) from "
        "`identities/book/scenes/demos.py`: edit the demo there, not this notebook."
    )


def _scene_code(demo: Demo) -> str:
    return (
        "from identities.book.scenes.compare import load_book_scene, run_book_scene\n"
        "from identities.cli.notebooks import plot_of\n"
        "from mechanics.scenes import builtin_path\n"
        "\n"
        f"result = run_book_scene(load_book_scene(builtin_path({json.dumps(demo.name)})))\n"
        "print(result.summary())\n"
        "plot_of(result)"
    )


def _check_code(demo: Demo) -> str:
    return (
        "from identities.cli.notebooks import backing_check, check_report\n"
        "\n"
        f"outcome, derivation = backing_check({json.dumps(demo.check)})\n"
        "print(check_report(outcome, derivation))\n"
        "assert outcome.passed, outcome.message"
    )


def notebook_of(demo: Demo) -> dict:
    """The notebook of ``demo`` without outputs, as nbformat 4.5 JSON (a dict)."""
    if not isinstance(demo, Demo):
        raise TypeError(f"notebook_of needs a Demo; got {type(demo).__name__}: {demo!r}")
    sources = (_markdown(demo), _scene_code(demo), _check_code(demo))
    cells = []
    for cid, kind, source in zip(_CELL_IDS, ("markdown", "code", "code"), sources, strict=True):
        cell = {"cell_type": kind, "id": cid, "metadata": {}, "source": _lines(source)}
        if kind == "code":
            cell |= {"execution_count": None, "outputs": []}
        cells.append(cell)
    return {
        "cells": cells,
        "metadata": {
            "bodycheck": {"demo": demo.name, "check": demo.check},
            "kernelspec": {"display_name": "Python 3", "language": "python", "name": "python3"},
            "language_info": {"name": "python"},
        },
        "nbformat": 4,
        "nbformat_minor": 5,
    }


def notebook_text(nb: dict) -> str:
    """``nb`` as nbformat writes it (sorted keys, indent 1, UTF-8 kept, final newline), so
    that saving it again in Jupyter changes nothing but what Jupyter adds."""
    return json.dumps(nb, sort_keys=True, indent=1, ensure_ascii=False) + "\n"


def _cells_of(nb: dict) -> list[tuple[str, str, str]]:
    """What :func:`notebook_of` decides about a notebook: each cell's kind, id and source."""

    def text(source) -> str:
        return source if isinstance(source, str) else "".join(map(str, source))

    return [
        (str(c.get("cell_type")), str(c.get("id", "")), text(c.get("source", "")))
        if isinstance(c, dict)
        else ("?", "", repr(c))
        for c in nb["cells"]
    ]


def _same_cells(nb: dict, demo: Demo) -> bool:
    want = notebook_of(demo)
    return (
        _cells_of(nb) == _cells_of(want)
        and nb.get("metadata", {}).get("bodycheck") == want["metadata"]["bodycheck"]
    )


def _ours(path: Path) -> bool:
    """Whether ``path`` is a notebook this module wrote (its metadata names a demo): only
    such a notebook of no current demo is stale or removed, never someone else's."""
    nb = _read(path)
    return nb is not None and isinstance(nb.get("metadata"), dict) and "bodycheck" in nb["metadata"]


def _read(path: Path) -> dict | None:
    try:
        nb = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return nb if isinstance(nb, dict) and isinstance(nb.get("cells"), list) else None


def stale_notebooks(folder: str | os.PathLike[str] = NOTEBOOKS) -> list[str]:
    """Why the notebooks in ``folder`` are not what :func:`write_notebooks` writes: one
    line per notebook that is missing, unreadable, has other cells than its demo's, or
    has no stored plot or passed check; one per notebook written for a demo that is no
    longer one (other ``.ipynb`` files are not ours and are left alone).  Empty when
    current."""
    folder = Path(folder)
    problems = []
    for demo in LECTURE_DEMOS:
        path = folder / f"{demo.name}.ipynb"
        nb = _read(path) if path.is_file() else None
        if not path.is_file():
            problems.append(f"{path}: missing")
        elif nb is None:
            problems.append(f"{path}: not a notebook (unreadable JSON)")
        elif not _same_cells(nb, demo):
            problems.append(f"{path}: its cells differ from the demo's ({demo.name})")
        else:
            out = stored_output(nb)
            if out.png is None or not out.passed:
                problems.append(
                    f"{path}: no stored outputs of a passing run (plot: "
                    f"{'yes' if out.png else 'no'}, check passed: {'yes' if out.passed else 'no'})"
                )
    known = {f"{d.name}.ipynb" for d in LECTURE_DEMOS}
    if folder.is_dir():
        problems += [
            f"{p}: a notebook of no lecture demo" for p in sorted(folder.glob("*.ipynb"))
            if p.name not in known and _ours(p)
        ]  # fmt: skip
    return problems


def execute_notebook(
    nb: dict, cwd: str | os.PathLike[str], *, name: str = "notebook", timeout: int = CELL_TIMEOUT_S
) -> dict:
    """Execute ``nb`` in a fresh ``python3`` kernel whose working folder is ``cwd``; return
    the executed notebook (a dict with the outputs).

    Raises :class:`NotebookError` naming ``name``, the failing cell's index and id and its
    error when a cell raises (the cells after it are not run), and ModuleNotFoundError
    saying :data:`INSTALL` when nbclient, nbformat or ipykernel is missing.
    """
    try:
        import ipykernel  # noqa: F401  (the python3 kernelspec the client starts)
        import nbclient
        import nbformat
    except ModuleNotFoundError as exc:
        raise ModuleNotFoundError(
            f"executing a notebook needs {exc.name}, which is not installed: {INSTALL}",
            name=exc.name,
        ) from None
    if not Path(cwd).is_dir():
        raise NotADirectoryError(f"execute_notebook: cwd {cwd} is not a folder")
    import gc
    import warnings

    from jupyter_client.kernelspec import KernelSpecManager
    from jupyter_client.manager import KernelManager

    node = nbformat.reads(notebook_text(nb), as_version=4)
    nbformat.validate(node)
    failure = None
    with tempfile.TemporaryDirectory(prefix="bodycheck-kernel-") as plumbing:
        # the kernel's connection file and sockets: files in a private folder (IPC), not
        # TCP ports any local user may reach, nor the user's jupyter runtime folder
        km = KernelManager(
            # no kernelspec folders: the python3 kernel is ipykernel's own, running this
            # Python (a user's python3 kernelspec elsewhere is not used, and finding none
            # creates no ~/.ipython)
            kernel_spec_manager=KernelSpecManager(kernel_dirs=[]),
            kernel_name="python3",
            transport="ipc",
            ip=str(Path(plumbing) / "k"),
            connection_file=str(Path(plumbing) / "kernel.json"),
        )
        client = nbclient.NotebookClient(
            node,
            km=km,
            timeout=timeout,
            kernel_name="python3",
            record_timing=False,  # no timestamps: an unchanged run stores the same metadata
            resources={"metadata": {"path": str(cwd)}},
        )
        with warnings.catch_warnings():
            # nbclient leaves its kernel client's zmq sockets to the garbage collector
            # (ResourceWarning: unclosed socket, also in nbclient's own tests:
            # jupyter/nbclient#316); they are collected here, before the folder goes
            warnings.simplefilter("ignore", ResourceWarning)
            try:
                # IPython's profile (history, startup files) in the private folder too: no
                # user configuration runs in the kernel, and nothing is written to ~/.ipython
                client.execute(env={**os.environ, "IPYTHONDIR": str(Path(plumbing) / "ipython")})
            except nbclient.exceptions.CellExecutionError as exc:
                failure = _failed_cell(node) or f"a cell failed: {str(exc)[-500:]}"
            except nbclient.exceptions.CellTimeoutError as exc:
                failure = f"a cell ran longer than {timeout} s: {exc}"
            del client, km
            gc.collect()
    if failure is not None:
        raise NotebookError(f"{name}: {failure}")
    return json.loads(nbformat.writes(node))


def _failed_cell(node) -> str | None:
    """The first cell of an executed notebook with an error output: its index, id and
    error; None if no cell has one."""
    for k, cell in enumerate(node.cells):
        for out in cell.get("outputs", []):
            if out.get("output_type") == "error":
                return (
                    f"cell {k} (id {cell.get('id')!r}) failed: "
                    f"{out.get('ename')}: {out.get('evalue')}"
                )
    return None


@dataclass(frozen=True)
class StoredOutput:
    """What an executed demo notebook shows: the plot (PNG bytes) of its scene cell and
    the report its check cell printed; None where the notebook holds none."""

    png: bytes | None
    report: str | None

    @property
    def passed(self) -> bool:
        """Whether the stored report ends with the check's pass."""
        return self.report is not None and self.report.rstrip().endswith(_PASSED)


def stored_output(nb: dict) -> StoredOutput:
    """The plot and the check's report stored in the demo notebook ``nb``."""
    import base64
    import binascii

    png = report = None
    for cell in nb.get("cells", []):
        for out in cell.get("outputs", []) if cell.get("cell_type") == "code" else []:
            data = out.get("data", {})
            if cell.get("id") == "scene" and "image/png" in data:
                try:
                    png = base64.b64decode("".join(data["image/png"]), validate=True)
                except (binascii.Error, ValueError):
                    png = None
            if cell.get("id") == "check" and out.get("name") == "stdout":
                text = out.get("text", "")
                report = (report or "") + (text if isinstance(text, str) else "".join(text))
    return StoredOutput(png, report)


def _shows_a_pass(nb: dict) -> bool:
    out = stored_output(nb)
    return out.png is not None and out.passed


def write_notebooks(
    folder: str | os.PathLike[str] = NOTEBOOKS, *, execute: bool = False
) -> list[Path]:
    """Write every lecture demo's notebook into ``folder``, executed, with its outputs;
    return the notebooks written.  A notebook whose cells are current and which stores
    a plot and a passed check is left as it is unless ``execute``; a notebook written
    for a demo that is no longer one is removed (any other ``.ipynb`` file is left).

    Raises :class:`NotebookError` when a notebook fails (nothing of it is written).
    """
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    written = []
    for demo in LECTURE_DEMOS:
        path = folder / f"{demo.name}.ipynb"
        old = _read(path) if path.is_file() else None
        current = old is not None and _same_cells(old, demo)
        if current and not execute and _shows_a_pass(old):
            continue
        with tempfile.TemporaryDirectory() as tmp:
            nb = execute_notebook(notebook_of(demo), tmp, name=path.name)
        if not _shows_a_pass(nb):
            raise NotebookError(f"{path.name}: ran, but stored no plot or no passed check")
        part = path.with_name(f".{path.name}.{os.getpid()}.part")
        part.write_text(notebook_text(nb), encoding="utf-8")
        os.replace(part, path)
        written.append(path)
    known = {f"{d.name}.ipynb" for d in LECTURE_DEMOS}
    for p in folder.glob("*.ipynb"):
        if p.name not in known and _ours(p):
            p.unlink()
    return written


@dataclass(frozen=True, repr=False)
class ScenePlot:
    """A scene's plot as PNG bytes; Jupyter shows it inline (``_repr_png_``)."""

    png: bytes
    scene: str = ""

    def _repr_png_(self) -> bytes:
        return self.png

    def __repr__(self) -> str:  # the text a notebook stores beside the image: short
        return f"<plot of the scene {self.scene}: PNG, {len(self.png)} bytes>"


def plot_of(result) -> ScenePlot:
    """The plot :func:`identities.cli.scene_plots.plot_result` draws of ``result`` (a
    :class:`mechanics.scenes.SceneResult`), as a :class:`ScenePlot`."""
    from identities.cli.scene_plots import plot_result

    with tempfile.TemporaryDirectory() as tmp:
        png = plot_result(result, Path(tmp) / "plot.png").read_bytes()
    return ScenePlot(png, result.scene.name)


def backing_check(check_id: str):
    """Run the catalogue check ``check_id``: ``(Outcome, Derivation)`` as
    :func:`identities.verify.catalogue.run_check` gives them.

    A scene's check (``thm.scene-*``) is found by importing only the module that
    registers the scenes' checks (about 1 s), not the whole catalogue (about 3 s: every
    chapter's proofs); any other id loads the catalogue.
    """
    import importlib

    from identities.verify import catalogue

    if check_id.startswith("thm.scene-"):
        importlib.import_module("identities.book.scenes.checks")
    if check_id not in catalogue.REGISTRY:
        catalogue.load_all()
    if check_id not in catalogue.REGISTRY:
        raise KeyError(f"backing_check: no catalogue check {check_id!r}")
    return catalogue.run_check(catalogue.REGISTRY[check_id])


def check_report(outcome, derivation) -> str:
    """A check's steps, numbered, and its verdict as the last line (``PASSED`` or
    ``FAILED: why``); no timings, so that the same run reads the same."""
    lines = [f"{outcome.id} (label {outcome.label or '-'}, status {outcome.status})"]
    lines += [f"{n:>2}. {step.text}" for n, step in enumerate(derivation.steps, 1)]
    lines.append(_PASSED if outcome.passed else f"FAILED: {outcome.message}")
    return "\n".join(lines)


def demos_page(
    out: Path, folder: str | os.PathLike[str] = NOTEBOOKS, *, check_href=None, scenes=True
) -> str:
    """The body of the site's ``demos.html``: each lecture demo with its paragraph, a link
    to its notebook (copied to ``out/notebooks/``), to its scene's player and to its
    check, and the notebook's stored outputs (its plot, written as
    ``out/demo-NAME.png``, and its check's report).  Nothing is executed.

    ``check_href(check_id)`` gives the site's link to a check's section (None: no link);
    ``scenes``: the site has its scenes' players to link (False: the demo names its scene).
    """
    folder, out = Path(folder), Path(out)
    stale = stale_notebooks(folder)
    lines = [
        "<p>The lecture demos as Jupyter notebooks: each runs its scene, shows its plot, "
        "and runs the catalogue check that backs it. Download one and run it where "
        f"bodycheck is installed with its notebooks extra (<code>{html.escape(INSTALL)}"
        "</code>). Shown below is what each notebook stored when it was last executed "
        "(<code>bodycheck notebooks --write notebooks/</code>, run by "
        "<code>make checks</code>); the tests execute every notebook afresh.</p>",
        "<ul>" + "".join(f"<li><a href='#{d.name}'>{d.name}</a></li>" for d in LECTURE_DEMOS)
        + "</ul>",
    ]  # fmt: skip
    if stale:
        lines.append(
            "<p class='pending'>The notebooks are not current (run <code>make checks</code>): "
            + "; ".join(html.escape(s) for s in stale)
            + "</p>"
        )
    for d in LECTURE_DEMOS:
        name = html.escape(d.name)
        src = folder / f"{d.name}.ipynb"
        nb = _read(src) if src.is_file() else None
        parts = [f"<section id='{name}'><h2>{html.escape(d.topic)} ({name})</h2>"]
        parts.append(f"<p>{html.escape(d.paragraph)}</p>")
        links = [
            f"<a href='scenes.html#{name}'>the scene played</a>"
            if scenes
            else f"the scene {name} (not played: a site built without its scenes)"
        ]
        href = check_href(d.check) if check_href else None
        links.append(
            f"<a href='{html.escape(href)}'>the check {html.escape(d.check)}</a>"
            if href
            else f"the check {html.escape(d.check)}"
        )
        if nb is not None:
            (out / "notebooks").mkdir(exist_ok=True)
            shutil.copyfile(src, out / "notebooks" / src.name)
            links.insert(0, f"<a href='notebooks/{name}.ipynb' download>the notebook</a>")
        parts.append("<p>" + ", ".join(links) + "</p>")
        stored = stored_output(nb) if nb is not None else StoredOutput(None, None)
        if stored.png is not None:
            (out / f"demo-{d.name}.png").write_bytes(stored.png)
            parts.append(
                f"<p><img src='demo-{name}.png' alt='plots of the demo {name}, as its "
                "notebook stored them'></p>"
            )
        if stored.report is not None:
            verdict = "verified" if stored.passed else "erratum"
            parts.append(
                f"<p>The check, as the notebook ran it: <span class='{verdict}'>"
                f"{'passed' if stored.passed else 'not passed'}</span></p>"
                f"<pre>{html.escape(stored.report)}</pre>"
            )
        if nb is None:
            parts.append("<p class='pending'>no notebook (run <code>make checks</code>)</p>")
        parts.append("</section>")
        lines.append("\n".join(parts))
    return "\n".join(lines)
