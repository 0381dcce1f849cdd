"""Kinematics from Python against independent references: Norton's closed form for the
four-bar, sympy's derivatives of the slider-crank's closed form, and the CLI's own numbers."""

import csv
import io
import json
import math
import subprocess

import numpy as np
import pytest

import nbar


def fourbar_closed_form(a, b, c, d, theta2, open_branch):
    """Norton, Design of Machinery, eq. 4.10: the rocker angle theta4 of a four-bar with frame d,
    crank a, coupler b, rocker c."""
    k1, k2, k3 = d / a, d / c, (a * a - b * b + c * c + d * d) / (2 * a * c)
    A = math.cos(theta2) - k1 - k2 * math.cos(theta2) + k3
    B = -2 * math.sin(theta2)
    C = k1 - (k2 + 1) * math.cos(theta2) + k3
    root = math.sqrt(B * B - 4 * A * C)
    return 2 * math.atan2(-B - root if open_branch else -B + root, 2 * A)


def test_fourbar_rocker_angle_matches_nortons_closed_form(examples):
    m = nbar.load(examples / "fourbar-crank-rocker.yaml")
    r = m.solve(steps=73, columns="crank,rocker.angle,rocker.omega")
    assert r.complete and r.units["rocker.angle"] == "deg"
    worst = 0.0
    for crank, rocker in zip(r["crank"], r["rocker.angle"]):
        expected = fourbar_closed_form(80, math.hypot(101.25, 148.823511), 150, 200, math.radians(crank), True)
        diff = (math.radians(rocker) - expected + math.pi) % (2 * math.pi) - math.pi
        worst = max(worst, abs(diff))
    assert worst < 1e-9


def test_angular_velocity_is_the_derivative_of_the_angle(examples):
    m = nbar.load(examples / "fourbar-crank-rocker.yaml")
    r = m.solve(steps=3601, columns="t,rocker.angle,rocker.omega")
    numeric = np.gradient(r["rocker.angle"], r["t"])
    assert np.max(np.abs(numeric[5:-5] - r["rocker.omega"][5:-5])) < 1e-3 * np.max(np.abs(r["rocker.omega"]))


def test_slider_crank_derivatives_to_fifth_order_match_sympy(examples):
    sympy = pytest.importorskip("sympy")
    t = sympy.symbols("t")
    r_, l_, w = 0.75, 2.0, 1750 * 2 * sympy.pi / 60
    theta = w * t
    x = r_ * sympy.cos(theta) + sympy.sqrt(l_ ** 2 - (r_ * sympy.sin(theta)) ** 2)
    derivatives = [x]
    for _ in range(5):
        derivatives.append(sympy.diff(derivatives[-1], t))
    m = nbar.load(examples / "compressor-myszka.yaml")
    names = ["C.x", "C.vx", "C.ax", "C.jx", "C.d4x", "C.d5x"]
    res = m.solve(steps=25, order=5, columns=["t"] + names)
    for k, name in enumerate(names):
        f = sympy.lambdify(t, derivatives[k], "math")
        exact = np.array([f(tt) for tt in res["t"]])
        scale = np.max(np.abs(exact))
        assert np.max(np.abs(res[name] - exact)) < 1e-9 * scale, name


def test_columns_agree_with_the_cli_csv(examples, cli):
    path = examples / "five-bar.yaml"
    out = subprocess.run([cli, "solve", str(path), "--steps", "7"], capture_output=True, text=True, check=True)
    rows = list(csv.reader(io.StringIO(out.stdout)))
    r = nbar.load(path).solve(steps=7)
    assert rows[0] == r.columns
    for c, name in enumerate(rows[0]):
        assert [float(v[c]) for v in rows[1:]] == pytest.approx(list(r[name]), rel=1e-10, abs=1e-10)


def test_result_carries_units_warnings_and_residual(examples):
    r = nbar.load(examples / "fourbar-crank-rocker.yaml").solve(steps=13)
    assert r.rows == 13 and "P.vx" in r and r.units["P.vx"] == "mm/s"
    assert r.complete and r.stop_reason is None and r.warnings == []
    assert 0 <= r.max_residual < 1e-9
    assert r.branches == ["open"]
    with pytest.raises(ValueError):
        r["P.vx"][0] = 1.0  # results are read-only views


