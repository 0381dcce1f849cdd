"""Reference solutions of six-bars 0.3 deg from a limit, to 60 digits (issue 37, item 3).

For each case the script reads an example model (examples/*.yaml: points, ground, bodies and one
angle driver), writes its constraint equations itself in mpmath at 100 digits, follows the drawn
branch from the drawn pose to the limit of the mechanism, locates the limit (where the driven
Jacobian is singular: the equations and its determinant solved together), and solves the pose at
the input angle 0.3 deg inside it (rounded to a double, the value nbar is driven to). The
velocities and accelerations there, for the input turning at 1 rad/s, are the first and second
derivatives of that pose in the input angle, by central differences of poses solved at 100
digits (step 1e-30, so the differences' own error is below 1e-40). Nothing is shared with nbar
but the model files: the equations are the plain definitions (a body's first two points at their
drawn distance, its further points fixed in the frame of the first two, the input body's angle).

  near_limit_reference.py                 writes tests/kinematics/data/near_limit_reference.txt
  near_limit_reference.py --check FILE    recomputes and compares with FILE (exit 1 if they differ)

tests/kinematics/near_limit_test.cpp compares nbar's sweeps with the file.
"""

import math
import os
import sys

import mpmath
import yaml
from mpmath import mp, mpf

mp.dps = 100
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
OUTPUT = os.path.join(ROOT, "tests", "kinematics", "data", "near_limit_reference.txt")
INSIDE = 0.3 * math.pi / 180.0  # how far inside the limit the sample lies, rad
DIGITS = 30  # significant digits written
# (example, direction the input moves towards the limit, a rough value of the limit in degrees
# from `nbar check`, only a starting guess: the limit is located here).
CASES = [
    ("watt-sixbar-limited.yaml", +1, 15.2758),
    ("watt-sixbar-limited.yaml", -1, -15.2758),
    ("stephenson-sixbar-limited.yaml", -1, -35.0038),
    ("stephenson-sixbar-limited.yaml", +1, 99.7151),
]
LENGTH_SCALE = {"mm": 0.001, "m": 1.0}
ANGLE_SCALE = {"deg": math.pi / 180.0, "rad": 1.0}


class Linkage:
    """The constraint equations of a model with one angle driver, in natural coordinates."""

    def __init__(self, path):
        with open(path) as f:
            model = yaml.safe_load(f)
        scale = LENGTH_SCALE[model["units"]["length"]]
        # The doubles nbar reads (its reader multiplies by the unit's scale), then exact.
        self.position = {name: [mpf(scale * float(v)) for v in xy] for name, xy in model["points"].items()}
        self.ground = set(model["ground"])
        self.moving = [name for name in model["points"] if name not in self.ground]
        self.bodies = model["bodies"]
        driver = model["drivers"][0]
        self.input = self.bodies[driver["angle"]]
        self.angle_scale = ANGLE_SCALE[model["units"]["angle"]]
        self.rows = []  # (kind, data)
        for points in self.bodies.values():
            i, j = points[0], points[1]
            pi, pj = self.position[i], self.position[j]
            ux, uy = pj[0] - pi[0], pj[1] - pi[1]
            if not (i in self.ground and j in self.ground):
                self.rows.append(("distance", (i, j, ux * ux + uy * uy)))
            uu = ux * ux + uy * uy
            for k in points[2:]:
                dx, dy = self.position[k][0] - pi[0], self.position[k][1] - pi[1]
                a = (dx * ux + dy * uy) / uu
                b = (-uy * dx + ux * dy) / uu
                self.rows.append(("rigid", (i, j, k, a, b)))

    def drawn(self):
        return [c for name in self.moving for c in self.position[name]]

    def point(self, q, name):
        if name in self.ground:
            return self.position[name]
        at = 2 * self.moving.index(name)
        return [q[at], q[at + 1]]

    def residuals(self, q, angle):
        out = []
        for kind, data in self.rows:
            if kind == "distance":
                i, j, length_squared = data
                ri, rj = self.point(q, i), self.point(q, j)
                out.append((rj[0] - ri[0]) ** 2 + (rj[1] - ri[1]) ** 2 - length_squared)
            else:
                i, j, k, a, b = data
                ri, rj, rk = self.point(q, i), self.point(q, j), self.point(q, k)
                ux, uy = rj[0] - ri[0], rj[1] - ri[1]
                out.append(rk[0] - ri[0] - a * ux + b * uy)
                out.append(rk[1] - ri[1] - a * uy - b * ux)
        ri, rj = self.point(q, self.input[0]), self.point(q, self.input[1])
        out.append((rj[0] - ri[0]) * mpmath.sin(angle) - (rj[1] - ri[1]) * mpmath.cos(angle))
        return out

    def jacobian(self, q, angle):
        """d residuals / d q, by exact differentiation of the (at most quadratic) rows."""
        n = len(q)
        rows = []
        for kind, data in self.rows:
            if kind == "distance":
                i, j, _ = data
                ri, rj = self.point(q, i), self.point(q, j)
                row = [mpf(0)] * n
                self._add(row, j, [2 * (rj[0] - ri[0]), 2 * (rj[1] - ri[1])])
                self._add(row, i, [-2 * (rj[0] - ri[0]), -2 * (rj[1] - ri[1])])
                rows.append(row)
            else:
                i, j, k, a, b = data
                x, y = [mpf(0)] * n, [mpf(0)] * n
                self._add(x, k, [1, 0])
                self._add(x, i, [a - 1, -b])
                self._add(x, j, [-a, b])
                self._add(y, k, [0, 1])
                self._add(y, i, [b, a - 1])
                self._add(y, j, [-b, -a])
                rows += [x, y]
        row = [mpf(0)] * n
        s, c = mpmath.sin(angle), mpmath.cos(angle)
        self._add(row, self.input[1], [s, -c])
        self._add(row, self.input[0], [-s, c])
        rows.append(row)
        return mpmath.matrix(rows)

    def _add(self, row, name, d):
        if name in self.ground:
            return
        at = 2 * self.moving.index(name)
        row[at] += d[0]
        row[at + 1] += d[1]

    def solve(self, q, angle):
        """Newton from q to the pose at `angle`, to the working precision."""
        q = mpmath.matrix(q)
        for _ in range(60):
            phi = mpmath.matrix(self.residuals(q, angle))
            dq = mpmath.lu_solve(self.jacobian(q, angle), -phi)
            q += dq
            if mpmath.norm(dq, mpmath.inf) < mpf(10) ** (-mp.dps + 5):
                return q
        raise SystemExit(f"Newton did not converge at {angle}")

    def follow(self, q, start, end, step):
        """The drawn branch from `start` to `end`, in steps of at most `step` (rad)."""
        count = max(1, int(math.ceil(abs(float(end - start)) / step)))
        with mp.workdps(30):
            for s in range(1, count + 1):
                q = self.solve(q, start + (end - start) * s / count)
        return self.solve(q, end)

    def limit(self, q, angle):
        """The limit near (q, angle): the equations and det(Jacobian) = 0 solved together."""

        def equations(*x):
            qq, a = mpmath.matrix(x[:-1]), x[-1]
            return self.residuals(qq, a) + [mpmath.det(self.jacobian(qq, a))]

        x = mpmath.findroot(equations, list(q) + [angle], tol=mpf(10) ** (-2 * mp.dps + 20))
        return x[len(q)]


