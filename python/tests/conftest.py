"""Shared fixtures: the bundled sample images and the built `aief` CLI (CTest passes AIEF_CLI)."""
import json
import os
import pathlib
import subprocess

import cv2
import numpy
import pytest

SAMPLES = pathlib.Path(__file__).resolve().parents[2] / "data" / "samples"
SEQUENCES = ("graf", "boat", "leuven")


def sample_path(sequence, index=1):
    return SAMPLES / sequence / f"img{index}.png"


def read_unchanged(path):
    """The decoded file as the CLI decodes it (BGR for these samples)."""
    image = cv2.imread(str(path), cv2.IMREAD_UNCHANGED)
    assert image is not None, path
    return image


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("AIEF_CLI")
    if not path:
        pytest.skip("AIEF_CLI is not set (the tests run through CTest, which sets it)")
    return path


def run_cli(cli, *args):
    result = subprocess.run([cli, *map(str, args)], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    return result


def cli_features(cli, tmp_path, image_path, *flags):
    """Keypoints (N x 6 float32: x, y, size, angle, response, octave) and descriptors of `aief extract`."""
    out = tmp_path / f"{image_path.parent.name}_{image_path.stem}.json"
    run_cli(cli, "extract", image_path, "-o", out, *flags)
    data = json.loads(out.read_text())
    keypoints = numpy.array([[k["x"], k["y"], k["size"], k["angle"], k["response"], k["octave"]] for k in data["keypoints"]],
                            dtype=numpy.float32).reshape(-1, 6)
    descriptors = numpy.array([list(bytes.fromhex(h)) for h in data["descriptors_hex"]], dtype=numpy.uint8).reshape(-1, 32)
    return keypoints, descriptors


def as_rows(features):
    """The same N x 6 float32 table from an aief.Features."""
    return numpy.column_stack([features.keypoints, features.size, features.angle, features.response,
                               features.octave.astype(numpy.float32)]).astype(numpy.float32).reshape(-1, 6)


def assert_same_features(a, b):
    assert len(a) == len(b)
    numpy.testing.assert_array_equal(as_rows(a), as_rows(b))
    numpy.testing.assert_array_equal(a.descriptors, b.descriptors)
