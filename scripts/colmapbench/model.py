"""A COLMAP sparse model as `colmap model_converter --output_type TXT` writes it (cameras.txt,
images.txt, points3D.txt): each registered image's pose and each 3D point's error and track."""
import os
from dataclasses import dataclass

import numpy as np


@dataclass
class Model:
    world_to_camera: dict  # image name -> 3 x 3 rotation
    centres: dict          # image name -> camera centre, 3
    point_errors: np.ndarray   # mean reprojection error of each 3D point, pixels
    track_lengths: np.ndarray  # observations of each 3D point


def quaternion_to_rotation(w, x, y, z):
    """COLMAP's qvec (w, x, y, z) as a rotation matrix."""
    q = np.array([w, x, y, z], np.float64)
    w, x, y, z = q / np.linalg.norm(q)
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def _data_lines(path):
    with open(path) as handle:
        return [line for line in handle.read().splitlines() if not line.startswith("#")]


def read_text_model(folder):
    """The model of `folder` (images.txt and points3D.txt); ValueError naming a missing file."""
    for file in ("images.txt", "points3D.txt"):
        if not os.path.isfile(os.path.join(folder, file)):
            raise ValueError(f"{folder}: no {file} (colmap model_converter --output_type TXT)")
    lines = _data_lines(os.path.join(folder, "images.txt"))
    # Two lines an image: the pose, then its 2D points (an empty line when it has none).
    rotations, centres = {}, {}
    for header in lines[0::2]:
        words = header.split()
        if len(words) < 10:
            continue
        qw, qx, qy, qz, tx, ty, tz = (float(v) for v in words[1:8])
        name = " ".join(words[9:])
        rotation = quaternion_to_rotation(qw, qx, qy, qz)
        rotations[name] = rotation
        centres[name] = -rotation.T @ np.array([tx, ty, tz])
    errors, tracks = [], []
    for line in _data_lines(os.path.join(folder, "points3D.txt")):
        words = line.split()
        if len(words) >= 8:
            errors.append(float(words[7]))
            tracks.append((len(words) - 8) // 2)
    return Model(rotations, centres, np.array(errors), np.array(tracks))
