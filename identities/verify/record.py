"""What each check showed, kept: its steps with their algebra as MathML, for the site.

``bodycheck explain ID`` runs a check and prints its steps; this module keeps the same
steps for every check, with each expression the check built rendered as MathML by
sympy's presentation printer (``sympy.printing.mathml``, ``printer="presentation"``)
from the sympy object itself, never from text. ``bodycheck site`` shows them, so that a
page shows what ``explain`` prints without running a proof (the whole catalogue takes
~100 s of proving; the site builds in seconds).

Conventions
-----------
- One record per check: ``{"id", "label", "passed", "steps": [...]}``; each step has
  its ``kind`` and ``rule`` (:class:`identities.verify.proof.Step`), its ``text`` with
  the proving time taken out (a time is not part of what a check shows), and, where
  the step holds them, the rendered pieces:

  ============  ============================================================
  ``lhs, rhs``  a proved claim's or a negative control's two sides
                (``rhs`` left out when the claim is "= 0": ``zero`` is true)
  ``point``     the exact point where a rejected variant or a printed form
                is false: one ``symbol = value`` piece per symbol
  ``derived``,  an erratum's two forms, and ``expr`` their difference as
  ``printed``   simplify gives it (what ``explain`` prints)
  ``expr``      a note's, a quantity's or a witness' expression
  ``examples``  a property's first drawn examples (their reprs, as text)
  ============  ============================================================

  A rendered piece is ``{"mathml": "<math ...>"}``; one sympy cannot print, or one of
  more than :data:`SHOW_OPS` operations (what ``explain`` also leaves out), is
  ``{"text": ..., "why": ...}`` and the site lists it (:func:`fallbacks`).
- The records live in ``identities/data/derivations/`` (one JSON file per chapter and
  ``named.json``), written by ``bodycheck catalogue --derivations`` (``make checks``)
  with the versions of the packages that decide them (:data:`PACKAGES`). The catalogue's
  test runs each check and compares its record with the stored one: equal, with the
  floats of numeric steps' texts (measured errors) masked, when the versions are the
  stored ones; the steps' kinds and rules only under other versions (the Python matrix
  runs newer sympy and hypothesis, whose printing and draws may differ).
"""

from __future__ import annotations

import json
import platform
import re
from collections.abc import Iterable
from importlib import metadata
from pathlib import Path
from typing import Any

import sympy as sp

__all__ = [
    "DATA",
    "PACKAGES",
    "RECORD_OPS",
    "SHOW_OPS",
    "compare",
    "fallbacks",
    "is_zero_literal",
    "load",
    "math_piece",
    "mathml_count",
    "record",
    "record_all",
    "record_by_id",
    "simplified",
    "too_large",
    "versions",
    "write_records",
]

#: a side larger than this (sympy's operation count) is summarised, not printed: a
#: 3 × 3 tensor of a few terms each prints in a screen, a full expansion does not
#: (``bodycheck explain`` and the site alike)
SHOW_OPS = 400
#: the site shows larger expressions folded (``<details>``, open on a click, no script),
#: up to this size; beyond it, a line as ``explain`` prints (a full expansion of a few
#: thousand operations is pages of MathML that no one reads)
RECORD_OPS = 4000
#: the folder of the stored records
DATA = Path(__file__).resolve().parents[1] / "data" / "derivations"
#: the packages whose versions decide a record (the printer, the draws, the arithmetic)
PACKAGES = ("sympy", "mpmath", "hypothesis", "numpy", "scipy")
#: a proving time in a step's text: "proved (expand, 2.93 s): ..."
_TIME = re.compile(r", \d+\.\d+ s\)")
#: a decimal number (a measured error in a numeric step's text)
_FLOAT = re.compile(r"\d*\.\d+(?:e[-+]?\d+)?|\d+e[-+]?\d+")
#: the step kinds whose texts carry measured floats
_MEASURED = ("numeric", "confirmed")


def versions() -> dict[str, str]:
    """Python's minor version and the versions of :data:`PACKAGES`."""
    out = {"python": ".".join(platform.python_version_tuple()[:2])}
    for name in PACKAGES:
        out[name] = metadata.version(name)
    return out


def _ops(expr) -> int | None:
    try:
        return int(sp.count_ops(expr))
    except (TypeError, AttributeError, ValueError):
        return None


