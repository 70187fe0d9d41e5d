"""The proof procedure: named reduction strategies, negative controls, honest labels.

A check function receives a :class:`Derivation` and records what it shows:

- :meth:`Derivation.prove_equal` reduces ``lhs - rhs`` to zero with one named,
  cheap strategy (``expand``, ``cancel``, ``trigsimp``, ``together``,
  ``expand_trig``; ``simplify`` only as a last resort).  Label ``proved``.
- :meth:`Derivation.reject` is the negative control: the *same* strategy must
  fail on a deliberately wrong variant, and an exact rational point must show
  the variant false (so a checker that accepts everything is caught).
- :meth:`Derivation.refute` shows a printed (book) statement false at an exact
  point: the first half of an erratum.
- :meth:`Derivation.witness_unequal` proves a "≠" by an exact counterexample.
- :meth:`Derivation.probable_equal` evaluates at random exact rational points:
  label ``probabilistic``, never ``proved``.
- :meth:`Derivation.numeric_close` compares floats within a named tolerance:
  label ``numeric``.
- :meth:`Derivation.holds_for_examples` runs a randomised property (hypothesis, a
  stated number of examples, the derivation's seed): label ``numeric``;
  :meth:`Derivation.reject_property` is its negative control.
- :meth:`Derivation.confirm` records an independent route (numeric through
  ``mechanics``, a limit, a second derivation) for a derived result.

A failed step raises :class:`CheckFailure`.  The label of a check is the weakest
label among its claims: proved > probabilistic > numeric.
"""

from __future__ import annotations

import random
import time
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import sympy as sp
from sympy.polys.polyerrors import CoercionFailed
from sympy.polys.rings import ring

__all__ = ["LABELS", "STRATEGIES", "CheckFailure", "Derivation", "Step", "is_zero"]


def _tan_half(expr):
    """Rewrite sin x, cos x as rational functions of T = tan(x/2), then cancel.

    An identity between rational functions of T holds for every x except odd
    multiples of π (T infinite), hence for all x by continuity: a proof.
    """
    expr = sp.expand_trig(sp.sympify(expr))
    args = {a.args[0] for a in expr.atoms(sp.sin, sp.cos)}
    reps = {}
    for i, x in enumerate(sorted(args, key=str)):
        T = sp.Symbol(f"_T{i}", real=True)
        reps[sp.sin(x)] = 2 * T / (1 + T**2)
        reps[sp.cos(x)] = (1 - T**2) / (1 + T**2)
    return sp.cancel(expr.xreplace(reps))


#: Reduction strategies by cost, cheapest first.  Each maps an expression to an
#: equivalent one; a difference is proved zero when the result is exactly 0.
STRATEGIES = {
    "expand": sp.expand,
    "cancel": sp.cancel,
    "together": lambda e: sp.cancel(sp.together(e)),
    # Over a common denominator that cannot vanish (here: sums of squares of a
    # non-zero quaternion), the expression is zero iff its expanded numerator is.
    "numerator": lambda e: sp.expand(sp.numer(sp.together(e))),
    "trigsimp": lambda e: sp.trigsimp(sp.expand(e)),
    "expand_trig": lambda e: sp.expand(sp.expand_trig(e)),
    "tan_half": _tan_half,
    "simplify": sp.simplify,
}

#: Labels, strongest first.
LABELS = ("proved", "probabilistic", "numeric")


def _short(text: str, limit: int = 240) -> str:
    """``text`` cut to ``limit`` characters (a drawn example can be long)."""
    return text if len(text) <= limit else text[: limit - 1] + "…"


class CheckFailure(AssertionError):
    """A claim of a check did not hold (or a negative control was accepted)."""


