"""The book as pages: ``bodycheck site OUT/`` writes a static site (no server, no
network, no JavaScript): an index, one page per chapter with every book item, its
verdict and its check, the errata on one page, a few built-in scenes with their
plots, the lecture demos' notebooks with the outputs they stored
(:mod:`identities.cli.notebooks`; none is executed here), and the work-precision plot.

Conventions
-----------
- The verdict of an item is the registry's static status (``verified``, ``erratum``,
  ``definition``, ``pending``), as in CHECKS.md; building the site runs no proof
  (``bodycheck check`` does), only the few scenes whose plots it shows.
- Equations are MathML printed by sympy (``printer="presentation"``), which current
  browsers render offline. A piece of a check's text is shown as MathML only when it
  is an equation chain in the small notation :func:`math_from_text` reads (one-letter
  symbols with subscripts, Greek letters, integers, ``+ − / ² ³ √( ) ½``, products
  written by juxtaposition) *and* the rendering keeps the text's symbols and numbers
  in the text's order (:func:`leaves_of_text` against :func:`leaves_of_mathml`);
  everything else is shown as the text itself. So a rendering never differs from the
  text it stands for, beyond layout (fractions stacked, roots drawn).
- The output folder holds a marker file :data:`MARKER`: a folder that exists, is not
  empty and lacks it is refused (it is not a previous site); a previous site is
  replaced.
- Every link is relative, so the folder can be copied anywhere and opened with
  ``file://``.
"""

from __future__ import annotations

import functools
import html
import json
import multiprocessing
import re
import shutil
import subprocess
import sys
import tempfile
import tokenize
from collections import defaultdict
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path
from urllib.parse import unquote, urlsplit

__all__ = [
    "MARKER",
    "SCENES",
    "SiteError",
    "as_text",
    "broken_links",
    "build_api",
    "build_site",
    "leaves_of_mathml",
    "leaves_of_text",
    "math_from_text",
]

#: the marker file that says "this folder is a bodycheck site"
MARKER = ".bodycheck-site"
#: built-in scenes shown with their plots (each runs in well under a second)
SCENES = ("bouncing_ball", "heavy_top", "free_top_flip")
#: the work-precision plot of the committed study (``make bench`` rewrites it)
_BENCH = Path(__file__).resolve().parents[2] / "docs" / "bench"
#: the search box's script (identities/data/site_search.js)
_SEARCH_JS = Path(__file__).resolve().parents[1] / "data" / "site_search.js"
#: the scene players' script (identities/data/scene_player.js)
_PLAYER_JS = Path(__file__).resolve().parents[1] / "data" / "scene_player.js"

_GREEK = {
    "α": "alpha",
    "β": "beta",
    "γ": "gamma",
    "δ": "delta",
    "ε": "epsilon",
    "θ": "theta",
    "κ": "kappa",
    "λ": "lamda",
    "μ": "mu",
    "ν": "nu",
    "ξ": "xi",
    "ρ": "rho",
    "σ": "sigma",
    "τ": "tau",
    "φ": "phi",
    "χ": "chi",
    "ψ": "psi",
    "ω": "omega",
    "Ω": "Omega",
    "Φ": "Phi",
    "Ψ": "Psi",
    "Δ": "Delta",
    "Γ": "Gamma",
    "Λ": "Lamda",
    "Θ": "Theta",
    "ℓ": "ell",
}
#: one token of the notation: a symbol (letter, optional digits or _subscript), an
#: integer, an operator, a parenthesis, a power sign, a root or a half
_TOKEN = re.compile(
    r"\s*(?:(?P<sym>[A-Za-z" + "".join(_GREEK) + r"](?:_[A-Za-z0-9]+|[0-9]+)?)"
    r"|(?P<num>[0-9]+)|(?P<op>[-+/=])|(?P<open>\()|(?P<close>\))|(?P<pow>[²³])"
    r"|(?P<root>√\()|(?P<half>½)|(?P<pi>π))"
)
#: a trailing book reference such as "(3.76)" or "(5.50)-(5.52)"
_REF = re.compile(r"\s*(\(\d\.\d+\)(?:\s*-\s*\(\d\.\d+\))?)\s*$")


class SiteError(ValueError):
    """The site cannot be written where it was asked (the message says why)."""


