"""Model.equilibrium (`nbar equilibrium`) against closed forms, and what the model file adds to
Model.simulate: its `simulation:` settings, joint friction and projected initial speeds."""

import math

import numpy as np
import pytest

import nbar

# A block of 2 kg hanging on a vertical guide from a spring of 400 N/m (free length 0.3 m,
# preload 4 N): at rest where k (l - l0) + P = m g, stable with stiffness k.
BLOCK = """units: {length: m, angle: deg}
points: {Y1: [0, 1.5], Y2: [0, -1], S: [0, 1], C: [0, 0.5]}
ground: [Y1, Y2, S]
gravity: [0, -9.81]
bodies:
  block: {points: [C], mass: 2}
sliders:
  - {body: block, point: C, along: [Y1, Y2]}
springs:
  - {between: [S, C], stiffness: 400, free_length: 0.3, preload: 4, damping: 20}
drivers:
  - {slide: block, free: true}
"""


def test_equilibrium_of_a_block_on_a_spring():
    e = nbar.loads(BLOCK, "block.yaml").equilibrium()
    length = 0.3 + (2 * 9.81 - 4) / 400
    assert e["stability"] == "stable"
    assert e["free_drivers"]["block"] == pytest.approx(length + 0.5, abs=1e-12)
    assert e["pose"]["C.y"] == pytest.approx(1 - length, abs=1e-12) and e["units"]["C.y"] == "m"
    assert e["eigenvalues"] == [pytest.approx(400, rel=1e-6)]
    assert e["residual"] < 1e-9 and e["iterations"] >= 1
    assert e["warnings"] == []


# A parallelogram whose crank pin a spring pulls onto the frame's line: at rest at the change point.
PARALLELOGRAM_PULLED_FLAT = """units: {length: m, angle: deg}
points: {O1: [0, 0], O2: [0.3, 0], A1: [0.05, 0.0866025403784], A2: [0.35, 0.0866025403784], S: [0.1, 0]}
ground: [O1, O2, S]
bodies:
  crank1: {points: [O1, A1], mass: 0.4, inertia: 2e-4}
  crank2: {points: [O2, A2], mass: 0.4, inertia: 2e-4}
  coupler: {points: [A1, A2], mass: 1.5, inertia: 0.01}
springs:
  - {between: [S, A1], stiffness: 100, free_length: 0}
drivers:
  - {angle: crank1, free: true}
"""


def test_an_equilibrium_at_a_change_point_is_said():
    e = nbar.loads(PARALLELOGRAM_PULLED_FLAT, "flat.yaml").equilibrium()
    assert e["free_drivers"]["crank1"] == pytest.approx(0, abs=1e-8)
    [(code, step, message)] = e["warnings"]
    assert code == "equilibrium_at_toggle" and "change point" in message


def test_a_damped_run_settles_at_the_equilibrium_and_the_model_sets_the_run():
    model = nbar.loads(BLOCK + "simulation: {to: 5, dt: 0.5, rtol: 1e-10}\n", "block.yaml")
    r = model.simulate()  # every setting from the model's `simulation:`
    assert list(r["t"]) == [0.5 * i for i in range(11)]
    assert r["block"][-1] == pytest.approx(model.equilibrium()["free_drivers"]["block"], abs=1e-6)
    assert model.simulate(to=1)["t"][-1] == 1  # a keyword overrides the model
    stopped = nbar.loads(BLOCK + "simulation: {to: 5, stop_when: 'C.y > 0.6'}\n").simulate()  # rising to 0.66
    assert stopped.events[0]["kind"] == "stop_when" and stopped["C.y"][-1] == pytest.approx(0.6, abs=1e-9)
    with pytest.raises(nbar.BadInputError, match="to"):
        nbar.loads(BLOCK).simulate()  # no time anywhere
    with pytest.raises(nbar.ModelError) as caught:
        nbar.loads(BLOCK + "simulation: {to: 1, stop_when: 'C.z < 0'}\n", "block.yaml").simulate()
    assert caught.value.line == 13 and "names no column 'C.z'" in str(caught.value)


def test_no_equilibrium_is_an_error_at_the_driver():
    crank = nbar.loads("""points: {O: [0, 0], A: [10, 0]}
ground: [O]
bodies:
  crank: {points: [O, A], mass: 1, inertia: 1e-4}
torques:
  - {body: crank, torque: 2}
drivers:
  - {angle: crank, free: true}
""", "crank.yaml")
    with pytest.raises(nbar.ModelError, match="there is no equilibrium") as caught:
        crank.equilibrium()
    assert caught.value.line == 8


def test_initial_speeds_the_constraints_do_not_allow_are_projected_and_said():
    """A slider-crank started at its dead centre (`from: 0.4`: crank and rod in line) with its
    piston free: the piston's speed must be zero there, so an initial speed of 0.5 m/s cannot hold
    (as InitialSpeeds.ThoseTheConstraintsDoNotAllowAreProjectedAndSaid); the run starts at rest,
    with a warning giving the correction."""
    model = nbar.loads("""units: {length: m, angle: deg}
points: {O: [0, 0], X: [1, 0], A: [0.06, 0.08], C: [0.3828427124746190, 0]}
ground: [O, X]
gravity: [0, -9.81]
bodies:
  crank: {points: [O, A], mass: 0.4, inertia: 2e-4, cg: [0.03, 0.04]}
  rod: {points: [A, C], mass: 0.6, inertia: 5e-3, cg: [0.2, 0.04]}
  piston: {points: [C], mass: 1}
sliders:
  - {body: piston, point: C, along: [O, X]}
lengths: {rod: 0.3}
drivers:
  - {slide: piston, from: 0.4, free: true, initial_speed: 0.5}
""")
    r = model.simulate(to=0.01, dt=0.01, columns="t,C.vx,crank.omega")
    assert r["C.vx"][0] == pytest.approx(0, abs=1e-9) and r["crank.omega"][0] == pytest.approx(0, abs=1e-6)
    messages = [w[2] for w in r.warnings]
    assert len(messages) == 1 and "a correction of 0.5 m/s" in messages[0], messages


def test_viscous_friction_dissipates_what_the_balance_says():
    model = nbar.loads("""units: {length: m, angle: rad}
points: {O: [0, 0], A: [0.5, 0]}
ground: [O]
gravity: [0, -9.81]
bodies:
  bar: {points: [O, A], mass: 2, inertia: 0.04, cg: [0.25, 0]}
friction:
  - {joint: O, viscous: 0.3}
drivers:
  - {angle: bar, free: true}
""")
    r = model.simulate(to=3, dt=0.1, rtol=1e-10)
    assert r["energy.dissipated"][-1] > 0.5
    assert np.max(np.abs(r["energy.balance"])) < 1e-8 * r["energy.dissipated"][-1]
    assert math.isclose(r["energy.dissipated"][0], 0.0, abs_tol=1e-15)