@dataclass
class Step:
    """One recorded step: prose, an optional expression, and what kind of step."""

    text: str
    expr: Any = None
    kind: str = (
        "note"  # note | proved | rejected | refuted | witness | probabilistic | numeric | confirmed
    )
    seconds: float = 0.0
    #: a claim's two sides as the check stated them (proved or rejected): what
    #: ``bodycheck explain`` shows as the algebra before and after the rule
    sides: tuple | None = None
    #: the rule (strategy) that reduced, or failed to reduce, their difference
    rule: str = ""
    #: the exact point where a negative control's, a refutation's or a witness' two sides differ
    #: ({symbol, f(t) or derivative: rational value}, over the differing entry's symbols)
    point: dict | None = None
    #: an erratum's two forms (derived, printed), shown side by side beside ``expr``
    #: (derived − printed)
    forms: tuple | None = None
    #: a property's first drawn examples (their reprs), as hypothesis drew them
    examples: tuple[str, ...] = ()


def _entries(expr) -> list:
    if isinstance(expr, sp.MatrixBase):
        return list(expr)
    if isinstance(expr, list | tuple):
        return [e for x in expr for e in _entries(x)]
    return [sp.sympify(expr)]


def is_zero(expr, strategy: str) -> bool:
    """True when the named strategy reduces every entry of ``expr`` to exactly 0."""
    try:
        reduce = STRATEGIES[strategy]
    except KeyError:
        raise ValueError(f"unknown strategy {strategy!r}; choose from {list(STRATEGIES)}") from None
    # f(t) and its derivatives become independent symbols: after differentiation
    # the expression is algebraic in them, and it vanishes identically as a
    # function of t iff it vanishes for all independent values (at any t the
    # values f(t), f'(t), ... can be chosen freely).  This keeps cancel fast.
    exact = _EXACT.get(strategy)
    for e in _entries(expr):
        e = _functions_to_symbols(e)
        verdict = exact(e) if exact is not None else None
        if verdict is None:
            verdict = reduce(e) == 0
        if not verdict:
            return False
    return True


def _polynomial(expr):
    """``expr`` as an element of ℚ[x₁, …, xₙ] over its free symbols (sympy's sparse
    polynomial ring), or None when it is not one: a non-integer power, a function, a
    float, an irrational or complex constant, or no symbol at all."""
    gens = sorted(expr.free_symbols, key=str)
    if not gens or expr.atoms(sp.Float):
        return None
    try:
        R, *_ = ring(gens, sp.QQ)
        return R.from_expr(expr)
    except (ValueError, CoercionFailed):
        return None


def _polynomial_zero(expr) -> bool | None:
    """Is ``expr``, a polynomial with rational coefficients, the zero polynomial?  None
    when it is not such a polynomial."""
    if expr.is_Rational:
        return expr == 0
    p = _polynomial(expr)
    return None if p is None else not p


def _rational_zero(expr) -> bool | None:
    """Is ``expr``, a rational function with rational coefficients, identically zero?
    None when it is not one.  ``together`` writes it as N/D with D a non-zero
    polynomial, so it vanishes iff N is the zero polynomial."""
    if expr.atoms(sp.Float):
        return None
    return _polynomial_zero(sp.numer(sp.together(expr)))


#: The same decision, made exactly and faster, for the strategies whose verdict on a
#: polynomial or rational function with rational coefficients is "is it the zero
#: polynomial / rational function": arithmetic in sympy's sparse polynomial ring
#: instead of ``expand`` on expression trees (eq2.63's proof: 15 s → 0.6 s).
#: ``None`` (not such an expression) falls back to the strategy itself; a test holds
#: the two routes to the same verdict.
_EXACT = {
    "expand": _polynomial_zero,
    "cancel": _rational_zero,
    "together": _rational_zero,
    "numerator": _rational_zero,
}


def _difference(lhs, rhs):
    if isinstance(lhs, sp.MatrixBase) or isinstance(rhs, sp.MatrixBase):
        L, R = sp.Matrix(lhs), sp.Matrix(rhs)
        if L.shape != R.shape:
            raise CheckFailure(f"shapes differ: {L.shape} vs {R.shape}")
        return L - R
    return sp.sympify(lhs) - sp.sympify(rhs)


