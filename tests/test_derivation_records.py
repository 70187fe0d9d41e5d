"""The stored records of the checks' steps (identities/verify/record.py), what the site
shows of every derivation: MathML printed from the expressions the checks built, the
negative controls' points, the errata's forms, fresh against the checks themselves
(``test_catalogue.py`` compares each check's record as it runs)."""

from __future__ import annotations

import html
import re

import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from identities.verify import record
from identities.verify.catalogue import item_rows, load_all
from identities.verify.proof import CheckFailure, Derivation

REGISTRY = load_all()
x, y, z = sp.symbols("x y z")
f = sp.Function("f")
t = sp.Symbol("t")


def _stored(c):
    rec, _ = record.load(c.id, c.chapter)
    assert rec is not None, f"{c.id}: no stored record; run `make checks`"
    return rec


def test_every_check_has_a_stored_record_that_passed() -> None:
    for c in REGISTRY.values():
        rec = _stored(c)
        assert rec["passed"] is True
        assert rec["id"] == c.id
        assert rec["label"] in {"proved", "probabilistic", "numeric"}


def test_every_proof_shows_its_steps_with_both_sides_rendered() -> None:
    """Each proof's record holds a proved claim whose sides are MathML, and its negative
    control with the exact point where the variant is false."""
    for c in REGISTRY.values():
        if c.kind != "proof":
            continue
        steps = _stored(c)["steps"]
        proved = [s for s in steps if s["kind"] == "proved" and "lhs" in s]
        witnessed = [s for s in steps if s["kind"] == "witness"]
        assert proved or witnessed, f"{c.id}: no proved step with its sides, no witness"
        assert any("mathml" in s["lhs"] for s in proved) or any(
            "mathml" in s["expr"] and s["point"] for s in witnessed
        ), f"{c.id}: no proved side (or witness and its point) rendered"
        rejected = [s for s in steps if s["kind"] == "rejected"]
        assert rejected, f"{c.id}: no negative control recorded"


def test_every_verified_equation_is_rendered_somewhere() -> None:
    """The issue's "every verified equation of the book appears rendered at least once":
    some check covering it holds a MathML piece."""
    missing = []
    for row in item_rows():
        if row.status != "verified" or not row.item.id.startswith("eq"):
            continue
        if not any(record.mathml_count(_stored(c)) for c in row.checks):
            missing.append(row.item.id)
    assert not missing, f"verified equations with no rendered algebra: {missing}"


def test_an_erratum_keeps_its_derived_and_printed_forms() -> None:
    errata = [c for c in REGISTRY.values() if c.errata]
    assert errata
    for c in errata:
        refuted = [s for s in _stored(c)["steps"] if s["kind"] == "refuted"]
        assert refuted, c.id
        for s in refuted:
            assert {"derived", "printed", "expr"} <= set(s), (c.id, sorted(s))
            assert "mathml" in s["derived"], c.id
            assert "mathml" in s["printed"], c.id


def test_a_piece_is_sympys_presentation_mathml_of_the_expression() -> None:
    piece = record.math_piece(sp.sqrt(x) / (y + 2))
    markup = piece["mathml"]
    assert markup.startswith('<math xmlns="http://www.w3.org/1998/Math/MathML"')
    assert "<msqrt>" in markup
    assert "<mfrac>" in markup
    assert re.findall(r"<mi>([^<]*)</mi>", markup) == ["x", "y"]
    matrix = record.math_piece(sp.Matrix([[x, 1], [0, y]]))["mathml"]
    assert "<mtable>" in matrix


def test_a_piece_too_large_or_unprintable_is_text_with_the_reason(monkeypatch) -> None:
    big = sum(sp.Symbol(f"a{i}") * sp.Symbol(f"b{i}") for i in range(record.SHOW_OPS))
    ops = int(sp.count_ops(big))
    assert record.SHOW_OPS < ops <= record.RECORD_OPS
    folded = record.math_piece(big)  # larger than explain prints: kept, with its size
    assert folded["ops"] == ops
    assert len(re.findall(r"<mi>a</mi>", folded["mathml"])) == record.SHOW_OPS
    piece = record.math_piece(big, limit=record.SHOW_OPS)
    assert "mathml" not in piece
    assert piece["why"] == "too large"
    assert f"{ops} operations" in piece["text"]

    import importlib

    printer = importlib.import_module("sympy.printing.mathml")  # the module, not its function

    def broken(*args, **kwargs):
        raise NotImplementedError("no presentation for this")

    monkeypatch.setattr(printer, "mathml", broken)
    piece = record.math_piece(x + y)
    assert piece["text"] == "x + y"
    assert piece["why"].startswith("sympy's MathML printer failed: NotImplementedError")


@settings(max_examples=25, deadline=None)
@given(
    a=st.integers(-5, 5).filter(bool),
    b=st.integers(-5, 5),
    wrong=st.sampled_from([x**2, 2 * x * y, sp.sin(x), f(t), sp.Derivative(f(t), t)]),
)
def test_a_rejected_variants_point_makes_it_false(a: int, b: int, wrong) -> None:
    """The point a negative control records is where its two sides differ: substituted
    (the f(t) and derivatives by what they stand for), the difference is not 0."""
    lhs = a * x + b * y
    rhs = lhs + wrong
    d = Derivation()
    d.reject(lhs, rhs, claim="a wrong variant")
    point = d.steps[-1].point
    assert point
    diff = (lhs - rhs).subs(sorted(point.items(), key=lambda kv: -sp.count_ops(kv[0])))
    assert sp.simplify(diff) != 0
    rec = record._step(d.steps[-1])
    assert all("mathml" in p for p in rec["point"])


