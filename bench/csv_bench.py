#!/usr/bin/python3
"""`nbar solve` of a four-bar, 100 001 rows to a CSV file, against Norton's closed form printing
the same 43 columns with printf (bench/csv_closed_form.cpp), in one run.

  /usr/bin/python3 bench/csv_bench.py [--nbar build/apps/nbar/nbar]
      [--closed-form build/bench/csv_closed_form] [--steps 100001] [--repetitions 7]

The two programs run alternately, so that load from other processes falls on both alike; each
run's CPU time (user + system, of the child) is measured, and the medians and the median of the
per-pair ratios nbar / closed form are printed. Wall times are printed too (they include the
wait for a shared machine's cores).

Measured 2026-11-25 (5 repetitions, medians, 2-core machine under load): nbar 0.42 s CPU
against the printf closed form's 0.93 s, ratio 0.45 (before streaming and std::to_chars, the same
run with the old program: nbar 0.72 s against 0.94 s, ratio 0.77). Peak memory of the whole
command (/usr/bin/time -v): 13.7 MB at 100 001 and at 1 000 001 steps (before: 75 MB and 638 MB).
"""
import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def timed(command):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return cpu, wall


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--nbar", default=os.path.join(ROOT, "build/apps/nbar/nbar"))
    parser.add_argument("--closed-form", default=os.path.join(ROOT, "build/bench/csv_closed_form"))
    parser.add_argument("--model", default=os.path.join(ROOT, "examples/fourbar-crank-rocker.yaml"))
    parser.add_argument("--steps", type=int, default=100001)
    parser.add_argument("--repetitions", type=int, default=7)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        nbar_csv, closed_csv = os.path.join(tmp, "nbar.csv"), os.path.join(tmp, "closed.csv")
        nbar = [args.nbar, "solve", args.model, "--steps", str(args.steps), "-o", nbar_csv]
        closed = [args.closed_form, str(args.steps), closed_csv]
        timed(nbar), timed(closed)  # warm the caches
        runs = []
        for _ in range(args.repetitions):
            runs.append((timed(nbar), timed(closed)))
        with open(nbar_csv) as a, open(closed_csv) as b:
            lines_a, lines_b = sum(1 for _ in a), sum(1 for _ in b)
            a.seek(0), b.seek(0)
            columns_a, columns_b = a.readline().count(","), b.readline().count(",")
        if lines_a != lines_b or columns_a != columns_b:
            sys.exit(f"csv_bench: the files differ in shape: {lines_a} x {columns_a + 1} against {lines_b} x {columns_b + 1}")
    cpu_nbar = statistics.median(r[0][0] for r in runs)
    cpu_closed = statistics.median(r[1][0] for r in runs)
    wall_nbar = statistics.median(r[0][1] for r in runs)
    wall_closed = statistics.median(r[1][1] for r in runs)
    ratio = statistics.median(r[0][0] / r[1][0] for r in runs)
    print(f"{lines_a - 1} rows x {columns_a + 1} columns, {args.repetitions} repetitions, medians")
    print(f"nbar solve     cpu {cpu_nbar:.3f} s   wall {wall_nbar:.3f} s")
    print(f"closed form    cpu {cpu_closed:.3f} s   wall {wall_closed:.3f} s")
    print(f"ratio nbar / closed form (cpu, per pair): {ratio:.2f}")


if __name__ == "__main__":
    main()
