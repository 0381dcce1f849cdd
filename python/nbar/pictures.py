"""Pictures that show themselves in Jupyter and save to files."""

from __future__ import annotations

import base64
import html
import os
from typing import Union


def _write(path: Union[str, os.PathLike], data: Union[str, bytes]) -> None:
    mode = "wb" if isinstance(data, bytes) else "w"
    try:
        with open(path, mode, **({} if isinstance(data, bytes) else {"encoding": "utf-8"})) as f:
            f.write(data)
    except OSError as e:
        from .errors import BadInputError
        folder = os.path.dirname(os.fspath(path)) or "."
        reason = f"the folder {folder} does not exist" if not os.path.isdir(folder) else e.strerror
        raise BadInputError(f"cannot write {os.fspath(path)}: {reason}") from None


class Drawing:
    """The mechanism in one pose. Shown as SVG in Jupyter; ``.svg`` is the text, ``.png()``
    the PNG bytes, ``.save("pose.svg"|"pose.png")`` writes a file."""

    def __init__(self, analysis=None, **options):
        self._png = (lambda: analysis.draw("png", **options)) if analysis is not None else None
        self.svg: str = analysis.draw("svg", **options) if analysis is not None else ""

    @classmethod
    def from_data(cls, svg: str, png) -> "Drawing":
        """A drawing of an SVG text, with ``png`` making its PNG bytes when asked."""
        d = cls()
        d.svg = svg
        d._png = png
        return d

    def png(self) -> bytes:
        return self._png()

    def save(self, path: Union[str, os.PathLike]) -> None:
        from ._args import path as as_path
        name = as_path("path", path)
        ext = name.rsplit(".", 1)[-1].lower()
        if ext == "png":
            _write(path, self.png())
        elif ext == "svg":
            _write(path, self.svg)
        else:
            from .errors import BadInputError
            raise BadInputError(f"{name}: a drawing is saved as .svg or .png")

    def _repr_svg_(self) -> str:
        # Without the XML declaration: notebook tools (nbconvert) embed the SVG in HTML.
        svg = self.svg
        if svg.startswith("<?xml"):
            svg = svg[svg.index("?>") + 2:].lstrip()
        return svg

    def _repr_html_(self) -> str:
        # An image of the SVG: it scales to a phone's width, and notebook exporters that strip
        # inline SVG (nbconvert) keep it.
        data = base64.b64encode(self.svg.encode("utf-8")).decode("ascii")
        return f'<img src="data:image/svg+xml;base64,{data}" style="max-width:100%;height:auto" alt="nbar drawing">'

    def __repr__(self) -> str:
        return "<nbar.Drawing: .svg, .png(), .save(path)>"


class Animation:
    """The whole sweep moving. Shown in Jupyter as the self-contained HTML player (in an
    iframe); ``.save(path)`` writes .html, .svg, .gif or .mp4 (MP4 needs the ffmpeg program)."""

    def __init__(self, analysis, **options):
        self._analysis = analysis
        self._options = options
        self.html: str = analysis.animate("html", **options)

    def data(self, format: str) -> Union[str, bytes]:
        """The animation as "html", "svg" (text) or "gif", "mp4" (bytes)."""
        return self.html if format == "html" else self._analysis.animate(format, **self._options)

    def save(self, path: Union[str, os.PathLike]) -> None:
        from ._args import path as as_path
        name = as_path("path", path)
        ext = name.rsplit(".", 1)[-1].lower()
        if ext not in ("html", "svg", "gif", "mp4"):
            from .errors import BadInputError
            raise BadInputError(f"{name}: an animation is saved as .html, .svg, .gif or .mp4")
        _write(path, self.data(ext))

    def _repr_html_(self) -> str:
        # The drawing scales with the width the notebook gives it, but the title, the controls and
        # the read-out around it do not, and on a phone they wrap to more lines: the frame is the
        # drawing's height at that width (a padding in percent is of the width) plus 175 px, or
        # more when narrow (193 px at a phone's 250 px output), where one aspect ratio for the
        # whole cut the controls off.
        width = self._options.get("width", 900)
        drawing = 100.0 * self._options.get("height", 640) / width
        return (f'<div style="max-width:{width}px"><div style="position:relative;padding-top:calc({drawing:.4g}% + '
                f'max(175px, 205px - 5%))"><iframe srcdoc="{html.escape(self.html, quote=True)}" style="position:'
                f'absolute;top:0;left:0;width:100%;height:100%;border:0" sandbox="allow-scripts"></iframe></div></div>')

    def __repr__(self) -> str:
        return "<nbar.Animation: .html, .data(format), .save(path)>"


class Report:
    """The one-file HTML report of ``nbar report``. ``.html`` is the page, ``.save(path)``
    writes it; Jupyter shows it in an iframe."""

    def __init__(self, page: str):
        self.html = page

    def save(self, path: Union[str, os.PathLike]) -> None:
        _write(path, self.html)

    def _repr_html_(self) -> str:
        return (f'<iframe srcdoc="{html.escape(self.html, quote=True)}" style="width:100%;height:80vh;border:0" '
                f'sandbox="allow-scripts"></iframe>')

    def __repr__(self) -> str:
        return "<nbar.Report: .html, .save(path)>"


def png_data_uri(data: bytes) -> str:
    return "data:image/png;base64," + base64.b64encode(data).decode("ascii")
