"""One run's figures, and the summary of a cell's runs (median and spread)."""
import json
import os

import numpy as np

from slambench import orbslam3
from slambench.metrics import absolute_trajectory_error


def evaluate_run(workdir, ground_truth, sensor, return_code, seconds):
    """The figures of one finished run (workdir of slambench.orbslam3.run) against the TUM ground truth file."""
    gt_times, gt_positions = orbslam3.read_ground_truth(ground_truth)
    frame_times, frame_positions = orbslam3.read_trajectory(os.path.join(workdir, f"f_{orbslam3.RUN_NAME}.txt"))
    kf_times, kf_positions = orbslam3.read_trajectory(os.path.join(workdir, f"kf_{orbslam3.RUN_NAME}.txt"))
    result = dict(return_code=return_code, wall_s=seconds, frames=len(gt_times), frames_tracked=len(frame_times),
                  tracked_share=len(frame_times) / len(gt_times), keyframes=len(kf_times), **orbslam3.read_log(workdir))
    with_scale = sensor == "mono"
    for name, times, positions in (("ate", frame_times, frame_positions), ("ate_kf", kf_times, kf_positions)):
        if len(times) >= 3:
            error = absolute_trajectory_error(times, positions, gt_times, gt_positions, with_scale)
            result[name] = error.rmse
            result[name + "_max"] = error.max
        else:
            result[name] = None
    timing = orbslam3.read_times(workdir)
    if timing is not None:
        extract, track = timing
        result.update(extract_ms_median=float(np.median(extract)), extract_ms_p95=float(np.percentile(extract, 95)),
                      track_ms_median=float(np.median(track)), track_ms_p95=float(np.percentile(track, 95)))
    return result


def save_aligned_trajectory(workdir, ground_truth, sensor, out_path):
    """The run's frames aligned to the ground truth (for the plots), as an N x 6 array (aligned, reference)."""
    gt_times, gt_positions = orbslam3.read_ground_truth(ground_truth)
    times, positions = orbslam3.read_trajectory(os.path.join(workdir, f"f_{orbslam3.RUN_NAME}.txt"))
    if len(times) < 3:
        return None
    error = absolute_trajectory_error(times, positions, gt_times, gt_positions, sensor == "mono")
    np.save(out_path, np.hstack([error.aligned, error.reference]))
    return out_path


FIELDS = ["ate", "ate_kf", "tracked_share", "keyframes", "lost", "map_resets", "extract_ms_median", "track_ms_median", "track_ms_p95"]


def summarise(runs):
    """Median, min and max of each field over a cell's runs; failed runs (no trajectory) count as
    ATE = inf so they are never hidden by the median."""
    summary = dict(runs=len(runs), failed=sum(1 for r in runs if r.get("ate") is None))
    for field in FIELDS:
        values = [r.get(field) for r in runs]
        if field.startswith("ate"):
            values = [np.inf if v is None else v for v in values]
        values = [v for v in values if v is not None]
        if values:
            summary[field] = dict(median=float(np.median(values)), min=float(np.min(values)), max=float(np.max(values)))
    return summary


def load_runs(folder):
    """The finished runs of a cell folder: (run folder, result dict), in run order."""
    runs = []
    for name in sorted(os.listdir(folder)) if os.path.isdir(folder) else []:
        path = os.path.join(folder, name, "result.json")
        if os.path.exists(path):
            runs.append((os.path.join(folder, name), json.load(open(path))))
    return runs


def median_run(runs):
    """The run folder whose ATE is the median of the cell's successful runs, or None."""
    finished = sorted((result["ate"], workdir) for workdir, result in runs if result.get("ate") is not None)
    return finished[len(finished) // 2][1] if finished else None
