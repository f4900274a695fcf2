"""What the benchmark reports of a run: the model against the ground truth, and how many of the
matches in the database survived COLMAP's two-view verification."""
import sqlite3

import numpy as np

from colmapbench.scenes import scene_extent
from slambench.metrics import umeyama


def rotation_angle_deg(rotation):
    """The angle of a rotation matrix, degrees."""
    cosine = np.clip((np.trace(rotation) - 1.0) / 2.0, -1.0, 1.0)
    return float(np.degrees(np.arccos(cosine)))


def pose_errors(model, scene):
    """Camera position errors (as % of the scene's extent) and rotation errors (degrees) of the
    images both hold, after the similarity that best maps the model's centres onto the ground
    truth's (Umeyama). None when fewer than 3 images are registered."""
    names = [name for name in scene.images if name in model.centres]
    if len(names) < 3:
        return None
    estimated = np.array([model.centres[name] for name in names])
    truth = np.array([scene.cameras[name].centre for name in names])
    alignment = umeyama(estimated, truth, with_scale=True)
    aligned = (alignment.scale * (alignment.rotation @ estimated.T)).T + alignment.translation
    positions = np.linalg.norm(aligned - truth, axis=1) / scene_extent(scene) * 100.0
    # With X_gt = s R_a X_m + t, a model camera's world-to-camera rotation in the ground truth's
    # frame is R_m R_a^T; the error is the angle between it and R_gt.
    rotations = [rotation_angle_deg(scene.cameras[name].world_to_camera @
                                    (model.world_to_camera[name] @ alignment.rotation.T).T)
                 for name in names]
    return {"position_error_pct": positions, "rotation_error_deg": np.array(rotations)}


def verified_share(database):
    """(matches verified, matches imported): the rows of two_view_geometries (the inliers COLMAP's
    verification kept) against the rows of matches, over the pairs that have matches."""
    connection = sqlite3.connect(f"file:{database}?mode=ro", uri=True)
    try:
        imported, verified = connection.execute(
            "SELECT COALESCE(SUM(m.rows), 0), COALESCE(SUM(g.rows), 0) FROM matches AS m "
            "LEFT JOIN two_view_geometries AS g ON g.pair_id = m.pair_id").fetchone()
    finally:
        connection.close()
    return int(verified), int(imported)


def keypoints_per_image(database):
    """The mean keypoint count of the database's images."""
    connection = sqlite3.connect(f"file:{database}?mode=ro", uri=True)
    try:
        (mean,) = connection.execute("SELECT AVG(rows) FROM keypoints").fetchone()
    finally:
        connection.close()
    return float(mean or 0.0)


def model_summary(model, scene):
    """One row of the table for a model of `scene`."""
    row = {
        "images": len(scene.images),
        "registered": sum(name in model.centres for name in scene.images),
        "points": int(len(model.point_errors)),
        "track_length": float(np.mean(model.track_lengths)) if len(model.track_lengths) else 0.0,
        "reprojection_error_px": float(np.mean(model.point_errors)) if len(model.point_errors) else None,
    }
    errors = pose_errors(model, scene)
    row["position_error_median_pct"] = float(np.median(errors["position_error_pct"])) if errors else None
    row["position_error_max_pct"] = float(np.max(errors["position_error_pct"])) if errors else None
    row["rotation_error_median_deg"] = float(np.median(errors["rotation_error_deg"])) if errors else None
    return row
