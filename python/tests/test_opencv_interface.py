"""Extractor.detectAndCompute, detect, compute: cv2.Feature2D's methods; the mask fills the budget inside it."""
import re

import cv2
import numpy
import pytest

import aief
from conftest import read_unchanged, sample_path


def test_keypoints_and_descriptors_like_cv2_orb():
    image = read_unchanged(sample_path("graf"))
    extractor = aief.Extractor()
    features = extractor.extract(image)
    keypoints, descriptors = extractor.detectAndCompute(image)
    orb_keypoints, orb_descriptors = cv2.ORB_create(1000).detectAndCompute(image, None)
    assert type(keypoints[0]) is type(orb_keypoints[0]) and descriptors.dtype == orb_descriptors.dtype
    assert descriptors.shape == (len(features), 32)
    numpy.testing.assert_array_equal(descriptors, features.descriptors)
    numpy.testing.assert_array_equal(numpy.float32([k.pt for k in keypoints]), features.keypoints)
    numpy.testing.assert_array_equal(numpy.float32([k.angle for k in keypoints]), features.angle)
    numpy.testing.assert_array_equal(numpy.float32([k.size for k in keypoints]), features.size)
    numpy.testing.assert_array_equal(numpy.float32([k.response for k in keypoints]), features.response)
    numpy.testing.assert_array_equal([k.octave for k in keypoints], features.octave)
    # Existing OpenCV code keeps working: a BFMatcher over the output.
    matches = cv2.BFMatcher(cv2.NORM_HAMMING, crossCheck=True).match(descriptors, descriptors)
    assert len(matches) == len(keypoints)


