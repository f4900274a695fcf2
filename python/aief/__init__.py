"""AIEF ORB features: extraction with the adaptive information entropy mask, Hamming matching,
RANSAC homography and the adaptive threshold sweep, on numpy arrays.

    import aief, cv2
    extractor = aief.Extractor(n_features=1000)
    features = extractor.extract(cv2.imread("img.png", cv2.IMREAD_GRAYSCALE))
    features.keypoints    # N x 2 float32, pixel centres at integers (OpenCV's convention)
    features.descriptors  # N x 32 uint8
"""
from aief._aief import (AdaptResult, Error, Extractor, Features, __version__, adapt, batch_inputs, default_options,
                        find_homography, match, read_image)

__all__ = ["AdaptResult", "Error", "Extractor", "Features", "adapt", "batch_inputs", "default_options",
           "find_homography", "match", "read_image"]


def _detect_and_compute(self, image, mask=None):
    """As cv2.Feature2D.detectAndCompute: (list of cv2.KeyPoint, N x 32 uint8 descriptors).

    A keypoint whose pixel (rounded position) is 0 in `mask` is dropped after extraction, as
    cv2.KeyPointsFilter.runByPixelsMask drops it; the distribution over blocks is not redone.
    Needs cv2 (python3-opencv).
    """
    import cv2  # only this method needs OpenCV
    import numpy

    features = self.extract(image)
    keep = numpy.ones(len(features), dtype=bool)
    if mask is not None:
        mask = numpy.asarray(mask)
        if mask.shape != numpy.asarray(image).shape[:2]:
            raise Error(f"mask shape {mask.shape} differs from the image's {numpy.asarray(image).shape[:2]}")
        cols = numpy.clip(numpy.rint(features.keypoints[:, 0]).astype(int), 0, mask.shape[1] - 1)
        rows = numpy.clip(numpy.rint(features.keypoints[:, 1]).astype(int), 0, mask.shape[0] - 1)
        keep = mask[rows, cols] != 0
    keypoints = [
        cv2.KeyPoint(float(x), float(y), float(size), float(angle), float(response), int(octave), -1)
        for (x, y), size, angle, response, octave, k in zip(features.keypoints, features.size, features.angle,
                                                            features.response, features.octave, keep) if k
    ]
    return keypoints, numpy.ascontiguousarray(features.descriptors[keep])


Extractor.detectAndCompute = _detect_and_compute
