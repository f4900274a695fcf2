"""Procedural albedo textures, deterministic from a numpy Generator.

A texture is a float32 array of albedo in [0.03, 0.97]: octaves of smooth noise plus shapes
(rectangles, discs, bars, stripes, small glyph grids) that give corners at several scales, the
way posters, furniture and tiles do. `contrast` scales the deviation from mid-grey: 1 is an
ordinary room, about 0.15 a weakly textured one.
"""
import cv2
import numpy as np


def smooth_noise(rng, height, width, cell):
    """Noise with features about `cell` texels wide (bicubic upsampling of a coarse grid)."""
    small = rng.random((max(2, height // cell + 2), max(2, width // cell + 2)), dtype=np.float32)
    big = cv2.resize(small, (width + 2 * cell, height + 2 * cell), interpolation=cv2.INTER_CUBIC)
    return big[cell:cell + height, cell:cell + width]


def _draw_shapes(rng, canvas, count, min_size):
    height, width = canvas.shape
    for _ in range(count):
        kind = rng.integers(0, 5)
        value = float(rng.uniform(-0.5, 0.5))
        size = int(rng.integers(min_size, max(min_size + 1, min(height, width) // 3)))
        x, y = int(rng.integers(0, width)), int(rng.integers(0, height))
        if kind == 0:
            cv2.rectangle(canvas, (x, y), (x + size, y + int(size * rng.uniform(0.3, 1.5))), value, -1)
        elif kind == 1:
            cv2.circle(canvas, (x, y), size // 2, value, -1)
        elif kind == 2:
            angle = rng.uniform(0, np.pi)
            dx, dy = int(size * np.cos(angle)), int(size * np.sin(angle))
            cv2.line(canvas, (x - dx, y - dy), (x + dx, y + dy), value, max(2, size // 10))
        elif kind == 3:  # stripes
            step = max(4, size // 6)
            for k in range(6):
                if k % 2 == 0:
                    cv2.rectangle(canvas, (x + k * step, y), (x + (k + 1) * step - 1, y + size), value, -1)
        else:  # a glyph grid, like a printed page
            cell = max(4, size // 8)
            for gy in range(6):
                for gx in range(8):
                    if rng.random() < 0.55:
                        cv2.rectangle(canvas, (x + gx * cell, y + gy * cell),
                                      (x + gx * cell + cell // 2, y + gy * cell + cell // 2), value, -1)


def make_texture(rng, height, width, contrast=1.0, shapes_per_mpx=400, min_feature=3):
    """An albedo texture of height x width texels; features at least `min_feature` texels wide."""
    base = (0.45 * smooth_noise(rng, height, width, max(8, min(height, width) // 4))
            + 0.35 * smooth_noise(rng, height, width, 24)
            + 0.20 * smooth_noise(rng, height, width, 6)) - 0.5
    shapes = np.zeros((height, width), np.float32)
    _draw_shapes(rng, shapes, max(3, int(shapes_per_mpx * height * width / 1e6)), 4 * min_feature)
    detail = base * 0.9 + shapes
    detail = cv2.GaussianBlur(detail, (0, 0), 0.5 * min_feature / 2.0)
    mean = float(rng.uniform(0.35, 0.65))
    return np.clip(mean + contrast * detail, 0.03, 0.97).astype(np.float32)
