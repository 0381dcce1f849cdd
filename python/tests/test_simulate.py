"""Model.simulate: the forward dynamics of `nbar simulate` from Python, checked against a motion
integrated here (the same reference as the C++ test ForwardDynamics.RedundantParallelogram...)."""

import math
import pickle

import numpy as np
import pytest

import nbar

# Three equal cranks (0.1 m, 0.4 kg, 2e-4 kg m^2 about their middles) carry a coupler of 1.5 kg,
# which translates: the whole is one pendulum in the crank angle th,
#   (3 (I + m r^2/4) + M r^2) th'' = -(3 m r/2 + M r) g cos th,
# released at th = 0 with th' = 30 deg/s. The third crank repeats a constraint.
PARALLELOGRAM = """units: {length: m, angle: deg}
points:
  O1: [0, 0]
  O2: [0.3, 0]
  O3: [0.15, 0.12]
  A1: [0.1, 0]
  A2: [0.4, 0]
  A3: [0.25, 0.12]
ground: [O1, O2, O3]
gravity: [0, -9.81]
bodies:
  crank1: {points: [O1, A1], mass: 0.4, inertia: 2e-4, cg: [0.05, 0]}
  crank2: {points: [O2, A2], mass: 0.4, inertia: 2e-4, cg: [0.35, 0]}
  crank3: {points: [O3, A3], mass: 0.4, inertia: 2e-4, cg: [0.2, 0.12]}
  coupler: {points: [A1, A2, A3], mass: 1.5, cg: [0.25, 0.05]}
drivers:
  - {angle: crank1, free: true, initial_speed: 30}
"""


def pendulum_angle(t, steps=20000):
    """th(t) of the equivalent pendulum, by the classical Runge-Kutta method."""
    r, m, inertia, big_m, g = 0.1, 0.4, 2e-4, 1.5, 9.81
    k = (3 * m * r / 2 + big_m * r) * g / (3 * (inertia + m * r * r / 4) + big_m * r * r)

    def f(th, w):
        return w, -k * math.cos(th)

    th, w, h = 0.0, math.radians(30), t / steps
    for _ in range(steps):
        a1, b1 = f(th, w)
        a2, b2 = f(th + h / 2 * a1, w + h / 2 * b1)
        a3, b3 = f(th + h / 2 * a2, w + h / 2 * b2)
        a4, b4 = f(th + h * a3, w + h * b3)
        th += h / 6 * (a1 + 2 * a2 + 2 * a3 + a4)
        w += h / 6 * (b1 + 2 * b2 + 2 * b3 + b4)
    return th


@pytest.fixture(scope="module")
def parallelogram():
    return nbar.loads(PARALLELOGRAM, "parallelogram.yaml")


def test_simulate_follows_the_pendulum_it_is(parallelogram):
    r = parallelogram.simulate(to=2, dt=0.5, rtol=1e-12)
    assert r.complete and r.stop_reason is None
    assert list(r["t"]) == [0, 0.5, 1.0, 1.5, 2.0]
    for t, crank1, crank3 in zip(r["t"], r["crank1"], r["crank3.angle"]):
        expected = math.degrees(pendulum_angle(t))
        assert crank1 == pytest.approx(expected, abs=1e-7)  # deg: 2e-9 rad
        assert math.remainder(crank3 - expected, 360) == pytest.approx(0, abs=1e-7)
    assert r.units["crank1"] == "deg" and r.units["energy.kinetic"] == "J"
    # Conservative: the balance stays at the integration error; the drift at rounding.
    assert np.max(np.abs(r["energy.balance"])) < 1e-9
    assert r.statistics is not None
    assert r.statistics["drift"]["position"] < 1e-12 and r.max_residual == r.statistics["drift"]["position"]
    assert r.statistics["accepted_steps"] > 10 and r.statistics["evaluations"] > 6 * r.statistics["accepted_steps"]


