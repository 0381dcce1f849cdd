"""Arguments checked as nbar checks its other input: a wrong type or an out-of-range count is a
``BadInputError`` that names the argument, never pybind11's TypeError listing the binding's
overloads (which a student cannot read)."""

from __future__ import annotations

import numbers
from typing import Any, Optional

from .errors import BadInputError

# The bindings take counts as C ints.
_INT_MAX = 2**31 - 1


def whole(name: str, value: Any, minimum: Optional[int] = None) -> Optional[int]:
    """A count as an int: 10.0 and numpy's integers are counts too; 2.5, "10" or a number past a C
    int is the caller's mistake. None stays None (the default)."""
    if value is None:
        return None
    if not (isinstance(value, numbers.Real) and not isinstance(value, bool) and float(value).is_integer()):
        raise BadInputError(f"{name} must be a whole number, not {value!r}")
    count = int(value)
    low = -_INT_MAX - 1 if minimum is None else minimum
    if not low <= count <= _INT_MAX:
        raise BadInputError(f"{name} must be a whole number from {low} to {_INT_MAX}, not {value!r}")
    return count


def real(name: str, value: Any) -> Optional[float]:
    """A number as a float (ints and numpy's scalars too); "90" is the caller's mistake."""
    if value is None:
        return None
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        return float(value)
    raise BadInputError(f"{name} must be a number, not {value!r}")


def flag(name: str, value: Any) -> bool:
    """A yes/no argument: True or False (numpy's too); "no" would be true to Python."""
    if isinstance(value, bool) or type(value).__name__ == "bool_":
        return bool(value)
    raise BadInputError(f"{name} must be True or False, not {value!r}")


def text(name: str, value: Any) -> str:
    """A string that is text: a lone surrogate (half of a UTF-16 pair, as a broken decoder or
    "\\ud800" leaves it) has no UTF-8 form for the core to read."""
    if not isinstance(value, str):
        raise BadInputError(f"{name} must be a string, not {value!r}")
    try:
        value.encode("utf-8")
    except UnicodeEncodeError as e:
        line = value.count("\n", 0, e.start) + 1
        column = e.start - (value.rfind("\n", 0, e.start) + 1) + 1
        raise BadInputError(f"{name} holds {value[e.start]!r} at line {line}, column {column}: half of a UTF-16 "
                            "surrogate pair, which is not text (decode the file as UTF-8)") from None
    return value


def path(name: str, value: Any) -> str:
    """A file's path: a string or an os.PathLike (pathlib's paths), as a string."""
    import os
    if isinstance(value, str):
        return value
    if isinstance(value, os.PathLike):
        text = os.fspath(value)
        if isinstance(text, str):
            return text
    raise BadInputError(f"{name} must be a path (a string or a pathlib.Path), not {value!r}")


def json_value(value: Any) -> Any:
    """numpy's arrays and scalars as the lists and numbers json writes (json.dumps' default=)."""
    import numpy as np
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    # json.dumps' protocol for default=: a TypeError, which from_dict and task() turn into BadInputError.
    raise TypeError(f"Object of type {type(value).__name__} is not JSON serializable")
