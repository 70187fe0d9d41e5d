"""Hypothesis profiles, chosen by HYPOTHESIS_PROFILE (default: ``ci`` when CI is set).

- ``ci``: derandomised (the same examples every run), no deadline.
- ``dev``: the default locally; random, no deadline (sympy and mpmath are slow on
  first call).
- ``explore``: ten times the examples of ``ci``, random, for hunting.

``bodycheck explain`` keeps its output in a cache (:mod:`identities.cli.cache`); the
suite gives each worker a fresh cache folder, so no test reads a user's cache or another
worker's entries, and none writes into ``~/.cache``.
"""

from __future__ import annotations

import os

import pytest
from hypothesis import HealthCheck, settings

_BASE = settings(deadline=None, suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("ci", _BASE, derandomize=True, max_examples=100, print_blob=True)
settings.register_profile("dev", _BASE, max_examples=100)
settings.register_profile("explore", _BASE, max_examples=1000)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci" if os.environ.get("CI") else "dev"))


@pytest.fixture(autouse=True, scope="session")
def _fresh_explain_cache(tmp_path_factory):
    old = os.environ.get("BODYCHECK_CACHE_DIR")
    os.environ["BODYCHECK_CACHE_DIR"] = str(tmp_path_factory.mktemp("bodycheck-cache"))
    yield
    if old is None:
        os.environ.pop("BODYCHECK_CACHE_DIR", None)
    else:
        os.environ["BODYCHECK_CACHE_DIR"] = old