def test_simulate_columns_pandas_json_and_pickle(parallelogram):
    import json
    r = parallelogram.simulate(to=0.2, columns="t,crank1,energy.*")
    assert r.columns == ["t", "crank1", "energy.kinetic", "energy.potential", "energy.spring", "energy.dissipated",
                         "energy.work", "energy.balance"]
    assert r.rows == 101  # dt defaults to to/100
    data = json.loads(r.to_json())
    assert data["complete"] is True and data["free_drivers"] == ["crank1"]
    assert data["columns"] == r.columns and len(data["rows"]) == 101
    pytest.importorskip("pandas")
    frame = r.to_pandas()
    assert frame["crank1"].iloc[-1] == r["crank1"][-1] and frame.attrs["units"]["t"] == "s"
    again = pickle.loads(pickle.dumps(r))
    assert again.statistics == r.statistics and list(again["crank1"]) == list(r["crank1"])


def test_a_run_that_stops_early_raises_with_the_rows_so_far(parallelogram):
    with pytest.raises(nbar.LimitError) as caught:
        parallelogram.simulate(to=2, dt=0.01, max_steps=5)
    assert "more than 5 steps" in str(caught.value)
    partial = caught.value.result
    assert not partial.complete and 0 < partial.rows < 201
    again = parallelogram.simulate(to=2, dt=0.01, max_steps=5, partial=True)
    assert list(again["t"]) == list(partial["t"])


def test_simulate_options_are_the_command_lines(parallelogram):
    with pytest.raises(nbar.BadInputError, match="rtol"):
        parallelogram.simulate(to=1, rtol=0.5)
    with pytest.raises(nbar.BadInputError, match="to"):
        parallelogram.simulate(to=0)
    with pytest.raises(nbar.BadInputError, match="dt"):
        parallelogram.simulate(to=10, dt=1e-6)  # more than a million rows
    with pytest.raises(nbar.ColumnError, match="did you mean 'crank1'"):
        parallelogram.simulate(to=0.1, columns="crank")
    with pytest.raises(nbar.BadInputError, match="threads"):
        parallelogram.simulate(to=0.1, threads=3)


def test_the_rows_thread_changes_nothing_but_the_time(parallelogram):
    """The output rows made on a second thread (the default where there are two cores) are the
    rows of a run on one thread, to the last bit."""
    two = parallelogram.simulate(to=0.5, dt=0.001, at_toggle="reverse")
    one = parallelogram.simulate(to=0.5, dt=0.001, at_toggle="reverse", threads=1)
    assert two.rows == one.rows == 501 and two.events == one.events
    assert (two.to_numpy() == one.to_numpy()).all()
    assert two.statistics == one.statistics


def test_a_stop_condition_ends_the_run_at_its_time():
    """A block falling along a vertical guide from y = 0.3 m at 0.5 m/s passes y = -0.2 m at the
    root of g t^2 / 2 + 0.5 t - 0.5 = 0 (as ForwardDynamics.AStopConditionEndsTheRunAtItsCrossingTime)."""
    block = nbar.loads("""units: {length: m, angle: deg}
points: {Y1: [0, 1], Y2: [0, -1], C: [0, 0.3]}
ground: [Y1, Y2]
gravity: [0, -9.81]
bodies:
  block: {points: [C], mass: 2}
sliders:
  - {body: block, point: C, along: [Y1, Y2]}
drivers:
  - {slide: block, free: true, initial_speed: 0.5}
""")
    r = block.simulate(to=1, dt=0.01, rtol=1e-10, stop_when="C.y < -0.2")
    g = 9.81
    expected = (-0.5 + math.sqrt(0.25 + 2 * g * 0.5)) / g
    assert r.complete and len(r.events) == 1
    assert r.events[0]["kind"] == "stop_when" and r.events[0]["row"] == r.rows - 1
    assert r.events[0]["time"] == pytest.approx(expected, abs=1e-10)
    assert r["t"][-1] == r.events[0]["time"] and r["C.y"][-1] == pytest.approx(-0.2, abs=1e-9)
    with pytest.raises(nbar.BadInputError, match="stop_when"):
        block.simulate(to=1, stop_when="C.y is low")
    with pytest.raises(nbar.BadInputError, match="at_toggle"):
        block.simulate(to=1, at_toggle="bounce")


