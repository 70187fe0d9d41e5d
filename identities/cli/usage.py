"""The command line's one error for bad input: :class:`UsageError`.

Its own module so that every subcommand's module can raise it without importing the
entry point (:mod:`identities.cli.main` imports the subcommands, never the reverse).
"""

from __future__ import annotations

__all__ = ["UsageError"]


class UsageError(Exception):
    """Bad command-line input: reported in one line, exit code 2."""
