"""One sample per strategy, shared by every question a test asks of it (issue 35).

A strategy-quality test asks many questions of one strategy: "never outside its bounds",
"reaches its upper end", "reaches its lower end", ...  Each used to be its own
``hypothesis.find`` run of 500–2000 draws; drawing is what costs (a contact is two
rigid bodies, an inertia tensor, a geometry), so one test paid for 10⁴ draws or more.
Here the draws of a strategy object are made once and every question reads them.  They
come from ``find`` itself, with a predicate that keeps each example and never matches,
so they are hypothesis' own generation (its boundary values and simple examples
included), as before.

- :func:`never` holds when none of n draws satisfies the predicate; it names the first
  that does.
- :func:`shared` gives one strategy object per factory and arguments, so the tests that
  ask questions of the same strategy (``rotvecs()`` reaching each of its regimes, one
  parametrised test per regime) read one sample.  The runs being seeded (below), a
  fresh object of the same strategy would draw the very same sample: sharing it changes
  what is drawn not at all, only how often.
- :func:`drawn_from` is a strategy that picks among the first n draws of another
  (``st.sampled_from`` of them), for a test of one part of a composite draw (a body's
  mass or position) whose other part is costly, drawn apart and not what the test asks
  about (the inertia tensor: about half of the ~4 ms a rigid body takes), given to the
  factory as that part's strategy.  The part keeps its variety (n of its own draws,
  read from its sample, so drawn once for every test that reads them) at the cost of
  one choice per draw.
- :func:`found` holds when one of the first n draws does (it reads the draws made so
  far first, and draws more only while none matches).  For an event of frequency p, n
  draws miss it with probability (1 − p)ⁿ: at n = 1000 that is below 10⁻⁶ for
  p ≥ 1.4 % and below 10⁻⁴ for p ≥ 0.92 %; a rarer event needs a larger n, stated
  where it is used.

Draws are added in runs of ``find`` of :data:`RUN` draws each, so a question answered
by the first draws costs only those, and a sample's k-th run is the same whichever
question asked for it (a run's size never depends on how many draws were asked for).  Under a derandomised
profile (``ci``) each run is seeded by its index (0, 1, 2, ...): the sample is the same
on every run of the suite, and its runs are different draws (a derandomised ``find``
seeds from the predicate's function, the same for every run, so the runs of a grown
sample used to repeat the first: 1000 draws of ``particle_systems()`` held 387 distinct
values).  Under ``dev`` each run is seeded too, from one random number drawn per
process (``secrets``: pytest-randomly reseeds ``random`` for every test, and an unseeded
``find`` then repeated its draws run after run as well).  A sample lives as long as
its strategy object, which a test builds for itself or takes from :func:`shared` (the
factories of :mod:`mechanics.strategies` keep one object per plain arguments,
``_common.memoised``, so a test's own ``ms.masses(...)`` may be the object another test
drew from first: the same draws either way, for the reason just given):
nothing but draws is shared, read and never changed, and since the same strategy
draws the same sample whichever test grows it first, tests stay independent of each
other and of their order.
"""

from __future__ import annotations

import contextlib
import random
import secrets
import weakref

from hypothesis import Phase, find, settings
from hypothesis import strategies as st
from hypothesis.errors import NoSuchExample

__all__ = ["drawn_from", "found", "never", "sample", "shared"]

#: the draws of one run of ``find``
RUN = 100
#: the seeds of a sample's runs under a random profile start here (one number per process)
_RANDOM_BASE = secrets.randbits(64)


class _Draws:
    __slots__ = ("examples", "exhausted", "runs")

    def __init__(self) -> None:
        self.examples: list = []
        self.runs = 0  # find runs made so far
        self.exhausted = False  # hypothesis ran out of distinct examples (a finite strategy)


_DRAWS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def _run(strategy, k: int, run: int) -> list:
    """k examples of the ``run``-th ``find`` run of a sample (fewer if the strategy has
    fewer): seeded by ``run`` under a derandomised profile, by a random base + ``run``
    otherwise."""
    got: list = []

    def keep(x) -> bool:
        got.append(x)
        return False

    budget = settings(max_examples=k, database=None, phases=[Phase.generate])
    seeded = random.Random(run if _derandomized() else _RANDOM_BASE + run)
    with contextlib.suppress(NoSuchExample):
        find(strategy, keep, settings=budget, random=seeded)
    return got


_SHARED: dict = {}


def shared(factory, **kwargs):
    """``factory(**kwargs)``, one object per factory and arguments (hashable) for the
    whole session of a worker (see the module's docstring)."""
    key = (factory, tuple(sorted(kwargs.items())))
    s = _SHARED.get(key)
    if s is None:
        s = _SHARED[key] = factory(**kwargs)
    return s


def _derandomized() -> bool:
    """Is the loaded profile derandomised (``ci``)?"""
    return bool(settings.default.derandomize)


def _draws(strategy) -> _Draws:
    d = _DRAWS.get(strategy)
    if d is None:
        d = _DRAWS[strategy] = _Draws()
    return d


def _grow(strategy, d: _Draws, n: int) -> None:
    got = _run(strategy, RUN, d.runs)
    d.runs += 1
    d.exhausted = len(got) < RUN
    d.examples.extend(got)


def sample(strategy, n: int) -> list:
    """The first n draws of ``strategy`` (fewer for a strategy of fewer values)."""
    d = _draws(strategy)
    while len(d.examples) < n and not d.exhausted:
        _grow(strategy, d, n)
    return d.examples[:n]


def drawn_from(strategy, n: int = RUN):
    """A strategy picking one of the first n draws of ``strategy`` (its sample, drawn
    once; see the module's docstring)."""
    return st.sampled_from(sample(strategy, n))


def never(strategy, predicate, n: int) -> None:
    """None of n draws satisfies ``predicate`` (else: the first that does)."""
    for x in sample(strategy, n):
        assert not predicate(x), f"a draw satisfies the predicate it never should: {x!r}"


def found(strategy, predicate, n: int):
    """The first of n draws that satisfies ``predicate`` (else the test fails, saying how
    many draws missed it)."""
    d = _draws(strategy)
    i = 0
    while True:
        for x in d.examples[i:n]:
            if predicate(x):
                return x
        i = min(len(d.examples), n)
        if i >= n or d.exhausted:
            raise AssertionError(f"none of {i} draws satisfies the predicate")
        _grow(strategy, d, n)
