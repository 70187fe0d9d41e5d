"""``bodycheck site``: the static site, its links, its MathML and a real browser.

The site is built once per module into a temporary folder. The link checker and the
MathML checks are pure Python and always run; the browser tests run headless
Chromium (``/usr/bin/chromium``, installed by ``.ci/run``) and are skipped with a
message saying how to install it where it is missing.

What the browser tests compare:

- every page loads: a harness page opens each in an iframe, in one browser run for
  many pages, and reads its title and heading (a check's page: its steps); Chromium
  logs no console message (``--enable-logging=stderr`` marks them ``CONSOLE``), e.g. no
  resource that failed to load; axe-core finds no accessibility violation;
- equations are rendered, not shown as markup: the DOM of a chapter page holds
  ``<math>`` elements, and its visible text holds no ``<math``, ``<mi>`` or
  ``&InvisibleTimes;``;
- the screenshots of the errata page and of a chapter page are not blank, and
  swapping the ``<math>`` elements for plain ``<span>`` elements (the negative
  control: the same tokens shown as text) changes the errata screenshot, so the
  browser lays the MathML out as mathematics.
"""

from __future__ import annotations

import html
import json
import re
import shutil
import subprocess
from pathlib import Path
from urllib.parse import quote

import numpy as np
import pytest

from identities.cli.main import main
from identities.cli.site import (
    MARKER,
    SiteError,
    broken_links,
    build_site,
    leaves_of_text,
    math_from_text,
)

CHROMIUM = Path("/usr/bin/chromium")
NO_CHROMIUM = "headless Chromium not found at /usr/bin/chromium (apt-get install -y chromium)"
#: a screenshot counts as not blank when this share of its pixels is not white: the
#: navigation bar and the title alone cover about 1 % of a 1200 x 900 page
MIN_INK = 0.005
#: a browser run that takes longer is hung (a page here loads in about a second)
BROWSER_TIMEOUT_S = 60


@pytest.fixture(scope="module")
def site(tmp_path_factory) -> Path:
    """The site with its scenes, built once per run for every worker (~13 s; the tests
    read it, and copy it to change it)."""
    from tests.conftest import shared_once

    return shared_once(tmp_path_factory, "site", lambda d: build_site(d / "out")) / "out"


def test_site_has_every_page_and_its_marker(site):
    names = {p.name for p in site.iterdir()}
    chapters = {f"ch{n}.html" for n in range(1, 9)}
    assert chapters | {"index.html", "errata.html", "scenes.html", "workprecision.html"} <= names
    assert MARKER in names
    assert {"scene-bouncing_ball.svg", "scene-heavy_top.svg", "workprecision.png"} <= names


def test_every_book_item_has_a_row_with_its_verdict(site):
    from identities.verify.catalogue import item_rows

    pages = {n: (site / f"ch{n}.html").read_text("utf-8") for n in range(1, 9)}
    for r in item_rows():
        row = re.search(f"<tr id='{re.escape(r.item.id)}'>.*?</tr>", pages[r.item.chapter])
        assert row, f"{r.item.id} has no row on ch{r.item.chapter}.html"
        assert f"class='{r.status}'>{r.status}<" in row.group(0), r.item.id


def test_every_link_of_the_site_resolves(site):
    assert broken_links(site) == []


def test_the_api_reference_is_built_into_api_and_linked_from_the_index(tmp_path, monkeypatch):
    """``build_site(api=True)`` builds the reference into ``api/`` (Sphinx, run by ``make
    docs`` and CI: stubbed here) and the index links it; a link of the reference that does
    not resolve fails the build, naming it."""
    import identities.cli.site as site_module

    def stub(out: Path, page: str = "<a href='../ch1.html#eq1.5'>(1.5)</a>") -> None:
        out.mkdir()
        (out / "index.html").write_text(f"<!DOCTYPE html><h1>api</h1>{page}", "utf-8")

    monkeypatch.setattr(site_module, "build_api", stub)
    build_site(tmp_path / "out", scenes=False, api=True)
    assert "href='api/index.html'" in (tmp_path / "out" / "index.html").read_text("utf-8")
    monkeypatch.setattr(site_module, "build_api", lambda out: stub(out, "<a href='x.html'>"))
    with pytest.raises(SiteError, match=r"1 links .* do not resolve:\napi/index.html: x.html"):
        build_site(tmp_path / "out", scenes=False, api=True)
    build_site(tmp_path / "plain", scenes=False)
    assert "api/index.html" not in (tmp_path / "plain" / "index.html").read_text("utf-8")


