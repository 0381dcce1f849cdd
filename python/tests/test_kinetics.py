"""Dynamics and stresses from Python: power balance, and the CLI's own numbers."""

import json
import subprocess

import numpy as np
import pytest

import nbar


def test_driver_power_balances_the_energy_rate_and_the_loads(examples):
    # Gravity and the spring's stiffness are in the potential energy; the tool force on P and
    # the spring's damper (0.5 N s/m between S and B) do work of their own.
    m = nbar.load(examples / "crank-rocker-gravity-spring.yaml")
    r = m.dynamics(steps=3601)
    omega = np.radians(r["crank.omega"])
    rate = np.gradient(r["energy.kinetic"] + r["energy.potential"], r["t"])
    tool = -40.0 * r["P.vy"] / 1000.0
    sx, sy = m.points["S"]
    length = np.hypot(r["B.x"] - sx, r["B.y"] - sy) / 1000.0
    stretch_rate = ((r["B.x"] - sx) * r["B.vx"] + (r["B.y"] - sy) * r["B.vy"]) / 1e6 / length
    damper = -0.5 * stretch_rate ** 2
    power = r["crank.torque"] * omega
    mismatch = power - (rate - tool - damper)
    assert np.max(np.abs(mismatch)[10:-10]) < 1e-4 * np.max(np.abs(power))


def test_stress_peaks_equal_the_cli(examples, cli):
    path = examples / "fourbar-steel-bars.yaml"
    s = nbar.load(path).stress(steps=37)
    out = subprocess.run([cli, "stress", str(path), "--steps", "37", "--format", "json"], capture_output=True,
                         text=True, check=True)
    assert json.loads(out.stdout) == s.data
    assert s.links and "crank" in str(s)
    profile = s.profile("coupler", step=3)
    assert profile.rows >= 200 and "von_mises" in " ".join(profile.columns)


def test_fe_stress_peaks_equal_the_cli(examples, cli):
    path = examples / "fourbar-steel-bars.yaml"
    s = nbar.load(path).stress(steps=5, method="fe", mesh_size=4)
    out = subprocess.run([cli, "stress", str(path), "--steps", "5", "--method", "fe", "--mesh-size", "4",
                          "--format", "json"], capture_output=True, text=True, check=True)
    assert json.loads(out.stdout) == s.data
    assert s.data["method"] == "fe"
    assert s["crank"]["von_mises"] > 0 and s["crank"]["nodes"] > 100
    with pytest.raises(nbar.BadInputError):
        nbar.load(path).stress(steps=5, method="fem")


def test_fe_field_queries_are_numpy_arrays_equal_to_the_cli(examples, cli):
    path = examples / "fourbar-ansys-plates.yaml"
    s = nbar.load(path).stress(steps=1, method="fe")

    def cli_csv(*options):
        out = subprocess.run([cli, "stress", str(path), "--steps", "1", "--method", "fe", "--format", "csv",
                              *options], capture_output=True, text=True, check=True)
        return np.loadtxt(out.stdout.splitlines()[1:], delimiter=",", ndmin=2)

    hole = s.field("crank", around_hole="A")
    assert isinstance(hole["von_mises"], np.ndarray) and hole.units["angle"] == "deg"
    # docs/kinetics.md's "other hole" figure: 667 kPa at the crank's A hole.
    assert abs(hole["von_mises"].max() - 0.667) < 0.002
    # The CSV is written to 12 digits.
    np.testing.assert_allclose(hole["sigma_hoop"], cli_csv("--around-hole", "crank:A")[:, 3], rtol=1e-10)
    line = s.field("crank", along=((0.1, 0.0), (0.9, 0.0)), samples=9)
    np.testing.assert_array_equal(line["arc"], np.linspace(0, 0.8, 9))
    points = s.field("crank", at=[(0.5, 0.0), (0.3, 0.1)])
    assert len(points["x"]) == 2
    assert points["von_mises"][0] == pytest.approx(line["von_mises"][4], rel=1e-9)  # the same place, x = 0.5
    sections = s.profile("crank")
    assert sections.columns[:5] == ["x", "area", "N", "V", "M"]
    assert s.vtu("coupler").startswith("<?xml")
    with pytest.raises(nbar.BadInputError, match="is not on the plate of 'crank'"):
        s.field("crank", at="O2")