def number(x):
    return mpmath.nstr(x, DIGITS, min_fixed=1, max_fixed=0, strip_zeros=False)


def reference(example, direction, guess_deg):
    linkage = Linkage(os.path.join(ROOT, "examples", example))
    drawn = mpf(0)  # the input's angle in the drawn pose: every case's input is drawn along +x
    guess = mpf(guess_deg) * mpmath.pi / 180
    near = guess - direction * mpf("1e-4")
    q = linkage.follow(linkage.drawn(), drawn, near, 0.01)
    limit = linkage.limit(q, near)
    # The sample nbar is driven to: a double, 0.3 deg inside the limit.
    sample = float(limit - direction * mpf(INSIDE))
    theta = mpf(sample)
    q = linkage.follow(q, near, theta, 0.001)
    h = mpf("1e-30")
    q_plus, q_minus = linkage.solve(q, theta + h), linkage.solve(q, theta - h)
    velocity = (q_plus - q_minus) / (2 * h)
    acceleration = (q_plus - 2 * q + q_minus) / (h * h)
    residual = max(abs(r) for r in linkage.residuals(q, theta))
    lines = [f"case {example} {direction:+d}", f"limit {number(limit)}", f"input {sample!r}"]
    lines.append(f"# largest residual of the reference pose: {mpmath.nstr(residual, 3)} m^2")
    for p, name in enumerate(linkage.moving):
        values = [q[2 * p], q[2 * p + 1], velocity[2 * p], velocity[2 * p + 1], acceleration[2 * p],
                  acceleration[2 * p + 1]]
        lines.append(f"point {name} " + " ".join(number(v) for v in values))
    return lines


def main():
    header = [
        "# Six-bars 0.3 deg from a limit of the mechanism, solved to 60 digits in mpmath by",
        "# tests/kinematics/near_limit_reference.py (run it to regenerate; do not edit). Per case:",
        "# the example and the way its input goes to the limit, the limit (input angle, rad), the",
        "# input angle of the sample (rad, a double: 0.3 deg inside the limit), then every moving",
        "# point: x y vx vy ax ay (m, m/s, m/s^2) for the input turning at 1 rad/s, no acceleration.",
    ]
    lines = list(header)
    for case in CASES:
        lines += reference(*case)
    text = "\n".join(lines) + "\n"
    if len(sys.argv) == 3 and sys.argv[1] == "--check":
        with open(sys.argv[2]) as f:
            kept = f.read()
        if not same_numbers(kept, text):
            print("the reference numbers differ from " + sys.argv[2])
            sys.exit(1)
        print("the reference numbers reproduce " + sys.argv[2])
        return
    with open(OUTPUT, "w") as f:
        f.write(text)
    print("wrote " + OUTPUT)


def same_numbers(a, b):
    """Same lines, numbers equal to 1e-25 relative (the digits written are 30)."""
    la, lb = a.splitlines(), b.splitlines()
    if len(la) != len(lb):
        return False
    for x, y in zip(la, lb):
        if x.startswith("#") and y.startswith("#"):
            continue
        wx, wy = x.split(), y.split()
        if len(wx) != len(wy):
            return False
        for u, v in zip(wx, wy):
            if u == v:
                continue
            try:
                fu, fv = mpf(u), mpf(v)
            except ValueError:
                return False
            if abs(fu - fv) > mpf("1e-25") * max(abs(fu), abs(fv)):
                return False
    return True


if __name__ == "__main__":
    main()
