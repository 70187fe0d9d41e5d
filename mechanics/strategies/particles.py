"""Hypothesis strategies for particles (see :mod:`mechanics.strategies`)."""

from __future__ import annotations

__all__: list[str] = []