def test_the_api_reference_needs_its_sources_and_the_docs_extra(tmp_path, monkeypatch):
    import importlib.util

    from identities.cli.site import build_api

    with pytest.raises(SiteError, match=r"built from a source checkout: no .*conf\.py"):
        build_api(tmp_path / "api", docs=tmp_path / "nowhere")
    real = importlib.util.find_spec
    monkeypatch.setattr(
        importlib.util, "find_spec", lambda name, *a: None if name == "numpydoc" else real(name)
    )
    with pytest.raises(SiteError, match=r"needs [\w, ]*numpydoc[\w, ]*, not installed: .*\[docs\]"):
        build_api(tmp_path / "api")


def test_a_broken_cross_reference_fails_the_api_build_naming_page_and_target(tmp_path):
    """The reference's build is Sphinx with -n -W (``make docs``, CI): a reference to a name
    that is documented nowhere fails it, and the error names the page and the target
    (a one-page project stands in for docs/, whose full build takes a minute)."""
    from identities.cli.site import build_api, docs_extra_missing

    if missing := docs_extra_missing():  # the 3.13 leg has Sphinx (numpydoc's) but no myst
        pytest.skip(f"the API reference needs {', '.join(missing)}: pip install 'bodycheck[docs]'")

    docs = tmp_path / "docs"
    docs.mkdir()
    (docs / "conf.py").write_text("project = 'x'\nextensions = []\n", "utf-8")
    (docs / "index.rst").write_text(
        "Title\n=====\n\nSee :py:func:`mechanics.no_such_function`.\n", "utf-8"
    )
    with pytest.raises(SiteError, match=r"index\.rst.*mechanics\.no_such_function"):
        build_api(tmp_path / "api", docs=docs)
    (docs / "index.rst").write_text("Title\n=====\n\nSee nothing.\n", "utf-8")
    build_api(tmp_path / "api", docs=docs)
    assert (tmp_path / "api" / "index.html").is_file()


def test_the_link_checker_finds_a_broken_link(site, tmp_path):
    copy = tmp_path / "copy"
    shutil.copytree(site, copy)
    (copy / "errata.html").unlink()
    (copy / "extra.html").write_text("<a href='ch1.html#no-such-id'>x</a>", encoding="utf-8")
    broken = broken_links(copy)
    assert any("errata.html (no file)" in b for b in broken)
    assert any("no-such-id" in b for b in broken)


def test_the_errata_page_has_every_erratum_and_equations(site):
    from identities.verify.catalogue import checks

    text = (site / "errata.html").read_text("utf-8")
    for c in checks():
        if c.errata:
            assert f"#check-{c.id.replace('.', '-')}'" in text, c.id
    assert text.count("<math") >= 5


def test_mathml_keeps_the_texts_symbols_in_order():
    markup = math_from_text("T_p = 2π √(τ_0/J_z)")
    assert markup is not None
    assert markup.startswith("<math")
    assert "<msqrt>" in markup
    assert "<mfrac>" in markup
    assert "<mi>&pi;</mi>" in markup
    assert leaves_of_text("T_p = 2π √(τ_0/J_z)") == ["T", "p", "2", "π", "τ", "0", "J", "z"]


@pytest.mark.parametrize(
    ("text", "why"),
    [
        ("T = 2π √(2τ_0/(m R²))", "sympy prints R² before m: the order would differ"),
        ("E = ½ m v²", "sympy prints m v²/2: the ½ would move"),
        ("g = 9.8 kg/s²", "a decimal and a unit are outside the notation"),
        ("v_j(t + Δt) = 0", "f(x) could be a product or a function"),
        ("rod m = 75 kg", "prose"),
        ("x = (a", "unbalanced"),
    ],
)
def test_text_outside_the_notation_stays_text(text, why):
    assert math_from_text(text) is None, why


def test_a_folder_that_is_not_a_site_is_refused(tmp_path, capsys):
    out = tmp_path / "mine"
    out.mkdir()
    (out / "notes.txt").write_text("keep me", encoding="utf-8")
    assert main(["site", str(out)]) == 2
    err = capsys.readouterr().err
    assert str(out) in err
    assert MARKER in err
    assert "not a previous site" in err
    assert (out / "notes.txt").read_text(encoding="utf-8") == "keep me"


def test_a_previous_site_is_replaced(site, tmp_path):
    out = tmp_path / "again"
    shutil.copytree(site, out)
    (out / "stale.html").write_text("old", encoding="utf-8")
    build_site(out, scenes=False)
    assert not (out / "stale.html").exists()
    assert (out / MARKER).is_file()
    assert (out / "ch1.html").is_file()


def _chromium(
    tmp_path: Path, *args: str, timeout: float = BROWSER_TIMEOUT_S
) -> subprocess.CompletedProcess:
    profile = tmp_path / "profile"
    profile.mkdir(exist_ok=True)
    flags = [
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-quic",
        "--no-first-run",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-sync",
        f"--user-data-dir={profile}",
    ]
    return subprocess.run(
        [str(CHROMIUM), *flags, *args],
        capture_output=True,
        text=True,
        timeout=timeout,
        check=False,
    )


