"""Camera paths: T_world_cam(t) as smooth closed-form functions of time.

The camera travels along an ellipse around the middle of the room (slamseq.scene keeps the boxes
out of it) at about 0.35 m/s, so every path TRANSLATES: monocular SLAM needs the parallax, a
path that mostly pans gives scale drift whatever the extractor. It looks outwards, at the walls
and the boxes in front of them, with a slow sweep of the heading; `fast_rotation` adds a
0.6 Hz yaw and 0.8 Hz pitch oscillation on top (peaks near 110 deg/s).
"""
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class PathSpec:
    centre: tuple            # (x, y) of the ellipse
    radii: tuple             # (rx, ry) metres
    height: float            # camera height, metres
    phase: float             # where on the ellipse the path starts, radians
    direction: float         # +1 counter-clockwise, -1 clockwise
    speed: float = 0.35      # m/s along the ellipse (approximately)
    sweep: float = 0.55      # heading sweep amplitude, radians
    fast_yaw: float = 0.0    # amplitude of the fast yaw oscillation, radians
    fast_pitch: float = 0.0  # amplitude of the fast pitch oscillation, radians


def random_path(rng, room_size, fast_rotation=False):
    return PathSpec(
        centre=(room_size[0] / 2 + rng.uniform(-0.2, 0.2), room_size[1] / 2 + rng.uniform(-0.15, 0.15)),
        radii=(rng.uniform(1.3, 1.7), rng.uniform(1.0, 1.3)),
        height=rng.uniform(1.2, 1.6), phase=rng.uniform(0, 2 * np.pi), direction=rng.choice([-1.0, 1.0]),
        fast_yaw=np.radians(20.0) if fast_rotation else 0.0, fast_pitch=np.radians(6.0) if fast_rotation else 0.0)


def look_rotation(forward, roll):
    """R_world_cam for an OpenCV camera looking along `forward` (world z up), rolled about it."""
    forward = forward / np.linalg.norm(forward)
    right = np.cross(forward, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    down = np.cross(forward, right)
    c, s = np.cos(roll), np.sin(roll)
    return np.stack([c * right + s * down, -s * right + c * down, forward], 1)


def pose_at(path, t):
    """T_world_cam (4 x 4) at time t seconds."""
    mean_radius = 0.5 * (path.radii[0] + path.radii[1])
    angle = path.phase + path.direction * path.speed / mean_radius * t
    position = np.array([path.centre[0] + path.radii[0] * np.cos(angle),
                         path.centre[1] + path.radii[1] * np.sin(angle),
                         path.height + 0.12 * np.sin(0.9 * t + path.phase)])
    outward = np.arctan2(np.sin(angle) * path.radii[1], np.cos(angle) * path.radii[0])
    yaw = outward + path.sweep * np.sin(2 * np.pi * t / 11.0 + path.phase) + path.fast_yaw * np.sin(2 * np.pi * 0.6 * t)
    pitch = -0.08 + 0.1 * np.sin(2 * np.pi * t / 7.0) + path.fast_pitch * np.sin(2 * np.pi * 0.8 * t + 1.0)
    roll = 0.05 * np.sin(2 * np.pi * t / 5.0 + path.phase)
    forward = np.array([np.cos(pitch) * np.cos(yaw), np.cos(pitch) * np.sin(yaw), np.sin(pitch)])
    pose = np.eye(4)
    pose[:3, :3] = look_rotation(forward, roll)
    pose[:3, 3] = position
    return pose