def _rational_point(symbols, rng: random.Random) -> dict:
    point = {}
    for s in symbols:
        q = Fraction(rng.randint(-97, 97), rng.randint(1, 13))
        if s.is_positive or s.is_nonnegative:
            q = abs(q) + Fraction(1, rng.randint(2, 11))
        point[s] = sp.Rational(q.numerator, q.denominator)
    return point


def _replaced_functions(expr) -> tuple[Any, dict]:
    """``expr`` with its applied undefined functions f(t) and their derivatives replaced
    by plain symbols, and the map back (each new symbol to what it stands for)."""
    # numbered in an order that does not depend on the hash seed (the sets' order
    # does), so that the exact point a negative control records is the same in every run
    derivs = sorted(
        expr.atoms(sp.Derivative), key=lambda d: (-sp.count_ops(d), sp.default_sort_key(d))
    )
    reps = {d: sp.Symbol(f"_d{i}", real=True) for i, d in enumerate(derivs)}
    expr = expr.xreplace(reps)
    funcs = sorted(
        (
            f
            for f in expr.atoms(sp.Function)
            if isinstance(f.func, sp.core.function.UndefinedFunction)
        ),
        key=sp.default_sort_key,
    )
    reps2 = {f: sp.Symbol(f"_f{i}", real=True) for i, f in enumerate(funcs)}
    back = {v: k for k, v in (reps | reps2).items()}
    return expr.xreplace(reps2), back


def _functions_to_symbols(expr):
    """Replace applied undefined functions f(t) and their derivatives by plain symbols."""
    return _replaced_functions(expr)[0]


def _evaluate_nonzero(diff, rng: random.Random, tries: int = 8) -> dict | None:
    """An exact point where some entry of ``diff`` is non-zero, or None: the values of
    that entry's symbols (and of its f(t) and derivatives, by what they stand for)."""
    replaced = [_replaced_functions(e) for e in _entries(diff)]
    symbols = sorted(set().union(*(e.free_symbols for e, _ in replaced)), key=str)
    for _ in range(tries):
        point = _rational_point(symbols, rng)
        for e, back in replaced:
            try:
                val = e.xreplace(point)
                val = sp.nsimplify(val) if val.has(sp.Float) else val
                val = sp.N(val, 50)
            except (ZeroDivisionError, ValueError):
                continue
            if val.is_number and val.is_finite is not False and abs(val) > sp.Rational(1, 10**30):
                own = sorted(e.free_symbols, key=str)
                return {back.get(s, s): point[s] for s in own}
    return None


