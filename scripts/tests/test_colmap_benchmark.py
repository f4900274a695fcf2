"""The COLMAP benchmark's pure parts (scripts/colmapbench/): the camera files, the model reader,
the alignment to the ground truth and the verified share of a database."""
import os
import sqlite3
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))

from colmapbench import metrics, pipelines  # noqa: E402
from colmapbench.model import Model, quaternion_to_rotation, read_text_model  # noqa: E402
from colmapbench.scenes import Camera, Scene, read_camera, read_scene, scene_extent  # noqa: E402


def rotation(axis, angle):
    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * k @ k


K = np.array([[2759.48, 0, 1520.69], [0, 2764.16, 1006.81], [0, 0, 1]])


def camera_text(camera_to_world, centre, size=(3072, 2048)):
    rows = [" ".join(f"{v:.12g}" for v in row) for row in K]
    rows.append("0 0 0")
    rows += [" ".join(f"{v:.12g}" for v in row) for row in camera_to_world]
    rows.append(" ".join(f"{v:.12g}" for v in centre))
    rows.append(f"{size[0]} {size[1]}")
    return "\n".join(rows) + "\n"


def test_a_strecha_camera_reads_as_its_projection(tmp_path):
    camera_to_world = rotation([0.2, 1.0, -0.3], 0.7)
    centre = np.array([-17.6, -3.1, 0.01])
    path = tmp_path / "0000.jpg.camera"
    path.write_text(camera_text(camera_to_world, centre))
    camera = read_camera(str(path))
    np.testing.assert_allclose(camera.K, K)
    np.testing.assert_allclose(camera.world_to_camera, camera_to_world.T, atol=1e-12)
    np.testing.assert_allclose(camera.centre, centre)
    assert (camera.width, camera.height) == (3072, 2048)
    # P = K [R^T | -R^T t]: the centre projects nowhere, a point ahead of the camera in front of it.
    ahead = centre + camera_to_world @ np.array([0.0, 0.0, 5.0])
    assert (camera.world_to_camera @ (ahead - camera.centre))[2] == pytest.approx(5.0)


def test_a_camera_file_of_the_wrong_length_or_rotation_is_named(tmp_path):
    short = tmp_path / "short.camera"
    short.write_text("1 2 3\n")
    with pytest.raises(ValueError, match="short.camera.*26 numbers.*3"):
        read_camera(str(short))
    skewed = tmp_path / "skewed.camera"
    skewed.write_text(camera_text(2 * np.eye(3), np.zeros(3)))
    with pytest.raises(ValueError, match="not a rotation"):
        read_camera(str(skewed))


def test_a_scene_pairs_images_with_cameras_and_ignores_the_rest(tmp_path):
    (tmp_path / "images").mkdir()
    (tmp_path / "gt_dense_cameras").mkdir()
    for i in range(4):
        (tmp_path / "images" / f"{i:04d}.jpg").write_bytes(b"jpeg")
        if i < 3:
            (tmp_path / "gt_dense_cameras" / f"{i:04d}.jpg.camera").write_text(
                camera_text(np.eye(3), [i * 3.0, i * 4.0, 0]))
    (tmp_path / "images" / "K.txt").write_text("K")
    scene = read_scene(str(tmp_path))
    assert scene.images == ["0000.jpg", "0001.jpg", "0002.jpg"]
    assert scene_extent(scene) == pytest.approx(10.0)
    with pytest.raises(ValueError, match="no folder"):
        read_scene(str(tmp_path / "images"))


def synthetic_scene(n=8):
    cameras = {}
    for i in range(n):
        angle = 0.3 * i
        centre = np.array([10 * np.cos(angle), 10 * np.sin(angle), 0.5 * i])
        cameras[f"{i:04d}.jpg"] = Camera(K, rotation([0.1, 1, 0.2 * i], 0.2 + 0.1 * i), centre, 3072, 2048)
    return Scene("synthetic", "", sorted(cameras), cameras)


