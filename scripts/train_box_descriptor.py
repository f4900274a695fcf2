#!/usr/bin/python3
"""Learns aief's own 256-bit box descriptor table, and compares tables on aief's keypoints.

  train_box_descriptor.py train [--out data/box_descriptor/aief_256.txt] [options]
  train_box_descriptor.py evaluate TABLE... [--oxford DIR] [--integral level|level0]

Needs the Python module (build target aief_python; PYTHONPATH=build/python) and the system's
numpy and OpenCV (python3-numpy, python3-opencv). Everything is seeded: the same command gives
the same table.

train: pairs of images with known homographies are made from the repository's own samples
(data/samples/graf and boat, img1 and img2) and three photographs Debian ships (python3-scipy's
scipy/misc/face.dat, python3-pywt's pywt/data/aero.npz and ascent.npz), 12 each, warped at random
(any rotation, scale 0.55-1.8, perspective, shift) and changed at random (blur, noise, JPEG,
lighting). aief's default extractor gives the keypoints of both images; a keypoint pair is
positive when the warp brings one onto the other (1.5 px, mutual, sizes agreeing with the warp's
scale), and each positive gets two negatives: the keypoint whose rBRIEF is nearest among those at
least 10 px away (the confusion a matcher makes), and a random one. A random pool of 2500
candidate box pairs (radius 1-7, inside the 32 x 32 patch) is read on every keypoint as the
engine reads its table (scripts/box_descriptor.py); BEBLID's boosting (box_descriptor.boost,
damped) then picks 256 (test, threshold within +-12 gray levels) in turn, reweighting the pairs
after each so the next bit covers what the chosen ones miss. About 5-6 minutes with the defaults
on a busy 2-core machine (one core used), about 1 GB of memory.

Measured and not kept as defaults (options, same held-out and Oxford pairs): thresholds up to
+-80 (lighting changes flip their bits: -10 MMA on the lighting condition), up to +-4 (lighting
fixed, the rest worse), undamped boosting (--shrinkage 1), --shrinkage 0.3, a limit on bit
correlation (--max-correlation 0.2) and TEBLID-style triplet weighting (--loss triplet): none
better than the defaults by more than the noise of these pairs.

evaluate: the held-out pairs are other images (data/samples/leuven/img1.png and matplotlib's
grace_hopper.jpg, python-matplotlib-data) under fixed conditions (rotation, zoom, perspective,
light and heavy blur, JPEG 15, lighting, noise), and the training images under the same
conditions with other warps; with --oxford DIR also the Oxford sequences (DIR/<seq>/img1..6,
H1toNp). Every table's descriptors, and aief's own rBRIEF, are computed on the same aief keypoints
of each pair and matched by mutual nearest neighbour (Hamming): MMA@3px is the share of those
matches within 3 px of where the homography puts them.
"""
import argparse
import bz2
import os
import sys
import time

import cv2
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)

import box_descriptor as bd  # noqa: E402

FACE = "/usr/lib/python3/dist-packages/scipy/misc/face.dat"          # python3-scipy
GRACE = "/usr/share/matplotlib/mpl-data/sample_data/grace_hopper.jpg"  # python-matplotlib-data
AERO = "/usr/lib/python3/dist-packages/pywt/data/aero.npz"             # python3-pywt
ASCENT = "/usr/lib/python3/dist-packages/pywt/data/ascent.npz"         # python3-pywt
PACKAGES = {FACE: "python3-scipy", GRACE: "python-matplotlib-data", AERO: "python3-pywt",
            ASCENT: "python3-pywt"}

TRAINING_IMAGES = ["data/samples/graf/img1.png", "data/samples/graf/img2.png",
                   "data/samples/boat/img1.png", "data/samples/boat/img2.png", FACE, AERO, ASCENT]
HELD_OUT_IMAGES = ["data/samples/leuven/img1.png", GRACE]

DEFAULTS = dict(seed=31, warps=12, candidates=2500, positives=200, integral="level",
                n_features=1000, shrinkage=0.1, max_threshold=12.0,
                lighting=0.7, max_correlation=1.0, loss="pair", rate=0.05, refresh=8)

# The numeric flags of `train` (flag, type, help), each defaulting to DEFAULTS under its name.
TRAIN_FLAGS = (
    ("--warps", int, "random pairs per image"),
    ("--candidates", int, "size of the random pool of box pairs"),
    ("--positives", int, "at most this many positive pairs per image pair"),
    ("--shrinkage", float, "damping of the boosting's reweighting (1: plain AdaBoost)"),
    ("--refresh", int, "score every candidate every N rounds, the best 256 between (1: exact)"),
    ("--max-correlation", float, "largest |correlation| of a new bit with a chosen one (1: no limit)"),
    ("--rate", float, "triplet loss: weight exp(-rate x margin in bits)"),
    ("--max-threshold", float, "largest |threshold| a test may take (mean gray levels)"),
    ("--lighting", float, "probability of a lighting change in a training pair"),
)


