"""matplotlib helpers: any columns of a result against the first driver (or time, or any column)."""

from __future__ import annotations

from typing import Optional, Sequence, Union

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
