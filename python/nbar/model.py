"""Models: loading, building from a dict, checking, solving, stresses, pictures."""

from __future__ import annotations

import html
import json
import os
from types import SimpleNamespace
from typing import Any, Dict, Generic, Iterable, Iterator, List, Mapping, Optional, Sequence, Tuple, TypeVar, Union

from . import _nbar
from ._args import flag as _flag, json_value as _json_value, path as _path, real as _real, text as _text, whole as _whole
from .errors import BadInputError, Cancelled, Error, LimitError
from .pictures import Animation, Drawing, Report, _write
from .results import Result, Table, _no_column

Columns = Union[None, str, Sequence[str]]


def _patterns(columns: Columns) -> Optional[List[str]]:
    if columns is None:
        return None
    patterns = [c.strip() for c in columns.split(",") if c.strip()] if isinstance(columns, str) else list(columns)
    if not all(isinstance(p, str) for p in patterns):
        raise BadInputError(f"columns must be names or globs (strings), not {columns!r}")
    if not patterns:
        raise BadInputError("columns is empty: give names or globs, or None for every column")
    return patterns


def _names(name: str, value: Any) -> List[str]:
    """Point names: one string is one name (or names separated by commas, as the command line's
    --trace), else an iterable of strings."""
    if value is None:
        return []
    if isinstance(value, str):
        return [n.strip() for n in value.split(",") if n.strip()]
    if not isinstance(value, Iterable):
        raise BadInputError(f"{name} must be a point name or a list of point names, not {value!r}")
    names = list(value)
    for n in names:
        if not isinstance(n, str):
            raise BadInputError(f"{name} must be point names (strings), not {n!r}")
    return names


_Value = TypeVar("_Value")


class ReadOnlyView(Mapping[str, _Value], Generic[_Value]):
    """A model's points or bodies by name. A Model never changes: assigning to the view raises,
    saying which method returns the edited Model, rather than changing a copy that is then lost."""

    def __init__(self, what: str, items: Dict[str, _Value], how_to_edit: str):
        self._what = what
        self._items = items
        self._how_to_edit = how_to_edit

    def __getitem__(self, name: str) -> _Value:
        try:
            return self._items[name]
        except KeyError:
            raise KeyError(f"no {self._what[:-1] if self._what != 'bodies' else 'body'} '{name}'; "
                           f"the {self._what} are {', '.join(self._items)}") from None

    def __iter__(self) -> Iterator[str]:
        return iter(self._items)

    def __len__(self) -> int:
        return len(self._items)

    def _refuse(self, *_: Any) -> None:
        raise TypeError(f"m.{self._what} is read-only (a Model never changes): {self._how_to_edit}")

    __setitem__ = __delitem__ = _refuse
    update = pop = popitem = clear = setdefault = _refuse

    def __repr__(self) -> str:
        return repr(self._items)


def _items(name: str, value: Any) -> List[Tuple[Any, Any]]:
    if not isinstance(value, Mapping):
        raise BadInputError(f"{name} must be a dict, not {value!r}")
    return list(value.items())


def _xy(name: str, value: Any) -> Tuple[float, float]:
    items = list(value) if isinstance(value, Iterable) and not isinstance(value, (str, bytes)) else None
    if items is None or len(items) != 2:
        raise BadInputError(f"point {name} must move to (x, y), not {value!r}")
    return (_number(f"x of {name}", items[0]), _number(f"y of {name}", items[1]))


def _number(name: str, value: Any) -> float:
    number = _real(name, value)
    if number is None:
        raise BadInputError(f"{name} must be a number, not None")
    return number


def _stopped(model, stop_reason: Optional[str], what: str, result: Any) -> "LimitError":
    """The LimitError solve() raises for a sweep that stopped at a limit, for another product of
    that sweep (an animation, a report): at the same place, with the part made as ``e.result``."""
    line, column = model.sweep_stop_place or (None, None)
    return LimitError(f"{stop_reason} ({what}; partial=True returns it)", kind="stopped_at_limit", file=model.file,
                      line=line, column=column, result=result)