def _ascii(text: str) -> tuple[str, dict] | None:
    """``text`` in sympy's input syntax, products made explicit, with the symbols it
    names; None when ``text`` is not in the notation (prose, decimals, dots, …)."""
    import sympy as sp

    text = text.replace("−", "-").strip()
    out: list[str] = []
    names: dict[str, object] = {}
    pos, prev = 0, None  # prev: did the last token end an operand?
    while pos < len(text):
        m = _TOKEN.match(text, pos)
        if m is None or m.end() == pos:
            return None
        pos = m.end()
        kind = m.lastgroup
        starts_operand = kind in ("sym", "num", "open", "root", "half", "pi")
        if starts_operand and prev:
            out.append("*")  # a product written by juxtaposition
        if kind == "sym":
            word = m.group("sym")
            if pos < len(text) and text[pos] == "(":
                return None  # f(x) or f·(x): ambiguous, shown as text
            key = "s" + str(len(names))
            names[key] = sp.Symbol(word)
            out.append(key)
        elif kind == "num":
            out.append(m.group("num"))
        elif kind == "pi":
            out.append("pi")
        elif kind == "half":
            out.append("(1/2)")
        elif kind == "root":
            out.append("sqrt(")
        elif kind == "pow":
            out.append("**" + {"²": "2", "³": "3"}[m.group("pow")])
        else:
            out.append(m.group(kind))
        prev = kind in ("sym", "num", "close", "pow", "half", "pi")
    return "".join(out), names


def leaves_of_text(text: str) -> list[str]:
    """The symbols' letters and subscripts and the numbers of ``text``, in order
    (``m_0`` gives ``m``, ``0``; ``v²`` gives ``v``, ``2``; ``½`` gives ``1``, ``2``)."""
    out: list[str] = []
    for m in _TOKEN.finditer(text.replace("−", "-")):
        kind = m.lastgroup
        if kind == "sym":
            word = m.group("sym")
            head, _, sub = word.partition("_")
            if not sub:
                head, sub = re.match(r"(\D)(\d*)$", word).groups()
            out += [head, sub] if sub else [head]
        elif kind == "num":
            out.append(m.group("num"))
        elif kind == "pow":
            out.append({"²": "2", "³": "3"}[m.group("pow")])
        elif kind == "half":
            out += ["1", "2"]
        elif kind == "pi":
            out.append("π")
    return out


def leaves_of_mathml(markup: str) -> list[str]:
    """The contents of the ``<mi>`` and ``<mn>`` elements of ``markup``, in order."""
    return [html.unescape(t) for t in re.findall(r"<m[in]>([^<]*)</m[in]>", markup)]


def math_from_text(text: str) -> str | None:
    """``text`` (an expression or an equation chain ``A = B = …``) as a ``<math>`` element, or None
    when it is outside the notation or sympy's rendering would not keep its symbols
    and numbers in order (see the module's Conventions)."""
    import sympy as sp
    from sympy.printing.mathml import mathml

    sides = text.split("=")
    if not all(s.strip() for s in sides):
        return None
    parts = []
    for side in sides:
        read = _ascii(side)
        if read is None:
            return None
        source, names = read
        try:
            expr = sp.parse_expr(source, local_dict=names, evaluate=False)
        except (SyntaxError, TypeError, ValueError, tokenize.TokenError):
            return None
        parts.append(mathml(expr, printer="presentation", order="none"))
    markup = "<mo>=</mo>".join(parts)
    if leaves_of_mathml(markup) != leaves_of_text(text):
        return None
    return f'<math display="inline"><mrow>{markup}</mrow></math>'


def _equation(text: str) -> str | None:
    """An equation chain as HTML: one ``<math>`` when the whole chain renders, else
    each side that renders as its own ``<math>`` and the others as text; None when no
    side with an operation renders (a lone symbol in MathML beside text is no help)."""
    whole = math_from_text(text)
    if whole is not None:
        return whole
    sides = [s.strip() for s in text.split("=")]
    shown = [math_from_text(s) if s else None for s in sides]
    if not any(m is not None and "<mo>" in m for m in shown):
        return None
    return " = ".join(html.escape(s) if m is None else m for s, m in zip(sides, shown, strict=True))