@dataclass
class Derivation:
    """Collects the steps, claims and quantities of one check."""

    seed: int = 20261122
    steps: list[Step] = field(default_factory=list)
    quantities: dict[str, Any] = field(default_factory=dict)
    labels: set[str] = field(default_factory=set)
    strategies: set[str] = field(default_factory=set)
    n_proved: int = 0
    n_rejected: int = 0
    n_refuted: int = 0
    n_confirmed: int = 0

    def __post_init__(self) -> None:
        self._rng = random.Random(self.seed)

    # -- prose and results ---------------------------------------------------
    def note(self, text: str, expr: Any = None) -> None:
        """Record a step of the derivation (no claim)."""
        self.steps.append(Step(text, expr))

    def quantity(self, name: str, expr) -> Any:
        """Record a derived quantity, in the book's symbols, for ``explain --json``."""
        expr = sp.sympify(expr) if not isinstance(expr, sp.MatrixBase) else sp.ImmutableMatrix(expr)
        self.quantities[name] = expr
        self.steps.append(Step(f"{name} =", expr))
        return expr

    # -- claims --------------------------------------------------------------
    def prove_equal(self, lhs, rhs, *, strategy: str = "expand", claim: str) -> None:
        """Prove lhs = rhs by reducing the difference to 0 with ``strategy``."""
        t0 = time.perf_counter()
        ok = is_zero(_difference(lhs, rhs), strategy)
        dt = time.perf_counter() - t0
        if not ok:
            raise CheckFailure(f"not proved by {strategy}: {claim}")
        self.steps.append(
            Step(
                f"proved ({strategy}, {dt:.2f} s): {claim}",
                None,
                "proved",
                dt,
                sides=(lhs, rhs),
                rule=strategy,
            )
        )
        self.labels.add("proved")
        self.strategies.add(strategy)
        self.n_proved += 1

    def prove_zero(self, expr, *, strategy: str = "expand", claim: str) -> None:
        """Prove ``expr`` = 0 (entrywise for matrices)."""
        self.prove_equal(
            expr,
            sp.zeros(*expr.shape) if isinstance(expr, sp.MatrixBase) else 0,
            strategy=strategy,
            claim=claim,
        )

    def reject(self, lhs, rhs, *, strategy: str = "expand", claim: str) -> None:
        """Negative control: the wrong statement lhs = rhs must not be proved.

        The same strategy must fail, *and* an exact rational point must show the
        two sides differ (so the rejection is not a weakness of the strategy).
        """
        diff = _difference(lhs, rhs)
        if is_zero(diff, strategy):
            raise CheckFailure(f"negative control accepted by {strategy}: {claim}")
        point = _evaluate_nonzero(diff, self._rng)
        if point is None:
            raise CheckFailure(f"negative control not shown false at any exact point: {claim}")
        self.steps.append(
            Step(
                f"rejected wrong variant ({strategy}; false at an exact point): {claim}",
                None,
                "rejected",
                sides=(lhs, rhs),
                rule=strategy,
                point=point,
            )
        )
        self.n_rejected += 1

    def refute(self, lhs, rhs, *, claim: str) -> None:
        """Show the printed statement lhs = rhs false (exactly): half of an erratum."""
        diff = _difference(lhs, rhs)
        point = _evaluate_nonzero(diff, self._rng)
        if point is None:
            raise CheckFailure(f"printed statement not refuted: {claim}")
        self.steps.append(
            Step(
                f"printed form is false: {claim}; derived − printed =",
                diff,
                "refuted",
                point=point,
                forms=(lhs, rhs),
            )
        )
        self.n_refuted += 1

    def witness_unequal(self, lhs, rhs, subs: dict, *, claim: str) -> None:
        """Prove lhs ≠ rhs by one exact point where they differ."""
        diff = _difference(lhs, rhs)
        vals = [sp.nsimplify(sp.simplify(e.subs(subs))) for e in _entries(diff)]
        if all(v == 0 for v in vals):
            raise CheckFailure(f"no witness at {subs}: {claim}")
        self.steps.append(
            Step(f"proved by witness {subs}: {claim}", diff.subs(subs), "witness", point=subs)
        )
        self.labels.add("proved")
        self.n_proved += 1

    def reject_witness(self, lhs, rhs, subs: dict, *, claim: str) -> None:
        """Negative control for :meth:`witness_unequal`: on an equal pair it finds no witness."""
        try:
            self.witness_unequal(lhs, rhs, subs, claim=claim)
        except CheckFailure:
            self.steps.append(
                Step(f"rejected: no witness for the equal pair {claim}", None, "rejected")
            )
            self.n_rejected += 1
            return
        raise CheckFailure(f"witness procedure claims an equal pair differs: {claim}")

    def probable_equal(self, lhs, rhs, *, points: int = 12, claim: str) -> None:
        """Support lhs = rhs by exact evaluation at random rational points."""
        diff = _difference(lhs, rhs)
        entries = [_functions_to_symbols(e) for e in _entries(diff)]
        symbols = sorted(set().union(*(e.free_symbols for e in entries)), key=str)
        for _ in range(points):
            pt = _rational_point(symbols, self._rng)
            for e in entries:
                if sp.simplify(e.xreplace(pt)) != 0:
                    raise CheckFailure(f"fails at {pt}: {claim}")
        self.steps.append(
            Step(f"holds at {points} random exact rational points: {claim}", None, "probabilistic")
        )
        self.labels.add("probabilistic")
        self.n_proved += 1

    @staticmethod
    def _max_error(actual, expected, what: str) -> tuple[float, float]:
        import numpy as np

        a = np.asarray(actual, dtype=float)
        e = np.asarray(expected, dtype=float)
        if a.shape != e.shape:
            raise CheckFailure(f"{what}: shapes differ, {a.shape} vs {e.shape}")
        err = float(np.max(np.abs(a - e))) if a.size else 0.0
        return err, float(np.max(np.abs(e))) if e.size else 0.0

    def numeric_close(self, actual, expected, *, atol: float, claim: str) -> None:
        """A float comparison within a named absolute tolerance (label ``numeric``)."""
        err, _ = self._max_error(actual, expected, claim)
        if not err <= atol:
            raise CheckFailure(f"{claim}: max error {err:.3g} > atol {atol:.3g}")
        self.steps.append(
            Step(f"numeric: {claim} (max error {err:.2g} <= {atol:.2g})", None, "numeric")
        )
        self.labels.add("numeric")
        self.n_proved += 1

    def holds_for_examples(self, prop, strategy, *, examples: int, claim: str) -> None:
        """A randomised property: ``prop(*args)`` holds for ``examples`` argument tuples
        drawn from the hypothesis ``strategy`` with this derivation's seed (label
        ``numeric``; :mod:`identities.verify.properties`)."""
        from identities.verify.properties import search_counterexample

        t0 = time.perf_counter()
        drawn: list[tuple] = []
        found = search_counterexample(
            prop, strategy, examples=examples, seed=self.seed, drawn=drawn
        )
        dt = time.perf_counter() - t0
        if found is not None:
            raise CheckFailure(f"{claim}: fails for {found.arguments!r}: {found.message}")
        self.steps.append(
            Step(
                f"holds for {examples} drawn examples (hypothesis, seed {self.seed}): {claim}",
                None,
                "numeric",
                dt,
                rule="property",
                examples=tuple(_short(repr(a)) for a in drawn),
            )
        )
        self.labels.add("numeric")
        self.n_proved += 1

    def reject_property(self, prop, strategy, *, examples: int, claim: str) -> None:
        """Negative control of a property: the same search, on a deliberately wrong
        variant, must find a counterexample (the first one found is shown)."""
        from identities.verify.properties import search_counterexample

        t0 = time.perf_counter()
        found = search_counterexample(
            prop, strategy, examples=examples, seed=self.seed, shrink=False
        )
        dt = time.perf_counter() - t0
        if found is None:
            raise CheckFailure(
                f"negative control accepted: no counterexample in {examples} examples: {claim}"
            )
        self.steps.append(
            Step(
                f"rejected wrong variant (a counterexample in {examples} drawn examples): "
                f"{claim}; fails for {_short(repr(found.arguments))}",
                None,
                "rejected",
                dt,
                rule="property",
            )
        )
        self.n_rejected += 1

    def confirm(self, actual, expected, *, atol: float, route: str) -> None:
        """An independent numeric route agrees with a derived quantity.

        A confirmation supports a derivation; it is not itself a claim, so it
        does not weaken the check's label.
        """
        err, _ = self._max_error(actual, expected, route)
        if not err <= atol:
            raise CheckFailure(
                f"independent route disagrees: {route}: max error {err:.3g} > atol {atol:.3g}"
            )
        self.steps.append(
            Step(
                f"confirmed by an independent route: {route} (max error {err:.2g} <= {atol:.2g})",
                None,
                "confirmed",
            )
        )
        self.n_confirmed += 1

    def confirm_exact(self, actual, expected, *, route: str, strategy: str = "expand") -> None:
        """An independent symbolic route gives the same quantity."""
        if not is_zero(_difference(actual, expected), strategy):
            raise CheckFailure(f"independent route disagrees: {route}")
        self.steps.append(
            Step(f"confirmed by an independent route ({strategy}): {route}", None, "confirmed")
        )
        self.n_confirmed += 1

    @property
    def label(self) -> str:
        """The weakest label among the claims, or '' when no claim was made."""
        for lab in reversed(LABELS):
            if lab in self.labels:
                return lab
        return ""
