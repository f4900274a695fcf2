"""Arrays that look like images but are not what they seem: a broadcast array describing
gigabytes in a few bytes, shapes whose pixel count overflows, masked arrays. Each gets aief.Error
before anything is copied."""
import subprocess
import sys

import numpy
import pytest

import aief
from conftest import read_unchanged, sample_path


@pytest.mark.parametrize("shape", [(40000, 40000), (2**20, 2**20), (2**31, 2**31), (64, 2**40)])
def test_oversized_arrays_are_refused_on_their_shape_before_any_copy(shape):
    free = numpy.broadcast_to(numpy.uint8(7), shape)  # a few bytes describing the whole shape
    with pytest.raises(aief.Error, match="more pixels than max_image_pixels = 67108864 \\(refused before any copy\\)"):
        aief.Extractor().extract(free)
    with pytest.raises(aief.Error, match="refused before any copy"):
        aief.adapt(free, free)


def test_refusing_a_free_40000_square_costs_no_memory():
    """The 1.6 GB copy the refusal used to make shows in the process's peak memory."""
    child = ("import resource, numpy, aief\n"
             "try:\n"
             "    aief.Extractor().extract(numpy.broadcast_to(numpy.uint8(7), (40000, 40000)))\n"
             "except aief.Error:\n"
             "    pass\n"
             "print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss)\n")
    peak_kib = int(subprocess.run([sys.executable, "-c", child], capture_output=True, text=True, check=True).stdout)
    assert peak_kib < 400 * 1024, f"peak {peak_kib / 1024:.0f} MiB"


def test_a_masked_array_that_masks_pixels_is_refused_naming_the_way_out():
    image = read_unchanged(sample_path("boat"))
    assert image.ndim == 2
    masked = numpy.ma.masked_less(image, 60)
    assert masked.mask.any()
    with pytest.raises(aief.Error, match="MaskedArray with masked pixels.*image.data.*image.filled"):
        aief.Extractor().extract(masked)
    with pytest.raises(aief.Error, match="MaskedArray"):
        aief.adapt(masked, image)
    # Nothing masked: the pixels are all there is, as for the plain array.
    unmasked = numpy.ma.masked_array(image, mask=False)
    expected = aief.Extractor().extract(image)
    assert numpy.array_equal(aief.Extractor().extract(unmasked).descriptors, expected.descriptors)
    assert numpy.array_equal(aief.Extractor().extract(masked.data).descriptors, expected.descriptors)