def test_globs_and_order_follow_the_columns_asked(examples):
    m = nbar.load(examples / "fourbar-crank-rocker.yaml")
    r = m.solve(steps=5, columns="rocker.*")
    assert r.columns == ["rocker.angle", "rocker.omega", "rocker.alpha"]
    r3 = m.solve(steps=5, columns="rocker.jerk")
    assert r3.columns == ["rocker.jerk"]


def test_centres_of_mass_and_cond_come_only_when_named(examples, cli):
    m = nbar.load(examples / "fourbar-steel-bars.yaml")
    assert "coupler.cg.x" not in m.solve(steps=5).columns
    assert m.solve(steps=5, columns="coupler.*").columns == ["coupler.angle", "coupler.omega", "coupler.alpha"]
    r = m.solve(steps=13, columns="A.x,B.x,coupler.cg.*,cond")
    assert r.columns[:4] == ["A.x", "B.x", "coupler.cg.x", "coupler.cg.y"] and r.columns[-1] == "cond"
    # The coupler is a symmetric steel bar between A and B: its centre of mass is their middle.
    assert np.allclose(r["coupler.cg.x"], 0.5 * (r["A.x"] + r["B.x"]), rtol=0, atol=1e-9)
    assert np.all(np.isfinite(r["cond"])) and np.all(r["cond"] >= 1.0)
    # The same numbers as the command line's.
    out = subprocess.run([cli, "solve", str(examples / "fourbar-steel-bars.yaml"), "--steps", "13",
                          "--columns", "coupler.cg.x,cond"], capture_output=True, text=True, check=True).stdout
    rows = list(csv.reader(io.StringIO(out)))[1:]
    assert np.allclose([float(row[0]) for row in rows], r["coupler.cg.x"], rtol=1e-10, atol=1e-9)  # CSV: 12 digits
    assert np.allclose([float(row[1]) for row in rows], r["cond"], rtol=1e-10, atol=0)


def test_a_model_from_a_dict_equals_the_file(examples):
    L1, L2, L3, d, theta = 80.0, math.hypot(101.25, 148.823511), 150.0, 200.0, 0.0
    file_model = nbar.load(examples / "fourbar-crank-rocker.yaml")
    pts = file_model.points
    m = nbar.Model.from_dict({
        "units": {"length": "mm", "angle": "deg"},
        "points": {"O2": [0, 0], "O4": [d, 0], "A": [L1 * math.cos(theta), L1 * math.sin(theta)],
                   "B": list(pts["B"])},
        "ground": ["O2", "O4"],
        "bodies": {"crank": ["O2", "A"], "coupler": ["A", "B"], "rocker": ["O4", "B"]},
        "lengths": {"crank": L1, "rocker": L3},
        "drivers": [{"angle": "crank", "from": 0, "to": 360, "speed": "120 rpm"}],
    })
    a = m.solve(steps=19, columns="rocker.angle")["rocker.angle"]
    b = file_model.solve(steps=19, columns="rocker.angle")["rocker.angle"]
    assert np.max(np.abs(a - b)) < 1e-9
    assert L2 > 0 and L3 > 0


def test_check_gives_the_structure(examples):
    s = nbar.load(examples / "fourbar-crank-rocker.yaml").check()
    assert (s.dof, s.gruebler) == (1, 1)
    assert s.loops[0].grashof == "crank-rocker" and s.loops[0].branch == "open"
    assert s.loops[0].input_turns_fully and not s.loops[0].output_turns_fully
    assert "Grashof" in str(s) or "crank-rocker" in str(s)
    assert "<table>" in s._repr_html_()
    red = nbar.load(examples / "parallelogram-redundant.yaml").check()
    assert red.dof == 1 and red.gruebler == 0 and len(red.redundant) == 1


