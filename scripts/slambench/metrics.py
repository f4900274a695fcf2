"""Trajectory metrics: timestamp association, Umeyama alignment, absolute trajectory error.

ATE is the RMSE of the position differences after aligning the estimate to the ground truth
with the similarity (monocular: Sim(3), scale is unobservable) or rigid motion (stereo: SE(3))
that minimises it (Umeyama, 1991).
"""
from dataclasses import dataclass

import numpy as np


@dataclass
class Alignment:
    scale: float
    rotation: np.ndarray     # 3 x 3
    translation: np.ndarray  # 3

    def apply(self, points):
        return self.scale * points @ self.rotation.T + self.translation


def umeyama(source, target, with_scale):
    """The alignment minimising sum |target - (s R source + t)|^2 (points as N x 3 rows)."""
    source = np.asarray(source, np.float64)
    target = np.asarray(target, np.float64)
    if source.shape != target.shape or source.ndim != 2 or source.shape[1] != 3 or len(source) < 3:
        raise ValueError(f"umeyama needs two N x 3 arrays with N >= 3, got {source.shape} and {target.shape}")
    mean_source, mean_target = source.mean(0), target.mean(0)
    centred_source, centred_target = source - mean_source, target - mean_target
    covariance = centred_target.T @ centred_source / len(source)
    u, singular, vt = np.linalg.svd(covariance)
    sign = np.eye(3)
    if np.linalg.det(u) * np.linalg.det(vt) < 0:
        sign[2, 2] = -1.0
    rotation = u @ sign @ vt
    variance_source = np.mean(np.sum(centred_source ** 2, 1))
    scale = float(np.trace(np.diag(singular) @ sign) / variance_source) if with_scale else 1.0
    return Alignment(scale, rotation, mean_target - scale * rotation @ mean_source)


def associate(times_a, times_b, max_difference=0.005):
    """Index pairs (i, j) with |times_a[i] - times_b[j]| <= max_difference, each index used once,
    nearest first (as TUM's associate.py)."""
    times_b = np.asarray(times_b)
    order = np.argsort(times_b)
    sorted_b = times_b[order]
    pairs, used = [], set()
    for i, t in enumerate(times_a):
        k = np.searchsorted(sorted_b, t)
        best = None
        for candidate in (k - 1, k):
            if 0 <= candidate < len(sorted_b) and abs(sorted_b[candidate] - t) <= max_difference:
                if best is None or abs(sorted_b[candidate] - t) < abs(sorted_b[best] - t):
                    best = candidate
        if best is not None and order[best] not in used:
            used.add(order[best])
            pairs.append((i, int(order[best])))
    return pairs


@dataclass
class TrajectoryError:
    rmse: float
    mean: float
    max: float
    matched: int
    scale: float
    aligned: np.ndarray  # the estimate's positions after alignment (matched rows)
    reference: np.ndarray  # the matching ground truth positions


def absolute_trajectory_error(estimate_times, estimate_positions, gt_times, gt_positions, with_scale):
    pairs = associate(estimate_times, gt_times)
    if len(pairs) < 3:
        raise ValueError(f"only {len(pairs)} estimated poses match ground truth timestamps")
    est = np.asarray(estimate_positions)[[i for i, _ in pairs]]
    ref = np.asarray(gt_positions)[[j for _, j in pairs]]
    alignment = umeyama(est, ref, with_scale)
    aligned = alignment.apply(est)
    errors = np.linalg.norm(aligned - ref, axis=1)
    return TrajectoryError(float(np.sqrt(np.mean(errors ** 2))), float(errors.mean()), float(errors.max()), len(pairs),
                           alignment.scale, aligned, ref)
