"""A room of textured, axis-aligned faces: walls, floor, ceiling and boxes that occlude.

World frame: x, y horizontal, z up, metres. The room is [0, W] x [0, D] x [0, H]; boxes stand on
the floor along the walls, and a pillar and a table stand in the middle, inside the loop the
camera paths follow (slamseq.paths), so objects pass in front of the walls as the camera moves.
Every face has its own texture in one atlas (three mip levels), `texel` metres per texel.
"""
from dataclasses import dataclass, field

import cv2
import numpy as np

from slamseq.textures import make_texture

TEXEL = 0.005  # metres per texel at mip level 0
PADDING = 8    # texels between faces in the atlas (mip levels 1 and 2 stay inside their face)
ATLAS_WIDTH = 4096
LOOP_CLEARANCE = np.array([2.3, 1.9])  # half-axes of the ellipse boxes keep out of: the loop plus 0.5 m


@dataclass
class Box:
    low: np.ndarray   # (3,) min corner
    high: np.ndarray  # (3,) max corner


@dataclass
class Face:
    axis: int         # the normal's axis
    coordinate: float  # the plane: X[axis] == coordinate
    normal_sign: float
    low: np.ndarray   # (2,) min of the two in-plane coordinates (axes (axis+1)%3, (axis+2)%3)
    high: np.ndarray
    atlas_x: int = 0
    atlas_y: int = 0


@dataclass
class Room:
    size: np.ndarray                 # (3,) W, D, H
    boxes: list                      # Box, rendered from outside
    faces: list                      # Face: 6 room faces (ids 0..5: axis*2 + side), then 6 per box
    atlas: list = field(default_factory=list)  # float32 albedo, mip levels 0..2

    @property
    def centre(self):
        return np.array([self.size[0] / 2, self.size[1] / 2, 0.0])


def _in_plane_axes(axis):
    return (axis + 1) % 3, (axis + 2) % 3


def _box_faces(low, high, inward):
    faces = []
    for axis in range(3):
        u, v = _in_plane_axes(axis)
        for side, coordinate in enumerate((low[axis], high[axis])):
            outward = -1.0 if side == 0 else 1.0
            faces.append(Face(axis, float(coordinate), -outward if inward else outward,
                              np.array([low[u], low[v]]), np.array([high[u], high[v]])))
    return faces


def _place_boxes(rng, size, count):
    """Boxes along the walls, clear of the camera's loop (slamseq.paths keeps within 2 m of the centre)."""
    boxes = []
    centre = size[:2] / 2
    attempts = 0
    while len(boxes) < count and attempts < 500:
        attempts += 1
        extent = np.array([rng.uniform(0.4, 1.2), rng.uniform(0.4, 1.2), rng.uniform(0.5, 1.8)])
        corner = np.array([rng.uniform(0.05, size[0] - extent[0] - 0.05), rng.uniform(0.05, size[1] - extent[1] - 0.05), 0.0])
        nearest = np.clip(centre, corner[:2], corner[:2] + extent[:2])
        if np.sum(((nearest - centre) / LOOP_CLEARANCE) ** 2) < 1.0:
            continue
        if any(np.all(corner[:2] < b.high[:2] + 0.1) and np.all(b.low[:2] < corner[:2] + extent[:2] + 0.1) for b in boxes):
            continue
        boxes.append(Box(corner, corner + extent))
    return boxes


def _centre_objects(rng, size):
    """A pillar and a low table inside the loop: they cross the view of the opposite walls."""
    centre = size / 2
    pillar_half = rng.uniform(0.12, 0.2)
    offset = np.array([rng.uniform(-0.3, 0.3), rng.uniform(-0.2, 0.2), 0.0])
    pillar = Box(np.array([centre[0] - pillar_half, centre[1] - pillar_half, 0.0]) + offset,
                 np.array([centre[0] + pillar_half, centre[1] + pillar_half, size[2]]) + offset)
    table_at = centre + np.array([rng.choice([-1, 1]) * 0.45, rng.uniform(-0.2, 0.2), 0.0])
    table = Box(np.array([table_at[0] - 0.25, table_at[1] - 0.2, 0.0]), np.array([table_at[0] + 0.25, table_at[1] + 0.2, 0.75]))
    return [pillar, table]


