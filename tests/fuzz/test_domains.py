"""Every public callable states its domain (issue 16, part 4).

A docstring states the domain in a paragraph that starts ``Domain:``: the inputs for
which the result is finite and right, and what is refused outside it. The callables
are the fuzzed ones (:data:`tests.fuzz.entries.ENTRIES`), so a new public function
needs both a fuzz entry and a domain. Modules not yet done are strict xfails that name
the callables still missing a domain: a module done turns its xfail into a failure to
remove here.
"""

from __future__ import annotations

import inspect

import pytest

from .entries import ENTRIES
from .surface import public_callables

SURFACE = public_callables()

#: modules whose docstrings do not state every domain yet, and why
NOT_YET: dict[str, str] = {}


def _modules() -> list[str]:
    return sorted({name.rsplit(".", 1)[0] for name in ENTRIES})


def _missing(module: str) -> list[str]:
    out = []
    for name in ENTRIES:
        if name.rsplit(".", 1)[0] != module:
            continue
        doc = inspect.getdoc(SURFACE[name]) or ""
        if "Domain:" not in doc:
            out.append(name.rsplit(".", 1)[1])
    return out


def _params():
    for m in _modules():
        marks = [pytest.mark.xfail(strict=True, reason=NOT_YET[m])] if m in NOT_YET else []
        yield pytest.param(m, id=m.removeprefix("mechanics."), marks=marks)


@pytest.mark.parametrize("module", list(_params()))
def test_every_public_callable_of_the_module_states_its_domain(module):
    missing = _missing(module)
    assert not missing, f"{module}: no 'Domain:' paragraph in {missing}"
