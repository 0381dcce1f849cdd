"""Four-bar synthesis: every four-bar that does a task, checked with the kinematics engine and
ranked (``nbar synth``).

>>> designs = nbar.synth.five_point(pivots=[(0, 0), (200, 0)], points=[...], units="mm")
>>> best = designs[0]; best.model().animate()

Each function builds the task a task file would hold (the same keys: see docs/synthesis.md), so
its checks and messages are the command line's.
"""

from __future__ import annotations

import html
import json
import numbers
import os
from typing import Any, Dict, Iterable, List, Optional, Sequence, Tuple, Union

from . import _nbar
from ._args import json_value, path as as_path, real
from .errors import BadInputError

Point = Sequence[float]


class Design:
    """One four-bar found: its rank, Grashof class, link lengths, smallest transmission angle,
    defects and how far the simulated linkage misses the targets (``error``). ``.model()``
    makes it a Model to solve, draw and animate; ``.yaml`` is its model file."""

    def __init__(self, outcome, row: int, data: Dict[str, Any]):
        self._outcome = outcome
        self._row = row
        self.data = data
        self.rank: int = data.get("rank", 0)
        self.real: bool = data.get("real", True)
        self.grashof: Optional[str] = data.get("grashof")
        self.lengths: Optional[Dict[str, float]] = data.get("lengths")
        self.defects: Optional[Dict[str, Any]] = data.get("defects")
        self.defect_free: bool = bool(data.get("defect_free", False))
        self.min_transmission: Optional[float] = data.get("min_transmission")
        self.error: Optional[float] = data.get("max_error")

    @property
    def yaml(self) -> str:
        return self._outcome.design_yaml(self._row, self.rank)

    def model(self):
        """The design as a Model (a four-bar driven through its targets)."""
        from .model import loads
        return loads(self.yaml, f"<design {self.rank}>")

    def __getitem__(self, key: str) -> Any:
        return self.data[key]

    def __repr__(self) -> str:
        if not self.real:
            return f"<nbar.synth.Design {self.rank}: complex>"
        lengths = ", ".join(f"{k} {v:.6g}" for k, v in (self.lengths or {}).items())
        return (f"<nbar.synth.Design {self.rank}: {self.grashof}, {lengths}; mu min {self.min_transmission:.4g}, "
                f"{'no defects' if self.defect_free else 'defective'}, error {self.error:.3g}>")


class Designs(list):
    """The designs of one task, best first (a list of Design). ``print()`` shows the table
    ``nbar synth`` prints; ``.json`` is its JSON; ``.export(dir)`` writes every design as a model
    file; ``.notes`` says how the solve went."""

    def __init__(self, outcome):
        self._outcome = outcome
        self.json: str = outcome.json()
        data = json.loads(self.json)
        self.data: Dict[str, Any] = data
        self.method: str = outcome.method
        self.notes: List[str] = list(outcome.notes)
        rows = outcome.shown()
        super().__init__(Design(outcome, row, d) for row, d in zip(rows, data.get("designs", [])))

    @property
    def best(self) -> Design:
        if not self:
            raise BadInputError("no design does the task: " + "; ".join(self.notes))
        return self[0]

    def table(self) -> str:
        return self._outcome.table()

    def export(self, folder: Union[str, os.PathLike]) -> None:
        self._outcome.export(as_path("folder", folder))

    def write_curves(self, path: Union[str, os.PathLike]) -> None:
        """Burmester through four poses: the centre- and circle-point curves (.svg, .csv, .json)."""
        self._outcome.write_curves(as_path("path", path))

    def __str__(self) -> str:
        return self.table()

    def __repr__(self) -> str:
        return f"<nbar.synth.Designs: {len(self)} designs ({self.method})>"

    def _repr_html_(self) -> str:
        rows = []
        for d in self:
            if not d.real:
                rows.append(f"<tr><td>{d.rank}</td><td colspan='4'>complex</td></tr>")
                continue
            rows.append(f"<tr><td>{d.rank}</td><td>{html.escape(str(d.grashof))}</td>"
                        f"<td>{d.min_transmission:.4g}</td><td>{'none' if d.defect_free else 'yes'}</td>"
                        f"<td>{d.error:.2g}</td></tr>")
        notes = "".join(f"<li>{html.escape(n)}</li>" for n in self.notes)
        real = sum(1 for d in self if d.real)
        head = (f"<p>{html.escape(self.method)}: {self.data.get('solutions', len(self))} solutions; "
                f"{real} real design{'s' if real != 1 else ''} listed</p>")
        return (f"{head}{'<ul>' + notes + '</ul>' if notes else ''}<table><tr><th>rank</th><th>Grashof</th><th>μ min</th><th>defects</th>"
                f"<th>error</th></tr>{''.join(rows)}</table>")


def _units(units: Union[None, str, Dict[str, str]]) -> Optional[Dict[str, str]]:
    if units is None:
        return None
    if isinstance(units, str):
        return {"length": units, "angle": "deg"}
    if not isinstance(units, dict):
        raise BadInputError(f"units must be a length unit such as \"mm\", or a dict such as "
                            f"{{\"length\": \"mm\", \"angle\": \"deg\"}}, not {units!r}")
    return dict(units)


def task(data: Dict[str, Any], name: str = "<task>"):
    """A task from a dict with a task file's keys (``task: five-point``, ``points``...)."""
    try:
        text = json.dumps(data, indent=2, default=json_value)  # NaN written, refused at its line
    except (TypeError, ValueError) as e:
        raise BadInputError(f"{name}: the task must hold only numbers, strings, lists and dicts: {e}") from None
    return _nbar.parse_task(text, name)


