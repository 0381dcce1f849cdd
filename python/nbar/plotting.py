"""matplotlib helpers: any columns of a result against the first driver (or time, or any column)."""

from __future__ import annotations

from typing import Any, List, Optional, Sequence, Union

from .results import Table


def default_x(result: Table) -> str:
    """The column plots run along: what ``nbar plot`` uses (t for sweeps in time, else the first
    driver), when the result has it; otherwise t."""
    preferred = getattr(result, "default_x", None)
    for name in (preferred, "t"):
        if name and name in result:
            return name
    from .errors import BadInputError
    raise BadInputError("these columns have neither the driver nor t to plot against: pass x=")


def columns(result: Table, y: Union[str, Sequence[str]]) -> List[str]:
    """The columns of ``result`` that names or globs ``y`` pick ("P.*", or "rocker.angle,rocker.omega"),
    as ``nbar plot --y`` and ``solve(columns=...)`` pick them."""
    from . import _nbar
    from .errors import BadInputError
    from .results import _no_column
    patterns = [c.strip() for c in y.split(",") if c.strip()] if isinstance(y, str) else list(y)
    if not patterns or not all(isinstance(p, str) for p in patterns):
        raise BadInputError(f"y must be column names or globs, not {y!r}")
    picked, message = _nbar.pick_columns(result.columns, patterns)
    if message:
        unmatched = next(p for p in patterns if _nbar.pick_columns(result.columns, [p])[1])
        raise _no_column(unmatched, result.columns)
    return [result.columns[i] for i in picked]


def _with_unit(name: str, unit: str) -> str:
    return f"{name} [{unit}]".strip() if unit else name


def plot(result: Table, *given: Union[str, Sequence[str]], x: Optional[str] = None, ax: Any = None,
         **line_options: Any) -> Any:
    """Plots columns of ``result`` (names or globs, as ``nbar plot --y``) on ``ax`` (default: a
    new figure), with units on the axes. The columns come in matplotlib's order:

    - ``plot(r, y)``: ``y`` against the first driver (or t, as ``nbar plot``), or against ``x=``;
    - ``plot(r, x, y)``: ``y`` against ``x``, as ``plt.plot(x, y)``: ``plot(r, "P.x", "P.y")``
      draws the coupler curve. Giving ``x=`` as well is refused, as is a third column.

    As ``nbar plot`` draws them: columns in two units go on two y axes, the second unit's on the
    right (``ax.right_ax``), each axis labelled with its unit; several columns in one unit share
    an axis labelled by the unit, with a legend naming them. Positions against positions get
    equal axis scales, so a coupler curve keeps its shape. Returns the (left) axes."""
    from .errors import BadInputError
    if len(given) == 2:
        if x is not None:
            raise BadInputError(f"plot(r, x, y) takes x once: plot(r, {given[0]!r}, {given[1]!r}) plots "
                                f"{given[1]!r} against {given[0]!r}; x={x!r} as well is ambiguous")
        if not isinstance(given[0], str):
            raise BadInputError(f"plot(r, x, y): x is one column's name, not {given[0]!r}")
        x, y = given
    elif len(given) == 1:
        y = given[0]
    else:
        raise BadInputError(f"plot takes the columns as (r, y) or (r, x, y), as matplotlib's plot(y) and "
                            f"plot(x, y), not {len(given)} of them" if given else
                            "plot(r, y) needs the columns to plot: a name or glob such as \"rocker.omega\" or \"P.*\"")
    import matplotlib.pyplot as plt

    ys = columns(result, y)
    if x is None:
        x = default_x(result)
    xs = result[x]
    if ax is None:
        _, ax = plt.subplots(figsize=(6.4, 4.0), layout="constrained")
    unit_of = {n: result.units.get(n, "") for n in ys}
    units = list(dict.fromkeys(unit_of.values()))
    path = all(n.endswith((".x", ".y")) for n in ys + [x]) and {result.units.get(x, "")} == set(units)
    two_axes = len(units) == 2 and not path
    axes = {units[0]: ax}
    if two_axes:
        axes[units[1]] = ax.twinx()
        ax.right_ax = axes[units[1]]
    lines = []
    for k, name in enumerate(ys):
        target = axes.get(unit_of[name], ax)
        options = dict(line_options)
        given = options.pop("label", None)  # label= names the line of one column
        if two_axes and "color" not in options and "c" not in options:
            options["color"] = f"C{k}"  # one colour cycle over both axes
        label = _with_unit(name, unit_of[name]) if len(units) > 1 else name
        if two_axes and target is not ax:
            label += " (right)"
        if given is not None and len(ys) == 1:
            label = given
        lines += target.plot(xs, result[name], label=label, **options)
    ax.set_xlabel(_with_unit(x, result.units.get(x, "")))
    if two_axes:
        for unit, axis in axes.items():
            on_it = [n for n in ys if unit_of[n] == unit]
            axis.set_ylabel(_with_unit(on_it[0], unit) if len(on_it) == 1 else _with_unit("", unit))
    elif len(ys) == 1:
        ax.set_ylabel(_with_unit(ys[0], units[0]))
    else:
        # The units, not the names (which the legend gives): a label of many names would not fit.
        ax.set_ylabel(", ".join(_with_unit("", u) for u in units if u))
    if path:
        ax.set_aspect("equal", adjustable="datalim")
    if two_axes:  # above the plot: inside, it would hide one axes' lines whichever it is drawn on
        ax.legend(handles=lines, labels=[line.get_label() for line in lines], loc="lower left",
                  bbox_to_anchor=(0.0, 1.0), ncol=min(len(lines), 2), frameon=False)
    elif len(ys) > 1:
        ax.legend(handles=lines, labels=[line.get_label() for line in lines])
    ax.grid(True, alpha=0.3)
    return ax
