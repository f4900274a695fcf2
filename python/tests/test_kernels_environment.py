"""AIEF_KERNELS decides which kernels `kernels="auto"` (the default) runs in the Python module too,
and a value that cannot apply is an aief.Error naming the variable, not a silent fallback."""
import platform

import pytest

import aief
from conftest import assert_same_features, read_unchanged, sample_path


def test_forced_scalar_gives_the_same_features(monkeypatch):
    image = read_unchanged(sample_path("graf", 1))
    best = aief.Extractor().extract(image)
    monkeypatch.setenv("AIEF_KERNELS", "scalar")
    assert_same_features(aief.Extractor().extract(image), best)


FOREIGN_SET = "avx2" if platform.machine() in ("aarch64", "arm64") else "neon64"


@pytest.mark.parametrize("value, reason", [("fastest", "unknown kernel set"),
                                           (FOREIGN_SET, "this CPU or build cannot run kernel set")])
def test_unknown_or_unavailable_sets_are_refused(monkeypatch, value, reason):
    monkeypatch.setenv("AIEF_KERNELS", value)
    with pytest.raises(aief.Error, match=f"AIEF_KERNELS={value}: {reason}"):
        aief.Extractor()


def test_an_explicit_set_is_not_overridden(monkeypatch):
    monkeypatch.setenv("AIEF_KERNELS", "fastest")  # would be refused if it applied
    aief.Extractor(kernels="scalar")