def too_large(expr, limit: int = SHOW_OPS) -> str | None:
    """A line saying ``expr`` is not shown (more than ``limit`` operations), or None
    when it is shown."""
    ops = _ops(expr)
    return f"(an expression of {ops} operations, not shown)" if ops and ops > limit else None


def math_piece(expr, *, display: str = "block", limit: int = RECORD_OPS) -> dict[str, Any]:
    """``expr`` as ``{"mathml": markup}`` printed by sympy's presentation printer (with
    ``"ops"``, its operation count, when that is over :data:`SHOW_OPS`: the site folds
    it), or as ``{"text", "why"}`` when it has more than ``limit`` operations or sympy
    cannot print it."""
    from sympy.printing.mathml import mathml

    if isinstance(expr, list | tuple):
        expr = sp.Tuple(*expr)
    try:
        obj = expr if isinstance(expr, sp.Basic | sp.MatrixBase) else sp.sympify(expr, strict=True)
    except (sp.SympifyError, TypeError, ValueError) as exc:
        return {"text": str(expr), "why": f"not a sympy expression ({type(exc).__name__})"}
    if (line := too_large(obj, limit)) is not None:
        return {"text": line, "why": "too large"}
    try:
        markup = mathml(obj, printer="presentation")
    except Exception as exc:  # any printer failure: shown as text, listed by the build
        return {"text": sp.sstr(obj), "why": f"sympy's MathML printer failed: {exc!r}"[:200]}
    piece: dict[str, Any] = {
        "mathml": f'<math xmlns="http://www.w3.org/1998/Math/MathML" display="{display}">'
        f"{markup}</math>"
    }
    if (ops := _ops(obj)) and ops > SHOW_OPS:
        piece["ops"] = ops
    return piece


def is_zero_literal(x) -> bool:
    """Is ``x`` the literal 0 (or a zero matrix): a claim "= 0"."""
    if isinstance(x, sp.MatrixBase):
        return x.is_zero_matrix is True
    return x == 0


def simplified(expr):
    """``derived − printed`` as simplify gives it (entrywise), for reading: the step's
    own record keeps the difference as it was formed (what ``explain`` prints)."""
    if isinstance(expr, sp.MatrixBase):
        return expr.applyfunc(sp.simplify)
    try:
        return sp.simplify(expr)
    except (TypeError, AttributeError):
        return expr


def _point(point: dict) -> list[dict[str, str]]:
    return [
        math_piece(sp.Eq(k, v, evaluate=False), display="inline")
        for k, v in sorted(point.items(), key=lambda kv: str(kv[0]))
    ]


def _step(step) -> dict[str, Any]:
    out: dict[str, Any] = {
        "kind": step.kind,
        "rule": step.rule,
        "text": _TIME.sub(")", step.text),
    }
    if step.sides is not None:
        lhs, rhs = step.sides
        out["lhs"] = math_piece(lhs)
        if is_zero_literal(rhs):
            out["zero"] = True
        else:
            out["rhs"] = math_piece(rhs)
    if step.forms is not None:
        out["derived"], out["printed"] = (math_piece(f) for f in step.forms)
    if step.expr is not None:
        expr = simplified(step.expr) if step.kind == "refuted" else step.expr
        out["expr"] = math_piece(expr)
    if step.point:
        out["point"] = _point(step.point)
    if step.examples:
        out["examples"] = list(step.examples)
    return out


def record(check_id: str, outcome, derivation) -> dict[str, Any]:
    """The record of one run of a check (its :class:`~identities.verify.catalogue.Outcome`
    and :class:`~identities.verify.proof.Derivation`)."""
    return {
        "id": check_id,
        "label": outcome.label,
        "passed": outcome.passed,
        "steps": [_step(s) for s in derivation.steps],
    }


#: the stored files read so far (path → their JSON)
_LOADED: dict[Path, dict] = {}


def _file(chapter: int | None) -> Path:
    return DATA / (f"ch{chapter}.json" if chapter else "named.json")