@functools.cache
def _rich(text: str) -> str:
    """``text`` as HTML: its equation pieces (between ``,``, ``;`` and ``:``) as MathML
    where :func:`math_from_text` renders them, the rest escaped."""
    out = []
    for piece in re.split(r"([,;:]\s+)", text):
        body, ref = piece, ""
        m = _REF.search(piece)
        if m:
            body, ref = piece[: m.start()], " " + m.group(1)
        rendered = _equation(body.strip()) if "=" in body else None
        if rendered is None:
            out.append(html.escape(piece))
        else:
            lead = body[: len(body) - len(body.lstrip())]
            out.append(html.escape(lead) + rendered + html.escape(ref))
    return "".join(out)


_CSS = """
body { font-family: sans-serif; max-width: 72em; margin: 1em auto; padding: 0 1em;
       color: #111; background: #fff; line-height: 1.4; }
nav a { margin-right: 1em; }
table { border-collapse: collapse; width: 100%; }
th, td { border-bottom: 1px solid #ccc; padding: 0.25em 0.5em; text-align: left;
         vertical-align: top; }
.verified { color: #176117; } .erratum { color: #a01010; font-weight: bold; }
.definition { color: #444; } .pending { color: #a06000; }
math { font-size: 1.1em; }
ol.steps > li { margin-bottom: 0.6em; }
.algebra { margin-left: 1.5em; overflow-x: auto; }
.algebra p, .point { margin: 0.2em 0; color: #333; }
pre.as-text { white-space: pre-wrap; font-size: 0.85em; background: #f4f4f4; }
table.forms { width: auto; }
code { font-size: 0.9em; }
img { max-width: 100%; }
"""


def _page(title: str, body: str, chapters: list[int]) -> str:
    nav = " ".join(
        ['<a href="index.html">index</a>']
        + [f'<a href="ch{c}.html">chapter {c}</a>' for c in chapters]
        + [
            '<a href="errata.html">errata</a>',
            '<a href="scenes.html">scenes</a>',
            '<a href="demos.html">lecture demos</a>',
            '<a href="workprecision.html">work-precision</a>',
        ]
    )
    return (
        "<!DOCTYPE html>\n<html lang='en'><head><meta charset='utf-8'>"
        f"<title>{html.escape(title)}</title>"
        "<link rel='stylesheet' href='style.css'>"
        "<script src='search-index.js' defer></script><script src='search.js' defer></script>"
        "<script src='scene-player.js' defer></script>"
        "</head>\n"
        f"<body><header><nav>{nav}</nav>\n{_SEARCH_BOX}</header>\n"
        f"<main><h1>{html.escape(title)}</h1>\n{body}\n</main></body></html>\n"
    )


#: the search box of every page: with JavaScript it lists the matches under it; without,
#: the form opens search.html, which lists every check with its topic words
_SEARCH_BOX = (
    "<form id='search' role='search' action='search.html'>"
    "<label for='search-query'>search the checks</label> "
    "<input id='search-query' type='search' name='q' placeholder='parallel axis, Bernoulli'> "
    "<button type='submit'>search</button> <span id='search-status' aria-live='polite'>"
    "</span></form>\n<ol id='search-results'></ol>"
)


def _check_href(c) -> str:
    """The page and anchor of a check's section."""
    page = f"ch{c.chapter}.html" if c.chapter else "named.html"
    return f"{page}#{_check_anchor(c.id)}"


def search_index(regs) -> dict:
    """What the search box searches (``search-index.js``): each check's id, title, page
    and topic words (:func:`identities.verify.topics.topic_text`, normalised as
    ``bodycheck search`` does), and the well-known names with their checks."""
    from identities.verify import topics

    return {
        "checks": [
            {
                "id": c.id,
                "title": c.title,
                "href": _check_href(c),
                "words": " ".join(topics.topic_words(c)),
            }
            for c in regs
        ],
        "names": [[name, list(ids)] for name, ids in topics.NAMES.items()],
    }


def _search_page(index: dict) -> str:
    """search.html: every check with its topic words (what the box searches; without
    JavaScript, the page to search with the browser's find)."""
    rows = [
        "<p>Type in the box above; without JavaScript, find in this page: every check "
        "with its topic words (its title and statement, the headings of the book's "
        "sections it stands in, the names it is known by).</p>",
        "<table><tr><th>check</th><th>topic words</th></tr>",
    ]
    for c in index["checks"]:
        rows.append(
            f"<tr><td><a href='{html.escape(c['href'])}'><code>{html.escape(c['id'])}</code>"
            f"</a> {html.escape(c['title'])}</td><td>{html.escape(c['words'])}</td></tr>"
        )
    rows.append("</table>")
    return "\n".join(rows)


