"""Results of an analysis as numpy arrays by column name, with units and the solver's report."""

from __future__ import annotations

import html
from collections.abc import Mapping
from typing import Any, Dict, Iterable, Iterator, List, NamedTuple, Optional, Tuple, Union

import numpy as np


class Warning(NamedTuple):  # noqa: A001 - the name users read in nbar's output
    """Something to read a result with: a change point passed, a loop that changed branch."""

    code: str
    step: int
    message: str


class Table(Mapping):
    """Named columns of equal length, each a 1-D numpy array, with their units.

    ``t["rocker.omega"]`` is a column; ``t.units["rocker.omega"]`` its unit; ``t.columns`` the
    names in order. ``t.to_pandas()`` makes a DataFrame when pandas is installed.
    """

    def __init__(self, names: List[str], units: List[str], arrays: List[np.ndarray]):
        self.columns: List[str] = list(names)
        self.units: Dict[str, str] = dict(zip(names, units))
        # Step numbers are counts: an integer column, so that r["crank"][r["step"][k]] indexes.
        arrays = [a.astype(np.int64) if n == "step" and a.dtype.kind == "f" else a for n, a in zip(names, arrays)]
        self._data: Dict[str, np.ndarray] = dict(zip(names, arrays))
        for a in arrays:
            a.flags.writeable = False

    def __getitem__(self, name: str) -> np.ndarray:
        from .errors import ColumnError
        if not isinstance(name, str):  # a KeyError still, so that `0 in t` is False as on any mapping
            raise ColumnError(f"columns are named by strings, not {name!r}")
        try:
            return self._data[name]
        except KeyError:
            raise ColumnError(f"no column '{name}'" + _did_you_mean(name, self.columns)) from None

    def __iter__(self) -> Iterator[str]:
        return iter(self.columns)

    def __len__(self) -> int:
        return len(self.columns)

    @property
    def rows(self) -> int:
        """The number of samples."""
        return len(next(iter(self._data.values()))) if self._data else 0

    def to_numpy(self) -> np.ndarray:
        """All columns as one 2-D array, one row per sample."""
        return np.column_stack([self._data[c] for c in self.columns]) if self.columns else np.empty((0, 0))

    def to_pandas(self):
        """A pandas DataFrame of the columns (needs ``python3-pandas``)."""
        try:
            import pandas
        except ImportError as e:  # pragma: no cover - depends on the machine
            raise ImportError("to_pandas() needs pandas: apt-get install python3-pandas") from e
        frame = pandas.DataFrame({c: self._data[c] for c in self.columns})
        frame.attrs["units"] = dict(self.units)
        return frame

    def __reduce__(self) -> Tuple[Any, Tuple[Any, ...]]:
        return (Table, (self.columns, [self.units[c] for c in self.columns], [self._data[c] for c in self.columns]))

    def _repr_html_(self) -> str:
        return _html_table(self, max_rows=8, max_columns=6)

    def __repr__(self) -> str:
        return f"<nbar.Table: {self.rows} rows x {len(self.columns)} columns>"


