"""Ray-cast rendering of a slamseq.scene.Room: radiance and depth for a pinhole camera.

Camera frame as OpenCV's (x right, y down, z forward); a pose is T_world_cam (4 x 4), mapping
camera coordinates to world coordinates. Depth is the camera-frame z of the first surface hit.
Radiance is albedo x (ambient + point lights, Lambert with 1 / (1 + d^2 / r^2) falloff): it does
not depend on the viewing direction, so a surface point has the same value in every frame lit
the same way (the reprojection test relies on it).
"""
from dataclasses import dataclass

import cv2
import numpy as np


@dataclass(frozen=True)
class Camera:
    width: int
    height: int
    fx: float
    fy: float
    cx: float
    cy: float

    @staticmethod
    def default(width=640, height=480):
        focal = 0.78125 * width  # 500 px at 640: a 65 degree horizontal field of view
        return Camera(width, height, focal, focal, (width - 1) / 2.0, (height - 1) / 2.0)

    def matrix(self):
        return np.array([[self.fx, 0, self.cx], [0, self.fy, self.cy], [0, 0, 1.0]])


@dataclass(frozen=True)
class Light:
    position: tuple
    power: float
    reach: float = 4.0  # metres at which the falloff halves the power


def _rays(camera, rotation):
    """World directions of the pixels' rays, scaled so camera z = 1 (t along them is depth): 3 arrays H x W."""
    u = (np.arange(camera.width, dtype=np.float64) - camera.cx) / camera.fx
    v = (np.arange(camera.height, dtype=np.float64) - camera.cy) / camera.fy
    return [rotation[k, 0] * u[None, :] + rotation[k, 1] * v[:, None] + rotation[k, 2] for k in range(3)]


def _screen_bounds(box, camera, pose):
    """The pixel rectangle (rows, cols slices) a box can cover, or everything if it reaches behind the camera."""
    corners = np.array([[x, y, z] for x in (box.low[0], box.high[0]) for y in (box.low[1], box.high[1]) for z in (box.low[2], box.high[2])])
    cam = (corners - pose[:3, 3]) @ pose[:3, :3]
    if np.any(cam[:, 2] < 0.05):
        return slice(0, camera.height), slice(0, camera.width)
    u = camera.fx * cam[:, 0] / cam[:, 2] + camera.cx
    v = camera.fy * cam[:, 1] / cam[:, 2] + camera.cy
    cols = slice(int(np.clip(np.floor(u.min()) - 1, 0, camera.width)), int(np.clip(np.ceil(u.max()) + 2, 0, camera.width)))
    rows = slice(int(np.clip(np.floor(v.min()) - 1, 0, camera.height)), int(np.clip(np.ceil(v.max()) + 2, 0, camera.height)))
    return rows, cols


def cast(room, camera, pose):
    """(depth, face id, world points) per pixel, flattened; depth is +inf where nothing is hit."""
    rotation, origin = pose[:3, :3], pose[:3, 3]
    rays = _rays(camera, rotation)
    with np.errstate(divide="ignore", invalid="ignore"):
        inverse = [1.0 / r for r in rays]
        # Room, from inside: the wall each ray leaves through, axis by axis.
        depth = np.full((camera.height, camera.width), np.inf)
        face = np.zeros((camera.height, camera.width), np.int64)
        for k in range(3):
            t = (np.where(rays[k] > 0, room.size[k], 0.0) - origin[k]) * inverse[k]
            t[~np.isfinite(t)] = np.inf
            closer = t < depth
            depth[closer] = t[closer]
            face[closer] = (2 * k + (rays[k] > 0))[closer]
        # Boxes, from outside: slab test over the pixels each box can cover.
        for index, box in enumerate(room.boxes):
            rows, cols = _screen_bounds(box, camera, pose)
            t_in, t_out = [], []
            for k in range(3):
                low = (box.low[k] - origin[k]) * inverse[k][rows, cols]
                high = (box.high[k] - origin[k]) * inverse[k][rows, cols]
                t_in.append(np.minimum(low, high))
                t_out.append(np.maximum(low, high))
            t_near = np.maximum(np.maximum(t_in[0], t_in[1]), t_in[2])
            t_far = np.minimum(np.minimum(t_out[0], t_out[1]), t_out[2])
            region_depth = depth[rows, cols]
            hit = (t_near <= t_far) & (t_near > 1e-6) & (t_near < region_depth)
            if not hit.any():
                continue
            region_face = face[rows, cols]
            region_depth[hit] = t_near[hit]
            for k in (2, 1, 0):  # the entry face: the axis whose slab is entered last
                on_axis = hit & (t_in[k] == t_near)
                region_face[on_axis] = 6 + 6 * index + 2 * k + (rays[k][rows, cols] < 0)[on_axis]
    depth = depth.reshape(-1)
    points = origin + np.stack([r.reshape(-1) for r in rays], 1) * depth[:, None]
    return depth, face.reshape(-1), points