def _check_anchor(check_id: str) -> str:
    return "check-" + re.sub(r"[^A-Za-z0-9-]", "-", check_id)


def _chapter_page(ch: int, rows: list, regs: list) -> str:
    lines = [
        "<p>Every numbered equation (eq), worked example (E) and problem (P) of the "
        "chapter, its verdict and the check behind it. Verdicts as in CHECKS.md: "
        "<span class='verified'>verified</span> (a check proves or reproduces it), "
        "<span class='erratum'>erratum</span> (the printed form is shown false, the "
        "corrected form proved), <span class='definition'>definition</span>.</p>",
        "<h2>Items</h2>",
        "<table><tr><th>item</th><th>page</th><th>section</th><th>verdict</th><th>check</th></tr>",
    ]
    for r in rows:
        cells = []
        for c in r.checks:
            cells.append(
                f"<a href='{_check_href(c)}'><code>{html.escape(c.id)}</code></a> "
                f"{html.escape(c.title)}"
            )
        lines.append(
            f"<tr id='{r.item.id}'><td>{r.item.id}</td><td>{r.item.page}</td>"
            f"<td>{html.escape(r.item.section)}</td><td class='{r.status}'>{r.status}</td>"
            f"<td>{'<br>'.join(cells) or '-'}</td></tr>"
        )
    lines.append("</table>")
    lines.append("<h2>Checks</h2>")
    lines += [_check_block(c) for c in regs if c.chapter == ch]
    return "\n".join(lines)


def _check_page_name(check_id: str) -> str:
    """The page of a check's derivation, step by step (one page per check: a chapter's
    algebra on one page is megabytes of MathML)."""
    return _check_anchor(check_id) + ".html"


def _check_page(c) -> str:
    """A check's own page: its section with every step, and the way back."""
    back = f"ch{c.chapter}.html" if c.chapter else "named.html"
    where = f"chapter {c.chapter}" if c.chapter else "the named results"
    return f"<p>Back to <a href='{back}#{_check_anchor(c.id)}'>{where}</a>.</p>\n" + _check_block(
        c, steps=True, level=2
    )


def _check_block(c, *, steps: bool = False, level: int = 3) -> str:
    """A check's section (its heading at ``level``): what it covers, its statement (and
    an erratum's forms), and its steps (``steps``) or a link to its page of steps."""
    parts = [
        f"<section id='{_check_anchor(c.id)}'><h{level}><code>{html.escape(c.id)}</code> "
        f"{html.escape(c.title)}</h{level}>",
        f"<p>kind: {c.kind}; verdict: <span class='{c.status}'>{c.status}</span>; "
        f"covers: {html.escape(', '.join(c.covers) or '-')}"
        + (f"; uses definitions {html.escape(', '.join(c.defines))}" if c.defines else "")
        + f"; code: <code>{html.escape(c.where)}</code></p>",
    ]
    if c.statement:
        parts.append(f"<p class='statement'>{_rich(c.statement)}</p>")
    if c.reading:
        parts.append(f"<p>reading of the text: {_rich(c.reading)}</p>")
    if c.errata:
        parts.append(
            f"<p class='erratum'>printed (false): {_rich(c.printed)}</p>"
            f"<p>corrected: {_rich(c.corrected)}</p>"
        )
    parts.append(_derivation(c, level + 1) if steps else _steps_link(c))
    parts.append("</section>")
    return "\n".join(parts)


def _piece(piece: dict) -> str:
    """A rendered piece of a record: its MathML, or its text (and why) in a box."""
    if "mathml" in piece:
        if "ops" in piece:  # larger than explain prints: folded, open on a click
            return (
                f"<details><summary>an expression of {piece['ops']} operations</summary>"
                f"{piece['mathml']}</details>"
            )
        return piece["mathml"]
    return (
        f"<pre class='as-text' title='{html.escape(piece['why'])}'>"
        f"{html.escape(piece['text'])}</pre>"
    )


def _point(step: dict) -> str:
    if "point" not in step:
        return ""
    inline = ", ".join(
        p["mathml"] if "mathml" in p else html.escape(p["text"]) for p in step["point"]
    )
    where = "they differ at" if step["kind"] == "witness" else "false at the exact point"
    return f"<p class='point'>{where} {inline}</p>"


