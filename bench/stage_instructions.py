#!/usr/bin/env python3
"""Instructions of one extraction, stage by stage (docs/speed.md, "Stage by stage").

Runs build/bench/aief_frame_instructions under valgrind --tool=callgrind on IMAGE twice and
counts the second extract() (buffers already sized, as in a video), then sums each engine
function's own instructions into the stage it belongs to. Valgrind hides AVX-512, so this is the
AVX2 path (or whatever kernels=... names). Repeatable on a loaded machine, unlike time. With
--branch-sim, valgrind's branch predictor model (the one cachegrind --branch-sim=yes runs) also
counts each stage's mispredicted conditional branches, the time that instructions do not show.

usage: bench/stage_instructions.py [--build build] IMAGE [KEY=VALUE...] [--threshold F|none]
                                   [--branch-sim]
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

# (stage, substrings of the function names that are its work), first match wins: the names of
# std:: algorithms instantiated for a stage carry that stage's function in their template
# arguments (a sort's comparator), so those come before the generic rows.
STAGES = [
    ("pyramid (resize)", ["resize_bilinear", "resize_opencv"]),
    ("detection smoothing", ["binomial5", "smooth_for_detection"]),
    ("integral images", ["integral_image", "IntegralImage"]),
    ("box descriptor", ["box_describe", "BoxOnIntegralBand"]),
    ("entropy: block histograms", ["accumulate_histogram"]),
    ("entropy: sums and logs", ["entropy_bits", "compute_block_entropies", "__log2", "log2"]),
    ("FAST scores", ["fast9_scores_row", "compute_score_rows"]),
    ("local maxima", ["fast9_local_maxima_bits"]),
    ("candidate bookkeeping", ["detect_kept_blocks", "write_block_candidates", "allowed_bits", "blocks_allowed"]),
    ("ORB-SLAM cells (walk)", ["detect_orbslam_cells"]),
    ("pool + distribution + raster sort",
     ["pool_candidates", "distribute_", "Quadtree", "OctreeNode", "select_candidates", "sort_in_raster_order",
      "sort_by_raster_rank", "raster_rank"]),
    ("orientation", ["ic_moments", "ic_angle", "atan2", "KeypointAngles"]),
    ("patch blur", ["gaussian7_rows", "blur_detail", "blur_patch_rows", "RbriefOnBlurredBand"]),
    ("rBRIEF", ["rbrief_describe", "sincos", "__cos", "__sin"]),
    ("frame: F, fallback, output", ["assemble", "keypoint_position", "parabola_peak", "auto_entropy",
                                   "auto_threshold", "FrameAnalysis", "FramePipeline", "ThresholdFallback",
                                   "LevelDescriptions", "level_candidate", "Extractor"]),
    ("libc (memcpy, memset, malloc)", ["memmove", "memcpy", "memset", "malloc", "free", "operator new",
                                       "operator delete", "_int_"]),
]


def stage_of(function):
    for stage, names in STAGES:
        if any(name in function for name in names):
            return stage
    return "other"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", default="build")
    parser.add_argument("--threshold", default="4", help="F, auto, carried or none (the mode's)")
    parser.add_argument("--show-other", action="store_true", help="list the functions left in 'other'")
    parser.add_argument("--branch-sim", action="store_true",
                        help="also count mispredicted conditional branches per stage")
    parser.add_argument("image")
    parser.add_argument("options", nargs="*", help="KEY=VALUE options (record keys)")
    args = parser.parse_args()
    binary = os.path.join(args.build, "bench", "aief_frame_instructions")
    with tempfile.TemporaryDirectory() as folder:
        out = os.path.join(folder, "callgrind.out")
        branch_sim = ["--branch-sim=yes"] if args.branch_sim else []
        run = subprocess.run(["valgrind", "--tool=callgrind", "--collect-atstart=no", *branch_sim,
                              f"--callgrind-out-file={out}", binary, *args.options, args.threshold,
                              args.image, args.image], capture_output=True, text=True)
        if run.returncode != 0:
            sys.exit(f"stage_instructions: {binary} failed:\n{run.stderr[-2000:]}")
        annotated = subprocess.run(["callgrind_annotate", "--threshold=100", "--auto=no", out + ".2"],
                                   check=True, capture_output=True, text=True).stdout
    # One column per event (Ir; with the branch model also Bc Bcm Bi Bim), each "count (share%)"
    # or "." for none, then the function.
    events = re.search(r"^Events shown:\s+(.*)$", annotated, re.M).group(1).split()
    cell = r"(?:([\d,]+)\s+\(\s*[\d.]+%\)|\.)\s+"
    row = re.compile(r"^\s*" + cell * len(events) + r"(.*)$")
    counts_of = lambda m: [int(m.group(k + 1).replace(",", "")) if m.group(k + 1) else 0
                           for k in range(len(events))]
    totals = counts_of(row.match(re.search(r"^.*PROGRAM TOTALS.*$", annotated, re.M).group(0)))
    sums, other = {}, []
    body = annotated.split("file:function", 1)[1]
    for line in body.splitlines():
        m = row.match(line)
        if not m or "(100.0%)" in line.split()[1]:
            continue
        counts, function = counts_of(m), m.group(len(events) + 1)
        stage = stage_of(function)
        sums[stage] = [a + b for a, b in zip(sums.get(stage, [0] * len(events)), counts)]
        if stage == "other":
            other.append((counts[0], function[:160]))
    total = totals[0]
    mispredicts = events.index("Bcm") if "Bcm" in events else None
    print(f"{args.image} {' '.join(args.options)} threshold {args.threshold}: "
          f"{total / 1e6:.2f} M instructions (second extract, 1 thread)"
          + (f", {totals[mispredicts]:,} mispredicted conditional branches" if mispredicts else ""))
    print("| stage | instructions (M) | share |" + (" mispredicts |" if mispredicts else ""))
    print("|---|---|---|" + ("---|" if mispredicts else ""))
    for stage, _ in STAGES + [("other", [])]:
        if stage in sums:
            print(f"| {stage} | {sums[stage][0] / 1e6:.2f} | {100 * sums[stage][0] / total:.1f}% |"
                  + (f" {sums[stage][mispredicts]:,} |" if mispredicts else ""))
    if args.show_other:
        for count, function in sorted(other, reverse=True)[:20]:
            print(f"  {count:>10,}  {function}")


if __name__ == "__main__":
    main()
