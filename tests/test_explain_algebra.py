"""``bodycheck explain`` shows each claim's algebra: both sides and the rule, as text or
LaTeX; an erratum's derived − printed simplified."""

from __future__ import annotations

import sympy as sp

from identities.cli.main import main
from identities.verify.proof import Derivation


def test_a_proved_claim_records_both_sides_and_its_rule() -> None:
    x = sp.Symbol("x")
    d = Derivation()
    d.prove_equal((x + 1) ** 2, x**2 + 2 * x + 1, strategy="expand", claim="square")
    d.reject((x + 1) ** 2, x**2 + 1, strategy="expand", claim="wrong square")
    proved, rejected = d.steps
    assert proved.sides == ((x + 1) ** 2, x**2 + 2 * x + 1)
    assert (proved.kind, proved.rule) == ("proved", "expand")
    assert rejected.sides == ((x + 1) ** 2, x**2 + 1)
    assert rejected.kind == "rejected"


def test_explain_prints_the_sides_the_rule_and_a_rejection(capsys) -> None:
    assert main(["explain", "eq4.47"]) == 0
    out = capsys.readouterr().out
    assert "equals, by " in out
    assert "is not" in out  # a wrong variant, with its sides
    assert "J₁⋅──(ω₁(t))" in out  # pretty-printed algebra, not only labels


def test_the_printed_forms_error_is_shown_simplified(capsys) -> None:
    """eq5.96's derived − printed was shown as two opposite terms; simplified it is one
    fraction."""
    assert main(["explain", "eq5.96"]) == 0
    out = capsys.readouterr().out
    assert "2⋅(J₂ - J₃)⋅ω₂(t)⋅ω₃(t)" in out


def test_latex_output(capsys) -> None:
    assert main(["explain", "eq5.96", "--latex"]) == 0
    out = capsys.readouterr().out
    assert "\\frac{2 \\left(J_{2} - J_{3}\\right)" in out
    assert "⎡" not in out  # no pretty-printed box drawing
