"""The one error a scene raises: :class:`SceneError`, naming the file, the field and the
reason.  The bottom of the scenes' import graph: it imports nothing from the package.
"""

from __future__ import annotations

__all__ = ["SceneError"]


class SceneError(ValueError):
    """A scene file is invalid: the message names the file, the field and the reason."""

    def __init__(self, source: str, field_: str, reason: str) -> None:
        self.source, self.field, self.reason = source, field_, reason
        super().__init__(f"{source}: {field_}: {reason}")
