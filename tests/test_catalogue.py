"""The registry, the tests and CHECKS.md agree; the proof procedure can fail."""

from __future__ import annotations

import re
import subprocess
import sys
from collections import Counter
from pathlib import Path

import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from identities.verify import catalogue, record
from identities.verify.catalogue import (
    DONE_CHAPTERS,
    Check,
    check,
    inventory,
    item_rows,
    load_all,
    run_check,
)
from identities.verify.proof import _EXACT, STRATEGIES, CheckFailure, Derivation, is_zero
from identities.verify.render import render_checks_md

ROOT = Path(__file__).resolve().parents[1]
BOOK = ROOT.parent / "shared" / "book" / "dynamics-of-bodies.txt"
REGISTRY = load_all()

#: Numbered items per chapter, counted in the book's text (tools/book_inventory.py).
#: Chapter 2 ends at (2.96): the foundation issue's "2.1-2.103" (589 in all) is not
#: what the book prints.
EQUATIONS = {1: 83, 2: 96, 3: 89, 4: 85, 5: 102, 6: 50, 7: 40, 8: 37}
EXAMPLES = {1: 2, 2: 3, 3: 7, 4: 5, 5: 4, 6: 3, 7: 3, 8: 1}
PROBLEMS = {1: 11, 2: 7, 3: 6, 4: 5, 5: 4, 6: 6, 7: 4}


@pytest.mark.parametrize("check_id", list(REGISTRY))
def test_catalogue_entry_passes(check_id: str) -> None:
    """Each check passes with an honest label, and the record of its steps that the site
    shows (identities/data/derivations, identities/verify/record.py) is this run's."""
    c = REGISTRY[check_id]
    outcome, d = run_check(c)
    assert outcome.passed, f"{check_id}: {outcome.message}"
    assert outcome.label in {"proved", "probabilistic", "numeric"}
    stored, versions = record.load(check_id, c.chapter)
    stale = record.compare(record.record(check_id, outcome, d), stored, versions)
    assert not stale, f"the stored record is stale (run `make checks`): {stale}"


def test_inventory_knows_every_numbered_item_of_the_book() -> None:
    inv = inventory()
    kinds = Counter(
        (i.id[:2] if i.id.startswith("eq") else i.id[0], i.chapter) for i in inv.values()
    )
    assert {ch: kinds["eq", ch] for ch in EQUATIONS} == EQUATIONS
    assert {ch: kinds["E", ch] for ch in EXAMPLES} == EXAMPLES
    assert {ch: kinds["P", ch] for ch in PROBLEMS} == PROBLEMS
    assert len(inv) == 582 + 28 + 43
    for ch, n in EQUATIONS.items():  # contiguous numbering
        assert all(f"eq{ch}.{k}" in inv for k in range(1, n + 1))


@pytest.mark.skipif(
    not BOOK.exists(), reason="the book text lives outside this repository (../shared)"
)
def test_inventory_matches_the_book_text() -> None:
    text = BOOK.read_text(encoding="utf-8")
    numbers = {f"eq{c}.{n}" for c, n in re.findall(r"\((\d)\.(\d{1,3})\)", text)}
    assert numbers == {i for i in inventory() if i.startswith("eq")}


def test_done_chapters_have_no_pending_item() -> None:
    pending = [
        r.item.id for r in item_rows() if r.item.chapter in DONE_CHAPTERS and r.status == "pending"
    ]
    assert pending == []


def test_other_chapters_are_pending_not_silently_missing() -> None:
    rows = item_rows()
    assert len(rows) == len(inventory())
    assert {r.status for r in rows if r.item.chapter not in DONE_CHAPTERS} <= {"pending"}


def test_every_chapter_of_the_book_is_done() -> None:
    assert {item.chapter for item in inventory().values()} == DONE_CHAPTERS


def test_every_problem_and_example_of_a_done_chapter_has_its_own_check() -> None:
    for item in inventory().values():
        if item.chapter in DONE_CHAPTERS and item.category in {"example", "problem"}:
            assert item.id in REGISTRY


def test_checks_md_is_fresh() -> None:
    on_disk = (ROOT / "CHECKS.md").read_text(encoding="utf-8")
    assert on_disk == render_checks_md(), "CHECKS.md is stale: run `make checks`"


