"""What a researcher expects of the API: pickling for process pools, a batch solve, models that
cannot be edited by accident, completion of the documented fields, a clean nbar.synth, plots in
matplotlib's order and a drawing in Jupyter."""

import base64
import math
import pickle
from concurrent.futures import ProcessPoolExecutor

import numpy as np
import pytest

import nbar

FRAME, COUPLER, ROCKER = 200.0, 180.0, 150.0  # examples/fourbar-crank-rocker.yaml (the coupler as drawn, to 1e-7)


def rocker_swing(crank):
    """The rocker's swing (deg) from the triangle O2-O4-B at its two limits, where crank and coupler
    lie in line (O2 to B = coupler + crank, then coupler - crank): the law of cosines at O4."""
    def angle_at_o4(o2_to_b):
        return math.degrees(math.acos((FRAME ** 2 + ROCKER ** 2 - o2_to_b ** 2) / (2 * FRAME * ROCKER)))
    return angle_at_o4(COUPLER + crank) - angle_at_o4(COUPLER - crank)


def swing_of(model):
    """A worker's task in the documented parameter study: the swing measured over a fine sweep."""
    angle = model.solve(steps=3601, columns="rocker.angle")["rocker.angle"]
    return float(angle.max() - angle.min())


# --- pickling ----------------------------------------------------------------------------------

def test_a_model_pickles_as_its_text_and_comes_back_the_same(examples):
    m = nbar.load(examples / "fourbar-crank-rocker.yaml")
    again = pickle.loads(pickle.dumps(m))
    assert again.name == m.name and again.points == m.points
    assert str(again.check()) == str(m.check())
    assert np.array_equal(again.solve(steps=91)["P.x"], m.solve(steps=91)["P.x"])
    assert len(pickle.dumps(m)) < 4 * len((examples / "fourbar-crank-rocker.yaml").read_text())


def test_a_pickled_model_keeps_its_edits_and_its_files_imports(examples, tmp_path, monkeypatch):
    edited = nbar.load(examples / "fourbar-crank-rocker.yaml").with_lengths({"crank": 70})
    again = pickle.loads(pickle.dumps(edited))
    assert again.check().loops[0].rocker.swing == pytest.approx(rocker_swing(70), abs=1e-6)
    # A plate read from a drawing beside the model file: unpickled elsewhere, it is read from there.
    (tmp_path / "plate.svg").write_text(
        '<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="20mm" viewBox="-10 -10 100 20">'
        '<rect x="-10" y="-10" width="100" height="20"/></svg>')
    (tmp_path / "crank.yaml").write_text(
        "units: {length: mm}\npoints: {O: [0, 0], A: [80, 0]}\nground: [O]\n"
        "bodies:\n  crank:\n    points: [O, A]\n    thickness: 8\n    material: steel\n"
        "    shape: {import: plate.svg}\ndrivers: [{angle: crank, from: 0, to: 360}]\n")
    monkeypatch.chdir(tmp_path)
    plate = nbar.load("crank.yaml")
    text = pickle.dumps(plate)
    monkeypatch.chdir(examples)
    unpickled = pickle.loads(text)
    mass = [b.mass for b in unpickled.check().bodies]
    assert mass == [b.mass for b in plate.check().bodies]
    assert mass[0]["area"] == pytest.approx(100 * 20, rel=1e-12)  # mm^2: the plate was read


def test_a_result_pickles_with_its_columns_report_and_json(examples):
    r = nbar.load(examples / "fourbar-crank-rocker.yaml").solve(steps=73)
    again = pickle.loads(pickle.dumps(r))
    assert again.columns == r.columns and again.units == r.units
    assert all(np.array_equal(again[c], r[c]) for c in r.columns)
    assert again["step"].dtype == np.int64 and not again["P.x"].flags.writeable
    for field in ["complete", "stop_reason", "warnings", "max_residual", "branches", "transmission_angles",
                  "default_x"]:
        assert getattr(again, field) == getattr(r, field), field
    assert again.to_json() == r.to_json()
    table = r  # a plain Table too
    plain = pickle.loads(pickle.dumps(nbar.Table(table.columns[:2], [r.units[c] for c in r.columns[:2]],
                                                 [r[c] for c in r.columns[:2]])))
    assert plain.columns == r.columns[:2] and np.array_equal(plain[r.columns[1]], r[r.columns[1]])


