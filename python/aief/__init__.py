"""AIEF ORB features: extraction with the adaptive information entropy mask, Hamming matching,
RANSAC homography and the adaptive threshold sweep, on numpy arrays.

    import aief, cv2
    extractor = aief.Extractor(n_features=1000)
    features = extractor.extract(cv2.imread("img.png", cv2.IMREAD_GRAYSCALE))
    features.keypoints    # N x 2 float32, pixel centres at integers (OpenCV's convention)
    features.descriptors  # N x 32 uint8
"""
from aief._aief import (AdaptResult, Error, Extractor, Features, FeaturesFile, __version__, adapt, batch_inputs,
                        default_options, find_homography, match, option_changes, read_image)

__all__ = ["AdaptResult", "Error", "Extractor", "Features", "FeaturesFile", "adapt", "batch_inputs", "default_options",
           "find_homography", "match", "option_changes", "read_image"]


def _cv_keypoints(features, class_ids=None):
    import cv2  # only the cv2-style methods need OpenCV

    ids = [-1] * len(features) if class_ids is None else class_ids
    return [
        cv2.KeyPoint(float(x), float(y), float(size), float(angle), float(response), int(octave), int(class_id))
        for (x, y), size, angle, response, octave, class_id in zip(features.keypoints, features.size, features.angle,
                                                                  features.response, features.octave, ids)
    ]


def _detect_and_compute(self, image, mask=None):
    """As cv2.Feature2D.detectAndCompute: (list of cv2.KeyPoint, N x 32 uint8 descriptors).

    `mask` (2-D uint8 or bool, non-zero where keypoints may be) acts inside the extraction, before
    the distribution, so the n_features budget is filled inside it, as cv2.ORB fills its own.
    Needs cv2 (python3-opencv).
    """
    features = self.extract(image, mask)
    return _cv_keypoints(features), features.descriptors


def _detect(self, image, mask=None):
    """As cv2.Feature2D.detect: the keypoints of detectAndCompute, as a list of cv2.KeyPoint."""
    return _cv_keypoints(self.extract(image, mask))


def _compute(self, image, keypoints, recompute_angles=False):
    """As cv2.Feature2D.compute: (keypoints, N x 32 uint8 descriptors) of the given cv2.KeyPoints.

    Each keypoint is described on the pyramid level its octave names with the angle it is given,
    as cv2.ORB.compute does (recompute_angles=True: the angle is recomputed as for detected
    keypoints); its other fields (class_id too) are kept; keypoints closer than 19 pixels to their
    level's edge are left out, as cv2.ORB leaves some out. detect() followed by compute() gives
    detectAndCompute() bit for bit. See Extractor.describe for arrays.
    """
    import numpy

    keypoints = None if isinstance(keypoints, (numpy.ndarray, Features)) else list(keypoints)
    if keypoints is None or not all(hasattr(k, "pt") for k in keypoints):
        raise TypeError("compute() takes a list of cv2.KeyPoint (as cv2.ORB.compute); for an N x 2 array of "
                        "positions or aief.Features use describe(image, keypoints, octave=...)")
    xy = numpy.float32([k.pt for k in keypoints]).reshape(-1, 2)
    features, kept = self.describe(image, xy, octave=numpy.int32([k.octave for k in keypoints]),
                                   size=numpy.float32([k.size for k in keypoints]),
                                   angle=numpy.float32([k.angle for k in keypoints]),
                                   response=numpy.float32([k.response for k in keypoints]),
                                   keep_angles=not recompute_angles)
    return _cv_keypoints(features, [keypoints[i].class_id for i in kept]), features.descriptors


Extractor.detectAndCompute = _detect_and_compute
Extractor.detect = _detect
Extractor.compute = _compute