class Summary:
    """What ``nbar check`` says: degrees of freedom counted two ways, redundant constraints,
    drivers, bodies with their mass properties, the assembly at the start and every four-bar
    loop with its Grashof class, branch and transmission angle. ``print(s)`` shows the text."""

    def __init__(self, data: Dict[str, Any], units: Optional[Dict[str, str]] = None):
        self._data = data
        self.units: Dict[str, str] = dict(units or {"length": "", "angle": ""})
        self.dof: int = data["dof"]
        self.gruebler: int = data["gruebler"]
        self.redundant: List[str] = data["redundant"]
        self.drivers: List[str] = data["drivers"]
        self.joints: List[str] = data["joints"]
        self.bodies = [SimpleNamespace(**b) for b in data["bodies"]]
        # Each loop's transmission_over_turn: {"min", "max", "design"} over the input's full turn
        # (a crank on the ground), else None; transmission_angle is at the start.
        self.loops = [SimpleNamespace(**{**loop, "rocker": SimpleNamespace(**loop["rocker"]) if loop["rocker"] else None})
                      for loop in data["loops"]]
        self.slider_cranks = [SimpleNamespace(**f) for f in data["slider_cranks"]]
        self.quick_returns = [SimpleNamespace(**f) for f in data["quick_returns"]]
        # The whole mechanism's limits on the sweep's path, as `nbar check --format json` has them.
        self.limits: Optional[Dict[str, Any]] = data["limits"]
        self.assembly = SimpleNamespace(**data["assembly"]) if data["assembly"] else None
        self.assembly_error: Optional[str] = data["assembly_error"]
        self.has_kinetics: bool = data["has_kinetics"]
        from .results import Warning
        self.warnings = [Warning(*w) for w in data["warnings"]]
        self.text: str = data["text"]
        if self.assembly_error:
            # The reason the start cannot be assembled, which `nbar check` prints on its standard
            # error after the summary: under the summary's "FAILED" line, or as a line of its own.
            failed = "Assembly at the start: FAILED\n"
            reason = "\n".join("  " + line for line in self.assembly_error.splitlines()) + "\n"
            if failed in self.text:
                self.text = self.text.replace(failed, failed + reason, 1)
            else:
                self.text += "Assembly at the start: not assembled\n" + reason

    def __str__(self) -> str:
        return self.text

    def __repr__(self) -> str:
        return self.text

    def _repr_html_(self) -> str:
        rows = [("degrees of freedom", f"{self.dof} (Gruebler–Kutzbach: {self.gruebler})")]
        if self.redundant:
            rows.append(("redundant", ", ".join(self.redundant)))
        rows += [("driver", d) for d in self.drivers]
        for loop in self.loops:
            # As `nbar check` says; over the sweep, solve()'s transmission_angles.
            angle = self.units['angle']
            text = (f"{loop.grashof}; at the start: {loop.branch} branch, transmission angle "
                    f"{loop.transmission_angle:.4g} {angle}")
            if loop.transmission_over_turn:
                t = loop.transmission_over_turn
                text += (f"; over the input's full turn {t['min']:.4g} to {t['max']:.4g} {angle}, "
                         f"design value {t['design']:.4g} {angle}")
            rows.append((loop.name, text))
        rows += [("rocker", loop.rocker.description) for loop in self.loops if loop.rocker]
        rows += [("slider-crank", f.description) for f in self.slider_cranks]
        rows += [("quick-return", f.description) for f in self.quick_returns]
        if self.assembly_error:
            rows.append(("assembly", self.assembly_error))
        cells = "".join(f"<tr><th style='text-align:left'>{html.escape(k)}</th><td style='text-align:left'>"
                        f"{html.escape(v)}</td></tr>" for k, v in rows)
        return f"<table>{cells}</table>"


def _places(value: Any) -> Optional[List[str]]:
    """Points as the request reads them: "X,Y" texts' parts or points' names."""
    if value is None:
        return None
    if isinstance(value, str):
        return value.split(",")
    items = list(value)
    if len(items) == 2 and all(isinstance(v, (int, float)) for v in items):
        items = [items]
    out: List[str] = []
    for item in items:
        out += [item] if isinstance(item, str) else [repr(float(v)) for v in item]
    return out