def test_errata_show_printed_and_corrected_forms() -> None:
    errata = [c for c in REGISTRY.values() if c.errata]
    assert errata, "Example 2.3(c) is a known erratum"
    text = render_checks_md()
    for c in errata:
        assert c.printed in text.replace("\\|", "|")
        assert c.corrected in text.replace("\\|", "|")


# -- the procedure can fail ------------------------------------------------------

x, y = sp.symbols("x y", real=True)


def _fake(func, kind: str = "proof", **kw) -> Check:
    return Check("thm.fake", "fake", kind, func, **kw)


def test_a_proof_without_negative_control_fails() -> None:
    def only_positive(d: Derivation) -> None:
        d.prove_equal((x + y) ** 2, x**2 + 2 * x * y + y**2, strategy="expand", claim="binomial")

    outcome, _ = run_check(_fake(only_positive))
    assert not outcome.passed
    assert "negative control" in outcome.message


def test_a_negative_control_that_is_true_is_caught() -> None:
    def accepts_truth(d: Derivation) -> None:
        d.prove_equal(x * (x + 1), x**2 + x, strategy="expand", claim="distributive")
        d.reject((x + y) ** 2, x**2 + 2 * x * y + y**2, strategy="expand", claim="true binomial")

    outcome, _ = run_check(_fake(accepts_truth))
    assert not outcome.passed
    assert "accepted" in outcome.message


def test_a_false_statement_is_not_proved() -> None:
    with pytest.raises(CheckFailure, match="not proved"):
        Derivation().prove_equal(
            (x + y) ** 2, x**2 + y**2, strategy="expand", claim="freshman's dream"
        )


def test_an_erratum_must_refute_the_printed_form() -> None:
    def no_refutation(d: Derivation) -> None:
        d.prove_equal(x, x, strategy="expand", claim="trivial")

    c = _fake(no_refutation, kind="derivation", errata=("eq2.92",), printed="p", corrected="c")
    outcome, _ = run_check(c)
    assert not outcome.passed
    assert "printed form failing" in outcome.message


def test_refute_rejects_a_true_printed_statement() -> None:
    with pytest.raises(CheckFailure, match="not refuted"):
        Derivation().refute(sp.sin(x) ** 2 + sp.cos(x) ** 2, 1, claim="Pythagoras")


def test_a_problem_needs_an_independent_confirmation() -> None:
    def unconfirmed(d: Derivation) -> None:
        d.quantity("answer", x + 1)
        d.prove_equal(x + 1, 1 + x, strategy="expand", claim="commutes")

    outcome, _ = run_check(Check("P2.1", "fake problem", "derivation", unconfirmed))
    assert not outcome.passed
    assert "independent confirmation" in outcome.message


def test_probabilistic_evidence_is_labelled_as_such() -> None:
    d = Derivation()
    d.probable_equal(sp.sin(2 * x), 2 * sp.sin(x) * sp.cos(x), claim="double angle", points=4)
    assert d.label == "probabilistic"
    d.prove_equal(x, x, strategy="expand", claim="trivial")
    assert d.label == "probabilistic", "the weakest claim sets the label"
    with pytest.raises(CheckFailure, match="fails at"):
        Derivation().probable_equal(sp.sin(2 * x), sp.sin(x) * sp.cos(x), claim="wrong", points=4)


@pytest.mark.parametrize(
    ("expr", "strategy", "zero"),
    [
        (sp.sin(x) ** 2 + sp.cos(x) ** 2 - 1, "tan_half", True),
        (sp.sin(x) ** 2 - sp.cos(x) ** 2 - 1, "tan_half", False),
        (sp.sin(x + y) - sp.sin(x) * sp.cos(y) - sp.cos(x) * sp.sin(y), "expand_trig", True),
        (1 / (x + 1) + x / (x + 1) - 1, "cancel", True),
        (1 / (x + 1) + 1 / (x + 1) - 1, "numerator", False),
    ],
)
def test_strategies_reduce_exactly_the_zero_expressions(expr, strategy: str, zero: bool) -> None:
    assert is_zero(expr, strategy) is zero


z = sp.Symbol("z")

#: small polynomials in x, y, z with integer coefficients: the pieces of the rational
#: functions below
_POLYNOMIALS = st.builds(
    lambda cs, es: sum(c * x**a * y**b * z**e for c, (a, b, e) in zip(cs, es, strict=False)),
    st.lists(st.integers(-5, 5), min_size=1, max_size=4),
    st.lists(st.tuples(*[st.integers(0, 3)] * 3), min_size=4, max_size=4),
)