def load(path: Union[str, os.PathLike]):
    """Reads a task file (docs/synthesis.md)."""
    return _nbar.load_task(as_path("path", path))


def _option(value: Any) -> Any:
    """numpy's scalars as Python's numbers and bools, which the request reads."""
    return value.item() if type(value).__module__ == "numpy" and hasattr(value, "item") else value


def run(the_task, all: Optional[bool] = None, top: Optional[int] = None, threads: Optional[int] = None,
        seed: Optional[int] = None, timeout: Optional[float] = None) -> Designs:
    """Solves a task (from ``task()``, ``load()`` or a path): the designs, best first. With
    ``all``, defective and complex solutions too; ``top`` keeps the best few (default 20, 0 for
    every one); ``threads`` (default: every hardware thread) and ``seed`` (default 1; the methods
    with random starts: five-point, nine-point, path) as ``nbar synth`` takes them, by the same
    rules."""
    given = {"all": all, "top": top, "threads": threads, "seed": seed}
    options = {k: _option(v) for k, v in given.items() if v is not None}
    # The options first, as `nbar synth` and the web API read them: by the method's rules when
    # the method is known before the task is read.
    kind = the_task.get("task") if isinstance(the_task, dict) else getattr(the_task, "kind", None)
    _nbar.check_synthesis_options(kind if isinstance(kind, str) else "", options)
    if isinstance(the_task, (str, os.PathLike)):
        the_task = load(the_task)
    elif isinstance(the_task, dict):
        the_task = task(the_task)
    return Designs(_nbar.synthesize(the_task, options, timeout=real("timeout", timeout)))


_DEFAULT_NAMES = {"five-point": "Five-point synthesis", "burmester": "Burmester synthesis",
                  "function": "Function generation"}


def _task_dict(kind: str, name: Optional[str], units, **keys) -> Dict[str, Any]:
    d: Dict[str, Any] = {"task": kind, "name": name or _DEFAULT_NAMES[kind]}
    if _units(units):
        d["units"] = _units(units)
    d.update({k: v for k, v in keys.items() if v is not None})
    return d


def _xy(p: Point) -> Any:
    """A point as the task reader is to see it: its items as given (numbers as floats), so that a
    point with three coordinates or a word for a number is reported by the reader at its place in
    the task, not cut short or converted here."""
    if isinstance(p, (str, bytes)) or not isinstance(p, Iterable):
        return p
    return [float(v) if isinstance(v, numbers.Real) and not isinstance(v, bool) else v for v in p]


def _pair(pair: Any, what: str) -> Tuple[Any, Any]:
    items = list(pair) if isinstance(pair, Iterable) and not isinstance(pair, (str, bytes)) else [pair]
    if len(items) != 2:
        raise BadInputError(f"{what} must be two points, not {len(items)} item{'s' if len(items) != 1 else ''}")
    return items[0], items[1]


def _pose(p: Any, index: int) -> Dict[str, Any]:
    items = _xy(p)
    if not isinstance(items, list) or len(items) != 3:
        raise BadInputError(f"pose {index + 1} must be (x, y, angle), not {p!r}")
    return {"point": items[:2], "angle": items[2]}


def five_point(pivots: Tuple[Point, Point], points: Iterable[Point], units=None, name: Optional[str] = None,
               **run_options) -> Designs:
    """Every four-bar with fixed pivots ``pivots`` (input's, output's) whose coupler point passes
    through the five ``points`` in order (all 36 solutions by homotopy continuation)."""
    a, b = _pair(pivots, "pivots (the input's and the output's)")
    d = _task_dict("five-point", name, units, pivots={"a": _xy(a), "b": _xy(b)}, points=[_xy(p) for p in points])
    return run(task(d, "<five_point>"), **run_options)


def burmester(poses: Iterable[Sequence[float]], fixed_pivots: Optional[Tuple[Point, Point]] = None,
              moving_pivots: Optional[Tuple[Point, Point]] = None, curves: Optional[Dict[str, Any]] = None,
              samples: Optional[int] = None, units=None, name: Optional[str] = None, **run_options) -> Designs:
    """Four-bars whose coupler takes 3, 4 or 5 poses ``(x, y, angle)``. Three poses need the two
    ``fixed_pivots`` or ``moving_pivots`` you choose."""
    pose_list = [_pose(p, i) for i, p in enumerate(poses)]
    extra: Dict[str, Any] = {}
    if fixed_pivots is not None:
        a, b = _pair(fixed_pivots, "fixed_pivots")
        extra["fixed_pivots"] = {"a": _xy(a), "b": _xy(b)}
    if moving_pivots is not None:
        a, b = _pair(moving_pivots, "moving_pivots")
        extra["moving_pivots"] = {"a": _xy(a), "b": _xy(b)}
    d = _task_dict("burmester", name, units, poses=pose_list, curves=curves, samples=samples, **extra)
    return run(task(d, "<burmester>"), **run_options)


def function(function: str, x: Tuple[float, float], input_range: Tuple[float, float],
             output_range: Tuple[float, float], points: int = 3, spacing: str = "chebyshev",
             frame: Optional[float] = None, units=None, name: Optional[str] = None, **run_options) -> Designs:
    """Freudenstein function generation: a four-bar whose output angle follows ``function`` of x
    (an expression in x) while the input turns through ``input_range``."""
    d = _task_dict("function", name, units, function=function, x=list(x), input_range=list(input_range),
                   output_range=list(output_range), points=points, spacing=spacing, frame=frame)
    return run(task(d, "<function>"), **run_options)


__all__ = ["Design", "Designs", "task", "load", "run", "five_point", "burmester", "function"]