@dataclass
class Surface:
    """What a camera sees, before lighting: per pixel (flattened) depth, world point, normal,
    atlas coordinates at mip level 0 and the mip level to sample. Rooms made from the same seed
    share it (their geometry is the same; only the textures differ)."""
    shape: tuple
    depth: np.ndarray
    points: np.ndarray
    normals: np.ndarray
    atlas_x: np.ndarray
    atlas_y: np.ndarray
    level: np.ndarray


def surface(room, camera, pose, texel):
    depth, face, points = cast(room, camera, pose)
    u_axis = np.array([(f.axis + 1) % 3 for f in room.faces])[face]
    v_axis = np.array([(f.axis + 2) % 3 for f in room.faces])[face]
    low = np.array([f.low for f in room.faces])[face]
    rows = np.arange(len(points))
    atlas_x = np.array([f.atlas_x for f in room.faces], np.float64)[face] + (points[rows, u_axis] - low[:, 0]) / texel
    atlas_y = np.array([f.atlas_y for f in room.faces], np.float64)[face] + (points[rows, v_axis] - low[:, 1]) / texel
    normals = np.zeros((len(room.faces), 3))
    normals[np.arange(len(room.faces)), [f.axis for f in room.faces]] = [f.normal_sign for f in room.faces]
    normals = normals[face]
    # Texels per pixel: distance over focal, stretched by the obliqueness of the face.
    view = points - pose[:3, 3]
    cosine = np.abs(np.einsum("ij,ij->i", normals, view)) / np.maximum(np.linalg.norm(view, axis=1), 1e-9)
    footprint = depth / camera.fx / texel / np.sqrt(np.maximum(cosine, 0.15))
    level = np.clip(np.log2(np.maximum(footprint, 1e-6)), 0.0, len(room.atlas) - 1.0)
    return Surface((camera.height, camera.width), depth, points, normals, atlas_x, atlas_y, level)


def albedo(atlas_levels, seen):
    """Bilinear, mip-mapped albedo of the surface points: levels blended linearly in seen.level."""
    total = np.zeros(len(seen.level))
    for n, image in enumerate(atlas_levels):
        weight = np.clip(1.0 - np.abs(seen.level - n), 0.0, 1.0)
        scale = 0.5 ** n
        map_x = ((seen.atlas_x + 0.5) * scale - 0.5).astype(np.float32).reshape(seen.shape)
        map_y = ((seen.atlas_y + 0.5) * scale - 0.5).astype(np.float32).reshape(seen.shape)
        total += weight * cv2.remap(image, map_x, map_y, cv2.INTER_LINEAR, borderMode=cv2.BORDER_REPLICATE).reshape(-1)
    return total


def radiance(albedo_values, seen, lights, ambient):
    """albedo x (ambient + sum of point lights), H x W float32."""
    light = np.full(len(seen.points), ambient)
    for source in lights:
        to_light = np.asarray(source.position, np.float64) - seen.points
        distance2 = np.einsum("ij,ij->i", to_light, to_light)
        lambert = np.maximum(np.einsum("ij,ij->i", seen.normals, to_light) / np.sqrt(np.maximum(distance2, 1e-12)), 0.0)
        light += source.power * lambert / (1.0 + distance2 / source.reach ** 2)
    return (albedo_values * light).reshape(seen.shape).astype(np.float32)


def render(room, camera, pose, lights, ambient, texel):
    """(radiance float32 H x W, depth float32 H x W) of the room seen from pose (T_world_cam)."""
    seen = surface(room, camera, pose, texel)
    return radiance(albedo(room.atlas, seen), seen, lights, ambient), seen.depth.reshape(seen.shape).astype(np.float32)


def project(camera, pose, points):
    """Pixel coordinates (N x 2) and camera depth (N) of world points seen from pose."""
    cam = (points - pose[:3, 3]) @ pose[:3, :3]
    z = cam[:, 2]
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.stack([camera.fx * cam[:, 0] / z + camera.cx, camera.fy * cam[:, 1] / z + camera.cy], 1), z
