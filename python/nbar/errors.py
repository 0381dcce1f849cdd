"""The exceptions nbar raises: one base class, one subclass per kind of problem.

Each carries what the command line prints: the message, and where it is — the file, line and
column of the model or task text, and the model entity (``("body", 2)``) when known.
"""

from __future__ import annotations

from typing import Any, Optional, Tuple


class Error(Exception):
    """Any problem nbar reports. ``str(e)`` is ``file:line:column: message``.

    ``e.kind`` names the kind as the command line's JSON does (``"bad_input"``...), whether the
    error was raised by the library or by this module.
    """

    default_kind = "error"

    def __init__(self, message: str, kind: str = "", file: Optional[str] = None, line: Optional[int] = None,
                 column: Optional[int] = None, entity: Optional[Tuple[str, int]] = None, result: Any = None):
        self.message = message
        self.kind = kind or self.default_kind
        self.file = file
        self.line = line
        self.column = column
        self.entity = entity
        self.result = result
        super().__init__(self._located())

    def __str__(self) -> str:
        return self._located()

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

    default_kind = "invalid_model"


class UndefinedLawError(ModelError):
    """A motion or load law has no value where the sweep needs it."""

    default_kind = "undefined_law"


class BadInputError(Error, ValueError):
    """An argument out of range: an unknown column, a step that was not solved, a bad option."""

    default_kind = "bad_input"


class AssemblyError(Error):
    """No pose meets the constraints at the start of the sweep."""

    default_kind = "cannot_assemble"


class LimitError(Error):
    """The sweep stopped at a limit (toggle) position before its end.

    ``e.result`` holds the rows solved up to there; ``solve(..., partial=True)`` returns them
    instead of raising.
    """

    default_kind = "stopped_at_limit"


class Cancelled(Error):
    """Stopped by a time-out."""

    default_kind = "cancelled"


class InternalError(Error):
    """A defect of nbar, or the system refused (a file that cannot be written, ffmpeg missing).

    Any C++ exception that is not one of nbar's own arrives as this class, with a message asking
    for a report.
    """

    default_kind = "internal"


class ColumnError(BadInputError, KeyError):
    """No column of that name: a ``BadInputError``, and a ``KeyError`` as a mapping's missing key is,
    so that ``name in result`` and ``result.get(name)`` work as on any mapping."""


__all__ = ["Error", "ModelError", "UndefinedLawError", "BadInputError", "ColumnError", "AssemblyError", "LimitError",
           "Cancelled", "InternalError"]
