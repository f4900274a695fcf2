"""The box descriptor training's pieces (scripts/box_descriptor.py), on tiny constructed cases:
a table written and read back in the engine's format, the tests read on an image as the engine
reads them, and boosting choosing the test and threshold that separate a constructed case.
Not the quality of a trained table (scripts/train_box_descriptor.py evaluate measures that)."""
import os
import sys

import numpy as np
import pytest

SCRIPTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
sys.path.insert(0, SCRIPTS)

import box_descriptor as bd  # noqa: E402


def test_table_written_and_read_back(tmp_path):
    rng = np.random.default_rng(3)
    geometry = bd.candidate_pool(256, rng)
    thresholds = np.round(rng.uniform(-20, 20, 256), 2)
    thresholds[:3] = [-0.001, 4.5, 12.0]  # -0.001 is written as 0 (two decimals at most)
    path = tmp_path / "table.txt"
    bd.write_table(path, bd.Table(geometry, thresholds), ["made by a test", "second line"])
    lines = path.read_text().splitlines()
    assert lines[0] == "# made by a test" and lines[1] == "# second line"
    assert lines[2].split()[5] == "0" and lines[3].split()[5] == "4.5" and lines[4].split()[5] == "12"
    for line in lines[2:]:
        fields = line.split()
        assert len(fields) == 6
        assert len(fields[5].partition(".")[2]) <= 2
    back = bd.read_table(path)
    bd.check_table(back)
    assert back.header == "made by a test\nsecond line"
    np.testing.assert_array_equal(back.geometry, geometry)
    np.testing.assert_allclose(back.thresholds, np.round(thresholds, 2), atol=1e-9)


def test_candidate_pool_stays_in_the_patch():
    pool = bd.candidate_pool(500, np.random.default_rng(0))
    r = pool[:, 4]
    assert (r >= 1).all() and (r <= 7).all()
    for c in range(4):
        assert (pool[:, c] - r >= -16).all() and (pool[:, c] + r <= 15).all()
    assert len({tuple(p) for p in pool.tolist()}) == 500
    assert not ((pool[:, 0] == pool[:, 2]) & (pool[:, 1] == pool[:, 3])).any()


def test_box_tests_read_the_image_as_the_engine_does():
    # Left half dark (10), right half bright (200): a test with box 1 left of the keypoint and
    # box 2 right of it reads -190 at angle 0 and +190 at angle 180.
    image = np.full((64, 64), 200, dtype=np.uint8)
    image[:, :32] = 10
    kps = bd.Keypoints([[31.5, 31.0], [31.5, 31.0]], [31.0, 31.0], [0.0, 180.0], [0, 0])
    geometry = np.array([[-8, 0, 8, 0, 3], [0, -8, 0, 8, 3]])
    r = bd.responses(bd.Pyramid(image), kps, geometry, "level0")
    np.testing.assert_allclose(r, [[-190, 0], [190, 0]])
    table = bd.Table(geometry, [-190, -0.01])
    bits = bd.describe(bd.Pyramid(image), kps, table, "level0")
    np.testing.assert_array_equal(bits, [[1, 0], [0, 0]])  # <= threshold, exactly


def test_boxes_are_clipped_at_the_border():
    image = np.arange(16 * 16, dtype=np.uint8).reshape(16, 16)
    kps = bd.Keypoints([[0.0, 0.0]], [32.0], [0.0], [0])
    r = bd.responses(bd.Pyramid(image), kps, np.array([[-5, -5, 0, 0, 2]]), "level0")
    corner = image[:1, :1].mean()             # box 1 clipped to pixel (0, 0)
    centre = image[0:3, 0:3].mean()           # box 2: [-2, 2] clipped to [0, 2]
    np.testing.assert_allclose(r, [[corner - centre]])


