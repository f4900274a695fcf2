"""The CLI's feature files read back by independent readers: h5py (hloc layout), numpy (npz)."""
import os
import shutil
import subprocess

import h5py
import numpy
import pytest

import aief
from conftest import SEQUENCES, read_unchanged, run_cli, sample_path


@pytest.fixture
def image_folder(tmp_path):
    """The six bundled images, two of them one folder down (relative names with '/')."""
    folder = tmp_path / "images"
    (folder / "sub").mkdir(parents=True)
    for sequence in SEQUENCES:
        shutil.copy(sample_path(sequence, 1), folder / f"{sequence}1.png")
        shutil.copy(sample_path(sequence, 2), folder / ("sub" if sequence == "graf" else ".") / f"{sequence}2.png")
    return folder


def expected_features(folder, name):
    return aief.Extractor().extract(read_unchanged(folder / name))


def assert_group_is(group, features):
    n = len(features)
    assert group["keypoints"].dtype == numpy.float32 and group["keypoints"].shape == (n, 2)
    numpy.testing.assert_array_equal(group["keypoints"][()], features.keypoints)
    assert group["descriptors"].dtype == numpy.uint8 and group["descriptors"].shape == (32, n)
    numpy.testing.assert_array_equal(group["descriptors"][()], features.descriptors.T)
    numpy.testing.assert_array_equal(group["scores"][()], features.response)
    numpy.testing.assert_array_equal(group["angle"][()], features.angle)
    numpy.testing.assert_array_equal(group["size"][()], features.size)
    numpy.testing.assert_array_equal(group["octave"][()], features.octave)
    numpy.testing.assert_array_equal(group["image_size"][()], [features.image_width, features.image_height])


def names_in(path):
    """hloc's list_h5_names: the parents of every dataset."""
    names = set()
    with h5py.File(path, "r") as f:
        f.visititems(lambda _, obj: names.add(obj.parent.name.strip("/")) if isinstance(obj, h5py.Dataset) else None)
    return sorted(names)


def test_batch_h5_in_hlocs_layout(cli, tmp_path, image_folder):
    out = tmp_path / "features.h5"
    run_cli(cli, "extract", "--batch", image_folder, "-o", out, "--format", "h5")
    names = names_in(out)
    assert names == sorted(["boat1.png", "boat2.png", "graf1.png", "sub/graf2.png", "leuven1.png", "leuven2.png"])
    with h5py.File(out, "r") as f:
        for name in names:
            assert_group_is(f[name], expected_features(image_folder, name))


def test_batch_h5_resumes_and_shards_merge_to_the_single_file(cli, tmp_path, image_folder):
    single = tmp_path / "single.h5"
    run_cli(cli, "extract", "--batch", image_folder, "-o", single, "--format", "h5")
    again = run_cli(cli, "extract", "--batch", image_folder, "-o", single, "--format", "h5")
    assert "0 extracted, 6 already done" in again.stdout
    # A killed run: a group without its last dataset is redone, complete ones are kept.
    with h5py.File(single, "a") as f:
        del f["boat1.png/image_size"]
    resumed = run_cli(cli, "extract", "--batch", image_folder, "-o", single, "--format", "h5")
    assert "1 extracted, 5 already done" in resumed.stdout
    shards = [tmp_path / f"shard{i}.h5" for i in range(3)]
    for i, shard in enumerate(shards):
        run_cli(cli, "extract", "--batch", image_folder, "-o", shard, "--format", "h5", "--shard", f"{i}/3")
    assert sum(len(names_in(s)) for s in shards) == 6
    merged = tmp_path / "merged.h5"
    run_cli(cli, "merge", "-o", merged, *shards)
    assert names_in(merged) == names_in(single)
    with h5py.File(merged, "r") as m, h5py.File(single, "r") as s:
        for name in names_in(single):
            for dataset in s[name]:
                numpy.testing.assert_array_equal(m[name][dataset][()], s[name][dataset][()])
    # Merging a shard twice into another output is an error naming the image.
    result = subprocess.run([cli, "merge", "-o", tmp_path / "twice.h5", shards[0], shards[0]],
                                          capture_output=True, text=True)
    assert result.returncode == 1 and "is in two of the files merged" in result.stderr


def test_match_pairs_in_hlocs_layout(cli, tmp_path, image_folder):
    features = tmp_path / "features.h5"
    run_cli(cli, "extract", "--batch", image_folder, "-o", features, "--format", "h5")
    pairs = tmp_path / "pairs.txt"
    pairs.write_text("# hloc pairs\ngraf1.png sub/graf2.png\nboat1.png boat2.png\n\nleuven2.png leuven1.png\n")
    out = tmp_path / "matches.h5"
    run_cli(cli, "match", "--pairs", pairs, "--features", features, "-o", out)
    with h5py.File(out, "r") as f:
        for name0, name1 in [("graf1.png", "sub/graf2.png"), ("boat1.png", "boat2.png"), ("leuven2.png", "leuven1.png")]:
            pair = "/".join((name0.replace("/", "-"), name1.replace("/", "-")))  # hloc's names_to_pair
            a, b = expected_features(image_folder, name0), expected_features(image_folder, name1)
            expected = aief.match(a, b)
            matches0, scores0 = f[pair]["matches0"][()], f[pair]["matching_scores0"][()]
            assert matches0.shape == (len(a),) and scores0.dtype == numpy.float32
            numpy.testing.assert_array_equal(numpy.flatnonzero(matches0 >= 0), expected[:, 0])
            numpy.testing.assert_array_equal(matches0[expected[:, 0]], expected[:, 1])
            numpy.testing.assert_array_equal(scores0[expected[:, 0]], 1 - expected[:, 2].astype(numpy.float32) / 256)
            assert (scores0[matches0 < 0] == 0).all() and len(expected) > 100