def _step_html(step: dict) -> str:
    """One step as ``bodycheck explain`` prints it: its text, then its algebra (both
    sides and the rule; the rejected variant and the point where it is false; an
    erratum's forms side by side; a quantity; a property's examples)."""
    kind = step["kind"]
    out = [f"<li class='step {kind}'><p>{html.escape(step['text'])}</p>"]
    if "lhs" in step:
        if step.get("zero"):
            verb = (
                f"reduces to 0 by <code>{html.escape(step['rule'])}</code>"
                if kind == "proved"
                else "is not 0"
            )
            out.append(
                f"<div class='algebra' tabindex='0'>{_piece(step['lhs'])}<p>{verb}</p></div>"
            )
        else:
            verb = (
                f"equals, by <code>{html.escape(step['rule'])}</code>:"
                if kind == "proved"
                else f"is not (<code>{html.escape(step['rule'])}</code> does not reduce "
                "the difference to 0):"
            )
            out.append(
                f"<div class='algebra' tabindex='0'>{_piece(step['lhs'])}<p>{verb}</p>"
                f"{_piece(step['rhs'])}</div>"
            )
    if "derived" in step:
        out.append(
            "<table class='forms'><tr><th>derived</th><th>printed (false)</th></tr>"
            f"<tr><td>{_piece(step['derived'])}</td><td>{_piece(step['printed'])}</td></tr>"
            "</table><p>derived − printed, simplified:</p>"
        )
    if "expr" in step:
        out.append(f"<div class='algebra' tabindex='0'>{_piece(step['expr'])}</div>")
    out.append(_point(step))
    if "examples" in step:
        out.append(
            "<p>the first examples drawn:</p><ul class='examples'>"
            + "".join(f"<li><code>{html.escape(e)}</code></li>" for e in step["examples"])
            + "</ul>"
        )
    out.append("</li>")
    return "".join(out)


def _steps_link(c) -> str:
    from identities.verify import record

    rec, _ = record.load(c.id, c.chapter)
    count = f"{len(rec['steps'])} steps" if rec else "its steps"
    return f"<p><a href='{_check_page_name(c.id)}'>the derivation, {count}</a></p>"


def _derivation(c, level: int) -> str:
    """The check's steps from its stored record (identities/data/derivations), as
    ``bodycheck explain`` shows them, under a heading at ``level``; a note when there is
    no record."""
    from identities.verify import record

    rec, _ = record.load(c.id, c.chapter)
    if rec is None:
        return (
            "<p class='pending'>its steps are not stored (run <code>make checks</code>); "
            f"<code>bodycheck explain {html.escape(c.id)}</code> prints them</p>"
        )
    label = html.escape(rec["label"] or "-")
    return (
        f"<h{level}>Steps (label {label}; <code>bodycheck explain {html.escape(c.id)}</code>)"
        f"</h{level}>"
        "<ol class='steps'>" + "".join(_step_html(s) for s in rec["steps"]) + "</ol>"
    )


def _errata_page(regs: list) -> str:
    lines = [
        "<p>Where the book's printed form is false: the check shows the printed form "
        "failing and proves the corrected one.</p>"
    ]
    for c in regs:
        if not c.errata:
            continue
        lines.append(
            f"<section id='{_check_anchor(c.id)}'><h2>{html.escape(', '.join(c.errata))}: "
            f"{html.escape(c.title)}</h2>"
            f"<p>check <a href='{_check_href(c)}'><code>{html.escape(c.id)}</code></a>"
            f", kind {c.kind}</p>"
            f"<p class='erratum'>printed (false): {_rich(c.printed)}</p>"
            f"<p>corrected: {_rich(c.corrected)}</p>{_refutations(c)}</section>"
        )
    return "\n".join(lines)


def _refutations(c) -> str:
    """An erratum's refuting steps from its stored record: the derived and the printed
    forms side by side, their difference and the point where the printed one fails."""
    from identities.verify import record

    rec, _ = record.load(c.id, c.chapter)
    steps = [s for s in rec["steps"] if s["kind"] == "refuted"] if rec else []
    return "<ol class='steps'>" + "".join(map(_step_html, steps)) + "</ol>" if steps else ""


def _built_in_scenes() -> dict[str, Path]:
    """The scenes scenes.html shows: every built-in one (name → its file)."""
    from mechanics.scenes import builtin_scenes

    return builtin_scenes()