def test_a_property_keeps_its_first_examples() -> None:
    d = Derivation()

    def holds(a: int) -> None:
        assert a * a >= 0

    d.holds_for_examples(holds, st.tuples(st.integers()), examples=20, claim="a² ≥ 0")
    examples = d.steps[-1].examples
    assert 1 <= len(examples) <= 3
    assert all(re.fullmatch(r"\(-?\d+,\)", e) for e in examples), examples


def test_the_stored_text_leaves_out_the_proving_time() -> None:
    d = Derivation()
    d.prove_equal((x + 1) ** 2, x**2 + 2 * x + 1, claim="the square")
    rec = record._step(d.steps[-1])
    assert " s)" in d.steps[-1].text
    assert rec["text"] == "proved (expand): the square"
    assert "mathml" in rec["lhs"]
    assert "mathml" in rec["rhs"]


def _some_record() -> tuple[dict, dict]:
    """P5.4's stored record, and the versions of this run as if it had been stored by it
    (so that ``compare`` reads every field whatever versions run the suite: the Python
    matrix runs newer ones than the stored records')."""
    c = REGISTRY["P5.4"]
    rec, _ = record.load(c.id, c.chapter)
    assert rec is not None
    return rec, record.versions()


def test_compare_accepts_the_same_record_and_masks_measured_errors_only() -> None:
    rec, versions = _some_record()
    assert record.compare(rec, rec, versions) == []
    numeric = [i for i, s in enumerate(rec["steps"]) if s["kind"] in ("numeric", "confirmed")]
    assert numeric, "P5.4 confirms by an independent route"
    other = dict(rec, steps=list(rec["steps"]))
    i = numeric[0]
    other["steps"][i] = dict(
        rec["steps"][i], text=re.sub(r"\d\.\d", "9.9", rec["steps"][i]["text"])
    )
    assert record.compare(other, rec, versions) == []


def test_compare_rejects_a_changed_claim_a_changed_rendering_and_a_lost_step() -> None:
    """The freshness test's negative control: each kind of change is reported."""
    rec, versions = _some_record()
    proved = next(i for i, s in enumerate(rec["steps"]) if s["kind"] == "proved")
    renamed = dict(rec, steps=list(rec["steps"]))
    renamed["steps"][proved] = dict(rec["steps"][proved], text="proved (expand): other")
    assert record.compare(renamed, rec, versions) == [f"P5.4: step {proved + 1} differs in text"]
    redrawn = dict(rec, steps=list(rec["steps"]))
    redrawn["steps"][proved] = dict(rec["steps"][proved], lhs={"mathml": "<math/>"})
    assert record.compare(redrawn, rec, versions) == [f"P5.4: step {proved + 1} differs in lhs"]
    shorter = dict(rec, steps=rec["steps"][:-1])
    assert f"P5.4: {len(rec['steps']) - 1} steps, stored {len(rec['steps'])}" in (
        record.compare(shorter, rec, versions)
    )
    assert record.compare(rec, None, versions) == ["P5.4: no stored record"]


def test_under_other_versions_compare_reads_kinds_and_rules_only() -> None:
    rec, versions = _some_record()
    older = dict(versions, sympy="0.0")
    proved = next(i for i, s in enumerate(rec["steps"]) if s["kind"] == "proved")
    redrawn = dict(rec, steps=list(rec["steps"]))
    redrawn["steps"][proved] = dict(rec["steps"][proved], lhs={"mathml": "<math/>"})
    assert record.compare(redrawn, rec, older) == []
    other_rule = dict(rec, steps=list(rec["steps"]))
    other_rule["steps"][proved] = dict(rec["steps"][proved], rule="simplify")
    assert record.compare(other_rule, rec, older) == [f"P5.4: step {proved + 1} differs in rule"]


def test_fallbacks_name_the_check_step_role_and_reason() -> None:
    rec = {
        "id": "eqX",
        "steps": [
            {"kind": "proved", "rule": "expand", "text": "", "lhs": {"mathml": "<math/>"}},
            {"kind": "proved", "rule": "expand", "text": "", "lhs": {"text": "…", "why": "w"}},
        ],
    }
    assert record.fallbacks(rec) == ["eqX step 2 lhs: w"]
    assert record.mathml_count(rec) == 1


@pytest.mark.parametrize("check_id", ["eq2.74", "P5.4"])
def test_the_stored_mathml_is_well_formed_xml(check_id: str) -> None:
    import xml.etree.ElementTree as ET
    from html.entities import html5

    def named(m: re.Match) -> str:  # HTML's named characters (&InvisibleTimes;) are not XML's
        name = m.group(1)
        return m.group(0) if name in ("lt", "gt", "amp", "quot", "apos") else html5[name + ";"]

    c = REGISTRY[check_id]
    for step in _stored(c)["steps"]:
        for role, piece in record._pieces(step):
            if "mathml" in piece:
                ET.fromstring(re.sub(r"&(\w+);", named, piece["mathml"]))  # raises if malformed
            else:
                assert html.escape(piece["text"]), (check_id, role)


def test_a_rejected_point_for_an_equal_pair_is_never_recorded() -> None:
    d = Derivation()
    with pytest.raises(CheckFailure, match="negative control accepted"):
        d.reject(x * (y + z), x * y + x * z, claim="an equal pair")
    assert d.steps == []
