"""`nbar simulate` against independent solutions (issue 38).

Each mechanism is written here as an nbar model with exact coordinates, simulated by the CLI, and
compared with its equations of motion derived here by hand in joint angles (Lagrange's equation in
one coordinate for the four-bar and the slider-crank, the closed-form equations of the compound
double pendulum), integrated by the classical Runge-Kutta method at a fixed small step written
below, whose own error is checked by halving the step. Nothing is shared with nbar but the model.

Usage: simulate_reference.py NBAR
"""

import csv
import io
import math
import os
import subprocess
import sys
import tempfile

NBAR = sys.argv[1] if len(sys.argv) > 1 else "nbar"
G = 9.81
failures = []


def check(name, value, limit):
    ok = value <= limit
    print(f"{'ok  ' if ok else 'FAIL'} {name}: {value:.3e} (limit {limit:.0e})")
    if not ok:
        failures.append(name)


def simulate(model_text, *args):
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "model.yaml")
        with open(path, "w") as f:
            f.write(model_text)
        run = subprocess.run([NBAR, "simulate", path, *args], capture_output=True, text=True)
    if run.returncode != 0:
        raise SystemExit(f"nbar simulate failed ({run.returncode}): {run.stderr}")
    rows = list(csv.DictReader(io.StringIO(run.stdout)))
    return [{k: float(v) for k, v in row.items()} for row in rows]


def rk4(derivative, state, h, steps):
    """Classical fourth-order Runge-Kutta, `steps` steps of size h."""
    for _ in range(steps):
        k1 = derivative(state)
        k2 = derivative([s + 0.5 * h * k for s, k in zip(state, k1)])
        k3 = derivative([s + 0.5 * h * k for s, k in zip(state, k2)])
        k4 = derivative([s + h * k for s, k in zip(state, k3)])
        state = [s + h / 6 * (a + 2 * b + 2 * c + d) for s, a, b, c, d in zip(state, k1, k2, k3, k4)]
    return state


def trajectory(derivative, state, output_step, outputs, substeps):
    """The state at every output time, `substeps` RK4 steps between outputs."""
    out = [state]
    for _ in range(outputs):
        state = rk4(derivative, state, output_step / substeps, substeps)
        out.append(state)
    return out