class FeConvergence:
    """A mesh-convergence study of the finite-element peaks (``StressResult.converge()``, ``nbar
    stress --method fe --converge``). ``.meshes`` lists each mesh (``refinement``, and per link
    ``mesh_size``, ``nodes``, ``elements``, ``von_mises`` in MPa, ``step``, ``x``, ``y``, ``change``
    in % from the mesh before); ``.converged`` says whether the last change of every peak is below
    ``.tolerance`` %, ``.stopped`` why the study stopped short, if it did."""

    def __init__(self, text: str):
        self.json: str = text
        self.data: Dict[str, Any] = json.loads(text)
        self.meshes: List[Dict[str, Any]] = self.data["meshes"]
        self.converged: bool = bool(self.data["converged"])
        self.tolerance: float = float(self.data["tolerance"])
        self.stopped: Optional[str] = self.data.get("stopped")

    def peaks(self, body: str) -> List[float]:
        """One link's peak von Mises stress (MPa) on each mesh, coarsest first."""
        found = [link["von_mises"] for mesh in self.meshes for link in mesh["links"] if link["body"] == body]
        if not found:
            raise BadInputError(f"'{body}' has no finite-element peak in the study")
        return found

    def __repr__(self) -> str:
        state = "converged" if self.converged else f"not converged ({self.stopped})"
        return f"<FeConvergence: {len(self.meshes)} meshes, {state} at {self.tolerance:g} %>"


class StressResult:
    """Each shaped link's largest von Mises stress over the sweep (``nbar stress``): where, when,
    N, V, M and the safety factor. ``.links`` is a list of dicts (stresses in MPa),
    ``.profile(body, step)`` every section of one link at one step."""

    def __init__(self, analysis):
        self._analysis = analysis
        self.json: str = analysis.stress_report("json")
        data = json.loads(self.json)
        self.links: List[Dict[str, Any]] = data.get("links", data.get("bodies", []))
        for link in self.links:  # counts are ints, so that r["crank"][link["step"]] indexes
            for key in ("step", "nodes", "elements"):
                if isinstance(link.get(key), float) and link[key].is_integer():
                    link[key] = int(link[key])
        self.data: Dict[str, Any] = data

    def profile(self, body: str, step: int = 0) -> Table:
        return Table(*self._analysis.section_profile(body, step))

    def field(self, body: str, step: int = 0, *, at: Any = None, along: Any = None,
              around_hole: Optional[Union[str, int]] = None, radius: Optional[float] = None,
              coordinates: Optional[str] = None, samples: Optional[int] = None) -> Table:
        """The finite-element stresses of one link at one step (``nbar stress --method fe``):
        ``at=(x, y)``, several points ``[(x1, y1), "A"]`` or a point's name; ``along=((x1, y1), (x2, y2))``
        or two points' names; ``around_hole="A"`` or its number from 1 (``radius=`` a circle about it);
        in the body's frame or ``coordinates="model"``. Columns are numpy arrays (MPa, model units)."""
        return Table(*self._analysis.stress_field(body, step, _places(at), _places(along),
                                                  None if around_hole is None else str(around_hole), radius,
                                                  coordinates, samples))

    def vtu(self, body: str, step: int = 0) -> str:
        """One link's mesh and stresses at one step as a VTK .vtu document (for ParaView)."""
        return self._analysis.fe_vtu(body, step)

    def converge(self, tolerance: float = 1.0, timeout: Optional[float] = None) -> "FeConvergence":
        """``nbar stress --method fe --converge``: these meshes, then every plate's element sizes
        halved until each link's peak changes by less than ``tolerance`` % (at most 8 meshes)."""
        return FeConvergence(self._analysis.fe_convergence(tolerance=_real("tolerance", tolerance),
                                                          timeout=_real("timeout", timeout)))

    def __getitem__(self, body: str) -> Dict[str, Any]:
        for link in self.links:
            if link.get("body") == body or link.get("name") == body:
                return link
        raise BadInputError(f"'{body}' has no stress result")

    def __str__(self) -> str:
        return self._analysis.stress_report("table")

    __repr__ = __str__

    def to_pandas(self):
        import pandas
        return pandas.json_normalize(self.links)


