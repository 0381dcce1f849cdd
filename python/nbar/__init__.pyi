# Type stub of the nbar package: what a notebook's completion and a type checker see.
import os
from typing import Any, Dict, Iterable, Iterator, List, Mapping, NamedTuple, Optional, Sequence, Tuple, Union

import numpy as np

from . import synth as synth

__version__: str

Columns = Union[None, str, Sequence[str]]
PathLike = Union[str, os.PathLike]

class Error(Exception):
    message: str
    kind: str
    file: Optional[str]
    line: Optional[int]
    column: Optional[int]
    entity: Optional[Tuple[str, int]]
    result: Any
class ModelError(Error, ValueError): ...
class UndefinedLawError(ModelError): ...
class BadInputError(Error, ValueError): ...
class ColumnError(BadInputError, KeyError): ...
class AssemblyError(Error): ...
class LimitError(Error):
    result: Result
class Cancelled(Error): ...
class InternalError(Error): ...

class Warning(NamedTuple):
    code: str
    step: int
    message: str

class Table(Mapping[str, np.ndarray]):
    columns: List[str]
    units: Dict[str, str]
    @property
    def rows(self) -> int: ...
    def __getitem__(self, name: str) -> np.ndarray: ...
    def __iter__(self) -> Iterator[str]: ...
    def __len__(self) -> int: ...
    def to_numpy(self) -> np.ndarray: ...
    def to_pandas(self) -> Any: ...

class Result(Table):
    complete: bool
    stop_reason: Optional[str]
    warnings: List[Warning]
    max_residual: float
    branches: List[str]
    transmission_angles: Dict[str, Dict[str, float]]
    forces_unique: Optional[bool]
    default_x: Optional[str]
    def to_json(self) -> str: ...

class Summary:
    dof: int
    gruebler: int
    redundant: List[str]
    drivers: List[str]
    joints: List[str]
    bodies: List[Any]
    loops: List[Any]
    assembly: Any
    assembly_error: Optional[str]
    has_kinetics: bool
    warnings: List[Warning]
    text: str

class StressResult:
    json: str
    data: Dict[str, Any]
    links: List[Dict[str, Any]]
    def profile(self, body: str, step: int = ...) -> Table: ...
    def __getitem__(self, body: str) -> Dict[str, Any]: ...
    def to_pandas(self) -> Any: ...

class Explanation:
    step: int
    time: float
    driver_values: List[float]
    count: Dict[str, int]
    coordinates: List[str]
    equations: List[Dict[str, Any]]
    newton: List[Dict[str, Any]]
    converged: bool
    start: str
    jacobian: np.ndarray
    q: np.ndarray
    velocity: Dict[str, np.ndarray]
    acceleration: Dict[str, np.ndarray]
    centres: List[Dict[str, Any]]
    residual: float
    matches_sweep: bool
    sweep_difference: float
    notes: List[str]
    @property
    def text(self) -> str: ...
    @property
    def markdown(self) -> str: ...
    @property
    def latex(self) -> str: ...
    def draw(self) -> Drawing: ...
    def to_json(self) -> str: ...

class Drawing:
    svg: str
    def png(self) -> bytes: ...
    def save(self, path: PathLike) -> None: ...

class Animation:
    html: str
    def data(self, format: str) -> Union[str, bytes]: ...
    def save(self, path: PathLike) -> None: ...

class Report:
    html: str
    def save(self, path: PathLike) -> None: ...

class Model:
    @classmethod
    def from_dict(cls, data: Dict[str, Any], name: str = ...) -> Model: ...
    @property
    def name(self) -> str: ...
    @property
    def units(self) -> Dict[str, str]: ...
    @property
    def points(self) -> Dict[str, Tuple[float, float]]: ...
    @property
    def ground(self) -> List[str]: ...
    @property
    def bodies(self) -> Dict[str, List[str]]: ...
    @property
    def drivers(self) -> List[str]: ...
    def columns(self, order: int = ..., dynamics: bool = ...) -> List[str]: ...
    def to_yaml(self) -> str: ...
    def check(self) -> Summary: ...
    def solve(self, steps: Optional[int] = ..., order: Optional[int] = ..., columns: Columns = ...,
              dynamics: bool = ..., partial: bool = ..., timeout: Optional[float] = ...) -> Result: ...
    def dynamics(self, steps: Optional[int] = ..., columns: Columns = ..., **options: Any) -> Result: ...
    def stress(self, steps: Optional[int] = ..., sections: int = ..., timeout: Optional[float] = ...,
               max_steps: Optional[int] = ..., method: str = ..., mesh_size: Optional[float] = ...,
               partial: bool = ...) -> StressResult: ...
    def draw(self, step: Optional[int] = ..., at: Optional[float] = ..., labels: bool = ...,
             traces: Union[str, Iterable[str]] = ...,
             width: int = ..., height: int = ..., title: str = ..., steps: Optional[int] = ...) -> Drawing: ...
    def animate(self, frames: int = ..., fps: float = ..., labels: bool = ..., traces: Union[str, Iterable[str]] = ...,
                width: int = ..., height: int = ..., title: str = ..., steps: Optional[int] = ...,
                partial: bool = ...) -> Animation: ...
    def report(self, path: Optional[PathLike] = ..., frames: int = ..., timeout: Optional[float] = ...,
               partial: bool = ...) -> Report: ...
    def explain(self, step: int = ..., steps: Optional[int] = ...) -> Explanation: ...

def load(path: PathLike) -> Model: ...
def loads(text: str, name: str = ...) -> Model: ...
def plot(result: Table, y: Union[str, Sequence[str]], x: Optional[str] = ..., ax: Any = ..., **line_options: Any) -> Any: ...
