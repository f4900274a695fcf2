"""aief.Extractor: same bytes as the CLI (and so the C++ API), image layouts, options, errors."""
import os
import pathlib
import shutil
import subprocess
import warnings

import cv2
import numpy
import pytest

import aief
from conftest import SEQUENCES, assert_same_features, as_rows, cli_features, read_unchanged, sample_path


@pytest.mark.parametrize("sequence", SEQUENCES)
def test_colour_image_gives_the_cli_bytes(cli, tmp_path, sequence):
    keypoints, descriptors = cli_features(cli, tmp_path, sample_path(sequence))
    features = aief.Extractor().extract(read_unchanged(sample_path(sequence)))
    assert len(features) > 0
    numpy.testing.assert_array_equal(as_rows(features), keypoints)
    numpy.testing.assert_array_equal(features.descriptors, descriptors)


def test_options_reach_the_engine_as_the_cli_flags_do(cli, tmp_path):
    path = sample_path("boat")
    keypoints, descriptors = cli_features(cli, tmp_path, path, "--features", 300, "--levels", 4, "--scale", 1.3,
                                          "--threshold", "auto", "--mode", "quadtree-entropy", "--block", 48)
    features = aief.Extractor(300, mode="quadtree-entropy", threshold="auto", levels=4, scale=1.3, block_size=48).extract(
        read_unchanged(path))
    numpy.testing.assert_array_equal(as_rows(features), keypoints)
    numpy.testing.assert_array_equal(features.descriptors, descriptors)


@pytest.mark.parametrize("flags, kwargs", [
    (["--mode", "aief-paper"], dict(mode="aief-paper")),
    (["--mode", "orbslam2", "--features", 500], dict(n_features=500, mode="orbslam2")),
    (["--pool", 2, "--coordinates", "scaled", "--subpixel", "off", "--starvation-guard", "frame",
      "--auto-uniform-blocks", "count", "--threshold", "auto"],
     dict(pool=2, coordinates="scaled", subpixel=False, starvation_guard="frame", auto_skips_uniform_blocks=False,
          threshold="auto")),
    (["--pool", "inf"], dict(pool="inf")),
    (["--ranking", "peak", "--auto-two-classes", "off", "--threshold", "auto"],
     dict(ranking="peak", auto_requires_two_classes=False, threshold="auto")),
])
def test_modes_and_quality_options_as_the_cli_flags(cli, tmp_path, flags, kwargs):
    path = sample_path("graf")
    keypoints, descriptors = cli_features(cli, tmp_path, path, *flags)
    features = aief.Extractor(**kwargs).extract(read_unchanged(path))
    numpy.testing.assert_array_equal(as_rows(features), keypoints)
    numpy.testing.assert_array_equal(features.descriptors, descriptors)


def test_defaults_are_the_cpp_structs():
    extractor = aief.Extractor()
    assert extractor.options == aief.default_options()
    assert extractor.options["distribution"] == "proportional" and extractor.options["entropy"] == "histogram"


def test_gray_bgr_and_bgra_agree():
    bgr = read_unchanged(sample_path("graf"))
    extractor = aief.Extractor()
    from_bgr = extractor.extract(bgr)
    assert_same_features(from_bgr, extractor.extract(cv2.cvtColor(bgr, cv2.COLOR_BGR2GRAY)))
    assert_same_features(from_bgr, extractor.extract(cv2.cvtColor(bgr, cv2.COLOR_BGR2BGRA)))
    assert_same_features(from_bgr, extractor.extract(cv2.cvtColor(bgr, cv2.COLOR_BGR2GRAY)[:, :, None]))


def test_any_strides_give_the_contiguous_answer():
    gray = cv2.cvtColor(read_unchanged(sample_path("leuven")), cv2.COLOR_BGR2GRAY)
    extractor = aief.Extractor(500)
    for view in (gray[::2, ::3], gray[::-1], gray[:, ::-1], numpy.asfortranarray(gray), gray[10:300, 20:400]):
        assert_same_features(extractor.extract(view), extractor.extract(numpy.ascontiguousarray(view)))
    rgb = cv2.cvtColor(read_unchanged(sample_path("leuven")), cv2.COLOR_BGR2RGB)
    bgr_view = rgb[:, :, ::-1]  # BGR through negative channel strides
    assert_same_features(extractor.extract(bgr_view), extractor.extract(numpy.ascontiguousarray(bgr_view)))


def test_contiguous_rows_are_not_copied():
    gray = read_unchanged(sample_path("boat"))
    assert gray.ndim == 2
    assert aief._aief._image_data_address(gray) == gray.ctypes.data
    cropped = gray[5:, 7:300]  # rows still contiguous, stride wider than the width
    assert aief._aief._image_data_address(cropped) == cropped.ctypes.data
    assert aief._aief._image_data_address(gray[:, ::2]) != gray.ctypes.data


