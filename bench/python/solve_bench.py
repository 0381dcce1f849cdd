"""Python's cost over C++: a 100 001-step four-bar solve into numpy arrays (Model.solve) against
the same work timed inside C++ in the same run — the pipeline's sweep and its column table —
and against the sweep alone. Target: Model.solve <= 1.2x the C++ work.

    PYTHONPATH=build/python /usr/bin/python3 bench/python/solve_bench.py [--repeat 7]
"""

import argparse
import pathlib
import time

import nbar
from nbar import _nbar

ROOT = pathlib.Path(__file__).resolve().parents[2]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=100_001)
    parser.add_argument("--repeat", type=int, default=7)
    args = parser.parse_args()
    m = nbar.load(ROOT / "examples" / "fourbar-crank-rocker.yaml")
    sweep, cpp, python = [], [], []
    for _ in range(args.repeat):  # interleaved, so that the machine's state is shared alike
        s, c = _nbar._time_in_cpp(m._c, args.steps, 2)
        sweep.append(s)
        cpp.append(c)
        start = time.perf_counter()
        r = m.solve(steps=args.steps, order=2)
        python.append(time.perf_counter() - start)
        del r  # freed before the next run, as the C++ run frees its own
    print(f"four-bar, {args.steps} steps, order 2, {len(m.columns())} columns; best of {args.repeat}")
    print(f"C++ sweep alone:                   {min(sweep) * 1e3:8.1f} ms")
    print(f"C++ sweep and column table:        {min(cpp) * 1e3:8.1f} ms")
    print(f"Python Model.solve, numpy arrays:  {min(python) * 1e3:8.1f} ms")
    print(f"ratio to the C++ work: {min(python) / min(cpp):.2f} (target <= 1.2); "
          f"to the sweep alone: {min(python) / min(sweep):.2f}")


if __name__ == "__main__":
    main()