def test_designs_pickle_with_their_table_models_and_export(tmp_path):
    points = [(-74.772, 20.544), (-3.664, 70.026), (44.303, 194.508), (-56.040, 164.598), (-90.203, 97.034)]
    designs = nbar.synth.five_point(pivots=[(0, 0), (200, 0)], points=points, units="mm")
    again = pickle.loads(pickle.dumps(designs))
    assert str(again) == str(designs) and again.json == designs.json and again.notes == designs.notes
    assert [d.yaml for d in again] == [d.yaml for d in designs]
    assert again.best.model().check().loops[0].grashof == "crank-rocker"
    one = pickle.loads(pickle.dumps(designs[0]))
    assert one.yaml == designs[0].yaml and one.lengths == designs[0].lengths
    designs.export(tmp_path / "here")
    again.export(tmp_path / "there")
    files = sorted(p.name for p in (tmp_path / "here").iterdir())
    assert files and files == sorted(p.name for p in (tmp_path / "there").iterdir())
    assert all((tmp_path / "here" / f).read_text() == (tmp_path / "there" / f).read_text() for f in files)


def test_a_process_pool_parameter_study_matches_the_closed_form(examples):
    base = nbar.load(examples / "fourbar-crank-rocker.yaml")
    cranks = [60.0, 70.0, 80.0, 90.0]
    models = [base.with_lengths({"crank": c}) for c in cranks]
    with ProcessPoolExecutor(max_workers=2) as pool:
        swings = list(pool.map(swing_of, models))
    assert swings == [swing_of(m) for m in models]  # the same numbers as in this process
    for crank, swing in zip(cranks, swings):
        # 3601 steps: 0.1 deg of crank a step; near a limit the rocker's angle is flat to second order.
        assert swing == pytest.approx(rocker_swing(crank), abs=2e-4), crank


# --- the batch solve ---------------------------------------------------------------------------

def test_solve_many_equals_solving_one_by_one(examples):
    models = [nbar.load(examples / name) for name in
              ["fourbar-crank-rocker.yaml", "five-bar.yaml", "slider-crank-offset.yaml", "fourbar-crank-rocker.yaml"]]
    batch = nbar.solve_many(models, steps=181, threads=2)
    assert len(batch) == len(models)
    for model, result in zip(models, batch):
        alone = model.solve(steps=181)
        assert result.columns == alone.columns
        assert all(np.array_equal(result[c], alone[c]) for c in alone.columns)
        assert result.default_x == alone.default_x
    picked = nbar.solve_many(models[:2], steps=19, columns="*.x", order=3)
    assert picked[0].columns == models[0].solve(steps=19, columns="*.x", order=3).columns


def test_solve_many_gives_cond_as_solve_does(examples):
    # `cond` comes from each sample's factorisation: the batch asks for it as solve() does (it was
    # nan there), and the numbers are the one-by-one solve's, bit for bit.
    models = [nbar.load(examples / name) for name in
              ["fourbar-crank-rocker.yaml", "watt-sixbar-limited.yaml", "slider-crank-inclined.yaml"]]
    batch = nbar.solve_many(models, steps=37, columns="cond,A.x", threads=2)
    for model, result in zip(models, batch):
        alone = model.solve(steps=37, columns="cond,A.x")
        assert result.columns == alone.columns and "cond" in result.columns
        assert np.all(np.isfinite(result["cond"])) and np.all(result["cond"] >= 1.0)
        assert np.array_equal(result["cond"], alone["cond"])
    # The crank-rocker's Jacobian is worst conditioned where its transmission angle is farthest from
    # 90 deg: not a constant column.
    assert batch[0]["cond"].max() > 1.5 * batch[0]["cond"].min()


def test_cond_from_an_analysis_run_without_it_is_the_same_number(examples):
    # An analysis run for other columns, asked for `cond` afterwards: the estimate is made from each
    # sample's pose (it was nan), and agrees with the sweep's own.
    m = nbar.load(examples / "fourbar-double-rocker.yaml")
    columns, _, arrays = m.analyse(steps=41).table(["cond"])
    assert columns == ["cond"]
    alone = m.solve(steps=41, columns="cond")
    assert np.all(np.isfinite(arrays[0])) and np.all(arrays[0] >= 1.0)
    assert np.allclose(arrays[0], alone["cond"], rtol=1e-12, atol=0)  # measured: equal to 4e-16


