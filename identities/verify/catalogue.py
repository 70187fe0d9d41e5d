"""The catalogue: one registry of checks, and the book's inventory of numbered items.

Every numbered equation (``eqN.M``), worked example (``EN.M``) and problem
(``PN.M``) of the book is an *item*; the inventory (``data/book_inventory.json``,
written by ``tools/book_inventory.py`` from the book's text) gives each its
chapter, section and page.  A *check* is a frozen record registered with
:func:`check`; it names the items it verifies (``covers``), the definitions it
builds on (``defines``) and the items whose printed form it shows false
(``errata``).  Three readers use the registry: ``bodycheck check`` (runs it),
pytest (``tests/test_catalogue.py`` runs every entry) and ``CHECKS.md`` (rendered
by :mod:`identities.verify.render`).

Item status: ``erratum`` (printed form false, corrected form proved), ``verified``,
``definition`` (a definition, exercised by the checks that build on it) or
``pending`` (no check yet: a chapter not done).
"""

from __future__ import annotations

import importlib
import json
import re
import time
import traceback
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cache
from importlib import resources
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # the proof machinery imports sympy: only run_check needs it
    from identities.verify.proof import Derivation

__all__ = [
    "CHAPTER_MODULES",
    "DONE_CHAPTERS",
    "KINDS",
    "REGISTRY",
    "Check",
    "Item",
    "Outcome",
    "check",
    "checks",
    "inventory",
    "item_rows",
    "load_all",
    "run_check",
]

KINDS = ("proof", "derivation", "property", "stability", "scene", "benchmark")
ID_PATTERN = re.compile(r"^(eq[1-8]\.\d{1,3}|[EP][1-8]\.\d{1,2}|thm\.[a-z0-9][a-z0-9-]*)$")

#: the identities package's folder (this module lives in its ``verify`` room)
_ROOT = Path(__file__).resolve().parent.parent
#: Modules that register checks, imported by :func:`load_all`: every module of the
#: rooms ``identities/book/`` (``chNN/`` per chapter, ``scenes/``),
#: ``identities/properties/`` and ``identities/stability/``, found on disk and imported in sorted order so the
#: registry order is reproducible.
CHAPTER_MODULES = tuple(
    sorted(
        ".".join(("identities", *p.relative_to(_ROOT).with_suffix("").parts))
        for room in ("book", "properties", "stability")
        for p in (_ROOT / room).rglob("*.py")
        if p.name != "__init__.py"
    )
)

#: Chapters whose every item must be covered (a test enforces it).
DONE_CHAPTERS = frozenset({1, 2, 3, 4, 5, 6, 7, 8})


@dataclass(frozen=True)
class Item:
    """A numbered item of the book."""

    id: str
    chapter: int
    section: str
    page: int

    @property
    def category(self) -> str:
        return {"e": "equation", "E": "example", "P": "problem"}[self.id[0]]


@cache
def inventory() -> dict[str, Item]:
    """All numbered items of the book, in book order."""
    text = resources.files("identities").joinpath("data/book_inventory.json").read_text("utf-8")
    raw = json.loads(text)
    return {k: Item(k, v["chapter"], v["section"], v["page"]) for k, v in raw.items()}


@dataclass(frozen=True)
class Check:
    """One registered check."""

    id: str
    title: str
    kind: str
    func: Callable[[Derivation], None] = field(repr=False, compare=False)
    covers: tuple[str, ...] = ()
    defines: tuple[str, ...] = ()
    errata: tuple[str, ...] = ()
    statement: str = ""
    printed: str = ""
    corrected: str = ""
    reading: str = ""

    @property
    def status(self) -> str:
        return "erratum" if self.errata else "verified"

    @property
    def where(self) -> str:
        return f"{self.func.__module__}:{self.func.__qualname__}"

    @property
    def items(self) -> tuple[str, ...]:
        return self.covers + self.defines

    @property
    def chapter(self) -> int | None:
        ids = [self.id, *self.items]
        for i in ids:
            if not i.startswith("thm."):
                return int(re.findall(r"\d", i)[0])
        return None

    @property
    def item(self) -> Item | None:
        """The book item this check is anchored to (its own id, or its first cover)."""
        inv = inventory()
        for i in (self.id, *self.items):
            if i in inv:
                return inv[i]
        return None


REGISTRY: dict[str, Check] = {}


def check(
    id: str,
    title: str,
    *,
    kind: str,
    covers: tuple[str, ...] | list[str] = (),
    defines: tuple[str, ...] | list[str] = (),
    errata: tuple[str, ...] | list[str] = (),
    statement: str = "",
    printed: str = "",
    corrected: str = "",
    reading: str = "",
):
    """Register the decorated function ``f(d: Derivation) -> None`` as a check."""

    def register(func: Callable[[Derivation], None]) -> Callable[[Derivation], None]:
        if not ID_PATTERN.match(id):
            raise ValueError(f"check id {id!r} is not eqN.M, EN.M, PN.M or thm.<name>")
        if kind not in KINDS:
            raise ValueError(f"check {id}: kind {kind!r} not in {KINDS}")
        if id in REGISTRY:
            raise ValueError(f"check id {id!r} registered twice")
        inv = inventory()
        unknown = [i for i in (*covers, *defines, *errata) if i not in inv]
        if unknown:
            raise ValueError(f"check {id}: unknown book items {unknown}")
        if errata and not (printed and corrected):
            raise ValueError(f"check {id}: an erratum needs the printed and the corrected form")
        REGISTRY[id] = Check(
            id,
            title,
            kind,
            func,
            tuple(covers),
            tuple(defines),
            tuple(errata),
            statement,
            printed,
            corrected,
            reading,
        )
        return func

    return register


