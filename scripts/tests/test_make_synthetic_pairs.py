"""The hard families of scripts/make_synthetic_pairs.py --families: every family's five pairs,
each image the true homography's warp of img1 (checked where the warp lands on the image)."""
import os
import subprocess
import sys

import cv2
import numpy as np

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "make_synthetic_pairs.py")
SAMPLE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "data", "samples",
                      "graf", "img1.png")


def make_families(tmp_path):
    subprocess.run([sys.executable, SCRIPT, "--families", str(tmp_path), SAMPLE], check=True)
    return sorted(os.listdir(tmp_path))


def test_seven_families_of_five_pairs(tmp_path):
    folders = make_families(tmp_path)
    assert folders == [f"{f}-graf1" for f in sorted(["heavy_blur", "light_blur", "jpeg15", "zoom16",
                                                     "persp20", "dark_noise", "rotation"])]
    for folder in folders:
        for n in range(2, 7):
            assert os.path.exists(tmp_path / folder / f"img{n}.png")
            assert np.loadtxt(tmp_path / folder / f"H1to{n}p").shape == (3, 3)


def test_rotation_and_dark_noise_are_the_warps_their_homographies_say(tmp_path):
    make_families(tmp_path)
    img1 = cv2.imread(str(tmp_path / "rotation-graf1" / "img1.png"), cv2.IMREAD_GRAYSCALE)
    h, w = img1.shape
    for n, angle in zip(range(2, 7), [60, 90, 120, 150, 180]):
        H = np.loadtxt(tmp_path / "rotation-graf1" / f"H1to{n}p")
        assert np.allclose([H[0, 0], abs(H[0, 1])], [np.cos(np.radians(angle)),
                                                     np.sin(np.radians(angle))], atol=1e-6)
        assert np.allclose(H @ [w / 2, h / 2, 1], [w / 2, h / 2, 1], atol=1e-6)  # about the centre
        warped = cv2.imread(str(tmp_path / "rotation-graf1" / f"img{n}.png"), cv2.IMREAD_GRAYSCALE)
        assert np.array_equal(warped, cv2.warpPerspective(img1, H, (w, h), flags=cv2.INTER_LINEAR,
                                                          borderValue=0))
    bright = img1.mean()
    for n in range(2, 7):
        dark = cv2.imread(str(tmp_path / "dark_noise-graf1" / f"img{n}.png"), cv2.IMREAD_GRAYSCALE)
        assert dark.mean() < 0.3 * bright  # x0.3 and gamma 1.5 on the warped image
    a = cv2.imread(str(tmp_path / "dark_noise-graf1" / "img2.png"), cv2.IMREAD_GRAYSCALE)
    make_families(tmp_path / "again")
    b = cv2.imread(str(tmp_path / "again" / "dark_noise-graf1" / "img2.png"), cv2.IMREAD_GRAYSCALE)
    assert np.array_equal(a, b)  # the noise has a fixed seed
