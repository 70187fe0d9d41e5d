"""What the benchmarks share: whether this run times them.

Under ``make test`` (``--benchmark-disable``, pyproject's addopts) a benchmark calls its
function once and checks the result; under ``make bench`` (``--benchmark-enable``) it
times it.  The checks need no million-entry batch, the timings do: :func:`timed` lets a
benchmark size its data by what the run is for.
"""

from __future__ import annotations

import pytest


@pytest.fixture(scope="session")
def timed(request) -> bool:
    """True when pytest-benchmark times this run (``--benchmark-enable``, no xdist)."""
    return not request.config._benchmarksession.disabled
