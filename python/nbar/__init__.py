"""nbar: analysis, simulation and synthesis of planar linkages.

>>> import nbar
>>> m = nbar.load(nbar.examples.path("fourbar-crank-rocker"))   # or a model file of yours
>>> print(m.check())                      # degrees of freedom, Grashof class, transmission angle
>>> r = m.solve(steps=361)                # numpy arrays by column name
>>> nbar.plot(r, "rocker.omega")
>>> m.explain()                           # the method step by step

Everything is computed by nbar's C++ core; this package only translates.
"""

try:
    import numpy  # noqa: F401  (the results are numpy arrays; say what to install before anything fails on it)
except ImportError as missing_numpy:
    raise ImportError("nbar needs numpy: apt-get install python3-numpy (for Debian's python3), "
                      "or pip install numpy") from missing_numpy

from . import examples, synth
from ._nbar import __version__
from .errors import (AssemblyError, BadInputError, Cancelled, ColumnError, Error, InternalError, LimitError,
                     ModelError, UndefinedLawError)
from .explain import EquationsOfMotion, Explanation
from .model import FeConvergence, Model, ReadOnlyView, StressResult, Summary, load, loads, solve_many
from .pictures import Animation, Drawing, Report
from .plotting import plot
from .results import Result, Table, Warning

__all__ = [
    "Model", "load", "loads", "solve_many", "ReadOnlyView", "Summary", "Result", "Table", "Warning", "StressResult", "FeConvergence", "Explanation", "EquationsOfMotion",
    "Drawing", "Animation", "Report", "plot", "synth", "examples",
    "Error", "ModelError", "UndefinedLawError", "BadInputError", "ColumnError", "AssemblyError", "LimitError", "Cancelled",
    "InternalError", "__version__",
]
