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

With --families, one sequence per hard family and image instead, OUT/<family>-<name>/img1..6,
each of img2..6 the family's change at five strengths or directions (docs/evaluation.md, "Hard
families"):

  heavy_blur   rotation 0-20 deg, scale 0.9-1.1     + Gaussian blur, sigma 3, 3.5, 4, 4.5, 5 px
  light_blur   rotation 0-20 deg, scale 0.9-1.1     + Gaussian blur, sigma 1.5, 1.75, 2, 2.25, 2.5
  jpeg15       rotation 0-20 deg, scale 0.9-1.1     + JPEG quality 15
  zoom16       scale 1.6 about the centre, rotation 0, 10, 20, 30, 45 deg
  persp20      the camera turned 20 deg about an axis in the image plane at 0, 45, 90, 135, 22.5
               deg (focal length = the image width), the centre kept
  dark_noise   rotation 0-20 deg, scale 0.9-1.1     + brightness x0.3, gamma 1.5 (darker
               shadows), Gaussian noise sigma 2-4 gray levels (fixed seed)
  rotation     rotation 60, 90, 120, 150, 180 deg about the centre, scale 1

Usage: make_synthetic_pairs.py --families OUT IMAGE...
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


def camera_turn(width, height, angle_deg, axis_deg):
    """The homography of a camera turned by angle_deg about the in-plane axis at axis_deg through
    the principal point (the image centre, focal length = width), shifted so the centre stays."""
    f = float(width)
    k = np.array([[f, 0, width / 2.0], [0, f, height / 2.0], [0, 0, 1.0]])
    axis = np.array([np.cos(np.radians(axis_deg)), np.sin(np.radians(axis_deg)), 0.0])
    rotation, _ = cv2.Rodrigues(axis * np.radians(angle_deg))
    h = k @ rotation @ np.linalg.inv(k)
    centre = h @ [width / 2.0, height / 2.0, 1.0]
    shift = np.array([[1, 0, width / 2.0 - centre[0] / centre[2]],
                      [0, 1, height / 2.0 - centre[1] / centre[2]], [0, 0, 1.0]])
    h = shift @ h
    return h / h[2, 2]


def blurred(sigma):
    return lambda image: cv2.GaussianBlur(image, (0, 0), sigma)


def jpeg(quality):
    def encode(image):
        ok, data = cv2.imencode(".jpg", image, [cv2.IMWRITE_JPEG_QUALITY, quality])
        return cv2.imdecode(data, cv2.IMREAD_GRAYSCALE)
    return encode


def unchanged(image):
    return image


def dark_noisy(noise_sigma, seed):
    """A dim, noisy exposure: brightness x0.3, gamma 1.5 (shadows darker still), then noise."""
    def expose(image):
        dim = 255.0 * (image * 0.3 / 255.0) ** 1.5
        noise = np.random.default_rng(seed).normal(0.0, noise_sigma, image.shape)
        return np.clip(dim + noise + 0.5, 0, 255).astype(np.uint8)
    return expose


def family_pairs(family, w, h):
    """The five (homography, photometric change) of a family, for img2..6."""
    mild = [(0, 1.0), (5, 0.9), (10, 1.1), (15, 0.95), (20, 1.05)]  # rotation deg, scale
    if family == "heavy_blur":
        return [(about_centre(w, h, r, s), blurred(sigma))
                for (r, s), sigma in zip(mild, [3.0, 3.5, 4.0, 4.5, 5.0])]
    if family == "light_blur":
        return [(about_centre(w, h, r, s), blurred(sigma))
                for (r, s), sigma in zip(mild, [1.5, 1.75, 2.0, 2.25, 2.5])]
    if family == "jpeg15":
        return [(about_centre(w, h, r, s), jpeg(15)) for r, s in mild]
    if family == "zoom16":
        return [(about_centre(w, h, r, 1.6), unchanged) for r in [0, 10, 20, 30, 45]]
    if family == "persp20":
        return [(camera_turn(w, h, 20, axis), unchanged) for axis in [0, 45, 90, 135, 22.5]]
    if family == "dark_noise":
        return [(about_centre(w, h, r, s), dark_noisy(sigma, seed))
                for seed, ((r, s), sigma) in enumerate(zip(mild, [2.0, 2.5, 3.0, 3.5, 4.0]))]
    if family == "rotation":
        return [(about_centre(w, h, r, 1.0), unchanged) for r in [60, 90, 120, 150, 180]]
    raise ValueError(family)


FAMILIES = ["heavy_blur", "light_blur", "jpeg15", "zoom16", "persp20", "dark_noise", "rotation"]


def write_families(out, paths):
    for path in paths:
        gray = cv2.imread(path, cv2.IMREAD_GRAYSCALE)
        if gray is None:
            sys.exit(f"cannot read {path}")
        parent = os.path.basename(os.path.dirname(os.path.abspath(path)))
        stem = os.path.splitext(os.path.basename(path))[0]
        name = parent + stem.replace("img", "") if stem.startswith("img") else stem
        h, w = gray.shape
        for family in FAMILIES:
            folder = os.path.join(out, f"{family}-{name}")
            os.makedirs(folder, exist_ok=True)
            cv2.imwrite(os.path.join(folder, "img1.png"), gray)
            for n, (homography, change) in enumerate(family_pairs(family, w, h), start=2):
                warped = cv2.warpPerspective(gray, homography, (w, h), flags=cv2.INTER_LINEAR,
                                             borderValue=0)
                cv2.imwrite(os.path.join(folder, f"img{n}.png"), change(warped))
                np.savetxt(os.path.join(folder, f"H1to{n}p"), homography, fmt="%.10e")


def main():
    if len(sys.argv) >= 4 and sys.argv[1] == "--families":
        write_families(sys.argv[2], sys.argv[3:])
        return
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
