"""The step-by-step explanation (``Model.explain``): the method as a course writes it out."""

from __future__ import annotations

from typing import Any, List


class _NativeFields:
    """A view of a native result whose FIELDS read through to it: listed by dir() (so that
    Jupyter completes them) and documented in docs/python.md."""

    FIELDS: tuple = ()

    def __init__(self, native: Any):
        self._native = native

    def __dir__(self) -> List[str]:
        return sorted(set(super().__dir__()) | set(self.FIELDS))

    def __getattr__(self, name: str) -> Any:
        # Only the fields: copy and pickle look for special names on an instance whose _native is
        # not set yet, which would otherwise look for _native forever.
        if name not in self.FIELDS:
            raise AttributeError(f"'{type(self).__name__}' object has no attribute '{name}'")
        return getattr(self._native, name)


class Explanation(_NativeFields):
    """Gruebler's count, q, Φ and Φq (symbolic and numeric), every Newton–Raphson iteration,
    the velocity and acceleration systems and the instant centres, at one sample. Jupyter shows
    it as Markdown with LaTeX; ``print()`` gives plain text; ``.latex`` a LaTeX fragment."""

    FIELDS = ("step", "time", "driver_values", "count", "coordinates", "equations", "newton", "converged", "start",
              "jacobian", "q", "velocity", "acceleration", "centres", "stresses", "residual", "matches_sweep",
              "sweep_difference", "notes")

    def __deepcopy__(self, memo) -> "Explanation":
        # The native explanation never changes once made: a copy may share it.
        return Explanation(self._native)

    @property
    def text(self) -> str:
        return self._native.render("text")

    @property
    def markdown(self) -> str:
        return self._native.render("markdown")

    @property
    def latex(self) -> str:
        return self._native.render("latex")

    def to_json(self) -> str:
        """The JSON ``nbar explain --format json`` writes."""
        return self._native.json()

    def draw(self):
        """The pose with its instant centres marked (I12, I13...: links numbered from 1 for the
        ground), as a Drawing."""
        from .pictures import Drawing
        return Drawing.from_data(self._native.centres_picture("svg"), lambda: self._native.centres_picture("png"))

    def __str__(self) -> str:
        return self.text

    def __repr__(self) -> str:
        return self.text

    def _repr_markdown_(self) -> str:
        return self.markdown


class EquationsOfMotion(_NativeFields):
    """The equations of motion of a simulation at one time (``Model.explain(simulate=True,
    at=T)``, ``nbar explain --simulate --at T``): [M Φqᵀ; Φq 0] [q̈; λ] = [Q; γ] at the state the
    run reaches at T, in SI (q in m, M in kg, Q in N, γ in m/s², λ in N). ``forces`` is a dict of
    Q by origin (``gravity``, ``given``, ``springs``, ``friction``, ``total``); ``acceleration``
    and ``multipliers`` solve the system; ``simulated_acceleration`` is the run's own row.
    ``print()`` gives the text; ``to_json()`` the JSON."""

    FIELDS = ("time", "q", "velocity", "coordinates", "rows", "free_drivers", "mass", "jacobian", "forces", "gamma",
              "acceleration", "multipliers", "residual", "simulated_acceleration")

    @property
    def text(self) -> str:
        return self._native.render()

    def to_json(self) -> str:
        """The JSON ``nbar explain --simulate --format json`` writes."""
        return self._native.json()

    def __str__(self) -> str:
        return self.text

    def __repr__(self) -> str:
        return f"<nbar.EquationsOfMotion at t = {self.time:g} s: {len(self.coordinates)} coordinates>"

