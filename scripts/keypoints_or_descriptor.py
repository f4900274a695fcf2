#!/usr/bin/env python3
"""Where the correct matches per pair are lost: in the keypoints or in the descriptor?

Swaps detectors and descriptors on the same image pairs (docs/evaluation.md, "Correct matches: the
keypoints, not the descriptor") and counts, per pair img1 -> imgN of every sequence, the mutual
nearest neighbours that land within 3 px of the true homography (aief eval's "correct"), and
their share (MMA@3px):

  aief quality            the quality mode's keypoints and box descriptors (as aief eval's row)
  SIFT on aief            the same keypoints described by SIFT (128 floats), at the keypoint's
                          size and at half of it
  AKAZE                   OpenCV AKAZE, its strongest 1000 keypoints and its descriptors
  box on AKAZE xM         the same AKAZE keypoints described by aief's box descriptor, each on the
                          pyramid level whose patch is M x the keypoint's size

A second table says where the correct matches a row misses are lost, per pair: its keypoints that
have a copy (another of its keypoints within 2 px, as the same corner found on a neighbouring
pyramid level), the nearest neighbours img1 -> imgN that are correct (one way, before the mutual
check), those of them the mutual check keeps (the first table's count) and those it drops.

Extraction and description are aief's (the Python module built in BUILD/python); SIFT and AKAZE
are OpenCV's, used as baselines only.

usage: scripts/keypoints_or_descriptor.py DATASET SEQ[,SEQ...] [--build build]
  DATASET holds <seq>/img1..6.png and H1to2p..H1to6p (aief eval's layout).
"""
import argparse
import math
import os
import sys

import cv2
import numpy as np

FEATURES = 1000
CORRECT_PX = 3.0
COPY_PX = 2.0


def mutual_matches(d1, d2, norm):
    return cv2.BFMatcher(norm, crossCheck=True).match(d1, d2)


def correct_and_putative(matches, points1, points2, h):
    if not matches:
        return 0, 0
    p1 = np.float32([points1[m.queryIdx] for m in matches]).reshape(-1, 1, 2)
    p2 = np.float32([points2[m.trainIdx] for m in matches])
    mapped = cv2.perspectiveTransform(p1, h).reshape(-1, 2)
    return int((np.linalg.norm(mapped - p2, axis=1) <= CORRECT_PX).sum()), len(matches)


def nearest_neighbours_correct(d1, d2, norm, points1, points2, h):
    """(correct one way, correct and mutual): img1's nearest neighbours in img2 within 3 px of
    the homography, and those of them that are also img2's nearest neighbours back."""
    forward = np.int64([m.trainIdx for m in cv2.BFMatcher(norm).match(d1, d2)])
    backward = np.int64([m.trainIdx for m in cv2.BFMatcher(norm).match(d2, d1)])
    mapped = cv2.perspectiveTransform(np.float32(points1).reshape(-1, 1, 2), h).reshape(-1, 2)
    correct = np.linalg.norm(mapped - np.float32(points2)[forward], axis=1) <= CORRECT_PX
    mutual = backward[forward] == np.arange(len(forward))
    return int(correct.sum()), int((correct & mutual).sum())


def with_a_copy(points, radius=COPY_PX):
    """How many of the points have another point within radius px."""
    points = np.float32(points)
    distance = np.linalg.norm(points[:, None, :] - points[None, :, :], axis=2)
    np.fill_diagonal(distance, np.inf)
    return int((distance.min(axis=1) <= radius).sum())


def strongest(keypoints, descriptors, n=FEATURES):
    order = np.argsort([-k.response for k in keypoints], kind="stable")[:n]
    return [keypoints[i] for i in order], descriptors[order]