def load_all() -> dict[str, Check]:
    """Import every chapter module (registering its checks) and return the registry."""
    for name in CHAPTER_MODULES:
        importlib.import_module(name)
    # registry order = CHAPTER_MODULES order, then definition order within a module,
    # whatever imported a module first (a test may import one directly)
    rank = {name: i for i, name in enumerate(CHAPTER_MODULES)}
    entries = list(REGISTRY.values())
    position = {c.id: i for i, c in enumerate(entries)}
    entries.sort(key=lambda c: (rank.get(c.func.__module__, len(rank)), position[c.id]))
    if [c.id for c in entries] != list(REGISTRY):
        REGISTRY.clear()
        REGISTRY.update((c.id, c) for c in entries)
    return REGISTRY


def checks(
    *, chapter: int | None = None, ids: list[str] | None = None, kind: str | None = None
) -> list[Check]:
    """Registered checks filtered by chapter, ids and kind, in registry order."""
    reg = load_all()
    out = list(reg.values())
    if ids:
        unknown = [i for i in ids if i not in reg]
        if unknown:
            raise KeyError(", ".join(unknown))
        out = [reg[i] for i in ids]
    if chapter is not None:
        out = [c for c in out if c.chapter == chapter]
    if kind is not None:
        out = [c for c in out if c.kind == kind]
    return out


@dataclass
class Outcome:
    """What running one check gave (picklable: no sympy objects)."""

    id: str
    passed: bool
    label: str
    status: str
    seconds: float
    message: str = ""
    chapter: int | None = None
    #: the reduction strategies its proofs used, and its slowest proof step (text, seconds)
    strategies: tuple[str, ...] = ()
    slowest_step: tuple[str, float] = ("", 0.0)


def _structure_problems(c: Check, d: Derivation) -> list[str]:
    """A check must make the claims its kind and status promise."""
    problems = []
    if d.n_proved == 0:
        problems.append("it made no claim")
    if c.kind == "proof" and d.n_rejected == 0:
        problems.append("a proof without a negative control")
    if c.kind == "property" and d.n_rejected == 0:
        problems.append("a property without a negative control (a wrong variant it rejects)")
    if c.errata and d.n_refuted == 0:
        problems.append("an erratum that does not show the printed form failing")
    if c.id.startswith("P") and (not d.quantities or d.n_confirmed == 0):
        problems.append("a problem needs derived quantities and an independent confirmation")
    return problems


def run_check(c: Check) -> tuple[Outcome, Derivation]:
    """Run one check; never raises for a failing check (the Outcome says so)."""
    from identities.verify.proof import CheckFailure, Derivation

    d = Derivation()
    t0 = time.perf_counter()
    try:
        c.func(d)
        problems = _structure_problems(c, d)
        passed, message = (not problems), "; ".join(problems)
    except CheckFailure as exc:
        passed, message = False, str(exc)
    except Exception as exc:  # a crash is a failure, reported with its origin
        tb = traceback.extract_tb(exc.__traceback__)[-1]
        passed = False
        message = f"{type(exc).__name__}: {exc} ({tb.filename.rsplit('/', 1)[-1]}:{tb.lineno})"
    seconds = time.perf_counter() - t0
    timed = [s for s in d.steps if s.seconds > 0]
    slowest = max(timed, key=lambda s: s.seconds) if timed else None
    outcome = Outcome(
        c.id,
        passed,
        d.label,
        c.status,
        seconds,
        message,
        c.chapter,
        tuple(sorted(d.strategies)),
        (slowest.text, slowest.seconds) if slowest else ("", 0.0),
    )
    return outcome, d


def run_by_id(check_id: str) -> Outcome:
    """Run the check ``check_id`` (for worker processes)."""
    return run_check(load_all()[check_id])[0]


@dataclass(frozen=True)
class ItemRow:
    """One row of CHECKS.md: a book item and the checks behind it."""

    item: Item
    status: str
    checks: tuple[Check, ...]


def item_rows() -> list[ItemRow]:
    """Every book item with its status and covering checks, in book order."""
    reg = load_all()
    rows = []
    for item in inventory().values():
        covering = tuple(c for c in reg.values() if item.id in c.covers or item.id == c.id)
        defining = tuple(c for c in reg.values() if item.id in c.defines)
        if any(item.id in c.errata for c in covering):
            status = "erratum"
        elif covering:
            status = "verified"
        elif defining:
            status = "definition"
        else:
            status = "pending"
        rows.append(ItemRow(item, status, covering + defining))
    return rows
