"""Count the book's numbered equations, examples and problems, with page and section.

Run from the repository root::

    python tools/book_inventory.py ../shared/book/dynamics-of-bodies.txt

It writes ``identities/data/book_inventory.json``, which the catalogue reads, so
that the registry knows every numbered item of the book without the book being
present (CI clones only this repository), and ``identities/data/book_sections.json``,
the headings of the chapters' sections (the topic words ``bodycheck search`` uses).
Deterministic: re-running it on the same text gives the same files.

Pages come from the running heads of the extracted text ("22 CHAPTER 2. ..." on
even pages, "2.2. ROTATION MATRICES 23" on odd ones); an item belongs to the page
of the last running head above it, or to the chapter's first page.
"""

from __future__ import annotations

import json
import re
import sys
from pathlib import Path

EVEN_HEAD = re.compile(r"^\s*(\d{1,3}) CHAPTER (\d)\.")
ODD_HEAD = re.compile(r"^\s*(\d)\.(\d)\.(?:\d\.)? [A-Z’'`,\- ]+ (\d{1,3})\s*$")
SECTION = re.compile(r"^(\d)\.(\d)(?:\.(\d))? ([A-Z][^.]{3,80})$")
EQUATION = re.compile(r"\((\d)\.(\d{1,3})\)")
EXAMPLE = re.compile(r"^\s*Example (\d)\.(\d+) ")
PROBLEM = re.compile(r"^\s*Problem (\d)\.(\d+) ")
CHAPTER_FIRST_PAGE = {1: 1, 2: 21, 3: 43, 4: 59, 5: 75, 6: 93, 7: 105, 8: 113}
BODY_START = re.compile(r"^1\.1 Linear and Angular Momentum of Particle Systems$")


def inventory(text: str) -> dict[str, dict[str, object]]:
    lines = text.splitlines()
    start = next(i for i, line in enumerate(lines) if BODY_START.match(line))
    items: dict[str, dict[str, object]] = {}
    page, chapter, section = 1, 1, "1.1"
    for line in lines[start:]:
        if m := EVEN_HEAD.match(line):
            page, chapter = int(m.group(1)), int(m.group(2))
        elif m := ODD_HEAD.match(line):
            page = int(m.group(3))
        if (m := SECTION.match(line.strip())) and int(m.group(1)) >= chapter:
            new_chapter = int(m.group(1))
            if new_chapter != chapter:
                page = CHAPTER_FIRST_PAGE[new_chapter]
            chapter = new_chapter
            section = ".".join(g for g in m.groups()[:3] if g)
        found = [(f"eq{c}.{n}", c) for c, n in EQUATION.findall(line)]
        if m := EXAMPLE.match(line):
            found.append((f"E{m.group(1)}.{m.group(2)}", m.group(1)))
        if m := PROBLEM.match(line):
            found.append((f"P{m.group(1)}.{m.group(2)}", m.group(1)))
        for key, c in found:
            if int(c) != chapter or key in items:
                continue  # a cross-reference to another chapter, or a later mention
            items[key] = {"chapter": chapter, "section": section, "page": page}
    return items


def sections(text: str) -> dict[str, str]:
    """The book's section headings in the body, {"4.3.1": "The Physical Pendulum"}."""
    lines = text.splitlines()
    start = next(i for i, line in enumerate(lines) if BODY_START.match(line))
    out: dict[str, str] = {}
    for line in lines[start:]:
        if m := SECTION.match(line.strip()):
            key = ".".join(g for g in m.groups()[:3] if g)
            out.setdefault(key, m.group(4).strip())
    return out


def main(argv: list[str]) -> int:
    if len(argv) != 2:
        print("usage: python tools/book_inventory.py BOOK.txt", file=sys.stderr)
        return 2
    items = inventory(Path(argv[1]).read_text(encoding="utf-8"))
    out = Path("identities/data/book_inventory.json")
    out.write_text(json.dumps(items, indent=1, sort_keys=False) + "\n", encoding="utf-8")
    print(f"wrote {len(items)} items to {out}")
    heads = sections(Path(argv[1]).read_text(encoding="utf-8"))
    out = Path("identities/data/book_sections.json")
    out.write_text(json.dumps(heads, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
    print(f"wrote {len(heads)} section headings to {out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv))
