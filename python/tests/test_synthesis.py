"""Synthesis from Python: the designs the CLI finds, and designs that become models which do the
task when the kinematics engine drives them."""

import json
import subprocess

import numpy as np
import pytest

import nbar

POINTS = [(-74.772, 20.544), (-3.664, 70.026), (44.303, 194.508), (-56.040, 164.598), (-90.203, 97.034)]


def test_five_point_finds_the_crank_rocker_and_its_model_passes_through_the_points():
    designs = nbar.synth.five_point(pivots=[(0, 0), (200, 0)], points=POINTS, units="mm")
    assert "36 solutions" in " ".join(designs.notes) or designs.data
    best = designs.best
    assert best.defect_free and best.grashof == "crank-rocker"
    assert best.lengths["frame"] == pytest.approx(200, rel=1e-9)
    assert best.lengths["input"] == pytest.approx(80, rel=1e-4)
    m = best.model()
    r = m.solve(steps=3601, columns="P.x,P.y")
    xy = np.column_stack([r["P.x"], r["P.y"]])
    for p in POINTS:
        assert np.min(np.linalg.norm(xy - np.array(p), axis=1)) < 0.2  # within the sampling of 0.1 deg


def test_five_point_from_a_file_equals_the_cli(examples, cli):
    path = examples / "synthesis" / "five-point-crank-rocker.yaml"
    designs = nbar.synth.run(path)
    out = subprocess.run([cli, "synth", "five-point", str(path), "--format", "json"], capture_output=True,
                         text=True, check=True)
    assert json.loads(out.stdout) == designs.data
    assert str(designs).startswith("five-point task")


def test_all_lists_the_complex_solutions_too():
    designs = nbar.synth.five_point(pivots=[(0, 0), (200, 0)], points=POINTS, units="mm", all=True, top=0)
    assert len(designs) == 36
    assert sum(1 for d in designs if not d.real) == 20
    # At most 20 by default, as `nbar synth --all` lists them: the best real ones first.
    first = nbar.synth.five_point(pivots=[(0, 0), (200, 0)], points=POINTS, units="mm", all=True)
    assert len(first) == 20
    assert [d.data for d in first] == [d.data for d in designs[:20]]


def test_burmester_and_function_run(examples):
    poses = [(-74.772, 20.544, 65.248), (22.802, 111.483, 55.771), (44.303, 194.508, 26.642)]
    three = nbar.synth.burmester(poses, fixed_pivots=[(0, 0), (200, 0)], units="mm")
    assert len(three) >= 1 and three.best.model().check().dof == 1
    log = nbar.synth.function("log10(x)", x=(1, 2), input_range=(90, 150), output_range=(60, 120), frame=100,
                              units="mm")
    assert len(log) >= 1 and log.best.data.get("structural_error") is not None


def test_bad_tasks_are_located():
    with pytest.raises(nbar.ModelError) as e:
        nbar.synth.five_point(pivots=[(0, 0), (0, 0)], points=POINTS)
    assert e.value.file == "<five_point>"
    with pytest.raises(nbar.ModelError) as e:
        nbar.synth.five_point(pivots=[(0, 0), (200, 0)], points=POINTS[:4])
    assert e.value.line is not None


def test_points_reach_the_task_reader_as_given():
    # A third coordinate used to be dropped without a word, a word to fail in float().
    with pytest.raises(nbar.ModelError, match="point 1 needs two numbers, like \\[x, y\\], not a list of 3") as e:
        nbar.synth.five_point(pivots=[(0, 0), (200, 0)], points=[(1, 2, 3)] + POINTS[1:], units="mm")
    assert e.value.file == "<five_point>" and e.value.line and e.value.column
    with pytest.raises(nbar.ModelError, match="pivot b needs two numbers"):
        nbar.synth.five_point(pivots=[(0, 0), (200, 0, 7)], points=POINTS, units="mm")
    with pytest.raises(nbar.ModelError, match="point 1 must be a number, not 'a'"):
        nbar.synth.five_point(pivots=[(0, 0), (200, 0)], points=[("a", 1)] + POINTS[1:], units="mm")
    with pytest.raises(nbar.BadInputError, match="pivots .* must be two points, not 1 item"):
        nbar.synth.five_point(pivots=[(0, 0)], points=POINTS)
    with pytest.raises(nbar.BadInputError, match="pose 1 must be \\(x, y, angle\\)"):
        nbar.synth.burmester([(0, 0), (1, 1, 3), (2, 2, 4)], fixed_pivots=[(0, 0), (200, 0)])
    with pytest.raises(nbar.BadInputError, match="top: must be 0 or more, not -1"):
        nbar.synth.five_point(pivots=[(0, 0), (200, 0)], points=POINTS, units="mm", top=-1)
    # numpy numbers are numbers.
    designs = nbar.synth.five_point(pivots=np.array([[0.0, 0.0], [200.0, 0.0]]), points=np.array(POINTS), units="mm")
    assert designs.best.grashof == "crank-rocker"
    # numpy's scalars too (they made json.dumps fail), and threads, seed, timeout are checked here.
    function = nbar.synth.function("log10(x)", x=(1, 2), input_range=(90, 150), output_range=(60, 120),
                                   points=np.int64(3))
    assert function.best is not None
    for options, message in [({"threads": -1}, "threads: must be from 0 to 1024, not -1"),
                             ({"seed": -1}, "seed: must be 0 or more, not -1"),
                             ({"top": 2.5}, "top: must be a whole number, not 2.5"),
                             ({"timeout": "5"}, "timeout must be a number, not '5'")]:
        with pytest.raises(nbar.BadInputError, match=message):
            nbar.synth.five_point(pivots=[(0, 0), (200, 0)], points=POINTS, units="mm", **options)


def test_a_task_dicts_curve_is_the_users_file_read_from_the_current_directory(tmp_path, monkeypatch):
    lines = ["x,y"] + [f"{np.cos(0.5 * k):.6f}, {np.sin(0.5 * k):.6f}" for k in range(11)] + ["2, oops"]
    (tmp_path / "c.csv").write_text("\n".join(lines) + "\n")
    monkeypatch.chdir(tmp_path)
    with pytest.raises(nbar.ModelError) as e:
        nbar.synth.task({"task": "path", "curve": "c.csv"})
    assert (e.value.file, e.value.line, e.value.column) == ("c.csv", 13, 4)
    assert "'oops' is not a finite number (y)" in str(e.value)