class Model:
    """A planar linkage, compiled and ready to analyse.

    Make one with ``nbar.load(path)``, ``nbar.loads(yaml_text)`` or ``nbar.Model.from_dict({...})``
    (the keys of a model file: ``points``, ``ground``, ``bodies``, ``drivers``...).
    """

    def __init__(self, compiled):
        self._c = compiled

    # --- making models -------------------------------------------------------------------------
    @classmethod
    def from_dict(cls, data: Dict[str, Any], name: str = "<dict>") -> "Model":
        """A model from a dict with a model file's keys. Errors name the line and column of the
        dict written as indented JSON (``e.text`` holds that text)."""
        name = _text("name", name)
        try:
            # NaN and infinities are written (as NaN, Infinity), for the reader to refuse at their line
            # and column like any other value that is no length.
            text = json.dumps(data, indent=2, default=_json_value)
        except (TypeError, ValueError) as e:
            raise BadInputError(f"{name}: the model must hold only numbers, strings, lists and dicts: {e}") from None
        except RecursionError:
            raise BadInputError(f"{name}: the model's lists and dicts are nested too deeply to be a model "
                                "(a model file needs a few levels)") from None
        try:
            return cls(_nbar.loads(text, name))
        except Exception as e:
            if hasattr(e, "message"):
                e.text = text
            raise

    # --- what it is ----------------------------------------------------------------------------
    @property
    def name(self) -> str:
        return self._c.name

    @property
    def units(self) -> Dict[str, str]:
        return {"length": self._c.length_unit, "angle": self._c.angle_unit}

    @property
    def points(self) -> ReadOnlyView[Tuple[float, float]]:
        """Every point's drawn position, in the model's length unit (read-only: ``with_points``
        returns a Model with points moved)."""
        return ReadOnlyView("points", {p[0]: (p[1], p[2]) for p in self._c.points},
                            "m.with_points({name: (x, y)}) returns the Model with points moved")

    @property
    def ground(self) -> List[str]:
        return [p[0] for p in self._c.points if p[3]]

    @property
    def bodies(self) -> ReadOnlyView[Tuple[str, ...]]:
        """Every body's points (read-only: ``with_lengths`` returns a Model with lengths set)."""
        return ReadOnlyView("bodies", {b[0]: tuple(b[1]) for b in self._c.bodies},
                            "m.with_lengths({body: length}) returns the Model with lengths set; "
                            "m.with_points({name: (x, y)}) one with points moved")

    # --- edited copies (a Model never changes) ---------------------------------------------------
    def with_points(self, points: Mapping[str, Sequence[float]]) -> "Model":
        """A new Model with ``points`` (name: (x, y), in the model's length unit) moved in the
        drawing; this one is unchanged. Checked as a model file is: a point on a shaped body, or a
        drawing that no longer assembles as asked, is an error."""
        moved = [(_text("point name", name), _xy(name, xy)) for name, xy in _items("points", points)]
        return Model(self._c.edited(moved, []))

    def with_lengths(self, lengths: Mapping[str, float]) -> "Model":
        """A new Model with the two-point bodies ``lengths`` (body: length, in the model's length
        unit) set, as the model file's ``lengths:`` sets them; this one is unchanged."""
        set_lengths = [(_text("body name", name), _number(f"the length of {name}", value))
                       for name, value in _items("lengths", lengths)]
        return Model(self._c.edited([], set_lengths))

    @property
    def drivers(self) -> List[str]:
        return list(self._c.drivers)

    def columns(self, order: int = 2, dynamics: bool = False) -> List[str]:
        """The names of the columns ``solve`` can give (with ``dynamics``, the force columns too)."""
        return [c[0] for c in self._c.catalogue(_whole("order", order), _flag("dynamics", dynamics))]

    def to_yaml(self) -> str:
        """The kinematic model as a model file."""
        return self._c.yaml()

    def __repr__(self) -> str:
        return (f"<nbar.Model '{self.name}': {len(self._c.points)} points, {len(self._c.bodies)} bodies, "
                f"drivers {', '.join(self.drivers) or 'none'}>")

    def _repr_html_(self) -> str:
        """Jupyter shows a model as its drawing in the starting pose, under its name."""
        head = f"<p>{html.escape(repr(self))}</p>"
        try:
            drawing = self.draw(steps=2, width=600, height=420)
        except Error as e:  # a model that does not assemble still shows what it is, and why
            return head + f"<p>Not drawn: {html.escape(str(e))}</p>"
        return head + drawing._repr_html_()

    # --- analyses ------------------------------------------------------------------------------
    def check(self) -> Summary:
        """The summary ``nbar check`` prints, as data (``print()`` it for the text)."""
        return Summary(self._c.summary(), self.units)

    def analyse(self, steps: Optional[int] = None, order: int = 2, dynamics: bool = False, stress: bool = False,
                sections: int = 200, timeout: Optional[float] = None, max_steps: Optional[int] = None,
                method: str = "beam", mesh_size: Optional[float] = None, at_limits: Optional[str] = None,
                cycles: Optional[int] = None, segments_per_hole: Optional[int] = None,
                edge_size: Optional[float] = None, condition: bool = False):
        """The pipeline's raw result (sweep, then dynamics, then stress), for the other methods.

        A sweep of more than ``max_steps`` samples (default 10 000 000, as ``--max-steps``) is an error.
        ``method`` is the stresses' (``"beam"`` or ``"fe"``), ``mesh_size`` the finite elements' edge
        far from holes, in the model's length unit (``segments_per_hole`` edges at least around each
        round hole, ``edge_size`` along holes and corners). ``at_limits="reverse"`` turns the sweep back at the
        mechanism's limits (over the driver's ``at_limits``), for ``cycles`` rocking cycles. ``condition``
        estimates each sample's condition number, for the ``cond`` column."""
        steps, order, sections = _whole("steps", steps), _whole("order", order), _whole("sections", sections)
        max_steps, cycles = _whole("max_steps", max_steps, minimum=1), _whole("cycles", cycles, minimum=1)
        timeout, mesh_size = _real("timeout", timeout), _real("mesh_size", mesh_size)
        at_limits = None if at_limits is None else _text("at_limits", at_limits)
        segments_per_hole, edge_size = _whole("segments_per_hole", segments_per_hole), _real("edge_size", edge_size)
        return _nbar.analyse(self._c, steps=steps, order=order, dynamics=_flag("dynamics", dynamics),
                             stress=_flag("stress", stress), sections=sections, timeout=timeout, max_steps=max_steps,
                             method=_text("method", method), mesh_size=mesh_size, at_limits=at_limits, cycles=cycles,
                             segments_per_hole=segments_per_hole, edge_size=edge_size,
                             condition=_flag("condition", condition))

    def solve(self, steps: Optional[int] = None, order: Optional[int] = None, columns: Columns = None,
              dynamics: bool = False, partial: bool = False, timeout: Optional[float] = None,
              max_steps: Optional[int] = None, at_limits: Optional[str] = None,
              cycles: Optional[int] = None) -> Result:
        """Sweeps the drivers: positions, velocities, accelerations (to ``order``, at most 5) of
        every point and body, and with ``dynamics=True`` every joint force and driver effort.

        ``columns`` picks columns by name or glob (``"rocker.*"``); asking for force columns
        switches dynamics on. A sweep that stops at a toggle raises ``nbar.LimitError`` (its
        ``.result`` holds the rows solved) unless ``partial=True``. Ctrl-C (Jupyter's interrupt)
        stops a long run; ``timeout`` (s) bounds it. A sweep of more than ``max_steps`` samples
        (default 10 000 000, as ``nbar solve --max-steps``) is an error. ``at_limits="reverse"``
        (``--at-limits reverse``) turns the sweep back at each limit of the mechanism instead of
        stopping there, for ``cycles`` cycles (``--cycles``); a ``reversals`` column counts the turns.
        """
        patterns = _patterns(columns)
        order, dynamics = self._plan(patterns, _whole("order", order), _flag("dynamics", dynamics))
        condition = bool(patterns) and self._c.needs(patterns, order, dynamics)["condition"]
        analysis = self.analyse(steps=steps, order=order, dynamics=dynamics, timeout=timeout, max_steps=max_steps,
                                at_limits=at_limits, cycles=cycles, condition=condition)
        return self._result(analysis, patterns, partial)

    def _plan(self, patterns: Optional[List[str]], order: Optional[int], dynamics: bool) -> Tuple[int, bool]:
        """The derivative order and dynamics a solve needs for ``patterns`` (None: every column)."""
        if patterns:
            needs = self._c.needs(patterns, order, dynamics)
            if needs["unmatched"] >= 0:
                raise _no_column(patterns[needs["unmatched"]], self.columns(order=5, dynamics=True))
            order, dynamics = needs["order"], needs["dynamics"]
        return (2 if order is None else order), dynamics

    def _result(self, analysis: Any, patterns: Optional[List[str]], partial: bool) -> Result:
        result = Result(analysis, *analysis.table(patterns))
        result.default_x = self._c.default_abscissa
        if not result.complete and not partial:
            line, column = self._c.sweep_stop_place or (None, None)
            raise LimitError(f"{result.stop_reason} ({result.rows} rows solved; solve(..., partial=True) returns "
                             f"them)", kind="stopped_at_limit", file=self._c.file, line=line, column=column,
                             result=result)
        return result

    def dynamics(self, steps: Optional[int] = None, columns: Columns = None, **options) -> Result:
        """``solve(dynamics=True)``: forces at every joint (N), driver torques (N m) or forces,
        kinetic and potential energy."""
        return self.solve(steps=steps, columns=columns, dynamics=True, **options)

    def simulate(self, to: Optional[float] = None, dt: Optional[float] = None, rtol: Optional[float] = None,
                 columns: Columns = None, max_steps: Optional[int] = None, stop_when: Optional[str] = None,
                 at_toggle: Optional[str] = None, partial: bool = False, timeout: Optional[float] = None,
                 threads: Optional[int] = None) -> Result:
        """Lets the mechanism move under its loads for ``to`` seconds (``nbar simulate``): the
        drivers marked ``free: true`` are released, the others stay kinematic. A row every ``dt``
        seconds (default ``to``/100) with the columns of ``solve`` and the energies
        (``energy.kinetic``, ``energy.balance``...); ``rtol`` is the integrator's relative
        tolerance (default 1e-8). Each of ``to``, ``dt``, ``rtol``, ``stop_when`` and
        ``at_toggle`` not given is the model's own (its ``simulation:`` section), if it has one;
        ``to`` must come from one or the other.

        ``stop_when="slider.x > 200"`` ends the run where a column crosses a value (in its unit),
        located to 1e-12 s; ``at_toggle="reverse"`` reverses every speed where the constraints
        become singular instead of stopping there. ``result.events`` lists both with their times;
        ``result.statistics`` holds the integrator's steps, the largest constraint drift and energy
        error. ``threads=1`` keeps the whole run on the calling thread; by default the output rows
        are made on a second one where the machine has two cores (the answer is the same to the
        last bit). A run that cannot continue (a toggle, a step size too small) raises
        ``nbar.LimitError`` with the rows so far as ``.result``, unless ``partial=True``; one
        stopped by ``timeout`` (s) raises ``nbar.Cancelled`` the same way. Ctrl-C raises
        ``KeyboardInterrupt`` (whatever ``partial`` says, so that a script stops) with the rows so
        far as its ``.result``: ``complete`` False, ``stop_reason`` "cancelled at t = ... s"."""
        patterns = _patterns(columns)
        run = _nbar.simulate(self._c, to=_real("to", to), dt=_real("dt", dt), rtol=_real("rtol", rtol),
                             max_steps=_whole("max_steps", max_steps, minimum=1),
                             stop_when=None if stop_when is None else _text("stop_when", stop_when),
                             at_toggle=None if at_toggle is None else _text("at_toggle", at_toggle),
                             threads=_whole("threads", threads, minimum=1),
                             timeout=_real("timeout", timeout))
        result = Result(run, *self._simulated_columns(run, patterns))
        result.default_x = "t"
        if run.interrupted:
            interrupt = KeyboardInterrupt(f"the simulation stopped early: {run.stop_reason} ({result.rows} rows kept "
                                          f"as .result)")
            interrupt.result = result  # type: ignore[attr-defined]
            raise interrupt
        if run.cancelled and not partial:
            raise Cancelled(f"the simulation stopped early: {result.stop_reason} ({result.rows} rows; "
                            f"simulate(..., partial=True) returns them)", result=result)
        if not result.complete and not partial:
            line, column = run.stop_place or (None, None)
            raise LimitError(f"the simulation stopped early: {result.stop_reason} ({result.rows} rows; "
                             f"simulate(..., partial=True) returns them)", kind="stopped_at_limit", file=self._c.file,
                             line=line, column=column, result=result)
        return result

    def equilibrium(self, max_iterations: Optional[int] = None, timeout: Optional[float] = None) -> Dict[str, Any]:
        """The static equilibrium of the drivers marked ``free: true`` under the model's loads
        (``nbar equilibrium``), the other drivers held at their start: a dict with
        ``free_drivers`` (name: value, model units), ``stability`` (``"stable"``, ``"unstable"``
        or ``"neutral"``), ``eigenvalues`` and ``stiffness`` (the reduced stiffness, SI),
        ``residual`` and ``forces`` (the generalised force left on each free driver, N m or N),
        ``iterations``, and ``pose`` (every column of the pose: drivers, points' x and y,
        bodies' angles) with their ``units``. No equilibrium, or none found, raises
        ``nbar.ModelError`` at the first free driver."""
        return dict(_nbar.equilibrium(self._c, max_iterations=_whole("max_iterations", max_iterations, minimum=1),
                                      timeout=_real("timeout", timeout)))

    @staticmethod
    def _simulated_columns(run: Any, patterns: Optional[List[str]]) -> Tuple[Any, ...]:
        """The run's columns ``patterns`` pick; a pattern that picks none is the ColumnError
        ``solve`` raises, with the names it is closest to."""
        try:
            return tuple(run.table(patterns))
        except BadInputError:
            names = run.table(None)[0]
            for pattern in patterns or []:
                if _nbar.pick_columns(names, [pattern])[1]:
                    raise _no_column(pattern, names) from None
            raise

    def stress(self, steps: Optional[int] = None, sections: int = 200, timeout: Optional[float] = None,
               max_steps: Optional[int] = None, method: str = "beam",
               mesh_size: Optional[float] = None, partial: bool = False, segments_per_hole: Optional[int] = None,
               edge_size: Optional[float] = None) -> StressResult:
        """Stresses in every link with a shape (``nbar stress``): ``method="beam"`` (beam theory on
        cross-sections) or ``"fe"`` (plane-stress finite elements, ``nbar stress --method fe``;
        ``mesh_size`` and ``edge_size`` in the model's length unit, ``segments_per_hole`` as
        ``--segments-per-hole``; ``.converge()`` on the result refines until the peaks settle).

        A sweep that stops at a toggle raises ``nbar.LimitError`` as ``solve()`` does (``nbar
        stress`` exits 4): its ``.result`` holds the peaks over the steps solved, which
        ``partial=True`` returns instead."""
        analysis = self.analyse(steps=steps, stress=True, sections=sections, timeout=timeout, max_steps=max_steps,
                                method=method, mesh_size=mesh_size, segments_per_hole=segments_per_hole,
                                edge_size=edge_size)
        result = StressResult(analysis)
        if not analysis.complete and not partial:
            raise _stopped(self._c, analysis.stop_reason, f"the peaks over the {analysis.samples} steps solved", result)
        return result

    # --- pictures ------------------------------------------------------------------------------
    def draw(self, step: Optional[int] = None, at: Optional[float] = None, labels: bool = True,
             traces: Union[str, Iterable[str]] = (), width: int = 900, height: int = 640, title: str = "",
             steps: Optional[int] = None) -> Drawing:
        """The mechanism at sample ``step`` of the sweep, or where the first driver is ``at``
        (model units), with the paths of ``traces`` (a name, or a list of names). As ``nbar draw``,
        it draws any solved step of a sweep that stopped at a limit."""
        step, width, height = _whole("step", step), _whole("width", width), _whole("height", height)
        return Drawing(self.analyse(steps=steps, order=0), step=step, at=_real("at", at), labels=_flag("labels", labels),
                       traces=_names("traces", traces), width=width, height=height, title=_text("title", title))

    def animate(self, frames: int = 0, fps: float = 24.0, labels: bool = False,
                traces: Union[str, Iterable[str]] = (), width: int = 900, height: int = 640, title: str = "",
                steps: Optional[int] = None, partial: bool = False) -> Animation:
        """The sweep as an animation: HTML in Jupyter; ``.save()`` as .html, .svg, .gif or .mp4.

        A sweep that stops at a toggle raises ``nbar.LimitError`` as ``solve()`` does (and
        ``nbar animate`` exits 4); its ``.result`` is the animation of the part solved, which
        ``partial=True`` returns instead."""
        frames, width, height = _whole("frames", frames), _whole("width", width), _whole("height", height)
        analysis = self.analyse(steps=steps, order=0)
        animation = Animation(analysis, frames=frames, fps=_real("fps", fps), labels=_flag("labels", labels),
                              traces=_names("traces", traces), width=width, height=height, title=_text("title", title))
        if not analysis.complete and not partial:
            raise _stopped(self._c, analysis.stop_reason, f"an animation of the {analysis.samples} steps solved",
                           animation)
        return animation

    def report(self, path: Union[None, str, os.PathLike] = None, frames: int = 72,
               timeout: Optional[float] = None, partial: bool = False) -> Report:
        """The one-file HTML report of ``nbar report``; written to ``path`` when given.

        A sweep that stops at a toggle raises ``nbar.LimitError`` (``nbar report`` exits 4), after
        writing ``path`` as the command line does; ``e.result`` is the report of the part solved,
        which ``partial=True`` returns instead."""
        page, complete, stop_reason = _nbar.report(self._c, frames=_whole("frames", frames),
                                                   timeout=_real("timeout", timeout))
        report = Report(page)
        if path is not None:
            _write(path, report.html)
        if not complete and not partial:
            raise _stopped(self._c, stop_reason, "a report of the steps solved", report)
        return report

    def explain(self, step: int = 0, steps: Optional[int] = None, simulate: bool = False, at: Optional[float] = None,
                dt: Optional[float] = None, rtol: Optional[float] = None, at_toggle: Optional[str] = None,
                timeout: Optional[float] = None):
        """The method step by step at one sample: Gruebler's count, q, Φ and Φq, every
        Newton–Raphson iteration, the velocity and acceleration systems and the instant centres.
        Renders as Markdown with LaTeX in Jupyter; ``print()`` it for plain text.

        ``simulate=True, at=T``: instead, the equations of motion of ``simulate()``'s run at time
        ``T`` (s): an ``EquationsOfMotion`` with ``mass``, ``jacobian``, ``forces`` (by origin),
        ``gamma`` and the ``acceleration`` and ``multipliers`` they give, in SI (``nbar explain
        --simulate --at T``); ``dt``, ``rtol`` and ``at_toggle`` are the run's, as in ``simulate``."""
        if _flag("simulate", simulate):
            from .explain import EquationsOfMotion
            if step not in (0, None) or steps is not None:
                raise BadInputError("step and steps are the sweep's; with simulate=True give at")
            if at is None:
                raise BadInputError("give the time of the simulation to explain, in s, e.g. simulate=True, at=0.5")
            return EquationsOfMotion(_nbar.explain_motion(
                self._c, at=_real("at", at), dt=_real("dt", dt), rtol=_real("rtol", rtol),
                at_toggle=None if at_toggle is None else _text("at_toggle", at_toggle), timeout=_real("timeout", timeout)))
        for name, value in (("at", at), ("dt", dt), ("rtol", rtol), ("at_toggle", at_toggle)):
            if value is not None:
                raise BadInputError(f"{name} is an option of a simulation: give simulate=True too")
        from .explain import Explanation
        return Explanation(_nbar.explain(self._c, step=_whole("step", 0 if step is None else step), steps=_whole("steps", steps)))


