#!/usr/bin/python3
"""Synthetic image pairs with exact homographies, in the Oxford layout `aief eval` reads.

For every image given, writes OUT/<name>/img1.png (the image in gray) and img2..img6.png, each a
known warp of img1 with a photometric change, and H1to2p..H1to6p (the homography from img1 to
imgN, Oxford's text format). Warped-in areas are black, as in the warped Oxford pairs the default
mode's options were chosen on (docs/evaluation.md).

  img2  rotation 15 deg                      + Gaussian noise, sigma 3 gray levels
  img3  scale 0.7                            + Gaussian blur, sigma 1 px
  img4  perspective (corners moved 8-12%)    + gamma 0.8
  img5  rotation 45 deg, scale 1.2           + JPEG quality 40
  img6  rotation 30 deg, scale 0.8           + brightness x0.7 + 20

Usage: make_synthetic_pairs.py OUT IMAGE...   (fixed seed: the same files every run)
"""
import os
import sys

import cv2
import numpy as np


def about_centre(width, height, angle_deg, scale):
    m = cv2.getRotationMatrix2D((width / 2.0, height / 2.0), angle_deg, scale)
    return np.vstack([m, [0.0, 0.0, 1.0]])


def perspective(width, height, rng):
    src = np.float32([[0, 0], [width, 0], [width, height], [0, height]])
    shift = rng.uniform(0.08, 0.12, size=(4, 2)) * [width, height]
    inward = np.float32([[1, 1], [-1, 1], [-1, -1], [1, -1]])
    return cv2.getPerspectiveTransform(src, np.float32(src + inward * shift))


def photometric(image, kind, rng):
    if kind == "noise":
        return np.clip(image + rng.normal(0.0, 3.0, image.shape), 0, 255).astype(np.uint8)
    if kind == "blur":
        return cv2.GaussianBlur(image, (0, 0), 1.0)
    if kind == "gamma":
        return np.clip(255.0 * (image / 255.0) ** 0.8 + 0.5, 0, 255).astype(np.uint8)
    if kind == "jpeg":
        ok, data = cv2.imencode(".jpg", image, [cv2.IMWRITE_JPEG_QUALITY, 40])
        return cv2.imdecode(data, cv2.IMREAD_GRAYSCALE)
    if kind == "brightness":
        return np.clip(image * 0.7 + 20.0 + 0.5, 0, 255).astype(np.uint8)
    raise ValueError(kind)


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    out = sys.argv[1]
    for path in sys.argv[2:]:
        gray = cv2.imread(path, cv2.IMREAD_GRAYSCALE)
        if gray is None:
            sys.exit(f"cannot read {path}")
        name = os.path.splitext(os.path.basename(path))[0]
        folder = os.path.join(out, name)
        os.makedirs(folder, exist_ok=True)
        rng = np.random.default_rng(9)
        h, w = gray.shape
        warps = [
            (about_centre(w, h, 15, 1.0), "noise"),
            (about_centre(w, h, 0, 0.7), "blur"),
            (perspective(w, h, rng), "gamma"),
            (about_centre(w, h, 45, 1.2), "jpeg"),
            (about_centre(w, h, 30, 0.8), "brightness"),
        ]
        cv2.imwrite(os.path.join(folder, "img1.png"), gray)
        for n, (homography, kind) in enumerate(warps, start=2):
            warped = cv2.warpPerspective(gray, homography, (w, h), flags=cv2.INTER_LINEAR, borderValue=0)
            cv2.imwrite(os.path.join(folder, f"img{n}.png"), photometric(warped, kind, rng))
            np.savetxt(os.path.join(folder, f"H1to{n}p"), homography, fmt="%.10e")


if __name__ == "__main__":
    main()
