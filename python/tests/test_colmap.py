"""aief colmap: the database read back by sqlite3, then verified and mapped by COLMAP itself."""
import os
import shutil
import sqlite3
import subprocess

import numpy
import pytest

import aief
from conftest import read_unchanged, run_cli, sample_path

MAX_IMAGE_ID = 2147483647


@pytest.fixture
def exported(cli, tmp_path):
    images = tmp_path / "images"
    images.mkdir()
    for sequence in ("graf", "boat"):
        for i in (1, 2):
            shutil.copy(sample_path(sequence, i), images / f"{sequence}{i}.png")
    run_cli(cli, "extract", "--batch", images, "-o", tmp_path / "features.h5", "--format", "h5")
    pairs = tmp_path / "pairs.txt"
    pairs.write_text("graf1.png graf2.png\nboat2.png boat1.png\n")  # the second pair in reverse id order
    run_cli(cli, "match", "--pairs", pairs, "--features", tmp_path / "features.h5", "-o", tmp_path / "matches.h5")
    database = tmp_path / "database.db"
    run_cli(cli, "colmap", "--features", tmp_path / "features.h5", "--matches", tmp_path / "matches.h5", "--pairs", pairs,
            "-o", database)
    return tmp_path, images, pairs, database


def blob(data, dtype, rows, cols):
    return numpy.frombuffer(data, dtype=dtype).reshape(rows, cols)


def test_database_read_back_by_sqlite(exported):
    _, images, _, database = exported
    db = sqlite3.connect(database)
    ids = dict(db.execute("SELECT name, image_id FROM images"))
    assert ids == {"boat1.png": 1, "boat2.png": 2, "graf1.png": 3, "graf2.png": 4}
    features = {name: aief.Extractor().extract(read_unchanged(images / name)) for name in ids}
    for name, image_id in ids.items():
        rows, cols, data = db.execute("SELECT rows, cols, data FROM keypoints WHERE image_id = ?", (image_id,)).fetchone()
        numpy.testing.assert_array_equal(blob(data, numpy.float32, rows, cols), features[name].keypoints + 0.5)
        rows, cols, data = db.execute("SELECT rows, cols, data FROM descriptors WHERE image_id = ?", (image_id,)).fetchone()
        numpy.testing.assert_array_equal(blob(data, numpy.uint8, rows, cols), features[name].descriptors)
        model, width, height, params = db.execute("SELECT model, width, height, params FROM cameras WHERE camera_id = ?",
                                                  (image_id,)).fetchone()
        f = features[name]
        assert (model, width, height) == (2, f.image_width, f.image_height)
        numpy.testing.assert_array_equal(numpy.frombuffer(params, numpy.float64),
                                         [1.2 * max(width, height), width / 2, height / 2, 0])
    for name0, name1 in [("graf1.png", "graf2.png"), ("boat2.png", "boat1.png")]:
        expected = aief.match(features[name0], features[name1])
        id0, id1 = ids[name0], ids[name1]
        pair_id = min(id0, id1) * MAX_IMAGE_ID + max(id0, id1)
        rows, cols, data = db.execute("SELECT rows, cols, data FROM matches WHERE pair_id = ?", (pair_id,)).fetchone()
        stored = blob(data, numpy.uint32, rows, cols)
        columns = expected[:, :2] if id0 < id1 else expected[:, 1::-1]
        numpy.testing.assert_array_equal(stored, columns)


def test_colmap_verifies_and_maps(exported):
    colmap = shutil.which("colmap")
    if colmap is None:
        pytest.skip("colmap is not installed (apt-get install colmap): the export is checked by sqlite3 only")
    tmp_path, images, pairs, database = exported
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen")
    subprocess.run([colmap, "matches_importer", "--database_path", database, "--match_list_path", pairs,
                    "--match_type", "pairs", "--SiftMatching.use_gpu", "0", "--SiftMatching.num_threads", "2"],
                   check=True, capture_output=True, env=env)
    db = sqlite3.connect(database)
    verified = {pair_id: (rows, cols, data, config)
                for pair_id, rows, cols, data, config in db.execute("SELECT pair_id, rows, cols, data, config FROM two_view_geometries")}
    matches = {pair_id: blob(data, numpy.uint32, rows, cols)
               for pair_id, rows, cols, data in db.execute("SELECT pair_id, rows, cols, data FROM matches")}
    assert sorted(verified) == sorted(matches) and len(verified) == 2
    for pair_id, (rows, cols, data, config) in verified.items():
        inliers = blob(data, numpy.uint32, rows, cols)
        assert config >= 2 and rows > 100  # a verified geometry with most of aief's ~400 matches
        assert {tuple(r) for r in inliers} <= {tuple(r) for r in matches[pair_id]}  # a subset of what aief matched
    sparse = tmp_path / "sparse"
    sparse.mkdir()
    # Two views of a plane triangulate at small angles: COLMAP's angle thresholds relaxed (docs/feature_files.md).
    subprocess.run([colmap, "mapper", "--database_path", database, "--image_path", images, "--output_path", sparse,
                    "--Mapper.num_threads", "2", "--Mapper.min_model_size", "2", "--Mapper.init_min_tri_angle", "1",
                    "--Mapper.tri_min_angle", "0.5", "--Mapper.filter_min_tri_angle", "0.5"],
                   check=True, capture_output=True, env=env)
    models = sorted(p for p in sparse.iterdir() if (p / "points3D.bin").exists())
    assert models, "colmap mapper reconstructed nothing"
    reconstructed = []
    for model in models:
        subprocess.run([colmap, "model_converter", "--input_path", model, "--output_path", model, "--output_type", "TXT"],
                       check=True, capture_output=True, env=env)
        registered = sorted(line.split()[-1] for line in (model / "images.txt").read_text().splitlines()[4::2])
        points = [line for line in (model / "points3D.txt").read_text().splitlines() if not line.startswith("#")]
        reconstructed.append((registered, len(points)))
    # Each model is one of the two pairs (they share no image); graf's viewpoint change gives a real
    # point cloud (boat, a rotation about the optical centre, has no baseline to triangulate).
    assert all(r in (["boat1.png", "boat2.png"], ["graf1.png", "graf2.png"]) for r, _ in reconstructed), reconstructed
    assert any(r == ["graf1.png", "graf2.png"] and n > 50 for r, n in reconstructed), reconstructed
