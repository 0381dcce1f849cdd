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


def test_traces_may_be_one_name(examples):
    m = nbar.load(examples / "fourbar-crank-rocker.yaml")
    assert m.draw(traces="P").svg == m.draw(traces=["P"]).svg != m.draw().svg
    assert m.draw(traces="P, O4").svg == m.draw(traces=["P", "O4"]).svg


def test_animation_and_report_of_a_sweep_stopped_at_a_toggle_raise_as_solve_does(tmp_path, toggle_stop):
    m = toggle_stop
    with pytest.raises(nbar.LimitError) as solved:
        m.solve()
    with pytest.raises(nbar.LimitError) as e:
        m.animate()
    assert e.value.line == solved.value.line == 6 and e.value.column == 5
    assert solved.value.result.stop_reason in e.value.message and "at crank = 99.7151 deg" in e.value.message
    assert isinstance(e.value.result, nbar.Animation)  # the part solved, as nbar animate writes it
    assert m.animate(partial=True).html == e.value.result.html
    path = tmp_path / "dr.html"
    with pytest.raises(nbar.LimitError) as e:
        m.report(path)
    assert path.exists() and isinstance(e.value.result, nbar.Report) and (e.value.line, e.value.column) == (6, 5)
    assert m.report(partial=True).html == e.value.result.html
    # A pose of the part solved is drawn, as `nbar draw` draws it.
    assert m.draw(step=50).svg.startswith("<?xml")


def test_plot_puts_two_units_on_two_labelled_axes(examples):
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    r = nbar.load(examples / "fourbar-crank-rocker.yaml").solve()
    ax = nbar.plot(r, ["rocker.angle", "rocker.omega"])
    assert (ax.get_ylabel(), ax.right_ax.get_ylabel()) == ("rocker.angle [deg]", "rocker.omega [deg/s]")
    assert list(ax.lines[0].get_ydata()) == list(r["rocker.angle"])
    assert list(ax.right_ax.lines[0].get_ydata()) == list(r["rocker.omega"])
    assert ax.right_ax.get_ylim()[0] < -400 and ax.get_ylim()[1] < 160  # each axis spans its own column
    assert [t.get_text() for t in ax.get_legend().get_texts()] == ["rocker.angle [deg]",
                                                                   "rocker.omega [deg/s] (right)"]


def test_plot_of_many_columns_is_labelled_by_unit_and_takes_globs(examples):
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    d = nbar.load(examples / "fourbar-steel-bars.yaml").dynamics()
    ax = nbar.plot(d, "*.Fx")
    names = [c for c in d.columns if c.endswith(".Fx")]
    assert len(names) == 4 and ax.get_ylabel() == "[N]"
    assert [t.get_text() for t in ax.get_legend().get_texts()] == names
    r = nbar.load(examples / "fourbar-crank-rocker.yaml").solve()
    ax = nbar.plot(r, "P.*")
    assert [line.get_label() for line in ax.lines] == [f"{c} [{r.units[c]}]" for c in r.columns if c.startswith("P.")]
    with pytest.raises(nbar.ColumnError, match="no column matches 'Q.*'"):
        nbar.plot(r, "Q.*")


def test_plot_takes_a_label_for_one_column(examples):
    pytest.importorskip("matplotlib").use("Agg")
    r = nbar.load(examples / "fourbar-crank-rocker.yaml").solve(steps=37)
    ax = nbar.plot(r, "P.y", x="P.x", label="P: the coupler curve")
    nbar.plot(r, "B.y", x="B.x", ax=ax, label="B")
    assert [line.get_label() for line in ax.lines] == ["P: the coupler curve", "B"]