def import_aief():
    try:
        import aief
    except ImportError:
        sys.exit("cannot import aief: build the module (cmake --build build --target aief_python) "
                 "and set PYTHONPATH=build/python")
    return aief


def read_gray(path):
    full = path if os.path.isabs(path) else os.path.join(ROOT, path)
    if not os.path.exists(full):
        package = PACKAGES.get(path, "")
        sys.exit(f"missing image {full}" + (f" (apt-get install {package})" if package else ""))
    if full.endswith("face.dat"):
        with open(full, "rb") as f:
            rgb = np.frombuffer(bz2.decompress(f.read()), dtype=np.uint8).reshape(768, 1024, 3)
        return cv2.cvtColor(rgb, cv2.COLOR_RGB2GRAY)
    if full.endswith(".npz"):
        with np.load(full, allow_pickle=False) as z:
            return np.ascontiguousarray(z["data"], dtype=np.uint8)
    gray = cv2.imread(full, cv2.IMREAD_GRAYSCALE)
    if gray is None:
        sys.exit(f"cannot read {full}")
    return gray


def short_name(path):
    if path in PACKAGES:
        return f"{os.path.basename(path)} ({PACKAGES[path]})"
    return path


# ----------------------------------------------------------------------------- training

def collect(images, args, extractor, log):
    """The training pairs' keypoints and labels, and the responses of the candidate pool."""
    rng = np.random.default_rng(args.seed)
    pool = bd.candidate_pool(args.candidates, rng)
    grid = bd.threshold_grid(args.max_threshold)
    side1, side2, labels, triplets = [], [], [], []
    for path in images:
        gray = read_gray(path)
        for w in range(args.warps):
            img1, img2, h = bd.random_training_pair(gray, rng, args.lighting)
            k1, k2 = bd.extract(extractor, img1), bd.extract(extractor, img2)
            pairs, lab = bd.training_pairs(k1, k2, h, rng, max_positives=args.positives)
            if len(pairs) == 0:
                continue
            for kps, img, column, out in ((k1, img1, 0, side1), (k2, img2, 1, side2)):
                used, inverse = np.unique(pairs[:, column], return_inverse=True)
                r = bd.responses(bd.Pyramid(img), kps.subset(used), pool, args.integral)
                out.append(bd.bins(r, grid)[inverse].T.copy())  # candidates x pairs
            n = int((lab > 0).sum())  # training_pairs: n positives, n hard then n random negatives
            offset = sum(len(x) for x in labels)
            k = offset + np.arange(n)
            triplets.append(np.concatenate([np.stack([k, k + n], 1), np.stack([k, k + 2 * n], 1)]))
            labels.append(lab)
        log(f"  {short_name(path)}: {args.warps} warps, {sum(len(x) for x in labels)} pairs so far")
    labels = np.concatenate(labels)
    return (pool, grid, np.concatenate(side1, axis=1), np.concatenate(side2, axis=1), labels,
            np.concatenate(triplets))