def model_in_another_frame(scene, scale, turn, shift):
    """The scene's cameras as a model whose world is X_m = scale * turn X_gt + shift."""
    rotations, centres = {}, {}
    for name, camera in scene.cameras.items():
        centres[name] = scale * turn @ camera.centre + shift
        rotations[name] = camera.world_to_camera @ turn.T
    return Model(rotations, centres, np.array([0.4, 0.6]), np.array([2, 4]))


def test_a_known_similarity_is_undone_exactly():
    scene = synthetic_scene()
    model = model_in_another_frame(scene, 0.013, rotation([1, -2, 0.5], 2.1), np.array([4.0, -7.0, 1.0]))
    errors = metrics.pose_errors(model, scene)
    assert np.max(errors["position_error_pct"]) < 1e-9
    assert np.max(errors["rotation_error_deg"]) < 1e-5
    row = metrics.model_summary(model, scene)
    assert (row["registered"], row["points"], row["track_length"]) == (8, 2, 3.0)
    assert row["reprojection_error_px"] == pytest.approx(0.5)


def test_one_misplaced_camera_shows_in_its_errors():
    scene = synthetic_scene()
    turn = rotation([0, 0, 1], 0.4)
    model = model_in_another_frame(scene, 2.0, turn, np.zeros(3))
    name = scene.images[3]
    model.world_to_camera[name] = rotation([1, 0, 0], np.radians(2.0)) @ model.world_to_camera[name]
    errors = metrics.pose_errors(model, scene)
    assert errors["rotation_error_deg"][3] == pytest.approx(2.0, abs=1e-6)
    assert np.delete(errors["rotation_error_deg"], 3).max() < 1e-5
    del model.centres[scene.images[0]]  # not registered: left out, the rest still aligned
    assert metrics.model_summary(model, scene)["registered"] == 7
    assert metrics.pose_errors(model, scene)["position_error_pct"].max() < 1e-9


def test_fewer_than_three_registered_images_have_no_pose_error():
    scene = synthetic_scene(3)
    model = model_in_another_frame(scene, 1.0, np.eye(3), np.zeros(3))
    del model.centres[scene.images[0]]
    assert metrics.pose_errors(model, scene) is None
    assert metrics.model_summary(model, scene)["position_error_median_pct"] is None


def test_a_text_model_reads_poses_points_and_tracks(tmp_path):
    turn = rotation([0.3, 0.4, 1.0], 0.9)
    # COLMAP's qvec of `turn`: w = cos(a/2), (x, y, z) = sin(a/2) axis.
    axis = np.array([0.3, 0.4, 1.0]) / np.linalg.norm([0.3, 0.4, 1.0])
    q = [np.cos(0.45), *(np.sin(0.45) * axis)]
    np.testing.assert_allclose(quaternion_to_rotation(*q), turn, atol=1e-12)
    t = np.array([1.0, 2.0, 3.0])
    (tmp_path / "images.txt").write_text(
        "# Image list\n"
        f"1 {q[0]} {q[1]} {q[2]} {q[3]} {t[0]} {t[1]} {t[2]} 1 0000.jpg\n"
        "10.5 20.5 -1 30.0 40.0 7\n"
        "2 1 0 0 0 0 0 -5 2 with space.jpg\n"
        "\n")
    (tmp_path / "points3D.txt").write_text(
        "# 3D point list\n"
        "7 0 0 0 1 2 3 0.25 1 1 2 0\n"
        "8 1 1 1 1 2 3 0.75 1 0 2 1 3 3\n")
    model = read_text_model(str(tmp_path))
    np.testing.assert_allclose(model.centres["0000.jpg"], -turn.T @ t, atol=1e-12)
    np.testing.assert_allclose(model.centres["with space.jpg"], [0, 0, 5])
    np.testing.assert_allclose(model.point_errors, [0.25, 0.75])
    np.testing.assert_array_equal(model.track_lengths, [2, 3])
    with pytest.raises(ValueError, match="no images.txt"):
        read_text_model(str(tmp_path / "nothing"))