def test_npz_single_and_batch(cli, tmp_path, image_folder):
    out = tmp_path / "graf1.npz"
    run_cli(cli, "extract", image_folder / "graf1.png", "-o", out)
    batch = tmp_path / "batch"
    run_cli(cli, "extract", "--batch", image_folder, "-o", batch, "--format", "npz")
    for path, name in [(out, "graf1.png"), (batch / "sub" / "graf2.png.npz", "sub/graf2.png"),
                       (batch / "boat1.png.npz", "boat1.png")]:
        features = expected_features(image_folder, name)
        with numpy.load(path) as data:
            assert {"keypoints", "descriptors", "scores", "size", "angle", "octave", "image_size"} <= set(data.files)
            numpy.testing.assert_array_equal(data["keypoints"], features.keypoints)
            assert data["descriptors"].shape == (len(features), 32)
            numpy.testing.assert_array_equal(data["descriptors"], features.descriptors)
            numpy.testing.assert_array_equal(data["scores"], features.response)
            numpy.testing.assert_array_equal(data["size"], features.size)
            numpy.testing.assert_array_equal(data["angle"], features.angle)
            numpy.testing.assert_array_equal(data["octave"], features.octave)
            numpy.testing.assert_array_equal(data["image_size"], [features.image_width, features.image_height])


def test_npz_without_keypoints(cli, tmp_path):
    import cv2
    flat = tmp_path / "flat.png"
    cv2.imwrite(str(flat), numpy.full((64, 80), 90, numpy.uint8))
    run_cli(cli, "extract", flat, "-o", tmp_path / "flat.npz")
    with numpy.load(tmp_path / "flat.npz") as data:
        assert data["keypoints"].shape == (0, 2) and data["descriptors"].shape == (0, 32)
        numpy.testing.assert_array_equal(data["image_size"], [80, 64])


@pytest.fixture(scope="module")
def error_case_files(cli, tmp_path_factory):
    """One features file and the pairs files the error cases read (built once for all of them)."""
    tmp = tmp_path_factory.mktemp("errors")
    (tmp / "bad_pairs.txt").write_text("a.png\n")
    (tmp / "pairs.txt").write_text("img1.png img2.png\n")
    (tmp / "unknown_pairs.txt").write_text("x.png img1.png\n")
    folder = tmp / "images"
    folder.mkdir()
    shutil.copy(sample_path("boat", 1), folder / "img1.png")
    run_cli(cli, "extract", "--batch", folder, "-o", tmp / "f.h5", "--format", "h5")
    return tmp


@pytest.mark.parametrize("args, message", [
    (["match", "--pairs", "{tmp}/missing.txt", "--features", "{tmp}/f.h5", "-o", "{tmp}/m.h5"], "cannot read pairs file"),
    (["match", "--pairs", "{tmp}/bad_pairs.txt", "--features", "{tmp}/f.h5", "-o", "{tmp}/m.h5"], "expected two image names"),
    (["match", "--pairs", "{tmp}/pairs.txt", "--features", "{tmp}/none.h5", "-o", "{tmp}/m.h5"], "no such file"),
    (["match", "--pairs", "{tmp}/pairs.txt", "--features", "{tmp}/pairs.txt", "-o", "{tmp}/m.h5"], "it is not an HDF5 file"),
    (["match", "--pairs", "{tmp}/unknown_pairs.txt", "--features", "{tmp}/f.h5", "-o", "{tmp}/m.h5"], "no image 'x.png'"),
    (["merge", "-o", "{tmp}/out.h5", "{tmp}/none.h5"], "no such file"),
    (["colmap", "--features", "{tmp}/f.h5", "--matches", "{tmp}/none.h5", "--pairs", "{tmp}/pairs.txt", "-o", "{tmp}/d.db"],
     "no such file"),
])
def test_file_errors_name_the_file(cli, error_case_files, args, message):
    result = subprocess.run([cli, *[a.format(tmp=error_case_files) for a in args]], capture_output=True, text=True)
    assert result.returncode == 1, result.stderr
    assert message in result.stderr


def test_a_features_file_open_in_python_is_refused_by_readers_with_libhdf5s_lock_off(cli, tmp_path, image_folder):
    """aief.FeaturesFile holds aief's own lock while open: `aief merge` reading that file with
    libhdf5's lock off (HDF5_USE_FILE_LOCKING=FALSE, as on Lustre) refuses it, naming the writer,
    and reads it once it is closed. Before: merged whatever the writer had flushed, exit 0."""
    path = tmp_path / "f.h5"
    env = dict(os.environ, HDF5_USE_FILE_LOCKING="FALSE")
    merge = [cli, "merge", "-o", str(tmp_path / "m.h5"), str(path)]
    subprocess.run([cli, "extract", "--batch", str(image_folder), "-o", str(path), "--format", "h5"],
                   check=True, env=env, capture_output=True)
    with aief.FeaturesFile(path):
        refused = subprocess.run(merge, env=env, capture_output=True, text=True)
        assert refused.returncode == 1, refused.stderr
        assert f"cannot open '{path}': it is locked by a writer, process {os.getpid()}" in refused.stderr
        assert not (tmp_path / "m.h5").exists()
    merged = subprocess.run(merge, env=env, capture_output=True, text=True)
    assert merged.returncode == 0, merged.stderr