class Result(Table):
    """The sweep (and, when asked, its dynamics) as columns, plus what the solver reports.

    - ``complete``: the sweep reached its end; otherwise ``stop_reason`` says where and why.
    - ``warnings``: change points passed, branch changes, forces that are not unique.
    - ``max_residual``: the largest constraint residual over the sweep, in the model's length unit.
    - ``transmission_angles``: per four-bar loop, ``{"min", "max", "design"}`` over the sweep (model
      angle unit; ``design`` is the smallest of min(mu, 180 deg - mu)) and the step of each.
    - ``statistics``: a simulation's (``Model.simulate``) integrator steps, constraint drift and
      energy error; None for a sweep.
    - ``events``: a simulation's toggles and stop condition, each ``{"kind", "time", "row",
      "message"}``; empty for a sweep.

    A simulation's Result is the same, its rows in time (``t``); ``max_residual`` is its largest
    position drift, and it has no warnings, branches or transmission angles.
    """

    def __init__(self, analysis, names, units, arrays):
        super().__init__(names, units, arrays)
        self._analysis = analysis
        self.complete: bool = analysis.complete
        self.stop_reason: Optional[str] = None if analysis.complete else analysis.stop_reason
        self.warnings: List[Warning] = [Warning(*w) for w in analysis.warnings]
        self.max_residual: float = analysis.max_residual
        self.branches: List[str] = list(analysis.branches)
        # Per four-bar loop, its transmission angle over the sweep in the model's angle unit: min and
        # max with their steps, and the design value, the smallest min(mu, 180 deg - mu), with its step.
        self.transmission_angles: Dict[str, Dict[str, float]] = dict(analysis.transmission_angles)
        self.forces_unique: Optional[bool] = analysis.forces_unique
        self.default_x: Optional[str] = None  # the column plots run along, as the CLI's plots
        # A simulation's (Model.simulate) integrator steps, largest constraint drift and energy
        # error; None for a sweep, which has no integrator.
        self.statistics: Optional[Dict[str, Any]] = getattr(analysis, "statistics", None)
        # A simulation's events (a toggle, a stop condition met): kind, time (s), row, message.
        self.events: List[Dict[str, Any]] = list(getattr(analysis, "events", []))

    def to_json(self) -> str:
        """The JSON that ``nbar solve --format json`` writes for these columns."""
        return self._analysis.json(self.columns)

    def animate(self, frames: int = 0, fps: float = 24.0, labels: bool = False,
                traces: Union[str, Iterable[str]] = (), width: int = 900, height: int = 640,
                title: str = "") -> "Animation":
        """A simulation's motion as an animation (``nbar animate --simulate``), its frames the rows
        at their times, evenly spaced; as ``Model.animate`` for a sweep (which this is not for)."""
        from ._args import flag, real, text, whole
        from .errors import BadInputError
        from .model import _names
        from .pictures import Animation
        if self.statistics is None:
            raise BadInputError("Result.animate() animates a simulation (Model.simulate); a sweep's is Model.animate()")
        return Animation(self._analysis, frames=whole("frames", frames), fps=real("fps", fps),
                         labels=flag("labels", labels), traces=_names("traces", traces),
                         width=whole("width", width), height=whole("height", height), title=text("title", title))

    def __reduce__(self) -> Tuple[Any, Tuple[Dict[str, Any]]]:
        # A Result crosses to another process (ProcessPoolExecutor, joblib) as its columns, what
        # the solver reported and its JSON, written now: the analysis behind it stays here.
        state = {name: getattr(self, name) for name in _RESULT_FIELDS}
        state["arrays"] = [self._data[c] for c in self.columns]
        state["units"] = [self.units[c] for c in self.columns]
        state["json"] = self.to_json()
        return (_unpickled_result, (state,))

    def __repr__(self) -> str:
        state = "complete" if self.complete else f"stopped: {self.stop_reason}"
        return f"<nbar.Result: {self.rows} samples x {len(self.columns)} columns, {state}>"

    def _repr_html_(self) -> str:
        head = "complete" if self.complete else "stopped early: " + html.escape(self.stop_reason or "")
        notes = "".join(f"<li>{html.escape(w.message)}</li>" for w in self.warnings)
        return (f"<p>{self.rows} samples, {head}; largest residual {self.max_residual:.3g}</p>"
                + (f"<ul>{notes}</ul>" if notes else "") + super()._repr_html_())


# What a Result reports besides its columns, in the order its docstring gives them.
_RESULT_FIELDS = ("columns", "complete", "stop_reason", "warnings", "max_residual", "branches",
                  "transmission_angles", "forces_unique", "default_x", "statistics", "events")


class _KeptJson:
    """An unpickled Result's stand-in for its analysis: the JSON written when it was pickled."""

    def __init__(self, text: str):
        self._text = text

    def json(self, columns: List[str]) -> str:
        return self._text


def _unpickled_result(state: Dict[str, Any]) -> Result:
    result = Result.__new__(Result)
    Table.__init__(result, state["columns"], state["units"], state["arrays"])
    result._analysis = _KeptJson(state["json"])
    for name in _RESULT_FIELDS[1:]:
        setattr(result, name, state[name])
    result.warnings = [Warning(*w) for w in state["warnings"]]
    return result


def _no_column(pattern: str, names: List[str]):
    """The ColumnError for a name or glob that picks no column: with the names it is closest to."""
    from .errors import ColumnError
    return ColumnError(f"no column matches '{pattern}'" + _did_you_mean(pattern, names))


def _did_you_mean(name: str, names: List[str]) -> str:
    import difflib
    folded = {n.lower(): n for n in names}
    if name.lower() in folded:
        return f"; did you mean '{folded[name.lower()]}'?"
    close = difflib.get_close_matches(name, names, n=3)
    return f"; did you mean {', '.join(repr(c) for c in close)}?" if close else ""


def _format(value: float) -> str:
    return f"{value:.6g}"


def _html_table(table: Table, max_rows: int, max_columns: int) -> str:
    """A small table that fits a phone: a few columns and rows, with a note of what is left out."""
    columns = table.columns[:max_columns]
    n = table.rows
    picked = list(range(n)) if n <= max_rows else list(range(max_rows // 2)) + list(range(n - max_rows // 2, n))
    head = "".join(f"<th>{html.escape(c)}<br><small>{html.escape(table.units.get(c, ''))}</small></th>"
                   for c in columns)
    body = []
    for i, r in enumerate(picked):
        if i == max_rows // 2 and n > max_rows:
            body.append(f"<tr><td colspan='{len(columns)}'>…</td></tr>")
        body.append("<tr>" + "".join(f"<td>{_format(table[c][r])}</td>" for c in columns) + "</tr>")
    more = len(table.columns) - len(columns)
    note = f"<p><small>{n} rows; {more} more columns: t.columns lists them</small></p>" if more > 0 else ""
    return f"<div style='overflow-x:auto'><table><tr>{head}</tr>{''.join(body)}</table></div>{note}"