def _dump(tmp_path: Path, page: Path, query: str = "") -> tuple[str, list[str]]:
    """The rendered DOM of ``page`` (opened with ``query``, e.g. ``?q=x``) and Chromium's
    console messages."""
    uri = page.as_uri() + query
    run = _chromium(tmp_path, "--enable-logging=stderr", "--v=0", "--dump-dom", uri)
    assert run.returncode == 0, run.stderr[-2000:]
    return run.stdout, [line for line in run.stderr.splitlines() if "CONSOLE" in line]


def _rgb(png: Path) -> np.ndarray:
    """The pixels of ``png``, (height, width, 3) bytes (Pillow, matplotlib's own PNG
    reader: decoding to bytes rather than floats keeps a 1200 x 6000 shot cheap)."""
    from PIL import Image

    with Image.open(png) as im:
        return np.asarray(im.convert("RGB"))


def _ink(png: Path) -> float:
    """The share of pixels of ``png`` that are not white (a channel below 90 %)."""
    return float((_rgb(png).min(axis=-1) < 0.9 * 255).mean())


def _screenshot(tmp_path: Path, page: Path, png: Path, query: str = "") -> Path:
    uri = page.as_uri() + query
    run = _chromium(tmp_path, f"--screenshot={png}", "--window-size=1200,900", uri)
    assert run.returncode == 0, run.stderr[-2000:]
    assert png.is_file(), run.stderr[-2000:]
    return png


def _visible_text(dom: str) -> str:
    return html.unescape(re.sub(r"<[^>]+>", " ", dom))


needs_chromium = pytest.mark.skipif(not CHROMIUM.exists(), reason=NO_CHROMIUM)


#: every page of the site but the checks' own pages, all loaded (and checked by axe) in
#: make test
TOP_PAGES = (
    "index.html",
    *(f"ch{n}.html" for n in range(1, 9)),
    "errata.html",
    "named.html",
    "scenes.html",
    "demos.html",
    "workprecision.html",
    "search.html",
    "as-text.html",
)
#: the checks' pages (one per check, 211) loaded and checked by axe with them in `make
#: test`: an erratum, a property, a problem, a proof by witness and a named result; every
#: check page is loaded, and checked by axe, in the slow tier (below: axe takes ~1.5 s a
#: page, 5 min for all of them)
CHECK_SAMPLE = (
    "check-eq5-96.html",
    "check-thm-impact-momentum.html",
    "check-P5-4.html",
    "check-eq2-38.html",
    "check-thm-small-angle-stability.html",
)
PAGES = TOP_PAGES + CHECK_SAMPLE
#: the largest check page (eq2.74: 0.6 MB, 10⁵ elements of MathML), loaded in `make test`
#: with its steps and MathML, but axe-checked only in the slow tier with every check page:
#: axe alone takes 25–35 s over it (measured, one page in one browser run: 2.3 s loaded
#: without axe, 29 s with it), three quarters of every other page's axe time together
LARGEST_CHECK = "check-eq2-74.html"


def _check_page(check_id: str) -> str:
    """The file of a check's page of steps: check-ID.html, the id's dots as dashes."""
    return "check-" + re.sub(r"[^A-Za-z0-9-]", "-", check_id) + ".html"


def test_the_browser_tests_cover_every_page(site):
    from identities.verify.catalogue import checks

    names = {p.name for p in site.glob("*.html")}
    own = {_check_page(c.id) for c in checks()}
    assert names - own == set(TOP_PAGES)
    assert own <= names
    assert set(CHECK_SAMPLE) | {LARGEST_CHECK} <= own
    assert max(own, key=lambda name: (site / name).stat().st_size) == LARGEST_CHECK


def _flattened(page: Path) -> Path:
    """A copy of ``page`` beside the site with every MathML element turned into a
    ``<span>``: the same tokens, shown as plain text (the negative control)."""
    control = page.parent.parent / f"flat-{page.name}"
    text = page.read_text("utf-8")
    control.write_text(re.sub(r"<(/?)(?:math|m[a-z]+)\b[^>]*>", r"<\1span>", text), "utf-8")
    shutil.copy(page.parent / "style.css", control.parent / "style.css")
    return control


def _changed(a: Path, b: Path) -> float:
    """The share of pixels that differ between two screenshots of the same size (a
    channel by more than 10 %)."""
    x, y = _rgb(a), _rgb(b)
    assert x.shape == y.shape
    return float(((np.maximum(x, y) - np.minimum(x, y)).max(axis=-1) > 0.1 * 255).mean())


#: the share of pixels that must change when MathML becomes text: one stacked
#: fraction or root moves a line's worth of text (measured: 5.5 % on chapter 4 at
#: 1200 x 6000, 6.0 % on the errata page at 1200 x 900)
MIN_CHANGED = 0.001


