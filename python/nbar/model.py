"""Models: loading, building from a dict, checking, solving, stresses, pictures."""

from __future__ import annotations

import html
import json
import os
from types import SimpleNamespace
from typing import Any, Dict, Iterable, List, Optional, Sequence, Tuple, Union

from . import _nbar
from ._args import flag as _flag, json_value as _json_value, path as _path, real as _real, text as _text, whole as _whole
from .errors import BadInputError, LimitError
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

    def __init__(self, data: Dict[str, Any]):
        self._data = data
        self.dof: int = data["dof"]
        self.gruebler: int = data["gruebler"]
        self.redundant: List[str] = data["redundant"]
        self.drivers: List[str] = data["drivers"]
        self.joints: List[str] = data["joints"]
        self.bodies = [SimpleNamespace(**b) for b in data["bodies"]]
        self.loops = [SimpleNamespace(**{**loop, "rocker": SimpleNamespace(**loop["rocker"]) if loop["rocker"] else None})
                      for loop in data["loops"]]
        self.slider_cranks = [SimpleNamespace(**f) for f in data["slider_cranks"]]
        self.quick_returns = [SimpleNamespace(**f) for f in data["quick_returns"]]
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
            rows.append((loop.name, f"{loop.grashof}, {loop.branch} branch, transmission angle "
                                    f"{loop.transmission_angle:.4g}"))
        rows += [("rocker", loop.rocker.description) for loop in self.loops if loop.rocker]
        rows += [("slider-crank", f.description) for f in self.slider_cranks]
        rows += [("quick-return", f.description) for f in self.quick_returns]
        if self.assembly_error:
            rows.append(("assembly", self.assembly_error))
        cells = "".join(f"<tr><th style='text-align:left'>{html.escape(k)}</th><td style='text-align:left'>"
                        f"{html.escape(v)}</td></tr>" for k, v in rows)
        return f"<table>{cells}</table>"


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
    def points(self) -> Dict[str, Tuple[float, float]]:
        """Every point's drawn position, in the model's length unit."""
        return {p[0]: (p[1], p[2]) for p in self._c.points}

    @property
    def ground(self) -> List[str]:
        return [p[0] for p in self._c.points if p[3]]

    @property
    def bodies(self) -> Dict[str, List[str]]:
        return {b[0]: b[1] for b in self._c.bodies}

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

    # --- analyses ------------------------------------------------------------------------------
    def check(self) -> Summary:
        """The summary ``nbar check`` prints, as data (``print()`` it for the text)."""
        return Summary(self._c.summary())

    def analyse(self, steps: Optional[int] = None, order: int = 2, dynamics: bool = False, stress: bool = False,
                sections: int = 200, timeout: Optional[float] = None, max_steps: Optional[int] = None,
                method: str = "beam", mesh_size: Optional[float] = None):
        """The pipeline's raw result (sweep, then dynamics, then stress), for the other methods.

        A sweep of more than ``max_steps`` samples (default 10 000 000, as ``--max-steps``) is an error.
        ``method`` is the stresses' (``"beam"`` or ``"fe"``), ``mesh_size`` the finite elements' edge
        far from holes, in the model's length unit."""
        steps, order, sections = _whole("steps", steps), _whole("order", order), _whole("sections", sections)
        max_steps = _whole("max_steps", max_steps, minimum=1)
        timeout, mesh_size = _real("timeout", timeout), _real("mesh_size", mesh_size)
        return _nbar.analyse(self._c, steps=steps, order=order, dynamics=_flag("dynamics", dynamics),
                             stress=_flag("stress", stress), sections=sections, timeout=timeout, max_steps=max_steps,
                             method=_text("method", method), mesh_size=mesh_size)

    def solve(self, steps: Optional[int] = None, order: Optional[int] = None, columns: Columns = None,
              dynamics: bool = False, partial: bool = False, timeout: Optional[float] = None,
              max_steps: Optional[int] = None) -> Result:
        """Sweeps the drivers: positions, velocities, accelerations (to ``order``, at most 5) of
        every point and body, and with ``dynamics=True`` every joint force and driver effort.

        ``columns`` picks columns by name or glob (``"rocker.*"``); asking for force columns
        switches dynamics on. A sweep that stops at a toggle raises ``nbar.LimitError`` (its
        ``.result`` holds the rows solved) unless ``partial=True``. Ctrl-C (Jupyter's interrupt)
        stops a long run; ``timeout`` (s) bounds it. A sweep of more than ``max_steps`` samples
        (default 10 000 000, as ``nbar solve --max-steps``) is an error.
        """
        patterns = _patterns(columns)
        order, dynamics = _whole("order", order), _flag("dynamics", dynamics)
        if patterns:
            needs = self._c.needs(patterns, order, dynamics)
            if needs["unmatched"] >= 0:
                raise _no_column(patterns[needs["unmatched"]], self.columns(order=5, dynamics=True))
            order, dynamics = needs["order"], needs["dynamics"]
        analysis = self.analyse(steps=steps, order=2 if order is None else order, dynamics=dynamics, timeout=timeout,
                                max_steps=max_steps)
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

    def stress(self, steps: Optional[int] = None, sections: int = 200, timeout: Optional[float] = None,
               max_steps: Optional[int] = None, method: str = "beam",
               mesh_size: Optional[float] = None, partial: bool = False) -> StressResult:
        """Stresses in every link with a shape (``nbar stress``): ``method="beam"`` (beam theory on
        cross-sections) or ``"fe"`` (plane-stress finite elements, ``nbar stress --method fe``;
        ``mesh_size`` in the model's length unit).

        A sweep that stops at a toggle raises ``nbar.LimitError`` as ``solve()`` does (``nbar
        stress`` exits 4): its ``.result`` holds the peaks over the steps solved, which
        ``partial=True`` returns instead."""
        analysis = self.analyse(steps=steps, stress=True, sections=sections, timeout=timeout, max_steps=max_steps,
                                method=method, mesh_size=mesh_size)
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

    def explain(self, step: int = 0, steps: Optional[int] = None):
        """The method step by step at one sample: Gruebler's count, q, Φ and Φq, every
        Newton–Raphson iteration, the velocity and acceleration systems and the instant centres.
        Renders as Markdown with LaTeX in Jupyter; ``print()`` it for plain text."""
        from .explain import Explanation
        return Explanation(_nbar.explain(self._c, step=_whole("step", 0 if step is None else step), steps=_whole("steps", steps)))


def load(path: Union[str, os.PathLike]) -> Model:
    """Reads a model file (YAML or JSON). Errors are ``nbar.ModelError`` with file, line, column."""
    return Model(_nbar.load(_path("path", path)))


def loads(text: str, name: str = "<string>") -> Model:
    """A model from YAML or JSON text; ``name`` stands for the file in messages."""
    return Model(_nbar.loads(_text("text", text), _text("name", name)))
