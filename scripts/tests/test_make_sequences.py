"""The sequence generator's ground truth and layouts (scripts/make_sequences.py), on small frames.

The poses are checked through the images: a point seen in one frame, placed in the world with
the rendered depth and the frame's T_world_cam, projected into another frame with that frame's
pose, must land where the second image shows the same surface (same radiance), unless something
occludes it there (the second frame's depth tells).
"""
import filecmp
import os
import subprocess
import sys

import cv2
import numpy as np
import pytest

SCRIPTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
sys.path.insert(0, SCRIPTS)

from slamseq import families  # noqa: E402
from slamseq.layouts import quaternion_wxyz  # noqa: E402
from slamseq.paths import pose_at  # noqa: E402
from slamseq.render import Camera, project, render  # noqa: E402
from slamseq.scene import TEXEL  # noqa: E402
from slamseq.sequence import Scene, right_of  # noqa: E402

CAMERA = Camera.default(160, 120)


@pytest.fixture(scope="module")
def scene():
    return Scene(5)


def reprojection_residual(scene, pose_a, pose_b, claimed_b=None):
    """Median |radiance_a - radiance_b at the reprojection| over points visible in both, and how many."""
    lights, ambient = families.lights(families.BY_NAME["baseline"], scene.room.size, 0.0)
    image_a, depth_a = render(scene.room, CAMERA, pose_a, lights, ambient, TEXEL)
    image_b, depth_b = render(scene.room, CAMERA, pose_b, lights, ambient, TEXEL)
    v, u = np.mgrid[4:CAMERA.height - 4:3, 4:CAMERA.width - 4:3]
    z = depth_a[v, u].astype(np.float64)
    cam = np.stack([(u - CAMERA.cx) / CAMERA.fx * z, (v - CAMERA.cy) / CAMERA.fy * z, z], -1).reshape(-1, 3)
    world = cam @ pose_a[:3, :3].T + pose_a[:3, 3]
    pixels, z_b = project(CAMERA, pose_b if claimed_b is None else claimed_b, world)
    inside = (pixels[:, 0] > 1) & (pixels[:, 0] < CAMERA.width - 2) & (pixels[:, 1] > 1) & (pixels[:, 1] < CAMERA.height - 2) & (z_b > 0)
    pixels, z_b, values_a = pixels[inside], z_b[inside], image_a[v, u].reshape(-1)[inside]
    seen_depth = cv2.remap(depth_b, pixels[:, 0].astype(np.float32), pixels[:, 1].astype(np.float32), cv2.INTER_NEAREST).reshape(-1)
    visible = np.abs(seen_depth - z_b) < 0.02 * z_b
    values_b = cv2.remap(image_b, pixels[:, 0].astype(np.float32), pixels[:, 1].astype(np.float32), cv2.INTER_LINEAR).reshape(-1)
    return float(np.median(np.abs(values_a - values_b)[visible])), int(visible.sum())


def test_points_reproject_onto_the_same_surface_between_frames(scene):
    path = scene.paths[False]
    residual, count = reprojection_residual(scene, pose_at(path, 0.0), pose_at(path, 0.6))
    assert count > 500
    assert residual < 0.01  # radiance units (about 2 grey levels)


def test_a_wrong_pose_is_caught(scene):
    """The check has teeth: a pose off by 1 degree gives a much larger residual."""
    path = scene.paths[False]
    pose_b = pose_at(path, 0.6)
    tilt = np.eye(4)
    c, s = np.cos(np.radians(1.0)), np.sin(np.radians(1.0))
    tilt[:3, :3] = [[c, 0, s], [0, 1, 0], [-s, 0, c]]
    good, _ = reprojection_residual(scene, pose_at(path, 0.0), pose_b)
    bad, _ = reprojection_residual(scene, pose_at(path, 0.0), pose_b, claimed_b=pose_b @ tilt)
    assert bad > 4 * good