def test_mask_fills_the_budget_inside_it():
    image = read_unchanged(sample_path("graf"))
    extractor = aief.Extractor()
    all_keypoints, _ = extractor.detectAndCompute(image)
    mask = numpy.zeros(image.shape[:2], numpy.uint8)
    mask[:, : image.shape[1] // 2] = 255
    inside = [k for k in all_keypoints if round(k.pt[0]) < image.shape[1] // 2]
    assert len(inside) == 549  # what dropping masked keypoints after extraction kept
    keypoints, descriptors = extractor.detectAndCompute(image, mask)
    assert len(keypoints) == len(descriptors) == 1000
    assert all(mask[round(k.pt[1]), round(k.pt[0])] for k in keypoints)
    features = extractor.extract(image, mask.astype(bool))
    numpy.testing.assert_array_equal(features.descriptors, descriptors)
    # A mask allowing every pixel is no mask.
    numpy.testing.assert_array_equal(extractor.extract(image, numpy.ones(image.shape[:2], numpy.uint8)).descriptors,
                                     extractor.extract(image).descriptors)


def test_detect_then_compute_is_detect_and_compute():
    image = read_unchanged(sample_path("boat"))
    for mode in ("aief", "aief-paper", "orbslam2", "quadtree-entropy"):
        extractor = aief.Extractor(mode=mode)
        keypoints, descriptors = extractor.detectAndCompute(image)
        detected = extractor.detect(image)
        described, described_descriptors = extractor.compute(image, detected)
        assert len(described) == len(keypoints)
        numpy.testing.assert_array_equal(described_descriptors, descriptors)
        for a, b in zip(described, keypoints):
            assert (a.pt, a.size, a.angle, a.response, a.octave) == (b.pt, b.size, b.angle, b.response, b.octave)
        # The array form gives back the extraction's bytes too.
        features = extractor.extract(image)
        again, kept = extractor.describe(image, features)
        assert kept.tolist() == list(range(len(features)))
        numpy.testing.assert_array_equal(again.descriptors, features.descriptors)
        numpy.testing.assert_array_equal(again.angle, features.angle)


def test_compute_keeps_class_ids_and_leaves_out_keypoints_near_the_edge():
    image = read_unchanged(sample_path("boat"))
    h, w = image.shape[:2]
    given = [cv2.KeyPoint(100, 100, 31, 0, 0, 0, 7), cv2.KeyPoint(18.4, 100, 31, 0, 0, 0, 8),
             cv2.KeyPoint(w - 19.6, 300, 31, 0, 0, 0, 9), cv2.KeyPoint(300, 300, 31, 0, 0, 2, 10)]
    keypoints, descriptors = aief.Extractor().compute(image, given)
    assert [k.class_id for k in keypoints] == [7, 9, 10] and descriptors.shape == (3, 32)
    features, kept = aief.Extractor().describe(image, numpy.float32([[100, 100], [300, 300]]), octave=[0, 9 - 9])
    assert kept.tolist() == [0, 1] and len(features) == 2
    try:
        aief.Extractor().describe(image, numpy.float32([[100, 100]]), octave=[8])
    except aief.Error as e:
        assert "octave[0] is 8, beyond the pyramid's levels 0..7" in str(e)
    else:
        raise AssertionError("no error")


# Octaves narrowed to int32 before any check: 2**40 wrapped to level 0, 1.7 was cut to level 1
# (both described without a word), NaN became -2147483648 in the message.
@pytest.mark.parametrize("octave, says", [
    (numpy.full(2, 2**40), "octave[0] is 1099511627776, beyond the pyramid's levels 0..7"),
    (numpy.full(2, 1.7), "octave[0] is 1.7, not an integer level"),
    (numpy.full(2, numpy.nan), "octave[0] is nan, not an integer level"),
    (numpy.array([0, -1]), "octave[1] is -1, beyond the pyramid's levels 0..7"),
    (numpy.array([0.0, numpy.inf]), "octave[1] is inf, beyond the pyramid's levels 0..7"),
])
def test_describe_refuses_an_octave_that_names_no_level(octave, says):
    image = read_unchanged(sample_path("boat"))
    with pytest.raises(aief.Error, match=re.escape(says)):
        aief.Extractor().describe(image, numpy.float32([[100, 100], [300, 300]]), octave=octave)


def test_describe_takes_integer_octaves_of_any_dtype():
    image = read_unchanged(sample_path("boat"))
    xy = numpy.float32([[100, 100], [300, 300]])
    expected = aief.Extractor().describe(image, xy, octave=numpy.int32([0, 2]))[0]
    for octave in (numpy.int64([0, 2]), numpy.uint8([0, 2]), numpy.float64([0.0, 2.0]), [0, 2]):
        again = aief.Extractor().describe(image, xy, octave=octave)[0]
        assert again.octave.tolist() == [0, 2]
        numpy.testing.assert_array_equal(again.descriptors, expected.descriptors)


def test_keep_angles_without_angles_is_refused():
    """keep_angles=True with no angle= described every keypoint at 0 degrees."""
    image = read_unchanged(sample_path("boat"))
    xy = numpy.float32([[100, 100], [300, 300]])
    with pytest.raises(aief.Error, match="keep_angles=True keeps the given angles, but no angle= is given"):
        aief.Extractor().describe(image, xy, keep_angles=True)
    assert len(aief.Extractor().describe(image, xy, angle=[10, 20], keep_angles=True)[0]) == 2
    features = aief.Extractor().extract(image)  # Features carry their angles
    assert len(aief.Extractor().describe(image, features, keep_angles=True)[0]) == len(features)


def test_mask_of_another_shape_is_an_error():
    image = read_unchanged(sample_path("boat"))
    for mask in (numpy.ones((10, 10), numpy.uint8), numpy.ones(image.shape[:2], numpy.float32)):
        try:
            aief.Extractor().detectAndCompute(image, mask)
        except aief.Error as e:
            assert "is not the image's size" in str(e) or "uint8 or bool" in str(e)
        else:
            raise AssertionError("no error")


def test_compute_keeps_the_given_angles_as_cv2_orb_does():
    """graf's keypoints carried to the image turned by 30 degrees with their true angles come back
    with those angles, as from cv2.ORB.compute; recompute_angles=True re-estimates them (the
    recomputation used to be the only behaviour)."""
    gray = cv2.cvtColor(read_unchanged(sample_path("graf")), cv2.COLOR_BGR2GRAY)
    h, w = gray.shape
    turn = 30.0
    rotation = cv2.getRotationMatrix2D((w / 2, h / 2), turn, 1.0)
    turned = cv2.warpAffine(gray, rotation, (w, h))
    extractor = aief.Extractor()
    moved = []
    for k in extractor.detect(gray):
        x, y = rotation @ numpy.float64([k.pt[0], k.pt[1], 1.0])
        # The image turns counter-clockwise (y down): an orientation theta becomes theta - 30.
        moved.append(cv2.KeyPoint(float(x), float(y), k.size, (k.angle - turn) % 360, k.response, k.octave,
                                  len(moved)))
    kept, descriptors = extractor.compute(turned, moved)
    assert len(kept) > len(moved) * 3 // 4 and descriptors.shape == (len(kept), 32)
    given = numpy.float32([moved[k.class_id].angle for k in kept])
    numpy.testing.assert_array_equal(numpy.float32([k.angle for k in kept]), given)
    orb_kept, _ = cv2.ORB_create().compute(turned, moved)
    numpy.testing.assert_array_equal(numpy.float32([k.angle for k in orb_kept]),
                                     numpy.float32([moved[k.class_id].angle for k in orb_kept]))
    recomputed, _ = extractor.compute(turned, moved, recompute_angles=True)
    assert sum(a.angle != b.angle for a, b in zip(recomputed, kept)) > len(kept) // 2


def test_compute_of_an_array_or_features_says_to_use_describe():
    image = read_unchanged(sample_path("graf"))
    extractor = aief.Extractor()
    features = extractor.extract(image)
    for wrong in (features.keypoints, features):
        try:
            extractor.compute(image, wrong)
        except TypeError as e:
            assert "cv2.KeyPoint" in str(e) and "describe(" in str(e)
        else:
            raise AssertionError("no error")