@needs_chromium
def test_chapter_page_renders_mathml_not_its_markup(site, tmp_path):
    dom, _ = _dump(tmp_path, site / "ch4.html")
    assert dom.count("<math") >= 10
    visible = _visible_text(dom)
    for raw in ("<math", "<mi>", "<mfrac", "InvisibleTimes"):
        assert raw not in visible, raw


@needs_chromium
def test_chapter_page_shows_equations_laid_out(site, tmp_path):
    page = site / "ch4.html"
    # tall enough to reach the checks below the items table
    size = "--window-size=1200,6000"
    shots = []
    for source, name in ((page, "ch4.png"), (_flattened(page), "flat.png")):
        png = tmp_path / name
        run = _chromium(tmp_path, f"--screenshot={png}", size, source.as_uri())
        assert run.returncode == 0, run.stderr[-2000:]
        shots.append(png)
    assert _ink(shots[0]) > MIN_INK
    assert _changed(*shots) > MIN_CHANGED, "the chapter's MathML looks like plain text"


@needs_chromium
def test_a_derivations_page_shows_its_algebra_laid_out(site, tmp_path):
    """A check's page of steps (P5.4: 36 pieces of MathML), against the same page with
    its MathML flattened to text."""
    page = site / "check-P5-4.html"
    rendered = _screenshot(tmp_path, page, tmp_path / "p54.png")
    assert _ink(rendered) > MIN_INK
    flat = _screenshot(tmp_path, _flattened(page), tmp_path / "flat.png")
    assert _changed(rendered, flat) > MIN_CHANGED, "the steps' MathML looks like plain text"


@needs_chromium
def test_errata_screenshot_shows_mathml_laid_out(site, tmp_path):
    page = site / "errata.html"
    rendered = _screenshot(tmp_path, page, tmp_path / "errata.png")
    assert _ink(rendered) > MIN_INK
    flat = _screenshot(tmp_path, _flattened(page), tmp_path / "flat.png")
    assert _changed(rendered, flat) > MIN_CHANGED, "the errata's MathML looks like plain text"


# ---------------------------------------------------------------- the search box

NODE = shutil.which("node")
NO_NODE = "node not found (apt-get install -y nodejs): the search box's script runs under it"
#: queries of every kind: a known name (its checks first), words of titles and of the
#: book's headings, an accent dropped, an apostrophe, a section number, nothing found
QUERIES = (
    "parallel axis",
    "Bernoulli",
    "König",
    "euler's equations",
    "restitution",
    "physical pendulum",
    "4.3.1",
    "rocket",
    "no such topic zzz",
    "",
)
#: a query run in the browser, and the check it must find first
BROWSER_QUERIES = {"parallel axis": "eq4.38", "Bernoulli": "eq8.34"}


def test_every_page_has_the_search_box_and_search_html_lists_every_check(site):
    from identities.verify.catalogue import checks

    for page in site.glob("*.html"):
        text = page.read_text("utf-8")
        assert "<form id='search' role='search' action='search.html'>" in text, page.name
        assert "<script src='search.js' defer></script>" in text, page.name
    listed = set(re.findall(r"<code>([^<]+)</code></a>", (site / "search.html").read_text()))
    assert listed == {html.escape(c.id) for c in checks()}


@pytest.mark.skipif(NODE is None, reason=NO_NODE)
def test_the_search_box_finds_what_bodycheck_search_finds(site):
    """The page's script (run by node on the site's own index) against the command's
    search, query by query: the same checks in the same order."""
    from identities.verify import topics

    runner = (
        "const vm = require('vm'), fs = require('fs');"
        "const ctx = {window: {}}; vm.createContext(ctx);"
        "for (const f of ['search-index.js', 'search.js'])"
        "  vm.runInContext(fs.readFileSync(process.argv[1] + '/' + f, 'utf8'), ctx);"
        "const q = JSON.parse(process.argv[2]);"
        "console.log(JSON.stringify(q.map((x) =>"
        "  ctx.bodycheckSearch(ctx.window.BODYCHECK_SEARCH, x).map((c) => c.id))));"
    )
    run = subprocess.run(
        [NODE, "-e", runner, str(site), json.dumps(QUERIES)],
        capture_output=True,
        text=True,
        timeout=BROWSER_TIMEOUT_S,
        check=False,
    )
    assert run.returncode == 0, run.stderr[-2000:]
    got = json.loads(run.stdout)
    for q, ids in zip(QUERIES, got, strict=True):
        assert ids == [c.id for c in topics.search(q)], q
    assert got[0][0] == "eq4.38"
    assert got[-2] == []
    assert got[-1] == []