def test_result_arrays():
    features = aief.Extractor(200).extract(read_unchanged(sample_path("graf")))
    n = len(features)
    assert features.keypoints.shape == (n, 2) and features.keypoints.dtype == numpy.float32
    assert features.descriptors.shape == (n, 32) and features.descriptors.dtype == numpy.uint8
    for name in ("size", "angle", "response"):
        assert getattr(features, name).shape == (n,) and getattr(features, name).dtype == numpy.float32
    assert features.octave.dtype == numpy.int32
    assert (features.image_width, features.image_height) == (800, 640)
    assert features.info["entropy_threshold_used"] == 4.0 and features.info["blocks_kept"] <= features.info["blocks_total"]
    assert features.info["auto_threshold_effectiveness"] == 0.0  # a given F, not --threshold auto


@pytest.mark.parametrize("image, message", [
    ([[1, 2], [3, 4]], "numpy array of uint8, got list"),
    (numpy.zeros((64, 64), numpy.float32), "must be uint8, got dtype float32"),
    (numpy.zeros((64, 64), numpy.uint16), "must be uint8, got dtype uint16"),
    (numpy.zeros((64, 64), numpy.int8), "must be uint8, got dtype int8"),
    (numpy.zeros((64, 64), bool), "must be uint8, got dtype bool"),
    (numpy.zeros(64, numpy.uint8), "got shape (64,)"),
    (numpy.zeros((4, 64, 64, 3), numpy.uint8), "got shape (4, 64, 64, 3)"),
    (numpy.zeros((64, 64, 2), numpy.uint8), "2 channels"),
    (numpy.zeros((64, 64, 5), numpy.uint8), "5 channels"),
    (numpy.zeros((0, 64), numpy.uint8), "empty"),
    (numpy.zeros((64, 0, 3), numpy.uint8), "empty"),
    (numpy.zeros((30, 64), numpy.uint8), "smaller than"),
    (numpy.zeros((64, 12, 3), numpy.uint8), "smaller than"),
])
def test_invalid_images_raise_aief_error(image, message):
    with pytest.raises(aief.Error, match=message.replace("(", r"\(").replace(")", r"\)")):
        aief.Extractor().extract(image)


def test_image_above_the_pixel_limit():
    with pytest.raises(aief.Error, match="max_image_pixels|pixels"):
        aief.Extractor(max_image_pixels=1000).extract(numpy.zeros((64, 64), numpy.uint8))


def test_flat_image_has_no_keypoints():
    features = aief.Extractor().extract(numpy.full((100, 120), 128, numpy.uint8))
    assert len(features) == 0 and features.descriptors.shape == (0, 32)


# The messages name the keyword as given and what it accepts, from the option table (as the CLI's).
@pytest.mark.parametrize("kwargs, message", [
    (dict(n_features=0), r"n_features expects an integer in \[1, 1000000\], got '0'"),
    (dict(n_features=1_000_001), "n_features expects an integer in"),
    (dict(n_features=2**40), "n_features expects an integer in"),
    (dict(levels=0), "levels expects an integer in"),
    (dict(levels=33), "levels expects an integer in"),
    (dict(scale=1.0), r"scale expects a number in \(1, 4\], got '1.0'"),
    (dict(scale=4.5), "scale expects a number in"),
    (dict(scale=float("nan")), "scale expects a number in"),
    (dict(scale=1.00000001), "scale_factor must be > 1 and <= 4 in single precision"),
    (dict(threads=-1), "threads expects an integer in"),
    (dict(threads=257), "threads expects an integer in"),
    (dict(fast_threshold=0), "fast_threshold expects an integer in"),
    (dict(fast_threshold=255), "fast_threshold expects an integer in"),
    (dict(fast_threshold=10, fast_min_threshold=11), "fast_min_threshold must be in"),
    (dict(fast_min_threshold=0), "fast_min_threshold expects an integer in"),
    (dict(block_size=7), "block_size expects an integer in"),
    (dict(block_size=1025), "block_size expects an integer in"),
    (dict(threshold=-0.5), "threshold expects a number in"),
    (dict(threshold=65), "threshold expects a number in"),
    (dict(threshold=float("inf")), "threshold expects a number in"),
    (dict(threshold="fast"), r"threshold expects a number in \[0, 64\], auto or carried, got 'fast'"),
    (dict(mode="orb"), "unknown mode"),
    (dict(kernels="neon9"), "unknown kernel set"),
    (dict(entropy="shannon"), "unknown entropy"),
    (dict(max_image_pixels=0), "max_image_pixels expects an integer in"),
    (dict(max_image_pixels=2**26 + 1), "max_image_pixels expects an integer in"),
    (dict(pool=0.5), "pool expects a number >= 1, inf or off"),
    (dict(pool=float("nan")), "pool expects a number >= 1"),
    (dict(pool="big"), "pool expects a number >= 1, inf or off, got 'big'"),
    (dict(coordinates="rounded"), "unknown coordinate"),
    (dict(starvation_guard="block"), "unknown starvation guard"),
])
def test_invalid_options_raise_aief_error(kwargs, message):
    with pytest.raises(aief.Error, match=message) as error:
        aief.Extractor(**kwargs)
    assert isinstance(error.value, ValueError)


