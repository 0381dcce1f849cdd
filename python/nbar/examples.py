"""The example models and synthesis tasks that come with nbar, installed inside the package, so
that a notebook or a script finds them wherever it is copied:

>>> m = nbar.load(nbar.examples.path("fourbar-crank-rocker"))
>>> nbar.synth.run(nbar.examples.path("synthesis/five-point-crank-rocker"))

``names()`` lists them (the repository's examples/ folder, without its C++ programs).
"""

from __future__ import annotations

import pathlib
from typing import List

from .errors import BadInputError

_FOLDER = pathlib.Path(__file__).resolve().parent / "_examples"


def folder() -> pathlib.Path:
    """Where the examples are: a folder inside the installed package."""
    return _FOLDER


def names() -> List[str]:
    """Every example model and task, by the name ``path()`` takes ("five-bar",
    "synthesis/nine-point-crank-rocker"...)."""
    return sorted(p.relative_to(_FOLDER).with_suffix("").as_posix() for p in _FOLDER.rglob("*.yaml"))


def path(name: str) -> pathlib.Path:
    """The file of the example ``name`` ("fourbar-crank-rocker", with or without ".yaml"; a
    task as "synthesis/burmester-four-positions"; any other file by its name with its suffix,
    "synthesis/path/d-shape.csv")."""
    if not isinstance(name, str) or not name:
        raise BadInputError(f"an example is named by a string such as \"fourbar-crank-rocker\", not {name!r}")
    for candidate in (name, name + ".yaml"):
        file = _FOLDER / candidate
        if file.is_file() and _FOLDER in file.resolve().parents:
            return file
    import difflib
    close = difflib.get_close_matches(name.removesuffix(".yaml"), names(), n=3)
    hint = f"; did you mean {', '.join(repr(c) for c in close)}?" if close else "; nbar.examples.names() lists them"
    raise BadInputError(f"no example '{name}'" + hint)


__all__ = ["folder", "names", "path"]