@needs_chromium
@pytest.mark.parametrize(("query", "first"), BROWSER_QUERIES.items())
def test_the_search_box_finds_in_the_browser(site, tmp_path, query, first):
    """A page opened with ?q= runs its query on load (as the form's submission without
    script lands): the results list in the rendered DOM, the expected check first."""
    dom, console = _dump(tmp_path, site / "ch1.html", "?q=" + quote(query))
    results = re.search(r"<ol id=\"search-results\"[^>]*>(.*?)</ol>", dom, re.S)
    assert results is not None, dom[:2000]
    ids = re.findall(r"<a href=\"[^\"]+\">([^ <]+) ", results.group(1))
    assert ids, dom[:2000]
    assert ids[0] == first, ids
    assert console == []


# ---------------------------------------------------------------- accessibility

AXE = Path(__file__).resolve().parent / "data" / "vendor" / "axe-core" / "axe.min.js"
#: tests/data/vendor/axe-core/SOURCE.md: the file as the npm registry ships it
AXE_SHA256 = "29348999450cdf2849a8e70b7912fc2da85a849da39c0d0d5394f51d4a9ed95c"
# ---------------------------------------------------------------- scenes that play


def test_the_scenes_page_has_a_player_for_every_built_in_scene(site):
    from mechanics.scenes import builtin_scenes

    text = (site / "scenes.html").read_text("utf-8")
    for name in builtin_scenes():
        assert f"<section class='scene' id='{name}'>" in text, name
    assert text.count("class='scene-data'") == len(builtin_scenes())
    assert (site / "scene-player.js").is_file()


def test_a_scene_whose_run_fails_is_shown_with_its_failure(tmp_path, monkeypatch):
    """A site of two built-in scenes, one whose run fails: that one's section says so and
    why, the other's has its player (the other 16 scenes are not the subject)."""
    import identities.book.scenes.compare as compare
    import identities.cli.site as site_module
    from mechanics.scenes import SceneError
    from mechanics.scenes import builtin_scenes as every_scene

    two = {n: p for n, p in every_scene().items() if n in ("box_drop", "bouncing_ball")}
    assert len(two) == 2
    monkeypatch.setattr(site_module, "_built_in_scenes", lambda: two)

    real = compare.run_book_scene

    def run(scene):
        if scene.name.startswith("Box dropped") or scene.source.endswith("box_drop.toml"):
            raise SceneError(scene.source, "scene.duration", "a failure for the test")
        return real(scene)

    monkeypatch.setattr(compare, "run_book_scene", run)
    build_site(tmp_path / "out")
    text = (tmp_path / "out" / "scenes.html").read_text("utf-8")
    failed = re.search(r"<section id='box_drop'>.*?</section>", text, re.S)
    assert failed is not None
    assert "the run failed" in failed.group(0)
    assert "a failure for the test" in failed.group(0)
    ran = re.search(r"<section class='scene' id='bouncing_ball'>.*?</section>", text, re.S)
    assert ran is not None
    assert "the run failed" not in ran.group(0)
    assert "<svg class='stage'" in ran.group(0)


def _bodies_at(tmp_path: Path, page: Path, frame: int) -> dict[str, str]:
    """Each player's frame and drawn bodies (its <g class="bodies">) in the DOM of
    ``page`` opened at ?frame=N."""
    dom, _ = _dump(tmp_path, page, f"?frame={frame}")
    out = {}
    for m in re.finditer(
        r'<section class="scene" id="([^"]+)"[^>]*data-frame="(\d+)".*?<g class="bodies">(.*?)</g>',
        dom,
        re.S,
    ):
        out[m.group(1)] = (int(m.group(2)), m.group(3))
    return out


@needs_chromium
def test_every_player_draws_its_bodies_and_a_moving_scene_changes_between_two_frames(
    site, tmp_path
):
    from mechanics.scenes import builtin_scenes

    first = _bodies_at(tmp_path, site / "scenes.html", 0)
    later = _bodies_at(tmp_path, site / "scenes.html", 40)
    assert set(first) == set(builtin_scenes())
    for name, (frame, drawn) in first.items():
        assert frame == 0, name
        assert later[name][0] == 40, name
        assert "<circle" in drawn or "<polyline" in drawn, name
    for name in ("bouncing_ball", "box_drop", "heavy_top", "newtons_cradle"):
        assert first[name][1] != later[name][1], name


@needs_chromium
def test_a_players_picture_changes_between_two_slider_positions(tmp_path):
    """The standalone page of ``bodycheck demo box_drop --html``: the screenshots at the
    first frame and at frame 60 differ (the box has fallen), and neither is blank."""
    page = tmp_path / "box.html"
    assert main(["demo", "box_drop", "--html", str(page)]) == 0
    shots = []
    for frame in (0, 60):
        png = _screenshot(tmp_path, page, tmp_path / f"box{frame}.png", f"?frame={frame}")
        assert _ink(png) > MIN_INK
        shots.append(_rgb(png))
    assert (shots[0] != shots[1]).any(axis=-1).mean() > MIN_INK / 10


# ------------------------------------------------------- the checks' steps (algebra)


