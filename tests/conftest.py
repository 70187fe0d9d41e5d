"""Hypothesis profiles, chosen by HYPOTHESIS_PROFILE (default: ``ci`` when CI is set).

- ``ci``: derandomised (the same examples every run), no deadline.
- ``dev``: the default locally; random, no deadline (sympy and mpmath are slow on
  first call).
- ``explore``: ten times the examples of ``ci``, random, for hunting.
"""

from __future__ import annotations

import os

from hypothesis import HealthCheck, settings

_BASE = settings(deadline=None, suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("ci", _BASE, derandomize=True, max_examples=100, print_blob=True)
settings.register_profile("dev", _BASE, max_examples=100)
settings.register_profile("explore", _BASE, max_examples=1000)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci" if os.environ.get("CI") else "dev"))
