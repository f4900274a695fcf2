"""aief.Extractor: same bytes as the CLI (and so the C++ API), image layouts, options, errors."""
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


@pytest.mark.parametrize("kwargs, message", [
    (dict(n_features=0), "n_features must be in"),
    (dict(n_features=1_000_001), "n_features must be in"),
    (dict(levels=0), "n_levels must be in"),
    (dict(levels=33), "n_levels must be in"),
    (dict(scale=1.0), "scale_factor must be > 1"),
    (dict(scale=4.5), "scale_factor must be > 1"),
    (dict(scale=float("nan")), "scale_factor"),
    (dict(threads=-1), "threads must be in"),
    (dict(threads=257), "threads must be in"),
    (dict(fast_threshold=0), "fast_threshold must be in"),
    (dict(fast_threshold=255), "fast_threshold must be in"),
    (dict(fast_threshold=10, fast_min_threshold=11), "fast_min_threshold must be in"),
    (dict(fast_min_threshold=0), "fast_min_threshold must be in"),
    (dict(block_size=7), "block_size must be in"),
    (dict(block_size=1025), "block_size must be in"),
    (dict(threshold=-0.5), "entropy_threshold must be in"),
    (dict(threshold=65), "entropy_threshold must be in"),
    (dict(threshold=float("inf")), "entropy_threshold must be in"),
    (dict(threshold="fast"), "threshold must be a number of bits or \"auto\""),
    (dict(threshold=True), "threshold must be a number of bits or \"auto\""),
    (dict(threshold=None), "threshold must be a number of bits or \"auto\""),
    (dict(mode="orb"), "unknown mode"),
    (dict(kernels="neon9"), "unknown kernel set"),
    (dict(entropy="shannon"), "unknown entropy"),
    (dict(max_image_pixels=0), "max_image_pixels must be in"),
    (dict(max_image_pixels=2**26 + 1), "max_image_pixels must be in"),
    (dict(pool=0.5), "candidate_pool must be >= 1"),
    (dict(pool=float("nan")), "candidate_pool must be >= 1"),
    (dict(pool="big"), "candidate pool must be a number >= 1 or inf"),
    (dict(pool=True), "pool must be a number >= 1"),
    (dict(coordinates="rounded"), "unknown coordinate"),
    (dict(starvation_guard="block"), "unknown starvation guard"),
])
def test_invalid_options_raise_aief_error(kwargs, message):
    with pytest.raises(aief.Error, match=message) as error:
        aief.Extractor(**kwargs)
    assert isinstance(error.value, ValueError)


@pytest.mark.parametrize("kwargs", [dict(n_features=1.5), dict(levels="8"), dict(scale="big"), dict(n_features=2**40),
                                    dict(unknown=1)])
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