def _section(site: Path, c) -> str:
    """The section of a check on its own page (``check-ID.html``)."""
    page = (site / _check_page(c.id)).read_text("utf-8")
    anchor = _check_page(c.id).removesuffix(".html")
    m = re.search(f"<section id='{re.escape(anchor)}'>(.*?)</section>", page, re.S)
    assert m, f"{c.id}: no section"
    return m.group(1)


def test_every_checks_section_shows_its_stored_steps(site):
    """What ``bodycheck explain`` prints is on the page: one list item per recorded step,
    with its text, and the step's rendered algebra as the MathML the record holds."""
    from identities.verify import record
    from identities.verify.catalogue import checks

    for c in checks():
        section = _section(site, c)
        chapter = (site / (f"ch{c.chapter}.html" if c.chapter else "named.html")).read_text()
        assert f"<a href='{_check_page(c.id)}'>the derivation" in chapter
        rec, _ = record.load(c.id, c.chapter)
        items = re.findall(r"<li class='step (\w+)'>", section)
        assert items == [s["kind"] for s in rec["steps"]], c.id
        for step in rec["steps"]:
            assert html.escape(step["text"]) in section, (c.id, step["text"])
            for _, piece in record._pieces(step):
                if "mathml" in piece:
                    assert piece["mathml"] in section, c.id


def test_a_proofs_section_shows_both_sides_the_rule_and_the_rejected_point(site):
    from identities.verify.catalogue import load_all

    section = _section(site, load_all()["eq4.38"])
    assert re.search(r"</math><p>(equals, by|reduces to 0 by) <code>\w+</code>", section)
    assert "is not (<code>" in section or "is not 0" in section
    assert "false at the exact point <math" in section


def test_the_errata_page_shows_the_derived_and_printed_forms_side_by_side(site):
    from identities.verify.catalogue import checks

    text = (site / "errata.html").read_text("utf-8")
    n = sum(bool(c.errata) for c in checks())
    tables = re.findall(
        r"<table class='forms'><tr><th>derived</th><th>printed \(false\)</th></tr>"
        r"<tr><td><math.*?</math></td><td><math.*?</math></td></tr></table>",
        text,
        re.S,
    )
    assert len(tables) >= n


def test_pieces_shown_as_text_are_listed_by_the_build(tmp_path, monkeypatch, capsys):
    """A piece sympy could not print is shown as its text and named on as-text.html and
    by the command; a check with no stored record is named too."""
    from identities.verify import record

    real = record.load

    def load(check_id, chapter):
        rec, versions = real(check_id, chapter)
        if check_id == "eq4.38":
            steps = [dict(rec["steps"][0], lhs={"text": "J(x)", "why": "printer failed"})]
            return dict(rec, steps=steps + rec["steps"][1:]), versions
        if check_id == "eq4.47":
            return None, versions
        return rec, versions

    monkeypatch.setattr(record, "load", load)
    out = tmp_path / "site"
    listed: list[str] = []
    build_site(out, scenes=False, listed=listed)
    assert "eq4.38 step 1 lhs: printer failed" in listed
    assert "eq4.47: no stored record" in listed
    import identities.cli.site as site_module

    real_build = site_module.build_site  # the command, without its scenes (not the subject)
    monkeypatch.setattr(
        site_module, "build_site", lambda o, **kw: real_build(o, scenes=False, **kw)
    )
    capsys.readouterr()
    assert main(["site", str(out)]) == 0
    said = capsys.readouterr().out
    assert f"{len(listed)} pieces of algebra shown as text" in said
    page = (out / "as-text.html").read_text("utf-8")
    assert "eq4.38 step 1 lhs: printer failed" in page
    assert "eq4.47: no stored record" in page
    steps = (out / "check-eq4-38.html").read_text("utf-8")
    assert "<pre class='as-text' title='printer failed'>J(x)</pre>" in steps
    assert "its steps are not stored" in (out / "check-eq4-47.html").read_text("utf-8")


# ----------------------------------------------- pages in one browser run, with axe

