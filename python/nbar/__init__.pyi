# Type stub of the nbar package: what a notebook's completion and a type checker see. Each module
# has its own stub; stubtest checks every one against the module (python/tests/test_typing.py).
from . import examples as examples, synth as synth
from .errors import AssemblyError as AssemblyError, BadInputError as BadInputError, Cancelled as Cancelled
from .errors import ColumnError as ColumnError, Error as Error, InternalError as InternalError
from .errors import LimitError as LimitError, ModelError as ModelError, UndefinedLawError as UndefinedLawError
from .explain import EquationsOfMotion as EquationsOfMotion, Explanation as Explanation
from .model import FeConvergence as FeConvergence, Model as Model, ReadOnlyView as ReadOnlyView
from .model import StressResult as StressResult, Summary as Summary
from .model import load as load, loads as loads, solve_many as solve_many
from .pictures import Animation as Animation, Drawing as Drawing, Report as Report
from .plotting import plot as plot
from .results import Result as Result, Table as Table, Warning as Warning

__version__: str
__all__ = [
    "Model",
    "load",
    "loads",
    "solve_many",
    "ReadOnlyView",
    "Summary",
    "Result",
    "Table",
    "Warning",
    "StressResult",
    "FeConvergence",
    "Explanation",
    "EquationsOfMotion",
    "Drawing",
    "Animation",
    "Report",
    "plot",
    "synth",
    "examples",
    "Error",
    "ModelError",
    "UndefinedLawError",
    "BadInputError",
    "ColumnError",
    "AssemblyError",
    "LimitError",
    "Cancelled",
    "InternalError",
    "__version__",
]
