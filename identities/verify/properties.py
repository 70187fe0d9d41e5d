"""Randomised properties as catalogue checks: hypothesis, a stated number of examples, a seed.

A *property* is a function that takes drawn arguments and raises ``AssertionError`` when
an invariant fails for them (momentum conservation in an impact, orthogonality of a
rotation...).  :func:`search_counterexample` draws ``examples`` argument tuples from a
hypothesis strategy with a fixed seed (the same examples on every run, no example
database) and returns the smallest failing one that hypothesis shrinks to, or ``None``.

A property check (kind ``property``) records with
:meth:`identities.verify.proof.Derivation.holds_for_examples` that the property found no
counterexample, and with :meth:`~identities.verify.proof.Derivation.reject_property` that
the *same* search finds one for a deliberately wrong variant (its negative control: a
search too weak to fail anything is caught).  The label is ``numeric``: floats at drawn
points, never a proof.
"""

from __future__ import annotations

import random
from collections.abc import Callable
from typing import Any, NamedTuple

__all__ = ["Counterexample", "search_counterexample"]


class Counterexample(NamedTuple):
    """The failing arguments (shrunk unless asked not to) and the assertion's message."""

    arguments: tuple
    message: str


def _failure(prop: Callable[..., Any], args: tuple) -> str | None:
    """The assertion message (or crash) of ``prop(*args)``, or None when it holds."""
    try:
        prop(*args)
    except AssertionError as exc:
        return f"AssertionError: {exc}" if str(exc) else "AssertionError"
    except Exception as exc:  # a crash on a drawn example is a failure too
        return f"{type(exc).__name__}: {exc}"
    return None


def search_counterexample(
    prop: Callable[..., Any],
    strategy,
    *,
    examples: int,
    seed: int,
    shrink: bool = True,
    drawn: list[tuple] | None = None,
    keep: int = 3,
) -> Counterexample | None:
    """Draw ``examples`` argument tuples from ``strategy`` (a hypothesis strategy of
    tuples) with ``seed``; the failing arguments of ``prop`` (shrunk to the simplest
    unless ``shrink`` is false: a negative control needs one, not the simplest, and
    shrinking can take a hundred times the search), or ``None``.

    Deterministic: the same seed and examples give the same draws on every run, and no
    example database is read or written (hypothesis' ``find`` with ``database=None``).
    When ``drawn`` is a list, the first ``keep`` argument tuples drawn are appended to it
    (what a reader sees as the property's examples).
    """
    import warnings

    from hypothesis import HealthCheck, Phase, find, settings
    from hypothesis.errors import NoSuchExample

    config = settings(
        max_examples=examples,
        database=None,
        deadline=None,
        phases=[Phase.generate, Phase.shrink] if shrink else [Phase.generate],
        # the catalogue states its examples and seed; slow draws are not a failure here
        suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
    )
    with warnings.catch_warnings():
        # find() runs the examples as hypothesis would in a test; a numpy warning in a
        # property is turned into an error so that it fails like it does under pytest
        warnings.simplefilter("error", RuntimeWarning)
        try:

            def fails(a: tuple) -> bool:
                if drawn is not None and len(drawn) < keep:
                    drawn.append(a)
                return _failure(prop, a) is not None

            args = find(
                strategy,
                fails,
                settings=config,
                random=random.Random(seed),
            )
        except NoSuchExample:
            return None
        return Counterexample(args, _failure(prop, args) or "fails only when not shrunk")