#: one browser run over many pages: each page opened in turn in an iframe of a harness
#: page beside them (file:// pages may read each other with
#: --allow-file-access-from-files), axe-core run in it after its own scripts, what was
#: seen written into a <pre> that --dump-dom shows.  A browser run costs ~1 s to start, so
#: one run for many pages rather than one per page (the 18 pages of make test took 116 s
#: of CPU one browser each, 2 runs now; measured, issue 35)
HARNESS = """<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'><title>every page</title>
</head><body><main><h1>every page</h1></main><script>
var pages = PAGES, axe_too = AXE, out = {};
function done(i, f, what) { out[pages[i]] = what; f.remove(); next(i + 1); }
function next(i) {
  if (i >= pages.length) {
    var pre = document.createElement('pre'); pre.id = 'result';
    pre.textContent = JSON.stringify(out); document.body.appendChild(pre); return;
  }
  var f = document.createElement('iframe'); f.src = pages[i];
  f.style.width = '1200px'; f.style.height = '900px';
  f.onload = function () {
    var d = f.contentDocument;
    if (!d) { done(i, f, {error: 'no document (not found, or not readable)'}); return; }
    var seen = {title: d.title, h1: d.getElementsByTagName('h1').length,
                math: d.getElementsByTagName('math').length,
                steps: d.querySelectorAll('li.step').length};
    if (!axe_too) { done(i, f, seen); return; }
    var s = d.createElement('script'); s.src = 'axe.min.js';
    s.onload = function () {
      f.contentWindow.axe.run(d, {resultTypes: ['violations']}).then(function (r) {
        seen.violations = r.violations.map(function (v) {
          return {id: v.id, impact: v.impact, nodes: v.nodes.length}; });
        done(i, f, seen);
      }, function (e) { seen.error = String(e); done(i, f, seen); });
    };
    d.body.appendChild(s);
  };
  document.body.appendChild(f);
}
next(0);
</script></body></html>"""
#: a harness run over every page with axe (5 min measured beside other work); a run
#: that takes longer is hung
ALL_PAGES_TIMEOUT_S = 1200
#: each run over many pages is split in this many parts, one browser each, which
#: pytest-xdist spreads over the cores
PARTS = 2


def _part(site: Path, pages, part: int) -> list[str]:
    """The ``part``-th of :data:`PARTS` shares of ``pages``, dealt from the largest file
    down, so that each browser run gets its share of the large pages (axe's time grows
    with a page's size)."""
    by_size = sorted(pages, key=lambda name: -(site / name).stat().st_size)
    return by_size[part::PARTS]


def _in_one_browser(
    site: Path, tmp_path: Path, pages: list[str], *, axe: bool = True,
    replaced: dict[str, str] | None = None,
) -> tuple[dict, list[str]]:  # fmt: skip
    """What the harness saw of each of ``pages`` of ``site`` (opened in this order), and
    Chromium's console messages (each names the page that logged it).  The pages are
    read through links to the site's files in a folder of the test's own, beside the
    harness and axe; ``replaced`` gives some of them (or new ones) other text there."""
    import hashlib

    assert hashlib.sha256(AXE.read_bytes()).hexdigest() == AXE_SHA256
    here = tmp_path / "all"
    here.mkdir()
    for f in site.iterdir():
        (here / f.name).symlink_to(f)
    for name, text in (replaced or {}).items():
        (here / name).unlink(missing_ok=True)
        (here / name).write_text(text, "utf-8")
    shutil.copyfile(AXE, here / "axe.min.js")
    harness = here / "every-page.html"
    harness.write_text(
        HARNESS.replace("PAGES", json.dumps(pages)).replace("AXE", json.dumps(axe)), "utf-8"
    )
    run = _chromium(
        tmp_path, "--allow-file-access-from-files", "--enable-logging=stderr", "--v=0",
        "--virtual-time-budget=60000", "--dump-dom", harness.as_uri(),
        timeout=ALL_PAGES_TIMEOUT_S,
    )  # fmt: skip
    assert run.returncode == 0, run.stderr[-2000:]
    found = re.search(r'<pre id="result">(.*?)</pre>', run.stdout, re.S)
    assert found is not None, (
        f"the harness did not finish: {run.stdout[-600:]}\n{run.stderr[-1500:]}"
    )
    seen = json.loads(html.unescape(found.group(1)))
    assert list(seen) == pages
    return seen, [line for line in run.stderr.splitlines() if "CONSOLE" in line]


def _assert_page_sound(name: str, seen: dict, *, axe: bool = True) -> None:
    """What a page of the site must show in the browser: its title and one heading; a
    check's page one list item per recorded step and MathML wherever its record holds
    some; and, where axe ran, no violation."""
    from identities.verify import record
    from identities.verify.catalogue import checks

    assert "error" not in seen, (name, seen)
    assert seen["title"], (name, seen)
    assert seen["h1"] == 1, (name, seen)
    own = {_check_page(c.id): c for c in checks()}
    if name in own:
        c = own[name]
        rec, _ = record.load(c.id, c.chapter)
        assert seen["title"] == f"{c.id}: {c.title}", (name, seen)
        assert seen["steps"] == len(rec["steps"]), (name, seen)
        if record.mathml_count(rec):
            assert seen["math"] > 0, (name, seen)
    if axe:
        assert seen["violations"] == [], (name, seen)