def test_stereo_pair_agrees_with_the_baseline(scene):
    pose = pose_at(scene.paths[True], 1.3)
    residual, count = reprojection_residual(scene, pose, right_of(pose))
    assert count > 500 and residual < 0.01


def test_paths_translate(scene):
    for fast in (False, True):
        positions = np.array([pose_at(scene.paths[fast], t)[:3, 3] for t in np.arange(0, 15, 0.5)])
        assert np.linalg.norm(positions[-1] - positions[0]) > 1.5
        assert np.all(np.linalg.norm(np.diff(positions, axis=0), axis=1) > 0.1)  # never a pure pan


def test_quaternion_round_trip():
    rng = np.random.default_rng(1)
    for _ in range(20):
        q = rng.normal(size=4)
        q /= np.linalg.norm(q)
        w, x, y, z = q
        m = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                      [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                      [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
        assert np.allclose(quaternion_wxyz(m), q if w >= 0 else -q)


def generate(out):
    subprocess.run([sys.executable, os.path.join(SCRIPTS, "make_sequences.py"), str(out), "--seed", "5", "--seconds", "0.15", "--fps", "20",
                    "--width", "96", "--height", "72", "--families", "baseline,fast_rotation,low_light", "--depth"],
                   check=True, capture_output=True)


def test_layouts_are_complete_consistent_and_deterministic(tmp_path):
    generate(tmp_path / "a")
    generate(tmp_path / "b")
    folder = tmp_path / "a" / "baseline"
    times = [int(line) for line in (folder / "times.txt").read_text().split()]
    assert len(times) == 3 and times == sorted(times)
    for cam in ("cam0", "cam1"):
        assert sorted(os.listdir(folder / "mav0" / cam / "data")) == sorted(f"{ns}.png" for ns in times)
        image = cv2.imread(str(folder / "mav0" / cam / "data" / f"{times[0]}.png"), cv2.IMREAD_UNCHANGED)
        assert image.shape == (72, 96) and image.dtype == np.uint8
    rgb = [line.split() for line in (folder / "rgb.txt").read_text().splitlines() if not line.startswith("#")]
    assert [float(t) for t, _ in rgb] == pytest.approx([ns / 1e9 for ns in times])
    assert all(os.path.isfile(folder / name) for _, name in rgb)
    gt = np.loadtxt(folder / "groundtruth.txt")
    euroc = np.loadtxt(folder / "mav0/state_groundtruth_estimate0/data.csv", delimiter=",")
    assert np.allclose(gt[:, 1:4], euroc[:, 1:4]) and np.allclose(gt[:, [7, 4, 5, 6]], euroc[:, 4:8])
    scene = Scene(5)
    assert np.allclose(gt[1, 1:4], pose_at(scene.paths[False], 1 / 20)[:3, 3], atol=1e-8)
    depth = cv2.imread(str(folder / "depth" / f"{times[0]}.png"), cv2.IMREAD_UNCHANGED)
    assert depth.dtype == np.uint16 and depth.min() > 0
    stereo = cv2.FileStorage(str(folder / "stereo.yaml"), cv2.FILE_STORAGE_READ)
    assert stereo.getNode("Camera.type").string() == "PinHole"
    assert stereo.getNode("Stereo.T_c1_c2").mat()[0, 3] == pytest.approx(0.12)
    assert stereo.getNode("ORBextractor.nFeatures").real() == 1000
    mono = cv2.FileStorage(str(folder / "mono.yaml"), cv2.FILE_STORAGE_READ)
    assert mono.getNode("Camera2.fx").empty() and mono.getNode("Camera1.fx").real() == pytest.approx(75.0)
    comparison = filecmp.dircmp(tmp_path / "a", tmp_path / "b")
    assert not comparison.diff_files and not comparison.left_only and not comparison.right_only
    for family in ("baseline", "fast_rotation", "low_light"):
        for cam in ("cam0", "cam1"):
            sub = filecmp.dircmp(tmp_path / "a" / family / "mav0" / cam / "data", tmp_path / "b" / family / "mav0" / cam / "data")
            assert not sub.diff_files


def test_families_differ_from_baseline_in_their_one_thing(tmp_path):
    generate(tmp_path)
    name = sorted(os.listdir(tmp_path / "baseline" / "mav0" / "cam0" / "data"))[1]
    read = lambda family: cv2.imread(str(tmp_path / family / "mav0" / "cam0" / "data" / name), cv2.IMREAD_GRAYSCALE).astype(float)
    assert read("low_light").mean() < 0.6 * read("baseline").mean()
    assert np.allclose(np.loadtxt(tmp_path / "low_light" / "groundtruth.txt"), np.loadtxt(tmp_path / "baseline" / "groundtruth.txt"))
    assert not np.allclose(np.loadtxt(tmp_path / "fast_rotation" / "groundtruth.txt"), np.loadtxt(tmp_path / "baseline" / "groundtruth.txt"))


def test_unknown_family_is_a_clear_error(tmp_path):
    result = subprocess.run([sys.executable, os.path.join(SCRIPTS, "make_sequences.py"), str(tmp_path), "--families", "baseline,fog"],
                            capture_output=True, text=True)
    assert result.returncode != 0 and "fog" in result.stderr


def test_every_seed_builds_its_room_or_is_refused_with_a_reason():
    """Seed 977 died in _pack ("could not broadcast ... (117,196) into shape (117,191)"): a face was
    kept on a shelf when it fitted without its right padding. Every seed tried builds its atlas,
    each face's padded block inside it, or make_room says why not."""
    from slamseq.scene import ATLAS_WIDTH, PADDING, make_room
    for seed in (977, 5, 17, 23, 101):
        try:
            room = make_room(seed)
        except ValueError as refusal:
            assert "atlas" in str(refusal)
            continue
        atlas = room.atlas[0]
        assert atlas.shape[1] == ATLAS_WIDTH
        for face in room.faces:
            assert face.atlas_x >= PADDING and face.atlas_y >= PADDING
            extent = np.ceil((face.high - face.low) / TEXEL).astype(int) + 1
            assert face.atlas_x + extent[0] + PADDING <= atlas.shape[1]
            assert face.atlas_y + extent[1] + PADDING <= atlas.shape[0]


def flat_block_share(image, block=32):
    """Share of block x block tiles whose smoothed grey levels vary by less than 2.5 (sd): no texture, only noise."""
    grey = image.astype(np.float64)
    flat = total = 0
    for y in range(0, grey.shape[0] - block + 1, block):
        for x in range(0, grey.shape[1] - block + 1, block):
            total += 1
            flat += cv2.GaussianBlur(grey[y:y + block, x:x + block], (0, 0), 2).std() < 2.5
    return flat / total


def test_blank_walls_are_about_half_flat_and_noisy_where_baseline_is_textured(tmp_path):
    subprocess.run([sys.executable, os.path.join(SCRIPTS, "make_sequences.py"), str(tmp_path), "--seed", "977", "--seconds", "1.0", "--fps", "2",
                    "--width", "320", "--height", "240", "--families", "baseline,blank_walls"], check=True, capture_output=True)
    for name in sorted(os.listdir(tmp_path / "baseline" / "mav0" / "cam0" / "data")):
        read = lambda family: cv2.imread(str(tmp_path / family / "mav0" / "cam0" / "data" / name), cv2.IMREAD_GRAYSCALE)
        blank, baseline = read("blank_walls"), read("baseline")
        assert 0.3 <= flat_block_share(blank) <= 0.75
        assert flat_block_share(baseline) < 0.1
        noise = blank.astype(np.float64) - cv2.GaussianBlur(blank.astype(np.float64), (0, 0), 2)
        assert noise.std() > 3.0  # shot and read noise: what FAST at minThFAST picks up on a blank wall
    assert np.allclose(np.loadtxt(tmp_path / "blank_walls" / "groundtruth.txt"), np.loadtxt(tmp_path / "baseline" / "groundtruth.txt"))