def test_a_simulation_animates_its_rows_at_their_times(parallelogram, examples):
    """Result.animate is `nbar animate --simulate`: one frame per row (11 rows, 11 frames), each
    read out at its row's time and crank angle."""
    import re

    sim = parallelogram.simulate(to=0.5, dt=0.05)
    animation = sim.animate(frames=11)
    assert isinstance(animation, nbar.Animation)
    readouts = re.findall(r'"t = ([-0-9.e]+) s, crank1 = ([-0-9.e]+) deg"', animation.html)
    assert [float(t) for t, _ in readouts] == pytest.approx(list(sim["t"]), abs=1e-9)
    assert [float(a) for _, a in readouts] == pytest.approx(list(sim["crank1"]), abs=1e-3)
    assert "<svg" in animation.data("svg")
    with pytest.raises(nbar.BadInputError, match="Model.animate"):
        nbar.load(examples / "crank-rocker-released.yaml").solve(steps=3).animate()


def test_ctrl_c_raises_keyboard_interrupt_with_the_rows_so_far(parallelogram):
    """SIGINT half a second into a long run: KeyboardInterrupt, as Python code expects, with the
    rows up to there as .result, a row every dt from the start."""
    import os
    import signal
    import threading

    timer = threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt) as caught:
            parallelogram.simulate(to=5000, dt=0.01)
    finally:
        timer.cancel()
    partial = caught.value.result
    assert not partial.complete and partial.stop_reason.startswith("cancelled at t = ")
    assert 1 < partial.rows < 500001
    assert np.allclose(np.diff(partial["t"]), 0.01, rtol=0, atol=1e-9)
    assert f"at t = {partial['t'][-1]:.9g} s" in partial.stop_reason


def test_a_timeout_keeps_the_rows_so_far(parallelogram):
    with pytest.raises(nbar.Cancelled) as caught:
        parallelogram.simulate(to=5000, dt=0.01, timeout=0.3)
    partial = caught.value.result
    assert not partial.complete and partial.stop_reason.startswith("cancelled: the time budget ran out at t = ")
    assert partial.rows > 1
    kept = parallelogram.simulate(to=5000, dt=0.01, timeout=0.3, partial=True)
    assert not kept.complete and kept.rows > 1


def test_explain_at_a_time_gives_the_simulated_accelerations(parallelogram):
    """The printed system [M Phi_q^T; Phi_q 0] [q''; lambda] = [Q; gamma], solved here (least
    squares: the third crank makes Phi_q rank-deficient), gives the accelerations of the row
    simulate() reports at that time."""
    e = parallelogram.explain(simulate=True, at=0.4, rtol=1e-10)
    assert isinstance(e, nbar.EquationsOfMotion) and e.time == 0.4
    n, m = e.mass.shape[0], e.jacobian.shape[0]
    assert n == 6 and m == 6
    system = np.block([[e.mass, e.jacobian.T], [e.jacobian, np.zeros((m, m))]])
    forces = e.forces
    q_forces = forces["gravity"] + forces["given"] + forces["springs"] + forces["friction"]
    solution = np.linalg.lstsq(system, np.concatenate([q_forces, e.gamma]), rcond=1e-12)[0]
    run = parallelogram.simulate(to=0.4, dt=0.04, rtol=1e-10)
    simulated = np.array([run[c[:-1] + "a" + c[-1]][-1] for c in e.coordinates])
    assert np.max(np.abs(solution[:n] - simulated)) < 1e-9 * np.max(np.abs(simulated))
    assert "[ Phi_q  0       ] [ lambda ] = [ gamma ]" in str(e)
    assert '"multipliers"' in e.to_json()
    with pytest.raises(nbar.BadInputError, match="at"):
        parallelogram.explain(simulate=True, at=-1)
    with pytest.raises(nbar.BadInputError, match="simulate=True"):
        parallelogram.explain(at=0.4)