class Methods:
    def __init__(self, aief):
        self.aief = aief.Extractor(mode="quality", n_features=FEATURES)
        self.scale_factor = self.aief.options["scale_factor"]
        self.levels = self.aief.options["n_levels"]
        self.sift = cv2.SIFT_create()
        self.akaze = cv2.AKAZE_create()
        self.akaze.setThreshold(1e-4)  # enough keypoints on blurred images to keep the best 1000

    def run(self, image):
        """Each row's (points, descriptors, norm) for one image."""
        rows = {}
        ours = self.aief.extract(image)
        rows["aief quality"] = (ours.keypoints, ours.descriptors, cv2.NORM_HAMMING)
        for share in (1.0, 0.5):
            keypoints = [cv2.KeyPoint(float(x), float(y), float(size) * share, float(angle))
                         for (x, y), size, angle in zip(ours.keypoints, ours.size, ours.angle)]
            _, descriptors = self.sift.compute(image, keypoints)
            rows[f"SIFT on aief (size x{share:g})"] = (ours.keypoints, descriptors, cv2.NORM_L2)
        keypoints, descriptors = strongest(*self.akaze.detectAndCompute(image, None))
        points = np.float32([k.pt for k in keypoints])
        rows["AKAZE"] = (points, descriptors, cv2.NORM_HAMMING)
        for patch in (1, 4, 8):
            sizes = np.float32([k.size for k in keypoints]) * patch
            octave = np.round(np.log(np.maximum(sizes, 31.0) / 31.0) / math.log(self.scale_factor))
            octave = np.clip(octave, 0, self.levels - 1).astype(np.int32)
            described, _ = self.aief.describe(image, points, octave=octave)
            rows[f"box on AKAZE x{patch}"] = (described.keypoints, described.descriptors,
                                               cv2.NORM_HAMMING)
        return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("dataset")
    parser.add_argument("sequences", help="comma-separated")
    parser.add_argument("--build", default="build")
    args = parser.parse_args()
    sys.path.insert(0, os.path.join(args.build, "python"))
    import aief  # noqa: E402 (the module of the build named on the command line)

    methods = Methods(aief)
    totals = {}  # row -> [(correct, putative)]
    losses = {}  # row -> [(keypoints with a copy, correct one way, correct and mutual)]
    for sequence in [s for s in args.sequences.split(",") if s]:
        folder = os.path.join(args.dataset, sequence)
        first = cv2.imread(os.path.join(folder, "img1.png"), cv2.IMREAD_GRAYSCALE)
        if first is None:
            sys.exit(f"keypoints_or_descriptor: cannot read {folder}/img1.png")
        rows1 = methods.run(first)
        for n in range(2, 7):
            image_path = os.path.join(folder, f"img{n}.png")
            h_path = os.path.join(folder, f"H1to{n}p")
            if not (os.path.exists(image_path) and os.path.exists(h_path)):
                continue  # a sequence may hold fewer pairs (the bundled samples: img2 only)
            image = cv2.imread(image_path, cv2.IMREAD_GRAYSCALE)
            if image is None:
                sys.exit(f"keypoints_or_descriptor: cannot read {image_path}")
            h = np.loadtxt(h_path)
            for row, (p2, d2, norm) in methods.run(image).items():
                p1, d1, _ = rows1[row]
                totals.setdefault(row, []).append(
                    correct_and_putative(mutual_matches(d1, d2, norm), p1, p2, h))
                losses.setdefault(row, []).append(
                    (with_a_copy(p1), *nearest_neighbours_correct(d1, d2, norm, p1, p2, h)))
    print("| keypoints and descriptor | correct per pair | MMA@3px | pairs |")
    print("|---|---|---|---|")
    for row, pairs in totals.items():
        correct = np.array([c for c, _ in pairs], float)
        share = np.array([c / p if p else 0.0 for c, p in pairs])
        print(f"| {row} | {correct.mean():.0f} | {100 * share.mean():.1f} | {len(pairs)} |")
    print()
    print("| keypoints and descriptor | with a copy | correct one way | kept by the mutual check "
          "| dropped by it |")
    print("|---|---|---|---|---|")
    for row, pairs in losses.items():
        copies, one_way, mutual = np.float64(pairs).mean(axis=0)
        print(f"| {row} | {copies:.0f} | {one_way:.0f} | {mutual:.0f} | {one_way - mutual:.0f} |")


if __name__ == "__main__":
    main()
