# Type stub of nbar.explain.
from typing import Any, ClassVar, Dict, List, Tuple

from numpy.typing import NDArray

from .pictures import Drawing

class Explanation:
    FIELDS: ClassVar[Tuple[str, ...]]
    step: int
    time: float
    driver_values: List[float]
    count: Dict[str, int]
    coordinates: List[str]
    equations: List[Dict[str, Any]]
    newton: List[Dict[str, Any]]
    converged: bool
    start: str
    jacobian: NDArray[Any]
    q: NDArray[Any]
    velocity: Dict[str, Any]
    acceleration: Dict[str, Any]
    centres: List[Dict[str, Any]]
    stresses: List[Dict[str, Any]]
    residual: float
    matches_sweep: bool
    sweep_difference: float
    notes: List[str]
    def __init__(self, native: Any) -> None: ...
    def __getattr__(self, name: str) -> Any: ...
    def __deepcopy__(self, memo: Dict[int, Any]) -> Explanation: ...
    @property
    def text(self) -> str: ...
    @property
    def markdown(self) -> str: ...
    @property
    def latex(self) -> str: ...
    def to_json(self) -> str: ...
    def draw(self) -> Drawing: ...

class EquationsOfMotion:
    FIELDS: ClassVar[Tuple[str, ...]]
    time: float
    q: NDArray[Any]
    velocity: NDArray[Any]
    coordinates: List[str]
    rows: List[str]
    free_drivers: List[str]
    mass: NDArray[Any]
    jacobian: NDArray[Any]
    forces: Dict[str, NDArray[Any]]
    gamma: NDArray[Any]
    acceleration: NDArray[Any]
    multipliers: NDArray[Any]
    residual: float
    simulated_acceleration: NDArray[Any]
    def __init__(self, native: Any) -> None: ...
    def __getattr__(self, name: str) -> Any: ...
    @property
    def text(self) -> str: ...
    def to_json(self) -> str: ...
