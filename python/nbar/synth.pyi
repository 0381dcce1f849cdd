# Type stub of nbar.synth: the public names of nbar._synth.
from ._synth import Design as Design, Designs as Designs, burmester as burmester, five_point as five_point
from ._synth import function as function, load as load, nine_point as nine_point, path as path, run as run
from ._synth import task as task

__all__ = ["Design", "Designs", "task", "load", "run", "five_point", "nine_point", "burmester", "function", "path"]
