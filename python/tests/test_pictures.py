"""Pictures from Python: the CLI's drawings and animations, shown by Jupyter and saved."""

import subprocess
import xml.etree.ElementTree as ET

import pytest

import nbar


def test_drawing_is_the_cli_drawing(examples, cli, tmp_path):
    path = examples / "fourbar-crank-rocker.yaml"
    d = nbar.load(path).draw(labels=True, traces=["P"])
    subprocess.run([cli, "draw", str(path), "-o", str(tmp_path / "cli.svg"), "--labels", "--trace", "P"], check=True)
    assert d.svg == (tmp_path / "cli.svg").read_text()
    assert d._repr_svg_().startswith("<svg") and d._repr_svg_() in d.svg
    assert d._repr_html_().startswith('<img src="data:image/svg+xml;base64,')
    ET.fromstring(d.svg)
    assert d.png().startswith(b"\x89PNG")
    d.save(tmp_path / "pose.png")
    assert (tmp_path / "pose.png").read_bytes() == d.png()


def test_draw_at_a_driver_value(examples):
    d = nbar.load(examples / "fourbar-crank-rocker.yaml").draw(at=90)
    assert "<svg" in d.svg


def test_animation_html_and_gif(examples, tmp_path):
    a = nbar.load(examples / "fourbar-crank-rocker.yaml").animate(frames=12, steps=37)
    assert "<script" in a.html and "iframe" in a._repr_html_()
    a.save(tmp_path / "a.gif")
    assert (tmp_path / "a.gif").read_bytes()[:6] in (b"GIF89a", b"GIF87a")
    with pytest.raises(nbar.BadInputError):
        a.save(tmp_path / "a.bmp")


def test_report_is_one_html_file(examples, tmp_path):
    r = nbar.load(examples / "fourbar-steel-bars.yaml").report(tmp_path / "report.html")
    assert r.html.startswith("<!DOCTYPE html>") and (tmp_path / "report.html").read_text() == r.html


def test_plot_with_units_and_equal_scales(examples):
    pytest.importorskip("matplotlib")
    import matplotlib
    matplotlib.use("Agg")
    r = nbar.load(examples / "fourbar-crank-rocker.yaml").solve(steps=37)
    ax = nbar.plot(r, "rocker.omega")
    assert ax.get_xlabel() == "crank [deg]" and "deg/s" in ax.get_ylabel()
    ax2 = nbar.plot(r, "P.y", x="P.x")
    assert ax2.get_aspect() == 1.0


def test_time_law_models_plot_against_time(examples):
    pytest.importorskip("matplotlib")
    import matplotlib
    matplotlib.use("Agg")
    r = nbar.load(examples / "fourbar-oscillating.yaml").solve(steps=41)
    assert nbar.plot(r, "output.omega").get_xlabel() == "t [s]"