def test_check_gives_slider_crank_and_quick_return_facts(examples):
    # Closed forms: offset slider-crank stroke sqrt((l+r)^2-e^2) - sqrt((l-r)^2-e^2);
    # quick-return time ratio (360 - 2 acos(r/d)) / (2 acos(r/d)) with r = 100, d = 250 mm.
    s = nbar.load(examples / "slider-crank-offset.yaml").check()
    f = s.slider_cranks[0]
    r, l, e = 50.0, math.hypot(178.255435, 25.0), 25.0
    assert f.stroke == pytest.approx(math.sqrt((l + r) ** 2 - e * e) - math.sqrt((l - r) ** 2 - e * e), abs=1e-9)
    assert f.dead_centres["outer"] == pytest.approx(math.degrees(math.asin(e / (l + r))), abs=1e-9)
    q = nbar.load(examples / "inverted-slider-crank-shaper.yaml").check().quick_returns[0]
    beta = 2 * math.acos(0.4)
    assert q.time_ratio == pytest.approx((2 * math.pi - beta) / beta, rel=1e-12)
    assert q.swing == pytest.approx(math.degrees(2 * math.asin(0.4)), abs=1e-9)
    assert "Slider-cranks: 1" in str(s)


def test_pandas_frame_has_the_columns(examples):
    pytest.importorskip("pandas")
    r = nbar.load(examples / "fourbar-crank-rocker.yaml").solve(steps=5, columns="crank,rocker.angle")
    frame = r.to_pandas()
    assert list(frame.columns) == ["crank", "rocker.angle"] and len(frame) == 5
    assert frame.attrs["units"]["crank"] == "deg"


def test_explanation_is_the_solvers_own_numbers(examples):
    m = nbar.load(examples / "fourbar-crank-rocker.yaml")
    r = m.solve(steps=37, columns="A.vx,A.vy,B.vx,B.vy,B.ax,B.ay")
    e = m.explain(step=5, steps=37)
    assert e.converged and e.matches_sweep and e.coordinates == ["A.x", "A.y", "B.x", "B.y", "P.x", "P.y"]
    assert (e.count["links"], e.count["lower_pairs"], e.count["higher_pairs"], e.count["dof"]) == (4, 4, 0, 1)
    v = e.velocity["solution"]
    assert np.allclose(v[:4], [r["A.vx"][5], r["A.vy"][5], r["B.vx"][5], r["B.vy"][5]], rtol=1e-9, atol=1e-9)
    assert np.allclose(e.velocity["matrix"] @ v, e.velocity["rhs"], atol=1e-9 * np.abs(e.velocity["rhs"]).max())
    assert np.allclose(e.acceleration["solution"][2:4], [r["B.ax"][5], r["B.ay"][5]], rtol=1e-8)
    residuals = [it["residual"] for it in e.newton]
    assert residuals[-1] < 1e-9 and all(b < a for a, b in zip(residuals, residuals[1:]))
    # three link lengths, the coupler point P held on the coupler (x and y), the driver
    assert [q["kind"] for q in e.equations].count("distance") == 3 and len(e.equations) == 6
    assert "\\Phi" in e.markdown and "Newton" in e.text and e.draw().svg.count("I") > 0
    assert len(e.centres) == 6


def test_step_numbers_are_integers(examples):
    r = nbar.load(examples / "fourbar-crank-rocker.yaml").solve(steps=361)
    assert r["step"].dtype == np.int64 and r["step"][-1] == 360
    assert r["crank"][r["step"][90]] == r["crank"][90]
    st = nbar.load(examples / "fourbar-steel-bars.yaml").stress()
    step = st.links[0]["step"]
    assert type(step) is int and step == 354
    r = nbar.load(examples / "fourbar-steel-bars.yaml").solve()
    assert r["crank"][step] == pytest.approx(354.0)


