"""nbar.synth's implementation: the task builders, the run and the designs. ``nbar.synth`` is its
public namespace (only the names in its ``__all__``)."""

from __future__ import annotations

import html
import json
import numbers
import os
from typing import Any, Dict, Iterable, List, Optional, Sequence, Tuple, Union

from . import _nbar
from ._args import json_value, path as as_path, real
from .errors import BadInputError
from .pictures import _write

Point = Sequence[float]


class Design:
    """One four-bar found: its rank, Grashof class, link lengths, smallest transmission angle,
    defects and how far the simulated linkage misses the targets (``error``). ``.model()``
    makes it a Model to solve, draw and animate; ``.yaml`` is its model file."""

    def __init__(self, outcome: Any, row: int, data: Dict[str, Any]):
        self._outcome = outcome
        self._row = row
        self.data = data
        self.rank: int = data.get("rank", 0)
        self.real: bool = data.get("real", True)
        self.grashof: Optional[str] = data.get("grashof")
        # A complex solution has no link lengths, angle or error: {} and NaN, so that a real
        # design's numbers are plain floats to index and round.
        self.lengths: Dict[str, float] = data.get("lengths") or {}
        self.defects: Optional[Dict[str, Any]] = data.get("defects")
        self.defect_free: bool = bool(data.get("defect_free", False))
        self.min_transmission: float = _number_or_nan(data.get("min_transmission"))
        self.error: float = _number_or_nan(data.get("max_error"))

    @property
    def yaml(self) -> str:
        return self._outcome.design_yaml(self._row, self.rank)

    def model(self) -> Any:
        """The design as a Model (a four-bar driven through its targets)."""
        from .model import loads
        return loads(self.yaml, f"<design {self.rank}>")

    def __getitem__(self, key: str) -> Any:
        return self.data[key]

    def __reduce__(self) -> Tuple[Any, Tuple[Any, ...]]:
        outcome = self._outcome if isinstance(self._outcome, _KeptOutcome) else _KeptOutcome(
            _KeptOutcome.state_of(self._outcome))
        return (Design, (outcome, self._row, self.data))

    def __repr__(self) -> str:
        if not self.real:
            return f"<nbar.synth.Design {self.rank}: complex>"
        lengths = ", ".join(f"{k} {v:.6g}" for k, v in (self.lengths or {}).items())
        return (f"<nbar.synth.Design {self.rank}: {self.grashof}, {lengths}; mu min {self.min_transmission:.4g}, "
                f"{'no defects' if self.defect_free else 'defective'}, error {self.error:.3g}>")


def _number_or_nan(value: Any) -> float:
    return float("nan") if value is None else float(value)


class _KeptOutcome:
    """An unpickled Designs' stand-in for its synthesis run: what the run wrote when pickled (the
    JSON, the table, each listed design's model file and the exported files)."""

    def __init__(self, state: Dict[str, Any]):
        self.__dict__.update(state)

    @staticmethod
    def state_of(outcome: Any) -> Dict[str, Any]:
        rows = list(outcome.shown())
        data = json.loads(outcome.json())
        yamls = {}
        for row, design in zip(rows, data.get("designs", [])):
            if design.get("real", True) and not design.get("invalid"):
                try:
                    yamls[row] = outcome.design_yaml(row, design.get("rank", 0))
                except Exception:  # a design no model file can be written for (design_yaml refuses it)
                    pass
        return {"method": outcome.method, "notes": list(outcome.notes), "_json": outcome.json(),
                "_table": outcome.table(), "_rows": rows, "_counts": tuple(outcome.counts()), "_yamls": yamls, "_files": list(outcome.design_files())}

    def json(self) -> str:
        return self._json

    def table(self) -> str:
        return self._table

    def shown(self) -> List[int]:
        return self._rows

    def counts(self) -> Tuple[int, int, int]:
        return self._counts

    def design_yaml(self, row: int, rank: int) -> str:
        if row not in self._yamls:
            raise BadInputError(f"design {rank} has no model file")
        return self._yamls[row]

    def design_files(self) -> List[Tuple[str, str]]:
        return self._files

    def export(self, folder: str) -> None:
        try:
            os.makedirs(folder, exist_ok=True)
        except OSError as e:
            raise BadInputError(f"cannot export to {folder}: {e.strerror}") from None
        for name, text in self._files:
            _write(os.path.join(folder, name), text)

    def write_curves(self, path: str) -> None:
        raise BadInputError("the Burmester curves are not kept when designs are pickled: write_curves() "
                            "before pickling, or run the task again")


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
        """The best design; ``nbar.BadInputError`` saying how many solutions there were, and
        why none is listed, when there is none."""
        if not self:
            raise BadInputError(self._none_listed())
        return self[0]

    def _none_listed(self) -> str:
        solutions, real, clean = self._outcome.counts()
        found = f"{solutions} solution{'s' if solutions != 1 else ''}, {real} real, {clean} without defects"
        why = ("all=True lists the defective ones too" if real and not clean else
               "top=0 lists every one" if clean else "none of them is real")
        notes = "".join(f"; {n}" for n in self.notes)
        return f"no design does the task ({self.method}): {found}; {why}{notes}"

    def table(self) -> str:
        """The ranked table ``nbar synth`` prints, in Python's words (``all=True``, ``top=N``)."""
        return self._outcome.table()

    def __reduce__(self) -> Tuple[Any, Tuple[Any, ...]]:
        # Designs cross to another process as what their run wrote: the run stays here.
        outcome = self._outcome if isinstance(self._outcome, _KeptOutcome) else _KeptOutcome(
            _KeptOutcome.state_of(self._outcome))
        return (_unpickled_designs, (outcome.__dict__,))

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


def _unpickled_designs(state: Dict[str, Any]) -> "Designs":
    return Designs(_KeptOutcome(state))


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
                  "function": "Function generation", "nine-point": "Nine-point synthesis",
                  "path": "Path fit"}


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


def nine_point(points: Iterable[Point], units: Union[None, str, Dict[str, str]] = None, name: Optional[str] = None,
               **run_options: Any) -> Designs:
    """Every four-bar whose coupler point passes through the nine ``points`` in order, pivots
    unknown (Alt's problem: 1442 triples of Roberts cognates by homotopy continuation;
    ``nbar synth nine-point``). Can take minutes: ``timeout=`` bounds it."""
    d = _task_dict("nine-point", name, units, points=[_xy(p) for p in points])
    return run(task(d, "<nine_point>"), **run_options)


def path(points: Optional[Iterable[Point]] = None, curve: Union[None, str, os.PathLike] = None,
         constraints: Optional[Dict[str, Any]] = None, nine_point_starts: Optional[int] = None,
         units: Union[None, str, Dict[str, str]] = None, name: Optional[str] = None, **run_options: Any) -> Designs:
    """The four-bars whose coupler curve passes closest to ``points`` (10 to 1000, in order), or
    to the points of the CSV file ``curve``, with no pivots given (best-fit path generation,
    ``nbar synth path``), ranked by their RMS deviation. ``constraints`` as a task file's:
    ``{"pivots": {"min": [x, y], "max": [x, y]}, "crank": True, "min_transmission": 30,
    "lengths": [10, 200]}``."""
    d = _task_dict("path", name, units, points=None if points is None else [_xy(p) for p in points],
                   curve=None if curve is None else as_path("curve", curve), constraints=constraints,
                   nine_point_starts=nine_point_starts)
    return run(task(d, "<path>"), **run_options)