def _scene_section(name: str, path: str, out: str) -> str:
    """One built-in scene's section of scenes.html (run in a worker process): its player,
    and for :data:`SCENES` its plots; a scene whose run fails, shown with its failure."""
    from identities.book.scenes.compare import load_book_scene, run_book_scene
    from identities.cli.scene_player import player_section
    from identities.cli.scene_plots import plot_result
    from mechanics.scenes import SceneError
    from mechanics.scenes.compiled import reference_path

    try:
        # the Python right-hand side (the reference; the compiled one is tested equal to
        # it): the 18 short runs take the same time either way, and the compiled path's
        # first use in a fresh checkout compiles its kernels (measured: the first build
        # 29.5 s with them, 8.2 s without; each run's method line says which side ran)
        with reference_path():
            result = run_book_scene(load_book_scene(path))
    except SceneError as exc:
        return (
            f"<section id='{name}'><h2>{html.escape(name)}</h2>"
            f"<p class='erratum'>the run failed: {html.escape(str(exc))}</p></section>"
        )
    lines = [player_section(result, name)]
    if name in SCENES:
        plot_result(result, Path(out) / f"scene-{name}.svg")
        lines.append(
            f"<p><img src='scene-{name}.svg' alt='plots of the scene {name}'></p>"
            f"<pre>{html.escape(result.summary())}</pre>"
        )
    return "\n".join(lines)


def _scenes_page(sections: dict[str, str]) -> str:
    """Every built-in scene, run while the site is built (``sections``: name → its
    section, :func:`_scene_section`): its player (the bodies moving, play, pause, a time
    slider, the events on the timeline, the invariants and derived quantities beside it),
    and for :data:`SCENES` its plots."""
    lines = [
        "<p>Every built-in scene, simulated while the site was built and compared with "
        "the book: press play or move the slider (<code>bodycheck demo NAME --html "
        "OUT.html</code> writes one such page, <code>bodycheck scene FILE --html "
        "OUT.html</code> one of your own scene).</p>",
        "<ul>" + "".join(f"<li><a href='#{n}'>{n}</a></li>" for n in sections) + "</ul>",
    ]
    lines += sections.values()
    return "\n".join(lines)


def _prepare(out: Path) -> None:
    """Make ``out`` an empty folder: refuse one that is not empty and not a site."""
    if out.exists() and not out.is_dir():
        raise SiteError(f"output {out} exists and is not a folder")
    if out.is_dir() and any(out.iterdir()) and not (out / MARKER).is_file():
        raise SiteError(
            f"output folder {out} exists, is not empty and is not a previous site "
            f"(no {MARKER} file): refusing to write into it; give a new or empty folder"
        )
    if out.is_dir():
        shutil.rmtree(out)
    out.mkdir(parents=True)


def as_text(regs) -> list[str]:
    """What the pages show as text instead of MathML: each piece of a stored record that
    sympy could not print or that is too large (check, step, role, why), and each check
    with no stored record."""
    from identities.verify import record

    out = []
    for c in regs:
        rec, _ = record.load(c.id, c.chapter)
        out += [f"{c.id}: no stored record"] if rec is None else record.fallbacks(rec)
    return out


def _as_text_page(listed: list[str]) -> str:
    lines = [
        "<p>The checks' algebra is MathML printed by sympy from the expressions each check "
        "built (<code>bodycheck catalogue --derivations</code>, <code>make checks</code>). "
        f"These {len(listed)} pieces are shown as text instead: sympy could not print "
        "them, or they are larger than <code>bodycheck explain</code> shows.</p><ul>"
    ]
    lines += [f"<li>{html.escape(x)}</li>" for x in listed]
    lines.append("</ul>")
    return "\n".join(lines)