def test_a_trained_bit_separates_a_constructed_case():
    # Candidate 2 with threshold 0 gives the two keypoints of every positive pair the same bit
    # and those of every negative pair different bits; the other candidates are noise.
    grid = bd.threshold_grid(12.0)
    rng = np.random.default_rng(1)
    n = 400
    labels = np.repeat([1, 0], n // 2).astype(np.int8)
    noise1 = rng.uniform(-60, 60, size=(5, n))
    noise2 = rng.uniform(-60, 60, size=(5, n))
    a = rng.choice([-5.0, 5.0], n)
    noise1[2] = a
    noise2[2] = np.where(labels > 0, a, -a)
    chosen = bd.boost(bd.bins(noise1, grid), bd.bins(noise2, grid), labels, grid, n_bits=2)
    candidate, k, agreement = chosen[0]
    assert candidate == 2
    assert -5 <= grid[k] < 5
    assert agreement == pytest.approx(1.0, abs=1e-5)
    assert chosen[1][0] != 2  # a test is not chosen twice
    # The same on triplets (positive pair t, negative pair t + n/2).
    half = np.arange(n // 2)
    chosen = bd.boost(bd.bins(noise1, grid), bd.bins(noise2, grid), labels, grid, n_bits=2,
                      triplets=np.stack([half, half + n // 2], 1))
    assert chosen[0][0] == 2 and -5 <= grid[chosen[0][1]] < 5
    assert chosen[0][2] == pytest.approx(1.0, abs=1e-6)


def test_training_pairs_from_a_known_warp():
    rng = np.random.default_rng(2)
    xy = rng.uniform(20, 200, size=(60, 2))
    h = bd.homography(240, 240, angle_deg=20, scale=1.1)
    rbrief = rng.integers(0, 256, size=(60, 32), dtype=np.uint8)
    k1 = bd.Keypoints(xy, np.full(60, 31.0), np.zeros(60), np.zeros(60), rbrief)
    k2 = bd.Keypoints(bd.project(h, xy)[::-1], np.full(60, 31.0 * 1.1), np.zeros(60), np.zeros(60),
                      rbrief[::-1])
    pairs, labels = bd.training_pairs(k1, k2, h, rng)
    positives = pairs[labels > 0]
    assert len(positives) == 60
    np.testing.assert_array_equal(positives[:, 1], 59 - positives[:, 0])
    negatives = pairs[labels == 0]
    assert len(negatives) == 120
    err = np.linalg.norm(bd.project(h, k1.xy[negatives[:, 0]]) - k2.xy[negatives[:, 1]], axis=1)
    assert (err > 10).all()


def test_mutual_nearest_and_accuracy():
    bits1 = np.array([[0, 0, 0, 0], [1, 1, 1, 1], [1, 0, 1, 0]], dtype=np.uint8)
    bits2 = np.array([[1, 1, 1, 0], [0, 0, 0, 1]], dtype=np.uint8)
    matches = bd.mutual_nearest(bits1, bits2)
    np.testing.assert_array_equal(matches, [[0, 1], [1, 0]])
    k1 = bd.Keypoints([[0, 0], [10, 10], [5, 5]], [31] * 3, [0] * 3, [0] * 3)
    k2 = bd.Keypoints([[14, 10], [1, 1]], [31] * 2, [0] * 2, [0] * 2)
    assert bd.match_accuracy(matches, k1, k2, np.eye(3)) == (1, 2)


def test_a_correlated_bit_is_passed_over():
    # Candidates 0 and 1 are the same test (the best); candidate 2 is a little worse and
    # independent. Without a limit the duplicate comes second; with one, candidate 2 does.
    grid = bd.threshold_grid(12.0)
    rng = np.random.default_rng(4)
    n = 2000
    labels = np.repeat([1, 0], n // 2).astype(np.int8)
    r1 = rng.uniform(-60, 60, size=(4, n))
    r2 = rng.uniform(-60, 60, size=(4, n))
    a, b = rng.choice([-5.0, 5.0], n), rng.choice([-5.0, 5.0], n)
    flip_a = (labels == 0) | (rng.random(n) < 0.1)
    flip_b = (labels == 0) & (rng.random(n) < 0.8)
    r1[0] = r1[1] = a
    r2[0] = r2[1] = np.where(flip_a, -a, a)
    r1[2], r2[2] = b, np.where(flip_b, -b, b)
    b1, b2 = bd.bins(r1, grid), bd.bins(r2, grid)
    free = bd.boost(b1, b2, labels, grid, n_bits=2, shrinkage=0.01)
    assert [c for c, _, _ in free] in ([0, 1], [1, 0])
    limited = bd.boost(b1, b2, labels, grid, n_bits=2, shrinkage=0.01, max_correlation=0.5)
    assert limited[0][0] in (0, 1) and limited[1][0] == 2