def _blank_wall(rng, texture, is_wall):
    """A flat face (one albedo, a gradient of at most 1%) with, on walls, one or two posters: pieces
    of the face's own texture 0.5-1.1 m wide. Floors and ceilings stay bare."""
    height, width = texture.shape
    albedo = float(rng.uniform(0.55, 0.8))
    ramp = np.linspace(-0.005, 0.005, width, dtype=np.float32)[None, :]
    blank = np.full((height, width), albedo, np.float32) + ramp
    for _ in range(int(rng.integers(1, 3)) if is_wall else 0):
        w = min(width - 2, int(rng.uniform(0.5, 1.1) / TEXEL))
        h = min(height - 2, int(w * rng.uniform(0.6, 1.4)))
        if w < 8 or h < 8:
            continue
        x, y = int(rng.integers(0, width - w)), int(rng.integers(0, height - h))
        blank[y:y + h, x:x + w] = texture[y:y + h, x:x + w]
    return blank


def _pack(faces, rng, contrast, shapes_per_mpx, blank_rng=None):
    """Textures for every face, shelf-packed into one atlas; returns the atlas (level 0). With
    blank_rng, the room's own six faces are blank walls (_blank_wall); the textures are drawn
    first either way, so the boxes keep theirs."""
    textures = []
    for face in faces:
        extent = face.high - face.low
        width, height = (int(np.ceil(e / TEXEL)) + 1 for e in extent)
        textures.append(make_texture(rng, height, width, contrast, shapes_per_mpx))
    if blank_rng is not None:
        for i in range(6):  # ids axis * 2 + side; axis 2 is the floor and the ceiling
            textures[i] = _blank_wall(blank_rng, textures[i], is_wall=faces[i].axis != 2)
    order = sorted(range(len(faces)), key=lambda i: -textures[i].shape[0])
    x = y = shelf = 0
    for i in order:
        height, width = textures[i].shape
        if width + 2 * PADDING > ATLAS_WIDTH:
            raise ValueError(f"a face of {width} texels does not fit the {ATLAS_WIDTH}-texel atlas")
        # A face takes its padding on both sides: x + PADDING + width + PADDING must fit.
        if x + width + 2 * PADDING > ATLAS_WIDTH:
            x, y, shelf = 0, y + shelf + PADDING, 0
        faces[i].atlas_x, faces[i].atlas_y = x + PADDING, y + PADDING
        x += width + PADDING
        shelf = max(shelf, height + PADDING)
    atlas = np.full((y + shelf + 2 * PADDING, ATLAS_WIDTH), 0.5, np.float32)
    for face, texture in zip(faces, textures):
        height, width = texture.shape
        block = np.pad(texture, PADDING, mode="edge")
        atlas[face.atlas_y - PADDING:face.atlas_y + height + PADDING, face.atlas_x - PADDING:face.atlas_x + width + PADDING] = block
    return atlas


def make_room(seed, contrast=1.0, shapes_per_mpx=400, blank_walls=False):
    """The room of `seed`: the same seed gives the same geometry (whatever the textures' contrast
    and shapes) and the same textures. blank_walls: flat walls, floor and ceiling with a few
    posters, the boxes textured as in the normal room."""
    rng = np.random.default_rng([seed, 0])
    size = np.array([rng.uniform(7.5, 9.0), rng.uniform(6.0, 7.0), rng.uniform(2.7, 3.2)])
    boxes = _place_boxes(rng, size, int(rng.integers(7, 11))) + _centre_objects(rng, size)
    faces = _box_faces(np.zeros(3), size, inward=True)
    for box in boxes:
        faces += _box_faces(box.low, box.high, inward=False)
    atlas = _pack(faces, np.random.default_rng([seed, 1]), contrast, shapes_per_mpx,
                  np.random.default_rng([seed, 3]) if blank_walls else None)
    levels = [atlas]
    for _ in range(2):
        levels.append(cv2.pyrDown(levels[-1]))
    return Room(size, boxes, faces, levels)