def test_solve_many_says_which_model_failed(examples, toggle_stop):
    models = [nbar.load(examples / "fourbar-crank-rocker.yaml"), toggle_stop]
    with pytest.raises(nbar.LimitError) as caught:
        nbar.solve_many(models, steps=361)
    assert "in nbar.solve_many: models[1]" in caught.value.__notes__[0]
    assert caught.value.file == "dr.yaml" and caught.value.line == 6
    partial = nbar.solve_many(models, steps=361, partial=True)
    assert partial[0].complete and not partial[1].complete
    assert partial[1].rows == toggle_stop.solve(steps=361, partial=True).rows
    with pytest.raises(nbar.BadInputError, match=r"models\[0\] must be an nbar.Model, not str"):
        nbar.solve_many(["fourbar-crank-rocker.yaml"])
    with pytest.raises(nbar.BadInputError, match="threads"):
        nbar.solve_many(models, threads=-1)
    assert nbar.solve_many([]) == []


# --- read-only views and edited copies ---------------------------------------------------------

def test_a_models_views_refuse_assignment_and_name_the_method_that_edits(examples):
    m = nbar.load(examples / "fourbar-crank-rocker.yaml")
    with pytest.raises(TypeError, match=r"m.points is read-only .*m.with_points\(\{name: \(x, y\)\}\)"):
        m.points["A"] = (0.0, 0.0)
    with pytest.raises(TypeError, match=r"m.bodies is read-only .*with_lengths"):
        m.bodies["crank"] = ("O2", "B")
    with pytest.raises(TypeError, match="read-only"):
        del m.points["A"]
    with pytest.raises(TypeError, match="read-only"):
        m.points.update({"A": (0, 0)})
    assert m.points == {"O2": (0.0, 0.0), "O4": (200.0, 0.0), **{k: m.points[k] for k in ["A", "B", "P"]}}
    assert m.bodies["crank"] == ("O2", "A")
    with pytest.raises(KeyError, match="no point 'Q'; the points are O2, O4, A, B, P"):
        m.points["Q"]


def test_edited_copies_leave_the_model_alone(examples):
    m = nbar.load(examples / "fourbar-crank-rocker.yaml")
    before = m.points["P"]
    moved = m.with_points({"P": (10.0, 120.0)})
    assert moved.points["P"] == (10.0, 120.0) and m.points["P"] == before
    text = (examples / "fourbar-crank-rocker.yaml").read_text()
    written = nbar.loads(text.replace("P:  [77.81169, 121.227931]", "P:  [10, 120]"))  # the same edit, in the file
    assert all(np.array_equal(moved.solve(steps=37)[c], written.solve(steps=37)[c]) for c in ["P.x", "P.y"])
    shorter = m.with_lengths({"crank": 70})
    assert shorter.check().loops[0].rocker.swing == pytest.approx(rocker_swing(70), abs=1e-6)
    assert m.check().loops[0].rocker.swing == pytest.approx(rocker_swing(80), abs=1e-6)
    with pytest.raises(nbar.BadInputError, match="no point 'Q'; the points are O2, O4, A, B, P"):
        m.with_points({"Q": (0, 0)})
    with pytest.raises(nbar.BadInputError, match="body 'coupler' has 3 points: only a body of two points"):
        m.with_lengths({"coupler": 100})
    with pytest.raises(nbar.BadInputError, match="point A must move to"):
        m.with_points({"A": 5})
    shaped = nbar.load(examples / "fourbar-curved-links.yaml")
    on_shape = shaped.bodies[next(iter(shaped.bodies))][0]
    with pytest.raises(nbar.BadInputError, match="whose shape is drawn around its points"):
        shaped.with_points({on_shape: (0, 0)})
    with pytest.raises(nbar.BadInputError, match="'crank' has a shape drawn around its points"):
        shaped.with_lengths({"crank": 50})


# --- completion, namespaces, messages ----------------------------------------------------------

def test_an_explanations_fields_are_listed_by_dir(examples):
    e = nbar.load(examples / "fourbar-crank-rocker.yaml").explain(step=3, steps=13)
    listed = dir(e)
    for field in ["q", "jacobian", "newton", "velocity", "acceleration", "centres", "count", "notes", "text",
                  "latex", "draw"]:
        assert field in listed, field
    assert e.count["dof"] == 1
    with pytest.raises(AttributeError, match="has no attribute 'render'"):
        e.render


def test_synth_exports_only_its_functions_and_classes():
    public = {n for n in dir(nbar.synth) if not n.startswith("_")}
    assert public == set(nbar.synth.__all__)
    assert {"path", "nine_point", "five_point", "burmester", "function", "run", "task", "load"} <= public
    assert not {"Any", "Dict", "os", "json", "html", "numbers"} & public