def test_from_dict_takes_numpy_values():
    L1, L2, L3, d = np.float64(80), np.int64(180), np.float32(150), 200
    A = np.array([L1, 0.0])
    m = nbar.Model.from_dict({
        "units": {"length": "mm", "angle": "deg"},
        "points": {"O2": [0, 0], "O4": [d, 0], "A": A, "B": np.array([181.25, 148.823511])},
        "ground": ["O2", "O4"],
        "bodies": {"crank": ["O2", "A"], "coupler": ["A", "B"], "rocker": ["O4", "B"]},
        "lengths": {"crank": L1, "coupler": L2, "rocker": L3},
        "drivers": [{"angle": "crank", "from": np.int64(0), "to": 360, "speed": "60 rpm"}],
    })
    assert m.points["A"] == (80.0, 0.0)
    loop = m.check().loops[0]
    assert [loop.lengths[k] for k in ("frame", "input", "coupler", "output")] == pytest.approx((200, 80, 180, 150))
    # The same loop as `nbar check --format json` and the web API give it: its Grashof margin too.
    assert loop.grashof_margin == pytest.approx((180 + 150) - (80 + 200))
    with pytest.raises(nbar.ModelError, match="<dict>:5:7: y must be a finite number, not 'NaN'"):
        nbar.Model.from_dict({"points": {"O": np.array([0.0, np.nan])}})  # NaN in an array: refused where it is


def test_explain_says_why_a_step_needs_no_iteration(examples):
    e = nbar.load(examples / "slider-crank-offset.yaml").explain(step=0)
    assert len(e.newton) == 1 and e.converged  # the drawn pose is the solution
    assert ("Converged after 0 iterations; at the solution max |Phi| = 1.93e-14 mm. There is nothing to iterate: the "
            "drawn pose already meets every constraint to within the tolerance, so it is the solution. A later step "
            "starts from the pose of the step before it and shows the iterations.") in " ".join(e.text.split())
    later = nbar.load(examples / "fourbar-crank-rocker.yaml").explain(step=30)
    assert len(later.newton) - 1 == 3 and "Converged after 3 iterations;" in later.text
    assert "nothing to iterate" not in later.text
    assert "Converged after 1 iteration;" in nbar.load(examples / "fourbar-crank-rocker.yaml").explain(step=0).text


def test_check_gives_a_crank_rockers_swing_and_time_ratio(examples):
    # Law of cosines on the example (frame 200, crank 80, coupler 180, rocker 150 mm): the
    # crank lies along O2-B at acos((r^2 + d^2 - c^2) / (2 r d)), r = 260 stretched, 100 folded.
    loop = nbar.load(f"{examples}/fourbar-crank-rocker.yaml").check().loops[0]
    stretched = math.degrees(math.acos((260**2 + 200**2 - 150**2) / (2 * 260 * 200)))
    folded = 180 + math.degrees(math.acos((100**2 + 200**2 - 150**2) / (2 * 100 * 200)))
    assert loop.rocker.crank_stretched == pytest.approx(stretched, abs=1e-6)
    assert loop.rocker.crank_folded == pytest.approx(folded, abs=1e-6)
    turn = stretched + 360 - folded
    assert loop.rocker.time_ratio == pytest.approx((360 - turn) / turn, rel=1e-8)
    assert loop.rocker.swing == pytest.approx(65.921, abs=1e-3)


def test_the_transmission_angle_over_the_sweep_comes_from_the_core(examples):
    # Frame 200, crank 80, coupler 180, rocker 150 mm: mu is extreme with the crank along the frame,
    # cos mu = (180^2 + 150^2 - d^2) / (2 180 150) with d = 200 - 80 and 200 + 80.
    m = nbar.load(examples / "fourbar-crank-rocker.yaml")
    r = m.solve(steps=361, order=0)
    mu = r.transmission_angles["crank-coupler-rocker"]
    b = math.dist(m.points["A"], m.points["B"])  # the drawing's coupler, 179.9999998 mm
    smallest = math.degrees(math.acos((b**2 + 150**2 - 120**2) / (2 * b * 150)))
    largest = math.degrees(math.acos((b**2 + 150**2 - 280**2) / (2 * b * 150)))
    assert mu["min"] == pytest.approx(smallest, abs=1e-9) and mu["min_step"] == 0
    assert mu["max"] == pytest.approx(largest, abs=1e-9) and mu["max_step"] == 180
    assert mu["design"] == pytest.approx(min(smallest, 180 - largest), abs=1e-9) and mu["design_step"] == 0
    # The same numbers as the JSON of `nbar solve --format json`.
    branches = json.loads(r.to_json())["branches"]
    assert branches[0]["transmission_angle"] == mu