# A value of the wrong type (a bool is no number) raises TypeError, as Python's own calls do.
@pytest.mark.parametrize("kwargs", [dict(n_features=1.5), dict(levels="8"), dict(scale="big"), dict(unknown=1),
                                    dict(threshold=True), dict(pool=True)])
def test_wrong_types_raise_type_error(kwargs):
    with pytest.raises(TypeError):
        aief.Extractor(**kwargs)


def test_every_kernel_set_gives_the_same_bytes():
    image = read_unchanged(sample_path("boat"))
    reference = aief.Extractor(kernels="scalar").extract(image)
    for kernels in ("auto", "sse4.2", "avx2", "avx512"):
        try:
            extractor = aief.Extractor(kernels=kernels)
        except aief.Error as e:  # not on this CPU
            assert "not available" in str(e) or "support" in str(e), e
            continue
        assert_same_features(extractor.extract(image), reference)


def test_file_names_as_path_objects_bytes_and_names_that_are_not_utf8(cli, tmp_path):
    """read_image and batch_inputs take str, bytes and os.PathLike (pathlib.Path was a TypeError);
    a file name that is not UTF-8, which the CLI extracts, comes back as os.fsdecode gives it (was
    UnicodeDecodeError) and reads back."""
    image = pathlib.Path(sample_path("graf"))
    expected = aief.read_image(str(image))
    for given in (image, os.fsencode(str(image))):
        numpy.testing.assert_array_equal(aief.read_image(given), expected)
    with pytest.raises(TypeError):
        aief.read_image(42)
    folder = os.fsencode(str(tmp_path / "images"))
    os.mkdir(folder)
    shutil.copy(str(image), os.path.join(folder, b"caf\xe9.png"))  # Latin-1, not UTF-8
    inputs = aief.batch_inputs(tmp_path / "images")
    assert [os.fsencode(name) for _, name in inputs] == [b"caf\xe9.png"]
    numpy.testing.assert_array_equal(aief.read_image(inputs[0][0]), expected)
    run = subprocess.run([cli, "extract", "--batch", folder, "-o", str(tmp_path / "out")], capture_output=True)
    assert run.returncode == 0 and b"1 extracted" in run.stdout, run.stdout


# A TIFF of 64 x 64 pixels in one 16384 x 16384 deflate tile took 7.5 s and 1.11 GB through
# aief.read_image: the decoder holds a whole tile. The tile is bounded as the image is, from the header.
def test_read_image_refuses_a_tiff_tile_larger_than_allowed_before_decoding(tmp_path):
    import struct
    entries = [(256, 4, 64), (257, 4, 64), (258, 3, 8), (259, 3, 8), (262, 3, 1), (277, 3, 1), (284, 3, 1),
               (322, 4, 16384), (323, 4, 16384), (324, 4, 8 + 2 + 10 * 12 + 4)]
    data = b"II*\0" + struct.pack("<I", 8) + struct.pack("<H", len(entries))
    data += b"".join(struct.pack("<HHII", tag, kind, 1, value) for tag, kind, value in entries)
    data += struct.pack("<I", 0) + bytes(16)
    path = tmp_path / "tile.tiff"
    path.write_bytes(data)
    with pytest.raises(aief.Error, match="is a TIFF of 16384x16384-pixel tiles"):
        aief.read_image(path)


# A JPEG cut before its end-of-image marker decodes with its rest grey: the CLI warned, read_image
# said nothing. The warning is the CLI's sentence, from io/image_io.cpp.
def test_read_image_warns_of_a_jpeg_cut_short_as_the_cli_does(cli, tmp_path):
    encoded = cv2.imencode(".jpg", read_unchanged(sample_path("graf")))[1].tobytes()
    path = tmp_path / "truncated.jpg"
    path.write_bytes(encoded[:len(encoded) // 2])
    cli_warning = subprocess.run([cli, "extract", str(path), "-o", str(tmp_path / "out.json")],
                                 capture_output=True, text=True).stderr.splitlines()[0]
    assert cli_warning.startswith("aief: warning: ") and "end-of-image marker" in cli_warning
    with pytest.warns(UserWarning) as caught:
        image = aief.read_image(path)
    assert [str(w.message) for w in caught] == [cli_warning[len("aief: warning: "):]]
    assert image.shape == read_unchanged(sample_path("graf")).shape[:2]
    whole = tmp_path / "whole.jpg"
    whole.write_bytes(encoded)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        aief.read_image(whole)
