#!/usr/bin/env python3
"""What --low-entropy-sharpen does to keypoints and matches on Oxford-style pairs (docs/design.md
§5, "Sharpened low-entropy blocks"): for each sequence, mode and pair 1 -> k (k = 2..6), with the
option off and on, the repeatability (share of image 1's keypoints inside image k whose homography
image has a keypoint within 2.5 px), the correct matches (mutual nearest neighbours within 3 px of
the ground truth) and image k's keypoints in level-0 blocks under 6 bits (32-pixel blocks from the
19-pixel border, histogram entropy). --darken S [--noise SIGMA] scales every image by S first and
adds seeded Gaussian noise (a dark, weak-texture stand-in). One line per pair, then the sums.

usage: PYTHONPATH=build/python low_entropy_sharpen_effect.py OXFORD_DIR
           [--sequences a,b] [--modes orbslam2,faithful] [--darken S] [--noise SIGMA]
"""
import argparse
import collections
import os

import numpy as np

import aief


def read(folder, stem, scale, noise, rng):
    name = next(os.path.join(folder, stem + ext) for ext in (".ppm", ".png", ".pgm")
                if os.path.exists(os.path.join(folder, stem + ext)))
    image = aief.read_image(name).astype(float)
    if scale != 1 or noise > 0:
        image = image * scale + (rng.normal(0, noise, image.shape) if noise > 0 else 0)
    return np.clip(np.round(image), 0, 255).astype(np.uint8)


def low_entropy_count(image, points, block=32, border=19, bits=6.0):
    count = 0
    for x, y in points:
        bx, by = int((x - border) // block), int((y - border) // block)
        patch = image[border + by * block:border + (by + 1) * block, border + bx * block:border + (bx + 1) * block]
        if patch.size == 0:
            continue
        p = np.bincount(patch.ravel(), minlength=256) / patch.size
        p = p[p > 0]
        count += float(-(p * np.log2(p)).sum()) < bits
    return count


def project(h, points):
    p = np.c_[points, np.ones(len(points))] @ h.T
    return p[:, :2] / p[:, 2:3]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("dataset")
    parser.add_argument("--sequences", default="bark,bikes,boat,graf,leuven,trees,ubc,wall")
    parser.add_argument("--modes", default="orbslam2,faithful")
    parser.add_argument("--darken", type=float, default=1.0)
    parser.add_argument("--noise", type=float, default=0.0)
    args = parser.parse_args()
    totals = collections.defaultdict(lambda: np.zeros(3))
    print("sequence mode sharpen pair repeatability correct low_entropy_keypoints")
    for sequence in args.sequences.split(","):
        folder = os.path.join(args.dataset, sequence)
        rng = np.random.default_rng(5)
        images = [read(folder, f"img{k}", args.darken, args.noise, rng) for k in range(1, 7)]
        for mode in args.modes.split(","):
            for sharpen in (False, True):
                extractor = aief.Extractor(n_features=1000, mode=mode, low_entropy_sharpen=sharpen, threads=1)
                first = extractor.extract(images[0])
                for k in range(2, 7):
                    h = np.loadtxt(os.path.join(folder, f"H1to{k}p"))
                    other = extractor.extract(images[k - 1])
                    a, b = first.keypoints[:, :2], other.keypoints[:, :2]
                    projected = project(h, a)
                    height, width = images[k - 1].shape
                    inside = ((projected >= 0) & (projected < [width, height])).all(1)
                    distances = np.sqrt(((projected[inside, None, :] - b[None, :, :]) ** 2).sum(-1))
                    repeatability = float((distances.min(1) < 2.5).mean()) if inside.any() else 0.0
                    matches = aief.match(first, other)
                    errors = np.sqrt(((project(h, a[matches[:, 0]]) - b[matches[:, 1]]) ** 2).sum(-1))
                    correct = int((errors < 3).sum())
                    low = low_entropy_count(images[k - 1], b)
                    totals[mode, sharpen] += [repeatability, correct, low]
                    print(sequence, mode, "on" if sharpen else "off", f"1-{k}", f"{repeatability:.3f}", correct, low,
                          flush=True)
    for mode in args.modes.split(","):
        off, on = totals[mode, False], totals[mode, True]
        print(f"{mode}: correct {off[1]:.0f} -> {on[1]:.0f} ({100 * (on[1] - off[1]) / off[1]:+.1f}%), "
              f"low-entropy keypoints {off[2]:.0f} -> {on[2]:.0f} ({100 * (on[2] - off[2]) / off[2]:+.1f}%)")


if __name__ == "__main__":
    main()
