"""Synthetic training and evaluation pairs for the box descriptor: a homography (rotation, scale,
corner shifts, a perspective tilt), photometric changes (gamma, gain, blur, noise, JPEG), the warp,
and where a homography takes a point and how much it scales there.

Used through scripts/box_descriptor.py, which re-exports these names.
"""
import math

import cv2
import numpy as np


def homography(width, height, angle_deg=0.0, scale=1.0, corner_shift=0.0, shift=(0.0, 0.0),
               rng=None):
    """Rotation and scale about the centre, then each corner moved by up to corner_shift of the
    image size (a perspective), then a translation (fractions of the size)."""
    src = np.float32([[0, 0], [width, 0], [width, height], [0, height]])
    m = cv2.getRotationMatrix2D((width / 2.0, height / 2.0), angle_deg, scale)
    dst = src @ m[:, :2].T.astype(np.float32) + m[:, 2].astype(np.float32)
    if corner_shift > 0:
        rng = rng if rng is not None else np.random.default_rng(0)
        dst = dst + rng.uniform(-corner_shift, corner_shift, size=(4, 2)) * [width, height]
    dst = dst + np.float32(shift) * [width, height]
    return cv2.getPerspectiveTransform(src, np.float32(dst))


def perspective_tilt(width, height, degrees, axis, f_ratio=1.2):
    """A plane seen turned by `degrees` about the image's vertical (axis 0) or horizontal (1)
    axis through its centre, focal length f_ratio x the width: H = K R K^-1, recentred."""
    f = f_ratio * width
    k = np.array([[f, 0, width / 2.0], [0, f, height / 2.0], [0, 0, 1.0]])
    t = math.radians(degrees)
    c, s = math.cos(t), math.sin(t)
    r = np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]]) if axis == 0 else \
        np.array([[1, 0, 0], [0, c, -s], [0, s, c]])
    h = k @ r @ np.linalg.inv(k)
    centre = h @ [width / 2.0, height / 2.0, 1.0]
    centre = centre[:2] / centre[2]
    shift = np.array([[1, 0, width / 2.0 - centre[0]], [0, 1, height / 2.0 - centre[1]], [0, 0, 1]])
    return shift @ h


def photometric(gray, rng=None, gamma=1.0, gain=1.0, offset=0.0, blur=0.0, noise=0.0, jpeg=None):
    """Lighting (gamma, gain, offset), then Gaussian blur, Gaussian noise, JPEG, in that order."""
    img = gray.astype(np.float64)
    if gamma != 1.0 or gain != 1.0 or offset != 0.0:
        img = 255.0 * (img / 255.0) ** gamma * gain + offset
    if blur > 0:
        img = cv2.GaussianBlur(img, (0, 0), blur)
    if noise > 0:
        rng = rng if rng is not None else np.random.default_rng(0)
        img = img + rng.normal(0.0, noise, img.shape)
    out = np.clip(img + 0.5, 0, 255).astype(np.uint8)
    if jpeg is not None:
        ok, data = cv2.imencode(".jpg", out, [cv2.IMWRITE_JPEG_QUALITY, int(jpeg)])
        out = cv2.imdecode(data, cv2.IMREAD_GRAYSCALE)
    return out


def warp(gray, h):
    return cv2.warpPerspective(gray, h, (gray.shape[1], gray.shape[0]), flags=cv2.INTER_LINEAR,
                               borderMode=cv2.BORDER_CONSTANT, borderValue=0)


def random_training_pair(gray, rng, lighting=0.5):
    """(img1, img2, H from img1 to img2): a random homography and photometric change, for training.

    Rotation any angle, scale 0.55-1.8 (log-uniform), corners moved up to 12%, then, each with a
    probability: blur sigma 0.5-3.5, noise 1-8 gray levels, JPEG quality 12-70, lighting (gamma
    0.5-1.8, gain 0.6-1.3, offset -30..30). img1 gets a milder change half the time."""
    height, width = gray.shape
    angle = rng.uniform(-180, 180) if rng.random() < 0.7 else rng.uniform(-20, 20)
    scale = math.exp(rng.uniform(math.log(0.55), math.log(1.8)))
    h = homography(width, height, angle, scale, corner_shift=rng.uniform(0, 0.12),
                   shift=rng.uniform(-0.1, 0.1, size=2), rng=rng)

    def change(strength):
        p = {}
        if rng.random() < 0.45 * strength:
            p["blur"] = rng.uniform(0.5, 3.5 * strength)
        if rng.random() < 0.4 * strength:
            p["noise"] = rng.uniform(1.0, 8.0 * strength)
        if rng.random() < 0.35 * strength:
            p["jpeg"] = int(rng.uniform(12, 70))
        if rng.random() < lighting * strength:
            p.update(gamma=math.exp(rng.uniform(math.log(0.5), math.log(1.8))),
                     gain=rng.uniform(0.6, 1.3), offset=rng.uniform(-30, 30))
        return p

    img1 = photometric(gray, rng, **(change(0.4) if rng.random() < 0.5 else {}))
    img2 = photometric(warp(gray, h), rng, **change(1.0))
    return img1, img2, h


# ----------------------------------------------------------------------------- correspondences

def project(h, xy):
    p = np.hstack([xy, np.ones((len(xy), 1))]) @ np.asarray(h, dtype=np.float64).T
    return p[:, :2] / p[:, 2:3]


def local_scale(h, xy):
    """sqrt |det J| of the homography at each point: how much it magnifies there."""
    h = np.asarray(h, dtype=np.float64)
    p = np.hstack([xy, np.ones((len(xy), 1))]) @ h.T
    w = p[:, 2]
    det = np.linalg.det(h) / w ** 3
    return np.sqrt(np.abs(det))