def test_path_function_equals_its_task_file(examples):
    file = examples / "synthesis" / "path" / "crank-rocker-measured.yaml"
    from_file = nbar.synth.run(file, top=3)
    from_function = nbar.synth.path(points=listed_points(file), units="mm", top=3,
                                    constraints={"crank": True, "min_transmission": 30},
                                    name="Thirty measured points of a crank-rocker's coupler curve")
    assert len(from_function) == 3
    assert [d.lengths for d in from_function] == [d.lengths for d in from_file]
    assert str(from_function) == str(from_file)


def test_nine_point_finds_the_crank_rocker_its_points_came_from(examples):
    # examples/synthesis/nine-point-crank-rocker.yaml: points of the coupler curve of frame 300,
    # crank 100, coupler 300, rocker 250 mm, rounded to 0.001 mm (about 10 s on two threads).
    points = listed_points(examples / "synthesis" / "nine-point-crank-rocker.yaml")
    assert len(points) == 9
    designs = nbar.synth.nine_point(points, units="mm", top=3, threads=2)
    source = [d for d in designs if abs(d.lengths["frame"] - 300) < 0.05]
    assert source, str(designs)
    lengths = source[0].lengths
    assert [lengths["input"], lengths["coupler"], lengths["output"]] == pytest.approx([100, 300, 250], abs=0.05)
    assert designs.method.startswith("parameter homotopy")


def listed_points(path):
    """The `  - [x, y]` lines of a task file, as the file lists them."""
    import re
    return [(float(x), float(y)) for x, y in re.findall(r"^\s+- \[([-\d.]+), ([-\d.]+)\]", path.read_text(), re.M)]


def test_no_design_says_why_and_the_table_speaks_python():
    # Three poses and both fixed pivots: one four-bar, which has a defect (the table says which).
    designs = nbar.synth.burmester([(0, 0, 0), (50, 20, 90), (100, 0, 180)], fixed_pivots=[(0, -50), (100, -50)],
                                   units="mm")
    assert len(designs) == 0
    with pytest.raises(nbar.BadInputError) as caught:
        designs.best
    assert str(caught.value) == ("no design does the task (three positions, fixed pivots chosen): 1 solution, 1 real, "
                                 "0 without defects; all=True lists the defective ones too")
    assert "no design without defects; all=True lists them all" in str(designs)
    assert "--" not in str(designs)
    assert len(nbar.synth.burmester([(0, 0, 0), (50, 20, 90), (100, 0, 180)], fixed_pivots=[(0, -50), (100, -50)],
                                    units="mm", all=True)) == 1
    assert pickle.loads(pickle.dumps(designs))._none_listed() == str(caught.value)


def test_the_checks_start_values_say_at_the_start_with_units(examples):
    summary = nbar.load(examples / "fourbar-crank-rocker.yaml").check()
    assert summary.units == {"length": "mm", "angle": "deg"}
    assert ("crank-rocker; at the start: open branch, transmission angle 41.41 deg" in summary._repr_html_())


# --- plots ---------------------------------------------------------------------------------------

def test_plot_takes_matplotlibs_order_or_refuses(examples):
    pytest.importorskip("matplotlib")
    r = nbar.load(examples / "fourbar-crank-rocker.yaml").solve(steps=37)
    ax = nbar.plot(r, "P.x", "P.y")  # plt.plot(x, y): P.y against P.x
    assert ax.get_xlabel() == "P.x [mm]" and ax.get_ylabel() == "P.y [mm]"
    assert np.array_equal(ax.lines[0].get_xdata(), r["P.x"]) and np.array_equal(ax.lines[0].get_ydata(), r["P.y"])
    same = nbar.plot(r, "P.y", x="P.x")
    assert np.array_equal(same.lines[0].get_xdata(), r["P.x"])
    with pytest.raises(nbar.BadInputError, match="takes x once"):
        nbar.plot(r, "P.x", "P.y", x="crank")
    with pytest.raises(nbar.BadInputError, match=r"\(r, y\) or \(r, x, y\)"):
        nbar.plot(r, "crank", "P.x", "P.y")
    with pytest.raises(nbar.BadInputError, match="needs the columns"):
        nbar.plot(r)


# --- Jupyter ---------------------------------------------------------------------------------------

def test_a_model_shows_its_drawing_in_jupyter(examples, toggle_stop):
    m = nbar.load(examples / "fourbar-crank-rocker.yaml")
    page = m._repr_html_()
    assert "Crank-rocker four-bar" in page
    data = page.split("data:image/svg+xml;base64,")[1].split('"')[0]
    svg = base64.b64decode(data).decode("utf-8")
    assert svg.lstrip().startswith(("<?xml", "<svg")) and ">O4<" in svg
    assert svg == m.draw(steps=2, width=600, height=420).svg
    broken = nbar.loads(TOO_SHORT, "short.yaml")
    assert "Not drawn: " in broken._repr_html_() and "short.yaml" in broken._repr_html_()


