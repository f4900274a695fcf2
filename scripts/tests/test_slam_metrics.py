"""The benchmark's metrics on constructed trajectories (scripts/slambench/metrics.py)."""
import os
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))

from slambench.metrics import absolute_trajectory_error, associate, umeyama  # noqa: E402


def rotation(axis, angle):
    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * k @ k


def helix(n=600):
    t = np.linspace(0, 12, n)
    return t, np.stack([1.5 * np.cos(t), np.sin(0.7 * t), 0.2 * t], 1)


def test_a_known_similarity_gives_zero_error_and_its_scale():
    t, truth = helix()
    r = rotation([0.3, -1.0, 0.5], 1.1)
    estimate = (truth @ r.T * 0.37 + [4.0, -2.0, 0.5])  # what a monocular run reports: any frame, any scale
    result = absolute_trajectory_error(t, estimate, t, truth, with_scale=True)
    assert result.rmse < 1e-9
    assert result.scale == pytest.approx(1 / 0.37)


def test_rigid_alignment_does_not_absorb_a_scale_error():
    t, truth = helix()
    estimate = truth * 1.1
    assert absolute_trajectory_error(t, estimate, t, truth, with_scale=True).rmse < 1e-9
    rigid = absolute_trajectory_error(t, estimate, t, truth, with_scale=False)
    assert rigid.scale == 1.0 and rigid.rmse > 0.05


def test_known_noise_gives_its_rmse():
    rng = np.random.default_rng(3)
    t, truth = helix(4000)
    sigma = 0.01
    noisy = truth + rng.normal(0, sigma, truth.shape)
    r = rotation([1, 2, 3], 0.4)
    estimate = noisy @ r.T + [1, 1, 1]
    for with_scale in (False, True):
        result = absolute_trajectory_error(t, estimate, t, truth, with_scale)
        assert result.rmse == pytest.approx(sigma * np.sqrt(3), rel=0.03)


def test_umeyama_recovers_a_reflection_free_rotation():
    rng = np.random.default_rng(0)
    points = rng.normal(size=(50, 3))
    r = rotation([0, 0, 1], np.pi * 0.9)
    alignment = umeyama(points, points @ r.T, with_scale=False)
    assert np.allclose(alignment.rotation, r) and np.linalg.det(alignment.rotation) > 0


def test_association_pairs_nearest_within_tolerance_once():
    pairs = associate([1.0, 1.05, 2.0, 3.0], [0.999, 1.047, 1.0515, 2.2, 1.0])
    assert pairs == [(0, 4), (1, 2)]


def test_too_few_matches_is_an_error():
    with pytest.raises(ValueError, match="match"):
        absolute_trajectory_error([0.0, 1.0], np.zeros((2, 3)), [5.0, 6.0], np.zeros((2, 3)), True)