def solve_many(models: Iterable[Model], steps: Optional[int] = None, order: int = 2, columns: Columns = None,
               dynamics: bool = False, threads: int = 0, partial: bool = False, timeout: Optional[float] = None,
               max_steps: Optional[int] = None) -> List[Result]:
    """``m.solve(...)`` of every model, run on ``threads`` threads of the core at once (0: one per
    hardware thread) with the interpreter's lock released: the Results in the models' order, each
    equal to its own ``solve``. A model whose sweep fails (or stops at a limit, unless
    ``partial=True``) raises its error after all have run, with a note saying which model it was;
    ``timeout`` (s) bounds the whole batch."""
    models = list(models)
    for i, m in enumerate(models):
        if not isinstance(m, Model):
            raise BadInputError(f"models[{i}] must be an nbar.Model, not {type(m).__name__}")
    patterns = _patterns(columns)
    order, dynamics = _whole("order", order), _flag("dynamics", dynamics)
    threads = _whole("threads", threads, minimum=0)
    if threads is not None and threads > 1024:
        raise BadInputError(f"threads must be a whole number from 0 to 1024, not {threads}")
    # Each model's (order, dynamics) and whether it estimates the Jacobian's condition (`cond`), as
    # its own solve() would.
    plans = []
    for m in models:
        o, d = m._plan(patterns, order, dynamics)
        plans.append((o, d, bool(patterns) and m._c.needs(patterns, o, d)["condition"]))
    # One batch per plan the columns need: usually one.
    analyses: List[Any] = [None] * len(models)
    for plan in set(plans):
        picked = [i for i, p in enumerate(plans) if p == plan]
        done = _nbar.analyse_many([models[i]._c for i in picked], steps=_whole("steps", steps), order=plan[0],
                                  dynamics=plan[1], max_steps=_whole("max_steps", max_steps, minimum=1),
                                  threads=threads or 0, timeout=_real("timeout", timeout), condition=plan[2])
        for i, a in zip(picked, done):
            analyses[i] = a
    results = []
    for i, a in enumerate(analyses):
        try:
            if isinstance(a, BaseException):
                raise a
            results.append(models[i]._result(a, patterns, partial))
        except Error as e:
            e.add_note(f"in nbar.solve_many: models[{i}] ({models[i].name or models[i]._c.file})")
            raise
    return results


def load(path: Union[str, os.PathLike]) -> Model:
    """Reads a model file (YAML or JSON). Errors are ``nbar.ModelError`` with file, line, column."""
    return Model(_nbar.load(_path("path", path)))


def loads(text: str, name: str = "<string>") -> Model:
    """A model from YAML or JSON text; ``name`` stands for the file in messages."""
    return Model(_nbar.loads(_text("text", text), _text("name", name)))
