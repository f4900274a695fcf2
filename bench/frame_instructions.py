#!/usr/bin/env python3
"""The video benchmark: the cost of each frame of a sequence, per threshold policy and
distribution, as median, p95, p99 and max, and each over the median (docs/speed.md, "The worst
frame"; docs/design.md §10, "F carried through a video").

Runs build/bench/aief_frame_instructions (one extractor, 1 thread, frames decoded before the
first extract()) once per configuration:
  instructions  under valgrind --tool=callgrind, each frame's extract() dumped on its own
                (repeatable on a loaded machine; valgrind hides AVX-512, so AVX2 kernels);
  --time R      natively, R runs with the configurations interleaved run by run, each frame's
                wall-clock time the median of its R runs (best-set kernels unless --options
                kernels=...).

usage: bench/frame_instructions.py [--build build] [--thresholds 4,auto,carried]
           [--distributions proportional,quadtree] [--options K=V,...] [--time R] FRAME...
"""
import argparse
import glob
import os
import re
import statistics
import subprocess
import sys
import tempfile


def run_binary(command):
    run = subprocess.run(command, capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit(f"frame_instructions: {' '.join(command[:4])} ... failed:\n{run.stderr[-2000:]}")
    return run.stdout


def frame_instructions(binary, arguments, frames):
    """Instructions of each frame's extract(), and the F each frame requested."""
    with tempfile.TemporaryDirectory() as folder:
        out = os.path.join(folder, "callgrind.out")
        stdout = run_binary(["valgrind", "--tool=callgrind", "--collect-atstart=no",
                             f"--callgrind-out-file={out}", binary, *arguments, *frames])
        counts = []
        for dump in sorted(glob.glob(out + ".*"), key=lambda p: int(p.rsplit(".", 1)[1])):
            with open(dump) as f:
                totals = [int(m.group(1)) for m in re.finditer(r"^totals:\s+(\d+)", f.read(), re.M)]
            counts.append(totals[0] if totals else 0)
    thresholds = [float(m.group(1)) for m in re.finditer(r" F=(\S+)", stdout)]
    return counts, thresholds


def frame_microseconds(binary, arguments, frames):
    stdout = run_binary([binary, *arguments, *frames])
    return [float(m.group(1)) for m in re.finditer(r" us=(\S+)", stdout)]


def percentile(ordered, p):
    """The nearest-rank p-th percentile of a sorted list."""
    return ordered[min(len(ordered) - 1, max(0, -(-len(ordered) * p // 100) - 1))]


def summary(values):
    ordered = sorted(values)
    median = statistics.median(ordered)
    return median, percentile(ordered, 95), percentile(ordered, 99), ordered[-1]


def print_table(title, unit, scale, rows):
    print(f"\n{title}")
    print(f"| threshold | distribution | median {unit} | p95 | p99 | max | p99 / median | max / median |")
    print("|---|---|---|---|---|---|---|---|")
    for (threshold, distribution), values in rows.items():
        median, p95, p99, top = summary(values)
        print(f"| {threshold} | {distribution} | {median / scale:.2f} | {p95 / scale:.2f} | "
              f"{p99 / scale:.2f} | {top / scale:.2f} | {p99 / median:.2f} | {top / median:.2f} |")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default="build")
    parser.add_argument("--thresholds", default="4,auto,carried",
                        help="threshold policies; none: the mode's (orbslam2 has no F)")
    parser.add_argument("--distributions", default="proportional,quadtree")
    parser.add_argument("--options", default="", help="more options, KEY=VALUE,... (record keys)")
    parser.add_argument("--time", type=int, default=0, metavar="R",
                        help="wall-clock times over R interleaved runs instead of instructions")
    parser.add_argument("--per-frame", action="store_true", help="also print every frame's figure")
    parser.add_argument("frames", nargs="+")
    args = parser.parse_args()
    binary = os.path.join(args.build, "bench", "aief_frame_instructions")
    extra = [o for o in args.options.split(",") if o]
    configurations = [(t, d) for t in args.thresholds.split(",") for d in args.distributions.split(",")]

    def arguments(threshold, distribution):
        return [f"distribution={distribution}", *extra, threshold]

    print(f"{len(args.frames)} frames ({args.frames[0]} ...), options {extra or 'defaults'}, 1 thread")
    if args.time:
        runs = {c: [] for c in configurations}
        for _ in range(args.time):
            for c in configurations:
                runs[c].append(frame_microseconds(binary, arguments(*c), args.frames))
        rows = {c: [statistics.median(frame) for frame in zip(*runs[c])] for c in configurations}
        print_table(f"wall-clock ms per frame, each frame the median of {args.time} interleaved runs",
                    "ms", 1000.0, rows)
    else:
        rows, used = {}, {}
        for c in configurations:
            rows[c], used[c] = frame_instructions(binary, arguments(*c), args.frames)
        print_table("instructions per frame (M, callgrind)", "M", 1e6, rows)
        for c in configurations:
            changes = [(i, f) for i, f in enumerate(used[c]) if i == 0 or f != used[c][i - 1]]
            print(f"{c[0]:>8} {c[1]:>12}: F by frame " + ", ".join(f"{f:g} from {i}" for i, f in changes))
    if args.per_frame:
        for c, values in rows.items():
            print(f"{c[0]} {c[1]}: " + " ".join(f"{v / (1e6 if not args.time else 1e3):.1f}" for v in values))


if __name__ == "__main__":
    main()
