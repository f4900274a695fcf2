"""The CLI never writes into another tool's HDF5 file: features into hloc's SuperPoint features
(256 x N float32 descriptors) or into a matches file, matches into a features file."""
import shutil

import h5py
import numpy
import pytest

from conftest import sample_path


def superpoint_file(path):
    """What hloc's extract_features writes for SuperPoint: one group per image, no aief record."""
    with h5py.File(path, "w") as f:
        group = f.create_group("img1.png")
        group["keypoints"] = numpy.zeros((10, 2), numpy.float32)
        group["descriptors"] = numpy.ones((256, 10), numpy.float32)
        group["scores"] = numpy.zeros(10, numpy.float32)
        group["image_size"] = numpy.array([640, 480], numpy.int64)


def contents(path):
    with h5py.File(path, "r") as f:
        names = []
        f.visititems(lambda name, item: names.append((name, item.shape, str(item.dtype))) if isinstance(item, h5py.Dataset) else None)
        return names


@pytest.fixture
def images(tmp_path):
    folder = tmp_path / "images"
    folder.mkdir()
    shutil.copy(sample_path("boat", 1), folder / "img1.png")
    shutil.copy(sample_path("boat", 2), folder / "img2.png")
    return folder


def run(cli, *args):
    import subprocess
    return subprocess.run([cli, *map(str, args)], capture_output=True, text=True)


def test_extract_refuses_another_tools_features_file(cli, tmp_path, images):
    target = tmp_path / "feats-superpoint.h5"
    superpoint_file(target)
    before = contents(target)
    result = run(cli, "extract", "--batch", images, "-o", target, "--format", "h5")
    assert result.returncode == 1, result.stdout + result.stderr
    assert "another tool's features" in result.stderr and "256 x 10 float32" in result.stderr, result.stderr
    assert contents(target) == before


# uint8 descriptors of another layout (64 x N bytes) were named "int8": numpy's names now.
@pytest.mark.parametrize("dtype, named", [(numpy.uint8, "64 x 10 uint8"), (numpy.int8, "64 x 10 int8")])
def test_another_tools_byte_descriptors_are_named_as_numpy_names_them(cli, tmp_path, images, dtype, named):
    target = tmp_path / "bytes.h5"
    superpoint_file(target)
    with h5py.File(target, "a") as f:
        del f["img1.png/descriptors"]
        f["img1.png/descriptors"] = numpy.ones((64, 10), dtype)
    result = run(cli, "extract", "--batch", images, "-o", target, "--format", "h5")
    assert result.returncode == 1 and named + " descriptors" in result.stderr, result.stderr


def test_extract_refuses_a_matches_file_and_match_refuses_a_features_file(cli, tmp_path, images):
    features, matches = tmp_path / "f.h5", tmp_path / "m.h5"
    pairs = tmp_path / "pairs.txt"
    pairs.write_text("img1.png img2.png\n")
    assert run(cli, "extract", "--batch", images, "-o", features, "--format", "h5").returncode == 0
    assert run(cli, "match", "--pairs", pairs, "--features", features, "-o", matches).returncode == 0
    features_before, matches_before = contents(features), contents(matches)

    into_features = run(cli, "match", "--pairs", pairs, "--features", features, "-o", features)
    assert into_features.returncode == 1 and "is the features file" in into_features.stderr, into_features.stderr
    other = tmp_path / "other.h5"
    shutil.copy(features, other)
    into_other = run(cli, "match", "--pairs", pairs, "--features", features, "-o", other)
    assert into_other.returncode == 1 and "holds features" in into_other.stderr, into_other.stderr
    assert contents(other) == features_before

    into_matches = run(cli, "extract", "--batch", images, "-o", matches, "--format", "h5")
    assert into_matches.returncode == 1 and "holds matches" in into_matches.stderr, into_matches.stderr
    assert contents(features) == features_before and contents(matches) == matches_before


@pytest.mark.parametrize("fault", ["shorter", "uint8"])
def test_colmap_refuses_matches0_of_another_length_or_unsigned(cli, tmp_path, images, fault):
    """matches0 has a row per keypoint of image 0, signed (-1: unmatched): a shorter one is of
    other features, an unsigned one would read 255 as an index."""
    features, matches, database = tmp_path / "f.h5", tmp_path / "m.h5", tmp_path / "db.db"
    pairs = tmp_path / "pairs.txt"
    pairs.write_text("img1.png img2.png\n")
    assert run(cli, "extract", "--batch", images, "-o", features, "--format", "h5").returncode == 0
    assert run(cli, "match", "--pairs", pairs, "--features", features, "-o", matches).returncode == 0
    with h5py.File(matches, "a") as f:
        group = f["img1.png/img2.png"]
        matches0, scores0 = group["matches0"][()], group["matching_scores0"][()]
        del group["matches0"], group["matching_scores0"]
        if fault == "shorter":
            group["matches0"], group["matching_scores0"] = matches0[:300], scores0[:300]
        else:
            group["matches0"] = numpy.where(matches0 < 0, 255, matches0 % 200).astype(numpy.uint8)
            group["matching_scores0"] = scores0
    result = run(cli, "colmap", "--features", features, "--matches", matches, "--pairs", pairs, "-o", database)
    assert result.returncode == 1, result.stdout + result.stderr
    expected = "matches0 has 300 rows but 'img1.png' has" if fault == "shorter" else "is unsigned uint8"
    assert expected in result.stderr, result.stderr
    assert not database.exists()


def test_merge_refuses_another_tools_features_as_a_shard_or_the_output(cli, tmp_path, images):
    """Before: merge copied hloc's SuperPoint groups beside aief's (exit 0)."""
    superpoint = tmp_path / "feats-superpoint.h5"
    superpoint_file(superpoint)
    before = contents(superpoint)
    shard = tmp_path / "shard.h5"
    assert run(cli, "extract", "--batch", images, "-o", shard, "--format", "h5").returncode == 0
    result = run(cli, "merge", "-o", tmp_path / "all.h5", shard, superpoint)
    assert result.returncode == 1 and "another tool's features" in result.stderr, result.stderr
    assert not (tmp_path / "all.h5").exists()
    result = run(cli, "merge", "-o", superpoint, shard)
    assert result.returncode == 1 and "the output" in result.stderr and "another tool's features" in result.stderr, result.stderr
    assert contents(superpoint) == before


def test_merge_says_it_leaves_out_incomplete_groups(cli, tmp_path, images):
    """A group a killed write left incomplete (keypoints but no image_size): before, left out of
    the merge without a word."""
    shard = tmp_path / "shard.h5"
    assert run(cli, "extract", "--batch", images, "-o", shard, "--format", "h5").returncode == 0
    with h5py.File(shard, "a") as f:
        del f["img2.png"]["image_size"]
    result = run(cli, "merge", "-o", tmp_path / "all.h5", shard)
    assert result.returncode == 0, result.stderr
    assert "1 images merged" in result.stdout
    assert "holds 1 incomplete image group(s)" in result.stderr and "'img2.png'" in result.stderr, result.stderr
