"""Real multi-view scenes with calibrated ground-truth cameras, in Strecha's layout as openMVG's
SfM_quality_evaluation holds them (castle-P19, entry-P10, Herz-Jesus-P25, fountain-P11, ...):

  SCENE/images/0000.jpg ...            the photographs (K.txt beside them is not an image)
  SCENE/gt_dense_cameras/0000.jpg.camera

A .camera file is 9 + 3 + 9 + 3 + 2 numbers: K (3 x 3, row by row), the radial distortion (3,
zero here), R (3 x 3) and t (3), and the image's width and height. The projection is
P = K [R^T | -R^T t]: R turns camera axes into world axes and t is the camera's centre in the world
(Strecha et al., CVPR 2008; openMVG reads them the same way).
"""
import os
from dataclasses import dataclass

import numpy as np


@dataclass
class Camera:
    K: np.ndarray                # 3 x 3
    world_to_camera: np.ndarray  # 3 x 3 rotation, R^T of the file
    centre: np.ndarray           # 3, in world units
    width: int
    height: int


def read_camera(path):
    """One Strecha .camera file; ValueError naming the file when it is not 26 numbers."""
    with open(path) as handle:
        words = handle.read().split()
    try:
        values = [float(word) for word in words]
    except ValueError as error:
        raise ValueError(f"{path}: not a Strecha camera file ({error})") from None
    if len(values) != 26:
        raise ValueError(f"{path}: a Strecha camera file holds 26 numbers (K, distortion, R, t, "
                         f"width height), this one {len(values)}")
    k = np.array(values[0:9]).reshape(3, 3)
    rotation = np.array(values[12:21]).reshape(3, 3)
    centre = np.array(values[21:24])
    if not np.allclose(rotation @ rotation.T, np.eye(3), atol=1e-4):
        raise ValueError(f"{path}: R is not a rotation")
    return Camera(k, rotation.T, centre, int(values[24]), int(values[25]))


@dataclass
class Scene:
    name: str
    image_folder: str
    images: list   # file names, sorted
    cameras: dict  # file name -> Camera


def read_scene(folder):
    """The scene of `folder`: every image with a ground-truth camera. ValueError naming what is
    missing."""
    image_folder = os.path.join(folder, "images")
    camera_folder = os.path.join(folder, "gt_dense_cameras")
    for needed in (image_folder, camera_folder):
        if not os.path.isdir(needed):
            raise ValueError(f"scene {folder}: no folder {needed} (Strecha's layout: images/ and "
                             f"gt_dense_cameras/)")
    suffix = ".camera"
    cameras = {}
    for file in sorted(os.listdir(camera_folder)):
        if file.endswith(suffix):
            image = file[: -len(suffix)]
            if os.path.isfile(os.path.join(image_folder, image)):
                cameras[image] = read_camera(os.path.join(camera_folder, file))
    if len(cameras) < 3:
        raise ValueError(f"scene {folder}: {len(cameras)} images with a camera, at least 3 needed")
    return Scene(os.path.basename(os.path.normpath(folder)), image_folder, sorted(cameras), cameras)


def scene_extent(scene):
    """The largest distance between two ground-truth camera centres: position errors are given as
    a share of it."""
    centres = np.array([scene.cameras[name].centre for name in scene.images])
    return float(np.max(np.linalg.norm(centres[:, None] - centres[None], axis=2)))
