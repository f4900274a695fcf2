"""scripts/keypoints_or_descriptor.py (docs/evaluation.md, "Correct matches: the keypoints, not
the descriptor"): what it counts as correct, and its table on the bundled graf pair."""
import os
import pathlib
import subprocess
import sys

import aief
import cv2
import numpy as np

REPO = pathlib.Path(__file__).resolve().parents[2]
SCRIPT = REPO / "scripts" / "keypoints_or_descriptor.py"
sys.path.insert(0, str(SCRIPT.parent))

import keypoints_or_descriptor as kod  # noqa: E402


def test_a_match_is_correct_within_3_px_of_the_homography():
    h = np.array([[1, 0, 5], [0, 1, 0], [0, 0, 1]], float)  # 5 px to the right
    first = np.float32([[10, 10], [20, 20], [30, 30]])
    second = np.float32([[17, 10], [29, 20], [35, 33]])  # 2 px off, 4 px off, 3 px off
    matches = [cv2.DMatch(i, i, 0.0) for i in range(3)]
    assert kod.correct_and_putative(matches, first, second, h) == (2, 3)
    assert kod.correct_and_putative([], first, second, h) == (0, 0)


def test_a_copy_is_another_keypoint_within_2_px():
    points = np.float32([[0, 0], [1.5, 1.2], [10, 10], [12.5, 10], [30, 30]])
    assert kod.with_a_copy(points) == 2  # the first two (1.92 px apart); 2.5 px is no copy


def test_the_mutual_check_drops_a_correct_match_to_a_copy():
    h = np.eye(3)
    second = np.float32([[10, 10], [10.5, 10], [90, 90]])  # a corner twice, and one far away
    d2 = np.uint8([[0b0001], [0b0011], [0b1111]])
    # img1's first keypoint finds the corner; its second finds the far one, in the wrong place.
    first = np.float32([[10, 10], [50, 50]])
    d1 = np.uint8([[0b0000], [0b1111]])
    assert kod.nearest_neighbours_correct(d1, d2, cv2.NORM_HAMMING, first, second, h) == (1, 1)
    # img1 holds the corner twice too, each copy nearest to its own twin: both pairs are mutual.
    first = np.float32([[10, 10], [10, 11]])
    d1 = np.uint8([[0b0000], [0b0011]])
    assert kod.nearest_neighbours_correct(d1, d2, cv2.NORM_HAMMING, first, second, h) == (2, 2)
    # Both of img1's copies are nearest to img2's first copy, which is mutual with one of them
    # only: a correct nearest neighbour the mutual check drops.
    d2 = np.uint8([[0b0001], [0b0111], [0b1111]])
    assert kod.nearest_neighbours_correct(d1, d2, cv2.NORM_HAMMING, first, second, h) == (2, 1)


def test_strongest_keeps_the_best_responses_with_their_descriptors():
    keypoints = [cv2.KeyPoint(float(i), 0.0, 7.0, -1, response=float(r))
                 for i, r in enumerate([0.5, 3.0, 1.0, 2.0])]
    descriptors = np.arange(4, dtype=np.uint8).reshape(4, 1)
    kept, kept_descriptors = kod.strongest(keypoints, descriptors, n=2)
    assert [k.pt[0] for k in kept] == [1.0, 3.0]
    assert kept_descriptors.ravel().tolist() == [1, 3]


def test_the_table_of_the_bundled_graf_pair():
    build = pathlib.Path(aief.__file__).resolve().parents[2]  # <build>/python/aief/__init__.py
    out = subprocess.run([sys.executable, str(SCRIPT), str(REPO / "data" / "samples"), "graf",
                          "--build", str(build)], capture_output=True, text=True, check=True,
                         env=dict(os.environ, PYTHONDONTWRITEBYTECODE="1"))
    first_table, second_table = out.stdout.strip().split("\n\n")
    rows = {}
    for line in first_table.splitlines()[2:]:
        name, correct, share, pairs = [cell.strip() for cell in line.strip("|").split("|")]
        rows[name] = (int(correct), float(share), int(pairs))
    losses = {}
    for line in second_table.splitlines()[2:]:
        name, *counts = [cell.strip() for cell in line.strip("|").split("|")]
        losses[name] = [int(count) for count in counts]
    assert list(losses) == list(rows)
    for name, (copies, one_way, mutual, dropped) in losses.items():
        assert mutual == rows[name][0]  # the mutual check's survivors are the first table's
        assert one_way == mutual + dropped and 0 <= copies <= 1000
    # The fine pyramid finds most corners on neighbouring levels too; AKAZE far fewer.
    assert losses["aief quality"][0] > 2 * losses["AKAZE"][0]
    assert list(rows) == ["aief quality", "SIFT on aief (size x1)", "SIFT on aief (size x0.5)",
                          "AKAZE", "box on AKAZE x1", "box on AKAZE x4", "box on AKAZE x8"]
    for correct, share, pairs in rows.values():
        assert pairs == 1  # graf img1 -> img2, the one pair the samples hold
        assert 0 < correct <= 1000 and 0 < share <= 100
    # The aief row is the quality mode's own matching, counted here independently: mutual
    # nearest neighbours by Hamming distance in numpy, mapped through the ground truth.
    extractor = aief.Extractor(mode="quality", n_features=1000)
    images = [cv2.imread(str(REPO / "data" / "samples" / "graf" / f"img{i}.png"),
                         cv2.IMREAD_GRAYSCALE) for i in (1, 2)]
    first, second = (extractor.extract(image) for image in images)
    bits1 = np.unpackbits(first.descriptors, axis=1).astype(np.int32)
    bits2 = np.unpackbits(second.descriptors, axis=1).astype(np.int32)
    distance = bits1 @ (1 - bits2).T + (1 - bits1) @ bits2.T
    forward, backward = distance.argmin(axis=1), distance.argmin(axis=0)
    mutual = np.nonzero(backward[forward] == np.arange(len(forward)))[0]
    h = np.loadtxt(REPO / "data" / "samples" / "graf" / "H1to2p")
    mapped = cv2.perspectiveTransform(first.keypoints[mutual].reshape(-1, 1, 2), h).reshape(-1, 2)
    error = np.linalg.norm(mapped - second.keypoints[forward[mutual]], axis=1)
    assert rows["aief quality"][0] == int((error <= 3).sum())
    assert abs(rows["aief quality"][1] - 100 * (error <= 3).mean()) < 0.05