def train(args):
    aief = import_aief()
    started = time.time()
    log = print
    extractor = aief.Extractor(n_features=args.n_features, threads=1)
    images = args.images or TRAINING_IMAGES
    log(f"collecting pairs from {len(images)} images x {args.warps} warps, "
        f"{args.candidates} candidate tests")
    pool, grid, bins1, bins2, labels, triplets = collect(images, args, extractor, log)
    n_pos = int((labels > 0).sum())
    log(f"{len(labels)} pairs ({n_pos} positive), responses in {time.time() - started:.0f} s")

    def progress(i, c, k, r):
        if i % 32 == 0 or i == 255:
            log(f"  bit {i:3d}: test {pool[c].tolist()} threshold {grid[k]:g} "
                f"weighted agreement {r:.3f}  ({time.time() - started:.0f} s)")

    chosen = bd.boost(bins1, bins2, labels, grid, n_bits=256, shrinkage=args.shrinkage,
                      refresh=args.refresh, max_correlation=args.max_correlation,
                      triplets=triplets if args.loss == "triplet" else None, rate=args.rate,
                      progress=progress)
    table = bd.Table([pool[c] for c, _, _ in chosen], [grid[k] for _, k, _ in chosen])
    bd.check_table(table)
    minutes = (time.time() - started) / 60.0
    header = [
        "aief-256: 256 box-average tests learned by the project for aief's own keypoints,",
        "by scripts/train_box_descriptor.py train (rerun it to get this file again):",
        f"  seed {args.seed}, {args.warps} random warps per image, {args.candidates} random "
        f"candidate box pairs (radius 1-7),",
        f"  boxes read on the integral image of the keypoint's {'own level' if args.integral == 'level' else 'level 0'}, "
        f"aief default mode, {args.n_features} features;",
        "  images: " + ", ".join(short_name(p) for p in images) + ";",
        f"  {len(labels)} keypoint pairs ({n_pos} positive; negatives: nearest rBRIEF >= 10 px away, "
        "and random);",
        f"  boosting ({'TEBLID-style, on triplets, rate %g' % args.rate if args.loss == 'triplet' else 'BEBLID-style, on pairs'})"
        f" over {len(grid)} thresholds (|t| <= {args.max_threshold:g}), shrinkage "
        f"{args.shrinkage:g}, {'bits correlated at most %g' % args.max_correlation if args.max_correlation < 1 else 'no limit on bit correlation'}, lighting changes in "
        f"{args.lighting:g} of the pairs.",
        "",
        "One line per bit i (line order = bit order): \"x1 y1 x2 y2 radius threshold\".",
        "  (x1, y1), (x2, y2)  the centres of box 1 and box 2, integer patch pixels, origin at the centre",
        "                      of the 32 x 32 patch, x to the right, y down, before rotation;",
        "  radius              both boxes are squares of side 2 * radius + 1 patch pixels;",
        "  threshold           on mean gray levels (0-255), a decimal with at most two decimals.",
        "  bit i = 1  iff  mean(box 1) - mean(box 2) <= threshold, else 0.",
        "A keypoint of size S (kPatchSize = 31 at its level) and angle A maps patch point (x, y) to",
        "  centre + (S / 32) * R(A) * (x, y), and a radius r to round(r * S / 32)",
        "(core/kernels/box_describe.hpp has the exact arithmetic; docs/design.md \"The box descriptor\").",
    ]
    out = args.out if os.path.isabs(args.out) else os.path.join(ROOT, args.out)
    os.makedirs(os.path.dirname(out), exist_ok=True)
    bd.write_table(out, table, header)
    log(f"wrote {out} in {minutes:.1f} min")
    return table


# ----------------------------------------------------------------------------- evaluation

def conditions(width, height, rng):
    """name -> (homography, photometric keywords): each with a small random base warp."""
    def base(angle=0.0, scale=1.0):
        return bd.homography(width, height, angle + rng.uniform(-10, 10),
                             scale * rng.uniform(0.92, 1.08), corner_shift=0.02, rng=rng)
    tilt = bd.perspective_tilt(width, height, 20 * rng.choice([-1, 1]), int(rng.integers(2)))
    return {
        "rotation 30 + noise 3": (base(30), dict(noise=3)),
        "rotation 90": (base(90), {}),
        "zoom 1.6": (base(0, 1.6), {}),
        "zoom 0.6": (base(0, 0.6), {}),
        "perspective 20 deg": (tilt @ base(), {}),
        "light blur 1.5": (base(), dict(blur=1.5)),
        "heavy blur 3": (base(), dict(blur=3.0)),
        "JPEG 15": (base(), dict(jpeg=15)),
        "lighting": (base(), dict(gamma=0.6, gain=0.6, offset=30)),
        "noise 8": (base(), dict(noise=8)),
    }


def synthetic_pairs(images, seed, draws=2):
    rng = np.random.default_rng(seed)
    for path in images:
        gray = read_gray(path)
        h_img, w_img = gray.shape
        for _ in range(draws):
            for name, (h, photo) in conditions(w_img, h_img, rng).items():
                yield name, gray, bd.photometric(bd.warp(gray, h), rng, **photo), h


def oxford_pairs(folder):
    for seq in sorted(os.listdir(folder)):
        d = os.path.join(folder, seq)
        if not os.path.isfile(os.path.join(d, "H1to2p")):
            continue
        img1 = read_gray(os.path.join(d, "img1.png") if os.path.exists(os.path.join(d, "img1.png"))
                         else os.path.join(d, "img1.ppm"))
        for n in range(2, 7):
            hp = os.path.join(d, f"H1to{n}p")
            name = next((os.path.join(d, f"img{n}.{e}") for e in ("png", "ppm", "pgm")
                         if os.path.exists(os.path.join(d, f"img{n}.{e}"))), None)
            if name is None or not os.path.exists(hp):
                continue
            yield f"oxford {seq}", img1, read_gray(name), np.loadtxt(hp)