def converged_trajectory(derivative, state, output_step, outputs, substeps, what):
    """The trajectory at `substeps`, and its error estimated against half as many (RK4: error/15)."""
    fine = trajectory(derivative, state, output_step, outputs, substeps)
    coarse = trajectory(derivative, state, output_step, outputs, substeps // 2)
    error = max(abs(a - b) for f, c in zip(fine, coarse) for a, b in zip(f, c)) / 15
    check(f"{what}: reference's own error (RK4, step halved)", error, 1e-10)
    return fine


def rot(v, a, b):
    """a v + b v_perp: a body-fixed point in terms of the body's direction v."""
    return (a * v[0] - b * v[1], a * v[1] + b * v[0])


def solve2(a11, a12, a21, a22, b1, b2):
    det = a11 * a22 - a12 * a21
    return ((b1 * a22 - a12 * b2) / det, (a11 * b2 - a21 * b1) / det)


# ------------------------------------------------------------------------------ four-bar

FOURBAR = dict(a=0.10, b=0.25, c=0.20, d=0.22, theta0=math.radians(60))
FOURBAR_MASS = [  # mass, inertia about the cg, cg as (along, across) fractions of the body's vector
    (1.2, 0.004, 0.5, 0.1),   # crank: O2 -> A
    (2.0, 0.015, 0.4, 0.15),  # coupler: A -> B
    (1.5, 0.008, 0.55, -0.05),  # rocker: O4 -> B
]


def fourbar_angles(t2):
    """Coupler and rocker angles (open branch) by Norton's closed form."""
    a, b, c, d = (FOURBAR[k] for k in "abcd")
    k1, k2, k3 = d / a, d / c, (a * a - b * b + c * c + d * d) / (2 * a * c)
    A = math.cos(t2) - k1 - k2 * math.cos(t2) + k3
    B = -2 * math.sin(t2)
    C = k1 - (k2 + 1) * math.cos(t2) + k3
    t4 = 2 * math.atan2(-B - math.sqrt(B * B - 4 * A * C), 2 * A)
    k4, k5 = d / b, (c * c - d * d - a * a - b * b) / (2 * a * b)
    D = math.cos(t2) - k1 + k4 * math.cos(t2) + k5
    E = -2 * math.sin(t2)
    F = k1 + (k4 - 1) * math.cos(t2) + k5
    t3 = 2 * math.atan2(-E - math.sqrt(E * E - 4 * D * F), 2 * D)
    return t3, t4


def fourbar_coefficients(t2):
    """Angles and their first and second derivatives with respect to the crank angle, from the
    loop a e2 + b e3 - c e4 - d = 0 differentiated once and twice."""
    a, b, c = FOURBAR["a"], FOURBAR["b"], FOURBAR["c"]
    t3, t4 = fourbar_angles(t2)
    s2, c2, s3, c3, s4, c4 = math.sin(t2), math.cos(t2), math.sin(t3), math.cos(t3), math.sin(t4), math.cos(t4)
    # -b s3 h3 + c s4 h4 = a s2 ; b c3 h3 - c c4 h4 = -a c2
    h3, h4 = solve2(-b * s3, c * s4, b * c3, -c * c4, a * s2, -a * c2)
    # derivative of the above: -b s3 g3 + c s4 g4 = a c2 + b c3 h3^2 - c c4 h4^2 ;
    #                           b c3 g3 - c c4 g4 = a s2 + b s3 h3^2 - c s4 h4^2
    g3, g4 = solve2(-b * s3, c * s4, b * c3, -c * c4, a * c2 + b * c3 * h3 ** 2 - c * c4 * h4 ** 2,
                    a * s2 + b * s3 * h3 ** 2 - c * s4 * h4 ** 2)
    return (t3, h3, g3), (t4, h4, g4)


def body_terms(length, angle, rate, curvature, along, across, base_j=(0, 0), base_k=(0, 0)):
    """dr/dtheta and d2r/dtheta2 of a body-fixed point: base + along v + across v_perp, v of
    length `length` at `angle`, the angle's derivatives `rate` and `curvature` by the coordinate."""
    v1 = (-length * math.sin(angle), length * math.cos(angle))  # dv/dangle
    v2 = (-length * math.cos(angle), -length * math.sin(angle))
    p1, p2 = rot(v1, along, across), rot(v2, along, across)
    j = (base_j[0] + p1[0] * rate, base_j[1] + p1[1] * rate)
    k = (base_k[0] + p2[0] * rate * rate + p1[0] * curvature, base_k[1] + p2[1] * rate * rate + p1[1] * curvature)
    return j, k


def fourbar_acceleration(state):
    t2, w2 = state
    (t3, h3, g3), (t4, h4, g4) = fourbar_coefficients(t2)
    a, b, c = FOURBAR["a"], FOURBAR["b"], FOURBAR["c"]
    (m1, i1, a1, b1), (m2, i2, a2, b2), (m3, i3, a3, b3) = FOURBAR_MASS
    j1, k1 = body_terms(a, t2, 1.0, 0.0, a1, b1)
    ja, ka = body_terms(a, t2, 1.0, 0.0, 1.0, 0.0)  # the crank pin A
    j2, k2 = body_terms(b, t3, h3, g3, a2, b2, ja, ka)
    j3, k3 = body_terms(c, t4, h4, g4, a3, b3)
    mass = inertia_rate = force = 0.0
    for m, i, j, k, h, g in ((m1, i1, j1, k1, 1.0, 0.0), (m2, i2, j2, k2, h3, g3), (m3, i3, j3, k3, h4, g4)):
        mass += m * (j[0] ** 2 + j[1] ** 2) + i * h * h
        inertia_rate += m * (j[0] * k[0] + j[1] * k[1]) + i * h * g
        force += -m * G * j[1]
    return [w2, (force - inertia_rate * w2 * w2) / mass]


def fourbar_model(duration_note=""):
    a, b, c, d, t0 = (FOURBAR[k] for k in ("a", "b", "c", "d", "theta0"))
    t3, t4 = fourbar_angles(t0)
    A = (a * math.cos(t0), a * math.sin(t0))
    B = (d + c * math.cos(t4), c * math.sin(t4))
    O2, O4 = (0.0, 0.0), (d, 0.0)

    def cg(p, q, along, across):
        v = (q[0] - p[0], q[1] - p[1])
        r = rot(v, along, across)
        return f"[{p[0] + r[0]!r}, {p[1] + r[1]!r}]"

    (m1, i1, a1, b1), (m2, i2, a2, b2), (m3, i3, a3, b3) = FOURBAR_MASS
    return f"""name: four-bar released under gravity{duration_note}
units: {{length: m, angle: rad}}
points:
  O2: [0, 0]
  O4: [{d!r}, 0]
  A: [{A[0]!r}, {A[1]!r}]
  B: [{B[0]!r}, {B[1]!r}]
ground: [O2, O4]
gravity: [0, -{G}]
bodies:
  crank: {{points: [O2, A], mass: {m1}, inertia: {i1}, cg: {cg(O2, A, a1, b1)}}}
  coupler: {{points: [A, B], mass: {m2}, inertia: {i2}, cg: {cg(A, B, a2, b2)}}}
  rocker: {{points: [O4, B], mass: {m3}, inertia: {i3}, cg: {cg(O4, B, a3, b3)}}}
drivers:
  - {{angle: crank, free: true}}
"""


def test_fourbar():
    rows = simulate(fourbar_model(), "--to", "3", "--dt", "0.01", "--rtol", "1e-12")
    ref = converged_trajectory(fourbar_acceleration, [FOURBAR["theta0"], 0.0], 0.01, 300, 100, "four-bar")
    angle = max(abs(r["crank.angle"] - s[0]) for r, s in zip(rows, ref))
    speed = max(abs(r["crank.omega"] - s[1]) for r, s in zip(rows, ref))
    check("four-bar under gravity, crank angle over 3 s (rad)", angle, 1e-8)
    check("four-bar under gravity, crank speed over 3 s (rad/s)", speed, 1e-8)
    swing = max(r["crank.angle"] for r in rows) - min(r["crank.angle"] for r in rows)
    check("four-bar: the crank really swings (1/swing, rad^-1)", 1 / swing, 2.0)
    # Its rocker from the closed form at nbar's own crank angles: the positions are consistent.
    rocker = max(abs(math.remainder(r["rocker.angle"] - fourbar_angles(r["crank.angle"])[1], 2 * math.pi)) for r in rows)
    check("four-bar: rocker angle against the closed form at the same crank angle (rad)", rocker, 1e-10)


def test_energy():
    rows = simulate(fourbar_model(" (energy)"), "--to", "10", "--dt", "0.05", "--rtol", "1e-12")
    scale = max(r["energy.kinetic"] for r in rows)
    drift = max(abs(r["energy.balance"]) for r in rows) / scale
    check("four-bar, conservative: energy balance over 10 s, relative to the largest kinetic energy", drift, 1e-9)
    total = [r["energy.kinetic"] + r["energy.potential"] for r in rows]
    check("four-bar, conservative: kinetic + potential constant (relative)",
          (max(total) - min(total)) / scale, 1e-9)


# ------------------------------------------------------------------------------ slider-crank

SLIDER = dict(r=0.05, l=0.18, theta0=math.radians(30), omega0=5.0, torque=0.05)  # a horizontal machine: no gravity
SLIDER_MASS = [(0.5, 2e-4, 0.5, 0.0), (0.8, 2.5e-3, 0.35, 0.05)]  # crank, rod as above
PISTON_MASS = 0.6


def slider_acceleration(state):
    t, w = state
    r, l = SLIDER["r"], SLIDER["l"]
    phi = math.asin(-r * math.sin(t) / l)
    h = -r * math.cos(t) / (l * math.cos(phi))
    g = (r * math.sin(t) + l * math.sin(phi) * h * h) / (l * math.cos(phi))
    (m1, i1, a1, b1), (m2, i2, a2, b2) = SLIDER_MASS
    j1, k1 = body_terms(r, t, 1.0, 0.0, a1, b1)
    ja, ka = body_terms(r, t, 1.0, 0.0, 1.0, 0.0)
    j2, k2 = body_terms(l, phi, h, g, a2, b2, ja, ka)
    jc, kc = body_terms(l, phi, h, g, 1.0, 0.0, ja, ka)  # the piston's pin C
    mass = inertia_rate = 0.0
    force = SLIDER["torque"]
    for m, i, j, k, hh, gg in ((m1, i1, j1, k1, 1.0, 0.0), (m2, i2, j2, k2, h, g), (PISTON_MASS, 0.0, jc, kc, 0, 0)):
        mass += m * (j[0] ** 2 + j[1] ** 2) + i * hh * hh
        inertia_rate += m * (j[0] * k[0] + j[1] * k[1]) + i * hh * gg
    return [w, (force - inertia_rate * w * w) / mass]


def slider_model():
    r, l, t0 = SLIDER["r"], SLIDER["l"], SLIDER["theta0"]
    phi = math.asin(-r * math.sin(t0) / l)
    A = (r * math.cos(t0), r * math.sin(t0))
    C = (A[0] + l * math.cos(phi), 0.0)

    def cg(p, q, along, across):
        v = (q[0] - p[0], q[1] - p[1])
        w = rot(v, along, across)
        return f"[{p[0] + w[0]!r}, {p[1] + w[1]!r}]"

    (m1, i1, a1, b1), (m2, i2, a2, b2) = SLIDER_MASS
    return f"""name: slider-crank under a constant torque
units: {{length: m, angle: deg}}
points:
  O: [0, 0]
  X: [1, 0]
  A: [{A[0]!r}, {A[1]!r}]
  C: [{C[0]!r}, 0]
ground: [O, X]
bodies:
  crank: {{points: [O, A], mass: {m1}, inertia: {i1}, cg: {cg((0, 0), A, a1, b1)}}}
  rod: {{points: [A, C], mass: {m2}, inertia: {i2}, cg: {cg(A, C, a2, b2)}}}
  piston: {{points: [C], mass: {PISTON_MASS}}}
sliders:
  - {{body: piston, point: C, along: [O, X]}}
torques:
  - {{body: crank, torque: {SLIDER["torque"]}}}
drivers:
  - {{angle: crank, free: true, initial_speed: {SLIDER["omega0"]} rad/s}}
"""


def test_slider_crank():
    # The crank reaches 55 rad/s: 1e-8 rad/s is 2e-10 of it, hence the tighter tolerance.
    rows = simulate(slider_model(), "--to", "3", "--dt", "0.01", "--rtol", "1e-13")
    ref = converged_trajectory(slider_acceleration, [SLIDER["theta0"], SLIDER["omega0"]], 0.01, 300, 800,
                               "slider-crank")
    angle = max(abs(math.radians(r["crank.angle"]) - s[0]) for r, s in zip(rows, ref))
    speed = max(abs(math.radians(r["crank.omega"]) - s[1]) for r, s in zip(rows, ref))
    turns = (ref[-1][0] - ref[0][0]) / (2 * math.pi)
    check("slider-crank under a constant torque, crank angle over 3 s (rad)", angle, 1e-8)
    check("slider-crank under a constant torque, crank speed over 3 s (rad/s)", speed, 1e-8)
    check("slider-crank: the crank turns several times (1/turns)", 1 / turns, 0.5)
    # The work of the torque is in the balance: it stays at the integration error.
    work = rows[-1]["energy.work"]
    check("slider-crank: work of the torque = torque x angle turned (relative)",
          abs(work - SLIDER["torque"] * (ref[-1][0] - ref[0][0])) / work, 1e-9)
    check("slider-crank: energy balance (relative to the work done)",
          max(abs(r["energy.balance"]) for r in rows) / work, 1e-9)


# ------------------------------------------------------------------------------ double pendulum

PENDULUM = dict(L1=0.3, L2=0.25, m1=1.0, m2=0.7, I1=0.006, I2=0.004, c1=0.14, c2=0.12,
                theta1=math.radians(-30), theta2=math.radians(10), omega1=1.0, omega2=-2.0)


def pendulum_acceleration(state):
    t1, t2, w1, w2 = state
    p = PENDULUM
    A = p["m1"] * p["c1"] ** 2 + p["I1"] + p["m2"] * p["L1"] ** 2
    B = p["m2"] * p["L1"] * p["c2"]
    C = p["m2"] * p["c2"] ** 2 + p["I2"]
    d = t1 - t2
    rhs1 = -B * math.sin(d) * w2 * w2 - (p["m1"] * p["c1"] + p["m2"] * p["L1"]) * G * math.cos(t1)
    rhs2 = B * math.sin(d) * w1 * w1 - p["m2"] * p["c2"] * G * math.cos(t2)
    a1, a2 = solve2(A, B * math.cos(d), B * math.cos(d), C, rhs1, rhs2)
    return [w1, w2, a1, a2]


def pendulum_model():
    p = PENDULUM
    A = (p["L1"] * math.cos(p["theta1"]), p["L1"] * math.sin(p["theta1"]))
    B = (A[0] + p["L2"] * math.cos(p["theta2"]), A[1] + p["L2"] * math.sin(p["theta2"]))
    g1 = (p["c1"] * math.cos(p["theta1"]), p["c1"] * math.sin(p["theta1"]))
    g2 = (A[0] + p["c2"] * math.cos(p["theta2"]), A[1] + p["c2"] * math.sin(p["theta2"]))
    return f"""name: double pendulum
units: {{length: m, angle: rad}}
points:
  O: [0, 0]
  A: [{A[0]!r}, {A[1]!r}]
  B: [{B[0]!r}, {B[1]!r}]
ground: [O]
gravity: [0, -{G}]
bodies:
  upper: {{points: [O, A], mass: {p["m1"]}, inertia: {p["I1"]}, cg: [{g1[0]!r}, {g1[1]!r}]}}
  lower: {{points: [A, B], mass: {p["m2"]}, inertia: {p["I2"]}, cg: [{g2[0]!r}, {g2[1]!r}]}}
drivers:
  - {{angle: upper, free: true, initial_speed: {p["omega1"]}}}
  - {{angle: lower, free: true, initial_speed: {p["omega2"]}}}
"""


def test_double_pendulum():
    p = PENDULUM
    rows = simulate(pendulum_model(), "--to", "2", "--dt", "0.01", "--rtol", "1e-12")
    ref = converged_trajectory(pendulum_acceleration, [p["theta1"], p["theta2"], p["omega1"], p["omega2"]], 0.01,
                               200, 100, "double pendulum")
    angles = max(max(abs(r["upper.angle"] - s[0]), abs(r["lower.angle"] - s[1])) for r, s in zip(rows, ref))
    speeds = max(max(abs(r["upper.omega"] - s[2]), abs(r["lower.omega"] - s[3])) for r, s in zip(rows, ref))
    check("double pendulum, both angles over 2 s (rad)", angles, 1e-8)
    check("double pendulum, both angular speeds over 2 s (rad/s)", speeds, 1e-8)


if __name__ == "__main__":
    test_fourbar()
    test_energy()
    test_slider_crank()
    test_double_pendulum()
    if failures:
        print(f"{len(failures)} check(s) failed: " + "; ".join(failures))
        sys.exit(1)
    print("all checks passed")
