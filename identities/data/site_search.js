// bodycheck site: the search box of every page (issue 31, item 4).  The same matching as
// `bodycheck search` (identities/verify/topics.py): a query matches a check when every one
// of its words starts a word of the check's topic words (title, statement, the book's
// section headings, well-known names), a known name's checks first.  The topic words are
// computed in Python and shipped in search-index.js; only the query is normalised here,
// as topics._words does: NFKD, non-ASCII dropped, lower case, apostrophes as spaces.
"use strict";

function bodycheckWords(text) {
  const ascii = text.normalize("NFKD").replace(/[^\x00-\x7f]/g, "");
  return ascii.toLowerCase().replace(/'/g, " ").match(/[a-z0-9]+(?:\.[0-9]+)*/g) || [];
}

function bodycheckStarts(query, words) {
  return query.every((q) => words.some((w) => w.startsWith(q)));
}

function bodycheckSearch(index, text) {
  const q = bodycheckWords(text);
  if (q.length === 0) return [];
  const byId = new Map(index.checks.map((c) => [c.id, c]));
  const seen = new Set();
  const out = [];
  for (const [name, ids] of index.names) {
    if (!bodycheckStarts(q, bodycheckWords(name))) continue;
    for (const id of ids) {
      if (byId.has(id) && !seen.has(id)) {
        seen.add(id);
        out.push(byId.get(id));
      }
    }
  }
  for (const c of index.checks) {
    if (!seen.has(c.id) && bodycheckStarts(q, c.words.split(" "))) {
      seen.add(c.id);
      out.push(c);
    }
  }
  return out;
}

function bodycheckShow(index, text, list) {
  list.replaceChildren();
  const found = bodycheckSearch(index, text);
  for (const c of found) {
    const item = document.createElement("li");
    const link = document.createElement("a");
    link.href = c.href;
    link.textContent = c.id + " " + c.title;
    item.appendChild(link);
    list.appendChild(item);
  }
  list.setAttribute("data-count", String(found.length));
  const status = document.getElementById("search-status");
  if (status) status.textContent = text.trim() ? found.length + " found" : "";
}

if (typeof document !== "undefined") {
  document.addEventListener("DOMContentLoaded", () => {
    const index = window.BODYCHECK_SEARCH;
    const form = document.getElementById("search");
    const list = document.getElementById("search-results");
    if (!index || !form || !list) return;
    const input = form.querySelector("input");
    form.addEventListener("submit", (event) => {
      event.preventDefault();
      bodycheckShow(index, input.value, list);
    });
    input.addEventListener("input", () => bodycheckShow(index, input.value, list));
    const asked = new URLSearchParams(window.location.search).get("q");
    if (asked) {
      input.value = asked;
      bodycheckShow(index, asked, list);
    }
  });
}

if (typeof module !== "undefined") {
  module.exports = { bodycheckSearch, bodycheckWords };
}
