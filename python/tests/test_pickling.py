"""Extractor, Features and AdaptResult pickle, so they go to and come back from worker
processes (concurrent.futures, multiprocessing, Dask): the same options, the same bytes."""
import concurrent.futures
import multiprocessing
import os
import pickle
import subprocess
import sys

import numpy
import pytest

import aief
from conftest import read_unchanged, sample_path

FEATURE_FIELDS = ("keypoints", "size", "angle", "response", "octave", "descriptors")


def assert_same_features(a, b):
    assert (a.image_width, a.image_height, a.info, a.descriptor) == (
        b.image_width, b.image_height, b.info, b.descriptor)
    for field in FEATURE_FIELDS:
        x, y = getattr(a, field), getattr(b, field)
        assert x.dtype == y.dtype and x.shape == y.shape and x.tobytes() == y.tobytes(), field


def assert_same_adapt_results(a, b):
    assert (a.found, a.threshold, a.chosen_index, a.image_entropy_bits, a.curve) == (
        b.found, b.threshold, b.chosen_index, b.image_entropy_bits, b.curve)
    assert_same_features(a.features_a, b.features_a)
    assert_same_features(a.features_b, b.features_b)
    assert numpy.array_equal(a.matches, b.matches)
    for x, y in zip(a.homography, b.homography):
        assert (x is None and y is None) or numpy.array_equal(x, y)


def images():
    return read_unchanged(sample_path("graf", 1)), read_unchanged(sample_path("graf", 2))


# Run in the worker processes: each receives pickles and returns pickles.
def extract_in_worker(extractor, image):
    return extractor, extractor.extract(image)


def adapt_in_worker(extractor, a, b):
    return aief.adapt(a, b, extractor=extractor, step=1.0)


EXTRACTORS = [dict(), dict(n_features=300, mode="orbslam2"), dict(threshold="auto", levels=4, scale=1.5),
              dict(entropy="intensity", threshold=3.5, pool="inf", subpixel=False, block_size=48),
              dict(n_features=300, descriptor="box")]


@pytest.mark.parametrize("kwargs", EXTRACTORS)
def test_round_trips_in_this_process(kwargs):
    a, b = images()
    extractor = aief.Extractor(**kwargs)
    copy = pickle.loads(pickle.dumps(extractor))
    assert copy.options == extractor.options
    features = extractor.extract(a)
    assert_same_features(copy.extract(a), features)
    assert_same_features(pickle.loads(pickle.dumps(features)), features)
    if extractor.options["entropy"] != "off":
        # The sweep chooses F itself: an extractor given one is refused (test_matching.py).
        swept = copy if "threshold" not in kwargs else aief.Extractor(
            **{k: v for k, v in kwargs.items() if k != "threshold"})
        result = aief.adapt(a, b, extractor=swept, step=1.0)
        assert_same_adapt_results(pickle.loads(pickle.dumps(result)), result)


def test_come_back_from_a_process_pool():
    a, b = images()
    local = [aief.Extractor(**kwargs) for kwargs in EXTRACTORS]
    # spawn: fresh interpreters that know nothing of this process but the pickles.
    with concurrent.futures.ProcessPoolExecutor(max_workers=2, mp_context=multiprocessing.get_context("spawn")) as pool:
        extracted = list(pool.map(extract_in_worker, local, [a] * len(local)))
        adapted = pool.submit(adapt_in_worker, local[0], a, b).result()
    for extractor, (returned, features) in zip(local, extracted):
        assert returned.options == extractor.options
        assert_same_features(features, extractor.extract(a))
    assert_same_adapt_results(adapted, aief.adapt(a, b, extractor=local[0], step=1.0))


def test_a_damaged_or_foreign_state_is_refused():
    state = aief.Extractor().__getstate__()
    version = aief.__version__.encode()
    foreign = state.replace(b"aief " + version, b"aief " + b"9" * len(version))  # another build, same length
    with pytest.raises(aief.Error, match="pickled by 'aief 999"):
        aief.Extractor.__new__(aief.Extractor).__setstate__(foreign)
    with pytest.raises(aief.Error, match="cut short"):
        aief.Extractor.__new__(aief.Extractor).__setstate__(state[:-3])


# Run in a child interpreter: protocols 0 and 1 used to abort the interpreter (exit 134,
# "instance allocation failed"), which would take the whole test run with it.
EVERY_PROTOCOL = """
import pickle, sys
import aief
from test_pickling import assert_same_adapt_results, assert_same_features, images
a, b = images()
extractor = aief.Extractor(n_features=300)
features = extractor.extract(a)
result = aief.adapt(a, b, extractor=extractor, step=1.0)
protocol = int(sys.argv[1])
copy = pickle.loads(pickle.dumps(extractor, protocol=protocol))
assert type(copy) is aief.Extractor and copy.options == extractor.options
assert_same_features(copy.extract(a), features)
assert_same_features(pickle.loads(pickle.dumps(features, protocol=protocol)), features)
assert_same_adapt_results(pickle.loads(pickle.dumps(result, protocol=protocol)), result)
"""


@pytest.mark.parametrize("protocol", range(pickle.HIGHEST_PROTOCOL + 1))
def test_every_pickle_protocol_round_trips(protocol):
    run = subprocess.run([sys.executable, "-c", EVERY_PROTOCOL, str(protocol)], capture_output=True, text=True,
                         cwd=os.path.dirname(os.path.abspath(__file__)))
    assert run.returncode == 0, run.stderr
