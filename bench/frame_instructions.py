#!/usr/bin/env python3
"""Instructions per frame of the extractor over a sequence, per source of F, under callgrind:
the figures of docs/design.md §10 ("F carried through a video"): a carried sweep spread over
the frames must leave every frame close to a fixed F's cost.

Runs build/bench/aief_frame_instructions under valgrind --tool=callgrind once per threshold
source (each frame's extract() dumped on its own) and prints, per source, the median, the 90th
percentile and the largest instruction count per frame, and the F each frame used.

usage: bench/frame_instructions.py [--build build] [--thresholds 4,auto,carried] FRAME...
"""
import argparse
import glob
import os
import re
import statistics
import subprocess
import sys
import tempfile


def frame_counts(binary, threshold, frames):
    """Instructions of each frame's extract() and the F each frame requested."""
    with tempfile.TemporaryDirectory() as folder:
        out = os.path.join(folder, "callgrind.out")
        run = subprocess.run(["valgrind", "--tool=callgrind", "--collect-atstart=no",
                              f"--callgrind-out-file={out}", binary, threshold, *frames],
                             capture_output=True, text=True)
        if run.returncode != 0:
            sys.exit(f"frame_instructions: {binary} failed:\n{run.stderr[-2000:]}")
        counts = []
        for dump in sorted(glob.glob(out + ".*"), key=lambda p: int(p.rsplit(".", 1)[1])):
            with open(dump) as f:
                totals = [int(m.group(1)) for m in re.finditer(r"^totals:\s+(\d+)", f.read(), re.M)]
            counts.append(totals[0] if totals else 0)
        thresholds = [float(m.group(1)) for m in re.finditer(r" F=(\S+)", run.stdout)]
    return counts, thresholds


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default="build")
    parser.add_argument("--thresholds", default="4,auto,carried")
    parser.add_argument("frames", nargs="+")
    args = parser.parse_args()
    binary = os.path.join(args.build, "bench", "aief_frame_instructions")
    rows = {}
    for threshold in args.thresholds.split(","):
        rows[threshold] = frame_counts(binary, threshold, args.frames)
    fixed = statistics.median(next(iter(rows.values()))[0])
    print(f"{len(args.frames)} frames; instructions per frame (M), and relative to the first "
          f"source's median")
    print(f"{'F':>8} {'median':>8} {'p90':>8} {'max':>8} {'max/ref':>8}  F per frame")
    for threshold, (counts, used) in rows.items():
        ordered = sorted(counts)
        p90 = ordered[min(len(ordered) - 1, int(0.9 * len(ordered)))]
        print(f"{threshold:>8} {statistics.median(counts) / 1e6:8.1f} {p90 / 1e6:8.1f} "
              f"{max(counts) / 1e6:8.1f} {max(counts) / fixed:8.2f}  "
              + " ".join(f"{f:g}" for f in used))
        print(f"{'':>8} per frame (M): " + " ".join(f"{c / 1e6:.0f}" for c in counts))


if __name__ == "__main__":
    main()