def build_site(
    out, *, scenes: bool = True, listed: list[str] | None = None, jobs: int = 1, api: bool = False
) -> list[Path]:
    """Write the site into the folder ``out``; return the pages written. When ``listed``
    is a list, what is shown as text instead of MathML (:func:`as_text`) is appended.
    With ``jobs`` > 1 the built-in scenes run in that many worker processes while the
    other pages are written (``bodycheck site`` uses the machine's cores).  With ``api``,
    the API reference is built into ``out/api`` (:func:`build_api`) and the index links it.

    Raises :class:`SiteError` when ``out`` exists, is not empty and holds no
    :data:`MARKER` (it is not a previous site).
    """

    out = Path(out)
    _prepare(out)
    known = _built_in_scenes() if scenes else {}
    if jobs > 1:
        # the built-in scenes run in worker processes while the pages of the checks are
        # written (18 scenes take ~10 s in one process, the check pages ~3 s); the
        # workers are started by a fork server, never forked from this process, which
        # may hold threads (pytest-xdist's; os.fork warns there from Python 3.12)
        context = multiprocessing.get_context("forkserver")
        with ProcessPoolExecutor(max_workers=jobs, mp_context=context) as pool:
            running = {
                n: pool.submit(_scene_section, n, str(p), str(out)) for n, p in known.items()
            }
            pages = _pages(out, listed, api, scenes)
            sections = {n: job.result() for n, job in running.items()}
    else:
        pages = _pages(out, listed, api, scenes)
        sections = {n: _scene_section(n, str(p), str(out)) for n, p in known.items()}
    if scenes:
        pages["scenes.html"] = ("Scenes", _scenes_page(sections))
    chapters = sorted({int(name[2:-5]) for name in pages if re.fullmatch(r"ch\d+\.html", name)})
    written = []
    for name, (title, body) in pages.items():
        path = out / name
        path.write_text(_page(title, body, chapters), encoding="utf-8")
        written.append(path)
    from identities.cli.scene_player import PLAYER_CSS

    (out / "style.css").write_text(_CSS.lstrip() + PLAYER_CSS, encoding="utf-8")
    (out / MARKER).write_text("written by bodycheck site\n", encoding="utf-8")
    if api:
        build_api(out / "api")
        bad = broken_links(out)
        if bad:
            raise SiteError(
                f"{len(bad)} links of the site and its API reference do not resolve:\n"
                + "\n".join(bad[:20])
            )
    return written


def _links(page: Path) -> list[str]:
    return re.findall(r"""(?:href|src)=['"]([^'"]+)['"]""", page.read_text("utf-8"))


def _ids(page: Path) -> set[str]:
    return set(re.findall(r"""\bid=['"]([^'"]+)['"]""", page.read_text("utf-8")))


def broken_links(root: Path) -> list[str]:
    """Every href/src of every page under ``root`` that does not resolve to a file
    (and, with a #fragment, to an element id in it); absolute URLs count as broken:
    the site works offline."""
    broken = []
    for page in sorted(root.rglob("*.html")):
        for link in _links(page):
            parts = urlsplit(link)
            if parts.scheme or parts.netloc:
                broken.append(f"{page.relative_to(root)}: {link} (not relative)")
                continue
            target = (page.parent / unquote(parts.path)) if parts.path else page
            if not target.is_file():
                broken.append(f"{page.relative_to(root)}: {link} (no file)")
            elif parts.fragment and parts.fragment not in _ids(target):
                broken.append(f"{page.relative_to(root)}: {link} (no id {parts.fragment!r})")
    return broken


#: the API reference's Sphinx sources (docs/conf.py): in a source checkout only
DOCS = Path(__file__).resolve().parents[2] / "docs"


#: the modules the ``docs`` extra installs, all needed by the API reference's build
DOCS_EXTRA = ("sphinx", "numpydoc", "myst_parser")


def docs_extra_missing() -> list[str]:
    """The modules of the ``docs`` extra that are not installed (Sphinx alone can come in
    with another package, numpydoc's, so each is looked for)."""
    import importlib.util

    return [m for m in DOCS_EXTRA if not importlib.util.find_spec(m)]


def build_api(out: Path, docs: Path = DOCS) -> None:
    """Build the API reference (Sphinx, ``docs/conf.py``) into ``out``, warnings as errors
    and every cross-reference to bodycheck's own names resolved.

    Raises :class:`SiteError` when ``docs`` holds no ``conf.py`` (an installed package has
    no sources to build from), when the ``docs`` extra is not installed (naming it), or
    when Sphinx fails, with its warnings (page and target).
    """
    if not (docs / "conf.py").is_file():
        raise SiteError(f"the API reference is built from a source checkout: no {docs / 'conf.py'}")
    missing = docs_extra_missing()
    if missing:
        raise SiteError(
            f"the API reference needs {', '.join(missing)}, not installed: "
            "pip install 'bodycheck[docs]'"
        )
    with tempfile.TemporaryDirectory() as doctrees:  # Sphinx's cache: not part of the site
        run = subprocess.run(
            [sys.executable, "-m", "sphinx", "-q", "-n", "-W", "--keep-going", "-b", "html",
             "-d", doctrees, str(docs), str(out)],
            capture_output=True, text=True, check=False,
        )  # fmt: skip
    if run.returncode != 0:
        raise SiteError(
            "the API reference did not build (Sphinx, warnings as errors):\n"
            + (run.stderr.strip() or run.stdout.strip())
        )


