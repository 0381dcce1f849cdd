#!/usr/bin/python3
"""Issue 14's kinematics ratios over several rounds: each round runs kinematics_bench's 'Over'
benchmarks once (every one measures the engine and its reference interleaved, in one run), and
with --baseline an older build of the program right after, so that both see the machine alike.
Prints, per benchmark and program, the minimum, median and maximum of the ratio and of the
engine's time. On a shared machine the host's other load comes and goes; the spread shows it.

  /usr/bin/python3 bench/kinematics_rounds.py [--bench build/bench/kinematics_bench]
      [--baseline OLD/kinematics_bench] [--rounds 10] [--min-time 0.2]
"""

import argparse
import re
import statistics
import subprocess
import sys


def run(binary, min_time):
    out = subprocess.run([binary, "--benchmark_filter=Over", f"--benchmark_min_time={min_time}"],
                         capture_output=True, text=True, check=True).stdout
    rows = {}
    for line in out.splitlines():
        if not line.startswith("BM_"):
            continue
        counters = dict((k, float(v)) for k, v in re.findall(r"(\w+)=([0-9.eE+-]+)", line))
        rows[line.split()[0]] = counters
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bench", default="build/bench/kinematics_bench")
    parser.add_argument("--baseline")
    parser.add_argument("--rounds", type=int, default=10)
    parser.add_argument("--min-time", type=float, default=0.2)
    args = parser.parse_args()
    programs = [("now", args.bench)] + ([("baseline", args.baseline)] if args.baseline else [])
    seen = {}
    for r in range(args.rounds):
        for tag, binary in programs:
            for name, counters in run(binary, args.min_time).items():
                seen.setdefault((name, tag), []).append(counters)
        print(f"round {r + 1} of {args.rounds}", file=sys.stderr)
    for (name, tag), rounds in sorted(seen.items()):
        ratio = sorted(c["ratio"] for c in rounds)
        engine_key = next(k for k in ("engine_step_us", "straight_step_us", "per_loop_step_us") if k in rounds[0])
        engine = sorted(c[engine_key] for c in rounds)
        print(f"{name:36s} {tag:8s} ratio min {ratio[0]:.2f} median {statistics.median(ratio):.2f} "
              f"max {ratio[-1]:.2f}; {engine_key} median {statistics.median(engine):.3f} min {engine[0]:.3f}")


if __name__ == "__main__":
    main()
