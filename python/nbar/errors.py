"""The exceptions nbar raises: one base class, one subclass per kind of problem.

Each carries what the command line prints: the message, and where it is — the file, line and
column of the model or task text, and the model entity (``("body", 2)``) when known.
"""

from __future__ import annotations

from typing import Any, Optional, Tuple


class Error(Exception):
    """Any problem nbar reports. ``str(e)`` is ``file:line:column: message``."""

    def __init__(self, message: str, kind: str = "", file: Optional[str] = None, line: Optional[int] = None,
                 column: Optional[int] = None, entity: Optional[Tuple[str, int]] = None, result: Any = None):
        self.message = message
        self.kind = kind
        self.file = file
        self.line = line
        self.column = column
        self.entity = entity
        self.result = result
        super().__init__(self._located())

    def _located(self) -> str:
        place = ""
        if self.file:
            place = self.file
            if self.line:
                place += f":{self.line}"
                if self.column:
                    place += f":{self.column}"
            place += ": "
        return place + self.message


class ModelError(Error, ValueError):
    """An invalid model or task: syntax, unknown names, wrong geometry, drivers not matching the mobility."""


class UndefinedLawError(ModelError):
    """A motion or load law has no value where the sweep needs it."""


class BadInputError(Error, ValueError):
    """An argument out of range: an unknown column, a step that was not solved, a bad option."""


class AssemblyError(Error):
    """No pose meets the constraints at the start of the sweep."""


class LimitError(Error):
    """The sweep stopped at a limit (toggle) position before its end.

    ``e.result`` holds the rows solved up to there; ``solve(..., partial=True)`` returns them
    instead of raising.
    """


class Cancelled(Error):
    """Stopped by a time-out."""


__all__ = ["Error", "ModelError", "UndefinedLawError", "BadInputError", "AssemblyError", "LimitError", "Cancelled"]