def _pages(
    out: Path, listed: list[str] | None, api: bool = False, scenes: bool = True
) -> dict[str, tuple[str, str]]:
    """Every page but scenes.html (title, body), and the search box's files; with ``api``
    the index links the API reference (``api/index.html``); ``scenes``: the scenes' players
    are built (the demos link them)."""
    from identities.verify.catalogue import checks, item_rows

    rows, regs = item_rows(), checks()
    by_ch: dict[int, list] = defaultdict(list)
    for r in rows:
        by_ch[r.item.chapter].append(r)
    chapters = sorted(by_ch)
    pages: dict[str, tuple[str, str]] = {}
    for ch in chapters:
        pages[f"ch{ch}.html"] = (f"Chapter {ch}", _chapter_page(ch, by_ch[ch], regs))
    named = [c for c in regs if c.chapter is None]
    pages["named.html"] = (
        "Named results",
        "<h2>Checks</h2>\n" + ("\n".join(_check_block(c) for c in named) or "<p>none</p>"),
    )
    pages["errata.html"] = ("Errata", _errata_page(regs))
    for c in regs:
        pages[_check_page_name(c.id)] = (f"{c.id}: {c.title}", _check_page(c))
    text = as_text(regs)
    if listed is not None:
        listed += text
    pages["as-text.html"] = ("Shown as text", _as_text_page(text))
    pages["scenes.html"] = ("Scenes", "<p>not built (scenes=False)</p>")
    from identities.cli.notebooks import demos_page  # the notebooks' stored outputs: no run

    pages["demos.html"] = (
        "Lecture demos",
        demos_page(out, check_href=_check_page_name, scenes=scenes),
    )
    png = _BENCH / "workprecision.png"
    if png.is_file():
        shutil.copyfile(png, out / "workprecision.png")
        bench = (
            "<p>What accuracy costs: error against time for each method on the reference "
            "problems with exact solutions (<code>bodycheck bench</code>, "
            "<code>docs/bench/</code>).</p>"
            "<img src='workprecision.png' alt='work-precision plot'>"
        )
    else:
        bench = "<p>No work-precision study found (run <code>bodycheck bench</code>).</p>"
    pages["workprecision.html"] = ("Work-precision", bench)
    counts = defaultdict(int)
    for r in rows:
        counts[r.status] += 1
    index = [
        "<p>H. Essén, <i>Dynamics of Bodies</i> (KTH, 1996), executable and checked: "
        f"{len(rows)} book items behind {len(regs)} checks ("
        + ", ".join(f"{n} {s}" for s, n in sorted(counts.items()))
        + ").</p><ul>",
        *(
            f"<li><a href='ch{ch}.html'>Chapter {ch}</a>: {len(by_ch[ch])} items</li>"
            for ch in chapters
        ),
        f"<li><a href='named.html'>Named results</a>: {len(named)} checks</li>",
        f"<li><a href='errata.html'>Errata</a>: {sum(bool(c.errata) for c in regs)} checks</li>",
        "<li><a href='scenes.html'>Scenes</a></li>",
        "<li><a href='demos.html'>Lecture demos</a>: the notebooks</li>",
        f"<li><a href='as-text.html'>Shown as text</a>: {len(text)} pieces of algebra</li>",
        "<li><a href='workprecision.html'>Work-precision</a></li>",
        *(
            ["<li><a href='api/index.html'>API reference</a>: the library, module by module</li>"]
            if api
            else []
        ),
        "</ul>",
    ]
    pages["index.html"] = ("bodycheck: the book, checked", "\n".join(index))
    found = search_index(regs)
    pages["search.html"] = ("Search", _search_page(found))
    data = json.dumps(found, ensure_ascii=True, separators=(",", ":"))
    (out / "search-index.js").write_text(f"window.BODYCHECK_SEARCH = {data};\n", "utf-8")
    shutil.copyfile(_SEARCH_JS, out / "search.js")
    shutil.copyfile(_PLAYER_JS, out / "scene-player.js")
    return pages