def test_the_verified_share_counts_rows_of_both_tables(tmp_path):
    path = str(tmp_path / "database.db")
    connection = sqlite3.connect(path)
    connection.executescript(
        "CREATE TABLE matches (pair_id INTEGER PRIMARY KEY NOT NULL, rows INTEGER NOT NULL, "
        "cols INTEGER NOT NULL, data BLOB);"
        "CREATE TABLE two_view_geometries (pair_id INTEGER PRIMARY KEY NOT NULL, rows INTEGER NOT NULL,"
        " cols INTEGER NOT NULL, data BLOB, config INTEGER NOT NULL, F BLOB, E BLOB, H BLOB, qvec BLOB,"
        " tvec BLOB);"
        "CREATE TABLE keypoints (image_id INTEGER PRIMARY KEY NOT NULL, rows INTEGER NOT NULL, "
        "cols INTEGER NOT NULL, data BLOB);"
        "INSERT INTO matches VALUES (2147483649, 100, 2, NULL), (2147483650, 50, 2, NULL), "
        "(4294967299, 10, 2, NULL);"
        # pair 1-2 kept 80, pair 1-3 failed (config 1, no rows), pair 2-3 never verified; a
        # geometry without matches (COLMAP's own matcher can leave one) is not counted.
        "INSERT INTO two_view_geometries VALUES (2147483649, 80, 2, NULL, 3, NULL, NULL, NULL, NULL, NULL),"
        " (2147483650, 0, 0, NULL, 1, NULL, NULL, NULL, NULL, NULL),"
        " (9999999999, 5, 2, NULL, 2, NULL, NULL, NULL, NULL, NULL);"
        "INSERT INTO keypoints VALUES (1, 8000, 2, NULL), (2, 6000, 2, NULL);")
    connection.commit()
    connection.close()
    assert metrics.verified_share(path) == (80, 160)
    assert metrics.keypoints_per_image(path) == 7000


def test_methods_parse_and_malformed_ones_are_named():
    method = pipelines.parse_method("q=aief:--mode quality;--matcher ratio --ratio 0.9")
    assert (method.name, method.kind) == ("q", "aief")
    assert method.extract == ["--mode", "quality"]
    assert method.match == ["--matcher", "ratio", "--ratio", "0.9"]
    assert pipelines.parse_method("sift=sift").extract == []
    only_matching = pipelines.parse_method("r=aief;--matcher ratio")
    assert (only_matching.kind, only_matching.extract, only_matching.match) == ("aief", [], ["--matcher", "ratio"])
    for bad in ("x", "=aief", "x=orb", "s=sift:;--matcher ratio"):
        with pytest.raises(ValueError, match="method"):
            pipelines.parse_method(bad)


def test_pairs_are_every_pair_once(tmp_path):
    path = tmp_path / "pairs.txt"
    pipelines.write_pairs(str(path), ["a.jpg", "b.jpg", "c.jpg"])
    assert path.read_text() == "a.jpg b.jpg\na.jpg c.jpg\nb.jpg c.jpg\n"


def test_a_step_done_as_now_is_kept_and_redone_when_an_input_changes(tmp_path):
    from colmapbench.runner import StepFailed, Steps
    pairs, count = tmp_path / "pairs.txt", tmp_path / "count"
    pairs.write_text("a b\n")
    command = ["sh", "-c", f"echo run >> {count}"]

    def run():
        Steps(str(tmp_path / "steps")).run("step", command, inputs=[str(pairs)])
        return count.read_text().count("run")

    assert run() == 1
    pairs.write_text("a b\n")  # rewritten alike (every run writes pairs.txt): kept
    assert run() == 1
    pairs.write_text("a c\n")
    assert run() == 2
    with pytest.raises(StepFailed, match="exited 3"):
        Steps(str(tmp_path / "steps")).run("failing", ["sh", "-c", "exit 3"])
