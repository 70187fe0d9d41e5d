"""Hypothesis strategies for inertia (see :mod:`mechanics.strategies`)."""

from __future__ import annotations

__all__: list[str] = []
