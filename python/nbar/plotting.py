"""matplotlib helpers: any columns of a result against the first driver (or time, or any column)."""

from __future__ import annotations

from typing import Optional, Sequence, Union

from .results import Table


def default_x(result: Table) -> str:
    """The column plots run along: time for models driven by laws in time, otherwise the first
    driver when it moves, otherwise time."""
    if getattr(result, "time_law", False) and "t" in result:
        return "t"
    names = result.columns
    first_driver = names[2] if len(names) > 2 and names[0] == "step" and names[1] == "t" else None
    if first_driver and result.units.get(first_driver) and len(set(result[first_driver])) > 1:
        return first_driver
    if "t" in result:
        return "t"
    from .errors import BadInputError
    raise BadInputError("these columns have neither the driver nor t to plot against: pass x=")


def plot(result: Table, y: Union[str, Sequence[str]], x: Optional[str] = None, ax=None, **line_options):
    """Plots columns ``y`` of ``result`` against ``x`` (default: the first driver, or t) on
    ``ax`` (default: a new figure), with units on the axes. Positions against positions get
    equal axis scales, so a coupler curve keeps its shape. Returns the axes."""
    import matplotlib.pyplot as plt

    ys = [y] if isinstance(y, str) else list(y)
    if x is None:
        x = default_x(result)
    if ax is None:
        _, ax = plt.subplots(figsize=(6.4, 4.0), layout="constrained")
    for name in ys:
        ax.plot(result[x], result[name], label=name, **line_options)
    ax.set_xlabel(f"{x} [{result.units.get(x, '')}]" if result.units.get(x) else x)
    units = {result.units.get(n, "") for n in ys}
    if len(units) == 1:
        unit = units.pop()
        ax.set_ylabel(f"{', '.join(ys)} [{unit}]" if unit else ", ".join(ys))
    length_units = {result.units.get(x, "")} | {result.units.get(n, "") for n in ys}
    if len(length_units) == 1 and all(n.endswith((".x", ".y")) for n in ys + [x]):
        ax.set_aspect("equal", adjustable="datalim")
    if len(ys) > 1:
        ax.legend()
    ax.grid(True, alpha=0.3)
    return ax
