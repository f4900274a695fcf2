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
    rows = {}
    for line in out.stdout.splitlines()[2:]:
        name, correct, share, pairs = [cell.strip() for cell in line.strip("|").split("|")]
        rows[name] = (int(correct), float(share), int(pairs))
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
