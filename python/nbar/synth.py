"""Four-bar synthesis: every four-bar that does a task, checked with the kinematics engine and
ranked (``nbar synth``).

>>> designs = nbar.synth.five_point(pivots=[(0, 0), (200, 0)], points=[...], units="mm")
>>> best = designs.best; best.model().animate()

One function per method (``five_point``, ``nine_point``, ``burmester``, ``function``, ``path``)
builds the task a task file would hold (the same keys: see docs/synthesis.md), so its checks and
messages are the command line's; ``run`` solves a task file or a dict with its keys.
"""

from ._synth import Design, Designs, burmester, five_point, function, load, nine_point, path, run, task

__all__ = ["Design", "Designs", "task", "load", "run", "five_point", "nine_point", "burmester", "function", "path"]