def test_fe_convergence_is_the_clis_and_mesh_options_reach_the_mesher(examples, cli):
    path = examples / "fourbar-ansys-plates.yaml"
    s = nbar.load(path).stress(steps=3, method="fe")
    # The crank's peak lies on the edge of its pivot's hole (radius 10 mm, centred on the body frame's
    # origin), where the stress is flat: the arc within 0.5 % of it holds the peak's own angle.
    crank = s["crank"]
    angle = np.degrees(np.arctan2(crank["y"], crank["x"])) % 360
    assert np.hypot(crank["x"], crank["y"]) == pytest.approx(0.01, rel=1e-6)
    assert crank["flat_from"] <= angle <= crank["flat_to"]
    assert crank["flat_arc"] == pytest.approx(0.01 * np.radians(crank["flat_to"] - crank["flat_from"]), rel=1e-9)
    assert crank["flat_to"] - crank["flat_from"] > 30  # the case: flat over a wide arc
    study = s.converge(tolerance=1)
    out = subprocess.run([cli, "stress", str(path), "--steps", "3", "--method", "fe", "--converge", "--tolerance",
                          "1", "--format", "json"], capture_output=True, text=True, check=True)
    assert json.loads(out.stdout) == study.data
    assert study.converged and study.tolerance == 1.0 and study.stopped is None
    crank = study.peaks("crank")
    # Each mesh halves the sizes of the one before; the last change is the one the tolerance judged.
    assert len(crank) == len(study.meshes) >= 2
    assert abs(crank[-1] - crank[-2]) < 0.01 * crank[-1]
    assert study.meshes[1]["links"][0]["nodes"] > study.meshes[0]["links"][0]["nodes"]
    assert "converged" in repr(study)
    with pytest.raises(nbar.BadInputError):
        study.peaks("frame")
    with pytest.raises(nbar.BadInputError, match="tolerance"):
        s.converge(tolerance=0)
    # More edges around each hole: more nodes, as `--segments-per-hole` gives.
    finer = nbar.load(path).stress(steps=1, method="fe", segments_per_hole=96)
    out = subprocess.run([cli, "stress", str(path), "--steps", "1", "--method", "fe", "--segments-per-hole", "96",
                          "--format", "json"], capture_output=True, text=True, check=True)
    assert json.loads(out.stdout) == finer.data
    assert finer["crank"]["nodes"] > nbar.load(path).stress(steps=1, method="fe")["crank"]["nodes"]
    with pytest.raises(nbar.BadInputError, match="segments_per_hole"):
        nbar.load(path).stress(steps=1, method="fe", segments_per_hole=2)
    with pytest.raises(nbar.BadInputError, match="edge_size"):
        nbar.load(path).stress(steps=1, method="fe", edge_size=-1)


def test_stress_on_a_model_without_shapes_is_a_model_error(examples):
    with pytest.raises(nbar.ModelError):
        nbar.load(examples / "fourbar-crank-rocker.yaml").stress()


def test_stresses_of_a_sweep_stopped_at_a_toggle_raise_as_solve_does(examples):
    text = (examples / "fourbar-steel-bars.yaml").read_text().replace("ground: [O2, O4]",
                                                                     "ground: [O2, O4]\nlengths: {crank: 130}")
    m = nbar.loads(text, "long-crank.yaml")
    with pytest.raises(nbar.LimitError) as e:
        m.stress()
    assert (e.value.line, e.value.column) == (37, 1)  # where solve() and `nbar stress` place it
    assert "at crank = 179.994 deg" in e.value.message and "the peaks over the 180 steps solved" in e.value.message
    peaks = e.value.result
    assert isinstance(peaks, nbar.StressResult) and all(link["step"] < 180 for link in peaks.links)
    assert m.stress(partial=True).links == peaks.links


def test_explain_gives_each_links_largest_stress_at_its_pose(examples):
    # Explain's stresses at step 90 of the steel four-bar are each link's largest von Mises over
    # the section profile of the stress analysis at that step.
    m = nbar.load(examples / "fourbar-steel-bars.yaml")
    e = m.explain(step=90)
    s = m.stress()
    assert [link["body"] for link in e.stresses] == ["crank", "coupler", "rocker"]
    for link in e.stresses:
        profile = s.profile(link["body"], step=90)
        top = int(np.argmax(np.abs(profile["von_mises"])))
        assert link["unit"] == "MPa" and profile.units["von_mises"] == "MPa"
        assert link["von_mises"] == pytest.approx(abs(profile["von_mises"][top]), rel=1e-9)
        assert link["at"] == pytest.approx(profile["x"][top], rel=1e-9)
        assert link["safety_factor"] == pytest.approx(250.0 / link["von_mises"], rel=1e-9)  # steel, 250 MPa
    assert "10. Stresses at this pose" in e.text
    assert nbar.load(examples / "fourbar-crank-rocker.yaml").explain(step=0).stresses == []
