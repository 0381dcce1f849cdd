# Type stub of nbar.results.
from typing import Any, Dict, Iterable, Iterator, List, Mapping, NamedTuple, Optional, Tuple, Union

from numpy.typing import NDArray

from .pictures import Animation

class Warning(NamedTuple):
    code: str
    step: int
    message: str

class Table(Mapping[str, NDArray[Any]]):
    columns: List[str]
    units: Dict[str, str]
    def __init__(self, names: List[str], units: List[str], arrays: List[NDArray[Any]]) -> None: ...
    def __getitem__(self, name: str) -> NDArray[Any]: ...
    def __iter__(self) -> Iterator[str]: ...
    def __len__(self) -> int: ...
    @property
    def rows(self) -> int: ...
    def to_numpy(self) -> NDArray[Any]: ...
    def to_pandas(self) -> Any: ...
    def __reduce__(self) -> Tuple[Any, Tuple[Any, ...]]: ...

class Result(Table):
    complete: bool
    stop_reason: Optional[str]
    warnings: List[Warning]
    max_residual: float
    branches: List[str]
    transmission_angles: Dict[str, Dict[str, float]]
    forces_unique: Optional[bool]
    default_x: Optional[str]
    statistics: Optional[Dict[str, Any]]
    events: List[Dict[str, Any]]
    def __init__(self, analysis: Any, names: List[str], units: List[str], arrays: List[NDArray[Any]]) -> None: ...
    def to_json(self) -> str: ...
    def animate(self, frames: int = ..., fps: float = ..., labels: bool = ..., traces: Union[str, Iterable[str]] = ...,
                width: int = ..., height: int = ..., title: str = ...) -> Animation: ...
    def __reduce__(self) -> Tuple[Any, Tuple[Dict[str, Any]]]: ...