# A coupler too short to close the loop: the start cannot be assembled.
TOO_SHORT = """units: {length: mm, angle: deg}
points: {O2: [0, 0], O4: [200, 0], A: [0, 80], B: [150, 150]}
ground: [O2, O4]
bodies: {crank: [O2, A], coupler: [A, B], rocker: [O4, B]}
drivers:
  - {angle: crank, from: 0, to: 360}
lengths: {crank: 20, coupler: 10, rocker: 20}
"""


# --- the examples inside the package --------------------------------------------------------------

def test_the_examples_come_with_the_package(examples):
    path = nbar.examples.path("fourbar-crank-rocker")
    assert path == nbar.examples.path("fourbar-crank-rocker.yaml")
    assert path.read_text() == (examples / "fourbar-crank-rocker.yaml").read_text()
    assert nbar.examples.folder() in path.parents
    names = nbar.examples.names()
    assert "five-bar" in names and "synthesis/nine-point-crank-rocker" in names
    on_disk = sorted(str(p.relative_to(examples).with_suffix("")) for p in examples.rglob("*.yaml")
                     if p.parts[len(examples.parts)] != "cpp")
    assert names == on_disk
    assert nbar.examples.path("synthesis/path/d-shape.csv").is_file()
    assert nbar.synth.run(nbar.examples.path("synthesis/path/d-shape"), top=1).best.grashof
    with pytest.raises(nbar.BadInputError, match="no example 'fourbar-crank-roker'; did you mean 'fourbar-crank-rocker'"):
        nbar.examples.path("fourbar-crank-roker")
    with pytest.raises(nbar.BadInputError, match="no example '../CMakeLists.txt'"):
        nbar.examples.path("../CMakeLists.txt")


# --- the transmission angle's design value --------------------------------------------------------

def transmission_angle(diagonal):
    """mu (deg) between coupler and rocker when O2-O4's partner diagonal A-O4 has this length."""
    return math.degrees(math.acos((COUPLER ** 2 + ROCKER ** 2 - diagonal ** 2) / (2 * COUPLER * ROCKER)))


def test_check_gives_the_transmission_angles_design_value_over_the_cranks_turn(examples):
    m = nbar.load(examples / "fourbar-crank-rocker.yaml")
    over_turn = m.check().loops[0].transmission_over_turn
    crank = 80.0
    # The input along the frame line: A-O4 is frame - crank, then frame + crank.
    assert over_turn["min"] == pytest.approx(transmission_angle(FRAME - crank), abs=1e-5)
    assert over_turn["max"] == pytest.approx(transmission_angle(FRAME + crank), abs=1e-5)
    assert over_turn["design"] == pytest.approx(min(over_turn["min"], 180 - over_turn["max"]), abs=1e-12)
    # The sweep's own design value, measured over 3 601 samples, agrees.
    r = m.solve(steps=3601)
    assert r.transmission_angles["crank-coupler-rocker"]["design"] == pytest.approx(over_turn["design"], abs=1e-4)
    assert nbar.load(examples / "fourbar-double-rocker.yaml").check().loops[0].transmission_over_turn is None
    # Per sample, min(mu, 180 - mu) on request: its min() is the design value, sample by sample
    # the nearer side of the .mu column.
    per_sample = m.solve(steps=3601, columns="*.mu,*.mu_design")
    assert list(per_sample.columns) == ["crank-coupler-rocker.mu", "crank-coupler-rocker.mu_design"]
    mu = per_sample["crank-coupler-rocker.mu"]
    assert per_sample["crank-coupler-rocker.mu_design"] == pytest.approx(np.minimum(mu, 180 - mu), abs=1e-12)
    assert per_sample["crank-coupler-rocker.mu_design"].min() == pytest.approx(over_turn["design"], abs=1e-4)


def test_a_result_says_what_it_is_in_the_shell_and_in_jupyter(examples):
    r = nbar.load(examples / "fourbar-crank-rocker.yaml").solve(steps=37)
    # The Result's own (they sat after a return in a module function and never ran: a Result
    # printed as a bare Table).
    assert repr(r) == f"<nbar.Result: 37 samples x {len(r.columns)} columns, complete>"
    page = r._repr_html_()
    assert page.startswith("<p>37 samples, complete; largest residual ") and "<table" in page