def write_records(records: dict[str, dict], chapters: dict[str, int | None]) -> list[Path]:
    """Write ``records`` (check id → record) into :data:`DATA`, one file per chapter
    (``chapters``: check id → chapter), with :func:`versions`; return the files."""
    by_file: dict[Path, dict[str, dict]] = {}
    for cid, rec in records.items():
        by_file.setdefault(_file(chapters[cid]), {})[cid] = rec
    DATA.mkdir(parents=True, exist_ok=True)
    _LOADED.clear()  # what load() read before is replaced now
    for old in DATA.glob("*.json"):
        if old not in by_file:
            old.unlink()
    for path, recs in by_file.items():
        payload = {"versions": versions(), "checks": recs}
        path.write_text(
            json.dumps(payload, ensure_ascii=False, indent=0, sort_keys=False) + "\n", "utf-8"
        )
    return sorted(by_file)


def load(check_id: str, chapter: int | None) -> tuple[dict | None, dict[str, str]]:
    """The stored record of a check (None when there is none) and the versions it was
    made with."""
    path = _file(chapter)
    if path not in _LOADED:
        _LOADED[path] = (
            json.loads(path.read_text("utf-8"))
            if path.is_file()
            else {"versions": {}, "checks": {}}
        )
    data = _LOADED[path]
    return data["checks"].get(check_id), data["versions"]


def _masked(rec: dict) -> dict:
    steps = []
    for s in rec["steps"]:
        s = dict(s)
        if s["kind"] in _MEASURED:
            s["text"] = _FLOAT.sub("#", s["text"])
        steps.append(s)
    return rec | {"steps": steps}


def compare(now: dict, stored: dict | None, stored_versions: dict[str, str]) -> list[str]:
    """Where a fresh record differs from the stored one (empty when it does not): every
    field when the versions are the stored ones (measured floats masked), else the steps'
    kinds and rules."""
    if stored is None:
        return [f"{now['id']}: no stored record"]
    same = stored_versions == versions()

    def view(rec: dict) -> dict:
        if same:
            return _masked(rec)
        return {"steps": [{"kind": s["kind"], "rule": s["rule"]} for s in rec["steps"]]}

    a, b = view(now), view(stored)
    if a == b:
        return []
    problems = []
    if len(a["steps"]) != len(b["steps"]):
        problems.append(f"{now['id']}: {len(a['steps'])} steps, stored {len(b['steps'])}")
    for n, (x, y) in enumerate(zip(a["steps"], b["steps"], strict=False), 1):
        if x != y:
            where = [k for k in sorted(set(x) | set(y)) if x.get(k) != y.get(k)]
            problems.append(f"{now['id']}: step {n} differs in {', '.join(where)}")
    for k in ("label", "passed"):
        if a.get(k) != b.get(k):
            problems.append(f"{now['id']}: {k} {a.get(k)!r}, stored {b.get(k)!r}")
    return problems


def _pieces(step: dict) -> Iterable[tuple[str, dict]]:
    for role in ("lhs", "rhs", "derived", "printed", "expr"):
        if role in step:
            yield role, step[role]
    for n, piece in enumerate(step.get("point", ()), 1):
        yield f"point {n}", piece


def fallbacks(rec: dict) -> list[str]:
    """The pieces of a record shown as text (each: check id, step, role, why)."""
    return [
        f"{rec['id']} step {n} {role}: {piece['why']}"
        for n, step in enumerate(rec["steps"], 1)
        for role, piece in _pieces(step)
        if "mathml" not in piece
    ]


def mathml_count(rec: dict) -> int:
    """How many pieces of a record are MathML."""
    return sum("mathml" in piece for step in rec["steps"] for _, piece in _pieces(step))


def record_by_id(check_id: str) -> dict[str, Any]:
    """Run the check ``check_id`` and return its record (for worker processes)."""
    from identities.verify.catalogue import load_all, run_check

    outcome, d = run_check(load_all()[check_id])
    return record(check_id, outcome, d)


def record_all(ids: list[str], jobs: int = 1) -> dict[str, dict]:
    """Records of the checks ``ids`` (run in ``jobs`` processes), in the order given."""
    from concurrent.futures import ProcessPoolExecutor

    if jobs <= 1:
        return {cid: record_by_id(cid) for cid in ids}
    with ProcessPoolExecutor(max_workers=jobs) as pool:
        return dict(zip(ids, pool.map(record_by_id, ids, chunksize=1), strict=True))