def evaluate_pairs(pairs, tables, extractor, integral):
    """{group: {method: [correct, matched, pairs]}} over (group, img1, img2, H) pairs."""
    results = {}
    for group, img1, img2, h in pairs:
        k1, k2 = bd.extract(extractor, img1), bd.extract(extractor, img2)
        p1, p2 = bd.Pyramid(img1), bd.Pyramid(img2)
        methods = {"rBRIEF": (np.unpackbits(k1.rbrief, axis=1), np.unpackbits(k2.rbrief, axis=1))}
        for name, table in tables.items():
            methods[name] = (bd.describe(p1, k1, table, integral), bd.describe(p2, k2, table, integral))
        row = results.setdefault(group, {})
        for name, (b1, b2) in methods.items():
            correct, matched = bd.match_accuracy(bd.mutual_nearest(b1, b2), k1, k2, h)
            acc = row.setdefault(name, [0, 0, 0])
            acc[0] += correct
            acc[1] += matched
            acc[2] += 1
    return results


def print_results(title, results, names):
    print(f"\n{title}: MMA@3px, mutual nearest neighbour (correct matches per pair)")
    print("| condition | pairs | " + " | ".join(names) + " |")
    print("|---|---|" + "---|" * len(names))
    totals = {n: [0.0, 0] for n in names}
    for group, row in results.items():
        cells = []
        for n in names:
            correct, matched, count = row[n]
            mma = 100.0 * correct / max(1, matched)
            totals[n][0] += mma
            totals[n][1] += 1
            cells.append(f"{mma:.1f} ({correct / count:.0f})")
        print(f"| {group} | {row[names[0]][2]} | " + " | ".join(cells) + " |")
    print("| mean of the rows | | " + " | ".join(f"{totals[n][0] / max(1, totals[n][1]):.1f}"
                                               for n in names) + " |")


def evaluate(args):
    aief = import_aief()
    extractor = aief.Extractor(n_features=args.n_features, threads=1)
    tables = {}
    for path in args.tables:
        name = os.path.splitext(os.path.basename(path))[0]
        tables[name] = bd.read_table(path)
    names = ["rBRIEF"] + list(tables)
    held_out = args.held_out or HELD_OUT_IMAGES
    print("tables: " + ", ".join(args.tables) + f"; boxes read on the {args.integral} integral image")
    res = evaluate_pairs(synthetic_pairs(held_out, args.seed + 1000), tables, extractor, args.integral)
    print_results("held-out images (" + ", ".join(short_name(p) for p in held_out) + ")", res, names)
    if not args.skip_seen:
        res = evaluate_pairs(synthetic_pairs(args.images or TRAINING_IMAGES, args.seed + 2000, draws=1),
                             tables, extractor, args.integral)
        print_results("training images, other warps", res, names)
    if args.oxford:
        res = evaluate_pairs(oxford_pairs(args.oxford), tables, extractor, args.integral)
        print_results("Oxford sequences, img1 -> img2..6 (graf and boat img1 are training images)",
                      res, names)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    for name in ("train", "evaluate"):
        p = sub.add_parser(name)
        p.add_argument("--seed", type=int, default=DEFAULTS["seed"])
        p.add_argument("--integral", choices=["level", "level0"], default=DEFAULTS["integral"],
                       help="where the boxes are read: the keypoint's own pyramid level (the engine's "
                            "choice) or level 0")
        p.add_argument("--n-features", type=int, default=DEFAULTS["n_features"])
        p.add_argument("--images", nargs="+", help="training images (default: the built-in list)")
        if name == "train":
            p.add_argument("--out", default="data/box_descriptor/aief_256.txt")
            for flag, kind, text in TRAIN_FLAGS:
                p.add_argument(flag, type=kind, default=DEFAULTS[flag[2:].replace("-", "_")],
                               help=text)
            p.add_argument("--loss", choices=["pair", "triplet"], default=DEFAULTS["loss"],
                           help="pair: AdaBoost on labelled pairs (BEBLID); triplet: weights by "
                                "the margin of anchor-positive-negative triplets (TEBLID)")
        else:
            p.add_argument("tables", nargs="+", help="table files to compare")
            p.add_argument("--oxford", help="a folder of Oxford sequences (<seq>/img1..6, H1toNp)")
            p.add_argument("--held-out", nargs="+", help="held-out images (default: the built-in list)")
            p.add_argument("--skip-seen", action="store_true",
                           help="skip the training images under other warps")
    args = parser.parse_args(argv)
    cv2.setNumThreads(1)
    if args.command == "train":
        train(args)
    else:
        evaluate(args)


if __name__ == "__main__":
    main()
