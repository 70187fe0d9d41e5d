"""Find checks by topic: ``bodycheck search restitution``, ``bodycheck explain parallel-axis``.

Conventions
-----------
- **Topic words** of a check: its title and statement, the headings of the book's
  sections its items stand in (and of their parent sections: 4.3.1 "The Physical
  Pendulum" under 4.3 "Fixed Axis Rotation and Reaction Forces";
  ``identities/data/book_sections.json``, written by ``tools/book_inventory.py``),
  and the well-known names in :data:`NAMES` (parallel-axis, Steiner, Euler's
  equations, …), each tied by hand to the checks that carry it.
- **Matching**: a query matches a check when every one of its words (lower case,
  hyphens and apostrophes as spaces, accents dropped: "König" is "konig") starts a word
  of the check's topic words; a name of :data:`NAMES` whose words the query's begin
  brings its checks.  Matches come in catalogue order, the checks of the names the query begins
  (parallel-axis: the parallel axis theorem's) first.
- **Nothing found**: :func:`nearest` suggests the closest names, ids and topic words
  (:func:`difflib.get_close_matches`).
"""

from __future__ import annotations

import difflib
import json
import re
import unicodedata
from functools import cache
from importlib import resources

from .catalogue import Check, inventory, load_all

__all__ = ["NAMES", "nearest", "search", "section_titles", "topic_text", "topic_words"]

#: well-known names of results -> the checks that carry them (read off their titles)
NAMES: dict[str, tuple[str, ...]] = {
    "parallel axis theorem": ("eq4.38", "E3.1"),
    "steiner": ("eq4.38", "E3.1"),
    "konig": ("eq3.7", "E3.1"),
    "euler's equations": ("eq4.47", "eq5.91", "E5.2"),
    "bernoulli": ("eq8.34", "E8.1"),
    "torricelli": ("E8.1", "thm.scene-tank-draining"),
    "tsiolkovsky": ("E7.2", "thm.scene-rocket"),
    "rocket equation": ("E7.2", "thm.scene-rocket"),
    "chasles": ("eq2.80",),
    "centre of percussion": ("thm.centre-of-percussion", "thm.scene-rod-struck"),
    "poinsot": ("eq5.90",),
    "lagrange top": ("eq5.50", "eq5.55", "eq5.61", "thm.scene-heavy-top"),
    "dzhanibekov": ("eq5.102", "thm.scene-free-top-flip", "thm.scene-flip-after-push"),
    "tennis racket theorem": ("eq5.102", "thm.scene-free-top-flip", "thm.scene-flip-after-push"),
    "intermediate axis theorem": ("eq5.102", "thm.scene-free-top-flip"),
    "newton's cradle": ("thm.scene-newtons-cradle",),
}


def _words(text: str) -> list[str]:
    """Lower case, accents dropped, hyphens and apostrophes as spaces, words only."""
    text = unicodedata.normalize("NFKD", text).encode("ascii", "ignore").decode()
    return re.findall(r"[a-z0-9]+(?:\.[0-9]+)*", text.lower().replace("'", " "))


@cache
def section_titles() -> dict[str, str]:
    """The book's section headings, {"4.3.1": "The Physical Pendulum", …}."""
    text = resources.files("identities").joinpath("data/book_sections.json").read_text("utf-8")
    return json.loads(text)


def topic_text(check: Check) -> str:
    """All the topic words of a check (see the Conventions), as one string."""
    inv, heads = inventory(), section_titles()
    parts = [check.id, check.title, check.statement]
    for item in check.items:
        if item in inv:
            sec = inv[item].section.split(".")
            parts += [heads.get(".".join(sec[:k]), "") for k in range(2, len(sec) + 1)]
    parts += [name for name, ids in NAMES.items() if check.id in ids]
    return " ".join(parts)


def topic_words(check: Check) -> list[str]:
    """The topic words of a check, normalised as a query is (what :func:`search` matches;
    the site's search box ships them)."""
    return _words(topic_text(check))


def _starts(query: list[str], words: list[str]) -> bool:
    return all(any(w.startswith(q) for w in words) for q in query)


def search(query: str) -> list[Check]:
    """The checks the query names: a known name's checks first, then every check whose
    topic words begin with each word of the query (catalogue order)."""
    reg = load_all()
    q = _words(query)
    if not q:
        return []
    named = [cid for name, ids in NAMES.items() if _starts(q, _words(name)) for cid in ids]
    found = [reg[c] for c in dict.fromkeys(named) if c in reg]
    for c in reg.values():
        if c not in found and _starts(q, topic_words(c)):
            found.append(c)
    return found


def nearest(query: str, n: int = 5) -> list[str]:
    """The names, check ids and topic words closest to an unknown query."""
    reg = load_all()
    vocabulary = set(NAMES) | set(reg)
    for c in reg.values():
        vocabulary |= set(_words(c.title))
    return difflib.get_close_matches(" ".join(_words(query)) or query, sorted(vocabulary), n=n)
