"""Rendering the frames of several families at once.

Families that share a path share the ray casting of each frame (slamseq.render.surface): the
expensive part is done once per frame, camera and path, and each family only samples its
textures, lights the points and runs its sensor.
"""
import os

import cv2
import numpy as np

from slamseq import families as fam
from slamseq.layouts import SequenceWriter, timestamp_ns
from slamseq.paths import pose_at, random_path
from slamseq.render import albedo, project, radiance, surface
from slamseq.scene import TEXEL, make_room

BASELINE_M = 0.12  # stereo: cam1 sits 12 cm to the right of cam0 (x of cam0)
WEAK_CONTRAST = 0.2
WEAK_SHAPES_PER_MPX = 60


def right_of(pose, baseline=BASELINE_M):
    offset = np.eye(4)
    offset[0, 3] = baseline
    return pose @ offset


def motion_blurred(sharp, seen, camera, path, t, exposure, cam_offset, taps=7):
    """Average of the image over the exposure: each pixel samples the sharp image where its
    surface point was at times t + s across the exposure. Positions come from the exact poses
    and depth at the exposure's ends, linearly in between; occlusion changes within the
    exposure are ignored."""
    here, _ = project(camera, cam_offset(pose_at(path, t)), seen.points)
    start, _ = project(camera, cam_offset(pose_at(path, t - exposure / 2)), seen.points)
    end, _ = project(camera, cam_offset(pose_at(path, t + exposure / 2)), seen.points)
    total = np.zeros_like(sharp)
    for s in np.linspace(0.0, 1.0, taps):
        source = (2 * here - (start + s * (end - start))).reshape(*sharp.shape, 2).astype(np.float32)
        total += cv2.remap(sharp, source[..., 0], source[..., 1], cv2.INTER_LINEAR, borderMode=cv2.BORDER_REFLECT)
    return total / taps


class Scene:
    """A seed's room (normal and weak textures) and its two paths."""

    def __init__(self, seed):
        self.seed = seed
        self.room = make_room(seed)
        self.weak_room = None
        self.blank_room = None
        # The same draws for both paths: the fast one is the main one plus the oscillations.
        self.paths = {fast: random_path(np.random.default_rng([seed, 2]), self.room.size, fast_rotation=fast) for fast in (False, True)}

    def atlas(self, family):
        if family.blank_walls:
            if self.blank_room is None:
                self.blank_room = make_room(self.seed, blank_walls=True)
            return self.blank_room.atlas
        if not family.weak_texture:
            return self.room.atlas
        if self.weak_room is None:
            self.weak_room = make_room(self.seed, WEAK_CONTRAST, WEAK_SHAPES_PER_MPX)
        return self.weak_room.atlas


def render_frame(scene, family, camera, frame, fps, seen_by_cam):
    """(left, right) uint8 images of one family at one frame; seen_by_cam: surfaces of cam0, cam1."""
    t = frame / fps
    path = scene.paths[family.fast_rotation]
    lights, ambient = fam.lights(family, scene.room.size, t)
    images = []
    for cam_index, seen in enumerate(seen_by_cam):
        sharp = radiance(albedo(scene.atlas(family), seen), seen, lights, ambient)
        offset = right_of if cam_index else (lambda pose: pose)
        if family.exposure > 0.01:
            sharp = motion_blurred(sharp, seen, camera, path, t, family.exposure, offset)
        rng = np.random.default_rng([scene.seed, fam.FAMILIES.index(family), frame, cam_index])
        images.append(fam.sensor(family, sharp, t, rng))
    return images


def _render_frames(job):
    """Renders frames [first, last) of every chosen family into its folder (one worker's share)."""
    out_folder, family_names, seed, fps, camera, with_depth, first, last = job
    scene = Scene(seed)
    chosen = [fam.BY_NAME[name] for name in family_names]
    writers = {f.name: SequenceWriter(os.path.join(out_folder, f.name), with_depth) for f in chosen}
    for fast in (False, True):
        group = [f for f in chosen if f.fast_rotation == fast]
        if not group:
            continue
        path = scene.paths[fast]
        for frame in range(first, last):
            pose = pose_at(path, frame / fps)
            seen = [surface(scene.room, camera, pose, TEXEL), surface(scene.room, camera, right_of(pose), TEXEL)]
            for family in group:
                left, right = render_frame(scene, family, camera, frame, fps, seen)
                writers[family.name].add(timestamp_ns(frame, fps), pose, left, right, seen[0].depth.reshape(seen[0].shape))
    return {name: writer.rows for name, writer in writers.items()}


def make_sequences(out_folder, family_names, seed, seconds, fps, camera, with_depth, jobs=1, progress=None):
    """Writes out_folder/<family>/ for each family name, frames split in chunks over `jobs`
    processes (the output does not depend on it); returns the folders."""
    frames = int(round(seconds * fps))
    chunk = max(5, -(-frames // (3 * jobs)))
    work = [(out_folder, family_names, seed, fps, camera, with_depth, first, min(frames, first + chunk)) for first in range(0, frames, chunk)]
    rows = {name: [] for name in family_names}
    if jobs > 1:
        import multiprocessing
        with multiprocessing.get_context("fork").Pool(jobs) as pool:
            results = pool.imap(_render_frames, work)
            for done, result in enumerate(results):
                for name in family_names:
                    rows[name] += result[name]
                if progress:
                    progress(min(frames, (done + 1) * chunk), frames)
    else:
        for done, job in enumerate(work):
            result = _render_frames(job)
            for name in family_names:
                rows[name] += result[name]
            if progress:
                progress(min(frames, (done + 1) * chunk), frames)
    for name in family_names:
        family = fam.BY_NAME[name]
        writer = SequenceWriter(os.path.join(out_folder, name), with_depth)
        writer.rows = sorted(rows[name], key=lambda row: row[0])
        writer.finish(camera, BASELINE_M, fps, dict(family=name, what=family.what, seed=seed, seconds=seconds))
    return [os.path.join(out_folder, name) for name in family_names]