@st.composite
def _rational_differences(draw):
    """A rational function written two ways, minus each other, plus a drawn remainder
    that is zero about half the time: each strategy's zero and non-zero cases."""
    a, b, c = draw(_POLYNOMIALS), draw(_POLYNOMIALS), draw(_POLYNOMIALS)
    d = draw(_POLYNOMIALS.filter(lambda p: p != 0))
    e = draw(_POLYNOMIALS.filter(lambda p: p != 0))
    rest = draw(st.sampled_from([0, 0, x - y, sp.Rational(1, 3), 1 / (x + 2)]))
    if draw(st.booleans()):  # a polynomial: a product against its expansion
        return a * (b + c) - sp.expand(a * b + a * c) + sp.expand(rest * d)
    return a / d + c / e - (a * e + c * d) / (d * e) + rest


@settings(max_examples=60, deadline=None)
@given(_rational_differences(), st.sampled_from(sorted(_EXACT)))
def test_the_exact_zero_test_agrees_with_the_strategy_it_stands_for(expr, strategy) -> None:
    """The ring arithmetic of ``is_zero`` decides exactly what the strategy decides."""
    verdict = _EXACT[strategy](expr)
    if verdict is not None:
        assert verdict is (STRATEGIES[strategy](expr) == 0), (expr, strategy)


@pytest.mark.parametrize(
    ("expr", "zero"),
    [
        # not polynomials with rational coefficients: the strategy itself decides
        ((sp.sqrt(2) * x + 1) ** 2 - (2 * x**2 + 2 * sp.sqrt(2) * x + 1), True),
        (sp.sin(x) * (x + 1) - sp.sin(x) * x - sp.sin(x), True),
        (sp.sqrt(x**2 + 1) * (x + 1) - sp.sqrt(x**2 + 1) * x - sp.sqrt(x**2 + 1), True),
        (sp.I * x * (x + sp.I) - (sp.I * x**2 - x), True),
        # binary floats stay floats: 0.1 + 0.2 - 0.3 is not 0 in float64
        (sp.Float(0.1) * x + sp.Float(0.2) * x - sp.Float(0.3) * x, False),
        (sp.Float(0.5) * x * (x + 1) - sp.Float(0.5) * x**2 - sp.Float(0.5) * x, True),
    ],
)
def test_expressions_outside_the_ring_fall_back_to_the_strategy(expr, zero: bool) -> None:
    assert _EXACT["expand"](expr) is None
    assert is_zero(expr, "expand") is zero
    assert is_zero(expr, "expand") is (sp.expand(expr) == 0)


def test_registration_rejects_unknown_items_and_bad_ids() -> None:
    with pytest.raises(ValueError, match="unknown book items"):
        check("thm.nope", "x", kind="proof", covers=("eq2.97",))(lambda d: None)
    with pytest.raises(ValueError, match=r"is not eqN\.M"):
        check("eq2-1", "x", kind="proof")(lambda d: None)
    with pytest.raises(ValueError, match="kind"):
        check("thm.nope", "x", kind="lemma")(lambda d: None)
    assert "thm.nope" not in catalogue.REGISTRY


# -- layers ------------------------------------------------------------------------


def test_mechanics_never_imports_sympy_or_identities() -> None:
    code = (
        "import sys, mechanics, mechanics.rotation, mechanics.kinematics, mechanics.errors; "
        "bad = [m for m in sys.modules if m.split('.')[0] in ('sympy', 'identities', 'hypothesis')]; "
        "print(bad); sys.exit(1 if bad else 0)"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=False)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    for path in (ROOT / "mechanics").rglob("*.py"):
        text = path.read_text(encoding="utf-8")
        assert not re.search(r"^\s*(import|from)\s+(sympy|identities)\b", text, re.M), path


def test_the_readme_states_the_catalogues_counts() -> None:
    # README's one-line summary of the catalogue is written by hand: it must not go stale
    readme = (Path(__file__).resolve().parent.parent / "README.md").read_text(encoding="utf-8")
    m = re.search(
        r"(\d+) book items \((\d+) verified, (\d+) definitions, (\d+) errata\)\s+behind (\d+) checks",
        readme,
    )
    assert m, "README no longer states the catalogue's counts"
    status = Counter(r.status for r in item_rows())
    assert tuple(int(x) for x in m.groups()) == (
        sum(status.values()),
        status["verified"],
        status["definition"],
        status["erratum"],
        len(load_all()),
    )