@needs_chromium
@pytest.mark.parametrize("part", range(PARTS))
def test_every_page_loads_without_console_messages_and_axe_finds_no_violation(site, tmp_path, part):
    """Every page but the checks' own (:data:`TOP_PAGES`) and :data:`CHECK_SAMPLE`, in
    :data:`PARTS` browser runs: each loads without a console message (e.g. no resource
    that failed to load, no script error), shows its title and heading (a check's page its
    steps), and axe-core finds no violation."""
    pages = _part(site, PAGES, part)
    seen, console = _in_one_browser(site, tmp_path, pages)
    assert console == []
    for name in pages:
        _assert_page_sound(name, seen[name])


@needs_chromium
def test_the_largest_check_page_loads_with_its_steps_and_its_mathml(site, tmp_path):
    """:data:`LARGEST_CHECK` loads without a console message, with its title, heading,
    steps and MathML (axe over it runs in the slow tier, below)."""
    seen, console = _in_one_browser(site, tmp_path, [LARGEST_CHECK], axe=False)
    assert console == []
    _assert_page_sound(LARGEST_CHECK, seen[LARGEST_CHECK], axe=False)
    assert seen[LARGEST_CHECK]["math"] > 0


@pytest.mark.slow
@needs_chromium
@pytest.mark.parametrize("part", range(PARTS))
def test_every_check_page_loads_with_its_steps_and_axe_finds_no_violation(site, tmp_path, part):
    """Slow tier (~5 min of one core: axe over 211 pages of MathML, ~1.5 s a page, in
    :data:`PARTS` parts): every check's page loads without a console message, with its
    title, one list item per recorded step and MathML wherever its record holds some, and
    axe-core finds no violation."""
    from identities.verify.catalogue import checks

    pages = _part(site, [_check_page(c.id) for c in checks()], part)
    seen, console = _in_one_browser(site, tmp_path, pages)
    assert console == []
    for name in pages:
        _assert_page_sound(name, seen[name])


@needs_chromium
def test_the_browser_run_sees_a_console_error_a_page_without_steps_and_violations(site, tmp_path):
    """The negative control of both runs above, in one browser run of their harness: a
    script's console error is logged naming its page; an image without text and an
    unlabelled field are axe violations; a check's page with its steps cut, one with an
    unlabelled field, a top page without its heading and a page that is not there each
    fail the pages' check; an untouched check page passes it."""
    bare = "<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'><title>x</title></head>"
    steps_cut = re.sub(
        r"<ol class='steps'>.*?</ol>", "", (site / "check-P5-4.html").read_text("utf-8"),
        flags=re.S,
    )  # fmt: skip
    field = (site / "check-eq2-38.html").read_text("utf-8")
    replaced = {
        "bad-console.html": bare + "<body><main><h1>x</h1><script>console.error('boom')"
        "</script></main></body></html>",
        "bad-axe.html": bare + "<body><main><h1>x</h1><img src='x.png'><input type='text'>"
        "</main></body></html>",
        "check-P5-4.html": steps_cut,
        "check-eq2-38.html": field.replace("</main>", "<input type='text'></main>"),
        "index.html": re.sub(r"<h1>.*?</h1>", "", (site / "index.html").read_text("utf-8")),
    }
    pages = [*replaced, "missing.html", "check-E5-1.html"]
    seen, console = _in_one_browser(site, tmp_path, pages, replaced=replaced)
    assert any("boom" in line and "bad-console.html" in line for line in console), console
    found = {v["id"]: v["impact"] for v in seen["bad-axe.html"]["violations"]}
    assert found.get("image-alt") == "critical"
    assert found.get("label") == "critical"
    assert seen["check-P5-4.html"]["steps"] == 0
    assert "error" in seen["missing.html"]
    for name in (
        "bad-axe.html",
        "check-P5-4.html",
        "check-eq2-38.html",
        "index.html",
        "missing.html",
    ):
        with pytest.raises(AssertionError):
            _assert_page_sound(name, seen[name])
    assert {v["id"] for v in seen["check-eq2-38.html"]["violations"]} >= {"label"}
    _assert_page_sound("check-E5-1.html", seen["check-E5-1.html"])


def test_scenes_run_in_worker_processes_give_the_same_sections(site, tmp_path, monkeypatch):
    """``bodycheck site`` runs the scenes in worker processes (``jobs``): three of them,
    built so, are the sections the one-process build (the ``site`` fixture) wrote."""
    import identities.cli.site as site_module
    from mechanics.scenes import builtin_scenes

    real = builtin_scenes()
    three = {n: real[n] for n in ("rocket", "bouncing_ball", "tank_draining")}
    monkeypatch.setattr(site_module, "_built_in_scenes", lambda: three)
    build_site(tmp_path / "out", jobs=2)

    def sections(page: Path) -> dict[str, str]:
        text = page.read_text("utf-8")
        return {
            n: re.search(f"<section class='scene' id='{n}'.*?</section>", text, re.S).group(0)
            for n in three
        }

    assert sections(tmp_path / "out" / "scenes.html") == sections(site / "scenes.html")
    assert (tmp_path / "out" / "scene-bouncing_ball.svg").is_file()
