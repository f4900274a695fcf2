#!/usr/bin/python3
"""Rendered SLAM sequences with exact ground truth, for scripts/slam_benchmark.py (docs/slam.md).

A room of procedurally textured faces with boxes that occlude, seen by a stereo camera that
translates through it; each family changes one thing (docs/slam.md lists them). Every family is
written in EuRoC and TUM layouts with ORB-SLAM3 settings (scripts/slamseq/layouts.py).
Deterministic: the same seed and arguments give the same files.

Usage: make_sequences.py OUT [--seed N] [--seconds S] [--fps F] [--width W --height H]
                             [--families a,b,...] [--depth] [--jobs N]
"""
import argparse
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from slamseq.families import FAMILIES  # noqa: E402
from slamseq.render import Camera  # noqa: E402
from slamseq.sequence import make_sequences  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("out")
    parser.add_argument("--seed", type=int, default=17)
    parser.add_argument("--seconds", type=float, default=15.0)
    parser.add_argument("--fps", type=int, default=10)
    parser.add_argument("--width", type=int, default=640)
    parser.add_argument("--height", type=int, default=480)
    parser.add_argument("--families", default=",".join(f.name for f in FAMILIES))
    parser.add_argument("--depth", action="store_true", help="also write cam0 depth (TUM depth/ layout)")
    parser.add_argument("--jobs", type=int, default=1, help="processes rendering frames (the output is the same)")
    args = parser.parse_args()
    names = [n for n in args.families.split(",") if n]
    known = {f.name for f in FAMILIES}
    if unknown := [n for n in names if n not in known]:
        parser.error(f"unknown families {unknown}; known: {sorted(known)}")
    if args.seconds <= 0 or args.fps <= 0 or args.width < 64 or args.height < 48:
        parser.error("seconds and fps must be positive, images at least 64 x 48")
    start = time.time()

    def progress(done, frames):
        print(f"{done}/{frames} frames ({time.time() - start:.0f} s)", flush=True)

    folders = make_sequences(args.out, names, args.seed, args.seconds, args.fps, Camera.default(args.width, args.height), args.depth,
                             max(1, args.jobs), progress)
    print("\n".join(folders))


if __name__ == "__main__":
    main()
