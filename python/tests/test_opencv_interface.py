"""Extractor.detectAndCompute: cv2.Feature2D's return shape, mask as cv2.KeyPointsFilter applies it."""
import cv2
import numpy

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


def test_mask_drops_keypoints_on_zero_pixels():
    image = read_unchanged(sample_path("boat"))
    extractor = aief.Extractor()
    all_keypoints, all_descriptors = extractor.detectAndCompute(image)
    mask = numpy.zeros(image.shape[:2], numpy.uint8)
    mask[:, : image.shape[1] // 2] = 255
    keypoints, descriptors = extractor.detectAndCompute(image, mask)
    kept = [i for i, k in enumerate(all_keypoints) if round(k.pt[0]) < image.shape[1] // 2]
    assert 0 < len(keypoints) == len(kept) < len(all_keypoints)
    numpy.testing.assert_array_equal(descriptors, all_descriptors[kept])


def test_mask_of_another_shape_is_an_error():
    image = read_unchanged(sample_path("boat"))
    try:
        aief.Extractor().detectAndCompute(image, numpy.ones((10, 10), numpy.uint8))
    except aief.Error as e:
        assert "mask shape" in str(e)
    else:
        raise AssertionError("no error")
